//! A frame's uniforms: the camera, the light, the ocean's inputs and the clipmap's rings.

use bytemuck::Zeroable;
use glam::{Mat4, Vec3};

use ocean_fft_render::clipmap::{rings, Ring, MAX_RINGS};
use ocean_fft_render::{Light, OceanInfo, Tiling};

use super::{Globals, RenderSettings, Renderer, View};

impl Renderer {
    /// The uniforms of a frame seen from `view` at `size` pixels, in `light` with `exposure`.
    pub fn globals(
        &mut self,
        info: &OceanInfo,
        view: &View,
        (light, exposure): (&Light, f32),
        settings: &RenderSettings,
        size: (u32, u32),
    ) -> Globals {
        let aspect = size.0 as f32 / size.1.max(1) as f32;
        let projection = Mat4::perspective_infinite_reverse_rh(view.fov_y, aspect, 0.1);
        let look = Mat4::look_to_rh(view.eye, view.forward, Vec3::Y);
        let view_proj = projection * look;
        let mut g = Globals::zeroed();
        g.view_proj = view_proj.to_cols_array_2d();
        g.inverse_view_proj = view_proj.inverse().to_cols_array_2d();
        g.eye = [view.eye.x, view.eye.y, view.eye.z, info.time as f32];
        g.ocean.set_light(light, 1.0, exposure);
        let tiling = Tiling {
            strength: settings.tiling,
            scale: settings.tiling_scale,
            ..Tiling::default()
        };
        g.ocean.set_ocean(info, [view.eye.x, view.eye.z], &tiling);
        g.ocean.wake = self.wake;
        [g.ocean.coast, g.ocean.coast_size] = self.coast;
        if !self.streaks_bound {
            g.ocean.streak_scale = [0.0; 4];
        }
        let mut ring_list = [Ring::default(); MAX_RINGS];
        let count = rings(
            [view.eye.x, view.eye.z],
            view.height_above_water,
            self.half_cells,
            &mut ring_list,
        );
        for (level, ring) in g.levels.iter_mut().zip(&ring_list[..count]) {
            *level = [
                ring.centre[0],
                ring.centre[1],
                ring.spacing,
                self.half_cells as f32,
            ];
        }
        self.ring_meshes = ring_list.map(|r| r.hole);
        g.ocean.tiling[3] = count as f32;
        let side = (2 * self.half_cells + 1) as usize;
        self.rings_drawn = (count, count * side * side);
        g
    }
}
