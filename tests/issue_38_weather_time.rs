//! Issue 38: a change of weather is a function of simulated time. The same calls at the same
//! times give the same cascade buffers, bit for bit, whatever steps lie between them: 30, 60
//! and 144 fps, one step across the whole change, `set_time` into it; and once the change is
//! over, those of an ocean built with the new spectrum.

use ocean_fft::{OceanConfig, OceanState, Spectrum};

/// Every cascade buffer, amplitude and statistic of `ocean`, and its foam calibration and
/// change weight, as bits, each under its name.
fn fingerprint(ocean: &OceanState) -> Vec<(String, Vec<u64>)> {
    let bits = |v: &[f32]| v.iter().map(|x| u64::from(x.to_bits())).collect::<Vec<_>>();
    let mut all = Vec::new();
    for (c, cascade) in ocean.cascades().iter().enumerate() {
        let h0: Vec<f32> = cascade.h0().iter().flat_map(|h| [h.re, h.im]).collect();
        let flat2 = |v: &[[f32; 2]]| bits(&v.iter().flatten().copied().collect::<Vec<_>>());
        let flat3 = |v: &[[f32; 3]]| bits(&v.iter().flatten().copied().collect::<Vec<_>>());
        let slope = cascade.subgrid_slope_variance();
        all.push((format!("cascade {c} h0"), bits(&h0)));
        all.push((format!("cascade {c} height"), bits(cascade.height())));
        all.push((
            format!("cascade {c} displacement"),
            flat2(cascade.displacement()),
        ));
        all.push((format!("cascade {c} slope"), flat2(cascade.slope())));
        all.push((format!("cascade {c} normal"), flat3(cascade.normal())));
        all.push((format!("cascade {c} jacobian"), bits(cascade.jacobian())));
        all.push((
            format!("cascade {c} statistics"),
            vec![
                cascade.expected_variance().to_bits(),
                u64::from(cascade.mean_level_offset().to_bits()),
                u64::from(slope.along.to_bits()),
                u64::from(slope.across.to_bits()),
            ],
        ));
    }
    let calibration = ocean.foam_view().calibration();
    all.push((
        "foam calibration".into(),
        bits(&[
            calibration.wind_speed,
            calibration.target,
            calibration.threshold,
            calibration.compression_std,
            calibration.breaking_fraction,
            calibration.episode_rate,
            calibration.predicted,
        ]),
    ));
    all.push((
        "time and weight".into(),
        vec![
            ocean.time().to_bits(),
            ocean
                .diagnostics()
                .transition_progress()
                .map_or(u64::MAX, f64::to_bits),
        ],
    ));
    all
}

/// `a` against `b` field by field, naming the first differing index of the first field that
/// differs.
fn assert_same(a: &[(String, Vec<u64>)], b: &[(String, Vec<u64>)], what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: field count");
    for ((name, x), (_, y)) in a.iter().zip(b) {
        assert_eq!(x.len(), y.len(), "{what}: {name} length");
        if let Some(i) = (0..x.len()).find(|&i| x[i] != y[i]) {
            let differing = (0..x.len()).filter(|&i| x[i] != y[i]).count();
            panic!(
                "{what}: {name} differs first at {i} ({:#x} against {:#x}), {differing} of {} differ",
                x[i],
                y[i],
                x.len()
            );
        }
    }
}

/// The seas: the default ocean's 6 m/s breeze turning into a 15 m/s wind.
fn seas() -> (Spectrum, Spectrum) {
    (
        Spectrum::jonswap(6.0, 100_000.0).unwrap(),
        Spectrum::jonswap(15.0, 100_000.0).unwrap(),
    )
}

/// When the change is called, how long it lasts, and when the seas are compared: just after
/// the blend's start, half way, after its end, and well after.
const CALL: f64 = 2.0;
const DURATION: f64 = 1.0;
const CHECKS: [f64; 4] = [2.5, 3.0, 4.0, 6.0];

/// The default ocean stepped with `step_to(i / fps)` up to the last check, the change called
/// at `CALL`: the fingerprints at the checks.
fn at_fps(fps: u32) -> Vec<Vec<(String, Vec<u64>)>> {
    let (calm, wind) = seas();
    let mut ocean = OceanState::new(calm, OceanConfig::default()).unwrap();
    let mut prints = Vec::new();
    let last = CHECKS[CHECKS.len() - 1];
    for i in 1.. {
        let t = f64::from(i) / f64::from(fps);
        if t > last {
            break;
        }
        ocean.step_to(t).unwrap();
        if t == CALL {
            ocean.set_spectrum(wind.clone(), DURATION).unwrap();
        }
        if CHECKS.contains(&t) {
            prints.push(fingerprint(&ocean));
        }
    }
    assert_eq!(prints.len(), CHECKS.len(), "{fps} fps: every check reached");
    prints
}

/// The table: 30, 60 and 144 fps, and one `step_to` from the call to each check,
/// give the same bits at every check; from the end of the change on, those of an ocean
/// built with the new spectrum. The old code began the blend at the step that finished
/// drawing the new amplitudes, a fixed number of steps after the call: at 2.5 s the 144 fps
/// ocean was blending while the 30 fps one still showed the old sea.
#[test]
fn the_sea_is_a_function_of_time_whatever_the_frame_rate() {
    let reference = at_fps(60);
    for fps in [30, 144] {
        for (k, print) in at_fps(fps).iter().enumerate() {
            assert_same(
                print,
                &reference[k],
                &format!("{fps} fps against 60 fps at {} s", CHECKS[k]),
            );
        }
    }
    let (calm, wind) = seas();
    for (k, &t) in CHECKS.iter().enumerate() {
        // One step from the call to the check.
        let mut ocean = OceanState::new(calm.clone(), OceanConfig::default()).unwrap();
        ocean.step_to(CALL).unwrap();
        ocean.set_spectrum(wind.clone(), DURATION).unwrap();
        ocean.step_to(t).unwrap();
        assert_same(
            &fingerprint(&ocean),
            &reference[k],
            &format!("one step to {t} s against 60 fps"),
        );
    }
    // After the change: the new sea itself.
    for (k, &t) in CHECKS.iter().enumerate() {
        if t < CALL + ocean_fft::limits::TRANSITION_LAG + DURATION {
            continue;
        }
        let mut fresh = OceanState::new(wind.clone(), OceanConfig::default()).unwrap();
        fresh.set_time(t).unwrap();
        let (mut print, mut expected) = (reference[k].clone(), fingerprint(&fresh));
        // The weight is `None` for both, the times equal: compared above.
        print.retain(|(name, _)| name != "time and weight");
        expected.retain(|(name, _)| name != "time and weight");
        assert_same(
            &print,
            &expected,
            &format!("at {t} s against a fresh ocean"),
        );
    }
}

/// `set_time` into the middle of a change, back before its blend's start, and into it again
/// shows at each time the sea the 60 fps ocean shows then; stepping on at another rate from
/// there too.
#[test]
fn set_time_into_a_change_shows_the_sea_of_that_time() {
    let (calm, wind) = seas();
    let config = OceanConfig::default();
    // The 60 fps ocean's fingerprints at the times below.
    let times = [2.25, 2.75, 3.0, 3.25, 4.0];
    let mut stepped = OceanState::new(calm.clone(), config.clone()).unwrap();
    let mut expected = Vec::new();
    for i in 1..=240 {
        let t = f64::from(i) / 60.0;
        stepped.step_to(t).unwrap();
        if t == CALL {
            stepped.set_spectrum(wind.clone(), DURATION).unwrap();
        }
        if times.contains(&t) {
            expected.push(fingerprint(&stepped));
        }
    }
    assert_eq!(expected.len(), times.len());
    let print_at = |t: f64| expected[times.iter().position(|&x| x == t).unwrap()].clone();

    let mut ocean = OceanState::new(calm, config).unwrap();
    ocean.step_to(CALL).unwrap();
    ocean.set_spectrum(wind, DURATION).unwrap();
    for t in [2.75, 2.25, 3.0, 2.25, 2.75] {
        ocean.set_time(t).unwrap();
        assert_same(
            &fingerprint(&ocean),
            &print_at(t),
            &format!("set_time({t}) against 60 fps"),
        );
    }
    // From 2.75 s on at 144 fps.
    for i in 397..=576 {
        let t = f64::from(i) / 144.0;
        ocean.step_to(t).unwrap();
        if times.contains(&t) {
            assert_same(
                &fingerprint(&ocean),
                &print_at(t),
                &format!("144 fps after set_time, at {t} s, against 60 fps"),
            );
        }
    }
    assert_eq!(ocean.time(), 4.0);
    assert_eq!(
        ocean.diagnostics().transition_progress(),
        None,
        "over at 4 s"
    );
}

/// A slider dragged for 300 frames at 60 fps (a new spectrum over 0.5 s every frame), then
/// one step a second after the last: the change is over and the ocean is the last
/// spectrum's, bit for bit. The old code restarted the preparation at every call and did one
/// piece of it in the last step, so the last spectrum's blend had not even begun.
#[test]
fn a_dragged_slider_ends_on_the_last_spectrum() {
    let config = OceanConfig::default();
    let mut ocean =
        OceanState::new(Spectrum::jonswap(6.0, 100_000.0).unwrap(), config.clone()).unwrap();
    let mut last = None;
    for i in 1..=300 {
        let spectrum = Spectrum::jonswap((6.0 + 0.03 * f64::from(i)) as f32, 100_000.0).unwrap();
        ocean.set_spectrum(spectrum.clone(), 0.5).unwrap();
        ocean.step_to(f64::from(i) / 60.0).unwrap();
        last = Some(spectrum);
    }
    let last = last.unwrap();
    // The last call was at 299/60 s, before the last step.
    ocean.step_to(299.0 / 60.0 + 1.0).unwrap();
    assert_eq!(
        ocean.diagnostics().transition_progress(),
        None,
        "over a second after"
    );
    let mut fresh = OceanState::new(last, config).unwrap();
    fresh.set_time(ocean.time()).unwrap();
    assert_same(
        &fingerprint(&ocean),
        &fingerprint(&fresh),
        "a second after the slider, against a fresh ocean",
    );
}

/// A pre-roll in the middle of a change goes back before the call and forward again: the
/// cascades come back to the sea of the time, the change goes on as the 60 fps ocean's.
#[test]
fn a_pre_roll_inside_a_change_keeps_the_sea_of_the_time() {
    let (calm, wind) = seas();
    let config = OceanConfig::default();
    let run = |pre_roll: bool| {
        let mut ocean = OceanState::new(calm.clone(), config.clone()).unwrap();
        let mut prints = Vec::new();
        for i in 1..=240 {
            let t = f64::from(i) / 60.0;
            ocean.step_to(t).unwrap();
            if t == CALL {
                ocean.set_spectrum(wind.clone(), DURATION).unwrap();
            }
            if pre_roll && t == 2.75 {
                ocean.pre_roll(1.5, 0.1).unwrap();
            }
            if CHECKS.contains(&t) || t == 2.75 {
                prints.push((t, fingerprint(&ocean)));
            }
        }
        prints
    };
    let (plain, rolled) = (run(false), run(true));
    assert_eq!(plain.len(), 4);
    for ((t, a), (_, b)) in plain.iter().zip(&rolled) {
        assert_same(b, a, &format!("after a pre-roll at 2.75 s, at {t} s"));
    }
}
