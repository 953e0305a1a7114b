//! Files: OpenEXR (half float, ZIP) and 16-bit PNG encoders, their channel tables, the PNG
//! decode scales, and atomic writes.

use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use half::f16;
use ocean_fft::OceanState;

use crate::args::Format;
use crate::sim::Texels;

/// One channel of a written file, for the sidecar and the guide.
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct Channel {
    /// Which file of the frame (`""` for the EXR, `"disp"` or `"normal"` for PNG).
    pub file: &'static str,
    /// The channel's name in the file.
    pub channel: &'static str,
    /// What it holds.
    pub meaning: &'static str,
    /// Its unit.
    pub unit: &'static str,
}

/// The EXR's channels: RGBA is the library's `DisplacementFoam` layout, so a reader of RGBA
/// alone gets the displacement and the foam; the normal and the Jacobian are layers.
pub const EXR_CHANNELS: [Channel; 8] = [
    Channel {
        file: "",
        channel: "R",
        meaning: "D_x: horizontal displacement along +x",
        unit: "m",
    },
    Channel {
        file: "",
        channel: "G",
        meaning: "η: height (displacement along +y, up)",
        unit: "m",
    },
    Channel {
        file: "",
        channel: "B",
        meaning: "D_z: horizontal displacement along +z",
        unit: "m",
    },
    Channel {
        file: "",
        channel: "A",
        meaning: "foam coverage in [0, 1]",
        unit: "1",
    },
    Channel {
        file: "",
        channel: "normal.X",
        meaning: "n_x of the unit normal (world axes, y up)",
        unit: "1",
    },
    Channel {
        file: "",
        channel: "normal.Y",
        meaning: "n_y of the unit normal (up; < 0 where the surface folds)",
        unit: "1",
    },
    Channel {
        file: "",
        channel: "normal.Z",
        meaning: "n_z of the unit normal",
        unit: "1",
    },
    Channel {
        file: "",
        channel: "jacobian.Y",
        meaning: "J: Jacobian of the horizontal map (1 flat, < 0 folded)",
        unit: "1",
    },
];

/// The PNGs' channels (decode with the scales in the sidecar, see [`PngScale`]).
pub const PNG_CHANNELS: [Channel; 8] = [
    Channel {
        file: "disp",
        channel: "R",
        meaning: "D_x = (2p/65535 − 1)·displacement_scale",
        unit: "m",
    },
    Channel {
        file: "disp",
        channel: "G",
        meaning: "η = (2p/65535 − 1)·displacement_scale",
        unit: "m",
    },
    Channel {
        file: "disp",
        channel: "B",
        meaning: "D_z = (2p/65535 − 1)·displacement_scale",
        unit: "m",
    },
    Channel {
        file: "disp",
        channel: "A",
        meaning: "foam = p/65535",
        unit: "1",
    },
    Channel {
        file: "normal",
        channel: "R",
        meaning: "n_x = 2p/65535 − 1",
        unit: "1",
    },
    Channel {
        file: "normal",
        channel: "G",
        meaning: "n_y = 2p/65535 − 1 (up)",
        unit: "1",
    },
    Channel {
        file: "normal",
        channel: "B",
        meaning: "n_z = 2p/65535 − 1",
        unit: "1",
    },
    Channel {
        file: "normal",
        channel: "A",
        meaning: "J = 1 + (2p/65535 − 1)·jacobian_scale",
        unit: "1",
    },
];

/// The file names of frame `frame` of cascade `cascade`.
pub fn file_names(name: &str, format: Format, cascade: usize, frame: u32) -> Vec<String> {
    match format {
        Format::Exr => vec![format!("{name}_c{cascade}_{frame:04}.exr")],
        Format::Png => vec![
            format!("{name}_c{cascade}_disp_{frame:04}.png"),
            format!("{name}_c{cascade}_normal_{frame:04}.png"),
        ],
    }
}

/// The file-name patterns, for the sidecar.
pub fn file_patterns(format: Format) -> Vec<&'static str> {
    match format {
        Format::Exr => vec!["{name}_c{cascade}_{frame:04}.exr"],
        Format::Png => vec![
            "{name}_c{cascade}_disp_{frame:04}.png",
            "{name}_c{cascade}_normal_{frame:04}.png",
        ],
    }
}

/// The EXR file of one cascade at one frame: half floats (the library's f16 packing:
/// nearest, ±65504 saturated), ZIP (16 scan lines a block), increasing line order, row 0
/// (z = 0) first, the channels of [`EXR_CHANNELS`].
///
/// # Errors
/// The encoder's message (it does not fail on valid buffers).
pub fn encode_exr(t: &Texels<f16>) -> Result<Vec<u8>, String> {
    use exr::prelude::*;
    let plane = |texels: &[[f16; 4]], c: usize| -> FlatSamples {
        FlatSamples::F16(texels.iter().map(|texel| texel[c]).collect())
    };
    let (df, nj) = (&t.displacement_foam, &t.normal_jacobian);
    let channels: Vec<AnyChannel<FlatSamples>> = vec![
        AnyChannel::new("R", plane(df, 0)),
        AnyChannel::new("G", plane(df, 1)),
        AnyChannel::new("B", plane(df, 2)),
        AnyChannel::new("A", plane(df, 3)),
        AnyChannel::new("normal.X", plane(nj, 0)),
        AnyChannel::new("normal.Y", plane(nj, 1)),
        AnyChannel::new("normal.Z", plane(nj, 2)),
        AnyChannel::new("jacobian.Y", plane(nj, 3)),
    ];
    let layer = Layer::new(
        (t.size, t.size),
        LayerAttributes::default(),
        Encoding {
            compression: Compression::ZIP16,
            blocks: Blocks::ScanLines,
            line_order: LineOrder::Increasing,
        },
        AnyChannels::sort(channels.into()),
    );
    let mut bytes = io::Cursor::new(Vec::new());
    Image::from_layer(layer)
        .write()
        .non_parallel()
        .to_buffered(&mut bytes)
        .map_err(|e| format!("OpenEXR encoder: {e}"))?;
    Ok(bytes.into_inner())
}

/// The decode scales of one cascade's PNGs.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PngScale {
    /// s_d in metres: D_x, η, D_z = (2p/65535 − 1)·s_d.
    pub displacement_scale: f64,
    /// s_J: J = 1 + (2p/65535 − 1)·s_J.
    pub jacobian_scale: f64,
}

/// `x` > 0 to three significant digits by `round` (`f64::ceil` to round up, `f64::round`
/// to the nearest), so that the sidecar and the messages show short numbers.
pub fn three_digits(x: f64, round: fn(f64) -> f64) -> f64 {
    let e = x.log10().floor() as i32 - 2;
    if e < 0 {
        // Divide by an exact power of ten rather than multiply by an inexact 10^e.
        let inverse = 10f64.powi(-e);
        round(x * inverse) / inverse
    } else {
        let step = 10f64.powi(e);
        round(x / step) * step
    }
}

/// `x` rounded up to three significant digits.
fn round_up_3(x: f64) -> f64 {
    three_digits(x, f64::ceil)
}

/// The PNG decode scales of every cascade: a function of the sea alone (never of the frames
/// baked), so split bakes agree. From the cascade's amplitudes h0 (a Gaussian sea): σ_η² =
/// Σ 2|h0|², σ_Dx² = λ² Σ 2|h0|² k_x²/k², σ_Dz² likewise, and the divergence of the
/// displacement, J − 1 ≈ its linear part, σ_div² = λ² Σ 2|h0|² k². The displacement scale
/// is 8·max(σ_η, σ_Dx, σ_Dz) (a Gaussian value exceeds 8σ with probability 1e-15); the
/// Jacobian's is m + 2m² with m = 8σ_div (the linear part and a bound on the quadratic
/// one). Both rounded up to three digits, at least 1e-3. Values beyond are clamped.
pub fn png_scales(ocean: &OceanState) -> Vec<PngScale> {
    let lambda = f64::from(ocean.config().choppiness);
    ocean
        .cascades()
        .iter()
        .map(|cascade| {
            let n = cascade.size();
            let dk = f64::from(cascade.delta_k());
            let m = |i: usize| {
                if i < n / 2 {
                    i as f64
                } else {
                    i as f64 - n as f64
                }
            };
            let (mut eta, mut dx, mut dz, mut div) = (0.0, 0.0, 0.0, 0.0);
            for (index, h) in cascade.h0().iter().enumerate() {
                let e = 2.0 * f64::from(h.norm_sqr());
                if e == 0.0 {
                    continue;
                }
                let (kx, kz) = (dk * m(index % n), dk * m(index / n));
                let k2 = kx * kx + kz * kz;
                eta += e;
                if k2 > 0.0 {
                    dx += e * kx * kx / k2;
                    dz += e * kz * kz / k2;
                }
                div += e * k2;
            }
            let sd = 8.0 * eta.sqrt().max(lambda * dx.sqrt()).max(lambda * dz.sqrt());
            let mj = 8.0 * lambda * div.sqrt();
            PngScale {
                displacement_scale: round_up_3(sd.max(1e-3)),
                jacobian_scale: round_up_3((mj + 2.0 * mj * mj).max(1e-3)),
            }
        })
        .collect()
}

/// `v` in [−1, 1] (scaled) to 16 bits: round(32767.5·(v + 1)), clamped; `clamped` counts
/// values outside.
fn unorm16(v: f64, clamped: &mut u64) -> u16 {
    let p = (v + 1.0) * 32767.5;
    if !(0.0..=65535.0).contains(&p) {
        *clamped += 1;
    }
    p.round().clamp(0.0, 65535.0) as u16
}

/// Encodes a 16-bit RGBA PNG of N×N pixels.
fn png_rgba16(size: usize, pixels: &[[u16; 4]]) -> Result<Vec<u8>, String> {
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, size as u32, size as u32);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Sixteen);
    let mut writer = encoder
        .write_header()
        .map_err(|e| format!("PNG encoder: {e}"))?;
    let data: Vec<u8> = pixels
        .iter()
        .flat_map(|p| p.iter().flat_map(|c| c.to_be_bytes()))
        .collect();
    writer
        .write_image_data(&data)
        .map_err(|e| format!("PNG encoder: {e}"))?;
    writer.finish().map_err(|e| format!("PNG encoder: {e}"))?;
    Ok(bytes)
}

/// The two PNG files of one cascade at one frame (displacement+foam, normal+Jacobian; see
/// [`PNG_CHANNELS`]), and how many values were clamped to the scales.
///
/// # Errors
/// The encoder's message (it does not fail on valid buffers).
pub fn encode_png(t: &Texels<f32>, scale: PngScale) -> Result<(Vec<Vec<u8>>, u64), String> {
    let mut clamped = 0;
    let sd = scale.displacement_scale;
    let disp: Vec<[u16; 4]> = t
        .displacement_foam
        .iter()
        .map(|d| {
            let [x, y, z] = [d[0], d[1], d[2]].map(|v| unorm16(f64::from(v) / sd, &mut clamped));
            let foam = (f64::from(d[3]).clamp(0.0, 1.0) * 65535.0).round() as u16;
            [x, y, z, foam]
        })
        .collect();
    let sj = scale.jacobian_scale;
    let normal: Vec<[u16; 4]> = t
        .normal_jacobian
        .iter()
        .map(|n| {
            let [x, y, z] = [n[0], n[1], n[2]].map(|v| unorm16(f64::from(v), &mut clamped));
            [x, y, z, unorm16((f64::from(n[3]) - 1.0) / sj, &mut clamped)]
        })
        .collect();
    Ok((
        vec![png_rgba16(t.size, &disp)?, png_rgba16(t.size, &normal)?],
        clamped,
    ))
}

/// The temporary name `path` is written under before its rename: `.NAME.PID.tmp` in the same
/// directory (never matched as a frame, so a resumed bake ignores leftovers of a killed one).
pub fn temporary_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

/// Writes `path` atomically: `write` fills a temporary file in the same directory, which is
/// then renamed over `path` (one `rename`, atomic on POSIX file systems). On any error the
/// temporary file is removed and `path` is untouched, so a reader, or a resumed bake, sees
/// either no file or a whole one, also when the process is killed. It is not synced to disk
/// (an fsync per file tripled a bake's wall time here): after a power cut, a file system
/// may hold an empty file under the final name; a crash of the machine calls for
/// `--overwrite` of the last frames.
///
/// # Errors
/// Those of creating, writing, syncing or renaming the file.
pub fn write_atomic_with(
    path: &Path,
    write: impl FnOnce(&mut File) -> io::Result<()>,
) -> io::Result<()> {
    let temporary = temporary_path(path);
    let result = (|| {
        let mut file = File::create(&temporary)?;
        write(&mut file)?;
        drop(file);
        std::fs::rename(&temporary, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    result
}

/// [`write_atomic_with`] of the bytes `bytes`.
///
/// # Errors
/// As [`write_atomic_with`].
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    write_atomic_with(path, |file| file.write_all(bytes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_write_leaves_neither_the_file_nor_a_temporary() {
        let dir = std::env::temp_dir().join(format!("ocean-fft-atomic-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("frame_0001.exr");
        let _ = std::fs::remove_file(&path);
        // Half the bytes reach the temporary file, then the "disk" fails.
        let error = write_atomic_with(&path, |file| {
            file.write_all(&[7u8; 1000])?;
            Err(io::Error::other("simulated failure"))
        })
        .unwrap_err();
        assert_eq!(error.to_string(), "simulated failure");
        assert!(!path.exists());
        assert!(!temporary_path(&path).exists());
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);

        // An existing file stays whole through a failed overwrite.
        write_atomic(&path, b"whole").unwrap();
        let _ = write_atomic_with(&path, |file| {
            file.write_all(b"par")?;
            Err(io::Error::other("simulated failure"))
        });
        assert_eq!(std::fs::read(&path).unwrap(), b"whole");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn three_digits_rounds_to_nearest() {
        assert_eq!(three_digits(90.123, f64::round), 90.1);
        assert_eq!(three_digits(4.5678, f64::round), 4.57);
        assert_eq!(three_digits(4012.0, f64::round), 4010.0);
    }

    #[test]
    fn round_up_keeps_three_digits_and_never_rounds_down() {
        assert_eq!(round_up_3(3.2101), 3.22);
        assert_eq!(round_up_3(0.012345), 0.0124);
        assert!(round_up_3(123456.0) >= 123456.0);
        for x in [1e-3, 0.5, 1.0, 7.77, 99.95, 1234.5] {
            let r = round_up_3(x);
            assert!(r >= x && r <= x * 1.01, "{x} → {r}");
        }
    }
}
