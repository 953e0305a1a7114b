//! An ocean in a Bevy game: [ocean-fft]'s FFT sea simulated off the main thread, drawn by
//! Bevy's renderer with the crate's reference shader, with weather that changes live, things
//! that float, and water queries the physics can trust.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_ocean_fft::prelude::*;
//!
//! App::new()
//!     .add_plugins((DefaultPlugins, OceanPlugin::default()))
//!     .insert_resource(OceanSettings::preset(SeaState::FreshBreeze))
//!     .add_systems(Startup, |mut commands: Commands| {
//!         commands.spawn((Camera3d::default(), Transform::from_xyz(0.0, 6.0, 0.0)));
//!         commands.spawn((DirectionalLight::default(), Transform::default()
//!             .looking_to(Vec3::new(-0.8, -0.4, -0.4), Vec3::Y)));
//!         // A 6 × 2.4 × 1.2 m hull of 3 t; give it a mesh to see it.
//!         commands.spawn((Buoyancy::boat(6.0, 2.4, 1.2, 3000.0), Transform::default()));
//!     })
//!     .run();
//! ```
//!
//! - [`OceanSettings`]: the sea (spectrum, grids, choppiness, foam); changing it changes the
//!   sea live (a transition of the weather, not a rebuild).
//! - [`OceanClock`]: Bevy's virtual time, or a time the game sets (a server's).
//! - The simulation steps on Bevy's `AsyncComputeTaskPool` while the frame renders
//!   ([`OceanSystems`] says where in the frame); the render world uploads its textures.
//! - [`Buoyancy`] bodies float kinematically, or hand a [`BuoyancyForce`] to a physics
//!   engine; [`Water`] answers height and normal queries. A [`Wake`] on a body makes it
//!   leave a Kelvin wake and a foam trail, in the queries and on the water drawn.
//! - With rendering (an app whose plugins include Bevy's `PbrPlugin`), the water is drawn
//!   on a clipmap that follows the camera ([`OceanCamera`], or the first 3D camera) with an
//!   [`OceanMaterial`], under a sky dome of the same shader; [`OceanAppearance`] holds the
//!   palette. Without it (`MinimalPlugins`, a server) the plugin simulates only.
//!
//! [ocean-fft]: ocean_fft

mod buoyancy;
mod render;
mod settings;
mod sim;
mod wake;
mod water;

use bevy::prelude::*;

pub use buoyancy::{Buoyancy, BuoyancyForce, BuoyancyMotion, BuoyancyPoint, SEA_WATER_DENSITY};
pub use ocean_fft;
pub use ocean_fft_render;
pub use ocean_fft_render::{OceanInfo, SeaSettings, Texels};
pub use render::{
    OceanAppearance, OceanCamera, OceanMaterial, OceanRender, OceanRing, OceanSky,
    OceanSkyMaterial, UniformBlock, UploadTime,
};
pub use settings::{OceanClock, OceanSettings};
pub use sim::{OceanSim, OceanStatus, OceanTexels, PackedFrame};
pub use wake::{Wake, WakeInput, WakeTrack, WakeWindow};
pub use water::Water;

/// The plugin's types and the crate's presets, for `use bevy_ocean_fft::prelude::*`.
pub mod prelude {
    pub use crate::{
        Buoyancy, BuoyancyForce, OceanAppearance, OceanCamera, OceanClock, OceanPlugin,
        OceanSettings, OceanStatus, OceanSystems, Wake, Water,
    };
    pub use ocean_fft::{SeaState, Spectrum};
}

/// Where the plugin's systems run in a frame.
#[derive(SystemSet, Debug, Clone, PartialEq, Eq, Hash)]
pub enum OceanSystems {
    /// `First`: the stepped ocean comes back from its task (the frame waits for it if it is
    /// not done) and its texels are handed to the render world.
    Collect,
    /// `FixedUpdate`: the water's push on every [`Buoyancy`] body.
    Buoyancy,
    /// `Last`: the settings are applied and the ocean leaves for its next step.
    Launch,
}

/// The ocean: simulation, buoyancy, queries, and (when the app renders) the water and sky.
#[derive(Debug, Clone)]
pub struct OceanPlugin {
    /// Half-width of each clipmap ring in cells (even, 8 to 256): the finest ring has
    /// (2M + 1)² vertices 0.25 m apart, and each coarser ring doubles the spacing.
    pub ring_half_cells: u32,
    /// Most anisotropic filtering of the fragment stage's look-ups (1 to 16). On a GPU 16 keeps
    /// distant water sharp; on a software rasteriser (Mesa's lavapipe, as in CI) anything
    /// above 1 makes a frame take minutes.
    pub anisotropy: u16,
}

impl Default for OceanPlugin {
    fn default() -> Self {
        OceanPlugin {
            ring_half_cells: 64,
            anisotropy: 16,
        }
    }
}

impl Plugin for OceanPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<OceanSettings>()
            .init_resource::<OceanClock>()
            .init_resource::<OceanSim>()
            .init_resource::<OceanStatus>()
            .init_resource::<OceanTexels>()
            .init_resource::<WakeInput>()
            .init_resource::<WakeWindow>()
            .configure_sets(First, OceanSystems::Collect.after(bevy::time::TimeSystems))
            .add_systems(First, sim::collect.in_set(OceanSystems::Collect))
            .add_systems(
                FixedUpdate,
                buoyancy::float_bodies.in_set(OceanSystems::Buoyancy),
            )
            .add_systems(
                PostUpdate,
                wake::collect_hulls.after(bevy::transform::TransformSystems::Propagate),
            )
            .add_systems(Last, sim::launch.in_set(OceanSystems::Launch));
        if app.is_plugin_added::<bevy::pbr::PbrPlugin>() {
            app.add_plugins(render::OceanRenderPlugin {
                half_cells: self.ring_half_cells,
                anisotropy: self.anisotropy.clamp(1, 16),
            });
        }
    }
}
