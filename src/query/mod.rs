//! The stage after the cascades and the foam: the world queries, which read both. The surface at a
//! world point (each cascade's fields interpolated by a periodic cubic B-spline, or bilinearly, and
//! summed; the foam bilinearly), the inversion of the horizontal displacement for the water at a
//! point, their batches in vector lanes and on rayon's threads, written once in the [`Water`] view
//! an ocean and a [`Surface`] handle both give, and the frames a handle keeps. The ocean
//! ([`crate::ocean`]) owns the frames and hands out its [`Water`].

pub(crate) mod batch;
pub(crate) mod config;
pub(crate) mod frame;
mod inversion;
mod lanes;
pub(crate) mod point;
pub(crate) mod results;
pub(crate) mod spline;
pub(crate) mod surface;
#[cfg(test)]
mod tests;
pub(crate) mod water;

pub use config::{Interpolation, QueryConfig};
pub use results::{Location, SurfaceSample};
pub use surface::Surface;
pub use water::Water;
