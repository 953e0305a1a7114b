//! The SIMD level the update's element loops run at, chosen once per cascade by run-time CPU
//! detection.
//!
//! The loops themselves (evolution, outputs) are plain scalar Rust that LLVM vectorises; run
//! through [`Simd::run`] they are compiled once more inside an AVX2 (x86-64-v3) and an
//! AVX-512 (x86-64-v4) context by the `pulp` crate, which checks the CPU and holds the only
//! `unsafe` of the dispatch. Wider lanes are the point: baseline x86-64 gives LLVM only SSE2's
//! four (what that buys is measured in docs/performance.md).
//!
//! Why pulp rather than `multiversion`: pulp's levels are values (`V3::try_new()`,
//! `V4::try_new()`), so a cascade stores the one it runs at and the tests force every level
//! the machine has through pulp's own API, with no override machinery of ours; and it needs
//! no proc macro. `multiversion` hides its choice in a static per function, so forcing a
//! lower level would take a second copy of every wrapper.
//!
//! **Bit-identical on every path.** The levels only change how many lanes an instruction
//! works on: each lane still rounds every operation as the scalar code does. Rust never fuses
//! a multiply and an add into an FMA on its own (that needs an explicit `mul_add`), even
//! where the FMA extension is enabled; square root and division are correctly rounded in
//! every SSE/AVX form; and the loops hold no reduction whose order a vectoriser could change.
//! Where the queries do fuse (their spline sums), they say so: [`Simd::mul_add`] in the
//! single queries and the lanes' `add_product` in the batches give IEEE 754's fused result
//! at every level ([`baseline_mul_add`] where the CPU has no FMA instruction).
//! `tests` in src/cascade/tests.rs compare every output bit of every level the machine has.

use crate::math::determinism::Determinism;

/// A SIMD level of the update's element loops, proven available on this CPU.
#[derive(Clone, Copy)]
pub(crate) enum Simd {
    /// The target's baseline (SSE2 on x86-64; whatever the target enables elsewhere).
    /// `fused`: whether the queries' fused multiply-adds give IEEE 754's fused result
    /// ([`baseline_mul_add`]) or, on a CPU without FMA in `Determinism::SameMachine` mode,
    /// a product and a sum rounded apart (see [`Simd::for_queries`]). Only the queries read
    /// it.
    Baseline { fused: bool },
    /// AVX2, FMA, BMI1/2 (x86-64-v3).
    #[cfg(target_arch = "x86_64")]
    Avx2(pulp::x86::V3),
    /// AVX-512 F, BW, CD, DQ, VL on top of x86-64-v3 (x86-64-v4).
    #[cfg(target_arch = "x86_64")]
    Avx512(pulp::x86::V4),
}

impl Simd {
    /// The widest level this CPU runs.
    pub(crate) fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        {
            if let Some(v4) = pulp::x86::V4::try_new() {
                return Simd::Avx512(v4);
            }
            if let Some(v3) = pulp::x86::V3::try_new() {
                return Simd::Avx2(v3);
            }
        }
        Simd::Baseline { fused: true }
    }

    /// This level for the queries of an ocean in `determinism` mode: the baseline of a CPU
    /// without an FMA instruction adds the queries' products unfused in
    /// `Determinism::SameMachine` mode (fused in software they cost several times as much,
    /// and the mode lets one machine's bits differ from another's), fused in
    /// `CrossPlatform` mode (the same bits on every machine).
    pub(crate) fn for_queries(self, determinism: Determinism) -> Simd {
        match self {
            Simd::Baseline { .. } => Simd::Baseline {
                fused: baseline_fused(determinism, cpu_has_fma()),
            },
            other => other,
        }
    }

    /// Every level this CPU runs, baseline first.
    #[cfg(test)]
    pub(crate) fn available() -> Vec<Self> {
        #[allow(unused_mut)]
        let mut levels = vec![Simd::Baseline { fused: true }];
        #[cfg(target_arch = "x86_64")]
        {
            levels.extend(pulp::x86::V3::try_new().map(Simd::Avx2));
            levels.extend(pulp::x86::V4::try_new().map(Simd::Avx512));
        }
        levels
    }

    /// Runs `kernel` compiled for this level. Only code inlined into `kernel` is compiled
    /// for it, so the loops it calls are `#[inline(always)]`.
    #[inline(always)]
    pub(crate) fn run<R>(self, kernel: impl FnOnce() -> R) -> R {
        match self {
            Simd::Baseline { .. } => kernel(),
            #[cfg(target_arch = "x86_64")]
            Simd::Avx2(v3) => v3.vectorize(kernel),
            #[cfg(target_arch = "x86_64")]
            Simd::Avx512(v4) => v4.vectorize(kernel),
        }
    }
}

/// Work for [`Simd::run_kernel`]: its `run` is `#[inline(always)]`, so that it, and what it
/// inlines, is compiled at each level (a closure called from the three arms of
/// [`Simd::run`] may stay a function of its own, compiled for the baseline only, when it is
/// large).
pub(crate) trait Kernel {
    type Output;
    fn run(self) -> Self::Output;
}

/// A [`Kernel`] as pulp's work item.
struct Pulp<K>(K);

impl<K: Kernel> pulp::NullaryFnOnce for Pulp<K> {
    type Output = K::Output;

    #[inline(always)]
    fn call(self) -> K::Output {
        self.0.run()
    }
}

impl Simd {
    /// Runs `kernel` compiled for this level (see [`Kernel`]).
    #[inline(always)]
    pub(crate) fn run_kernel<K: Kernel>(self, kernel: K) -> K::Output {
        match self {
            Simd::Baseline { .. } => kernel.run(),
            #[cfg(target_arch = "x86_64")]
            Simd::Avx2(v3) => v3.vectorize(Pulp(kernel)),
            #[cfg(target_arch = "x86_64")]
            Simd::Avx512(v4) => v4.vectorize(Pulp(kernel)),
        }
    }
}

impl Simd {
    /// a·b + c rounded once (`f32::mul_add`'s bits), for code running at this level: the
    /// FMA instruction at AVX2 and AVX-512, [`baseline_mul_add`] at the baseline.
    #[inline(always)]
    pub(crate) fn mul_add(self, a: f32, b: f32, c: f32) -> f32 {
        match self {
            Simd::Baseline { fused: true } => baseline_mul_add(a, b, c),
            Simd::Baseline { fused: false } => a * b + c,
            #[cfg(target_arch = "x86_64")]
            _ => a.mul_add(b, c),
        }
    }
}

impl std::fmt::Debug for Simd {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Simd::Baseline { fused: true } => "Baseline",
            Simd::Baseline { fused: false } => "Baseline (unfused)",
            #[cfg(target_arch = "x86_64")]
            Simd::Avx2(_) => "Avx2",
            #[cfg(target_arch = "x86_64")]
            Simd::Avx512(_) => "Avx512",
        })
    }
}

/// Rayon pools of 1, 2 and 3 threads, each with its size, for the tests that compare every
/// SIMD level at every thread count.
#[cfg(test)]
pub(crate) fn test_pools() -> Vec<(usize, rayon::ThreadPool)> {
    [1, 2, 3]
        .into_iter()
        .map(|threads| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("a thread pool");
            (threads, pool)
        })
        .collect()
}

/// Whether code compiled at the baseline level has an FMA instruction (aarch64 always has;
/// an x86-64 build only with the feature enabled for the whole crate).
const HARDWARE_FMA: bool = cfg!(any(target_feature = "fma", target_arch = "aarch64"));

/// a·b + c rounded once (IEEE 754's fused multiply-add: `f32::mul_add`'s bits) for code
/// compiled at the [`Simd::Baseline`] level, where x86-64 has no FMA instruction and
/// `f32::mul_add` calls the C library's `fmaf`, far slower (docs/performance.md, "Fused
/// multiply-adds"). The product of two f32 is exact in f64 (24 + 24 bits), so
/// the sum rounds once in f64 and once more to f32; the second rounding gives the fused
/// result unless the first landed exactly halfway between two f32 (or among the f32
/// subnormals, whose halfway points lie elsewhere), rare cases left to `libm::fmaf`.
#[inline(always)]
pub(crate) fn baseline_mul_add(a: f32, b: f32, c: f32) -> f32 {
    if HARDWARE_FMA {
        return a.mul_add(b, c);
    }
    let sum = f64::from(a) * f64::from(b) + f64::from(c);
    if double_rounding_hazard(sum) {
        libm::fmaf(a, b, c)
    } else {
        sum as f32
    }
}

/// Whether the queries at the baseline level fuse their multiply-adds: always in
/// `CrossPlatform` mode, in `SameMachine` mode where the CPU has FMA (`has_fma`).
fn baseline_fused(determinism: Determinism, has_fma: bool) -> bool {
    determinism == Determinism::CrossPlatform || has_fma
}

/// Whether this CPU has a fused multiply-add instruction.
fn cpu_has_fma() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        HARDWARE_FMA
    }
}

/// `a·b + c` of eight lanes at the baseline level: [`baseline_mul_add_lanes`] if `fused`,
/// else a product and a sum (see [`Simd::Baseline`]).
#[inline(always)]
pub(crate) fn baseline_lanes(fused: bool, a: [f32; 8], b: [f32; 8], c: [f32; 8]) -> [f32; 8] {
    if fused {
        baseline_mul_add_lanes(a, b, c)
    } else {
        let mut out = [0.0f32; 8];
        for l in 0..8 {
            out[l] = a[l] * b[l] + c[l];
        }
        out
    }
}

/// [`baseline_mul_add`] of eight lanes (the common case vectorised, the rare ones lane by
/// lane).
#[inline(always)]
pub(crate) fn baseline_mul_add_lanes(a: [f32; 8], b: [f32; 8], c: [f32; 8]) -> [f32; 8] {
    if HARDWARE_FMA {
        return std::array::from_fn(|l| a[l].mul_add(b[l], c[l]));
    }
    let mut sum = [0.0f64; 8];
    for l in 0..8 {
        sum[l] = f64::from(a[l]) * f64::from(b[l]) + f64::from(c[l]);
    }
    if sum.iter().any(|&s| double_rounding_hazard(s)) {
        return std::array::from_fn(|l| baseline_mul_add(a[l], b[l], c[l]));
    }
    let mut out = [0.0f32; 8];
    for l in 0..8 {
        out[l] = sum[l] as f32;
    }
    out
}

/// Whether rounding the f64 `sum` to f32 may differ from rounding the exact value it was
/// rounded from: `sum` lies exactly halfway between two normal f32 (its low 29 significand
/// bits 1000…0), or below the smallest normal f32 (and is not zero).
#[inline(always)]
fn double_rounding_hazard(sum: f64) -> bool {
    // The low 29 bits lie in the low 32 (a 32-bit comparison, which SSE2 has).
    const LOW: u32 = (1 << 29) - 1;
    let halfway = sum.to_bits() as u32 & LOW == 1 << 28;
    let tiny = sum != 0.0 && sum.abs() < f64::from(f32::MIN_POSITIVE);
    halfway | tiny
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One fused multiply-add checked against two independent ones (`libm::fmaf`, pure
    /// Rust, and std's `f32::mul_add`: the CPU's instruction or the C library's routine),
    /// alone and in lanes.
    fn check(a: f32, b: f32, c: f32) {
        let want = libm::fmaf(a, b, c);
        assert_eq!(
            a.mul_add(b, c).to_bits(),
            want.to_bits(),
            "{a:e}·{b:e} + {c:e}"
        );
        let got = baseline_mul_add(a, b, c);
        assert_eq!(got.to_bits(), want.to_bits(), "{a:e}·{b:e} + {c:e}");
        let lanes = baseline_mul_add_lanes([a; 8], [b; 8], [c; 8]);
        assert!(lanes.iter().all(|v| v.to_bits() == want.to_bits()));
    }

    /// 2^k, exactly (−126 ≤ k ≤ 127).
    fn two_to(k: i32) -> f32 {
        f32::from_bits(((k + 127) as u32) << 23)
    }

    #[test]
    fn the_baseline_adds_unfused_only_on_a_cpu_without_fma_in_same_machine_mode() {
        use Determinism::{CrossPlatform, SameMachine};
        assert!(baseline_fused(CrossPlatform, false));
        assert!(baseline_fused(CrossPlatform, true));
        assert!(baseline_fused(SameMachine, true));
        assert!(!baseline_fused(SameMachine, false));
        // The wider levels are left as they are.
        if let Some(level) = Simd::available().last() {
            let queries = level.for_queries(SameMachine);
            assert_eq!(format!("{queries:?}"), format!("{level:?}"));
        }
    }

    #[test]
    fn the_baseline_fused_multiply_add_rounds_once() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let mut unit = || (next() >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0;
        let mut hazards = 0;
        for i in 0..200_000 {
            // Products and addends of nearby and distant scales, with cancellation.
            let scale = two_to;
            let (a, b) = (unit() * scale(i % 40 - 20), unit() * scale(i % 7 - 3));
            let c = unit() * scale(i % 50 - 25);
            check(a, b, c);
            // c in [1, 2) and a product half c's last place (2⁻²⁴) times 1 − k²·2⁻³⁶
            // ((1 + k·2⁻¹⁸)(1 − k·2⁻¹⁸), k ≤ 8): off the halfway point between two f32 by
            // at most 2⁻⁵⁴, which the f64 sum rounds away, landing on it.
            let m = (i % 8 + 1) as f32 * two_to(-18);
            let c = 1.0 + (i % 4096) as f32 * f32::EPSILON;
            let half_ulp = f32::EPSILON / 2.0;
            let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
            let (a, b) = (sign * half_ulp * (1.0 + m), 1.0 - m);
            if double_rounding_hazard(f64::from(a) * f64::from(b) + f64::from(c)) {
                hazards += 1;
            }
            check(a, b, c);
            // The same among the subnormals (2⁻¹³⁰ = 2⁻⁶⁵ · 2⁻⁶⁵).
            let tiny = two_to(-65) * two_to(-65);
            check(a * tiny, b, c * tiny);
        }
        // The constructed cases must reach the exact routine (and did agree above).
        assert!(hazards > 100_000, "{hazards} hazards");
        for (a, b, c) in [
            (0.0, 5.0, -0.0),
            (-0.0, 5.0, -0.0),
            (f32::MAX, 2.0, -f32::MAX),
            (f32::MIN_POSITIVE, 0.5, 0.0),
            (f32::INFINITY, 1.0, 1.0),
            (1.0, 1.0, f32::NEG_INFINITY),
        ] {
            check(a, b, c);
        }
    }
}
