//! Random numbers per wave vector: a small counter-based generator seeded from
//! (seed, m_x, m_z), so a wave vector's amplitude depends on nothing else — not on the grid
//! size, not on the order of generation, not on the number of threads.

use rand::RngCore;

use crate::math::determinism::{Determinism, Math};

/// SplitMix64 finaliser (Steele, Lea & Flood 2014): a bijective 64-bit mixer.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// SplitMix64 stream whose state starts from a hash of (seed, m_x, m_z).
///
/// The algorithm is fixed here (not delegated to `rand`'s unspecified `SmallRng`), so an
/// ocean's waves stay the same across versions of the dependencies.
#[derive(Debug, Clone)]
pub(crate) struct WaveRng {
    state: u64,
}

const GOLDEN: u64 = 0x9e37_79b9_7f4a_7c15;

impl WaveRng {
    /// Generator for the wave vector with integer coordinates (`m_x`, `m_z`) of a grid
    /// seeded by `seed`.
    pub(crate) fn new(seed: u64, m_x: i32, m_z: i32) -> Self {
        // Each input goes through the mixer before the next is added, so (seed, m_x, m_z)
        // triples that differ anywhere give unrelated streams.
        let mut h = mix(seed ^ GOLDEN);
        h = mix(h ^ (m_x as u32 as u64).wrapping_mul(GOLDEN));
        h = mix(h ^ (m_z as u32 as u64).wrapping_add(0x632b_e59b_d9b4_e019));
        WaveRng { state: h }
    }
}

impl RngCore for WaveRng {
    fn next_u32(&mut self) -> u32 {
        (self.next_u64() >> 32) as u32
    }

    fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(GOLDEN);
        mix(self.state)
    }

    fn fill_bytes(&mut self, dest: &mut [u8]) {
        for chunk in dest.chunks_mut(8) {
            let bytes = self.next_u64().to_le_bytes();
            chunk.copy_from_slice(&bytes[..chunk.len()]);
        }
    }
}

/// Two independent standard normal numbers (ξ_r, ξ_i) for the wave vector (`m_x`, `m_z`):
/// with [`Std`](crate::math::determinism::Std), `rand_distr`'s ziggurat (whose values a release
/// of `rand_distr` may change); with [`Libm`](crate::math::determinism::Libm), the crate's own
/// [`box_muller`], specified here down to the bit.
pub(crate) fn gaussian_pair<M: Math>(seed: u64, m_x: i32, m_z: i32) -> (f64, f64) {
    use rand_distr::{Distribution, StandardNormal};
    let mut rng = WaveRng::new(seed, m_x, m_z);
    match M::MODE {
        Determinism::SameMachine => {
            let a: f64 = StandardNormal.sample(&mut rng);
            let b: f64 = StandardNormal.sample(&mut rng);
            (a, b)
        }
        Determinism::CrossPlatform => box_muller::<M>(rng.next_u64(), rng.next_u64()),
    }
}

/// The Box–Muller transform (Box & Muller 1958) of two uniform 64-bit draws: with
/// u₁ = (⌊a/2¹¹⌋ + 1)·2⁻⁵³ in (0, 1] and u₂ = ⌊b/2¹¹⌋·2⁻⁵³ in [0, 1) (both exact in f64),
/// r = √(−2 ln u₁) and θ = 2π u₂, the pair (r cos θ, r sin θ) is two independent standard
/// normals. Every step is IEEE arithmetic or a function of `M`, so with
/// [`Libm`](crate::math::determinism::Libm) the bits are the same on every target. The largest
/// |ξ| it gives is √(2·53 ln 2) ≈ 8.57.
pub(crate) fn box_muller<M: Math>(a: u64, b: u64) -> (f64, f64) {
    const SCALE: f64 = 1.0 / (1u64 << 53) as f64;
    let u1 = ((a >> 11) + 1) as f64 * SCALE;
    let u2 = (b >> 11) as f64 * SCALE;
    let r = (-2.0 * M::ln(u1)).sqrt();
    let (sin, cos) = M::sin_cos(std::f64::consts::TAU * u2);
    (r * cos, r * sin)
}

#[cfg(test)]
// References in the standard library\'s maths: tests are not simulation code.
#[allow(clippy::disallowed_methods)]
mod tests {
    use super::*;
    use crate::math::determinism::{Libm, Std};

    #[test]
    fn streams_depend_only_on_the_triple() {
        fn check<M: Math>() {
            let g = gaussian_pair::<M>;
            assert_eq!(g(7, 3, -2), g(7, 3, -2));
            assert_ne!(g(7, 3, -2), g(7, -2, 3));
            assert_ne!(g(7, 3, -2), g(8, 3, -2));
            assert_ne!(g(7, 3, -2), g(7, -3, 2));
        }
        check::<Std>();
        check::<Libm>();
    }

    #[test]
    fn normals_have_unit_variance_and_no_correlation_between_neighbours() {
        fn check<M: Math>() {
            // 2·40 401 samples: the standard error of a variance estimate is √(2/n) ≈ 0.005,
            // so ±0.03 is six standard errors; of a correlation 1/√n ≈ 0.005, so 0.03 is six
            // too. The correlation between ξ_r and ξ_i of one wave vector (the two halves of
            // one Box–Muller pair) is checked the same way.
            let (mut sum, mut sum_sq, mut cross, mut pair, mut n) = (0.0, 0.0, 0.0, 0.0, 0.0);
            for mx in -100..=100 {
                for mz in -100..=100 {
                    let (a, b) = gaussian_pair::<M>(42, mx, mz);
                    let (c, _) = gaussian_pair::<M>(42, mx + 1, mz);
                    sum += a + b;
                    sum_sq += a * a + b * b;
                    cross += a * c;
                    pair += a * b;
                    n += 2.0;
                }
            }
            let mean = sum / n;
            let var = sum_sq / n - mean * mean;
            assert!(mean.abs() < 0.03, "{:?} mean {mean}", M::MODE);
            assert!((var - 1.0).abs() < 0.03, "{:?} variance {var}", M::MODE);
            assert!((cross / (n / 2.0)).abs() < 0.03, "neighbour correlation");
            assert!((pair / (n / 2.0)).abs() < 0.03, "pair correlation");
        }
        check::<Std>();
        check::<Libm>();
    }

    /// The crate's own Box–Muller draws follow the standard normal distribution: the
    /// Kolmogorov–Smirnov distance of 2·40 401 draws from Φ (computed independently, from
    /// libm's erfc) stays below 1.95/√n, its 0.1 % critical value; and the share beyond
    /// 3σ is the normal's 0.27 % within five binomial standard errors.
    #[test]
    fn box_muller_draws_are_standard_normal() {
        let mut draws = Vec::new();
        for mx in -100..=100 {
            for mz in -100..=100 {
                let (a, b) = gaussian_pair::<Libm>(9, mx, mz);
                draws.extend([a, b]);
            }
        }
        draws.sort_by(f64::total_cmp);
        let n = draws.len() as f64;
        let phi = |x: f64| 0.5 * libm::erfc(-x / std::f64::consts::SQRT_2);
        let distance = draws
            .iter()
            .enumerate()
            .map(|(i, &x)| {
                let p = phi(x);
                (p - i as f64 / n).abs().max(((i + 1) as f64 / n - p).abs())
            })
            .fold(0.0, f64::max);
        assert!(distance < 1.95 / n.sqrt(), "KS distance {distance}");
        let tail = draws.iter().filter(|x| x.abs() > 3.0).count() as f64 / n;
        let expected = 2.0 * phi(-3.0);
        let sigma = (expected * (1.0 - expected) / n).sqrt();
        assert!(
            (tail - expected).abs() < 5.0 * sigma,
            "tail {tail} vs {expected}"
        );
    }

    /// The transform's edges: the smallest and largest draws give finite values, u₁ = 1
    /// gives r = 0, and the quadrants of θ come out in order.
    #[test]
    fn box_muller_edges() {
        let (a, b) = box_muller::<Libm>(0, 0);
        let r = (-2.0 * (2f64).powi(-53).ln()).sqrt();
        assert!((a - r).abs() < 1e-12 && b == 0.0, "{a} {b}");
        assert_eq!(box_muller::<Libm>(u64::MAX, 1 << 62), (0.0, 0.0));
        let (x, z) = box_muller::<Libm>(0, 1 << 62); // θ = π/2
        assert!(x.abs() < 1e-12 && (z - r).abs() < 1e-12, "{x} {z}");
        let (x, z) = box_muller::<Libm>(0, u64::MAX); // θ just below 2π
        assert!((x - r).abs() < 1e-12 && z < 0.0 && z > -1e-12, "{x} {z}");
    }
}
