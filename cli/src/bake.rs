//! `ocean-fft bake`: the simulation on this thread, the encoders on their own threads, fed
//! through a bounded channel so that frames are encoded while the next ones are simulated.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use crate::args::{BakeArgs, Format};
use crate::describe;
use crate::encode::{self, PngScale};
use crate::error::{CliError, Kind};
use crate::setup::{self, Sea};
use crate::sim::{self, LoopConvergence, Simulator, Texels};

/// Told about every file as it is written.
pub trait Progress {
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
    fn start(&mut self, _: u64) {}
    fn written(&mut self, _: &Path) {}
}

/// What a bake did, and how long it took.
#[derive(Debug, Clone, Default)]
pub struct Report {
    /// The files written, in the order they were finished.
    pub written: Vec<PathBuf>,
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

/// One cascade of one frame, to encode.
struct Job {
    paths: Vec<PathBuf>,
    cascade: usize,
    texels: Texels,
}

/// What an encoder sends back.
struct Done {
    paths: Vec<PathBuf>,
    time: Duration,
    clamped: u64,
}

/// Encodes `job` and writes its files atomically.
fn encode_job(job: &Job, format: Format, scales: &[PngScale]) -> Result<Done, CliError> {
    let start = Instant::now();
    let (files, clamped) = match format {
        Format::Exr => (vec![encode::encode_exr(&job.texels)], 0),
        Format::Png => {
            let (files, clamped) = encode::encode_png(&job.texels, scales[job.cascade])
                .map_err(|e| CliError::new(Kind::Internal, e))?;
            (files.into_iter().map(Ok).collect(), clamped)
        }
    };
    for (bytes, path) in files.into_iter().zip(&job.paths) {
        let bytes = bytes.map_err(|e| CliError::new(Kind::Internal, e))?;
        encode::write_atomic(path, &bytes)
            .map_err(|e| CliError::output(format!("writing {}: {e}", path.display())))?;
    }
    Ok(Done {
        paths: job.paths.clone(),
        time: start.elapsed(),
        clamped,
    })
}

/// Writes the sidecar unless the same one is there; refuses another bake's unless
/// `overwrite`.
fn write_sidecar(path: &Path, text: &str, overwrite: bool) -> Result<(), CliError> {
    match std::fs::read_to_string(path) {
        Ok(existing) if existing == text => return Ok(()),
        Ok(_) if !overwrite => {
            return Err(CliError::new(
                Kind::Conflict,
                format!(
                    "--out: {} describes a bake with other parameters; use another --out \
                     directory, or --overwrite to replace that bake",
                    path.display()
                ),
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
    if !(1..=256).contains(&encoders) {
        return Err(CliError::usage(format!(
            "--encoders {encoders}: expected 1 to 256 threads"
        )));
    }
    let start = Instant::now();
    std::fs::create_dir_all(&args.out)
        .map_err(|e| CliError::output(format!("--out {}: {e}", args.out.display())))?;
    let mut simulator = Simulator::new(&sea)?;
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
    for &frame in args.frames.frames() {
        let mut jobs = Vec::new();
        for c in 0..cascades {
            let paths: Vec<PathBuf> = encode::file_names(&name, args.format, c, frame)
                .into_iter()
                .map(|f| args.out.join(f))
                .collect();
            if !args.overwrite && paths.iter().all(|p| p.exists()) {
                skipped += paths.len();
            } else {
                files += paths.len() as u64;
                jobs.push((c, paths));
            }
        }
        if !jobs.is_empty() {
            plan.push((frame, jobs));
        }
    }
    progress.start(files);

    let mut report = Report {
        skipped,
        sidecar,
        encoders,
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
                let result = encode_job(&job, format, scales);
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
                let size = simulator.ocean().cascades()[*c].size();
                let mut texels = Texels::new(size);
                if let Err(e) = sim::capture(simulator.ocean(), *c, &mut texels) {
                    first_error.get_or_insert(e);
                    break 'frames;
                }
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
        "{} files written, {} skipped (existed), {} frames in {:.2} s: {:.2} frames/s; {} \
         simulation steps (pre-roll included) took {:.2} s on the main thread, encoding and \
         writing {:.2} s over {} encoder threads ({:.0} % of the busy time)",
        report.written.len(),
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
