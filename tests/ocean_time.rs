//! Time for networked and saved games: following a given clock, jumping, snapshots and
//! rollback, cloning; and the world queries added with them (`locate`, `sample_grid`).
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

use std::ops::Bound;

use ocean_fft::{
    Cascade, CascadeConfig, Error, OceanConfig, OceanState, QueryConfig, SeaState, Spectrum,
    SurfaceSample,
};

fn ocean(size: usize, choppiness: f32) -> OceanState {
    let (spectrum, mut config) = SeaState::FreshBreeze.build();
    config.size = size;
    config.choppiness = choppiness;
    OceanState::new(spectrum, config).unwrap()
}

/// Every buffer of every cascade, the foam buffers, the coverage and the time, bit for bit.
fn bits(ocean: &OceanState) -> Vec<u32> {
    let mut out = vec![
        (ocean.time().to_bits() >> 32) as u32,
        ocean.time().to_bits() as u32,
    ];
    for buffer in [
        ocean.foam_view().total(),
        ocean.foam_view().active(),
        ocean.foam_view().residual(),
        ocean.foam_view().breaking(),
    ] {
        out.extend(buffer.iter().map(|v| v.to_bits()));
    }
    let c = ocean.foam_view().coverage();
    out.extend([c.active, c.residual, c.total].map(f32::to_bits));
    for cascade in ocean.cascades() {
        out.extend(cascade.height().iter().map(|v| v.to_bits()));
        out.extend(cascade.jacobian().iter().map(|v| v.to_bits()));
        out.extend(
            cascade
                .displacement()
                .as_flattened()
                .iter()
                .map(|v| v.to_bits()),
        );
        out.extend(cascade.slope().as_flattened().iter().map(|v| v.to_bits()));
        out.extend(cascade.normal().as_flattened().iter().map(|v| v.to_bits()));
    }
    out
}

fn foam_total(ocean: &OceanState) -> f64 {
    ocean
        .foam_view()
        .total()
        .iter()
        .map(|&f| f64::from(f))
        .sum()
}

#[test]
fn step_to_follows_a_given_clock_with_the_foam() {
    // A client follows a server clock with jittery frame times; a reference steps the same
    // intervals. The waves depend only on the time, so the cascades agree bit for bit; the
    // foam integrates the same intervals, so it agrees to rounding of the differences.
    let mut client = ocean(32, 1.6);
    let mut reference = ocean(32, 1.6);
    let mut server_time = 0.0f64;
    for frame in 0..240 {
        let dt = 1.0 / 60.0 + 0.004 * f64::from(frame % 7) - 0.012;
        server_time += dt;
        client.step_to(server_time).unwrap();
        reference.step(dt).unwrap();
    }
    assert_eq!(client.time(), server_time);
    assert!(foam_total(&client) > 1.0, "the test sea must make foam");
    for (a, b) in client.cascades().iter().zip(reference.cascades()) {
        assert_eq!(a.height(), b.height());
        assert_eq!(a.jacobian(), b.jacobian());
    }
    for (a, b) in client
        .foam_view()
        .total()
        .iter()
        .zip(reference.foam_view().total())
    {
        // Each interval t_k − t_(k−1) differs from dt by at most an ulp of t (4e-15 s
        // here); over 240 frames the foam differs by far less than 1e-6.
        assert!((a - b).abs() < 1e-6, "{a} vs {b}");
    }
}

#[test]
fn step_to_refuses_going_back_or_too_far_and_changes_nothing() {
    let mut ocean = ocean(16, 1.0);
    ocean.step(2.0).unwrap();
    let before = bits(&ocean);
    assert_eq!(
        ocean.step_to(1.5),
        Err(Error::OutOfRange {
            name: "t",
            value: 1.5,
            min: Bound::Included(2.0),
            max: Bound::Included(2.0 + ocean_fft::limits::MAX_STEP),
        })
    );
    assert!(matches!(
        ocean.step_to(2.0 + ocean_fft::limits::MAX_STEP * 2.0),
        Err(Error::OutOfRange { name: "t", .. })
    ));
    assert_eq!(ocean.step_to(f64::NAN), Err(Error::NonFinite { name: "t" }));
    assert_eq!(bits(&ocean), before);
    // The same time again is a step of zero: nothing moves.
    ocean.step_to(2.0).unwrap();
    assert_eq!(bits(&ocean), before);
}

#[test]
fn set_time_keeps_the_foam_and_clear_foam_removes_it() {
    let mut ocean = ocean(32, 1.6);
    for _ in 0..60 {
        ocean.step(1.0 / 30.0).unwrap();
    }
    let foam = ocean.foam_view().total().to_vec();
    assert!(foam_total(&ocean) > 1.0);
    ocean.set_time(-500.0).unwrap();
    assert_eq!(ocean.time(), -500.0);
    assert_eq!(ocean.foam_view().total(), foam.as_slice());
    // The cascades are those of t = −500 s.
    let mut fresh = ocean.clone();
    fresh.set_time(-500.0).unwrap();
    assert_eq!(bits(&fresh), bits(&ocean));
    ocean.clear_foam();
    assert_eq!(foam_total(&ocean), 0.0);
}

#[test]
fn a_restored_snapshot_steps_to_the_same_bits() {
    let mut original = ocean(32, 1.6);
    for _ in 0..45 {
        original.step(1.0 / 30.0).unwrap();
    }
    original.set_choppiness(1.2).unwrap();
    let snapshot = original.snapshot();
    let at_snapshot = bits(&original);
    let mut later = Vec::new();
    for _ in 0..30 {
        original.step(1.0 / 30.0).unwrap();
        later.push(bits(&original));
    }

    // Roll the same ocean back, and restore into a fresh one built from the same config.
    let mut fresh = ocean(32, 1.6);
    fresh.step(7.0).unwrap();
    for target in [&mut original, &mut fresh] {
        target.restore(&snapshot).unwrap();
        assert_eq!(bits(target), at_snapshot);
        assert_eq!(target.config().choppiness, 1.2);
        for expected in &later {
            target.step(1.0 / 30.0).unwrap();
            assert_eq!(&bits(target), expected);
        }
    }

    // A clone steps like the original too.
    let mut clone = original.clone();
    original.step(0.1).unwrap();
    clone.step(0.1).unwrap();
    assert_eq!(bits(&clone), bits(&original));

    // capture refills an existing snapshot to the same value.
    let mut reused = snapshot.clone();
    reused.capture(&original);
    assert_eq!(reused, original.snapshot());
    assert_eq!(reused.time(), original.time());
}

#[test]
fn a_snapshot_of_other_grids_is_refused_and_changes_nothing() {
    let small = ocean(16, 1.0).snapshot();
    let mut ocean = ocean(32, 1.0);
    ocean.step(1.0).unwrap();
    let before = bits(&ocean);
    assert_eq!(
        ocean.restore(&small),
        Err(Error::LengthMismatch {
            name: "snapshot.active",
            expected: 32 * 32,
            got: 16 * 16
        })
    );
    assert_eq!(bits(&ocean), before);
}

#[test]
fn locate_reports_convergence_honestly() {
    // On a gentle sea every point converges, and the located water lands where asked.
    let gentle = ocean(64, 1.0);
    for i in 0..200 {
        let (x, z) = (f64::from(i) * 3.7 - 300.0, f64::from(i) * 1.3);
        let found = gentle.water().locate(x, z).unwrap();
        assert!(found.converged && found.miss < 1e-4, "{found:?}");
        let water = gentle
            .water()
            .at_rest(found.undisplaced[0], found.undisplaced[1])
            .unwrap();
        let landed = [
            found.undisplaced[0] + f64::from(water.displacement[0]),
            found.undisplaced[1] + f64::from(water.displacement[1]),
        ];
        let miss = (landed[0] - x).hypot(landed[1] - z);
        assert!(
            (miss - f64::from(found.miss)).abs() < 1e-6,
            "{miss} vs {found:?}"
        );
        assert_eq!(gentle.water().height_at(x, z).unwrap(), water.height);
    }

    // At the largest choppiness the ocean accepts (the surface folded on about half its area),
    // with a single Newton step allowed and a tolerance of a micrometre, many searches end
    // before they converge, and locate says so, with the miss it measured (checked
    // independently here).
    let (spectrum, mut config) = SeaState::FreshBreeze.build();
    config.size = 64;
    config.query = QueryConfig {
        max_iterations: 1,
        tolerance: 1e-6,
        ..QueryConfig::default()
    };
    let mut folded = OceanState::new(spectrum, config).unwrap();
    folded
        .set_choppiness(folded.diagnostics().max_choppiness())
        .unwrap();
    let mut failures = 0;
    for i in 0..200 {
        let (x, z) = (f64::from(i) * 3.7 - 300.0, f64::from(i) * 1.3);
        let found = folded.water().locate(x, z).unwrap();
        let water = folded
            .water()
            .at_rest(found.undisplaced[0], found.undisplaced[1])
            .unwrap();
        let miss = (found.undisplaced[0] + f64::from(water.displacement[0]) - x)
            .hypot(found.undisplaced[1] + f64::from(water.displacement[1]) - z);
        assert!((miss / f64::from(found.miss) - 1.0).abs() < 1e-3 || miss < 1e-6);
        assert_eq!(found.converged, found.miss < 1e-6);
        if !found.converged {
            failures += 1;
        }
    }
    assert!(
        failures > 50,
        "only {failures} of 200 points failed to converge at the largest choppiness"
    );
}

#[test]
fn relaxed_iteration_converges_where_the_plain_one_overshoots() {
    // At the largest choppiness the ocean accepts the displacement's gradient is far beyond 1:
    // the plain fixed point x₀ ← p − D(x₀) overshoots at most points. Relaxed, most points find
    // water that lands within the tolerance.
    let (spectrum, mut config) = SeaState::FreshBreeze.build();
    config.size = 64;
    config.query = QueryConfig {
        max_iterations: 100,
        ..QueryConfig::default()
    };
    let mut ocean = OceanState::new(spectrum, config).unwrap();
    ocean
        .set_choppiness(ocean.diagnostics().max_choppiness())
        .unwrap();
    let converged = (0..1000)
        .filter(|&i| {
            let (x, z) = (f64::from(i) * 7.31 % 900.0, f64::from(i) * 13.7 % 700.0);
            ocean.water().locate(x, z).unwrap().converged
        })
        .count();
    assert!(converged >= 500, "{converged} of 1000");
}

#[test]
fn sample_grid_is_sample_on_a_grid() {
    let ocean = ocean(32, 1.0);
    let (columns, rows) = (37, 23);
    let origin = [-1234.5, 987.25];
    let spacing = 3.25;
    let mut grid = vec![SurfaceSample::default(); columns * rows];
    ocean
        .water()
        .at_rest_grid(origin, spacing, [columns, rows], &mut grid)
        .unwrap();
    for r in 0..rows {
        for c in 0..columns {
            let x = origin[0] + c as f64 * spacing;
            let z = origin[1] + r as f64 * spacing;
            assert_eq!(
                grid[r * columns + c],
                ocean.water().at_rest(x, z).unwrap(),
                "({c}, {r})"
            );
        }
    }
    // Errors name the argument and write nothing.
    let sentinel = SurfaceSample {
        height: -7.0,
        ..SurfaceSample::default()
    };
    let mut out = vec![sentinel; 12];
    let cases = [
        (
            ocean
                .water()
                .at_rest_grid(origin, spacing, [4, 4], &mut out),
            "out",
        ),
        (
            ocean.water().at_rest_grid(origin, 0.0, [4, 3], &mut out),
            "spacing",
        ),
        (
            ocean
                .water()
                .at_rest_grid(origin, f64::NAN, [4, 3], &mut out),
            "spacing",
        ),
        (
            ocean.water().at_rest_grid(origin, 1e308, [4, 3], &mut out),
            "spacing",
        ),
        (
            ocean
                .water()
                .at_rest_grid([f64::INFINITY, 0.0], 1.0, [4, 3], &mut out),
            "x",
        ),
        (
            ocean.water().at_rest_grid(origin, 1.0, [0, 3], &mut out),
            "columns",
        ),
        (
            ocean
                .water()
                .at_rest_grid(origin, 1.0, [usize::MAX, 3], &mut out),
            "rows",
        ),
    ];
    for (result, name) in cases {
        let error = result.unwrap_err();
        let named = match error {
            Error::NonFinite { name }
            | Error::OutOfRange { name, .. }
            | Error::CountOutOfRange { name, .. }
            | Error::LengthMismatch { name, .. } => name,
            other => panic!("unexpected {other:?}"),
        };
        assert_eq!(named, name, "{error:?}");
    }
    assert!(out.iter().all(|s| *s == sentinel));
}

#[test]
fn a_cascade_clone_updates_to_the_same_bits() {
    let spectrum = Spectrum::jonswap(10.0, 100_000.0).unwrap();
    let config = CascadeConfig {
        size: 32,
        length: 200.0,
        ..CascadeConfig::default()
    };
    let mut a = Cascade::new(&spectrum, config).unwrap();
    let mut b = a.clone();
    a.update(12.5).unwrap();
    b.update(12.5).unwrap();
    assert_eq!(a.height(), b.height());
    assert_eq!(a.normal(), b.normal());
    let _ = OceanConfig::default();
}
