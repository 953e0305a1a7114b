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
}
