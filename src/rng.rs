//! Random numbers per wave vector: a small counter-based generator seeded from
//! (seed, m_x, m_z), so a wave vector's amplitude depends on nothing else — not on the grid
//! size, not on the order of generation, not on the number of threads.

use rand::RngCore;

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

/// Two independent standard normal numbers (ξ_r, ξ_i) for the wave vector (`m_x`, `m_z`).
pub(crate) fn gaussian_pair(seed: u64, m_x: i32, m_z: i32) -> (f64, f64) {
    use rand_distr::{Distribution, StandardNormal};
    let mut rng = WaveRng::new(seed, m_x, m_z);
    let a: f64 = StandardNormal.sample(&mut rng);
    let b: f64 = StandardNormal.sample(&mut rng);
    (a, b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_depend_only_on_the_triple() {
        assert_eq!(gaussian_pair(7, 3, -2), gaussian_pair(7, 3, -2));
        assert_ne!(gaussian_pair(7, 3, -2), gaussian_pair(7, -2, 3));
        assert_ne!(gaussian_pair(7, 3, -2), gaussian_pair(8, 3, -2));
        assert_ne!(gaussian_pair(7, 3, -2), gaussian_pair(7, -3, 2));
    }

    #[test]
    fn normals_have_unit_variance_and_no_correlation_between_neighbours() {
        // 2·40 401 samples: the standard error of a variance estimate is √(2/n) ≈ 0.005, so
        // ±0.03 is six standard errors; of a correlation 1/√n ≈ 0.005, so 0.03 is six too.
        let (mut sum, mut sum_sq, mut cross, mut n) = (0.0, 0.0, 0.0, 0.0);
        for mx in -100..=100 {
            for mz in -100..=100 {
                let (a, b) = gaussian_pair(42, mx, mz);
                let (c, _) = gaussian_pair(42, mx + 1, mz);
                sum += a + b;
                sum_sq += a * a + b * b;
                cross += a * c;
                n += 2.0;
            }
        }
        let mean = sum / n;
        let var = sum_sq / n - mean * mean;
        assert!(mean.abs() < 0.03, "mean {mean}");
        assert!((var - 1.0).abs() < 0.03, "variance {var}");
        assert!((cross / (n / 2.0)).abs() < 0.03, "neighbour correlation");
    }
}
