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
//! Writes `out/buoyancy.csv` (`t,y,pitch_deg,roll_deg`) and `out/buoyancy.png` (heave on top,
//! pitch and roll below), and prints the standard deviation of the heave beside H_s/4 of the
//! sea (a box this small follows the long waves, so they should be close; over only 60 s of
//! one point the estimate scatters by tens of per cent).
//!
//! Run with `cargo run --release -p ocean-fft-examples --example buoyancy`.

mod common;

use std::io::Write;

use ocean_fft::{OceanConfig, OceanState, Spectrum};

use common::{out_dir, Canvas, Result};

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

fn main() -> Result<()> {
    let start = std::time::Instant::now();
    let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
    let hs = spectrum.significant_wave_height();
    let config = OceanConfig {
        size: 128,
        ..OceanConfig::default()
    };
    let mut ocean = OceanState::new(spectrum, config)?;
    let hs_grid = 4.0 * ocean.expected_variance().sqrt();

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
        ocean.heights_at(&corners, &mut heights)?;
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
    plot(&frames)?.save(&path)?;
    println!(
        "wrote {} (top: heave y [m]; bottom: pitch (blue) and roll (orange) [deg]; 0 to {DURATION} s)",
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

/// Heave (top panel) and pitch/roll (bottom panel) against time.
fn plot(frames: &[Frame]) -> Result<Canvas> {
    let (w, h) = (900usize, 460usize);
    let mut canvas = Canvas::new(w, h, [255, 255, 255]);
    let left = 60.0;
    let right = w as f32 - 20.0;
    let panels = [(30.0f32, 210.0f32), (260.0f32, 440.0f32)];
    let grey = [150, 150, 150];
    let max_y = frames.iter().fold(0.1f32, |m, f| m.max(f.y.abs())) * 1.1;
    let max_angle = frames.iter().fold(0.5f32, |m, f| {
        m.max(f.pitch_deg.abs()).max(f.roll_deg.abs())
    }) * 1.1;
    let t_end = frames.last().map_or(1.0, |f| f.t) as f32;
    let x_of = |t: f64| left + (t as f32 / t_end) * (right - left);
    for (index, &(top, bottom)) in panels.iter().enumerate() {
        let mid = 0.5 * (top + bottom);
        canvas.line((left, top), (left, bottom), 1, grey);
        canvas.line((left, mid), (right, mid), 1, grey);
        for second in (0..=t_end as usize).step_by(10) {
            let x = x_of(second as f64);
            canvas.line((x, mid - 3.0), (x, mid + 3.0), 1, grey);
            if index == 1 {
                canvas.text(
                    x as i64 - 4,
                    bottom as i64 + 6,
                    &format!("{second}"),
                    2,
                    grey,
                );
            }
        }
        let (label, range) = if index == 0 {
            (format!("HEAVE M, +-{max_y:.2}"), max_y)
        } else {
            (format!("PITCH, ROLL DEG, +-{max_angle:.1}"), max_angle)
        };
        canvas.text(left as i64 + 6, top as i64 - 16, &label, 2, [60, 60, 60]);
        let y_of = |v: f32| mid - v / range * 0.5 * (bottom - top);
        if index == 0 {
            let points: Vec<(f32, f32)> = frames.iter().map(|f| (x_of(f.t), y_of(f.y))).collect();
            canvas.polyline(&points, 2, [31, 119, 180]);
        } else {
            let pitch: Vec<(f32, f32)> = frames
                .iter()
                .map(|f| (x_of(f.t), y_of(f.pitch_deg)))
                .collect();
            let roll: Vec<(f32, f32)> = frames
                .iter()
                .map(|f| (x_of(f.t), y_of(f.roll_deg)))
                .collect();
            canvas.polyline(&pitch, 2, [31, 119, 180]);
            canvas.polyline(&roll, 2, [255, 127, 14]);
        }
    }
    Ok(canvas)
}
