//! The reproducers of issue 8 (the 0.2 public surface), each as it was reported, now an `Err`
//! or a finite answer; and the memory budget that keeps a typo from aborting the process.
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

use std::f64::consts::TAU;
use std::ops::Bound;

use ocean_fft::gpu::TexelLayout;
use ocean_fft::inspect;
use ocean_fft::inspect::{Fft2d, Field};
use ocean_fft::{
    Cascade, CascadeConfig, Dispersion, Error, FoamConfig, OceanConfig, OceanState, SeaState,
    Spectrum,
};

/// 1. `bands()` on an inverted, NaN or negative band returns the validation error instead of
///    panicking in `f32::clamp`.
#[test]
fn issue_8_bands_of_a_bad_band_are_an_error() {
    let inverted = OceanConfig {
        k_min: 2.0,
        k_max: 1.0,
        ..OceanConfig::default()
    };
    assert!(matches!(
        inverted.bands(),
        Err(Error::EmptyBand { k_min, k_max }) if k_min == 2.0 && k_max == 1.0
    ));
    let nan = OceanConfig {
        k_min: f32::NAN,
        ..OceanConfig::default()
    };
    assert_eq!(nan.bands(), Err(Error::NonFinite { name: "k_min" }));
    // What a loaded config with "k_max": -1.5 holds.
    let negative = OceanConfig {
        k_max: -1.5,
        ..OceanConfig::default()
    };
    assert!(matches!(negative.bands(), Err(Error::EmptyBand { .. })));
    // And a good config still gets its bands: three, meeting where the docs say.
    let config = OceanConfig::default();
    let bands = config.bands().unwrap();
    let nyquist = |length: f32| std::f32::consts::PI * config.size as f32 / length;
    assert_eq!(bands.len(), 3);
    assert_eq!(bands[0], (0.0, 0.5 * nyquist(1000.0)));
    assert_eq!(bands[1], (0.5 * nyquist(1000.0), 0.5 * nyquist(230.0)));
    assert_eq!(bands[2], (0.5 * nyquist(230.0), nyquist(51.0)));
}

/// 2. The foam settings that made NaN foam are refused by name (the fields have changed since:
///    the same kinds of values on today's fields); the extreme accepted settings keep the foam
///    finite in [0, 1] on the storm preset, at a zero-length step too.
#[test]
fn issue_8_foam_settings_that_made_nan_are_refused() {
    let cases = [
        (
            FoamConfig {
                active_decay: 1e-45,
                ..FoamConfig::default()
            },
            "foam.active_decay",
        ),
        (
            FoamConfig {
                coverage: 1e38,
                ..FoamConfig::default()
            },
            "foam.coverage",
        ),
        (
            FoamConfig {
                drift: f32::MAX,
                ..FoamConfig::default()
            },
            "foam.drift",
        ),
    ];
    for (foam, parameter) in cases {
        let error = foam.validate().unwrap_err();
        assert!(
            matches!(error, Error::OutOfRange { name, .. } if name == parameter),
            "{foam:?}: {error:?}"
        );
        let (spectrum, mut config) = SeaState::Storm.build();
        config.size = 16;
        config.foam = foam;
        assert_eq!(OceanState::new(spectrum, config).unwrap_err(), error);
    }

    // The extremes that are accepted: everything at its largest with the shortest lifetimes,
    // then at its smallest with the longest, on a storm made choppy enough to fold.
    for foam in [
        FoamConfig {
            coverage: FoamConfig::MAX_COVERAGE,
            wind_speed: Some(Spectrum::MAX_WIND_SPEED),
            active_decay: FoamConfig::MIN_DECAY,
            residual_decay: FoamConfig::MIN_DECAY,
            drift: FoamConfig::MAX_DRIFT,
            streak_length: FoamConfig::MAX_STREAK,
            streak_width: FoamConfig::MAX_STREAK,
        },
        FoamConfig {
            coverage: 0.0,
            wind_speed: Some(0.0),
            active_decay: FoamConfig::MAX_DECAY,
            residual_decay: FoamConfig::MAX_DECAY,
            drift: 0.0,
            streak_length: 0.0,
            streak_width: 0.0,
        },
        FoamConfig {
            coverage: FoamConfig::MAX_COVERAGE,
            active_decay: FoamConfig::MAX_DECAY,
            residual_decay: FoamConfig::MAX_DECAY,
            ..FoamConfig::default()
        },
    ] {
        let (spectrum, mut config) = SeaState::Storm.build();
        config.size = 32;
        config.choppiness = 3.0;
        config.foam = foam;
        let mut ocean = OceanState::new(spectrum, config).unwrap();
        for dt in [
            0.0,
            1.0 / 60.0,
            0.0,
            ocean_fft::limits::MAX_STEP,
            1.0 / 60.0,
        ] {
            ocean.step(dt).unwrap();
            for buffer in [
                ocean.foam_view().total(),
                ocean.foam_view().active(),
                ocean.foam_view().residual(),
            ] {
                assert!(buffer.iter().all(|f| (0.0..=1.0).contains(f)), "dt {dt}");
            }
            assert!(ocean
                .foam_view()
                .breaking()
                .iter()
                .all(|s| s.is_finite() && *s >= 0.0));
            let coverage = ocean.foam_view().coverage();
            for c in [coverage.active, coverage.residual, coverage.total] {
                assert!((0.0..=1.0).contains(&c), "{coverage:?}");
            }
            let s = ocean.water().surface_at(10.0, -3.0).unwrap();
            assert!(s.foam.is_finite() && s.height.is_finite(), "{s:?}");
        }
    }
}

/// 3. A Phillips spectrum is defined on k: its H_s does not depend on the water depth, and it
///    matches an independent quadrature of `density` over the plane.
#[test]
fn issue_8_phillips_wave_height_does_not_depend_on_depth() {
    let deep = Spectrum::phillips(24.28, 1e-3).unwrap();
    let hs = deep.significant_wave_height();
    for depth in [1e-30, 1e-4, 1.0, 100.0] {
        let shallow = deep.clone().with_depth(depth).unwrap();
        assert_eq!(shallow.significant_wave_height(), hs, "depth {depth}");
    }
    // Polar midpoint quadrature of S(k) over the plane, in ln k (2000 steps from 1e-5 to
    // 1e3 rad/m: the Phillips spectrum at L_w = 60 m is negligible below, and S(k)·k falls as
    // k⁻³ beyond, so the part above 1e3 rad/m is about 1e-10 of the total) and θ (360 steps).
    // Independent of the crate's own Simpson rule over the omnidirectional spectrum.
    let shallow = deep.clone().with_depth(1e-4).unwrap();
    let (a, b) = (1e-5f64.ln(), 1e3f64.ln());
    let (steps_k, steps_theta) = (2000, 360);
    let mut variance = 0.0;
    for i in 0..steps_k {
        let k = (a + (i as f64 + 0.5) * (b - a) / steps_k as f64).exp();
        for j in 0..steps_theta {
            let theta = (j as f64 + 0.5) * TAU / steps_theta as f64;
            let kv = [(k * theta.cos()) as f32, (k * theta.sin()) as f32];
            variance += f64::from(shallow.density(kv)) * k * k;
        }
    }
    variance *= (b - a) / steps_k as f64 * TAU / steps_theta as f64;
    let quadrature = 4.0 * variance.sqrt();
    // Midpoint rules this fine (0.007 in ln k, 1° in θ) agree with the exact integral far
    // better than 1e-3; the truncated ends are negligible.
    assert!(
        (quadrature / f64::from(hs) - 1.0).abs() < 1e-3,
        "H_s {hs} m vs quadrature {quadrature} m"
    );
}

/// 4. The evolved spectrum at a huge finite time is an error like `update` gives, not NaN.
#[test]
fn issue_8_wave_spectrum_at_huge_time_is_an_error() {
    let spectrum = Spectrum::jonswap(10.0, 100_000.0).unwrap();
    let config = CascadeConfig {
        size: 8,
        length: 4.0,
        ..CascadeConfig::default()
    };
    let cascade = Cascade::new(&spectrum, config).unwrap();
    for t in [f64::MAX, -f64::MAX, 1e10] {
        let error = inspect::wave_spectrum(&cascade, t).unwrap_err();
        assert_eq!(
            error,
            Error::OutOfRange {
                name: "t",
                value: t,
                min: Bound::Included(-Cascade::MAX_TIME),
                max: Bound::Included(Cascade::MAX_TIME),
            }
        );
    }
    assert_eq!(
        inspect::wave_spectrum(&cascade, f64::NAN).unwrap_err(),
        Error::NonFinite { name: "t" }
    );
    let at_limit = inspect::wave_spectrum(&cascade, Cascade::MAX_TIME).unwrap();
    assert!(at_limit
        .iter()
        .all(|c| c.re.is_finite() && c.im.is_finite()));
}

/// 5. The group velocity at k = +∞ is the limit (0 for gravity waves; saturated +∞ for
///    capillary ones), never NaN.
#[test]
fn issue_8_group_velocity_at_infinity_is_its_limit() {
    assert_eq!(Dispersion::Deep.d_omega_dk(f32::INFINITY), 0.0);
    assert_eq!(
        Dispersion::FiniteDepth { depth: 10.0 }.d_omega_dk(f32::INFINITY),
        0.0
    );
    assert_eq!(
        Dispersion::Capillary { depth: 10.0 }.d_omega_dk(f32::INFINITY),
        f32::MAX
    );
    // Finite but huge k: gravity waves slow down toward 0, capillary ones speed up.
    let far = Dispersion::FiniteDepth { depth: 10.0 }.d_omega_dk(1e30);
    assert!(far > 0.0 && far < 1e-10, "{far}");
    let capillary = Dispersion::Capillary { depth: 10.0 }.d_omega_dk(1e30);
    assert!(capillary > 1e10 && capillary.is_finite(), "{capillary}");
}

/// 6. Field multipliers at huge wave vectors are finite (computed in f64, saturated).
#[test]
fn issue_8_multipliers_at_huge_wave_vectors_are_finite() {
    for k in [[f32::MAX, f32::MAX], [1e20, 1e20], [-f32::MAX, 3.0]] {
        for field in Field::ALL {
            let m = field.multiplier(k);
            assert!(
                m.re.is_finite() && m.im.is_finite(),
                "{field:?} at {k:?}: {m}"
            );
        }
    }
    // −k_x²/k at (1e20, 1e20) is −1e40/√2e20 = −7.07e19: representable, so not saturated.
    let m = Field::DisplacementXX.multiplier([1e20, 1e20]);
    assert!(
        (f64::from(m.re) / -(1e20 / 2f64.sqrt()) - 1.0).abs() < 1e-6,
        "{m}"
    );
    // −k_x²/k at (MAX, MAX) is −MAX/√2: representable too.
    let m = Field::DisplacementXX.multiplier([f32::MAX, f32::MAX]);
    let expected = -f64::from(f32::MAX) / 2f64.sqrt();
    assert!((f64::from(m.re) / expected - 1.0).abs() < 1e-6, "{m}");
}

/// The memory budget: eight cascades of the largest size are refused before any allocation,
/// as is a gigantic `Fft2d`; the footprint reported is what the docs say per point.
#[test]
fn issue_8_memory_budget_refuses_what_would_abort() {
    let huge = OceanConfig {
        lengths: vec![8000.0, 2000.0, 500.0, 125.0, 31.0, 7.7, 1.9, 0.47],
        size: CascadeConfig::MAX_SIZE,
        ..OceanConfig::default()
    };
    let bytes = huge.memory_bytes();
    // 8 × (≈ 94 + 4 + 24) · 4096² bytes ≈ 15.3 GiB (cascade at 4096², whose pass-2 blocks
    // are bounded (docs/performance.md), foam, query spline tiles of 35² points of five f32
    // coefficients per 32² points).
    assert!(bytes > 15 << 30 && bytes < 16 << 30, "{bytes}");
    assert_eq!(
        huge.validate(),
        Err(Error::MemoryLimit {
            bytes,
            limit: CascadeConfig::DEFAULT_MEMORY_LIMIT
        })
    );
    let spectrum = Spectrum::jonswap(10.0, 100_000.0).unwrap();
    assert!(matches!(
        OceanState::new(spectrum.clone(), huge),
        Err(Error::MemoryLimit { .. })
    ));
    let cascade = CascadeConfig {
        size: 1024,
        memory_limit: 1 << 20,
        ..CascadeConfig::default()
    };
    assert!(matches!(
        Cascade::new(&spectrum, cascade),
        Err(Error::MemoryLimit { limit, .. }) if limit == 1 << 20
    ));
    assert!(matches!(
        Fft2d::new(CascadeConfig::MAX_SIZE, Fft2d::MAX_COUNT),
        Err(Error::MemoryLimit { .. })
    ));
    // Per point: h0 8 + the pass-1 buffer 32 + outputs 36 + half a 28-byte evolution entry 14
    // = 90 bytes, plus the pass-2 block buffers (at most 32 blocks of 16 rows of four packed
    // transforms: the whole grid, 32 bytes a point, at 256²; 32·16/1024 of it, 16 bytes, at
    // 1024²) and a few bytes of row padding (one cache line in 4·N values), FFT scratch and
    // tables.
    for (n, expected) in [(256usize, 90.0 + 32.0), (1024, 90.0 + 16.0)] {
        let per_point = CascadeConfig {
            size: n,
            ..CascadeConfig::default()
        }
        .memory_bytes() as f64
            / (n * n) as f64;
        assert!(
            (expected..expected + 6.0).contains(&per_point),
            "N {n}: {per_point} bytes per point, expected {expected} + a few"
        );
    }
}

/// Limits are written once: the bounds an error reports are the associated consts.
#[test]
fn issue_8_errors_report_the_limits_the_checks_use() {
    let error = Spectrum::pierson_moskowitz(250.0).unwrap_err();
    assert_eq!(
        error,
        Error::OutOfRange {
            name: "wind_speed",
            value: 250.0,
            min: Bound::Excluded(0.0),
            max: Bound::Included(f64::from(Spectrum::MAX_WIND_SPEED)),
        }
    );
    let config = CascadeConfig {
        length: 0.001,
        ..CascadeConfig::default()
    };
    // f32 limits are reported through their shortest decimal form (0.01, not 0.0099999998).
    assert_eq!(CascadeConfig::MIN_LENGTH, 0.01);
    assert_eq!(CascadeConfig::MAX_LENGTH, 1e7);
    assert_eq!(
        config.validate(),
        Err(Error::OutOfRange {
            name: "length",
            value: 0.001,
            min: Bound::Included(0.01),
            max: Bound::Included(1e7),
        })
    );
    assert_eq!(
        config.validate().unwrap_err().to_string(),
        "parameter `length` = 0.001 is out of range: expected 0.01 ≤ length ≤ 1e7"
    );
    let mut ocean = OceanState::new(
        Spectrum::jonswap(10.0, 100_000.0).unwrap(),
        OceanConfig {
            size: 8,
            ..OceanConfig::default()
        },
    )
    .unwrap();
    assert_eq!(
        ocean.step(ocean_fft::limits::MAX_STEP * 2.0),
        Err(Error::OutOfRange {
            name: "dt",
            value: ocean_fft::limits::MAX_STEP * 2.0,
            min: Bound::Included(0.0),
            max: Bound::Included(ocean_fft::limits::MAX_STEP),
        })
    );
    ocean.set_time(Cascade::MAX_TIME).unwrap();
    assert!(matches!(
        ocean.step(1.0),
        Err(Error::OutOfRange {
            name: "time + dt",
            ..
        })
    ));
    assert_eq!(ocean.time(), Cascade::MAX_TIME);
    assert_eq!(
        ocean.textures().pack(3, TexelLayout::Normal, &mut []),
        Err(Error::IndexOutOfRange {
            name: "cascade",
            index: 3,
            len: 3
        })
    );
}
