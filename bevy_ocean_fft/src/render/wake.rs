//! The wake window and the foam's streak field on the GPU: an RGBA16F image of the window's
//! texels (clamped, linear), written by the render world when a new frame of texels arrives,
//! an R16F image of the streak field (repeat, linear), written when the field changes, and
//! the coast's 2-layer RGBA16F array over the depth map (clamped, linear), written when its
//! texels are new.

use std::sync::Arc;

use bevy::asset::RenderAssetUsages;
use bevy::image::{ImageAddressMode, ImageFilterMode, ImageSampler, ImageSamplerDescriptor};
use bevy::prelude::*;
use bevy::render::render_asset::RenderAssets;
use bevy::render::render_resource::{
    Extent3d, Origin3d, TexelCopyBufferLayout, TexelCopyTextureInfo, TextureAspect,
    TextureDimension, TextureFormat, TextureUsages, TextureViewDescriptor, TextureViewDimension,
};
use bevy::render::renderer::RenderQueue;
use bevy::render::texture::GpuImage;
use ocean_fft_render::CoastTexels;

use crate::sim::PackedFrame;

/// An n×n RGBA16F image for the wake window (1×1 without wakes: the shader reads none),
/// sampled with linear filtering and clamp-to-edge addressing.
pub(super) fn wake_image(n: usize) -> Image {
    image_2d(
        [n, n],
        TextureFormat::Rgba16Float,
        ImageAddressMode::ClampToEdge,
    )
}

/// A `size` (width, height; at least 1) 2D image of `format` to write texels into, sampled
/// with linear filtering and `address` on both axes.
fn image_2d(size: [usize; 2], format: TextureFormat, address: ImageAddressMode) -> Image {
    let mut image = Image::new_uninit(
        Extent3d {
            width: size[0].max(1) as u32,
            height: size[1].max(1) as u32,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        format,
        RenderAssetUsages::RENDER_WORLD,
    );
    image.texture_descriptor.usage = TextureUsages::TEXTURE_BINDING | TextureUsages::COPY_DST;
    image.sampler = ImageSampler::Descriptor(ImageSamplerDescriptor {
        address_mode_u: address,
        address_mode_v: address,
        mag_filter: ImageFilterMode::Linear,
        min_filter: ImageFilterMode::Linear,
        ..Default::default()
    });
    image
}

/// Writes `texels` (`bytes_per_texel` each, rows of `width`) into mip level `mip` of layer
/// `layer` of `image`, a `width`×`height` region from its corner.
pub(super) fn write_level(
    queue: &RenderQueue,
    image: &GpuImage,
    texels: &[u8],
    [layer, mip]: [u32; 2],
    [width, height]: [u32; 2],
    bytes_per_texel: u32,
) {
    queue.write_texture(
        TexelCopyTextureInfo {
            texture: &image.texture,
            mip_level: mip,
            origin: Origin3d {
                x: 0,
                y: 0,
                z: layer,
            },
            aspect: TextureAspect::All,
        },
        texels,
        TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(width * bytes_per_texel),
            rows_per_image: Some(height),
        },
        Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
}

/// Writes `frame`'s wake texels into `image` if it has their size.
pub(super) fn write_wake(queue: &RenderQueue, image: &GpuImage, frame: &Arc<PackedFrame>) {
    let wake = &frame.wake;
    let side = image.texture_descriptor.size.width;
    if !wake.active() || side as usize != wake.size {
        return;
    }
    let texels = bytemuck::cast_slice(&wake.texels);
    write_level(queue, image, texels, [0, 0], [side, side], 8);
}

/// A 2-layer RGBA16F array image of `size` texels (x, z; [1, 1] without a map, the
/// placeholder) for the coast (`CoastTexels`), clamped to the edge, linear.
pub(super) fn coast_image(size: [usize; 2]) -> Image {
    let mut image = image_2d(
        size,
        TextureFormat::Rgba16Float,
        ImageAddressMode::ClampToEdge,
    );
    image.texture_descriptor.size.depth_or_array_layers = CoastTexels::LAYERS as u32;
    image.texture_view_descriptor = Some(TextureViewDescriptor {
        dimension: Some(TextureViewDimension::D2Array),
        ..Default::default()
    });
    image
}

/// Writes `frame`'s coast texels into `image` if it has their size and they are not the
/// ones written last (`written`: their generation).
pub(super) fn write_coast(
    queue: &RenderQueue,
    image: &GpuImage,
    frame: &Arc<PackedFrame>,
    written: &mut u64,
) {
    let Some(coast) = frame.coast.as_deref() else {
        return;
    };
    let size = image.texture_descriptor.size;
    if *written == coast.generation || [size.width as usize, size.height as usize] != coast.size {
        return;
    }
    for layer in 0..CoastTexels::LAYERS {
        let texels = bytemuck::cast_slice(coast.layer(layer));
        write_level(
            queue,
            image,
            texels,
            [layer as u32, 0],
            [size.width, size.height],
            8,
        );
    }
    *written = coast.generation;
}

/// An `across`×`along` R16F image for the streak field (repeat, linear).
pub(super) fn streak_image(across: usize, along: usize) -> Image {
    image_2d(
        [across, along],
        TextureFormat::R16Float,
        ImageAddressMode::Repeat,
    )
}

/// Writes `frame`'s streak field into `image` if it has its size and differs from the
/// field written last (`written`: its fingerprint).
pub(super) fn write_streaks(
    queue: &RenderQueue,
    image: &GpuImage,
    frame: &Arc<PackedFrame>,
    written: &mut u64,
) {
    let streaks = &frame.streaks;
    let size = image.texture_descriptor.size;
    if streaks.texels.is_empty()
        || *written == streaks.fingerprint
        || size.width as usize != streaks.across
        || size.height as usize != streaks.along
    {
        return;
    }
    let texels = bytemuck::cast_slice(&streaks.texels);
    write_level(queue, image, texels, [0, 0], [size.width, size.height], 2);
    *written = streaks.fingerprint;
}

/// The image the wake goes to, in the render world.
pub(super) fn wake_gpu_image(
    images: &RenderAssets<GpuImage>,
    id: Option<AssetId<Image>>,
) -> Option<&GpuImage> {
    id.and_then(|id| images.get(id))
}
