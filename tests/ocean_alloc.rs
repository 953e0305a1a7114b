//! `OceanState::step` allocates nothing once built, during a change of weather and with
//! second-order waves too: a counting
//! global allocator sees every allocation of every thread, rayon's workers included.
//!
//! The frames run inside `ThreadPool::install`, as a game that owns a pool does. Called from
//! a thread outside every pool, each parallel call is handed to rayon through its global
//! injector queue, which allocates one 1.5 KiB block per 63 jobs it receives — rayon's
//! allocation, amortised to a few bytes a frame, not the crate's.

mod counting;

use counting::count;
use ocean_fft::{Determinism, OceanConfig, OceanState, Spectrum};

#[global_allocator]
static GLOBAL: counting::Counting = counting::Counting;

#[test]
fn stepping_and_querying_allocate_nothing() {
    let spectrum = Spectrum::jonswap(12.0, 200_000.0).unwrap();
    // Every worker runs once and settles before anything is counted (as in tests/alloc.rs).
    let pools = counting::warm_pools(&[2]);
    let pool = &pools[0];
    let modes = [Determinism::SameMachine, Determinism::CrossPlatform];
    for (parallel_cascades, determinism, second_order) in [
        (false, modes[0], false),
        (true, modes[0], false),
        (true, modes[1], false),
        (true, modes[0], true),
    ] {
        let config = OceanConfig {
            size: 128,
            parallel_cascades,
            determinism,
            second_order,
            ..OceanConfig::default()
        };
        let mut ocean = OceanState::new(spectrum.clone(), config).unwrap();
        // A change of weather's buffers are made by the first `set_spectrum`, before counting.
        let squall = Spectrum::jonswap(18.0, 200_000.0)
            .unwrap()
            .with_wind_direction(1.0)
            .unwrap();
        ocean.set_spectrum(squall.clone(), 0.0).unwrap();
        let points: Vec<[f64; 2]> = (0..256).map(|i| [f64::from(i) * 1.7, -3.0]).collect();
        let mut heights = vec![0.0; points.len()];
        // A rollback ring's slot, filled once before counting.
        let mut snapshot = ocean.snapshot();
        let (before, after) = pool.install(|| {
            // Warm-up: the first parallel calls size the workers' queues.
            for _ in 0..3 {
                ocean.step(1.0 / 60.0).unwrap();
                ocean.water().heights_at(&points, &mut heights).unwrap();
            }
            let before = count();
            for frame in 0..200 {
                ocean.step(1.0 / 60.0).unwrap();
                ocean.water().heights_at(&points, &mut heights).unwrap();
                let _ = ocean.water().at_rest(3.0, 4.0).unwrap();
                let _ = ocean.water().locate(3.0, 4.0).unwrap();
                let _ = ocean.foam_view().breaking_at(3.0, 4.0).unwrap();
                let _ = ocean.foam_view().coverage();
                // A networked game: follow a given clock, keep snapshots, roll back.
                let t = ocean.time();
                ocean.step_to(t + 0.01).unwrap();
                snapshot.capture(&ocean);
                if frame % 50 == 49 {
                    ocean.restore(&snapshot).unwrap();
                }
                // A bake or a joining client: spin the foam up from nothing.
                if frame % 100 == 99 {
                    ocean.pre_roll(0.5, 0.1).unwrap();
                }
                // The weather changes: the new sea prepared and blended in over the frames.
                if frame == 10 {
                    ocean.set_spectrum(spectrum.clone(), 1.0).unwrap();
                }
                if frame == 120 {
                    ocean.set_spectrum(squall.clone(), 0.5).unwrap();
                }
            }
            (before, count())
        });
        assert_eq!(
            after - before,
            0,
            "parallel_cascades = {parallel_cascades}, second order {second_order}: {} allocations in 200 frames",
            after - before
        );
    }
}
