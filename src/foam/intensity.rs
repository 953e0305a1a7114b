//! The breaking intensity (where and how fast the summed surface starts to break: the
//! fraction below the threshold over τ_A plus Rice's rate of new breaking, docs/theory.md
//! §15.2) and the aging of active into residual foam over a step, point by point.

use num_complex::Complex32;

use super::moments::GradientMoments;
use crate::math::exp::exp;

/// Points of a row the foam's element loops handle at once, through arrays on the stack.
pub(super) const BLOCK: usize = 64;

/// The per-point constants of the foam update.
///
/// The intensity works on the gradient scaled by `unit` = c (a power of two, 1 unless the sea
/// is extreme), with c in place of the 1 of J = (1 + D_xx)(1 + D_zz) − D_xz²: every quantity of
/// the intensity is then its unscaled value times a power of c, so in f32's normal range the
/// result has the same bits as unscaled. The unscaled sums reach the fourth power of the
/// gradient and the square of its rate, which overflow f32 on seas the cascades accept (a
/// gradient of 1e15 at most); scaled, the gradient's standard deviation is at most
/// [`SCALE_LIMIT`] and so is its rate's (in 1/s, after a scale d of its own, undone in
/// `crossing_scale`).
#[derive(Debug, Clone, Copy)]
pub(super) struct Params {
    /// The breaking threshold J_b (−∞: nothing breaks), times c².
    pub(super) threshold: f32,
    /// The scale c of the gradient, a power of two in (0, 1].
    pub(super) unit: f32,
    /// Covariance of the unresolved gradient (cascades 1 and up) as (AA, BB, CC, AB, AC, BC),
    /// times c².
    pub(super) unresolved: [f32; 6],
    /// Covariance of the rate of the whole gradient, the same way, in 1/s², times (cd)².
    pub(super) rate: [f32; 6],
    /// Variance added to the unresolved part everywhere, (0.05 σ_T)² times c⁴: keeps a
    /// one-cascade ocean's intensity a smooth function of J.
    pub(super) floor: f32,
    /// 1/(√(2π) d): Rice's rate's constant with the rate's scale d undone.
    pub(super) crossing_scale: f32,
    pub(super) inv_active: f32,
    pub(super) inv_residual: f32,
}

/// Largest standard deviation, after scaling, of the gradient (dimensionless) and of its rate
/// (1/s) the intensity works at. A point's gradient is within √2·N standard deviations of 0
/// (its fields are sums over N² wave vectors; Cauchy–Schwarz), N ≤ 4096, so the intensity's
/// largest sums (σ², the discriminant and the rate's quadratic form, of order |∇J|²·|U|²)
/// stay below 2⁶⁴, far inside f32; the smallest that matters, the floor, stays above 2⁻⁸⁴ for
/// any sea the cascades accept (a gradient of at most 1e15).
const SCALE_LIMIT: f64 = 256.0;

/// The power of two 2⁻ᵉ (e ≥ 0, the smallest) that brings `deviation` down to at most
/// [`SCALE_LIMIT`]; 1 for a deviation that is not finite.
fn scale_for(deviation: f64) -> f64 {
    let mut scale = 1.0;
    if deviation.is_finite() {
        // Exact halvings; at most 1017 for f64::MAX.
        while deviation * scale > SCALE_LIMIT {
            scale *= 0.5;
        }
    }
    scale
}

impl Params {
    /// The constants of the foam update: the breaking `threshold` and the compression's
    /// standard deviation `compression_std` of the calibration, the moments of the gradient
    /// of the unresolved cascades and of all of them, and the lifetimes of active and
    /// residual foam in seconds.
    pub(super) fn new(
        threshold: f32,
        compression_std: f32,
        unresolved: &GradientMoments,
        total: &GradientMoments,
        active_decay: f32,
        residual_decay: f32,
    ) -> Params {
        let trace = |m: &[[f64; 3]; 3]| m[0][0] + m[1][1] + m[2][2];
        let c = scale_for(trace(&total.value).max(0.0).sqrt());
        let d = scale_for(c * trace(&total.rate).max(0.0).sqrt());
        let c2 = (c * c) as f32;
        let floor = 0.05 * compression_std * c2;
        Params {
            threshold: threshold * c2,
            unit: c as f32,
            unresolved: packed(&unresolved.value, c * c),
            rate: packed(&total.rate, (c * d) * (c * d)),
            floor: (floor * floor).max(f32::MIN_POSITIVE),
            crossing_scale: INV_SQRT_TAU / d as f32,
            inv_active: 1.0 / active_decay,
            inv_residual: 1.0 / residual_decay,
        }
    }
}

/// gᵀ M g for a symmetric M stored as (AA, BB, CC, AB, AC, BC).
#[inline(always)]
pub(super) fn quadratic_form(m: &[f32; 6], g: [f32; 3]) -> f32 {
    m[0] * g[0] * g[0]
        + m[1] * g[1] * g[1]
        + m[2] * g[2] * g[2]
        + 2.0 * (m[3] * g[0] * g[1] + m[4] * g[0] * g[2] + m[5] * g[1] * g[2])
}

/// The symmetric 3×3 `m` times `scale` as (AA, BB, CC, AB, AC, BC), in f32.
fn packed(m: &[[f64; 3]; 3], scale: f64) -> [f32; 6] {
    [m[0][0], m[1][1], m[2][2], m[0][1], m[0][2], m[1][2]].map(|v| (v * scale) as f32)
}

/// 1/√(2π).
pub(super) const INV_SQRT_TAU: f32 = 0.398_942_3;

/// Q(x) = 1 − Φ(x) for x ≥ 0 from φ(x) = e^{−x²/2}/√(2π), by the approximation of
/// Börjesson & Sundberg (1979): Q ≈ φ(x)/((1 − a)x + a√(x² + b)), a = 0.339, b = 5.510,
/// relative error below 0.3 % for every x ≥ 0.
#[inline(always)]
pub(super) fn upper_tail(x: f32, density: f32) -> f32 {
    density / (0.661 * x + 0.339 * (x * x + 5.51).sqrt())
}

/// Φ(x) and φ(x) of the standard normal at a crossing x, from one exponential (Φ in the lower
/// tail with full relative accuracy); beyond |x| = 12 (φ < 1e-31) exactly 0 or 1 and 0, and so
/// for x = ±∞. Branch-free.
#[inline(always)]
pub(super) fn normal_at(x: f32) -> (f32, f32) {
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

/// ∇J of the Jacobian J = (u + D_xx)(u + D_zz) − D_xz² with respect to (D_xx, D_zz, D_xz),
/// for the gradient and the 1 scaled by `unit` = u.
#[inline(always)]
pub(super) fn jacobian_gradient(g: [f32; 3], unit: f32) -> [f32; 3] {
    let [xx, zz, xz] = g;
    [unit + zz, unit + xx, -2.0 * xz]
}

/// What the first stage of the intensity hands to the others (see [`Params::roots`]). The
/// stages are functions of plain values because a closure over σ, β and ∇J kept the loop over
/// points from vectorising (docs/performance.md, "The foam").
#[derive(Clone, Copy)]
pub(super) struct Roots {
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
    /// §15). For a finite threshold (the caller handles J_b = −∞), with the gradient and the
    /// 1 of J scaled by `unit` (the caller passes [`Params::unit`], or the constant 1 when it
    /// is 1, which then costs nothing).
    ///
    /// Branch-free, so that a loop over points vectorises: both roots are computed whatever
    /// their number, and selects pick the result. J − J_b = a2·x² + σx + c in x; where a2 = 0
    /// (J linear in x) the root the stable formula gives first is set to −∞, where φ = 0 and
    /// Φ = 0, which leaves P(J < J_b) = Φ(x₁) and one crossing.
    #[inline(always)]
    pub(super) fn intensity(&self, g: [f32; 3], unit: f32) -> f32 {
        let g = g.map(|v| v * unit);
        let r = self.roots(g, unit);
        let (cdf_lo, density_lo) = normal_at(r.lo);
        let (cdf_hi, density_hi) = normal_at(r.hi);
        let episodes = self.crossing_rate(r.lo, density_lo, r.sigma, g, unit, r.beta)
            + self.crossing_rate(r.hi, density_hi, r.sigma, g, unit, r.beta);
        self.combine(r.a2, r.disc, r.slope, cdf_lo, cdf_hi, episodes)
    }

    /// The first stage of [`intensity`](Self::intensity): σ, β, the quadratic in x and its
    /// roots, for the scaled gradient `g`.
    #[inline(always)]
    fn roots(&self, g: [f32; 3], unit: f32) -> Roots {
        let [xx, zz, xz] = g;
        let jacobian = (unit + xx) * (unit + zz) - xz * xz;
        let gradient = jacobian_gradient(g, unit);
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
    fn crossing_rate(
        &self,
        x: f32,
        density: f32,
        sigma: f32,
        g: [f32; 3],
        unit: f32,
        beta: [f32; 3],
    ) -> f32 {
        let gradient = jacobian_gradient(g, unit);
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
        let crossing = episodes * self.crossing_scale / slope + fraction * self.inv_active;
        // No crossing (disc ≤ 0): J is above J_b everywhere if it opens upward, below if
        // downward.
        let uniform = if a2 < 0.0 { self.inv_active } else { 0.0 };
        if disc > 0.0 {
            crossing
        } else {
            uniform
        }
    }

    /// The breaking intensity at each point of a row of cascade 0's gradient, into `out` (as long).
    /// Inlined into its caller's [`Simd::run`](crate::math::simd::Simd::run), so that its loop is
    /// compiled for the caller's SIMD level; every level gives the same bits (no reduction, no
    /// FMA).
    #[inline(always)]
    pub(super) fn intensities(&self, gradient: &[[f32; 3]], out: &mut [f32]) {
        if self.threshold == f32::NEG_INFINITY {
            // Nothing breaks.
            out.fill(0.0);
            return;
        }
        // An ordinary sea (c = 1) runs the loop with the scale a constant, which the compiler
        // folds away: the scaling costs it nothing.
        if self.unit == 1.0 {
            for (g, s) in gradient.iter().zip(out.iter_mut()) {
                *s = self.intensity(*g, 1.0);
            }
        } else {
            for (g, s) in gradient.iter().zip(out.iter_mut()) {
                *s = self.intensity(*g, self.unit);
            }
        }
    }

    /// The breaking intensity along a row of cascade 0's gradient into `out` (as long), in
    /// blocks of [`BLOCK`] points through an array on the stack, as [`react_row`] does.
    /// Inlined into its caller's [`Simd::run`](crate::math::simd::Simd::run).
    ///
    /// [`react_row`]: Self::react_row
    #[inline(always)]
    pub(super) fn intensity_row(&self, gradient: &[[f32; 3]], out: &mut [f32]) {
        let n = out.len();
        for start in (0..n).step_by(BLOCK) {
            let len = BLOCK.min(n - start);
            let mut fresh = [0.0f32; BLOCK];
            self.intensities(&gradient[start..start + len], &mut fresh[..len]);
            out[start..start + len].copy_from_slice(&fresh[..len]);
        }
    }

    /// One row of the step: the new intensity from cascade 0's `gradient`, the active and residual
    /// foam `a`, `r` aged with the intensity going from `s` (replaced by the new one) to it, and
    /// the residual foam copied into the transform's input `w`. In blocks of [`BLOCK`] points
    /// through arrays on the stack (written straight into the five row slices, the loop did not
    /// vectorise). Inlined into its caller's [`Simd::run`](crate::math::simd::Simd::run).
    #[inline(always)]
    pub(super) fn react_row(
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
    pub(super) fn step(&self, dt: f32) -> Step {
        Step { dt }
    }

    /// Active and residual foam after a step with the intensity going from `old` to `new`
    /// (trapezoidal mean held over the step, the linear equations solved exactly).
    /// Branch-free.
    #[inline(always)]
    pub(super) fn react(
        &self,
        step: &Step,
        active: f32,
        residual: f32,
        old: f32,
        new: f32,
    ) -> (f32, f32) {
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
pub(super) fn mean_factor(x: f32, e: f32) -> f32 {
    let direct = (1.0 - e) / x;
    let series = 1.0 - x * (0.5 - x / 6.0);
    if x > 1e-3 {
        direct
    } else {
        series
    }
}

/// What every point's update over one step shares.
#[derive(Debug, Clone, Copy)]
pub(super) struct Step {
    pub(super) dt: f32,
}
