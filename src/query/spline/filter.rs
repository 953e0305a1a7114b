//! The filter that computes a tile's coefficients from a cascade's samples: a causal and an
//! anticausal pass along x on each row of the tile's window, then along z (see the module's
//! docs for the filter and its halo).

use super::{Source, TileData, HALO, HEIGHT, SLOPE, STRIDE};
use crate::math::simd::{Kernel, Simd};

/// The pole √3 − 2 of the cubic B-spline's interpolation filter.
const POLE: f32 = -0.267_949_2;
/// Gain −6z of the two passes together: 1/(1 − z)² times it is 1, so constants pass.
const GAIN: f32 = 1.607_695_2;
/// Samples along each side of the window a tile is filtered from.
const WINDOW: usize = STRIDE + 2 * HALO;

/// Values the filter computes together at a grid point, in one 32-byte texel (the lanes
/// vectorise across the fields): `[D_x, D_z, η, ∂y/∂x, ∂y/∂z, 0, 0, 0]`.
const LANES: usize = 8;
/// One texel of the filter: [`LANES`] values.
type Texel = [f32; LANES];

impl Source<'_> {
    /// The texel of grid point `index`.
    #[inline(always)]
    fn texel(&self, index: usize) -> Texel {
        let [dx, dz] = self.displacement[index];
        let [sx, sz] = self.slope[index];
        [dx, dz, self.height[index], sx, sz, 0.0, 0.0, 0.0]
    }
}

/// [`compute_tile`] at SIMD level `simd`, into `out`; not inlined into the queries.
#[inline(never)]
pub(super) fn compute_tile_at(
    simd: Simd,
    source: &Source,
    grid: [usize; 2],
    at: [usize; 2],
    out: &mut TileData,
) {
    simd.run_kernel(TileKernel {
        source,
        grid,
        at,
        out,
    })
}

/// [`compute_tile`] as a [`Kernel`].
struct TileKernel<'a, 's> {
    source: &'a Source<'s>,
    /// N and the cells along a tile's side.
    grid: [usize; 2],
    at: [usize; 2],
    out: &'a mut TileData,
}

impl Kernel for TileKernel<'_, '_> {
    type Output = ();

    #[inline(always)]
    fn run(self) {
        let [n, tile] = self.grid;
        compute_tile(self.source, n, tile, self.at, self.out);
    }
}

/// Window rows the x pass filters together: their recursions are independent, so
/// interleaving them hides the latency of each one's dependency chain (8 texels of 8 lanes
/// fill half the AVX registers).
const INTERLEAVE: usize = 8;

/// The coefficients of tile (`tx`, `tz`) of an N×N grid with `tile` cells a side, into
/// `out`: its entry (a, b) of each field is the coefficient of grid point
/// (tx·tile − 1 + a, tz·tile − 1 + b), wrapped. The x pass runs on every row of the window,
/// each started [`HALO`] samples left of the tile; the z pass on whole rows (so that it
/// vectorises), started [`HALO`] rows above, its causal half folded in as the x pass
/// delivers the rows. The rows above the tile are needed only for that causal state and the
/// rows below it only for the anticausal half, so both share one small scratch; the tile's
/// own rows go through `out`, split into its fields (no 39 kB scratch to zero for them).
/// Inlined into its caller's [`Simd::run`].
#[inline(always)]
fn compute_tile(source: &Source, n: usize, tile: usize, [tx, tz]: [usize; 2], out: &mut TileData) {
    // Window sample w sits at grid point start + w, wrapped (`offset` is a multiple of n that
    // keeps the start from underflowing).
    let offset = (1 + HALO).div_ceil(n) * n;
    let x_start = offset + tx * tile - 1 - HALO;
    let z_start = offset + tz * tile - 1 - HALO;
    let mut columns = [0usize; WINDOW];
    // One division, then a wrap by comparison (n may be smaller than the window).
    let mut next = x_start % n;
    for column in &mut columns {
        *column = next;
        next = if next + 1 == n { 0 } else { next + 1 };
    }
    // Window rows 0..HALO (above the tile), then the tile's STRIDE rows (split into the
    // fields of `out`), then HALO rows below it, in `scratch` again once the rows above were
    // folded in.
    let mut scratch = [[[0.0f32; LANES]; STRIDE]; HALO];
    let mut line = [[[0.0f32; LANES]; INTERLEAVE]; WINDOW];
    // The z pass's causal state: y[r − 1] of the row before.
    let mut state = [[0.0f32; LANES]; STRIDE];
    let mut w = 0;
    while w < WINDOW {
        let count = if w + INTERLEAVE <= WINDOW {
            INTERLEAVE
        } else {
            1
        };
        if count == INTERLEAVE {
            filter_x::<INTERLEAVE>(source, &columns, n, z_start + w, &mut line);
        } else {
            let mut single = [[[0.0f32; LANES]; 1]; WINDOW];
            filter_x::<1>(source, &columns, n, z_start + w, &mut single);
            for (l, s) in line.iter_mut().zip(&single) {
                l[0] = s[0];
            }
        }
        for k in 0..count {
            let r = w + k;
            // The x pass's result (its anticausal half kept the tile's STRIDE texels, at
            // window samples HALO..), then the z pass, causal: y[r] = x[r] + z·y[r − 1].
            // (Each texel computed in a register and stored twice: stored lane by lane and
            // read back whole, it stalled the store buffer.)
            let x = line[HALO..].iter().map(|x| &x[k]);
            if (HALO..HALO + STRIDE).contains(&r) {
                for (column, (s, x)) in state.iter_mut().zip(x).enumerate() {
                    let y: Texel = std::array::from_fn(|l| x[l] + POLE * s[l]);
                    *s = y;
                    store(out, (r - HALO) * STRIDE + column, &y);
                }
            } else {
                let row = &mut scratch[if r < HALO { r } else { r - HALO - STRIDE }];
                for ((v, s), x) in row.iter_mut().zip(state.iter_mut()).zip(x) {
                    let y: Texel = std::array::from_fn(|l| x[l] + POLE * s[l]);
                    *v = y;
                    *s = y;
                }
            }
        }
        w += count;
    }
    // Anticausal with the gain, from the last row of the window up to the tile:
    // c[r] = G·y[r] + z·c[r + 1].
    let mut below = [[0.0f32; LANES]; STRIDE];
    for row in scratch.iter().rev() {
        for (v, b) in row.iter().zip(below.iter_mut()) {
            *b = std::array::from_fn(|l| GAIN * v[l] + POLE * b[l]);
        }
    }
    for row in (0..STRIDE).rev() {
        for (column, b) in below.iter_mut().enumerate() {
            let at = row * STRIDE + column;
            let v = load(out, at);
            let c: Texel = std::array::from_fn(|l| GAIN * v[l] + POLE * b[l]);
            *b = c;
            store(out, at, &c);
        }
    }
}

/// Writes the five used lanes of texel `v` into point `at` of the fields of `out`.
#[inline(always)]
fn store(out: &mut TileData, at: usize, v: &Texel) {
    out[2 * at..2 * at + 2].copy_from_slice(&v[..2]);
    out[HEIGHT + at] = v[2];
    out[SLOPE + 2 * at..SLOPE + 2 * at + 2].copy_from_slice(&v[3..5]);
}

/// The texel of point `at` of the fields of `out` ([`store`]'s inverse: the three unused
/// lanes are zero, as the filter keeps them).
#[inline(always)]
fn load(out: &TileData, at: usize) -> Texel {
    [
        out[2 * at],
        out[2 * at + 1],
        out[HEIGHT + at],
        out[SLOPE + 2 * at],
        out[SLOPE + 2 * at + 1],
        0.0,
        0.0,
        0.0,
    ]
}

/// The x pass of R window rows starting at (unwrapped) grid row `first`: a causal pass from
/// zero before the window, y\[i\] = f\[i\] + z·y\[i − 1\], then the anticausal one with the
/// gain, c\[i\] = G·y\[i\] + z·c\[i + 1\] from zero after it, in `line` (the tile's texels
/// are its entries [`HALO`]..[`HALO`] + [`STRIDE`]).
#[inline(always)]
fn filter_x<const R: usize>(
    source: &Source,
    columns: &[usize; WINDOW],
    n: usize,
    first: usize,
    line: &mut [[Texel; R]; WINDOW],
) {
    // The rows' samples, as slices of N (so that a column < N needs one check a field).
    let rows: [Source; R] = std::array::from_fn(|k| {
        let base = (first + k) % n * n;
        Source {
            height: &source.height[base..base + n],
            displacement: &source.displacement[base..base + n],
            slope: &source.slope[base..base + n],
        }
    });
    let mut state = [[0.0f32; LANES]; R];
    for (y, &column) in line.iter_mut().zip(columns) {
        for (k, row) in rows.iter().enumerate() {
            let f = row.texel(column);
            for l in 0..LANES {
                state[k][l] = f[l] + POLE * state[k][l];
            }
        }
        *y = state;
    }
    let mut state = [[0.0f32; LANES]; R];
    for y in line[HALO..].iter_mut().rev() {
        for k in 0..R {
            for l in 0..LANES {
                state[k][l] = GAIN * y[k][l] + POLE * state[k][l];
            }
        }
        *y = state;
    }
}
