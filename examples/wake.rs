//! Kelvin wakes seen from above: `out/wake.png`, a 20 m × 5 m hull of 1 m draft at 8 m/s
//! (length Froude number 0.57) in deep water for 50 s, the 256 m wake window (512 cells of
//! 0.5 m) following it, the wake's height shaded (crests light, troughs dark), its foam trail
//! blended in white, and Kelvin's cusp lines at ±19.47° from the track drawn in red from the
//! hull's centre; and `out/wake_depth.png`, the same hull over deep water and over water
//! 13.3 m and 7.2 m deep (depth Froude numbers U/√(gh) = 0.7 and 0.95), where the wedge
//! widens beyond Kelvin's lines as Havelock (1908) found.
//!
//! Option: `--palette` writes both pictures as indexed PNGs of 256 colours (for the README's
//! gallery).
//!
//! Run with `cargo run --release -p ocean-fft-examples --example wake` (about 20 s on 2 cores).

mod common;

use clap::Parser;
use ocean_fft::{Hull, OceanConfig, OceanState, Spectrum, WakeConfig};

use common::{out_dir, save_indexed, Canvas, Result};

/// Kelvin wakes from above: out/wake.png and out/wake_depth.png.
#[derive(Parser)]
#[command(name = "wake", max_term_width = 100, args_override_self = true)]
struct Options {
    /// Write the pictures as indexed PNGs of at most 256 colours, as the README's gallery does.
    #[arg(long)]
    palette: bool,
}

/// Writes `canvas` as RGB, or indexed with `palette`.
fn save(canvas: &Canvas, path: &std::path::Path, palette: bool) -> Result<()> {
    if palette {
        save_indexed(path, canvas.width, canvas.height, &canvas.pixels)
    } else {
        canvas.save(path)
    }
}

/// The hull's speed, m/s.
const SPEED: f64 = 8.0;
/// Side of the wake window, m (512 cells of 0.5 m).
const SIDE: f64 = 256.0;
/// Standard gravity, m/s².
const G: f64 = 9.81;

/// Runs the default hull straight along +x for 50 s at `SPEED` over a light sea of the
/// `spectrum`'s depth, the wake window a third of its side ahead of the hull's track.
fn sail(spectrum: Spectrum) -> Result<OceanState> {
    let wakes = WakeConfig {
        size: 512,
        spacing: 0.5,
        substep: 0.05,
        ..WakeConfig::default()
    };
    let config = OceanConfig {
        size: 16,
        wakes: Some(wakes),
        ..OceanConfig::default()
    }
    .with_fitted_lengths(&spectrum)?;
    let mut ocean = OceanState::new(spectrum, config)?;
    ocean.set_hulls(&[Hull {
        velocity: [SPEED as f32, 0.0],
        ..Hull::default()
    }])?;
    for step in 1..=1000 {
        ocean.step_to(f64::from(step) * 0.05)?;
        ocean.set_wake_centre(SPEED * ocean.time() - 0.3 * SIDE, 0.0)?;
    }
    Ok(ocean)
}

/// The wake window of `ocean` as an image, one pixel a cell, with Kelvin's cusp lines.
fn draw(ocean: &OceanState) -> Canvas {
    let wakes = ocean.wakes().expect("wakes are on");
    let n = wakes.size();
    let scale = 0.3; // m of wake height to full contrast
    let mut canvas = Canvas::new(n, n, [0, 0, 0]);
    for (index, (&h, &foam)) in wakes.height().iter().zip(wakes.foam()).enumerate() {
        let v = (0.5 + 0.5 * (h / scale).clamp(-1.0, 1.0)) * 255.0;
        let (i, j) = (index % n, index / n);
        let water = [v * 0.6, v * 0.8, v];
        let white = water.map(|c| (c + (255.0 - c) * foam) as u8);
        canvas.set(i as i64, j as i64, white);
    }
    // The cusp lines from the hull's centre, backwards along the track.
    let spacing = f64::from(wakes.spacing());
    let hull = [SPEED * ocean.time(), 0.0];
    let to_pixel = |x: f64, z: f64| {
        (
            ((x - wakes.origin()[0]) / spacing) as f32,
            ((z - wakes.origin()[1]) / spacing) as f32,
        )
    };
    let cusp = (1.0f64 / 3.0).asin();
    for sign in [-1.0, 1.0] {
        let end = [hull[0] - 300.0 * cusp.cos(), sign * 300.0 * cusp.sin()];
        canvas.line(
            to_pixel(hull[0], hull[1]),
            to_pixel(end[0], end[1]),
            1,
            [220, 40, 40],
        );
    }
    canvas
}

/// The lowest and highest wake height of `ocean`, m.
fn range(ocean: &OceanState) -> (f32, f32) {
    let height = ocean.wakes().expect("wakes are on").height();
    let low = height.iter().copied().fold(f32::MAX, f32::min);
    let high = height.iter().copied().fold(f32::MIN, f32::max);
    (low, high)
}

fn main() -> Result<()> {
    let options = Options::parse();
    let deep = sail(Spectrum::jonswap(2.0, 1000.0)?)?;
    let canvas = draw(&deep);
    let path = out_dir("")?.join("wake.png");
    save(&canvas, &path, options.palette)?;
    let (low, high) = range(&deep);
    println!(
        "{}: t = {:.1} s, hull at x = {:.1} m, wake height in [{low:.3}, {high:.3}] m",
        path.display(),
        deep.time(),
        SPEED * deep.time(),
    );

    // Deep water, then two depths with U/√(gh) = 0.7 and 0.95, side by side under labels.
    let label = 30;
    let n = canvas.width;
    let mut strip = Canvas::new(3 * n + 4 * 8, n + label + 8, [255, 255, 255]);
    let mut panels = vec![("DEEP WATER".to_string(), canvas)];
    for froude in [0.7, 0.95] {
        let depth = (SPEED / froude).powi(2) / G;
        let ocean = sail(Spectrum::tma(2.0, 1000.0, depth as f32)?)?;
        let (low, high) = range(&ocean);
        println!(
            "depth {depth:.1} m (U/sqrt(gh) = {froude}): wake height in [{low:.3}, {high:.3}] m"
        );
        panels.push((format!("DEPTH {depth:.1} M  FROUDE {froude}"), draw(&ocean)));
    }
    for (index, (title, panel)) in panels.iter().enumerate() {
        let x = 8 + index as i64 * (n as i64 + 8);
        strip.text(x, 8, title, 3, [20, 20, 20]);
        strip.blit(x, label as i64, n, n, &panel.pixels);
    }
    let path = out_dir("")?.join("wake_depth.png");
    save(&strip, &path, options.palette)?;
    println!("{}", path.display());
    Ok(())
}
