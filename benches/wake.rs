//! The cost of wakes (issue 40): the default ocean's step at 256² beside the same ocean with
//! the default wake window (256 cells of 0.5 m, ticks of 1/60 s) and four moving hulls, one
//! after the other in one process, on one thread and on two; and the wake window alone at
//! 128, 256 and 512 cells (how it grows with the window).
//!
//! Groups:
//! - `ocean_wakes`: `step_1t`, `step_wakes_1t`, `step_2t`, `step_wakes_2t` (a 1/60 s step:
//!   one wake tick each). The target: `step_wakes_1t` ≤ 1.3 × `step_1t`.
//! - `wake_window`: `step_wakes_1t` of a one-cascade 64² ocean with wake windows of 128,
//!   256 and 512 cells (the window's share dominates).
//!
//! `cargo bench -p ocean-fft-benches --bench wake`; the first line printed names the CPU.

mod common;

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, SamplingMode, Throughput};
use ocean_fft::{Hull, OceanConfig, OceanState, Spectrum, WakeConfig};

/// Four boats crossing the default window.
fn hulls() -> Vec<Hull> {
    (0..4)
        .map(|k| {
            let k = f64::from(k);
            Hull {
                position: [-40.0 + 20.0 * k, -30.0 + 15.0 * k],
                velocity: [6.0, 1.0 - 0.5 * k as f32],
                heading: 0.1 * k as f32,
                length: 12.0 + 2.0 * k as f32,
                beam: 4.0,
                draft: 0.8,
            }
        })
        .collect()
}

fn ocean(size: usize, lengths: Vec<f32>, wakes: Option<WakeConfig>) -> OceanState {
    let spectrum = Spectrum::jonswap(10.0, 100_000.0).expect("valid spectrum");
    let has_wakes = wakes.is_some();
    let config = OceanConfig {
        size,
        lengths,
        wakes,
        ..OceanConfig::default()
    };
    let mut ocean = OceanState::new(spectrum, config).expect("valid ocean");
    if has_wakes {
        ocean.set_hulls(&hulls()).expect("valid hulls");
    }
    ocean
}

fn ocean_wakes(c: &mut Criterion) {
    let mut group = c.benchmark_group("ocean_wakes");
    group
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(30)
        .throughput(Throughput::Elements(256 * 256));
    let lengths = OceanConfig::default().lengths;
    for threads in [1, 2] {
        let pool = common::pool(threads);
        for (name, wakes) in [("step", None), ("step_wakes", Some(WakeConfig::default()))] {
            let mut state = ocean(256, lengths.clone(), wakes);
            group.bench_function(BenchmarkId::new(format!("{name}_{threads}t"), 256), |b| {
                pool.install(|| b.iter(|| state.step(black_box(1.0 / 60.0)).expect("step")))
            });
        }
    }
    group.finish();
}

fn wake_window(c: &mut Criterion) {
    let mut group = c.benchmark_group("wake_window");
    group
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .sample_size(20);
    let pool = common::pool(1);
    for size in [128, 256, 512] {
        group.throughput(Throughput::Elements((size * size) as u64));
        let wakes = WakeConfig {
            size,
            ..WakeConfig::default()
        };
        let mut state = ocean(64, vec![200.0], Some(wakes));
        group.bench_function(BenchmarkId::new("step_wakes_1t", size), |b| {
            pool.install(|| b.iter(|| state.step(black_box(1.0 / 60.0)).expect("step")))
        });
    }
    group.finish();
}

fn main() {
    common::print_machine();
    let mut criterion = Criterion::default().configure_from_args();
    ocean_wakes(&mut criterion);
    wake_window(&mut criterion);
    criterion.final_summary();
}
