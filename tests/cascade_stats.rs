//! Statistics of the synthesised surface: Parseval, the calibration of var(η) and H_s against
//! the spectrum over many seeds, resolution-independent seeding and the band limits.
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

mod common;

use std::f64::consts::TAU;

use common::*;
use ocean_fft::{inspect, Cascade, CascadeConfig, Spectrum};

fn config(n: usize, length: f32, seed: u64) -> CascadeConfig {
    CascadeConfig {
        size: n,
        length,
        seed,
        ..CascadeConfig::default()
    }
}

/// Σ_k S(k) Δk² over the grid vectors with k_min ≤ |k| < k_max (no k = 0, no Nyquist row or
/// column), from `Spectrum::density` at k = Δk·(m(i), m(j)), summed in f64.
fn grid_variance(spectrum: &Spectrum, n: usize, length: f64, k_min: f64, k_max: f64) -> f64 {
    let dk = TAU / length;
    let mut sum = 0.0;
    for j in 0..n {
        for i in 0..n {
            if i == n / 2 || j == n / 2 {
                continue;
            }
            let (kx, kz) = (m(i, n) as f64 * dk, m(j, n) as f64 * dk);
            let k = kx.hypot(kz);
            if k == 0.0 || k < k_min || k >= k_max {
                continue;
            }
            sum += f64::from(spectrum.density([kx as f32, kz as f32])) * dk * dk;
        }
    }
    sum
}

#[test]
fn parseval_spatial_variance_equals_spectral_energy() {
    let cases = [
        (jonswap(0.4), 64, 300.0),
        (phillips(-1.1), 24, 200.0),
        (jonswap(-2.0), 256, 1000.0),
    ];
    for (spectrum, n, length) in cases {
        let mut cascade = Cascade::new(&spectrum, config(n, length, 3)).unwrap();
        for t in [0.0, 4.4, 333.3] {
            cascade.update(t).unwrap();
            // The buffer holds η plus the constant mean-level correction.
            let offset = f64::from(cascade.mean_level_offset());
            let eta: Vec<f64> = to_f64(cascade.height())
                .iter()
                .map(|h| h - offset)
                .collect();
            let mu = mean(&eta);
            let spatial = eta.iter().map(|x| x * x).sum::<f64>() / (n * n) as f64;
            let spectral: f64 = inspect::wave_spectrum(&cascade, t)
                .unwrap()
                .iter()
                .map(|c| f64::from(c.norm_sqr()))
                .sum();
            // η = Σ h̃ e^{ik·x} unnormalised, so (1/N²) Σ_x η² = Σ_k |h̃|². The f32 fields carry
            // errors of a few 1e-7 of max|η| ≈ 4 rms (cascade_dft), i.e. ~1e-6 of the variance
            // after squaring; 1e-5 relative is "f32 precision" with a margin.
            let rel = (spatial - spectral).abs() / spectral;
            println!("N={n} t={t}: Parseval relative difference {rel:.1e}");
            assert!(rel < 1e-5, "N={n} t={t}: {spatial} vs {spectral}");
            // h̃(0) = 0, so the mean is zero up to the same rounding.
            assert!(mu.abs() < 1e-5 * spatial.sqrt(), "N={n} t={t}: mean {mu}");
        }
    }
}

#[test]
fn expected_variance_is_the_grid_sum_of_the_density() {
    for (spectrum, n, length, k_min, k_max) in [
        (jonswap(0.4), 64, 300.0, 0.0, f32::INFINITY),
        (jonswap(0.4), 128, 1000.0, 0.05, 0.3),
        (jonswap(0.4), 256, 1000.0, 0.0, f32::INFINITY),
        (phillips(-1.1), 24, 200.0, 0.0, f32::INFINITY),
    ] {
        let cascade = Cascade::new(
            &spectrum,
            CascadeConfig {
                k_min,
                k_max,
                ..config(n, length, 1)
            },
        )
        .unwrap();
        let sum = grid_variance(
            &spectrum,
            n,
            f64::from(length),
            f64::from(k_min),
            f64::from(k_max),
        );
        // density() returns f32 at an f32 k: each term is off by ~1e-7 relative; 1e-5 is far
        // above that and far below any real difference (one missing vector is ≥ 1e-4 here).
        let rel = (cascade.expected_variance() - sum).abs() / sum;
        assert!(
            rel < 1e-5,
            "N={n}: expected_variance {} vs Σ S Δk² {sum}",
            cascade.expected_variance()
        );
    }
}

/// var(η) and std(η) of one seed's height field at t = 0 and t = 50 s (averaged).
fn height_stats(spectrum: &Spectrum, config: CascadeConfig) -> (f64, f64, f64) {
    let mut cascade = Cascade::new(spectrum, config).unwrap();
    let mut var = 0.0;
    let mut std = 0.0;
    for t in [0.0, 50.0] {
        cascade.update(t).unwrap();
        let v = variance(&to_f64(cascade.height()));
        var += v / 2.0;
        std += v.sqrt() / 2.0;
    }
    (var, std, cascade.expected_variance())
}

#[test]
fn calibration_over_seeds_matches_expected_variance_and_hs() {
    // JONSWAP U = 10 m/s, F = 100 km: peak wavelength ≈ 60 m, on L = 1000 m, N = 256 (cell
    // 3.9 m, k up to 0.80 rad/m on the axes): the peak (k_p ≈ 0.10) sits 16 Δk from the
    // origin, so ~100 grid vectors share its ring and the spectrum is well resolved.
    let spectrum = jonswap(0.4);
    let (n, length) = (256, 1000.0f32);
    let seeds = 32;
    let mut vars = Vec::new();
    let mut stds = Vec::new();
    let mut expected = None;
    for seed in 0..seeds {
        let (var, std, e) = height_stats(&spectrum, config(n, length, 1000 + seed));
        vars.push(var);
        stds.push(std);
        // The expectation does not depend on the seed.
        assert_eq!(*expected.get_or_insert(e), e);
    }
    let expected = expected.unwrap();
    let mean_var = mean(&vars);
    // Standard error of the seed average from the per-seed spread.
    let se_var = sample_std(&vars) / (seeds as f64).sqrt() / mean_var;
    let ratio_var = mean_var / expected;
    println!(
        "var(η): seed mean {mean_var:.5} m², expected_variance {expected:.5} m², ratio {ratio_var:.4}, \
         relative standard error {se_var:.4} (per-seed spread {:.3})",
        sample_std(&vars) / mean_var
    );
    // E[var η] = Σ E|h̃|² = Σ S Δk² exactly for h0 = ½(ξr + iξi)√S Δk, so only sampling noise
    // remains. Measured: per-seed spread 4.1 %, relative standard error of the 32-seed mean
    // 0.73 %, ratio 1.0010; 5 % is ≈ 7 standard errors, so a miscalibration of ≥ 5 % (the
    // classic 2× amplitude error is +300 %) fails and sampling noise does not.
    assert!(
        (ratio_var - 1.0).abs() < 0.05,
        "var ratio {ratio_var} (SE {se_var})"
    );

    // H_s = 4·std(η), seed-averaged (E√var is below √E var by ≈ spread²/8 ≈ 0.3 %).
    let hs_sim = 4.0 * mean(&stds);
    let se_hs = sample_std(&stds) / (seeds as f64).sqrt() * 4.0 / hs_sim;
    let hs_expected = 4.0 * expected.sqrt();
    // The grid covers the square |m_x|, |m_z| < N/2; `band_variance` integrates annuli. The
    // largest annulus inside the square is [Δk, (N/2)Δk) (no grid vector below Δk; the
    // spectrum has nothing there: e^{−5/4 (ω_p/ω)⁴} < e^{−300}). The corners beyond it hold at
    // most band_variance((N/2)Δk, √2(N/2)Δk), checked to be < 1 % of the total below, so the
    // annulus is a fair independent (quadrature) stand-in for the square.
    let dk = TAU as f32 / length;
    let k_in = dk * (n / 2) as f32;
    let annulus = f64::from(spectrum.band_variance(dk, k_in));
    let corners = f64::from(spectrum.band_variance(k_in, k_in * std::f32::consts::SQRT_2));
    assert!(
        corners < 0.01 * annulus,
        "corners {corners} vs annulus {annulus}"
    );
    let hs_annulus = 4.0 * annulus.sqrt();
    let hs_spectrum = f64::from(spectrum.significant_wave_height());
    println!(
        "H_s: simulated {hs_sim:.4} m (relative SE {se_hs:.4}); 4√expected_variance {hs_expected:.4} m \
         (ratio {:.4}); 4√band_variance(Δk, N/2·Δk) {hs_annulus:.4} m (ratio {:.4}); corner band \
         variance {:.2e} of the annulus; spectrum H_s {hs_spectrum:.4} m (ratio {:.4})",
        hs_sim / hs_expected,
        hs_sim / hs_annulus,
        corners / annulus,
        hs_sim / hs_spectrum
    );
    assert!((hs_sim / hs_expected - 1.0).abs() < 0.05);
    assert!((hs_sim / hs_annulus - 1.0).abs() < 0.05);
    // The grid sum against the quadrature, without sampling noise: the grid resolves the
    // peak, so Σ S Δk² over the square matches the annulus integral plus at most the corners
    // to a few per cent (Δk-grid quadrature of a peak 16 Δk wide).
    let quadrature = (expected - annulus) / annulus;
    println!("expected_variance vs annulus quadrature: {quadrature:+.4}");
    assert!(quadrature.abs() < 0.03, "{expected} vs {annulus}");
}

#[test]
fn same_seed_and_length_give_identical_h0_at_every_resolution() {
    let spectrum = jonswap(0.4);
    let length = 1000.0;
    let sizes = [64, 128, 256];
    let cascades: Vec<Cascade> = sizes
        .iter()
        .map(|&n| Cascade::new(&spectrum, config(n, length, 77)).unwrap())
        .collect();
    for (a, &na) in sizes.iter().enumerate() {
        for (b, &nb) in sizes.iter().enumerate().skip(a + 1) {
            let (ha, hb) = (cascades[a].h0(), cascades[b].h0());
            let mut compared = 0;
            let mut nonzero = 0;
            for j in 0..na {
                for i in 0..na {
                    // The smaller grid's Nyquist row and column are zero there, but ordinary
                    // vectors of the larger grid.
                    if i == na / 2 || j == na / 2 {
                        continue;
                    }
                    let (mx, mz) = (m(i, na), m(j, na));
                    let other = index_of(mz, nb) * nb + index_of(mx, nb);
                    let (x, y) = (ha[j * na + i], hb[other]);
                    assert!(
                        x.re.to_bits() == y.re.to_bits() && x.im.to_bits() == y.im.to_bits(),
                        "m = ({mx}, {mz}): N={na} {x} vs N={nb} {y}"
                    );
                    compared += 1;
                    nonzero += usize::from(x.norm() > 0.0);
                }
            }
            assert_eq!(compared, (na - 1) * (na - 1));
            assert!(
                nonzero > compared / 2,
                "mostly zero h0: the test compares nothing"
            );
        }
    }
    // A different seed gives different waves.
    let other = Cascade::new(&spectrum, config(64, length, 78)).unwrap();
    assert!(other.h0()[3 * 64 + 5] != cascades[0].h0()[3 * 64 + 5]);
}

#[test]
fn h0_is_zero_exactly_outside_the_band() {
    let spectrum = jonswap(0.4);
    let (n, length) = (128, 1000.0f32);
    let dk = TAU / f64::from(length);
    for (k_min, k_max) in [(0.05f32, 0.3f32), (0.0, 0.1), (0.2, f32::INFINITY)] {
        let cascade = Cascade::new(
            &spectrum,
            CascadeConfig {
                k_min,
                k_max,
                ..config(n, length, 9)
            },
        )
        .unwrap();
        let (lo, hi) = (f64::from(k_min), f64::from(k_max));
        let mut inside = 0;
        for j in 0..n {
            for i in 0..n {
                let h = cascade.h0()[j * n + i];
                let k = dk * (m(i, n) as f64).hypot(m(j, n) as f64);
                // No grid |k| sits within 1e-6 of a band edge here, so f32/f64 rounding of the
                // limits cannot move a vector across.
                assert!(
                    k == 0.0
                        || ((k - lo).abs() > 1e-6 * lo
                            && (hi.is_infinite() || (k - hi).abs() > 1e-6 * hi)),
                    "|k| = {k} on a band edge"
                );
                let nyquist = i == n / 2 || j == n / 2;
                if k == 0.0 || k < lo || k >= hi || nyquist {
                    assert!(h.re == 0.0 && h.im == 0.0, "({i},{j}) |k| = {k}: h0 = {h}");
                } else {
                    // In the band h0 = ½ξ√S Δk is non-zero wherever S is not negligible (at
                    // |k| = Δk, far below the peak, JONSWAP's e^{−5/4 (ω_p/ω)⁴} ≈ e^{−320}
                    // underflows h0 in f32); a normal pair is (0, 0) with probability 0.
                    let s = spectrum
                        .density([(m(i, n) as f64 * dk) as f32, (m(j, n) as f64 * dk) as f32]);
                    assert!(
                        h.norm() > 0.0 || s < 1e-40,
                        "({i},{j}) |k| = {k} in band, S = {s}, but h0 = 0"
                    );
                    inside += 1;
                }
            }
        }
        println!("band [{k_min}, {k_max}): {inside} wave vectors");
        assert!(inside > 0);
    }
}
