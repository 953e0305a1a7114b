//! Steps with a [`Surface`] handle in use allocate nothing: the counting global allocator
//! sees every allocation of every thread (so this test has a binary of its own: another
//! test running beside it would be counted too).

mod counting;

use counting::count;
use ocean_fft::{OceanConfig, OceanState, Spectrum, Surface};

#[global_allocator]
static GLOBAL: counting::Counting = counting::Counting;

/// A game whose physics reads a [`Surface`] handle of frame n while frame n + 1 steps: the
/// ocean's two frames take turns, so no step and no handle allocates once both frames have
/// been used.
#[test]
fn stepping_with_a_surface_handle_in_use_allocates_nothing() {
    let spectrum = Spectrum::jonswap(12.0, 200_000.0).unwrap();
    let pools = counting::warm_pools(&[2]);
    let pool = &pools[0];
    let config = OceanConfig {
        size: 128,
        ..OceanConfig::default()
    };
    let mut ocean = OceanState::new(spectrum, config).unwrap();
    let points: Vec<[f64; 2]> = (0..256).map(|i| [f64::from(i) * 1.7, -3.0]).collect();
    let mut heights = vec![0.0; points.len()];
    let (before, after) = pool.install(|| {
        let mut held: Option<Surface> = None;
        // Warm-up: both frames get their copies' room.
        for _ in 0..4 {
            ocean.step(1.0 / 60.0).unwrap();
            let surface = ocean.surface();
            surface.water().heights_at(&points, &mut heights).unwrap();
            held = Some(surface);
        }
        let before = count();
        for _ in 0..100 {
            // The handle of the frame before is still held while this step runs.
            ocean.step(1.0 / 60.0).unwrap();
            let surface = ocean.surface();
            surface.water().heights_at(&points, &mut heights).unwrap();
            let _ = surface.water().height_at(3.0, 4.0).unwrap();
            let _ = held.as_ref().map(|old| old.water().height_at(3.0, 4.0));
            held = Some(surface);
        }
        (before, count())
    });
    assert_eq!(
        after - before,
        0,
        "{} allocations in 100 frames with a handle in use",
        after - before
    );
}
