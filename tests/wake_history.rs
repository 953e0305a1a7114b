//! The wake window's history: a snapshot brings back its waves, foam trail, place and hulls
//! bit for bit (and steps on identically), and a pre-roll spins a boat's wake up as if the
//! boat had sailed there.

use ocean_fft::{Error, Hull, OceanConfig, OceanState, Spectrum, WakeConfig};

fn config() -> OceanConfig {
    OceanConfig {
        size: 32,
        wakes: Some(WakeConfig {
            size: 64,
            spacing: 1.0,
            substep: 0.05,
            ..WakeConfig::default()
        }),
        ..OceanConfig::default()
    }
}

fn spectrum() -> Spectrum {
    Spectrum::jonswap(5.0, 10_000.0).unwrap()
}

fn boat() -> Hull {
    Hull {
        position: [-10.0, 2.0],
        velocity: [3.0, 0.4],
        length: 8.0,
        beam: 3.0,
        draft: 0.6,
        ..Hull::default()
    }
}

/// The wake's height, slope and foam buffers, its origin and heights at a few points.
type Seen = (Vec<f32>, Vec<[f32; 2]>, Vec<f32>, [f64; 2], Vec<f32>);

/// The wake's buffers and a few queries, everything a game reads of the wake.
fn seen(ocean: &OceanState) -> Seen {
    let wakes = ocean.wakes().unwrap();
    let points: Vec<[f64; 2]> = (0..60)
        .map(|i| [f64::from(i) - 30.0, f64::from(i % 5) * 2.5 - 5.0])
        .collect();
    let mut heights = vec![0.0; points.len()];
    ocean.water().heights_at(&points, &mut heights).unwrap();
    (
        wakes.height().to_vec(),
        wakes.slope().to_vec(),
        wakes.foam().to_vec(),
        wakes.origin(),
        heights,
    )
}

#[test]
fn a_snapshot_brings_the_wake_back_and_it_steps_on_identically() {
    let mut ocean = OceanState::new(spectrum(), config()).unwrap();
    ocean.set_hulls(&[boat()]).unwrap();
    ocean.step_to(2.0).unwrap();
    ocean.set_wake_centre(4.0, 1.0).unwrap();
    let saved = ocean.snapshot();
    let at_snapshot = seen(&ocean);
    assert!(
        at_snapshot.0.iter().any(|&h| h.abs() > 0.01),
        "a wake to save"
    );
    // On: the hull turns and the window moves, then the reference future.
    let turned = Hull {
        velocity: [0.0, 3.0],
        ..boat()
    };
    ocean.set_hulls(&[turned]).unwrap();
    ocean.set_wake_centre(-6.0, 9.0).unwrap();
    ocean.step_to(3.0).unwrap();
    ocean.set_hulls(&[boat()]).unwrap();
    ocean.restore(&saved).unwrap();
    assert_eq!(seen(&ocean), at_snapshot, "restored in the same ocean");
    ocean.step_to(3.5).unwrap();
    let future = seen(&ocean);

    // Another ocean with another history, restored from the same snapshot.
    let mut other = OceanState::new(spectrum(), config()).unwrap();
    other.set_hulls(&[turned, boat()]).unwrap();
    other.step_to(1.3).unwrap();
    other.restore(&saved).unwrap();
    assert_eq!(seen(&other), at_snapshot, "restored in another ocean");
    other.step_to(3.5).unwrap();
    assert_eq!(seen(&other), future, "and stepped on");

    // `capture` into the used snapshot: the same snapshot again.
    let mut reused = other.snapshot();
    reused.capture(&ocean);
    assert_eq!(reused, ocean.snapshot());
}

/// A restore refused because only one of the snapshot and the ocean has a wake window.
fn assert_refused(error: &Error) {
    let named = matches!(error, Error::NotApplicable { name, .. } if *name == "snapshot.wake");
    assert!(named, "{error:?}");
}

#[test]
fn snapshots_of_oceans_with_and_without_wakes_do_not_mix() {
    let plain = OceanConfig {
        wakes: None,
        ..config()
    };
    let without = OceanState::new(spectrum(), plain.clone())
        .unwrap()
        .snapshot();
    let mut ocean = OceanState::new(spectrum(), config()).unwrap();
    ocean.set_hulls(&[boat()]).unwrap();
    ocean.step_to(1.0).unwrap();
    let before = seen(&ocean);
    let error = ocean.restore(&without).unwrap_err();
    assert_refused(&error);
    assert_eq!(seen(&ocean), before, "a refused restore changes nothing");
    assert_eq!(ocean.time(), 1.0);

    let with = ocean.snapshot();
    let mut plain_ocean = OceanState::new(spectrum(), plain).unwrap();
    let error = plain_ocean.restore(&with).unwrap_err();
    assert_refused(&error);

    // A window of another size.
    let larger = OceanConfig {
        wakes: Some(WakeConfig {
            size: 128,
            ..config().wakes.unwrap()
        }),
        ..config()
    };
    let mut other = OceanState::new(spectrum(), larger).unwrap();
    let error = other.restore(&with).unwrap_err();
    assert!(
        matches!(
            error,
            Error::LengthMismatch {
                name: "snapshot.wake.eta",
                ..
            }
        ),
        "{error:?}"
    );
}

#[test]
fn a_pre_roll_spins_the_wake_up_as_if_the_boat_had_sailed_there() {
    let (end, seconds, dt) = (40.0, 12.0, 0.05);
    // Rolled: the boat placed at its end position, the last 12 s spun up.
    let mut rolled = OceanState::new(spectrum(), config()).unwrap();
    rolled.step(3.3).unwrap(); // a history the roll must forget
    rolled.set_time(end).unwrap();
    rolled.set_hulls(&[boat()]).unwrap();
    rolled.pre_roll(seconds, dt).unwrap();
    assert_eq!(rolled.time(), end);

    // Sailed: the boat set 12 s earlier, 36 m back along its track, and stepped there.
    let mut sailed = OceanState::new(spectrum(), config()).unwrap();
    sailed.set_time(end - seconds).unwrap();
    let [vx, vz] = boat().velocity;
    let start = Hull {
        position: [
            boat().position[0] - f64::from(vx) * seconds,
            boat().position[1] - f64::from(vz) * seconds,
        ],
        ..boat()
    };
    sailed.set_hulls(&[start]).unwrap();
    for k in 1..=240 {
        sailed.step_to(end - seconds + f64::from(k) * dt).unwrap();
    }
    let (a, b) = (seen(&rolled), seen(&sailed));
    let largest = b.0.iter().fold(0.0f32, |m, &h| m.max(h.abs()));
    assert!(largest > 0.05, "a wake behind the boat: {largest} m");
    // The same waves but for rounding: the hull's centre is extrapolated from another
    // starting point (f64), which can move a cell's pressure by an f32 ulp or so; 1e-4 of the
    // wake's largest height is far above that and far below any wave the roll could miss.
    for (name, x, y) in [("height", &a.0, &b.0), ("foam", &a.2, &b.2)] {
        let worst = x
            .iter()
            .zip(y)
            .fold(0.0f32, |m, (p, q)| m.max((p - q).abs()));
        assert!(worst <= 1e-4 * largest.max(1.0), "{name}: {worst}");
    }
    let foam: f32 = a.2.iter().sum();
    assert!(foam > 1.0, "a foam trail: {foam} cells' worth");

    // Another history, the same roll: the same bits.
    let mut again = OceanState::new(spectrum(), config()).unwrap();
    again.set_hulls(&[boat(), start]).unwrap();
    again.step(7.0).unwrap();
    again.set_time(end).unwrap();
    again.set_hulls(&[boat()]).unwrap();
    again.pre_roll(seconds, dt).unwrap();
    assert_eq!(seen(&again), a);
}
