//! [`Water`]: gameplay queries of the simulated surface.

use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use ocean_fft::{OceanState, SurfaceSample};

use crate::sim::OceanSim;

/// The water surface for gameplay: height and normal at a point, from the same ocean the
/// frame draws (its textures and these answers are the same sea time). Available from
/// `First` to `PostUpdate` once the first ocean is built; every method returns `None` before
/// that (and in `Last`, when the ocean is stepping).
///
/// World x and z are the sea's x and z (metres, y up; the still water level is y = 0).
///
/// ```no_run
/// use bevy::prelude::*;
/// use bevy_ocean_fft::Water;
///
/// fn splash(water: Water, swimmers: Query<&Transform, With<Name>>) {
///     for transform in &swimmers {
///         let p = transform.translation;
///         if let Some(height) = water.height(p.x, p.z) {
///             if p.y < height {
///                 info!("under water by {:.2} m", height - p.y);
///             }
///         }
///     }
/// }
/// ```
#[derive(SystemParam)]
pub struct Water<'w> {
    sim: Res<'w, OceanSim>,
}

impl Water<'_> {
    /// The ocean itself, for the crate's whole query API (`water().surfaces_at` for many
    /// points at once, `foam_view().foam_at`, …).
    pub fn ocean(&self) -> Option<&OceanState> {
        self.sim.ocean()
    }

    /// Height of the water surface (m) above world point (x, z) (m): the displaced surface
    /// that lies over that point, not the water displaced from it.
    pub fn height(&self, x: f32, z: f32) -> Option<f32> {
        self.ocean()?
            .water()
            .height_at(f64::from(x), f64::from(z))
            .ok()
    }

    /// Unit normal of the water surface above world point (x, z) (m), y up.
    pub fn normal(&self, x: f32, z: f32) -> Option<Vec3> {
        self.surface(x, z).map(|s| Vec3::from_array(s.normal))
    }

    /// Everything about the surface above (x, z): height, displacement, slope, normal, foam.
    pub fn surface(&self, x: f32, z: f32) -> Option<SurfaceSample> {
        self.ocean()?
            .water()
            .surface_at(f64::from(x), f64::from(z))
            .ok()
    }

    /// Sea time of the water, s.
    pub fn time(&self) -> Option<f64> {
        self.ocean().map(OceanState::time)
    }
}
