//! [`CascadeConfig`]: the passive parameters of one cascade and their checks.

use std::ops::Bound::Included;

use crate::error::{self, Error};
use crate::math::determinism::Determinism;
use crate::math::grid;

/// Parameters of one [`Cascade`](crate::Cascade): passive data, validated by [`Cascade::new`](crate::Cascade::new).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CascadeConfig {
    /// Grid size N (samples per side): even, [`MIN_SIZE`](Self::MIN_SIZE) ≤ N ≤
    /// [`MAX_SIZE`](Self::MAX_SIZE); powers of two are fastest (default: `256`).
    pub size: usize,
    /// Side L of the square patch in metres (Δk = 2π/L), from
    /// [`MIN_LENGTH`](Self::MIN_LENGTH) to [`MAX_LENGTH`](Self::MAX_LENGTH) (default: `1000.0`).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::length")
    )]
    pub length: f32,
    /// Lower band limit in rad/m, ≥ 0: wave vectors with |k| < `k_min` are left out
    /// (default: `0.0`).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::k_min")
    )]
    pub k_min: f32,
    /// Upper band limit in rad/m, above `k_min`: wave vectors with |k| ≥ `k_max` are left out
    /// (may be +∞; default: `f32::INFINITY`).
    #[cfg_attr(
        feature = "serde",
        serde(
            with = "crate::serde_impls::band_limit",
            default = "crate::serde_impls::band_limit::infinite"
        )
    )]
    pub k_max: f32,
    /// Choppiness λ ≥ 0 (dimensionless): grid points move by λ·D. 1 gives the Gerstner
    /// profile for a single wave (default: `1.0`).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::choppiness")
    )]
    pub choppiness: f32,
    /// Seed of the random amplitudes; the same seed and L give the same waves at every N
    /// (default: `0`).
    pub seed: u64,
    /// Repeat period T in seconds, from [`MIN_REPEAT_PERIOD`](Self::MIN_REPEAT_PERIOD) to
    /// [`MAX_REPEAT_PERIOD`](Self::MAX_REPEAT_PERIOD): when set, every ω becomes the nearest
    /// multiple of 2π/T and at least 2π/T, so the fields at t and t + T are equal and no wave
    /// stands still (for looping bakes; see [`Cascade::loop_error`](crate::Cascade::loop_error))
    /// (default: `None`).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::repeat_period")
    )]
    pub repeat_period: Option<f32>,
    /// Most bytes the cascade may hold; [`Cascade::new`](crate::Cascade::new) refuses a
    /// config whose [`memory_bytes`](Self::memory_bytes) exceed it (default:
    /// [`DEFAULT_MEMORY_LIMIT`](Self::DEFAULT_MEMORY_LIMIT), 4 GiB).
    #[cfg_attr(feature = "serde", serde(default = "default_memory_limit"))]
    pub memory_limit: usize,
    /// How far the same config gives the same bits: [`Determinism::SameMachine`] (the
    /// default, fastest) or [`Determinism::CrossPlatform`] (the same bits on every CPU and
    /// operating system; slower). The two modes draw different (equally calibrated) waves.
    /// Configs saved without it read back with the default.
    #[cfg_attr(feature = "serde", serde(default))]
    pub determinism: Determinism,
}

/// The value of a missing `memory_limit` (with the `serde` feature).
#[cfg(feature = "serde")]
pub(crate) fn default_memory_limit() -> usize {
    CascadeConfig::DEFAULT_MEMORY_LIMIT
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
            memory_limit: Self::DEFAULT_MEMORY_LIMIT,
            determinism: Determinism::SameMachine,
        }
    }
}

impl CascadeConfig {
    /// Smallest grid size N.
    pub const MIN_SIZE: usize = grid::MIN_SIZE;
    /// Largest grid size N (a cascade of 4096² holds about 1.5 GiB).
    pub const MAX_SIZE: usize = grid::MAX_SIZE;
    /// Smallest patch side L, in metres.
    pub const MIN_LENGTH: f32 = 1e-2;
    /// Largest patch side L, in metres.
    pub const MAX_LENGTH: f32 = 1e7;
    /// Shortest repeat period T, in seconds.
    pub const MIN_REPEAT_PERIOD: f32 = 1e-2;
    /// Longest repeat period T, in seconds (11.6 days).
    pub const MAX_REPEAT_PERIOD: f32 = 1e6;
    /// Default memory limit, in bytes: 4 GiB (the whole address space on 32-bit targets).
    pub const DEFAULT_MEMORY_LIMIT: usize = grid::DEFAULT_MEMORY_LIMIT;

    /// Checks every field; the error names the first bad one.
    ///
    /// # Errors
    /// [`Error::InvalidSize`] for `size`; [`Error::NonFinite`] or [`Error::OutOfRange`] for
    /// `length`, `k_min`, `choppiness` or `repeat_period` outside the ranges their docs
    /// give, or a NaN `k_max`; [`Error::EmptyBand`] unless `k_max` > `k_min`;
    /// [`Error::MemoryLimit`] if the cascade would hold more than `memory_limit` bytes.
    pub fn validate(&self) -> Result<(), Error> {
        grid::check_size("size", self.size)?;
        error::in_range(
            "length",
            self.length,
            Included(Self::MIN_LENGTH),
            Included(Self::MAX_LENGTH),
        )?;
        check_band(self.k_min, self.k_max)?;
        error::non_negative("choppiness", self.choppiness)?;
        if let Some(period) = self.repeat_period {
            error::in_range(
                "repeat_period",
                period,
                Included(Self::MIN_REPEAT_PERIOD),
                Included(Self::MAX_REPEAT_PERIOD),
            )?;
        }
        grid::check_memory(self.memory_bytes(), self.memory_limit)
    }

    /// Bytes a cascade of this size holds (buffers, tables and FFT scratch; the FFT plans'
    /// own small twiddle tables are not counted): about 123·N² up to N = 512 (N = `size`),
    /// less above as the second pass keeps only 32 blocks of 16 rows (106·N² at 1024²,
    /// 94·N² at 4096²). Any size gives an answer, even one [`validate`](Self::validate)
    /// refuses.
    pub fn memory_bytes(&self) -> usize {
        super::memory_bytes(self.size, self.determinism)
    }
}

/// Checks a band `[k_min, k_max)` in rad/m: `k_min` finite and ≥ 0, `k_max` not NaN and
/// above `k_min` (+∞ allowed).
pub(crate) fn check_band(k_min: f32, k_max: f32) -> Result<(), Error> {
    error::non_negative("k_min", k_min)?;
    if k_max.is_nan() {
        return Err(Error::NonFinite { name: "k_max" });
    }
    if k_max <= k_min {
        return Err(Error::EmptyBand {
            k_min: f64::from(k_min),
            k_max: f64::from(k_max),
        });
    }
    Ok(())
}
