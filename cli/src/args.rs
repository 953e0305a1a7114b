//! The command line: `ocean-fft bake …` and `ocean-fft info …`.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};
use ocean_fft::{CascadeConfig, OceanConfig, SeaState};

use crate::frames::FrameList;

/// Accepted frames per second.
pub const FPS_RANGE: (f64, f64) = (0.1, 1000.0);
/// Accepted foam tolerances.
pub const TOLERANCE_RANGE: (f64, f64) = (1e-6, 0.1);
/// Accepted numbers of encoder threads.
pub const ENCODERS_RANGE: (usize, usize) = (1, 256);

/// The accepted range of an option as its `--help` and its error both state it:
/// "`min` to `max`".
pub fn range_text(min: impl std::fmt::Display, max: impl std::fmt::Display) -> String {
    format!("{min} to {max}")
}

/// `--size`'s range: what the library accepts.
pub fn size_range() -> String {
    format!(
        "even, {}",
        range_text(CascadeConfig::MIN_SIZE, CascadeConfig::MAX_SIZE)
    )
}

/// `--loop`'s range in seconds: the library's repeat periods.
pub fn loop_range() -> String {
    range_text(
        CascadeConfig::MIN_REPEAT_PERIOD,
        CascadeConfig::MAX_REPEAT_PERIOD,
    )
}

/// `--lengths`' rule: the library's checks of `OceanConfig::lengths`.
pub fn lengths_rule() -> String {
    format!(
        "{} tile sides in metres, each {}, largest first, strictly decreasing",
        range_text(1, OceanConfig::MAX_CASCADES),
        range_text(CascadeConfig::MIN_LENGTH, CascadeConfig::MAX_LENGTH)
    )
}

/// The preset names, for clap's value check and its `--help`.
pub fn preset_names() -> clap::builder::PossibleValuesParser {
    clap::builder::PossibleValuesParser::new(SeaState::ALL.map(SeaState::name))
}

/// The exit codes, as `--help` lists them.
pub const EXIT_CODES: &str = "\
Exit codes:
  0  success (also when every frame already existed and was skipped)
  1  internal error (a bug: please report it)
  2  bad command line: unknown option, bad value, bad frame list, inconsistent options
  3  bad sea configuration: the --config file cannot be read or parsed, or a parameter in it
     (or one an override produced) is out of range
  4  an output file or directory could not be written (permissions, disk full)
  5  --out holds a bake with other parameters (its sidecar JSON differs; the message names
     the parameters that differ); use another directory, or --overwrite to replace it";

/// Bakes an FFT ocean (ocean-fft) into texture sequences for tools, engines and render farms.
///
/// `ocean-fft info --preset fresh_breeze` describes a sea; `ocean-fft bake --preset
/// fresh_breeze --frames 1-120 --out bake/` writes one half-float OpenEXR per frame and
/// cascade with displacement, normal, Jacobian and foam, and a JSON sidecar that says how to
/// decode them. Frame f's content depends only on the parameters and f, so a render farm
/// may split the frame list across machines and resume interrupted bakes.
#[derive(Debug, Parser)]
#[command(name = "ocean-fft", version, after_help = EXIT_CODES, max_term_width = 100)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Bake frames: EXR (or PNG) files per frame and cascade, plus a JSON sidecar.
    #[command(after_help = EXIT_CODES)]
    Bake(BakeArgs),
    /// Describe a sea without baking: Hs, Tp, cascades, bands, memory, loop error.
    #[command(after_help = EXIT_CODES)]
    Info(InfoArgs),
}

/// The sea: where it comes from, and the overrides.
#[derive(Debug, Clone, Args)]
#[group(id = "source", required = true, multiple = false)]
pub struct Source {
    /// A named sea state: calm, moderate_breeze, fresh_breeze, storm, swell, shallow_bay.
    #[arg(long, value_name = "NAME", value_parser = preset_names())]
    pub preset: Option<String>,
    /// A JSON file with the keys "spectrum" and "config" (as ocean-fft's serde writes them;
    /// a bake's sidecar JSON is such a file).
    #[arg(long, value_name = "FILE.json")]
    pub config: Option<PathBuf>,
}

/// Everything that decides the content of the frames.
#[derive(Debug, Clone, Args)]
pub struct SeaArgs {
    /// Where the sea comes from.
    #[command(flatten)]
    pub source: Source,
    /// Override: wind speed U10 in m/s (rebuilds the spectrum with the fetch law; needs
    /// --fetch if the spectrum has no fetch).
    #[arg(
        long,
        value_name = "M/S",
        allow_negative_numbers = true,
        help_heading = "Overrides"
    )]
    pub wind: Option<f32>,
    /// Override: fetch in metres (rebuilds the spectrum with the fetch law).
    #[arg(
        long,
        value_name = "M",
        allow_negative_numbers = true,
        help_heading = "Overrides"
    )]
    pub fetch: Option<f32>,
    /// Override: water depth in metres (finite-depth dispersion; a TMA spectrum's depth
    /// factor follows).
    #[arg(
        long,
        value_name = "M",
        allow_negative_numbers = true,
        help_heading = "Overrides"
    )]
    pub depth: Option<f32>,
    /// Override: the direction the wind blows toward, in degrees from +x toward +z.
    #[arg(
        long,
        value_name = "D",
        allow_negative_numbers = true,
        help_heading = "Overrides"
    )]
    pub direction_deg: Option<f32>,
    /// Override: grid size N of every cascade ([`size_range`]).
    #[arg(long, value_name = "N", help_heading = "Overrides", help = format!(
        "Override: grid size N of every cascade ({}; presets use 256; at 4096² the default \
         memory limit, 4 GiB, admits one cascade)",
        size_range()
    ))]
    pub size: Option<usize>,
    /// Override: the cascades' tile sides in metres ([`lengths_rule`]).
    #[arg(
        long,
        value_name = "L0,L1,…",
        value_delimiter = ',',
        allow_negative_numbers = true,
        help_heading = "Overrides",
        help = format!(
            "Override: the cascades' tiles, comma-separated ({}; presets use three, the \
             largest about 12 peak wavelengths)",
            lengths_rule()
        )
    )]
    pub lengths: Option<Vec<f32>>,
    /// Override: choppiness λ ≥ 0 (horizontal displacement; presets use 0.8 to 1.2).
    #[arg(
        long,
        value_name = "L",
        allow_negative_numbers = true,
        help_heading = "Overrides"
    )]
    pub choppiness: Option<f32>,
    /// Override: the random seed (cascade c uses seed + c).
    #[arg(long, value_name = "S", help_heading = "Overrides")]
    pub seed: Option<u64>,
    /// Frames per second: frame f shows time t = f / fps ([`FPS_RANGE`]).
    #[arg(long, value_name = "F", default_value_t = 30.0, allow_negative_numbers = true, help = format!(
        "Frames per second: frame f shows time t = f / fps ({})",
        range_text(FPS_RANGE.0, FPS_RANGE.1)
    ))]
    pub fps: f64,
    /// Make a seamless loop of this many seconds ([`loop_range`]).
    #[arg(long = "loop", value_name = "SECONDS", allow_negative_numbers = true, help = format!(
        "Make a seamless loop of this many seconds ({}, a whole number of frames at --fps; \
         at least twice the sea's peak period looks natural): frame f shows the same as \
         frame f + loop·fps, foam included",
        loop_range()
    ))]
    pub loop_seconds: Option<f64>,
    /// Foam pre-roll tolerance ([`TOLERANCE_RANGE`]).
    #[arg(
        long,
        value_name = "EPS",
        default_value_t = 1e-3,
        help_heading = "Foam pre-roll",
        help = format!(
            "Foam pre-roll tolerance: how far the foam may be from that of an ocean simulated \
             forever (the pre-roll is long enough for its decay to reach this; {})",
            range_text(TOLERANCE_RANGE.0, TOLERANCE_RANGE.1)
        )
    )]
    pub foam_tolerance: f64,
    /// Foam anchors (at least 1): the foam of frame f is simulated from the anchor frame
    /// a ≤ f (a multiple of this) minus the pre-roll, so a farm chunk that starts on an
    /// anchor pays one pre-roll. Ignored for loops.
    #[arg(
        long,
        value_name = "FRAMES",
        default_value_t = 240,
        help_heading = "Foam pre-roll"
    )]
    pub anchor_every: u32,
}

/// File formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// OpenEXR, half float, ZIP: one file per frame and cascade with every channel.
    Exr,
    /// 16-bit RGBA PNG: two files per frame and cascade (displacement+foam, normal+Jacobian),
    /// scales in the sidecar.
    Png,
}

/// `ocean-fft bake`.
#[derive(Debug, Clone, Args)]
pub struct BakeArgs {
    /// The sea and the frame times.
    #[command(flatten)]
    pub sea: SeaArgs,
    /// Frames to write, render-farm syntax: `1-100`, `1-3,5,7-20:2` (every 2nd from 7 to
    /// 20), `0-238x2`.
    #[arg(long, value_name = "RANGE")]
    pub frames: FrameList,
    /// File format.
    #[arg(long, value_enum, default_value_t = Format::Exr)]
    pub format: Format,
    /// Output directory (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Rewrite frames that exist (default: skip them, so an interrupted bake resumes), and
    /// replace a sidecar with other parameters.
    #[arg(long)]
    pub overwrite: bool,
    /// Base of the file names (default: the preset's name, or the config file's stem).
    #[arg(long, value_name = "NAME")]
    pub name: Option<String>,
    /// Encoder threads ([`ENCODERS_RANGE`]; default: the number of CPUs).
    #[arg(long, value_name = "N", help = format!(
        "Encoder threads ({}; default: the number of CPUs)",
        range_text(ENCODERS_RANGE.0, ENCODERS_RANGE.1)
    ))]
    pub encoders: Option<usize>,
}

/// `ocean-fft info`.
#[derive(Debug, Clone, Args)]
pub struct InfoArgs {
    /// The sea and the frame times.
    #[command(flatten)]
    pub sea: SeaArgs,
    /// For a loop: also pre-roll the foam as a bake does and print how it converged (takes
    /// as long as simulating several loops).
    #[arg(long)]
    pub measure_foam: bool,
}
