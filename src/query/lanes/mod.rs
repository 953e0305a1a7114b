//! Batch queries on the spline eight points at a time, one point a lane: the cells, the
//! weights, the sums over the taps and the Newton updates of eight points are each one
//! vector operation (written as loops over `[_; 8]`, which the compiler turns into vector
//! instructions at each SIMD level), and only the tile lookup is done point by point.
//!
//! Every lane runs the scalar code's operations in the scalar code's order
//! ([`super::inversion`] and [`spline`]: the same wrap and cell, the same weight formulas,
//! a pair field's taps summed columns first and the taps added (0 + 2) + (1 + 3), the same
//! Newton step), so each point's result has the bits of its single query. How the lanes take
//! their points depends on what the query reads (see [`locate`]).

// Lanes are the same index into several arrays at once; an iterator over one of them hides
// that.
#![allow(clippy::needless_range_loop)]
use super::frame::Fields;
use super::inversion::{self, guessing, MIN_DETERMINANT};
use super::results::{normal_from_slope, Location, SurfaceSample};
use super::spline::{self, Lanes, TileData, STRIDE};
use crate::cascade::MAX_CASCADES;
use crate::math::periodic::{wrap, Period, FAR_PERIODS};

/// Points a vector holds.
pub(super) const LANES: usize = 8;
/// Fewest points a batch (or [`sample`]'s last group) puts in lanes: up to three points
/// are queried one at a time, eight lanes' work costing more than their single queries (on
/// one thread a batch of one point took 2.7×, of two 1.5× and of three 1.0–1.1× their
/// single queries, of four 0.8×; see docs/performance.md).
pub(super) const FEWEST: usize = 4;

type F32s = [f32; LANES];
type F64s = [f64; LANES];

/// `f(l)` for each lane `l` (a plain loop: `std::array::from_fn`'s adapter is sometimes
/// left out of line, and a closure out of line runs without the batch's SIMD level).
#[inline(always)]
fn each<T: Copy + Default>(mut f: impl FnMut(usize) -> T) -> [T; LANES] {
    let mut out = [T::default(); LANES];
    for (l, out) in out.iter_mut().enumerate() {
        *out = f(l);
    }
    out
}

/// The cell and the fraction across it of eight coordinates along one axis of a periodic
/// grid: [`cell_on`](crate::math::periodic::cell_on)'s wrap and split, lane by lane.
#[inline(always)]
fn cells(v: &F64s, period: &Period) -> ([u32; LANES], F32s) {
    let Period {
        length,
        inverse,
        cells,
        n,
    } = *period;
    let periods: F64s = each(|l| (v[l] * inverse).floor());
    let mut wrapped: F64s = each(|l| {
        let r = v[l] - periods[l] * length;
        let (low, high) = (r + length, r - length);
        if r < 0.0 {
            low
        } else if r >= length {
            high
        } else {
            r
        }
    });
    // Far from the origin `wrap` takes another path; rare, so lane by lane.
    if periods.iter().any(|p| p.abs() >= FAR_PERIODS) {
        for l in 0..LANES {
            if periods[l].abs() >= FAR_PERIODS {
                wrapped[l] = wrap(v[l], length, inverse);
            }
        }
    }
    let g: F64s = each(|l| wrapped[l] * cells);
    let floor: F64s = each(|l| g[l].floor());
    let fraction: F32s = each(|l| (g[l] - floor[l]) as f32);
    // 0 ≤ ⌊g⌋ ≤ n < 2³¹, a whole number: adding 1.5·2⁵² puts it in the low bits of the
    // f64 exactly (a cheaper conversion than `as`, which must saturate).
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    let n = n as u32;
    let cell = each(|l| {
        let cell = (floor[l] + SHIFT).to_bits() as u32;
        if cell >= n {
            cell - n
        } else {
            cell
        }
    });
    (cell, fraction)
}

/// How a batch's lanes turn rows of taps into vectors (pure data movement) and add
/// products (IEEE operations, each rounded once: a fused multiply-add is one operation), so
/// every implementation gives the same bits (the single queries' at the same level). Chosen
/// once for a whole batch (see `run_batch`), so that the lanes' code is compiled once for
/// each SIMD level rather than branching on it at every tap.
pub(crate) trait Shuffle: Copy {
    /// Eight rows of eight floats, one a lane, as eight vectors of eight lanes.
    fn transpose8(self, rows: [&[f32; 8]; LANES]) -> [F32s; 8];
    /// Eight rows of four floats, one a lane, as four vectors of eight lanes.
    fn transpose4(self, rows: [&[f32; 4]; LANES]) -> [F32s; 4];
    /// `sum + w·x` lane by lane, rounded once (a fused multiply-add, as `f32::mul_add`),
    /// except at a baseline level that adds unfused (see `Simd::Baseline`).
    fn add_product(self, sum: F32s, w: F32s, x: F32s) -> F32s;
    /// `w·x` lane by lane.
    fn mul(self, w: F32s, x: F32s) -> F32s;
    /// `a + b` lane by lane.
    fn add(self, a: F32s, b: F32s) -> F32s;
}

/// [`Shuffle`] written as plain array code (the baseline level), its products added fused
/// or not as the level says (see `Simd::Baseline`).
#[derive(Clone, Copy)]
pub(crate) struct Plain {
    pub(crate) fused: bool,
}

impl Shuffle for Plain {
    #[inline(always)]
    fn transpose8(self, rows: [&[f32; 8]; LANES]) -> [F32s; 8] {
        std::array::from_fn(|j| each(|l| rows[l][j]))
    }

    #[inline(always)]
    fn transpose4(self, rows: [&[f32; 4]; LANES]) -> [F32s; 4] {
        std::array::from_fn(|j| each(|l| rows[l][j]))
    }

    #[inline(always)]
    fn add_product(self, sum: F32s, w: F32s, x: F32s) -> F32s {
        crate::math::simd::baseline_lanes(self.fused, w, x, sum)
    }

    #[inline(always)]
    fn mul(self, w: F32s, x: F32s) -> F32s {
        each(|l| w[l] * x[l])
    }

    #[inline(always)]
    fn add(self, a: F32s, b: F32s) -> F32s {
        each(|l| a[l] + b[l])
    }
}

/// [`Shuffle`] with AVX2's unpack and shuffle network (also used on AVX-512 machines: the
/// lanes are eight `f32` wide).
#[cfg(target_arch = "x86_64")]
impl Shuffle for pulp::x86::V3 {
    #[inline(always)]
    fn transpose8(self, rows: [&[f32; 8]; LANES]) -> [F32s; 8] {
        transpose8_v3(self, rows)
    }

    #[inline(always)]
    fn transpose4(self, rows: [&[f32; 4]; LANES]) -> [F32s; 4] {
        transpose4_v3(self, rows)
    }

    #[inline(always)]
    fn add_product(self, sum: F32s, w: F32s, x: F32s) -> F32s {
        use pulp::{cast, f32x8, Simd as _};
        cast(self.mul_add_f32s(
            cast::<_, f32x8>(w),
            cast::<_, f32x8>(x),
            cast::<_, f32x8>(sum),
        ))
    }

    #[inline(always)]
    fn mul(self, w: F32s, x: F32s) -> F32s {
        use pulp::{cast, f32x8, Simd as _};
        cast(self.mul_f32s(cast::<_, f32x8>(w), cast::<_, f32x8>(x)))
    }

    #[inline(always)]
    fn add(self, a: F32s, b: F32s) -> F32s {
        use pulp::{cast, f32x8, Simd as _};
        cast(self.add_f32s(cast::<_, f32x8>(a), cast::<_, f32x8>(b)))
    }
}

/// The 8 × 8 transpose: unpack and shuffle within the 128-bit halves, then a permute
/// across them.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn transpose8_v3(v3: pulp::x86::V3, rows: [&[f32; 8]; LANES]) -> [F32s; 8] {
    use std::arch::x86_64::__m256;
    let avx = v3.avx;
    let r: [__m256; 8] = [
        pulp::cast(*rows[0]),
        pulp::cast(*rows[1]),
        pulp::cast(*rows[2]),
        pulp::cast(*rows[3]),
        pulp::cast(*rows[4]),
        pulp::cast(*rows[5]),
        pulp::cast(*rows[6]),
        pulp::cast(*rows[7]),
    ];
    let t = [
        avx._mm256_unpacklo_ps(r[0], r[1]),
        avx._mm256_unpackhi_ps(r[0], r[1]),
        avx._mm256_unpacklo_ps(r[2], r[3]),
        avx._mm256_unpackhi_ps(r[2], r[3]),
        avx._mm256_unpacklo_ps(r[4], r[5]),
        avx._mm256_unpackhi_ps(r[4], r[5]),
        avx._mm256_unpacklo_ps(r[6], r[7]),
        avx._mm256_unpackhi_ps(r[6], r[7]),
    ];
    let s = [
        avx._mm256_shuffle_ps::<0x44>(t[0], t[2]),
        avx._mm256_shuffle_ps::<0xEE>(t[0], t[2]),
        avx._mm256_shuffle_ps::<0x44>(t[1], t[3]),
        avx._mm256_shuffle_ps::<0xEE>(t[1], t[3]),
        avx._mm256_shuffle_ps::<0x44>(t[4], t[6]),
        avx._mm256_shuffle_ps::<0xEE>(t[4], t[6]),
        avx._mm256_shuffle_ps::<0x44>(t[5], t[7]),
        avx._mm256_shuffle_ps::<0xEE>(t[5], t[7]),
    ];
    [
        pulp::cast(avx._mm256_permute2f128_ps::<0x20>(s[0], s[4])),
        pulp::cast(avx._mm256_permute2f128_ps::<0x20>(s[1], s[5])),
        pulp::cast(avx._mm256_permute2f128_ps::<0x20>(s[2], s[6])),
        pulp::cast(avx._mm256_permute2f128_ps::<0x20>(s[3], s[7])),
        pulp::cast(avx._mm256_permute2f128_ps::<0x31>(s[0], s[4])),
        pulp::cast(avx._mm256_permute2f128_ps::<0x31>(s[1], s[5])),
        pulp::cast(avx._mm256_permute2f128_ps::<0x31>(s[2], s[6])),
        pulp::cast(avx._mm256_permute2f128_ps::<0x31>(s[3], s[7])),
    ]
}

/// Lanes l and l + 4 share a register (one a 128-bit half), so two 4 × 4 transposes run
/// side by side within the halves and no instruction crosses them.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn transpose4_v3(v3: pulp::x86::V3, rows: [&[f32; 4]; LANES]) -> [F32s; 4] {
    use std::arch::x86_64::{__m128, __m256};
    let avx = v3.avx;
    let half: [__m128; LANES] = [
        pulp::cast(*rows[0]),
        pulp::cast(*rows[1]),
        pulp::cast(*rows[2]),
        pulp::cast(*rows[3]),
        pulp::cast(*rows[4]),
        pulp::cast(*rows[5]),
        pulp::cast(*rows[6]),
        pulp::cast(*rows[7]),
    ];
    let r: [__m256; 4] = [
        avx._mm256_set_m128(half[4], half[0]),
        avx._mm256_set_m128(half[5], half[1]),
        avx._mm256_set_m128(half[6], half[2]),
        avx._mm256_set_m128(half[7], half[3]),
    ];
    let t = [
        avx._mm256_unpacklo_ps(r[0], r[1]),
        avx._mm256_unpackhi_ps(r[0], r[1]),
        avx._mm256_unpacklo_ps(r[2], r[3]),
        avx._mm256_unpackhi_ps(r[2], r[3]),
    ];
    [
        pulp::cast(avx._mm256_shuffle_ps::<0x44>(t[0], t[2])),
        pulp::cast(avx._mm256_shuffle_ps::<0xEE>(t[0], t[2])),
        pulp::cast(avx._mm256_shuffle_ps::<0x44>(t[1], t[3])),
        pulp::cast(avx._mm256_shuffle_ps::<0xEE>(t[1], t[3])),
    ]
}

/// The cells `[ix, iz]` of up to eight world points `[x, z]` on a periodic grid, one a
/// lane (the missing lanes take the first point's).
#[inline(always)]
pub(super) fn cells_at(points: &[[f64; 2]], period: &Period) -> [[u32; LANES]; 2] {
    let x = each(|l| points.get(l).unwrap_or(&points[0])[0]);
    let z = each(|l| points.get(l).unwrap_or(&points[0])[1]);
    [cells(&x, period).0, cells(&z, period).0]
}

/// What eight lanes sum over the cascades at their points (zero where not asked).
#[derive(Clone, Copy, Default)]
pub(super) struct SummedLanes {
    /// `[D_x, D_z]` in metres.
    pub(super) displacement: [F32s; 2],
    /// `[∂D_x/∂x, ∂D_x/∂z, ∂D_z/∂x, ∂D_z/∂z]`.
    jacobian: [F32s; 4],
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
/// summed in order as [`super::inversion`]'s `evaluate` sums them: the displacement with
/// `DISPLACEMENT`, its Jacobian with `JACOBIAN`, the height with `HEIGHT`, the slope with
/// `SLOPE`. Every cascade in `range` must have spline tiles.
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
    [x, z]: &[F64s; 2],
    range: std::ops::Range<usize>,
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
        if DISPLACEMENT || JACOBIAN {
            let [value, gx, gz] = pairs::<S, JACOBIAN>(shuffle, found, 0, &at, &weights);
            for k in 0..2 {
                total.displacement[k] = shuffle.add(total.displacement[k], value[k]);
            }
            if JACOBIAN {
                let g = [gx[0], gz[0], gx[1], gz[1]];
                for (sum, &g) in total.jacobian.iter_mut().zip(&g) {
                    *sum = shuffle.add_product(*sum, [*per_metre; LANES], g);
                }
            }
        }
        if HEIGHT {
            let height = heights(shuffle, found, &at, [&weights[0], &weights[1]]);
            total.height = shuffle.add(total.height, height);
        }
        if SLOPE {
            let [slope, _, _] = pairs::<S, false>(shuffle, found, spline::SLOPE, &at, &weights);
            for k in 0..2 {
                total.slope[k] = shuffle.add(total.slope[k], slope[k]);
            }
        }
    }
    total
}

/// The foam coverage at eight undisplaced world points: [`Fields::foam_at`] lane by lane
/// (the same cell, the bilinear stencil's weights and sum, clamped to [0, 1]).
#[inline(always)]
// max then min, as `Fields::foam_at` clamps (`clamp` differs on NaN and −0).
#[allow(clippy::manual_clamp)]
fn foam(fields: &Fields<'_>, [x, z]: &[F64s; 2]) -> F32s {
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
    each(|l| {
        (((p[0][l] + p[1][l]) + p[2][l]) + p[3][l])
            .max(0.0)
            .min(1.0)
    })
}

/// `newton_step` lane by lane: the Newton step δ solving (I + ∇D) δ = `residual` for the
/// Jacobian `j`, or `residual` itself where the surface (nearly) folds.
#[inline(always)]
fn newton_steps(residual: &[F64s; 2], j: &[F32s; 4]) -> [F64s; 2] {
    let a: F64s = each(|l| 1.0 + f64::from(j[0][l]));
    let b: F64s = each(|l| f64::from(j[1][l]));
    let c: F64s = each(|l| f64::from(j[2][l]));
    let d: F64s = each(|l| 1.0 + f64::from(j[3][l]));
    let determinant: F64s = each(|l| a[l] * d[l] - b[l] * c[l]);
    let newton: [bool; LANES] = each(|l| determinant[l] > MIN_DETERMINANT);
    [
        each(|l| {
            let s = (d[l] * residual[0][l] - b[l] * residual[1][l]) / determinant[l];
            if newton[l] {
                s
            } else {
                residual[0][l]
            }
        }),
        each(|l| {
            let s = (a[l] * residual[1][l] - c[l] * residual[0][l]) / determinant[l];
            if newton[l] {
                s
            } else {
                residual[1][l]
            }
        }),
    ]
}

/// Up to eight points about to be searched for, with their first guesses.
struct Guesses {
    /// The batch index of the first, how many there are, and how many were given a lane.
    first: usize,
    count: usize,
    taken: usize,
    target: [[f64; 2]; LANES],
    /// Each one's first guess `[x, z]` (`first_guess`, lane by lane).
    start: [F64s; 2],
}

impl Guesses {
    const EMPTY: Guesses = Guesses {
        first: 0,
        count: 0,
        taken: 0,
        target: [[0.0; 2]; LANES],
        start: [[0.0; LANES]; 2],
    };

    /// The first guesses of `points` (at most [`LANES`], the first being the batch's point
    /// `first`): one Newton step on the larger cascades, less the smaller cascades'
    /// displacement there, with the single query's operations.
    #[inline(always)]
    fn of<S: Shuffle>(
        shuffle: S,
        fields: &Fields<'_>,
        points: &[[f64; 2]],
        first: usize,
    ) -> Guesses {
        let target: [[f64; 2]; LANES] =
            std::array::from_fn(|l| *points.get(l).unwrap_or(&points[0]));
        let at = [each(|l| target[l][0]), each(|l| target[l][1])];
        let count = fields.frame().grids.len();
        let cascades = guessing(count);
        let rest = cascades.end..count;
        let summed = evaluate::<S, true, true, false, false>(shuffle, fields, &at, cascades);
        let d = &summed.displacement;
        let residual = [each(|l| -f64::from(d[0][l])), each(|l| -f64::from(d[1][l]))];
        let step = newton_steps(&residual, &summed.jacobian);
        let stepped = [
            each(|l| at[0][l] + step[0][l]),
            each(|l| at[1][l] + step[1][l]),
        ];
        let short = evaluate::<S, true, false, false, false>(shuffle, fields, &stepped, rest);
        let d = &short.displacement;
        Guesses {
            first,
            count: points.len(),
            taken: 0,
            target,
            start: [
                each(|l| stepped[0][l] - f64::from(d[0][l])),
                each(|l| stepped[1][l] - f64::from(d[1][l])),
            ],
        }
    }
}

/// The Newton searches of up to [`LANES`] points, one a lane (see [`super::inversion`]'s
/// `Search`, whose update each lane runs), and the fields at each one's best iterate.
struct Searches {
    /// The point each lane searches for (an index into the batch), or `None`.
    point: [Option<usize>; LANES],
    /// Evaluations each lane's search has made.
    iteration: [usize; LANES],
    target: [F64s; 2],
    /// The iterate to evaluate next.
    next: [F64s; 2],
    base: [F64s; 2],
    step: [F64s; 2],
    fraction: F64s,
    best: [F64s; 2],
    miss: F32s,
    iterations: [usize; LANES],
    converged: [bool; LANES],
    /// The summed displacement at the best iterate.
    displacement: [F32s; 2],
    /// The summed height at the best iterate, where `height_read`.
    height: F32s,
    /// Whether the evaluation of the best iterate read the height.
    height_read: [bool; LANES],
}

/// What a search found: where the water at a point comes from, and the summed fields there
/// (the height and slope once read).
#[derive(Clone, Copy)]
pub(super) struct Found {
    pub(super) location: Location,
    pub(super) displacement: [f32; 2],
    pub(super) height: f32,
    /// Whether `height` was read (with the search or after it).
    pub(super) height_read: bool,
    pub(super) slope: [f32; 2],
    /// Foam coverage in [0, 1] (with the slope).
    pub(super) foam: f32,
}

impl Found {
    const EMPTY: Found = Found {
        location: Location {
            undisplaced: [0.0; 2],
            miss: f32::INFINITY,
            iterations: 0,
            converged: false,
        },
        displacement: [0.0; 2],
        height: 0.0,
        height_read: false,
        slope: [0.0; 2],
        foam: 0.0,
    };
}

/// A batch's result for one point, from what its search found.
pub(super) trait FromFound: Sized {
    fn from_found(found: Found) -> Self;
}

impl FromFound for f32 {
    #[inline(always)]
    fn from_found(found: Found) -> f32 {
        found.height
    }
}

impl FromFound for SurfaceSample {
    #[inline(always)]
    fn from_found(found: Found) -> SurfaceSample {
        surface(found.height, found.displacement, found.slope, found.foam)
    }
}

/// The [`SurfaceSample`] of summed fields and foam `foam` (as the single queries build it).
#[inline(always)]
fn surface(height: f32, displacement: [f32; 2], slope: [f32; 2], foam: f32) -> SurfaceSample {
    SurfaceSample {
        height,
        displacement,
        slope,
        normal: normal_from_slope(glam::Vec2::from_array(slope)).to_array(),
        foam,
    }
}

impl Searches {
    fn new() -> Searches {
        let zero = [[0.0; LANES]; 2];
        Searches {
            point: [None; LANES],
            iteration: [0; LANES],
            target: zero,
            next: zero,
            base: zero,
            step: zero,
            fraction: [1.0; LANES],
            best: zero,
            miss: [f32::INFINITY; LANES],
            iterations: [0; LANES],
            converged: [false; LANES],
            displacement: [[0.0; LANES]; 2],
            height: [0.0; LANES],
            height_read: [false; LANES],
        }
    }

    /// The searches of the points `guesses` holds, one a lane from lane 0 (`Search::new`
    /// of each).
    #[inline(always)]
    fn begin(guesses: &Guesses) -> Searches {
        let mut searches = Searches::new();
        searches.point = each(|l| (l < guesses.count).then_some(guesses.first + l));
        for k in 0..2 {
            searches.target[k] = each(|l| guesses.target[l][k]);
            searches.next[k] = guesses.start[k];
            searches.base[k] = guesses.start[k];
            searches.best[k] = guesses.start[k];
        }
        searches
    }

    /// Starts lane `l` on the point `guesses` holds at `p` (`Search::new`).
    #[inline(always)]
    fn start(&mut self, l: usize, guesses: &Guesses, p: usize) {
        self.point[l] = Some(guesses.first + p);
        self.iteration[l] = 0;
        for k in 0..2 {
            self.target[k][l] = guesses.target[p][k];
            self.next[k][l] = guesses.start[k][p];
            self.base[k][l] = guesses.start[k][p];
            self.step[k][l] = 0.0;
            self.best[k][l] = guesses.start[k][p];
        }
        self.fraction[l] = 1.0;
        self.miss[l] = f32::INFINITY;
        self.iterations[l] = 0;
        self.converged[l] = false;
        self.height_read[l] = false;
    }

    /// Moves lane `l`'s search to lane `to` of `other` (whose lane `to` is idle).
    #[inline(always)]
    fn hand_over(&mut self, l: usize, other: &mut Searches, to: usize) {
        other.point[to] = self.point[l].take();
        other.iteration[to] = self.iteration[l];
        for k in 0..2 {
            other.target[k][to] = self.target[k][l];
            other.next[k][to] = self.next[k][l];
            other.base[k][to] = self.base[k][l];
            other.step[k][to] = self.step[k][l];
            other.best[k][to] = self.best[k][l];
            other.displacement[k][to] = self.displacement[k][l];
        }
        other.fraction[to] = self.fraction[l];
        other.miss[to] = self.miss[l];
        other.iterations[to] = self.iterations[l];
        other.converged[to] = self.converged[l];
        other.height[to] = self.height[l];
        other.height_read[to] = self.height_read[l];
    }

    /// Takes the sums at each lane's iterate, and sets the iterate after it; returns which
    /// lanes' searches ended. With `track` (a query of heights alone) each search keeps the
    /// height at its best iterate, which the sums hold if `read`.
    #[inline(always)]
    fn update(
        &mut self,
        summed: &SummedLanes,
        track: bool,
        read: bool,
        tolerance: f32,
        max: usize,
    ) -> [bool; LANES] {
        let (d, j) = (&summed.displacement, &summed.jacobian);
        let mut residual = [[0.0f64; LANES]; 2];
        for k in 0..2 {
            residual[k] = each(|l| self.target[k][l] - (self.next[k][l] + f64::from(d[k][l])));
        }
        // A correctly rounded square root, as the single query's.
        let miss: F32s = each(|l| {
            let [rx, rz] = [residual[0][l], residual[1][l]];
            (rx * rx + rz * rz).sqrt() as f32
        });
        let step = newton_steps(&residual, j);
        let better: [bool; LANES] = each(|l| miss[l] < self.miss[l]);
        let converged: [bool; LANES] = each(|l| miss[l] < tolerance);
        for k in 0..2 {
            self.best[k] = each(|l| {
                if better[l] {
                    self.next[k][l]
                } else {
                    self.best[k][l]
                }
            });
            self.displacement[k] = each(|l| {
                if better[l] {
                    d[k][l]
                } else {
                    self.displacement[k][l]
                }
            });
            self.step[k] = each(|l| {
                if better[l] {
                    step[k][l]
                } else {
                    self.step[k][l]
                }
            });
            self.base[k] = each(|l| {
                if better[l] {
                    self.next[k][l]
                } else {
                    self.base[k][l]
                }
            });
        }
        if track {
            if read {
                self.height = each(|l| {
                    if better[l] {
                        summed.height[l]
                    } else {
                        self.height[l]
                    }
                });
            }
            self.height_read = each(|l| if better[l] { read } else { self.height_read[l] });
        }
        self.miss = each(|l| if better[l] { miss[l] } else { self.miss[l] });
        self.fraction = each(|l| {
            if better[l] {
                1.0
            } else {
                self.fraction[l] * 0.5
            }
        });
        for k in 0..2 {
            self.next[k] = each(|l| self.base[k][l] + self.fraction[l] * self.step[k][l]);
        }
        let mut ended = [false; LANES];
        for l in 0..LANES {
            if better[l] {
                self.iterations[l] = self.iteration[l];
                self.converged[l] = converged[l];
            }
            ended[l] = self.point[l].is_some()
                && ((better[l] && converged[l]) || self.iteration[l] == max);
            self.iteration[l] += 1;
        }
        ended
    }

    /// What lane `l`'s search found.
    #[inline(always)]
    fn found(&self, l: usize) -> Found {
        Found {
            location: Location {
                undisplaced: [self.best[0][l], self.best[1][l]],
                miss: self.miss[l],
                iterations: self.iterations[l],
                converged: self.converged[l],
            },
            displacement: [self.displacement[0][l], self.displacement[1][l]],
            height: self.height[l],
            height_read: self.height_read[l],
            slope: [0.0; 2],
            foam: 0.0,
        }
    }
}

/// Each of `points` located and its result written into `out`, eight points at a time.
/// A query of heights alone (`HEIGHT` without `SLOPE`) reads them with its search (see
/// [`heights_with_search`]); otherwise lanes take the next point as their searches end (see
/// [`refilling`]) and, with `SLOPE`, eight found points at a time, the height (with
/// `HEIGHT`), the slope and the foam are read where they were found. Each result has the
/// bits of its single query.
#[inline(always)]
pub(super) fn locate<S: Shuffle, T: FromFound, const HEIGHT: bool, const SLOPE: bool>(
    shuffle: S,
    fields: &Fields<'_>,
    points: &[[f64; 2]],
    out: &mut [T],
) {
    let mut ended = Ended::EMPTY;
    if HEIGHT && !SLOPE {
        heights_with_search::<S, T, HEIGHT, SLOPE>(shuffle, fields, points, &mut ended, out);
    } else {
        refilling::<S, T, HEIGHT, SLOPE>(shuffle, fields, points, &mut ended, out);
    }
    let count = ended.count;
    finish::<S, T, HEIGHT, SLOPE>(
        shuffle,
        fields,
        &mut ended.found[..count],
        &ended.at[..count],
        out,
    );
}

/// The searches for `points`, eight at a time from their first guesses, each lane taking
/// the batch's next point when its search ends (so that a group does not wait for its
/// slowest point); no heights are read.
#[inline(always)]
fn refilling<S: Shuffle, T: FromFound, const HEIGHT: bool, const SLOPE: bool>(
    shuffle: S,
    fields: &Fields<'_>,
    points: &[[f64; 2]],
    ended: &mut Ended,
    out: &mut [T],
) {
    let mut searches = Searches::new();
    // The points not yet started, eight at a time with their first guesses.
    let mut chunks = points.chunks(LANES).enumerate();
    let mut next = Guesses::EMPTY;
    loop {
        for l in 0..LANES {
            if searches.point[l].is_none() {
                if next.taken == next.count {
                    if let Some((c, chunk)) = chunks.next() {
                        next = Guesses::of(shuffle, fields, chunk, c * LANES);
                    }
                }
                if next.taken < next.count {
                    searches.start(l, &next, next.taken);
                    next.taken += 1;
                }
            }
        }
        if searches.point.iter().all(Option::is_none) {
            break;
        }
        // (Calls, not a closure: a closure out of line would run without the SIMD level.)
        advance::<S, T, HEIGHT, SLOPE>(shuffle, fields, &mut searches, false, ended, out);
    }
}

/// The searches for `points` of a query of heights alone, eight points at a time: their
/// first guesses, an evaluation of the displacement and its Jacobian at each (after which
/// a search almost never ends, so the heights are not read there) and a second that reads
/// the heights too. The searches that go on (about one in twelve on the default sea) move
/// to a second set of lanes, evaluated with the heights whenever all its lanes are busy and
/// at the end. Each search keeps its best iterate's height; [`finish`] reads it for one
/// whose best iterate was evaluated without it.
#[inline(always)]
fn heights_with_search<S: Shuffle, T: FromFound, const HEIGHT: bool, const SLOPE: bool>(
    shuffle: S,
    fields: &Fields<'_>,
    points: &[[f64; 2]],
    ended: &mut Ended,
    out: &mut [T],
) {
    let mut stragglers = Searches::new();
    for (c, chunk) in points.chunks(LANES).enumerate() {
        let mut searches = Searches::begin(&Guesses::of(shuffle, fields, chunk, c * LANES));
        advance::<S, T, HEIGHT, SLOPE>(shuffle, fields, &mut searches, false, ended, out);
        advance::<S, T, HEIGHT, SLOPE>(shuffle, fields, &mut searches, true, ended, out);
        for l in 0..LANES {
            if searches.point[l].is_none() {
                continue;
            }
            let to = loop {
                if let Some(to) = stragglers.point.iter().position(Option::is_none) {
                    break to;
                }
                advance::<S, T, HEIGHT, SLOPE>(shuffle, fields, &mut stragglers, true, ended, out);
            };
            searches.hand_over(l, &mut stragglers, to);
        }
    }
    while stragglers.point.iter().any(Option::is_some) {
        advance::<S, T, HEIGHT, SLOPE>(shuffle, fields, &mut stragglers, true, ended, out);
    }
}

/// One evaluation of the busy lanes of `searches` (the height too if `read`), their
/// searches' updates, and the ended ones' results handed to `ended`.
#[inline(always)]
fn advance<S: Shuffle, T: FromFound, const HEIGHT: bool, const SLOPE: bool>(
    shuffle: S,
    fields: &Fields<'_>,
    searches: &mut Searches,
    read: bool,
    ended: &mut Ended,
    out: &mut [T],
) {
    let Some(busy) = searches.point.iter().position(Option::is_some) else {
        return;
    };
    // An idle lane evaluates a busy lane's iterate (any point the tiles cover would do).
    for l in 0..LANES {
        if searches.point[l].is_none() {
            for k in 0..2 {
                searches.next[k][l] = searches.next[k][busy];
            }
        }
    }
    let frame = fields.frame();
    let cascades = 0..frame.grids.len();
    let summed = if read {
        evaluate::<S, true, true, true, false>(shuffle, fields, &searches.next, cascades)
    } else {
        evaluate::<S, true, true, false, false>(shuffle, fields, &searches.next, cascades)
    };
    let query = &frame.query;
    let done = searches.update(
        &summed,
        HEIGHT && !SLOPE,
        read,
        query.tolerance,
        query.max_iterations,
    );
    for l in 0..LANES {
        if done[l] {
            if let Some(index) = searches.point[l].take() {
                ended.push::<S, T, HEIGHT, SLOPE>(shuffle, fields, searches.found(l), index, out);
            }
        }
    }
}

/// Searches ended whose results are not yet written: what each found, and its point's
/// index in the batch.
struct Ended {
    found: [Found; LANES],
    at: [usize; LANES],
    count: usize,
}

impl Ended {
    const EMPTY: Ended = Ended {
        found: [Found::EMPTY; LANES],
        at: [0; LANES],
        count: 0,
    };

    /// Adds what the search for point `index` found, writing the results held so far first
    /// (see [`finish`]) if there are [`LANES`] of them.
    #[inline(always)]
    fn push<S: Shuffle, T: FromFound, const HEIGHT: bool, const SLOPE: bool>(
        &mut self,
        shuffle: S,
        fields: &Fields<'_>,
        found: Found,
        index: usize,
        out: &mut [T],
    ) {
        if self.count == LANES {
            finish::<S, T, HEIGHT, SLOPE>(shuffle, fields, &mut self.found, &self.at, out);
            self.count = 0;
        }
        self.found[self.count] = found;
        self.at[self.count] = index;
        self.count += 1;
    }
}

/// Reads the height (with `HEIGHT`), slope and foam at the points `found` (at most
/// [`LANES`]) when the query asks for the slope (`SLOPE`), or the height alone if a search
/// did not read it at its best iterate, and writes each result to `out[found_at[i]]`.
#[inline(always)]
fn finish<S: Shuffle, T: FromFound, const HEIGHT: bool, const SLOPE: bool>(
    shuffle: S,
    fields: &Fields<'_>,
    found: &mut [Found],
    found_at: &[usize],
    out: &mut [T],
) {
    if found.is_empty() {
        return;
    }
    if SLOPE || (HEIGHT && found.iter().any(|f| !f.height_read)) {
        let at = [
            each(|l| found.get(l).unwrap_or(&found[0]).location.undisplaced[0]),
            each(|l| found.get(l).unwrap_or(&found[0]).location.undisplaced[1]),
        ];
        let cascades = 0..fields.frame().grids.len();
        let sums = evaluate::<S, false, false, HEIGHT, SLOPE>(shuffle, fields, &at, cascades);
        // The foam comes with the slope (a surface sample).
        let foam = if SLOPE {
            foam(fields, &at)
        } else {
            [0.0; LANES]
        };
        for (l, found) in found.iter_mut().enumerate() {
            if HEIGHT {
                found.height = sums.height[l];
            }
            if SLOPE {
                found.slope = [sums.slope[0][l], sums.slope[1][l]];
                found.foam = foam[l];
            }
        }
    }
    for (found, &index) in found.iter().zip(found_at) {
        out[index] = T::from_found(*found);
    }
}

/// The surface at each of `points` (undisplaced), summed over cascades `range` (the foam
/// only if cascade 0 is among them), eight points at a time.
#[inline(always)]
pub(super) fn sample<S: Shuffle>(
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
        let sums = evaluate::<S, true, false, true, true>(shuffle, fields, &at, range.clone());
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
