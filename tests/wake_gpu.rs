//! The wake window's GPU packing (issue 40): `Textures::pack_wakes` copies the window's
//! height, slope and foam bit for bit, in the documented texel order, and refuses a wrong
//! buffer or an ocean without wakes by name, writing nothing.

use ocean_fft::{Error, Hull, OceanConfig, OceanState, Spectrum, WakeConfig};

fn ocean(wakes: Option<WakeConfig>) -> OceanState {
    let config = OceanConfig {
        size: 16,
        wakes,
        ..OceanConfig::default()
    };
    OceanState::new(Spectrum::jonswap(5.0, 10_000.0).unwrap(), config).unwrap()
}

#[test]
fn pack_wakes_copies_height_slope_and_foam() {
    let wakes = WakeConfig {
        size: 64,
        spacing: 1.0,
        ..WakeConfig::default()
    };
    let mut ocean = ocean(Some(wakes));
    ocean
        .set_hulls(&[Hull {
            velocity: [7.0, 0.5],
            position: [-20.0, 3.0],
            ..Hull::default()
        }])
        .unwrap();
    for _ in 0..120 {
        ocean.step(1.0 / 30.0).unwrap();
    }
    let w = ocean.wakes().unwrap();
    let n = w.size();
    assert!(w.foam().iter().any(|&f| f > 0.1) && w.height().iter().any(|&h| h.abs() > 0.1));
    let mut texels = vec![[f32::NAN; 4]; n * n];
    ocean.textures().pack_wakes(&mut texels).unwrap();
    for j in 0..n {
        for i in 0..n {
            let k = j * n + i;
            let want = [w.height()[k], w.slope()[k][0], w.slope()[k][1], w.foam()[k]];
            assert_eq!(
                texels[k].map(f32::to_bits),
                want.map(f32::to_bits),
                "({i}, {j})"
            );
            // The texel is the world point origin + (i, j)·spacing.
            let (x, z) = (
                w.origin()[0] + i as f64 * f64::from(w.spacing()),
                w.origin()[1] + j as f64 * f64::from(w.spacing()),
            );
            if i + 1 < n && j + 1 < n {
                assert_eq!(w.at(x, z).0, texels[k][0]);
            }
        }
    }

    // Bad input: nothing written.
    let mut short = vec![[7.0f32; 4]; n * n - 1];
    match ocean.textures().pack_wakes(&mut short) {
        Err(Error::LengthMismatch { name, .. }) => assert_eq!(name, "out"),
        other => panic!("{other:?}"),
    }
    assert!(short.iter().all(|t| *t == [7.0; 4]));
    let plain = self::ocean(None);
    let mut out = vec![[7.0f32; 4]; 16];
    match plain.textures().pack_wakes(&mut out) {
        Err(Error::NotApplicable { name, .. }) => assert_eq!(name, "wakes"),
        other => panic!("{other:?}"),
    }
    assert!(out.iter().all(|t| *t == [7.0; 4]));
}
