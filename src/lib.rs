//! # ocean-fft
//!
//! A pure-CPU simulation of the open-ocean surface with Tessendorf's statistical FFT method and
//! calibrated oceanographic spectra.
//!
//! ```
//! use ocean_fft::{Spectrum, Spreading, Vec2};
//!
//! let spectrum = Spectrum::jonswap(10.0, 100_000.0)?   // U10 [m/s], fetch [m]
//!     .with_wind_direction(0.3)?                       // rad, toward which the wind blows
//!     .with_spreading(Spreading::DonelanBanner)?;
//! let hs = spectrum.significant_wave_height();         // m
//! let s = spectrum.density(Vec2::new(0.1, 0.03));      // S(k) in m⁴
//! assert!(hs > 2.0 && hs < 2.3 && s > 0.0);
//! # Ok::<(), ocean_fft::Error>(())
//! ```
//!
//! # Conventions
//!
//! - Right-handed, **y up**; the sea surface is the (x, z) plane. Horizontal vectors are
//!   [`Vec2`] holding **(x, z)**; 3-vectors are [`Vec3`] (x, y, z).
//! - Angles in radians. A direction θ is the unit vector (cos θ, sin θ) in (x, z). The wind
//!   direction is the direction the wind blows **toward**; waves travel downwind.
//! - SI units: metres, seconds, rad/s, m/s; g = 9.81 m/s² ([`GRAVITY`]).
//! - Spectra: S(ω) in m²·s/rad, D(ω, θ) in 1/rad with ∫D dθ = 1, S(k) in m⁴ with
//!   ∫∫S(k) d²k the surface variance and H_s = 4√m0.
//!
//! The formulas, their sources and the choices made where sources differ are in the
//! repository's `docs/theory.md`.
#![warn(missing_docs)]

mod cascade;
mod dispersion;
mod error;
mod fft2d;
mod ocean;
mod presets;
mod sampling;
mod seed;
mod spectrum;

pub use cascade::{Cascade, CascadeConfig, Field, MAX_TIME};
pub use dispersion::{Dispersion, GRAVITY, SURFACE_TENSION, WATER_DENSITY};
pub use error::Error;
pub use fft2d::Fft2d;
pub use glam::{Vec2, Vec3};
pub use num_complex::Complex32;
pub use ocean::{FoamConfig, OceanConfig, OceanState, BAND_SPLIT, MAX_STEP};
pub use presets::SeaState;
pub use sampling::{SurfaceSample, HEIGHT_AT_MAX_ITERATIONS, HEIGHT_AT_TOLERANCE};
pub use spectrum::{DepthFactor, Spectrum, Spreading, DEFAULT_GAMMA, MAX_WIND_SPEED};

/// Largest supported grid size N (a cascade holds about 40·N² bytes per field set).
pub const MAX_SIZE: usize = 4096;
