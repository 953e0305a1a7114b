// bevy_ocean_fft's sky: the reference shader's `ocean_sky` (shaders/ocean_common.wgsl,
// imported as `ocean_fft::common`) on the inside of a large sphere that follows the camera,
// lit by Bevy's first directional light as the water is (src/shaders/water.wgsl), so that the
// water reflects the sky it is drawn under.

#import bevy_pbr::{
    mesh_functions::{get_world_from_local, mesh_position_local_to_world},
    mesh_view_bindings::{view, lights},
    view_transformations::position_world_to_clip,
}
#ifdef TONEMAP_IN_SHADER
#import bevy_core_pipeline::tonemapping::tone_mapping
#endif
#import ocean_fft::common::{OceanLight, OceanUniforms, ocean_light, ocean_sky, ocean_haze_colour}

// The water's uniforms (the light and the palette are what the sky reads).
@group(#{MATERIAL_BIND_GROUP}) @binding(0) var<uniform> sky: OceanUniforms;

struct Vertex {
    @builtin(instance_index) instance_index: u32,
    @location(0) position: vec3<f32>,
}

struct SkyVarying {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
}

@vertex
fn vertex(v: Vertex) -> SkyVarying {
    let world = mesh_position_local_to_world(get_world_from_local(v.instance_index), vec4<f32>(v.position, 1.0));
    var out: SkyVarying;
    out.world = world.xyz;
    out.clip = position_world_to_clip(world.xyz);
    return out;
}

@fragment
fn fragment(in: SkyVarying) -> @location(0) vec4<f32> {
    var l = ocean_light(sky, normalize(sky.sun.xyz), sky.sun_colour.rgb);
    if (lights.n_directional_lights > 0u) {
        let sun = lights.directional_lights[0];
        l = ocean_light(sky, normalize(sun.direction_to_light), sun.color.rgb * view.exposure * sky.sun_colour.w);
    }
    let dir = normalize(in.world - view.world_position);
    var colour: vec3<f32>;
    if (dir.y < 0.0) {
        // Below the horizon beyond the water's last ring: the haze.
        colour = ocean_haze_colour(l, dir);
    } else {
        colour = ocean_sky(l, dir, true);
    }
    var out = vec4<f32>(colour, 1.0);
#ifdef TONEMAP_IN_SHADER
    out = tone_mapping(out, view.color_grading);
#endif
    return out;
}
