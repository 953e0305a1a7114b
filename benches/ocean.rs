//! `OceanState::step` of the default ocean (three cascades of 1000, 230 and 51 m) beside the
//! bare floor of its FFTs (the three cascades' twelve packed complex 2D inverse FFTs done by
//! one `Fft2d`), in one process, and the world queries with cubic B-spline and bilinear
//! interpolation.
//!
//! Groups (throughput in grid points of one cascade, N² per iteration):
//! - `ocean_step`: `step_1t`, `twelve_ffts_1t`, `step_2t`, `twelve_ffts_2t` at
//!   N = 64 … 1024, each inside a rayon pool of that many threads; the project's target is
//!   step ≤ 1.2 × twelve_ffts.
//! - `ocean_foam`: `step_1t`/`step_no_foam_1t`, `step_2t`/`step_no_foam_2t` at N = 64, 128
//!   and 256: the default step beside the same ocean with its foam switched off
//!   (`FoamConfig::coverage` 0, no drift, no streaks: nothing breaks, nothing moves, only the
//!   aging and the totals run), so that the difference is what the foam costs.
//! - `ocean_parallel_cascades`: at N = 256 in a pool of 2 threads, `sequential` and
//!   `parallel` (`OceanConfig::parallel_cascades` off and on), and `parallel_bilinear_queries`
//!   (parallel, with bilinear queries; no step computes the spline coefficients, so it times
//!   the same work as `parallel`).
//! - `ocean_determinism`: the default ocean's step with `Determinism::SameMachine` and
//!   `Determinism::CrossPlatform` (`step_same_machine`, `step_cross_platform`) at
//!   N = 64 … 512 in a pool of 2 threads, one after the other for each N; and building the
//!   default ocean at 256² in both modes (`new_same_machine`, `new_cross_platform`).
//! - `ocean_queries`: one `sample`, one `height_at`, `heights_at` and `sample_many` of 10 000
//!   points and a 100×100 `sample_grid` on the default ocean at 256², with cubic B-spline and
//!   bilinear interpolation.
//!
//! - `ocean_query_batch`: `heights_at_1t`, `surfaces_at_1t`, `heights_at_2t`,
//!   `surfaces_at_2t` of 100, 1 000, 10 000 and 100 000 points scattered uniformly over a
//!   2 km square, on the default ocean at 256² (throughput in points: criterion prints the
//!   time a point), the tiles the points read computed before timing.
//! - `ocean_small_batches`: `heights_at_n` and `height_at_singles_n` (the same n points one
//!   `height_at` at a time) for batches of n = 1 … 4 scattered points on one thread: a batch
//!   too small for the lanes must not cost more than its single queries.
//! - `ocean_first_query`: `step_1t` and `step_and_height_at_1t` (the step and one
//!   `height_at` after it, which computes the spline tiles it reads), and the same at 2
//!   threads, on the default ocean at N = 128, 256 and 512: the cost a game loop that steps
//!   and asks one boat's height pays beyond the step.
//!
//! - `ocean_full_coverage`: at N = 128 and 256, 1 and 2 threads: `step` (a step of the
//!   default ocean), `step_and_heights_at` (the step and `heights_at` of a 64×64 grid of points
//!   over the largest cascade's tile, which reads every tile of every cascade),
//!   `heights_at` (the same batch again, its tiles computed) and `step_and_old_prefilter`
//!   (the step and the whole-grid prefilter the queries used before issue 25, on every
//!   cascade): the batch's tiles cost `step_and_heights_at − step − heights_at`, against
//!   `step_and_old_prefilter − step`.
//!
//! - `ocean_live`: a change of weather on the default ocean at 256² on one thread: `step`
//!   (a plain step), `set_spectrum_and_step` (`set_spectrum` with a 10 s duration and the
//!   step after it), `transition_step` (the mean step of a whole change: preparation and
//!   blend), `set_spectrum_0_and_step` (duration 0: the new sea drawn at once) and `new`
//!   (building the ocean). `cargo run --release -p ocean-fft-benches --bin live-frames` times
//!   every frame of a change against a plain step.
//!
//! - `ocean_second_order`: the default ocean's step with `OceanConfig::second_order` off and
//!   on (`step_off_1t`, `step_on_1t`, `step_off_2t`, `step_on_2t`) at N = 128, 256 and 512,
//!   each pair one right after the other.
//!
//! - `ocean_coast`: the default ocean at 256² on one thread without and with a 512² depth
//!   map (a 1:50 beach, 4 m cells) over the queried points: `step_open`/`step_map`,
//!   `height_at_open`/`height_at_map`, `heights_at_10k_open`/`heights_at_10k_map`, and
//!   `set_depth_map_512` (the solve, once per map).
//!
//! `cargo bench -p ocean-fft-benches --bench ocean [-- GROUP]`; the first line printed names
//! the CPU.

mod common;
#[path = "common/points.rs"]
mod points;
use points::scattered;
#[path = "common/old_prefilter.rs"]
mod old_prefilter;

use std::hint::black_box;
use std::time::Duration;

use criterion::{BatchSize, BenchmarkId, Criterion, SamplingMode, Throughput};
use ocean_fft::inspect::{Complex32, Fft2d};
use ocean_fft::{
    DepthMap, Determinism, FoamConfig, Interpolation, OceanConfig, OceanState, Spectrum,
    SurfaceSample,
};

const SIZES: [usize; 5] = [64, 128, 256, 512, 1024];
const THREADS: [usize; 2] = [1, 2];

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

/// Samples per benchmark at N: many short ones, so that on a shared machine the fastest
/// samples are free of other work.
fn samples(n: usize) -> usize {
    match n {
        0..=128 => 200,
        256 => 100,
        512 => 30,
        _ => 12,
    }
}

fn step(c: &mut Criterion) {
    let pools: Vec<_> = THREADS.iter().map(|&t| (t, common::pool(t))).collect();
    let mut group = c.benchmark_group("ocean_step");
    group
        // Each sample the same number of iterations (the larger N take tens of ms an
        // iteration, which linear sampling would stretch to minutes).
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    for size in SIZES {
        group
            .sample_size(samples(size))
            .throughput(Throughput::Elements((size * size) as u64));
        for (threads, pool) in &pools {
            // Made on first use, so that a filtered run builds only what it measures.
            let mut state: Option<OceanState> = None;
            group.bench_with_input(
                BenchmarkId::new(format!("step_{threads}t"), size),
                &size,
                |b, _| {
                    let state = state.get_or_insert_with(|| ocean(size, true));
                    pool.install(|| b.iter(|| state.step(black_box(1.0 / 60.0)).expect("step")))
                },
            );
            drop(state);
            // Three cascades of four packed transforms each. `process` uses its input as
            // working space, so each iteration gets a fresh copy (made outside the timed
            // region); the values do not change the FFT's cost.
            let count = 3 * 4;
            let mut fft: Option<(Fft2d, Vec<Complex32>)> = None;
            group.bench_with_input(
                BenchmarkId::new(format!("twelve_ffts_{threads}t"), size),
                &size,
                |b, _| {
                    let (fft, input) = fft.get_or_insert_with(|| {
                        let input = (0..count * size * size)
                            .map(|i| {
                                Complex32::new((i as f32 * 0.37).sin(), (i as f32 * 0.11).cos())
                            })
                            .collect();
                        (Fft2d::new(size, count).expect("valid size"), input)
                    });
                    pool.install(|| {
                        b.iter_batched_ref(
                            || input.clone(),
                            |data| black_box(fft.process(data).expect("right length")[0]),
                            BatchSize::PerIteration,
                        )
                    })
                },
            );
        }
    }
    group.finish();
}

fn foam(c: &mut Criterion) {
    let pools: Vec<_> = THREADS.iter().map(|&t| (t, common::pool(t))).collect();
    let mut group = c.benchmark_group("ocean_foam");
    group
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    for size in [64, 128, 256] {
        group
            .sample_size(samples(size))
            .throughput(Throughput::Elements((size * size) as u64));
        for (threads, pool) in &pools {
            for (name, foam) in [("step", true), ("step_no_foam", false)] {
                let mut state: Option<OceanState> = None;
                group.bench_with_input(
                    BenchmarkId::new(format!("{name}_{threads}t"), size),
                    &size,
                    |b, _| {
                        let state = state.get_or_insert_with(|| {
                            let spectrum = Spectrum::jonswap(10.0, 100_000.0).expect("spectrum");
                            let mut config = OceanConfig {
                                size,
                                ..OceanConfig::default()
                            };
                            if !foam {
                                config.foam = FoamConfig {
                                    coverage: 0.0,
                                    drift: 0.0,
                                    streak_length: 0.0,
                                    streak_width: 0.0,
                                    ..FoamConfig::default()
                                };
                            }
                            OceanState::new(spectrum, config).expect("valid ocean")
                        });
                        pool.install(|| b.iter(|| state.step(black_box(1.0 / 60.0)).expect("step")))
                    },
                );
            }
        }
    }
    group.finish();
}

fn parallel_cascades(c: &mut Criterion) {
    let pool = common::pool(2);
    let mut group = c.benchmark_group("ocean_parallel_cascades");
    group
        .sample_size(20)
        // Each sample the same number of iterations: the larger N take tens of ms an
        // iteration, which linear sampling would stretch to minutes.
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    let size = 256;
    group.throughput(Throughput::Elements((size * size) as u64));
    for parallel in [false, true] {
        let mut state = ocean(size, parallel);
        let name = if parallel { "parallel" } else { "sequential" };
        group.bench_with_input(BenchmarkId::new(name, size), &size, |b, _| {
            pool.install(|| b.iter(|| state.step(black_box(1.0 / 60.0)).expect("step")))
        });
    }
    // The same parallel step with bilinear queries. The step computes no spline coefficients
    // (the first query after it does), so this times the same work as `parallel`.
    let mut state = ocean_with(size, true, Interpolation::Bilinear);
    group.bench_with_input(
        BenchmarkId::new("parallel_bilinear_queries", size),
        &size,
        |b, _| pool.install(|| b.iter(|| state.step(black_box(1.0 / 60.0)).expect("step"))),
    );
    group.finish();
}

/// The default ocean at N in a determinism mode.
fn ocean_in(size: usize, determinism: Determinism) -> OceanState {
    let spectrum = Spectrum::jonswap(10.0, 100_000.0).expect("valid spectrum");
    let config = OceanConfig {
        size,
        determinism,
        ..OceanConfig::default()
    };
    OceanState::new(spectrum, config).expect("valid ocean")
}

fn determinism(c: &mut Criterion) {
    let pool = common::pool(2);
    let mut group = c.benchmark_group("ocean_determinism");
    group
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    let modes = [
        ("same_machine", Determinism::SameMachine),
        ("cross_platform", Determinism::CrossPlatform),
    ];
    for size in [64, 128, 256, 512] {
        group
            .sample_size(samples(size).min(60))
            .throughput(Throughput::Elements((size * size) as u64));
        for (name, mode) in modes {
            let mut state: Option<OceanState> = None;
            group.bench_with_input(
                BenchmarkId::new(format!("step_{name}"), size),
                &size,
                |b, _| {
                    let state = state.get_or_insert_with(|| ocean_in(size, mode));
                    pool.install(|| b.iter(|| state.step(black_box(1.0 / 60.0)).expect("step")))
                },
            );
        }
    }
    group
        .sample_size(10)
        .throughput(Throughput::Elements(256 * 256));
    for (name, mode) in modes {
        group.bench_with_input(
            BenchmarkId::new(format!("new_{name}"), 256),
            &256,
            |b, &n| pool.install(|| b.iter(|| black_box(ocean_in(n, mode)))),
        );
    }
    group.finish();
}

fn queries(c: &mut Criterion) {
    let mut group = c.benchmark_group("ocean_queries");
    group
        .sample_size(20)
        .sampling_mode(SamplingMode::Flat)
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
                    .water()
                    .at_rest(black_box(123.4), black_box(-56.7))
                    .expect("sample")
            })
        });
        group.bench_function(BenchmarkId::new("height_at", name), |b| {
            b.iter(|| {
                state
                    .water()
                    .height_at(black_box(123.4), black_box(-56.7))
                    .expect("height_at")
            })
        });
        group.bench_function(BenchmarkId::new("heights_at_10k", name), |b| {
            b.iter(|| {
                state
                    .water()
                    .heights_at(&points, &mut heights)
                    .expect("heights_at")
            })
        });
        group.bench_function(BenchmarkId::new("sample_many_10k", name), |b| {
            b.iter(|| {
                state
                    .water()
                    .at_rest_many(&points, &mut samples)
                    .expect("sample_many")
            })
        });
        group.bench_function(BenchmarkId::new("sample_grid_100x100", name), |b| {
            b.iter(|| {
                state
                    .water()
                    .at_rest_grid([-300.0, 0.0], 3.1, [100, 100], &mut samples)
                    .expect("sample_grid")
            })
        });
    }
    group.finish();
}

fn query_batch(c: &mut Criterion) {
    let mut group = c.benchmark_group("ocean_query_batch");
    group
        .sample_size(20)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1));
    let mut state = ocean_with(256, true, Interpolation::CubicBSpline);
    state.step(3.0).expect("step");
    for count in [100, 1_000, 10_000, 100_000] {
        let points = scattered(count);
        let mut heights = vec![0.0f32; count];
        let mut surfaces = vec![SurfaceSample::default(); count];
        group.throughput(Throughput::Elements(count as u64));
        for threads in THREADS {
            let pool = common::pool(threads);
            group.bench_with_input(
                BenchmarkId::new(format!("heights_at_{threads}t"), count),
                &count,
                |b, _| {
                    pool.install(|| {
                        b.iter(|| {
                            state
                                .water()
                                .heights_at(&points, &mut heights)
                                .expect("heights_at")
                        })
                    })
                },
            );
            group.bench_with_input(
                BenchmarkId::new(format!("surfaces_at_{threads}t"), count),
                &count,
                |b, _| {
                    pool.install(|| {
                        b.iter(|| {
                            state
                                .water()
                                .surfaces_at(&points, &mut surfaces)
                                .expect("surfaces_at")
                        })
                    })
                },
            );
        }
    }
    group.finish();
}

fn small_batches(c: &mut Criterion) {
    let mut group = c.benchmark_group("ocean_small_batches");
    group
        .sample_size(50)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1));
    let mut state = ocean_with(256, true, Interpolation::CubicBSpline);
    state.step(3.0).expect("step");
    let pool = common::pool(1);
    // 64 batches of n points after one another, so that they read scattered tiles.
    let points = scattered(256);
    for n in 1..=4 {
        let batches: Vec<&[[f64; 2]]> = points.chunks(n).take(64).collect();
        let mut heights = vec![0.0f32; n];
        group.throughput(Throughput::Elements((64 * n) as u64));
        group.bench_function(BenchmarkId::new("heights_at", n), |b| {
            pool.install(|| {
                b.iter(|| {
                    for batch in &batches {
                        state
                            .water()
                            .heights_at(batch, &mut heights)
                            .expect("heights_at");
                    }
                })
            })
        });
        group.bench_function(BenchmarkId::new("height_at_singles", n), |b| {
            pool.install(|| {
                b.iter(|| {
                    for batch in &batches {
                        for (height, &[x, z]) in heights.iter_mut().zip(*batch) {
                            *height = state.water().height_at(x, z).expect("height_at");
                        }
                    }
                })
            })
        });
    }
    group.finish();
}

fn first_query(c: &mut Criterion) {
    let mut group = c.benchmark_group("ocean_first_query");
    group
        .sample_size(40)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1));
    for size in [128, 256, 512] {
        group.throughput(Throughput::Elements((size * size) as u64));
        for threads in THREADS {
            let pool = common::pool(threads);
            let mut state = ocean(size, true);
            group.bench_with_input(
                BenchmarkId::new(format!("step_{threads}t"), size),
                &size,
                |b, _| pool.install(|| b.iter(|| state.step(black_box(1.0 / 60.0)).expect("step"))),
            );
            // A boat drifting with the current: a new point every frame.
            let mut x = 0.0;
            group.bench_with_input(
                BenchmarkId::new(format!("step_and_height_at_{threads}t"), size),
                &size,
                |b, _| {
                    pool.install(|| {
                        b.iter(|| {
                            state.step(black_box(1.0 / 60.0)).expect("step");
                            x += 0.37;
                            state
                                .water()
                                .height_at(black_box(x), 12.0)
                                .expect("height_at")
                        })
                    })
                },
            );
        }
    }
    group.finish();
}

fn full_coverage(c: &mut Criterion) {
    let mut group = c.benchmark_group("ocean_full_coverage");
    group
        .sample_size(40)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1));
    for size in [128, 256] {
        group.throughput(Throughput::Elements((size * size) as u64));
        for threads in THREADS {
            let pool = common::pool(threads);
            let mut state = ocean(size, true);
            let length = f64::from(state.cascades()[0].length());
            let side = 64;
            let points: Vec<[f64; 2]> = (0..side * side)
                .map(|i| {
                    let spacing = length / side as f64;
                    [(i % side) as f64 * spacing, (i / side) as f64 * spacing]
                })
                .collect();
            let mut heights = vec![0.0f32; points.len()];
            let mut old: Vec<old_prefilter::OldSpline> = state
                .cascades()
                .iter()
                .map(|c| old_prefilter::OldSpline::new(c.size()))
                .collect();
            group.bench_with_input(
                BenchmarkId::new(format!("step_{threads}t"), size),
                &size,
                |b, _| pool.install(|| b.iter(|| state.step(black_box(1.0 / 60.0)).expect("step"))),
            );
            group.bench_with_input(
                BenchmarkId::new(format!("step_and_heights_at_{threads}t"), size),
                &size,
                |b, _| {
                    pool.install(|| {
                        b.iter(|| {
                            state.step(black_box(1.0 / 60.0)).expect("step");
                            state
                                .water()
                                .heights_at(&points, &mut heights)
                                .expect("heights_at");
                            heights[7]
                        })
                    })
                },
            );
            group.bench_with_input(
                BenchmarkId::new(format!("heights_at_{threads}t"), size),
                &size,
                |b, _| {
                    pool.install(|| {
                        b.iter(|| {
                            state
                                .water()
                                .heights_at(&points, &mut heights)
                                .expect("heights_at");
                            heights[7]
                        })
                    })
                },
            );
            group.bench_with_input(
                BenchmarkId::new(format!("step_and_old_prefilter_{threads}t"), size),
                &size,
                |b, _| {
                    pool.install(|| {
                        b.iter(|| {
                            state.step(black_box(1.0 / 60.0)).expect("step");
                            let mut probe = 0.0;
                            for (o, c) in old.iter_mut().zip(state.cascades()) {
                                o.compute(c.height(), c.displacement(), c.slope());
                                probe += o.probe();
                            }
                            probe
                        })
                    })
                },
            );
        }
    }
    group.finish();
}

/// The two seas of the `ocean_live` benches: the default breeze and a gale from another
/// direction.
fn live_seas() -> (Spectrum, Spectrum) {
    let breeze = Spectrum::jonswap(10.0, 100_000.0).expect("valid spectrum");
    let gale = Spectrum::jonswap(18.0, 300_000.0)
        .and_then(|s| s.with_wind_direction(1.0))
        .expect("valid spectrum");
    (breeze, gale)
}

fn live(c: &mut Criterion) {
    let pool = common::pool(1);
    let mut group = c.benchmark_group("ocean_live");
    group
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(60)
        .throughput(Throughput::Elements(256 * 256));
    let (breeze, gale) = live_seas();
    let dt = 1.0 / 60.0;
    let mut base = ocean(256, true);
    // A first change, so that the change's buffers exist (as in a game after its first).
    pool.install(|| {
        base.set_spectrum(gale.clone(), 0.0).expect("change");
        base.step(dt).expect("step");
        base.set_spectrum(breeze.clone(), 0.0).expect("change");
        base.step(dt).expect("step");
    });
    group.bench_function("step", |b| {
        let mut state = base.clone();
        pool.install(|| b.iter(|| state.step(black_box(dt)).expect("step")))
    });
    for (name, duration) in [
        ("set_spectrum_and_step", 10.0),
        ("set_spectrum_0_and_step", 0.0),
    ] {
        group.bench_function(name, |b| {
            pool.install(|| {
                b.iter_batched_ref(
                    || base.clone(),
                    |state| {
                        state.set_spectrum(gale.clone(), duration).expect("change");
                        state.step(dt).expect("step")
                    },
                    BatchSize::PerIteration,
                )
            })
        });
    }
    // The step that reaches the blend's start with the whole preparation left (a jump or a
    // long frame across the lag): the dearest step of a change.
    group.bench_function("set_spectrum_and_step_across_lag", |b| {
        pool.install(|| {
            b.iter_batched_ref(
                || {
                    let mut state = base.clone();
                    state.set_spectrum(gale.clone(), 10.0).expect("change");
                    state
                },
                |state| {
                    state
                        .step(black_box(ocean_fft::limits::TRANSITION_LAG))
                        .expect("step")
                },
                BatchSize::PerIteration,
            )
        })
    });
    group.bench_function("transition_step", |b| {
        let mut state = base.clone();
        let mut toward_gale = true;
        pool.install(|| {
            b.iter(|| {
                if state.diagnostics().transition_progress().is_none() {
                    let to = if toward_gale { &gale } else { &breeze };
                    state.set_spectrum(to.clone(), 10.0).expect("change");
                    toward_gale = !toward_gale;
                }
                state.step(black_box(dt)).expect("step")
            })
        })
    });
    group.bench_function("new", |b| {
        pool.install(|| b.iter(|| black_box(ocean(256, true))))
    });
    group.finish();
}

/// The default ocean at N with second order off or on.
fn ocean_second_order(size: usize, second_order: bool) -> OceanState {
    let spectrum = Spectrum::jonswap(10.0, 100_000.0).expect("valid spectrum");
    let config = OceanConfig {
        size,
        second_order,
        ..OceanConfig::default()
    };
    OceanState::new(spectrum, config).expect("valid ocean")
}

fn second_order(c: &mut Criterion) {
    let pools: Vec<_> = THREADS.iter().map(|&t| (t, common::pool(t))).collect();
    let mut group = c.benchmark_group("ocean_second_order");
    group
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    for size in [128, 256, 512] {
        group
            .sample_size(samples(size))
            .throughput(Throughput::Elements((size * size) as u64));
        for (threads, pool) in &pools {
            for (name, on) in [("off", false), ("on", true)] {
                let mut state: Option<OceanState> = None;
                group.bench_with_input(
                    BenchmarkId::new(format!("step_{name}_{threads}t"), size),
                    &size,
                    |b, _| {
                        let state = state.get_or_insert_with(|| ocean_second_order(size, on));
                        pool.install(|| b.iter(|| state.step(black_box(1.0 / 60.0)).expect("step")))
                    },
                );
            }
        }
    }
    group.finish();
}

fn main() {
    common::print_machine();
    let mut criterion = Criterion::default().configure_from_args();
    step(&mut criterion);
    foam(&mut criterion);
    parallel_cascades(&mut criterion);
    determinism(&mut criterion);
    queries(&mut criterion);
    query_batch(&mut criterion);
    small_batches(&mut criterion);
    first_query(&mut criterion);
    full_coverage(&mut criterion);
    live(&mut criterion);
    second_order(&mut criterion);
    coast(&mut criterion);
    criterion.final_summary();
}

/// A 512² planar beach (slope 1:50, 4 m cells) from 40 m deep at x = −1000 m to land.
fn beach_map() -> DepthMap {
    let n = 512;
    let depth = (0..n * n)
        .map(|c| (40.0 - (c % n) as f32 * 4.0 / 50.0).max(-1.0))
        .collect();
    DepthMap {
        origin: [-1000.0, -1000.0],
        spacing: 4.0,
        size: [n, n],
        depth,
    }
}

fn coast(c: &mut Criterion) {
    let mut group = c.benchmark_group("ocean_coast");
    group
        .sample_size(20)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool");
    // Points over the map's water (x from −900 to 0 m: 32 m to 12 m deep).
    let points: Vec<[f64; 2]> = (0..10_000)
        .map(|i| {
            [
                f64::from(i % 100) * 9.0 - 900.0,
                f64::from(i / 100) * 7.0 - 300.0,
            ]
        })
        .collect();
    let mut heights = vec![0.0f32; points.len()];
    for (name, map) in [("open", None), ("map", Some(beach_map()))] {
        let mut state = ocean(256, false);
        state.set_depth_map(map).expect("map");
        state.step(3.0).expect("step");
        group.bench_function(format!("step_{name}"), |b| {
            pool.install(|| b.iter(|| state.step(black_box(1.0 / 60.0)).expect("step")))
        });
        group.bench_function(format!("height_at_{name}"), |b| {
            b.iter(|| {
                state
                    .water()
                    .height_at(black_box(-423.4), black_box(-56.7))
                    .expect("height_at")
            })
        });
        group.bench_function(format!("heights_at_10k_{name}"), |b| {
            pool.install(|| {
                b.iter(|| {
                    state
                        .water()
                        .heights_at(&points, &mut heights)
                        .expect("heights_at")
                })
            })
        });
    }
    let mut state = ocean(256, false);
    let map = beach_map();
    group.bench_function("set_depth_map_512", |b| {
        b.iter(|| state.set_depth_map(Some(map.clone())).expect("map"))
    });
    group.finish();
}
