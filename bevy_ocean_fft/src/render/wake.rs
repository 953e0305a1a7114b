//! The wake window and the foam's streak field on the GPU: an RGBA16F image of the window's
//! texels (clamped, linear), written by the render world when a new frame of texels arrives,
//! and an R16F image of the streak field (repeat, linear), written when the field changes.

use std::sync::Arc;

use bevy::asset::RenderAssetUsages;
use bevy::image::{ImageAddressMode, ImageFilterMode, ImageSampler, ImageSamplerDescriptor};
use bevy::prelude::*;
use bevy::render::render_asset::RenderAssets;
use bevy::render::render_resource::{
    Extent3d, Origin3d, TexelCopyBufferLayout, TexelCopyTextureInfo, TextureAspect,
    TextureDimension, TextureFormat, TextureUsages,
};
use bevy::render::renderer::RenderQueue;
use bevy::render::texture::GpuImage;

use crate::sim::PackedFrame;

/// An n×n RGBA16F image for the wake window (1×1 without wakes: the shader reads none),
/// sampled with linear filtering and clamp-to-edge addressing.
pub(super) fn wake_image(n: usize) -> Image {
    let mut image = Image::new_uninit(
        Extent3d {
            width: n.max(1) as u32,
            height: n.max(1) as u32,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        TextureFormat::Rgba16Float,
        RenderAssetUsages::RENDER_WORLD,
    );
    image.texture_descriptor.usage = TextureUsages::TEXTURE_BINDING | TextureUsages::COPY_DST;
    image.sampler = ImageSampler::Descriptor(ImageSamplerDescriptor {
        address_mode_u: ImageAddressMode::ClampToEdge,
        address_mode_v: ImageAddressMode::ClampToEdge,
        mag_filter: ImageFilterMode::Linear,
        min_filter: ImageFilterMode::Linear,
        ..Default::default()
    });
    image
}

/// Writes `frame`'s wake texels into `image` if it has their size.
pub(super) fn write_wake(queue: &RenderQueue, image: &GpuImage, frame: &Arc<PackedFrame>) {
    let wake = &frame.wake;
    let side = image.texture_descriptor.size.width;
    if !wake.active() || side as usize != wake.size {
        return;
    }
    queue.write_texture(
        TexelCopyTextureInfo {
            texture: &image.texture,
            mip_level: 0,
            origin: Origin3d::ZERO,
            aspect: TextureAspect::All,
        },
        bytemuck::cast_slice(&wake.texels),
        TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(side * 8),
            rows_per_image: Some(side),
        },
        Extent3d {
            width: side,
            height: side,
            depth_or_array_layers: 1,
        },
    );
}

/// An `across`×`along` R16F image for the streak field (repeat, linear).
pub(super) fn streak_image(across: usize, along: usize) -> Image {
    let mut image = Image::new_uninit(
        Extent3d {
            width: across.max(1) as u32,
            height: along.max(1) as u32,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        TextureFormat::R16Float,
        RenderAssetUsages::RENDER_WORLD,
    );
    image.texture_descriptor.usage = TextureUsages::TEXTURE_BINDING | TextureUsages::COPY_DST;
    image.sampler = ImageSampler::Descriptor(ImageSamplerDescriptor {
        address_mode_u: ImageAddressMode::Repeat,
        address_mode_v: ImageAddressMode::Repeat,
        mag_filter: ImageFilterMode::Linear,
        min_filter: ImageFilterMode::Linear,
        ..Default::default()
    });
    image
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
    queue.write_texture(
        TexelCopyTextureInfo {
            texture: &image.texture,
            mip_level: 0,
            origin: Origin3d::ZERO,
            aspect: TextureAspect::All,
        },
        bytemuck::cast_slice(&streaks.texels),
        TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(size.width * 2),
            rows_per_image: Some(size.height),
        },
        size,
    );
    *written = streaks.fingerprint;
}

/// The image the wake goes to, in the render world.
pub(super) fn wake_gpu_image(
    images: &RenderAssets<GpuImage>,
    id: Option<AssetId<Image>>,
) -> Option<&GpuImage> {
    id.and_then(|id| images.get(id))
}
