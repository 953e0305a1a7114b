//! `OceanState::step` with the cascades updated one after another or in parallel, beside the
//! bare floor of its FFTs (the three cascades' twelve packed complex 2D inverse FFTs done by
//! one `Fft2d`), and the world queries. Run with
//! `cargo bench -p ocean-fft-benches --bench ocean`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BatchSize, BenchmarkId, Criterion};
use ocean_fft::{Complex32, Fft2d, OceanConfig, OceanState, Spectrum};

fn ocean(size: usize, parallel_cascades: bool) -> OceanState {
    let spectrum = Spectrum::jonswap(10.0, 100_000.0).expect("valid spectrum");
    let config = OceanConfig {
        size,
        parallel_cascades,
        ..OceanConfig::default()
    };
    OceanState::new(spectrum, config).expect("valid ocean")
}

fn step(c: &mut Criterion) {
    let mut group = c.benchmark_group("ocean_step");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    for size in [64, 128, 256] {
        for parallel in [false, true] {
            let mut state = ocean(size, parallel);
            let name = if parallel { "parallel" } else { "sequential" };
            group.bench_with_input(BenchmarkId::new(name, size), &size, |b, _| {
                b.iter(|| state.step(black_box(1.0 / 60.0)).expect("step"))
            });
        }
        // Three cascades of four packed transforms each. `process` uses its input as working
        // space, so each iteration gets a fresh copy (made outside the timed region); the
        // values do not change the FFT's cost.
        let count = 3 * 4;
        let mut fft = Fft2d::new(size, count).expect("valid size");
        let input: Vec<Complex32> = (0..count * size * size)
            .map(|i| Complex32::new((i as f32 * 0.37).sin(), (i as f32 * 0.11).cos()))
            .collect();
        group.bench_with_input(BenchmarkId::new("twelve_ffts", size), &size, |b, _| {
            b.iter_batched_ref(
                || input.clone(),
                |data| black_box(fft.process(data).expect("right length")[0]),
                BatchSize::PerIteration,
            )
        });
    }
    group.finish();
}

fn queries(c: &mut Criterion) {
    let mut group = c.benchmark_group("ocean_queries");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    let mut state = ocean(256, false);
    state.step(3.0).expect("step");
    let points: Vec<[f64; 2]> = (0..10_000)
        .map(|i| [f64::from(i % 100) * 7.3 - 300.0, f64::from(i / 100) * 5.1])
        .collect();
    let mut heights = vec![0.0f32; points.len()];
    group.bench_function("sample", |b| {
        b.iter(|| {
            state
                .sample(black_box(123.4), black_box(-56.7))
                .expect("sample")
        })
    });
    group.bench_function("height_at", |b| {
        b.iter(|| {
            state
                .height_at(black_box(123.4), black_box(-56.7))
                .expect("height_at")
        })
    });
    group.bench_function("heights_at_10k", |b| {
        b.iter(|| state.heights_at(&points, &mut heights).expect("heights_at"))
    });
    group.finish();
}

criterion_group!(benches, step, queries);
criterion_main!(benches);
