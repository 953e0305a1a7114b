//! One query at one world point ([`PointQuery`]: sample, locate, surface, height), the
//! ways it answers a group or a batch of points, and its run at the frame's SIMD level.

use super::frame::Fields;
use super::inversion::{
    coast_factors, evaluate_group, height_at, locate, located_group, sample, surface_at,
    surface_sample, GROUP,
};
use super::lanes::{self, Shuffle};
use super::results::{surface, Location, SurfaceSample};
use crate::error::Error;
use crate::math::simd::Kernel;
use crate::wake::Wakes;

/// Checks a world point: both coordinates finite (any finite value: the cascades wrap).
pub(crate) fn check_point(x: f64, z: f64) -> Result<(), Error> {
    for (name, value) in [("x", x), ("z", z)] {
        if !value.is_finite() {
            return Err(Error::NonFinite { name });
        }
    }
    Ok(())
}

/// A query at one world point, for [`run`] and [`for_each_point`](super::batch::for_each_point):
/// plain functions of the fields rather than closures, so that each is compiled at the frame's SIMD
/// level (see [`Kernel`]).
pub(crate) trait PointQuery: Sync {
    type Output: Send;
    fn at(&self, fields: &Fields<'_>, x: f64, z: f64) -> Self::Output;

    /// Adds the wake window's `wakes` to `out`, the answer at world (x, z) (nothing by
    /// default: a [`Location`] has no wake).
    #[inline(always)]
    fn add_wake(&self, wakes: &Wakes, x: f64, z: f64, out: &mut Self::Output) {
        let _ = (wakes, x, z, out);
    }

    /// [`PointQuery::add_wake`] of each of `points` to `out`, if the frame has a wake.
    #[inline(always)]
    fn add_wakes(&self, fields: &Fields<'_>, points: &[[f64; 2]], out: &mut [Self::Output]) {
        if let Some(wakes) = &fields.frame().wake {
            for (value, &[x, z]) in out.iter_mut().zip(points) {
                self.add_wake(wakes, x, z, value);
            }
        }
    }

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

    /// The wake where the water of the undisplaced point (x, z) lands (with cascade 0, which
    /// carries the wake as it carries the foam).
    #[inline(always)]
    fn add_wake(&self, wakes: &Wakes, x: f64, z: f64, out: &mut SurfaceSample) {
        if self.0.start == 0 && !self.0.is_empty() {
            let [dx, dz] = out.displacement;
            add_wake_to(wakes, x + f64::from(dx), z + f64::from(dz), out);
        }
    }

    #[inline(always)]
    fn group(&self, fields: &Fields<'_>, points: &[[f64; 2]], out: &mut [SurfaceSample]) {
        let mut factors = [None; GROUP];
        if fields.frame().coast.is_some() {
            for (factors, &[x, z]) in factors.iter_mut().zip(points) {
                *factors = coast_factors(fields, x, z);
            }
        }
        let range = self.0.clone();
        let sums =
            evaluate_group::<true, true>(fields, |p| points[p], points.len(), range, &factors);
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
    fn add_wake(&self, wakes: &Wakes, x: f64, z: f64, out: &mut SurfaceSample) {
        add_wake_to(wakes, x, z, out);
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
    fn add_wake(&self, wakes: &Wakes, x: f64, z: f64, out: &mut f32) {
        *out += wakes.at(x, z).0;
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
/// query and a [`Surface`](super::surface::Surface)'s share one compiled copy.
#[inline(never)]
pub(crate) fn run<Q: PointQuery>(fields: &Fields<'_>, query: Q, x: f64, z: f64) -> Q::Output {
    let frame = fields.frame();
    let mut out = frame.simd.run_kernel(One {
        fields,
        query: &query,
        point: [x, z],
    });
    if let Some(wakes) = &frame.wake {
        query.add_wake(wakes, x, z, &mut out);
    }
    out
}

/// Adds the wake at world (x, z) to a surface sample: its height, its slope, the normal of
/// the summed slope, and its foam w over the ocean's f as f + w·(1 − f) (unchanged outside
/// the window).
#[inline(always)]
pub(crate) fn add_wake_to(wakes: &Wakes, x: f64, z: f64, out: &mut SurfaceSample) {
    let (height, slope, foam) = wakes.sample(x, z);
    if height == 0.0 && slope == [0.0; 2] && foam == 0.0 {
        return;
    }
    let slope = [out.slope[0] + slope[0], out.slope[1] + slope[1]];
    let foam = out.foam + foam * (1.0 - out.foam);
    *out = surface(out.height + height, out.displacement, slope, foam);
}

/// One point's query, as a [`Kernel`].
struct One<'a, Q> {
    fields: &'a Fields<'a>,
    query: &'a Q,
    point: [f64; 2],
}

impl<Q: PointQuery> Kernel for One<'_, Q> {
    type Output = Q::Output;

    #[inline(always)]
    fn run(self) -> Q::Output {
        self.query.at(self.fields, self.point[0], self.point[1])
    }
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
