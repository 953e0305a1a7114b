//! The live sea: a change of weather while the ocean runs ([`OceanState::set_spectrum`]) and
//! live foam settings ([`OceanState::set_foam_config`]).

use std::ops::Bound::Included;

use crate::cascade::Cascade;
use crate::determinism::with_math;
use crate::error::{self, Error};
use crate::spectrum::Spectrum;

use super::foam::FoamConfig;
use super::OceanState;

/// Wave vectors of the band whose new amplitudes a step draws during a change of weather: a
/// fixed amount (so that the result depends on the steps taken, never on the machine), about
/// a third of a default step's work.
const DRAW_BUDGET: usize = 4096;

/// A change of weather in progress.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Change {
    /// The blend's length in seconds of simulated time.
    duration: f64,
    /// The time the blend began: the step that finished drawing the new amplitudes (`None`
    /// while they are drawn).
    start: Option<f64>,
    /// The new sea's weight at the last update.
    weight: f64,
}

impl Change {
    /// The new sea's weight in energy at time `t`: 0 before the blend begins, 1 from
    /// `start + duration` on, and in between the smoothstep 3τ² − 2τ³ of τ = (t − start)/
    /// duration, whose zero slope at both ends lets waves that appear or vanish grow or
    /// shrink in amplitude at a bounded rate (√3/duration of their full height) rather than
    /// with the infinite rate √τ would give them at the start.
    fn weight_at(&self, t: f64) -> f64 {
        let Some(start) = self.start else {
            return 0.0;
        };
        if t >= start + self.duration {
            return 1.0;
        }
        if t <= start {
            return 0.0;
        }
        let tau = (t - start) / self.duration;
        tau * tau * (3.0 - 2.0 * tau)
    }
}

impl OceanState {
    /// Longest accepted `duration` of [`set_spectrum`](Self::set_spectrum), in seconds (as
    /// long as the ocean's time can run).
    pub const MAX_TRANSITION: f64 = Cascade::MAX_TIME;

    /// Changes the weather: from the current time the sea turns into `spectrum` over
    /// `duration` seconds of simulated time, every wave keeping its phase, the foam kept.
    ///
    /// ```
    /// use ocean_fft::{OceanConfig, OceanState, Spectrum};
    /// let config = OceanConfig { size: 32, ..OceanConfig::default() };
    /// let mut ocean = OceanState::new(Spectrum::jonswap(5.0, 50_000.0)?, config.clone())?;
    /// ocean.step(1.0)?;
    /// let squall = Spectrum::jonswap(15.0, 50_000.0)?;
    /// ocean.set_spectrum(squall.clone(), 30.0)?;      // s: over half a minute
    /// while ocean.transition_progress().is_some() {
    ///     ocean.step(1.0 / 30.0)?;                     // the sea grows, frame by frame
    /// }
    /// // Over: the same bits as an ocean built with the new spectrum.
    /// let mut fresh = OceanState::new(squall, config)?;
    /// fresh.set_time(ocean.time())?;
    /// assert_eq!(ocean.cascades()[0].height(), fresh.cascades()[0].height());
    /// # Ok::<(), ocean_fft::Error>(())
    /// ```
    ///
    /// **How the seas blend.** The random draw of each wave vector depends only on the seed
    /// and the wave vector, so the new spectrum's amplitudes have the same phases as the old
    /// one's: the blend keeps every wave's phase and moves its energy,
    /// `|h0|² = (1 − w)·|h0_old|² + w·|h0_new|²`. Blending energy (not amplitude) makes the
    /// variance, the mean level and
    /// the whitecap statistics move linearly in w from the old sea's to the new sea's, and
    /// never dip (a wind that turns 90° moves energy from one lobe to the other; an amplitude
    /// blend would halve the sea half way). The weight w rises from 0 to 1 as the smoothstep
    /// 3τ² − 2τ³ of the elapsed fraction τ of `duration`, so waves that appear or vanish do so
    /// smoothly; [`expected_variance`](Self::expected_variance) moves monotonically.
    ///
    /// **When.** The new amplitudes are drawn a few rows per step (a fixed amount of work,
    /// about half a default step on top of it), so the blend begins at the step that finishes
    /// them: for the default ocean about 24 steps after the call (0.4 s at 60 fps); `duration`
    /// counts from there. With `duration` 0 they are drawn here at once (this call then costs
    /// about as much as building the cascades) and the next step shows the new sea. Once the
    /// blend is over, every cascade and the foam's model are exactly those of an ocean built
    /// with `spectrum` and this config (the same bits at the same time). A new call during a
    /// change starts from the sea as it is.
    ///
    /// **What the getters say.** [`spectrum`](Self::spectrum) returns `spectrum` from this call
    /// on; [`transition_progress`](Self::transition_progress) the new sea's weight w while
    /// the change lasts; the cascades' buffers, [`Cascade::h0`], the expected variance and
    /// the [foam calibration](Self::foam_calibration) the sea as blended at the last update.
    /// The change is a function of the simulated time: [`set_time`](Self::set_time) before
    /// its start shows the old sea, after its end the new one (and ends the change).
    ///
    /// **Foam.** The foam is kept; its breaking threshold follows the blended sea (calibrated
    /// afresh at w = 0, 1/8, …, 1 and interpolated between), its drift and streaks follow
    /// the wind.
    ///
    /// **Depth.** The water depth, and with it the waves' speeds, cannot change while the
    /// ocean runs: a spectrum with another [`Dispersion`](crate::Dispersion) is refused (waves
    /// whose speed changed would either jump in phase or leave the ocean different from a
    /// freshly built one forever). Build a new ocean for another depth.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for a negative, NaN or infinite
    /// `duration` or one above [`MAX_TRANSITION`](Self::MAX_TRANSITION);
    /// [`Error::SeaDoesNotFit`] naming `spectrum` if the grids hold less than
    /// [`MIN_CHANGE_SHARE`](Self::MIN_CHANGE_SHARE) of its variance (build the ocean for the
    /// roughest sea it will change to, with [`OceanConfig::fitted`](crate::OceanConfig::fitted),
    /// or accept the loss with [`set_spectrum_unfitted`](Self::set_spectrum_unfitted));
    /// [`Error::NotApplicable`] naming `spectrum.dispersion` for another dispersion, or
    /// naming `spectrum` for a sea so steep that the current choppiness is above its
    /// [`max_choppiness`](Self::max_choppiness);
    /// [`Error::AmplitudeTooLarge`] if the new sea is too strong for the grids at the
    /// current choppiness (as [`OceanState::new`] would refuse it); [`Error::OutOfMemory`] if
    /// the system refuses the change's buffers (16 bytes a grid point, once). Nothing
    /// changes then.
    pub fn set_spectrum(&mut self, spectrum: Spectrum, duration: f64) -> Result<(), Error> {
        self.check_change_fit(&spectrum)?;
        self.set_spectrum_unfitted(spectrum, duration)
    }

    /// [`set_spectrum`](Self::set_spectrum) without its checks of the fit and the
    /// choppiness.
    pub(super) fn change_spectrum(
        &mut self,
        spectrum: Spectrum,
        duration: f64,
    ) -> Result<(), Error> {
        error::in_range_f64(
            "duration",
            duration,
            Included(0.0),
            Included(Self::MAX_TRANSITION),
        )?;
        if spectrum.dispersion() != self.spectrum.dispersion() {
            return Err(Error::NotApplicable {
                name: "spectrum.dispersion",
                reason: "a live change keeps the ocean's dispersion (the water depth); build a \
                         new ocean for another",
            });
        }
        self.check_new_amplitudes(&spectrum)?;
        for cascade in &mut self.cascades {
            cascade.reserve_change()?;
        }
        for cascade in &mut self.cascades {
            cascade.begin_change();
        }
        self.foam.begin_change();
        self.spectrum = spectrum;
        self.change = Some(Change {
            duration,
            start: None,
            weight: 0.0,
        });
        if duration == 0.0 {
            self.prepare_change(self.time, true);
        }
        Ok(())
    }

    /// The weight w in [0, 1] of the new sea in a change of weather at the last update
    /// (`None` when no change is in progress): 0 while its amplitudes are drawn, then rising
    /// to 1 over the change's duration (see [`set_spectrum`](Self::set_spectrum)).
    pub fn transition_progress(&self) -> Option<f64> {
        self.change.map(|change| change.weight)
    }

    /// Changes the foam's settings while the ocean runs: the whitecaps are calibrated afresh
    /// for the sea as it is, drift and streaks follow, the foam on the water is kept. A
    /// change of weather in progress goes on with the new settings. Allocates nothing.
    ///
    /// # Errors
    /// Those of [`FoamConfig::validate`]; nothing changes then.
    pub fn set_foam_config(&mut self, config: FoamConfig) -> Result<(), Error> {
        self.foam.set_config(&config)?;
        self.config.foam = config;
        Ok(())
    }

    /// Refuses a spectrum `OceanState::new` would refuse for this config: too strong for a
    /// cascade's grid at the current choppiness. A bound from the spectrum's variance says so
    /// for any sea within a factor of a million of the limit; nearer, the amplitudes are
    /// drawn here and checked exactly.
    fn check_new_amplitudes(&self, spectrum: &Spectrum) -> Result<(), Error> {
        for cascade in &self.cascades {
            cascade.check_amplitudes_for(spectrum)?;
        }
        Ok(())
    }

    /// Moves a change of weather on to time `t`, as part of the step to `t`: while the new sea
    /// is prepared, one piece of that work; then the cascades and the foam blended with the
    /// weight at `t`, and the change ended at weight 1.
    pub(super) fn advance_change(&mut self, t: f64) {
        if self.change.is_some_and(|c| c.start.is_none()) {
            self.prepare_change(t, false);
        }
        let Some(change) = self.change.as_mut() else {
            return;
        };
        let w = change.weight_at(t);
        change.weight = w;
        if change.start.is_none() {
            return;
        }
        for cascade in &mut self.cascades {
            cascade.blend_change(w);
        }
        self.foam.blend_change(w);
        if w >= 1.0 {
            self.change = None;
        }
    }

    /// Prepares the change's new sea: one piece of the work (`all`: every piece left), each
    /// at most about a third of a default step: a few rows of one cascade's new amplitudes,
    /// what one cascade derives from them, the foam's moments of one cascade, the foam's new
    /// model, or one of its calibrations. When nothing is left, the blend begins at time `t`.
    fn prepare_change(&mut self, t: f64, all: bool) {
        let determinism = self.config.determinism;
        loop {
            let spectrum = &self.spectrum;
            if let Some(cascade) = self.cascades.iter_mut().find(|c| !c.change_rows_drawn()) {
                with_math!(determinism, M => cascade.draw_change::<M>(spectrum, DRAW_BUDGET));
            } else if let Some(cascade) = self.cascades.iter_mut().find(|c| !c.change_drawn()) {
                with_math!(determinism, M => cascade.finish_change::<M>(spectrum));
                if cascade.check_change().is_err() {
                    // Not reached: `set_spectrum` checked a bound on these amplitudes.
                    self.cancel_change();
                    return;
                }
            } else if !self.foam.prepare_change(&self.cascades, spectrum) {
                if let Some(change) = self.change.as_mut() {
                    change.start = Some(t);
                }
                return;
            }
            if !all {
                return;
            }
        }
    }

    /// Abandons a change of weather, keeping the sea as it is.
    fn cancel_change(&mut self) {
        for cascade in &mut self.cascades {
            cascade.cancel_change();
        }
        self.foam.cancel_change();
        self.change = None;
    }

    /// Draws whatever is left of a change's new amplitudes at once, so that its blend begins
    /// at time `t` (before a pre-roll, whose steps go back in time).
    pub(super) fn finish_drawing(&mut self, t: f64) {
        if self.change.is_some_and(|c| c.start.is_none()) {
            self.prepare_change(t, true);
        }
    }
}
