//! What the game sets: the sea ([`OceanSettings`]) and the clock the waves follow
//! ([`OceanClock`]).

use bevy::prelude::*;
use ocean_fft::SeaState;
use ocean_fft_render::SeaSettings;

/// The sea the plugin simulates: the render layer's `SeaSettings` (spectrum, grids with
/// the choppiness and the foam, transition time; its methods and fields are reached through
/// `Deref`). Change it at any time: the plugin compares it with what the
/// ocean runs and applies the difference through the crate's live API —
///
/// - a new `spectrum` (the weather) with [`OceanState::set_spectrum`] over
///   `transition_seconds` of sea time: every wave keeps its phase, the foam stays;
/// - a new `config.choppiness` with [`OceanState::set_choppiness`];
/// - new `config.foam` settings with [`OceanState::set_foam_config`];
/// - anything else in `config` (the grids: lengths, size, seed, band limits…), a spectrum
///   with another water depth, or a spectrum the grids cannot hold (a storm on a calm
///   sea's grids: below [`limits::MIN_CHANGE_SHARE`] of its variance), which a running
///   ocean cannot take, builds a new ocean off the main thread (its foam spun up; for a
///   sea the grids cannot hold, on grids fitted to it, `SeaSettings::grids`) and swaps
///   it in when it is ready; the old one runs until then (`SeaSettings::plan` decides).
///
/// A change the crate refuses (say a storm too strong for the grids) leaves the sea as it is
/// and is reported in [`OceanStatus::last_error`](crate::OceanStatus::last_error).
///
/// [`OceanState::set_spectrum`]: ocean_fft::OceanState::set_spectrum
/// [`OceanState::set_choppiness`]: ocean_fft::OceanState::set_choppiness
/// [`OceanState::set_foam_config`]: ocean_fft::OceanState::set_foam_config
/// [`limits::MIN_CHANGE_SHARE`]: ocean_fft::limits::MIN_CHANGE_SHARE
#[derive(Resource, Debug, Clone, PartialEq, Default, Deref, DerefMut)]
pub struct OceanSettings(pub SeaSettings);

impl OceanSettings {
    /// The preset's spectrum and config (its grids suit its waves), changing over 10 s.
    pub fn preset(state: SeaState) -> OceanSettings {
        OceanSettings(SeaSettings::preset(state))
    }
}

/// The time the waves follow, in seconds of sea time.
///
/// - [`OceanClock::Virtual`] (the default): Bevy's virtual time (`Time<Virtual>`), so pausing
///   or slowing the game's time pauses or slows the sea.
/// - [`OceanClock::Manual`]: a time the game sets every frame — a networked game's server
///   time, a replay's timeline. Every client that sets the same time sees the same waves (the
///   cascades are a function of the time; the foam of the history, so clients that joined
///   late agree on it within its few seconds of memory).
///
/// A clock that goes back, or jumps forward by more than an hour, jumps the sea there
/// (`OceanState::set_time`: the foam is kept as it is); otherwise the sea steps to it with its
/// foam evolving (`OceanState::step_to`).
#[derive(Resource, Debug, Clone, Copy, PartialEq, Default)]
pub enum OceanClock {
    /// Bevy's `Time<Virtual>` elapsed seconds.
    #[default]
    Virtual,
    /// This time, in seconds.
    Manual(f64),
}
