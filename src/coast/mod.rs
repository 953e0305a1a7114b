//! Coasts: a map of the water depth ([`DepthMap`]) and what it does to the waves of each
//! cascade ([`CoastField`]): linear shoaling and depth-limited breaking of a random sea
//! (Battjes & Janssen 1978), solved once when the map is set, read by the world queries as a
//! factor per cascade. See docs/theory.md, "Coasts".

use std::sync::Arc;

use crate::cascade::Cascade;
use crate::error::{self, Error};
use crate::math::determinism::{with_math, Determinism, Math};
use crate::spectrum::dispersion::Dispersion;
use crate::spectrum::Spectrum;

/// The water depth over a rectangle of the world: what
/// [`OceanState::set_depth_map`](crate::OceanState::set_depth_map) takes.
///
/// Cell (i, j) is the point x = `origin[0]` + i·`spacing`, z = `origin[1]` + j·`spacing`
/// (metres); its depth is `depth[j * size[0] + i]` (rows along x, z as the row, as every
/// buffer of the crate), in metres of water below the still level y = 0, ≤ 0 on land.
/// Between cells the depth and the wave factors are interpolated bilinearly; outside the
/// rectangle the spectrum's own depth holds and the waves are those of the open sea.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct DepthMap {
    /// World (x, z) of cell (0, 0), metres.
    pub origin: [f64; 2],
    /// Distance between neighbouring cells, metres (> 0).
    pub spacing: f32,
    /// Cells along x and along z (each ≥ 2, their product ≤ [`DepthMap::MAX_CELLS`]).
    pub size: [usize; 2],
    /// Water depth of each cell in metres (≤ 0: land), `size[0] * size[1]` values.
    pub depth: Vec<f32>,
}

impl DepthMap {
    /// The most cells a map may hold: 4096² (the factors of three cascades then take
    /// 200 MB).
    pub const MAX_CELLS: usize = 4096 * 4096;

    /// Checks the map.
    ///
    /// # Errors
    /// [`Error::NonFinite`] naming `origin`, `spacing` or `depth` for a NaN or infinite
    /// value; [`Error::OutOfRange`] naming `spacing` if it is not > 0;
    /// [`Error::CountOutOfRange`] naming `size` if a side is below 2 or the cells exceed
    /// [`DepthMap::MAX_CELLS`]; [`Error::LengthMismatch`] naming `depth` if it does not hold
    /// `size[0] * size[1]` values.
    pub fn validate(&self) -> Result<(), Error> {
        if !self.origin.iter().all(|v| v.is_finite()) {
            return Err(Error::NonFinite { name: "origin" });
        }
        error::positive("spacing", self.spacing)?;
        for &side in &self.size {
            if side < 2 {
                return Err(Error::CountOutOfRange {
                    name: "size",
                    count: side,
                    min: 2,
                    max: Self::MAX_CELLS / 2,
                });
            }
        }
        let cells = self.size[0]
            .checked_mul(self.size[1])
            .filter(|&cells| cells <= Self::MAX_CELLS)
            .ok_or(Error::CountOutOfRange {
                name: "size",
                count: self.size[0].saturating_mul(self.size[1]),
                min: 4,
                max: Self::MAX_CELLS,
            })?;
        error::length("depth", self.depth.len(), cells)?;
        if !self.depth.iter().all(|d| d.is_finite()) {
            return Err(Error::NonFinite { name: "depth" });
        }
        Ok(())
    }

    /// The map's bilinear weights at world (x, z): the cell (i, j) below-left of it and the
    /// fractions (fx, fz), or `None` outside the map.
    fn cell(&self, x: f64, z: f64) -> Option<(usize, usize, f32, f32)> {
        let spacing = f64::from(self.spacing);
        let gx = (x - self.origin[0]) / spacing;
        let gz = (z - self.origin[1]) / spacing;
        let (nx, nz) = ((self.size[0] - 1) as f64, (self.size[1] - 1) as f64);
        if !(0.0..=nx).contains(&gx) || !(0.0..=nz).contains(&gz) {
            return None;
        }
        // The last row and column use the cell before them, at fraction 1.
        let i = (gx.floor() as usize).min(self.size[0] - 2);
        let j = (gz.floor() as usize).min(self.size[1] - 2);
        Some((i, j, (gx - i as f64) as f32, (gz - j as f64) as f32))
    }
}

/// Cells of the ramp at the map's edge over which the factors go to 1, so that the map's
/// edge shows no seam with the open sea outside.
pub const EDGE_RAMP_CELLS: usize = 8;

/// Simulated seconds over which a replaced map's factors blend into the new map's.
pub const BLEND_SECONDS: f64 = 2.0;

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

/// The waves over one depth map: the amplitude factor of each cascade and the fraction of
/// breaking waves Q_b at each cell of the map (see docs/theory.md, "Coasts"). What a
/// renderer uploads as a texture over the map: [`factors`](Self::factors) holds, cell after
/// cell in the map's order, one factor per cascade.
#[derive(Debug, Clone)]
pub struct CoastField {
    map: DepthMap,
    cascades: usize,
    factors: Vec<f32>,
    breaking: Vec<f32>,
    direction: f32,
}

impl CoastField {
    /// The depth map.
    pub fn map(&self) -> &DepthMap {
        &self.map
    }

    /// Amplitude factors (no unit): cell after cell in the map's order (index
    /// `j * size[0] + i`), [`cascade_count`](Self::cascade_count) values each, largest
    /// cascade first. 1 is the open sea, 0 land or a sheltered cell.
    pub fn factors(&self) -> &[f32] {
        &self.factors
    }

    /// The number of factors per cell.
    pub fn cascade_count(&self) -> usize {
        self.cascades
    }

    /// The fraction of waves breaking on the bottom at each cell, in [0, 1] (Battjes &
    /// Janssen's Q_b), in the map's order.
    pub fn breaking(&self) -> &[f32] {
        &self.breaking
    }

    /// The mean direction the waves travel toward, radians (the direction of the march).
    pub fn direction(&self) -> f32 {
        self.direction
    }

    /// Factor of cascade `c` at world (x, z): bilinear between cells, 1 outside the map.
    #[inline]
    pub(crate) fn factor(&self, c: usize, x: f64, z: f64) -> f32 {
        self.bilinear(x, z, 1.0, |cell| self.factors[cell * self.cascades + c])
    }

    /// Q_b at world (x, z), 0 outside the map.
    #[inline]
    pub(crate) fn breaking_at(&self, x: f64, z: f64) -> f32 {
        self.bilinear(x, z, 0.0, |cell| self.breaking[cell])
    }

    /// Depth in metres at world (x, z), `None` outside the map.
    pub(crate) fn depth_at(&self, x: f64, z: f64) -> Option<f32> {
        let depth = &self.map.depth;
        self.map
            .cell(x, z)
            .map(|(i, j, fx, fz)| bilerp(|cell| depth[cell], self.map.size[0], i, j, fx, fz))
    }

    #[inline]
    fn bilinear(&self, x: f64, z: f64, outside: f32, value: impl Fn(usize) -> f32) -> f32 {
        match self.map.cell(x, z) {
            Some((i, j, fx, fz)) => bilerp(value, self.map.size[0], i, j, fx, fz),
            None => outside,
        }
    }
}

#[inline]
fn bilerp(value: impl Fn(usize) -> f32, nx: usize, i: usize, j: usize, fx: f32, fz: f32) -> f32 {
    let c = j * nx + i;
    let bottom = value(c) + (value(c + 1) - value(c)) * fx;
    let top = value(c + nx) + (value(c + nx + 1) - value(c + nx)) * fx;
    bottom + (top - bottom) * fz
}

/// The coast the queries read: the current field, and while a map is being replaced the
/// one before it, blended over [`BLEND_SECONDS`] from `start`.
#[derive(Debug, Clone)]
pub(crate) struct Coast {
    pub(crate) current: Option<Arc<CoastField>>,
    previous: Option<Arc<CoastField>>,
    start: f64,
}

impl Coast {
    /// `current` replacing `previous` from simulated time `start` (s).
    pub(crate) fn new(
        current: Option<Arc<CoastField>>,
        previous: Option<Arc<CoastField>>,
        start: f64,
    ) -> Coast {
        Coast {
            current,
            previous,
            start,
        }
    }

    /// Weight of the current field at time `t`, in [0, 1].
    #[inline]
    fn weight(&self, t: f64) -> f32 {
        ((t - self.start) / BLEND_SECONDS).clamp(0.0, 1.0) as f32
    }

    /// `value` of the blended fields at time `t` (`outside` where a field is absent).
    #[inline]
    fn blend(&self, t: f64, outside: f32, value: impl Fn(&CoastField) -> f32) -> f32 {
        let new = self.current.as_deref().map_or(outside, &value);
        let w = self.weight(t);
        if w >= 1.0 {
            return new;
        }
        let old = self.previous.as_deref().map_or(outside, &value);
        old + (new - old) * w
    }

    /// The factor of cascade `c` at world (x, z) and time `t`.
    #[inline]
    pub(crate) fn factor(&self, t: f64, c: usize, x: f64, z: f64) -> f32 {
        self.blend(t, 1.0, |field| field.factor(c, x, z))
    }

    /// The fraction of breaking waves at world (x, z) and time `t`.
    #[inline]
    pub(crate) fn breaking(&self, t: f64, x: f64, z: f64) -> f32 {
        self.blend(t, 0.0, |field| field.breaking_at(x, z))
    }
}

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
