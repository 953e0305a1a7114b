//! Steps with wakes allocate nothing once built: the wake's ticks, its hulls and the moves
//! of its window included (a counting global allocator sees every thread's allocations).

mod counting;

use counting::count;
use ocean_fft::{Determinism, Hull, OceanConfig, OceanState, Spectrum, WakeConfig};

#[global_allocator]
static GLOBAL: counting::Counting = counting::Counting;

#[test]
fn stepping_with_wakes_allocates_nothing() {
    let spectrum = Spectrum::jonswap(8.0, 50_000.0).unwrap();
    let pools = counting::warm_pools(&[2]);
    let pool = &pools[0];
    for determinism in [Determinism::SameMachine, Determinism::CrossPlatform] {
        let config = OceanConfig {
            size: 32,
            determinism,
            wakes: Some(WakeConfig {
                size: 64,
                spacing: 1.0,
                ..WakeConfig::default()
            }),
            ..OceanConfig::default()
        };
        let mut ocean = OceanState::new(spectrum.clone(), config).unwrap();
        let hulls: Vec<Hull> = (0..4)
            .map(|k| Hull {
                position: [f64::from(k) * 8.0 - 12.0, f64::from(k) * 3.0],
                velocity: [4.0, 0.5 * f32::from(k as u8)],
                heading: 0.1 * f32::from(k as u8),
                ..Hull::default()
            })
            .collect();
        let points: Vec<[f64; 2]> = (0..256).map(|i| [f64::from(i) * 0.3, -3.0]).collect();
        let mut heights = vec![0.0; points.len()];
        let (before, after) = pool.install(|| {
            for _ in 0..3 {
                ocean.set_hulls(&hulls).unwrap();
                ocean.step(1.0 / 60.0).unwrap();
                ocean.water().heights_at(&points, &mut heights).unwrap();
            }
            let before = count();
            for frame in 0..120 {
                ocean.set_hulls(&hulls).unwrap();
                ocean.step(1.0 / 60.0).unwrap();
                ocean.set_wake_centre(f64::from(frame) * 0.1, 0.0).unwrap();
                ocean.water().heights_at(&points, &mut heights).unwrap();
                let _ = ocean.water().at_rest(3.0, 4.0).unwrap();
                let _ = ocean.water().surface_at(3.0, 4.0).unwrap();
            }
            (before, count())
        });
        assert_eq!(
            after - before,
            0,
            "{determinism:?}: {} allocations",
            after - before
        );
    }
}
