//! The viewer's flags: defaults, ranges, errors and the options they make.
use super::*;

fn parse(args: &[&str]) -> Result<Options, clap::Error> {
    Options::try_parse_from(std::iter::once("ocean-fft-viewer").chain(args.iter().copied()))
}

/// The error's text, which must name `flag`.
fn error(args: &[&str], flag: &str) -> String {
    let text = parse(args).expect_err("a bad command line").to_string();
    assert!(text.contains(flag), "{args:?}: {text}");
    text
}

/// clap's checks of the definition (names, `requires`, defaults); they run where clap is
/// compiled with debug assertions (the dev and test profiles; in the headless profile add
/// `--config 'profile.headless.package.clap_builder.debug-assertions=true'`).
#[test]
fn the_definition_is_consistent() {
    Cli::command().debug_assert();
}

#[test]
fn defaults_are_the_documented_ones() {
    let o = parse(&[]).unwrap();
    let mut sea = SeaParams::preset("default").unwrap();
    // With boats (the default) the sea has a wake window.
    sea.wakes = true;
    assert_eq!(o.sea, sea);
    assert_eq!((o.boat_speed, o.follow), (0.0, false));
    assert_eq!((o.frames, o.screenshot), (None, None));
    assert_eq!((o.width, o.height), (1280, 720));
    let hs = o.sea.spectrum().unwrap().significant_wave_height();
    assert_eq!(o.camera, crate::default_eye(hs));
    assert_eq!((o.heading, o.pitch, o.fov), (20.0, -6.0, 50.0));
    assert_eq!(o.light, LightSettings::default());
    assert_eq!(o.render.tiling, RenderSettings::default().tiling);
    assert_eq!(
        o.render.tiling_scale,
        RenderSettings::default().tiling_scale
    );
    assert_eq!((o.time, o.pre_roll, o.time_scale), (60.0, 20.0, 1.0));
    assert_eq!(
        (o.msaa, o.anisotropy, o.mesh, o.threads),
        (None, None, 64, 2)
    );
    assert!(o.bodies && !o.hide_ui && o.vsync);
    assert_eq!(o.coast, None);
}

/// `--coast` picks the procedural coast and, without `--camera`, the eye of its view.
#[test]
fn the_coast_flag() {
    let o = parse(&["--coast", "island"]).unwrap();
    assert_eq!(o.coast, Some(CoastKind::Island));
    assert_eq!(o.camera, Vec3::from_array(CoastKind::Island.view().0));
    let o = parse(&["--coast", "breakwater", "--camera", "1,2,3"]).unwrap();
    assert_eq!(o.coast, Some(CoastKind::Breakwater));
    assert_eq!(o.camera, Vec3::new(1.0, 2.0, 3.0));
    assert_eq!(parse(&["--coast", "none"]).unwrap().coast, None);
    error(&["--coast", "reef"], "--coast");
}

#[test]
fn every_flag_sets_its_field() {
    let o = parse(&[
        "--preset",
        "calm",
        "--choppiness",
        "0.5",
        "--foam",
        "2",
        "--frames",
        "30",
        "--screenshot",
        "out/viewer.png",
        "--width",
        "640",
        "--height",
        "360",
        "--camera",
        "1, 2 ,3",
        "--heading",
        "45",
        "--pitch",
        "10",
        "--fov",
        "60",
        "--sun",
        "35,160",
        "--overcast",
        "0.5",
        "--exposure",
        "1.2",
        "--haze",
        "3000",
        "--time",
        "5",
        "--pre-roll",
        "0",
        "--time-scale",
        "2",
        "--tiling",
        "0.25",
        "--msaa",
        "1",
        "--anisotropy",
        "8",
        "--mesh",
        "32",
        "--threads",
        "4",
        "--no-bodies",
        "--coast",
        "breakwater",
        "--hide-ui",
        "--no-vsync",
    ])
    .unwrap();
    assert_eq!(o.coast, Some(CoastKind::Breakwater));
    let mut calm = SeaParams::preset("calm").unwrap();
    calm.choppiness = 0.5;
    calm.foam_coverage = 2.0;
    assert_eq!(o.sea, calm);
    assert_eq!(o.frames, Some(30));
    assert_eq!(o.screenshot, Some(PathBuf::from("out/viewer.png")));
    assert_eq!((o.width, o.height), (640, 360));
    assert_eq!(o.camera, Vec3::new(1.0, 2.0, 3.0));
    assert_eq!((o.heading, o.pitch, o.fov), (45.0, 10.0, 60.0));
    let light = LightSettings {
        elevation: 35.0,
        azimuth: 160.0,
        overcast: 0.5,
        exposure: 1.2,
        haze: 3000.0,
    };
    assert_eq!(o.light, light);
    assert_eq!((o.time, o.pre_roll, o.time_scale), (5.0, 0.0, 2.0));
    assert_eq!(o.render.tiling, 0.25);
    assert_eq!(
        (o.msaa, o.anisotropy, o.mesh, o.threads),
        (Some(1), Some(8), 32, 4)
    );
    assert!(!o.bodies && o.hide_ui && !o.vsync);
}

/// The boats' flags: a speed, the camera following them, and no wakes.
#[test]
fn the_boats_flags() {
    let o = parse(&["--boat-speed", "8", "--follow-boat"]).unwrap();
    assert_eq!((o.boat_speed, o.follow, o.sea.wakes), (8.0, true, true));
    assert!(!o.deck);
    assert!(parse(&["--on-deck"]).unwrap().deck);
    assert!(o.sea.config().wakes.is_some());
    let o = parse(&["--no-wakes"]).unwrap();
    assert!(!o.sea.wakes && o.sea.config().wakes.is_none());
    error(&["--boat-speed", "25"], "--boat-speed");
}

#[test]
fn negative_values_are_values() {
    let o = parse(&[
        "--pitch",
        "-8",
        "--heading",
        "-.5",
        "--camera",
        "-150,25,-400",
        "--sun",
        "-5,-30",
    ])
    .unwrap();
    assert_eq!((o.pitch, o.heading), (-8.0, -0.5));
    assert_eq!(o.camera, Vec3::new(-150.0, 25.0, -400.0));
    assert_eq!((o.light.elevation, o.light.azimuth), (-5.0, -30.0));
    // A negative value where only positive ones are valid is a range error, not an
    // unknown option.
    let text = error(&["--choppiness", "-1"], "--choppiness");
    assert!(text.contains("out of range"), "{text}");
}

#[test]
fn the_documented_command_lines_parse() {
    // .ci/run and CONTRIBUTING.md, viewer/README.md, scripts/viewer_gallery.sh's three.
    let shot = "--frames 2 --hide-ui --msaa 4 --anisotropy 1 --width 1280 --height 720 \
                --screenshot out/viewer_shot.png";
    for line in [
        "--frames 30 --screenshot out/viewer.png".to_string(),
        "--preset storm".to_string(),
        "--frames 60 --screenshot out/viewer.png".to_string(),
        format!(
            "{shot} --preset calm --camera 0,3,0 --heading 25 --pitch -4 --sun 6,30 \
             --exposure 0.9"
        ),
        format!("{shot} --preset fresh_breeze --camera 0,9,0 --heading 20 --pitch -7 --sun 35,160"),
        format!("{shot} --preset storm --camera 150,25,-400 --heading 100 --pitch -9"),
    ] {
        let args: Vec<&str> = line.split_whitespace().collect();
        if let Err(e) = parse(&args) {
            panic!("{line}: {e}");
        }
    }
}

#[test]
fn the_storm_is_overcast_unless_told() {
    assert_eq!(parse(&["--preset", "storm"]).unwrap().light.overcast, 0.85);
    let told = parse(&["--preset", "storm", "--overcast", "0.2"]).unwrap();
    assert_eq!(told.light.overcast, 0.2);
    assert_eq!(parse(&["--preset", "swell"]).unwrap().light.overcast, 0.0);
}

#[test]
fn the_last_of_a_repeated_flag_wins() {
    let o = parse(&["--width", "800", "--width", "900", "--hide-ui", "--hide-ui"]).unwrap();
    assert_eq!(o.width, 900);
    assert!(o.hide_ui);
}

#[test]
fn values_out_of_range_are_errors_naming_the_flag() {
    for (args, flag) in [
        (&["--choppiness", "6"][..], "--choppiness"),
        (&["--foam", "NaN"], "--foam"),
        (&["--frames", "0"], "--frames"),
        (&["--width", "15"], "--width"),
        (&["--height", "9000"], "--height"),
        (&["--camera", "0,inf,0"], "--camera"),
        (&["--camera", "0,1"], "--camera"),
        (&["--heading", "4000"], "--heading"),
        (&["--pitch", "-90"], "--pitch"),
        (&["--fov", "4"], "--fov"),
        (&["--sun", "-11,0"], "--sun"),
        (&["--sun", "14"], "--sun"),
        (&["--overcast", "1.5"], "--overcast"),
        (&["--exposure", "0"], "--exposure"),
        (&["--haze", "inf"], "--haze"),
        (&["--time", "-1"], "--time"),
        (&["--pre-roll", "601"], "--pre-roll"),
        (&["--time-scale", "x"], "--time-scale"),
        (&["--tiling", "2"], "--tiling"),
        (&["--msaa", "2"], "--msaa"),
        (&["--anisotropy", "17"], "--anisotropy"),
        (&["--mesh", "63"], "--mesh"),
        (&["--mesh", "6"], "--mesh"),
        (&["--threads", "0"], "--threads"),
    ] {
        let e = parse(args).expect_err("out of range");
        assert_eq!(e.kind(), ErrorKind::ValueValidation, "{args:?}: {e}");
        error(args, flag);
    }
}

#[test]
fn bad_command_lines_are_errors() {
    error(&["--frames"], "--frames");
    error(&["--bogus"], "--bogus");
    let text = error(&["--preset", "hurricane"], "--preset");
    assert!(text.contains("shallow_bay"), "the names are listed: {text}");
    // The screenshot is of the last of a fixed number of frames.
    error(&["--screenshot", "out.png"], "--frames");
    assert!(parse(&["--frames", "1", "--screenshot", "out.png"]).is_ok());
}

#[test]
fn help_lists_every_flag_with_its_default() {
    let e = parse(&["--help"]).expect_err("help is not a run");
    assert_eq!(e.kind(), ErrorKind::DisplayHelp);
    assert_eq!(parse(&["-h"]).unwrap_err().kind(), ErrorKind::DisplayHelp);
    let help = Cli::command().render_help().to_string();
    for flag in [
        "--preset",
        "--choppiness",
        "--foam",
        "--frames",
        "--screenshot",
        "--width",
        "--height",
        "--camera",
        "--heading",
        "--pitch",
        "--fov",
        "--sun",
        "--overcast",
        "--exposure",
        "--haze",
        "--time",
        "--pre-roll",
        "--time-scale",
        "--tiling",
        "--msaa",
        "--anisotropy",
        "--mesh",
        "--threads",
        "--no-bodies",
        "--coast",
        "--hide-ui",
        "--no-vsync",
    ] {
        assert!(help.contains(flag), "{flag} missing from\n{help}");
    }
    for default in [
        "[default: 14,30]",
        "[default: 0.8]",
        "[default: 6000]",
        "[default: -6]",
    ] {
        assert!(help.contains(default), "{default} missing from\n{help}");
    }
}
