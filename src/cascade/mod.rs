//! One N×N patch of ocean: h0(k) made once, h̃(k, t) evolved and turned into eight real
//! fields by four packed complex inverse FFTs on every [`Cascade::update`].

mod config;
mod evolve;
mod field;
mod inspect;
mod outputs;
mod tables;

use std::f64::consts::TAU;
use std::ops::Bound::Included;

use num_complex::Complex32;
use rayon::prelude::*;

use crate::error::{self, Error};
use crate::fft2d::{transpose_into, RowFft, ROWS_PER_TASK};
use crate::grid::{self, wave_index};
use crate::spectrum::Spectrum;

pub(crate) use config::check_band;
pub use config::CascadeConfig;
pub use field::Field;
pub(crate) use inspect::GradientMoments;

use evolve::{evolve_row_pair, fract_turns, packed_pair};
use outputs::write_outputs;
pub use tables::LoopError;
use tables::{check_amplitude, Amplitudes, EvolutionTable};

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
///
/// `Clone` copies every table and buffer (about 127·N² bytes): the copy updates to the same
/// bits as the original.
#[derive(Clone)]
pub struct Cascade {
    config: CascadeConfig,
    n: usize,
    dk: f32,
    time: f64,
    expected_variance: f64,
    /// Σ 2|h0| · max(1, k_grid_max): a bound on every synthesised field's magnitude.
    amplitude_bound: f64,
    /// How far looping moved the frequencies (None without a repeat period).
    loop_error: Option<LoopError>,
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
    displacement: Vec<[f32; 2]>,
    slope: Vec<[f32; 2]>,
    normal: Vec<[f32; 3]>,
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

/// Checks a simulation time `name`: finite, |t| ≤ [`Cascade::MAX_TIME`].
pub(crate) fn check_time(name: &'static str, t: f64) -> Result<f64, Error> {
    error::in_range_f64(
        name,
        t,
        Included(-Cascade::MAX_TIME),
        Included(Cascade::MAX_TIME),
    )
}

/// Bytes a cascade of size `n` holds: its buffers, tables, FFT plan and scratch (planned
/// for a valid size; for larger ones the scratch is estimated at N per task).
pub(crate) fn memory_bytes(n: usize) -> usize {
    let points = n.saturating_mul(n);
    let complex = std::mem::size_of::<Complex32>();
    let scratch_len = if n <= grid::MAX_SIZE {
        RowFft::new(n).scratch_len()
    } else {
        n
    };
    let per_point = [
        complex,                  // h0
        2 * TRANSFORMS * complex, // pass-1 and pass-2 buffers
        4 + 2 * 8 + 12 + 4,       // height, displacement, slope, normal, jacobian
    ];
    let evolution_entry = 4 * 4 + 8 + 4; // p, q, freq, 1/|k|, for half the points
    let tables = (points / 2).saturating_mul(evolution_entry) + n.saturating_mul(4);
    let scratch = tasks(n).saturating_mul(scratch_len).saturating_mul(complex);
    per_point
        .iter()
        .fold(tables.saturating_add(scratch), |sum, &bytes| {
            sum.saturating_add(points.saturating_mul(bytes))
        })
}

/// Parallel tasks of one update, each with its own scratch: the row pairs of pass 1 and the
/// row blocks of pass 2 at once.
fn tasks(n: usize) -> usize {
    n.div_ceil(ROWS_PER_TASK) + n / 2
}

impl Cascade {
    /// Largest |t| accepted by [`Cascade::update`], in seconds (about 31.7 years). Up to here
    /// the f64 phase ω·t keeps an error below 1e-5 rad.
    pub const MAX_TIME: f64 = 1e9;

    /// Largest bound on the fields' magnitude that [`Cascade::new`] accepts (see
    /// [`Error::AmplitudeTooLarge`]): far enough below f32::MAX that squares and cross
    /// products of the fields stay finite.
    pub const MAX_AMPLITUDE: f64 = tables::AMPLITUDE_LIMIT;

    /// Draws h0(k) = ½(ξ_r + iξ_i)·√S(k)·Δk for every wave vector of the grid with
    /// `k_min` ≤ |k| < `k_max` (zero elsewhere, and on k = 0 and the Nyquist row and column),
    /// ξ standard normals drawn from (seed, m_x, m_z); tabulates ω(k) of the spectrum's
    /// dispersion; allocates every buffer the updates use. The fields are those of t = 0.
    ///
    /// # Errors
    /// Those of [`CascadeConfig::validate`]; [`Error::EmptyBand`] if the band holds no wave
    /// vector of the grid; [`Error::AmplitudeTooLarge`] if the spectrum is so strong at this
    /// grid and choppiness that the fields could overflow f32; [`Error::OutOfMemory`] if the
    /// system refuses an allocation.
    pub fn new(spectrum: &Spectrum, config: CascadeConfig) -> Result<Cascade, Error> {
        config.validate()?;
        let n = config.size;
        let dk64 = TAU / f64::from(config.length);
        let dk = dk64 as f32;
        let Amplitudes {
            h0,
            expected_variance,
            amplitude_bound,
        } = Amplitudes::draw(spectrum, &config)?;
        check_amplitude(amplitude_bound, config.choppiness)?;
        let looping = config.repeat_period.map(f64::from);
        let evolution = EvolutionTable::new(&h0, n, dk64, spectrum.dispersion(), looping);
        let loop_error =
            looping.map(|period| LoopError::new(&h0, n, dk64, spectrum.dispersion(), period));
        let kz = (0..n).map(|j| wave_index(j, n) as f32 * dk).collect();
        let rows = RowFft::new(n);
        let points = n * n;
        let mut cascade = Cascade {
            config,
            n,
            dk,
            time: 0.0,
            expected_variance,
            amplitude_bound,
            loop_error,
            h0,
            evolution,
            kz,
            spectral: error::try_vec(TRANSFORMS * points, Complex32::default())?,
            spatial: error::try_vec(TRANSFORMS * points, Complex32::default())?,
            scratch: error::try_vec(tasks(n) * rows.scratch_len(), Complex32::default())?,
            rows,
            height: error::try_vec(points, 0.0)?,
            displacement: error::try_vec(points, [0.0; 2])?,
            slope: error::try_vec(points, [0.0; 2])?,
            normal: error::try_vec(points, [0.0, 1.0, 0.0])?,
            jacobian: error::try_vec(points, 1.0)?,
        };
        cascade.update(0.0)?;
        Ok(cascade)
    }

    /// Evolves the spectrum to time `t` (seconds, f64; any t with
    /// |t| ≤ [`MAX_TIME`](Self::MAX_TIME)) and recomputes every output buffer. Allocates
    /// nothing inside a rayon pool; the result does not depend on the number of threads.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for `t`; the buffers are left as they
    /// were.
    pub fn update(&mut self, t: f64) -> Result<(), Error> {
        check_time("t", t)?;
        self.update_checked(t);
        Ok(())
    }

    /// [`Cascade::update`] for a time already checked with [`check_time`].
    pub(crate) fn update_checked(&mut self, t: f64) {
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
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for a negative or non-finite
    /// `choppiness`; [`Error::AmplitudeTooLarge`] if the fields could overflow f32 at this
    /// choppiness. The choppiness is then unchanged.
    pub fn set_choppiness(&mut self, choppiness: f32) -> Result<(), Error> {
        let lambda = self.check_choppiness(choppiness)?;
        self.set_choppiness_checked(lambda);
        Ok(())
    }

    /// Sets a choppiness [`Cascade::check_choppiness`] accepted.
    pub(crate) fn set_choppiness_checked(&mut self, choppiness: f32) {
        self.config.choppiness = choppiness;
    }

    /// The checks of [`Cascade::set_choppiness`] without the change.
    pub(crate) fn check_choppiness(&self, choppiness: f32) -> Result<f32, Error> {
        let lambda = error::non_negative("choppiness", choppiness)?;
        check_amplitude(self.amplitude_bound, lambda)?;
        Ok(lambda)
    }

    /// How far the repeat period moved the waves' frequencies from the dispersion relation
    /// (`None` without one): every ω becomes the nearest whole number of cycles per loop, at
    /// least one, so waves longer than the loop speed up and none stands still.
    pub fn loop_error(&self) -> Option<LoopError> {
        self.loop_error
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

    /// Horizontal displacement λ·(D_x, D_z) in metres, as `[x, z]`: grid point x₀ moves to
    /// x₀ + this.
    pub fn displacement(&self) -> &[[f32; 2]] {
        &self.displacement
    }

    /// Slope (∂y/∂x, ∂y/∂z) of the displaced surface at each grid point's displaced position,
    /// (−n_x/n_y, −n_z/n_y) as `[x, z]`, dimensionless. n_y = J is kept at least 1e-4·|n|, so
    /// where the surface is vertical or folds (J ≤ 0) the slope stays finite (magnitude
    /// ≤ 1e4).
    pub fn slope(&self) -> &[[f32; 2]] {
        &self.slope
    }

    /// Unit normal of the displaced surface, (T_z × T_x)/|T_z × T_x|; it points down where
    /// the surface folds over itself (J < 0). `[x, y, z]`, y up.
    pub fn normal(&self) -> &[[f32; 3]] {
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
}
