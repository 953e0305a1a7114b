//! Many points at once: batches of queries split over rayon's threads, each task's points
//! answered with its SIMD level's [`Shuffle`], the spline tiles a batch reads computed first
//! in parallel, and the rows of a grid of samples.

use rayon::prelude::*;

use super::frame::{Fields, Grid};
use super::lanes::{self, Shuffle};
use super::point::{check_point, PointQuery, Sample};
use super::results::SurfaceSample;
use super::spline::Tiles;
use crate::error::{self, Error};
use crate::math::simd::{Kernel, Simd};

/// Work that runs with a SIMD level's [`Shuffle`] (see [`run_shuffled`]).
trait ShuffledKernel {
    fn run<S: Shuffle>(self, shuffle: S);
}

/// A [`ShuffledKernel`] with its level's [`Shuffle`], as a [`Kernel`] of that level.
struct Shuffled<K, S> {
    kernel: K,
    shuffle: S,
}

impl<K: ShuffledKernel, S: Shuffle> Kernel for Shuffled<K, S> {
    type Output = ();

    #[inline(always)]
    fn run(self) {
        self.kernel.run(self.shuffle);
    }
}

/// `kernel` at SIMD level `simd`, with that level's [`Shuffle`] (AVX2's, and the AVX2 level,
/// on AVX-512 machines too: the lanes are eight `f32`).
#[inline(always)]
fn run_shuffled<K: ShuffledKernel>(simd: Simd, kernel: K) {
    match simd {
        Simd::Baseline { fused } => kernel.run(lanes::Plain { fused }),
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2(v3) => simd.run_kernel(Shuffled {
            kernel,
            shuffle: v3,
        }),
        // The lanes are eight `f32` wide: AVX-512 machines run the AVX2 build of them, no
        // slower, where a build of their own would be the largest code to compile.
        #[cfg(target_arch = "x86_64")]
        Simd::Avx512(v4) => Simd::Avx2(*v4).run_kernel(Shuffled {
            kernel,
            shuffle: *v4,
        }),
    }
}

/// A batch's query of each point into `out`, as a [`ShuffledKernel`].
struct Batch<'a, T, Q> {
    fields: &'a Fields<'a>,
    points: &'a [[f64; 2]],
    out: &'a mut [T],
    query: &'a Q,
}

impl<Q: PointQuery> ShuffledKernel for Batch<'_, Q::Output, Q> {
    #[inline(always)]
    fn run<S: Shuffle>(self, shuffle: S) {
        self.query
            .batch(shuffle, self.fields, self.points, self.out);
    }
}

/// [`Batch`] at SIMD level `simd`. Out of line: [`for_each_point`] calls it from two
/// places (the calling thread and rayon's tasks), which would otherwise each hold a copy of
/// the baseline level's lanes, the largest code of the crate to compile.
#[inline(never)]
fn run_batch<Q: PointQuery>(
    simd: Simd,
    fields: &Fields<'_>,
    points: &[[f64; 2]],
    out: &mut [Q::Output],
    query: &Q,
) {
    run_shuffled(
        simd,
        Batch {
            fields,
            points,
            out,
            query,
        },
    );
}

/// The samples of [`Water::at_rest_grid`](crate::Water::at_rest_grid) once its
/// arguments are checked: a grid of rows `columns` long, sample (c, r) at
/// `origin` + (c, r)·`spacing` summed over cascades `cascades`, rows in parallel at the
/// frame's SIMD level, into `out`. Each row's points are batches of [`Sample`], so that the
/// grid shares [`Water::at_rest_many`](crate::Water::at_rest_many)'s compiled lanes.
pub(crate) fn sample_rows(
    fields: &Fields<'_>,
    origin: [f64; 2],
    spacing: f64,
    columns: usize,
    cascades: std::ops::Range<usize>,
    out: &mut [SurfaceSample],
) {
    let simd = fields.frame().simd;
    let query = Sample(cascades);
    out.par_chunks_mut(columns)
        .enumerate()
        .for_each(|(r, row)| {
            let [x, z] = [origin[0], origin[1] + r as f64 * spacing];
            // Eight points at a time, as the lanes take them (no allocation).
            for (chunk, out) in row.chunks_mut(lanes::LANES).enumerate() {
                let first = chunk * lanes::LANES;
                let points: [[f64; 2]; lanes::LANES] =
                    std::array::from_fn(|c| [x + (first + c) as f64 * spacing, z]);
                run_batch(simd, fields, &points[..out.len()], out, &query);
                query.add_wakes(fields, &points[..out.len()], out);
            }
        });
}

/// Batches of at least this many points are spread over rayon's threads; smaller ones (a
/// boat's few hull points) run on the calling thread, where handing them to the pool would
/// cost more than it saves.
const PARALLEL_BATCH: usize = 64;
/// Fewest and most points one parallel task answers: about eight tasks a thread between
/// them, so that threads even out, while a task keeps its lanes full for long (the lanes
/// idle as a task's last searches end). The results do not depend on the split.
const TASK_POINTS: [usize; 2] = [32, 1024];

/// `query` of every point into `out`, at the frame's SIMD level.
pub(crate) fn for_each_point<Q: PointQuery>(
    fields: &Fields<'_>,
    points: &[[f64; 2]],
    out: &mut [Q::Output],
    query: Q,
) {
    let simd = fields.frame().simd;
    let query = &query;
    let chunk = |out: &mut [Q::Output], points: &[[f64; 2]]| {
        run_batch(simd, fields, points, out, query);
        query.add_wakes(fields, points, out);
    };
    if points.len() < PARALLEL_BATCH {
        chunk(out, points);
    } else {
        prepare_tiles(fields, points);
        let [fewest, most] = TASK_POINTS;
        let task = (points.len() / (8 * rayon::current_num_threads())).clamp(fewest, most);
        out.par_chunks_mut(task)
            .zip(points.par_chunks(task))
            .for_each(|(out, points)| chunk(out, points));
    }
}

/// Computes, in parallel, the spline tiles under a batch's `points` that no query computed
/// yet (the queries' threads would otherwise wait for each other's tiles; the tiles a
/// query's Newton iterates move on to are computed when they are read, as always).
fn prepare_tiles(fields: &Fields<'_>, points: &[[f64; 2]]) {
    let frame = fields.frame();
    // Nothing to do with bilinear queries, or once every tile is computed (a second batch
    // on the same frame).
    let ready = |grid: &Grid| grid.tiles.as_ref().is_none_or(Tiles::all_ready);
    if frame.grids.iter().all(ready) {
        return;
    }
    // Marking costs a few ns a point and cascade: split like the queries, at the frame's
    // SIMD level (the baseline has no instruction for the cell's floor).
    points.par_chunks(MARK_POINTS).for_each(|points| {
        frame.simd.run_kernel(Mark {
            grids: &frame.grids,
            points,
        })
    });
    for (c, grid) in frame.grids.iter().enumerate() {
        if let Some(tiles) = grid.tiles.as_ref().filter(|tiles| !tiles.all_ready()) {
            tiles.prepare(fields.source(c), frame.simd);
        }
    }
}

/// The marking of the tiles under some of a batch's points, as a [`Kernel`].
struct Mark<'a> {
    grids: &'a [Grid],
    points: &'a [[f64; 2]],
}

impl Kernel for Mark<'_> {
    type Output = ();

    #[inline(always)]
    fn run(self) {
        for grid in self.grids {
            if let Some(tiles) = grid.tiles.as_ref().filter(|tiles| !tiles.all_ready()) {
                // Eight points at a time, as the lanes find their cells.
                for points in self.points.chunks(lanes::LANES) {
                    let [ix, iz] = lanes::cells_at(points, &grid.period);
                    let (index, _) = tiles.cells_of(&ix, &iz);
                    for &index in &index[..points.len()] {
                        tiles.want_tile(index as usize);
                    }
                }
            }
        }
    }
}

/// Points one parallel task of [`prepare_tiles`] marks.
const MARK_POINTS: usize = 512;

/// Checks a batch: `out` as long as `points`, every coordinate finite.
pub(crate) fn check_batch(points: &[[f64; 2]], out_len: usize) -> Result<(), Error> {
    error::length("out", out_len, points.len())?;
    points.iter().try_for_each(|&[x, z]| check_point(x, z))
}
