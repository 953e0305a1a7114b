//! Tests of the foam's detail (`detail.rs`): the quantile table, the ramp's mean, the
//! standardised compression, the streak field and its drift.
// The references use the standard library's exponential: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

use super::*;
use crate::math::determinism::Std;
use crate::ocean::OceanState;
use crate::presets::SeaState;

/// E[ρ] by Simpson's rule on steps of 1e-4 over the ramp and the tail beyond it,
/// independent of the table's cumulative sums.
fn expected_ramp(q: f64, w: f64) -> f64 {
    let phi = |t: f64| (-0.5 * t * t).exp() / std::f64::consts::TAU.sqrt();
    let ramp = |t: f64| ((t - q) / (2.0 * w) + 0.5).clamp(0.0, 1.0);
    let simpson = |a: f64, b: f64, f: &dyn Fn(f64) -> f64| {
        let n = (((b - a) / 1e-4).ceil() as usize).max(2) / 2 * 2;
        let h = (b - a) / n as f64;
        let mut sum = f(a) + f(b);
        for i in 1..n {
            sum += f(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
        }
        sum * h / 3.0
    };
    simpson(q - w, q + w, &|t| ramp(t) * phi(t)) + simpson(q + w, 12.0, &phi)
}

/// The table's E(q) against an independent quadrature, and its inverse against E: the
/// trapezoidal sums on steps of 1/256 are exact to about h²/12·max|φ'| ≈ 4e-7 absolute.
#[test]
fn quantile_table_matches_an_independent_integral() {
    for edge in [ACTIVE_EDGE, RESIDUAL_EDGE] {
        let table = Quantiles::new::<Std>(edge);
        let w = f64::from(table.edge);
        for q in [-3.0, -1.0, 0.0, 0.7, 2.0, 3.5, 5.0] {
            let i = ((q - f64::from(table.first)) / STEP).round() as usize;
            // The table's own node (0.7 is not one).
            let q = f64::from(table.first) + i as f64 * STEP;
            let expected = expected_ramp(q, w);
            let got = f64::from(table.mean[i]);
            assert!(
                (got - expected).abs() < 2e-6 + 1e-4 * expected,
                "w {w} q {q}: table {got}, quadrature {expected}"
            );
            let back = f64::from(table.threshold(expected as f32));
            assert!((back - q).abs() < 2e-3, "w {w} q {q}: inverse {back}");
        }
        assert_eq!(table.threshold(0.0), f32::INFINITY);
        assert_eq!(table.threshold(f32::NAN), f32::INFINITY);
        assert_eq!(table.threshold(1.0), f32::NEG_INFINITY);
        assert_eq!(table.ramp(100.0, 0.0), 0.0);
        assert_eq!(table.ramp(-100.0, 1.0), 1.0);
    }
}

/// The ramp at the tabulated threshold keeps the fraction in expectation: its mean over
/// 10⁶ standard normal draws is the fraction within five standard errors (the ramp's
/// variance is at most f(1 − f)).
#[test]
fn ramp_keeps_the_fraction_in_expectation() {
    let table = Quantiles::new::<Std>(ACTIVE_EDGE);
    let draws: Vec<f32> = (0..500_000)
        .flat_map(|i| {
            let (a, b) = crate::math::rng::gaussian_pair::<Std>(39, i, 7);
            [a as f32, b as f32]
        })
        .collect();
    for fraction in [0.001f32, 0.02, 0.1, 0.5, 0.9] {
        let mean = draws
            .iter()
            .map(|&t| f64::from(table.ramp(t, fraction)))
            .sum::<f64>()
            / draws.len() as f64;
        let f = f64::from(fraction);
        let error = (f * (1.0 - f) / draws.len() as f64).sqrt();
        assert!((mean - f).abs() < 5.0 * error, "{fraction}: mean {mean}");
    }
}

/// The standardised compression of the finer cascades, sampled at 2·10⁵ points over
/// 730 m × 630 m of both seas, has mean 0 and variance 1 (each within 0.03: the points
/// hold some 10⁴ independent waves of the cascades ≥ 1, standard error below 0.015) and
/// exceeds 1 and 2 as often as a standard normal does, within 4 % and 12 % (the
/// Cornish–Fisher term leaves a residual skewness of about 0.03, which moves the tail
/// at 2 by about 5 %); without the skewness term the storm's tail at 2 was 11 % low.
#[test]
fn standardised_compression_is_standard_normal() {
    for sea in [SeaState::FreshBreeze, SeaState::Storm] {
        let (spectrum, config) = sea.build();
        let mut ocean = OceanState::new(spectrum, config).unwrap();
        ocean.pre_roll(20.0, 0.1).unwrap();
        let foam = &ocean.foam;
        let variance = foam.sea.unresolved_compression();
        let (mut m1, mut m2, mut count) = (0.0f64, 0.0, 0.0);
        let mut exceed = [0.0f64; 2];
        for k in 0..200_000u32 {
            let (x, z) = (f64::from(k % 1000) * 0.731, f64::from(k / 1000) * 3.17);
            let detail = &foam.detail;
            let u = detail.compression_at(&ocean.cascades, variance, x, z);
            let u = f64::from(u.unwrap());
            m1 += u;
            m2 += u * u;
            for (e, q) in exceed.iter_mut().zip([1.0, 2.0]) {
                *e += f64::from(u8::from(u > q));
            }
            count += 1.0;
        }
        let (mean, var) = (m1 / count, m2 / count - (m1 / count).powi(2));
        let exceed = exceed.map(|e| e / count);
        assert!(
            mean.abs() < 0.03 && (var - 1.0).abs() < 0.03,
            "{sea:?}: {mean} {var}"
        );
        assert!(
            (exceed[0] / 0.158_655 - 1.0).abs() < 0.04,
            "{sea:?}: {exceed:?}"
        );
        assert!(
            (exceed[1] / 0.022_750 - 1.0).abs() < 0.12,
            "{sea:?}: {exceed:?}"
        );
    }
}

/// The streak field at any point has unit variance (within 0.03 over 2·10⁵ points of a
/// 256 m × 128 m tile) and its correlation falls to 1/e within 1.5 m across the wind but
/// only beyond 6 m along it, whatever the wind's direction.
#[test]
fn streaks_are_long_along_the_wind_and_thin_across() {
    for direction in [0.0f32, 0.6, -2.0] {
        let (spectrum, config) = SeaState::FreshBreeze.build();
        let spectrum = spectrum.with_wind_direction(direction).unwrap();
        let ocean = OceanState::new(spectrum, config).unwrap();
        let detail = &ocean.foam.detail;
        let (c, s) = (f64::from(direction).cos(), f64::from(direction).sin());
        let at = |along: f64, across: f64| {
            f64::from(detail.streak_at(along * c - across * s, along * s + across * c))
        };
        let points: Vec<(f64, f64)> = (0..200_000u32)
            .map(|k| (f64::from(k % 400) * 1.37, f64::from(k / 400) * 0.613))
            .collect();
        let correlation = |da: f64, dc: f64| {
            points
                .iter()
                .map(|&(a, b)| at(a, b) * at(a + da, b + dc))
                .sum::<f64>()
                / points.len() as f64
        };
        let variance = correlation(0.0, 0.0);
        assert!((variance - 1.0).abs() < 0.03, "{direction}: {variance}");
        let e = (-1.0f64).exp();
        assert!(correlation(0.0, 1.5) < e * variance, "{direction}");
        assert!(correlation(6.0, 0.0) > e * variance, "{direction}");
    }
}

/// Residual foam's detail moves with the surface layer: after 10 s of steps the streak
/// field at a point displaced by the drift holds the value the point had (to f32
/// rounding of the interpolation weights), and the field has moved, not stayed put.
#[test]
fn streaks_drift_with_the_water() {
    let (spectrum, mut config) = SeaState::FreshBreeze.build();
    config.size = 64;
    let spectrum = spectrum.with_wind_direction(0.4).unwrap();
    let mut ocean = OceanState::new(spectrum, config).unwrap();
    let drift = ocean.foam.transport.drift;
    assert!(drift[0] > 0.1 && drift[1] > 0.05, "{drift:?}");
    let points: Vec<(f64, f64)> = (0..500).map(|k| (f64::from(k) * 0.37, 5.0)).collect();
    let before: Vec<f32> = points
        .iter()
        .map(|&(x, z)| ocean.foam.detail.streak_at(x, z))
        .collect();
    for _ in 0..100 {
        ocean.step(0.1).unwrap();
    }
    let mut moved = 0.0f32;
    for (&(x, z), &b) in points.iter().zip(&before) {
        let now = ocean
            .foam
            .detail
            .streak_at(x + 10.0 * drift[0], z + 10.0 * drift[1]);
        assert!((now - b).abs() < 1e-4, "({x}, {z}): {b} then {now}");
        moved = moved.max((ocean.foam.detail.streak_at(x, z) - b).abs());
    }
    assert!(moved > 0.1, "{moved}");
}

/// The streak field as a renderer samples it (`Textures::foam_streaks`), read the way a
/// shader does — f32 world coordinates, the wind frame's rotation, the origin, texel
/// centres half a texel in, repeat addressing, bilinear filtering and the variance
/// correction the docs give — equals `streak_at` after the streaks have drifted. The
/// shader's coordinates are f32 near 100 m (error ~1e-5 m, 4e-5 of a 0.25 m texel across)
/// and the field changes by at most a few units per texel, so 1e-3 bounds the difference.
#[test]
fn a_shader_reads_the_streaks_as_foam_at_does() {
    let (spectrum, mut config) = SeaState::Storm.build();
    config.size = 64;
    let spectrum = spectrum.with_wind_direction(2.3).unwrap();
    let mut ocean = OceanState::new(spectrum, config).unwrap();
    for _ in 0..50 {
        ocean.step(0.2).unwrap();
    }
    let streaks = ocean.textures().foam_streaks();
    assert_eq!(
        streaks.texels.len(),
        streaks.across_texels * streaks.along_texels
    );
    let shader = |x: f32, z: f32| -> f32 {
        let [a0, a1] = streaks.axis;
        let along = x * a0 + z * a1 - streaks.origin[1];
        let across = z * a0 - x * a1 - streaks.origin[0];
        let (nc, na) = (streaks.across_texels, streaks.along_texels);
        // Texture coordinates with the half texel, then the hardware's texel space.
        let u = across / (streaks.spacing[0] * nc as f32) + 0.5 / nc as f32;
        let v = along / (streaks.spacing[1] * na as f32) + 0.5 / na as f32;
        let (tu, tv) = (u * nc as f32 - 0.5, v * na as f32 - 0.5);
        let (iu, iv) = (tu.floor(), tv.floor());
        let (fu, fv) = (tu - iu, tv - iv);
        let texel = |i: f32, j: f32| {
            let i = (i as i64).rem_euclid(nc as i64) as usize;
            let j = (j as i64).rem_euclid(na as i64) as usize;
            streaks.texels[j * nc + i]
        };
        let row0 = texel(iu, iv) * (1.0 - fu) + texel(iu + 1.0, iv) * fu;
        let row1 = texel(iu, iv + 1.0) * (1.0 - fu) + texel(iu + 1.0, iv + 1.0) * fu;
        let kept = |f: f32, rho: f32| (1.0 - f) * (1.0 - f) + f * f + 2.0 * f * (1.0 - f) * rho;
        let [rc, ra] = streaks.neighbour_correlation;
        (row0 * (1.0 - fv) + row1 * fv) / (kept(fu, rc) * kept(fv, ra)).sqrt()
    };
    let mut spread = 0.0f32;
    for k in 0..3000 {
        let (x, z) = (f64::from(k) * 0.093 - 140.0, f64::from(k % 53) * 1.7 - 40.0);
        let expected = ocean.foam.detail.streak_at(x, z);
        let got = shader(x as f32, z as f32);
        assert!(
            (got - expected).abs() < 1e-3,
            "({x}, {z}): {got} vs {expected}"
        );
        spread = spread.max(expected.abs());
    }
    // The points cross many texels of a field of unit variance, not a flat patch.
    assert!(spread > 1.5, "{spread}");
}
