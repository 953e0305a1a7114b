//! The hub at the end of the data flow, what a game holds ([`OceanState`]): several cascades of
//! one spectrum on disjoint wave-number bands, the time, and the foam, stepped together and
//! queried through the world queries; its config, its fit to a sea, its changes of weather and
//! its snapshots.

mod config;
mod fit;
mod foam_api;
mod live;
mod query_api;
mod snapshot;
mod time;
mod wake_api;

use crate::cascade::{Cascade, LoopError};
use crate::error::{self, Error};
use crate::foam::Foam;
use crate::query::frame::{Frame, Frames};
use crate::spectrum::{SlopeVariance, Spectrum};
use crate::wake::sim::WakeSim;

pub use config::OceanConfig;
pub use fit::SeaFit;
pub use snapshot::OceanSnapshot;

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
///
/// `Clone` copies the whole ocean (every cascade's tables and buffers); for rollback and save
/// games, [`OceanState::snapshot`] keeps only the state that cannot be recomputed.
#[derive(Debug, Clone)]
pub struct OceanState {
    pub(crate) spectrum: Spectrum,
    pub(crate) config: OceanConfig,
    pub(crate) cascades: Vec<Cascade>,
    pub(crate) foam: Foam,
    /// What the world queries read about the current frame (the cubic B-spline
    /// coefficients, computed tile by tile by the queries that read them), and the frame
    /// before it while a [`Surface`](crate::Surface) handle may hold it.
    pub(crate) frames: Frames,
    pub(crate) time: f64,
    /// The choppiness the cascades' buffers were last computed with (a new choppiness takes
    /// effect at the next update).
    pub(crate) applied_choppiness: f32,
    /// A change of weather in progress ([`OceanState::set_spectrum`]).
    pub(crate) change: Option<live::Change>,
    /// The wake layer ([`OceanConfig::wakes`]); its buffers live in the current frame.
    pub(crate) wake: Option<WakeSim>,
}

impl OceanState {
    /// Largest accepted time step of [`OceanState::step`], in seconds.
    pub const MAX_STEP: f64 = 3600.0;

    /// Builds the cascades (h0 of each drawn once) on the bands of
    /// [`OceanConfig::bands`], at t = 0 with no foam, and calibrates the whitecaps (the
    /// breaking threshold, [`foam_calibration`](Self::foam_calibration)).
    ///
    /// # Errors
    /// Those of [`OceanConfig::validate`] and of [`Cascade::new`] for each cascade;
    /// [`Error::SeaDoesNotFit`] naming `spectrum` if the grids hold less than
    /// [`MIN_BUILD_SHARE`](Self::MIN_BUILD_SHARE) of its variance (the message says whether
    /// the largest tile or the finest cell is at fault; [`OceanConfig::fitted`] gives grids
    /// that hold it); [`Error::OutOfRange`] naming `choppiness` above
    /// [`max_choppiness`](Self::max_choppiness);
    /// [`Error::AmplitudeTooLarge`] also if, with [`OceanConfig::second_order`], the
    /// second-order terms could overflow f32; [`Error::OutOfMemory`] if the system refuses the
    /// foam's or the second order's buffers.
    pub fn new(spectrum: Spectrum, config: OceanConfig) -> Result<OceanState, Error> {
        let bands = config.bands()?;
        let cascades = bands
            .iter()
            .enumerate()
            .map(|(index, &band)| Cascade::new(&spectrum, config.cascade_config(index, band)))
            .collect::<Result<Vec<_>, _>>()?;
        // After the cascades' own checks, whose errors (an amplitude that could overflow)
        // say more about an absurd spectrum.
        fit::check_build_fit(&spectrum, &config, &bands)?;
        fit::check_choppiness(&spectrum, &bands, config.choppiness)?;
        let mut cascades = cascades;
        if config.second_order {
            if let Some(first) = cascades.first_mut() {
                first.enable_second_order()?;
            }
        }
        let foam = Foam::new(&mut cascades, &config.foam, &spectrum)?;
        let mut frame = Frame::new(config.query, config.determinism, &cascades, &foam, 0.0)?;
        let wake = match &config.wakes {
            Some(wakes) => {
                let sim = WakeSim::new(wakes, spectrum.dispersion(), config.determinism, 0.0)?;
                let mut output = sim.new_output()?;
                sim.write(&mut output, 0.0);
                frame.wake = Some(output);
                Some(sim)
            }
            None => None,
        };
        let frames = Frames::new(frame);
        Ok(OceanState {
            spectrum,
            applied_choppiness: config.choppiness,
            config,
            cascades,
            foam,
            frames,
            time: 0.0,
            change: None,
            wake,
        })
    }

    /// Removes all foam (coverage 0 everywhere; the breaking intensity, a function of the
    /// time, stays).
    pub fn clear_foam(&mut self) {
        self.foam.clear();
        // Handles taken before keep the foam they saw.
        self.frames.advance(self.time, self.config.query);
        self.write_wake();
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

    /// Sets the choppiness λ ≥ 0 of every cascade (takes effect at the next step).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] naming `choppiness` above
    /// [`max_choppiness`](Self::max_choppiness), where the surface folds nearly everywhere
    /// it can; as [`Cascade::set_choppiness`], for any cascade; no cascade changes then.
    /// (The check costs a slope quadrature, about a millisecond: set it when it changes, not
    /// every frame.)
    pub fn set_choppiness(&mut self, choppiness: f32) -> Result<(), Error> {
        self.check_choppiness(choppiness)?;
        self.set_choppiness_checked(choppiness);
        Ok(())
    }

    /// The checks of [`set_choppiness`](Self::set_choppiness), for every cascade, without the
    /// change.
    fn check_choppiness(&self, choppiness: f32) -> Result<(), Error> {
        let lambda = error::non_negative("choppiness", choppiness)?;
        for cascade in &self.cascades {
            cascade.check_choppiness(lambda)?;
        }
        fit::check_choppiness(&self.spectrum, &self.config.bands_unchecked(), lambda)?;
        Ok(())
    }

    /// Sets a choppiness [`check_choppiness`](Self::check_choppiness) accepted.
    fn set_choppiness_checked(&mut self, choppiness: f32) {
        for cascade in &mut self.cascades {
            cascade.set_choppiness_checked(choppiness);
        }
        self.config.choppiness = choppiness;
    }

    /// How far the repeat period moved the waves' frequencies, over every cascade (`None`
    /// without one): the largest relative error, and the mean weighted by each wave's share
    /// of the height variance.
    pub fn loop_error(&self) -> Option<LoopError> {
        LoopError::combine(self.cascades.iter().filter_map(Cascade::loop_error))
    }

    /// The mean-level correction in metres in the summed height: the sum of every cascade's
    /// [`Cascade::mean_level_offset`], λ·2 Σ_k |k| |h0(k)|² over all of them. With it the
    /// Eulerian mean of the displaced surface is still water (y = 0) for any choppiness;
    /// without it the sea would sit about λ ∫ k S(k) d²k lower (about 4.8 cm for the
    /// default sea at λ = 1, 34 cm for the storm preset at its λ = 1.2).
    pub fn mean_level_offset(&self) -> f32 {
        self.cascades.iter().map(Cascade::mean_level_offset).sum()
    }

    /// Slope variance along and across the wind that the spectrum holds above the finest
    /// cascade's band, up to [`SlopeVariance::DEFAULT_CUTOFF`]: the roughness the grids
    /// cannot show (the last cascade's [`Cascade::subgrid_slope_variance`]; a cascade `c`
    /// reports what lies above its own band). For another cut-off use
    /// [`Spectrum::slope_variance`] from the top of the last band.
    pub fn subgrid_slope_variance(&self) -> SlopeVariance {
        self.cascades
            .last()
            .map(Cascade::subgrid_slope_variance)
            .unwrap_or_default()
    }

    /// Expected variance of the summed height in m²: the sum over cascades of
    /// [`Cascade::expected_variance`]; 4√ of it is the expected H_s of the simulated sea.
    pub fn expected_variance(&self) -> f64 {
        self.cascades.iter().map(Cascade::expected_variance).sum()
    }
}
