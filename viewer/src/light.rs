//! The light panel's settings, turned into the render layer's [`Light`].

use ocean_fft_render::Light;

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
    /// The light of these settings (`Light::from_sun`).
    pub fn light(&self) -> Light {
        Light::from_sun(self.elevation, self.azimuth, self.overcast, self.haze)
    }
}
