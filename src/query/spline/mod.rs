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
//!
//! `tiles.rs` holds the tiles of a cascade and computes each once, `filter.rs` the filter
//! that computes a tile, `stencil.rs` the weights and the sums over a point's taps.

mod filter;
mod stencil;
#[cfg(test)]
mod tests;
mod tiles;

pub(crate) use stencil::{displacement, height, slope, weight_slopes, weights, Lanes, Weights};
pub(crate) use tiles::Tiles;

/// Cells along each side of a tile (fewer on grids smaller than this).
pub(crate) const TILE: usize = 32;
/// Samples each pass runs through before it reaches the tile: |z|¹⁷ ≈ 2·10⁻¹⁰ (see the
/// module's docs).
const HALO: usize = 16;
/// Coefficients along each side of a stored tile: its cells and the stencil's reach of one
/// before and two after, so that every point of a cell finds its 4×4 taps in one tile.
pub(crate) const STRIDE: usize = TILE + 3;

/// Coefficients in a tile: [`STRIDE`]² of each field.
const TEXELS: usize = STRIDE * STRIDE;
/// Where the height's coefficients start in [`TileData`] (after the displacement's pairs).
pub(crate) const HEIGHT: usize = 2 * TEXELS;
/// Where the slope's pairs start in [`TileData`].
pub(crate) const SLOPE: usize = 3 * TEXELS;

/// The samples of one cascade the queries read: its height, displacement and slope buffers.
#[derive(Clone, Copy)]
pub(crate) struct Source<'a> {
    pub(crate) height: &'a [f32],
    pub(crate) displacement: &'a [[f32; 2]],
    pub(crate) slope: &'a [[f32; 2]],
}

/// The coefficients of one tile, each field apart so that a query reads only the fields it
/// needs (the inversion only the displacement): the [`STRIDE`]² displacement pairs
/// `[D_x, D_z]`, then the heights, then the slope pairs `[∂y/∂x, ∂y/∂z]`, each row-major with
/// z as the row (20 bytes a grid point).
pub(crate) type TileData = [f32; 5 * TEXELS];
