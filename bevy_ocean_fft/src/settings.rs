//! What the game sets: the sea ([`OceanSettings`]) and the clock the waves follow
//! ([`OceanClock`]).

use bevy::prelude::*;
use ocean_fft::{FoamConfig, OceanConfig, OceanState, SeaState, Spectrum};

/// The sea the plugin simulates. Change it at any time: the plugin compares it with what the
/// ocean runs and applies the difference through the crate's live API —
///
/// - a new `spectrum` (the weather) with [`OceanState::set_spectrum`] over
///   `transition_seconds` of sea time: every wave keeps its phase, the foam stays;
/// - a new `config.choppiness` with [`OceanState::set_choppiness`];
/// - new `config.foam` settings with [`OceanState::set_foam_config`];
/// - anything else in `config` (the grids: lengths, size, seed, band limits…), a spectrum
///   with another water depth, or a spectrum the grids cannot hold (a storm on a calm
///   sea's grids: below [`OceanState::MIN_CHANGE_SHARE`] of its variance), which a running
///   ocean cannot take, builds a new ocean off the main thread (its foam spun up; for a
///   sea the grids cannot hold, on grids fitted to it, [`OceanSettings::grids`]) and swaps
///   it in when it is ready; the old one runs until then.
///
/// A change the crate refuses (say a storm too strong for the grids) leaves the sea as it is
/// and is reported in [`OceanStatus::last_error`](crate::OceanStatus::last_error).
///
/// [`OceanState::set_spectrum`]: ocean_fft::OceanState::set_spectrum
/// [`OceanState::set_choppiness`]: ocean_fft::OceanState::set_choppiness
/// [`OceanState::set_foam_config`]: ocean_fft::OceanState::set_foam_config
/// [`OceanState::MIN_CHANGE_SHARE`]: ocean_fft::OceanState::MIN_CHANGE_SHARE
#[derive(Resource, Debug, Clone, PartialEq)]
pub struct OceanSettings {
    /// The wave spectrum: wind, fetch, spreading, depth.
    pub spectrum: Spectrum,
    /// The cascades' grids, the choppiness (`config.choppiness`, dimensionless) and the foam
    /// (`config.foam`).
    pub config: OceanConfig,
    /// Seconds of sea time over which a new spectrum replaces the old one (0: at the next
    /// step).
    pub transition_seconds: f64,
}

impl Default for OceanSettings {
    /// A fresh breeze (Beaufort 5) on the crate's default grids, changing over 10 s.
    fn default() -> Self {
        OceanSettings::preset(SeaState::FreshBreeze)
    }
}

impl OceanSettings {
    /// The preset's spectrum and config (its grids suit its waves), changing over 10 s.
    pub fn preset(state: SeaState) -> OceanSettings {
        let (spectrum, config) = state.build();
        OceanSettings {
            spectrum,
            config,
            transition_seconds: 10.0,
        }
    }

    /// Takes the preset's weather (spectrum, choppiness, foam) and keeps the grids, so that the
    /// change is a live transition, not a new ocean (unless the preset's water depth differs:
    /// the shallow bay's does; or the grids cannot hold the new sea, a storm on a calm sea's
    /// grids: then the new ocean's grids are fitted to it, see [`OceanSettings::grids`]).
    pub fn set_weather(&mut self, state: SeaState) {
        let (spectrum, config) = state.build();
        self.spectrum = spectrum;
        self.config.choppiness = config.choppiness;
        self.config.foam = config.foam;
    }

    /// Whether going from `self` to `other` needs a new ocean because of the grids: a config
    /// that differs in anything but the choppiness and the foam, or a new spectrum the grids
    /// hold less than [`OceanState::MIN_CHANGE_SHARE`] of (`set_spectrum` would refuse it;
    /// the new ocean's grids are then fitted to it, see [`OceanSettings::grids`]). (The
    /// plugin also rebuilds for a spectrum of another water depth, which `set_spectrum`
    /// would refuse.)
    ///
    /// [`OceanState::MIN_CHANGE_SHARE`]: ocean_fft::OceanState::MIN_CHANGE_SHARE
    pub fn needs_rebuild(&self, other: &OceanSettings) -> bool {
        let mut a = self.config.clone();
        a.choppiness = other.config.choppiness;
        a.foam = other.config.foam;
        a != other.config || self.spectrum != other.spectrum && !other.fits()
    }

    /// Whether the grids of `config` hold at least [`OceanState::MIN_CHANGE_SHARE`] of the
    /// spectrum's variance.
    ///
    /// [`OceanState::MIN_CHANGE_SHARE`]: ocean_fft::OceanState::MIN_CHANGE_SHARE
    pub fn fits(&self) -> bool {
        self.config
            .fit(&self.spectrum)
            .is_ok_and(|fit| fit.held >= OceanState::MIN_CHANGE_SHARE)
    }

    /// The config an ocean of these settings is built with: `config` itself if its grids
    /// hold the spectrum ([`fits`](Self::fits)), else `config` with its lengths fitted to the
    /// spectrum ([`OceanConfig::with_fitted_lengths`]).
    pub fn grids(&self) -> OceanConfig {
        if self.fits() {
            self.config.clone()
        } else {
            self.config
                .clone()
                .with_fitted_lengths(&self.spectrum)
                .unwrap_or_else(|_| self.config.clone())
        }
    }
}

/// One live change the simulation applies before its next step.
#[derive(Debug, Clone)]
pub(crate) enum Change {
    Spectrum(Spectrum, f64),
    Choppiness(f32),
    Foam(FoamConfig),
}

/// The changes from `old` to `new` that a running ocean can take (empty if a rebuild is
/// needed: the caller checks [`OceanSettings::needs_rebuild`] first).
pub(crate) fn live_changes(old: &OceanSettings, new: &OceanSettings) -> Vec<Change> {
    let mut changes = Vec::new();
    // The choppiness first: a calmer sea at a higher choppiness, or the reverse, is checked
    // against the grids with the choppiness it will run with.
    if old.config.choppiness != new.config.choppiness {
        changes.push(Change::Choppiness(new.config.choppiness));
    }
    if old.spectrum != new.spectrum {
        changes.push(Change::Spectrum(
            new.spectrum.clone(),
            new.transition_seconds,
        ));
    }
    if old.config.foam != new.config.foam {
        changes.push(Change::Foam(new.config.foam));
    }
    changes
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
