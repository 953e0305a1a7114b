//! A floating box riding the waves: the game-side use of `OceanState::heights_at`.
//!
//! A 4 m × 2 m box (long side along the wind, +x) sits at world point (120, 40). The default
//! ocean (`Spectrum::jonswap(10.0, 100_000.0)`, default cascade lengths, but size 128 to stay
//! quick) is stepped for 60 s at 30 Hz; every frame one `heights_at` call gives the water
//! height at the box's four corners (after horizontal displacement), and the box follows
//! them kinematically: its height is their mean, its pitch the slope bow-to-stern
//! (positive: bow, +x, up) and its roll the slope port-to-starboard (positive: port side,
//! −z, up). No dynamics: this is the heightfield-follower games use for small floating props.
//!
//! Writes `out/buoyancy.csv` (`t,y,pitch_deg,roll_deg`) and `out/buoyancy.png` (heave in
//! metres on top with ±H_s/2 of the sea, pitch and roll in degrees below, against time in
//! seconds), and prints the standard deviation of the heave beside H_s/4 of the
//! sea (a box this small follows the long waves, so they should be close; over only 60 s of
//! one point the estimate scatters by tens of per cent).
//!
//! Option: `--palette` writes the plot as an indexed PNG of 256 colours (for the README's
//! gallery).
//!
//! Run with `cargo run --release -p ocean-fft-examples --example buoyancy`.

mod common;

use std::io::Write;

use clap::Parser;
use ocean_fft::{OceanConfig, OceanState, Spectrum};

use plotters::prelude::*;

use common::plot::{draw_legend, draw_png, line_swatch, FONT, SERIES};
use common::{out_dir, Result};

const LENGTH: f64 = 4.0;
const WIDTH: f64 = 2.0;
const CENTRE: [f64; 2] = [120.0, 40.0];
const RATE: f64 = 30.0;
const DURATION: f64 = 60.0;

struct Frame {
    t: f64,
    y: f32,
    pitch_deg: f32,
    roll_deg: f32,
}

/// A 4 m × 2 m box riding the default ocean for 60 s: out/buoyancy.csv and out/buoyancy.png.
#[derive(Parser)]
#[command(name = "buoyancy", max_term_width = 100, args_override_self = true)]
struct Options {
    /// Write the plot as an indexed PNG of at most 256 colours, as the README's gallery does.
    #[arg(long)]
    palette: bool,
}

fn main() -> Result<()> {
    let start = std::time::Instant::now();
    let options = Options::parse();
    let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
    let hs = spectrum.significant_wave_height();
    let config = OceanConfig {
        size: 128,
        ..OceanConfig::default()
    };
    let mut ocean = OceanState::new(spectrum, config)?;
    let hs_grid = 4.0 * ocean.diagnostics().expected_variance().sqrt();

    // Corners: bow-port, bow-starboard, stern-port, stern-starboard (bow +x, port −z).
    let (hl, hw) = (0.5 * LENGTH, 0.5 * WIDTH);
    let corners = [
        [CENTRE[0] + hl, CENTRE[1] - hw],
        [CENTRE[0] + hl, CENTRE[1] + hw],
        [CENTRE[0] - hl, CENTRE[1] - hw],
        [CENTRE[0] - hl, CENTRE[1] + hw],
    ];
    let mut heights = [0.0f32; 4];
    let frames_total = (DURATION * RATE).round() as usize;
    let mut frames = Vec::with_capacity(frames_total + 1);
    for frame in 0..=frames_total {
        if frame > 0 {
            ocean.step(1.0 / RATE)?;
        }
        ocean.water().heights_at(&corners, &mut heights)?;
        let [bp, bs, sp, ss] = heights;
        let y = 0.25 * (bp + bs + sp + ss);
        let pitch = ((0.5 * (bp + bs) - 0.5 * (sp + ss)) / LENGTH as f32).atan();
        let roll = ((0.5 * (bp + sp) - 0.5 * (bs + ss)) / WIDTH as f32).atan();
        frames.push(Frame {
            t: ocean.time(),
            y,
            pitch_deg: pitch.to_degrees(),
            roll_deg: roll.to_degrees(),
        });
    }

    let dir = out_dir("")?;
    let path = dir.join("buoyancy.csv");
    let mut csv = std::io::BufWriter::new(std::fs::File::create(&path)?);
    writeln!(csv, "t,y,pitch_deg,roll_deg")?;
    for f in &frames {
        writeln!(
            csv,
            "{:.4},{:.5},{:.4},{:.4}",
            f.t, f.y, f.pitch_deg, f.roll_deg
        )?;
    }
    csv.flush()?;
    println!(
        "wrote {} ({} frames at {RATE} Hz)",
        path.display(),
        frames.len()
    );

    let path = dir.join("buoyancy.png");
    plot(&path, &frames, hs, options.palette)?;
    println!(
        "wrote {} (top: heave y [m]; bottom: pitch and roll [degrees]; 0 to {DURATION} s)",
        path.display()
    );

    let std = |values: &mut dyn Iterator<Item = f32>| {
        let v: Vec<f64> = values.map(f64::from).collect();
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / v.len() as f64).sqrt()
    };
    let heave = std(&mut frames.iter().map(|f| f.y));
    let pitch = std(&mut frames.iter().map(|f| f.pitch_deg));
    let roll = std(&mut frames.iter().map(|f| f.roll_deg));
    println!(
        "heave std {heave:.3} m vs H_s/4 = {:.3} m (spectrum; grids {:.3} m); pitch std {pitch:.2}°, roll std {roll:.2}°",
        hs / 4.0,
        hs_grid / 4.0
    );
    println!("done in {:.2} s", start.elapsed().as_secs_f32());
    Ok(())
}

/// Heave (top panel, metres) and pitch and roll (bottom panel, degrees) against time in
/// seconds, with ticks, units and a legend.
fn plot(path: &std::path::Path, frames: &[Frame], hs: f32, palette: bool) -> Result<()> {
    draw_png(path, 900, 560, palette, |root| {
        let text = 15.0;
        let root = root.titled(
            "A 4 m × 2 m box on the default sea (JONSWAP, U10 = 10 m/s, 100 km fetch)",
            (FONT, text * 1.15).into_font(),
        )?;
        let (top, bottom) = root.split_vertically(root.dim_in_pixel().1 / 2);
        let t_end = frames.last().map_or(1.0, |f| f.t);
        let heave = frames.iter().fold(0.1f32, |m, f| m.max(f.y.abs())) as f64 * 1.15;
        let angle = frames.iter().fold(0.5f32, |m, f| {
            m.max(f.pitch_deg.abs()).max(f.roll_deg.abs())
        }) as f64
            * 1.15;

        let mut chart = ChartBuilder::on(&top)
            .margin(10)
            .x_label_area_size(text * 2.0)
            .y_label_area_size(text * 4.0)
            .build_cartesian_2d(0.0..t_end, -heave..heave)?;
        chart
            .configure_mesh()
            .y_desc("heave y [m]")
            .label_style((FONT, text).into_font())
            .axis_desc_style((FONT, text).into_font())
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&|v| format!("{v:.1}"))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()?;
        let blue = SERIES[0];
        chart
            .draw_series(LineSeries::new(
                frames.iter().map(|f| (f.t, f64::from(f.y))),
                blue.stroke_width(2),
            ))?
            .label("heave (mean of the four corners)")
            .legend(line_swatch(blue));
        let grey = RGBColor(130, 130, 130);
        for level in [-0.5 * f64::from(hs), 0.5 * f64::from(hs)] {
            chart.draw_series(LineSeries::new(
                [(0.0, level), (t_end, level)],
                ShapeStyle::from(&grey).stroke_width(1),
            ))?;
        }
        chart
            .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())?
            .label(format!("±Hs/2 of the sea (Hs = {hs:.2} m)"))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], grey));
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight, text * 0.95)?;

        let mut chart = ChartBuilder::on(&bottom)
            .margin(10)
            .x_label_area_size(text * 3.0)
            .y_label_area_size(text * 4.0)
            .build_cartesian_2d(0.0..t_end, -angle..angle)?;
        chart
            .configure_mesh()
            .x_desc("time t [s]")
            .y_desc("angle [degrees]")
            .label_style((FONT, text).into_font())
            .axis_desc_style((FONT, text).into_font())
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&|v| format!("{v:.0}°"))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()?;
        for (index, label, value) in [
            (
                0usize,
                "pitch (bow, +x, up)",
                &(|f: &Frame| f.pitch_deg) as &dyn Fn(&Frame) -> f32,
            ),
            (1, "roll (port, −z, up)", &|f: &Frame| f.roll_deg),
        ] {
            let colour = SERIES[index];
            chart
                .draw_series(LineSeries::new(
                    frames.iter().map(|f| (f.t, f64::from(value(f)))),
                    colour.stroke_width(2),
                ))?
                .label(label)
                .legend(line_swatch(colour));
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight, text * 0.95)?;
        Ok(())
    })
}
