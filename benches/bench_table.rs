//! Regenerates docs/benchmarks.md, the one file that holds the project's measured bench
//! figures: runs the criterion benches `cascade_update`, `ocean_step`, `ocean_first_query`,
//! `ocean_query_batch` and `cascade_scaling`
//! (`cargo bench -p ocean-fft-benches`) a few rounds, reads criterion's samples, and rewrites
//! the whole file with the tables and the machine, commit and toolchain they ran on. Every
//! other document links to that file rather than quoting its numbers.
//!
//! ```sh
//! cargo run --release -p ocean-fft-benches --bin bench-table               # 3 rounds
//! cargo run --release -p ocean-fft-benches --bin bench-table -- --rounds 5
//! cargo run --release -p ocean-fft-benches --bin bench-table -- --no-run   # print the last results
//! cargo run --release -p ocean-fft-benches --bin bench-table -- --out FILE # write elsewhere
//! ```
//!
//! Every ratio is taken within one round (update and its bare FFTs measured one right after
//! the other in the same process); the table gives the median over the rounds and their
//! range, so that a shared, noisy machine shows how far to trust it.

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use ocean_fft::CascadeConfig;

const SIZES: [usize; 5] = [64, 128, 256, 512, 1024];
const LARGE_SIZES: [usize; 2] = [2048, 4096];
const THREADS: [usize; 2] = [1, 2];
/// Points per batch of `ocean_query_batch`.
const BATCHES: [usize; 4] = [100, 1_000, 10_000, 100_000];

/// What the generated file says before the tables: what it is and where the explanations are.
const HEADER: &str = "\
# Benchmarks

This file is generated: `cargo run --release -p ocean-fft-benches --bin bench-table` runs the
benches and rewrites it whole, so edit `benches/bench_table.rs` rather than this file. It holds
the measured cost of `Cascade::update` and of the default `OceanState::step` beside the bare
FFTs they cannot do without, with the machine, the commit and the toolchain of the run. What
the benches compare, the targets, what makes an update cheap and the other measurements of the
project are in [performance.md](performance.md). Timings from one machine say little about
another: measure on yours.

";

struct Options {
    rounds: usize,
    run: bool,
    scaling: bool,
    criterion: PathBuf,
    out: Option<PathBuf>,
}

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("benches/ is inside the workspace")
        .to_path_buf()
}

fn options() -> Options {
    let root = workspace();
    let target =
        std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| root.join("target"), PathBuf::from);
    let mut options = Options {
        rounds: 3,
        run: true,
        scaling: true,
        criterion: std::env::var_os("CRITERION_HOME")
            .map_or_else(|| target.join("criterion"), PathBuf::from),
        out: Some(root.join("docs/benchmarks.md")),
    };
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--rounds" => {
                options.rounds = args
                    .next()
                    .and_then(|v| v.parse().ok())
                    .filter(|&r| r > 0)
                    .expect("--rounds takes a positive integer")
            }
            "--no-run" => {
                options.run = false;
                options.rounds = 1;
                options.out = None;
            }
            "--no-scaling" => options.scaling = false,
            "--criterion-dir" => {
                options.criterion =
                    PathBuf::from(args.next().expect("--criterion-dir takes a path"))
            }
            "--out" => options.out = Some(PathBuf::from(args.next().expect("--out takes a path"))),
            other => {
                panic!("unknown argument {other:?} (see the doc comment of benches/bench_table.rs)")
            }
        }
    }
    options
}

/// `cargo bench -p ocean-fft-benches --bench BENCH -- GROUP`, its output passed through.
fn run_bench(bench: &str, group: &str) {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let status = Command::new(cargo)
        .current_dir(workspace())
        .args([
            "bench",
            "-p",
            "ocean-fft-benches",
            "--bench",
            bench,
            "--",
            group,
        ])
        .status()
        .expect("cargo bench runs");
    assert!(
        status.success(),
        "cargo bench --bench {bench} -- {group} failed"
    );
}

/// One benchmark's per-iteration times of its samples, in ns, from criterion's
/// `new/sample.json`: the median, and the minimum (the sample least disturbed by other work
/// on a shared machine).
#[derive(Debug, Clone, Copy)]
struct Estimate {
    median: f64,
    min: f64,
}

fn estimate(criterion: &Path, group: &str, function: &str, n: usize) -> Option<Estimate> {
    estimate_at(&criterion.join(group).join(function).join(n.to_string()))
}

/// [`estimate`] of a benchmark in directory `dir` (criterion's layout: `dir/new/sample.json`).
fn estimate_at(dir: &Path) -> Option<Estimate> {
    let path = dir.join("new/sample.json");
    let text = std::fs::read_to_string(&path).ok()?;
    let json: serde_json::Value = serde_json::from_str(&text).ok()?;
    let iters = json["iters"].as_array()?;
    let times = json["times"].as_array()?;
    let per_iteration: Vec<f64> = iters
        .iter()
        .zip(times)
        .filter_map(|(i, t)| Some(t.as_f64()? / i.as_f64()?))
        .collect();
    if per_iteration.is_empty() {
        return None;
    }
    Some(Estimate {
        median: median(&per_iteration),
        min: per_iteration.iter().copied().fold(f64::INFINITY, f64::min),
    })
}

/// The live sea's benches (`ocean_live`, no size parameter), each as (name, what it times).
const LIVE: [(&str, &str); 5] = [
    ("step", "a plain step"),
    (
        "set_spectrum_and_step",
        "`set_spectrum` (10 s) and the step after it",
    ),
    (
        "transition_step",
        "the mean step of a whole change (preparation and blend)",
    ),
    (
        "set_spectrum_0_and_step",
        "`set_spectrum` with duration 0 (drawn at once) and the step after it",
    ),
    ("new", "`OceanState::new`"),
];

/// The live sea's table: each bench's fastest sample per round, its median over the rounds,
/// and its ratio to the plain step of the same round; then the per-frame figures of
/// `live-frames`.
fn live(rounds: &[BTreeMap<String, Estimate>], frames: &str) -> String {
    let mut out = String::from("| bench | what | time | ÷ step |\n|---|---|---|---|\n");
    for (name, what) in LIVE {
        let times: Vec<f64> = rounds
            .iter()
            .filter_map(|r| r.get(name).map(|e| e.min))
            .collect();
        let ratios: Vec<f64> = rounds
            .iter()
            .filter_map(|r| Some(r.get(name)?.min / r.get("step")?.min))
            .collect();
        if times.is_empty() {
            continue;
        }
        out.push_str(&format!(
            "| `{name}` | {what} | {} | {:.2} |\n",
            time(median(&times)),
            median(&ratios)
        ));
    }
    out.push_str(&format!(
        "\nEvery frame of a 10 s change against a plain step, fastest of 8 runs per frame \
         (`cargo run --release -p ocean-fft-benches --bin live-frames`):\n\n```text\n{frames}\n```\n"
    ));
    out
}

/// Estimates of each (group, function, N), one per round.
type Samples = BTreeMap<(String, String, usize), Vec<Estimate>>;

fn collect(
    samples: &mut Samples,
    criterion: &Path,
    group: &str,
    functions: &[String],
    sizes: &[usize],
) {
    for function in functions {
        for &n in sizes {
            if let Some(e) = estimate(criterion, group, function, n) {
                samples
                    .entry((group.to_string(), function.clone(), n))
                    .or_default()
                    .push(e);
            }
        }
    }
}

fn median(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let mid = v.len() / 2;
    if v.len() % 2 == 1 {
        v[mid]
    } else {
        0.5 * (v[mid - 1] + v[mid])
    }
}

fn time(ns: f64) -> String {
    if ns >= 1e6 {
        format!("{:.2} ms", ns / 1e6)
    } else {
        format!("{:.0} µs", ns / 1e3)
    }
}

/// The ratio a / b of the samples' minima, "median (min–max)" over the rounds, and the
/// ratio of the medians (median over the rounds).
fn ratio(a: &[Estimate], b: &[Estimate]) -> (String, String) {
    let of_min: Vec<f64> = a.iter().zip(b).map(|(a, b)| a.min / b.min).collect();
    let of_median: Vec<f64> = a.iter().zip(b).map(|(a, b)| a.median / b.median).collect();
    let lo = of_min.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = of_min.iter().copied().fold(0.0, f64::max);
    let min = if of_min.len() > 1 {
        format!("**{:.2}** ({lo:.2}–{hi:.2})", median(&of_min))
    } else {
        format!("**{:.2}**", median(&of_min))
    };
    (min, format!("{:.2}", median(&of_median)))
}

fn fastest(values: &[Estimate]) -> f64 {
    values.iter().map(|e| e.min).fold(f64::INFINITY, f64::min)
}

fn comparison(samples: &Samples, group: &str, variant: &str, floor: &str, title: &str) -> String {
    let mut out = format!(
        "| N | threads | `{variant}` | `{floor}` | {title} | ratio of the medians |\n\
         |---|---|---|---|---|---|\n"
    );
    for n in SIZES {
        for threads in THREADS {
            let key = |f: &str| (group.to_string(), format!("{f}_{threads}t"), n);
            let (Some(a), Some(b)) = (samples.get(&key(variant)), samples.get(&key(floor))) else {
                continue;
            };
            let (of_min, of_median) = ratio(a, b);
            out += &format!(
                "| {n} | {threads} | {} | {} | {of_min} | {of_median} |\n",
                time(fastest(a)),
                time(fastest(b)),
            );
        }
    }
    out
}

/// ns a point of the batch queries, fastest sample over the rounds.
fn batches(samples: &Samples) -> String {
    let mut out = String::from(
        "| points | threads | `heights_at` ns a point | `surfaces_at` ns a point |\n|---|---|---|---|\n",
    );
    for points in BATCHES {
        for threads in THREADS {
            let per_point = |f: &str| {
                samples
                    .get(&(
                        "ocean_query_batch".to_string(),
                        format!("{f}_{threads}t"),
                        points,
                    ))
                    .map_or("—".to_string(), |e| {
                        format!("{:.0}", fastest(e) / points as f64)
                    })
            };
            out += &format!(
                "| {points} | {threads} | {} | {} |\n",
                per_point("heights_at"),
                per_point("surfaces_at")
            );
        }
    }
    out
}

fn scaling(samples: &Samples) -> String {
    let mut out = String::from(
        "| N | memory per cascade | bytes per point | `update` (2 threads) | ns per point | `four_ffts` | update ÷ four_ffts |\n\
         |---|---|---|---|---|---|---|\n",
    );
    for n in SIZES.into_iter().chain(LARGE_SIZES) {
        let (group, suffix) = if n <= 1024 {
            ("cascade_update", "_2t")
        } else {
            ("cascade_scaling", "")
        };
        let key = |f: &str| (group.to_string(), format!("{f}{suffix}"), n);
        let bytes = CascadeConfig {
            size: n,
            ..CascadeConfig::default()
        }
        .memory_bytes();
        let points = (n * n) as f64;
        let mib = bytes as f64 / (1024.0 * 1024.0);
        let (update, ffts, per_point, r) =
            match (samples.get(&key("update")), samples.get(&key("four_ffts"))) {
                (Some(a), Some(b)) => (
                    time(fastest(a)),
                    time(fastest(b)),
                    format!("{:.1}", fastest(a) / points),
                    ratio(a, b).0,
                ),
                _ => ("—".into(), "—".into(), "—".into(), "—".into()),
            };
        out += &format!(
            "| {n} | {mib:.1} MiB | {:.1} | {update} | {per_point} | {ffts} | {r} |\n",
            bytes as f64 / points
        );
    }
    out
}

fn command_output(program: &str, args: &[&str]) -> String {
    Command::new(program)
        .args(args)
        .current_dir(workspace())
        .output()
        .ok()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_else(|| "?".into())
}

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "?".into())
}

fn main() {
    let options = options();
    let load_before = load_average();
    let mut samples = Samples::new();
    let cascade_functions: Vec<String> = ["update", "four_ffts"]
        .iter()
        .flat_map(|f| THREADS.iter().map(move |t| format!("{f}_{t}t")))
        .collect();
    let step_functions: Vec<String> = ["step", "twelve_ffts"]
        .iter()
        .flat_map(|f| THREADS.iter().map(move |t| format!("{f}_{t}t")))
        .collect();
    let scaling_functions = vec!["update".to_string(), "four_ffts".to_string()];
    let first_query_functions: Vec<String> = ["step", "step_and_height_at"]
        .iter()
        .flat_map(|f| THREADS.iter().map(move |t| format!("{f}_{t}t")))
        .collect();
    let batch_functions: Vec<String> = ["heights_at", "surfaces_at"]
        .iter()
        .flat_map(|f| THREADS.iter().map(move |t| format!("{f}_{t}t")))
        .collect();
    let mut live_rounds = Vec::new();
    for round in 0..options.rounds {
        if options.run {
            eprintln!("== round {} of {}", round + 1, options.rounds);
            run_bench("cascade", "cascade_update");
            run_bench("ocean", "ocean_step");
            run_bench("ocean", "ocean_live");
            run_bench("ocean", "ocean_first_query");
            run_bench("ocean", "ocean_query_batch");
        }
        live_rounds.push(
            LIVE.iter()
                .filter_map(|(name, _)| {
                    let dir = options.criterion.join("ocean_live").join(name);
                    Some((name.to_string(), estimate_at(&dir)?))
                })
                .collect::<BTreeMap<_, _>>(),
        );
        collect(
            &mut samples,
            &options.criterion,
            "cascade_update",
            &cascade_functions,
            &SIZES,
        );
        collect(
            &mut samples,
            &options.criterion,
            "ocean_step",
            &step_functions,
            &SIZES,
        );
        collect(
            &mut samples,
            &options.criterion,
            "ocean_first_query",
            &first_query_functions,
            &SIZES,
        );
        collect(
            &mut samples,
            &options.criterion,
            "ocean_query_batch",
            &batch_functions,
            &BATCHES,
        );
    }
    if options.run && options.scaling {
        run_bench("cascade", "cascade_scaling");
    }
    collect(
        &mut samples,
        &options.criterion,
        "cascade_scaling",
        &scaling_functions,
        &LARGE_SIZES,
    );
    let frames = if options.run {
        command_output(
            std::env::var("CARGO").as_deref().unwrap_or("cargo"),
            &[
                "run",
                "--quiet",
                "--release",
                "-p",
                "ocean-fft-benches",
                "--bin",
                "live-frames",
            ],
        )
    } else {
        String::from("(not run: --no-run)")
    };
    let load_after = load_average();

    let rounds = options.rounds;
    let table = format!(
        "Generated by `cargo run --release -p ocean-fft-benches --bin bench-table` on {date}, \
         commit `{commit}`, {rustc}.\n\
         Machine: {machine}. Load average (1, 5, 15 min) {load_before} before and {load_after} after.\n\
         Times are the fastest of criterion's samples (per iteration; on a shared machine the \
         least disturbed), over {rounds} round(s). A ratio is taken within one round (the variant \
         and its floor measured one right after the other) from the samples' minima, and shown as \
         the median over the rounds with their range in brackets; the last column gives the \
         ratio of the samples' medians, which other work on the machine inflates.\n\n\
         ## `Cascade::update` ÷ its four bare packed FFTs (`cascade_update`, a 500 m cascade \
         over the whole band; target ≤ 1.3)\n\n{update}\n\
         ## Default `OceanState::step` ÷ the twelve bare FFTs of its three cascades \
         (`ocean_step`; target ≤ 1.2)\n\n{step}\n\
         ## Time and memory per cascade (`cascade_update` at 2 threads and `cascade_scaling`; \
         memory from `CascadeConfig::memory_bytes`)\n\n{scaling}\n\
         ## A change of weather on the default ocean at 256², one thread (`ocean_live`)\n\n{live}\n\
         ## A step and the first `height_at` after it ÷ the step alone (`ocean_first_query`, the \
         default ocean; target ≤ 1.1)\n\n{first_query}\n\
         ## Batch queries of points scattered over 2 km × 2 km, default ocean at 256² \
         (`ocean_query_batch`)\n\n{batches}",
        date = command_output("date", &["-u", "+%Y-%m-%d %H:%M UTC"]),
        commit = command_output("git", &["rev-parse", "--short", "HEAD"]),
        rustc = command_output("rustc", &["--version"]),
        machine = common::machine(),
        update = comparison(&samples, "cascade_update", "update", "four_ffts", "update ÷ four_ffts"),
        step = comparison(&samples, "ocean_step", "step", "twelve_ffts", "step ÷ twelve_ffts"),
        scaling = scaling(&samples),
        live = live(&live_rounds, &frames),
        first_query = comparison(
            &samples,
            "ocean_first_query",
            "step_and_height_at",
            "step",
            "(step + height_at) ÷ step"
        ),
        batches = batches(&samples),
    );
    match options.out {
        None => println!("{table}"),
        Some(path) => {
            std::fs::write(&path, format!("{HEADER}{table}")).expect("the output file is writable");
            println!("{table}");
            eprintln!("wrote {}", path.display());
        }
    }
}
