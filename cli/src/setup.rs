//! From the command line to a sea: the spectrum and config (preset or file, then the
//! overrides), the frame times, the loop and the foam pre-roll.

use std::path::Path;

use ocean_fft::{CascadeConfig, OceanConfig, SeaState, Spectrum};

use crate::args::SeaArgs;
use crate::error::CliError;

/// Accepted frames per second.
pub const FPS_RANGE: (f64, f64) = (0.1, 1000.0);
/// Accepted foam tolerances.
pub const TOLERANCE_RANGE: (f64, f64) = (1e-6, 0.1);

/// The preset names, for clap's value check and its `--help`.
pub fn preset_names() -> clap::builder::PossibleValuesParser {
    clap::builder::PossibleValuesParser::new(SeaState::ALL.map(SeaState::name))
}

/// A seamless loop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Looping {
    /// The repeat period T in seconds, as the ocean's config holds it.
    pub period: f32,
    /// Frames per loop, T·fps (a whole number).
    pub frames: u32,
}

/// How the foam's history is made a pure function of the frame number (see
/// docs/guide/baking.md, "Render farms").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Preroll {
    /// ε: the largest difference from the foam of an ocean simulated forever.
    pub tolerance: f64,
    /// W = (τ_A + τ_R)·ln(1/ε) in seconds, a whole number of frames: after W of simulation
    /// from any foam, the foam is within ε of any other history's (0 when no foam forms).
    pub window: f64,
    /// P = ⌈(τ_A + τ_R)·ln(1/ε)·fps⌉: the pre-roll in frames before an anchor.
    pub frames: u32,
    /// The step of the pre-roll in seconds: whole frames, as many as fit in 0.1 s (at least
    /// one).
    pub step: f64,
    /// Anchors every this many frames (not for loops).
    pub anchor_every: u32,
    /// For loops: the pre-roll stops once a whole loop changes no foam value by more than
    /// this, ε·(1 − q) with q = e^{−T/τ_R} the contraction of one loop, so that the foam is
    /// within ε of the loop's periodic steady state (a geometric series of changes ≤ q·ε/(1 − q)
    /// is left).
    pub loop_change: f64,
    /// For loops: the most whole loops pre-rolled (twice what the contraction alone needs to
    /// bring a change of 1 below `loop_change`, plus two).
    pub max_loops: u32,
}

/// Everything that decides the frames' content.
#[derive(Debug, Clone)]
pub struct Sea {
    /// Base of the file names.
    pub name: String,
    /// The spectrum.
    pub spectrum: Spectrum,
    /// The ocean's config (with `repeat_period` set for a loop).
    pub config: OceanConfig,
    /// Frames per second.
    pub fps: f64,
    /// The loop, if any.
    pub looping: Option<Looping>,
    /// The foam pre-roll.
    pub preroll: Preroll,
}

impl Sea {
    /// Time in seconds of frame `index` of the simulation (negative in a pre-roll).
    pub fn time(&self, index: i64) -> f64 {
        index as f64 / self.fps
    }
}

/// The JSON a `--config` file holds (and a sidecar too): `{"spectrum": …, "config": …}`.
#[derive(serde::Deserialize)]
struct ConfigFile {
    spectrum: Spectrum,
    config: OceanConfig,
}

/// Reads a `--config` file.
fn read_config(path: &Path) -> Result<(Spectrum, OceanConfig), CliError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| CliError::config(format!("--config {}: {e}", path.display())))?;
    let file: ConfigFile = serde_json::from_str(&text).map_err(|e| {
        CliError::config(format!(
            "--config {}: {e} (expected a JSON object with the keys \"spectrum\" and \"config\")",
            path.display()
        ))
    })?;
    Ok((file.spectrum, file.config))
}

/// An override's value checked against the library: its error names the flag.
fn flag<T>(
    flag: &str,
    value: impl std::fmt::Display,
    r: Result<T, ocean_fft::Error>,
) -> Result<T, CliError> {
    r.map_err(|e| CliError::usage(format!("{flag} {value}: {e}")))
}

/// The spectrum with the overrides applied.
fn override_spectrum(base: Spectrum, args: &SeaArgs) -> Result<Spectrum, CliError> {
    let mut spectrum = base.clone();
    if args.wind.is_some() || args.fetch.is_some() {
        let wind = args.wind.unwrap_or(base.wind_speed());
        let fetch = match (args.fetch, base.fetch()) {
            (Some(f), _) | (None, Some(f)) => f,
            (None, None) => {
                return Err(CliError::usage(
                    "--wind: this spectrum was not built from a fetch; give --fetch too",
                ))
            }
        };
        let (name, value) = match args.wind {
            Some(w) => ("--wind", w),
            None => ("--fetch", fetch),
        };
        if base.gamma().is_none() {
            return Err(CliError::usage(format!(
                "{name} {value}: the spectrum is a Phillips spectrum, which has no fetch law"
            )));
        }
        spectrum = flag(name, value, Spectrum::jonswap(wind, fetch))?;
        // Everything else as the base spectrum had it.
        let keep = |s: Spectrum| -> Result<Spectrum, ocean_fft::Error> {
            s.with_gamma(base.gamma().unwrap_or(Spectrum::DEFAULT_GAMMA))?
                .with_wind_direction(base.wind_direction())?
                .with_spreading(base.spreading_kind())?
                .with_swell(base.swell())?
                .with_spread_blend(base.spread_blend())?
                .with_short_wave_length(base.short_wave_length())?
                .with_dispersion(base.dispersion())?
                .with_depth_factor(base.depth_factor())
        };
        spectrum = flag(name, value, keep(spectrum))?;
    }
    if let Some(depth) = args.depth {
        spectrum = flag("--depth", depth, spectrum.with_depth(depth))?;
    }
    if let Some(degrees) = args.direction_deg {
        if !degrees.is_finite() {
            return Err(CliError::usage(format!(
                "--direction-deg {degrees}: expected a finite angle in degrees"
            )));
        }
        spectrum = flag(
            "--direction-deg",
            degrees,
            spectrum.with_wind_direction(degrees.to_radians()),
        )?;
    }
    Ok(spectrum)
}

/// A number in a closed range, or an error naming `name`.
fn in_range(name: &str, value: f64, (min, max): (f64, f64)) -> Result<f64, CliError> {
    if value.is_finite() && (min..=max).contains(&value) {
        Ok(value)
    } else {
        Err(CliError::usage(format!(
            "{name} {value}: expected {min} ≤ {} ≤ {max}",
            name.trim_start_matches('-')
        )))
    }
}

/// Builds the sea from the arguments.
///
/// # Errors
/// [`CliError`] of kind `Usage` naming the flag for a bad override, frame rate, loop or
/// tolerance; of kind `Config` for an unreadable or invalid `--config` file or a config the
/// library refuses.
pub fn build(args: &SeaArgs) -> Result<Sea, CliError> {
    let (spectrum, mut config, name) = match (&args.source.preset, &args.source.config) {
        (Some(preset), _) => {
            let state = SeaState::ALL
                .into_iter()
                .find(|s| s.name() == preset)
                .ok_or_else(|| CliError::usage(format!("--preset {preset}: unknown preset")))?;
            let (spectrum, config) = state.build();
            (spectrum, config, state.name().to_string())
        }
        (None, Some(path)) => {
            let (spectrum, config) = read_config(path)?;
            let stem = path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "ocean".into());
            (spectrum, config, stem)
        }
        (None, None) => {
            return Err(CliError::usage(
                "give the sea with --preset NAME or --config FILE.json",
            ))
        }
    };
    let spectrum = override_spectrum(spectrum, args)?;
    if let Some(size) = args.size {
        if !(CascadeConfig::MIN_SIZE..=CascadeConfig::MAX_SIZE).contains(&size) || size % 2 != 0 {
            return Err(CliError::usage(format!(
                "--size {size}: expected an even grid size from {} to {}",
                CascadeConfig::MIN_SIZE,
                CascadeConfig::MAX_SIZE
            )));
        }
        config.size = size;
    }
    if let Some(choppiness) = args.choppiness {
        if !(choppiness.is_finite() && choppiness >= 0.0) {
            return Err(CliError::usage(format!(
                "--choppiness {choppiness}: expected a finite choppiness ≥ 0"
            )));
        }
        config.choppiness = choppiness;
    }
    if let Some(seed) = args.seed {
        config.seed = seed;
    }
    let fps = in_range("--fps", args.fps, FPS_RANGE)?;
    let tolerance = in_range("--foam-tolerance", args.foam_tolerance, TOLERANCE_RANGE)?;
    if args.anchor_every == 0 {
        return Err(CliError::usage(
            "--anchor-every 0: expected at least 1 frame",
        ));
    }

    // The loop: from --loop, else from the config file's repeat period.
    let (period, flag_name) = match (args.loop_seconds, config.repeat_period) {
        (Some(t), _) => (Some(t), "--loop"),
        (None, Some(t)) => (Some(f64::from(t)), "repeat_period (in --config)"),
        (None, None) => (None, ""),
    };
    let looping = match period {
        None => None,
        Some(t) => {
            let range = (
                f64::from(CascadeConfig::MIN_REPEAT_PERIOD),
                f64::from(CascadeConfig::MAX_REPEAT_PERIOD),
            );
            let t = in_range(flag_name, t, range)?;
            let frames = t * fps;
            let whole = frames.round();
            if whole < 1.0 || (frames - whole).abs() > 1e-6 * whole || whole > f64::from(u32::MAX) {
                return Err(CliError::usage(format!(
                    "{flag_name} {t}: a loop must last a whole number of frames at --fps {fps} \
                     ({t} s × {fps} fps = {frames} frames)"
                )));
            }
            config.repeat_period = Some(t as f32);
            Some(Looping {
                period: t as f32,
                frames: whole as u32,
            })
        }
    };
    config
        .validate()
        .map_err(|e| CliError::config(format!("the sea's configuration: {e}")))?;

    // The foam's memory: a difference in active foam decays at least as e^{−t/τ_A}, one in
    // residual foam as e^{−t/τ_R} plus what the active difference still feeds it, which
    // (τ_A + τ_R)·ln(1/ε) covers for the default decays (docs/guide/baking.md, "Render farms").
    let tau = f64::from(config.foam.active_decay) + f64::from(config.foam.residual_decay);
    let frames = if config.foam.coverage > 0.0 {
        (tau * (1.0 / tolerance).ln() * fps).ceil()
    } else {
        0.0
    };
    let window = frames / fps;
    let (loop_change, max_loops) = match looping {
        Some(l) => {
            let slowest = f64::from(config.foam.active_decay.max(config.foam.residual_decay));
            let q = (-f64::from(l.period) / slowest).exp();
            let change = tolerance * (1.0 - q);
            let needed = (change.ln() / q.ln()).ceil().min(1e6) as u32;
            (change, 2 + 2 * needed)
        }
        None => (tolerance, 0),
    };
    let preroll = Preroll {
        tolerance,
        window,
        frames: frames as u32,
        step: (0.1 * fps).floor().max(1.0) / fps,
        anchor_every: args.anchor_every,
        loop_change,
        max_loops,
    };
    Ok(Sea {
        name,
        spectrum,
        config,
        fps,
        looping,
        preroll,
    })
}
