//! The breaking intensity of an ocean's foam recomputed in f64 from the documented model and
//! the public pieces, for the foam tests. Nothing here calls the crate's foam code.

#![allow(dead_code)]

use std::f64::consts::TAU;

use ocean_fft::inspect;
use ocean_fft::inspect::Field;
use ocean_fft::OceanState;

/// Q(x) = P(Z > x) for a standard normal Z, by Simpson's rule (independent of the crate's
/// approximation): Q(x) = φ(x) ∫₀^∞ e^{−xu − u²/2} du for x ≥ 0, over the u where the
/// integrand is above e⁻⁴⁰, in 400 intervals (relative error below 1e-6 for every x ≥ 0: the
/// step times x + u stays below 0.1).
pub fn upper_tail(x: f64) -> f64 {
    if x < 0.0 {
        return 1.0 - upper_tail(-x);
    }
    let width = (x * x + 80.0).sqrt() - x;
    let steps = 400;
    let h = width / f64::from(steps);
    let f = |u: f64| (-x * u - 0.5 * u * u).exp();
    let mut sum = f(0.0) + f(width);
    for k in 1..steps {
        sum += f(f64::from(k) * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
    }
    (-0.5 * x * x).exp() / TAU.sqrt() * sum * h / 3.0
}

/// The model's intensity at one point of the foam grid, and how far f32 arithmetic may
/// legitimately move it.
#[derive(Debug, Clone, Copy)]
pub struct Expected {
    /// The intensity in 1/s.
    pub value: f64,
    /// J_R at the point.
    pub jacobian: f64,
    /// The largest change of `value` when the constant and the discriminant of the quadratic
    /// in x move by the rounding of computing them in f32 (a few ulps of their largest
    /// terms): near a tangent of J to J_b, or where J_R cancels, the f32 result is only this
    /// well defined. Infinite where that rounding can close the discriminant or moves the
    /// roots by more than 0.01.
    pub conditioning: f64,
}

/// The breaking intensity at each point of `ocean`'s foam grid from the documented model.
/// Cascade 0's displacement gradient g from `Cascade::field` gives J_R = (1 + g_xx)(1 + g_zz)
/// − g_xz² and ∇J = (1 + g_zz, 1 + g_xx, −2g_xz); the smaller cascades' gradient covariance
/// Σ_u = Σ_k 2|h0(k)|² M_a(k) M_b(k) (and the rate covariance of all cascades, with ω(k)²
/// more) comes from their public `h0`, `Field::multiplier` and `omega_at`. With
/// σ² = ∇Jᵀ Σ_u ∇J + (0.05 σ_T)², β = Σ_u ∇J/σ², κ = β_xx β_zz − β_xz²,
/// J = J_R + σx + κσ²(x² − 1) for x standard normal: the intensity is Σ over the roots x_r
/// of J = J_b of φ(x_r) σ'(x_r)/(√(2π) |dJ/dx|) plus P(J < J_b)/τ_A, with σ'² = ∇Jᵀ Σ' ∇J at
/// the gradient where the surface crosses.
pub fn breaking_intensities(ocean: &OceanState) -> Vec<Expected> {
    let n = ocean.config().size;
    let fields = [
        Field::DisplacementXX,
        Field::DisplacementZZ,
        Field::DisplacementXZ,
    ];
    let mut unresolved = [[0.0f64; 3]; 3];
    let mut rate = [[0.0f64; 3]; 3];
    for (c, cascade) in ocean.cascades().iter().enumerate() {
        let dk = f64::from(cascade.delta_k());
        for j in 0..n {
            for i in 0..n {
                let h = cascade.h0()[j * n + i];
                let weight = 2.0 * f64::from(h.norm_sqr());
                let signed = |i: usize| {
                    if i < n / 2 {
                        i as f64
                    } else {
                        i as f64 - n as f64
                    }
                };
                let k = [(signed(i) * dk) as f32, (signed(j) * dk) as f32];
                let m = fields.map(|f| f64::from(f.multiplier(k).re));
                let omega = inspect::omega_at(cascade, i, j).unwrap();
                for a in 0..3 {
                    for b in 0..3 {
                        let v = weight * m[a] * m[b];
                        if c > 0 {
                            unresolved[a][b] += v;
                        }
                        rate[a][b] += v * omega * omega;
                    }
                }
            }
        }
    }
    let first = &ocean.cascades()[0];
    let g0 = fields.map(|f| inspect::field(first, f));
    let calibration = ocean.foam_view().calibration();
    let threshold = f64::from(calibration.threshold);
    let floor = (0.05 * f64::from(calibration.compression_std)).powi(2);
    let tau = f64::from(ocean.config().foam.active_decay);
    let times = |m: &[[f64; 3]; 3], g: [f64; 3]| -> [f64; 3] {
        [0, 1, 2].map(|a| (0..3).map(|b| m[a][b] * g[b]).sum::<f64>())
    };
    let dot = |a: [f64; 3], b: [f64; 3]| -> f64 { (0..3).map(|i| a[i] * b[i]).sum() };
    let phi = |x: f64| (-0.5 * x * x).exp() / TAU.sqrt();
    if threshold == f64::NEG_INFINITY {
        // Nothing breaks.
        let nothing = Expected {
            value: 0.0,
            jacobian: f64::NAN,
            conditioning: 0.0,
        };
        return vec![nothing; n * n];
    }
    (0..n * n)
        .map(|k| {
            let [xx, zz, xz] = [0, 1, 2].map(|a| f64::from(g0[a][k]));
            let jacobian = (1.0 + xx) * (1.0 + zz) - xz * xz;
            let gradient = [1.0 + zz, 1.0 + xx, -2.0 * xz];
            let su = times(&unresolved, gradient);
            let variance = dot(su, gradient) + floor;
            let sigma = variance.sqrt();
            let beta = su.map(|v| v / variance);
            let kappa = beta[0] * beta[1] - beta[2] * beta[2];
            let a2 = kappa * variance;
            // The intensity for J(x) − J_b = a2 x² + σx + c with the discriminant moved by
            // `shift`.
            let model = |c: f64, shift: f64| -> f64 {
                let crossing = |x: f64, slope: f64| {
                    let w = sigma * x;
                    let at = [
                        gradient[0] + beta[1] * w,
                        gradient[1] + beta[0] * w,
                        gradient[2] - 2.0 * beta[2] * w,
                    ];
                    let speed = dot(times(&rate, at), at).sqrt();
                    phi(x) * speed / (TAU.sqrt() * slope)
                };
                if a2 == 0.0 {
                    // J linear in x: below J_b for x < −c/σ.
                    let root = -c / sigma;
                    return (1.0 - upper_tail(root)) / tau + crossing(root, sigma);
                }
                let disc = sigma * sigma - 4.0 * a2 * c + shift;
                if disc <= 0.0 {
                    return if a2 < 0.0 { 1.0 / tau } else { 0.0 };
                }
                let q = -0.5 * (sigma + disc.sqrt());
                let (lo, hi) = ((q / a2).min(c / q), (q / a2).max(c / q));
                let fraction = if a2 > 0.0 {
                    upper_tail(lo) - upper_tail(hi)
                } else {
                    1.0 - upper_tail(lo) + upper_tail(hi)
                };
                fraction / tau + crossing(lo, disc.sqrt()) + crossing(hi, disc.sqrt())
            };
            let c = jacobian - a2 - threshold;
            let value = model(c, 0.0);
            // f32's rounding of c (its terms) and of the discriminant (its two terms).
            let eps = 8.0 * f64::from(f32::EPSILON);
            let dc =
                eps * ((1.0 + xx).abs() * (1.0 + zz).abs() + xz * xz + a2.abs() + threshold.abs());
            let dd = eps * (variance + (4.0 * a2 * c).abs());
            let disc = variance - 4.0 * a2 * c;
            let conditioning = if a2 != 0.0 && disc.abs() <= 4.0 * a2.abs() * dc + dd {
                // So near a tangent that the rounding may close or open it: Rice's rate is
                // proportional to 1/√disc, unbounded there.
                f64::INFINITY
            } else if disc > 0.0 && dc > 0.01 * disc.sqrt() {
                // The rounding moves the roots (by dc/|dJ/dx| = dc/√disc) by more than 0.01:
                // f32 does not resolve where J crosses J_b (a sea flatter than f32's
                // resolution of J near 1), and the model may peak inside [c − dc, c + dc].
                f64::INFINITY
            } else {
                [(dc, 0.0), (-dc, 0.0), (0.0, dd), (0.0, -dd)]
                    .into_iter()
                    .map(|(delta, shift)| (model(c + delta, shift) - value).abs())
                    .fold(0.0, f64::max)
            };
            Expected {
                value,
                jacobian,
                conditioning,
            }
        })
        .collect()
}
