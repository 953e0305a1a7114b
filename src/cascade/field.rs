//! [`Field`]: the eight real fields a cascade synthesises and their spectral multipliers.

use glam::Vec2;
use num_complex::Complex32;

/// The eight real fields a cascade synthesises, for [`Cascade::field`]. Each is the inverse
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

    /// Which packed transform holds this field and whether it is the imaginary part.
    /// Transform p holds fields 2p (real part) and 2p + 1 (imaginary part) of [`Field::ALL`].
    pub fn packing(self) -> (usize, bool) {
        let index = Field::ALL.iter().position(|&f| f == self).unwrap_or(0);
        (index / 2, index % 2 == 1)
    }

    /// The spectral multiplier of this field at wave vector `k` = (k_x, k_z) in rad/m
    /// (0 at k = 0).
    pub fn multiplier(self, k: Vec2) -> Complex32 {
        let (kx, kz) = (k.x, k.y);
        let len = kx.hypot(kz);
        if len == 0.0 {
            return Complex32::new(0.0, 0.0);
        }
        match self {
            Field::Height => Complex32::new(1.0, 0.0),
            Field::DisplacementX => Complex32::new(0.0, kx / len),
            Field::DisplacementZ => Complex32::new(0.0, kz / len),
            Field::SlopeX => Complex32::new(0.0, kx),
            Field::SlopeZ => Complex32::new(0.0, kz),
            Field::DisplacementXX => Complex32::new(-kx * kx / len, 0.0),
            Field::DisplacementZZ => Complex32::new(-kz * kz / len, 0.0),
            Field::DisplacementXZ => Complex32::new(-kx * kz / len, 0.0),
        }
    }
}
