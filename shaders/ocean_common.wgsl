// ocean-fft's reference shading functions: how to draw the water from the textures
// `OceanState::pack_texels` (or `pack_texels_f16`) fills. No bindings and no entry points, so
// that any pipeline can use them: the viewer (ocean.wgsl beside this file holds its bindings
// and entry points, compiled as this file followed by that one) and an engine's material (in
// Bevy, register this file as a shader library with `#define_import_path ocean_fft::common`
// put before it). docs/guide/shader.md describes the recipe.
//
// Conventions (those of the crate):
// - Right-handed, y up, metres; the sea is the (x, z) plane. A 2-vector of the sea holds
//   [x, z]; a direction θ is (cos θ, sin θ) in (x, z). The wind blows toward `wind`.
// - Texel (i, j) of a cascade of side L and N×N texels is the water displaced from the world
//   grid point (x₀ + i·L/N, z₀ + j·L/N), for every tile origin (x₀, z₀) on a multiple of L:
//   the textures repeat (address mode Repeat) and world point (x, z) reads at
//   uv = (x, z)/L + ½/N (texel centres at (i + ½)/N, v = 0 at row 0 = z₀).
// - Layouts (ocean_fft::TexelLayout): DisplacementFoam = (D_x, η, D_z, foam) in metres,
//   SlopeJacobianFoam = (∂y/∂x, ∂y/∂z, J, foam), dimensionless. Displacements and slopes of
//   the cascades add. The foam is the whole ocean's coverage in [0, 1] on the largest
//   cascade's grid (cascade 0's alpha; the other cascades' alpha is 0): a fraction of each
//   cell, not a picture of it, so the shader places it inside the cell.
// - Textures are looked up at the *undisplaced* point: the vertex stage moves the grid point
//   by the summed displacement, and the fragment stage reads slopes, Jacobian and foam at the
//   undisplaced point it interpolates from the vertices.
// - Radiance is linear RGB; the caller tone-maps (`ocean_tone_map`) or lets its engine do it.

const OCEAN_PI: f32 = 3.14159265;

// ---- Texture coordinates, levels of detail and the tiling of the cascades ----

// uv of world point `xz` (m) in a cascade of side `length` (m) and `size` texels a side,
// measured from `origin`, a tile corner (a multiple of `length` on both axes) near the eye:
// uv stays small (precision) and continuous over the whole view, and the sampler's repeat
// wraps it. (Taking the remainder of xz/L in the shader instead made uv jump from 1 to 0 at
// every tile edge, and the 2×2 pixel quads across the jump drew a seam.)
fn ocean_uv(xz: vec2<f32>, origin: vec2<f32>, length: f32, size: f32) -> vec2<f32> {
    return (xz - origin) / length + vec2<f32>(0.5 / size);
}

// Mip level at which a cascade of texel size `texel` (m) is sampled by vertices `spacing` m
// apart: two levels coarser than the spacing. A mip level is a 2×2 box mean, and a box of
// width w passes a wave of length λ with amplitude |sinc(w/λ)|, which at one level coarser
// (w = 2·spacing) still lets 20 % of the waves just below the vertices' Nyquist length through
// and draws them as a moiré; at two levels (w = 4·spacing) the waves the vertices cannot hold
// are averaged out (they stay in the fragment stage's normals).
fn ocean_vertex_lod(spacing: f32, texel: f32) -> f32 {
    return max(log2(spacing / texel) + 2.0, 0.0);
}

// Hash of an integer lattice point to [0, 1].
fn ocean_hash(p: vec2<i32>) -> f32 {
    var h = (u32(p.x) * 0x27d4eb2du) ^ (u32(p.y) * 0x165667b1u);
    h = h ^ (h >> 15u);
    h = h * 0x85ebca6bu;
    h = h ^ (h >> 13u);
    return f32(h & 0xffffu) / 65535.0;
}

// Smooth value noise in [0, 1] on a unit lattice (hashed corners, smoothstep blend); not
// periodic, so patterns built on it never repeat with the cascades.
fn ocean_noise(p: vec2<f32>) -> f32 {
    let cell = floor(p);
    let f = p - cell;
    let u = f * f * (3.0 - 2.0 * f);
    let i = vec2<i32>(cell);
    let a = ocean_hash(i);
    let b = ocean_hash(i + vec2<i32>(1, 0));
    let c = ocean_hash(i + vec2<i32>(0, 1));
    let d = ocean_hash(i + vec2<i32>(1, 1));
    return mix(mix(a, b, u.x), mix(c, d, u.x), u.y);
}

// `ocean_noise` at `p` with its gradient: (value, ∂/∂p.x, ∂/∂p.y), per unit of the lattice.
// With independent uniform corners the gradient's components have a standard deviation of
// √(2/12 · 1.2 · 0.743) = 0.3855 (E[(6f(1 − f))²] = 1.2; E[(1 − u)² + u²] = 0.743 for the
// smoothstep u).
fn ocean_noise_gradient(p: vec2<f32>) -> vec3<f32> {
    let cell = floor(p);
    let f = p - cell;
    let u = f * f * (3.0 - 2.0 * f);
    let du = 6.0 * f * (1.0 - f);
    let i = vec2<i32>(cell);
    let a = ocean_hash(i);
    let b = ocean_hash(i + vec2<i32>(1, 0));
    let c = ocean_hash(i + vec2<i32>(0, 1));
    let d = ocean_hash(i + vec2<i32>(1, 1));
    let k = a - b - c + d;
    return vec3<f32>(
        a + (b - a) * u.x + (c - a) * u.y + k * u.x * u.y,
        du.x * ((b - a) + k * u.y),
        du.y * ((c - a) + k * u.x),
    );
}

// `p` turned by the angle whose sine and cosine are `sine` and `cosine`.
fn ocean_rotate(p: vec2<f32>, sine: f32, cosine: f32) -> vec2<f32> {
    return vec2<f32>(cosine * p.x - sine * p.y, sine * p.x + cosine * p.y);
}

// Second look-up offset (in uv) of cascade `c` against visible tiling: a fixed irrational
// shift, different for each cascade, far larger than the waves' correlation length.
fn ocean_tiling_offset(c: u32) -> vec2<f32> {
    let fc = f32(c);
    return fract(vec2<f32>(0.3819660 + 0.6180340 * fc, 0.7548777 + 0.5698403 * fc));
}

// Weights (a, b), a² + b² = 1, of a cascade's two look-ups at world point `xz`, `distance`
// metres from the eye, for a tiling breaker of strength `strength` in [0, 1] whose pattern
// has cells of `scale` metres. Within `near` metres of the eye (a = 1, b = 0) the water is
// exactly the simulated one (what the CPU queries return); beyond 3·`near` a slow noise blends
// in the second, shifted look-up. Two look-ups of a field at points much farther apart than
// its correlation length are uncorrelated, so weights with a² + b² = 1 keep the variance of
// heights, displacements and slopes, while the blend's pattern, which does not repeat, breaks
// up the period L of every cascade.
fn ocean_tiling_weights(xz: vec2<f32>, distance: f32, strength: f32, scale: f32, near: f32) -> vec2<f32> {
    let ramp = smoothstep(near, 3.0 * near, distance) * strength;
    let n = 0.65 * ocean_noise(xz / scale) + 0.35 * ocean_noise(xz / (0.37 * scale) + vec2<f32>(17.3, 5.1));
    let angle = ramp * smoothstep(0.15, 0.85, n) * 0.5 * OCEAN_PI;
    return vec2<f32>(cos(angle), sin(angle));
}

// ---- Surface from the summed textures ----

// The unit normal of a surface of slope (∂y/∂x, ∂y/∂z) (the sum over the cascades' RG of
// SlopeJacobianFoam), y up.
fn ocean_normal(slope: vec2<f32>) -> vec3<f32> {
    return normalize(vec3<f32>(-slope.x, 1.0, -slope.y));
}

// ---- Light ----

// Everything the shading needs to know about the light and the water's colours.
struct OceanLight {
    // Unit vector toward the sun (y up).
    sun_direction: vec3<f32>,
    // 0 for a clear sky with a sun, 1 for a heavy overcast (no sun disc, no glitter).
    overcast: f32,
    // Sun irradiance on a surface facing it, linear RGB.
    sun_colour: vec3<f32>,
    // Distance in metres over which the haze takes 63 % of the light.
    haze_distance: f32,
    // Sky radiance at the zenith and at the horizon, linear RGB.
    zenith: vec3<f32>,
    horizon: vec3<f32>,
    // Water: the colour of deep water and the subsurface tint of thin, high crests.
    deep: vec3<f32>,
    subsurface: vec3<f32>,
}

// Sky radiance in the unit direction `dir` (linear RGB); `with_sun` adds the sun's disc.
// Clear: zenith to horizon gradient and a warm glow around the sun. Overcast: the CIE
// standard overcast sky, L ∝ (1 + 2 sin θ)/3 (Moon & Spencer 1942), under a deck of cloud
// masses 1 km up, fading toward the horizon where the deck is seen edge on.
fn ocean_sky(light: OceanLight, dir: vec3<f32>, with_sun: bool) -> vec3<f32> {
    let elevation = max(dir.y, 0.0);
    let cosine = max(dot(dir, light.sun_direction), 0.0);
    var clear = mix(light.horizon, light.zenith, pow(elevation, 0.45));
    let sun_seen = 1.0 - light.overcast;
    clear += vec3<f32>(1.0, 0.80, 0.55) * (0.25 * pow(cosine, 12.0) + 0.4 * pow(cosine, 400.0))
        * length(light.sun_colour) * 0.26 * sun_seen;
    if (with_sun && cosine > 0.99988) {
        clear += light.sun_colour * 18.0 * sun_seen;
    }
    if (light.overcast <= 0.0) {
        return clear;
    }
    let l = (1.0 + 2.0 * elevation) / 3.0;
    let grey = mix(light.horizon, light.zenith, (l - 1.0 / 3.0) * 1.5) * (0.6 + 0.4 * l);
    var overcast = grey;
    if (elevation > 0.0) {
        let deck = 1000.0 / max(dir.y, 0.02);
        let p = dir.xz * deck / 900.0;
        let clouds = 0.55 * ocean_noise(p) + 0.3 * ocean_noise(2.1 * p + vec2<f32>(5.2, 0.0))
            + 0.15 * ocean_noise(4.3 * p + vec2<f32>(0.0, 1.7));
        overcast = grey * (1.0 + 0.9 * sqrt(min(elevation, 1.0)) * (clouds - 0.5));
    }
    return mix(clear, overcast, light.overcast);
}

// Sky light on a horizontal surface, as radiance of a uniform sky: the mean of the zenith
// and the horizon, half way to its grey (the sky near the horizon, seen by most of the
// hemisphere, is paler than the zenith).
fn ocean_sky_irradiance(light: OceanLight) -> vec3<f32> {
    let sky = 0.5 * (light.zenith + light.horizon);
    let grey = vec3<f32>(dot(sky, vec3<f32>(0.2126, 0.7152, 0.0722)));
    return mix(sky, grey, 0.5);
}

// The colour distant water and air fade to in the horizontal direction of `dir`.
fn ocean_haze_colour(light: OceanLight, dir: vec3<f32>) -> vec3<f32> {
    let flat = vec3<f32>(dir.x, 0.0, dir.z);
    let len = length(flat);
    var horizontal = vec3<f32>(1.0, 0.0, 0.0);
    if (len > 1e-6) {
        horizontal = flat / len;
    }
    return ocean_sky(light, horizontal, false);
}

// Schlick's Fresnel reflectance of water (n = 1.33, F0 ≈ 0.02) at incidence cosine `c`.
fn ocean_fresnel(c: f32) -> f32 {
    let f0 = 0.0200593;
    return f0 + (1.0 - f0) * pow(1.0 - clamp(c, 0.0, 1.0), 5.0);
}

// Sun glitter: radiance reflected toward `view` from a sun of irradiance 1 in direction
// `sun` by facets tilted about the resolved normal `normal` with the anisotropic Gaussian
// slope distribution of Cox & Munk (1954), variances `variance` = (along, across) the unit
// horizontal `wind` (x, z): L = F p(ζ) / (4 cos θ_v cos⁴ β). The variances are what the pixel
// does not resolve (sub-grid σ² plus the simulated slopes too small for its footprint), so a
// distant sea turns into a wide, smooth glitter path instead of flickering points.
fn ocean_glitter(normal: vec3<f32>, view: vec3<f32>, sun: vec3<f32>, wind: vec2<f32>, variance: vec2<f32>) -> f32 {
    let half_vector = normalize(sun + view);
    let wind3 = vec3<f32>(wind.x, 0.0, wind.y);
    var t1 = wind3 - normal * dot(normal, wind3);
    let t1_length = length(t1);
    if (t1_length < 1e-5) {
        t1 = vec3<f32>(1.0, 0.0, 0.0);
    } else {
        t1 = t1 / t1_length;
    }
    let t2 = cross(normal, t1);
    let hn = max(dot(half_vector, normal), 1e-3);
    let zeta = vec2<f32>(dot(half_vector, t1), dot(half_vector, t2)) / hn;
    let v = max(variance, vec2<f32>(1e-5));
    let density = exp(-0.5 * (zeta.x * zeta.x / v.x + zeta.y * zeta.y / v.y))
        / (2.0 * OCEAN_PI * sqrt(v.x * v.y));
    let cos_view = max(dot(normal, view), 0.05);
    let fresnel = ocean_fresnel(dot(half_vector, view));
    return density * fresnel / (4.0 * cos_view * hn * hn * hn * hn);
}

// ---- Foam ----

// The standard normal quantile Φ⁻¹(p), p in (0, 1) (Acklam's rational approximation; a few
// 10⁻⁷ relative in f64, ample here).
fn ocean_probit(p_in: f32) -> f32 {
    let p = clamp(p_in, 1e-6, 1.0 - 1e-6);
    let low = 0.02425;
    if (p < low || p > 1.0 - low) {
        let q = sqrt(-2.0 * log(min(p, 1.0 - p)));
        let x = (((((-0.007784894 * q - 0.32239646) * q - 2.400758) * q - 2.5497325) * q + 4.374664) * q + 2.938164)
            / ((((0.007784696 * q + 0.32246713) * q + 2.445134) * q + 3.7544087) * q + 1.0);
        return select(-x, x, p < low);
    }
    let q = p - 0.5;
    let r = q * q;
    return (((((-39.69683 * r + 220.9461) * r - 275.9285) * r + 138.35775) * r - 30.664799) * r + 2.5066283) * q
        / (((((-54.4761 * r + 161.58583) * r - 155.699) * r + 66.80131) * r - 13.280682) * r + 1.0);
}

// The standard normal distribution function Φ(x) (Abramowitz & Stegun 7.1.26 for erf,
// |error| < 1.5·10⁻⁷).
fn ocean_normal_cdf(x: f32) -> f32 {
    let t = abs(x) * 0.70710678;
    let k = 1.0 / (1.0 + 0.3275911 * t);
    let poly = k * (0.2548296 + k * (-0.2844967 + k * (1.4214137 + k * (-1.453152 + k * 1.0614054))));
    let erf = 1.0 - poly * exp(-t * t);
    return 0.5 * (1.0 + select(-erf, erf, x >= 0.0));
}

// A soft threshold of a rank at `q` (in the rank's standard deviations) of half-width `w`.
fn ocean_soft_step(rank: f32, q: f32, w: f32) -> f32 {
    return smoothstep(q - w, q + w, rank);
}

// Foam from the coverage the textures carry and the streak field: (cover, bubbles) in [0, 1]
// at undisplaced point `xz` (m). `coverage` is the whole ocean's foam f = a + r(1 − a) of the
// cell; the sea's `active_share` splits it into active whitecaps a and residual foam r (the
// library's two parts, docs/theory.md §15.8). Whitecaps: white where a rank of the
// whitecaps' placement field `crest` (standard normal: `ocean_whitecap_rank`) and a fine lace
// noise passes its (1 − a) normal quantile, so they sit on the crests the breakers compress
// (`has_crests` false: no such field, the lace alone). Residual foam: where the library's
// streak field `streak` (unit variance, long along the wind, thin across, moving with the
// water) passes its (1 − r) quantile, 40 % opaque where r is small (old foam is thin) to 80 %
// where it covers most of the sea, with marbled foam (15 %) just below
// the threshold. Bubbles: a halo below the whitecaps' threshold. Edges widen with the pixel's
// `footprint` (m; `across_footprint`, its extent across the wind, for the streaks), and each
// layer blends into its expectation (the same coverage) where the
// footprint outgrows its detail, so the distant sea keeps its foam statistically: no shimmer,
// and no band where the detail hands over.
fn ocean_foam_layers(
    coverage: f32,
    active_share: f32,
    crest: f32,
    has_crests: bool,
    xz: vec2<f32>,
    wind: vec2<f32>,
    footprint: f32,
    across_footprint: f32,
    streak: f32,
) -> vec2<f32> {
    let f = clamp(coverage, 0.0, 1.0);
    let a = f * clamp(active_share, 0.0, 1.0);
    let r = clamp((f - a) / max(1.0 - a, 1e-4), 0.0, 1.0);
    let along = dot(xz, wind);
    let across = dot(xz, vec2<f32>(-wind.y, wind.x));
    let z = select(0.0, crest, has_crests);
    // Value noise has a standard deviation of 0.2149; this sum 0.1550.
    // The lace's octaves on lattices turned 37° and 71° from the wind: thresholded value noise
    // on lattices aligned with each other (and with the streaks) draws square steps.
    let lace = (0.6 * ocean_noise(ocean_rotate(vec2<f32>(along, across), 0.6018, 0.7986) / 2.5 + vec2<f32>(7.3, 0.0))
        + 0.4 * ocean_noise(ocean_rotate(vec2<f32>(along, across), 0.9455, 0.3256) / 0.6) - 0.5) / 0.1550;
    let fine = (ocean_noise(vec2<f32>(along / 1.5, across / 0.35) + vec2<f32>(1.7, 9.2)) - 0.5) / 0.2149;
    // Ranks of unit standard deviation.
    let rank_w = select(lace, 0.85 * z + 0.527 * lace, has_crests);
    let rank_s = 0.85 * streak + 0.527 * fine;
    let q_w = ocean_probit(1.0 - a);
    let q_s = ocean_probit(1.0 - r);
    let soft = 0.5 * min(footprint, 2.0);
    let white = ocean_soft_step(rank_w, q_w, 0.25 + soft);
    // Residual foam is thin where there is little of it (a breeze's streaks: 40 % opaque)
    // and thick where the sea is covered (a gale's sheets: 80 %).
    let opacity = mix(0.4, 0.8, smoothstep(0.1, 0.6, r));
    let streaks = opacity * ocean_soft_step(rank_s, q_s, 0.45 + soft);
    let marble = 0.15 * ocean_soft_step(rank_s, q_s - 0.6, 0.4 + soft);
    // The aerated water fades out over a standard deviation of the rank below the whitecap,
    // quadratically, so its outer edge is lost in the water instead of drawn as a ring (a
    // fixed width: widened with the footprint, the one-sided halo would grow with distance).
    let halo = smoothstep(q_w - 1.0, q_w, rank_w);
    let bubbles = halo * halo * (1.0 - white);
    // Expectations: the soft steps of a standard normal rank cover 1 − Φ(q) (a, r exactly).
    let blur_w = smoothstep(0.2, 1.5, footprint);
    // The streaks are about a metre wide across the wind: where a pixel spans a fair part of
    // that across them (a grazing view across the wind), their detail would alias into
    // bright dashes, so they blend into their expectation by that extent too.
    let blur_s = max(smoothstep(0.08, 0.5, footprint), smoothstep(0.1, 0.35, across_footprint));
    let w_far = a;
    let s_far = opacity * r;
    let m_far = 0.15 * (1.0 - ocean_normal_cdf(q_s - 0.6));
    // The halo's expectation: h²(1 − white) over the standard normal rank, by the midpoint
    // rule on eight bands of a quarter of a standard deviation from q_w − 1 to q_w + 1.
    var b_far = 0.0;
    for (var k = 0; k < 8; k++) {
        let x = q_w - 1.0 + (f32(k) + 0.5) * 0.25;
        let h = smoothstep(q_w - 1.0, q_w, x);
        let band = ocean_normal_cdf(x + 0.125) - ocean_normal_cdf(x - 0.125);
        b_far += h * h * (1.0 - ocean_soft_step(x, q_w, 0.25 + soft)) * band;
    }
    let w_mix = mix(white, w_far, blur_w);
    let s_mix = mix(streaks, s_far, blur_s);
    let m_mix = mix(marble, m_far, blur_s);
    var cover = w_mix + (1.0 - w_mix) * (s_mix + (1.0 - s_mix) * m_mix);
    // Foam is a raft of bubbles, not paint: within a few metres of the eye (footprints below
    // 1–3 cm, a quarter of the finer lattice: coarser pixels turn them into grain) holes a few
    // centimetres across open in it, about 8 % of its area.
    let near = 1.0 - smoothstep(0.012, 0.03, footprint);
    if (near > 0.0) {
        let cells = 0.6 * ocean_noise(xz / 0.18 + vec2<f32>(5.1, 2.3))
            + 0.4 * ocean_noise(xz / 0.07 + vec2<f32>(1.3, 8.7));
        cover *= 1.0 - 0.5 * near * smoothstep(0.55, 0.75, cells);
    }
    return vec2<f32>(clamp(cover, 0.0, 1.0), clamp(mix(bubbles, b_far, blur_w), 0.0, 1.0));
}

// uv of undisplaced point `xz` (m) in the streak field's texture (repeat addressing), from
// the field's placement in the uniforms (`FoamStreaks`' sampling rule).
fn ocean_streak_uv(u: OceanUniforms, xz: vec2<f32>) -> vec2<f32> {
    let axis = u.streaks.xy;
    let along = xz.x * axis.x + xz.y * axis.y - u.streaks.w;
    let across = xz.y * axis.x - xz.x * axis.y - u.streaks.z;
    let texels = max(u.streak_scale.zw, vec2<f32>(1.0));
    return vec2<f32>(across, along) * u.streak_scale.xy + vec2<f32>(0.5) / texels;
}

// The streak field at `xz` when the engine binds it (`u.streak_scale.z` > 0), else value
// noise stretched 40× along the wind (unit variance).
fn ocean_streak(streaks: texture_2d<f32>, streak_sampler: sampler, u: OceanUniforms, xz: vec2<f32>) -> f32 {
    if (u.streak_scale.z > 0.0) {
        return textureSampleLevel(streaks, streak_sampler, ocean_streak_uv(u, xz), 0.0).x;
    }
    let wind = u.wind.xy;
    let along = dot(xz, wind);
    let across = dot(xz, vec2<f32>(-wind.y, wind.x));
    return (0.7 * ocean_noise(vec2<f32>(along / 40.0, across / 1.0))
        + 0.3 * ocean_noise(vec2<f32>(along / 9.0 + 3.1, across / 0.4)) - 0.5) / 0.1637;
}

// Display values (linear, in [0, 1], about to be written to an 8-bit sRGB target) with a
// triangular dither of one 8-bit step in the sRGB encoding added at pixel `pixel`, which
// turns the sky's and the water's banding into fine noise.
fn ocean_dither(colour: vec3<f32>, pixel: vec2<f32>) -> vec3<f32> {
    let p = vec2<i32>(floor(pixel));
    let noise = ocean_hash(p) + ocean_hash(p + vec2<i32>(7919, 104729)) - 1.0;
    let encoded = pow(max(colour, vec3<f32>(0.0)), vec3<f32>(1.0 / 2.2));
    let dithered = clamp(encoded + vec3<f32>(noise / 255.0), vec3<f32>(0.0), vec3<f32>(1.0));
    return pow(dithered, vec3<f32>(2.2));
}

// ---- The water's colour ----

// What the fragment stage knows about one point of water.
struct OceanSurface {
    // Unit normal of the resolved surface (y up).
    normal: vec3<f32>,
    // Summed height η (m) and its standard deviation over the sea (m).
    height: f32,
    height_sd: f32,
    // Foam cover of the pixel in [0, 1]: the cell's coverage from `ocean_water_surface`, the
    // foam drawn once `ocean_foam_surface` (`ocean_foam_layers`) has placed it.
    foam: f32,
    // Bubbles under and around the whitecaps in [0, 1]: a turquoise glow in the water.
    bubbles: f32,
    // What the foam is made from (`ocean_foam_surface`): the cell's foam coverage, the
    // summed Jacobian J and the pixel's footprint on the water (m).
    coverage: f32,
    jacobian: f32,
    footprint: f32,
    // The whitecaps' placement field Σ ŵ_c (1 − J_c) (`ocean_whitecap_rank`).
    whitecap: f32,
    // The pixel's extent on the water across the wind (m), which the streaks resolve by.
    across_footprint: f32,
    // Slope variance (along, across the wind) that the pixel does not resolve.
    variance: vec2<f32>,
    // Horizontal unit wind (x, z).
    wind: vec2<f32>,
    // Water depth under the point (m): the coast's depth map, 1e4 for the open sea
    // (`ocean_coast_water_surface`); shallow water over sand shows the sand.
    depth: f32,
}

// Linear radiance leaving the water toward an eye `distance` metres away along the unit
// direction `dir` (from the eye to the water): Fresnel-weighted sky reflection, the body
// colour of deep water with a subsurface tint on high crests, sun glitter, foam lit by sky
// and sun, and haze.
fn ocean_shade(light: OceanLight, surface: OceanSurface, dir: vec3<f32>, distance: f32) -> vec3<f32> {
    let view = -dir;
    var normal = surface.normal;
    // Facing away (behind a crest or folded): bend it toward the viewer.
    let facing = dot(normal, view);
    if (facing < 0.02) {
        normal = normalize(normal + view * (0.02 - facing));
    }
    let cosine = clamp(dot(normal, view), 0.0, 1.0);
    let fresnel = ocean_fresnel(cosine);
    var reflected = reflect(dir, normal);
    reflected.y = abs(reflected.y);
    let reflection = ocean_sky(light, normalize(reflected), false);

    let sun = light.sun_direction;
    // √(sin elevation): a crude dimming of a low sun by its longer path through the air.
    let sun_strength = (1.0 - light.overcast) * sqrt(max(sun.y, 0.0));
    let glitter = light.sun_colour * sun_strength
        * ocean_glitter(normal, view, sun, surface.wind, surface.variance);

    let crest = clamp(surface.height / max(surface.height_sd, 1e-4) * 0.5, 0.0, 1.5);
    let toward = mix(0.35 + 0.65 * pow(max(dot(dir, sun), 0.0), 3.0), 0.3, light.overcast);
    let ambient = ocean_sky_irradiance(light);
    let luminance = dot(ambient, vec3<f32>(0.2126, 0.7152, 0.0722));
    let deep_body = light.deep * (0.6 + 0.8 * luminance) + light.subsurface * crest * toward
        + light.deep * normal.y;
    // Shallow water over sand: the sand's light back through 2·depth of water, red absorbed
    // first (attenuation about 0.5, 0.14, 0.12 per m: coastal water), so the shallows
    // turn turquoise and the sand shows through near the waterline.
    let through = exp(-vec3<f32>(0.5, 0.14, 0.12) * 2.0 * max(surface.depth, 0.0));
    let sand = vec3<f32>(0.55, 0.48, 0.34)
        * (ambient + light.sun_colour * (1.0 - light.overcast) * max(sun.y, 0.0)) * 0.3;
    let body = mix(deep_body, sand, through);

    // Bubbles under and around the whitecaps scatter the light back up: a pale turquoise.
    let bubble_light = light.subsurface * (2.5 * ambient + 0.8 * light.sun_colour * max(sun.y, 0.0))
        + vec3<f32>(0.02, 0.05, 0.05) * luminance;
    let water = mix(body, bubble_light, 0.3 * surface.bubbles);
    var colour = water * (1.0 - fresnel) + reflection * fresnel + glitter;
    // Foam: a bright, rough, partly translucent scatterer (albedo about 0.85): the sky's
    // light, the sun on the facets facing it, and a share of the sun scattered through it.
    let sunlit = (1.0 - light.overcast) * (0.75 * max(dot(normal, sun), 0.0) + 0.25) * max(sun.y, 0.0);
    let foam_light = vec3<f32>(0.85, 0.87, 0.88) * (1.2 * ambient + light.sun_colour * sunlit);
    colour = mix(colour, foam_light, surface.foam);

    let haze = 1.0 - exp(-distance / light.haze_distance);
    return mix(colour, ocean_haze_colour(light, dir), haze);
}

// Linear radiance to display values in [0, 1] (still linear: write them to an sRGB target)
// through the ACES filmic curve, Narkowicz's (2015) fit x(2.51x + 0.03)/(x(2.43x + 0.59) + 0.14).
fn ocean_tone_map(colour: vec3<f32>, exposure: f32) -> vec3<f32> {
    let x = max(colour * exposure, vec3<f32>(0.0));
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), vec3<f32>(0.0), vec3<f32>(1.0));
}

// ---- The per-frame inputs and the water's two stages ----
//
// What an engine binds besides the two textures and their samplers: `OceanUniforms`
// (ocean_fft_render::OceanUniforms in Rust, field for field, filled by its `set_light` and
// `set_ocean`). The functions below take it and the textures as parameters, so the viewer and
// an engine's material draw the water with the same code and only bind it their own way.

struct OceanUniforms {
    // xyz: unit vector toward the sun; w: overcast in [0, 1].
    sun: vec4<f32>,
    // rgb: sun irradiance; w: the engine's own (the viewer's exposure; in Bevy the shader's
    // sun per unit of Bevy's exposed illuminance).
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
    // exactly the simulated one; z: number of cascades; w: the engine's own (the viewer's
    // number of rings, Bevy's ring half-width in cells).
    tiling: vec4<f32>,
    // x: first wave number of `slope_table` (rad/m); y: 1/ln of the ratio between entries;
    // z: number of entries; w: the share of the sea's foam that is active whitecaps.
    table: vec4<f32>,
    // Cascade c: x = L (m), y = L/N (m), z = N, w = mip levels.
    cascades: array<vec4<f32>, 8>,
    // Cascade c: xy = the corner of the tile under the eye (a multiple of L, m), which uv is
    // measured from; z = the weight ŵ_c of its compression in the whitecaps' placement
    // (`FoamView::whitecap_weights`; all 0: `ocean_whitecap_rank` falls back to σ_J).
    origins: array<vec4<f32>, 8>,
    // Entry i: x = wave number k_i (rad/m, k_i = table.x · ratio^i); y, z = slope variance
    // along and across the wind of the simulated waves with wave numbers above k_i.
    slope_table: array<vec4<f32>, 32>,
    // The wake window (ocean_fft_render::WakeTexels::uniform): xy = world x, z of its texel
    // (0, 0) (m), z = 1/side (1/m), w = N, its samples a side (0: no window, no wake read).
    wake: vec4<f32>,
    // The foam's streak field (ocean_fft_render::streak_uniforms): xy = the wind's axis
    // (x, z), zw = the field's origin across and along the wind (m).
    streaks: vec4<f32>,
    // xy = 1/(spacing·texels) across and along (1/m), zw = texels across and along (0: no
    // streak texture, `ocean_foam_layers` uses its own noise).
    streak_scale: vec4<f32>,
    // The coast texture over the depth map (ocean_fft_render::CoastTexels::uniforms): xy =
    // world x, z of its texel (0, 0) (m), z = 1/spacing (1/m), w = 1 with a map (0: no
    // coast read).
    coast: vec4<f32>,
    // xy = the coast texture's texels along x and z.
    coast_size: vec4<f32>,
}

// The light of the uniforms, with the sun an engine gives (its own light, or the uniforms'
// `sun.xyz` and `sun_colour.rgb`).
fn ocean_light(u: OceanUniforms, sun_direction: vec3<f32>, sun_colour: vec3<f32>) -> OceanLight {
    var l: OceanLight;
    l.sun_direction = sun_direction;
    l.overcast = u.sun.w;
    l.sun_colour = sun_colour;
    l.haze_distance = u.zenith.w;
    l.zenith = u.zenith.rgb;
    l.horizon = u.horizon.rgb;
    l.deep = u.deep.rgb;
    l.subsurface = u.subsurface.rgb;
    return l;
}

fn ocean_cascade_count(u: OceanUniforms) -> u32 {
    return min(u32(u.tiling.z), 8u);
}

// A clipmap grid point `cell` (in cells from its ring's centre, M = `half_cells` from centre
// to edge, M even) moved for CDLOD-style morphing (Strugar 2009): in the outer fifth of a
// ring the odd grid points slide onto their even neighbours, so that the ring's border has
// the vertices of the next, twice coarser ring and the two meet without cracks. Returns the
// morphed cell (xy) and the morph factor in [0, 1] (z): the vertex spacing grows from s to
// 2s across that band, s·(1 + z).
fn ocean_morph(cell: vec2<f32>, half_cells: f32) -> vec3<f32> {
    let border = max(abs(cell.x), abs(cell.y)) / half_cells;
    let morph = clamp((border - 0.75) / 0.2, 0.0, 1.0);
    // 1 for odd cells (M is even, so the parity from the centre is that from the corner).
    let odd = cell - 2.0 * floor(cell * 0.5);
    return vec3<f32>(cell - odd * morph, morph);
}

// The summed displacement (D_x, η, D_z; m) of the water whose undisplaced point is `xz`, for
// vertices `spacing` m apart and an eye above `eye_xz`: every cascade read at the level of
// detail the spacing asks for (explicit LOD, with a sampler without anisotropy), the tiling
// breaker's second look-up far away. Where the surface folds (J < 0) a mesh turns inside out
// into spikes, so below J = 0.5 the horizontal displacement is drawn in, to 30 % at
// J ≤ −0.2 (the height is kept).
fn ocean_displacement(
    displacement_foam: texture_2d_array<f32>,
    slope_jacobian_foam: texture_2d_array<f32>,
    vertex_sampler: sampler,
    u: OceanUniforms,
    xz: vec2<f32>,
    spacing: f32,
    eye_xz: vec2<f32>,
) -> vec3<f32> {
    return ocean_coast_displacement(
        displacement_foam, slope_jacobian_foam, vertex_sampler, u, xz, spacing, eye_xz, ocean_open_sea());
}

// `ocean_displacement` over a coast (`ocean_coast` at `xz`): each cascade's displacement
// scaled by its factor there.
fn ocean_coast_displacement(
    displacement_foam: texture_2d_array<f32>,
    slope_jacobian_foam: texture_2d_array<f32>,
    vertex_sampler: sampler,
    u: OceanUniforms,
    xz: vec2<f32>,
    spacing: f32,
    eye_xz: vec2<f32>,
    coast: OceanCoast,
) -> vec3<f32> {
    let weights = ocean_tiling_weights(xz, length(xz - eye_xz), u.horizon.w, u.tiling.x, u.tiling.y);
    var displacement = vec3<f32>(0.0);
    var jacobian = 1.0;
    for (var c = 0u; c < ocean_cascade_count(u); c++) {
        let cascade = u.cascades[c];
        let lod = min(ocean_vertex_lod(spacing, cascade.y), cascade.w - 1.0);
        let uv = ocean_uv(xz, u.origins[c].xy, cascade.x, cascade.z);
        var d = textureSampleLevel(displacement_foam, vertex_sampler, uv, c, lod).xyz * weights.x;
        var j = (textureSampleLevel(slope_jacobian_foam, vertex_sampler, uv, c, lod).z - 1.0) * weights.x;
        if (weights.y > 0.0) {
            let shifted = uv + ocean_tiling_offset(c);
            d += textureSampleLevel(displacement_foam, vertex_sampler, shifted, c, lod).xyz * weights.y;
            j += (textureSampleLevel(slope_jacobian_foam, vertex_sampler, shifted, c, lod).z - 1.0) * weights.y;
        }
        let factor = ocean_coast_factor(coast, c);
        displacement += d * factor;
        jacobian += j * factor;
    }
    let unfold = mix(0.3, 1.0, smoothstep(-0.2, 0.5, jacobian));
    return vec3<f32>(displacement.x * unfold, displacement.y, displacement.z * unfold);
}

// What the water's vertex stage hands its fragment stage.
struct OceanVarying {
    @builtin(position) clip: vec4<f32>,
    // The displaced water point (m).
    @location(0) world: vec3<f32>,
    // The undisplaced grid point (x, z) the textures are read at (m).
    @location(1) undisplaced: vec2<f32>,
    // Summed height η (m).
    @location(2) height: f32,
}

// The varying of the water at undisplaced point `xz` (m) moved by `displacement`
// (`ocean_displacement`); the caller sets `clip` from `world` with its own projection.
fn ocean_varying(xz: vec2<f32>, displacement: vec3<f32>) -> OceanVarying {
    var out: OceanVarying;
    out.world = vec3<f32>(xz.x + displacement.x, displacement.y, xz.y + displacement.z);
    out.clip = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    out.undisplaced = xz;
    out.height = displacement.y;
    return out;
}

// The slopes of the waves shorter than the finest cascade's grid, drawn where the pixel is
// small enough to see them: three octaves of value noise at 0.6, 0.25 and 0.1 of the finest
// texel `u.cascades[n − 1].y`, each with a third of the sub-grid slope variance `u.wind.zw`
// along and across the wind (a k⁻⁴ saturation range holds the same slope variance in every
// octave), fading out as the footprint `footprint` (m) grows from an eighth to a quarter of
// its lattice (a coarser pixel turns its glints into grain).
// Returns the slopes (∂y/∂x, ∂y/∂z) to add to the normal's and the variance (along, across)
// they show, which the glitter then leaves out, so the sea's total slope variance stays the
// same at every distance.
fn ocean_detail_slope(u: OceanUniforms, xz: vec2<f32>, footprint: f32) -> vec4<f32> {
    let n = ocean_cascade_count(u);
    if (n == 0u) {
        return vec4<f32>(0.0);
    }
    let texel = u.cascades[n - 1u].y;
    let wind = u.wind.xy;
    let sd = sqrt(max(u.wind.zw, vec2<f32>(0.0)) / 3.0);
    let p = vec2<f32>(dot(xz, wind), dot(xz, vec2<f32>(-wind.y, wind.x)));
    var s = vec2<f32>(0.0);
    var shown = vec2<f32>(0.0);
    var scale = 0.6;
    for (var o = 0u; o < 3u; o++) {
        let lattice = texel * scale;
        let fade = 1.0 - smoothstep(0.12 * lattice, 0.25 * lattice, footprint);
        if (fade > 0.0) {
            let shift = vec2<f32>(17.3, 5.9) * f32(o + 1u);
            let g = ocean_noise_gradient(p / lattice + shift).yz / 0.3855;
            s += fade * g * sd;
            shown += fade * fade * sd * sd;
        }
        scale *= 0.42;
    }
    return vec4<f32>(s.x * wind.x - s.y * wind.y, s.x * wind.y + s.y * wind.x, shown);
}

// Slope variance (along, across the wind) of the simulated waves with wave numbers above
// `k` (rad/m), interpolated in ln k in the uniforms' table.
fn ocean_unresolved_variance(u: OceanUniforms, k: f32) -> vec2<f32> {
    let entries = u32(u.table.z);
    if (entries < 2u) {
        return vec2<f32>(0.0);
    }
    let position = log(max(k, 1e-6) / u.table.x) * u.table.y;
    if (position <= 0.0) {
        return u.slope_table[0].yz;
    }
    if (position >= f32(entries - 1u)) {
        return u.slope_table[entries - 1u].yz;
    }
    let i = u32(floor(position));
    let f = position - f32(i);
    return mix(u.slope_table[i].yz, u.slope_table[i + 1u].yz, f);
}

// The surface a fragment shows: the water displaced to `world` (m) from the undisplaced
// point `xz` (m), summed height `height` (m), seen from an eye above `eye_xz`. Call it in
// uniform control flow (it takes screen-space derivatives). The texture look-ups use
// explicit gradients, the same for every look-up (the tiling breaker's second one is skipped
// near the eye): where the surface is squeezed or folds, the undisplaced point races across a
// triangle far faster than the water drawn, so the gradients are limited to 3 times the
// water's own and such a triangle is not filtered (and foamed) flat as a whole. The mipmaps
// average away the slopes of waves shorter than about twice the pixel's footprint on the
// water; their variance goes into the glitter's slope distribution with the sub-grid σ², so
// the sea's total slope variance (and the width of the glitter path) does not depend on the
// distance.
fn ocean_water_surface(
    slope_jacobian_foam: texture_2d_array<f32>,
    ocean_sampler: sampler,
    u: OceanUniforms,
    world: vec3<f32>,
    xz: vec2<f32>,
    height: f32,
    eye_xz: vec2<f32>,
) -> OceanSurface {
    return ocean_coast_water_surface(
        slope_jacobian_foam, ocean_sampler, u, world, xz, height, eye_xz, ocean_open_sea());
}

// `ocean_water_surface` over a coast (`ocean_coast` at `xz`): each cascade's slope and
// compression scaled by its factor there, and the depth for the shallows' colour.
fn ocean_coast_water_surface(
    slope_jacobian_foam: texture_2d_array<f32>,
    ocean_sampler: sampler,
    u: OceanUniforms,
    world: vec3<f32>,
    xz: vec2<f32>,
    height: f32,
    eye_xz: vec2<f32>,
    coast: OceanCoast,
) -> OceanSurface {
    let wx = dpdx(world);
    let wy = dpdy(world);
    let limit = 3.0 * max(length(wx), length(wy)) + 1e-4;
    let gx = dpdx(xz) * min(1.0, limit / max(length(dpdx(xz)), 1e-6));
    let gy = dpdy(xz) * min(1.0, limit / max(length(dpdy(xz)), 1e-6));
    let weights = ocean_tiling_weights(xz, length(xz - eye_xz), u.horizon.w, u.tiling.x, u.tiling.y);

    var slope = vec2<f32>(0.0);
    var jacobian = 1.0;
    var whitecap = 0.0;
    var foam = 0.0;
    for (var c = 0u; c < ocean_cascade_count(u); c++) {
        let cascade = u.cascades[c];
        let uv = ocean_uv(xz, u.origins[c].xy, cascade.x, cascade.z);
        let ux = gx / cascade.x;
        let uy = gy / cascade.x;
        let factor = ocean_coast_factor(coast, c);
        let a = textureSampleGrad(slope_jacobian_foam, ocean_sampler, uv, c, ux, uy);
        let w = u.origins[c].z;
        slope += a.xy * weights.x * factor;
        jacobian += (a.z - 1.0) * weights.x * factor;
        whitecap += w * (1.0 - a.z) * weights.x * factor;
        foam += a.w * weights.x * weights.x;
        if (weights.y > 0.0) {
            let b = textureSampleGrad(slope_jacobian_foam, ocean_sampler, uv + ocean_tiling_offset(c), c, ux, uy);
            slope += b.xy * weights.y * factor;
            jacobian += (b.z - 1.0) * weights.y * factor;
            whitecap += w * (1.0 - b.z) * weights.y * factor;
            foam += b.w * weights.y * weights.y;
        }
    }

    // The pixel's footprint on the water: geometric mean of its two axes in the undisplaced
    // plane, m.
    let footprint = max(sqrt(length(gx) * length(gy)), 1e-4);
    let detail = ocean_detail_slope(u, xz, footprint);
    var surface: OceanSurface;
    surface.normal = ocean_normal(slope + detail.xy);
    surface.height = height;
    surface.height_sd = u.deep.w;
    surface.wind = u.wind.xy;
    surface.variance = max(u.wind.zw - detail.zw, vec2<f32>(0.0))
        + ocean_unresolved_variance(u, OCEAN_PI / footprint);
    surface.foam = clamp(foam, 0.0, 1.0);
    surface.bubbles = 0.0;
    surface.coverage = foam;
    surface.jacobian = jacobian;
    surface.whitecap = whitecap;
    surface.footprint = footprint;
    let across = vec2<f32>(-u.wind.y, u.wind.x);
    surface.across_footprint = max(abs(dot(gx, across)), abs(dot(gy, across)));
    surface.depth = coast.far.x;
    return surface;
}

// The whitecaps' placement field at a fragment (x) and whether there is one (y = 1, else 0):
// Σ ŵ_c (1 − J_c), which `ocean_water_surface` sums with the weights the library gives
// (`FoamView::whitecap_weights`, in `origins[c].z`), standard normal; where an engine sets
// no weights, the standardised compression of all cascades, −(J − 1)/σ_J.
fn ocean_whitecap_rank(u: OceanUniforms, surface: OceanSurface) -> vec2<f32> {
    var weighted = false;
    for (var c = 0u; c < ocean_cascade_count(u); c++) {
        weighted = weighted || u.origins[c].z > 0.0;
    }
    if (weighted) {
        return vec2<f32>(surface.whitecap, 1.0);
    }
    let sd = u.subsurface.w;
    if (sd > 1e-3) {
        return vec2<f32>(-(surface.jacobian - 1.0) / sd, 1.0);
    }
    return vec2<f32>(0.0);
}

// `surface` (`ocean_water_surface` at undisplaced point `xz`, m) with its foam drawn by
// `ocean_foam_layers`: whitecaps on the compressed crests, residual foam in the streak field
// `streaks` (the library's `FoamStreaks`, an R16F texture_2d uploaded once, read with a
// repeat, linear sampler; with `u.streak_scale.z` = 0 a value noise stands in), bubbles.
fn ocean_foam_surface(
    streaks: texture_2d<f32>,
    streak_sampler: sampler,
    u: OceanUniforms,
    xz: vec2<f32>,
    surface: OceanSurface,
) -> OceanSurface {
    var s = surface;
    let streak = ocean_streak(streaks, streak_sampler, u, xz);
    let rank = ocean_whitecap_rank(u, s);
    let foam = ocean_foam_layers(
        s.coverage, u.table.w, rank.x, rank.y > 0.0, xz, u.wind.xy, s.footprint,
        s.across_footprint, streak);
    s.foam = foam.x;
    s.bubbles = foam.y;
    return s;
}

// ---- Wakes ----
//
// The wake window (`OceanState::wakes`, packed by `pack_wakes`): an N×N texture_2d of
// RGBA16F texels (η (m), ∂y/∂x, ∂y/∂z, foam in [0, 1]) for world (x₀ + i·Δ, z₀ + j·Δ), read
// with a linear, clamp-to-edge sampler. Its texels fade to zero toward the window's edge, and
// outside the window nothing is read, so the wake ends without a seam. The wake has no
// horizontal displacement.

// uv of world point `xz` (m) in the wake window, and in z whether the wake is read there (1
// inside the window, 0 outside it or without a window).
fn ocean_wake_uv(u: OceanUniforms, xz: vec2<f32>) -> vec3<f32> {
    let n = u.wake.w;
    if (n < 1.0) {
        return vec3<f32>(0.0);
    }
    let uv = (xz - u.wake.xy) * u.wake.z + vec2<f32>(0.5 / n);
    let inside = all(uv >= vec2<f32>(0.0)) && all(uv <= vec2<f32>(1.0));
    return vec3<f32>(uv, select(0.0, 1.0, inside));
}

// `displacement` (`ocean_displacement`) with the wake's height added at undisplaced point
// `xz` (m).
fn ocean_add_wake_displacement(
    wake: texture_2d<f32>,
    wake_sampler: sampler,
    u: OceanUniforms,
    xz: vec2<f32>,
    displacement: vec3<f32>,
) -> vec3<f32> {
    let w = ocean_wake_uv(u, xz);
    if (w.z <= 0.0) {
        return displacement;
    }
    let height = textureSampleLevel(wake, wake_sampler, w.xy, 0.0).x;
    return displacement + vec3<f32>(0.0, height, 0.0);
}

// `surface` (`ocean_water_surface` at undisplaced point `xz`, m) with the wake's slope added
// to its normal and the wake's foam f_w to its foam f as f + f_w·(1 − f) (as the crate's
// queries combine them). The trail's foam, a coverage on the window's grid, is placed like
// the sea's: white where a two-scale noise (patches about a metre across) passes its
// (1 − f_w) normal quantile, with soft edges, opaque where the trail is thick (fresh, behind
// the hull) and thinner as it thins out, so an old trail turns into marbled patches; bubbles
// around it tint the water turquoise.
fn ocean_add_wake_surface(
    wake: texture_2d<f32>,
    wake_sampler: sampler,
    u: OceanUniforms,
    xz: vec2<f32>,
    surface: OceanSurface,
) -> OceanSurface {
    let w = ocean_wake_uv(u, xz);
    if (w.z <= 0.0) {
        return surface;
    }
    let t = textureSampleLevel(wake, wake_sampler, w.xy, 0.0);
    var s = surface;
    let slope = -s.normal.xz / max(s.normal.y, 1e-3) + t.yz;
    s.normal = ocean_normal(slope);
    // Value noise has a standard deviation of 0.2149; this sum 0.1550.
    let rank = (0.6 * ocean_noise(xz / 1.3 + vec2<f32>(3.7, 1.1)) + 0.4 * ocean_noise(xz / 0.45) - 0.5) / 0.1550;
    let f = clamp(t.w, 0.0, 1.0);
    let soft = 0.3 + 0.5 * min(s.footprint, 2.0);
    let detailed = ocean_soft_step(rank, ocean_probit(1.0 - f), soft);
    let blur = smoothstep(0.2, 1.5, s.footprint);
    let foam = mix(detailed, f, blur) * mix(0.55, 1.0, smoothstep(0.3, 0.9, f));
    s.foam = s.foam + foam * (1.0 - s.foam);
    s.bubbles = max(s.bubbles, smoothstep(0.02, 0.4, f) * (1.0 - foam));
    return s;
}

// ---- Coasts ----
//
// The coast texture over a depth map (`ocean_fft_render::CoastTexels`, from the crate's
// `pack_coast`): a 2-layer texture_2d_array of RGBA16F texels for world (x₀ + i·Δ, z₀ + j·Δ),
// read with a linear, clamp-to-edge sampler; layer 0 = (f₀, f₁, f₂, Q_b), the amplitude
// factors of cascades 0–2 (1 the open sea, 0 land or shelter) and the fraction of waves
// breaking on the bottom; layer 1 = (depth (m), f₃, f₄, f₅). The factors reach 1 and Q_b 0
// at the map's edge, and outside the map nothing is read, so the coast ends without a seam.
// What the tiles cannot show: the waves do not turn toward the shore (no refraction) nor
// shorten; their crests keep the open sea's direction and length, only their height, slope
// and foam follow the depth.

// The coast at one point: `near` = (f₀, f₁, f₂, Q_b), `far` = (depth (m), f₃, f₄, f₅).
struct OceanCoast {
    near: vec4<f32>,
    far: vec4<f32>,
}

// The open sea: every factor 1, no surf, deep water.
fn ocean_open_sea() -> OceanCoast {
    var c: OceanCoast;
    c.near = vec4<f32>(1.0, 1.0, 1.0, 0.0);
    c.far = vec4<f32>(1e4, 1.0, 1.0, 1.0);
    return c;
}

// uv of world point `xz` (m) in the coast texture, and in z whether the coast is read there
// (1 inside the map, 0 outside it or without a map).
fn ocean_coast_uv(u: OceanUniforms, xz: vec2<f32>) -> vec3<f32> {
    if (u.coast.w <= 0.0) {
        return vec3<f32>(0.0);
    }
    let size = max(u.coast_size.xy, vec2<f32>(1.0));
    let uv = ((xz - u.coast.xy) * u.coast.z + vec2<f32>(0.5)) / size;
    let inside = all(uv >= vec2<f32>(0.0)) && all(uv <= vec2<f32>(1.0));
    return vec3<f32>(uv, select(0.0, 1.0, inside));
}

// The coast at undisplaced point `xz` (m): the texture's two layers, bilinear, or the open
// sea outside the map.
fn ocean_coast(coast: texture_2d_array<f32>, coast_sampler: sampler, u: OceanUniforms, xz: vec2<f32>) -> OceanCoast {
    let c = ocean_coast_uv(u, xz);
    if (c.z <= 0.0) {
        return ocean_open_sea();
    }
    var out: OceanCoast;
    out.near = textureSampleLevel(coast, coast_sampler, c.xy, 0, 0.0);
    out.far = textureSampleLevel(coast, coast_sampler, c.xy, 1, 0.0);
    return out;
}

// The amplitude factor of cascade `c` (largest first) at a point of `coast`; a cascade past
// the sixth takes the sixth's (the shortest waves, limited by the same breaking).
fn ocean_coast_factor(coast: OceanCoast, c: u32) -> f32 {
    if (c < 3u) {
        return coast.near[c];
    }
    return coast.far[min(c - 2u, 3u)];
}

// `ocean_foam_surface` over a coast: the open sea's whitecaps and residual foam fade where
// the waves die (cascade 0's factor below 1), and the surf lays active foam over the fraction
// Q_b of breaking waves (as the crate's `foam_at` does, on 55 % of it: broken waves' bores
// are not white all over), with residual foam left behind in the surf zone (the streaks
// between the breakers, 35 % of Q_b). The breakers' foam sits on
// the most compressed crests: the whitecaps' placement field is measured against the local
// waves' (divided by cascade 1's factor, the cascade that field mostly holds), so a surf
// zone's shrunken waves still break on their crests.
fn ocean_coast_foam_surface(
    streaks: texture_2d<f32>,
    streak_sampler: sampler,
    u: OceanUniforms,
    xz: vec2<f32>,
    surface: OceanSurface,
    coast: OceanCoast,
) -> OceanSurface {
    var s = surface;
    let open = clamp(coast.near.x, 0.0, 1.0);
    let surf = clamp(coast.near.w, 0.0, 1.0);
    let f = clamp(s.coverage, 0.0, 1.0);
    let whitecaps = f * clamp(u.table.w, 0.0, 1.0);
    let residual = clamp((f - whitecaps) / max(1.0 - whitecaps, 1e-4), 0.0, 1.0);
    // Even where every wave has broken (Q_b = 1) the bores' foam covers part of the water:
    // 55 % active, 35 % of the rest residual (70 % in all; the residual drawn 55 % opaque).
    let a = max(whitecaps * open, 0.55 * surf);
    let r = max(residual * open, 0.35 * surf);
    let coverage = a + r * (1.0 - a);
    let share = a / max(coverage, 1e-4);
    let rank = ocean_whitecap_rank(u, s);
    let crest = rank.x / max(coast.near.y, 0.25);
    let streak = ocean_streak(streaks, streak_sampler, u, xz);
    let foam = ocean_foam_layers(coverage, share, crest, rank.y > 0.0, xz, u.wind.xy, s.footprint,
        s.across_footprint, streak);
    s.foam = foam.x;
    s.bubbles = foam.y;
    return s;
}
