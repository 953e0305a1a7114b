//! A shaded perspective picture of the displaced ocean surface, `out/render.png` (960×540 by
//! default), of the default sea or any preset, from a camera you place.
//!
//! ```text
//! cargo run --release -p ocean-fft-examples --example render -- --preset storm
//! cargo run --release -p ocean-fft-examples --example render -- --preset calm --camera 0,3,0 --heading 20 --pitch -8
//! ```
//!
//! Options (all optional; `--help` lists them):
//!
//! - `--preset NAME`: `default` (`Spectrum::jonswap(10.0, 100_000.0)` with
//!   `OceanConfig::default()`) or a `SeaState` name: `calm`, `moderate_breeze`,
//!   `fresh_breeze`, `storm`, `swell`, `shallow_bay`;
//! - `--camera X,Y,Z`: the eye in metres (default: 2 m + 1.5 H_s above the mean surface, at
//!   most 10 m, at the origin; the storm's at x = 150 m, z = −400 m, where its foam shows a
//!   breaking crest and streaks);
//! - `--heading DEG`: the view direction in degrees from +x (the wind direction) toward +z;
//!   `--pitch DEG`: up (positive) or down from the horizontal; `--fov DEG`: the horizontal
//!   field of view (default 70, the storm 55); an eye less than 1 m above the water under it
//!   is raised to 1 m above it;
//! - `--width`, `--height` in pixels; `--samples N`: N × N rays per pixel (default 2);
//! - `--time SECONDS` of the sea (default 30); `--exposure` (default 0.8); `--out FILE`;
//!   `--palette`: an indexed PNG of 256 colours (median cut), as the README's gallery uses.
//!
//! The sea is stepped for 4 s at 30 Hz up to the time so that foam builds up. Every ray is
//! marched against the displaced surface (the water height at a world point after
//! horizontal displacement, by two fixed-point steps of `OceanState::sample`; the converged
//! form is `OceanState::height_at`) and refined by bisection; the hit point is shaded from
//! `OceanState::surface_at` (normal and foam):
//!
//! - **Light that suits the sea.** Fair weather (every preset but the storm): a sun with a
//!   blue sky, whose reflection, glitter path and subsurface glow give the picture its
//!   contrast. Storm: an overcast sky (the CIE standard overcast sky's luminance, three times
//!   brighter at the zenith than at the horizon, Moon & Spencer 1942) under a cloud deck, no
//!   sun, dark slate water, low haze; the camera looks into the crests coming at it.
//! - **Foam** from the ocean's calibrated foam field (`OceanState::active_foam`,
//!   `residual_foam`), which holds how much of each cell of the largest cascade's grid
//!   (15.6 m for the storm) is covered: the picture puts the active whitecaps on the crests
//!   (the fraction a of the cell where the normalised height, broken up by noise, is highest)
//!   and the residual foam into thin streaks along the wind; a footprint wider than that
//!   detail sees the mean coverage.
//! - **Sub-grid roughness in the glint.** The sun's glitter is an anisotropic Gaussian
//!   slope distribution (Cox & Munk 1954) whose along- and across-wind variances are what the
//!   pixel does not resolve: the ocean's sub-grid slope variance
//!   (`OceanState::subgrid_slope_variance`, waves too small for the finest grid), plus the
//!   slope variance of the simulated waves too short for the pixel's footprint on the water
//!   (`Spectrum::slope_variance` from π/footprint to the finest grid's band edge).
//! - **Distance-aware filtering.** N × N rays per pixel, and each hit's resolved slope scaled
//!   down by the share of the slope variance its footprint cannot resolve, which moves into
//!   the glint's distribution above (the surface's total slope variance is kept): far water
//!   turns into a smooth, wide glitter path instead of speckle.
//! - **Tone mapping.** Linear radiance is exposed and mapped with the ACES filmic curve
//!   (Narkowicz's 2015 fit) to sRGB: highlights roll off instead of clipping to flat white.
//! - Schlick's Fresnel (water n = 1.33, F0 ≈ 0.02), a deep-water colour with a subsurface
//!   tint brighter on high crests, foam lit by the sky and the sun, haze to the horizon.
//!
//! Rows are rendered in parallel with rayon.

mod common;

use clap::Parser;
use glam::Vec3;
use ocean_fft::{OceanConfig, OceanState, SeaState, Spectrum, SurfaceSample};
use rayon::prelude::*;

use common::{out_dir, save_indexed, save_rgb8, Result};

/// Rays that have not hit the water this far out (m) end in the haze.
const FAR: f32 = 8000.0;

/// The light of a scene.
#[derive(Clone, Copy)]
struct Light {
    /// Unit vector toward the sun (fair weather) or `None` (overcast).
    sun: Option<Vec3>,
    /// Sun irradiance on a surface facing it (linear RGB).
    sun_colour: Vec3,
    /// Sky radiance at the zenith and at the horizon (linear RGB).
    zenith: Vec3,
    horizon: Vec3,
    /// Water colours: deep body and subsurface (crest) tint.
    deep: Vec3,
    subsurface: Vec3,
    /// Distance in metres over which the haze takes 63 % of the light.
    haze: f32,
}

impl Light {
    /// Sun at `elevation` (rad) and `azimuth` (rad from +x toward +z) with a clear blue sky.
    fn fair(azimuth: f32, elevation: f32) -> Light {
        Light {
            sun: Some(Vec3::new(
                elevation.cos() * azimuth.cos(),
                elevation.sin(),
                elevation.cos() * azimuth.sin(),
            )),
            sun_colour: Vec3::new(1.0, 0.88, 0.72) * 2.2,
            zenith: Vec3::new(0.06, 0.17, 0.46),
            horizon: Vec3::new(0.48, 0.58, 0.74),
            deep: Vec3::new(0.004, 0.030, 0.055),
            subsurface: Vec3::new(0.03, 0.21, 0.19),
            haze: 3500.0,
        }
    }

    /// A heavy overcast: grey sky, no sun, dark water, close haze.
    fn overcast() -> Light {
        Light {
            sun: None,
            sun_colour: Vec3::ZERO,
            zenith: Vec3::new(0.42, 0.44, 0.47),
            horizon: Vec3::new(0.15, 0.16, 0.175),
            deep: Vec3::new(0.004, 0.008, 0.011),
            subsurface: Vec3::new(0.010, 0.030, 0.028),
            haze: 1200.0,
        }
    }

    /// Sky radiance in direction `dir`; `with_sun` adds the sun's disc.
    fn sky(&self, dir: Vec3, with_sun: bool) -> Vec3 {
        let elevation = dir.y.max(0.0);
        match self.sun {
            None => {
                // CIE standard overcast sky: L(θ) ∝ (1 + 2 sin θ)/3 of the elevation θ.
                let l = (1.0 + 2.0 * elevation) / 3.0;
                let base = self.horizon.lerp(self.zenith, (l - 1.0 / 3.0) * 1.5) * (0.6 + 0.4 * l);
                // Darker and lighter masses of a cloud deck 1 km up (projected value noise),
                // fading toward the horizon where the deck is seen edge-on.
                let deck = 1000.0 / dir.y.max(0.02);
                let (x, z) = (dir.x * deck / 900.0, dir.z * deck / 900.0);
                let clouds = 0.55 * noise(x, z)
                    + 0.3 * noise(2.1 * x + 5.2, 2.1 * z)
                    + 0.15 * noise(4.3 * x, 4.3 * z + 1.7);
                let contrast = 0.45 * elevation.sqrt().min(1.0);
                base * (1.0 + contrast * (clouds - 0.5) * 2.0)
            }
            Some(sun) => {
                let mut colour = self.horizon.lerp(self.zenith, elevation.powf(0.45));
                let cosine = dir.dot(sun).max(0.0);
                colour +=
                    Vec3::new(1.0, 0.80, 0.55) * (0.25 * cosine.powi(12) + 0.4 * cosine.powi(400));
                if with_sun && cosine > 0.99988 {
                    colour += Vec3::splat(40.0);
                }
                colour
            }
        }
    }

    /// The colour far rays fade to: the sky at the horizon in that direction.
    fn haze_colour(&self, dir: Vec3) -> Vec3 {
        self.sky(Vec3::new(dir.x, 0.0, dir.z).normalize_or(Vec3::X), false)
    }
}

/// Everything the shading needs besides the ocean.
struct Scene {
    eye: Vec3,
    forward: Vec3,
    right: Vec3,
    up: Vec3,
    /// tan of half the horizontal field of view.
    tan: f32,
    width: usize,
    height: usize,
    light: Light,
    /// Bound on |surface height| in m: no water above +bound or below −bound.
    bound: f32,
    /// Standard deviation of the height in m (for the crest tint).
    sigma: f32,
    /// Unit vector along the wind (horizontal).
    wind: Vec3,
    /// Sub-grid slope variance [along, across] (waves shorter than the finest grid).
    subgrid: [f32; 2],
    /// Slope variance [along, across] of the simulated waves between wave number
    /// `k_table[i]` and the finest grid's band edge, on a logarithmic table of wave numbers.
    k_table: Vec<f32>,
    unresolved: Vec<[f32; 2]>,
    /// Total slope variance of the simulated waves.
    resolved_total: f32,
    /// Width of one ray's share of a pixel, in radians.
    ray_angle: f32,
    /// The foam grid (cascade 0's): side in metres, points per side, and the active and
    /// residual foam on it.
    foam_length: f64,
    foam_size: usize,
    active: Vec<f32>,
    residual: Vec<f32>,
}

impl Scene {
    /// Bilinear interpolation of a foam-grid field at the undisplaced world point (x, z)
    /// (grid point (i, j) at (i, j)·L/N, periodic).
    fn foam_field(&self, values: &[f32], x: f64, z: f64) -> f32 {
        let n = self.foam_size;
        let cells = n as f64 / self.foam_length;
        let split = |v: f64| {
            let g = v.rem_euclid(self.foam_length) * cells;
            let cell = g.floor();
            ((cell as usize) % n, (g - cell) as f32)
        };
        let ((ix, fx), (iz, fz)) = (split(x), split(z));
        let (ix1, iz1) = ((ix + 1) % n, (iz + 1) % n);
        let v = |i: usize, j: usize| values[j * n + i];
        (1.0 - fz) * ((1.0 - fx) * v(ix, iz) + fx * v(ix1, iz))
            + fz * ((1.0 - fx) * v(ix, iz1) + fx * v(ix1, iz1))
    }

    /// Slope variance [along, across] of the simulated waves shorter than π/`footprint`
    /// (interpolated in the table).
    fn unresolved_at(&self, footprint: f32) -> [f32; 2] {
        let k = std::f32::consts::PI / footprint.max(1e-4);
        let table = &self.k_table;
        if k <= table[0] {
            return self.unresolved[0];
        }
        if k >= table[table.len() - 1] {
            return [0.0; 2];
        }
        let position = (k / table[0]).ln() / (table[1] / table[0]).ln();
        let i = (position.floor() as usize).min(table.len() - 2);
        let f = position - i as f32;
        let (a, b) = (self.unresolved[i], self.unresolved[i + 1]);
        [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])]
    }
}

/// The names `--preset` takes: `default` and the `SeaState` names.
fn preset_names() -> Vec<&'static str> {
    let mut names = vec!["default"];
    names.extend(SeaState::ALL.iter().map(|s| s.name()));
    names
}

/// A ray-marched picture of the displaced ocean surface to the horizon: out/render.png.
#[derive(Parser)]
#[command(
    name = "render",
    max_term_width = 100,
    args_override_self = true,
    allow_negative_numbers = true
)]
struct Options {
    /// Sea state: `default` is JONSWAP at U10 = 10 m/s over a 100 km fetch.
    #[arg(
        long,
        value_name = "NAME",
        default_value = "default",
        value_parser = clap::builder::PossibleValuesParser::new(preset_names())
    )]
    preset: String,
    /// The eye in metres, y up [default: 0, 2 m + 1.5 Hs (at most 10 m), 0; storm: x 150, z -400].
    #[arg(
        long,
        value_name = "X,Y,Z",
        allow_hyphen_values = true,
        value_parser = common::numbers::<3>
    )]
    camera: Option<[f32; 3]>,
    /// View direction in degrees from the wind direction (+x) toward +z [default: 20; storm 165].
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        value_parser = common::finite::<f32>
    )]
    heading: Option<f32>,
    /// Pitch in degrees, up (+) or down (-) from the horizontal [default: -3.5; storm -3].
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        value_parser = common::finite::<f32>
    )]
    pitch: Option<f32>,
    /// Horizontal field of view in degrees, 1 to 170 [default: 70; storm 55].
    #[arg(long, value_name = "DEG", value_parser = common::within(1.0f32, 170.0))]
    fov: Option<f32>,
    /// Width of the picture in pixels, 1 to 8192.
    #[arg(
        long,
        value_name = "PIXELS",
        default_value_t = 960,
        value_parser = common::within(1usize, 8192)
    )]
    width: usize,
    /// Height of the picture in pixels, 1 to 8192.
    #[arg(
        long,
        value_name = "PIXELS",
        default_value_t = 540,
        value_parser = common::within(1usize, 8192)
    )]
    height: usize,
    /// Rays per pixel along each axis (N × N a pixel), 1 to 8.
    #[arg(long, value_name = "N", default_value_t = 2, value_parser = common::within(1usize, 8))]
    samples: usize,
    /// Time of the sea in seconds (stepped over the 4 s before it so that foam builds up).
    #[arg(
        long,
        value_name = "SECONDS",
        default_value_t = 30.0,
        allow_hyphen_values = true,
        value_parser = common::finite::<f64>
    )]
    time: f64,
    /// Exposure before the tone curve (a factor above 0).
    #[arg(long, value_name = "X", default_value_t = 0.8, value_parser = common::positive::<f32>)]
    exposure: f32,
    /// The picture's file [default: out/render.png].
    #[arg(long, value_name = "FILE")]
    out: Option<std::path::PathBuf>,
    /// Write an indexed PNG of at most 256 colours (median cut), as the README's gallery does.
    #[arg(long)]
    palette: bool,
}

fn main() -> Result<()> {
    let start = std::time::Instant::now();
    let options = Options::parse();
    let preset = options.preset;
    let (spectrum, config, state) = if preset == "default" {
        (
            Spectrum::jonswap(10.0, 100_000.0)?,
            OceanConfig::default(),
            None,
        )
    } else {
        let state = SeaState::ALL
            .into_iter()
            .find(|s| s.name() == preset)
            .ok_or_else(|| format!("--preset: unknown {preset:?}"))?;
        let (spectrum, config) = state.build();
        (spectrum, config, Some(state))
    };
    let storm = state == Some(SeaState::Storm);
    let hs = spectrum.significant_wave_height();
    let wind_direction = spectrum.wind_direction();

    // Camera: defaults per sea. Fair weather looks downwind, a little off the sun; the storm
    // looks across and into the waves coming at the camera.
    let (default_heading, default_pitch) = if storm { (165.0, -3.0) } else { (20.0, -3.5) };
    let eye_height = (2.0 + 1.5 * hs).min(10.0);
    // The storm's camera stands where its foam field shows a breaking crest and streaks.
    let origin = if storm { [150.0, -400.0] } else { [0.0, 0.0] };
    let camera = options.camera.unwrap_or([origin[0], eye_height, origin[1]]);
    let heading = options.heading.unwrap_or(default_heading).to_radians() + wind_direction;
    let pitch = options.pitch.unwrap_or(default_pitch).to_radians();
    let fov = options.fov.unwrap_or(if storm { 55.0 } else { 70.0 });
    let (width, height, samples) = (options.width, options.height, options.samples);
    let (time, exposure) = (options.time, options.exposure);

    let mut ocean = OceanState::new(spectrum, config)?;
    ocean.set_time((time - 4.0).max(0.0))?;
    for _ in 0..120 {
        ocean.step(1.0 / 30.0)?;
    }
    let simulated = start.elapsed().as_secs_f32();
    let coverage = ocean.foam_view().coverage();
    let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
    println!(
        "foam: active coverage {:.3}, residual {:.3}; mean active {:.3}, residual {:.3}",
        coverage.active,
        coverage.residual,
        mean(ocean.foam_view().active()),
        mean(ocean.foam_view().residual())
    );

    // The sum of each cascade's largest |η| bounds the summed height (plus a margin for the
    // spline, which may overshoot the grid values slightly).
    let bound: f32 = ocean
        .cascades()
        .iter()
        .map(|c| c.height().iter().fold(0.0f32, |m, &h| m.max(h.abs())))
        .sum::<f32>()
        * 1.05
        + 0.01;
    let sigma = ocean.diagnostics().expected_variance().sqrt() as f32;
    let mut camera = camera;
    let water = ocean
        .water()
        .height_at(f64::from(camera[0]), f64::from(camera[2]))?;
    if camera[1] < water + 1.0 {
        println!(
            "the eye at y = {:.2} m is below or within 1 m of the water ({water:.2} m): raised \
             to {:.2} m",
            camera[1],
            water + 1.0
        );
        camera[1] = water + 1.0;
    }

    let forward = Vec3::new(
        pitch.cos() * heading.cos(),
        pitch.sin(),
        pitch.cos() * heading.sin(),
    );
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    let light = if storm {
        Light::overcast()
    } else {
        // A low sun 25° to the side of the view, so its glitter path lies in the picture.
        Light::fair(heading + 0.45, 0.24)
    };

    // Slope variance of the simulated waves above wave number k, on a table of k.
    let top = ocean.config().bands()?.last().map_or(1.0, |band| band.1);
    let k_table: Vec<f32> = (0..=64)
        .map(|i| 1e-3 * (top / 1e-3).powf(i as f32 / 64.0))
        .collect();
    let unresolved: Vec<[f32; 2]> = k_table
        .iter()
        .map(|&k| {
            let v = ocean.spectrum().slope_variance(k, top);
            [v.along, v.across]
        })
        .collect();
    let subgrid = ocean.textures().subgrid_slope_variance();
    let wind = Vec3::new(wind_direction.cos(), 0.0, wind_direction.sin());
    let tan = (fov.to_radians() * 0.5).tan();
    let scene = Scene {
        eye: Vec3::from_array(camera),
        forward,
        right,
        up,
        tan,
        width,
        height,
        light,
        bound,
        sigma,
        wind,
        subgrid: [subgrid.along, subgrid.across],
        resolved_total: unresolved[0][0] + unresolved[0][1],
        k_table,
        unresolved,
        ray_angle: 2.0 * tan / (width * samples) as f32,
        foam_length: f64::from(ocean.cascades()[0].length()),
        foam_size: ocean.cascades()[0].size(),
        active: ocean.foam_view().active().to_vec(),
        residual: ocean.foam_view().residual().to_vec(),
    };

    let mut pixels = vec![0u8; width * height * 3];
    pixels
        .par_chunks_mut(width * 3)
        .enumerate()
        .for_each(|(row, line)| {
            for column in 0..width {
                let mut sum = Vec3::ZERO;
                for sy in 0..samples {
                    for sx in 0..samples {
                        let u = (column as f32 + (sx as f32 + 0.5) / samples as f32) / width as f32;
                        let v = (row as f32 + (sy as f32 + 0.5) / samples as f32) / height as f32;
                        sum += render_ray(&ocean, &scene, u, v);
                    }
                }
                let colour = sum / (samples * samples) as f32;
                line[column * 3..column * 3 + 3].copy_from_slice(&tone_map(colour * exposure));
            }
        });

    let path = match options.out {
        Some(file) => file,
        None => out_dir("")?.join("render.png"),
    };
    if options.palette {
        save_indexed(&path, width, height, &pixels)?;
    } else {
        save_rgb8(&path, width, height, &pixels)?;
    }
    println!(
        "wrote {} ({width}×{height}, {}×{} rays per pixel; preset {preset}, Hs {hs:.2} m; eye \
         at ({:.1}, {:.1}, {:.1}) m, heading {:.1}° from the wind, pitch {:.1}°, fov {fov}°; \
         t = {:.1} s; {} light; |η| ≤ {bound:.2} m)",
        path.display(),
        samples,
        samples,
        camera[0],
        camera[1],
        camera[2],
        (heading - wind_direction).to_degrees(),
        pitch.to_degrees(),
        ocean.time(),
        if storm { "overcast" } else { "sun" }
    );
    println!(
        "simulation {simulated:.2} s, rendering {:.2} s",
        start.elapsed().as_secs_f32() - simulated
    );
    Ok(())
}

/// Linear RGB seen along the ray through (u, v) ∈ [0, 1]² of the image.
fn render_ray(ocean: &OceanState, scene: &Scene, u: f32, v: f32) -> Vec3 {
    let sx = (u * 2.0 - 1.0) * scene.tan;
    let sy = (1.0 - v * 2.0) * scene.tan * scene.height as f32 / scene.width as f32;
    let dir = (scene.forward + sx * scene.right + sy * scene.up).normalize();
    if dir.y > -1e-4 {
        return scene.light.sky(dir, true);
    }
    match march(ocean, scene, dir) {
        Some(distance) => shade_water(ocean, scene, dir, distance),
        None => scene.light.haze_colour(dir),
    }
}

/// Ray height minus water height at distance `t` along `dir` (negative below the water).
///
/// For speed the march uses two fixed-point steps x₀ ← p − D(x₀) with `sample` instead of
/// `height_at`'s converged iteration (up to 16 steps): the height error is far below a
/// pixel except on the steepest crests. The hit point is then shaded with the exact
/// `surface_at`.
fn gap(ocean: &OceanState, eye: Vec3, dir: Vec3, t: f32) -> f32 {
    let p = eye + dir * t;
    let (x, z) = (f64::from(p.x), f64::from(p.z));
    let approximate = || -> std::result::Result<f32, ocean_fft::Error> {
        let d = ocean.water().at_rest(x, z)?.displacement;
        let d = ocean
            .water()
            .at_rest(x - f64::from(d[0]), z - f64::from(d[1]))?
            .displacement;
        Ok(ocean
            .water()
            .at_rest(x - f64::from(d[0]), z - f64::from(d[1]))?
            .height)
    };
    match approximate() {
        Ok(h) => p.y - h,
        Err(_) => p.y,
    }
}

/// Distance along `dir` to the first crossing of the displaced surface, or `None` if the
/// ray reaches [`FAR`] first.
fn march(ocean: &OceanState, scene: &Scene, dir: Vec3) -> Option<f32> {
    let down = -dir.y;
    // Enter the slab |y| ≤ bound.
    let mut t = ((scene.eye.y - scene.bound) / down).max(0.0);
    let end = ((scene.eye.y + scene.bound) / down).min(FAR);
    let mut previous = (t, gap(ocean, scene.eye, dir, t));
    while t < end {
        // A step that cannot skip a crest much: the vertical gap over the ray's descent plus
        // the steepest slopes, but at least a distance-proportional minimum.
        let f = previous.1.max(0.0);
        let step = (0.8 * f / (down + 0.5)).max(0.005 * t + 0.03);
        t = (t + step).min(end);
        let g = gap(ocean, scene.eye, dir, t);
        if g < 0.0 {
            // Bisection between the last point above and this one below.
            let (mut lo, mut hi) = (previous.0, t);
            for _ in 0..8 {
                let mid = 0.5 * (lo + hi);
                if gap(ocean, scene.eye, dir, mid) > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return Some(0.5 * (lo + hi));
        }
        previous = (t, g);
    }
    if end < FAR {
        // Left the slab from below without a recorded crossing (numerically); take the end.
        Some(end)
    } else {
        None
    }
}

/// Shades the water hit at `distance` along `dir`.
fn shade_water(ocean: &OceanState, scene: &Scene, dir: Vec3, distance: f32) -> Vec3 {
    let light = &scene.light;
    let p = scene.eye + dir * distance;
    let Ok(surface) = ocean.water().surface_at(f64::from(p.x), f64::from(p.z)) else {
        return light.haze_colour(dir);
    };
    let view = -dir;

    // The ray's footprint on the water: its angular width times the distance, stretched by
    // the grazing angle (geometric mean of the two axes of the footprint ellipse).
    let grazing = (-dir.y).clamp(0.02, 1.0);
    let footprint = scene.ray_angle * distance / grazing.sqrt();
    let far = scene.unresolved_at(footprint);
    // The share of the simulated slope variance the footprint cannot resolve: taken out of
    // the hit's slope and put into the glint's slope distribution.
    let share = ((far[0] + far[1]) / scene.resolved_total.max(1e-12)).clamp(0.0, 1.0);
    let keep = (1.0 - share).sqrt();
    let normal = normal_with(&surface, keep);
    let mut normal = normal;
    if normal.dot(view) < 0.02 {
        // Facing away (behind a crest or folded): bend it toward the viewer.
        normal = (normal + view * (0.02 - normal.dot(view))).normalize_or(Vec3::Y);
    }
    let cosine = normal.dot(view).clamp(0.0, 1.0);
    let f0 = ((1.0f32 - 1.33) / (1.0 + 1.33)).powi(2);
    let fresnel = f0 + (1.0 - f0) * (1.0 - cosine).powi(5);

    let mut reflected = dir - 2.0 * dir.dot(normal) * normal;
    reflected.y = reflected.y.abs();
    let reflection = light.sky(reflected.normalize_or(Vec3::Y), false);

    // Sun glitter: the facets too small to see tilt with the anisotropic Gaussian slope
    // distribution of Cox & Munk (1954), variances along and across the wind = sub-grid +
    // unresolved simulated slopes; L = E F p(ζ) / (4 cos θ_v cos⁴ β).
    let mut glitter = Vec3::ZERO;
    if let Some(sun) = light.sun {
        let along = scene.subgrid[0] + far[0];
        let across = scene.subgrid[1] + far[1];
        let half = (sun + view).normalize_or(Vec3::Y);
        // The half vector's slopes in the frame of the resolved normal.
        let t1 = (scene.wind - normal * normal.dot(scene.wind)).normalize_or(Vec3::X);
        let t2 = normal.cross(t1);
        let hn = half.dot(normal).max(1e-3);
        let (zx, zz) = (half.dot(t1) / hn, half.dot(t2) / hn);
        let density = (-0.5 * (zx * zx / along + zz * zz / across)).exp()
            / (2.0 * std::f32::consts::PI * (along * across).sqrt());
        let specular = density / (4.0 * cosine.max(0.05) * hn.powi(4));
        let sun_fresnel = {
            let c = half.dot(view).clamp(0.0, 1.0);
            f0 + (1.0 - f0) * (1.0 - c).powi(5)
        };
        // √(sin elevation): a crude dimming of a low sun by the longer path through the air.
        glitter = light.sun_colour * specular * sun_fresnel * sun.y.max(0.0).sqrt();
    }

    // Body colour: deep water, lit more where the wave is high and thin, and more when
    // looking toward the sun through the crest.
    let crest = ((surface.height / scene.sigma) * 0.5).clamp(0.0, 1.5);
    let toward = light
        .sun
        .map_or(0.3, |sun| 0.35 + 0.65 * dir.dot(sun).max(0.0).powi(3));
    let ambient = light.sky(Vec3::Y, false);
    let luminance = ambient.dot(Vec3::new(0.2126, 0.7152, 0.0722));
    let body = light.deep * (0.6 + 0.8 * luminance)
        + light.subsurface * crest * toward * (1.0 - share)
        + light.deep * normal.y;

    let mut colour = body * (1.0 - fresnel) + reflection * fresnel + glitter;
    // Foam: white, lit by the sky and the sun, with the detail the foam grid does not hold.
    let foam = foam_cover(scene, &surface, p, footprint);
    let sunlit = light.sun.map_or(0.0, |sun| normal.dot(sun).max(0.0));
    let foam_light =
        Vec3::new(0.85, 0.88, 0.90) * (0.75 * ambient + light.sun_colour * 0.35 * sunlit);
    colour = colour.lerp(foam_light, foam);

    // Haze: exponential in distance toward the horizon colour.
    let haze = 1.0 - (-distance / light.haze).exp();
    colour.lerp(light.haze_colour(dir), haze)
}

/// How much of the water at the hit point `p` foam covers, in [0, 1].
///
/// The ocean's foam lives on the largest cascade's grid (1000 m / 256 = 3.9 m by default,
/// 15.6 m for the storm), which holds how much of each cell is covered — active whitecaps a
/// and residual foam r — but not where in the cell. The picture puts it where the sea would:
/// whitecaps on the crests, covering the fraction a of the area where the normalised height
/// Φ(η/σ), broken up by small-scale noise, is highest (Φ(η/σ) is uniform in [0, 1] for
/// Gaussian η, so the covered fraction stays a); residual foam in streaks along the wind
/// (noise stretched 12 × along it), thinner. A footprint wider than that detail sees the mean
/// coverage a + r(1 − a)/2.
fn foam_cover(scene: &Scene, surface: &SurfaceSample, p: Vec3, footprint: f32) -> f32 {
    let (x, z) = (
        f64::from(p.x - surface.displacement[0]),
        f64::from(p.z - surface.displacement[1]),
    );
    let active = scene.foam_field(&scene.active, x, z).clamp(0.0, 1.0);
    let residual = scene.foam_field(&scene.residual, x, z).clamp(0.0, 1.0);
    let mean = active + 0.5 * residual * (1.0 - active);
    if active + residual < 1e-4 {
        return 0.0;
    }
    // Position in the wind's frame, metres.
    let along = p.x * scene.wind.x + p.z * scene.wind.z;
    let across = -p.x * scene.wind.z + p.z * scene.wind.x;
    // Whitecaps: crests first, broken up by noise at 3 m and 0.8 m into lace.
    let lace =
        0.6 * noise(along / 3.0, across / 3.0) + 0.4 * noise(along / 0.8 + 7.3, across / 0.8);
    let rank = 0.5 * normal_cdf(surface.height / scene.sigma.max(1e-6)) + 0.5 * lace;
    // The rank is roughly normal about 0.5 with a spread of 0.2: its (1 − a) quantile.
    let threshold = 0.5 + 0.2 * probit(1.0 - active.clamp(1e-4, 1.0 - 1e-4));
    let white = smoothstep(threshold - 0.03, threshold + 0.03, rank)
        * (0.75 + 0.25 * noise(along / 0.5 + 1.3, across / 0.5));
    // Residual foam: thin streaks along the wind, 25 m × 0.9 m noise.
    let streak =
        0.75 * noise(along / 25.0 + 3.1, across / 0.9) + 0.25 * noise(along / 6.0, across / 0.4);
    let streak_threshold = 0.5 + 0.2 * probit(1.0 - residual.clamp(1e-4, 1.0 - 1e-4));
    let streaks = smoothstep(streak_threshold - 0.05, streak_threshold + 0.05, streak) * 0.45;
    let detailed = white + streaks * (1.0 - white);
    let blur = (footprint / 1.5).clamp(0.0, 1.0);
    detailed + blur * (mean - detailed)
}

/// Hermite step from 0 at `a` to 1 at `b`.
fn smoothstep(a: f32, b: f32, x: f32) -> f32 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The standard normal quantile Φ⁻¹(p) for p in (0, 1) (Acklam's rational approximation, in
/// f32: a few 10⁻⁷ relative, ample for a foam threshold).
fn probit(p: f32) -> f32 {
    let a = [
        -39.696_83,
        220.946_1,
        -275.928_5,
        138.357_75,
        -30.664_799,
        2.506_628_3,
    ];
    let b = [-54.476_1, 161.585_83, -155.699, 66.801_31, -13.280_682];
    let c = [
        -0.007_784_894,
        -0.322_396_46,
        -2.400_758,
        -2.549_732_5,
        4.374_664,
        2.938_164,
    ];
    let d = [0.007_784_696, 0.322_467_13, 2.445_134, 3.754_408_7];
    let tail = |q: f32| {
        (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5])
            / ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0)
    };
    let low = 0.024_25;
    if p < low {
        tail((-2.0 * p.ln()).sqrt())
    } else if p <= 1.0 - low {
        let q = p - 0.5;
        let r = q * q;
        (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q
            / (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0)
    } else {
        -tail((-2.0 * (1.0 - p).ln()).sqrt())
    }
}

/// The standard normal distribution function Φ(x) (Abramowitz & Stegun 7.1.26 for erf,
/// |error| < 1.5·10⁻⁷).
fn normal_cdf(x: f32) -> f32 {
    let t = x.abs() / std::f32::consts::SQRT_2;
    let k = 1.0 / (1.0 + 0.327_591_1 * t);
    let poly = k
        * (0.254_829_6
            + k * (-0.284_496_7 + k * (1.421_413_7 + k * (-1.453_152 + k * 1.061_405_4))));
    let erf = 1.0 - poly * (-t * t).exp();
    0.5 * (1.0 + erf.copysign(x))
}

/// The normal of `surface` with its slope scaled by `keep` (the part the pixel resolves).
fn normal_with(surface: &SurfaceSample, keep: f32) -> Vec3 {
    let [sx, sz] = surface.slope;
    Vec3::new(-sx * keep, 1.0, -sz * keep).normalize_or(Vec3::Y)
}

/// Linear RGB to 8-bit sRGB through the ACES filmic tone curve (Narkowicz 2015 fit:
/// x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14)) and the sRGB transfer function.
fn tone_map(colour: Vec3) -> [u8; 3] {
    colour.to_array().map(|c| {
        let x = c.max(0.0);
        let mapped = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
        let m = mapped.clamp(0.0, 1.0);
        let srgb = if m <= 0.003_130_8 {
            12.92 * m
        } else {
            1.055 * m.powf(1.0 / 2.4) - 0.055
        };
        (srgb * 255.0).round() as u8
    })
}

/// Smooth value noise in [0, 1] on a unit lattice (hashed corner values, smoothstep blend).
fn noise(x: f32, z: f32) -> f32 {
    let hash = |i: i32, j: i32| {
        let mut h = (i as u32).wrapping_mul(0x27d4_eb2d) ^ (j as u32).wrapping_mul(0x1656_67b1);
        h ^= h >> 15;
        h = h.wrapping_mul(0x85eb_ca6b);
        h ^= h >> 13;
        (h & 0xffff) as f32 / 65535.0
    };
    let (fx, fz) = (x.floor(), z.floor());
    let (i, j) = (fx as i32, fz as i32);
    let (u, v) = (x - fx, z - fz);
    let (u, v) = (u * u * (3.0 - 2.0 * u), v * v * (3.0 - 2.0 * v));
    let a = hash(i, j) + u * (hash(i + 1, j) - hash(i, j));
    let b = hash(i, j + 1) + u * (hash(i + 1, j + 1) - hash(i, j + 1));
    a + v * (b - a)
}
