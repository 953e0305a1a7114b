//! `Cascade::update` allocates nothing after a warm-up update: a counting global allocator
//! (every thread, rayon's workers included) must not move across 20 updates.
//!
//! One #[test] only, so that no other test of this binary allocates concurrently while the
//! counter is read; the harness's main thread only waits for the test meanwhile.
//!
//! What rayon itself does (investigated with backtraces from this allocator, rayon-core 1.13,
//! crossbeam-deque 0.8.8):
//! - A freshly built pool's worker threads allocate their own state (a `JobFifo` injector
//!   block, a crossbeam-epoch handle on their first steal) whenever they first get to run,
//!   asynchronously — so the warm-up below makes every worker run (`broadcast`) and lets the
//!   pools settle (200 ms) before anything is measured.
//! - A parallel call made from a thread *outside* the pool is injected into the pool's global
//!   `crossbeam_deque::Injector`, which allocates a new 63-slot block (and frees the old one)
//!   every 63 injections. A cascade update hands rayon one job, a scope holding both passes
//!   (measured: 5 blocks of 1520 B in 323 updates, net growth 0), so on the global pool,
//!   called from the main thread, an update allocates 1/63 of a 1.5 KB block on average:
//!   rayon's queue, not the crate, and no net growth. Inside `ThreadPool::install` every call
//!   is made from a worker and nothing is injected: there the count is exactly zero.

mod counting;

use counting::{count, live, start_recording, stop_recording};
use ocean_fft::{Cascade, CascadeConfig, Spectrum};

#[global_allocator]
static GLOBAL: counting::Counting = counting::Counting;

/// Allocations made by `updates` updates of `cascade` after a few warm-up updates.
fn allocations_during_updates(cascade: &mut Cascade, updates: usize) -> usize {
    for step in 0..3 {
        cascade.update(0.5 + f64::from(step)).unwrap();
    }
    let before = count();
    for step in 0..updates {
        cascade.update(10.0 + step as f64 * 0.033).unwrap();
    }
    count() - before
}

#[test]
fn update_allocates_nothing_after_warm_up() {
    let spectrum = Spectrum::jonswap(10.0, 100_000.0).unwrap();
    // The counter itself works: a Vec allocates once.
    let before = count();
    let v = std::hint::black_box(vec![1u8; 100]);
    assert_eq!(count() - before, 1);
    drop(v);

    // The dedicated pools live to the end: a dropped pool's threads exit in the background and
    // allocate while doing so (crossbeam-epoch flushes its thread-local garbage; seen as a
    // 2072-byte allocation), which this process-wide counter would see during a later
    // measurement.
    // Every worker of these pools and of the global one runs once and settles before
    // anything is counted (without that, the set-up of a late-starting worker occasionally
    // landed in a measurement: 2 allocations).
    let pools = counting::warm_pools(&[1, 2, 3]);

    for n in [64, 256] {
        let config = CascadeConfig {
            size: n,
            length: 500.0,
            ..CascadeConfig::default()
        };
        let mut cascade = Cascade::new(&spectrum, config).unwrap();

        // The crate's promise, strictly: inside a pool (1, 2 and 3 threads) after warm-up,
        // 20 updates allocate nothing at all.
        for (pool, threads) in pools.iter().zip([1, 2, 3]) {
            let installed = pool.install(|| allocations_during_updates(&mut cascade, 20));
            println!("N={n}: {installed} allocations in 20 updates inside a {threads}-thread pool");
            assert_eq!(
                installed, 0,
                "N={n}: update allocated inside a {threads}-thread pool"
            );
        }

        // On rayon's global pool, called from this (non-pool) thread, as a game's main loop
        // would: 20 updates, then 320 for the amortised behaviour described above.
        let global = allocations_during_updates(&mut cascade, 20);
        println!("N={n}: {global} allocations in 20 updates on the global pool");
        let live_before = live();
        start_recording();
        let many = allocations_during_updates(&mut cascade, 320);
        let (lo, hi) = stop_recording();
        let growth = live() - live_before;
        println!(
            "N={n}: {many} allocations in 323 updates on the global pool (sizes {lo}..={hi} B), \
             net live bytes {growth}"
        );
        // At most one injector block per 63 injections, and `update` hands rayon one job
        // (a scope holding both passes): ≤ 323/63 + 1 = 6. All of one block size, and the
        // old block is freed as the new one is made, so nothing accumulates (≤ 1 block).
        assert!(global <= 2, "N={n}: {global} allocations in 20 updates");
        assert!(many <= 6, "N={n}: {many} allocations in 323 updates");
        if many > 0 {
            assert_eq!(
                lo, hi,
                "N={n}: allocations of different sizes: not only rayon's injector"
            );
            assert!(growth <= hi as isize, "N={n}: memory grew by {growth} B");
        }
    }

    // `CascadeConfig::memory_bytes` against what a cascade really keeps: the live bytes the
    // allocator counts across `Cascade::new` (everything it allocated and did not free).
    // The formula leaves out the FFT plans' twiddle tables and a few small vectors, so the
    // live bytes may exceed it by a little, never fall below it.
    for n in [64, 256, 1024] {
        let config = CascadeConfig {
            size: n,
            length: 500.0,
            ..CascadeConfig::default()
        };
        let expected = config.memory_bytes();
        let before = live();
        let cascade = pools[0].install(|| Cascade::new(&spectrum, config).unwrap());
        let live = (live() - before) as usize;
        drop(cascade);
        println!("N={n}: memory_bytes {expected}, live after Cascade::new {live}");
        // Twiddles of a length-N plan are a few N complex values: 64 N bytes is ample.
        assert!(
            live >= expected && live <= expected + 64 * n + 4096,
            "N={n}: memory_bytes says {expected} B, the cascade holds {live} B"
        );
    }
}
