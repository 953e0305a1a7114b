//! The names 0.4 deprecated (issue 37) still answer, with the same bits as the views they
//! forward to, until they are removed.
#![allow(deprecated)]

use ocean_fft::gpu::TexelLayout;
use ocean_fft::{Hull, OceanConfig, OceanState, Spectrum, SurfaceSample, WakeConfig};

fn ocean() -> OceanState {
    let config = OceanConfig {
        size: 16,
        ..OceanConfig::default()
    };
    let mut ocean = OceanState::new(Spectrum::jonswap(15.0, 200_000.0).unwrap(), config).unwrap();
    ocean.pre_roll(5.0, 0.25).unwrap();
    ocean
}

/// [`ocean`] with a wake window (128 m wide around the origin: the first two of
/// [`POINTS`] inside it, the third outside) and a hull moving through it.
fn ocean_with_wakes() -> OceanState {
    let config = OceanConfig {
        size: 16,
        wakes: Some(WakeConfig::default()),
        ..OceanConfig::default()
    };
    let mut ocean = OceanState::new(Spectrum::jonswap(15.0, 200_000.0).unwrap(), config).unwrap();
    let hull = Hull {
        velocity: [4.0, 1.0],
        ..Hull::default()
    };
    ocean.pre_roll(5.0, 0.25).unwrap();
    ocean.set_hulls(&[hull]).unwrap();
    for _ in 0..20 {
        ocean.step(0.1).unwrap();
    }
    assert!(ocean.wakes().unwrap().at(0.0, 0.0).0 != 0.0);
    ocean
}

const POINTS: [[f64; 2]; 3] = [[0.0, 0.0], [12.5, -40.0], [300.0, 77.0]];

#[test]
fn the_old_query_names_answer_as_the_water_view() {
    old_query_names_answer_as_the_water_view(ocean());
}

#[test]
fn the_old_query_names_answer_as_the_water_view_with_wakes() {
    old_query_names_answer_as_the_water_view(ocean_with_wakes());
}

fn old_query_names_answer_as_the_water_view(mut ocean: OceanState) {
    let water = ocean.water();
    for [x, z] in POINTS {
        assert_eq!(ocean.sample(x, z).unwrap(), water.at_rest(x, z).unwrap());
        assert_eq!(
            ocean.sample_cascades(x, z, 1..3).unwrap(),
            water.at_rest_cascades(x, z, 1..3).unwrap()
        );
        assert_eq!(ocean.locate(x, z).unwrap(), water.locate(x, z).unwrap());
        assert_eq!(
            ocean.surface_at(x, z).unwrap(),
            water.surface_at(x, z).unwrap()
        );
        let (old, new) = (
            ocean.height_at(x, z).unwrap(),
            water.height_at(x, z).unwrap(),
        );
        assert_eq!(old.to_bits(), new.to_bits());
    }
    let batch = |f: &dyn Fn(&mut [SurfaceSample])| {
        let mut out = [SurfaceSample::default(); 3];
        f(&mut out);
        out
    };
    assert_eq!(
        batch(&|out| ocean.sample_many(&POINTS, out).unwrap()),
        batch(&|out| water.at_rest_many(&POINTS, out).unwrap())
    );
    assert_eq!(
        batch(&|out| ocean.surfaces_at(&POINTS, out).unwrap()),
        batch(&|out| water.surfaces_at(&POINTS, out).unwrap())
    );
    assert_eq!(
        batch(&|out| ocean.sample_grid([-3.0, 4.0], 2.5, [3, 1], out).unwrap()),
        batch(&|out| water.at_rest_grid([-3.0, 4.0], 2.5, [3, 1], out).unwrap())
    );
    let (mut old, mut new) = ([0.0f32; 3], [0.0f32; 3]);
    ocean.heights_at(&POINTS, &mut old).unwrap();
    water.heights_at(&POINTS, &mut new).unwrap();
    assert_eq!(old.map(f32::to_bits), new.map(f32::to_bits));
    // Errors too.
    assert_eq!(ocean.sample(f64::NAN, 0.0), water.at_rest(f64::NAN, 0.0));

    let heights = ocean.water().height_at(5.0, 6.0).unwrap();
    let surface = ocean.surface();
    ocean.step(0.1).unwrap();
    let water = surface.water();
    assert_eq!(surface.height_at(5.0, 6.0).unwrap(), heights);
    for [x, z] in POINTS {
        assert_eq!(surface.sample(x, z).unwrap(), water.at_rest(x, z).unwrap());
        assert_eq!(surface.locate(x, z).unwrap(), water.locate(x, z).unwrap());
        assert_eq!(
            surface.surface_at(x, z).unwrap(),
            water.surface_at(x, z).unwrap()
        );
        assert_eq!(
            surface.height_at(x, z).unwrap(),
            water.height_at(x, z).unwrap()
        );
    }
    assert_eq!(
        batch(&|out| surface.sample_many(&POINTS, out).unwrap()),
        batch(&|out| water.at_rest_many(&POINTS, out).unwrap())
    );
    assert_eq!(
        batch(&|out| surface.surfaces_at(&POINTS, out).unwrap()),
        batch(&|out| water.surfaces_at(&POINTS, out).unwrap())
    );
    surface.heights_at(&POINTS, &mut old).unwrap();
    water.heights_at(&POINTS, &mut new).unwrap();
    assert_eq!(old.map(f32::to_bits), new.map(f32::to_bits));
}

#[test]
fn the_old_foam_texture_and_diagnostic_names_answer_as_their_views() {
    let ocean = ocean();
    let foam = ocean.foam_view();
    assert!(
        ocean.foam_coverage().active > 0.0,
        "the test wants whitecaps"
    );
    assert_eq!(ocean.active_foam(), foam.active());
    assert_eq!(ocean.residual_foam(), foam.residual());
    assert_eq!(ocean.breaking(), foam.breaking());
    assert_eq!(ocean.foam(), foam.total());
    assert_eq!(ocean.foam_coverage(), foam.coverage());
    assert_eq!(ocean.foam_calibration(), foam.calibration());
    for [x, z] in POINTS {
        assert_eq!(ocean.foam_at(x, z).unwrap(), foam.foam_at(x, z).unwrap());
        assert_eq!(
            ocean.breaking_at(x, z).unwrap(),
            foam.breaking_at(x, z).unwrap()
        );
    }
    assert_eq!(
        ocean.foam_at(0.0, f64::INFINITY),
        foam.foam_at(0.0, f64::INFINITY)
    );

    let textures = ocean.textures();
    for cascade in 0..ocean.cascades().len() {
        let (mut old, mut new) = (vec![[0.0f32; 4]; 256], vec![[1.0f32; 4]; 256]);
        ocean
            .pack_texels(cascade, TexelLayout::DisplacementFoam, &mut old)
            .unwrap();
        textures
            .pack(cascade, TexelLayout::DisplacementFoam, &mut new)
            .unwrap();
        assert_eq!(old, new);
    }
    assert_eq!(
        ocean.subgrid_slope_variance(),
        textures.subgrid_slope_variance()
    );

    let diagnostics = ocean.diagnostics();
    assert_eq!(ocean.fit(), diagnostics.fit());
    assert_eq!(ocean.max_choppiness(), diagnostics.max_choppiness());
    assert_eq!(ocean.loop_error(), diagnostics.loop_error());
    assert_eq!(ocean.mean_level_offset(), diagnostics.mean_level_offset());
    assert_eq!(ocean.expected_variance(), diagnostics.expected_variance());
}

#[test]
fn the_old_limits_snapshot_and_weather_names_answer_as_the_new_ones() {
    use ocean_fft::limits;
    assert_eq!(OceanState::MAX_STEP, limits::MAX_STEP);
    assert_eq!(OceanState::MAX_PRE_ROLL_STEPS, limits::MAX_PRE_ROLL_STEPS);
    assert_eq!(OceanState::MAX_TRANSITION, limits::MAX_TRANSITION);
    assert_eq!(OceanState::TRANSITION_LAG, limits::TRANSITION_LAG);
    assert_eq!(OceanState::MIN_CHANGE_SHARE, limits::MIN_CHANGE_SHARE);
    assert_eq!(OceanState::MIN_BUILD_SHARE, limits::MIN_BUILD_SHARE);
    assert_eq!(OceanState::MAX_FOLD_SCALE, limits::MAX_FOLD_SCALE);

    let mut ocean = ocean();
    assert_eq!(ocean.transition_progress(), None);
    let stronger = Spectrum::jonswap(17.0, 200_000.0).unwrap();
    ocean.set_spectrum(stronger, 2.0).unwrap();
    for _ in 0..8 {
        ocean.step(0.25).unwrap();
        let (old, new) = (
            ocean.transition_progress(),
            ocean.diagnostics().transition_progress(),
        );
        assert_eq!(old.map(f64::to_bits), new.map(f64::to_bits));
    }
    // Mid-change, so that both names are read on a weight strictly between 0 and 1.
    assert!(ocean
        .diagnostics()
        .transition_progress()
        .is_some_and(|w| w > 0.0 && w < 1.0));

    let mut old = ocean.snapshot();
    let mut new = ocean.snapshot();
    ocean.step(0.5).unwrap();
    ocean.snapshot_into(&mut old);
    new.capture(&ocean);
    let (mut a, mut b) = (ocean.clone(), ocean.clone());
    a.step(1.0).unwrap();
    a.restore(&old).unwrap();
    b.step(1.0).unwrap();
    b.restore(&new).unwrap();
    assert_eq!(old.time(), new.time());
    assert_eq!(a.foam(), b.foam());
    assert_eq!(a.foam(), ocean.foam());
}
