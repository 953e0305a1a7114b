//! Pass-1 kernels: the evolution h̃(k, t) = p cos φ + q sin φ of each table entry and its
//! four packed spectral values, a row pair (k_x and −k_x) at a time, written so that the
//! element loops vectorise.

use num_complex::Complex32;

use super::tables::EvolutionRow;

/// 1.5·2^52: adding and subtracting it rounds an f64 of magnitude below 2^51 to an integer
/// (ties to even) with plain arithmetic, which vectorises (`f64::round` is a libm call on
/// baseline x86-64).
const ROUND_F64: f64 = 6_755_399_441_055_744.0;
/// 1.5·2^23, the same for f32 below 2^22; the low mantissa bits of `x + ROUND_F32` are then
/// the rounded integer in two's complement.
const ROUND_F32: f32 = 12_582_912.0;

/// `turns` minus the nearest integer, in [−½, ½] for |turns| < 2^51 (larger values give an
/// integer, which [`sin_cos_turns`] also handles).
#[inline(always)]
pub(super) fn fract_turns(turns: f64) -> f32 {
    (turns - ((turns + ROUND_F64) - ROUND_F64)) as f32
}

/// sin and cos of 2π·`turns` for `turns` in [−½, ½] (any |turns| < 2^20 works), to about
/// 1e-7: reduced to a quarter turn and a short Taylor polynomial on [−π/4, π/4] (truncation
/// error below 2e-9 for the sine and 3e-8 for the cosine). Branch-free, so that loops over it vectorise.
#[inline(always)]
pub(crate) fn sin_cos_turns(turns: f32) -> (f32, f32) {
    let shifted = turns * 4.0 + ROUND_F32;
    let quadrant = shifted - ROUND_F32;
    let q = shifted.to_bits();
    let a = (turns - quadrant * 0.25) * std::f32::consts::TAU;
    let a2 = a * a;
    let sin = a
        * (1.0
            + a2 * (-1.0 / 6.0
                + a2 * (1.0 / 120.0 + a2 * (-1.0 / 5040.0 + a2 * (1.0 / 362_880.0)))));
    let cos = 1.0 + a2 * (-0.5 + a2 * (1.0 / 24.0 + a2 * (-1.0 / 720.0 + a2 * (1.0 / 40_320.0))));
    // Quadrant q: (sin, cos) → (s, c), (c, −s), (−s, −c), (−c, s).
    let (x, y) = if q & 1 == 0 { (sin, cos) } else { (cos, sin) };
    let sin_sign = (q & 2) << 30;
    let cos_sign = (q.wrapping_add(1) & 2) << 30;
    (
        f32::from_bits(x.to_bits() ^ sin_sign),
        f32::from_bits(y.to_bits() ^ cos_sign),
    )
}

/// The four packed spectral values at k = (`kx`, `kz`) and at −k, from an evolution entry's
/// p and q and its phase in `turns` (reduced, see [`fract_turns`]).
///
/// Transform p holds A + iB for the field pair (A, B) = (η, D_x), (D_z, η_x), (η_z, D_xx),
/// (D_zz, D_xz). With A = α h̃, B = β h̃ and Hermitian fields, the value at k is (α + iβ) h̃
/// and at −k it is (conj α + i conj β) conj h̃. With u = k/|k|, the factors of h̃ at k are
/// 1 − u_x, −k_x + i u_z, i(k_z − k_x u_x) and −u_z(k_z + i k_x), and the factors of conj h̃
/// at −k are 1 + u_x, k_x − i u_z, −i(k_z + k_x u_x) and −u_z(k_z + i k_x); the products of
/// h̃ they share are computed once.
#[inline(always)]
pub(super) fn packed_pair(
    turns: f32,
    p: Complex32,
    q: Complex32,
    kx: f32,
    kz: f32,
    inv_k: f32,
) -> ([Complex32; 4], [Complex32; 4]) {
    let (sin, cos) = sin_cos_turns(turns);
    let (hr, hi) = (p.re * cos + q.re * sin, p.im * cos + q.im * sin);
    let (ux, uz) = (kx * inv_k, kz * inv_k);
    // Transform 0: h̃(1 − u_x) at k, conj h̃ (1 + u_x) at −k.
    let (a, b) = (1.0 - ux, 1.0 + ux);
    let hib = hi * b;
    // Transform 1: h̃(−k_x + i u_z) at k, conj h̃ (k_x − i u_z) at −k.
    let (kx_hr, uz_hi, kx_hi, uz_hr) = (kx * hr, uz * hi, kx * hi, uz * hr);
    // Transform 2: i c h̃ at k, −i d conj h̃ at −k.
    let kx_ux = kx * ux;
    let (c, d) = (kz - kx_ux, kz + kx_ux);
    // Transform 3: (e + i f) h̃ at k and (e + i f) conj h̃ at −k.
    let (e, f) = (-(kz * uz), -(kx * uz));
    let (hr_e, hi_f, hr_f, hi_e) = (hr * e, hi * f, hr * f, hi * e);
    let plus = [
        Complex32::new(hr * a, hi * a),
        Complex32::new(-kx_hr - uz_hi, uz_hr - kx_hi),
        Complex32::new(-(c * hi), c * hr),
        Complex32::new(hr_e - hi_f, hr_f + hi_e),
    ];
    let minus = [
        Complex32::new(hr * b, -hib),
        Complex32::new(kx_hr - uz_hi, -uz_hr - kx_hi),
        Complex32::new(-(d * hi), -(d * hr)),
        Complex32::new(hr_e + hi_f, hr_f - hi_e),
    ];
    (plus, minus)
}

/// Columns evolved by one [`evolve_block`] call.
const EVOLVE_BLOCK: usize = 64;

/// The column ranges of [`evolve_row_pair`]'s blocks over columns 1..N, in order: blocks of
/// [`EVOLVE_BLOCK`] columns (fewer only when N is below it). Every block is full: the last
/// one starts early and recomputes a few columns, writing the same values, so that the
/// vector loops have no scalar remainder; when N ≤ EVOLVE_BLOCK the one block starts at
/// column 0 (which [`evolve_row_pair`] also computes on its own) for the same reason (at 64²
/// the 63 columns 1..64 left 15 to the narrow remainder loops). At most 64 blocks for
/// N ≤ 4097, so a row's blocks fit the bits of a `u64` (see [`zero_blocks`]).
pub(super) fn column_blocks(n: usize) -> impl Iterator<Item = std::ops::Range<usize>> {
    let len = EVOLVE_BLOCK.min(n);
    (1..n).step_by(EVOLVE_BLOCK).map(move |next| {
        let start = next.min(n - len);
        start..start + len
    })
}

/// Bit b set where block b of [`column_blocks`] has p = q = 0 in every column of table row
/// `table`: that block's spectral values are zero at every t, so [`evolve_row_pair`] writes
/// zeros there instead of evolving them. A cascade whose band stops below the Nyquist wave
/// number (every cascade of an ocean but the smallest) has whole blocks of them in every row.
pub(super) fn zero_blocks(table: EvolutionRow<'_>) -> u64 {
    let n = table.p_re.len();
    column_blocks(n).enumerate().fold(0, |bits, (b, range)| {
        let zero = [table.p_re, table.p_im, table.q_re, table.q_im]
            .iter()
            .all(|values| values[range.clone()].iter().all(|&v| v == 0.0));
        bits | (u64::from(zero) << b)
    })
}

/// Largest N whose evolution writes a block's own values straight into the four upper rows
/// (see [`evolve_block`]); larger grids stage them on the stack and copy them out, because
/// from N = 512 on a row's four transforms lie a multiple of 4 KiB apart and four streams of
/// stores at the same offset fall into one L1 cache set (docs/performance.md).
const STRAIGHT_MAX: usize = 256;

/// Arrays on the stack [`evolve_row_pair`] computes a block's phases and values into before
/// they are copied out (see [`evolve_block`]); made once per task rather than per row pair,
/// so that their zeroing is paid once.
pub(super) struct EvolveBuffers {
    turns: [f32; EVOLVE_BLOCK],
    /// The block's own values, for N above [`STRAIGHT_MAX`].
    plus: [[Complex32; EVOLVE_BLOCK]; 4],
    /// Their partners' values, in the block's order (reversed into the lower rows).
    minus: [[Complex32; EVOLVE_BLOCK]; 4],
}

impl EvolveBuffers {
    pub(super) fn new() -> Self {
        EvolveBuffers {
            turns: [0.0; EVOLVE_BLOCK],
            plus: [[Complex32::default(); EVOLVE_BLOCK]; 4],
            minus: [[Complex32::default(); EVOLVE_BLOCK]; 4],
        }
    }
}

/// Fills spectral rows i (`upper`, k_x > 0) and N − i (`lower`, its Hermitian partner), each
/// four packed transforms of N, from table row i: (i, j) pairs with (N − i, N − j). Blocks
/// whose bit is set in `zero` (see [`zero_blocks`]) are written as zeros without evolving.
/// Inlined into its caller's [`Simd::run`](crate::math::simd::Simd::run), so that its loops are
/// compiled for the level the cascade runs at.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn evolve_row_pair(
    buffers: &mut EvolveBuffers,
    table: EvolutionRow<'_>,
    zero: u64,
    kx: f32,
    kz: &[f32],
    t: f64,
    upper: &mut [Complex32],
    lower: &mut [Complex32],
) {
    let n = kz.len();
    let (u0, rest) = upper.split_at_mut(n);
    let (u1, rest) = rest.split_at_mut(n);
    let (u2, u3) = rest.split_at_mut(n);
    let (l0, rest) = lower.split_at_mut(n);
    let (l1, rest) = rest.split_at_mut(n);
    let (l2, l3) = rest.split_at_mut(n);
    let (u3, l3) = (&mut u3[..n], &mut l3[..n]);
    // Column 0 pairs with itself; the rest pair j with N − j. (The Nyquist column's table
    // entries are zero, so it comes out zero.)
    let e = table.get(0);
    let (plus, minus) = packed_pair(fract_turns(e.freq * t), e.p, e.q, kx, kz[0], table.inv_k[0]);
    (u0[0], u1[0], u2[0], u3[0]) = (plus[0], plus[1], plus[2], plus[3]);
    (l0[0], l1[0], l2[0], l3[0]) = (minus[0], minus[1], minus[2], minus[3]);
    // Per block: the f64 phase reduction first (2 lanes per SSE vector), then the f32 work
    // (4 lanes), each loop vectorising at its own width.
    let EvolveBuffers { turns, plus, minus } = buffers;
    let (mut u, mut l) = ([u0, u1, u2, u3], [l0, l1, l2, l3]);
    for (b, range) in column_blocks(n).enumerate() {
        let len = range.len();
        // Partners N − j of the block's columns j ≥ 1 (column 0 is its own partner).
        let skip = usize::from(range.start == 0);
        let mirror = n - range.end + 1..n - range.start - skip + 1;
        if zero & (1 << b) != 0 {
            // Zeros in, zeros out: a fill costs a fraction of the sines and cosines. (The
            // evolution would give ±0 here; the sign of a zero never reaches an output, which
            // the hash check of every buffer confirmed.)
            for out in &mut u {
                out[range.clone()].fill(Complex32::default());
            }
            for out in &mut l {
                out[mirror.clone()].fill(Complex32::default());
            }
            continue;
        }
        let turns = &mut turns[..len];
        for (turns, &freq) in turns.iter_mut().zip(&table.freq[range.clone()]) {
            *turns = fract_turns(freq * t);
        }
        let (p_re, p_im) = (&table.p_re[range.clone()], &table.p_im[range.clone()]);
        let (q_re, q_im) = (&table.q_re[range.clone()], &table.q_im[range.clone()]);
        let (inv_k, kz) = (&table.inv_k[range.clone()], &kz[range.clone()]);
        if n <= STRAIGHT_MAX {
            let [u0, u1, u2, u3] = &mut u;
            evolve_block(
                turns,
                p_re,
                p_im,
                q_re,
                q_im,
                inv_k,
                kx,
                kz,
                &mut u0[range.clone()],
                &mut u1[range.clone()],
                &mut u2[range.clone()],
                &mut u3[range.clone()],
                minus,
            );
        } else {
            let [p0, p1, p2, p3] = &mut *plus;
            evolve_block(
                turns, p_re, p_im, q_re, q_im, inv_k, kx, kz, p0, p1, p2, p3, minus,
            );
            for (out, values) in u.iter_mut().zip(plus.iter()) {
                out[range.clone()].copy_from_slice(&values[..len]);
            }
        }
        // Out to the rows: the partners N − j of the block's columns, reversed.
        for (out, values) in l.iter_mut().zip(minus.iter()) {
            for (out, value) in out[mirror.clone()]
                .iter_mut()
                .zip(values[skip..len].iter().rev())
            {
                *out = *value;
            }
            if skip == 1 {
                out[0] = values[0];
            }
        }
    }
}

/// The four packed values of a block of columns j into `u0`…`u3` (the block's part of the
/// four upper rows, or arrays on the stack: see [`STRAIGHT_MAX`]) and of their partners
/// N − j into `minus` (arrays on the caller's stack, in the block's order, reversed into the
/// lower rows afterwards), from the block's reduced phases and its table entries
/// (p_re, p_im, q_re, q_im, 1/|k|).
///
/// A loop on its own with every slice an argument of its own: LLVM knows that reference
/// arguments do not overlap and keeps that knowledge once this is inlined, so the loop
/// vectorises at every SIMD level (slices passed in an array lose that). The partners always
/// go through the stack because their columns run backwards: written straight into the lower
/// rows, even as separate arguments, the loop stays scalar inside the AVX-512 kernel
/// (docs/performance.md).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn evolve_block(
    turns: &[f32],
    p_re: &[f32],
    p_im: &[f32],
    q_re: &[f32],
    q_im: &[f32],
    inv_k: &[f32],
    kx: f32,
    kz: &[f32],
    u0: &mut [Complex32],
    u1: &mut [Complex32],
    u2: &mut [Complex32],
    u3: &mut [Complex32],
    minus: &mut [[Complex32; EVOLVE_BLOCK]; 4],
) {
    let len = turns.len().min(EVOLVE_BLOCK);
    let (p_re, p_im) = (&p_re[..len], &p_im[..len]);
    let (q_re, q_im) = (&q_re[..len], &q_im[..len]);
    let (inv_k, kz) = (&inv_k[..len], &kz[..len]);
    let (u0, u1, u2, u3) = (
        &mut u0[..len],
        &mut u1[..len],
        &mut u2[..len],
        &mut u3[..len],
    );
    let [l0, l1, l2, l3] = minus;
    let (l0, l1, l2, l3) = (
        &mut l0[..len],
        &mut l1[..len],
        &mut l2[..len],
        &mut l3[..len],
    );
    for b in 0..len {
        let p = Complex32::new(p_re[b], p_im[b]);
        let q = Complex32::new(q_re[b], q_im[b]);
        let (plus, minus) = packed_pair(turns[b], p, q, kx, kz[b], inv_k[b]);
        (u0[b], u1[b], u2[b], u3[b]) = (plus[0], plus[1], plus[2], plus[3]);
        (l0[b], l1[b], l2[b], l3[b]) = (minus[0], minus[1], minus[2], minus[3]);
    }
}

#[cfg(test)]
// References in the standard library\'s maths: tests are not simulation code.
#[allow(clippy::disallowed_methods)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    #[test]
    fn fast_sin_cos_matches_std_over_a_turn() {
        let mut worst = 0.0f64;
        for step in -50_000..=50_000 {
            let turns = step as f32 / 100_000.0;
            let (s, c) = sin_cos_turns(turns);
            let (es, ec) = (f64::from(turns) * TAU).sin_cos();
            worst = worst
                .max((f64::from(s) - es).abs())
                .max((f64::from(c) - ec).abs());
        }
        // f32 rounding of the reduced angle and of the polynomial: a few ulps of 1.
        assert!(worst < 5e-7, "worst error {worst}");
    }

    #[test]
    fn fast_sin_cos_handles_quadrant_ties_and_whole_turns() {
        // Exact quadrant boundaries (ties of the rounding) and values beyond half a turn.
        for step in -12..=12 {
            let turns = step as f32 / 8.0;
            let (s, c) = sin_cos_turns(turns);
            let (es, ec) = (f64::from(turns) * TAU).sin_cos();
            assert!((f64::from(s) - es).abs() < 1e-6, "sin at {turns}");
            assert!((f64::from(c) - ec).abs() < 1e-6, "cos at {turns}");
        }
    }

    #[test]
    fn fract_turns_reduces_large_phases_exactly() {
        for (turns, expected) in [
            (0.25, 0.25),
            (-0.25, -0.25),
            (3.75, -0.25),
            (-7.125, -0.125),
            (1e12 + 0.375, 0.375),
            (-(2f64.powi(40)) - 0.0625, -0.0625),
        ] {
            assert_eq!(fract_turns(turns), expected, "turns {turns}");
        }
        // Beyond 2^52 every f64 is an integer: the phase is a whole number of turns.
        let (s, c) = sin_cos_turns(fract_turns(2f64.powi(60) + 4096.0));
        assert!(s.abs() < 1e-7 && (c - 1.0).abs() < 1e-7);
    }
}
