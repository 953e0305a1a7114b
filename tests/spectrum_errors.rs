//! Invalid parameters give `Error`, never a panic or a NaN.

use ocean_fft::{DepthFactor, Dispersion, Error, Spectrum, Spreading};

fn is_bad_number(result: Result<Spectrum, Error>, expected: &str) -> bool {
    match result {
        Err(Error::NonFinite { name }) | Err(Error::OutOfRange { name, .. }) => name == expected,
        _ => false,
    }
}

#[test]
fn constructors_reject_bad_numbers() {
    for bad in [0.0, -1.0, f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        assert!(
            is_bad_number(Spectrum::jonswap(bad, 1e5), "wind_speed"),
            "{bad}"
        );
        assert!(
            is_bad_number(Spectrum::jonswap(10.0, bad), "fetch"),
            "{bad}"
        );
        assert!(is_bad_number(
            Spectrum::pierson_moskowitz(bad),
            "wind_speed"
        ));
        assert!(is_bad_number(Spectrum::phillips(bad, 1.0), "wind_speed"));
        assert!(is_bad_number(Spectrum::tma(bad, 1e5, 10.0), "wind_speed"));
        assert!(is_bad_number(Spectrum::tma(10.0, bad, 10.0), "fetch"));
        assert!(is_bad_number(Spectrum::tma(10.0, 1e5, bad), "depth"));
        assert!(is_bad_number(
            Spectrum::jonswap_from_parameters(bad, 1.0, 3.3),
            "alpha"
        ));
        assert!(is_bad_number(
            Spectrum::jonswap_from_parameters(0.01, bad, 3.3),
            "peak_omega"
        ));
        assert!(is_bad_number(
            Spectrum::jonswap_from_parameters(0.01, 1.0, bad),
            "gamma"
        ));
        assert!(matches!(
            Dispersion::finite_depth(bad),
            Err(Error::NonFinite { .. } | Error::OutOfRange { .. })
        ));
        assert!(matches!(
            Dispersion::capillary(bad),
            Err(Error::NonFinite { .. } | Error::OutOfRange { .. })
        ));
    }
    assert!(is_bad_number(Spectrum::phillips(10.0, -1.0), "amplitude"));
    assert!(is_bad_number(
        Spectrum::phillips(10.0, f32::NAN),
        "amplitude"
    ));
    // Wind speeds above any measured at sea are rejected (they would overflow the cascade).
    assert!(is_bad_number(Spectrum::jonswap(201.0, 1e5), "wind_speed"));
    assert!(is_bad_number(Spectrum::phillips(1e6, 1.0), "wind_speed"));
    assert!(is_bad_number(
        Spectrum::pierson_moskowitz(250.0),
        "wind_speed"
    ));
}

#[test]
fn setters_reject_bad_numbers() {
    let s = || Spectrum::jonswap(10.0, 1e5).unwrap();
    for bad in [f32::NAN, f32::INFINITY] {
        assert!(is_bad_number(
            s().with_wind_direction(bad),
            "wind_direction"
        ));
        assert!(is_bad_number(
            s().with_short_wave_length(bad),
            "short_wave_length"
        ));
    }
    for bad in [0.0, -2.0, f32::NAN, f32::INFINITY] {
        assert!(is_bad_number(s().with_gamma(bad), "gamma"));
        assert!(is_bad_number(s().with_depth(bad), "depth"));
        assert!(is_bad_number(
            s().with_spreading(Spreading::Cos2s { s: bad }),
            "s"
        ));
    }
    for bad in [-0.1, 1.1, f32::NAN] {
        assert!(is_bad_number(s().with_swell(bad), "swell"));
        assert!(is_bad_number(s().with_spread_blend(bad), "spread_blend"));
        let spreading = Spreading::Cosine {
            exponent: 2.0,
            upwind: bad,
        };
        assert!(is_bad_number(s().with_spreading(spreading), "upwind"));
    }
    let spreading = Spreading::Cosine {
        exponent: -1.0,
        upwind: 0.5,
    };
    assert!(is_bad_number(s().with_spreading(spreading), "exponent"));
    assert!(is_bad_number(
        s().with_short_wave_length(-1.0),
        "short_wave_length"
    ));
    let unchecked = Dispersion::FiniteDepth { depth: -3.0 };
    assert!(is_bad_number(s().with_dispersion(unchecked), "depth"));
    // Parameters a model does not have.
    let phillips = || Spectrum::phillips(10.0, 1.0).unwrap();
    assert!(matches!(
        phillips().with_gamma(2.0),
        Err(Error::NotApplicable { name: "gamma", .. })
    ));
    assert!(matches!(
        phillips().with_depth_factor(DepthFactor::Kitaigorodskii),
        Err(Error::NotApplicable { .. })
    ));
}

#[test]
fn evaluation_is_finite_everywhere() {
    let spectra = [
        Spectrum::jonswap(10.0, 1e5)
            .unwrap()
            .with_spreading(Spreading::Mitsuyasu)
            .unwrap(),
        Spectrum::tma(30.0, 1e6, 0.5)
            .unwrap()
            .with_spreading(Spreading::Hasselmann)
            .unwrap(),
        Spectrum::phillips(0.5, 1.0).unwrap(),
        Spectrum::pierson_moskowitz(40.0)
            .unwrap()
            .with_swell(1.0)
            .unwrap(),
    ];
    let values = [
        0.0,
        -1.0,
        1e-30,
        1e-6,
        0.3,
        1.0,
        7.0,
        1e4,
        1e30,
        f32::MAX,
        f32::NAN,
        f32::INFINITY,
    ];
    for spectrum in &spectra {
        for &a in &values {
            let s = spectrum.omega_spectrum(a);
            assert!(s.is_finite() && s >= 0.0, "{spectrum:?} S({a}) = {s}");
            for &b in &values {
                let d = spectrum.spreading(a, b);
                assert!(d.is_finite() && d >= 0.0, "D({a}, {b}) = {d}");
                let k = spectrum.density([a, b]);
                assert!(k.is_finite() && k >= 0.0, "S(({a}, {b})) = {k}");
            }
        }
        let hs = spectrum.significant_wave_height();
        assert!(hs.is_finite() && hs > 0.0);
    }
}

#[test]
fn spreading_exponents_are_bounded_so_evaluation_stays_finite() {
    const MAX_SPREADING_EXPONENT: f32 = Spreading::MAX_EXPONENT;
    let base = Spectrum::jonswap(10.0, 100_000.0).unwrap();
    for bad in [1e20f32, f32::MAX, MAX_SPREADING_EXPONENT * 1.01] {
        assert!(base
            .clone()
            .with_spreading(Spreading::Cos2s { s: bad })
            .is_err());
        let cosine = Spreading::Cosine {
            exponent: bad,
            upwind: 1.0,
        };
        assert!(base.clone().with_spreading(cosine).is_err());
    }
    // At the bound the spreading still integrates to 1 (midpoint rule on a grid fine enough
    // for its 1° width: 200 000 steps of 3e-5 rad) and S(k) is finite everywhere.
    let narrow = base
        .with_spreading(Spreading::Cos2s {
            s: MAX_SPREADING_EXPONENT,
        })
        .unwrap();
    let steps = 200_000;
    let h = 2.0 * std::f64::consts::PI / f64::from(steps);
    let omega = narrow.peak_omega();
    let integral: f64 = (0..steps)
        .map(|i| {
            let theta = -std::f64::consts::PI + (f64::from(i) + 0.5) * h;
            f64::from(narrow.spreading(omega, theta as f32)) * h
        })
        .sum();
    assert!((integral - 1.0).abs() < 1e-3, "∫D = {integral}");
    for kx in [-0.3f32, 0.0, 0.01, 0.1, 2.0] {
        for kz in [-0.2f32, 0.0, 0.05] {
            assert!(narrow.density([kx, kz]).is_finite());
        }
    }
}
