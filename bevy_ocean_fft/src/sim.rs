//! The simulation: one [`OceanState`] moved into a task on Bevy's async compute pool every
//! frame (stepped to the clock and packed into texels there, while the frame renders) and
//! back at the start of the next frame, when the game's queries and the buoyancy use it. New
//! oceans (new grids, a new depth) are built by a second task while the old one runs on.

use std::sync::Arc;
use std::time::Instant;

use bevy::prelude::*;
use bevy::tasks::{block_on, AsyncComputeTaskPool, Task};
use ocean_fft::{Error, OceanState, Spectrum};
use ocean_fft_render::{
    apply, build_sea, follow_clock, CoastPacker, CoastTexels, OceanInfo, Plan, SeaSettings,
    SlopeTable, StreakTexels, Texels, WakeTexels,
};

use crate::settings::{OceanClock, OceanSettings};
use crate::wake::{WakeInput, WakeWindow};

/// One frame's textures and what the shader needs with them.
#[derive(Debug, Default)]
pub struct PackedFrame {
    /// Every cascade's texels with their mip chains.
    pub texels: Texels,
    /// The wake window's texels (empty without wakes).
    pub wake: WakeTexels,
    /// The foam's streak field (copied when the ocean is new).
    pub streaks: StreakTexels,
    /// The coast's texels over the depth map (`None` without one; upload them when their
    /// generation changes).
    pub coast: Option<Arc<CoastTexels>>,
    /// The ocean at the time the texels hold.
    pub info: OceanInfo,
}

impl PackedFrame {
    /// Packs `ocean` as it is now (allocates only when the grid changed).
    fn pack(
        &mut self,
        ocean: &OceanState,
        slopes: &mut SlopeTable,
        coast: &mut CoastPacker,
    ) -> Result<(), Error> {
        self.texels.pack(ocean)?;
        self.wake.pack(ocean)?;
        self.streaks.pack(ocean);
        self.coast = coast.pack(ocean)?;
        self.info.update(ocean, slopes)?;
        self.info.jacobian_sd = self.texels.jacobian_sd;
        Ok(())
    }
}

/// A step's result, back from the task.
struct Stepped {
    ocean: OceanState,
    texels: PackedFrame,
    slopes: Box<SlopeTable>,
    coast: Box<CoastPacker>,
    errors: Vec<String>,
    step_ms: f64,
    pack_ms: f64,
}

/// A new ocean's result, back from the task.
struct Built {
    ocean: Result<OceanState, Error>,
    settings: SeaSettings,
}

/// The plugin's simulation state. Between `First` and `Last` of every frame the ocean is
/// here (see [`Water`](crate::Water) for queries); from `Last` to the next `First` it is in a
/// task, stepping.
#[derive(Resource, Default)]
pub struct OceanSim {
    ocean: Option<OceanState>,
    /// The settings the ocean runs.
    applied: Option<SeaSettings>,
    /// Settings whose new ocean the crate refused (not tried again until they change).
    refused: Option<SeaSettings>,
    step: Option<Task<Stepped>>,
    build: Option<Task<Built>>,
    /// Texel buffers free for the next step, and those the render world may still hold.
    pool: Vec<PackedFrame>,
    lent: Vec<Arc<PackedFrame>>,
    slopes: Option<Box<SlopeTable>>,
    coast: Option<Box<CoastPacker>>,
}

impl OceanSim {
    /// The ocean, between `First` and `Last` of a frame once the first one is built (`None`
    /// before, and while it steps).
    pub fn ocean(&self) -> Option<&OceanState> {
        self.ocean.as_ref()
    }
}

/// What the simulation did last: for HUDs, logs and tests.
#[derive(Resource, Debug, Clone, Default)]
pub struct OceanStatus {
    /// Whether an ocean runs (false until the first is built).
    pub ready: bool,
    /// Sea time of the ocean (and of the textures drawn this frame), s.
    pub time: f64,
    /// The new sea's weight w in [0, 1] while the weather changes
    /// (`OceanState::transition_progress`).
    pub transition_progress: Option<f64>,
    /// The spectrum the ocean runs (during a change of weather: the new one).
    pub spectrum: Option<Spectrum>,
    /// New oceans built (the first included): grids or depth changed.
    pub rebuilds: u64,
    /// Frames stepped.
    pub steps: u64,
    /// The last change the crate refused, or the last failed build.
    pub last_error: Option<String>,
    /// The last step's time in the task (step, then texel packing with mipmaps), ms.
    pub step_ms: f64,
    pub pack_ms: f64,
    /// How long `First` waited for the step to come back, ms (0 when the step finished
    /// while the frame rendered).
    pub wait_ms: f64,
}

/// The latest packed texels, for the render world.
#[derive(Resource, Default, Clone)]
pub struct OceanTexels {
    /// Incremented with every new frame of texels.
    pub generation: u64,
    pub texels: Option<Arc<PackedFrame>>,
}

/// The sea time the clock asks for now.
pub(crate) fn clock_time(clock: &OceanClock, time: &Time<Virtual>) -> f64 {
    match *clock {
        OceanClock::Virtual => time.elapsed_secs_f64(),
        OceanClock::Manual(t) => t,
    }
}

/// `First`: takes the stepped ocean and its texels back from the task (waiting for it if
/// the frame was quicker than the step), and swaps in a newly built ocean.
pub(crate) fn collect(
    mut sim: ResMut<OceanSim>,
    mut status: ResMut<OceanStatus>,
    mut texels: ResMut<OceanTexels>,
) {
    let sim = &mut *sim;
    if let Some(task) = sim.step.take() {
        let start = Instant::now();
        let stepped = block_on(task);
        status.wait_ms = start.elapsed().as_secs_f64() * 1e3;
        status.step_ms = stepped.step_ms;
        status.pack_ms = stepped.pack_ms;
        status.steps += 1;
        if let Some(error) = stepped.errors.into_iter().last() {
            status.last_error = Some(error);
        }
        sim.ocean = Some(stepped.ocean);
        sim.slopes = Some(stepped.slopes);
        sim.coast = Some(stepped.coast);
        let previous = texels.texels.replace(Arc::new(stepped.texels));
        texels.generation += 1;
        // The render world holds a frame's texels until its next extraction: recycle them
        // once it has let go, so that steps reuse two or three buffers.
        sim.lent.extend(previous);
        let mut i = 0;
        while i < sim.lent.len() {
            if Arc::strong_count(&sim.lent[i]) == 1 {
                if let Ok(free) = Arc::try_unwrap(sim.lent.swap_remove(i)) {
                    sim.pool.push(free);
                }
            } else {
                i += 1;
            }
        }
    }
    if sim.build.as_ref().is_some_and(|task| task.is_finished()) {
        let task = sim.build.take().expect("checked above");
        let built = block_on(task);
        match built.ocean {
            Ok(ocean) => {
                sim.ocean = Some(ocean);
                sim.applied = Some(built.settings);
                status.rebuilds += 1;
            }
            Err(error) => {
                // The old sea (if any) runs on.
                status.last_error = Some(format!("new ocean refused: {error}"));
                sim.refused = Some(built.settings);
            }
        }
    }
    if let Some(ocean) = &sim.ocean {
        status.ready = true;
        status.time = ocean.time();
        status.transition_progress = ocean.diagnostics().transition_progress();
        status.spectrum = Some(ocean.spectrum().clone());
    }
}

/// `Last`: applies the settings (live changes, or a new ocean built off the main thread;
/// with a wake window while a [`Wake`](crate::Wake) body exists), hands the ocean the
/// frame's hulls, and sends it to step to the clock's time while the frame renders.
pub(crate) fn launch(
    mut sim: ResMut<OceanSim>,
    mut status: ResMut<OceanStatus>,
    settings: Res<OceanSettings>,
    (wakes, window): (Res<WakeInput>, Res<WakeWindow>),
    clock: Res<OceanClock>,
    time: Res<Time<Virtual>>,
    mut with_wakes: Local<Option<(SeaSettings, ocean_fft::WakeConfig, SeaSettings)>>,
) {
    let sim = &mut *sim;
    let target = clock_time(&clock, &time);
    let mut changes = Vec::new();
    let wanted = if wakes.wanted && settings.0.config.wakes.is_none() {
        // The settings with the plugin's window, made again only when they change (no
        // allocation a frame).
        let fresh = with_wakes
            .as_ref()
            .is_some_and(|(from, window_of, _)| *from == settings.0 && *window_of == window.0);
        if !fresh {
            let mut sea = settings.0.clone();
            sea.config.wakes = Some(window.0.clone());
            *with_wakes = Some((settings.0.clone(), window.0.clone(), sea));
        }
        &with_wakes.as_ref().expect("set above").2
    } else {
        &settings.0
    };
    if sim.build.is_none()
        && sim.applied.as_ref() != Some(wanted)
        && sim.refused.as_ref() != Some(wanted)
    {
        let plan = match (&sim.applied, &sim.ocean) {
            (Some(applied), Some(ocean)) => wanted.plan(applied, ocean),
            _ => Plan::Rebuild(wanted.grids()),
        };
        match plan {
            Plan::Nothing => sim.applied = Some(wanted.clone()),
            Plan::Live(live) => {
                changes = live;
                sim.applied = Some(wanted.clone());
            }
            Plan::Rebuild(config) => {
                let wanted = wanted.clone();
                sim.build = Some(AsyncComputeTaskPool::get().spawn(async move {
                    Built {
                        ocean: build_sea(&wanted, config, target),
                        settings: wanted,
                    }
                }));
            }
        }
    }
    let Some(mut ocean) = sim.ocean.take() else {
        return;
    };
    if ocean.wakes().is_some() {
        let centre = wakes
            .centre
            .map_or(Ok(()), |[x, z]| ocean.set_wake_centre(x, z));
        if let Err(error) = centre.and_then(|()| ocean.set_hulls(&wakes.hulls)) {
            status.last_error = Some(format!("wake refused: {error}"));
        }
    }
    let mut texels = sim.pool.pop().unwrap_or_default();
    let mut slopes = sim.slopes.take().unwrap_or_default();
    let mut coast = sim.coast.take().unwrap_or_default();
    sim.step = Some(AsyncComputeTaskPool::get().spawn(async move {
        let mut errors = Vec::new();
        for change in changes {
            if let Err(error) = apply(&mut ocean, change) {
                errors.push(format!("change refused: {error}"));
            }
        }
        let start = Instant::now();
        if let Err(error) = follow_clock(&mut ocean, target) {
            errors.push(format!("step refused: {error}"));
        }
        let stepped = Instant::now();
        if let Err(error) = texels.pack(&ocean, &mut slopes, &mut coast) {
            errors.push(format!("packing refused: {error}"));
        }
        Stepped {
            ocean,
            texels,
            slopes,
            coast,
            errors,
            step_ms: (stepped - start).as_secs_f64() * 1e3,
            pack_ms: stepped.elapsed().as_secs_f64() * 1e3,
        }
    }));
}
