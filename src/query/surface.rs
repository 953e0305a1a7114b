//! A handle on the water of one frame, [`Surface`]: the world queries ([`Water`]) from any
//! thread while the ocean steps on, with the bits the ocean's own queries give.

use std::sync::Arc;

use super::frame::{Fields, Frame, Frames};
use super::results::{Location, SurfaceSample};
use super::water::Water;
use crate::cascade::Cascade;
use crate::error::Error;
use crate::foam::Foam;

/// A handle on the water of one frame: the ocean's fields at the time
/// [`OceanState::surface`](crate::OceanState::surface) was called, answering the same world
/// queries as the ocean (its [`water`](Surface::water): [`Water::height_at`],
/// [`Water::heights_at`], …) with the same bits, from any thread and while the ocean steps on.
///
/// `Send + Sync + Clone` (an [`Arc`]: cloning costs an atomic increment). The ocean keeps
/// two frames: a step writes the one no handle reads and makes it current, so taking a
/// handle every frame and dropping it within the next step costs no allocation and never
/// makes the step wait. A handle kept across two steps makes the second one allocate a third
/// frame (as large as the query data of every cascade: about 24·N² bytes per cascade and
/// the fields' 20·N²); the old frame is freed when its last handle drops.
///
/// ```
/// use ocean_fft::{OceanConfig, OceanState, Spectrum};
/// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
/// let mut ocean = OceanState::new(spectrum, OceanConfig { size: 32, ..Default::default() })?;
/// ocean.step(1.0 / 60.0)?;
/// let surface = ocean.surface();                  // the water at t = 1/60 s
/// let physics = std::thread::spawn(move || surface.water().height_at(3.0, 4.0));
/// let y = ocean.water().height_at(3.0, 4.0)?;     // m
/// ocean.step(1.0 / 60.0)?;                        // the handle still answers about 1/60 s
/// assert_eq!(physics.join().unwrap()?, y);
/// # Ok::<(), ocean_fft::Error>(())
/// ```
#[derive(Clone)]
pub struct Surface(pub(crate) Arc<Frame>);

impl std::fmt::Debug for Surface {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Surface")
            .field("time", &self.0.time)
            .field("cascades", &self.0.grids.len())
            .finish_non_exhaustive()
    }
}

impl Surface {
    /// Simulated time in seconds of the water this handle answers about.
    pub fn time(&self) -> f64 {
        self.0.time
    }

    /// The world queries of this frame: the same [`Water`] an ocean's
    /// [`OceanState::water`](crate::OceanState::water) gives, answering with the same bits.
    #[inline]
    pub fn water(&self) -> Water<'_> {
        Water::new(Fields::Frame(&self.0))
    }

    /// Deprecated: [`Water::at_rest`] through [`Surface::water`].
    ///
    /// # Errors
    /// As [`Water::at_rest`].
    #[deprecated(since = "0.4.0", note = "use `surface.water().at_rest(x0, z0)`")]
    #[doc(hidden)]
    pub fn sample(&self, x: f64, z: f64) -> Result<SurfaceSample, Error> {
        self.water().at_rest(x, z)
    }

    /// Deprecated: [`Water::locate`] through [`Surface::water`].
    ///
    /// # Errors
    /// As [`Water::locate`].
    #[deprecated(since = "0.4.0", note = "use `surface.water().locate(x, z)`")]
    #[doc(hidden)]
    pub fn locate(&self, x: f64, z: f64) -> Result<Location, Error> {
        self.water().locate(x, z)
    }

    /// Deprecated: [`Water::surface_at`] through [`Surface::water`].
    ///
    /// # Errors
    /// As [`Water::surface_at`].
    #[deprecated(since = "0.4.0", note = "use `surface.water().surface_at(x, z)`")]
    #[doc(hidden)]
    pub fn surface_at(&self, x: f64, z: f64) -> Result<SurfaceSample, Error> {
        self.water().surface_at(x, z)
    }

    /// Deprecated: [`Water::height_at`] through [`Surface::water`].
    ///
    /// # Errors
    /// As [`Water::height_at`].
    #[deprecated(since = "0.4.0", note = "use `surface.water().height_at(x, z)`")]
    #[doc(hidden)]
    pub fn height_at(&self, x: f64, z: f64) -> Result<f32, Error> {
        self.water().height_at(x, z)
    }

    /// Deprecated: [`Water::heights_at`] through [`Surface::water`].
    ///
    /// # Errors
    /// As [`Water::heights_at`].
    #[deprecated(
        since = "0.4.0",
        note = "use `surface.water().heights_at(points, out)`"
    )]
    #[doc(hidden)]
    pub fn heights_at(&self, points: &[[f64; 2]], out: &mut [f32]) -> Result<(), Error> {
        self.water().heights_at(points, out)
    }

    /// Deprecated: [`Water::surfaces_at`] through [`Surface::water`].
    ///
    /// # Errors
    /// As [`Water::surfaces_at`].
    #[deprecated(
        since = "0.4.0",
        note = "use `surface.water().surfaces_at(points, out)`"
    )]
    #[doc(hidden)]
    pub fn surfaces_at(&self, points: &[[f64; 2]], out: &mut [SurfaceSample]) -> Result<(), Error> {
        self.water().surfaces_at(points, out)
    }

    /// Deprecated: [`Water::at_rest_many`] through [`Surface::water`].
    ///
    /// # Errors
    /// As [`Water::at_rest_many`].
    #[deprecated(
        since = "0.4.0",
        note = "use `surface.water().at_rest_many(points, out)`"
    )]
    #[doc(hidden)]
    pub fn sample_many(&self, points: &[[f64; 2]], out: &mut [SurfaceSample]) -> Result<(), Error> {
        self.water().at_rest_many(points, out)
    }
}

impl Frames {
    /// A handle on the current frame, copying the fields into it first if no handle did.
    pub(crate) fn surface(&mut self, cascades: &[Cascade], foam: &Foam) -> Surface {
        if !self.current.detached {
            if Arc::get_mut(&mut self.current).is_none() {
                // Only a handle shares a frame, and handles detach it first; kept for safety.
                self.current = Arc::new(self.current.as_ref().clone());
            }
            if let Some(frame) = Arc::get_mut(&mut self.current) {
                frame.detach(cascades, foam);
            }
        }
        Surface(Arc::clone(&self.current))
    }
}
