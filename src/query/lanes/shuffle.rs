//! How the lanes' vectors are made and combined at each SIMD level ([`Shuffle`]): rows of
//! taps transposed into lanes, and products added with one rounding.

use super::{each, F32s, LANES};
use crate::math::simd::Kernel;

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
    /// `kernel` at this level as a function of its own, which the compiler may inline or
    /// call: one compiled copy for all its callers rather than one inlined into each.
    fn run<K: Kernel>(self, kernel: K) -> K::Output;
}

/// [`Kernel::run`] as a function of its own (see [`Shuffle::run`]): `#[inline]` alone left the
/// baseline's copies inlined.
#[inline(never)]
fn outlined<K: Kernel>(kernel: K) -> K::Output {
    kernel.run()
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

    #[inline(always)]
    fn run<K: Kernel>(self, kernel: K) -> K::Output {
        outlined(kernel)
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

    #[inline(always)]
    fn run<K: Kernel>(self, kernel: K) -> K::Output {
        // pulp's entry into the level is a function of its own, compiled with its features.
        crate::math::simd::Simd::Avx2(self).run_kernel(kernel)
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
