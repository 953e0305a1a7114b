//! Waves on a beach (`OceanState::set_depth_map`): the fresh breeze preset running onto a
//! planar beach of slope 1:50, measured by virtual buoys, beside a Battjes & Janssen model.
//!
//! The depth map is 2 200 m long along the wind (+x), 40 m deep at its offshore edge (x = 0)
//! and dry from x = 2 000 m on, 400 m wide, in 4 m cells. At each depth from 20 m to 1 m a
//! row of 32 buoys across the beach records the water height (`heights_at`) at 160 instants
//! 1.37 s apart; H_s = 4·std. Beside them: the Battjes & Janssen (1978) model of the same
//! beach (one frequency, the spectrum's peak; the energy flux integrated by RK4 from the
//! map's edge, with Ruessink et al.'s (2003) breaker index, as `tests/coast.rs` does), linear
//! shoaling alone (no breaking), and the band 0.3 d ≤ H_s ≤ 0.6 d where measured surf zones
//! lie (Thornton & Guza 1983: H_s ≈ 0.59 d).
//!
//! Writes `out/beach.png` and prints the table: depth, the buoys' H_s, the model's, their
//! ratio, H_s/d and the fraction of breaking waves Q_b at the buoys.
//!
//! Option: `--palette` writes an indexed PNG of 256 colours (for the README's gallery).
//!
//! Run with `cargo run --release -p ocean-fft-examples --example beach`.

mod common;

use std::f64::consts::TAU;

use clap::Parser;
use ocean_fft::{DepthMap, OceanState, SeaState};

use plotters::prelude::*;

use common::plot::{draw_legend, draw_png, line_swatch, FONT, SERIES};
use common::{out_dir, Result};

const G: f64 = 9.81;
/// Depth at the map's offshore edge (m), the beach's slope, and the map's cells (m).
const DEEP: f64 = 40.0;
const SLOPE: f64 = 1.0 / 50.0;
const SPACING: f32 = 4.0;
/// The buoys' depths (m).
const DEPTHS: [f64; 13] = [
    20.0, 16.0, 12.0, 10.0, 8.0, 6.0, 5.0, 4.0, 3.0, 2.5, 2.0, 1.5, 1.0,
];

/// The fresh breeze on a 1:50 beach, buoys against Battjes & Janssen: out/beach.png.
#[derive(Parser)]
#[command(name = "beach", max_term_width = 100, args_override_self = true)]
struct Options {
    /// Write the plot as an indexed PNG of at most 256 colours, as the README's gallery does.
    #[arg(long)]
    palette: bool,
}

fn main() -> Result<()> {
    let start = std::time::Instant::now();
    let options = Options::parse();
    let (spectrum, config) = SeaState::FreshBreeze.build();
    let hs0 = f64::from(spectrum.significant_wave_height());
    let omega_p = f64::from(spectrum.peak_omega());
    let mut ocean = OceanState::new(spectrum, config)?;
    let (nx, nz) = (551, 101);
    let depth = (0..nx * nz)
        .map(|c| (DEEP - SLOPE * (c % nx) as f64 * f64::from(SPACING)) as f32)
        .collect();
    let map = DepthMap {
        origin: [0.0, -200.0],
        spacing: SPACING,
        size: [nx, nz],
        depth,
    };
    let solve = std::time::Instant::now();
    ocean.set_depth_map(Some(map))?;
    println!(
        "the 551 × 101 map solved in {:.2} s",
        solve.elapsed().as_secs_f32()
    );
    ocean.set_time(10.0)?; // past the 2 s blend from the open sea

    let model = battjes_janssen(hs0, omega_p);
    let at = |d: f64| {
        let s = (DEEP - d) / SLOPE;
        model
            .iter()
            .min_by(|a, b| (a.0 - s).abs().total_cmp(&(b.0 - s).abs()))
            .map_or(0.0, |m| m.1)
    };
    println!(
        "fresh breeze: H_s {hs0:.2} m offshore, T_p {:.1} s",
        TAU / omega_p
    );
    println!("depth [m]  buoys H_s [m]  model H_s [m]  ratio  H_s/d  Q_b");
    let mut buoys = Vec::new();
    for d in DEPTHS {
        let s = (DEEP - d) / SLOPE;
        let hs = buoy_hs(&mut ocean, s)?;
        let coast = ocean.textures().coast().expect("the map is set");
        let cell = nz / 2 * nx + (s / f64::from(SPACING)).round() as usize;
        let q = coast.breaking()[cell];
        let m = at(d);
        println!(
            "{d:9.1}  {hs:13.2}  {m:13.2}  {:5.2}  {:5.2}  {q:.2}",
            hs / m,
            hs / d
        );
        buoys.push((d, hs));
    }
    // Over land the water is still: the queries say so.
    let land = ocean.water().height_at(DEEP / SLOPE + 60.0, 0.0)?;
    println!("60 m up the beach (dry): height {land} m");

    let path = out_dir("")?.join("beach.png");
    let curve = |shoal_only: bool| -> Vec<(f64, f64)> {
        model
            .iter()
            .map(|&(s, hs, shoaled)| (DEEP - SLOPE * s, if shoal_only { shoaled } else { hs }))
            .filter(|&(d, _)| (0.4..=22.0).contains(&d))
            .collect()
    };
    let (breaking, shoaling) = (curve(false), curve(true));
    draw_png(&path, 1000, 620, options.palette, |root| {
        let text = 16.0;
        let top = buoys
            .iter()
            .map(|b| b.1)
            .chain(shoaling.iter().map(|p| p.1))
            .fold(0.0f64, f64::max)
            * 1.15;
        let mut chart = ChartBuilder::on(root)
            .margin(14)
            .caption(
                format!(
                    "Fresh breeze (H_s {hs0:.1} m, T_p {:.1} s) on a 1:50 beach",
                    TAU / omega_p
                ),
                (FONT, text * 1.15).into_font(),
            )
            .x_label_area_size(text * 3.0)
            .y_label_area_size(text * 3.5)
            .build_cartesian_2d(0.0..21.0, 0.0..top)?;
        chart
            .configure_mesh()
            .x_desc("water depth d [m] (the waves come from the right)")
            .y_desc("significant wave height H_s [m]")
            .label_style((FONT, text).into_font())
            .axis_desc_style((FONT, text).into_font())
            .light_line_style(RGBColor(240, 240, 240))
            .draw()?;
        let grey = RGBColor(160, 160, 160);
        for (factor, label) in [(0.6, "H_s = 0.6 d"), (0.3, "H_s = 0.3 d")] {
            chart
                .draw_series(DashedLineSeries::new(
                    (0..=210)
                        .map(|i| (f64::from(i) / 10.0, f64::from(i) / 10.0 * factor))
                        .filter(|&(_, h)| h <= top),
                    6,
                    4,
                    grey.stroke_width(1),
                ))?
                .label(label)
                .legend(line_swatch(grey));
        }
        chart
            .draw_series(LineSeries::new(shoaling, SERIES[1].stroke_width(2)))?
            .label("linear shoaling alone")
            .legend(line_swatch(SERIES[1]));
        chart
            .draw_series(LineSeries::new(breaking, SERIES[0].stroke_width(3)))?
            .label("Battjes & Janssen model")
            .legend(line_swatch(SERIES[0]));
        let dots = SERIES[3];
        chart
            .draw_series(
                buoys
                    .iter()
                    .map(|&(d, hs)| Circle::new((d, hs), 5, dots.filled())),
            )?
            .label("buoys (heights_at)")
            .legend(move |(x, y)| Circle::new((x + 10, y), 5, dots.filled()));
        draw_legend(&mut chart, SeriesLabelPosition::UpperLeft, text * 0.9)?;
        Ok(())
    })?;
    println!("wrote {} (H_s [m] against depth [m])", path.display());
    println!("done in {:.2} s", start.elapsed().as_secs_f32());
    Ok(())
}

/// H_s = 4 std(η) of 32 buoys across the beach at distance `s` (m) from the map's edge, at
/// 160 instants 1.37 s apart.
fn buoy_hs(ocean: &mut OceanState, s: f64) -> Result<f64> {
    let points: Vec<[f64; 2]> = (0..32).map(|n| [s, -150.0 + 9.5 * f64::from(n)]).collect();
    let mut out = vec![0.0f32; points.len()];
    let (mut sum, mut sum2, mut count) = (0.0f64, 0.0f64, 0.0f64);
    for t in 0..160 {
        ocean.set_time(100.0 + 1.37 * f64::from(t))?;
        ocean.water().heights_at(&points, &mut out)?;
        for &h in &out {
            let h = f64::from(h);
            sum += h;
            sum2 += h * h;
            count += 1.0;
        }
    }
    let mean = sum / count;
    Ok(4.0 * (sum2 / count - mean * mean).max(0.0).sqrt())
}

/// Wave number (rad/m) of angular frequency ω at depth d: Newton on ω² = g k tanh(k d).
fn wavenumber(omega: f64, d: f64) -> f64 {
    let mut k = omega * omega / G / (omega * omega * d / G).sqrt().tanh().max(1e-9);
    for _ in 0..50 {
        let t = (k * d).tanh();
        k -= (G * k * t - omega * omega) / (G * t + G * k * d * (1.0 - t * t));
    }
    k
}

/// Group velocity (m/s) at depth d (∞: deep water).
fn group_velocity(omega: f64, d: f64) -> f64 {
    if d.is_infinite() {
        return G / (2.0 * omega);
    }
    let k = wavenumber(omega, d);
    0.5 * omega / k * (1.0 + 2.0 * k * d / (2.0 * k * d).sinh())
}

/// Battjes & Janssen's fraction of breaking waves: the root Q of (1 − Q)/(−ln Q) = b², by
/// the fixed point Q ← exp(−(1 − Q)/b²) from 0 (1 for b ≥ 1).
fn q_b(b: f64) -> f64 {
    if b >= 1.0 {
        return 1.0;
    }
    let mut q = 0.0f64;
    for _ in 0..100_000 {
        let next = (-(1.0 - q) / (b * b)).exp();
        if (next - q).abs() < 1e-13 {
            return next;
        }
        q = next;
    }
    q
}

/// The model along the beach: (distance s from the map's edge in m, H_s with breaking,
/// H_s by linear shoaling alone), every 5 m from the edge to 0.4 m of water. One frequency
/// (the peak), the energy flux F = H_rms² c_g/8 integrated by RK4 in steps of 0.25 m:
/// dF/ds = −(α/4) f_p Q_b H_max², α = 1, H_max = 0.88/k tanh(γ k d/0.88),
/// γ = 0.29 + 0.76 k d.
fn battjes_janssen(hs0: f64, omega_p: f64) -> Vec<(f64, f64, f64)> {
    let fp = omega_p / TAU;
    let depth = |s: f64| DEEP - SLOPE * s;
    let h_rms0 = hs0 / 2.0f64.sqrt();
    let flux0 = h_rms0 * h_rms0 * group_velocity(omega_p, f64::INFINITY) / 8.0;
    let rhs = |s: f64, flux: f64| {
        let d = depth(s);
        let cg = group_velocity(omega_p, d);
        let h_rms = (8.0 * flux.max(0.0) / cg).sqrt();
        let k = wavenumber(omega_p, d);
        let h_max = 0.88 / k * ((0.29 + 0.76 * k * d) * k * d / 0.88).tanh();
        -0.25 * fp * q_b(h_rms / h_max) * h_max * h_max
    };
    let hs = |flux: f64, s: f64| {
        (8.0 * flux.max(0.0) / group_velocity(omega_p, depth(s))).sqrt() * 2.0f64.sqrt()
    };
    let (ds, end) = (0.25, (DEEP - 0.4) / SLOPE);
    let (mut s, mut flux) = (0.0f64, flux0);
    let mut out = vec![(0.0, hs(flux, 0.0), hs(flux0, 0.0))];
    while s < end {
        let k1 = rhs(s, flux);
        let k2 = rhs(s + ds / 2.0, flux + ds / 2.0 * k1);
        let k3 = rhs(s + ds / 2.0, flux + ds / 2.0 * k2);
        let k4 = rhs(s + ds, flux + ds * k3);
        flux += ds / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
        s += ds;
        if (s / 5.0).fract() < 1e-9 || s >= end {
            out.push((s, hs(flux, s), hs(flux0, s)));
        }
    }
    out
}
