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

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, OnceLock, PoisonError};

use rayon::prelude::*;

use crate::error::{self, Error};
use crate::math::simd::{baseline_lanes, Kernel, Simd};

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

/// Values the filter computes together at a grid point, in one 32-byte texel (the lanes
/// vectorise across the fields): `[D_x, D_z, η, ∂y/∂x, ∂y/∂z, 0, 0, 0]`.
const LANES: usize = 8;
/// One texel of the filter: [`LANES`] values.
type Texel = [f32; LANES];

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

impl Source<'_> {
    /// The texel of grid point `index`.
    #[inline(always)]
    fn texel(&self, index: usize) -> Texel {
        let [dx, dz] = self.displacement[index];
        let [sx, sz] = self.slope[index];
        [dx, dz, self.height[index], sx, sz, 0.0, 0.0, 0.0]
    }
}

/// The coefficients of one tile, each field apart so that a query reads only the fields it
/// needs (the inversion only the displacement): the [`STRIDE`]² displacement pairs
/// `[D_x, D_z]`, then the heights, then the slope pairs `[∂y/∂x, ∂y/∂z]`, each row-major with
/// z as the row (20 bytes a grid point).
pub(crate) type TileData = [f32; 5 * TEXELS];

/// One tile's room: the computed coefficients once a query computed them, and otherwise
/// the buffer they will be computed into (allocated with the [`Tiles`], moved between the
/// two without copying the texels).
#[derive(Debug)]
struct Slot {
    /// The coefficients of the current fields. Its state (empty, being computed, ready) is
    /// the tile's: a query that finds it being computed waits for it (a few µs).
    ready: OnceLock<Box<TileData>>,
    /// The buffer while the tile is stale.
    spare: Mutex<Option<Box<TileData>>>,
}

impl Slot {
    fn new() -> Result<Slot, Error> {
        Ok(Slot {
            ready: OnceLock::new(),
            spare: Mutex::new(Some(tile_buffer()?)),
        })
    }

    /// The coefficients of tile (`tx`, `tz`), computed from `source` into the spare buffer if
    /// no query did so yet (only one initialiser runs at a time, so the buffer is there,
    /// unless one panicked: then a new one is allocated).
    #[inline(always)]
    fn get<'s>(
        &self,
        grid: [usize; 2],
        at: [usize; 2],
        source: impl FnOnce() -> Source<'s>,
        simd: Simd,
        computed: &AtomicUsize,
    ) -> &TileData {
        self.ready.get_or_init(|| {
            computed.fetch_add(1, Ordering::Relaxed);
            let spare = self
                .spare
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
                .take();
            let mut data = spare.unwrap_or_else(|| Box::new([0.0; 5 * TEXELS]));
            compute_tile_at(simd, &source(), grid, at, &mut data);
            data
        })
    }
}

/// A zeroed tile buffer on the heap (never on the stack: it is 25 kB).
fn tile_buffer() -> Result<Box<TileData>, Error> {
    let boxed = error::try_vec(5 * TEXELS, 0.0f32)?.into_boxed_slice();
    Ok(boxed.try_into().expect("the vector holds STRIDE² texels"))
}

/// The cubic B-spline coefficients of one N×N cascade, in tiles of [`TILE`]² cells, each
/// computed by the first query that reads it (see the module's docs) into room allocated
/// here, and kept until [`Tiles::reset`].
#[derive(Debug)]
pub(crate) struct Tiles {
    n: usize,
    /// Cells along a tile's side: [`TILE`], or N if smaller.
    tile: usize,
    /// Tiles along each axis, ⌈N / tile⌉.
    per_axis: usize,
    slots: Vec<Slot>,
    /// Tiles a batch is about to read (see [`Tiles::prepare`]).
    wanted: Vec<AtomicBool>,
    /// Tiles computed since the last [`Tiles::reset`] (each counted by its initialiser).
    computed: AtomicUsize,
}

impl Tiles {
    /// Room for the coefficients of an N×N cascade, none computed.
    pub(crate) fn new(n: usize) -> Result<Tiles, Error> {
        let tile = TILE.min(n);
        let per_axis = n.div_ceil(tile);
        let count = per_axis * per_axis;
        let mut slots = Vec::new();
        slots
            .try_reserve_exact(count)
            .map_err(|_| Error::OutOfMemory {
                bytes: Self::memory_bytes(n),
            })?;
        for _ in 0..count {
            slots.push(Slot::new()?);
        }
        let mut wanted = Vec::new();
        wanted
            .try_reserve_exact(count)
            .map_err(|_| Error::OutOfMemory {
                bytes: Self::memory_bytes(n),
            })?;
        wanted.extend((0..count).map(|_| AtomicBool::new(false)));
        Ok(Tiles {
            n,
            tile,
            per_axis,
            slots,
            wanted,
            computed: AtomicUsize::new(0),
        })
    }

    /// Bytes the coefficients of an N×N cascade take: 20 bytes for each of the
    /// ([`TILE`] + 3)² grid points of each of its ⌈N/[`TILE`]⌉² tiles (about 24·N² for large
    /// N).
    pub(crate) fn memory_bytes(n: usize) -> usize {
        let per_axis = n.div_ceil(TILE.min(n.max(1)));
        per_axis.saturating_mul(per_axis).saturating_mul(
            std::mem::size_of::<TileData>()
                + std::mem::size_of::<Slot>()
                + std::mem::size_of::<AtomicBool>(),
        )
    }

    /// Forgets every computed tile (the cascade's buffers changed), keeping its room.
    /// Allocates nothing.
    pub(crate) fn reset(&mut self) {
        for slot in &mut self.slots {
            if let Some(data) = slot.ready.take() {
                *slot.spare.get_mut().unwrap_or_else(PoisonError::into_inner) = Some(data);
            }
        }
        *self.computed.get_mut() = 0;
    }

    /// The tile (x, z) holding cell (`ix`, `iz`).
    #[inline(always)]
    fn tile_of(&self, ix: usize, iz: usize) -> [usize; 2] {
        // Tiles of TILE cells divide by a shift (an integer division costs more than the
        // spline); only grids smaller than a tile have other sizes.
        if self.tile == TILE {
            [ix / TILE, iz / TILE]
        } else {
            [ix / self.tile, iz / self.tile]
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
        let [tx, tz] = self.tile_of(ix, iz);
        let data = self.slots[tz * self.per_axis + tx].get(
            [self.n, self.tile],
            [tx, tz],
            source,
            simd,
            &self.computed,
        );
        (data, ix - tx * self.tile, iz - tz * self.tile)
    }

    /// [`Tiles::cell`] of eight cells (`ix`, `iz`) at once, one a lane: each cell's tile
    /// (an index for [`Tiles::tile`]) and its first tap's index in the tile's fields
    /// (`lz·STRIDE + lx`).
    #[inline(always)]
    pub(crate) fn cells_of(&self, ix: &[u32; 8], iz: &[u32; 8]) -> ([u32; 8], [u32; 8]) {
        // A grid smaller than a tile is one tile (tile = N > every cell).
        let shift = if self.tile == TILE {
            TILE.trailing_zeros()
        } else {
            u32::BITS - 1
        };
        let (per_axis, tile) = (self.per_axis as u32, self.tile as u32);
        let tx: [u32; 8] = std::array::from_fn(|l| ix[l] >> shift);
        let tz: [u32; 8] = std::array::from_fn(|l| iz[l] >> shift);
        let index = std::array::from_fn(|l| tz[l] * per_axis + tx[l]);
        let offset = std::array::from_fn(|l| {
            (iz[l] - tz[l] * tile) * STRIDE as u32 + (ix[l] - tx[l] * tile)
        });
        (index, offset)
    }

    /// Tile `index` (from [`Tiles::cells_of`]), computed from `source` at SIMD level `simd`
    /// if no query did so yet.
    #[inline(always)]
    pub(crate) fn tile<'s>(
        &self,
        index: usize,
        source: impl FnOnce() -> Source<'s>,
        simd: Simd,
    ) -> &TileData {
        let slot = &self.slots[index];
        match slot.ready.get() {
            Some(data) => data,
            None => self.compute(index, source(), simd),
        }
    }

    /// [`Tiles::tile`] when the tile is not ready (once a step for each tile a query reads).
    #[cold]
    #[inline(never)]
    fn compute(&self, index: usize, source: Source<'_>, simd: Simd) -> &TileData {
        let at = [index % self.per_axis, index / self.per_axis];
        self.slots[index].get([self.n, self.tile], at, || source, simd, &self.computed)
    }

    /// Whether every tile is computed (a batch then has nothing to prepare).
    #[inline(always)]
    pub(crate) fn all_ready(&self) -> bool {
        self.computed.load(Ordering::Relaxed) == self.slots.len()
    }

    /// Marks tile `index` (from [`Tiles::cells_of`]) as wanted by the batch being prepared.
    #[inline(always)]
    pub(crate) fn want_tile(&self, index: usize) {
        self.wanted[index].store(true, Ordering::Relaxed);
    }

    /// Computes every wanted tile that is not computed yet, in parallel (each by the same
    /// function as a query's, so to the same bits), and clears the marks. A batch calls it
    /// before its queries, whose threads would otherwise wait for each other's tiles. (Two
    /// batches preparing at once may clear each other's marks: a tile missed here is
    /// computed by the query that reads it, to the same bits.)
    pub(crate) fn prepare(&self, source: Source<'_>, simd: Simd) {
        let grid = [self.n, self.tile];
        let (per_axis, computed) = (self.per_axis, &self.computed);
        self.slots
            .par_iter()
            .zip(&self.wanted)
            .enumerate()
            .for_each(|(i, (slot, wanted))| {
                if wanted.swap(false, Ordering::Relaxed) {
                    slot.get(
                        grid,
                        [i % per_axis, i / per_axis],
                        || source,
                        simd,
                        computed,
                    );
                }
            });
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
            slots: (0..self.slots.len())
                .map(|_| Slot {
                    ready: OnceLock::new(),
                    spare: Mutex::new(Some(Box::new([0.0; 5 * TEXELS]))),
                })
                .collect(),
            wanted: (0..self.wanted.len())
                .map(|_| AtomicBool::new(false))
                .collect(),
            computed: AtomicUsize::new(0),
        }
    }
}

/// [`compute_tile`] at SIMD level `simd`, into `out`; not inlined into the queries.
#[inline(never)]
fn compute_tile_at(
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
/// same bits, and the batch queries' lanes (`query/lanes.rs`) run them too.
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
                    let (data, lx, lz) =
                        tiles.cell(ix, iz, || source, Simd::Baseline { fused: true });
                    // The cell's 4×4 taps are grid points ix − 1 … ix + 2, iz − 1 … iz + 2.
                    for b in 0..4 {
                        for a in 0..4 {
                            let (i, j) = ((ix + n + a - 1) % n, (iz + n + b - 1) % n);
                            let at = (lz + b) * STRIDE + lx + a;
                            let h = data[HEIGHT + at];
                            worst = worst.max((f64::from(h) - reference[j * n + i]).abs());
                            // The fields are filtered independently (scaling by a power of two
                            // commutes with every rounding).
                            assert_eq!(data[2 * at..2 * at + 2], [h * 0.5, -h]);
                            assert_eq!(data[SLOPE + 2 * at..SLOPE + 2 * at + 2], [h * 0.5, -h]);
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
