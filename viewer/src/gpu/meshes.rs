//! The floating bodies' meshes: a buoy and a boat of flat-shaded quads.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

/// A vertex of a body's mesh: position and normal in the body's frame (m).
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub(super) struct BodyVertex {
    position: [f32; 3],
    normal: [f32; 3],
}

fn push_quad(vertices: &mut Vec<BodyVertex>, indices: &mut Vec<u32>, corners: [Vec3; 4]) {
    let normal = (corners[1] - corners[0])
        .cross(corners[2] - corners[0])
        .normalize_or(Vec3::Y);
    let base = vertices.len() as u32;
    for c in corners {
        vertices.push(BodyVertex {
            position: c.to_array(),
            normal: normal.to_array(),
        });
    }
    indices.extend_from_slice(&[base, base + 1, base + 2, base, base + 2, base + 3]);
}

/// A box from `min` to `max`.
fn push_box(vertices: &mut Vec<BodyVertex>, indices: &mut Vec<u32>, min: Vec3, max: Vec3) {
    let p = |x: bool, y: bool, z: bool| {
        Vec3::new(
            if x { max.x } else { min.x },
            if y { max.y } else { min.y },
            if z { max.z } else { min.z },
        )
    };
    let faces = [
        [
            p(true, false, false),
            p(true, true, false),
            p(true, true, true),
            p(true, false, true),
        ],
        [
            p(false, false, true),
            p(false, true, true),
            p(false, true, false),
            p(false, false, false),
        ],
        [
            p(false, true, false),
            p(false, true, true),
            p(true, true, true),
            p(true, true, false),
        ],
        [
            p(false, false, true),
            p(false, false, false),
            p(true, false, false),
            p(true, false, true),
        ],
        [
            p(false, false, true),
            p(true, false, true),
            p(true, true, true),
            p(false, true, true),
        ],
        [
            p(true, false, false),
            p(false, false, false),
            p(false, true, false),
            p(true, true, false),
        ],
    ];
    for face in faces {
        push_quad(vertices, indices, face);
    }
}

/// A spar buoy: a cylinder 2.2 m tall (0.8 m of it under water) of radius 0.5 m with a cone
/// on top, y up, the waterline at y = 0.
pub(super) fn buoy() -> (Vec<BodyVertex>, Vec<u32>) {
    let (mut vertices, mut indices) = (Vec::new(), Vec::new());
    let segments = 16;
    let ring = |k: usize, r: f32, y: f32| {
        let a = k as f32 / segments as f32 * std::f32::consts::TAU;
        Vec3::new(r * a.cos(), y, r * a.sin())
    };
    for k in 0..segments {
        let (k1, k0) = (k, k + 1);
        push_quad(
            &mut vertices,
            &mut indices,
            [
                ring(k0, 0.5, -0.8),
                ring(k0, 0.5, 1.4),
                ring(k1, 0.5, 1.4),
                ring(k1, 0.5, -0.8),
            ],
        );
        push_quad(
            &mut vertices,
            &mut indices,
            [
                ring(k0, 0.5, 1.4),
                ring(k0, 0.05, 2.6),
                ring(k1, 0.05, 2.6),
                ring(k1, 0.5, 1.4),
            ],
        );
    }
    (vertices, indices)
}

/// A small boat: a hull 9 m long (along x) and 3 m wide with a cabin, y up, the waterline at
/// y = 0.
pub(super) fn boat() -> (Vec<BodyVertex>, Vec<u32>) {
    let (mut vertices, mut indices) = (Vec::new(), Vec::new());
    push_box(
        &mut vertices,
        &mut indices,
        Vec3::new(-4.5, -0.7, -1.5),
        Vec3::new(3.0, 0.9, 1.5),
    );
    // The bow: a wedge from the hull's front to a point.
    let (top, bottom) = (0.9, -0.7);
    let tip_top = Vec3::new(5.5, top + 0.3, 0.0);
    let tip_bottom = Vec3::new(4.6, bottom, 0.0);
    push_quad(
        &mut vertices,
        &mut indices,
        [
            Vec3::new(3.0, bottom, 1.5),
            tip_bottom,
            tip_top,
            Vec3::new(3.0, top, 1.5),
        ],
    );
    push_quad(
        &mut vertices,
        &mut indices,
        [
            tip_bottom,
            Vec3::new(3.0, bottom, -1.5),
            Vec3::new(3.0, top, -1.5),
            tip_top,
        ],
    );
    push_quad(
        &mut vertices,
        &mut indices,
        [
            Vec3::new(3.0, top, 1.5),
            tip_top,
            tip_top,
            Vec3::new(3.0, top, -1.5),
        ],
    );
    push_box(
        &mut vertices,
        &mut indices,
        Vec3::new(-3.5, 0.9, -1.1),
        Vec3::new(0.5, 2.6, 1.1),
    );
    (vertices, indices)
}
