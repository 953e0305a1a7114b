//! The march that solves a [`CoastField`]: linear shoaling and Battjes & Janssen's (1978)
//! breaking of each cascade's band along the mean wave direction, cell after cell of the
//! map (docs/theory.md, "Coasts").

use super::{CoastField, DepthMap, EDGE_RAMP_CELLS};
use rayon::prelude::*;

use crate::cascade::{Cascade, MAX_CASCADES};
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
/// of (1 − Q)/(−ln Q) = b² (1 for b ≥ 1).
pub(crate) fn breaking_fraction<M: Math>(b: f64) -> f64 {
    if b.is_nan() || b <= 0.0 {
        return 0.0;
    }
    if b >= 1.0 {
        return 1.0;
    }
    let b2 = b * b;
    // g(L) = 1 − e^L + b² L with L = ln Q is concave and rises to a peak at L = ln b², above
    // the root; from L₀ = −1/b² (where g = −e^L₀ < 0) Newton's tangents stay above g, so
    // the steps climb to the root without passing it.
    let mut l = -1.0 / b2;
    if l < -60.0 {
        return M::exp(l); // Q = e^(−1/b²) to within a relative e^(−60)
    }
    for _ in 0..200 {
        let q = M::exp(l);
        let (g, slope) = (1.0 - q + b2 * l, b2 - q);
        if g >= 0.0 || slope <= 0.0 {
            break;
        }
        let step = -g / slope;
        l += step;
        if step <= 1e-15 * l.abs() {
            break;
        }
    }
    M::exp(l)
}

/// Battjes & Janssen's largest wave height in metres at depth `d` (m) for the peak wave
/// number `k` (rad/m): H_max = 0.88/k · tanh(γ k d / 0.88), γ of [`breaker_index`].
pub(crate) fn max_height<M: Math>(k: f64, d: f64) -> f64 {
    0.88 / k * M::tanh(breaker_index(k, d) * k * d / 0.88)
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
    let open_depth = match dispersion {
        Dispersion::Deep => f64::INFINITY,
        Dispersion::FiniteDepth { depth } | Dispersion::Capillary { depth } => f64::from(depth),
    };
    // The open sea's group velocity of each band: the flux the waves bring into the map.
    let open: Vec<f64> = bands
        .iter()
        .map(|b| group_velocity::<M>(&dispersion, b.omega))
        .collect();
    let sea = Sea {
        bands: &bands,
        open: &open,
        table: DepthTable::new::<M>(&bands, &dispersion, omega_peak),
        f_peak: omega_peak / std::f64::consts::TAU,
    };
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
    // The ray back from a cell along −u crosses the column i − si (if a ≥ b) or the row
    // j − sj, so the cells of one column (or row) depend only on the one before it: the
    // march goes line by line, the cells of a line in parallel (each the same bits
    // whatever the threads).
    let along_x = a >= b;
    let (lines, line_len, step) = if along_x { (nx, nz, si) } else { (nz, nx, sj) };
    let mut line_energy = error::try_vec(line_len * count, 0.0_f64)?;
    let mut line_q = error::try_vec(line_len, 0.0_f64)?;
    let cell_of = |line: usize, m: usize| -> (isize, isize) {
        let fixed = if step > 0 { line } else { lines - 1 - line } as isize;
        if along_x {
            (fixed, m as isize)
        } else {
            (m as isize, fixed)
        }
    };
    for line in 0..lines {
        line_energy
            .par_chunks_mut(count)
            .zip(line_q.par_iter_mut())
            .enumerate()
            .with_min_len(32)
            .for_each(|(m, (out, q))| {
                let (i, j) = cell_of(line, m);
                let depth = f64::from(map.depth[j as usize * nx + i as usize]);
                if depth <= 0.0 {
                    out.fill(0.0); // land: no waves, nothing carried on
                    *q = 0.0;
                    return;
                }
                // The state upstream, interpolated between the two cells between which the
                // ray crosses the line before.
                let (near, far, t, length) = if along_x {
                    (at(i - si, j), at(i - si, j - sj), b / a, spacing / a)
                } else {
                    (at(i, j - sj), at(i - si, j - sj), a / b, spacing / b)
                };
                for (k, e) in out.iter_mut().enumerate() {
                    let value = |c: Option<usize>| c.map_or(1.0, |c| energy[c * count + k]);
                    *e = value(near) * (1.0 - t) + value(far) * t;
                }
                let mut depth_up = 0.0;
                for (c, w) in [(near, 1.0 - t), (far, t)] {
                    // Skipped at weight 0: the open sea's depth may be infinite.
                    if w > 0.0 {
                        depth_up += w * c.map_or(open_depth, |c| f64::from(map.depth[c]));
                    }
                }
                *q = march::<M>(&sea, depth_up, depth, length, out);
            });
        for (m, q) in line_q.iter().enumerate() {
            let (i, j) = cell_of(line, m);
            let cell = j as usize * nx + i as usize;
            energy[cell * count..][..count].copy_from_slice(&line_energy[m * count..][..count]);
            breaking[cell] = *q as f32;
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

/// Nodes of the depth table per e-fold of depth: linear interpolation in ln d between them
/// is off by about (Δ²/8)·|f''|, near 1e-6 of the group velocity (checked in the tests).
const NODES_PER_E_FOLD: f64 = 200.0;

/// The dispersion at every depth the march meets, tabulated once per solve: at nodes
/// spaced evenly in ln d from [`MIN_DEPTH`] to where every band is deep (k d ≥ 20, tanh
/// then 1 to double precision), the group velocity of each band and the peak's wave
/// number. The exact solve of k from ω costs a dozen transcendental calls; the march asks
/// for it a few times per band and cell.
struct DepthTable {
    ln_min: f64,
    /// Nodes per unit of ln d.
    scale: f64,
    nodes: usize,
    /// Per node: `stride − 1` group velocities (m/s), then the peak's k (rad/m).
    values: Vec<f64>,
    stride: usize,
}

impl DepthTable {
    fn new<M: Math>(bands: &[Band], dispersion: &Dispersion, omega_peak: f64) -> DepthTable {
        let omegas: Vec<f64> = bands.iter().map(|b| b.omega).chain([omega_peak]).collect();
        // The smallest k of any band in deep water sets the depth beyond which all are deep.
        let deep = at_depth(*dispersion, 1.0e7);
        let k_min = omegas
            .iter()
            .map(|&w| deep.k_from_omega_with::<M>(w))
            .filter(|k| *k > 0.0)
            .fold(f64::INFINITY, f64::min);
        let ln_min = M::ln(MIN_DEPTH);
        let ln_max = if k_min.is_finite() {
            M::ln((20.0 / k_min).max(2.0 * MIN_DEPTH))
        } else {
            ln_min + 1.0
        };
        let nodes = ((ln_max - ln_min) * NODES_PER_E_FOLD).ceil() as usize + 1;
        let scale = (nodes - 1) as f64 / (ln_max - ln_min);
        let stride = omegas.len();
        let mut values = Vec::with_capacity(nodes * stride);
        for n in 0..nodes {
            let at = at_depth(*dispersion, M::exp(ln_min + n as f64 / scale));
            for &w in &omegas[..stride - 1] {
                values.push(group_velocity::<M>(&at, w));
            }
            values.push(at.k_from_omega_with::<M>(omega_peak));
        }
        DepthTable {
            ln_min,
            scale,
            nodes,
            values,
            stride,
        }
    }

    /// The group velocities of the bands (into `cg`, m/s) and the peak's wave number
    /// (rad/m) at depth `d` (m; clamped to the table, whose last node is deep water).
    fn at<M: Math>(&self, d: f64, cg: &mut [f64]) -> f64 {
        let x = ((M::ln(d.max(MIN_DEPTH)) - self.ln_min) * self.scale).max(0.0);
        let n = (x as usize).min(self.nodes - 2);
        let t = (x - n as f64).min(1.0);
        let lo = &self.values[n * self.stride..][..self.stride];
        let hi = &self.values[(n + 1) * self.stride..][..self.stride];
        for (k, c) in cg.iter_mut().enumerate() {
            *c = lo[k] + (hi[k] - lo[k]) * t;
        }
        let p = self.stride - 1;
        lo[p] + (hi[p] - lo[p]) * t
    }
}

/// What every cell's step of the march shares.
struct Sea<'a> {
    bands: &'a [Band],
    /// The open sea's group velocity of each band (m/s).
    open: &'a [f64],
    table: DepthTable,
    /// Peak frequency in Hz.
    f_peak: f64,
}

/// One step of the march from the upstream state (the energy of each band relative to the
/// open sea's, reached at `upstream_depth` m, infinite for the deep open sea) to a cell
/// `depth` m deep, `length` m downstream: linear shoaling (the energy flux E c_g of each
/// band kept) and Battjes & Janssen's dissipation, shared among the bands in proportion to
/// their energy, over sub-steps of at most 2 m. `out` holds the upstream energies on entry
/// and the cell's on return; returns Q_b at the cell.
fn march<M: Math>(
    sea: &Sea<'_>,
    upstream_depth: f64,
    depth: f64,
    length: f64,
    out: &mut [f64],
) -> f64 {
    let count = sea.bands.len();
    let steps = (length / 2.0).ceil().clamp(1.0, 16.0) as usize;
    let ds = length / steps as f64;
    let (mut before, mut now) = ([0.0_f64; MAX_CASCADES], [0.0_f64; MAX_CASCADES]);
    let (before, now) = (&mut before[..count], &mut now[..count]);
    let start = if upstream_depth.is_finite() {
        sea.table.at::<M>(upstream_depth, before);
        upstream_depth.max(MIN_DEPTH)
    } else {
        before.copy_from_slice(sea.open);
        depth.max(MIN_DEPTH)
    };
    let mut q = 0.0;
    for s in 1..=steps {
        let d = (start + (depth - start) * s as f64 / steps as f64).max(MIN_DEPTH);
        let kp = sea.table.at::<M>(d, now);
        let mut variance = 0.0;
        for k in 0..count {
            out[k] *= before[k] / now[k];
            before[k] = now[k];
            variance += out[k] * sea.bands[k].variance;
        }
        let h_rms2 = 8.0 * variance;
        if h_rms2 <= 0.0 {
            continue;
        }
        let h_max = max_height::<M>(kp, d);
        q = breaking_fraction::<M>(h_rms2.sqrt() / h_max);
        // D/E = (α/4) f_p Q_b H_max² / (H_rms²/8): the same relative loss rate for every band.
        let rate = 2.0 * ALPHA * sea.f_peak * q * h_max * h_max / h_rms2;
        for (e, cg) in out.iter_mut().zip(before.iter()) {
            *e *= M::exp(-rate * ds / cg);
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
        for b in [0.05, 0.1, 0.15, 0.2, 0.4, 0.6, 0.8, 0.95, 0.999, 0.999_999] {
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

    /// The table's group velocities and peak wave number against the exact solve, at depths
    /// between the nodes from 5 cm to deep water: linear interpolation at 200 nodes per
    /// e-fold is off by about Δ²/8 = 3e-6 times the curvature in ln d, order one here, so
    /// 2e-5 leaves room and would catch a wrong node or a slip of one node.
    #[test]
    fn depth_table_matches_the_exact_dispersion() {
        let bands: Vec<Band> = [0.4, 1.1, 3.0, 9.0, 27.0]
            .iter()
            .map(|&omega| Band {
                variance: 1.0,
                omega,
            })
            .collect();
        for dispersion in [
            Dispersion::Deep,
            Dispersion::FiniteDepth { depth: 30.0 },
            Dispersion::Capillary { depth: 30.0 },
        ] {
            let omega_peak = 0.8;
            let table = DepthTable::new::<Std>(&bands, &dispersion, omega_peak);
            let mut cg = vec![0.0; bands.len()];
            for n in 0..400 {
                let d = 0.05 * Std::exp(0.036_43 * f64::from(n)); // 5 cm to 100 km, off the nodes
                let kp = table.at::<Std>(d, &mut cg);
                let at = at_depth(dispersion, d);
                let exact = at.k_from_omega_with::<Std>(omega_peak);
                assert!(
                    (kp / exact - 1.0).abs() < 2e-5,
                    "{dispersion:?} {d}: {kp} {exact}"
                );
                for (band, c) in bands.iter().zip(&cg) {
                    let exact = group_velocity::<Std>(&at, band.omega);
                    assert!(
                        (c / exact - 1.0).abs() < 2e-5,
                        "{dispersion:?} {d}: {c} {exact}"
                    );
                }
            }
        }
    }
}
