//! The foam of an ocean as a game reads it ([`FoamView`]): its fields, the foam and breaking
//! at a point, the coverage and the calibration.

use super::calibration::FoamCalibration;
use super::state::Foam;
use super::FoamCoverage;
use crate::cascade::Cascade;
use crate::coast::Coast;
use crate::error::Error;

/// The foam of an ocean, read-only: what
/// [`OceanState::foam_view`](crate::OceanState::foam_view) returns. One field for the whole
/// ocean on the grid of cascade 0 (the largest): index j·N + i of each slice is its grid
/// point (i·L/N, j·L/N) in metres, and the field tiles the plane with that cascade's period
/// L. Only cascade 0's textures carry foam
/// ([`OceanState::textures`](crate::OceanState::textures)). Borrows the ocean; `Copy`;
/// allocates nothing.
///
/// ```
/// use ocean_fft::{OceanConfig, OceanState, Spectrum};
/// let config = OceanConfig { size: 32, ..OceanConfig::default() };
/// let mut ocean = OceanState::new(Spectrum::jonswap(20.0, 300_000.0)?, config)?;
/// ocean.pre_roll(20.0, 0.1)?;
/// let foam = ocean.foam_view();
/// let here = foam.foam_at(40.0, -12.0)?;            // at rest point (x0, z0) in m
/// assert!((here.active + here.residual - here.total).abs() < 1e-6);
/// let fraction = ocean.water().at_rest(40.0, -12.0)?.foam; // the coarse coverage there
/// assert!((0.0..=1.0).contains(&here.total) && (0.0..=1.0).contains(&fraction));
/// assert!(foam.coverage().active > 0.0);            // whitecaps somewhere
/// # Ok::<(), ocean_fft::Error>(())
/// ```
#[derive(Clone, Copy)]
pub struct FoamView<'a> {
    foam: &'a Foam,
    /// The ocean's cascades: the finer ones place the foam's detail.
    cascades: &'a [Cascade],
    /// The foam the wake window adds, with an ocean's wakes.
    extra: Option<&'a dyn ExtraFoam>,
    /// The ocean's coast and its time (s), with a depth map.
    coast: Option<(&'a Coast, f64)>,
}

/// Foam added to the ocean's at a rest point: the wake window's trail, where the water of
/// that point lands.
pub(crate) trait ExtraFoam: Sync {
    /// The extra foam in [0, 1] at the rest point (`x0`, `z0`) (m, finite), laid over the
    /// ocean's as residual foam.
    fn trail_at(&self, x0: f64, z0: f64) -> f32;
}

impl std::fmt::Debug for FoamView<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FoamView")
            .field("size", &self.foam.n)
            .field("length", &self.foam.length)
            .field("coverage", &self.foam.coverage())
            .finish_non_exhaustive()
    }
}

impl<'a> FoamView<'a> {
    /// The view of `foam` on the ocean of `cascades`, with the `extra` foam of its wakes.
    pub(crate) fn new(
        foam: &'a Foam,
        cascades: &'a [Cascade],
        extra: Option<&'a dyn ExtraFoam>,
        coast: Option<(&'a Coast, f64)>,
    ) -> FoamView<'a> {
        FoamView {
            foam,
            cascades,
            extra,
            coast,
        }
    }

    /// All foam in [0, 1] — active whitecaps and residual foam together, a + r(1 − a) — on
    /// the foam grid (the slice a shader gets in cascade 0's texels).
    pub fn total(&self) -> &'a [f32] {
        self.foam.total()
    }

    /// Active whitecap foam a in [0, 1] on the foam grid: foam of waves breaking now or
    /// within about [`FoamConfig::active_decay`](crate::FoamConfig::active_decay).
    pub fn active(&self) -> &'a [f32] {
        self.foam.active()
    }

    /// Residual foam r in [0, 1] on the foam grid: older foam that has aged out of the
    /// active whitecaps, drifting and stretched into streaks.
    pub fn residual(&self) -> &'a [f32] {
        self.foam.residual()
    }

    /// The breaking intensity s ≥ 0 in 1/s at the current time on the foam grid: how fast
    /// the surface around each point starts to break — new breaking per second, as a
    /// fraction of the area, plus the area breaking now over τ_A — and so how fast active
    /// foam is injected there (it grows at s·(1 − a)). Large on the compressed crests of the
    /// largest waves, where the smaller ones break on top of them; near zero elsewhere. For
    /// spray particles and the sound of breaking waves.
    pub fn breaking(&self) -> &'a [f32] {
        self.foam.breaking()
    }

    /// The foam at the rest (undisplaced) point (`x0`, `z0`) in metres (any finite
    /// coordinates), patterned at the finest breaking scale: the active whitecaps a, the
    /// residual foam not under them r·(1 − a), and all foam, each in [0, 1] — white (1) on
    /// foam, 0 on water, with soft edges — so that their means over a stretch of sea are the
    /// fractions of [`coverage`](Self::coverage). Whitecaps lie where the finer cascades
    /// compress the surface most (their Jacobians), as many as the coarse active foam on the
    /// foam grid ([`active`](Self::active)) says; residual foam lies in thin streaks along the
    /// wind, as much as the coarse residual foam says, carried with the water (its wind
    /// drift, and the orbital motion of the rest point itself) and fading with it
    /// (docs/theory.md, §15.8). [`Water::at_rest`](crate::Water::at_rest)'s `foam` (and a
    /// [`Surface`](crate::Surface)'s) is the coarse coverage, the expectation of this
    /// `total`. To draw fresh whitecaps apart from older foam; for a world point, find its
    /// rest point with [`Water::locate`](crate::Water::locate) first.
    /// With [`OceanConfig::wakes`](crate::OceanConfig::wakes), the wake's foam trail where
    /// that point's water lands is part of the residual foam and of the total (the fields of
    /// this view are the ocean's alone; the trail's is [`Wakes::foam`](crate::Wakes::foam)).
    /// Over a depth map ([`OceanState::set_depth_map`](crate::OceanState::set_depth_map))
    /// the whitecaps and residual foam fade where the waves die (cascade 0's factor below
    /// 1, land), and the surf is active foam: the coarse active fraction there is at least
    /// the fraction Q_b of waves breaking on the bottom
    /// ([`CoastField::breaking`](crate::CoastField::breaking)), patterned like the
    /// whitecaps, so that its mean along the beach follows Q_b.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn foam_at(&self, x0: f64, z0: f64) -> Result<FoamCoverage, Error> {
        check_point(x0, z0)?;
        let mut foam = self.foam.detail_at(self.cascades, x0, z0, self.coast);
        if let Some(extra) = self.extra {
            let trail = extra.trail_at(x0, z0);
            if trail > 0.0 {
                foam.total += trail * (1.0 - foam.total);
                foam.residual = (foam.total - foam.active).max(0.0);
            }
        }
        Ok(foam)
    }

    /// The breaking intensity in 1/s at the rest (undisplaced) point (`x0`, `z0`) in metres
    /// (any finite coordinates: the foam grid wraps with cascade 0's period), interpolated
    /// bilinearly from [`breaking`](Self::breaking). For a world point, find its rest point
    /// with [`Water::locate`](crate::Water::locate) first.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn breaking_at(&self, x0: f64, z0: f64) -> Result<f32, Error> {
        check_point(x0, z0)?;
        Ok(self.foam.breaking_at(x0, z0))
    }

    /// The area fractions covered by active whitecaps, residual foam and all foam (summed in
    /// a fixed order over the foam grid when the foam last changed; costs nothing here): the
    /// open sea's, calibrated against measured whitecap coverage. A depth map does not change
    /// it; the surf's coverage over the map is the mean of
    /// [`CoastField::breaking`](crate::CoastField::breaking) there, which
    /// [`foam_at`](Self::foam_at) draws.
    pub fn coverage(&self) -> FoamCoverage {
        self.foam.coverage()
    }

    /// How [`foam_at`](Self::foam_at) places the whitecaps inside a cell, for a shader that
    /// draws them alike: weight ŵ_c of cascade c (dimensionless), so that
    /// Σ_c ŵ_c (1 − J_c), with J_c each cascade's Jacobian (the `J` of its
    /// `SlopeJacobianFoam` texels), is the placement field with unit variance at the grid
    /// nodes. Whitecaps are white where it passes the normal quantile of 1 − a, a the cell's
    /// active fraction. Cascade 0 (whose compression sets a) and entries past the cascades
    /// are 0; the finer cascades are weighted toward the compression of the waves that make
    /// visible whitecaps, about 0.16 peak wavelengths and longer (docs/theory.md §15.8). All
    /// 0 without finer cascades, choppiness or waves.
    pub fn whitecap_weights(&self) -> [f32; crate::cascade::MAX_CASCADES] {
        let variance = self.foam.sea.unresolved_compression();
        self.foam.detail.placement(self.cascades, variance)
    }

    /// The whitecap calibration of this ocean: the breaking threshold, the target coverage
    /// and what the statistics of the sea predict.
    pub fn calibration(&self) -> FoamCalibration {
        self.foam.calibration()
    }
}

/// Checks a point: both coordinates finite, the error naming `x` or `z` as the ocean's
/// foam queries always have.
fn check_point(x: f64, z: f64) -> Result<(), Error> {
    for (name, value) in [("x", x), ("z", z)] {
        if !value.is_finite() {
            return Err(Error::NonFinite { name });
        }
    }
    Ok(())
}
