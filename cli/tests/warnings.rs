//! What the bake tool says before it works: the warnings for a loop too short for the sea
//! and for tiles that do not fit it (each present for the bad case, absent for the good
//! one, and its suggested value silencing it), the disk size announced before any file is
//! written, the message of exit code 5, and `--help` stating the ranges the errors state
//! (and the library accepts). Seas of 16² to 64², a frame or two.

use std::path::Path;

use clap::CommandFactory;
use ocean_fft::{CascadeConfig, OceanConfig, OceanState};
use ocean_fft_cli::args::Cli;
use ocean_fft_cli::bake::{bake, Progress, Report};
use ocean_fft_cli::error::Kind;
use ocean_fft_cli::setup;
use ocean_fft_cli::warnings::{self, Warning};

mod common;
use common::{bake_args, binary, scratch, sea_args};

/// The warnings `info` and `bake` print for these sea arguments, and the ocean they judged.
fn warnings_for(args: &[&str]) -> (Vec<Warning>, OceanState) {
    let sea = setup::build(&sea_args(args)).unwrap();
    let ocean = OceanState::new(sea.spectrum.clone(), sea.config.clone()).unwrap();
    (warnings::check(&sea, &ocean), ocean)
}

/// The value a warning suggests for `flag`: the word after "use FLAG ".
fn suggested<'a>(warning: &'a Warning, flag: &str) -> &'a str {
    let after = warning
        .message
        .split(&format!("use {flag} "))
        .nth(1)
        .unwrap_or_else(|| panic!("no suggestion for {flag}: {}", warning.message));
    after.split_whitespace().next().unwrap()
}

#[test]
fn a_loop_shorter_than_twice_the_peak_period_warns_and_suggests_one_that_does_not() {
    // The README's old command: the storm (T_p 14.65 s) in an 8 s loop.
    let storm = ["--preset", "storm", "--size", "32", "--fps", "10"];
    let (bad, ocean) = warnings_for(&[&storm[..], &["--loop", "8"]].concat());
    assert_eq!(bad.len(), 1, "{bad:?}");
    let warning = &bad[0];
    assert_eq!(warning.parameter, "--loop");
    assert!(warning.message.starts_with("--loop 8 "), "{warning}");
    // The numbers it quotes are the library's own account of the loop.
    let error = ocean.diagnostics().loop_error().unwrap();
    let mean = format!("{:.0} % on average", 100.0 * error.mean_relative);
    assert!(warning.message.contains(&mean), "{warning}");
    // The suggestion: whole seconds at or above 2·T_p, computed here from the spectrum.
    let t_p = f64::from(ocean.spectrum().peak_period());
    let expected = (2.0 * t_p).ceil();
    assert_eq!(suggested(warning, "--loop"), expected.to_string());
    let fixed = expected.to_string();
    let (good, ocean) = warnings_for(&[&storm[..], &["--loop", &fixed]].concat());
    assert!(good.is_empty(), "{good:?}");
    // And the suggested loop keeps the waves near their speeds (the guide: about 8–9 % at
    // 2·T_p; a loop is never exact, so a bound rather than zero).
    assert!(ocean.diagnostics().loop_error().unwrap().mean_relative < 0.12);

    // A loop read from a --config's repeat_period is named as such.
    let dir = scratch("loop-config");
    let path = dir.join("short.json");
    let (spectrum, mut config) = ocean_fft::SeaState::FreshBreeze.build();
    config.size = 16;
    config.repeat_period = Some(4.0);
    let json = serde_json::json!({"spectrum": spectrum, "config": config});
    std::fs::write(&path, json.to_string()).unwrap();
    let (from_file, _) = warnings_for(&["--config", path.to_str().unwrap(), "--fps", "10"]);
    let loops: Vec<_> = from_file
        .iter()
        .filter(|w| w.parameter == "--loop")
        .collect();
    assert_eq!(loops.len(), 1, "{from_file:?}");
    assert!(
        loops[0]
            .message
            .starts_with("repeat_period (in --config) 4 "),
        "{}",
        loops[0]
    );
    // T_p = 6.94 s: 14 s, which is 140 frames at 10 fps.
    assert!(loops[0]
        .message
        .contains("--loop 14 (140 frames at 10 fps)"));
    std::fs::remove_dir_all(dir).unwrap();
}

/// Each cascade's share of the simulated height variance and slope variance, from its grid
/// (the library's expected Σ S(k)Δk², and the mean square of the slope buffer at t = 0),
/// not from the band integrals the tool judges by.
fn grid_shares(ocean: &mut OceanState) -> Vec<(f64, f64)> {
    ocean.set_time(0.0).unwrap();
    let heights: Vec<f64> = ocean
        .cascades()
        .iter()
        .map(|c| c.expected_variance())
        .collect();
    let slopes: Vec<f64> = ocean
        .cascades()
        .iter()
        .map(|c| {
            c.slope()
                .iter()
                .map(|s| f64::from(s[0]).powi(2) + f64::from(s[1]).powi(2))
                .sum::<f64>()
                / c.slope().len() as f64
        })
        .collect();
    let (h, s): (f64, f64) = (heights.iter().sum(), slopes.iter().sum());
    heights
        .iter()
        .zip(&slopes)
        .map(|(a, b)| (a / h, b / s))
        .collect()
}

#[test]
fn tiles_that_leave_a_cascade_empty_warn_and_the_suggested_lengths_do_not() {
    // The case: the storm's 4000 m tiles for a 3 m/s sea (peak wavelength 7.5 m).
    let (bad, mut ocean) = warnings_for(&["--preset", "storm", "--wind", "3", "--size", "64"]);
    assert_eq!(bad.len(), 1, "{bad:?}");
    let warning = &bad[0];
    assert_eq!(warning.parameter, "--lengths");
    for part in ["nearly empty", "--wind 3 changed the sea", "preset `storm`"] {
        assert!(warning.message.contains(part), "{part}: {warning}");
    }
    // The cascades it names are those the grid finds nearly empty (under 0.1 % of the
    // height variance and 1 % of the slope variance): on 64² grids the two larger ones.
    let shares = grid_shares(&mut ocean);
    for (c, &(height, slope)) in shares.iter().enumerate() {
        let named = warning.message.contains(&format!("cascade {c} ("));
        assert_eq!(
            named,
            height < 1e-3 && slope < 1e-2,
            "cascade {c}: {shares:?}"
        );
        assert_eq!(named, c < 2, "{warning}");
    }
    // And 64² texels of 204 m tiles (3.2 m) miss much of a sea whose peak is 7.5 m long.
    assert!(warning
        .message
        .contains("waves shorter than the finest texels"));

    let lengths = suggested(warning, "--lengths").to_string();
    let (good, mut ocean) = warnings_for(&[
        "--preset",
        "storm",
        "--wind",
        "3",
        "--size",
        "64",
        "--lengths",
        &lengths,
    ]);
    assert!(good.is_empty(), "--lengths {lengths}: {good:?}");
    // Every cascade of the refitted tiles carries a real share of the height or the slope.
    for (c, (height, slope)) in grid_shares(&mut ocean).into_iter().enumerate() {
        assert!(
            height > 0.01 || slope > 0.05,
            "cascade {c}: {height} {slope}"
        );
    }
    // The preset's own sea fits its tiles.
    let (storm, _) = warnings_for(&["--preset", "storm", "--size", "64"]);
    assert!(storm.is_empty(), "{storm:?}");
}

#[test]
fn no_preset_warns_at_the_sizes_it_is_made_for() {
    for preset in ocean_fft::SeaState::ALL {
        for size in ["64", "256"] {
            let (found, _) = warnings_for(&["--preset", preset.name(), "--size", size]);
            assert!(found.is_empty(), "{} at {size}²: {found:?}", preset.name());
        }
    }
}

#[test]
fn tiles_too_small_for_the_sea_warn_with_what_they_miss() {
    // The swell (peak wavelength 225 m) on tiles of 100 m and less.
    let args = [
        "--preset",
        "swell",
        "--size",
        "64",
        "--lengths",
        "100,23,5.1",
    ];
    let (bad, ocean) = warnings_for(&args);
    assert_eq!(bad.len(), 1, "{bad:?}");
    assert!(
        bad[0]
            .message
            .contains("waves longer than the largest tile (100 m) are missing"),
        "{}",
        bad[0]
    );
    // The grid holds well under 81 % of the spectrum's variance (H_s² ratio).
    let hs = ocean.spectrum().significant_wave_height();
    let held = ocean.diagnostics().expected_variance() / f64::from(hs / 4.0).powi(2);
    assert!(held < 0.5, "{held}");
    let lengths = suggested(&bad[0], "--lengths").to_string();
    let mut fixed = args[..4].to_vec();
    fixed.extend(["--lengths", &lengths]);
    let (good, ocean) = warnings_for(&fixed);
    assert!(good.is_empty(), "{good:?}");
    let held = ocean.diagnostics().expected_variance() / f64::from(hs / 4.0).powi(2);
    assert!(held > 0.9, "{held}");
}

#[test]
fn info_and_bake_print_the_warnings_on_stderr_before_the_bake() {
    let (code, stderr) = binary(&["info", "--preset", "storm", "--size", "16", "--loop", "8"]);
    assert_eq!(code, 0);
    assert!(stderr.contains("warning: --loop 8 "), "{stderr}");
    assert!(stderr.contains("use --lengths "), "{stderr}");

    let dir = scratch("stderr");
    let o = dir.to_str().unwrap();
    let (code, stderr) = binary(&[
        "bake", "--preset", "storm", "--size", "32", "--fps", "10", "--loop", "8", "--frames", "0",
        "--out", o,
    ]);
    assert_eq!(code, 0, "{stderr}");
    let warning = stderr.find("warning: --loop 8 ").expect(&stderr);
    let announced = stderr.find("bake: 3 files").expect(&stderr);
    let summary = stderr.find("files written").expect(&stderr);
    assert!(warning < announced && announced < summary, "{stderr}");
    // The good case says nothing of the kind.
    let (code, stderr) = binary(&[
        "bake",
        "--preset",
        "storm",
        "--size",
        "32",
        "--fps",
        "10",
        "--frames",
        "0",
        "--out",
        o,
        "--overwrite",
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(!stderr.contains("warning"), "{stderr}");
    std::fs::remove_dir_all(dir).unwrap();
}

/// Notes and written files, in the order the bake reports them.
#[derive(Default)]
struct Recorder(Vec<String>);

impl Progress for Recorder {
    fn note(&mut self, text: &str) {
        self.0.push(format!("note {text}"));
    }
    fn start(&mut self, files: u64) {
        self.0.push(format!("start {files}"));
    }
    fn written(&mut self, path: &Path) {
        self.0.push(format!("written {}", path.display()));
    }
}

/// "about 12.3 KiB" → bytes.
fn parse_bytes(text: &str) -> f64 {
    let mut words = text.split_whitespace();
    let value: f64 = words.next().unwrap().parse().unwrap();
    let unit = match words.next().unwrap().trim_end_matches([')', ',']) {
        "bytes" => 1.0,
        "KiB" => 1024.0,
        "MiB" => 1024.0 * 1024.0,
        other => panic!("unit {other}"),
    };
    value * unit
}

#[test]
fn the_disk_size_is_announced_before_any_file_and_bounds_what_is_written() {
    for format in ["exr", "png"] {
        let dir = scratch(&format!("disk-{format}"));
        let o = dir.to_str().unwrap();
        let args = bake_args(&[
            "--preset", "storm", "--size", "32", "--fps", "10", "--frames", "0-1", "--format",
            format, "--out", o,
        ]);
        let mut recorder = Recorder::default();
        let report: Report = bake(&args, &mut recorder).unwrap();
        let events = recorder.0;
        let files = if format == "exr" { 6 } else { 12 };
        let note = events
            .iter()
            .position(|e| e.starts_with(&format!("note bake: {files} files (2 frames × 3")))
            .unwrap_or_else(|| panic!("{events:?}"));
        let first_file = events
            .iter()
            .position(|e| e.starts_with("written"))
            .unwrap();
        assert!(note < first_file, "{events:?}");
        // What the frames take on disk, measured here (the sidecar is not counted).
        let on_disk: u64 = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap())
            .filter(|e| !e.file_name().to_string_lossy().ends_with(".json"))
            .map(|e| e.metadata().unwrap().len())
            .sum();
        assert_eq!(on_disk, report.bytes);
        let text = &events[note];
        let about = parse_bytes(text.split("about ").nth(1).unwrap());
        let most = parse_bytes(text.split("at most ").nth(1).unwrap());
        assert!(
            (on_disk as f64) <= most,
            "{format}: {on_disk} bytes, at most {most}"
        );
        // The estimate is an estimate: within a quarter of the truth for these frames.
        let ratio = on_disk as f64 / about;
        assert!(
            (0.75..1.25).contains(&ratio),
            "{format}: {on_disk} vs {about}"
        );
        std::fs::remove_dir_all(dir).unwrap();
    }
}

#[test]
fn exit_code_5_names_the_parameters_that_differ() {
    let dir = scratch("conflict");
    let o = dir.to_str().unwrap();
    let sea = [
        "--preset", "storm", "--size", "16", "--fps", "10", "--frames", "0",
    ];
    let with = |extra: &[&str]| {
        let mut args = vec!["bake"];
        args.extend_from_slice(&sea);
        args.extend_from_slice(extra);
        args.extend(["--out", o]);
        binary(&args)
    };
    assert_eq!(with(&[]).0, 0);
    // The storm preset's lengths are fitted to its sea (`SeaState::build`), written as the
    // sidecar writes f32s: their shortest digits.
    let storm = ocean_fft::SeaState::Storm.build().1.lengths;
    let lengths = format!(
        "--lengths (config.lengths is {} there, [4000.0,920.0] here)",
        serde_json::to_string(&storm).unwrap()
    );
    let cases: [(&[&str], &[&str]); 5] = [
        (
            &["--seed", "7"],
            &["--seed (config.seed is 0 there, 7 here)"],
        ),
        (
            &["--wind", "20"],
            &["--wind (spectrum.wind_speed is 26.0 there, 20.0 here)"],
        ),
        (
            &["--format", "png"],
            &["--format (files.encoding.format is \"OpenEXR\" there, \"PNG\" here)"],
        ),
        (
            &["--choppiness", "1", "--loop", "2"],
            &[
                "--choppiness (config.choppiness is 1.2 there, 1.0 here)",
                "--loop (config.repeat_period is null there, 2.0 here)",
            ],
        ),
        (&["--lengths", "4000,920"], &[&lengths]),
    ];
    for (extra, mentions) in cases {
        let (code, stderr) = with(extra);
        assert_eq!(code, 5, "{extra:?}: {stderr}");
        for mention in mentions {
            assert!(stderr.contains(mention), "{extra:?}: {stderr}");
        }
        // What follows from the parameter is not listed as a cause of its own.
        assert!(!stderr.contains("significant_wave_height"), "{stderr}");
        assert!(!stderr.contains("the spectrum (--preset"), "{stderr}");
    }
    // Through the library call too: the kind and the code.
    let error = bake(
        &bake_args(&[&sea[..], &["--seed", "3", "--out", o]].concat()),
        &mut ocean_fft_cli::bake::Silent,
    )
    .unwrap_err();
    assert_eq!((error.kind, error.kind.exit_code()), (Kind::Conflict, 5));
    assert!(error.message.contains("--seed"), "{}", error.message);
    std::fs::remove_dir_all(dir).unwrap();
}

/// The help text of `bake`'s option `--long`.
fn help_of(long: &str) -> String {
    let mut cli = Cli::command();
    let bake = cli.find_subcommand_mut("bake").unwrap();
    let help = bake
        .get_arguments()
        .find(|a| a.get_long() == Some(long))
        .unwrap_or_else(|| panic!("no --{long}"))
        .get_help()
        .unwrap()
        .to_string();
    help
}

#[test]
fn help_texts_state_the_ranges_the_errors_state_and_the_library_accepts() {
    // The ranges, written here from the library's constants (and the tool's own ones).
    let size = format!("{} to {}", CascadeConfig::MIN_SIZE, CascadeConfig::MAX_SIZE);
    let period = format!(
        "{} to {}",
        CascadeConfig::MIN_REPEAT_PERIOD,
        CascadeConfig::MAX_REPEAT_PERIOD
    );
    let length = format!(
        "{} to {}",
        CascadeConfig::MIN_LENGTH,
        CascadeConfig::MAX_LENGTH
    );
    let fps = "0.1 to 1000".to_string();
    let tolerance = "0.000001 to 0.1".to_string();
    let encoders = "1 to 256".to_string();
    assert_eq!(size, "4 to 4096");

    // The library accepts the ends of the size range and refuses what lies beyond.
    let valid = |n: usize| {
        CascadeConfig {
            size: n,
            ..CascadeConfig::default()
        }
        .validate()
        .is_ok()
    };
    assert!(valid(CascadeConfig::MIN_SIZE) && valid(CascadeConfig::MAX_SIZE));
    assert!(!valid(CascadeConfig::MIN_SIZE - 2) && !valid(CascadeConfig::MAX_SIZE + 2));
    assert!(!valid(CascadeConfig::MIN_SIZE + 1));

    // option, range, accepted values, refused values (each with a tiny sea).
    let cases: [(&str, &String, &[&str], &[&str]); 5] = [
        ("size", &size, &["4", "4096"], &["2", "5", "4098"]),
        ("fps", &fps, &["0.1", "1000"], &["0.05", "1001"]),
        ("loop", &period, &["0.01", "1000000"], &["0.005", "2000000"]),
        (
            "foam-tolerance",
            &tolerance,
            &["1e-6", "0.1"],
            &["1e-7", "0.2"],
        ),
        (
            "lengths",
            &length,
            &["10000000", "0.02,0.01"],
            &["20000000", "0.005", "1,2"],
        ),
    ];
    for (option, range, accepted, refused) in cases {
        let help = help_of(option);
        assert!(help.contains(range.as_str()), "--{option} help: {help}");
        let flag = format!("--{option}");
        // One cascade, so that 4096² stays in the memory limit; 100 fps, so that 0.01 s is a
        // whole frame.
        let base = |value: &str| {
            let mut args = vec!["--preset", "calm", "--fps", "100", &flag, value];
            if option != "lengths" {
                args.extend(["--lengths", "60"]);
            }
            if option == "fps" {
                args.drain(2..4);
            }
            args.iter().map(|s| s.to_string()).collect::<Vec<_>>()
        };
        for value in accepted {
            let args = base(value);
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            assert!(
                setup::build(&sea_args(&args)).is_ok(),
                "{flag} {value} refused"
            );
        }
        for value in refused {
            let args = base(value);
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            let error = setup::build(&sea_args(&args)).unwrap_err();
            assert_eq!(error.kind, Kind::Usage);
            assert!(
                error.message.starts_with(&format!("{flag} "))
                    && error.message.contains(range.as_str()),
                "{flag} {value}: {}",
                error.message
            );
        }
    }
    // --encoders is checked by the bake, before it writes anything.
    assert!(help_of("encoders").contains(&encoders));
    let dir = scratch("encoders");
    for value in ["0", "257"] {
        let args = bake_args(&[
            "--preset",
            "calm",
            "--size",
            "16",
            "--frames",
            "0",
            "--encoders",
            value,
            "--out",
            dir.to_str().unwrap(),
        ]);
        let error = bake(&args, &mut ocean_fft_cli::bake::Silent).unwrap_err();
        assert!(
            error.message.starts_with(&format!("--encoders {value}: "))
                && error.message.contains(&encoders),
            "{}",
            error.message
        );
    }
    std::fs::remove_dir_all(dir).unwrap();

    // The library takes what --lengths accepts: one tile of the largest side.
    let config = OceanConfig {
        lengths: vec![CascadeConfig::MAX_LENGTH],
        size: 16,
        ..OceanConfig::default()
    };
    assert!(config.validate().is_ok());
}
