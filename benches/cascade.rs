//! `Cascade::update` beside the bare time of its four packed complex 2D inverse FFTs done the
//! same way (rows in parallel, blocked transpose, rows again) with the public [`Fft2d`], in
//! one criterion group per N so that the ratio can be read off; plus `Cascade::new` (h0
//! generation and tables) once at N = 256. In the N = 256 group, beside `update`, the GPU
//! upload writers: `pack_f32` (RGBA32F `DisplacementJacobian` texels), `pack_f16` (the same in
//! RGBA16F, with `--features half`), `vertices` and `normal_map` (RGBA8).
//!
//! `cargo bench -p ocean-fft-benches --bench cascade [--features half]`. The project's target
//! is update ≤ 1.3 × four_ffts.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use ocean_fft::{
    Cascade, CascadeConfig, Complex32, Fft2d, NormalMapGreen, Spectrum, TexelLayout, Vertex,
};

const SIZES: [usize; 4] = [64, 128, 256, 512];

fn config(size: usize) -> CascadeConfig {
    CascadeConfig {
        size,
        length: 500.0,
        seed: 7,
        ..CascadeConfig::default()
    }
}

fn spectrum() -> Spectrum {
    Spectrum::jonswap(12.0, 200_000.0).expect("valid spectrum")
}

/// Four N×N spectra with the cascade's packed values at t = 0 (any finite data would do:
/// the FFT's cost does not depend on the values).
fn fft_input(cascade: &Cascade) -> Vec<Complex32> {
    let n = cascade.size();
    let h = cascade.wave_spectrum(0.0).expect("finite t");
    let mut data = Vec::with_capacity(4 * n * n);
    for transform in 0..4 {
        let scale = 1.0 + transform as f32;
        data.extend(h.iter().map(|c| c * scale));
    }
    data
}

fn update_vs_fft(c: &mut Criterion) {
    let spectrum = spectrum();
    for n in SIZES {
        let mut group = c.benchmark_group(format!("cascade_{n}"));
        group
            .sample_size(20)
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(2));

        let mut cascade = Cascade::new(&spectrum, config(n)).expect("valid cascade");
        let mut t = 0.0f64;
        group.bench_function("update", |b| {
            b.iter(|| {
                t += 1.0 / 60.0;
                cascade.update(black_box(t)).expect("finite t");
                black_box(cascade.height()[0]);
            })
        });

        // `process` uses its input as working space, so each iteration gets a fresh copy
        // (made outside the timed region).
        let input = fft_input(&cascade);
        let mut fft = Fft2d::new(n, 4).expect("valid size");
        group.bench_function("four_ffts", |b| {
            b.iter_batched_ref(
                || input.clone(),
                |data| {
                    let out = fft.process(data).expect("right length");
                    black_box(out[0]);
                },
                BatchSize::PerIteration,
            )
        });
        if n == 256 {
            bench_upload(&mut group, &cascade);
        }
        group.finish();
    }
}

/// The GPU upload writers on one updated cascade, into buffers allocated once.
fn bench_upload(
    group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    cascade: &Cascade,
) {
    let points = cascade.size() * cascade.size();
    let mut texels = vec![[0.0f32; 4]; points];
    group.bench_function("pack_f32", |b| {
        b.iter(|| {
            cascade
                .pack_texels(TexelLayout::DisplacementJacobian, &mut texels)
                .expect("right length");
            black_box(texels[0]);
        })
    });
    #[cfg(feature = "half")]
    {
        let mut texels = vec![[ocean_fft::half::f16::ZERO; 4]; points];
        group.bench_function("pack_f16", |b| {
            b.iter(|| {
                cascade
                    .pack_texels_f16(TexelLayout::DisplacementJacobian, &mut texels)
                    .expect("right length");
                black_box(texels[0]);
            })
        });
    }
    let mut vertices = vec![Vertex::default(); points];
    group.bench_function("vertices", |b| {
        b.iter(|| {
            cascade.write_vertices(&mut vertices).expect("right length");
            black_box(vertices[0]);
        })
    });
    let mut pixels = vec![[0u8; 4]; points];
    group.bench_function("normal_map", |b| {
        b.iter(|| {
            cascade
                .write_normal_map(NormalMapGreen::OpenGl, &mut pixels)
                .expect("right length");
            black_box(pixels[0]);
        })
    });
}

fn cascade_new(c: &mut Criterion) {
    let spectrum = spectrum();
    let mut group = c.benchmark_group("cascade_new");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    group.bench_function("new_256", |b| {
        b.iter(|| Cascade::new(black_box(&spectrum), config(256)).expect("valid cascade"))
    });
    group.finish();
}

criterion_group!(benches, update_vs_fft, cascade_new);
criterion_main!(benches);
