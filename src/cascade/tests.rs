//! Every SIMD level of the element loops gives the same bits as the baseline build, at every
//! thread count, for cascades over the whole band and pruned ones.

use super::{Cascade, CascadeConfig};
use crate::inspect::Field;
use crate::math::simd::Simd;
use crate::spectrum::{Spectrum, Spreading};

/// The bit patterns of every buffer a cascade exposes after updates at `times`.
fn fingerprint(cascade: &mut Cascade, times: &[f64]) -> Vec<Vec<u32>> {
    let mut out = Vec::new();
    for &t in times {
        cascade.update(t).unwrap();
        out.push(cascade.height().iter().map(|v| v.to_bits()).collect());
        out.push(cascade.jacobian().iter().map(|v| v.to_bits()).collect());
        out.push(
            cascade
                .displacement()
                .iter()
                .flatten()
                .map(|v| v.to_bits())
                .collect(),
        );
        out.push(
            cascade
                .slope()
                .iter()
                .flatten()
                .map(|v| v.to_bits())
                .collect(),
        );
        out.push(
            cascade
                .normal()
                .iter()
                .flatten()
                .map(|v| v.to_bits())
                .collect(),
        );
        for field in Field::ALL {
            out.push(cascade.field(field).iter().map(|v| v.to_bits()).collect());
        }
    }
    out
}

fn configs() -> Vec<(Spectrum, CascadeConfig)> {
    let jonswap = Spectrum::jonswap(12.0, 200_000.0).unwrap();
    let phillips = Spectrum::phillips(9.0, 3e-4)
        .unwrap()
        .with_wind_direction(-1.1)
        .unwrap()
        .with_spreading(Spreading::DonelanBanner)
        .unwrap();
    let full = |size| CascadeConfig {
        size,
        length: 500.0,
        choppiness: 1.3,
        seed: 7,
        ..CascadeConfig::default()
    };
    // A band like the default ocean's larger cascades: up to half the Nyquist wave number,
    // so band pruning skips row pairs, evolution blocks and gather tiles.
    let banded = |size: usize| {
        let length = 230.0;
        let nyquist = std::f32::consts::PI * size as f32 / length;
        CascadeConfig {
            size,
            length,
            k_min: 0.11 * nyquist,
            k_max: 0.5 * nyquist,
            repeat_period: Some(9.0),
            seed: 3,
            ..CascadeConfig::default()
        }
    };
    vec![
        (jonswap.clone(), full(34)),
        (jonswap.clone(), full(128)),
        (phillips.clone(), full(256)),
        // Above `STRAIGHT_MAX` (src/cascade/evolve.rs), where the evolution stages a block's
        // values on the stack; not a power of two, so its last block starts early.
        (jonswap.clone(), full(300)),
        (jonswap, banded(64)),
        (phillips, banded(256)),
    ]
}

#[test]
fn every_simd_level_and_thread_count_gives_the_same_bits() {
    let levels = Simd::available();
    // On a CPU with AVX-512 (as the project's machines) the test must cover all three
    // levels, or it would pass vacuously.
    #[cfg(target_arch = "x86_64")]
    {
        let avx2 = std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma");
        let avx512 = std::is_x86_feature_detected!("avx512f")
            && std::is_x86_feature_detected!("avx512bw")
            && std::is_x86_feature_detected!("avx512cd")
            && std::is_x86_feature_detected!("avx512dq")
            && std::is_x86_feature_detected!("avx512vl");
        let expected = 1 + usize::from(avx2) + usize::from(avx2 && avx512);
        assert_eq!(levels.len(), expected, "levels {levels:?}");
    }
    println!("SIMD levels: {levels:?}");
    let pools = crate::math::simd::test_pools();
    let times = [0.0, 7.25, 1000.5];
    for (spectrum, config) in configs() {
        let mut reference = Cascade::new(&spectrum, config).unwrap();
        reference.set_simd(Simd::Baseline { fused: true });
        let expected = pools[0].1.install(|| fingerprint(&mut reference, &times));
        for &level in &levels {
            for (threads, pool) in &pools {
                let mut cascade = Cascade::new(&spectrum, config).unwrap();
                cascade.set_simd(level);
                let got = pool.install(|| fingerprint(&mut cascade, &times));
                assert!(
                    got == expected,
                    "N = {}, band {}..{}: {level:?} with {threads} threads differs from the \
                     baseline build with 1 thread",
                    config.size,
                    config.k_min,
                    config.k_max
                );
            }
        }
    }
}
