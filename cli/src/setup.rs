//! From the command line to a sea: the spectrum and config (preset or file, then the
//! overrides), the frame times, the loop and the foam pre-roll.

use std::path::Path;

use ocean_fft::{CascadeConfig, OceanConfig, SeaState, Spectrum, SpectrumKind};

use crate::args::{self, SeaArgs, FPS_RANGE, TOLERANCE_RANGE};
use crate::error::CliError;

/// A seamless loop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Looping {
    /// The repeat period T in seconds, as the ocean's config holds it.
    pub period: f32,
    /// Frames per loop, T·fps (a whole number).
    pub frames: u32,
    /// Where T came from, as the user wrote it: `--loop` or `repeat_period (in --config)`.
    pub parameter: &'static str,
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
    /// Where the tiles (the cascades' lengths) came from: "from preset `storm`", "from
    /// --config FILE" or "given with --lengths".
    pub tiles_from: String,
    /// The overrides that changed the waves or the grids after the tiles were chosen, as
    /// the user gave them: "--wind 3 changed the sea", "--size 32 changed the grids".
    pub overrides: Vec<String>,
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

/// The spectrum with the overrides applied: `--wind` and `--fetch` make it a JONSWAP of that
/// fetch law, every other parameter as the base spectrum had it.
fn override_spectrum(base: Spectrum, args: &SeaArgs) -> Result<Spectrum, CliError> {
    let mut spectrum = base.clone();
    if args.wind.is_some() || args.fetch.is_some() {
        let mut params = base.params();
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
        let Some(gamma) = base.gamma() else {
            return Err(CliError::usage(format!(
                "{name} {value}: the spectrum is a Phillips spectrum, which has no fetch law"
            )));
        };
        params.wind_speed = args.wind.unwrap_or(params.wind_speed);
        params.kind = SpectrumKind::Jonswap { fetch, gamma };
        spectrum = flag(name, value, Spectrum::from_params(&params))?;
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

/// A number in a closed range, or an error naming `name` that states the range as
/// `text`, the words of the option's `--help`.
fn in_range(name: &str, value: f64, (min, max): (f64, f64), text: &str) -> Result<f64, CliError> {
    if value.is_finite() && (min..=max).contains(&value) {
        Ok(value)
    } else {
        Err(CliError::usage(format!("{name} {value}: expected {text}")))
    }
}

/// `--lengths`, checked as the library checks `OceanConfig::lengths`, the error naming the
/// flag.
fn check_lengths(lengths: &[f32]) -> Result<(), CliError> {
    let count_ok = (1..=OceanConfig::MAX_CASCADES).contains(&lengths.len());
    let each_ok = lengths
        .iter()
        .all(|l| (CascadeConfig::MIN_LENGTH..=CascadeConfig::MAX_LENGTH).contains(l));
    let decreasing = lengths.windows(2).all(|w| w[1] < w[0]);
    if count_ok && each_ok && decreasing {
        return Ok(());
    }
    let text: Vec<String> = lengths.iter().map(f32::to_string).collect();
    Err(CliError::usage(format!(
        "--lengths {}: expected {}",
        text.join(","),
        args::lengths_rule()
    )))
}

/// Builds the sea from the arguments.
///
/// # Errors
/// [`CliError`] of kind `Usage` naming the flag for a bad override, frame rate, loop or
/// tolerance; of kind `Config` for an unreadable or invalid `--config` file or a config the
/// library refuses.
pub fn build(args: &SeaArgs) -> Result<Sea, CliError> {
    let (spectrum, mut config, name, mut tiles_from) =
        match (&args.source.preset, &args.source.config) {
            (Some(preset), _) => {
                let state = SeaState::ALL
                    .into_iter()
                    .find(|s| s.name() == preset)
                    .ok_or_else(|| CliError::usage(format!("--preset {preset}: unknown preset")))?;
                let (spectrum, config) = state.build();
                let name = state.name().to_string();
                let tiles = format!("from preset `{name}`");
                (spectrum, config, name, tiles)
            }
            (None, Some(path)) => {
                let (spectrum, config) = read_config(path)?;
                let stem = path
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_else(|| "ocean".into());
                let tiles = format!("from --config {}", path.display());
                (spectrum, config, stem, tiles)
            }
            (None, None) => {
                return Err(CliError::usage(
                    "give the sea with --preset NAME or --config FILE.json",
                ))
            }
        };
    let spectrum = override_spectrum(spectrum, args)?;
    let mut overrides = Vec::new();
    for (flag, value) in [
        ("--wind", args.wind),
        ("--fetch", args.fetch),
        ("--depth", args.depth),
    ] {
        if let Some(v) = value {
            overrides.push(format!("{flag} {v} changed the sea"));
        }
    }
    if let Some(size) = args.size {
        if !(CascadeConfig::MIN_SIZE..=CascadeConfig::MAX_SIZE).contains(&size) || size % 2 != 0 {
            return Err(CliError::usage(format!(
                "--size {size}: expected {}",
                args::size_range()
            )));
        }
        config.size = size;
        overrides.push(format!("--size {size} changed the grids"));
    }
    if let Some(lengths) = &args.lengths {
        check_lengths(lengths)?;
        config.lengths.clone_from(lengths);
        tiles_from = "given with --lengths".into();
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
    let fps = in_range(
        "--fps",
        args.fps,
        FPS_RANGE,
        &args::range_text(FPS_RANGE.0, FPS_RANGE.1),
    )?;
    let tolerance = in_range(
        "--foam-tolerance",
        args.foam_tolerance,
        TOLERANCE_RANGE,
        &args::range_text(TOLERANCE_RANGE.0, TOLERANCE_RANGE.1),
    )?;
    if args.anchor_every == 0 {
        return Err(CliError::usage(
            "--anchor-every 0: expected at least 1 frame",
        ));
    }

    // The loop: from --loop, else from the config file's repeat period.
    let (period, parameter) = match (args.loop_seconds, config.repeat_period) {
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
            let t = in_range(parameter, t, range, &args::loop_range())?;
            let frames = t * fps;
            let whole = frames.round();
            if whole < 1.0 || (frames - whole).abs() > 1e-6 * whole || whole > f64::from(u32::MAX) {
                return Err(CliError::usage(format!(
                    "{parameter} {t}: a loop must last a whole number of frames at --fps {fps} \
                     ({t} s × {fps} fps = {frames} frames)"
                )));
            }
            config.repeat_period = Some(t as f32);
            Some(Looping {
                period: t as f32,
                frames: whole as u32,
                parameter,
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
        tiles_from,
        overrides,
    })
}
