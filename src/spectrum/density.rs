//! Evaluation of a [`Spectrum`]: S(ω), D(ω, θ) and S(k), infallible and NaN-free.

use super::elfouhaily;
use super::omega;
use super::spreading::Shape;
use super::spreading::SpreadingParams;
use super::{wrap_angle, DepthFactor, Model, Spectrum};
use crate::error::saturate;
use crate::math::determinism::{Math, Std};
use crate::spectrum::dispersion::Dispersion;

impl Spectrum {
    /// Non-directional spectrum S(ω) in m²·s/rad at angular frequency `omega` in rad/s,
    /// including the depth factor. 0 for ω ≤ 0 and for non-finite ω (outside the domain);
    /// values beyond `f32::MAX` saturate there.
    pub fn omega_spectrum(&self, omega: f32) -> f32 {
        saturate(self.omega_spectrum_f64::<Std>(f64::from(omega)))
    }

    fn omega_spectrum_f64<M: Math>(&self, omega: f64) -> f64 {
        if !omega.is_finite() || omega <= 0.0 {
            return 0.0;
        }
        match self.model {
            Model::Jonswap { .. } => {
                self.jonswap_shape::<M>(omega) * self.depth_factor_at::<M>(omega, None)
            }
            Model::Phillips { .. } | Model::Elfouhaily { .. } => {
                // S(ω) = S(k) dk/dω with k = k(ω) of this spectrum's dispersion.
                let k = self.dispersion.k_from_omega_with::<M>(omega);
                let group = self.dispersion.d_omega_dk_with::<M>(k);
                if !(group > 0.0 && group.is_finite()) {
                    return 0.0;
                }
                self.k_model_omni::<M>(k) / group
            }
        }
    }

    /// The depth factor Φ at `omega`; `k`, when given, is ω's wave number under this
    /// spectrum's dispersion.
    fn depth_factor_at<M: Math>(&self, omega: f64, k: Option<f64>) -> f64 {
        let Some(h) = self.dispersion.depth().map(f64::from) else {
            return 1.0;
        };
        match self.depth_factor {
            DepthFactor::None => 1.0,
            DepthFactor::ThompsonVincent => omega::thompson_vincent(omega, h),
            // With finite-depth dispersion a known k is the gravity-wave k(ω, h), so the exact
            // factor needs no Newton solve. With capillary dispersion the gravity k is solved
            // for: the capillary correction matters only where Φ = 1 already.
            DepthFactor::Kitaigorodskii => match (k, self.dispersion) {
                (Some(k), Dispersion::FiniteDepth { .. }) => omega::kitaigorodskii_kh::<M>(k * h),
                _ => omega::kitaigorodskii::<M>(omega, h),
            },
        }
    }

    fn jonswap_shape<M: Math>(&self, omega: f64) -> f64 {
        match self.model {
            Model::Jonswap {
                alpha,
                peak_omega,
                gamma,
            } => omega::jonswap::<M>(
                omega,
                f64::from(alpha),
                f64::from(peak_omega),
                f64::from(gamma),
            ),
            _ => 0.0,
        }
    }

    /// The omnidirectional S(k) of the models defined on k (0 for JONSWAP).
    fn k_model_omni<M: Math>(&self, k: f64) -> f64 {
        match self.model {
            Model::Phillips { amplitude } => {
                omega::phillips_omni::<M>(k, f64::from(amplitude), self.wind_length())
            }
            Model::Elfouhaily { inverse_wave_age } => {
                elfouhaily::omni::<M>(k, f64::from(self.wind_speed), f64::from(inverse_wave_age))
            }
            Model::Jonswap { .. } => 0.0,
        }
    }

    /// Directional spreading D(ω, θ) in 1/rad at angular frequency `omega` in rad/s and
    /// direction `theta` in radians relative to the wind (any real angle; it is wrapped),
    /// including the swell and spread-blend controls. ∫_{−π}^{π} D dθ = 1. Outside the
    /// domain: 0 for a NaN or infinite `theta`; 1/(2π) (flat) for ω ≤ 0 or NaN.
    pub fn spreading(&self, omega: f32, theta: f32) -> f32 {
        if !theta.is_finite() {
            return 0.0;
        }
        saturate(
            self.spreading_params()
                .evaluate::<Std>(f64::from(omega), wrap_angle(f64::from(theta))),
        )
    }

    /// Directional wave-number spectrum S(k) in m⁴ at wave vector `k` = `[k_x, k_z]` in rad/m,
    /// including the short-wave fade:
    ///
    /// ```text
    /// S(k) = S(ω) · D(ω, θ) · (dω/dk) / k · e^{−k²ℓ²},   ω = ω(|k|), θ = atan2(k_z, k_x) − θ_w
    /// ```
    ///
    /// Its integral over the plane is the surface variance. 0 at k = 0 and for a wave vector
    /// with a NaN or infinite component (outside the domain); values beyond `f32::MAX`
    /// saturate there.
    pub fn density(&self, k: [f32; 2]) -> f32 {
        let (kx, kz) = (f64::from(k[0]), f64::from(k[1]));
        saturate(self.density_with::<Std>(kx, kz, &self.spreading_params()))
    }

    /// [`density`](Self::density) in f64 with the functions of `M`.
    pub(crate) fn density_with<M: Math>(
        &self,
        kx: f64,
        kz: f64,
        spreading: &SpreadingParams,
    ) -> f64 {
        let k = M::hypot(kx, kz);
        match self.radial_with::<M>(k, spreading) {
            Some(radial) => self.angular_with::<M>(&radial, kx, kz, spreading),
            None => 0.0,
        }
    }

    /// What S(k) needs from |k| = `k` alone (`None` where S is 0 for every direction): wave
    /// vectors of the same length share it, so a grid can compute it once per length.
    pub(crate) fn radial_with<M: Math>(
        &self,
        k: f64,
        spreading: &SpreadingParams,
    ) -> Option<Radial> {
        if !(k > 0.0 && k.is_finite()) {
            return None;
        }
        let omni = self.omni_k::<M>(k);
        if omni == 0.0 {
            return None;
        }
        let omega = self.dispersion.omega_with::<M>(k);
        Some(Radial {
            k,
            omni,
            shape: spreading.shape::<M>(omega, Some(k)),
        })
    }

    /// S(k) at wave vector (`kx`, `kz`) from its length's [`Radial`] part (the same value
    /// [`density_with`](Self::density_with) gives).
    pub(crate) fn angular_with<M: Math>(
        &self,
        radial: &Radial,
        kx: f64,
        kz: f64,
        spreading: &SpreadingParams,
    ) -> f64 {
        let theta = wrap_angle(M::atan2(kz, kx) - f64::from(self.wind_direction));
        radial.omni * spreading.angular::<M>(&radial.shape, theta) / radial.k
    }

    /// Omnidirectional wave-number spectrum ∫ S(k) k dθ in m³ at |k| = `k`, with the fade.
    pub(super) fn omni_k<M: Math>(&self, k: f64) -> f64 {
        let fade = if self.short_wave_length > 0.0 {
            let l = f64::from(self.short_wave_length);
            M::exp(-(k * l) * (k * l))
        } else {
            1.0
        };
        if fade == 0.0 {
            return 0.0;
        }
        let value = match self.model {
            Model::Jonswap { .. } => {
                let omega = self.dispersion.omega_with::<M>(k);
                let group = self.dispersion.d_omega_dk_with::<M>(k);
                self.jonswap_shape::<M>(omega) * self.depth_factor_at::<M>(omega, Some(k)) * group
            }
            Model::Phillips { .. } | Model::Elfouhaily { .. } => self.k_model_omni::<M>(k),
        };
        value * fade
    }
}

/// The part of S(k) that depends only on |k| (see [`Spectrum::radial_with`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Radial {
    /// |k| in rad/m.
    pub(crate) k: f64,
    /// The omnidirectional spectrum at |k| with the fade, m³.
    omni: f64,
    /// The spreading at ω(|k|).
    shape: Shape,
}
