//! The wake window's history in a snapshot: what [`OceanState::restore`] needs to bring the
//! waves, the foam trail and the hulls back exactly. The pressure head and the tick count
//! follow from these and the time.
//!
//! [`OceanState::restore`]: crate::OceanState::restore

use num_complex::Complex32;

use super::config::Hull;
use super::sim::WakeSim;
use crate::error::{self, Error};
use crate::math::determinism::Determinism;

/// The wake layer's state at a snapshot: 16 bytes per cell of the window.
#[derive(Debug, Clone, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct WakeSnapshot {
    /// The elevation η in metres (`[z][x]`), after the border's damping.
    pub(crate) eta: Vec<f32>,
    /// The scaled potential ψ̂ (re, im interleaved, transposed as in the simulation).
    pub(crate) psi: Vec<f32>,
    /// The foam trail's coverage in [0, 1] (`[z][x]`).
    pub(crate) foam: Vec<f32>,
    /// Whether a hull pressed at the last tick.
    pub(crate) pressed: bool,
    /// The hulls as last set, and the time in seconds they were set at.
    pub(crate) hulls: Vec<Hull>,
    pub(crate) hull_time: f64,
    /// Cell indices (x, z) of the window's sample (0, 0).
    pub(crate) origin: [i64; 2],
}

impl WakeSim {
    /// Copies the history into `out`, reusing its buffers (no allocation when they have the
    /// window's size already).
    pub(crate) fn save(&self, out: &mut WakeSnapshot) {
        out.eta.clear();
        out.eta.extend(self.field.iter().map(|v| v.re));
        out.psi.clear();
        out.psi.extend(self.psi.iter().flat_map(|v| [v.re, v.im]));
        out.foam.clear();
        out.foam.extend_from_slice(&self.foam);
        out.pressed = self.pressed;
        out.hulls.clear();
        // Room for the most hulls at once, so that a capture after more hulls were set does
        // not allocate.
        out.hulls.reserve_exact(super::WakeConfig::MAX_HULLS);
        out.hulls
            .extend(self.hulls.iter().map(|placed| placed.hull));
        out.hull_time = self.hull_time;
        out.origin = self.origin;
    }

    /// Checks that `saved` fits this window (hulls checked against a window of side `inner`
    /// metres inside its border) and holds finite values.
    pub(crate) fn check(&self, saved: &WakeSnapshot, inner: f32) -> Result<(), Error> {
        let cells = self.n * self.n;
        error::length("snapshot.wake.eta", saved.eta.len(), cells)?;
        error::length("snapshot.wake.psi", saved.psi.len(), 2 * cells)?;
        error::length("snapshot.wake.foam", saved.foam.len(), cells)?;
        if saved.eta.iter().chain(&saved.psi).any(|v| !v.is_finite()) {
            return Err(Error::NonFinite {
                name: "snapshot.wake",
            });
        }
        for &value in &saved.foam {
            error::unit_interval("snapshot.wake.foam", value)?;
        }
        if saved.hulls.len() > super::WakeConfig::MAX_HULLS {
            return Err(Error::CountOutOfRange {
                name: "snapshot.wake.hulls",
                count: saved.hulls.len(),
                min: 0,
                max: super::WakeConfig::MAX_HULLS,
            });
        }
        for hull in &saved.hulls {
            hull.validate(inner)?;
        }
        crate::cascade::check_time("snapshot.wake.hull_time", saved.hull_time)?;
        // A window centred within the hulls' range of positions (and a cell beyond).
        let reach = Hull::MAX_POSITION / self.spacing + self.n as f64;
        for (name, cell) in [
            ("snapshot.wake.origin[0]", saved.origin[0]),
            ("snapshot.wake.origin[1]", saved.origin[1]),
        ] {
            error::in_range_f64(
                name,
                cell as f64,
                std::ops::Bound::Included(-reach),
                std::ops::Bound::Included(reach),
            )?;
        }
        Ok(())
    }

    /// Brings back the history `saved` (checked by [`check`](Self::check)); the tick count
    /// follows with the ocean's next jump to the snapshot's time.
    pub(crate) fn load(&mut self, saved: &WakeSnapshot, determinism: Determinism) {
        for (cell, &eta) in self.field.iter_mut().zip(&saved.eta) {
            *cell = Complex32::new(eta, 0.0);
        }
        for (mode, pair) in self.psi.iter_mut().zip(saved.psi.chunks_exact(2)) {
            *mode = Complex32::new(pair[0], pair[1]);
        }
        self.foam.copy_from_slice(&saved.foam);
        // Recomputed by the next tick's press while a hull presses; zero otherwise.
        self.head.fill(0.0);
        self.pressed = saved.pressed;
        self.set_hulls(&saved.hulls, saved.hull_time, determinism);
        self.origin = saved.origin;
        self.generation += 1;
    }

    /// Still water and no foam (the hulls and the window's place are kept).
    pub(crate) fn clear_state(&mut self) {
        self.field.fill(Complex32::default());
        self.psi.fill(Complex32::default());
        self.foam.fill(0.0);
        self.head.fill(0.0);
        self.pressed = false;
        self.generation += 1;
    }
}
