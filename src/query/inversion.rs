//! The evaluation of the summed fields at a point (spline taps or bilinear stencil, cascade
//! by cascade) and the inversion of the horizontal displacement by Newton's method, for one
//! point or a group of points whose work is interleaved.

use glam::Vec2;

use super::config::QueryConfig;
use super::frame::{cell_in, Fields};
use super::results::{normal_from_slope, Location, SurfaceSample};
use super::spline::{self, Source, TileData, Weights};
use crate::coast::Factors;
use crate::math::periodic::Stencil;

/// What a query sums over the cascades at one undisplaced point (what it did not ask for is
/// zero).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Summed {
    /// `[D_x, D_z]` in metres.
    pub(super) displacement: [f32; 2],
    /// `[∂D_x/∂x, ∂D_x/∂z, ∂D_z/∂x, ∂D_z/∂z]` of the summed displacement.
    jacobian: [f32; 4],
    /// η in metres.
    pub(super) height: f32,
    /// `[∂y/∂x, ∂y/∂z]`.
    slope: [f32; 2],
}

/// Where a point lies on one cascade: its spline taps (tile, cell in the tile, weights), or
/// its bilinear stencil.
enum Taps<'a> {
    Spline(&'a TileData, usize, usize, Weights),
    Bilinear(Stencil, Source<'a>, f32, f32),
}

/// The taps of undisplaced world (x, z) on cascade `c` (the weights' derivatives with
/// `GRADIENT`), computing the spline tile it reads if no query did so yet.
#[inline(always)]
fn taps<'a, const GRADIENT: bool>(fields: &'a Fields<'a>, c: usize, x: f64, z: f64) -> Taps<'a> {
    let frame = fields.frame();
    let grid = &frame.grids[c];
    let at = cell_in(grid, x, z);
    let (ix, fx, iz, fz) = at;
    match &grid.tiles {
        Some(tiles) => {
            let (tile, lx, lz) = tiles.cell(ix, iz, || fields.source(c), frame.simd);
            Taps::Spline(tile, lx, lz, Weights::new::<GRADIENT>(fx, fz))
        }
        None => Taps::Bilinear(Stencil::new(at, grid.n), fields.source(c), fx, fz),
    }
}

/// Adds the fields of cascade `c` at undisplaced world (x, z) to `total`: the
/// displacement with `DISPLACEMENT`, and with `JACOBIAN` its derivatives (per metre), the
/// height with `HEIGHT`, the slope with `SLOPE`. A field's value does not depend on what
/// else is asked: the same operations in the same order. Summing the cascades in order
/// from [`Summed::default`] gives the queries' values, whether one point is summed at a
/// time or several in turn (see [`PointQuery::group`](super::point::PointQuery::group)).
#[inline(always)]
fn accumulate<
    const DISPLACEMENT: bool,
    const JACOBIAN: bool,
    const HEIGHT: bool,
    const SLOPE: bool,
>(
    fields: &Fields<'_>,
    c: usize,
    [x, z]: [f64; 2],
    factors: Option<&Factors>,
    total: &mut Summed,
) {
    let frame = fields.frame();
    let (per_metre, simd) = (frame.grids[c].per_metre, frame.simd);
    let (mut displacement, [mut gx, mut gz], mut height, mut slope) =
        match taps::<JACOBIAN>(fields, c, x, z) {
            Taps::Spline(tile, lx, lz, w) => {
                let [displacement, gx, gz] = if DISPLACEMENT || JACOBIAN {
                    spline::displacement::<JACOBIAN>(simd, tile, lx, lz, &w)
                } else {
                    [[0.0; 2]; 3]
                };
                let height = if HEIGHT {
                    spline::height(simd, tile, lx, lz, &w)
                } else {
                    0.0
                };
                let slope = if SLOPE {
                    spline::slope(simd, tile, lx, lz, &w)
                } else {
                    [0.0; 2]
                };
                (displacement, [gx, gz], height, slope)
            }
            Taps::Bilinear(bilinear, source, fx, fz) => {
                let displacement = if DISPLACEMENT || JACOBIAN {
                    bilinear.vector(source.displacement).to_array()
                } else {
                    [0.0; 2]
                };
                let gradient = if JACOBIAN {
                    let d = bilinear
                        .index
                        .map(|i| Vec2::from_array(source.displacement[i]));
                    let gx = (d[1] - d[0]) * (1.0 - fz) + (d[3] - d[2]) * fz;
                    let gz = (d[2] - d[0]) * (1.0 - fx) + (d[3] - d[1]) * fx;
                    [gx.to_array(), gz.to_array()]
                } else {
                    [[0.0; 2]; 2]
                };
                let height = if HEIGHT {
                    bilinear.scalar(source.height)
                } else {
                    0.0
                };
                let slope = if SLOPE {
                    bilinear.vector(source.slope).to_array()
                } else {
                    [0.0; 2]
                };
                (displacement, gradient, height, slope)
            }
        };
    if let Some(factors) = factors {
        // The cascade's waves scaled by the coast's factor at the point (its gradient
        // neglected: it varies over many wavelengths, see docs/theory.md, "Coasts").
        let f = factors[c];
        displacement = displacement.map(|v| v * f);
        gx = gx.map(|v| v * f);
        gz = gz.map(|v| v * f);
        height *= f;
        slope = slope.map(|v| v * f);
    }
    if DISPLACEMENT || JACOBIAN {
        total.displacement[0] += displacement[0];
        total.displacement[1] += displacement[1];
    }
    if JACOBIAN {
        // Fused (one rounding), as the lanes add them.
        let j = &mut total.jacobian;
        j[0] = simd.mul_add(gx[0], per_metre, j[0]);
        j[1] = simd.mul_add(gz[0], per_metre, j[1]);
        j[2] = simd.mul_add(gx[1], per_metre, j[2]);
        j[3] = simd.mul_add(gz[1], per_metre, j[3]);
    }
    if HEIGHT {
        total.height += height;
    }
    if SLOPE {
        total.slope[0] += slope[0];
        total.slope[1] += slope[1];
    }
}

/// [`accumulate`] of cascades `range` at undisplaced world (x, z), in order, each scaled by
/// its coast factor in `factors` (`None`: no depth map).
#[inline(always)]
fn evaluate<
    const DISPLACEMENT: bool,
    const JACOBIAN: bool,
    const HEIGHT: bool,
    const SLOPE: bool,
>(
    fields: &Fields<'_>,
    x: f64,
    z: f64,
    range: std::ops::Range<usize>,
    factors: Option<&Factors>,
) -> Summed {
    let mut total = Summed::default();
    for c in range {
        accumulate::<DISPLACEMENT, JACOBIAN, HEIGHT, SLOPE>(fields, c, [x, z], factors, &mut total);
    }
    total
}

/// The coast's factors of the cascades at world (x, z) (`None` without a depth map:
/// nothing scaled). A query at an undisplaced point reads them there; a query at a world
/// point p (`height_at`, `surface_at`, `locate`) reads them at p once and scales the
/// cascades by them at every iterate of its search and where it lands: the factors vary
/// over the map's cells and the shoaling distance, not over the metre between p and the
/// water's rest point (see docs/theory.md, "Coasts").
#[inline(always)]
pub(super) fn coast_factors(fields: &Fields<'_>, x: f64, z: f64) -> Option<Factors> {
    let frame = fields.frame();
    frame
        .coast
        .as_ref()
        .map(|coast| coast.factors(frame.time, x, z))
}

/// The [`SurfaceSample`] of displacement `displacement`, height and slope `fields` and foam
/// `foam`.
#[inline(always)]
pub(super) fn surface_sample(displacement: [f32; 2], fields: Summed, foam: f32) -> SurfaceSample {
    let slope = Vec2::from_array(fields.slope);
    SurfaceSample {
        height: fields.height,
        displacement,
        slope: fields.slope,
        normal: normal_from_slope(slope).to_array(),
        foam,
    }
}

/// The surface at undisplaced world (x, z), summed over the cascades in `range` (the foam
/// only if cascade 0 is among them).
#[inline(always)]
pub(super) fn sample(
    fields: &Fields<'_>,
    x: f64,
    z: f64,
    range: std::ops::Range<usize>,
) -> SurfaceSample {
    let foam = if range.contains(&0) {
        fields.foam_at(x, z)
    } else {
        0.0
    };
    let factors = coast_factors(fields, x, z);
    let summed = evaluate::<true, false, true, true>(fields, x, z, range, factors.as_ref());
    surface_sample(summed.displacement, summed, foam)
}

/// Smallest determinant of I + ∇D for which a Newton step is taken; below it (a surface that
/// folds, or nearly) the step is the fixed point's, p − x₀ − D(x₀).
pub(super) const MIN_DETERMINANT: f64 = 0.05;

/// The Newton step δ solving (I + ∇D) δ = `residual` for the Jacobian `jacobian` of D
/// (`[∂D_x/∂x, ∂D_x/∂z, ∂D_z/∂x, ∂D_z/∂z]`), or the fixed point's step, `residual` itself,
/// where the surface (nearly) folds.
#[inline(always)]
pub(super) fn newton_step(residual: [f64; 2], jacobian: [f32; 4]) -> [f64; 2] {
    let [a, b, c, d] = jacobian.map(f64::from);
    let (a, d) = (1.0 + a, 1.0 + d);
    let determinant = a * d - b * c;
    if determinant > MIN_DETERMINANT {
        [
            (d * residual[0] - b * residual[1]) / determinant,
            (a * residual[1] - c * residual[0]) / determinant,
        ]
    } else {
        residual
    }
}

/// Cascades the first step of a search reads ([`first_guess`]): the larger half of an
/// ocean's `count` (the small waves move the water least). The rest correct the step
/// without their Jacobian.
#[inline(always)]
pub(super) fn guessing(count: usize) -> std::ops::Range<usize> {
    0..count.div_ceil(2)
}

/// Where a search for the water landing on world p = (x, z) starts: p plus one Newton step
/// on the [`guessing`] cascades alone (their displacement D_L and its Jacobian at p, the
/// step solving (I + ∇D_L) δ = −D_L), less the displacement of the other cascades where that
/// step lands (the short waves' Jacobian changes too fast to carry over from p, and their
/// displacement is centimetres). On the default sea it lands 4.6 mm from the answer
/// (median; 2.5 cm without the subtraction) where p is metres from it, and 92 % of searches
/// then end after one Newton step (half without it): 9.2 cascades evaluated a point, one
/// without the Jacobian, instead of 9.5 (10.2 from p).
#[inline(always)]
pub(super) fn first_guess(
    fields: &Fields<'_>,
    x: f64,
    z: f64,
    factors: Option<&Factors>,
) -> [f64; 2] {
    let count = fields.frame().grids.len();
    let cascades = guessing(count);
    let rest = cascades.end..count;
    let summed = evaluate::<true, true, false, false>(fields, x, z, cascades, factors);
    let [dx, dz] = summed.displacement.map(f64::from);
    let step = newton_step([-dx, -dz], summed.jacobian);
    let [x, z] = [x + step[0], z + step[1]];
    let short = evaluate::<true, false, false, false>(fields, x, z, rest, factors).displacement;
    [x - f64::from(short[0]), z - f64::from(short[1])]
}

/// One point's search for the undisplaced point whose water lands on it, by Newton's
/// method on x₀ + D(x₀) = p from [`first_guess`] (see
/// [`Water::locate`](crate::Water::locate)): the iterate to evaluate next and what
/// the evaluations so far found.
#[derive(Debug, Clone, Copy)]
pub(super) struct Search {
    /// The query point p.
    target: [f64; 2],
    /// The best iterate so far.
    pub(super) best: Location,
    /// The summed displacement at the best iterate.
    pub(super) displacement: [f32; 2],
    /// The last step taken from the best point, and the fraction of it being tried: halved
    /// whenever the miss does not shrink (a step that overshoots, near a fold).
    base: [f64; 2],
    step: [f64; 2],
    fraction: f64,
    /// The iterate to evaluate next.
    next: [f64; 2],
    /// Whether the search is over (converged, or out of iterations).
    done: bool,
    /// The coast's factors at the target ([`coast_factors`]).
    pub(super) factors: Option<Factors>,
}

impl Search {
    /// The search for the water landing on world (x, z), from the undisplaced point `start`
    /// ([`first_guess`]), with the coast's `factors` there.
    #[inline(always)]
    pub(super) fn new(x: f64, z: f64, start: [f64; 2], factors: Option<Factors>) -> Search {
        Search {
            target: [x, z],
            best: Location {
                undisplaced: start,
                miss: f32::INFINITY,
                iterations: 0,
                converged: false,
            },
            displacement: [0.0; 2],
            base: start,
            step: [0.0; 2],
            fraction: 1.0,
            next: start,
            done: false,
            factors,
        }
    }

    /// Takes the summed displacement and Jacobian at [`Search::next`] (evaluation number
    /// `iteration`), and sets the iterate after it or ends the search.
    #[inline(always)]
    fn update(&mut self, iteration: usize, fields: &Summed, query: &QueryConfig) {
        let [x, z] = self.target;
        let x0 = self.next;
        let Summed {
            displacement,
            jacobian,
            ..
        } = *fields;
        let landed = [
            x0[0] + f64::from(displacement[0]),
            x0[1] + f64::from(displacement[1]),
        ];
        let residual = [x - landed[0], z - landed[1]];
        // A correctly rounded square root: the same bits in both determinism modes (no
        // overflow: a residual is at most a few displacements).
        let miss = (residual[0] * residual[0] + residual[1] * residual[1]).sqrt() as f32;
        if miss < self.best.miss {
            self.best = Location {
                undisplaced: x0,
                miss,
                iterations: iteration,
                converged: miss < query.tolerance,
            };
            self.displacement = displacement;
            if self.best.converged {
                self.done = true;
                return;
            }
            self.step = newton_step(residual, jacobian);
            self.base = x0;
            self.fraction = 1.0;
        } else {
            self.fraction *= 0.5;
        }
        self.done = iteration == query.max_iterations;
        self.next = [
            self.base[0] + self.fraction * self.step[0],
            self.base[1] + self.fraction * self.step[1],
        ];
    }
}

/// The undisplaced point whose water lands on world (x, z), by Newton's method on
/// x₀ + D(x₀) = p from [`first_guess`] (see
/// [`Water::locate`](crate::Water::locate)), and the summed displacement there.
#[inline(always)]
pub(super) fn locate(fields: &Fields<'_>, x: f64, z: f64) -> (Location, [f32; 2], Option<Factors>) {
    let frame = fields.frame();
    let factors = coast_factors(fields, x, z);
    let start = first_guess(fields, x, z, factors.as_ref());
    let mut search = Search::new(x, z, start, factors);
    for iteration in 0..=frame.query.max_iterations {
        let [x0, z0] = search.next;
        let cascades = 0..frame.grids.len();
        let summed =
            evaluate::<true, true, false, false>(fields, x0, z0, cascades, factors.as_ref());
        search.update(iteration, &summed, &frame.query);
        if search.done {
            break;
        }
    }
    (search.best, search.displacement, factors)
}

/// Points whose queries [`PointQuery::group`](super::point::PointQuery::group) interleaves: enough
/// independent work for the CPU to overlap one point's memory reads with the others' arithmetic.
pub(super) const GROUP: usize = 8;

/// [`locate`] of each of `points` (at most [`GROUP`]) into `searches`, the points' Newton
/// iterations in step and each iteration's cascades visited point after point (the same
/// operations for each point as [`locate`]'s, so the same bits).
#[inline(always)]
fn locate_group(fields: &Fields<'_>, points: &[[f64; 2]], searches: &mut [Search; GROUP]) {
    let frame = fields.frame();
    let count = points.len();
    for (search, &[x, z]) in searches.iter_mut().zip(points) {
        let factors = coast_factors(fields, x, z);
        *search = Search::new(x, z, first_guess(fields, x, z, factors.as_ref()), factors);
    }
    for iteration in 0..=frame.query.max_iterations {
        let mut sums = [Summed::default(); GROUP];
        for c in 0..frame.grids.len() {
            for (sum, search) in sums.iter_mut().zip(&searches[..count]) {
                if !search.done {
                    let factors = search.factors.as_ref();
                    accumulate::<true, true, false, false>(fields, c, search.next, factors, sum);
                }
            }
        }
        let mut done = true;
        for (sum, search) in sums.iter().zip(&mut searches[..count]) {
            if !search.done {
                search.update(iteration, sum, &frame.query);
                done &= search.done;
            }
        }
        if done {
            break;
        }
    }
}

/// The height (and with `SLOPE` the slope) of cascades `range` at each of `points` (at most
/// [`GROUP`]), scaled by each point's coast `factors`, the cascades visited point after point (the same operations for each point
/// as [`evaluate`]'s, so the same bits).
#[inline(always)]
pub(super) fn evaluate_group<const DISPLACEMENT: bool, const SLOPE: bool>(
    fields: &Fields<'_>,
    points: impl Fn(usize) -> [f64; 2],
    count: usize,
    range: std::ops::Range<usize>,
    factors: &[Option<Factors>; GROUP],
) -> [Summed; GROUP] {
    let mut sums = [Summed::default(); GROUP];
    for c in range {
        for (p, sum) in sums[..count].iter_mut().enumerate() {
            let factors = factors[p].as_ref();
            accumulate::<DISPLACEMENT, false, true, SLOPE>(fields, c, points(p), factors, sum);
        }
    }
    sums
}

/// The surface where the water at world (x, z) comes from: the sample at the located point.
#[inline(always)]
pub(super) fn surface_at(fields: &Fields<'_>, x: f64, z: f64) -> SurfaceSample {
    let (location, displacement, factors) = locate(fields, x, z);
    let [x0, z0] = location.undisplaced;
    let cascades = 0..fields.frame().grids.len();
    let summed = evaluate::<false, false, true, true>(fields, x0, z0, cascades, factors.as_ref());
    surface_sample(displacement, summed, fields.foam_at(x0, z0))
}

/// The water height at world (x, z).
#[inline(always)]
pub(super) fn height_at(fields: &Fields<'_>, x: f64, z: f64) -> f32 {
    let (location, _, factors) = locate(fields, x, z);
    let [x0, z0] = location.undisplaced;
    let cascades = 0..fields.frame().grids.len();
    evaluate::<false, false, true, false>(fields, x0, z0, cascades, factors.as_ref()).height
}

/// [`locate_group`] of `points` (at most [`GROUP`]), then the height (and with `SLOPE` the
/// slope) of every cascade at each point found: what the grouped `heights_at` and
/// `surfaces_at` need.
#[inline(always)]
pub(super) fn located_group<const SLOPE: bool>(
    fields: &Fields<'_>,
    points: &[[f64; 2]],
) -> ([Search; GROUP], [Summed; GROUP]) {
    let mut searches = [Search::new(0.0, 0.0, [0.0; 2], None); GROUP];
    locate_group(fields, points, &mut searches);
    let at = |p: usize| searches[p].best.undisplaced;
    let cascades = 0..fields.frame().grids.len();
    let factors = searches.map(|search| search.factors);
    let sums = evaluate_group::<false, SLOPE>(fields, at, points.len(), cascades, &factors);
    (searches, sums)
}
