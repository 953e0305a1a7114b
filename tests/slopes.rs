//! Slope variance along and across the wind (`Spectrum::slope_variance`, the sub-grid part
//! of cascades and oceans) against an independent quadrature, and the Elfouhaily et al.
//! (1997) spectrum against statements of the paper and Cox & Munk's (1954) measurements.
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

use std::f64::consts::{PI, TAU};

use ocean_fft::inspect::SlopeVariance;
use ocean_fft::{DepthFactor, Error, OceanConfig, OceanState, Spectrum, Spreading, GRAVITY};

/// Slope variance along and across the wind of `spectrum` over k_min ≤ |k| < k_max by a
/// polar quadrature of `Spectrum::density` (f32 evaluation, as a user would): trapezoid
/// in ln k with `nk` nodes, midpoint rule over 720 directions; integrand
/// S(k) (k·ŵ)² k² d(ln k) dθ. Nothing of the library's quadrature is shared.
fn polar_slope_variance(spectrum: &Spectrum, k_min: f64, k_max: f64, nk: usize) -> [f64; 2] {
    let wind = f64::from(spectrum.wind_direction());
    let (a, b) = (k_min.ln(), k_max.ln());
    let h = (b - a) / (nk - 1) as f64;
    let directions = 720;
    let dtheta = TAU / directions as f64;
    let (mut along, mut across) = (0.0, 0.0);
    for i in 0..nk {
        let k = (a + i as f64 * h).exp();
        let weight = if i == 0 || i == nk - 1 { 0.5 } else { 1.0 };
        for d in 0..directions {
            let theta = (d as f64 + 0.5) * dtheta;
            let (s, c) = theta.sin_cos();
            let density = f64::from(spectrum.density([(k * c) as f32, (k * s) as f32]));
            let (sr, cr) = (theta - wind).sin_cos();
            let common = weight * density * k.powi(4) * h * dtheta;
            along += common * cr * cr;
            across += common * sr * sr;
        }
    }
    [along, across]
}

fn close(got: SlopeVariance, expected: [f64; 2], tolerance: f64) -> bool {
    (f64::from(got.along) / expected[0] - 1.0).abs() < tolerance
        && (f64::from(got.across) / expected[1] - 1.0).abs() < tolerance
}

/// `Spectrum::slope_variance` (Simpson in ln k with closed-form angular moments) against
/// the polar quadrature of the density, for every kind of spreading, a wind direction off
/// the axes, and bands across the peak and in the tail. Tolerance 0.5 %: the polar
/// quadrature's f32 density (1e-7), its trapezoid in ln k over 2000 nodes (~1e-5 of a
/// smooth integrand) and its 720 midpoints in θ (exact for the trigonometric spreadings,
/// ~1e-4 for the narrowest cos-2s here, s ≈ 40 with swell) leave ~1e-4.
#[test]
fn slope_variance_matches_a_polar_quadrature_of_the_density() {
    let jonswap = Spectrum::jonswap(10.0, 100_000.0).unwrap();
    let cases = vec![
        (
            jonswap.clone().with_wind_direction(0.7).unwrap(),
            0.05,
            50.0,
        ),
        (
            jonswap
                .clone()
                .with_spreading(Spreading::Mitsuyasu)
                .unwrap()
                .with_swell(0.5)
                .unwrap(),
            0.08,
            5.0,
        ),
        (
            jonswap
                .clone()
                .with_spreading(Spreading::Cosine {
                    exponent: 4.0,
                    upwind: 0.3,
                })
                .unwrap()
                .with_spread_blend(0.6)
                .unwrap(),
            0.2,
            20.0,
        ),
        (
            jonswap
                .clone()
                .with_spreading(Spreading::Hasselmann)
                .unwrap(),
            0.05,
            2.0,
        ),
        (jonswap.with_spreading(Spreading::Cos2).unwrap(), 1.0, 30.0),
        (
            Spectrum::elfouhaily(10.0, 0.84)
                .unwrap()
                .with_wind_direction(-2.0)
                .unwrap(),
            0.02,
            3000.0,
        ),
        (Spectrum::elfouhaily(6.0, 3.0).unwrap(), 1.0, 2000.0),
    ];
    for (spectrum, k_min, k_max) in cases {
        let got = spectrum.slope_variance(k_min as f32, k_max as f32);
        let expected = polar_slope_variance(&spectrum, k_min, k_max, 2000);
        println!(
            "{:?} {k_min}–{k_max} rad/m: along {:.6} across {:.6} (polar {:.6} {:.6})",
            spectrum.spreading_kind(),
            got.along,
            got.across,
            expected[0],
            expected[1]
        );
        assert!(
            close(got, expected, 5e-3),
            "{spectrum:?}: {got:?} vs {expected:?}"
        );
        assert_eq!(got.total(), got.along + got.across);
    }
    // Empty and inverted bands hold nothing.
    let s = Spectrum::jonswap(10.0, 100_000.0).unwrap();
    assert_eq!(s.slope_variance(5.0, 5.0), SlopeVariance::default());
    assert_eq!(s.slope_variance(5.0, 1.0), SlopeVariance::default());
    assert_eq!(s.slope_variance(f32::NAN, 1.0), SlopeVariance::default());
}

/// Each cascade's sub-grid slope variance is what the spectrum holds between the top of its
/// band and the cut-off (by the independent quadrature), the ocean's is the last cascade's,
/// and the `Normal` texels carry its total in alpha.
#[test]
fn sub_grid_slope_variance_is_the_spectrum_above_the_band() {
    let spectrum = Spectrum::jonswap(10.0, 100_000.0).unwrap();
    let config = OceanConfig {
        size: 64,
        ..OceanConfig::default()
    };
    let bands = config.bands().unwrap();
    let ocean = OceanState::new(spectrum.clone(), config).unwrap();
    let cutoff = f64::from(SlopeVariance::DEFAULT_CUTOFF);
    for (c, cascade) in ocean.cascades().iter().enumerate() {
        let top = f64::from(bands[c].1);
        let expected = polar_slope_variance(&spectrum, top, cutoff, 2000);
        let got = cascade.subgrid_slope_variance();
        println!("cascade {c}: above {top:.2} rad/m: {got:?} (polar {expected:?})");
        assert!(close(got, expected, 5e-3), "cascade {c}");
        let mut texels = vec![[0.0f32; 4]; 64 * 64];
        ocean
            .textures()
            .pack(c, ocean_fft::gpu::TexelLayout::Normal, &mut texels)
            .unwrap();
        assert!(texels.iter().all(|t| t[3] == got.total()));
    }
    assert_eq!(
        ocean.textures().subgrid_slope_variance(),
        ocean.cascades()[2].subgrid_slope_variance()
    );
    // The grid plus the sub-grid part is the whole spectrum up to the cut-off.
    let resolved: f32 = bands
        .iter()
        .map(|&(lo, hi)| spectrum.slope_variance(lo, hi).total())
        .sum();
    let whole = spectrum
        .slope_variance(0.0, SlopeVariance::DEFAULT_CUTOFF)
        .total();
    let sum = resolved + ocean.textures().subgrid_slope_variance().total();
    assert!((sum / whole - 1.0).abs() < 1e-3, "{sum} vs {whole}");
}

/// The omnidirectional spectrum ∫ S(k) k dθ by a midpoint rule over 720 directions.
fn omni(spectrum: &Spectrum, k: f64) -> f64 {
    let n = 720;
    (0..n)
        .map(|i| {
            let t = (i as f64 + 0.5) / n as f64 * TAU;
            f64::from(spectrum.density([(k * t.cos()) as f32, (k * t.sin()) as f32]))
        })
        .sum::<f64>()
        * TAU
        / n as f64
        * k
}

/// The wave number in [lo, hi] where `f` peaks, on a geometric grid of ratio 1.001.
fn argmax(lo: f64, hi: f64, f: impl Fn(f64) -> f64) -> f64 {
    let mut best = (lo, f(lo));
    let mut k = lo;
    while k < hi {
        k *= 1.001;
        let v = f(k);
        if v > best.1 {
            best = (k, v);
        }
    }
    best.0
}

/// Elfouhaily et al. (1997) against their own statements and Cox & Munk (1954).
///
/// - The curvature spectrum k³S(k) has its gravity–capillary peak at k_m = 370 rad/m
///   (within 2 %: the long-wave part's slope shifts the maximum slightly).
/// - Long-wave limit: the elevation spectrum peaks at k_p = Ω² g/U10², the JONSWAP peak
///   of the wave age (within 3 %: the peak enhancement is asymmetric around k_p), for
///   Ω = 0.84 (fully developed) to 5.
/// - Mean-square slope against Cox & Munk's clean-surface fit 0.003 + 5.12·10⁻³ U10 for
///   U10 = 5, 10, 15 m/s: within 15 % (measured +11 %, +12 %, +6 %; Cox & Munk's own scatter
///   about their fit is ±0.004, 7–14 % of these values), and the cross-wind share against
///   their up/cross-wind fits (3.16·10⁻³ U10 and 0.003 + 1.92·10⁻³ U10) within 10 %.
#[test]
fn elfouhaily_matches_the_paper_and_cox_munk() {
    for u in [5.0f32, 10.0, 15.0] {
        let spectrum = Spectrum::elfouhaily(u, 0.84).unwrap();
        let peak = argmax(100.0, 2000.0, |k| k.powi(3) * omni(&spectrum, k));
        let slopes = spectrum.slope_variance(0.0, 1e5);
        let u = f64::from(u);
        let cox_munk = 0.003 + 5.12e-3 * u;
        let (up, cross) = (3.16e-3 * u, 0.003 + 1.92e-3 * u);
        let mss = f64::from(slopes.total());
        let share = f64::from(slopes.across) / mss;
        println!(
            "U10 = {u}: curvature peak {peak:.1} rad/m; mss {mss:.4} (Cox & Munk {cox_munk:.4}, \
             {:+.1} %), along {:.4} across {:.4} (Cox & Munk {up:.4} {cross:.4}); Hs {:.2} m",
            100.0 * (mss / cox_munk - 1.0),
            slopes.along,
            slopes.across,
            spectrum.significant_wave_height()
        );
        assert!((peak / 370.0 - 1.0).abs() < 0.02, "U10 = {u}: peak {peak}");
        assert!((mss / cox_munk - 1.0).abs() < 0.15, "U10 = {u}: mss {mss}");
        assert!(
            (share / (cross / (up + cross)) - 1.0).abs() < 0.1,
            "U10 = {u}: cross-wind share {share}"
        );
        // The default cut-off keeps all but 0.1 % of it.
        let cut = spectrum
            .slope_variance(0.0, SlopeVariance::DEFAULT_CUTOFF)
            .total();
        assert!(f64::from(cut) / mss > 0.999);
    }
    for omega_c in [0.84f32, 1.0, 2.0, 5.0] {
        let u = 10.0f32;
        let spectrum = Spectrum::elfouhaily(u, omega_c).unwrap();
        let k_p = f64::from(omega_c * omega_c) * f64::from(GRAVITY) / f64::from(u * u);
        let peak = argmax(0.2 * k_p, 5.0 * k_p, |k| omni(&spectrum, k));
        println!("Ω = {omega_c}: elevation peak {peak:.5} rad/m, k_p = {k_p:.5}");
        assert!(
            (peak / k_p - 1.0).abs() < 0.03,
            "Ω = {omega_c}: {peak} vs {k_p}"
        );
        assert_eq!(spectrum.inverse_wave_age(), Some(omega_c));
        // The peak frequency is that of k_p (the capillary term (k_p/k_m)² is below 5e-5
        // there, so deep water to 1e-4).
        let omega_p = (f64::from(GRAVITY) * k_p).sqrt();
        assert!((f64::from(spectrum.peak_omega()) / omega_p - 1.0).abs() < 1e-4);
    }
}

/// Two independent quadratures of the Elfouhaily variance: the library's Simpson in ln k
/// of the omnidirectional spectrum (`significant_wave_height`) and a Cartesian midpoint sum
/// of the directional density over the (k_x, k_z) plane (step k_p/20 out to 40 k_p, which
/// leaves out ~1e-4 of the variance; the midpoint rule's error on the peak, ~(Δk/width)²/24
/// with a peak width ~0.3 k_p, is ~1e-3). Tolerance 1 % in Hs. And the spreading integrates to 1 over direction and is
/// centrosymmetric, D(θ) = D(θ + π), as the paper requires.
#[test]
fn elfouhaily_variance_by_two_quadratures_and_its_spreading() {
    for (u, omega_c) in [(10.0f32, 0.84f32), (7.0, 2.5)] {
        let spectrum = Spectrum::elfouhaily(u, omega_c).unwrap();
        let k_p = f64::from(omega_c * omega_c) * f64::from(GRAVITY) / f64::from(u * u);
        let step = k_p / 20.0;
        let cells = 800i64;
        let mut variance = 0.0;
        for j in -cells..cells {
            for i in -cells..cells {
                let (kx, kz) = ((i as f64 + 0.5) * step, (j as f64 + 0.5) * step);
                variance += f64::from(spectrum.density([kx as f32, kz as f32]));
            }
        }
        let hs_cartesian = 4.0 * (variance * step * step).sqrt();
        let hs = f64::from(spectrum.significant_wave_height());
        println!("U10 = {u}, Ω = {omega_c}: Hs {hs:.4} m (Cartesian sum {hs_cartesian:.4} m)");
        assert!((hs / hs_cartesian - 1.0).abs() < 0.01);
        for k in [0.5 * k_p, k_p, 10.0 * k_p, 100.0, 370.0, 1500.0] {
            let omega = (f64::from(GRAVITY) * k * (1.0 + (k / 370.0).powi(2))).sqrt() as f32;
            let n = 720;
            let mut total = 0.0;
            for d in 0..n {
                let theta = ((d as f64 + 0.5) / n as f64 * TAU - PI) as f32;
                let here = spectrum.spreading(omega, theta);
                let opposite = spectrum.spreading(omega, theta + std::f32::consts::PI);
                // θ + π in f32 moves θ by up to 2e-7 rad: 1e-5 of D's largest value 1/π is
                // "equal".
                assert!((here - opposite).abs() <= 3e-6, "{here} {opposite}");
                total += f64::from(here) * TAU / n as f64;
            }
            assert!((total - 1.0).abs() < 1e-5, "k = {k}: ∫D = {total}");
        }
    }
}

#[test]
fn elfouhaily_refuses_bad_input_naming_the_parameter() {
    let refused = |result: Result<Spectrum, Error>, name: &str| match result {
        Err(Error::OutOfRange { name: n, .. }) | Err(Error::NonFinite { name: n }) => {
            assert_eq!(n, name)
        }
        other => panic!("{name}: {other:?}"),
    };
    refused(Spectrum::elfouhaily(0.0, 1.0), "wind_speed");
    refused(Spectrum::elfouhaily(f32::NAN, 1.0), "wind_speed");
    refused(Spectrum::elfouhaily(250.0, 1.0), "wind_speed");
    refused(Spectrum::elfouhaily(10.0, 0.5), "inverse_wave_age");
    refused(Spectrum::elfouhaily(10.0, 5.5), "inverse_wave_age");
    refused(
        Spectrum::elfouhaily(10.0, f32::INFINITY),
        "inverse_wave_age",
    );
    let spectrum = Spectrum::elfouhaily(10.0, 1.0).unwrap();
    assert!(matches!(
        spectrum.clone().with_gamma(2.0),
        Err(Error::NotApplicable { name: "gamma", .. })
    ));
    assert!(matches!(
        spectrum
            .clone()
            .with_depth_factor(DepthFactor::Kitaigorodskii),
        Err(Error::NotApplicable {
            name: "depth_factor",
            ..
        })
    ));
    assert_eq!(spectrum.alpha(), None);
    assert_eq!(spectrum.gamma(), None);
    assert_eq!(spectrum.fetch(), None);
    assert_eq!(spectrum.spreading_kind(), Spreading::Elfouhaily);
    // Extreme but accepted winds evaluate finitely everywhere.
    for u in [1e-6f32, 0.3, 200.0] {
        for omega_c in [0.84f32, 5.0] {
            let s = Spectrum::elfouhaily(u, omega_c).unwrap();
            for k in [1e-6f32, 1e-3, 0.1, 10.0, 370.0, 1e5, f32::MAX] {
                let d = s.density([k, 0.3 * k]);
                assert!(d.is_finite() && d >= 0.0, "U {u} Ω {omega_c} k {k}: {d}");
                assert!(s.spreading(k, 0.4).is_finite());
                assert!(s.omega_spectrum(k).is_finite());
            }
            assert!(s.significant_wave_height().is_finite());
            let slopes = s.slope_variance(0.0, f32::INFINITY);
            assert!(slopes.along.is_finite() && slopes.across.is_finite());
        }
    }
}
