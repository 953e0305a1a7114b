//! The engine mappings keep what the docs' table says: each engine's up, handedness and unit,
//! exact inverses, and lengths and angles (the mappings are rotations or mirrors).

use ocean_fft::gpu::Engine;

const UP: [f32; 3] = [0.0, 1.0, 0.0];

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The engines' up axes and units as the table gives them (written out here, not read from
/// the crate).
fn documented(engine: Engine) -> ([f32; 3], bool, f64) {
    match engine {
        Engine::Bevy | Engine::Godot | Engine::Houdini => ([0.0, 1.0, 0.0], true, 1.0),
        Engine::Unity => ([0.0, 1.0, 0.0], false, 1.0),
        Engine::Unreal => ([0.0, 0.0, 1.0], false, 100.0),
        Engine::Blender => ([0.0, 0.0, 1.0], true, 1.0),
        _ => unreachable!("a new engine needs its row here"),
    }
}

#[test]
fn up_handedness_and_units_match_the_table() {
    let basis = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for engine in Engine::ALL {
        let (up, right_handed, units) = documented(engine);
        assert_eq!(engine.direction(UP), up, "{engine:?} up");
        assert_eq!(engine.right_handed(), right_handed, "{engine:?}");
        assert_eq!(engine.units_per_metre(), units, "{engine:?}");
        // The images of the crate's basis: orthonormal, with determinant +1 for a
        // right-handed engine (a rotation) and −1 for a left-handed one (a mirror).
        let [ex, ey, ez] = basis.map(|v| engine.direction(v));
        for (a, b) in [(ex, ey), (ey, ez), (ez, ex)] {
            assert_eq!(dot(a, b), 0.0, "{engine:?}");
        }
        for e in [ex, ey, ez] {
            assert_eq!(dot(e, e), 1.0, "{engine:?}");
        }
        let determinant = dot(cross(ex, ey), ez);
        assert_eq!(
            determinant,
            if right_handed { 1.0 } else { -1.0 },
            "{engine:?}"
        );
    }
}

#[test]
fn conversions_invert_exactly_and_keep_geometry() {
    let points = [[12.5, -3.25, 7.0], [1e6, 0.5, -2.5e5], [-0.125, 40.0, 0.0]];
    for engine in Engine::ALL {
        for p in points {
            let there = engine.position(p);
            assert_eq!(engine.position_to_crate(there), p, "{engine:?}");
            let length = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            let scale = engine.units_per_metre();
            assert!((length(there) / (scale * length(p)) - 1.0).abs() < 1e-15);
            let v = p.map(|c| c as f32);
            assert_eq!(
                engine.direction_to_crate(engine.direction(v)),
                v,
                "{engine:?}"
            );
        }
        // A surface normal tilted toward +x stays tilted toward the engine's image of +x,
        // by the same angle.
        let normal = [0.6, 0.8, 0.0];
        let mapped = engine.direction(normal);
        assert_eq!(dot(mapped, engine.direction(UP)), 0.8, "{engine:?}");
        assert_eq!(
            dot(mapped, engine.direction([1.0, 0.0, 0.0])),
            0.6,
            "{engine:?}"
        );
    }
}

#[test]
fn a_water_point_maps_where_the_engine_expects_it() {
    // 10 m along x, 2 m above still water, 3 m along z.
    let p = [10.0, 2.0, 3.0];
    assert_eq!(Engine::Bevy.position(p), [10.0, 2.0, 3.0]);
    assert_eq!(Engine::Unity.position(p), [10.0, 2.0, -3.0]);
    assert_eq!(Engine::Unreal.position(p), [1000.0, 300.0, 200.0]);
    assert_eq!(Engine::Blender.position(p), [10.0, -3.0, 2.0]);
    // Texture and normal-map conventions, as tabled.
    let top: Vec<_> = Engine::ALL
        .iter()
        .filter(|e| e.texture_origin_top())
        .collect();
    assert_eq!(top, [&Engine::Bevy, &Engine::Godot, &Engine::Unreal]);
    let directx: Vec<_> = Engine::ALL
        .iter()
        .filter(|e| e.directx_normal_maps())
        .collect();
    assert_eq!(directx, [&Engine::Unreal]);
}
