//! Whitecap coverage against wind speed on the default ocean: for U10 = 5, 7.5, 10, 15 and
//! 20 m/s, fully developed JONSWAP (`Spectrum::jonswap(u, 1e7)`, the fetch capped at full
//! development) and Pierson–Moskowitz seas on `OceanConfig::default()` (three cascades of 256²
//! over 1000, 230 and 51 m, default `FoamConfig`), the foam is pre-rolled for 20 s (five
//! active lifetimes) and the coverage averaged over the next 20 s in steps of 1/20 s. Prints
//! the active and residual coverage beside the whitecap fraction of Monahan &
//! O'Muircheartaigh (1980), W = 3.84e-6 U10^3.41, and plots them on log–log axes into
//! `out/whitecaps.png` (wind speed in m/s against the fraction of the surface covered; the
//! black line: the formula, grey lines: 1.5 times above and below it; filled dots: active
//! whitecaps, rings: residual foam; JONSWAP blue, Pierson–Moskowitz orange).
//!
//! Option: `--palette` writes the plot as an indexed PNG of 256 colours (for the README's
//! gallery).
//!
//! Run with `cargo run --release -p ocean-fft-examples --example whitecaps` (two to three minutes
//! on 2 cores).

mod common;

use clap::Parser;
use ocean_fft::{OceanConfig, OceanState, Spectrum};
use plotters::prelude::*;

use common::plot::{draw_legend, draw_png, line_swatch, FONT, SERIES};
use common::{out_dir, Result};

const WINDS: [f32; 5] = [5.0, 7.5, 10.0, 15.0, 20.0];

fn monahan(wind: f64) -> f64 {
    3.84e-6 * wind.powf(3.41)
}

/// Whitecap coverage against wind speed, beside Monahan & O'Muircheartaigh: out/whitecaps.png.
#[derive(Parser)]
#[command(name = "whitecaps", max_term_width = 100, args_override_self = true)]
struct Options {
    /// Write the plot as an indexed PNG of at most 256 colours, as the README's gallery does.
    #[arg(long)]
    palette: bool,
}

fn main() -> Result<()> {
    let start = std::time::Instant::now();
    let options = Options::parse();
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
                let c = ocean.foam_view().coverage();
                active += f64::from(c.active);
                residual += f64::from(c.residual);
            }
            let (active, residual) = (active / steps as f64, residual / steps as f64);
            let expected = monahan(f64::from(wind));
            println!(
                "{name:8} {wind:7.1} {expected:10.3e} {active:10.3e} {:7.3} {residual:9.3e} {:.3}",
                active / expected,
                ocean.foam_view().calibration().threshold
            );
            rows.push((index, wind, active, residual));
        }
    }

    let path = out_dir("")?.join("whitecaps.png");
    plot(&path, &rows, options.palette)?;
    println!(
        "wrote {}; done in {:.0} s",
        path.display(),
        start.elapsed().as_secs_f32()
    );
    Ok(())
}

/// Coverage against U10 on log–log axes: the Monahan & O'Muircheartaigh (1980) line with its
/// factor-1.5 band, active coverage as dots and residual coverage as rings, JONSWAP and
/// Pierson–Moskowitz in two colours.
fn plot(path: &std::path::Path, rows: &[(usize, f32, f64, f64)], palette: bool) -> Result<()> {
    draw_png(path, 760, 520, palette, |root| {
        let text = 15.0;
        let mut chart = ChartBuilder::on(root)
            .caption(
                "Whitecap coverage against wind, default ocean",
                (FONT, text * 1.2).into_font(),
            )
            .margin(12)
            .x_label_area_size(text * 3.0)
            .y_label_area_size(text * 4.5)
            .build_cartesian_2d(
                (4.0f64..25.0)
                    .log_scale()
                    .with_key_points(vec![4.0, 5.0, 7.5, 10.0, 15.0, 20.0, 25.0]),
                (1e-4f64..1.0).log_scale(),
            )?;
        chart
            .configure_mesh()
            .x_desc("wind speed U10 [m/s]")
            .y_desc("fraction of the surface covered")
            .label_style((FONT, text).into_font())
            .axis_desc_style((FONT, text).into_font())
            .x_label_formatter(&|v| format!("{v}"))
            .y_label_formatter(&|v| {
                if *v >= 0.01 {
                    format!("{:.0} %", v * 100.0)
                } else {
                    format!("{} %", v * 100.0)
                }
            })
            .light_line_style(RGBColor(235, 235, 235))
            .draw()?;
        let winds: Vec<f64> = (0..=100)
            .map(|i| 4.0 * (25.0f64 / 4.0).powf(f64::from(i) / 100.0))
            .collect();
        let grey = RGBColor(190, 190, 190);
        for factor in [1.5, 1.0 / 1.5] {
            chart.draw_series(LineSeries::new(
                winds.iter().map(|&u| (u, factor * monahan(u))),
                ShapeStyle::from(&grey).stroke_width(1),
            ))?;
        }
        chart
            .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())?
            .label("× 1.5 and ÷ 1.5 of the formula")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], grey));
        let black = RGBColor(30, 30, 30);
        chart
            .draw_series(LineSeries::new(
                winds.iter().map(|&u| (u, monahan(u))),
                black.stroke_width(2),
            ))?
            .label("Monahan & O'Muircheartaigh (1980): W = 3.84·10⁻⁶ U10^3.41")
            .legend(line_swatch(black));
        for (index, name) in [(0usize, "JONSWAP"), (1, "Pierson–Moskowitz")] {
            let colour = SERIES[index];
            let shift = if index == 0 { 0.985 } else { 1.015 };
            chart
                .draw_series(
                    rows.iter()
                        .filter(|r| r.0 == index && r.2 > 0.0)
                        .map(|r| Circle::new((f64::from(r.1) * shift, r.2), 5, colour.filled())),
                )?
                .label(format!("{name}: active whitecaps"))
                .legend(move |(x, y)| Circle::new((x + 10, y), 5, colour.filled()));
            chart
                .draw_series(rows.iter().filter(|r| r.0 == index && r.3 > 0.0).map(|r| {
                    Circle::new((f64::from(r.1) * shift, r.3), 5, colour.stroke_width(2))
                }))?
                .label(format!("{name}: residual foam"))
                .legend(move |(x, y)| Circle::new((x + 10, y), 5, colour.stroke_width(2)));
        }
        draw_legend(&mut chart, SeriesLabelPosition::LowerRight, text * 0.9)?;
        Ok(())
    })
}
