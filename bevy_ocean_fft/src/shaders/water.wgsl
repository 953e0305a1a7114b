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
    OceanLight, OceanUniforms, OceanVarying, ocean_light, ocean_morph, ocean_varying,
    ocean_shade, ocean_add_wake_displacement, ocean_add_wake_surface, ocean_coast,
    ocean_coast_displacement, ocean_coast_water_surface, ocean_coast_foam_surface,
}

@group(#{MATERIAL_BIND_GROUP}) @binding(0) var displacement_foam: texture_2d_array<f32>;
// Repeat, linear, no anisotropy: the vertex stage's explicit-LOD look-ups (of both textures).
@group(#{MATERIAL_BIND_GROUP}) @binding(1) var vertex_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(2) var slope_jacobian_foam: texture_2d_array<f32>;
// Repeat, trilinear, anisotropic: the fragment stage's look-ups with gradients.
@group(#{MATERIAL_BIND_GROUP}) @binding(3) var ocean_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(4) var<uniform> ocean: OceanUniforms;
// The wake window (η, ∂y/∂x, ∂y/∂z, foam), clamped to the edge, linear.
@group(#{MATERIAL_BIND_GROUP}) @binding(5) var wake: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(6) var wake_sampler: sampler;
// The foam's streak field (R16F), repeat, linear.
@group(#{MATERIAL_BIND_GROUP}) @binding(7) var streaks: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(8) var streak_sampler: sampler;
// The coast over the depth map (2 layers: f₀, f₁, f₂, Q_b; depth, f₃, f₄, f₅), read with
// wake_sampler (clamped, linear); `ocean.coast.w` = 0 without a map.
@group(#{MATERIAL_BIND_GROUP}) @binding(9) var coast: texture_2d_array<f32>;

// The light: Bevy's first directional light (colour × exposure, scaled to the reference
// shader's sun) when there is one, the uniforms' sun otherwise; the sky and water colours of
// the uniforms.
fn scene_light() -> OceanLight {
    if (lights.n_directional_lights > 0u) {
        let sun = lights.directional_lights[0];
        return ocean_light(ocean, normalize(sun.direction_to_light), sun.color.rgb * view.exposure * ocean.sun_colour.w);
    }
    return ocean_light(ocean, normalize(ocean.sun.xyz), ocean.sun_colour.rgb);
}

struct Vertex {
    @builtin(instance_index) instance_index: u32,
    // The grid point in cells from the ring's centre (x, z; y = 0).
    @location(0) position: vec3<f32>,
}


// A grid point of a ring: the ring's transform puts its centre at the translation and its
// cells `scale.x` metres apart; morphed toward the next ring at its border (`ocean_morph`).
@vertex
fn vertex(v: Vertex) -> OceanVarying {
    let model = get_world_from_local(v.instance_index);
    let cell_size = length(model[0].xyz);
    let morphed = ocean_morph(v.position.xz, ocean.tiling.w);
    let xz = model[3].xz + morphed.xy * cell_size;
    let spacing = cell_size * (1.0 + morphed.z);
    let shore = ocean_coast(coast, wake_sampler, ocean, xz);
    let displacement = ocean_add_wake_displacement(wake, wake_sampler, ocean, xz, ocean_coast_displacement(
        displacement_foam, slope_jacobian_foam, vertex_sampler, ocean, xz, spacing, view.world_position.xz, shore));
    var out = ocean_varying(xz, displacement);
    out.clip = position_world_to_clip(out.world);
    return out;
}

@fragment
fn fragment(in: OceanVarying) -> @location(0) vec4<f32> {
    let eye = view.world_position;
    let shore = ocean_coast(coast, wake_sampler, ocean, in.undisplaced);
    let water = ocean_coast_water_surface(
        slope_jacobian_foam, ocean_sampler, ocean, in.world, in.undisplaced, in.height, eye.xz, shore);
    let foamed = ocean_coast_foam_surface(streaks, streak_sampler, ocean, in.undisplaced, water, shore);
    let surface = ocean_add_wake_surface(wake, wake_sampler, ocean, in.undisplaced, foamed);
    let to_eye = in.world - eye;
    let distance = length(to_eye);
    let dir = to_eye / distance;

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
