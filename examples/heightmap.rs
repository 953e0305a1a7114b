//! The default ocean in a few seconds: builds `Spectrum::jonswap(10.0, 100_000.0)` (U10 = 10 m/s,
//! 100 km fetch) with `OceanConfig::default()` (three cascades of 256² over 1000, 230 and 51 m),
//! pre-rolls its foam over the 15 s before t = 10 s (300 steps of 1/20 s) and maps a
//! 400 m × 400 m world-space window of the whole
//! ocean (every cascade summed, `OceanState::sample_grid`), 512 × 512 pixels of 0.78 m, each
//! the mean of 3 × 3 samples (so waves shorter than a pixel average out instead of aliasing
//! into speckle):
//!
//! - `out/heightmap.png`: 16-bit grayscale height η, mapped linearly from [−a, a] to
//!   [0, 65535] with a = max |η| of the window (printed);
//! - `out/normal.png`: 8-bit RGB normal map of the displaced surface, each component mapped
//!   from [−1, 1] to [0, 255] with **R = n_x, G = n_z, B = n_y** (the usual tangent-space
//!   layout with the surface's up axis y in blue, so flat water is (128, 128, 255));
//! - `out/foam.png`: 8-bit foam of the whole ocean (active whitecaps and residual foam
//!   together, [0, 1] → [0, 255]) as `foam_view().foam_at` places it: whitecaps on the
//!   short crests the finer cascades compress and streaks along the wind, patterned at the
//!   finest cascade's scale, with the coverage of the calibration.
//!
//! In each picture the top 512 rows are the window (pixel (i, j) covers x ∈ [i, i + 1)·s,
//! z ∈ [j, j + 1)·s, s = 0.78 m; image rows are z) and a 32-pixel band below holds a scale bar
//! and the window's size.
//!
//! It prints the foam coverage beside the whitecap fraction the calibration aims at, and the
//! significant wave height H_s = 4·std(η) measured on a grid of world
//! points (all cascades summed, via `sample_many`) beside the spectrum's 4√m0 and the
//! expected 4√(Σ S(k)Δk²) of the grids.
//!
//! Options (`--help` lists them): `--window METRES` (side of the window, default 400),
//! `--pixels N` (16 to 4096, default 512).
//!
//! Run with `cargo run --release -p ocean-fft-examples --example heightmap` from the repository
//! root.

mod common;

use clap::Parser;
use ocean_fft::{OceanConfig, OceanState, Spectrum, SurfaceSample};
use plotters::prelude::*;

use common::plot::{draw_on, metres, scale_bar};
use common::{out_dir, sample_window, save_gray16, save_gray8, save_rgb8, to_u16, to_u8, Result};

/// The default ocean's height, normal and foam maps, written to out/.
#[derive(Parser)]
#[command(name = "heightmap", max_term_width = 100, args_override_self = true)]
struct Options {
    /// Side of the square world-space window in metres (above 0).
    #[arg(
        long,
        value_name = "METRES",
        default_value_t = 400.0,
        value_parser = common::positive::<f64>
    )]
    window: f64,
    /// Side of the maps in pixels, 16 to 4096.
    #[arg(
        long,
        value_name = "N",
        default_value_t = 512,
        value_parser = common::within(16usize, 4096)
    )]
    pixels: usize,
}

/// Samples per pixel along each axis (averaged).
const SUPER: usize = 3;
/// Height in pixels of the band under each map with its scale bar.
const FOOTER: usize = 32;

fn main() -> Result<()> {
    let start = std::time::Instant::now();
    let Options { window, pixels } = Options::parse();
    let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
    let hs_spectrum = spectrum.significant_wave_height();
    let mut ocean = OceanState::new(spectrum, OceanConfig::default())?;

    // Jump to t = 10 s and pre-roll the foam over the 15 s before it: active whitecaps (τ_A =
    // 3.85 s) reach their steady coverage, residual foam (τ_R = 15 s) is still building.
    ocean.set_time(10.0)?;
    ocean.pre_roll(15.0, 1.0 / 20.0)?;
    let simulated = start.elapsed().as_secs_f32();

    // The window: SUPER × SUPER samples per pixel at the centres of its sub-pixels.
    let n = pixels;
    let fine = n * SUPER;
    let samples = sample_window(&ocean, window, fine)?;
    let mut height = vec![0.0f32; n * n];
    let mut normal = vec![[0.0f32; 3]; n * n];
    let mut foam = vec![0.0f32; n * n];
    let weight = 1.0 / (SUPER * SUPER) as f32;
    let foam_view = ocean.foam_view();
    let spacing = window / fine as f64;
    for (p, sample) in samples.iter().enumerate() {
        let (c, r) = (p % fine, p / fine);
        let (i, j) = (c / SUPER, r / SUPER);
        let pixel = j * n + i;
        height[pixel] += sample.height * weight;
        for (sum, c) in normal[pixel].iter_mut().zip(sample.normal) {
            *sum += c;
        }
        // The foam itself at the sample's rest point (patterned at the breaking scale), not
        // the coarse fraction `sample.foam` of the foam grid's 3.9 m cells.
        let (x0, z0) = ((c as f64 + 0.5) * spacing, (r as f64 + 0.5) * spacing);
        foam[pixel] += foam_view.foam_at(x0, z0)?.total * weight;
    }
    let sampled = start.elapsed().as_secs_f32() - simulated;

    let dir = out_dir("")?;
    let metres_per_pixel = window / n as f64;
    let caption = format!(
        "window {} × {}, all {} cascades summed",
        metres(window),
        metres(window),
        ocean.cascades().len()
    );
    let footer = footer(n, metres_per_pixel, &caption)?;

    // Height, 16-bit; the footer's gray levels widened to 16 bits.
    let a = height.iter().fold(0.0f32, |m, &h| m.max(h.abs())).max(1e-6);
    let mut image: Vec<u16> = height.iter().map(|&h| to_u16(h, a)).collect();
    image.extend(footer.chunks(3).map(|c| u16::from(c[1]) * 257));
    let path = dir.join("heightmap.png");
    save_gray16(&path, n, n + FOOTER, &image)?;
    println!(
        "wrote {} ({n}×{n} pixels of {metres_per_pixel:.3} m over a {window} m window at \
         (0, 0), height mapped from [−{a:.3}, {a:.3}] m to [0, 65535]; scale bar below)",
        path.display()
    );

    // Normal map: R = n_x, G = n_z, B = n_y (up), of the mean normal of each pixel.
    let mut image: Vec<u8> = normal
        .iter()
        .flat_map(|v| {
            let length = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-12);
            [v[0], v[2], v[1]].map(|c| to_u8(0.5 + 0.5 * c / length))
        })
        .collect();
    image.extend_from_slice(&footer);
    let path = dir.join("normal.png");
    save_rgb8(&path, n, n + FOOTER, &image)?;
    println!(
        "wrote {} (R = n_x, G = n_z, B = n_y, each from [−1, 1] to [0, 255])",
        path.display()
    );

    // Foam.
    let mut image: Vec<u8> = foam.iter().map(|&f| to_u8(f)).collect();
    image.extend(footer.chunks(3).map(|c| c[1]));
    let path = dir.join("foam.png");
    save_gray8(&path, n, n + FOOTER, &image)?;
    let coverage = ocean.foam_view().coverage();
    let calibration = ocean.foam_view().calibration();
    println!(
        "wrote {} (foam in [0, 1] → [0, 255]); coverage: active whitecaps {:.2} %, residual \
         {:.2} %; whitecap fraction aimed at (Monahan & O'Muircheartaigh 1980, U10 = {} m/s): \
         {:.2} %, breaking threshold J_b = {:.3}",
        path.display(),
        100.0 * coverage.active,
        100.0 * coverage.residual,
        calibration.wind_speed,
        100.0 * calibration.target,
        calibration.threshold,
    );

    // Measured H_s: the summed surface on a 512×512 grid of world points spanning exactly
    // one period of the largest cascade (the smaller ones are periodic inside it).
    let m = 512;
    let period = f64::from(ocean.cascades()[0].length());
    let points: Vec<[f64; 2]> = (0..m * m)
        .map(|p| {
            let (i, j) = (p % m, p / m);
            [i as f64 * period / m as f64, j as f64 * period / m as f64]
        })
        .collect();
    let mut samples = vec![SurfaceSample::default(); points.len()];
    ocean.water().at_rest_many(&points, &mut samples)?;
    let mean = samples.iter().map(|s| f64::from(s.height)).sum::<f64>() / samples.len() as f64;
    let variance = samples
        .iter()
        .map(|s| (f64::from(s.height) - mean).powi(2))
        .sum::<f64>()
        / samples.len() as f64;
    let hs_measured = 4.0 * variance.sqrt();
    let hs_expected = 4.0 * ocean.diagnostics().expected_variance().sqrt();
    println!("t = {:.2} s", ocean.time());
    println!(
        "H_s measured, 4·std of the summed height at {m}×{m} world points: {hs_measured:.3} m"
    );
    println!("H_s expected from the grids, 4·√(expected_variance()):          {hs_expected:.3} m");
    println!("H_s of the spectrum, significant_wave_height() (4√m0):           {hs_spectrum:.3} m");
    println!(
        "(one random realisation: the few longest waves dominate, so the measured value \
         scatters by several per cent around the expected one)"
    );
    println!(
        "simulation {simulated:.2} s, window ({} samples) {sampled:.2} s, done in {:.2} s",
        fine * fine,
        start.elapsed().as_secs_f32()
    );
    Ok(())
}

/// The band under each map: a scale bar and `caption` on dark grey, `width` × [`FOOTER`] RGB.
fn footer(width: usize, metres_per_pixel: f64, caption: &str) -> Result<Vec<u8>> {
    let mut band = vec![40u8; width * FOOTER * 3];
    let (w, h) = (u32::try_from(width)?, FOOTER as u32);
    draw_on(&mut band, w, h, |area| {
        area.fill(&RGBColor(40, 40, 40))?;
        scale_bar(area, metres_per_pixel, w, caption)
    })?;
    Ok(band)
}
