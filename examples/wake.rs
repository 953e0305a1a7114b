//! A Kelvin wake seen from above, `out/wake.png`: a 20 m × 5 m hull of 1 m draft at 8 m/s
//! (length Froude number 0.57) in deep water for 50 s, the 256 m wake window (512 cells of
//! 0.5 m) following it, the wake's height shaded (crests light, troughs dark), its foam trail
//! blended in white, and Kelvin's cusp lines at ±19.47° from the track drawn in red from the
//! hull's centre.
//!
//! Run with `cargo run --release -p ocean-fft-examples --example wake`.

mod common;

use ocean_fft::{Hull, OceanConfig, OceanState, Spectrum, WakeConfig};

use common::{out_dir, save_rgb8, Canvas, Result};

fn main() -> Result<()> {
    let spectrum = Spectrum::jonswap(2.0, 1000.0)?;
    let wakes = WakeConfig {
        size: 512,
        spacing: 0.5,
        substep: 0.05,
        ..WakeConfig::default()
    };
    let config = OceanConfig {
        size: 16,
        wakes: Some(wakes),
        ..OceanConfig::default()
    }
    .with_fitted_lengths(&spectrum)?;
    let mut ocean = OceanState::new(spectrum, config)?;
    let speed = 8.0;
    ocean.set_hulls(&[Hull {
        velocity: [speed as f32, 0.0],
        ..Hull::default()
    }])?;
    let side = 256.0;
    for step in 1..=1000 {
        ocean.step_to(f64::from(step) * 0.05)?;
        ocean.set_wake_centre(speed * ocean.time() - 0.3 * side, 0.0)?;
    }
    let wakes = ocean.wakes().expect("wakes are on");
    let n = wakes.size();
    let scale = 0.3; // m of wake height to full contrast
    let mut canvas = Canvas::new(n, n, [0, 0, 0]);
    for (index, (&h, &foam)) in wakes.height().iter().zip(wakes.foam()).enumerate() {
        let v = (0.5 + 0.5 * (h / scale).clamp(-1.0, 1.0)) * 255.0;
        let (i, j) = (index % n, index / n);
        let water = [v * 0.6, v * 0.8, v];
        let white = water.map(|c| (c + (255.0 - c) * foam) as u8);
        canvas.set(i as i64, j as i64, white);
    }
    // The cusp lines from the hull's centre, backwards along the track.
    let spacing = f64::from(wakes.spacing());
    let hull = [speed * ocean.time(), 0.0];
    let to_pixel = |x: f64, z: f64| {
        (
            ((x - wakes.origin()[0]) / spacing) as f32,
            ((z - wakes.origin()[1]) / spacing) as f32,
        )
    };
    let cusp = (1.0f64 / 3.0).asin();
    for sign in [-1.0, 1.0] {
        let end = [hull[0] - 300.0 * cusp.cos(), sign * 300.0 * cusp.sin()];
        canvas.line(
            to_pixel(hull[0], hull[1]),
            to_pixel(end[0], end[1]),
            1,
            [220, 40, 40],
        );
    }
    let path = out_dir("")?.join("wake.png");
    save_rgb8(&path, n, n, &canvas.pixels)?;
    println!(
        "{}: t = {:.1} s, hull at x = {:.1} m, wake height in [{:.3}, {:.3}] m",
        path.display(),
        ocean.time(),
        hull[0],
        wakes.height().iter().copied().fold(f32::MAX, f32::min),
        wakes.height().iter().copied().fold(f32::MIN, f32::max)
    );
    Ok(())
}
