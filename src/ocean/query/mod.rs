//! World-space queries on an [`OceanState`]: periodic cubic B-spline sampling of every
//! cascade's height, displacement and slope (bilinear for the foam), summed, and the
//! inversion of the horizontal displacement for the water height at a point.

use glam::{Vec2, Vec3};
use std::ops::Bound::{Excluded, Included};

use rayon::prelude::*;

mod inversion;
pub(crate) mod lanes;

use super::frame::{Fields, Grid, Surface};
use super::spline::Tiles;
use super::OceanState;
use crate::error::{self, Error};
use crate::math::periodic::cell_on;
use crate::math::simd::{Kernel, Simd};
use inversion::{
    evaluate_group, height_at, locate, located_group, sample, surface_at, surface_sample, GROUP,
};
use lanes::Shuffle;

/// The surface at one undisplaced world point, summed over the cascades.
///
/// `#[repr(C)]`: nine `f32` in the order of the fields, without padding (36 bytes). With the
/// `bytemuck` feature it is `bytemuck::Pod` and `bytemuck::Zeroable`, so
/// `bytemuck::cast_slice` views a `&[SurfaceSample]` as `&[f32]` (or as a GPU buffer of
/// structs with the same layout) without copying.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
#[repr(C)]
pub struct SurfaceSample {
    /// Height η in metres.
    pub height: f32,
    /// Horizontal displacement `[x, z]` in metres (already × choppiness): the water at the
    /// undisplaced point sits at that point plus this.
    pub displacement: [f32; 2],
    /// Slope `[∂y/∂x, ∂y/∂z]` of the displaced surface, dimensionless: the sum of the
    /// cascades' slopes.
    pub slope: [f32; 2],
    /// Unit normal `[x, y, z]` of the displaced surface (y up), from the summed slope.
    pub normal: [f32; 3],
    /// Foam coverage in [0, 1]: the ocean's one foam field ([`OceanState::foam`], on
    /// cascade 0's grid) interpolated bilinearly; 0 from a range of cascades without
    /// cascade 0 ([`OceanState::sample_cascades`]), as cascade 0's textures carry the foam.
    pub foam: f32,
}

impl Default for SurfaceSample {
    /// Flat, still water: zero height, displacement and slope, the normal straight up, no
    /// foam.
    fn default() -> Self {
        SurfaceSample {
            height: 0.0,
            displacement: [0.0; 2],
            slope: [0.0; 2],
            normal: [0.0, 1.0, 0.0],
            foam: 0.0,
        }
    }
}

/// Where the water at a world point comes from: the result of [`OceanState::locate`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Location {
    /// The undisplaced world point `[x, z]` in metres whose water lands on the query point
    /// (the best one found).
    pub undisplaced: [f64; 2],
    /// Distance in metres between the query point and where the water at `undisplaced`
    /// actually lands (0 for an exact inversion).
    pub miss: f32,
    /// Newton steps it took to reach `undisplaced` from the search's first guess (0: the
    /// first guess itself, one Newton step on the larger cascades from the query point less
    /// the smaller cascades' displacement there), at most
    /// [`QueryConfig::max_iterations`](crate::QueryConfig::max_iterations).
    pub iterations: usize,
    /// Whether `miss` is below [`QueryConfig::tolerance`](crate::QueryConfig::tolerance).
    pub converged: bool,
}

/// Checks a world point: both coordinates finite (any finite value: the cascades wrap).
pub(crate) fn check_point(x: f64, z: f64) -> Result<(), Error> {
    for (name, value) in [("x", x), ("z", z)] {
        if !value.is_finite() {
            return Err(Error::NonFinite { name });
        }
    }
    Ok(())
}

/// The cell of (x, z) on `grid`.
#[inline(always)]
fn cell_in(grid: &Grid, x: f64, z: f64) -> (usize, f32, usize, f32) {
    cell_on(x, z, &grid.period)
}

/// A query at one world point, for [`run`] and [`for_each_point`]: plain functions of the
/// fields rather than closures, so that each is compiled at the frame's SIMD level (see
/// [`Kernel`]).
pub(crate) trait PointQuery: Sync {
    type Output: Send;
    fn at(&self, fields: &Fields<'_>, x: f64, z: f64) -> Self::Output;

    /// [`PointQuery::at`] of each of `points` (at most [`GROUP`]) into `out`, with the same
    /// bits; the queries that read the spline interleave the points (see [`located_group`]).
    #[inline(always)]
    fn group(&self, fields: &Fields<'_>, points: &[[f64; 2]], out: &mut [Self::Output]) {
        self.singles(fields, points, out);
    }

    /// [`PointQuery::at`] of each of `points` into `out`, one point at a time.
    #[inline(always)]
    fn singles(&self, fields: &Fields<'_>, points: &[[f64; 2]], out: &mut [Self::Output]) {
        for (value, &[x, z]) in out.iter_mut().zip(points) {
            *value = self.at(fields, x, z);
        }
    }

    /// [`PointQuery::group`] of each [`GROUP`] of `points` in turn, into `out`.
    #[inline(always)]
    fn groups(&self, fields: &Fields<'_>, points: &[[f64; 2]], out: &mut [Self::Output]) {
        for (out, points) in out.chunks_mut(GROUP).zip(points.chunks(GROUP)) {
            self.group(fields, points, out);
        }
    }

    /// [`PointQuery::at`] of each of `points` into `out`, with the same bits: by groups
    /// unless the query has a faster way (the spline's lanes, see [`lanes`], with
    /// `shuffle`).
    #[inline(always)]
    fn batch<S: Shuffle>(
        &self,
        shuffle: S,
        fields: &Fields<'_>,
        points: &[[f64; 2]],
        out: &mut [Self::Output],
    ) {
        let _ = shuffle;
        self.groups(fields, points, out);
    }
}

/// Whether batches run in lanes in this build: not with debug assertions (a game's dev
/// profile), where overflow checks break the lanes' loops into scalar code that LLVM's SLP
/// vectorizer then takes minutes over at each SIMD level; such builds answer batches by
/// groups of points, with the same bits (see docs/performance.md, "Compile time").
const LANES_BUILT: bool = !cfg!(debug_assertions);

/// Whether cascades `range` all have spline tiles, so that a batch over them runs in lanes
/// (callers test [`LANES_BUILT`] first, so that a build without lanes never compiles them).
#[inline(always)]
fn in_lanes(fields: &Fields<'_>, range: std::ops::Range<usize>) -> bool {
    fields.frame().grids[range]
        .iter()
        .all(|grid| grid.tiles.is_some())
}

/// [`sample`] over a range of cascades.
pub(crate) struct Sample(pub(crate) std::ops::Range<usize>);
/// [`locate`].
pub(crate) struct Locate;
/// [`surface_at`].
pub(crate) struct SurfaceAt;
/// [`height_at`].
pub(crate) struct HeightAt;

impl PointQuery for Sample {
    type Output = SurfaceSample;
    #[inline(always)]
    fn at(&self, fields: &Fields<'_>, x: f64, z: f64) -> SurfaceSample {
        sample(fields, x, z, self.0.clone())
    }

    #[inline(always)]
    fn group(&self, fields: &Fields<'_>, points: &[[f64; 2]], out: &mut [SurfaceSample]) {
        let sums =
            evaluate_group::<true, true>(fields, |p| points[p], points.len(), self.0.clone());
        for ((value, sum), &[x, z]) in out.iter_mut().zip(&sums).zip(points) {
            let foam = if self.0.contains(&0) {
                fields.foam_at(x, z)
            } else {
                0.0
            };
            *value = surface_sample(sum.displacement, *sum, foam);
        }
    }

    #[inline(always)]
    fn batch<S: Shuffle>(
        &self,
        shuffle: S,
        fields: &Fields<'_>,
        points: &[[f64; 2]],
        out: &mut [SurfaceSample],
    ) {
        if LANES_BUILT && in_lanes(fields, self.0.clone()) {
            lanes::sample(shuffle, fields, points, self.0.clone(), out);
        } else {
            self.groups(fields, points, out);
        }
    }
}

impl PointQuery for Locate {
    type Output = Location;
    #[inline(always)]
    fn at(&self, fields: &Fields<'_>, x: f64, z: f64) -> Location {
        locate(fields, x, z).0
    }
}

impl PointQuery for SurfaceAt {
    type Output = SurfaceSample;
    #[inline(always)]
    fn at(&self, fields: &Fields<'_>, x: f64, z: f64) -> SurfaceSample {
        surface_at(fields, x, z)
    }

    #[inline(always)]
    fn group(&self, fields: &Fields<'_>, points: &[[f64; 2]], out: &mut [SurfaceSample]) {
        let (searches, sums) = located_group::<true>(fields, points);
        for ((value, sum), search) in out.iter_mut().zip(&sums).zip(&searches) {
            let [x0, z0] = search.best.undisplaced;
            *value = surface_sample(search.displacement, *sum, fields.foam_at(x0, z0));
        }
    }

    #[inline(always)]
    fn batch<S: Shuffle>(
        &self,
        shuffle: S,
        fields: &Fields<'_>,
        points: &[[f64; 2]],
        out: &mut [SurfaceSample],
    ) {
        if points.len() < lanes::FEWEST {
            self.singles(fields, points, out);
        } else if LANES_BUILT && in_lanes(fields, 0..fields.frame().grids.len()) {
            lanes::locate::<S, SurfaceSample, true, true>(shuffle, fields, points, out);
        } else {
            self.groups(fields, points, out);
        }
    }
}

impl PointQuery for HeightAt {
    type Output = f32;
    #[inline(always)]
    fn at(&self, fields: &Fields<'_>, x: f64, z: f64) -> f32 {
        height_at(fields, x, z)
    }

    #[inline(always)]
    fn group(&self, fields: &Fields<'_>, points: &[[f64; 2]], out: &mut [f32]) {
        let (_, sums) = located_group::<false>(fields, points);
        for (value, sum) in out.iter_mut().zip(&sums) {
            *value = sum.height;
        }
    }

    #[inline(always)]
    fn batch<S: Shuffle>(
        &self,
        shuffle: S,
        fields: &Fields<'_>,
        points: &[[f64; 2]],
        out: &mut [f32],
    ) {
        if points.len() < lanes::FEWEST {
            self.singles(fields, points, out);
        } else if LANES_BUILT && in_lanes(fields, 0..fields.frame().grids.len()) {
            lanes::locate::<S, f32, true, false>(shuffle, fields, points, out);
        } else {
            self.groups(fields, points, out);
        }
    }
}

/// `query` at world (x, z), at the frame's SIMD level. Out of line, so that an ocean's
/// query and a [`Surface`]'s share one compiled copy.
#[inline(never)]
pub(crate) fn run<Q: PointQuery>(fields: &Fields<'_>, query: Q, x: f64, z: f64) -> Q::Output {
    fields.frame().simd.run_kernel(One {
        fields,
        query,
        point: [x, z],
    })
}

/// One point's query, as a [`Kernel`].
struct One<'a, Q> {
    fields: &'a Fields<'a>,
    query: Q,
    point: [f64; 2],
}

impl<Q: PointQuery> Kernel for One<'_, Q> {
    type Output = Q::Output;

    #[inline(always)]
    fn run(self) -> Q::Output {
        self.query.at(self.fields, self.point[0], self.point[1])
    }
}

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

/// `kernel` at SIMD level `simd`, with that level's [`Shuffle`] (AVX2's on AVX-512
/// machines too: the lanes are eight `f32`).
#[inline(always)]
fn run_shuffled<K: ShuffledKernel>(simd: Simd, kernel: K) {
    match simd {
        Simd::Baseline { fused } => kernel.run(lanes::Plain { fused }),
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2(v3) => simd.run_kernel(Shuffled {
            kernel,
            shuffle: v3,
        }),
        #[cfg(target_arch = "x86_64")]
        Simd::Avx512(v4) => simd.run_kernel(Shuffled {
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

/// One row of [`OceanState::sample_grid`], as a [`ShuffledKernel`]: its points eight at a
/// time, as [`OceanState::sample_many`] samples them.
struct GridRow<'a> {
    fields: &'a Fields<'a>,
    /// The row's first point `[x, z]`, in metres.
    start: [f64; 2],
    spacing: f64,
    row: &'a mut [SurfaceSample],
    cascades: &'a std::ops::Range<usize>,
}

impl ShuffledKernel for GridRow<'_> {
    #[inline(always)]
    fn run<S: Shuffle>(self, shuffle: S) {
        let [x, z] = self.start;
        let query = Sample(self.cascades.clone());
        for (chunk, out) in self.row.chunks_mut(lanes::LANES).enumerate() {
            let first = chunk * lanes::LANES;
            let points: [[f64; 2]; lanes::LANES] =
                std::array::from_fn(|c| [x + (first + c) as f64 * self.spacing, z]);
            query.batch(shuffle, self.fields, &points[..out.len()], out);
        }
    }
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
    let chunk =
        |out: &mut [Q::Output], points: &[[f64; 2]]| run_batch(simd, fields, points, out, query);
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

/// Checks a range of cascades of an ocean with `count` of them.
pub(crate) fn check_range(range: &std::ops::Range<usize>, count: usize) -> Result<(), Error> {
    if (range.start..=count).contains(&range.end) {
        Ok(())
    } else {
        Err(Error::CountOutOfRange {
            name: "cascades.end",
            count: range.end,
            min: range.start,
            max: count,
        })
    }
}

/// Unit normal (−s_x, 1, −s_z)/|…| of a surface with slope `slope`.
#[inline(always)]
pub(crate) fn normal_from_slope(slope: Vec2) -> Vec3 {
    Vec3::new(-slope.x, 1.0, -slope.y).normalize_or(Vec3::Y)
}

impl OceanState {
    /// The surface at the undisplaced world point (`x`, `z`) in metres (any finite
    /// coordinates; every cascade wraps periodically): each cascade's height, displacement
    /// and slope interpolated by a cubic B-spline through its grid values (exact at the grid
    /// points, smooth between them, with the same statistics wherever the point lies in a
    /// cell; see docs/theory.md), its foam bilinearly, and summed. With
    /// [`Interpolation::Bilinear`](crate::Interpolation::Bilinear) every field is
    /// bilinear.
    ///
    /// The spline's coefficients are computed in tiles of 32×32 grid cells, each by the
    /// first query after a step that reads it; a query reads one tile
    /// of each cascade, rarely two.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn sample(&self, x: f64, z: f64) -> Result<SurfaceSample, Error> {
        check_point(x, z)?;
        let cascades = 0..self.cascades.len();
        Ok(run(&Fields::Live(self), Sample(cascades), x, z))
    }

    /// [`OceanState::sample`] summed over the cascades in `cascades` only (indices into
    /// [`OceanState::cascades`], largest first) — for level of detail: far from the camera,
    /// `0..1` or `0..2` leave out waves too small to see, which would only shimmer. An empty
    /// range (`start == end`) gives flat water.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate; [`Error::CountOutOfRange`]
    /// unless `cascades.start ≤ cascades.end ≤` the number of cascades.
    pub fn sample_cascades(
        &self,
        x: f64,
        z: f64,
        cascades: std::ops::Range<usize>,
    ) -> Result<SurfaceSample, Error> {
        check_point(x, z)?;
        check_range(&cascades, self.cascades.len())?;
        Ok(run(&Fields::Live(self), Sample(cascades), x, z))
    }

    /// Finds the undisplaced point x₀ whose water lands on world point (`x`, `z`), i.e.
    /// x₀ + D(x₀) = (x, z), by Newton's method with the Jacobian of the interpolated
    /// displacement, from a first guess one Newton step away from (x, z) on the larger half
    /// of the cascades alone (whose waves move the water most), less the smaller cascades'
    /// displacement where that step lands, then with every cascade (at most
    /// [`QueryConfig::max_iterations`] steps, stopping once within
    /// [`QueryConfig::tolerance`]; on the default sea one step after the first guess, two
    /// for about 8 % of points), and says how well it did. A step that does not bring the
    /// water closer is halved, and where the surface (nearly) folds the step is the fixed
    /// point's x₀ ← p − D(x₀), so it converges wherever the surface does not fold (J > 0);
    /// where it folds (high choppiness, breaking crests) several points land on (x, z) or
    /// none does exactly, and the best iterate found is returned with `converged: false`.
    ///
    /// [`QueryConfig::max_iterations`]: crate::QueryConfig::max_iterations
    /// [`QueryConfig::tolerance`]: crate::QueryConfig::tolerance
    ///
    /// ```
    /// use ocean_fft::{OceanConfig, OceanState, Spectrum};
    /// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
    /// let ocean = OceanState::new(spectrum, OceanConfig { size: 32, ..Default::default() })?;
    /// let found = ocean.locate(25.0, -7.5)?;
    /// assert!(found.converged && found.miss < 1e-4);
    /// let water = ocean.sample(found.undisplaced[0], found.undisplaced[1])?;
    /// assert_eq!(water.height, ocean.height_at(25.0, -7.5)?);
    /// # Ok::<(), ocean_fft::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn locate(&self, x: f64, z: f64) -> Result<Location, Error> {
        check_point(x, z)?;
        Ok(run(&Fields::Live(self), Locate, x, z))
    }

    /// The surface at world point (`x`, `z`) after horizontal displacement: the sample of
    /// the undisplaced point whose water lands there (see [`OceanState::locate`], which also
    /// says whether the search converged).
    /// Its height, normal and foam are what a floating object at (x, z) feels.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn surface_at(&self, x: f64, z: f64) -> Result<SurfaceSample, Error> {
        check_point(x, z)?;
        Ok(run(&Fields::Live(self), SurfaceAt, x, z))
    }

    /// Water height y in metres at world point (`x`, `z`), after horizontal displacement —
    /// the query buoyancy and gameplay need. Where the surface folds the inversion may not
    /// converge; [`OceanState::locate`] reports how close it came.
    ///
    /// Cost: a few evaluations of the displacement and one of the height once the spline
    /// tiles it reads are computed; the first query after a step computes them (a tile of
    /// 32×32 cells of each cascade, rarely two: a few per cent of the step), so stepping and
    /// asking one boat's height costs little more than the step (measured figures: the
    /// repository's `docs/performance.md`). For many points use [`OceanState::heights_at`]
    /// (eight points at a time in vector lanes); to query from other threads while the ocean
    /// steps, [`OceanState::surface`].
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn height_at(&self, x: f64, z: f64) -> Result<f32, Error> {
        check_point(x, z)?;
        Ok(run(&Fields::Live(self), HeightAt, x, z))
    }

    /// [`OceanState::height_at`] for many world points (x, z), into `out` (same length as
    /// `points`), in parallel from 64 points on (fewer run on the calling thread); each
    /// result has the same bits as [`OceanState::height_at`] gives.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless `out` is as long as `points`; [`Error::NonFinite`]
    /// for a NaN or infinite coordinate. Nothing is written then.
    pub fn heights_at(&self, points: &[[f64; 2]], out: &mut [f32]) -> Result<(), Error> {
        check_batch(points, out.len())?;
        for_each_point(&Fields::Live(self), points, out, HeightAt);
        Ok(())
    }

    /// [`OceanState::surface_at`] for many world points (x, z): height, normal, slope and
    /// foam where the water is, into `out`.
    ///
    /// # Errors
    /// As [`OceanState::heights_at`].
    pub fn surfaces_at(&self, points: &[[f64; 2]], out: &mut [SurfaceSample]) -> Result<(), Error> {
        check_batch(points, out.len())?;
        for_each_point(&Fields::Live(self), points, out, SurfaceAt);
        Ok(())
    }

    /// [`OceanState::sample`] for many undisplaced world points (x, z), into `out` (same
    /// length as `points`).
    ///
    /// # Errors
    /// As [`OceanState::heights_at`].
    pub fn sample_many(&self, points: &[[f64; 2]], out: &mut [SurfaceSample]) -> Result<(), Error> {
        check_batch(points, out.len())?;
        let cascades = 0..self.cascades.len();
        for_each_point(&Fields::Live(self), points, out, Sample(cascades));
        Ok(())
    }

    /// A handle on the water as it is now, for queries from other threads while the ocean
    /// steps on: the [`Surface`] keeps answering about this frame's time, with the same bits
    /// as this ocean's own queries give now. The first handle of a frame copies the fields
    /// the queries read (the height, displacement and slope of every cascade and the foam,
    /// about 24·N² bytes per cascade); later handles
    /// of the same frame share it. See [`Surface`] for what a step does while a handle is
    /// held.
    pub fn surface(&mut self) -> Surface {
        let OceanState {
            frames,
            cascades,
            foam,
            ..
        } = self;
        frames.surface(cascades, foam)
    }

    /// The surface over a world-space window that sums every cascade: a `columns` × `rows`
    /// grid of undisplaced points with spacing `spacing` metres, starting at `origin`
    /// `[x, z]`, so sample (c, r) is [`sample`](Self::sample) at
    /// (x + c·`spacing`, z + r·`spacing`) and is stored at index r·`columns` + c (z is the
    /// row, as in the cascades' buffers). Rows run in parallel; the result does not depend on
    /// the number of threads. For heightmaps, previews and textures of the whole ocean over a
    /// region (a cascade's own buffers cover only its tile, and only its band of waves).
    ///
    /// ```
    /// use ocean_fft::{OceanConfig, OceanState, Spectrum, SurfaceSample};
    /// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
    /// let ocean = OceanState::new(spectrum, OceanConfig { size: 32, ..Default::default() })?;
    /// let mut window = vec![SurfaceSample::default(); 64 * 48];
    /// ocean.sample_grid([-100.0, 250.0], 2.0, [64, 48], &mut window)?;   // 128 m × 96 m
    /// assert_eq!(window[5 * 64 + 7], ocean.sample(-100.0 + 7.0 * 2.0, 250.0 + 5.0 * 2.0)?);
    /// # Ok::<(), ocean_fft::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite `origin`; [`Error::NonFinite`] or
    /// [`Error::OutOfRange`] unless `spacing` is finite and > 0; [`Error::CountOutOfRange`]
    /// for a zero column or row count, or one whose product overflows;
    /// [`Error::LengthMismatch`] unless `out` holds `columns`·`rows` samples. Nothing is
    /// written then.
    pub fn sample_grid(
        &self,
        origin: [f64; 2],
        spacing: f64,
        [columns, rows]: [usize; 2],
        out: &mut [SurfaceSample],
    ) -> Result<(), Error> {
        check_point(origin[0], origin[1])?;
        for (name, count) in [("columns", columns), ("rows", rows)] {
            if count == 0 {
                return Err(Error::CountOutOfRange {
                    name,
                    count,
                    min: 1,
                    max: usize::MAX,
                });
            }
        }
        // The far corner must stay finite too.
        let room = |start: f64, count: usize| (f64::MAX - start.abs()) / (count - 1).max(1) as f64;
        let widest = room(origin[0], columns).min(room(origin[1], rows));
        error::in_range_f64("spacing", spacing, Excluded(0.0), Included(widest))?;
        let len = columns.checked_mul(rows).ok_or(Error::CountOutOfRange {
            name: "rows",
            count: rows,
            min: 1,
            max: usize::MAX / columns,
        })?;
        error::length("out", out.len(), len)?;
        let fields = Fields::Live(self);
        let cascades = 0..self.cascades.len();
        let simd = self.frames.current.simd;
        out.par_chunks_mut(columns)
            .enumerate()
            .for_each(|(r, row)| {
                run_shuffled(
                    simd,
                    GridRow {
                        fields: &fields,
                        start: [origin[0], origin[1] + r as f64 * spacing],
                        spacing,
                        row,
                        cascades: &cascades,
                    },
                );
            });
        Ok(())
    }
}
