//! A handle on the water of one frame, [`Surface`]: the world queries from any thread while
//! the ocean steps on, with the bits the ocean's own queries give.

use std::sync::Arc;

use super::batch::{check_batch, for_each_point};
use super::frame::{Fields, Frame, Frames};
use super::point::{check_point, run, HeightAt, Locate, Sample, SurfaceAt};
use super::results::{Location, SurfaceSample};
use crate::cascade::Cascade;
use crate::error::Error;
use crate::foam::Foam;

/// A handle on the water of one frame: the ocean's fields at the time
/// [`OceanState::surface`](crate::OceanState::surface) was called, answering the same world queries
/// as the ocean ([`Surface::height_at`], [`Surface::heights_at`], …) with the same bits, from any
/// thread and while the ocean steps on.
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
/// let physics = std::thread::spawn(move || surface.height_at(3.0, 4.0));
/// let y = ocean.height_at(3.0, 4.0)?;             // m
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

    /// As [`OceanState::sample`](crate::OceanState::sample), for this frame.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn sample(&self, x: f64, z: f64) -> Result<SurfaceSample, Error> {
        check_point(x, z)?;
        Ok(run(
            &Fields::Frame(&self.0),
            Sample(0..self.0.grids.len()),
            x,
            z,
        ))
    }

    /// As [`OceanState::locate`](crate::OceanState::locate), for this frame.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn locate(&self, x: f64, z: f64) -> Result<Location, Error> {
        check_point(x, z)?;
        Ok(run(&Fields::Frame(&self.0), Locate, x, z))
    }

    /// As [`OceanState::surface_at`](crate::OceanState::surface_at), for this frame.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn surface_at(&self, x: f64, z: f64) -> Result<SurfaceSample, Error> {
        check_point(x, z)?;
        Ok(run(&Fields::Frame(&self.0), SurfaceAt, x, z))
    }

    /// Water height y in metres at world point (`x`, `z`) after horizontal displacement, as
    /// [`OceanState::height_at`](crate::OceanState::height_at), for this frame.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn height_at(&self, x: f64, z: f64) -> Result<f32, Error> {
        check_point(x, z)?;
        Ok(run(&Fields::Frame(&self.0), HeightAt, x, z))
    }

    /// As [`OceanState::heights_at`](crate::OceanState::heights_at), for this frame: water heights
    /// in metres at world points (x, z), into `out`.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless `out` is as long as `points`; [`Error::NonFinite`]
    /// for a NaN or infinite coordinate. Nothing is written then.
    pub fn heights_at(&self, points: &[[f64; 2]], out: &mut [f32]) -> Result<(), Error> {
        check_batch(points, out.len())?;
        for_each_point(&Fields::Frame(&self.0), points, out, HeightAt);
        Ok(())
    }

    /// As [`OceanState::surfaces_at`](crate::OceanState::surfaces_at), for this frame.
    ///
    /// # Errors
    /// As [`Surface::heights_at`].
    pub fn surfaces_at(&self, points: &[[f64; 2]], out: &mut [SurfaceSample]) -> Result<(), Error> {
        check_batch(points, out.len())?;
        for_each_point(&Fields::Frame(&self.0), points, out, SurfaceAt);
        Ok(())
    }

    /// As [`OceanState::sample_many`](crate::OceanState::sample_many), for this frame.
    ///
    /// # Errors
    /// As [`Surface::heights_at`].
    pub fn sample_many(&self, points: &[[f64; 2]], out: &mut [SurfaceSample]) -> Result<(), Error> {
        check_batch(points, out.len())?;
        for_each_point(
            &Fields::Frame(&self.0),
            points,
            out,
            Sample(0..self.0.grids.len()),
        );
        Ok(())
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
