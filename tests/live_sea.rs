//! The live sea (`OceanState::set_spectrum`, `set_foam_config`): exact at the end of a change,
//! continuous during it, the foam following the new wind, depth changes refused, bad input
//! refused with nothing changed.
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

use ocean_fft::{
    Determinism, Dispersion, Error, FoamConfig, OceanConfig, OceanState, Spectrum, Spreading,
};

/// Every buffer and number of `ocean` against `fresh`, bit for bit.
fn assert_same_sea(ocean: &OceanState, fresh: &OceanState, what: &str) {
    assert_eq!(
        ocean.time().to_bits(),
        fresh.time().to_bits(),
        "{what}: time"
    );
    for (c, (a, b)) in ocean.cascades().iter().zip(fresh.cascades()).enumerate() {
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let flat2 = |v: &[[f32; 2]]| v.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
        let flat3 = |v: &[[f32; 3]]| v.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert!(a.h0() == b.h0(), "{what}: cascade {c} h0");
        assert_eq!(
            bits(a.height()),
            bits(b.height()),
            "{what}: cascade {c} height"
        );
        assert_eq!(
            flat2(a.displacement()),
            flat2(b.displacement()),
            "{what}: c{c} disp"
        );
        assert_eq!(
            flat2(a.slope()),
            flat2(b.slope()),
            "{what}: cascade {c} slope"
        );
        assert_eq!(
            flat3(a.normal()),
            flat3(b.normal()),
            "{what}: cascade {c} normal"
        );
        assert_eq!(
            bits(a.jacobian()),
            bits(b.jacobian()),
            "{what}: cascade {c} jacobian"
        );
        assert_eq!(
            a.expected_variance(),
            b.expected_variance(),
            "{what}: c{c} variance"
        );
        assert_eq!(
            a.mean_level_offset(),
            b.mean_level_offset(),
            "{what}: c{c} mean level"
        );
        assert_eq!(
            a.subgrid_slope_variance(),
            b.subgrid_slope_variance(),
            "{what}: c{c}"
        );
        assert_eq!(
            a.loop_error(),
            b.loop_error(),
            "{what}: cascade {c} loop error"
        );
    }
    assert_eq!(
        ocean.foam_view().calibration(),
        fresh.foam_view().calibration(),
        "{what}: calibration"
    );
    assert_eq!(ocean.spectrum(), fresh.spectrum(), "{what}: spectrum");
}

/// Steps `ocean` by `dt` until its change of weather is over (at most `limit` steps).
fn finish_change(ocean: &mut OceanState, dt: f64, limit: usize) {
    for _ in 0..limit {
        if ocean.diagnostics().transition_progress().is_none() {
            return;
        }
        ocean.step(dt).unwrap();
    }
    panic!("the change did not end within {limit} steps");
}

fn small(determinism: Determinism, repeat_period: Option<f32>) -> OceanConfig {
    OceanConfig {
        size: 32,
        determinism,
        repeat_period,
        ..OceanConfig::default()
    }
}

/// Once a change is over, every cascade buffer, the amplitudes, the statistics and the foam
/// calibration are those of an ocean built with the new spectrum at the same time: the
/// change installs what `OceanState::new` computes, by the same code (checked bit for bit).
/// Changes of wind speed, fetch, direction, spreading, swell and model, in both modes, with
/// and without a loop and with second-order waves (which follow the blended amplitudes:
/// they are formed from the evolution table each step), with `duration` 0 (the next step)
/// and longer, and a second change in the middle of a first.
#[test]
fn the_sea_after_a_change_is_the_new_sea_bit_for_bit() {
    let calm = Spectrum::jonswap(6.0, 40_000.0).unwrap();
    let storm = Spectrum::jonswap(18.0, 300_000.0)
        .unwrap()
        .with_wind_direction(1.1)
        .unwrap();
    let swell = Spectrum::pierson_moskowitz(12.0)
        .unwrap()
        .with_spreading(Spreading::DonelanBanner)
        .unwrap()
        .with_swell(0.8)
        .unwrap()
        .with_wind_direction(-2.5)
        .unwrap();
    for determinism in [Determinism::SameMachine, Determinism::CrossPlatform] {
        for (repeat, second_order) in [(None, false), (Some(40.0), false), (None, true)] {
            for (from, to, duration) in [
                (&calm, &storm, 0.0),
                (&calm, &storm, 2.0),
                (&storm, &swell, 0.7),
                (&swell, &calm, 0.0),
            ] {
                let config = OceanConfig {
                    second_order,
                    ..small(determinism, repeat)
                };
                let mut ocean = OceanState::new(from.clone(), config.clone()).unwrap();
                for _ in 0..5 {
                    ocean.step(0.1).unwrap();
                }
                ocean.set_spectrum(to.clone(), duration).unwrap();
                assert_eq!(ocean.spectrum(), to);
                assert!(ocean.diagnostics().transition_progress().is_some());
                if duration == 0.0 {
                    // At once: the next step shows the new sea.
                    ocean.step(0.1).unwrap();
                    assert_eq!(ocean.diagnostics().transition_progress(), None);
                }
                finish_change(&mut ocean, 1.0 / 30.0, 400);
                let mut fresh = OceanState::new(to.clone(), config.clone()).unwrap();
                fresh.set_time(ocean.time()).unwrap();
                let what = format!(
                    "{determinism:?} loop {repeat:?} second order {second_order} duration {duration}"
                );
                assert_same_sea(&ocean, &fresh, &what);
                // And it steps on as the new sea does.
                ocean.step(0.25).unwrap();
                fresh.step(0.25).unwrap();
                assert_same_sea(&ocean, &fresh, &format!("{what}, a step later"));
            }
        }
    }
    // A second change in the middle of a first ends on the second sea.
    let config = small(Determinism::SameMachine, None);
    let mut ocean = OceanState::new(calm.clone(), config.clone()).unwrap();
    ocean.set_spectrum(storm, 3.0).unwrap();
    for _ in 0..60 {
        ocean.step(1.0 / 30.0).unwrap();
    }
    let w = ocean.diagnostics().transition_progress().unwrap();
    assert!(w > 0.05 && w < 0.95, "half way: {w}");
    ocean.set_spectrum(swell.clone(), 1.0).unwrap();
    finish_change(&mut ocean, 1.0 / 30.0, 400);
    let mut fresh = OceanState::new(swell, config).unwrap();
    fresh.set_time(ocean.time()).unwrap();
    assert_same_sea(&ocean, &fresh, "a change on top of a change");
}

/// Root-mean-square over every cascade's height buffer of the difference of two sets of
/// buffers, m.
fn rms_change(before: &[Vec<f32>], after: &OceanState) -> f64 {
    let mut sum = 0.0;
    let mut count = 0usize;
    for (old, cascade) in before.iter().zip(after.cascades()) {
        for (a, b) in old.iter().zip(cascade.height()) {
            let d = f64::from(b - a);
            sum += d * d;
            count += 1;
        }
    }
    (sum / count as f64).sqrt()
}

fn heights(ocean: &OceanState) -> Vec<Vec<f32>> {
    ocean
        .cascades()
        .iter()
        .map(|c| c.height().to_vec())
        .collect()
}

/// At 60 fps, no frame of a change moves the surface more than the faster of the two seas
/// moves by itself in that frame (RMS of the height change over every cascade's grid), within
/// what the blend itself must add, and the expected variance moves monotonically from the
/// old sea's to the new sea's. A calm sea turning into a gale and back, and a gale turning by
/// 90°, each over 10 s.
///
/// The two seas alone are simulated beside it at the same times (fresh oceans, the same seed,
/// so the same phases): the comparison is frame by frame. The blended sea moves by itself no
/// faster than the faster sea (its energy at each wave is between theirs); on top of that the
/// blend changes each wave's amplitude b at most at √3·b/duration per second (the
/// smoothstep's steepest slope, for a wave that appears from nothing), against the ω·b of its
/// own motion, and the two add in quadrature (one changes the amplitude, the other the
/// phase). So a frame may move at most √(1 + 3/(ω·duration)²) times the faster sea, ω the
/// lowest angular frequency that carries energy (the peak's, ω_p, to within a few per cent of
/// the energy): 2.7 % for the turns of the gale (ω_p = 0.74 rad/s), where both seas move
/// alike; where one sea is much faster (calm and gale) the blended sea is slower than it and
/// no frame comes near it. Measured: at most 1.0000 (calm and gale, the last frame, when the
/// sea is the new one) and 1.0065 (the turn).
#[test]
fn a_change_moves_the_sea_no_faster_than_the_sea_moves_itself() {
    let calm = Spectrum::jonswap(5.0, 30_000.0).unwrap();
    let gale = Spectrum::jonswap(17.0, 150_000.0)
        .unwrap()
        .with_wind_direction(0.6)
        .unwrap();
    let turned = gale
        .clone()
        .with_wind_direction(0.6 + std::f32::consts::FRAC_PI_2)
        .unwrap();
    let (dt, duration) = (1.0 / 60.0, 10.0);
    for (from, to) in [(&calm, &gale), (&gale, &calm), (&gale, &turned)] {
        let config = OceanConfig {
            size: 64,
            ..OceanConfig::default()
        };
        let mut ocean = OceanState::new(from.clone(), config.clone()).unwrap();
        let mut alone = [
            OceanState::new(from.clone(), config.clone()).unwrap(),
            OceanState::new(to.clone(), config.clone()).unwrap(),
        ];
        let (v_from, v_to) = (
            alone[0].diagnostics().expected_variance(),
            alone[1].diagnostics().expected_variance(),
        );
        let slowest = from.peak_omega().min(to.peak_omega()) as f64;
        let allowed = (1.0 + 3.0 / (slowest * duration).powi(2)).sqrt();
        ocean.set_spectrum(to.clone(), duration).unwrap();
        let mut previous_variance = ocean.diagnostics().expected_variance();
        let mut worst: f64 = 0.0;
        let mut frames = 0;
        while ocean.diagnostics().transition_progress().is_some() {
            let before = heights(&ocean);
            let before_alone = [heights(&alone[0]), heights(&alone[1])];
            ocean.step(dt).unwrap();
            let own = rms_change(&before, &ocean);
            let mut fastest: f64 = 0.0;
            for (sea, before) in alone.iter_mut().zip(&before_alone) {
                sea.step(dt).unwrap();
                fastest = fastest.max(rms_change(before, sea));
            }
            worst = worst.max(own / fastest);
            let variance = ocean.diagnostics().expected_variance();
            // Monotonic, within the rounding of a sum over the grid (1e-12 relative).
            let slack = 1e-12 * variance.max(previous_variance);
            if v_to > v_from {
                assert!(variance >= previous_variance - slack, "frame {frames}");
            } else {
                assert!(variance <= previous_variance + slack, "frame {frames}");
            }
            previous_variance = variance;
            frames += 1;
            assert!(frames < 60 * 60, "the change did not end");
        }
        println!("{frames} frames, largest own/fastest {worst:.4}, allowed {allowed:.4}");
        assert!(
            worst <= allowed,
            "a frame moved {worst}× the faster sea's own motion (allowed {allowed})"
        );
        assert_eq!(previous_variance, v_to);
    }
}

/// The whitecap fraction of Monahan & O'Muircheartaigh (1980): W = 3.84·10⁻⁶ U10^3.41.
fn monahan(wind_speed: f64) -> f64 {
    3.84e-6 * wind_speed.powf(3.41)
}

/// Mean active coverage over `seconds` of steps of `dt`.
fn mean_active(ocean: &mut OceanState, seconds: f64, dt: f64) -> f64 {
    let steps = (seconds / dt).round() as usize;
    let mut sum = 0.0;
    for _ in 0..steps {
        ocean.step(dt).unwrap();
        sum += f64::from(ocean.foam_view().coverage().active);
    }
    sum / steps as f64
}

/// The foam follows a change of wind: after a change from 8 to 15 m/s (and from 15 to 8)
/// over 10 s and 20 s of settling (five active lifetimes), the whitecap coverage measured
/// over 40 s lies within the foam tests' factor 1.5 of Monahan & O'Muircheartaigh at the new
/// wind, as that of an ocean built with the new wind does (measured beside it); the foam is
/// never reset (there is foam at the moment of the change and right after it).
#[test]
fn the_whitecaps_follow_the_new_wind() {
    let dt = 0.1;
    for (from, to) in [(8.0f32, 15.0f32), (15.0, 8.0)] {
        let config = OceanConfig {
            size: 64,
            lengths: vec![400.0, 92.0, 20.5],
            ..OceanConfig::default()
        };
        let mut ocean =
            OceanState::new(Spectrum::pierson_moskowitz(from).unwrap(), config.clone()).unwrap();
        ocean.set_time(500.0).unwrap();
        ocean.pre_roll(20.0, dt).unwrap();
        let before = ocean.foam_view().coverage().total;
        assert!(before > 0.0);
        ocean
            .set_spectrum(Spectrum::pierson_moskowitz(to).unwrap(), 10.0)
            .unwrap();
        ocean.step(dt).unwrap();
        assert!(
            ocean.foam_view().coverage().total > 0.5 * before,
            "the foam was kept"
        );
        while ocean.diagnostics().transition_progress().is_some() {
            ocean.step(dt).unwrap();
        }
        let _ = mean_active(&mut ocean, 20.0, dt);
        let changed = mean_active(&mut ocean, 40.0, dt);
        let mut built =
            OceanState::new(Spectrum::pierson_moskowitz(to).unwrap(), config.clone()).unwrap();
        built.set_time(ocean.time()).unwrap();
        built.pre_roll(20.0, dt).unwrap();
        let fresh = mean_active(&mut built, 40.0, dt);
        let expected = monahan(f64::from(to));
        println!(
            "{from} → {to} m/s: changed {:.3}, built {:.3} of Monahan",
            changed / expected,
            fresh / expected
        );
        for (what, value) in [("changed", changed), ("built", fresh)] {
            let ratio = value / expected;
            assert!((1.0 / 1.5..=1.5).contains(&ratio), "{what}: {ratio}");
        }
    }
}

/// Another water depth is refused, naming the dispersion, and nothing changes; so are a
/// negative, NaN, infinite or too long duration.
#[test]
fn bad_changes_are_errors_that_change_nothing() {
    let config = small(Determinism::SameMachine, None);
    let spectrum = Spectrum::tma(10.0, 100_000.0, 30.0).unwrap();
    let mut ocean = OceanState::new(spectrum.clone(), config.clone()).unwrap();
    ocean.step(0.5).unwrap();
    let reference = ocean.clone();
    let shallower = Spectrum::tma(10.0, 100_000.0, 8.0).unwrap();
    let error = ocean.set_spectrum(shallower, 10.0).unwrap_err();
    assert!(
        matches!(
            error,
            Error::NotApplicable {
                name: "spectrum.dispersion",
                ..
            }
        ),
        "{error}"
    );
    let deep = spectrum.clone().with_dispersion(Dispersion::Deep).unwrap();
    assert!(ocean.set_spectrum(deep, 10.0).is_err());
    for duration in [-1.0, f64::NAN, f64::INFINITY, 2e9] {
        let error = ocean.set_spectrum(spectrum.clone(), duration).unwrap_err();
        assert!(
            matches!(
                error,
                Error::OutOfRange {
                    name: "duration",
                    ..
                } | Error::NonFinite { name: "duration" }
            ),
            "{duration}: {error}"
        );
    }
    let bad_foam = FoamConfig {
        active_decay: -1.0,
        ..FoamConfig::default()
    };
    assert!(ocean.set_foam_config(bad_foam).is_err());
    assert_eq!(ocean.diagnostics().transition_progress(), None);
    assert_same_sea(&ocean, &reference, "after refused changes");
    assert_eq!(ocean.foam_view().total(), reference.foam_view().total());
    assert_eq!(ocean.config(), reference.config());
    ocean.step(0.5).unwrap();
    let mut reference = reference;
    reference.step(0.5).unwrap();
    assert_same_sea(&ocean, &reference, "a step later");
    assert_eq!(ocean.foam_view().total(), reference.foam_view().total());
}

/// New foam settings take effect while the ocean runs: doubling the coverage doubles the
/// target the calibration aims at, the foam on the water is kept, and the ocean then equals
/// one built with those settings in everything but its foam's history.
#[test]
fn foam_settings_are_live() {
    let config = small(Determinism::SameMachine, None);
    let spectrum = Spectrum::pierson_moskowitz(14.0).unwrap();
    let mut ocean = OceanState::new(spectrum.clone(), config.clone()).unwrap();
    ocean.pre_roll(10.0, 0.1).unwrap();
    let foam = ocean.foam_view().total().to_vec();
    let target = ocean.foam_view().calibration().target;
    let doubled = FoamConfig {
        coverage: 2.0,
        streak_length: 2.0,
        ..FoamConfig::default()
    };
    ocean.set_foam_config(doubled).unwrap();
    assert_eq!(ocean.foam_view().total(), &foam[..], "the foam is kept");
    assert!((ocean.foam_view().calibration().target / target - 2.0).abs() < 1e-5);
    assert_eq!(ocean.config().foam, doubled);
    let built = OceanState::new(
        spectrum,
        OceanConfig {
            foam: doubled,
            ..config
        },
    )
    .unwrap();
    assert_eq!(
        ocean.foam_view().calibration(),
        built.foam_view().calibration()
    );
}
