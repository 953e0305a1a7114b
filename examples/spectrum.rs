//! Plots the frequency spectra and the directional spreading functions, and prints each preset's
//! significant wave height and peak period.
//!
//! - `out/spectrum.png`: S(ω) in m²·s/rad of every preset in `SeaState::ALL` against the
//!   angular frequency ω in rad/s, both axes logarithmic (the presets' spectra span six
//!   decades; on a linear scale the calm ones would be flat lines near zero), with the ω⁻⁵
//!   slope of the Phillips saturation range for reference;
//! - `out/spreading.png`: D(ω_p, θ) in 1/rad at the peak frequency of
//!   `Spectrum::jonswap(10.0, 100_000.0)` for each spreading function, against the angle θ from
//!   the wind direction in degrees (each integrates to 1 over the circle).
//!
//! Options (`--help` lists them): `--width PIXELS` and `--height PIXELS` of both plots (1 to
//! 8192, default 900 × 560);
//! `--palette`: indexed PNGs of 256 colours (smaller, for the README's gallery).
//!
//! Run with `cargo run --release -p ocean-fft-examples --example spectrum`.

mod common;

use std::f32::consts::PI;

use clap::Parser;
use ocean_fft::{SeaState, Spectrum, Spreading};
use plotters::prelude::*;

use common::plot::{draw_legend, draw_png, line_swatch, FONT, SERIES};
use common::{out_dir, Result};

/// The presets' frequency spectra and the spreading functions: out/spectrum.png, out/spreading.png.
#[derive(Parser)]
#[command(name = "spectrum", max_term_width = 100, args_override_self = true)]
struct Options {
    /// Width of both plots in pixels, 1 to 8192.
    #[arg(
        long,
        value_name = "PIXELS",
        default_value_t = 900,
        value_parser = common::within(1u32, 8192)
    )]
    width: u32,
    /// Height of both plots in pixels, 1 to 8192.
    #[arg(
        long,
        value_name = "PIXELS",
        default_value_t = 560,
        value_parser = common::within(1u32, 8192)
    )]
    height: u32,
    /// Write indexed PNGs of at most 256 colours, as the README's gallery does.
    #[arg(long)]
    palette: bool,
}

fn main() -> Result<()> {
    let Options {
        width,
        height,
        palette,
    } = Options::parse();
    let dir = out_dir("")?;
    let text = (f64::from(height) / 36.0).clamp(11.0, 18.0);

    // S(ω) of every preset, log–log.
    let omegas: Vec<f32> = (0..=800)
        .map(|i| 0.15 * (40.0f32 / 0.15).powf(i as f32 / 800.0))
        .collect();
    println!(
        "{:<16} {:>8} {:>8} {:>11}",
        "preset", "Hs [m]", "Tp [s]", "ω_p [rad/s]"
    );
    let mut curves = Vec::new();
    for state in SeaState::ALL {
        let (spectrum, _) = state.build();
        println!(
            "{:<16} {:>8.3} {:>8.2} {:>11.3}",
            state.name(),
            spectrum.significant_wave_height(),
            spectrum.peak_period(),
            spectrum.peak_omega()
        );
        let points: Vec<(f64, f64)> = omegas
            .iter()
            .map(|&w| (f64::from(w), f64::from(spectrum.omega_spectrum(w))))
            .filter(|&(_, s)| s > 0.0)
            .collect();
        let label = format!(
            "{}: Hs {:.2} m, Tp {:.1} s",
            state.name().replace('_', " "),
            spectrum.significant_wave_height(),
            spectrum.peak_period()
        );
        curves.push((label, points));
    }
    let top = curves
        .iter()
        .flat_map(|(_, p)| p.iter().map(|&(_, s)| s))
        .fold(0.0f64, f64::max);
    let (y_max, y_min) = (
        10f64.powf((top * 3.0).log10().ceil()),
        10f64.powf((top * 3.0).log10().ceil() - 8.0),
    );
    let path = dir.join("spectrum.png");
    draw_png(&path, width, height, palette, |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                "Frequency spectra of the presets",
                (FONT, text * 1.25).into_font(),
            )
            .margin(12)
            .x_label_area_size(text * 3.0)
            .y_label_area_size(text * 4.5)
            .build_cartesian_2d(
                (0.15f64..40.0)
                    .log_scale()
                    .with_key_points(vec![0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0]),
                (y_min..y_max).log_scale(),
            )?;
        chart
            .configure_mesh()
            .x_desc("angular frequency ω [rad/s]")
            .y_desc("S(ω) [m²·s/rad]")
            .label_style((FONT, text).into_font())
            .axis_desc_style((FONT, text).into_font())
            .y_label_formatter(&|v| power_of_ten(*v))
            .x_label_formatter(&|v| format!("{v}"))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()?;
        for (index, (label, points)) in curves.iter().enumerate() {
            let colour = SERIES[index % SERIES.len()];
            chart
                .draw_series(LineSeries::new(
                    points.iter().copied().filter(|&(_, s)| s >= y_min),
                    colour.stroke_width(2),
                ))?
                .label(label.clone())
                .legend(line_swatch(colour));
        }
        // The ω⁻⁵ slope of the saturation range (Phillips 1958), through the storm's tail.
        let reference = |w: f64| 0.5 * 9.81f64.powi(2) * 0.008 * w.powi(-5);
        let grey = RGBColor(120, 120, 120);
        chart
            .draw_series(LineSeries::new(
                omegas
                    .iter()
                    .map(|&w| (f64::from(w), reference(f64::from(w))))
                    .filter(|&(_, s)| (y_min..y_max).contains(&s)),
                ShapeStyle::from(&grey).stroke_width(1),
            ))?
            .label("ω⁻⁵ slope (Phillips)")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], grey));
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight, text * 0.95)?;
        Ok(())
    })?;
    println!(
        "wrote {} (S(ω) of the presets, log–log, {width}×{height})",
        path.display()
    );

    // D(ω_p, θ) of every spreading function.
    let base = Spectrum::jonswap(10.0, 100_000.0)?;
    let spreadings = [
        ("Donelan–Banner (default)", Spreading::DonelanBanner),
        ("Mitsuyasu cos-2s", Spreading::Mitsuyasu),
        ("Hasselmann cos-2s", Spreading::Hasselmann),
        ("cos-2s, s = 4", Spreading::Cos2s { s: 4.0 }),
        ("Elfouhaily", Spreading::Elfouhaily),
        ("cos² (downwind only)", Spreading::Cos2),
        ("flat", Spreading::Flat),
    ];
    let thetas: Vec<f32> = (0..=720).map(|i| -PI + i as f32 * PI / 360.0).collect();
    let mut curves = Vec::new();
    for (label, spreading) in spreadings {
        let spectrum = base.clone().with_spreading(spreading)?;
        let wp = spectrum.peak_omega();
        let points: Vec<(f64, f64)> = thetas
            .iter()
            .map(|&t| {
                (
                    f64::from(t.to_degrees()),
                    f64::from(spectrum.spreading(wp, t)),
                )
            })
            .collect();
        curves.push((label, points));
    }
    let top = curves
        .iter()
        .flat_map(|(_, p)| p.iter().map(|&(_, d)| d))
        .fold(0.0f64, f64::max);
    let path = dir.join("spreading.png");
    draw_png(&path, width, height, palette, |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                format!(
                    "Directional spreading at the peak, ωₚ = {:.2} rad/s (JONSWAP, U10 = 10 m/s, 100 km fetch)",
                    base.peak_omega()
                ),
                (FONT, text * 1.1).into_font(),
            )
            .margin(12)
            .x_label_area_size(text * 3.0)
            .y_label_area_size(text * 4.0)
            .build_cartesian_2d(-180.0f64..180.0, 0.0..top * 1.08)?;
        chart
            .configure_mesh()
            .x_desc("direction θ from the wind [degrees]")
            .y_desc("D(ωₚ, θ) [1/rad]")
            .x_labels(9)
            .label_style((FONT, text).into_font())
            .axis_desc_style((FONT, text).into_font())
            .x_label_formatter(&|v| format!("{v:.0}°"))
            .y_label_formatter(&|v| format!("{v:.1}"))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()?;
        for (index, (label, points)) in curves.iter().enumerate() {
            let colour = SERIES[index % SERIES.len()];
            chart
                .draw_series(LineSeries::new(points.clone(), colour.stroke_width(2)))?
                .label(*label)
                .legend(line_swatch(colour));
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight, text * 0.95)?;
        Ok(())
    })?;
    println!(
        "wrote {} (D(θ) at ω_p of each spreading function, {width}×{height})",
        path.display()
    );
    Ok(())
}

/// A power of ten as "10⁻³" (the labels of a logarithmic axis).
fn power_of_ten(value: f64) -> String {
    let exponent = value.log10().round() as i32;
    let digits: String = exponent
        .to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            d => ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'][d as usize - '0' as usize],
        })
        .collect();
    format!("10{digits}")
}
