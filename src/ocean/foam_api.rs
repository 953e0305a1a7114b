//! The foam as an [`OceanState`] shows it: the fields, the coverage, the calibration and the
//! breaking intensity at a point.

use crate::error::Error;
use crate::foam::{FoamCalibration, FoamCoverage};

use super::OceanState;

impl OceanState {
    /// The foam of the whole ocean in [0, 1] — active whitecaps and residual foam together,
    /// a + r(1 − a) — on the grid of cascade 0 (the largest): index j·N + i is its grid point
    /// (i·L/N, j·L/N), and the field tiles the plane with that cascade's period L. Only
    /// cascade 0's textures carry foam ([`OceanState::pack_texels`]).
    pub fn foam(&self) -> &[f32] {
        self.foam.total()
    }

    /// Active whitecap foam a in [0, 1] on the foam grid (see [`foam`](Self::foam)): foam of
    /// waves breaking now or within about [`FoamConfig::active_decay`](crate::FoamConfig::active_decay).
    pub fn active_foam(&self) -> &[f32] {
        self.foam.active()
    }

    /// Residual foam r in [0, 1] on the foam grid (see [`foam`](Self::foam)): older foam that
    /// has aged out of the active whitecaps, drifting and stretched into streaks.
    pub fn residual_foam(&self) -> &[f32] {
        self.foam.residual()
    }

    /// The breaking intensity s ≥ 0 in 1/s at the current time on the foam grid (see
    /// [`foam`](Self::foam)): how fast the surface around each point starts to break — new
    /// breaking per second, as a fraction of the area, plus the area breaking now over τ_A —
    /// and so how fast active foam is injected there (it grows at s·(1 − a)). Large on the
    /// compressed crests of the largest waves, where the smaller ones break on top of them;
    /// near zero elsewhere. For spray particles and the sound of breaking waves.
    pub fn breaking(&self) -> &[f32] {
        self.foam.breaking()
    }

    /// The breaking intensity in 1/s at the undisplaced world point (`x`, `z`) (any finite
    /// coordinates: the foam grid wraps with cascade 0's period), interpolated bilinearly
    /// from [`breaking`](Self::breaking). For a point of the displaced surface, find its
    /// undisplaced point with [`locate`](Self::locate) first.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn breaking_at(&self, x: f64, z: f64) -> Result<f32, Error> {
        for (name, value) in [("x", x), ("z", z)] {
            if !value.is_finite() {
                return Err(Error::NonFinite { name });
            }
        }
        Ok(self.foam.breaking_at(x, z))
    }

    /// The foam at the undisplaced world point (`x`, `z`) (any finite coordinates), patterned
    /// at the finest breaking scale: the active whitecaps a, the residual foam not under them
    /// r·(1 − a), and all foam, each in [0, 1] — white (1) on foam, 0 on water, with soft
    /// edges — so that their means over a stretch of sea are the fractions of
    /// [`foam_coverage`](Self::foam_coverage). Whitecaps lie where the finer cascades
    /// compress the surface most (their Jacobians), as many of them as the coarse active foam
    /// on the foam grid ([`active_foam`](Self::active_foam)) says; residual foam lies in thin
    /// streaks along the wind, as much as the coarse residual foam says, carried with the
    /// water (its wind drift, and the orbital motion of the undisplaced point itself) and
    /// fading with it (docs/theory.md, §15.8). [`sample`](Self::sample)'s `foam` is the
    /// coarse coverage, the expectation of this `total`. To draw fresh whitecaps apart from
    /// older foam, or for a point of the displaced surface after [`locate`](Self::locate).
    ///
    /// ```
    /// use ocean_fft::{OceanConfig, OceanState, Spectrum};
    /// let config = OceanConfig { size: 32, ..OceanConfig::default() };
    /// let mut ocean = OceanState::new(Spectrum::jonswap(20.0, 300_000.0)?, config)?;
    /// ocean.pre_roll(20.0, 0.1)?;
    /// let foam = ocean.foam_at(40.0, -12.0)?;
    /// assert!((foam.active + foam.residual - foam.total).abs() < 1e-6);
    /// assert!((0.0..=1.0).contains(&foam.total));
    /// # Ok::<(), ocean_fft::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn foam_at(&self, x: f64, z: f64) -> Result<FoamCoverage, Error> {
        for (name, value) in [("x", x), ("z", z)] {
            if !value.is_finite() {
                return Err(Error::NonFinite { name });
            }
        }
        Ok(self.foam.detail_at(&self.cascades, x, z))
    }

    /// The area fractions covered by active whitecaps, residual foam and all foam (summed in
    /// a fixed order over the foam grid when the foam last changed; costs nothing here).
    pub fn foam_coverage(&self) -> FoamCoverage {
        self.foam.coverage()
    }

    /// The whitecap calibration of this ocean: the breaking threshold, the target coverage and
    /// what the statistics of the sea predict.
    pub fn foam_calibration(&self) -> FoamCalibration {
        self.foam.calibration()
    }
}
