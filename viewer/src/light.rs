//! The light of a scene: sun, sky and water colours from the sun's position and the
//! overcast, as the shader's `OceanLight` takes them.

use glam::Vec3;

/// Linear RGB colours and the sun's direction.
#[derive(Debug, Clone, Copy)]
pub struct Light {
    /// Unit vector toward the sun.
    pub sun: Vec3,
    /// Overcast in [0, 1].
    pub overcast: f32,
    pub sun_colour: Vec3,
    pub zenith: Vec3,
    pub horizon: Vec3,
    pub deep: Vec3,
    pub subsurface: Vec3,
    /// Distance over which the haze takes 63 % of the light, m.
    pub haze: f32,
    /// Exposure before the tone curve.
    pub exposure: f32,
}

/// Settings of the light panel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightSettings {
    /// Sun elevation above the horizon, degrees.
    pub elevation: f32,
    /// Sun azimuth, degrees from +x toward +z.
    pub azimuth: f32,
    /// 0 clear, 1 heavy overcast.
    pub overcast: f32,
    /// Exposure before the tone curve.
    pub exposure: f32,
    /// Haze distance of a clear day, m (an overcast's is a third of it).
    pub haze: f32,
}

impl Default for LightSettings {
    fn default() -> Self {
        LightSettings {
            elevation: 14.0,
            azimuth: 30.0,
            overcast: 0.0,
            exposure: 0.8,
            haze: 6000.0,
        }
    }
}

impl LightSettings {
    /// The light for these settings. A low sun reaches the sea through more air: its colour
    /// is the extraterrestrial one attenuated by optical depths (0.05, 0.09, 0.18) per air
    /// mass (a reddening of the right order for clear maritime air), with Kasten & Young's
    /// (1989) air mass; the sky dims with the sun.
    pub fn light(&self) -> Light {
        let elevation = self.elevation.to_radians();
        let azimuth = self.azimuth.to_radians();
        let sun = Vec3::new(
            elevation.cos() * azimuth.cos(),
            elevation.sin(),
            elevation.cos() * azimuth.sin(),
        );
        let degrees = self.elevation.max(0.0);
        let air_mass =
            1.0 / (degrees.to_radians().sin() + 0.50572 * (degrees + 6.07995).powf(-1.6364));
        let tau = Vec3::new(0.05, 0.09, 0.18);
        let transmittance = Vec3::new(
            (-tau.x * air_mass).exp(),
            (-tau.y * air_mass).exp(),
            (-tau.z * air_mass).exp(),
        );
        let day = (0.25 + 0.75 * sun.y.max(0.0).sqrt()).min(1.0);
        let t = self.overcast.clamp(0.0, 1.0);
        let mix = |a: Vec3, b: Vec3| a.lerp(b, t);
        Light {
            sun,
            overcast: t,
            sun_colour: Vec3::new(1.0, 0.92, 0.82) * 2.4 * transmittance,
            zenith: mix(
                Vec3::new(0.06, 0.17, 0.46) * day,
                Vec3::new(0.42, 0.44, 0.47),
            ),
            horizon: mix(
                Vec3::new(0.48, 0.58, 0.74) * day * (0.55 + 0.45 * transmittance),
                Vec3::new(0.15, 0.16, 0.175),
            ),
            deep: mix(
                Vec3::new(0.004, 0.030, 0.055),
                Vec3::new(0.004, 0.008, 0.011),
            ),
            subsurface: mix(Vec3::new(0.03, 0.21, 0.19), Vec3::new(0.010, 0.030, 0.028)),
            haze: self.haze * (1.0 - 0.67 * t),
            exposure: self.exposure,
        }
    }
}
