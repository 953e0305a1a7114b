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

use crate::determinism::Math;

/// The transport of an ocean's residual foam.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Transport {
    /// Drift `[x, z]` in m/s.
    pub(crate) drift: [f64; 2],
    /// Diffusion tensor (K_xx, K_xz, K_zz) in m²/s.
    pub(crate) tensor: [f64; 3],
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
            dk: TAU / length,
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
                let k = self.dk * f64::from(crate::grid::wave_index(i, n));
                // The phase reduced to whole turns first, so that long steps stay accurate.
                let turns = (dt * self.drift[axis] * k / TAU).rem_euclid(1.0);
                let (s, c) = M::sin_cos(TAU * turns);
                *value = Complex32::new(c as f32, -s as f32);
            }
        }
    }

    /// The coefficients (a, b, c) of the Gaussian exponent −(a·m_x² + 2b·m_x·m_z + c·m_z²)
    /// over `dt` seconds, in grid wave indices m: a = dt·K_xx·Δk² and so on.
    pub(crate) fn exponent(&self, dt: f64) -> [f32; 3] {
        let scale = dt * self.dk * self.dk;
        self.tensor.map(|k| (scale * k) as f32)
    }
}

#[cfg(test)]
// The test checks the tensor against the standard library's sine and cosine.
#[allow(clippy::disallowed_methods)]
mod tests {
    use super::*;
    use crate::determinism::Std;

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
}
