//! Snapshots of an ocean's history-dependent state, for rollback, replays and save games.

use crate::cascade::check_time;
use crate::error::Error;

use super::time::{FoamMotion, Scope};
use super::OceanState;
use crate::wake::snapshot::WakeSnapshot;

/// Everything about an [`OceanState`] that cannot be recomputed from its spectrum and config:
/// the time, the choppiness (the one the buffers were computed with, and the one last set if
/// it has not been applied yet), the foam's state (active and residual foam) and, with
/// [`OceanConfig::wakes`](crate::OceanConfig::wakes), the wake window's waves, foam trail,
/// place and hulls. Everything
/// else (the cascades' buffers, the breaking intensity, the total foam and its coverage)
/// follows from these, so [`OceanState::restore`] brings an ocean back to exactly the bits it
/// had when the snapshot was taken, and it then steps to the same bits as the original did.
///
/// A snapshot holds 8 bytes per point of the foam grid (cascade 0's N×N) and the drift of
/// the foam's streaks; with wakes, 16 bytes more per cell of the wake window (1 MiB for the
/// default 256² window). Take one with [`OceanState::snapshot`], or refill one without
/// allocating with [`capture`](Self::capture). With the `serde` feature it can be saved and
/// loaded; a loaded snapshot is checked when it is restored. For a restore that is bit-exact,
/// the format must read numbers back exactly: binary formats do, and so does `serde_json`
/// with its `float_roundtrip` feature (its default parser may be one ulp off).
///
/// ```
/// use ocean_fft::{OceanConfig, OceanState, Spectrum};
/// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
/// let config = OceanConfig { size: 16, ..OceanConfig::default() };
/// let mut ocean = OceanState::new(spectrum, config)?;
/// ocean.step(0.5)?;
/// let saved = ocean.snapshot();
/// ocean.step(0.25)?;
/// let later = ocean.water().height_at(3.0, 4.0)?;
///
/// ocean.restore(&saved)?;                  // back to t = 0.5 s, foam and all
/// ocean.step(0.25)?;
/// assert_eq!(ocean.water().height_at(3.0, 4.0)?, later);
/// # Ok::<(), ocean_fft::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct OceanSnapshot {
    time: f64,
    /// The choppiness last set, applied at the next update.
    choppiness: f32,
    /// The choppiness the buffers were computed with.
    applied_choppiness: f32,
    /// Active whitecap foam on the foam grid.
    active: Vec<f32>,
    /// Residual foam on the foam grid.
    residual: Vec<f32>,
    /// How far the foam's streak field has drifted, `[x, z]` m (absent from snapshots saved
    /// before 0.4: 0).
    #[cfg_attr(feature = "serde", serde(default))]
    foam_drift: [f64; 2],
    /// The wake window's state, with [`OceanConfig::wakes`](crate::OceanConfig::wakes)
    /// (absent from snapshots saved before 0.4, which had no wakes).
    #[cfg_attr(feature = "serde", serde(default))]
    wake: Option<WakeSnapshot>,
}

impl OceanSnapshot {
    /// Simulated time of the snapshot, in seconds.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Overwrites this snapshot with `ocean`'s state. Allocates nothing when the snapshot was
    /// taken from an ocean of the same config (its foam buffers are reused), so a game can keep
    /// a ring of snapshots for rollback.
    pub fn capture(&mut self, ocean: &OceanState) {
        self.time = ocean.time;
        self.choppiness = ocean.config.choppiness;
        self.applied_choppiness = ocean.applied_choppiness;
        self.active.clear();
        self.active.extend_from_slice(ocean.foam.active());
        self.residual.clear();
        self.residual.extend_from_slice(ocean.foam.residual());
        self.foam_drift = ocean.foam.drift_offset();
        match &ocean.wake {
            Some(wake) => wake.save(self.wake.get_or_insert_with(WakeSnapshot::default)),
            None => self.wake = None,
        }
    }
}

impl OceanState {
    /// The state that cannot be recomputed: time, choppiness and foam (allocates the foam's
    /// copy; see [`OceanSnapshot::capture`] to reuse one). Not the depth map
    /// ([`set_depth_map`](Self::set_depth_map)): restoring keeps the ocean's own.
    pub fn snapshot(&self) -> OceanSnapshot {
        let mut snapshot = OceanSnapshot {
            time: 0.0,
            choppiness: 0.0,
            applied_choppiness: 0.0,
            active: Vec::new(),
            residual: Vec::new(),
            foam_drift: [0.0; 2],
            wake: None,
        };
        snapshot.capture(self);
        snapshot
    }

    #[deprecated(since = "0.4.0", note = "use `snapshot.capture(&ocean)`")]
    #[doc(hidden)]
    pub fn snapshot_into(&self, snapshot: &mut OceanSnapshot) {
        snapshot.capture(self);
    }

    /// Brings the ocean back to the state `snapshot` holds: its time, choppiness, foam and
    /// wake window, and every cascade updated to that time. The result is bit-identical to the ocean the
    /// snapshot was taken from, and steps on identically. Allocates nothing inside a rayon
    /// pool.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] (naming `snapshot.active` or `snapshot.residual`) if the
    /// snapshot comes from an ocean with another foam grid; for a snapshot loaded from a file,
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for a time beyond
    /// [`Cascade::MAX_TIME`](crate::Cascade::MAX_TIME) or a foam value outside [0, 1], and the
    /// errors of [`set_choppiness`](Self::set_choppiness); [`Error::NonFinite`] naming
    /// `snapshot.foam_drift` for a drift of the foam's streaks that is not finite;
    /// [`Error::NotApplicable`] naming `snapshot.wake` when one of the snapshot and the ocean
    /// has a wake window and the other has not, and for a wake window of another size
    /// [`Error::LengthMismatch`] (naming `snapshot.wake.eta`, `.psi` or `.foam`), or
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] naming the `snapshot.wake` field that
    /// is not finite or out of its range (its hulls as [`set_hulls`](Self::set_hulls) checks
    /// them). Nothing changes then.
    pub fn restore(&mut self, snapshot: &OceanSnapshot) -> Result<(), Error> {
        self.foam.check_state(
            ("snapshot.active", &snapshot.active),
            ("snapshot.residual", &snapshot.residual),
        )?;
        let t = check_time("snapshot.time", snapshot.time)?;
        self.check_choppiness(snapshot.applied_choppiness)?;
        self.check_choppiness(snapshot.choppiness)?;
        if snapshot.foam_drift.iter().any(|v| !v.is_finite()) {
            return Err(Error::NonFinite {
                name: "snapshot.foam_drift",
            });
        }
        match (&self.wake, &snapshot.wake, &self.config.wakes) {
            (Some(wake), Some(saved), Some(config)) => wake.check(saved, config.inner_side())?,
            (None, None, _) => {}
            (Some(_), None, _) => {
                return Err(Error::NotApplicable {
                    name: "snapshot.wake",
                    reason: "the snapshot was taken from an ocean without wakes",
                })
            }
            _ => {
                return Err(Error::NotApplicable {
                    name: "snapshot.wake",
                    reason: "the ocean was built without `OceanConfig::wakes`",
                })
            }
        }
        if let (Some(wake), Some(saved)) = (&mut self.wake, &snapshot.wake) {
            wake.load(saved, self.config.determinism);
        }
        self.foam.set_state(&snapshot.active, &snapshot.residual);
        self.foam.set_drift_offset(snapshot.foam_drift);
        // The buffers as they were (with the choppiness they were computed with), then the
        // choppiness set since, for the next update.
        self.set_choppiness_checked(snapshot.applied_choppiness);
        self.advance(t, FoamMotion::Jump, Scope::All);
        self.set_choppiness_checked(snapshot.choppiness);
        Ok(())
    }
}
