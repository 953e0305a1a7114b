//! ocean-fft on macroquad: the functions docs/guide/rendering.md shows in "Using ocean-fft
//! from Bevy, wgpu, macroquad and Godot", compiled by CI (never run: CI has no window). The guide quotes
//! the code between the `// guide:` markers verbatim; the root crate's test `tests/guide.rs`
//! fails if the two drift apart.

// guide: macroquad
use macroquad::math::{Vec2, Vec3};
use macroquad::models::{Mesh, Vertex as MqVertex};
use macroquad::texture::Texture2D;
use ocean_fft::gpu::{NormalMapGreen, Vertex};
use ocean_fft::{Cascade, Error, OceanState};

/// macroquad draws a mesh in one draw call only if its buffers hold it: raise the capacities
/// (the defaults are 10 000 vertices and 5 000 indices) for an N×N cascade mesh.
pub fn window_conf(n: usize) -> macroquad::conf::Conf {
    macroquad::conf::Conf {
        miniquad_conf: macroquad::miniquad::conf::Conf {
            window_title: "ocean".to_owned(),
            ..Default::default()
        },
        draw_call_vertex_capacity: n * n + 1,
        draw_call_index_capacity: 6 * n.saturating_sub(1).pow(2) + 1,
        ..Default::default()
    }
}

/// A mesh for `cascade` (once): macroquad's indices are u16, so N ≤ 256 (None above). Each
/// vertex's uv is its texel's centre.
pub fn ocean_mesh(cascade: &Cascade) -> Option<Mesh> {
    let n = cascade.size();
    let indices = cascade.triangle_indices().flatten().map(u16::try_from);
    let uv = |k: usize| Vec2::new((k % n) as f32 + 0.5, (k / n) as f32 + 0.5) / n as f32;
    Some(Mesh {
        vertices: (0..n * n)
            .map(|k| MqVertex::new2(Vec3::ZERO, uv(k), macroquad::color::WHITE))
            .collect(),
        indices: indices.collect::<Result<_, _>>().ok()?,
        texture: None,
    })
}

/// Every frame, after `ocean.step(dt)`: the cascade's displaced vertices into the mesh.
/// macroquad's `Vertex` has a layout of its own (position, uv, colour, normal), so this
/// copies; its default material has no lighting, so the colour is shaded here from the normal.
pub fn update_mesh(
    cascade: &Cascade,
    vertices: &mut [Vertex],
    mesh: &mut Mesh,
    sun: Vec3,
) -> Result<(), Error> {
    cascade.write_vertices(vertices)?;
    for (out, v) in mesh.vertices.iter_mut().zip(vertices.iter()) {
        let normal = Vec3::from_array(v.normal);
        let light = normal.dot(sun).max(0.0);
        out.position = Vec3::from_array(v.position);
        out.normal = normal.extend(0.0);
        out.color = [
            (10.0 + 60.0 * light) as u8,
            (40.0 + 90.0 * light) as u8,
            (70.0 + 120.0 * light) as u8,
            255,
        ];
    }
    Ok(())
}

/// For a custom material: the cascade's normal map in an RGBA8 texture (the only format
/// macroquad's safe API uploads), made once with `Texture2D::from_rgba8`. With DirectX green
/// a shader decodes the world normal as (r, b, g)·2 − 1, no tangent frame needed.
pub fn update_normal_map(
    cascade: &Cascade,
    pixels: &mut [[u8; 4]],
    texture: &Texture2D,
) -> Result<(), Error> {
    cascade.write_normal_map(NormalMapGreen::DirectX, pixels)?;
    let n = cascade.size() as u32;
    texture.update_from_bytes(n, n, pixels.as_flattened()); // a view of `pixels`, no copy
    Ok(())
}

/// A boat on the water: macroquad's 3D frame (`Camera3D`: right-handed, y up, and metres if
/// you say so) is the crate's, so its x and z go to `height_at` as they are.
pub fn on_water(ocean: &OceanState, position: Vec3) -> Result<Vec3, Error> {
    let height = ocean
        .water()
        .height_at(f64::from(position.x), f64::from(position.z))?;
    Ok(Vec3::new(position.x, height, position.z))
}
// guide: end
