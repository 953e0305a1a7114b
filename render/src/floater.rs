//! Floating bodies: the water's push on a body made of vertical columns, and the kinematic
//! step that heaves, pitches and rolls it.
//!
//! A [`Body`] is a set of vertical [`Column`]s fixed to it, with a mass, moments of inertia, a
//! drag and the water's density. Every step an engine asks the ocean for the water height
//! above each column ([`Body::columns_at`] gives the points, in one batch with its other
//! queries), then [`Body::push`] sums the water's push: each column pushes up with the weight
//! of the water it displaces, ρ·g·V·(submerged fraction) (Archimedes), at its centre, and
//! resists motion through the water with a linear drag. [`Body::step`] moves the body under
//! that push and gravity: heave, pitch and roll only, as x, z and the heading are the game's.
//! A physics engine takes the [`Push`] instead. [`Floater`] holds a body with its pose and
//! motion for engines that move bodies themselves.
//!
//! Plain arrays in the API: positions `[f32; 3]` (x, y, z; m, y up), rotations `[f32; 4]`
//! (a unit quaternion x, y, z, w), so that no engine's math types meet here.

use glam::{Quat, Vec3};
use ocean_fft::GRAVITY;

/// Density of sea water, kg/m³.
pub const SEA_WATER_DENSITY: f32 = 1025.0;

/// A vertical column of a floating body: its share of the body's volume.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Column {
    /// Centre of the column in the body's frame, m.
    pub offset: [f32; 3],
    /// Volume of the column, m³ (displaced when it is fully under water).
    pub volume: f32,
    /// Height of the column, m: it is under water from its bottom (the centre's world y
    /// minus `height/2`) up to the water line. It stays vertical as the body tilts.
    pub height: f32,
}

/// A floating body: its columns, mass, inertia and drag.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Body {
    /// The columns that displace water.
    pub columns: Vec<Column>,
    /// Mass, kg.
    pub mass: f32,
    /// Moments of inertia about the body's own x, y, z axes through its origin (its centre of
    /// mass), kg·m².
    pub inertia: [f32; 3],
    /// Drag of the water on a submerged column per unit of its displaced mass, 1/s: a column
    /// moving at v (m/s) through the water feels −damping·ρ·V_submerged·v (N). For a body
    /// floating at rest this damps its heave with the damping ratio damping/(2ω), ω its heave
    /// frequency ([`Body::heave_frequency`]).
    pub damping: f32,
    /// Density of the water, kg/m³.
    pub water_density: f32,
}

/// Where a body is: its origin (centre of mass) and orientation, world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Position of the body's origin, m.
    pub position: [f32; 3],
    /// Rotation from the body's frame to the world's: a unit quaternion x, y, z, w.
    pub rotation: [f32; 4],
}

/// How a body moves, world frame.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Motion {
    /// Velocity of the body's origin, m/s (only y in [`Body::step`]).
    pub velocity: [f32; 3],
    /// Angular velocity, rad/s (no spin about y in [`Body::step`]).
    pub angular_velocity: [f32; 3],
}

/// The water's push on a body: buoyancy and drag, no gravity.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Push {
    /// Force, N, world frame.
    pub force: [f32; 3],
    /// Torque about the body's origin, N·m, world frame.
    pub torque: [f32; 3],
    /// Volume under water, m³.
    pub submerged_volume: f32,
}

/// How fast the columns move through the water, for the drag.
#[derive(Debug, Clone, Copy)]
pub enum Velocities<'a> {
    /// From the body's motion: a column at r from the origin moves at v + ω × r.
    Motion(&'a Motion),
    /// From where the columns were (world positions, m) `dt` seconds before: for bodies
    /// moved by something else, a physics engine.
    Previous { positions: &'a [[f32; 3]], dt: f32 },
}

impl Pose {
    /// A level body with its origin at `position` (m) and its bow, the body's +z axis (the
    /// length of [`Body::boat`]), toward `heading`: the direction (cos θ, sin θ) in (x, z),
    /// radians.
    pub fn new(position: [f32; 3], heading: f32) -> Pose {
        Pose {
            position,
            rotation: heading_rotation(heading).to_array(),
        }
    }

    /// The heading of the body's +z axis, radians (its direction (cos θ, sin θ) in (x, z),
    /// 0 if it points straight up or down).
    pub fn heading(&self) -> f32 {
        let bow = Quat::from_array(self.rotation) * Vec3::Z;
        if bow.x == 0.0 && bow.z == 0.0 {
            return 0.0;
        }
        bow.z.atan2(bow.x)
    }

    /// Turns the body about the vertical so that its heading is `heading` (radians), its tilt
    /// (pitch and roll) kept.
    pub fn set_heading(&mut self, heading: f32) {
        let turn = Quat::from_rotation_y(self.heading() - heading);
        self.rotation = (turn * Quat::from_array(self.rotation))
            .normalize()
            .to_array();
    }
}

impl Default for Pose {
    /// At the origin, level, heading 0 (the body's +z along the world's +x).
    fn default() -> Pose {
        Pose::new([0.0; 3], 0.0)
    }
}

/// The rotation that turns the body's +z to the heading θ: about y by π/2 − θ.
fn heading_rotation(heading: f32) -> Quat {
    Quat::from_rotation_y(std::f32::consts::FRAC_PI_2 - heading)
}

impl Body {
    /// A box-shaped hull `length` (along the body's z) × `beam` (along x) × `height` (y)
    /// metres, centred on the origin, of `mass` kg, in sea water: 4 × 2 columns, the
    /// inertia of a uniform box, and a drag that damps the heave to about a third of
    /// critical (damping ratio 0.35).
    pub fn boat(length: f32, beam: f32, height: f32, mass: f32) -> Body {
        let (along, across) = (4usize, 2usize);
        let volume = length * beam * height / (along * across) as f32;
        let mut columns = Vec::with_capacity(along * across);
        for i in 0..along {
            for j in 0..across {
                let z = ((i as f32 + 0.5) / along as f32 - 0.5) * length;
                let x = ((j as f32 + 0.5) / across as f32 - 0.5) * beam;
                columns.push(Column {
                    offset: [x, 0.0, z],
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
        Body {
            columns,
            mass,
            inertia: inertia.to_array(),
            damping: 0.7 * omega,
            water_density: SEA_WATER_DENSITY,
        }
    }

    /// The columns' water-plane area, m²: Σ volume/height.
    pub fn water_plane_area(&self) -> f32 {
        self.columns.iter().map(|c| c.volume / c.height).sum()
    }

    /// Depth of the body's origin under the still water line when it floats at rest on a
    /// flat sea, m (negative: above it), for bodies whose columns all have the same height
    /// and stand level ([`Body::boat`]): the draft d with ρ·A·d = m, A the columns'
    /// water-plane area, minus half the columns' height.
    pub fn rest_depth(&self) -> f32 {
        let height = self.columns.first().map_or(0.0, |c| c.height);
        self.mass / (self.water_density * self.water_plane_area()) - 0.5 * height
    }

    /// Angular frequency of the undamped heave about the rest depth, rad/s: √(ρ g A / m), A
    /// the water-plane area (while no column leaves the water or goes under).
    pub fn heave_frequency(&self) -> f32 {
        (self.water_density * GRAVITY * self.water_plane_area() / self.mass).sqrt()
    }

    /// Appends the world position (m) of every column's centre for a body at `pose` to
    /// `world`, and its (x, z) to `queries` (m; f64 as the ocean's batch queries take them):
    /// the points whose water heights [`Body::push`] needs, in the columns' order.
    pub fn columns_at(&self, pose: &Pose, world: &mut Vec<[f32; 3]>, queries: &mut Vec<[f64; 2]>) {
        for p in self.world_columns(pose) {
            world.push(p.to_array());
            queries.push([f64::from(p.x), f64::from(p.z)]);
        }
    }

    /// The columns' centres in the world for a body at `pose`, m.
    fn world_columns<'a>(&'a self, pose: &Pose) -> impl Iterator<Item = Vec3> + 'a {
        let rotation = Quat::from_array(pose.rotation);
        let position = Vec3::from_array(pose.position);
        self.columns
            .iter()
            .map(move |c| rotation * Vec3::from_array(c.offset) + position)
    }

    /// The water's push on the body at `pose` whose columns' centres are at `columns` (world,
    /// m, as [`Body::columns_at`] gives them) under water heights `heights` (m, one a column),
    /// the columns moving at `velocities`. Columns past the shorter of the slices push
    /// nothing.
    pub fn push(
        &self,
        pose: &Pose,
        columns: &[[f32; 3]],
        heights: &[f32],
        velocities: Velocities,
    ) -> Push {
        let centre = Vec3::from_array(pose.position);
        let (mut force, mut torque, mut submerged_volume) = (Vec3::ZERO, Vec3::ZERO, 0.0);
        for (i, ((column, &world), &height)) in
            self.columns.iter().zip(columns).zip(heights).enumerate()
        {
            let world = Vec3::from_array(world);
            let bottom = world.y - 0.5 * column.height;
            let fraction = ((height - bottom) / column.height).clamp(0.0, 1.0);
            let submerged = column.volume * fraction;
            let velocity = match velocities {
                Velocities::Motion(motion) => {
                    Vec3::from_array(motion.velocity)
                        + Vec3::from_array(motion.angular_velocity).cross(world - centre)
                }
                Velocities::Previous { positions, dt } => positions
                    .get(i)
                    .map_or(Vec3::ZERO, |&p| (world - Vec3::from_array(p)) / dt),
            };
            let mut up = Vec3::Y * (self.water_density * GRAVITY * submerged);
            up -= velocity * (self.damping * self.water_density * submerged);
            force += up;
            torque += (world - centre).cross(up);
            submerged_volume += submerged;
        }
        Push {
            force: force.to_array(),
            torque: torque.to_array(),
            submerged_volume,
        }
    }

    /// One semi-implicit Euler step of `dt` seconds of heave, pitch and roll under gravity
    /// and `push`: the vertical velocity and the horizontal angular velocity change first,
    /// then the pose moves with them. x, z and the spin about y do not move (the game's).
    pub fn step(&self, pose: &mut Pose, motion: &mut Motion, push: &Push, dt: f32) {
        let acceleration = Vec3::from_array(push.force) / self.mass - Vec3::Y * GRAVITY;
        motion.velocity = [0.0, motion.velocity[1] + acceleration.y * dt, 0.0];
        // The inverse inertia in the world frame: R · diag(1/I) · Rᵀ.
        let rotation = Quat::from_array(pose.rotation);
        let local_torque = rotation.inverse() * Vec3::from_array(push.torque);
        let local_alpha = local_torque / Vec3::from_array(self.inertia).max(Vec3::splat(1e-6));
        let mut spin = Vec3::from_array(motion.angular_velocity) + (rotation * local_alpha) * dt;
        spin.y = 0.0;
        motion.angular_velocity = spin.to_array();
        pose.position[1] += motion.velocity[1] * dt;
        let turn = Quat::from_scaled_axis(spin * dt);
        pose.rotation = (turn * rotation).normalize().to_array();
    }
}

/// A body with its pose and motion, for an engine that moves its floating bodies itself: it
/// queries the water at [`Floater::write_queries`] and hands the heights to
/// [`Floater::float`] with its frame's time step.
#[derive(Debug, Clone, PartialEq)]
pub struct Floater {
    pub body: Body,
    pub pose: Pose,
    pub motion: Motion,
    /// The columns' world positions (scratch, kept to allocate once).
    columns: Vec<[f32; 3]>,
    queries: Vec<[f64; 2]>,
}

impl Floater {
    /// The longest step [`Floater::float`] takes, s: a longer time step is split into steps
    /// of at most this (stable and accurate for heave and roll frequencies up to ~20 rad/s).
    pub const MAX_STEP: f32 = 1.0 / 60.0;
    /// The most steps [`Floater::float`] takes at once: a longer time step is cut to
    /// `MAX_STEPS · MAX_STEP` (4 s, long enough to come to rest on the water given).
    pub const MAX_STEPS: usize = 240;

    /// `body` at `pose`, at rest.
    pub fn new(body: Body, pose: Pose) -> Floater {
        let n = body.columns.len();
        Floater {
            body,
            pose,
            motion: Motion::default(),
            columns: Vec::with_capacity(n),
            queries: Vec::with_capacity(n),
        }
    }

    /// How many points [`Floater::write_queries`] writes: one a column.
    pub fn query_count(&self) -> usize {
        self.body.columns.len()
    }

    /// Writes the world (x, z) of every column (m) into `out`, as long as
    /// [`Floater::query_count`] (extra entries are left alone).
    pub fn write_queries(&mut self, out: &mut [[f64; 2]]) {
        self.fill_columns();
        for (out, query) in out.iter_mut().zip(&self.queries) {
            *out = *query;
        }
    }

    /// Puts the body at rest on water whose heights above its columns are `heights` (m):
    /// level, its heading kept, its origin at the columns' mean water height (weighted by
    /// their water-plane areas) minus [`Body::rest_depth`]. Where to start a body, so that it
    /// does not fall onto the sea.
    pub fn settle(&mut self, heights: &[f32]) {
        let (mut sum, mut area) = (0.0, 0.0);
        for (column, &height) in self.body.columns.iter().zip(heights) {
            let a = column.volume / column.height;
            sum += a * height;
            area += a;
        }
        let water = if area > 0.0 { sum / area } else { 0.0 };
        let [x, _, z] = self.pose.position;
        self.pose = Pose::new([x, water - self.body.rest_depth(), z], self.pose.heading());
        self.motion = Motion::default();
    }

    /// Floats the body for `dt` seconds on water whose heights above its columns are
    /// `heights` (m): the push at the current pose, then [`Body::step`], in steps of at most
    /// [`Floater::MAX_STEP`]. The heights may come from a query at a pose a step or two old:
    /// the columns' x, z move only as the body tilts. Returns the last push (N, N·m); does
    /// not move the body if `dt` is not positive.
    pub fn float(&mut self, heights: &[f32], dt: f32) -> Push {
        if dt.is_nan() || dt <= 0.0 {
            self.fill_columns();
            return self.push(heights);
        }
        let duration = dt.min(Self::MAX_STEP * Self::MAX_STEPS as f32);
        let steps = (duration / Self::MAX_STEP).ceil().max(1.0);
        let h = duration / steps;
        let mut push = Push::default();
        for _ in 0..steps as usize {
            self.fill_columns();
            push = self.push(heights);
            self.body.step(&mut self.pose, &mut self.motion, &push, h);
        }
        push
    }

    /// The push at the current pose and motion, the columns filled.
    fn push(&self, heights: &[f32]) -> Push {
        self.body.push(
            &self.pose,
            &self.columns,
            heights,
            Velocities::Motion(&self.motion),
        )
    }

    fn fill_columns(&mut self) {
        self.columns.clear();
        self.queries.clear();
        self.body
            .columns_at(&self.pose, &mut self.columns, &mut self.queries);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 6 × 2.4 × 1.2 m, 3 t hull of the Bevy example.
    fn hull() -> Body {
        Body::boat(6.0, 2.4, 1.2, 3000.0)
    }

    /// Heaves `floater` on flat water at height 0 for `seconds` in steps of `dt`; its height
    /// after every step.
    fn heave(floater: &mut Floater, seconds: f32, dt: f32) -> Vec<f32> {
        let heights = vec![0.0; floater.query_count()];
        let steps = (seconds / dt).round() as usize;
        (0..steps)
            .map(|_| {
                floater.float(&heights, dt);
                floater.pose.position[1]
            })
            .collect()
    }

    /// Mean period of an oscillation about `centre`: the time between its first and last
    /// upward crossings over the number of cycles between them.
    fn period(ys: &[f32], centre: f32, dt: f32) -> f32 {
        let crossings: Vec<f32> = ys
            .windows(2)
            .enumerate()
            .filter(|(_, w)| w[0] < centre && w[1] >= centre)
            .map(|(i, w)| (i as f32 + (centre - w[0]) / (w[1] - w[0])) * dt)
            .collect();
        assert!(crossings.len() >= 3, "{} crossings", crossings.len());
        (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f32
    }

    /// Dropped level from the still water line, a box comes to rest with its origin at
    /// `rest_depth` (Archimedes: ρ·g·V_submerged = m·g), its displaced volume m/ρ.
    #[test]
    fn a_box_on_flat_water_rests_at_its_rest_depth() {
        let body = hull();
        // Draft m/(ρA) = 3000/(1025·14.4) = 0.2033 m, the origin 0.6 m above the bottom.
        let rest = body.rest_depth();
        assert!((rest - (3000.0 / (1025.0 * 14.4) - 0.6)).abs() < 1e-6);
        let mut floater = Floater::new(body.clone(), Pose::new([5.0, 0.0, -3.0], 0.7));
        let ys = heave(&mut floater, 20.0, 1.0 / 60.0);
        let y = ys[ys.len() - 1];
        assert!(
            (y + rest).abs() < 1e-4,
            "rests at {y} m, expected {}",
            -rest
        );
        let push = floater.float(&[0.0; 8], 0.0);
        let displaced = push.submerged_volume * SEA_WATER_DENSITY;
        assert!((displaced - body.mass).abs() < 1e-3 * body.mass, "{push:?}");
        // Level, where it was put, heading kept.
        let [x, _, z] = floater.pose.position;
        assert_eq!((x, z), (5.0, -3.0));
        assert!((floater.pose.heading() - 0.7).abs() < 1e-5);
        let up = Quat::from_array(floater.pose.rotation) * Vec3::Y;
        assert!(up.angle_between(Vec3::Y) < 1e-5);
        eprintln!(
            "rest: origin at y = {y:.5} m, Archimedes −rest_depth = {:.5} m",
            -rest
        );
    }

    /// Displaced from rest, the undamped heave oscillates at ω = √(ρ g A / m), and with the
    /// boat's drag at the damped frequency ω·√(1 − ζ²), ζ = damping/(2ω).
    #[test]
    fn heave_oscillates_at_the_closed_form_frequency() {
        let dt = 1.0 / 600.0;
        let mut body = hull();
        let omega = body.heave_frequency();
        let expected = (1025.0f32 * GRAVITY * 14.4 / 3000.0).sqrt();
        assert!((omega - expected).abs() < 1e-4 * expected);
        let damping = body.damping;
        body.damping = 0.0;
        let rest = -body.rest_depth();
        // 0.1 m down: every column stays partly in the water (draft 0.2 m of 1.2 m).
        let mut free = Floater::new(body.clone(), Pose::new([0.0, rest - 0.1, 0.0], 0.0));
        let ys = heave(&mut free, 10.0, dt);
        let measured = period(&ys, rest, dt);
        let closed = std::f32::consts::TAU / omega;
        assert!(
            (measured / closed - 1.0).abs() < 0.02,
            "free heave period {measured} s, closed form {closed} s"
        );
        body.damping = damping;
        let zeta = damping / (2.0 * omega);
        let mut damped = Floater::new(body, Pose::new([0.0, rest - 0.1, 0.0], 0.0));
        let ys = heave(&mut damped, 3.0, dt);
        let measured_damped = period(&ys, rest, dt);
        let closed_damped = closed / (1.0 - zeta * zeta).sqrt();
        assert!(
            (measured_damped / closed_damped - 1.0).abs() < 0.03,
            "damped heave period {measured_damped} s, closed form {closed_damped} s"
        );
        eprintln!(
            "heave: free period {measured:.4} s (2π/ω = {closed:.4} s), damped \
             {measured_damped:.4} s (ζ = {zeta:.3}: {closed_damped:.4} s)"
        );
    }

    /// A body deep under water, not moving, feels ρ·g·V up and no torque, whatever its pose.
    #[test]
    fn a_submerged_body_is_pushed_up_by_the_weight_of_its_volume() {
        let body = hull();
        let volume = 6.0 * 2.4 * 1.2;
        let mut pose = Pose::new([1.0, -20.0, 2.0], 2.0);
        pose.rotation = (Quat::from_rotation_x(0.3) * Quat::from_array(pose.rotation)).to_array();
        let (mut world, mut queries) = (Vec::new(), Vec::new());
        body.columns_at(&pose, &mut world, &mut queries);
        let heights = vec![0.5; world.len()];
        let push = body.push(
            &pose,
            &world,
            &heights,
            Velocities::Motion(&Motion::default()),
        );
        let weight = SEA_WATER_DENSITY * GRAVITY * volume;
        assert!((push.submerged_volume - volume).abs() < 1e-4 * volume);
        assert!((push.force[1] - weight).abs() < 1e-5 * weight, "{push:?}");
        assert!(push.force[0].abs() + push.force[2].abs() < 1e-6 * weight);
        assert!(
            Vec3::from_array(push.torque).length() < 1e-5 * weight,
            "{push:?}"
        );
    }

    /// One column off the centre, partly under water: its push is ρ·g·V·(fraction) up plus
    /// the drag on its velocity, and the torque r × F about the body's origin, the velocity
    /// from the motion or from the previous position alike.
    #[test]
    fn an_off_centre_column_turns_the_body_by_r_cross_f() {
        let body = Body {
            columns: vec![Column {
                offset: [1.5, 0.2, -0.7],
                volume: 2.0,
                height: 1.0,
            }],
            mass: 1000.0,
            inertia: [500.0, 800.0, 600.0],
            damping: 3.0,
            water_density: SEA_WATER_DENSITY,
        };
        let rotation = Quat::from_rotation_y(0.4) * Quat::from_rotation_z(0.1);
        let pose = Pose {
            position: [10.0, 0.3, -4.0],
            rotation: rotation.to_array(),
        };
        let (mut world, mut queries) = (Vec::new(), Vec::new());
        body.columns_at(&pose, &mut world, &mut queries);
        let p = Vec3::from_array(world[0]);
        let r = p - Vec3::from_array(pose.position);
        assert!((r - rotation * Vec3::new(1.5, 0.2, -0.7)).length() < 1e-6);
        assert_eq!(queries[0], [f64::from(p.x), f64::from(p.z)]);
        let water = 0.45;
        let fraction = (water - (p.y - 0.5)) / 1.0;
        assert!(fraction > 0.1 && fraction < 0.9, "{fraction}");
        let submerged = 2.0 * fraction;

        // At rest: Archimedes alone.
        let push = body.push(
            &pose,
            &world,
            &[water],
            Velocities::Motion(&Motion::default()),
        );
        let f = Vec3::Y * SEA_WATER_DENSITY * GRAVITY * submerged;
        assert!((Vec3::from_array(push.force) - f).length() < 1e-4 * f.length());
        assert!((Vec3::from_array(push.torque) - r.cross(f)).length() < 1e-4 * f.length());
        assert!((push.submerged_volume - submerged).abs() < 1e-6);

        // Moving: the drag on the column's velocity v + ω × r, the same from where it was.
        let motion = Motion {
            velocity: [0.0, -0.4, 0.0],
            angular_velocity: [0.2, 0.0, -0.1],
        };
        let v =
            Vec3::from_array(motion.velocity) + Vec3::from_array(motion.angular_velocity).cross(r);
        let f = f - v * body.damping * SEA_WATER_DENSITY * submerged;
        let moving = body.push(&pose, &world, &[water], Velocities::Motion(&motion));
        assert!((Vec3::from_array(moving.force) - f).length() < 1e-4 * f.length());
        assert!((Vec3::from_array(moving.torque) - r.cross(f)).length() < 1e-4 * f.length());
        let dt = 0.01;
        let before = [(p - v * dt).to_array()];
        let from_before = body.push(
            &pose,
            &world,
            &[water],
            Velocities::Previous {
                positions: &before,
                dt,
            },
        );
        assert!((Vec3::from_array(from_before.force) - f).length() < 1e-3 * f.length());
    }

    /// A heading is the direction (cos θ, sin θ) of the body's +z in (x, z); setting it
    /// keeps the tilt; a tilted body rights itself on flat water with x, z and heading kept.
    #[test]
    fn headings_and_tilts() {
        let pose = Pose::new([0.0; 3], 0.5);
        let bow = Quat::from_array(pose.rotation) * Vec3::Z;
        assert!((bow - Vec3::new(0.5f32.cos(), 0.0, 0.5f32.sin())).length() < 1e-6);
        assert!((pose.heading() - 0.5).abs() < 1e-6);
        let mut tilted = pose;
        tilted.rotation = (Quat::from_rotation_x(0.2) * Quat::from_array(pose.rotation)).to_array();
        let tilt = |p: &Pose| (Quat::from_array(p.rotation) * Vec3::Y).angle_between(Vec3::Y);
        let before = tilt(&tilted);
        tilted.set_heading(-2.0);
        assert!((tilted.heading() + 2.0).abs() < 1e-5);
        assert!((tilt(&tilted) - before).abs() < 1e-5);

        let body = hull();
        let mut floater = Floater::new(body.clone(), tilted);
        floater.pose.position = [3.0, -body.rest_depth(), 4.0];
        heave(&mut floater, 20.0, 1.0 / 30.0);
        assert!(tilt(&floater.pose) < 1e-3, "tilt {}", tilt(&floater.pose));
        let [x, _, z] = floater.pose.position;
        assert_eq!((x, z), (3.0, 4.0));
        assert!((floater.pose.heading() + 2.0).abs() < 0.05);
    }

    /// A frame's time step of any length is split into stable steps: a long one leaves the
    /// body at rest on the water, finite.
    #[test]
    fn long_time_steps_stay_stable() {
        let body = hull();
        let mut floater = Floater::new(body.clone(), Pose::new([0.0, 3.0, 0.0], 1.0));
        let heights = vec![0.4; 8];
        floater.float(&heights, 2.5);
        floater.float(&heights, 1.0e6);
        let y = floater.pose.position[1];
        assert!((y - (0.4 - body.rest_depth())).abs() < 1e-3, "{y}");
        let mut settled = Floater::new(body.clone(), Pose::new([0.0, 3.0, 0.0], 1.0));
        settled.settle(&heights);
        assert!((settled.pose.position[1] - y).abs() < 1e-3);
        let mut queries = vec![[0.0; 2]; settled.query_count()];
        settled.write_queries(&mut queries);
        let (mut world, mut expected) = (Vec::new(), Vec::new());
        body.columns_at(&settled.pose, &mut world, &mut expected);
        assert_eq!(queries, expected);
    }
}
