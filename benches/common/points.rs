//! The scattered points of the query benches, also read by `scripts/ab_queries.sh`'s
//! harness (std only, so that it can be included by path).

/// `count` world points scattered uniformly over a 2 km square (a fixed linear congruential
/// sequence, so every run and every version measured sees the same points).
pub fn scattered(count: usize) -> Vec<[f64; 2]> {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..count)
        .map(|_| [next() * 2000.0 - 1000.0, next() * 2000.0 - 1000.0])
        .collect()
}
