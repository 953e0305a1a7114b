//! OceanState: band coverage, foam, world queries, presets — each against an independent
//! computation.
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

use std::ops::Bound;

use ocean_fft::{
    Cascade, Error, FoamConfig, Interpolation, OceanConfig, OceanState, QueryConfig, SeaState,
    Spectrum, SurfaceSample,
};

/// Euclidean length of a 3-vector.
fn length3(v: [f32; 3]) -> f32 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// Distance between two horizontal vectors `[x, z]`.
fn distance2(a: [f32; 2], b: [f32; 2]) -> f32 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// Sum of two horizontal vectors `[x, z]`.
fn add2(a: [f32; 2], b: [f32; 2]) -> [f32; 2] {
    [a[0] + b[0], a[1] + b[1]]
}

fn small_config() -> OceanConfig {
    OceanConfig {
        size: 64,
        ..OceanConfig::default()
    }
}

fn ocean(config: OceanConfig) -> OceanState {
    let spectrum = Spectrum::jonswap(10.0, 100_000.0)
        .and_then(|s| s.with_wind_direction(0.5))
        .expect("valid spectrum");
    OceanState::new(spectrum, config).expect("valid ocean")
}

#[test]
fn cascades_split_the_band_without_gaps_or_overlap_and_keep_all_the_energy() {
    let spectrum = Spectrum::jonswap(10.0, 100_000.0).unwrap();
    for size in [64, 256] {
        let config = OceanConfig {
            size,
            ..OceanConfig::default()
        };
        let ocean = OceanState::new(spectrum.clone(), config.clone()).unwrap();
        let bands = config.bands().unwrap();
        assert_eq!(ocean.cascades().len(), 3);
        for pair in bands.windows(2) {
            assert_eq!(pair[0].1, pair[1].0, "bands must meet exactly");
        }
        // Every nonzero h0 of a cascade lies inside its own band, so no wave vector is
        // counted by two cascades.
        for (cascade, &(lo, hi)) in ocean.cascades().iter().zip(&bands) {
            let n = cascade.size();
            let dk = std::f64::consts::TAU / f64::from(cascade.length());
            let m = |i: usize| {
                if i < n / 2 {
                    i as f64
                } else {
                    i as f64 - n as f64
                }
            };
            let (lo, hi) = (f64::from(lo), f64::from(hi));
            for j in 0..n {
                for i in 0..n {
                    let k = (m(i) * dk).hypot(m(j) * dk);
                    if cascade.h0()[j * n + i] != Default::default() {
                        assert!(k >= lo && k < hi, "h0 outside band at |k| = {k}");
                    }
                }
            }
        }
        // Σ S(k)Δk² of all cascades against the quadrature of S over the whole band
        // (Simpson in ln k, independent of any grid). The difference is the grids' Riemann
        // error: measured 0.05 % at N = 256 and 0.9 % at N = 64; the issue allows 2 %.
        let whole = f64::from(spectrum.band_variance(bands[0].0, bands[2].1));
        let sum = ocean.diagnostics().expected_variance();
        let ratio = sum / whole;
        println!("N = {size}: Σ S Δk² / ∫ S = {ratio}");
        assert!((ratio - 1.0).abs() < 0.02, "N = {size}: ratio {ratio}");
        // The band reaches past the spectrum's energy: at least 99 % of the total variance.
        let total = f64::from(spectrum.significant_wave_height() / 4.0).powi(2);
        assert!(whole / total > 0.99, "band holds {}", whole / total);
    }
}

/// Bilinear sample of one cascade at world (x, z), written out independently of the crate:
/// wrap by subtracting whole periods, then interpolate the four neighbours.
fn reference_height(cascade: &Cascade, x: f64, z: f64) -> f64 {
    let n = cascade.size();
    let l = f64::from(cascade.length());
    let wrap = |v: f64| v - (v / l).floor() * l;
    let (gx, gz) = (wrap(x) / l * n as f64, wrap(z) / l * n as f64);
    let (ix, iz) = (gx.floor() as usize, gz.floor() as usize);
    let (fx, fz) = (gx - gx.floor(), gz - gz.floor());
    let h = |i: usize, j: usize| f64::from(cascade.height()[(j % n) * n + (i % n)]);
    h(ix, iz) * (1.0 - fx) * (1.0 - fz)
        + h(ix + 1, iz) * fx * (1.0 - fz)
        + h(ix, iz + 1) * (1.0 - fx) * fz
        + h(ix + 1, iz + 1) * fx * fz
}

/// The cubic B-spline coefficients of a periodic N×N field (z rows), by a separable DFT:
/// along each axis C(k) = F(k) · 6/(4 + 2 cos(2πk/N)), the inverse of the spline's sampled
/// kernel (1, 4, 1)/6 — independent of the library's recursive filter.
fn spline_coefficients(values: &[f64], n: usize) -> Vec<f64> {
    use std::f64::consts::TAU;
    let line = |f: &[f64]| -> Vec<f64> {
        (0..n)
            .map(|p| {
                let mut sum = 0.0;
                for k in 0..n {
                    let (mut re, mut im) = (0.0, 0.0);
                    for (q, &v) in f.iter().enumerate() {
                        let phase = -TAU * (k * q) as f64 / n as f64;
                        re += v * phase.cos();
                        im += v * phase.sin();
                    }
                    let gain = 6.0 / (4.0 + 2.0 * (TAU * k as f64 / n as f64).cos());
                    let phase = TAU * (k * p) as f64 / n as f64;
                    sum += gain * (re * phase.cos() - im * phase.sin());
                }
                sum / n as f64
            })
            .collect()
    };
    let mut rows: Vec<f64> = values.chunks(n).flat_map(line).collect();
    for i in 0..n {
        let column: Vec<f64> = (0..n).map(|j| rows[j * n + i]).collect();
        for (j, v) in line(&column).into_iter().enumerate() {
            rows[j * n + i] = v;
        }
    }
    rows
}

/// The centred cubic B-spline β³(t) (textbook piecewise form).
fn beta3(t: f64) -> f64 {
    let a = t.abs();
    if a < 1.0 {
        2.0 / 3.0 - a * a + a * a * a / 2.0
    } else if a < 2.0 {
        (2.0 - a).powi(3) / 6.0
    } else {
        0.0
    }
}

/// Σ c[a, b] β³(g_x − a) β³(g_z − b) at world (x, z) over a periodic grid of side `length`.
fn spline_value(c: &[f64], n: usize, length: f64, x: f64, z: f64) -> f64 {
    let wrap = |v: f64| v - (v / length).floor() * length;
    let (gx, gz) = (wrap(x) / length * n as f64, wrap(z) / length * n as f64);
    let (ix, iz) = (gx.floor() as i64, gz.floor() as i64);
    let mut sum = 0.0;
    for b in iz - 2..=iz + 3 {
        for a in ix - 2..=ix + 3 {
            let w = beta3(gx - a as f64) * beta3(gz - b as f64);
            if w != 0.0 {
                let (i, j) = (
                    a.rem_euclid(n as i64) as usize,
                    b.rem_euclid(n as i64) as usize,
                );
                sum += w * c[j * n + i];
            }
        }
    }
    sum
}

#[test]
fn sample_is_the_sum_of_cubic_spline_cascades_through_the_grid_values() {
    let mut state = ocean(OceanConfig {
        size: 32,
        ..small_config()
    });
    state.step(4.2).unwrap();
    // Per cascade: the spline coefficients of η, D_x and ∂y/∂z by the DFT above.
    let fields: Vec<[Vec<f64>; 3]> = state
        .cascades()
        .iter()
        .map(|c| {
            let n = c.size();
            let eta: Vec<f64> = c.height().iter().map(|&v| f64::from(v)).collect();
            let dx: Vec<f64> = c.displacement().iter().map(|d| f64::from(d[0])).collect();
            let sz: Vec<f64> = c.slope().iter().map(|s| f64::from(s[1])).collect();
            [
                spline_coefficients(&eta, n),
                spline_coefficients(&dx, n),
                spline_coefficients(&sz, n),
            ]
        })
        .collect();
    let points = [
        (0.0, 0.0),
        (12.34, -56.78),
        (-1234.5, 987.25),
        (999.99, 230.0),
        (5.1e5, -7.3e5),
        (1.6, 3.2),
    ];
    for &(x, z) in &points {
        let s = state.water().at_rest(x, z).unwrap();
        let reference = |field: usize| -> f64 {
            state
                .cascades()
                .iter()
                .zip(&fields)
                .map(|(c, f)| spline_value(&f[field], c.size(), f64::from(c.length()), x, z))
                .sum()
        };
        // f32 coefficients and weights against f64: a few ulps of the ~1 m fields.
        assert!(
            (f64::from(s.height) - reference(0)).abs() < 2e-5,
            "({x}, {z}): height {} vs {}",
            s.height,
            reference(0)
        );
        assert!((f64::from(s.displacement[0]) - reference(1)).abs() < 2e-5);
        assert!((f64::from(s.slope[1]) - reference(2)).abs() < 2e-5);
    }
    // Through the grid values: at a grid point of every cascade (the origin) the sample is
    // the sum of the buffers.
    let s = state.water().at_rest(0.0, 0.0).unwrap();
    let at_nodes: f32 = state.cascades().iter().map(|c| c.height()[0]).sum();
    assert!((s.height - at_nodes).abs() < 1e-5);
}

#[test]
fn sample_is_the_sum_of_bilinear_cascades_and_wraps_at_any_coordinate() {
    let mut config = small_config();
    config.query.interpolation = Interpolation::Bilinear;
    let mut state = ocean(config);
    state.step(4.2).unwrap();
    let points = [
        (0.0, 0.0),
        (12.34, -56.78),
        (-1234.5, 987.25),
        (999.99, 230.0),
        (5.1e5, -7.3e5),
    ];
    for &(x, z) in &points {
        let s = state.water().at_rest(x, z).unwrap();
        let reference: f64 = state
            .cascades()
            .iter()
            .map(|c| reference_height(c, x, z))
            .sum();
        // f32 bilinear weights against f64: a few ulps of the ~1 m heights.
        assert!((f64::from(s.height) - reference).abs() < 1e-5, "({x}, {z})");
        assert!((length3(s.normal) - 1.0).abs() < 1e-5 && s.normal[1] > 0.0);
    }
    // The lengths 1000, 230 and 51 m share the period lcm = 1 173 000 m: the summed
    // surface must repeat there, at coordinates where f32 would have a 0.125 m step — more
    // than half the smallest cascade's 0.2 m grid spacing — and on the negative side too.
    let period = 1_173_000.0;
    for &(x, z) in &points[..4] {
        let base = state.water().at_rest(x, z).unwrap();
        for (ox, oz) in [(period, 0.0), (0.0, -period), (-period, period)] {
            let far = state.water().at_rest(x + ox, z + oz).unwrap();
            assert!(
                (far.height - base.height).abs() < 1e-5,
                "({x}+{ox}, {z}+{oz})"
            );
            assert!(distance2(far.displacement, base.displacement) < 1e-5);
            assert!(distance2(far.slope, base.slope) < 1e-4);
        }
    }
    // Small waves survive far away: a 2 cm move at x ≈ 1e6 m changes the height as it
    // does near the origin (in f32 coordinates both samples would land in the same spot).
    let near = state.water().at_rest(3.0, 4.0).unwrap().height
        - state.water().at_rest(3.02, 4.0).unwrap().height;
    let far = state.water().at_rest(3.0 + period, 4.0).unwrap().height
        - state.water().at_rest(3.02 + period, 4.0).unwrap().height;
    assert!(near != 0.0);
    assert!((near - far).abs() < 1e-5, "near {near} far {far}");
}

#[test]
fn height_at_inverts_the_displacement_like_a_brute_force_search() {
    let config = OceanConfig {
        size: 64,
        choppiness: 1.0,
        ..OceanConfig::default()
    };
    let mut state = ocean(config);
    state.step(7.0).unwrap();
    let mut worst = 0.0f32;
    let mut moved = 0.0f32;
    for &(px, pz) in &[(3.0, 4.0), (-250.5, 77.7), (640.0, -1000.2), (1.0e6, 3.3)] {
        let y = state.water().height_at(px, pz).unwrap();
        let found = state.water().locate(px, pz).unwrap();
        let (x0, miss) = (found.undisplaced, found.miss);
        assert!(
            found.converged,
            "fixed point did not converge: miss {miss} m"
        );
        // Brute force: scan undisplaced points on a 1 cm grid around the query (the
        // displacement here is below 1.5 m) and keep the one whose water lands closest.
        let (mut best, mut best_y) = (f64::INFINITY, 0.0f32);
        let step = 0.01;
        let reach = 150;
        for a in -reach..=reach {
            for b in -reach..=reach {
                let (x, z) = (px + f64::from(a) * step, pz + f64::from(b) * step);
                let s = state.water().at_rest(x, z).unwrap();
                let landed = (
                    x + f64::from(s.displacement[0]),
                    z + f64::from(s.displacement[1]),
                );
                let d = (landed.0 - px).hypot(landed.1 - pz);
                if d < best {
                    best = d;
                    best_y = s.height;
                }
            }
        }
        // The search lands within ~0.7 cm (half a diagonal of its grid, stretched by the
        // displacement map); the surface slope is below ~0.5, so heights agree to ~4 mm.
        assert!(best < 0.01, "brute force missed by {best} m");
        worst = worst.max((y - best_y).abs());
        moved = moved.max(((x0[0] - px).hypot(x0[1] - pz)) as f32);
        assert!(
            (y - best_y).abs() < 5e-3,
            "height_at {y} vs brute force {best_y}"
        );
    }
    assert!(
        moved > 0.05,
        "the test needs displaced points (moved {moved} m)"
    );
    println!("height_at vs brute force: worst {worst} m");
}

#[test]
fn searches_on_the_default_sea_mostly_end_after_one_newton_step() {
    // The first guess (a Newton step on the long waves, less the short waves' displacement
    // where it lands) starts within millimetres, so one Newton step on every cascade
    // reaches the 0.1 mm tolerance for most points; from the long waves' step alone (2.5 cm
    // away) about half the points needed a second. 2000 points make the share good to ±2 %.
    let mut state = ocean(OceanConfig::default());
    state.step(3.0).unwrap();
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2000.0 - 1000.0
    };
    let mut steps = [0usize; 4];
    for _ in 0..2000 {
        let found = state.water().locate(next(), next()).unwrap();
        assert!(found.converged, "miss {} m", found.miss);
        assert!(found.iterations <= 3, "{} steps", found.iterations);
        steps[found.iterations] += 1;
    }
    let one = steps[0] + steps[1];
    assert!(one >= 1700, "steps taken (0, 1, 2, 3): {steps:?}");
    println!("steps taken (0, 1, 2, 3) by 2000 points: {steps:?}");
}

#[test]
fn batch_queries_equal_single_queries() {
    let points: Vec<[f64; 2]> = (0..500)
        .map(|i| {
            [
                f64::from(i) * 3.7 - 900.0,
                f64::from(i * i % 97) * 11.0 - 400.0,
            ]
        })
        .collect();
    // A tolerance of 10 m ends every search at its first guess, and one iteration every
    // search after its first step (asserted below): `heights_at` does not read the heights
    // at a search's first evaluation, so those heights come from its last pass instead.
    let configs = [
        (small_config(), None),
        (
            OceanConfig {
                query: QueryConfig {
                    tolerance: 10.0,
                    ..QueryConfig::default()
                },
                ..small_config()
            },
            Some(0),
        ),
        (
            OceanConfig {
                query: QueryConfig {
                    tolerance: 1e-9,
                    max_iterations: 1,
                    ..QueryConfig::default()
                },
                ..small_config()
            },
            Some(1),
        ),
    ];
    for (config, iterations) in configs {
        let mut state = ocean(config);
        state.step(2.0).unwrap();
        if let Some(iterations) = iterations {
            for p in &points {
                let location = state.water().locate(p[0], p[1]).unwrap();
                assert_eq!(location.iterations, iterations, "{p:?}");
            }
        }
        batch_equals_single(&state, &points);
    }
}

fn batch_equals_single(state: &OceanState, points: &[[f64; 2]]) {
    // 500 points go through the pool, 5 through the calling thread.
    for count in [500, 5] {
        let points = &points[..count];
        let mut heights = vec![0.0; count];
        let mut samples = vec![SurfaceSample::default(); count];
        let mut surfaces = vec![SurfaceSample::default(); count];
        state.water().heights_at(points, &mut heights).unwrap();
        state.water().at_rest_many(points, &mut samples).unwrap();
        state.water().surfaces_at(points, &mut surfaces).unwrap();
        for (((p, h), s), w) in points.iter().zip(&heights).zip(&samples).zip(&surfaces) {
            assert_eq!(
                h.to_bits(),
                state.water().height_at(p[0], p[1]).unwrap().to_bits()
            );
            assert_eq!(*s, state.water().at_rest(p[0], p[1]).unwrap());
            assert_eq!(*w, state.water().surface_at(p[0], p[1]).unwrap());
        }
    }
}

#[test]
fn parallel_and_sequential_cascade_updates_agree_bit_for_bit() {
    let mut a = ocean(OceanConfig {
        parallel_cascades: false,
        ..small_config()
    });
    let mut b = ocean(OceanConfig {
        parallel_cascades: true,
        ..small_config()
    });
    for _ in 0..5 {
        a.step(0.25).unwrap();
        b.step(0.25).unwrap();
    }
    for (ca, cb) in a.cascades().iter().zip(b.cascades()) {
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(ca.height()), bits(cb.height()));
        assert_eq!(bits(ca.jacobian()), bits(cb.jacobian()));
    }
    assert_eq!(a.foam_view().total(), b.foam_view().total());
    assert_eq!(a.foam_view().breaking(), b.foam_view().breaking());
}

#[test]
fn set_time_reaches_the_same_waves_as_stepping() {
    let mut stepped = ocean(small_config());
    for _ in 0..4 {
        stepped.step(0.5).unwrap();
    }
    let mut jumped = ocean(small_config());
    jumped.set_time(2.0).unwrap();
    assert_eq!(stepped.time(), jumped.time());
    assert_eq!(
        stepped.cascades()[1].height(),
        jumped.cascades()[1].height()
    );
    assert!(jumped.foam_view().total().iter().all(|&f| f == 0.0));
}

#[test]
fn presets_build_and_grow_with_the_wind() {
    let mut heights = Vec::new();
    for preset in SeaState::ALL {
        let (spectrum, mut config) = preset.build();
        config.size = 64;
        let hs = spectrum.significant_wave_height();
        let state = OceanState::new(spectrum, config).unwrap();
        // The cascades hold the sea's energy: 4√(Σ S Δk²) within 3 % of the quadrature Hs.
        let simulated = 4.0 * state.diagnostics().expected_variance().sqrt() as f32;
        assert!(
            (simulated / hs - 1.0).abs() < 0.03,
            "{}: {simulated} vs {hs}",
            preset.name()
        );
        heights.push((preset, hs));
    }
    // Calm < moderate breeze < fresh breeze < storm, as their wind speeds.
    for pair in heights[..4].windows(2) {
        assert!(pair[0].1 < pair[1].1, "{:?} vs {:?}", pair[0], pair[1]);
        assert!(pair[0].0.wind_speed() < pair[1].0.wind_speed());
    }
    let names: std::collections::HashSet<_> = SeaState::ALL.iter().map(|s| s.name()).collect();
    assert_eq!(names.len(), SeaState::ALL.len());
}

#[test]
fn bad_input_is_an_error_and_leaves_the_state_alone() {
    let spectrum = Spectrum::pierson_moskowitz(8.0).unwrap();
    let bad_configs = [
        OceanConfig {
            lengths: vec![],
            ..small_config()
        },
        OceanConfig {
            lengths: vec![100.0, 200.0],
            ..small_config()
        },
        OceanConfig {
            lengths: vec![100.0, f32::NAN],
            ..small_config()
        },
        OceanConfig {
            size: 63,
            ..small_config()
        },
        OceanConfig {
            choppiness: -1.0,
            ..small_config()
        },
        OceanConfig {
            k_min: 1.0,
            k_max: 0.5,
            ..small_config()
        },
        OceanConfig {
            k_max: 1e-4,
            ..small_config()
        },
        OceanConfig {
            foam: FoamConfig {
                active_decay: 0.0,
                ..FoamConfig::default()
            },
            ..small_config()
        },
        OceanConfig {
            foam: FoamConfig {
                coverage: f32::INFINITY,
                ..FoamConfig::default()
            },
            ..small_config()
        },
        OceanConfig {
            repeat_period: Some(-2.0),
            ..small_config()
        },
        OceanConfig {
            repeat_period: Some(2e6),
            ..small_config()
        },
        OceanConfig {
            band_split: 0.0,
            ..small_config()
        },
        OceanConfig {
            band_split: 1.5,
            ..small_config()
        },
        OceanConfig {
            foam: FoamConfig {
                coverage: 101.0,
                ..FoamConfig::default()
            },
            ..small_config()
        },
        OceanConfig {
            foam: FoamConfig {
                drift: 1.5,
                ..FoamConfig::default()
            },
            ..small_config()
        },
        OceanConfig {
            foam: FoamConfig {
                residual_decay: 2e6,
                ..FoamConfig::default()
            },
            ..small_config()
        },
        OceanConfig {
            foam: FoamConfig {
                streak_width: 0.6,
                streak_length: 0.5,
                ..FoamConfig::default()
            },
            ..small_config()
        },
        OceanConfig {
            foam: FoamConfig {
                wind_speed: Some(-1.0),
                ..FoamConfig::default()
            },
            ..small_config()
        },
        OceanConfig {
            query: QueryConfig {
                max_iterations: 0,
                ..QueryConfig::default()
            },
            ..small_config()
        },
        OceanConfig {
            query: QueryConfig {
                tolerance: 0.0,
                ..QueryConfig::default()
            },
            ..small_config()
        },
        OceanConfig {
            memory_limit: 1000,
            ..small_config()
        },
    ];
    for config in bad_configs {
        let result = OceanState::new(spectrum.clone(), config.clone());
        assert!(result.is_err(), "{config:?} was accepted");
        // bands() checks the config first and gives the same error.
        assert_eq!(config.bands().err(), result.err(), "{config:?}: bands()");
    }
    let mut state = OceanState::new(spectrum, small_config()).unwrap();
    state.step(1.0).unwrap();
    let before = state.cascades()[0].height().to_vec();
    assert_eq!(state.step(f64::NAN), Err(Error::NonFinite { name: "dt" }));
    assert!(matches!(
        state.step(-0.1),
        Err(Error::OutOfRange { name: "dt", .. })
    ));
    assert!(matches!(
        state.step(1e5),
        Err(Error::OutOfRange { name: "dt", .. })
    ));
    assert!(state.set_time(f64::INFINITY).is_err());
    assert!(state.set_time(2e9).is_err());
    assert!(state.set_choppiness(f32::NAN).is_err());
    assert_eq!(state.time(), 1.0);
    assert_eq!(state.cascades()[0].height(), &before[..]);
    assert!(state.water().at_rest(f64::NAN, 0.0).is_err());
    assert!(state.water().height_at(0.0, f64::INFINITY).is_err());
    let mut out = vec![0.0; 2];
    assert_eq!(
        state.water().heights_at(&[[0.0, 0.0]], &mut out),
        Err(Error::LengthMismatch {
            name: "out",
            expected: 1,
            got: 2
        })
    );
    assert!(state
        .water()
        .heights_at(&[[0.0, 0.0], [f64::NAN, 1.0]], &mut out)
        .is_err());
    assert_eq!(out, vec![0.0, 0.0]);
    // A step that would carry the time past Cascade::MAX_TIME is refused and changes nothing;
    // one that reaches it exactly is fine.
    state.set_time(Cascade::MAX_TIME - 1.0).unwrap();
    let before = state.cascades()[0].height().to_vec();
    assert_eq!(
        state.step(2.0),
        Err(Error::OutOfRange {
            name: "time + dt",
            value: Cascade::MAX_TIME + 1.0,
            min: Bound::Included(-Cascade::MAX_TIME),
            max: Bound::Included(Cascade::MAX_TIME),
        })
    );
    assert_eq!(state.time(), Cascade::MAX_TIME - 1.0);
    assert_eq!(state.cascades()[0].height(), &before[..]);
    state.step(1.0).unwrap();
    assert_eq!(state.time(), Cascade::MAX_TIME);
}

#[test]
fn outputs_stay_finite_in_a_folding_storm() {
    let (spectrum, mut config) = SeaState::Storm.build();
    config.size = 64;
    config.choppiness = 8.0;
    let mut state = OceanState::new(spectrum, config).unwrap();
    for _ in 0..10 {
        state.step(0.5).unwrap();
    }
    let folded = state.cascades()[0].jacobian().iter().any(|&j| j < 0.0);
    assert!(folded, "choppiness 8 should fold the storm's surface");
    for c in state.cascades() {
        assert!(c.height().iter().all(|v| v.is_finite()));
        assert!(c.slope().iter().flatten().all(|v| v.is_finite()));
        assert!(c.normal().iter().flatten().all(|v| v.is_finite()));
    }
    assert!(state
        .foam_view()
        .total()
        .iter()
        .all(|v| (0.0..=1.0).contains(v)));
    let y = state.water().height_at(100.0, 100.0).unwrap();
    assert!(y.is_finite());
}

#[test]
fn ocean_state_can_be_shared_between_threads() {
    fn send_sync<T: Send + Sync>() {}
    send_sync::<OceanState>();
    send_sync::<SurfaceSample>();
    // Queries from several threads at once agree with the same queries on this thread.
    let mut state = ocean(small_config());
    state.step(1.5).unwrap();
    let here: Vec<f32> = (0..4)
        .map(|i| state.water().height_at(f64::from(i) * 10.0, 5.0).unwrap())
        .collect();
    let there: Vec<f32> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..4)
            .map(|i| {
                let state = &state;
                scope.spawn(move || state.water().height_at(f64::from(i) * 10.0, 5.0).unwrap())
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert_eq!(here, there);
}

#[test]
fn a_refused_choppiness_changes_no_cascade() {
    // λ = 1e12 would let the fields overflow f32 (the amplitude bound): refused, and every
    // cascade keeps its choppiness. (This sea is so steep, σ about 130, that its largest
    // choppiness is 0.03: it is built at 0.01.)
    let spectrum = Spectrum::phillips(30.0, 1e3).unwrap();
    let config = OceanConfig {
        choppiness: 0.01,
        ..small_config()
    };
    let mut state = OceanState::new(spectrum, config).unwrap();
    let before: Vec<f32> = state
        .cascades()
        .iter()
        .map(|c| c.config().choppiness)
        .collect();
    assert!(matches!(
        state.set_choppiness(1e12),
        Err(Error::AmplitudeTooLarge { .. })
    ));
    let after: Vec<f32> = state
        .cascades()
        .iter()
        .map(|c| c.config().choppiness)
        .collect();
    assert_eq!(before, after);
    assert_eq!(state.config().choppiness, 0.01);
    // Above the largest choppiness: refused too, nothing changed.
    assert!(matches!(
        state.set_choppiness(1.0),
        Err(Error::OutOfRange {
            name: "choppiness",
            ..
        })
    ));
    assert_eq!(state.config().choppiness, 0.01);
    state.set_choppiness(0.02).unwrap();
    assert!(state
        .cascades()
        .iter()
        .all(|c| c.config().choppiness == 0.02));
}

#[test]
fn sampling_a_subset_of_cascades_adds_up_to_the_whole() {
    let mut state = ocean(small_config());
    state.step(3.3).unwrap();
    for &(x, z) in &[(1.0, 2.0), (-345.6, 789.1), (2.5e5, -1.0e5)] {
        let whole = state.water().at_rest(x, z).unwrap();
        let parts = [
            state.water().at_rest_cascades(x, z, 0..1).unwrap(),
            state.water().at_rest_cascades(x, z, 1..2).unwrap(),
            state.water().at_rest_cascades(x, z, 2..3).unwrap(),
        ];
        // Height, displacement and slope are sums over cascades: the parts add up to the
        // whole up to f32 rounding of the ~1 m values.
        let height: f32 = parts.iter().map(|p| p.height).sum();
        assert!((height - whole.height).abs() < 1e-5);
        let slope = add2(add2(parts[0].slope, parts[1].slope), parts[2].slope);
        assert!(distance2(slope, whole.slope) < 1e-5);
        assert_eq!(state.water().at_rest_cascades(x, z, 0..3).unwrap(), whole);
        let flat = state.water().at_rest_cascades(x, z, 1..1).unwrap();
        assert_eq!(flat.height, 0.0);
        assert_eq!(flat.normal, [0.0, 1.0, 0.0]);
    }
    assert_eq!(
        state.water().at_rest_cascades(0.0, 0.0, 0..4),
        Err(Error::CountOutOfRange {
            name: "cascades.end",
            count: 4,
            min: 0,
            max: 3
        })
    );
    // A range must not end before it starts.
    let (start, end) = (2, 1);
    assert_eq!(
        state.water().at_rest_cascades(0.0, 0.0, start..end),
        Err(Error::CountOutOfRange {
            name: "cascades.end",
            count: 1,
            min: 2,
            max: 3
        })
    );
    assert!(state.water().at_rest_cascades(f64::NAN, 0.0, 0..1).is_err());
}
