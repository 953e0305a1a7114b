//! Everything the optional `serde` feature adds, in one place: the validated mirrors through
//! which [`Spectrum`], [`Dispersion`] and [`Spreading`] are read (so a loaded value passes the
//! same checks as a built one), the number type they use, and the encoding of a band limit
//! that may be +∞.

use std::fmt;

use serde::de::{self, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use std::ops::Bound::{Included, Unbounded};

use crate::error::{self, Error};
use crate::spectrum::dispersion::Dispersion;
use crate::spectrum::{
    check_inverse_wave_age, check_wind_speed, DepthFactor, Model, Spectrum, Spreading, G,
    PIERSON_MOSKOWITZ_PEAK,
};

/// An f32 in a validated mirror struct (`Spectrum`, `Dispersion`, `Spreading`).
///
/// It serialises as a plain f32. In human-readable formats it also reads `null` as NaN and a
/// string such as `"NaN"` or `"inf"` as the number it spells, so that a tampered value reaches
/// the crate's own checks and fails with an [`Error`](crate::Error) naming the parameter
/// ("parameter `wind_speed` is not finite") instead of a bare type error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Float(pub f32);

impl From<f32> for Float {
    fn from(value: f32) -> Self {
        Float(value)
    }
}

impl Serialize for Float {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_f32(self.0)
    }
}

impl<'de> Deserialize<'de> for Float {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        if deserializer.is_human_readable() {
            deserializer.deserialize_any(FloatVisitor)
        } else {
            deserializer.deserialize_f32(FloatVisitor)
        }
    }
}

struct FloatVisitor;

impl Visitor<'_> for FloatVisitor {
    type Value = Float;

    fn expecting(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        formatter.write_str("a number")
    }

    fn visit_f32<E: de::Error>(self, value: f32) -> Result<Float, E> {
        Ok(Float(value))
    }

    fn visit_f64<E: de::Error>(self, value: f64) -> Result<Float, E> {
        // Out-of-range doubles become ±∞ and are then rejected as not finite.
        Ok(Float(value as f32))
    }

    fn visit_i64<E: de::Error>(self, value: i64) -> Result<Float, E> {
        Ok(Float(value as f32))
    }

    fn visit_u64<E: de::Error>(self, value: u64) -> Result<Float, E> {
        Ok(Float(value as f32))
    }

    fn visit_unit<E: de::Error>(self) -> Result<Float, E> {
        // serde_json writes NaN and ±∞ as null.
        Ok(Float(f32::NAN))
    }

    fn visit_none<E: de::Error>(self) -> Result<Float, E> {
        Ok(Float(f32::NAN))
    }

    fn visit_str<E: de::Error>(self, value: &str) -> Result<Float, E> {
        value
            .trim()
            .parse::<f32>()
            .map(Float)
            .map_err(|_| E::invalid_value(de::Unexpected::Str(value), &self))
    }
}

/// `serde(with = "crate::serde_impls::band_limit")` for an upper band limit `k_max` that
/// may be +∞, which JSON cannot hold: +∞ is written as a missing value (`null` in JSON) and
/// read back from one; finite values are plain numbers. NaN and −∞ are refused when
/// serialising (no constructor accepts them, and JSON would turn them into `null`, which
/// reads back as +∞).
pub(crate) mod band_limit {
    use serde::{de, ser, Deserialize, Deserializer, Serialize, Serializer};

    pub(crate) fn serialize<S: Serializer>(value: &f32, serializer: S) -> Result<S::Ok, S::Error> {
        if *value == f32::INFINITY {
            None::<f32>.serialize(serializer)
        } else if value.is_finite() {
            Some(*value).serialize(serializer)
        } else {
            Err(ser::Error::custom(format_args!(
                "parameter `k_max` = {value} cannot be saved (expected a number or +inf)"
            )))
        }
    }

    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<f32, D::Error> {
        match Option::<f32>::deserialize(deserializer)? {
            None => Ok(f32::INFINITY),
            Some(value) if value.is_nan() => Err(de::Error::custom(
                "parameter `k_max` is NaN (expected a number or null for +inf)",
            )),
            Some(value) => Ok(value),
        }
    }

    /// The value of a missing `k_max`: +∞ (formats without `null`, such as TOML, omit it).
    pub(crate) fn infinite() -> f32 {
        f32::INFINITY
    }
}

/// The serialised form of [`Dispersion`], checked by `TryFrom` on the way in.
#[derive(Serialize, Deserialize)]
#[serde(rename = "Dispersion")]
pub(crate) enum DispersionData {
    Deep,
    FiniteDepth { depth: Float },
    Capillary { depth: Float },
}

impl From<Dispersion> for DispersionData {
    fn from(dispersion: Dispersion) -> Self {
        match dispersion {
            Dispersion::Deep => DispersionData::Deep,
            Dispersion::FiniteDepth { depth } => DispersionData::FiniteDepth {
                depth: depth.into(),
            },
            Dispersion::Capillary { depth } => DispersionData::Capillary {
                depth: depth.into(),
            },
        }
    }
}

impl TryFrom<DispersionData> for Dispersion {
    type Error = Error;

    fn try_from(data: DispersionData) -> Result<Self, Error> {
        let dispersion = match data {
            DispersionData::Deep => Dispersion::Deep,
            DispersionData::FiniteDepth { depth } => Dispersion::FiniteDepth { depth: depth.0 },
            DispersionData::Capillary { depth } => Dispersion::Capillary { depth: depth.0 },
        };
        dispersion.validate()?;
        Ok(dispersion)
    }
}

/// The serialised form of [`Spreading`], checked by `TryFrom` on the way in.
#[derive(Serialize, Deserialize)]
#[serde(rename = "Spreading")]
pub(crate) enum SpreadingData {
    Mitsuyasu,
    Hasselmann,
    Cos2s { s: Float },
    DonelanBanner,
    Flat,
    Cos2,
    Cosine { exponent: Float, upwind: Float },
    Elfouhaily,
}

impl From<Spreading> for SpreadingData {
    fn from(spreading: Spreading) -> Self {
        match spreading {
            Spreading::Mitsuyasu => SpreadingData::Mitsuyasu,
            Spreading::Hasselmann => SpreadingData::Hasselmann,
            Spreading::Cos2s { s } => SpreadingData::Cos2s { s: s.into() },
            Spreading::DonelanBanner => SpreadingData::DonelanBanner,
            Spreading::Flat => SpreadingData::Flat,
            Spreading::Elfouhaily => SpreadingData::Elfouhaily,
            Spreading::Cos2 => SpreadingData::Cos2,
            Spreading::Cosine { exponent, upwind } => SpreadingData::Cosine {
                exponent: exponent.into(),
                upwind: upwind.into(),
            },
        }
    }
}

impl TryFrom<SpreadingData> for Spreading {
    type Error = Error;

    fn try_from(data: SpreadingData) -> Result<Self, Error> {
        match data {
            SpreadingData::Mitsuyasu => Spreading::Mitsuyasu,
            SpreadingData::Hasselmann => Spreading::Hasselmann,
            SpreadingData::Cos2s { s } => Spreading::Cos2s { s: s.0 },
            SpreadingData::DonelanBanner => Spreading::DonelanBanner,
            SpreadingData::Flat => Spreading::Flat,
            SpreadingData::Elfouhaily => Spreading::Elfouhaily,
            SpreadingData::Cos2 => Spreading::Cos2,
            SpreadingData::Cosine { exponent, upwind } => Spreading::Cosine {
                exponent: exponent.0,
                upwind: upwind.0,
            },
        }
        .validate()
    }
}

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

/// The value of a missing `memory_limit`.
pub(crate) fn default_memory_limit() -> usize {
    crate::CascadeConfig::DEFAULT_MEMORY_LIMIT
}

/// The value of a missing `band_split`.
pub(crate) fn default_band_split() -> f32 {
    crate::OceanConfig::DEFAULT_BAND_SPLIT
}

/// `serialize_with` functions for the number fields of the passive configs: a NaN or infinite
/// value is refused when saving, naming the field, because JSON would write it as `null` and a
/// round trip would then change the config (an `Option` would read back as `None`).
pub(crate) mod finite {
    use serde::{ser, Serialize, Serializer};

    #[cold]
    fn refuse<E: ser::Error>(name: &str, value: f32) -> E {
        E::custom(format_args!(
            "parameter `{name}` = {value} cannot be saved (expected a finite number)"
        ))
    }

    fn check<E: ser::Error>(name: &str, value: f32) -> Result<f32, E> {
        if value.is_finite() {
            Ok(value)
        } else {
            Err(refuse(name, value))
        }
    }

    macro_rules! finite_fields {
        ($($function:ident: $name:literal),* $(,)?) => {$(
            pub(crate) fn $function<S: Serializer>(value: &f32, s: S) -> Result<S::Ok, S::Error> {
                check($name, *value)?.serialize(s)
            }
        )*};
    }

    finite_fields! {
        length: "length",
        k_min: "k_min",
        choppiness: "choppiness",
        band_split: "band_split",
        coverage: "foam.coverage",
        active_decay: "foam.active_decay",
        residual_decay: "foam.residual_decay",
        drift: "foam.drift",
        streak_length: "foam.streak_length",
        streak_width: "foam.streak_width",
        tolerance: "query.tolerance",
    }

    pub(crate) fn repeat_period<S: Serializer>(
        value: &Option<f32>,
        s: S,
    ) -> Result<S::Ok, S::Error> {
        value
            .map(|v| check("repeat_period", v))
            .transpose()?
            .serialize(s)
    }

    pub(crate) fn wind_speed<S: Serializer>(value: &Option<f32>, s: S) -> Result<S::Ok, S::Error> {
        value
            .map(|v| check("foam.wind_speed", v))
            .transpose()?
            .serialize(s)
    }

    pub(crate) fn lengths<S: Serializer>(value: &[f32], s: S) -> Result<S::Ok, S::Error> {
        for &v in value {
            check::<S::Error>("lengths", v)?;
        }
        value.serialize(s)
    }
}
