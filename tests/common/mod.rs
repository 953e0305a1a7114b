//! Independent reference computations shared by the cascade tests: a naive O(N⁴) inverse DFT
//! in f64, the spectral multipliers of the eight fields written out from the table in docs/theory.md,
//! seeded spectra and statistics in f64. Nothing here calls the crate's own synthesis code.
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]
#![allow(dead_code)]

use std::f64::consts::TAU;

use ocean_fft::inspect::{Complex32, Field};
use ocean_fft::Spectrum;

/// A complex number in f64 as (re, im).
pub type C64 = (f64, f64);

pub fn cmul(a: C64, b: C64) -> C64 {
    (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0)
}

pub fn cabs(a: C64) -> f64 {
    a.0.hypot(a.1)
}

pub fn to64(c: Complex32) -> C64 {
    (f64::from(c.re), f64::from(c.im))
}

/// Signed wave-number index of grid index `i` on an N grid: i for i < N/2, i − N otherwise.
pub fn m(i: usize, n: usize) -> i64 {
    if i < n / 2 {
        i as i64
    } else {
        i as i64 - n as i64
    }
}

/// Grid index of signed wave number `m` on an N grid (inverse of [`m`]).
pub fn index_of(m: i64, n: usize) -> usize {
    m.rem_euclid(n as i64) as usize
}

/// Index of −k for the spectral index (i, j): ((N − i) mod N, (N − j) mod N) as a buffer index.
pub fn neg_index(i: usize, j: usize, n: usize) -> usize {
    ((n - j) % n) * n + (n - i) % n
}

/// Field order of `Field::ALL` as documented (packing: transform p holds 2p and 2p + 1).
pub const FIELDS: [Field; 8] = [
    Field::Height,
    Field::DisplacementX,
    Field::DisplacementZ,
    Field::SlopeX,
    Field::SlopeZ,
    Field::DisplacementXX,
    Field::DisplacementZZ,
    Field::DisplacementXZ,
];

/// The spectral multiplier of `field` at k = (kx, kz), in f64, written out from the table in docs/theory.md:
/// η: 1; D_x, D_z: i k_x/k, i k_z/k; η_x, η_z: i k_x, i k_z; D_xx, D_zz, D_xz: −k_x²/k,
/// −k_z²/k, −k_x k_z/k; 0 at k = 0.
pub fn multiplier(field: Field, kx: f64, kz: f64) -> C64 {
    let k = (kx * kx + kz * kz).sqrt();
    if k == 0.0 {
        return (0.0, 0.0);
    }
    match field {
        Field::Height => (1.0, 0.0),
        Field::DisplacementX => (0.0, kx / k),
        Field::DisplacementZ => (0.0, kz / k),
        Field::SlopeX => (0.0, kx),
        Field::SlopeZ => (0.0, kz),
        Field::DisplacementXX => (-kx * kx / k, 0.0),
        Field::DisplacementZZ => (-kz * kz / k, 0.0),
        Field::DisplacementXZ => (-kx * kz / k, 0.0),
    }
}

/// The spectrum of `field`: h̃(k) times the multiplier, zero at k = 0 and on the Nyquist row
/// and column. `length` is the patch side L (Δk = 2π/L).
pub fn field_spectrum(h: &[Complex32], n: usize, length: f64, field: Field) -> Vec<C64> {
    let dk = TAU / length;
    let mut out = vec![(0.0, 0.0); n * n];
    for j in 0..n {
        for i in 0..n {
            if i == n / 2 || j == n / 2 {
                continue;
            }
            let kx = m(i, n) as f64 * dk;
            let kz = m(j, n) as f64 * dk;
            out[j * n + i] = cmul(to64(h[j * n + i]), multiplier(field, kx, kz));
        }
    }
    out
}

/// Naive inverse DFT, O(N⁴): out(i, j) = Σ_{p,q} c(p, q) e^{i 2π (m(p) i + m(q) j)/N}
/// (k·x with k = Δk·(m(p), m(q)), x = (i, j)·L/N), buffer index j·N + i on both sides.
/// Every term is added explicitly; the exponentials come from a table of e^{2πi r/N} with
/// r = (m(p) i + m(q) j) mod N, each entry computed directly by sin/cos in f64.
pub fn naive_idft(c: &[C64], n: usize) -> Vec<C64> {
    let table: Vec<C64> = (0..n)
        .map(|r| {
            let a = TAU * r as f64 / n as f64;
            (a.cos(), a.sin())
        })
        .collect();
    let mut out = vec![(0.0, 0.0); n * n];
    for (idx, &v) in c.iter().enumerate() {
        if v == (0.0, 0.0) {
            continue;
        }
        // m(p) mod N and m(q) mod N are just p and q.
        let (p, q) = (idx % n, idx / n);
        for j in 0..n {
            let mut r = (q * j) % n;
            let row = &mut out[j * n..(j + 1) * n];
            for value in row.iter_mut() {
                let e = table[r];
                value.0 += v.0 * e.0 - v.1 * e.1;
                value.1 += v.0 * e.1 + v.1 * e.0;
                r += p;
                if r >= n {
                    r -= n;
                }
            }
        }
    }
    out
}

/// JONSWAP U = 10 m/s, F = 100 km (peak wavelength about 60 m), wind toward `direction` rad.
pub fn jonswap(direction: f32) -> Spectrum {
    Spectrum::jonswap(10.0, 100_000.0)
        .unwrap()
        .with_wind_direction(direction)
        .unwrap()
}

/// Tessendorf's Phillips spectrum, U = 10 m/s, A = 3e-4 (a moderate sea in metres), wind
/// toward `direction` rad.
pub fn phillips(direction: f32) -> Spectrum {
    Spectrum::phillips(10.0, 3e-4)
        .unwrap()
        .with_wind_direction(direction)
        .unwrap()
}

pub fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

/// Population variance (divides by n).
pub fn variance(v: &[f64]) -> f64 {
    let mu = mean(v);
    v.iter().map(|x| (x - mu) * (x - mu)).sum::<f64>() / v.len() as f64
}

/// Sample standard deviation (divides by n − 1).
pub fn sample_std(v: &[f64]) -> f64 {
    let mu = mean(v);
    (v.iter().map(|x| (x - mu) * (x - mu)).sum::<f64>() / (v.len() as f64 - 1.0)).sqrt()
}

/// Pearson correlation of two equally long samples.
pub fn correlation(a: &[f64], b: &[f64]) -> f64 {
    let (ma, mb) = (mean(a), mean(b));
    let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        sab += (x - ma) * (y - mb);
        saa += (x - ma) * (x - ma);
        sbb += (y - mb) * (y - mb);
    }
    sab / (saa * sbb).sqrt()
}

pub fn to_f64(v: &[f32]) -> Vec<f64> {
    v.iter().map(|&x| f64::from(x)).collect()
}

pub fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |a, &x| a.max(x.abs()))
}

/// The same inverse DFT as [`naive_idft`] evaluated separably in f64, O(N³): first along x
/// (for every k_z row), then along z. Every sum is still a direct sum of N terms with
/// exponentials from the table (no FFT), so it serves as an independent reference at sizes
/// where the O(N⁴) form is too slow.
pub fn separable_idft(c: &[C64], n: usize) -> Vec<C64> {
    let table: Vec<C64> = (0..n)
        .map(|r| {
            let a = TAU * r as f64 / n as f64;
            (a.cos(), a.sin())
        })
        .collect();
    // rows[q][i] = Σ_p c(p, q) e^{2πi p i/N}
    let mut rows = vec![(0.0, 0.0); n * n];
    for q in 0..n {
        for i in 0..n {
            let (mut re, mut im) = (0.0, 0.0);
            for p in 0..n {
                let v = c[q * n + p];
                let e = table[(p * i) % n];
                re += v.0 * e.0 - v.1 * e.1;
                im += v.0 * e.1 + v.1 * e.0;
            }
            rows[q * n + i] = (re, im);
        }
    }
    // out[j][i] = Σ_q rows[q][i] e^{2πi q j/N}
    let mut out = vec![(0.0, 0.0); n * n];
    for j in 0..n {
        for q in 0..n {
            let e = table[(q * j) % n];
            let row = &rows[q * n..(q + 1) * n];
            for (o, v) in out[j * n..(j + 1) * n].iter_mut().zip(row) {
                o.0 += v.0 * e.0 - v.1 * e.1;
                o.1 += v.0 * e.1 + v.1 * e.0;
            }
        }
    }
    out
}
