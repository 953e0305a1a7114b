// ocean-fft's reference ocean shader: the bindings and entry points of the viewer
// (viewer/, `cargo run --release -p ocean-fft-viewer`), compiled as ocean_common.wgsl followed
// by this file. docs/guide/shader.md describes the recipe; the conventions are at the top of
// ocean_common.wgsl.
//
// Bindings (group 0):
//   0  Globals (uniform, below)
//   1  displacement_foam    texture_2d_array<f32>: layer c = cascade c's DisplacementFoam texels
//                           (D_x, η, D_z, foam), RGBA16F, with mipmaps
//   2  slope_jacobian_foam  texture_2d_array<f32>: layer c = cascade c's SlopeJacobianFoam
//                           texels (∂y/∂x, ∂y/∂z, J, foam), RGBA16F, with mipmaps
//   3  ocean_sampler        repeat in u and v, linear min/mag/mip filters, anisotropic (the
//                           fragment stage's lookups, with gradients)
//   4  vertex_sampler       the same without anisotropy: the vertex stage's explicit-LOD
//                           lookups (an anisotropic sampler has no defined footprint without
//                           derivatives; lavapipe returned displacements that tore the mesh)
//   5  wake                 texture_2d<f32>: the wake window's texels (η, ∂y/∂x, ∂y/∂z, foam),
//                           RGBA16F (1×1 of zeros without wakes; `ocean.wake.w` = 0 then)
//   6  wake_sampler         clamp to edge, linear
//   7  streaks              texture_2d<f32>: the foam's streak field (`FoamStreaks`), R16F,
//                           read with vertex_sampler (repeat, linear); uploaded when the
//                           ocean is new
//   8  coast                texture_2d_array<f32>: the coast over the depth map
//                           (`CoastTexels`: layer 0 = f₀, f₁, f₂, Q_b; layer 1 = depth, f₃,
//                           f₄, f₅), RGBA16F, read with wake_sampler (clamp, linear); 1×1 of
//                           zeros without a map (`ocean.coast.w` = 0 then)
//
// Entry points: vs_ocean/fs_ocean draw the water on a clipmap of square rings (no vertex
// buffer: the vertex index is the grid point, the instance index the ring), vs_sky/fs_sky the
// sky behind it (a full-screen triangle), vs_body/fs_body the floating bodies,
// vs_terrain/fs_terrain the ground of a coast (a mesh with a colour per vertex).

struct Globals {
    // World (m) to clip space (reversed, infinite depth) and back.
    view_proj: mat4x4<f32>,
    inverse_view_proj: mat4x4<f32>,
    // xyz: the eye (m); w: the sea's time (s).
    eye: vec4<f32>,
    // Ring r: xy = centre (m, on the grid of the next coarser ring), z = vertex spacing (m),
    // w = M, the ring's half-width in cells (even).
    levels: array<vec4<f32>, 16>,
    // The shading functions' inputs (ocean_common.wgsl); `sun_colour.w` is the exposure,
    // `tiling.w` the number of rings.
    ocean: OceanUniforms,
}

@group(0) @binding(0) var<uniform> globals: Globals;
@group(0) @binding(1) var displacement_foam: texture_2d_array<f32>;
@group(0) @binding(2) var slope_jacobian_foam: texture_2d_array<f32>;
@group(0) @binding(3) var ocean_sampler: sampler;
@group(0) @binding(4) var vertex_sampler: sampler;
@group(0) @binding(5) var wake: texture_2d<f32>;
@group(0) @binding(6) var wake_sampler: sampler;
@group(0) @binding(7) var streaks: texture_2d<f32>;
@group(0) @binding(8) var coast: texture_2d_array<f32>;

fn light() -> OceanLight {
    return ocean_light(globals.ocean, globals.ocean.sun.xyz, globals.ocean.sun_colour.rgb);
}

// ---- Water ----


// Grid point `vertex` of ring `ring`: the vertex index is j·(2M + 1) + i over a
// (2M + 1)² grid centred on the ring's centre, morphed toward the next ring at its border
// (`ocean_morph`).
@vertex
fn vs_ocean(@builtin(vertex_index) vertex: u32, @builtin(instance_index) ring: u32) -> OceanVarying {
    let level = globals.levels[ring];
    let side = 2u * u32(level.w) + 1u;
    let cell = vec2<f32>(f32(vertex % side), f32(vertex / side)) - vec2<f32>(level.w);
    let morphed = ocean_morph(cell, level.w);
    let xz = level.xy + morphed.xy * level.z;
    let spacing = level.z * (1.0 + morphed.z);
    let shore = ocean_coast(coast, wake_sampler, globals.ocean, xz);
    let displacement = ocean_add_wake_displacement(wake, wake_sampler, globals.ocean, xz, ocean_coast_displacement(
        displacement_foam, slope_jacobian_foam, vertex_sampler, globals.ocean, xz, spacing, globals.eye.xz, shore));
    var out = ocean_varying(xz, displacement);
    out.clip = globals.view_proj * vec4<f32>(out.world, 1.0);
    return out;
}

@fragment
fn fs_ocean(in: OceanVarying) -> @location(0) vec4<f32> {
    let shore = ocean_coast(coast, wake_sampler, globals.ocean, in.undisplaced);
    let water = ocean_coast_water_surface(
        slope_jacobian_foam, ocean_sampler, globals.ocean, in.world, in.undisplaced, in.height, globals.eye.xz, shore);
    let foamed = ocean_coast_foam_surface(streaks, vertex_sampler, globals.ocean, in.undisplaced, water, shore);
    let surface = ocean_add_wake_surface(wake, wake_sampler, globals.ocean, in.undisplaced, foamed);
    let to_eye = in.world - globals.eye.xyz;
    let distance = length(to_eye);
    let colour = ocean_shade(light(), surface, to_eye / distance, distance);
    return vec4<f32>(ocean_dither(ocean_tone_map(colour, globals.ocean.sun_colour.w), in.clip.xy), 1.0);
}

// ---- Sky ----

struct SkyVarying {
    @builtin(position) clip: vec4<f32>,
    @location(0) ndc: vec2<f32>,
}

@vertex
fn vs_sky(@builtin(vertex_index) vertex: u32) -> SkyVarying {
    let ndc = vec2<f32>(f32(vertex & 1u) * 4.0 - 1.0, f32(vertex >> 1u) * 4.0 - 1.0);
    var out: SkyVarying;
    out.clip = vec4<f32>(ndc, 0.0, 1.0);
    out.ndc = ndc;
    return out;
}

@fragment
fn fs_sky(in: SkyVarying) -> @location(0) vec4<f32> {
    let point = globals.inverse_view_proj * vec4<f32>(in.ndc, 0.5, 1.0);
    let dir = normalize(point.xyz / point.w - globals.eye.xyz);
    var colour: vec3<f32>;
    if (dir.y < 0.0) {
        // Below the horizon beyond the last ring: the haze.
        colour = ocean_haze_colour(light(), dir);
    } else {
        colour = ocean_sky(light(), dir, true);
    }
    return vec4<f32>(ocean_dither(ocean_tone_map(colour, globals.ocean.sun_colour.w), in.clip.xy), 1.0);
}

// ---- Floating bodies ----

struct BodyVarying {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) colour: vec3<f32>,
}

// A body's mesh (model space, y up) placed by its instance's model matrix (columns 0–3).
@vertex
fn vs_body(
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) m0: vec4<f32>,
    @location(3) m1: vec4<f32>,
    @location(4) m2: vec4<f32>,
    @location(5) m3: vec4<f32>,
    @location(6) colour: vec4<f32>,
) -> BodyVarying {
    let model = mat4x4<f32>(m0, m1, m2, m3);
    var out: BodyVarying;
    let world = model * vec4<f32>(position, 1.0);
    out.world = world.xyz;
    out.clip = globals.view_proj * world;
    out.normal = normalize((model * vec4<f32>(normal, 0.0)).xyz);
    out.colour = colour.rgb;
    return out;
}

@fragment
fn fs_body(in: BodyVarying) -> @location(0) vec4<f32> {
    let l = light();
    let to_eye = in.world - globals.eye.xyz;
    let distance = length(to_eye);
    // Lit on both sides (the meshes are not closed everywhere).
    var n = normalize(in.normal);
    if (dot(n, to_eye) > 0.0) {
        n = -n;
    }
    let ambient = ocean_sky_irradiance(l) * (0.6 + 0.4 * n.y);
    let sun = l.sun_colour * (1.0 - l.overcast) * max(dot(n, l.sun_direction), 0.0);
    var colour = in.colour * (ambient + sun * 0.6);
    let haze = 1.0 - exp(-distance / l.haze_distance);
    colour = mix(colour, ocean_haze_colour(l, to_eye / distance), haze);
    return vec4<f32>(ocean_tone_map(colour, globals.ocean.sun_colour.w), 1.0);
}

// ---- The ground of a coast ----

struct TerrainVarying {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) colour: vec3<f32>,
}

// The ground's mesh, in world space (m).
@vertex
fn vs_terrain(
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) colour: vec4<f32>,
) -> TerrainVarying {
    var out: TerrainVarying;
    out.world = position;
    out.clip = globals.view_proj * vec4<f32>(position, 1.0);
    out.normal = normal;
    out.colour = colour.rgb;
    return out;
}

// Lambert under the sky and the sun (no shadows), the haze of the water.
@fragment
fn fs_terrain(in: TerrainVarying) -> @location(0) vec4<f32> {
    let l = light();
    let to_eye = in.world - globals.eye.xyz;
    let distance = length(to_eye);
    let n = normalize(in.normal);
    let ambient = ocean_sky_irradiance(l) * (0.6 + 0.4 * n.y);
    let sun = l.sun_colour * (1.0 - l.overcast) * max(dot(n, l.sun_direction), 0.0);
    var colour = in.colour * (ambient + sun * 0.6);
    let haze = 1.0 - exp(-distance / l.haze_distance);
    colour = mix(colour, ocean_haze_colour(l, to_eye / distance), haze);
    return vec4<f32>(ocean_dither(ocean_tone_map(colour, globals.ocean.sun_colour.w), in.clip.xy), 1.0);
}
