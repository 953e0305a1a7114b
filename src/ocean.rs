//! What a game holds: several cascades of one spectrum on disjoint wave-number bands, the
//! time, and the foam.

use rayon::prelude::*;

use crate::cascade::{check_time, Cascade, CascadeConfig};
use crate::error::{self, Error};
use crate::spectrum::Spectrum;

/// Largest accepted time step of [`OceanState::step`], in seconds.
pub const MAX_STEP: f64 = 3600.0;

/// Fraction of a cascade's Nyquist wave number πN/L at which the next, smaller cascade takes
/// over. At ½ the larger cascade still samples every direction of its band's top with 4 grid
/// points per wavelength, and the smaller one starts N/4 of its own Δk above zero (for the
/// length ratios ≈ 4–5 used here about 14 Δk), so both resolve the band where they meet.
pub const BAND_SPLIT: f32 = 0.5;

/// How foam is injected and decays (per cascade, from that cascade's Jacobian J).
///
/// Foam coverage f ∈ [0, 1] obeys df/dt = s·(1 − f) − f/τ with injection rate
/// s = `injection`·max(0, `bias` − J); over a step the exact solution for J held at its new
/// value is used, so the result barely depends on the frame rate and never leaves [0, 1].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FoamConfig {
    /// Jacobian threshold (dimensionless): foam is injected where J < `bias`. Default 0.8
    /// (a look control: about 1 % of a fresh breeze's grid points lie below it).
    pub bias: f32,
    /// Injection rate per unit of (bias − J), in 1/s. Default 8.
    pub injection: f32,
    /// Decay time constant τ in seconds. Default 2.5.
    pub decay: f32,
}

impl Default for FoamConfig {
    fn default() -> Self {
        FoamConfig {
            bias: 0.8,
            injection: 8.0,
            decay: 2.5,
        }
    }
}

impl FoamConfig {
    /// Checks every field: finite `bias`, `injection` ≥ 0, `decay` > 0.
    pub fn validate(&self) -> Result<(), Error> {
        error::finite("foam.bias", self.bias)?;
        error::non_negative("foam.injection", self.injection)?;
        error::positive("foam.decay", self.decay)?;
        Ok(())
    }
}

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
            with = "crate::serde_support::band_limit",
            default = "crate::serde_support::band_limit::infinite"
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
    fn cascade_config(&self, index: usize, (k_min, k_max): (f32, f32)) -> CascadeConfig {
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

/// An ocean: cascades of one spectrum over disjoint wave-number bands, the time, and foam.
///
/// ```
/// use ocean_fft::{OceanConfig, OceanState, Spectrum};
/// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
/// let config = OceanConfig { size: 64, ..OceanConfig::default() };
/// let mut ocean = OceanState::new(spectrum, config)?;
/// ocean.step(1.0 / 60.0)?;                       // s
/// let s = ocean.sample(12.0, -40.0)?;            // world x, z in m
/// let y = ocean.height_at(12.0, -40.0)?;         // water height at that point, m
/// assert!(s.height.is_finite() && y.is_finite());
/// # Ok::<(), ocean_fft::Error>(())
/// ```
#[derive(Debug)]
pub struct OceanState {
    pub(crate) spectrum: Spectrum,
    pub(crate) config: OceanConfig,
    pub(crate) cascades: Vec<Cascade>,
    pub(crate) foam: Vec<Vec<f32>>,
    pub(crate) time: f64,
}

impl OceanState {
    /// Builds the cascades (h0 of each drawn once) on the bands of
    /// [`OceanConfig::bands`], at t = 0 with no foam.
    pub fn new(spectrum: Spectrum, config: OceanConfig) -> Result<OceanState, Error> {
        config.validate()?;
        let bands = config.bands();
        let cascades = bands
            .iter()
            .enumerate()
            .map(|(index, &band)| Cascade::new(&spectrum, config.cascade_config(index, band)))
            .collect::<Result<Vec<_>, _>>()?;
        let foam = cascades
            .iter()
            .map(|c| vec![0.0; c.size() * c.size()])
            .collect();
        Ok(OceanState {
            spectrum,
            config,
            cascades,
            foam,
            time: 0.0,
        })
    }

    /// Advances the time by `dt` seconds (0 ≤ dt ≤ [`MAX_STEP`]), updates every cascade and
    /// the foam. Allocates nothing.
    pub fn step(&mut self, dt: f64) -> Result<(), Error> {
        if !dt.is_finite() {
            return Err(Error::NonFinite { name: "dt" });
        }
        if !(0.0..=MAX_STEP).contains(&dt) {
            return Err(Error::OutOfRange {
                name: "dt",
                value: dt,
                expected: "in [0, 3600] s",
            });
        }
        let t = self.time + dt;
        // One job handed to rayon per step (see `Cascade::update`).
        rayon::scope(|_| {
            self.update_cascades(t)?;
            self.time = t;
            self.advance_foam(dt as f32);
            Ok(())
        })
    }

    /// Jumps to time `t` in seconds (|t| ≤ [`crate::MAX_TIME`]) and updates every cascade.
    /// The foam has no history across a jump: it is cleared.
    pub fn set_time(&mut self, t: f64) -> Result<(), Error> {
        self.update_cascades(t)?;
        self.time = t;
        for foam in &mut self.foam {
            foam.fill(0.0);
        }
        Ok(())
    }

    fn update_cascades(&mut self, t: f64) -> Result<(), Error> {
        // Validate once up front so that either every cascade is updated or none is.
        check_time(t)?;
        if self.config.parallel_cascades {
            self.cascades
                .par_iter_mut()
                .try_for_each(|cascade| cascade.update(t))
        } else {
            self.cascades
                .iter_mut()
                .try_for_each(|cascade| cascade.update(t))
        }
    }

    fn advance_foam(&mut self, dt: f32) {
        let FoamConfig {
            bias,
            injection,
            decay,
        } = self.config.foam;
        let inv_tau = 1.0 / decay;
        for (cascade, foam) in self.cascades.iter().zip(&mut self.foam) {
            let n = cascade.size();
            foam.par_chunks_mut(n)
                .zip(cascade.jacobian().par_chunks(n))
                .for_each(|(foam_row, jacobian_row)| {
                    for (f, &j) in foam_row.iter_mut().zip(jacobian_row) {
                        *f = foam_step(*f, j, dt, bias, injection, inv_tau);
                    }
                });
        }
    }

    /// Simulated time in seconds.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The spectrum the cascades were drawn from.
    pub fn spectrum(&self) -> &Spectrum {
        &self.spectrum
    }

    /// The configuration this ocean was built with.
    pub fn config(&self) -> &OceanConfig {
        &self.config
    }

    /// The cascades, largest first.
    pub fn cascades(&self) -> &[Cascade] {
        &self.cascades
    }

    /// Foam coverage in [0, 1] of cascade `index` on that cascade's grid (index j·N + i),
    /// or `None` for an index past the last cascade.
    pub fn foam(&self, index: usize) -> Option<&[f32]> {
        self.foam.get(index).map(Vec::as_slice)
    }

    /// Sets the choppiness λ ≥ 0 of every cascade (takes effect at the next step).
    pub fn set_choppiness(&mut self, choppiness: f32) -> Result<(), Error> {
        let lambda = error::non_negative("choppiness", choppiness)?;
        // Check every cascade before changing any, so an error leaves them all as they were.
        for cascade in &self.cascades {
            cascade.check_choppiness(lambda)?;
        }
        for cascade in &mut self.cascades {
            cascade.set_choppiness(lambda)?;
        }
        self.config.choppiness = lambda;
        Ok(())
    }

    /// Expected variance of the summed height in m²: the sum over cascades of
    /// [`Cascade::expected_variance`]; 4√ of it is the expected H_s of the simulated sea.
    pub fn expected_variance(&self) -> f64 {
        self.cascades.iter().map(Cascade::expected_variance).sum()
    }
}

/// One exact step of df/dt = s(1 − f) − f/τ with s = injection·max(0, bias − J) held
/// constant: f relaxes toward s/(s + 1/τ) at rate s + 1/τ.
#[inline]
pub(crate) fn foam_step(
    f: f32,
    jacobian: f32,
    dt: f32,
    bias: f32,
    injection: f32,
    inv_tau: f32,
) -> f32 {
    let source = injection * (bias - jacobian).max(0.0);
    let rate = source + inv_tau;
    let equilibrium = source / rate;
    let next = equilibrium + (f - equilibrium) * (-rate * dt).exp();
    next.clamp(0.0, 1.0)
}
