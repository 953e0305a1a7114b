//! What the benches share: the machine they ran on, printed first, and rayon pools of a
//! given size to run a variant in.

#![allow(dead_code)]

/// The CPU model, family and model numbers, logical CPU count and the widest SIMD extension
/// the CPU reports, on one line (from /proc/cpuinfo on Linux; "unknown" elsewhere).
pub fn machine() -> String {
    let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let field = |name: &str| {
        cpuinfo
            .lines()
            .find(|line| line.split(':').next().map(str::trim) == Some(name))
            .and_then(|line| line.split_once(':'))
            .map(|(_, value)| value.trim().to_string())
    };
    let model = field("model name").unwrap_or_else(|| "unknown CPU".to_string());
    let family = field("cpu family").unwrap_or_else(|| "?".to_string());
    let number = field("model").unwrap_or_else(|| "?".to_string());
    let cpus = std::thread::available_parallelism().map_or(0, usize::from);
    format!(
        "{model} (family {family}, model {number}), {cpus} logical CPUs, {}",
        simd()
    )
}

/// The widest x86 SIMD extension the CPU reports at run time.
fn simd() -> &'static str {
    #[cfg(target_arch = "x86_64")]
    {
        if std::is_x86_feature_detected!("avx512f") {
            return "AVX-512";
        }
        if std::is_x86_feature_detected!("avx2") {
            return "AVX2";
        }
        "SSE2"
    }
    #[cfg(not(target_arch = "x86_64"))]
    "no x86 SIMD"
}

/// Prints the machine line before any measurement, so that every bench log names its CPU.
pub fn print_machine() {
    println!("machine: {}", machine());
}

/// A rayon pool of `threads` workers whose threads have all started (their one-time set-up
/// is not measured).
pub fn pool(threads: usize) -> rayon::ThreadPool {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool");
    pool.broadcast(|_| ());
    pool
}
