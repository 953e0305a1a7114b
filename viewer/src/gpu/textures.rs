//! The textures the water is drawn from: the cascades (two 2D arrays, a layer per cascade,
//! RGBA16F with mipmaps), the wake window (a 2D texture, RGBA16F, one level; a 1×1 zero
//! texel when the ocean has no wakes), the foam's streak field (R16F, written when the ocean
//! is new), the coast over the depth map (a 2-layer 2D array, RGBA16F; 1×1 zeros without a
//! map, written when its generation changes), and the bind group that holds them.

use ocean_fft::half::f16;
use ocean_fft_render::{CoastTexels, Frame, StreakTexels, WakeTexels};

use super::Renderer;

/// The textures and their bind group, kept while their sizes stay.
pub struct OceanTextures {
    displacement: wgpu::Texture,
    slope: wgpu::Texture,
    wake: wgpu::Texture,
    streaks: wgpu::Texture,
    coast: wgpu::Texture,
    pub bind_group: wgpu::BindGroup,
    size: usize,
    cascades: usize,
    mips: usize,
    /// Side of the wake texture (1: the placeholder).
    wake_size: usize,
    /// Size of the streak texture (across, along) and the fingerprint of the field in it.
    streak_size: (usize, usize),
    streak_fingerprint: u64,
    /// Size of the coast texture ([1, 1]: the placeholder) and the generation in it.
    coast_size: [usize; 2],
    coast_generation: u64,
}

/// Writes `texels` (RGBA16F, `side`² of them) into `texture`'s level `level`, layer `layer`.
fn write(
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    (level, layer): (u32, u32),
    side: u32,
    texels: &[[f16; 4]],
) {
    write_rect(queue, texture, (level, layer), [side, side], texels);
}

/// Writes `texels` (RGBA16F, `size[0]` × `size[1]`) into `texture`'s level `level`, layer
/// `layer`.
fn write_rect(
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    (level, layer): (u32, u32),
    [width, height]: [u32; 2],
    texels: &[[f16; 4]],
) {
    queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: level,
            origin: wgpu::Origin3d {
                x: 0,
                y: 0,
                z: layer,
            },
            aspect: wgpu::TextureAspect::All,
        },
        bytemuck::cast_slice(texels),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(width * 8),
            rows_per_image: Some(height),
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
}

impl Renderer {
    /// Uploads a frame's texels and wake (creating the textures when a size changed).
    pub fn upload(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, frame: &Frame) {
        let texels = &frame.texels;
        let mips = texels.level_offsets.len();
        let wake_size = frame.wake.size.max(1);
        let streak_size = (frame.streaks.across.max(1), frame.streaks.along.max(1));
        let coast_size = frame.coast.as_ref().map_or([1, 1], |c| c.size);
        let fits = self.textures.as_ref().is_some_and(|t| {
            t.size == texels.size
                && t.cascades == texels.cascades
                && t.mips == mips
                && t.wake_size == wake_size
                && t.streak_size == streak_size
                && t.coast_size == coast_size
        });
        if !fits {
            self.textures = Some(self.create_textures(
                device,
                (texels.size, texels.cascades, mips),
                (wake_size, streak_size, coast_size),
            ));
            let textures = self.textures.as_ref().expect("created above");
            if !frame.wake.active() {
                write(queue, &textures.wake, (0, 0), 1, &[[f16::ZERO; 4]]);
            }
            if frame.coast.is_none() {
                for layer in 0..CoastTexels::LAYERS as u32 {
                    write(queue, &textures.coast, (0, layer), 1, &[[f16::ZERO; 4]]);
                }
            }
        }
        let textures = self.textures.as_ref().expect("created above");
        for (texture, data) in [
            (&textures.displacement, &texels.displacement),
            (&textures.slope, &texels.slope),
        ] {
            for level in texels.levels(data) {
                let at = (level.level as u32, level.layer as u32);
                write(queue, texture, at, level.side as u32, level.texels);
            }
        }
        self.upload_wake(queue, &frame.wake);
        self.upload_streaks(queue, &frame.streaks);
        self.upload_coast(queue, frame.coast.as_deref());
    }

    /// The coast's texels when they are new, and their place.
    fn upload_coast(&mut self, queue: &wgpu::Queue, coast: Option<&CoastTexels>) {
        self.coast = ocean_fft_render::coast_uniforms(coast);
        let (Some(coast), Some(textures)) = (coast, self.textures.as_mut()) else {
            return;
        };
        if textures.coast_generation == coast.generation {
            return;
        }
        textures.coast_generation = coast.generation;
        let size = coast.size.map(|n| n as u32);
        for layer in 0..CoastTexels::LAYERS {
            write_rect(
                queue,
                &textures.coast,
                (0, layer as u32),
                size,
                coast.layer(layer),
            );
        }
    }

    /// The streak field, when it is not the one on the GPU.
    fn upload_streaks(&mut self, queue: &wgpu::Queue, streaks: &StreakTexels) {
        let Some(textures) = self.textures.as_mut() else {
            return;
        };
        self.streaks_bound = !streaks.texels.is_empty();
        if !self.streaks_bound || textures.streak_fingerprint == streaks.fingerprint {
            return;
        }
        textures.streak_fingerprint = streaks.fingerprint;
        let (width, height) = (streaks.across as u32, streaks.along as u32);
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &textures.streaks,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            bytemuck::cast_slice(&streaks.texels),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(width * 2),
                rows_per_image: Some(height),
            },
            wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
        );
    }

    /// The wake window's texels and place.
    fn upload_wake(&mut self, queue: &wgpu::Queue, wake: &WakeTexels) {
        self.wake = wake.uniform();
        if let (true, Some(textures)) = (wake.active(), self.textures.as_ref()) {
            write(
                queue,
                &textures.wake,
                (0, 0),
                wake.size as u32,
                &wake.texels,
            );
        }
    }

    fn create_textures(
        &self,
        device: &wgpu::Device,
        (size, cascades, mips): (usize, usize, usize),
        (wake_size, streak_size, coast_size): (usize, (usize, usize), [usize; 2]),
    ) -> OceanTextures {
        let texture = |label: &str, (width, height), layers: usize, mips: usize, format| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: width as u32,
                    height: height as u32,
                    depth_or_array_layers: layers as u32,
                },
                mip_level_count: mips as u32,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            })
        };
        let rgba = wgpu::TextureFormat::Rgba16Float;
        let displacement = texture("displacement + foam", (size, size), cascades, mips, rgba);
        let slope = texture(
            "slope + jacobian + foam",
            (size, size),
            cascades,
            mips,
            rgba,
        );
        let wake = texture("wake", (wake_size, wake_size), 1, 1, rgba);
        let streaks = texture(
            "foam streaks",
            streak_size,
            1,
            1,
            wgpu::TextureFormat::R16Float,
        );
        let coast = texture(
            "coast",
            (coast_size[0], coast_size[1]),
            CoastTexels::LAYERS,
            1,
            rgba,
        );
        let view = |t: &wgpu::Texture, dimension| {
            t.create_view(&wgpu::TextureViewDescriptor {
                dimension: Some(dimension),
                ..Default::default()
            })
        };
        let array = wgpu::TextureViewDimension::D2Array;
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ocean"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: self.globals.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&view(&displacement, array)),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(&view(&slope, array)),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::Sampler(&self.sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: wgpu::BindingResource::Sampler(&self.vertex_sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 5,
                    resource: wgpu::BindingResource::TextureView(&view(
                        &wake,
                        wgpu::TextureViewDimension::D2,
                    )),
                },
                wgpu::BindGroupEntry {
                    binding: 6,
                    resource: wgpu::BindingResource::Sampler(&self.wake_sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 7,
                    resource: wgpu::BindingResource::TextureView(&view(
                        &streaks,
                        wgpu::TextureViewDimension::D2,
                    )),
                },
                wgpu::BindGroupEntry {
                    binding: 8,
                    resource: wgpu::BindingResource::TextureView(&view(&coast, array)),
                },
            ],
        });
        OceanTextures {
            displacement,
            slope,
            wake,
            streaks,
            coast,
            bind_group,
            size,
            cascades,
            mips,
            wake_size,
            streak_size,
            streak_fingerprint: 0,
            coast_size,
            coast_generation: 0,
        }
    }
}
