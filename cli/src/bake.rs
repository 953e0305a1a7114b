//! `ocean-fft bake`: the simulation on this thread, the encoders on their own threads, fed
//! through a bounded channel so that frames are encoded while the next ones are simulated.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use half::f16;
use serde_json::Value;

use crate::args::{self, BakeArgs, Format, ENCODERS_RANGE};
use crate::describe;
use crate::encode::{self, PngScale};
use crate::error::{CliError, Kind};
use crate::setup::{self, Sea};
use crate::sim::{LoopConvergence, Simulator, Texels};
use crate::warnings;

/// Told what the bake is about to do, and about every file as it is written.
pub trait Progress {
    /// A warning or a notice for the user, before the bake starts (default: a line on
    /// stderr).
    fn note(&mut self, text: &str) {
        eprintln!("{text}");
    }
    /// The number of files the bake will write (after skipping existing ones).
    fn start(&mut self, files: u64);
    /// One file is on disk under its final name.
    fn written(&mut self, path: &Path);
    /// The bake is over (successfully or not).
    fn finish(&mut self) {}
}

/// No output (tests).
pub struct Silent;

impl Progress for Silent {
    fn note(&mut self, _: &str) {}
    fn start(&mut self, _: u64) {}
    fn written(&mut self, _: &Path) {}
}

/// What a bake did, and how long it took.
#[derive(Debug, Clone, Default)]
pub struct Report {
    /// The files written, in the order they were finished.
    pub written: Vec<PathBuf>,
    /// Their bytes.
    pub bytes: u64,
    /// The bound on those bytes announced before the bake (see [`disk_size`]).
    pub bound: u64,
    /// Files that existed and were skipped.
    pub skipped: usize,
    /// The sidecar's path.
    pub sidecar: PathBuf,
    /// Frames simulated and captured (at least one file written).
    pub frames: usize,
    /// Simulation steps, pre-roll included.
    pub steps: u64,
    /// Wall-clock time of the whole bake, from the ocean's construction.
    pub wall: Duration,
    /// Time the simulation thread spent simulating and copying the channels.
    pub simulate: Duration,
    /// Time the encoder threads spent encoding and writing, summed over the threads.
    pub encode: Duration,
    /// Encoder threads.
    pub encoders: usize,
    /// Values clamped to the PNG scales (always 0 for EXR).
    pub clamped: u64,
    /// The loop's foam convergence, for a loop.
    pub convergence: Option<LoopConvergence>,
}

/// The files of one cascade to write at a frame: (cascade, paths).
type CascadeFiles = (usize, Vec<PathBuf>);

/// One cascade of one frame as the library packed it: f16 for EXR, f32 for PNG.
enum Captured {
    Exr(Texels<f16>),
    Png(Texels<f32>),
}

impl Captured {
    /// Packs cascade `cascade` of `ocean` for `format`.
    fn new(
        format: Format,
        ocean: &ocean_fft::OceanState,
        cascade: usize,
    ) -> Result<Captured, CliError> {
        let size = ocean.cascades()[cascade].size();
        Ok(match format {
            Format::Exr => {
                let mut texels = Texels::new(size);
                texels.capture(ocean, cascade)?;
                Captured::Exr(texels)
            }
            Format::Png => {
                let mut texels = Texels::new(size);
                texels.capture(ocean, cascade)?;
                Captured::Png(texels)
            }
        })
    }
}

/// One cascade of one frame, to encode.
struct Job {
    paths: Vec<PathBuf>,
    cascade: usize,
    texels: Captured,
}

/// What an encoder sends back.
struct Done {
    paths: Vec<PathBuf>,
    bytes: u64,
    time: Duration,
    clamped: u64,
}

/// Encodes `job` and writes its files atomically.
fn encode_job(job: &Job, scales: &[PngScale]) -> Result<Done, CliError> {
    let start = Instant::now();
    let internal = |e: String| CliError::new(Kind::Internal, e);
    let (files, clamped) = match &job.texels {
        Captured::Exr(texels) => (vec![encode::encode_exr(texels).map_err(internal)?], 0),
        Captured::Png(texels) => {
            encode::encode_png(texels, scales[job.cascade]).map_err(internal)?
        }
    };
    let mut written = 0;
    for (bytes, path) in files.into_iter().zip(&job.paths) {
        encode::write_atomic(path, &bytes)
            .map_err(|e| CliError::output(format!("writing {}: {e}", path.display())))?;
        written += bytes.len() as u64;
    }
    Ok(Done {
        paths: job.paths.clone(),
        bytes: written,
        time: start.elapsed(),
        clamped,
    })
}

/// The uncompressed pixel bytes of one file of an N×N cascade: 8 half floats a texel for
/// EXR, 4 16-bit values a texel and a filter byte a row for each PNG.
pub fn file_raw(format: Format, size: usize) -> u64 {
    let pixels = (size * size) as u64;
    match format {
        Format::Exr => 16 * pixels,
        Format::Png => 8 * pixels + size as u64,
    }
}

/// An upper bound on the bytes of one file of an N×N cascade: [`file_raw`] plus 1/64 of it
/// and 1 KiB for headers, offset tables and the worst case of compression (ZIP and PNG's
/// deflate store data they cannot shrink, at a few bytes per block).
pub fn file_bound(format: Format, size: usize) -> u64 {
    let raw = file_raw(format, size);
    raw + raw / 64 + 1024
}

/// The share of [`file_raw`] a file typically takes: ZIP and deflate compress the presets'
/// frames to 68–74 % (EXR) and 84–90 % (PNG) of it at 64² to 512² (calm, fresh breeze,
/// storm and swell, frames with foam).
pub fn typical_share(format: Format) -> f64 {
    match format {
        Format::Exr => 0.72,
        Format::Png => 0.88,
    }
}

/// The bytes of the files a bake writes, `count` files of each N×N cascade in `files`:
/// (typical, at most) by [`typical_share`] and [`file_bound`].
pub fn disk_size(format: Format, files: &[(usize, u64)]) -> (u64, u64) {
    let sum = |f: &dyn Fn(usize) -> f64| -> u64 {
        files
            .iter()
            .map(|&(size, count)| (count as f64 * f(size)) as u64)
            .sum()
    };
    (
        sum(&|size| file_raw(format, size) as f64 * typical_share(format)),
        sum(&|size| file_bound(format, size) as f64),
    )
}

/// Bytes in binary units: "755.0 MiB".
pub fn bytes_text(bytes: u64) -> String {
    let units = ["bytes", "KiB", "MiB", "GiB", "TiB"];
    let mut value = bytes as f64;
    let mut unit = 0;
    while value >= 1024.0 && unit + 1 < units.len() {
        value /= 1024.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{bytes} bytes")
    } else {
        format!("{value:.1} {}", units[unit])
    }
}

/// The sidecar fields that the options set (a prefix of a field's path), with the option, in
/// the order a conflict lists them. The other fields (H_s, the cascades' bands, the channel
/// table, …) follow from these.
const PARAMETERS: [(&str, &str); 17] = [
    ("version", "the ocean-fft version"),
    ("spectrum.wind_speed", "--wind"),
    ("spectrum.fetch", "--fetch"),
    ("spectrum.dispersion", "--depth"),
    ("spectrum.depth_factor", "--depth"),
    ("spectrum.wind_direction", "--direction-deg"),
    ("spectrum", "the spectrum (--preset or --config)"),
    ("config.size", "--size"),
    ("config.lengths", "--lengths"),
    ("config.choppiness", "--choppiness"),
    ("config.seed", "--seed"),
    ("config.repeat_period", "--loop"),
    ("config", "the config (--preset or --config)"),
    ("fps", "--fps"),
    ("files.encoding.format", "--format"),
    ("foam_preroll.tolerance", "--foam-tolerance"),
    ("foam_preroll.anchor_every_frames", "--anchor-every"),
];

/// The index in [`PARAMETERS`] of the option that sets the field at `path`.
fn parameter_of(path: &str) -> Option<usize> {
    PARAMETERS.iter().position(|(prefix, _)| {
        path == *prefix
            || path
                .strip_prefix(prefix)
                .is_some_and(|rest| rest.starts_with(['.', '[']))
    })
}

/// The leaves where two JSON values differ: (path, old, new). Arrays of other lengths are
/// one leaf.
fn differing(path: &str, old: &Value, new: &Value, out: &mut Vec<(String, String, String)>) {
    let join = |key: &str| {
        if path.is_empty() {
            key.to_string()
        } else {
            format!("{path}.{key}")
        }
    };
    match (old, new) {
        (Value::Object(a), Value::Object(b)) => {
            let mut keys: Vec<&String> = a.keys().chain(b.keys()).collect();
            keys.sort();
            keys.dedup();
            for key in keys {
                let (x, y) = (
                    a.get(key).unwrap_or(&Value::Null),
                    b.get(key).unwrap_or(&Value::Null),
                );
                differing(&join(key), x, y, out);
            }
        }
        (Value::Array(a), Value::Array(b)) if a.len() == b.len() => {
            for (i, (x, y)) in a.iter().zip(b).enumerate() {
                differing(&format!("{path}[{i}]"), x, y, out);
            }
        }
        _ if old != new => out.push((path.to_string(), old.to_string(), new.to_string())),
        _ => {}
    }
}

/// What differs between the sidecar in `--out` (`existing`) and this bake's (`text`): each
/// option behind a difference, with its field's values there and here.
pub fn conflict_message(path: &Path, existing: &str, text: &str) -> String {
    let head = format!(
        "--out: {} describes a bake with other parameters",
        path.display()
    );
    let tail = "use another --out directory, or --overwrite to replace that bake";
    let (Ok(old), Ok(new)) = (
        serde_json::from_str::<Value>(existing),
        serde_json::from_str::<Value>(text),
    ) else {
        return format!("{head} (it is not a sidecar JSON); {tail}");
    };
    let mut all = Vec::new();
    differing("", &old, &new, &mut all);
    // The first differing field of each option.
    let mut by_option: Vec<Option<&(String, String, String)>> = vec![None; PARAMETERS.len()];
    for difference in &all {
        if let Some(i) = parameter_of(&difference.0) {
            by_option[i].get_or_insert(difference);
        }
    }
    let index = |prefix: &str| {
        PARAMETERS
            .iter()
            .position(|(p, _)| *p == prefix)
            .expect("listed")
    };
    // What another difference explains: a changed wind, fetch or depth rebuilds the
    // spectrum's model, and a loop drops the anchors.
    if (index("spectrum.wind_speed")..index("spectrum")).any(|i| by_option[i].is_some()) {
        by_option[index("spectrum")] = None;
    }
    if by_option[index("config.repeat_period")].is_some() {
        by_option[index("foam_preroll.anchor_every_frames")] = None;
    }
    let mut parts: Vec<String> = by_option
        .iter()
        .enumerate()
        .filter_map(|(i, d)| d.map(|d| (i, d)))
        .map(|(i, (field, there, here))| {
            format!(
                "{} ({field} is {there} there, {here} here)",
                PARAMETERS[i].1
            )
        })
        .collect();
    if parts.is_empty() {
        // No option explains it (a hand-edited sidecar): the first fields that differ.
        parts = all
            .iter()
            .take(3)
            .map(|(field, there, here)| format!("{field} is {there} there, {here} here"))
            .collect();
    }
    format!("{head}: {}; {tail}", parts.join(", "))
}

/// Writes the sidecar unless the same one is there; refuses another bake's unless
/// `overwrite`, naming the parameters that differ.
fn write_sidecar(path: &Path, text: &str, overwrite: bool) -> Result<(), CliError> {
    match std::fs::read_to_string(path) {
        Ok(existing) if existing == text => return Ok(()),
        Ok(existing) if !overwrite => {
            return Err(CliError::new(
                Kind::Conflict,
                conflict_message(path, &existing, text),
            ))
        }
        _ => {}
    }
    encode::write_atomic(path, text.as_bytes())
        .map_err(|e| CliError::output(format!("writing {}: {e}", path.display())))
}

/// Runs a bake.
///
/// # Errors
/// A [`CliError`] whose kind gives the exit code: bad arguments, a bad config, an output
/// failure, or an output directory holding another bake.
pub fn bake(args: &BakeArgs, progress: &mut dyn Progress) -> Result<Report, CliError> {
    let sea = setup::build(&args.sea)?;
    let name = args.name.clone().unwrap_or_else(|| sea.name.clone());
    if name.is_empty() || name.contains(['/', '\\']) || name.starts_with('.') {
        return Err(CliError::usage(format!(
            "--name {name:?}: expected a file-name base without slashes, not starting with a dot"
        )));
    }
    let encoders = args
        .encoders
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(2, |n| n.get()));
    if !(ENCODERS_RANGE.0..=ENCODERS_RANGE.1).contains(&encoders) {
        return Err(CliError::usage(format!(
            "--encoders {encoders}: expected {}",
            args::range_text(ENCODERS_RANGE.0, ENCODERS_RANGE.1)
        )));
    }
    let start = Instant::now();
    std::fs::create_dir_all(&args.out)
        .map_err(|e| CliError::output(format!("--out {}: {e}", args.out.display())))?;
    let mut simulator = Simulator::new(&sea)?;
    for warning in warnings::check(&sea, simulator.ocean()) {
        progress.note(&warning.to_string());
    }
    let scales = encode::png_scales(simulator.ocean());
    let sea_named = Sea {
        name: name.clone(),
        ..sea.clone()
    };
    let text = describe::sidecar(&sea_named, args.format, simulator.ocean(), &scales);
    let sidecar = args.out.join(format!("{name}.json"));
    write_sidecar(&sidecar, &text, args.overwrite)?;

    // What to write: every cascade of every frame, less the files that exist.
    let cascades = simulator.ocean().cascades().len();
    let mut plan: Vec<(u32, Vec<CascadeFiles>)> = Vec::new();
    let mut skipped = 0;
    let mut files = 0u64;
    // Files to write per cascade, for the disk bound.
    let mut per_cascade = vec![0u64; cascades];
    for &frame in args.frames.frames() {
        let mut jobs = Vec::new();
        for (c, count) in per_cascade.iter_mut().enumerate() {
            let paths: Vec<PathBuf> = encode::file_names(&name, args.format, c, frame)
                .into_iter()
                .map(|f| args.out.join(f))
                .collect();
            if !args.overwrite && paths.iter().all(|p| p.exists()) {
                skipped += paths.len();
            } else {
                files += paths.len() as u64;
                *count += paths.len() as u64;
                jobs.push((c, paths));
            }
        }
        if !jobs.is_empty() {
            plan.push((frame, jobs));
        }
    }
    let sizes: Vec<(usize, u64)> = simulator
        .ocean()
        .cascades()
        .iter()
        .zip(&per_cascade)
        .map(|(cascade, &count)| (cascade.size(), count))
        .collect();
    let (typical, bound) = disk_size(args.format, &sizes);
    progress.note(&format!(
        "bake: {files} files ({} frames × {cascades} cascades{}) into {}: about {} (at most {} \
         uncompressed)",
        plan.len(),
        if skipped > 0 {
            format!("; {skipped} existing files skipped")
        } else {
            String::new()
        },
        args.out.display(),
        bytes_text(typical),
        bytes_text(bound),
    ));
    progress.start(files);

    let mut report = Report {
        skipped,
        sidecar,
        encoders,
        bound,
        ..Report::default()
    };
    let (job_tx, job_rx) = mpsc::sync_channel::<Job>(encoders);
    let job_rx = Mutex::new(job_rx);
    let (done_tx, done_rx) = mpsc::channel::<Result<Done, CliError>>();
    let failed = AtomicBool::new(false);
    let format = args.format;
    let mut first_error: Option<CliError> = None;

    std::thread::scope(|scope| {
        for _ in 0..encoders {
            let (job_rx, done_tx, failed, scales) = (&job_rx, done_tx.clone(), &failed, &scales);
            scope.spawn(move || loop {
                let job = job_rx.lock().expect("no encoder panics").recv();
                let Ok(job) = job else { break };
                if failed.load(Ordering::Relaxed) {
                    continue;
                }
                let result = encode_job(&job, scales);
                if result.is_err() {
                    failed.store(true, Ordering::Relaxed);
                }
                if done_tx.send(result).is_err() {
                    break;
                }
            });
        }
        drop(done_tx);
        let mut collect =
            |result: Result<Done, CliError>,
             report: &mut Report,
             first_error: &mut Option<CliError>| match result {
                Ok(done) => {
                    for path in &done.paths {
                        progress.written(path);
                    }
                    report.encode += done.time;
                    report.bytes += done.bytes;
                    report.clamped += done.clamped;
                    report.written.extend(done.paths);
                }
                Err(e) => {
                    first_error.get_or_insert(e);
                }
            };
        'frames: for (frame, jobs) in &plan {
            let t = Instant::now();
            if let Err(e) = simulator.advance_to(*frame) {
                first_error.get_or_insert(e);
                break;
            }
            let mut captured = Vec::with_capacity(jobs.len());
            for (c, paths) in jobs {
                let texels = match Captured::new(format, simulator.ocean(), *c) {
                    Ok(texels) => texels,
                    Err(e) => {
                        first_error.get_or_insert(e);
                        break 'frames;
                    }
                };
                captured.push(Job {
                    paths: paths.clone(),
                    cascade: *c,
                    texels,
                });
            }
            report.simulate += t.elapsed();
            report.frames += 1;
            for job in captured {
                if job_tx.send(job).is_err() {
                    break 'frames;
                }
            }
            while let Ok(result) = done_rx.try_recv() {
                collect(result, &mut report, &mut first_error);
            }
            if failed.load(Ordering::Relaxed) {
                break;
            }
        }
        drop(job_tx);
        for result in done_rx.iter() {
            collect(result, &mut report, &mut first_error);
        }
    });
    progress.finish();
    report.steps = simulator.steps;
    report.convergence = simulator.convergence();
    report.wall = start.elapsed();
    match first_error {
        Some(e) => Err(e),
        None => Ok(report),
    }
}

/// The summary printed after a bake (to stderr).
pub fn summary(report: &Report) -> String {
    let wall = report.wall.as_secs_f64();
    let simulate = report.simulate.as_secs_f64();
    let encode = report.encode.as_secs_f64();
    let mut s = format!(
        "{} files written ({}), {} skipped (existed), {} frames in {:.2} s: {:.2} frames/s; {} \
         simulation steps (pre-roll included) took {:.2} s on the main thread, encoding and \
         writing {:.2} s over {} encoder threads ({:.0} % of the busy time)",
        report.written.len(),
        bytes_text(report.bytes),
        report.skipped,
        report.frames,
        wall,
        report.frames as f64 / wall.max(1e-9),
        report.steps,
        simulate,
        encode,
        report.encoders,
        100.0 * encode / (encode + simulate).max(1e-9),
    );
    if let Some(c) = report.convergence {
        s += &format!(
            "\nloop foam: steady after {} loops (last change {:.2e}; seam ≤ {:.2e})",
            c.loops, c.last_change, c.seam_bound
        );
    }
    if report.clamped > 0 {
        s += &format!(
            "\nwarning: {} values lay beyond the PNG scales and were clamped",
            report.clamped
        );
    }
    s
}
