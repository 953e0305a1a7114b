//! One N×N patch of ocean: h0(k) made once, h̃(k, t) evolved and turned into eight real
//! fields by four packed complex inverse FFTs on every [`Cascade::update`].

use std::f64::consts::TAU;

use glam::{Vec2, Vec3};
use num_complex::Complex32;
use rayon::prelude::*;

use crate::error::{self, Error};
use crate::fft2d::{transpose_into, RowFft, ROWS_PER_TASK};
use crate::seed;
use crate::spectrum::Spectrum;
use crate::MAX_SIZE;

/// Largest |t| accepted by [`Cascade::update`], in seconds (about 31.7 years). Up to here the
/// f64 phase ω·t keeps an error below 1e-5 rad.
pub const MAX_TIME: f64 = 1e9;

/// Smallest and largest accepted patch side, in metres.
const LENGTH_RANGE: (f32, f32) = (1e-2, 1e7);

/// Largest accepted bound on the outputs' magnitude (see [`Cascade::new`]): far enough below
/// f32::MAX that squares and cross products of the fields stay finite.
const AMPLITUDE_LIMIT: f64 = 1e15;

/// Where the displaced surface is vertical or folded (J ≤ 0), the slope's denominator n_y is
/// kept at least this fraction of |n|, so the slope stays finite (≤ 1e4).
const MIN_SLOPE_NY: f32 = 1e-4;

/// Parameters of one [`Cascade`]: passive data, validated by [`Cascade::new`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CascadeConfig {
    /// Grid size N (samples per side): even, 4 ≤ N ≤ [`MAX_SIZE`]; powers of two are fastest.
    /// Default 256.
    pub size: usize,
    /// Side L of the square patch, in metres (Δk = 2π/L). Default 1000 m.
    pub length: f32,
    /// Lower band limit in rad/m: wave vectors with |k| < `k_min` are left out. Default 0.
    pub k_min: f32,
    /// Upper band limit in rad/m: wave vectors with |k| ≥ `k_max` are left out (may be
    /// +∞). Default +∞.
    #[cfg_attr(
        feature = "serde",
        serde(
            with = "crate::serde_support::band_limit",
            default = "crate::serde_support::band_limit::infinite"
        )
    )]
    pub k_max: f32,
    /// Choppiness λ ≥ 0 (dimensionless): grid points move by λ·D. 1 gives the Gerstner
    /// profile for a single wave. Default 1.
    pub choppiness: f32,
    /// Seed of the random amplitudes; the same seed and L give the same waves at every N.
    /// Default 0.
    pub seed: u64,
    /// Repeat period T in seconds: when set, every ω is rounded down to a multiple of 2π/T,
    /// so the fields at t and t + T are equal (for looping bakes). Default `None`.
    pub repeat_period: Option<f32>,
}

impl Default for CascadeConfig {
    fn default() -> Self {
        CascadeConfig {
            size: 256,
            length: 1000.0,
            k_min: 0.0,
            k_max: f32::INFINITY,
            choppiness: 1.0,
            seed: 0,
            repeat_period: None,
        }
    }
}

/// The eight real fields a cascade synthesises, for [`Cascade::field`]. Each is the inverse
/// DFT of h̃(k, t) times the multiplier named (k = |k|); the displacement fields are per unit
/// choppiness.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Field {
    /// η, height in m (multiplier 1).
    Height,
    /// D_x in m (multiplier i k_x/k).
    DisplacementX,
    /// D_z in m (multiplier i k_z/k).
    DisplacementZ,
    /// ∂η/∂x of the undisplaced surface, dimensionless (multiplier i k_x).
    SlopeX,
    /// ∂η/∂z of the undisplaced surface, dimensionless (multiplier i k_z).
    SlopeZ,
    /// ∂D_x/∂x, dimensionless (multiplier −k_x²/k).
    DisplacementXX,
    /// ∂D_z/∂z, dimensionless (multiplier −k_z²/k).
    DisplacementZZ,
    /// ∂D_x/∂z = ∂D_z/∂x, dimensionless (multiplier −k_x k_z/k).
    DisplacementXZ,
}

impl Field {
    /// All eight fields, in packing order.
    pub const ALL: [Field; 8] = [
        Field::Height,
        Field::DisplacementX,
        Field::DisplacementZ,
        Field::SlopeX,
        Field::SlopeZ,
        Field::DisplacementXX,
        Field::DisplacementZZ,
        Field::DisplacementXZ,
    ];

    /// Which packed transform holds this field and whether it is the imaginary part.
    /// Transform p holds fields 2p (real part) and 2p + 1 (imaginary part) of [`Field::ALL`].
    pub fn packing(self) -> (usize, bool) {
        let index = Field::ALL.iter().position(|&f| f == self).unwrap_or(0);
        (index / 2, index % 2 == 1)
    }

    /// The spectral multiplier of this field at wave vector `k` = (k_x, k_z) in rad/m
    /// (0 at k = 0).
    pub fn multiplier(self, k: Vec2) -> Complex32 {
        let (kx, kz) = (k.x, k.y);
        let len = kx.hypot(kz);
        if len == 0.0 {
            return Complex32::new(0.0, 0.0);
        }
        match self {
            Field::Height => Complex32::new(1.0, 0.0),
            Field::DisplacementX => Complex32::new(0.0, kx / len),
            Field::DisplacementZ => Complex32::new(0.0, kz / len),
            Field::SlopeX => Complex32::new(0.0, kx),
            Field::SlopeZ => Complex32::new(0.0, kz),
            Field::DisplacementXX => Complex32::new(-kx * kx / len, 0.0),
            Field::DisplacementZZ => Complex32::new(-kz * kz / len, 0.0),
            Field::DisplacementXZ => Complex32::new(-kx * kz / len, 0.0),
        }
    }
}

/// One entry of the evolution table, for a wave vector k of the half plane that is evolved
/// (its partner −k gets the conjugate): h̃(k, t) = p cos φ + q sin φ, φ = 2π·`freq`·t.
///
/// From h̃ = h0(k) e^{−iφ} + conj(h0(−k)) e^{iφ}: p = h0(k) + conj(h0(−k)),
/// q = i (conj(h0(−k)) − h0(k)).
#[derive(Debug, Clone, Copy, Default)]
struct Evolution {
    p: Complex32,
    q: Complex32,
    /// ω(k)/2π in Hz (quantised when looping).
    freq: f64,
}

/// The evolution table in struct-of-arrays layout (so the evolution loop reads each
/// component contiguously and vectorises), transposed: index `i * N + j` holds the
/// [`Evolution`] of k_x index i in 0..N/2 and k_z index j.
#[derive(Debug, Default)]
struct EvolutionTable {
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

    fn get(&self, index: usize) -> Evolution {
        Evolution {
            p: Complex32::new(self.p_re[index], self.p_im[index]),
            q: Complex32::new(self.q_re[index], self.q_im[index]),
            freq: self.freq[index],
        }
    }

    /// Row `i` (k_x index) of an N-wide table.
    fn get_row(&self, i: usize, n: usize) -> EvolutionRow<'_> {
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
struct EvolutionRow<'a> {
    p_re: &'a [f32],
    p_im: &'a [f32],
    q_re: &'a [f32],
    q_im: &'a [f32],
    freq: &'a [f64],
    inv_k: &'a [f32],
}

impl EvolutionRow<'_> {
    fn get(&self, j: usize) -> Evolution {
        Evolution {
            p: Complex32::new(self.p_re[j], self.p_im[j]),
            q: Complex32::new(self.q_re[j], self.q_im[j]),
            freq: self.freq[j],
        }
    }
}

/// One N×N patch of ocean surface of side L: the wave amplitudes h0(k) drawn once from a
/// [`Spectrum`], and after every [`Cascade::update`] the height, horizontal displacement,
/// slope, normal and Jacobian of the surface at time t.
///
/// Buffers are row-major with z as the row: sample (i, j) at x = i·L/N, z = j·L/N is at
/// index `j * N + i`.
///
/// ```
/// use ocean_fft::{Cascade, CascadeConfig, Spectrum};
/// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
/// let config = CascadeConfig { size: 64, length: 250.0, ..CascadeConfig::default() };
/// let mut cascade = Cascade::new(&spectrum, config)?;
/// cascade.update(12.5)?;                          // t in seconds
/// let eta = cascade.height()[3 * 64 + 5];        // m, at x = 5·L/N, z = 3·L/N
/// assert!(eta.is_finite());
/// # Ok::<(), ocean_fft::Error>(())
/// ```
pub struct Cascade {
    config: CascadeConfig,
    n: usize,
    dk: f32,
    time: f64,
    expected_variance: f64,
    /// Σ 2|h0| · max(1, k_grid_max): a bound on every synthesised field's magnitude.
    amplitude_bound: f64,
    h0: Vec<Complex32>,
    /// Evolution table, transposed layout: rows are k_x index i in 0..N/2, columns k_z
    /// index j.
    evolution: EvolutionTable,
    /// k_z = Δk·m(j) of spectral column j.
    kz: Vec<f32>,
    rows: RowFft,
    /// Pass-1 buffer, layout [i][transform][j] (k_x row, k_z column → after the FFT, z).
    spectral: Vec<Complex32>,
    /// Pass-2 buffer, layout [j][transform][i] (z row, x column) once transformed.
    spatial: Vec<Complex32>,
    scratch: Vec<Complex32>,
    height: Vec<f32>,
    displacement: Vec<Vec2>,
    slope: Vec<Vec2>,
    normal: Vec<Vec3>,
    jacobian: Vec<f32>,
}

impl std::fmt::Debug for Cascade {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Cascade")
            .field("config", &self.config)
            .field("time", &self.time)
            .field("expected_variance", &self.expected_variance)
            .finish_non_exhaustive()
    }
}

/// Number of packed complex transforms per update.
const TRANSFORMS: usize = 4;

/// Checks a grid size: even, at least 4, at most [`MAX_SIZE`].
pub(crate) fn check_size(size: usize) -> Result<usize, Error> {
    if size < 4 || size % 2 != 0 || size > MAX_SIZE {
        return Err(Error::InvalidSize { size });
    }
    Ok(size)
}

/// Checks a simulation time: finite, |t| ≤ [`MAX_TIME`].
pub(crate) fn check_time(t: f64) -> Result<(), Error> {
    if !t.is_finite() {
        return Err(Error::NonFinite { name: "t" });
    }
    if t.abs() > MAX_TIME {
        return Err(Error::OutOfRange {
            name: "t",
            value: t,
            expected: "|t| ≤ 1e9 s",
        });
    }
    Ok(())
}

/// Signed wave-number index of grid index `i` on an N grid (plain FFT order).
#[inline]
pub(crate) fn wave_index(i: usize, n: usize) -> i32 {
    if i < n / 2 {
        i as i32
    } else {
        i as i32 - n as i32
    }
}

impl CascadeConfig {
    /// Checks every field; the error names the first bad one.
    pub fn validate(&self) -> Result<(), Error> {
        check_size(self.size)?;
        let length = error::positive("length", self.length)?;
        if length < LENGTH_RANGE.0 || length > LENGTH_RANGE.1 {
            return Err(error::out_of_range("length", length, "in [0.01, 1e7] m"));
        }
        let k_min = error::non_negative("k_min", self.k_min)?;
        if self.k_max.is_nan() {
            return Err(Error::NonFinite { name: "k_max" });
        }
        if self.k_max <= k_min {
            return Err(Error::EmptyBand {
                k_min: f64::from(k_min),
                k_max: f64::from(self.k_max),
            });
        }
        error::non_negative("choppiness", self.choppiness)?;
        if let Some(period) = self.repeat_period {
            error::positive("repeat_period", period)?;
        }
        Ok(())
    }
}

impl Cascade {
    /// Draws h0(k) = ½(ξ_r + iξ_i)·√S(k)·Δk for every wave vector of the grid with
    /// `k_min` ≤ |k| < `k_max` (zero elsewhere, and on k = 0 and the Nyquist row and column),
    /// ξ standard normals drawn from (seed, m_x, m_z); tabulates ω(k) of the spectrum's
    /// dispersion; allocates every buffer the updates use. The fields are those of t = 0.
    ///
    /// Errors: an invalid config ([`CascadeConfig::validate`]), a band holding no wave vector
    /// of the grid ([`Error::EmptyBand`]), or a spectrum so large at this grid that the fields
    /// could overflow f32 ([`Error::OutOfRange`] on `amplitude`).
    pub fn new(spectrum: &Spectrum, config: CascadeConfig) -> Result<Cascade, Error> {
        config.validate()?;
        let n = config.size;
        let dk64 = TAU / f64::from(config.length);
        let dk = dk64 as f32;
        let k_min = f64::from(config.k_min);
        let k_max = f64::from(config.k_max);
        let in_band = |i: usize, j: usize| -> Option<(f64, f64)> {
            if i == n / 2 || j == n / 2 {
                return None;
            }
            let kx = f64::from(wave_index(i, n)) * dk64;
            let kz = f64::from(wave_index(j, n)) * dk64;
            let k = kx.hypot(kz);
            (k > 0.0 && k >= k_min && k < k_max).then_some((kx, kz))
        };
        let band_has_vectors = (0..n).any(|j| (0..n).any(|i| in_band(i, j).is_some()));
        if !band_has_vectors {
            return Err(Error::EmptyBand { k_min, k_max });
        }

        // h0 in natural order, rows in parallel; each value depends only on its wave vector.
        let params = spectrum.spreading_params();
        let mut h0 = vec![Complex32::default(); n * n];
        let mut variance_rows = vec![0.0f64; n];
        h0.par_chunks_mut(n)
            .zip(variance_rows.par_iter_mut())
            .enumerate()
            .for_each(|(j, (row, variance))| {
                for (i, value) in row.iter_mut().enumerate() {
                    let Some((kx, kz)) = in_band(i, j) else {
                        continue;
                    };
                    let s = spectrum.density_f64(kx, kz, &params);
                    if s <= 0.0 {
                        continue;
                    }
                    *variance += s * dk64 * dk64;
                    let (xr, xi) =
                        seed::gaussian_pair(config.seed, wave_index(i, n), wave_index(j, n));
                    let amplitude = 0.5 * s.sqrt() * dk64;
                    *value = Complex32::new((xr * amplitude) as f32, (xi * amplitude) as f32);
                }
            });
        // Summed in a fixed order: the same result whatever the thread count.
        let expected_variance: f64 = variance_rows.iter().sum();
        let abs_sum: f64 = h0.iter().map(|c| f64::from(c.norm())).sum();
        let k_grid_max = dk64 * (n as f64 / 2.0) * std::f64::consts::SQRT_2;
        let amplitude_bound = 2.0 * abs_sum * k_grid_max.max(1.0);
        check_amplitude(amplitude_bound, config.choppiness)?;

        let dispersion = spectrum.dispersion();
        let looping = config.repeat_period.map(f64::from);
        let half = n / 2;
        // Each entry with 1/|k| (0 at k = 0), which the evolution loads instead of computing a
        // square root and a division.
        let mut evolution = vec![(Evolution::default(), 0.0f32); half * n];
        evolution
            .par_chunks_mut(n)
            .enumerate()
            .for_each(|(i, row)| {
                for (j, entry) in row.iter_mut().enumerate() {
                    let a = h0[j * n + i];
                    let b = h0[((n - j) % n) * n + (n - i) % n].conj();
                    let kx = f64::from(wave_index(i, n)) * dk64;
                    let kz = f64::from(wave_index(j, n)) * dk64;
                    let k = kx.hypot(kz);
                    let omega = dispersion.omega_f64(k);
                    let freq = match looping {
                        Some(period) => (omega * period / TAU).floor() / period,
                        None => omega / TAU,
                    };
                    let inv_k = if k > 0.0 { (1.0 / k) as f32 } else { 0.0 };
                    *entry = (
                        Evolution {
                            p: a + b,
                            q: Complex32::i() * (b - a),
                            freq,
                        },
                        inv_k,
                    );
                }
            });
        let evolution = EvolutionTable::from_entries(&evolution);
        let kz = (0..n).map(|j| wave_index(j, n) as f32 * dk).collect();
        let rows = RowFft::new(n);
        let tasks = n.div_ceil(ROWS_PER_TASK) + half;
        let mut cascade = Cascade {
            config,
            n,
            dk,
            time: 0.0,
            expected_variance,
            amplitude_bound,
            h0,
            evolution,
            kz,
            spectral: vec![Complex32::default(); TRANSFORMS * n * n],
            spatial: vec![Complex32::default(); TRANSFORMS * n * n],
            scratch: vec![Complex32::default(); tasks * rows.scratch_len()],
            rows,
            height: vec![0.0; n * n],
            displacement: vec![Vec2::ZERO; n * n],
            slope: vec![Vec2::ZERO; n * n],
            normal: vec![Vec3::Y; n * n],
            jacobian: vec![1.0; n * n],
        };
        cascade.update(0.0)?;
        Ok(cascade)
    }

    /// Evolves the spectrum to time `t` (seconds, f64; any t with |t| ≤ [`MAX_TIME`]) and
    /// recomputes every output buffer. Allocates nothing; the result does not depend on the
    /// number of rayon threads.
    ///
    /// Errors: non-finite t ([`Error::NonFinite`]) or |t| > [`MAX_TIME`]
    /// ([`Error::OutOfRange`]); the buffers are left as they were.
    pub fn update(&mut self, t: f64) -> Result<(), Error> {
        check_time(t)?;
        self.time = t;
        // Looping: the phases are integer multiples of t/T, so t mod T gives the same fields
        // with smaller, more precise phases.
        let phase_time = match self.config.repeat_period {
            Some(period) => t.rem_euclid(f64::from(period)),
            None => t,
        };
        // One job handed to rayon per update: inside it both passes run on the pool's
        // workers, whose own queues do not allocate (see `tests/alloc.rs`).
        rayon::scope(|_| {
            self.spectral_pass(phase_time);
            self.spatial_pass();
        });
        Ok(())
    }

    /// Pass 1: builds the four packed spectra row by row (rows are k_x, so a row and its
    /// Hermitian partner −k are rows i and N − i) and transforms each row along k_z while it
    /// is in cache.
    fn spectral_pass(&mut self, t: f64) {
        let n = self.n;
        let half = n / 2;
        let row_len = TRANSFORMS * n;
        let dk = self.dk;
        let evolution = &self.evolution;
        let rows = &self.rows;
        let s = rows.scratch_len();

        let (row0, rest) = self.spectral.split_at_mut(row_len);
        let (top, rest) = rest.split_at_mut((half - 1) * row_len);
        let (nyquist, bottom) = rest.split_at_mut(row_len);
        let (scratch0, scratch_pairs) = self.scratch.split_at_mut(s);

        let kz = &self.kz;
        rayon::join(
            || {
                // Row i = 0 (k_x = 0) is its own partner: (0, j) pairs with (0, N − j).
                row0.fill(Complex32::default());
                let table = evolution.get_row(0, n);
                for j in 1..half {
                    let e = table.get(j);
                    let (plus, minus) = packed_pair(
                        fract_turns(e.freq * t),
                        e.p,
                        e.q,
                        0.0,
                        kz[j],
                        table.inv_k[j],
                    );
                    for f in 0..TRANSFORMS {
                        row0[f * n + j] = plus[f];
                        row0[f * n + n - j] = minus[f];
                    }
                }
                rows.process(row0, scratch0);
                // Row N/2 is the Nyquist column: zero, and so is its transform.
                nyquist.fill(Complex32::default());
            },
            || {
                top.par_chunks_mut(row_len)
                    .zip(bottom.par_rchunks_mut(row_len))
                    .zip(scratch_pairs.par_chunks_mut(s))
                    .enumerate()
                    .for_each(|(index, ((upper, lower), scratch))| {
                        let i = index + 1;
                        let kx = i as f32 * dk;
                        evolve_row_pair(evolution.get_row(i, n), kx, kz, t, upper, lower);
                        rows.process(upper, scratch);
                        rows.process(lower, scratch);
                    });
            },
        );
    }

    /// Pass 2: gathers blocks of z rows from the pass-1 buffer (a blocked transpose),
    /// transforms them along x and turns the four packed results into the output buffers.
    fn spatial_pass(&mut self) {
        let n = self.n;
        let row_len = TRANSFORMS * n;
        let lambda = self.config.choppiness;
        let spectral = &self.spectral;
        let rows = &self.rows;
        let s = rows.scratch_len();
        let block = ROWS_PER_TASK * n;
        (
            self.spatial.par_chunks_mut(ROWS_PER_TASK * row_len),
            self.scratch.par_chunks_mut(s),
            self.height.par_chunks_mut(block),
            self.displacement.par_chunks_mut(block),
            self.slope.par_chunks_mut(block),
            self.normal.par_chunks_mut(block),
            self.jacobian.par_chunks_mut(block),
        )
            .into_par_iter()
            .enumerate()
            .for_each(
                |(b, (spatial, scratch, height, displacement, slope, normal, jacobian))| {
                    let j0 = b * ROWS_PER_TASK;
                    let count = spatial.len() / row_len;
                    // Gather: spatial[r][f][i] = spectral[i][f][j0 + r].
                    for f in 0..TRANSFORMS {
                        transpose_into(
                            &spectral[f * n + j0..],
                            row_len,
                            &mut spatial[f * n..],
                            row_len,
                            count,
                            n,
                        );
                    }
                    rows.process(spatial, scratch);
                    for r in 0..count {
                        let row = &spatial[r * row_len..(r + 1) * row_len];
                        let out = r * n..(r + 1) * n;
                        write_outputs(
                            row,
                            n,
                            lambda,
                            &mut height[out.clone()],
                            &mut displacement[out.clone()],
                            &mut slope[out.clone()],
                            &mut normal[out.clone()],
                            &mut jacobian[out],
                        );
                    }
                },
            );
    }

    /// The configuration this cascade was built with (choppiness as last set).
    pub fn config(&self) -> &CascadeConfig {
        &self.config
    }

    /// Grid size N.
    pub fn size(&self) -> usize {
        self.n
    }

    /// Side L of the patch in metres.
    pub fn length(&self) -> f32 {
        self.config.length
    }

    /// Grid spacing Δk = 2π/L of the wave vectors, in rad/m.
    pub fn delta_k(&self) -> f32 {
        self.dk
    }

    /// Time in seconds of the last [`Cascade::update`] (0 after construction).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Changes the choppiness λ (dimensionless, ≥ 0). Takes effect at the next
    /// [`Cascade::update`].
    pub fn set_choppiness(&mut self, choppiness: f32) -> Result<(), Error> {
        let lambda = self.check_choppiness(choppiness)?;
        self.config.choppiness = lambda;
        Ok(())
    }

    /// The checks of [`Cascade::set_choppiness`] without the change.
    pub(crate) fn check_choppiness(&self, choppiness: f32) -> Result<f32, Error> {
        let lambda = error::non_negative("choppiness", choppiness)?;
        check_amplitude(self.amplitude_bound, lambda)?;
        Ok(lambda)
    }

    /// Expected variance of η in m²: Σ S(k) Δk² over the wave vectors of the grid in the
    /// band. 16 times this is the expected square of the simulated H_s.
    pub fn expected_variance(&self) -> f64 {
        self.expected_variance
    }

    /// Height η in metres at every grid point (undisplaced positions).
    pub fn height(&self) -> &[f32] {
        &self.height
    }

    /// Horizontal displacement λ·(D_x, D_z) in metres: grid point x₀ moves to x₀ + this.
    pub fn displacement(&self) -> &[Vec2] {
        &self.displacement
    }

    /// Slope (∂y/∂x, ∂y/∂z) of the displaced surface at each grid point's displaced position,
    /// (−n_x/n_y, −n_z/n_y), dimensionless. n_y = J is kept at least 1e-4·|n|, so where the
    /// surface is vertical or folds (J ≤ 0) the slope stays finite (magnitude ≤ 1e4).
    pub fn slope(&self) -> &[Vec2] {
        &self.slope
    }

    /// Unit normal of the displaced surface, (T_z × T_x)/|T_z × T_x|; it points down where
    /// the surface folds over itself (J < 0).
    pub fn normal(&self) -> &[Vec3] {
        &self.normal
    }

    /// Jacobian J = (1 + λD_xx)(1 + λD_zz) − λ²D_xz² of the horizontal displacement map,
    /// dimensionless: below 1 at crests, negative where the surface folds (foam).
    pub fn jacobian(&self) -> &[f32] {
        &self.jacobian
    }

    /// The initial amplitudes h0(k) in m, in the grid's FFT order (index j·N + i holds
    /// k = Δk·(m(i), m(j))).
    pub fn h0(&self) -> &[Complex32] {
        &self.h0
    }

    /// The evolved spectrum h̃(k, t) = h0(k)e^{−iωt} + conj(h0(−k))e^{iωt} in m, in the grid's
    /// FFT order, computed afresh in f64 (for verification and tools; allocates). Non-finite
    /// t gives zeros.
    pub fn wave_spectrum(&self, t: f64) -> Vec<Complex32> {
        let n = self.n;
        if !t.is_finite() {
            return vec![Complex32::default(); n * n];
        }
        let t = match self.config.repeat_period {
            Some(period) => t.rem_euclid(f64::from(period)),
            None => t,
        };
        let mut out = vec![Complex32::default(); n * n];
        for j in 0..n {
            for i in 0..n {
                let (entry, conjugate) = self.evolution_entry(i, j);
                let phase = (entry.freq * t).fract() * TAU;
                let (sin, cos) = phase.sin_cos();
                let p = (f64::from(entry.p.re), f64::from(entry.p.im));
                let q = (f64::from(entry.q.re), f64::from(entry.q.im));
                let value = Complex32::new(
                    (p.0 * cos + q.0 * sin) as f32,
                    (p.1 * cos + q.1 * sin) as f32,
                );
                out[j * n + i] = if conjugate { value.conj() } else { value };
            }
        }
        out
    }

    /// Angular frequency ω(k) in rad/s used for the wave vector at grid index (i, j)
    /// (quantised when looping). Out-of-grid indices give 0.
    pub fn omega_at(&self, i: usize, j: usize) -> f64 {
        if i >= self.n || j >= self.n {
            return 0.0;
        }
        self.evolution_entry(i, j).0.freq * TAU
    }

    /// The table entry that evolves (i, j), and whether (i, j) is the conjugate partner.
    fn evolution_entry(&self, i: usize, j: usize) -> (Evolution, bool) {
        let n = self.n;
        let half = n / 2;
        if i == half || j == half {
            (Evolution::default(), false)
        } else if i < half {
            (self.evolution.get(i * n + j), false)
        } else {
            let (pi, pj) = ((n - i) % n, (n - j) % n);
            (self.evolution.get(pi * n + pj), true)
        }
    }

    /// One of the eight real fields at the last update, in metres or dimensionless as
    /// [`Field`] says, in buffer order (index j·N + i). Allocates; read straight from the
    /// packed transforms.
    pub fn field(&self, field: Field) -> Vec<f32> {
        let n = self.n;
        let (transform, imaginary) = field.packing();
        let mut out = Vec::with_capacity(n * n);
        for j in 0..n {
            let row = &self.spatial[(j * TRANSFORMS + transform) * n..][..n];
            out.extend(row.iter().map(|c| if imaginary { c.im } else { c.re }));
        }
        out
    }

    /// The raw result of packed transform `transform` (0..4) at the last update, in buffer
    /// order: real part field 2·`transform`, imaginary part field 2·`transform` + 1 of
    /// [`Field::ALL`]. An index ≥ 4 gives an empty vector.
    pub fn packed_transform(&self, transform: usize) -> Vec<Complex32> {
        let n = self.n;
        if transform >= TRANSFORMS {
            return Vec::new();
        }
        let mut out = Vec::with_capacity(n * n);
        for j in 0..n {
            out.extend_from_slice(&self.spatial[(j * TRANSFORMS + transform) * n..][..n]);
        }
        out
    }
}

fn check_amplitude(bound: f64, choppiness: f32) -> Result<(), Error> {
    let bound = bound * f64::from(choppiness).max(1.0);
    if bound.is_nan() || bound > AMPLITUDE_LIMIT {
        return Err(Error::OutOfRange {
            name: "amplitude",
            value: bound,
            expected: "2·Σ|h0|·max(1, k)·max(1, λ) ≤ 1e15 (fields would overflow f32)",
        });
    }
    Ok(())
}

/// 1.5·2^52: adding and subtracting it rounds an f64 of magnitude below 2^51 to an integer
/// (ties to even) with plain arithmetic, which vectorises (`f64::round` is a libm call on
/// baseline x86-64).
const ROUND_F64: f64 = 6_755_399_441_055_744.0;
/// 1.5·2^23, the same for f32 below 2^22; the low mantissa bits of `x + ROUND_F32` are then
/// the rounded integer in two's complement.
const ROUND_F32: f32 = 12_582_912.0;

/// `turns` minus the nearest integer, in [−½, ½] for |turns| < 2^51 (larger values give an
/// integer, which [`sin_cos_turns`] also handles).
#[inline(always)]
fn fract_turns(turns: f64) -> f32 {
    (turns - ((turns + ROUND_F64) - ROUND_F64)) as f32
}

/// sin and cos of 2π·`turns` for `turns` in [−½, ½] (any |turns| < 2^20 works), to about
/// 1e-7: reduced to a quarter turn and a short Taylor polynomial on [−π/4, π/4] (truncation
/// error below 2e-9 for the sine and 3e-8 for the cosine). Branch-free, so that loops over it vectorise.
#[inline(always)]
pub(crate) fn sin_cos_turns(turns: f32) -> (f32, f32) {
    let shifted = turns * 4.0 + ROUND_F32;
    let quadrant = shifted - ROUND_F32;
    let q = shifted.to_bits();
    let a = (turns - quadrant * 0.25) * std::f32::consts::TAU;
    let a2 = a * a;
    let sin = a
        * (1.0
            + a2 * (-1.0 / 6.0
                + a2 * (1.0 / 120.0 + a2 * (-1.0 / 5040.0 + a2 * (1.0 / 362_880.0)))));
    let cos = 1.0 + a2 * (-0.5 + a2 * (1.0 / 24.0 + a2 * (-1.0 / 720.0 + a2 * (1.0 / 40_320.0))));
    // Quadrant q: (sin, cos) → (s, c), (c, −s), (−s, −c), (−c, s).
    let (x, y) = if q & 1 == 0 { (sin, cos) } else { (cos, sin) };
    let sin_sign = (q & 2) << 30;
    let cos_sign = (q.wrapping_add(1) & 2) << 30;
    (
        f32::from_bits(x.to_bits() ^ sin_sign),
        f32::from_bits(y.to_bits() ^ cos_sign),
    )
}

/// The four packed spectral values at k = (`kx`, `kz`) and at −k, from an evolution entry's
/// p and q and its phase in `turns` (reduced, see [`fract_turns`]).
///
/// Transform p holds A + iB for the field pair (A, B) = (η, D_x), (D_z, η_x), (η_z, D_xx),
/// (D_zz, D_xz). With A = α h̃, B = β h̃ and Hermitian fields, the value at k is (α + iβ) h̃
/// and at −k it is (conj α + i conj β) conj h̃. With u = k/|k| the multipliers α + iβ at k
/// and at −k are 1 ∓ u_x, ∓k_x + i u_z, i(k_z ∓ k_x u_x) and −u_z(k_z + i k_x); the
/// products of h̃ they share are computed once.
#[inline(always)]
fn packed_pair(
    turns: f32,
    p: Complex32,
    q: Complex32,
    kx: f32,
    kz: f32,
    inv_k: f32,
) -> ([Complex32; 4], [Complex32; 4]) {
    let (sin, cos) = sin_cos_turns(turns);
    let (hr, hi) = (p.re * cos + q.re * sin, p.im * cos + q.im * sin);
    let (ux, uz) = (kx * inv_k, kz * inv_k);
    // Transform 0: h̃(1 − u_x) at k, conj h̃ (1 + u_x) at −k.
    let (a, b) = (1.0 - ux, 1.0 + ux);
    let hib = hi * b;
    // Transform 1: h̃(−k_x + i u_z) at k, conj h̃ (k_x − i u_z) at −k.
    let (kx_hr, uz_hi, kx_hi, uz_hr) = (kx * hr, uz * hi, kx * hi, uz * hr);
    // Transform 2: i c h̃ at k, −i d conj h̃ at −k.
    let kx_ux = kx * ux;
    let (c, d) = (kz - kx_ux, kz + kx_ux);
    // Transform 3: (e + i f) h̃ at k and (e + i f) conj h̃ at −k.
    let (e, f) = (-(kz * uz), -(kx * uz));
    let (hr_e, hi_f, hr_f, hi_e) = (hr * e, hi * f, hr * f, hi * e);
    let plus = [
        Complex32::new(hr * a, hi * a),
        Complex32::new(-kx_hr - uz_hi, uz_hr - kx_hi),
        Complex32::new(-(c * hi), c * hr),
        Complex32::new(hr_e - hi_f, hr_f + hi_e),
    ];
    let minus = [
        Complex32::new(hr * b, -hib),
        Complex32::new(kx_hr - uz_hi, -uz_hr - kx_hi),
        Complex32::new(-(d * hi), -(d * hr)),
        Complex32::new(hr_e + hi_f, hr_f - hi_e),
    ];
    (plus, minus)
}

/// Columns evolved by one [`evolve_block`] call.
const EVOLVE_BLOCK: usize = 64;

/// Fills spectral rows i (`upper`, k_x > 0) and N − i (`lower`, its Hermitian partner), each
/// four packed transforms of N, from table row i: (i, j) pairs with (N − i, N − j).
#[inline(never)]
fn evolve_row_pair(
    table: EvolutionRow<'_>,
    kx: f32,
    kz: &[f32],
    t: f64,
    upper: &mut [Complex32],
    lower: &mut [Complex32],
) {
    let n = kz.len();
    let (u0, rest) = upper.split_at_mut(n);
    let (u1, rest) = rest.split_at_mut(n);
    let (u2, u3) = rest.split_at_mut(n);
    let (l0, rest) = lower.split_at_mut(n);
    let (l1, rest) = rest.split_at_mut(n);
    let (l2, l3) = rest.split_at_mut(n);
    let (u3, l3) = (&mut u3[..n], &mut l3[..n]);
    // Column 0 pairs with itself; the rest pair j with N − j. (The Nyquist column's table
    // entries are zero, so it comes out zero.)
    let e = table.get(0);
    let (plus, minus) = packed_pair(fract_turns(e.freq * t), e.p, e.q, kx, kz[0], table.inv_k[0]);
    (u0[0], u1[0], u2[0], u3[0]) = (plus[0], plus[1], plus[2], plus[3]);
    (l0[0], l1[0], l2[0], l3[0]) = (minus[0], minus[1], minus[2], minus[3]);
    // Blocks of EVOLVE_BLOCK columns over 1..N: the f64 phase reduction first (2 lanes per
    // SSE vector), then the f32 work (4 lanes), each loop vectorising at its own width. When
    // N − 1 ≥ EVOLVE_BLOCK every block is full (the last one starts early and recomputes a
    // few columns, writing the same values), so the vector loops have no scalar remainder.
    let mut turns = [0.0f32; EVOLVE_BLOCK];
    let columns = n - 1;
    let len = EVOLVE_BLOCK.min(columns);
    let mut next = 1;
    while next < n {
        let start = next.min(n - len);
        let range = start..start + len;
        let turns = &mut turns[..len];
        for (turns, &freq) in turns.iter_mut().zip(&table.freq[range.clone()]) {
            *turns = fract_turns(freq * t);
        }
        let mirror = n - start - len + 1..n - start + 1;
        evolve_block(
            turns,
            &table.p_re[range.clone()],
            &table.p_im[range.clone()],
            &table.q_re[range.clone()],
            &table.q_im[range.clone()],
            &table.inv_k[range.clone()],
            kx,
            &kz[range.clone()],
            &mut u0[range.clone()],
            &mut u1[range.clone()],
            &mut u2[range.clone()],
            &mut u3[range],
            &mut l0[mirror.clone()],
            &mut l1[mirror.clone()],
            &mut l2[mirror.clone()],
            &mut l3[mirror],
        );
        next = start + len;
    }
}

/// The four packed values of a block of columns j (`plus`, at the block's columns) and of
/// their partners N − j (`minus`, in reverse order), from the block's reduced phases and
/// table entries (p_re, p_im, q_re, q_im). A function of its own, every output slice a
/// separate `&mut` argument (so that LLVM knows they do not overlap and needs no run-time
/// checks), so that the loop vectorises.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn evolve_block(
    turns: &[f32],
    p_re: &[f32],
    p_im: &[f32],
    q_re: &[f32],
    q_im: &[f32],
    inv_k: &[f32],
    kx: f32,
    kz: &[f32],
    u0: &mut [Complex32],
    u1: &mut [Complex32],
    u2: &mut [Complex32],
    u3: &mut [Complex32],
    l0: &mut [Complex32],
    l1: &mut [Complex32],
    l2: &mut [Complex32],
    l3: &mut [Complex32],
) {
    let len = turns.len();
    let (p_re, p_im) = (&p_re[..len], &p_im[..len]);
    let (q_re, q_im) = (&q_re[..len], &q_im[..len]);
    let (inv_k, kz) = (&inv_k[..len], &kz[..len]);
    let (u0, u1, u2, u3) = (
        &mut u0[..len],
        &mut u1[..len],
        &mut u2[..len],
        &mut u3[..len],
    );
    let (l0, l1, l2, l3) = (
        &mut l0[..len],
        &mut l1[..len],
        &mut l2[..len],
        &mut l3[..len],
    );
    for b in 0..len {
        let p = Complex32::new(p_re[b], p_im[b]);
        let q = Complex32::new(q_re[b], q_im[b]);
        let (plus, minus) = packed_pair(turns[b], p, q, kx, kz[b], inv_k[b]);
        (u0[b], u1[b], u2[b], u3[b]) = (plus[0], plus[1], plus[2], plus[3]);
        let m = len - 1 - b;
        (l0[m], l1[m], l2[m], l3[m]) = (minus[0], minus[1], minus[2], minus[3]);
    }
}

/// Output buffers of one grid row from its four packed, transformed rows.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn write_outputs(
    row: &[Complex32],
    n: usize,
    lambda: f32,
    height: &mut [f32],
    displacement: &mut [Vec2],
    slope: &mut [Vec2],
    normal: &mut [Vec3],
    jacobian: &mut [f32],
) {
    let (t0, rest) = row.split_at(n);
    let (t1, rest) = rest.split_at(n);
    let (t2, t3) = rest.split_at(n);
    // Blocks of OUTPUT_BLOCK: the arithmetic runs into plain f32 arrays for the normals (so
    // that it vectorises; stores of Vec3 in the same loop keep it scalar), then the normals
    // are copied out.
    const OUTPUT_BLOCK: usize = 128;
    let mut nx = [0.0f32; OUTPUT_BLOCK];
    let mut ny = [0.0f32; OUTPUT_BLOCK];
    let mut nz = [0.0f32; OUTPUT_BLOCK];
    for start in (0..n).step_by(OUTPUT_BLOCK) {
        let len = OUTPUT_BLOCK.min(n - start);
        let range = start..start + len;
        output_block(
            &t0[range.clone()],
            &t1[range.clone()],
            &t2[range.clone()],
            &t3[range.clone()],
            lambda,
            &mut height[range.clone()],
            &mut jacobian[range.clone()],
            &mut displacement[range.clone()],
            &mut slope[range.clone()],
            &mut nx[..len],
            &mut ny[..len],
            &mut nz[..len],
        );
        for (normal, ((&x, &y), &z)) in normal[range].iter_mut().zip(nx.iter().zip(&ny).zip(&nz)) {
            *normal = Vec3::new(x, y, z);
        }
    }
}

/// The arithmetic of [`write_outputs`] on one block, with the normals into plain f32 arrays.
/// A function of its own, with every slice a separate argument (so that LLVM knows they do
/// not overlap and needs no run-time checks), so that the loop vectorises.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn output_block(
    t0: &[Complex32],
    t1: &[Complex32],
    t2: &[Complex32],
    t3: &[Complex32],
    lambda: f32,
    height: &mut [f32],
    jacobian: &mut [f32],
    displacement: &mut [Vec2],
    slope: &mut [Vec2],
    nx: &mut [f32],
    ny: &mut [f32],
    nz: &mut [f32],
) {
    let len = t0.len();
    let (t1, t2, t3) = (&t1[..len], &t2[..len], &t3[..len]);
    let (height, jacobian) = (&mut height[..len], &mut jacobian[..len]);
    let (displacement, slope) = (&mut displacement[..len], &mut slope[..len]);
    let (nx, ny, nz) = (&mut nx[..len], &mut ny[..len], &mut nz[..len]);
    for i in 0..len {
        let (eta, dx) = (t0[i].re, t0[i].im);
        let (dz, eta_x) = (t1[i].re, t1[i].im);
        let (eta_z, dxx) = (t2[i].re, t2[i].im);
        let (dzz, dxz) = (t3[i].re, t3[i].im);
        let jxx = 1.0 + lambda * dxx;
        let jzz = 1.0 + lambda * dzz;
        let jxz = lambda * dxz;
        let det = jxx * jzz - jxz * jxz;
        // n = T_z × T_x with T_x = (jxx, η_x, jxz), T_z = (jxz, η_z, jzz); n_y = J.
        let (rx, rz) = (eta_z * jxz - jzz * eta_x, jxz * eta_x - eta_z * jxx);
        let norm = (rx * rx + det * det + rz * rz).sqrt();
        // Branch-free (selects); false for NaN too.
        let valid = (norm > 0.0) & (norm < f32::INFINITY);
        let inv_len = 1.0 / norm;
        // A plain compare rather than f32::max (which handles NaN, at a cost): a NaN here
        // only comes with a NaN norm, where `valid` is false anyway.
        let min_ny = MIN_SLOPE_NY * norm;
        let inv_ny = 1.0 / if det > min_ny { det } else { min_ny };
        height[i] = eta;
        displacement[i] = Vec2::new(lambda * dx, lambda * dz);
        jacobian[i] = det;
        nx[i] = if valid { rx * inv_len } else { 0.0 };
        ny[i] = if valid { det * inv_len } else { 1.0 };
        nz[i] = if valid { rz * inv_len } else { 0.0 };
        slope[i] = if valid {
            Vec2::new(-rx * inv_ny, -rz * inv_ny)
        } else {
            Vec2::ZERO
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fast_sin_cos_matches_std_over_a_turn() {
        let mut worst = 0.0f64;
        for step in -50_000..=50_000 {
            let turns = step as f32 / 100_000.0;
            let (s, c) = sin_cos_turns(turns);
            let (es, ec) = (f64::from(turns) * TAU).sin_cos();
            worst = worst
                .max((f64::from(s) - es).abs())
                .max((f64::from(c) - ec).abs());
        }
        // f32 rounding of the reduced angle and of the polynomial: a few ulps of 1.
        assert!(worst < 5e-7, "worst error {worst}");
    }

    #[test]
    fn fast_sin_cos_handles_quadrant_ties_and_whole_turns() {
        // Exact quadrant boundaries (ties of the rounding) and values beyond half a turn.
        for step in -12..=12 {
            let turns = step as f32 / 8.0;
            let (s, c) = sin_cos_turns(turns);
            let (es, ec) = (f64::from(turns) * TAU).sin_cos();
            assert!((f64::from(s) - es).abs() < 1e-6, "sin at {turns}");
            assert!((f64::from(c) - ec).abs() < 1e-6, "cos at {turns}");
        }
    }

    #[test]
    fn fract_turns_reduces_large_phases_exactly() {
        for (turns, expected) in [
            (0.25, 0.25),
            (-0.25, -0.25),
            (3.75, -0.25),
            (-7.125, -0.125),
            (1e12 + 0.375, 0.375),
            (-(2f64.powi(40)) - 0.0625, -0.0625),
        ] {
            assert_eq!(fract_turns(turns), expected, "turns {turns}");
        }
        // Beyond 2^52 every f64 is an integer: the phase is a whole number of turns.
        let (s, c) = sin_cos_turns(fract_turns(2f64.powi(60) + 4096.0));
        assert!(s.abs() < 1e-7 && (c - 1.0).abs() < 1e-7);
    }

    #[test]
    fn wave_index_is_plain_fft_order() {
        let n = 8;
        let m: Vec<i32> = (0..n).map(|i| wave_index(i, n)).collect();
        assert_eq!(m, vec![0, 1, 2, 3, -4, -3, -2, -1]);
    }
}
