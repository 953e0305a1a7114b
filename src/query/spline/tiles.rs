//! The coefficients of one cascade in tiles ([`Tiles`]), each computed once from the
//! cascade's samples by the first query that reads it, or by a batch beforehand, and kept
//! until the fields change.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, OnceLock, PoisonError};

use rayon::prelude::*;

use super::filter::compute_tile_at;
use super::{Source, TileData, STRIDE, TEXELS, TILE};
use crate::error::{self, Error};
use crate::math::simd::Simd;

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
