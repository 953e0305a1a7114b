//! `OceanState::step` with the cascades updated one after another or in parallel, beside the
//! bare floor of its FFTs (the three cascades' twelve packed complex 2D inverse FFTs done by
//! one `Fft2d`), and with bilinear queries (no spline prefilter on update); and the world
//! queries with cubic B-spline and bilinear interpolation, side by side. Run with
//! `cargo bench -p ocean-fft-benches --bench ocean`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BatchSize, BenchmarkId, Criterion};
use ocean_fft::{
    Complex32, Fft2d, Interpolation, OceanConfig, OceanState, Spectrum, SurfaceSample,
};

fn ocean(size: usize, parallel_cascades: bool) -> OceanState {
    ocean_with(size, parallel_cascades, Interpolation::CubicBSpline)
}

fn ocean_with(size: usize, parallel_cascades: bool, interpolation: Interpolation) -> OceanState {
    let spectrum = Spectrum::jonswap(10.0, 100_000.0).expect("valid spectrum");
    let mut config = OceanConfig {
        size,
        parallel_cascades,
        ..OceanConfig::default()
    };
    config.query.interpolation = interpolation;
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
        // The same parallel step without the cubic B-spline prefilter of the queries.
        let mut state = ocean_with(size, true, Interpolation::Bilinear);
        group.bench_with_input(
            BenchmarkId::new("parallel_bilinear_queries", size),
            &size,
            |b, _| b.iter(|| state.step(black_box(1.0 / 60.0)).expect("step")),
        );
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
    let points: Vec<[f64; 2]> = (0..10_000)
        .map(|i| [f64::from(i % 100) * 7.3 - 300.0, f64::from(i / 100) * 5.1])
        .collect();
    let mut heights = vec![0.0f32; points.len()];
    let mut samples = vec![SurfaceSample::default(); points.len()];
    for (name, interpolation) in [
        ("cubic", Interpolation::CubicBSpline),
        ("bilinear", Interpolation::Bilinear),
    ] {
        let mut state = ocean_with(256, false, interpolation);
        state.step(3.0).expect("step");
        group.bench_function(BenchmarkId::new("sample", name), |b| {
            b.iter(|| {
                state
                    .sample(black_box(123.4), black_box(-56.7))
                    .expect("sample")
            })
        });
        group.bench_function(BenchmarkId::new("height_at", name), |b| {
            b.iter(|| {
                state
                    .height_at(black_box(123.4), black_box(-56.7))
                    .expect("height_at")
            })
        });
        group.bench_function(BenchmarkId::new("heights_at_10k", name), |b| {
            b.iter(|| state.heights_at(&points, &mut heights).expect("heights_at"))
        });
        group.bench_function(BenchmarkId::new("sample_many_10k", name), |b| {
            b.iter(|| {
                state
                    .sample_many(&points, &mut samples)
                    .expect("sample_many")
            })
        });
        group.bench_function(BenchmarkId::new("sample_grid_100x100", name), |b| {
            b.iter(|| {
                state
                    .sample_grid([-300.0, 0.0], 3.1, [100, 100], &mut samples)
                    .expect("sample_grid")
            })
        });
    }
    group.finish();
}

criterion_group!(benches, step, queries);
criterion_main!(benches);
