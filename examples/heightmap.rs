//! The default ocean in a few seconds: builds `Spectrum::jonswap(10.0, 100_000.0)` (U10 = 10 m/s,
//! 100 km fetch) with `OceanConfig::default()` (three cascades of 256² over 1000, 230 and 51 m),
//! pre-rolls its foam over the 15 s before t = 10 s (300 steps of 1/20 s) and writes, for the
//! largest cascade (1000 m, 256×256):
//!
//! - `out/heightmap.png`: 16-bit grayscale height η, mapped linearly from [−a, a] to
//!   [0, 65535] with a = max |η| of the tile (printed);
//! - `out/normal.png`: 8-bit RGB normal map of the displaced surface, each component mapped
//!   from [−1, 1] to [0, 255] with **R = n_x, G = n_z, B = n_y** (the usual tangent-space
//!   layout with the surface's up axis y in blue, so flat water is (128, 128, 255));
//! - `out/foam.png`: 8-bit foam of the whole ocean, which lives on the largest cascade's grid
//!   (active whitecaps and residual foam together, [0, 1] → [0, 255]).
//!
//! It prints the foam coverage beside the whitecap fraction the calibration aims at, and the significant wave height H_s = 4·std(η) measured on a grid of world
//! points (all cascades summed, via `sample_many`) beside the spectrum's 4√m0 and the
//! expected 4√(Σ S(k)Δk²) of the grids.
//!
//! Run with `cargo run --release -p ocean-fft-examples --example heightmap` from the repository
//! root. Pixel (i, j) of every image is grid sample (i, j) at x = i·L/N, z = j·L/N (image rows
//! are z).

mod common;

use ocean_fft::{OceanConfig, OceanState, Spectrum, SurfaceSample};

use common::{out_dir, save_gray16, save_gray8, save_rgb8, to_u16, to_u8, Result};

fn main() -> Result<()> {
    let start = std::time::Instant::now();
    let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
    let hs_spectrum = spectrum.significant_wave_height();
    let mut ocean = OceanState::new(spectrum, OceanConfig::default())?;

    // Jump to t = 10 s and pre-roll the foam over the 15 s before it: active whitecaps (τ_A =
    // 3.85 s) reach their steady coverage, residual foam (τ_R = 20 s) is still building.
    ocean.set_time(10.0)?;
    ocean.pre_roll(15.0, 1.0 / 20.0)?;

    let dir = out_dir("")?;
    let cascade = &ocean.cascades()[0];
    let n = cascade.size();

    // Height of the largest cascade, 16-bit.
    let height = cascade.height();
    let a = height.iter().fold(0.0f32, |m, &h| m.max(h.abs())).max(1e-6);
    let pixels: Vec<u16> = height.iter().map(|&h| to_u16(h, a)).collect();
    let path = dir.join("heightmap.png");
    save_gray16(&path, n, n, &pixels)?;
    println!(
        "wrote {} ({n}×{n}, L = {} m, height mapped from [−{a:.3}, {a:.3}] m to [0, 65535])",
        path.display(),
        cascade.length()
    );

    // Normal map: R = n_x, G = n_z, B = n_y (up).
    let pixels: Vec<u8> = cascade
        .normal()
        .iter()
        .flat_map(|v| [v[0], v[2], v[1]].map(|c| to_u8(0.5 + 0.5 * c)))
        .collect();
    let path = dir.join("normal.png");
    save_rgb8(&path, n, n, &pixels)?;
    println!(
        "wrote {} (R = n_x, G = n_z, B = n_y, each from [−1, 1] to [0, 255])",
        path.display()
    );

    // The ocean's foam, on the largest cascade's grid.
    let foam = ocean.foam();
    let pixels: Vec<u8> = foam.iter().map(|&f| to_u8(f)).collect();
    let path = dir.join("foam.png");
    save_gray8(&path, n, n, &pixels)?;
    let coverage = ocean.foam_coverage();
    let calibration = ocean.foam_calibration();
    println!(
        "wrote {} (foam in [0, 1] → [0, 255]); coverage: active whitecaps {:.2} %, residual \
         {:.2} %; whitecap fraction aimed at (Monahan & O'Muircheartaigh 1980, U10 = {} m/s): \
         {:.2} %, breaking threshold J_b = {:.3}",
        path.display(),
        100.0 * coverage.active,
        100.0 * coverage.residual,
        calibration.wind_speed,
        100.0 * calibration.target,
        calibration.threshold,
    );

    // Measured H_s: the summed surface on a 512×512 grid of world points spanning exactly
    // one period of the largest cascade (the smaller ones are periodic inside it).
    let m = 512;
    let period = f64::from(cascade.length());
    let points: Vec<[f64; 2]> = (0..m * m)
        .map(|p| {
            let (i, j) = (p % m, p / m);
            [i as f64 * period / m as f64, j as f64 * period / m as f64]
        })
        .collect();
    let mut samples = vec![SurfaceSample::default(); points.len()];
    ocean.sample_many(&points, &mut samples)?;
    let mean = samples.iter().map(|s| f64::from(s.height)).sum::<f64>() / samples.len() as f64;
    let variance = samples
        .iter()
        .map(|s| (f64::from(s.height) - mean).powi(2))
        .sum::<f64>()
        / samples.len() as f64;
    let hs_measured = 4.0 * variance.sqrt();
    let hs_expected = 4.0 * ocean.expected_variance().sqrt();
    println!("t = {:.2} s", ocean.time());
    println!(
        "H_s measured, 4·std of the summed height at {m}×{m} world points: {hs_measured:.3} m"
    );
    println!("H_s expected from the grids, 4·√(expected_variance()):          {hs_expected:.3} m");
    println!("H_s of the spectrum, significant_wave_height() (4√m0):           {hs_spectrum:.3} m");
    println!(
        "(one random realisation: the few longest waves dominate, so the measured value \
         scatters by several per cent around the expected one)"
    );
    println!("done in {:.2} s", start.elapsed().as_secs_f32());
    Ok(())
}
