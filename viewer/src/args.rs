//! The command line, parsed by clap: `Cli` is what the user types, [`Options`] what the
//! viewer runs with (the preset's sea with its overrides, the light, the defaults that depend
//! on the sea).

use std::fmt;
use std::path::PathBuf;
use std::str::FromStr;

use clap::builder::PossibleValuesParser;
use clap::error::ErrorKind;
use clap::{CommandFactory, Parser};
use glam::Vec3;
use ocean_fft_render::CoastKind;

use crate::gpu::RenderSettings;
use crate::light::LightSettings;
use crate::sea::SeaParams;

/// Everything the command line sets.
#[derive(Debug, Clone)]
pub struct Options {
    pub sea: SeaParams,
    pub frames: Option<usize>,
    pub screenshot: Option<std::path::PathBuf>,
    pub width: u32,
    pub height: u32,
    pub camera: Vec3,
    pub heading: f32,
    pub pitch: f32,
    pub fov: f32,
    pub light: LightSettings,
    pub render: RenderSettings,
    pub time: f64,
    pub pre_roll: f64,
    pub time_scale: f32,
    /// `None`: chosen by the adapter (see [`Options::quality_for`]).
    pub msaa: Option<u32>,
    pub anisotropy: Option<u16>,
    pub mesh: u32,
    pub threads: usize,
    pub bodies: bool,
    /// The boats' speed, m/s (0: moored).
    pub boat_speed: f32,
    /// The camera moves with the first boat.
    pub follow: bool,
    /// The camera rides the first boat's stern, looking back along its track.
    pub deck: bool,
    pub hide_ui: bool,
    pub vsync: bool,
    /// The coast drawn (a depth map and its ground), `None` for the open sea.
    pub coast: Option<CoastKind>,
}

/// ocean-fft-viewer: the ocean in real time (winit + wgpu + egui).
#[derive(Debug, Parser)]
#[command(
    name = "ocean-fft-viewer",
    after_help = "viewer/README.md lists the mouse and keyboard controls.",
    max_term_width = 100,
    args_override_self = true,
    allow_negative_numbers = true
)]
struct Cli {
    /// Sea state: `default` is JONSWAP at U10 = 10 m/s over a 100 km fetch.
    #[arg(
        long,
        value_name = "NAME",
        default_value = "default",
        value_parser = PossibleValuesParser::new(SeaParams::preset_names())
    )]
    preset: String,
    /// Choppiness λ (horizontal displacement scale), 0 to 5 [default: the preset's].
    #[arg(long, value_name = "X", value_parser = within(0.0f32, 5.0))]
    choppiness: Option<f32>,
    /// Foam coverage multiplier, 0 to 100 [default: the preset's, 1].
    #[arg(long, value_name = "X", value_parser = within(0.0f32, 100.0))]
    foam: Option<f32>,
    /// Render N frames (1/30 s of sea time each), print their mean times, then exit.
    #[arg(long, value_name = "N", value_parser = within(1usize, 1_000_000))]
    frames: Option<usize>,
    /// With --frames: write the last frame as a PNG.
    #[arg(long, value_name = "FILE", requires = "frames")]
    screenshot: Option<PathBuf>,
    /// Window (and screenshot) width in pixels, 16 to 8192.
    #[arg(long, value_name = "W", default_value_t = 1280, value_parser = within(16u32, 8192))]
    width: u32,
    /// Window (and screenshot) height in pixels, 16 to 8192.
    #[arg(long, value_name = "H", default_value_t = 720, value_parser = within(16u32, 8192))]
    height: u32,
    /// The eye in metres, y up [default: 0, 2 m + 1.5 Hs (at most 12 m), 0].
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = numbers::<3>)]
    camera: Option<Numbers<3>>,
    /// View direction in degrees from +x toward +z, -3600 to 3600.
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 20.0,
        allow_hyphen_values = true,
        value_parser = within(-3600.0f32, 3600.0)
    )]
    heading: f32,
    /// Pitch in degrees, up (+) or down (-) from the horizontal, -89 to 89.
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = -6.0,
        allow_hyphen_values = true,
        value_parser = within(-89.0f32, 89.0)
    )]
    pitch: f32,
    /// Vertical field of view in degrees, 5 to 150.
    #[arg(long, value_name = "DEG", default_value_t = 50.0, value_parser = within(5.0f32, 150.0))]
    fov: f32,
    /// Sun elevation (-10 to 90) and azimuth (from +x toward +z), degrees.
    #[arg(
        long,
        value_name = "ELEV,AZIM",
        allow_hyphen_values = true,
        value_parser = sun,
        default_value_t = default_sun()
    )]
    sun: Numbers<2>,
    /// Overcast, 0 clear to 1 heavy overcast [default: 0; 0.85 for the storm preset].
    #[arg(long, value_name = "X", value_parser = within(0.0f32, 1.0))]
    overcast: Option<f32>,
    /// Exposure before the tone curve (a factor), 0.01 to 100.
    #[arg(
        long,
        value_name = "X",
        default_value_t = LightSettings::default().exposure,
        value_parser = within(0.01f32, 100.0)
    )]
    exposure: f32,
    /// Haze distance of a clear day in metres, 10 to 1000000.
    #[arg(
        long,
        value_name = "M",
        default_value_t = LightSettings::default().haze,
        value_parser = within(10.0f32, 1e6)
    )]
    haze: f32,
    /// Sea time of the first frame in seconds, 0 to 100000000.
    #[arg(long, value_name = "T", default_value_t = 60.0, value_parser = within(0.0f64, 1e8))]
    time: f64,
    /// Seconds of foam spin-up before the first frame, 0 to 600.
    #[arg(long, value_name = "S", default_value_t = 20.0, value_parser = within(0.0f64, 600.0))]
    pre_roll: f64,
    /// Sea seconds per real second, 0 to 100.
    #[arg(long, value_name = "X", default_value_t = 1.0, value_parser = within(0.0f32, 100.0))]
    time_scale: f32,
    /// Strength of the tiling breaker, 0 (off) to 1.
    #[arg(
        long,
        value_name = "X",
        default_value_t = RenderSettings::default().tiling,
        value_parser = within(0.0f32, 1.0)
    )]
    tiling: f32,
    /// Samples per pixel, 1 or 4 [default: 4; 1 on a software rasteriser].
    #[arg(long, value_name = "N", value_parser = msaa)]
    msaa: Option<u32>,
    /// Anisotropic filtering in samples, 1 to 16 [default: 16; 1 on a software rasteriser].
    #[arg(long, value_name = "N", value_parser = within(1u16, 16))]
    anisotropy: Option<u16>,
    /// Clipmap ring half-width in cells, even, 8 to 256.
    #[arg(long, value_name = "M", default_value_t = 64, value_parser = mesh)]
    mesh: u32,
    /// Threads of the simulation's pool, 1 to 64.
    #[arg(long, value_name = "N", default_value_t = 2, value_parser = within(1usize, 64))]
    threads: usize,
    /// No buoys or boats.
    #[arg(long)]
    no_bodies: bool,
    /// The boats make no wakes (with boats, the sea has a wake window around the camera).
    #[arg(long)]
    no_wakes: bool,
    /// The boats' speed ahead in m/s, 0 (moored) to 20.
    #[arg(long, value_name = "M/S", default_value_t = 0.0, value_parser = within(0.0f32, 20.0))]
    boat_speed: f32,
    /// The camera moves with the first boat (keeps its offset from it).
    #[arg(long)]
    follow_boat: bool,
    /// The camera rides the first boat: 3 m above its stern, looking back along its track
    /// (--pitch and --fov still apply; --camera and --heading do not).
    #[arg(long)]
    on_deck: bool,
    /// A coast: `island` (a beach and a bay facing the waves, 250 m ahead of the default
    /// coast eye) or `breakwater` (a beach sheltered by a wall), drawn with its ground; the
    /// waves shrink and break over it (a 256² depth map, solved in about a second at the
    /// start and again after a change of weather). With a coast, --camera defaults to a view
    /// of it (pair it with --heading and --pitch: island 28, -11; breakwater 42, -13).
    #[arg(
        long,
        value_name = "NAME",
        default_value = "none",
        value_parser = PossibleValuesParser::new(["none", "island", "breakwater"])
    )]
    coast: String,
    /// Start without the panels (Tab toggles them).
    #[arg(long)]
    hide_ui: bool,
    /// Do not wait for the display's refresh.
    #[arg(long)]
    no_vsync: bool,
}

/// `K` numbers separated by commas, each finite (`--camera X,Y,Z`, `--sun ELEV,AZIM`); shown
/// as it is typed (help's defaults).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Numbers<const K: usize>([f32; K]);

impl<const K: usize> fmt::Display for Numbers<K> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, v) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(",")?;
            }
            write!(f, "{v}")?;
        }
        Ok(())
    }
}

/// The value parser of [`Numbers`].
fn numbers<const K: usize>(text: &str) -> Result<Numbers<K>, String> {
    let parts: Vec<&str> = text.split(',').collect();
    if parts.len() != K {
        return Err(format!("expected {K} numbers separated by commas"));
    }
    let mut out = [0.0; K];
    for (o, p) in out.iter_mut().zip(parts) {
        *o = p
            .trim()
            .parse()
            .ok()
            .filter(|v: &f32| v.is_finite())
            .ok_or_else(|| format!("{:?} is not a finite number", p.trim()))?;
    }
    Ok(Numbers(out))
}

/// `value` if it lies from `min` to `max` inclusive (NaN does not).
fn in_range<T: PartialOrd + fmt::Display>(value: T, min: T, max: T) -> Result<T, String> {
    if value >= min && value <= max {
        Ok(value)
    } else {
        Err(format!("{value} is out of range [{min}, {max}]"))
    }
}

/// A value parser of numbers from `min` to `max` inclusive.
fn within<T>(min: T, max: T) -> impl Fn(&str) -> Result<T, String> + Clone + Send + Sync + 'static
where
    T: FromStr + PartialOrd + fmt::Display + Copy + Send + Sync + 'static,
{
    move |text| {
        let value: T = text
            .trim()
            .parse()
            .map_err(|_| "not a valid number".to_string())?;
        in_range(value, min, max)
    }
}

/// `--sun`: the elevation from -10 to 90 degrees, any finite azimuth.
fn sun(text: &str) -> Result<Numbers<2>, String> {
    let angles = numbers::<2>(text)?;
    in_range(angles.0[0], -10.0, 90.0).map_err(|e| format!("the elevation {e}"))?;
    Ok(angles)
}

/// `--sun`'s default: the light panel's.
fn default_sun() -> Numbers<2> {
    let light = LightSettings::default();
    Numbers([light.elevation, light.azimuth])
}

/// `--msaa`: the sample counts the renderer supports.
fn msaa(text: &str) -> Result<u32, String> {
    match within(1u32, 4)(text)? {
        samples @ (1 | 4) => Ok(samples),
        samples => Err(format!("{samples} samples: 1 or 4")),
    }
}

/// `--mesh`: an even half-width from 8 to 256 cells.
fn mesh(text: &str) -> Result<u32, String> {
    let cells = within(8u32, 256)(text)?;
    if cells % 2 == 0 {
        Ok(cells)
    } else {
        Err(format!("{cells} is odd: the half-width must be even"))
    }
}

impl Options {
    /// Samples per pixel and anisotropy on an adapter: a software rasteriser (llvmpipe,
    /// lavapipe, WARP) spends 5–6 times longer per pixel with 8× anisotropic filtering than
    /// with trilinear filtering, so it gets neither unless asked.
    pub fn quality_for(&self, device_type: wgpu::DeviceType) -> (u32, u16) {
        let software = device_type == wgpu::DeviceType::Cpu;
        (
            self.msaa.unwrap_or(if software { 1 } else { 4 }),
            self.anisotropy.unwrap_or(if software { 1 } else { 16 }),
        )
    }

    /// The options of the process's arguments. After `--help` it prints the help and exits
    /// with code 0; on a bad command line it prints clap's error (which names the flag) and
    /// exits with code 2.
    pub fn parse() -> Options {
        Options::try_parse_from(std::env::args_os()).unwrap_or_else(|e| e.exit())
    }

    /// The options of `args` (the program's name first), or clap's error: a bad command line,
    /// or `--help` (`ErrorKind::DisplayHelp`, whose `exit` prints the help).
    pub fn try_parse_from<I, T>(args: I) -> Result<Options, clap::Error>
    where
        I: IntoIterator<Item = T>,
        T: Into<std::ffi::OsString> + Clone,
    {
        Options::from_cli(Cli::try_parse_from(args)?)
    }

    fn from_cli(cli: Cli) -> Result<Options, clap::Error> {
        // The value parser admits only these names.
        let mut sea = SeaParams::preset(&cli.preset).ok_or_else(|| {
            Cli::command().error(
                ErrorKind::InvalidValue,
                format!("--preset: unknown {:?}", cli.preset),
            )
        })?;
        sea.choppiness = cli.choppiness.unwrap_or(sea.choppiness);
        sea.foam_coverage = cli.foam.unwrap_or(sea.foam_coverage);
        sea.wakes = !cli.no_bodies && !cli.no_wakes;
        let hs = sea
            .spectrum()
            .map_err(|e| Cli::command().error(ErrorKind::ValueValidation, e))?
            .significant_wave_height();
        let coast = match cli.coast.as_str() {
            "none" => None,
            name => Some(CoastKind::from_str(name).map_err(|e| {
                Cli::command().error(ErrorKind::InvalidValue, format!("--coast: {e}"))
            })?),
        };
        let [elevation, azimuth] = cli.sun.0;
        let light = LightSettings {
            elevation,
            azimuth,
            overcast: cli
                .overcast
                .unwrap_or(if cli.preset == "storm" { 0.85 } else { 0.0 }),
            exposure: cli.exposure,
            haze: cli.haze,
        };
        Ok(Options {
            sea,
            frames: cli.frames,
            screenshot: cli.screenshot,
            width: cli.width,
            height: cli.height,
            camera: cli
                .camera
                .map(|c| Vec3::from_array(c.0))
                .unwrap_or_else(|| match coast {
                    Some(coast) => Vec3::from_array(coast.view().0),
                    None => crate::default_eye(hs),
                }),
            heading: cli.heading,
            pitch: cli.pitch,
            fov: cli.fov,
            light,
            render: RenderSettings {
                tiling: cli.tiling,
                ..RenderSettings::default()
            },
            time: cli.time,
            pre_roll: cli.pre_roll,
            time_scale: cli.time_scale,
            msaa: cli.msaa,
            anisotropy: cli.anisotropy,
            mesh: cli.mesh,
            threads: cli.threads,
            bodies: !cli.no_bodies,
            boat_speed: cli.boat_speed,
            follow: cli.follow_boat,
            deck: cli.on_deck,
            hide_ui: cli.hide_ui,
            vsync: !cli.no_vsync,
            coast,
        })
    }
}

#[cfg(test)]
mod tests;
