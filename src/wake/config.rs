//! [`WakeConfig`] (the wake window's grid, clock and absorbing border) and [`Hull`] (a body
//! that presses on the water), with their checks.

use std::ops::Bound::{Excluded, Included};

use crate::error::{self, Error};

/// The wake layer of an [`OceanState`](crate::OceanState): a square window of linear
/// free-surface waves around a point the game chooses (the camera or the player), in which
/// hulls ([`Hull`]) make Kelvin wakes. Passive data, checked by
/// [`OceanState::new`](crate::OceanState::new) through [`WakeConfig::validate`].
///
/// The window has `size`×`size` samples `spacing` metres apart; sample (i, j) sits at world
/// (x₀ + i·spacing, z₀ + j·spacing), (x₀, z₀) being [`Wakes::origin`](crate::Wakes::origin).
/// Waves are absorbed in a border `border`·`size` cells wide on every side, so none re-enters
/// or wraps around; queries fade the wake to zero across the outer half of that border.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct WakeConfig {
    /// Samples per side of the window: a power of two from [`MIN_SIZE`](Self::MIN_SIZE) to
    /// [`MAX_SIZE`](Self::MAX_SIZE) (default: `256`).
    pub size: usize,
    /// Distance between samples in metres, from [`MIN_SPACING`](Self::MIN_SPACING) to
    /// [`MAX_SPACING`](Self::MAX_SPACING) (default: `0.5`: a 128 m window). The shortest
    /// wave the window holds is 2·`spacing` long.
    pub spacing: f32,
    /// The wake's own time step in seconds, in (0, [`MAX_SUBSTEP`](Self::MAX_SUBSTEP)]
    /// (default: 1/60 s). The wake is advanced in ticks of this length at the absolute times
    /// n·`substep`, whatever steps the ocean takes, so that one long step and many short ones
    /// draw the same wake (to the bit); queries see the wake of the last tick at or before
    /// the ocean's time. A hull should move less than a cell in a tick.
    pub substep: f32,
    /// Width of the absorbing border on each side, as a fraction of `size`, in
    /// (0, [`MAX_BORDER`](Self::MAX_BORDER)] (default: `0.125`: 32 of 256 cells).
    pub border: f32,
    /// Damping rate in 1/s at the window's edge of the absorbing border, which grows as the
    /// square of the depth into the border (default: `6.0`), in (0, 1000].
    pub damping: f32,
}

impl Default for WakeConfig {
    fn default() -> Self {
        WakeConfig {
            size: 256,
            spacing: 0.5,
            substep: 1.0 / 60.0,
            border: 0.125,
            damping: 6.0,
        }
    }
}

impl WakeConfig {
    /// Smallest [`size`](Self::size).
    pub const MIN_SIZE: usize = 16;
    /// Largest [`size`](Self::size).
    pub const MAX_SIZE: usize = 2048;
    /// Smallest [`spacing`](Self::spacing), in metres.
    pub const MIN_SPACING: f32 = 0.01;
    /// Largest [`spacing`](Self::spacing), in metres.
    pub const MAX_SPACING: f32 = 100.0;
    /// Largest [`substep`](Self::substep), in seconds.
    pub const MAX_SUBSTEP: f32 = 1.0;
    /// Largest [`border`](Self::border).
    pub const MAX_BORDER: f32 = 0.25;
    /// Most hulls [`OceanState::set_hulls`](crate::OceanState::set_hulls) accepts.
    pub const MAX_HULLS: usize = 64;

    /// Checks every field.
    ///
    /// # Errors
    /// [`Error::InvalidSize`] naming `wakes.size` unless it is a power of two within
    /// [`MIN_SIZE`](Self::MIN_SIZE)..=[`MAX_SIZE`](Self::MAX_SIZE); [`Error::NonFinite`] or
    /// [`Error::OutOfRange`] naming `wakes.spacing`, `wakes.substep`, `wakes.border` or
    /// `wakes.damping` outside their ranges.
    pub fn validate(&self) -> Result<(), Error> {
        if !(Self::MIN_SIZE..=Self::MAX_SIZE).contains(&self.size) || !self.size.is_power_of_two() {
            return Err(Error::InvalidSize {
                name: "wakes.size",
                size: self.size,
                min: Self::MIN_SIZE,
                max: Self::MAX_SIZE,
            });
        }
        error::in_range(
            "wakes.spacing",
            self.spacing,
            Included(Self::MIN_SPACING),
            Included(Self::MAX_SPACING),
        )?;
        error::in_range(
            "wakes.substep",
            self.substep,
            Excluded(0.0),
            Included(Self::MAX_SUBSTEP),
        )?;
        error::in_range(
            "wakes.border",
            self.border,
            Excluded(0.0),
            Included(Self::MAX_BORDER),
        )?;
        error::in_range(
            "wakes.damping",
            self.damping,
            Excluded(0.0),
            Included(1000.0),
        )?;
        Ok(())
    }

    /// Cells of the absorbing border on each side (at least one).
    pub(crate) fn border_cells(&self) -> usize {
        ((self.border * self.size as f32).round() as usize).clamp(1, self.size / 4)
    }

    /// Side in metres of the window's inside (the window less its two borders): the largest
    /// hull length or beam it accepts.
    pub fn inner_side(&self) -> f32 {
        (self.size - 2 * self.border_cells()) as f32 * self.spacing
    }

    /// Bytes the wake layer holds: four complex and eight real grids of `size`² (the state,
    /// the transforms' working space, the tables, the hulls' pressure, the foam trail and
    /// its moves, and the buffers the queries read).
    pub fn memory_bytes(&self) -> usize {
        self.size
            .saturating_mul(self.size)
            .saturating_mul(4 * 8 + 8 * 4)
    }
}

/// A body pressing on the water: a waterplane `length` × `beam` metres (a smooth bump,
/// deepest, `draft` metres, at its centre), at `position`, moving at `velocity`, its bow
/// towards `heading`. Hulls outside the wake window make no wake.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Hull {
    /// World `[x, z]` of the waterplane's centre in metres, at the time
    /// [`OceanState::set_hulls`](crate::OceanState::set_hulls) was called.
    pub position: [f64; 2],
    /// Velocity `[x, z]` in m/s: within and between steps the hull moves along it from
    /// `position`, until the next `set_hulls`.
    pub velocity: [f32; 2],
    /// Direction of the bow in radians: the unit vector (cos θ, sin θ) in (x, z), as every
    /// direction of the crate. It may differ from the velocity's (a drifting hull).
    pub heading: f32,
    /// Length of the waterplane in metres, bow to stern.
    pub length: f32,
    /// Width of the waterplane in metres.
    pub beam: f32,
    /// Depth in metres the hull presses the water down at its centre (the pressure
    /// ρ·g·`draft`).
    pub draft: f32,
}

impl Default for Hull {
    /// A 20 m × 5 m hull of 1 m draft at the origin, at rest, bow towards +x.
    fn default() -> Self {
        Hull {
            position: [0.0; 2],
            velocity: [0.0; 2],
            heading: 0.0,
            length: 20.0,
            beam: 5.0,
            draft: 1.0,
        }
    }
}

impl Hull {
    /// Largest speed in m/s.
    pub const MAX_SPEED: f32 = 100.0;
    /// Largest |x| or |z| of a position, in metres.
    pub const MAX_POSITION: f64 = 1.0e9;

    /// Checks a hull for a window of side `inner` metres inside its border.
    pub(crate) fn validate(&self, inner: f32) -> Result<(), Error> {
        for value in self.position {
            error::in_range_f64(
                "hull.position",
                value,
                Included(-Self::MAX_POSITION),
                Included(Self::MAX_POSITION),
            )?;
        }
        for value in self.velocity {
            error::in_range(
                "hull.velocity",
                value,
                Included(-Self::MAX_SPEED),
                Included(Self::MAX_SPEED),
            )?;
        }
        error::finite("hull.heading", self.heading)?;
        error::in_range("hull.length", self.length, Excluded(0.0), Included(inner))?;
        error::in_range("hull.beam", self.beam, Excluded(0.0), Included(inner))?;
        error::in_range(
            "hull.draft",
            self.draft,
            Excluded(0.0),
            Included(self.length),
        )?;
        Ok(())
    }
}
