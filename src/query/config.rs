//! [`QueryConfig`] and [`Interpolation`]: how the world queries interpolate the cascades and
//! find where the water at a point comes from (passive data and its checks).

use crate::error::{self, Error};

/// How the world queries ([`Water::at_rest`](crate::Water::at_rest) and everything
/// built on it) interpolate each cascade's grid between its points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum Interpolation {
    /// Cubic B-spline through the grid values (Unser, Aldroubi & Eden 1991): exact at the
    /// grid points, C² between them, and its statistics hardly depend on where a point lies
    /// in a cell: averaged over positions it keeps 97 % of the variance of a wave with 4
    /// grid points per wavelength (bilinear keeps 67 %). 16 taps per cascade and field, and
    /// a prefilter of the height, displacement and slope buffers, computed by the first
    /// query after each update, so that a step that is never queried does not pay for it
    /// (its cost is measured in `docs/performance.md`). The default.
    #[default]
    CubicBSpline,
    /// Bilinear between the four surrounding grid points: the cheapest query and no work on
    /// update, but between grid points it loses variance (a wave with 4 points per
    /// wavelength keeps (2 + cos(π/2))/3 = 67 % along its axis, averaged over positions), so
    /// heave and slope statistics depend on the position in a cell.
    Bilinear,
}

/// How the world queries interpolate the cascades and find the undisplaced point whose
/// water lands on a query point (the fixed-point iteration x₀ ← p − D(x₀)).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct QueryConfig {
    /// Most fixed-point iterations, 1 to [`MAX_ITERATIONS`](Self::MAX_ITERATIONS)
    /// (default: `16`).
    pub max_iterations: usize,
    /// Stop once the displaced point lands this close to the query point, in metres, > 0
    /// (default: `1e-4`).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::serde_impls::finite::tolerance")
    )]
    pub tolerance: f32,
    /// How each cascade is interpolated between its grid points (default:
    /// [`Interpolation::CubicBSpline`]; configs saved without it read back with the
    /// default).
    #[cfg_attr(feature = "serde", serde(default))]
    pub interpolation: Interpolation,
}

impl Default for QueryConfig {
    fn default() -> Self {
        QueryConfig {
            max_iterations: 16,
            tolerance: 1e-4,
            interpolation: Interpolation::default(),
        }
    }
}

impl QueryConfig {
    /// Largest accepted `max_iterations`.
    pub const MAX_ITERATIONS: usize = 1000;

    /// Checks both fields.
    ///
    /// # Errors
    /// [`Error::CountOutOfRange`] for `max_iterations`; [`Error::NonFinite`] or
    /// [`Error::OutOfRange`] unless `tolerance` is finite and > 0.
    pub fn validate(&self) -> Result<(), Error> {
        if !(1..=Self::MAX_ITERATIONS).contains(&self.max_iterations) {
            return Err(Error::CountOutOfRange {
                name: "query.max_iterations",
                count: self.max_iterations,
                min: 1,
                max: Self::MAX_ITERATIONS,
            });
        }
        error::positive("query.tolerance", self.tolerance)?;
        Ok(())
    }
}
