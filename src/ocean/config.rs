//! [`OceanConfig`]: the passive parameters of an ocean, its cascades' bands and their checks.

use std::ops::Bound::{Excluded, Included};

use crate::cascade::{check_band, CascadeConfig};
use crate::error::{self, Error};
use crate::foam::FoamConfig;
use crate::math::determinism::Determinism;
use crate::math::grid;
use crate::query::config::{Interpolation, QueryConfig};
use crate::wake::WakeConfig;

/// Parameters of an [`OceanState`](crate::OceanState): passive data, validated by
/// [`OceanState::new`](crate::OceanState::new).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct OceanConfig {
    /// Side L of each cascade's patch in metres, strictly decreasing, each from
    /// [`CascadeConfig::MIN_LENGTH`] to [`CascadeConfig::MAX_LENGTH`]; 1 to
    /// [`MAX_CASCADES`](Self::MAX_CASCADES) cascades (default: `[1000.0, 230.0, 51.0]`:
    /// non-integer ratios hide the tiling).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::lengths")
    )]
    pub lengths: Vec<f32>,
    /// Grid size N of every cascade: even, [`CascadeConfig::MIN_SIZE`] ≤ N ≤
    /// [`CascadeConfig::MAX_SIZE`] (default: `256`).
    pub size: usize,
    /// Choppiness λ ≥ 0 of every cascade, dimensionless (default: `1.0`).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::choppiness")
    )]
    pub choppiness: f32,
    /// Seed of the random amplitudes; cascade c uses `seed + c` (default: `0`).
    pub seed: u64,
    /// Lower limit of the whole band in rad/m, ≥ 0 (default: `0.0`).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::k_min")
    )]
    pub k_min: f32,
    /// Upper limit of the whole band in rad/m, above `k_min` (may be +∞; the smallest
    /// cascade's Nyquist wave number πN/L caps it; default: `f32::INFINITY`, saved as `null`
    /// with the `serde` feature).
    #[cfg_attr(
        feature = "serde",
        serde(
            with = "crate::serde_impls::band_limit",
            default = "crate::serde_impls::band_limit::infinite"
        )
    )]
    pub k_max: f32,
    /// Where adjacent cascades' bands meet, as a fraction of the larger cascade's Nyquist wave
    /// number πN/L, in (0, 1] (default: [`DEFAULT_BAND_SPLIT`](Self::DEFAULT_BAND_SPLIT),
    /// `0.5`).
    ///
    /// At ½ the larger cascade still samples every direction of its band's top with 4 grid
    /// points per wavelength, and the smaller one starts N/4 of its own Δk above zero (for
    /// length ratios of 4–5, about 14 Δk), so both resolve the band where they meet.
    #[cfg_attr(
        feature = "serde",
        serde(
            default = "default_band_split",
            serialize_with = "crate::serde_impls::finite::band_split"
        )
    )]
    pub band_split: f32,
    /// Foam: whitecap coverage, lifetimes, drift and streaks.
    pub foam: FoamConfig,
    /// Repeat period in seconds for looping (see [`CascadeConfig::repeat_period`])
    /// (default: `None`).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::repeat_period")
    )]
    pub repeat_period: Option<f32>,
    /// Update the cascades in parallel with each other, on top of the parallel rows inside
    /// each (default: `true`, faster for three 256² cascades on 2 cores in the
    /// `ocean_parallel_cascades` bench). The results are bit-identical either way.
    pub parallel_cascades: bool,
    /// How [`Water::height_at`](crate::Water::height_at) and the queries built on
    /// it invert the horizontal displacement.
    #[cfg_attr(feature = "serde", serde(default))]
    pub query: QueryConfig,
    /// Most bytes the whole ocean may hold (every cascade and the foam);
    /// [`OceanState::new`](crate::OceanState::new) refuses a config whose
    /// [`memory_bytes`](Self::memory_bytes) exceed it (default:
    /// [`CascadeConfig::DEFAULT_MEMORY_LIMIT`], 4 GiB).
    #[cfg_attr(
        feature = "serde",
        serde(default = "crate::cascade::default_memory_limit")
    )]
    pub memory_limit: usize,
    /// How far the same config gives the same bits, for every cascade, the foam and the
    /// world queries: [`Determinism::SameMachine`] (the default, fastest) or
    /// [`Determinism::CrossPlatform`] (the same bits on every CPU and operating system, for
    /// lockstep or server-authoritative networking and replays shared between machines;
    /// slower, see `docs/guide/networking.md`). The two modes draw different,
    /// equally calibrated waves. Configs saved without it read back with the default.
    #[cfg_attr(feature = "serde", serde(default))]
    pub determinism: Determinism,
    /// Second-order bound waves (default: `false`): crests higher and troughs shallower, as
    /// at sea. The largest cascade's waves below half its Nyquist wave number (the energetic
    /// peak of every preset) get the group-scale bound waves of second-order theory that the
    /// horizontal displacement lacks (Longuet-Higgins 1963), added to the height and its
    /// slopes, and so to the normals, the texels and every query; the horizontal
    /// displacement, the Jacobian and the foam are unchanged. It costs the largest cascade
    /// three transforms on a grid of about 3N/4 per update (see `docs/theory.md` and
    /// `docs/performance.md`). Off, nothing changes. Configs saved without it read back
    /// with it off.
    #[cfg_attr(feature = "serde", serde(default))]
    pub second_order: bool,
    /// The wake layer (default: `None`, and then nothing of the ocean changes, its bits and
    /// its cost included): a window of linear waves in which hulls
    /// ([`OceanState::set_hulls`](crate::OceanState::set_hulls)) make Kelvin wakes that
    /// every world query includes (see [`WakeConfig`]). Configs saved without it read back
    /// without wakes.
    #[cfg_attr(feature = "serde", serde(default))]
    pub wakes: Option<WakeConfig>,
}

/// The value of a missing `band_split` (with the `serde` feature).
#[cfg(feature = "serde")]
fn default_band_split() -> f32 {
    OceanConfig::DEFAULT_BAND_SPLIT
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
            band_split: Self::DEFAULT_BAND_SPLIT,
            foam: FoamConfig::default(),
            repeat_period: None,
            parallel_cascades: true,
            query: QueryConfig::default(),
            memory_limit: CascadeConfig::DEFAULT_MEMORY_LIMIT,
            determinism: Determinism::SameMachine,
            second_order: false,
            wakes: None,
        }
    }
}

impl OceanConfig {
    /// Most cascades.
    pub const MAX_CASCADES: usize = crate::cascade::MAX_CASCADES;

    /// Default [`band_split`](Self::band_split).
    pub const DEFAULT_BAND_SPLIT: f32 = 0.5;

    /// The wave-number band `(lower, upper)` of each cascade, in rad/m, largest cascade first:
    /// adjacent bands meet at [`band_split`](Self::band_split) of the larger cascade's
    /// Nyquist wave number πN/L, the first starts at `k_min` and the last ends at
    /// min(`k_max`, πN/L_last).
    ///
    /// # Errors
    /// Those of [`OceanConfig::validate`]: the bands of an invalid config are not computed.
    pub fn bands(&self) -> Result<Vec<(f32, f32)>, Error> {
        self.validate()?;
        Ok(self.bands_unchecked().to_vec())
    }

    /// The bands of a config whose fields (not yet its bands) have been checked.
    pub(super) fn bands_unchecked(&self) -> Bands {
        // Held on the stack: a live ocean's checks (`set_spectrum`, `set_choppiness`) read
        // them and allocate nothing.
        let count = self.lengths.len().min(Self::MAX_CASCADES);
        let nyquist = |length: f32| std::f32::consts::PI * self.size as f32 / length;
        let mut edges = [self.k_min; Self::MAX_CASCADES + 1];
        for (edge, &length) in edges[1..count].iter_mut().zip(&self.lengths) {
            *edge = (self.band_split * nyquist(length)).clamp(self.k_min, self.k_max);
        }
        edges[count] = self
            .k_max
            .min(nyquist(self.lengths[count - 1]))
            .max(self.k_min);
        let mut bands = [(0.0, 0.0); Self::MAX_CASCADES];
        for (band, edge) in bands.iter_mut().zip(edges.windows(2)).take(count) {
            *band = (edge[0], edge[1]);
        }
        Bands { bands, count }
    }

    /// Checks every field, that every cascade's band is non-empty, and the memory the ocean
    /// would hold.
    ///
    /// # Errors
    /// [`Error::CountOutOfRange`] for the number of `lengths`; those of
    /// [`CascadeConfig::validate`] for `size`, each length ([`Error::NotDecreasing`] unless
    /// the lengths strictly decrease), `choppiness`, `k_min`, `k_max` and `repeat_period`;
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for `band_split`; those of
    /// [`FoamConfig::validate`], [`QueryConfig::validate`] and [`WakeConfig::validate`];
    /// [`Error::EmptyBand`] if a
    /// cascade's band is empty; [`Error::MemoryLimit`] if the ocean would hold more than
    /// `memory_limit` bytes.
    pub fn validate(&self) -> Result<(), Error> {
        if !(1..=Self::MAX_CASCADES).contains(&self.lengths.len()) {
            return Err(Error::CountOutOfRange {
                name: "lengths.len()",
                count: self.lengths.len(),
                min: 1,
                max: Self::MAX_CASCADES,
            });
        }
        grid::check_size("size", self.size)?;
        for (index, &length) in self.lengths.iter().enumerate() {
            // Within the cascades' limits, and below the length before.
            error::in_range(
                "lengths",
                length,
                Included(CascadeConfig::MIN_LENGTH),
                Included(CascadeConfig::MAX_LENGTH),
            )?;
            if index > 0 && length >= self.lengths[index - 1] {
                return Err(Error::NotDecreasing {
                    name: "lengths",
                    index,
                    value: error::widen(length),
                    previous: error::widen(self.lengths[index - 1]),
                });
            }
        }
        error::non_negative("choppiness", self.choppiness)?;
        check_band(self.k_min, self.k_max)?;
        error::in_range("band_split", self.band_split, Excluded(0.0), Included(1.0))?;
        self.foam.validate()?;
        if let Some(period) = self.repeat_period {
            error::in_range(
                "repeat_period",
                period,
                Included(CascadeConfig::MIN_REPEAT_PERIOD),
                Included(CascadeConfig::MAX_REPEAT_PERIOD),
            )?;
        }
        self.query.validate()?;
        if let Some(wakes) = &self.wakes {
            wakes.validate()?;
        }
        for &(lower, upper) in self.bands_unchecked().iter() {
            if upper <= lower {
                return Err(Error::EmptyBand {
                    k_min: f64::from(lower),
                    k_max: f64::from(upper),
                });
            }
        }
        grid::check_memory(self.memory_bytes(), self.memory_limit)
    }

    /// Bytes the ocean holds: every cascade ([`CascadeConfig::memory_bytes`]), the foam on
    /// cascade 0's grid (about 40·N² and its transform's scratch) and, with
    /// [`Interpolation::CubicBSpline`], the spline coefficients of the world queries (about
    /// 24·N² per cascade; a [`Surface`](crate::Surface) handle kept across steps adds a second
    /// frame of them and copies of the queried fields, not counted here). Any config gives an
    /// answer, even one [`validate`](Self::validate) refuses.
    pub fn memory_bytes(&self) -> usize {
        let cascade = crate::cascade::memory_bytes(self.size, self.determinism);
        let foam = crate::foam::memory_bytes(self.size, self.determinism);
        let spline = match self.query.interpolation {
            Interpolation::CubicBSpline => crate::query::spline::Tiles::memory_bytes(self.size),
            Interpolation::Bilinear => 0,
        };
        let second = if self.second_order {
            crate::cascade::second_order_memory_bytes(self.size)
        } else {
            0
        };
        cascade
            .saturating_add(spline)
            .saturating_mul(self.lengths.len())
            .saturating_add(foam)
            .saturating_add(second)
            .saturating_add(self.wakes.as_ref().map_or(0, WakeConfig::memory_bytes))
    }

    /// The config of cascade `index` (its length, band, seed and determinism mode).
    pub(super) fn cascade_config(&self, index: usize, (k_min, k_max): (f32, f32)) -> CascadeConfig {
        CascadeConfig {
            size: self.size,
            length: self.lengths[index],
            k_min,
            k_max,
            choppiness: self.choppiness,
            seed: self.seed.wrapping_add(index as u64),
            repeat_period: self.repeat_period,
            memory_limit: self.memory_limit,
            determinism: self.determinism,
        }
    }
}

/// The wave-number bands of a config's cascades, `(lower, upper)` in rad/m, largest cascade
/// first (see [`OceanConfig::bands`]), on the stack.
#[derive(Debug, Clone, Copy)]
pub(super) struct Bands {
    bands: [(f32, f32); OceanConfig::MAX_CASCADES],
    count: usize,
}

impl std::ops::Deref for Bands {
    type Target = [(f32, f32)];

    fn deref(&self) -> &[(f32, f32)] {
        &self.bands[..self.count]
    }
}
