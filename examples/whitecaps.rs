//! Whitecap coverage against wind speed on the default ocean: for U10 = 5, 7.5, 10, 15 and
//! 20 m/s, fully developed JONSWAP (`Spectrum::jonswap(u, 1e7)`, the fetch capped at full
//! development) and Pierson–Moskowitz seas on `OceanConfig::default()` (three cascades of 256²
//! over 1000, 230 and 51 m, default `FoamConfig`), the foam is pre-rolled for 20 s (five
//! active lifetimes) and the coverage averaged over the next 20 s in steps of 1/20 s. Prints
//! the active and residual coverage beside the whitecap fraction of Monahan &
//! O'Muircheartaigh (1980), W = 3.84e-6 U10^3.41, and plots them on log–log axes into
//! `out/whitecaps.png` (the line: the formula; dots: active coverage, JONSWAP blue, P–M
//! orange; rings: residual coverage).
//!
//! Run with `cargo run --release -p ocean-fft-examples --example whitecaps` (two to three minutes
//! on 2 cores).

mod common;

use ocean_fft::{OceanConfig, OceanState, Spectrum};

use common::{out_dir, Canvas, Result};

const WINDS: [f32; 5] = [5.0, 7.5, 10.0, 15.0, 20.0];
const WIDTH: usize = 640;
const HEIGHT: usize = 480;
const MARGIN: f32 = 60.0;

fn monahan(wind: f64) -> f64 {
    3.84e-6 * wind.powf(3.41)
}

fn main() -> Result<()> {
    let start = std::time::Instant::now();
    let dt = 1.0 / 20.0;
    let mut rows = Vec::new();
    println!("spectrum  U10 m/s   W (MO80)   active    ratio  residual   J_b");
    for (name, index) in [("JONSWAP", 0usize), ("P-M", 1)] {
        for wind in WINDS {
            let spectrum = if index == 0 {
                Spectrum::jonswap(wind, 1e7)?
            } else {
                Spectrum::pierson_moskowitz(wind)?
            };
            let mut ocean = OceanState::new(spectrum, OceanConfig::default())?;
            ocean.set_time(100.0)?;
            ocean.pre_roll(20.0, dt)?;
            let steps = 400;
            let (mut active, mut residual) = (0.0f64, 0.0f64);
            for _ in 0..steps {
                ocean.step(dt)?;
                let c = ocean.foam_coverage();
                active += f64::from(c.active);
                residual += f64::from(c.residual);
            }
            let (active, residual) = (active / steps as f64, residual / steps as f64);
            let expected = monahan(f64::from(wind));
            println!(
                "{name:8} {wind:7.1} {expected:10.3e} {active:10.3e} {:7.3} {residual:9.3e} {:.3}",
                active / expected,
                ocean.foam_calibration().threshold
            );
            rows.push((index, wind, active, residual));
        }
    }

    // Log–log axes: U10 from 4 to 25 m/s, coverage from 1e-4 to 1.
    let mut canvas = Canvas::new(WIDTH, HEIGHT, [255, 255, 255]);
    let (u0, u1, w0, w1) = (4f32.ln(), 25f32.ln(), 1e-4f32.ln(), 1f32.ln());
    let to_px = |u: f32, w: f32| {
        let x = MARGIN + (u.ln() - u0) / (u1 - u0) * (WIDTH as f32 - 2.0 * MARGIN);
        let y = HEIGHT as f32 - MARGIN - (w.ln() - w0) / (w1 - w0) * (HEIGHT as f32 - 2.0 * MARGIN);
        (x, y)
    };
    let grey = [200, 200, 200];
    for decade in [1e-4f32, 1e-3, 1e-2, 1e-1, 1.0] {
        let (a, b) = (to_px(4.0, decade), to_px(25.0, decade));
        canvas.line(a, b, 1, grey);
        let label = format!("{decade:e}").to_uppercase();
        canvas.text(8, a.1 as i64 - 3, &label, 1, [80, 80, 80]);
    }
    for wind in [5.0f32, 10.0, 20.0] {
        let (a, b) = (to_px(wind, 1e-4), to_px(wind, 1.0));
        canvas.line(a, b, 1, grey);
        canvas.text(
            a.0 as i64 - 4,
            HEIGHT as i64 - 40,
            &format!("{wind}"),
            2,
            [80, 80, 80],
        );
    }
    canvas.text(
        WIDTH as i64 / 2 - 60,
        HEIGHT as i64 - 20,
        "U10 M/S (LOG)",
        2,
        [80, 80, 80],
    );
    canvas.text(
        MARGIN as i64,
        12,
        "COVERAGE (LOG): LINE MO80, DOTS ACTIVE, RINGS RESIDUAL",
        1,
        [80, 80, 80],
    );
    let line: Vec<(f32, f32)> = (0..=100)
        .map(|k| {
            let u = 4.0 * (25.0f32 / 4.0).powf(k as f32 / 100.0);
            to_px(u, monahan(f64::from(u)) as f32)
        })
        .collect();
    canvas.polyline(&line, 2, [40, 40, 40]);
    let colours = [[31, 119, 180], [255, 127, 14]];
    for &(index, wind, active, residual) in &rows {
        let shift = if index == 0 { -3.0 } else { 3.0 };
        let (x, y) = to_px(wind, active as f32);
        canvas.dot((x + shift) as i64 - 4, y as i64 - 4, 9, colours[index]);
        let (x, y) = to_px(wind, residual as f32);
        for k in 0..24 {
            let angle = k as f32 / 24.0 * std::f32::consts::TAU;
            canvas.dot(
                (x + shift + 5.0 * angle.cos()) as i64,
                (y + 5.0 * angle.sin()) as i64,
                2,
                colours[index],
            );
        }
    }
    let path = out_dir("")?.join("whitecaps.png");
    canvas.save(&path)?;
    println!(
        "wrote {}; done in {:.0} s",
        path.display(),
        start.elapsed().as_secs_f32()
    );
    Ok(())
}
