//! What the foam's model reads from the sea and the model built from it: the breaking
//! threshold calibrated for the sea as it is, the moments of the unresolved gradient, and the
//! transport of residual foam; and the record of a change of weather between two seas, which
//! `change.rs` follows.

use crate::cascade::{Cascade, MAX_CASCADES};
use crate::math::determinism::Math;
use crate::spectrum::Spectrum;

use super::calibration::{calibrate, Settings};
use super::intensity::Params;
use super::moments::GradientMoments;
use super::transport::Transport;
use super::{FoamCalibration, FoamConfig};

/// What the foam's model needs to know about the sea: the second moments of the gradient
/// (of the cascades the foam grid does not resolve, and of all of them) and the wind and
/// peak wavelength of the spectrum.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FoamSea {
    unresolved: GradientMoments,
    total: GradientMoments,
    /// The spectrum's U10 in m/s (a `FoamConfig::wind_speed` replaces it in [`Model::new`]).
    wind_speed: f32,
    /// θ_w in rad, toward which the wind blows.
    wind_direction: f64,
    /// The peak wavelength in m.
    wavelength: f64,
}

impl FoamSea {
    /// The sea of `cascades` with the amplitudes `amplitudes` gives each (their own, or the
    /// new ones of a change) and `spectrum`, with the functions of `M`. The moments are
    /// summed in the cascades' order (cascade 0 resolved, the others not).
    pub(crate) fn of<'a, M: Math>(
        cascades: &'a [Cascade],
        amplitudes: impl Fn(&'a Cascade) -> &'a [num_complex::Complex32],
        spectrum: &Spectrum,
    ) -> FoamSea {
        let moments = |c: &'a Cascade| GradientMoments::of_amplitudes::<M>(c, amplitudes(c));
        Self::from_moments::<M>(
            moments(&cascades[0]),
            cascades[1..].iter().map(moments),
            spectrum,
        )
    }

    /// The sea whose cascades have the moments `resolved` (cascade 0) and `unresolved` (the
    /// others, in order), of `spectrum`, with the functions of `M`.
    pub(super) fn from_moments<M: Math>(
        resolved: GradientMoments,
        unresolved: impl IntoIterator<Item = GradientMoments>,
        spectrum: &Spectrum,
    ) -> FoamSea {
        let mut sum = GradientMoments::default();
        for moments in unresolved {
            sum.add(&moments);
        }
        let unresolved = sum;
        let mut total = resolved;
        total.add(&unresolved);
        let peak = spectrum
            .dispersion()
            .k_from_omega_with::<M>(f64::from(spectrum.peak_omega()));
        FoamSea {
            unresolved,
            total,
            wind_speed: spectrum.wind_speed(),
            wind_direction: f64::from(spectrum.wind_direction()),
            wavelength: std::f64::consts::TAU / peak,
        }
    }

    /// The peak wavelength in m.
    pub(super) fn peak_wavelength(&self) -> f64 {
        self.wavelength
    }

    /// θ_w in rad, toward which the wind blows.
    pub(super) fn wind_direction(&self) -> f64 {
        self.wind_direction
    }

    /// The variance of the compression −(D_xx + D_zz) at unit choppiness of the cascades the
    /// foam grid does not resolve (cascades 1 and up).
    pub(super) fn unresolved_compression(&self) -> f64 {
        let v = &self.unresolved.value;
        v[0][0] + v[1][1] + 2.0 * v[0][1]
    }

    /// The U10 in m/s the whitecaps answer to under `config`.
    pub(super) fn wind_speed(&self, config: &FoamConfig) -> f32 {
        config.wind_speed.unwrap_or(self.wind_speed)
    }

    /// The calibration of this sea under `config`, with the functions of `M`.
    pub(super) fn calibration<M: Math>(
        &self,
        config: &FoamConfig,
        wind_speed: f32,
    ) -> FoamCalibration {
        calibrate::<M>(
            &self.total,
            Settings {
                wind_speed,
                coverage: config.coverage,
                active_decay: config.active_decay,
            },
        )
    }

    /// The transport of residual foam on a grid of side `length` m under `config`, with the
    /// functions of `M`: spreads over a residual lifetime, √(2Kτ_R) = streak·λ_p, give the
    /// diffusivities.
    pub(super) fn transport<M: Math>(&self, config: &FoamConfig, length: f32) -> Transport {
        let diffusivity = |streak: f32| {
            let spread = f64::from(streak) * self.wavelength;
            spread * spread / (2.0 * f64::from(config.residual_decay))
        };
        Transport::new::<M>(
            self.wind_direction,
            f64::from(config.drift) * f64::from(self.wind_speed(config)),
            diffusivity(config.streak_length),
            diffusivity(config.streak_width),
            f64::from(length),
        )
    }
}

/// The foam model of a sea: its calibration, the per-point constants and the transport.
#[derive(Debug, Clone)]
pub(crate) struct Model {
    pub(crate) calibration: FoamCalibration,
    pub(crate) params: Params,
    pub(crate) transport: Transport,
}

impl Model {
    /// The model of `sea` under `config` on a foam grid of side `length` m, with the
    /// functions of `M`.
    pub(crate) fn new<M: Math>(sea: &FoamSea, config: &FoamConfig, length: f32) -> Model {
        let calibration = sea.calibration::<M>(config, sea.wind_speed(config));
        Model {
            params: params(sea, config, &calibration),
            calibration,
            transport: sea.transport::<M>(config, length),
        }
    }
}

/// The per-point constants for `sea` under `config` with `calibration`'s threshold.
pub(super) fn params(sea: &FoamSea, config: &FoamConfig, calibration: &FoamCalibration) -> Params {
    Params::new(
        calibration.threshold,
        calibration.compression_std,
        &sea.unresolved,
        &sea.total,
        config.active_decay,
        config.residual_decay,
    )
}

/// Points of a change of weather at which the breaking threshold is calibrated afresh (a
/// calibration costs about as much as a third of a default step); between them it is
/// interpolated linearly in the blend weight.
pub(super) const CHECKPOINTS: usize = 8;

/// The foam's side of a change of weather: the sea it comes from and the one it goes to,
/// their transports, and the calibrations made so far at the checkpoints w = k/8.
#[derive(Debug, Clone)]
pub(crate) struct FoamChange {
    pub(super) from: FoamSea,
    /// The moments of each cascade's new amplitudes, computed one cascade a step.
    pub(super) moments: [Option<GradientMoments>; MAX_CASCADES],
    pub(super) to: Option<FoamSea>,
    pub(super) from_transport: Transport,
    pub(super) to_transport: Option<Transport>,
    pub(super) calibrations: [Option<FoamCalibration>; CHECKPOINTS + 1],
}

impl FoamSea {
    /// The sea (1 − w)·`self` + w·`other`: moments linear (they are sums of energies), the
    /// wind speed linear; the direction and wavelength are only read through the transports,
    /// which blend on their own.
    pub(super) fn blend(&self, other: &FoamSea, w: f64) -> FoamSea {
        FoamSea {
            unresolved: self.unresolved.blend(&other.unresolved, w),
            total: self.total.blend(&other.total, w),
            wind_speed: ((1.0 - w) * f64::from(self.wind_speed) + w * f64::from(other.wind_speed))
                as f32,
            wind_direction: if w < 0.5 {
                self.wind_direction
            } else {
                other.wind_direction
            },
            wavelength: (1.0 - w) * self.wavelength + w * other.wavelength,
        }
    }
}
