//! The variance a [`Spectrum`] carries over a band of wave numbers, and H_s, by quadrature.

use super::Spectrum;
use crate::error::saturate;
use crate::math::determinism::{Math, Std};

impl Spectrum {
    /// Variance of the surface elevation carried by the wave vectors with
    /// k_min ≤ |k| < k_max (rad/m), in m²: ∫∫ S(k) d²k over that annulus.
    ///
    /// Computed by composite Simpson quadrature in ln k of the omnidirectional spectrum (the
    /// spreading integrates to 1 over direction), 400 nodes a decade, relative error below
    /// 1e-6 for the spectra here. `k_max` may be +∞; an empty or invalid band gives 0.
    pub fn band_variance(&self, k_min: f32, k_max: f32) -> f32 {
        saturate(self.band_variance_f64(f64::from(k_min), f64::from(k_max)))
    }

    pub(crate) fn band_variance_f64(&self, k_min: f64, k_max: f64) -> f64 {
        if k_min.is_nan() || k_max.is_nan() || k_max <= k_min {
            return 0.0;
        }
        // The spectra vanish faster than any power below 1e-3 k_p and carry about 1e-12 of
        // their energy above 1e6 k_p (omnidirectional tails ∝ k⁻³ or steeper).
        // The peak is taken on k: Phillips is defined there, and its ω_p under a shallow
        // dispersion says nothing about where its energy lies.
        let k_peak = self.peak_wave_number_f64();
        let lo = k_min.max(1e-3 * k_peak);
        let hi = k_max.min(1e6 * k_peak);
        if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
            return 0.0;
        }
        let (a, b) = (Std::ln(lo), Std::ln(hi));
        let decades = (b - a) / std::f64::consts::LN_10;
        let intervals = ((decades * 400.0).ceil() as usize)
            .max(2)
            .next_multiple_of(2);
        let h = (b - a) / intervals as f64;
        let f = |u: f64| {
            let k = Std::exp(u);
            self.omni_k::<Std>(k) * k
        };
        let mut sum = f(a) + f(b);
        for i in 1..intervals {
            let weight = if i % 2 == 1 { 4.0 } else { 2.0 };
            sum += weight * f(a + i as f64 * h);
        }
        sum * h / 3.0
    }

    /// Significant wave height H_s = 4√m0 in metres, m0 the variance of the whole spectrum
    /// (with the short-wave fade) by quadrature.
    #[doc(alias = "Hs")]
    pub fn significant_wave_height(&self) -> f32 {
        saturate(4.0 * self.band_variance_f64(0.0, f64::INFINITY).sqrt())
    }
}
