//! Cubic B-spline interpolation of the cascades' fields for the world queries: the
//! coefficients (the prefilter, computed once per update) and the 4×4 stencil of a point.
//!
//! A field f sampled on the periodic grid is represented as f(x) = Σ_n c\[n\] β³(x/Δ − n),
//! β³ the cubic B-spline. Interpolating the samples means (c\[n−1\] + 4c\[n\] + c\[n+1\])/6 = f\[n\]
//! along each axis, solved by the recursive filter of Unser, Aldroubi & Eden (1991): with
//! the pole z = √3 − 2, a causal pass y\[n\] = f\[n\] + z·y\[n−1\], an anticausal pass
//! c\[n\] = y\[n\] + z·c\[n+1\], and the gain −6z, each pass started from its exact periodic
//! initial value (a geometric sum over the period; terms beyond z²⁴ ≈ 2·10⁻¹⁴ dropped).

use std::sync::{PoisonError, RwLock, RwLockReadGuard};

use rayon::prelude::*;

use crate::cascade::Cascade;
use crate::error::{self, Error};

/// The pole √3 − 2 of the cubic B-spline's interpolation filter.
const POLE: f32 = -0.267_949_2;
/// Gain −6z of the two passes together: 1/(1 − z)² times it is 1, so constants pass.
const GAIN: f32 = 1.607_695_2;
/// Terms of the periodic initial sums (z^24 ≈ 2·10⁻¹⁴, far below f32 precision).
const INIT_TERMS: usize = 24;
/// Rows one parallel task of the row pass filters.
const ROWS_PER_TASK: usize = 32;
/// Smallest grid whose coefficients are computed with parallel tasks.
const PARALLEL_SIZE: usize = 256;

/// The cubic B-spline coefficients of one cascade's displacement `[D_x, D_z]` and surface
/// `[η, ∂y/∂x, ∂y/∂z]` (z rows, as the cascade's buffers), with the scratch rows of the
/// column pass.
#[derive(Debug, Clone)]
pub(crate) struct Spline {
    n: usize,
    pub(crate) displacement: Vec<[f32; 2]>,
    pub(crate) surface: Vec<[f32; 3]>,
    scratch2: Vec<[f32; 2]>,
    scratch3: Vec<[f32; 3]>,
}

impl Spline {
    /// Allocates the coefficients of an N×N cascade (all zero until [`Spline::compute`]).
    pub(crate) fn new(n: usize) -> Result<Spline, Error> {
        Ok(Spline {
            n,
            displacement: error::try_vec(n * n, [0.0; 2])?,
            surface: error::try_vec(n * n, [0.0; 3])?,
            scratch2: error::try_vec(n, [0.0; 2])?,
            scratch3: error::try_vec(n, [0.0; 3])?,
        })
    }

    /// Bytes the coefficients of an N×N cascade hold: 20·N² and two scratch rows.
    pub(crate) fn memory_bytes(n: usize) -> usize {
        n.saturating_mul(n)
            .saturating_mul(20)
            .saturating_add(n.saturating_mul(20))
    }

    /// Recomputes the coefficients from the cascade's buffers: each array a copy, a row pass
    /// and a column pass (whole rows at a time, so that it vectorises). From N =
    /// [`PARALLEL_SIZE`] on the two arrays and the row blocks run in parallel; below, the
    /// work is too small to be worth handing to the pool. Allocates nothing; the split into
    /// tasks depends only on N, and every value is computed the same way in any task, so
    /// the result does not depend on the number of threads.
    pub(crate) fn compute(&mut self, cascade: &Cascade) {
        let n = self.n;
        let parallel = n >= PARALLEL_SIZE;
        let Spline {
            displacement,
            surface,
            scratch2,
            scratch3,
            ..
        } = self;
        let mut first = || {
            displacement.copy_from_slice(cascade.displacement());
            filter_2d(displacement, scratch2, n, parallel);
        };
        let mut second = || {
            for ((c, &eta), s) in surface
                .iter_mut()
                .zip(cascade.height())
                .zip(cascade.slope())
            {
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
}

/// The interpolation filter along both axes of an N×N periodic grid, in place; the row
/// blocks in parallel if `parallel`.
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

/// Rows filtered together by [`filter_rows`]: their recursions are independent, so
/// interleaving them hides the latency of each one's dependency chain.
const INTERLEAVE: usize = 8;

/// 1/(1 − z^N), the correction of the periodic initial sums (1 to f32 precision for large
/// N, exact for small ones, whose sums run over the whole period).
fn periodic_factor(n: usize) -> f32 {
    1.0 / (1.0 - crate::determinism::powi_f32(POLE, n.min(64) as i32))
}

/// The interpolation filter along each of the R periodic rows of N values in `group`, in
/// place, the R recursions interleaved. The gain is applied in the anticausal pass,
/// c'\[n\] = G·y\[n\] + z·c'\[n + 1\] (the same as G·c, without a pass of its own).
fn filter_rows<const C: usize, const R: usize>(group: &mut [[f32; C]], n: usize) {
    let mut chunks = group.chunks_exact_mut(n);
    let rows: [&mut [[f32; C]]; R] =
        std::array::from_fn(|_| chunks.next().expect("the group holds R rows of N values"));
    let terms = n.min(INIT_TERMS);
    let factor = periodic_factor(n);
    // Causal: y[−1] = Σ_k z^k f[N − 1 − k] / (1 − z^N).
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
    let mut rows = rows;
    for i in 0..n {
        for (s, row) in state.iter_mut().zip(rows.iter_mut()) {
            let v = &mut row[i];
            for ch in 0..C {
                v[ch] += POLE * s[ch];
            }
            *s = *v;
        }
    }
    // Anticausal: c'[N − 1] = G Σ_k z^k y[(N − 1 + k) mod N] / (1 − z^N).
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

/// The interpolation filter along z (down the columns) of an N×N grid, in place, a whole
/// row at a time, on the rows as flat f32 slices (so that it vectorises whatever C is);
/// `scratch` holds one row. The gain is applied in the anticausal pass, as in
/// [`filter_rows`].
fn filter_columns<const C: usize>(data: &mut [[f32; C]], scratch: &mut [[f32; C]], n: usize) {
    let data = data.as_flattened_mut();
    let scratch = scratch.as_flattened_mut();
    let width = C * n;
    let terms = n.min(INIT_TERMS);
    let factor = periodic_factor(n);
    // Causal: the row y[−1] = Σ_k z^k f[N − 1 − k] / (1 − z^N), into the scratch row.
    weighted_sum(data, scratch, width, (0..terms).map(|k| n - 1 - k), factor);
    recurse(&mut data[..width], scratch, 1.0);
    for j in 1..n {
        let (done, rest) = data.split_at_mut(j * width);
        recurse(&mut rest[..width], &done[(j - 1) * width..], 1.0);
    }
    // Anticausal: c'[N − 1] = G Σ_k z^k y[(N − 1 + k) mod N] / (1 − z^N).
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

/// `out` = factor · Σ_k z^k · row(rows_k), rows of `width` values.
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

/// `row` = `gain` · `row` + z · `other`, element-wise.
#[inline]
fn recurse(row: &mut [f32], other: &[f32], gain: f32) {
    for (v, o) in row.iter_mut().zip(other) {
        *v = gain * *v + POLE * o;
    }
}

/// The 16 taps of world point (x, z) on a periodic N×N grid of side `length`: the rows
/// (start indices j·N) and columns of the 4×4 neighbourhood and the cubic B-spline weights
/// along each axis. The wrap is done in f64, so a point a million metres out keeps the
/// grid's sub-millimetre resolution.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SplineStencil {
    rows: [usize; 4],
    columns: [usize; 4],
    wx: [f32; 4],
    wz: [f32; 4],
}

/// Cubic B-spline weights of the taps at offsets −1, 0, 1, 2 from the cell's node, for the
/// fraction `t` ∈ [0, 1] of the way to the next node. They sum to 1; at t = 0 they are
/// (1, 4, 1, 0)/6.
#[inline]
pub(crate) fn weights(t: f32) -> [f32; 4] {
    let s = 1.0 - t;
    let t2 = t * t;
    let t3 = t2 * t;
    [
        s * s * s / 6.0,
        (4.0 - 6.0 * t2 + 3.0 * t3) / 6.0,
        (1.0 + 3.0 * (t + t2 - t3)) / 6.0,
        t3 / 6.0,
    ]
}

impl SplineStencil {
    /// From the grid cell (`ix`, `iz`) and the fractions (`fx`, `fz`) within it.
    #[inline]
    pub(crate) fn new(ix: usize, fx: f32, iz: usize, fz: f32, n: usize) -> SplineStencil {
        let around = |i: usize| [(i + n - 1) % n, i, (i + 1) % n, (i + 2) % n];
        let columns = around(ix);
        let rows = around(iz).map(|j| j * n);
        SplineStencil {
            rows,
            columns,
            wx: weights(fx),
            wz: weights(fz),
        }
    }

    /// Σ w_x w_z c over the 16 taps of `coefficients`.
    #[inline]
    pub(crate) fn apply<const C: usize>(&self, coefficients: &[[f32; C]]) -> [f32; C] {
        let mut sum = [0.0f32; C];
        for (&row, &wz) in self.rows.iter().zip(&self.wz) {
            let mut line = [0.0f32; C];
            for (&column, &wx) in self.columns.iter().zip(&self.wx) {
                let c = coefficients[row + column];
                for ch in 0..C {
                    line[ch] += wx * c[ch];
                }
            }
            for ch in 0..C {
                sum[ch] += wz * line[ch];
            }
        }
        sum
    }
}

/// The spline coefficients of every cascade for the world queries, computed on the first query
/// after an update rather than in the step: a step whose ocean is never queried (a game that
/// only draws the buffers, a bake) does not pay for them, and one that is queried pays once.
///
/// Queries take `&self` and may run on many threads at once, so the coefficients sit behind a
/// read–write lock: a query takes the read lock (uncontended, a few nanoseconds); the first
/// one after an update finds them stale, takes the write lock and computes them (any
/// concurrent query waits for it). The computation does not depend on which thread does it,
/// so the results are the same bits however the queries are scheduled.
#[derive(Debug)]
pub(crate) struct QuerySplines {
    state: RwLock<SplineState>,
}

#[derive(Debug, Clone)]
struct SplineState {
    /// Whether `splines` hold the coefficients of the cascades' current buffers.
    fresh: bool,
    /// One per cascade; empty with bilinear queries.
    splines: Vec<Spline>,
}

/// Read access to coefficients that are fresh: the cascades' splines, largest first (empty
/// with bilinear queries).
pub(crate) struct FreshSplines<'a>(RwLockReadGuard<'a, SplineState>);

impl std::ops::Deref for FreshSplines<'_> {
    type Target = [Spline];

    fn deref(&self) -> &[Spline] {
        &self.0.splines
    }
}

impl QuerySplines {
    /// Holds `splines` (one per cascade, or none), stale until the first query.
    pub(crate) fn new(splines: Vec<Spline>) -> Self {
        QuerySplines {
            state: RwLock::new(SplineState {
                fresh: false,
                splines,
            }),
        }
    }

    /// Marks the coefficients stale after the cascades changed (no locking: `&mut self`).
    pub(crate) fn invalidate(&mut self) {
        let state = self.state.get_mut().unwrap_or_else(PoisonError::into_inner);
        state.fresh = false;
    }

    /// The coefficients of `cascades` as their buffers are now, computing them first if an
    /// update made them stale. Allocates nothing.
    pub(crate) fn fresh(&self, cascades: &[Cascade]) -> FreshSplines<'_> {
        {
            let state = self.state.read().unwrap_or_else(PoisonError::into_inner);
            if state.fresh || state.splines.is_empty() {
                return FreshSplines(state);
            }
        }
        {
            let mut state = self.state.write().unwrap_or_else(PoisonError::into_inner);
            if !state.fresh {
                state
                    .splines
                    .par_iter_mut()
                    .zip(cascades)
                    .for_each(|(spline, cascade)| spline.compute(cascade));
                state.fresh = true;
            }
        }
        FreshSplines(self.state.read().unwrap_or_else(PoisonError::into_inner))
    }
}

impl Clone for QuerySplines {
    fn clone(&self) -> Self {
        let state = self.state.read().unwrap_or_else(PoisonError::into_inner);
        QuerySplines {
            state: RwLock::new(state.clone()),
        }
    }
}
