//! The `serde` feature: spectra, configs and presets round-trip through JSON unchanged, and
//! deserialising never yields an invalid `Spectrum`, `Dispersion` or `Spreading`.
//!
//! Run with `cargo test --release --features serde --test serde`.
#![cfg(feature = "serde")]
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

use ocean_fft::{
    CascadeConfig, DepthFactor, Dispersion, FoamConfig, Interpolation, OceanConfig, OceanState,
    QueryConfig, SeaState, Spectrum, Spreading,
};
use serde_json::{json, Value};

/// The wave vector `[k_x, k_z]` of length `k` in direction `theta` (radians).
fn polar(theta: f32, k: f32) -> [f32; 2] {
    let (sin, cos) = theta.sin_cos();
    [k * cos, k * sin]
}

fn round_trip<T>(value: &T) -> T
where
    T: serde::Serialize + serde::de::DeserializeOwned,
{
    let text = serde_json::to_string(value).expect("serialise");
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("deserialise {text}: {e}"))
}

#[test]
fn every_preset_round_trips_and_builds_the_same_ocean() {
    for preset in SeaState::ALL {
        let (spectrum, config) = preset.build();
        let pair = (spectrum.clone(), config.clone());
        let back: (Spectrum, OceanConfig) = round_trip(&pair);
        assert_eq!(back, pair, "{}", preset.name());
        assert_eq!(round_trip(&preset), preset);

        let original = OceanState::new(spectrum, config).unwrap();
        let loaded = OceanState::new(back.0, back.1).unwrap();
        assert_eq!(original.cascades().len(), loaded.cascades().len());
        for (c, (a, b)) in original
            .cascades()
            .iter()
            .zip(loaded.cascades())
            .enumerate()
        {
            let (a, b) = (a.h0(), b.h0());
            assert_eq!(a.len(), b.len());
            // A spread of indices, including the lowest wave vectors where the energy is.
            for index in [1, 2, 257, 513, a.len() / 3, a.len() / 2 + 7, a.len() - 1] {
                assert_eq!(
                    (a[index].re.to_bits(), a[index].im.to_bits()),
                    (b[index].re.to_bits(), b[index].im.to_bits()),
                    "{} cascade {c} h0[{index}]",
                    preset.name()
                );
            }
            assert!(a == b, "{} cascade {c}: h0 differs", preset.name());
        }
    }
}

/// A spectrum of every kind, with non-default settings everywhere.
fn assorted_spectra() -> Vec<Spectrum> {
    vec![
        Spectrum::jonswap(10.0, 100_000.0)
            .unwrap()
            .with_gamma(2.0)
            .unwrap()
            .with_wind_direction(-2.5)
            .unwrap()
            .with_spreading(Spreading::Mitsuyasu)
            .unwrap()
            .with_swell(0.4)
            .unwrap()
            .with_spread_blend(0.7)
            .unwrap()
            .with_short_wave_length(0.05)
            .unwrap(),
        Spectrum::pierson_moskowitz(12.0)
            .unwrap()
            .with_spreading(Spreading::Cos2s { s: 7.5 })
            .unwrap()
            .with_dispersion(Dispersion::capillary(30.0).unwrap())
            .unwrap(),
        Spectrum::tma(8.0, 15_000.0, 4.0)
            .unwrap()
            .with_depth_factor(DepthFactor::ThompsonVincent)
            .unwrap()
            .with_spreading(Spreading::Hasselmann)
            .unwrap()
            .with_swell(1.0)
            .unwrap()
            .with_wind_direction(std::f32::consts::PI)
            .unwrap(),
        Spectrum::phillips(15.0, 3e-4)
            .unwrap()
            .with_spreading(Spreading::Cosine {
                exponent: 4.0,
                upwind: 0.25,
            })
            .unwrap()
            .with_short_wave_length(0.1)
            .unwrap()
            .with_dispersion(Dispersion::finite_depth(50.0).unwrap())
            .unwrap()
            .with_wind_direction(1.0)
            .unwrap(),
        Spectrum::phillips(5.0, 0.0).unwrap(),
        // ω_p = 0.03 rad/s implies a wind of 287 m/s, above what the fetch law accepts.
        Spectrum::jonswap_from_parameters(0.0025, 0.03, 5.0)
            .unwrap()
            .with_spreading(Spreading::Flat)
            .unwrap()
            .with_spread_blend(0.0)
            .unwrap(),
        Spectrum::jonswap(20.0, 1e9)
            .unwrap()
            .with_spreading(Spreading::Cos2)
            .unwrap()
            .with_depth(25.0)
            .unwrap()
            .with_depth_factor(DepthFactor::Kitaigorodskii)
            .unwrap()
            .with_wind_direction(-std::f32::consts::PI)
            .unwrap(),
        Spectrum::jonswap(3.0, 5_000.0)
            .unwrap()
            .with_spreading(Spreading::DonelanBanner)
            .unwrap()
            .with_dispersion(Dispersion::capillary(0.5).unwrap())
            .unwrap()
            .with_wind_direction(0.1)
            .unwrap(),
        Spectrum::elfouhaily(10.0, 0.84).unwrap(),
        Spectrum::elfouhaily(7.0, 3.0)
            .unwrap()
            .with_wind_direction(1.2)
            .unwrap()
            .with_depth(30.0)
            .unwrap(),
        Spectrum::jonswap(12.0, 50_000.0)
            .unwrap()
            .with_spreading(Spreading::Elfouhaily)
            .unwrap(),
    ]
}

#[test]
fn spectra_of_every_kind_round_trip() {
    for spectrum in assorted_spectra() {
        let back = round_trip(&spectrum);
        assert_eq!(back, spectrum);
        // Same parameters, so the same values to the bit.
        assert_eq!(
            back.significant_wave_height().to_bits(),
            spectrum.significant_wave_height().to_bits()
        );
        // And through a `serde_json::Value`, as tools that edit the tree do.
        let value = serde_json::to_value(&spectrum).unwrap();
        assert_eq!(serde_json::from_value::<Spectrum>(value).unwrap(), spectrum);
    }
    for dispersion in [
        Dispersion::Deep,
        Dispersion::finite_depth(7.5).unwrap(),
        Dispersion::capillary(0.25).unwrap(),
    ] {
        assert_eq!(round_trip(&dispersion), dispersion);
    }
    for factor in [
        DepthFactor::None,
        DepthFactor::Kitaigorodskii,
        DepthFactor::ThompsonVincent,
    ] {
        assert_eq!(round_trip(&factor), factor);
    }
}

#[test]
fn the_serialised_form_is_readable() {
    let spectrum = Spectrum::tma(8.0, 15_000.0, 4.0).unwrap();
    let value = serde_json::to_value(&spectrum).unwrap();
    assert_eq!(value["wind_speed"], json!(8.0));
    assert_eq!(value["fetch"], json!(15_000.0));
    assert_eq!(value["spreading"], json!("DonelanBanner"));
    assert_eq!(
        value["dispersion"],
        json!({ "FiniteDepth": { "depth": 4.0 } })
    );
    assert_eq!(value["depth_factor"], json!("Kitaigorodskii"));
    assert!(value["model"]["Jonswap"]["gamma"].is_number());
}

/// A valid JSON object to tamper with, and its model's key.
fn valid(kind: &str) -> Value {
    let spectrum = match kind {
        "Phillips" => Spectrum::phillips(10.0, 1e-3).unwrap(),
        "Elfouhaily" => Spectrum::elfouhaily(10.0, 1.0).unwrap(),
        _ => Spectrum::jonswap(10.0, 100_000.0).unwrap(),
    };
    serde_json::to_value(spectrum).unwrap()
}

/// Deserialises `value` from its JSON text and returns the error message; panics if it loads.
fn rejected(value: &Value) -> String {
    let text = value.to_string();
    match serde_json::from_str::<Spectrum>(&text) {
        Ok(spectrum) => panic!("{text} loaded as {spectrum:?}"),
        Err(error) => error.to_string(),
    }
}

#[test]
fn tampered_spectra_fail_naming_the_parameter() {
    type Tamper = fn(&mut Value);
    let cases: Vec<(&str, &str, Tamper)> = vec![
        ("Jonswap", "`wind_speed`", |v| v["wind_speed"] = json!(-5.0)),
        ("Elfouhaily", "`wind_speed`", |v| {
            v["wind_speed"] = json!(0.0)
        }),
        ("Elfouhaily", "`inverse_wave_age`", |v| {
            v["model"]["Elfouhaily"]["inverse_wave_age"] = json!(0.5)
        }),
        ("Elfouhaily", "`inverse_wave_age`", |v| {
            v["model"]["Elfouhaily"]["inverse_wave_age"] = json!("nan")
        }),
        ("Elfouhaily", "`fetch`", |v| v["fetch"] = json!(1000.0)),
        ("Elfouhaily", "`depth_factor`", |v| {
            v["depth_factor"] = json!("Kitaigorodskii")
        }),
        ("Jonswap", "`wind_speed`", |v| v["wind_speed"] = json!(0)),
        ("Jonswap", "`wind_speed`", |v| {
            v["wind_speed"] = json!("NaN")
        }),
        ("Jonswap", "`wind_speed`", |v| v["wind_speed"] = json!(null)),
        ("Jonswap", "`wind_speed`", |v| {
            v["wind_speed"] = json!(300.0)
        }),
        ("Jonswap", "`wind_speed`", |v| {
            v["wind_speed"] = json!(1e300)
        }),
        ("Jonswap", "`fetch`", |v| v["fetch"] = json!(-1.0)),
        ("Jonswap", "`fetch`", |v| v["fetch"] = json!("inf")),
        ("Jonswap", "`gamma`", |v| {
            v["model"]["Jonswap"]["gamma"] = json!(0.0)
        }),
        ("Jonswap", "`gamma`", |v| {
            v["model"]["Jonswap"]["gamma"] = json!(-1)
        }),
        ("Jonswap", "`alpha`", |v| {
            v["model"]["Jonswap"]["alpha"] = json!("inf")
        }),
        ("Jonswap", "`peak_omega`", |v| {
            v["model"]["Jonswap"]["peak_omega"] = json!(null)
        }),
        ("Jonswap", "`swell`", |v| v["swell"] = json!(2.0)),
        ("Jonswap", "`swell`", |v| v["swell"] = json!("nan")),
        ("Jonswap", "`spread_blend`", |v| {
            v["spread_blend"] = json!(-0.1)
        }),
        ("Jonswap", "`short_wave_length`", |v| {
            v["short_wave_length"] = json!(-1.0)
        }),
        ("Jonswap", "`wind_direction`", |v| {
            v["wind_direction"] = json!("-infinity")
        }),
        ("Jonswap", "`depth`", |v| {
            v["dispersion"] = json!({ "FiniteDepth": { "depth": -1.0 } })
        }),
        ("Jonswap", "`depth`", |v| {
            v["dispersion"] = json!({ "Capillary": { "depth": 0.0 } })
        }),
        ("Jonswap", "`depth`", |v| {
            v["dispersion"] = json!({ "FiniteDepth": { "depth": "NaN" } })
        }),
        ("Jonswap", "`s`", |v| {
            v["spreading"] = json!({ "Cos2s": { "s": 0.0 } })
        }),
        ("Jonswap", "`s`", |v| {
            v["spreading"] = json!({ "Cos2s": { "s": null } })
        }),
        ("Jonswap", "`upwind`", |v| {
            v["spreading"] = json!({ "Cosine": { "exponent": 2.0, "upwind": 2.0 } })
        }),
        ("Jonswap", "`exponent`", |v| {
            v["spreading"] = json!({ "Cosine": { "exponent": -2.0, "upwind": 1.0 } })
        }),
        ("Jonswap", "unknown variant `Gaussian`", |v| {
            v["spreading"] = json!("Gaussian")
        }),
        ("Jonswap", "unknown variant `Lagrangian`", |v| {
            v["dispersion"] = json!("Lagrangian")
        }),
        ("Jonswap", "unknown variant `Exact`", |v| {
            v["depth_factor"] = json!("Exact")
        }),
        ("Jonswap", "missing field `gamma`", |v| {
            v["model"]["Jonswap"]
                .as_object_mut()
                .unwrap()
                .remove("gamma");
        }),
        ("Jonswap", "missing field `swell`", |v| {
            v.as_object_mut().unwrap().remove("swell");
        }),
        ("Phillips", "`amplitude`", |v| {
            v["model"]["Phillips"]["amplitude"] = json!(-1.0)
        }),
        ("Phillips", "`wind_speed`", |v| {
            v["wind_speed"] = json!(201.0)
        }),
        ("Phillips", "`depth_factor`", |v| {
            v["depth_factor"] = json!("Kitaigorodskii")
        }),
        ("Phillips", "`fetch`", |v| v["fetch"] = json!(1000.0)),
    ];
    for (kind, expected, tamper) in cases {
        let mut value = valid(kind);
        // The untampered value loads.
        serde_json::from_value::<Spectrum>(value.clone()).unwrap();
        tamper(&mut value);
        let message = rejected(&value);
        assert!(
            message.contains(expected),
            "{value}: message {message:?} does not contain {expected:?}"
        );
    }
}

#[test]
fn a_wind_direction_outside_pi_is_wrapped_as_the_setter_does() {
    let mut value = valid("Jonswap");
    value["wind_direction"] = json!(10.0);
    let loaded: Spectrum = serde_json::from_value(value).unwrap();
    let expected = Spectrum::jonswap(10.0, 100_000.0)
        .unwrap()
        .with_wind_direction(10.0)
        .unwrap();
    assert_eq!(loaded, expected);
    assert!(loaded.wind_direction().abs() <= std::f32::consts::PI);
}

#[test]
fn dispersion_and_spreading_validate_on_their_own() {
    for (text, expected) in [
        (r#"{"FiniteDepth":{"depth":-1.0}}"#, "`depth`"),
        (r#"{"Capillary":{"depth":null}}"#, "`depth`"),
        (r#"{"FiniteDepth":{"depth":"inf"}}"#, "`depth`"),
    ] {
        let error = serde_json::from_str::<Dispersion>(text).unwrap_err();
        assert!(error.to_string().contains(expected), "{text}: {error}");
    }
    for (text, expected) in [
        (r#"{"Cos2s":{"s":-3}}"#, "`s`"),
        (r#"{"Cosine":{"exponent":2.0,"upwind":-0.5}}"#, "`upwind`"),
        (r#""Gaussian""#, "unknown variant `Gaussian`"),
    ] {
        let error = serde_json::from_str::<Spreading>(text).unwrap_err();
        assert!(error.to_string().contains(expected), "{text}: {error}");
    }
    assert_eq!(
        serde_json::from_str::<Spreading>(r#"{"Cos2s":{"s":12}}"#).unwrap(),
        Spreading::Cos2s { s: 12.0 }
    );
}

#[test]
fn garbage_is_an_error_not_a_panic() {
    let base = valid("Jonswap").to_string();
    let mut inputs: Vec<String> = vec![
        String::new(),
        "null".into(),
        "[]".into(),
        "{}".into(),
        "42".into(),
        r#""Jonswap""#.into(),
        r#"{"model":"Jonswap"}"#.into(),
        r#"{"model":{"Phillips":{"amplitude":[1]}}}"#.into(),
    ];
    // Every prefix of a valid spectrum.
    inputs.extend(
        (0..base.len())
            .step_by(7)
            .map(|end| base[..end].to_string()),
    );
    for text in inputs {
        assert!(serde_json::from_str::<Spectrum>(&text).is_err(), "{text}");
        assert!(serde_json::from_str::<Dispersion>(&text).is_err(), "{text}");
        let _ = serde_json::from_str::<Spreading>(&text);
        let _ = serde_json::from_str::<OceanConfig>(&text);
        let _ = serde_json::from_str::<CascadeConfig>(&text);
        let _ = serde_json::from_str::<SeaState>(&text);
    }
}

#[test]
fn an_infinite_band_limit_is_saved_as_null() {
    let config = CascadeConfig::default();
    assert_eq!(config.k_max, f32::INFINITY);
    let value = serde_json::to_value(config).unwrap();
    assert_eq!(value["k_max"], Value::Null);
    assert_eq!(round_trip(&config), config);

    let ocean = OceanConfig::default();
    let value = serde_json::to_value(&ocean).unwrap();
    assert_eq!(value["k_max"], Value::Null);
    assert_eq!(round_trip(&ocean), ocean);

    // A missing k_max (formats without null, such as TOML, leave it out) is +∞ too.
    let mut value = serde_json::to_value(config).unwrap();
    value.as_object_mut().unwrap().remove("k_max");
    let loaded: CascadeConfig = serde_json::from_value(value).unwrap();
    assert_eq!(loaded.k_max, f32::INFINITY);

    // Finite limits are plain numbers.
    let finite = OceanConfig {
        k_min: 0.01,
        k_max: 12.5,
        repeat_period: Some(30.0),
        parallel_cascades: false,
        foam: FoamConfig {
            coverage: 0.5,
            wind_speed: Some(12.5),
            active_decay: 1.0,
            residual_decay: 30.0,
            drift: 0.02,
            streak_length: 0.75,
            streak_width: 0.25,
        },
        band_split: 0.375,
        query: QueryConfig {
            max_iterations: 7,
            tolerance: 2e-3,
            interpolation: Interpolation::Bilinear,
        },
        memory_limit: 123_456_789,
        ..OceanConfig::default()
    };
    let value = serde_json::to_value(&finite).unwrap();
    assert_eq!(value["k_max"], json!(12.5));
    assert_eq!(round_trip(&finite), finite);
    let cascade = CascadeConfig {
        size: 64,
        length: 250.0,
        k_max: 3.0,
        seed: u64::MAX,
        memory_limit: 1 << 20,
        ..CascadeConfig::default()
    };
    assert_eq!(round_trip(&cascade), cascade);
}

#[test]
fn fields_added_in_0_2_read_their_defaults_when_missing() {
    // Configs saved before `band_split`, `query` and `memory_limit` existed still load.
    let mut value = serde_json::to_value(OceanConfig::default()).unwrap();
    for key in ["band_split", "query", "memory_limit"] {
        assert!(
            value.as_object_mut().unwrap().remove(key).is_some(),
            "{key}"
        );
    }
    let loaded: OceanConfig = serde_json::from_value(value).unwrap();
    assert_eq!(loaded, OceanConfig::default());
    assert_eq!(loaded.band_split, OceanConfig::DEFAULT_BAND_SPLIT);
    assert_eq!(loaded.memory_limit, CascadeConfig::DEFAULT_MEMORY_LIMIT);

    let mut value = serde_json::to_value(CascadeConfig::default()).unwrap();
    value.as_object_mut().unwrap().remove("memory_limit");
    let loaded: CascadeConfig = serde_json::from_value(value).unwrap();
    assert_eq!(loaded, CascadeConfig::default());
}

#[test]
fn configs_saved_before_second_order_load_with_it_off() {
    let mut value = serde_json::to_value(OceanConfig::default()).unwrap();
    assert!(value
        .as_object_mut()
        .unwrap()
        .remove("second_order")
        .is_some());
    let loaded: OceanConfig = serde_json::from_value(value).unwrap();
    assert!(!loaded.second_order);
    assert_eq!(loaded, OceanConfig::default());
    let on = OceanConfig {
        second_order: true,
        ..OceanConfig::default()
    };
    assert_eq!(round_trip(&on), on);
}

#[test]
fn a_band_limit_that_json_cannot_hold_is_refused() {
    for bad in [f32::NAN, f32::NEG_INFINITY] {
        let config = CascadeConfig {
            k_max: bad,
            ..CascadeConfig::default()
        };
        let error = serde_json::to_string(&config).unwrap_err();
        assert!(error.to_string().contains("`k_max`"), "{error}");
    }
    let mut value = serde_json::to_value(CascadeConfig::default()).unwrap();
    value["k_max"] = json!("inf");
    assert!(serde_json::from_value::<CascadeConfig>(value).is_err());
}

#[test]
fn configs_are_passive_data_checked_by_the_constructors() {
    // An invalid config loads (it is plain data) and is refused where it is used.
    let text = serde_json::to_string(&OceanConfig {
        size: 7,
        ..OceanConfig::default()
    })
    .unwrap();
    let config: OceanConfig = serde_json::from_str(&text).unwrap();
    let spectrum = Spectrum::jonswap(10.0, 100_000.0).unwrap();
    assert!(OceanState::new(spectrum, config).is_err());
}

/// A loaded spectrum's parameters need not be related as the constructors relate them (the
/// wind and ω_p of a JONSWAP without fetch are independent in the file); any combination that
/// loads still evaluates without NaN.
#[test]
fn loaded_combinations_no_constructor_makes_evaluate_finite() {
    let base = valid("Jonswap");
    // A sea more than fully developed (ω_p U/g < 0.877) is refused: no constructor makes one,
    // and the Mitsuyasu spreading's s would overflow.
    for (wind, peak) in [(1e-30, 1e-3), (200.0, 1e-6), (10.0, 0.8)] {
        let mut value = base.clone();
        value["fetch"] = Value::Null;
        value["wind_speed"] = json!(wind);
        value["model"]["Jonswap"]["peak_omega"] = json!(peak);
        let message = rejected(&value);
        assert!(message.contains("`peak_omega`"), "{message}");
    }
    let mut value = base.clone();
    value["model"]["Jonswap"]["peak_omega"] = json!(1e-3);
    assert!(rejected(&value).contains("`peak_omega`"));
    for (wind, peak) in [(1e30, 100.0), (0.5, 50.0), (10.0, 0.861), (1e-3, 1e4)] {
        for spreading in [
            json!("Mitsuyasu"),
            json!("Hasselmann"),
            json!("DonelanBanner"),
            json!({ "Cos2s": { "s": 1e-6 } }),
        ] {
            let mut value = base.clone();
            value["fetch"] = Value::Null;
            value["wind_speed"] = json!(wind);
            value["model"]["Jonswap"]["peak_omega"] = json!(peak);
            value["spreading"] = spreading;
            value["swell"] = json!(1.0);
            let spectrum: Spectrum = serde_json::from_value(value.clone()).unwrap();
            for k in [1e-4f32, 0.01, 0.3, 2.0, 50.0] {
                for angle in [0.0f32, 1.0, 3.0, -2.0] {
                    let density = spectrum.density(polar(angle, k));
                    assert!(density.is_finite() && density >= 0.0, "{value} k {k}");
                    let d = spectrum.spreading(k, angle);
                    assert!(d.is_finite() && d >= 0.0, "{value} ω {k}");
                }
            }
            assert!(spectrum.significant_wave_height().is_finite(), "{value}");
        }
    }
}

/// Whatever a constructor accepts, even at the ends of its ranges, saves and loads unchanged.
#[test]
fn every_constructible_spectrum_loads() {
    let winds = [1e-6f32, 0.01, 0.5, 10.0, 60.0, 200.0];
    let lengths = [1e-6f32, 1.0, 1e3, 1e6, 1e12, 3e38];
    let mut spectra = Vec::new();
    for u in winds {
        spectra.push(Spectrum::pierson_moskowitz(u));
        spectra.push(Spectrum::phillips(u, 1e-3));
        for omega in [0.84f32, 1.0, 5.0] {
            spectra.push(Spectrum::elfouhaily(u, omega));
        }
        for f in lengths {
            spectra.push(Spectrum::jonswap(u, f));
            spectra.push(Spectrum::tma(u, f, f));
        }
    }
    for alpha in [1e-30f32, 1e-3, 1.0, 1e30] {
        for peak in [1e-30f32, 1e-6, 0.1, 10.0, 1e6, 1e30] {
            for gamma in [1e-6f32, 1.0, 1e6] {
                spectra.push(Spectrum::jonswap_from_parameters(alpha, peak, gamma));
            }
        }
    }
    let mut built = 0;
    for spectrum in spectra.into_iter().flatten() {
        for spreading in [Spreading::Mitsuyasu, Spreading::Hasselmann] {
            let spectrum = spectrum.clone().with_spreading(spreading).unwrap();
            assert_eq!(round_trip(&spectrum), spectrum);
            built += 1;
        }
    }
    assert!(built > 200, "{built}");
}

#[test]
fn a_saved_snapshot_restores_and_a_tampered_one_is_refused() {
    let (spectrum, mut config) = ocean_fft::SeaState::Storm.build();
    config.size = 16;
    let mut ocean = OceanState::new(spectrum, config).unwrap();
    for _ in 0..30 {
        ocean.step(1.0 / 30.0).unwrap();
    }
    let snapshot = ocean.snapshot();
    let text = serde_json::to_string(&snapshot).unwrap();
    let loaded: ocean_fft::OceanSnapshot = serde_json::from_str(&text).unwrap();
    assert_eq!(loaded, snapshot);
    let heights = ocean.cascades()[0].height().to_vec();
    ocean.step(1.0).unwrap();
    ocean.restore(&loaded).unwrap();
    assert_eq!(ocean.cascades()[0].height(), heights.as_slice());

    // A file edited by hand: foam outside [0, 1], a time past the limit.
    for (field, name) in [
        ("active", "snapshot.active"),
        ("residual", "snapshot.residual"),
    ] {
        let mut value: Value = serde_json::from_str(&text).unwrap();
        value[field][5] = json!(2.0);
        let bad: ocean_fft::OceanSnapshot = serde_json::from_value(value).unwrap();
        assert!(matches!(
            ocean.restore(&bad),
            Err(ocean_fft::Error::OutOfRange { name: n, .. }) if n == name
        ));
    }
    let mut value: Value = serde_json::from_str(&text).unwrap();
    value["time"] = json!(1e12);
    let bad: ocean_fft::OceanSnapshot = serde_json::from_value(value).unwrap();
    assert!(matches!(
        ocean.restore(&bad),
        Err(ocean_fft::Error::OutOfRange {
            name: "snapshot.time",
            ..
        })
    ));
    assert_eq!(ocean.cascades()[0].height(), heights.as_slice());
}

#[test]
fn a_saved_snapshot_with_a_wake_restores_and_a_tampered_one_is_refused() {
    let config = OceanConfig {
        size: 16,
        wakes: Some(ocean_fft::WakeConfig {
            size: 32,
            spacing: 1.0,
            ..ocean_fft::WakeConfig::default()
        }),
        ..OceanConfig::default()
    };
    let spectrum = ocean_fft::Spectrum::jonswap(5.0, 10_000.0).unwrap();
    let mut ocean = OceanState::new(spectrum, config).unwrap();
    let hull = ocean_fft::Hull {
        velocity: [2.0, 0.0],
        length: 6.0,
        beam: 2.0,
        draft: 0.5,
        ..ocean_fft::Hull::default()
    };
    ocean.set_hulls(&[hull]).unwrap();
    ocean.step(1.0).unwrap();
    let snapshot = ocean.snapshot();
    let text = serde_json::to_string(&snapshot).unwrap();
    let loaded: ocean_fft::OceanSnapshot = serde_json::from_str(&text).unwrap();
    assert_eq!(loaded, snapshot);
    let wake = ocean.wakes().unwrap().height().to_vec();
    assert!(wake.iter().any(|&h| h != 0.0));
    ocean.step(1.0).unwrap();
    ocean.restore(&loaded).unwrap();
    assert_eq!(ocean.wakes().unwrap().height(), wake.as_slice());

    // Hand edits: foam above 1, a hull of zero length, one value fewer, no wake at all.
    type Edit = (&'static str, fn(&mut Value));
    let edits: [Edit; 4] = [
        ("snapshot.wake.foam", |v| v["wake"]["foam"][3] = json!(1.5)),
        ("hull.length", |v| {
            v["wake"]["hulls"][0]["length"] = json!(0.0)
        }),
        ("snapshot.wake.eta", |v| {
            v["wake"]["eta"].as_array_mut().unwrap().pop();
        }),
        ("snapshot.wake", |v| v["wake"] = Value::Null),
    ];
    ocean.step(0.5).unwrap();
    let before = ocean.wakes().unwrap().height().to_vec();
    for (name, edit) in edits {
        let mut value: Value = serde_json::from_str(&text).unwrap();
        edit(&mut value);
        let bad: ocean_fft::OceanSnapshot = serde_json::from_value(value).unwrap();
        let error = ocean.restore(&bad).unwrap_err();
        let named = match error {
            ocean_fft::Error::OutOfRange { name, .. }
            | ocean_fft::Error::LengthMismatch { name, .. }
            | ocean_fft::Error::NotApplicable { name, .. } => name,
            other => panic!("{other:?}"),
        };
        assert_eq!(named, name);
        assert_eq!(ocean.wakes().unwrap().height(), before.as_slice());
    }
}
