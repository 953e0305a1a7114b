//! Coasts (issue 41): waves over a planar beach against an independent Battjes & Janssen
//! model, land, bad maps, and no map at all.
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

use ocean_fft::{DepthMap, Error, OceanState, SeaState};

const G: f64 = 9.81;
/// Beach slope 1:50, from `DEEP` m at the map's offshore edge to the shore.
const SLOPE: f64 = 1.0 / 50.0;
const DEEP: f64 = 40.0;
const SPACING: f32 = 4.0;

/// A planar beach facing the waves travelling along `theta`: depth falls along the
/// direction from `DEEP` to 0 at distance DEEP/SLOPE, land beyond. The map is centred on
/// the world origin's offshore side: along-direction coordinate s from 0 at the edge.
fn beach(theta: f64) -> (DepthMap, impl Fn(f64, f64) -> [f64; 2]) {
    let length = DEEP / SLOPE + 200.0;
    let width = 400.0;
    let nx = (length / f64::from(SPACING)) as usize + 1;
    let nz = (width / f64::from(SPACING)) as usize + 1;
    let (c, s) = (theta.cos(), theta.sin());
    // Only axis-aligned directions give a map whose rows are along the beach; the presets
    // blow along +x (checked below).
    assert!(s.abs() < 1e-6 && c > 0.0, "preset direction {theta}");
    let origin = [0.0, -width / 2.0];
    let depth = (0..nz)
        .flat_map(|_| (0..nx).map(|i| (DEEP - SLOPE * i as f64 * f64::from(SPACING)) as f32))
        .collect();
    let map = DepthMap {
        origin,
        spacing: SPACING,
        size: [nx, nz],
        depth,
    };
    (map, move |along: f64, across: f64| [along, across])
}

/// Wave number of angular frequency ω at depth d (Newton on ω² = g k tanh(k d)).
fn wavenumber(omega: f64, d: f64) -> f64 {
    let mut k = omega * omega / G / (omega * omega * d / G).sqrt().tanh().max(1e-9);
    for _ in 0..50 {
        let t = (k * d).tanh();
        let f = G * k * t - omega * omega;
        let df = G * t + G * k * d * (1.0 - t * t);
        k -= f / df;
    }
    k
}

fn group_velocity(omega: f64, d: f64) -> f64 {
    if d.is_infinite() {
        return G / (2.0 * omega);
    }
    let k = wavenumber(omega, d);
    let kd = k * d;
    0.5 * omega / k * (1.0 + 2.0 * kd / (2.0 * kd).sinh())
}

/// Q_b from (1 − Q)/ln Q = −b² by the fixed point Q ← exp(−(1 − Q)/b²) from Q = 0 (its
/// own solver, not the crate's bisection): the map rises, so from below it climbs to the
/// smallest root, never to the spurious Q = 1.
fn q_b(b: f64) -> f64 {
    if b >= 1.0 {
        return 1.0;
    }
    let mut q = 0.0_f64;
    for _ in 0..100_000 {
        let next = (-(1.0 - q) / (b * b)).exp();
        if (next - q).abs() < 1e-13 {
            return next;
        }
        q = next;
    }
    q
}

/// Battjes & Janssen (1978) with H_max = 0.88/k tanh(γ k d/0.88), γ = 0.29 + 0.76 k d
/// (Ruessink, Walstra & Southgate 2003),
/// one frequency (the peak), integrated with RK4 in the energy flux F = E c_g from deep water
/// at the map's edge: H_s at distance `s` from the edge (depth DEEP − SLOPE s).
fn bj_hs(hs0: f64, omega_p: f64, s_end: f64) -> f64 {
    let fp = omega_p / std::f64::consts::TAU;
    let depth = |s: f64| DEEP - SLOPE * s;
    let h_rms0 = hs0 / 2.0_f64.sqrt();
    // Flux (per ρg) F = H_rms² c_g / 8; dF/ds = −(α/4) f_p Q_b H_max².
    let mut flux = h_rms0 * h_rms0 * group_velocity(omega_p, f64::INFINITY) / 8.0;
    let rhs = |s: f64, flux: f64| {
        let d = depth(s);
        let cg = group_velocity(omega_p, d);
        let h_rms = (8.0 * flux.max(0.0) / cg).sqrt();
        let k = wavenumber(omega_p, d);
        let gamma = 0.29 + 0.76 * k * d;
        let h_max = 0.88 / k * (gamma * k * d / 0.88).tanh();
        -0.25 * fp * q_b(h_rms / h_max) * h_max * h_max
    };
    let steps = (s_end / 0.25).ceil() as usize;
    let ds = s_end / steps as f64;
    for n in 0..steps {
        let s = n as f64 * ds;
        let k1 = rhs(s, flux);
        let k2 = rhs(s + ds / 2.0, flux + ds / 2.0 * k1);
        let k3 = rhs(s + ds / 2.0, flux + ds / 2.0 * k2);
        let k4 = rhs(s + ds, flux + ds * k3);
        flux += ds / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    let cg = group_velocity(omega_p, depth(s_end));
    (8.0 * flux.max(0.0) / cg).sqrt() * 2.0_f64.sqrt()
}

/// H_s = 4 std(η) of virtual buoys: heights_at along a line of `count` points across the
/// beach at distance `s` from the edge, at `times` instants 1.37 s apart.
fn buoy_hs(ocean: &mut OceanState, s: f64, count: usize, times: usize) -> f64 {
    let points: Vec<[f64; 2]> = (0..count)
        .map(|n| [s, -120.0 + 240.0 * n as f64 / count as f64])
        .collect();
    let mut out = vec![0.0_f32; count];
    let (mut sum, mut sum2, mut total) = (0.0_f64, 0.0_f64, 0.0_f64);
    for t in 0..times {
        ocean.set_time(100.0 + 1.37 * t as f64).unwrap();
        ocean.water().heights_at(&points, &mut out).unwrap();
        for &h in &out {
            sum += f64::from(h);
            sum2 += f64::from(h) * f64::from(h);
            total += 1.0;
        }
    }
    let mean = sum / total;
    4.0 * (sum2 / total - mean * mean).max(0.0).sqrt()
}

fn beach_against_model(state: SeaState) {
    let (spectrum, config) = state.build();
    let hs0 = f64::from(spectrum.significant_wave_height());
    let omega_p = f64::from(spectrum.peak_omega());
    let mut ocean = OceanState::new(spectrum.clone(), config).unwrap();
    let (map, _) = beach(f64::from(spectrum.wind_direction()));
    ocean.set_depth_map(Some(map)).unwrap();
    ocean.set_time(10.0).unwrap(); // past the blend from no map
    for d in [20.0, 10.0, 5.0, 3.0, 2.0, 1.0] {
        let s = (DEEP - d) / SLOPE;
        let measured = buoy_hs(&mut ocean, s, 64, 200);
        let model = bj_hs(hs0, omega_p, s);
        // What the factors promise, 4 (Σ f_c² m0_c)^½, to tell the march from the sampling.
        let coast = ocean.textures().coast().unwrap();
        let i = (s / f64::from(SPACING)).round() as usize;
        let cell = coast.map().size[1] / 2 * coast.map().size[0] + i;
        let n = coast.cascade_count();
        let promised = 4.0
            * ocean
                .cascades()
                .iter()
                .zip(&coast.factors()[cell * n..][..n])
                .map(|(c, &f)| c.expected_variance() * f64::from(f * f))
                .sum::<f64>()
                .sqrt();
        println!(
            "{}: d {d} m: buoys H_s {measured:.3} m, factors {promised:.3} m, BJ {model:.3} m, \
             ratio {:.3}, H_s/d {:.2}",
            state.name(),
            measured / model,
            measured / d
        );
        // 20 %: the bound. It covers the band-by-band shoaling against the model's
        // single peak frequency (a few %), the grids' share of the spectrum (≥ 0.9 of its
        // variance) and the sampling error of 64 × 200 correlated samples (about 5 %).
        assert!(
            (measured / model - 1.0).abs() < 0.2,
            "{}: d {d}: {measured} vs {model}",
            state.name()
        );
        if d <= 2.0 {
            // Inside the surf zone: depth-limited (Thornton & Guza 1983 measured
            // H_rms ≈ 0.42 d, H_s ≈ 0.59 d; the band).
            let ratio = measured / d;
            assert!((0.3..=0.6).contains(&ratio), "H_s/d {ratio} at {d} m");
        }
    }
    // Over land: the still level, exactly.
    // 100 m past the shoreline, inside the map (which ends 200 m past it).
    let land = DEEP / SLOPE + 100.0;
    let mut out = [1.0_f32; 4];
    ocean
        .water()
        .heights_at(
            &[[land, 0.0], [land, 30.0], [land + 40.0, -10.0], [land, 5.0]],
            &mut out,
        )
        .unwrap();
    assert_eq!(out, [0.0; 4]);
    assert!(ocean.water().depth_at(land, 0.0).unwrap().unwrap() <= 0.0);
}

#[test]
fn fresh_breeze_on_a_planar_beach() {
    beach_against_model(SeaState::FreshBreeze);
}

#[test]
fn swell_on_a_planar_beach() {
    beach_against_model(SeaState::Swell);
}

fn small_ocean() -> OceanState {
    let (spectrum, mut config) = SeaState::ModerateBreeze.build();
    config.size = 32;
    OceanState::new(spectrum, config).unwrap()
}

fn good_map() -> DepthMap {
    DepthMap {
        origin: [-50.0, -50.0],
        spacing: 2.0,
        size: [50, 40],
        depth: vec![5.0; 2000],
    }
}

#[test]
fn bad_maps_name_the_field_and_change_nothing() {
    let mut ocean = small_ocean();
    ocean.step(0.1).unwrap();
    let before = ocean.water().height_at(3.0, 4.0).unwrap();
    let cases: Vec<(DepthMap, &str)> = vec![
        (
            DepthMap {
                spacing: 0.0,
                ..good_map()
            },
            "spacing",
        ),
        (
            DepthMap {
                spacing: -1.0,
                ..good_map()
            },
            "spacing",
        ),
        (
            DepthMap {
                spacing: f32::NAN,
                ..good_map()
            },
            "spacing",
        ),
        (
            DepthMap {
                origin: [f64::INFINITY, 0.0],
                ..good_map()
            },
            "origin",
        ),
        (
            DepthMap {
                size: [51, 40],
                ..good_map()
            },
            "depth",
        ),
        (
            DepthMap {
                size: [1, 2000],
                ..good_map()
            },
            "size",
        ),
        (
            DepthMap {
                size: [1 << 20, 1 << 20],
                depth: vec![],
                ..good_map()
            },
            "size",
        ),
        (
            DepthMap {
                size: [usize::MAX, 2],
                depth: vec![],
                ..good_map()
            },
            "size",
        ),
        (
            DepthMap {
                depth: {
                    let mut d = vec![5.0; 2000];
                    d[777] = f32::NAN;
                    d
                },
                ..good_map()
            },
            "depth",
        ),
    ];
    for (map, field) in cases {
        let err = ocean.set_depth_map(Some(map.clone())).unwrap_err();
        let name = match err {
            Error::NonFinite { name }
            | Error::OutOfRange { name, .. }
            | Error::CountOutOfRange { name, .. }
            | Error::LengthMismatch { name, .. } => name,
            other => panic!("{other:?}"),
        };
        assert_eq!(name, field, "{map:?}");
        assert!(ocean.textures().coast().is_none());
        assert_eq!(ocean.water().height_at(3.0, 4.0).unwrap(), before);
    }
}

#[test]
fn no_map_keeps_the_bits_and_a_replaced_map_blends() {
    let mut a = small_ocean();
    let mut b = small_ocean();
    b.set_depth_map(None).unwrap();
    a.step(0.5).unwrap();
    b.step(0.5).unwrap();
    let points: Vec<[f64; 2]> = (0..64).map(|n| [n as f64 * 3.1, -n as f64 * 1.7]).collect();
    let (mut ha, mut hb) = (vec![0.0; 64], vec![0.0; 64]);
    a.water().heights_at(&points, &mut ha).unwrap();
    b.water().heights_at(&points, &mut hb).unwrap();
    assert_eq!(ha, hb);
    // A map and then its removal: back to the same bits once the blend is over.
    b.set_depth_map(Some(good_map())).unwrap();
    let p = [-10.0, -10.0];
    let start = b.water().height_at(p[0], p[1]).unwrap();
    assert_eq!(
        start,
        a.water().height_at(p[0], p[1]).unwrap(),
        "no pop at the change"
    );
    b.set_depth_map(None).unwrap();
    a.set_time(20.0).unwrap();
    b.set_time(20.0).unwrap();
    a.water().heights_at(&points, &mut ha).unwrap();
    b.water().heights_at(&points, &mut hb).unwrap();
    assert_eq!(ha, hb);
}

/// A map replacing another blends linearly over BLEND_SECONDS: half-way, each cascade's
/// factor is the mean of the two, so a height is the mean of the heights under each map
/// alone (the fields are linear in the factors).
#[test]
fn a_replaced_map_blends_without_a_pop() {
    let shallow = DepthMap {
        depth: vec![0.6; 2000],
        ..good_map()
    };
    let mut old = small_ocean();
    old.set_depth_map(Some(good_map())).unwrap();
    let mut new = small_ocean();
    new.set_depth_map(Some(shallow.clone())).unwrap();
    let mut both = small_ocean();
    both.set_depth_map(Some(good_map())).unwrap();
    // Each first map has blended in from the open sea by t = 5 s; then `both` changes.
    for ocean in [&mut old, &mut new, &mut both] {
        ocean.set_time(5.0).unwrap();
    }
    both.set_depth_map(Some(shallow)).unwrap();
    let half = ocean_fft::coast::BLEND_SECONDS / 2.0;
    for ocean in [&mut old, &mut new, &mut both] {
        ocean.set_time(5.0 + half).unwrap();
    }
    let mut checked = 0;
    for n in 0..40 {
        let [x, z] = [-40.0 + 2.0 * n as f64, -30.0 + 1.3 * n as f64];
        let (a, b) = (
            old.water().at_rest(x, z).unwrap().height,
            new.water().at_rest(x, z).unwrap().height,
        );
        let mid = both.water().at_rest(x, z).unwrap().height;
        // f32 sums of three cascades of centimetre waves: 1e-5 m covers their rounding.
        assert!(
            (mid - 0.5 * (a + b)).abs() < 1e-5,
            "{x} {z}: {mid} vs {a} {b}"
        );
        checked += usize::from(a != b);
    }
    assert!(checked > 30, "the two maps must differ where checked");
}

/// Over land the surface is the still level, flat, without foam; in the surf zone the foam
/// is at least the fraction of breaking waves.
#[test]
fn land_is_still_and_surf_foams() {
    let (spectrum, config) = SeaState::FreshBreeze.build();
    let mut ocean = OceanState::new(spectrum, config).unwrap();
    let (map, _) = beach(0.0);
    ocean.set_depth_map(Some(map)).unwrap();
    ocean.set_time(30.0).unwrap();
    let land = DEEP / SLOPE + 100.0;
    let s = ocean.water().surface_at(land, 7.0).unwrap();
    assert_eq!(
        (s.height, s.displacement, s.slope, s.foam),
        (0.0, [0.0; 2], [0.0; 2], 0.0)
    );
    assert_eq!(s.normal, [0.0, 1.0, 0.0]);
    let coast = ocean.textures().coast().unwrap();
    let nx = coast.map().size[0];
    // The cell 1.5 m deep on the centre row: breaking (Q_b > 0.1 under a 2.5 m sea).
    let i = ((DEEP - 1.5) / SLOPE / f64::from(SPACING)) as usize;
    let j = coast.map().size[1] / 2;
    let q = coast.breaking()[j * nx + i];
    assert!(q > 0.1, "Q_b {q}");
    let x = f64::from(SPACING) * i as f64;
    let z = coast.map().origin[1] + f64::from(SPACING) * j as f64;
    let foam = ocean.water().at_rest(x, z).unwrap().foam;
    assert!(foam >= q - 1e-6, "foam {foam} below Q_b {q}");
    // Offshore of the map, the open sea's factors.
    assert!(coast.factors()[j * nx * coast.cascade_count()..][..3]
        .iter()
        .all(|&f| f == 1.0));
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]
    /// Any map with one bad field is refused naming it, and nothing changes.
    #[test]
    fn any_bad_field_is_named(
        which in 0usize..4,
        bad in proptest::prop_oneof![
            proptest::prelude::Just(f32::NAN),
            proptest::prelude::Just(f32::INFINITY),
            proptest::prelude::Just(f32::NEG_INFINITY),
            -1e6f32..=0.0,
        ],
        cell in 0usize..2000,
        extra in 1usize..50,
    ) {
        let mut map = good_map();
        let field = match which {
            0 => { map.spacing = bad; "spacing" }
            1 if !bad.is_finite() => { map.depth[cell] = bad; "depth" }
            1 | 2 => { map.depth.truncate(2000 - extra.min(1999)); "depth" }
            _ => { map.origin[cell % 2] = f64::from(if bad.is_finite() { f32::NAN } else { bad }); "origin" }
        };
        let mut ocean = small_ocean();
        let err = ocean.set_depth_map(Some(map)).unwrap_err();
        let name = match err {
            Error::NonFinite { name }
            | Error::OutOfRange { name, .. }
            | Error::CountOutOfRange { name, .. }
            | Error::LengthMismatch { name, .. } => name,
            other => panic!("{other:?}"),
        };
        proptest::prop_assert_eq!(name, field);
        proptest::prop_assert!(ocean.textures().coast().is_none());
    }
}

/// With wakes and a depth map, every query carries both: the cascades scaled by the coast's
/// factors, then the wake added where the query lands (as without a map: the wake is not
/// scaled, it is made by the hulls in the water there).
#[test]
fn queries_carry_the_coast_and_the_wake_together() {
    use ocean_fft::{Hull, OceanConfig, WakeConfig};
    let (spectrum, config) = SeaState::ModerateBreeze.build();
    let config = |wakes: bool| OceanConfig {
        size: 32,
        wakes: wakes.then(|| WakeConfig {
            size: 64,
            spacing: 1.0,
            substep: 0.05,
            ..WakeConfig::default()
        }),
        ..config.clone()
    };
    let build = |wakes: bool, map: bool| {
        let mut ocean = OceanState::new(spectrum.clone(), config(wakes)).unwrap();
        if wakes {
            ocean.set_hulls(&[Hull::default()]).unwrap();
        }
        if map {
            ocean.set_depth_map(Some(good_map())).unwrap();
        }
        // Past the map's blend (2 s from t = 0).
        ocean.step(2.5).unwrap();
        ocean
    };
    let (both, wake, coast, open) = (
        build(true, true),
        build(true, false),
        build(false, true),
        build(false, false),
    );
    let wakes = both.wakes().unwrap();
    // Inside the wake window (±32 m) and the map (x −50…48, z −50…28); the last point is on
    // the map only, outside the window.
    let points = [[0.5, 0.25], [3.0, -1.7], [-9.2, 2.0], [-40.0, -45.0]];
    let mut batch = vec![0.0; points.len()];
    both.water().heights_at(&points, &mut batch).unwrap();
    for (&[x, z], &batched) in points.iter().zip(&batch) {
        let (h, _) = wakes.at(x, z);
        assert_eq!(h != 0.0, x.abs() < 30.0, "({x}, {z})");
        let all = both.water().height_at(x, z).unwrap();
        let coast_only = coast.water().height_at(x, z).unwrap();
        assert_eq!(all, coast_only + h, "({x}, {z})");
        assert_eq!(batched, all, "the batch answers as the point query");
        // The coast acts here: 5 m of water shortens the breeze's waves (factors ≠ 1).
        let open_h = open.water().height_at(x, z).unwrap();
        assert_ne!(coast_only, open_h, "({x}, {z})");
        let wake_h = wake.water().height_at(x, z).unwrap();
        assert_eq!(wake_h, open_h + wake.wakes().unwrap().at(x, z).0);
        let s = both.water().surface_at(x, z).unwrap();
        let c = coast.water().surface_at(x, z).unwrap();
        assert_eq!(s.height, c.height + h);
    }
}
