//! Dispersion relations ω(k) of surface gravity(-capillary) waves, their group-velocity
//! derivative dω/dk, and the inverse k(ω).

use crate::error::{self, saturate, Error};
use crate::math::determinism::{Math, Std};
#[cfg(feature = "serde")]
use crate::serde_impls::Float;

/// Gravitational acceleration g, in m/s².
pub const GRAVITY: f32 = 9.81;
/// Surface tension of sea water σ, in N/m (used by [`Dispersion::Capillary`]).
pub const SURFACE_TENSION: f32 = 0.074;
/// Density of water ρ, in kg/m³ (used by [`Dispersion::Capillary`]).
pub const WATER_DENSITY: f32 = 1000.0;

const G: f64 = GRAVITY as f64;
const TENSION: f64 = SURFACE_TENSION as f64 / WATER_DENSITY as f64;

/// The dispersion relation ω(k) linking a wave's angular frequency ω (rad/s) to its wave number
/// k = |k| (rad/m).
///
/// ```text
/// Deep                 ω² = g k
/// FiniteDepth { h }    ω² = g k tanh(k h)
/// Capillary   { h }    ω² = (g k + (σ/ρ) k³) tanh(k h),  σ = 0.074 N/m, ρ = 1000 kg/m³
/// ```
///
/// (Tessendorf 2001, "Simulating Ocean Water", §3.2; Horvath 2015, "Empirical directional wave
/// spectra for computer graphics", §4.) The variants' fields are public so that a value can be
/// matched on; build one with [`Dispersion::finite_depth`] or [`Dispersion::capillary`] to have
/// the depth checked. An unchecked depth that is not finite and positive is treated as deep
/// water, so evaluation never yields NaN. With the `serde` feature, deserialising checks the
/// depth as [`Dispersion::finite_depth`] does.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(
        try_from = "crate::spectrum::dispersion::DispersionData",
        into = "crate::spectrum::dispersion::DispersionData"
    )
)]
pub enum Dispersion {
    /// Deep water: ω = √(g k).
    #[default]
    Deep,
    /// Water of finite depth: ω = √(g k tanh(k h)).
    FiniteDepth {
        /// Water depth h, in metres.
        depth: f32,
    },
    /// Gravity-capillary waves on water of finite depth: ω = √((g k + (σ/ρ) k³) tanh(k h)).
    Capillary {
        /// Water depth h, in metres.
        depth: f32,
    },
}

impl Dispersion {
    /// Finite-depth dispersion for a water depth in metres.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] unless `depth` is finite and > 0.
    pub fn finite_depth(depth: f32) -> Result<Self, Error> {
        Ok(Dispersion::FiniteDepth {
            depth: error::positive("depth", depth)?,
        })
    }

    /// Gravity-capillary dispersion for a water depth in metres.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] unless `depth` is finite and > 0.
    pub fn capillary(depth: f32) -> Result<Self, Error> {
        Ok(Dispersion::Capillary {
            depth: error::positive("depth", depth)?,
        })
    }

    /// Water depth in metres, or `None` in deep water.
    pub fn depth(&self) -> Option<f32> {
        match *self {
            Dispersion::Deep => None,
            Dispersion::FiniteDepth { depth } | Dispersion::Capillary { depth } => {
                valid_depth(depth).map(|h| h as f32)
            }
        }
    }

    /// Checks that the depth of this dispersion, if any, is finite and > 0.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for a bad depth.
    pub fn validate(&self) -> Result<(), Error> {
        match *self {
            Dispersion::Deep => Ok(()),
            Dispersion::FiniteDepth { depth } | Dispersion::Capillary { depth } => {
                error::positive("depth", depth).map(|_| ())
            }
        }
    }

    /// Angular frequency ω(k) in rad/s of a wave of wave number `k` in rad/m, evaluated in
    /// f64.
    ///
    /// Outside the domain: 0 for k ≤ 0 or NaN. Values beyond `f32::MAX` (k = +∞) saturate
    /// there.
    #[inline]
    pub fn omega(&self, k: f32) -> f32 {
        saturate(self.omega_with::<Std>(f64::from(k)))
    }

    /// Derivative dω/dk in m/s (the group velocity) at wave number `k` in rad/m.
    ///
    /// ```text
    /// Deep         dω/dk = g / (2ω)
    /// FiniteDepth  dω/dk = g (tanh(kh) + kh sech²(kh)) / (2ω)
    /// Capillary    dω/dk = ((g + 3(σ/ρ)k²) tanh(kh) + (g k + (σ/ρ)k³) h sech²(kh)) / (2ω)
    /// ```
    ///
    /// Evaluated in f64. At k ≤ 0 it returns the limit k → 0⁺ (√(g h) at finite depth, +∞
    /// in deep water) and at k = +∞ the limit k → ∞ (0 for gravity waves, +∞ for capillary
    /// ones); infinite values saturate at `f32::MAX`. NaN gives 0.
    #[inline]
    pub fn d_omega_dk(&self, k: f32) -> f32 {
        if k.is_nan() {
            return 0.0;
        }
        saturate(self.d_omega_dk_with::<Std>(f64::from(k)))
    }

    /// Wave number k in rad/m of the wave whose angular frequency is `omega` in rad/s: the
    /// inverse of [`omega`](Self::omega).
    ///
    /// Deep water has the closed form k = ω²/g; otherwise a safeguarded Newton iteration on
    /// the monotonic ω²(k) converges for every ω > 0 and depth > 0. Outside the domain: 0
    /// for ω ≤ 0 or NaN. Values beyond `f32::MAX` (ω = +∞) saturate there.
    pub fn k_from_omega(&self, omega: f32) -> f32 {
        saturate(self.k_from_omega_with::<Std>(f64::from(omega)))
    }

    /// [`omega`](Self::omega) in f64 with the functions of `M`.
    pub(crate) fn omega_with<M: Math>(&self, k: f64) -> f64 {
        if k.is_nan() || k <= 0.0 {
            return 0.0;
        }
        self.omega_squared::<M>(k).sqrt()
    }

    /// [`d_omega_dk`](Self::d_omega_dk) in f64 with the functions of `M`.
    pub(crate) fn d_omega_dk_with<M: Math>(&self, k: f64) -> f64 {
        let h = self.depth_f64();
        if k.is_nan() || k <= 0.0 {
            return match h {
                Some(h) => (G * h).sqrt(),
                None => f64::INFINITY,
            };
        }
        if k == f64::INFINITY {
            // The limits: g/(2ω) → 0 for gravity waves; capillary waves speed up as √k.
            return match self {
                Dispersion::Capillary { .. } => f64::INFINITY,
                _ => 0.0,
            };
        }
        let omega = self.omega_squared::<M>(k).sqrt();
        self.d_omega_squared::<M>(k) / (2.0 * omega)
    }

    /// [`k_from_omega`](Self::k_from_omega) in f64 with the functions of `M`.
    pub(crate) fn k_from_omega_with<M: Math>(&self, omega: f64) -> f64 {
        if omega.is_nan() || omega <= 0.0 {
            return 0.0;
        }
        if omega == f64::INFINITY {
            return f64::INFINITY;
        }
        let target = omega * omega;
        let deep_k = target / G;
        let h = match (self, self.depth_f64()) {
            (Dispersion::Deep, _) | (_, None) => return deep_k,
            (_, Some(h)) => h,
        };
        // Start from Fenton & McKee's (1990) explicit approximation for gravity waves,
        // k h ≈ y coth(y^{3/4})^{2/3} with y = ω² h / g, accurate to ~1.5 %.
        let y = deep_k * h;
        let guess = y * M::powf(1.0 / M::tanh(M::powf(y, 0.75)), 2.0 / 3.0) / h;
        // Bracket the root of f(k) = ω²(k) − ω², increasing in k, then polish with Newton
        // steps kept inside the bracket (bisection when a step leaves it).
        let f = |k: f64| self.omega_squared::<M>(k) - target;
        let (mut lo, mut hi) = (guess, guess);
        while f(lo) > 0.0 {
            lo *= 0.5;
        }
        while f(hi) < 0.0 {
            hi *= 2.0;
        }
        let mut k = guess.clamp(lo, hi);
        for _ in 0..200 {
            let fk = f(k);
            if fk == 0.0 {
                return k;
            }
            if fk < 0.0 {
                lo = k;
            } else {
                hi = k;
            }
            let step = fk / self.d_omega_squared::<M>(k);
            let mut next = k - step;
            if !(next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            }
            if (next - k).abs() <= 1e-15 * k || hi - lo <= 1e-15 * hi {
                return next;
            }
            k = next;
        }
        k
    }

    fn depth_f64(&self) -> Option<f64> {
        match *self {
            Dispersion::Deep => None,
            Dispersion::FiniteDepth { depth } | Dispersion::Capillary { depth } => {
                valid_depth(depth)
            }
        }
    }

    /// ω²(k) for k > 0.
    #[inline]
    fn omega_squared<M: Math>(&self, k: f64) -> f64 {
        let depth_term = self.depth_f64().map_or(1.0, |h| M::tanh(k * h));
        match self {
            Dispersion::Capillary { .. } => (G * k + TENSION * k * k * k) * depth_term,
            _ => G * k * depth_term,
        }
    }

    /// d(ω²)/dk for k > 0.
    #[inline]
    fn d_omega_squared<M: Math>(&self, k: f64) -> f64 {
        let (force, d_force) = match self {
            Dispersion::Capillary { .. } => {
                (G * k + TENSION * k * k * k, G + 3.0 * TENSION * k * k)
            }
            _ => (G * k, G),
        };
        match self.depth_f64() {
            None => d_force,
            Some(h) => {
                let kh = k * h;
                let sech = 1.0 / M::cosh(kh);
                d_force * M::tanh(kh) + force * h * sech * sech
            }
        }
    }
}

fn valid_depth(depth: f32) -> Option<f64> {
    (depth.is_finite() && depth > 0.0).then_some(f64::from(depth))
}

/// The serialised form of [`Dispersion`], checked by `TryFrom` on the way in.
#[cfg(feature = "serde")]
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(rename = "Dispersion")]
pub(crate) enum DispersionData {
    Deep,
    FiniteDepth { depth: Float },
    Capillary { depth: Float },
}

#[cfg(feature = "serde")]
impl From<Dispersion> for DispersionData {
    fn from(dispersion: Dispersion) -> Self {
        match dispersion {
            Dispersion::Deep => DispersionData::Deep,
            Dispersion::FiniteDepth { depth } => DispersionData::FiniteDepth {
                depth: depth.into(),
            },
            Dispersion::Capillary { depth } => DispersionData::Capillary {
                depth: depth.into(),
            },
        }
    }
}

#[cfg(feature = "serde")]
impl TryFrom<DispersionData> for Dispersion {
    type Error = Error;

    fn try_from(data: DispersionData) -> Result<Self, Error> {
        let dispersion = match data {
            DispersionData::Deep => Dispersion::Deep,
            DispersionData::FiniteDepth { depth } => Dispersion::FiniteDepth { depth: depth.0 },
            DispersionData::Capillary { depth } => Dispersion::Capillary { depth: depth.0 },
        };
        dispersion.validate()?;
        Ok(dispersion)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn newton_inverts_omega_everywhere() {
        for dispersion in [
            Dispersion::Deep,
            Dispersion::FiniteDepth { depth: 1e-3 },
            Dispersion::FiniteDepth { depth: 0.5 },
            Dispersion::FiniteDepth { depth: 20.0 },
            Dispersion::FiniteDepth { depth: 4000.0 },
            Dispersion::Capillary { depth: 0.01 },
            Dispersion::Capillary { depth: 100.0 },
        ] {
            let mut omega = 1e-4_f64;
            while omega < 1e3 {
                let k = dispersion.k_from_omega_with::<Std>(omega);
                assert!(k > 0.0 && k.is_finite(), "{dispersion:?} ω={omega}: k={k}");
                let back = dispersion.omega_with::<Std>(k);
                assert!(
                    ((back - omega) / omega).abs() < 1e-12,
                    "{dispersion:?} ω={omega}: k={k} gives ω={back}"
                );
                omega *= 1.37;
            }
        }
    }

    #[test]
    fn shallow_and_deep_limits() {
        // k h ≪ 1: ω ≈ k √(g h); k h ≫ 1: ω ≈ √(g k).
        let shallow = Dispersion::FiniteDepth { depth: 1.0 };
        let k = 1e-3;
        let expect = k * (G * 1.0).sqrt();
        assert!((shallow.omega_with::<Std>(k) / expect - 1.0).abs() < 1e-6);
        let deep = Dispersion::FiniteDepth { depth: 1000.0 };
        assert!((deep.omega_with::<Std>(1.0) / (G * 1.0).sqrt() - 1.0).abs() < 1e-12);
        assert_eq!(Dispersion::Deep.k_from_omega(0.0), 0.0);
        assert_eq!(Dispersion::Deep.omega(-1.0), 0.0);
        assert_eq!(Dispersion::Deep.omega(f32::NAN), 0.0);
    }
}
