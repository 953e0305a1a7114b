//! The wake's foam trail: a coverage in [0, 1] on the window's grid, made where a moving hull
//! breaks the water (discs at its bow and stern) and where the wake's crests are steeper than
//! a breaking slope, kept where it was made (it moves with the window's whole-cell moves) and
//! fading with the ocean's residual-foam lifetime. See docs/theory.md, "Wakes".

use num_complex::Complex32;
use rayon::prelude::*;

use super::bump;
use crate::math::determinism::{with_math, Determinism, Math};
use crate::math::fft2d::ROWS_PER_TASK;
use crate::spectrum::dispersion::GRAVITY;

/// Slope |∇η| of the wake's waves above which their crests break: the linear slope a·k of a
/// wave at a steepness H/λ of 0.1, 70 % of Stokes's limiting 0.142 (Michell 1893), about
/// where steep deep-water crests are seen to start spilling.
pub(crate) const CREST_SLOPE: f32 = 0.1 * std::f32::consts::PI;

/// Foam made per second on a crest, per unit of its slope's relative excess over
/// [`CREST_SLOPE`] (a look setting: a crest 50 % over the limit for a second whitens
/// 1 − e^(−1) of its area).
const CREST_RATE: f32 = 2.0;

/// The foam's settings over one tick of the wake's clock.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TrailClock {
    /// Tick in seconds.
    pub(crate) tick: f32,
    /// The factor the foam keeps over a tick, e^(−tick/lifetime).
    pub(crate) keep: f32,
}

impl TrailClock {
    /// The clock of ticks of `tick` s for foam of lifetime `lifetime` s (> 0).
    pub(crate) fn new(tick: f64, lifetime: f32, determinism: Determinism) -> TrailClock {
        let keep = with_math!(determinism, M => M::exp(-tick / f64::from(lifetime)));
        TrailClock {
            tick: tick as f32,
            keep: keep as f32,
        }
    }
}

/// `foam` covered further by a source of `amount` (the share of the bare water it whitens).
#[inline(always)]
fn whiten(foam: &mut f32, amount: f32) {
    *foam += (1.0 - *foam) * amount.clamp(0.0, 1.0);
}

/// A hull's foam over one tick at row `z` (m) of the window: discs of the beam's diameter at
/// its bow and stern (`centre` ± half its length along `bow`), whitening at a rate that grows
/// with the square of its speed `speed` (m/s) against its draft, so that a point the disc's
/// centre passes over gets 1 − e^(−1.8·b) of cover, b = min(1, U²/(2g·draft)) being the
/// stagnation head at the bow over the draft (a hull at rest makes none).
#[allow(clippy::too_many_arguments)]
pub(crate) fn hull_row(
    row: &mut [f32],
    z: f64,
    first_x: f64,
    spacing: f64,
    centre: [f64; 2],
    bow: [f32; 2],
    [length, beam, draft]: [f32; 3],
    speed: f32,
    tick: f32,
) {
    let head = speed * speed / (2.0 * GRAVITY * draft);
    let radius = 0.5 * beam;
    // ∫ bump(u) du over [−1, 1] is 32/35: on the track rate·(radius/U)·32/35 ≈ 1.8 b.
    let rate = 2.0 * head.min(1.0) * speed / radius;
    if rate <= 0.0 {
        return;
    }
    for side in [0.5f32, -0.5] {
        let cx = centre[0] + f64::from(side * length * bow[0]);
        let cz = centre[1] + f64::from(side * length * bow[1]);
        let dz = (z - cz) as f32;
        if dz.abs() >= radius {
            continue;
        }
        let n = row.len() as i64;
        let first = (((cx - f64::from(radius) - first_x) / spacing).ceil() as i64).clamp(0, n);
        let last = (((cx + f64::from(radius) - first_x) / spacing).floor() as i64 + 1).clamp(0, n);
        for (i, foam) in row
            .iter_mut()
            .enumerate()
            .take(last as usize)
            .skip(first as usize)
        {
            let dx = (first_x + i as f64 * spacing - cx) as f32;
            let d = (dx * dx + dz * dz).sqrt() / radius;
            whiten(foam, rate * tick * bump(d));
        }
    }
}

/// One tick of the trail on an `n`×`n` grid `spacing` m apart: every cell keeps
/// `clock.keep` of its foam, then crests whose waves are steeper than [`CREST_SLOPE`] whiten.
/// The waves are `eta` + `head` (the elevation less the hulls' static dip, −`head`, so that
/// the water pressed down under a hull at rest is no crest).
pub(crate) fn crest_tick(
    foam: &mut [f32],
    eta: &[Complex32],
    head: &[f32],
    n: usize,
    spacing: f64,
    clock: TrailClock,
) {
    let per = (0.5 / spacing) as f32;
    let row = |j: usize| (&eta[j * n..][..n], &head[j * n..][..n]);
    foam.par_chunks_mut(n)
        .enumerate()
        .with_min_len(ROWS_PER_TASK)
        .for_each(|(j, foam)| {
            // One-sided differences at the edges (the border has absorbed the waves there).
            let (here, down, up) = (row(j), row(j.saturating_sub(1)), row((j + 1).min(n - 1)));
            let wave = |(eta, head): (&[Complex32], &[f32]), i: usize| eta[i].re + head[i];
            let mut slope_x = |i: usize, left: usize, right: usize| {
                let sx = (wave(here, right) - wave(here, left)) * per;
                let sz = (wave(up, i) - wave(down, i)) * per;
                crest(&mut foam[i], sx, sz, clock);
            };
            slope_x(0, 0, 1);
            slope_x(n - 1, n - 2, n - 1);
            // The inside, in straight slices (a loop the compiler vectorises).
            let sx = here.0[2..].iter().zip(&here.1[2..]);
            let sx = sx.zip(here.0[..n - 2].iter().zip(&here.1[..n - 2]));
            let sz = up.0[1..n - 1].iter().zip(&up.1[1..n - 1]);
            let sz = sz.zip(down.0[1..n - 1].iter().zip(&down.1[1..n - 1]));
            for ((foam, ((r, rh), (l, lh))), ((u, uh), (d, dh))) in
                foam[1..n - 1].iter_mut().zip(sx).zip(sz)
            {
                let sx = ((r.re + rh) - (l.re + lh)) * per;
                let sz = ((u.re + uh) - (d.re + dh)) * per;
                crest(foam, sx, sz, clock);
            }
        });
}

/// One cell of [`crest_tick`]: its foam kept over the tick, then whitened by a crest of
/// slope (`sx`, `sz`) steeper than [`CREST_SLOPE`] (no branch: the loop vectorises).
#[inline(always)]
fn crest(foam: &mut f32, sx: f32, sz: f32, clock: TrailClock) {
    let slope = (sx * sx + sz * sz).sqrt();
    let excess = (slope / CREST_SLOPE - 1.0).max(0.0);
    let kept = *foam * clock.keep;
    *foam = kept + (1.0 - kept) * (CREST_RATE * excess * clock.tick).min(1.0);
}

/// `to[j][i] = keep(from[j + dz][i + dx])`, or `U::default()` (0) where that lies outside
/// the `n`×`n` grid: the window's buffers moved by whole cells.
pub(crate) fn shift_grid<T: Copy + Sync, U: Default + Send>(
    from: &[T],
    to: &mut [U],
    n: usize,
    [dx, dz]: [i64; 2],
    keep: impl Fn(T) -> U + Sync,
) {
    to.par_chunks_mut(n)
        .enumerate()
        .with_min_len(ROWS_PER_TASK)
        .for_each(|(j, row)| {
            let source = j as i64 + dz;
            for (i, value) in row.iter_mut().enumerate() {
                let column = i as i64 + dx;
                let inside = (0..n as i64).contains(&source) && (0..n as i64).contains(&column);
                *value = if inside {
                    keep(from[source as usize * n + column as usize])
                } else {
                    U::default()
                };
            }
        });
}
