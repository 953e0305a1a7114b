//! A contact sheet of every preset in `SeaState::ALL`: the same 200 m × 200 m window of each
//! sea seen from straight above, side by side in `out/sea_states.png`, each tile labelled with
//! the preset's name, H_s and T_p. Also prints a table of the presets (U10, fetch, depth, H_s,
//! T_p, cascade lengths).
//!
//! Each preset is built at size 128 (instead of its default 256) to stay fast, stepped for
//! 4 s at 30 Hz so that foam builds up, then sampled (`sample_many`, all cascades summed) at
//! 720×720 undisplaced points of the window (3×3 per pixel of a 240-pixel tile, averaged to
//! tame the aliasing of the small waves). Shading: a low sun from the upper left on the
//! surface normal (hill shading, which shows the slopes of small and large seas alike), a
//! tint that brightens crests by η/H_s of that preset, and foam blended to white.
//!
//! Run with `cargo run --release -p ocean-fft-examples --example sea_states`.

mod common;

use glam::Vec3;
use ocean_fft::{OceanState, SeaState, SurfaceSample};

use common::{out_dir, Canvas, Result};

/// Side of the world window shown in every tile, in metres.
const WINDOW: f64 = 200.0;
/// Tile side in pixels.
const TILE: usize = 240;
/// Samples per pixel along each axis (averaged, to tame aliasing of the small waves).
const SUPER: usize = 3;
const COLUMNS: usize = 3;
const PAD: usize = 12;
const LABEL: usize = 34;

fn main() -> Result<()> {
    let start = std::time::Instant::now();
    let rows = SeaState::ALL.len().div_ceil(COLUMNS);
    let width = COLUMNS * (TILE + PAD) + PAD;
    let height = rows * (TILE + LABEL + PAD) + PAD;
    let mut sheet = Canvas::new(width, height, [20, 24, 30]);

    let fine = TILE * SUPER;
    let points: Vec<[f64; 2]> = (0..fine * fine)
        .map(|p| {
            let (i, j) = (p % fine, p / fine);
            [
                (i as f64 + 0.5) * WINDOW / fine as f64,
                (j as f64 + 0.5) * WINDOW / fine as f64,
            ]
        })
        .collect();
    let mut samples = vec![SurfaceSample::default(); points.len()];
    let sun = Vec3::new(-0.7, 0.35, -0.5).normalize();

    println!(
        "{:<16} {:>8} {:>10} {:>9} {:>8} {:>7}  cascade lengths [m]",
        "preset", "U10 m/s", "fetch km", "depth m", "Hs m", "Tp s"
    );
    for (index, state) in SeaState::ALL.iter().enumerate() {
        let (spectrum, mut config) = state.build();
        let hs = spectrum.significant_wave_height();
        let tp = spectrum.peak_period();
        let fetch = spectrum
            .fetch()
            .map_or("-".to_string(), |f| format!("{:.0}", f / 1000.0));
        let depth = spectrum
            .depth()
            .map_or("deep".to_string(), |d| format!("{d:.1}"));
        println!(
            "{:<16} {:>8.2} {:>10} {:>9} {:>8.3} {:>7.2}  {:?}",
            state.name(),
            state.wind_speed(),
            fetch,
            depth,
            hs,
            tp,
            config.lengths
        );
        config.size = 128;
        let mut ocean = OceanState::new(spectrum, config)?;
        ocean.set_time(20.0)?;
        for _ in 0..120 {
            ocean.step(1.0 / 30.0)?;
        }
        ocean.sample_many(&points, &mut samples)?;

        let tile: Vec<u8> = (0..TILE * TILE)
            .flat_map(|p| {
                let (i, j) = (p % TILE, p / TILE);
                let mut sum = Vec3::ZERO;
                for dj in 0..SUPER {
                    for di in 0..SUPER {
                        sum += shade(&samples[(j * SUPER + dj) * fine + i * SUPER + di], sun, hs);
                    }
                }
                to_srgb(sum / (SUPER * SUPER) as f32)
            })
            .collect();
        let x0 = PAD + (index % COLUMNS) * (TILE + PAD);
        let y0 = PAD + (index / COLUMNS) * (TILE + LABEL + PAD);
        sheet.text(x0 as i64, y0 as i64, state.name(), 2, [235, 235, 235]);
        let numbers = format!("HS {hs:.2} M  TP {tp:.1} S");
        sheet.text(x0 as i64, y0 as i64 + 14, &numbers, 2, [170, 190, 210]);
        sheet.blit(x0 as i64, (y0 + LABEL) as i64, TILE, TILE, &tile);
    }

    let path = out_dir("")?.join("sea_states.png");
    sheet.save(&path)?;
    println!(
        "wrote {} (each tile: the same {WINDOW} m × {WINDOW} m window from above, x to the \
         right, z down; size 128, t = 24 s)",
        path.display()
    );
    println!("done in {:.2} s", start.elapsed().as_secs_f32());
    Ok(())
}

/// Linear colour of one top-view sample: hill shading from the normal, crests tinted by
/// η/H_s, foam blended to white.
fn shade(sample: &SurfaceSample, sun: Vec3, hs: f32) -> Vec3 {
    let deep = Vec3::new(0.01, 0.07, 0.14);
    let crest = Vec3::new(0.06, 0.30, 0.36);
    let lit = Vec3::from_array(sample.normal).dot(sun).max(0.0);
    let relative = (sample.height / hs.max(1e-6)).clamp(-0.5, 0.5) + 0.5;
    let water = deep.lerp(crest, relative) * (0.15 + 2.2 * lit * lit);
    water.lerp(Vec3::splat(0.95), sample.foam.clamp(0.0, 1.0))
}

/// Linear colour to 8-bit with gamma 2.2.
fn to_srgb(colour: Vec3) -> [u8; 3] {
    colour
        .to_array()
        .map(|c| (c.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0).round() as u8)
}
