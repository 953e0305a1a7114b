//! Warnings before a bake starts, for parameters that would waste it: a loop too short for
//! the sea's waves, and tiles that do not fit the sea (a cascade left nearly empty, or the
//! sea's waves outside what the tiles hold). Each names the parameter and a value to try.
//!
//! The tool warns rather than refitting the tiles itself: the tile sides are part of what a
//! bake hands to the engine (the sidecar's `length_m`, the uv of every world point), so they
//! change only when the user says so, and a `--config` file's tiles are the user's choice.

use std::fmt;

use ocean_fft::{CascadeConfig, OceanConfig, OceanState, SeaFit, Spectrum};

use crate::encode::three_digits;
use crate::setup::Sea;

/// A loop shorter than this many peak periods warns: the guide's rule for a natural look
/// (the mean frequency error is 15 % for the fresh breeze at 1.15·T_p, and 8–9 % for the
/// fresh breeze, the moderate breeze and the storm at 2·T_p).
pub const LOOP_PEAK_PERIODS: f64 = 2.0;

/// A cascade is nearly empty when it holds less than this share of the simulated height
/// variance and less than [`EMPTY_SLOPE_SHARE`] of the slope variance: it costs as much as
/// the others and shows nothing. (The presets' finest cascade holds 0.07–0.2 % of the height
/// variance at 256² and 0.01 % at 1024², but a third of the slope variance, so the slope
/// share keeps it.)
pub const EMPTY_HEIGHT_SHARE: f64 = 1e-3;
/// See [`EMPTY_HEIGHT_SHARE`].
pub const EMPTY_SLOPE_SHARE: f64 = 0.01;

/// The tiles warn when they hold less than this share of the spectrum's height variance
/// (H_s below 90 % of the sea's).
pub const MIN_COVERAGE: f64 = 0.81;

/// The largest tile of a fitted suggestion, in peak wavelengths: the presets use 9 to 14.
pub const FIT_PEAK_WAVELENGTHS: f64 = 12.0;

/// A warning: the parameter to change, and a message that names it, says why and suggests
/// a value.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Warning {
    /// The option to change: `--loop` or `--lengths`.
    pub parameter: &'static str,
    /// The whole message (without `warning: `).
    pub message: String,
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "warning: {}", self.message)
    }
}

/// A length in metres with three significant digits or more: 7.50, 62.5, 4000.
fn metres(x: f64) -> String {
    if x >= 100.0 {
        format!("{x:.0} m")
    } else if x >= 10.0 {
        format!("{x:.1} m")
    } else if x >= 1.0 {
        format!("{x:.2} m")
    } else {
        format!("{x:.3} m")
    }
}

/// Every warning for this sea and its ocean (built, not yet simulated).
pub fn check(sea: &Sea, ocean: &OceanState) -> Vec<Warning> {
    let mut warnings = Vec::new();
    warnings.extend(check_loop(sea, ocean));
    warnings.extend(check_tiles(sea));
    warnings
}

/// The shortest loop at `fps` of at least `seconds`: whole seconds when those are whole
/// frames, else whole frames; (T, frames).
fn loop_at_least(seconds: f64, fps: f64) -> (f64, u64) {
    let whole_seconds = seconds.ceil();
    let frames = whole_seconds * fps;
    if (frames - frames.round()).abs() <= 1e-9 * frames {
        (whole_seconds, frames.round() as u64)
    } else {
        let frames = (seconds * fps).ceil();
        (frames / fps, frames as u64)
    }
}

/// A loop shorter than [`LOOP_PEAK_PERIODS`]·T_p.
fn check_loop(sea: &Sea, ocean: &OceanState) -> Option<Warning> {
    let looping = sea.looping?;
    let peak = f64::from(sea.spectrum.peak_period());
    let period = f64::from(looping.period);
    let wanted = LOOP_PEAK_PERIODS * peak;
    if period >= wanted {
        return None;
    }
    let (t, frames) = loop_at_least(
        wanted.min(f64::from(CascadeConfig::MAX_REPEAT_PERIOD)),
        sea.fps,
    );
    let error = ocean.diagnostics().loop_error().map_or(String::new(), |e| {
        format!(
            ": the loop moves the waves' frequencies by {:.0} % on average (largest {:.0} %)",
            100.0 * e.mean_relative,
            100.0 * e.max_relative
        )
    });
    Some(Warning {
        parameter: "--loop",
        message: format!(
            "{} {} is shorter than {LOOP_PEAK_PERIODS} peak periods of this sea \
             (T_p = {peak:.2} s){error}, and waves near the peak visibly change speed; use \
             --loop {t} ({frames} frames at {} fps) or longer",
            looping.parameter, looping.period, sea.fps
        ),
    })
}

/// What the tiles of a config hold of a spectrum: the library's [`SeaFit`] (the sea held,
/// and where the rest is lost), with each cascade's share of the height and slope variance
/// from the spectrum's integrals over its band (the grid's sums,
/// `Cascade::expected_variance`, agree with them to a few percent from 64² up; cheap and free
/// of the grid, they also judge a suggested config without building it).
#[derive(Debug, Clone, PartialEq)]
pub struct TileFit {
    /// Height variance of each cascade's band in m².
    pub height: Vec<f64>,
    /// Slope variance of each cascade's band (dimensionless).
    pub slope: Vec<f64>,
    /// What the tiles hold of the sea, from `OceanConfig::fit`.
    pub fit: SeaFit,
    /// The sea's peak wavelength in metres.
    pub peak_wavelength: f64,
}

impl TileFit {
    /// Integrates `spectrum` over the bands of `config`; `None` for a config the library
    /// refuses (or a spectrum without variance, which nothing would fit).
    pub fn new(spectrum: &Spectrum, config: &OceanConfig) -> Option<TileFit> {
        let fit = config.fit(spectrum).ok()?;
        if !(fit.variance > 0.0 && fit.variance.is_finite()) {
            return None;
        }
        let mut bands = config.bands().ok()?;
        // Cascade 0's grid holds no wave longer than its tile: its lowest wave vectors are
        // Δk = 2π/L apart and k = 0 is left out, a cell of area Δk², i.e. a disc of radius
        // Δk/√π (as `OceanConfig::fit` counts it).
        let dk = std::f32::consts::TAU / config.lengths[0];
        bands[0].0 = bands[0].0.max(dk / std::f32::consts::PI.sqrt());
        let height = bands
            .iter()
            .map(|&(lo, hi)| f64::from(spectrum.band_variance(lo, hi)))
            .collect();
        let slope = bands
            .iter()
            .map(|&(lo, hi)| f64::from(spectrum.slope_variance(lo, hi).total()))
            .collect();
        let k_peak = spectrum.dispersion().k_from_omega(spectrum.peak_omega());
        Some(TileFit {
            height,
            slope,
            fit,
            peak_wavelength: std::f64::consts::TAU / f64::from(k_peak),
        })
    }

    /// Cascade `c`'s share of the simulated height variance.
    pub fn height_share(&self, c: usize) -> f64 {
        share(self.height[c], &self.height)
    }

    /// Cascade `c`'s share of the simulated slope variance.
    pub fn slope_share(&self, c: usize) -> f64 {
        share(self.slope[c], &self.slope)
    }

    /// The share of the sea's height variance the tiles hold.
    pub fn coverage(&self) -> f64 {
        self.fit.held
    }

    /// The cascades that are nearly empty.
    pub fn empty(&self) -> Vec<usize> {
        (0..self.height.len())
            .filter(|&c| {
                self.height_share(c) < EMPTY_HEIGHT_SHARE && self.slope_share(c) < EMPTY_SLOPE_SHARE
            })
            .collect()
    }

    /// Whether these tiles fit: no cascade nearly empty, and enough of the sea held.
    pub fn fits(&self) -> bool {
        self.empty().is_empty() && self.coverage() >= MIN_COVERAGE
    }
}

fn share(part: f64, all: &[f64]) -> f64 {
    let total: f64 = all.iter().sum();
    if total > 0.0 {
        part / total
    } else {
        0.0
    }
}

/// Tiles that fit the sea: the config's proportions, scaled so that the largest is
/// [`FIT_PEAK_WAVELENGTHS`] peak wavelengths (at most N/4 of them, so that the peak stays in
/// cascade 0's band on a small grid: its band ends at πN/(2L)), three digits, less any
/// cascade still nearly empty. `None` if no such tiles fit.
pub fn fitted_lengths(spectrum: &Spectrum, config: &OceanConfig) -> Option<Vec<f32>> {
    let fit = TileFit::new(spectrum, config)?;
    let largest = fit.peak_wavelength * FIT_PEAK_WAVELENGTHS.min(config.size as f64 / 4.0);
    let scale = largest / f64::from(config.lengths[0]);
    let mut lengths: Vec<f32> = config
        .lengths
        .iter()
        .map(|&l| three_digits(f64::from(l) * scale, f64::round) as f32)
        .collect();
    lengths.dedup();
    let mut candidate = OceanConfig {
        lengths,
        ..config.clone()
    };
    let fit = TileFit::new(spectrum, &candidate)?;
    let empty = fit.empty();
    if !empty.is_empty() && empty.len() < candidate.lengths.len() {
        candidate.lengths = candidate
            .lengths
            .iter()
            .enumerate()
            .filter(|(c, _)| !empty.contains(c))
            .map(|(_, &l)| l)
            .collect();
    }
    TileFit::new(spectrum, &candidate)
        .filter(TileFit::fits)
        .map(|_| candidate.lengths)
}

/// `--lengths` as the user would type it.
pub fn lengths_text(lengths: &[f32]) -> String {
    let text: Vec<String> = lengths.iter().map(f32::to_string).collect();
    text.join(",")
}

/// Tiles that leave a cascade nearly empty, or hold too little of the sea.
fn check_tiles(sea: &Sea) -> Option<Warning> {
    let config = &sea.config;
    let fit = TileFit::new(&sea.spectrum, config)?;
    let empty = fit.empty();
    let coverage = fit.coverage();
    if empty.is_empty() && coverage >= MIN_COVERAGE {
        return None;
    }
    let hs = |variance: f64| 4.0 * variance.sqrt();
    let bands = config.bands().ok()?;
    let mut why = Vec::new();
    for &c in &empty {
        let (lo, hi) = bands[c];
        let wavelength = |k: f32| metres(std::f64::consts::TAU / f64::from(k));
        let waves = if lo > 0.0 {
            format!("{} to {}", wavelength(hi), wavelength(lo))
        } else {
            format!("{} and longer", wavelength(hi))
        };
        why.push(format!(
            "cascade {c} (waves {waves}) is nearly empty, with H_s {:.3} m of the sea's {:.3} m \
             ({:.2} % of the height variance, {:.2} % of the slope variance)",
            hs(fit.height[c]),
            fit.fit.significant_wave_height(),
            100.0 * fit.height_share(c),
            100.0 * fit.slope_share(c),
        ));
    }
    if !empty.is_empty() {
        why.push(format!(
            "{} of {} cascades cost their share of the bake for nothing",
            empty.len(),
            config.lengths.len()
        ));
    }
    if coverage < MIN_COVERAGE {
        let missing = if fit.fit.too_long >= fit.fit.too_short {
            format!(
                "waves longer than the largest tile ({}) are missing",
                metres(f64::from(config.lengths[0]))
            )
        } else {
            let last = config.lengths.len() - 1;
            format!(
                "waves shorter than the finest texels ({}) are missing",
                metres(f64::from(config.lengths[last]) / config.size as f64)
            )
        };
        why.push(format!(
            "the tiles hold about H_s {:.3} m of the sea's {:.3} m ({:.0} % of its height \
             variance): {missing}",
            fit.fit.held_significant_wave_height(),
            fit.fit.significant_wave_height(),
            100.0 * coverage
        ));
    }
    let cause = if sea.overrides.is_empty() {
        String::new()
    } else {
        format!("; {}", sea.overrides.join(", "))
    };
    let advice = match fitted_lengths(&sea.spectrum, config) {
        Some(lengths) => format!(
            "use --lengths {} ({}the largest tile {:.0} × the peak wavelength), or a preset \
             nearer this sea",
            lengths_text(&lengths),
            if lengths.len() == config.lengths.len() {
                "the same proportions, "
            } else {
                "without the cascades that stay empty, "
            },
            f64::from(lengths[0]) / fit.peak_wavelength,
        ),
        None => "choose other --lengths or --size, or a preset nearer this sea".into(),
    };
    Some(Warning {
        parameter: "--lengths",
        message: format!(
            "the tiles {} m ({}{cause}) do not fit this sea, whose peak wavelength is {} \
             (T_p = {:.2} s): {}; {advice}",
            lengths_text(&config.lengths),
            sea.tiles_from,
            metres(fit.peak_wavelength),
            sea.spectrum.peak_period(),
            why.join("; "),
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggested_loops_are_whole_frames_and_long_enough() {
        assert_eq!(loop_at_least(29.3, 30.0), (30.0, 900));
        assert_eq!(loop_at_least(13.88, 24.0), (14.0, 336));
        // 29.97 fps: 30 s is 899.1 frames, so whole frames: 29.3 s × 29.97 = 878.1, 879.
        let (t, frames) = loop_at_least(29.3, 29.97);
        assert_eq!(frames, 879);
        assert!(t >= 29.3 && (t * 29.97 - 879.0).abs() < 1e-9);
    }
}
