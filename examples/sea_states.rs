//! A contact sheet of every preset in `SeaState::ALL`, `out/sea_states.png`: each sea seen from
//! straight above over a window sized to its own waves, labelled with the preset's name, H_s,
//! T_p and the window's size, with a scale bar. Also prints a table of the presets (U10, fetch,
//! depth, H_s, T_p, peak wavelength, cascade lengths) and, for each tile, how much it repeats.
//!
//! **Windows.** Each tile shows a square window of side 8 peak wavelengths λ_p (from the
//! spectrum's peak frequency and its dispersion), at most 0.9 of the largest cascade's length
//! L₀: the largest cascade, which holds most of the height variance, never repeats inside a
//! tile, and a tile always holds several waves (the swell's window is 1.8 km, the calm sea's
//! 42 m).
//!
//! **Repeats.** Inside a tile, the only shifts that can repeat are the lengths L of the smaller
//! cascades (each cascade's field is periodic with its own L). For every cascade length shorter
//! than the window the example measures the correlation coefficient of the tile's heights with
//! the same heights shifted by L along x and along z (over the part of the tile where both lie
//! inside it) and prints the largest, for L ≥ λ_p (a shorter shift lies inside one wave, where
//! any smooth surface correlates with itself); the same for the slope vectors at every L. The
//! crate's test `tests/preset_repeat.rs` checks that the height correlation stays below 0.2
//! for every preset, on average over six seeds.
//!
//! **Filtering.** A pixel of a tile covers 0.2 m (calm) to 11 m (storm), far more than the
//! smallest waves of the preset (down to 2 cm). Instead of letting them alias into speckle, each
//! tile's ocean is built with `OceanConfig::k_max` at the pixels' Nyquist wave number π/Δx
//! (dropping cascades whose band falls above it) and `band_split` 1 (each cascade up to its
//! own Nyquist wave number, so the largest, which never repeats in the tile, holds most of
//! what the tile shows), and each pixel is the mean of 2 × 2 samples.
//!
//! Shading: a low sun from the upper left on the surface normal (hill shading, which shows
//! the slopes of small and large seas alike), a tint that brightens crests by η/H_s of that
//! preset, residual foam as a pale veil and active whitecaps in white (the ocean's foam at
//! each point, `OceanState::foam_at`, interpolated from the largest cascade's grid). Each preset is built at size 256 (its default) and shown at t = 24 s,
//! its foam pre-rolled over the 15 s before (`OceanState::pre_roll`).
//!
//! Options (`--help` lists them): `--tile PIXELS` (side of each tile, 32 to 2048, default
//! 240); `--palette`: write an indexed
//! PNG of 256 colours (median cut), about a third of the size, as the README's gallery does.
//!
//! Run with `cargo run --release -p ocean-fft-examples --example sea_states`.

mod common;

use clap::Parser;
use glam::Vec3;
use ocean_fft::{Error, OceanState, SeaState, SurfaceSample};
use plotters::prelude::*;

use common::plot::{draw_on, metres, scale_bar, FONT};
use common::{out_dir, sample_window, save_indexed, save_rgb8, shade, to_srgb, Result};

/// Every preset from above, side by side with its H_s, T_p and window, in out/sea_states.png.
#[derive(Parser)]
#[command(name = "sea_states", max_term_width = 100, args_override_self = true)]
struct Options {
    /// Side of each tile in pixels, 32 to 2048.
    #[arg(
        long,
        value_name = "PIXELS",
        default_value_t = 240,
        value_parser = common::within(32usize, 2048)
    )]
    tile: usize,
    /// Write an indexed PNG of at most 256 colours (median cut), as the README's gallery does.
    #[arg(long)]
    palette: bool,
}

/// Samples per pixel along each axis (averaged).
const SUPER: usize = 2;
const COLUMNS: usize = 3;
const PAD: usize = 12;
/// Window side in peak wavelengths.
const WAVELENGTHS: f64 = 8.0;
/// Largest window side as a fraction of the largest cascade's length.
const MAX_FRACTION: f64 = 0.9;

fn main() -> Result<()> {
    let start = std::time::Instant::now();
    let Options {
        tile: tile_px,
        palette,
    } = Options::parse();
    let big = (tile_px as f64 / 12.0).clamp(14.0, 19.0);
    let small = (tile_px as f64 / 15.0).clamp(12.0, 14.0);
    // Three lines of labels above each tile: name, H_s and T_p, window.
    let label = (big + 2.0 * small + 14.0).round() as usize;
    let rows = SeaState::ALL.len().div_ceil(COLUMNS);
    let width = COLUMNS * (tile_px + PAD) + PAD;
    let height = rows * (tile_px + label + PAD) + PAD;
    let background = [20u8, 24, 30];
    let mut sheet: Vec<u8> = background
        .iter()
        .copied()
        .cycle()
        .take(width * height * 3)
        .collect();
    let fine = tile_px * SUPER;
    let sun = Vec3::new(-0.7, 0.35, -0.5).normalize();

    println!(
        "{:<16} {:>7} {:>8} {:>7} {:>7} {:>6} {:>7} {:>8}  cascade lengths [m]",
        "preset", "U10 m/s", "fetch km", "depth m", "Hs m", "Tp s", "λp m", "window m"
    );
    let mut labels = Vec::new();
    let mut repeats = Vec::new();
    for (index, state) in SeaState::ALL.iter().enumerate() {
        let (spectrum, config) = state.build();
        let hs = spectrum.significant_wave_height();
        let tp = spectrum.peak_period();
        let window = window_side(*state);
        let wavelength = peak_wavelength(*state);
        let fetch = spectrum
            .fetch()
            .map_or("-".to_string(), |f| format!("{:.0}", f / 1000.0));
        let depth = spectrum
            .depth()
            .map_or("deep".to_string(), |d| format!("{d:.1}"));
        println!(
            "{:<16} {:>7.2} {:>8} {:>7} {:>7.3} {:>6.2} {:>7.1} {:>8.0}  {:?}",
            state.name(),
            state.wind_speed(),
            fetch,
            depth,
            hs,
            tp,
            wavelength,
            window,
            config.lengths
        );

        // Band-limit the sea to what a pixel resolves: k_max = π/Δx, and drop the cascades
        // whose whole band lies above it.
        let pixel = window / tile_px as f64;
        let mut tile_config = config.clone();
        tile_config.k_max = (std::f64::consts::PI / pixel) as f32;
        // Each cascade's band up to its own Nyquist wave number (the presets split at half
        // of it): the tile's pixels are about as fine as the largest cascade's grid, so it
        // carries nearly every wave the tile resolves, and the smaller cascade, which does
        // repeat inside the tile, holds little of the slope the shading shows (its repeat
        // correlation of slopes falls from 0.27–0.50 to 0.02–0.24).
        tile_config.band_split = 1.0;
        let mut ocean = loop {
            match OceanState::new(spectrum.clone(), tile_config.clone()) {
                Err(Error::EmptyBand { .. }) if tile_config.lengths.len() > 1 => {
                    tile_config.lengths.pop();
                }
                other => break other?,
            }
        };
        // t = 24 s with the foam of the 15 s before it (active whitecaps at their steady
        // coverage, residual foam building).
        ocean.set_time(24.0)?;
        ocean.pre_roll(15.0, 0.1)?;
        let spacing = window / fine as f64;
        let samples = sample_window(&ocean, window, fine)?;
        let repeat = repeat_correlation(&ocean, window, wavelength, 160)?;
        repeats.push((state.name(), window, repeat, tile_config.lengths.len()));

        let foam = |p: usize| {
            let (i, j) = ((p % fine) as f64 + 0.5, (p / fine) as f64 + 0.5);
            ocean.foam_view().foam_at(i * spacing, j * spacing)
        };
        let x0 = PAD + (index % COLUMNS) * (tile_px + PAD);
        let y0 = PAD + (index / COLUMNS) * (tile_px + label + PAD) + label;
        for j in 0..tile_px {
            for i in 0..tile_px {
                let mut sum = Vec3::ZERO;
                for dj in 0..SUPER {
                    for di in 0..SUPER {
                        let p = (j * SUPER + dj) * fine + i * SUPER + di;
                        let foam = foam(p)?;
                        sum += shade(&samples[p], sun, hs, foam.active, foam.residual);
                    }
                }
                let colour = to_srgb(sum / (SUPER * SUPER) as f32);
                let at = ((y0 + j) * width + x0 + i) * 3;
                sheet[at..at + 3].copy_from_slice(&colour);
            }
        }
        labels.push((
            x0,
            y0,
            state.name().replace('_', " "),
            format!("Hs {hs:.2} m · Tp {tp:.1} s"),
            format!("{} window", metres(window)),
            pixel,
        ));
    }

    draw_on(&mut sheet, width as u32, height as u32, |root| {
        for (x0, y0, name, numbers, caption, pixel) in &labels {
            let (x0, y0) = (*x0 as i32, *y0 as i32);
            let top = y0 - label as i32 + 2;
            root.draw(&Text::new(
                name.clone(),
                (x0, top),
                (FONT, big).into_font().color(&RGBColor(235, 235, 235)),
            ))?;
            root.draw(&Text::new(
                numbers.clone(),
                (x0, top + big as i32 + 3),
                (FONT, small).into_font().color(&RGBColor(170, 190, 210)),
            ))?;
            root.draw(&Text::new(
                caption.clone(),
                (x0, top + big as i32 + small as i32 + 6),
                (FONT, small).into_font().color(&RGBColor(170, 190, 210)),
            ))?;
            let bar = root.clone().shrink(
                (x0 as u32, (y0 as usize + tile_px - 30) as u32),
                (tile_px as u32, 30),
            );
            scale_bar(&bar, *pixel, tile_px as u32, "")?;
        }
        Ok(())
    })?;

    let path = out_dir("")?.join("sea_states.png");
    if palette {
        save_indexed(&path, width, height, &sheet)?;
    } else {
        save_rgb8(&path, width, height, &sheet)?;
    }
    println!(
        "wrote {} ({width}×{height}; each tile {tile_px}² pixels from above, x to the right, \
         z down, t = 24 s)",
        path.display()
    );
    println!(
        "repeats inside each tile: the largest correlation coefficient of the heights (and of \
         the slope vectors) with themselves shifted by a cascade length L < window along x or \
         z; below 0.2 means no visible repeat (heights of shifts L < λp, inside one wave, \
         correlate whether or not anything repeats, and are not counted)"
    );
    for (name, window, repeat, cascades) in repeats {
        let text: Vec<String> = repeat
            .iter()
            .map(|r| {
                let height = if r.length as f64 >= r.wavelength {
                    format!("height {:+.3}", r.height)
                } else {
                    "height (L < λp)".to_string()
                };
                format!("L = {} m: {height}, slope {:+.3}", r.length, r.slope)
            })
            .collect();
        println!(
            "  {name:<16} window {window:>5.0} m, {cascades} cascade(s) drawn: {}",
            if text.is_empty() {
                "no cascade shorter than the window".to_string()
            } else {
                text.join("; ")
            }
        );
    }
    println!("done in {:.2} s", start.elapsed().as_secs_f32());
    Ok(())
}

/// Peak wavelength λ_p = 2π/k_p in metres, k_p from the peak frequency under the preset's
/// dispersion.
fn peak_wavelength(state: SeaState) -> f64 {
    let (spectrum, _) = state.build();
    let k = spectrum.dispersion().k_from_omega(spectrum.peak_omega());
    std::f64::consts::TAU / f64::from(k)
}

/// The side of a preset's tile window in metres: [`WAVELENGTHS`] peak wavelengths, at most
/// [`MAX_FRACTION`] of the largest cascade's length, rounded down to 2 significant digits.
fn window_side(state: SeaState) -> f64 {
    let (_, config) = state.build();
    let side =
        (WAVELENGTHS * peak_wavelength(state)).min(MAX_FRACTION * f64::from(config.lengths[0]));
    let unit = 10f64.powf(side.log10().floor() - 1.0);
    (side / unit).floor() * unit
}

/// The correlation of a tile with itself shifted by one cascade length.
struct Repeat {
    length: f32,
    /// The sea's peak wavelength in metres.
    wavelength: f64,
    /// Largest correlation coefficient of the heights over the shifts along x and along z.
    height: f64,
    /// Largest correlation coefficient of the slope vectors (Σ s·s′ / √(Σ|s|² Σ|s′|²), means
    /// removed) over the same shifts.
    slope: f64,
}

/// For every cascade shorter than `window`: the correlation of the surface over the
/// `window`-wide tile at the origin with itself shifted by the cascade's length, along x and
/// along z, on an `m`×`m` grid of points, over the points whose shifted twin also lies inside
/// the tile.
fn repeat_correlation(
    ocean: &OceanState,
    window: f64,
    wavelength: f64,
    m: usize,
) -> Result<Vec<Repeat>> {
    let spacing = window / m as f64;
    let mut base = vec![SurfaceSample::default(); m * m];
    let mut shifted = vec![SurfaceSample::default(); m * m];
    ocean
        .water()
        .at_rest_grid([0.0, 0.0], spacing, [m, m], &mut base)?;
    let mut out = Vec::new();
    for cascade in ocean.cascades() {
        let length = f64::from(cascade.length());
        if length >= window {
            continue;
        }
        let inside = ((window - length) / spacing).floor() as usize;
        let mut repeat = Repeat {
            length: cascade.length(),
            wavelength,
            height: f64::NEG_INFINITY,
            slope: f64::NEG_INFINITY,
        };
        for axis in 0..2 {
            let origin = if axis == 0 {
                [length, 0.0]
            } else {
                [0.0, length]
            };
            ocean
                .water()
                .at_rest_grid(origin, spacing, [m, m], &mut shifted)?;
            let pairs = (0..m * m).filter(|&p| {
                let (i, j) = (p % m, p / m);
                (if axis == 0 { i } else { j }) < inside
            });
            let pairs: Vec<usize> = pairs.collect();
            let heights = |s: &[SurfaceSample]| -> Vec<[f64; 1]> {
                pairs.iter().map(|&p| [f64::from(s[p].height)]).collect()
            };
            let slopes = |s: &[SurfaceSample]| -> Vec<[f64; 2]> {
                pairs.iter().map(|&p| s[p].slope.map(f64::from)).collect()
            };
            repeat.height = repeat
                .height
                .max(correlation(&heights(&base), &heights(&shifted)));
            repeat.slope = repeat
                .slope
                .max(correlation(&slopes(&base), &slopes(&shifted)));
        }
        out.push(repeat);
    }
    Ok(out)
}

/// Correlation coefficient of two equally long lists of vectors: Σ a·b / √(Σ|a|² Σ|b|²) after
/// removing each list's mean.
fn correlation<const D: usize>(a: &[[f64; D]], b: &[[f64; D]]) -> f64 {
    let mean = |v: &[[f64; D]]| {
        let mut m = [0.0; D];
        for x in v {
            for d in 0..D {
                m[d] += x[d] / v.len() as f64;
            }
        }
        m
    };
    let (ma, mb) = (mean(a), mean(b));
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        for d in 0..D {
            let (p, q) = (x[d] - ma[d], y[d] - mb[d]);
            ab += p * q;
            aa += p * p;
            bb += q * q;
        }
    }
    ab / (aa * bb).sqrt().max(1e-300)
}
