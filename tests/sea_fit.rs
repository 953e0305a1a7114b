//! How much of a sea the grids hold (`OceanConfig::fit`, `OceanState::fit`), grids fitted to
//! a sea (`OceanConfig::fitted`), a change of weather the grids cannot hold refused
//! (`set_spectrum`) unless accepted (`set_spectrum_unfitted`), a sea the grids cannot hold
//! refused by `OceanState::new`, and the largest choppiness (`max_choppiness`).
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

use ocean_fft::{Error, OceanConfig, OceanState, SeaFit, SeaState, Spectrum};

/// ∫∫ S(k) d²k over lo ≤ |k| < hi, in f64 from `Spectrum::density` (the 2D spectrum, not the
/// crate's 1D quadrature of the omnidirectional one): Simpson in ln k, 400 nodes a decade,
/// times the trapezoid rule over 512 directions (exact to rounding for a smooth periodic
/// integrand). Limited to [1e-3, 1e4]·k_p, outside which these spectra hold below 1e-9 of
/// their variance.
fn variance_2d(spectrum: &Spectrum, lo: f64, hi: f64) -> f64 {
    let k_peak = f64::from(spectrum.dispersion().k_from_omega(spectrum.peak_omega()));
    let (lo, hi) = (lo.max(1e-3 * k_peak), hi.min(1e4 * k_peak));
    if hi <= lo {
        return 0.0;
    }
    let (a, b) = (lo.ln(), hi.ln());
    let n = (((b - a) / std::f64::consts::LN_10 * 400.0).ceil() as usize).max(2) & !1;
    let n = n.max(2);
    let h = (b - a) / n as f64;
    let directions = 512;
    let ring = |k: f64| -> f64 {
        let mut sum = 0.0;
        for d in 0..directions {
            let theta = std::f64::consts::TAU * d as f64 / directions as f64;
            let kv = [(k * theta.cos()) as f32, (k * theta.sin()) as f32];
            sum += f64::from(spectrum.density(kv));
        }
        // ∫ S(k) k dθ, and d k = k d(ln k).
        sum * std::f64::consts::TAU / directions as f64 * k * k
    };
    let mut total = ring(a.exp()) + ring(b.exp());
    for i in 1..n {
        let weight = if i % 2 == 1 { 4.0 } else { 2.0 };
        total += weight * ring((a + i as f64 * h).exp());
    }
    total * h / 3.0
}

/// The calm preset's grids (60 / 13.8 / 3.1 m) and the storm's spectrum.
fn calm_ocean_and_storm() -> (OceanState, Spectrum) {
    let (calm, mut config) = SeaState::Calm.build();
    config.size = 64;
    let ocean = OceanState::new(calm, config).unwrap();
    let (storm, _) = SeaState::Storm.build();
    (ocean, storm)
}

#[test]
fn a_change_of_weather_the_grids_cannot_hold_is_refused() {
    // Fails on the code before `SeaFit`: `set_spectrum` accepted this and the sea settled at
    // H_s 2.71 m of the storm's 12.22 m (4.9 % of its variance on a 256² grid).
    let (mut ocean, storm) = calm_ocean_and_storm();
    let before = ocean.spectrum().clone();
    let error = ocean.set_spectrum(storm.clone(), 10.0).unwrap_err();
    let Error::SeaDoesNotFit {
        name,
        held,
        min,
        too_long,
        ..
    } = error.clone()
    else {
        panic!("{error:?}");
    };
    assert_eq!(name, "spectrum");
    assert_eq!(min, ocean_fft::limits::MIN_CHANGE_SHARE);
    // The quadrature of the bands gives 7.7 %, nearly all the rest too long for the 60 m
    // tile (the grid's own sums at 64² are a few percent of the variance off).
    assert!(held < 0.1, "{held}");
    assert!(too_long > 0.9, "{too_long}");
    let text = error.to_string();
    for word in [
        "`spectrum`",
        "longer than the largest tile",
        "OceanConfig::fitted",
    ] {
        assert!(text.contains(word), "{text}");
    }
    // Nothing changed.
    assert_eq!(ocean.spectrum(), &before);
    assert_eq!(ocean.diagnostics().transition_progress(), None);
    // Accepted when asked, and then the ocean says what it holds.
    ocean.set_spectrum_unfitted(storm.clone(), 0.0).unwrap();
    assert_eq!(ocean.spectrum(), &storm);
    let fit = ocean.diagnostics().fit();
    assert!((fit.held - held).abs() < 1e-12, "{fit:?} {held}");
}

#[test]
fn fit_is_the_quadrature_of_the_bands() {
    // Three seas on three sets of grids, a good fit and two poor ones.
    let cases = [
        (SeaState::FreshBreeze, vec![1000.0, 230.0, 51.0]),
        (SeaState::Storm, vec![60.0, 13.8, 3.1]),
        (SeaState::Calm, vec![4000.0, 920.0]),
    ];
    for (sea, lengths) in cases {
        let (spectrum, _) = sea.build();
        let config = OceanConfig {
            lengths,
            size: 64,
            ..OceanConfig::default()
        };
        let fit: SeaFit = config.fit(&spectrum).unwrap();
        let bands = config.bands().unwrap();
        let first =
            std::f64::consts::TAU / f64::from(config.lengths[0]) / std::f64::consts::PI.sqrt();
        let top = f64::from(bands.last().unwrap().1);
        let sea_variance = variance_2d(&spectrum, 0.0, f64::INFINITY);
        let held = variance_2d(&spectrum, first, top) / sea_variance;
        let long = variance_2d(&spectrum, 0.0, first) / sea_variance;
        let short = variance_2d(&spectrum, top, f64::INFINITY) / sea_variance;
        // Both quadratures are converged to ~1e-6 (the density is f32); 1e-4 of the
        // variance separates them from a band edge off by a tenth of a percent.
        for (what, got, want) in [
            ("held", fit.held, held),
            ("too_long", fit.too_long, long),
            ("too_short", fit.too_short, short),
        ] {
            assert!((got - want).abs() < 1e-4, "{sea:?} {what}: {got} vs {want}");
        }
        assert!(
            (fit.variance / sea_variance - 1.0).abs() < 1e-4,
            "{sea:?}: {} vs {sea_variance}",
            fit.variance
        );
        assert!((fit.held + fit.too_long + fit.too_short - 1.0).abs() < 1e-4);
        // And the grids' own sums Σ S Δk² over their wave vectors: a Riemann sum of the same
        // integral, within a few percent from 64² (the cell around k = 0 and the rings'
        // edges); 5 % of the sea's variance.
        let ocean = OceanState::new(spectrum.clone(), config.clone());
        if let Ok(ocean) = ocean {
            let grid = ocean.diagnostics().expected_variance() / fit.variance;
            assert!(
                (grid - fit.held).abs() < 0.05,
                "{sea:?}: grid {grid} fit {fit:?}"
            );
            assert_eq!(ocean.diagnostics().fit(), fit);
        } else {
            // Only the storm on the calm grids, which hold below a quarter of it.
            assert!(
                fit.held < ocean_fft::limits::MIN_BUILD_SHARE,
                "{sea:?} {fit:?}"
            );
        }
        eprintln!("{sea:?}: {fit:?}");
    }
}

#[test]
fn fitted_grids_hold_the_sea() {
    let mut seas: Vec<Spectrum> = SeaState::ALL.iter().map(|s| s.build().0).collect();
    for wind in [0.5, 2.0, 5.0, 10.0, 20.0, 40.0, 80.0, 150.0] {
        seas.push(Spectrum::pierson_moskowitz(wind).unwrap());
        seas.push(Spectrum::jonswap(wind, 10_000.0).unwrap());
    }
    seas.push(Spectrum::phillips(10.0, 1e-3).unwrap());
    seas.push(Spectrum::tma(20.0, 100_000.0, 3.0).unwrap());
    for spectrum in &seas {
        let config = OceanConfig::fitted(spectrum).unwrap();
        let fit = config.fit(spectrum).unwrap();
        assert!(
            fit.held >= OceanConfig::FITTED_SHARE,
            "{spectrum:?}: {fit:?}"
        );
        let small = OceanConfig {
            size: 32,
            ..config.clone()
        };
        OceanState::new(spectrum.clone(), small).unwrap();
    }
}

#[test]
fn presets_use_fitted_grids_near_the_hand_chosen_ones_of_0_3() {
    // 0.3's hand-chosen lengths, 9 to 14 peak wavelengths for the largest tile: an
    // independent judgement of what suits each sea, which fitted grids (12) stay near.
    let hand_chosen: [(SeaState, [f32; 3]); 6] = [
        (SeaState::Calm, [60.0, 13.8, 3.1]),
        (SeaState::ModerateBreeze, [500.0, 115.0, 25.5]),
        (SeaState::FreshBreeze, [1000.0, 230.0, 51.0]),
        (SeaState::Storm, [4000.0, 920.0, 204.0]),
        (SeaState::Swell, [2000.0, 460.0, 102.0]),
        (SeaState::ShallowBay, [200.0, 46.0, 10.2]),
    ];
    for (sea, old) in hand_chosen {
        let (spectrum, preset) = sea.build();
        let fit = preset.fit(&spectrum).unwrap();
        assert!(fit.held >= OceanConfig::FITTED_SHARE, "{sea:?}: {fit:?}");
        let fitted = OceanConfig {
            choppiness: preset.choppiness,
            foam: preset.foam,
            ..OceanConfig::default()
        }
        .with_fitted_lengths(&spectrum)
        .unwrap();
        assert_eq!(preset, fitted, "{sea:?}");
        eprintln!("{sea:?}: preset {:?}, 0.3 {old:?}", preset.lengths);
        assert_eq!(preset.lengths.len(), old.len(), "{sea:?}");
        // 12 peak wavelengths against 9 to 14: within 0.8 and 1.4 of the hand-chosen tile.
        for (new, old) in preset.lengths.iter().zip(old) {
            assert!((0.8..1.4).contains(&(new / old)), "{sea:?}: {new} vs {old}");
        }
    }
}

#[test]
fn a_sea_the_default_grids_cannot_hold_is_refused() {
    // A 150 m/s wind: H_s 306 m, of which the default grids held 48 m.
    let spectrum = Spectrum::pierson_moskowitz(150.0).unwrap();
    let error = OceanState::new(spectrum.clone(), OceanConfig::default()).unwrap_err();
    let Error::SeaDoesNotFit { name, held, .. } = error else {
        panic!("{error:?}");
    };
    assert_eq!(name, "spectrum");
    assert!(held < ocean_fft::limits::MIN_BUILD_SHARE, "{held}");
    // Fitted grids hold it.
    let config = OceanConfig {
        size: 32,
        ..OceanConfig::fitted(&spectrum).unwrap()
    };
    OceanState::new(spectrum, config).unwrap();
}

#[test]
fn absurd_choppiness_is_refused() {
    let (spectrum, mut config) = SeaState::FreshBreeze.build();
    config.size = 64;
    let mut ocean = OceanState::new(spectrum.clone(), config.clone()).unwrap();
    let limit = ocean.diagnostics().max_choppiness();
    // The presets' λσ lies in 0.2–0.5: their choppiness is far inside.
    assert!(limit > 8.0 * config.choppiness, "{limit}");
    let error = ocean.set_choppiness(1e9).unwrap_err();
    assert!(
        matches!(
            error,
            Error::OutOfRange {
                name: "choppiness",
                ..
            }
        ),
        "{error:?}"
    );
    assert_eq!(ocean.config().choppiness, config.choppiness);
    ocean.set_choppiness(limit).unwrap();
    assert!(ocean.set_choppiness(limit * 1.01).is_err());
    let refused = OceanState::new(
        spectrum,
        OceanConfig {
            choppiness: limit * 1.01,
            ..config
        },
    );
    assert!(matches!(
        refused,
        Err(Error::OutOfRange {
            name: "choppiness",
            ..
        })
    ));
}

/// The fraction of a Gaussian sea's surface that folds, J = (1 + λa)(1 + λb) − λ²c² < 0, with
/// (a, b, c) = (D_xx, D_zz, D_xz) jointly Gaussian with the covariance the cascade's evolved
/// spectrum gives them (Σ_k m_p(k) m_q(k) |h̃(k)|², the spatial covariance of two fields of
/// real multipliers, by Parseval), by Monte Carlo over `samples` draws.
fn gaussian_fold_fraction(cascade: &ocean_fft::Cascade, lambda: f64, samples: usize) -> f64 {
    let n = cascade.size();
    let dk = std::f64::consts::TAU / f64::from(cascade.length());
    let h = ocean_fft::inspect::wave_spectrum(cascade, cascade.time()).unwrap();
    let m = |i: usize| {
        if i < n / 2 {
            i as f64
        } else {
            i as f64 - n as f64
        }
    };
    let mut cov = [[0.0f64; 3]; 3];
    for j in 0..n {
        for i in 0..n {
            let (kx, kz) = (dk * m(i), dk * m(j));
            let k = kx.hypot(kz);
            if k == 0.0 {
                continue;
            }
            let power = f64::from(h[j * n + i].norm_sqr());
            let mult = [-kx * kx / k, -kz * kz / k, -kx * kz / k];
            for p in 0..3 {
                for q in 0..3 {
                    cov[p][q] += mult[p] * mult[q] * power;
                }
            }
        }
    }
    // Cholesky factor L of the covariance: (a, b, c) = L·ξ.
    let mut l = [[0.0f64; 3]; 3];
    for p in 0..3 {
        for q in 0..=p {
            let sum: f64 = (0..q).map(|r| l[p][r] * l[q][r]).sum();
            l[p][q] = if p == q {
                (cov[p][p] - sum).max(0.0).sqrt()
            } else {
                (cov[p][q] - sum) / l[q][q]
            };
        }
    }
    // xorshift64* and Box–Muller: a generator of the test's own.
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut uniform = || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        ((state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    let mut folded = 0usize;
    for _ in 0..samples {
        let (u1, u2, u3, u4) = (uniform(), uniform(), uniform(), uniform());
        let r1 = (-2.0 * u1.ln()).sqrt();
        let r2 = (-2.0 * u3.ln()).sqrt();
        let xi = [
            r1 * (std::f64::consts::TAU * u2).cos(),
            r1 * (std::f64::consts::TAU * u2).sin(),
            r2 * (std::f64::consts::TAU * u4).cos(),
        ];
        let v: Vec<f64> = (0..3)
            .map(|p| (0..3).map(|q| l[p][q] * xi[q]).sum())
            .collect();
        let j = (1.0 + lambda * v[0]) * (1.0 + lambda * v[1]) - lambda * lambda * v[2] * v[2];
        if j < 0.0 {
            folded += 1;
        }
    }
    folded as f64 / samples as f64
}

#[test]
fn the_largest_choppiness_folds_the_surface_nearly_everywhere_it_can() {
    // One cascade, so that its Jacobian is the ocean's; the fold fraction of its grid over
    // 8 seeds against the Gaussian model of the same realisations.
    let (spectrum, _) = SeaState::FreshBreeze.build();
    let seeds = 8;
    let mut measured = [0.0; 3];
    let mut model = [0.0; 3];
    // λσ = 0.5 (the presets' range), 2 and 4 (the limit).
    let scales = [0.5, 2.0, 4.0];
    for seed in 0..seeds {
        let config = OceanConfig {
            lengths: vec![300.0],
            size: 128,
            seed,
            ..OceanConfig::default()
        };
        let mut ocean = OceanState::new(spectrum.clone(), config).unwrap();
        let limit = ocean.diagnostics().max_choppiness();
        for (s, scale) in scales.iter().enumerate() {
            let lambda = limit * scale / ocean_fft::limits::MAX_FOLD_SCALE;
            ocean.set_choppiness(lambda).unwrap();
            ocean.step(1.0).unwrap();
            let cascade = &ocean.cascades()[0];
            let j = cascade.jacobian();
            measured[s] += j.iter().filter(|&&j| j < 0.0).count() as f64 / j.len() as f64;
            model[s] += gaussian_fold_fraction(cascade, f64::from(lambda), 200_000);
        }
        // At the limit the inversion may not converge, but no height is absurd: |η| stays
        // below about 5σ_η = 1.25 H_s over these points and the mean-level correction
        // λ∫kS d²k below H_s (Cauchy–Schwarz: ∫kS ≤ σ·√m0, and λσ = 4), so 4 H_s bounds
        // them with room; λ = 1e9 gave 5.7e7 m.
        let hs = f64::from(ocean.spectrum().significant_wave_height());
        let points: Vec<[f64; 2]> = (0..400)
            .map(|i| [f64::from(i) * 7.31, f64::from(i % 37) * 11.7])
            .collect();
        let mut heights = vec![0.0f32; points.len()];
        ocean.water().heights_at(&points, &mut heights).unwrap();
        for (&[x, z], &h) in points.iter().zip(&heights) {
            assert!(f64::from(h).abs() < 4.0 * hs, "{h} m at ({x}, {z})");
            let single = ocean.water().height_at(x, z).unwrap();
            assert!(
                f64::from(single).abs() < 4.0 * hs,
                "{single} m at ({x}, {z})"
            );
        }
    }
    for s in 0..3 {
        measured[s] /= f64::from(seeds as u32);
        model[s] /= f64::from(seeds as u32);
    }
    eprintln!("λσ {scales:?}: folded {measured:?}, Gaussian model {model:?}");
    for s in 0..3 {
        // The grid's field is a sum of a few thousand waves, Gaussian to a few percent of the
        // fraction in the bulk; the rare folds at λσ = 0.5 sit in the tail, where the sum's
        // non-Gaussian tail and the 8 × 128² correlated points allow a factor 1.5.
        let tolerance = if s == 0 { 0.5 } else { 0.1 };
        assert!(
            (measured[s] / model[s] - 1.0).abs() < tolerance,
            "λσ = {}: {} vs {}",
            scales[s],
            measured[s],
            model[s]
        );
    }
    // At the limit about half the surface folds, the most a Gaussian sea's linear term
    // allows: nearly everywhere it can.
    assert!(measured[2] > 0.4, "{measured:?}");
    // The presets' range folds little.
    assert!(measured[0] < 0.02, "{measured:?}");
}

#[test]
fn increasing_lengths_are_refused_saying_they_must_decrease() {
    let config = OceanConfig {
        lengths: vec![60.0, 230.0],
        ..OceanConfig::default()
    };
    let error = config.validate().unwrap_err();
    assert_eq!(
        error,
        Error::NotDecreasing {
            name: "lengths",
            index: 1,
            value: 230.0,
            previous: 60.0
        }
    );
    let text = error.to_string();
    assert!(text.contains("must strictly decrease"), "{text}");
    // Equal lengths too.
    let equal = OceanConfig {
        lengths: vec![60.0, 60.0],
        ..OceanConfig::default()
    };
    assert!(matches!(
        equal.validate(),
        Err(Error::NotDecreasing { index: 1, .. })
    ));
}

#[test]
fn grids_fitted_to_the_roughest_sea_hold_the_calmer_ones() {
    // What the weather guide promises: grids fitted to the storm take every deep-water
    // preset down to the moderate breeze as a live change.
    let (storm, _) = SeaState::Storm.build();
    let config = OceanConfig::fitted(&storm).unwrap();
    for sea in [
        SeaState::ModerateBreeze,
        SeaState::FreshBreeze,
        SeaState::Swell,
    ] {
        let fit = config.fit(&sea.build().0).unwrap();
        eprintln!("{sea:?} on the storm's fitted grids: {fit:?}");
        assert!(
            fit.held >= ocean_fft::limits::MIN_CHANGE_SHARE,
            "{sea:?}: {fit:?}"
        );
    }
    let calm = config.fit(&SeaState::Calm.build().0).unwrap();
    eprintln!("Calm on the storm's fitted grids: {calm:?}");
}

#[test]
fn every_preset_sits_far_below_the_largest_choppiness() {
    // λσ < 0.5 for every preset on its own 256² grids, as the guide says (the slope
    // variance grows with N, so 256² is the presets' steepest case here).
    for sea in SeaState::ALL {
        let (spectrum, config) = sea.build();
        let choppiness = config.choppiness;
        let ocean = OceanState::new(spectrum, config).unwrap();
        let scale =
            choppiness / ocean.diagnostics().max_choppiness() * ocean_fft::limits::MAX_FOLD_SCALE;
        eprintln!("{sea:?}: λσ = {scale}");
        assert!(scale < 0.5, "{sea:?}: λσ = {scale}");
    }
}
