//! The render world's side of the textures: the frame's texels extracted, then written into
//! the cascade images (every layer and mip level) and the wake image.

use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::time::Instant;

use bevy::prelude::*;
use bevy::render::render_asset::RenderAssets;
use bevy::render::renderer::RenderQueue;
use bevy::render::texture::GpuImage;
use bevy::render::Extract;

use super::wake::{wake_gpu_image, write_coast, write_level, write_streaks, write_wake};
use super::{OceanRender, UploadTime};
use crate::sim::{OceanTexels, PackedFrame};

/// The texels and the images they go to, in the render world.
#[derive(Resource, Default)]
pub(super) struct ExtractedTexels {
    generation: u64,
    texels: Option<Arc<PackedFrame>>,
    images: Option<(AssetId<Image>, AssetId<Image>)>,
    wake: Option<AssetId<Image>>,
    streaks: Option<AssetId<Image>>,
    coast: Option<AssetId<Image>>,
}

pub(super) fn extract_texels(
    mut commands: Commands,
    texels: Extract<Res<OceanTexels>>,
    render: Extract<Option<Res<OceanRender>>>,
) {
    commands.insert_resource(ExtractedTexels {
        generation: texels.generation,
        texels: texels.texels.clone(),
        images: render.as_ref().map(|r| (r.displacement.id(), r.slope.id())),
        wake: render.as_ref().map(|r| r.wake.id()),
        streaks: render.as_ref().map(|r| r.streaks.id()),
        coast: render.as_ref().map(|r| r.coast.id()),
    });
}

/// Writes a new frame's texels, every layer and mip level, into the images' textures.
pub(super) fn upload_texels(
    extracted: Option<Res<ExtractedTexels>>,
    images: Res<RenderAssets<GpuImage>>,
    queue: Res<RenderQueue>,
    upload: Res<UploadTime>,
    mut uploaded: Local<u64>,
    mut streaks_written: Local<(Option<AssetId<Image>>, u64)>,
    mut coast_written: Local<(Option<AssetId<Image>>, u64)>,
) {
    let Some(extracted) = extracted else {
        return;
    };
    let (Some(texels), Some((displacement, slope))) = (&extracted.texels, extracted.images) else {
        return;
    };
    if extracted.generation == *uploaded {
        return;
    }
    let (Some(displacement), Some(slope)) = (images.get(displacement), images.get(slope)) else {
        return;
    };
    let frame = texels;
    let texels = &texels.texels;
    let fits = |image: &GpuImage| {
        let size = image.texture_descriptor.size;
        size.width as usize == texels.size
            && size.depth_or_array_layers as usize == texels.cascades
            && image.texture_descriptor.mip_level_count as usize == texels.level_offsets.len()
    };
    if !fits(displacement) || !fits(slope) {
        // The images for a new grid are not on the GPU yet.
        return;
    }
    let start = Instant::now();
    for (image, data) in [(displacement, &texels.displacement), (slope, &texels.slope)] {
        for level in texels.levels(data) {
            let side = level.side as u32;
            let place = [level.layer as u32, level.level as u32];
            let texels = bytemuck::cast_slice(level.texels);
            write_level(&queue, image, texels, place, [side, side], 8);
        }
    }
    if let Some(image) = wake_gpu_image(&images, extracted.wake) {
        write_wake(&queue, image, frame);
    }
    if let Some(image) = wake_gpu_image(&images, extracted.streaks) {
        // A new image holds no field yet.
        if streaks_written.0 != extracted.streaks {
            *streaks_written = (extracted.streaks, 0);
        }
        write_streaks(&queue, image, frame, &mut streaks_written.1);
    }
    if let Some(image) = wake_gpu_image(&images, extracted.coast) {
        // A new image holds no coast yet.
        if coast_written.0 != extracted.coast {
            *coast_written = (extracted.coast, 0);
        }
        write_coast(&queue, image, frame, &mut coast_written.1);
    }
    upload.0.store(
        (start.elapsed().as_secs_f64() * 1e3).to_bits(),
        Ordering::Relaxed,
    );
    *uploaded = extracted.generation;
}
