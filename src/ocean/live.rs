//! The live sea: a change of weather while the ocean runs ([`OceanState::set_spectrum`]) and
//! live foam settings ([`OceanState::set_foam_config`]).

use std::ops::Bound::Included;

use crate::error::{self, Error};
use crate::math::determinism::with_math;
use crate::spectrum::Spectrum;

use super::OceanState;
use crate::foam::FoamConfig;

/// Wave vectors of the band whose new amplitudes one piece of a change's preparation draws:
/// a fixed amount (so that the pieces are the same on every machine), about a third of a
/// default step's work.
const DRAW_BUDGET: usize = 4096;

/// A change of weather in progress.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Change {
    /// The time of the call, s.
    called: f64,
    /// The blend's length in seconds of simulated time.
    duration: f64,
    /// The time the blend begins: `called` + [`limits::TRANSITION_LAG`](crate::limits::TRANSITION_LAG) (`called` for a
    /// change at once).
    start: f64,
    /// The work that prepares the new sea in wave vectors drawn (see
    /// `OceanState::prepare_piece`), and how much of it is done.
    work: usize,
    done: usize,
    /// Whether every piece is done.
    prepared: bool,
    /// The new sea's weight at the last update (what the cascades and the foam show).
    pub(super) weight: f64,
}

impl Change {
    /// The work of the preparation due by time `t`: the elapsed share of the lag, so that
    /// the work follows simulated time, not steps; all of it from the blend's start on.
    fn work_due(&self, t: f64) -> usize {
        if t >= self.start {
            return usize::MAX;
        }
        let share = (t - self.called) / (self.start - self.called);
        (share * self.work as f64)
            .ceil()
            .clamp(0.0, self.work as f64) as usize
    }

    /// The new sea's weight in energy at time `t`: 0 before the blend begins, 1 from
    /// `start + duration` on, and in between the smoothstep 3τ² − 2τ³ of τ = (t − start)/
    /// duration, whose zero slope at both ends lets waves that appear or vanish grow or
    /// shrink in amplitude at a bounded rate (√3/duration of their full height) rather than
    /// with the infinite rate √τ would give them at the start.
    fn weight_at(&self, t: f64) -> f64 {
        let start = self.start;
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
    #[deprecated(since = "0.4.0", note = "use `ocean_fft::limits::MAX_TRANSITION`")]
    #[doc(hidden)]
    pub const MAX_TRANSITION: f64 = super::limits::MAX_TRANSITION;

    #[deprecated(since = "0.4.0", note = "use `ocean_fft::limits::TRANSITION_LAG`")]
    #[doc(hidden)]
    pub const TRANSITION_LAG: f64 = super::limits::TRANSITION_LAG;

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
    /// smoothly; [`expected_variance`](super::Diagnostics::expected_variance) moves monotonically.
    ///
    /// **When.** With a positive `duration` the blend begins
    /// [`limits::TRANSITION_LAG`](crate::limits::TRANSITION_LAG) seconds of simulated time after the call and
    /// `duration` counts from there. Over the lag the new sea is prepared in pieces of up to
    /// about half a plain step (new amplitudes drawn a few rows at a time, the foam's
    /// calibrations), each step doing the share of the work that the share of the lag
    /// elapsed by its time asks for: on the default ocean at 60 fps about a third of a plain
    /// step a frame. A step that reaches the blend's start does whatever is left (a single
    /// step across the lag does it all: about as much as building the cascades). With
    /// `duration` 0 the new sea is prepared here at once (this call then costs about as much
    /// as building the cascades) and the next step shows it. Once the blend is over, every
    /// cascade and the foam's model are exactly those of an ocean built with `spectrum` and
    /// this config (the same bits at the same time).
    ///
    /// **A function of time.** The waves are a function of the calls, the simulated times
    /// they were made at and the current time, never of the steps between: every cascade
    /// buffer, [`Cascade::h0`](crate::Cascade::h0), the statistics and the
    /// [foam calibration](crate::FoamView::calibration) have the same bits at the same time
    /// whether the ocean stepped at 30 or 144 fps, took one step across the change or jumped
    /// into it with [`set_time`](Self::set_time) (before the blend's start the old sea, during it the blend of that time, after its end the new
    /// sea, and the change is over: a later jump back shows the new sea). A new call during a
    /// change starts from the sea as it is at the current time. The foam on the water is
    /// not a function of time: it is integrated over the steps taken, as always.
    ///
    /// **What the getters say.** [`spectrum`](Self::spectrum) returns `spectrum` from this call
    /// on; [`Diagnostics::transition_progress`](super::Diagnostics::transition_progress)
    /// the new sea's weight w at the
    /// last update while the change lasts (0 before the blend begins); the cascades'
    /// buffers, [`Cascade::h0`](crate::Cascade::h0), the expected variance and the
    /// [foam calibration](crate::FoamView::calibration) the sea as blended at the last update.
    ///
    /// **Foam.** The foam is kept; its breaking threshold follows the blended sea (calibrated
    /// afresh at w = 0, 1/8, …, 1 and interpolated between, so a function of w), its drift
    /// and streaks follow the wind.
    ///
    /// **Depth.** The water depth, and with it the waves' speeds, cannot change while the
    /// ocean runs: a spectrum with another [`Dispersion`](crate::Dispersion) is refused (waves
    /// whose speed changed would either jump in phase or leave the ocean different from a
    /// freshly built one forever). Build a new ocean for another depth. A depth map's
    /// factors are not solved again (see [`set_depth_map`](Self::set_depth_map), "Weather").
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for a negative, NaN or infinite
    /// `duration` or one above [`limits::MAX_TRANSITION`](crate::limits::MAX_TRANSITION);
    /// [`Error::SeaDoesNotFit`] naming `spectrum` if the grids hold less than
    /// [`limits::MIN_CHANGE_SHARE`](crate::limits::MIN_CHANGE_SHARE) of its variance (build the ocean for the
    /// roughest sea it will change to, with [`OceanConfig::fitted`](crate::OceanConfig::fitted),
    /// or accept the loss with [`set_spectrum_unfitted`](Self::set_spectrum_unfitted));
    /// [`Error::NotApplicable`] naming `spectrum.dispersion` for another dispersion, or
    /// naming `spectrum` for a sea so steep that the current choppiness is above its
    /// [`max_choppiness`](super::Diagnostics::max_choppiness);
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
            Included(super::limits::MAX_TRANSITION),
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
        let work = self
            .cascades
            .iter()
            .map(|c| c.change_cost(DRAW_BUDGET))
            .sum::<usize>()
            + self.foam.change_cost(&self.cascades);
        let called = self.time;
        let lag = if duration == 0.0 {
            0.0
        } else {
            super::limits::TRANSITION_LAG
        };
        self.change = Some(Change {
            called,
            duration,
            start: called + lag,
            work,
            done: 0,
            prepared: false,
            weight: 0.0,
        });
        if duration == 0.0 {
            self.prepare_all();
        }
        Ok(())
    }

    #[deprecated(
        since = "0.4.0",
        note = "use `ocean.diagnostics().transition_progress()`"
    )]
    #[doc(hidden)]
    pub fn transition_progress(&self) -> Option<f64> {
        self.diagnostics().transition_progress()
    }

    /// Changes the foam's settings while the ocean runs: the whitecaps are calibrated afresh
    /// for the sea as it is, drift and streaks follow, the wake's foam trail fades with the
    /// new residual lifetime, the foam on the water is kept. A
    /// change of weather in progress goes on with the new settings. Allocates nothing.
    ///
    /// # Errors
    /// Those of [`FoamConfig::validate`]; nothing changes then.
    pub fn set_foam_config(&mut self, config: FoamConfig) -> Result<(), Error> {
        self.foam.set_config(&config)?;
        if let Some(wake) = &mut self.wake {
            wake.set_foam_lifetime(config.residual_decay, self.config.determinism);
        }
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

    /// Moves a change of weather on to time `t`, as part of the step to `t`: the pieces of
    /// the preparation due by `t` (all that are left from the blend's start on), then the
    /// cascades and the foam blended with the weight at `t` (only the foam when the weight is
    /// the last one), and the change ended at weight 1.
    pub(super) fn advance_change(&mut self, t: f64) {
        let Some(change) = self.change else {
            return;
        };
        if !change.prepared {
            let due = change.work_due(t);
            let mut done = change.done;
            let mut prepared = false;
            while done < due && self.change.is_some() {
                let Some(work) = self.prepare_piece() else {
                    prepared = true;
                    break;
                };
                done = done.saturating_add(work);
            }
            let Some(change) = self.change.as_mut() else {
                return; // Cancelled.
            };
            change.done = done;
            change.prepared = prepared;
        }
        let Some(change) = self.change.as_mut() else {
            return;
        };
        let w = change.weight_at(t);
        if change.prepared {
            if w != change.weight {
                for cascade in &mut self.cascades {
                    cascade.blend_change(w);
                }
            }
            self.foam.blend_change(w);
        }
        change.weight = w;
        if w >= 1.0 {
            self.change = None;
        }
    }

    /// Does the next piece of the work that prepares the change's new sea, each at most about
    /// half a default step: a few rows of one cascade's new amplitudes, what one cascade
    /// derives from them, one cascade's blend coefficients, the foam's moments of one
    /// cascade, the foam's new model, or one of its calibrations. Returns its cost in wave
    /// vectors drawn, `None` if none was left (the change may have been cancelled then).
    fn prepare_piece(&mut self) -> Option<usize> {
        let determinism = self.config.determinism;
        let spectrum = &self.spectrum;
        if let Some(cascade) = self.cascades.iter_mut().find(|c| !c.change_rows_drawn()) {
            Some(with_math!(determinism, M => cascade.draw_change::<M>(spectrum, DRAW_BUDGET)))
        } else if let Some(cascade) = self.cascades.iter_mut().find(|c| !c.change_drawn()) {
            with_math!(determinism, M => cascade.finish_change::<M>(spectrum));
            let cost = cascade.finish_cost();
            if cascade.check_change().is_err() {
                // Not reached: `set_spectrum` checked a bound on these amplitudes.
                self.cancel_change();
            }
            Some(cost)
        } else if let Some(cascade) = self.cascades.iter_mut().find(|c| !c.change_formed()) {
            cascade.form_change();
            Some(cascade.form_cost())
        } else {
            self.foam.prepare_change(&self.cascades, spectrum)
        }
    }

    /// Does every piece of the change's preparation left.
    fn prepare_all(&mut self) {
        while self.change.is_some_and(|c| !c.prepared) {
            if self.prepare_piece().is_none() {
                if let Some(change) = self.change.as_mut() {
                    change.prepared = true;
                }
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

    /// Prepares whatever is left of a change's new sea at once (before a pre-roll, whose
    /// steps go back in time and forward again; the blend stays a function of time).
    pub(super) fn finish_preparing(&mut self) {
        self.prepare_all();
    }
}
