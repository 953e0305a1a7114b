//! Things that float: [`Buoyancy`] bodies, moved by the plugin (kinematically) or handed as
//! forces to a physics engine ([`BuoyancyForce`]).
//!
//! A body is a set of vertical columns ([`BuoyancyPoint`]s) fixed to it. Every fixed update
//! the plugin asks the ocean for the water height above every column of every body in one
//! batch (`OceanState::heights_at`), and each column pushes up with the weight of the water
//! it displaces, ρ·g·V·(submerged fraction) (Archimedes), at its centre, and resists motion
//! through the water with a linear drag. Summed over the columns these give a force and a
//! torque about the body's origin (its centre of mass). The model, the push and the step are
//! the render layer's (`ocean_fft_render::floater`, which the viewer's boats float with);
//! this module holds the Bevy glue: components, the system, `Vec3`/`Transform` conversions.

use bevy::prelude::*;
use ocean_fft_render::{Body, Column, Motion, Pose, Push, Velocities};

use crate::sim::OceanSim;

/// Density of sea water, kg/m³.
pub use ocean_fft_render::SEA_WATER_DENSITY;

/// A vertical column of a floating body: its share of the body's volume.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BuoyancyPoint {
    /// Centre of the column in the body's frame, m.
    pub offset: Vec3,
    /// Volume of the column, m³ (displaced when it is fully under water).
    pub volume: f32,
    /// Height of the column, m: it is under water from its bottom (`offset.y − height/2`)
    /// up to the water line.
    pub height: f32,
}

/// Makes an entity float on the plugin's ocean. Without [`BuoyancyForce`] the plugin moves
/// the entity itself every fixed update (kinematic mode): it heaves, pitches and rolls with
/// the waves under its own weight, its buoyancy and the water's drag; x, z and the heading
/// stay the game's. With a [`BuoyancyForce`] component the plugin only writes the force and
/// torque there, for a physics engine to apply (see its docs).
///
/// The entity's `Transform` is its centre of mass, in world space (put floating bodies at
/// the root of the hierarchy); its scale does not apply to the columns, whose offsets,
/// volumes and heights are in metres. The render layer's `ocean_fft_render::Body` is the same
/// model (`Body::from(&buoyancy)`, `Buoyancy::from(&body)`).
#[derive(Component, Debug, Clone, PartialEq)]
#[require(BuoyancyMotion)]
pub struct Buoyancy {
    /// The columns that displace water.
    pub points: Vec<BuoyancyPoint>,
    /// Mass, kg.
    pub mass: f32,
    /// Moments of inertia about the body's own x, y, z axes through its origin, kg·m²
    /// (kinematic mode).
    pub inertia: Vec3,
    /// Drag of the water on a submerged column per unit of its displaced mass, 1/s: a column
    /// moving at v through the water feels −damping·ρ·V_submerged·v. For a body floating at
    /// rest this damps its heave with the damping ratio damping/(2ω), ω its heave frequency.
    pub damping: f32,
    /// Density of the water, kg/m³.
    pub water_density: f32,
}

impl Buoyancy {
    /// A box-shaped hull `length` (along z) × `beam` (along x) × `height` (y) metres,
    /// centred on the origin, of `mass` kg: 4 × 2 columns, the inertia of a uniform box,
    /// and a drag that damps the heave to about a third of critical.
    pub fn boat(length: f32, beam: f32, height: f32, mass: f32) -> Buoyancy {
        Buoyancy::from(&Body::boat(length, beam, height, mass))
    }

    /// Depth of the body's origin under the still water line when it floats at rest on a
    /// flat sea, m, for bodies whose columns all have the same height and stand level
    /// (`Buoyancy::boat`): the draft d with ρ·A·d = m, A the columns' water-plane area,
    /// minus half the columns' height.
    pub fn rest_depth(&self) -> f32 {
        Body::from(self).rest_depth()
    }

    /// Writes this body into the render layer's `body`, reusing its columns' allocation.
    pub(crate) fn write(&self, body: &mut Body) {
        body.columns.clear();
        body.columns.extend(self.points.iter().map(|p| Column {
            offset: p.offset.to_array(),
            volume: p.volume,
            height: p.height,
        }));
        body.mass = self.mass;
        body.inertia = self.inertia.to_array();
        body.damping = self.damping;
        body.water_density = self.water_density;
    }
}

impl From<&Buoyancy> for Body {
    /// The render layer's model of the body.
    fn from(buoyancy: &Buoyancy) -> Body {
        let mut body = Body::default();
        buoyancy.write(&mut body);
        body
    }
}

impl From<&Body> for Buoyancy {
    /// A body of the render layer's model as a component.
    fn from(body: &Body) -> Buoyancy {
        Buoyancy {
            points: body
                .columns
                .iter()
                .map(|c| BuoyancyPoint {
                    offset: Vec3::from_array(c.offset),
                    volume: c.volume,
                    height: c.height,
                })
                .collect(),
            mass: body.mass,
            inertia: Vec3::from_array(body.inertia),
            damping: body.damping,
            water_density: body.water_density,
        }
    }
}

/// The kinematic mode's state: the body's velocity and angular velocity, world frame.
#[derive(Component, Debug, Clone, Default, PartialEq)]
pub struct BuoyancyMotion {
    /// m/s (only y moves in kinematic mode).
    pub velocity: Vec3,
    /// rad/s (no spin about y in kinematic mode).
    pub angular_velocity: Vec3,
    /// The columns' world positions at the last fixed update (their velocities in force
    /// mode).
    previous: Vec<[f32; 3]>,
}

/// The water's push on a [`Buoyancy`] body, written every fixed update for a physics engine
/// to apply; with this component the plugin does not move the body.
///
/// Buoyancy and drag only: the engine adds gravity. The torque is about the entity's origin,
/// which should be the body's centre of mass.
///
/// With avian (its `ExternalForce` / `ExternalTorque` components, or `Forces` in newer
/// releases) or bevy_rapier (`ExternalForce { force, torque }`), copy it over in
/// `FixedUpdate` after [`OceanSystems::Buoyancy`](crate::OceanSystems::Buoyancy):
///
/// ```ignore
/// // bevy_rapier3d: the engine's rigid body reads ExternalForce every step.
/// fn apply_buoyancy(mut bodies: Query<(&BuoyancyForce, &mut ExternalForce)>) {
///     for (water, mut external) in &mut bodies {
///         external.force = water.force;
///         external.torque = water.torque;
///     }
/// }
/// app.add_systems(FixedUpdate, apply_buoyancy.after(OceanSystems::Buoyancy));
/// ```
#[derive(Component, Debug, Clone, Copy, Default, PartialEq)]
pub struct BuoyancyForce {
    /// Force, N, world frame.
    pub force: Vec3,
    /// Torque about the entity's origin, N·m, world frame.
    pub torque: Vec3,
    /// Volume under water, m³.
    pub submerged_volume: f32,
}

impl From<Push> for BuoyancyForce {
    fn from(push: Push) -> BuoyancyForce {
        BuoyancyForce {
            force: Vec3::from_array(push.force),
            torque: Vec3::from_array(push.torque),
            submerged_volume: push.submerged_volume,
        }
    }
}

/// A transform's translation and rotation (its scale does not apply to the columns: their
/// offsets, volumes and heights are in metres).
fn pose(transform: &Transform) -> Pose {
    Pose {
        position: transform.translation.to_array(),
        rotation: transform.rotation.to_array(),
    }
}

/// `FixedUpdate`: the water's push on every floating body, from one batch of height
/// queries; kinematic bodies moved by it.
#[allow(clippy::type_complexity)]
pub(crate) fn float_bodies(
    sim: Res<OceanSim>,
    time: Res<Time>,
    mut bodies: Query<(
        &Buoyancy,
        &mut Transform,
        &mut BuoyancyMotion,
        Option<&mut BuoyancyForce>,
    )>,
    mut models: Local<Vec<Body>>,
    mut points: Local<Vec<[f64; 2]>>,
    mut heights: Local<Vec<f32>>,
    mut world: Local<Vec<[f32; 3]>>,
) {
    let Some(ocean) = sim.ocean() else {
        return;
    };
    let dt = time.delta_secs();
    if dt <= 0.0 {
        return;
    }
    points.clear();
    world.clear();
    for (i, (buoyancy, transform, _, _)) in bodies.iter().enumerate() {
        if models.len() == i {
            models.push(Body::default());
        }
        let body = &mut models[i];
        buoyancy.write(body);
        body.columns_at(&pose(transform), &mut world, &mut points);
    }
    heights.clear();
    heights.resize(points.len(), 0.0);
    if ocean.water().heights_at(&points, &mut heights).is_err() {
        return;
    }
    let mut start = 0;
    for ((_, mut transform, mut motion, force), body) in bodies.iter_mut().zip(models.iter()) {
        let end = start + body.columns.len();
        let (world, heights) = (&world[start..end], &heights[start..end]);
        start = end;
        if motion.previous.len() != world.len() {
            motion.previous = world.to_vec();
        }
        let mut pose = pose(&transform);
        match force {
            Some(mut out) => {
                let velocities = Velocities::Previous {
                    positions: &motion.previous,
                    dt,
                };
                *out = body.push(&pose, world, heights, velocities).into();
            }
            None => {
                let mut state = Motion {
                    velocity: motion.velocity.to_array(),
                    angular_velocity: motion.angular_velocity.to_array(),
                };
                let push = body.push(&pose, world, heights, Velocities::Motion(&state));
                body.step(&mut pose, &mut state, &push, dt);
                transform.translation = Vec3::from_array(pose.position);
                transform.rotation = Quat::from_array(pose.rotation);
                motion.velocity = Vec3::from_array(state.velocity);
                motion.angular_velocity = Vec3::from_array(state.angular_velocity);
            }
        }
        motion.previous.clear();
        motion.previous.extend_from_slice(world);
    }
}
