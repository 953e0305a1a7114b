// bevy_ocean_fft's water: the crate's reference shader (shaders/ocean_common.wgsl at the
// repository root, imported as `ocean_fft::common`) with Bevy's bindings. The vertex stage
// displaces a clipmap ring (a mesh entity of its own, placed and scaled by its transform);
// the fragment stage shades with Bevy's first directional light (its direction, colour,
// exposure and shadow map) and Bevy's distance fog, and leaves the tone mapping to Bevy.
// docs/guide/shader.md describes the recipe; ocean.wgsl (the viewer's) is the same recipe
// with bindings of its own.

#import bevy_pbr::{
    mesh_functions::get_world_from_local,
    mesh_view_bindings::{view, lights},
    mesh_view_types::DIRECTIONAL_LIGHT_FLAGS_SHADOWS_ENABLED_BIT,
    view_transformations::{position_world_to_clip, position_world_to_view},
    shadows::fetch_directional_shadow,
}
#ifdef DISTANCE_FOG
#import bevy_pbr::{
    mesh_view_bindings::fog,
    mesh_view_types::{FOG_MODE_LINEAR, FOG_MODE_EXPONENTIAL, FOG_MODE_EXPONENTIAL_SQUARED, FOG_MODE_ATMOSPHERIC},
    fog::{linear_fog, exponential_fog, exponential_squared_fog, atmospheric_fog},
}
#endif
#ifdef TONEMAP_IN_SHADER
#import bevy_core_pipeline::tonemapping::tone_mapping
#endif
#import ocean_fft::common::{
    OceanLight, OceanSurface, OCEAN_PI, ocean_uv, ocean_vertex_lod, ocean_tiling_offset,
    ocean_tiling_weights, ocean_normal, ocean_foam, ocean_shade,
}

// OceanUniforms in src/render.rs, field for field.
struct OceanUniforms {
    // xyz: unit vector toward the sun when the scene has no directional light; w: overcast.
    sun: vec4<f32>,
    // rgb: the sun's colour then; w: the shader's sun per unit of Bevy's exposed illuminance.
    sun_colour: vec4<f32>,
    // rgb: sky at the zenith; w: haze distance (m).
    zenith: vec4<f32>,
    // rgb: sky at the horizon; w: strength of the tiling breaker in [0, 1].
    horizon: vec4<f32>,
    // rgb: deep water; w: standard deviation of the summed height (m).
    deep: vec4<f32>,
    // rgb: subsurface tint; w: standard deviation of the summed J − 1.
    subsurface: vec4<f32>,
    // xy: unit wind (x, z); zw: sub-grid slope variance along and across the wind.
    wind: vec4<f32>,
    // x: cell of the tiling breaker's pattern (m); y: distance within which the water is
    // exactly the simulated one (m); z: number of cascades; w: the rings' half-width M in cells.
    tiling: vec4<f32>,
    // x: first wave number of `slope_table` (rad/m); y: 1/ln of the ratio between entries;
    // z: number of entries; w: unused.
    table: vec4<f32>,
    // Cascade c: x = L (m), y = L/N (m), z = N, w = mip levels.
    cascades: array<vec4<f32>, 8>,
    // Cascade c: xy = the corner of the tile under the eye (a multiple of L, m).
    origins: array<vec4<f32>, 8>,
    // Entry i: x = k_i (rad/m); y, z = slope variance along and across the wind of the
    // simulated waves with wave numbers above k_i.
    slope_table: array<vec4<f32>, 32>,
}

@group(#{MATERIAL_BIND_GROUP}) @binding(0) var displacement_foam: texture_2d_array<f32>;
// Repeat, linear, no anisotropy: the vertex stage's explicit-LOD look-ups (of both textures).
@group(#{MATERIAL_BIND_GROUP}) @binding(1) var vertex_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(2) var slope_jacobian_foam: texture_2d_array<f32>;
// Repeat, trilinear, anisotropic: the fragment stage's look-ups with gradients.
@group(#{MATERIAL_BIND_GROUP}) @binding(3) var ocean_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(4) var<uniform> ocean: OceanUniforms;

// The light: Bevy's first directional light (colour × exposure, scaled to the reference
// shader's sun) when there is one, the uniforms' sun otherwise; the sky and water colours of
// the uniforms.
fn scene_light() -> OceanLight {
    var l: OceanLight;
    l.overcast = ocean.sun.w;
    if (lights.n_directional_lights > 0u) {
        let sun = lights.directional_lights[0];
        l.sun_direction = normalize(sun.direction_to_light);
        l.sun_colour = sun.color.rgb * view.exposure * ocean.sun_colour.w;
    } else {
        l.sun_direction = normalize(ocean.sun.xyz);
        l.sun_colour = ocean.sun_colour.rgb;
    }
    l.haze_distance = ocean.zenith.w;
    l.zenith = ocean.zenith.rgb;
    l.horizon = ocean.horizon.rgb;
    l.deep = ocean.deep.rgb;
    l.subsurface = ocean.subsurface.rgb;
    return l;
}

fn cascade_count() -> u32 {
    return min(u32(ocean.tiling.z), 8u);
}

struct Vertex {
    @builtin(instance_index) instance_index: u32,
    // The grid point in cells from the ring's centre (x, z; y = 0).
    @location(0) position: vec3<f32>,
}

struct WaterVarying {
    @builtin(position) clip: vec4<f32>,
    // The displaced water point (m).
    @location(0) world: vec3<f32>,
    // The undisplaced grid point (x, z) the textures are read at (m).
    @location(1) undisplaced: vec2<f32>,
    // Summed height η (m).
    @location(2) height: f32,
}

// A grid point of a ring: the ring's transform puts its centre at the translation and its
// cells `scale.x` metres apart. In the outer fifth of a ring the odd grid points slide onto
// their even neighbours (CDLOD-style morphing, Strugar 2009), so that the ring's border has
// the vertices of the next, twice coarser ring.
@vertex
fn vertex(v: Vertex) -> WaterVarying {
    let model = get_world_from_local(v.instance_index);
    let cell_size = length(model[0].xyz);
    let half_cells = ocean.tiling.w;
    var cell = v.position.xz;
    let border = max(abs(cell.x), abs(cell.y)) / half_cells;
    let morph = clamp((border - 0.75) / 0.2, 0.0, 1.0);
    // 1 for odd cells (M is even, so the parity from the centre is that from the corner).
    let odd = cell - 2.0 * floor(cell * 0.5);
    cell -= odd * morph;
    let xz = model[3].xz + cell * cell_size;
    let spacing = cell_size * (1.0 + morph);

    let eye = view.world_position;
    let horizontal = length(xz - eye.xz);
    let weights = ocean_tiling_weights(xz, horizontal, ocean.horizon.w, ocean.tiling.x, ocean.tiling.y);
    var displacement = vec3<f32>(0.0);
    var jacobian = 1.0;
    for (var c = 0u; c < cascade_count(); c++) {
        let cascade = ocean.cascades[c];
        let lod = min(ocean_vertex_lod(spacing, cascade.y), cascade.w - 1.0);
        let uv = ocean_uv(xz, ocean.origins[c].xy, cascade.x, cascade.z);
        var d = textureSampleLevel(displacement_foam, vertex_sampler, uv, c, lod).xyz * weights.x;
        var j = (textureSampleLevel(slope_jacobian_foam, vertex_sampler, uv, c, lod).z - 1.0) * weights.x;
        if (weights.y > 0.0) {
            let shifted = uv + ocean_tiling_offset(c);
            d += textureSampleLevel(displacement_foam, vertex_sampler, shifted, c, lod).xyz * weights.y;
            j += (textureSampleLevel(slope_jacobian_foam, vertex_sampler, shifted, c, lod).z - 1.0) * weights.y;
        }
        displacement += d;
        jacobian += j;
    }
    // Where the surface folds (J < 0) the mesh would turn inside out: below J = 0.5 the
    // horizontal displacement is drawn in, to 30 % at J ≤ −0.2 (the height is kept).
    let unfold = mix(0.3, 1.0, smoothstep(-0.2, 0.5, jacobian));
    displacement.x *= unfold;
    displacement.z *= unfold;
    var out: WaterVarying;
    out.world = vec3<f32>(xz.x + displacement.x, displacement.y, xz.y + displacement.z);
    out.clip = position_world_to_clip(out.world);
    out.undisplaced = xz;
    out.height = displacement.y;
    return out;
}

// Slope variance (along, across the wind) of the simulated waves with wave numbers above
// `k` (rad/m), interpolated in ln k in the table.
fn unresolved_variance(k: f32) -> vec2<f32> {
    let entries = u32(ocean.table.z);
    if (entries < 2u) {
        return vec2<f32>(0.0);
    }
    let position = log(max(k, 1e-6) / ocean.table.x) * ocean.table.y;
    if (position <= 0.0) {
        return ocean.slope_table[0].yz;
    }
    if (position >= f32(entries - 1u)) {
        return ocean.slope_table[entries - 1u].yz;
    }
    let i = u32(floor(position));
    let f = position - f32(i);
    return mix(ocean.slope_table[i].yz, ocean.slope_table[i + 1u].yz, f);
}

@fragment
fn fragment(in: WaterVarying) -> @location(0) vec4<f32> {
    let xz = in.undisplaced;
    // Explicit gradients, limited to 3 times the displaced water's own (where the surface is
    // squeezed the undisplaced point races across a triangle): see docs/guide/shader.md.
    let wx = dpdx(in.world);
    let wy = dpdy(in.world);
    let limit = 3.0 * max(length(wx), length(wy)) + 1e-4;
    let gx = dpdx(xz) * min(1.0, limit / max(length(dpdx(xz)), 1e-6));
    let gy = dpdy(xz) * min(1.0, limit / max(length(dpdy(xz)), 1e-6));
    let eye = view.world_position;
    let to_eye = in.world - eye;
    let distance = length(to_eye);
    let dir = to_eye / distance;
    let weights = ocean_tiling_weights(xz, length(xz - eye.xz), ocean.horizon.w, ocean.tiling.x, ocean.tiling.y);

    var slope = vec2<f32>(0.0);
    var jacobian = 1.0;
    var foam = 0.0;
    for (var c = 0u; c < cascade_count(); c++) {
        let cascade = ocean.cascades[c];
        let uv = ocean_uv(xz, ocean.origins[c].xy, cascade.x, cascade.z);
        let ux = gx / cascade.x;
        let uy = gy / cascade.x;
        let a = textureSampleGrad(slope_jacobian_foam, ocean_sampler, uv, c, ux, uy);
        slope += a.xy * weights.x;
        jacobian += (a.z - 1.0) * weights.x;
        foam += a.w * weights.x * weights.x;
        if (weights.y > 0.0) {
            let b = textureSampleGrad(slope_jacobian_foam, ocean_sampler, uv + ocean_tiling_offset(c), c, ux, uy);
            slope += b.xy * weights.y;
            jacobian += (b.z - 1.0) * weights.y;
            foam += b.w * weights.y * weights.y;
        }
    }

    let footprint = max(sqrt(length(gx) * length(gy)), 1e-4);
    let lost = unresolved_variance(OCEAN_PI / footprint);

    var surface: OceanSurface;
    surface.normal = ocean_normal(slope);
    surface.height = in.height;
    surface.height_sd = ocean.deep.w;
    surface.wind = ocean.wind.xy;
    surface.variance = ocean.wind.zw + lost;
    surface.foam = ocean_foam(foam, jacobian, ocean.subsurface.w, xz, ocean.wind.xy, footprint);

    var light = scene_light();
    // Bevy's shadow map darkens the sun's share (glitter, sunlit foam) where a body shades
    // the water.
    if (lights.n_directional_lights > 0u
        && (lights.directional_lights[0].flags & DIRECTIONAL_LIGHT_FLAGS_SHADOWS_ENABLED_BIT) != 0u) {
        let view_z = position_world_to_view(in.world).z;
        let shadow = fetch_directional_shadow(0u, vec4<f32>(in.world, 1.0), surface.normal, view_z, in.clip.xy);
        light.sun_colour *= shadow;
    }
    var colour = vec4<f32>(ocean_shade(light, surface, dir, distance), 1.0);
#ifdef DISTANCE_FOG
    if (fog.mode == FOG_MODE_LINEAR) {
        colour = linear_fog(fog, colour, distance, vec3<f32>(0.0));
    } else if (fog.mode == FOG_MODE_EXPONENTIAL) {
        colour = exponential_fog(fog, colour, distance, vec3<f32>(0.0));
    } else if (fog.mode == FOG_MODE_EXPONENTIAL_SQUARED) {
        colour = exponential_squared_fog(fog, colour, distance, vec3<f32>(0.0));
    } else if (fog.mode == FOG_MODE_ATMOSPHERIC) {
        colour = atmospheric_fog(fog, colour, distance, vec3<f32>(0.0));
    }
#endif
#ifdef TONEMAP_IN_SHADER
    colour = tone_mapping(colour, view.color_grading);
#endif
    return colour;
}
