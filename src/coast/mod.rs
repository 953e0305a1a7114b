//! Coasts: a map of the water depth ([`DepthMap`]) and what it does to the waves of each
//! cascade ([`CoastField`]): linear shoaling and depth-limited breaking of a random sea
//! (Battjes & Janssen 1978), solved once when the map is set, read by the world queries as a
//! factor per cascade. See docs/theory.md, "Coasts".

use std::sync::Arc;

use crate::cascade::MAX_CASCADES;
use crate::error::{self, Error};

mod solve;

pub use solve::breaker_index;
pub(crate) use solve::solve;

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
    /// `inverse` is 1/`spacing` (a product is cheaper than a quotient, and the queries ask
    /// at every point).
    #[inline]
    fn cell(&self, x: f64, z: f64, inverse: f64) -> Option<(usize, usize, f32, f32)> {
        let gx = (x - self.origin[0]) * inverse;
        let gz = (z - self.origin[1]) * inverse;
        let (nx, nz) = ((self.size[0] - 1) as f64, (self.size[1] - 1) as f64);
        if !(0.0..=nx).contains(&gx) || !(0.0..=nz).contains(&gz) {
            return None;
        }
        // The last row and column use the cell before them, at fraction 1. (gx, gz ≥ 0
        // here: the cast truncates as `floor` would, without its call on a CPU without
        // SSE4.1.)
        let i = (gx as usize).min(self.size[0] - 2);
        let j = (gz as usize).min(self.size[1] - 2);
        Some((i, j, (gx - i as f64) as f32, (gz - j as f64) as f32))
    }
}

/// Cells of the ramp at the map's edge over which the factors go to 1, so that the map's
/// edge shows no seam with the open sea outside.
pub const EDGE_RAMP_CELLS: usize = 8;

/// Simulated seconds over which a replaced map's factors blend into the new map's.
pub const BLEND_SECONDS: f64 = 2.0;

/// The waves over one depth map: the amplitude factor of each cascade and the fraction of
/// breaking waves Q_b at each cell of the map (see docs/theory.md, "Coasts"). What a
/// renderer uploads as a texture over the map: [`factors`](Self::factors) holds, cell after
/// cell in the map's order, one factor per cascade.
#[derive(Debug, Clone)]
pub struct CoastField {
    map: DepthMap,
    /// 1/`map.spacing` in 1/m.
    inverse: f64,
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

    /// The factor of every cascade at world (x, z) into `out` (bilinear between cells, 1
    /// outside the map; entries past [`cascade_count`](Self::cascade_count) untouched):
    /// [`factor`](Self::factor)'s values, the cell found once for all cascades.
    #[inline]
    fn factors_into(&self, x: f64, z: f64, out: &mut Factors) {
        let count = self.cascades.min(MAX_CASCADES);
        match self.map.cell(x, z, self.inverse) {
            Some((i, j, fx, fz)) => {
                // The four corners' factors, each `count` contiguous values: bilerp's
                // operations, one bounds check.
                let (stride, row) = (self.cascades, self.map.size[0] * self.cascades);
                let start = (j * self.map.size[0] + i) * stride;
                let f = &self.factors[start..start + row + 2 * stride];
                for (c, out) in out[..count].iter_mut().enumerate() {
                    let (a, b) = (f[c], f[stride + c]);
                    let (d, e) = (f[row + c], f[row + stride + c]);
                    let bottom = a + (b - a) * fx;
                    let top = d + (e - d) * fx;
                    *out = bottom + (top - bottom) * fz;
                }
            }
            None => out[..count].fill(1.0),
        }
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
            .cell(x, z, self.inverse)
            .map(|(i, j, fx, fz)| bilerp(|cell| depth[cell], self.map.size[0], i, j, fx, fz))
    }

    #[inline]
    fn bilinear(&self, x: f64, z: f64, outside: f32, value: impl Fn(usize) -> f32) -> f32 {
        match self.map.cell(x, z, self.inverse) {
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

/// The coast's factor of each cascade at one point (no unit; 1 for the open sea).
pub(crate) type Factors = [f32; MAX_CASCADES];

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

    /// Weight of the current field at time `t`, in [0, 1]: 0 when it was set, 1 from
    /// [`BLEND_SECONDS`] later on, and 1 before it was set.
    #[inline]
    fn weight(&self, t: f64) -> f32 {
        let w = (t - self.start) / BLEND_SECONDS;
        // Before the change (the time moved back): the map set last, not the one it replaced.
        if w < 0.0 {
            1.0
        } else {
            w.min(1.0) as f32
        }
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

    /// The factors of all cascades at world (x, z) and time `t` (1 for a cascade the
    /// fields have no factor for): [`Coast::factor`] of each, with the same bits, the map's
    /// cell found once.
    #[inline]
    pub(crate) fn factors(&self, t: f64, x: f64, z: f64) -> Factors {
        let [factors] = self.factors_many(t, &[x], &[z]);
        factors
    }

    /// [`Coast::factors`] at N points (`x[p]`, `z[p]`): each point's the same operations, so the
    /// same bits, the blend's weight found once. Out of line: the queries call it once per
    /// point (or eight in lanes) and evaluation, from every SIMD level and field
    /// combination, and it holds no vector work worth a copy each.
    #[inline(never)]
    pub(crate) fn factors_many<const N: usize>(
        &self,
        t: f64,
        x: &[f64; N],
        z: &[f64; N],
    ) -> [Factors; N] {
        let mut new = [[1.0; MAX_CASCADES]; N];
        if let Some(field) = self.current.as_deref() {
            for p in 0..N {
                field.factors_into(x[p], z[p], &mut new[p]);
            }
        }
        let w = self.weight(t);
        if w >= 1.0 {
            return new;
        }
        for p in 0..N {
            let mut old = [1.0; MAX_CASCADES];
            if let Some(field) = self.previous.as_deref() {
                field.factors_into(x[p], z[p], &mut old);
            }
            for (new, old) in new[p].iter_mut().zip(old) {
                *new = old + (*new - old) * w;
            }
        }
        new
    }

    /// The foam coverage `foam` (in [0, 1]) of the open sea at world (x, z) and time `t`
    /// over the coast: the whitecaps fade where the waves die (land, shelter: cascade 0's
    /// factor below 1), and the surf adds the fraction of waves breaking on the bottom.
    #[inline(never)]
    #[allow(clippy::manual_clamp)]
    pub(crate) fn foam(&self, t: f64, x: f64, z: f64, foam: f32) -> f32 {
        let open = self.factor(t, 0, x, z).min(1.0);
        (foam * open).max(self.breaking(t, x, z)).min(1.0)
    }

    /// The coarse active and residual foam fractions `a`, `r` (in [0, 1]) of the open sea
    /// at world (x, z) and time `t` over the coast, before the foam's detail patterns them:
    /// the whitecaps and the residual foam fade where the waves die (cascade 0's factor
    /// below 1), and the surf is active foam covering the fraction Q_b of breaking waves.
    #[inline(never)]
    pub(crate) fn surf(&self, t: f64, x: f64, z: f64, a: f32, r: f32) -> (f32, f32) {
        let open = self.factor(t, 0, x, z).min(1.0);
        ((a * open).max(self.breaking(t, x, z)).min(1.0), r * open)
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
