//! The crate's one error type and the checks that produce it.

use std::fmt;
use std::ops::{Bound, RangeBounds};

/// Everything that can go wrong when building a spectrum, a cascade or an ocean, stepping it
/// or querying it.
///
/// Every public constructor, setter, step and query validates its inputs and returns one of
/// these instead of panicking, and a call that fails changes nothing. Each variant names the
/// parameter at fault as it is spelled in the function's signature or the config's field
/// (`"wind_speed"`, `"foam.decay"`, `"query.tolerance"`), and range errors carry the bounds the
/// check used, so the message and the check cannot disagree.
///
/// ```
/// use ocean_fft::{Error, Spectrum};
/// use std::ops::Bound;
///
/// let error = Spectrum::pierson_moskowitz(250.0).unwrap_err();
/// assert_eq!(
///     error,
///     Error::OutOfRange {
///         name: "wind_speed",
///         value: 250.0,
///         min: Bound::Excluded(0.0),
///         max: Bound::Included(f64::from(Spectrum::MAX_WIND_SPEED)),
///     }
/// );
/// assert_eq!(
///     error.to_string(),
///     "parameter `wind_speed` = 250 is out of range: expected 0 < wind_speed ≤ 200"
/// );
/// ```
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// A parameter was NaN or infinite.
    NonFinite {
        /// Name of the parameter.
        name: &'static str,
    },
    /// A finite number lay outside its valid range `min .. max`.
    OutOfRange {
        /// Name of the parameter.
        name: &'static str,
        /// The value that was given (an f32 parameter is converted through its shortest
        /// decimal form, so `0.1_f32` reads back as `0.1`).
        value: f64,
        /// Lower bound of the valid range (an f32 limit through its shortest decimal form,
        /// like `value`).
        min: Bound<f64>,
        /// Upper bound of the valid range (likewise).
        max: Bound<f64>,
    },
    /// The grid size N was odd, or outside
    /// [`CascadeConfig::MIN_SIZE`](crate::CascadeConfig::MIN_SIZE) ..=
    /// [`CascadeConfig::MAX_SIZE`](crate::CascadeConfig::MAX_SIZE).
    InvalidSize {
        /// Name of the parameter.
        name: &'static str,
        /// The size that was given.
        size: usize,
        /// Smallest valid size.
        min: usize,
        /// Largest valid size.
        max: usize,
    },
    /// A count (of cascades, of transforms, a range end) lay outside `min ..= max`.
    CountOutOfRange {
        /// Name of the parameter.
        name: &'static str,
        /// The count that was given.
        count: usize,
        /// Smallest valid count.
        min: usize,
        /// Largest valid count.
        max: usize,
    },
    /// An index was not below the length of what it indexes.
    IndexOutOfRange {
        /// Name of the parameter.
        name: &'static str,
        /// The index that was given.
        index: usize,
        /// The length of what it indexes: valid indices are `0..len`.
        len: usize,
    },
    /// A caller's buffer did not have the length the call needs.
    LengthMismatch {
        /// Name of the buffer.
        name: &'static str,
        /// The length it must have.
        expected: usize,
        /// The length it had.
        got: usize,
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
    /// The spectrum is so strong at this grid and choppiness that the synthesised fields
    /// could overflow f32: the bound 2·Σ|h0|·max(1, k_max)·max(1, λ) on their magnitude
    /// exceeded `limit`.
    AmplitudeTooLarge {
        /// The bound on the fields' magnitude.
        bound: f64,
        /// The largest accepted bound.
        limit: f64,
    },
    /// The grids hold less than `min` of a sea's height variance (see
    /// [`OceanConfig::fit`](crate::OceanConfig::fit)): the simulated sea would be much
    /// smaller than the spectrum's. Fractions are of the variance, whose square root scales
    /// H_s.
    SeaDoesNotFit {
        /// Name of the parameter (`"spectrum"`).
        name: &'static str,
        /// Fraction of the sea's variance the grids would hold.
        held: f64,
        /// The least fraction accepted.
        min: f64,
        /// Fraction in waves longer than the largest tile.
        too_long: f64,
        /// Fraction in waves shorter than the finest grid cell.
        too_short: f64,
        /// The sea's significant wave height in metres.
        significant_wave_height: f64,
        /// Side of the largest tile in metres.
        largest_tile: f64,
        /// Side of the finest grid cell in metres.
        finest_cell: f64,
    },
    /// A list that must strictly decrease (the cascade lengths, largest tile first) did not.
    NotDecreasing {
        /// Name of the list.
        name: &'static str,
        /// Index of the first element not below the one before it.
        index: usize,
        /// That element.
        value: f64,
        /// The element before it.
        previous: f64,
    },
    /// What a constructor would allocate exceeds the memory limit it was given.
    MemoryLimit {
        /// Bytes the object would hold.
        bytes: usize,
        /// The limit, in bytes.
        limit: usize,
    },
    /// The system refused an allocation within the memory limit.
    OutOfMemory {
        /// Bytes that were asked for.
        bytes: usize,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::NonFinite { name } => write!(f, "parameter `{name}` is not finite"),
            Error::OutOfRange {
                name,
                value,
                min,
                max,
            } => {
                write!(
                    f,
                    "parameter `{name}` = {} is out of range: expected ",
                    Number(value)
                )?;
                write_range(f, name, min, max)
            }
            Error::InvalidSize {
                name,
                size,
                min,
                max,
            } => write!(
                f,
                "grid size `{name}` = {size} is invalid: expected an even number from {min} to {max}"
            ),
            Error::CountOutOfRange {
                name,
                count,
                min,
                max,
            } => write!(
                f,
                "`{name}` = {count} is out of range: expected {min} ≤ {name} ≤ {max}"
            ),
            Error::IndexOutOfRange { name, index, len } => write!(
                f,
                "index `{name}` = {index} is out of range: expected {name} < {len}"
            ),
            Error::LengthMismatch {
                name,
                expected,
                got,
            } => write!(
                f,
                "buffer `{name}` has length {got}: expected length {expected}"
            ),
            Error::NotApplicable { name, reason } => {
                write!(f, "parameter `{name}` does not apply: {reason}")
            }
            Error::EmptyBand { k_min, k_max } => write!(
                f,
                "wave-number band [{}, {}) rad/m is empty or holds no grid wave vector",
                Number(k_min),
                Number(k_max)
            ),
            Error::AmplitudeTooLarge { bound, limit } => write!(
                f,
                "the spectrum is too strong for this grid and choppiness: the fields could \
                 reach {} (expected at most {}, far inside f32)",
                Number(bound),
                Number(limit)
            ),
            Error::SeaDoesNotFit {
                name,
                held,
                min,
                too_long,
                too_short,
                significant_wave_height,
                largest_tile,
                finest_cell,
            } => {
                let lost = if too_long >= too_short {
                    format!(
                        "{:.0} % is in waves longer than the largest tile ({} m)",
                        100.0 * too_long,
                        Number(largest_tile)
                    )
                } else {
                    format!(
                        "{:.0} % is in waves shorter than the finest grid cell ({} m)",
                        100.0 * too_short,
                        Number(finest_cell)
                    )
                };
                write!(
                    f,
                    "`{name}` does not fit the grids: they hold {:.0} % of its height variance \
                     (H_s {:.3} m of {:.3} m; at least {:.0} % expected), {lost}; fit the \
                     lengths to the roughest sea with `OceanConfig::fitted` (or \
                     `with_fitted_lengths`)",
                    100.0 * held,
                    significant_wave_height * held.max(0.0).sqrt(),
                    significant_wave_height,
                    100.0 * min
                )
            }
            Error::NotDecreasing {
                name,
                index,
                value,
                previous,
            } => write!(
                f,
                "`{name}` must strictly decrease, the largest first: {name}[{index}] = {} is not \
                 below {name}[{}] = {}",
                Number(value),
                index - 1,
                Number(previous)
            ),
            Error::MemoryLimit { bytes, limit } => write!(
                f,
                "this would hold {} of memory, over the limit of {}",
                Bytes(bytes),
                Bytes(limit)
            ),
            Error::OutOfMemory { bytes } => {
                write!(f, "the system refused to allocate {}", Bytes(bytes))
            }
        }
    }
}

impl std::error::Error for Error {}

/// Writes `min < name ≤ max` and its one-sided forms.
fn write_range(
    f: &mut fmt::Formatter<'_>,
    name: &str,
    min: Bound<f64>,
    max: Bound<f64>,
) -> fmt::Result {
    match min {
        Bound::Included(a) => write!(f, "{} ≤ ", Number(a))?,
        Bound::Excluded(a) => write!(f, "{} < ", Number(a))?,
        Bound::Unbounded => {}
    }
    f.write_str(name)?;
    match max {
        Bound::Included(b) => write!(f, " ≤ {}", Number(b)),
        Bound::Excluded(b) => write!(f, " < {}", Number(b)),
        Bound::Unbounded if matches!(min, Bound::Unbounded) => f.write_str(" finite"),
        Bound::Unbounded => Ok(()),
    }
}

/// A number in an error message: plain for ordinary magnitudes, exponent form otherwise
/// (`1e9`, not `1000000000`).
struct Number(f64);

impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let magnitude = self.0.abs();
        if magnitude != 0.0 && magnitude.is_finite() && !(1e-3..1e6).contains(&magnitude) {
            write!(f, "{:e}", self.0)
        } else {
            write!(f, "{}", self.0)
        }
    }
}

/// A byte count in an error message, in the largest binary unit that keeps it ≥ 1.
struct Bytes(usize);

impl fmt::Display for Bytes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        const UNITS: [&str; 4] = ["KiB", "MiB", "GiB", "TiB"];
        let mut value = self.0 as f64;
        if value < 1024.0 {
            return write!(f, "{} bytes", self.0);
        }
        let mut unit = "bytes";
        for next in UNITS {
            if value < 1024.0 {
                break;
            }
            value /= 1024.0;
            unit = next;
        }
        write!(f, "{value:.1} {unit}")
    }
}

/// An f32 parameter as an f64 through its shortest decimal form: `0.1_f32` gives `0.1`, not
/// `0.10000000149011612`.
pub(crate) fn widen(value: f32) -> f64 {
    value.to_string().parse().unwrap_or(f64::from(value))
}

/// Checks that `value` is finite.
pub(crate) fn finite(name: &'static str, value: f32) -> Result<f32, Error> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::NonFinite { name })
    }
}

/// Checks that `value` is finite and lies within `min .. max`, compared in f32; the error
/// reports the value and bounds through their shortest decimal forms.
pub(crate) fn in_range(
    name: &'static str,
    value: f32,
    min: Bound<f32>,
    max: Bound<f32>,
) -> Result<f32, Error> {
    finite(name, value)?;
    if (min, max).contains(&value) {
        Ok(value)
    } else {
        Err(out_of_range(
            name,
            widen(value),
            min.map(widen),
            max.map(widen),
        ))
    }
}

/// [`in_range`] for an f64 parameter.
pub(crate) fn in_range_f64(
    name: &'static str,
    value: f64,
    min: Bound<f64>,
    max: Bound<f64>,
) -> Result<f64, Error> {
    if !value.is_finite() {
        return Err(Error::NonFinite { name });
    }
    if (min, max).contains(&value) {
        Ok(value)
    } else {
        Err(out_of_range(name, value, min, max))
    }
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn positive(name: &'static str, value: f32) -> Result<f32, Error> {
    in_range(name, value, Bound::Excluded(0.0), Bound::Unbounded)
}

/// Checks that `value` is finite and not negative.
pub(crate) fn non_negative(name: &'static str, value: f32) -> Result<f32, Error> {
    in_range(name, value, Bound::Included(0.0), Bound::Unbounded)
}

/// Checks that `value` is finite and in `[0, 1]`.
pub(crate) fn unit_interval(name: &'static str, value: f32) -> Result<f32, Error> {
    in_range(name, value, Bound::Included(0.0), Bound::Included(1.0))
}

/// Checks that `index < len`.
pub(crate) fn index(name: &'static str, index: usize, len: usize) -> Result<usize, Error> {
    if index < len {
        Ok(index)
    } else {
        Err(Error::IndexOutOfRange { name, index, len })
    }
}

/// Checks that a caller's buffer has the length the call needs.
pub(crate) fn length(name: &'static str, got: usize, expected: usize) -> Result<(), Error> {
    if got == expected {
        Ok(())
    } else {
        Err(Error::LengthMismatch {
            name,
            expected,
            got,
        })
    }
}

#[cold]
fn out_of_range(name: &'static str, value: f64, min: Bound<f64>, max: Bound<f64>) -> Error {
    Error::OutOfRange {
        name,
        value,
        min,
        max,
    }
}

/// A vector of `len` copies of `value`, or [`Error::OutOfMemory`] if the system refuses the
/// allocation (rather than aborting the process).
pub(crate) fn try_vec<T: Clone>(len: usize, value: T) -> Result<Vec<T>, Error> {
    let mut vec = Vec::new();
    vec.try_reserve_exact(len).map_err(|_| Error::OutOfMemory {
        bytes: len.saturating_mul(std::mem::size_of::<T>()),
    })?;
    vec.resize(len, value);
    Ok(vec)
}

/// An f64 rounded to f32, saturating at ±`f32::MAX` instead of becoming infinite (for finite
/// input).
pub(crate) fn saturate(value: f64) -> f32 {
    value.clamp(-f64::from(f32::MAX), f64::from(f32::MAX)) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_read_as_inequalities() {
        let error = |min, max| Error::OutOfRange {
            name: "x",
            value: -1.5,
            min,
            max,
        };
        let cases = [
            (
                error(Bound::Excluded(0.0), Bound::Unbounded),
                "parameter `x` = -1.5 is out of range: expected 0 < x",
            ),
            (
                error(Bound::Included(0.01), Bound::Included(1e7)),
                "parameter `x` = -1.5 is out of range: expected 0.01 ≤ x ≤ 1e7",
            ),
            (
                error(Bound::Unbounded, Bound::Excluded(-2.0)),
                "parameter `x` = -1.5 is out of range: expected x < -2",
            ),
        ];
        for (error, text) in cases {
            assert_eq!(error.to_string(), text);
        }
    }

    #[test]
    fn f32_values_keep_their_shortest_form() {
        let error = positive("length", -0.1).unwrap_err();
        assert!(matches!(error, Error::OutOfRange { value, .. } if value == -0.1));
    }

    #[test]
    fn byte_counts_are_readable() {
        assert_eq!(Bytes(512).to_string(), "512 bytes");
        assert_eq!(Bytes(3 << 29).to_string(), "1.5 GiB");
    }
}
