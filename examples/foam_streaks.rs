//! The foam of a 14 m/s sea seen from above, `out/foam_streaks.png` (two 512×512 views).
//!
//! A fully developed JONSWAP sea (U10 = 14 m/s, wind toward 0.5 rad from +x, peak wavelength
//! λ_p ≈ 163 m) on three cascades of 256² over 650, 150 and 33 m (four peak wavelengths for
//! the largest, so the foam grid, cascade 0's, has 2.5 m points). The foam is pre-rolled over
//! the 45 s before t = 600 s (900 steps of 1/20 s), then drawn twice, the whole foam tile
//! (left) and a quarter of it enlarged (right): the summed surface hill-shaded from its normal
//! (`sample_grid`, undisplaced points), residual foam blended in pale grey and active
//! whitecaps in white, with the wind direction as an arrow and a scale bar under each view. The coverage is printed beside the
//! whitecap fraction the calibration aims at.
//!
//! Run with `cargo run --release -p ocean-fft-examples --example foam_streaks`.

mod common;

use glam::Vec3;
use ocean_fft::{OceanConfig, OceanState, Spectrum, SurfaceSample};
use plotters::prelude::*;

use common::plot::{draw_on, metres, outlined_text, scale_bar, FONT};
use common::{out_dir, Canvas, Result};

/// Side of each view in pixels, the gap around them and the label strip.
const PANEL: usize = 512;
const PAD: usize = 12;
const LABEL: usize = 26;

/// The summed surface over a `side`-metre square at the origin, PANEL² undisplaced points,
/// hill-shaded from its normal, with residual foam in pale grey and active whitecaps in white
/// (each blended by its coverage, read bilinearly from its buffer).
fn draw(ocean: &OceanState, side: f64) -> Result<Vec<u8>> {
    let spacing = side / PANEL as f64;
    let mut samples = vec![SurfaceSample::default(); PANEL * PANEL];
    ocean
        .water()
        .at_rest_grid([0.0, 0.0], spacing, [PANEL, PANEL], &mut samples)?;
    let n = ocean.cascades()[0].size();
    let cell = f64::from(ocean.cascades()[0].length()) / n as f64;
    let (active, residual) = (ocean.foam_view().active(), ocean.foam_view().residual());
    // Bilinear, periodic: a foam buffer at world (x, z).
    let at = |buffer: &[f32], x: f64, z: f64| {
        let (x, z) = ((x / cell) as f32, (z / cell) as f32);
        let (i, j) = (x.floor() as usize, z.floor() as usize);
        let (fx, fz) = (x - x.floor(), z - z.floor());
        let v = |i: usize, j: usize| buffer[(j % n) * n + i % n];
        (1.0 - fz) * ((1.0 - fx) * v(i, j) + fx * v(i + 1, j))
            + fz * ((1.0 - fx) * v(i, j + 1) + fx * v(i + 1, j + 1))
    };
    let sun = Vec3::new(-0.6, 0.55, -0.58).normalize();
    let water = Vec3::new(0.03, 0.16, 0.25);
    let residual_colour = Vec3::new(0.86, 0.90, 0.93);
    let whitecap = Vec3::new(0.98, 0.99, 1.0);
    let mut image = Vec::with_capacity(3 * PANEL * PANEL);
    for r in 0..PANEL {
        for c in 0..PANEL {
            let s = &samples[r * PANEL + c];
            let normal = Vec3::from_array(s.normal);
            let light = 0.35 + 0.65 * normal.dot(sun).max(0.0);
            let mut colour = water * (0.6 + 0.8 * light);
            // Residual foam first, then the active whitecaps over it.
            let (x, z) = (c as f64 * spacing, r as f64 * spacing);
            let a = at(active, x, z).clamp(0.0, 1.0);
            let old = at(residual, x, z).clamp(0.0, 1.0);
            colour = colour.lerp(residual_colour * (0.8 + 0.2 * light), old);
            colour = colour.lerp(whitecap, a);
            image.extend(
                colour
                    .to_array()
                    .map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8),
            );
        }
    }
    Ok(image)
}

fn main() -> Result<()> {
    let start = std::time::Instant::now();
    let wind_direction = 0.5f32;
    let spectrum = Spectrum::jonswap(14.0, 1e6)?.with_wind_direction(wind_direction)?;
    let first = 650.0;
    let config = OceanConfig {
        size: 512,
        lengths: vec![first, first * 0.23, first * 0.051],
        ..OceanConfig::default()
    };
    let mut ocean = OceanState::new(spectrum, config)?;
    ocean.set_time(600.0)?;
    ocean.pre_roll(40.0, 1.0 / 10.0)?;
    let simulated = start.elapsed().as_secs_f32();
    let n = ocean.cascades()[0].size();

    // Two views: the whole foam tile (left) and a quarter of it, a 162 m square, enlarged
    // (right), each PANEL² pixels of undisplaced points shaded from the summed surface.
    let mut canvas = Canvas::new(2 * PANEL + 3 * PAD, PANEL + 2 * PAD + LABEL, [20, 24, 30]);
    let mut labels = Vec::new();
    for (panel, side) in [(0, f64::from(first)), (1, f64::from(first) / 4.0)] {
        let image = draw(&ocean, side)?;
        let x = PAD + panel * (PANEL + PAD);
        canvas.blit(x as i64, PAD as i64, PANEL, PANEL, &image);
        labels.push((x, side));
    }
    // The zoomed square, outlined on the whole tile.
    let quarter = (PANEL / 4) as f32;
    let (x0, y0) = (PAD as f32, PAD as f32);
    let outline = [
        (x0, y0),
        (x0 + quarter, y0),
        (x0 + quarter, y0 + quarter),
        (x0, y0 + quarter),
        (x0, y0),
    ];
    canvas.polyline(&outline, 1, [255, 210, 60]);
    // Wind arrow (image x = +x, image y = +z).
    let (sin, cos) = wind_direction.sin_cos();
    let origin = ((PAD + PANEL + PAD + 40) as f32, (PAD + 40) as f32);
    let tip = (origin.0 + 40.0 * cos, origin.1 + 40.0 * sin);
    let yellow = [255, 210, 60];
    canvas.line(origin, tip, 3, yellow);
    for side in [0.5f32, -0.5] {
        let back = (
            tip.0 - 12.0 * (wind_direction + side).cos(),
            tip.1 - 12.0 * (wind_direction + side).sin(),
        );
        canvas.line(tip, back, 3, yellow);
    }
    // Labels and scale bars.
    let (width, height) = (canvas.width as u32, canvas.height as u32);
    draw_on(&mut canvas.pixels, width, height, |root| {
        for &(x, side) in &labels {
            root.draw(&Text::new(
                format!("{} × {} window", metres(side), metres(side)),
                (x as i32, (PAD + PANEL + 5) as i32),
                (FONT, 16.0).into_font().color(&RGBColor(230, 230, 230)),
            ))?;
            let bar = root
                .clone()
                .shrink((x as u32, (PAD + PANEL - 30) as u32), (PANEL as u32, 30));
            scale_bar(&bar, side / PANEL as f64, PANEL as u32, "")?;
        }
        outlined_text(
            root,
            "wind 14 m/s",
            (origin.0 as i32 - 30, origin.1 as i32 + 44),
            16.0,
        )
    })?;

    let dir = out_dir("")?;
    let path = dir.join("foam_streaks.png");
    canvas.save(&path)?;
    let coverage = ocean.foam_view().coverage();
    let calibration = ocean.foam_view().calibration();
    println!(
        "wrote {} (the {first} m tile of the foam grid, {n}² points, and a quarter of it)",
        path.display()
    );
    println!(
        "coverage: active whitecaps {:.2} % (aimed at {:.2} %, Monahan & O'Muircheartaigh 1980), \
         residual {:.2} %, total {:.2} %",
        100.0 * coverage.active,
        100.0 * calibration.target,
        100.0 * coverage.residual,
        100.0 * coverage.total
    );
    println!(
        "breaking threshold J_b = {:.3} (σ_T = {:.3}); a breaking episode lasts {:.2} s on average",
        calibration.threshold,
        calibration.compression_std,
        calibration.episode_duration()
    );
    println!(
        "pre-roll {simulated:.1} s, done in {:.1} s",
        start.elapsed().as_secs_f32()
    );
    Ok(())
}
