//! The hub at the end of the data flow, what a game holds ([`OceanState`]): several cascades of
//! one spectrum on disjoint wave-number bands, the time, and the foam, stepped together and
//! queried through the world queries; its config, its fit to a sea, its changes of weather and
//! its snapshots.

mod coast_api;
mod config;
mod diagnostics;
mod fit;
mod foam_api;
pub mod limits;
mod live;
mod query_api;
mod snapshot;
mod time;
mod wake_api;

use crate::cascade::{Cascade, LoopError};
use crate::error::{self, Error};
use crate::foam::Foam;
use crate::query::frame::{Frame, Frames};
use crate::spectrum::Spectrum;
use crate::wake::sim::WakeSim;

pub use config::OceanConfig;
pub use diagnostics::Diagnostics;
pub use fit::SeaFit;
pub use snapshot::OceanSnapshot;

/// An ocean: cascades of one spectrum over disjoint wave-number bands, the time, and foam.
///
/// What it does, by group:
///
/// - **Stepping**: [`new`](Self::new), [`step`](Self::step), [`step_to`](Self::step_to),
///   [`set_time`](Self::set_time), [`pre_roll`](Self::pre_roll), [`time`](Self::time).
/// - **Weather**: [`set_spectrum`](Self::set_spectrum) (a change over simulated time),
///   [`set_spectrum_unfitted`](Self::set_spectrum_unfitted),
///   [`set_choppiness`](Self::set_choppiness), [`set_foam_config`](Self::set_foam_config),
///   [`spectrum`](Self::spectrum), [`config`](Self::config).
/// - **Queries**: [`water`](Self::water) for the world queries (heights and surfaces at world
///   points, samples at rest points, batches, grids), [`surface`](Self::surface) for a handle
///   other threads query while the ocean steps.
/// - **Foam**: [`foam`](Self::foam) (the field), [`foam_view`](Self::foam_view) (its parts,
///   breaking, values at a point, coverage, calibration), [`clear_foam`](Self::clear_foam).
/// - **Buffers and textures**: [`cascades`](Self::cascades) (each cascade's buffers),
///   [`textures`](Self::textures) (texels with the foam, the sub-grid slope variance).
/// - **Wakes** (with [`OceanConfig::wakes`]): [`set_hulls`](Self::set_hulls),
///   [`set_wake_centre`](Self::set_wake_centre), [`wakes`](Self::wakes).
/// - **Snapshots**: [`snapshot`](Self::snapshot), [`restore`](Self::restore) (and
///   [`OceanSnapshot::capture`] to refill one without allocating).
/// - **Diagnostics**: [`diagnostics`](Self::diagnostics) (what the grids hold of the sea, the
///   progress of a change of weather, the largest choppiness, the loop error, the mean level,
///   the expected variance).
///
/// The limits its calls check (the longest step, the share of a sea the grids must hold, …)
/// are constants of the [`limits`] module.
///
/// ```
/// use ocean_fft::{OceanConfig, OceanState, Spectrum};
/// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
/// let config = OceanConfig { size: 64, ..OceanConfig::default() };
/// let mut ocean = OceanState::new(spectrum, config)?;
/// ocean.step(1.0 / 60.0)?;                              // s
/// let water = ocean.water();
/// let y = water.height_at(12.0, -40.0)?;                // m, water height at world (x, z)
/// let s = water.at_rest(12.0, -40.0)?;                  // the water resting at (x0, z0), m
/// assert!(y.is_finite() && s.height.is_finite());
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
    #[deprecated(since = "0.4.0", note = "use `ocean_fft::limits::MAX_STEP`")]
    #[doc(hidden)]
    pub const MAX_STEP: f64 = limits::MAX_STEP;

    /// Builds the cascades (h0 of each drawn once) on the bands of
    /// [`OceanConfig::bands`], at t = 0 with no foam, and calibrates the whitecaps (the
    /// breaking threshold, [`calibration`](crate::FoamView::calibration)).
    ///
    /// # Errors
    /// Those of [`OceanConfig::validate`] and of [`Cascade::new`] for each cascade;
    /// [`Error::SeaDoesNotFit`] naming `spectrum` if the grids hold less than
    /// [`limits::MIN_BUILD_SHARE`] of its variance (the message says whether
    /// the largest tile or the finest cell is at fault; [`OceanConfig::fitted`] gives grids
    /// that hold it); [`Error::OutOfRange`] naming `choppiness` above
    /// [`max_choppiness`](super::Diagnostics::max_choppiness);
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
                let sim = WakeSim::new(
                    wakes,
                    spectrum.dispersion(),
                    config.determinism,
                    0.0,
                    config.foam.residual_decay,
                )?;
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
    /// [`max_choppiness`](super::Diagnostics::max_choppiness), where the surface folds nearly everywhere
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

    /// Deprecated: [`Diagnostics::loop_error`] through [`OceanState::diagnostics`].
    #[deprecated(since = "0.4.0", note = "use `ocean.diagnostics().loop_error()`")]
    #[doc(hidden)]
    pub fn loop_error(&self) -> Option<LoopError> {
        self.diagnostics().loop_error()
    }

    /// Deprecated: [`Diagnostics::mean_level_offset`] through [`OceanState::diagnostics`].
    #[deprecated(
        since = "0.4.0",
        note = "use `ocean.diagnostics().mean_level_offset()`"
    )]
    #[doc(hidden)]
    pub fn mean_level_offset(&self) -> f32 {
        self.diagnostics().mean_level_offset()
    }

    /// Deprecated: [`Diagnostics::expected_variance`] through [`OceanState::diagnostics`].
    #[deprecated(
        since = "0.4.0",
        note = "use `ocean.diagnostics().expected_variance()`"
    )]
    #[doc(hidden)]
    pub fn expected_variance(&self) -> f64 {
        self.diagnostics().expected_variance()
    }
}
