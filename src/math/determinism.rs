//! [`Determinism`]: how far the same inputs give the same bits, and the two sets of
//! transcendental functions ([`Math`]) the simulation is written against; [`with_math`] turns
//! a mode chosen at run time into one of them. `clippy.toml` bans the standard library's
//! transcendental methods everywhere else, so no call can bypass the mode.
//!
//! Everything that feeds a simulation (spectra, dispersion, spreading, h0, the evolution,
//! the FFTs, foam and queries) calls its transcendental functions through [`Math`], so one
//! generic body serves both modes: [`Std`] (the standard library's `f64::exp` etc., which
//! call the platform's C library or LLVM intrinsics, whose last bits differ between C
//! libraries and CPUs) and [`Libm`] (the `libm` crate, a pure-Rust port of musl's libm: the
//! same integer and IEEE arithmetic on every target, hence the same bits).
//!
//! Square root, division, rounding to an integer, `rem_euclid`, `abs`, `min`/`max` and
//! conversions are exactly specified by IEEE 754 (and Rust) and need no second version.
//! `powi` does (its rounding sequence is unspecified and may differ by platform).

/// How far the results of the same inputs are guaranteed to be equal: a field of
/// [`CascadeConfig`](crate::CascadeConfig) and [`OceanConfig`](crate::OceanConfig)
/// (`determinism`), chosen at run time so that one binary can run a server's ocean and a
/// client's side by side.
///
/// In both modes a simulation is bit-identical whatever the number of threads and whatever
/// SIMD level the CPU offers. They differ across machines:
///
/// - [`SameMachine`](Self::SameMachine) (the default, fastest): the FFTs run rustfft's
///   kernels for the CPU at hand (AVX, SSE4.1, NEON or scalar), the spectra call the
///   platform's `exp`, `powf`, `tanh`, … and the Gaussian draws come from `rand_distr`.
///   The same binary on the same CPU model gives the same bits; another CPU, operating
///   system, toolchain or dependency release may move the last bits of values (by
///   rounding errors: the waves look the same).
/// - [`CrossPlatform`](Self::CrossPlatform): one fixed scalar FFT code path
///   (rustfft's `FftPlannerScalar`) whatever the CPU offers, every transcendental function
///   from the `libm` crate (pure Rust), no multiply and add fused by the compiler (the
///   queries' spline sums use explicit fused multiply-adds, which IEEE 754 rounds once on
///   every CPU, in hardware or in software; in `SameMachine` mode a CPU without FMA adds
///   them unfused, which is faster there), and the crate's own Box–Muller transform for
///   the Gaussian draws. Every output buffer, h0 and query
///   result is then bit-identical on every CPU and operating system with IEEE 754
///   arithmetic (x86-64, aarch64, wasm32, …; not x87-only 32-bit x86), for the same
///   versions of this crate, `rustfft` and `libm`. Slower: the guide's chapter
///   `docs/guide/networking.md` says what it costs and what else a game must keep equal.
///
/// The two modes give different waves (the Gaussian draws differ), equally calibrated.
///
/// ```
/// use ocean_fft::{Determinism, OceanConfig, OceanState, Spectrum};
///
/// // A server's ocean, which every client rebuilds from the same spectrum and config.
/// let config = OceanConfig {
///     size: 16,
///     determinism: Determinism::CrossPlatform,
///     ..OceanConfig::default()
/// };
/// let mut ocean = OceanState::new(Spectrum::jonswap(10.0, 100_000.0)?, config)?;
/// for tick in 1..=3 {
///     ocean.step_to(f64::from(tick) / 30.0)?;      // the same f64 times on every peer
/// }
/// let y = ocean.water().height_at(12.0, -3.5)?;             // m: the same bits on every machine
/// assert!(y.is_finite());
/// # Ok::<(), ocean_fft::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum Determinism {
    /// Bit-identical across thread counts and SIMD levels on one machine and build; not
    /// across CPUs, operating systems or toolchains. The default.
    #[default]
    SameMachine,
    /// Bit-identical on every supported CPU and operating system, at any thread count, for
    /// the same versions of this crate, `rustfft` and `libm`.
    CrossPlatform,
}

/// Runs `$body` with `$m` standing for the [`Math`] set of the run-time mode `$mode` (a
/// [`Determinism`]): the one place where the mode chosen in a config becomes the functions the
/// simulation is written against.
///
/// ```ignore
/// let k = with_math!(config.determinism, M => dispersion.k_from_omega_with::<M>(omega));
/// ```
macro_rules! with_math {
    ($mode:expr, $m:ident => $body:expr) => {
        match $mode {
            $crate::math::determinism::Determinism::SameMachine => {
                type $m = $crate::math::determinism::Std;
                $body
            }
            $crate::math::determinism::Determinism::CrossPlatform => {
                type $m = $crate::math::determinism::Libm;
                $body
            }
        }
    };
}
pub(crate) use with_math;

/// The transcendental functions a simulation calls: [`Std`] or [`Libm`].
pub(crate) trait Math: Copy + Send + Sync + 'static {
    /// The mode these functions belong to.
    const MODE: Determinism;
    fn exp(x: f64) -> f64;
    fn ln(x: f64) -> f64;
    fn log10(x: f64) -> f64;
    fn powf(x: f64, y: f64) -> f64;
    /// `x` to an integer power.
    fn powi(x: f64, n: i32) -> f64;
    fn tanh(x: f64) -> f64;
    fn sinh(x: f64) -> f64;
    fn cosh(x: f64) -> f64;
    fn sin(x: f64) -> f64;
    fn cos(x: f64) -> f64;
    fn sin_cos(x: f64) -> (f64, f64);
    fn atan2(y: f64, x: f64) -> f64;
    fn hypot(x: f64, y: f64) -> f64;
    fn cbrt(x: f64) -> f64;
}

/// The standard library's functions: the platform's C library or LLVM's intrinsics. The one
/// place simulation code may call them (`Determinism::SameMachine` means them).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Std;

/// The `libm` crate's functions: pure Rust, the same bits on every IEEE 754 target.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Libm;

// SameMachine is defined as the standard library's functions (clippy.toml bans them elsewhere).
#[allow(clippy::disallowed_methods)]
impl Math for Std {
    const MODE: Determinism = Determinism::SameMachine;
    #[inline]
    fn exp(x: f64) -> f64 {
        x.exp()
    }
    #[inline]
    fn ln(x: f64) -> f64 {
        x.ln()
    }
    #[inline]
    fn log10(x: f64) -> f64 {
        x.log10()
    }
    #[inline]
    fn powf(x: f64, y: f64) -> f64 {
        x.powf(y)
    }
    #[inline]
    fn powi(x: f64, n: i32) -> f64 {
        x.powi(n)
    }
    #[inline]
    fn tanh(x: f64) -> f64 {
        x.tanh()
    }
    #[inline]
    fn sinh(x: f64) -> f64 {
        x.sinh()
    }
    #[inline]
    fn cosh(x: f64) -> f64 {
        x.cosh()
    }
    #[inline]
    fn sin(x: f64) -> f64 {
        x.sin()
    }
    #[inline]
    fn cos(x: f64) -> f64 {
        x.cos()
    }
    #[inline]
    fn sin_cos(x: f64) -> (f64, f64) {
        x.sin_cos()
    }
    #[inline]
    fn atan2(y: f64, x: f64) -> f64 {
        y.atan2(x)
    }
    #[inline]
    fn hypot(x: f64, y: f64) -> f64 {
        x.hypot(y)
    }
    #[inline]
    fn cbrt(x: f64) -> f64 {
        x.cbrt()
    }
}

impl Math for Libm {
    const MODE: Determinism = Determinism::CrossPlatform;
    #[inline]
    fn exp(x: f64) -> f64 {
        libm::exp(x)
    }
    #[inline]
    fn ln(x: f64) -> f64 {
        libm::log(x)
    }
    #[inline]
    fn log10(x: f64) -> f64 {
        libm::log10(x)
    }
    #[inline]
    fn powf(x: f64, y: f64) -> f64 {
        libm::pow(x, y)
    }
    #[inline]
    fn powi(x: f64, n: i32) -> f64 {
        // pow is exact for the small integer powers of exactly representable results and
        // within an ulp otherwise, the same on every target.
        libm::pow(x, f64::from(n))
    }
    #[inline]
    fn tanh(x: f64) -> f64 {
        libm::tanh(x)
    }
    #[inline]
    fn sinh(x: f64) -> f64 {
        libm::sinh(x)
    }
    #[inline]
    fn cosh(x: f64) -> f64 {
        libm::cosh(x)
    }
    #[inline]
    fn sin(x: f64) -> f64 {
        libm::sin(x)
    }
    #[inline]
    fn cos(x: f64) -> f64 {
        libm::cos(x)
    }
    #[inline]
    fn sin_cos(x: f64) -> (f64, f64) {
        libm::sincos(x)
    }
    #[inline]
    fn atan2(y: f64, x: f64) -> f64 {
        libm::atan2(y, x)
    }
    #[inline]
    fn hypot(x: f64, y: f64) -> f64 {
        libm::hypot(x, y)
    }
    #[inline]
    fn cbrt(x: f64) -> f64 {
        libm::cbrt(x)
    }
}

#[cfg(test)]
// The tests compare both sets against the standard library.
#[allow(clippy::disallowed_methods)]
mod tests {
    use super::*;

    /// Both sets agree with each other to a few ulps on ordinary arguments: they compute the
    /// same functions (a swapped argument or a wrong function would be far off).
    #[test]
    fn std_and_libm_compute_the_same_functions() {
        fn close(a: f64, b: f64) -> bool {
            a == b || (a - b).abs() <= 4.0 * f64::EPSILON * a.abs().max(b.abs())
        }
        for i in 1..200 {
            let x = f64::from(i) * 0.173 - 7.0;
            let y = f64::from(i) * 0.05 + 0.01;
            assert!(close(Std::exp(x), Libm::exp(x)), "exp {x}");
            assert!(close(Std::ln(y), Libm::ln(y)), "ln {y}");
            assert!(close(Std::log10(y), Libm::log10(y)), "log10 {y}");
            assert!(close(Std::powf(y, x), Libm::powf(y, x)), "powf {y} {x}");
            assert!(close(Std::powi(x, 5), Libm::powi(x, 5)), "powi {x}");
            assert!(close(Std::tanh(x), Libm::tanh(x)), "tanh {x}");
            assert!(close(Std::sinh(x), Libm::sinh(x)), "sinh {x}");
            assert!(close(Std::cosh(x), Libm::cosh(x)), "cosh {x}");
            assert!(close(Std::sin(x), Libm::sin(x)), "sin {x}");
            assert!(close(Std::cos(x), Libm::cos(x)), "cos {x}");
            let (s, c) = Libm::sin_cos(x);
            assert!(
                close(s, Std::sin(x)) && close(c, Std::cos(x)),
                "sin_cos {x}"
            );
            assert!(close(Std::atan2(x, y), Libm::atan2(x, y)), "atan2 {x} {y}");
            assert!(close(Std::hypot(x, y), Libm::hypot(x, y)), "hypot {x} {y}");
            assert!(close(Std::cbrt(x), Libm::cbrt(x)), "cbrt {x}");
        }
    }
}
