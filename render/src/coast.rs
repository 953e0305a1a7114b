//! Coasts as an engine draws them: the coast's texels over the depth map ([`CoastTexels`],
//! packed by a [`CoastPacker`] once per map or weather), their place for the shader
//! (`OceanUniforms::coast`, `coast_size`), and procedural coasts both engines show
//! ([`CoastKind`]: an [`island`] with a beach and a bay, a [`breakwater`] sheltering a
//! beach) with the [`Terrain`] mesh of their land and sea bed.
//!
//! The shader (shaders/ocean_common.wgsl: `ocean_coast`, `ocean_coast_displacement`,
//! `ocean_coast_water_surface`, `ocean_coast_foam_surface`) scales each cascade's
//! displacement and slope by its factor at the point, lays the surf's foam (the fraction of
//! breaking waves Q_b) over the whitecaps, and tints shallow water over sand; outside the map
//! it reads nothing (factors 1, Q_b 0, deep water).

use std::str::FromStr;
use std::sync::Arc;

use ocean_fft::coast::BLEND_SECONDS;
use ocean_fft::half::f16;
use ocean_fft::{DepthMap, Error, OceanState};

/// The coast's texels over the depth map, RGBA16F, two layers of `size[0]` × `size[1]`
/// texels (texel (i, j) of layer l at `l·size[0]·size[1] + j·size[0] + i`, for world
/// (x₀ + i·Δ, z₀ + j·Δ) with (x₀, z₀) = `origin`, Δ = `spacing`):
///
/// - layer 0: `[f₀, f₁, f₂, Q_b]`, the amplitude factors of cascades 0–2 (no unit; 1 the open
///   sea, 0 land or shelter) and the fraction of waves breaking on the bottom in [0, 1]
///   (`Textures::pack_coast`, blended while a replaced map fades in);
/// - layer 1: `[d, f₃, f₄, f₅]`, the water depth d (m, ≤ 0 on land) and the factors of
///   cascades 3–5 (1 where the ocean has fewer cascades; a cascade past 5 takes f₅). These
///   are the current map's factors (`CoastField::factors`), not blended during a change of
///   map: the shortest waves, whose factor a 2 s blend hides least.
///
/// Upload to a 2-layer 2D array texture sampled with linear filtering and clamp-to-edge
/// addressing when [`generation`](Self::generation) changes.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CoastTexels {
    /// Both layers' texels, layer 0 first.
    pub texels: Vec<[f16; 4]>,
    /// Texels along x and along z.
    pub size: [usize; 2],
    /// World `[x, z]` of texel (0, 0), m.
    pub origin: [f64; 2],
    /// Distance between texels, m.
    pub spacing: f32,
    /// Incremented with every pack (never 0 once packed): upload when it changes.
    pub generation: u64,
}

impl CoastTexels {
    /// Layers of the texture.
    pub const LAYERS: usize = 2;

    /// The texels of layer `layer` (0 or 1).
    pub fn layer(&self, layer: usize) -> &[[f16; 4]] {
        let n = self.size[0] * self.size[1];
        &self.texels[layer * n..(layer + 1) * n]
    }

    /// `OceanUniforms::coast` and `coast_size`: x, z of texel (0, 0) (m), 1/spacing (1/m)
    /// and 1 (a map is bound); the texels along x and z.
    pub fn uniforms(&self) -> [[f32; 4]; 2] {
        [
            [
                self.origin[0] as f32,
                self.origin[1] as f32,
                1.0 / self.spacing,
                1.0,
            ],
            [self.size[0] as f32, self.size[1] as f32, 0.0, 0.0],
        ]
    }
}

/// `OceanUniforms::coast` and `coast_size` for `texels`, zeros without a map (the shader
/// reads no coast then).
pub fn coast_uniforms(texels: Option<&CoastTexels>) -> [[f32; 4]; 2] {
    texels.map_or([[0.0; 4]; 2], CoastTexels::uniforms)
}

/// Keeps an ocean's [`CoastTexels`]: packs them when the ocean's depth map (or the weather
/// it was solved for) changed, and every call during the [`BLEND_SECONDS`] that a new map
/// blends in; otherwise hands back the same texels (an `Arc` clone, no copy).
#[derive(Debug, Default)]
pub struct CoastPacker {
    texels: Option<Arc<CoastTexels>>,
    /// Address of the coast field packed last (a new `set_depth_map` makes a new one).
    field: usize,
    /// Sea time at which that field was first seen, s.
    seen: f64,
    generation: u64,
    scratch: Vec<[f32; 4]>,
}

impl CoastPacker {
    /// The coast texels of `ocean` now (`None` without a depth map).
    ///
    /// # Errors
    /// The crate's from `pack_coast`.
    pub fn pack(&mut self, ocean: &OceanState) -> Result<Option<Arc<CoastTexels>>, Error> {
        let textures = ocean.textures();
        let Some(field) = textures.coast() else {
            self.texels = None;
            self.field = 0;
            return Ok(None);
        };
        let address = std::ptr::from_ref(field) as usize;
        let t = ocean.time();
        if address != self.field {
            self.field = address;
            self.seen = t;
        } else if self.texels.is_some() && !(t >= self.seen && t - self.seen <= BLEND_SECONDS) {
            return Ok(self.texels.clone());
        }
        let map = field.map();
        let n = map.size[0] * map.size[1];
        self.scratch.resize(n, [0.0; 4]);
        textures.pack_coast(&mut self.scratch)?;
        self.generation += 1;
        let mut texels = match self.texels.take().map(Arc::try_unwrap) {
            Some(Ok(texels)) => texels,
            _ => CoastTexels::default(),
        };
        texels.texels.clear();
        texels
            .texels
            .extend(self.scratch.iter().map(|t| t.map(f16::from_f32)));
        let (factors, count) = (field.factors(), field.cascade_count());
        texels.texels.extend((0..n).map(|cell| {
            let f = |c: usize| {
                if count > 3 {
                    factors[cell * count + c.min(count - 1)]
                } else {
                    1.0
                }
            };
            [map.depth[cell], f(3), f(4), f(5)].map(f16::from_f32)
        }));
        texels.size = map.size;
        texels.origin = map.origin;
        texels.spacing = map.spacing;
        texels.generation = self.generation;
        let texels = Arc::new(texels);
        self.texels = Some(texels.clone());
        Ok(Some(texels))
    }
}

/// A procedural coast both engines show (`--coast` in the viewer and the Bevy example).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CoastKind {
    /// [`island`]: an island with beaches and a bay facing the waves.
    Island,
    /// [`breakwater`]: a straight beach behind a breakwater.
    Breakwater,
}

impl CoastKind {
    /// The names `--coast` takes besides `none`.
    pub const NAMES: [&'static str; 2] = ["island", "breakwater"];

    /// The coast's depth map for waves travelling toward +x (the presets' wind).
    pub fn depth_map(self) -> DepthMap {
        match self {
            CoastKind::Island => island(),
            CoastKind::Breakwater => breakwater(),
        }
    }

    /// A view of the coast: the eye (x, y, z; m), its heading (degrees from +x toward +z)
    /// and its pitch (degrees, negative down).
    pub fn view(self) -> ([f32; 3], f32, f32) {
        match self {
            CoastKind::Island => ([60.0, 38.0, -150.0], 28.0, -11.0),
            CoastKind::Breakwater => ([40.0, 32.0, -150.0], 42.0, -13.0),
        }
    }
}

impl FromStr for CoastKind {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "island" => Ok(CoastKind::Island),
            "breakwater" => Ok(CoastKind::Breakwater),
            other => Err(format!("unknown coast {other:?} (island, breakwater)")),
        }
    }
}

/// Side of both procedural maps in cells.
const CELLS: usize = 256;

/// The island's centre (world x, z; m), its shore's mean radius and the bay's depth into it
/// (m).
pub const ISLAND_CENTRE: [f64; 2] = [420.0, 0.0];
const ISLAND_RADIUS: f64 = 170.0;
const BAY_DEPTH: f64 = 90.0;

/// Depth (m) of the sea bed `s` metres offshore of a beach: 1:25 at the waterline,
/// steepening slowly offshore (12 m at 225 m, 21 m at 350 m), at most 35 m.
pub fn beach_depth(s: f64) -> f64 {
    (0.04 * s + 6e-5 * s * s).min(35.0)
}

/// Height (m) of dry land `s` metres inland of the waterline: a beach of 1:25 rounding off
/// into a 2.5 m berm.
fn land_height(s: f64) -> f64 {
    2.5 * (1.0 - (-s / 62.5).exp())
}

/// The island's shore radius (m) in direction `theta` from its centre (radians, from +x
/// toward +z): a wavy circle with a bay facing the waves (toward −x).
pub fn island_shore(theta: f64) -> f64 {
    let from_bay = (theta - std::f64::consts::PI)
        .sin()
        .atan2((theta - std::f64::consts::PI).cos());
    ISLAND_RADIUS + 12.0 * (3.0 * theta + 0.5).sin() + 7.0 * (5.0 * theta + 2.0).sin()
        - BAY_DEPTH * (-(from_bay / 0.55).powi(2)).exp()
}

/// An island with sandy beaches, a bay facing the waves (toward −x) and a 26 m hill, centred
/// on [`ISLAND_CENTRE`]: 256² cells 4 m apart (1 020 m a side), the sea bed falling at 1:25
/// from the waterline ([`beach_depth`]) to 20 m at the map's edge.
pub fn island() -> DepthMap {
    let spacing = 4.0f32;
    let half = 0.5 * (CELLS - 1) as f64 * f64::from(spacing);
    let origin = [ISLAND_CENTRE[0] - half, ISLAND_CENTRE[1] - half];
    let depth = cells(origin, spacing, |x, z| {
        let (dx, dz) = (x - ISLAND_CENTRE[0], z - ISLAND_CENTRE[1]);
        let r = dx.hypot(dz);
        let shore = island_shore(dz.atan2(dx));
        if r >= shore {
            beach_depth(r - shore)
        } else {
            let inland = shore - r;
            // The hill stands back from the bay, toward +x.
            let from_hill = (dx - 45.0).hypot(dz);
            let hill = 26.0 * (-(from_hill / 75.0).powi(2)).exp() * smoothstep(0.0, 60.0, inland);
            -(land_height(inland) + hill)
        }
    });
    DepthMap {
        origin,
        spacing,
        size: [CELLS, CELLS],
        depth,
    }
}

/// World x of the breakwater beach's waterline, and of the wall's axis (m); the wall's half
/// length along z, its crest height above still water and its crest's half width (m).
pub const BEACH_SHORE: f64 = 400.0;
pub const WALL_X: f64 = 250.0;
pub const WALL_HALF_LENGTH: f64 = 110.0;
const WALL_CREST: f64 = 3.0;
const WALL_HALF_WIDTH: f64 = 3.0;

/// A straight beach along z (its waterline at x = [`BEACH_SHORE`], the sea toward −x, the
/// sea bed of [`beach_depth`]) sheltered by a rubble-mound breakwater parallel to it (axis
/// x = [`WALL_X`], 220 m long, crest 3 m above the water and 6 m wide, sides of 1:1.5): 256²
/// cells 2 m apart (510 m a side), from x = 150 m.
pub fn breakwater() -> DepthMap {
    let spacing = 2.0f32;
    let origin = [150.0, -0.5 * (CELLS - 1) as f64 * f64::from(spacing)];
    let depth = cells(origin, spacing, |x, z| {
        let bed = if x <= BEACH_SHORE {
            beach_depth(BEACH_SHORE - x)
        } else {
            -land_height(x - BEACH_SHORE)
        };
        let along = (z.abs() - WALL_HALF_LENGTH).max(0.0);
        let off = (x - WALL_X).hypot(along);
        let wall = WALL_CREST - (off - WALL_HALF_WIDTH).max(0.0) / 1.5;
        // The higher of the bed and the wall: the least water.
        bed.min(-wall)
    });
    DepthMap {
        origin,
        spacing,
        size: [CELLS, CELLS],
        depth,
    }
}

/// Depths of a CELLS² map at `origin`, `spacing` apart, from `depth(x, z)` (f64 m).
fn cells(origin: [f64; 2], spacing: f32, depth: impl Fn(f64, f64) -> f64) -> Vec<f32> {
    let s = f64::from(spacing);
    (0..CELLS * CELLS)
        .map(|c| {
            let (i, j) = (c % CELLS, c / CELLS);
            depth(origin[0] + i as f64 * s, origin[1] + j as f64 * s) as f32
        })
        .collect()
}

fn smoothstep(a: f64, b: f64, x: f64) -> f64 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The ground of a depth map as a triangle mesh: a vertex per cell at (x, −depth, z) (m),
/// its unit normal, and a linear RGB colour by height and slope (wet sand at and below the
/// waterline, dry sand up to 1.5 m, grass above, rock where steeper than 1:1.5 and on land
/// with water within 16 m on both sides: a wall, a spit); counter-clockwise seen
/// from above.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Terrain {
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    pub colours: Vec<[f32; 4]>,
    pub indices: Vec<u32>,
}

/// Linear RGB colours of the ground.
const WET_SAND: [f32; 3] = [0.20, 0.16, 0.105];
const SAND: [f32; 3] = [0.48, 0.41, 0.28];
const GRASS: [f32; 3] = [0.075, 0.13, 0.035];
const ROCK: [f32; 3] = [0.22, 0.21, 0.195];

fn mix3(a: [f32; 3], b: [f32; 3], t: f32) -> [f32; 3] {
    std::array::from_fn(|k| a[k] + (b[k] - a[k]) * t)
}

/// The ground of `map` ([`Terrain`]).
pub fn terrain(map: &DepthMap) -> Terrain {
    let [nx, nz] = map.size;
    let s = map.spacing;
    let height = |i: usize, j: usize| -map.depth[j.min(nz - 1) * nx + i.min(nx - 1)];
    // Narrow land: water within 16 m on both sides along x or along z.
    let reach = (16.0 / s).ceil().max(1.0) as isize;
    let wet = |i: isize, j: isize| {
        (0..nx as isize).contains(&i)
            && (0..nz as isize).contains(&j)
            && height(i as usize, j as usize) < 0.0
    };
    let water_within = |i: usize, j: usize, di: isize, dj: isize| {
        (1..=reach).any(|k| wet(i as isize + k * di, j as isize + k * dj))
    };
    let mut t = Terrain::default();
    for j in 0..nz {
        for i in 0..nx {
            let y = height(i, j);
            let x = (map.origin[0] + i as f64 * f64::from(s)) as f32;
            let z = (map.origin[1] + j as f64 * f64::from(s)) as f32;
            t.positions.push([x, y, z]);
            // Central differences (one-sided at the edges).
            let (i0, i1) = (i.saturating_sub(1), (i + 1).min(nx - 1));
            let (j0, j1) = (j.saturating_sub(1), (j + 1).min(nz - 1));
            let gx = (height(i1, j) - height(i0, j)) / ((i1 - i0) as f32 * s);
            let gz = (height(i, j1) - height(i, j0)) / ((j1 - j0) as f32 * s);
            let len = (gx * gx + 1.0 + gz * gz).sqrt();
            t.normals.push([-gx / len, 1.0 / len, -gz / len]);
            let steep = gx.hypot(gz);
            // A slow wobble breaks the line between sand and grass.
            let jitter = (x * 0.031).sin() * (z * 0.027 + (x * 0.011).sin()).cos();
            let narrow = y > -0.5
                && (water_within(i, j, -1, 0) && water_within(i, j, 1, 0)
                    || water_within(i, j, 0, -1) && water_within(i, j, 0, 1));
            let dry = smoothstep(0.15, 0.5, f64::from(y)) as f32;
            let grassy = smoothstep(1.2, 2.0, f64::from(y + 0.5 * jitter)) as f32;
            let rocky = if narrow {
                1.0
            } else {
                smoothstep(0.45, 0.65, f64::from(steep)) as f32
            };
            let ground = mix3(mix3(WET_SAND, SAND, dry), GRASS, grassy);
            let c = mix3(ground, ROCK, rocky);
            t.colours.push([c[0], c[1], c[2], 1.0]);
        }
    }
    for j in 0..nz - 1 {
        for i in 0..nx - 1 {
            let a = (j * nx + i) as u32;
            let (b, c, d) = (a + 1, a + nx as u32, a + nx as u32 + 1);
            // Counter-clockwise from above (+y): x right, z toward the viewer of a
            // right-handed frame.
            t.indices.extend_from_slice(&[a, c, b, b, c, d]);
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use ocean_fft::SeaState;

    /// The island's sea bed falls from its waterline at the beach's slope; its centre is
    /// land and its corners are water at least 15 m deep; the bay cuts into it toward −x.
    #[test]
    fn the_island_is_what_it_says() {
        let map = island();
        map.validate().unwrap();
        let at = |x: f64, z: f64| {
            let i = ((x - map.origin[0]) / f64::from(map.spacing)).round() as usize;
            let j = ((z - map.origin[1]) / f64::from(map.spacing)).round() as usize;
            map.depth[j * map.size[0] + i]
        };
        let [cx, cz] = ISLAND_CENTRE;
        assert!(at(cx + 45.0, cz) < -20.0, "the hill: {}", at(cx + 45.0, cz));
        assert!(at(map.origin[0], map.origin[1]) > 15.0);
        // Toward +z (θ = π/2): shore radius from `island_shore`; 100 m off it, 1:25 and a
        // little more.
        let shore = island_shore(std::f64::consts::FRAC_PI_2);
        let d = at(cx, cz + shore + 100.0);
        assert!((f64::from(d) - beach_depth(100.0)).abs() < 0.3, "{d}");
        assert!((beach_depth(100.0) - 4.6).abs() < 1e-9);
        // The bay: water 40 m inside the shore's mean radius toward −x, land toward +x.
        assert!(at(cx - ISLAND_RADIUS + 40.0, cz) > 0.5);
        assert!(at(cx + ISLAND_RADIUS - 40.0, cz) < 0.0);
    }

    /// The breakwater's cells are dry (depth ≤ 0) along its crest, water stands on both
    /// sides of it, and the beach behind is where it says.
    #[test]
    fn the_breakwater_is_what_it_says() {
        let map = breakwater();
        map.validate().unwrap();
        let s = f64::from(map.spacing);
        let at = |x: f64, z: f64| {
            let i = ((x - map.origin[0]) / s).round() as usize;
            let j = ((z - map.origin[1]) / s).round() as usize;
            map.depth[j * map.size[0] + i]
        };
        for z in [-100.0, -50.0, 0.0, 50.0, 100.0] {
            assert!(at(WALL_X, z) <= 0.0, "crest at z = {z}: {}", at(WALL_X, z));
            assert!((at(WALL_X, z) + WALL_CREST as f32).abs() < 1e-4);
            assert!(at(WALL_X - 20.0, z) > 4.0);
            assert!(at(WALL_X + 20.0, z) > 4.0);
        }
        // Beyond the wall's ends the sea is open.
        assert!(at(WALL_X, 160.0) > 5.0);
        assert!((f64::from(at(BEACH_SHORE - 50.0, 0.0)) - beach_depth(50.0)).abs() < 1e-4);
        assert!(at(BEACH_SHORE + 20.0, 0.0) < 0.0);
    }

    /// The terrain has a vertex per cell at the map's ground, unit normals up, indices
    /// inside, and sand at the waterline, grass high up, rock on the breakwater's side.
    #[test]
    fn the_terrain_follows_the_map() {
        let map = breakwater();
        let t = terrain(&map);
        let n = map.size[0] * map.size[1];
        assert_eq!(t.positions.len(), n);
        assert_eq!(t.indices.len(), 6 * (map.size[0] - 1) * (map.size[1] - 1));
        assert!(t.indices.iter().all(|&i| (i as usize) < n));
        for (k, p) in t.positions.iter().enumerate() {
            assert_eq!(p[1], -map.depth[k]);
            let len = t.normals[k].iter().map(|v| v * v).sum::<f32>().sqrt();
            assert!((len - 1.0).abs() < 1e-4 && t.normals[k][1] > 0.0);
        }
        // The first triangle faces up: (b − a) × (c − a) along +y for a, c, b.
        let [a, c, b] = [0, 1, 2].map(|k| t.positions[t.indices[k] as usize]);
        let (u, v) = ([c[0] - a[0], c[2] - a[2]], [b[0] - a[0], b[2] - a[2]]);
        assert!(u[1] * v[0] - u[0] * v[1] > 0.0, "faces up");
        let colour_at = |x: f64, z: f64| {
            let i = ((x - map.origin[0]) / f64::from(map.spacing)).round() as usize;
            let j = ((z - map.origin[1]) / f64::from(map.spacing)).round() as usize;
            t.colours[j * map.size[0] + i]
        };
        let near = |c: [f32; 4], want: [f32; 3]| (0..3).all(|k| (c[k] - want[k]).abs() < 0.02);
        assert!(near(colour_at(BEACH_SHORE, 0.0), WET_SAND));
        assert!(near(colour_at(BEACH_SHORE + 200.0, 0.0), GRASS));
        let side = colour_at(WALL_X + 6.0, 0.0);
        assert!(near(side, ROCK), "{side:?}");
        for x in [-3.0, 0.0, 3.0] {
            let crest = colour_at(WALL_X + x, 0.0);
            assert!(near(crest, ROCK), "the wall's crest is rock: {crest:?}");
        }
    }

    /// The packer's texels are `pack_coast`'s in f16 at every map cell, with the depth and
    /// the other cascades' factors in layer 1; it packs again only for a new map (or while
    /// one blends in), and an ocean without a map has none.
    #[test]
    fn texels_are_the_crates_coast() {
        let (spectrum, mut config) = SeaState::FreshBreeze.build();
        config.size = 32;
        let mut ocean = OceanState::new(spectrum, config).unwrap();
        let mut packer = CoastPacker::default();
        assert!(packer.pack(&ocean).unwrap().is_none());
        assert_eq!(coast_uniforms(None), [[0.0; 4]; 2]);

        // A small 1:25 beach: 64 × 16 cells 4 m apart rising along +x.
        let map = DepthMap {
            origin: [-100.0, 20.0],
            spacing: 4.0,
            size: [64, 16],
            depth: (0..64 * 16)
                .map(|c| 14.0 - 0.25 * (c % 64) as f32)
                .collect(),
        };
        ocean.set_depth_map(Some(map.clone())).unwrap();
        ocean.set_time(30.0).unwrap();
        let texels = packer.pack(&ocean).unwrap().expect("a map");
        let mut expected = vec![[0.0f32; 4]; 64 * 16];
        ocean.textures().pack_coast(&mut expected).unwrap();
        assert_eq!(texels.size, [64, 16]);
        assert_eq!(texels.texels.len(), 2 * 64 * 16);
        for (got, want) in texels.layer(0).iter().zip(&expected) {
            for k in 0..4 {
                assert_eq!(got[k], f16::from_f32(want[k]));
            }
        }
        // Cell (40, 7): x = 60 m, z = 48 m, 4 m deep.
        let cell = 7 * 64 + 40;
        assert_eq!(texels.layer(1)[cell][0], f16::from_f32(map.depth[cell]));
        assert!(expected.iter().any(|t| t[3] > 0.05), "surf on the beach");
        assert!(expected.iter().any(|t| t[0] < 0.9), "waves shrink");
        let field = ocean.textures().coast().unwrap();
        let count = field.cascade_count();
        let f3 = if count > 3 {
            field.factors()[cell * count + 3]
        } else {
            1.0
        };
        assert_eq!(texels.layer(1)[cell][1], f16::from_f32(f3));
        let u = texels.uniforms();
        assert_eq!(u[0], [-100.0, 20.0, 0.25, 1.0]);
        assert_eq!(u[1], [64.0, 16.0, 0.0, 0.0]);

        // Past the blend (counted from when the packer saw the map), the same texels (the
        // same allocation) until the map changes.
        ocean.step(2.5).unwrap();
        let again = packer.pack(&ocean).unwrap().unwrap();
        assert!(Arc::ptr_eq(&texels, &again));
        let mut shallower = map;
        shallower.depth.iter_mut().for_each(|d| *d -= 1.0);
        ocean.set_depth_map(Some(shallower)).unwrap();
        let new = packer.pack(&ocean).unwrap().unwrap();
        assert!(new.generation > texels.generation);
        ocean.set_depth_map(None).unwrap();
        ocean.step(3.0).unwrap();
        assert!(packer.pack(&ocean).unwrap().is_none());
    }
}
