//! The wgpu side: the reference shader's pipelines, the cascade textures, the clipmap mesh,
//! the floating bodies' meshes, and drawing a frame into any target (the window or a
//! screenshot).

use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use wgpu::util::DeviceExt;

use ocean_fft_render::clipmap::{grid_indices, HOLES, MAX_RINGS};
use ocean_fft_render::{OceanUniforms, Tiling};

use meshes::{boat, buoy, BodyVertex};

mod meshes;
mod terrain;
mod textures;
mod uniforms;

use textures::OceanTextures;

/// The reference shading functions alone (shaders/ocean_common.wgsl), for the tests that
/// run them.
#[cfg(test)]
pub const COMMON: &str = include_str!("../../shaders/ocean_common.wgsl");

/// The reference shader: the shading functions, then the viewer's bindings and entry points.
pub const SHADER: &str = concat!(
    include_str!("../../shaders/ocean_common.wgsl"),
    "\n",
    include_str!("../../shaders/ocean.wgsl")
);

/// Depth format (reversed depth: 1 near, 0 at infinity).
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// The shader's `Globals` (ocean.wgsl), field for field; its size is checked against
/// naga's layout of the WGSL struct in the tests.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct Globals {
    pub view_proj: [[f32; 4]; 4],
    pub inverse_view_proj: [[f32; 4]; 4],
    /// xyz: the eye (m); w: the sea's time (s).
    pub eye: [f32; 4],
    /// Ring r: centre x, z (m), vertex spacing (m), half-width M in cells.
    pub levels: [[f32; 4]; MAX_RINGS],
    /// The shading functions' inputs: `sun_colour.w` the exposure, `tiling.w` the number of
    /// rings.
    pub ocean: OceanUniforms,
}

/// One floating body's instance: model matrix columns and colour.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct BodyInstance {
    pub model: [[f32; 4]; 4],
    pub colour: [f32; 4],
}

/// A camera for one frame.
#[derive(Debug, Clone, Copy)]
pub struct View {
    pub eye: Vec3,
    pub forward: Vec3,
    /// Vertical field of view, radians.
    pub fov_y: f32,
    /// Height of the eye above the water under it, m (picks the finest ring).
    pub height_above_water: f32,
}

/// Settings of the rendering panel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderSettings {
    /// Strength of the tiling breaker in [0, 1].
    pub tiling: f32,
    /// Cell of the tiling breaker's pattern, as a fraction of the largest cascade.
    pub tiling_scale: f32,
}

impl Default for RenderSettings {
    fn default() -> Self {
        let tiling = Tiling::default();
        RenderSettings {
            tiling: tiling.strength,
            tiling_scale: tiling.scale,
        }
    }
}

/// Which bodies to draw: `(mesh, instances)`.
pub struct Bodies<'a> {
    pub buoys: &'a [BodyInstance],
    pub boats: &'a [BodyInstance],
}

/// Render targets of one size (multisampled colour and depth).
struct Targets {
    size: (u32, u32),
    colour: Option<wgpu::TextureView>,
    depth: wgpu::TextureView,
}

/// Everything the viewer draws with.
pub struct Renderer {
    /// The scene's format (sRGB) and the window's (its linear twin, for egui).
    pub scene_format: wgpu::TextureFormat,
    pub samples: u32,
    globals: wgpu::Buffer,
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    /// Without anisotropy, for the vertex stage's explicit-LOD lookups.
    vertex_sampler: wgpu::Sampler,
    /// Clamped to the edge: the wake window's look-ups.
    wake_sampler: wgpu::Sampler,
    textures: Option<OceanTextures>,
    /// `OceanUniforms::wake` of the last upload.
    wake: [f32; 4],
    /// Whether the streak texture holds the ocean's field.
    streaks_bound: bool,
    /// `OceanUniforms::coast` and `coast_size` of the last upload.
    coast: [[f32; 4]; 2],
    ocean_pipeline: wgpu::RenderPipeline,
    terrain_pipeline: wgpu::RenderPipeline,
    /// The coast's ground: vertices, indices, index count.
    terrain: Option<(wgpu::Buffer, wgpu::Buffer, u32)>,
    sky_pipeline: wgpu::RenderPipeline,
    body_pipeline: wgpu::RenderPipeline,
    /// Index buffers of the clipmap: the full square, and the rings with their hole at each
    /// of the four offsets.
    full: (wgpu::Buffer, u32),
    rings: [(wgpu::Buffer, u32); 4],
    half_cells: u32,
    buoy_mesh: (wgpu::Buffer, wgpu::Buffer, u32),
    boat_mesh: (wgpu::Buffer, wgpu::Buffer, u32),
    instances: wgpu::Buffer,
    targets: Option<Targets>,
    /// The rings of the last frame (for the HUD): count, vertices.
    pub rings_drawn: (usize, usize),
    /// The mesh of each ring of the last frame's uniforms (`None`: the full square).
    ring_meshes: [Option<usize>; MAX_RINGS],
}

/// Most body instances.
pub const MAX_BODIES: usize = 64;

impl Renderer {
    /// Pipelines for targets of `scene_format` with `samples` samples per pixel, a clipmap of
    /// rings `half_cells` cells from centre to edge (even), and textures sampled with up to
    /// `anisotropy`× anisotropic filtering.
    pub fn new(
        device: &wgpu::Device,
        scene_format: wgpu::TextureFormat,
        samples: u32,
        half_cells: u32,
        anisotropy: u16,
    ) -> Renderer {
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("ocean.wgsl"),
            source: wgpu::ShaderSource::Wgsl(SHADER.into()),
        });
        let texture_entry = |binding: u32| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: true },
                view_dimension: wgpu::TextureViewDimension::D2Array,
                multisampled: false,
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ocean"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(
                            std::mem::size_of::<Globals>() as u64
                        ),
                    },
                    count: None,
                },
                texture_entry(1),
                texture_entry(2),
                wgpu::BindGroupLayoutEntry {
                    binding: 3,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 4,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 5,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 6,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 7,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                texture_entry(8),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("ocean"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let globals = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("globals"),
            size: std::mem::size_of::<Globals>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let sampler_with = |anisotropy: u16| {
            device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some("ocean"),
                address_mode_u: wgpu::AddressMode::Repeat,
                address_mode_v: wgpu::AddressMode::Repeat,
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                mipmap_filter: wgpu::MipmapFilterMode::Linear,
                anisotropy_clamp: anisotropy.max(1),
                ..Default::default()
            })
        };
        let sampler = sampler_with(anisotropy);
        let vertex_sampler = sampler_with(1);
        let wake_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("wake"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });

        let pipeline = |label: &str,
                        vs: &str,
                        fs: &str,
                        buffers: &[Option<wgpu::VertexBufferLayout>],
                        depth_write: bool,
                        compare: wgpu::CompareFunction,
                        cull: Option<wgpu::Face>| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &shader,
                    entry_point: Some(vs),
                    compilation_options: Default::default(),
                    buffers,
                },
                fragment: Some(wgpu::FragmentState {
                    module: &shader,
                    entry_point: Some(fs),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format: scene_format,
                        blend: None,
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                primitive: wgpu::PrimitiveState {
                    cull_mode: cull,
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(depth_write),
                    depth_compare: Some(compare),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: wgpu::MultisampleState {
                    count: samples,
                    ..Default::default()
                },
                multiview_mask: None,
                cache: None,
            })
        };
        let ocean_pipeline = pipeline(
            "ocean",
            "vs_ocean",
            "fs_ocean",
            &[],
            true,
            wgpu::CompareFunction::GreaterEqual,
            None,
        );
        let sky_pipeline = pipeline(
            "sky",
            "vs_sky",
            "fs_sky",
            &[],
            false,
            wgpu::CompareFunction::Always,
            None,
        );
        let body_layouts = [
            Some(wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<BodyVertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3],
            }),
            Some(wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<BodyInstance>() as u64,
                step_mode: wgpu::VertexStepMode::Instance,
                attributes: &wgpu::vertex_attr_array![
                    2 => Float32x4, 3 => Float32x4, 4 => Float32x4, 5 => Float32x4, 6 => Float32x4
                ],
            }),
        ];
        let body_pipeline = pipeline(
            "bodies",
            "vs_body",
            "fs_body",
            &body_layouts,
            true,
            wgpu::CompareFunction::GreaterEqual,
            None,
        );
        let terrain_pipeline = pipeline(
            "terrain",
            "vs_terrain",
            "fs_terrain",
            &[Some(terrain::layout())],
            true,
            wgpu::CompareFunction::GreaterEqual,
            None,
        );

        let index_buffer = |label: &str, indices: &[u32]| {
            let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytemuck::cast_slice(indices),
                usage: wgpu::BufferUsages::INDEX,
            });
            (buffer, indices.len() as u32)
        };
        let m = half_cells.max(4) & !1;
        let full = index_buffer("clipmap full", &grid_indices(m, None));
        let rings = HOLES.map(|hole| index_buffer("clipmap ring", &grid_indices(m, Some(hole))));
        let vertex_buffer = |label: &str, vertices: &[BodyVertex]| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytemuck::cast_slice(vertices),
                usage: wgpu::BufferUsages::VERTEX,
            })
        };
        let mesh = |label: &str, (vertices, indices): (Vec<BodyVertex>, Vec<u32>)| {
            (
                vertex_buffer(label, &vertices),
                index_buffer(label, &indices).0,
                indices.len() as u32,
            )
        };
        let buoy_mesh = mesh("buoy", buoy());
        let boat_mesh = mesh("boat", boat());
        let instances = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("body instances"),
            size: (MAX_BODIES * std::mem::size_of::<BodyInstance>()) as u64,
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Renderer {
            scene_format,
            samples,
            globals,
            layout,
            sampler,
            vertex_sampler,
            wake_sampler,
            textures: None,
            wake: [0.0; 4],
            streaks_bound: false,
            coast: [[0.0; 4]; 2],
            ocean_pipeline,
            terrain_pipeline,
            terrain: None,
            sky_pipeline,
            body_pipeline,
            full,
            rings,
            half_cells: m,
            buoy_mesh,
            boat_mesh,
            instances,
            targets: None,
            rings_drawn: (0, 0),
            ring_meshes: [None; MAX_RINGS],
        }
    }

    fn targets(&mut self, device: &wgpu::Device, size: (u32, u32)) {
        if self.targets.as_ref().is_some_and(|t| t.size == size) {
            return;
        }
        let texture = |label: &str, format: wgpu::TextureFormat| {
            device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size: wgpu::Extent3d {
                        width: size.0,
                        height: size.1,
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: self.samples,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
                    view_formats: &[],
                })
                .create_view(&Default::default())
        };
        self.targets = Some(Targets {
            size,
            colour: (self.samples > 1).then(|| texture("msaa colour", self.scene_format)),
            depth: texture("depth", DEPTH_FORMAT),
        });
    }

    /// Records the scene (sky, water, bodies) into `target` (a view of `scene_format`, `size`
    /// pixels), with the uniforms `globals`.
    pub fn draw(
        &mut self,
        (device, queue): (&wgpu::Device, &wgpu::Queue),
        encoder: &mut wgpu::CommandEncoder,
        (target, size): (&wgpu::TextureView, (u32, u32)),
        globals: &Globals,
        bodies: &Bodies,
    ) {
        let Some(textures) = self.textures.as_ref() else {
            return;
        };
        queue.write_buffer(&self.globals, 0, bytemuck::bytes_of(globals));
        let buoys = bodies.buoys.len().min(MAX_BODIES);
        let boats = bodies.boats.len().min(MAX_BODIES - buoys);
        let stride = std::mem::size_of::<BodyInstance>() as u64;
        if buoys > 0 {
            queue.write_buffer(
                &self.instances,
                0,
                bytemuck::cast_slice(&bodies.buoys[..buoys]),
            );
        }
        if boats > 0 {
            queue.write_buffer(
                &self.instances,
                buoys as u64 * stride,
                bytemuck::cast_slice(&bodies.boats[..boats]),
            );
        }
        let bind_group = textures.bind_group.clone();
        self.targets(device, size);
        let targets = self.targets.as_ref().expect("created above");
        let (view, resolve) = match &targets.colour {
            Some(msaa) => (msaa, Some(target)),
            None => (target, None),
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("scene"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: resolve,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: if resolve.is_some() {
                        wgpu::StoreOp::Discard
                    } else {
                        wgpu::StoreOp::Store
                    },
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &targets.depth,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(0, &bind_group, &[]);
        pass.set_pipeline(&self.sky_pipeline);
        pass.draw(0..3, 0..1);

        pass.set_pipeline(&self.ocean_pipeline);
        let count = globals.ocean.tiling[3] as usize;
        for ring in 0..count {
            let (buffer, indices) = match self.ring_meshes[ring] {
                None => &self.full,
                Some(hole) => &self.rings[hole],
            };
            pass.set_index_buffer(buffer.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..*indices, 0, ring as u32..ring as u32 + 1);
        }

        if let Some((vertices, indices, count)) = &self.terrain {
            pass.set_pipeline(&self.terrain_pipeline);
            pass.set_vertex_buffer(0, vertices.slice(..));
            pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..*count, 0, 0..1);
        }

        pass.set_pipeline(&self.body_pipeline);
        for (mesh, range) in [
            (&self.buoy_mesh, 0..buoys as u32),
            (&self.boat_mesh, buoys as u32..(buoys + boats) as u32),
        ] {
            if range.is_empty() {
                continue;
            }
            pass.set_vertex_buffer(0, mesh.0.slice(..));
            pass.set_vertex_buffer(1, self.instances.slice(..));
            pass.set_index_buffer(mesh.1.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..mesh.2, 0, range);
        }
    }
}
