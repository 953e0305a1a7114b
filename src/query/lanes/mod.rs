//! Batch queries on the spline eight points at a time, one point a lane: the cells, the
//! weights, the sums over the taps and the Newton updates of eight points are each one
//! vector operation (written as loops over `[_; 8]`, which the compiler turns into vector
//! instructions at each SIMD level), and only the tile lookup is done point by point.
//!
//! Every lane runs the scalar code's operations in the scalar code's order ([`super::inversion`]
//! and [`spline`](super::spline): the same wrap and cell, the same weight formulas, a pair field's
//! taps summed columns first and the taps added (0 + 2) + (1 + 3), the same Newton step), so each
//! point's result has the bits of its single query. How the lanes take their points depends on what
//! the query reads (see [`locate`]).
//!
//! `shuffle.rs` holds each SIMD level's transposes and products, `evaluate.rs` the fields at
//! eight points, `search.rs` eight Newton searches, and `schedule.rs` which points the lanes
//! take and when their results are written.

// Lanes are the same index into several arrays at once; an iterator over one of them hides
// that.
#![allow(clippy::needless_range_loop)]

mod evaluate;
mod schedule;
mod search;
mod shuffle;

pub(super) use evaluate::sample;
pub(super) use schedule::locate;
pub(super) use shuffle::{Plain, Shuffle};

use crate::math::periodic::{wrap, Period, FAR_PERIODS};

/// Points a vector holds.
pub(super) const LANES: usize = 8;
/// Fewest points a batch (or [`sample`]'s last group) puts in lanes: up to three points
/// are queried one at a time, eight lanes' work costing more than their single queries (on
/// one thread a batch of one point took 2.7×, of two 1.5× and of three 1.0–1.1× their
/// single queries, of four 0.8×; see docs/performance.md).
pub(super) const FEWEST: usize = 4;

type F32s = [f32; LANES];
type F64s = [f64; LANES];

/// `f(l)` for each lane `l` (a plain loop: `std::array::from_fn`'s adapter is sometimes
/// left out of line, and a closure out of line runs without the batch's SIMD level).
#[inline(always)]
fn each<T: Copy + Default>(mut f: impl FnMut(usize) -> T) -> [T; LANES] {
    let mut out = [T::default(); LANES];
    for (l, out) in out.iter_mut().enumerate() {
        *out = f(l);
    }
    out
}

/// The cell and the fraction across it of eight coordinates along one axis of a periodic
/// grid: [`cell_on`](crate::math::periodic::cell_on)'s wrap and split, lane by lane.
#[inline(always)]
fn cells(v: &F64s, period: &Period) -> ([u32; LANES], F32s) {
    let Period {
        length,
        inverse,
        cells,
        n,
    } = *period;
    let periods: F64s = each(|l| (v[l] * inverse).floor());
    let mut wrapped: F64s = each(|l| {
        let r = v[l] - periods[l] * length;
        let (low, high) = (r + length, r - length);
        if r < 0.0 {
            low
        } else if r >= length {
            high
        } else {
            r
        }
    });
    // Far from the origin `wrap` takes another path; rare, so lane by lane.
    if periods.iter().any(|p| p.abs() >= FAR_PERIODS) {
        for l in 0..LANES {
            if periods[l].abs() >= FAR_PERIODS {
                wrapped[l] = wrap(v[l], length, inverse);
            }
        }
    }
    let g: F64s = each(|l| wrapped[l] * cells);
    let floor: F64s = each(|l| g[l].floor());
    let fraction: F32s = each(|l| (g[l] - floor[l]) as f32);
    // 0 ≤ ⌊g⌋ ≤ n < 2³¹, a whole number: adding 1.5·2⁵² puts it in the low bits of the
    // f64 exactly (a cheaper conversion than `as`, which must saturate).
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    let n = n as u32;
    let cell = each(|l| {
        let cell = (floor[l] + SHIFT).to_bits() as u32;
        if cell >= n {
            cell - n
        } else {
            cell
        }
    });
    (cell, fraction)
}

/// The cells `[ix, iz]` of up to eight world points `[x, z]` on a periodic grid, one a
/// lane (the missing lanes take the first point's).
#[inline(always)]
pub(super) fn cells_at(points: &[[f64; 2]], period: &Period) -> [[u32; LANES]; 2] {
    let x = each(|l| points.get(l).unwrap_or(&points[0])[0]);
    let z = each(|l| points.get(l).unwrap_or(&points[0])[1]);
    [cells(&x, period).0, cells(&z, period).0]
}
