//! Foam: one field for the whole ocean on the largest cascade's grid, injected where the
//! summed surface breaks (its Jacobian below a threshold calibrated against the whitecap
//! fraction of Monahan & O'Muircheartaigh 1980), aging from active whitecaps into residual
//! foam, drifting downwind and spreading into streaks (docs/theory.md, §15).

mod calibration;
mod config;
mod transport;

use std::ops::Bound::{Excluded, Included};

use num_complex::Complex32;
use rayon::prelude::*;

use crate::cascade::{check_time, Cascade, GradientMoments};
use crate::determinism::Determinism;
use crate::error::{self, Error};
use crate::exp::exp;
use crate::fft2d::{transpose_into, RowFft, ROWS_PER_TASK};
use crate::simd::Simd;

use super::OceanState;

pub use calibration::FoamCalibration;
pub use config::FoamConfig;

use calibration::{calibrate, Settings};
use transport::Transport;

/// Points of a row the foam's element loops handle at once, through arrays on the stack.
const BLOCK: usize = 64;

/// Rows of the foam grid one parallel task handles in every pass (the split depends only on
/// N, never on the number of threads): as many as a task of the transforms' second pass
/// gathers, so that the row pass, the column pass and the last pass share one scratch per
/// task.
const ROWS: usize = ROWS_PER_TASK;

/// Fewest grid points one rayon task of a foam pass works through, so that the smallest
/// grids (below 64²) do not pay a fork and join per block of a few hundred points. From 64²
/// on every block of [`ROWS`] rows is a task of its own: at 64² and 128² in a pool of two
/// threads the default step was 10–25 % faster than with one task per pass at 64² (same
/// process, fastest of 3 × 5 chunks, shared machine).
const MIN_TASK_POINTS: usize = 1024;

/// Blocks of [`ROWS`] rows one rayon task takes at least, for a grid of side `n`.
fn min_tasks(n: usize) -> usize {
    MIN_TASK_POINTS.div_ceil(ROWS * n).max(1)
}

/// Residual foam below this after a transport step is set to zero: the rounding of the two
/// FFTs (about 1e-7 of the largest value) would otherwise leave a faint haze everywhere.
const FLUSH: f32 = 1e-6;

/// How much of the surface is covered by foam: area fractions in [0, 1], each grid point
/// counted with the fraction of it that is covered (the foam value there), summed in a fixed
/// order (so the numbers do not depend on the number of threads).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FoamCoverage {
    /// Active whitecaps: foam of waves breaking now or within about the active lifetime τ_A
    /// ([`FoamConfig::active_decay`]) — the mean of [`OceanState::active_foam`]. The
    /// whitecap fraction the calibration aims at.
    pub active: f32,
    /// Residual foam not under active foam: the mean of r·(1 − a), older foam and streaks
    /// that photographs of whitecaps leave out.
    pub residual: f32,
    /// All foam: the mean of [`OceanState::foam`], `active + residual`.
    pub total: f32,
}

/// The per-point constants of the foam update.
#[derive(Debug, Clone, Copy)]
struct Params {
    /// The breaking threshold J_b (−∞: nothing breaks).
    threshold: f32,
    /// Covariance of the unresolved gradient (cascades 1 and up) as (AA, BB, CC, AB, AC, BC).
    unresolved: [f32; 6],
    /// Covariance of the rate of the whole gradient, the same way, in 1/s².
    rate: [f32; 6],
    /// Variance added to the unresolved part everywhere, (0.05 σ_T)²: keeps a one-cascade
    /// ocean's intensity a smooth function of J.
    floor: f32,
    inv_active: f32,
    inv_residual: f32,
}

/// gᵀ M g for a symmetric M stored as (AA, BB, CC, AB, AC, BC).
#[inline(always)]
fn quadratic_form(m: &[f32; 6], g: [f32; 3]) -> f32 {
    m[0] * g[0] * g[0]
        + m[1] * g[1] * g[1]
        + m[2] * g[2] * g[2]
        + 2.0 * (m[3] * g[0] * g[1] + m[4] * g[0] * g[2] + m[5] * g[1] * g[2])
}

/// The symmetric 3×3 `m` as (AA, BB, CC, AB, AC, BC), in f32.
fn packed(m: &[[f64; 3]; 3]) -> [f32; 6] {
    [m[0][0], m[1][1], m[2][2], m[0][1], m[0][2], m[1][2]].map(|v| v as f32)
}

/// 1/√(2π).
const INV_SQRT_TAU: f32 = 0.398_942_3;

/// Q(x) = 1 − Φ(x) for x ≥ 0 from φ(x) = e^{−x²/2}/√(2π), by the approximation of
/// Börjesson & Sundberg (1979): Q ≈ φ(x)/((1 − a)x + a√(x² + b)), a = 0.339, b = 5.510,
/// relative error below 0.3 % for every x ≥ 0.
#[inline(always)]
fn upper_tail(x: f32, density: f32) -> f32 {
    density / (0.661 * x + 0.339 * (x * x + 5.51).sqrt())
}

/// Φ(x) and φ(x) of the standard normal at a crossing x, from one exponential (Φ in the lower
/// tail with full relative accuracy); beyond |x| = 12 (φ < 1e-31) exactly 0 or 1 and 0, and so
/// for x = ±∞. Branch-free.
#[inline(always)]
fn normal_at(x: f32) -> (f32, f32) {
    let density = exp(-0.5 * x * x) * INV_SQRT_TAU;
    let tail = upper_tail(x.abs(), density);
    let cdf = if x <= 0.0 { tail } else { 1.0 - tail };
    let far = x.abs() > 12.0;
    let edge = if x > 0.0 { 1.0 } else { 0.0 };
    (
        if far { edge } else { cdf },
        if far { 0.0 } else { density },
    )
}

/// ∇J of the Jacobian J = (1 + D_xx)(1 + D_zz) − D_xz² with respect to (D_xx, D_zz, D_xz).
#[inline(always)]
fn jacobian_gradient(g: [f32; 3]) -> [f32; 3] {
    let [xx, zz, xz] = g;
    [1.0 + zz, 1.0 + xx, -2.0 * xz]
}

/// What the first stage of the intensity hands to the others (see [`Params::roots`]). The
/// stages are functions of plain values: written as one function with a closure over σ, β
/// and ∇J for the crossing rates, the loop over points ran at 9.7 ns a point under AVX-512 and
/// stayed scalar under AVX2 (84 ns); as stages, 4.4 and 12 ns.
#[derive(Clone, Copy)]
struct Roots {
    /// The roots, lo ≤ hi (lo = −∞ where J is linear in x).
    lo: f32,
    hi: f32,
    /// σ = √(σ² + floor).
    sigma: f32,
    /// |dJ/dx| at the roots, √disc (0 where there is no root).
    slope: f32,
    /// The coefficient of x².
    a2: f32,
    /// The discriminant.
    disc: f32,
    /// The regression β of U on w.
    beta: [f32; 3],
}

impl Params {
    /// The breaking intensity s in 1/s at a point where cascade 0's gradient is `g`
    /// (D_xx, D_zz, D_xz), from its Jacobian J_R and the unresolved cascades' gradient U
    /// (Gaussian, covariance Σ_u): J ≈ J_R + w + κ(w² − σ²) with w = ∇J_R·U (standard deviation
    /// σ, σ² = ∇Jᵀ Σ_u ∇J) and κ w² the mean of U's own quadratic term given w. With
    /// f = P(J < J_b) and Rice's rate ν of new breaking there, s = ν + f/τ_A (docs/theory.md
    /// §15). For a finite threshold (the caller handles J_b = −∞).
    ///
    /// Branch-free, so that a loop over points vectorises: both roots are computed whatever
    /// their number, and selects pick the result. J − J_b = a2·x² + σx + c in x; where a2 = 0
    /// (J linear in x) the root the stable formula gives first is set to −∞, where φ = 0 and
    /// Φ = 0, which leaves P(J < J_b) = Φ(x₁) and one crossing.
    #[inline(always)]
    fn intensity(&self, g: [f32; 3]) -> f32 {
        let r = self.roots(g);
        let (cdf_lo, density_lo) = normal_at(r.lo);
        let (cdf_hi, density_hi) = normal_at(r.hi);
        let episodes = self.crossing_rate(r.lo, density_lo, r.sigma, g, r.beta)
            + self.crossing_rate(r.hi, density_hi, r.sigma, g, r.beta);
        self.combine(r.a2, r.disc, r.slope, cdf_lo, cdf_hi, episodes)
    }

    /// The first stage of [`intensity`](Self::intensity): σ, β, the quadratic in x and its
    /// roots.
    #[inline(always)]
    fn roots(&self, g: [f32; 3]) -> Roots {
        let [xx, zz, xz] = g;
        let jacobian = (1.0 + xx) * (1.0 + zz) - xz * xz;
        let gradient = jacobian_gradient(g);
        let u = &self.unresolved;
        // Σ_u ∇J, then σ² and the regression β = Σ_u ∇J/σ² of U on w.
        let su = [
            u[0] * gradient[0] + u[3] * gradient[1] + u[4] * gradient[2],
            u[3] * gradient[0] + u[1] * gradient[1] + u[5] * gradient[2],
            u[4] * gradient[0] + u[5] * gradient[1] + u[2] * gradient[2],
        ];
        let variance =
            (su[0] * gradient[0] + su[1] * gradient[1] + su[2] * gradient[2]).max(0.0) + self.floor;
        let inverse = 1.0 / variance;
        let beta = su.map(|v| v * inverse);
        let kappa = beta[0] * beta[1] - beta[2] * beta[2];
        let a2 = kappa * variance;
        // σ ≥ √floor > 0.
        let sigma = variance.sqrt();
        let c = jacobian - a2 - self.threshold;
        // The roots of a2 x² + σx + c, found stably: q = −(σ + √disc)/2, the roots q/a2 and
        // c/q, |dJ/dx| = √disc at both.
        let disc = sigma * sigma - 4.0 * a2 * c;
        let slope = disc.max(0.0).sqrt();
        let q = -0.5 * (sigma + slope);
        let first = if a2 == 0.0 { f32::NEG_INFINITY } else { q / a2 };
        let second = c / q;
        Roots {
            lo: first.min(second),
            hi: first.max(second),
            sigma,
            slope,
            a2,
            disc,
            beta,
        }
    }

    /// φ(x)·|J̇| at a root x of [`intensity`](Self::intensity) (φ = `density`): J̇ = ∇J·ġ
    /// with ∇J where the surface crosses J_b, U at its mean given w = σx.
    #[inline(always)]
    fn crossing_rate(&self, x: f32, density: f32, sigma: f32, g: [f32; 3], beta: [f32; 3]) -> f32 {
        let gradient = jacobian_gradient(g);
        let w = sigma * x;
        let at = [
            gradient[0] + beta[1] * w,
            gradient[1] + beta[0] * w,
            gradient[2] - 2.0 * beta[2] * w,
        ];
        let speed = quadratic_form(&self.rate, at).max(0.0).sqrt();
        // At x = ±∞ (φ = 0) the speed is not a number: the select drops it.
        if density > 0.0 {
            density * speed
        } else {
            0.0
        }
    }

    /// The last stage of [`intensity`](Self::intensity): Rice's rate and the fraction
    /// breaking, or the uniform answer where J does not cross J_b.
    #[inline(always)]
    fn combine(
        &self,
        a2: f32,
        disc: f32,
        slope: f32,
        cdf_lo: f32,
        cdf_hi: f32,
        episodes: f32,
    ) -> f32 {
        // P(J < J_b): between the roots where J opens upward (below the one root of a linear
        // J), outside them where it opens downward.
        let fraction = if a2 >= 0.0 {
            (cdf_hi - cdf_lo).max(0.0)
        } else {
            (cdf_lo + 1.0 - cdf_hi).min(1.0)
        };
        let crossing = episodes * INV_SQRT_TAU / slope + fraction * self.inv_active;
        // No crossing (disc ≤ 0): J is above J_b everywhere if it opens upward, below if
        // downward.
        let uniform = if a2 < 0.0 { self.inv_active } else { 0.0 };
        if disc > 0.0 {
            crossing
        } else {
            uniform
        }
    }

    /// The breaking intensity at each point of a row of cascade 0's gradient, into `out`
    /// (as long). Inlined into its caller's [`Simd::run`], so that its loop is compiled for
    /// the caller's SIMD level; every level gives the same bits (no reduction, no FMA).
    #[inline(always)]
    fn intensities(&self, gradient: &[[f32; 3]], out: &mut [f32]) {
        if self.threshold == f32::NEG_INFINITY {
            // Nothing breaks.
            out.fill(0.0);
            return;
        }
        for (g, s) in gradient.iter().zip(out.iter_mut()) {
            *s = self.intensity(*g);
        }
    }

    /// The breaking intensity along a row of cascade 0's gradient into `out` (as long), in
    /// blocks of [`BLOCK`] points through an array on the stack, as [`react_row`] does.
    /// Inlined into its caller's [`Simd::run`].
    ///
    /// [`react_row`]: Self::react_row
    #[inline(always)]
    fn intensity_row(&self, gradient: &[[f32; 3]], out: &mut [f32]) {
        let n = out.len();
        for start in (0..n).step_by(BLOCK) {
            let len = BLOCK.min(n - start);
            let mut fresh = [0.0f32; BLOCK];
            self.intensities(&gradient[start..start + len], &mut fresh[..len]);
            out[start..start + len].copy_from_slice(&fresh[..len]);
        }
    }

    /// One row of the step: the new intensity from cascade 0's `gradient`, the active and
    /// residual foam `a`, `r` aged with the intensity going from `s` (replaced by the new one)
    /// to it, and the residual foam copied into the transform's input `w`. In blocks of
    /// [`BLOCK`] points through arrays on the stack (written straight into the five row
    /// slices, the loop did not vectorise). Inlined into its caller's [`Simd::run`].
    #[inline(always)]
    fn react_row(
        &self,
        step: &Step,
        gradient: &[[f32; 3]],
        a: &mut [f32],
        r: &mut [f32],
        s: &mut [f32],
        w: &mut [Complex32],
    ) {
        let n = a.len();
        for start in (0..n).step_by(BLOCK) {
            let len = BLOCK.min(n - start);
            let range = start..start + len;
            let mut fresh = [0.0f32; BLOCK];
            self.intensities(&gradient[range.clone()], &mut fresh[..len]);
            let mut active = [0.0f32; BLOCK];
            let mut residual = [0.0f32; BLOCK];
            active[..len].copy_from_slice(&a[range.clone()]);
            residual[..len].copy_from_slice(&r[range.clone()]);
            let old = &s[range.clone()];
            for k in 0..len {
                let (a1, r1) = self.react(step, active[k], residual[k], old[k], fresh[k]);
                active[k] = a1;
                residual[k] = r1;
            }
            a[range.clone()].copy_from_slice(&active[..len]);
            r[range.clone()].copy_from_slice(&residual[..len]);
            s[range.clone()].copy_from_slice(&fresh[..len]);
            for (w, &r1) in w[range].iter_mut().zip(&residual[..len]) {
                *w = Complex32::new(r1, 0.0);
            }
        }
    }

    /// The constants of a step of `dt` seconds.
    fn step(&self, dt: f32) -> Step {
        Step { dt }
    }

    /// Active and residual foam after a step with the intensity going from `old` to `new`
    /// (trapezoidal mean held over the step, the linear equations solved exactly).
    /// Branch-free.
    #[inline(always)]
    fn react(&self, step: &Step, active: f32, residual: f32, old: f32, new: f32) -> (f32, f32) {
        let dt = step.dt;
        let s = 0.5 * (old + new);
        let kappa = s + self.inv_active;
        let x = kappa * dt;
        let e = exp(-x);
        let a_star = s / kappa;
        let a1 = a_star + (active - a_star) * e;
        let a_mean = a_star + (active - a_star) * mean_factor(x, e);
        let g = a_mean * self.inv_active;
        let rho = g + self.inv_residual;
        let r_star = g / rho;
        let r1 = r_star + (residual - r_star) * exp(-rho * dt);
        (a1.clamp(0.0, 1.0), r1.clamp(0.0, 1.0))
    }
}

/// (1 − e^{−x})/x from x and e = e^{−x}, by its series for small x: the mean of an
/// exponential relaxation over a step, as a fraction of its start. Branch-free.
#[inline(always)]
fn mean_factor(x: f32, e: f32) -> f32 {
    let direct = (1.0 - e) / x;
    let series = 1.0 - x * (0.5 - x / 6.0);
    if x > 1e-3 {
        direct
    } else {
        series
    }
}

/// Partial sums per row in [`Foam::finish`].
const LANES: usize = 8;

/// The total foam a + r(1 − a) of a row into `f`, and the row's sums of a, r(1 − a) and the
/// total in f64 (see [`Foam::finish`]): column i goes into partial sum i mod [`LANES`], and
/// the partial sums are added in order at the end. Written over whole arrays of [`LANES`]
/// values (one 512-bit register of f64), so that the conversions and additions vectorise at
/// every SIMD level; the order of the additions is the code's, whatever the level. Inlined
/// into its caller's [`Simd::run`].
#[inline(always)]
fn total_row(a: &[f32], r: &[f32], f: &mut [f32]) -> [f64; 3] {
    let mut sum_a = [0.0f64; LANES];
    let mut sum_r = [0.0f64; LANES];
    let mut sum_f = [0.0f64; LANES];
    let whole = a.len() / LANES * LANES;
    let chunks = a[..whole]
        .chunks_exact(LANES)
        .zip(r[..whole].chunks_exact(LANES))
        .zip(f[..whole].chunks_exact_mut(LANES));
    for ((a, r), f) in chunks {
        let a: &[f32; LANES] = a.try_into().expect("LANES values");
        let r: &[f32; LANES] = r.try_into().expect("LANES values");
        let rest: [f32; LANES] = std::array::from_fn(|k| r[k] * (1.0 - a[k]));
        let total: [f32; LANES] = std::array::from_fn(|k| a[k] + rest[k]);
        f.copy_from_slice(&total);
        for k in 0..LANES {
            sum_a[k] += f64::from(a[k]);
            sum_r[k] += f64::from(rest[k]);
            sum_f[k] += f64::from(total[k]);
        }
    }
    for (k, ((&a, &r), f)) in a[whole..]
        .iter()
        .zip(&r[whole..])
        .zip(&mut f[whole..])
        .enumerate()
    {
        let rest = r * (1.0 - a);
        *f = a + rest;
        sum_a[k] += f64::from(a);
        sum_r[k] += f64::from(rest);
        sum_f[k] += f64::from(*f);
    }
    [sum_a, sum_r, sum_f].map(|lane| lane.iter().sum())
}

/// Packs two real rows (the real parts of `a` and `b`) into `a` as one complex row a + ib,
/// so that one complex transform does both.
#[inline(always)]
fn pack_rows(a: &mut [Complex32], b: &[Complex32]) {
    for (a, b) in a.iter_mut().zip(b) {
        a.im = b.re;
    }
}

/// From W, the transform of a + ib for two real rows a and b (in `w`), the transforms of a
/// and b at m = 0 … N/2 (the rest follows from their Hermitian symmetry) into `w` and `b`:
/// A\[m\] = (W\[m\] + conj W\[N − m\])/2 and B\[m\] = (W\[m\] − conj W\[N − m\])/(2i). Each m reads
/// W\[m\] and W\[N − m\] before writing index m, and N − m > N/2 for 0 < m < N/2, so `w` can
/// take A in place.
#[inline(always)]
fn unpack_halves(w: &mut [Complex32], b: &mut [Complex32]) {
    let n = w.len();
    let half = n / 2;
    // (x − y)/(2i) = −i(x − y)/2.
    let split = |x: Complex32, y: Complex32| {
        (
            Complex32::new(0.5 * (x.re + y.re), 0.5 * (x.im + y.im)),
            Complex32::new(0.5 * (x.im - y.im), -0.5 * (x.re - y.re)),
        )
    };
    (w[0], b[0]) = split(w[0], w[0].conj());
    (w[half], b[half]) = split(w[half], w[half].conj());
    let (low, high) = w.split_at_mut(half);
    // m = 1 … N/2 − 1 pairs with N − m = N − 1 … N/2 + 1.
    for ((x, b), y) in low[1..]
        .iter_mut()
        .zip(b[1..half].iter_mut())
        .zip(high[1..].iter().rev())
    {
        (*x, *b) = split(*x, y.conj());
    }
}

/// The inverse of [`unpack_halves`] before the last transform: from the half spectra Y_a
/// (in `v`) and Y_b (in `w`) at m = 0 … N/2 of two rows whose transforms are real, the row
/// Y_a + iY_b over all m in `v`, extended by Y\[N − m\] = conj Y\[m\]; at m = 0 and N/2, where
/// Y is its own partner, only its real part is kept (what taking the real part of a complex
/// result keeps there).
#[inline(always)]
fn repack_halves(v: &mut [Complex32], w: &[Complex32]) {
    let n = v.len();
    let half = n / 2;
    let join = |a: Complex32, b: Complex32| Complex32::new(a.re - b.im, a.im + b.re);
    let (low, high) = v.split_at_mut(half + 1);
    // m = N/2 + 1 … N − 1 from N − m = N/2 − 1 … 1.
    for ((y, a), b) in high
        .iter_mut()
        .zip(low[1..half].iter().rev())
        .zip(w[1..half].iter().rev())
    {
        *y = join(a.conj(), b.conj());
    }
    for (a, b) in low[1..half].iter_mut().zip(&w[1..half]) {
        *a = join(*a, *b);
    }
    for m in [0, half] {
        v[m] = Complex32::new(v[m].re, w[m].re);
    }
}

/// What every point's update over one step shares.
#[derive(Debug, Clone, Copy)]
struct Step {
    dt: f32,
}

/// The foam of an ocean: its state (active and residual foam), the breaking intensity at the
/// current time, the total foam and the coverage, the calibration, and the buffers of the
/// transport step (all allocated once).
#[derive(Debug, Clone)]
pub(crate) struct Foam {
    n: usize,
    /// Side of the foam grid's tile, L of cascade 0, in metres.
    length: f32,
    pub(super) active: Vec<f32>,
    pub(super) residual: Vec<f32>,
    total: Vec<f32>,
    breaking: Vec<f32>,
    coverage: FoamCoverage,
    calibration: FoamCalibration,
    params: Params,
    transport: Transport,
    /// The transport's drift factors (see `Transport::fill_tables`) for a step of
    /// `tables_dt` seconds (NaN: not filled yet), kept while the step stays the same.
    tables: Vec<Complex32>,
    tables_dt: f64,
    /// The transport's grid in space order (row z, column x or m_x): the residual foam
    /// transformed along x, and in the last pass each task's gathered rows.
    spatial: Vec<Complex32>,
    /// The transport's grid transposed (row m_x, column m_z or z), for m_x = 0 … N/2 only.
    spectral: Vec<Complex32>,
    /// The inverse FFT of length N both axes use (the plan `Fft2d` would make).
    fft: RowFft,
    /// FFT scratch, one slice per task of [`ROWS`] rows.
    scratch: Vec<Complex32>,
    row_sums: Vec<[f64; 3]>,
    /// The SIMD level of the element loops.
    simd: Simd,
}

/// Bytes the foam of an ocean of `cascades` cascades of size `n` holds: active, residual,
/// total and breaking (4 bytes each per point), the transport's complex grid (8 bytes per
/// point) and its transposed half (N/2 + 1 rows of N, 8 bytes each), FFT scratch for one
/// task per block of rows, small tables, and the displacement gradient cascade 0 keeps for
/// it (12 bytes per point, see `Cascade::keep_gradient`).
pub(crate) fn memory_bytes(n: usize, cascades: usize, determinism: Determinism) -> usize {
    let points = n.saturating_mul(n);
    let scratch = if n <= crate::grid::MAX_SIZE {
        crate::fft2d::RowFft::new(n, determinism).scratch_len()
    } else {
        n
    };
    let tasks = n.div_ceil(crate::fft2d::ROWS_PER_TASK);
    let _ = cascades;
    let tables = n.saturating_mul(2 * 8 + 24);
    let half = (n / 2 + 1).saturating_mul(n);
    points
        .saturating_mul(4 * 4 + 8 + 12)
        .saturating_add(half.saturating_mul(8))
        .saturating_add(tasks.saturating_mul(scratch).saturating_mul(8))
        .saturating_add(tables)
}

impl Foam {
    /// The foam of an ocean with these (updated) cascades: no foam, the breaking intensity
    /// of the cascades' time, the threshold calibrated for their amplitudes.
    pub(crate) fn new(
        cascades: &[Cascade],
        config: &FoamConfig,
        spectrum: &crate::spectrum::Spectrum,
    ) -> Result<Foam, Error> {
        let wind_speed = config.wind_speed_for(spectrum);
        let first = &cascades[0];
        let determinism = first.config().determinism;
        let n = first.size();
        let length = first.length();
        let resolved = first.gradient_moments();
        let mut unresolved = GradientMoments::default();
        for cascade in &cascades[1..] {
            unresolved.add(&cascade.gradient_moments());
        }
        let mut total = resolved;
        total.add(&unresolved);
        let calibration = calibrate(
            &total,
            Settings {
                wind_speed,
                coverage: config.coverage,
                active_decay: config.active_decay,
                determinism,
            },
        );
        let floor = 0.05 * calibration.compression_std;
        let params = Params {
            threshold: calibration.threshold,
            unresolved: packed(&unresolved.value),
            rate: packed(&total.rate),
            floor: (floor * floor).max(f32::MIN_POSITIVE),
            inv_active: 1.0 / config.active_decay,
            inv_residual: 1.0 / config.residual_decay,
        };
        // Spreads over a residual lifetime, √(2Kτ_R) = streak·λ_p, give the diffusivities.
        let peak = spectrum
            .dispersion()
            .k_from_omega_with_mode(f64::from(spectrum.peak_omega()), determinism);
        let wavelength = std::f64::consts::TAU / peak;
        let diffusivity = |streak: f32| {
            let spread = f64::from(streak) * wavelength;
            spread * spread / (2.0 * f64::from(config.residual_decay))
        };
        let transport = Transport::new(
            f64::from(spectrum.wind_direction()),
            f64::from(config.drift) * f64::from(wind_speed),
            diffusivity(config.streak_length),
            diffusivity(config.streak_width),
            f64::from(length),
            determinism,
        );
        let points = n * n;
        let fft = RowFft::new(n, determinism);
        let mut foam = Foam {
            n,
            length,
            active: error::try_vec(points, 0.0)?,
            residual: error::try_vec(points, 0.0)?,
            total: error::try_vec(points, 0.0)?,
            breaking: error::try_vec(points, 0.0)?,
            coverage: FoamCoverage::default(),
            calibration,
            params,
            transport,
            tables: error::try_vec(2 * n, Complex32::default())?,
            tables_dt: f64::NAN,
            spatial: error::try_vec(points, Complex32::default())?,
            spectral: error::try_vec((n / 2 + 1) * n, Complex32::default())?,
            scratch: error::try_vec(n.div_ceil(ROWS) * fft.scratch_len(), Complex32::default())?,
            fft,
            row_sums: error::try_vec(n, [0.0; 3])?,
            simd: Simd::detect(),
        };
        foam.refresh(cascades);
        Ok(foam)
    }

    /// Recomputes the breaking intensity from the cascades as they are now (after a jump in
    /// time or a restore), and the total foam and coverage from the state
    /// ([`finish`](Self::finish)). Not on the per-frame path (a step with dt > 0 computes
    /// the intensity in its first pass), so the intensity has a pass of its own.
    pub(crate) fn refresh(&mut self, cascades: &[Cascade]) {
        let n = self.n;
        let params = self.params;
        let simd = self.simd;
        let first = &cascades[0];
        self.breaking
            .par_chunks_mut(ROWS * n)
            .with_min_len(min_tasks(n))
            .enumerate()
            .for_each(|(b, breaking)| {
                for (r, s) in breaking.chunks_mut(n).enumerate() {
                    let gradient = first.gradient_row(b * ROWS + r).values();
                    simd.run(
                        #[inline(always)]
                        || params.intensity_row(gradient, s),
                    );
                }
            });
        self.finish();
    }

    /// Integrates the foam over `dt` seconds up to the cascades' (new) time.
    ///
    /// Three passes over the grid, each one parallel loop over blocks of [`ROWS`] rows:
    /// 1. per row z: the new intensity, the aging of a and r, and r transformed along x, two
    ///    rows in one complex transform (or, with no transport, the total foam and the row
    ///    sums straight away);
    /// 2. per block of m_x = 0 … N/2 (r is real, so its transform at −m_x is the conjugate of
    ///    that at m_x): the block gathered by a tiled transpose, transformed along z, the
    ///    factor M(k) of the transport (see `transport.rs`), and transformed back along z;
    /// 3. per block of z: gathered back, transformed along x, two rows in one complex
    ///    transform, the residual foam (clamped to [0, 1], flushed below [`FLUSH`]), the
    ///    total foam and the row sums.
    ///
    /// The forward transform is the conjugate of the inverse transform of the real r. Packing
    /// two real rows in one complex row and transforming half the columns halves the
    /// transforms, transposes and factors of a complex transport, to the same result within
    /// the transforms' rounding (tested against two plain `Fft2d` transforms). Active foam
    /// stays where its wave broke (the grid already follows the water's orbital motion; the
    /// drift moves it less than a metre in its lifetime).
    pub(crate) fn advance(&mut self, cascades: &[Cascade], dt: f64) {
        if dt <= 0.0 {
            // The same time: the intensity is recomputed (bit for bit the same), nothing
            // else changes.
            self.refresh(cascades);
            return;
        }
        let n = self.n;
        let moving = self.transport.is_active();
        if moving {
            // A game steps by the same dt frame after frame: the tables (2N sines and cosines
            // in f64, a few per cent of the foam at 64²) are a function of dt alone.
            if dt.to_bits() != self.tables_dt.to_bits() {
                self.transport.fill_tables(dt, n, &mut self.tables);
                self.tables_dt = dt;
            }
        }
        let Foam {
            active,
            residual,
            breaking,
            total,
            row_sums,
            spatial,
            spectral,
            fft,
            scratch,
            tables,
            transport,
            params,
            simd,
            ..
        } = self;
        let (params, simd, fft) = (*params, *simd, &*fft);
        let step = params.step(dt as f32);
        let first = &cascades[0];
        let block = ROWS * n;
        let s = fft.scratch_len();
        let min_len = min_tasks(n);
        // 1. Intensity and aging row by row; r transformed along x.
        (
            active.par_chunks_mut(block),
            residual.par_chunks_mut(block),
            breaking.par_chunks_mut(block),
            total.par_chunks_mut(block),
            row_sums.par_chunks_mut(ROWS),
            spatial.par_chunks_mut(block),
            scratch.par_chunks_mut(s),
        )
            .into_par_iter()
            .with_min_len(min_len)
            .enumerate()
            .for_each(
                |(b, (active, residual, breaking, total, sums, work, scratch))| {
                    let rows = active
                        .chunks_mut(n)
                        .zip(residual.chunks_mut(n))
                        .zip(breaking.chunks_mut(n))
                        .zip(work.chunks_mut(n))
                        .zip(total.chunks_mut(n).zip(sums.iter_mut()));
                    for (r, ((((a, rr), s), w), (f, sum))) in rows.enumerate() {
                        let gradient = first.gradient_row(b * ROWS + r).values();
                        simd.run(
                            #[inline(always)]
                            || {
                                params.react_row(&step, gradient, a, rr, s, w);
                                if !moving {
                                    *sum = total_row(a, rr, f);
                                }
                            },
                        );
                    }
                    if moving {
                        for pair in work.chunks_exact_mut(2 * n) {
                            let (a, b) = pair.split_at_mut(n);
                            simd.run(
                                #[inline(always)]
                                || pack_rows(a, b),
                            );
                            fft.process(a, scratch);
                            simd.run(
                                #[inline(always)]
                                || unpack_halves(a, b),
                            );
                        }
                    }
                },
            );
        if !moving {
            self.sum_rows();
            return;
        }
        // 2. Columns: along z, the transport's factor, back along z. The block's rows are
        // m_x = j0 … j0 + ROWS − 1, its columns m_z (then z).
        let [ca, cb, cc] = transport.exponent(dt);
        let tables = &*tables;
        let source = &*spatial;
        let half = n / 2 + 1;
        spectral
            .par_chunks_mut(block)
            .zip(scratch.par_chunks_mut(s))
            .with_min_len(min_len)
            .enumerate()
            .for_each(|(b, (rows, scratch))| {
                let j0 = b * ROWS;
                let height = rows.len() / n;
                transpose_into(&source[j0..], n, rows, n, height, n);
                fft.process(rows, scratch);
                let shifts = &tables[n..2 * n];
                for (r, row) in rows.chunks_mut(n).enumerate() {
                    let ix = j0 + r;
                    let mx = crate::grid::wave_index(ix, n) as f32;
                    let shift_x = tables[ix];
                    let (ax, bx) = (ca * mx * mx, 2.0 * cb * mx);
                    simd.run(
                        #[inline(always)]
                        || {
                            for (iz, (g, shift_z)) in row.iter_mut().zip(shifts).enumerate() {
                                let mz = crate::grid::wave_index(iz, n) as f32;
                                let decay = exp(-(ax + mz * (bx + cc * mz)));
                                *g = g.conj() * (shift_x * shift_z) * decay;
                            }
                        },
                    );
                }
                fft.process(rows, scratch);
            });
        // 3. Rows again: gathered, along x, and the residual foam, the total foam and the row
        // sums of `finish` while the row is in cache.
        let scale = 1.0 / (n * n) as f32;
        let flush = |v: f32| if v < FLUSH { 0.0 } else { v.min(1.0) };
        let source = &*spectral;
        (
            spatial.par_chunks_mut(block),
            scratch.par_chunks_mut(s),
            residual.par_chunks_mut(block),
            active.par_chunks(block),
            total.par_chunks_mut(block),
            row_sums.par_chunks_mut(ROWS),
        )
            .into_par_iter()
            .with_min_len(min_len)
            .enumerate()
            .for_each(|(b, (work, scratch, residual, active, total, sums))| {
                let j0 = b * ROWS;
                let height = work.len() / n;
                transpose_into(&source[j0..], n, work, n, height, half);
                let rows = residual
                    .chunks_mut(2 * n)
                    .zip(work.chunks_exact_mut(2 * n))
                    .zip(active.chunks(2 * n))
                    .zip(total.chunks_mut(2 * n))
                    .zip(sums.chunks_mut(2));
                for ((((r, pair), a), f), sums) in rows {
                    let (v, w) = pair.split_at_mut(n);
                    simd.run(
                        #[inline(always)]
                        || repack_halves(v, w),
                    );
                    fft.process(v, scratch);
                    let (r0, r1) = r.split_at_mut(n);
                    let (a0, a1) = a.split_at(n);
                    let (f0, f1) = f.split_at_mut(n);
                    simd.run(
                        #[inline(always)]
                        || {
                            for ((r0, r1), v) in r0.iter_mut().zip(r1.iter_mut()).zip(&*v) {
                                *r0 = flush(v.re * scale);
                                *r1 = flush(v.im * scale);
                            }
                            sums[0] = total_row(a0, r0, f0);
                            sums[1] = total_row(a1, r1, f1);
                        },
                    );
                }
            });
        self.sum_rows();
    }

    /// The total foam a + r(1 − a) and the coverage: each row summed in f64 in [`LANES`]
    /// interleaved partial sums (column i into sum i mod `LANES`, so that the loop vectorises
    /// and its order is fixed by the code, not by the SIMD level), those added in order, and
    /// the rows added in order.
    fn finish(&mut self) {
        let n = self.n;
        let simd = self.simd;
        (
            self.active.par_chunks(ROWS * n),
            self.residual.par_chunks(ROWS * n),
            self.total.par_chunks_mut(ROWS * n),
            self.row_sums.par_chunks_mut(ROWS),
        )
            .into_par_iter()
            .with_min_len(min_tasks(n))
            .for_each(|(active, residual, total, sums)| {
                let rows = active
                    .chunks(n)
                    .zip(residual.chunks(n))
                    .zip(total.chunks_mut(n));
                for (((a, r), f), sum) in rows.zip(sums.iter_mut()) {
                    *sum = simd.run(
                        #[inline(always)]
                        || total_row(a, r, f),
                    );
                }
            });
        self.sum_rows();
    }

    /// The coverage from the row sums of [`finish`](Self::finish), added in order.
    fn sum_rows(&mut self) {
        let n = self.n;
        let mut sum = [0.0f64; 3];
        for row in &self.row_sums {
            for k in 0..3 {
                sum[k] += row[k];
            }
        }
        let points = (n * n) as f64;
        self.coverage = FoamCoverage {
            active: (sum[0] / points) as f32,
            residual: (sum[1] / points) as f32,
            total: (sum[2] / points) as f32,
        };
    }

    /// Runs the element loops at `simd` from now on (the tests force every level).
    #[cfg(test)]
    pub(crate) fn set_simd(&mut self, simd: Simd) {
        self.simd = simd;
    }

    /// Removes all foam (the breaking intensity, a function of the time, stays).
    pub(crate) fn clear(&mut self) {
        self.active.fill(0.0);
        self.residual.fill(0.0);
        self.finish();
    }

    /// Number of grid points.
    pub(crate) fn points(&self) -> usize {
        self.n * self.n
    }

    /// Periodic bilinear interpolation of `values` (a foam-grid buffer) at world (x, z); the
    /// wrap in f64.
    fn interpolate(&self, values: &[f32], x: f64, z: f64) -> f32 {
        let n = self.n;
        let length = f64::from(self.length);
        let cells = n as f64 / length;
        let split = |v: f64| {
            let g = v.rem_euclid(length) * cells;
            let cell = g.floor();
            ((cell as usize) % n, (g - cell) as f32)
        };
        let (ix, fx) = split(x);
        let (iz, fz) = split(z);
        let (ix1, iz1) = ((ix + 1) % n, (iz + 1) % n);
        let v = |i: usize, j: usize| values[j * n + i];
        let value = (1.0 - fz) * ((1.0 - fx) * v(ix, iz) + fx * v(ix1, iz))
            + fz * ((1.0 - fx) * v(ix, iz1) + fx * v(ix1, iz1));
        value.max(0.0)
    }

    /// The total foam at undisplaced world (x, z), in [0, 1].
    pub(crate) fn foam_at(&self, x: f64, z: f64) -> f32 {
        self.interpolate(&self.total, x, z).min(1.0)
    }
}

impl OceanState {
    /// Most steps [`pre_roll`](Self::pre_roll) takes.
    pub const MAX_PRE_ROLL_STEPS: usize = 1_000_000;

    /// The foam of the whole ocean in [0, 1] — active whitecaps and residual foam together,
    /// a + r(1 − a) — on the grid of cascade 0 (the largest): index j·N + i is its grid point
    /// (i·L/N, j·L/N), and the field tiles the plane with that cascade's period L. Only
    /// cascade 0's textures carry foam ([`OceanState::pack_texels`]).
    pub fn foam(&self) -> &[f32] {
        &self.foam.total
    }

    /// Active whitecap foam a in [0, 1] on the foam grid (see [`foam`](Self::foam)): foam of
    /// waves breaking now or within about [`FoamConfig::active_decay`].
    pub fn active_foam(&self) -> &[f32] {
        &self.foam.active
    }

    /// Residual foam r in [0, 1] on the foam grid (see [`foam`](Self::foam)): older foam that
    /// has aged out of the active whitecaps, drifting and stretched into streaks.
    pub fn residual_foam(&self) -> &[f32] {
        &self.foam.residual
    }

    /// The breaking intensity s ≥ 0 in 1/s at the current time on the foam grid (see
    /// [`foam`](Self::foam)): how fast the surface around each point starts to break — new
    /// breaking per second, as a fraction of the area, plus the area breaking now over τ_A —
    /// and so how fast active foam is injected there (it grows at s·(1 − a)). Large on the
    /// compressed crests of the largest waves, where the smaller ones break on top of them;
    /// near zero elsewhere. For spray particles and the sound of breaking waves.
    pub fn breaking(&self) -> &[f32] {
        &self.foam.breaking
    }

    /// The breaking intensity in 1/s at the undisplaced world point (`x`, `z`) (any finite
    /// coordinates: the foam grid wraps with cascade 0's period), interpolated bilinearly
    /// from [`breaking`](Self::breaking). For a point of the displaced surface, find its
    /// undisplaced point with [`locate`](Self::locate) first.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn breaking_at(&self, x: f64, z: f64) -> Result<f32, Error> {
        for (name, value) in [("x", x), ("z", z)] {
            if !value.is_finite() {
                return Err(Error::NonFinite { name });
            }
        }
        Ok(self.foam.interpolate(&self.foam.breaking, x, z))
    }

    /// The area fractions covered by active whitecaps, residual foam and all foam (summed in
    /// a fixed order over the foam grid when the foam last changed; costs nothing here).
    pub fn foam_coverage(&self) -> FoamCoverage {
        self.foam.coverage
    }

    /// The whitecap calibration of this ocean: the breaking threshold, the target coverage and
    /// what the statistics of the sea predict.
    pub fn foam_calibration(&self) -> FoamCalibration {
        self.foam.calibration
    }

    /// Pre-rolls the foam: clears it, goes back `seconds` before the current time and steps
    /// forward to it again in steps of `dt` (the last one shorter if `dt` does not divide
    /// `seconds`), so that the foam is spun up as if the sea had been running. The result
    /// depends only on the current time, `seconds`, `dt` and the ocean's spectrum and config,
    /// not on any earlier history: every client of a networked game, or every frame range of
    /// a bake, gets the same bits. Whitecaps reach their steady coverage within about five
    /// [`FoamConfig::active_decay`] (20 s by default), residual foam within about five
    /// [`FoamConfig::residual_decay`]. Allocates nothing inside a rayon pool.
    ///
    /// ```
    /// use ocean_fft::{OceanConfig, OceanState, Spectrum};
    /// let spectrum = Spectrum::jonswap(15.0, 200_000.0)?;
    /// let config = OceanConfig { size: 32, ..OceanConfig::default() };
    /// let mut ocean = OceanState::new(spectrum.clone(), config.clone())?;
    /// ocean.set_time(100.0)?;
    /// ocean.pre_roll(20.0, 0.05)?;               // s: 400 steps back from t = 80 s
    /// assert_eq!(ocean.time(), 100.0);
    ///
    /// // Another ocean with another history gets the same foam.
    /// let mut other = OceanState::new(spectrum, config)?;
    /// other.step(3.0)?;
    /// other.set_time(100.0)?;
    /// other.pre_roll(20.0, 0.05)?;
    /// assert_eq!(ocean.foam(), other.foam());
    /// # Ok::<(), ocean_fft::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for `dt` outside
    /// (0, [`MAX_STEP`](Self::MAX_STEP)], for `seconds` below 0 or above
    /// [`MAX_PRE_ROLL_STEPS`](Self::MAX_PRE_ROLL_STEPS)·`dt`, or (naming `time - seconds`) for
    /// a start before −[`Cascade::MAX_TIME`]. Nothing changes then.
    pub fn pre_roll(&mut self, seconds: f64, dt: f64) -> Result<(), Error> {
        error::in_range_f64("dt", dt, Excluded(0.0), Included(Self::MAX_STEP))?;
        let longest = dt * Self::MAX_PRE_ROLL_STEPS as f64;
        error::in_range_f64("seconds", seconds, Included(0.0), Included(longest))?;
        let end = self.time;
        let start = check_time("time - seconds", end - seconds)?;
        let steps = ((end - start) / dt).ceil() as usize;
        // The foam reads only cascade 0 (its breaking intensity is cascade 0's Jacobian with
        // the other cascades' statistics), so the roll updates cascade 0 alone and the others
        // once at the end: the same bits as updating all of them at every step, at a third of
        // the cost for the default three cascades.
        rayon::scope(|_| {
            self.cascades[0].update_checked(start);
            self.time = start;
            self.foam.clear();
            self.foam.refresh(&self.cascades);
            let mut previous = start;
            for k in 1..=steps {
                let t = if k == steps {
                    end
                } else {
                    (start + k as f64 * dt).min(end)
                };
                self.cascades[0].update_checked(t);
                self.time = t;
                self.foam.advance(&self.cascades, t - previous);
                previous = t;
            }
            self.update_cascades(end);
        });
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{OceanConfig, Spectrum};

    /// An ocean that never breaks (coverage 0) with a Gaussian blob of residual foam, σ₀ = 3
    /// grid points, in the middle of its 64² foam grid.
    fn blob_ocean(wind_direction: f32) -> (OceanState, [f64; 2], f64) {
        let spectrum = Spectrum::pierson_moskowitz(20.0)
            .and_then(|s| s.with_wind_direction(wind_direction))
            .unwrap();
        let config = OceanConfig {
            size: 64,
            lengths: vec![200.0, 46.0],
            foam: FoamConfig {
                coverage: 0.0,
                streak_length: 0.05,
                streak_width: 0.02,
                residual_decay: 30.0,
                ..FoamConfig::default()
            },
            ..OceanConfig::default()
        };
        let mut ocean = OceanState::new(spectrum, config).unwrap();
        let h = 200.0 / 64.0;
        let (centre, sigma) = ([100.0, 90.0], 3.0 * h);
        for j in 0..64 {
            for i in 0..64 {
                let (dx, dz) = (i as f64 * h - centre[0], j as f64 * h - centre[1]);
                let r = 0.5 * (-(dx * dx + dz * dz) / (2.0 * sigma * sigma)).exp();
                ocean.foam.residual[j * 64 + i] = r as f32;
            }
        }
        ocean.foam.finish();
        (ocean, centre, sigma)
    }

    /// Mass, centroid and covariance (m²) of the residual foam.
    fn moments(ocean: &OceanState) -> (f64, [f64; 2], [[f64; 2]; 2]) {
        let h = 200.0 / 64.0;
        let r = &ocean.foam.residual;
        let mass: f64 = r.iter().map(|&v| f64::from(v)).sum();
        let mut mean = [0.0; 2];
        let mut second = [[0.0; 2]; 2];
        for j in 0..64 {
            for i in 0..64 {
                let w = f64::from(r[j * 64 + i]) / mass;
                let p = [i as f64 * h, j as f64 * h];
                for a in 0..2 {
                    mean[a] += w * p[a];
                    for b in 0..2 {
                        second[a][b] += w * p[a] * p[b];
                    }
                }
            }
        }
        let cov = [0, 1].map(|a| [0, 1].map(|b| second[a][b] - mean[a] * mean[b]));
        (mass, mean, cov)
    }

    /// The transport against the closed form of advection-diffusion with constant
    /// coefficients: the blob's mass decays as e^{−t/τ_R} (nothing else acts on it), its
    /// centroid moves by u·t downwind and its covariance grows by 2K·t, with K∥ along the wind
    /// and K⊥ across (from the streak settings: (streak·λ_p)²/(2τ_R)).
    #[test]
    fn residual_blob_drifts_and_spreads_as_the_closed_form_says() {
        let wind = 0.6f32;
        let (mut ocean, centre, sigma) = blob_ocean(wind);
        let (mass0, _, _) = moments(&ocean);
        let t = 10.0;
        for _ in 0..20 {
            ocean.step(t / 20.0).unwrap();
        }
        let (mass, mean, cov) = moments(&ocean);
        let spectrum = ocean.spectrum();
        let k = spectrum
            .dispersion()
            .k_from_omega_f64(f64::from(spectrum.peak_omega()));
        let wavelength = std::f64::consts::TAU / k;
        let diffusivity = |streak: f64| (streak * wavelength).powi(2) / 60.0;
        let (along, across) = (diffusivity(0.05), diffusivity(0.02));
        let drift = 0.03 * 20.0;
        let (w, n) = (
            [f64::from(wind).cos(), f64::from(wind).sin()],
            [-f64::from(wind).sin(), f64::from(wind).cos()],
        );
        // f32 buffers and transforms, and the flush of foam below 1e-6 (the blob's far tails)
        // at every step: a relative error of a few 1e-5 on the mass.
        assert!(
            (mass / mass0 - (-t / 30.0f64).exp()).abs() < 2e-4,
            "{mass} {mass0}"
        );
        for a in 0..2 {
            let expected = centre[a] + drift * t * w[a];
            assert!((mean[a] - expected).abs() < 1e-3, "mean {mean:?}");
        }
        let form = |u: [f64; 2], v: [f64; 2]| {
            (0..2)
                .map(|a| (0..2).map(|b| u[a] * cov[a][b] * v[b]).sum::<f64>())
                .sum::<f64>()
        };
        let s2 = sigma * sigma;
        // The blob is 3 grid points wide and grows to 4–6: its tails beyond the tile and the
        // grid's Nyquist cut are far below 1e-3 of its variance.
        assert!(
            (form(w, w) - (s2 + 2.0 * along * t)).abs() < 1e-3 * s2,
            "{cov:?}"
        );
        assert!(
            (form(n, n) - (s2 + 2.0 * across * t)).abs() < 1e-3 * s2,
            "{cov:?}"
        );
        assert!(form(w, n).abs() < 1e-3 * s2, "{cov:?}");
        assert!(
            along > 2.0 * across && along * t > s2 / 4.0,
            "{along} {across}"
        );
    }

    /// The foam's element loops (intensity, aging, transport multipliers, totals and sums)
    /// give the same bits at every SIMD level the machine has and at 1, 2 and 3 threads, as
    /// the baseline build at 1 thread: the active, residual and total foam, the intensity and
    /// the coverage after steps with breaking, residual foam and transport, a refresh (a jump
    /// in time) and a pre-roll.
    #[test]
    fn every_simd_level_and_thread_count_gives_the_same_foam() {
        let levels = Simd::available();
        // On a CPU with AVX-512 (as the project's machines) all three levels must be covered,
        // or the test would pass vacuously.
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx512f") && std::is_x86_feature_detected!("avx512bw") {
            assert_eq!(levels.len(), 3, "{levels:?}");
        }
        let pools = crate::simd::test_pools();
        let run = |level: Simd, pool: &rayon::ThreadPool| {
            pool.install(|| {
                let spectrum = Spectrum::jonswap(16.0, 300_000.0).unwrap();
                let config = OceanConfig {
                    size: 64,
                    ..OceanConfig::default()
                };
                let mut ocean = OceanState::new(spectrum, config).unwrap();
                ocean.foam.set_simd(level);
                ocean.set_time(500.0).unwrap();
                let mut bits: Vec<u32> = Vec::new();
                let mut record = |ocean: &OceanState| {
                    let foam = &ocean.foam;
                    for buffer in [&foam.active, &foam.residual, &foam.total, &foam.breaking] {
                        bits.extend(buffer.iter().map(|v| v.to_bits()));
                    }
                    let c = ocean.foam_coverage();
                    bits.extend([c.active, c.residual, c.total].map(f32::to_bits));
                };
                for _ in 0..40 {
                    ocean.step(0.1).unwrap();
                }
                record(&ocean);
                ocean.set_time(731.25).unwrap();
                record(&ocean);
                ocean.pre_roll(3.0, 1.0 / 30.0).unwrap();
                record(&ocean);
                let coverage = ocean.foam_coverage();
                assert!(
                    coverage.active > 1e-3 && coverage.residual > 1e-4,
                    "the test needs foam: {coverage:?}"
                );
                bits
            })
        };
        let expected = run(Simd::Baseline, &pools[0].1);
        for &level in &levels {
            for (threads, pool) in &pools {
                assert!(
                    run(level, pool) == expected,
                    "{level:?} at {threads} threads differs from the baseline at 1 thread"
                );
            }
        }
    }

    /// The fused real-data step (two rows packed in one complex row, half the columns
    /// transformed, the transport's factor between the two column transforms, the last row
    /// transform fused with the totals) gives, to the rounding of the transforms, what the
    /// plain complex sequence gives: the residual foam after aging, transformed by the public
    /// `Fft2d`, multiplied by M(k) point by point, transformed back by `Fft2d`, scaled,
    /// clamped and flushed. Run for both determinism modes and two grid sizes, at 1 and 2
    /// threads; the reference runs at the baseline SIMD level, the step at the machine's
    /// widest.
    #[test]
    fn real_data_transport_matches_two_plain_complex_fft2d_transforms() {
        let pools = crate::simd::test_pools();
        for determinism in [Determinism::SameMachine, Determinism::CrossPlatform] {
            for (n, threads) in [(64, 1), (64, 2), (128, 2)] {
                let (_, pool) = &pools[threads - 1];
                pool.install(|| {
                    let spectrum = Spectrum::jonswap(16.0, 300_000.0).unwrap();
                    let config = OceanConfig {
                        size: n,
                        determinism,
                        ..OceanConfig::default()
                    };
                    let mut ocean = OceanState::new(spectrum, config).unwrap();
                    for _ in 0..30 {
                        ocean.step(0.1).unwrap();
                    }
                    let dt = 0.1;
                    // The same step without transport: the aged foam the transport starts from.
                    let mut reference = ocean.foam.clone();
                    let transport = reference.transport.clone();
                    assert!(transport.is_active());
                    reference.transport.drift = [0.0; 2];
                    reference.transport.tensor = [0.0; 3];
                    ocean.step(dt).unwrap();
                    reference.advance(&ocean.cascades, dt);
                    let mut tables = vec![Complex32::default(); 2 * n];
                    transport.fill_tables(dt, n, &mut tables);
                    let [a, b, c] = transport.exponent(dt);
                    let mut fft = crate::Fft2d::with_determinism(n, 1, determinism).unwrap();
                    let mut work: Vec<Complex32> = reference
                        .residual
                        .iter()
                        .map(|&r| Complex32::new(r, 0.0))
                        .collect();
                    // The transform is left transposed: index m_x·N + m_z.
                    let spectrum = fft.process(&mut work).unwrap().to_vec();
                    for ix in 0..n {
                        let mx = crate::grid::wave_index(ix, n) as f32;
                        for iz in 0..n {
                            let mz = crate::grid::wave_index(iz, n) as f32;
                            let (ax, bx) = (a * mx * mx, 2.0 * b * mx);
                            let decay = exp(-(ax + mz * (bx + c * mz)));
                            work[ix * n + iz] = spectrum[ix * n + iz].conj()
                                * (tables[ix] * tables[n + iz])
                                * decay;
                        }
                    }
                    let moved = fft.process(&mut work).unwrap();
                    let scale = 1.0 / (n * n) as f32;
                    let mut moving = 0;
                    let (mut worst, mut peak) = (0.0f32, 0.0f32);
                    for (k, v) in moved.iter().enumerate() {
                        let r = v.re * scale;
                        let r = if r < FLUSH { 0.0 } else { r.min(1.0) };
                        worst = worst.max((r - ocean.foam.residual[k]).abs());
                        peak = peak.max(r);
                        moving += usize::from(r != reference.residual[k]);
                    }
                    // Two transforms of N² points in f32 round each value to about
                    // ε·log₂(N²) ≈ 6e-8 × 14 of the largest (8e-7); the real-data transform
                    // rounds in other places (and keeps only the Hermitian part at the
                    // Nyquist wave numbers, which hold next to nothing), so it may differ by
                    // that much, not more. Measured: 1.5e-8 at a peak of 0.09.
                    assert!(
                        worst <= 1e-6 * peak,
                        "{determinism:?} N = {n}, {threads} threads: {worst:e} (peak {peak})"
                    );
                    assert!(moving > n * n / 2, "the test needs foam that moves");
                    for (x, y) in ocean.foam.active.iter().zip(&reference.active) {
                        assert_eq!(x.to_bits(), y.to_bits());
                    }
                });
            }
        }
    }

    /// Steps compose exactly: twenty steps of 0.5 s move the blob as ten of 1 s and one of
    /// 10 s, to the rounding of the transforms (1e-7 of the peak per step) and the flush of
    /// values below 1e-6 at each step.
    #[test]
    fn transport_steps_compose() {
        let runs: Vec<Vec<f32>> = [(20, 0.5), (10, 1.0), (1, 10.0)]
            .iter()
            .map(|&(steps, dt)| {
                let (mut ocean, _, _) = blob_ocean(2.2);
                for _ in 0..steps {
                    ocean.step(dt).unwrap();
                }
                ocean.foam.residual.clone()
            })
            .collect();
        for other in &runs[1..] {
            let worst = runs[0]
                .iter()
                .zip(other)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0f32, f32::max);
            assert!(worst < 1e-5, "{worst}");
        }
    }
}
