//! The unified directional spectrum of Elfouhaily, Chapron, Katsaros & Vandemark (1997), "A
//! unified directional spectrum for long and short wind-driven waves", J. Geophys. Res.
//! 102(C7), 15781–15796: pure f64 functions of the wave number, the wind speed U10 and the
//! inverse wave age Ω = U10/c_p.
//!
//! ```text
//! S(k) = k⁻³ (B_l + B_h)                                  omnidirectional, m³
//! B_l = ½ α_p (c_p/c) F_p,  B_h = ½ α_m (c_m/c) F_m       long- and short-wave curvature
//! c(k) = √(g/k · (1 + (k/k_m)²)),  k_m = 370 rad/m,  c_m = 0.23 m/s
//! k_p = Ω² g/U10²,  c_p = U10/Ω
//! L_PM = exp(−5/4 (k_p/k)²),  J_p = γ^Γ,  Γ = exp(−(√(k/k_p) − 1)² / (2σ²))
//! σ = 0.08 (1 + 4 Ω⁻³),  γ = 1.7 (Ω < 1),  1.7 + 6 log₁₀ Ω (Ω ≥ 1)
//! α_p = 6·10⁻³ √Ω
//! F_p = L_PM J_p exp(−Ω/√10 · (√(k/k_p) − 1))
//! α_m = 10⁻² (1 + ln(u*/c_m)) (u* ≤ c_m),  10⁻² (1 + 3 ln(u*/c_m)) (u* > c_m)
//! F_m = L_PM J_p exp(−¼ (k/k_m − 1)²)
//! D(k, φ) = (1 + Δ(k) cos 2φ) / (2π)
//! Δ(k) = tanh(a_0 + a_p (c/c_p)^2.5 + a_m (c_m/c)^2.5),  a_0 = ln 2 / 4,  a_p = 4,
//! a_m = 0.13 u*/c_m
//! ```
//!
//! The friction velocity u* is taken from U10 with Wu's (1982) drag coefficient
//! C_D = (0.8 + 0.065 U10)·10⁻³, u* = √C_D U10. α_m is kept ≥ 0 (the logarithm turns it
//! negative for u* < c_m/e, U10 below about 2.6 m/s: the short-wave part then vanishes).
//! F_m carries the factor L_PM J_p of the long waves so that the spectrum vanishes below
//! the peak (without it k⁻³ B_h ∝ k^−2.5 would not be integrable at k → 0).

use super::omega::G;
use crate::math::determinism::Math;

/// Wave number of the gravity–capillary phase-speed minimum, rad/m.
pub(crate) const K_M: f64 = 370.0;
/// Minimum phase speed, m/s.
pub(crate) const C_M: f64 = 0.23;

/// Phase speed c(k) = √(g/k · (1 + (k/k_m)²)) in m/s of the spectrum's own dispersion.
pub(crate) fn phase_speed(k: f64) -> f64 {
    let r = k / K_M;
    (G / k * (1.0 + r * r)).sqrt()
}

/// The wave number k of angular frequency ω under ω² = g k (1 + (k/k_m)²): Newton from the
/// smaller of the gravity and capillary asymptotes (f is convex and increasing, so the
/// iteration decreases monotonically onto the root from above).
pub(crate) fn wave_number<M: Math>(omega: f64) -> f64 {
    if omega.is_nan() || omega <= 0.0 {
        return 0.0;
    }
    let target = omega * omega / G;
    let mut k = target.min(M::cbrt(target * K_M * K_M)) * 1.0000001;
    // Start at or above the root: both asymptotes over-estimate k.
    for _ in 0..60 {
        let r2 = (k / K_M) * (k / K_M);
        let f = k * (1.0 + r2) - target;
        let df = 1.0 + 3.0 * r2;
        let step = f / df;
        k -= step;
        if step.abs() <= 1e-15 * k {
            break;
        }
    }
    k
}

/// Friction velocity u* = √C_D U10 in m/s, C_D = (0.8 + 0.065 U10)·10⁻³ (Wu 1982).
pub(crate) fn friction_velocity(wind_speed: f64) -> f64 {
    ((0.8 + 0.065 * wind_speed) * 1e-3).sqrt() * wind_speed
}

/// Peak wave number k_p = Ω² g / U10² in rad/m.
pub(crate) fn peak_wave_number(wind_speed: f64, inverse_wave_age: f64) -> f64 {
    inverse_wave_age * inverse_wave_age * G / (wind_speed * wind_speed)
}

/// Omnidirectional wave-number spectrum S(k) = k⁻³ (B_l + B_h) in m³.
pub(crate) fn omni<M: Math>(k: f64, wind_speed: f64, inverse_wave_age: f64) -> f64 {
    if k.is_nan() || k <= 0.0 {
        return 0.0;
    }
    let omega_c = inverse_wave_age;
    let k_p = peak_wave_number(wind_speed, omega_c);
    let ratio = k_p / k;
    let lpm_exponent = -1.25 * ratio * ratio;
    if lpm_exponent < -700.0 {
        return 0.0;
    }
    let c = phase_speed(k);
    let c_p = wind_speed / omega_c;
    let sigma = 0.08 * (1.0 + 4.0 / (omega_c * omega_c * omega_c));
    let gamma = if omega_c < 1.0 {
        1.7
    } else {
        1.7 + 6.0 * M::log10(omega_c)
    };
    let root = (k / k_p).sqrt() - 1.0;
    let big_gamma = M::exp(-root * root / (2.0 * sigma * sigma));
    let long = M::exp(lpm_exponent) * M::powf(gamma, big_gamma);
    let alpha_p = 6e-3 * omega_c.sqrt();
    let f_p = long * M::exp(-omega_c / 10f64.sqrt() * root);
    let b_l = 0.5 * alpha_p * (c_p / c) * f_p;
    let alpha_m = short_wave_alpha::<M>(friction_velocity(wind_speed));
    let m = k / K_M - 1.0;
    let f_m = long * M::exp(-0.25 * m * m);
    let b_h = 0.5 * alpha_m * (C_M / c) * f_m;
    (b_l + b_h) / (k * k * k)
}

/// α_m of the short waves, kept ≥ 0.
fn short_wave_alpha<M: Math>(u_star: f64) -> f64 {
    let log = M::ln(u_star / C_M);
    let alpha = if u_star <= C_M {
        1e-2 * (1.0 + log)
    } else {
        1e-2 * (1.0 + 3.0 * log)
    };
    alpha.max(0.0)
}

/// The spreading's Δ(k) ∈ [0, 1) at wave number `k`, for a peak at `k_p` and wind speed
/// U10 (m/s).
pub(crate) fn delta<M: Math>(k: f64, k_p: f64, wind_speed: f64) -> f64 {
    if !(k > 0.0 && k_p > 0.0) {
        return 0.0;
    }
    let c = phase_speed(k);
    let c_p = phase_speed(k_p);
    let a_m = 0.13 * friction_velocity(wind_speed) / C_M;
    let a_0 = std::f64::consts::LN_2 / 4.0;
    M::tanh(a_0 + 4.0 * M::powf(c / c_p, 2.5) + a_m * M::powf(C_M / c, 2.5))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::determinism::Std;

    #[test]
    fn wave_number_inverts_the_dispersion() {
        for k in [1e-4, 0.01, 1.0, 50.0, 370.0, 5e3, 1e5] {
            let omega = k * phase_speed(k);
            let back = wave_number::<Std>(omega);
            assert!((back / k - 1.0).abs() < 1e-12, "k = {k}: {back}");
        }
    }
}
