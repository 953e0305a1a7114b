//! The sea state the panels edit: every parameter of the spectrum and the ocean's
//! configuration as plain numbers, read from and turned into a [`Spectrum`] (through its
//! [`SpectrumParams`](ocean_fft::SpectrumParams)) and an [`OceanConfig`].

use ocean_fft::{
    DepthFactor, Dispersion, Error, OceanConfig, SeaState, Spectrum, SpectrumKind, Spreading,
    WakeConfig,
};

/// The fetch in m the panel starts from when a sea built without one switches to JONSWAP.
const DEFAULT_FETCH: f32 = 100_000.0;

/// The boats' wake window: 256² samples 0.75 m apart (192 m, the shortest wave 1.5 m long),
/// wide enough for the Kelvin wedge of a boat at 8 m/s (transverse waves 41 m long) seen from
/// 40 m above.
pub fn wake_config() -> WakeConfig {
    WakeConfig {
        size: 256,
        spacing: 0.75,
        ..WakeConfig::default()
    }
}

/// The spectrum's model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Model {
    /// JONSWAP from wind and fetch (γ adjustable).
    Jonswap,
    /// Pierson–Moskowitz: a fully developed sea from the wind alone.
    PiersonMoskowitz,
    /// TMA: JONSWAP with the depth factor of finite depth.
    Tma,
    /// JONSWAP from its own parameters (α, peak period, γ), as the swell preset.
    JonswapParameters { alpha: f32, peak_period: f32 },
    /// Elfouhaily et al.'s unified spectrum with an inverse wave age.
    Elfouhaily { inverse_wave_age: f32 },
    /// Tessendorf's Phillips spectrum with an amplitude.
    Phillips { amplitude: f32 },
}

impl Model {
    /// The names the spectrum panel lists.
    pub const NAMES: [&'static str; 6] = [
        "JONSWAP",
        "Pierson–Moskowitz",
        "TMA (shallow)",
        "JONSWAP (α, Tp)",
        "Elfouhaily",
        "Phillips",
    ];

    /// Index into [`Model::NAMES`].
    pub fn index(self) -> usize {
        match self {
            Model::Jonswap => 0,
            Model::PiersonMoskowitz => 1,
            Model::Tma => 2,
            Model::JonswapParameters { .. } => 3,
            Model::Elfouhaily { .. } => 4,
            Model::Phillips { .. } => 5,
        }
    }

    /// The model of index `index` with default parameters.
    pub fn from_index(index: usize) -> Model {
        match index {
            1 => Model::PiersonMoskowitz,
            2 => Model::Tma,
            3 => Model::JonswapParameters {
                alpha: 0.0025,
                peak_period: 12.0,
            },
            4 => Model::Elfouhaily {
                inverse_wave_age: 0.84,
            },
            5 => Model::Phillips { amplitude: 3e-7 },
            _ => Model::Jonswap,
        }
    }
}

/// The directional spreading's choices.
pub const SPREADINGS: [&str; 7] = [
    "Donelan–Banner",
    "Mitsuyasu",
    "Hasselmann",
    "cos-2s (fixed s)",
    "cos²",
    "Elfouhaily",
    "flat",
];

/// Every parameter of the sea the panels show.
#[derive(Debug, Clone, PartialEq)]
pub struct SeaParams {
    /// The preset it started from (its name), for the panel's title.
    pub name: String,
    pub model: Model,
    /// U10 in m/s.
    pub wind_speed: f32,
    /// Fetch in m (JONSWAP, TMA).
    pub fetch: f32,
    /// Direction the wind blows toward, degrees from +x toward +z.
    pub direction: f32,
    /// Index into [`SPREADINGS`].
    pub spreading: usize,
    /// s of the fixed cos-2s spreading.
    pub spreading_s: f32,
    /// Horvath's swell parameter in [0, 1].
    pub swell: f32,
    /// JONSWAP's peak enhancement γ.
    pub gamma: f32,
    /// Water depth in m, `None` for deep water (TMA needs one).
    pub depth: Option<f32>,
    /// Choppiness λ.
    pub choppiness: f32,
    /// Multiplier on the calibrated whitecap fraction.
    pub foam_coverage: f32,
    /// Wind for the whitecaps when it differs from the spectrum's (the swell's light breeze).
    pub foam_wind: Option<f32>,
    /// Cascade sides in m, largest first.
    pub lengths: Vec<f32>,
    /// Grid size N of every cascade.
    pub size: usize,
    /// Seed of the random amplitudes.
    pub seed: u64,
    /// Whether the boats make wakes (the ocean's wake window, [`wake_config`]).
    pub wakes: bool,
}

impl SeaParams {
    /// The names `--preset` takes: `default` and the `SeaState` names.
    pub fn preset_names() -> Vec<&'static str> {
        let mut names = vec!["default"];
        names.extend(SeaState::ALL.iter().map(|s| s.name()));
        names
    }

    /// The sea of `--preset NAME`.
    pub fn preset(name: &str) -> Option<SeaParams> {
        if name == "default" {
            return Some(Self::default_sea());
        }
        let state = SeaState::ALL.into_iter().find(|s| s.name() == name)?;
        let (spectrum, config) = state.build();
        Some(Self::from_built(name, &spectrum, &config))
    }

    /// The crate's default sea: `Spectrum::jonswap(10.0, 100_000.0)` on
    /// `OceanConfig::default()` (three 256² cascades of 1000, 230 and 51 m).
    pub fn default_sea() -> SeaParams {
        let spectrum = Spectrum::jonswap(10.0, 100_000.0).expect("constant parameters");
        Self::from_built("default", &spectrum, &OceanConfig::default())
    }

    /// The parameters of a built spectrum (read as [`SpectrumParams`](ocean_fft::SpectrumParams)) and config.
    fn from_built(name: &str, spectrum: &Spectrum, config: &OceanConfig) -> SeaParams {
        let params = spectrum.params();
        let (model, fetch, gamma) = match params.kind {
            SpectrumKind::Jonswap { fetch, gamma } => {
                let tma = params.dispersion.depth().is_some()
                    && params.depth_factor == DepthFactor::Kitaigorodskii;
                (if tma { Model::Tma } else { Model::Jonswap }, fetch, gamma)
            }
            SpectrumKind::PiersonMoskowitz => (Model::PiersonMoskowitz, DEFAULT_FETCH, 1.0),
            SpectrumKind::JonswapShape { alpha, gamma, .. } => {
                let peak_period = spectrum.peak_period();
                let model = Model::JonswapParameters { alpha, peak_period };
                (model, DEFAULT_FETCH, gamma)
            }
            SpectrumKind::Elfouhaily { inverse_wave_age } => {
                let model = Model::Elfouhaily { inverse_wave_age };
                (model, DEFAULT_FETCH, Spectrum::DEFAULT_GAMMA)
            }
            SpectrumKind::Phillips { amplitude } => {
                let model = Model::Phillips { amplitude };
                (model, DEFAULT_FETCH, Spectrum::DEFAULT_GAMMA)
            }
            // A model this viewer does not know yet: its default sea's.
            _ => (Model::Jonswap, DEFAULT_FETCH, Spectrum::DEFAULT_GAMMA),
        };
        let spreading = match params.spreading {
            Spreading::Mitsuyasu => 1,
            Spreading::Hasselmann => 2,
            Spreading::Cos2s { .. } => 3,
            Spreading::Cos2 => 4,
            Spreading::Elfouhaily => 5,
            Spreading::Flat => 6,
            _ => 0,
        };
        let spreading_s = match params.spreading {
            Spreading::Cos2s { s } => s,
            _ => 10.0,
        };
        SeaParams {
            name: name.to_string(),
            model,
            wind_speed: params.wind_speed,
            fetch,
            direction: params.wind_direction.to_degrees(),
            spreading,
            spreading_s,
            swell: params.swell,
            gamma,
            depth: params.dispersion.depth(),
            choppiness: config.choppiness,
            foam_coverage: config.foam.coverage,
            foam_wind: config.foam.wind_speed,
            lengths: config.lengths.clone(),
            size: config.size,
            seed: config.seed,
            wakes: config.wakes.is_some(),
        }
    }

    /// The spectrum these parameters describe.
    ///
    /// # Errors
    /// The crate's, naming the parameter (a fetch or depth out of range, …).
    pub fn spectrum(&self) -> Result<Spectrum, Error> {
        let spectrum = match self.model {
            Model::Jonswap => {
                Spectrum::jonswap(self.wind_speed, self.fetch)?.with_gamma(self.gamma)?
            }
            Model::PiersonMoskowitz => Spectrum::pierson_moskowitz(self.wind_speed)?,
            Model::Tma => Spectrum::tma(self.wind_speed, self.fetch, self.depth.unwrap_or(20.0))?,
            Model::JonswapParameters { alpha, peak_period } => Spectrum::jonswap_from_parameters(
                alpha,
                std::f32::consts::TAU / peak_period.max(0.1),
                self.gamma,
            )?,
            Model::Elfouhaily { inverse_wave_age } => {
                Spectrum::elfouhaily(self.wind_speed, inverse_wave_age)?
            }
            Model::Phillips { amplitude } => Spectrum::phillips(self.wind_speed, amplitude)?,
        };
        // The model's own parameters from its constructor, the rest as the panels set it.
        let mut params = spectrum.params();
        params.wind_direction = self.direction.to_radians();
        params.spreading = match self.spreading {
            1 => Spreading::Mitsuyasu,
            2 => Spreading::Hasselmann,
            3 => Spreading::Cos2s {
                s: self.spreading_s,
            },
            4 => Spreading::Cos2,
            5 => Spreading::Elfouhaily,
            6 => Spreading::Flat,
            _ => Spreading::DonelanBanner,
        };
        params.swell = self.swell;
        if let (Some(depth), false) = (self.depth, self.model == Model::Tma) {
            params.dispersion = Dispersion::FiniteDepth { depth };
        }
        Spectrum::from_params(&params)
    }

    /// The ocean's configuration (everything but the spectrum).
    pub fn config(&self) -> OceanConfig {
        let mut config = OceanConfig {
            lengths: self.lengths.clone(),
            size: self.size,
            choppiness: self.choppiness,
            seed: self.seed,
            wakes: self.wakes.then(wake_config),
            ..OceanConfig::default()
        };
        config.foam.coverage = self.foam_coverage;
        config.foam.wind_speed = self.foam_wind;
        config
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every preset read back into parameters builds the preset's own spectrum and config:
    /// the panels start from exactly the crate's sea.
    #[test]
    fn presets_round_trip_through_the_parameters() {
        for state in SeaState::ALL {
            let (spectrum, config) = state.build();
            let params = SeaParams::preset(state.name()).expect("a preset name");
            let rebuilt = params.spectrum().expect("a valid spectrum");
            let hs = spectrum.significant_wave_height();
            let rebuilt_hs = rebuilt.significant_wave_height();
            // The parameters round-trip through degrees and periods, so allow f32 rounding
            // of a few ulps on H_s (1e-4 relative).
            assert!(
                (hs - rebuilt_hs).abs() <= 1e-4 * hs,
                "{}: H_s {hs} vs {rebuilt_hs}",
                state.name()
            );
            assert_eq!(params.config(), config, "{}", state.name());
        }
        let default = SeaParams::default_sea();
        assert_eq!(default.config(), OceanConfig::default());
    }
}
