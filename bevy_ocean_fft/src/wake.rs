//! Wakes: a [`Buoyancy`] body with a [`Wake`] presses on the water as a hull (its size from
//! its columns, the render layer's `hull_of`) and leaves a Kelvin wake and a foam trail. The
//! plugin collects the bodies into `OceanState::set_hulls` every frame, moves the wake window
//! with the camera (`set_wake_centre`), and turns the ocean's wake window on while any body
//! has a `Wake` (a new ocean when it first appears, unless the settings already have one).

use bevy::prelude::*;
use ocean_fft::{Hull, WakeConfig};
use ocean_fft_render::{heading_of, hull_of, wake_centre, Body, Pose};

use crate::buoyancy::Buoyancy;

/// Makes a [`Buoyancy`] body leave a wake: a hull of its columns' waterplane (length along
/// the body's z, beam along x, the draft it floats at), moving with the entity's transform
/// (its velocity measured from frame to frame, or `velocity` when the game knows it).
#[derive(Component, Debug, Clone, Copy, PartialEq)]
#[require(WakeTrack)]
pub struct Wake {
    /// Factor on the draft the hull presses the water down with (1: the body's own).
    pub strength: f32,
    /// The body's horizontal velocity (x, z; m/s); `None`: measured from its motion.
    pub velocity: Option<Vec2>,
}

impl Default for Wake {
    fn default() -> Self {
        Wake {
            strength: 1.0,
            velocity: None,
        }
    }
}

/// Where a [`Wake`] body was at the last frame, for its measured velocity.
#[derive(Component, Debug, Clone, Copy, Default, PartialEq)]
pub struct WakeTrack {
    previous: Option<Vec3>,
    velocity: Vec2,
}

/// The wake window the plugin turns on when a [`Wake`] body exists and the settings have
/// none (`OceanConfig::wakes`): 256² samples 0.5 m apart (a 128 m window) by default.
#[derive(Resource, Debug, Clone, Default, PartialEq)]
pub struct WakeWindow(pub WakeConfig);

/// This frame's hulls and the window's centre, handed to the ocean before its step.
#[derive(Resource, Debug, Clone, Default)]
pub struct WakeInput {
    /// The hulls (at most `WakeConfig::MAX_HULLS`).
    pub hulls: Vec<Hull>,
    /// World x, z of the window's centre (m): ahead of the camera, or the first hull's.
    pub centre: Option<[f64; 2]>,
    /// Whether any body has a [`Wake`].
    pub wanted: bool,
}

/// `PostUpdate`, after the transforms: the [`Wake`] bodies as hulls (their `Transform`s:
/// floating bodies live at the root, as [`Buoyancy`] asks), the window's centre.
pub(crate) fn collect_hulls(
    time: Res<Time>,
    mut input: ResMut<WakeInput>,
    mut bodies: Query<(&Buoyancy, &Wake, &mut WakeTrack, &Transform)>,
    cameras: Query<(&GlobalTransform, Has<crate::OceanCamera>), With<Camera3d>>,
    (window, settings): (Res<WakeWindow>, Res<crate::OceanSettings>),
    mut body: Local<Body>,
) {
    let input = &mut *input;
    input.hulls.clear();
    input.wanted = false;
    let dt = time.delta_secs();
    for (buoyancy, wake, mut track, transform) in &mut bodies {
        input.wanted = true;
        let (rotation, position) = (transform.rotation, transform.translation);
        if let (Some(previous), true) = (track.previous, dt > 0.0) {
            let moved = (position - previous) / dt;
            track.velocity = Vec2::new(moved.x, moved.z);
        }
        track.previous = Some(position);
        if input.hulls.len() == WakeConfig::MAX_HULLS {
            continue;
        }
        buoyancy.write(&mut body);
        let pose = Pose::new(position.to_array(), heading_of(rotation.to_array()));
        let velocity = wake.velocity.unwrap_or(track.velocity);
        let mut hull = hull_of(&body, &pose, velocity.to_array());
        hull.draft = (hull.draft * wake.strength.max(0.0)).clamp(0.01, hull.length);
        if hull.velocity.iter().all(|v| v.is_finite()) {
            input.hulls.push(hull);
        }
    }
    let camera = cameras
        .iter()
        .max_by_key(|(_, marked)| *marked)
        .map(|(t, _)| t.compute_transform());
    input.centre = match camera {
        Some(camera) => {
            // The settings' own window if they have one, else the plugin's.
            let config = settings.0.config.wakes.as_ref().unwrap_or(&window.0);
            let side = config.size as f32 * config.spacing;
            Some(wake_centre(
                camera.translation.to_array(),
                camera.forward().as_vec3().to_array(),
                side,
            ))
        }
        None => input.hulls.first().map(|h| h.position),
    };
}
