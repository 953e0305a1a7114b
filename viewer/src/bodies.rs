//! Floating bodies moved by the crate's CPU queries every frame: spar buoys that heave and
//! tilt with the water's normal, and boats that heave, pitch and roll on four points of the
//! water under them. One batch of `OceanState::surfaces_at` (on the simulation thread, right
//! after the step of the frame they are drawn in) answers every body and the eye.

use glam::{Mat4, Quat, Vec3};
use ocean_fft::SurfaceSample;

use crate::gpu::BodyInstance;

/// Half the boat's length and beam between its query points, m.
const BOAT_HALF_LENGTH: f32 = 4.0;
const BOAT_HALF_BEAM: f32 = 1.4;

/// The bodies, at fixed (moored) horizontal positions.
pub struct Fleet {
    /// (x, z) of each buoy.
    buoys: Vec<[f32; 2]>,
    /// (x, z, heading) of each boat.
    boats: Vec<[f32; 3]>,
    buoy_instances: Vec<BodyInstance>,
    boat_instances: Vec<BodyInstance>,
}

impl Fleet {
    /// A few buoys and boats in front of an eye at `eye` looking toward `heading` (degrees),
    /// none if `enabled` is false.
    pub fn new(eye: Vec3, heading: f32, enabled: bool) -> Fleet {
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
                vec![
                    {
                        let p = at(60.0, -14.0);
                        [p[0], p[1], h + 1.1]
                    },
                    {
                        let p = at(210.0, 40.0);
                        [p[0], p[1], h - 0.5]
                    },
                ],
            )
        } else {
            (Vec::new(), Vec::new())
        };
        let instance = BodyInstance {
            model: Mat4::IDENTITY.to_cols_array_2d(),
            colour: [0.0; 4],
        };
        Fleet {
            buoy_instances: vec![instance; buoys.len()],
            boat_instances: vec![instance; boats.len()],
            buoys,
            boats,
        }
    }

    /// Points queried every frame: one per buoy, bow, stern, port and starboard per boat,
    /// and the eye last.
    pub fn queries(&self, eye: Vec3) -> Vec<[f64; 2]> {
        let mut points = vec![[0.0; 2]; self.buoys.len() + 4 * self.boats.len() + 1];
        self.write_queries(eye, &mut points);
        points
    }

    /// Fills `points` (as long as [`Fleet::queries`] made it) for an eye at `eye`.
    pub fn write_queries(&self, eye: Vec3, points: &mut [[f64; 2]]) {
        let mut k = 0;
        for b in &self.buoys {
            points[k] = [f64::from(b[0]), f64::from(b[1])];
            k += 1;
        }
        for &[x, z, heading] in &self.boats {
            let along = [heading.cos(), heading.sin()];
            let across = [-along[1], along[0]];
            for (a, c) in [
                (BOAT_HALF_LENGTH, 0.0),
                (-BOAT_HALF_LENGTH, 0.0),
                (0.0, BOAT_HALF_BEAM),
                (0.0, -BOAT_HALF_BEAM),
            ] {
                points[k] = [
                    f64::from(x + a * along[0] + c * across[0]),
                    f64::from(z + a * along[1] + c * across[1]),
                ];
                k += 1;
            }
        }
        points[k] = [f64::from(eye.x), f64::from(eye.z)];
    }

    /// Places every body on the water of `samples` (the answers to the queries); returns the
    /// water height under the eye.
    pub fn place(&mut self, samples: &[SurfaceSample]) -> f32 {
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
        for (b, instance) in self.boats.iter().zip(&mut self.boat_instances) {
            let [bow, stern, port, starboard] = [0, 1, 2, 3].map(|i| samples[k + i].height);
            k += 4;
            let heave = 0.25 * (bow + stern + port + starboard);
            let pitch = ((bow - stern) / (2.0 * BOAT_HALF_LENGTH)).atan();
            let roll = ((port - starboard) / (2.0 * BOAT_HALF_BEAM)).atan();
            // Local x is the bow, z is port: yaw turns x to the heading (about −y, as a
            // heading θ is the direction (cos θ, sin θ) in (x, z)), pitch lifts the bow
            // (about z), roll lifts port (about −x).
            let rotation = Quat::from_rotation_y(-b[2])
                * Quat::from_rotation_z(pitch)
                * Quat::from_rotation_x(-roll);
            let model = Mat4::from_rotation_translation(rotation, Vec3::new(b[0], heave, b[1]));
            *instance = BodyInstance {
                model: model.to_cols_array_2d(),
                colour: [0.75, 0.74, 0.70, 1.0],
            };
        }
        samples[k].height
    }

    pub fn buoys(&self) -> &[BodyInstance] {
        &self.buoy_instances
    }

    pub fn boats(&self) -> &[BodyInstance] {
        &self.boat_instances
    }
}
