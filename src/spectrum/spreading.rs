//! Directional spreading functions D(ω, θ), each normalised so that ∫_{−π}^{π} D dθ = 1.

use std::f64::consts::{LN_2, PI};
use std::ops::Bound::{Excluded, Included};

use crate::error::{self, Error};
use crate::math::determinism::Math;
#[cfg(feature = "serde")]
use crate::serde_impls::Float;

use super::elfouhaily;
use super::omega::G;

/// Directional spreading D(ω, θ) in 1/rad: how a frequency's energy is shared among the
/// directions θ relative to the wind.
///
/// Every variant is normalised so that ∫_{−π}^{π} D(ω, θ) dθ = 1 at every ω.
///
/// With the `serde` feature, deserialising checks the variant's parameters as
/// [`Spectrum::with_spreading`](crate::Spectrum::with_spreading) does.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(
        try_from = "crate::spectrum::spreading::SpreadingData",
        into = "crate::spectrum::spreading::SpreadingData"
    )
)]
#[non_exhaustive]
pub enum Spreading {
    /// Cos-2s with Mitsuyasu et al.'s (1975) frequency-dependent s:
    ///
    /// ```text
    /// s = s_p (ω/ω_p)^5  (ω ≤ ω_p),  s_p (ω/ω_p)^−2.5  (ω > ω_p),  s_p = 11.5 (ω_p U / g)^−2.5
    /// ```
    Mitsuyasu,
    /// Cos-2s with Hasselmann et al.'s (1980) frequency-dependent s:
    ///
    /// ```text
    /// s = 6.97 (ω/ω_p)^4.06  (ω ≤ ω_p),  9.77 (ω/ω_p)^(−2.33 − 1.45 (U ω_p / g − 1.17))  (ω > ω_p)
    /// ```
    Hasselmann,
    /// Cos-2s with a fixed spreading exponent `s` (larger is narrower).
    Cos2s {
        /// The exponent s of |cos(θ/2)|^{2s}, dimensionless, 0 < s ≤
        /// [`MAX_EXPONENT`](Spreading::MAX_EXPONENT).
        s: f32,
    },
    /// Donelan, Hamilton & Hui (1985) sech² spreading with Banner's (1990) extension above
    /// 1.6 ω_p: β/(2 tanh(βπ)) sech²(βθ).
    DonelanBanner,
    /// Energy in every direction alike: 1/(2π).
    Flat,
    /// Elfouhaily et al.'s (1997) centrosymmetric spreading (1 + Δ(k) cos 2θ)/(2π), with
    /// Δ(k) = tanh(ln 2/4 + 4 (c/c_p)^2.5 + 0.13 (u*/c_m) (c_m/c)^2.5): c(k) the phase speed
    /// of ω² = g k (1 + (k/k_m)²), k_m = 370 rad/m, c_m = 0.23 m/s, c_p that of the peak and
    /// u* the friction velocity of the wind (Wu's 1982 drag law). Nearly cos²θ/π at the peak
    /// (Δ → 1), broadening toward the short gravity waves and narrowing again near k_m. The
    /// default of [`Spectrum::elfouhaily`](crate::Spectrum::elfouhaily); usable with any
    /// spectrum (k is taken from ω under that dispersion). Like the paper's, it puts equal
    /// energy upwind and downwind.
    Elfouhaily,
    /// (2/π) cos²θ for |θ| < π/2 and 0 upwind.
    Cos2,
    /// |cos θ|^p with upwind waves (|θ| > π/2) scaled by `upwind`: Tessendorf's (2001) Phillips
    /// angular factor |k̂·ŵ|^p, with his damping of waves moving against the wind.
    /// `Cosine { exponent: 2.0, upwind: 1.0 }` is the classic two-way |k̂·ŵ|².
    Cosine {
        /// The exponent p, dimensionless, 0 ≤ p ≤ [`MAX_EXPONENT`](Spreading::MAX_EXPONENT).
        exponent: f32,
        /// Energy of upwind waves relative to downwind ones, in [0, 1].
        upwind: f32,
    },
}

impl Spreading {
    /// Largest accepted cos-2s exponent s and cosine exponent p (dimensionless): at s = 1e4
    /// the spreading falls to half power 0.95° either side of the wind, and its normalisation
    /// is still far from overflowing.
    pub const MAX_EXPONENT: f32 = 1e4;

    /// Checks the variant's parameters.
    pub(crate) fn validate(self) -> Result<Self, Error> {
        let max = Included(Self::MAX_EXPONENT);
        match self {
            Spreading::Cos2s { s } => {
                error::in_range("s", s, Excluded(0.0), max)?;
            }
            Spreading::Cosine { exponent, upwind } => {
                error::in_range("exponent", exponent, Included(0.0), max)?;
                error::unit_interval("upwind", upwind)?;
            }
            _ => {}
        }
        Ok(self)
    }

    /// The cos-2s exponent s at `omega` for the cos-2s family, `None` for the other variants.
    /// `peak_omega` in rad/s, `wind_speed` in m/s.
    pub(crate) fn cos_2s_exponent<M: Math>(
        self,
        omega: f64,
        peak_omega: f64,
        wind_speed: f64,
    ) -> Option<f64> {
        let r = omega / peak_omega;
        match self {
            Spreading::Mitsuyasu => {
                let s_p = 11.5 * M::powf(peak_omega * wind_speed / G, -2.5);
                Some(if r <= 1.0 {
                    s_p * M::powi(r, 5)
                } else {
                    s_p * M::powf(r, -2.5)
                })
            }
            Spreading::Hasselmann => Some(if r <= 1.0 {
                6.97 * M::powf(r, 4.06)
            } else {
                let exponent = -2.33 - 1.45 * (wind_speed * peak_omega / G - 1.17);
                9.77 * M::powf(r, exponent)
            }),
            Spreading::Cos2s { s } => Some(f64::from(s)),
            _ => None,
        }
    }
}

/// Parameters that the spreading functions share, in f64.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SpreadingParams {
    pub spreading: Spreading,
    pub peak_omega: f64,
    pub wind_speed: f64,
    /// Horvath's swell ξ in [0, 1].
    pub swell: f64,
    /// Horvath's spread blend μ in [0, 1].
    pub spread_blend: f64,
}

/// The direction-independent part of a spreading function at one frequency (see
/// [`SpreadingParams::shape`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Shape {
    /// No spreading at all (spread blend 0): D = 1/(2π) exactly.
    Flat,
    /// A shape with nothing to prepare that is uniform: 1/(2π), then blended.
    Uniform,
    /// cos-2s with its exponent and normalisation Q(s).
    Cos2s { s: f64, norm: f64 },
    /// Donelan–Banner with its β and normalisation β/(2 tanh(βπ)).
    DonelanBanner { beta: f64, norm: f64 },
    /// (2/π) cos²θ downwind.
    Cos2,
    /// |cos θ|^p with the upwind weight and the half-plane integral.
    Cosine {
        exponent: f64,
        upwind: f64,
        half: f64,
    },
    /// Elfouhaily with its Δ.
    Elfouhaily { delta: f64 },
}

impl SpreadingParams {
    /// D(ω, θ) in 1/rad, θ relative to the wind and already wrapped to [−π, π].
    pub(crate) fn evaluate<M: Math>(&self, omega: f64, theta: f64) -> f64 {
        self.evaluate_at::<M>(omega, None, theta)
    }

    /// D at ω and, when known, the wave number `k` of ω (the Elfouhaily spreading is a
    /// function of k; without it k is solved from ω under its own dispersion).
    pub(crate) fn evaluate_at<M: Math>(&self, omega: f64, k: Option<f64>, theta: f64) -> f64 {
        self.angular::<M>(&self.shape::<M>(omega, k), theta)
    }

    /// What D at ω (and `k`) needs that does not depend on the direction: every wave vector of
    /// the same length shares it.
    pub(crate) fn shape<M: Math>(&self, omega: f64, k: Option<f64>) -> Shape {
        if self.spread_blend == 0.0 {
            return Shape::Flat;
        }
        if omega.is_nan() || omega <= 0.0 {
            return Shape::Uniform;
        }
        if let Some(s) =
            self.spreading
                .cos_2s_exponent::<M>(omega, self.peak_omega, self.wind_speed)
        {
            // Horvath (2015) §5.2: swell narrows the spreading, s += 16 tanh(ω_p/ω) ξ².
            let s = s + 16.0 * M::tanh(self.peak_omega / omega) * self.swell * self.swell;
            return Shape::Cos2s {
                s,
                norm: cos_2s_norm::<M>(s),
            };
        }
        match self.spreading {
            Spreading::DonelanBanner => {
                let beta = donelan_banner_beta::<M>(omega / self.peak_omega);
                Shape::DonelanBanner {
                    beta,
                    norm: donelan_banner_norm::<M>(beta),
                }
            }
            Spreading::Cos2 => Shape::Cos2,
            Spreading::Cosine { exponent, upwind } => Shape::Cosine {
                exponent: f64::from(exponent),
                upwind: f64::from(upwind),
                half: cosine_half::<M>(f64::from(exponent)),
            },
            Spreading::Elfouhaily => Shape::Elfouhaily {
                delta: self.elfouhaily_delta::<M>(omega, k),
            },
            _ => Shape::Uniform,
        }
    }

    /// D in 1/rad at θ (relative to the wind, in [−π, π]) for a frequency whose
    /// [`shape`](Self::shape) is `shape`.
    pub(crate) fn angular<M: Math>(&self, shape: &Shape, theta: f64) -> f64 {
        let flat = 1.0 / (2.0 * PI);
        let d = match *shape {
            Shape::Flat => return flat,
            Shape::Uniform => 1.0 / (2.0 * PI),
            Shape::Cos2s { s, norm } => norm * M::powf(M::cos(0.5 * theta).abs(), 2.0 * s),
            Shape::DonelanBanner { beta, norm } => {
                let sech = 1.0 / M::cosh(beta * theta);
                norm * sech * sech
            }
            Shape::Cos2 => {
                if theta.abs() < 0.5 * PI {
                    let c = M::cos(theta);
                    2.0 / PI * c * c
                } else {
                    0.0
                }
            }
            Shape::Cosine {
                exponent,
                upwind,
                half,
            } => cosine_power_with::<M>(exponent, upwind, half, theta),
            Shape::Elfouhaily { delta } => (1.0 + delta * M::cos(2.0 * theta)) / (2.0 * PI),
        };
        flat + self.spread_blend * (d - flat)
    }

    /// The Elfouhaily Δ at ω (or at `k` when given).
    fn elfouhaily_delta<M: Math>(&self, omega: f64, k: Option<f64>) -> f64 {
        let k = k.unwrap_or_else(|| elfouhaily::wave_number::<M>(omega));
        let k_p = elfouhaily::wave_number::<M>(self.peak_omega);
        elfouhaily::delta::<M>(k, k_p, self.wind_speed)
    }

    /// ∫_{−π}^{π} cos²θ D(ω, θ) dθ: the share of a frequency's slope variance that lies
    /// along the wind (the rest, 1 − this, lies across it). Closed forms where they exist
    /// (cos-2s: E[cos 2θ] = s(s − 1)/((s + 1)(s + 2)); |cos θ|^p: (p + 1)/(p + 2) on either
    /// lobe; Elfouhaily: ½ + Δ/4; flat: ½), composite Simpson over θ for Donelan–Banner.
    pub(crate) fn cos2_moment<M: Math>(&self, omega: f64, k: Option<f64>) -> f64 {
        let flat = 0.5;
        if self.spread_blend == 0.0 {
            return flat;
        }
        let shaped = self.shaped_cos2_moment::<M>(omega, k);
        flat + self.spread_blend * (shaped - flat)
    }

    fn shaped_cos2_moment<M: Math>(&self, omega: f64, k: Option<f64>) -> f64 {
        if omega.is_nan() || omega <= 0.0 {
            return 0.5;
        }
        if let Some(s) =
            self.spreading
                .cos_2s_exponent::<M>(omega, self.peak_omega, self.wind_speed)
        {
            let s = s + 16.0 * M::tanh(self.peak_omega / omega) * self.swell * self.swell;
            // E[cos 2θ] = Γ(s+1)² / (Γ(s−1)Γ(s+3)) = s(s − 1)/((s + 1)(s + 2)).
            let cos_2theta = s * (s - 1.0) / ((s + 1.0) * (s + 2.0));
            return 0.5 * (1.0 + cos_2theta);
        }
        match self.spreading {
            Spreading::DonelanBanner => {
                // Even in θ: twice the integral over [0, π], Simpson with 64 intervals
                // (h = π/64; with β ≤ 2.61 the fourth derivative of cos²θ sech²(βθ) stays
                // below ~10³, so the error h⁴/180·π·max|f⁗| is below 1e-4).
                let r = omega / self.peak_omega;
                simpson(0.0, PI, 64, |theta| {
                    let c = M::cos(theta);
                    2.0 * c * c * donelan_banner::<M>(r, theta)
                })
            }
            Spreading::Cos2 => 0.75,
            Spreading::Cosine { exponent, .. } => {
                let p = f64::from(exponent);
                (p + 1.0) / (p + 2.0)
            }
            Spreading::Elfouhaily => 0.5 + 0.25 * self.elfouhaily_delta::<M>(omega, k),
            _ => 0.5,
        }
    }
}

/// Composite Simpson rule of `f` over [a, b] with `intervals` (even) intervals.
pub(crate) fn simpson(a: f64, b: f64, intervals: usize, f: impl Fn(f64) -> f64) -> f64 {
    let h = (b - a) / intervals as f64;
    let mut sum = f(a) + f(b);
    for i in 1..intervals {
        let weight = if i % 2 == 1 { 4.0 } else { 2.0 };
        sum += weight * f(a + i as f64 * h);
    }
    sum * h / 3.0
}

/// Normalisation Q(s) of the cos-2s spreading, computed exactly with log-gamma:
///
/// ```text
/// Q(s) = 2^{2s−1} Γ(s+1)² / (π Γ(2s+1))
/// ```
///
/// (Longuet-Higgins, Cartwright & Smith 1963; Mitsuyasu et al. 1975.)
pub(crate) fn cos_2s_norm<M: Math>(s: f64) -> f64 {
    M::exp(
        (2.0 * s - 1.0) * LN_2 + 2.0 * ln_gamma::<M>(s + 1.0)
            - M::ln(PI)
            - ln_gamma::<M>(2.0 * s + 1.0),
    )
}

/// Donelan–Banner β as a function of r = ω/ω_p (Donelan, Hamilton & Hui 1985; Banner 1990):
///
/// ```text
/// β = 2.61 r^1.3                                  r < 0.95 (used below 0.56 too)
///     2.28 r^−1.3                                 0.95 ≤ r < 1.6
///     10^(−0.4 + 0.8393 exp(−0.567 ln(r²)))       r ≥ 1.6
/// ```
pub(crate) fn donelan_banner_beta<M: Math>(r: f64) -> f64 {
    if r < 0.95 {
        2.61 * M::powf(r, 1.3)
    } else if r < 1.6 {
        2.28 * M::powf(r, -1.3)
    } else {
        M::powf(10f64, -0.4 + 0.8393 * M::exp(-0.567 * M::ln(r * r)))
    }
}

/// β/(2 tanh(βπ)) sech²(βθ).
pub(crate) fn donelan_banner<M: Math>(r: f64, theta: f64) -> f64 {
    let beta = donelan_banner_beta::<M>(r);
    let norm = donelan_banner_norm::<M>(beta);
    let sech = 1.0 / M::cosh(beta * theta);
    norm * sech * sech
}

/// β/(2 tanh(βπ)), the Donelan–Banner normalisation.
fn donelan_banner_norm<M: Math>(beta: f64) -> f64 {
    // β → 0 (r → 0): the limit is flat, 1/(2π); avoid 0/0.
    if beta < 1e-8 {
        1.0 / (2.0 * PI)
    } else {
        beta / (2.0 * M::tanh(beta * PI))
    }
}

/// ∫_{−π/2}^{π/2} cos^p θ dθ = √π Γ((p+1)/2) / Γ(p/2 + 1).
fn cosine_half<M: Math>(exponent: f64) -> f64 {
    M::exp(
        0.5 * M::ln(PI) + ln_gamma::<M>(0.5 * (exponent + 1.0))
            - ln_gamma::<M>(0.5 * exponent + 1.0),
    )
}

/// |cos θ|^p, upwind half scaled by `upwind`, normalised over [−π, π], with the half-plane
/// integral `half` ([`cosine_half`]) already computed.
fn cosine_power_with<M: Math>(exponent: f64, upwind: f64, half: f64, theta: f64) -> f64 {
    let c = M::cos(theta);
    let weight = if c >= 0.0 { 1.0 } else { upwind };
    if weight == 0.0 {
        return 0.0;
    }
    weight * M::powf(c.abs(), exponent) / ((1.0 + upwind) * half)
}

/// ln Γ(x) for x > 0 by the Lanczos approximation (Lanczos 1964) with g = 7 and nine
/// coefficients, relative error below 1e-14 over the range used here (x ≥ 0.5).
pub(crate) fn ln_gamma<M: Math>(x: f64) -> f64 {
    const COEFFICIENTS: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // Reflection: Γ(x) Γ(1 − x) = π / sin(πx).
        return M::ln(PI / M::sin(PI * x)) - ln_gamma::<M>(1.0 - x);
    }
    let x = x - 1.0;
    let mut sum = COEFFICIENTS[0];
    for (i, &c) in COEFFICIENTS.iter().enumerate().skip(1) {
        sum += c / (x + i as f64);
    }
    let t = x + 7.5;
    0.5 * M::ln(2.0 * PI) + (x + 0.5) * M::ln(t) - t + M::ln(sum)
}

/// The serialised form of [`Spreading`], checked by `TryFrom` on the way in.
#[cfg(feature = "serde")]
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(rename = "Spreading")]
pub(crate) enum SpreadingData {
    Mitsuyasu,
    Hasselmann,
    Cos2s { s: Float },
    DonelanBanner,
    Flat,
    Cos2,
    Cosine { exponent: Float, upwind: Float },
    Elfouhaily,
}

#[cfg(feature = "serde")]
impl From<Spreading> for SpreadingData {
    fn from(spreading: Spreading) -> Self {
        match spreading {
            Spreading::Mitsuyasu => SpreadingData::Mitsuyasu,
            Spreading::Hasselmann => SpreadingData::Hasselmann,
            Spreading::Cos2s { s } => SpreadingData::Cos2s { s: s.into() },
            Spreading::DonelanBanner => SpreadingData::DonelanBanner,
            Spreading::Flat => SpreadingData::Flat,
            Spreading::Elfouhaily => SpreadingData::Elfouhaily,
            Spreading::Cos2 => SpreadingData::Cos2,
            Spreading::Cosine { exponent, upwind } => SpreadingData::Cosine {
                exponent: exponent.into(),
                upwind: upwind.into(),
            },
        }
    }
}

#[cfg(feature = "serde")]
impl TryFrom<SpreadingData> for Spreading {
    type Error = Error;

    fn try_from(data: SpreadingData) -> Result<Self, Error> {
        match data {
            SpreadingData::Mitsuyasu => Spreading::Mitsuyasu,
            SpreadingData::Hasselmann => Spreading::Hasselmann,
            SpreadingData::Cos2s { s } => Spreading::Cos2s { s: s.0 },
            SpreadingData::DonelanBanner => Spreading::DonelanBanner,
            SpreadingData::Flat => Spreading::Flat,
            SpreadingData::Elfouhaily => Spreading::Elfouhaily,
            SpreadingData::Cos2 => Spreading::Cos2,
            SpreadingData::Cosine { exponent, upwind } => Spreading::Cosine {
                exponent: exponent.0,
                upwind: upwind.0,
            },
        }
        .validate()
    }
}

#[cfg(test)]
// References in the standard library\'s maths: tests are not simulation code.
#[allow(clippy::disallowed_methods)]
mod tests {
    use super::*;
    use crate::math::determinism::Std;

    #[test]
    fn ln_gamma_matches_factorials_and_half_integers() {
        let mut factorial = 1.0_f64;
        for n in 1..=30 {
            // Γ(n) = (n − 1)!
            let expected = factorial.ln();
            assert!(
                (ln_gamma::<Std>(n as f64) - expected).abs() <= 1e-13 * expected.abs().max(1.0),
                "n = {n}"
            );
            factorial *= n as f64;
        }
        // Γ(1/2) = √π, Γ(3/2) = √π/2, Γ(5/2) = 3√π/4.
        let sqrt_pi = PI.sqrt();
        for (x, g) in [(0.5, sqrt_pi), (1.5, 0.5 * sqrt_pi), (2.5, 0.75 * sqrt_pi)] {
            assert!((ln_gamma::<Std>(x) - g.ln()).abs() < 1e-14, "x = {x}");
        }
        // Reflection branch: Γ(0.25) = 3.625609908221908...
        assert!((ln_gamma::<Std>(0.25) - 3.625_609_908_221_908_f64.ln()).abs() < 1e-13);
    }

    #[test]
    fn cos_2s_norm_closed_forms() {
        // s = 1: Q = 2 Γ(2)² / (π Γ(3)) = 1/π; s = 2: 8·4/(π·24) = 4/(3π).
        assert!((cos_2s_norm::<Std>(1.0) - 1.0 / PI).abs() < 1e-14);
        assert!((cos_2s_norm::<Std>(2.0) - 4.0 / (3.0 * PI)).abs() < 1e-14);
        // s → 0: flat 1/(2π).
        assert!((cos_2s_norm::<Std>(0.0) - 0.5 / PI).abs() < 1e-14);
    }
}
