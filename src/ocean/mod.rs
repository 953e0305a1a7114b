//! What a game holds: several cascades of one spectrum on disjoint wave-number bands, the
//! time, and the foam.

mod config;
mod foam;
mod query;

use rayon::prelude::*;

use std::ops::Bound::Included;

use crate::cascade::{check_time, Cascade};
use crate::error::{self, Error};
use crate::spectrum::Spectrum;

pub use config::{OceanConfig, QueryConfig};
pub use foam::FoamConfig;
pub use query::SurfaceSample;

/// An ocean: cascades of one spectrum over disjoint wave-number bands, the time, and foam.
///
/// ```
/// use ocean_fft::{OceanConfig, OceanState, Spectrum};
/// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
/// let config = OceanConfig { size: 64, ..OceanConfig::default() };
/// let mut ocean = OceanState::new(spectrum, config)?;
/// ocean.step(1.0 / 60.0)?;                       // s
/// let s = ocean.sample(12.0, -40.0)?;            // world x, z in m
/// let y = ocean.height_at(12.0, -40.0)?;         // water height at that point, m
/// assert!(s.height.is_finite() && y.is_finite());
/// # Ok::<(), ocean_fft::Error>(())
/// ```
#[derive(Debug)]
pub struct OceanState {
    pub(crate) spectrum: Spectrum,
    pub(crate) config: OceanConfig,
    pub(crate) cascades: Vec<Cascade>,
    pub(crate) foam: Vec<Vec<f32>>,
    pub(crate) time: f64,
}

impl OceanState {
    /// Largest accepted time step of [`OceanState::step`], in seconds.
    pub const MAX_STEP: f64 = 3600.0;

    /// Builds the cascades (h0 of each drawn once) on the bands of
    /// [`OceanConfig::bands`], at t = 0 with no foam.
    ///
    /// # Errors
    /// Those of [`OceanConfig::validate`] and of [`Cascade::new`] for each cascade.
    pub fn new(spectrum: Spectrum, config: OceanConfig) -> Result<OceanState, Error> {
        let bands = config.bands()?;
        let cascades = bands
            .iter()
            .enumerate()
            .map(|(index, &band)| Cascade::new(&spectrum, config.cascade_config(index, band)))
            .collect::<Result<Vec<_>, _>>()?;
        let foam = cascades
            .iter()
            .map(|c| error::try_vec(c.size() * c.size(), 0.0))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(OceanState {
            spectrum,
            config,
            cascades,
            foam,
            time: 0.0,
        })
    }

    /// Advances the time by `dt` seconds (0 ≤ dt ≤ [`MAX_STEP`](Self::MAX_STEP)), updates
    /// every cascade and the foam. Allocates nothing inside a rayon pool.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for `dt`, or for the new time
    /// (`time + dt`) beyond [`Cascade::MAX_TIME`]. Nothing changes then.
    pub fn step(&mut self, dt: f64) -> Result<(), Error> {
        error::in_range_f64("dt", dt, Included(0.0), Included(Self::MAX_STEP))?;
        let t = check_time("time + dt", self.time + dt)?;
        // One job handed to rayon per step (see `Cascade::update`).
        rayon::scope(|_| {
            self.update_cascades(t)?;
            self.time = t;
            self.advance_foam(dt as f32);
            Ok(())
        })
    }

    /// Jumps to time `t` in seconds (|t| ≤ [`Cascade::MAX_TIME`]) and updates every cascade.
    /// The foam has no history across a jump: it is cleared.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for `t`. Nothing changes then.
    pub fn set_time(&mut self, t: f64) -> Result<(), Error> {
        check_time("t", t)?;
        self.update_cascades(t)?;
        self.time = t;
        for foam in &mut self.foam {
            foam.fill(0.0);
        }
        Ok(())
    }

    /// Updates every cascade to a time already checked, so that either every cascade is
    /// updated or none is.
    fn update_cascades(&mut self, t: f64) -> Result<(), Error> {
        if self.config.parallel_cascades {
            self.cascades
                .par_iter_mut()
                .try_for_each(|cascade| cascade.update(t))
        } else {
            self.cascades
                .iter_mut()
                .try_for_each(|cascade| cascade.update(t))
        }
    }

    /// Simulated time in seconds.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The spectrum the cascades were drawn from.
    pub fn spectrum(&self) -> &Spectrum {
        &self.spectrum
    }

    /// The configuration this ocean was built with.
    pub fn config(&self) -> &OceanConfig {
        &self.config
    }

    /// The cascades, largest first.
    pub fn cascades(&self) -> &[Cascade] {
        &self.cascades
    }

    /// Foam coverage in [0, 1] of cascade `index` (0 the largest) on that cascade's grid
    /// (index j·N + i).
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`] unless `index` is below the number of cascades.
    pub fn foam(&self, index: usize) -> Result<&[f32], Error> {
        error::index("index", index, self.foam.len())?;
        Ok(&self.foam[index])
    }

    /// Sets the choppiness λ ≥ 0 of every cascade (takes effect at the next step).
    ///
    /// # Errors
    /// As [`Cascade::set_choppiness`], for any cascade; no cascade changes then.
    pub fn set_choppiness(&mut self, choppiness: f32) -> Result<(), Error> {
        let lambda = error::non_negative("choppiness", choppiness)?;
        // Check every cascade before changing any, so an error leaves them all as they were.
        for cascade in &self.cascades {
            cascade.check_choppiness(lambda)?;
        }
        for cascade in &mut self.cascades {
            cascade.set_choppiness(lambda)?;
        }
        self.config.choppiness = lambda;
        Ok(())
    }

    /// Expected variance of the summed height in m²: the sum over cascades of
    /// [`Cascade::expected_variance`]; 4√ of it is the expected H_s of the simulated sea.
    pub fn expected_variance(&self) -> f64 {
        self.cascades.iter().map(Cascade::expected_variance).sum()
    }
}
