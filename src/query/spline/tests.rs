//! The tiles against the exact periodic interpolation filter.

use super::{Source, Tiles, HEIGHT, SLOPE, STRIDE};
use crate::math::simd::Simd;

/// The exact periodic interpolation filter along one axis, in f64, by solving the
/// circulant system in the frequency domain (an independent computation): c = f / B̂
/// with B̂(k) = (4 + 2 cos(2πk/N))/6, through a direct DFT.
// Reference maths in the standard library's functions: a test, not simulation code.
#[allow(clippy::disallowed_methods)]
fn exact_1d(values: &[f64]) -> Vec<f64> {
    use std::f64::consts::TAU;
    let n = values.len();
    let spectrum: Vec<(f64, f64)> = (0..n)
        .map(|k| {
            let b = (4.0 + 2.0 * (TAU * k as f64 / n as f64).cos()) / 6.0;
            let (mut re, mut im) = (0.0, 0.0);
            for (x, v) in values.iter().enumerate() {
                let phase = TAU * ((k * x) % n) as f64 / n as f64;
                re += v * phase.cos();
                im -= v * phase.sin();
            }
            (re / b, im / b)
        })
        .collect();
    (0..n)
        .map(|x| {
            let sum: f64 = spectrum
                .iter()
                .enumerate()
                .map(|(k, (re, im))| {
                    let phase = TAU * ((k * x) % n) as f64 / n as f64;
                    re * phase.cos() - im * phase.sin()
                })
                .sum();
            sum / n as f64
        })
        .collect()
}

/// The exact 2D coefficients: along x on every row, then along z on every column.
fn exact(values: &[f64], n: usize) -> Vec<f64> {
    let mut rows: Vec<f64> = values.chunks(n).flat_map(exact_1d).collect();
    for i in 0..n {
        let column: Vec<f64> = (0..n).map(|j| rows[j * n + i]).collect();
        for (j, c) in exact_1d(&column).into_iter().enumerate() {
            rows[j * n + i] = c;
        }
    }
    rows
}

#[test]
fn tiles_hold_the_periodic_coefficients_to_f32_precision() {
    // One tile (wrapping several times), whole tiles, and a partial last tile (100).
    for n in [4usize, 6, 10, 16, 64, 100] {
        let height: Vec<f32> = (0..n * n)
            .map(|i| ((i * 7919) % 101) as f32 / 50.0 - 1.0)
            .collect();
        let pairs: Vec<[f32; 2]> = height.iter().map(|&h| [h * 0.5, -h]).collect();
        let source = Source {
            height: &height,
            displacement: &pairs,
            slope: &pairs,
        };
        let reference = exact(&height.iter().map(|&h| f64::from(h)).collect::<Vec<_>>(), n);
        let tiles = Tiles::new(n).unwrap();
        let mut worst = 0.0f64;
        for iz in 0..n {
            for ix in 0..n {
                let (data, lx, lz) = tiles.cell(ix, iz, || source, Simd::Baseline { fused: true });
                // The cell's 4×4 taps are grid points ix − 1 … ix + 2, iz − 1 … iz + 2.
                for b in 0..4 {
                    for a in 0..4 {
                        let (i, j) = ((ix + n + a - 1) % n, (iz + n + b - 1) % n);
                        let at = (lz + b) * STRIDE + lx + a;
                        let h = data[HEIGHT + at];
                        worst = worst.max((f64::from(h) - reference[j * n + i]).abs());
                        // The fields are filtered independently (scaling by a power of two
                        // commutes with every rounding).
                        assert_eq!(data[2 * at..2 * at + 2], [h * 0.5, -h]);
                        assert_eq!(data[SLOPE + 2 * at..SLOPE + 2 * at + 2], [h * 0.5, -h]);
                    }
                }
            }
        }
        // Each of the four recursions rounds once a step; the errors are summed with the
        // weights |z|^k (Σ 1.37) and the gain (1.6) per pass, so they stay within a few
        // f32 ε of the largest coefficient (measured: 1.7 ε). Dropping the terms beyond
        // z^8 instead of z^16 would show about 20·|z|^9 ≈ 1.4e-4 of it, 1000 ε.
        let largest = reference.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        let bound = 8.0 * f64::from(f32::EPSILON) * largest;
        assert!(worst < bound, "N = {n}: worst {worst:e}, bound {bound:e}");
    }
}
