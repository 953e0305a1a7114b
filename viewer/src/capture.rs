//! Screenshots: the frame drawn once more into a texture of its own, read back and written as
//! an 8-bit RGB PNG.

use crate::gpu::{self, Bodies};
use crate::State;

impl State {
    /// Draws the frame once more into a texture of its own and copies it to a buffer, for the
    /// screenshot: the buffer, its padded row length in bytes and the size.
    pub(crate) fn capture(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        size: (u32, u32),
        globals: &gpu::Globals,
        egui: Option<(&Vec<egui::ClippedPrimitive>, &egui_wgpu::ScreenDescriptor)>,
    ) -> (wgpu::Buffer, u32, (u32, u32)) {
        let texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("screenshot"),
            size: wgpu::Extent3d {
                width: size.0,
                height: size.1,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: self.config.format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[self.renderer.scene_format],
        });
        let scene_view = texture.create_view(&wgpu::TextureViewDescriptor {
            format: Some(self.renderer.scene_format),
            ..Default::default()
        });
        let bodies = Bodies {
            buoys: self.fleet.buoys(),
            boats: self.fleet.boats(),
        };
        self.renderer.draw(
            (&self.device, &self.queue),
            encoder,
            (&scene_view, size),
            globals,
            &bodies,
        );
        if let Some((jobs, screen)) = egui {
            let plain = texture.create_view(&Default::default());
            crate::ui::paint(&mut self.egui_renderer, encoder, &plain, (jobs, screen));
        }
        let padded = (size.0 * 4).div_ceil(256) * 256;
        let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("screenshot"),
            size: u64::from(padded) * u64::from(size.1),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        encoder.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded),
                    rows_per_image: Some(size.1),
                },
            },
            texture.size(),
        );
        (buffer, padded, size)
    }
}

/// Maps the screenshot buffer and writes it as an 8-bit RGB PNG.
pub(crate) fn save_capture(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
    padded: u32,
    width: u32,
    height: u32,
    bgra: bool,
    path: &std::path::Path,
) -> Result<(), String> {
    let slice = buffer.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |result| {
        let _ = tx.send(result);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| format!("screenshot: {e}"))?;
    rx.recv()
        .map_err(|e| format!("screenshot: {e}"))?
        .map_err(|e| format!("screenshot: {e}"))?;
    let data = slice
        .get_mapped_range()
        .map_err(|e| format!("screenshot: {e}"))?;
    let mut rgb = Vec::with_capacity((width * height * 3) as usize);
    for row in data.chunks(padded as usize).take(height as usize) {
        for px in row[..(width * 4) as usize].chunks(4) {
            if bgra {
                rgb.extend_from_slice(&[px[2], px[1], px[0]]);
            } else {
                rgb.extend_from_slice(&[px[0], px[1], px[2]]);
            }
        }
    }
    drop(data);
    buffer.unmap();
    write_png(path, width, height, &rgb)
}

fn write_png(path: &std::path::Path, width: u32, height: u32, rgb: &[u8]) -> Result<(), String> {
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent).map_err(|e| format!("{}: {e}", parent.display()))?;
    }
    let file = std::fs::File::create(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder
        .write_header()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    writer
        .write_image_data(rgb)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(())
}
