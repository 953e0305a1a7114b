//! The builder-style `with_*` setters of a [`Spectrum`]: each checks its value, so a spectrum
//! stays valid from construction on.

use super::{wrap_angle, DepthFactor, Model, Spectrum, Spreading};
use crate::error::{self, Error};
use crate::spectrum::dispersion::Dispersion;

impl Spectrum {
    /// Sets the JONSWAP peak enhancement γ (dimensionless, > 0; 1 gives Pierson–Moskowitz).
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] unless `gamma` is finite and > 0;
    /// [`Error::NotApplicable`] on a Phillips or Elfouhaily spectrum.
    #[must_use = "with_* returns the changed spectrum"]
    pub fn with_gamma(mut self, gamma: f32) -> Result<Self, Error> {
        let gamma = error::positive("gamma", gamma)?;
        match &mut self.model {
            Model::Jonswap { gamma: g, .. } => *g = gamma,
            Model::Phillips { .. } => {
                return Err(Error::NotApplicable {
                    name: "gamma",
                    reason: "the Phillips spectrum has no peak enhancement",
                })
            }
            Model::Elfouhaily { .. } => {
                return Err(Error::NotApplicable {
                    name: "gamma",
                    reason: "the Elfouhaily spectrum's peak enhancement follows from its \
                             inverse wave age",
                })
            }
        }
        Ok(self)
    }

    /// Sets the wind direction θ_w in radians: the direction the wind blows toward, as the
    /// angle of the unit vector (cos θ_w, sin θ_w) in (x, z). Waves travel downwind.
    /// Stored wrapped to [−π, π].
    ///
    /// # Errors
    /// [`Error::NonFinite`] unless `wind_direction` is finite.
    #[must_use = "with_* returns the changed spectrum"]
    pub fn with_wind_direction(mut self, wind_direction: f32) -> Result<Self, Error> {
        let theta = error::finite("wind_direction", wind_direction)?;
        self.wind_direction = wrap_angle(f64::from(theta)) as f32;
        Ok(self)
    }

    /// Sets the directional spreading.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for bad variant parameters (`s` ≤ 0,
    /// `exponent` < 0, `upwind` outside [0, 1]).
    #[must_use = "with_* returns the changed spectrum"]
    pub fn with_spreading(mut self, spreading: Spreading) -> Result<Self, Error> {
        self.spreading = spreading.validate()?;
        Ok(self)
    }

    /// Sets Horvath's (2015) swell parameter ξ in [0, 1]: it narrows the cos-2s family of
    /// spreadings, s += 16 tanh(ω_p/ω) ξ², so long waves line up as swell. No effect on other
    /// spreadings. Default 0.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] unless `swell` is in [0, 1].
    #[must_use = "with_* returns the changed spectrum"]
    pub fn with_swell(mut self, swell: f32) -> Result<Self, Error> {
        self.swell = error::unit_interval("swell", swell)?;
        Ok(self)
    }

    /// Sets Horvath's (2015) spread blend μ in [0, 1]: D = (1 − μ)/(2π) + μ D_spreading, from
    /// flat (0) to the chosen spreading (1, the default).
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] unless `spread_blend` is in [0, 1].
    #[must_use = "with_* returns the changed spectrum"]
    pub fn with_spread_blend(mut self, spread_blend: f32) -> Result<Self, Error> {
        self.spread_blend = error::unit_interval("spread_blend", spread_blend)?;
        Ok(self)
    }

    /// Sets the short-wave fade length ℓ in metres (≥ 0): S(k) is multiplied by e^{−k²ℓ²}
    /// (Tessendorf 2001, eq. 41). Default 0 (no fade).
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] unless `length` is finite and ≥ 0.
    #[must_use = "with_* returns the changed spectrum"]
    pub fn with_short_wave_length(mut self, length: f32) -> Result<Self, Error> {
        self.short_wave_length = error::non_negative("short_wave_length", length)?;
        Ok(self)
    }

    /// Sets the water depth h in metres: the dispersion becomes finite-depth (or stays
    /// capillary, at the new depth), and the depth factor, if any, uses h.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] unless `depth` is finite and > 0.
    #[must_use = "with_* returns the changed spectrum"]
    pub fn with_depth(mut self, depth: f32) -> Result<Self, Error> {
        let depth = error::positive("depth", depth)?;
        self.dispersion = match self.dispersion {
            Dispersion::Capillary { .. } => Dispersion::Capillary { depth },
            _ => Dispersion::FiniteDepth { depth },
        };
        Ok(self)
    }

    /// Sets the dispersion relation (deep, finite depth or capillary).
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for a depth that is not finite and > 0.
    #[must_use = "with_* returns the changed spectrum"]
    pub fn with_dispersion(mut self, dispersion: Dispersion) -> Result<Self, Error> {
        dispersion.validate()?;
        self.dispersion = dispersion;
        Ok(self)
    }

    /// Sets the shallow-water depth factor (used only at finite depth).
    ///
    /// # Errors
    /// [`Error::NotApplicable`] for a factor other than [`DepthFactor::None`] on a Phillips or
    /// Elfouhaily spectrum, which are defined on k directly.
    #[must_use = "with_* returns the changed spectrum"]
    pub fn with_depth_factor(mut self, depth_factor: DepthFactor) -> Result<Self, Error> {
        if !matches!(self.model, Model::Jonswap { .. }) && depth_factor != DepthFactor::None {
            return Err(Error::NotApplicable {
                name: "depth_factor",
                reason: "the Phillips and Elfouhaily spectra are defined on k and have no \
                         depth factor",
            });
        }
        self.depth_factor = depth_factor;
        Ok(self)
    }
}
