//! Non-directional spectra S(ω) and the shallow-water depth factors, as free functions in f64.
//!
//! Every function here is pure, takes SI units and returns 0 where its formula is undefined
//! (ω ≤ 0), so callers never see NaN.

use crate::math::determinism::Math;
use crate::spectrum::dispersion::Dispersion;

/// g in f64, m/s².
pub(crate) const G: f64 = crate::spectrum::dispersion::GRAVITY as f64;

/// Phillips constant of the Pierson–Moskowitz spectrum (Pierson & Moskowitz 1964).
pub(crate) const PIERSON_MOSKOWITZ_ALPHA: f64 = 0.0081;
/// ω_p U / g of a fully developed sea (Pierson & Moskowitz 1964, as ω_p = 0.877 g/U).
pub(crate) const PIERSON_MOSKOWITZ_PEAK: f64 = 0.877;

/// JONSWAP spectrum S(ω) in m²·s/rad (Hasselmann et al. 1973):
///
/// ```text
/// S(ω) = α g² ω⁻⁵ exp(−5/4 (ω_p/ω)⁴) γ^r,   r = exp(−(ω − ω_p)² / (2 σ² ω_p²)),
/// σ = 0.07 for ω ≤ ω_p, 0.09 above.
/// ```
///
/// With γ = 1 this is the Pierson–Moskowitz shape.
pub(crate) fn jonswap<M: Math>(omega: f64, alpha: f64, peak_omega: f64, gamma: f64) -> f64 {
    if omega.is_nan() || omega <= 0.0 {
        return 0.0;
    }
    let ratio = peak_omega / omega;
    let ratio2 = ratio * ratio;
    let exponent = -1.25 * ratio2 * ratio2;
    // Below ~ω_p/6 the exponential underflows; skip the rest (and avoid ∞·0).
    if exponent < -700.0 {
        return 0.0;
    }
    let sigma = if omega <= peak_omega { 0.07 } else { 0.09 };
    let d = (omega - peak_omega) / (sigma * peak_omega);
    let r = M::exp(-0.5 * d * d);
    let omega2 = omega * omega;
    alpha * G * G / (omega2 * omega2 * omega) * M::exp(exponent) * M::powf(gamma, r)
}

/// JONSWAP α from wind speed U (m/s at 10 m) and fetch F (m): α = 0.076 (U²/(F g))^0.22
/// (Hasselmann et al. 1973, as used by Horvath 2015).
pub(crate) fn jonswap_alpha<M: Math>(wind_speed: f64, fetch: f64) -> f64 {
    0.076 * M::powf(wind_speed * wind_speed / (fetch * G), 0.22)
}

/// JONSWAP peak angular frequency ω_p in rad/s from wind speed U (m/s) and fetch F (m):
/// ω_p = 22 (g² / (U F))^(1/3) (Hasselmann et al. 1973).
pub(crate) fn jonswap_peak_omega<M: Math>(wind_speed: f64, fetch: f64) -> f64 {
    22.0 * M::cbrt(G * G / (wind_speed * fetch))
}

/// Kitaigorodskii's exact depth factor Φ as a function of the dimensionless depth k h:
///
/// ```text
/// Φ = tanh²(k h) / (1 + 2 k h / sinh(2 k h))
/// ```
///
/// (Kitaigorodskii, Krasitskii & Zaslavskii 1975; Hughes 1984), with k = k(ω, h) from the
/// gravity-wave dispersion ω² = g k tanh(k h). Tends to 1 in deep water and to ½(k h)² in
/// shallow water.
pub(crate) fn kitaigorodskii_kh<M: Math>(kh: f64) -> f64 {
    if kh.is_nan() || kh <= 0.0 {
        return 0.0;
    }
    if kh > 20.0 {
        // tanh²(20) = 1 − 2e-17 and 40/sinh(40) ~ 1e-16: 1 to f64 precision.
        return 1.0;
    }
    let t = M::tanh(kh);
    // 2kh / sinh(2kh) underflows gracefully to 0 for large kh (sinh → ∞).
    let x = 2.0 * kh;
    let ratio = if x < 1e-4 {
        1.0 - x * x / 6.0
    } else {
        x / M::sinh(x)
    };
    t * t / (1.0 + ratio)
}

/// Kitaigorodskii's Φ(ω, h): solves k from ω² = g k tanh(k h) by Newton, then
/// [`kitaigorodskii_kh`].
pub(crate) fn kitaigorodskii<M: Math>(omega: f64, depth: f64) -> f64 {
    let k = Dispersion::FiniteDepth {
        depth: depth as f32,
    }
    .k_from_omega_with::<M>(omega);
    kitaigorodskii_kh::<M>(k * depth)
}

/// Thompson & Vincent's (1983) piecewise approximation of Φ with ω_h = ω √(h/g):
///
/// ```text
/// Φ ≈ ½ ω_h²             ω_h ≤ 1
///     1 − ½ (2 − ω_h)²   1 < ω_h < 2
///     1                  ω_h ≥ 2
/// ```
pub(crate) fn thompson_vincent(omega: f64, depth: f64) -> f64 {
    if omega.is_nan() || omega <= 0.0 {
        return 0.0;
    }
    let omega_h = omega * (depth / G).sqrt();
    if omega_h <= 1.0 {
        0.5 * omega_h * omega_h
    } else if omega_h < 2.0 {
        let d = 2.0 - omega_h;
        1.0 - 0.5 * d * d
    } else {
        1.0
    }
}

/// Omnidirectional Phillips wave-number spectrum in m³ (Tessendorf 2001, eq. 40, with the
/// angular factor |k̂·ŵ|² integrated over direction, ∫cos²θ dθ = π):
///
/// ```text
/// S(k) = π A exp(−1/(k L_w)²) / k³,   L_w = U² / g
/// ```
///
/// so that S(k)/k · cos²θ/π is Tessendorf's A exp(−1/(kL)²)/k⁴ |k̂·ŵ|².
pub(crate) fn phillips_omni<M: Math>(k: f64, amplitude: f64, wind_length: f64) -> f64 {
    if k.is_nan() || k <= 0.0 {
        return 0.0;
    }
    let u = 1.0 / (k * wind_length);
    let exponent = -u * u;
    if exponent < -700.0 {
        return 0.0;
    }
    std::f64::consts::PI * amplitude * M::exp(exponent) / (k * k * k)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::determinism::Std;

    #[test]
    fn jonswap_is_zero_and_finite_at_the_ends() {
        assert_eq!(jonswap::<Std>(0.0, 0.01, 1.0, 3.3), 0.0);
        assert_eq!(jonswap::<Std>(-1.0, 0.01, 1.0, 3.3), 0.0);
        assert_eq!(jonswap::<Std>(1e-3, 0.01, 1.0, 3.3), 0.0);
        let far = jonswap::<Std>(1e6, 0.01, 1.0, 3.3);
        assert!(far.is_finite() && far > 0.0);
    }

    #[test]
    fn kitaigorodskii_small_kh_branch_is_continuous() {
        let below = kitaigorodskii_kh::<Std>(0.49999e-4);
        let above = kitaigorodskii_kh::<Std>(0.50001e-4);
        assert!((below / above - 1.0).abs() < 1e-3);
        assert_eq!(kitaigorodskii_kh::<Std>(1e4), 1.0);
    }
}
