//! ocean-fft's render layer: what every engine that draws the ocean needs besides its own
//! API, written once and engine-neutral (no GPU API, no engine).
//!
//! - [`Texels`]: every cascade's RGBA16F texels with their mip chains, ready to upload.
//! - [`OceanInfo`] and [`OceanUniforms`]: the shader's per-frame inputs (σ², the slope table,
//!   the channel variances, the tile origins) in the layout of `OceanUniforms` in
//!   shaders/ocean_common.wgsl; [`Light`] the palette it is shaded with.
//! - [`clipmap`]: the rings of grid points the water is drawn on.
//! - [`SeaSettings`] and [`SeaSettings::plan`]: a change of the sea an engine asks for, turned
//!   into live changes or a new ocean.
//! - [`Simulation`]: a double-buffered simulation thread that steps, packs and queries while
//!   the engine draws the previous frame.
//! - [`StreakTexels`]: the foam's streak field, uploaded once per ocean, placed each frame.
//! - [`WakeTexels`]: the wake window's texels and place; [`hull_of`] a floating body's
//!   [`Hull`](ocean_fft::Hull), [`wake_centre`] where the window goes for a camera.
//! - [`coast`]: the coast's texels over a depth map ([`CoastTexels`], kept by a
//!   [`CoastPacker`]) and procedural coasts with their ground ([`CoastKind`], [`Terrain`]).
//! - [`floater`]: floating bodies ([`Body`] of vertical columns, [`Pose`], [`Motion`]): the
//!   water's push on them from a batch of height queries ([`Push`]: Archimedes and drag) and
//!   the kinematic step of their heave, pitch and roll; [`Floater`] holds one with its state.
//!
//! The viewer (viewer/) and the Bevy plugin (bevy_ocean_fft/) draw with it; a port to another
//! engine adds only that engine's glue (textures, buffers, pipelines, its scheduling).

pub mod clipmap;
pub mod coast;
pub mod floater;
mod info;
mod sea;
#[cfg(test)]
mod shader_tests;
mod streaks;
mod texels;
mod thread;
mod uniforms;
mod wake;

pub use coast::{coast_uniforms, terrain, CoastKind, CoastPacker, CoastTexels, Terrain};
pub use floater::{Body, Column, Floater, Motion, Pose, Push, Velocities, SEA_WATER_DENSITY};
pub use info::{OceanInfo, SlopeTable, MAX_CASCADES, SLOPE_TABLE};
pub use sea::{
    apply, build, build_sea, follow_clock, set_depth_map_at_once, Change, Plan, SeaSettings,
    PRE_ROLL, PRE_ROLL_DT,
};
pub use streaks::{streak_uniforms, StreakTexels};
pub use texels::{mip_levels, Level, Texels};
pub use thread::{Frame, SimTimes, Simulation};
pub use uniforms::{Light, OceanUniforms, Tiling, EXACT_WITHIN};
pub use wake::{heading_of, hull_of, wake_centre, WakeTexels};
