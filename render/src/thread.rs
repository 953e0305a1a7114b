//! The double-buffered simulation thread: it owns the [`OceanState`], steps it, packs every
//! cascade into RGBA16F texels with their mipmaps, and answers the frame's CPU queries, while
//! the engine draws the previous frame.
//!
//! Two [`Frame`]s circulate between the threads: the engine uploads one while the simulation
//! fills the other, so step n + 1 runs while frame n renders. Once both exist the loop
//! allocates nothing: the frames keep their buffers, the channels are bounded (their slots
//! are allocated once), and every step, pack and query runs inside the thread's own rayon
//! pool (called from outside a pool, rayon's job queue would allocate a block every 63
//! calls). Only a change of sea allocates (a new ocean, new tables).

use std::sync::mpsc::{sync_channel, Receiver, SyncSender};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Instant;

use ocean_fft::{Error, Hull, OceanState, SurfaceSample};

use crate::coast::{CoastPacker, CoastTexels};
use crate::info::{OceanInfo, SlopeTable};
use crate::sea::{apply, build_sea, set_depth_map_at_once, Plan, SeaSettings, PRE_ROLL_DT};
use crate::streaks::StreakTexels;
use crate::texels::Texels;
use crate::wake::WakeTexels;

/// Timings of the simulation's share of a frame, ms.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SimTimes {
    /// The step.
    pub step: f64,
    /// Packing the texels, their mipmaps and the f16 conversion.
    pub pack: f64,
    /// The frame's CPU queries.
    pub query: f64,
    /// A change of sea applied before the step (0 on most frames).
    pub change: f64,
}

/// One frame's data, passed back and forth between the threads.
#[derive(Debug, Default)]
pub struct Frame {
    /// Every cascade's texels with their mip chains.
    pub texels: Texels,
    /// The wake window's texels (empty without `OceanConfig::wakes`).
    pub wake: WakeTexels,
    /// The foam's streak field (copied when the ocean is new; upload it when its
    /// generation changes).
    pub streaks: StreakTexels,
    /// The coast's texels over the depth map (`None` without one; upload them when their
    /// `generation` changes).
    pub coast: Option<Arc<CoastTexels>>,
    /// The world points (x, z; m) queried after the step, and their surfaces.
    pub queries: Vec<[f64; 2]>,
    pub samples: Vec<SurfaceSample>,
    /// What the shader needs besides the textures, for the time the textures hold.
    pub info: OceanInfo,
    pub times: SimTimes,
    /// New oceans built since the start (a new grid or depth; the textures' size may change).
    pub rebuilds: u64,
    /// The last error of a change of sea or a step, if any.
    pub error: Option<String>,
}

impl Frame {
    fn new(queries: usize) -> Frame {
        Frame {
            queries: vec![[0.0; 2]; queries],
            samples: vec![SurfaceSample::default(); queries],
            ..Frame::default()
        }
    }
}

/// A request to the simulation thread: take the sea to `sea` (if given), set the wake's
/// hulls and window, step by `dt` seconds, fill `frame`.
struct Request {
    dt: f64,
    sea: Option<SeaSettings>,
    wake: Option<Box<WakeRequest>>,
    frame: Box<Frame>,
}

/// The hulls and the window's centre the next step's wake takes (an ocean without wakes
/// ignores them).
#[derive(Debug, Clone, Default)]
struct WakeRequest {
    centre: [f64; 2],
    hulls: Vec<Hull>,
}

/// The simulation thread's own state.
struct Worker {
    ocean: OceanState,
    running: SeaSettings,
    slopes: SlopeTable,
    coast: CoastPacker,
    rebuilds: u64,
}

/// The engine's handle on the simulation thread.
pub struct Simulation {
    requests: SyncSender<Option<Request>>,
    results: Receiver<Box<Frame>>,
    /// The frame the engine holds (uploaded, sent back with the next request).
    spare: Option<Box<Frame>>,
    /// The wake input of the next request, and the one the thread gave back (kept so that
    /// setting hulls every frame allocates nothing).
    wake: Option<Box<WakeRequest>>,
    wake_spare: Option<Box<WakeRequest>>,
    returned: Receiver<Box<WakeRequest>>,
    thread: Option<JoinHandle<()>>,
}

impl Simulation {
    /// Builds the ocean of `sea` at sea time `time` with its foam spun up over `pre_roll`
    /// seconds (at most `time`), on a thread of its own with a rayon pool of `threads`
    /// threads, and starts the first frame, which answers `queries` (world points x, z, m;
    /// as many are queried every frame).
    ///
    /// # Errors
    /// The crate's for the sea; a message if a thread cannot start.
    pub fn start(
        sea: SeaSettings,
        time: f64,
        pre_roll: f64,
        threads: usize,
        queries: &[[f64; 2]],
    ) -> Result<Simulation, String> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .thread_name(|i| format!("ocean-sim-{i}"))
            .build()
            .map_err(|e| format!("rayon pool: {e}"))?;
        let mut first = Box::new(Frame::new(queries.len()));
        first.queries.copy_from_slice(queries);
        let mut worker = pool
            .install(|| -> Result<Worker, Error> {
                let mut ocean = OceanState::new(sea.spectrum.clone(), sea.grids())?;
                ocean.set_time(time)?;
                set_depth_map_at_once(&mut ocean, sea.depth_map.as_deref())?;
                if pre_roll > 0.0 {
                    ocean.pre_roll(pre_roll.min(time.max(PRE_ROLL_DT)), PRE_ROLL_DT)?;
                }
                let mut worker = Worker {
                    ocean,
                    running: sea,
                    slopes: SlopeTable::default(),
                    coast: CoastPacker::default(),
                    rebuilds: 0,
                };
                worker.fill(&mut first)?;
                Ok(worker)
            })
            .map_err(|e| e.to_string())?;
        let (request_tx, request_rx) = sync_channel::<Option<Request>>(1);
        let (result_tx, result_rx) = sync_channel::<Box<Frame>>(2);
        let (wake_tx, wake_rx) = sync_channel::<Box<WakeRequest>>(2);
        result_tx.send(first).map_err(|e| e.to_string())?;
        let thread = std::thread::Builder::new()
            .name("ocean-sim".into())
            .spawn(move || {
                while let Ok(Some(mut request)) = request_rx.recv() {
                    let wake = request.wake.take();
                    let frame = pool.install(|| worker.serve(request, wake.as_deref()));
                    if let Some(wake) = wake {
                        let _ = wake_tx.try_send(wake);
                    }
                    if result_tx.send(frame).is_err() {
                        break;
                    }
                }
            })
            .map_err(|e| format!("simulation thread: {e}"))?;
        Ok(Simulation {
            requests: request_tx,
            results: result_rx,
            spare: Some(Box::new(Frame::new(queries.len()))),
            wake: None,
            wake_spare: None,
            returned: wake_rx,
            thread: Some(thread),
        })
    }

    /// The hulls that make the wake and the window's centre (world x, z, m), taken by the
    /// next request's step (`OceanState::set_wake_centre`, then `set_hulls`; an ocean built
    /// without `OceanConfig::wakes` ignores them). Call it before [`next`](Self::next) each
    /// frame the hulls move; a frame without the call keeps the last hulls moving along
    /// their velocities. Allocates nothing once the hulls' buffer has grown.
    pub fn set_wake(&mut self, centre: [f64; 2], hulls: &[Hull]) {
        while let Ok(back) = self.returned.try_recv() {
            self.wake_spare = Some(back);
        }
        let mut wake = self
            .wake
            .take()
            .or_else(|| self.wake_spare.take())
            .unwrap_or_default();
        wake.centre = centre;
        wake.hulls.clear();
        wake.hulls.extend_from_slice(hulls);
        self.wake = Some(wake);
    }

    /// Waits for the next stepped frame, then at once asks for the one after it (the sea
    /// taken to `sea` if given, a step of `dt` seconds, queries at `queries`), so that it is
    /// computed while the caller uploads and draws the frame returned. The caller gives the
    /// frame back with [`Simulation::give_back`] once uploaded.
    ///
    /// # Errors
    /// A message if the simulation thread stopped, or `queries` is not as long as the points
    /// given to [`start`](Self::start).
    pub fn next(
        &mut self,
        dt: f64,
        sea: Option<SeaSettings>,
        queries: &[[f64; 2]],
    ) -> Result<Box<Frame>, String> {
        let ready = self
            .results
            .recv()
            .map_err(|_| "the simulation thread stopped".to_string())?;
        let mut spare = self.spare.take().ok_or("no frame to fill")?;
        if spare.queries.len() != queries.len() {
            return Err(format!(
                "{} queries, {} expected",
                queries.len(),
                spare.queries.len()
            ));
        }
        spare.queries.copy_from_slice(queries);
        self.requests
            .send(Some(Request {
                dt,
                sea,
                wake: self.wake.take(),
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

impl Worker {
    /// Takes the ocean to `sea`: live changes where it can, a new ocean at the same time
    /// otherwise (or when a live change is refused).
    fn change(&mut self, sea: SeaSettings) -> Result<(), Error> {
        let config = match sea.plan(&self.running, &self.ocean) {
            Plan::Nothing => return Ok(()),
            Plan::Live(changes) => {
                let mut refused = None;
                for change in changes {
                    if let Err(e) = apply(&mut self.ocean, change) {
                        refused = Some(e);
                        break;
                    }
                }
                match refused {
                    None => {
                        self.running = sea;
                        return Ok(());
                    }
                    // A change the running ocean refuses (a choppiness its sea cannot take
                    // until the new spectrum is in): a new ocean of the whole sea.
                    Some(_) => sea.grids(),
                }
            }
            Plan::Rebuild(config) => config,
        };
        let time = self.ocean.time();
        self.ocean = build_sea(&sea, config, time)?;
        self.running = sea;
        self.rebuilds += 1;
        Ok(())
    }

    /// Packs the ocean as it is into `frame` and answers its queries.
    fn fill(&mut self, frame: &mut Frame) -> Result<(), Error> {
        let start = Instant::now();
        frame.texels.pack(&self.ocean)?;
        frame.wake.pack(&self.ocean)?;
        frame.streaks.pack(&self.ocean);
        frame.coast = self.coast.pack(&self.ocean)?;
        frame.info.update(&self.ocean, &mut self.slopes)?;
        frame.info.jacobian_sd = frame.texels.jacobian_sd;
        frame.rebuilds = self.rebuilds;
        frame.times.pack = start.elapsed().as_secs_f64() * 1e3;
        let start = Instant::now();
        let Frame {
            queries, samples, ..
        } = frame;
        self.ocean.water().surfaces_at(queries, samples)?;
        frame.times.query = start.elapsed().as_secs_f64() * 1e3;
        Ok(())
    }

    /// One request: the change, the wake's input, the step, the pack and the queries.
    fn serve(&mut self, request: Request, wake: Option<&WakeRequest>) -> Box<Frame> {
        let Request {
            dt, sea, mut frame, ..
        } = request;
        frame.times = SimTimes::default();
        frame.error = None;
        if let Some(sea) = sea {
            let start = Instant::now();
            if let Err(e) = self.change(sea) {
                frame.error = Some(e.to_string());
            }
            frame.times.change = start.elapsed().as_secs_f64() * 1e3;
        }
        if let Some(wake) = wake.filter(|_| self.ocean.wakes().is_some()) {
            let [x, z] = wake.centre;
            let set = self
                .ocean
                .set_wake_centre(x, z)
                .and_then(|()| self.ocean.set_hulls(&wake.hulls));
            if let Err(e) = set {
                frame.error = Some(format!("wake: {e}"));
            }
        }
        let start = Instant::now();
        if let Err(e) = self.ocean.step(dt) {
            frame.error = Some(e.to_string());
        }
        frame.times.step = start.elapsed().as_secs_f64() * 1e3;
        if let Err(e) = self.fill(&mut frame) {
            frame.error = Some(e.to_string());
        }
        frame
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ocean_fft::SeaState;

    /// The thread answers frame after frame at the clock's times, takes a new sea live or by a
    /// rebuild as the plan says, and hands back the frame it was given.
    #[test]
    fn frames_follow_the_clock_and_the_sea() {
        let mut sea = SeaSettings::preset(SeaState::FreshBreeze);
        sea.config.size = 32;
        let queries = [[0.0, 0.0], [3.0, -4.0]];
        let mut sim = Simulation::start(sea.clone(), 10.0, 0.5, 1, &queries).unwrap();
        let mut times = Vec::new();
        let mut calmer = sea.clone();
        calmer.set_weather(SeaState::ModerateBreeze);
        let mut grids = sea.clone();
        grids.config.seed += 1;
        for n in 0..6 {
            let change = match n {
                2 => Some(calmer.clone()),
                4 => Some(grids.clone()),
                _ => None,
            };
            let frame = sim.next(0.5, change, &queries).unwrap();
            assert_eq!(frame.error, None);
            assert_eq!(frame.texels.cascades, frame.info.cascades);
            assert!(frame.samples.iter().all(|s| s.height.is_finite()));
            times.push((frame.info.time, frame.rebuilds));
            sim.give_back(frame);
        }
        // Frame n holds the time after n steps; the new grids (asked with frame 4's request)
        // are a rebuild, seen from frame 5 on; the calmer weather was live.
        let expected: Vec<(f64, u64)> = (0..6)
            .map(|n| (10.0 + 0.5 * n as f64, u64::from(n >= 5)))
            .collect();
        assert_eq!(times, expected);
    }

    /// With a wake window, the hulls set before a request press the water in the frames that
    /// follow, the window moves to the centre given, and the frames carry the wake's texels
    /// and the streak field.
    #[test]
    fn hulls_reach_the_wake_and_its_texels() {
        let mut sea = SeaSettings::preset(SeaState::Calm);
        sea.config.size = 32;
        sea.config.wakes = Some(ocean_fft::WakeConfig {
            size: 64,
            spacing: 1.0,
            ..ocean_fft::WakeConfig::default()
        });
        let queries = [[0.0, 0.0]];
        let mut sim = Simulation::start(sea, 5.0, 0.0, 1, &queries).unwrap();
        let mut deepest = 0.0f32;
        let mut origin = [0.0; 2];
        for n in 0..8 {
            let hull = Hull {
                position: [200.0 + 0.5 * n as f64, -40.0],
                velocity: [4.0, 0.0],
                length: 10.0,
                beam: 3.0,
                draft: 0.8,
                ..Hull::default()
            };
            sim.set_wake([200.0, -40.0], &[hull]);
            let frame = sim.next(0.125, None, &queries).unwrap();
            assert_eq!(frame.error, None);
            if frame.wake.active() {
                origin = frame.wake.origin;
                let low = frame.wake.texels.iter().map(|t| t[0].to_f32());
                deepest = deepest.min(low.fold(0.0, f32::min));
            }
            assert!(!frame.streaks.texels.is_empty());
            sim.give_back(frame);
        }
        assert!(deepest < -0.1, "the hull presses the water: {deepest}");
        // The window (64 m) is centred on (200, -40) to a cell.
        assert!(
            (origin[0] - 168.0).abs() <= 1.0 && (origin[1] + 72.0).abs() <= 1.0,
            "{origin:?}"
        );
    }

    /// A sea with a depth map carries the coast's texels from the first frame on; new
    /// weather solves the map again (a new generation); a sea without the map drops them.
    #[test]
    fn frames_carry_the_coast() {
        let mut sea = SeaSettings::preset(SeaState::FreshBreeze);
        sea.config.size = 32;
        sea.depth_map = Some(Arc::new(ocean_fft::DepthMap {
            origin: [-64.0, -32.0],
            spacing: 4.0,
            size: [32, 16],
            depth: (0..32 * 16).map(|c| 12.0 - (c % 32) as f32 * 0.5).collect(),
        }));
        let queries = [[0.0, 0.0]];
        let mut sim = Simulation::start(sea.clone(), 5.0, 0.0, 1, &queries).unwrap();
        let mut calmer = sea.clone();
        calmer.set_weather(SeaState::ModerateBreeze);
        let mut open = calmer.clone();
        open.depth_map = None;
        let mut generations = Vec::new();
        for n in 0..8 {
            let change = match n {
                1 => Some(calmer.clone()),
                5 => Some(open.clone()),
                _ => None,
            };
            let frame = sim.next(1.0, change, &queries).unwrap();
            assert_eq!(frame.error, None);
            generations.push(frame.coast.as_ref().map(|c| {
                assert_eq!(c.size, [32, 16]);
                assert_eq!(c.origin, [-64.0, -32.0]);
                c.generation
            }));
            sim.give_back(frame);
        }
        // Frames 0–1: the first map (repacked while it blends in); 2 on: the map solved for
        // the calmer weather (asked with frame 1's request), new texels; from 6 on none.
        assert!(
            generations[..6].iter().all(Option::is_some),
            "{generations:?}"
        );
        assert!(generations[2] > generations[1], "{generations:?}");
        assert!(
            generations[6..].iter().all(Option::is_none),
            "{generations:?}"
        );
    }
}
