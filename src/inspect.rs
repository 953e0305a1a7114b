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
//! - [`BitHash`]: a hash of numbers' bit patterns that is the same on every platform and
//!   release, to check that two runs computed the same bits.
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
pub use crate::foam::FoamCalibration;
pub use crate::math::fft2d::Fft2d;
pub use crate::spectrum::dispersion::{SURFACE_TENSION, WATER_DENSITY};
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

/// A 64-bit FNV-1a hash (Fowler, Noll & Vo) of numbers' bit patterns, fed as little-endian
/// bytes: the same value on every platform, toolchain and release, unlike std's
/// `DefaultHasher`. For checking that two runs computed the same bits — two thread counts,
/// two machines in [`Determinism::CrossPlatform`](crate::Determinism::CrossPlatform), a
/// server and its clients in lockstep, a replay against the original. It detects change; it
/// is no defence against someone forging a collision.
///
/// ```
/// use ocean_fft::inspect::BitHash;
/// use ocean_fft::{OceanConfig, OceanState, Spectrum};
///
/// let config = OceanConfig { size: 16, ..OceanConfig::default() };
/// let mut ocean = OceanState::new(Spectrum::jonswap(10.0, 100_000.0)?, config)?;
/// ocean.step(0.5)?;
/// let mut hash = BitHash::new();
/// for cascade in ocean.cascades() {
///     hash.f32s(cascade.height().iter().copied());
/// }
/// let mine = hash.finish();                 // send to the server, compare with its own
/// assert_ne!(mine, BitHash::new().finish());
/// # Ok::<(), ocean_fft::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct BitHash(u64);

impl Default for BitHash {
    fn default() -> Self {
        Self::new()
    }
}

impl BitHash {
    /// The hash of nothing (FNV-1a's offset basis).
    pub fn new() -> Self {
        BitHash(0xcbf2_9ce4_8422_2325)
    }

    /// Feeds `bytes`.
    pub fn bytes(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    /// Feeds the bit patterns of `values` (4 little-endian bytes each).
    pub fn f32s(&mut self, values: impl IntoIterator<Item = f32>) {
        for v in values {
            self.bytes(&v.to_bits().to_le_bytes());
        }
    }

    /// Feeds the bit patterns of `values` (8 little-endian bytes each).
    pub fn f64s(&mut self, values: impl IntoIterator<Item = f64>) {
        for v in values {
            self.bytes(&v.to_bits().to_le_bytes());
        }
    }

    /// The hash of everything fed so far.
    pub fn finish(&self) -> u64 {
        self.0
    }
}

#[cfg(test)]
mod tests {
    use super::BitHash;

    /// The published FNV-1a 64-bit test vectors (Fowler, Noll & Vo; IETF draft
    /// draft-eastlake-fnv): "" → cbf29ce484222325, "a" → af63dc4c8601ec8c,
    /// "foobar" → 85944171f73967e8.
    #[test]
    fn bit_hash_is_fnv_1a_64() {
        let of = |bytes: &[u8]| {
            let mut hash = BitHash::new();
            hash.bytes(bytes);
            hash.finish()
        };
        assert_eq!(of(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(of(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(of(b"foobar"), 0x8594_4171_f739_67e8);
        // A value's bit pattern goes in as its little-endian bytes.
        let mut value = BitHash::new();
        value.f32s([1.0]);
        assert_eq!(value.finish(), of(&1.0f32.to_bits().to_le_bytes()));
    }
}
