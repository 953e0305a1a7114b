//! Pass-2 kernels: height, displacement, slope, normal and Jacobian of one grid row from its
//! four packed, transformed rows.

use num_complex::Complex32;

/// Where the displaced surface is vertical or folded (J ≤ 0), the slope's denominator n_y is
/// kept at least this fraction of |n|, so the slope stays finite (≤ 1e4).
const MIN_SLOPE_NY: f32 = 1e-4;

/// Normals per output block: computed into plain f32 arrays (so that the arithmetic
/// vectorises; stores of `[f32; 3]` in the same loop keep it scalar), then copied out. Made
/// once per task rather than per row, so that their zeroing is paid once.
pub(super) struct NormalBuffers {
    nx: [f32; OUTPUT_BLOCK],
    ny: [f32; OUTPUT_BLOCK],
    nz: [f32; OUTPUT_BLOCK],
}

impl NormalBuffers {
    pub(super) fn new() -> Self {
        NormalBuffers {
            nx: [0.0; OUTPUT_BLOCK],
            ny: [0.0; OUTPUT_BLOCK],
            nz: [0.0; OUTPUT_BLOCK],
        }
    }
}

/// Points [`write_outputs`] computes at once.
const OUTPUT_BLOCK: usize = 128;

/// Output buffers of one grid row from its four packed, transformed rows; `offset` (m) is
/// added to every height (the mean-level correction, see `Cascade::mean_level_offset`).
/// Inlined into its caller's [`Simd::run`](crate::math::simd::Simd::run), so that its loops are
/// compiled for the level the cascade runs at.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn write_outputs(
    normals: &mut NormalBuffers,
    row: &[Complex32],
    n: usize,
    lambda: f32,
    offset: f32,
    height: &mut [f32],
    displacement: &mut [[f32; 2]],
    slope: &mut [[f32; 2]],
    normal: &mut [[f32; 3]],
    jacobian: &mut [f32],
) {
    let (t0, rest) = row.split_at(n);
    let (t1, rest) = rest.split_at(n);
    let (t2, t3) = rest.split_at(n);
    let NormalBuffers { nx, ny, nz } = normals;
    for start in (0..n).step_by(OUTPUT_BLOCK) {
        let len = OUTPUT_BLOCK.min(n - start);
        let range = start..start + len;
        output_block(
            &t0[range.clone()],
            &t1[range.clone()],
            &t2[range.clone()],
            &t3[range.clone()],
            lambda,
            offset,
            &mut height[range.clone()],
            &mut jacobian[range.clone()],
            &mut displacement[range.clone()],
            &mut slope[range.clone()],
            &mut nx[..len],
            &mut ny[..len],
            &mut nz[..len],
        );
        for (normal, ((&x, &y), &z)) in normal[range]
            .iter_mut()
            .zip(nx.iter().zip(ny.iter()).zip(nz.iter()))
        {
            *normal = [x, y, z];
        }
    }
}

/// The arithmetic of [`write_outputs`] on one block, with the normals into plain f32 arrays.
/// A function of its own, with every slice a separate argument (so that LLVM knows they do
/// not overlap and needs no run-time checks: inlined, they keep that knowledge as alias
/// scopes), so that the loop vectorises.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn output_block(
    t0: &[Complex32],
    t1: &[Complex32],
    t2: &[Complex32],
    t3: &[Complex32],
    lambda: f32,
    offset: f32,
    height: &mut [f32],
    jacobian: &mut [f32],
    displacement: &mut [[f32; 2]],
    slope: &mut [[f32; 2]],
    nx: &mut [f32],
    ny: &mut [f32],
    nz: &mut [f32],
) {
    let len = t0.len();
    let (t1, t2, t3) = (&t1[..len], &t2[..len], &t3[..len]);
    let (height, jacobian) = (&mut height[..len], &mut jacobian[..len]);
    let (displacement, slope) = (&mut displacement[..len], &mut slope[..len]);
    let (nx, ny, nz) = (&mut nx[..len], &mut ny[..len], &mut nz[..len]);
    for i in 0..len {
        let (eta, dx) = (t0[i].re, t0[i].im);
        let (dz, eta_x) = (t1[i].re, t1[i].im);
        let (eta_z, dxx) = (t2[i].re, t2[i].im);
        let (dzz, dxz) = (t3[i].re, t3[i].im);
        let jxx = 1.0 + lambda * dxx;
        let jzz = 1.0 + lambda * dzz;
        let jxz = lambda * dxz;
        let det = jxx * jzz - jxz * jxz;
        // n = T_z × T_x with T_x = (jxx, η_x, jxz), T_z = (jxz, η_z, jzz); n_y = J.
        let (rx, rz) = (eta_z * jxz - jzz * eta_x, jxz * eta_x - eta_z * jxx);
        let norm = (rx * rx + det * det + rz * rz).sqrt();
        // Branch-free (selects); false for NaN too.
        let valid = (norm > 0.0) & (norm < f32::INFINITY);
        let inv_len = 1.0 / norm;
        // A plain compare rather than f32::max (which handles NaN, at a cost): a NaN here
        // only comes with a NaN norm, where `valid` is false anyway.
        let min_ny = MIN_SLOPE_NY * norm;
        let inv_ny = 1.0 / if det > min_ny { det } else { min_ny };
        height[i] = eta + offset;
        displacement[i] = [lambda * dx, lambda * dz];
        jacobian[i] = det;
        nx[i] = if valid { rx * inv_len } else { 0.0 };
        ny[i] = if valid { det * inv_len } else { 1.0 };
        nz[i] = if valid { rz * inv_len } else { 0.0 };
        slope[i] = if valid {
            [-rx * inv_ny, -rz * inv_ny]
        } else {
            [0.0; 2]
        };
    }
}

/// The displacement gradient `[D_xx, D_zz, D_xz]` at unit choppiness of one grid row, from
/// its four packed, transformed rows (transform 2 holds D_xx in its imaginary part,
/// transform 3 D_zz and D_xz: see `Field::packing`).
#[inline(always)]
pub(super) fn write_gradient(row: &[Complex32], n: usize, gradient: &mut [[f32; 3]]) {
    let t2 = &row[2 * n..3 * n];
    let t3 = &row[3 * n..4 * n];
    for (g, (a, b)) in gradient.iter_mut().zip(t2.iter().zip(t3)) {
        *g = [a.im, b.re, b.im];
    }
}
