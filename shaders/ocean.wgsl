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
//
// Entry points: vs_ocean/fs_ocean draw the water on a clipmap of square rings (no vertex
// buffer: the vertex index is the grid point, the instance index the ring), vs_sky/fs_sky the
// sky behind it (a full-screen triangle), vs_body/fs_body the floating bodies.

struct Globals {
    // World (m) to clip space (reversed, infinite depth) and back.
    view_proj: mat4x4<f32>,
    inverse_view_proj: mat4x4<f32>,
    // xyz: the eye (m); w: the sea's time (s).
    eye: vec4<f32>,
    // xyz: unit vector toward the sun; w: overcast in [0, 1].
    sun: vec4<f32>,
    // rgb: sun irradiance; w: exposure.
    sun_colour: vec4<f32>,
    // rgb: sky at the zenith; w: haze distance (m).
    zenith: vec4<f32>,
    // rgb: sky at the horizon; w: strength of the tiling breaker in [0, 1].
    horizon: vec4<f32>,
    // rgb: deep water; w: standard deviation of the summed height (m).
    deep: vec4<f32>,
    // rgb: subsurface tint; w: standard deviation of the summed J − 1.
    subsurface: vec4<f32>,
    // xy: unit wind (x, z); zw: sub-grid slope variance along and across the wind (the
    // finest cascade's `subgrid_slope_variance`).
    wind: vec4<f32>,
    // x: cell of the tiling breaker's pattern (m); y: distance (m) within which the water is
    // exactly the simulated one; z: number of cascades; w: number of mesh rings.
    tiling: vec4<f32>,
    // x: first wave number of `slope_table` (rad/m); y: 1/ln of the ratio between entries;
    // z: number of entries; w: unused.
    table: vec4<f32>,
    // Cascade c: x = L (m), y = L/N (m), z = N, w = mip levels.
    cascades: array<vec4<f32>, 8>,
    // Cascade c: xy = the corner of the tile under the eye (a multiple of L, m), which uv is
    // measured from.
    origins: array<vec4<f32>, 8>,
    // Entry i: x = wave number k_i (rad/m, k_i = table.x · ratio^i); y, z = slope variance
    // along and across the wind of the simulated waves with wave numbers above k_i.
    slope_table: array<vec4<f32>, 32>,
    // Ring r: xy = centre (m, on the grid of the next coarser ring), z = vertex spacing (m),
    // w = M, the ring's half-width in cells (even).
    levels: array<vec4<f32>, 16>,
}

@group(0) @binding(0) var<uniform> globals: Globals;
@group(0) @binding(1) var displacement_foam: texture_2d_array<f32>;
@group(0) @binding(2) var slope_jacobian_foam: texture_2d_array<f32>;
@group(0) @binding(3) var ocean_sampler: sampler;
@group(0) @binding(4) var vertex_sampler: sampler;

fn light() -> OceanLight {
    var l: OceanLight;
    l.sun_direction = globals.sun.xyz;
    l.overcast = globals.sun.w;
    l.sun_colour = globals.sun_colour.rgb;
    l.haze_distance = globals.zenith.w;
    l.zenith = globals.zenith.rgb;
    l.horizon = globals.horizon.rgb;
    l.deep = globals.deep.rgb;
    l.subsurface = globals.subsurface.rgb;
    return l;
}

fn cascade_count() -> u32 {
    return min(u32(globals.tiling.z), 8u);
}

// ---- Water ----

struct WaterVarying {
    @builtin(position) clip: vec4<f32>,
    // The displaced water point (m).
    @location(0) world: vec3<f32>,
    // The undisplaced grid point (x, z) the textures are read at (m).
    @location(1) undisplaced: vec2<f32>,
    // Summed height η (m).
    @location(2) height: f32,
}

// Grid point `vertex` of ring `ring`: the vertex index is j·(2M + 1) + i over a
// (2M + 1)² grid centred on the ring's centre. In the outer fifth of a ring the odd grid
// points slide onto their even neighbours (CDLOD-style morphing, Strugar 2009), so that the
// ring's border has the vertices of the next, twice coarser ring and the two meet without
// cracks; the vertex spacing grows continuously from s to 2s across that band.
@vertex
fn vs_ocean(@builtin(vertex_index) vertex: u32, @builtin(instance_index) ring: u32) -> WaterVarying {
    let level = globals.levels[ring];
    let half_cells = u32(level.w);
    let side = 2u * half_cells + 1u;
    let i = vertex % side;
    let j = vertex / side;
    var cell = vec2<f32>(f32(i), f32(j)) - vec2<f32>(level.w);
    let border = max(abs(cell.x), abs(cell.y)) / level.w;
    let morph = clamp((border - 0.75) / 0.2, 0.0, 1.0);
    // M is even, so the parity of i is that of the cell index from the centre.
    cell -= vec2<f32>(f32(i & 1u), f32(j & 1u)) * morph;
    let xz = level.xy + cell * level.z;
    let spacing = level.z * (1.0 + morph);

    let horizontal = length(xz - globals.eye.xz);
    let weights = ocean_tiling_weights(xz, horizontal, globals.horizon.w, globals.tiling.x, globals.tiling.y);
    var displacement = vec3<f32>(0.0);
    var jacobian = 1.0;
    for (var c = 0u; c < cascade_count(); c++) {
        let cascade = globals.cascades[c];
        let lod = min(ocean_vertex_lod(spacing, cascade.y), cascade.w - 1.0);
        let uv = ocean_uv(xz, globals.origins[c].xy, cascade.x, cascade.z);
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
    // Where the surface folds (J < 0) a mesh turns inside out into spikes; below J = 0.5 the
    // horizontal displacement is drawn in, to 30 % at J ≤ −0.2 (the height is kept).
    let unfold = mix(0.3, 1.0, smoothstep(-0.2, 0.5, jacobian));
    displacement.x *= unfold;
    displacement.z *= unfold;
    var out: WaterVarying;
    out.world = vec3<f32>(xz.x + displacement.x, displacement.y, xz.y + displacement.z);
    out.clip = globals.view_proj * vec4<f32>(out.world, 1.0);
    out.undisplaced = xz;
    out.height = displacement.y;
    return out;
}

// Slope variance (along, across the wind) of the simulated waves with wave numbers above
// `k` (rad/m), interpolated in ln k in the table.
fn unresolved_variance(k: f32) -> vec2<f32> {
    let entries = u32(globals.table.z);
    if (entries < 2u) {
        return vec2<f32>(0.0);
    }
    let position = log(max(k, 1e-6) / globals.table.x) * globals.table.y;
    if (position <= 0.0) {
        return globals.slope_table[0].yz;
    }
    if (position >= f32(entries - 1u)) {
        return globals.slope_table[entries - 1u].yz;
    }
    let i = u32(floor(position));
    let f = position - f32(i);
    return mix(globals.slope_table[i].yz, globals.slope_table[i + 1u].yz, f);
}

@fragment
fn fs_ocean(in: WaterVarying) -> @location(0) vec4<f32> {
    let xz = in.undisplaced;
    // Explicit gradients: the same for every look-up, usable in non-uniform control flow
    // (the tiling breaker's second look-up is skipped near the eye). Where the surface is
    // squeezed or folds, the undisplaced point races across a triangle far faster than the
    // water drawn; the gradients are limited to 3 times the water's own, so that such a
    // triangle is not filtered (and foamed) flat as a whole.
    let wx = dpdx(in.world);
    let wy = dpdy(in.world);
    let limit = 3.0 * max(length(wx), length(wy)) + 1e-4;
    let gx = dpdx(xz) * min(1.0, limit / max(length(dpdx(xz)), 1e-6));
    let gy = dpdy(xz) * min(1.0, limit / max(length(dpdy(xz)), 1e-6));
    let to_eye = in.world - globals.eye.xyz;
    let distance = length(to_eye);
    let dir = to_eye / distance;
    let weights = ocean_tiling_weights(xz, length(xz - globals.eye.xz), globals.horizon.w, globals.tiling.x, globals.tiling.y);

    var slope = vec2<f32>(0.0);
    var jacobian = 1.0;
    var foam = 0.0;
    for (var c = 0u; c < cascade_count(); c++) {
        let cascade = globals.cascades[c];
        let uv = ocean_uv(xz, globals.origins[c].xy, cascade.x, cascade.z);
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

    // The pixel's footprint on the water (geometric mean of its two axes in the undisplaced
    // plane, m): the mipmaps
    // average away the slopes of waves shorter than about twice that, and their variance goes
    // into the glitter's slope distribution with the sub-grid σ², so the sea's total slope
    // variance (and the width of the glitter path) does not depend on the distance.
    let footprint = max(sqrt(length(gx) * length(gy)), 1e-4);
    let lost = unresolved_variance(OCEAN_PI / footprint);

    var surface: OceanSurface;
    surface.normal = ocean_normal(slope);
    surface.height = in.height;
    surface.height_sd = globals.deep.w;
    surface.wind = globals.wind.xy;
    surface.variance = globals.wind.zw + lost;
    surface.foam = ocean_foam(foam, jacobian, globals.subsurface.w, xz, globals.wind.xy, footprint);
    let colour = ocean_shade(light(), surface, dir, distance);
    return vec4<f32>(ocean_tone_map(colour, globals.sun_colour.w), 1.0);
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
    return vec4<f32>(ocean_tone_map(colour, globals.sun_colour.w), 1.0);
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
    return vec4<f32>(ocean_tone_map(colour, globals.sun_colour.w), 1.0);
}
