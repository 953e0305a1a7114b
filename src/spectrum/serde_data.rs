//! The serialised form of [`Spectrum`] (feature `serde`): a mirror of its private fields,
//! turned back into a spectrum only through [`Spectrum::validate`].

use serde::{Deserialize, Serialize};

use crate::dispersion::Dispersion;
use crate::error::Error;
use crate::serde_support::Float;

use super::{DepthFactor, Model, Spectrum, Spreading};

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
        };
        Spectrum {
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
        }
        .validate()
    }
}
