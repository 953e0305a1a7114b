//! The calibration's tests: the statistics against a Monte Carlo of the Gaussian gradient,
//! erfc against closed forms.
// Matrix arithmetic reads best with its indices; the references use the standard library's
// maths (tests are not simulation code).
#![allow(clippy::needless_range_loop, clippy::disallowed_methods)]

use super::*;
use crate::math::determinism::Std;
use rand::{Rng, SeedableRng};
use rand_distr::StandardNormal;

#[test]
fn erfc_matches_reference_values() {
    // erfc at these points (Abramowitz & Stegun 1964, table 7.1, extended; the same
    // digits as any double-precision library).
    let cases = [
        (0.0, 1.0),
        (0.5, 0.479_500_122_186_953_5),
        (1.0, 0.157_299_207_050_285_13),
        (2.0, 0.004_677_734_981_047_266),
        (2.5, 4.069_520_174_449_59e-4),
        (3.0, 2.209_049_699_858_544e-5),
        (5.0, 1.537_459_794_428_035e-12),
        (10.0, 2.088_487_583_762_545e-45),
        (-1.0, 1.842_700_792_949_715),
    ];
    for (x, expected) in cases {
        let got = erfc::<Std>(x);
        assert!(
            ((got - expected) / expected).abs() < 2e-13,
            "erfc::<Std>({x}) = {got}, expected {expected}"
        );
    }
    // Continuity where the two methods meet.
    let below = erfc::<Std>(SERIES_LIMIT - 1e-12);
    let above = erfc::<Std>(SERIES_LIMIT + 1e-12);
    assert!(((below - above) / above).abs() < 1e-10);
}

/// The probability and the crossing rate against a Monte-Carlo simulation of the Gaussian
/// vector (independent of the integrals: sampled, not integrated). The rate is checked
/// through its definition as the expected number of down-crossings per unit time: with
/// (g, ġ) sampled, the surface follows g + ġτ for |τ| ≤ dt/2, and a down-crossing of J_b
/// within that window is counted (the symmetric window has no first-order bias in dt).
#[test]
fn fraction_and_rate_match_a_monte_carlo_of_the_gaussian_gradient() {
    // A short-crested sea's gradient covariance (correlated A and B, a C correlated with
    // both as for a wind off the axes) and a rate covariance of its own shape.
    let value = [
        [0.012, 0.004, 0.002],
        [0.004, 0.008, 0.0015],
        [0.002, 0.0015, 0.004],
    ];
    let rate = [[0.9, 0.3, 0.1], [0.3, 0.6, 0.12], [0.1, 0.12, 0.3]];
    let moments = GradientMoments { value, rate };
    let stats = Statistics::<Std>::new(&moments);
    let threshold = 0.7;
    let (fraction, crossing) = stats.crossing(threshold);
    let chol = |m: [[f64; 3]; 3]| {
        let mut l = [[0.0f64; 3]; 3];
        for i in 0..3 {
            for j in 0..=i {
                let mut s = m[i][j];
                for k in 0..j {
                    s -= l[i][k] * l[j][k];
                }
                l[i][j] = if i == j { s.sqrt() } else { s / l[j][j] };
            }
        }
        l
    };
    let jacobian = |g: [f64; 3]| (1.0 + g[0]) * (1.0 + g[1]) - g[2] * g[2];
    let (lv, lr) = (chol(value), chol(rate));
    let mut rng = rand::rngs::StdRng::seed_from_u64(12);
    let samples = 4_000_000;
    let dt = 0.01;
    let (mut below, mut crossings) = (0u64, 0u64);
    for _ in 0..samples {
        let z: [f64; 6] = std::array::from_fn(|_| rng.sample(StandardNormal));
        let g: [f64; 3] = std::array::from_fn(|i| (0..3).map(|k| lv[i][k] * z[k]).sum());
        let d: [f64; 3] = std::array::from_fn(|i| (0..3).map(|k| lr[i][k] * z[3 + k]).sum());
        below += u64::from(jacobian(g) < threshold);
        let before = jacobian(std::array::from_fn(|i| g[i] - 0.5 * dt * d[i]));
        let after = jacobian(std::array::from_fn(|i| g[i] + 0.5 * dt * d[i]));
        crossings += u64::from(before >= threshold && after < threshold);
    }
    let measured_fraction = below as f64 / f64::from(samples);
    let measured_rate = crossings as f64 / f64::from(samples) / dt;
    // p ≈ 0.04 and ~1e4 crossings here: relative standard errors of 0.25 % and 1 %; the
    // window's bias is second order in dt (below 0.5 % at this dt). 4 % is four standard
    // errors of the rate.
    assert!(
        (measured_fraction / fraction - 1.0).abs() < 0.02,
        "P(J < J_b): integral {fraction}, Monte Carlo {measured_fraction}"
    );
    assert!(
        (measured_rate / crossing - 1.0).abs() < 0.04,
        "crossing rate: integral {crossing}, Monte Carlo {measured_rate} ({crossings})"
    );
}

/// A long-crested sea (all waves along x) makes T, P and C degenerate: J = 1 + D_xx is
/// linear and Gaussian, with the closed forms p = Φ((J_b − 1)/σ) and Rice's
/// ν = (σ'/σ) φ((1 − J_b)/σ)/(2π)·√(2π).
#[test]
fn a_long_crested_sea_gives_rices_closed_forms() {
    let (var, var_rate) = (0.01, 0.5);
    let mut moments = GradientMoments::default();
    moments.value[0][0] = var;
    moments.rate[0][0] = var_rate;
    let stats = Statistics::<Std>::new(&moments);
    for threshold in [0.9, 0.75, 0.6] {
        let (p, nu) = stats.crossing(threshold);
        let u = (1.0 - threshold) / var.sqrt();
        let expected_p = normal_cdf::<Std>(-u);
        let expected_nu = (var_rate / var).sqrt() / std::f64::consts::TAU * (-0.5 * u * u).exp();
        assert!((p / expected_p - 1.0).abs() < 1e-9, "{p} vs {expected_p}");
        assert!(
            (nu / expected_nu - 1.0).abs() < 1e-9,
            "{nu} vs {expected_nu}"
        );
    }
}
