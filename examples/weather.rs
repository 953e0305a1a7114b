//! A change of weather while the ocean runs (`OceanState::set_spectrum`): the default ocean
//! (three cascades of 256² over 1000, 230 and 51 m) starts as a calm sea (U10 = 4 m/s,
//! fetch 20 km), turns into a storm (U10 = 20 m/s, fetch 300 km, the wind backed by 30°) over
//! 60 s from t = 10 s, holds it for 20 s and turns back over 60 s, in steps of 1/20 s.
//!
//! Writes two pictures into `out/`:
//! - `weather.png`: against time, the significant wave height measured from the cascades'
//!   height buffers (4·√ of the summed variance of η) beside what the blended spectra predict
//!   (4√ of `OceanState::expected_variance`), and the active whitecap coverage measured over
//!   the foam grid beside the coverage the calibration predicts for the blended sea;
//! - `weather_strip.png`: a strip of top views of a 300 m window (hill-shaded, crests tinted
//!   by η/H_s of the storm, residual foam pale, whitecaps white) at seven moments of the
//!   change.
//!
//! Option: `--palette` writes both as indexed PNGs of 256 colours (for the README's gallery).
//!
//! Run with `cargo run --release -p ocean-fft-examples --example weather` (about a minute on
//! 2 cores after the build).

mod common;

use clap::Parser;
use glam::Vec3;
use ocean_fft::{OceanConfig, OceanState, Spectrum};
use plotters::prelude::*;

use common::plot::{draw_legend, draw_on, draw_png, line_swatch, outlined_text, FONT, SERIES};
use common::{out_dir, sample_window, save_indexed, save_rgb8, shade, to_srgb, Result};

/// Steps of the simulation, s.
const DT: f64 = 1.0 / 20.0;
/// When the storm starts to build, when the calm returns, and each change's duration, s.
const STORM_AT: f64 = 10.0;
const CALM_AT: f64 = 90.0;
const CHANGE: f64 = 60.0;
/// The end of the run, s.
const END: f64 = 170.0;
/// The moments of the strip, s.
const MOMENTS: [f64; 7] = [5.0, 30.0, 50.0, 80.0, 110.0, 130.0, 165.0];
/// Side of the strip's window, m, and of one frame, pixels.
const WINDOW: f64 = 300.0;
const FRAME: usize = 200;

/// One sample of the time series.
struct Row {
    t: f64,
    hs_measured: f64,
    hs_predicted: f64,
    active: f64,
    predicted_active: f64,
}

/// A calm sea built into a storm and calmed again: out/weather.png and out/weather_strip.png.
#[derive(Parser)]
#[command(name = "weather", max_term_width = 100, args_override_self = true)]
struct Options {
    /// Write both pictures as indexed PNGs of at most 256 colours, as the README's gallery does.
    #[arg(long)]
    palette: bool,
}

fn main() -> Result<()> {
    let start = std::time::Instant::now();
    let options = Options::parse();
    let calm = Spectrum::jonswap(4.0, 20_000.0)?.with_wind_direction(0.3)?;
    let storm = Spectrum::jonswap(20.0, 300_000.0)?.with_wind_direction(0.3 + 0.52)?;
    let mut ocean = OceanState::new(calm.clone(), OceanConfig::default())?;
    // The calm sea with its (little) foam spun up, as if it had been running.
    ocean.pre_roll(10.0, DT)?;
    let storm_hs = 4.0 * storm.significant_wave_height();

    let mut rows = Vec::new();
    let mut frames = Vec::new();
    let mut next_moment = 0;
    let steps = (END / DT).round() as usize;
    println!("   t s   w      Hs m (measured, predicted)   active coverage (measured, predicted)");
    for step in 0..=steps {
        let t = step as f64 * DT;
        if step > 0 {
            ocean.step_to(t)?;
        }
        if (t - STORM_AT).abs() < 0.5 * DT {
            ocean.set_spectrum(storm.clone(), CHANGE)?;
        }
        if (t - CALM_AT).abs() < 0.5 * DT {
            ocean.set_spectrum(calm.clone(), CHANGE)?;
        }
        if step % 10 == 0 {
            let row = measure(&ocean, t);
            if step % 200 == 0 {
                println!(
                    "{:6.1} {:5.3}   {:6.3} {:6.3}                  {:9.3e} {:9.3e}",
                    t,
                    ocean
                        .diagnostics()
                        .transition_progress()
                        .unwrap_or(f64::NAN),
                    row.hs_measured,
                    row.hs_predicted,
                    row.active,
                    row.predicted_active
                );
            }
            rows.push(row);
        }
        if next_moment < MOMENTS.len() && t >= MOMENTS[next_moment] - 0.5 * DT {
            frames.push((t, top_view(&ocean, storm_hs / 4.0)?));
            next_moment += 1;
        }
    }

    let dir = out_dir("")?;
    let plot = dir.join("weather.png");
    draw_png(&plot, 900, 600, options.palette, |root| {
        draw_series(root, &rows)
    })?;
    let strip = dir.join("weather_strip.png");
    write_strip(&strip, &frames, options.palette)?;
    println!(
        "wrote {} and {} in {:.1} s",
        plot.display(),
        strip.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

/// The measured and predicted H_s and whitecap coverage at time `t`.
fn measure(ocean: &OceanState, t: f64) -> Row {
    // The cascades are independent fields on disjoint bands: the summed surface's variance
    // is the sum of theirs (each about its own mean, which is the mean-level correction).
    let variance: f64 = ocean
        .cascades()
        .iter()
        .map(|c| {
            let h = c.height();
            let mean = h.iter().map(|&v| f64::from(v)).sum::<f64>() / h.len() as f64;
            h.iter()
                .map(|&v| (f64::from(v) - mean).powi(2))
                .sum::<f64>()
                / h.len() as f64
        })
        .sum();
    let calibration = ocean.foam_view().calibration();
    Row {
        t,
        hs_measured: 4.0 * variance.sqrt(),
        hs_predicted: 4.0 * ocean.diagnostics().expected_variance().sqrt(),
        active: f64::from(ocean.foam_view().coverage().active),
        predicted_active: f64::from(calibration.predicted),
    }
}

/// A top view of the window at the origin: RGB, `FRAME`² pixels, 2×2 samples a pixel.
fn top_view(ocean: &OceanState, sigma_storm: f32) -> Result<Vec<u8>> {
    let fine = 2 * FRAME;
    let spacing = WINDOW / fine as f64;
    let samples = sample_window(ocean, WINDOW, fine)?;
    let sun = Vec3::new(-0.5, 0.6, -0.62).normalize();
    let mut pixels = vec![0u8; FRAME * FRAME * 3];
    for j in 0..FRAME {
        for i in 0..FRAME {
            let mut sum = Vec3::ZERO;
            for (di, dj) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let p = (2 * j + dj) * fine + 2 * i + di;
                let (x, z) = (
                    (p % fine) as f64 * spacing + 0.5 * spacing,
                    (p / fine) as f64 * spacing + 0.5 * spacing,
                );
                let foam = ocean.foam_view().foam_at(x, z)?;
                sum += shade(
                    &samples[p],
                    sun,
                    4.0 * sigma_storm,
                    foam.active,
                    foam.residual,
                );
            }
            let at = (j * FRAME + i) * 3;
            pixels[at..at + 3].copy_from_slice(&to_srgb(sum / 4.0));
        }
    }
    Ok(pixels)
}

/// The strip: the frames side by side, each labelled with its time.
fn write_strip(path: &std::path::Path, frames: &[(f64, Vec<u8>)], palette: bool) -> Result<()> {
    const PAD: usize = 6;
    const LABEL: usize = 22;
    let width = frames.len() * (FRAME + PAD) + PAD;
    let height = FRAME + LABEL + 2 * PAD;
    let mut sheet = vec![255u8; width * height * 3];
    for (index, (_, pixels)) in frames.iter().enumerate() {
        let x0 = PAD + index * (FRAME + PAD);
        for j in 0..FRAME {
            let at = ((PAD + LABEL + j) * width + x0) * 3;
            sheet[at..at + FRAME * 3].copy_from_slice(&pixels[j * FRAME * 3..(j + 1) * FRAME * 3]);
        }
    }
    draw_on(&mut sheet, width as u32, height as u32, |root| {
        for (index, (t, _)) in frames.iter().enumerate() {
            let x = (PAD + index * (FRAME + PAD)) as i32;
            root.draw(&Text::new(
                format!("t = {t:.0} s"),
                (x + 4, PAD as i32 + 2),
                (FONT, 15).into_font().color(&BLACK),
            ))?;
        }
        outlined_text(
            root,
            &format!("{WINDOW:.0} m"),
            (width as i32 - 70, height as i32 - PAD as i32 - 22),
            14.0,
        )?;
        Ok(())
    })?;
    if palette {
        save_indexed(path, width, height, &sheet)
    } else {
        save_rgb8(path, width, height, &sheet)
    }
}

/// The two panels of the time series.
fn draw_series(
    root: &DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>,
    rows: &[Row],
) -> Result<()> {
    let (top, bottom) = root.split_vertically(300);
    let hs_max = rows
        .iter()
        .map(|r| r.hs_measured.max(r.hs_predicted))
        .fold(0.0, f64::max)
        * 1.1;
    let mut chart = ChartBuilder::on(&top)
        .caption(
            "A calm sea, a storm built over 60 s, calm again over 60 s: significant wave height",
            (FONT, 17),
        )
        .margin(10)
        .x_label_area_size(30)
        .y_label_area_size(50)
        .build_cartesian_2d(0.0..END, 0.0..hs_max)?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc("H_s (m)")
        .label_style((FONT, 13))
        .draw()?;
    chart
        .draw_series(LineSeries::new(
            rows.iter().map(|r| (r.t, r.hs_predicted)),
            BLACK.stroke_width(2),
        ))?
        .label("predicted: 4√(expected variance)")
        .legend(line_swatch(BLACK));
    chart
        .draw_series(LineSeries::new(
            rows.iter().map(|r| (r.t, r.hs_measured)),
            SERIES[0].stroke_width(2),
        ))?
        .label("measured: 4·std of the cascades' heights")
        .legend(line_swatch(SERIES[0]));
    draw_legend(&mut chart, SeriesLabelPosition::UpperRight, 13.0)?;

    let low = 1e-5;
    let high = rows
        .iter()
        .map(|r| r.active.max(r.predicted_active))
        .fold(low, f64::max)
        * 2.0;
    let mut chart = ChartBuilder::on(&bottom)
        .caption("active whitecap coverage", (FONT, 17))
        .margin(10)
        .x_label_area_size(30)
        .y_label_area_size(50)
        .build_cartesian_2d(0.0..END, (low..high).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc("fraction of the surface")
        .label_style((FONT, 13))
        .draw()?;
    chart
        .draw_series(LineSeries::new(
            rows.iter().map(|r| (r.t, r.predicted_active.max(low))),
            BLACK.stroke_width(2),
        ))?
        .label("predicted by the calibration of the blended sea")
        .legend(line_swatch(BLACK));
    chart
        .draw_series(LineSeries::new(
            rows.iter().map(|r| (r.t, r.active.max(low))),
            SERIES[1].stroke_width(2),
        ))?
        .label("measured over the foam grid")
        .legend(line_swatch(SERIES[1]));
    draw_legend(&mut chart, SeriesLabelPosition::LowerRight, 13.0)?;
    Ok(())
}
