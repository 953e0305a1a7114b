//! The stage after the cascades, beside the world queries: the foam, which reads the cascades'
//! surface and which the ocean steps. One field for the whole ocean on the largest cascade's grid,
//! injected where the summed surface breaks (its Jacobian below a threshold calibrated against the
//! whitecap fraction of Monahan & O'Muircheartaigh 1980), aging from active whitecaps into residual
//! foam, drifting downwind and spreading into streaks (docs/theory.md, §15).

mod calibration;
mod change;
mod config;
mod detail;
mod intensity;
mod model;
mod moments;
mod rows;
mod state;
mod streaks;
#[cfg(test)]
mod tests;
mod transport;
pub(crate) mod view;

pub use calibration::FoamCalibration;
pub use config::FoamConfig;
pub(crate) use state::{memory_bytes, Foam};
pub use streaks::FoamStreaks;
pub use view::FoamView;

/// How much of the surface is covered by foam: area fractions in [0, 1], each grid point
/// counted with the fraction of it that is covered (the foam value there), summed in a fixed
/// order (so the numbers do not depend on the number of threads).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FoamCoverage {
    /// Active whitecaps: foam of waves breaking now or within about the active lifetime τ_A
    /// ([`FoamConfig::active_decay`]) — the mean of [`FoamView::active`]. The whitecap
    /// fraction the calibration aims at.
    pub active: f32,
    /// Residual foam not under active foam: the mean of r·(1 − a), older foam and streaks
    /// that photographs of whitecaps leave out.
    pub residual: f32,
    /// All foam: the mean of [`FoamView::total`](crate::FoamView::total), `active + residual`.
    pub total: f32,
}
