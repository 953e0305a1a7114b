//! ocean-fft on wgpu: the functions docs/guide/rendering.md shows in "Using ocean-fft from
//! Bevy, wgpu, macroquad and Godot", compiled by CI (never run: CI has no GPU). The guide quotes the code
//! between the `// guide:` markers verbatim; the root crate's test `tests/guide.rs` fails if
//! the two drift apart.

use client_glam_0_33::OceanTexels;

// guide: wgpu
use ocean_fft::{Error, OceanState};

/// One texture per packed layout and cascade: `[c][0]` displacement + foam, `[c][1]` slope +
/// Jacobian + foam. Rgba16Float is filterable on every adapter; Rgba32Float is only with
/// `Features::FLOAT32_FILTERABLE` (or read it with `textureLoad`).
pub fn create_ocean_textures(device: &wgpu::Device, ocean: &OceanState) -> Vec<[wgpu::Texture; 2]> {
    let texture = |n: u32| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some("ocean cascade"),
            size: wgpu::Extent3d {
                width: n,
                height: n,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba16Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        })
    };
    let sizes = ocean.cascades().iter().map(|c| c.size() as u32);
    sizes.map(|n| [texture(n), texture(n)]).collect()
}

/// The cascades tile the plane with period L: wrap mode repeat, bilinear. A shader samples
/// world point (x, z) of cascade c at uv = (x, z)/L_c + ½/N: texel (i, j), the water of grid
/// point (i, j)·L/N, has its centre at ((i + ½)/N, (j + ½)/N), v = 0 at row 0 (z = 0).
pub fn create_ocean_sampler(device: &wgpu::Device) -> wgpu::Sampler {
    device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("ocean"),
        address_mode_u: wgpu::AddressMode::Repeat,
        address_mode_v: wgpu::AddressMode::Repeat,
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    })
}

/// Every frame: step and pack on the CPU, then copy the texels to the GPU straight from the
/// packed buffers (`queue.write_texture` takes `&[u8]`; `bytes` views them without a copy).
pub fn update_ocean(
    ocean: &mut OceanState,
    dt: f64,
    texels: &mut OceanTexels,
    textures: &[[wgpu::Texture; 2]],
    queue: &wgpu::Queue,
) -> Result<(), Error> {
    texels.step_and_pack(ocean, dt)?;
    for (c, pair) in textures.iter().enumerate() {
        for (texture, bytes) in pair.iter().zip(texels.bytes(c)) {
            let size = texture.size();
            let layout = wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(size.width * 8), // 4 channels × 2 bytes
                rows_per_image: Some(size.height),
            };
            queue.write_texture(texture.as_image_copy(), bytes, layout, size);
        }
    }
    Ok(())
}
// guide: end
