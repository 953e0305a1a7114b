//! ocean-fft's buffers as glam 0.33 types (the glam of Bevy 0.20, rapier, parry and avian),
//! without copying; the conversions through mint; and the engine functions of src/lib.rs.

#[path = "../../zero_copy.rs"]
mod zero_copy;

use glam::Vec3;
use zero_copy::{ocean, varies};

#[test]
fn buffer_elements_convert_through_mint() {
    let ocean = ocean();
    let cascade = &ocean.cascades()[0];
    for (a, d) in cascade.normal().iter().zip(cascade.displacement()) {
        // mint's vectors convert from the crate's arrays with `From`: no feature needed.
        let normal = mint::Vector3::from(*a);
        assert_eq!((normal.x, normal.y, normal.z), (a[0], a[1], a[2]));
        let horizontal: mint::Vector2<f32> = (*d).into();
        assert_eq!((horizontal.x, horizontal.y), (d[0], d[1]));
        // And any library that speaks mint takes them (glam with its `mint` feature here).
        assert_eq!(Vec3::from(normal), Vec3::from_array(*a));
        assert_eq!(<[f32; 3]>::from(normal), *a);
    }
    varies(cascade.normal().iter().map(|a| mint::Vector3::from(*a).x));
}

/// The engine-independent functions the guide's engine section shows (src/lib.rs), checked
/// against the crate's own buffers and queries computed separately.
mod engines {
    use super::zero_copy::{ocean, same_memory, varies};
    use client_glam_0_33::{engine_types, float_on_water, water_point_under, OceanTexels};
    use glam::Vec3;
    use ocean_fft::gpu::Engine;
    use ocean_fft::half::f16;
    use ocean_fft::OceanState;

    #[test]
    fn step_and_pack_fills_every_cascade_from_the_stepped_ocean() {
        let mut ocean: OceanState = ocean();
        let mut texels = OceanTexels::new(&ocean);
        let time = ocean.time();
        texels.step_and_pack(&mut ocean, 0.1).unwrap();
        assert_eq!(ocean.time(), time + 0.1);
        for (c, cascade) in ocean.cascades().iter().enumerate() {
            let n2 = cascade.size() * cascade.size();
            // The ocean's one foam field rides in cascade 0's texels; the others carry 0.
            let zeros = vec![0.0; n2];
            let foam = if c == 0 {
                ocean.foam_view().total()
            } else {
                &zeros[..]
            };
            // Each channel is the f16 nearest to the buffer it comes from, after this step.
            let near = |texel: f16, value: f32| texel == f16::from_f32(value);
            assert_eq!(
                (texels.displacement[c].len(), texels.slope[c].len()),
                (n2, n2)
            );
            #[allow(clippy::needless_range_loop)] // one index into eight buffers
            for k in 0..n2 {
                let (d, s) = (texels.displacement[c][k], texels.slope[c][k]);
                assert!(near(d[0], cascade.displacement()[k][0]));
                assert!(near(d[1], cascade.height()[k]));
                assert!(near(d[2], cascade.displacement()[k][1]));
                assert!(near(d[3], foam[k]));
                assert!(near(s[0], cascade.slope()[k][0]));
                assert!(near(s[1], cascade.slope()[k][1]));
                assert!(near(s[2], cascade.jacobian()[k]));
                assert!(near(s[3], foam[k]));
            }
            varies(texels.displacement[c].iter().map(|t| t[1].to_f32()));
            let [displacement, slope] = texels.bytes(c);
            same_memory(displacement, &texels.displacement[c]);
            same_memory(slope, &texels.slope[c]);
            assert_eq!(displacement.len(), n2 * 8);
        }
        // A refused step changes nothing and packs nothing.
        let before = texels.displacement[0].clone();
        assert!(texels.step_and_pack(&mut ocean, -1.0).is_err());
        assert_eq!(texels.displacement[0], before);
    }

    #[test]
    fn water_point_under_is_height_at_in_each_engines_frame() {
        let ocean = ocean();
        for (x, z) in [(0.0, 0.0), (3.7, -12.25), (-40.0, 7.5)] {
            let y = f64::from(ocean.water().height_at(x, z).unwrap());
            assert!(ocean.water().locate(x, z).unwrap().converged);
            // The crate's point (x, 5, z) in each engine, by the table of the guide (not through
            // Engine::position), and the water point under it in that engine's frame and units.
            let cases = [
                (Engine::Bevy, [x, 5.0, z], [x, y, z]),
                (Engine::Godot, [x, 5.0, z], [x, y, z]),
                (Engine::Unity, [x, 5.0, -z], [x, y, -z]),
                (
                    Engine::Unreal,
                    [100.0 * x, 100.0 * z, 500.0],
                    [100.0 * x, 100.0 * z, 100.0 * y],
                ),
                (Engine::Blender, [x, -z, 5.0], [x, -z, y]),
            ];
            for (engine, position, expected) in cases {
                let (water, converged) = water_point_under(&ocean, engine, position).unwrap();
                assert!(converged);
                for a in 0..3 {
                    // Scaling by 100 and back rounds: within 1e-12 relative.
                    assert!((water[a] - expected[a]).abs() <= 1e-12 * expected[a].abs().max(1.0));
                }
            }
        }
        assert!(water_point_under(&ocean, Engine::Bevy, [f64::NAN, 0.0, 0.0]).is_err());
    }

    #[test]
    fn float_on_water_moves_only_the_height() {
        let ocean = ocean();
        let buoy = Vec3::new(3.5, 40.0, -8.0);
        let floated = float_on_water(&ocean, buoy).unwrap();
        assert_eq!((floated.x, floated.z), (buoy.x, buoy.z));
        assert_eq!(floated.y, ocean.water().height_at(3.5, -8.0).unwrap());
    }

    #[test]
    fn engine_types_are_views_and_copies_of_the_normals() {
        let ocean = ocean();
        let cascade = &ocean.cascades()[1];
        let (one, all, mint) = engine_types(cascade);
        same_memory(all, cascade.normal());
        assert_eq!(one.to_array(), cascade.normal()[0]);
        assert_eq!([mint.x, mint.y, mint.z], cascade.normal()[0]);
        varies(all.iter().map(|v| v.z));
    }
}
