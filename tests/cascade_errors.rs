//! Bad cascade configurations and inputs give the right `Error` variant, failed calls leave
//! the buffers untouched, and no buffer ever holds NaN or ∞ after an Ok operation — including
//! a folding storm sea.

mod common;

use std::ops::Bound;

use common::*;
use ocean_fft::inspect;
use ocean_fft::inspect::{Complex32, Fft2d, Field};
use ocean_fft::{Cascade, CascadeConfig, Error, Spectrum};

const MAX_SIZE: usize = CascadeConfig::MAX_SIZE;

/// Euclidean length of a 3-vector.
fn length3(v: [f32; 3]) -> f32 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn small() -> CascadeConfig {
    CascadeConfig {
        size: 16,
        length: 200.0,
        ..CascadeConfig::default()
    }
}

fn build(config: CascadeConfig) -> Result<Cascade, Error> {
    Cascade::new(&jonswap(0.0), config)
}

/// Every value of every buffer (five outputs, eight fields, h0) is finite.
fn assert_all_finite(cascade: &Cascade, context: &str) {
    assert!(
        cascade.height().iter().all(|v| v.is_finite()),
        "{context}: height"
    );
    assert!(
        cascade.jacobian().iter().all(|v| v.is_finite()),
        "{context}: jacobian"
    );
    assert!(
        cascade
            .displacement()
            .iter()
            .flatten()
            .all(|v| v.is_finite()),
        "{context}: displacement"
    );
    assert!(
        cascade.slope().iter().flatten().all(|v| v.is_finite()),
        "{context}: slope"
    );
    assert!(
        cascade.normal().iter().flatten().all(|v| v.is_finite()),
        "{context}: normal"
    );
    for field in FIELDS {
        assert!(
            inspect::field(cascade, field).iter().all(|v| v.is_finite()),
            "{context}: {field:?}"
        );
    }
    assert!(
        cascade
            .h0()
            .iter()
            .all(|c| c.re.is_finite() && c.im.is_finite()),
        "{context}: h0"
    );
}

/// Bit patterns of everything a caller can read.
fn snapshot(cascade: &Cascade) -> Vec<u32> {
    let mut bits: Vec<u32> = cascade.height().iter().map(|v| v.to_bits()).collect();
    bits.extend(cascade.jacobian().iter().map(|v| v.to_bits()));
    let v2 = |v: &[f32; 2]| v.map(f32::to_bits);
    let v3 = |v: &[f32; 3]| v.map(f32::to_bits);
    bits.extend(cascade.displacement().iter().flat_map(v2));
    bits.extend(cascade.slope().iter().flat_map(v2));
    bits.extend(cascade.normal().iter().flat_map(v3));
    for field in FIELDS {
        bits.extend(inspect::field(cascade, field).iter().map(|v| v.to_bits()));
    }
    bits
}

#[test]
fn invalid_sizes() {
    for size in [
        0,
        1,
        2,
        3,
        5,
        17,
        255,
        MAX_SIZE + 1,
        MAX_SIZE + 2,
        2 * MAX_SIZE,
    ] {
        let result = build(CascadeConfig { size, ..small() });
        assert_eq!(
            result.err(),
            Some(Error::InvalidSize {
                name: "size",
                size,
                min: CascadeConfig::MIN_SIZE,
                max: MAX_SIZE
            }),
            "size {size}"
        );
    }
    // The smallest size and an even size that is not a power of two are fine.
    assert!(build(CascadeConfig { size: 4, ..small() }).is_ok());
    assert!(build(CascadeConfig { size: 6, ..small() }).is_ok());
}

#[test]
fn invalid_lengths_bands_choppiness_and_periods() {
    let cases: Vec<(CascadeConfig, &str, &str)> = vec![
        (
            CascadeConfig {
                length: 0.0,
                ..small()
            },
            "range",
            "length",
        ),
        (
            CascadeConfig {
                length: -5.0,
                ..small()
            },
            "range",
            "length",
        ),
        (
            CascadeConfig {
                length: f32::NAN,
                ..small()
            },
            "nonfinite",
            "length",
        ),
        (
            CascadeConfig {
                length: f32::INFINITY,
                ..small()
            },
            "nonfinite",
            "length",
        ),
        (
            CascadeConfig {
                length: f32::NEG_INFINITY,
                ..small()
            },
            "nonfinite",
            "length",
        ),
        (
            CascadeConfig {
                k_min: -0.1,
                ..small()
            },
            "range",
            "k_min",
        ),
        (
            CascadeConfig {
                k_min: f32::NAN,
                ..small()
            },
            "nonfinite",
            "k_min",
        ),
        (
            CascadeConfig {
                k_max: f32::NAN,
                ..small()
            },
            "nonfinite",
            "k_max",
        ),
        (
            CascadeConfig {
                k_min: 0.5,
                k_max: 0.5,
                ..small()
            },
            "band",
            "",
        ),
        (
            CascadeConfig {
                k_min: 0.5,
                k_max: 0.2,
                ..small()
            },
            "band",
            "",
        ),
        (
            CascadeConfig {
                k_max: 0.0,
                ..small()
            },
            "band",
            "",
        ),
        (
            CascadeConfig {
                choppiness: -1.0,
                ..small()
            },
            "range",
            "choppiness",
        ),
        (
            CascadeConfig {
                choppiness: f32::NAN,
                ..small()
            },
            "nonfinite",
            "choppiness",
        ),
        (
            CascadeConfig {
                choppiness: f32::INFINITY,
                ..small()
            },
            "nonfinite",
            "choppiness",
        ),
        (
            CascadeConfig {
                repeat_period: Some(0.0),
                ..small()
            },
            "range",
            "repeat_period",
        ),
        (
            CascadeConfig {
                repeat_period: Some(-3.0),
                ..small()
            },
            "range",
            "repeat_period",
        ),
        (
            CascadeConfig {
                repeat_period: Some(1e-3),
                ..small()
            },
            "range",
            "repeat_period",
        ),
        (
            CascadeConfig {
                repeat_period: Some(2e6),
                ..small()
            },
            "range",
            "repeat_period",
        ),
        (
            CascadeConfig {
                repeat_period: Some(f32::NAN),
                ..small()
            },
            "nonfinite",
            "repeat_period",
        ),
        (
            CascadeConfig {
                repeat_period: Some(f32::INFINITY),
                ..small()
            },
            "nonfinite",
            "repeat_period",
        ),
    ];
    for (config, kind, name) in cases {
        let error = build(config).expect_err(&format!("{config:?} accepted"));
        let ok = match (&error, kind) {
            (Error::OutOfRange { name: n, .. }, "range") => *n == name,
            (Error::NonFinite { name: n }, "nonfinite") => *n == name,
            (Error::EmptyBand { .. }, "band") => true,
            _ => false,
        };
        assert!(ok, "{config:?}: got {error:?}, expected {kind} {name}");
        // Display works and names the problem.
        assert!(!error.to_string().is_empty());
    }
}

#[test]
fn band_without_grid_vectors_is_empty_band() {
    // L = 200 m: Δk = 0.0314 rad/m; the ring [1.2 Δk, 1.3 Δk) holds no |m| = √(a² + b²)
    // (1, √2 = 1.41 are the nearest), and a band above the grid's largest |k| (N = 16:
    // √2·7·Δk = 0.311) holds none either.
    let dk = std::f32::consts::TAU / 200.0;
    for (k_min, k_max) in [(1.2 * dk, 1.3 * dk), (0.4, 10.0), (0.0, 0.5 * dk)] {
        let result = build(CascadeConfig {
            k_min,
            k_max,
            ..small()
        });
        assert!(
            matches!(result, Err(Error::EmptyBand { .. })),
            "[{k_min}, {k_max}): {:?}",
            result.err()
        );
    }
    // A band holding exactly the |m| = 1 ring is fine.
    assert!(build(CascadeConfig {
        k_min: 0.9 * dk,
        k_max: 1.1 * dk,
        ..small()
    })
    .is_ok());
}

#[test]
fn enormous_phillips_amplitude_is_out_of_range() {
    let spectrum = Spectrum::phillips(30.0, 1e35).unwrap();
    match Cascade::new(&spectrum, small()) {
        Err(Error::AmplitudeTooLarge { bound, limit }) => {
            assert_eq!(limit, Cascade::MAX_AMPLITUDE);
            assert!(bound > limit, "bound {bound} within the limit {limit}");
        }
        other => panic!("expected AmplitudeTooLarge, got {:?}", other.err()),
    }
    // A large but representable amplitude is accepted and stays finite, and raising the
    // choppiness far enough to overflow the displacement derivatives is refused.
    let spectrum = Spectrum::phillips(30.0, 1.0).unwrap();
    let mut cascade = Cascade::new(&spectrum, small()).unwrap();
    assert_all_finite(&cascade, "Phillips A = 1");
    assert!(matches!(
        cascade.set_choppiness(1e30),
        Err(Error::AmplitudeTooLarge { bound, limit })
            if limit == Cascade::MAX_AMPLITUDE && bound > limit
    ));
    assert_eq!(cascade.config().choppiness, 1.0);
}

#[test]
fn bad_times_are_refused_and_leave_buffers_unchanged() {
    let mut cascade = build(small()).unwrap();
    cascade.update(12.5).unwrap();
    let before = snapshot(&cascade);
    for t in [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        2e9,
        -2e9,
        1e9 + 1.0,
    ] {
        let result = cascade.update(t);
        assert!(result.is_err(), "update({t}) accepted");
        assert_eq!(
            snapshot(&cascade),
            before,
            "update({t}) changed the buffers"
        );
        assert_eq!(cascade.time(), 12.5, "update({t}) changed the time");
    }
    assert!(matches!(
        cascade.update(f64::NAN),
        Err(Error::NonFinite { name: "t" })
    ));
    assert_eq!(
        cascade.update(2e9),
        Err(Error::OutOfRange {
            name: "t",
            value: 2e9,
            min: Bound::Included(-Cascade::MAX_TIME),
            max: Bound::Included(Cascade::MAX_TIME),
        })
    );
    // The extremes of the accepted range work and stay finite.
    for t in [1e9, -1e9, -3.5] {
        cascade.update(t).unwrap();
        assert_all_finite(&cascade, &format!("t = {t}"));
    }
    // wave_spectrum checks its time as update does: a non-finite or too large time is an
    // error, not NaN.
    assert_eq!(
        inspect::wave_spectrum(&cascade, f64::NAN),
        Err(Error::NonFinite { name: "t" })
    );
    assert!(matches!(
        inspect::wave_spectrum(&cascade, -2e9),
        Err(Error::OutOfRange { name: "t", .. })
    ));
}

#[test]
fn bad_choppiness_setter_is_refused() {
    let mut cascade = build(small()).unwrap();
    for lambda in [-1.0, f32::NAN, f32::INFINITY, -f32::INFINITY] {
        assert!(cascade.set_choppiness(lambda).is_err(), "{lambda}");
        assert_eq!(cascade.config().choppiness, 1.0);
    }
    cascade.set_choppiness(0.0).unwrap();
    cascade.update(1.0).unwrap();
    assert_all_finite(&cascade, "λ = 0");
    assert!(cascade.displacement().iter().all(|d| *d == [0.0; 2]));
}

#[test]
fn folding_storm_stays_finite() {
    // Pierson–Moskowitz at 25 m/s (H_s ≈ 13 m, peak wavelength ≈ 520 m) on a 400 m patch with
    // choppiness 3: the short waves a fine grid adds fold the surface (J < 0; measured: N = 64
    // barely folds, N = 128 and 256 fold at 14 and 362 samples over 20 updates), where the
    // normal points down and the slope is clamped — everything must stay finite.
    let spectrum = Spectrum::pierson_moskowitz(25.0).unwrap();
    for n in [128, 256] {
        let mut cascade = Cascade::new(
            &spectrum,
            CascadeConfig {
                size: n,
                length: 400.0,
                choppiness: 3.0,
                seed: 3,
                ..CascadeConfig::default()
            },
        )
        .unwrap();
        let mut folded = 0;
        for step in 0..20 {
            cascade.update(step as f64 * 0.7).unwrap();
            assert_all_finite(&cascade, &format!("storm N={n} step {step}"));
            folded += cascade.jacobian().iter().filter(|&&j| j < 0.0).count();
            for nrm in cascade.normal() {
                assert!((length3(*nrm) - 1.0).abs() < 1e-5, "normal {nrm:?}");
            }
        }
        let min_j = cascade
            .jacobian()
            .iter()
            .fold(f32::INFINITY, |a, &j| a.min(j));
        println!("storm N={n}: {folded} folded samples over 20 updates, last min J {min_j}");
        assert!(
            folded > 0,
            "the storm never folds: the test does not test folding"
        );
    }
}

#[test]
fn degenerate_but_valid_configs_stay_finite() {
    // Tiny and huge patches, a single-ring band, looping, λ = 0: all Ok, all finite.
    let configs = [
        CascadeConfig {
            size: 4,
            length: 0.01,
            ..small()
        },
        CascadeConfig {
            size: 8,
            length: 1e7,
            ..small()
        },
        CascadeConfig {
            size: 8,
            choppiness: 0.0,
            ..small()
        },
        // The shortest and longest accepted repeat periods (0.01 s and 1e6 s).
        CascadeConfig {
            repeat_period: Some(CascadeConfig::MIN_REPEAT_PERIOD),
            ..small()
        },
        CascadeConfig {
            repeat_period: Some(CascadeConfig::MAX_REPEAT_PERIOD),
            ..small()
        },
    ];
    for spectrum in [jonswap(1.0), phillips(-2.0)] {
        for config in configs {
            // Every one of them is valid and builds (the band [0, ∞) always holds grid wave
            // vectors, and these spectra stay far below the amplitude limit).
            let mut cascade = Cascade::new(&spectrum, config)
                .unwrap_or_else(|error| panic!("{config:?}: {error}"));
            cascade.update(123.4).unwrap();
            assert_all_finite(&cascade, &format!("{config:?}"));
            assert!(inspect::field(&cascade, Field::Height)
                .iter()
                .all(|v| v.is_finite()));
        }
    }
}

#[test]
fn out_of_range_queries_do_not_panic() {
    let cascade = build(small()).unwrap();
    assert_eq!(
        inspect::omega_at(&cascade, 16, 0),
        Err(Error::IndexOutOfRange {
            name: "i",
            index: 16,
            len: 16
        })
    );
    assert_eq!(
        inspect::omega_at(&cascade, 0, usize::MAX),
        Err(Error::IndexOutOfRange {
            name: "j",
            index: usize::MAX,
            len: 16
        })
    );
    assert_eq!(
        inspect::packed_transform(&cascade, 4),
        Err(Error::IndexOutOfRange {
            name: "transform",
            index: 4,
            len: 4
        })
    );
    assert_eq!(
        inspect::packed_transform(&cascade, usize::MAX),
        Err(Error::IndexOutOfRange {
            name: "transform",
            index: usize::MAX,
            len: 4
        })
    );
    assert_eq!(
        inspect::wave_spectrum(&cascade, f64::INFINITY),
        Err(Error::NonFinite { name: "t" })
    );
    // The last valid indices still answer.
    assert!(inspect::omega_at(&cascade, 15, 15).is_ok());
    assert_eq!(
        inspect::packed_transform(&cascade, 3).unwrap().len(),
        16 * 16
    );
}

#[test]
fn fft2d_wrong_length_is_an_error() {
    let mut fft = Fft2d::new(8, 2).unwrap();
    for len in [0, 63, 64, 127, 129, 256] {
        let mut data = vec![Complex32::new(1.0, 0.0); len];
        assert_eq!(
            fft.process(&mut data).err(),
            Some(Error::LengthMismatch {
                name: "data",
                expected: 128,
                got: len
            }),
            "length {len}"
        );
    }
    let mut data = vec![Complex32::new(0.0, 0.0); 128];
    assert_eq!(fft.process(&mut data).unwrap().len(), 128);
    assert!(matches!(
        Fft2d::new(7, 1),
        Err(Error::InvalidSize {
            name: "size",
            size: 7,
            ..
        })
    ));
    for count in [0, Fft2d::MAX_COUNT + 1] {
        assert!(
            matches!(
                Fft2d::new(8, count),
                Err(Error::CountOutOfRange { name: "count", count: c, min: 1, max })
                    if c == count && max == Fft2d::MAX_COUNT
            ),
            "count {count}"
        );
    }
}
