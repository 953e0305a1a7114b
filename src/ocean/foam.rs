//! Foam: injected where the surface is compressed (J below a bias), decaying over time.

use std::ops::Bound::Included;

use rayon::prelude::*;

use crate::determinism::{Determinism, Libm, Math, Std};
use crate::error::{self, Error};

use super::OceanState;

/// How foam is injected and decays (per cascade, from that cascade's Jacobian J).
///
/// Foam coverage f ∈ [0, 1] obeys df/dt = s·(1 − f) − f/τ with injection rate
/// s = `injection`·max(0, `bias` − J); over a step the exact solution for J held at its new
/// value is used, so the result barely depends on the frame rate and never leaves [0, 1].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FoamConfig {
    /// Jacobian threshold (dimensionless): foam is injected where J < `bias`, within
    /// ±[`MAX_BIAS`](Self::MAX_BIAS) (default: `0.8`, a look control: about 1 % of a fresh
    /// breeze's grid points lie below it).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::bias")
    )]
    pub bias: f32,
    /// Injection rate per unit of (bias − J), in 1/s, from 0 to
    /// [`MAX_INJECTION`](Self::MAX_INJECTION) (default: `8.0`).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::injection")
    )]
    pub injection: f32,
    /// Decay time constant τ in seconds, from [`MIN_DECAY`](Self::MIN_DECAY) to
    /// [`MAX_DECAY`](Self::MAX_DECAY) (default: `2.5`).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::decay")
    )]
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
    /// Largest |`bias`|. J is 1 on flat water and rarely outside (−1, 2) on a sea, so a bias
    /// beyond ±10 means foam everywhere or nowhere.
    pub const MAX_BIAS: f32 = 10.0;
    /// Largest `injection`, in 1/s: foam saturates within 0.1 ms at bias − J = 1.
    pub const MAX_INJECTION: f32 = 1e4;
    /// Shortest `decay`, in seconds.
    pub const MIN_DECAY: f32 = 1e-3;
    /// Longest `decay`, in seconds (11.6 days).
    pub const MAX_DECAY: f32 = 1e6;

    /// Checks every field against the ranges their docs give. Within them the foam update
    /// stays finite for any surface (|J| ≤ 1e30 under [`Cascade::MAX_AMPLITUDE`]).
    ///
    /// [`Cascade::MAX_AMPLITUDE`]: crate::Cascade::MAX_AMPLITUDE
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] naming `foam.bias`, `foam.injection` or
    /// `foam.decay`.
    pub fn validate(&self) -> Result<(), Error> {
        let bias = Self::MAX_BIAS;
        error::in_range("foam.bias", self.bias, Included(-bias), Included(bias))?;
        error::in_range(
            "foam.injection",
            self.injection,
            Included(0.0),
            Included(Self::MAX_INJECTION),
        )?;
        error::in_range(
            "foam.decay",
            self.decay,
            Included(Self::MIN_DECAY),
            Included(Self::MAX_DECAY),
        )?;
        Ok(())
    }
}

impl OceanState {
    pub(super) fn advance_foam(&mut self, dt: f32) {
        match self.config.determinism {
            Determinism::SameMachine => self.advance_foam_with::<Std>(dt),
            Determinism::CrossPlatform => self.advance_foam_with::<Libm>(dt),
        }
    }

    fn advance_foam_with<M: Math>(&mut self, dt: f32) {
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
                        *f = foam_step::<M>(*f, j, dt, bias, injection, inv_tau);
                    }
                });
        }
    }
}

/// One exact step of df/dt = s(1 − f) − f/τ with s = injection·max(0, bias − J) held
/// constant: f relaxes toward s/(s + 1/τ) at rate s + 1/τ.
#[inline]
fn foam_step<M: Math>(
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
    let next = equilibrium + (f - equilibrium) * M::expf(-rate * dt);
    next.clamp(0.0, 1.0)
}
