//! The limits and thresholds of an ocean's calls, in their units: the longest step and
//! change of weather, how much of a sea the grids must hold, the largest choppiness's
//! scale. Each call that checks one names it in its `# Errors` section.

use crate::cascade::Cascade;

/// Largest accepted time step of [`OceanState::step`](crate::OceanState::step), in seconds.
pub const MAX_STEP: f64 = 3600.0;

/// Most steps [`OceanState::pre_roll`](crate::OceanState::pre_roll) takes.
pub const MAX_PRE_ROLL_STEPS: usize = 1_000_000;

/// Longest accepted `duration` of
/// [`OceanState::set_spectrum`](crate::OceanState::set_spectrum), in seconds (as long as the
/// ocean's time can run).
pub const MAX_TRANSITION: f64 = Cascade::MAX_TIME;

/// Delay in seconds of simulated time between a call of
/// [`OceanState::set_spectrum`](crate::OceanState::set_spectrum) with a positive duration and
/// the start of its blend, over which the new sea is prepared a piece at a time.
pub const TRANSITION_LAG: f64 = 0.45;

/// The share of a new spectrum's variance that the grids must hold for
/// [`OceanState::set_spectrum`](crate::OceanState::set_spectrum) to accept it (H_s at least
/// 89 % of the sea's);
/// [`OceanState::set_spectrum_unfitted`](crate::OceanState::set_spectrum_unfitted) takes any.
pub const MIN_CHANGE_SHARE: f64 = 0.8;

/// The share of the spectrum's variance (in the config's band) that the grids must hold for
/// [`OceanState::new`](crate::OceanState::new) to build the ocean: below it the simulated H_s
/// is under half the sea's, another sea than the one asked for.
pub const MIN_BUILD_SHARE: f64 = 0.25;

/// λ_max·σ at the largest choppiness λ_max, σ² the mean-square slope the grids hold: about
/// 53 % of a Gaussian sea's surface folds there. See
/// [`Diagnostics::max_choppiness`](crate::Diagnostics::max_choppiness).
pub const MAX_FOLD_SCALE: f32 = 4.0;
