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
//! `tests` in src/cascade/mod.rs compare every output bit of every level the machine has.

/// A SIMD level of the update's element loops, proven available on this CPU.
#[derive(Clone, Copy)]
pub(crate) enum Simd {
    /// The target's baseline (SSE2 on x86-64; whatever the target enables elsewhere).
    Baseline,
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
        Simd::Baseline
    }

    /// Every level this CPU runs, baseline first.
    #[cfg(test)]
    pub(crate) fn available() -> Vec<Self> {
        #[allow(unused_mut)]
        let mut levels = vec![Simd::Baseline];
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
            Simd::Baseline => kernel(),
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
            Simd::Baseline => kernel.run(),
            #[cfg(target_arch = "x86_64")]
            Simd::Avx2(v3) => v3.vectorize(Pulp(kernel)),
            #[cfg(target_arch = "x86_64")]
            Simd::Avx512(v4) => v4.vectorize(Pulp(kernel)),
        }
    }
}

impl std::fmt::Debug for Simd {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Simd::Baseline => "Baseline",
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
