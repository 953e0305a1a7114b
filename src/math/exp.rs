//! The crate's own single-precision exponential: branch-free (so loops that call it
//! vectorise), and the same bits on every CPU and at every SIMD level.
//!
//! e^x = 2^n · e^r with n = round(x/ln 2) and r = x − n ln 2 in [−ln 2/2, ln 2/2]. The
//! reduction subtracts n ln 2 in two parts (Cody & Waite 1980): `LN2_HI` has only 9
//! significant bits, so n·`LN2_HI` is exact for |n| ≤ 2⁸ and so is the subtraction
//! x − n·`LN2_HI` (the two are within a factor 2 of each other, Sterbenz's lemma); the
//! remainder of ln 2, `LN2_LO`, then costs one rounding of a number far below r. e^r is its
//! Taylor polynomial of degree 7 (the omitted terms are below |r|⁸/8! ≈ 5·10⁻⁹, under a
//! tenth of an ulp), evaluated by Horner's rule; 2^n is built from its bits and the product
//! is exact. Rounding to n uses the classic addition of 1.5·2²³ (exact in round-to-nearest),
//! not a rounding instruction, which x86-64's baseline lacks.
//!
//! Only +, −, × and bit operations, each correctly rounded in IEEE 754 and never fused into
//! an FMA by Rust, so every CPU, every compiler back end and every SIMD width gives the same
//! bits (unlike the platform's `expf`, whose last bits vary between C libraries). Accuracy:
//! within 2 ulp of e^x over the whole domain (a unit test sweeps it against f64's `exp`).

/// Below this the result is exactly 0: e^−87 ≈ 1.6·10⁻³⁸ is still a normal f32, so the
/// function never returns a subnormal (slow on many CPUs, and of no use to its callers).
pub(crate) const EXP_MIN: f32 = -87.0;

/// Arguments above this are clamped to it: e^88 ≈ 1.65·10³⁸, below `f32::MAX`.
pub(crate) const EXP_MAX: f32 = 88.0;

const LOG2_E: f32 = std::f32::consts::LOG2_E;
/// ln 2 to 9 significant bits (355/512).
const LN2_HI: f32 = 0.693_359_4;
/// ln 2 − `LN2_HI`.
const LN2_LO: f32 = -2.121_944_4e-4;
/// 1.5·2²³: adding it rounds a float of magnitude below 2²² to an integer (round to nearest
/// even), which then sits in the low bits of the sum's significand.
const ROUND: f32 = 12_582_912.0;

/// e^x in f32: 0 for x < [`EXP_MIN`] (and −∞), e^[`EXP_MAX`] for x > [`EXP_MAX`] (and +∞),
/// NaN for NaN; otherwise within 2 ulp. Branch-free.
#[inline(always)]
pub(crate) fn exp(x: f32) -> f32 {
    // The comparisons are false for NaN, which then runs through and comes out NaN.
    let clamped = if x > EXP_MAX { EXP_MAX } else { x };
    let clamped = if clamped < EXP_MIN { EXP_MIN } else { clamped };
    let shifted = clamped * LOG2_E + ROUND;
    let n = shifted - ROUND;
    // The integer n from the low bits of `shifted` (its exponent is that of 1.5·2²³).
    let whole = (shifted.to_bits() as i32).wrapping_sub(ROUND.to_bits() as i32);
    let r = (clamped - n * LN2_HI) - n * LN2_LO;
    let p = 1.0
        + r * (1.0
            + r * (0.5
                + r * (1.0 / 6.0
                    + r * (1.0 / 24.0
                        + r * (1.0 / 120.0 + r * (1.0 / 720.0 + r * (1.0 / 5040.0)))))));
    // 2^n for n in [−126, 127] (|x| ≤ 88 gives |n| ≤ 127).
    let scale = f32::from_bits((whole.wrapping_add(127) as u32) << 23);
    let value = p * scale;
    if x < EXP_MIN {
        0.0
    } else {
        value
    }
}

#[cfg(test)]
// References in the standard library\'s maths: tests are not simulation code.
#[allow(clippy::disallowed_methods)]
mod tests {
    use super::*;

    /// Distance in units in the last place of f32 between `got` and the exact `want` (f64).
    fn ulps(got: f32, want: f64) -> f64 {
        let ulp = f64::from(f32::EPSILON) * 2f64.powi((want as f32).abs().log2().floor() as i32);
        (f64::from(got) - want).abs() / ulp
    }

    /// Against f64's `exp` (accurate to far more bits than f32 holds) at every 13th f32 in
    /// [−87, 0] (86 million arguments) and every 23rd in [0, 88]: within 2 ulp, and the
    /// largest error is printed. (f64's libm is off by under 1 ulp of f64, 2⁻²⁹ of an f32
    /// ulp.)
    #[test]
    fn matches_f64_exp_within_two_ulp() {
        let mut worst = (0.0f64, 0.0f32);
        let mut check = |x: f32| {
            let got = exp(x);
            let error = ulps(got, f64::from(x).exp());
            if error > worst.0 {
                worst = (error, x);
            }
        };
        // Every f32 from −0 down to −87: their bits run from 0x8000_0000 upward.
        let last = EXP_MIN.to_bits();
        for bits in (0x8000_0000u32..=last).step_by(13) {
            check(f32::from_bits(bits));
        }
        check(EXP_MIN);
        for bits in (0u32..=EXP_MAX.to_bits()).step_by(23) {
            check(f32::from_bits(bits));
        }
        check(EXP_MAX);
        println!("largest error {} ulp at x = {}", worst.0, worst.1);
        assert!(worst.0 <= 2.0, "{} ulp at {}", worst.0, worst.1);
    }

    /// The ends: exactly 1 at 0, exactly 0 below `EXP_MIN` and at −∞, never a subnormal, the
    /// clamp above `EXP_MAX`, NaN through.
    #[test]
    fn ends_are_exact() {
        assert_eq!(exp(0.0), 1.0);
        assert_eq!(exp(-0.0), 1.0);
        for x in [
            -87.000_01f32,
            -88.0,
            -100.0,
            -1e30,
            f32::MIN,
            f32::NEG_INFINITY,
        ] {
            assert_eq!(exp(x).to_bits(), 0, "{x}");
        }
        let smallest = exp(EXP_MIN);
        assert!(smallest.is_normal() && (f64::from(smallest) / (-87f64).exp() - 1.0).abs() < 1e-6);
        for x in [88.5f32, 1e30, f32::MAX, f32::INFINITY] {
            assert_eq!(exp(x), exp(EXP_MAX), "{x}");
        }
        assert!(exp(EXP_MAX).is_finite());
        assert!(exp(f32::NAN).is_nan());
        // Integers: e^n against f64, where the reduction leaves r small.
        for n in -87..=88 {
            let x = n as f32;
            assert!(ulps(exp(x), f64::from(x).exp()) <= 2.0, "{n}");
        }
    }
}
