//! The wake window on the GPU: an RGBA16F image of the window's texels (clamped, linear),
//! written by the render world when a new frame of texels arrives.

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

/// The image the wake goes to, in the render world.
pub(super) fn wake_gpu_image(
    images: &RenderAssets<GpuImage>,
    id: Option<AssetId<Image>>,
) -> Option<&GpuImage> {
    id.and_then(|id| images.get(id))
}
