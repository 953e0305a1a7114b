//! Every frame of a change of weather against a plain step, in one process: the default ocean
//! (three 256² cascades) on one thread changes from the default breeze to a gale from another
//! direction over 10 s at 60 fps, eight times over (each run from the same state); for every
//! frame of the change its fastest time over the runs is divided by the fastest plain step of
//! the same ocean measured between the runs. Fastest-of-runs takes out what other work on the
//! machine adds, frame by frame.
//!
//! `cargo run --release -p ocean-fft-benches --bin live-frames`; prints the CPU, the plain
//! step, `set_spectrum`'s own cost, and the largest, 99th percentile and mean frame ratio,
//! with the frames of the preparation and the blend apart.

mod common;

use std::time::Instant;

use ocean_fft::{OceanConfig, OceanState, Spectrum};

fn main() {
    println!("{}", common::machine());
    let pool = common::pool(1);
    let breeze = Spectrum::jonswap(10.0, 100_000.0).expect("valid spectrum");
    let gale = Spectrum::jonswap(18.0, 300_000.0)
        .and_then(|s| s.with_wind_direction(1.0))
        .expect("valid spectrum");
    let dt = 1.0 / 60.0;
    pool.install(|| {
        let mut base = OceanState::new(breeze.clone(), OceanConfig::default()).expect("ocean");
        // A first change, so that the change's buffers exist (as in a game after its first).
        base.set_spectrum(gale.clone(), 0.0).expect("change");
        base.step(dt).expect("step");
        base.set_spectrum(breeze.clone(), 0.0).expect("change");
        base.step(dt).expect("step");
        let mut plain = f64::INFINITY;
        let mut set = f64::INFINITY;
        let mut frames: Vec<f64> = Vec::new();
        let mut prepared = usize::MAX;
        for _run in 0..8 {
            let mut ocean = base.clone();
            for _ in 0..20 {
                let t = Instant::now();
                ocean.step(dt).expect("step");
                plain = plain.min(t.elapsed().as_secs_f64());
            }
            let t = Instant::now();
            ocean.set_spectrum(gale.clone(), 10.0).expect("change");
            set = set.min(t.elapsed().as_secs_f64());
            let mut k = 0;
            while ocean.diagnostics().transition_progress().is_some() {
                let t = Instant::now();
                ocean.step(dt).expect("step");
                let e = t.elapsed().as_secs_f64();
                if k == frames.len() {
                    frames.push(e);
                } else {
                    frames[k] = frames[k].min(e);
                }
                if ocean.diagnostics().transition_progress() > Some(0.0) {
                    prepared = prepared.min(k);
                }
                k += 1;
            }
        }
        let ratios: Vec<f64> = frames.iter().map(|f| f / plain).collect();
        let report = |name: &str, r: &[f64]| {
            let mut sorted = r.to_vec();
            sorted.sort_by(f64::total_cmp);
            let mean = r.iter().sum::<f64>() / r.len() as f64;
            println!(
                "{name}: {} frames, largest {:.2}, 99th percentile {:.2}, mean {:.2} (× a plain step)",
                r.len(),
                sorted[sorted.len() - 1],
                sorted[(sorted.len() * 99 / 100).min(sorted.len() - 1)],
                mean
            );
        };
        println!(
            "plain step {:.3} ms; set_spectrum {:.3} ms ({:.2} × a step)",
            plain * 1e3,
            set * 1e3,
            set / plain
        );
        if std::env::var_os("LIVE_FRAMES_ALL").is_some() {
            let all: Vec<String> = ratios[..prepared].iter().map(|r| format!("{r:.2}")).collect();
            println!("preparation frames: {}", all.join(" "));
            let first: Vec<String> = ratios[prepared..]
                .iter()
                .take(10)
                .map(|r| format!("{r:.2}"))
                .collect();
            println!("first blend frames: {}", first.join(" "));
            let (largest, ratio) = ratios[prepared..]
                .iter()
                .enumerate()
                .max_by(|a, b| a.1.total_cmp(b.1))
                .expect("a blend");
            println!("largest blend frame: {largest} ({ratio:.2})");
        }
        report("preparation", &ratios[..prepared]);
        report("blend", &ratios[prepared..]);
        report("whole change", &ratios);
    });
}
