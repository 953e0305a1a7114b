//! Packing texels, writing vertices and normal maps allocate nothing inside a rayon pool: a
//! counting global allocator (every thread, rayon's workers included) must not move across
//! 20 rounds of every pack, in pools of 1, 2 and 3 threads.
//!
//! One #[test] only, so that no other test of this binary allocates while the counter is
//! read. The warm-up follows tests/alloc.rs: every worker of every pool runs once and the
//! pools settle before anything is counted.

mod counting;

use counting::count;
use ocean_fft::gpu::{NormalMapGreen, TexelLayout, Vertex};
use ocean_fft::{OceanConfig, OceanState, Spectrum};

#[global_allocator]
static GLOBAL: counting::Counting = counting::Counting;

/// The caller's buffers, allocated once.
struct Buffers {
    texels: Vec<[f32; 4]>,
    #[cfg(feature = "half")]
    texels_f16: Vec<[ocean_fft::half::f16; 4]>,
    vertices: Vec<Vertex>,
    pixels: Vec<[u8; 4]>,
}

/// Every pack of every cascade once; returns a checksum so that nothing is optimised away.
fn pack_everything(ocean: &OceanState, buffers: &mut Buffers) -> u64 {
    let mut sum = 0u64;
    for (c, cascade) in ocean.cascades().iter().enumerate() {
        for &layout in TexelLayout::ALL {
            ocean
                .textures()
                .pack(c, layout, &mut buffers.texels)
                .unwrap();
            sum += u64::from(buffers.texels[7][0].to_bits());
            #[cfg(feature = "half")]
            {
                ocean
                    .textures()
                    .pack_f16(c, layout, &mut buffers.texels_f16)
                    .unwrap();
                sum += u64::from(buffers.texels_f16[7][0].to_bits());
            }
            if !layout.has_foam() {
                cascade.pack_texels(layout, &mut buffers.texels).unwrap();
            }
        }
        cascade.write_vertices(&mut buffers.vertices).unwrap();
        sum += u64::from(buffers.vertices[9].position[0].to_bits());
        for green in [NormalMapGreen::OpenGl, NormalMapGreen::DirectX] {
            cascade
                .write_normal_map(green, &mut buffers.pixels)
                .unwrap();
            sum += u64::from(buffers.pixels[11][1]);
        }
        sum += cascade
            .triangle_indices()
            .map(|t| u64::from(t[2]))
            .sum::<u64>();
    }
    sum
}

#[test]
fn packing_allocates_nothing_inside_a_pool() {
    // The counter itself works: a Vec allocates once.
    let before = count();
    let v = std::hint::black_box(vec![1u8; 100]);
    assert_eq!(count() - before, 1);
    drop(v);

    let pools = counting::warm_pools(&[1, 2, 3]);

    for size in [64, 256] {
        let config = OceanConfig {
            size,
            ..OceanConfig::default()
        };
        let mut ocean =
            OceanState::new(Spectrum::jonswap(12.0, 200_000.0).unwrap(), config).unwrap();
        ocean.step(0.5).unwrap();
        let points = size * size;
        let mut buffers = Buffers {
            texels: vec![[0.0; 4]; points],
            #[cfg(feature = "half")]
            texels_f16: vec![[ocean_fft::half::f16::ZERO; 4]; points],
            vertices: vec![Vertex::default(); points],
            pixels: vec![[0; 4]; points],
        };
        for (pool, threads) in pools.iter().zip([1, 2, 3]) {
            let allocations = pool.install(|| {
                // Warm-up: the first parallel calls in this pool.
                let mut sum = pack_everything(&ocean, &mut buffers);
                let before = count();
                for _ in 0..20 {
                    sum = sum.wrapping_add(pack_everything(&ocean, &mut buffers));
                }
                let allocations = count() - before;
                std::hint::black_box(sum);
                allocations
            });
            println!(
                "N={size}: {allocations} allocations in 20 rounds of packs, {threads} threads"
            );
            assert_eq!(
                allocations, 0,
                "N={size}: packing allocated inside a {threads}-thread pool"
            );
        }
    }
}
