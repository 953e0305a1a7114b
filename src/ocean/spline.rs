//! Cubic B-spline interpolation of the cascades' fields for the world queries: the
//! coefficients, computed tile by tile when a query first reads a tile, and the 4×4 stencil
//! of a point (values and derivatives).
//!
//! A field f sampled on the periodic grid is represented as f(x) = Σ_n c\[n\] β³(x/Δ − n),
//! β³ the cubic B-spline. Interpolating the samples means (c\[n−1\] + 4c\[n\] + c\[n+1\])/6 = f\[n\]
//! along each axis, solved by the recursive filter of Unser, Aldroubi & Eden (1991): with
//! the pole z = √3 − 2, a causal pass y\[n\] = f\[n\] + z·y\[n−1\], an anticausal pass
//! c\[n\] = y\[n\] + z·c\[n+1\], and the gain −6z. Its impulse response is √3·z^|m|, so a
//! coefficient depends on the samples around it with a weight that falls by |z| ≈ 0.268 a
//! grid point: a tile's coefficients need only the samples within [`HALO`] points of it.
//! Each pass starts from zero [`HALO`] points outside the tile (wrapping periodically), which
//! drops the terms beyond z¹⁶ of the exact periodic filter: in 2D at most about
//! 20·|z|¹⁷/(1 − |z|) ≈ 5·10⁻⁹ of the largest value of the field, below f32 rounding
//! (6·10⁻⁸), so the coefficients are the exact periodic ones to f32 precision. Every
//! tile is computed the same way from the same samples, so its bits do not depend on which
//! query (or thread) computed it.

use std::sync::OnceLock;

use crate::error::{self, Error};
use crate::simd::{Kernel, Simd};

/// The pole √3 − 2 of the cubic B-spline's interpolation filter.
const POLE: f32 = -0.267_949_2;
/// Gain −6z of the two passes together: 1/(1 − z)² times it is 1, so constants pass.
const GAIN: f32 = 1.607_695_2;
/// Cells along each side of a tile (fewer on grids smaller than this).
pub(crate) const TILE: usize = 32;
/// Samples each pass runs through before it reaches the tile: |z|¹⁷ ≈ 2·10⁻¹⁰ (see the
/// module's docs).
const HALO: usize = 16;
/// Coefficients along each side of a stored tile: its cells and the stencil's reach of one
/// before and two after, so that every point of a cell finds its 4×4 taps in one tile.
pub(crate) const STRIDE: usize = TILE + 3;
/// Samples along each side of the window a tile is filtered from.
const WINDOW: usize = STRIDE + 2 * HALO;

/// Values a query interpolates at a grid point, in one 32-byte texel (the lanes vectorise
/// across the fields): `[D_x, D_z, η, ∂y/∂x, ∂y/∂z, 0, 0, 0]`.
pub(crate) const LANES: usize = 8;
/// One texel: [`LANES`] values.
pub(crate) type Texel = [f32; LANES];

/// The samples of one cascade the queries read: its height, displacement and slope buffers.
#[derive(Clone, Copy)]
pub(crate) struct Source<'a> {
    pub(crate) height: &'a [f32],
    pub(crate) displacement: &'a [[f32; 2]],
    pub(crate) slope: &'a [[f32; 2]],
}

impl Source<'_> {
    /// The texel of grid point `index`.
    #[inline(always)]
    pub(crate) fn texel(&self, index: usize) -> Texel {
        let [dx, dz] = self.displacement[index];
        let [sx, sz] = self.slope[index];
        [dx, dz, self.height[index], sx, sz, 0.0, 0.0, 0.0]
    }
}

/// The coefficients of one tile: [`STRIDE`]² texels, row-major with z as the row.
pub(crate) type TileData = [Texel; STRIDE * STRIDE];

/// The cubic B-spline coefficients of one N×N cascade, in tiles of [`TILE`]² cells, each
/// computed by the first query that reads it (see the module's docs) and kept until
/// [`Tiles::reset`].
#[derive(Debug)]
pub(crate) struct Tiles {
    n: usize,
    /// Cells along a tile's side: [`TILE`], or N if smaller.
    tile: usize,
    /// Tiles along each axis, ⌈N / tile⌉.
    per_axis: usize,
    tiles: Vec<OnceLock<TileData>>,
}

impl Tiles {
    /// Room for the coefficients of an N×N cascade, none computed.
    pub(crate) fn new(n: usize) -> Result<Tiles, Error> {
        let tile = TILE.min(n);
        let per_axis = n.div_ceil(tile);
        Ok(Tiles {
            n,
            tile,
            per_axis,
            tiles: error::try_vec(per_axis * per_axis, OnceLock::new())?,
        })
    }

    /// Bytes the coefficients of an N×N cascade take: 32 bytes for each of the
    /// ([`TILE`] + 3)² texels of each of its ⌈N/[`TILE`]⌉² tiles (about 38·N² for large N).
    pub(crate) fn memory_bytes(n: usize) -> usize {
        let per_axis = n.div_ceil(TILE.min(n.max(1)));
        per_axis
            .saturating_mul(per_axis)
            .saturating_mul(std::mem::size_of::<OnceLock<TileData>>())
    }

    /// Forgets every computed tile (the cascade's buffers changed). Allocates nothing.
    pub(crate) fn reset(&mut self) {
        for tile in &mut self.tiles {
            // Only the tiles a query computed hold anything to forget.
            if tile.get().is_some() {
                tile.take();
            }
        }
    }

    /// The tile holding cell (`ix`, `iz`) and the cell's position in it (`lx`, `lz`: its
    /// taps are the texels `lx..lx + 4` of rows `lz..lz + 4`), computed from `source` (the
    /// samples these tiles belong to) at SIMD level `simd` if no query did so yet.
    #[inline(always)]
    pub(crate) fn cell<'s>(
        &self,
        ix: usize,
        iz: usize,
        source: impl FnOnce() -> Source<'s>,
        simd: Simd,
    ) -> (&TileData, usize, usize) {
        // Tiles of TILE cells divide by a shift (an integer division costs more than the
        // spline); only grids smaller than a tile have other sizes.
        let (tx, tz) = if self.tile == TILE {
            (ix / TILE, iz / TILE)
        } else {
            (ix / self.tile, iz / self.tile)
        };
        let data = self.tiles[tz * self.per_axis + tx]
            .get_or_init(|| compute_tile_at(simd, &source(), self.n, self.tile, tx, tz));
        (data, ix - tx * self.tile, iz - tz * self.tile)
    }
}

impl Clone for Tiles {
    /// Room for the same grid's coefficients, none computed (a clone recomputes what it
    /// reads, to the same bits).
    fn clone(&self) -> Self {
        Tiles {
            n: self.n,
            tile: self.tile,
            per_axis: self.per_axis,
            tiles: (0..self.tiles.len()).map(|_| OnceLock::new()).collect(),
        }
    }
}

/// [`compute_tile`] at SIMD level `simd`; not inlined, so that its large stack frame stays
/// out of the queries that call it.
#[inline(never)]
fn compute_tile_at(
    simd: Simd,
    source: &Source,
    n: usize,
    tile: usize,
    tx: usize,
    tz: usize,
) -> TileData {
    simd.run_kernel(TileKernel {
        source,
        n,
        tile,
        at: [tx, tz],
    })
}

/// [`compute_tile`] as a [`Kernel`].
struct TileKernel<'a, 's> {
    source: &'a Source<'s>,
    n: usize,
    tile: usize,
    at: [usize; 2],
}

impl Kernel for TileKernel<'_, '_> {
    type Output = TileData;

    #[inline(always)]
    fn run(self) -> TileData {
        compute_tile(self.source, self.n, self.tile, self.at[0], self.at[1])
    }
}

/// Window rows the x pass filters together: their recursions are independent, so
/// interleaving them hides the latency of each one's dependency chain.
const INTERLEAVE: usize = 4;

/// The coefficients of tile (`tx`, `tz`) of an N×N grid with `tile` cells a side: texel
/// (a, b) of the result is the coefficient of grid point (tx·tile − 1 + a, tz·tile − 1 + b),
/// wrapped. The x pass runs on every row of the window, each started [`HALO`] samples left
/// of the tile; the z pass on whole rows of the result (so that it vectorises), started
/// [`HALO`] rows above. Inlined into its caller's [`Simd::run`].
#[inline(always)]
fn compute_tile(source: &Source, n: usize, tile: usize, tx: usize, tz: usize) -> TileData {
    // Window sample w sits at grid point start + w, wrapped (`offset` is a multiple of n that
    // keeps the start from underflowing).
    let offset = (1 + HALO).div_ceil(n) * n;
    let x_start = offset + tx * tile - 1 - HALO;
    let z_start = offset + tz * tile - 1 - HALO;
    let mut columns = [0usize; WINDOW];
    for (w, column) in columns.iter_mut().enumerate() {
        *column = (x_start + w) % n;
    }
    // The x pass of every window row; after the z pass's causal half, rows HALO.. of the
    // window (the anticausal half starts at the last one and needs no row above the tile).
    let mut rows = [[[0.0f32; LANES]; STRIDE]; WINDOW];
    let mut w = 0;
    while w + INTERLEAVE <= WINDOW {
        filter_x::<INTERLEAVE>(
            source,
            &columns,
            n,
            z_start + w,
            &mut rows[w..w + INTERLEAVE],
        );
        w += INTERLEAVE;
    }
    while w < WINDOW {
        filter_x::<1>(source, &columns, n, z_start + w, &mut rows[w..w + 1]);
        w += 1;
    }
    // z pass, causal: y[r] = x[r] + z·y[r − 1], whole rows at a time.
    for r in 1..WINDOW {
        let (done, rest) = rows.split_at_mut(r);
        let above = &done[r - 1];
        for (v, a) in rest[0].iter_mut().zip(above) {
            for l in 0..LANES {
                v[l] += POLE * a[l];
            }
        }
    }
    // Anticausal with the gain, from the last row of the window up to the tile.
    let mut below = [[0.0f32; LANES]; STRIDE];
    let mut out = [[0.0f32; LANES]; STRIDE * STRIDE];
    for r in (HALO..WINDOW).rev() {
        let row = &mut rows[r];
        for (v, b) in row.iter_mut().zip(below.iter()) {
            for l in 0..LANES {
                v[l] = GAIN * v[l] + POLE * b[l];
            }
        }
        below = *row;
        if r < HALO + STRIDE {
            out[(r - HALO) * STRIDE..(r - HALO + 1) * STRIDE].copy_from_slice(row);
        }
    }
    out
}

/// The x pass of R window rows starting at (unwrapped) grid row `first`: a causal pass from
/// zero before the window, y\[i\] = f\[i\] + z·y\[i − 1\], then the anticausal one with the
/// gain, c\[i\] = G·y\[i\] + z·c\[i + 1\] from zero after it, kept at the tile's [`STRIDE`]
/// texels.
#[inline(always)]
fn filter_x<const R: usize>(
    source: &Source,
    columns: &[usize; WINDOW],
    n: usize,
    first: usize,
    out: &mut [[Texel; STRIDE]],
) {
    let bases: [usize; R] = std::array::from_fn(|k| (first + k) % n * n);
    let mut line = [[[0.0f32; LANES]; R]; WINDOW];
    let mut state = [[0.0f32; LANES]; R];
    for (y, &column) in line.iter_mut().zip(columns) {
        for k in 0..R {
            let f = source.texel(bases[k] + column);
            for l in 0..LANES {
                state[k][l] = f[l] + POLE * state[k][l];
            }
        }
        *y = state;
    }
    let mut state = [[0.0f32; LANES]; R];
    for i in (HALO..WINDOW).rev() {
        for k in 0..R {
            for l in 0..LANES {
                state[k][l] = GAIN * line[i][k][l] + POLE * state[k][l];
            }
        }
        if i < HALO + STRIDE {
            for k in 0..R {
                out[k][i - HALO] = state[k];
            }
        }
    }
}

/// Cubic B-spline weights of the taps at offsets −1, 0, 1, 2 from the cell's node, for the
/// fraction `t` ∈ [0, 1] of the way to the next node. They sum to 1; at t = 0 they are
/// (1, 4, 1, 0)/6.
#[inline(always)]
pub(crate) fn weights(t: f32) -> [f32; 4] {
    let s = 1.0 - t;
    let t2 = t * t;
    let t3 = t2 * t;
    [
        s * s * s / 6.0,
        (4.0 - 6.0 * t2 + 3.0 * t3) / 6.0,
        (1.0 + 3.0 * (t + t2 - t3)) / 6.0,
        t3 / 6.0,
    ]
}

/// The derivatives of [`weights`] with respect to `t` (per cell; they sum to 0).
#[inline(always)]
pub(crate) fn weight_slopes(t: f32) -> [f32; 4] {
    let s = 1.0 - t;
    [
        -0.5 * s * s,
        t * (1.5 * t - 2.0),
        0.5 + t * (1.0 - 1.5 * t),
        0.5 * t * t,
    ]
}

/// Σ w_x w_z c over the 4×4 taps from texel (`lx`, `lz`) of `tile`: the interpolated
/// value of every lane.
#[inline(always)]
pub(crate) fn value(tile: &TileData, lx: usize, lz: usize, wx: &[f32; 4], wz: &[f32; 4]) -> Texel {
    let mut sum = [0.0f32; LANES];
    for (r, &wz) in wz.iter().enumerate() {
        let taps = &tile[(lz + r) * STRIDE + lx..][..4];
        let mut line = [0.0f32; LANES];
        for (c, &wx) in taps.iter().zip(wx) {
            for l in 0..LANES {
                line[l] += wx * c[l];
            }
        }
        for l in 0..LANES {
            sum[l] += wz * line[l];
        }
    }
    sum
}

/// [`value`] (the same operations, so the same bits) and its derivatives along x and z per
/// cell, from the weights' derivatives `dx`, `dz`.
#[inline(always)]
pub(crate) fn value_and_gradient(
    tile: &TileData,
    lx: usize,
    lz: usize,
    [wx, wz]: [&[f32; 4]; 2],
    [dx, dz]: [&[f32; 4]; 2],
) -> [Texel; 3] {
    let mut sum = [0.0f32; LANES];
    let mut sum_x = [0.0f32; LANES];
    let mut sum_z = [0.0f32; LANES];
    for r in 0..4 {
        let taps = &tile[(lz + r) * STRIDE + lx..][..4];
        let mut line = [0.0f32; LANES];
        let mut line_x = [0.0f32; LANES];
        for ((c, &wx), &dx) in taps.iter().zip(wx).zip(dx) {
            for l in 0..LANES {
                line[l] += wx * c[l];
                line_x[l] += dx * c[l];
            }
        }
        for l in 0..LANES {
            sum[l] += wz[r] * line[l];
            sum_x[l] += wz[r] * line_x[l];
            sum_z[l] += dz[r] * line[l];
        }
    }
    [sum, sum_x, sum_z]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The exact periodic interpolation filter along one axis, in f64, by solving the
    /// circulant system in the frequency domain (an independent computation): c = f / B̂
    /// with B̂(k) = (4 + 2 cos(2πk/N))/6, through a direct DFT.
    // Reference maths in the standard library's functions: a test, not simulation code.
    #[allow(clippy::disallowed_methods)]
    fn exact_1d(values: &[f64]) -> Vec<f64> {
        use std::f64::consts::TAU;
        let n = values.len();
        let spectrum: Vec<(f64, f64)> = (0..n)
            .map(|k| {
                let b = (4.0 + 2.0 * (TAU * k as f64 / n as f64).cos()) / 6.0;
                let (mut re, mut im) = (0.0, 0.0);
                for (x, v) in values.iter().enumerate() {
                    let phase = TAU * ((k * x) % n) as f64 / n as f64;
                    re += v * phase.cos();
                    im -= v * phase.sin();
                }
                (re / b, im / b)
            })
            .collect();
        (0..n)
            .map(|x| {
                let sum: f64 = spectrum
                    .iter()
                    .enumerate()
                    .map(|(k, (re, im))| {
                        let phase = TAU * ((k * x) % n) as f64 / n as f64;
                        re * phase.cos() - im * phase.sin()
                    })
                    .sum();
                sum / n as f64
            })
            .collect()
    }

    /// The exact 2D coefficients: along x on every row, then along z on every column.
    fn exact(values: &[f64], n: usize) -> Vec<f64> {
        let mut rows: Vec<f64> = values.chunks(n).flat_map(exact_1d).collect();
        for i in 0..n {
            let column: Vec<f64> = (0..n).map(|j| rows[j * n + i]).collect();
            for (j, c) in exact_1d(&column).into_iter().enumerate() {
                rows[j * n + i] = c;
            }
        }
        rows
    }

    #[test]
    fn tiles_hold_the_periodic_coefficients_to_f32_precision() {
        // One tile (wrapping several times), whole tiles, and a partial last tile (100).
        for n in [4usize, 6, 10, 16, 64, 100] {
            let height: Vec<f32> = (0..n * n)
                .map(|i| ((i * 7919) % 101) as f32 / 50.0 - 1.0)
                .collect();
            let pairs: Vec<[f32; 2]> = height.iter().map(|&h| [h * 0.5, -h]).collect();
            let source = Source {
                height: &height,
                displacement: &pairs,
                slope: &pairs,
            };
            let reference = exact(&height.iter().map(|&h| f64::from(h)).collect::<Vec<_>>(), n);
            let tiles = Tiles::new(n).unwrap();
            let mut worst = 0.0f64;
            for iz in 0..n {
                for ix in 0..n {
                    let (data, lx, lz) = tiles.cell(ix, iz, || source, Simd::Baseline);
                    // The cell's 4×4 taps are grid points ix − 1 … ix + 2, iz − 1 … iz + 2.
                    for b in 0..4 {
                        for a in 0..4 {
                            let (i, j) = ((ix + n + a - 1) % n, (iz + n + b - 1) % n);
                            let got = data[(lz + b) * STRIDE + lx + a];
                            worst = worst.max((f64::from(got[2]) - reference[j * n + i]).abs());
                            // The lanes are filtered independently (scaling by a power of two
                            // commutes with every rounding).
                            assert_eq!(got[0], got[2] * 0.5);
                            assert_eq!(got[1], -got[2]);
                            assert_eq!(got[5..], [0.0; 3]);
                        }
                    }
                }
            }
            // Each of the four recursions rounds once a step; the errors are summed with the
            // weights |z|^k (Σ 1.37) and the gain (1.6) per pass, so they stay within a few
            // f32 ε of the largest coefficient (measured: 1.7 ε). Dropping the terms beyond
            // z^8 instead of z^16 would show about 20·|z|^9 ≈ 1.4e-4 of it, 1000 ε.
            let largest = reference.iter().fold(0.0f64, |m, c| m.max(c.abs()));
            let bound = 8.0 * f64::from(f32::EPSILON) * largest;
            assert!(worst < bound, "N = {n}: worst {worst:e}, bound {bound:e}");
        }
    }
}
