//! The world queries of one frame, written once ([`Water`]): what an
//! [`OceanState`](crate::OceanState) and a [`Surface`](super::surface::Surface) handle both
//! answer with.

use std::ops::Bound::{Excluded, Included};
use std::ops::Range;

use super::batch::{check_batch, for_each_point, sample_rows};
use super::frame::Fields;
use super::point::{check_point, check_range, run, HeightAt, Locate, Sample, SurfaceAt};
use super::results::{Location, SurfaceSample};
use crate::error::{self, Error};

/// The world queries of one frame of the water: what
/// [`OceanState::water`](crate::OceanState::water) and
/// [`Surface::water`](super::surface::Surface::water) return. A few pointers, `Copy`: take
/// one per call or keep it for a batch of calls; it borrows the ocean (or the handle) and
/// allocates nothing.
///
/// Two kinds of point, in metres on the sea's (x, z) plane:
///
/// - **World points** (x, z), where something stands: the `_at` queries
///   ([`height_at`](Self::height_at), [`surface_at`](Self::surface_at), their batches
///   [`heights_at`](Self::heights_at) and [`surfaces_at`](Self::surfaces_at), and
///   [`locate`](Self::locate)) find the water that the horizontal displacement carried there.
///   What buoyancy, boats and gameplay need.
/// - **Rest points** (x₀, z₀), the undisplaced (Lagrangian) positions of the water: the
///   `at_rest` queries ([`at_rest`](Self::at_rest), [`at_rest_many`](Self::at_rest_many),
///   [`at_rest_grid`](Self::at_rest_grid), [`at_rest_cascades`](Self::at_rest_cascades)) give
///   the surface of the water whose rest position is (x₀, z₀); it sits at
///   (x₀, z₀) + [`SurfaceSample::displacement`]. What meshes, heightmaps and particles
///   riding the surface need: no inversion, so cheaper.
///
/// ```
/// use ocean_fft::{OceanConfig, OceanState, Spectrum};
/// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
/// let mut ocean = OceanState::new(spectrum, OceanConfig { size: 32, ..Default::default() })?;
/// ocean.step(1.0 / 60.0)?;
/// let water = ocean.water();
/// let y = water.height_at(12.0, -40.0)?;          // m, at world (x, z)
/// let found = water.locate(12.0, -40.0)?;         // where that water rests
/// let [x0, z0] = found.undisplaced;
/// assert_eq!(water.at_rest(x0, z0)?.height, y);   // the same water
/// # Ok::<(), ocean_fft::Error>(())
/// ```
///
/// Every query checks its input: [`Error::NonFinite`] for a NaN or infinite coordinate (any
/// finite one is fine: every cascade wraps periodically).
#[derive(Clone, Copy)]
pub struct Water<'a> {
    pub(crate) fields: Fields<'a>,
}

impl std::fmt::Debug for Water<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let frame = self.fields.frame();
        f.debug_struct("Water")
            .field("time", &frame.time)
            .field("cascades", &frame.grids.len())
            .finish_non_exhaustive()
    }
}

impl<'a> Water<'a> {
    /// The queries of `fields`.
    pub(crate) fn new(fields: Fields<'a>) -> Water<'a> {
        Water { fields }
    }

    /// Simulated time in seconds of the water these queries answer about.
    pub fn time(&self) -> f64 {
        self.fields.frame().time
    }

    /// The number of cascades summed, for [`at_rest_cascades`](Self::at_rest_cascades).
    fn cascade_count(&self) -> usize {
        self.fields.frame().grids.len()
    }

    /// Depth of the water in metres at world (`x`, `z`) on the ocean's depth map
    /// ([`OceanState::set_depth_map`](crate::OceanState::set_depth_map)): ≤ 0 on land, where
    /// the queries answer the still level (height 0, flat); `None` outside the map or
    /// without one (the open sea).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn depth_at(&self, x: f64, z: f64) -> Result<Option<f32>, Error> {
        check_point(x, z)?;
        let coast = self.fields.frame().coast.as_ref();
        Ok(coast
            .and_then(|c| c.current.as_ref())
            .and_then(|field| field.depth_at(x, z)))
    }

    /// Water height y in metres at world point (`x`, `z`) in metres, after horizontal
    /// displacement — the query buoyancy and gameplay need. Where the surface folds the
    /// inversion may not converge; [`locate`](Self::locate) reports how close it came.
    ///
    /// Cost: a few evaluations of the displacement and one of the height once the spline
    /// tiles it reads are computed; the first query after a step computes them (a tile of
    /// 32×32 cells of each cascade, rarely two: a few per cent of the step), so stepping and
    /// asking one boat's height costs little more than the step (measured figures: the
    /// repository's `docs/performance.md`). For many points use
    /// [`heights_at`](Self::heights_at) (eight points at a time in vector lanes); to query
    /// from other threads while the ocean steps, a
    /// [`Surface`](crate::OceanState::surface) handle.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn height_at(&self, x: f64, z: f64) -> Result<f32, Error> {
        check_point(x, z)?;
        Ok(run(&self.fields, HeightAt, x, z))
    }

    /// The surface at world point (`x`, `z`) in metres after horizontal displacement: the
    /// [`at_rest`](Self::at_rest) sample of the rest point whose water lands there (see
    /// [`locate`](Self::locate), which also says whether the search converged). Its height,
    /// normal and foam are what a floating object at (x, z) feels.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn surface_at(&self, x: f64, z: f64) -> Result<SurfaceSample, Error> {
        check_point(x, z)?;
        Ok(run(&self.fields, SurfaceAt, x, z))
    }

    /// Finds the rest (undisplaced) point x₀ whose water lands on world point (`x`, `z`) in
    /// metres, i.e. x₀ + D(x₀) = (x, z), by Newton's method with the Jacobian of the
    /// interpolated displacement, from a first guess one Newton step away from (x, z) on the
    /// larger half of the cascades alone (whose waves move the water most), less the smaller
    /// cascades' displacement where that step lands, then with every cascade (at most
    /// [`QueryConfig::max_iterations`] steps, stopping once within
    /// [`QueryConfig::tolerance`]; on the default sea one step after the first guess, two
    /// for about 8 % of points), and says how well it did. A step that does not bring the
    /// water closer is halved, and where the surface (nearly) folds the step is the fixed
    /// point's x₀ ← p − D(x₀), so it converges wherever the surface does not fold (J > 0);
    /// where it folds (high choppiness, breaking crests) several points land on (x, z) or
    /// none does exactly, and the best iterate found is returned with `converged: false`.
    ///
    /// [`QueryConfig::max_iterations`]: crate::QueryConfig::max_iterations
    /// [`QueryConfig::tolerance`]: crate::QueryConfig::tolerance
    ///
    /// ```
    /// use ocean_fft::{OceanConfig, OceanState, Spectrum};
    /// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
    /// let ocean = OceanState::new(spectrum, OceanConfig { size: 32, ..Default::default() })?;
    /// let water = ocean.water();
    /// let found = water.locate(25.0, -7.5)?;
    /// assert!(found.converged && found.miss < 1e-4);
    /// let rest = water.at_rest(found.undisplaced[0], found.undisplaced[1])?;
    /// assert_eq!(rest.height, water.height_at(25.0, -7.5)?);
    /// # Ok::<(), ocean_fft::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn locate(&self, x: f64, z: f64) -> Result<Location, Error> {
        check_point(x, z)?;
        Ok(run(&self.fields, Locate, x, z))
    }

    /// [`height_at`](Self::height_at) for many world points `[x, z]` in metres, into `out`
    /// (same length as `points`), in parallel from 64 points on (fewer run on the calling
    /// thread); each result has the same bits as [`height_at`](Self::height_at) gives.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless `out` is as long as `points`; [`Error::NonFinite`]
    /// for a NaN or infinite coordinate. Nothing is written then.
    pub fn heights_at(&self, points: &[[f64; 2]], out: &mut [f32]) -> Result<(), Error> {
        check_batch(points, out.len())?;
        for_each_point(&self.fields, points, out, HeightAt);
        Ok(())
    }

    /// [`surface_at`](Self::surface_at) for many world points `[x, z]` in metres: height,
    /// normal, slope and foam where the water is, into `out`.
    ///
    /// # Errors
    /// As [`heights_at`](Self::heights_at).
    pub fn surfaces_at(&self, points: &[[f64; 2]], out: &mut [SurfaceSample]) -> Result<(), Error> {
        check_batch(points, out.len())?;
        for_each_point(&self.fields, points, out, SurfaceAt);
        Ok(())
    }

    /// The surface of the water whose rest (undisplaced) point is (`x0`, `z0`) in metres:
    /// each cascade's height, displacement and slope interpolated by a cubic B-spline through
    /// its grid values (exact at the grid points, smooth between them, with the same
    /// statistics wherever the point lies in a cell; see docs/theory.md), its foam
    /// bilinearly, and summed. That water sits at (`x0`, `z0`) +
    /// [`displacement`](SurfaceSample::displacement); for the water at a world point use
    /// [`surface_at`](Self::surface_at). With
    /// [`Interpolation::Bilinear`](crate::Interpolation::Bilinear) every field is bilinear.
    ///
    /// The spline's coefficients are computed in tiles of 32×32 grid cells, each by the
    /// first query after a step that reads it; a query reads one tile of each cascade,
    /// rarely two.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn at_rest(&self, x0: f64, z0: f64) -> Result<SurfaceSample, Error> {
        check_point(x0, z0)?;
        Ok(run(&self.fields, Sample(0..self.cascade_count()), x0, z0))
    }

    /// [`at_rest`](Self::at_rest) summed over the cascades in `cascades` only (indices into
    /// [`OceanState::cascades`](crate::OceanState::cascades), largest first) — for level of
    /// detail: far from the camera, `0..1` or `0..2` leave out waves too small to see, which
    /// would only shimmer. An empty range (`start == end`) gives flat water; a range without
    /// cascade 0 gives no foam (cascade 0's grid carries it).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate; [`Error::CountOutOfRange`]
    /// unless `cascades.start ≤ cascades.end ≤` the number of cascades.
    pub fn at_rest_cascades(
        &self,
        x0: f64,
        z0: f64,
        cascades: Range<usize>,
    ) -> Result<SurfaceSample, Error> {
        check_point(x0, z0)?;
        check_range(&cascades, self.cascade_count())?;
        Ok(run(&self.fields, Sample(cascades), x0, z0))
    }

    /// [`at_rest`](Self::at_rest) for many rest points `[x0, z0]` in metres, into `out` (same
    /// length as `points`), in parallel from 64 points on; each result has the same bits as
    /// [`at_rest`](Self::at_rest) gives.
    ///
    /// # Errors
    /// As [`heights_at`](Self::heights_at).
    pub fn at_rest_many(
        &self,
        points: &[[f64; 2]],
        out: &mut [SurfaceSample],
    ) -> Result<(), Error> {
        check_batch(points, out.len())?;
        for_each_point(&self.fields, points, out, Sample(0..self.cascade_count()));
        Ok(())
    }

    /// The surface over a window of rest points, summing every cascade: a `columns` × `rows`
    /// grid with spacing `spacing` metres, starting at `origin` `[x0, z0]` in metres, so
    /// sample (c, r) is [`at_rest`](Self::at_rest) at (x0 + c·`spacing`, z0 + r·`spacing`)
    /// and is stored at index r·`columns` + c (z is the row, as in the cascades' buffers).
    /// Rows run in parallel; the result does not depend on the number of threads. For
    /// heightmaps, previews and textures of the whole ocean over a region (a cascade's own
    /// buffers cover only its tile, and only its band of waves).
    ///
    /// ```
    /// use ocean_fft::{OceanConfig, OceanState, Spectrum, SurfaceSample};
    /// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
    /// let ocean = OceanState::new(spectrum, OceanConfig { size: 32, ..Default::default() })?;
    /// let water = ocean.water();
    /// let mut window = vec![SurfaceSample::default(); 64 * 48];
    /// water.at_rest_grid([-100.0, 250.0], 2.0, [64, 48], &mut window)?;   // 128 m × 96 m
    /// assert_eq!(window[5 * 64 + 7], water.at_rest(-100.0 + 7.0 * 2.0, 250.0 + 5.0 * 2.0)?);
    /// # Ok::<(), ocean_fft::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite `origin`; [`Error::NonFinite`] or
    /// [`Error::OutOfRange`] unless `spacing` is finite and > 0; [`Error::CountOutOfRange`]
    /// for a zero column or row count, or one whose product overflows;
    /// [`Error::LengthMismatch`] unless `out` holds `columns`·`rows` samples. Nothing is
    /// written then.
    pub fn at_rest_grid(
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
        let cascades = 0..self.cascade_count();
        sample_rows(&self.fields, origin, spacing, columns, cascades, out);
        Ok(())
    }
}
