//! How residual foam moves over the foam grid: a downwind drift and a diffusion that is
//! strong along the wind and weak across it, applied exactly in Fourier space.
//!
//! On the periodic grid, ∂r/∂t = −u·∇r + ∇·(K∇r) with a constant drift u and a constant
//! diffusion tensor K = K∥ ŵŵᵀ + K⊥ n̂n̂ᵀ (ŵ the wind direction, n̂ across it) is diagonal in
//! Fourier space: over a step dt every wave vector k is multiplied by
//!
//! ```text
//! M(k) = exp(−dt kᵀK k) · exp(−i dt k·u)
//! ```
//!
//! Steps compose exactly (M of s + t is M of s times M of t), so one step of 2·dt moves foam
//! as two steps of dt do, for any dt, with no stability limit and no numerical diffusion. The
//! drift factor is separable in (k_x, k_z) and tabulated per step; the Gaussian factor is one
//! exponential per wave vector.

use std::f64::consts::TAU;

use num_complex::Complex32;

use crate::math::determinism::Math;

/// Largest exponent dt·K·Δk² of a diffusivity K over a step, per squared grid wave index along
/// its axis: capped there, every wave vector with a component of 0.01 index or more along that
/// axis is still damped to exactly 0 in f32 (by e^{−105} or less), as by any larger K, and the
/// exponent at the grid's corner, 2·(N/2)²·2²⁰ ≤ 2⁴³, stays finite.
const EXPONENT_LIMIT: f64 = 1_048_576.0;

/// The transport of an ocean's residual foam.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Transport {
    /// Drift `[x, z]` in m/s.
    pub(crate) drift: [f64; 2],
    /// Diffusion tensor (K_xx, K_xz, K_zz) in m²/s.
    pub(crate) tensor: [f64; 3],
    /// Its eigenvalues, the diffusivities (K∥, K⊥) along and across the wind, in m²/s.
    diffusivities: [f64; 2],
    /// The wind direction ŵ = (cos θ_w, sin θ_w), its eigenvector of K∥.
    wind: [f64; 2],
    /// Δk = 2π/L of the grid, rad/m.
    dk: f64,
}

impl Transport {
    /// The transport for a drift of `drift` m/s along the wind direction `wind` (rad) and
    /// diffusivities `along` and `across` the wind (m²/s), on a grid of side `length` m, with
    /// the functions of `M`.
    pub(crate) fn new<M: Math>(
        wind: f64,
        drift: f64,
        along: f64,
        across: f64,
        length: f64,
    ) -> Self {
        let (sin, cos) = M::sin_cos(wind);
        Transport {
            drift: [drift * cos, drift * sin],
            tensor: [
                along * cos * cos + across * sin * sin,
                (along - across) * cos * sin,
                along * sin * sin + across * cos * cos,
            ],
            diffusivities: [along, across],
            wind: [cos, sin],
            dk: TAU / length,
        }
    }

    /// The transport (1 − w)·`self` + w·`other` (0 ≤ w ≤ 1): drift and tensor linear, the cap's
    /// diffusivities the larger of each pair and its axes those of the side weighted more.
    pub(crate) fn blend(&self, other: &Transport, w: f64) -> Transport {
        let lerp = |a: f64, b: f64| (1.0 - w) * a + w * b;
        Transport {
            drift: [0, 1].map(|i| lerp(self.drift[i], other.drift[i])),
            tensor: [0, 1, 2].map(|i| lerp(self.tensor[i], other.tensor[i])),
            diffusivities: [0, 1].map(|i| self.diffusivities[i].max(other.diffusivities[i])),
            wind: if w < 0.5 { self.wind } else { other.wind },
            dk: self.dk,
        }
    }

    /// Whether foam moves at all.
    pub(crate) fn is_active(&self) -> bool {
        self.drift.iter().chain(&self.tensor).any(|&v| v != 0.0)
    }

    /// The drift factors over `dt` seconds on an N grid: `tables[..N]` holds
    /// exp(−i dt u_x k_x) for k_x = Δk·m(i), `tables[N..2N]` the same for z, with the
    /// functions of `M`.
    pub(crate) fn fill_tables<M: Math>(&self, dt: f64, n: usize, tables: &mut [Complex32]) {
        for (axis, table) in tables.chunks_mut(n).take(2).enumerate() {
            for (i, value) in table.iter_mut().enumerate() {
                let k = self.dk * f64::from(crate::math::grid::wave_index(i, n));
                // The phase reduced to whole turns first, so that long steps stay accurate.
                let turns = (dt * self.drift[axis] * k / TAU).rem_euclid(1.0);
                let (s, c) = M::sin_cos(TAU * turns);
                *value = Complex32::new(c as f32, -s as f32);
            }
        }
    }

    /// The coefficients (a, b, c) of the Gaussian exponent −(a·m_x² + 2b·m_x·m_z + c·m_z²)
    /// over `dt` seconds, in grid wave indices m: a = dt·K_xx·Δk² and so on, with each
    /// diffusivity's share at most [`EXPONENT_LIMIT`].
    pub(crate) fn exponent(&self, dt: f64) -> [f32; 3] {
        let scale = dt * self.dk * self.dk;
        let [along, across] = self.diffusivities;
        if scale * along.max(across) <= EXPONENT_LIMIT {
            return self.tensor.map(|k| (scale * k) as f32);
        }
        // A diffusivity so strong that its exponent would overflow f32 (and make ∞·0 = NaN at
        // m = 0): capped where it already damps everything along its axis to 0.
        let [cos, sin] = self.wind;
        let along = (scale * along).min(EXPONENT_LIMIT);
        let across = (scale * across).min(EXPONENT_LIMIT);
        [
            along * cos * cos + across * sin * sin,
            (along - across) * cos * sin,
            along * sin * sin + across * cos * cos,
        ]
        .map(|k| k as f32)
    }
}

#[cfg(test)]
// The test checks the tensor against the standard library's sine and cosine.
#[allow(clippy::disallowed_methods)]
mod tests {
    use super::*;
    use crate::math::determinism::Std;

    /// The tensor has the wind as a principal axis with K∥ along it and K⊥ across, and the
    /// drift points downwind, in every direction.
    #[test]
    fn tensor_and_drift_follow_the_wind() {
        for degree in (-180..180).step_by(7) {
            let theta = f64::from(degree).to_radians();
            let t = Transport::new::<Std>(theta, 0.3, 4.0, 0.5, 100.0);
            let (w, n) = ([theta.cos(), theta.sin()], [-theta.sin(), theta.cos()]);
            let form = |a: [f64; 2], b: [f64; 2]| {
                a[0] * t.tensor[0] * b[0]
                    + t.tensor[1] * (a[0] * b[1] + a[1] * b[0])
                    + a[1] * t.tensor[2] * b[1]
            };
            assert!((form(w, w) - 4.0).abs() < 1e-12);
            assert!((form(n, n) - 0.5).abs() < 1e-12);
            assert!(form(w, n).abs() < 1e-12);
            assert!((t.drift[0] - 0.3 * w[0]).abs() < 1e-12);
            assert!((t.drift[1] - 0.3 * w[1]).abs() < 1e-12);
        }
    }

    /// Diffusivities whose exponent overflows f32 (a peak wavelength of 6e41 m, from
    /// ω_p = 1e-20 rad/s) give finite coefficients: the exponent, evaluated as the step does,
    /// is 0 at m = 0 and beyond the exponential's range (87) at every other wave vector of a
    /// 64² grid.
    #[test]
    fn huge_diffusivities_give_a_finite_exponent() {
        for wind in [0.0, 0.7, -2.1] {
            let t = Transport::new::<Std>(wind, 0.3, 1e82, 1e79, 100.0);
            let [a, b, c] = t.exponent(0.5);
            assert!([a, b, c].iter().all(|v| v.is_finite()), "{:?}", [a, b, c]);
            for mx in -32i16..32 {
                for mz in -32i16..32 {
                    let (x, z) = (f32::from(mx), f32::from(mz));
                    let e = a * x * x + z * (2.0 * b * x + c * z);
                    if (mx, mz) == (0, 0) {
                        assert_eq!(e, 0.0);
                    } else {
                        assert!(e > 87.0, "{wind} ({mx}, {mz}): {e}");
                    }
                }
            }
        }
    }
}
