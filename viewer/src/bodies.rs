//! Floating bodies moved by the crate's CPU queries every frame: spar buoys that heave and
//! tilt with the water's normal, and boats that float, bodies of the render layer's model
//! (`ocean_fft_render::floater`, the Bevy plugin's too): the water's push on their columns
//! heaves, pitches and rolls them. One batch of `OceanState::surfaces_at` (on the simulation
//! thread, right after the step of the frame they are drawn in) answers every body and the
//! eye.
//!
//! The boats make wakes: each frame they are handed to the ocean as hulls
//! ([`Fleet::hulls`], the render layer's `hull_of` of their bodies), moving ahead along their
//! heading at [`Fleet::speed`].
//!
//! The buoys stay kinematic: a spar stands upright by its ballast, deep below its buoyancy,
//! which the model's vertical columns (righted by their water-plane spread) do not hold, and
//! following half the water's normal looks right at one query a buoy.

use std::f32::consts::FRAC_PI_2;

use glam::{Mat4, Quat, Vec3};
use ocean_fft::{Hull, SurfaceSample};
use ocean_fft_render::{hull_of, Body, Floater, Pose, SEA_WATER_DENSITY};

use crate::gpu::BodyInstance;

/// The boat's hull as it floats (the box of `gpu::boat`'s mesh, bow wedge included), m.
const BOAT_LENGTH: f32 = 9.0;
const BOAT_BEAM: f32 = 3.0;
/// From the keel (the mesh's y = −0.7) to the deck (0.9), m.
const BOAT_HEIGHT: f32 = 1.6;
/// The draft at rest, m: the mesh's waterline (y = 0) is 0.7 m above its keel. The boat's
/// mass, ρ·L·B·draft = 19.4 t, makes it so.
const BOAT_DRAFT: f32 = 0.7;

/// A boat: a floating body and the heading it keeps (radians; x and z stay too).
struct Boat {
    floater: Floater,
    heading: f32,
}

/// The bodies: buoys at fixed horizontal positions, boats moored or going ahead.
pub struct Fleet {
    /// The boats' speed ahead, m/s (0: moored).
    pub speed: f32,
    /// How far the first boat moved (x, z; m) in the last [`Fleet::place`].
    pub lead_moved: [f32; 2],
    /// (x, z) of each buoy.
    buoys: Vec<[f32; 2]>,
    boats: Vec<Boat>,
    /// Whether the boats have been put on the water (at the first answers).
    afloat: bool,
    /// The water heights above one boat's columns (scratch).
    heights: Vec<f32>,
    buoy_instances: Vec<BodyInstance>,
    boat_instances: Vec<BodyInstance>,
}

/// A boat's body: its hull as a box with the mesh's draft.
fn boat_body() -> Body {
    let mass = SEA_WATER_DENSITY * BOAT_LENGTH * BOAT_BEAM * BOAT_DRAFT;
    Body::boat(BOAT_LENGTH, BOAT_BEAM, BOAT_HEIGHT, mass)
}

/// From the boat mesh's frame (bow +x, waterline y = 0) to its body's (bow +z, the hull's
/// box centred on the origin).
fn boat_mesh_to_body() -> Mat4 {
    Mat4::from_rotation_translation(
        Quat::from_rotation_y(-FRAC_PI_2),
        Vec3::new(0.0, BOAT_DRAFT - 0.5 * BOAT_HEIGHT, 0.0),
    )
}

impl Fleet {
    /// A few buoys and boats in front of an eye at `eye` looking toward `heading` (degrees),
    /// none if `enabled` is false.
    pub fn new(eye: Vec3, heading: f32, enabled: bool, speed: f32) -> Fleet {
        let h = heading.to_radians();
        let at = |distance: f32, side: f32| {
            let (c, s) = (h.cos(), h.sin());
            [
                eye.x + distance * c - side * s,
                eye.z + distance * s + side * c,
            ]
        };
        let (buoys, boats) = if enabled {
            (
                vec![
                    at(22.0, -6.0),
                    at(45.0, 10.0),
                    at(90.0, -25.0),
                    at(160.0, 30.0),
                ],
                vec![(at(60.0, -14.0), h + 1.1), (at(210.0, 40.0), h - 0.5)],
            )
        } else {
            (Vec::new(), Vec::new())
        };
        let instance = BodyInstance {
            model: Mat4::IDENTITY.to_cols_array_2d(),
            colour: [0.0; 4],
        };
        // At the still water line until the first answers put them on the water.
        let body = boat_body();
        let rest = -body.rest_depth();
        let boats: Vec<Boat> = boats
            .into_iter()
            .map(|([x, z], heading)| Boat {
                floater: Floater::new(body.clone(), Pose::new([x, rest, z], heading)),
                heading,
            })
            .collect();
        Fleet {
            speed,
            lead_moved: [0.0; 2],
            buoy_instances: vec![instance; buoys.len()],
            boat_instances: vec![instance; boats.len()],
            buoys,
            boats,
            afloat: false,
            heights: Vec::with_capacity(body.columns.len()),
        }
    }

    /// The first boat's stern at its waterline (m) and its heading (radians from +x toward
    /// +z), if there is a boat.
    pub fn stern(&self) -> Option<(Vec3, f32)> {
        let boat = self.boats.first()?;
        let [x, y, z] = boat.floater.pose.position;
        let back = 0.5 * BOAT_LENGTH;
        let (c, s) = (boat.heading.cos(), boat.heading.sin());
        Some((Vec3::new(x - back * c, y, z - back * s), boat.heading))
    }

    /// Points queried every frame: one per buoy, one per column of each boat (as it floats
    /// now), and the eye last.
    pub fn queries(&mut self, eye: Vec3) -> Vec<[f64; 2]> {
        let columns: usize = self.boats.iter().map(|b| b.floater.query_count()).sum();
        let mut points = vec![[0.0; 2]; self.buoys.len() + columns + 1];
        self.write_queries(eye, &mut points);
        points
    }

    /// Fills `points` (as long as [`Fleet::queries`] made it) for an eye at `eye`.
    pub fn write_queries(&mut self, eye: Vec3, points: &mut [[f64; 2]]) {
        let mut k = 0;
        for b in &self.buoys {
            points[k] = [f64::from(b[0]), f64::from(b[1])];
            k += 1;
        }
        for boat in &mut self.boats {
            let n = boat.floater.query_count();
            boat.floater.write_queries(&mut points[k..k + n]);
            k += n;
        }
        points[k] = [f64::from(eye.x), f64::from(eye.z)];
    }

    /// Places every body on the water of `samples` (the answers to the queries), the boats
    /// floated for `dt` seconds of sea time (put at rest on the water at the first answers);
    /// returns the water height under the eye.
    pub fn place(&mut self, samples: &[SurfaceSample], dt: f32) -> f32 {
        let mut k = 0;
        for (b, instance) in self.buoys.iter().zip(&mut self.buoy_instances) {
            let s = &samples[k];
            k += 1;
            // A spar follows the water's normal half way (its own inertia resists the rest).
            let normal = Vec3::from_array(s.normal)
                .lerp(Vec3::Y, 0.5)
                .normalize_or(Vec3::Y);
            let tilt = Quat::from_rotation_arc(Vec3::Y, normal);
            let model = Mat4::from_rotation_translation(tilt, Vec3::new(b[0], s.height, b[1]));
            *instance = BodyInstance {
                model: model.to_cols_array_2d(),
                colour: [0.55, 0.06, 0.03, 1.0],
            };
        }
        let mesh = boat_mesh_to_body();
        self.lead_moved = [0.0; 2];
        for (index, (boat, instance)) in self
            .boats
            .iter_mut()
            .zip(&mut self.boat_instances)
            .enumerate()
        {
            let floater = &mut boat.floater;
            let n = floater.query_count();
            self.heights.clear();
            self.heights
                .extend(samples[k..k + n].iter().map(|s| s.height));
            k += n;
            if self.afloat {
                floater.float(&self.heights, dt);
            } else {
                floater.settle(&self.heights);
            }
            // The step keeps x, z and the spin about y; the heading is kept exactly against
            // the drift of many small tilts.
            floater.pose.set_heading(boat.heading);
            if self.afloat {
                let step = self.speed * dt;
                let moved = [step * boat.heading.cos(), step * boat.heading.sin()];
                floater.pose.position[0] += moved[0];
                floater.pose.position[2] += moved[1];
                if index == 0 {
                    self.lead_moved = moved;
                }
            }
            let pose = floater.pose;
            let model = Mat4::from_rotation_translation(
                Quat::from_array(pose.rotation),
                Vec3::from_array(pose.position),
            ) * mesh;
            *instance = BodyInstance {
                model: model.to_cols_array_2d(),
                colour: [0.75, 0.74, 0.70, 1.0],
            };
        }
        self.afloat = true;
        samples[k].height
    }

    /// The boats as the ocean's hulls (their waterplanes, going ahead at [`Fleet::speed`]),
    /// into `out`.
    pub fn hulls(&self, out: &mut Vec<Hull>) {
        out.clear();
        out.extend(self.boats.iter().map(|boat| {
            let v = [
                self.speed * boat.heading.cos(),
                self.speed * boat.heading.sin(),
            ];
            hull_of(&boat.floater.body, &boat.floater.pose, v)
        }));
    }

    pub fn buoys(&self) -> &[BodyInstance] {
        &self.buoy_instances
    }

    pub fn boats(&self) -> &[BodyInstance] {
        &self.boat_instances
    }
}
