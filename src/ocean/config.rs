//! [`OceanConfig`]: the passive parameters of an ocean, its cascades' bands and their checks.

use crate::cascade::CascadeConfig;
use crate::error::{self, Error};

use super::foam::FoamConfig;

/// Fraction of a cascade's Nyquist wave number πN/L at which the next, smaller cascade takes
/// over. At ½ the larger cascade still samples every direction of its band's top with 4 grid
/// points per wavelength, and the smaller one starts N/4 of its own Δk above zero (for the
/// length ratios ≈ 4–5 used here about 14 Δk), so both resolve the band where they meet.
pub const BAND_SPLIT: f32 = 0.5;

/// Parameters of an [`OceanState`]: passive data, validated by [`OceanState::new`].
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct OceanConfig {
    /// Side L of each cascade's patch in metres, strictly decreasing. Default
    /// `[1000, 230, 51]`: non-integer ratios hide the tiling.
    pub lengths: Vec<f32>,
    /// Grid size N of every cascade (even, 4 ≤ N ≤ [`crate::MAX_SIZE`]). Default 256.
    pub size: usize,
    /// Choppiness λ ≥ 0 of every cascade (dimensionless). Default 1.
    pub choppiness: f32,
    /// Seed of the random amplitudes; cascade c uses `seed + c`. Default 0.
    pub seed: u64,
    /// Lower limit of the whole band in rad/m. Default 0.
    pub k_min: f32,
    /// Upper limit of the whole band in rad/m (may be +∞; the smallest cascade's Nyquist
    /// wave number πN/L caps it). Default +∞ (saved as `null` with the `serde` feature).
    #[cfg_attr(
        feature = "serde",
        serde(
            with = "crate::serde_impls::band_limit",
            default = "crate::serde_impls::band_limit::infinite"
        )
    )]
    pub k_max: f32,
    /// Foam injection and decay.
    pub foam: FoamConfig,
    /// Repeat period in seconds for looping (see [`CascadeConfig::repeat_period`]).
    /// Default `None`.
    pub repeat_period: Option<f32>,
    /// Update the cascades in parallel with each other, on top of the parallel rows inside
    /// each. Default `true`: on 2 cores, 3 cascades of 256² step in 2.5–2.75 ms this way
    /// against 2.6–3.5 ms one after another, and 128² and 64² grids gain or lose at most
    /// 15–20 % (`cargo bench --bench ocean`). The results are bit-identical either way.
    pub parallel_cascades: bool,
}

impl Default for OceanConfig {
    fn default() -> Self {
        OceanConfig {
            lengths: vec![1000.0, 230.0, 51.0],
            size: 256,
            choppiness: 1.0,
            seed: 0,
            k_min: 0.0,
            k_max: f32::INFINITY,
            foam: FoamConfig::default(),
            repeat_period: None,
            parallel_cascades: true,
        }
    }
}

impl OceanConfig {
    /// The wave-number band [lower, upper) of each cascade, in rad/m: adjacent bands meet at
    /// [`BAND_SPLIT`] of the larger cascade's Nyquist wave number, the first starts at
    /// `k_min` and the last ends at min(`k_max`, πN/L_last). Call [`OceanConfig::validate`]
    /// first; for an invalid config the bands may be empty.
    pub fn bands(&self) -> Vec<(f32, f32)> {
        let count = self.lengths.len();
        let nyquist = |length: f32| std::f32::consts::PI * self.size as f32 / length;
        let mut edges = Vec::with_capacity(count + 1);
        edges.push(self.k_min);
        for &length in &self.lengths[..count.saturating_sub(1)] {
            edges.push((BAND_SPLIT * nyquist(length)).clamp(self.k_min, self.k_max));
        }
        let last = self.lengths.last().copied().unwrap_or(1.0);
        edges.push(self.k_max.min(nyquist(last)).max(self.k_min));
        edges.windows(2).map(|w| (w[0], w[1])).collect()
    }

    /// Checks every field and that every cascade's band is non-empty.
    pub fn validate(&self) -> Result<(), Error> {
        if self.lengths.is_empty() || self.lengths.len() > 8 {
            return Err(error::out_of_range(
                "lengths.len()",
                self.lengths.len() as f32,
                "1 to 8 cascades",
            ));
        }
        for (index, &length) in self.lengths.iter().enumerate() {
            let probe = CascadeConfig {
                length,
                size: self.size,
                ..CascadeConfig::default()
            };
            probe.validate()?;
            if index > 0 && length >= self.lengths[index - 1] {
                return Err(error::out_of_range(
                    "lengths",
                    length,
                    "strictly decreasing lengths",
                ));
            }
        }
        error::non_negative("choppiness", self.choppiness)?;
        error::non_negative("k_min", self.k_min)?;
        if self.k_max.is_nan() {
            return Err(Error::NonFinite { name: "k_max" });
        }
        if self.k_max <= self.k_min {
            return Err(Error::EmptyBand {
                k_min: f64::from(self.k_min),
                k_max: f64::from(self.k_max),
            });
        }
        self.foam.validate()?;
        if let Some(period) = self.repeat_period {
            error::positive("repeat_period", period)?;
        }
        for (lower, upper) in self.bands() {
            if upper <= lower {
                return Err(Error::EmptyBand {
                    k_min: f64::from(lower),
                    k_max: f64::from(upper),
                });
            }
        }
        Ok(())
    }

    /// The config of cascade `index` (its length, band and seed).
    pub(super) fn cascade_config(&self, index: usize, (k_min, k_max): (f32, f32)) -> CascadeConfig {
        CascadeConfig {
            size: self.size,
            length: self.lengths[index],
            k_min,
            k_max,
            choppiness: self.choppiness,
            seed: self.seed.wrapping_add(index as u64),
            repeat_period: self.repeat_period,
        }
    }
}
