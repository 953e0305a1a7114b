//! The crate's one error type and the checks that produce it.

use std::fmt;

/// Everything that can go wrong when building a spectrum, a cascade or an ocean.
///
/// Every public constructor and `with_*` setter validates its inputs and returns one of these
/// instead of panicking, so a value that exists is valid and its evaluation never yields NaN.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// A parameter was NaN or infinite.
    NonFinite {
        /// Name of the parameter, as in the function's signature.
        name: &'static str,
    },
    /// A finite parameter lay outside its valid range.
    OutOfRange {
        /// Name of the parameter, as in the function's signature.
        name: &'static str,
        /// The value that was given.
        value: f64,
        /// The valid range, in words (for example `"> 0"` or `"in [0, 1]"`).
        expected: &'static str,
    },
    /// The grid size N was odd, smaller than 4 or larger than the supported maximum.
    InvalidSize {
        /// The size that was given.
        size: usize,
    },
    /// A parameter that the chosen model does not have (for example γ on a Phillips spectrum).
    NotApplicable {
        /// Name of the parameter.
        name: &'static str,
        /// Why it does not apply.
        reason: &'static str,
    },
    /// The wave-number band `[k_min, k_max)` was empty or inverted, or held no wave vector of
    /// the grid.
    EmptyBand {
        /// Lower band limit, in rad/m.
        k_min: f64,
        /// Upper band limit, in rad/m.
        k_max: f64,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NonFinite { name } => write!(f, "parameter `{name}` is not finite"),
            Error::OutOfRange {
                name,
                value,
                expected,
            } => write!(
                f,
                "parameter `{name}` = {value} is out of range (expected {expected})"
            ),
            Error::InvalidSize { size } => write!(
                f,
                "grid size {size} is invalid (expected an even number from 4 to {})",
                crate::MAX_SIZE
            ),
            Error::NotApplicable { name, reason } => {
                write!(f, "parameter `{name}` does not apply: {reason}")
            }
            Error::EmptyBand { k_min, k_max } => write!(
                f,
                "wave-number band [{k_min}, {k_max}) rad/m is empty or holds no grid wave vector"
            ),
        }
    }
}

impl std::error::Error for Error {}

/// Checks that `value` is finite.
pub(crate) fn finite(name: &'static str, value: f32) -> Result<f32, Error> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::NonFinite { name })
    }
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn positive(name: &'static str, value: f32) -> Result<f32, Error> {
    finite(name, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(out_of_range(name, value, "> 0"))
    }
}

/// Checks that `value` is finite and not negative.
pub(crate) fn non_negative(name: &'static str, value: f32) -> Result<f32, Error> {
    finite(name, value)?;
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(out_of_range(name, value, ">= 0"))
    }
}

/// Checks that `value` is finite and in `[0, 1]`.
pub(crate) fn unit_interval(name: &'static str, value: f32) -> Result<f32, Error> {
    finite(name, value)?;
    if (0.0..=1.0).contains(&value) {
        Ok(value)
    } else {
        Err(out_of_range(name, value, "in [0, 1]"))
    }
}

#[cold]
pub(crate) fn out_of_range(name: &'static str, value: f32, expected: &'static str) -> Error {
    Error::OutOfRange {
        name,
        value: f64::from(value),
        expected,
    }
}
