//! The command line.

use glam::Vec3;

use crate::gpu::RenderSettings;
use crate::light::LightSettings;
use crate::sea::SeaParams;

const HELP: &str = "\
ocean-fft-viewer: the ocean in real time (winit + wgpu + egui)

USAGE: ocean-fft-viewer [OPTIONS]

  --preset NAME        default (JONSWAP 10 m/s, 100 km), calm, moderate_breeze, fresh_breeze,
                       storm, swell, shallow_bay                           [default]
  --choppiness X       choppiness λ instead of the preset's
  --foam X             foam coverage multiplier instead of the preset's (1)
  --frames N           render N frames, then exit (headless runs; a fixed 1/30 s of sea time
                       a frame) and print `frames N, mean frame … ms, step … ms, upload … ms`
  --screenshot FILE    with --frames: write the last frame as a PNG
  --width W --height H window (and screenshot) size in pixels              [1280 720]
  --camera X,Y,Z       the eye in metres                                   [0, 2 m + 1.5 Hs, 0]
  --heading DEG        view direction, degrees from +x toward +z           [20]
  --pitch DEG          up (+) or down (−) from the horizontal              [-6]
  --fov DEG            vertical field of view                              [50]
  --sun ELEV,AZIM      sun elevation and azimuth in degrees                [14,30]
  --overcast X         0 clear … 1 heavy overcast          [0; 0.85 for the storm preset]
  --exposure X         exposure before the tone curve                      [0.8]
  --haze M             haze distance of a clear day, m                     [6000]
  --time T             sea time of the first frame, s                      [60]
  --pre-roll S         seconds of foam spin-up before it                   [20]
  --time-scale X       sea seconds per real second                         [1]
  --tiling X           strength of the tiling breaker, 0 … 1               [1]
  --msaa N             samples per pixel: 1 or 4      [4; 1 on a software rasteriser]
  --anisotropy N       anisotropic filtering, 1 … 16 [16; 1 on a software rasteriser]
  --mesh M             clipmap ring half-width in cells (even, 8 … 256)    [64]
  --threads N          threads of the simulation's pool                    [2]
  --no-bodies          no buoys or boats
  --hide-ui            start without the panels (Tab toggles them)
  --no-vsync           do not wait for the display's refresh
  --help               this text
";

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
    /// `None`: chosen by the adapter (see [`Options::msaa_for`]).
    pub msaa: Option<u32>,
    pub anisotropy: Option<u16>,
    pub mesh: u32,
    pub threads: usize,
    pub bodies: bool,
    pub hide_ui: bool,
    pub vsync: bool,
}

fn number<T: std::str::FromStr>(name: &str, value: Option<String>) -> Result<T, String> {
    let value = value.ok_or_else(|| format!("{name} needs a value"))?;
    value
        .trim()
        .parse()
        .map_err(|_| format!("{name}: {value:?} is not a valid number"))
}

fn list<const K: usize>(name: &str, value: Option<String>) -> Result<[f32; K], String> {
    let value = value.ok_or_else(|| format!("{name} needs a value"))?;
    let parts: Vec<&str> = value.split(',').collect();
    if parts.len() != K {
        return Err(format!(
            "{name}: expected {K} numbers separated by commas, got {value:?}"
        ));
    }
    let mut out = [0.0; K];
    for (o, p) in out.iter_mut().zip(parts) {
        *o = p
            .trim()
            .parse()
            .ok()
            .filter(|v: &f32| v.is_finite())
            .ok_or_else(|| format!("{name}: {p:?} is not a finite number"))?;
    }
    Ok(out)
}

fn check<T: PartialOrd + std::fmt::Display + Copy>(
    name: &str,
    value: T,
    min: T,
    max: T,
) -> Result<T, String> {
    if value >= min && value <= max {
        Ok(value)
    } else {
        Err(format!("{name} = {value} is out of range [{min}, {max}]"))
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

    /// Parses the arguments; `None` after printing the help.
    pub fn parse(args: impl Iterator<Item = String>) -> Result<Option<Options>, String> {
        let mut args = args.peekable();
        let mut preset = "default".to_string();
        let (mut choppiness, mut foam) = (None, None);
        let mut frames = None;
        let mut screenshot = None;
        let (mut width, mut height) = (1280u32, 720u32);
        let mut camera = None;
        let (mut heading, mut pitch, mut fov) = (20.0f32, -6.0f32, 50.0f32);
        let mut light = LightSettings::default();
        let mut overcast = None;
        let mut render = RenderSettings::default();
        let (mut time, mut pre_roll, mut time_scale) = (60.0f64, 20.0f64, 1.0f32);
        let (mut msaa, mut anisotropy, mut mesh, mut threads) = (None, None, 64u32, 2usize);
        let (mut bodies, mut hide_ui, mut vsync) = (true, false, true);
        while let Some(arg) = args.next() {
            let name = arg.as_str();
            match name {
                "--help" | "-h" => {
                    print!("{HELP}");
                    return Ok(None);
                }
                "--preset" => preset = args.next().ok_or("--preset needs a name")?,
                "--choppiness" => {
                    choppiness = Some(check(name, number(name, args.next())?, 0.0, 5.0)?)
                }
                "--foam" => foam = Some(check(name, number(name, args.next())?, 0.0, 100.0)?),
                "--frames" => {
                    frames = Some(check(
                        name,
                        number::<usize>(name, args.next())?,
                        1,
                        1_000_000,
                    )?)
                }
                "--screenshot" => {
                    screenshot = Some(args.next().ok_or("--screenshot needs a file")?.into())
                }
                "--width" => width = check(name, number(name, args.next())?, 16, 8192)?,
                "--height" => height = check(name, number(name, args.next())?, 16, 8192)?,
                "--camera" => camera = Some(Vec3::from_array(list::<3>(name, args.next())?)),
                "--heading" => heading = check(name, number(name, args.next())?, -3600.0, 3600.0)?,
                "--pitch" => pitch = check(name, number(name, args.next())?, -89.0, 89.0)?,
                "--fov" => fov = check(name, number(name, args.next())?, 5.0, 150.0)?,
                "--sun" => {
                    let [e, a] = list::<2>(name, args.next())?;
                    light.elevation = check("--sun elevation", e, -10.0, 90.0)?;
                    light.azimuth = a;
                }
                "--overcast" => overcast = Some(check(name, number(name, args.next())?, 0.0, 1.0)?),
                "--exposure" => {
                    light.exposure = check(name, number(name, args.next())?, 0.01, 100.0)?
                }
                "--haze" => light.haze = check(name, number(name, args.next())?, 10.0, 1e6)?,
                "--time" => time = check(name, number(name, args.next())?, 0.0, 1e8)?,
                "--pre-roll" => pre_roll = check(name, number(name, args.next())?, 0.0, 600.0)?,
                "--time-scale" => time_scale = check(name, number(name, args.next())?, 0.0, 100.0)?,
                "--tiling" => render.tiling = check(name, number(name, args.next())?, 0.0, 1.0)?,
                "--msaa" => {
                    let samples: u32 = number(name, args.next())?;
                    if samples != 1 && samples != 4 {
                        return Err(format!("--msaa = {samples}: 1 or 4"));
                    }
                    msaa = Some(samples);
                }
                "--anisotropy" => {
                    anisotropy = Some(check(name, number(name, args.next())?, 1, 16)?)
                }
                "--mesh" => {
                    mesh = check(name, number(name, args.next())?, 8, 256)?;
                    if mesh % 2 != 0 {
                        return Err(format!("--mesh = {mesh} must be even"));
                    }
                }
                "--threads" => threads = check(name, number(name, args.next())?, 1, 64)?,
                "--no-bodies" => bodies = false,
                "--hide-ui" => hide_ui = true,
                "--no-vsync" => vsync = false,
                other => return Err(format!("unknown option {other:?}")),
            }
        }
        if screenshot.is_some() && frames.is_none() {
            return Err("--screenshot needs --frames N".into());
        }
        let mut sea = SeaParams::preset(&preset).ok_or_else(|| {
            format!(
                "--preset: unknown {preset:?} ({})",
                SeaParams::preset_names().join(", ")
            )
        })?;
        sea.choppiness = choppiness.unwrap_or(sea.choppiness);
        sea.foam_coverage = foam.unwrap_or(sea.foam_coverage);
        light.overcast = overcast.unwrap_or(if preset == "storm" { 0.85 } else { 0.0 });
        let hs = sea
            .spectrum()
            .map_err(|e| e.to_string())?
            .significant_wave_height();
        Ok(Some(Options {
            sea,
            frames,
            screenshot,
            width,
            height,
            camera: camera.unwrap_or_else(|| crate::default_eye(hs)),
            heading,
            pitch,
            fov,
            light,
            render,
            time,
            pre_roll,
            time_scale,
            msaa,
            anisotropy,
            mesh,
            threads,
            bodies,
            hide_ui,
            vsync,
        }))
    }
}
