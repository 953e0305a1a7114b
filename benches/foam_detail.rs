//! Issue 39: what the foam's detail costs, in one run. `step`: a default ocean's step
//! (256², three cascades, 1/60 s), whose only addition is the drift of the streak field
//! (two multiply-adds); `step_no_foam`: the same without foam, for scale. `foam_at`: 4096
//! patterned foam lookups (the coarse fractions, the finer cascades' Jacobians, the streak
//! field and two quantile searches); `coarse_lookup`: 4096 bilinear lookups of one foam-grid
//! buffer (`breaking_at`), half of what 0.3's `foam_at` did. Run with
//! `cargo bench -p ocean-fft-benches --bench foam_detail`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode};
use ocean_fft::{FoamConfig, OceanConfig, OceanState, Spectrum};

fn ocean(foam: bool) -> OceanState {
    let spectrum = Spectrum::jonswap(10.0, 100_000.0).expect("spectrum");
    let mut config = OceanConfig {
        size: 256,
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
    let mut ocean = OceanState::new(spectrum, config).expect("valid ocean");
    ocean.pre_roll(10.0, 0.1).expect("pre-roll");
    ocean
}

fn points() -> Vec<(f64, f64)> {
    (0..4096u32)
        .map(|k| {
            (
                f64::from(k % 64) * 1.713 + 3.1,
                f64::from(k / 64) * 2.377 - 7.9,
            )
        })
        .collect()
}

fn foam_detail(c: &mut Criterion) {
    let mut group = c.benchmark_group("foam_detail");
    group
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(20);
    for (name, foam) in [("step", true), ("step_no_foam", false)] {
        let mut state = ocean(foam);
        group.bench_function(name, |b| {
            b.iter(|| state.step(black_box(1.0 / 60.0)).expect("step"))
        });
    }
    let state = ocean(true);
    let points = points();
    group.bench_function("foam_at_4096", |b| {
        b.iter(|| {
            let mut sum = 0.0f32;
            for &(x, z) in &points {
                sum += state
                    .foam_view()
                    .foam_at(black_box(x), z)
                    .expect("finite")
                    .total;
            }
            sum
        })
    });
    group.bench_function("coarse_lookup_4096", |b| {
        b.iter(|| {
            let mut sum = 0.0f32;
            for &(x, z) in &points {
                sum += state
                    .foam_view()
                    .breaking_at(black_box(x), z)
                    .expect("finite");
            }
            sum
        })
    });
    group.finish();
}

criterion_group!(benches, foam_detail);
criterion_main!(benches);
