//! Batched complex 2D inverse FFTs on the CPU: one rustfft plan, scratch made once per task,
//! rows in parallel with rayon and a cache-blocked parallel transpose between the passes.
//!
//! The building blocks ([`RowFft`], [`transpose_into`]) are shared with the cascade, which
//! fuses them with its own spectral and output passes; [`Fft2d`] strings them together plainly
//! and is the speed baseline the benches compare a cascade update with.

use std::sync::Arc;

use num_complex::Complex32;
use rayon::prelude::*;
use rustfft::{Fft, FftPlanner, FftPlannerScalar};

use crate::error::{self, Error};
use crate::math::determinism::Determinism;
use crate::math::grid;

/// Rows handled by one parallel task of the second pass (the rows a task gathers by a
/// transpose and transforms). 16 rows of a 512-point complex transform are 64 KiB (256 KiB
/// for a cascade's four packed transforms): they stay in a core's L2 cache while they are
/// worked on, and a 512² grid still gives 32 tasks to balance over the threads.
pub(crate) const ROWS_PER_TASK: usize = 16;

/// An inverse complex FFT of length N applied to many rows, with scratch for a fixed number
/// of tasks allocated once.
#[derive(Clone)]
pub(crate) struct RowFft {
    fft: Arc<dyn Fft<f32>>,
    scratch_len: usize,
}

impl RowFft {
    /// The inverse FFT of length `n`: rustfft's fastest kernels for this CPU
    /// ([`Determinism::SameMachine`]) or its scalar planner's, the same code on every CPU
    /// ([`Determinism::CrossPlatform`]; see [`Determinism`] for why that is enough).
    pub(crate) fn new(n: usize, determinism: Determinism) -> Self {
        let fft = match determinism {
            Determinism::SameMachine => FftPlanner::<f32>::new().plan_fft_inverse(n),
            Determinism::CrossPlatform => FftPlannerScalar::<f32>::new().plan_fft_inverse(n),
        };
        Self::from_plan(fft)
    }

    /// The forward FFT of length `n` (the planner as in [`RowFft::new`]): the second-order
    /// waves transform products of fields back to wave vectors.
    pub(crate) fn new_forward(n: usize, determinism: Determinism) -> Self {
        let fft = match determinism {
            Determinism::SameMachine => FftPlanner::<f32>::new().plan_fft_forward(n),
            Determinism::CrossPlatform => FftPlannerScalar::<f32>::new().plan_fft_forward(n),
        };
        Self::from_plan(fft)
    }

    fn from_plan(fft: Arc<dyn Fft<f32>>) -> Self {
        // `par_chunks_mut` needs a non-zero chunk length.
        let scratch_len = fft.get_inplace_scratch_len().max(1);
        RowFft { fft, scratch_len }
    }

    /// Scratch length one task needs.
    pub(crate) fn scratch_len(&self) -> usize {
        self.scratch_len
    }

    /// Transforms `rows` (a whole number of length-N rows) in place.
    pub(crate) fn process(&self, rows: &mut [Complex32], scratch: &mut [Complex32]) {
        self.fft
            .process_with_scratch(rows, &mut scratch[..self.scratch_len]);
    }
}

impl std::fmt::Debug for RowFft {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RowFft")
            .field("len", &self.fft.len())
            .field("scratch_len", &self.scratch_len)
            .finish()
    }
}

/// Side of the square tiles [`transpose_into`] moves at once: 8 complex values are one 64-byte
/// cache line.
pub(crate) const TILE: usize = 8;

/// `dst[r * dst_stride + c] = src[c * src_stride + r]` for `r < rows`, `c < cols`.
///
/// Works in [`TILE`]×[`TILE`] tiles: a tile's source rows are read and its destination rows
/// written a whole cache line at a time, so the few lines in flight stay in L1 even when
/// the strides are powers of two (a column-at-a-time copy with a 4 KiB stride keeps missing
/// L1 as all its lines fall into the same cache set; at N = 128 that made the transpose cost
/// three times the row FFTs).
pub(crate) fn transpose_into(
    src: &[Complex32],
    src_stride: usize,
    dst: &mut [Complex32],
    dst_stride: usize,
    rows: usize,
    cols: usize,
) {
    for c0 in (0..cols).step_by(TILE) {
        let width = TILE.min(cols - c0);
        for r0 in (0..rows).step_by(TILE) {
            let height = TILE.min(rows - r0);
            if width == TILE && height == TILE {
                let lines: [&[Complex32; TILE]; TILE] = std::array::from_fn(|k| {
                    let start = (c0 + k) * src_stride + r0;
                    src[start..start + TILE].try_into().expect("TILE values")
                });
                for r in 0..TILE {
                    let out = &mut dst[(r0 + r) * dst_stride + c0..][..TILE];
                    for (value, line) in out.iter_mut().zip(&lines) {
                        *value = line[r];
                    }
                }
            } else {
                for c in c0..c0 + width {
                    for r in r0..r0 + height {
                        dst[r * dst_stride + c] = src[c * src_stride + r];
                    }
                }
            }
        }
    }
}

/// `count` unnormalised inverse complex 2D FFTs of N×N arrays, done the way a cascade does
/// its transforms: the rows of all arrays in parallel, then, in parallel blocks of 16 rows, a
/// tiled transpose of the block and its rows again while in cache. Plans, scratch and the
/// intermediate buffer are made once in [`Fft2d::new`]; [`Fft2d::process`] allocates nothing.
///
/// The result is left **transposed** (`result[a][x][z]` for input `[a][k_z][k_x]`), as in the
/// cascade, which lays its spectra out so that no transpose back is needed.
///
/// ```
/// use ocean_fft::inspect::{Complex32, Fft2d};
/// let mut fft = Fft2d::new(8, 1)?;
/// let mut data = vec![Complex32::new(0.0, 0.0); 64];
/// data[0] = Complex32::new(1.0, 0.0);
/// let out = fft.process(&mut data)?;
/// assert!(out.iter().all(|c| (c.re - 1.0).abs() < 1e-6 && c.im.abs() < 1e-6));
/// # Ok::<(), ocean_fft::Error>(())
/// ```
#[derive(Debug)]
pub struct Fft2d {
    n: usize,
    count: usize,
    rows: RowFft,
    scratch: Vec<Complex32>,
    transposed: Vec<Complex32>,
}

impl Fft2d {
    /// Most arrays one `Fft2d` transforms at once.
    pub const MAX_COUNT: usize = 64;

    /// Most bytes an `Fft2d` may hold (its intermediate buffer, plans and scratch): 4 GiB, as
    /// the default limit of a cascade.
    pub const MEMORY_LIMIT: usize = grid::DEFAULT_MEMORY_LIMIT;

    /// Plans `count` transforms of N×N arrays, N = `size` (even,
    /// [`CascadeConfig::MIN_SIZE`] ≤ N ≤ [`CascadeConfig::MAX_SIZE`]).
    ///
    /// [`CascadeConfig::MIN_SIZE`]: crate::CascadeConfig::MIN_SIZE
    /// [`CascadeConfig::MAX_SIZE`]: crate::CascadeConfig::MAX_SIZE
    ///
    /// # Errors
    /// [`Error::InvalidSize`] for `size`; [`Error::CountOutOfRange`] unless
    /// 1 ≤ `count` ≤ [`MAX_COUNT`](Self::MAX_COUNT); [`Error::MemoryLimit`] if it would hold
    /// more than [`MEMORY_LIMIT`](Self::MEMORY_LIMIT) bytes; [`Error::OutOfMemory`] if the
    /// system refuses an allocation.
    pub fn new(size: usize, count: usize) -> Result<Self, Error> {
        Self::with_determinism(size, count, Determinism::SameMachine)
    }

    /// [`Fft2d::new`] with the FFT code path of a [`Determinism`] mode:
    /// [`Determinism::CrossPlatform`] runs the same scalar kernels on every CPU, so the
    /// results are the same bits everywhere (and slower where the CPU has SIMD).
    ///
    /// # Errors
    /// Those of [`Fft2d::new`].
    pub fn with_determinism(
        size: usize,
        count: usize,
        determinism: Determinism,
    ) -> Result<Self, Error> {
        grid::check_size("size", size)?;
        if !(1..=Self::MAX_COUNT).contains(&count) {
            return Err(Error::CountOutOfRange {
                name: "count",
                count,
                min: 1,
                max: Self::MAX_COUNT,
            });
        }
        let rows = RowFft::new(size, determinism);
        // The first pass runs (count·N)/ROWS_PER_TASK tasks, the second count·⌈N/ROWS_PER_TASK⌉.
        let tasks = count * size.div_ceil(ROWS_PER_TASK);
        let scratch_len = tasks * rows.scratch_len();
        let values = count * size * size;
        let bytes = (scratch_len + values) * std::mem::size_of::<Complex32>();
        grid::check_memory(bytes, Self::MEMORY_LIMIT)?;
        Ok(Fft2d {
            n: size,
            count,
            scratch: error::try_vec(scratch_len, Complex32::default())?,
            rows,
            transposed: error::try_vec(values, Complex32::default())?,
        })
    }

    /// Transforms `data` (`count` arrays of N×N, row-major, one after another) and returns
    /// the transposed result. `data` is used as working space. Allocates nothing.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless `data` holds exactly `count`·N² values; nothing is
    /// transformed then.
    pub fn process(&mut self, data: &mut [Complex32]) -> Result<&[Complex32], Error> {
        let n = self.n;
        error::length("data", data.len(), self.count * n * n)?;
        let rows = &self.rows;
        let s = rows.scratch_len();
        data.par_chunks_mut(n * ROWS_PER_TASK)
            .zip(self.scratch.par_chunks_mut(s))
            .for_each(|(chunk, scratch)| rows.process(chunk, scratch));
        // Second pass: each task gathers a block of rows of one array (the transpose) and
        // transforms them while they are in cache, as a cascade does.
        let blocks = n.div_ceil(ROWS_PER_TASK);
        let data = &*data;
        self.transposed
            .par_chunks_mut(n * n)
            .zip(self.scratch.par_chunks_mut(blocks * s))
            .enumerate()
            .for_each(|(a, (array, scratch))| {
                let src = &data[a * n * n..(a + 1) * n * n];
                array
                    .par_chunks_mut(n * ROWS_PER_TASK)
                    .zip(scratch.par_chunks_mut(s))
                    .enumerate()
                    .for_each(|(block, (rows_out, scratch))| {
                        let j0 = block * ROWS_PER_TASK;
                        let height = rows_out.len() / n;
                        transpose_into(&src[j0..], n, rows_out, n, height, n);
                        rows.process(rows_out, scratch);
                    });
            });
        Ok(&self.transposed)
    }
}

#[cfg(test)]
// References in the standard library\'s maths: tests are not simulation code.
#[allow(clippy::disallowed_methods)]
mod tests {
    use super::*;

    #[test]
    fn transpose_matches_definition_for_sizes_not_multiple_of_the_tile() {
        for n in [4, 6, 24, 34] {
            let src: Vec<Complex32> = (0..n * n)
                .map(|v| Complex32::new(v as f32, -(v as f32)))
                .collect();
            let mut dst = vec![Complex32::default(); n * n];
            transpose_into(&src, n, &mut dst, n, n, n);
            for i in 0..n {
                for j in 0..n {
                    assert_eq!(dst[j * n + i], src[i * n + j]);
                }
            }
        }
    }

    #[test]
    fn fft2d_matches_a_naive_inverse_dft() {
        let modes = [Determinism::SameMachine, Determinism::CrossPlatform];
        for (n, determinism) in [4, 6, 8, 34, 62]
            .into_iter()
            .flat_map(|n| modes.map(|d| (n, d)))
        {
            let count = 2;
            let input: Vec<Complex32> = (0..count * n * n)
                .map(|v| Complex32::new(((v * 7) % 11) as f32 - 5.0, ((v * 3) % 5) as f32))
                .collect();
            let mut fft = Fft2d::with_determinism(n, count, determinism).unwrap();
            let mut data = input.clone();
            let out = fft.process(&mut data).unwrap().to_vec();
            let tau = std::f64::consts::TAU;
            for a in 0..count {
                for x in 0..n {
                    for z in 0..n {
                        // result[a][x][z] = Σ input[a][kz][kx] e^{+i 2π (kx x + kz z)/N}
                        let (mut re, mut im) = (0.0f64, 0.0f64);
                        for kz in 0..n {
                            for kx in 0..n {
                                let v = input[a * n * n + kz * n + kx];
                                let phase = tau * ((kx * x + kz * z) % n) as f64 / n as f64;
                                let (s, c) = phase.sin_cos();
                                re += f64::from(v.re) * c - f64::from(v.im) * s;
                                im += f64::from(v.re) * s + f64::from(v.im) * c;
                            }
                        }
                        let got = out[a * n * n + x * n + z];
                        let scale = (n * n) as f64 * 8.0;
                        let tolerance = 1e-5 * scale;
                        assert!(
                            (f64::from(got.re) - re).abs() < tolerance,
                            "{determinism:?} {n}"
                        );
                        assert!(
                            (f64::from(got.im) - im).abs() < tolerance,
                            "{determinism:?} {n}"
                        );
                    }
                }
            }
        }
    }
}
