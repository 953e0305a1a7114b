//! The bake tool end to end, on small seas (32² to 64², a few frames) so that CI stays fast:
//! split bakes are byte-identical to one bake, resumes skip, overwrites rewrite, the EXR and
//! PNG files decode to the simulation's buffers, loops close including foam, and errors
//! exit with their documented codes.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::{Command, Stdio};

use ocean_fft::{OceanConfig, OceanState, Spectrum};
use ocean_fft_cli::bake::{bake, Report, Silent};
use ocean_fft_cli::error::Kind;
use ocean_fft_cli::setup;
use ocean_fft_cli::sim::Simulator;

mod common;
use common::{bake_args as parse, binary, scratch};

fn run(args: &[&str]) -> Report {
    bake(&parse(args), &mut Silent).unwrap()
}

/// Every file of a directory: name → bytes.
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect()
}

/// The storm: plenty of foam even on a small grid, so foam differences show.
const SEA: [&str; 6] = ["--preset", "storm", "--size", "32", "--fps", "10"];

#[test]
fn two_processes_write_what_one_writes_foam_included() {
    let whole = scratch("split-whole");
    let (a, b, c) = (scratch("split-a"), scratch("split-b"), scratch("split-c"));
    let out = |d: &Path| d.to_str().unwrap().to_string();
    // Anchors every 8 frames: the split at 6 falls inside the first block, the one at 11
    // inside the second.
    let common = [&SEA[..], &["--anchor-every", "8"]].concat();
    let with = |frames: &str, dir: &Path| {
        let o = out(dir);
        let mut v: Vec<&str> = common.clone();
        v.extend(["--frames", frames, "--out", &o]);
        run(&v)
    };
    with("0-13", &whole);
    with("0-5", &a);
    with("6-10", &b);
    with("11-13", &c);
    let whole_files = files(&whole);
    let mut split = files(&a);
    for part in [&b, &c] {
        let part = files(part);
        // The sidecars of every part are the same bytes as the whole bake's.
        assert_eq!(split["storm.json"], part["storm.json"]);
        split.extend(part);
    }
    assert_eq!(whole_files.len(), 14 * 3 + 1);
    assert_eq!(
        split.keys().collect::<Vec<_>>(),
        whole_files.keys().collect::<Vec<_>>()
    );
    for (name, bytes) in &whole_files {
        assert!(
            split[name] == *bytes,
            "{name} differs between the split and the whole bake"
        );
    }
    // A sparse list writes the same bytes for its frames too.
    let sparse = scratch("split-sparse");
    with("1-3,9,11-13:2", &sparse);
    for (name, bytes) in files(&sparse) {
        assert!(
            whole_files[&name] == bytes,
            "{name} differs in the sparse bake"
        );
    }
    // The test is about foam: make sure there is some in the frames compared.
    let foam = read_exr(&whole.join("storm_c0_0009.exr"));
    assert!(foam["A"].iter().any(|&f| f > 0.05), "no foam to compare");
    for d in [whole, a, b, c, sparse] {
        std::fs::remove_dir_all(d).unwrap();
    }
}

#[test]
fn existing_frames_are_skipped_unless_overwrite_and_another_bake_is_refused() {
    let dir = scratch("resume");
    let o = dir.to_str().unwrap();
    let first = run(&[&SEA[..], &["--frames", "0-3", "--out", o]].concat());
    assert_eq!((first.written.len(), first.skipped), (12, 0));
    let original = std::fs::read(dir.join("storm_c1_0002.exr")).unwrap();
    std::fs::write(dir.join("storm_c1_0002.exr"), b"stale").unwrap();

    // Resume over a longer range: only the new frames are written, the stale file stays.
    let resumed = run(&[&SEA[..], &["--frames", "0-5", "--out", o]].concat());
    assert_eq!((resumed.written.len(), resumed.skipped), (6, 12));
    assert_eq!(resumed.frames, 2);
    assert_eq!(
        std::fs::read(dir.join("storm_c1_0002.exr")).unwrap(),
        b"stale"
    );

    // --overwrite rewrites every frame asked for, with the same bytes as the first time.
    let again = run(&[&SEA[..], &["--frames", "2", "--out", o, "--overwrite"]].concat());
    assert_eq!((again.written.len(), again.skipped), (3, 0));
    assert_eq!(
        std::fs::read(dir.join("storm_c1_0002.exr")).unwrap(),
        original
    );

    // Another sea into the same directory is refused (exit code 5), nothing written.
    let before = files(&dir);
    let other = bake(
        &parse(&[&SEA[..], &["--seed", "7", "--frames", "6", "--out", o]].concat()),
        &mut Silent,
    )
    .unwrap_err();
    assert_eq!(other.kind, Kind::Conflict);
    assert_eq!(other.kind.exit_code(), 5);
    assert!(
        other.message.contains("other parameters"),
        "{}",
        other.message
    );
    assert_eq!(files(&dir), before);
    // No temporary file is left behind by any of these runs.
    assert!(before.keys().all(|n| !n.ends_with(".tmp")));
    std::fs::remove_dir_all(dir).unwrap();
}

/// Every channel of an EXR file as f32, by name; checks it is half-float, ZIP, N×N.
fn read_exr(path: &Path) -> BTreeMap<String, Vec<f32>> {
    use exr::prelude::*;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .unwrap();
    let layer = image.layer_data;
    assert_eq!(layer.encoding.compression, Compression::ZIP16);
    layer
        .channel_data
        .list
        .iter()
        .map(|c| {
            assert!(
                matches!(c.sample_data, FlatSamples::F16(_)),
                "{} not half",
                c.name
            );
            (c.name.to_string(), c.sample_data.values_as_f32().collect())
        })
        .collect()
}

/// Half-float rounding: round to nearest keeps |f16(v) − v| ≤ ½ ulp ≤ 2⁻¹¹|v| for normal
/// halves, and ≤ 2⁻²⁵ (half the subnormal step 2⁻²⁴) below 2⁻¹⁴.
fn assert_half(name: &str, file: &[f32], memory: impl Iterator<Item = f32>) {
    let mut count = 0;
    for (i, (&got, want)) in file.iter().zip(memory).enumerate() {
        let tolerance = (want.abs() * 2f32.powi(-11)).max(2f32.powi(-25));
        assert!(
            (got - want).abs() <= tolerance,
            "{name}[{i}]: file {got}, memory {want}, tolerance {tolerance}"
        );
        count += 1;
    }
    assert_eq!(count, file.len(), "{name}: length");
}

/// The ocean at `frame` as the bake defines it, built here from the sidecar's spectrum and
/// config (not from the tool's own setup).
fn ocean_at(args: &[&str], frame: u32) -> Simulator<'static> {
    let b = parse(args);
    let sea = Box::leak(Box::new(setup::build(&b.sea).unwrap()));
    let mut simulator = Simulator::new(sea).unwrap();
    simulator.advance_to(frame).unwrap();
    simulator
}

#[test]
fn exr_files_hold_the_simulation_buffers_within_half_float_rounding() {
    let dir = scratch("exr");
    let o = dir.to_str().unwrap();
    let args = [&SEA[..], &["--frames", "4", "--out", o]].concat();
    run(&args);
    let simulator = ocean_at(&args, 4);
    let ocean = simulator.ocean();
    for (c, cascade) in ocean.cascades().iter().enumerate() {
        let channels = read_exr(&dir.join(format!("storm_c{c}_0004.exr")));
        let names: Vec<&str> = channels.keys().map(String::as_str).collect();
        assert_eq!(
            names,
            [
                "A",
                "B",
                "G",
                "R",
                "jacobian.Y",
                "normal.X",
                "normal.Y",
                "normal.Z"
            ]
        );
        assert_eq!(channels["R"].len(), 32 * 32);
        // The library's own buffers, not the tool's packing.
        let d = cascade.displacement();
        let n = cascade.normal();
        assert_half("R", &channels["R"], d.iter().map(|v| v[0]));
        assert_half("G", &channels["G"], cascade.height().iter().copied());
        assert_half("B", &channels["B"], d.iter().map(|v| v[1]));
        // The ocean's one foam field is on cascade 0's grid; the other cascades carry 0.
        let foam: Vec<f32> = if c == 0 {
            ocean.foam_view().total().to_vec()
        } else {
            vec![0.0; 32 * 32]
        };
        assert_half("A", &channels["A"], foam.iter().copied());
        assert_half("normal.X", &channels["normal.X"], n.iter().map(|v| v[0]));
        assert_half("normal.Y", &channels["normal.Y"], n.iter().map(|v| v[1]));
        assert_half("normal.Z", &channels["normal.Z"], n.iter().map(|v| v[2]));
        assert_half(
            "jacobian.Y",
            &channels["jacobian.Y"],
            cascade.jacobian().iter().copied(),
        );
        // Not a trivially flat file.
        assert!(channels["G"].iter().any(|&h| h.abs() > 0.01));
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// The RGBA16 pixels of a PNG.
fn read_png(path: &Path) -> Vec<[u16; 4]> {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut data = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut data).unwrap();
    assert_eq!(
        (info.color_type, info.bit_depth),
        (png::ColorType::Rgba, png::BitDepth::Sixteen)
    );
    data[..info.buffer_size()]
        .chunks_exact(8)
        .map(|p| std::array::from_fn(|c| u16::from_be_bytes([p[2 * c], p[2 * c + 1]])))
        .collect()
}

#[test]
fn png_files_decode_with_the_sidecar_scales() {
    let dir = scratch("png");
    let o = dir.to_str().unwrap();
    let args = [&SEA[..], &["--frames", "3", "--format", "png", "--out", o]].concat();
    let report = run(&args);
    assert_eq!(report.clamped, 0);
    let sidecar: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("storm.json")).unwrap()).unwrap();
    let simulator = ocean_at(&args, 3);
    let ocean = simulator.ocean();
    for (c, cascade) in ocean.cascades().iter().enumerate() {
        let scales = &sidecar["files"]["encoding"]["decode_scales"][c];
        let sd = scales["displacement_scale"].as_f64().unwrap();
        let sj = scales["jacobian_scale"].as_f64().unwrap();
        // The decode the sidecar documents, written out here.
        let signed = |p: u16| 2.0 * f64::from(p) / 65535.0 - 1.0;
        let disp = read_png(&dir.join(format!("storm_c{c}_disp_0003.png")));
        let normal = read_png(&dir.join(format!("storm_c{c}_normal_0003.png")));
        // Rounding to the nearest of 65536 levels over [−s, s]: ≤ half a level, s/65535,
        // plus f32 rounding of the buffers (relative 1e-7).
        let check = |what: &str, got: f64, want: f32, scale: f64| {
            let tolerance = scale / 65535.0 * (1.0 + 1e-6) + 1e-6 * f64::from(want).abs();
            assert!(
                (got - f64::from(want)).abs() <= tolerance,
                "cascade {c} {what}: decoded {got}, memory {want}"
            );
        };
        let mut largest = 0.0f32;
        for i in 0..32 * 32 {
            let d = cascade.displacement()[i];
            let h = cascade.height()[i];
            largest = largest.max(h.abs()).max(d[0].abs()).max(d[1].abs());
            check("D_x", signed(disp[i][0]) * sd, d[0], sd);
            check("η", signed(disp[i][1]) * sd, h, sd);
            check("D_z", signed(disp[i][2]) * sd, d[1], sd);
            check(
                "foam",
                f64::from(disp[i][3]) / 65535.0,
                if c == 0 {
                    ocean.foam_view().total()[i]
                } else {
                    0.0
                },
                0.5,
            );
            for (&p, &n) in normal[i].iter().zip(&cascade.normal()[i]) {
                check("n", signed(p), n, 1.0);
            }
            check(
                "J",
                1.0 + signed(normal[i][3]) * sj,
                cascade.jacobian()[i],
                sj,
            );
        }
        // The scale is 8σ: the largest of 32² samples of a Gaussian lies near 3–4σ, so well
        // inside it, and not so far inside that precision is wasted.
        let ratio = f64::from(largest) / sd;
        assert!(
            (0.15..0.8).contains(&ratio),
            "cascade {c}: max {largest} m vs scale {sd} m"
        );
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_loop_closes_in_every_channel_with_the_foam_in_its_periodic_steady_state() {
    let dir = scratch("loop");
    let o = dir.to_str().unwrap();
    // A 1 s loop at 10 fps: 10 frames; frame 10 must equal frame 0.
    let args = [&SEA[..], &["--loop", "1", "--frames", "0-10", "--out", o]].concat();
    let report = run(&args);
    let convergence = report.convergence.unwrap();
    for c in 0..3 {
        let first = std::fs::read(dir.join(format!("storm_c{c}_0000.exr"))).unwrap();
        let last = std::fs::read(dir.join(format!("storm_c{c}_0010.exr"))).unwrap();
        assert!(first == last, "cascade {c}: frame 10 differs from frame 0");
    }

    // Independently: an ocean of the sidecar's spectrum and config simulated without a
    // break for 200 loops from no foam (continuous time, no jump back to t = 0). The foam
    // forgets its start at least as about 2.35·e^{−t/τ_R} (τ_R = 15 s, see
    // docs/guide/baking.md, "Render farms"), so after 200 s it is within 4e-6 of the periodic steady state; at
    // t = 200 s and 200.3 s it must match frames 0 and 3.
    let sidecar: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("storm.json")).unwrap()).unwrap();
    let spectrum: Spectrum = serde_json::from_value(sidecar["spectrum"].clone()).unwrap();
    let config: OceanConfig = serde_json::from_value(sidecar["config"].clone()).unwrap();
    let mut ocean = OceanState::new(spectrum, config).unwrap();
    let mut foam_seen = 0.0f32;
    for (index, frame) in [(2000, 0), (2003, 3)] {
        while ocean.time() < index as f64 / 10.0 - 1e-9 {
            let next = (ocean.time() * 10.0).round() + 1.0;
            ocean.step_to(next / 10.0).unwrap();
        }
        for c in 0..3 {
            let file = read_exr(&dir.join(format!("storm_c{c}_{frame:04}.exr")));
            let zeros = vec![0.0; 32 * 32];
            let foam = if c == 0 {
                ocean.foam_view().total()
            } else {
                &zeros[..]
            };
            // f16 rounding (≤ 2⁻¹² on [0, 1]) plus the stop rule's ε = 1e-3 (the default)
            // plus the start's remainder (4e-6) and f32 drift of a 2000-step history.
            for (i, (&got, &want)) in file["A"].iter().zip(foam).enumerate() {
                assert!(
                    (got - want).abs() <= 2f32.powi(-12) + 1e-3 + 2e-5,
                    "cascade {c} frame {frame} texel {i}: baked foam {got}, continuous {want}"
                );
                foam_seen = foam_seen.max(want);
            }
            // The waves too: 200 s differs from 0 s by whole loops, so by whole periods of
            // every wave.
            let height = ocean.cascades()[c].height();
            for (&got, &want) in file["G"].iter().zip(height) {
                assert!((got - want).abs() <= want.abs() * 2f32.powi(-11) + 1e-4);
            }
        }
    }
    // Foam that a start from zero at phase 0 would have missed.
    assert!(foam_seen > 0.1, "largest foam {foam_seen}: nothing to test");
    // And the tool's own account of it.
    assert!(convergence.last_change <= 1e-4, "{convergence:?}");
    assert!(convergence.seam_bound <= 1e-4 * (-1.0f64 / 2.5).exp() * 1.000001);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn bad_input_exits_with_its_code_and_names_the_argument() {
    let dir = scratch("errors");
    let o = dir.to_str().unwrap();
    let cases: [(&[&str], i32, &str); 11] = [
        // A negative value is a value, refused by the library's check, not an unknown option.
        (
            &[
                "bake", "--preset", "calm", "--wind", "-5", "--frames", "1", "--out", o,
            ],
            2,
            "--wind -5",
        ),
        (
            &[
                "bake",
                "--preset",
                "calm",
                "--choppiness",
                "-1",
                "--frames",
                "1",
                "--out",
                o,
            ],
            2,
            "--choppiness -1",
        ),
        (
            &["bake", "--preset", "calm", "--frames", "10-1", "--out", o],
            2,
            "--frames",
        ),
        (
            &["bake", "--preset", "calmer", "--frames", "1", "--out", o],
            2,
            "calmer",
        ),
        (&["bake", "--frames", "1", "--out", o], 2, "--preset"),
        (
            &[
                "bake", "--preset", "calm", "--wind", "500", "--frames", "1", "--out", o,
            ],
            2,
            "--wind 500",
        ),
        (
            &[
                "bake", "--preset", "calm", "--size", "33", "--frames", "1", "--out", o,
            ],
            2,
            "--size 33",
        ),
        (
            &[
                "bake", "--preset", "calm", "--loop", "4.01", "--frames", "1", "--out", o,
            ],
            2,
            "--loop 4.01",
        ),
        (
            &[
                "bake", "--preset", "calm", "--fps", "0", "--frames", "1", "--out", o,
            ],
            2,
            "--fps 0",
        ),
        (
            &["info", "--config", "/nonexistent/sea.json"],
            3,
            "--config /nonexistent/sea.json",
        ),
        (
            &[
                "bake",
                "--preset",
                "calm",
                "--frames",
                "1",
                "--out",
                "/proc/no/such/dir",
            ],
            4,
            "--out",
        ),
    ];
    for (args, code, mention) in cases {
        let (got, stderr) = binary(args);
        assert_eq!(got, code, "{args:?}: {stderr}");
        assert!(stderr.contains(mention), "{args:?}: {stderr}");
    }
    // A config file with a parameter out of range: named, exit 3.
    let bad = dir.join("bad.json");
    let (spectrum, config) = ocean_fft::SeaState::Calm.build();
    let text = serde_json::json!({"spectrum": spectrum, "config": config})
        .to_string()
        .replace("\"swell\":0.0", "\"swell\":2.0");
    std::fs::write(&bad, text).unwrap();
    let (got, stderr) = binary(&["info", "--config", bad.to_str().unwrap()]);
    assert_eq!(got, 3, "{stderr}");
    assert!(stderr.contains("swell"), "{stderr}");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_killed_bake_leaves_only_whole_files_and_resumes_to_the_same_bytes() {
    let dir = scratch("killed");
    let o = dir.to_str().unwrap().to_string();
    let args = [
        "bake", "--preset", "storm", "--size", "64", "--fps", "10", "--frames", "0-39",
    ];
    let mut child = Command::new(env!("CARGO_BIN_EXE_ocean-fft"))
        .args(args)
        .args(["--out", &o, "--encoders", "1"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // Kill it once it has reported a few files (stdout is a pipe: `OUTPUT_FILE:` lines).
    use std::io::BufRead;
    let stdout = std::io::BufReader::new(child.stdout.take().unwrap());
    let mut lines = stdout.lines();
    for _ in 0..4 {
        let line = lines.next().unwrap().unwrap();
        assert!(line.starts_with("OUTPUT_FILE: "), "{line}");
    }
    child.kill().unwrap();
    child.wait().unwrap();
    // Every file under a frame's name reads back whole.
    let after_kill = files(&dir);
    let frames: Vec<&String> = after_kill.keys().filter(|n| n.ends_with(".exr")).collect();
    assert!(
        frames.len() >= 4 && frames.len() < 120,
        "{} files",
        frames.len()
    );
    for name in &frames {
        read_exr(&dir.join(name));
    }
    // Resume: the rest is written, and everything equals a bake that was never killed.
    let resumed = parse(&[&args[1..], &["--out", &o]].concat());
    let report = bake(&resumed, &mut Silent).unwrap();
    assert!(report.skipped >= frames.len());
    let clean = scratch("killed-clean");
    let c = clean.to_str().unwrap().to_string();
    bake(&parse(&[&args[1..], &["--out", &c]].concat()), &mut Silent).unwrap();
    let (resumed_files, clean_files) = (files(&dir), files(&clean));
    for (name, bytes) in &clean_files {
        assert!(
            resumed_files[name] == *bytes,
            "{name} differs after the resume"
        );
    }
    // Leftover temporaries of the killed process, if any, are hidden `.tmp` files only.
    for name in resumed_files
        .keys()
        .filter(|n| !clean_files.contains_key(*n))
    {
        assert!(name.starts_with('.') && name.ends_with(".tmp"), "{name}");
    }
    std::fs::remove_dir_all(dir).unwrap();
    std::fs::remove_dir_all(clean).unwrap();
}

#[test]
fn the_tool_reports_the_library_version() {
    let manifest =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../Cargo.toml")).unwrap();
    let line = manifest
        .lines()
        .find(|l| l.starts_with("version = "))
        .unwrap();
    assert_eq!(
        line,
        format!("version = \"{}\"", ocean_fft_cli::describe::VERSION)
    );
}

#[test]
fn the_sidecar_loads_back_as_the_same_sea_and_is_readable() {
    let dir = scratch("sidecar");
    let o = dir.to_str().unwrap();
    let args = [&SEA[..], &["--loop", "2", "--frames", "0", "--out", o]].concat();
    run(&args);
    let text = std::fs::read_to_string(dir.join("storm.json")).unwrap();
    let sidecar: serde_json::Value = serde_json::from_str(&text).unwrap();
    let spectrum: Spectrum = serde_json::from_value(sidecar["spectrum"].clone()).unwrap();
    let config: OceanConfig = serde_json::from_value(sidecar["config"].clone()).unwrap();
    let sea = setup::build(&parse(&args).sea).unwrap();
    // Bit for bit (PartialEq on f32 fields), though the f32s are written short.
    assert_eq!(spectrum, sea.spectrum);
    assert_eq!(config, sea.config);
    assert!(text.contains("\"residual_decay\": 15.0,"), "{text}");
    assert_eq!(sidecar["seed"], 0);
    assert_eq!(sidecar["loop"]["frames"], 20);
    assert!(
        sidecar["loop"]["mean_relative_frequency_error"]
            .as_f64()
            .unwrap()
            > 0.0
    );
    // The preset's second tile (fitted to the storm, about 925 m) and its 32 texels.
    let length = f64::from(sea.config.lengths[1]);
    assert!((900.0..950.0).contains(&length), "{length}");
    assert_eq!(sidecar["cascades"][1]["length_m"], length);
    assert_eq!(sidecar["cascades"][1]["texel_size_m"], length / 32.0);
    // And as a --config, it bakes the same bytes as the preset did.
    let again = scratch("sidecar-again");
    let a = again.to_str().unwrap();
    let path = dir.join("storm.json");
    let from_file = [
        "--config",
        path.to_str().unwrap(),
        "--fps",
        "10",
        "--frames",
        "0",
        "--out",
        a,
        "--name",
        "storm",
    ];
    run(&from_file);
    assert!(
        files(&again) == files(&dir),
        "the sidecar as --config bakes other bytes"
    );
    std::fs::remove_dir_all(dir).unwrap();
    std::fs::remove_dir_all(again).unwrap();
}
