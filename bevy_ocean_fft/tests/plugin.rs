//! The plugin's logic under `MinimalPlugins` (no window, no renderer): weather changes are
//! live transitions, grid changes rebuild, bodies float at their water line and follow the
//! waves, and the forces handed to a physics engine are Archimedes'. Every expectation is
//! computed independently of the plugin, from an `OceanState` the test builds itself.

use std::time::{Duration, Instant};

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_ocean_fft::ocean_fft::{OceanState, SeaState, GRAVITY};
use bevy_ocean_fft::prelude::*;
use bevy_ocean_fft::{
    BuoyancyPoint, OceanSim, OceanTexels, WakeInput, WakeWindow, SEA_WATER_DENSITY,
};

/// Frames of 1/60 s.
const DT: f64 = 1.0 / 60.0;

/// A preset on 64² grids (quick steps), changing over `transition` s.
fn settings(state: SeaState, transition: f64) -> OceanSettings {
    let mut settings = OceanSettings::preset(state);
    settings.config.size = 64;
    settings.transition_seconds = transition;
    settings
}

/// An app that simulates only, its virtual time advancing 1/60 s a frame.
fn app(settings: OceanSettings) -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, OceanPlugin::default()))
        .insert_resource(settings)
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
            DT,
        )));
    app
}

/// Runs frames until `done` (the ocean is built by a task on another thread: real time).
fn run_until(app: &mut App, what: &str, done: impl Fn(&World) -> bool) {
    let start = Instant::now();
    while !done(app.world()) {
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "timed out waiting for {what}"
        );
        app.update();
        std::thread::sleep(Duration::from_millis(1));
    }
}

fn status(app: &App) -> &OceanStatus {
    app.world().resource::<OceanStatus>()
}

/// Water heights the game saw through `Water` during a frame, and the sea time.
#[derive(Resource, Default)]
struct Probe {
    points: Vec<[f32; 2]>,
    /// (sea time, heights at `points`) every frame.
    seen: Vec<(f64, Vec<f32>)>,
}

fn probe(water: Water, mut probe: ResMut<Probe>) {
    let Some(time) = water.time() else {
        return;
    };
    let heights = probe
        .points
        .iter()
        .map(|&[x, z]| water.height(x, z).expect("the ocean answers"))
        .collect();
    probe.seen.push((time, heights));
}

/// A change of weather runs as the crate's live transition (progress from 0 to 1, no new
/// ocean), ends on exactly the sea a fresh ocean of the new spectrum has, and a change of
/// grids builds a new ocean while the old one runs on.
#[test]
fn a_change_of_weather_is_a_transition_and_a_new_grid_a_rebuild() {
    let mut app = app(settings(SeaState::ModerateBreeze, 3.0));
    app.insert_resource(Probe {
        points: vec![[0.0, 0.0], [13.7, -4.2], [-30.5, 22.25]],
        seen: Vec::new(),
    })
    .add_systems(Update, probe);
    run_until(&mut app, "the first ocean", |w| {
        w.resource::<OceanStatus>().ready
    });
    assert_eq!(status(&app).rebuilds, 1);
    assert_eq!(status(&app).transition_progress, None);

    app.world_mut()
        .resource_mut::<OceanSettings>()
        .set_weather(SeaState::FreshBreeze);
    let target = app.world().resource::<OceanSettings>().clone();
    let mut progress = Vec::new();
    let mut frames = 0;
    loop {
        app.update();
        frames += 1;
        let w = status(&app).transition_progress;
        if let Some(w) = w {
            progress.push(w);
        } else if !progress.is_empty() {
            break;
        }
        assert!(frames < 2000, "the change never ended");
    }
    // The change began (progress reported), moved through intermediate weights, never went
    // back, and took about its 3 s (plus the preparation steps before the blend starts).
    assert!(progress.len() > 150, "{} frames of change", progress.len());
    assert!(progress.iter().any(|&w| w > 0.2 && w < 0.8), "{progress:?}");
    assert!(progress.windows(2).all(|p| p[1] >= p[0]), "{progress:?}");
    assert_eq!(
        status(&app).rebuilds,
        1,
        "a weather change must not rebuild"
    );
    assert_eq!(status(&app).last_error, None);
    assert_eq!(status(&app).spectrum.as_ref(), Some(&target.spectrum));

    // Over: the plugin's water is, bit for bit, a fresh ocean of the new spectrum at the
    // same time (the crate's guarantee for a finished change; heights do not depend on the
    // foam's history).
    app.update();
    let probe = app.world().resource::<Probe>();
    let (time, seen) = probe.seen.last().expect("probed").clone();
    let mut fresh = OceanState::new(target.spectrum.clone(), target.config.clone()).unwrap();
    fresh.set_time(time).unwrap();
    for (&[x, z], height) in probe.points.iter().zip(seen) {
        let expected = fresh.water().height_at(f64::from(x), f64::from(z)).unwrap();
        assert_eq!(height, expected, "at ({x}, {z}), t = {time}");
    }

    // A new seed is a new grid: a new ocean, built while the old one runs on.
    app.world_mut().resource_mut::<OceanSettings>().config.seed = 7;
    run_until(&mut app, "the rebuild", |w| {
        let status = w.resource::<OceanStatus>();
        assert!(status.ready, "the old ocean runs during the rebuild");
        status.rebuilds == 2
    });
}

/// The heights the game saw in an app whose `OceanClock::Manual` runs at `fps` frames a
/// second for 4 s, the weather changing (over 1 s) in the frame after the clock read 1 s:
/// the plugin calls `set_spectrum` before it steps, so at sea time 1 s whatever the rate.
fn heights_at_fps(fps: u32, points: &[[f32; 2]]) -> (Vec<(f64, Vec<f32>)>, OceanSettings) {
    let mut app = app(settings(SeaState::ModerateBreeze, 1.0));
    app.insert_resource(OceanClock::Manual(0.0))
        .insert_resource(Probe {
            points: points.to_vec(),
            seen: Vec::new(),
        })
        .add_systems(Update, probe);
    run_until(&mut app, "the first ocean", |w| {
        w.resource::<OceanStatus>().ready
    });
    for i in 1..=4 * fps {
        if i == fps + 1 {
            app.world_mut()
                .resource_mut::<OceanSettings>()
                .set_weather(SeaState::FreshBreeze);
        }
        app.insert_resource(OceanClock::Manual(f64::from(i) / f64::from(fps)));
        app.update();
    }
    // The frame that collects the last step.
    app.update();
    assert_eq!(status(&app).last_error, None);
    assert_eq!(status(&app).transition_progress, None, "the change is over");
    let target = app.world().resource::<OceanSettings>().clone();
    assert_eq!(status(&app).spectrum.as_ref(), Some(&target.spectrum));
    let seen = app.world().resource::<Probe>().seen.clone();
    (seen, target)
}

/// Two games on a manual clock, at 30 and 144 fps, see the same heights at the same sea
/// times through a change of weather (the waves, changes of weather included, are a
/// function of the time), and at 4 s those of a fresh ocean of the new spectrum.
#[test]
fn a_change_of_weather_looks_the_same_at_any_frame_rate() {
    let points = [[0.0, 0.0], [13.7, -4.2], [-30.5, 22.25]];
    let (slow, target) = heights_at_fps(30, &points);
    let (fast, _) = heights_at_fps(144, &points);
    let mut common = 0;
    for (time, heights) in &slow {
        if let Some((_, other)) = fast.iter().find(|(t, _)| t == time) {
            assert_eq!(heights, other, "30 against 144 fps at t = {time}");
            common += 1;
        }
    }
    // Every sixth of a second from 1/6 s to 4 s, the change (1.45 s to 2.45 s) among them.
    assert!(common >= 20, "{common} common sea times");
    let (time, seen) = slow.last().expect("probed").clone();
    assert_eq!(time, 4.0);
    let mut fresh = OceanState::new(target.spectrum.clone(), target.config.clone()).unwrap();
    fresh.set_time(time).unwrap();
    for (&[x, z], height) in points.iter().zip(seen) {
        let expected = fresh.water().height_at(f64::from(x), f64::from(z)).unwrap();
        assert_eq!(height, expected, "at ({x}, {z}), t = {time}");
    }
}

/// The columns of a test body, as the plugin places them: world (x, z) of each.
fn columns(body: &Buoyancy, transform: &Transform) -> Vec<[f64; 2]> {
    body.points
        .iter()
        .map(|p| {
            let w = transform.transform_point(p.offset);
            [f64::from(w.x), f64::from(w.z)]
        })
        .collect()
}

/// Drops `body` on `sea` at (3, 2.5, −2) and, after 10 s of settling, records every frame
/// for 15 s its height and the mean water height under its columns, the latter from an ocean
/// the test builds itself.
fn float(sea: &OceanSettings, body: &Buoyancy) -> Vec<(f32, f32)> {
    let mut app = app(sea.clone());
    let entity = app
        .world_mut()
        .spawn((body.clone(), Transform::from_xyz(3.0, 2.5, -2.0)))
        .id();
    run_until(&mut app, "the first ocean", |w| {
        w.resource::<OceanStatus>().ready
    });
    let mut reference = OceanState::new(sea.spectrum.clone(), sea.config.clone()).unwrap();
    let mut samples = Vec::new();
    for frame in 0..1500 {
        app.update();
        if frame < 600 {
            continue;
        }
        let transform = *app.world().get::<Transform>(entity).unwrap();
        // The ocean the fixed updates of this frame used is the one collected at its start.
        reference.set_time(status(&app).time).unwrap();
        let points = columns(body, &transform);
        let mut heights = vec![0.0; points.len()];
        reference.water().heights_at(&points, &mut heights).unwrap();
        let water = heights.iter().sum::<f32>() / heights.len() as f32;
        samples.push((transform.translation.y, water));
    }
    // It stayed where it was put (kinematic mode moves y, pitch and roll only).
    let transform = app.world().get::<Transform>(entity).unwrap();
    assert_eq!(
        (transform.translation.x, transform.translation.z),
        (3.0, -2.0)
    );
    samples
}

/// A body dropped on the sea settles at its water line (on a calm sea, where its columns stay
/// in the water and the model is linear) and follows the waves (on a moderate sea): its
/// height against the mean water height under its columns, the latter from an independent
/// ocean, and the rest depth from Archimedes.
/// A storm on the calm preset's grids, which hold 8 % of it: `set_spectrum` would refuse it,
/// so the plugin builds a new ocean on grids fitted to the storm instead of reporting an
/// error.
#[test]
fn a_sea_the_grids_cannot_hold_rebuilds_on_fitted_grids() {
    let mut app = app(settings(SeaState::Calm, 1.0));
    run_until(&mut app, "the first ocean", |w| {
        w.resource::<OceanStatus>().ready
    });
    assert_eq!(status(&app).rebuilds, 1);
    app.world_mut()
        .resource_mut::<OceanSettings>()
        .set_weather(SeaState::Storm);
    let storm = app.world().resource::<OceanSettings>().clone();
    assert!(!storm.fits());
    assert!(storm.grids().fit(&storm.spectrum).unwrap().held >= 0.97);
    run_until(&mut app, "the storm's ocean", |w| {
        w.resource::<OceanStatus>().rebuilds == 2
    });
    assert_eq!(status(&app).last_error, None);
    assert_eq!(status(&app).spectrum.as_ref(), Some(&storm.spectrum));
}

#[test]
fn a_body_settles_at_its_water_line_and_follows_the_waves() {
    // A 2 × 2 × 2 m body of 1 t: draft m/(ρA) = 0.244 m, heave frequency √(ρgA/m) =
    // 6.3 rad/s, damping ratio 0.35.
    let body = Buoyancy::boat(2.0, 2.0, 2.0, 1000.0);
    let rest = body.rest_depth();
    assert!((rest - (1000.0 / (1025.0 * 4.0) - 1.0)).abs() < 1e-6);

    // Calm (H_s 0.17 m): the columns never leave the water or go under, so the push is linear
    // in the water height and its mean equals the weight when the mean acceleration vanishes:
    // mean offset = −rest depth. Over 15 s the mean acceleration is at most 2·v_max/T
    // (v_max < 0.3 m/s here: 0.4 % of g, 1 mm of draft); the drag's share, correlated with
    // the submersion, is of the order of the relative motion squared: 1 cm (4 % of the
    // draft) bounds both.
    let calm = float(&settings(SeaState::Calm, 10.0), &body);
    let n = calm.len() as f32;
    let mean_offset = calm.iter().map(|(y, h)| y - h).sum::<f32>() / n;
    assert!(
        (mean_offset + rest).abs() < 0.01,
        "calm: mean height above the water {mean_offset} m, expected {}",
        -rest
    );

    // Moderate breeze (H_s 1.2 m, peak 1.3 rad/s): the body follows the water under it. A
    // linear oscillator of natural frequency 6.3 rad/s and damping ratio 0.35 driven at the
    // peak answers within |1 − H| ≈ 0.15 of the drive; the shorter waves of the spectrum do
    // worse (and lift a column out of the water now and then, which sinks the body a little
    // deeper on average), so the bound on the rms error is 0.35 of the water's rms motion.
    let moderate = float(&settings(SeaState::ModerateBreeze, 10.0), &body);
    let n = moderate.len() as f32;
    let mean_water = moderate.iter().map(|(_, h)| h).sum::<f32>() / n;
    let mean_offset = moderate.iter().map(|(y, h)| y - h).sum::<f32>() / n;
    let heave = (moderate
        .iter()
        .map(|(_, h)| (h - mean_water).powi(2))
        .sum::<f32>()
        / n)
        .sqrt();
    let error = (moderate
        .iter()
        .map(|(y, h)| (y - h - mean_offset).powi(2))
        .sum::<f32>()
        / n)
        .sqrt();
    assert!(
        heave > 0.1,
        "the water under the body hardly moves: {heave} m"
    );
    assert!(
        error < 0.35 * heave,
        "rms error {error} m against the water's rms motion {heave} m"
    );
    eprintln!(
        "calm: offset {:.4} m (Archimedes {:.4}); moderate: offset {mean_offset:.4} m, \
         rms error {error:.3} m, water rms {heave:.3} m",
        calm.iter().map(|(y, h)| y - h).sum::<f32>() / calm.len() as f32,
        -rest
    );
}

/// With a `BuoyancyForce` the plugin does not move the body and writes Archimedes' force
/// and its torque: ρ·g·(submerged volume) up at each column, from the water heights an
/// independent ocean gives.
#[test]
fn forces_for_a_physics_engine_are_archimedes() {
    let sea = settings(SeaState::FreshBreeze, 10.0);
    let mut app = app(sea.clone());
    let body = Buoyancy {
        points: vec![
            BuoyancyPoint {
                offset: Vec3::new(-2.0, 0.0, 0.5),
                volume: 3.0,
                height: 1.5,
            },
            BuoyancyPoint {
                offset: Vec3::new(2.5, -0.2, -1.0),
                volume: 2.0,
                height: 1.0,
            },
        ],
        mass: 2000.0,
        inertia: Vec3::splat(1000.0),
        damping: 2.0,
        water_density: SEA_WATER_DENSITY,
    };
    let transform = Transform::from_xyz(10.0, 0.1, 5.0).with_rotation(Quat::from_rotation_y(0.4));
    let entity = app
        .world_mut()
        .spawn((body.clone(), transform, BuoyancyForce::default()))
        .id();
    run_until(&mut app, "the first ocean", |w| {
        w.resource::<OceanStatus>().ready
    });
    let mut reference = OceanState::new(sea.spectrum.clone(), sea.config.clone()).unwrap();
    let mut checked = 0;
    for _ in 0..120 {
        let before = app.world().get::<BuoyancyForce>(entity).copied();
        app.update();
        let force = *app.world().get::<BuoyancyForce>(entity).unwrap();
        // Only frames with a fixed update wrote a new force.
        if Some(force) == before || force == BuoyancyForce::default() {
            continue;
        }
        assert_eq!(*app.world().get::<Transform>(entity).unwrap(), transform);
        reference.set_time(status(&app).time).unwrap();
        let mut expected_force = Vec3::ZERO;
        let mut expected_torque = Vec3::ZERO;
        for point in &body.points {
            let p = transform.transform_point(point.offset);
            let h = reference
                .water()
                .height_at(f64::from(p.x), f64::from(p.z))
                .unwrap();
            let depth = (h - (p.y - 0.5 * point.height)).clamp(0.0, point.height);
            let up = Vec3::Y * SEA_WATER_DENSITY * GRAVITY * point.volume * depth / point.height;
            expected_force += up;
            expected_torque += (p - transform.translation).cross(up);
        }
        // The body does not move, so there is no drag; f32 sums of a few terms: 1e-4 relative.
        let scale = expected_force.length().max(1.0);
        assert!(
            (force.force - expected_force).length() < 1e-4 * scale,
            "{force:?} against {expected_force}"
        );
        assert!(
            (force.torque - expected_torque).length() < 1e-4 * scale * 4.0,
            "{force:?} against {expected_torque}"
        );
        checked += 1;
    }
    assert!(checked > 50, "only {checked} fixed updates checked");
}

/// What the game saw of the wake during a frame (the ocean is in its step task between
/// frames).
#[derive(Resource, Default)]
struct WakeSeen {
    /// The wake's height under the body, from the ocean's own window.
    dip: Option<f32>,
    /// The world query's height there, and the same ocean's without the wake.
    height: Option<(f32, f32)>,
}

fn see_wake(
    sim: Res<OceanSim>,
    water: Water,
    boats: Query<&Transform, With<Wake>>,
    mut seen: ResMut<WakeSeen>,
) {
    let (Some(ocean), Ok(boat)) = (sim.ocean(), boats.single()) else {
        return;
    };
    let (x, z) = (boat.translation.x, boat.translation.z);
    let Some(wakes) = ocean.wakes() else {
        return;
    };
    let (dip, _) = wakes.at(f64::from(x), f64::from(z));
    seen.dip = Some(dip);
    if let Some(h) = water.height(x, z) {
        seen.height = Some((h, dip));
    }
}

/// A `Wake` on a `Buoyancy` body turns the ocean's wake window on (a new ocean with the
/// plugin's `WakeWindow`), hands the body to the ocean as a hull of its columns' size moving
/// at its measured velocity, and the water under it dips: the ocean's own wake window and
/// the texels the renderer uploads see it.
#[test]
fn a_wake_body_presses_the_water_and_is_packed() {
    let mut app = app(settings(SeaState::Calm, 0.0));
    app.init_resource::<WakeSeen>();
    app.world_mut().spawn((
        Buoyancy::boat(8.0, 3.0, 1.5, 1025.0 * 8.0 * 3.0 * 0.6),
        Wake::default(),
        Transform::from_xyz(5.0, 0.0, -3.0),
    ));
    app.add_systems(
        Update,
        (see_wake, |mut q: Query<&mut Transform, With<Wake>>| {
            for mut t in &mut q {
                // 4 m/s along +z (the body's bow: heading π/2).
                t.translation.z += (4.0 * DT) as f32;
            }
        }),
    );
    run_until(&mut app, "an ocean with wakes", |w| {
        w.resource::<WakeSeen>().dip.is_some()
    });
    for _ in 0..120 {
        app.update();
    }
    let input = app.world().resource::<WakeInput>().clone();
    assert!(input.wanted);
    assert_eq!(input.hulls.len(), 1);
    let hull = input.hulls[0];
    assert!((hull.length - 8.0).abs() < 1e-3 && (hull.beam - 3.0).abs() < 1e-3);
    assert!((hull.draft - 0.6).abs() < 1e-3, "{hull:?}");
    assert!((hull.velocity[1] - 4.0).abs() < 0.05, "{hull:?}");
    assert!(hull.velocity[0].abs() < 0.05, "{hull:?}");
    assert!(
        // (the waves roll and pitch it a little)
        (hull.heading - std::f32::consts::FRAC_PI_2).abs() < 0.02,
        "{hull:?}"
    );
    // No camera: the window follows the hull.
    assert_eq!(input.centre, Some(hull.position));

    let seen = app.world().resource::<WakeSeen>();
    let dip = seen.dip.expect("seen");
    assert!(dip < -0.1, "the water under the hull dips: {dip}");
    let texels = app.world().resource::<OceanTexels>();
    let frame = texels.texels.as_ref().expect("packed texels");
    assert!(frame.wake.active());
    assert_eq!(frame.wake.size, WakeWindow::default().0.size);
    let deepest = frame
        .wake
        .texels
        .iter()
        .map(|t| t[0].to_f32())
        .fold(0.0f32, f32::min);
    assert!(deepest < -0.1, "the texels hold the dip: {deepest}");
    assert!(
        status(&app).last_error.is_none(),
        "{:?}",
        status(&app).last_error
    );
}

/// A depth map in the settings reaches the ocean (its queries see the beach) and the packed
/// texels (the coast, as the crate packs it); new weather solves it again (new texels), and
/// a sea without it drops them.
#[test]
fn a_depth_map_reaches_the_ocean_and_the_texels() {
    use bevy_ocean_fft::ocean_fft::DepthMap;
    use std::sync::Arc;
    let mut sea = settings(SeaState::FreshBreeze, 1.0);
    // 48 × 8 cells 4 m apart from x = 0: 1:16 from 12 m deep to dry land past x = 192 m.
    let map = Arc::new(DepthMap {
        origin: [0.0, -16.0],
        spacing: 4.0,
        size: [48, 8],
        depth: (0..48 * 8).map(|c| 12.0 - (c % 48) as f32 * 0.25).collect(),
    });
    sea.depth_map = Some(map.clone());
    let mut app = app(sea.clone());
    let coast = |app: &App| {
        let texels = app.world().resource::<OceanTexels>();
        texels.texels.as_ref().and_then(|f| f.coast.clone())
    };
    run_until(&mut app, "the coast packed", |w| {
        let texels = w.resource::<OceanTexels>();
        texels.texels.as_ref().is_some_and(|f| f.coast.is_some())
    });
    for _ in 0..10 {
        app.update();
    }
    let first = coast(&app).expect("a coast");
    assert_eq!(first.size, [48, 8]);
    assert_eq!(first.origin, [0.0, -16.0]);
    // The game's queries see the ocean with the map.
    #[derive(Resource, Default)]
    struct MapSeen(Option<DepthMap>);
    app.init_resource::<MapSeen>();
    app.add_systems(Update, |water: Water, mut seen: ResMut<MapSeen>| {
        if let Some(field) = water.ocean().and_then(|o| o.textures().coast()) {
            seen.0 = Some(field.map().clone());
        }
    });
    app.update();
    assert_eq!(app.world().resource::<MapSeen>().0.as_ref(), Some(&*map));

    let mut calmer = sea.clone();
    calmer.set_weather(SeaState::ModerateBreeze);
    app.insert_resource(calmer.clone());
    run_until(&mut app, "the map solved for new weather", |w| {
        let texels = w.resource::<OceanTexels>();
        let generation = texels
            .texels
            .as_ref()
            .and_then(|f| f.coast.as_ref())
            .map(|c| c.generation);
        generation.is_some_and(|g| g > first.generation)
    });
    let mut open = calmer;
    open.depth_map = None;
    app.insert_resource(open);
    run_until(&mut app, "the coast dropped", |w| {
        let texels = w.resource::<OceanTexels>();
        texels.texels.as_ref().is_some_and(|f| f.coast.is_none())
    });
    assert!(
        status(&app).last_error.is_none(),
        "{:?}",
        status(&app).last_error
    );
}
