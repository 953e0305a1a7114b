//! Helpers for the optional `serde` feature: the number type of the validated mirrors and the
//! encoding of a band limit that may be +∞.

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

/// `serde(with = "crate::serde_support::band_limit")` for an upper band limit `k_max` that
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
