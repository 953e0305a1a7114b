//! Second-order bound waves (`OceanConfig::second_order`), checked against independent
//! computations: a naive double sum over every pair of waves of the largest cascade in f64
//! (the kernel written out from docs/theory.md), and the Sharma & Dean (1981) kernels derived
//! here from the free-surface boundary conditions, which the crate does not contain.
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

use std::f64::consts::TAU;

use ocean_fft::{OceanConfig, OceanState, Spectrum};

const G: f64 = 9.81;

/// One travelling wave of the reference: wave vector (rad/m), angular frequency (rad/s) and
/// complex amplitude A = h0(k) at t = 0 (the wave is 2 Re(A e^{i(k·x − ωt)})).
#[derive(Clone, Copy)]
struct Wave {
    /// Wave indices (k = Δk·m), so that differences of wave vectors are formed exactly.
    m: [i64; 2],
    dk: f64,
    k: [f64; 2],
    omega: f64,
    a: (f64, f64),
}

/// The waves of cascade 0 with 0 < |k| < k_top = min(k_max, πN/2L), from its h0.
fn waves(ocean: &OceanState) -> (Vec<Wave>, f64) {
    let cascade = &ocean.cascades()[0];
    let n = cascade.size();
    let length = f64::from(cascade.length());
    let dk = TAU / length;
    let k_max = f64::from(ocean.config().bands().unwrap()[0].1);
    let k_top = k_max.min(std::f64::consts::PI * n as f64 / length / 2.0);
    let dispersion = ocean.spectrum().dispersion();
    let mut out = Vec::new();
    for j in 0..n {
        for i in 0..n {
            if i == n / 2 || j == n / 2 {
                continue;
            }
            let m = |i: usize| {
                if i < n / 2 {
                    i as i64
                } else {
                    i as i64 - n as i64
                }
            };
            let k = [m(i) as f64 * dk, m(j) as f64 * dk];
            let kk = k[0].hypot(k[1]);
            if kk == 0.0 || kk >= k_top {
                continue;
            }
            let h = cascade.h0()[j * n + i];
            if h.re == 0.0 && h.im == 0.0 {
                continue;
            }
            out.push(Wave {
                m: [m(i), m(j)],
                dk,
                k,
                omega: f64::from(dispersion.omega(kk as f32)),
                a: (f64::from(h.re), f64::from(h.im)),
            });
        }
    }
    (out, k_top)
}

/// The implemented correction by a naive double sum: η₂(x, t) = Σ_a Σ_b 4γ Re(A_a conj(A_b)
/// e^{i((k_a − k_b)·x − (ω_a − ω_b)t)}), γ = ¼(|k_a| + |k_b|) − ¼|k_a − k_b|, over the pairs
/// with 0 < |k_a − k_b| < k_top (docs/theory.md), and its gradient.
fn naive_correction(waves: &[Wave], k_top: f64, t: f64, points: &[[f64; 2]]) -> Vec<[f64; 3]> {
    // Every pair's term 4γ A_a conj(A_b) e^{−i(ω_a − ω_b)t} gathered by its difference wave
    // vector (a map keyed by the integer indices), then each wave vector's sum summed at every
    // point directly (no transform): the same sum in another order, O(pairs + vectors·points).
    let mut terms: std::collections::BTreeMap<(i64, i64), (f64, f64)> = Default::default();
    for a in waves {
        for b in waves {
            let m = (a.m[0] - b.m[0], a.m[1] - b.m[1]);
            let kd = [m.0 as f64 * a.dk, m.1 as f64 * a.dk];
            let kdn = kd[0].hypot(kd[1]);
            if kdn == 0.0 || kdn >= k_top {
                continue;
            }
            let gamma = 0.25 * (a.k[0].hypot(a.k[1]) + b.k[0].hypot(b.k[1])) - 0.25 * kdn;
            // A_a conj(A_b) e^{−i(ω_a − ω_b)t}
            let c = (a.a.0 * b.a.0 + a.a.1 * b.a.1, a.a.1 * b.a.0 - a.a.0 * b.a.1);
            let (s, co) = (-(a.omega - b.omega) * t).sin_cos();
            let term = terms.entry(m).or_default();
            term.0 += 4.0 * gamma * (c.0 * co - c.1 * s);
            term.1 += 4.0 * gamma * (c.0 * s + c.1 * co);
        }
    }
    let dk = waves[0].dk;
    let mut out = vec![[0.0; 3]; points.len()];
    for (&(mx, mz), &c) in &terms {
        let kd = [mx as f64 * dk, mz as f64 * dk];
        for (p, o) in points.iter().zip(out.iter_mut()) {
            let (s, co) = (kd[0] * p[0] + kd[1] * p[1]).sin_cos();
            let re = c.0 * co - c.1 * s;
            let im = c.0 * s + c.1 * co;
            o[0] += re;
            // ∂/∂x Re(c e^{iθ}) = Re(i k_x c e^{iθ}) = −k_x Im(c e^{iθ})
            o[1] -= kd[0] * im;
            o[2] -= kd[1] * im;
        }
    }
    out
}

fn ocean(spectrum: Spectrum, size: usize, lengths: Vec<f32>, second_order: bool) -> OceanState {
    let config = OceanConfig {
        size,
        lengths,
        choppiness: 0.0,
        second_order,
        ..OceanConfig::default()
    };
    OceanState::new(spectrum, config).unwrap()
}

/// The height and slope buffers of cascade 0 with second order on, less those with it off
/// (λ = 0: the slope buffer is then ∇η), against the naive double sum at every grid point.
fn check_against_naive(spectrum: Spectrum, size: usize, lengths: Vec<f32>, t: f64) {
    let mut on = ocean(spectrum.clone(), size, lengths.clone(), true);
    let mut off = ocean(spectrum, size, lengths, false);
    on.set_time(t).unwrap();
    off.set_time(t).unwrap();
    let (waves, k_top) = waves(&on);
    let (c_on, c_off) = (&on.cascades()[0], &off.cascades()[0]);
    let n = c_on.size();
    let spacing = f64::from(c_on.length()) / n as f64;
    let points: Vec<[f64; 2]> = (0..n * n)
        .map(|p| [(p % n) as f64 * spacing, (p / n) as f64 * spacing])
        .collect();
    let expected = naive_correction(&waves, k_top, t, &points);
    let (mut err, mut rms, mut err_s, mut rms_s) = (0.0, 0.0, 0.0, 0.0);
    for (p, e) in expected.iter().enumerate() {
        let dh = f64::from(c_on.height()[p]) - f64::from(c_off.height()[p]);
        err += (dh - e[0]).powi(2);
        rms += e[0] * e[0];
        for axis in 0..2 {
            let ds = f64::from(c_on.slope()[p][axis]) - f64::from(c_off.slope()[p][axis]);
            err_s += (ds - e[1 + axis]).powi(2);
            rms_s += e[1 + axis] * e[1 + axis];
        }
    }
    let (rel, rel_s) = ((err / rms).sqrt(), (err_s / rms_s).sqrt());
    println!(
        "{} waves, rms correction {:.3e} m, rms slope {:.3e}: relative error {rel:.2e} (height), {rel_s:.2e} (slope)",
        waves.len(),
        (rms / points.len() as f64).sqrt(),
        (rms_s / points.len() as f64).sqrt()
    );
    // Measured 3–4e-6 (height) and 0.6–1.2e-5 (slope): the f32 transforms of fields some
    // thirty times larger than the correction (their rounding, ~1e-7 of η, is a few 1e-6 of
    // η₂) and the f32 phases (5e-7 rad). 1e-4 leaves a factor of eight; a wrong sign, factor
    // or pair in the sum gives errors of order 1e-2 to 1 (one pair at the band edge counted
    // on one side only gave 7e-3).
    assert!(rel < 1e-4 && rel_s < 1e-4, "{rel} {rel_s}");
    assert!(rms > 0.0);
}

#[test]
fn deep_water_matches_the_naive_double_sum() {
    // A 64² largest cascade: 771 waves below k_top, 594 000 pairs.
    check_against_naive(
        Spectrum::jonswap(10.0, 100_000.0).unwrap(),
        64,
        vec![400.0, 90.0],
        23.7,
    );
}

#[test]
fn finite_depth_matches_the_naive_double_sum() {
    check_against_naive(
        Spectrum::tma(8.0, 15_000.0, 4.0).unwrap(),
        64,
        vec![120.0, 27.0],
        5.3,
    );
}

/// Forristall's (2000) short-crested (3D) Weibull fit of crest heights: the crest height over
/// H_s exceeded with probability `p`. P(C > c) = exp(−(c/(α H_s))^β) with
/// α = 0.3536 + 0.2568 S₁ + 0.0800 U_r and β = 2 − 1.7912 S₁ − 0.5302 U_r + 0.284 U_r², from
/// the steepness S₁ = 2π H_s/(g T₁²) and the Ursell number U_r = H_s/(k₁² d³) (0 in deep
/// water), T₁ = 2π m0/m1 and k₁ the wave number of period T₁.
fn forristall(spectrum: &Spectrum, p: f64) -> f64 {
    // m0, m1 by the trapezoidal rule over 0.01–40 rad/s (the spectra hold < 1e-6 outside).
    let (mut m0, mut m1) = (0.0, 0.0);
    let steps = 400_000;
    let (w0, w1) = (0.01f64, 40.0f64);
    let dw = (w1 - w0) / steps as f64;
    for s in 0..=steps {
        let w = w0 + s as f64 * dw;
        let weight = if s == 0 || s == steps { 0.5 } else { 1.0 };
        let e = f64::from(spectrum.omega_spectrum(w as f32)) * weight * dw;
        m0 += e;
        m1 += e * w;
    }
    let hs = 4.0 * m0.sqrt();
    let t1 = TAU * m0 / m1;
    let s1 = TAU / G * hs / (t1 * t1);
    let ursell = match spectrum.depth() {
        Some(d) => {
            let d = f64::from(d);
            let k1 = f64::from(spectrum.dispersion().k_from_omega((TAU / t1) as f32));
            hs / (k1 * k1 * d * d * d)
        }
        None => 0.0,
    };
    let alpha = 0.3536 + 0.2568 * s1 + 0.0800 * ursell;
    let beta = 2.0 - 1.7912 * s1 - 0.5302 * ursell + 0.284 * ursell * ursell;
    alpha * (-p.ln()).powf(1.0 / beta)
}

/// What virtual wave buoys see: the water height (`heights_at`, the Eulerian surface) at a
/// grid of points one peak wavelength apart over the largest tile, every `dt` for `frames`
/// frames. Returns the skewness of the elevation with its standard error (from the spread
/// of 16 blocks of buoys), H_s = 4σ, the mean level, and the crests of the zero-up-crossing
/// waves (the largest elevation of each, refined by a parabola through the three samples
/// around it), over H_s.
fn buoys(ocean: &mut OceanState, dt: f64, frames: usize) -> (f64, f64, f64, f64, Vec<f64>) {
    let length = f64::from(ocean.cascades()[0].length());
    let peak = TAU
        / f64::from(
            ocean
                .spectrum()
                .dispersion()
                .k_from_omega(ocean.spectrum().peak_omega()),
        );
    let side = ((length / peak).floor() as usize).max(4);
    let spacing = length / side as f64;
    let points: Vec<[f64; 2]> = (0..side * side)
        .map(|i| {
            [
                (i % side) as f64 * spacing + 0.31,
                (i / side) as f64 * spacing + 0.77,
            ]
        })
        .collect();
    let mut series = vec![Vec::with_capacity(frames); points.len()];
    let mut heights = vec![0.0f32; points.len()];
    for _ in 0..frames {
        ocean.step(dt).unwrap();
        ocean.water().heights_at(&points, &mut heights).unwrap();
        for (s, &h) in series.iter_mut().zip(&heights) {
            s.push(f64::from(h));
        }
    }
    let count = (points.len() * frames) as f64;
    let mean = series.iter().flatten().sum::<f64>() / count;
    let var = series
        .iter()
        .flatten()
        .map(|h| (h - mean).powi(2))
        .sum::<f64>()
        / count;
    let third = |s: &[Vec<f64>]| {
        let c = (s.len() * frames) as f64;
        s.iter().flatten().map(|h| (h - mean).powi(3)).sum::<f64>() / c / var.powf(1.5)
    };
    let skew = third(&series);
    let blocks: Vec<f64> = series
        .chunks(series.len().div_ceil(16))
        .map(third)
        .collect();
    let bm = blocks.iter().sum::<f64>() / blocks.len() as f64;
    let se = (blocks.iter().map(|b| (b - bm).powi(2)).sum::<f64>()
        / (blocks.len() * (blocks.len() - 1)) as f64)
        .sqrt();
    let hs = 4.0 * var.sqrt();
    let mut crests = Vec::new();
    for s in &series {
        let mut start = None;
        for t in 1..s.len() {
            if s[t - 1] < mean && s[t] >= mean {
                if let Some(a) = start {
                    let (mut best, mut at) = (f64::MIN, a);
                    for (u, &v) in s.iter().enumerate().take(t).skip(a) {
                        if v > best {
                            (best, at) = (v, u);
                        }
                    }
                    if at > 0 && at + 1 < s.len() {
                        let (y0, y1, y2) = (s[at - 1], s[at], s[at + 1]);
                        let den = y0 - 2.0 * y1 + y2;
                        if den < 0.0 {
                            best = y1 - 0.125 * (y2 - y0).powi(2) / den;
                        }
                    }
                    crests.push((best - mean) / hs);
                }
                start = Some(t);
            }
        }
    }
    crests.sort_by(|a, b| b.partial_cmp(a).unwrap());
    (skew, se, hs, mean, crests)
}

/// The skewness the implemented second order predicts for this realisation: the bound waves
/// add E[η³] = 3E[η₁²η₂] = 3·8 Σ_a Σ_b |h0_a|²|h0_b|² γ_ab over the pairs it keeps (the
/// horizontal displacement's own second order adds none: its sum and difference terms
/// cancel in E[η₁²η₂]), over σ³ with σ² = 2 Σ |h0|² of every cascade.
fn predicted_skewness(ocean: &OceanState) -> f64 {
    let (waves, k_top) = waves(ocean);
    let mut third = 0.0;
    for a in &waves {
        let ea = a.a.0 * a.a.0 + a.a.1 * a.a.1;
        for b in &waves {
            let kd = [
                (a.m[0] - b.m[0]) as f64 * a.dk,
                (a.m[1] - b.m[1]) as f64 * a.dk,
            ];
            let kdn = kd[0].hypot(kd[1]);
            if kdn == 0.0 || kdn >= k_top {
                continue;
            }
            let gamma = 0.25 * (a.k[0].hypot(a.k[1]) + b.k[0].hypot(b.k[1])) - 0.25 * kdn;
            third += 24.0 * ea * (b.a.0 * b.a.0 + b.a.1 * b.a.1) * gamma;
        }
    }
    let var: f64 = ocean
        .cascades()
        .iter()
        .flat_map(|c| c.h0().iter())
        .map(|h| 2.0 * (f64::from(h.re).powi(2) + f64::from(h.im).powi(2)))
        .sum();
    third / var.powf(1.5)
}

/// The skewness Sharma & Dean's kernels give the same waves (those the correction covers, of
/// this realisation): 24 Σ_a Σ_b |h0_a|²|h0_b|² (K⁺ + K⁻)(a, b) over σ³, the pairs of a wave
/// with itself left out as in [`predicted_skewness`]. Waves below 1e-4 of the largest energy
/// are skipped (they hold < 1 % of the variance; it keeps the pairs to a few million).
fn sharma_dean_skewness(ocean: &OceanState) -> f64 {
    let depth = ocean.spectrum().depth().map(f64::from);
    let (mut waves, _) = waves(ocean);
    let energy = |w: &Wave| w.a.0 * w.a.0 + w.a.1 * w.a.1;
    let top = waves.iter().map(energy).fold(0.0, f64::max);
    waves.retain(|w| energy(w) >= 1e-4 * top);
    for w in &mut waves {
        let k = w.k[0].hypot(w.k[1]);
        w.omega = (G * k * depth.map_or(1.0, |h| (k * h).tanh())).sqrt();
    }
    let mut third = 0.0;
    for a in &waves {
        for b in &waves {
            if a.m == b.m {
                continue;
            }
            let (plus, minus) = sharma_dean(a, b, depth);
            third += 24.0 * energy(a) * energy(b) * (plus + minus);
        }
    }
    let var: f64 = ocean
        .cascades()
        .iter()
        .flat_map(|c| c.h0().iter())
        .map(|h| 2.0 * (f64::from(h.re).powi(2) + f64::from(h.im).powi(2)))
        .sum();
    third / var.powf(1.5)
}

/// A measurement of one sea: skewness ± its standard error, the prediction, H_s, the mean
/// level, the crest heights over H_s at exceedance 0.1, 0.01 and 0.001, the number of crests
/// and Sharma & Dean's skewness over the same waves.
fn measure(spectrum: &Spectrum, config: &OceanConfig, second_order: bool) -> [f64; 10] {
    let config = OceanConfig {
        second_order,
        ..config.clone()
    };
    let mut ocean = OceanState::new(spectrum.clone(), config).unwrap();
    // 16 samples a peak period (the parabola through the top three puts a sampled crest
    // within 0.1 % of the continuous one), 4000 frames: 250 peak periods at each of 121–256
    // buoys, 38 000–80 000 waves.
    let tp = TAU / f64::from(spectrum.peak_omega());
    let (skew, se, hs, mean, crests) = buoys(&mut ocean, tp / 16.0, 4000);
    let q = |p: f64| crests[(p * crests.len() as f64) as usize];
    [
        skew,
        se,
        predicted_skewness(&ocean),
        hs,
        mean,
        q(0.1),
        q(0.01),
        q(0.001),
        crests.len() as f64,
        if second_order {
            sharma_dean_skewness(&ocean)
        } else {
            0.0
        },
    ]
}

/// The buoys' statistics of one sea with second order against theory and Forristall. Each
/// sea is its own test (4000 frames each), so that the test threads run two at a time.
fn check_sea(name: &str, spectrum: &Spectrum, config: &OceanConfig) {
    let [skew, se, predicted, hs, mean, c1, c2, c3, waves, sd] = measure(spectrum, config, true);
    let forristall = [0.1, 0.01, 0.001].map(|p| forristall(spectrum, p));
    println!(
        "{name}: skewness {skew:.4} ± {se:.4} (predicted {predicted:.4}, Sharma–Dean over the \
         same waves {sd:.4}); H_s {hs:.3} m \
         (spectrum {:.3}); mean {mean:.5} m; {waves} crests over H_s at 0.1, 0.01, 0.001: \
         {c1:.3}, {c2:.3}, {c3:.3} (Forristall {:.3}, {:.3}, {:.3})",
        spectrum.significant_wave_height(),
        forristall[0],
        forristall[1],
        forristall[2]
    );
    // The prediction is the expectation for this very realisation, so only the time
    // sampling scatters the measurement: 4 standard errors.
    assert!((skew - predicted).abs() < 4.0 * se, "{name}: skewness");
    assert!(
        (0.1..0.3).contains(&skew),
        "{name}: skewness of a second-order sea"
    );
    // Within 3 % of Forristall's short-crested fit (the measured 0.2–1.2 %).
    for (c, f) in [c1, c2, c3].iter().zip(forristall) {
        assert!((c / f - 1.0).abs() < 0.03, "{name}: crest {c} against {f}");
    }
    // H_s as calibrated (the realisation scatters by about 1 %) and the mean level still
    // water (the bound waves have no mean: 0.02 % of H_s measured).
    let target = f64::from(spectrum.significant_wave_height());
    assert!(
        (hs / target - 1.0).abs() < 0.02,
        "{name}: H_s {hs} against {target}"
    );
    assert!(mean.abs() < 2e-3 * hs, "{name}: mean level {mean}");
}

/// The default sea of the statistics tests.
fn default_sea() -> (Spectrum, OceanConfig) {
    (
        Spectrum::jonswap(10.0, 100_000.0).unwrap(),
        OceanConfig::default(),
    )
}

#[test]
fn statistics_match_second_order_theory_default() {
    let (spectrum, config) = default_sea();
    check_sea("default", &spectrum, &config);
}

#[test]
fn statistics_match_second_order_theory_storm() {
    let (spectrum, config) = ocean_fft::SeaState::Storm.build();
    check_sea("storm", &spectrum, &config);
}

#[test]
fn statistics_match_second_order_theory_shallow_bay() {
    let (spectrum, config) = ocean_fft::SeaState::ShallowBay.build();
    check_sea("shallow bay", &spectrum, &config);
}

/// Without second order the same sea is symmetric and its crests are those of a linear sea,
/// 5 % and more below Forristall's at 0.01.
#[test]
fn statistics_without_second_order_are_linear() {
    let (spectrum, config) = default_sea();
    let [skew, se, _, _, _, _, c2, _, _, _] = measure(&spectrum, &config, false);
    println!("default without second order: skewness {skew:.4} ± {se:.4}, crest at 0.01 {c2:.3}");
    assert!(
        skew.abs() < 4.0 * se + 0.005,
        "skewness without second order"
    );
    assert!(c2 < 0.97 * forristall(&spectrum, 0.01));
}

/// Sharma & Dean's (1981) second-order elevation of an ordered pair of unit waves a, b (the
/// coefficients of cos(ψ_a + ψ_b) and cos(ψ_a − ψ_b); summed over both orders they are the
/// symmetric kernels K±), derived from the free-surface conditions expanded about z = 0: the
/// bound potential φ₂ answers the forcing F = ∂_t R_D − g R_K at the pair's frequency and
/// wave vector with 1/(g|K| tanh(|K|h) − Ω²), and η₂ = (R_D − ∂_t φ₂)/g, where
/// R_K = −∇η·∇φ + η φ_zz and R_D = −½|∇φ|² − ½φ_z² − η φ_zt are the products of the linear
/// waves. `depth` None is deep water.
fn sharma_dean(a: &Wave, b: &Wave, depth: Option<f64>) -> (f64, f64) {
    let tanh = |k: f64| depth.map_or(1.0, |h| (k * h).tanh());
    let dot = a.k[0] * b.k[0] + a.k[1] * b.k[1];
    let kb2 = b.k[0] * b.k[0] + b.k[1] * b.k[1];
    let (wa, wb) = (a.omega, b.omega);
    // R_K = (g/ω_b)(k_a·k_b) sin ψ_a cos ψ_b + (g k_b²/ω_b) cos ψ_a sin ψ_b: its sin(ψ_a ± ψ_b)
    // coefficients.
    let (p, q) = (G / wb * dot, G * kb2 / wb);
    let rk = [0.5 * (p + q), 0.5 * (p - q)];
    // R_D = (−½ g²(k_a·k_b)/(ω_a ω_b) + ω_b²) cos ψ_a cos ψ_b − ½ ω_a ω_b sin ψ_a sin ψ_b.
    let (c, s) = (-0.5 * G * G * dot / (wa * wb) + wb * wb, -0.5 * wa * wb);
    let rd = [0.5 * (c - s), 0.5 * (c + s)];
    let mut out = [0.0; 2];
    for (o, sign) in [1.0, -1.0].into_iter().enumerate() {
        let omega = wa + sign * wb;
        let kk = (a.k[0] + sign * b.k[0]).hypot(a.k[1] + sign * b.k[1]);
        let forcing = rd[o] * omega - G * rk[o];
        let den = G * kk * tanh(kk) - omega * omega;
        let phi = if den.abs() > 1e-12 {
            forcing / den
        } else {
            0.0
        };
        out[o] = (rd[o] + omega * phi) / G;
    }
    (out[0], out[1])
}

/// The second order the ocean is built to have at λ = 1, for an ordered pair: the
/// horizontal displacement's, whose Eulerian height at second order is −D·∇η
/// (¼(|k_a| + |k_b|) cos θ_ab on both the sum and, negated, the difference), and the
/// correction γ on the difference where 0 < |k_a − k_b| < k_top.
fn implemented(a: &Wave, b: &Wave, k_top: f64) -> (f64, f64) {
    let (ka, kb) = (a.k[0].hypot(a.k[1]), b.k[0].hypot(b.k[1]));
    let cos = (a.k[0] * b.k[0] + a.k[1] * b.k[1]) / (ka * kb);
    let cwm = 0.25 * (ka + kb) * cos;
    let kd = [
        (a.m[0] - b.m[0]) as f64 * a.dk,
        (a.m[1] - b.m[1]) as f64 * a.dk,
    ];
    let kdn = kd[0].hypot(kd[1]);
    let gamma = if kdn > 0.0 && kdn < k_top {
        0.25 * (ka + kb) - 0.25 * kdn
    } else {
        0.0
    };
    // Symmetric already: each ordered pair carries the whole kernel.
    (cwm, gamma - cwm)
}

/// Σ over ordered pairs of `kernel` (sum and difference coefficients) times a_a a_b
/// cos(ψ_a ± ψ_b), a e^{iψ} = 2A e^{i(k·x − ωt)}, at each point.
fn pair_sum(
    waves: &[Wave],
    t: f64,
    points: &[[f64; 2]],
    kernel: impl Fn(&Wave, &Wave) -> (f64, f64),
) -> Vec<f64> {
    let mut out = vec![0.0; points.len()];
    for a in waves {
        for b in waves {
            let (plus, minus) = kernel(a, b);
            // 4 A_a A_b and 4 A_a conj(A_b)
            let s = (
                4.0 * (a.a.0 * b.a.0 - a.a.1 * b.a.1),
                4.0 * (a.a.0 * b.a.1 + a.a.1 * b.a.0),
            );
            let d = (
                4.0 * (a.a.0 * b.a.0 + a.a.1 * b.a.1),
                4.0 * (a.a.1 * b.a.0 - a.a.0 * b.a.1),
            );
            for (p, o) in points.iter().zip(out.iter_mut()) {
                let phase_a = a.k[0] * p[0] + a.k[1] * p[1] - a.omega * t;
                let phase_b = b.k[0] * p[0] + b.k[1] * p[1] - b.omega * t;
                let (ss, sc) = (phase_a + phase_b).sin_cos();
                let (ds, dc) = (phase_a - phase_b).sin_cos();
                *o += plus * (s.0 * sc - s.1 * ss) + minus * (d.0 * dc - d.1 * ds);
            }
        }
    }
    out
}

/// The water height at world points of a one-cascade ocean at λ = 1 whose waves all take
/// part (its band ends below k_top), less its linear waves summed naively, against the
/// implemented second order and Sharma & Dean's, each summed naively over every ordered pair
/// (means over the points removed: the crate keeps the mean level at still water). Returns
/// the relative RMS differences (measured − implemented, measured − Sharma–Dean, and the
/// same sea without second order − Sharma–Dean).
fn eulerian_against_theory(spectrum: Spectrum, length: f32, t: f64) -> [f64; 3] {
    let depth = spectrum.depth().map(f64::from);
    let size = 128;
    // A quarter of the Nyquist wave number: 8 grid points per wavelength at the top, where
    // the queries' cubic spline keeps 99.98 % of the amplitude.
    let k_max = std::f32::consts::PI * size as f32 / length / 4.0 * 0.999;
    let build = |second_order| {
        let config = OceanConfig {
            size,
            lengths: vec![length],
            k_max,
            second_order,
            ..OceanConfig::default()
        };
        let mut ocean = OceanState::new(spectrum.clone(), config).unwrap();
        ocean.set_time(t).unwrap();
        ocean
    };
    let (on, off) = (build(true), build(false));
    let (mut waves, k_top) = waves(&on);
    for w in &mut waves {
        let k = w.k[0].hypot(w.k[1]);
        w.omega = (G * k * depth.map_or(1.0, |h| (k * h).tanh())).sqrt();
    }
    let points: Vec<[f64; 2]> = (0..144)
        .map(|p| {
            let (i, j) = ((p % 12) as f64, (p / 12) as f64);
            let step = f64::from(length) / 12.0;
            [i * step + 0.37 * step, j * step + 0.71 * step]
        })
        .collect();
    let linear: Vec<f64> = points
        .iter()
        .map(|p| {
            waves
                .iter()
                .map(|w| {
                    let (s, c) = (w.k[0] * p[0] + w.k[1] * p[1] - w.omega * t).sin_cos();
                    2.0 * (w.a.0 * c - w.a.1 * s)
                })
                .sum::<f64>()
        })
        .collect();
    let centred = |v: Vec<f64>| {
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        v.into_iter().map(|x| x - mean).collect::<Vec<_>>()
    };
    let measured = |ocean: &OceanState| {
        let mut heights = vec![0.0f32; points.len()];
        ocean.water().heights_at(&points, &mut heights).unwrap();
        centred(
            heights
                .iter()
                .zip(&linear)
                .map(|(&h, l)| f64::from(h) - l)
                .collect(),
        )
    };
    let (m_on, m_off) = (measured(&on), measured(&off));
    let implemented = centred(pair_sum(&waves, t, &points, |a, b| {
        implemented(a, b, k_top)
    }));
    let theory = centred(pair_sum(&waves, t, &points, |a, b| {
        sharma_dean(a, b, depth)
    }));
    let rel = |x: &[f64], y: &[f64]| {
        let e: f64 = x.iter().zip(y).map(|(a, b)| (a - b).powi(2)).sum();
        let r: f64 = y.iter().map(|b| b * b).sum();
        (e / r).sqrt()
    };
    let out = [
        rel(&m_on, &implemented),
        rel(&m_on, &theory),
        rel(&m_off, &theory),
    ];
    println!(
        "{} waves: measured − implemented {:.3}, measured − Sharma–Dean {:.3} (without second order {:.3}), rms Sharma–Dean {:.2e} m",
        waves.len(),
        out[0],
        out[1],
        out[2],
        (theory.iter().map(|x| x * x).sum::<f64>() / theory.len() as f64).sqrt()
    );
    out
}

/// The bounds of both seas. Measured − implemented (0.13 deep, 0.17 at depth) is what the
/// pair sums leave out: the displaced surface's third and higher orders (of relative size
/// k·a, a few per cent of η, i.e. some 10–20 % of η₂) and the queries' interpolation; 0.25
/// bounds it. Against Sharma & Dean the implemented form differs by 0.26 and 0.30 (the
/// directional and finite-depth kernel it simplifies, see docs/theory.md); the surface
/// without second order by 0.96 and 0.92: its group-scale set-down is of the size of η₂
/// itself.
fn check_theory(r: [f64; 3]) {
    assert!(r[0] < 0.25, "measured − implemented {}", r[0]);
    assert!(r[1] < 0.35, "measured − Sharma–Dean {}", r[1]);
    assert!(
        r[2] > 0.8 && r[1] < 0.5 * r[2],
        "without second order {}",
        r[2]
    );
}

#[test]
fn eulerian_surface_against_sharma_dean_deep() {
    check_theory(eulerian_against_theory(
        Spectrum::jonswap(10.0, 100_000.0).unwrap(),
        400.0,
        20.0,
    ));
}

#[test]
fn eulerian_surface_against_sharma_dean_finite_depth() {
    check_theory(eulerian_against_theory(
        Spectrum::tma(8.0, 15_000.0, 4.0).unwrap(),
        120.0,
        7.0,
    ));
}

#[test]
fn the_sharma_dean_reference_has_the_known_limits() {
    // Wave indices on a grid of Δk = 0.1 rad/m.
    let wave = |mx: i64, mz: i64| {
        let k = [mx as f64 * 0.1, mz as f64 * 0.1];
        Wave {
            m: [mx, mz],
            dk: 0.1,
            k,
            omega: (G * k[0].hypot(k[1])).sqrt(),
            a: (0.0, 0.0),
        }
    };
    let symmetric = |a: &Wave, b: &Wave| {
        let (p1, m1) = sharma_dean(a, b, None);
        let (p2, m2) = sharma_dean(b, a, None);
        (p1 + p2, m1 + m2)
    };
    // Stokes: one wave a cos ψ gets ½ k a² cos 2ψ (the diagonal sum term, a² K⁺ with K⁺ = ½k
    // from the one ordered pair), and no mean.
    let a = wave(3, 0);
    let (plus, minus) = sharma_dean(&a, &a, None);
    assert!((plus - 0.15).abs() < 1e-12 && minus.abs() < 1e-12);
    // Longuet-Higgins (1963), collinear deep water: K⁺ = ¼(k_a + k_b), K⁻ = −¼|k_a − k_b|
    // (both orders summed: twice each).
    let b = wave(1, 0);
    let (plus, minus) = symmetric(&a, &b);
    assert!((plus - 2.0 * 0.1).abs() < 1e-12 && (minus + 2.0 * 0.05).abs() < 1e-12);
    // The implemented form agrees there (both orders summed).
    let (p1, m1) = implemented(&a, &b, 1.0);
    let (p2, m2) = implemented(&b, &a, 1.0);
    assert!((p1 + p2 - plus).abs() < 1e-12 && (m1 + m2 - minus).abs() < 1e-12);
}
