//! The wake methods of [`OceanState`]: the hulls, the window's centre, its buffers.

use std::ops::Bound::Included;
use std::sync::Arc;

use crate::error::{self, Error};
use crate::wake::{Hull, WakeConfig, Wakes};

use super::OceanState;

impl OceanState {
    /// The hulls that disturb the water from the next step on, replacing those set before
    /// (an empty slice: none). Each hull moves along its velocity from its position at the
    /// current time, within and between steps, until the next call: a game that sets its
    /// boats every frame gets their path piecewise straight, and one long step draws the same
    /// wake as many short ones. Hulls outside the wake window make no wake. Allocates
    /// nothing.
    ///
    /// ```
    /// use ocean_fft::{Hull, OceanConfig, OceanState, Spectrum, WakeConfig};
    /// let config = OceanConfig {
    ///     size: 16,
    ///     wakes: Some(WakeConfig { size: 64, spacing: 1.0, ..WakeConfig::default() }),
    ///     ..OceanConfig::default()
    /// };
    /// let mut ocean = OceanState::new(Spectrum::jonswap(5.0, 10_000.0)?, config)?;
    /// let boat = Hull { velocity: [4.0, 0.0], ..Hull::default() };   // 20 m × 5 m, 1 m draft
    /// ocean.set_hulls(&[boat])?;
    /// ocean.step(2.0)?;
    /// let wakes = ocean.wakes().expect("wakes are on");
    /// assert!(wakes.height_at(8.0, 0.0) < 0.0);                      // pressed down under it
    /// # Ok::<(), ocean_fft::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NotApplicable`] naming `wakes` without [`OceanConfig::wakes`](crate::OceanConfig::wakes);
    /// [`Error::CountOutOfRange`] naming `hulls` for more than
    /// [`WakeConfig::MAX_HULLS`]; [`Error::NonFinite`] or [`Error::OutOfRange`] naming
    /// `hull.position` (|x|, |z| ≤ [`Hull::MAX_POSITION`]), `hull.velocity` (each component
    /// within ±[`Hull::MAX_SPEED`]), `hull.heading`, `hull.length` or `hull.beam` (above 0,
    /// at most [`WakeConfig::inner_side`]: a hull must fit inside the window's border) or
    /// `hull.draft` (above 0, at most the length). Nothing changes then.
    pub fn set_hulls(&mut self, hulls: &[Hull]) -> Result<(), Error> {
        let Some(config) = &self.config.wakes else {
            return Err(no_wakes());
        };
        if hulls.len() > WakeConfig::MAX_HULLS {
            return Err(Error::CountOutOfRange {
                name: "hulls",
                count: hulls.len(),
                min: 0,
                max: WakeConfig::MAX_HULLS,
            });
        }
        let inner = config.inner_side();
        for hull in hulls {
            hull.validate(inner)?;
        }
        if let Some(wake) = &mut self.wake {
            wake.set_hulls(hulls, self.time, self.config.determinism);
        }
        Ok(())
    }

    /// Moves the wake window so that it is centred on world (x, z) in metres (the camera or
    /// the player): by whole cells, so the waves it still covers stay where they are and
    /// the new ground is still water. A move of less than half a cell changes nothing.
    /// It costs two transforms of the window when it moves.
    ///
    /// # Errors
    /// [`Error::NotApplicable`] naming `wakes` without [`OceanConfig::wakes`](crate::OceanConfig::wakes);
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] naming `x` or `z` beyond
    /// ±[`Hull::MAX_POSITION`]. Nothing changes then.
    pub fn set_wake_centre(&mut self, x: f64, z: f64) -> Result<(), Error> {
        if self.wake.is_none() {
            return Err(no_wakes());
        }
        let limit = (Included(-Hull::MAX_POSITION), Included(Hull::MAX_POSITION));
        error::in_range_f64("x", x, limit.0, limit.1)?;
        error::in_range_f64("z", z, limit.0, limit.1)?;
        let moved = self.wake.as_mut().is_some_and(|wake| wake.move_to(x, z));
        if moved {
            // Handles taken before keep the window they saw.
            self.frames.advance(self.time, self.config.query);
            self.write_wake();
        }
        Ok(())
    }

    /// The wake window at the current time (`None` without
    /// [`OceanConfig::wakes`](crate::OceanConfig::wakes)): its place, its grid and its
    /// height, slope and foam buffers, which the world queries already include.
    pub fn wakes(&self) -> Option<&Wakes> {
        self.frames.current.wake.as_ref()
    }

    /// Writes the wake's buffers into the current frame (which nothing else holds after
    /// `Frames::advance`).
    pub(super) fn write_wake(&mut self) {
        let (Some(wake), Some(frame)) = (&self.wake, Arc::get_mut(&mut self.frames.current)) else {
            return;
        };
        if let Some(out) = &mut frame.wake {
            wake.write(out, self.time);
        }
    }
}

/// The error of a wake method on an ocean without wakes.
fn no_wakes() -> Error {
    Error::NotApplicable {
        name: "wakes",
        reason: "the ocean was built without `OceanConfig::wakes`",
    }
}
