//! The mean water level under choppiness: measured as an observer would (the water height at
//! fixed world points, `heights_at`, over a large area and many frames), it is still water
//! for any λ, and the correction that makes it so is the expected λ Σ |k| S(k) Δk².
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

use std::f64::consts::TAU;

use ocean_fft::{OceanConfig, OceanState, SeaState, Spectrum};

/// Σ_k |k| S(k) Δk² over every cascade's grid wave vectors in its band (from
/// `Spectrum::density`), and the standard deviation of its random counterpart
/// 2 Σ_k |k| |h0(k)|²: the h0(k) are independent, each |h0|² exponential with mean
/// ½ S Δk², so each term 2|k||h0|² has mean w = |k| S Δk² and standard deviation w.
fn expected_level_per_choppiness(ocean: &OceanState) -> (f64, f64) {
    let bands = ocean.config().bands().unwrap();
    let (mut sum, mut var) = (0.0, 0.0);
    for (cascade, &(k_min, k_max)) in ocean.cascades().iter().zip(&bands) {
        let n = cascade.size() as i64;
        let dk = TAU / f64::from(cascade.length());
        for j in -n / 2 + 1..n / 2 {
            for i in -n / 2 + 1..n / 2 {
                let (kx, kz) = (i as f64 * dk, j as f64 * dk);
                let k = kx.hypot(kz);
                if k == 0.0 || k < f64::from(k_min) || k >= f64::from(k_max) {
                    continue;
                }
                let w = k * f64::from(ocean.spectrum().density([kx as f32, kz as f32])) * dk * dk;
                sum += w;
                var += w * w;
            }
        }
    }
    (sum, var.sqrt())
}

/// Mean over `frames` frames of the mean water height at a P×P grid of world points
/// covering the largest cascade's tile, and the standard error of that mean from the spread
/// of the frame means.
fn observed_mean_level(ocean: &mut OceanState, frames: usize) -> (f64, f64) {
    let length = f64::from(ocean.cascades()[0].length());
    let p = 181;
    let spacing = length / p as f64;
    let points: Vec<[f64; 2]> = (0..p * p)
        .map(|i| {
            [
                (i % p) as f64 * spacing + 0.37,
                (i / p) as f64 * spacing - 0.61,
            ]
        })
        .collect();
    let mut heights = vec![0.0f32; points.len()];
    let mut means = Vec::with_capacity(frames);
    for _ in 0..frames {
        // 13.7 s apart: longer than the peak periods, so the frames' wave phases differ.
        ocean.step(13.7).unwrap();
        ocean.water().heights_at(&points, &mut heights).unwrap();
        means.push(heights.iter().map(|&h| f64::from(h)).sum::<f64>() / heights.len() as f64);
    }
    let f = frames as f64;
    let mean = means.iter().sum::<f64>() / f;
    let var = means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (f - 1.0);
    (mean, (var / f).sqrt())
}

/// Over the largest tile (1 km or 4 km square) and 24 frames, the observed mean level is
/// within 0.2 % of Hs of still water for λ = 0, the preset's and twice the default's (the
/// storm: half and all of its 1.2). Without the correction it would sit at −offset: 2.3 %
/// of Hs for the default sea at λ = 1, 2.9 % for the storm at 1.2.
///
/// Tolerance: what remains random is the realised Σ|k||h̃(k, t)|² of each frame about its
/// time average, and the spatial mean of η itself over the points (zero on the largest
/// tile's own period, small for the incommensurate smaller tiles). The test measures the
/// standard error of the 24-frame mean from the spread of the frame means and requires
/// 3 standard errors to fit inside 0.2 % of Hs, so the check has the power to see a bias of
/// that size; it also checks that the correction it relies on is much larger than the
/// tolerance (so leaving it out fails).
#[test]
fn the_observed_mean_level_is_still_water_for_any_choppiness() {
    let default_sea = (
        Spectrum::jonswap(10.0, 100_000.0).unwrap(),
        OceanConfig::default(),
    );
    for (name, (spectrum, config), lambdas) in [
        ("default", default_sea, [0.0f32, 1.0, 2.0]),
        ("storm", SeaState::Storm.build(), [0.0, 0.6, 1.2]),
    ] {
        let hs = f64::from(spectrum.significant_wave_height());
        for lambda in lambdas {
            let config = OceanConfig {
                size: 128,
                choppiness: lambda,
                ..config.clone()
            };
            let mut ocean = OceanState::new(spectrum.clone(), config).unwrap();
            let offset = f64::from(ocean.diagnostics().mean_level_offset());
            let (expected, sd) = expected_level_per_choppiness(&ocean);
            let (mean, se) = observed_mean_level(&mut ocean, 24);
            println!(
                "{name} λ = {lambda}: observed mean level {:+.4} m ± {:.4} ({:+.3} % of Hs = \
                 {hs:.2} m); correction {offset:.4} m = λ·{:.5} (expected λ·{expected:.5} ± \
                 {sd:.5}: λ Σ|k|S Δk²)",
                mean,
                se,
                100.0 * mean / hs,
                if lambda > 0.0 {
                    offset / f64::from(lambda)
                } else {
                    0.0
                }
            );
            assert!(
                3.0 * se < 0.002 * hs,
                "{name} λ = {lambda}: too noisy ({se})"
            );
            assert!(
                mean.abs() < 0.002 * hs,
                "{name} λ = {lambda}: mean level {mean} m, Hs {hs} m"
            );
            if lambda > 0.0 {
                let lambda = f64::from(lambda);
                // The realised correction is the expected one up to the amplitudes' chance.
                assert!(
                    (offset / lambda - expected).abs() < 4.0 * sd,
                    "{name}: correction {offset} vs λ·{expected} ± λ·{sd}"
                );
                assert!(offset > 0.005 * hs, "{name}: correction too small to test");
            } else {
                assert_eq!(offset, 0.0);
            }
        }
    }
}
