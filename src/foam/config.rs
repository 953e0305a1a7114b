//! [`FoamConfig`]: the passive parameters of the foam and their checks.

use std::ops::Bound::Included;

use crate::error::{self, Error};
use crate::spectrum::Spectrum;

/// How whitecaps form, age and move (see docs/theory.md, §15, and the guide's chapter
/// docs/guide/foam.md).
///
/// Waves break where the Jacobian J of the summed displacement of all cascades (at unit
/// choppiness) falls below a breaking threshold J_b. At every point of the foam grid
/// (cascade 0's) the breaking intensity s (1/s) follows from cascade 0's local Jacobian and the
/// statistics of the smaller cascades' waves, which the grid does not resolve. Active
/// whitecap foam a ∈ [0, 1] grows at s(1 − a) and turns into residual foam r ∈ [0, 1] with
/// time constant `active_decay`; residual foam decays with `residual_decay`:
///
/// ```text
/// da/dt = s (1 − a) − a/τ_A,     dr/dt = (a/τ_A)(1 − r) − r/τ_R
/// ```
///
/// Active foam stays where its wave broke (the grid follows the water's orbital motion);
/// residual foam is carried downwind at `drift`·U10 and spread along the wind
/// (`streak_length`) more than across it (`streak_width`), which draws it into streaks. J_b is
/// not a setting: it is calibrated from the statistics of the sea so that the active coverage
/// follows the whitecap fraction W = 3.84·10⁻⁶·U10^3.41 of Monahan & O'Muircheartaigh (1980),
/// times `coverage`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FoamConfig {
    /// Multiplier on the calibrated whitecap fraction, from 0 (no foam) to
    /// [`MAX_COVERAGE`](Self::MAX_COVERAGE) (default: `1.0`, Monahan & O'Muircheartaigh's
    /// fraction; targets are capped at half the surface).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::coverage")
    )]
    pub coverage: f32,
    /// Wind speed U10 in m/s that sets the whitecap fraction and the drift, from 0 to
    /// [`Spectrum::MAX_WIND_SPEED`] (default: `None`, the spectrum's
    /// [`wind_speed`](Spectrum::wind_speed); set it for a swell under a lighter local wind).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::wind_speed")
    )]
    pub wind_speed: Option<f32>,
    /// Lifetime τ_A of active whitecap foam in seconds, from [`MIN_DECAY`](Self::MIN_DECAY)
    /// to [`MAX_DECAY`](Self::MAX_DECAY) (default: `3.85`, the e-folding time of whitecap
    /// area measured by Monahan 1971).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::active_decay")
    )]
    pub active_decay: f32,
    /// Lifetime τ_R of residual foam in seconds, from [`MIN_DECAY`](Self::MIN_DECAY) to
    /// [`MAX_DECAY`](Self::MAX_DECAY) (default: `15.0`, a look setting: the thin foam and
    /// streaks left behind whitecaps).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::residual_decay")
    )]
    pub residual_decay: f32,
    /// Downwind drift of residual foam as a fraction of U10, from 0 to
    /// [`MAX_DRIFT`](Self::MAX_DRIFT) (default: `0.03`, the wind drift of the surface
    /// layer, about 3 % of the wind speed).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::drift")
    )]
    pub drift: f32,
    /// How far residual foam spreads along the wind over one `residual_decay`, as a fraction
    /// of the peak wavelength λ_p of the spectrum, from 0 to
    /// [`MAX_STREAK`](Self::MAX_STREAK): the RMS spread √(2K∥τ_R) of a patch, which sets the
    /// along-wind diffusivity K∥ (default: `1.0`, a look setting: streaks about one peak
    /// wavelength long, 61 m on the default sea, JONSWAP at 10 m/s over 100 km).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::streak_length")
    )]
    pub streak_length: f32,
    /// The same across the wind, from 0 to `streak_length` (default: `0.03`, a look setting:
    /// streaks far longer than wide, 1.8 m across on the default sea). The foam grid shows
    /// nothing narrower than its spacing L₀/N (3.9 m on the default ocean), so on most seas
    /// the grid, not this setting, sets how thin a streak looks.
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::streak_width")
    )]
    pub streak_width: f32,
}

impl Default for FoamConfig {
    fn default() -> Self {
        FoamConfig {
            coverage: 1.0,
            wind_speed: None,
            active_decay: 3.85,
            residual_decay: 15.0,
            drift: 0.03,
            streak_length: 1.0,
            streak_width: 0.03,
        }
    }
}

impl FoamConfig {
    /// Largest `coverage` multiplier.
    pub const MAX_COVERAGE: f32 = 100.0;
    /// Shortest `active_decay` and `residual_decay`, in seconds.
    pub const MIN_DECAY: f32 = 1e-3;
    /// Longest `active_decay` and `residual_decay`, in seconds (11.6 days).
    pub const MAX_DECAY: f32 = 1e6;
    /// Largest `drift`, as a fraction of U10.
    pub const MAX_DRIFT: f32 = 1.0;
    /// Largest `streak_length` (and so `streak_width`), in peak wavelengths.
    pub const MAX_STREAK: f32 = 10.0;

    /// Checks every field against the ranges their docs give. Within them the foam update
    /// stays finite and in [0, 1] for any surface and any step.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] naming `foam.coverage`,
    /// `foam.wind_speed`, `foam.active_decay`, `foam.residual_decay`,
    /// `foam.drift`, `foam.streak_length` or `foam.streak_width`.
    pub fn validate(&self) -> Result<(), Error> {
        let range = |name, value, max| error::in_range(name, value, Included(0.0), Included(max));
        range("foam.coverage", self.coverage, Self::MAX_COVERAGE)?;
        if let Some(wind) = self.wind_speed {
            range("foam.wind_speed", wind, Spectrum::MAX_WIND_SPEED)?;
        }
        let decay = |name, value| {
            error::in_range(
                name,
                value,
                Included(Self::MIN_DECAY),
                Included(Self::MAX_DECAY),
            )
        };
        decay("foam.active_decay", self.active_decay)?;
        decay("foam.residual_decay", self.residual_decay)?;
        range("foam.drift", self.drift, Self::MAX_DRIFT)?;
        range("foam.streak_length", self.streak_length, Self::MAX_STREAK)?;
        range("foam.streak_width", self.streak_width, self.streak_length)?;
        Ok(())
    }
}
