//! The foam on the extremes of every spectrum constructor (issue 21, point 5): every ocean
//! `OceanState::new` accepts keeps its breaking intensity, its foam fields and its coverage
//! finite (the foam in [0, 1], the intensity ≥ 0) after `new`, after steps, after `set_time`
//! and after `pre_roll`, and its residual foam does not appear faster than the aging allows.
//!
//! Each constructor's parameters are drawn from their limits and the scales either side:
//! winds from the smallest positive f32 to `Spectrum::MAX_WIND_SPEED`, fetches and depths from
//! the smallest positive f32 to `f32::MAX`, γ and ω_p over the whole positive range, and α
//! (and the Phillips amplitude) up to the largest value `OceanState::new` accepts for that
//! ocean, found by bisection on the bits. Grids of 8² to 32² over several sets of tiles (the
//! shortest accepted, the longest, and between), with capillary and finite-depth dispersion,
//! both determinism modes, and ordinary and extreme foam settings.
//!
//! Run time: about two seconds in release mode (128 cases, fixed seed; `PROPTEST_CASES`
//! overrides the count for a longer local search).
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

mod props;

use ocean_fft::{
    Cascade, CascadeConfig, Determinism, Dispersion, Error, FoamConfig, OceanConfig, OceanState,
    Spectrum,
};
use proptest::prelude::*;
use proptest::test_runner::Config;

mod foam_model;

/// Cases per property, unless `PROPTEST_CASES` says otherwise.
const CASES: u32 = 128;

/// The fixed seed of every property.
const SEED: u64 = 0x0cea_21f5;

fn config() -> Config {
    props::config(CASES, SEED)
}

/// The next f32 up (`up`) or down from a positive finite `v`.
fn next(v: f32, up: bool) -> f32 {
    f32::from_bits(if up { v.to_bits() + 1 } else { v.to_bits() - 1 })
}

/// Winds: the smallest positive f32 up to the largest accepted.
fn wind() -> impl Strategy<Value = f32> {
    prop::sample::select(vec![
        1e-45,
        1e-30,
        1e-3,
        0.5,
        12.0,
        next(Spectrum::MAX_WIND_SPEED, false),
        Spectrum::MAX_WIND_SPEED,
    ])
}

/// Fetches and depths: any positive f32.
fn length() -> impl Strategy<Value = f32> {
    prop::sample::select(vec![1e-45, 1e-20, 1e-3, 1.0, 2e3, 1e6, 1e20, f32::MAX])
}

/// Any positive f32 (γ, ω_p).
fn positive() -> impl Strategy<Value = f32> {
    prop::sample::select(vec![
        1e-45,
        1e-30,
        2.6e-38,
        1e-6,
        0.3,
        1.0,
        3.2373254,
        7.4815707,
        1e3,
        1e20,
        1e30,
        f32::MAX,
    ])
}

/// How α or a Phillips amplitude is chosen: a fixed value, or relative to the largest the
/// ocean accepts (found by bisection).
#[derive(Debug, Clone, Copy)]
enum Strength {
    Fixed(f32),
    /// The largest accepted value times this factor (≤ 1).
    Limit(f32),
}

fn strength() -> impl Strategy<Value = Strength> {
    prop_oneof![
        1 => prop::sample::select(vec![1e-45f32, 1e-20, 8.1e-3, 1.0, f32::MAX]).prop_map(Strength::Fixed),
        3 => prop::sample::select(vec![1.0f32, 0.5, 1e-3]).prop_map(Strength::Limit),
    ]
}

#[derive(Debug, Clone)]
enum Build {
    Jonswap(f32, f32),
    PiersonMoskowitz(f32),
    Tma(f32, f32, f32),
    Phillips(f32, Strength),
    FromParameters(Strength, f32, f32),
    Elfouhaily(f32, f32),
}

fn build_strategy() -> impl Strategy<Value = Build> {
    prop_oneof![
        1 => (wind(), length()).prop_map(|(u, f)| Build::Jonswap(u, f)),
        1 => wind().prop_map(Build::PiersonMoskowitz),
        1 => (wind(), length(), length()).prop_map(|(u, f, h)| Build::Tma(u, f, h)),
        1 => (wind(), strength()).prop_map(|(u, a)| Build::Phillips(u, a)),
        2 => (strength(), positive(), positive())
            .prop_map(|(a, w, g)| Build::FromParameters(a, w, g)),
        1 => (
            wind(),
            prop::sample::select(vec![
                Spectrum::MIN_INVERSE_WAVE_AGE,
                2.0,
                Spectrum::MAX_INVERSE_WAVE_AGE
            ])
        )
            .prop_map(|(u, omega)| Build::Elfouhaily(u, omega)),
    ]
}

/// What is done to the spectrum after its constructor.
#[derive(Debug, Clone, Copy)]
struct Setting {
    wind_direction: f32,
    /// None: the constructor's dispersion; Some(None): capillary in deep water; Some(h):
    /// finite depth h (capillary if `capillary`).
    depth: Option<Option<f32>>,
    capillary: bool,
}

fn setting() -> impl Strategy<Value = Setting> {
    (
        prop::sample::select(vec![0.0f32, 0.7, -2.1]),
        prop_oneof![
            2 => Just(None),
            1 => Just(Some(None)),
            1 => prop::sample::select(vec![1e-45f32, 1e-3, 5.0, f32::MAX]).prop_map(|h| Some(Some(h))),
        ],
        any::<bool>(),
    )
        .prop_map(|(wind_direction, depth, capillary)| Setting {
            wind_direction,
            depth,
            capillary,
        })
}

/// The spectrum of `build` with `strength` resolved to `value` and `setting` applied, or the
/// constructor's or a setter's error.
fn spectrum(build: &Build, value: f32, setting: &Setting) -> Result<Spectrum, Error> {
    let spectrum = match *build {
        Build::Jonswap(u, f) => Spectrum::jonswap(u, f),
        Build::PiersonMoskowitz(u) => Spectrum::pierson_moskowitz(u),
        Build::Tma(u, f, h) => Spectrum::tma(u, f, h),
        Build::Phillips(u, _) => Spectrum::phillips(u, value),
        Build::FromParameters(_, w, g) => Spectrum::jonswap_from_parameters(value, w, g),
        Build::Elfouhaily(u, omega) => Spectrum::elfouhaily(u, omega),
    }?
    .with_wind_direction(setting.wind_direction)?;
    match setting.depth {
        None => Ok(spectrum),
        Some(depth) => {
            let dispersion = match (depth, setting.capillary) {
                (None, _) => Dispersion::Capillary { depth: f32::MAX },
                (Some(depth), true) => Dispersion::Capillary { depth },
                (Some(depth), false) => Dispersion::FiniteDepth { depth },
            };
            spectrum.with_dispersion(dispersion)
        }
    }
}

/// Tiles: the reported ones, the default ones, the shortest and longest accepted, and a
/// capillary-scale set.
fn tiles() -> impl Strategy<Value = Vec<f32>> {
    prop::sample::select(vec![
        vec![117.6, 27.3, 6.2],
        vec![1000.0, 230.0, 51.0],
        vec![CascadeConfig::MIN_LENGTH],
        vec![CascadeConfig::MAX_LENGTH, 2e6],
        vec![0.5, 0.1, CascadeConfig::MIN_LENGTH],
        vec![40.0],
    ])
}

fn foam_settings() -> impl Strategy<Value = FoamConfig> {
    prop::sample::select(vec![
        FoamConfig::default(),
        FoamConfig {
            coverage: FoamConfig::MAX_COVERAGE,
            active_decay: FoamConfig::MIN_DECAY,
            residual_decay: FoamConfig::MIN_DECAY,
            drift: FoamConfig::MAX_DRIFT,
            streak_length: FoamConfig::MAX_STREAK,
            streak_width: 0.0,
            ..FoamConfig::default()
        },
        FoamConfig {
            active_decay: FoamConfig::MAX_DECAY,
            residual_decay: FoamConfig::MAX_DECAY,
            streak_length: FoamConfig::MAX_STREAK,
            streak_width: FoamConfig::MAX_STREAK,
            ..FoamConfig::default()
        },
    ])
}

fn ocean_config() -> impl Strategy<Value = OceanConfig> {
    (
        tiles(),
        prop::sample::select(vec![8usize, 16, 32]),
        prop::sample::select(vec![0.0f32, 1.0, 3.0]),
        foam_settings(),
        any::<bool>(),
    )
        .prop_map(|(lengths, size, choppiness, foam, cross)| OceanConfig {
            lengths,
            size,
            choppiness,
            foam,
            determinism: if cross {
                Determinism::CrossPlatform
            } else {
                Determinism::SameMachine
            },
            ..OceanConfig::default()
        })
}

/// The largest value v in [`low`, f32::MAX] for which `accepted(v)` holds, for an `accepted`
/// that holds below some value and fails above it (α and the Phillips amplitude scale every
/// amplitude by √v): by bisection on the bits, which order positive floats. None if even
/// `low` is refused.
fn largest_accepted(low: f32, accepted: impl Fn(f32) -> bool) -> Option<f32> {
    if !accepted(low) {
        return None;
    }
    if accepted(f32::MAX) {
        return Some(f32::MAX);
    }
    let (mut good, mut bad) = (low.to_bits(), f32::MAX.to_bits());
    while bad - good > 1 {
        let middle = good + (bad - good) / 2;
        if accepted(f32::from_bits(middle)) {
            good = middle;
        } else {
            bad = middle;
        }
    }
    Some(f32::from_bits(good))
}

/// What is wrong with the foam of `ocean`, if anything.
fn foam_fault(ocean: &OceanState) -> Option<String> {
    let unit = |v: &f32| (0.0..=1.0).contains(v);
    for (name, buffer) in [
        ("foam", ocean.foam_view().total()),
        ("active_foam", ocean.foam_view().active()),
        ("residual_foam", ocean.foam_view().residual()),
    ] {
        if let Some(v) = buffer.iter().find(|v| !unit(v)) {
            return Some(format!("{name} holds {v}"));
        }
    }
    if let Some(s) = ocean
        .foam_view()
        .breaking()
        .iter()
        .find(|s| !(s.is_finite() && **s >= 0.0))
    {
        return Some(format!("breaking holds {s}"));
    }
    let c = ocean.foam_view().coverage();
    if ![c.active, c.residual, c.total].iter().all(unit) {
        return Some(format!("coverage {c:?}"));
    }
    let k = ocean.foam_view().calibration();
    let finite = [
        k.wind_speed,
        k.target,
        k.compression_std,
        k.breaking_fraction,
        k.episode_rate,
        k.predicted,
    ];
    // The threshold is −∞ when nothing breaks.
    if k.threshold.is_nan() || k.threshold == f32::INFINITY || !finite.iter().all(|v| v.is_finite())
    {
        return Some(format!("calibration {k:?}"));
    }
    None
}

/// Where `ocean`'s breaking intensity is not the documented model's (recomputed in f64 by
/// `foam_model`), if anywhere: within 0.5 % (the crate's tail approximation is good to
/// 0.3 %), the change that f32 rounding of the quadratic's terms makes to the model there
/// (`Expected::conditioning`), and an f32 ulp of the fraction's Φ(x) near 1 over τ_A.
fn model_fault(ocean: &OceanState) -> Option<String> {
    let tau = f64::from(ocean.config().foam.active_decay);
    let expected = foam_model::breaking_intensities(ocean);
    for (k, (&got, e)) in ocean
        .foam_view()
        .breaking()
        .iter()
        .zip(&expected)
        .enumerate()
    {
        let got = f64::from(got);
        let tolerance = 5e-3 * e.value + e.conditioning + 3e-7 / tau + 1e-9;
        // Written so that a NaN fails.
        let close = (got - e.value).abs() <= tolerance;
        if !close {
            return Some(format!(
                "point {k}: intensity {got}, model {e:?} ({} points)",
                expected.len()
            ));
        }
    }
    None
}

proptest! {
    #![proptest_config(config())]

    /// Every ocean `new` accepts on an extreme spectrum keeps its foam finite through steps
    /// (the shortest a game takes, a long one and the longest accepted), a jump in time and a
    /// pre-roll. From a clean sea, the first step of dt ≤ 0.5 s makes at most dt/τ_A of
    /// residual foam on average (it grows at (a/τ_A)(1 − r) ≤ 1/τ_A, and the transport keeps
    /// its mean): a NaN the transport's clamp to [0, 1] turned into 1 would show there.
    #[test]
    fn foam_stays_finite_on_extreme_spectra(
        build in build_strategy(),
        setting in setting(),
        config in ocean_config(),
        first_dt in prop::sample::select(vec![1.0 / 60.0, 0.5]),
        long_dt in prop::sample::select(vec![2.0, ocean_fft::limits::MAX_STEP]),
        jump in prop::sample::select(vec![-17.25, 123.4, Cascade::MAX_TIME - 10.0]),
    ) {
        let accepted = |value: f32| {
            spectrum(&build, value, &setting)
                .and_then(|s| OceanState::new(s, config.clone()))
                .is_ok()
        };
        let value = match build {
            Build::Phillips(_, strength) | Build::FromParameters(strength, _, _) => match strength {
                Strength::Fixed(v) => v,
                Strength::Limit(factor) => match largest_accepted(1e-30, accepted) {
                    Some(limit) => limit * factor,
                    None => return Ok(()),
                },
            },
            _ => 1.0,
        };
        let Ok(spectrum) = spectrum(&build, value, &setting) else {
            return Ok(());
        };
        let Ok(mut ocean) = OceanState::new(spectrum, config.clone()) else {
            return Ok(());
        };
        let fault = |ocean: &OceanState, when: &str| {
            foam_fault(ocean).map(|f| format!("{f} {when} (value {value})"))
        };
        prop_assert_eq!(fault(&ocean, "after new"), None);
        ocean.step(first_dt).unwrap();
        prop_assert_eq!(fault(&ocean, "after the first step"), None);
        let bound = first_dt / f64::from(config.foam.active_decay);
        let residual = f64::from(ocean.foam_view().coverage().residual);
        // 1e-6: the transforms' rounding (the FLUSH level).
        prop_assert!(
            residual <= bound + 1e-6,
            "residual coverage {} after {} s from a clean sea, at most {}", residual, first_dt, bound
        );
        if let Some(fault) = model_fault(&ocean) {
            prop_assert!(false, "{} (value {})", fault, value);
        }
        ocean.step(long_dt).unwrap();
        prop_assert_eq!(fault(&ocean, "after a long step"), None);
        ocean.step(0.0).unwrap();
        prop_assert_eq!(fault(&ocean, "after a step of 0 s"), None);
        ocean.set_time(jump).unwrap();
        prop_assert_eq!(fault(&ocean, "after set_time"), None);
        ocean.step(first_dt).unwrap();
        prop_assert_eq!(fault(&ocean, "after a step past the jump"), None);
        ocean.pre_roll(1.0, 0.25).unwrap();
        prop_assert_eq!(fault(&ocean, "after pre_roll"), None);
    }
}

/// The bisection finds the limit: the reported sea's α limit at N = 16 is accepted and the
/// next f32 up refused by name (the amplitude bound), and the foam at the limit is finite and
/// whitecaps show.
#[test]
fn jonswap_alpha_at_its_limit_keeps_the_foam_finite() {
    // Choppiness 0: the amplitude bound takes max(1, λ), so the limit is λ = 1's, and the
    // choppiness limit (which refuses λ = 1 long before) stays out of the bisection.
    let config = OceanConfig {
        lengths: vec![117.6, 27.3, 6.2],
        size: 16,
        choppiness: 0.0,
        ..OceanConfig::default()
    };
    let ocean = |alpha: f32| {
        Spectrum::jonswap_from_parameters(alpha, 3.2373254, 7.4815707)
            .and_then(|s| OceanState::new(s, config.clone()))
    };
    let limit = largest_accepted(1e-30, |alpha| ocean(alpha).is_ok()).unwrap();
    assert!(limit > 1e19 && limit < f32::MAX, "{limit}");
    assert!(matches!(
        ocean(next(limit, true)),
        Err(Error::AmplitudeTooLarge { .. })
    ));
    let mut o = ocean(limit).unwrap();
    assert_eq!(foam_fault(&o), None);
    o.pre_roll(5.0, 0.1).unwrap();
    assert_eq!(foam_fault(&o), None);
    assert!(
        o.foam_view().coverage().active > 0.1,
        "{:?}",
        o.foam_view().coverage()
    );
}
