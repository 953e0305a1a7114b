//! Results do not depend on the number of rayon threads: every output buffer, every field,
//! h0 and the expected variance are bit-identical in pools of 1, 2 and 3 threads.

mod common;

use common::*;
use ocean_fft::inspect;
use ocean_fft::{Cascade, CascadeConfig, Spectrum};

/// Bit patterns of everything a cascade exposes after an update, plus h0 and its expected
/// variance.
fn fingerprint(spectrum: &Spectrum, config: CascadeConfig, times: &[f64]) -> Vec<Vec<u32>> {
    let mut cascade = Cascade::new(spectrum, config).unwrap();
    let mut out = vec![
        cascade
            .h0()
            .iter()
            .flat_map(|c| [c.re.to_bits(), c.im.to_bits()])
            .collect::<Vec<u32>>(),
        {
            let bits = cascade.expected_variance().to_bits();
            vec![bits as u32, (bits >> 32) as u32]
        },
    ];
    for &t in times {
        cascade.update(t).unwrap();
        out.push(cascade.height().iter().map(|v| v.to_bits()).collect());
        out.push(cascade.jacobian().iter().map(|v| v.to_bits()).collect());
        out.push(
            cascade
                .displacement()
                .iter()
                .flat_map(|v| v.map(f32::to_bits))
                .collect(),
        );
        out.push(
            cascade
                .slope()
                .iter()
                .flat_map(|v| v.map(f32::to_bits))
                .collect(),
        );
        out.push(
            cascade
                .normal()
                .iter()
                .flat_map(|v| v.map(f32::to_bits))
                .collect(),
        );
        for field in FIELDS {
            out.push(
                inspect::field(&cascade, field)
                    .iter()
                    .map(|v| v.to_bits())
                    .collect(),
            );
        }
    }
    out
}

const NAMES: [&str; 13] = [
    "height",
    "jacobian",
    "displacement",
    "slope",
    "normal",
    "η",
    "D_x",
    "D_z",
    "η_x",
    "η_z",
    "D_xx",
    "D_zz",
    "D_xz",
];

#[test]
fn outputs_are_bit_identical_for_1_2_and_3_threads() {
    let spectra = [jonswap(0.4), phillips(-1.1)];
    let times = [0.0, 7.25, 1000.5];
    let pools: Vec<rayon::ThreadPool> = [1, 2, 3]
        .into_iter()
        .map(|threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
        })
        .collect();
    for spectrum in &spectra {
        for n in [64, 256, 24] {
            let config = CascadeConfig {
                size: n,
                length: 300.0,
                choppiness: 1.3,
                seed: 11,
                ..CascadeConfig::default()
            };
            let results: Vec<Vec<Vec<u32>>> = pools
                .iter()
                .map(|pool| pool.install(|| fingerprint(spectrum, config, &times)))
                .collect();
            // Sanity: the pools really have the sizes asked for.
            for (pool, threads) in pools.iter().zip([1, 2, 3]) {
                assert_eq!(pool.current_num_threads(), threads);
            }
            for (threads, result) in [2, 3].iter().zip(&results[1..]) {
                assert_eq!(result.len(), results[0].len());
                assert!(
                    result[0] == results[0][0],
                    "N={n}: h0 differs, {threads} threads"
                );
                assert!(
                    result[1] == results[0][1],
                    "N={n}: expected_variance differs, {threads} threads"
                );
                for (index, (a, b)) in result[2..].iter().zip(&results[0][2..]).enumerate() {
                    let (t, buffer) = (times[index / NAMES.len()], NAMES[index % NAMES.len()]);
                    let first = a.iter().zip(b).position(|(x, y)| x != y);
                    assert!(
                        first.is_none(),
                        "N={n} t={t}: {buffer} differs between 1 and {threads} threads at {first:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn cascade_can_move_to_and_be_shared_with_other_threads() {
    fn send_sync<T: Send + Sync>() {}
    send_sync::<Cascade>();
    send_sync::<CascadeConfig>();
    // Built on one thread, updated on another, read from two at once: same bits as at home.
    let spectrum = jonswap(0.4);
    let config = CascadeConfig {
        size: 32,
        length: 200.0,
        ..CascadeConfig::default()
    };
    let mut home = Cascade::new(&spectrum, config).unwrap();
    home.update(3.0).unwrap();
    let away = std::thread::spawn(move || {
        let mut cascade = Cascade::new(&spectrum, config).unwrap();
        cascade.update(3.0).unwrap();
        cascade
    })
    .join()
    .unwrap();
    std::thread::scope(|s| {
        let a = s.spawn(|| away.height().to_vec());
        let b = s.spawn(|| away.jacobian().to_vec());
        let (a, b) = (a.join().unwrap(), b.join().unwrap());
        assert!(a
            .iter()
            .zip(home.height())
            .all(|(x, y)| x.to_bits() == y.to_bits()));
        assert!(b
            .iter()
            .zip(home.jacobian())
            .all(|(x, y)| x.to_bits() == y.to_bits()));
    });
}

/// With second-order waves (their own transforms and products, in parallel rows) the default
/// ocean's buffers are the same bits on 1, 2 and 3 threads.
#[test]
fn second_order_is_bit_identical_for_1_2_and_3_threads() {
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let config = ocean_fft::OceanConfig {
                size: 128,
                second_order: true,
                ..ocean_fft::OceanConfig::default()
            };
            let mut ocean =
                ocean_fft::OceanState::new(Spectrum::jonswap(11.0, 120_000.0).unwrap(), config)
                    .unwrap();
            for _ in 0..3 {
                ocean.step(0.7).unwrap();
            }
            let c = &ocean.cascades()[0];
            let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            let flat = |v: &[[f32; 2]]| v.iter().flatten().copied().collect::<Vec<_>>();
            (bits(c.height()), bits(&flat(c.slope())))
        })
    };
    let one = run(1);
    assert!(run(2) == one && run(3) == one);
}
