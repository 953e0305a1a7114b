//! A camera to fly: W/S forward and back, A/D sideways, E/Q (or Space/C) up and down, Shift
//! ten times faster, the mouse (dragged with the left or right button) to look around, the
//! wheel to change the speed. It stays between the water line and [`Camera::MAX_HEIGHT`].

use glam::Vec3;
use winit::keyboard::KeyCode;

/// The fly camera.
#[derive(Debug, Clone, Copy)]
pub struct Camera {
    pub position: Vec3,
    /// Heading, radians from +x toward +z.
    pub yaw: f32,
    /// Up (positive) or down from the horizontal, radians.
    pub pitch: f32,
    /// Vertical field of view, radians.
    pub fov_y: f32,
    /// Flying speed, m/s.
    pub speed: f32,
    /// Keys held: forward, back, left, right, up, down, fast.
    held: [bool; 7],
}

impl Camera {
    /// Highest eye, m.
    pub const MAX_HEIGHT: f32 = 500.0;
    /// Closest the eye comes to the water under it, m.
    pub const ABOVE_WATER: f32 = 0.4;

    pub fn new(position: Vec3, yaw: f32, pitch: f32, fov_y: f32) -> Camera {
        Camera {
            position,
            yaw,
            pitch,
            fov_y,
            speed: 12.0,
            held: [false; 7],
        }
    }

    /// The unit view direction.
    pub fn forward(&self) -> Vec3 {
        Vec3::new(
            self.pitch.cos() * self.yaw.cos(),
            self.pitch.sin(),
            self.pitch.cos() * self.yaw.sin(),
        )
    }

    /// A key went down or up; whether the camera uses it.
    pub fn key(&mut self, code: KeyCode, pressed: bool) -> bool {
        let slot = match code {
            KeyCode::KeyW | KeyCode::ArrowUp => 0,
            KeyCode::KeyS | KeyCode::ArrowDown => 1,
            KeyCode::KeyA | KeyCode::ArrowLeft => 2,
            KeyCode::KeyD | KeyCode::ArrowRight => 3,
            KeyCode::KeyE | KeyCode::Space => 4,
            KeyCode::KeyQ | KeyCode::KeyC => 5,
            KeyCode::ShiftLeft | KeyCode::ShiftRight => 6,
            _ => return false,
        };
        self.held[slot] = pressed;
        true
    }

    /// The mouse moved by (dx, dy) pixels with a button held.
    pub fn look(&mut self, dx: f32, dy: f32) {
        self.yaw += dx * 0.003;
        self.pitch = (self.pitch - dy * 0.003).clamp(-1.5, 1.5);
    }

    /// The wheel turned by `lines`.
    pub fn zoom_speed(&mut self, lines: f32) {
        self.speed = (self.speed * 1.25f32.powf(lines)).clamp(0.5, 2000.0);
    }

    /// Moves by the keys held over `dt` seconds, keeping the eye between `water` +
    /// [`ABOVE_WATER`](Self::ABOVE_WATER) and [`MAX_HEIGHT`](Self::MAX_HEIGHT).
    pub fn update(&mut self, dt: f32, water: f32) {
        let forward = self.forward();
        let right = forward.cross(Vec3::Y).normalize_or(Vec3::Z);
        let axis = |a: usize, b: usize| {
            f32::from(u8::from(self.held[a])) - f32::from(u8::from(self.held[b]))
        };
        let mut motion = forward * axis(0, 1) + right * axis(3, 2) + Vec3::Y * axis(4, 5);
        if motion.length_squared() > 0.0 {
            motion = motion.normalize();
        }
        let fast = if self.held[6] { 10.0 } else { 1.0 };
        self.position += motion * self.speed * fast * dt;
        self.clamp_height(water);
    }

    /// Keeps the eye above the water (`water`, m) and below the ceiling.
    pub fn clamp_height(&mut self, water: f32) {
        self.position.y = self
            .position
            .y
            .max(water + Self::ABOVE_WATER)
            .min(Self::MAX_HEIGHT);
    }
}
