//! # ocean-fft
//!
//! A pure-CPU simulation of the open-ocean surface with Tessendorf's statistical FFT method and
//! calibrated oceanographic spectra.
#![warn(missing_docs)]

mod dispersion;
mod error;
mod spectrum;

pub use dispersion::{Dispersion, GRAVITY, SURFACE_TENSION, WATER_DENSITY};
pub use error::Error;
pub use glam::{Vec2, Vec3};
pub use num_complex::Complex32;
pub use spectrum::{DepthFactor, Spectrum, Spreading, DEFAULT_GAMMA, MAX_WIND_SPEED};

/// Largest supported grid size N (a cascade holds about 40·N² bytes per field set).
pub const MAX_SIZE: usize = 4096;
