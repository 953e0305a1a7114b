//! How much of a sea an ocean's grids hold ([`SeaFit`]), grids fitted to a sea
//! ([`OceanConfig::fitted`]), and the limits derived from them: the share a change of weather
//! must keep, the share a new ocean must hold, and the largest choppiness.

use std::ops::Bound::Included;

use crate::cascade::CascadeConfig;
use crate::error::{self, Error};
use crate::math::determinism::{Libm, Math};
use crate::spectrum::Spectrum;

use super::{OceanConfig, OceanState};

/// What an ocean's grids hold of a spectrum's height variance, as fractions of the variance
/// in the config's band [`k_min`](OceanConfig::k_min), [`k_max`](OceanConfig::k_max) (the
/// whole spectrum by default); `held + too_long + too_short` is 1 to the quadrature's
/// precision.
///
/// From the spectrum's integrals over each cascade's band ([`Spectrum::band_variance`]), not
/// from the drawn waves: a grid's sum over its wave vectors agrees with them to a few percent
/// from 64² up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeaFit {
    /// Fraction of the variance the cascades hold: (simulated H_s / the sea's H_s)².
    pub held: f64,
    /// Fraction in waves too long for the largest tile: wave numbers below 2π/(L₀√π), the
    /// grid's first ring of wave vectors (the cell around k = 0 of area (2π/L₀)² holds
    /// none); with a very low [`band_split`](OceanConfig::band_split), also the part of
    /// another cascade's band below its own such limit.
    pub too_long: f64,
    /// Fraction in waves too short for the finest grid cell: wave numbers above the last
    /// cascade's band, πN/L_last.
    pub too_short: f64,
    /// The variance of the sea in the config's band, in m² ((H_s/4)²).
    pub variance: f64,
}

impl SeaFit {
    /// H_s the grids hold, in metres: 4√(held · variance).
    pub fn held_significant_wave_height(&self) -> f64 {
        4.0 * (self.held * self.variance).sqrt()
    }

    /// H_s of the sea in the config's band, in metres: 4√variance.
    pub fn significant_wave_height(&self) -> f64 {
        4.0 * self.variance.sqrt()
    }
}

impl OceanConfig {
    /// The largest tile of [`fitted`](Self::fitted) grids, in peak wavelengths: enough that
    /// the waves longer than it hold far below 1 % of any sea here, and that a view of a few
    /// wavelengths shows no repeat (0.3's hand-chosen preset tiles were 9 to 14).
    pub const FIT_PEAK_WAVELENGTHS: f32 = 12.0;

    /// The share of a spectrum's variance that [`fitted`](Self::fitted) grids hold at least
    /// (H_s within 1.5 % of the sea's).
    pub const FITTED_SHARE: f64 = 0.97;

    /// What these grids hold of `spectrum` (see [`SeaFit`]). Costs a few quadratures of the
    /// spectrum, about half a millisecond: not a per-frame call.
    ///
    /// # Errors
    /// Those of [`OceanConfig::validate`].
    pub fn fit(&self, spectrum: &Spectrum) -> Result<SeaFit, Error> {
        let bands = self.bands()?;
        Ok(self.fit_bands(spectrum, &bands))
    }

    /// [`fit`](Self::fit) for this config's `bands`.
    pub(super) fn fit_bands(&self, spectrum: &Spectrum, bands: &[(f32, f32)]) -> SeaFit {
        let variance = |lo: f64, hi: f64| spectrum.band_variance_f64(lo, hi);
        let (k_min, k_max) = (f64::from(self.k_min), f64::from(self.k_max));
        let top = bands.last().map_or(k_max, |&(_, hi)| f64::from(hi));
        let sea = variance(k_min, k_max);
        let (mut held, mut long) = (0.0, 0.0);
        for (&(lo, hi), &length) in bands.iter().zip(&self.lengths) {
            let (lo, hi) = (f64::from(lo), f64::from(hi));
            // A grid holds no wave vector inside the cell of area Δk² around k = 0, a disc
            // of radius Δk/√π: the part of its band below that is too long for its tile
            // (only cascade 0's, unless a band split puts a band's start that low).
            let first = (std::f64::consts::TAU / f64::from(length) / std::f64::consts::PI.sqrt())
                .clamp(lo, hi.max(lo));
            long += variance(lo, first);
            held += variance(first, hi);
        }
        let fraction = |v: f64| if sea > 0.0 { v / sea } else { 0.0 };
        SeaFit {
            held: if sea > 0.0 { held / sea } else { 1.0 },
            too_long: fraction(long),
            too_short: fraction(variance(top, k_max)),
            variance: sea,
        }
    }

    /// The default config with its cascade lengths fitted to `spectrum`: see
    /// [`with_fitted_lengths`](Self::with_fitted_lengths).
    ///
    /// ```
    /// use ocean_fft::{OceanConfig, OceanState, Spectrum};
    /// let storm = Spectrum::jonswap(26.0, 500_000.0)?;    // U10 m/s, fetch m
    /// let config = OceanConfig::fitted(&storm)?;
    /// assert!(config.fit(&storm)?.held >= OceanConfig::FITTED_SHARE);
    /// # Ok::<(), ocean_fft::Error>(())
    /// ```
    ///
    /// # Errors
    /// Those of [`with_fitted_lengths`](Self::with_fitted_lengths).
    pub fn fitted(spectrum: &Spectrum) -> Result<OceanConfig, Error> {
        OceanConfig::default().with_fitted_lengths(spectrum)
    }

    /// This config with cascade lengths that hold at least
    /// [`FITTED_SHARE`](Self::FITTED_SHARE) of `spectrum`'s variance, every other field
    /// (the size N among them) kept.
    ///
    /// The largest tile is [`FIT_PEAK_WAVELENGTHS`](Self::FIT_PEAK_WAVELENGTHS) peak
    /// wavelengths (at most N/4 of them, so that the peak lies inside cascade 0's band, which
    /// ends at πN/(2L₀)), the others 0.23 and 0.051 of it, the default's non-integer ratios
    /// that hide the tiling, each rounded to three significant digits. If those hold less
    /// than the share, the largest grows (waves too long were lost) or a cascade 0.23 times
    /// the last is added (waves too short), up to [`MAX_CASCADES`](Self::MAX_CASCADES).
    ///
    /// # Errors
    /// Those of [`OceanConfig::validate`] for the other fields; [`Error::SeaDoesNotFit`]
    /// naming `spectrum` if no such lengths within
    /// [`CascadeConfig::MIN_LENGTH`](CascadeConfig::MIN_LENGTH) ..
    /// [`CascadeConfig::MAX_LENGTH`](CascadeConfig::MAX_LENGTH) hold the share at
    /// this size.
    pub fn with_fitted_lengths(self, spectrum: &Spectrum) -> Result<OceanConfig, Error> {
        // Libm: the same lengths on every machine, for `Determinism::CrossPlatform`.
        let peak = std::f64::consts::TAU / spectrum.peak_wave_number_with::<Libm>();
        let wavelengths = f64::from(Self::FIT_PEAK_WAVELENGTHS).min(self.size as f64 / 4.0);
        let mut largest = peak * wavelengths;
        let mut count = 3;
        let mut config = self;
        let mut last = None;
        // Each round grows the largest tile by a quarter or adds a cascade: 40 rounds cover
        // 1.25⁴⁰ ≈ 7500× and every cascade count.
        for _ in 0..40 {
            config.lengths = fitted_lengths(largest, count);
            let fit = config.fit(spectrum)?;
            if fit.held >= Self::FITTED_SHARE {
                return Ok(config);
            }
            last = Some(fit);
            let max = f64::from(CascadeConfig::MAX_LENGTH);
            if fit.too_long >= fit.too_short && largest < max {
                largest = (largest * 1.25).min(max);
            } else if count < Self::MAX_CASCADES
                && config.lengths[count - 1] * 0.23 >= CascadeConfig::MIN_LENGTH
            {
                count += 1;
            } else {
                break;
            }
        }
        let fit = last.unwrap_or_else(|| config.fit_bands(spectrum, &config.bands_unchecked()));
        Err(fit.error("spectrum", &config, Self::FITTED_SHARE))
    }
}

/// `count` lengths from `largest` down by the ratios 0.23 and then 0.051 / 0.23 (the
/// default's 1 : 0.23 : 0.051), each to three significant digits.
fn fitted_lengths(largest: f64, count: usize) -> Vec<f32> {
    let largest = largest.clamp(
        f64::from(CascadeConfig::MIN_LENGTH),
        f64::from(CascadeConfig::MAX_LENGTH),
    );
    let ratios = [1.0, 0.23, 0.051];
    let mut lengths: Vec<f32> = (0..count)
        .map(|c| {
            let ratio = if c < 3 {
                ratios[c]
            } else {
                0.051 * Libm::powi(0.23, c as i32 - 2)
            };
            three_digits(largest * ratio) as f32
        })
        .collect();
    lengths.dedup();
    lengths
}

/// `x` rounded to three significant digits (in libm: the same digits on every machine).
fn three_digits(x: f64) -> f64 {
    if x <= 0.0 || !x.is_finite() {
        return x;
    }
    let scale = Libm::powi(10.0, 2 - Libm::log10(x).floor() as i32);
    (x * scale).round() / scale
}

impl SeaFit {
    /// The error that says these grids hold less than `min` of the sea.
    pub(super) fn error(&self, name: &'static str, config: &OceanConfig, min: f64) -> Error {
        let last = config.lengths.len().saturating_sub(1);
        Error::SeaDoesNotFit {
            name,
            held: self.held,
            min,
            too_long: self.too_long,
            too_short: self.too_short,
            significant_wave_height: self.significant_wave_height(),
            largest_tile: f64::from(config.lengths.first().copied().unwrap_or(0.0)),
            finest_cell: f64::from(config.lengths.get(last).copied().unwrap_or(0.0))
                / config.size as f64,
        }
    }
}

impl OceanState {
    #[deprecated(since = "0.4.0", note = "use `ocean_fft::limits::MIN_CHANGE_SHARE`")]
    #[doc(hidden)]
    pub const MIN_CHANGE_SHARE: f64 = super::limits::MIN_CHANGE_SHARE;

    #[deprecated(since = "0.4.0", note = "use `ocean_fft::limits::MIN_BUILD_SHARE`")]
    #[doc(hidden)]
    pub const MIN_BUILD_SHARE: f64 = super::limits::MIN_BUILD_SHARE;

    #[deprecated(since = "0.4.0", note = "use `ocean_fft::limits::MAX_FOLD_SCALE`")]
    #[doc(hidden)]
    pub const MAX_FOLD_SCALE: f32 = super::limits::MAX_FOLD_SCALE;

    /// Deprecated: [`Diagnostics::fit`](super::Diagnostics::fit) through
    /// [`OceanState::diagnostics`].
    #[deprecated(since = "0.4.0", note = "use `ocean.diagnostics().fit()`")]
    #[doc(hidden)]
    pub fn fit(&self) -> SeaFit {
        self.diagnostics().fit()
    }

    /// Deprecated: [`Diagnostics::max_choppiness`](super::Diagnostics::max_choppiness)
    /// through [`OceanState::diagnostics`].
    #[deprecated(since = "0.4.0", note = "use `ocean.diagnostics().max_choppiness()`")]
    #[doc(hidden)]
    pub fn max_choppiness(&self) -> f32 {
        self.diagnostics().max_choppiness()
    }

    /// [`set_spectrum`](Self::set_spectrum) for a sea the grids may hold less than
    /// [`limits::MIN_CHANGE_SHARE`](crate::limits::MIN_CHANGE_SHARE) of: the caller accepts a sea whose
    /// simulated H_s falls short of the spectrum's (see [`Diagnostics::fit`](super::Diagnostics::fit) after the call).
    ///
    /// # Errors
    /// Those of [`set_spectrum`](Self::set_spectrum) but [`Error::SeaDoesNotFit`]; nothing
    /// changes then.
    pub fn set_spectrum_unfitted(
        &mut self,
        spectrum: Spectrum,
        duration: f64,
    ) -> Result<(), Error> {
        self.check_change_choppiness(&spectrum)?;
        self.change_spectrum(spectrum, duration)
    }

    /// Refuses a new spectrum the grids hold less than
    /// [`limits::MIN_CHANGE_SHARE`](crate::limits::MIN_CHANGE_SHARE) of.
    pub(super) fn check_change_fit(&self, spectrum: &Spectrum) -> Result<(), Error> {
        let fit = self
            .config
            .fit_bands(spectrum, &self.config.bands_unchecked());
        if fit.held < super::limits::MIN_CHANGE_SHARE {
            return Err(fit.error("spectrum", &self.config, super::limits::MIN_CHANGE_SHARE));
        }
        Ok(())
    }

    /// Refuses a new spectrum too steep for the current choppiness (its
    /// [`max_choppiness`](super::Diagnostics::max_choppiness) below it).
    pub(super) fn check_change_choppiness(&self, spectrum: &Spectrum) -> Result<(), Error> {
        let bands = self.config.bands_unchecked();
        if self.config.choppiness > max_choppiness(spectrum, &bands) {
            return Err(Error::NotApplicable {
                name: "spectrum",
                reason: "the new sea is so steep that the current choppiness would fold it \
                         nearly everywhere: lower the choppiness first (see \
                         `Diagnostics::max_choppiness`)",
            });
        }
        Ok(())
    }
}

/// [`Diagnostics::max_choppiness`](super::Diagnostics::max_choppiness) for a spectrum and bands.
pub(super) fn max_choppiness(spectrum: &Spectrum, bands: &[(f32, f32)]) -> f32 {
    let slope: f64 = bands
        .iter()
        .map(|&(lo, hi)| f64::from(spectrum.slope_variance(lo, hi).total()))
        .sum();
    if slope > 0.0 {
        error::saturate(f64::from(super::limits::MAX_FOLD_SCALE) / slope.sqrt())
    } else {
        f32::MAX
    }
}

/// Checks a choppiness against [`max_choppiness`] for these bands.
pub(super) fn check_choppiness(
    spectrum: &Spectrum,
    bands: &[(f32, f32)],
    choppiness: f32,
) -> Result<f32, Error> {
    let limit = max_choppiness(spectrum, bands);
    error::in_range("choppiness", choppiness, Included(0.0), Included(limit))
}

/// Checks that the grids hold at least [`limits::MIN_BUILD_SHARE`](crate::limits::MIN_BUILD_SHARE) of the sea.
pub(super) fn check_build_fit(
    spectrum: &Spectrum,
    config: &OceanConfig,
    bands: &[(f32, f32)],
) -> Result<(), Error> {
    let fit = config.fit_bands(spectrum, bands);
    if fit.held < super::limits::MIN_BUILD_SHARE {
        return Err(fit.error("spectrum", config, super::limits::MIN_BUILD_SHARE));
    }
    Ok(())
}
