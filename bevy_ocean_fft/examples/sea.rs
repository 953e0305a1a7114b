//! The sea in Bevy: the ocean, a few floating boats, and a panel to change the weather live.
//!
//! ```text
//! cargo run --release -p bevy_ocean_fft --example sea
//! cargo run --release -p bevy_ocean_fft --example sea -- --frames 60 --screenshot out/bevy.png
//! ```
//!
//! The boats leave wakes (`Wake`); `--boat-speed 8` drives them ahead, `--follow-boat` keeps
//! the camera's offset from the first one, `--camera X,Y,Z --look-at X,Y,Z` places it.
//!
//! `--coast island` or `--coast breakwater` puts a coast in the sea (the render layer's
//! procedural depth maps, `OceanSettings::depth_map`) and its ground (a mesh with a colour
//! per vertex and a `StandardMaterial`): the waves shrink and break on its beaches, and the
//! camera starts at a view of it.
//!
//! `--anisotropy 1` for a software rasteriser (as in CI): anisotropic filtering makes its
//! frames take minutes. With `--frames N` it renders N frames and exits, printing
//! `frames N, mean frame … ms, step … ms, upload … ms, …`; with `--screenshot FILE` it saves
//! the last frame as a PNG first.

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;

use bevy::asset::RenderAssetUsages;
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::light::CascadeShadowConfigBuilder;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;
use bevy::render::view::screenshot::{save_to_disk, Screenshot, ScreenshotCaptured};
use bevy::window::WindowResolution;
use bevy_ocean_fft::prelude::*;
use bevy_ocean_fft::UploadTime;
use clap::Parser;
use ocean_fft_render::{terrain, CoastKind};

/// The sea in Bevy: a fresh breeze, four boats, and a panel that changes the weather.
#[derive(Parser, Resource, Debug, Clone)]
#[command(
    name = "sea",
    max_term_width = 100,
    args_override_self = true,
    allow_negative_numbers = true
)]
struct Options {
    /// Render N frames after the first ocean is built, print their mean times, then exit.
    #[arg(long, value_name = "N", value_parser = frame_count)]
    frames: Option<u64>,
    /// With --frames: save the last frame as a PNG first.
    #[arg(long, value_name = "FILE.png", requires = "frames")]
    screenshot: Option<PathBuf>,
    /// Anisotropic filtering in samples, 1 to 16 (1 for a software rasteriser).
    #[arg(
        long,
        value_name = "N",
        default_value_t = 16,
        value_parser = clap::value_parser!(u16).range(1..=16)
    )]
    anisotropy: u16,
    /// Sea state to start from.
    #[arg(long, value_name = "NAME", default_value = "fresh_breeze", value_parser = preset)]
    preset: SeaState,
    /// The boats' speed ahead in m/s, 0 (drifting where they are) to 20.
    #[arg(long, value_name = "M/S", default_value_t = 0.0, value_parser = speed)]
    boat_speed: f32,
    /// The camera moves with the first boat (keeps its offset from it).
    #[arg(long)]
    follow_boat: bool,
    /// The camera's place in metres, y up.
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = point)]
    camera: Option<Vec3>,
    /// The point the camera looks at, m.
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = point)]
    look_at: Option<Vec3>,
    /// A coast: `island` (beaches and a bay facing the waves) or `breakwater` (a beach behind
    /// a wall), with its ground; `none` for the open sea.
    #[arg(long, value_name = "NAME", default_value = "none", value_parser = coast)]
    coast: Coast,
}

/// `--coast`'s value: a coast, or none.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Coast(Option<CoastKind>);

/// `--coast`: `none` or a `CoastKind` name.
fn coast(text: &str) -> Result<Coast, String> {
    match text {
        "none" => Ok(Coast(None)),
        name => name.parse().map(|kind| Coast(Some(kind))),
    }
}

/// `--preset`: a `SeaState` name.
fn preset(text: &str) -> Result<SeaState, String> {
    SeaState::ALL
        .into_iter()
        .find(|s| s.name() == text)
        .ok_or_else(|| {
            let names: Vec<&str> = SeaState::ALL.iter().map(|s| s.name()).collect();
            format!("one of {}", names.join(", "))
        })
}

/// `--boat-speed`: 0 to 20 m/s.
fn speed(text: &str) -> Result<f32, String> {
    match text.parse::<f32>() {
        Ok(v) if (0.0..=20.0).contains(&v) => Ok(v),
        _ => Err("a speed from 0 to 20 m/s".into()),
    }
}

/// `--camera`, `--look-at`: three finite numbers separated by commas.
fn point(text: &str) -> Result<Vec3, String> {
    let v: Vec<f32> = text
        .split(',')
        .map(|p| p.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|_| "three numbers X,Y,Z".to_string())?;
    match v[..] {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok(Vec3::new(x, y, z)),
        _ => Err("three finite numbers X,Y,Z".into()),
    }
}

/// `--frames`: a whole number, at least 1.
fn frame_count(text: &str) -> Result<u64, String> {
    match text.parse() {
        Ok(0) => Err("at least 1 frame".into()),
        Ok(n) => Ok(n),
        Err(_) => Err("not a whole number".into()),
    }
}

fn main() -> ExitCode {
    // clap's: the help and exit 0 after --help, its error and exit 2 on a bad command line.
    let options = Options::parse();
    // guide: app
    let exit = App::new()
        .add_plugins(DefaultPlugins.set(WindowPlugin {
            primary_window: Some(Window {
                title: "bevy_ocean_fft: sea".into(),
                resolution: WindowResolution::new(1280, 720),
                ..default()
            }),
            ..default()
        }))
        // The simulation, buoyancy, queries, and the water and sky drawn on this app's camera.
        .add_plugins(OceanPlugin {
            anisotropy: options.anisotropy,
            ..default()
        })
        // The sea of --preset (a fresh breeze by default) on its default grids.
        .insert_resource(OceanSettings::preset(options.preset))
        // A storm under a heavy overcast, as the viewer draws it; the panel toggles it.
        .insert_resource(if options.preset == SeaState::Storm {
            OceanAppearance::overcast()
        } else {
            OceanAppearance::default()
        })
        .insert_resource(options)
        .init_resource::<Stats>()
        .add_systems(Startup, (coast_settings, scene, panel))
        .add_systems(Update, (buttons, hud, frames, drive))
        .run();
    // guide: end
    match exit {
        AppExit::Success => ExitCode::SUCCESS,
        AppExit::Error(code) => ExitCode::from(code.get()),
    }
}

/// The sea of the options: the preset, and the coast's depth map if any.
fn settings(options: &Options) -> OceanSettings {
    let mut settings = OceanSettings::preset(options.preset);
    settings.depth_map = options.coast.0.map(|coast| Arc::new(coast.depth_map()));
    settings
}

/// `--coast`: the coast's depth map in the settings before the first ocean is built (in
/// `Last` of the first frame).
fn coast_settings(options: Res<Options>, mut sea: ResMut<OceanSettings>) {
    if options.coast.0.is_some() {
        *sea = settings(&options);
    }
}

/// The coast's ground as a Bevy mesh: positions, normals and a colour per vertex.
fn ground_mesh(coast: CoastKind) -> Mesh {
    let t = terrain(&coast.depth_map());
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::default(),
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, t.positions)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, t.normals)
    .with_inserted_attribute(Mesh::ATTRIBUTE_COLOR, t.colours)
    .with_inserted_indices(Indices::U32(t.indices))
}

/// The sun: 24° up, 30° to the right of the view, so that its glitter path runs toward the
/// viewer on the right and the sky on the left is the clear sky away from the sun.
fn sun_direction() -> Vec3 {
    let (elevation, azimuth) = (24f32.to_radians(), (-60f32).to_radians());
    Vec3::new(
        elevation.cos() * azimuth.cos(),
        elevation.sin(),
        elevation.cos() * azimuth.sin(),
    )
}

/// The first boat (the one `--follow-boat` follows).
#[derive(Component)]
struct Lead;

fn scene(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    options: Res<Options>,
) {
    // A coast's own view (its eye, heading and pitch), else the boats'.
    let (default_eye, default_target) = match options.coast.0 {
        Some(coast) => {
            let (eye, heading, pitch) = coast.view();
            let (h, p) = (heading.to_radians(), pitch.to_radians());
            let eye = Vec3::from_array(eye);
            let look = Vec3::new(h.cos() * p.cos(), p.sin(), h.sin() * p.cos());
            (eye, eye + 100.0 * look)
        }
        None => (Vec3::new(0.0, 7.0, 24.0), Vec3::new(0.0, 1.0, -40.0)),
    };
    let eye = options.camera.unwrap_or(default_eye);
    let target = options.look_at.unwrap_or(default_target);
    if let Some(coast) = options.coast.0 {
        // Vertex colours times white: sand, grass and rock, matte.
        commands.spawn((
            Name::new("coast"),
            Mesh3d(meshes.add(ground_mesh(coast))),
            MeshMaterial3d(materials.add(StandardMaterial {
                perceptual_roughness: 0.95,
                ..default()
            })),
        ));
    }
    commands.spawn((
        Camera3d::default(),
        // The filmic curve the reference shader's palette was tuned with (ACES).
        Tonemapping::AcesFitted,
        OceanCamera,
        Transform::from_translation(eye).looking_at(target, Vec3::Y),
    ));
    // About 3.8 klx: with Bevy's default exposure (EV100 9.7) a white body facing the sun
    // shows about 1.15, the brightness the reference shader is tuned for.
    commands.spawn((
        DirectionalLight {
            illuminance: 3800.0,
            shadow_maps_enabled: true,
            ..default()
        },
        Transform::default().looking_to(-sun_direction(), Vec3::Y),
        CascadeShadowConfigBuilder {
            maximum_distance: 150.0,
            first_cascade_far_bound: 25.0,
            ..default()
        }
        .build(),
    ));
    // The sky's light on the shaded sides (Bevy's default, 80 cd/m², is a dim room's).
    commands.insert_resource(GlobalAmbientLight {
        color: Color::srgb(0.75, 0.85, 1.0),
        brightness: 500.0,
        ..default()
    });
    let hull = meshes.add(Cuboid::new(2.4, 1.2, 6.0));
    let cabin = meshes.add(Cuboid::new(1.8, 1.0, 2.2));
    let mast = meshes.add(Cylinder::new(0.06, 5.0));
    let colours = [
        Color::srgb(0.75, 0.12, 0.08),
        Color::srgb(0.92, 0.90, 0.85),
        Color::srgb(0.95, 0.65, 0.10),
        Color::srgb(0.10, 0.25, 0.55),
    ];
    let white = materials.add(Color::srgb(0.9, 0.9, 0.88));
    let places = [
        Vec3::new(-7.0, 0.0, -8.0),
        Vec3::new(6.0, 0.0, -18.0),
        Vec3::new(-3.0, 0.0, -34.0),
        Vec3::new(14.0, 0.0, -45.0),
    ];
    for (i, (place, colour)) in places.into_iter().zip(colours).enumerate() {
        let heading = Quat::from_rotation_y(0.6 * i as f32 - 0.5);
        // guide: boat
        // A 6 × 2.4 × 1.2 m hull of 3 t: it heaves, pitches and rolls on the waves (the
        // plugin moves it every fixed update; add a BuoyancyForce to hand the push to a
        // physics engine instead), and leaves a wake and a foam trail as it moves.
        let mut boat = commands.spawn((
            Name::new(format!("boat {i}")),
            Buoyancy::boat(6.0, 2.4, 1.2, 3000.0),
            Wake::default(),
            Transform::from_translation(place).with_rotation(heading),
            Mesh3d(hull.clone()),
            MeshMaterial3d(materials.add(colour)),
        ));
        // guide: end
        if i == 0 {
            boat.insert(Lead);
        }
        boat.with_children(|boat| {
            boat.spawn((
                Mesh3d(cabin.clone()),
                MeshMaterial3d(white.clone()),
                Transform::from_xyz(0.0, 1.0, 0.8),
            ));
            boat.spawn((
                Mesh3d(mast.clone()),
                MeshMaterial3d(white.clone()),
                Transform::from_xyz(0.0, 3.0, -0.8),
            ));
        });
    }
}

/// The boats that `drive` moves (not the camera).
type Boats<'w, 's> =
    Query<'w, 's, (&'static mut Transform, Has<Lead>), (With<Wake>, Without<OceanCamera>)>;

/// `--boat-speed`: the boats go ahead (their +z) on the water; `--follow-boat`: the camera
/// moves with the first.
fn drive(
    time: Res<Time>,
    options: Res<Options>,
    mut boats: Boats,
    mut camera: Query<&mut Transform, With<OceanCamera>>,
) {
    let mut lead = Vec3::ZERO;
    for (mut transform, is_lead) in &mut boats {
        let ahead = transform.rotation * Vec3::Z;
        let moved = Vec3::new(ahead.x, 0.0, ahead.z).normalize_or_zero()
            * options.boat_speed
            * time.delta_secs();
        transform.translation += moved;
        if is_lead {
            lead = moved;
        }
    }
    if options.follow_boat {
        for mut eye in &mut camera {
            eye.translation += lead;
        }
    }
}

/// A weather button.
#[derive(Component, Clone, Copy)]
enum Choice {
    Sea(SeaState),
    Overcast,
}

#[derive(Component)]
struct Hud;

fn panel(mut commands: Commands) {
    let font = TextFont::from_font_size(14.0);
    commands
        .spawn((
            Node {
                position_type: PositionType::Absolute,
                left: px(10.0),
                top: px(10.0),
                flex_direction: FlexDirection::Column,
                row_gap: px(4.0),
                padding: UiRect::all(px(8.0)),
                ..default()
            },
            BackgroundColor(Color::srgba(0.0, 0.0, 0.0, 0.45)),
        ))
        .with_children(|panel| {
            panel.spawn((Text::new("Weather (10 s change)"), font.clone()));
            let choices = SeaState::ALL
                .into_iter()
                .map(Choice::Sea)
                .chain([Choice::Overcast]);
            for choice in choices {
                let label = match choice {
                    Choice::Sea(state) => state.name().replace('_', " "),
                    Choice::Overcast => "overcast / clear".to_string(),
                };
                panel
                    .spawn((
                        Button,
                        choice,
                        Node {
                            padding: UiRect::axes(px(8.0), px(3.0)),
                            ..default()
                        },
                        BackgroundColor(Color::srgba(0.2, 0.3, 0.4, 0.8)),
                    ))
                    .with_child((Text::new(label), font.clone()));
            }
            panel.spawn((Text::new(""), font.clone(), Hud));
        });
}

// guide: weather
fn buttons(
    presses: Query<(&Interaction, &Choice), Changed<Interaction>>,
    mut settings: ResMut<OceanSettings>,
    mut appearance: ResMut<OceanAppearance>,
) {
    for (interaction, choice) in &presses {
        if *interaction != Interaction::Pressed {
            continue;
        }
        match *choice {
            // The preset's weather on the running grids: a live change of 10 s.
            Choice::Sea(state) => settings.set_weather(state),
            Choice::Overcast => {
                *appearance = if appearance.overcast > 0.5 {
                    OceanAppearance::default()
                } else {
                    OceanAppearance::overcast()
                };
            }
        }
    }
}
// guide: end

fn hud(
    status: Res<OceanStatus>,
    water: Water,
    camera: Query<&Transform, With<OceanCamera>>,
    mut text: Query<&mut Text, With<Hud>>,
) {
    let Ok(mut text) = text.single_mut() else {
        return;
    };
    let Some(spectrum) = &status.spectrum else {
        text.0 = "building the ocean…".into();
        return;
    };
    let change = status
        .transition_progress
        .map(|w| format!(", changing {:.0} %", 100.0 * w))
        .unwrap_or_default();
    text.0 = format!(
        "wind {:.1} m/s, Hs {:.2} m{change}\nstep {:.1} ms, pack {:.1} ms",
        spectrum.wind_speed(),
        spectrum.significant_wave_height(),
        status.step_ms,
        status.pack_ms,
    );
    // guide: query
    // Gameplay queries: the water under the camera, from the sea this frame draws.
    if let Ok(eye) = camera.single() {
        let (x, z) = (eye.translation.x, eye.translation.z);
        if let (Some(height), Some(normal)) = (water.height(x, z), water.normal(x, z)) {
            let tilt = normal.angle_between(Vec3::Y).to_degrees();
            text.0 += &format!("\nwater under the camera {height:+.2} m, tilted {tilt:.1} deg");
        }
    }
    // guide: end
    if let Some(error) = &status.last_error {
        text.0.push_str(&format!("\n{error}"));
    }
}

/// Frame timing for `--frames`.
#[derive(Resource, Default)]
struct Stats {
    /// Frames since the ocean's first texels, and the sums of their times, ms.
    counted: u64,
    frame: f64,
    step: f64,
    pack: f64,
    upload: f64,
    wait: f64,
    requested: bool,
    saved: bool,
}

#[derive(Resource)]
struct Saved;

#[allow(clippy::too_many_arguments)]
fn frames(
    mut commands: Commands,
    options: Res<Options>,
    mut stats: ResMut<Stats>,
    status: Res<OceanStatus>,
    upload: Res<UploadTime>,
    time: Res<Time<Real>>,
    saved: Option<Res<Saved>>,
    mut exit: MessageWriter<AppExit>,
) {
    let Some(n) = options.frames else {
        return;
    };
    // Frames are counted from the first one drawn with the ocean (its build and the
    // pipelines' compilation before it are not a frame's cost).
    if status.steps < 2 {
        return;
    }
    if stats.counted < n {
        stats.counted += 1;
        stats.frame += time.delta_secs_f64() * 1e3;
        stats.step += status.step_ms;
        stats.pack += status.pack_ms;
        stats.upload += upload.ms();
        stats.wait += status.wait_ms;
        return;
    }
    if let (Some(path), false) = (&options.screenshot, stats.requested) {
        stats.requested = true;
        let path = path.clone();
        commands
            .spawn(Screenshot::primary_window())
            .observe(save_to_disk(path))
            .observe(|_: On<ScreenshotCaptured>, mut commands: Commands| {
                commands.insert_resource(Saved);
            });
        return;
    }
    if options.screenshot.is_some() && saved.is_none() {
        return;
    }
    if !stats.saved {
        stats.saved = true;
        let k = stats.counted.max(1) as f64;
        println!(
            "frames {n}, mean frame {:.2} ms, step {:.2} ms, upload {:.2} ms, pack {:.2} ms, wait {:.2} ms",
            stats.frame / k,
            stats.step / k,
            stats.upload / k,
            stats.pack / k,
            stats.wait / k,
        );
        exit.write(AppExit::Success);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::error::ErrorKind;
    use clap::CommandFactory;

    fn parse(args: &[&str]) -> Result<Options, clap::Error> {
        Options::try_parse_from(std::iter::once("sea").chain(args.iter().copied()))
    }

    /// clap's checks of the definition (names, `requires`, defaults); they run where clap is
    /// compiled with debug assertions (the dev and test profiles; in the headless profile add
    /// `--config 'profile.headless.package.clap_builder.debug-assertions=true'`).
    #[test]
    fn the_definition_is_consistent() {
        Options::command().debug_assert();
    }

    #[test]
    fn defaults_and_flags() {
        let o = parse(&[]).unwrap();
        assert_eq!((o.frames, o.screenshot, o.anisotropy), (None, None, 16));
        assert_eq!(
            (o.preset, o.boat_speed, o.follow_boat),
            (SeaState::FreshBreeze, 0.0, false)
        );
        assert_eq!((o.camera, o.look_at, o.coast), (None, None, Coast(None)));
        let island = parse(&["--coast", "island"]).unwrap();
        assert_eq!(island.coast, Coast(Some(CoastKind::Island)));
        let sea = settings(&island);
        assert_eq!(
            sea.depth_map.as_deref(),
            Some(&CoastKind::Island.depth_map())
        );
        assert_eq!(settings(&o).depth_map, None);
        let ground = ground_mesh(CoastKind::Breakwater);
        assert_eq!(ground.count_vertices(), 256 * 256);
        let o = parse(&[
            "--preset",
            "calm",
            "--boat-speed",
            "8",
            "--follow-boat",
            "--camera",
            "-10,40,-20",
            "--look-at",
            "0,0,0",
        ])
        .unwrap();
        assert_eq!(
            (o.preset, o.boat_speed, o.follow_boat),
            (SeaState::Calm, 8.0, true)
        );
        assert_eq!(o.camera, Some(Vec3::new(-10.0, 40.0, -20.0)));
        assert_eq!(o.look_at, Some(Vec3::ZERO));
        // CI's command line.
        let o = parse(&[
            "--frames",
            "30",
            "--anisotropy",
            "1",
            "--screenshot",
            "out/bevy.png",
        ])
        .unwrap();
        assert_eq!(o.frames, Some(30));
        assert_eq!(o.screenshot, Some(PathBuf::from("out/bevy.png")));
        assert_eq!(o.anisotropy, 1);
        assert_eq!(
            parse(&["--frames", "2", "--frames", "3"]).unwrap().frames,
            Some(3)
        );
    }

    #[test]
    fn bad_values_are_errors_naming_the_flag() {
        for (args, flag) in [
            (&["--frames", "0"][..], "--frames"),
            (&["--frames", "-1"], "--frames"),
            (&["--frames", "x"], "--frames"),
            (&["--anisotropy", "0"], "--anisotropy"),
            (&["--anisotropy", "17"], "--anisotropy"),
            (&["--screenshot", "out.png"], "--frames"),
            (&["--boat-speed", "30"], "--boat-speed"),
            (&["--camera", "1,2"], "--camera"),
            (&["--preset", "gale"], "--preset"),
            (&["--coast", "reef"], "--coast"),
            (&["--bogus"], "--bogus"),
        ] {
            let text = parse(args).expect_err("a bad command line").to_string();
            assert!(text.contains(flag), "{args:?}: {text}");
        }
        let help = parse(&["--help"]).expect_err("help is not a run");
        assert_eq!(help.kind(), ErrorKind::DisplayHelp);
    }
}
