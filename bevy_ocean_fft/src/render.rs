//! Drawing the sea with Bevy's renderer: the cascade textures (two 2D array textures, a layer
//! per cascade, RGBA16F with mip chains, uploaded by the render world with
//! `RenderQueue::write_texture` from the texels the step task packed), a clipmap of ring
//! meshes that follows the camera, the water material carrying the crate's reference shader,
//! and a sky dome with the same shader's sky.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use bevy::asset::uuid_handle;
use bevy::camera::visibility::NoFrustumCulling;
use bevy::light::{NotShadowCaster, NotShadowReceiver};
use bevy::mesh::MeshVertexBufferLayoutRef;
use bevy::pbr::{MaterialPipeline, MaterialPipelineKey, MaterialPlugin};
use bevy::prelude::*;
use bevy::render::render_resource::{
    AsBindGroup, RenderPipelineDescriptor, ShaderType, SpecializedMeshPipelineError,
};
use bevy::render::{ExtractSchedule, Render, RenderApp, RenderSystems};
use bevy::shader::{Shader, ShaderRef};

use ocean_fft_render::clipmap::{rings, Ring, HOLES, MAX_RINGS};
use ocean_fft_render::{Light, OceanInfo, OceanUniforms, Tiling};

use crate::sim::OceanTexels;

use assets::{cascade_image, ring_mesh};
use upload::{extract_texels, upload_texels};
use wake::{coast_image, streak_image, wake_image};

mod assets;
mod upload;
mod wake;

const COMMON_SHADER: Handle<Shader> = uuid_handle!("5b0e3c52-8f0b-4d6e-9a51-0c8f1f5a7e31");
const WATER_SHADER: Handle<Shader> = uuid_handle!("0b7a2f41-6c3d-4e8a-b1f2-7d9e5c4a3b20");
const SKY_SHADER: Handle<Shader> = uuid_handle!("c3e91d07-2a4b-4f6c-8e1d-5b7a9f0c2d48");

/// Radius of the sky dome, m (beyond the mesh's corners).
pub const SKY_RADIUS: f32 = 400_000.0;

/// How the sea and the sky look: the reference shader's palette (linear RGB, in the units
/// the water is shaded in before Bevy's tone mapping) and its haze. The sun's direction and
/// colour come from the scene's first `DirectionalLight` (its illuminance times the camera's
/// exposure, scaled by `sun_scale`); `fallback_sun` is used when the scene has none.
#[derive(Resource, Debug, Clone, Copy, PartialEq)]
pub struct OceanAppearance {
    /// 0 for a clear sky, 1 for a heavy overcast (no sun disc, no glitter).
    pub overcast: f32,
    /// Sky radiance at the zenith and at the horizon.
    pub zenith: Vec3,
    pub horizon: Vec3,
    /// The colour of deep water, and the tint of thin, high crests lit from behind.
    pub deep: Vec3,
    pub subsurface: Vec3,
    /// Distance over which the haze takes 63 % of the light, m.
    pub haze_distance: f32,
    /// Factor on the palette (the reference shader's exposure).
    pub exposure: f32,
    /// The reference shader's sun per unit of Bevy's exposed illuminance (colour × lux ×
    /// exposure). 1/(0.6π): a white Lambertian body in Bevy shows E·exposure/π, and the
    /// reference shader's bodies show 0.6 of its sun, so both agree on how bright the sun is.
    pub sun_scale: f32,
    /// Without a directional light: unit vector toward the sun, and its colour.
    pub fallback_sun: Vec3,
    pub fallback_sun_colour: Vec3,
    /// Strength of the tiling breaker in [0, 1] (0: every cascade repeats exactly).
    pub tiling: f32,
}

impl Default for OceanAppearance {
    /// A clear day (the viewer's palette for a sun 25° up).
    fn default() -> Self {
        OceanAppearance {
            overcast: 0.0,
            zenith: Vec3::new(0.06, 0.17, 0.46) * 0.77,
            horizon: Vec3::new(0.48, 0.58, 0.74) * 0.77 * 0.93,
            deep: Vec3::new(0.004, 0.030, 0.055),
            subsurface: Vec3::new(0.03, 0.21, 0.19),
            haze_distance: 6000.0,
            exposure: 0.8,
            sun_scale: 1.0 / (0.6 * std::f32::consts::PI),
            fallback_sun: Vec3::new(0.8, 0.42, 0.42).normalize(),
            fallback_sun_colour: Vec3::new(1.0, 0.92, 0.82) * 2.0,
            tiling: 1.0,
        }
    }
}

impl OceanAppearance {
    /// A heavy overcast: grey sky and water, no sun disc, a third of the haze distance.
    pub fn overcast() -> OceanAppearance {
        OceanAppearance {
            overcast: 1.0,
            zenith: Vec3::new(0.42, 0.44, 0.47),
            horizon: Vec3::new(0.15, 0.16, 0.175),
            deep: Vec3::new(0.004, 0.008, 0.011),
            subsurface: Vec3::new(0.010, 0.030, 0.028),
            haze_distance: 2000.0,
            ..OceanAppearance::default()
        }
    }
}

/// The reference shader's `OceanUniforms` (shaders/ocean_common.wgsl) as Bevy binds it: the
/// render layer's block, vec4 by vec4 (its std140 layout is its plain one).
#[derive(Debug, Clone, Copy, ShaderType)]
pub struct UniformBlock {
    pub vec4s: [Vec4; OceanUniforms::VEC4S],
}

impl Default for UniformBlock {
    fn default() -> Self {
        UniformBlock::from(&bytemuck::Zeroable::zeroed())
    }
}

impl From<&OceanUniforms> for UniformBlock {
    fn from(uniforms: &OceanUniforms) -> Self {
        let vec4s: &[[f32; 4]; OceanUniforms::VEC4S] = bytemuck::cast_ref(uniforms);
        UniformBlock {
            vec4s: vec4s.map(Vec4::from_array),
        }
    }
}

/// The water: the crate's reference shader with Bevy's bindings (src/shaders/water.wgsl),
/// a `Material` of its own so that it takes Bevy's directional light, shadows, fog, exposure
/// and tone mapping.
#[derive(Asset, AsBindGroup, TypePath, Debug, Clone)]
pub struct OceanMaterial {
    /// Layer c: cascade c's `DisplacementFoam` texels (D_x, η, D_z, foam), with the
    /// vertex stage's sampler (no anisotropy).
    #[texture(0, dimension = "2d_array")]
    #[sampler(1)]
    pub displacement: Handle<Image>,
    /// Layer c: cascade c's `SlopeJacobianFoam` texels (∂y/∂x, ∂y/∂z, J, foam), with the
    /// fragment stage's anisotropic sampler.
    #[texture(2, dimension = "2d_array")]
    #[sampler(3)]
    pub slope: Handle<Image>,
    #[uniform(4)]
    pub uniforms: UniformBlock,
    /// The wake window's texels (η, ∂y/∂x, ∂y/∂z, foam), clamped to the edge (1×1 without
    /// wakes).
    #[texture(5)]
    #[sampler(6)]
    pub wake: Handle<Image>,
    /// The foam's streak field (the library's `FoamStreaks`), R16F, repeat, linear.
    #[texture(7)]
    #[sampler(8)]
    pub streaks: Handle<Image>,
    /// The coast over the depth map (`CoastTexels`: layer 0 = f₀, f₁, f₂, Q_b; layer 1 =
    /// depth, f₃, f₄, f₅), read with the wake's sampler (clamped, linear); 1×1 without a map.
    #[texture(9, dimension = "2d_array")]
    pub coast: Handle<Image>,
}

impl Material for OceanMaterial {
    fn vertex_shader() -> ShaderRef {
        ShaderRef::Handle(WATER_SHADER)
    }

    fn fragment_shader() -> ShaderRef {
        ShaderRef::Handle(WATER_SHADER)
    }

    // The prepasses and shadow maps would draw the undisplaced rings.
    fn enable_prepass() -> bool {
        false
    }

    fn enable_shadows() -> bool {
        false
    }

    fn specialize(
        _pipeline: &MaterialPipeline,
        descriptor: &mut RenderPipelineDescriptor,
        _layout: &MeshVertexBufferLayoutRef,
        _key: MaterialPipelineKey<Self>,
    ) -> Result<(), SpecializedMeshPipelineError> {
        // Seen from below too (a camera under a crest).
        descriptor.primitive.cull_mode = None;
        Ok(())
    }
}

/// The sky dome: the reference shader's `ocean_sky` (src/shaders/sky.wgsl).
#[derive(Asset, AsBindGroup, TypePath, Debug, Clone)]
pub struct OceanSkyMaterial {
    #[uniform(0)]
    pub uniforms: UniformBlock,
}

impl Material for OceanSkyMaterial {
    fn vertex_shader() -> ShaderRef {
        ShaderRef::Handle(SKY_SHADER)
    }

    fn fragment_shader() -> ShaderRef {
        ShaderRef::Handle(SKY_SHADER)
    }

    fn enable_prepass() -> bool {
        false
    }

    fn enable_shadows() -> bool {
        false
    }

    fn specialize(
        _pipeline: &MaterialPipeline,
        descriptor: &mut RenderPipelineDescriptor,
        _layout: &MeshVertexBufferLayoutRef,
        _key: MaterialPipelineKey<Self>,
    ) -> Result<(), SpecializedMeshPipelineError> {
        // Seen from inside.
        descriptor.primitive.cull_mode = None;
        Ok(())
    }
}

/// Marks the camera the water's rings and the sky follow (without one: the first 3D camera).
#[derive(Component, Debug, Clone, Copy, Default)]
pub struct OceanCamera;

/// A ring of the clipmap (0 the finest).
#[derive(Component, Debug, Clone, Copy)]
pub struct OceanRing(pub usize);

/// The sky dome.
#[derive(Component, Debug, Clone, Copy)]
pub struct OceanSky;

/// The render side's assets.
#[derive(Resource, Debug, Clone)]
pub struct OceanRender {
    pub material: Handle<OceanMaterial>,
    pub sky: Handle<OceanSkyMaterial>,
    /// The full square (ring 0) and the rings with their hole at each of the four offsets.
    pub full: Handle<Mesh>,
    pub rings: [Handle<Mesh>; 4],
    /// Half-width of every ring in cells (even).
    pub half_cells: u32,
    /// The textures' grid: (N, cascades), and the images.
    grid: (usize, usize),
    displacement: Handle<Image>,
    slope: Handle<Image>,
    /// The wake window's image and side (0: the 1×1 placeholder).
    wake: Handle<Image>,
    wake_size: usize,
    /// The streak field's image and size (across, along; (0, 0): the placeholder).
    streaks: Handle<Image>,
    streak_size: (usize, usize),
    /// The coast's image and size ([0, 0]: the placeholder), and its place for the uniforms.
    coast: Handle<Image>,
    coast_size: [usize; 2],
    coast_uniforms: [[f32; 4]; 2],
    /// The last texels' information.
    info: OceanInfo,
    /// The uniforms both materials get.
    uniforms: OceanUniforms,
}

/// The render world's last upload of the texels (CPU time of the `write_texture` calls), ms,
/// as f64 bits.
#[derive(Resource, Debug, Clone, Default)]
pub struct UploadTime(pub Arc<AtomicU64>);

impl UploadTime {
    /// The last upload's CPU time, ms.
    pub fn ms(&self) -> f64 {
        f64::from_bits(self.0.load(Ordering::Relaxed))
    }
}

/// The rendering half of the plugin (added by `OceanPlugin` when the app renders).
pub(crate) struct OceanRenderPlugin {
    pub half_cells: u32,
    pub anisotropy: u16,
}

impl Plugin for OceanRenderPlugin {
    fn build(&self, app: &mut App) {
        let common = Shader::from_wgsl(
            concat!(
                "#define_import_path ocean_fft::common\n",
                include_str!("../../shaders/ocean_common.wgsl")
            ),
            "ocean_fft/ocean_common.wgsl",
        );
        let mut shaders = app.world_mut().resource_mut::<Assets<Shader>>();
        for (handle, shader) in [
            (&COMMON_SHADER, common),
            (
                &WATER_SHADER,
                Shader::from_wgsl(
                    include_str!("shaders/water.wgsl"),
                    "bevy_ocean_fft/water.wgsl",
                ),
            ),
            (
                &SKY_SHADER,
                Shader::from_wgsl(include_str!("shaders/sky.wgsl"), "bevy_ocean_fft/sky.wgsl"),
            ),
        ] {
            shaders
                .insert(handle.id(), shader)
                .expect("a uuid handle is always valid");
        }
        let upload = UploadTime::default();
        app.add_plugins((
            MaterialPlugin::<OceanMaterial>::default(),
            MaterialPlugin::<OceanSkyMaterial>::default(),
        ))
        .init_resource::<OceanAppearance>()
        .insert_resource(upload.clone())
        .insert_resource(RingHalfCells(self.half_cells.clamp(8, 256) & !1))
        .insert_resource(Anisotropy(self.anisotropy))
        .add_systems(Startup, setup)
        .add_systems(
            PostUpdate,
            (fit_textures, follow_camera)
                .chain()
                .after(bevy::transform::TransformSystems::Propagate),
        );
        if let Some(render_app) = app.get_sub_app_mut(RenderApp) {
            render_app
                .insert_resource(upload)
                .add_systems(ExtractSchedule, extract_texels)
                .add_systems(
                    Render,
                    upload_texels.in_set(RenderSystems::PrepareResources),
                );
        }
    }
}

#[derive(Resource)]
struct RingHalfCells(u32);

#[derive(Resource)]
struct Anisotropy(u16);

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut images: ResMut<Assets<Image>>,
    mut materials: ResMut<Assets<OceanMaterial>>,
    mut skies: ResMut<Assets<OceanSkyMaterial>>,
    half: Res<RingHalfCells>,
    anisotropy: Res<Anisotropy>,
) {
    let m = half.0;
    let full = meshes.add(ring_mesh(m, None));
    let rings = HOLES.map(|hole| meshes.add(ring_mesh(m, Some(hole))));
    // Placeholders until the first ocean's grid is known.
    let displacement = images.add(cascade_image(2, 1, 1));
    let slope = images.add(cascade_image(2, 1, anisotropy.0));
    let wake = images.add(wake_image(0));
    let streaks = images.add(streak_image(0, 0));
    let coast = images.add(coast_image([1, 1]));
    let material = materials.add(OceanMaterial {
        displacement: displacement.clone(),
        slope: slope.clone(),
        uniforms: UniformBlock::default(),
        wake: wake.clone(),
        streaks: streaks.clone(),
        coast: coast.clone(),
    });
    let sky = skies.add(OceanSkyMaterial {
        uniforms: UniformBlock::default(),
    });
    for ring in 0..MAX_RINGS {
        commands.spawn((
            Name::new(format!("ocean ring {ring}")),
            OceanRing(ring),
            Mesh3d(if ring == 0 {
                full.clone()
            } else {
                rings[0].clone()
            }),
            MeshMaterial3d(material.clone()),
            Transform::default(),
            Visibility::Hidden,
            NoFrustumCulling,
            NotShadowCaster,
            NotShadowReceiver,
        ));
    }
    commands.spawn((
        Name::new("ocean sky"),
        OceanSky,
        Mesh3d(meshes.add(Sphere::new(1.0).mesh().uv(48, 24))),
        MeshMaterial3d(sky.clone()),
        Transform::from_scale(Vec3::splat(SKY_RADIUS)),
        NoFrustumCulling,
        NotShadowCaster,
        NotShadowReceiver,
    ));
    commands.insert_resource(OceanRender {
        material,
        sky,
        full,
        rings,
        half_cells: m,
        grid: (0, 0),
        displacement,
        slope,
        wake,
        wake_size: 0,
        streaks,
        streak_size: (0, 0),
        coast,
        coast_size: [0, 0],
        coast_uniforms: [[0.0; 4]; 2],
        info: OceanInfo::default(),
        uniforms: bytemuck::Zeroable::zeroed(),
    });
}

/// New images when the ocean's grid (N or the number of cascades) changed.
fn fit_textures(
    texels: Res<OceanTexels>,
    render: Option<ResMut<OceanRender>>,
    mut images: ResMut<Assets<Image>>,
    mut materials: ResMut<Assets<OceanMaterial>>,
    anisotropy: Res<Anisotropy>,
) {
    let (Some(mut render), Some(frame)) = (render, texels.texels.as_ref()) else {
        return;
    };
    render.info = frame.info;
    render.uniforms.wake = frame.wake.uniform();
    if render.wake_size != frame.wake.size {
        render.wake_size = frame.wake.size;
        render.wake = images.add(wake_image(frame.wake.size));
        if let Some(mut material) = materials.get_mut(&render.material) {
            material.wake = render.wake.clone();
        }
    }
    let streak_size = (frame.streaks.across, frame.streaks.along);
    if render.streak_size != streak_size {
        render.streak_size = streak_size;
        render.streaks = images.add(streak_image(streak_size.0, streak_size.1));
        if let Some(mut material) = materials.get_mut(&render.material) {
            material.streaks = render.streaks.clone();
        }
    }
    render.coast_uniforms = ocean_fft_render::coast_uniforms(frame.coast.as_deref());
    let coast_size = frame.coast.as_ref().map_or([0, 0], |c| c.size);
    if render.coast_size != coast_size {
        render.coast_size = coast_size;
        render.coast = images.add(coast_image(coast_size.map(|n| n.max(1))));
        if let Some(mut material) = materials.get_mut(&render.material) {
            material.coast = render.coast.clone();
        }
    }
    let grid = (frame.texels.size, frame.texels.cascades);
    if render.grid == grid {
        return;
    }
    render.grid = grid;
    render.displacement = images.add(cascade_image(grid.0, grid.1, 1));
    render.slope = images.add(cascade_image(grid.0, grid.1, anisotropy.0));
    if let Some(mut material) = materials.get_mut(&render.material) {
        material.displacement = render.displacement.clone();
        material.slope = render.slope.clone();
    }
}

/// The rings and the sky follow the camera; the uniforms follow the camera, the light and
/// the ocean.
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
fn follow_camera(
    render: Option<ResMut<OceanRender>>,
    appearance: Res<OceanAppearance>,
    cameras: Query<(&GlobalTransform, Has<OceanCamera>), With<Camera3d>>,
    mut rings_query: Query<
        (
            &OceanRing,
            &mut Transform,
            &mut GlobalTransform,
            &mut Visibility,
            &mut Mesh3d,
        ),
        (Without<OceanSky>, Without<Camera3d>),
    >,
    mut sky: Query<
        (&mut Transform, &mut GlobalTransform),
        (With<OceanSky>, Without<OceanRing>, Without<Camera3d>),
    >,
    mut materials: ResMut<Assets<OceanMaterial>>,
    mut skies: ResMut<Assets<OceanSkyMaterial>>,
) {
    let Some(mut render) = render else {
        return;
    };
    let Some((camera, _)) = cameras
        .iter()
        .max_by_key(|(_, marked)| *marked)
        .map(|(t, m)| (t.translation(), m))
    else {
        return;
    };
    let ready = render.info.cascades > 0;
    let mut levels = [Ring::default(); MAX_RINGS];
    let count = rings(
        [camera.x, camera.z],
        camera.y,
        render.half_cells,
        &mut levels,
    );
    for (ring, mut transform, mut global, mut visibility, mut mesh) in &mut rings_query {
        let Some(level) = levels[..count].get(ring.0).filter(|_| ready) else {
            *visibility = Visibility::Hidden;
            continue;
        };
        *visibility = Visibility::Visible;
        *transform = Transform::from_xyz(level.centre[0], 0.0, level.centre[1])
            .with_scale(Vec3::new(level.spacing, 1.0, level.spacing));
        *global = GlobalTransform::from(*transform);
        let wanted = match level.hole {
            None => &render.full,
            Some(hole) => &render.rings[hole],
        };
        if mesh.0 != *wanted {
            mesh.0 = wanted.clone();
        }
    }
    for (mut transform, mut global) in &mut sky {
        transform.translation = camera;
        *global = GlobalTransform::from(*transform);
    }

    let a = &*appearance;
    let light = Light {
        sun: a.fallback_sun.normalize_or_zero().to_array(),
        overcast: a.overcast,
        sun_colour: a.fallback_sun_colour.to_array(),
        zenith: a.zenith.to_array(),
        horizon: a.horizon.to_array(),
        deep: a.deep.to_array(),
        subsurface: a.subsurface.to_array(),
        haze_distance: a.haze_distance,
    };
    let tiling = Tiling {
        strength: a.tiling,
        ..Tiling::default()
    };
    let render = &mut *render;
    let u = &mut render.uniforms;
    u.set_light(&light, a.exposure, a.sun_scale);
    u.set_ocean(&render.info, [camera.x, camera.z], &tiling);
    u.tiling[3] = render.half_cells as f32;
    [u.coast, u.coast_size] = render.coast_uniforms;
    let block = UniformBlock::from(&*u);
    if let Some(mut sky) = skies.get_mut(&render.sky) {
        sky.uniforms = block;
    }
    if let Some(mut material) = materials.get_mut(&render.material) {
        material.uniforms = block;
    }
}
