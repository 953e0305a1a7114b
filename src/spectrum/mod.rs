//! The first stage of the data flow: the directional wave spectrum S(k) built from the wind,
//! fetch and depth, with its dispersion relation ω(k) ([`dispersion`]): what a
//! [`Cascade`](crate::cascade::Cascade) turns into waves.

mod density;
pub(crate) mod dispersion;
mod elfouhaily;
mod omega;
mod params;
#[cfg(feature = "serde")]
mod serde_data;
mod setters;
mod slope;
mod spreading;
mod variance;

use std::f64::consts::PI;
use std::ops::Bound::{Excluded, Included};

use crate::error::{self, Error};
use crate::math::determinism::{Libm, Math, Std};
use crate::spectrum::dispersion::Dispersion;

pub use params::{SpectrumKind, SpectrumParams};
pub use slope::SlopeVariance;
pub use spreading::Spreading;

pub(crate) use density::Radial;
use omega::PIERSON_MOSKOWITZ_ALPHA;
pub(crate) use omega::{G, PIERSON_MOSKOWITZ_PEAK};
pub(crate) use spreading::SpreadingParams;

/// How the shallow-water depth factor Φ(ω, h) of the TMA spectrum is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum DepthFactor {
    /// No depth factor: Φ = 1 (JONSWAP, Pierson–Moskowitz and Phillips by default).
    #[default]
    None,
    /// Kitaigorodskii, Krasitskii & Zaslavskii's (1975) exact factor
    /// Φ = tanh²(kh) / (1 + 2kh / sinh(2kh)), with k solved from ω² = g k tanh(kh)
    /// (the TMA default; Bouws et al. 1985).
    Kitaigorodskii,
    /// Thompson & Vincent's (1983) piecewise approximation in ω_h = ω√(h/g)
    /// (within 5 % of the exact factor; Hughes 1984).
    ThompsonVincent,
}

/// The model behind S(ω).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Model {
    /// JONSWAP shape (Pierson–Moskowitz when γ = 1).
    Jonswap {
        alpha: f32,
        peak_omega: f32,
        gamma: f32,
    },
    /// Tessendorf's Phillips spectrum, defined on k.
    Phillips { amplitude: f32 },
    /// Elfouhaily et al.'s (1997) unified spectrum, defined on k, with inverse wave age
    /// Ω = U10/c_p.
    Elfouhaily { inverse_wave_age: f32 },
}

/// A directional wave spectrum S(k) = S(ω) · D(ω, θ) · (dω/dk)/k · F(k), in m⁴.
///
/// Plain data, valid from construction on: every constructor and `with_*` setter checks its
/// numbers and returns [`Error`] for bad ones, so evaluation is infallible and NaN-free.
///
/// ```
/// # use ocean_fft::{Spectrum, Spreading};
/// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?   // U10 [m/s], fetch [m]
///     .with_wind_direction(0.3)?                       // rad, toward which the wind blows
///     .with_spreading(Spreading::DonelanBanner)?;
/// let hs = spectrum.significant_wave_height();         // m
/// assert!(hs > 1.0 && hs < 3.0);
/// # Ok::<(), ocean_fft::Error>(())
/// ```
///
/// The default spreading is [`Spreading::DonelanBanner`] for the oceanographic spectra,
/// `Spreading::Cosine { exponent: 2.0, upwind: 1.0 }` (Tessendorf's |k̂·ŵ|²) for Phillips
/// and [`Spreading::Elfouhaily`] for [`Spectrum::elfouhaily`].
///
/// With the `serde` feature a spectrum serialises as its stored parameters (the model's α,
/// ω_p and γ, amplitude or inverse wave age, the wind, fetch, spreading, swell, blend, short-wave length,
/// dispersion and depth factor), and deserialising re-runs the checks of the constructors and
/// setters on every one of them: invalid data gives a deserialisation error naming the
/// parameter, never an invalid spectrum.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(
        try_from = "crate::spectrum::serde_data::SpectrumData",
        into = "crate::spectrum::serde_data::SpectrumData"
    )
)]
pub struct Spectrum {
    pub(crate) model: Model,
    pub(crate) wind_speed: f32,
    pub(crate) fetch: Option<f32>,
    pub(crate) wind_direction: f32,
    pub(crate) spreading: Spreading,
    pub(crate) swell: f32,
    pub(crate) spread_blend: f32,
    pub(crate) short_wave_length: f32,
    pub(crate) dispersion: Dispersion,
    pub(crate) depth_factor: DepthFactor,
}

impl Spectrum {
    /// Dimensionless fetch gF/U² at which the JONSWAP peak 22 (g²/(UF))^(1/3) reaches the
    /// Pierson–Moskowitz peak 0.877 g/U of a fully developed sea: (22/0.877)³ ≈ 15 786.
    /// [`Spectrum::jonswap`] caps the fetch there.
    pub const FULLY_DEVELOPED_FETCH: f32 = 15_786.0;

    /// Default JONSWAP peak enhancement γ (Hasselmann et al. 1973).
    pub const DEFAULT_GAMMA: f32 = 3.3;

    /// Largest accepted wind speed, in m/s: above any wind measured at sea, and low enough
    /// that the derived spectra stay well inside f32.
    pub const MAX_WIND_SPEED: f32 = 200.0;

    fn with_model(model: Model, wind_speed: f32, fetch: Option<f32>) -> Self {
        let spreading = match model {
            Model::Jonswap { .. } => Spreading::DonelanBanner,
            Model::Phillips { .. } => Spreading::Cosine {
                exponent: 2.0,
                upwind: 1.0,
            },
            Model::Elfouhaily { .. } => Spreading::Elfouhaily,
        };
        Spectrum {
            model,
            wind_speed,
            fetch,
            wind_direction: 0.0,
            spreading,
            swell: 0.0,
            spread_blend: 1.0,
            short_wave_length: 0.0,
            dispersion: Dispersion::Deep,
            depth_factor: DepthFactor::None,
        }
    }

    /// JONSWAP spectrum of a fetch-limited sea (Hasselmann et al. 1973) from the wind speed U
    /// at 10 m in m/s and the fetch F in metres, with γ = 3.3, deep water:
    ///
    /// ```text
    /// α = 0.076 (U² / (F g))^0.22,   ω_p = 22 (g² / (U F))^(1/3)
    /// ```
    ///
    /// A fetch-limited sea cannot outgrow a fully developed one, so the dimensionless fetch
    /// gF/U² is capped at [`FULLY_DEVELOPED_FETCH`](Self::FULLY_DEVELOPED_FETCH), where this ω_p reaches the
    /// Pierson–Moskowitz peak 0.877 g/U (α is then 0.0091): beyond about 16 000 U²/g metres
    /// (160 km at 10 m/s) more fetch changes nothing. [`Spectrum::fetch`] returns the fetch
    /// used.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] unless both are finite and > 0 and
    /// `wind_speed` ≤ [`MAX_WIND_SPEED`](Self::MAX_WIND_SPEED).
    pub fn jonswap(wind_speed: f32, fetch: f32) -> Result<Self, Error> {
        let u = check_wind_speed(wind_speed)?;
        let f = error::positive("fetch", fetch)?;
        let full = Self::FULLY_DEVELOPED_FETCH * u * u / G as f32;
        let f = f.min(full);
        let (u64, f64_) = (f64::from(u), f64::from(f));
        // With libm's functions whatever the mode: the parameters a spectrum stores are then
        // the same bits on every platform (Determinism::CrossPlatform needs that).
        let alpha = omega::jonswap_alpha::<Libm>(u64, f64_) as f32;
        let peak_omega = omega::jonswap_peak_omega::<Libm>(u64, f64_) as f32;
        Self::check_model(alpha, peak_omega)?;
        Ok(Self::with_model(
            Model::Jonswap {
                alpha,
                peak_omega,
                gamma: Self::DEFAULT_GAMMA,
            },
            u,
            Some(f),
        ))
    }

    /// JONSWAP spectrum from its parameters: α (dimensionless, > 0), ω_p in rad/s (> 0) and
    /// γ (> 0), deep water.
    ///
    /// The wind speed used by the [`Spreading::Mitsuyasu`] and [`Spreading::Hasselmann`]
    /// spreadings is taken as that of a fully developed sea with this peak,
    /// U = 0.877 g / ω_p.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] unless all three are finite and > 0.
    pub fn jonswap_from_parameters(alpha: f32, peak_omega: f32, gamma: f32) -> Result<Self, Error> {
        let alpha = error::positive("alpha", alpha)?;
        let peak_omega = error::positive("peak_omega", peak_omega)?;
        let gamma = error::positive("gamma", gamma)?;
        let wind_speed = (PIERSON_MOSKOWITZ_PEAK * G / f64::from(peak_omega)) as f32;
        Self::check_model(alpha, peak_omega)?;
        Ok(Self::with_model(
            Model::Jonswap {
                alpha,
                peak_omega,
                gamma,
            },
            error::positive("wind_speed", wind_speed)?,
            None,
        ))
    }

    /// Pierson–Moskowitz spectrum of a fully developed sea (Pierson & Moskowitz 1964) from the
    /// wind speed U in m/s: JONSWAP with α = 0.0081, ω_p = 0.877 g/U, γ = 1.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] unless `wind_speed` is in
    /// (0, [`MAX_WIND_SPEED`](Self::MAX_WIND_SPEED)].
    pub fn pierson_moskowitz(wind_speed: f32) -> Result<Self, Error> {
        let u = check_wind_speed(wind_speed)?;
        let peak_omega = (PIERSON_MOSKOWITZ_PEAK * G / f64::from(u)) as f32;
        let alpha = PIERSON_MOSKOWITZ_ALPHA as f32;
        Self::check_model(alpha, peak_omega)?;
        Ok(Self::with_model(
            Model::Jonswap {
                alpha,
                peak_omega,
                gamma: 1.0,
            },
            u,
            None,
        ))
    }

    /// TMA spectrum of a fetch-limited sea in water of finite depth (Bouws et al. 1985):
    /// JONSWAP from wind speed U (m/s) and fetch F (m) times Kitaigorodskii's depth factor,
    /// with finite-depth dispersion for depth h in metres.
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] unless all three are finite and > 0 and
    /// `wind_speed` ≤ [`MAX_WIND_SPEED`](Self::MAX_WIND_SPEED).
    pub fn tma(wind_speed: f32, fetch: f32, depth: f32) -> Result<Self, Error> {
        Self::jonswap(wind_speed, fetch)?
            .with_depth(depth)?
            .with_depth_factor(DepthFactor::Kitaigorodskii)
    }

    /// Tessendorf's (2001) Phillips spectrum from the wind speed U in m/s and a free amplitude
    /// A in m² (not calibrated to a wave height):
    ///
    /// ```text
    /// S(k) = A exp(−1/(k L_w)²) / k⁴ · |k̂·ŵ|²,   L_w = U²/g
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] unless `wind_speed` is in
    /// (0, [`MAX_WIND_SPEED`](Self::MAX_WIND_SPEED)] and `amplitude` finite and ≥ 0.
    pub fn phillips(wind_speed: f32, amplitude: f32) -> Result<Self, Error> {
        let u = check_wind_speed(wind_speed)?;
        let amplitude = error::non_negative("amplitude", amplitude)?;
        Ok(Self::with_model(Model::Phillips { amplitude }, u, None))
    }

    /// Smallest accepted inverse wave age Ω = U10/c_p of [`Spectrum::elfouhaily`]: a fully
    /// developed sea (Elfouhaily et al. 1997).
    pub const MIN_INVERSE_WAVE_AGE: f32 = 0.84;

    /// Largest accepted inverse wave age: a very young sea, the top of the range of the
    /// paper's peak enhancement γ = 1.7 + 6 log₁₀ Ω.
    pub const MAX_INVERSE_WAVE_AGE: f32 = 5.0;

    /// The unified directional spectrum of Elfouhaily, Chapron, Katsaros & Vandemark (1997)
    /// from the wind speed U10 in m/s and the inverse wave age Ω = U10/c_p (0.84 for a fully
    /// developed sea, up to 5 for a very young one), deep water, with its own spreading
    /// [`Spreading::Elfouhaily`]:
    ///
    /// ```text
    /// S(k) = k⁻³ (B_l + B_h),   B_l = ½ α_p (c_p/c) F_p,   B_h = ½ α_m (c_m/c) F_m
    /// ```
    ///
    /// a JONSWAP-like peak at k_p = Ω² g/U10² with a long-wave curvature B_l, and a
    /// short-wave curvature B_h peaking at the gravity–capillary wave number k_m = 370 rad/m,
    /// set by the friction velocity u* of the wind (from U10 by Wu's 1982 drag law). Its short
    /// waves end by themselves, so its mean-square slope has no cut-off to choose: 0.0605 at
    /// 10 m/s, above Cox & Munk's (1954) sun-glitter measurement of 0.054 ± 0.004 (+6 to +12 %
    /// on their fit from 5 to 15 m/s), which is what a renderer's sub-grid roughness needs (see
    /// [`Spectrum::slope_variance`]). The formulas and their parameters are listed in
    /// docs/theory.md.
    ///
    /// ```
    /// # use ocean_fft::inspect::SlopeVariance;
    /// # use ocean_fft::Spectrum;
    /// let spectrum = Spectrum::elfouhaily(10.0, 0.84)?;   // U10 [m/s], Ω
    /// let mss = spectrum.slope_variance(0.0, 1e4).total();
    /// assert!((mss - 0.054).abs() < 0.01);                 // Cox & Munk: 0.003 + 5.12e-3 U10 ± 0.004
    /// # Ok::<(), ocean_fft::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] unless `wind_speed` is in
    /// (0, [`MAX_WIND_SPEED`](Self::MAX_WIND_SPEED)] and `inverse_wave_age` in
    /// [[`MIN_INVERSE_WAVE_AGE`](Self::MIN_INVERSE_WAVE_AGE),
    /// [`MAX_INVERSE_WAVE_AGE`](Self::MAX_INVERSE_WAVE_AGE)].
    pub fn elfouhaily(wind_speed: f32, inverse_wave_age: f32) -> Result<Self, Error> {
        let u = check_wind_speed(wind_speed)?;
        let inverse_wave_age = check_inverse_wave_age(inverse_wave_age)?;
        Ok(Self::with_model(
            Model::Elfouhaily { inverse_wave_age },
            u,
            None,
        ))
    }

    /// Inverse wave age Ω = U10/c_p of an Elfouhaily spectrum (`None` for the others).
    pub fn inverse_wave_age(&self) -> Option<f32> {
        match self.model {
            Model::Elfouhaily { inverse_wave_age } => Some(inverse_wave_age),
            _ => None,
        }
    }

    pub(crate) fn check_model(alpha: f32, peak_omega: f32) -> Result<(), Error> {
        // Extreme but finite inputs can push the derived parameters out of f32.
        error::positive("alpha", alpha)?;
        error::positive("peak_omega", peak_omega)?;
        Ok(())
    }

    /// Wind speed U in m/s (at 10 m for JONSWAP and TMA).
    pub fn wind_speed(&self) -> f32 {
        self.wind_speed
    }

    /// Fetch F in metres used by the fetch law, for spectra built from a fetch: the given
    /// fetch, capped at full development (see [`Spectrum::jonswap`]).
    pub fn fetch(&self) -> Option<f32> {
        self.fetch
    }

    /// Wind direction θ_w in radians, in [−π, π]: the direction the wind blows toward.
    pub fn wind_direction(&self) -> f32 {
        self.wind_direction
    }

    /// Unit vector `[x, z]` of the wind direction.
    pub fn wind_vector(&self) -> [f32; 2] {
        // The f32 sine and cosine of the platform, as this returned before the lint: a
        // convenience for callers that nothing in the simulation reads.
        #[allow(clippy::disallowed_methods)]
        let (sin, cos) = self.wind_direction.sin_cos();
        [cos, sin]
    }

    /// The directional spreading function in use (evaluate it with
    /// [`spreading`](Self::spreading)).
    pub fn spreading_kind(&self) -> Spreading {
        self.spreading
    }

    /// Horvath's swell parameter ξ in [0, 1].
    pub fn swell(&self) -> f32 {
        self.swell
    }

    /// Horvath's spread blend μ in [0, 1].
    pub fn spread_blend(&self) -> f32 {
        self.spread_blend
    }

    /// Short-wave fade length ℓ in metres.
    pub fn short_wave_length(&self) -> f32 {
        self.short_wave_length
    }

    /// The dispersion relation ω(k).
    pub fn dispersion(&self) -> Dispersion {
        self.dispersion
    }

    /// Water depth in metres, `None` in deep water.
    pub fn depth(&self) -> Option<f32> {
        self.dispersion.depth()
    }

    /// The shallow-water depth factor.
    pub fn depth_factor(&self) -> DepthFactor {
        self.depth_factor
    }

    /// JONSWAP peak enhancement γ (`None` for Phillips and Elfouhaily).
    pub fn gamma(&self) -> Option<f32> {
        match self.model {
            Model::Jonswap { gamma, .. } => Some(gamma),
            _ => None,
        }
    }

    /// JONSWAP Phillips constant α, dimensionless (`None` for Phillips and Elfouhaily).
    pub fn alpha(&self) -> Option<f32> {
        match self.model {
            Model::Jonswap { alpha, .. } => Some(alpha),
            _ => None,
        }
    }

    /// Peak angular frequency ω_p in rad/s.
    ///
    /// For JONSWAP, Pierson–Moskowitz and TMA the ω_p parameter of the JONSWAP shape (the
    /// TMA depth factor moves the actual maximum of S(ω) slightly). For Phillips the maximum
    /// of its deep-water S(ω), at k = (2/√5)/L_w. For Elfouhaily the frequency
    /// √(g k_p (1 + (k_p/k_m)²)) of its peak wave number k_p = Ω² g/U10².
    #[doc(alias = "Tp")]
    pub fn peak_omega(&self) -> f32 {
        self.peak_omega_f64() as f32
    }

    /// Peak period T_p = 2π/ω_p in seconds.
    pub fn peak_period(&self) -> f32 {
        (2.0 * PI / self.peak_omega_f64()) as f32
    }

    fn peak_omega_f64(&self) -> f64 {
        match self.model {
            Model::Jonswap { peak_omega, .. } => f64::from(peak_omega),
            Model::Phillips { .. } => (G * self.phillips_peak_wave_number()).sqrt(),
            Model::Elfouhaily { .. } => {
                let k_p = self.elfouhaily_peak_wave_number();
                k_p * elfouhaily::phase_speed(k_p)
            }
        }
    }

    /// k_p = Ω² g/U10² of an Elfouhaily spectrum (0 for the others).
    fn elfouhaily_peak_wave_number(&self) -> f64 {
        match self.model {
            Model::Elfouhaily { inverse_wave_age } => elfouhaily::peak_wave_number(
                f64::from(self.wind_speed),
                f64::from(inverse_wave_age),
            ),
            _ => 0.0,
        }
    }

    /// Wave number of the spectrum's peak in rad/m: k(ω_p) under this spectrum's dispersion
    /// for the spectra defined on ω; for Phillips, defined on k, the wave number of its
    /// deep-water peak whatever the dispersion (see [`Spectrum::peak_omega`]).
    pub(crate) fn peak_wave_number_f64(&self) -> f64 {
        self.peak_wave_number_with::<Std>()
    }

    /// [`peak_wave_number_f64`](Self::peak_wave_number_f64) with the functions of `M`.
    pub(crate) fn peak_wave_number_with<M: Math>(&self) -> f64 {
        match self.model {
            Model::Jonswap { peak_omega, .. } => self
                .dispersion
                .k_from_omega_with::<M>(f64::from(peak_omega)),
            Model::Phillips { .. } => self.phillips_peak_wave_number(),
            Model::Elfouhaily { .. } => self.elfouhaily_peak_wave_number(),
        }
    }

    /// Where the Phillips spectrum's deep-water S(ω) peaks, in rad/m: S(ω) = S(k) dk/dω
    /// ∝ k^(−5/2) exp(−1/(k L_w)²) is largest at k = (2/√5)/L_w.
    fn phillips_peak_wave_number(&self) -> f64 {
        2.0 / (5f64.sqrt() * self.wind_length())
    }

    /// L_w = U²/g in metres, the Phillips spectrum's largest wave.
    fn wind_length(&self) -> f64 {
        let u = f64::from(self.wind_speed);
        u * u / G
    }

    pub(crate) fn spreading_params(&self) -> SpreadingParams {
        SpreadingParams {
            spreading: self.spreading,
            peak_omega: self.peak_omega_f64(),
            wind_speed: f64::from(self.wind_speed),
            swell: f64::from(self.swell),
            spread_blend: f64::from(self.spread_blend),
        }
    }
}

/// Checks a wind speed in m/s: 0 < U ≤ [`Spectrum::MAX_WIND_SPEED`].
pub(crate) fn check_wind_speed(wind_speed: f32) -> Result<f32, Error> {
    error::in_range(
        "wind_speed",
        wind_speed,
        Excluded(0.0),
        Included(Spectrum::MAX_WIND_SPEED),
    )
}

/// Checks an inverse wave age Ω of the Elfouhaily spectrum.
pub(crate) fn check_inverse_wave_age(value: f32) -> Result<f32, Error> {
    error::in_range(
        "inverse_wave_age",
        value,
        Included(Spectrum::MIN_INVERSE_WAVE_AGE),
        Included(Spectrum::MAX_INVERSE_WAVE_AGE),
    )
}

/// Wraps an angle in radians to [−π, π].
fn wrap_angle(theta: f64) -> f64 {
    let wrapped = (theta + PI).rem_euclid(2.0 * PI) - PI;
    if wrapped < -PI {
        -PI
    } else {
        wrapped
    }
}
