//! Things that float: [`Buoyancy`] bodies, moved by the plugin (kinematically) or handed as
//! forces to a physics engine ([`BuoyancyForce`]).
//!
//! A body is a set of vertical columns ([`BuoyancyPoint`]s) fixed to it. Every fixed update
//! the plugin asks the ocean for the water height above every column of every body in one
//! batch (`OceanState::heights_at`), and each column pushes up with the weight of the water
//! it displaces, ρ·g·V·(submerged fraction) (Archimedes), at its centre, and resists motion
//! through the water with a linear drag. Summed over the columns these give a force and a
//! torque about the body's origin (its centre of mass).

use bevy::prelude::*;
use ocean_fft::GRAVITY;

use crate::sim::OceanSim;

/// Density of sea water, kg/m³.
pub const SEA_WATER_DENSITY: f32 = 1025.0;

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
/// the root of the hierarchy).
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
        let (along, across) = (4usize, 2usize);
        let volume = length * beam * height / (along * across) as f32;
        let mut points = Vec::with_capacity(along * across);
        for i in 0..along {
            for j in 0..across {
                let z = ((i as f32 + 0.5) / along as f32 - 0.5) * length;
                let x = ((j as f32 + 0.5) / across as f32 - 0.5) * beam;
                points.push(BuoyancyPoint {
                    offset: Vec3::new(x, 0.0, z),
                    volume,
                    height,
                });
            }
        }
        let inertia = Vec3::new(
            height * height + length * length,
            beam * beam + length * length,
            beam * beam + height * height,
        ) * mass
            / 12.0;
        // Heave frequency ω = √(ρ g A / m) with the water-plane area A; ζ = damping/(2ω).
        let area = length * beam;
        let omega = (SEA_WATER_DENSITY * GRAVITY * area / mass).sqrt();
        Buoyancy {
            points,
            mass,
            inertia,
            damping: 0.7 * omega,
            water_density: SEA_WATER_DENSITY,
        }
    }

    /// Depth of the body's origin under the still water line when it floats at rest on a
    /// flat sea, m, for bodies whose columns all have the same height and stand level
    /// (`Buoyancy::boat`): the draft d with ρ·A·d = m, A the columns' water-plane area,
    /// minus half the columns' height.
    pub fn rest_depth(&self) -> f32 {
        let area: f32 = self.points.iter().map(|p| p.volume / p.height).sum();
        let height = self.points.first().map_or(0.0, |p| p.height);
        self.mass / (self.water_density * area) - 0.5 * height
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
    previous: Vec<Vec3>,
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

/// Force and torque of the water on a body at `transform` whose columns are at the world
/// positions `world` with velocities `velocity`, above which the water stands at `heights`.
fn water_push(
    body: &Buoyancy,
    transform: &Transform,
    world: &[Vec3],
    velocity: impl Fn(usize) -> Vec3,
    heights: &[f32],
) -> BuoyancyForce {
    let mut push = BuoyancyForce::default();
    for (i, point) in body.points.iter().enumerate() {
        let bottom = world[i].y - 0.5 * point.height;
        let fraction = ((heights[i] - bottom) / point.height).clamp(0.0, 1.0);
        let submerged = point.volume * fraction;
        let mut force = Vec3::Y * (body.water_density * GRAVITY * submerged);
        force -= velocity(i) * (body.damping * body.water_density * submerged);
        push.force += force;
        push.torque += (world[i] - transform.translation).cross(force);
        push.submerged_volume += submerged;
    }
    push
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
    mut points: Local<Vec<[f64; 2]>>,
    mut heights: Local<Vec<f32>>,
    mut world: Local<Vec<Vec3>>,
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
    for (body, transform, _, _) in &bodies {
        for point in &body.points {
            let p = transform.transform_point(point.offset);
            world.push(p);
            points.push([f64::from(p.x), f64::from(p.z)]);
        }
    }
    heights.clear();
    heights.resize(points.len(), 0.0);
    if ocean.heights_at(&points, &mut heights).is_err() {
        return;
    }
    let mut start = 0;
    for (body, mut transform, mut motion, force) in &mut bodies {
        let end = start + body.points.len();
        let (world, heights) = (&world[start..end], &heights[start..end]);
        start = end;
        if motion.previous.len() != world.len() {
            motion.previous = world.to_vec();
        }
        match force {
            Some(mut out) => {
                let previous = &motion.previous;
                *out = water_push(
                    body,
                    &transform,
                    world,
                    |i| (world[i] - previous[i]) / dt,
                    heights,
                );
            }
            None => {
                let (v, w, centre) = (
                    motion.velocity,
                    motion.angular_velocity,
                    transform.translation,
                );
                let push = water_push(
                    body,
                    &transform,
                    world,
                    |i| v + w.cross(world[i] - centre),
                    heights,
                );
                integrate(body, &mut transform, &mut motion, &push, dt);
            }
        }
        motion.previous.clear();
        motion.previous.extend_from_slice(world);
    }
}

/// One semi-implicit Euler step of heave, pitch and roll under gravity and `push`.
fn integrate(
    body: &Buoyancy,
    transform: &mut Transform,
    motion: &mut BuoyancyMotion,
    push: &BuoyancyForce,
    dt: f32,
) {
    let acceleration = push.force / body.mass - Vec3::Y * GRAVITY;
    motion.velocity.y += acceleration.y * dt;
    motion.velocity.x = 0.0;
    motion.velocity.z = 0.0;
    // The inverse inertia in the world frame: R · diag(1/I) · Rᵀ.
    let rotation = transform.rotation;
    let local_torque = rotation.inverse() * push.torque;
    let local_alpha = local_torque / body.inertia.max(Vec3::splat(1e-6));
    motion.angular_velocity += (rotation * local_alpha) * dt;
    motion.angular_velocity.y = 0.0;
    transform.translation.y += motion.velocity.y * dt;
    let turn = Quat::from_scaled_axis(motion.angular_velocity * dt);
    transform.rotation = (turn * rotation).normalize();
}
