//! What the foam's model reads from the sea, and how it follows a change of weather or of its
//! own settings: the breaking threshold calibrated for the sea as it is, the moments of the
//! unresolved gradient, and the transport of residual foam.

use crate::cascade::Cascade;
use crate::error::Error;
use crate::math::determinism::{with_math, Math};
use crate::spectrum::Spectrum;

use super::calibration::{calibrate, Settings};
use super::intensity::Params;
use super::moments::GradientMoments;
use super::state::Foam;
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
    fn from_moments<M: Math>(
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

    /// The U10 in m/s the whitecaps answer to under `config`.
    fn wind_speed(&self, config: &FoamConfig) -> f32 {
        config.wind_speed.unwrap_or(self.wind_speed)
    }

    /// The calibration of this sea under `config`, with the functions of `M`.
    fn calibration<M: Math>(&self, config: &FoamConfig, wind_speed: f32) -> FoamCalibration {
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
    fn transport<M: Math>(&self, config: &FoamConfig, length: f32) -> Transport {
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
fn params(sea: &FoamSea, config: &FoamConfig, calibration: &FoamCalibration) -> Params {
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
const CHECKPOINTS: usize = 8;

/// What one calibration costs, in wave vectors drawn (the unit of a change's preparation;
/// only the pacing of the preparation depends on it).
const CALIBRATION_COST: usize = 20_000;

/// What the gradient moments of `cascade`'s amplitudes cost, in wave vectors drawn.
fn moments_cost(cascade: &Cascade) -> usize {
    cascade.size() * cascade.size() / 4
}

/// The foam's side of a change of weather: the sea it comes from and the one it goes to,
/// their transports, and the calibrations made so far at the checkpoints w = k/8.
#[derive(Debug, Clone)]
pub(crate) struct FoamChange {
    from: FoamSea,
    /// The moments of each cascade's new amplitudes, computed one cascade a step.
    moments: [Option<GradientMoments>; crate::OceanConfig::MAX_CASCADES],
    to: Option<FoamSea>,
    from_transport: Transport,
    to_transport: Option<Transport>,
    calibrations: [Option<FoamCalibration>; CHECKPOINTS + 1],
}

impl Foam {
    /// Starts following a change of weather from the sea as it is now (a blend, if a change
    /// was in progress).
    pub(crate) fn begin_change(&mut self) {
        let from = self.sea;
        let mut calibrations = [None; CHECKPOINTS + 1];
        calibrations[0] = Some(self.calibration);
        self.change = Some(FoamChange {
            from,
            moments: [None; crate::OceanConfig::MAX_CASCADES],
            to: None,
            from_transport: self.transport.clone(),
            to_transport: None,
            calibrations,
        });
    }

    /// What [`prepare_change`](Self::prepare_change) costs for `cascades`, in wave vectors
    /// drawn (the unit of a change's preparation).
    pub(crate) fn change_cost(&self, cascades: &[Cascade]) -> usize {
        cascades.iter().map(moments_cost).sum::<usize>() + CHECKPOINTS * CALIBRATION_COST
    }

    /// One piece of the work that prepares the foam for the change's new sea of `cascades`
    /// (each with its new amplitudes drawn) and `spectrum`, the next one not done yet: the
    /// moments of one cascade, or the new sea's model, or the calibration at one checkpoint.
    /// Each costs up to half a default step. Returns its cost in wave vectors drawn, `None`
    /// if none was left.
    pub(crate) fn prepare_change(
        &mut self,
        cascades: &[Cascade],
        spectrum: &Spectrum,
    ) -> Option<usize> {
        let (config, length, determinism) = (self.config, self.length, self.determinism);
        let change = self.change.as_mut()?;
        with_math!(determinism, M => {
            if let Some(c) = (0..cascades.len()).find(|&c| change.moments[c].is_none()) {
                let cascade = &cascades[c];
                let amplitudes = cascade.change_target().unwrap_or(cascade.h0());
                change.moments[c] = Some(GradientMoments::of_amplitudes::<M>(cascade, amplitudes));
                return Some(moments_cost(cascade));
            }
            if change.to.is_none() {
                let moments = |c: usize| change.moments[c].unwrap_or_default();
                let to = FoamSea::from_moments::<M>(
                    moments(0),
                    (1..cascades.len()).map(moments),
                    spectrum,
                );
                change.calibrations[CHECKPOINTS] =
                    Some(to.calibration::<M>(&config, to.wind_speed(&config)));
                change.to_transport = Some(to.transport::<M>(&config, length));
                change.to = Some(to);
                return Some(CALIBRATION_COST);
            }
            let to = change.to.expect("made above");
            if let Some(k) = (1..CHECKPOINTS).find(|&k| change.calibrations[k].is_none()) {
                let at = change.from.blend(&to, k as f64 / CHECKPOINTS as f64);
                change.calibrations[k] = Some(at.calibration::<M>(&config, at.wind_speed(&config)));
                return Some(CALIBRATION_COST);
            }
            None
        })
    }

    /// Follows the change to the blend weight `w` in [0, 1] of the new sea: the moments and
    /// the wind move linearly, the threshold through the calibrations at the checkpoints
    /// around `w` (made here the first time they are needed), the transport linearly. The
    /// model depends on `w` alone: at w ≤ 0 the old sea's model comes back exactly, at w = 1
    /// the new sea's is installed, the one `Foam::new` builds for it, and the change ends.
    /// The foam's state is kept throughout.
    pub(crate) fn blend_change(&mut self, w: f64) {
        let Some(mut change) = self.change.take() else {
            return;
        };
        let (Some(to), Some(to_transport)) = (change.to, change.to_transport.clone()) else {
            // Not prepared: the blend waits for `prepare_change`.
            self.change = Some(change);
            return;
        };
        let config = self.config;
        if w >= 1.0 {
            let calibration = change.calibrations[CHECKPOINTS].expect("calibrated with the target");
            self.params = params(&to, &config, &calibration);
            self.calibration = calibration;
            self.set_transport(to_transport);
            self.sea = to;
            return;
        }
        if w <= 0.0 {
            let calibration = change.calibrations[0].expect("calibrated when the change began");
            self.params = params(&change.from, &config, &calibration);
            self.calibration = calibration;
            self.set_transport(change.from_transport.clone());
            self.sea = change.from;
            self.change = Some(change);
            return;
        }
        let sea = change.from.blend(&to, w);
        // The checkpoints around w: k/8 ≤ w < (k + 1)/8.
        let position = w.max(0.0) * CHECKPOINTS as f64;
        let k = (position.floor() as usize).min(CHECKPOINTS - 1);
        for c in [k, k + 1] {
            if change.calibrations[c].is_none() {
                let at = change.from.blend(&to, c as f64 / CHECKPOINTS as f64);
                let wind = at.wind_speed(&config);
                change.calibrations[c] =
                    Some(with_math!(self.determinism, M => at.calibration::<M>(&config, wind)));
            }
        }
        let (a, b) = (
            change.calibrations[k].expect("made above"),
            change.calibrations[k + 1].expect("made above"),
        );
        let calibration = interpolate(&a, &b, (position - k as f64) as f32);
        self.params = params(&sea, &config, &calibration);
        self.calibration = calibration;
        self.set_transport(change.from_transport.blend(&to_transport, w));
        self.sea = sea;
        self.change = Some(change);
    }

    /// Replaces the transport; the drift tables made for the old one are refilled at the
    /// next step.
    fn set_transport(&mut self, transport: Transport) {
        if transport != self.transport {
            self.transport = transport;
            self.tables_dt = f64::NAN;
        }
    }

    /// Abandons a change in progress, keeping the model as it is.
    pub(crate) fn cancel_change(&mut self) {
        self.change = None;
    }

    /// Changes the foam's settings: the model is rebuilt for the sea as it is (and a change
    /// of weather in progress follows the new settings), the foam itself is kept.
    ///
    /// # Errors
    /// Those of [`FoamConfig::validate`]; nothing changes then.
    pub(crate) fn set_config(&mut self, config: &FoamConfig) -> Result<(), Error> {
        config.validate()?;
        self.config = *config;
        let length = self.length;
        let model = with_math!(self.determinism, M => Model::new::<M>(&self.sea, config, length));
        self.calibration = model.calibration;
        self.params = model.params;
        self.set_transport(model.transport);
        if let Some(change) = self.change.as_mut() {
            change.calibrations = [None; CHECKPOINTS + 1];
            let (from, to) = (change.from, change.to);
            with_math!(self.determinism, M => {
                change.calibrations[0] =
                    Some(from.calibration::<M>(config, from.wind_speed(config)));
                change.from_transport = from.transport::<M>(config, length);
                if let Some(to) = to {
                    change.calibrations[CHECKPOINTS] =
                        Some(to.calibration::<M>(config, to.wind_speed(config)));
                    change.to_transport = Some(to.transport::<M>(config, length));
                }
            });
        }
        Ok(())
    }
}

impl FoamSea {
    /// The sea (1 − w)·`self` + w·`other`: moments linear (they are sums of energies), the
    /// wind speed linear; the direction and wavelength are only read through the transports,
    /// which blend on their own.
    fn blend(&self, other: &FoamSea, w: f64) -> FoamSea {
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

/// The calibration a fraction `f` of the way from `a` to `b`: each number linearly, a
/// threshold of −∞ (nothing breaks) held to the nearer end.
fn interpolate(a: &FoamCalibration, b: &FoamCalibration, f: f32) -> FoamCalibration {
    let lerp = |x: f32, y: f32| {
        if x.is_finite() && y.is_finite() {
            x + f * (y - x)
        } else if f < 0.5 {
            x
        } else {
            y
        }
    };
    FoamCalibration {
        wind_speed: lerp(a.wind_speed, b.wind_speed),
        target: lerp(a.target, b.target),
        threshold: lerp(a.threshold, b.threshold),
        compression_std: lerp(a.compression_std, b.compression_std),
        breaking_fraction: lerp(a.breaking_fraction, b.breaking_fraction),
        episode_rate: lerp(a.episode_rate, b.episode_rate),
        predicted: lerp(a.predicted, b.predicted),
    }
}
