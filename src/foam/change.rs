//! How the foam's model follows a change of weather or of its own settings: the moments of
//! the new sea one cascade at a time, its calibration at the checkpoints of the change, and the
//! blend of the two seas' models, with the foam itself kept.

use crate::cascade::{Cascade, MAX_CASCADES};
use crate::error::Error;
use crate::math::determinism::with_math;
use crate::spectrum::Spectrum;

use super::model::{params, FoamChange, FoamSea, Model, CHECKPOINTS};
use super::moments::GradientMoments;
use super::state::Foam;
use super::transport::Transport;
use super::{FoamCalibration, FoamConfig};

/// What one calibration costs, in wave vectors drawn (the unit of a change's preparation;
/// only the pacing of the preparation depends on it).
const CALIBRATION_COST: usize = 20_000;

/// What the gradient moments of `cascade`'s amplitudes cost, in wave vectors drawn.
fn moments_cost(cascade: &Cascade) -> usize {
    cascade.size() * cascade.size() / 4
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
            moments: [None; MAX_CASCADES],
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
