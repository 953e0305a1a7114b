//! A shaded perspective picture of the displaced ocean surface, `out/render.png` (960×540).
//!
//! The default ocean (`Spectrum::jonswap(10.0, 100_000.0)`, `OceanConfig::default()`) is
//! stepped for 4 s at 30 Hz so that foam builds up. A camera 6 m above the mean surface looks
//! toward the horizon, slightly off the wind direction, into a low sun. Every pixel casts a
//! ray, marched against the displaced surface (the water height at a world point after
//! horizontal displacement, by two fixed-point steps of `OceanState::sample`; the converged
//! form is `OceanState::height_at`) and refined by bisection; the hit point is
//! shaded from `OceanState::surface_at` (normal and foam):
//!
//! - sky gradient reflected with Schlick's Fresnel (water n = 1.33, F0 ≈ 0.02);
//! - a sun glitter path: a Beckmann lobe whose slope variance is the ocean's sub-grid
//!   mean-square slope (`OceanState::subgrid_slope_variance`, the waves too small for the
//!   finest grid), plus the grid's own slopes that a distant pixel averages over;
//! - a deep-water colour plus a subsurface tint that is brighter on high crests;
//! - foam blended to white;
//! - distance fog to the horizon colour.
//!
//! Rows are rendered in parallel with rayon. Run with
//! `cargo run --release -p ocean-fft-examples --example render`.

mod common;

use glam::Vec3;
use ocean_fft::{OceanConfig, OceanState, Spectrum};
use rayon::prelude::*;

use common::{out_dir, save_rgb8, Result};

const WIDTH: usize = 960;
const HEIGHT: usize = 540;
/// Horizontal field of view in degrees.
const FOV_DEG: f32 = 70.0;
/// Rays that have not hit the water this far out (m) end in the fog.
const FAR: f32 = 6000.0;

/// Everything the shading needs besides the ocean.
struct Scene {
    eye: Vec3,
    forward: Vec3,
    right: Vec3,
    up: Vec3,
    sun: Vec3,
    /// Bound on |surface height| in m: no water above +bound or below −bound.
    bound: f32,
    /// Standard deviation of the height in m (for the crest tint).
    sigma: f32,
    /// Mean-square slope of the waves shorter than the finest grid (sub-grid roughness).
    subgrid_mss: f32,
    /// Mean-square slope the grids hold (averaged away by a distant pixel).
    resolved_mss: f32,
}

fn main() -> Result<()> {
    let start = std::time::Instant::now();
    let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
    let mut ocean = OceanState::new(spectrum, OceanConfig::default())?;
    ocean.set_time(30.0)?;
    for _ in 0..120 {
        ocean.step(1.0 / 30.0)?;
    }
    let simulated = start.elapsed().as_secs_f32();

    // The sum of each cascade's largest |η| bounds the summed height (plus a margin for the
    // bilinear sampling, which never exceeds the grid values).
    let bound: f32 = ocean
        .cascades()
        .iter()
        .map(|c| c.height().iter().fold(0.0f32, |m, &h| m.max(h.abs())))
        .sum::<f32>()
        + 0.01;
    let sigma = ocean.expected_variance().sqrt() as f32;

    let yaw = 0.35f32; // rad from +x (the wind direction) toward +z
    let pitch = -0.06f32;
    let forward = Vec3::new(
        pitch.cos() * yaw.cos(),
        pitch.sin(),
        pitch.cos() * yaw.sin(),
    );
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    let sun_azimuth = yaw + 0.45;
    let sun_elevation = 0.22f32;
    let sun = Vec3::new(
        sun_elevation.cos() * sun_azimuth.cos(),
        sun_elevation.sin(),
        sun_elevation.cos() * sun_azimuth.sin(),
    );
    let scene = Scene {
        eye: Vec3::new(0.0, 6.0, 0.0),
        forward,
        right,
        up,
        sun,
        bound,
        sigma,
        subgrid_mss: ocean.subgrid_slope_variance().total(),
        resolved_mss: {
            let bands = ocean.config().bands()?;
            let top = bands.last().map_or(0.0, |band| band.1);
            ocean.spectrum().slope_variance(0.0, top).total()
        },
    };

    let mut pixels = vec![0u8; WIDTH * HEIGHT * 3];
    pixels
        .par_chunks_mut(WIDTH * 3)
        .enumerate()
        .for_each(|(row, line)| {
            for column in 0..WIDTH {
                let colour = render_pixel(&ocean, &scene, column, row);
                let out = &mut line[column * 3..column * 3 + 3];
                out.copy_from_slice(&to_srgb(colour));
            }
        });

    let path = out_dir("")?.join("render.png");
    save_rgb8(&path, WIDTH, HEIGHT, &pixels)?;
    println!(
        "wrote {} ({WIDTH}×{HEIGHT}, eye at y = {} m, t = {:.1} s, |η| ≤ {bound:.2} m)",
        path.display(),
        scene.eye.y,
        ocean.time()
    );
    println!(
        "simulation {simulated:.2} s, rendering {:.2} s",
        start.elapsed().as_secs_f32() - simulated
    );
    Ok(())
}

/// Linear RGB of the pixel at (`column`, `row`).
fn render_pixel(ocean: &OceanState, scene: &Scene, column: usize, row: usize) -> Vec3 {
    let tan = (FOV_DEG.to_radians() * 0.5).tan();
    let sx = ((column as f32 + 0.5) / WIDTH as f32 * 2.0 - 1.0) * tan;
    let sy = (1.0 - (row as f32 + 0.5) / HEIGHT as f32 * 2.0) * tan * HEIGHT as f32 / WIDTH as f32;
    let dir = (scene.forward + sx * scene.right + sy * scene.up).normalize();
    if dir.y > -1e-4 {
        return sky(dir, scene.sun, true);
    }
    match march(ocean, scene, dir) {
        Some(distance) => shade_water(ocean, scene, dir, distance),
        None => fog_colour(scene.sun, dir),
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
        let d = ocean.sample(x, z)?.displacement;
        let d = ocean
            .sample(x - f64::from(d[0]), z - f64::from(d[1]))?
            .displacement;
        Ok(ocean
            .sample(x - f64::from(d[0]), z - f64::from(d[1]))?
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
        let step = (0.8 * f / (down + 0.5)).max(0.006 * t + 0.03);
        t = (t + step).min(end);
        let g = gap(ocean, scene.eye, dir, t);
        if g < 0.0 {
            // Bisection between the last point above and this one below.
            let (mut lo, mut hi) = (previous.0, t);
            for _ in 0..6 {
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

/// Sky radiance in direction `dir` (linear RGB); `with_sun` adds the sun's disc.
fn sky(dir: Vec3, sun: Vec3, with_sun: bool) -> Vec3 {
    let horizon = Vec3::new(0.66, 0.75, 0.84);
    let zenith = Vec3::new(0.09, 0.22, 0.52);
    let elevation = dir.y.max(0.0);
    let mut colour = horizon.lerp(zenith, elevation.powf(0.45));
    let cosine = dir.dot(sun).max(0.0);
    // Warm glow around the sun.
    colour += Vec3::new(1.0, 0.78, 0.5) * (0.30 * cosine.powi(16) + 0.35 * cosine.powi(300));
    if with_sun && cosine > 0.99985 {
        colour += Vec3::splat(20.0);
    }
    colour
}

/// The colour far rays fade to.
fn fog_colour(sun: Vec3, dir: Vec3) -> Vec3 {
    sky(
        Vec3::new(dir.x, 0.0, dir.z).normalize_or(Vec3::X),
        sun,
        false,
    )
}

/// Shades the water hit at `distance` along `dir`.
fn shade_water(ocean: &OceanState, scene: &Scene, dir: Vec3, distance: f32) -> Vec3 {
    let p = scene.eye + dir * distance;
    let Ok(surface) = ocean.surface_at(f64::from(p.x), f64::from(p.z)) else {
        return fog_colour(scene.sun, dir);
    };
    // Far away a pixel covers many small waves: flatten the normal toward their mean (up)
    // instead of letting the bilinear normals alias.
    let far = (distance / 900.0).clamp(0.0, 1.0);
    // The crate's `[x, y, z]` arrays convert to any vector type; glam here.
    let mut normal = Vec3::from_array(surface.normal)
        .lerp(Vec3::Y, 0.75 * far)
        .normalize_or(Vec3::Y);
    let view = -dir;
    if normal.dot(view) < 0.02 {
        // Facing away (behind a crest or folded): bend it toward the viewer.
        normal = (normal + view * (0.02 - normal.dot(view))).normalize_or(Vec3::Y);
    }
    let cosine = normal.dot(view).clamp(0.0, 1.0);
    let f0 = ((1.0f32 - 1.33) / (1.0 + 1.33)).powi(2);
    let fresnel = f0 + (1.0 - f0) * (1.0 - cosine).powi(5);

    let mut reflected = dir - 2.0 * dir.dot(normal) * normal;
    reflected.y = reflected.y.abs();
    let reflection = sky(reflected.normalize_or(Vec3::Y), scene.sun, false);

    // Sun glitter: a Beckmann lobe over the facet slopes the pixel does not resolve — the
    // sub-grid mean-square slope the ocean reports, plus the share of the grid's own slopes
    // that the flattened normal (above) averages away far off.
    let mss = scene.subgrid_mss + 0.75 * far * scene.resolved_mss;
    let half = (scene.sun + view).normalize_or(Vec3::Y);
    let nh = normal.dot(half).max(1e-3);
    let tan2 = (1.0 - nh * nh) / (nh * nh);
    let lobe = (-tan2 / mss).exp() / (std::f32::consts::PI * mss * nh.powi(4));
    let specular = lobe / (4.0 * cosine.max(0.05));
    let sun_light = Vec3::new(1.0, 0.85, 0.65) * 0.9 * specular * fresnel.max(0.1);

    // Body colour: deep blue-green, lit more where the wave is high and thin, and more when
    // looking toward the sun through the crest.
    let deep = Vec3::new(0.004, 0.028, 0.050);
    let subsurface = Vec3::new(0.03, 0.20, 0.18);
    let crest = ((surface.height / scene.sigma) * 0.5).clamp(0.0, 1.5);
    let toward_sun = dir.dot(scene.sun).max(0.0).powi(3);
    let scatter = crest * (0.35 + 0.65 * toward_sun) * (1.0 - far);
    let body = deep + subsurface * scatter + Vec3::new(0.01, 0.03, 0.04) * normal.y;

    let mut colour = body * (1.0 - fresnel) + reflection * fresnel + sun_light;
    // Foam: white, lit by the sky and the sun.
    let coverage = ((surface.foam - 0.03) / 0.4).clamp(0.0, 1.0);
    let foam = coverage * coverage * (3.0 - 2.0 * coverage) * (1.0 - far);
    let foam_light = Vec3::new(0.80, 0.84, 0.88) * (0.55 + 0.45 * normal.dot(scene.sun).max(0.0));
    colour = colour.lerp(foam_light, foam);

    // Fog: exponential in distance toward the horizon colour.
    let fog = 1.0 - (-distance / 2500.0).exp();
    colour.lerp(fog_colour(scene.sun, dir), fog)
}

/// Linear RGB to 8-bit sRGB-ish (simple exposure, Reinhard on bright values, gamma 2.2).
fn to_srgb(colour: Vec3) -> [u8; 3] {
    colour.to_array().map(|c| {
        let c = c.max(0.0);
        let mapped = if c > 0.8 {
            0.8 + (c - 0.8) / (1.0 + (c - 0.8) * 4.0)
        } else {
            c
        };
        (mapped.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0).round() as u8
    })
}
