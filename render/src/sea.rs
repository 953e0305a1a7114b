//! The sea an engine asks for ([`SeaSettings`]) and the policy that turns a change of it into
//! what a running ocean can take live (new weather over a transition, a new choppiness, new
//! foam settings, a new depth map) or a new ocean (new grids, a new water depth, a sea the
//! grids cannot hold).

use std::sync::Arc;

use ocean_fft::{DepthMap, Error, FoamConfig, OceanConfig, OceanState, SeaState, Spectrum};

/// Seconds of foam spun up when a new ocean is built (at steps of [`PRE_ROLL_DT`]).
pub const PRE_ROLL: f64 = 6.0;
/// Time step of the spin-up, s.
pub const PRE_ROLL_DT: f64 = 0.1;

/// The sea to simulate: the wave spectrum, the grids (with the choppiness and the foam), and
/// how long a new spectrum takes to replace the old one.
#[derive(Debug, Clone, PartialEq)]
pub struct SeaSettings {
    /// The wave spectrum: wind, fetch, spreading, depth.
    pub spectrum: Spectrum,
    /// The cascades' grids, the choppiness (`config.choppiness`, dimensionless) and the foam
    /// (`config.foam`).
    pub config: OceanConfig,
    /// Seconds of sea time over which a new spectrum replaces the old one (0: at the next
    /// step).
    pub transition_seconds: f64,
    /// The water depth over a part of the world (`OceanState::set_depth_map`; `None`: the
    /// spectrum's depth everywhere). The map is solved for the weather: a new spectrum
    /// solves it again. A 256² map takes about a second on the thread that applies it.
    pub depth_map: Option<Arc<DepthMap>>,
}

impl Default for SeaSettings {
    /// A fresh breeze (Beaufort 5) on its preset's grids, changing over 10 s.
    fn default() -> Self {
        SeaSettings::preset(SeaState::FreshBreeze)
    }
}

/// One live change a running ocean takes before its next step.
#[derive(Debug, Clone, PartialEq)]
pub enum Change {
    /// New weather reached over this many seconds (`OceanState::set_spectrum`).
    Spectrum(Spectrum, f64),
    /// A new choppiness (`OceanState::set_choppiness`).
    Choppiness(f32),
    /// New foam settings (`OceanState::set_foam_config`).
    Foam(FoamConfig),
    /// A depth map set (again) (`OceanState::set_depth_map`): a new map, or the same one
    /// solved for new weather.
    DepthMap(Option<Arc<DepthMap>>),
}

/// What going from the sea an ocean runs to a new one takes.
#[derive(Debug, Clone, PartialEq)]
pub enum Plan {
    /// Nothing: the same sea.
    Nothing,
    /// Live changes, applied in order with [`apply`].
    Live(Vec<Change>),
    /// A new ocean with this configuration ([`SeaSettings::grids`]), built with [`build`].
    Rebuild(OceanConfig),
}

impl SeaSettings {
    /// The preset's spectrum and config (grids fitted to its waves), changing over 10 s.
    pub fn preset(state: SeaState) -> SeaSettings {
        let (spectrum, config) = state.build();
        SeaSettings {
            spectrum,
            config,
            transition_seconds: 10.0,
            depth_map: None,
        }
    }

    /// Takes the preset's weather (spectrum, choppiness, foam) and keeps the grids, so that
    /// the change is live where the grids hold the new sea (see [`SeaSettings::plan`]).
    pub fn set_weather(&mut self, state: SeaState) {
        let (spectrum, config) = state.build();
        self.spectrum = spectrum;
        self.config.choppiness = config.choppiness;
        self.config.foam = config.foam;
    }

    /// Whether the grids of `config` hold at least `limits::MIN_CHANGE_SHARE` of the
    /// spectrum's variance.
    pub fn fits(&self) -> bool {
        self.config
            .fit(&self.spectrum)
            .is_ok_and(|fit| fit.held >= ocean_fft::limits::MIN_CHANGE_SHARE)
    }

    /// The config an ocean of these settings is built with: `config` itself if its grids
    /// hold the spectrum ([`fits`](Self::fits)), else `config` with its lengths fitted to the
    /// spectrum (`OceanConfig::with_fitted_lengths`).
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

    /// What taking `self` to an ocean that runs `ocean` (built or last changed to `running`)
    /// needs: a new ocean when the grids differ in anything but the choppiness and the foam,
    /// when the water depth changes (`set_spectrum` keeps the dispersion), or when the
    /// running grids hold less than `limits::MIN_CHANGE_SHARE` of the new sea (they may
    /// be fitted to an earlier one); live changes otherwise, the choppiness first (so that a
    /// calmer sea at a higher choppiness is checked with the choppiness it will run with),
    /// the depth map after the spectrum (a map is solved for the weather, so new weather
    /// sets it again).
    pub fn plan(&self, running: &SeaSettings, ocean: &OceanState) -> Plan {
        if self == running {
            return Plan::Nothing;
        }
        if self.spectrum == running.spectrum
            && self.config == running.config
            && self.transition_seconds == running.transition_seconds
        {
            // Only the map changed.
            return Plan::Live(vec![Change::DepthMap(self.depth_map.clone())]);
        }
        let mut grids = running.config.clone();
        grids.choppiness = self.config.choppiness;
        grids.foam = self.config.foam;
        let same_grids = grids == self.config;
        let same_sea = self.spectrum == *ocean.spectrum();
        let holds = same_sea
            || self.spectrum.dispersion() == ocean.spectrum().dispersion()
                && ocean
                    .config()
                    .fit(&self.spectrum)
                    .is_ok_and(|fit| fit.held >= ocean_fft::limits::MIN_CHANGE_SHARE);
        if !same_grids || !holds {
            return Plan::Rebuild(self.grids());
        }
        let mut changes = Vec::new();
        if running.config.choppiness != self.config.choppiness {
            changes.push(Change::Choppiness(self.config.choppiness));
        }
        if running.spectrum != self.spectrum {
            changes.push(Change::Spectrum(
                self.spectrum.clone(),
                self.transition_seconds,
            ));
        }
        if running.config.foam != self.config.foam {
            changes.push(Change::Foam(self.config.foam));
        }
        let new_weather = running.spectrum != self.spectrum && self.depth_map.is_some();
        if running.depth_map != self.depth_map || new_weather {
            changes.push(Change::DepthMap(self.depth_map.clone()));
        }
        Plan::Live(changes)
    }
}

/// Applies one live change to `ocean`.
///
/// # Errors
/// The crate's, for a change it refuses; `ocean` is unchanged then.
pub fn apply(ocean: &mut OceanState, change: Change) -> Result<(), Error> {
    match change {
        Change::Spectrum(spectrum, duration) => ocean.set_spectrum(spectrum, duration),
        Change::Choppiness(choppiness) => ocean.set_choppiness(choppiness),
        Change::Foam(foam) => ocean.set_foam_config(foam),
        Change::DepthMap(map) => ocean.set_depth_map(map.as_deref().cloned()),
    }
}

/// A new ocean of `sea` on the grids `config` at sea time `time` ([`build`]) with its depth
/// map set.
///
/// # Errors
/// The crate's, for a sea, grids or map it refuses.
pub fn build_sea(sea: &SeaSettings, config: OceanConfig, time: f64) -> Result<OceanState, Error> {
    let mut ocean = build(sea.spectrum.clone(), config, time)?;
    set_depth_map_at_once(&mut ocean, sea.depth_map.as_deref())?;
    Ok(ocean)
}

/// Sets `map` on a new `ocean` without the blend from the open sea a running ocean gets
/// (there is no earlier sea to hide a pop from): set at a time
/// [`BLEND_SECONDS`](ocean_fft::coast::BLEND_SECONDS) before the ocean's, then back (the foam
/// is kept as it is).
///
/// # Errors
/// The crate's, for a map it refuses; the ocean is unchanged then.
pub fn set_depth_map_at_once(ocean: &mut OceanState, map: Option<&DepthMap>) -> Result<(), Error> {
    let Some(map) = map else {
        return Ok(());
    };
    map.validate()?;
    let time = ocean.time();
    ocean.set_time(time - ocean_fft::coast::BLEND_SECONDS)?;
    let set = ocean.set_depth_map(Some(map.clone()));
    ocean.set_time(time)?;
    set
}

/// A new ocean of `spectrum` and `config` at sea time `time`, its foam spun up over the
/// [`PRE_ROLL`] seconds before it (so a new ocean shows the foam of a sea that has run).
///
/// # Errors
/// The crate's, for a sea or grids it refuses.
pub fn build(spectrum: Spectrum, config: OceanConfig, time: f64) -> Result<OceanState, Error> {
    let mut ocean = OceanState::new(spectrum, config)?;
    ocean.set_time(time)?;
    ocean.pre_roll(PRE_ROLL, PRE_ROLL_DT)?;
    Ok(ocean)
}

/// Moves `ocean` to sea time `t`: a step with the foam evolving, or a jump for a clock that
/// went back or leapt ahead by more than `limits::MAX_STEP` (the foam is kept as it is).
///
/// # Errors
/// The crate's, for a time it refuses (not finite).
pub fn follow_clock(ocean: &mut OceanState, t: f64) -> Result<(), Error> {
    let now = ocean.time();
    if t >= now && t - now <= ocean_fft::limits::MAX_STEP {
        ocean.step_to(t)
    } else {
        ocean.set_time(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small(state: SeaState) -> SeaSettings {
        let mut settings = SeaSettings::preset(state);
        settings.config.size = 32;
        settings
    }

    /// Each kind of edit takes the path the running ocean can take: weather, choppiness and
    /// foam live (choppiness first), new grids, a new depth and a sea the grids cannot hold
    /// (a storm on a calm sea's grids) a new ocean, on grids fitted to it for the last.
    #[test]
    fn edits_take_the_path_the_ocean_can_take() {
        let breeze = small(SeaState::FreshBreeze);
        let ocean = OceanState::new(breeze.spectrum.clone(), breeze.config.clone()).unwrap();
        assert_eq!(breeze.plan(&breeze, &ocean), Plan::Nothing);

        let mut weather = breeze.clone();
        weather.set_weather(SeaState::ModerateBreeze);
        weather.config.choppiness = breeze.config.choppiness * 0.5;
        match weather.plan(&breeze, &ocean) {
            Plan::Live(changes) => {
                assert!(matches!(changes[0], Change::Choppiness(_)), "{changes:?}");
                assert!(changes.iter().any(
                    |c| matches!(c, Change::Spectrum(s, d) if *s == weather.spectrum && *d == 10.0)
                ));
            }
            other => panic!("{other:?}"),
        }

        let mut grids = breeze.clone();
        grids.config.seed += 1;
        assert_eq!(
            grids.plan(&breeze, &ocean),
            Plan::Rebuild(grids.config.clone())
        );

        let mut bay = breeze.clone();
        bay.set_weather(SeaState::ShallowBay);
        assert_ne!(bay.spectrum.dispersion(), breeze.spectrum.dispersion());
        assert!(matches!(bay.plan(&breeze, &ocean), Plan::Rebuild(_)));

        let calm = small(SeaState::Calm);
        let ocean = OceanState::new(calm.spectrum.clone(), calm.config.clone()).unwrap();
        let mut storm = calm.clone();
        storm.set_weather(SeaState::Storm);
        assert!(!storm.fits());
        let Plan::Rebuild(config) = storm.plan(&calm, &ocean) else {
            panic!("a storm on calm grids must rebuild");
        };
        let fit = config.fit(&storm.spectrum).unwrap();
        assert!(fit.held >= ocean_fft::limits::MIN_CHANGE_SHARE, "{fit:?}");
        assert_eq!(config.size, 32);
    }

    /// A new depth map is a live change; new weather over a map sets the map again, after
    /// the spectrum; a rebuild keeps the map ([`build_sea`]).
    #[test]
    fn depth_maps_follow_the_weather() {
        let breeze = small(SeaState::FreshBreeze);
        let ocean = OceanState::new(breeze.spectrum.clone(), breeze.config.clone()).unwrap();
        let map = Arc::new(DepthMap {
            origin: [0.0, 0.0],
            spacing: 4.0,
            size: [8, 8],
            depth: (0..64).map(|c| 10.0 - (c % 8) as f32 * 2.0).collect(),
        });
        let mut coast = breeze.clone();
        coast.depth_map = Some(map.clone());
        assert_eq!(
            coast.plan(&breeze, &ocean),
            Plan::Live(vec![Change::DepthMap(Some(map.clone()))])
        );
        let mut weather = coast.clone();
        weather.set_weather(SeaState::ModerateBreeze);
        let Plan::Live(changes) = weather.plan(&coast, &ocean) else {
            panic!("new weather is live");
        };
        let spectrum = changes
            .iter()
            .position(|c| matches!(c, Change::Spectrum(..)));
        let solved = changes
            .iter()
            .position(|c| *c == Change::DepthMap(Some(map.clone())));
        assert!(spectrum.unwrap() < solved.unwrap(), "{changes:?}");
        let mut no_map = coast.clone();
        no_map.depth_map = None;
        assert_eq!(
            no_map.plan(&coast, &ocean),
            Plan::Live(vec![Change::DepthMap(None)])
        );
        let rebuilt = build_sea(&coast, coast.config.clone(), 5.0).unwrap();
        assert_eq!(rebuilt.textures().coast().unwrap().map(), &*map);
        // At once: the queries read the map's waves now, not a blend from the open sea.
        let mut later = OceanState::new(coast.spectrum.clone(), coast.config.clone()).unwrap();
        later.set_time(5.0).unwrap();
        later.set_depth_map(Some(DepthMap::clone(&map))).unwrap();
        later
            .set_time(5.0 + ocean_fft::coast::BLEND_SECONDS)
            .unwrap();
        let mut packed = vec![[0.0f32; 4]; 64];
        let mut settled = vec![[0.0f32; 4]; 64];
        rebuilt.textures().pack_coast(&mut packed).unwrap();
        later.textures().pack_coast(&mut settled).unwrap();
        assert_eq!(packed, settled);
    }
}
