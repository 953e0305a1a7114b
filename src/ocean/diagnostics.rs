//! What an ocean can say about itself ([`Diagnostics`]): how much of its sea the grids hold,
//! the largest choppiness, the loop's frequency error, the mean-level correction and the
//! expected variance. For tools, tests and settings screens; a game's frame reads none of it.

use crate::cascade::{Cascade, LoopError};

use super::fit::{self, SeaFit};
use super::OceanState;

/// The diagnostics of an ocean: what
/// [`OceanState::diagnostics`](crate::OceanState::diagnostics) returns. Borrows the ocean;
/// `Copy`.
///
/// ```
/// use ocean_fft::{OceanConfig, OceanState, Spectrum};
/// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
/// let ocean = OceanState::new(spectrum, OceanConfig::default())?;
/// let diagnostics = ocean.diagnostics();
/// assert!(diagnostics.fit().held > 0.9);                          // share of the variance
/// let hs = 4.0 * diagnostics.expected_variance().sqrt();          // m
/// assert!(hs > 1.5 && hs < 2.5);
/// assert!(ocean.config().choppiness <= diagnostics.max_choppiness());
/// # Ok::<(), ocean_fft::Error>(())
/// ```
#[derive(Clone, Copy)]
pub struct Diagnostics<'a> {
    ocean: &'a OceanState,
}

impl std::fmt::Debug for Diagnostics<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Diagnostics")
            .field("time", &self.ocean.time)
            .finish_non_exhaustive()
    }
}

impl OceanState {
    /// What this ocean can say about itself: how much of its sea the grids hold
    /// ([`Diagnostics::fit`]), the largest choppiness they take
    /// ([`Diagnostics::max_choppiness`]), the loop's frequency error, the mean-level
    /// correction and the expected variance. Costs nothing until a method is called.
    #[inline]
    pub fn diagnostics(&self) -> Diagnostics<'_> {
        Diagnostics { ocean: self }
    }
}

impl Diagnostics<'_> {
    /// The weight w in [0, 1] of the new sea in a change of weather at the last update
    /// (`None` when no change is in progress): 0 until the blend begins
    /// ([`limits::TRANSITION_LAG`](crate::limits::TRANSITION_LAG) after the call), then rising to 1 over the
    /// change's duration (see [`OceanState::set_spectrum`]).
    pub fn transition_progress(&self) -> Option<f64> {
        self.ocean.change.map(|change| change.weight)
    }

    /// What the grids hold of the current spectrum (see [`SeaFit`]; during a change of
    /// weather, of the new one). Costs a few quadratures, about half a millisecond.
    pub fn fit(&self) -> SeaFit {
        let config = &self.ocean.config;
        config.fit_bands(&self.ocean.spectrum, &config.bands_unchecked())
    }

    /// The largest choppiness [`OceanState::set_choppiness`] and [`OceanState::new`] accept
    /// for this spectrum and these grids, [`limits::MAX_FOLD_SCALE`](crate::limits::MAX_FOLD_SCALE)/σ, with σ² the
    /// mean-square slope the cascades' bands hold
    /// ([`Spectrum::slope_variance`](crate::Spectrum::slope_variance) summed over them: a
    /// quadrature of about a millisecond, which [`OceanState::set_choppiness`] pays too).
    ///
    /// Why: the Jacobian of the horizontal displacement is J = (1 + λD_xx)(1 + λD_zz) −
    /// λ²D_xz², and D_xx + D_zz (multiplier −|k|) has the variance of the slope, σ². For a
    /// Gaussian sea (an isotropic one; a wind sea's spreading changes these little) the
    /// surface folds, J < 0, on 0.3 % of its area at λσ = 0.5 (the presets sit below it),
    /// 41 % at λσ = 2, 53 % at λσ = 4 and never more than 58 % at any λ (where
    /// D_xx·D_zz < D_xz²). Beyond λσ = 4 more choppiness folds at most a few percent more
    /// of a surface already folded nearly everywhere it can, and the world queries'
    /// inversion of the displacement stops converging. Their heights stay those of the sea
    /// even then: the inversion's iterate is a point of the surface, and the mean-level
    /// correction λ∫k S d²k is at most λσ·√m0 = H_s here (Cauchy–Schwarz).
    pub fn max_choppiness(&self) -> f32 {
        let ocean = self.ocean;
        fit::max_choppiness(&ocean.spectrum, &ocean.config.bands_unchecked())
    }

    /// How far the repeat period moved the waves' frequencies, over every cascade (`None`
    /// without one): the largest relative error, and the mean weighted by each wave's share
    /// of the height variance.
    pub fn loop_error(&self) -> Option<LoopError> {
        LoopError::combine(self.ocean.cascades.iter().filter_map(Cascade::loop_error))
    }

    /// The mean-level correction in metres in the summed height: the sum of every cascade's
    /// [`Cascade::mean_level_offset`], λ·2 Σ_k |k| |h0(k)|² over all of them. With it the
    /// Eulerian mean of the displaced surface is still water (y = 0) for any choppiness;
    /// without it the sea would sit about λ ∫ k S(k) d²k lower (about 4.8 cm for the
    /// default sea at λ = 1, 34 cm for the storm preset at its λ = 1.2).
    pub fn mean_level_offset(&self) -> f32 {
        self.ocean
            .cascades
            .iter()
            .map(Cascade::mean_level_offset)
            .sum()
    }

    /// Expected variance of the summed height in m²: the sum over cascades of
    /// [`Cascade::expected_variance`]; 4√ of it is the expected H_s of the simulated sea.
    pub fn expected_variance(&self) -> f64 {
        self.ocean
            .cascades
            .iter()
            .map(Cascade::expected_variance)
            .sum()
    }
}
