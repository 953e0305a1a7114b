//! One N×N patch of ocean: h0(k) made once, h̃(k, t) evolved and turned into eight real
//! fields by four packed complex inverse FFTs on every [`Cascade::update`].

mod config;
mod evolve;
mod field;
mod inspect;
mod outputs;
mod tables;
#[cfg(test)]
mod tests;

use std::f64::consts::TAU;
use std::ops::Bound::Included;

use num_complex::Complex32;
use rayon::prelude::*;

use crate::determinism::{Determinism, Libm, Math, Std};
use crate::error::{self, Error};
use crate::fft2d::{transpose_into, RowFft, ROWS_PER_TASK, TILE};
use crate::grid::{self, wave_index};
use crate::simd::Simd;
use crate::spectrum::{SlopeVariance, Spectrum};

pub(crate) use config::check_band;
pub use config::CascadeConfig;
pub use field::Field;

use evolve::{
    column_blocks, evolve_row_pair, fract_turns, packed_pair, zero_blocks, EvolveBuffers,
};
use outputs::{write_gradient, write_outputs, NormalBuffers};
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
/// `Clone` copies every table and buffer ([`CascadeConfig::memory_bytes`], about 123·N²
/// bytes): the copy updates to the same bits as the original.
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
    /// 2 Σ |k| |h0(k)|² in m: the mean-level correction per unit choppiness.
    mean_level: f64,
    /// The correction in m the buffers were last computed with (λ · `mean_level`).
    mean_level_offset: f32,
    /// Slope variance the spectrum holds above this cascade's band (to the cut-off).
    subgrid_slope: SlopeVariance,
    h0: Vec<Complex32>,
    /// Evolution table, transposed layout: rows are k_x index i in 0..N/2, columns k_z
    /// index j.
    evolution: EvolutionTable,
    /// k_z = Δk·m(j) of spectral column j.
    kz: Vec<f32>,
    rows: RowFft,
    /// The SIMD level of the element loops (the widest the CPU has; the tests force each).
    simd: Simd,
    tasks: Tasks,
    /// Band pruning, per table row i in 0..N/2: which evolution blocks hold no wave.
    pruning: Vec<RowPruning>,
    /// Row pairs 1..=`live_pairs` are evolved and transformed; the pairs beyond hold no wave
    /// (p = q = 0 in their whole table row), so their spectral rows stay zero from
    /// construction on and pass 2 writes zeros for them without reading them.
    live_pairs: usize,
    /// Pass-1 buffer, layout `[i][transform][j]` (k_x row, k_z column → after the FFT, z).
    spectral: Vec<Complex32>,
    /// Pass-2 block buffers, one per pass-2 task, each [`ROWS_PER_TASK`] rows of layout
    /// `[j][transform][i]` (z row, x column) once transformed.
    blocks: Vec<Complex32>,
    /// FFT scratch, one slot per task of the pass running (the passes run one after the
    /// other and share it).
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

/// Values between the starts of two rows of the pass-1 buffer and of a pass-2 block: the
/// row's four transforms and one cache line of padding. Without it rows lie a power of two
/// of bytes apart (32·N), so the lines a transpose tile reads or writes at once, one per
/// row, all fall into the same cache set and evict each other.
pub(crate) fn row_stride(n: usize) -> usize {
    (TRANSFORMS * n).saturating_add(TILE)
}

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
pub(crate) fn memory_bytes(n: usize, determinism: Determinism) -> usize {
    let points = n.saturating_mul(n);
    let complex = std::mem::size_of::<Complex32>();
    let scratch_len = if n <= grid::MAX_SIZE {
        RowFft::new(n, determinism).scratch_len()
    } else {
        n
    };
    let tasks = Tasks::new(n);
    let per_point = [
        complex,            // h0
        4 + 2 * 8 + 12 + 4, // height, displacement, slope, normal, jacobian
    ];
    let spectral = n.saturating_mul(row_stride(n)).saturating_mul(complex);
    let evolution_entry = 4 * 4 + 8 + 4; // p, q, freq, 1/|k|, for half the points
    let pruning = std::mem::size_of::<RowPruning>();
    let tables = (points / 2)
        .saturating_mul(evolution_entry)
        .saturating_add(n.saturating_mul(4 + pruning));
    let scratch = tasks
        .scratch_slots()
        .saturating_mul(scratch_len)
        .saturating_mul(complex);
    let blocks = tasks.block_values(n).saturating_mul(complex);
    per_point.iter().fold(
        tables
            .saturating_add(scratch)
            .saturating_add(blocks)
            .saturating_add(spectral),
        |sum, &bytes| sum.saturating_add(points.saturating_mul(bytes)),
    )
}

/// Most parallel tasks of each pass. Every task owns an FFT scratch slot (and in pass 2 a
/// block buffer of [`ROWS_PER_TASK`] rows, which it works through its z rows with), so this
/// bounds those buffers: up to N = 512 each pass-2 task still handles one block, as before;
/// at 1024² pass 2 holds 32 blocks (17 MB) instead of the whole grid (34 MB), at 4096² 67 MB
/// instead of 537 MB. 32 tasks still balance the load over as many threads.
const MAX_TASKS: usize = 32;

/// Parallel tasks a pass runs on a pool of `threads` threads (fewer when it has less work;
/// see [`Tasks::pass2_blocks_per_task`]).
fn tasks_for(threads: usize) -> usize {
    if threads <= 1 {
        1
    } else {
        threads.saturating_mul(4)
    }
}

/// How one update's work is split into parallel tasks.
#[derive(Debug, Clone, Copy)]
struct Tasks {
    /// Row pairs (k_x and −k_x) each pass-1 task evolves and transforms.
    pairs_per_task: usize,
    /// Pass-1 tasks for the whole band (a pruned band runs fewer).
    pass1: usize,
    /// Blocks of [`ROWS_PER_TASK`] z rows each pass-2 task gathers, transforms and writes
    /// out, one after the other through its block buffer.
    blocks_per_task: usize,
    /// Pass-2 tasks at most (and block buffers).
    pass2: usize,
    /// Blocks of [`ROWS_PER_TASK`] z rows in the grid.
    blocks: usize,
}

impl Tasks {
    fn new(n: usize) -> Self {
        let pairs = (n / 2).saturating_sub(1).max(1);
        let pairs_per_task = pairs.div_ceil(MAX_TASKS);
        let blocks = n.div_ceil(ROWS_PER_TASK).max(1);
        let blocks_per_task = blocks.div_ceil(MAX_TASKS);
        Tasks {
            pairs_per_task,
            pass1: pairs.div_ceil(pairs_per_task),
            blocks_per_task,
            pass2: blocks.div_ceil(blocks_per_task),
            blocks,
        }
    }

    /// Row pairs each pass-1 task evolves and transforms when `pairs` row pairs are live and
    /// the pool has `threads` threads: as many tasks as
    /// [`pass2_blocks_per_task`](Self::pass2_blocks_per_task) gives pass 2, for the same
    /// reasons (and on one thread, each further task is a split and a call that buys
    /// nothing), never more than FFT scratch slots.
    fn pass1_pairs_per_task(&self, pairs: usize, threads: usize) -> usize {
        let tasks = tasks_for(threads).min(self.pass1);
        pairs.div_ceil(tasks).max(self.pairs_per_task)
    }

    /// Blocks each pass-2 task works through when the pool has `threads` threads: one task
    /// for one thread, four per thread otherwise (enough for the work stealing to even out a
    /// thread that other work on the machine holds up), and never more tasks than block
    /// buffers. Every block is computed alike whichever task does it, so the result does not
    /// depend on this; what it changes is how many block buffers an update touches, and so
    /// how much of the cache they take from the cascade's other buffers (at 256², 16 buffers
    /// are as large as the pass-1 buffer).
    fn pass2_blocks_per_task(&self, threads: usize) -> usize {
        let blocks = self.blocks;
        let tasks = tasks_for(threads);
        blocks
            .div_ceil(tasks.min(self.pass2))
            .max(self.blocks_per_task)
    }

    /// FFT scratch slots: pass 1 (row 0 beside the row-pair tasks) and pass 2 run one after
    /// the other, so they share.
    fn scratch_slots(&self) -> usize {
        (self.pass1 + 1).max(self.pass2)
    }

    /// Values of all pass-2 block buffers of an N grid.
    fn block_values(&self, n: usize) -> usize {
        self.pass2
            .saturating_mul(ROWS_PER_TASK)
            .saturating_mul(row_stride(n))
    }
}

/// Band pruning of one evolution-table row (one row pair of the spectrum).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct RowPruning {
    /// Bit b set: block b of the row's columns holds no wave (see [`evolve::zero_blocks`]).
    zero_blocks: u64,
    /// The whole row holds no wave (every block and column 0).
    empty: bool,
}

impl RowPruning {
    /// The pruning of every table row of an N grid.
    fn of(evolution: &EvolutionTable, n: usize) -> Vec<RowPruning> {
        let blocks = column_blocks(n).count();
        let all = if blocks == 64 {
            u64::MAX
        } else {
            (1u64 << blocks) - 1
        };
        (0..n / 2)
            .map(|i| {
                let row = evolution.get_row(i, n);
                let zero_blocks = zero_blocks(row);
                let column0 = row.p_re[0] == 0.0
                    && row.p_im[0] == 0.0
                    && row.q_re[0] == 0.0
                    && row.q_im[0] == 0.0;
                RowPruning {
                    zero_blocks,
                    empty: column0 && zero_blocks == all,
                }
            })
            .collect()
    }
}

/// 2 Σ_k |k| |h0(k)|² in m over the grid's wave vectors (h0 in FFT order, index j·N + i at
/// k = Δk·(m(i), m(j))): the time-averaged Σ_k |k| |h̃(k, t)|², since |h̃(k)|² averages to
/// |h0(k)|² + |h0(−k)|².
fn mean_level_per_choppiness<M: Math>(h0: &[Complex32], n: usize, dk: f64) -> f64 {
    let mut sum = 0.0;
    for j in 0..n {
        let kz = f64::from(wave_index(j, n)) * dk;
        for i in 0..n {
            let kx = f64::from(wave_index(i, n)) * dk;
            let h = h0[j * n + i];
            // In f64: |h0|² of an extreme (but accepted) spectrum can overflow f32, while
            // λ Σ|k||h0|² stays below the square of the amplitude bound (≤ 1e30).
            let (re, im) = (f64::from(h.re), f64::from(h.im));
            sum += M::hypot(kx, kz) * (re * re + im * im);
        }
    }
    2.0 * sum
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
        match config.determinism {
            Determinism::SameMachine => Self::new_with::<Std>(spectrum, config),
            Determinism::CrossPlatform => Self::new_with::<Libm>(spectrum, config),
        }
    }

    /// [`Cascade::new`] for a checked config, with the functions of its determinism mode.
    fn new_with<M: Math>(spectrum: &Spectrum, config: CascadeConfig) -> Result<Cascade, Error> {
        let n = config.size;
        let dk64 = TAU / f64::from(config.length);
        let dk = dk64 as f32;
        let Amplitudes {
            h0,
            expected_variance,
            amplitude_bound,
        } = Amplitudes::draw::<M>(spectrum, &config)?;
        check_amplitude(amplitude_bound, config.choppiness)?;
        let looping = config.repeat_period.map(f64::from);
        let evolution = EvolutionTable::new::<M>(&h0, n, dk64, spectrum.dispersion(), looping);
        let loop_error =
            looping.map(|period| LoopError::new::<M>(&h0, n, dk64, spectrum.dispersion(), period));
        let kz = (0..n).map(|j| wave_index(j, n) as f32 * dk).collect();
        let mean_level = mean_level_per_choppiness::<M>(&h0, n, dk64);
        let nyquist = std::f64::consts::PI * n as f64 / f64::from(config.length);
        let band_top = f64::from(config.k_max).min(nyquist);
        let subgrid_slope =
            spectrum.slope_variance_with::<M>(band_top, f64::from(SlopeVariance::DEFAULT_CUTOFF));
        let rows = RowFft::new(n, config.determinism);
        let tasks = Tasks::new(n);
        let pruning = RowPruning::of(&evolution, n);
        let live_pairs = (1..n / 2).rev().find(|&i| !pruning[i].empty).unwrap_or(0);
        let points = n * n;
        let mut cascade = Cascade {
            config,
            n,
            dk,
            time: 0.0,
            expected_variance,
            amplitude_bound,
            loop_error,
            mean_level,
            mean_level_offset: 0.0,
            subgrid_slope,
            h0,
            evolution,
            kz,
            spectral: error::try_vec(n * row_stride(n), Complex32::default())?,
            blocks: error::try_vec(tasks.block_values(n), Complex32::default())?,
            scratch: error::try_vec(
                tasks.scratch_slots() * rows.scratch_len(),
                Complex32::default(),
            )?,
            rows,
            simd: Simd::detect(),
            tasks,
            pruning,
            live_pairs,
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
        self.update_checked(t, &mut []);
        Ok(())
    }

    /// [`Cascade::update`] for a time already checked with [`check_time`]; a `gradient` of N²
    /// points also receives the displacement gradient `[D_xx, D_zz, D_xz]` at unit choppiness
    /// of every grid point (what the foam reads), an empty one nothing.
    pub(crate) fn update_checked(&mut self, t: f64, gradient: &mut [[f32; 3]]) {
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
            self.spatial_pass(gradient);
        });
    }

    /// Pass 1: builds the four packed spectra row by row (rows are k_x, so a row and its
    /// Hermitian partner −k are rows i and N − i) and transforms each row along k_z while it
    /// is in cache. Only row 0 and the row pairs 1..=`live_pairs` are touched: the rows
    /// beyond hold no wave and stay zero (as does the Nyquist row N/2), and empty pairs in
    /// between are skipped. For the default ocean's two larger cascades, whose band stops at
    /// half their Nyquist wave number, that skips half the row pairs.
    fn spectral_pass(&mut self, t: f64) {
        let n = self.n;
        let half = n / 2;
        let row_len = TRANSFORMS * n;
        let stride = row_stride(n);
        let dk = self.dk;
        let evolution = &self.evolution;
        let pruning = &self.pruning;
        let rows = &self.rows;
        let s = rows.scratch_len();
        let pairs = self.live_pairs;
        let per_task = self
            .tasks
            .pass1_pairs_per_task(pairs, rayon::current_num_threads());
        let simd = self.simd;

        // Rows 1..=pairs, and their partners N − pairs..N − 1.
        let (row0, rest) = self.spectral.split_at_mut(stride);
        let row0 = &mut row0[..row_len];
        let (top, rest) = rest.split_at_mut(pairs * stride);
        let bottom = &mut rest[(n - 1 - 2 * pairs) * stride..];
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
            },
            || {
                // Each task: `per_task` consecutive row pairs, the upper rows in order and
                // their partners (from the end of the buffer) in reverse.
                top.par_chunks_mut(per_task * stride)
                    .zip(bottom.par_rchunks_mut(per_task * stride))
                    .zip(scratch_pairs.par_chunks_mut(s))
                    .enumerate()
                    .for_each(|(task, ((uppers, lowers), scratch))| {
                        let count = uppers.len() / stride;
                        let mut buffers = EvolveBuffers::new();
                        for m in 0..count {
                            let i = task * per_task + m + 1;
                            if pruning[i].empty {
                                continue;
                            }
                            let upper = &mut uppers[m * stride..][..row_len];
                            let lower = &mut lowers[(count - 1 - m) * stride..][..row_len];
                            let kx = i as f32 * dk;
                            let table = evolution.get_row(i, n);
                            let zero = pruning[i].zero_blocks;
                            simd.run(
                                #[inline(always)]
                                || {
                                    evolve_row_pair(
                                        &mut buffers,
                                        table,
                                        zero,
                                        kx,
                                        kz,
                                        t,
                                        upper,
                                        lower,
                                    )
                                },
                            );
                            rows.process(upper, scratch);
                            rows.process(lower, scratch);
                        }
                    });
            },
        );
    }

    /// The columns i of a pass-2 block that hold no wave: the spectral rows beyond the live
    /// row pairs (and the Nyquist row), shrunk to whole [`TILE`]s so that the transpose
    /// around them keeps its full tiles. Empty when the band reaches the Nyquist wave number.
    fn zero_columns(&self) -> std::ops::Range<usize> {
        let n = self.n;
        let start = (self.live_pairs + 1).next_multiple_of(TILE);
        let end = (n - self.live_pairs) / TILE * TILE;
        if start < end {
            start..end
        } else {
            n..n
        }
    }

    /// Pass 2: gathers blocks of z rows from the pass-1 buffer (a blocked transpose),
    /// transforms them along x and turns the four packed results into the output buffers.
    /// Each task works through its share of blocks with one block buffer. A non-empty
    /// `gradient` (N² points) receives the displacement gradient too.
    fn spatial_pass(&mut self, gradient_out: &mut [[f32; 3]]) {
        let n = self.n;
        let row_len = TRANSFORMS * n;
        let stride = row_stride(n);
        let lambda = self.config.choppiness;
        let offset = (f64::from(lambda) * self.mean_level) as f32;
        self.mean_level_offset = offset;
        let spectral = &self.spectral;
        let rows = &self.rows;
        let s = rows.scratch_len();
        let zero = self.zero_columns();
        let simd = self.simd;
        let rows_per_task = self
            .tasks
            .pass2_blocks_per_task(rayon::current_num_threads())
            * ROWS_PER_TASK;
        let out = rows_per_task * n;
        // Each task's share of the gradient, or an empty slice for every task where none is
        // asked for (on the stack: the update allocates nothing).
        let mut gradient: [&mut [[f32; 3]]; MAX_TASKS] = Default::default();
        for (slot, chunk) in gradient.iter_mut().zip(gradient_out.chunks_mut(out)) {
            *slot = chunk;
        }
        (
            self.blocks.par_chunks_mut(ROWS_PER_TASK * stride),
            self.scratch.par_chunks_mut(s),
            self.height.par_chunks_mut(out),
            self.displacement.par_chunks_mut(out),
            self.slope.par_chunks_mut(out),
            self.normal.par_chunks_mut(out),
            self.jacobian.par_chunks_mut(out),
            gradient.par_iter_mut(),
        )
            .into_par_iter()
            .enumerate()
            .for_each(
                |(
                    task,
                    (block, scratch, height, displacement, slope, normal, jacobian, gradient),
                )| {
                    let task_rows = height.len() / n;
                    let mut normals = NormalBuffers::new();
                    for r0 in (0..task_rows).step_by(ROWS_PER_TASK) {
                        let count = ROWS_PER_TASK.min(task_rows - r0);
                        let j0 = task * rows_per_task + r0;
                        gather(spectral, n, j0, count, zero.clone(), block);
                        for row in block.chunks_exact_mut(stride).take(count) {
                            rows.process(&mut row[..row_len], scratch);
                        }
                        simd.run(
                            #[inline(always)]
                            || {
                                for r in 0..count {
                                    let row = &block[r * stride..][..row_len];
                                    let out = (r0 + r) * n..(r0 + r + 1) * n;
                                    write_outputs(
                                        &mut normals,
                                        row,
                                        n,
                                        lambda,
                                        offset,
                                        &mut height[out.clone()],
                                        &mut displacement[out.clone()],
                                        &mut slope[out.clone()],
                                        &mut normal[out.clone()],
                                        &mut jacobian[out.clone()],
                                    );
                                    if !gradient.is_empty() {
                                        write_gradient(row, n, &mut gradient[out]);
                                    }
                                }
                            },
                        );
                    }
                },
            );
    }

    /// Writes the displacement gradient of the current time into `gradient` (N² points) by
    /// running pass 2 again: the pass-1 buffer still holds this time's transforms, so the
    /// output buffers get the same bits again.
    pub(crate) fn fill_gradient(&mut self, gradient: &mut [[f32; 3]]) {
        rayon::scope(|_| self.spatial_pass(gradient));
    }

    /// Runs the element loops at `simd` from now on (the tests force every level).
    #[cfg(test)]
    pub(crate) fn set_simd(&mut self, simd: Simd) {
        self.simd = simd;
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

    /// The mean-level correction in metres that the last update added to every height:
    /// λ · 2 Σ_k |k| |h0(k)|², the time average of λ Σ_k |k| |h̃(k, t)|².
    ///
    /// Horizontal displacement moves water toward the crests (J < 1 there), so without it
    /// the Eulerian mean of the displaced surface, the mean of η·J over the undisplaced grid,
    /// would sit λ ∫ k S(k) d²k below still water (Nouguier, Guérin & Chapron 2009; the
    /// mean-level term of Guérin et al.'s 2019 improved choppy wave model): to first order
    /// ⟨η J⟩ = λ⟨η ∇·D⟩ = −λ Σ_k |k| |h̃(k)|², and the second-order term of J adds a third
    /// moment of a Gaussian field, zero on average. Adding this constant to η puts the
    /// mean water level back at y = 0 for any λ; it is 0 at λ = 0. The height buffer, the
    /// texels and vertices packed from it and every world query include it. See
    /// docs/theory.md.
    pub fn mean_level_offset(&self) -> f32 {
        self.mean_level_offset
    }

    /// Slope variance along and across the wind that the spectrum holds between the top of
    /// this cascade's band (min(`k_max`, πN/L)) and [`SlopeVariance::DEFAULT_CUTOFF`]: the
    /// slopes too short for this grid, computed once at construction by
    /// [`Spectrum::slope_variance`]. A renderer that draws this cascade and the larger ones
    /// adds it as BRDF roughness; it is the alpha channel of
    /// [`TexelLayout::Normal`](crate::TexelLayout::Normal).
    pub fn subgrid_slope_variance(&self) -> SlopeVariance {
        self.subgrid_slope
    }

    /// Height η in metres at every grid point (undisplaced positions), including the
    /// [mean-level correction](Self::mean_level_offset).
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

/// `block[r][f][i] = spectral[i][f][j0 + r]` for the `count` z rows r of a block: a tiled
/// transpose per transform (the pass-2 gather), with zeros written for the columns i in
/// `zero` instead of reading spectral rows that hold no wave. With the default ocean's band
/// split, the two larger cascades skip reading half their rows (the gather is a fifth to a
/// third of an update).
fn gather(
    spectral: &[Complex32],
    n: usize,
    j0: usize,
    count: usize,
    zero: std::ops::Range<usize>,
    block: &mut [Complex32],
) {
    let stride = row_stride(n);
    for f in 0..TRANSFORMS {
        let src = &spectral[f * n + j0..];
        let dst = &mut block[f * n..];
        transpose_into(src, stride, dst, stride, count, zero.start);
        if zero.end < n {
            let (src, dst) = (&src[zero.end * stride..], &mut dst[zero.end..]);
            transpose_into(src, stride, dst, stride, count, n - zero.end);
        }
        if !zero.is_empty() {
            for r in 0..count {
                dst[r * stride + zero.start..r * stride + zero.end].fill(Complex32::default());
            }
        }
    }
}
