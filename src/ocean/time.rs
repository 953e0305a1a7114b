//! The one path through time. Every change of the ocean's time (a step, a step to a given
//! time, a jump, a restore, a pre-roll) goes through [`OceanState::advance`], which moves the
//! cascades, then the foam, then the clock, so that no two of them can drift apart.

use std::ops::Bound::{Excluded, Included};

use rayon::prelude::*;

use crate::cascade::{check_time, Cascade};
use crate::error::{self, Error};

use super::OceanState;

/// What the foam does when the ocean moves to a new time.
#[derive(Debug, Clone, Copy)]
pub(super) enum FoamMotion {
    /// A step forward of this many seconds: the foam is integrated over it (over 0 s only
    /// the breaking intensity is recomputed, to the same bits).
    Integrate(f64),
    /// A jump with no history: the foam's state is kept and its breaking intensity, total and
    /// coverage are recomputed at the new time.
    Jump,
    /// Left as it is: the foam is already at the new time (the end of a pre-roll).
    Keep,
}

/// Which cascades a move in time updates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Scope {
    /// Every cascade.
    All,
    /// The foam's source, cascade 0, alone (the foam reads nothing else).
    FoamSource,
}

impl OceanState {
    #[deprecated(since = "0.4.0", note = "use `ocean_fft::limits::MAX_PRE_ROLL_STEPS`")]
    #[doc(hidden)]
    pub const MAX_PRE_ROLL_STEPS: usize = super::limits::MAX_PRE_ROLL_STEPS;

    /// Advances the time by `dt` seconds (0 ≤ dt ≤ [`limits::MAX_STEP`](crate::limits::MAX_STEP)), updates
    /// every cascade and the foam. Allocates nothing inside a rayon pool.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for `dt`, or for the new time
    /// (`time + dt`) beyond [`Cascade::MAX_TIME`]. Nothing changes then.
    pub fn step(&mut self, dt: f64) -> Result<(), Error> {
        error::in_range_f64("dt", dt, Included(0.0), Included(super::limits::MAX_STEP))?;
        let t = check_time("time + dt", self.time + dt)?;
        self.advance(t, FoamMotion::Integrate(dt), Scope::All);
        Ok(())
    }

    /// Advances to the absolute time `t` in seconds, from [`time`](Self::time) up to
    /// `time + MAX_STEP`: the cascades are evaluated at `t` itself and the foam is integrated
    /// over `t − time`, as [`step`](Self::step) does. For a game that follows a time it is
    /// given (a server clock, a replay's timeline) rather than accumulating steps, so that
    /// the waves match the given time exactly whatever the frame rate. Allocates nothing
    /// inside a rayon pool.
    ///
    /// ```
    /// use ocean_fft::{OceanConfig, OceanState, Spectrum};
    /// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
    /// let mut ocean = OceanState::new(spectrum, OceanConfig { size: 16, ..Default::default() })?;
    /// for server_time in [0.016, 0.035, 0.049] {
    ///     ocean.step_to(server_time)?;          // s, foam carried along
    /// }
    /// assert_eq!(ocean.time(), 0.049);
    /// // A time behind the ocean's is refused: jump there with `set_time` (or restore a
    /// // snapshot) instead.
    /// assert!(ocean.step_to(0.02).is_err());
    /// # Ok::<(), ocean_fft::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] (naming `t`) unless
    /// `time` ≤ `t` ≤ `time + MAX_STEP` and |t| ≤ [`Cascade::MAX_TIME`]. Nothing changes
    /// then.
    pub fn step_to(&mut self, t: f64) -> Result<(), Error> {
        let t = check_time("t", t)?;
        let max = (self.time + super::limits::MAX_STEP).min(Cascade::MAX_TIME);
        error::in_range_f64("t", t, Included(self.time), Included(max))?;
        self.advance(t, FoamMotion::Integrate(t - self.time), Scope::All);
        Ok(())
    }

    /// Jumps to time `t` in seconds (|t| ≤ [`Cascade::MAX_TIME`]), forward or back, and
    /// updates every cascade. The foam is kept as it is: a jump has no history, so foam
    /// neither builds nor decays across it (call [`clear_foam`](Self::clear_foam) for a
    /// clean sea). To follow a clock forward with the foam evolving, use
    /// [`step_to`](Self::step_to); to go back to an earlier state exactly, use
    /// [`restore`](Self::restore).
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for `t`. Nothing changes then.
    pub fn set_time(&mut self, t: f64) -> Result<(), Error> {
        let t = check_time("t", t)?;
        self.advance(t, FoamMotion::Jump, Scope::All);
        Ok(())
    }

    /// Pre-rolls the foam: clears it, goes back `seconds` before the current time and steps
    /// forward to it again in steps of `dt` (the last one shorter if `dt` does not divide
    /// `seconds`), so that the foam is spun up as if the sea had been running. The result
    /// depends only on the current time, `seconds`, `dt` and the ocean's spectrum and config,
    /// not on any earlier history: every client of a networked game, or every frame range of
    /// a bake, gets the same bits. Whitecaps reach their steady coverage within about five
    /// [`FoamConfig::active_decay`](crate::FoamConfig::active_decay) (20 s by default), residual foam within about five
    /// [`FoamConfig::residual_decay`](crate::FoamConfig::residual_decay). With
    /// [`OceanConfig::wakes`](crate::OceanConfig::wakes) the wake window, where it stands,
    /// is cleared to still water and spun up over the same seconds with the hulls last set,
    /// each moving along its velocity, so a boat starts with its wake behind it (the window's
    /// ticks cost what they cost in a step). Allocates nothing inside a rayon pool.
    ///
    /// ```
    /// use ocean_fft::{OceanConfig, OceanState, Spectrum};
    /// let spectrum = Spectrum::jonswap(15.0, 200_000.0)?;
    /// let config = OceanConfig { size: 32, ..OceanConfig::default() };
    /// let mut ocean = OceanState::new(spectrum.clone(), config.clone())?;
    /// ocean.set_time(100.0)?;
    /// ocean.pre_roll(20.0, 0.05)?;               // s: 400 steps back from t = 80 s
    /// assert_eq!(ocean.time(), 100.0);
    ///
    /// // Another ocean with another history gets the same foam.
    /// let mut other = OceanState::new(spectrum, config)?;
    /// other.step(3.0)?;
    /// other.set_time(100.0)?;
    /// other.pre_roll(20.0, 0.05)?;
    /// assert_eq!(ocean.foam_view().total(), other.foam_view().total());
    /// # Ok::<(), ocean_fft::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for `dt` outside
    /// (0, [`limits::MAX_STEP`](crate::limits::MAX_STEP)], for `seconds` below 0 or above
    /// [`limits::MAX_PRE_ROLL_STEPS`](crate::limits::MAX_PRE_ROLL_STEPS)·`dt`, or (naming `time - seconds`) for
    /// a start before −[`Cascade::MAX_TIME`]. Nothing changes then.
    pub fn pre_roll(&mut self, seconds: f64, dt: f64) -> Result<(), Error> {
        error::in_range_f64("dt", dt, Excluded(0.0), Included(super::limits::MAX_STEP))?;
        let longest = dt * super::limits::MAX_PRE_ROLL_STEPS as f64;
        error::in_range_f64("seconds", seconds, Included(0.0), Included(longest))?;
        let end = self.time;
        let start = check_time("time - seconds", end - seconds)?;
        let steps = ((end - start) / dt).ceil() as usize;
        // The foam reads only cascade 0 (its breaking intensity is cascade 0's Jacobian with
        // the other cascades' statistics), so the roll moves cascade 0 alone and the others
        // once at the end: the same bits as moving all of them at every step.
        rayon::scope(|_| {
            self.finish_preparing();
            self.foam.clear_state();
            if let Some(wake) = &mut self.wake {
                wake.clear_state();
            }
            self.advance(start, FoamMotion::Jump, Scope::FoamSource);
            let mut previous = start;
            for k in 1..=steps {
                let t = if k == steps {
                    end
                } else {
                    (start + k as f64 * dt).min(end)
                };
                self.advance(t, FoamMotion::Integrate(t - previous), Scope::FoamSource);
                previous = t;
            }
            self.advance(end, FoamMotion::Keep, Scope::All);
        });
        Ok(())
    }

    /// Moves the ocean to the checked time `t`: the cascades of `scope` (the choppiness last
    /// set applied), then the foam as `foam` says, then the
    /// clock. One job handed to rayon (see `Cascade::update`), so nothing allocates inside a
    /// pool.
    pub(super) fn advance(&mut self, t: f64, foam: FoamMotion, scope: Scope) {
        rayon::scope(|_| {
            self.advance_change(t);
            self.update_cascades(t, scope);
            match foam {
                FoamMotion::Integrate(dt) => self.foam.advance(dt),
                FoamMotion::Jump => self.foam.refresh(),
                FoamMotion::Keep => {}
            }
            if let Some(wake) = &mut self.wake {
                // A pre-roll's steps (cascade 0 alone) move the wake too.
                match foam {
                    FoamMotion::Integrate(_) => wake.advance(t),
                    _ => wake.jump(t),
                }
            }
            self.time = t;
            self.frames.advance(t, self.config.query);
            self.write_wake();
        });
    }

    /// Updates the cascades of `scope` to the checked time `t`; cascade 0 through the foam,
    /// which keeps its displacement gradient.
    fn update_cascades(&mut self, t: f64, scope: Scope) {
        self.applied_choppiness = self.config.choppiness;
        let Some((first, rest)) = self.cascades.split_first_mut() else {
            return;
        };
        let foam = &mut self.foam;
        let update = |cascade: &mut Cascade| cascade.update_checked(t, &mut []);
        match scope {
            Scope::FoamSource => foam.update_source(first, t),
            Scope::All if self.config.parallel_cascades => {
                rayon::join(
                    || foam.update_source(first, t),
                    || rest.par_iter_mut().for_each(update),
                );
            }
            Scope::All => {
                foam.update_source(first, t);
                rest.iter_mut().for_each(update);
            }
        }
    }
}
