//! `Cascade::update` beside the bare time of its four packed complex 2D inverse FFTs done the
//! same way (rows in parallel, blocked transpose, rows again) by the public [`Fft2d`], in one
//! process, so that the ratio update ÷ four_ffts can be read off per N and thread count.
//!
//! Groups (throughput in grid points, N² per iteration):
//! - `cascade_update`: `update_1t`, `four_ffts_1t`, `update_2t`, `four_ffts_2t` at
//!   N = 64 … 1024, each inside a rayon pool of that many threads; the project's target is
//!   update ≤ 1.3 × four_ffts.
//! - `cascade_scaling`: `update` and `four_ffts` at N = 2048 and 4096 (film bakes), in a pool
//!   of 2 threads; with `cascade_update` it gives the time per cascade from 64² to 4096².
//! - `cascade_upload`: at N = 256, `update` beside the GPU upload writers: `pack_f32`
//!   (RGBA32F `DisplacementJacobian` texels), `pack_f16` (the same in RGBA16F, with
//!   `--features half`), `vertices` and `normal_map` (RGBA8).
//! - `cascade_new`: building a 256² cascade (h0 and the tables, once).
//!
//! `cargo bench -p ocean-fft-benches --bench cascade [--features half] [-- GROUP]`; the bench
//! tables of docs/benchmarks.md come from `cargo run --release -p ocean-fft-benches --bin
//! bench-table`. The first line printed names the CPU.

mod common;

use std::hint::black_box;
use std::time::Duration;

use criterion::{BatchSize, BenchmarkId, Criterion, SamplingMode, Throughput};
use ocean_fft::gpu::{NormalMapGreen, TexelLayout, Vertex};
use ocean_fft::inspect;
use ocean_fft::inspect::{Complex32, Fft2d};
use ocean_fft::{Cascade, CascadeConfig, Spectrum};

const SIZES: [usize; 5] = [64, 128, 256, 512, 1024];
const LARGE_SIZES: [usize; 2] = [2048, 4096];
const THREADS: [usize; 2] = [1, 2];

/// A 500 m cascade over the whole band (no pruning: every row carries waves).
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
    let h = inspect::wave_spectrum(cascade, 0.0).expect("finite t");
    let mut data = Vec::with_capacity(4 * n * n);
    for transform in 0..4 {
        let scale = 1.0 + transform as f32;
        data.extend(h.iter().map(|c| c * scale));
    }
    data
}

type Group<'a> = criterion::BenchmarkGroup<'a, criterion::measurement::WallTime>;

/// `update_{label}` and `four_ffts_{label}` of an N×N cascade, one after the other, inside
/// `pool`. The cascade and the FFT input are made on first use, so that a filtered run does
/// not build what it does not measure (a 4096² cascade holds 1.6 GB).
fn update_beside_ffts(group: &mut Group<'_>, pool: &rayon::ThreadPool, n: usize, label: &str) {
    let mut cascade: Option<Cascade> = None;
    let make = || Cascade::new(&spectrum(), config(n)).expect("valid cascade");
    let mut t = 0.0f64;
    group.bench_with_input(BenchmarkId::new(format!("update{label}"), n), &n, |b, _| {
        let cascade = cascade.get_or_insert_with(make);
        pool.install(|| {
            b.iter(|| {
                t += 1.0 / 60.0;
                cascade.update(black_box(t)).expect("finite t");
                black_box(cascade.height()[0]);
            })
        })
    });
    drop(cascade);
    // `process` uses its input as working space, so each iteration gets a fresh copy (made
    // outside the timed region).
    let mut fft: Option<(Fft2d, Vec<Complex32>)> = None;
    group.bench_with_input(
        BenchmarkId::new(format!("four_ffts{label}"), n),
        &n,
        |b, _| {
            let (fft, input) = fft.get_or_insert_with(|| {
                let input = fft_input(&make());
                (Fft2d::new(n, 4).expect("valid size"), input)
            });
            pool.install(|| {
                b.iter_batched_ref(
                    || input.clone(),
                    |data| {
                        let out = fft.process(data).expect("right length");
                        black_box(out[0]);
                    },
                    BatchSize::PerIteration,
                )
            })
        },
    );
}

/// Samples per benchmark at N: many short ones, so that on a shared machine the fastest
/// samples are free of other work (about 10 ms of update each).
fn samples(n: usize) -> usize {
    match n {
        0..=128 => 200,
        256 => 150,
        512 => 60,
        _ => 25,
    }
}

fn cascade_update(c: &mut Criterion) {
    let pools: Vec<_> = THREADS.iter().map(|&t| (t, common::pool(t))).collect();
    let mut group = c.benchmark_group("cascade_update");
    group
        // Each sample the same number of iterations (the larger N take tens of ms an
        // iteration, which linear sampling would stretch to minutes).
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    for n in SIZES {
        group
            .sample_size(samples(n))
            .throughput(Throughput::Elements((n * n) as u64));
        for (threads, pool) in &pools {
            update_beside_ffts(&mut group, pool, n, &format!("_{threads}t"));
        }
    }
    group.finish();
}

fn cascade_scaling(c: &mut Criterion) {
    let pool = common::pool(2);
    let mut group = c.benchmark_group("cascade_scaling");
    group
        .sample_size(10)
        // Each sample the same number of iterations: the larger N take tens of ms an
        // iteration, which linear sampling would stretch to minutes.
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(5));
    for n in LARGE_SIZES {
        group.throughput(Throughput::Elements((n * n) as u64));
        update_beside_ffts(&mut group, &pool, n, "");
    }
    group.finish();
}

/// The GPU upload writers on one updated 256² cascade, into buffers allocated once, beside
/// its update.
fn cascade_upload(c: &mut Criterion) {
    let n = 256;
    let points = n * n;
    let mut group = c.benchmark_group("cascade_upload");
    group
        .sample_size(20)
        // Each sample the same number of iterations: the larger N take tens of ms an
        // iteration, which linear sampling would stretch to minutes.
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .throughput(Throughput::Elements(points as u64));
    let mut cascade = Cascade::new(&spectrum(), config(n)).expect("valid cascade");
    let mut t = 0.0f64;
    group.bench_with_input(BenchmarkId::new("update", n), &n, |b, _| {
        b.iter(|| {
            t += 1.0 / 60.0;
            cascade.update(black_box(t)).expect("finite t");
            black_box(cascade.height()[0]);
        })
    });
    let mut texels = vec![[0.0f32; 4]; points];
    group.bench_with_input(BenchmarkId::new("pack_f32", n), &n, |b, _| {
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
        group.bench_with_input(BenchmarkId::new("pack_f16", n), &n, |b, _| {
            b.iter(|| {
                cascade
                    .pack_texels_f16(TexelLayout::DisplacementJacobian, &mut texels)
                    .expect("right length");
                black_box(texels[0]);
            })
        });
    }
    let mut vertices = vec![Vertex::default(); points];
    group.bench_with_input(BenchmarkId::new("vertices", n), &n, |b, _| {
        b.iter(|| {
            cascade.write_vertices(&mut vertices).expect("right length");
            black_box(vertices[0]);
        })
    });
    let mut pixels = vec![[0u8; 4]; points];
    group.bench_with_input(BenchmarkId::new("normal_map", n), &n, |b, _| {
        b.iter(|| {
            cascade
                .write_normal_map(NormalMapGreen::OpenGl, &mut pixels)
                .expect("right length");
            black_box(pixels[0]);
        })
    });
    group.finish();
}

fn cascade_new(c: &mut Criterion) {
    let spectrum = spectrum();
    let mut group = c.benchmark_group("cascade_new");
    group
        .sample_size(10)
        // Each sample the same number of iterations: the larger N take tens of ms an
        // iteration, which linear sampling would stretch to minutes.
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    group.bench_with_input(BenchmarkId::new("new", 256), &256, |b, &n| {
        b.iter(|| Cascade::new(black_box(&spectrum), config(n)).expect("valid cascade"))
    });
    group.finish();
}

fn main() {
    common::print_machine();
    let mut criterion = Criterion::default().configure_from_args();
    cascade_update(&mut criterion);
    cascade_scaling(&mut criterion);
    cascade_upload(&mut criterion);
    cascade_new(&mut criterion);
    criterion.final_summary();
}
