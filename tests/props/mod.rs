//! What the property tests share: proptest's configuration with a fixed seed, so that CI sees
//! the same inputs on every run.

use proptest::test_runner::{Config, RngSeed};

/// A configuration of `cases` cases per property (unless `PROPTEST_CASES` says otherwise),
/// drawn from the fixed `seed`, persisting no failures (a failure is turned into a named
/// regression test instead).
pub fn config(cases: u32, seed: u64) -> Config {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|value| value.parse().ok())
        .unwrap_or(cases);
    Config {
        cases,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        ..Config::default()
    }
}
