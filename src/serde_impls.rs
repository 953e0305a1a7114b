//! The encodings the optional `serde` feature shares: the number type of the validated
//! mirrors through which [`Spectrum`](crate::spectrum::Spectrum),
//! [`Dispersion`](crate::spectrum::dispersion::Dispersion) and
//! [`Spreading`](crate::spectrum::spreading::Spreading) are read (each mirror lives beside its
//! type, so a loaded value passes the same checks as a built one), the encoding of a band limit
//! that may be +∞, and the checks that refuse to save a non-finite number. A leaf: it names no
//! type of the crate.

use std::fmt;

use serde::de::{self, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

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
