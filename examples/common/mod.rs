//! Helpers shared by the examples: the value parsers of their command lines, PNG writing (8-
//! and 16-bit, gray and RGB), a small RGB canvas with lines and a 3×5 bitmap font, and the
//! `out/` folder.
//!
//! Each example includes this with `mod common;`; not every example uses every helper.
#![allow(dead_code)]

pub mod plot;

use glam::Vec3;
use ocean_fft::SurfaceSample;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

// The command lines: each example derives its own `Options` with clap (its flags, their
// defaults and help); the value parsers below check the values, so that a bad one is clap's
// error naming the flag.

/// The floating-point types of the examples' flags.
pub trait Real: std::str::FromStr + PartialOrd + std::fmt::Display + Copy + Send + Sync {
    const ZERO: Self;
    fn is_finite(self) -> bool;
}

impl Real for f32 {
    const ZERO: f32 = 0.0;
    fn is_finite(self) -> bool {
        f32::is_finite(self)
    }
}

impl Real for f64 {
    const ZERO: f64 = 0.0;
    fn is_finite(self) -> bool {
        f64::is_finite(self)
    }
}

/// Value parser: a finite number.
pub fn finite<T: Real>(text: &str) -> std::result::Result<T, String> {
    text.trim()
        .parse()
        .ok()
        .filter(|v: &T| v.is_finite())
        .ok_or_else(|| "not a finite number".to_string())
}

/// Value parser: a finite number above 0.
pub fn positive<T: Real>(text: &str) -> std::result::Result<T, String> {
    let value: T = finite(text)?;
    if value > T::ZERO {
        Ok(value)
    } else {
        Err(format!("{value} is not positive"))
    }
}

/// Value parser: a number from `min` to `max` inclusive (NaN is not).
pub fn within<T>(
    min: T,
    max: T,
) -> impl Fn(&str) -> std::result::Result<T, String> + Clone + Send + Sync + 'static
where
    T: std::str::FromStr + PartialOrd + std::fmt::Display + Copy + Send + Sync + 'static,
{
    move |text| {
        let value: T = text
            .trim()
            .parse()
            .map_err(|_| "not a valid number".to_string())?;
        if value >= min && value <= max {
            Ok(value)
        } else {
            Err(format!("{value} is out of range [{min}, {max}]"))
        }
    }
}

/// Value parser: `K` finite numbers separated by commas (`--camera 0,6,0`).
pub fn numbers<const K: usize>(text: &str) -> std::result::Result<[f32; K], String> {
    let parts: Vec<&str> = text.split(',').collect();
    if parts.len() != K {
        return Err(format!("expected {K} numbers separated by commas"));
    }
    let mut out = [0.0; K];
    for (o, p) in out.iter_mut().zip(parts) {
        *o = finite(p).map_err(|e| format!("{:?}: {e}", p.trim()))?;
    }
    Ok(out)
}

/// The error type of the examples' `main`: library errors, I/O and PNG errors alike.
pub type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// Creates `out/` (and `out/<sub>` when `sub` is not empty) and returns its path.
pub fn out_dir(sub: &str) -> Result<PathBuf> {
    let dir = if sub.is_empty() {
        PathBuf::from("out")
    } else {
        Path::new("out").join(sub)
    };
    std::fs::create_dir_all(&dir)?;
    Ok(dir)
}

/// Writes raw PNG image data (`data` already in PNG byte order: 16-bit samples big-endian).
fn write_png(
    path: &Path,
    width: usize,
    height: usize,
    color: png::ColorType,
    depth: png::BitDepth,
    data: &[u8],
) -> Result<()> {
    let mut encoder = png::Encoder::new(
        BufWriter::new(File::create(path)?),
        u32::try_from(width)?,
        u32::try_from(height)?,
    );
    encoder.set_color(color);
    encoder.set_depth(depth);
    // Smallest files (plots shrink about fourfold) for a few milliseconds more per picture.
    encoder.set_compression(png::Compression::Best);
    encoder.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
    encoder.write_header()?.write_image_data(data)?;
    Ok(())
}

/// Writes an 8-bit grayscale PNG (`pixels` row-major, `width * height` values).
pub fn save_gray8(path: &Path, width: usize, height: usize, pixels: &[u8]) -> Result<()> {
    write_png(
        path,
        width,
        height,
        png::ColorType::Grayscale,
        png::BitDepth::Eight,
        pixels,
    )
}

/// Writes a 16-bit grayscale PNG (`pixels` row-major, `width * height` values).
pub fn save_gray16(path: &Path, width: usize, height: usize, pixels: &[u16]) -> Result<()> {
    let bytes: Vec<u8> = pixels.iter().flat_map(|v| v.to_be_bytes()).collect();
    write_png(
        path,
        width,
        height,
        png::ColorType::Grayscale,
        png::BitDepth::Sixteen,
        &bytes,
    )
}

/// Writes an 8-bit RGB PNG (`pixels` row-major, 3 bytes per pixel).
pub fn save_rgb8(path: &Path, width: usize, height: usize, pixels: &[u8]) -> Result<()> {
    write_png(
        path,
        width,
        height,
        png::ColorType::Rgb,
        png::BitDepth::Eight,
        pixels,
    )
}

/// Writes a 16-bit RGB PNG (`pixels` row-major, 3 values per pixel).
pub fn save_rgb16(path: &Path, width: usize, height: usize, pixels: &[u16]) -> Result<()> {
    let bytes: Vec<u8> = pixels.iter().flat_map(|v| v.to_be_bytes()).collect();
    write_png(
        path,
        width,
        height,
        png::ColorType::Rgb,
        png::BitDepth::Sixteen,
        &bytes,
    )
}

/// Maps `value` linearly from [−`range`, `range`] to [0, 65535], clamping outside.
pub fn to_u16(value: f32, range: f32) -> u16 {
    let unit = (0.5 + 0.5 * value / range).clamp(0.0, 1.0);
    (unit * 65535.0).round() as u16
}

/// Maps `value` linearly from [0, 1] to [0, 255], clamping outside.
pub fn to_u8(value: f32) -> u8 {
    (value.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// An 8-bit RGB image to draw on: pixels, lines and text.
pub struct Canvas {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Row-major RGB bytes.
    pub pixels: Vec<u8>,
}

impl Canvas {
    /// A canvas filled with `background`.
    pub fn new(width: usize, height: usize, background: [u8; 3]) -> Self {
        Canvas {
            width,
            height,
            pixels: background
                .iter()
                .copied()
                .cycle()
                .take(width * height * 3)
                .collect(),
        }
    }

    /// Sets one pixel; points outside the canvas are ignored.
    pub fn set(&mut self, x: i64, y: i64, color: [u8; 3]) {
        if x >= 0 && y >= 0 && (x as usize) < self.width && (y as usize) < self.height {
            let i = (y as usize * self.width + x as usize) * 3;
            self.pixels[i..i + 3].copy_from_slice(&color);
        }
    }

    /// A `size`×`size` square with its top-left corner at (x, y).
    pub fn dot(&mut self, x: i64, y: i64, size: i64, color: [u8; 3]) {
        for dy in 0..size {
            for dx in 0..size {
                self.set(x + dx, y + dy, color);
            }
        }
    }

    /// A straight line from `a` to `b` (pixel coordinates), `width` pixels thick.
    pub fn line(&mut self, a: (f32, f32), b: (f32, f32), width: i64, color: [u8; 3]) {
        let steps = ((b.0 - a.0).abs().max((b.1 - a.1).abs()).ceil() as usize).max(1);
        for s in 0..=steps {
            let t = s as f32 / steps as f32;
            let x = a.0 + t * (b.0 - a.0);
            let y = a.1 + t * (b.1 - a.1);
            self.dot(x as i64, y as i64, width, color);
        }
    }

    /// A polyline through `points` (pixel coordinates).
    pub fn polyline(&mut self, points: &[(f32, f32)], width: i64, color: [u8; 3]) {
        for pair in points.windows(2) {
            self.line(pair[0], pair[1], width, color);
        }
    }

    /// A filled rectangle.
    pub fn fill_rect(&mut self, x: i64, y: i64, w: i64, h: i64, color: [u8; 3]) {
        for yy in y..y + h {
            for xx in x..x + w {
                self.set(xx, yy, color);
            }
        }
    }

    /// Writes `text` with the 3×5 font at (x, y) (top-left), each font pixel `scale`×`scale`.
    /// Letters are drawn upper case; characters without a glyph are left blank.
    pub fn text(&mut self, x: i64, y: i64, text: &str, scale: i64, color: [u8; 3]) {
        for (index, c) in text.chars().enumerate() {
            let bits = glyph(c);
            let left = x + index as i64 * 4 * scale;
            for row in 0..5 {
                for col in 0..3 {
                    if bits >> (14 - (row * 3 + col)) & 1 == 1 {
                        self.dot(left + col * scale, y + row * scale, scale, color);
                    }
                }
            }
        }
    }

    /// Width in pixels of `text` drawn at `scale`.
    pub fn text_width(text: &str, scale: i64) -> i64 {
        (text.chars().count() as i64 * 4 - 1).max(0) * scale
    }

    /// Copies `tile` (an RGB image of `w`×`h`) with its top-left corner at (x, y).
    pub fn blit(&mut self, x: i64, y: i64, w: usize, h: usize, tile: &[u8]) {
        for ty in 0..h {
            for tx in 0..w {
                let i = (ty * w + tx) * 3;
                self.set(
                    x + tx as i64,
                    y + ty as i64,
                    [tile[i], tile[i + 1], tile[i + 2]],
                );
            }
        }
    }

    /// Writes the canvas as an 8-bit RGB PNG.
    pub fn save(&self, path: &Path) -> Result<()> {
        save_rgb8(path, self.width, self.height, &self.pixels)
    }
}

/// The 3×5 glyph of `c`: 15 bits, top row first, leftmost pixel the most significant.
fn glyph(c: char) -> u16 {
    let rows: [u8; 5] = match c.to_ascii_uppercase() {
        'A' => [0b010, 0b101, 0b111, 0b101, 0b101],
        'B' => [0b110, 0b101, 0b110, 0b101, 0b110],
        'C' => [0b011, 0b100, 0b100, 0b100, 0b011],
        'D' => [0b110, 0b101, 0b101, 0b101, 0b110],
        'E' => [0b111, 0b100, 0b110, 0b100, 0b111],
        'F' => [0b111, 0b100, 0b110, 0b100, 0b100],
        'G' => [0b011, 0b100, 0b101, 0b101, 0b011],
        'H' => [0b101, 0b101, 0b111, 0b101, 0b101],
        'I' => [0b111, 0b010, 0b010, 0b010, 0b111],
        'J' => [0b001, 0b001, 0b001, 0b101, 0b010],
        'K' => [0b101, 0b101, 0b110, 0b101, 0b101],
        'L' => [0b100, 0b100, 0b100, 0b100, 0b111],
        'M' => [0b101, 0b111, 0b111, 0b101, 0b101],
        'N' => [0b110, 0b101, 0b101, 0b101, 0b101],
        'O' => [0b010, 0b101, 0b101, 0b101, 0b010],
        'P' => [0b110, 0b101, 0b110, 0b100, 0b100],
        'Q' => [0b010, 0b101, 0b101, 0b110, 0b011],
        'R' => [0b110, 0b101, 0b110, 0b101, 0b101],
        'S' => [0b011, 0b100, 0b010, 0b001, 0b110],
        'T' => [0b111, 0b010, 0b010, 0b010, 0b010],
        'U' => [0b101, 0b101, 0b101, 0b101, 0b111],
        'V' => [0b101, 0b101, 0b101, 0b101, 0b010],
        'W' => [0b101, 0b101, 0b111, 0b111, 0b101],
        'X' => [0b101, 0b101, 0b010, 0b101, 0b101],
        'Y' => [0b101, 0b101, 0b010, 0b010, 0b010],
        'Z' => [0b111, 0b001, 0b010, 0b100, 0b111],
        '0' => [0b111, 0b101, 0b101, 0b101, 0b111],
        '1' => [0b010, 0b110, 0b010, 0b010, 0b111],
        '2' => [0b110, 0b001, 0b010, 0b100, 0b111],
        '3' => [0b110, 0b001, 0b010, 0b001, 0b110],
        '4' => [0b101, 0b101, 0b111, 0b001, 0b001],
        '5' => [0b111, 0b100, 0b110, 0b001, 0b110],
        '6' => [0b011, 0b100, 0b111, 0b101, 0b111],
        '7' => [0b111, 0b001, 0b010, 0b010, 0b010],
        '8' => [0b111, 0b101, 0b111, 0b101, 0b111],
        '9' => [0b111, 0b101, 0b111, 0b001, 0b110],
        '.' => [0b000, 0b000, 0b000, 0b000, 0b010],
        ',' => [0b000, 0b000, 0b000, 0b010, 0b100],
        '-' => [0b000, 0b000, 0b111, 0b000, 0b000],
        '+' => [0b000, 0b010, 0b111, 0b010, 0b000],
        '_' => [0b000, 0b000, 0b000, 0b000, 0b111],
        '=' => [0b000, 0b111, 0b000, 0b111, 0b000],
        ':' => [0b000, 0b010, 0b000, 0b010, 0b000],
        '/' => [0b001, 0b001, 0b010, 0b100, 0b100],
        '(' => [0b010, 0b100, 0b100, 0b100, 0b010],
        ')' => [0b010, 0b001, 0b001, 0b001, 0b010],
        _ => [0; 5],
    };
    rows.iter().fold(0u16, |acc, &r| (acc << 3) | u16::from(r))
}

/// Writes an RGB image (`pixels` row-major, 3 bytes per pixel) as an 8-bit indexed PNG of at
/// most 256 colours chosen by median cut (Heckbert 1982), each pixel mapped to the nearest:
/// two to three times smaller than RGB for the sea pictures, for the README's gallery.
pub fn save_indexed(path: &Path, width: usize, height: usize, pixels: &[u8]) -> Result<()> {
    use std::collections::HashMap;
    let mut counts: HashMap<[u8; 3], u32> = HashMap::new();
    for c in pixels.chunks_exact(3) {
        *counts.entry([c[0], c[1], c[2]]).or_insert(0) += 1;
    }
    let colours: Vec<([u8; 3], u32)> = counts.into_iter().collect();
    // Boxes of colours; split the one with the widest channel range weighted by its pixel
    // count at the pixel median of that channel, until 256 boxes or nothing left to split.
    let mut boxes: Vec<Vec<([u8; 3], u32)>> = vec![colours];
    let extent = |b: &[([u8; 3], u32)]| -> (usize, u32) {
        (0..3)
            .map(|ch| {
                let lo = b.iter().map(|c| c.0[ch]).min().unwrap_or(0);
                let hi = b.iter().map(|c| c.0[ch]).max().unwrap_or(0);
                (ch, u32::from(hi - lo))
            })
            .max_by_key(|&(_, r)| r)
            .unwrap_or((0, 0))
    };
    while boxes.len() < 256 {
        let Some((index, channel)) = boxes
            .iter()
            .enumerate()
            .filter(|(_, b)| b.len() > 1)
            .map(|(i, b)| {
                let (ch, range) = extent(b);
                let count: u64 = b.iter().map(|c| u64::from(c.1)).sum();
                (i, ch, u64::from(range) * count)
            })
            .filter(|&(_, _, score)| score > 0)
            .max_by_key(|&(_, _, score)| score)
            .map(|(i, ch, _)| (i, ch))
        else {
            break;
        };
        let mut b = boxes.swap_remove(index);
        b.sort_unstable_by_key(|c| c.0[channel]);
        let total: u64 = b.iter().map(|c| u64::from(c.1)).sum();
        let mut seen = 0u64;
        let mut cut = 1;
        for (i, c) in b.iter().enumerate() {
            seen += u64::from(c.1);
            if seen * 2 >= total {
                cut = (i + 1).clamp(1, b.len() - 1);
                break;
            }
        }
        let rest = b.split_off(cut);
        boxes.push(b);
        boxes.push(rest);
    }
    let palette: Vec<[u8; 3]> = boxes
        .iter()
        .map(|b| {
            let total: f64 = b.iter().map(|c| f64::from(c.1)).sum();
            let mut mean = [0.0f64; 3];
            for c in b {
                for (m, v) in mean.iter_mut().zip(c.0) {
                    *m += f64::from(v) * f64::from(c.1) / total;
                }
            }
            mean.map(|m| m.round() as u8)
        })
        .collect();
    let mut lookup: HashMap<[u8; 3], u8> = HashMap::new();
    let indices: Vec<u8> = pixels
        .chunks_exact(3)
        .map(|c| {
            let colour = [c[0], c[1], c[2]];
            *lookup.entry(colour).or_insert_with(|| {
                let distance = |p: &[u8; 3]| -> i32 {
                    (0..3)
                        .map(|ch| (i32::from(p[ch]) - i32::from(colour[ch])).pow(2))
                        .sum()
                };
                (0..palette.len())
                    .min_by_key(|&i| distance(&palette[i]))
                    .unwrap_or(0) as u8
            })
        })
        .collect();
    let mut encoder = png::Encoder::new(
        BufWriter::new(File::create(path)?),
        u32::try_from(width)?,
        u32::try_from(height)?,
    );
    encoder.set_color(png::ColorType::Indexed);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_palette(palette.concat());
    encoder.set_compression(png::Compression::Best);
    encoder.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
    encoder.write_header()?.write_image_data(&indices)?;
    Ok(())
}

/// Linear colour of one top-view sample: hill shading from the normal, crests tinted by
/// η/H_s, residual foam a pale veil (half its coverage), active whitecaps white.
pub fn shade(sample: &SurfaceSample, sun: Vec3, hs: f32, active: f32, residual: f32) -> Vec3 {
    let deep = Vec3::new(0.01, 0.07, 0.14);
    let crest = Vec3::new(0.06, 0.30, 0.36);
    let lit = Vec3::from_array(sample.normal).dot(sun).max(0.0);
    let relative = (sample.height / hs.max(1e-6)).clamp(-0.5, 0.5) + 0.5;
    let water = deep.lerp(crest, relative) * (0.15 + 2.2 * lit * lit);
    water
        .lerp(Vec3::new(0.55, 0.62, 0.66), 0.5 * residual)
        .lerp(Vec3::splat(0.95), active)
}

/// Linear colour to 8-bit with gamma 2.2.
pub fn to_srgb(colour: Vec3) -> [u8; 3] {
    colour
        .to_array()
        .map(|c| (c.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0).round() as u8)
}

/// Samples of the summed surface over the window [0, `window`]² (m) at `fine` × `fine`
/// points, at the centres of its cells (`OceanState::sample_grid`).
pub fn sample_window(
    ocean: &ocean_fft::OceanState,
    window: f64,
    fine: usize,
) -> Result<Vec<SurfaceSample>> {
    let spacing = window / fine as f64;
    let mut samples = vec![SurfaceSample::default(); fine * fine];
    ocean.water().at_rest_grid(
        [0.5 * spacing, 0.5 * spacing],
        spacing,
        [fine, fine],
        &mut samples,
    )?;
    Ok(samples)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn value_parsers_check_their_rules() {
        assert_eq!(finite::<f32>(" -8 "), Ok(-8.0));
        assert!(finite::<f64>("inf").is_err() && finite::<f64>("NaN").is_err());
        assert!(finite::<f32>("x").is_err());
        assert_eq!(positive::<f64>("400"), Ok(400.0));
        assert!(positive::<f64>("0").is_err() && positive::<f32>("-1").is_err());
        assert!(positive::<f64>("inf").is_err());
        let pixels = within(16usize, 4096);
        assert_eq!(pixels("512"), Ok(512));
        assert!(pixels("15").is_err() && pixels("4097").is_err() && pixels("-1").is_err());
        assert!(within(1.0f32, 170.0)("NaN").is_err());
        assert_eq!(numbers::<3>("150, 25,-400"), Ok([150.0, 25.0, -400.0]));
        assert!(numbers::<3>("0,6").is_err() && numbers::<3>("0,inf,0").is_err());
    }
}
