//! The foam's detail: where inside a cell of the coarse foam grid (cascade 0's) the foam lies
//! (docs/theory.md §15.8). The coarse grid holds the expected fractions a (active) and r
//! (residual); the detail thresholds a zero-mean, unit-variance Gaussian field at the quantile
//! that keeps those fractions in expectation:
//!
//! - active whitecaps on the finer cascades' compression u = Σ_{c ≥ 1} (1 − J_c), standardised by
//!   its analytic standard deviation at the point (the bilinear interpolation of each cascade's
//!   Jacobian loses variance between nodes, by a known amount);
//! - residual foam on a world-anchored streak field, long along the wind and thin across it,
//!   carried with the water (the wind drift accumulated by the steps; the orbital motion is
//!   that of the undisplaced point itself).
//!
//! The threshold is a soft ramp ρ(t) = clamp((t − q)/(2w) + ½, 0, 1) of half-width w, and q(f)
//! solves E\[ρ\] = f for a standard normal t; the inverse is tabulated once, in f64 with the
//! functions of the ocean's determinism mode.

use crate::cascade::Cascade;
use crate::math::determinism::Math;
use crate::math::periodic::{cell_on, wrap, Period, Stencil};
use crate::math::rng::gaussian_pair;

use super::FoamCoverage;

/// Step of the quantile table in standard deviations (the edges below are whole multiples).
const STEP: f64 = 1.0 / 256.0;
/// The table covers thresholds q in [−`REACH`, `REACH`] standard deviations.
const REACH: f64 = 8.0;
/// Half-width w of the soft edge of active foam, in standard deviations of the compression:
/// 20 table steps (0.078).
pub(super) const ACTIVE_EDGE: usize = 20;
/// Half-width w of the soft edge of residual foam, in standard deviations of the streak field:
/// 32 table steps (0.125).
pub(super) const RESIDUAL_EDGE: usize = 32;

/// Texels of the streak field along the wind and across it.
pub(super) const STREAK_ALONG: usize = 128;
pub(super) const STREAK_ACROSS: usize = 512;
/// Spacing of the streak field's texels along and across the wind, m (a tile of 256 m × 128 m).
const ALONG_SPACING: f64 = 2.0;
const ACROSS_SPACING: f64 = 0.25;
/// Standard deviations of the Gaussian kernels that smooth white noise into the streak field,
/// along and across the wind, m: its correlation falls to 1/e at twice these, 12 m and 1 m.
const ALONG_KERNEL: f64 = 6.0;
const ACROSS_KERNEL: f64 = 0.5;
/// Mixed into cascade 0's seed for the streak field's noise.
const STREAK_SEED: u64 = 0x5f0a_3d7e_c41b_9265;

/// Bytes of the detail's tables: the quantile table and the streak field.
pub(crate) const DETAIL_BYTES: usize =
    4 * ((2.0 * REACH / STEP) as usize + 1) * 2 + 4 * STREAK_ALONG * STREAK_ACROSS;

/// E\[ρ\] as a function of the threshold q for one edge half-width: `mean[i]` at
/// q = −REACH + (i + edge)·STEP, decreasing in i.
#[derive(Debug, Clone)]
pub(super) struct Quantiles {
    mean: Vec<f32>,
    /// q of `mean[0]`.
    first: f32,
    /// w, in standard deviations.
    pub(super) edge: f32,
}

impl Quantiles {
    /// The table for a half-width of `edge` table steps, with the functions of `M`: Q(t) by
    /// the trapezoidal rule from the right on steps of 1/256 (error below 1e-6 of φ), its
    /// integral H(t) = ∫_t^∞ Q the same way, and E(q) = (H(q − w) − H(q + w))/(2w), exact
    /// for the tabulated Q since w is a whole number of steps.
    pub(super) fn new<M: Math>(edge: usize) -> Quantiles {
        let points = (2.0 * REACH / STEP) as usize + 1;
        let t = |i: usize| -REACH + i as f64 * STEP;
        let density = |i: usize| M::exp(-0.5 * t(i) * t(i)) / std::f64::consts::TAU.sqrt();
        let mut tail = vec![0.0f64; points];
        for i in (0..points - 1).rev() {
            tail[i] = tail[i + 1] + 0.5 * STEP * (density(i) + density(i + 1));
        }
        let mut area = vec![0.0f64; points];
        for i in (0..points - 1).rev() {
            area[i] = area[i + 1] + 0.5 * STEP * (tail[i] + tail[i + 1]);
        }
        let w = edge as f64 * STEP;
        let mean = (edge..points - edge)
            .map(|i| ((area[i - edge] - area[i + edge]) / (2.0 * w)) as f32)
            .collect();
        Quantiles {
            mean,
            first: t(edge) as f32,
            edge: w as f32,
        }
    }

    /// The threshold q (standard deviations) at which E\[ρ\] is `fraction`: +∞ for no foam,
    /// −∞ for all of it, linear between the table's entries.
    #[inline]
    pub(super) fn threshold(&self, fraction: f32) -> f32 {
        // NaN counts as no foam.
        if fraction.is_nan() || fraction <= 0.0 {
            return f32::INFINITY;
        }
        if fraction >= 1.0 {
            return f32::NEG_INFINITY;
        }
        let mean = &self.mean;
        let i = mean.partition_point(|&e| e >= fraction);
        if i == 0 {
            return self.first;
        }
        if i == mean.len() {
            return self.first + (mean.len() - 1) as f32 * STEP as f32;
        }
        let (hi, lo) = (mean[i - 1], mean[i]);
        let s = if hi > lo {
            (hi - fraction) / (hi - lo)
        } else {
            0.0
        };
        self.first + ((i - 1) as f32 + s) * STEP as f32
    }

    /// The soft ramp ρ = clamp((t − q)/(2w) + ½, 0, 1) at standardised value `t` for the
    /// fraction `fraction` (exactly 0 where it is 0 and 1 where it is 1).
    #[inline]
    pub(super) fn ramp(&self, t: f32, fraction: f32) -> f32 {
        let q = self.threshold(fraction);
        if q == f32::INFINITY {
            return 0.0;
        }
        if q == f32::NEG_INFINITY {
            return 1.0;
        }
        ((t - q) / (2.0 * self.edge) + 0.5).clamp(0.0, 1.0)
    }
}

/// How much of a cascade's compression variance its bilinear interpolation keeps at a point
/// a fraction (fx, fz) across a cell: for a wave k the interpolant's amplitude² is
/// b(fx, k_xΔ)·b(fz, k_zΔ) with b(f, θ) = 1 − 2f(1 − f)(1 − cos θ), so the variance is
/// V₀ − 2f'ₓVₓ − 2f'_zV_z + 4f'ₓf'_zV_xz with f' = f(1 − f).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct BilinearVariance {
    /// (V₀, Vₓ, V_z, V_xz) of the compression −(D_xx + D_zz) at unit choppiness, whose
    /// multiplier is k: Σ 2|h0|² k² times 1, (1 − cos k_xΔ), (1 − cos k_zΔ) and both.
    parts: [f64; 4],
    /// E\[T²K\] with T = D_xx + D_zz and K = D_xx·D_zz − D_xz² at unit choppiness (Isserlis'
    /// theorem on the covariance of the gradient): 1 − J = −λT − λ²K has the third moment
    /// −3λ⁴E\[T²K\] to leading order.
    third: f64,
}

impl BilinearVariance {
    /// The variance parts of `cascade`'s amplitudes, with the functions of `M`.
    fn of<M: Math>(cascade: &Cascade) -> BilinearVariance {
        let n = cascade.size();
        let dk = f64::from(cascade.delta_k());
        let spacing = f64::from(cascade.length()) / n as f64;
        let h0 = cascade.h0();
        let mut parts = [0.0f64; 4];
        // Covariance of (A, B, C) = (D_xx, D_zz, D_xz).
        let mut cov = [[0.0f64; 3]; 3];
        for j in 0..n {
            let kz = f64::from(crate::math::grid::wave_index(j, n)) * dk;
            let cz = 1.0 - M::cos(kz * spacing);
            for i in 0..n {
                let weight = 2.0 * f64::from(h0[j * n + i].norm_sqr());
                if weight == 0.0 {
                    continue;
                }
                let kx = f64::from(crate::math::grid::wave_index(i, n)) * dk;
                let cx = 1.0 - M::cos(kx * spacing);
                let k2 = kx * kx + kz * kz;
                let v = weight * k2;
                let m = [kx * kx, kz * kz, kx * kz].map(|p| p / k2.sqrt());
                for (a, row) in cov.iter_mut().enumerate() {
                    for (b, value) in row.iter_mut().enumerate() {
                        *value += weight * m[a] * m[b];
                    }
                }
                parts[0] += v;
                parts[1] += v * cx;
                parts[2] += v * cz;
                parts[3] += v * cx * cz;
            }
        }
        let [[aa, ab, ac], [_, bb, bc], [_, _, cc]] = cov;
        let tt = aa + bb + 2.0 * ab;
        let tc = ac + bc;
        // E[T²AB] = E[A³B] + 2E[A²B²] + E[AB³]; E[T²C²] = σ_TT σ_CC + 2σ_TC².
        let t2ab = 3.0 * aa * ab + 2.0 * (aa * bb + 2.0 * ab * ab) + 3.0 * bb * ab;
        let t2cc = tt * cc + 2.0 * tc * tc;
        BilinearVariance {
            parts,
            third: t2ab - t2cc,
        }
    }

    /// The variance kept a fraction (`fx`, `fz`) across a cell, as a share of V₀·`scale`.
    #[inline]
    fn at(&self, fx: f32, fz: f32, scale: f32) -> f32 {
        let [v0, vx, vz, vxz] = self.parts.map(|v| v as f32);
        let (px, pz) = (fx * (1.0 - fx), fz * (1.0 - fz));
        scale * (v0 - 2.0 * px * vx - 2.0 * pz * vz + 4.0 * px * pz * vxz).max(0.0)
    }
}

/// The foam's detail fields and tables.
#[derive(Debug, Clone)]
pub(crate) struct Detail {
    active: Quantiles,
    residual: Quantiles,
    /// Per cascade c ≥ 1 (index c − 1), the compression variance its bilinear interpolation
    /// keeps.
    variance: Vec<BilinearVariance>,
    /// Σ V₀ of the cascades ≥ 1 when the detail was built: the sea's unresolved compression
    /// variance is read at every query and divided by it, so a change of weather rescales.
    built_variance: f64,
    /// The streak field, unit variance, row j along the wind, column i across it.
    streaks: Vec<f32>,
    /// The correlations of its neighbouring texels along and across the wind: its bilinear
    /// interpolation a fraction f across keeps (1 − f)² + f² + 2f(1 − f)ρ of the variance on
    /// each axis.
    neighbours: [f32; 2],
    /// ŵ = (cos θ_w, sin θ_w), the axis of the streaks.
    wind: [f64; 2],
    /// How far the water's surface layer has drifted since the foam was made, `[x, z]` m:
    /// the streak field is read at the undisplaced point minus this.
    pub(super) offset: [f64; 2],
}

impl Detail {
    /// The detail of an ocean whose cascades are `cascades` (cascade 0's seed seeds the
    /// streaks) and whose wind blows toward `wind_direction` (rad), with the functions of `M`.
    pub(super) fn new<M: Math>(cascades: &[Cascade], wind_direction: f64) -> Detail {
        let variance: Vec<BilinearVariance> = cascades[1..]
            .iter()
            .map(BilinearVariance::of::<M>)
            .collect();
        let built_variance = variance.iter().map(|v| v.parts[0]).sum();
        let (sin, cos) = M::sin_cos(wind_direction);
        let (streaks, neighbours) = streak_field::<M>(cascades[0].config().seed ^ STREAK_SEED);
        Detail {
            active: Quantiles::new::<M>(ACTIVE_EDGE),
            residual: Quantiles::new::<M>(RESIDUAL_EDGE),
            variance,
            built_variance,
            streaks,
            neighbours,
            wind: [cos, sin],
            offset: [0.0; 2],
        }
    }

    /// The streak field's value at undisplaced world (x, z), interpolated bilinearly and
    /// divided by the standard deviation that interpolation keeps there: unit variance.
    #[inline]
    pub(super) fn streak_at(&self, x: f64, z: f64) -> f32 {
        let (px, pz) = (x - self.offset[0], z - self.offset[1]);
        let [c, s] = self.wind;
        let along = px * c + pz * s;
        let across = pz * c - px * s;
        let length_a = STREAK_ALONG as f64 * ALONG_SPACING;
        let length_c = STREAK_ACROSS as f64 * ACROSS_SPACING;
        let ga = wrap(along, length_a, 1.0 / length_a) / ALONG_SPACING;
        let gc = wrap(across, length_c, 1.0 / length_c) / ACROSS_SPACING;
        let (ja, fa) = split(ga, STREAK_ALONG);
        let (ic, fc) = split(gc, STREAK_ACROSS);
        let (ja1, ic1) = ((ja + 1) % STREAK_ALONG, (ic + 1) % STREAK_ACROSS);
        let v = |j: usize, i: usize| self.streaks[j * STREAK_ACROSS + i];
        let row0 = v(ja, ic) * (1.0 - fc) + v(ja, ic1) * fc;
        let row1 = v(ja1, ic) * (1.0 - fc) + v(ja1, ic1) * fc;
        let kept = |f: f32, rho: f32| (1.0 - f) * (1.0 - f) + f * f + 2.0 * f * (1.0 - f) * rho;
        let variance = kept(fa, self.neighbours[0]) * kept(fc, self.neighbours[1]);
        (row0 * (1.0 - fa) + row1 * fa) / variance.sqrt()
    }

    /// The streak field laid out for a texture, its origin wrapped into one tile: the same
    /// coordinates [`streak_at`](Self::streak_at) computes, with the offset projected onto
    /// the wind's frame.
    pub(super) fn streaks(&self) -> super::FoamStreaks<'_> {
        let [c, s] = self.wind;
        let [ox, oz] = self.offset;
        let length_a = STREAK_ALONG as f64 * ALONG_SPACING;
        let length_c = STREAK_ACROSS as f64 * ACROSS_SPACING;
        let along = wrap(ox * c + oz * s, length_a, 1.0 / length_a);
        let across = wrap(oz * c - ox * s, length_c, 1.0 / length_c);
        super::FoamStreaks {
            texels: &self.streaks,
            across_texels: STREAK_ACROSS,
            along_texels: STREAK_ALONG,
            spacing: [ACROSS_SPACING as f32, ALONG_SPACING as f32],
            axis: [c as f32, s as f32],
            origin: [across as f32, along as f32],
            neighbour_correlation: [self.neighbours[1], self.neighbours[0]],
        }
    }

    /// The standardised compression of the cascades ≥ 1 at undisplaced world (x, z):
    /// Σ (1 − J_c) over the analytic standard deviation of that bilinear interpolation there,
    /// for a sea whose unresolved compression variance at unit choppiness is `variance`.
    /// `None` where it has none (one cascade, no choppiness, no waves).
    #[inline]
    pub(super) fn compression_at(
        &self,
        cascades: &[Cascade],
        variance: f64,
        x: f64,
        z: f64,
    ) -> Option<f32> {
        if !(self.built_variance > 0.0 && variance > 0.0) {
            return None;
        }
        let scale = (variance / self.built_variance) as f32;
        let mut sum = 0.0f32;
        let mut var = 0.0f32;
        let (mut nodes, mut third) = (0.0f32, 0.0f32);
        for (cascade, parts) in cascades[1..].iter().zip(&self.variance) {
            let n = cascade.size();
            let cell = cell_on(x, z, &Period::new(f64::from(cascade.length()), n));
            let (_, fx, _, fz) = cell;
            sum += 1.0 - Stencil::new(cell, n).scalar(cascade.jacobian());
            let chop2 = cascade.config().choppiness * cascade.config().choppiness;
            var += chop2 * parts.at(fx, fz, scale);
            nodes += chop2 * scale * parts.parts[0] as f32;
            third -= 3.0 * chop2 * chop2 * scale * scale * parts.third as f32;
        }
        if !(var > 0.0 && var.is_finite() && sum.is_finite()) {
            return None;
        }
        // Standardised, then brought to a standard normal by the first Cornish–Fisher term
        // of the skewness γ of the nodes' values: z = u − γ(u² − 1)/6 (γ = 0 where the
        // moments leave f32's range).
        let u = sum / var.sqrt();
        let skew = third / (nodes * nodes.sqrt());
        let skew = if skew.is_finite() { skew } else { 0.0 };
        let z = u - skew * (u * u - 1.0) / 6.0;
        (!z.is_nan()).then_some(z)
    }

    /// The foam at a point from the coarse active fraction `a` and residual fraction `r`
    /// there, the standardised compression `u` (`None`: the coarse `a` itself) and streak
    /// value `s`.
    #[inline]
    pub(super) fn foam(&self, a: f32, r: f32, u: Option<f32>, s: f32) -> FoamCoverage {
        let active = match u {
            Some(u) => self.active.ramp(u, a),
            None => a,
        };
        let residual = self.residual.ramp(s, r) * (1.0 - active);
        FoamCoverage {
            active,
            residual,
            total: (active + residual).min(1.0),
        }
    }
}

/// The integer cell and the fraction across it of a grid coordinate g in [0, n].
#[inline]
fn split(g: f64, n: usize) -> (usize, f32) {
    let i = g.floor();
    let f = (g - i) as f32;
    ((i as usize).min(n - 1), f)
}

/// The streak field: white noise (one standard normal per texel from `seed`) smoothed by
/// periodic Gaussian kernels along and across the wind, brought to mean 0 and variance 1,
/// with the functions of `M`; and the correlations of neighbouring texels along and across.
fn streak_field<M: Math>(seed: u64) -> (Vec<f32>, [f32; 2]) {
    let kernel = |std: f64, spacing: f64| -> Vec<f64> {
        let radius = (4.0 * std / spacing).ceil() as i32;
        (-radius..=radius)
            .map(|d| {
                let x = f64::from(d) * spacing / std;
                M::exp(-0.5 * x * x)
            })
            .collect()
    };
    let wa = kernel(ALONG_KERNEL, ALONG_SPACING);
    let wc = kernel(ACROSS_KERNEL, ACROSS_SPACING);
    let (na, nc) = (STREAK_ALONG, STREAK_ACROSS);
    let noise: Vec<f64> = (0..na * nc)
        .map(|k| gaussian_pair::<M>(seed, (k % nc) as i32, (k / nc) as i32).0)
        .collect();
    // Across (within rows), then along (between rows), both periodic.
    let mut rows = vec![0.0f64; na * nc];
    let rc = (wc.len() / 2) as isize;
    for j in 0..na {
        for i in 0..nc {
            let mut v = 0.0;
            for (d, w) in wc.iter().enumerate() {
                let ii = (i as isize + d as isize - rc).rem_euclid(nc as isize) as usize;
                v += w * noise[j * nc + ii];
            }
            rows[j * nc + i] = v;
        }
    }
    let norm =
        (wa.iter().map(|w| w * w).sum::<f64>() * wc.iter().map(|w| w * w).sum::<f64>()).sqrt();
    let ra = (wa.len() / 2) as isize;
    let mut out = vec![0.0f64; na * nc];
    for j in 0..na {
        for i in 0..nc {
            let mut v = 0.0;
            for (d, w) in wa.iter().enumerate() {
                let jj = (j as isize + d as isize - ra).rem_euclid(na as isize) as usize;
                v += w * rows[jj * nc + i];
            }
            out[j * nc + i] = v / norm;
        }
    }
    // The realised field to mean 0 and variance 1 exactly (its few thousand independent
    // values leave them a few per cent off), and its neighbours' correlations.
    let count = (na * nc) as f64;
    let mean = out.iter().sum::<f64>() / count;
    let deviation = (out.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / count).sqrt();
    let field: Vec<f64> = out.iter().map(|v| (v - mean) / deviation).collect();
    let (mut along, mut across) = (0.0, 0.0);
    for j in 0..na {
        for i in 0..nc {
            let v = field[j * nc + i];
            along += v * field[(j + 1) % na * nc + i];
            across += v * field[j * nc + (i + 1) % nc];
        }
    }
    let values = field.iter().map(|&v| v as f32).collect();
    (values, [(along / count) as f32, (across / count) as f32])
}

#[cfg(test)]
#[path = "detail_tests.rs"]
mod tests;
