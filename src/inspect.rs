//! Verification and tooling: what the crate's own tests check it with, and what tools that
//! study a sea read. A game needs none of it.
//!
//! - [`Fft2d`]: the packed 2D inverse FFT the cascades run, on its own (with [`Complex32`],
//!   rustfft's complex type).
//! - A cascade's spectral views: the evolved spectrum h̃(k, t) ([`wave_spectrum`]), the
//!   frequency of each wave vector ([`omega_at`]), any of the eight synthesised [`Field`]s
//!   ([`field`]) and the raw packed transforms ([`packed_transform`]). These allocate.
//! - Diagnostics a few methods return: [`LoopError`] (how far a repeat period moved the
//!   frequencies), [`FoamCalibration`] (the whitecap threshold and what the sea's statistics
//!   predict), [`SlopeVariance`] (the slope variance the grids cannot show).
//! - The physical constants of the capillary dispersion, [`SURFACE_TENSION`] and
//!   [`WATER_DENSITY`] (the gravity [`GRAVITY`](crate::GRAVITY) is at the crate root).
//!
//! ```
//! use ocean_fft::inspect::{self, Field};
//! use ocean_fft::{Cascade, CascadeConfig, Spectrum};
//!
//! let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
//! let mut cascade = Cascade::new(&spectrum, CascadeConfig { size: 16, ..Default::default() })?;
//! cascade.update(2.5)?;                                       // s
//! let spectrum_now = inspect::wave_spectrum(&cascade, 2.5)?;  // h̃(k, 2.5 s), FFT order
//! let eta = inspect::field(&cascade, Field::Height);          // m, before the mean level
//! assert_eq!(spectrum_now.len(), 16 * 16);
//! // The height buffer is η plus the mean-level correction.
//! let offset = cascade.mean_level_offset();
//! assert!(eta.iter().zip(cascade.height()).all(|(e, h)| (e + offset - h).abs() < 1e-6));
//! # Ok::<(), ocean_fft::Error>(())
//! ```

pub use crate::cascade::{Field, LoopError};
pub use crate::dispersion::{SURFACE_TENSION, WATER_DENSITY};
pub use crate::fft2d::Fft2d;
pub use crate::ocean::FoamCalibration;
pub use crate::spectrum::SlopeVariance;
pub use num_complex::Complex32;

use crate::cascade::Cascade;
use crate::error::Error;

/// The evolved spectrum h̃(k, t) = h0(k)e^{−iωt} + conj(h0(−k))e^{iωt} of `cascade` in m, in
/// its grid's FFT order (index j·N + i holds k = Δk·(m(i), m(j))), computed afresh in f64 at
/// time `t` in seconds. Its unnormalised inverse DFT is the height field at `t`.
///
/// # Errors
/// [`Error::NonFinite`] or [`Error::OutOfRange`] for `t` outside
/// ±[`Cascade::MAX_TIME`], as [`Cascade::update`].
pub fn wave_spectrum(cascade: &Cascade, t: f64) -> Result<Vec<Complex32>, Error> {
    cascade.wave_spectrum(t)
}

/// Angular frequency ω(k) in rad/s that `cascade` evolves the wave vector at spectral index
/// (i, j) with, k = Δk·(m(i), m(j)) (quantised when looping; 0 on the Nyquist row and column,
/// which hold no wave).
///
/// # Errors
/// [`Error::IndexOutOfRange`] unless `i` and `j` are below N.
pub fn omega_at(cascade: &Cascade, i: usize, j: usize) -> Result<f64, Error> {
    cascade.omega_at(i, j)
}

/// One of the eight real fields of `cascade` at its last update, in metres or
/// dimensionless as [`Field`] says, in buffer order (index j·N + i), the displacement fields
/// per unit choppiness. Its packed transform is finished afresh from the update's first
/// pass, to the same bits the update's outputs were computed from.
pub fn field(cascade: &Cascade, field: Field) -> Vec<f32> {
    cascade.field(field)
}

/// The raw result of packed transform `transform` (0..4) of `cascade` at its last update,
/// in buffer order: real part field 2·`transform`, imaginary part field 2·`transform` + 1 of
/// [`Field::ALL`] (see [`Field::packing`]).
///
/// # Errors
/// [`Error::IndexOutOfRange`] unless `transform` < 4.
pub fn packed_transform(cascade: &Cascade, transform: usize) -> Result<Vec<Complex32>, Error> {
    cascade.packed_transform(transform)
}
