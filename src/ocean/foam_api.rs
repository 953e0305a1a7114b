//! The foam as an [`OceanState`] shows it: the combined field, the [`FoamView`] of the rest
//! (the fields, the foam and breaking at a point, the coverage and the calibration), and the
//! old foam methods, forwarded for a release.

use crate::error::Error;
use crate::foam::view::ExtraFoam;
use crate::foam::{FoamCalibration, FoamCoverage, FoamView};

use super::OceanState;

impl OceanState {
    /// Deprecated: [`FoamView::total`] through [`OceanState::foam_view`] (moved off the
    /// page to leave room for the coasts, issue 41).
    #[deprecated(since = "0.4.0", note = "use `ocean.foam_view().total()`")]
    #[doc(hidden)]
    pub fn foam(&self) -> &[f32] {
        self.foam.total()
    }

    /// The foam in detail: the active and residual fields and the breaking intensity, the
    /// foam and breaking at a point, the coverage and the whitecap calibration (see
    /// [`FoamView`]). Costs nothing.
    #[inline]
    pub fn foam_view(&self) -> FoamView<'_> {
        let wakes = self.wake.as_ref().map(|_| self as &dyn ExtraFoam);
        let coast = self.coast_state().map(|coast| (coast, self.time));
        FoamView::new(&self.foam, &self.cascades, wakes, coast)
    }

    /// Deprecated: [`FoamView::active`] through [`OceanState::foam_view`].
    #[deprecated(since = "0.4.0", note = "use `ocean.foam_view().active()`")]
    #[doc(hidden)]
    pub fn active_foam(&self) -> &[f32] {
        self.foam_view().active()
    }

    /// Deprecated: [`FoamView::residual`] through [`OceanState::foam_view`].
    #[deprecated(since = "0.4.0", note = "use `ocean.foam_view().residual()`")]
    #[doc(hidden)]
    pub fn residual_foam(&self) -> &[f32] {
        self.foam_view().residual()
    }

    /// Deprecated: [`FoamView::breaking`] through [`OceanState::foam_view`].
    #[deprecated(since = "0.4.0", note = "use `ocean.foam_view().breaking()`")]
    #[doc(hidden)]
    pub fn breaking(&self) -> &[f32] {
        self.foam_view().breaking()
    }

    /// Deprecated: [`FoamView::breaking_at`] through [`OceanState::foam_view`].
    ///
    /// # Errors
    /// As [`FoamView::breaking_at`].
    #[deprecated(since = "0.4.0", note = "use `ocean.foam_view().breaking_at(x0, z0)`")]
    #[doc(hidden)]
    pub fn breaking_at(&self, x: f64, z: f64) -> Result<f32, Error> {
        self.foam_view().breaking_at(x, z)
    }

    /// Deprecated: [`FoamView::foam_at`] through [`OceanState::foam_view`].
    ///
    /// # Errors
    /// As [`FoamView::foam_at`].
    #[deprecated(since = "0.4.0", note = "use `ocean.foam_view().foam_at(x0, z0)`")]
    #[doc(hidden)]
    pub fn foam_at(&self, x: f64, z: f64) -> Result<FoamCoverage, Error> {
        self.foam_view().foam_at(x, z)
    }

    /// Deprecated: [`FoamView::coverage`] through [`OceanState::foam_view`].
    #[deprecated(since = "0.4.0", note = "use `ocean.foam_view().coverage()`")]
    #[doc(hidden)]
    pub fn foam_coverage(&self) -> FoamCoverage {
        self.foam_view().coverage()
    }

    /// Deprecated: [`FoamView::calibration`] through [`OceanState::foam_view`].
    #[deprecated(since = "0.4.0", note = "use `ocean.foam_view().calibration()`")]
    #[doc(hidden)]
    pub fn foam_calibration(&self) -> FoamCalibration {
        self.foam_view().calibration()
    }
}

/// The wake's foam trail where the water of a rest point lands (the ocean's displacement
/// there; the wake moves the water up and down only).
impl ExtraFoam for OceanState {
    fn trail_at(&self, x0: f64, z0: f64) -> f32 {
        let Some(wakes) = self.wakes() else {
            return 0.0;
        };
        self.water().at_rest(x0, z0).map_or(0.0, |sample| {
            let [dx, dz] = sample.displacement;
            wakes.foam_at(x0 + f64::from(dx), z0 + f64::from(dz))
        })
    }
}
