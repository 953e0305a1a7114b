//! Every buffer of ocean-fft viewed as glam types without copying, the way a game reads them.
//!
//! Shared by the client crates (`clients/glam-*/tests/zero_copy.rs`): the same code compiled
//! against each glam version, which is the point. Each test checks, for every buffer, that the
//! cast kept the pointer and the length in bytes (no copy) and that every value reads the same
//! through the glam type as through the array, on an ocean that is not flat (so that a wrong
//! component order could not pass).

use bytemuck::{cast_slice, Pod, Zeroable};
use glam::{Vec2, Vec3};
use ocean_fft::{FoamConfig, OceanConfig, OceanState, Spectrum, SurfaceSample};

const N: usize = 16;

/// A small ocean (three cascades of 16²) after a second of steps, with ten times the
/// calibrated whitecaps, so that the foam buffers are not all zero.
pub fn ocean() -> OceanState {
    let spectrum = Spectrum::jonswap(14.0, 300_000.0)
        .and_then(|s| s.with_wind_direction(0.3))
        .expect("valid spectrum");
    let config = OceanConfig {
        size: N,
        choppiness: 1.5,
        foam: FoamConfig {
            coverage: 10.0,
            ..FoamConfig::default()
        },
        ..OceanConfig::default()
    };
    let mut ocean = OceanState::new(spectrum, config).expect("valid config");
    for _ in 0..30 {
        ocean.step(1.0 / 30.0).expect("finite step");
    }
    ocean
}

/// `cast` is `original` itself: same address, same size in bytes.
#[track_caller]
pub fn same_memory<A, B>(cast: &[A], original: &[B]) {
    assert_eq!(cast.as_ptr().cast::<u8>(), original.as_ptr().cast::<u8>());
    assert_eq!(std::mem::size_of_val(cast), std::mem::size_of_val(original));
}

/// Not every value is the same (a flat or constant buffer would let a swapped component pass).
#[track_caller]
pub fn varies(values: impl IntoIterator<Item = f32>) {
    let mut values = values.into_iter();
    let first = values.next().expect("a non-empty buffer");
    assert!(values.any(|v| v != first), "buffer is constant ({first})");
}

#[test]
fn scalar_buffers_are_f32_slices_and_bytes_for_the_gpu() {
    let ocean = ocean();
    assert_eq!(ocean.cascades().len(), 3);
    // The foam buffers live on cascade 0's grid.
    let foam = [
        ocean.foam_view().total(),
        ocean.foam_view().active(),
        ocean.foam_view().residual(),
        ocean.foam_view().breaking(),
    ];
    for (c, cascade) in ocean.cascades().iter().enumerate() {
        let own = [cascade.height(), cascade.jacobian()];
        let buffers = if c == 0 {
            &[own.as_slice(), &foam].concat()
        } else {
            &own.to_vec()
        };
        for &buffer in buffers {
            assert_eq!(buffer.len(), N * N);
            let floats: &[f32] = cast_slice(buffer);
            same_memory(floats, buffer);
            assert_eq!(floats, buffer);
            // What `wgpu::Queue::write_texture` or `write_buffer` takes.
            let bytes: &[u8] = cast_slice(buffer);
            same_memory(bytes, buffer);
            assert_eq!(bytes[4..8], buffer[1].to_ne_bytes());
        }
        varies(cascade.height().iter().copied());
        varies(cascade.jacobian().iter().copied());
    }
    for buffer in foam {
        varies(buffer.iter().copied());
    }
}

#[test]
fn displacement_and_slope_are_vec2_slices() {
    let ocean = ocean();
    for cascade in ocean.cascades() {
        for buffer in [cascade.displacement(), cascade.slope()] {
            assert_eq!(buffer.len(), N * N);
            let vectors: &[Vec2] = cast_slice(buffer);
            same_memory(vectors, buffer);
            for (v, a) in vectors.iter().zip(buffer) {
                // [x, z] of the crate is (x, y) of a Vec2.
                assert_eq!((v.x, v.y), (a[0], a[1]));
                assert_eq!(*v, Vec2::from_array(*a));
                assert_eq!(v.to_array(), *a);
            }
            varies(vectors.iter().map(|v| v.x));
            varies(vectors.iter().map(|v| v.y));
        }
    }
}

#[test]
fn normals_are_vec3_slices() {
    let ocean = ocean();
    for cascade in ocean.cascades() {
        let normal = cascade.normal();
        assert_eq!(normal.len(), N * N);
        // Vec3, not Vec3A: Vec3A is 16 bytes with a padding lane, so it cannot alias [f32; 3].
        let vectors: &[Vec3] = cast_slice(normal);
        same_memory(vectors, normal);
        for (v, a) in vectors.iter().zip(normal) {
            assert_eq!((v.x, v.y, v.z), (a[0], a[1], a[2]));
            assert_eq!(*v, Vec3::from_array(*a));
            assert_eq!(*v, Vec3::from(*a));
            assert!((v.length() - 1.0).abs() < 1e-5, "unit normal, y up: {v}");
            assert!(v.y > 0.0);
        }
        varies(vectors.iter().map(|v| v.x));
        varies(vectors.iter().map(|v| v.z));
    }
}

/// The caller's own GPU-side struct, with glam fields, laid out as `SurfaceSample`.
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
#[repr(C)]
struct GpuSample {
    height: f32,
    displacement: Vec2,
    slope: Vec2,
    normal: Vec3,
    foam: f32,
}

#[test]
fn surface_samples_cast_to_f32_and_to_a_struct_of_glam_fields() {
    let ocean = ocean();
    let points: Vec<[f64; 2]> = (0..100)
        .map(|i| [f64::from(i) * 7.3 - 300.0, f64::from(i % 13) * 21.1 - 90.0])
        .collect();
    let mut samples = vec![SurfaceSample::default(); points.len()];
    ocean
        .water()
        .surfaces_at(&points, &mut samples)
        .expect("finite points");

    let floats: &[f32] = cast_slice(&samples);
    same_memory(floats, &samples);
    assert_eq!(floats.len(), 9 * samples.len());
    for (f, s) in floats.chunks_exact(9).zip(&samples) {
        assert_eq!(f[0], s.height);
        assert_eq!(f[1..3], s.displacement);
        assert_eq!(f[3..5], s.slope);
        assert_eq!(f[5..8], s.normal);
        assert_eq!(f[8], s.foam);
    }

    let gpu: &[GpuSample] = cast_slice(&samples);
    same_memory(gpu, &samples);
    for (g, s) in gpu.iter().zip(&samples) {
        assert_eq!(g.height, s.height);
        assert_eq!(g.displacement, Vec2::from_array(s.displacement));
        assert_eq!(g.slope, Vec2::from_array(s.slope));
        assert_eq!(g.normal, Vec3::from_array(s.normal));
        assert_eq!(g.foam, s.foam);
    }
    varies(samples.iter().map(|s| s.height));
    varies(samples.iter().map(|s| s.displacement[1]));
    varies(samples.iter().map(|s| s.slope[0]));
    varies(samples.iter().map(|s| s.normal[2]));
}
