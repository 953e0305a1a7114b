//! The fields of the cascades at eight points, one a lane ([`evaluate`]): each lane's cell
//! and tile, then every cascade's taps summed as the single query sums them; the foam at
//! eight points, and the surface at eight undisplaced points ([`sample`]).

use super::shuffle::Shuffle;
use super::{cells, each, F32s, F64s, FEWEST, LANES};
use crate::cascade::MAX_CASCADES;
use crate::coast::Factors;
use crate::math::periodic::Period;
use crate::math::simd::Kernel;
use crate::query::frame::Fields;
use crate::query::inversion;
use crate::query::results::{surface, SurfaceSample};
use crate::query::spline::{self, Lanes, TileData, STRIDE};

/// What eight lanes sum over the cascades at their points (zero where not asked).
#[derive(Clone, Copy, Default)]
pub(super) struct SummedLanes {
    /// `[D_x, D_z]` in metres.
    pub(super) displacement: [F32s; 2],
    /// `[∂D_x/∂x, ∂D_x/∂z, ∂D_z/∂x, ∂D_z/∂z]`.
    pub(super) jacobian: [F32s; 4],
    /// η in metres.
    pub(super) height: F32s,
    /// `[∂y/∂x, ∂y/∂z]`.
    pub(super) slope: [F32s; 2],
}

/// Σ w_x w_z c of eight lanes' pairs (taps of two components, interleaved) over their 4×4
/// taps (the field of pairs starting at `field` in each tile), and with `GRADIENT` its
/// derivatives along x and z per cell: [`spline::displacement`]'s operations lane by lane
/// (columns first: tap j's Σ_r w_z,r c_r,j, then Σ_t w_x,t S_t).
#[inline(always)]
fn pairs<S: Shuffle, const GRADIENT: bool>(
    shuffle: S,
    tiles: &[&TileData; LANES],
    field: usize,
    at: &[usize; LANES],
    [wx, wz, dx, dz]: &[[Lanes; 4]; 4],
) -> [[F32s; 2]; 3] {
    let windows: [&[f32; PAIR_WINDOW]; LANES] = std::array::from_fn(|l| {
        let start = field + 2 * at[l];
        tiles[l][start..start + PAIR_WINDOW]
            .try_into()
            .expect("a cell's taps lie in its tile")
    });
    let zero = [0.0f32; LANES];
    if GRADIENT {
        // Whole rows (timed faster here than two taps at a time, though more registers
        // spill).
        let mut columns = [zero; 8];
        let mut columns_z = [zero; 8];
        for r in 0..4 {
            let rows = std::array::from_fn(|l| {
                let start = 2 * r * STRIDE;
                windows[l][start..start + 8].try_into().expect("four pairs")
            });
            let taps = shuffle.transpose8(rows);
            let (w, d) = (wz[r].0, dz[r].0);
            for ((column, column_z), &taps) in columns.iter_mut().zip(&mut columns_z).zip(&taps) {
                *column = shuffle.add_product(*column, w, taps);
                *column_z = shuffle.add_product(*column_z, d, taps);
            }
        }
        let mut out = [[zero; 2]; 3];
        for k in 0..2 {
            out[0][k] = across(shuffle, wx, &columns, k);
            out[1][k] = across(shuffle, dx, &columns, k);
            out[2][k] = across(shuffle, wx, &columns_z, k);
        }
        return out;
    }
    // Two taps (four floats) of each row at a time, so that the column sums, the rows and
    // the weights fit in the registers; terms[i] holds taps i's and i + 2's terms of each
    // output (tap i's product, then tap i + 2's added to it in one rounding).
    let mut terms = [[[zero; 2]; 3]; 2];
    let outputs = if GRADIENT { 3 } else { 1 };
    for half in 0..2 {
        let mut columns = [zero; 4];
        let mut columns_z = [zero; 4];
        for r in 0..4 {
            let taps = shuffle.transpose4(pair_row(&windows, r, half));
            let (w, d) = (wz[r].0, dz[r].0);
            for ((column, column_z), &taps) in columns.iter_mut().zip(&mut columns_z).zip(&taps) {
                *column = shuffle.add_product(*column, w, taps);
                if GRADIENT {
                    *column_z = shuffle.add_product(*column_z, d, taps);
                }
            }
        }
        for i in 0..2 {
            let t = 2 * half + i;
            for k in 0..2 {
                let column = columns[2 * i + k];
                let column_z = columns_z[2 * i + k];
                let factors = [(wx[t].0, column), (dx[t].0, column), (wx[t].0, column_z)];
                for (o, &(w, column)) in factors.iter().enumerate().take(outputs) {
                    terms[i][o][k] = if half == 0 {
                        shuffle.mul(w, column)
                    } else {
                        shuffle.add_product(terms[i][o][k], w, column)
                    };
                }
            }
        }
    }
    // Σ_t as the scalar code adds the taps: (0 + 2) + (1 + 3).
    let mut out = [[zero; 2]; 3];
    for o in 0..outputs {
        for k in 0..2 {
            out[o][k] = shuffle.add(terms[0][o][k], terms[1][o][k]);
        }
    }
    out
}

/// Σ_t w_t S_t over the four taps of component `k` of `columns` (pair t at 2t + k), added
/// (tap 0 + tap 2) + (tap 1 + tap 3) as the scalar code adds them (tap 2's and 3's
/// products fused into the sums).
#[inline(always)]
fn across<S: Shuffle>(shuffle: S, w: &[Lanes; 4], columns: &[F32s; 8], k: usize) -> F32s {
    let a = shuffle.mul(w[0].0, columns[k]);
    let c = shuffle.mul(w[1].0, columns[2 + k]);
    let ab = shuffle.add_product(a, w[2].0, columns[4 + k]);
    let cd = shuffle.add_product(c, w[3].0, columns[6 + k]);
    shuffle.add(ab, cd)
}

/// Floats from a cell's first pair to its last (four rows of four pairs, `STRIDE` pairs
/// apart).
const PAIR_WINDOW: usize = 2 * (3 * STRIDE + 4);

/// Pairs 2·`half` and 2·`half` + 1 of row `r` of each lane's window.
#[inline(always)]
fn pair_row<'a>(
    windows: &[&'a [f32; PAIR_WINDOW]; LANES],
    r: usize,
    half: usize,
) -> [&'a [f32; 4]; LANES] {
    let start = 2 * r * STRIDE + 4 * half;
    std::array::from_fn(|l| windows[l][start..start + 4].try_into().expect("two pairs"))
}

/// One cascade's part of an evaluation, before its taps are read: each lane's tile, its
/// first tap's index there and its fractions across the cell, and the cascade's cells per
/// metre.
#[derive(Clone, Copy)]
struct Prepared<'a> {
    found: [&'a TileData; LANES],
    at: [u32; LANES],
    fraction: [F32s; 2],
    per_metre: f32,
}

/// Σ w_x w_z c of eight lanes' heights: [`spline::height`] lane by lane.
#[inline(always)]
fn heights<S: Shuffle>(
    shuffle: S,
    tiles: &[&TileData; LANES],
    at: &[usize; LANES],
    [wx, wz]: [&[Lanes; 4]; 2],
) -> F32s {
    let mut sum = [[0.0f32; LANES]; 4];
    for r in 0..4 {
        let taps = shuffle.transpose4(std::array::from_fn(|l| {
            let start = spline::HEIGHT + at[l] + r * STRIDE;
            tiles[l][start..start + 4]
                .try_into()
                .expect("the row lies in the tile")
        }));
        for (t, taps) in taps.iter().enumerate() {
            let line = shuffle.mul(wx[t].0, *taps);
            sum[t] = shuffle.add_product(sum[t], wz[r].0, line);
        }
    }
    shuffle.add(shuffle.add(sum[0], sum[2]), shuffle.add(sum[1], sum[3]))
}

/// The fields of cascades `range` at the undisplaced world points `[x, z]` of eight lanes,
/// each cascade scaled by each lane's coast `factors` (`None`: no depth map), summed in
/// order as [`inversion`]'s `evaluate` sums them: the displacement with
/// `DISPLACEMENT`, its Jacobian with `JACOBIAN`, the height with `HEIGHT`, the slope with
/// `SLOPE`. Every cascade in `range` must have spline tiles.
/// Out of line at the batch's SIMD level (see [`Shuffle::run`]): the searches call it from
/// several places, each of which would otherwise hold a copy.
#[inline(always)]
pub(super) fn evaluate<
    S: Shuffle,
    const DISPLACEMENT: bool,
    const JACOBIAN: bool,
    const HEIGHT: bool,
    const SLOPE: bool,
>(
    shuffle: S,
    fields: &Fields<'_>,
    at: &[F64s; 2],
    range: std::ops::Range<usize>,
    factors: Option<&[Factors; LANES]>,
) -> SummedLanes {
    shuffle.run(Evaluate::<S, DISPLACEMENT, JACOBIAN, HEIGHT, SLOPE> {
        shuffle,
        fields,
        at,
        range,
        factors,
    })
}

/// The coast's factors at eight world points (`None` without a depth map): what
/// `inversion::coast_factors` gives at each.
#[inline(always)]
pub(super) fn coast_factors(fields: &Fields<'_>, [x, z]: &[F64s; 2]) -> Option<[Factors; LANES]> {
    let frame = fields.frame();
    frame
        .coast
        .as_ref()
        .map(|coast| coast.factors_many(frame.time, x, z))
}

/// [`evaluate`]'s arguments, as a [`Kernel`].
struct Evaluate<
    'a,
    S,
    const DISPLACEMENT: bool,
    const JACOBIAN: bool,
    const HEIGHT: bool,
    const SLOPE: bool,
> {
    shuffle: S,
    fields: &'a Fields<'a>,
    at: &'a [F64s; 2],
    range: std::ops::Range<usize>,
    factors: Option<&'a [Factors; LANES]>,
}

impl<
        S: Shuffle,
        const DISPLACEMENT: bool,
        const JACOBIAN: bool,
        const HEIGHT: bool,
        const SLOPE: bool,
    > Kernel for Evaluate<'_, S, DISPLACEMENT, JACOBIAN, HEIGHT, SLOPE>
{
    type Output = SummedLanes;

    #[inline(always)]
    fn run(self) -> SummedLanes {
        let Evaluate {
            shuffle,
            fields,
            at: [x, z],
            range,
            factors,
        } = self;
        sum::<S, DISPLACEMENT, JACOBIAN, HEIGHT, SLOPE>(shuffle, fields, [x, z], range, factors)
    }
}

/// [`evaluate`]'s work.
#[inline(always)]
fn sum<
    S: Shuffle,
    const DISPLACEMENT: bool,
    const JACOBIAN: bool,
    const HEIGHT: bool,
    const SLOPE: bool,
>(
    shuffle: S,
    fields: &Fields<'_>,
    [x, z]: [&F64s; 2],
    range: std::ops::Range<usize>,
    factors: Option<&[Factors; LANES]>,
) -> SummedLanes {
    let frame = fields.frame();
    let mut total = SummedLanes::default();
    // Every cascade's cells and tiles first, then the taps: the tile lookups of all
    // cascades are in flight together instead of each waiting for the previous cascade's
    // arithmetic.
    let mut prepared: [Option<Prepared<'_>>; MAX_CASCADES] = [None; MAX_CASCADES];
    for c in range.clone() {
        let grid = &frame.grids[c];
        let Some(tiles) = &grid.tiles else {
            unreachable!("lanes are used only when every cascade has spline tiles")
        };
        let (ix, fx) = cells(x, &grid.period);
        let (iz, fz) = cells(z, &grid.period);
        let (index, at) = tiles.cells_of(&ix, &iz);
        let first = tiles.tile(index[0] as usize, || fields.source(c), frame.simd);
        let mut found: [&TileData; LANES] = [first; LANES];
        for l in 1..LANES {
            found[l] = tiles.tile(index[l] as usize, || fields.source(c), frame.simd);
        }
        prepared[c] = Some(Prepared {
            found,
            at,
            fraction: [fx, fz],
            per_metre: grid.per_metre,
        });
    }
    for c in range {
        let Some(Prepared {
            found,
            at,
            fraction: [fx, fz],
            per_metre,
        }) = &prepared[c]
        else {
            unreachable!("prepared above")
        };
        // A first tap lies in the tile's first TILE rows and columns: the bound lets the
        // compiler drop the slices' checks.
        const LAST: u32 = ((spline::TILE - 1) * (STRIDE + 1)) as u32;
        let at: [usize; LANES] = each(|l| at[l].min(LAST) as usize);
        let (fx, fz) = (Lanes(*fx), Lanes(*fz));
        let zero = [Lanes::from(0.0); 4];
        let (dx, dz) = if JACOBIAN {
            (spline::weight_slopes(fx), spline::weight_slopes(fz))
        } else {
            (zero, zero)
        };
        let weights = [spline::weights(fx), spline::weights(fz), dx, dz];
        // The cascade's fields times its coast factor, rounded as the single query rounds
        // them (the product, then the sum).
        let factor: Option<F32s> = factors.map(|f| each(|l| f[l][c]));
        let scale = |v: F32s| match factor {
            Some(f) => shuffle.mul(v, f),
            None => v,
        };
        if DISPLACEMENT || JACOBIAN {
            let [value, gx, gz] = pairs::<S, JACOBIAN>(shuffle, found, 0, &at, &weights);
            for k in 0..2 {
                total.displacement[k] = shuffle.add(total.displacement[k], scale(value[k]));
            }
            if JACOBIAN {
                let g = [scale(gx[0]), scale(gz[0]), scale(gx[1]), scale(gz[1])];
                for (sum, &g) in total.jacobian.iter_mut().zip(&g) {
                    *sum = shuffle.add_product(*sum, [*per_metre; LANES], g);
                }
            }
        }
        if HEIGHT {
            let height = heights(shuffle, found, &at, [&weights[0], &weights[1]]);
            total.height = shuffle.add(total.height, scale(height));
        }
        if SLOPE {
            let [slope, _, _] = pairs::<S, false>(shuffle, found, spline::SLOPE, &at, &weights);
            for k in 0..2 {
                total.slope[k] = shuffle.add(total.slope[k], scale(slope[k]));
            }
        }
    }
    total
}

/// The foam coverage at eight undisplaced world points: [`Fields::foam_at`] lane by lane
/// (the same cell, the bilinear stencil's weights and sum, clamped to [0, 1], then the
/// coast's, point by point).
#[inline(always)]
// max then min, as `Fields::foam_at` clamps (`clamp` differs on NaN and −0).
#[allow(clippy::manual_clamp)]
pub(super) fn foam(fields: &Fields<'_>, [x, z]: &[F64s; 2]) -> F32s {
    let (values, n, length) = fields.foam_grid();
    let period = Period::new(length, n);
    let (ix, fx) = cells(x, &period);
    let (iz, fz) = cells(z, &period);
    let n = n as u32;
    let next = |i: u32| if i + 1 == n { 0 } else { i + 1 };
    let (ix1, iz1): ([u32; LANES], [u32; LANES]) = (each(|l| next(ix[l])), each(|l| next(iz[l])));
    let weight = [
        each(|l| (1.0 - fx[l]) * (1.0 - fz[l])),
        each(|l| fx[l] * (1.0 - fz[l])),
        each(|l| (1.0 - fx[l]) * fz[l]),
        each(|l| fx[l] * fz[l]),
    ];
    let value = |row: &[u32; LANES], column: &[u32; LANES]| -> F32s {
        each(|l| values[row[l] as usize * n as usize + column[l] as usize])
    };
    let corner = [
        value(&iz, &ix),
        value(&iz, &ix1),
        value(&iz1, &ix),
        value(&iz1, &ix1),
    ];
    let p: [F32s; 4] = std::array::from_fn(|c| each(|l| corner[c][l] * weight[c][l]));
    let foam = each(|l| {
        (((p[0][l] + p[1][l]) + p[2][l]) + p[3][l])
            .max(0.0)
            .min(1.0)
    });
    let frame = fields.frame();
    match &frame.coast {
        None => foam,
        Some(coast) => each(|l| coast.foam(frame.time, x[l], z[l], foam[l])),
    }
}

/// The surface at each of `points` (undisplaced), summed over cascades `range` (the foam
/// only if cascade 0 is among them), eight points at a time.
#[inline(always)]
pub(crate) fn sample<S: Shuffle>(
    shuffle: S,
    fields: &Fields<'_>,
    points: &[[f64; 2]],
    range: std::ops::Range<usize>,
    out: &mut [SurfaceSample],
) {
    for (out, points) in out.chunks_mut(LANES).zip(points.chunks(LANES)) {
        if points.len() < FEWEST {
            for (value, &[x, z]) in out.iter_mut().zip(points) {
                *value = inversion::sample(fields, x, z, range.clone());
            }
            continue;
        }
        let at = [
            each(|l| points.get(l).unwrap_or(&points[0])[0]),
            each(|l| points.get(l).unwrap_or(&points[0])[1]),
        ];
        let factors = coast_factors(fields, &at);
        let sums = evaluate::<S, true, false, true, true>(
            shuffle,
            fields,
            &at,
            range.clone(),
            factors.as_ref(),
        );
        let foam = if range.contains(&0) {
            foam(fields, &at)
        } else {
            [0.0; LANES]
        };
        for (l, value) in out.iter_mut().enumerate() {
            let foam = foam[l];
            let displacement = [sums.displacement[0][l], sums.displacement[1][l]];
            let slope = [sums.slope[0][l], sums.slope[1][l]];
            *value = surface(sums.height[l], displacement, slope, foam);
        }
    }
}
