//! The reference shader's per-frame inputs besides the textures: `OceanUniforms`, the struct
//! of the same name in shaders/ocean_common.wgsl, field for field (a uniform block of vec4s,
//! so its bytes are the same under std140 and plain C layout).

use bytemuck::{Pod, Zeroable};

use crate::info::{OceanInfo, MAX_CASCADES, SLOPE_TABLE};

/// Distance within which the water is exactly the simulated one (no tiling breaker), m.
pub const EXACT_WITHIN: f32 = 400.0;

/// The light and palette a scene is shaded with (linear RGB, in the units the shader's
/// radiance comes out in before exposure and tone mapping).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// Unit vector toward the sun, (x, y, z), y up.
    pub sun: [f32; 3],
    /// Overcast in [0, 1]: 0 a clear sky, 1 a heavy overcast (no sun disc, no glitter).
    pub overcast: f32,
    /// Sun irradiance.
    pub sun_colour: [f32; 3],
    /// Sky radiance at the zenith and at the horizon.
    pub zenith: [f32; 3],
    pub horizon: [f32; 3],
    /// The colour of deep water, and the tint of thin, high crests lit from behind.
    pub deep: [f32; 3],
    pub subsurface: [f32; 3],
    /// Distance over which the haze takes 63 % of the light, m.
    pub haze_distance: f32,
}

impl Light {
    /// The light of a sun `elevation` degrees above the horizon and `azimuth` degrees from +x
    /// toward +z, under an `overcast` in [0, 1], with a clear day's haze distance `haze` (m;
    /// an overcast's is a third of it). A low sun reaches the sea through more air: its colour
    /// is the extraterrestrial one attenuated by optical depths (0.05, 0.09, 0.18) per air
    /// mass (a reddening of the right order for clear maritime air), with Kasten & Young's
    /// (1989) air mass; the sky dims with the sun.
    pub fn from_sun(elevation: f32, azimuth: f32, overcast: f32, haze: f32) -> Light {
        let (e, a) = (elevation.to_radians(), azimuth.to_radians());
        let sun = [e.cos() * a.cos(), e.sin(), e.cos() * a.sin()];
        let degrees = elevation.max(0.0);
        let air_mass =
            1.0 / (degrees.to_radians().sin() + 0.50572 * (degrees + 6.07995).powf(-1.6364));
        let transmittance = [0.05f32, 0.09, 0.18].map(|tau| (-tau * air_mass).exp());
        let day = (0.25 + 0.75 * sun[1].max(0.0).sqrt()).min(1.0);
        let t = overcast.clamp(0.0, 1.0);
        let mix = |a: [f32; 3], b: [f32; 3]| std::array::from_fn(|i| a[i] + (b[i] - a[i]) * t);
        let scale = |a: [f32; 3], f: [f32; 3]| std::array::from_fn(|i| a[i] * f[i]);
        Light {
            sun,
            overcast: t,
            sun_colour: scale([1.0 * 2.4, 0.92 * 2.4, 0.82 * 2.4], transmittance),
            zenith: mix([0.06 * day, 0.17 * day, 0.46 * day], [0.42, 0.44, 0.47]),
            horizon: mix(
                scale(
                    [0.48 * day, 0.58 * day, 0.74 * day],
                    transmittance.map(|x| 0.55 + 0.45 * x),
                ),
                [0.15, 0.16, 0.175],
            ),
            deep: mix([0.004, 0.030, 0.055], [0.004, 0.008, 0.011]),
            subsurface: mix([0.03, 0.21, 0.19], [0.010, 0.030, 0.028]),
            haze_distance: haze * (1.0 - 0.67 * t),
        }
    }
}

/// The tiling breaker: far from the eye every cascade is read a second time at a shifted
/// place and blended in, so that its repeats do not show (ocean_common.wgsl's
/// `ocean_tiling_weights`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tiling {
    /// Strength in [0, 1] (0: every cascade repeats exactly).
    pub strength: f32,
    /// Cell of the blend's pattern as a fraction of the largest cascade's side.
    pub scale: f32,
    /// Distance within which the water is exactly the simulated one, m.
    pub exact_within: f32,
}

impl Default for Tiling {
    fn default() -> Self {
        Tiling {
            strength: 1.0,
            scale: 0.61,
            exact_within: EXACT_WITHIN,
        }
    }
}

/// `OceanUniforms` of shaders/ocean_common.wgsl, field for field: what the reference shader's
/// functions read besides the textures. Cast it to bytes with `bytemuck::bytes_of`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct OceanUniforms {
    /// xyz: unit vector toward the sun; w: overcast in [0, 1].
    pub sun: [f32; 4],
    /// rgb: sun irradiance; w: the engine's own (the viewer's exposure; in Bevy the shader's
    /// sun per unit of Bevy's exposed illuminance).
    pub sun_colour: [f32; 4],
    /// rgb: sky at the zenith; w: haze distance (m).
    pub zenith: [f32; 4],
    /// rgb: sky at the horizon; w: strength of the tiling breaker in [0, 1].
    pub horizon: [f32; 4],
    /// rgb: deep water; w: standard deviation of the summed height (m).
    pub deep: [f32; 4],
    /// rgb: subsurface tint; w: standard deviation of the summed J − 1.
    pub subsurface: [f32; 4],
    /// xy: unit wind (x, z); zw: sub-grid slope variance along and across the wind.
    pub wind: [f32; 4],
    /// x: cell of the tiling breaker's pattern (m); y: distance within which the water is
    /// exactly the simulated one (m); z: number of cascades; w: the engine's own (the
    /// viewer's number of rings, Bevy's ring half-width in cells).
    pub tiling: [f32; 4],
    /// x: first wave number of `slope_table` (rad/m); y: 1/ln of the ratio between entries;
    /// z: number of entries; w: the share of the sea's foam that is active whitecaps.
    pub table: [f32; 4],
    /// Cascade c: x = L (m), y = L/N (m), z = N, w = mip levels.
    pub cascades: [[f32; 4]; MAX_CASCADES],
    /// Cascade c: xy = the corner of the tile under the eye (a multiple of L, m), which uv is
    /// measured from (keeps uv small and continuous over the view); z = the weight of its
    /// compression in the whitecaps' placement ([`OceanInfo::whitecap_weights`]); w unused.
    pub origins: [[f32; 4]; MAX_CASCADES],
    /// Entry i: x = k_i (rad/m); y, z = slope variance along and across the wind of the
    /// simulated waves with wave numbers above k_i.
    pub slope_table: [[f32; 4]; SLOPE_TABLE],
    /// The wake window ([`WakeTexels::uniform`](crate::WakeTexels::uniform)): x, z of its
    /// texel (0, 0) (m), 1/side (1/m), w = N, its samples a side (0: no window).
    pub wake: [f32; 4],
    /// The foam's streak field ([`streak_uniforms`](crate::streak_uniforms)): xy = the wind's
    /// axis (x, z), zw = the field's origin across and along the wind (m).
    pub streaks: [f32; 4],
    /// x, y = 1/(spacing·texels) across and along (1/m); z, w = texels across and along (0:
    /// no streak texture bound, the shader uses its own noise).
    pub streak_scale: [f32; 4],
    /// The depth map's coast texture ([`CoastTexels::uniforms`](crate::CoastTexels::uniforms)):
    /// x, z of its texel (0, 0) (m), 1/spacing (1/m), w = 1 with a map (0: no coast read).
    pub coast: [f32; 4],
    /// x, y = the coast texture's texels along x and z; z, w unused.
    pub coast_size: [f32; 4],
}

impl OceanUniforms {
    /// Size of the block in vec4s (16 bytes each).
    pub const VEC4S: usize = std::mem::size_of::<OceanUniforms>() / 16;

    /// Writes `light`'s direction, sun and palette (colours times `palette_scale`, an
    /// exposure an engine applies before its own), and `sun_w` into `sun_colour.w`; leaves
    /// what [`set_ocean`](Self::set_ocean) writes alone.
    pub fn set_light(&mut self, light: &Light, palette_scale: f32, sun_w: f32) {
        let rgb = |c: [f32; 3], w: f32| {
            [
                c[0] * palette_scale,
                c[1] * palette_scale,
                c[2] * palette_scale,
                w,
            ]
        };
        self.sun = [light.sun[0], light.sun[1], light.sun[2], light.overcast];
        self.sun_colour = [
            light.sun_colour[0],
            light.sun_colour[1],
            light.sun_colour[2],
            sun_w,
        ];
        self.zenith = rgb(light.zenith, light.haze_distance);
        self.horizon = rgb(light.horizon, self.horizon[3]);
        self.deep = rgb(light.deep, self.deep[3]);
        self.subsurface = rgb(light.subsurface, self.subsurface[3]);
    }

    /// Writes the coast texture's place ([`coast_uniforms`](crate::coast_uniforms)), or
    /// turns the coast off with `None`.
    pub fn set_coast(&mut self, coast: Option<&crate::CoastTexels>) {
        [self.coast, self.coast_size] = crate::coast_uniforms(coast);
    }

    /// Writes what `info` says of the ocean (cascades, wind, statistics, slope table) for an
    /// eye above (x, z) = `eye` (m), and the tiling breaker; leaves the light and `tiling.w`
    /// alone.
    pub fn set_ocean(&mut self, info: &OceanInfo, eye: [f32; 2], tiling: &Tiling) {
        self.horizon[3] = tiling.strength;
        self.deep[3] = info.height_sd;
        self.subsurface[3] = info.jacobian_sd;
        self.wind = [info.wind[0], info.wind[1], info.subgrid[0], info.subgrid[1]];
        self.tiling = [
            tiling.scale * info.lengths[0],
            tiling.exact_within,
            info.cascades as f32,
            self.tiling[3],
        ];
        let (k0, k1) = (info.slope_table[0][0], info.slope_table[SLOPE_TABLE - 1][0]);
        self.table = [
            k0,
            (SLOPE_TABLE - 1) as f32 / (k1 / k0.max(1e-6)).ln().max(1e-6),
            SLOPE_TABLE as f32,
            info.foam_active_share,
        ];
        self.streaks = info.streaks;
        self.streak_scale = info.streak_scale;
        for c in 0..MAX_CASCADES {
            if c >= info.cascades {
                self.cascades[c] = [0.0; 4];
                self.origins[c] = [0.0; 4];
                continue;
            }
            let l = info.lengths[c];
            self.cascades[c] = [
                l,
                l / info.size as f32,
                info.size as f32,
                info.mip_levels as f32,
            ];
            // The corner of the tile under the eye, in f64 so that it stays a multiple of L.
            let corner = |v: f32| ((f64::from(v) / f64::from(l)).floor() * f64::from(l)) as f32;
            self.origins[c] = [
                corner(eye[0]),
                corner(eye[1]),
                info.whitecap_weights[c],
                0.0,
            ];
        }
        for (entry, t) in self.slope_table.iter_mut().zip(&info.slope_table) {
            *entry = [t[0], t[1], t[2], 0.0];
        }
    }
}
