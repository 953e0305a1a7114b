//! The update: pass 1 evolves h̃(k, t) row pair by row pair and transforms along k_z; pass 2
//! gathers blocks of rows, transforms them along x and writes the output buffers.

use num_complex::Complex32;
use rayon::prelude::*;

use super::evolve::{
    column_blocks, evolve_row_pair, fract_turns, packed_pair, zero_blocks, EvolveBuffers,
};
use super::outputs::{write_gradient, write_outputs, NormalBuffers};
use super::second_order::{self, SecondOrder};
use super::tables::EvolutionTable;
use super::{check_time, row_stride, Cascade, TRANSFORMS};
use crate::error::Error;
use crate::math::fft2d::{transpose_into, ROWS_PER_TASK, TILE};
#[cfg(test)]
use crate::math::simd::Simd;

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
pub(super) struct Tasks {
    /// Row pairs (k_x and −k_x) each pass-1 task evolves and transforms.
    pub(super) pairs_per_task: usize,
    /// Pass-1 tasks for the whole band (a pruned band runs fewer).
    pub(super) pass1: usize,
    /// Blocks of [`ROWS_PER_TASK`] z rows each pass-2 task gathers, transforms and writes
    /// out, one after the other through its block buffer.
    pub(super) blocks_per_task: usize,
    /// Pass-2 tasks at most (and block buffers).
    pub(super) pass2: usize,
    /// Blocks of [`ROWS_PER_TASK`] z rows in the grid.
    pub(super) blocks: usize,
}

impl Tasks {
    pub(super) fn new(n: usize) -> Self {
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
    pub(super) fn scratch_slots(&self) -> usize {
        (self.pass1 + 1).max(self.pass2)
    }

    /// Values of all pass-2 block buffers of an N grid.
    pub(super) fn block_values(&self, n: usize) -> usize {
        self.pass2
            .saturating_mul(ROWS_PER_TASK)
            .saturating_mul(row_stride(n))
    }
}

/// Band pruning of one evolution-table row (one row pair of the spectrum).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct RowPruning {
    /// Bit b set: block b of the row's columns holds no wave (see [`zero_blocks`]).
    pub(super) zero_blocks: u64,
    /// The whole row holds no wave (every block and column 0).
    pub(super) empty: bool,
}

impl RowPruning {
    /// The pruning of every table row of an N grid.
    pub(super) fn of(evolution: &EvolutionTable, n: usize) -> Vec<RowPruning> {
        (0..n / 2).map(|i| Self::of_row(evolution, i, n)).collect()
    }

    /// The pruning of table row `i` of an N grid.
    pub(super) fn of_row(evolution: &EvolutionTable, i: usize, n: usize) -> RowPruning {
        let blocks = column_blocks(n).count();
        let all = if blocks == 64 {
            u64::MAX
        } else {
            (1u64 << blocks) - 1
        };
        let row = evolution.get_row(i, n);
        let zero_blocks = zero_blocks(row);
        let column0 =
            row.p_re[0] == 0.0 && row.p_im[0] == 0.0 && row.q_re[0] == 0.0 && row.q_im[0] == 0.0;
        RowPruning {
            zero_blocks,
            empty: column0 && zero_blocks == all,
        }
    }
}

impl Cascade {
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
            if let Some(second) = self.second_order.as_deref_mut() {
                second.compute(&self.evolution, phase_time);
            }
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
        let second = self.second_order.as_deref();
        // Rows up to this one may receive second-order terms, so are never skipped.
        let second_top = second.map_or(0, SecondOrder::top_row);

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
                if let Some(second) = second {
                    second_order::add_to_row0(second.row(0), kz, row0);
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
                            if pruning[i].empty && i > second_top {
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
                            if let Some(second) = second.filter(|_| i <= second_top) {
                                second_order::add_to_row_pair(second.row(i), kx, kz, upper, lower);
                            }
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
