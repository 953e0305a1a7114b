//! The stored form of a [`Spectrum`] (with the `serde` feature): its fields unchecked, and the
//! gate that checks them with the checks of the constructors and setters, so that a loaded
//! spectrum is as valid as a built one.

use serde::{Deserialize, Serialize};

use super::dispersion::Dispersion;
use super::params::validate_spectrum;
use super::spreading::Spreading;
use super::{DepthFactor, Model, Spectrum};
use crate::error::Error;
use crate::serde_impls::Float;

/// The model behind S(ω), as stored.
#[derive(Serialize, Deserialize)]
#[serde(rename = "Model")]
enum ModelData {
    Jonswap {
        alpha: Float,
        peak_omega: Float,
        gamma: Float,
    },
    Phillips {
        amplitude: Float,
    },
    Elfouhaily {
        inverse_wave_age: Float,
    },
}

/// Every field of a [`Spectrum`], unchecked.
#[derive(Serialize, Deserialize)]
#[serde(rename = "Spectrum")]
pub(crate) struct SpectrumData {
    model: ModelData,
    wind_speed: Float,
    fetch: Option<Float>,
    wind_direction: Float,
    spreading: Spreading,
    swell: Float,
    spread_blend: Float,
    short_wave_length: Float,
    dispersion: Dispersion,
    depth_factor: DepthFactor,
}

impl From<Spectrum> for SpectrumData {
    fn from(spectrum: Spectrum) -> Self {
        let model = match spectrum.model {
            Model::Jonswap {
                alpha,
                peak_omega,
                gamma,
            } => ModelData::Jonswap {
                alpha: alpha.into(),
                peak_omega: peak_omega.into(),
                gamma: gamma.into(),
            },
            Model::Phillips { amplitude } => ModelData::Phillips {
                amplitude: amplitude.into(),
            },
            Model::Elfouhaily { inverse_wave_age } => ModelData::Elfouhaily {
                inverse_wave_age: inverse_wave_age.into(),
            },
        };
        SpectrumData {
            model,
            wind_speed: spectrum.wind_speed.into(),
            fetch: spectrum.fetch.map(Float),
            wind_direction: spectrum.wind_direction.into(),
            spreading: spectrum.spreading,
            swell: spectrum.swell.into(),
            spread_blend: spectrum.spread_blend.into(),
            short_wave_length: spectrum.short_wave_length.into(),
            dispersion: spectrum.dispersion,
            depth_factor: spectrum.depth_factor,
        }
    }
}

impl TryFrom<SpectrumData> for Spectrum {
    type Error = Error;

    fn try_from(data: SpectrumData) -> Result<Self, Error> {
        let model = match data.model {
            ModelData::Jonswap {
                alpha,
                peak_omega,
                gamma,
            } => Model::Jonswap {
                alpha: alpha.0,
                peak_omega: peak_omega.0,
                gamma: gamma.0,
            },
            ModelData::Phillips { amplitude } => Model::Phillips {
                amplitude: amplitude.0,
            },
            ModelData::Elfouhaily { inverse_wave_age } => Model::Elfouhaily {
                inverse_wave_age: inverse_wave_age.0,
            },
        };
        let spectrum = Spectrum {
            model,
            wind_speed: data.wind_speed.0,
            fetch: data.fetch.map(|fetch| fetch.0),
            wind_direction: data.wind_direction.0,
            spreading: data.spreading,
            swell: data.swell.0,
            spread_blend: data.spread_blend.0,
            short_wave_length: data.short_wave_length.0,
            dispersion: data.dispersion,
            depth_factor: data.depth_factor,
        };
        validate_spectrum(spectrum)
    }
}
