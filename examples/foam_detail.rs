//! The foam at the breaking scale, `out/foam_detail.png`: a 128 m square of the fresh breeze
//! (top) and the storm (bottom), wind along +x (to the right), after a minute of pre-roll,
//! sampled every 0.25 m. Left: the coarse foam coverage (`water().at_rest(..).foam`, what
//! `foam_at` returned before 0.4: a fraction on cascade 0's grid); right:
//! `foam_view().foam_at(..).total`, the foam
//! placed at the finest cascade's resolution, white whitecaps on the most compressed short
//! crests and thin residual streaks along the wind (docs/theory.md §15.8). Gray levels are
//! the foam value, 0 black to 1 white; the left panels are stretched (×1/max) so their fog
//! shows.
//!
//! Run with `cargo run --release -p ocean-fft-examples --example foam_detail`.

mod common;

use ocean_fft::{OceanState, SeaState};

use common::{out_dir, save_gray8, Result};

/// Samples per panel side (128 m every 0.25 m) and the gap between panels.
const SIDE: usize = 512;
const GAP: usize = 8;

fn main() -> Result<()> {
    let width = 2 * SIDE + GAP;
    let height = 2 * SIDE + GAP;
    let mut pixels = vec![40u8; width * height];
    for (row, sea) in [SeaState::FreshBreeze, SeaState::Storm]
        .into_iter()
        .enumerate()
    {
        let (spectrum, config) = sea.build();
        let spectrum = spectrum.with_wind_direction(0.0)?;
        let mut ocean = OceanState::new(spectrum, config)?;
        ocean.pre_roll(60.0, 1.0 / 30.0)?;
        let (x0, z0) = (137.3, -52.9);
        let mut coarse = vec![0.0f32; SIDE * SIDE];
        let mut detail = vec![0.0f32; SIDE * SIDE];
        for j in 0..SIDE {
            for i in 0..SIDE {
                let (x, z) = (x0 + i as f64 * 0.25, z0 + j as f64 * 0.25);
                coarse[j * SIDE + i] = ocean.water().at_rest(x, z)?.foam;
                detail[j * SIDE + i] = ocean.foam_view().foam_at(x, z)?.total;
            }
        }
        let stretch = 1.0 / coarse.iter().fold(1e-6f32, |m, &v| m.max(v));
        for j in 0..SIDE {
            let y = row * (SIDE + GAP) + j;
            for i in 0..SIDE {
                let k = j * SIDE + i;
                pixels[y * width + i] = (255.0 * (coarse[k] * stretch).min(1.0)) as u8;
                pixels[y * width + SIDE + GAP + i] = (255.0 * detail[k]) as u8;
            }
        }
        let coverage = ocean.foam_view().coverage();
        let mean = detail.iter().map(|&v| f64::from(v)).sum::<f64>() / detail.len() as f64;
        println!(
            "{sea:?}: coverage {:.4}, mean of foam_at {mean:.4}, coarse max {:.3}",
            coverage.total,
            1.0 / stretch
        );
    }
    let path = out_dir("")?.join("foam_detail.png");
    save_gray8(&path, width, height, &pixels)?;
    println!("wrote {}", path.display());
    Ok(())
}
