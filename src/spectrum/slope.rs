//! The slope variance a [`Spectrum`] holds over a band of wave numbers, along and across the
//! wind, by quadrature.

use super::Spectrum;
use crate::error::saturate;
use crate::math::determinism::{Math, Std};

/// Variance of the surface slope along and across the wind, dimensionless: ⟨(∂η/∂x')²⟩ and
/// ⟨(∂η/∂z')²⟩ in a frame whose x' axis points where the wind blows. Their sum is the
/// mean-square slope that Cox & Munk (1954) measured from sun glitter, and what a
/// microfacet BRDF takes as roughness (σ² of the facet slopes; Bruneton, Neyret &
/// Holzschuch 2010).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SlopeVariance {
    /// Slope variance along the wind (upwind–downwind), dimensionless.
    pub along: f32,
    /// Slope variance across the wind, dimensionless.
    pub across: f32,
}

impl SlopeVariance {
    /// Wave number in rad/m (a wavelength of 3.1 mm) up to which
    /// [`Cascade::subgrid_slope_variance`](crate::Cascade::subgrid_slope_variance) and the
    /// alpha channel of [`TexelLayout::Normal`](crate::gpu::TexelLayout::Normal) count sub-grid
    /// slopes: above it viscosity damps capillary waves within a fraction of a second, and
    /// the Elfouhaily spectrum holds less than 0.1 % of its slope variance there. The
    /// JONSWAP and Pierson–Moskowitz ω⁻⁵ tails have no such end (their slope variance grows
    /// with the logarithm of the cut-off), so for them this choice sets the roughness.
    pub const DEFAULT_CUTOFF: f32 = 2000.0;

    /// The mean-square slope `along + across`.
    pub fn total(&self) -> f32 {
        self.along + self.across
    }
}

impl Spectrum {
    /// Slope variance along and across the wind that the wave vectors with
    /// k_min ≤ |k| < k_max (rad/m) hold: ∫∫ (k·ŵ)² S(k) d²k and ∫∫ (k×ŵ)² S(k) d²k.
    ///
    /// Computed as ∫ k² S(k) m(k) dk and ∫ k² S(k) (1 − m(k)) dk over the omnidirectional
    /// spectrum S(k), with m(k) = ∫ cos²θ D(ω(k), θ) dθ the share along the wind (closed
    /// forms for every spreading but Donelan–Banner, whose m is a Simpson quadrature over θ),
    /// by composite Simpson quadrature in ln k with 100 nodes a decade. `k_max` may be +∞
    /// (the tails above 10⁶ k_p are left out); an empty or invalid band gives zero.
    ///
    /// The grid of a cascade holds its band's share; the rest, above the finest cascade's
    /// band, is what [`Cascade::subgrid_slope_variance`](crate::Cascade::subgrid_slope_variance)
    /// reports.
    pub fn slope_variance(&self, k_min: f32, k_max: f32) -> SlopeVariance {
        self.slope_variance_with::<Std>(f64::from(k_min), f64::from(k_max))
    }

    /// [`slope_variance`](Self::slope_variance) in f64 with the functions of `M`.
    pub(crate) fn slope_variance_with<M: Math>(&self, k_min: f64, k_max: f64) -> SlopeVariance {
        let zero = SlopeVariance::default();
        if k_min.is_nan() || k_max.is_nan() || k_max <= k_min {
            return zero;
        }
        let k_peak = self.peak_wave_number_with::<M>();
        let lo = k_min.max(1e-3 * k_peak);
        let hi = k_max.min(1e6 * k_peak);
        if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
            return zero;
        }
        let (a, b) = (M::ln(lo), M::ln(hi));
        let decades = (b - a) / std::f64::consts::LN_10;
        let intervals = ((decades * 100.0).ceil() as usize)
            .max(2)
            .next_multiple_of(2);
        let h = (b - a) / intervals as f64;
        let spreading = self.spreading_params();
        let (mut along, mut across) = (0.0, 0.0);
        for i in 0..=intervals {
            let weight = if i == 0 || i == intervals {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            let k = M::exp(a + i as f64 * h);
            // ∫ k² S(k) dk = ∫ k³ S(k) d(ln k).
            let value = self.omni_k::<M>(k) * k * k * k;
            if value == 0.0 {
                continue;
            }
            let m = spreading.cos2_moment::<M>(self.dispersion.omega_with::<M>(k), Some(k));
            along += weight * value * m;
            across += weight * value * (1.0 - m);
        }
        SlopeVariance {
            along: saturate(along * h / 3.0),
            across: saturate(across * h / 3.0),
        }
    }
}
