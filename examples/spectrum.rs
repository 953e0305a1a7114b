//! Plots the frequency spectrum S(ω) of a few sea states and the directional spreading D(θ) at
//! the peak for each spreading function into `out/spectrum.png`, and prints each sea state's
//! significant wave height and peak period.
//!
//! Run with `cargo run --release -p ocean-fft-examples --example spectrum`.

mod common;

use std::f32::consts::PI;
use std::path::Path;

use ocean_fft::{Spectrum, Spreading};

const WIDTH: usize = 1200;
const HEIGHT: usize = 500;
const PANEL: usize = 600;
const MARGIN: usize = 40;
const COLORS: [[u8; 3]; 6] = [
    [31, 119, 180],
    [255, 127, 14],
    [44, 160, 44],
    [214, 39, 40],
    [148, 103, 189],
    [23, 190, 207],
];

struct Canvas {
    pixels: Vec<u8>,
}

impl Canvas {
    fn new() -> Self {
        Canvas {
            pixels: vec![255; WIDTH * HEIGHT * 3],
        }
    }

    fn dot(&mut self, x: i64, y: i64, color: [u8; 3]) {
        for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let (px, py) = (x + dx, y + dy);
            if px >= 0 && py >= 0 && (px as usize) < WIDTH && (py as usize) < HEIGHT {
                let i = (py as usize * WIDTH + px as usize) * 3;
                self.pixels[i..i + 3].copy_from_slice(&color);
            }
        }
    }

    /// Plots `points` (x, y in [0, 1]) as a polyline in panel `panel` (0 or 1).
    fn curve(&mut self, panel: usize, points: &[(f32, f32)], color: [u8; 3]) {
        let to_px = |(x, y): (f32, f32)| {
            let w = (PANEL - 2 * MARGIN) as f32;
            let h = (HEIGHT - 2 * MARGIN) as f32;
            (
                (panel * PANEL + MARGIN) as f32 + x * w,
                (HEIGHT - MARGIN) as f32 - y * h,
            )
        };
        for pair in points.windows(2) {
            let (a, b) = (to_px(pair[0]), to_px(pair[1]));
            let steps = ((b.0 - a.0).abs().max((b.1 - a.1).abs()).ceil() as usize).max(1);
            for s in 0..=steps {
                let t = s as f32 / steps as f32;
                let x = a.0 + t * (b.0 - a.0);
                let y = a.1 + t * (b.1 - a.1);
                self.dot(x as i64, y as i64, color);
            }
        }
    }

    fn axes(&mut self, panel: usize) {
        let grey = [120, 120, 120];
        self.curve(panel, &[(0.0, 0.0), (1.0, 0.0)], grey);
        self.curve(panel, &[(0.0, 0.0), (0.0, 1.0)], grey);
    }

    fn save(&self, path: &str) -> common::Result<()> {
        common::save_rgb8(Path::new(path), WIDTH, HEIGHT, &self.pixels)
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let sea_states = [
        (
            "Pierson-Moskowitz U=10 m/s",
            Spectrum::pierson_moskowitz(10.0)?,
        ),
        (
            "JONSWAP U=10 m/s F=100 km",
            Spectrum::jonswap(10.0, 100_000.0)?,
        ),
        (
            "JONSWAP U=15 m/s F=300 km",
            Spectrum::jonswap(15.0, 300_000.0)?,
        ),
        (
            "TMA U=10 m/s F=100 km h=5 m",
            Spectrum::tma(10.0, 100_000.0, 5.0)?,
        ),
        ("JONSWAP U=6 m/s F=20 km", Spectrum::jonswap(6.0, 20_000.0)?),
    ];
    let mut canvas = Canvas::new();

    // Left: S(ω) for ω in [0, 3] rad/s, normalised by the largest peak.
    let omegas: Vec<f32> = (1..=600).map(|i| i as f32 * 3.0 / 600.0).collect();
    let peak = sea_states
        .iter()
        .flat_map(|(_, s)| omegas.iter().map(move |&w| s.omega_spectrum(w)))
        .fold(0.0_f32, f32::max);
    canvas.axes(0);
    println!(
        "{:<30} {:>8} {:>8} {:>10}",
        "sea state", "Hs [m]", "Tp [s]", "ω_p [rad/s]"
    );
    for (i, (name, spectrum)) in sea_states.iter().enumerate() {
        let points: Vec<(f32, f32)> = omegas
            .iter()
            .map(|&w| (w / 3.0, spectrum.omega_spectrum(w) / peak))
            .collect();
        canvas.curve(0, &points, COLORS[i]);
        println!(
            "{name:<30} {:>8.3} {:>8.2} {:>10.3}",
            spectrum.significant_wave_height(),
            spectrum.peak_period(),
            spectrum.peak_omega()
        );
    }

    // Right: D(ω_p, θ) for θ in [−π, π] for each spreading, normalised by the largest.
    let base = Spectrum::jonswap(10.0, 100_000.0)?;
    let spreadings = [
        Spreading::DonelanBanner,
        Spreading::Mitsuyasu,
        Spreading::Hasselmann,
        Spreading::Cos2s { s: 4.0 },
        Spreading::Cos2,
        Spreading::Flat,
    ];
    let thetas: Vec<f32> = (0..=720)
        .map(|i| -PI + i as f32 * 2.0 * PI / 720.0)
        .collect();
    let curves: Vec<Vec<f32>> = spreadings
        .iter()
        .map(|&s| {
            let spectrum = base.clone().with_spreading(s)?;
            Ok(thetas
                .iter()
                .map(|&t| spectrum.spreading(spectrum.peak_omega(), t))
                .collect())
        })
        .collect::<Result<_, ocean_fft::Error>>()?;
    let top = curves.iter().flatten().fold(0.0_f32, |a, &b| a.max(b));
    canvas.axes(1);
    for (i, curve) in curves.iter().enumerate() {
        let points: Vec<(f32, f32)> = thetas
            .iter()
            .zip(curve)
            .map(|(&t, &d)| ((t + PI) / (2.0 * PI), d / top))
            .collect();
        canvas.curve(1, &points, COLORS[i]);
    }
    println!("spreading at ω_p (right panel, colours in order): {spreadings:?}");

    std::fs::create_dir_all("out")?;
    canvas.save("out/spectrum.png")?;
    println!("wrote out/spectrum.png (left: S(ω), ω from 0 to 3 rad/s; right: D(θ) at ω_p, θ from −π to π)");
    Ok(())
}
