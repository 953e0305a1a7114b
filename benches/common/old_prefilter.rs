//! The whole-grid spline prefilter the queries used before issue 25 (commit f849527,
//! `src/ocean/spline.rs`), kept as the baseline of the `ocean_full_coverage` benches: the
//! periodic cubic B-spline filter of Unser, Aldroubi & Eden (1991) along the rows, then the
//! columns, of every cascade's displacement and surface arrays, the row blocks and the two
//! arrays in parallel from N = 256 on.

use rayon::prelude::*;

const POLE: f32 = -0.267_949_2;
const GAIN: f32 = 1.607_695_2;
const INIT_TERMS: usize = 24;
const ROWS_PER_TASK: usize = 32;
const PARALLEL_SIZE: usize = 256;
const INTERLEAVE: usize = 8;

/// The coefficients of one cascade, as the old code kept them.
pub struct OldSpline {
    n: usize,
    displacement: Vec<[f32; 2]>,
    surface: Vec<[f32; 3]>,
    scratch2: Vec<[f32; 2]>,
    scratch3: Vec<[f32; 3]>,
}

impl OldSpline {
    pub fn new(n: usize) -> OldSpline {
        OldSpline {
            n,
            displacement: vec![[0.0; 2]; n * n],
            surface: vec![[0.0; 3]; n * n],
            scratch2: vec![[0.0; 2]; n],
            scratch3: vec![[0.0; 3]; n],
        }
    }

    /// The old `Spline::compute` from a cascade's buffers.
    pub fn compute(&mut self, height: &[f32], displacement: &[[f32; 2]], slope: &[[f32; 2]]) {
        let n = self.n;
        let parallel = n >= PARALLEL_SIZE;
        let OldSpline {
            displacement: d,
            surface,
            scratch2,
            scratch3,
            ..
        } = self;
        let mut first = || {
            d.copy_from_slice(displacement);
            filter_2d(d, scratch2, n, parallel);
        };
        let mut second = || {
            for ((c, &eta), s) in surface.iter_mut().zip(height).zip(slope) {
                *c = [eta, s[0], s[1]];
            }
            filter_2d(surface, scratch3, n, parallel);
        };
        if parallel {
            rayon::join(first, second);
        } else {
            first();
            second();
        }
    }

    /// One coefficient, so that the work cannot be optimised away.
    pub fn probe(&self) -> f32 {
        self.surface[self.n + 1][0] + self.displacement[1][1]
    }
}

fn filter_2d<const C: usize>(
    data: &mut [[f32; C]],
    scratch: &mut [[f32; C]],
    n: usize,
    parallel: bool,
) {
    let rows = |block: &mut [[f32; C]]| {
        let mut groups = block.chunks_exact_mut(INTERLEAVE * n);
        for group in &mut groups {
            filter_rows::<C, INTERLEAVE>(group, n);
        }
        for row in groups.into_remainder().chunks_mut(n) {
            filter_rows::<C, 1>(row, n);
        }
    };
    if parallel {
        data.par_chunks_mut(ROWS_PER_TASK * n).for_each(rows);
    } else {
        rows(data);
    }
    filter_columns(data, scratch, n);
}

fn periodic_factor(n: usize) -> f32 {
    1.0 / (1.0 - POLE.powi(n.min(64) as i32))
}

fn filter_rows<const C: usize, const R: usize>(group: &mut [[f32; C]], n: usize) {
    let mut chunks = group.chunks_exact_mut(n);
    let mut rows: [&mut [[f32; C]]; R] =
        std::array::from_fn(|_| chunks.next().expect("the group holds R rows of N values"));
    let terms = n.min(INIT_TERMS);
    let factor = periodic_factor(n);
    let mut state = [[0.0f32; C]; R];
    for (s, row) in state.iter_mut().zip(rows.iter()) {
        let mut weight = factor;
        for k in 0..terms {
            let v = row[n - 1 - k];
            for ch in 0..C {
                s[ch] += weight * v[ch];
            }
            weight *= POLE;
        }
    }
    for i in 0..n {
        for (s, row) in state.iter_mut().zip(rows.iter_mut()) {
            let v = &mut row[i];
            for ch in 0..C {
                v[ch] += POLE * s[ch];
            }
            *s = *v;
        }
    }
    for (s, row) in state.iter_mut().zip(rows.iter_mut()) {
        *s = [0.0; C];
        let mut weight = GAIN * factor;
        for k in 0..terms {
            let v = row[(n - 1 + k) % n];
            for ch in 0..C {
                s[ch] += weight * v[ch];
            }
            weight *= POLE;
        }
        row[n - 1] = *s;
    }
    for i in (0..n - 1).rev() {
        for (s, row) in state.iter_mut().zip(rows.iter_mut()) {
            let v = &mut row[i];
            for ch in 0..C {
                v[ch] = GAIN * v[ch] + POLE * s[ch];
            }
            *s = *v;
        }
    }
}

fn filter_columns<const C: usize>(data: &mut [[f32; C]], scratch: &mut [[f32; C]], n: usize) {
    let data = data.as_flattened_mut();
    let scratch = scratch.as_flattened_mut();
    let width = C * n;
    let terms = n.min(INIT_TERMS);
    let factor = periodic_factor(n);
    weighted_sum(data, scratch, width, (0..terms).map(|k| n - 1 - k), factor);
    recurse(&mut data[..width], scratch, 1.0);
    for j in 1..n {
        let (done, rest) = data.split_at_mut(j * width);
        recurse(&mut rest[..width], &done[(j - 1) * width..], 1.0);
    }
    weighted_sum(
        data,
        scratch,
        width,
        (0..terms).map(|k| (n - 1 + k) % n),
        GAIN * factor,
    );
    data[(n - 1) * width..].copy_from_slice(scratch);
    for j in (0..n - 1).rev() {
        let (head, tail) = data.split_at_mut((j + 1) * width);
        recurse(&mut head[j * width..], &tail[..width], GAIN);
    }
}

fn weighted_sum(
    data: &[f32],
    out: &mut [f32],
    width: usize,
    rows: impl Iterator<Item = usize>,
    factor: f32,
) {
    out.fill(0.0);
    let mut weight = factor;
    for j in rows {
        for (o, v) in out.iter_mut().zip(&data[j * width..(j + 1) * width]) {
            *o += weight * v;
        }
        weight *= POLE;
    }
}

#[inline]
fn recurse(row: &mut [f32], other: &[f32], gain: f32) {
    for (v, o) in row.iter_mut().zip(other) {
        *v = gain * *v + POLE * o;
    }
}
