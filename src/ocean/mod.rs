//! What a game holds: several cascades of one spectrum on disjoint wave-number bands, the
//! time, and the foam.

mod config;
mod foam;
mod query;

use rayon::prelude::*;

use crate::cascade::{check_time, Cascade};
use crate::error::{self, Error};
use crate::spectrum::Spectrum;

pub use config::{OceanConfig, BAND_SPLIT};
pub use foam::FoamConfig;
pub use query::{SurfaceSample, HEIGHT_AT_MAX_ITERATIONS, HEIGHT_AT_TOLERANCE, PARALLEL_BATCH};

/// Largest accepted time step of [`OceanState::step`], in seconds.
pub const MAX_STEP: f64 = 3600.0;

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
    /// Builds the cascades (h0 of each drawn once) on the bands of
    /// [`OceanConfig::bands`], at t = 0 with no foam.
    pub fn new(spectrum: Spectrum, config: OceanConfig) -> Result<OceanState, Error> {
        config.validate()?;
        let bands = config.bands();
        let cascades = bands
            .iter()
            .enumerate()
            .map(|(index, &band)| Cascade::new(&spectrum, config.cascade_config(index, band)))
            .collect::<Result<Vec<_>, _>>()?;
        let foam = cascades
            .iter()
            .map(|c| vec![0.0; c.size() * c.size()])
            .collect();
        Ok(OceanState {
            spectrum,
            config,
            cascades,
            foam,
            time: 0.0,
        })
    }

    /// Advances the time by `dt` seconds (0 ≤ dt ≤ [`MAX_STEP`]), updates every cascade and
    /// the foam. Allocates nothing.
    pub fn step(&mut self, dt: f64) -> Result<(), Error> {
        if !dt.is_finite() {
            return Err(Error::NonFinite { name: "dt" });
        }
        if !(0.0..=MAX_STEP).contains(&dt) {
            return Err(Error::OutOfRange {
                name: "dt",
                value: dt,
                expected: "in [0, 3600] s",
            });
        }
        let t = self.time + dt;
        // One job handed to rayon per step (see `Cascade::update`).
        rayon::scope(|_| {
            self.update_cascades(t)?;
            self.time = t;
            self.advance_foam(dt as f32);
            Ok(())
        })
    }

    /// Jumps to time `t` in seconds (|t| ≤ [`crate::MAX_TIME`]) and updates every cascade.
    /// The foam has no history across a jump: it is cleared.
    pub fn set_time(&mut self, t: f64) -> Result<(), Error> {
        self.update_cascades(t)?;
        self.time = t;
        for foam in &mut self.foam {
            foam.fill(0.0);
        }
        Ok(())
    }

    fn update_cascades(&mut self, t: f64) -> Result<(), Error> {
        // Validate once up front so that either every cascade is updated or none is.
        check_time(t)?;
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

    /// Foam coverage in [0, 1] of cascade `index` on that cascade's grid (index j·N + i),
    /// or `None` for an index past the last cascade.
    pub fn foam(&self, index: usize) -> Option<&[f32]> {
        self.foam.get(index).map(Vec::as_slice)
    }

    /// Sets the choppiness λ ≥ 0 of every cascade (takes effect at the next step).
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
