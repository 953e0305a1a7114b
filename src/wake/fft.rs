//! The wake window's 2D transforms: forward and inverse complex FFTs of an N×N grid, rows in
//! parallel blocks and a tiled transpose between the passes, with the crate's row plans
//! ([`RowFft`]) and their determinism modes. Scratch is made once; a transform allocates
//! nothing.

use num_complex::Complex32;
use rayon::prelude::*;

use crate::error::{self, Error};
use crate::math::determinism::Determinism;
use crate::math::fft2d::{transpose_into, RowFft, ROWS_PER_TASK};

/// Forward and inverse unnormalised 2D FFTs of N×N complex grids.
#[derive(Debug, Clone)]
pub(crate) struct Fft {
    n: usize,
    forward: RowFft,
    inverse: RowFft,
    /// One task's scratch per block of [`ROWS_PER_TASK`] rows.
    scratch: Vec<Complex32>,
    /// Scratch length of one task.
    task: usize,
}

impl Fft {
    pub(crate) fn new(n: usize, determinism: Determinism) -> Result<Fft, Error> {
        let forward = RowFft::new_forward(n, determinism);
        let inverse = RowFft::new(n, determinism);
        let task = forward.scratch_len().max(inverse.scratch_len());
        let scratch = error::try_vec(n.div_ceil(ROWS_PER_TASK) * task, Complex32::default())?;
        Ok(Fft {
            n,
            forward,
            inverse,
            scratch,
            task,
        })
    }

    /// Transforms `src` (row-major `[r][c]`, used as working space) along both axes into
    /// `dst`, left transposed (`[c][r]`): a forward transform (e^{−i…}) or an inverse one
    /// (e^{+i…}, unnormalised). Both hold N² values.
    pub(crate) fn run(&mut self, inverse: bool, src: &mut [Complex32], dst: &mut [Complex32]) {
        let n = self.n;
        let plan = if inverse {
            &self.inverse
        } else {
            &self.forward
        };
        let task = self.task;
        src.par_chunks_mut(n * ROWS_PER_TASK)
            .zip(self.scratch.par_chunks_mut(task))
            .for_each(|(rows, scratch)| plan.process(rows, &mut scratch[..plan.scratch_len()]));
        let src = &*src;
        dst.par_chunks_mut(n * ROWS_PER_TASK)
            .zip(self.scratch.par_chunks_mut(task))
            .enumerate()
            .for_each(|(block, (rows, scratch))| {
                let height = rows.len() / n;
                transpose_into(&src[block * ROWS_PER_TASK..], n, rows, n, height, n);
                plan.process(rows, &mut scratch[..plan.scratch_len()]);
            });
    }
    /// The inverse of [`run`](Self::run)'s forward output for a real field: `src` holds the
    /// transposed spectrum (`[k_x][k_z]`, Hermitian: the value at −k the conjugate of that at
    /// k; used as working space), and `dst`'s first N/2 rows receive the real field's rows
    /// two by two, row 2p in the real parts of row p and row 2p + 1 in the imaginary parts
    /// (unnormalised, as [`run`](Self::run)'s inverse). Half the work of the complex
    /// inverse: only the rows k_x = 0..=N/2 are transformed along k_z, and each transform
    /// along k_x carries two rows of the field.
    pub(crate) fn inverse_real(&mut self, src: &mut [Complex32], dst: &mut [Complex32]) {
        let n = self.n;
        let half = n / 2;
        let (plan, task) = (&self.inverse, self.task);
        // Along k_z, the rows k_x = 0..=N/2 (the others are their conjugates).
        src[..(half + 1) * n]
            .par_chunks_mut(n * ROWS_PER_TASK)
            .zip(self.scratch.par_chunks_mut(task))
            .for_each(|(rows, scratch)| plan.process(rows, &mut scratch[..plan.scratch_len()]));
        let g = &*src;
        // Row p of the pairs: G(k_x, z₁) + i·G(k_x, z₂), z₁ = 2p, z₂ = 2p + 1, over all k_x
        // (G(−k_x, z) = conj G(k_x, z)), read a block's columns a row of G at a time.
        dst[..half * n]
            .par_chunks_mut(n * ROWS_PER_TASK)
            .zip(self.scratch.par_chunks_mut(task))
            .enumerate()
            .for_each(|(block, (rows, scratch))| {
                let pairs = rows.len() / n;
                let first = 2 * block * ROWS_PER_TASK;
                for a in 0..=half {
                    let segment = &g[a * n + first..][..2 * pairs];
                    for (q, two) in segment.chunks_exact(2).enumerate() {
                        let (g1, g2) = (two[0], two[1]);
                        let row = &mut rows[q * n..][..n];
                        row[a] = Complex32::new(g1.re - g2.im, g1.im + g2.re);
                        if a != 0 && a != half {
                            row[n - a] = Complex32::new(g1.re + g2.im, g2.re - g1.im);
                        }
                    }
                }
                plan.process(rows, &mut scratch[..plan.scratch_len()]);
            });
    }
}
