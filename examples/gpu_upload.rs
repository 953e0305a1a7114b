//! The per-frame GPU upload path as an engine runs it, without a GPU: step the default ocean
//! (three cascades of 256²), pack every cascade into buffers allocated once, view them as bytes
//! with `bytemuck::cast_slice` (no copy) and hand those bytes to `upload`, a stand-in for
//! wgpu's `queue.write_texture` / `queue.write_buffer` or OpenGL's `glTexSubImage2D`.
//!
//! Per frame and cascade it packs two textures, `DisplacementFoam` (D_x, η, D_z, foam) and
//! `SlopeJacobianFoam` (∂y/∂x, ∂y/∂z, J, foam); for the largest cascade it also writes a vertex
//! array (`write_vertices`; its triangle indices are uploaded once) and an RGBA8 normal map.
//! It runs the loop twice, with RGBA32F texels (`pack_texels`) and with RGBA16F
//! (`pack_texels_f16`), and prints the bytes uploaded per frame and the median time of the
//! step and of the packing. It counts heap allocations over the measured frames (a counting
//! global allocator) and fails if there is any: after the warm-up a frame allocates nothing.
//!
//! The frames run inside a rayon pool (`pool.install`), as an engine keeps the simulation off
//! its own threads: called from outside every pool, rayon's job queue allocates one 1.5 KiB
//! block per 63 parallel calls (see docs/guide/networking.md, "Threads and determinism").
//!
//! Run with `cargo run --release -p ocean-fft-examples --example gpu_upload`.

use std::alloc::System;
use std::hint::black_box;
use std::time::{Duration, Instant};

use ocean_fft::gpu::{NormalMapGreen, TexelLayout, Vertex};
use ocean_fft::half::f16;
use ocean_fft::{Error, OceanConfig, OceanState, Spectrum};
use stats_alloc::{StatsAlloc, INSTRUMENTED_SYSTEM};

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

const WARM_UP: usize = 10;
const FRAMES: usize = 120;
const DT: f64 = 1.0 / 60.0; // s

/// Stands in for `queue.write_texture(…, bytes, …)`: takes the bytes, returns how many.
fn upload(bytes: &[u8]) -> usize {
    black_box(bytes).len()
}

/// What one run measured.
struct Run {
    bytes_per_frame: usize,
    step: Duration,
    pack: Duration,
    allocations: usize,
}

/// Runs the frame loop with texels of type `T`, packed by `pack` (`ocean.textures().pack`
/// or `pack_f16`).
fn run<T: bytemuck::Pod>(
    pack: impl Fn(&OceanState, usize, TexelLayout, &mut [T]) -> Result<(), Error>,
) -> Result<Run, Error> {
    let mut ocean = OceanState::new(Spectrum::jonswap(10.0, 100_000.0)?, OceanConfig::default())?;

    // Allocated once: two textures per cascade, the largest cascade's vertices and normal map.
    let grid = |c: &ocean_fft::Cascade| c.size() * c.size();
    let mut displacement: Vec<Vec<T>> = ocean
        .cascades()
        .iter()
        .map(|c| vec![T::zeroed(); grid(c)])
        .collect();
    let mut slope = displacement.clone();
    let largest = grid(&ocean.cascades()[0]);
    let mut vertices = vec![Vertex::default(); largest];
    let mut normal_map = vec![[0u8; 4]; largest];
    // The mesh's triangles never change: built and uploaded once.
    let indices: Vec<[u32; 3]> = ocean.cascades()[0].triangle_indices().collect();
    upload(bytemuck::cast_slice(&indices));

    let (mut step, mut packing) = ([Duration::ZERO; FRAMES], [Duration::ZERO; FRAMES]);
    let mut bytes_per_frame = 0;
    let mut allocations = 0;
    for frame in 0..WARM_UP + FRAMES {
        let before = GLOBAL.stats().allocations + GLOBAL.stats().reallocations;
        let start = Instant::now();
        ocean.step(DT)?;
        let stepped = Instant::now();

        let mut bytes = 0;
        for c in 0..ocean.cascades().len() {
            pack(
                &ocean,
                c,
                TexelLayout::DisplacementFoam,
                &mut displacement[c],
            )?;
            pack(&ocean, c, TexelLayout::SlopeJacobianFoam, &mut slope[c])?;
            bytes += upload(bytemuck::cast_slice(&displacement[c]));
            bytes += upload(bytemuck::cast_slice(&slope[c]));
        }
        let cascade = &ocean.cascades()[0];
        cascade.write_vertices(&mut vertices)?;
        bytes += upload(bytemuck::cast_slice(&vertices)); // Vertex is Pod (`bytemuck` feature)
        cascade.write_normal_map(NormalMapGreen::OpenGl, &mut normal_map)?;
        bytes += upload(normal_map.as_flattened());
        let packed = Instant::now();

        if frame >= WARM_UP {
            let k = frame - WARM_UP;
            (step[k], packing[k]) = (stepped - start, packed - stepped);
            bytes_per_frame = bytes;
            allocations += GLOBAL.stats().allocations + GLOBAL.stats().reallocations - before;
        }
    }
    Ok(Run {
        bytes_per_frame,
        step: median(&mut step),
        pack: median(&mut packing),
        allocations,
    })
}

fn median(times: &mut [Duration]) -> Duration {
    times.sort_unstable();
    times[times.len() / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let pool = rayon::ThreadPoolBuilder::new().build()?;
    let (f32_run, f16_run) = pool.install(|| -> Result<_, Error> {
        let f32_run =
            run::<[f32; 4]>(|ocean, c, layout, out| ocean.textures().pack(c, layout, out))?;
        let f16_run =
            run::<[f16; 4]>(|ocean, c, layout, out| ocean.textures().pack_f16(c, layout, out))?;
        Ok((f32_run, f16_run))
    })?;

    println!(
        "default ocean: 3 cascades of 256², {} rayon threads; medians of {FRAMES} frames after {WARM_UP} of warm-up",
        pool.current_num_threads()
    );
    println!("per frame: 2 textures per cascade, the largest cascade's vertices (24 B each) and RGBA8 normal map");
    println!("texels    bytes uploaded per frame   step       pack + write   heap allocations");
    for (name, run) in [("RGBA32F", &f32_run), ("RGBA16F", &f16_run)] {
        println!(
            "{name}   {:>10} B ({:5.2} MiB)     {:6.3} ms   {:6.3} ms       {}",
            run.bytes_per_frame,
            run.bytes_per_frame as f64 / (1024.0 * 1024.0),
            run.step.as_secs_f64() * 1e3,
            run.pack.as_secs_f64() * 1e3,
            run.allocations,
        );
    }
    let allocations = f32_run.allocations + f16_run.allocations;
    if allocations > 0 {
        return Err(format!(
            "{allocations} heap allocations in the measured frames (expected none)"
        )
        .into());
    }
    Ok(())
}
