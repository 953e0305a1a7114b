//! The march that solves a [`CoastField`]: linear shoaling and Battjes & Janssen's (1978)
//! breaking of each cascade's band along the mean wave direction, cell after cell of the
//! map (docs/theory.md, "Coasts").

use super::{CoastField, DepthMap, EDGE_RAMP_CELLS};
use crate::cascade::Cascade;
use crate::error::{self, Error};
use crate::math::determinism::{with_math, Determinism, Math};
use crate::spectrum::dispersion::Dispersion;
use crate::spectrum::Spectrum;

/// Breaker index γ of H_max = 0.88/k · tanh(γ k d / 0.88) at the peak wave number k and
/// depth d: γ = 0.29 + 0.76 k d, fitted by Ruessink, Walstra & Southgate (2003) to field
/// data of random waves breaking on beaches (a constant γ = 0.73, Battjes & Stive 1985,
/// keeps the inner surf zone of a gentle beach too high: H_s/d near 0.8 under a swell).
pub fn breaker_index(k: f64, d: f64) -> f64 {
    0.29 + 0.76 * k * d
}

/// Battjes & Janssen's (1978) dissipation coefficient α (order one, their value).
const ALPHA: f64 = 1.0;

/// Shallowest depth in metres the march evaluates the dispersion at (a wet cell shallower
/// than this is treated as this deep; it keeps the group velocity finite and positive).
const MIN_DEPTH: f64 = 0.05;

/// What the march needs of one cascade's band: its variance (m²) and its energy-weighted
/// mean angular frequency (rad/s).
#[derive(Debug, Clone, Copy)]
struct Band {
    variance: f64,
    omega: f64,
}

/// Group velocity in m/s of waves of angular frequency `omega` under `dispersion`.
fn group_velocity<M: Math>(dispersion: &Dispersion, omega: f64) -> f64 {
    let k = dispersion.k_from_omega_with::<M>(omega);
    dispersion.d_omega_dk_with::<M>(k)
}

/// The ocean's dispersion law at depth `depth` (m).
fn at_depth(dispersion: Dispersion, depth: f64) -> Dispersion {
    let depth = depth.max(MIN_DEPTH) as f32;
    match dispersion {
        Dispersion::Capillary { .. } => Dispersion::Capillary { depth },
        _ => Dispersion::FiniteDepth { depth },
    }
}

/// Battjes & Janssen's (1978) fraction of breaking waves Q_b for b = H_rms/H_max: the root
/// of (1 − Q)/(−ln Q) = b² (1 for b ≥ 1), by bisection on ln Q.
pub(crate) fn breaking_fraction<M: Math>(b: f64) -> f64 {
    if b.is_nan() || b <= 0.0 {
        return 0.0;
    }
    if b >= 1.0 {
        return 1.0;
    }
    let b2 = b * b;
    // g(Q) = (1 − Q) + b² ln Q rises from −∞ at 0 to 0 at Q = 1 through one root below 1.
    let (mut lo, mut hi) = (-60.0_f64, 0.0_f64);
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        let q = M::exp(mid);
        if (1.0 - q) + b2 * mid < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    M::exp(lo)
}

/// Battjes & Janssen's largest wave height in metres at depth `d` (m) for the peak wave
/// number `k` (rad/m): H_max = 0.88/k · tanh(γ k d / 0.88), γ of [`breaker_index`].
pub(crate) fn max_height<M: Math>(k: f64, d: f64) -> f64 {
    0.88 / k * M::tanh(breaker_index(k, d) * k * d / 0.88)
}

/// The march's state at one cell: the energy of each band relative to the open sea's, and
/// the depth (m) it was reached at.
#[derive(Debug, Clone)]
struct State {
    energy: Vec<f64>,
    depth: f64,
}

/// Solves the waves of `cascades` (drawn from `spectrum`) over `map` (validated), with the
/// transcendental functions of `determinism`.
pub(crate) fn solve(
    map: DepthMap,
    spectrum: &Spectrum,
    cascades: &[Cascade],
    determinism: Determinism,
) -> Result<CoastField, Error> {
    with_math!(determinism, M => solve_with::<M>(map, spectrum, cascades))
}

fn solve_with<M: Math>(
    map: DepthMap,
    spectrum: &Spectrum,
    cascades: &[Cascade],
) -> Result<CoastField, Error> {
    let dispersion = spectrum.dispersion();
    let (bands, direction) = bands::<M>(cascades, &dispersion);
    let count = bands.len();
    let [nx, nz] = map.size;
    let cells = nx * nz;
    let mut factors = error::try_vec(cells * count, 0.0_f32)?;
    let mut breaking = error::try_vec(cells, 0.0_f32)?;
    let mut energy = error::try_vec(cells * count, 0.0_f64)?;
    let omega_peak = f64::from(spectrum.peak_omega());
    let f_peak = omega_peak / std::f64::consts::TAU;
    let open_depth = match dispersion {
        Dispersion::Deep => f64::INFINITY,
        Dispersion::FiniteDepth { depth } | Dispersion::Capillary { depth } => f64::from(depth),
    };
    // The open sea's group velocity of each band: the flux the waves bring into the map.
    let open: Vec<f64> = bands
        .iter()
        .map(|b| group_velocity::<M>(&dispersion, b.omega))
        .collect();
    let (ux, uz) = (M::cos(direction), M::sin(direction));
    let (si, sj) = (
        if ux >= 0.0 { 1isize } else { -1 },
        if uz >= 0.0 { 1isize } else { -1 },
    );
    let (a, b) = (ux.abs(), uz.abs());
    let spacing = f64::from(map.spacing);
    let at = |i: isize, j: isize| -> Option<usize> {
        (i >= 0 && j >= 0 && (i as usize) < nx && (j as usize) < nz)
            .then(|| j as usize * nx + i as usize)
    };
    let mut upstream = State {
        energy: vec![0.0; count],
        depth: 0.0,
    };
    let mut shoaled = vec![0.0; count];
    for jj in 0..nz as isize {
        let j = if sj > 0 { jj } else { nz as isize - 1 - jj };
        for ii in 0..nx as isize {
            let i = if si > 0 { ii } else { nx as isize - 1 - ii };
            let cell = j as usize * nx + i as usize;
            let depth = f64::from(map.depth[cell]);
            if depth <= 0.0 {
                continue; // land: no waves, nothing carried on
            }
            // The ray back from this cell along −u crosses the column i − si (if a ≥ b) or
            // the row j − sj; the state there is interpolated between the two cells on it.
            let (near, far, t, length) = if a >= b {
                (at(i - si, j), at(i - si, j - sj), b / a, spacing / a)
            } else {
                (at(i, j - sj), at(i - si, j - sj), a / b, spacing / b)
            };
            let mut depth_up = 0.0;
            for (k, e) in upstream.energy.iter_mut().enumerate() {
                let value = |c: Option<usize>| c.map_or(1.0, |c| energy[c * count + k]);
                *e = value(near) * (1.0 - t) + value(far) * t;
            }
            for (c, w) in [(near, 1.0 - t), (far, t)] {
                // Skipped at weight 0: the open sea's depth may be infinite.
                if w > 0.0 {
                    depth_up += w * c.map_or(open_depth, |c| f64::from(map.depth[c]));
                }
            }
            upstream.depth = depth_up;
            let q = march::<M>(
                &upstream,
                depth,
                length,
                &bands,
                &open,
                &dispersion,
                omega_peak,
                f_peak,
                &mut shoaled,
            );
            energy[cell * count..][..count].copy_from_slice(&shoaled);
            breaking[cell] = q as f32;
        }
    }
    for j in 0..nz {
        for i in 0..nx {
            let cell = j * nx + i;
            let wet = map.depth[cell] > 0.0;
            let edge = i.min(j).min(nx - 1 - i).min(nz - 1 - j);
            let w = (edge as f64 / EDGE_RAMP_CELLS as f64).min(1.0);
            let w = w * w * (3.0 - 2.0 * w);
            for k in 0..count {
                let f = energy[cell * count + k].sqrt();
                factors[cell * count + k] = if wet {
                    (1.0 + (f - 1.0) * w) as f32
                } else {
                    0.0
                };
            }
            breaking[cell] = (f64::from(breaking[cell]) * w) as f32;
        }
    }
    Ok(CoastField {
        inverse: 1.0 / f64::from(map.spacing),
        map,
        cascades: count,
        factors,
        breaking,
        direction: direction as f32,
    })
}

/// One step of the march from the `upstream` state to a cell `depth` m deep, `length` m
/// downstream: linear shoaling (the energy flux E c_g of each band kept) and Battjes &
/// Janssen's dissipation, shared among the bands in proportion to their energy, over
/// sub-steps of at most 2 m. Writes the bands' energies to `out`, returns Q_b at the cell.
#[allow(clippy::too_many_arguments)]
fn march<M: Math>(
    upstream: &State,
    depth: f64,
    length: f64,
    bands: &[Band],
    open: &[f64],
    dispersion: &Dispersion,
    omega_peak: f64,
    f_peak: f64,
    out: &mut [f64],
) -> f64 {
    out.copy_from_slice(&upstream.energy);
    let steps = (length / 2.0).ceil().clamp(1.0, 16.0) as usize;
    let ds = length / steps as f64;
    let group = |band: &Band, open: f64, d: f64| {
        if d.is_infinite() {
            open
        } else {
            group_velocity::<M>(&at_depth(*dispersion, d), band.omega)
        }
    };
    let mut before: Vec<f64> = bands
        .iter()
        .zip(open)
        .map(|(band, &open)| group(band, open, upstream.depth.max(MIN_DEPTH)))
        .collect();
    let start = if upstream.depth.is_finite() {
        upstream.depth.max(MIN_DEPTH)
    } else {
        depth.max(MIN_DEPTH)
    };
    let mut q = 0.0;
    for s in 1..=steps {
        let d = (start + (depth - start) * s as f64 / steps as f64).max(MIN_DEPTH);
        let mut variance = 0.0;
        for (k, band) in bands.iter().enumerate() {
            let cg = group(band, open[k], d);
            out[k] *= before[k] / cg;
            before[k] = cg;
            variance += out[k] * band.variance;
        }
        let h_rms2 = 8.0 * variance;
        if h_rms2 <= 0.0 {
            continue;
        }
        let kp = at_depth(*dispersion, d).k_from_omega_with::<M>(omega_peak);
        let h_max = max_height::<M>(kp, d);
        q = breaking_fraction::<M>(h_rms2.sqrt() / h_max);
        // D/E = (α/4) f_p Q_b H_max² / (H_rms²/8): the same relative loss rate for every band.
        let rate = 2.0 * ALPHA * f_peak * q * h_max * h_max / h_rms2;
        for (k, e) in out.iter_mut().enumerate() {
            *e *= M::exp(-rate * ds / before[k]);
        }
    }
    q
}

/// Each cascade's band (variance, mean frequency from its h0) and the mean direction the
/// waves travel toward (radians), energy-weighted over every cascade.
fn bands<M: Math>(cascades: &[Cascade], dispersion: &Dispersion) -> (Vec<Band>, f64) {
    let (mut sx, mut sz) = (0.0_f64, 0.0_f64);
    let bands = cascades
        .iter()
        .map(|cascade| {
            let n = cascade.size();
            let dk = f64::from(cascade.delta_k());
            let (mut total, mut weighted) = (0.0_f64, 0.0_f64);
            for (index, h) in cascade.h0().iter().enumerate() {
                let w = f64::from(h.norm_sqr());
                if w == 0.0 {
                    continue;
                }
                let m = |i: usize| {
                    if i < n / 2 {
                        i as f64
                    } else {
                        i as f64 - n as f64
                    }
                };
                let (kx, kz) = (m(index % n) * dk, m(index / n) * dk);
                let k = M::hypot(kx, kz);
                total += w;
                weighted += w * dispersion.omega_with::<M>(k);
                sx += w * kx / k;
                sz += w * kz / k;
            }
            let omega = if total > 0.0 {
                weighted / total
            } else {
                dispersion.omega_with::<M>(dk * n as f64 / 4.0)
            };
            Band {
                variance: cascade.expected_variance(),
                omega,
            }
        })
        .collect();
    (bands, M::atan2(sz, sx))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::determinism::Std;

    /// Q_b solves (1 − Q)/(−ln Q) = b²: put the root back into the relation.
    #[test]
    fn breaking_fraction_solves_its_relation() {
        for b in [0.2, 0.4, 0.6, 0.8, 0.95, 0.999] {
            let q = breaking_fraction::<Std>(b);
            assert!(q > 0.0 && q < 1.0, "{b}: {q}");
            let back = (1.0 - q) / (-Std::ln(q));
            // Bisection to 2⁻⁸⁰ of 60 in ln Q: far below 1e-9 relative.
            assert!((back - b * b).abs() < 1e-9 * b * b, "{b}: {back}");
        }
        assert_eq!(breaking_fraction::<Std>(1.2), 1.0);
        assert_eq!(breaking_fraction::<Std>(0.0), 0.0);
    }

    /// H_max tends to γ d in shallow water (tanh x ≈ x) and to 0.88/k in deep water.
    #[test]
    fn max_height_limits() {
        let (k, d) = (1e-3, 1.0);
        let gamma = breaker_index(k, d);
        assert!((max_height::<Std>(k, d) / (gamma * d) - 1.0).abs() < 1e-6);
        assert!((max_height::<Std>(1.0, 100.0) / 0.88 - 1.0).abs() < 1e-12);
    }
}
