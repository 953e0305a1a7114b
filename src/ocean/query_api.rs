//! The world queries as an [`OceanState`] gives them: its [`Water`] (the queries of the
//! current frame, written once in [`crate::query`]), the [`Surface`] handle for other threads,
//! and the old query methods, forwarded for a release.

use crate::error::Error;
use crate::query::frame::Fields;
use crate::query::results::{Location, SurfaceSample};
use crate::query::surface::Surface;
use crate::query::water::Water;

use super::OceanState;

impl OceanState {
    /// The world queries of the water as it is now: heights and surfaces at world points
    /// ([`Water::height_at`], [`Water::surface_at`], their batches, [`Water::locate`]) and at
    /// rest points ([`Water::at_rest`] and its batch, grid and level-of-detail forms). Costs
    /// nothing; the view borrows the ocean until it is dropped, so take it after the step.
    ///
    /// ```
    /// use ocean_fft::{OceanConfig, OceanState, Spectrum};
    /// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
    /// let mut ocean = OceanState::new(spectrum, OceanConfig { size: 32, ..Default::default() })?;
    /// ocean.step(1.0 / 60.0)?;
    /// let y = ocean.water().height_at(12.0, -40.0)?;   // m, at world (x, z) in m
    /// assert!(y.abs() < 5.0);
    /// # Ok::<(), ocean_fft::Error>(())
    /// ```
    #[inline]
    pub fn water(&self) -> Water<'_> {
        Water::new(Fields::Live {
            frame: &self.frames.current,
            cascades: &self.cascades,
            foam: &self.foam,
        })
    }

    /// A handle on the water as it is now, for queries from other threads while the ocean
    /// steps on: the [`Surface`] keeps answering about this frame's time (its
    /// [`water`](Surface::water)), with the same bits as this ocean's own
    /// [`water`](Self::water) gives now. The first handle of a frame copies the fields the
    /// queries read (the height, displacement and slope of every cascade and the foam, about
    /// 24·N² bytes per cascade); later handles of the same frame share it. See [`Surface`]
    /// for what a step does while a handle is held.
    pub fn surface(&mut self) -> Surface {
        let OceanState {
            frames,
            cascades,
            foam,
            ..
        } = self;
        frames.surface(cascades, foam)
    }

    /// Deprecated: [`Water::at_rest`] through [`OceanState::water`].
    ///
    /// # Errors
    /// As [`Water::at_rest`].
    #[deprecated(since = "0.4.0", note = "use `ocean.water().at_rest(x0, z0)`")]
    #[doc(hidden)]
    pub fn sample(&self, x: f64, z: f64) -> Result<SurfaceSample, Error> {
        self.water().at_rest(x, z)
    }

    /// Deprecated: [`Water::at_rest_cascades`] through [`OceanState::water`].
    ///
    /// # Errors
    /// As [`Water::at_rest_cascades`].
    #[deprecated(
        since = "0.4.0",
        note = "use `ocean.water().at_rest_cascades(x0, z0, cascades)`"
    )]
    #[doc(hidden)]
    pub fn sample_cascades(
        &self,
        x: f64,
        z: f64,
        cascades: std::ops::Range<usize>,
    ) -> Result<SurfaceSample, Error> {
        self.water().at_rest_cascades(x, z, cascades)
    }

    /// Deprecated: [`Water::locate`] through [`OceanState::water`].
    ///
    /// # Errors
    /// As [`Water::locate`].
    #[deprecated(since = "0.4.0", note = "use `ocean.water().locate(x, z)`")]
    #[doc(hidden)]
    pub fn locate(&self, x: f64, z: f64) -> Result<Location, Error> {
        self.water().locate(x, z)
    }

    /// Deprecated: [`Water::surface_at`] through [`OceanState::water`].
    ///
    /// # Errors
    /// As [`Water::surface_at`].
    #[deprecated(since = "0.4.0", note = "use `ocean.water().surface_at(x, z)`")]
    #[doc(hidden)]
    pub fn surface_at(&self, x: f64, z: f64) -> Result<SurfaceSample, Error> {
        self.water().surface_at(x, z)
    }

    /// Deprecated: [`Water::height_at`] through [`OceanState::water`].
    ///
    /// # Errors
    /// As [`Water::height_at`].
    #[deprecated(since = "0.4.0", note = "use `ocean.water().height_at(x, z)`")]
    #[doc(hidden)]
    pub fn height_at(&self, x: f64, z: f64) -> Result<f32, Error> {
        self.water().height_at(x, z)
    }

    /// Deprecated: [`Water::heights_at`] through [`OceanState::water`].
    ///
    /// # Errors
    /// As [`Water::heights_at`].
    #[deprecated(since = "0.4.0", note = "use `ocean.water().heights_at(points, out)`")]
    #[doc(hidden)]
    pub fn heights_at(&self, points: &[[f64; 2]], out: &mut [f32]) -> Result<(), Error> {
        self.water().heights_at(points, out)
    }

    /// Deprecated: [`Water::surfaces_at`] through [`OceanState::water`].
    ///
    /// # Errors
    /// As [`Water::surfaces_at`].
    #[deprecated(since = "0.4.0", note = "use `ocean.water().surfaces_at(points, out)`")]
    #[doc(hidden)]
    pub fn surfaces_at(&self, points: &[[f64; 2]], out: &mut [SurfaceSample]) -> Result<(), Error> {
        self.water().surfaces_at(points, out)
    }

    /// Deprecated: [`Water::at_rest_many`] through [`OceanState::water`].
    ///
    /// # Errors
    /// As [`Water::at_rest_many`].
    #[deprecated(
        since = "0.4.0",
        note = "use `ocean.water().at_rest_many(points, out)`"
    )]
    #[doc(hidden)]
    pub fn sample_many(&self, points: &[[f64; 2]], out: &mut [SurfaceSample]) -> Result<(), Error> {
        self.water().at_rest_many(points, out)
    }

    /// Deprecated: [`Water::at_rest_grid`] through [`OceanState::water`].
    ///
    /// # Errors
    /// As [`Water::at_rest_grid`].
    #[deprecated(
        since = "0.4.0",
        note = "use `ocean.water().at_rest_grid(origin, spacing, [columns, rows], out)`"
    )]
    #[doc(hidden)]
    pub fn sample_grid(
        &self,
        origin: [f64; 2],
        spacing: f64,
        size: [usize; 2],
        out: &mut [SurfaceSample],
    ) -> Result<(), Error> {
        self.water().at_rest_grid(origin, spacing, size, out)
    }
}
