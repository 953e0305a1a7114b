//! Bakes a seamlessly looping texture sequence for a GPU engine.
//!
//! With `OceanConfig::repeat_period = Some(T)` every wave frequency is rounded to the nearest
//! multiple of 2π/T (at least one cycle per loop), so the surface at t + T equals the surface
//! at t. (The `ocean-fft` bake tool, `cli/`, does this for every cascade with foam, in EXR.) This example uses the
//! default sea (`Spectrum::jonswap(10.0, 100_000.0)`) at size 128 with T = 8 s, and writes
//! F = 16 frames t = k·T/F (k = 0..F−1) of the largest cascade (1000 m tile, 128×128):
//!
//! - `out/loop/displacement_000.png` …: 16-bit RGB, R = D_x, G = η (height), B = D_z in
//!   metres, each mapped linearly from [−s, s] to [0, 65535] with one scale s for all
//!   frames (printed; decode with value = (p/65535·2 − 1)·s);
//! - `out/loop/normal_000.png` …: 8-bit RGB normal maps, R = n_x, G = n_z, B = n_y (up), from
//!   [−1, 1] to [0, 255].
//!
//! It then checks that the frame at t = T equals the frame at t = 0 within 1e-5 m, both by
//! `set_time(T)` and by stepping from 0 at 60 Hz as a game loop would, and prints the
//! largest differences (and, as a sanity check, how different the frame at T/2 is).
//!
//! Run with `cargo run --release -p ocean-fft-examples --example bake_loop`.

mod common;

use ocean_fft::{OceanConfig, OceanState, Spectrum};

use common::{out_dir, save_rgb16, save_rgb8, to_u16, to_u8, Result};

const PERIOD: f32 = 8.0;
const FRAMES: usize = 16;
const SIZE: usize = 128;
const TOLERANCE: f32 = 1e-5;

/// The largest cascade's height, displacement and normal at one time.
struct Frame {
    height: Vec<f32>,
    /// `[x, z]` per grid point.
    displacement: Vec<[f32; 2]>,
    /// `[x, y, z]` per grid point, y up.
    normal: Vec<[f32; 3]>,
}

fn capture(ocean: &OceanState) -> Frame {
    let cascade = &ocean.cascades()[0];
    Frame {
        height: cascade.height().to_vec(),
        displacement: cascade.displacement().to_vec(),
        normal: cascade.normal().to_vec(),
    }
}

/// Largest difference in metres between the heights and displacements of two frames.
fn max_difference(a: &Frame, b: &Frame) -> f32 {
    let height = a
        .height
        .iter()
        .zip(&b.height)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0f32, f32::max);
    let displacement = a
        .displacement
        .iter()
        .zip(&b.displacement)
        .map(|(x, y)| (x[0] - y[0]).abs().max((x[1] - y[1]).abs()))
        .fold(0.0f32, f32::max);
    height.max(displacement)
}

fn main() -> Result<()> {
    let start = std::time::Instant::now();
    let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
    let config = OceanConfig {
        size: SIZE,
        repeat_period: Some(PERIOD),
        ..OceanConfig::default()
    };
    let mut ocean = OceanState::new(spectrum, config)?;
    let length = ocean.cascades()[0].length();

    let mut frames = Vec::with_capacity(FRAMES);
    for k in 0..FRAMES {
        ocean.set_time(f64::from(PERIOD) * k as f64 / FRAMES as f64)?;
        frames.push(capture(&ocean));
    }
    // One scale for the whole sequence, so the frames blend consistently.
    let scale = frames
        .iter()
        .flat_map(|f| {
            f.height
                .iter()
                .copied()
                .chain(f.displacement.iter().map(|d| d[0].abs().max(d[1].abs())))
        })
        .fold(0.0f32, |m, v| m.max(v.abs()))
        .max(1e-6);

    let dir = out_dir("loop")?;
    for (k, frame) in frames.iter().enumerate() {
        let pixels: Vec<u16> = frame
            .height
            .iter()
            .zip(&frame.displacement)
            .flat_map(|(&h, d)| [d[0], h, d[1]].map(|v| to_u16(v, scale)))
            .collect();
        let path = dir.join(format!("displacement_{k:03}.png"));
        save_rgb16(&path, SIZE, SIZE, &pixels)?;
        println!("wrote {}", path.display());
        let pixels: Vec<u8> = frame
            .normal
            .iter()
            .flat_map(|n| [n[0], n[2], n[1]].map(|c| to_u8(0.5 + 0.5 * c)))
            .collect();
        let path = dir.join(format!("normal_{k:03}.png"));
        save_rgb8(&path, SIZE, SIZE, &pixels)?;
        println!("wrote {}", path.display());
    }
    println!(
        "{FRAMES} frames of the {length} m cascade at t = k·{:.3} s, loop period T = {PERIOD} s; \
         displacement maps: R = D_x, G = η, B = D_z, mapped from [−{scale:.4}, {scale:.4}] m \
         to [0, 65535]",
        PERIOD / FRAMES as f32
    );

    // The loop check.
    ocean.set_time(f64::from(PERIOD))?;
    let jumped = max_difference(&capture(&ocean), &frames[0]);
    ocean.set_time(0.0)?;
    // A 60 Hz game loop: 480 steps of 1/60 s, whose rounded sum is not exactly T.
    let dt = 1.0 / 60.0;
    let steps = (f64::from(PERIOD) / dt).round() as usize;
    for _ in 0..steps {
        ocean.step(dt)?;
    }
    let stepped = max_difference(&capture(&ocean), &frames[0]);
    let half = max_difference(&frames[FRAMES / 2], &frames[0]);

    // What the looping costs: every frequency moved to a whole number of cycles per loop.
    let error = ocean
        .diagnostics()
        .loop_error()
        .ok_or("a looping ocean reports its loop error")?;
    println!("max |frame(T) − frame(0)| over η, D_x, D_z: {jumped:.2e} m by set_time(T)");
    println!(
        "max |frame(T) − frame(0)| over η, D_x, D_z: {stepped:.2e} m after {steps} steps of 1/60 s (t = {:.15} s)",
        ocean.time()
    );
    println!("(for comparison max |frame(T/2) − frame(0)| = {half:.3} m)");
    println!(
        "looping moves the wave frequencies by {:.1} % on average (weighted by energy), {:.0} % \
         at most; no wave stands still; choose a longer T for a more natural loop",
        100.0 * error.mean_relative,
        100.0 * error.max_relative
    );
    if jumped <= TOLERANCE && stepped <= TOLERANCE {
        println!("loop OK: frame at t = T equals frame at t = 0 within {TOLERANCE:.0e} m");
    } else {
        return Err(format!(
            "loop check failed: differences {jumped:.2e} m and {stepped:.2e} m exceed {TOLERANCE:.0e} m"
        )
        .into());
    }
    println!("done in {:.2} s", start.elapsed().as_secs_f32());
    Ok(())
}
