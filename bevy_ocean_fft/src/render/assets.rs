//! The assets the sea is drawn with: the clipmap's ring meshes and the cascade images.

use bevy::asset::RenderAssetUsages;
use bevy::image::{ImageAddressMode, ImageFilterMode, ImageSampler, ImageSamplerDescriptor};
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;
use bevy::render::render_resource::{
    Extent3d, TextureDimension, TextureFormat, TextureUsages, TextureViewDescriptor,
    TextureViewDimension,
};

use ocean_fft_render::clipmap::{grid_indices, grid_point};
use ocean_fft_render::mip_levels;

/// A ring's mesh: vertex (i, j) at (i − m, 0, j − m), in cells from the centre.
pub(super) fn ring_mesh(m: u32, hole: Option<(u32, u32)>) -> Mesh {
    let side = 2 * m + 1;
    let positions: Vec<[f32; 3]> = (0..side * side)
        .map(|v| {
            let [x, z] = grid_point(m, v);
            [x, 0.0, z]
        })
        .collect();
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::RENDER_WORLD,
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, positions)
    .with_inserted_indices(Indices::U32(grid_indices(m, hole)))
}

/// An RGBA16F 2D array image of `layers` layers of n×n texels with their mip chains, its
/// contents uploaded by the render world.
pub(super) fn cascade_image(n: usize, layers: usize, anisotropy: u16) -> Image {
    let mut image = Image::new_uninit(
        Extent3d {
            width: n as u32,
            height: n as u32,
            depth_or_array_layers: layers.max(1) as u32,
        },
        TextureDimension::D2,
        TextureFormat::Rgba16Float,
        RenderAssetUsages::RENDER_WORLD,
    );
    image.texture_descriptor.mip_level_count = mip_levels(n) as u32;
    image.texture_descriptor.usage = TextureUsages::TEXTURE_BINDING | TextureUsages::COPY_DST;
    image.texture_view_descriptor = Some(TextureViewDescriptor {
        dimension: Some(TextureViewDimension::D2Array),
        ..Default::default()
    });
    image.sampler = ImageSampler::Descriptor(ImageSamplerDescriptor {
        address_mode_u: ImageAddressMode::Repeat,
        address_mode_v: ImageAddressMode::Repeat,
        mag_filter: ImageFilterMode::Linear,
        min_filter: ImageFilterMode::Linear,
        mipmap_filter: ImageFilterMode::Linear,
        anisotropy_clamp: anisotropy,
        ..Default::default()
    });
    image
}
