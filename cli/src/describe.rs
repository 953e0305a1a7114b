//! What a bake is: the JSON sidecar (every parameter and every convention a shader needs)
//! and the text `ocean-fft info` prints.

use std::fmt::Write as _;

use ocean_fft::gpu::Engine;
use ocean_fft::OceanState;
use serde_json::{json, Value};

use crate::args::Format;
use crate::encode::{self, PngScale};
use crate::setup::Sea;
use crate::sim::LoopConvergence;

/// The version of the library and of this tool (one workspace, one version; a test checks
/// that the library's Cargo.toml says the same).
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// Frame time, as the sidecar states it.
fn frame_time(sea: &Sea) -> String {
    match sea.looping {
        None => format!("t = frame / {} s", sea.fps),
        Some(l) => format!(
            "t = (frame mod {}) / {} s: frame f + {} is frame f",
            l.frames, sea.fps, l.frames
        ),
    }
}

/// How the foam's pre-roll is defined, as the sidecar states it.
fn preroll_text(sea: &Sea) -> String {
    let p = sea.preroll;
    match sea.looping {
        None => format!(
            "frame f's foam is pre-rolled (OceanState::pre_roll) from zero over the {} frames \
             before a = f − f mod {} (its anchor) in steps of {:.4} s, then stepped with step_to \
             to every frame time i/fps up to f; W = (τ_A + τ_R)·ln(1/ε) = {:.3} s, so it is \
             within about ε = {} of an ocean simulated forever, and jumps by at most about 2ε at \
             anchors",
            p.frames, p.anchor_every, p.step, p.window, p.tolerance
        ),
        Some(l) => format!(
            "the foam starts from zero at phase 0; whole loops of {} frames (steps to i/fps, i = \
             1..={}, then back to t = 0 with the foam kept) are simulated until one changes no \
             foam value by more than ε·(1 − q) = {:.3e} (ε = {}, q = e^(−T/τ_R) the contraction \
             of one loop; at most {} loops), which leaves the foam within ε of the loop's \
             periodic steady state; phase p is then stepped from that steady state",
            l.frames, l.frames, p.loop_change, p.tolerance, p.max_loops
        ),
    }
}

/// The cascades: lengths, sizes, texel sizes, bands and expected H_s of each.
fn cascades(ocean: &OceanState) -> Vec<Value> {
    let bands = ocean.config().bands().unwrap_or_default();
    ocean
        .cascades()
        .iter()
        .enumerate()
        .map(|(c, cascade)| {
            let (lo, hi) = bands.get(c).copied().unwrap_or((0.0, 0.0));
            let wavelength = |k: f32| {
                if k > 0.0 {
                    Some(std::f64::consts::TAU / f64::from(k))
                } else {
                    None
                }
            };
            json!({
                "index": c,
                "length_m": cascade.length(),
                "size": cascade.size(),
                "texel_size_m": f64::from(cascade.length()) / cascade.size() as f64,
                "band_rad_per_m": [lo, hi],
                "band_wavelength_m": [wavelength(lo), wavelength(hi)],
                "expected_hs_m": 4.0 * cascade.expected_variance().sqrt(),
                "uv_of_world_xz": format!(
                    "uv = (x / {L} + 0.5 / {N}, z / {L} + 0.5 / {N}), wrap repeat",
                    L = cascade.length(), N = cascade.size()
                ),
            })
        })
        .collect()
}

/// The engines table: where the crate's axes land in each engine.
fn engines() -> Vec<Value> {
    Engine::ALL
        .iter()
        .map(|&e| {
            json!({
                "engine": e.name(),
                "right_handed": e.right_handed(),
                "units_per_metre": e.units_per_metre(),
                "crate_x_is": e.direction([1.0, 0.0, 0.0]),
                "crate_y_is": e.direction([0.0, 1.0, 0.0]),
                "crate_z_is": e.direction([0.0, 0.0, 1.0]),
                "image_first_row_at_v": if e.texture_origin_top() { 0 } else { 1 },
                "normal_map_green": if e.directx_normal_maps() { "DirectX (-Y)" } else { "OpenGL (+Y)" },
            })
        })
        .collect()
}

/// The sidecar JSON of a bake: a function of the sea and the format only (never of the
/// frames baked), so every process of a split bake writes the same bytes. It is also a valid
/// `--config` file (its keys "spectrum" and "config").
pub fn sidecar(sea: &Sea, format: Format, ocean: &OceanState, scales: &[PngScale]) -> String {
    let looping = sea.looping.map(|l| {
        let error = ocean.diagnostics().loop_error();
        json!({
            "period_s": l.period,
            "frames": l.frames,
            "max_relative_frequency_error": error.map(|e| e.max_relative),
            "mean_relative_frequency_error": error.map(|e| e.mean_relative),
            "foam_seam_bound": (-f64::from(l.period) / crate::sim::slowest_decay(sea)).exp() * sea.preroll.tolerance,
        })
    });
    let channels = match format {
        Format::Exr => &encode::EXR_CHANNELS,
        Format::Png => &encode::PNG_CHANNELS,
    };
    let encoding = match format {
        Format::Exr => json!({
            "format": "OpenEXR",
            "pixel_type": "half (f16), nearest, ±65504 saturated",
            "compression": "ZIP (16 scan lines per block)",
            "line_order": "increasing (row 0 = z 0 first, the top of the image)",
            "files_per_frame_and_cascade": 1,
        }),
        Format::Png => json!({
            "format": "PNG",
            "pixel_type": "16-bit unsigned RGBA (p in 0..=65535), linear data (no gamma)",
            "files_per_frame_and_cascade": 2,
            "decode_scales": scales,
            "scales_from": "8 standard deviations of the cascade's Gaussian fields (from h0); J: m + 2m² with m = 8σ of its linear part; values beyond are clamped",
            "viewing": "the alpha channel is data (foam in disp files, the Jacobian in normal files), not transparency: an image viewer that honours alpha shows a disp file nearly blank where there is no foam. To look at one, drop or flatten its alpha (for example `magick NAME_c0_disp_0000.png -alpha off preview.png`)",
        }),
    };
    let value = json!({
        "tool": "ocean-fft bake",
        "version": VERSION,
        "name": sea.name,
        "seed": sea.config.seed,
        "spectrum": sea.spectrum,
        "config": sea.config,
        "significant_wave_height_m": sea.spectrum.significant_wave_height(),
        "peak_period_s": sea.spectrum.peak_period(),
        "fps": sea.fps,
        "frame_time": frame_time(sea),
        "loop": looping,
        "foam_preroll": {
            "tolerance": sea.preroll.tolerance,
            "active_decay_s": sea.config.foam.active_decay,
            "residual_decay_s": sea.config.foam.residual_decay,
            "step_s": sea.preroll.step,
            "window_s": sea.preroll.window,
            "preroll_frames": sea.preroll.frames,
            "anchor_every_frames": if sea.looping.is_some() { None } else { Some(sea.preroll.anchor_every) },
            "definition": preroll_text(sea),
        },
        "files": {
            "patterns": encode::file_patterns(format),
            "encoding": encoding,
            "channels": channels,
        },
        "cascades": cascades(ocean),
        "conventions": {
            "axes": "right-handed, y up, the sea in the (x, z) plane, metres (glTF's frame)",
            "texel_to_world": "texel (i, j) (column i, row j, row 0 first) is the grid point x = i·L/N, z = j·L/N of a tile of side L (cascades[].length_m) that repeats in x and z: wrap mode repeat; its water sits at (x, 0, z) + (R, G, B) = (x + D_x, η, z + D_z)",
            "combining_cascades": "add the displacements (and slopes) of every cascade sampled at the same world point; foam combines as 1 − Π(1 − foam_c)",
            "normal": "the unit normal of the displaced surface in world axes (x, y, z), y up; not a tangent-space map. On a flat plane with u along +x and image rows along +z, an OpenGL (+Y green) tangent-space map is (n_x, −n_z, n_y), a DirectX (−Y) one (n_x, n_z, n_y)",
            "image_rows": "the first row of every image is z = 0 (the top of the image); engines whose v runs up sample uv = (x/L, 1 − z/L) or flip on import",
            "engines": engines(),
        },
    });
    let mut value = value;
    shorten_f32(&mut value);
    let mut text = serde_json::to_string_pretty(&value).expect("JSON of plain data");
    text.push('\n');
    text
}

/// Writes every number that is exactly an f32 (the configs' fields are f32, and a JSON value
/// holds them as f64) with the f32's shortest digits: 0.8 rather than 0.800000011920929.
/// Parsed as f32, those digits give the same f32 back, so the sidecar still loads as a
/// `--config` bit for bit; a number that is not an f32 is left as it is.
fn shorten_f32(value: &mut Value) {
    match value {
        Value::Number(n) => {
            if let Some(x) = n.as_f64().filter(|_| n.is_f64()) {
                let single = x as f32;
                if f64::from(single) == x && single.is_finite() {
                    let short: f64 = single.to_string().parse().expect("a float's digits");
                    if let Some(m) = serde_json::Number::from_f64(short) {
                        *n = m;
                    }
                }
            }
        }
        Value::Array(items) => items.iter_mut().for_each(shorten_f32),
        Value::Object(map) => map.values_mut().for_each(shorten_f32),
        _ => {}
    }
}

/// Bytes as "12.3 MiB".
fn mib(bytes: usize) -> String {
    format!("{:.1} MiB", bytes as f64 / (1024.0 * 1024.0))
}

/// What `ocean-fft info` prints.
pub fn info(sea: &Sea, ocean: &OceanState, convergence: Option<LoopConvergence>) -> String {
    let mut s = String::new();
    let spectrum = &sea.spectrum;
    let config = ocean.config();
    let _ = writeln!(s, "sea `{}`", sea.name);
    let _ = writeln!(
        s,
        "  wind {:.2} m/s toward {:.1}° (from +x toward +z), fetch {}, depth {}",
        spectrum.wind_speed(),
        spectrum.wind_direction().to_degrees(),
        spectrum
            .fetch()
            .map_or("none".into(), |f| format!("{f:.0} m")),
        spectrum.depth().map_or("deep".into(), |d| format!("{d} m")),
    );
    let _ = writeln!(
        s,
        "  Hs {:.3} m (spectrum), {:.3} m (the cascades' bands); Tp {:.2} s",
        spectrum.significant_wave_height(),
        4.0 * ocean.diagnostics().expected_variance().sqrt(),
        spectrum.peak_period()
    );
    let _ = writeln!(
        s,
        "  choppiness {}, seed {}, foam: coverage ×{}, active decay τ_A = {} s, residual decay τ_R = {} s",
        config.choppiness, config.seed, config.foam.coverage, config.foam.active_decay, config.foam.residual_decay
    );
    let calibration = ocean.foam_view().calibration();
    let _ = writeln!(
        s,
        "  whitecaps: {:.2} % of the surface at U10 = {} m/s (Monahan & O'Muircheartaigh 1980)",
        100.0 * calibration.target,
        calibration.wind_speed
    );
    let bands = config.bands().unwrap_or_default();
    let fit = crate::warnings::TileFit::new(spectrum, config);
    let _ = writeln!(
        s,
        "cascades ({} of {}²; peak wavelength {:.2} m):",
        ocean.cascades().len(),
        config.size,
        fit.as_ref().map_or(f64::NAN, |f| f.peak_wavelength)
    );
    for (c, cascade) in ocean.cascades().iter().enumerate() {
        let (lo, hi) = bands.get(c).copied().unwrap_or((0.0, 0.0));
        let longest = if lo > 0.0 {
            format!("{:.2} m", std::f32::consts::TAU / lo)
        } else {
            "the tile".into()
        };
        let shares = fit.as_ref().map_or(String::new(), |f| {
            format!(
                " ({:.2} % of the height variance, {:.1} % of the slope variance)",
                100.0 * f.height_share(c),
                100.0 * f.slope_share(c)
            )
        });
        let _ = writeln!(
            s,
            "  {c}: tile {} m, texel {:.4} m, band {:.4}–{:.3} rad/m (wavelengths {} down to {:.3} m), Hs {:.3} m{shares}",
            cascade.length(),
            f64::from(cascade.length()) / cascade.size() as f64,
            lo,
            hi,
            longest,
            std::f32::consts::TAU / hi,
            4.0 * cascade.expected_variance().sqrt()
        );
    }
    let points: usize = ocean.cascades().iter().map(|c| c.size().pow(2)).sum();
    // A frame in flight: two RGBA buffers per texel, f16 for EXR, f32 for PNG.
    let _ = writeln!(
        s,
        "memory: ocean {}, plus about {} per frame in flight while baking EXR ({} for PNG)",
        mib(config.memory_bytes()),
        mib(points * 16),
        mib(points * 32)
    );
    let _ = writeln!(s, "frames: {} fps; {}", sea.fps, frame_time(sea));
    match sea.looping {
        Some(l) => {
            let _ = writeln!(s, "loop: {} s = {} frames", l.period, l.frames);
            if let Some(e) = ocean.diagnostics().loop_error() {
                let _ = writeln!(
                    s,
                    "  frequency error of the loop: largest {:.2} %, mean {:.3} % (weighted by wave energy); every wave keeps ≥ 1 cycle per loop",
                    100.0 * e.max_relative,
                    100.0 * e.mean_relative
                );
            }
            let _ = writeln!(
                s,
                "  foam: whole loops pre-rolled until one changes the foam by ≤ {:.3e} (within ε = {} of the steady state; at most {} loops)",
                sea.preroll.loop_change, sea.preroll.tolerance, sea.preroll.max_loops
            );
            if let Some(c) = convergence {
                let _ = writeln!(
                    s,
                    "  measured: {} loops, last change {:.2e}, so the seam at frame {} is ≤ {:.2e}",
                    c.loops, c.last_change, l.frames, c.seam_bound
                );
            }
        }
        None => {
            let _ = writeln!(
                s,
                "foam pre-roll: {} frames ({:.2} s = (τ_A + τ_R)·ln(1/{}), in steps of {:.4} s) before each anchor, anchors every {} frames",
                sea.preroll.frames, sea.preroll.window, sea.preroll.tolerance, sea.preroll.step, sea.preroll.anchor_every
            );
        }
    }
    s
}
