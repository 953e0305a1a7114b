//! The coast's ground: the render layer's [`Terrain`] mesh (a vertex per depth-map cell with
//! its normal and colour) in a vertex and an index buffer, drawn by ocean.wgsl's
//! `vs_terrain`/`fs_terrain`.

use bytemuck::{Pod, Zeroable};
use ocean_fft_render::Terrain;
use wgpu::util::DeviceExt;

use super::Renderer;

/// A vertex of the ground: world position (m), unit normal, linear RGBA colour.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct TerrainVertex {
    position: [f32; 3],
    normal: [f32; 3],
    colour: [f32; 4],
}

/// The vertex buffer's layout (locations 0–2 of `vs_terrain`).
pub(super) fn layout() -> wgpu::VertexBufferLayout<'static> {
    const ATTRIBUTES: [wgpu::VertexAttribute; 3] =
        wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x4];
    wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<TerrainVertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &ATTRIBUTES,
    }
}

impl Renderer {
    /// The ground drawn from now on (`None`: none).
    pub fn set_terrain(&mut self, device: &wgpu::Device, terrain: Option<&Terrain>) {
        self.terrain = terrain.map(|t| {
            let vertices: Vec<TerrainVertex> = (0..t.positions.len())
                .map(|k| TerrainVertex {
                    position: t.positions[k],
                    normal: t.normals[k],
                    colour: t.colours[k],
                })
                .collect();
            let buffer = |label: &str, contents: &[u8], usage| {
                device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents,
                    usage,
                })
            };
            (
                buffer(
                    "terrain vertices",
                    bytemuck::cast_slice(&vertices),
                    wgpu::BufferUsages::VERTEX,
                ),
                buffer(
                    "terrain indices",
                    bytemuck::cast_slice(&t.indices),
                    wgpu::BufferUsages::INDEX,
                ),
                t.indices.len() as u32,
            )
        });
    }
}
