//! The cascade's physical conventions: waves travel downwind, the Jacobian is lowest at
//! crests, a single wave is a Gerstner trochoid with sharp crests, and looping repeats.
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

mod common;

use std::f64::consts::{PI, TAU};

use common::*;
use ocean_fft::inspect;
use ocean_fft::{Cascade, CascadeConfig, Spectrum, Spreading, GRAVITY};

const G: f64 = GRAVITY as f64;

/// Periodic cross-correlation Σ_x a(x) b(x + s) for integer shifts s = (sx, sz), |s| ≤ r.
fn best_shift(a: &[f64], b: &[f64], n: usize, r: i64) -> ((i64, i64), Vec<f64>) {
    let w = (2 * r + 1) as usize;
    let mut c = vec![0.0; w * w];
    for sz in -r..=r {
        for sx in -r..=r {
            let mut sum = 0.0;
            for j in 0..n {
                let jj = index_of(j as i64 + sz, n);
                for i in 0..n {
                    let ii = index_of(i as i64 + sx, n);
                    sum += a[j * n + i] * b[jj * n + ii];
                }
            }
            c[(sz + r) as usize * w + (sx + r) as usize] = sum;
        }
    }
    let best = (0..w * w).max_by(|&p, &q| c[p].total_cmp(&c[q])).unwrap();
    (((best % w) as i64 - r, (best / w) as i64 - r), c)
}

/// Vertex of the parabola through (−1, l), (0, m), (1, r): the sub-cell position of a maximum.
fn parabola_peak(l: f64, m: f64, r: f64) -> f64 {
    let d = l - 2.0 * m + r;
    if d < 0.0 {
        0.5 * (l - r) / d
    } else {
        0.0
    }
}

#[test]
fn waves_travel_downwind() {
    // Pierson–Moskowitz, U = 10 m/s: ω_p = 0.877 g/U = 0.86 rad/s, peak wavelength 2πg/ω_p² ≈
    // 83 m, phase speed g/ω_p ≈ 11.4 m/s. Grid N = 128 on L = 800 m: cell 6.25 m. With
    // dt = 2 s the peak waves move ≈ 23 m ≈ 3.6 cells: several cells (so the direction of an
    // integer shift is resolved to ≈ atan(0.5/3.6) ≈ 8°, better with the parabolic sub-cell
    // refinement), yet well under half a peak wavelength (no aliasing to the neighbouring
    // crest) and short enough that dispersion has not decorrelated the field.
    let (n, length, dt) = (128usize, 800.0f32, 2.0);
    let cell = f64::from(length) / n as f64;
    for theta_w in [0.0f32, 1.0, -2.3] {
        let spectrum = Spectrum::pierson_moskowitz(10.0)
            .unwrap()
            .with_wind_direction(theta_w)
            .unwrap();
        let mut cascade = Cascade::new(
            &spectrum,
            CascadeConfig {
                size: n,
                length,
                seed: 21,
                ..CascadeConfig::default()
            },
        )
        .unwrap();
        let t0 = 30.0;
        cascade.update(t0).unwrap();
        let a = to_f64(cascade.height());
        cascade.update(t0 + dt).unwrap();
        let b = to_f64(cascade.height());
        let r = 8;
        let ((sx, sz), c) = best_shift(&a, &b, n, r);
        assert!(sx.abs() < r && sz.abs() < r, "peak at the search edge");
        let w = (2 * r + 1) as usize;
        let at = |x: i64, z: i64| c[(z + r) as usize * w + (x + r) as usize];
        let fx = sx as f64 + parabola_peak(at(sx - 1, sz), at(sx, sz), at(sx + 1, sz));
        let fz = sz as f64 + parabola_peak(at(sx, sz - 1), at(sx, sz), at(sx, sz + 1));
        let wind = (f64::from(theta_w).cos(), f64::from(theta_w).sin());
        let projection = (fx * wind.0 + fz * wind.1) * cell;
        let angle = (fz.atan2(fx) - f64::from(theta_w) + PI).rem_euclid(TAU) - PI;
        let c_p = G / f64::from(spectrum.peak_omega());
        println!(
            "θw = {theta_w}: integer shift ({sx}, {sz}) cells, refined ({fx:.2}, {fz:.2}); \
             {:.1} m along the wind in {dt} s ({:.1} m/s; peak phase speed {c_p:.1} m/s); \
             angle to the wind {:.1}°",
            projection,
            projection / dt,
            angle.to_degrees()
        );
        assert!(projection > 0.0, "θw = {theta_w}: waves move upwind");
        assert!(
            angle.abs() < 20f64.to_radians(),
            "θw = {theta_w}: shift direction {:.1}° off the wind",
            angle.to_degrees()
        );
        // The speed is that of the energetic waves: between the phase speed of waves twice
        // as short as the peak (c_p/√2) and c_p·1.2 (longer waves carry little energy).
        let speed = projection / dt;
        assert!(
            speed > c_p / 2f64.sqrt() && speed < 1.2 * c_p,
            "speed {speed} vs c_p {c_p}"
        );
    }
}

#[test]
fn jacobian_is_anticorrelated_with_height() {
    // J − 1 ≈ λ(D_xx + D_zz) = −λ·(k-weighted η): lowest at crests. With λ = 1:
    for (spectrum, n, length) in [(jonswap(0.4), 128, 500.0), (phillips(-1.1), 64, 200.0)] {
        let mut cascade = Cascade::new(
            &spectrum,
            CascadeConfig {
                size: n,
                length,
                choppiness: 1.0,
                seed: 4,
                ..CascadeConfig::default()
            },
        )
        .unwrap();
        for t in [0.0, 12.0] {
            cascade.update(t).unwrap();
            let rho = correlation(&to_f64(cascade.height()), &to_f64(cascade.jacobian()));
            println!("N={n} t={t}: corr(η, J) = {rho:.3}");
            // Clearly negative: a sign error in the D_xx multipliers would make it positive.
            assert!(rho < -0.3, "corr(η, J) = {rho}");
        }
    }
}

/// Radius-inverse of the circle through three points (the discrete curvature).
fn curvature(p: [(f64, f64); 3]) -> f64 {
    let d = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).hypot(a.1 - b.1);
    let area2 =
        ((p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1)).abs();
    2.0 * area2 / (d(p[0], p[1]) * d(p[1], p[2]) * d(p[0], p[2]))
}

#[test]
fn single_wave_is_a_gerstner_trochoid() {
    // L = 100 m, N = 64: Δk = 0.0628 rad/m. The band [0.99, 1.01)·2Δk holds exactly the grid
    // vectors with m_x² + m_z² = 4: (±2, 0) and (0, ±2). A Phillips spectrum with the wind along
    // +x, angular factor |cos θ|^50 and upwind factor 0 gives (−2, 0) nothing and (0, ±2)
    // |cos(π/2)|^50 = (6e-17)^50 = 0 in f64: one wave along +x (checked below). A = 0.14 makes
    // it steep but not folding with seed 2 (ka ≈ 0.3).
    let (n, length) = (64usize, 100.0f32);
    let dk = TAU / f64::from(length);
    let k = 2.0 * dk;
    let spectrum = Spectrum::phillips(10.0, 0.14)
        .unwrap()
        .with_spreading(Spreading::Cosine {
            exponent: 50.0,
            upwind: 0.0,
        })
        .unwrap();
    let mut results = Vec::new();
    for lambda in [1.0f32, 0.0] {
        let mut cascade = Cascade::new(
            &spectrum,
            CascadeConfig {
                size: n,
                length,
                k_min: (0.99 * k) as f32,
                k_max: (1.01 * k) as f32,
                choppiness: lambda,
                seed: 2,
                ..CascadeConfig::default()
            },
        )
        .unwrap();
        let h0 = cascade.h0();
        let c = to64(h0[index_of(2, n)]);
        for (idx, value) in h0.iter().enumerate() {
            if idx != index_of(2, n) {
                assert_eq!(value.norm(), 0.0, "h0 at index {idx} = {value}");
            }
        }
        // η = c e^{i(kx − ωt)} + conj = a cos(kx − ωt + φ0), a = 2|c|; D_x = −a sin(…).
        let a = 2.0 * cabs(c);
        let phi0 = c.1.atan2(c.0);
        let omega = (G * k).sqrt();
        assert!(a > 0.0);
        let t = 3.7;
        cascade.update(t).unwrap();
        let lam = f64::from(lambda);
        // The trochoid's Eulerian mean level: over one wavelength of X = x0 − λa sin θ,
        // ∫ y dX / ∫ dX = ⟨a cos θ (1 − λ a k cos θ)⟩ = −λ k a²/2. The cascade lifts every
        // height by that much (its mean-level correction), so the water's mean is 0.
        let lift = lam * k * a * a / 2.0;
        let offset = f64::from(cascade.mean_level_offset());
        assert!(
            (offset - lift).abs() <= 1e-6 * lift.max(a * 1e-3),
            "λ={lambda}: mean-level offset {offset} vs λka²/2 = {lift}"
        );
        let (height, disp) = (cascade.height(), cascade.displacement());
        let mut points = Vec::new();
        for j in [0, 17, n - 1] {
            for i in 0..n {
                let x = i as f64 * f64::from(length) / n as f64;
                let theta = k * x - omega * t + phi0;
                let (big_x, big_y) = (
                    x + f64::from(disp[j * n + i][0]),
                    f64::from(height[j * n + i]) - lift,
                );
                // The trochoid x = x0 − λa sin θ, y = a cos θ; f32 synthesis of a single mode
                // is good to a few 1e-7 of a, so 1e-5·a is "f32 exact" with a margin.
                assert!(
                    (big_x - (x - lam * a * theta.sin())).abs() < 1e-5 * a
                        && (big_y - a * theta.cos()).abs() < 1e-5 * a,
                    "λ={lambda} ({i},{j}): ({big_x}, {big_y}) vs trochoid ({}, {})",
                    x - lam * a * theta.sin(),
                    a * theta.cos()
                );
                assert!(f64::from(disp[j * n + i][1]).abs() < 1e-6 * a, "D_z ≠ 0");
                if j == 0 {
                    points.push((big_x, big_y));
                }
            }
        }
        // Slope of the displaced surface along x: dy/dX = (dy/dθ)/(dX/dθ) with
        // dy/dθ = −a sin θ and dX/dθ = 1/k − λa cos θ.
        for i in 0..n {
            let x = i as f64 * f64::from(length) / n as f64;
            let theta = k * x - omega * t + phi0;
            let expected = (-a * theta.sin()) / (1.0 / k - lam * a * theta.cos());
            let got = f64::from(cascade.slope()[i][0]);
            assert!(
                (got - expected).abs() < 1e-5 * (1.0 + expected.abs()),
                "slope {got} vs {expected}"
            );
        }
        // Curvature at the sampled crest (highest point) and trough (lowest), from three
        // consecutive displaced points.
        let top = (0..n)
            .max_by(|&p, &q| points[p].1.total_cmp(&points[q].1))
            .unwrap();
        let bottom = (0..n)
            .min_by(|&p, &q| points[p].1.total_cmp(&points[q].1))
            .unwrap();
        let around = |i: usize| {
            let mut p = [points[(i + n - 1) % n], points[i], points[(i + 1) % n]];
            // Unwrap the periodic x across the patch edge.
            for q in p.iter_mut() {
                if q.0 - points[i].0 > f64::from(length) / 2.0 {
                    q.0 -= f64::from(length);
                } else if points[i].0 - q.0 > f64::from(length) / 2.0 {
                    q.0 += f64::from(length);
                }
            }
            curvature(p)
        };
        let (crest, trough) = (around(top), around(bottom));
        println!(
            "λ = {lambda}: a = {a:.4} m, ka = {:.3}; curvature crest {crest:.5} trough {trough:.5} \
             1/m (ratio {:.3}; trochoid ratio at the exact extremes ((1 + λka)/(1 − λka))² = {:.3})",
            k * a,
            crest / trough,
            ((1.0 + lam * k * a) / (1.0 - lam * k * a)).powi(2)
        );
        // Exact trochoid curvatures: κ = a/(1/k ∓ λa)² at crest and trough. The three-point
        // estimate from samples 1.56 m apart on a 50 m wave, not centred on the extremes, is
        // good to ~1 % here (measured 3.457 vs 3.492); allow 5 %.
        let predicted = ((1.0 + lam * k * a) / (1.0 - lam * k * a)).powi(2);
        assert!(
            (crest / trough / predicted - 1.0).abs() < 0.05,
            "λ={lambda}: curvature ratio {} vs trochoid {predicted}",
            crest / trough
        );
        results.push(crest / trough);
    }
    // λ = 1 sharpens crests and flattens troughs; λ = 0 is a symmetric cosine (the ratio
    // differs from 1 only by where the samples fall relative to the extremes).
    assert!(
        results[0] > 1.1,
        "crest/trough curvature ratio {}",
        results[0]
    );
    assert!(
        (results[1] - 1.0).abs() < 0.05,
        "λ = 0 ratio {}",
        results[1]
    );
}

#[test]
fn looping_repeats_after_the_period() {
    let spectrum = jonswap(0.4);
    let period = 20.0f32;
    let make = |repeat_period| {
        Cascade::new(
            &spectrum,
            CascadeConfig {
                size: 32,
                length: 200.0,
                seed: 8,
                repeat_period,
                ..CascadeConfig::default()
            },
        )
        .unwrap()
    };
    let snapshot = |cascade: &mut Cascade, t: f64| -> Vec<Vec<f64>> {
        cascade.update(t).unwrap();
        let mut out: Vec<Vec<f64>> = FIELDS
            .iter()
            .map(|&f| to_f64(&inspect::field(cascade, f)))
            .collect();
        out.push(to_f64(cascade.height()));
        out.push(to_f64(cascade.jacobian()));
        out.push(
            cascade
                .displacement()
                .iter()
                .flat_map(|v| v.map(f64::from))
                .collect(),
        );
        out.push(
            cascade
                .slope()
                .iter()
                .flat_map(|v| v.map(f64::from))
                .collect(),
        );
        out.push(
            cascade
                .normal()
                .iter()
                .flat_map(|v| v.map(f64::from))
                .collect(),
        );
        out
    };
    let max_rel_diff = |a: &[Vec<f64>], b: &[Vec<f64>]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| {
                let scale = max_abs(x).max(1e-30);
                x.iter()
                    .zip(y)
                    .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()))
                    / scale
            })
            .fold(0.0f64, f64::max)
    };
    let p = f64::from(period);
    let mut looping = make(Some(period));
    let mut free = make(None);
    for t in [3.3, 0.0, 1234.5, -7.0] {
        let base = snapshot(&mut looping, t);
        for shift in [p, 5.0 * p, -p, 1000.0 * p] {
            let later = snapshot(&mut looping, t + shift);
            // The phase time is reduced mod T in f64 (error ~1e-16·|t|), then the same f32
            // synthesis runs: equal to f32 rounding, 1e-6 of each buffer's max.
            let d = max_rel_diff(&base, &later);
            assert!(
                d < 1e-6,
                "t = {t}, +{shift}: looping fields differ by {d:e}"
            );
        }
        let free_base = snapshot(&mut free, t);
        let free_later = snapshot(&mut free, t + p);
        let d = max_rel_diff(&free_base, &free_later);
        assert!(
            d > 0.1,
            "t = {t}: without looping the fields repeat after T ({d})"
        );
    }
}

#[test]
fn looping_moves_omega_to_the_nearest_multiple_of_two_pi_over_t_and_never_to_zero() {
    let period = 20.0f64;
    let (n, length) = (32usize, 200.0f32);
    let cascade = Cascade::new(
        &jonswap(0.4),
        CascadeConfig {
            size: n,
            length,
            repeat_period: Some(period as f32),
            ..CascadeConfig::default()
        },
    )
    .unwrap();
    let dk = TAU / f64::from(length);
    let step = TAU / period;
    let mut distinct = std::collections::BTreeSet::new();
    for j in 0..n {
        for i in 0..n {
            if i == n / 2 || j == n / 2 || (i == 0 && j == 0) {
                continue;
            }
            let k = dk * (m(i, n) as f64).hypot(m(j, n) as f64);
            let exact = (G * k).sqrt();
            let q = inspect::omega_at(&cascade, i, j).unwrap();
            let multiple = q / step;
            assert!(
                (multiple - multiple.round()).abs() < 1e-9,
                "({i},{j}): ω = {q} is {multiple} × 2π/T"
            );
            // The nearest multiple (half a step away at most), and never fewer than one
            // cycle per loop: no wave stands still.
            assert!(q >= step * (1.0 - 1e-12), "({i},{j}): ω {q} below 2π/T");
            if exact >= step {
                assert!(
                    (q - exact).abs() <= 0.5 * step * (1.0 + 1e-9),
                    "({i},{j}): ω {q} more than π/T from {exact}"
                );
            } else {
                assert_eq!(
                    multiple.round(),
                    1.0,
                    "({i},{j}): ω {q} for a wave longer than T"
                );
            }
            distinct.insert(multiple.round() as i64);
        }
    }
    assert!(
        distinct.len() > 3,
        "quantisation collapsed ω to {distinct:?}"
    );
}
