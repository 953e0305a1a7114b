//! The 4×4 stencil of a point in a tile: the cubic B-spline weights (on one point or eight in
//! lanes) and the sums over the taps of the displacement, the height and the slope, with the
//! displacement's derivatives.

use super::{TileData, HEIGHT, SLOPE, STRIDE};
use crate::math::simd::{baseline_lanes, Simd};

/// What the spline weights are computed on: an `f32`, or eight of them in lanes (one
/// point each, [`Lanes`]); the same operations in the same order either way, so each lane
/// holds the bits of the scalar formula.
pub(crate) trait Real:
    Copy
    + From<f32>
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::Mul<Output = Self>
{
}

impl Real for f32 {}

/// Eight `f32`, one a lane, with elementwise arithmetic (written as loops over arrays, which
/// the compiler turns into vector instructions at each SIMD level).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Lanes(pub(crate) [f32; 8]);

impl From<f32> for Lanes {
    #[inline(always)]
    fn from(value: f32) -> Lanes {
        Lanes([value; 8])
    }
}

impl std::ops::Add for Lanes {
    type Output = Lanes;
    #[inline(always)]
    fn add(self, other: Lanes) -> Lanes {
        Lanes(std::array::from_fn(|l| self.0[l] + other.0[l]))
    }
}

impl std::ops::Sub for Lanes {
    type Output = Lanes;
    #[inline(always)]
    fn sub(self, other: Lanes) -> Lanes {
        Lanes(std::array::from_fn(|l| self.0[l] - other.0[l]))
    }
}

impl std::ops::Mul for Lanes {
    type Output = Lanes;
    #[inline(always)]
    fn mul(self, other: Lanes) -> Lanes {
        Lanes(std::array::from_fn(|l| self.0[l] * other.0[l]))
    }
}

impl Real for Lanes {}

/// Cubic B-spline weights of the taps at offsets −1, 0, 1, 2 from the cell's node, for the
/// fraction `t` ∈ [0, 1] of the way to the next node. They sum to 1; at t = 0 they are
/// (1, 4, 1, 0)/6.
#[inline(always)]
pub(crate) fn weights<T: Real>(t: T) -> [T; 4] {
    // × 1/6 rather than ÷ 6: a division costs ten multiplications' time.
    let sixth = T::from(1.0 / 6.0);
    let [one, three, four, six] = [1.0, 3.0, 4.0, 6.0].map(T::from);
    let s = one - t;
    let t2 = t * t;
    let t3 = t2 * t;
    [
        s * s * s * sixth,
        (four - six * t2 + three * t3) * sixth,
        (one + three * (t + t2 - t3)) * sixth,
        t3 * sixth,
    ]
}

/// The derivatives of [`weights`] with respect to `t` (per cell; they sum to 0).
#[inline(always)]
pub(crate) fn weight_slopes<T: Real>(t: T) -> [T; 4] {
    let [half, one, one_and_half, two] = [0.5, 1.0, 1.5, 2.0].map(T::from);
    let s = one - t;
    [
        T::from(-0.5) * s * s,
        t * (one_and_half * t - two),
        half + t * (one - one_and_half * t),
        half * t * t,
    ]
}

/// The cubic B-spline weights of a point's 4×4 taps along x and z ([`weights`]), and
/// with `GRADIENT` their derivatives ([`weight_slopes`]; zero without), for the evaluations
/// below.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Weights {
    x: [f32; 4],
    z: [f32; 4],
    dx: [f32; 4],
    dz: [f32; 4],
}

impl Weights {
    /// The weights at fractions (`fx`, `fz`) ∈ [0, 1] of the way across a cell, with their
    /// derivatives if `GRADIENT`.
    #[inline(always)]
    pub(crate) fn new<const GRADIENT: bool>(fx: f32, fz: f32) -> Weights {
        let (dx, dz) = if GRADIENT {
            (weight_slopes(fx), weight_slopes(fz))
        } else {
            ([0.0; 4], [0.0; 4])
        };
        Weights {
            x: weights(fx),
            z: weights(fz),
            dx,
            dz,
        }
    }
}

/// The four taps' weights `w` each twice, for a row of four pairs.
#[inline(always)]
fn paired(w: &[f32; 4]) -> [f32; 8] {
    [w[0], w[0], w[1], w[1], w[2], w[2], w[3], w[3]]
}

/// Σ_t w_t v_t of each pair's component over the four pairs of `v` (pair t at 2t, 2t + 1):
/// taps 0 + 2 and 1 + 3 first, tap 2's and 3's products fused into those sums.
#[inline(always)]
fn weighted_pairs(simd: Simd, w: &[f32; 8], v: &[f32; 8]) -> [f32; 2] {
    let half: [f32; 4] = std::array::from_fn(|l| simd.mul_add(w[l + 4], v[l + 4], w[l] * v[l]));
    [half[0] + half[2], half[1] + half[3]]
}

/// The four rows of four pairs from (`lx`, `lz`) of the field of pairs starting at `start`.
#[inline(always)]
fn pair_rows(tile: &TileData, start: usize, lx: usize, lz: usize) -> [[f32; 8]; 4] {
    std::array::from_fn(|r| {
        let at = start + 2 * ((lz + r) * STRIDE + lx);
        tile[at..at + 8].try_into().expect("four pairs")
    })
}

/// Σ w_x w_z c of a field of pairs starting at `start` in `tile`, over the 4×4 taps from
/// (`lx`, `lz`), and with `GRADIENT` its derivatives along x and z per cell (zero without;
/// the value's operations are the same either way, so its bits are too). Columns first: a
/// row of four taps is one 32-byte vector, S = Σ_r w_z,r · row_r (and with `GRADIENT`
/// Z = Σ_r d_z,r · row_r), then the value is Σ_t w_x,t S_t, the x derivative Σ_t d_x,t S_t
/// and the z derivative Σ_t w_x,t Z_t, each added (tap 0 + tap 2) + (tap 1 + tap 3). With
/// AVX2 the rows are written with pulp's 8-lane operations (the vectoriser, left to itself,
/// paired the lanes badly); the same operations in the same order as the plain code, so the
/// same bits, and the batch queries' lanes (`query/lanes/`) run them too.
#[inline(always)]
fn pairs<const GRADIENT: bool>(
    simd: Simd,
    tile: &TileData,
    start: usize,
    lx: usize,
    lz: usize,
    w: &Weights,
) -> [[f32; 2]; 3] {
    let rows = pair_rows(tile, start, lx, lz);
    let [columns, columns_z] = match simd {
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2(v3) => columns_v3::<GRADIENT>(v3, &rows, w),
        #[cfg(target_arch = "x86_64")]
        Simd::Avx512(v4) => columns_v3::<GRADIENT>(*v4, &rows, w),
        Simd::Baseline { fused } => {
            let mut sum = [0.0f32; 8];
            let mut sum_z = [0.0f32; 8];
            for (r, taps) in rows.iter().enumerate() {
                sum = baseline_lanes(fused, [w.z[r]; 8], *taps, sum);
                if GRADIENT {
                    sum_z = baseline_lanes(fused, [w.dz[r]; 8], *taps, sum_z);
                }
            }
            [sum, sum_z]
        }
    };
    let (wx, dx) = (paired(&w.x), paired(&w.dx));
    [
        weighted_pairs(simd, &wx, &columns),
        weighted_pairs(simd, &dx, &columns),
        weighted_pairs(simd, &wx, &columns_z),
    ]
}

/// [`pairs`]' column sums over the rows with AVX2's 8-lane multiply and add.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn columns_v3<const GRADIENT: bool>(
    v3: pulp::x86::V3,
    rows: &[[f32; 8]; 4],
    w: &Weights,
) -> [[f32; 8]; 2] {
    use pulp::{cast, Simd as _};
    let zero = v3.splat_f32s(0.0);
    let (mut sum, mut sum_z) = (zero, zero);
    for (r, &taps) in rows.iter().enumerate() {
        let taps = cast::<_, pulp::f32x8>(taps);
        sum = v3.mul_add_f32s(v3.splat_f32s(w.z[r]), taps, sum);
        if GRADIENT {
            sum_z = v3.mul_add_f32s(v3.splat_f32s(w.dz[r]), taps, sum_z);
        }
    }
    [cast(sum), cast(sum_z)]
}

/// The displacement `[D_x, D_z]` at a point of the tile's cell (`lx`, `lz`) (its taps are
/// the coefficients `lx..lx + 4` of rows `lz..lz + 4`), and with `GRADIENT` its
/// derivatives along x and z per cell.
#[inline(always)]
pub(crate) fn displacement<const GRADIENT: bool>(
    simd: Simd,
    tile: &TileData,
    lx: usize,
    lz: usize,
    w: &Weights,
) -> [[f32; 2]; 3] {
    pairs::<GRADIENT>(simd, tile, 0, lx, lz, w)
}

/// The slope `[∂y/∂x, ∂y/∂z]` at a point of the tile's cell (`lx`, `lz`).
#[inline(always)]
pub(crate) fn slope(simd: Simd, tile: &TileData, lx: usize, lz: usize, w: &Weights) -> [f32; 2] {
    pairs::<false>(simd, tile, SLOPE, lx, lz, w)[0]
}

/// The height η at a point of the tile's cell (`lx`, `lz`).
#[inline(always)]
pub(crate) fn height(simd: Simd, tile: &TileData, lx: usize, lz: usize, w: &Weights) -> f32 {
    let mut sum = [0.0f32; 4];
    for r in 0..4 {
        let at = HEIGHT + (lz + r) * STRIDE + lx;
        let taps: &[f32; 4] = tile[at..at + 4].try_into().expect("four taps");
        let line: [f32; 4] = std::array::from_fn(|l| w.x[l] * taps[l]);
        for l in 0..4 {
            sum[l] = simd.mul_add(w.z[r], line[l], sum[l]);
        }
    }
    (sum[0] + sum[2]) + (sum[1] + sum[3])
}
