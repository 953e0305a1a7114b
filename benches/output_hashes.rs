//! Prints a hash of every output buffer of a few cascades and oceans, updated at several
//! times in rayon pools of 1, 2 and 3 threads: one line per (configuration, threads, time,
//! buffer). For checking that a change to the update's internals (pruning, SIMD, buffer
//! layout) leaves every bit of every output as it was:
//!
//! ```sh
//! cargo run --release -p ocean-fft-benches --bin output-hashes > before.txt
//! # ... change the code ...
//! cargo run --release -p ocean-fft-benches --bin output-hashes > after.txt
//! diff before.txt after.txt
//! ```
//!
//! The hashes depend on the CPU (rustfft picks its own SIMD path) and on the Rust version, so
//! none is committed: compare two runs on the same machine.

use ocean_fft::inspect;
use ocean_fft::inspect::{BitHash, Field};
use ocean_fft::{Cascade, CascadeConfig, OceanConfig, OceanState, Spectrum, Spreading};

/// The crate's own bit hash of the values whose bit patterns are `bits` (the same as the
/// golden tests use).
fn hash_bits(bits: impl IntoIterator<Item = u32>) -> u64 {
    let mut hash = BitHash::new();
    for b in bits {
        hash.bytes(&b.to_le_bytes());
    }
    hash.finish()
}

fn flat<const K: usize>(values: &[[f32; K]]) -> impl Iterator<Item = u32> + '_ {
    values.iter().flat_map(|v| v.iter().map(|x| x.to_bits()))
}

/// Every buffer a cascade exposes, hashed.
fn cascade_lines(cascade: &Cascade) -> Vec<(String, u64)> {
    let mut lines = vec![
        (
            "height".to_string(),
            hash_bits(cascade.height().iter().map(|v| v.to_bits())),
        ),
        (
            "displacement".to_string(),
            hash_bits(flat(cascade.displacement())),
        ),
        ("slope".to_string(), hash_bits(flat(cascade.slope()))),
        ("normal".to_string(), hash_bits(flat(cascade.normal()))),
        (
            "jacobian".to_string(),
            hash_bits(cascade.jacobian().iter().map(|v| v.to_bits())),
        ),
    ];
    for field in Field::ALL {
        lines.push((
            format!("field {field:?}"),
            hash_bits(inspect::field(cascade, field).iter().map(|v| v.to_bits())),
        ));
    }
    for transform in 0..4 {
        let packed = inspect::packed_transform(cascade, transform).expect("transform < 4");
        lines.push((
            format!("packed {transform}"),
            hash_bits(packed.iter().flat_map(|c| [c.re.to_bits(), c.im.to_bits()])),
        ));
    }
    lines
}

fn cascade_configs() -> Vec<(String, Spectrum, CascadeConfig, Vec<f64>)> {
    let jonswap = Spectrum::jonswap(12.0, 200_000.0).expect("valid spectrum");
    let phillips = Spectrum::phillips(9.0, 3e-4)
        .expect("valid spectrum")
        .with_wind_direction(-1.1)
        .expect("valid direction");
    let spread = Spectrum::jonswap(8.0, 50_000.0)
        .expect("valid spectrum")
        .with_wind_direction(0.4)
        .expect("valid direction")
        .with_spreading(Spreading::DonelanBanner)
        .expect("valid spreading");
    let times = vec![0.0, 7.25, 1000.5, -3.0];
    let mut out = Vec::new();
    for n in [6, 34, 64, 128, 256, 512, 1024] {
        out.push((
            format!("cascade jonswap full band N={n}"),
            jonswap.clone(),
            CascadeConfig {
                size: n,
                length: 500.0,
                seed: 7,
                ..CascadeConfig::default()
            },
            times.clone(),
        ));
    }
    for n in [34, 64, 256] {
        // A band like the default ocean's middle cascade: both limits inside the grid.
        let length = 230.0;
        let nyquist = std::f32::consts::PI * n as f32 / length;
        out.push((
            format!("cascade phillips banded N={n}"),
            phillips.clone(),
            CascadeConfig {
                size: n,
                length,
                k_min: 0.11 * nyquist,
                k_max: 0.5 * nyquist,
                choppiness: 1.7,
                seed: 3,
                ..CascadeConfig::default()
            },
            times.clone(),
        ));
        out.push((
            format!("cascade spread looping low band N={n}"),
            spread.clone(),
            CascadeConfig {
                size: n,
                length: 800.0,
                k_max: 0.3 * std::f32::consts::PI * n as f32 / 800.0,
                repeat_period: Some(12.0),
                seed: 11,
                ..CascadeConfig::default()
            },
            times.clone(),
        ));
    }
    out
}

fn ocean_configs() -> Vec<(String, Spectrum, OceanConfig)> {
    let jonswap = Spectrum::jonswap(10.0, 100_000.0).expect("valid spectrum");
    let mut out = Vec::new();
    for size in [64, 256] {
        for parallel_cascades in [false, true] {
            out.push((
                format!("ocean default N={size} parallel={parallel_cascades}"),
                jonswap.clone(),
                OceanConfig {
                    size,
                    parallel_cascades,
                    ..OceanConfig::default()
                },
            ));
        }
    }
    out.push((
        "ocean two cascades N=128 split 0.3".to_string(),
        jonswap,
        OceanConfig {
            size: 128,
            lengths: vec![600.0, 90.0],
            band_split: 0.3,
            choppiness: 1.4,
            ..OceanConfig::default()
        },
    ));
    out
}

fn main() {
    let pools: Vec<(usize, rayon::ThreadPool)> = [1, 2, 3]
        .into_iter()
        .map(|threads| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("thread pool");
            (threads, pool)
        })
        .collect();
    for (name, spectrum, config, times) in cascade_configs() {
        for (threads, pool) in &pools {
            pool.install(|| {
                let mut cascade = Cascade::new(&spectrum, config).expect("valid cascade");
                for &t in &times {
                    cascade.update(t).expect("valid time");
                    for (buffer, hash) in cascade_lines(&cascade) {
                        println!("{name} | threads {threads} | t {t} | {buffer} | {hash:016x}");
                    }
                }
            });
        }
    }
    for (name, spectrum, config) in ocean_configs() {
        for (threads, pool) in &pools {
            pool.install(|| {
                let mut ocean = OceanState::new(spectrum.clone(), config.clone()).expect("ocean");
                for step in 0..4 {
                    ocean.step(0.4).expect("valid step");
                    let t = ocean.time();
                    for (index, cascade) in ocean.cascades().iter().enumerate() {
                        for (buffer, hash) in cascade_lines(cascade) {
                            println!(
                                "{name} | threads {threads} | step {step} t {t} | cascade {index} {buffer} | {hash:016x}"
                            );
                        }
                    }
                    for (buffer, values) in [
                        ("foam", ocean.foam_view().total()),
                        ("active", ocean.foam_view().active()),
                        ("residual", ocean.foam_view().residual()),
                        ("breaking", ocean.foam_view().breaking()),
                    ] {
                        let hash = hash_bits(values.iter().map(|v| v.to_bits()));
                        println!(
                            "{name} | threads {threads} | step {step} t {t} | foam {buffer} | {hash:016x}"
                        );
                    }
                }
            });
        }
    }
}
