//! [`CascadeConfig`]: the passive parameters of one cascade and their checks.

use crate::error::{self, Error};
use crate::grid::check_size;

/// Smallest and largest accepted patch side, in metres.
const LENGTH_RANGE: (f32, f32) = (1e-2, 1e7);

/// Parameters of one [`Cascade`]: passive data, validated by [`Cascade::new`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CascadeConfig {
    /// Grid size N (samples per side): even, 4 ≤ N ≤ [`MAX_SIZE`]; powers of two are fastest.
    /// Default 256.
    pub size: usize,
    /// Side L of the square patch, in metres (Δk = 2π/L). Default 1000 m.
    pub length: f32,
    /// Lower band limit in rad/m: wave vectors with |k| < `k_min` are left out. Default 0.
    pub k_min: f32,
    /// Upper band limit in rad/m: wave vectors with |k| ≥ `k_max` are left out (may be
    /// +∞). Default +∞.
    #[cfg_attr(
        feature = "serde",
        serde(
            with = "crate::serde_impls::band_limit",
            default = "crate::serde_impls::band_limit::infinite"
        )
    )]
    pub k_max: f32,
    /// Choppiness λ ≥ 0 (dimensionless): grid points move by λ·D. 1 gives the Gerstner
    /// profile for a single wave. Default 1.
    pub choppiness: f32,
    /// Seed of the random amplitudes; the same seed and L give the same waves at every N.
    /// Default 0.
    pub seed: u64,
    /// Repeat period T in seconds: when set, every ω is rounded down to a multiple of 2π/T,
    /// so the fields at t and t + T are equal (for looping bakes). Default `None`.
    pub repeat_period: Option<f32>,
}

impl Default for CascadeConfig {
    fn default() -> Self {
        CascadeConfig {
            size: 256,
            length: 1000.0,
            k_min: 0.0,
            k_max: f32::INFINITY,
            choppiness: 1.0,
            seed: 0,
            repeat_period: None,
        }
    }
}

impl CascadeConfig {
    /// Checks every field; the error names the first bad one.
    pub fn validate(&self) -> Result<(), Error> {
        check_size(self.size)?;
        let length = error::positive("length", self.length)?;
        if length < LENGTH_RANGE.0 || length > LENGTH_RANGE.1 {
            return Err(error::out_of_range("length", length, "in [0.01, 1e7] m"));
        }
        let k_min = error::non_negative("k_min", self.k_min)?;
        if self.k_max.is_nan() {
            return Err(Error::NonFinite { name: "k_max" });
        }
        if self.k_max <= k_min {
            return Err(Error::EmptyBand {
                k_min: f64::from(k_min),
                k_max: f64::from(self.k_max),
            });
        }
        error::non_negative("choppiness", self.choppiness)?;
        if let Some(period) = self.repeat_period {
            error::positive("repeat_period", period)?;
        }
        Ok(())
    }
}
