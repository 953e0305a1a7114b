//! Second-order waves (`OceanConfig::second_order`): a long-crested swell seen along its
//! direction of travel, without and with them, beside the Stokes second-order profile.
//!
//! The swell is JONSWAP from parameters (T_p = 10 s, α = 0.008, γ = 5; H_s about 5.4 m)
//! with a narrow cos-2s spreading (s = 60), its band cut at 2 k_p so that the swell alone
//! shows, on one 256² cascade of 16 peak wavelengths, at the default choppiness 1. The water
//! height along a line in the direction of travel (`heights_at`, what a row of buoys sees)
//! is drawn at one moment for the same waves three ways: linear (choppiness 0, no second
//! order: crests and troughs alike), the crate's default (choppiness 1: crests sharper,
//! troughs flatter, but no higher), and with second order (crests higher, troughs shallower:
//! the bound waves of second-order theory). Below, each less the linear profile: what the
//! horizontal displacement and the bound waves add. Beside it, one wave of the swell's peak
//! wave number k and amplitude a = H_s/2: its linear profile a cos θ and Stokes'
//! second-order profile a cos θ + ½ k a² cos 2θ, and below their difference.
//!
//! Writes `out/second_order.png` and prints the mean crest height and trough depth of each
//! profile on the transect (a few waves: the statistics of many are in `docs/theory.md`).
//!
//! Option: `--palette` writes an indexed PNG of 256 colours (for the README's gallery).
//!
//! Run with `cargo run --release -p ocean-fft-examples --example second_order`.

mod common;

use std::f64::consts::TAU;

use clap::Parser;
use ocean_fft::{OceanConfig, OceanState, Spectrum, Spreading};

use plotters::prelude::*;

use common::plot::{draw_legend, draw_png, line_swatch, FONT, SERIES};
use common::{out_dir, Result};

/// Points along the transect.
const POINTS: usize = 1600;

/// Second-order waves of a long-crested swell along a transect: out/second_order.png.
#[derive(Parser)]
#[command(name = "second_order", max_term_width = 100, args_override_self = true)]
struct Options {
    /// Write the plot as an indexed PNG of at most 256 colours, as the README's gallery does.
    #[arg(long)]
    palette: bool,
}

fn main() -> Result<()> {
    let start = std::time::Instant::now();
    let options = Options::parse();
    let peak_omega = (TAU / 10.0) as f32;
    let spectrum = Spectrum::jonswap_from_parameters(0.008, peak_omega, 5.0)?
        .with_spreading(Spreading::Cos2s { s: 60.0 })?;
    let hs = f64::from(spectrum.significant_wave_height());
    let k_peak = f64::from(peak_omega).powi(2) / 9.81;
    let peak_length = TAU / k_peak;
    // 16 peak wavelengths on one tile, the band cut at 2 k_p (below half its Nyquist wave
    // number, so every wave takes part in the second order).
    let lengths = vec![(16.0 * peak_length) as f32];
    let profile = |choppiness: f32, second_order: bool| -> Result<Vec<(f64, f64)>> {
        let config = OceanConfig {
            lengths: lengths.clone(),
            k_max: (2.0 * k_peak) as f32,
            choppiness,
            second_order,
            ..OceanConfig::default()
        };
        let mut ocean = OceanState::new(spectrum.clone(), config)?;
        ocean.set_time(140.0)?;
        // Five peak wavelengths along the direction of travel (+x, the wind's direction).
        let span = 5.0 * peak_length;
        let points: Vec<[f64; 2]> = (0..POINTS)
            .map(|i| [i as f64 / (POINTS - 1) as f64 * span + 311.0, 57.0])
            .collect();
        let mut heights = vec![0.0f32; POINTS];
        ocean.water().heights_at(&points, &mut heights)?;
        Ok(points
            .iter()
            .zip(&heights)
            .map(|(p, &h)| (p[0] - 311.0, f64::from(h)))
            .collect())
    };
    let linear = profile(0.0, false)?;
    let choppy = profile(1.0, false)?;
    let second = profile(1.0, true)?;
    for (name, p) in [
        ("linear", &linear),
        ("choppiness 1", &choppy),
        ("choppiness 1, second order", &second),
    ] {
        let (crest, trough) = crests_and_troughs(p);
        println!(
            "{name}: mean crest {crest:.2} m, mean trough {trough:.2} m (over the transect; H_s {hs:.2} m)"
        );
    }

    let path = out_dir("")?.join("second_order.png");
    let a = 0.5 * hs;
    draw_png(&path, 1100, 640, options.palette, |root| {
        let text = 15.0;
        let root = root.titled(
            &format!(
                "A long-crested swell (T_p = 10 s, H_s = {hs:.1} m) along its direction of travel"
            ),
            (FONT, text * 1.15).into_font(),
        )?;
        let (left, right) = root.split_horizontally(root.dim_in_pixel().0 * 68 / 100);
        let (left_top, left_bottom) = left.split_vertically(left.dim_in_pixel().1 * 62 / 100);
        let (right_top, right_bottom) = right.split_vertically(right.dim_in_pixel().1 * 62 / 100);
        let span = linear.last().map_or(1.0, |p| p.0);
        let top = [&linear, &choppy, &second]
            .iter()
            .flat_map(|p| p.iter())
            .fold(0.5f64, |m, p| m.max(p.1.abs()))
            * 1.25;
        let minus = |p: &[(f64, f64)]| -> Vec<(f64, f64)> {
            p.iter()
                .zip(&linear)
                .map(|(a, b)| (a.0, a.1 - b.1))
                .collect()
        };
        let (d_choppy, d_second) = (minus(&choppy), minus(&second));
        let bottom = d_choppy
            .iter()
            .chain(&d_second)
            .fold(0.1f64, |m, p| m.max(p.1.abs()))
            * 1.2;
        let grey = RGBColor(150, 150, 150);
        let mesh = |chart: &mut ChartContext<'_, BitMapBackend<'_>, _>,
                    x: &str,
                    y: &str,
                    (x_digits, digits): (usize, usize)|
         -> Result<()> {
            chart
                .configure_mesh()
                .x_desc(x)
                .y_desc(y)
                .x_labels(8)
                .y_labels(7)
                .max_light_lines(1)
                .label_style((FONT, text).into_font())
                .axis_desc_style((FONT, text).into_font())
                .x_label_formatter(&|v: &f64| {
                    format!("{:.x_digits$}", if v.abs() < 1e-9 { 0.0 } else { *v })
                })
                .y_label_formatter(&|v: &f64| {
                    format!("{:.digits$}", if v.abs() < 1e-9 { 0.0 } else { *v })
                })
                .light_line_style(RGBColor(240, 240, 240))
                .draw()?;
            Ok(())
        };

        let mut chart = ChartBuilder::on(&left_top)
            .margin(10)
            .x_label_area_size(text * 1.5)
            .y_label_area_size(text * 3.5)
            .build_cartesian_2d(0.0..span, -top..top)?;
        mesh(&mut chart, "", "water height y [m]", (0, 0))?;
        for (p, colour, width, label) in [
            (&linear, grey, 1, "linear (choppiness 0)"),
            (&choppy, SERIES[0], 2, "choppiness 1, second order off"),
            (&second, SERIES[3], 2, "choppiness 1, second order on"),
        ] {
            chart
                .draw_series(LineSeries::new(
                    p.iter().copied(),
                    colour.stroke_width(width),
                ))?
                .label(label)
                .legend(line_swatch(colour));
        }
        draw_legend(&mut chart, SeriesLabelPosition::LowerRight, text * 0.9)?;

        let mut chart = ChartBuilder::on(&left_bottom)
            .margin(10)
            .x_label_area_size(text * 3.0)
            .y_label_area_size(text * 3.5)
            .build_cartesian_2d(0.0..span, -bottom..bottom)?;
        mesh(
            &mut chart,
            "distance along the swell [m]",
            "less linear [m]",
            (0, 1),
        )?;
        for (p, colour, label) in [
            (&d_choppy, SERIES[0], "second order off"),
            (&d_second, SERIES[3], "second order on"),
        ] {
            chart
                .draw_series(LineSeries::new(p.iter().copied(), colour.stroke_width(2)))?
                .label(label)
                .legend(line_swatch(colour));
        }
        draw_legend(&mut chart, SeriesLabelPosition::LowerRight, text * 0.9)?;

        // One peak wave: a cos θ and Stokes' a cos θ + ½ k a² cos 2θ, over one wavelength.
        let wave = |order: usize| {
            (0..=400).map(move |i| {
                let u = i as f64 / 400.0 - 0.5;
                let theta = TAU * u;
                let first = if order == 2 { 0.0 } else { a * theta.cos() };
                let second = if order == 0 {
                    0.0
                } else {
                    0.5 * k_peak * a * a * (2.0 * theta).cos()
                };
                (u, first + second)
            })
        };
        let mut chart = ChartBuilder::on(&right_top)
            .margin(10)
            .x_label_area_size(text * 1.5)
            .y_label_area_size(text * 2.5)
            .caption(
                format!("Stokes, k = k_p, a = H_s/2 (ka = {:.2})", k_peak * a),
                (FONT, text).into_font(),
            )
            .build_cartesian_2d(-0.5..0.5, -top..top)?;
        mesh(&mut chart, "", "", (1, 0))?;
        chart
            .draw_series(LineSeries::new(wave(0), grey.stroke_width(1)))?
            .label("a cos θ")
            .legend(line_swatch(grey));
        chart
            .draw_series(LineSeries::new(wave(1), SERIES[2].stroke_width(2)))?
            .label("a cos θ + ½ka² cos 2θ")
            .legend(line_swatch(SERIES[2]));
        draw_legend(&mut chart, SeriesLabelPosition::LowerMiddle, text * 0.9)?;
        let mut chart = ChartBuilder::on(&right_bottom)
            .margin(10)
            .x_label_area_size(text * 3.0)
            .y_label_area_size(text * 2.5)
            .build_cartesian_2d(-0.5..0.5, -bottom..bottom)?;
        mesh(&mut chart, "phase θ/2π", "", (1, 1))?;
        chart
            .draw_series(LineSeries::new(wave(2), SERIES[2].stroke_width(2)))?
            .label("½ka² cos 2θ")
            .legend(line_swatch(SERIES[2]));
        draw_legend(&mut chart, SeriesLabelPosition::LowerMiddle, text * 0.9)?;
        Ok(())
    })?;
    println!(
        "wrote {} (left: water height [m] against distance [m]; right: one wave against phase)",
        path.display()
    );
    println!("done in {:.2} s", start.elapsed().as_secs_f32());
    Ok(())
}

/// Mean crest height and mean trough depth (positive down) of the zero-crossing waves of a
/// profile: the highest point between an up-crossing and the next down-crossing, the lowest
/// between a down-crossing and the next up-crossing.
fn crests_and_troughs(profile: &[(f64, f64)]) -> (f64, f64) {
    let (mut crests, mut troughs) = (Vec::new(), Vec::new());
    let mut extreme: Option<f64> = None;
    for pair in profile.windows(2) {
        let (y0, y1) = (pair[0].1, pair[1].1);
        let crossed = (y0 < 0.0) != (y1 < 0.0);
        if crossed {
            if let Some(e) = extreme.take() {
                if y0 >= 0.0 {
                    crests.push(e);
                } else {
                    troughs.push(-e);
                }
            }
            extreme = Some(y1);
        } else if let Some(e) = extreme.as_mut() {
            *e = if y1 >= 0.0 { e.max(y1) } else { e.min(y1) };
        }
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    (mean(&crests), mean(&troughs))
}
