//! Coasts (issue 41) where the renderers look: the surf in `FoamView::foam_at`, and the
//! coast's texels (`Textures::pack_coast`) against the field the queries read.

use ocean_fft::{DepthMap, Error, OceanState, SeaState};

/// A 1:50 beach along +x (the presets' wind direction), 20 m deep at x = 0 to land at
/// x = 1000 m, 4 m cells, 80 m wide; `tide` metres deeper everywhere.
fn beach(tide: f32) -> DepthMap {
    let (nx, nz) = (300, 21);
    DepthMap {
        origin: [0.0, 0.0],
        spacing: 4.0,
        size: [nx, nz],
        depth: (0..nx * nz)
            .map(|c| 20.0 + tide - (c % nx) as f32 * 4.0 / 50.0)
            .collect(),
    }
}

fn ocean() -> OceanState {
    let (spectrum, mut config) = SeaState::FreshBreeze.build();
    config.size = 64;
    OceanState::new(spectrum, config).unwrap()
}

#[test]
fn pack_coast_holds_the_queries_factors_and_the_surf() {
    let mut ocean = ocean();
    let mut out = vec![[7.0f32; 4]; 300 * 21];
    match ocean.textures().pack_coast(&mut out) {
        Err(Error::NotApplicable { name, .. }) => assert_eq!(name, "depth_map"),
        other => panic!("{other:?}"),
    }
    ocean.set_depth_map(Some(beach(0.0))).unwrap();
    ocean.step(2.5).unwrap(); // past the 2 s blend from no map
    let mut short = vec![[7.0f32; 4]; 300 * 21 - 1];
    match ocean.textures().pack_coast(&mut short) {
        Err(Error::LengthMismatch { name, .. }) => assert_eq!(name, "out"),
        other => panic!("{other:?}"),
    }
    assert!(short.iter().all(|t| *t == [7.0; 4]), "nothing written");
    ocean.textures().pack_coast(&mut out).unwrap();
    let coast = ocean.textures().coast().unwrap();
    let n = coast.cascade_count();
    assert!(n <= 3, "the preset's cascades fit the texels");
    let mut surf = 0.0f32;
    for (cell, texel) in out.iter().enumerate() {
        for (c, &value) in texel[..3].iter().enumerate() {
            let want = if c < n {
                coast.factors()[cell * n + c]
            } else {
                1.0
            };
            // At a node the bilinear weights are 0 or 1 up to the rounding of
            // (x − origin)/Δ (relative 1e-16): the node's value to f32's last bits.
            assert!((value - want).abs() <= 1e-5 * want.max(1.0), "{cell} {c}");
        }
        assert!((texel[3] - coast.breaking()[cell]).abs() <= 1e-5, "{cell}");
        surf = surf.max(texel[3]);
    }
    assert!(
        surf > 0.3,
        "the fresh breeze breaks on the beach: Q_b up to {surf}"
    );

    // A tide (1 m deeper) blends in over 2 s: halfway, each texel is halfway too.
    let before = out.clone();
    ocean.set_depth_map(Some(beach(1.0))).unwrap();
    ocean.step(1.0).unwrap();
    ocean.textures().pack_coast(&mut out).unwrap();
    let new = ocean.textures().coast().unwrap();
    let mut moved = 0;
    for (cell, (texel, old)) in out.iter().zip(&before).enumerate() {
        for c in 0..n {
            let want = old[c] + (new.factors()[cell * n + c] - old[c]) * 0.5;
            assert!(
                (texel[c] - want).abs() <= 1e-5 * want.max(1.0),
                "{cell} {c}"
            );
            moved += usize::from((texel[c] - old[c]).abs() > 1e-3);
        }
    }
    assert!(moved > 100, "the tide changes the factors ({moved} moved)");
}

#[test]
fn foam_at_draws_the_surf_and_nothing_on_land() {
    let mut plain = ocean();
    let mut ocean = ocean();
    ocean.set_depth_map(Some(beach(0.0))).unwrap();
    for o in [&mut plain, &mut ocean] {
        o.step(30.0).unwrap();
    }
    let coast = ocean.textures().coast().unwrap();
    // Offshore, outside the map: the open sea's foam, to the bit.
    for [x, z] in [[-50.0, 10.0], [300.0, -40.0], [2000.0, 500.0]] {
        let a = ocean.foam_view().foam_at(x, z).unwrap();
        assert_eq!(a, plain.foam_view().foam_at(x, z).unwrap(), "({x}, {z})");
    }
    // On land (x ≥ 1000 m, 2 cells past the shore line): no foam.
    for k in 0..50 {
        let (x, z) = (1010.0 + f64::from(k) * 3.7, 3.0 + f64::from(k) * 1.3);
        assert_eq!(ocean.foam_view().foam_at(x, z).unwrap().total, 0.0);
    }
    // The surf zone, d from 2 m to 0.5 m (x 900–975 m): the patterned active foam's mean
    // follows Q_b there.
    let (mut foam, mut q, mut count) = (0.0f64, 0.0f64, 0.0f64);
    for i in 0..40 {
        for k in 0..100 {
            let (x, z) = (900.0 + f64::from(i) * 1.9, 2.0 + f64::from(k) * 0.76);
            foam += f64::from(ocean.foam_view().foam_at(x, z).unwrap().active);
            let cell = (z / 4.0).round() as usize * 300 + (x / 4.0).round() as usize;
            q += f64::from(coast.breaking()[cell]);
            count += 1.0;
        }
    }
    let (foam, q) = (foam / count, q / count);
    println!("surf zone: mean active foam {foam:.3}, mean Q_b {q:.3}");
    // (0.18 on this beach: far above the open sea's whitecap coverage of about 1 %.)
    assert!(q > 0.1, "the test wants surf: Q_b {q}");
    // 4000 points over 76 m × 80 m, the pattern correlated over metres: some hundreds of
    // independent samples, a standard error of the mean near 0.02; Q_b read at the nearest
    // cell rather than interpolated adds less than its change over half a cell (~0.02).
    assert!((foam - q).abs() < 0.08, "mean foam {foam} against Q_b {q}");
}

/// A change of weather keeps the map's factors until the map is set again, which then solves
/// them for the new sea; going back in time (restore) keeps the map set last.
#[test]
fn weather_keeps_the_factors_until_set_again_and_restore_keeps_the_map() {
    use ocean_fft::Spectrum;
    let mut ocean = ocean();
    let early = ocean.snapshot(); // t = 0
    ocean.step(5.0).unwrap();
    ocean.set_depth_map(Some(beach(0.0))).unwrap(); // set at t = 5 s
    ocean.step(2.5).unwrap();
    let surf = |o: &OceanState| o.textures().coast().unwrap().breaking().iter().sum::<f32>();
    let breeze = surf(&ocean);
    // A stronger sea (20 m/s over 300 km, beside the preset's), at once.
    let storm = Spectrum::jonswap(20.0, 300_000.0).unwrap();
    ocean.set_spectrum_unfitted(storm, 0.0).unwrap();
    ocean.step(0.5).unwrap();
    assert_eq!(surf(&ocean), breeze, "not solved again by the change");
    ocean.set_depth_map(Some(beach(0.0))).unwrap();
    let stormy = surf(&ocean);
    println!("sum of Q_b: breeze {breeze:.1}, storm {stormy:.1}");
    assert!(stormy > 1.5 * breeze, "the storm breaks further out");

    // Back to t = 0, before the map was set (at 5 s and again at 8 s): the map holds, land
    // is still water.
    ocean.restore(&early).unwrap();
    assert_eq!(ocean.time(), 0.0);
    for k in 0..20 {
        let (x, z) = (1020.0 + f64::from(k) * 5.3, 10.0 + f64::from(k) * 2.9);
        assert_eq!(ocean.water().height_at(x, z).unwrap(), 0.0, "({x}, {z})");
    }
}
