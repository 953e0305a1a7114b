//! `Spectrum::params` and `Spectrum::from_params` (issue 37): a spectrum's parameters as plain
//! data round-trip to the same spectrum, bit for bit, and bad fields are refused by name.

mod props;

use ocean_fft::{DepthFactor, Dispersion, Spectrum, SpectrumKind, SpectrumParams, Spreading};
use proptest::prelude::*;

fn config() -> proptest::test_runner::Config {
    props::config(256, 0x5bec_7a37)
}

/// A spectrum from one of the constructors, with random (valid) setters on top.
fn spectra() -> impl Strategy<Value = Spectrum> {
    let model = prop_oneof![
        (0.5f32..60.0, 10.0f32..2e6).prop_map(|(u, f)| Spectrum::jonswap(u, f)),
        (0.5f32..60.0).prop_map(Spectrum::pierson_moskowitz),
        (0.5f32..60.0, 1e3f32..1e6, 1.0f32..200.0).prop_map(|(u, f, h)| Spectrum::tma(u, f, h)),
        (1e-4f32..0.05, 0.1f32..3.0, 1.0f32..7.0)
            .prop_map(|(a, w, g)| Spectrum::jonswap_from_parameters(a, w, g)),
        (0.5f32..60.0, 0.0f32..1e-3).prop_map(|(u, a)| Spectrum::phillips(u, a)),
        (0.5f32..60.0, 0.84f32..5.0).prop_map(|(u, w)| Spectrum::elfouhaily(u, w)),
    ];
    let spreading = prop_oneof![
        Just(Spreading::DonelanBanner),
        Just(Spreading::Mitsuyasu),
        Just(Spreading::Hasselmann),
        Just(Spreading::Flat),
        (0.5f32..50.0).prop_map(|s| Spreading::Cos2s { s }),
    ];
    (
        model,
        -10.0f32..10.0,
        spreading,
        0.0f32..=1.0,
        0.0f32..=1.0,
        0.0f32..0.5,
        prop::option::of(1.0f32..500.0),
    )
        .prop_map(|(model, direction, spreading, swell, blend, fade, depth)| {
            let mut s = model
                .unwrap()
                .with_wind_direction(direction)
                .unwrap()
                .with_spreading(spreading)
                .unwrap()
                .with_swell(swell)
                .unwrap()
                .with_spread_blend(blend)
                .unwrap()
                .with_short_wave_length(fade)
                .unwrap();
            if let Some(depth) = depth {
                s = s.with_depth(depth).unwrap();
            }
            s
        })
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn params_round_trip_to_the_same_bits(spectrum in spectra()) {
        let params = spectrum.params();
        let rebuilt = Spectrum::from_params(&params).unwrap();
        prop_assert_eq!(&rebuilt, &spectrum);
        prop_assert_eq!(rebuilt.params(), params);
        // And it behaves the same: S(k), D and H_s to the bit.
        for k in [[0.01f32, 0.0], [0.05, 0.02], [0.3, -0.1], [2.0, 1.5]] {
            prop_assert_eq!(rebuilt.density(k).to_bits(), spectrum.density(k).to_bits());
        }
        prop_assert_eq!(
            rebuilt.significant_wave_height().to_bits(),
            spectrum.significant_wave_height().to_bits()
        );
    }
}

#[test]
fn each_constructor_reads_as_its_kind() {
    let kind = |s: Spectrum| s.params().kind;
    assert_eq!(
        kind(
            Spectrum::jonswap(10.0, 1e5)
                .unwrap()
                .with_gamma(2.0)
                .unwrap()
        ),
        SpectrumKind::Jonswap {
            fetch: 1e5,
            gamma: 2.0
        }
    );
    // The fetch as stored: capped at full development.
    let capped = Spectrum::jonswap(10.0, 1e9).unwrap();
    assert_eq!(
        kind(capped.clone()),
        SpectrumKind::Jonswap {
            fetch: capped.fetch().unwrap(),
            gamma: 3.3
        }
    );
    let tma = Spectrum::tma(10.0, 1e5, 12.0).unwrap().params();
    assert_eq!(
        tma.kind,
        SpectrumKind::Jonswap {
            fetch: 1e5,
            gamma: 3.3
        }
    );
    assert_eq!(tma.dispersion, Dispersion::FiniteDepth { depth: 12.0 });
    assert_eq!(tma.depth_factor, DepthFactor::Kitaigorodskii);
    assert_eq!(
        kind(Spectrum::pierson_moskowitz(12.0).unwrap()),
        SpectrumKind::PiersonMoskowitz
    );
    assert!(matches!(
        kind(Spectrum::jonswap_from_parameters(0.01, 0.8, 2.0).unwrap()),
        SpectrumKind::JonswapShape { gamma: 2.0, .. }
    ));
    assert_eq!(
        kind(Spectrum::phillips(8.0, 3e-7).unwrap()),
        SpectrumKind::Phillips { amplitude: 3e-7 }
    );
    assert_eq!(
        kind(Spectrum::elfouhaily(8.0, 1.5).unwrap()),
        SpectrumKind::Elfouhaily {
            inverse_wave_age: 1.5
        }
    );
}

#[test]
fn bad_fields_are_refused_by_name() {
    let good = Spectrum::jonswap(10.0, 1e5).unwrap().params();
    let cases: Vec<(&str, SpectrumParams)> = vec![
        (
            "wind_speed",
            SpectrumParams {
                wind_speed: -1.0,
                ..good
            },
        ),
        (
            "wind_speed",
            SpectrumParams {
                wind_speed: f32::NAN,
                ..good
            },
        ),
        (
            "fetch",
            SpectrumParams {
                kind: SpectrumKind::Jonswap {
                    fetch: 0.0,
                    gamma: 3.3,
                },
                ..good
            },
        ),
        (
            "gamma",
            SpectrumParams {
                kind: SpectrumKind::Jonswap {
                    fetch: 1e5,
                    gamma: -1.0,
                },
                ..good
            },
        ),
        (
            "alpha",
            SpectrumParams {
                kind: SpectrumKind::JonswapShape {
                    alpha: 0.0,
                    peak_omega: 1.0,
                    gamma: 1.0,
                },
                ..good
            },
        ),
        (
            "peak_omega",
            // Far below a fully developed sea of this wind.
            SpectrumParams {
                kind: SpectrumKind::JonswapShape {
                    alpha: 0.01,
                    peak_omega: 0.01,
                    gamma: 1.0,
                },
                ..good
            },
        ),
        (
            "amplitude",
            SpectrumParams {
                kind: SpectrumKind::Phillips { amplitude: -1.0 },
                ..good
            },
        ),
        (
            "inverse_wave_age",
            SpectrumParams {
                kind: SpectrumKind::Elfouhaily {
                    inverse_wave_age: 9.0,
                },
                ..good
            },
        ),
        (
            "wind_direction",
            SpectrumParams {
                wind_direction: f32::INFINITY,
                ..good
            },
        ),
        ("swell", SpectrumParams { swell: 1.5, ..good }),
        (
            "spread_blend",
            SpectrumParams {
                spread_blend: -0.5,
                ..good
            },
        ),
        (
            "short_wave_length",
            SpectrumParams {
                short_wave_length: -2.0,
                ..good
            },
        ),
        (
            "depth",
            SpectrumParams {
                dispersion: Dispersion::FiniteDepth { depth: 0.0 },
                ..good
            },
        ),
        (
            "depth_factor",
            SpectrumParams {
                kind: SpectrumKind::Phillips { amplitude: 1e-7 },
                depth_factor: DepthFactor::ThompsonVincent,
                ..good
            },
        ),
        (
            "s",
            SpectrumParams {
                spreading: Spreading::Cos2s { s: 0.0 },
                ..good
            },
        ),
    ];
    for (name, params) in cases {
        let error = Spectrum::from_params(&params).unwrap_err();
        assert!(
            error.to_string().contains(&format!("`{name}`")),
            "{name}: {error}"
        );
    }
    // A wind direction beyond ±π is wrapped, as with_wind_direction does.
    let turned = Spectrum::from_params(&SpectrumParams {
        wind_direction: 7.0,
        ..good
    })
    .unwrap();
    assert_eq!(
        turned,
        Spectrum::jonswap(10.0, 1e5)
            .unwrap()
            .with_wind_direction(7.0)
            .unwrap()
    );
}
