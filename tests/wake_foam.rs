//! The wake's foam trail (issue 40, item 3): made where a moving hull breaks the water and on
//! the wake's breaking crests, none ahead of the bow nor from a hull at rest once its start-up
//! splash has faded, fading along the track with the ocean's residual-foam lifetime (checked
//! against the exponential law), and seen by every foam query.
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

use ocean_fft::{FoamConfig, Hull, OceanConfig, OceanState, Spectrum, WakeConfig, Wakes};

/// An ocean whose own waves are tiny (a light breeze) with the default wake window, its
/// residual foam lasting `lifetime` s.
fn ocean(lifetime: f32) -> OceanState {
    let spectrum = Spectrum::jonswap(2.0, 1000.0).unwrap();
    let config = OceanConfig {
        size: 16,
        wakes: Some(WakeConfig::default()),
        foam: FoamConfig {
            residual_decay: lifetime,
            ..FoamConfig::default()
        },
        ..OceanConfig::default()
    }
    .with_fitted_lengths(&spectrum)
    .unwrap();
    OceanState::new(spectrum, config).unwrap()
}

/// A 20 m × 5 m hull of `draft` m running along +x at `speed` m/s for `seconds` in steps of
/// 1/30 s, the window keeping it 30 m ahead of its centre; the ocean and the hull's final x.
fn run(speed: f32, draft: f32, seconds: f64, lifetime: f32) -> (OceanState, f64) {
    let mut ocean = ocean(lifetime);
    let start = -40.0;
    ocean
        .set_hulls(&[Hull {
            position: [start, 0.0],
            velocity: [speed, 0.0],
            draft,
            ..Hull::default()
        }])
        .unwrap();
    let steps = (seconds * 30.0).round() as i32;
    for step in 1..=steps {
        ocean.step_to(f64::from(step) / 30.0).unwrap();
        let x = start + f64::from(speed) * ocean.time();
        ocean.set_wake_centre(x - 30.0, 0.0).unwrap();
    }
    let x = start + f64::from(speed) * ocean.time();
    (ocean, x)
}

fn wakes(ocean: &OceanState) -> &Wakes {
    ocean.wakes().unwrap()
}

#[test]
fn the_trail_behind_a_hull_fades_with_the_foam_lifetime() {
    // 3 m/s for 40 s: 120 m of track, the last 90 m inside the window. Points 15 m and 45 m
    // behind the centre are behind the stern (10 m) and away from the window's border.
    for lifetime in [15.0f32, 30.0] {
        let (ocean, x) = run(3.0, 1.0, 40.0, lifetime);
        let w = wakes(&ocean);
        let near = f64::from(w.foam_at(x - 15.0, 0.0));
        let far = f64::from(w.foam_at(x - 45.0, 0.0));
        assert!(near > 0.3, "near {near}");
        // The foam at 45 m was made 30 m / 3 m/s = 10 s before that at 15 m, with the same
        // sources (the hull's speed is steady, the sea flat): the ratio is e^(−10 s/lifetime).
        // 1 %: both points are read bilinearly between cells 0.5 m apart, and at 3 m/s the
        // wake's crests (which would add foam) stay below the breaking slope.
        let expected = (-10.0 / f64::from(lifetime)).exp();
        assert!(
            (far / near / expected - 1.0).abs() < 0.01,
            "lifetime {lifetime}: {far} / {near} against {expected}"
        );
        // Ahead of the bow's foam (10 m ahead of the centre, its disc 2.5 m across) the water
        // has none.
        for dz in [-3.0, 0.0, 3.0] {
            for ahead in [13.0, 20.0, 40.0] {
                assert_eq!(
                    w.foam_at(x + ahead, dz),
                    0.0,
                    "{ahead} m ahead, {dz} m aside"
                );
            }
        }
    }
}

#[test]
fn breaking_crests_whiten_beside_the_track_for_a_fast_hull_only() {
    // Beside the bow and stern discs (radius 2.5 m), 20–40 m behind the centre: only the
    // wake's crests make foam there. At 8 m/s (length Froude number 0.57) the diverging
    // waves are steep enough to break; at 2 m/s (0.14) they are far from it.
    let beside = |ocean: &OceanState, x: f64| {
        let w = wakes(ocean);
        let mut most = 0.0f32;
        for k in 0..=20 {
            for dz in [-6.0, -4.5, 4.5, 6.0] {
                most = most.max(w.foam_at(x - 20.0 - f64::from(k), dz));
            }
        }
        most
    };
    // 30 s: the start-up splash 60 m or more behind, out of the way.
    let (fast, x) = run(8.0, 1.0, 30.0, 15.0);
    let (slow, y) = run(2.0, 1.0, 30.0, 15.0);
    assert!(beside(&fast, x) > 0.2, "fast {}", beside(&fast, x));
    assert_eq!(beside(&slow, y), 0.0);
    // More foam in all with speed and, for the crests, with draft.
    let total = |ocean: &OceanState| {
        wakes(ocean)
            .foam()
            .iter()
            .map(|&f| f64::from(f))
            .sum::<f64>()
    };
    let (shallow, _) = run(8.0, 0.5, 30.0, 15.0);
    assert!(total(&fast) > 2.0 * total(&slow));
    assert!(total(&fast) > 1.5 * total(&shallow));
}

#[test]
fn a_hull_at_rest_makes_no_lasting_foam() {
    // Set down on the water, a hull makes a start-up splash; its foam fades with the
    // lifetime (15 s), and the steady dip under the hull is no crest: after 90 s (six
    // lifetimes, e^−6 = 0.0025 of any foam) almost nothing is left.
    let (ocean, _) = run(0.0, 1.0, 90.0, 15.0);
    let most = wakes(&ocean).foam().iter().fold(0.0f32, |a, &b| a.max(b));
    assert!(most < 0.005, "{most}");
}

#[test]
fn foam_queries_include_the_trail() {
    let (mut ocean, x) = run(6.0, 1.0, 8.0, 15.0);
    let w = wakes(&ocean).clone();
    let water = ocean.water();
    let view = ocean.foam_view();
    let mut seen = 0;
    for k in 0..40 {
        let (x0, z0) = (x - 40.0 + f64::from(k) * 1.3, f64::from(k % 7) - 3.0);
        let rest = water.at_rest(x0, z0).unwrap();
        let coverage = view.foam_at(x0, z0).unwrap();
        // foam_at's total is the trail where the water lands laid over the ocean's detailed
        // foam d: d + w(1 − d), so at least the trail and at most 1, and what is left of it
        // once the trail is taken out, d, is a foam value in [0, 1]; active whitecaps are the
        // ocean's alone.
        let [dx, dz] = rest.displacement.map(f64::from);
        let trail = w.foam_at(x0 + dx, z0 + dz);
        assert!(coverage.total >= trail - 1e-6 && coverage.total <= 1.0);
        if trail < 0.99 {
            let detail = (coverage.total - trail) / (1.0 - trail);
            assert!((-1e-5..=1.0 + 1e-5).contains(&detail), "{detail}");
        }
        let ocean_alone = rest.foam - trail;
        assert!(
            (ocean_alone / (1.0 - trail).max(1e-6)).abs() < 0.05,
            "{ocean_alone}"
        );
        assert!((coverage.active + coverage.residual - coverage.total).abs() < 1e-6);
        let at = water.surface_at(x0, z0).unwrap();
        assert!(at.foam >= w.foam_at(x0, z0) - 1e-6);
        if trail > 0.1 {
            seen += 1;
        }
    }
    assert!(seen > 5, "{seen} points on the trail");
    // A shorter lifetime from now on fades the trail faster: over 6 s a lifetime of 2 s
    // leaves e^−3 = 0.05 of the foam, 15 s leaves e^−0.4 = 0.67 (and the crests still
    // running and the hull make some in both).
    let mut control = ocean.clone();
    let config = FoamConfig {
        residual_decay: 2.0,
        ..FoamConfig::default()
    };
    ocean.set_foam_config(config).unwrap();
    let t = ocean.time();
    ocean.step_to(t + 6.0).unwrap();
    control.step_to(t + 6.0).unwrap();
    let sum = |ocean: &OceanState| {
        wakes(ocean)
            .foam()
            .iter()
            .map(|&f| f64::from(f))
            .sum::<f64>()
    };
    assert!(
        sum(&ocean) < 0.5 * sum(&control),
        "{} against {}",
        sum(&ocean),
        sum(&control)
    );
}
