//! A counting global allocator for the allocation tests (tests/alloc.rs, ocean_alloc.rs,
//! gpu_alloc.rs): it sees every allocation of every thread, rayon's workers included. A test
//! binary installs it with
//! `#[global_allocator] static GLOBAL: counting::Counting = counting::Counting;`
//! and keeps to one `#[test]` that counts, so that no other test allocates meanwhile.

#![allow(dead_code)] // each test binary uses part of it

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicIsize, AtomicUsize, Ordering};

/// The allocator: `System`'s, counting.
pub struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);
/// Bytes currently allocated (allocations minus deallocations).
static LIVE: AtomicIsize = AtomicIsize::new(0);
/// While set, the smallest and largest allocation sizes are recorded.
static RECORD: AtomicBool = AtomicBool::new(false);
static MIN_SIZE: AtomicUsize = AtomicUsize::new(usize::MAX);
static MAX_SIZE: AtomicUsize = AtomicUsize::new(0);

fn note(size: usize) {
    ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
    LIVE.fetch_add(size as isize, Ordering::SeqCst);
    if RECORD.load(Ordering::SeqCst) {
        MIN_SIZE.fetch_min(size, Ordering::SeqCst);
        MAX_SIZE.fetch_max(size, Ordering::SeqCst);
    }
}

// SAFETY: every method forwards to `System` with the caller's own arguments; the counting
// touches only atomics.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note(layout.size());
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note(layout.size());
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note(new_size);
        LIVE.fetch_sub(layout.size() as isize, Ordering::SeqCst);
        unsafe { System.realloc(ptr, layout, new_size) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size() as isize, Ordering::SeqCst);
        unsafe { System.dealloc(ptr, layout) }
    }
}

/// Allocations (and reallocations) so far.
pub fn count() -> usize {
    ALLOCATIONS.load(Ordering::SeqCst)
}

/// Bytes allocated now.
pub fn live() -> isize {
    LIVE.load(Ordering::SeqCst)
}

/// Starts recording the smallest and largest allocation sizes afresh.
pub fn start_recording() {
    MIN_SIZE.store(usize::MAX, Ordering::SeqCst);
    MAX_SIZE.store(0, Ordering::SeqCst);
    RECORD.store(true, Ordering::SeqCst);
}

/// Stops recording; the smallest and largest sizes seen since `start_recording`.
pub fn stop_recording() -> (usize, usize) {
    RECORD.store(false, Ordering::SeqCst);
    (
        MIN_SIZE.load(Ordering::SeqCst),
        MAX_SIZE.load(Ordering::SeqCst),
    )
}

/// Rayon pools of these many threads, warmed up: every worker's one-time set-up happens when
/// it first runs, asynchronously, so each pool (and the global one) runs a job on every
/// worker and they are given time to settle before anything is counted.
pub fn warm_pools(threads: &[usize]) -> Vec<rayon::ThreadPool> {
    let pools: Vec<rayon::ThreadPool> = threads
        .iter()
        .map(|&threads| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("a thread pool");
            pool.broadcast(|_| ());
            pool
        })
        .collect();
    rayon::broadcast(|_| ());
    std::thread::sleep(std::time::Duration::from_millis(200));
    pools
}
