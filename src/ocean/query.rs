//! World-space queries on an [`OceanState`]: periodic cubic B-spline sampling of every
//! cascade's height, displacement and slope (bilinear for the foam), summed, and the
//! inversion of the horizontal displacement for the water height at a point.

use glam::{Vec2, Vec3};
use std::ops::Bound::{Excluded, Included};

use rayon::prelude::*;

use super::spline::{Spline, SplineStencil};
use super::OceanState;
use crate::cascade::Cascade;
use crate::determinism::{with_math, Math};
use crate::error::{self, Error};

/// The surface at one undisplaced world point, summed over the cascades.
///
/// `#[repr(C)]`: nine `f32` in the order of the fields, without padding (36 bytes). With the
/// `bytemuck` feature it is `bytemuck::Pod` and `bytemuck::Zeroable`, so
/// `bytemuck::cast_slice` views a `&[SurfaceSample]` as `&[f32]` (or as a GPU buffer of
/// structs with the same layout) without copying.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
#[repr(C)]
pub struct SurfaceSample {
    /// Height η in metres.
    pub height: f32,
    /// Horizontal displacement `[x, z]` in metres (already × choppiness): the water at the
    /// undisplaced point sits at that point plus this.
    pub displacement: [f32; 2],
    /// Slope `[∂y/∂x, ∂y/∂z]` of the displaced surface, dimensionless: the sum of the
    /// cascades' slopes.
    pub slope: [f32; 2],
    /// Unit normal `[x, y, z]` of the displaced surface (y up), from the summed slope.
    pub normal: [f32; 3],
    /// Foam coverage in [0, 1]: the ocean's one foam field ([`OceanState::foam`], on
    /// cascade 0's grid) interpolated bilinearly; 0 from a range of cascades without
    /// cascade 0 ([`OceanState::sample_cascades`]), as cascade 0's textures carry the foam.
    pub foam: f32,
}

impl Default for SurfaceSample {
    /// Flat, still water: zero height, displacement and slope, the normal straight up, no
    /// foam.
    fn default() -> Self {
        SurfaceSample {
            height: 0.0,
            displacement: [0.0; 2],
            slope: [0.0; 2],
            normal: [0.0, 1.0, 0.0],
            foam: 0.0,
        }
    }
}

/// Where the water at a world point comes from: the result of [`OceanState::locate`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Location {
    /// The undisplaced world point `[x, z]` in metres whose water lands on the query point
    /// (the best one found).
    pub undisplaced: [f64; 2],
    /// Distance in metres between the query point and where the water at `undisplaced`
    /// actually lands (0 for an exact inversion).
    pub miss: f32,
    /// Fixed-point iterations it took to reach `undisplaced`.
    pub iterations: usize,
    /// Whether `miss` is below [`QueryConfig::tolerance`](crate::QueryConfig::tolerance).
    pub converged: bool,
}

/// Bilinear weights and the four sample indices of a grid cell on a periodic N×N grid (for
/// the foam).
#[derive(Debug, Clone, Copy)]
struct Stencil {
    index: [usize; 4],
    weight: [f32; 4],
}

/// The grid cell (ix, iz) of world point (x, z) on a periodic N×N grid of side `length`, and
/// the fractions (fx, fz) in [0, 1] of the way across it, wrapped in f64.
fn cell(x: f64, z: f64, length: f64, n: usize) -> (usize, f32, usize, f32) {
    let cells = n as f64 / length;
    let gx = x.rem_euclid(length) * cells;
    let gz = z.rem_euclid(length) * cells;
    let (ix, fx) = split(gx, n);
    let (iz, fz) = split(gz, n);
    (ix, fx, iz, fz)
}

impl Stencil {
    fn new((ix, fx, iz, fz): (usize, f32, usize, f32), n: usize) -> Stencil {
        let ix1 = (ix + 1) % n;
        let iz1 = (iz + 1) % n;
        Stencil {
            index: [iz * n + ix, iz * n + ix1, iz1 * n + ix, iz1 * n + ix1],
            weight: [
                (1.0 - fx) * (1.0 - fz),
                fx * (1.0 - fz),
                (1.0 - fx) * fz,
                fx * fz,
            ],
        }
    }

    #[inline]
    fn scalar(&self, values: &[f32]) -> f32 {
        (0..4).map(|c| values[self.index[c]] * self.weight[c]).sum()
    }

    #[inline]
    fn vector(&self, values: &[[f32; 2]]) -> Vec2 {
        (0..4)
            .map(|c| Vec2::from_array(values[self.index[c]]) * self.weight[c])
            .sum()
    }
}

/// Periodic bilinear interpolation of `values`, a field on an N×N grid of side `length` m
/// (grid point (i, j) at (i, j)·`length`/N, index j·N + i), at world (x, z).
pub(crate) fn periodic_bilinear(values: &[f32], n: usize, length: f64, x: f64, z: f64) -> f32 {
    Stencil::new(cell(x, z, length, n), n).scalar(values)
}

/// Integer cell and fraction of grid coordinate `g` in [0, n]; rounding can give exactly n,
/// which wraps to cell 0.
fn split(g: f64, n: usize) -> (usize, f32) {
    let cell = g.floor();
    let fraction = (g - cell) as f32;
    ((cell as usize) % n, fraction)
}

/// Checks a world point: both coordinates finite (any finite value: the cascades wrap).
fn check_point(x: f64, z: f64) -> Result<(), Error> {
    for (name, value) in [("x", x), ("z", z)] {
        if !value.is_finite() {
            return Err(Error::NonFinite { name });
        }
    }
    Ok(())
}

/// The cell of (x, z) on `cascade`'s grid.
#[inline]
fn cell_of(cascade: &Cascade, x: f64, z: f64) -> (usize, f32, usize, f32) {
    cell(x, z, f64::from(cascade.length()), cascade.size())
}

/// The cubic B-spline stencil of a cell on an N×N grid.
#[inline]
fn spline_of((ix, fx, iz, fz): (usize, f32, usize, f32), n: usize) -> SplineStencil {
    SplineStencil::new(ix, fx, iz, fz, n)
}

impl OceanState {
    /// The surface at the undisplaced world point (`x`, `z`) in metres (any finite
    /// coordinates; every cascade wraps periodically): each cascade's height, displacement
    /// and slope interpolated by a cubic B-spline through its grid values (exact at the grid
    /// points, smooth between them, with the same statistics wherever the point lies in a
    /// cell; see docs/theory.md), its foam bilinearly, and summed. With
    /// [`Interpolation::Bilinear`](crate::Interpolation::Bilinear) every field is
    /// bilinear.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn sample(&self, x: f64, z: f64) -> Result<SurfaceSample, Error> {
        check_point(x, z)?;
        Ok(self.sample_unchecked(x, z, &self.fresh_splines()))
    }

    /// The spline coefficients the queries need, fresh (computed now if the last update made
    /// them stale).
    fn fresh_splines(&self) -> super::spline::FreshSplines<'_> {
        self.splines.fresh(&self.cascades)
    }

    fn sample_unchecked(&self, x: f64, z: f64, splines: &[Spline]) -> SurfaceSample {
        self.sample_range(x, z, 0..self.cascades.len(), splines)
    }

    /// [`OceanState::sample`] summed over the cascades in `cascades` only (indices into
    /// [`OceanState::cascades`], largest first) — for level of detail: far from the camera,
    /// `0..1` or `0..2` leave out waves too small to see, which would only shimmer. An empty
    /// range (`start == end`) gives flat water.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate; [`Error::CountOutOfRange`]
    /// unless `cascades.start ≤ cascades.end ≤` the number of cascades.
    pub fn sample_cascades(
        &self,
        x: f64,
        z: f64,
        cascades: std::ops::Range<usize>,
    ) -> Result<SurfaceSample, Error> {
        check_point(x, z)?;
        if !(cascades.start..=self.cascades.len()).contains(&cascades.end) {
            return Err(Error::CountOutOfRange {
                name: "cascades.end",
                count: cascades.end,
                min: cascades.start,
                max: self.cascades.len(),
            });
        }
        Ok(self.sample_range(x, z, cascades, &self.fresh_splines()))
    }

    fn sample_range(
        &self,
        x: f64,
        z: f64,
        range: std::ops::Range<usize>,
        splines: &[Spline],
    ) -> SurfaceSample {
        let (mut height, mut displacement, mut slope) = (0.0f32, Vec2::ZERO, Vec2::ZERO);
        let foam = if range.contains(&0) {
            self.foam.foam_at(x, z)
        } else {
            0.0
        };
        let cascades = &self.cascades[range.clone()];
        // Empty with bilinear queries.
        let splines = splines.get(range).unwrap_or_default();
        for (c, cascade) in cascades.iter().enumerate() {
            let n = cascade.size();
            let at = cell_of(cascade, x, z);
            if let Some(spline) = splines.get(c) {
                let s = spline_of(at, n);
                let [eta, sx, sz] = s.apply(&spline.surface);
                height += eta;
                displacement += Vec2::from_array(s.apply(&spline.displacement));
                slope += Vec2::new(sx, sz);
            } else {
                let bilinear = Stencil::new(at, n);
                height += bilinear.scalar(cascade.height());
                displacement += bilinear.vector(cascade.displacement());
                slope += bilinear.vector(cascade.slope());
            }
        }
        SurfaceSample {
            height,
            displacement: displacement.to_array(),
            slope: slope.to_array(),
            normal: normal_from_slope(slope).to_array(),
            foam,
        }
    }

    /// Summed horizontal displacement at the undisplaced point, in metres.
    fn displacement_at(&self, x: f64, z: f64, splines: &[Spline]) -> Vec2 {
        if splines.is_empty() {
            return self
                .cascades
                .iter()
                .map(|cascade| {
                    Stencil::new(cell_of(cascade, x, z), cascade.size())
                        .vector(cascade.displacement())
                })
                .sum();
        }
        self.cascades
            .iter()
            .zip(splines)
            .map(|(cascade, spline)| {
                let s = spline_of(cell_of(cascade, x, z), cascade.size());
                Vec2::from_array(s.apply(&spline.displacement))
            })
            .sum()
    }

    /// Finds the undisplaced point x₀ whose water lands on world point (`x`, `z`), i.e.
    /// x₀ + D(x₀) = (x, z), by the fixed-point iteration x₀ ← p − D(x₀) (at most
    /// [`QueryConfig::max_iterations`], stopping once within [`QueryConfig::tolerance`]), and
    /// says how well it did. The iteration converges where the surface does not fold (J > 0
    /// and the displacement's gradient contracts); where it folds (high choppiness, breaking
    /// crests) several points land on (x, z) or none does exactly, and the best iterate found
    /// is returned with `converged: false`.
    ///
    /// [`QueryConfig::max_iterations`]: crate::QueryConfig::max_iterations
    /// [`QueryConfig::tolerance`]: crate::QueryConfig::tolerance
    ///
    /// ```
    /// use ocean_fft::{OceanConfig, OceanState, Spectrum};
    /// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
    /// let ocean = OceanState::new(spectrum, OceanConfig { size: 32, ..Default::default() })?;
    /// let found = ocean.locate(25.0, -7.5)?;
    /// assert!(found.converged && found.miss < 1e-4);
    /// let water = ocean.sample(found.undisplaced[0], found.undisplaced[1])?;
    /// assert_eq!(water.height, ocean.height_at(25.0, -7.5)?);
    /// # Ok::<(), ocean_fft::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn locate(&self, x: f64, z: f64) -> Result<Location, Error> {
        check_point(x, z)?;
        Ok(self.locate_unchecked(x, z, &self.fresh_splines()))
    }

    fn locate_unchecked(&self, x: f64, z: f64, splines: &[Spline]) -> Location {
        let query = self.config.query;
        let mut d = self.displacement_at(x, z, splines);
        let mut x0 = [x - f64::from(d.x), z - f64::from(d.y)];
        let mut best = Location {
            undisplaced: x0,
            miss: f32::INFINITY,
            iterations: 0,
            converged: false,
        };
        // Relaxation factor ω of x₀ ← x₀ + ω (p − x₀ − D(x₀)); ω = 1 is the plain fixed point
        // x₀ ← p − D(x₀). Where the surface is stretched by more than its own size (|∇D| > 1
        // in troughs at high choppiness) the plain iteration overshoots; halving ω whenever
        // the miss grows restores convergence wherever the surface does not fold.
        let mut omega = 1.0;
        let mut previous = f32::INFINITY;
        for iteration in 1..=query.max_iterations {
            d = self.displacement_at(x0[0], x0[1], splines);
            let landed = [x0[0] + f64::from(d.x), x0[1] + f64::from(d.y)];
            let residual = [x - landed[0], z - landed[1]];
            let miss =
                with_math!(self.config.determinism, M => M::hypot(residual[0], residual[1])) as f32;
            if miss < best.miss {
                best = Location {
                    undisplaced: x0,
                    miss,
                    iterations: iteration,
                    converged: miss < query.tolerance,
                };
            }
            if best.converged {
                break;
            }
            if miss > previous {
                omega *= 0.5;
            }
            previous = miss;
            x0 = if omega == 1.0 {
                [x - f64::from(d.x), z - f64::from(d.y)]
            } else {
                [x0[0] + omega * residual[0], x0[1] + omega * residual[1]]
            };
        }
        best
    }

    /// The surface at world point (`x`, `z`) after horizontal displacement: the sample of
    /// the undisplaced point whose water lands there (see [`OceanState::locate`], which also
    /// says whether the search converged).
    /// Its height, normal and foam are what a floating object at (x, z) feels.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn surface_at(&self, x: f64, z: f64) -> Result<SurfaceSample, Error> {
        check_point(x, z)?;
        let splines = self.fresh_splines();
        let x0 = self.locate_unchecked(x, z, &splines).undisplaced;
        Ok(self.sample_unchecked(x0[0], x0[1], &splines))
    }

    /// Water height y in metres at world point (`x`, `z`), after horizontal displacement —
    /// the query buoyancy and gameplay need. Where the surface folds the inversion may not
    /// converge; [`OceanState::locate`] reports how close it came.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn height_at(&self, x: f64, z: f64) -> Result<f32, Error> {
        self.surface_at(x, z).map(|s| s.height)
    }

    /// [`OceanState::height_at`] for many world points (x, z), into `out` (same length as
    /// `points`), in parallel from 64 points on (fewer run on the calling thread).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless `out` is as long as `points`; [`Error::NonFinite`]
    /// for a NaN or infinite coordinate. Nothing is written then.
    pub fn heights_at(&self, points: &[[f64; 2]], out: &mut [f32]) -> Result<(), Error> {
        check_batch(points, out.len())?;
        let splines = self.fresh_splines();
        for_each_point(points, out, |[x, z]| {
            let x0 = self.locate_unchecked(x, z, &splines).undisplaced;
            self.sample_unchecked(x0[0], x0[1], &splines).height
        });
        Ok(())
    }

    /// [`OceanState::surface_at`] for many world points (x, z): height, normal, slope and
    /// foam where the water is, into `out`.
    ///
    /// # Errors
    /// As [`OceanState::heights_at`].
    pub fn surfaces_at(&self, points: &[[f64; 2]], out: &mut [SurfaceSample]) -> Result<(), Error> {
        check_batch(points, out.len())?;
        let splines = self.fresh_splines();
        for_each_point(points, out, |[x, z]| {
            let x0 = self.locate_unchecked(x, z, &splines).undisplaced;
            self.sample_unchecked(x0[0], x0[1], &splines)
        });
        Ok(())
    }

    /// [`OceanState::sample`] for many undisplaced world points (x, z), into `out` (same
    /// length as `points`).
    ///
    /// # Errors
    /// As [`OceanState::heights_at`].
    pub fn sample_many(&self, points: &[[f64; 2]], out: &mut [SurfaceSample]) -> Result<(), Error> {
        check_batch(points, out.len())?;
        let splines = self.fresh_splines();
        for_each_point(points, out, |[x, z]| self.sample_unchecked(x, z, &splines));
        Ok(())
    }

    /// The surface over a world-space window that sums every cascade: a `columns` × `rows`
    /// grid of undisplaced points with spacing `spacing` metres, starting at `origin`
    /// `[x, z]`, so sample (c, r) is [`sample`](Self::sample) at
    /// (x + c·`spacing`, z + r·`spacing`) and is stored at index r·`columns` + c (z is the
    /// row, as in the cascades' buffers). Rows run in parallel; the result does not depend on
    /// the number of threads. For heightmaps, previews and textures of the whole ocean over a
    /// region (a cascade's own buffers cover only its tile, and only its band of waves).
    ///
    /// ```
    /// use ocean_fft::{OceanConfig, OceanState, Spectrum, SurfaceSample};
    /// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
    /// let ocean = OceanState::new(spectrum, OceanConfig { size: 32, ..Default::default() })?;
    /// let mut window = vec![SurfaceSample::default(); 64 * 48];
    /// ocean.sample_grid([-100.0, 250.0], 2.0, [64, 48], &mut window)?;   // 128 m × 96 m
    /// assert_eq!(window[5 * 64 + 7], ocean.sample(-100.0 + 7.0 * 2.0, 250.0 + 5.0 * 2.0)?);
    /// # Ok::<(), ocean_fft::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite `origin`; [`Error::NonFinite`] or
    /// [`Error::OutOfRange`] unless `spacing` is finite and > 0; [`Error::CountOutOfRange`]
    /// for a zero column or row count, or one whose product overflows;
    /// [`Error::LengthMismatch`] unless `out` holds `columns`·`rows` samples. Nothing is
    /// written then.
    pub fn sample_grid(
        &self,
        origin: [f64; 2],
        spacing: f64,
        [columns, rows]: [usize; 2],
        out: &mut [SurfaceSample],
    ) -> Result<(), Error> {
        check_point(origin[0], origin[1])?;
        for (name, count) in [("columns", columns), ("rows", rows)] {
            if count == 0 {
                return Err(Error::CountOutOfRange {
                    name,
                    count,
                    min: 1,
                    max: usize::MAX,
                });
            }
        }
        // The far corner must stay finite too.
        let room = |start: f64, count: usize| (f64::MAX - start.abs()) / (count - 1).max(1) as f64;
        let widest = room(origin[0], columns).min(room(origin[1], rows));
        error::in_range_f64("spacing", spacing, Excluded(0.0), Included(widest))?;
        let len = columns.checked_mul(rows).ok_or(Error::CountOutOfRange {
            name: "rows",
            count: rows,
            min: 1,
            max: usize::MAX / columns,
        })?;
        error::length("out", out.len(), len)?;
        let splines = self.fresh_splines();
        let splines: &[Spline] = &splines;
        out.par_chunks_mut(columns)
            .enumerate()
            .for_each(|(r, row)| {
                let z = origin[1] + r as f64 * spacing;
                for (c, sample) in row.iter_mut().enumerate() {
                    *sample = self.sample_unchecked(origin[0] + c as f64 * spacing, z, splines);
                }
            });
        Ok(())
    }
}

/// Batches of at least this many points are spread over rayon's threads; smaller ones (a
/// boat's few hull points) run on the calling thread, where handing them to the pool would
/// cost more than it saves.
const PARALLEL_BATCH: usize = 64;

fn for_each_point<T: Send>(
    points: &[[f64; 2]],
    out: &mut [T],
    query: impl Fn([f64; 2]) -> T + Sync,
) {
    if points.len() < PARALLEL_BATCH {
        for (value, &point) in out.iter_mut().zip(points) {
            *value = query(point);
        }
    } else {
        out.par_iter_mut()
            .zip(points)
            .with_min_len(PARALLEL_BATCH / 2)
            .for_each(|(value, &point)| *value = query(point));
    }
}

fn check_batch(points: &[[f64; 2]], out_len: usize) -> Result<(), Error> {
    error::length("out", out_len, points.len())?;
    points.iter().try_for_each(|&[x, z]| check_point(x, z))
}

/// Unit normal (−s_x, 1, −s_z)/|…| of a surface with slope `slope`.
pub(crate) fn normal_from_slope(slope: Vec2) -> Vec3 {
    Vec3::new(-slope.x, 1.0, -slope.y).normalize_or(Vec3::Y)
}
