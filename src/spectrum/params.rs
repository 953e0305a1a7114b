//! A spectrum's parameters as plain data ([`SpectrumParams`]): read with
//! [`Spectrum::params`], edit, build again with [`Spectrum::from_params`], which checks every
//! field as the constructors and setters do. Also the gate that checks a spectrum assembled
//! from stored fields (deserialisation).

use std::ops::Bound::{Included, Unbounded};

use super::dispersion::Dispersion;
use super::omega::{G, PIERSON_MOSKOWITZ_PEAK};
use super::spreading::Spreading;
use super::{check_inverse_wave_age, check_wind_speed, DepthFactor, Model, Spectrum};
use crate::error::{self, Error};

/// The model behind S(ω) and its own parameters, in a [`SpectrumParams`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum SpectrumKind {
    /// JONSWAP of a fetch-limited sea, α and ω_p from the wind speed and `fetch` in metres
    /// by the fetch law ([`Spectrum::jonswap`], which caps the fetch at full development),
    /// with peak enhancement `gamma` (dimensionless, > 0). With a finite-depth
    /// [`Dispersion`] and [`DepthFactor::Kitaigorodskii`] this is TMA ([`Spectrum::tma`]).
    Jonswap {
        /// Fetch F in metres, > 0.
        fetch: f32,
        /// Peak enhancement γ, > 0 ([`Spectrum::DEFAULT_GAMMA`] by default).
        gamma: f32,
    },
    /// Pierson–Moskowitz, a fully developed sea from the wind speed alone
    /// ([`Spectrum::pierson_moskowitz`]).
    PiersonMoskowitz,
    /// The JONSWAP shape from its own parameters ([`Spectrum::jonswap_from_parameters`]):
    /// α (dimensionless), ω_p in rad/s and γ, each > 0. The wind speed is then the one the
    /// Mitsuyasu and Hasselmann spreadings read, any positive value with
    /// ω_p·U/g ≥ 0.877 (a sea at most fully developed).
    JonswapShape {
        /// Phillips constant α, dimensionless, > 0.
        alpha: f32,
        /// Peak angular frequency ω_p in rad/s, > 0.
        peak_omega: f32,
        /// Peak enhancement γ, > 0.
        gamma: f32,
    },
    /// Tessendorf's Phillips spectrum with its free `amplitude` A in m², ≥ 0
    /// ([`Spectrum::phillips`]).
    Phillips {
        /// Amplitude A in m², ≥ 0.
        amplitude: f32,
    },
    /// Elfouhaily et al.'s unified spectrum with its inverse wave age Ω = U10/c_p
    /// ([`Spectrum::elfouhaily`]).
    Elfouhaily {
        /// Inverse wave age Ω, in
        /// [[`Spectrum::MIN_INVERSE_WAVE_AGE`], [`Spectrum::MAX_INVERSE_WAVE_AGE`]].
        inverse_wave_age: f32,
    },
}

/// Every parameter of a [`Spectrum`] as plain data, to read, show, edit and build again:
/// [`Spectrum::params`] gives them, [`Spectrum::from_params`] checks them and builds the
/// spectrum (the same bits for parameters read from a spectrum).
///
/// ```
/// use ocean_fft::{Spectrum, SpectrumKind, Spreading};
/// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?.with_wind_direction(0.3)?;
/// let mut params = spectrum.params();
/// assert_eq!(Spectrum::from_params(&params)?, spectrum);    // exact
///
/// params.wind_speed = 14.0;                                 // m/s: a stronger wind …
/// params.kind = SpectrumKind::Jonswap { fetch: 250_000.0, gamma: 3.3 };   // … over more sea
/// params.spreading = Spreading::Mitsuyasu;
/// let stormier = Spectrum::from_params(&params)?;
/// assert!(stormier.significant_wave_height() > spectrum.significant_wave_height());
/// assert_eq!(stormier.wind_direction(), 0.3);               // the rest kept
///
/// params.swell = 2.0;                                       // out of [0, 1]
/// let error = Spectrum::from_params(&params).unwrap_err();
/// assert!(error.to_string().contains("swell"));
/// # Ok::<(), ocean_fft::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpectrumParams {
    /// The model and its own parameters.
    pub kind: SpectrumKind,
    /// Wind speed U in m/s (at 10 m), in (0, [`Spectrum::MAX_WIND_SPEED`]] (for
    /// [`SpectrumKind::JonswapShape`] any positive value, see there).
    pub wind_speed: f32,
    /// Wind direction θ_w in radians, finite: the direction the wind blows toward (stored
    /// wrapped to [−π, π]).
    pub wind_direction: f32,
    /// The directional spreading.
    pub spreading: Spreading,
    /// Horvath's swell parameter ξ in [0, 1].
    pub swell: f32,
    /// Horvath's spread blend μ in [0, 1].
    pub spread_blend: f32,
    /// Short-wave fade length ℓ in metres, ≥ 0.
    pub short_wave_length: f32,
    /// The dispersion relation, with the water depth in metres if finite.
    pub dispersion: Dispersion,
    /// The shallow-water depth factor ([`DepthFactor::None`] for Phillips and Elfouhaily).
    pub depth_factor: DepthFactor,
}

impl Spectrum {
    /// Every parameter of this spectrum as plain data (see [`SpectrumParams`]):
    /// [`from_params`](Self::from_params) of it gives this spectrum again, with the same
    /// bits. A JONSWAP spectrum whose α and ω_p follow its wind and fetch (every one built by
    /// [`jonswap`](Self::jonswap) or [`tma`](Self::tma)) reads as [`SpectrumKind::Jonswap`],
    /// one built by [`pierson_moskowitz`](Self::pierson_moskowitz) as
    /// [`SpectrumKind::PiersonMoskowitz`], any other as [`SpectrumKind::JonswapShape`] (a
    /// spectrum loaded from a file whose α and ω_p do not follow its fetch then loses the
    /// fetch, which nothing but [`fetch`](Self::fetch) reads).
    pub fn params(&self) -> SpectrumParams {
        let kind = match self.model {
            Model::Jonswap {
                alpha,
                peak_omega,
                gamma,
            } => {
                // Whether `built` has this spectrum's α, ω_p and fetch, to the bit.
                let follows = |built: Result<Spectrum, Error>| {
                    built.is_ok_and(|built| match built.model {
                        Model::Jonswap {
                            alpha: a,
                            peak_omega: p,
                            ..
                        } => {
                            a.to_bits() == alpha.to_bits()
                                && p.to_bits() == peak_omega.to_bits()
                                && built.fetch.map(f32::to_bits) == self.fetch.map(f32::to_bits)
                        }
                        _ => false,
                    })
                };
                match self.fetch {
                    Some(fetch) if follows(Spectrum::jonswap(self.wind_speed, fetch)) => {
                        SpectrumKind::Jonswap { fetch, gamma }
                    }
                    None if gamma == 1.0
                        && follows(Spectrum::pierson_moskowitz(self.wind_speed)) =>
                    {
                        SpectrumKind::PiersonMoskowitz
                    }
                    _ => SpectrumKind::JonswapShape {
                        alpha,
                        peak_omega,
                        gamma,
                    },
                }
            }
            Model::Phillips { amplitude } => SpectrumKind::Phillips { amplitude },
            Model::Elfouhaily { inverse_wave_age } => SpectrumKind::Elfouhaily { inverse_wave_age },
        };
        SpectrumParams {
            kind,
            wind_speed: self.wind_speed,
            wind_direction: self.wind_direction,
            spreading: self.spreading,
            swell: self.swell,
            spread_blend: self.spread_blend,
            short_wave_length: self.short_wave_length,
            dispersion: self.dispersion,
            depth_factor: self.depth_factor,
        }
    }

    /// The spectrum `params` describe, every field checked as the constructors and `with_*`
    /// setters check it (see [`SpectrumParams`]). For parameters read with
    /// [`params`](Self::params), the spectrum read, with the same bits.
    ///
    /// # Errors
    /// [`Error::NonFinite`], [`Error::OutOfRange`] or [`Error::NotApplicable`] naming the
    /// first field that is out of its range (`wind_speed`, `fetch`, `gamma`, `alpha`,
    /// `peak_omega`, `amplitude`, `inverse_wave_age`, `wind_direction`, the spreading's,
    /// `swell`, `spread_blend`, `short_wave_length`, `depth`, `depth_factor`).
    pub fn from_params(params: &SpectrumParams) -> Result<Spectrum, Error> {
        let u = params.wind_speed;
        let base = match params.kind {
            SpectrumKind::Jonswap { fetch, gamma } => {
                Spectrum::jonswap(u, fetch)?.with_gamma(gamma)?
            }
            SpectrumKind::PiersonMoskowitz => Spectrum::pierson_moskowitz(u)?,
            SpectrumKind::JonswapShape {
                alpha,
                peak_omega,
                gamma,
            } => {
                let model = Model::Jonswap {
                    alpha,
                    peak_omega,
                    gamma,
                };
                Spectrum::with_model(model, u, None)
            }
            SpectrumKind::Phillips { amplitude } => Spectrum::phillips(u, amplitude)?,
            SpectrumKind::Elfouhaily { inverse_wave_age } => {
                Spectrum::elfouhaily(u, inverse_wave_age)?
            }
        };
        validate_spectrum(Spectrum {
            wind_direction: params.wind_direction,
            spreading: params.spreading,
            swell: params.swell,
            spread_blend: params.spread_blend,
            short_wave_length: params.short_wave_length,
            dispersion: params.dispersion,
            depth_factor: params.depth_factor,
            ..base
        })
    }
}

/// Checks every stored parameter with the checks of the constructors and setters, and
/// wraps the wind direction to [−π, π] as [`Spectrum::with_wind_direction`]
/// does: the gate for spectra assembled from stored fields (deserialisation,
/// [`Spectrum::from_params`]).
///
/// The parameters are checked one by one, plus the one relation every constructor keeps
/// and evaluation relies on (ω_p U/g ≥ 0.877, a sea at most fully developed); α and ω_p
/// need not follow the fetch law of the stored wind and fetch, as they need not for
/// [`Spectrum::jonswap_from_parameters`].
pub(crate) fn validate_spectrum(mut spectrum: Spectrum) -> Result<Spectrum, Error> {
    match spectrum.model {
        Model::Jonswap {
            alpha,
            peak_omega,
            gamma,
        } => {
            Spectrum::check_model(alpha, peak_omega)?;
            error::positive("gamma", gamma)?;
            // The fetch law caps the wind at MAX_WIND_SPEED; jonswap_from_parameters
            // derives it from ω_p, which has no upper bound.
            match spectrum.fetch {
                Some(fetch) => {
                    check_wind_speed(spectrum.wind_speed)?;
                    error::positive("fetch", fetch)?;
                }
                None => {
                    error::positive("wind_speed", spectrum.wind_speed)?;
                }
            }
            // Every constructor gives a sea at most fully developed, ω_p U/g ≥ 0.877 (the
            // fetch law is capped there; Pierson–Moskowitz and jonswap_from_parameters sit
            // on it). The Mitsuyasu spreading's s_p = 11.5 (ω_p U/g)^−2.5 relies on it:
            // far below, s overflows the cos-2s normalisation into NaN.
            let fully_developed =
                (PIERSON_MOSKOWITZ_PEAK * (1.0 - 1e-4) * G / f64::from(spectrum.wind_speed)) as f32;
            error::in_range(
                "peak_omega",
                peak_omega,
                Included(fully_developed),
                Unbounded,
            )?;
        }
        Model::Phillips { amplitude } => {
            check_wind_speed(spectrum.wind_speed)?;
            error::non_negative("amplitude", amplitude)?;
            if spectrum.fetch.is_some() {
                return Err(Error::NotApplicable {
                    name: "fetch",
                    reason: "the Phillips spectrum is not built from a fetch",
                });
            }
        }
        Model::Elfouhaily { inverse_wave_age } => {
            check_wind_speed(spectrum.wind_speed)?;
            check_inverse_wave_age(inverse_wave_age)?;
            if spectrum.fetch.is_some() {
                return Err(Error::NotApplicable {
                    name: "fetch",
                    reason: "the Elfouhaily spectrum is built from its inverse wave age",
                });
            }
        }
    }
    let wind_direction = error::finite("wind_direction", spectrum.wind_direction)?;
    if wind_direction.abs() > std::f32::consts::PI {
        spectrum = spectrum.with_wind_direction(wind_direction)?;
    }
    spectrum.spreading = spectrum.spreading.validate()?;
    let (swell, blend, length) = (
        spectrum.swell,
        spectrum.spread_blend,
        spectrum.short_wave_length,
    );
    let (dispersion, depth_factor) = (spectrum.dispersion, spectrum.depth_factor);
    spectrum
        .with_swell(swell)?
        .with_spread_blend(blend)?
        .with_short_wave_length(length)?
        .with_dispersion(dispersion)?
        .with_depth_factor(depth_factor)
}
