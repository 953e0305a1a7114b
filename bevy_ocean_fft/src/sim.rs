//! The simulation: one [`OceanState`] moved into a task on Bevy's async compute pool every
//! frame (stepped to the clock and packed into texels there, while the frame renders) and
//! back at the start of the next frame, when the game's queries and the buoyancy use it. New
//! oceans (new grids, a new depth) are built by a second task while the old one runs on.

use std::sync::Arc;
use std::time::Instant;

use bevy::prelude::*;
use bevy::tasks::{block_on, AsyncComputeTaskPool, Task};
use ocean_fft::gpu::TexelLayout;
use ocean_fft::half::f16;
use ocean_fft::half::slice::HalfFloatSliceExt;
use ocean_fft::{Error, OceanState, Spectrum};

use crate::settings::{live_changes, Change, OceanClock, OceanSettings};

/// Most cascades the shader takes.
pub const MAX_CASCADES: usize = 8;
/// Entries of the table of the slope variance the pixels do not resolve.
pub const SLOPE_TABLE: usize = 32;
/// Seconds of foam spun up when a new ocean is built (at steps of [`PRE_ROLL_DT`]).
pub const PRE_ROLL: f64 = 6.0;
/// Time step of the spin-up, s.
pub const PRE_ROLL_DT: f64 = 0.1;

/// What the shader needs about the ocean besides its textures, for the frame they hold.
#[derive(Debug, Clone, Copy, Default)]
pub struct OceanInfo {
    /// Sea time of the textures, s.
    pub time: f64,
    /// Number of cascades, their sides L (m) and their grid size N.
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
    /// Wave numbers k_i (rad/m, geometric) and the slope variance (along, across the wind)
    /// of the simulated waves above each.
    pub slope_table: [[f32; 3]; SLOPE_TABLE],
}

/// One frame's textures: every cascade's `DisplacementFoam` and `SlopeJacobianFoam` texels
/// (RGBA16F) with their mip chains, layer-major: layer c's level m starts at
/// `c * layer_len + level_offsets[m]`.
#[derive(Debug, Default)]
pub struct Texels {
    pub displacement: Vec<[f16; 4]>,
    pub slope: Vec<[f16; 4]>,
    pub layer_len: usize,
    pub level_offsets: Vec<usize>,
    pub info: OceanInfo,
    /// f32 scratch: one layer's mip chain.
    scratch: Vec<[f32; 4]>,
}

/// The slope-variance table and the spectrum and choppiness it was computed for (32
/// integrals of the spectrum: computed again only when they change).
#[derive(Debug, Default)]
struct SlopeTable {
    key: Option<(Spectrum, f32)>,
    table: [[f32; 3]; SLOPE_TABLE],
}

/// Mip levels of an N×N texture whose side halves while it is even.
pub fn mip_levels(n: usize) -> usize {
    (n.trailing_zeros() as usize + 1).min(13)
}

impl Texels {
    /// Packs every cascade of `ocean` with its mip chains (allocates only when the grid
    /// changed since this buffer's last use).
    fn pack(&mut self, ocean: &OceanState, slopes: &mut SlopeTable) -> Result<(), Error> {
        let n = ocean.config().size;
        let cascades = ocean.cascades().len().min(MAX_CASCADES);
        let levels = mip_levels(n);
        let layer_len: usize = (0..levels).map(|m| (n >> m) * (n >> m)).sum();
        if self.layer_len != layer_len || self.displacement.len() != layer_len * cascades {
            self.level_offsets = (0..levels)
                .map(|m| (0..m).map(|k| (n >> k) * (n >> k)).sum())
                .collect();
            self.layer_len = layer_len;
            self.displacement = vec![[f16::ZERO; 4]; layer_len * cascades];
            self.slope = vec![[f16::ZERO; 4]; layer_len * cascades];
            self.scratch = vec![[0.0; 4]; layer_len];
        }
        let mut jacobian_variance = 0.0f64;
        for c in 0..cascades {
            for layout in [
                TexelLayout::DisplacementFoam,
                TexelLayout::SlopeJacobianFoam,
            ] {
                ocean.pack_texels(c, layout, &mut self.scratch[..n * n])?;
                if layout == TexelLayout::SlopeJacobianFoam {
                    // The bands are independent, so the variances of J − 1 add.
                    jacobian_variance += channel_variance(&self.scratch[..n * n], 2);
                }
                for m in 1..levels {
                    let (done, rest) = self.scratch.split_at_mut(self.level_offsets[m]);
                    box_down(&done[self.level_offsets[m - 1]..], rest, n >> m);
                }
                let out = if layout == TexelLayout::DisplacementFoam {
                    &mut self.displacement
                } else {
                    &mut self.slope
                };
                out[c * layer_len..(c + 1) * layer_len]
                    .as_flattened_mut()
                    .convert_from_f32_slice(self.scratch.as_flattened());
            }
        }
        let info = &mut self.info;
        info.time = ocean.time();
        info.cascades = cascades;
        info.size = n;
        info.mip_levels = levels;
        info.lengths = [0.0; MAX_CASCADES];
        for (length, cascade) in info.lengths.iter_mut().zip(ocean.cascades()) {
            *length = cascade.length();
        }
        info.jacobian_sd = jacobian_variance.sqrt() as f32;
        info.height_sd = ocean.expected_variance().sqrt() as f32;
        let spectrum = ocean.spectrum();
        info.wind = spectrum.wind_vector();
        let subgrid = ocean.subgrid_slope_variance();
        info.subgrid = [subgrid.along, subgrid.across];
        let fresh = slopes
            .key
            .as_ref()
            .is_some_and(|(s, c)| s == spectrum && *c == ocean.config().choppiness);
        if !fresh {
            let bands = ocean.config().bands()?;
            let (bottom, top) = (bands[0].0.max(1e-3), bands[bands.len() - 1].1);
            for (i, entry) in slopes.table.iter_mut().enumerate() {
                let k = bottom * (top / bottom).powf(i as f32 / (SLOPE_TABLE - 1) as f32);
                let v = spectrum.slope_variance(k, top);
                *entry = [k, v.along, v.across];
            }
            slopes.key = Some((spectrum.clone(), ocean.config().choppiness));
        }
        info.slope_table = slopes.table;
        Ok(())
    }
}

/// Variance of channel `k` of `texels`, summed in f64.
fn channel_variance(texels: &[[f32; 4]], k: usize) -> f64 {
    let (sum, sum2) = texels.iter().fold((0.0f64, 0.0f64), |(s, s2), t| {
        let v = f64::from(t[k]);
        (s + v, s2 + v * v)
    });
    let count = texels.len() as f64;
    let mean = sum / count;
    (sum2 / count - mean * mean).max(0.0)
}

/// Mip level of side `side` (in `target`) as 2×2 means of the level of side 2·side in
/// `source`.
fn box_down(source: &[[f32; 4]], target: &mut [[f32; 4]], side: usize) {
    let wide = 2 * side;
    for j in 0..side {
        for i in 0..side {
            let a = source[2 * j * wide + 2 * i];
            let b = source[2 * j * wide + 2 * i + 1];
            let c = source[(2 * j + 1) * wide + 2 * i];
            let d = source[(2 * j + 1) * wide + 2 * i + 1];
            target[j * side + i] = std::array::from_fn(|k| 0.25 * (a[k] + b[k] + c[k] + d[k]));
        }
    }
}

/// A step's result, back from the task.
struct Stepped {
    ocean: OceanState,
    texels: Texels,
    slopes: Box<SlopeTable>,
    errors: Vec<String>,
    step_ms: f64,
    pack_ms: f64,
}

/// A new ocean's result, back from the task.
struct Built {
    ocean: Result<OceanState, Error>,
    settings: OceanSettings,
}

/// The plugin's simulation state. Between `First` and `Last` of every frame the ocean is
/// here (see [`Water`](crate::Water) for queries); from `Last` to the next `First` it is in a
/// task, stepping.
#[derive(Resource, Default)]
pub struct OceanSim {
    ocean: Option<OceanState>,
    /// The settings the ocean runs.
    applied: Option<OceanSettings>,
    /// Settings whose new ocean the crate refused (not tried again until they change).
    refused: Option<OceanSettings>,
    step: Option<Task<Stepped>>,
    build: Option<Task<Built>>,
    /// Texel buffers free for the next step, and those the render world may still hold.
    pool: Vec<Texels>,
    lent: Vec<Arc<Texels>>,
    slopes: Option<Box<SlopeTable>>,
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
    pub texels: Option<Arc<Texels>>,
}

/// The sea time the clock asks for now.
pub(crate) fn clock_time(clock: &OceanClock, time: &Time<Virtual>) -> f64 {
    match *clock {
        OceanClock::Virtual => time.elapsed_secs_f64(),
        OceanClock::Manual(t) => t,
    }
}

/// A new ocean of `settings` at sea time `time`, its foam spun up.
fn build_ocean(settings: &OceanSettings, time: f64) -> Result<OceanState, Error> {
    let mut ocean = OceanState::new(settings.spectrum.clone(), settings.grids())?;
    ocean.set_time(time)?;
    ocean.pre_roll(PRE_ROLL, PRE_ROLL_DT)?;
    Ok(ocean)
}

/// Moves `ocean` to sea time `t`: a step with the foam evolving, or a jump for a clock that
/// went back or leapt ahead.
fn follow_clock(ocean: &mut OceanState, t: f64) -> Result<(), Error> {
    let now = ocean.time();
    if t >= now && t - now <= OceanState::MAX_STEP {
        ocean.step_to(t)
    } else {
        ocean.set_time(t)
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
        status.transition_progress = ocean.transition_progress();
        status.spectrum = Some(ocean.spectrum().clone());
    }
}

/// `Last`: applies the settings (live changes, or a new ocean built off the main thread)
/// and sends the ocean to step to the clock's time while the frame renders.
pub(crate) fn launch(
    mut sim: ResMut<OceanSim>,
    settings: Res<OceanSettings>,
    clock: Res<OceanClock>,
    time: Res<Time<Virtual>>,
) {
    let sim = &mut *sim;
    let target = clock_time(&clock, &time);
    let mut changes = Vec::new();
    let wanted = &*settings;
    if sim.build.is_none()
        && sim.applied.as_ref() != Some(wanted)
        && sim.refused.as_ref() != Some(wanted)
    {
        let live = match (&sim.applied, &sim.ocean) {
            (Some(applied), Some(ocean)) => {
                !applied.needs_rebuild(wanted)
                    && wanted.spectrum.dispersion() == ocean.spectrum().dispersion()
                    // The running grids may be fitted to an earlier sea: they must hold this one.
                    && (wanted.spectrum == *ocean.spectrum()
                        || ocean.config().fit(&wanted.spectrum).is_ok_and(|fit| {
                            fit.held >= OceanState::MIN_CHANGE_SHARE
                        }))
            }
            _ => false,
        };
        if live {
            changes = live_changes(sim.applied.as_ref().expect("live"), wanted);
            sim.applied = Some(wanted.clone());
        } else {
            let wanted = wanted.clone();
            sim.build = Some(AsyncComputeTaskPool::get().spawn(async move {
                Built {
                    ocean: build_ocean(&wanted, target),
                    settings: wanted,
                }
            }));
        }
    }
    let Some(mut ocean) = sim.ocean.take() else {
        return;
    };
    let mut texels = sim.pool.pop().unwrap_or_default();
    let mut slopes = sim.slopes.take().unwrap_or_default();
    sim.step = Some(AsyncComputeTaskPool::get().spawn(async move {
        let mut errors = Vec::new();
        for change in changes {
            let result = match change {
                Change::Spectrum(spectrum, duration) => ocean.set_spectrum(spectrum, duration),
                Change::Choppiness(choppiness) => ocean.set_choppiness(choppiness),
                Change::Foam(foam) => ocean.set_foam_config(foam),
            };
            if let Err(error) = result {
                errors.push(format!("change refused: {error}"));
            }
        }
        let start = Instant::now();
        if let Err(error) = follow_clock(&mut ocean, target) {
            errors.push(format!("step refused: {error}"));
        }
        let stepped = Instant::now();
        if let Err(error) = texels.pack(&ocean, &mut slopes) {
            errors.push(format!("packing refused: {error}"));
        }
        Stepped {
            ocean,
            texels,
            slopes,
            errors,
            step_ms: (stepped - start).as_secs_f64() * 1e3,
            pack_ms: stepped.elapsed().as_secs_f64() * 1e3,
        }
    }));
}
