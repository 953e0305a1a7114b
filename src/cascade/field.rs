//! [`Field`]: the eight real fields a cascade synthesises and their spectral multipliers.

use num_complex::Complex32;

use crate::error;
use crate::math::determinism::{Math, Std};

/// The eight real fields a cascade synthesises, for [`inspect::field`](crate::inspect::field). Each is the inverse
/// DFT of h̃(k, t) times the multiplier named (k = |k|); the displacement fields are per unit
/// choppiness.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Field {
    /// η, height in m (multiplier 1).
    Height,
    /// D_x in m (multiplier i k_x/k).
    DisplacementX,
    /// D_z in m (multiplier i k_z/k).
    DisplacementZ,
    /// ∂η/∂x of the undisplaced surface, dimensionless (multiplier i k_x).
    SlopeX,
    /// ∂η/∂z of the undisplaced surface, dimensionless (multiplier i k_z).
    SlopeZ,
    /// ∂D_x/∂x, dimensionless (multiplier −k_x²/k).
    DisplacementXX,
    /// ∂D_z/∂z, dimensionless (multiplier −k_z²/k).
    DisplacementZZ,
    /// ∂D_x/∂z = ∂D_z/∂x, dimensionless (multiplier −k_x k_z/k).
    DisplacementXZ,
}

impl Field {
    /// All eight fields, in packing order.
    pub const ALL: [Field; 8] = [
        Field::Height,
        Field::DisplacementX,
        Field::DisplacementZ,
        Field::SlopeX,
        Field::SlopeZ,
        Field::DisplacementXX,
        Field::DisplacementZZ,
        Field::DisplacementXZ,
    ];

    /// Which packed transform holds this field and whether it is the imaginary part:
    /// transform p holds fields 2p (real part) and 2p + 1 (imaginary part) of [`Field::ALL`].
    /// For inspecting [`inspect::packed_transform`](crate::inspect::packed_transform).
    pub fn packing(self) -> (usize, bool) {
        let index = self as usize;
        (index / 2, index % 2 == 1)
    }

    /// The spectral multiplier of this field at wave vector `k` = `[k_x, k_z]` in rad/m,
    /// evaluated in f64 and rounded to f32 (parts beyond ±`f32::MAX` saturate there). 0 at
    /// k = 0, and for a wave vector with a NaN or infinite component (outside the domain).
    pub fn multiplier(self, k: [f32; 2]) -> Complex32 {
        let zero = Complex32::new(0.0, 0.0);
        if !(k[0].is_finite() && k[1].is_finite()) {
            return zero;
        }
        let (kx, kz) = (f64::from(k[0]), f64::from(k[1]));
        let len = Std::hypot(kx, kz);
        if len == 0.0 {
            return zero;
        }
        let (re, im) = match self {
            Field::Height => (1.0, 0.0),
            Field::DisplacementX => (0.0, kx / len),
            Field::DisplacementZ => (0.0, kz / len),
            Field::SlopeX => (0.0, kx),
            Field::SlopeZ => (0.0, kz),
            Field::DisplacementXX => (-kx * kx / len, 0.0),
            Field::DisplacementZZ => (-kz * kz / len, 0.0),
            Field::DisplacementXZ => (-kx * kz / len, 0.0),
        };
        Complex32::new(error::saturate(re), error::saturate(im))
    }
}
