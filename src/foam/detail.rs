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

use crate::cascade::{Cascade, MAX_CASCADES};
use crate::math::determinism::Math;
use crate::math::periodic::{cell_on, wrap, Period, Stencil};
use crate::math::rng::gaussian_pair;
use rayon::prelude::*;

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
pub(super) const STREAK_ACROSS: usize = 1024;
/// Spacing of the streak field's texels along and across the wind, m (a tile of 256 m × 256 m).
const ALONG_SPACING: f64 = 2.0;
const ACROSS_SPACING: f64 = 0.25;
/// Standard deviations of the Gaussian kernels that smooth white noise into the windrows of
/// the streak field, along and across the wind, m: their correlation falls to 1/e at twice
/// these, 36 m and 1 m.
const ALONG_KERNEL: f64 = 18.0;
const ACROSS_KERNEL: f64 = 0.5;
/// The same for the patches that group the windrows, `[along, across]` m.
const PATCH_KERNEL: [f64; 2] = [14.0, 6.0];
/// Weights of the windrows and the patches in the streak field (before it is normalised):
/// the patches hold a fifth of its variance, enough to group the windrows without stacking
/// them into bars.
const STREAK_WEIGHTS: [f64; 2] = [1.0, 0.5];
/// The patches' columns lie this many texels apart (2 m).
const PATCH_STRIDE: usize = 8;
/// Speed of the breakers that make the visible whitecaps as a share of the peak's phase
/// speed: Ding & Farmer (1994) found breaking events travelling 45–75 % slower than the
/// dominant waves, and Gemmrich & Farmer (1999) breaking at 5–80 % of the dominant wave
/// scale. At 0.4 the breakers are (0.4)² = 0.16 peak wavelengths long, 13 m in the fresh
/// breeze: the whitecaps sit on the compression of waves about that long and longer.
const BREAKER_SPEED_RATIO: f64 = 0.4;

/// The least weight of a finer cascade in the whitecaps' placement, as a share of the largest:
/// its compression then holds a few per cent of the field's variance, enough to tear the
/// edges at its scale without moving the whitecaps off the breakers (at 0.3 the fresh
/// breeze's whitecaps shrank to a 0.75 m correlation along the wind, from 1 m).
const WEIGHT_FLOOR: f32 = 0.2;

/// Mixed into cascade 0's seed for the streak field's noise, and again for the patches'.
const STREAK_SEED: u64 = 0x5f0a_3d7e_c41b_9265;
const PATCH_SEED: u64 = 0x1d3b_77a2_90c4_e651;

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
    /// V₀ with each wave weighted by e^(−(k/k_b)²), k_b the breakers' wave number: the part of
    /// the compression at the whitecaps' scale.
    breaking: f64,
    /// E\[T²K\] with T = D_xx + D_zz and K = D_xx·D_zz − D_xz² at unit choppiness (Isserlis'
    /// theorem on the covariance of the gradient): 1 − J = −λT − λ²K has the third moment
    /// −3λ⁴E\[T²K\] to leading order.
    third: f64,
}

impl BilinearVariance {
    /// The variance parts of `cascade`'s amplitudes for breakers of wave number `k_b`
    /// (rad/m), with the functions of `M`.
    fn of<M: Math>(cascade: &Cascade, k_b: f64) -> BilinearVariance {
        let n = cascade.size();
        let dk = f64::from(cascade.delta_k());
        let spacing = f64::from(cascade.length()) / n as f64;
        let h0 = cascade.h0();
        let mut parts = [0.0f64; 4];
        let mut breaking = 0.0f64;
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
                breaking += v * M::exp(-k2 / (k_b * k_b));
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
            breaking,
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
    /// Per cascade c ≥ 1 (index c − 1), the weight w_c of its compression in the whitecaps'
    /// placement: √(its variance at the breakers' scale / its variance), so that the
    /// weighted sum has, cascade by cascade, the variance of the compression low-passed at
    /// the breakers' wave number (docs/theory.md §15.8).
    weights: Vec<f32>,
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
    /// streaks), whose wind blows toward `wind_direction` (rad) and whose peak wavelength is
    /// `peak_wavelength` (m), with the functions of `M`.
    pub(super) fn new<M: Math>(
        cascades: &[Cascade],
        wind_direction: f64,
        peak_wavelength: f64,
    ) -> Detail {
        let breaker_length = BREAKER_SPEED_RATIO * BREAKER_SPEED_RATIO * peak_wavelength;
        let k_b = std::f64::consts::TAU / breaker_length.max(1e-3);
        let variance: Vec<BilinearVariance> = cascades[1..]
            .iter()
            .map(|c| BilinearVariance::of::<M>(c, k_b))
            .collect();
        let mut weights: Vec<f32> = variance
            .iter()
            .map(|v| {
                let w = (v.breaking / v.parts[0]).sqrt();
                if w.is_finite() {
                    w as f32
                } else {
                    0.0
                }
            })
            .collect();
        // Only the ratios count (the sum is standardised). Every finer cascade keeps at least
        // WEIGHT_FLOOR of the largest weight, so the whitecaps' edges are torn at the finest
        // scale as a breaking crest's are; breakers far longer than every finer cascade's
        // waves weigh them all near 0, and they then share alike.
        let largest = weights.iter().copied().fold(0.0f32, f32::max);
        if largest < 1e-6 {
            weights.fill(1.0);
        } else {
            for w in &mut weights {
                *w = w.max(WEIGHT_FLOOR * largest);
            }
        }
        let built_variance = variance.iter().map(|v| v.parts[0]).sum();
        let (sin, cos) = M::sin_cos(wind_direction);
        let (streaks, neighbours) = streak_field::<M>(cascades[0].config().seed ^ STREAK_SEED);
        Detail {
            active: Quantiles::new::<M>(ACTIVE_EDGE),
            residual: Quantiles::new::<M>(RESIDUAL_EDGE),
            variance,
            weights,
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
    /// Σ w_c (1 − J_c) over the analytic standard deviation of that bilinear interpolation there,
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
        for ((cascade, parts), &w) in cascades[1..].iter().zip(&self.variance).zip(&self.weights) {
            if w == 0.0 {
                continue;
            }
            let n = cascade.size();
            let cell = cell_on(x, z, &Period::new(f64::from(cascade.length()), n));
            let (_, fx, _, fz) = cell;
            sum += w * (1.0 - Stencil::new(cell, n).scalar(cascade.jacobian()));
            let chop2 = cascade.config().choppiness * cascade.config().choppiness;
            let w2 = w * w;
            var += w2 * chop2 * parts.at(fx, fz, scale);
            nodes += w2 * chop2 * scale * parts.parts[0] as f32;
            third -= 3.0 * w2 * w * chop2 * chop2 * scale * scale * parts.third as f32;
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

    /// The weights of each cascade's compression 1 − J_c in the whitecaps' placement field
    /// for a sea whose unresolved compression variance at unit choppiness is `variance`:
    /// w_c / σ with σ the standard deviation of Σ w_c (1 − J_c) at the cascades' nodes, so
    /// that the weighted sum is that field standardised (0 for cascade 0 and past the
    /// cascades; all 0 where the field is not defined, as [`compression_at`](Self::compression_at) says `None`).
    pub(super) fn placement(&self, cascades: &[Cascade], variance: f64) -> [f32; MAX_CASCADES] {
        let mut out = [0.0f32; MAX_CASCADES];
        if !(self.built_variance > 0.0 && variance > 0.0) {
            return out;
        }
        let scale = (variance / self.built_variance) as f32;
        let mut nodes = 0.0f32;
        for ((cascade, parts), &w) in cascades[1..].iter().zip(&self.variance).zip(&self.weights) {
            let chop = cascade.config().choppiness;
            nodes += w * w * chop * chop * scale * parts.parts[0] as f32;
        }
        if !(nodes > 0.0 && nodes.is_finite()) {
            return out;
        }
        let sd = nodes.sqrt();
        for (o, &w) in out[1..].iter_mut().zip(&self.weights) {
            *o = w / sd;
        }
        out
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

/// The streak field: two fields of white noise (one standard normal per texel from `seed`
/// and from a second seed) smoothed by periodic Gaussian kernels, the windrows (long along
/// the wind, thin across) and the patches that group them, summed with the weights
/// [`STREAK_WEIGHTS`], brought to mean 0 and variance 1, with the functions of `M`; and the
/// correlations of neighbouring texels along and across.
fn streak_field<M: Math>(seed: u64) -> (Vec<f32>, [f32; 2]) {
    let (na, nc) = (STREAK_ALONG, STREAK_ACROSS);
    let windrows = smoothed::<M>(seed, [ALONG_KERNEL, ACROSS_KERNEL], nc, ACROSS_SPACING);
    // The patches are smooth over metres: made on every PATCH_STRIDE-th column (2 m apart)
    // and interpolated linearly across, which keeps all but 0.3 % of their variance between
    // the columns (correlation 0.97 at 2 m).
    let coarse = nc / PATCH_STRIDE;
    let spacing = ACROSS_SPACING * PATCH_STRIDE as f64;
    let patches = smoothed::<M>(seed ^ PATCH_SEED, PATCH_KERNEL, coarse, spacing);
    let [w, p] = STREAK_WEIGHTS;
    let out: Vec<f64> = windrows
        .iter()
        .enumerate()
        .map(|(k, a)| {
            let (j, i) = (k / nc, k % nc);
            let (c, f) = (
                i / PATCH_STRIDE,
                (i % PATCH_STRIDE) as f64 / PATCH_STRIDE as f64,
            );
            let row = &patches[j * coarse..(j + 1) * coarse];
            let b = (1.0 - f) * row[c] + f * row[(c + 1) % coarse];
            w * a + p * b
        })
        .collect();
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

/// White noise on a periodic grid of `STREAK_ALONG` rows of `nc` texels `across_spacing`
/// metres apart (one standard normal per texel from `seed`) smoothed by Gaussian kernels of
/// standard deviation `[along, across]` metres, with unit variance in expectation.
fn smoothed<M: Math>(
    seed: u64,
    [along, across]: [f64; 2],
    nc: usize,
    across_spacing: f64,
) -> Vec<f64> {
    let kernel = |std: f64, spacing: f64| -> Vec<f64> {
        let radius = (4.0 * std / spacing).ceil() as i32;
        (-radius..=radius)
            .map(|d| {
                let x = f64::from(d) * spacing / std;
                M::exp(-0.5 * x * x)
            })
            .collect()
    };
    let wa = kernel(along, ALONG_SPACING);
    let wc = kernel(across, across_spacing);
    let na = STREAK_ALONG;
    let noise: Vec<f64> = (0..na * nc)
        .into_par_iter()
        .map(|k| gaussian_pair::<M>(seed, (k % nc) as i32, (k / nc) as i32).0)
        .collect();
    // Across (within rows), then along (between rows), both periodic; rows in parallel, each
    // value summed in one order whatever the threads.
    let mut rows = vec![0.0f64; na * nc];
    let rc = (wc.len() / 2) as isize;
    rows.par_chunks_mut(nc).enumerate().for_each(|(j, row)| {
        for (i, value) in row.iter_mut().enumerate() {
            let mut v = 0.0;
            for (d, w) in wc.iter().enumerate() {
                let ii = (i as isize + d as isize - rc).rem_euclid(nc as isize) as usize;
                v += w * noise[j * nc + ii];
            }
            *value = v;
        }
    });
    let norm =
        (wa.iter().map(|w| w * w).sum::<f64>() * wc.iter().map(|w| w * w).sum::<f64>()).sqrt();
    let ra = (wa.len() / 2) as isize;
    let mut out = vec![0.0f64; na * nc];
    out.par_chunks_mut(nc).enumerate().for_each(|(j, row)| {
        for (i, value) in row.iter_mut().enumerate() {
            let mut v = 0.0;
            for (d, w) in wa.iter().enumerate() {
                let jj = (j as isize + d as isize - ra).rem_euclid(na as isize) as usize;
                v += w * rows[jj * nc + i];
            }
            *value = v / norm;
        }
    });
    out
}

#[cfg(test)]
#[path = "detail_tests.rs"]
mod tests;
