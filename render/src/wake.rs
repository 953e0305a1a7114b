//! The wake window as an engine draws it: its texels in RGBA16F ([`WakeTexels`]), where it
//! lies for the shader (`OceanUniforms::wake`), the [`Hull`] a floating body presses on the
//! water with ([`hull_of`]), and where the window goes for a camera ([`wake_centre`]).
//!
//! The shader (shaders/ocean_common.wgsl: `ocean_wake_uv`, `ocean_add_wake_displacement`,
//! `ocean_add_wake_surface`) adds the wake's height to the vertex stage's displacement and
//! its slope and foam to the fragment stage's surface inside the window; the texels fade to
//! zero at the window's edge, and outside it nothing is read.

use glam::{Quat, Vec3};
use ocean_fft::half::f16;
use ocean_fft::half::slice::HalfFloatSliceExt;
use ocean_fft::{Error, Hull, OceanState};

use crate::floater::{Body, Pose};

/// The wake window's texels: `[η, ∂y/∂x, ∂y/∂z, foam]` (m, dimensionless, [0, 1]) of the
/// window's N×N grid, row-major (z the row), RGBA16F, for world (x₀ + i·Δ, z₀ + j·Δ) with
/// (x₀, z₀) = `origin` and Δ = `spacing`. Upload to an N×N texture sampled with linear
/// filtering and clamp-to-edge addressing (the edge texels are zero). Buffers are kept from
/// frame to frame: packing allocates only when the window's size changes.
#[derive(Debug, Clone, Default)]
pub struct WakeTexels {
    /// The texels (empty when the ocean has no wakes).
    pub texels: Vec<[f16; 4]>,
    /// Samples a side, N (0: no wakes).
    pub size: usize,
    /// World `[x, z]` of texel (0, 0), m.
    pub origin: [f64; 2],
    /// Distance between texels, m.
    pub spacing: f32,
    /// f32 scratch of one window.
    scratch: Vec<[f32; 4]>,
}

impl WakeTexels {
    /// Packs `ocean`'s wake window (`OceanState::wakes`); an ocean without wakes leaves
    /// [`size`](Self::size) at 0 and the texels empty.
    ///
    /// # Errors
    /// The crate's from `pack_wakes`.
    pub fn pack(&mut self, ocean: &OceanState) -> Result<(), Error> {
        let Some(wakes) = ocean.wakes() else {
            self.size = 0;
            self.texels.clear();
            return Ok(());
        };
        let n = wakes.size();
        if self.scratch.len() != n * n {
            self.scratch = vec![[0.0; 4]; n * n];
            self.texels = vec![[f16::ZERO; 4]; n * n];
        }
        self.texels.resize(n * n, [f16::ZERO; 4]);
        ocean.textures().pack_wakes(&mut self.scratch)?;
        self.texels
            .as_flattened_mut()
            .convert_from_f32_slice(self.scratch.as_flattened());
        self.size = n;
        self.origin = wakes.origin();
        self.spacing = wakes.spacing();
        Ok(())
    }

    /// Whether there is a window to draw.
    pub fn active(&self) -> bool {
        self.size > 0
    }

    /// `OceanUniforms::wake`: x, z of the window's texel (0, 0) (m), 1/side (1/m), and N,
    /// its samples a side (0 without a window: the shader reads no wake then).
    pub fn uniform(&self) -> [f32; 4] {
        if !self.active() {
            return [0.0; 4];
        }
        let side = self.size as f32 * self.spacing;
        [
            self.origin[0] as f32,
            self.origin[1] as f32,
            1.0 / side,
            self.size as f32,
        ]
    }
}

/// The waterplane of `body` as a [`Hull`] at `pose`, moving at `velocity` ([x, z], m/s):
/// length along the body's +z and beam along its x from the columns' spread (for a grid of
/// columns, the distance between the outer centres plus one column spacing), draft from the
/// mass the columns float at rest, heading from the pose.
pub fn hull_of(body: &Body, pose: &Pose, velocity: [f32; 2]) -> Hull {
    let span = |axis: usize| {
        let mut values: Vec<f32> = body.columns.iter().map(|c| c.offset[axis]).collect();
        values.sort_by(f32::total_cmp);
        values.dedup_by(|a, b| (*a - *b).abs() < 1e-3);
        let (lo, hi) = (values.first().copied(), values.last().copied());
        match (lo, hi, values.len()) {
            (Some(lo), Some(hi), n) if n > 1 => Some((hi - lo) * n as f32 / (n - 1) as f32),
            _ => None,
        }
    };
    let area = body.water_plane_area().max(1e-6);
    let (length, beam) = match (span(2), span(0)) {
        (Some(l), Some(b)) => (l, b),
        (Some(l), None) => (l, area / l),
        (None, Some(b)) => (area / b, b),
        (None, None) => (area.sqrt(), area.sqrt()),
    };
    let draft = (body.mass / (body.water_density.max(1.0) * area)).min(length);
    Hull {
        position: [f64::from(pose.position[0]), f64::from(pose.position[2])],
        velocity,
        heading: pose.heading(),
        length: length.max(0.1),
        beam: beam.max(0.1),
        draft: draft.max(0.01),
    }
}

/// Where the wake window of side `side` metres goes for an eye at `eye` looking along
/// `forward` (unit, y up): over the water the eye sees most, a quarter of the side ahead of
/// the eye horizontally (less as the view turns down; straight down it is under the eye).
pub fn wake_centre(eye: [f32; 3], forward: [f32; 3], side: f32) -> [f64; 2] {
    let f = Vec3::from_array(forward);
    let flat = Vec3::new(f.x, 0.0, f.z);
    let ahead = flat.normalize_or_zero() * 0.25 * side * flat.length();
    [f64::from(eye[0] + ahead.x), f64::from(eye[2] + ahead.z)]
}

/// The heading (radians, the crate's convention) of a body whose rotation is `rotation` (a
/// unit quaternion x, y, z, w): the direction of its +z in (x, z).
pub fn heading_of(rotation: [f32; 4]) -> f32 {
    let z = Quat::from_array(rotation) * Vec3::Z;
    z.z.atan2(z.x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use ocean_fft::{OceanConfig, Spectrum, WakeConfig};

    /// A boat's columns give back its length, beam and draft; its heading and place are the
    /// pose's.
    #[test]
    fn a_boats_hull_is_its_box() {
        let body = Body::boat(9.0, 3.0, 1.6, 1025.0 * 9.0 * 3.0 * 0.7);
        let pose = Pose::new([10.0, -0.1, -4.0], 0.6);
        let hull = hull_of(&body, &pose, [8.0, 0.0]);
        assert!((hull.length - 9.0).abs() < 1e-4, "{hull:?}");
        assert!((hull.beam - 3.0).abs() < 1e-4, "{hull:?}");
        assert!((hull.draft - 0.7).abs() < 1e-4, "{hull:?}");
        assert!((hull.heading - 0.6).abs() < 1e-5, "{hull:?}");
        assert_eq!(hull.position, [10.0, -4.0]);
        assert_eq!(hull.velocity, [8.0, 0.0]);
        assert!((heading_of(pose.rotation) - 0.6).abs() < 1e-5);
    }

    /// The window goes ahead of an eye looking at the horizon, under one looking down.
    #[test]
    fn the_window_lies_where_the_eye_looks() {
        let ahead = wake_centre([1.0, 40.0, 2.0], [1.0, 0.0, 0.0], 128.0);
        assert_eq!(ahead, [33.0, 2.0]);
        let down = wake_centre([1.0, 40.0, 2.0], [0.0, -1.0, 0.0], 128.0);
        assert_eq!(down, [1.0, 2.0]);
    }

    /// An ocean without wakes packs nothing and disables the shader's look-up; with wakes
    /// the texels are the crate's f32 ones in f16, with the window's place.
    #[test]
    fn packs_the_crates_window() {
        let spectrum = Spectrum::jonswap(8.0, 50_000.0).unwrap();
        let mut config = OceanConfig {
            size: 32,
            ..OceanConfig::default()
        };
        let mut ocean = OceanState::new(spectrum.clone(), config.clone()).unwrap();
        let mut texels = WakeTexels::default();
        texels.pack(&ocean).unwrap();
        assert!(!texels.active());
        assert_eq!(texels.uniform(), [0.0; 4]);

        config.wakes = Some(WakeConfig {
            size: 64,
            spacing: 1.0,
            ..WakeConfig::default()
        });
        ocean = OceanState::new(spectrum, config).unwrap();
        ocean.set_wake_centre(100.0, -20.0).unwrap();
        let hull = Hull {
            position: [100.0, -20.0],
            velocity: [5.0, 0.0],
            length: 10.0,
            beam: 3.0,
            draft: 0.8,
            ..Hull::default()
        };
        ocean.set_hulls(&[hull]).unwrap();
        ocean.step(3.0).unwrap();
        texels.pack(&ocean).unwrap();
        assert!(texels.active());
        assert_eq!(texels.size, 64);
        let wakes = ocean.wakes().unwrap();
        assert_eq!(texels.origin, wakes.origin());
        let u = texels.uniform();
        assert_eq!(u[3], 64.0);
        assert!((u[2] - 1.0 / 64.0).abs() < 1e-9);
        let mut expected = vec![[0.0f32; 4]; 64 * 64];
        ocean.textures().pack_wakes(&mut expected).unwrap();
        let deepest = expected.iter().map(|t| t[0]).fold(0.0f32, f32::min);
        assert!(
            deepest < -0.05,
            "the hull presses the water down: {deepest}"
        );
        for (got, want) in texels.texels.iter().zip(&expected) {
            for k in 0..4 {
                assert_eq!(got[k], f16::from_f32(want[k]));
            }
        }
    }
}
