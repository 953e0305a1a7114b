//! The foam's unit tests: transport, calibration and the step against plain transforms.
//! References use the standard library's maths (tests are not simulation code).
#![allow(clippy::disallowed_methods)]

use num_complex::Complex32;

use super::state::FLUSH;
use super::FoamConfig;
use crate::math::determinism::{with_math, Determinism, Std};
use crate::math::exp::exp;
use crate::math::simd::Simd;
use crate::ocean::{OceanConfig, OceanState};
use crate::spectrum::Spectrum;

/// An ocean that never breaks (coverage 0) with a Gaussian blob of residual foam, σ₀ = 3
/// grid points, in the middle of its 64² foam grid.
fn blob_ocean(wind_direction: f32) -> (OceanState, [f64; 2], f64) {
    let spectrum = Spectrum::pierson_moskowitz(20.0)
        .and_then(|s| s.with_wind_direction(wind_direction))
        .unwrap();
    let config = OceanConfig {
        size: 64,
        lengths: vec![200.0, 46.0],
        foam: FoamConfig {
            coverage: 0.0,
            streak_length: 0.05,
            streak_width: 0.02,
            residual_decay: 30.0,
            ..FoamConfig::default()
        },
        ..OceanConfig::default()
    };
    let mut ocean = OceanState::new(spectrum, config).unwrap();
    let h = 200.0 / 64.0;
    let (centre, sigma) = ([100.0, 90.0], 3.0 * h);
    for j in 0..64 {
        for i in 0..64 {
            let (dx, dz) = (i as f64 * h - centre[0], j as f64 * h - centre[1]);
            let r = 0.5 * (-(dx * dx + dz * dz) / (2.0 * sigma * sigma)).exp();
            ocean.foam.residual[j * 64 + i] = r as f32;
        }
    }
    ocean.foam.finish();
    (ocean, centre, sigma)
}

/// Mass, centroid and covariance (m²) of the residual foam.
fn moments(ocean: &OceanState) -> (f64, [f64; 2], [[f64; 2]; 2]) {
    let h = 200.0 / 64.0;
    let r = &ocean.foam.residual;
    let mass: f64 = r.iter().map(|&v| f64::from(v)).sum();
    let mut mean = [0.0; 2];
    let mut second = [[0.0; 2]; 2];
    for j in 0..64 {
        for i in 0..64 {
            let w = f64::from(r[j * 64 + i]) / mass;
            let p = [i as f64 * h, j as f64 * h];
            for a in 0..2 {
                mean[a] += w * p[a];
                for b in 0..2 {
                    second[a][b] += w * p[a] * p[b];
                }
            }
        }
    }
    let cov = [0, 1].map(|a| [0, 1].map(|b| second[a][b] - mean[a] * mean[b]));
    (mass, mean, cov)
}

/// The transport against the closed form of advection-diffusion with constant
/// coefficients: the blob's mass decays as e^{−t/τ_R} (nothing else acts on it), its
/// centroid moves by u·t downwind and its covariance grows by 2K·t, with K∥ along the wind
/// and K⊥ across (from the streak settings: (streak·λ_p)²/(2τ_R)).
#[test]
fn residual_blob_drifts_and_spreads_as_the_closed_form_says() {
    let wind = 0.6f32;
    let (mut ocean, centre, sigma) = blob_ocean(wind);
    let (mass0, _, _) = moments(&ocean);
    let t = 10.0;
    for _ in 0..20 {
        ocean.step(t / 20.0).unwrap();
    }
    let (mass, mean, cov) = moments(&ocean);
    let spectrum = ocean.spectrum();
    let k = spectrum
        .dispersion()
        .k_from_omega_with::<Std>(f64::from(spectrum.peak_omega()));
    let wavelength = std::f64::consts::TAU / k;
    let diffusivity = |streak: f64| (streak * wavelength).powi(2) / 60.0;
    let (along, across) = (diffusivity(0.05), diffusivity(0.02));
    let drift = 0.03 * 20.0;
    let (w, n) = (
        [f64::from(wind).cos(), f64::from(wind).sin()],
        [-f64::from(wind).sin(), f64::from(wind).cos()],
    );
    // f32 buffers and transforms, and the flush of foam below 1e-6 (the blob's far tails)
    // at every step: a relative error of a few 1e-5 on the mass.
    assert!(
        (mass / mass0 - (-t / 30.0f64).exp()).abs() < 2e-4,
        "{mass} {mass0}"
    );
    for a in 0..2 {
        let expected = centre[a] + drift * t * w[a];
        assert!((mean[a] - expected).abs() < 1e-3, "mean {mean:?}");
    }
    let form = |u: [f64; 2], v: [f64; 2]| {
        (0..2)
            .map(|a| (0..2).map(|b| u[a] * cov[a][b] * v[b]).sum::<f64>())
            .sum::<f64>()
    };
    let s2 = sigma * sigma;
    // The blob is 3 grid points wide and grows to 4–6: its tails beyond the tile and the
    // grid's Nyquist cut are far below 1e-3 of its variance.
    assert!(
        (form(w, w) - (s2 + 2.0 * along * t)).abs() < 1e-3 * s2,
        "{cov:?}"
    );
    assert!(
        (form(n, n) - (s2 + 2.0 * across * t)).abs() < 1e-3 * s2,
        "{cov:?}"
    );
    assert!(form(w, n).abs() < 1e-3 * s2, "{cov:?}");
    assert!(
        along > 2.0 * across && along * t > s2 / 4.0,
        "{along} {across}"
    );
}

/// The foam's element loops (intensity, aging, transport multipliers, totals and sums)
/// give the same bits at every SIMD level the machine has and at 1, 2 and 3 threads, as
/// the baseline build at 1 thread: the active, residual and total foam, the intensity and
/// the coverage after steps with breaking, residual foam and transport, a refresh (a jump
/// in time) and a pre-roll.
#[test]
fn every_simd_level_and_thread_count_gives_the_same_foam() {
    let levels = Simd::available();
    // On a CPU with AVX-512 (as the project's machines) all three levels must be covered,
    // or the test would pass vacuously.
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx512f") && std::is_x86_feature_detected!("avx512bw") {
        assert_eq!(levels.len(), 3, "{levels:?}");
    }
    let pools = crate::math::simd::test_pools();
    let run = |level: Simd, pool: &rayon::ThreadPool| {
        pool.install(|| {
            let spectrum = Spectrum::jonswap(16.0, 300_000.0).unwrap();
            let config = OceanConfig {
                size: 64,
                ..OceanConfig::default()
            };
            let mut ocean = OceanState::new(spectrum, config).unwrap();
            ocean.foam.set_simd(level);
            ocean.set_time(500.0).unwrap();
            let mut bits: Vec<u32> = Vec::new();
            let mut record = |ocean: &OceanState| {
                let foam = &ocean.foam;
                for buffer in [&foam.active, &foam.residual, &foam.total, &foam.breaking] {
                    bits.extend(buffer.iter().map(|v| v.to_bits()));
                }
                let c = ocean.foam_view().coverage();
                bits.extend([c.active, c.residual, c.total].map(f32::to_bits));
            };
            for _ in 0..40 {
                ocean.step(0.1).unwrap();
            }
            record(&ocean);
            ocean.set_time(731.25).unwrap();
            record(&ocean);
            ocean.pre_roll(3.0, 1.0 / 30.0).unwrap();
            record(&ocean);
            let coverage = ocean.foam_view().coverage();
            assert!(
                coverage.active > 1e-3 && coverage.residual > 1e-4,
                "the test needs foam: {coverage:?}"
            );
            bits
        })
    };
    let expected = run(Simd::Baseline { fused: true }, &pools[0].1);
    for &level in &levels {
        for (threads, pool) in &pools {
            assert!(
                run(level, pool) == expected,
                "{level:?} at {threads} threads differs from the baseline at 1 thread"
            );
        }
    }
}

/// The fused real-data step (two rows packed in one complex row, half the columns
/// transformed, the transport's factor between the two column transforms, the last row
/// transform fused with the totals) gives, to the rounding of the transforms, what the
/// plain complex sequence gives: the residual foam after aging, transformed by the public
/// `Fft2d`, multiplied by M(k) point by point, transformed back by `Fft2d`, scaled,
/// clamped and flushed. Run for both determinism modes and two grid sizes, at 1 and 2
/// threads; the reference runs at the baseline SIMD level, the step at the machine's
/// widest.
#[test]
fn real_data_transport_matches_two_plain_complex_fft2d_transforms() {
    let pools = crate::math::simd::test_pools();
    for determinism in [Determinism::SameMachine, Determinism::CrossPlatform] {
        for (n, threads) in [(64, 1), (64, 2), (128, 2)] {
            let (_, pool) = &pools[threads - 1];
            pool.install(|| {
                let spectrum = Spectrum::jonswap(16.0, 300_000.0).unwrap();
                let config = OceanConfig {
                    size: n,
                    determinism,
                    ..OceanConfig::default()
                };
                let mut ocean = OceanState::new(spectrum, config).unwrap();
                for _ in 0..30 {
                    ocean.step(0.1).unwrap();
                }
                let dt = 0.1;
                // The same step without transport: the aged foam the transport starts from.
                let mut reference = ocean.foam.clone();
                let transport = reference.transport.clone();
                assert!(transport.is_active());
                reference.transport.drift = [0.0; 2];
                reference.transport.tensor = [0.0; 3];
                ocean.step(dt).unwrap();
                reference.gradient.copy_from_slice(&ocean.foam.gradient);
                reference.advance(dt);
                let mut tables = vec![Complex32::default(); 2 * n];
                with_math!(determinism, M => transport.fill_tables::<M>(dt, n, &mut tables));
                let [a, b, c] = transport.exponent(dt);
                let mut fft = crate::inspect::Fft2d::with_determinism(n, 1, determinism).unwrap();
                let mut work: Vec<Complex32> = reference
                    .residual
                    .iter()
                    .map(|&r| Complex32::new(r, 0.0))
                    .collect();
                // The transform is left transposed: index m_x·N + m_z.
                let spectrum = fft.process(&mut work).unwrap().to_vec();
                for ix in 0..n {
                    let mx = crate::math::grid::wave_index(ix, n) as f32;
                    for iz in 0..n {
                        let mz = crate::math::grid::wave_index(iz, n) as f32;
                        let (ax, bx) = (a * mx * mx, 2.0 * b * mx);
                        let decay = exp(-(ax + mz * (bx + c * mz)));
                        work[ix * n + iz] =
                            spectrum[ix * n + iz].conj() * (tables[ix] * tables[n + iz]) * decay;
                    }
                }
                let moved = fft.process(&mut work).unwrap();
                let scale = 1.0 / (n * n) as f32;
                let mut moving = 0;
                let (mut worst, mut peak) = (0.0f32, 0.0f32);
                for (k, v) in moved.iter().enumerate() {
                    let r = v.re * scale;
                    let r = if r < FLUSH { 0.0 } else { r.min(1.0) };
                    worst = worst.max((r - ocean.foam.residual[k]).abs());
                    peak = peak.max(r);
                    moving += usize::from(r != reference.residual[k]);
                }
                // Two transforms of N² points in f32 round each value to about
                // ε·log₂(N²) ≈ 6e-8 × 14 of the largest (8e-7); the real-data transform
                // rounds in other places (and keeps only the Hermitian part at the
                // Nyquist wave numbers, which hold next to nothing), so it may differ by
                // that much, not more. Measured: 1.5e-8 at a peak of 0.09.
                assert!(
                    worst <= 1e-6 * peak,
                    "{determinism:?} N = {n}, {threads} threads: {worst:e} (peak {peak})"
                );
                assert!(moving > n * n / 2, "the test needs foam that moves");
                for (x, y) in ocean.foam.active.iter().zip(&reference.active) {
                    assert_eq!(x.to_bits(), y.to_bits());
                }
            });
        }
    }
}

/// Steps compose exactly: twenty steps of 0.5 s move the blob as ten of 1 s and one of
/// 10 s, to the rounding of the transforms (1e-7 of the peak per step) and the flush of
/// values below 1e-6 at each step.
#[test]
fn transport_steps_compose() {
    let runs: Vec<Vec<f32>> = [(20, 0.5), (10, 1.0), (1, 10.0)]
        .iter()
        .map(|&(steps, dt)| {
            let (mut ocean, _, _) = blob_ocean(2.2);
            for _ in 0..steps {
                ocean.step(dt).unwrap();
            }
            ocean.foam.residual.clone()
        })
        .collect();
    for other in &runs[1..] {
        let worst = runs[0]
            .iter()
            .zip(other)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f32, f32::max);
        assert!(worst < 1e-5, "{worst}");
    }
}

/// The intensity works on the gradient scaled by c and on its rate scaled by d, powers of two
/// that are 1 on ordinary seas (`Params::new`): every quantity is then its unscaled value
/// times a power of two, so with any c and d that keep them in f32's normal range the
/// intensity has the same bits as unscaled, on the scaled path and at every SIMD level. On a
/// 15 m/s sea at 64², with c and d from 1 to 2⁻²⁰ (its sums then stay above 1e-35).
#[test]
fn scaling_the_intensity_by_powers_of_two_keeps_its_bits() {
    let spectrum = Spectrum::jonswap(15.0, 300_000.0)
        .and_then(|s| s.with_wind_direction(0.7))
        .unwrap();
    let config = OceanConfig {
        size: 64,
        choppiness: 1.5,
        ..OceanConfig::default()
    };
    let mut ocean = OceanState::new(spectrum, config).unwrap();
    ocean.step(2.5).unwrap();
    let foam = &ocean.foam;
    let (n, p) = (foam.n, foam.params);
    assert_eq!(
        (p.unit, p.crossing_scale),
        (1.0, super::intensity::INV_SQRT_TAU)
    );
    let mut unscaled = vec![0.0f32; n * n];
    Simd::Baseline { fused: true }.run(|| p.intensity_row(&foam.gradient, &mut unscaled));
    assert!(unscaled.iter().filter(|&&s| s > 0.1 * p.inv_active).count() > 20);
    for (c, d) in [(0, 3), (1, 0), (5, 2), (12, 7), (20, 9)] {
        let (c, d) = (0.5f32.powi(c), 0.5f32.powi(d));
        let scaled = super::intensity::Params {
            threshold: p.threshold * c * c,
            unit: c,
            unresolved: p.unresolved.map(|v| v * c * c),
            rate: p.rate.map(|v| v * (c * d) * (c * d)),
            floor: p.floor * (c * c) * (c * c),
            crossing_scale: p.crossing_scale / d,
            ..p
        };
        for simd in Simd::available() {
            let mut out = vec![f32::NAN; n * n];
            simd.run(
                #[inline(always)]
                || scaled.intensity_row(&foam.gradient, &mut out),
            );
            for (k, (a, b)) in out.iter().zip(&unscaled).enumerate() {
                assert_eq!(
                    a.to_bits(),
                    b.to_bits(),
                    "c {c}, d {d}, {simd:?}, point {k}: {a} {b}"
                );
            }
        }
    }
}
