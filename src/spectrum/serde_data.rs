//! The stored form of a [`Spectrum`] (with the `serde` feature): its fields unchecked, and the
//! gate that checks them with the checks of the constructors and setters, so that a loaded
//! spectrum is as valid as a built one.

use std::ops::Bound::{Included, Unbounded};

use serde::{Deserialize, Serialize};

use super::dispersion::Dispersion;
use super::omega::{G, PIERSON_MOSKOWITZ_PEAK};
use super::spreading::Spreading;
use super::{check_inverse_wave_age, check_wind_speed, DepthFactor, Model, Spectrum};
use crate::error::{self, Error};
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

/// Checks every stored parameter with the checks of the constructors and setters, and
/// wraps the wind direction to [−π, π] as [`Spectrum::with_wind_direction`]
/// does: the gate for spectra assembled from stored fields (deserialisation).
///
/// The parameters are checked one by one, plus the one relation every constructor keeps
/// and evaluation relies on (ω_p U/g ≥ 0.877, a sea at most fully developed); α and ω_p
/// need not follow the fetch law of the stored wind and fetch, as they need not for
/// [`Spectrum::jonswap_from_parameters`].
fn validate_spectrum(mut spectrum: Spectrum) -> Result<Spectrum, Error> {
    match spectrum.model {
        Model::Jonswap {
            alpha,
            peak_omega,
            gamma,
        } => {
            Spectrum::check_model(alpha, peak_omega)?;
            error::positive("gamma", gamma)?;
            // The fetch law caps the wind at MAX_WIND_SPEED; jonswap_from_parameters
            // derives it from ω_p, which has no upper bound.
            match spectrum.fetch {
                Some(fetch) => {
                    check_wind_speed(spectrum.wind_speed)?;
                    error::positive("fetch", fetch)?;
                }
                None => {
                    error::positive("wind_speed", spectrum.wind_speed)?;
                }
            }
            // Every constructor gives a sea at most fully developed, ω_p U/g ≥ 0.877 (the
            // fetch law is capped there; Pierson–Moskowitz and jonswap_from_parameters sit
            // on it). The Mitsuyasu spreading's s_p = 11.5 (ω_p U/g)^−2.5 relies on it:
            // far below, s overflows the cos-2s normalisation into NaN.
            let fully_developed =
                (PIERSON_MOSKOWITZ_PEAK * (1.0 - 1e-4) * G / f64::from(spectrum.wind_speed)) as f32;
            error::in_range(
                "peak_omega",
                peak_omega,
                Included(fully_developed),
                Unbounded,
            )?;
        }
        Model::Phillips { amplitude } => {
            check_wind_speed(spectrum.wind_speed)?;
            error::non_negative("amplitude", amplitude)?;
            if spectrum.fetch.is_some() {
                return Err(Error::NotApplicable {
                    name: "fetch",
                    reason: "the Phillips spectrum is not built from a fetch",
                });
            }
        }
        Model::Elfouhaily { inverse_wave_age } => {
            check_wind_speed(spectrum.wind_speed)?;
            check_inverse_wave_age(inverse_wave_age)?;
            if spectrum.fetch.is_some() {
                return Err(Error::NotApplicable {
                    name: "fetch",
                    reason: "the Elfouhaily spectrum is built from its inverse wave age",
                });
            }
        }
    }
    let wind_direction = error::finite("wind_direction", spectrum.wind_direction)?;
    if wind_direction.abs() > std::f32::consts::PI {
        spectrum = spectrum.with_wind_direction(wind_direction)?;
    }
    spectrum.spreading = spectrum.spreading.validate()?;
    let (swell, blend, length) = (
        spectrum.swell,
        spectrum.spread_blend,
        spectrum.short_wave_length,
    );
    let (dispersion, depth_factor) = (spectrum.dispersion, spectrum.depth_factor);
    spectrum
        .with_swell(swell)?
        .with_spread_blend(blend)?
        .with_short_wave_length(length)?
        .with_dispersion(dispersion)?
        .with_depth_factor(depth_factor)
}
