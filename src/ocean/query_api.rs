//! The world queries as an [`OceanState`] answers them: the surface at a point, where the
//! water at a point comes from, the water height there, their batches, the grid of samples
//! over a window, and the [`Surface`] handle for other threads.

use std::ops::Bound::{Excluded, Included};

use crate::error::{self, Error};
use crate::query::batch::{check_batch, for_each_point, sample_rows};
use crate::query::frame::Fields;
use crate::query::point::{check_point, check_range, run, HeightAt, Locate, Sample, SurfaceAt};
use crate::query::results::{Location, SurfaceSample};
use crate::query::surface::Surface;

use super::OceanState;

impl OceanState {
    /// The surface at the undisplaced world point (`x`, `z`) in metres (any finite
    /// coordinates; every cascade wraps periodically): each cascade's height, displacement
    /// and slope interpolated by a cubic B-spline through its grid values (exact at the grid
    /// points, smooth between them, with the same statistics wherever the point lies in a
    /// cell; see docs/theory.md), its foam bilinearly, and summed. With
    /// [`Interpolation::Bilinear`](crate::Interpolation::Bilinear) every field is
    /// bilinear.
    ///
    /// The spline's coefficients are computed in tiles of 32×32 grid cells, each by the
    /// first query after a step that reads it; a query reads one tile
    /// of each cascade, rarely two.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn sample(&self, x: f64, z: f64) -> Result<SurfaceSample, Error> {
        check_point(x, z)?;
        let cascades = 0..self.cascades.len();
        Ok(run(&self.fields(), Sample(cascades), x, z))
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
        check_range(&cascades, self.cascades.len())?;
        Ok(run(&self.fields(), Sample(cascades), x, z))
    }

    /// Finds the undisplaced point x₀ whose water lands on world point (`x`, `z`), i.e.
    /// x₀ + D(x₀) = (x, z), by Newton's method with the Jacobian of the interpolated
    /// displacement, from a first guess one Newton step away from (x, z) on the larger half
    /// of the cascades alone (whose waves move the water most), less the smaller cascades'
    /// displacement where that step lands, then with every cascade (at most
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
        Ok(run(&self.fields(), Locate, x, z))
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
        Ok(run(&self.fields(), SurfaceAt, x, z))
    }

    /// Water height y in metres at world point (`x`, `z`), after horizontal displacement —
    /// the query buoyancy and gameplay need. Where the surface folds the inversion may not
    /// converge; [`OceanState::locate`] reports how close it came.
    ///
    /// Cost: a few evaluations of the displacement and one of the height once the spline
    /// tiles it reads are computed; the first query after a step computes them (a tile of
    /// 32×32 cells of each cascade, rarely two: a few per cent of the step), so stepping and
    /// asking one boat's height costs little more than the step (measured figures: the
    /// repository's `docs/performance.md`). For many points use [`OceanState::heights_at`]
    /// (eight points at a time in vector lanes); to query from other threads while the ocean
    /// steps, [`OceanState::surface`].
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn height_at(&self, x: f64, z: f64) -> Result<f32, Error> {
        check_point(x, z)?;
        Ok(run(&self.fields(), HeightAt, x, z))
    }

    /// [`OceanState::height_at`] for many world points (x, z), into `out` (same length as
    /// `points`), in parallel from 64 points on (fewer run on the calling thread); each
    /// result has the same bits as [`OceanState::height_at`] gives.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless `out` is as long as `points`; [`Error::NonFinite`]
    /// for a NaN or infinite coordinate. Nothing is written then.
    pub fn heights_at(&self, points: &[[f64; 2]], out: &mut [f32]) -> Result<(), Error> {
        check_batch(points, out.len())?;
        for_each_point(&self.fields(), points, out, HeightAt);
        Ok(())
    }

    /// [`OceanState::surface_at`] for many world points (x, z): height, normal, slope and
    /// foam where the water is, into `out`.
    ///
    /// # Errors
    /// As [`OceanState::heights_at`].
    pub fn surfaces_at(&self, points: &[[f64; 2]], out: &mut [SurfaceSample]) -> Result<(), Error> {
        check_batch(points, out.len())?;
        for_each_point(&self.fields(), points, out, SurfaceAt);
        Ok(())
    }

    /// [`OceanState::sample`] for many undisplaced world points (x, z), into `out` (same
    /// length as `points`).
    ///
    /// # Errors
    /// As [`OceanState::heights_at`].
    pub fn sample_many(&self, points: &[[f64; 2]], out: &mut [SurfaceSample]) -> Result<(), Error> {
        check_batch(points, out.len())?;
        let cascades = 0..self.cascades.len();
        for_each_point(&self.fields(), points, out, Sample(cascades));
        Ok(())
    }

    /// A handle on the water as it is now, for queries from other threads while the ocean
    /// steps on: the [`Surface`] keeps answering about this frame's time, with the same bits
    /// as this ocean's own queries give now. The first handle of a frame copies the fields
    /// the queries read (the height, displacement and slope of every cascade and the foam,
    /// about 24·N² bytes per cascade); later handles
    /// of the same frame share it. See [`Surface`] for what a step does while a handle is
    /// held.
    pub fn surface(&mut self) -> Surface {
        let OceanState {
            frames,
            cascades,
            foam,
            ..
        } = self;
        frames.surface(cascades, foam)
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
        let cascades = 0..self.cascades.len();
        sample_rows(&self.fields(), origin, spacing, columns, cascades, out);
        Ok(())
    }

    /// What the world queries read: the current frame, and the cascades' and the foam's own
    /// buffers.
    fn fields(&self) -> Fields<'_> {
        Fields::Live {
            frame: &self.frames.current,
            cascades: &self.cascades,
            foam: &self.foam,
        }
    }
}
