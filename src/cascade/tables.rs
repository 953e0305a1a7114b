//! The tables a cascade builds once: h0(k) drawn per wave vector and the evolution table
//! (p, q, frequency and 1/|k| per wave vector of the evolved half plane).

use std::f64::consts::TAU;

use num_complex::Complex32;
use rayon::prelude::*;

use super::CascadeConfig;
use crate::error::{self, Error};
use crate::math::determinism::Math;
use crate::math::grid::wave_index;
use crate::math::rng;
use crate::spectrum::dispersion::Dispersion;
use crate::spectrum::{Radial, Spectrum};

/// Largest accepted bound on the outputs' magnitude (see [`Cascade::new`](crate::Cascade::new)): far enough below
/// f32::MAX that squares and cross products of the fields stay finite.
pub(super) const AMPLITUDE_LIMIT: f64 = 1e15;

/// One entry of the evolution table, for a wave vector k of the half plane that is evolved
/// (its partner −k gets the conjugate): h̃(k, t) = p cos φ + q sin φ, φ = 2π·`freq`·t.
///
/// From h̃ = h0(k) e^{−iφ} + conj(h0(−k)) e^{iφ}: p = h0(k) + conj(h0(−k)),
/// q = i (conj(h0(−k)) − h0(k)).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Evolution {
    pub(super) p: Complex32,
    pub(super) q: Complex32,
    /// ω(k)/2π in Hz (quantised when looping).
    pub(super) freq: f64,
}

/// The evolution table in struct-of-arrays layout (so the evolution loop reads each
/// component contiguously and vectorises), transposed: index `i * N + j` holds the
/// [`Evolution`] of k_x index i in 0..N/2 and k_z index j.
#[derive(Debug, Clone, Default)]
pub(super) struct EvolutionTable {
    p_re: Vec<f32>,
    p_im: Vec<f32>,
    q_re: Vec<f32>,
    q_im: Vec<f32>,
    freq: Vec<f64>,
    /// 1/|k| (0 at k = 0), tabulated: cheaper to load than a square root and a division.
    inv_k: Vec<f32>,
}

impl EvolutionTable {
    /// From entries with their 1/|k|, in table order.
    fn from_entries(entries: &[(Evolution, f32)]) -> Self {
        EvolutionTable {
            p_re: entries.iter().map(|(e, _)| e.p.re).collect(),
            p_im: entries.iter().map(|(e, _)| e.p.im).collect(),
            q_re: entries.iter().map(|(e, _)| e.q.re).collect(),
            q_im: entries.iter().map(|(e, _)| e.q.im).collect(),
            freq: entries.iter().map(|(e, _)| e.freq).collect(),
            inv_k: entries.iter().map(|&(_, inv_k)| inv_k).collect(),
        }
    }

    pub(super) fn get(&self, index: usize) -> Evolution {
        Evolution {
            p: Complex32::new(self.p_re[index], self.p_im[index]),
            q: Complex32::new(self.q_re[index], self.q_im[index]),
            freq: self.freq[index],
        }
    }

    /// Row `i` (k_x index) of an N-wide table.
    pub(super) fn get_row(&self, i: usize, n: usize) -> EvolutionRow<'_> {
        let range = i * n..(i + 1) * n;
        EvolutionRow {
            p_re: &self.p_re[range.clone()],
            p_im: &self.p_im[range.clone()],
            q_re: &self.q_re[range.clone()],
            q_im: &self.q_im[range.clone()],
            freq: &self.freq[range.clone()],
            inv_k: &self.inv_k[range],
        }
    }
}

/// One row of an [`EvolutionTable`].
#[derive(Clone, Copy)]
pub(super) struct EvolutionRow<'a> {
    pub(super) p_re: &'a [f32],
    pub(super) p_im: &'a [f32],
    pub(super) q_re: &'a [f32],
    pub(super) q_im: &'a [f32],
    pub(super) freq: &'a [f64],
    pub(super) inv_k: &'a [f32],
}

impl EvolutionRow<'_> {
    pub(super) fn get(&self, j: usize) -> Evolution {
        Evolution {
            p: Complex32::new(self.p_re[j], self.p_im[j]),
            q: Complex32::new(self.q_re[j], self.q_im[j]),
            freq: self.freq[j],
        }
    }
}

pub(super) fn check_amplitude(bound: f64, choppiness: f32) -> Result<(), Error> {
    let bound = bound * f64::from(choppiness).max(1.0);
    if bound.is_nan() || bound > AMPLITUDE_LIMIT {
        return Err(Error::AmplitudeTooLarge {
            bound,
            limit: AMPLITUDE_LIMIT,
        });
    }
    Ok(())
}

/// The random amplitudes of a cascade and what follows from them.
pub(super) struct Amplitudes {
    /// h0(k) in m, in the grid's FFT order.
    pub(super) h0: Vec<Complex32>,
    /// Σ S(k) Δk² over the wave vectors in the band, in m².
    pub(super) expected_variance: f64,
    /// Σ 2|h0| · max(1, k_grid_max): a bound on every synthesised field's magnitude.
    pub(super) amplitude_bound: f64,
}

/// The part of S(k) that depends on |k| alone, for every length of wave vector an N grid
/// holds once (a ≥ b ≥ 0 for |m_x|, |m_z| in either order, at index a(a + 1)/2 + b), filled
/// for those in the band: a grid evaluates the costly radial part (the omnidirectional
/// spectrum, the dispersion and the spreading's shape at ω(k)) once per length instead of up
/// to eight times.
#[derive(Debug, Clone, Copy)]
pub(super) struct RadialEntry {
    /// The |k| the entry was computed at (NaN: none).
    k: f64,
    radial: Option<Radial>,
}

impl RadialEntry {
    pub(super) const NONE: RadialEntry = RadialEntry {
        k: f64::NAN,
        radial: None,
    };
}

/// Entries of the radial table of an N grid.
pub(super) fn radial_entries(n: usize) -> usize {
    let half = n / 2;
    (half + 1) * (half + 2) / 2
}

/// The index of |m| = (a, b) (either order) in the radial table.
fn radial_index(a: usize, b: usize) -> usize {
    let (a, b) = (a.max(b), a.min(b));
    a * (a + 1) / 2 + b
}

/// Fills the radial table's rows a of `rows` (each the entries (a, 0 … a)) for `spectrum` on
/// the config's grid, with the functions of `M`; `table` is the whole table. Serial and
/// allocation-free (a step of a change of weather fills a few rows). Returns the number of
/// entries computed (those in the band), a measure of the work done.
pub(super) fn fill_radial<M: Math>(
    spectrum: &Spectrum,
    config: &CascadeConfig,
    rows: std::ops::Range<usize>,
    table: &mut [RadialEntry],
) -> usize {
    let dk64 = TAU / f64::from(config.length);
    let params = spectrum.spreading_params();
    let (k_min, k_max) = (f64::from(config.k_min), f64::from(config.k_max));
    let mut count = 0;
    for a in rows {
        for b in 0..=a {
            let k = M::hypot(a as f64 * dk64, b as f64 * dk64);
            table[radial_index(a, b)] = if k > 0.0 && k >= k_min && k < k_max {
                count += 1;
                RadialEntry {
                    k,
                    radial: spectrum.radial_with::<M>(k, &params),
                }
            } else {
                RadialEntry::NONE
            };
        }
    }
    count
}

/// Draws h0(k) = ½(ξ_r + iξ_i)·√S(k)·Δk for the grid rows (z index j) of `rows`, into `h0`
/// (those rows of an N×N buffer in the grid's FFT order) and each row's Σ S(k)Δk² into
/// `variance` (one value per row of `rows`): every wave vector of the band
/// `k_min` ≤ |k| < `k_max` (zero elsewhere, and on k = 0 and the Nyquist row and column), ξ
/// standard normals drawn from (seed, m_x, m_z). S(k) comes from the radial table `radial`
/// (filled by [`fill_radial`]) where it holds the wave vector's length, to the same bits as
/// [`Spectrum::density_with`] gives. Rows in parallel; each value depends only on its wave
/// vector, so any split of the rows gives the same amplitudes.
pub(super) fn draw_rows<M: Math>(
    spectrum: &Spectrum,
    config: &CascadeConfig,
    rows: std::ops::Range<usize>,
    radial: &[RadialEntry],
    h0: &mut [Complex32],
    variance: &mut [f64],
) {
    let n = config.size;
    let dk64 = TAU / f64::from(config.length);
    let params = spectrum.spreading_params();
    let first = rows.start;
    h0[first * n..rows.end * n]
        .par_chunks_mut(n)
        .zip(variance.par_iter_mut())
        .enumerate()
        .for_each(|(r, (row, variance))| {
            let j = first + r;
            let mz = wave_index(j, n);
            *variance = 0.0;
            for (i, value) in row.iter_mut().enumerate() {
                *value = Complex32::default();
                let Some((kx, kz, k)) = in_band_with_length::<M>(config, i, j) else {
                    continue;
                };
                let mx = wave_index(i, n);
                let entry =
                    radial[radial_index(mx.unsigned_abs() as usize, mz.unsigned_abs() as usize)];
                let s = if entry.k.to_bits() == k.to_bits() {
                    match &entry.radial {
                        Some(part) => spectrum.angular_with::<M>(part, kx, kz, &params),
                        None => 0.0,
                    }
                } else {
                    // Not in the table (a length the table computed otherwise): directly.
                    spectrum.density_with::<M>(kx, kz, &params)
                };
                if s <= 0.0 {
                    continue;
                }
                *variance += s * dk64 * dk64;
                let (xr, xi) = rng::gaussian_pair::<M>(config.seed, mx, mz);
                let amplitude = 0.5 * s.sqrt() * dk64;
                *value = Complex32::new((xr * amplitude) as f32, (xi * amplitude) as f32);
            }
        });
}

/// The wave vector (k_x, k_z) in rad/m of grid index (i, j) when it lies in the config's band
/// (`k_min` ≤ |k| < `k_max`, not k = 0, not on the Nyquist row or column).
pub(super) fn in_band<M: Math>(config: &CascadeConfig, i: usize, j: usize) -> Option<(f64, f64)> {
    in_band_with_length::<M>(config, i, j).map(|(kx, kz, _)| (kx, kz))
}

/// [`in_band`] with the wave vector's length |k| = hypot(k_x, k_z).
fn in_band_with_length<M: Math>(
    config: &CascadeConfig,
    i: usize,
    j: usize,
) -> Option<(f64, f64, f64)> {
    let n = config.size;
    if i == n / 2 || j == n / 2 {
        return None;
    }
    let dk64 = TAU / f64::from(config.length);
    let kx = f64::from(wave_index(i, n)) * dk64;
    let kz = f64::from(wave_index(j, n)) * dk64;
    let (k_min, k_max) = (f64::from(config.k_min), f64::from(config.k_max));
    // Far outside the band by k² alone (which hypot's k matches to an ulp): skip hypot, the
    // costly part, for most of a band-limited grid.
    let square = kx * kx + kz * kz;
    let (lo, hi) = (k_min * (1.0 - 1e-9), k_max * (1.0 + 1e-9));
    if square < lo * lo || square >= hi * hi {
        return None;
    }
    let k = M::hypot(kx, kz);
    (k > 0.0 && k >= k_min && k < k_max).then_some((kx, kz, k))
}

/// Σ 2|h0| · max(1, k_grid_max) of amplitudes `h0` on the config's grid: a bound on every
/// synthesised field's magnitude (see [`check_amplitude`]).
pub(super) fn amplitude_bound<M: Math>(h0: &[Complex32], config: &CascadeConfig) -> f64 {
    let n = config.size;
    let dk64 = TAU / f64::from(config.length);
    // Zeros (most of a band-limited grid) add nothing and are skipped.
    let abs_sum: f64 = h0
        .iter()
        .filter(|c| c.re != 0.0 || c.im != 0.0)
        .map(|c| M::hypot(f64::from(c.re), f64::from(c.im)))
        .sum();
    let k_grid_max = dk64 * (n as f64 / 2.0) * std::f64::consts::SQRT_2;
    2.0 * abs_sum * k_grid_max.max(1.0)
}

impl Amplitudes {
    /// Draws every row's amplitudes (see [`draw_rows`]). Errors with [`Error::EmptyBand`]
    /// when the band holds no wave vector of the grid.
    pub(super) fn draw<M: Math>(
        spectrum: &Spectrum,
        config: &CascadeConfig,
    ) -> Result<Self, Error> {
        let n = config.size;
        let band_has_vectors = (0..n).any(|j| (0..n).any(|i| in_band::<M>(config, i, j).is_some()));
        if !band_has_vectors {
            return Err(Error::EmptyBand {
                k_min: f64::from(config.k_min),
                k_max: f64::from(config.k_max),
            });
        }
        let mut h0 = error::try_vec(n * n, Complex32::default())?;
        let mut variance_rows = vec![0.0f64; n];
        let mut radial = error::try_vec(radial_entries(n), RadialEntry::NONE)?;
        fill_radial::<M>(spectrum, config, 0..n / 2 + 1, &mut radial);
        draw_rows::<M>(spectrum, config, 0..n, &radial, &mut h0, &mut variance_rows);
        // Summed in a fixed order: the same result whatever the thread count.
        let expected_variance: f64 = variance_rows.iter().sum();
        let amplitude_bound = amplitude_bound::<M>(&h0, config);
        Ok(Amplitudes {
            h0,
            expected_variance,
            amplitude_bound,
        })
    }
}

impl EvolutionTable {
    /// The table of an N×N grid with spacing `dk` (rad/m) from its amplitudes `h0`: p and q
    /// of every wave vector with k_x index i in 0..N/2, ω(k)/2π from `dispersion` (rounded
    /// to the nearest multiple of 1/T, at least 1/T, when `looping` gives a period T in
    /// seconds: see [`frequency`]), and 1/|k|.
    pub(super) fn new<M: Math>(
        h0: &[Complex32],
        n: usize,
        dk: f64,
        dispersion: Dispersion,
        looping: Option<f64>,
    ) -> Self {
        let half = n / 2;
        // Each entry with 1/|k| (0 at k = 0), which the evolution loads instead of computing a
        // square root and a division.
        let mut evolution = vec![(Evolution::default(), 0.0f32); half * n];
        evolution
            .par_chunks_mut(n)
            .enumerate()
            .for_each(|(i, row)| {
                for (j, entry) in row.iter_mut().enumerate() {
                    let (p, q) = evolved_pair(h0, n, i, j);
                    let kx = f64::from(wave_index(i, n)) * dk;
                    let kz = f64::from(wave_index(j, n)) * dk;
                    let k = M::hypot(kx, kz);
                    let omega = dispersion.omega_with::<M>(k);
                    let freq = frequency(omega, looping);
                    let inv_k = if k > 0.0 { (1.0 / k) as f32 } else { 0.0 };
                    *entry = (Evolution { p, q, freq }, inv_k);
                }
            });
        EvolutionTable::from_entries(&evolution)
    }
}

/// (p, q) of the table entry (i, j) (i < N/2) from the amplitudes `h0` (N×N, FFT order):
/// p = h0(k) + conj(h0(−k)), q = i (conj(h0(−k)) − h0(k)).
#[inline]
fn evolved_pair(h0: &[Complex32], n: usize, i: usize, j: usize) -> (Complex32, Complex32) {
    let a = h0[j * n + i];
    let b = h0[((n - j) % n) * n + (n - i) % n].conj();
    (a + b, Complex32::i() * (b - a))
}

impl EvolutionTable {
    /// Replaces p and q with those of the amplitudes `h0` (N×N, FFT order), keeping the
    /// frequencies and 1/|k|: the table [`EvolutionTable::new`] builds from `h0`. Table rows
    /// i (k_x index) for which `live(i)` is false are left as they are (the caller knows
    /// that `h0` is zero in grid column i and its partner, so p = q = 0 there already).
    pub(super) fn set_amplitudes(
        &mut self,
        h0: &[Complex32],
        n: usize,
        live: impl Fn(usize) -> bool + Sync,
    ) {
        let EvolutionTable {
            p_re,
            p_im,
            q_re,
            q_im,
            ..
        } = self;
        (
            p_re.par_chunks_mut(n),
            p_im.par_chunks_mut(n),
            q_re.par_chunks_mut(n),
            q_im.par_chunks_mut(n),
        )
            .into_par_iter()
            .enumerate()
            .filter(|(i, _)| live(*i))
            .for_each(|(i, (p_re, p_im, q_re, q_im))| {
                for j in 0..n {
                    let (p, q) = evolved_pair(h0, n, i, j);
                    (p_re[j], p_im[j], q_re[j], q_im[j]) = (p.re, p.im, q.re, q.im);
                }
            });
    }
}

/// The frequency ω/2π in Hz a wave of angular frequency `omega` (rad/s) is evolved with: as it
/// is, or on a loop of period T (`looping`, s) the nearest whole number of cycles per loop,
/// and at least one, so that the fields repeat after T and no wave stands still.
pub(super) fn frequency(omega: f64, looping: Option<f64>) -> f64 {
    match looping {
        Some(period) => (omega * period / TAU).round().max(1.0) / period,
        None => omega / TAU,
    }
}

/// How far looping moves the waves' frequencies from the dispersion relation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoopError {
    /// The largest relative frequency error |ω_loop − ω|/ω over the wave vectors that carry
    /// energy, dimensionless. Waves much longer than the loop get one cycle per loop, so this
    /// grows without bound as T shrinks.
    pub max_relative: f64,
    /// The mean of |ω_loop − ω|/ω weighted by each wave's share of the height variance,
    /// dimensionless: what the eye sees on average.
    pub mean_relative: f64,
    /// The time-averaged height variance of the waves weighed, in m² (2 Σ|h0|² of this
    /// realisation), by which cascades' errors are combined.
    pub variance: f64,
}

impl LoopError {
    /// The loop error of the wave vectors with amplitudes `h0` on an N×N grid of spacing `dk`
    /// (rad/m) under `dispersion`, looping with period `period` in seconds.
    pub(super) fn new<M: Math>(
        h0: &[Complex32],
        n: usize,
        dk: f64,
        dispersion: Dispersion,
        period: f64,
    ) -> Self {
        let mut out = LoopError {
            max_relative: 0.0,
            mean_relative: 0.0,
            variance: 0.0,
        };
        for j in 0..n {
            for i in 0..n {
                let energy = f64::from(h0[j * n + i].norm_sqr());
                if energy == 0.0 {
                    continue;
                }
                let kx = f64::from(wave_index(i, n)) * dk;
                let kz = f64::from(wave_index(j, n)) * dk;
                let omega = dispersion.omega_with::<M>(M::hypot(kx, kz));
                let looped = frequency(omega, Some(period)) * TAU;
                let relative = (looped - omega).abs() / omega;
                out.max_relative = out.max_relative.max(relative);
                out.mean_relative += energy * relative;
                out.variance += energy;
            }
        }
        if out.variance > 0.0 {
            out.mean_relative /= out.variance;
        }
        // The time-averaged variance of η is Σ_k (|h0(k)|² + |h0(−k)|²) = 2 Σ_k |h0(k)|².
        out.variance *= 2.0;
        out
    }

    /// The errors of several cascades together, each weighted by its variance.
    pub(crate) fn combine(errors: impl IntoIterator<Item = LoopError>) -> Option<LoopError> {
        let mut total: Option<LoopError> = None;
        for e in errors {
            let t = total.get_or_insert(LoopError {
                max_relative: 0.0,
                mean_relative: 0.0,
                variance: 0.0,
            });
            t.max_relative = t.max_relative.max(e.max_relative);
            t.mean_relative += e.mean_relative * e.variance;
            t.variance += e.variance;
        }
        if let Some(t) = total.as_mut() {
            if t.variance > 0.0 {
                t.mean_relative /= t.variance;
            }
        }
        total
    }
}
