//! The simulation thread: it owns the [`OceanState`], steps it, packs every cascade into
//! RGBA16F texels with their mipmaps, and answers the frame's CPU queries, while the render
//! thread draws the previous frame.
//!
//! Two [`Frame`]s circulate between the threads: the render thread uploads one while the
//! simulation fills the other, so step n + 1 runs while frame n renders. Once both exist the
//! loop allocates nothing: the frames keep their buffers, the channels are bounded (their
//! slots are allocated once), and every step, pack and query runs inside the thread's own
//! rayon pool (called from outside a pool, rayon's job queue would allocate a block every 63
//! calls). Only a change of sea allocates (a new ocean).

use std::sync::mpsc::{sync_channel, Receiver, SyncSender};
use std::thread::JoinHandle;
use std::time::Instant;

use ocean_fft::gpu::TexelLayout;
use ocean_fft::half::f16;
use ocean_fft::half::slice::HalfFloatSliceExt;
use ocean_fft::{Error, FoamConfig, OceanConfig, OceanState, Spectrum, SurfaceSample};
use rayon::prelude::*;

/// Most cascades the shader takes.
pub const MAX_CASCADES: usize = 8;
/// Entries of the unresolved slope-variance table.
pub const SLOPE_TABLE: usize = 32;
/// Seconds of foam spin-up after a rebuild (steps of [`PRE_ROLL_DT`]).
pub const PRE_ROLL_ON_CHANGE: f64 = 6.0;
/// Time step of the foam's spin-up, s.
pub const PRE_ROLL_DT: f64 = 0.1;

/// A change of sea, applied by the simulation thread before its next step.
#[derive(Debug, Clone)]
pub enum SeaChange {
    /// New weather over `duration` seconds of simulated time ([`change_sea`]).
    Spectrum { spectrum: Spectrum, duration: f64 },
    /// A new configuration (cascade lengths, size, seed, foam): a new ocean at the same time.
    Rebuild {
        spectrum: Spectrum,
        config: OceanConfig,
    },
    /// A new choppiness, taking effect at the next step.
    Choppiness(f32),
    /// New foam settings, live (`OceanState::set_foam_config`).
    Foam(FoamConfig),
}

/// Every sea-state change of the viewer goes through here: new weather `spectrum` reached
/// over `duration` seconds of simulated time with the ocean's live change
/// (`OceanState::set_spectrum`: every wave's phase and the foam kept). A new water depth,
/// which the live change refuses, takes the rebuild path: a new ocean at the same time; so
/// does a sea the grids cannot hold (`Error::SeaDoesNotFit`), on grids fitted to it
/// (`OceanConfig::with_fitted_lengths`).
///
/// # Errors
/// The crate's, for a spectrum the ocean refuses; nothing changes then.
pub fn change_sea(ocean: &mut OceanState, spectrum: Spectrum, duration: f64) -> Result<(), Error> {
    match ocean.set_spectrum(spectrum.clone(), duration) {
        Err(Error::NotApplicable {
            name: "spectrum.dispersion",
            ..
        }) => {
            let config = ocean.config().clone();
            rebuild(ocean, spectrum, config)
        }
        Err(Error::SeaDoesNotFit { .. }) => {
            let config = ocean.config().clone().with_fitted_lengths(&spectrum)?;
            rebuild(ocean, spectrum, config)
        }
        other => other,
    }
}

/// A new ocean of `spectrum` and `config` at the time of `ocean`, its foam spun up over
/// [`PRE_ROLL_ON_CHANGE`] seconds; the path for new grids and for a new depth, which the live
/// change refuses.
///
/// # Errors
/// The crate's; nothing changes then.
pub fn rebuild(
    ocean: &mut OceanState,
    spectrum: Spectrum,
    config: OceanConfig,
) -> Result<(), Error> {
    let time = ocean.time();
    let mut fresh = OceanState::new(spectrum, config)?;
    fresh.set_time(time)?;
    fresh.pre_roll(PRE_ROLL_ON_CHANGE.min(time.max(PRE_ROLL_DT)), PRE_ROLL_DT)?;
    *ocean = fresh;
    Ok(())
}

/// What the shader needs to know about the ocean besides its textures.
#[derive(Debug, Clone, Copy, Default)]
pub struct OceanInfo {
    /// Sea time of the frame, s.
    pub time: f64,
    /// Cascades, their sides L (m) and grid size N.
    pub cascades: usize,
    pub lengths: [f32; MAX_CASCADES],
    pub size: usize,
    /// Mip levels of every layer.
    pub mip_levels: usize,
    /// Unit wind (x, z).
    pub wind: [f32; 2],
    /// Sub-grid slope variance along and across the wind (the finest cascade's).
    pub subgrid: [f32; 2],
    /// Standard deviation of the summed height (m) and of the summed J − 1.
    pub height_sd: f32,
    pub jacobian_sd: f32,
    /// Wave numbers k_i (rad/m, geometric) and the slope variance (along, across) of the
    /// simulated waves above each.
    pub slope_table: [[f32; 3]; SLOPE_TABLE],
    /// Significant wave height (m) and peak wavelength (m) of the spectrum.
    pub significant_wave_height: f32,
    pub peak_wavelength: f32,
    /// Foam coverage over the sea (active + residual, area fraction).
    pub foam_total: f32,
    /// Incremented by every rebuild (the textures' size may have changed).
    pub generation: u64,
}

/// Timings of the simulation's share of a frame, ms.
#[derive(Debug, Clone, Copy, Default)]
pub struct SimTimes {
    pub step: f64,
    /// Packing the texels, their mipmaps and the f16 conversion.
    pub pack: f64,
    pub query: f64,
    /// A change of sea applied before the step (0 on most frames).
    pub change: f64,
}

/// One frame's data, passed back and forth between the threads.
pub struct Frame {
    /// Every cascade's `DisplacementFoam` and `SlopeJacobianFoam` texels with their mip
    /// chains: layer c's level m starts at `c * layer_len + level_offsets[m]`.
    pub displacement: Vec<[f16; 4]>,
    pub slope: Vec<[f16; 4]>,
    pub layer_len: usize,
    pub level_offsets: Vec<usize>,
    /// f32 packing scratch: one layer's mip chain.
    scratch: Vec<[f32; 4]>,
    /// The world points (x, z) to query after the step, and their surfaces.
    pub queries: Vec<[f64; 2]>,
    pub samples: Vec<SurfaceSample>,
    pub info: OceanInfo,
    pub times: SimTimes,
    /// The last error of a change of sea, if any (shown by the panel).
    pub error: Option<String>,
}

impl Frame {
    fn new(queries: usize) -> Frame {
        Frame {
            displacement: Vec::new(),
            slope: Vec::new(),
            layer_len: 0,
            level_offsets: Vec::new(),
            scratch: Vec::new(),
            queries: vec![[0.0; 2]; queries],
            samples: vec![SurfaceSample::default(); queries],
            info: OceanInfo::default(),
            times: SimTimes::default(),
            error: None,
        }
    }

    /// Sizes the buffers for `ocean` (allocates only when its size or cascades changed).
    fn fit(&mut self, ocean: &OceanState) {
        let n = ocean.config().size;
        let cascades = ocean.cascades().len();
        let levels = mip_levels(n);
        let layer_len: usize = (0..levels).map(|m| (n >> m) * (n >> m)).sum();
        let same = self.level_offsets.len() == levels
            && self.layer_len == layer_len
            && self.displacement.len() == layer_len * cascades;
        if !same {
            self.level_offsets = (0..levels)
                .map(|m| (0..m).map(|k| (n >> k) * (n >> k)).sum())
                .collect();
            self.layer_len = layer_len;
            self.displacement = vec![[f16::ZERO; 4]; layer_len * cascades];
            self.slope = vec![[f16::ZERO; 4]; layer_len * cascades];
            self.scratch = vec![[0.0; 4]; layer_len];
        }
    }
}

/// Mip levels of an N×N texture whose levels halve while the side is even.
pub fn mip_levels(n: usize) -> usize {
    (n.trailing_zeros() as usize + 1).min(13)
}

/// Averages level `m − 1` of a mip chain (side `2·side`) into level m (side `side`), 2×2 box.
fn downsample(source: &[[f32; 4]], target: &mut [[f32; 4]], side: usize) {
    let wide = 2 * side;
    let rows_per_block = (4096 / side).max(1);
    target
        .par_chunks_mut(rows_per_block * side)
        .enumerate()
        .for_each(|(block, rows)| {
            for (r, row) in rows.chunks_mut(side).enumerate() {
                let j = block * rows_per_block + r;
                let (top, bottom) = (&source[2 * j * wide..], &source[(2 * j + 1) * wide..]);
                for (i, texel) in row.iter_mut().enumerate() {
                    let (a, b, c, d) =
                        (top[2 * i], top[2 * i + 1], bottom[2 * i], bottom[2 * i + 1]);
                    for k in 0..4 {
                        texel[k] = 0.25 * (a[k] + b[k] + c[k] + d[k]);
                    }
                }
            }
        });
}

impl Frame {
    /// Packs every cascade of `ocean` with its mipmaps into the f16 buffers.
    fn pack(&mut self, ocean: &OceanState) -> Result<(), Error> {
        let n = ocean.config().size;
        let layouts = [
            TexelLayout::DisplacementFoam,
            TexelLayout::SlopeJacobianFoam,
        ];
        let mut jacobian_variance = 0.0f64;
        for c in 0..ocean.cascades().len() {
            for layout in layouts {
                let chain = &mut self.scratch;
                ocean.pack_texels(c, layout, &mut chain[..n * n])?;
                if layout == TexelLayout::SlopeJacobianFoam {
                    jacobian_variance += variance_of_channel(&chain[..n * n], 2);
                }
                for m in 1..self.level_offsets.len() {
                    let side = n >> m;
                    let (done, rest) = chain.split_at_mut(self.level_offsets[m]);
                    let source = &done[self.level_offsets[m - 1]..];
                    downsample(source, &mut rest[..side * side], side);
                }
                let out = match layout {
                    TexelLayout::DisplacementFoam => &mut self.displacement,
                    _ => &mut self.slope,
                };
                let layer = &mut out[c * self.layer_len..(c + 1) * self.layer_len];
                layer
                    .par_chunks_mut(4096)
                    .zip(chain.par_chunks(4096))
                    .for_each(|(half, full)| {
                        half.as_flattened_mut()
                            .convert_from_f32_slice(full.as_flattened());
                    });
            }
        }
        self.info.jacobian_sd = jacobian_variance.sqrt() as f32;
        Ok(())
    }
}

/// Variance of channel `k` of `texels` (sums in f64, in order; on the calling thread, so
/// that nothing is allocated: about 0.1 ms for 256²).
fn variance_of_channel(texels: &[[f32; 4]], k: usize) -> f64 {
    let (sum, sum2) = texels.iter().fold((0.0f64, 0.0f64), |(s, s2), t| {
        let v = f64::from(t[k]);
        (s + v, s2 + v * v)
    });
    let count = texels.len() as f64;
    let mean = sum / count;
    (sum2 / count - mean * mean).max(0.0)
}

/// The parts of [`OceanInfo`] that change only with the ocean (on a rebuild or a change of
/// choppiness).
fn static_info(ocean: &OceanState, info: &mut OceanInfo) -> Result<(), Error> {
    let config = ocean.config();
    info.cascades = ocean.cascades().len().min(MAX_CASCADES);
    info.lengths = [0.0; MAX_CASCADES];
    for (length, cascade) in info.lengths.iter_mut().zip(ocean.cascades()) {
        *length = cascade.length();
    }
    info.size = config.size;
    info.mip_levels = mip_levels(config.size);
    let spectrum = ocean.spectrum();
    info.wind = spectrum.wind_vector();
    let subgrid = ocean.subgrid_slope_variance();
    info.subgrid = [subgrid.along, subgrid.across];
    info.height_sd = ocean.expected_variance().sqrt() as f32;
    info.significant_wave_height = spectrum.significant_wave_height();
    let peak_k = spectrum.peak_omega().powi(2) / ocean_fft::GRAVITY;
    info.peak_wavelength = std::f32::consts::TAU / peak_k;
    let bands = config.bands()?;
    let (bottom, top) = (bands[0].0.max(1e-3), bands[bands.len() - 1].1);
    for (i, entry) in info.slope_table.iter_mut().enumerate() {
        let k = bottom * (top / bottom).powf(i as f32 / (SLOPE_TABLE - 1) as f32);
        let v = spectrum.slope_variance(k, top);
        *entry = [k, v.along, v.across];
    }
    Ok(())
}

/// A request from the render thread: step by `dt` (after `change`, if any) into `frame`.
struct Request {
    dt: f64,
    change: Option<SeaChange>,
    frame: Box<Frame>,
}

/// The render thread's handle on the simulation thread.
pub struct Simulation {
    requests: SyncSender<Option<Request>>,
    results: Receiver<Box<Frame>>,
    /// The frame the render thread holds (uploaded, to be sent back with the next request).
    spare: Option<Box<Frame>>,
    thread: Option<JoinHandle<()>>,
}

impl Simulation {
    /// Builds the ocean at `time` with its foam spun up over `pre_roll` seconds, on a thread
    /// of its own with a rayon pool of `threads` threads, and starts the first step (frame 0
    /// at `time`). `queries` is the number of world points queried every frame.
    ///
    /// # Errors
    /// The crate's for the spectrum and config; a message if a thread cannot start.
    pub fn start(
        spectrum: Spectrum,
        config: OceanConfig,
        time: f64,
        pre_roll: f64,
        threads: usize,
        queries: usize,
    ) -> Result<Simulation, String> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .thread_name(|i| format!("ocean-sim-{i}"))
            .build()
            .map_err(|e| format!("rayon pool: {e}"))?;
        let mut ocean = pool
            .install(|| -> Result<OceanState, Error> {
                let mut ocean = OceanState::new(spectrum, config)?;
                ocean.set_time(time)?;
                if pre_roll > 0.0 {
                    ocean.pre_roll(pre_roll.min(time.max(PRE_ROLL_DT)), PRE_ROLL_DT)?;
                }
                Ok(ocean)
            })
            .map_err(|e| e.to_string())?;
        let mut first = Box::new(Frame::new(queries));
        let second = Box::new(Frame::new(queries));
        let mut info = OceanInfo::default();
        pool.install(|| -> Result<(), Error> {
            static_info(&ocean, &mut info)?;
            first.fit(&ocean);
            first.info = info;
            first.pack(&ocean)?;
            first.info.time = ocean.time();
            Ok(())
        })
        .map_err(|e| e.to_string())?;
        let (request_tx, request_rx) = sync_channel::<Option<Request>>(1);
        let (result_tx, result_rx) = sync_channel::<Box<Frame>>(2);
        result_tx.send(first).map_err(|e| e.to_string())?;
        let thread = std::thread::Builder::new()
            .name("ocean-sim".into())
            .spawn(move || {
                let mut info = info;
                while let Ok(Some(request)) = request_rx.recv() {
                    let frame = pool.install(|| serve(&mut ocean, &mut info, request));
                    if result_tx.send(frame).is_err() {
                        break;
                    }
                }
            })
            .map_err(|e| format!("simulation thread: {e}"))?;
        Ok(Simulation {
            requests: request_tx,
            results: result_rx,
            spare: Some(second),
            thread: Some(thread),
        })
    }

    /// Waits for the next stepped frame, then at once asks for the one after it (a step of
    /// `dt` seconds after `change`, queries at `queries`), so that it is computed while the
    /// caller uploads and draws the frame returned. The caller gives the frame back with
    /// [`Simulation::give_back`] once uploaded.
    pub fn next(
        &mut self,
        dt: f64,
        change: Option<SeaChange>,
        queries: &[[f64; 2]],
    ) -> Result<Box<Frame>, String> {
        let ready = self
            .results
            .recv()
            .map_err(|_| "the simulation thread stopped".to_string())?;
        let mut spare = self.spare.take().ok_or("no frame to fill")?;
        spare.queries.copy_from_slice(queries);
        self.requests
            .send(Some(Request {
                dt,
                change,
                frame: spare,
            }))
            .map_err(|_| "the simulation thread stopped".to_string())?;
        Ok(ready)
    }

    /// Returns an uploaded frame, to be filled again.
    pub fn give_back(&mut self, frame: Box<Frame>) {
        self.spare = Some(frame);
    }
}

impl Drop for Simulation {
    fn drop(&mut self) {
        let _ = self.requests.send(None);
        // Unblock a thread waiting to hand back a result.
        while self.results.try_recv().is_ok() {}
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

/// One request on the simulation thread: the change, the step, the pack and the queries.
fn serve(ocean: &mut OceanState, info: &mut OceanInfo, request: Request) -> Box<Frame> {
    let Request {
        dt,
        change,
        mut frame,
    } = request;
    frame.times = SimTimes::default();
    if let Some(change) = change {
        let start = Instant::now();
        let result = match change {
            SeaChange::Spectrum { spectrum, duration } => change_sea(ocean, spectrum, duration),
            SeaChange::Rebuild { spectrum, config } => rebuild(ocean, spectrum, config),
            SeaChange::Choppiness(lambda) => ocean.set_choppiness(lambda),
            SeaChange::Foam(config) => ocean.set_foam_config(config),
        }
        .and_then(|()| static_info(ocean, info));
        frame.error = result.err().map(|e| e.to_string());
        info.generation += 1;
        frame.times.change = start.elapsed().as_secs_f64() * 1e3;
    }
    let start = Instant::now();
    if let Err(e) = ocean.step(dt) {
        frame.error = Some(e.to_string());
    }
    frame.times.step = start.elapsed().as_secs_f64() * 1e3;

    let start = Instant::now();
    frame.fit(ocean);
    frame.info = *info;
    if let Err(e) = frame.pack(ocean) {
        frame.error = Some(e.to_string());
    }
    frame.info.time = ocean.time();
    frame.info.foam_total = ocean.foam_coverage().total;
    frame.times.pack = start.elapsed().as_secs_f64() * 1e3;

    let start = Instant::now();
    let Frame {
        queries, samples, ..
    } = &mut *frame;
    if let Err(e) = ocean.surfaces_at(queries, samples) {
        frame.error = Some(e.to_string());
    }
    frame.times.query = start.elapsed().as_secs_f64() * 1e3;
    frame
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The mip chain's levels are 2×2 box means of the level above: checked against a direct
    /// mean over the 2^m × 2^m block of level 0 (in f64), for a random-looking field.
    #[test]
    fn mip_levels_are_block_means_of_level_zero() {
        let n = 16;
        let levels = mip_levels(n);
        assert_eq!(levels, 5);
        let mut chain = vec![[0.0f32; 4]; (0..levels).map(|m| (n >> m) * (n >> m)).sum()];
        for (index, texel) in chain[..n * n].iter_mut().enumerate() {
            let v = ((index * 7919) % 101) as f32 / 10.0 - 5.0;
            *texel = [v, -v, 0.5 * v, 1.0];
        }
        let mut offsets = vec![0];
        for m in 1..levels {
            offsets.push(offsets[m - 1] + (n >> (m - 1)) * (n >> (m - 1)));
        }
        for m in 1..levels {
            let side = n >> m;
            let (done, rest) = chain.split_at_mut(offsets[m]);
            downsample(&done[offsets[m - 1]..], &mut rest[..side * side], side);
        }
        for m in 0..levels {
            let side = n >> m;
            let block = 1 << m;
            for j in 0..side {
                for i in 0..side {
                    let mut mean = 0.0f64;
                    for y in 0..block {
                        for x in 0..block {
                            mean += f64::from(chain[(j * block + y) * n + i * block + x][0]);
                        }
                    }
                    mean /= (block * block) as f64;
                    let got = f64::from(chain[offsets[m] + j * side + i][0]);
                    // Pairwise f32 means of values below 5 in magnitude: a few ulps of 5.
                    assert!(
                        (got - mean).abs() < 1e-5,
                        "level {m} ({i}, {j}): {got} vs {mean}"
                    );
                }
            }
        }
    }

    /// A frame packed by the simulation carries the crate's own texels at level 0: the f16
    /// of `OceanState::pack_texels_f16`, bit for bit, in every cascade's layer.
    #[test]
    fn level_zero_is_the_crates_f16_packing() {
        let config = OceanConfig {
            size: 32,
            ..OceanConfig::default()
        };
        let spectrum = Spectrum::jonswap(12.0, 200_000.0).unwrap();
        let mut ocean = OceanState::new(spectrum, config).unwrap();
        ocean.step(0.5).unwrap();
        let mut frame = Frame::new(0);
        frame.fit(&ocean);
        frame.pack(&ocean).unwrap();
        let mut expected = vec![[f16::ZERO; 4]; 32 * 32];
        for c in 0..ocean.cascades().len() {
            for (layout, buffer) in [
                (TexelLayout::DisplacementFoam, &frame.displacement),
                (TexelLayout::SlopeJacobianFoam, &frame.slope),
            ] {
                ocean.pack_texels_f16(c, layout, &mut expected).unwrap();
                let got = &buffer[c * frame.layer_len..c * frame.layer_len + 32 * 32];
                let same = got
                    .iter()
                    .zip(&expected)
                    .all(|(a, b)| a.map(f16::to_bits) == b.map(f16::to_bits));
                assert!(same, "cascade {c}, {layout:?}");
            }
        }
    }
}
