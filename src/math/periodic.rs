//! Periodic grids: the cell of a world coordinate on an N×N grid that tiles the plane (its
//! wrap, exact in f64) and bilinear interpolation between the cell's four samples.

use glam::Vec2;

/// Bilinear weights and the four sample indices of a grid cell on a periodic N×N grid (for
/// the foam).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Stencil {
    pub(crate) index: [usize; 4],
    pub(crate) weight: [f32; 4],
}

/// The grid cell (ix, iz) of world point (x, z) on a periodic N×N grid of side `length`, and
/// the fractions (fx, fz) in [0, 1] of the way across it, wrapped in f64.
#[inline(always)]
fn cell(x: f64, z: f64, length: f64, n: usize) -> (usize, f32, usize, f32) {
    cell_on(x, z, &Period::new(length, n))
}

/// A periodic grid's side L (m), 1/L and cells per metre N/L, and N: what [`cell_on`] needs,
/// computed once.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Period {
    pub(crate) length: f64,
    pub(crate) inverse: f64,
    pub(crate) cells: f64,
    pub(crate) n: usize,
}

impl Period {
    pub(crate) fn new(length: f64, n: usize) -> Period {
        Period {
            length,
            inverse: 1.0 / length,
            cells: n as f64 / length,
            n,
        }
    }
}

/// [`cell`] on a [`Period`].
#[inline(always)]
pub(crate) fn cell_on(x: f64, z: f64, period: &Period) -> (usize, f32, usize, f32) {
    let Period {
        length,
        inverse,
        cells,
        n,
    } = *period;
    let gx = wrap(x, length, inverse) * cells;
    let gz = wrap(z, length, inverse) * cells;
    let (ix, fx) = split(gx, n);
    let (iz, fz) = split(gz, n);
    (ix, fx, iz, fz)
}

impl Stencil {
    #[inline(always)]
    pub(crate) fn new((ix, fx, iz, fz): (usize, f32, usize, f32), n: usize) -> Stencil {
        let ix1 = (ix + 1) % n;
        let iz1 = (iz + 1) % n;
        Stencil {
            index: [iz * n + ix, iz * n + ix1, iz1 * n + ix, iz1 * n + ix1],
            weight: [
                (1.0 - fx) * (1.0 - fz),
                fx * (1.0 - fz),
                (1.0 - fx) * fz,
                fx * fz,
            ],
        }
    }

    #[inline(always)]
    pub(crate) fn scalar(&self, values: &[f32]) -> f32 {
        let [a, b, c, d] = std::array::from_fn(|c| values[self.index[c]] * self.weight[c]);
        // In this order in the batches' lanes too.
        ((a + b) + c) + d
    }

    #[inline(always)]
    pub(crate) fn vector(&self, values: &[[f32; 2]]) -> Vec2 {
        (0..4)
            .map(|c| Vec2::from_array(values[self.index[c]]) * self.weight[c])
            .sum()
    }
}

/// Periodic bilinear interpolation of `values`, a field on an N×N grid of side `length` m
/// (grid point (i, j) at (i, j)·`length`/N, index j·N + i), at world (x, z).
#[inline(always)]
pub(crate) fn periodic_bilinear(values: &[f32], n: usize, length: f64, x: f64, z: f64) -> f32 {
    Stencil::new(cell(x, z, length, n), n).scalar(values)
}

/// Periods from the origin from which [`wrap`] falls back on `rem_euclid` (see there).
pub(crate) const FAR_PERIODS: f64 = (1u64 << 29) as f64;

/// `x` modulo `length` (> 0, `inverse` its reciprocal), in [0, `length`]:
/// `x.rem_euclid(length)` without its software `fmod`, which costs more than a query's
/// arithmetic. Below 2²⁹ periods q = ⌊x/L⌋ times an f32 length is exact in f64 and so is
/// x − qL (at most two periods, on x's grid of ulps), so the remainder is exact; a q one off
/// by the rounding of x·(1/L) is corrected.
#[inline(always)]
pub(crate) fn wrap(x: f64, length: f64, inverse: f64) -> f64 {
    let periods = (x * inverse).floor();
    if periods.abs() >= FAR_PERIODS {
        return x.rem_euclid(length);
    }
    let r = x - periods * length;
    if r < 0.0 {
        r + length
    } else if r >= length {
        r - length
    } else {
        r
    }
}

/// Integer cell and fraction of grid coordinate `g` in [0, n]; rounding can give exactly n,
/// which wraps to cell 0.
#[inline(always)]
fn split(g: f64, n: usize) -> (usize, f32) {
    let cell = g.floor();
    let fraction = (g - cell) as f32;
    // g ≤ n (a subtraction, not `%`: an integer division costs more than the spline).
    let cell = cell as usize;
    (if cell >= n { cell - n } else { cell }, fraction)
}
