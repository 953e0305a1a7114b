//! Loops without frozen waves: with a repeat period every wave keeps a frequency of at least
//! one cycle per loop, the fields repeat exactly, and the reported frequency error is what the
//! wave vectors' frequencies say.
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

use std::f64::consts::TAU;

use ocean_fft::inspect;
use ocean_fft::{Dispersion, OceanConfig, OceanState, Spectrum};

fn looping_ocean(period: f32, size: usize) -> OceanState {
    let spectrum = Spectrum::jonswap(10.0, 100_000.0).unwrap();
    let config = OceanConfig {
        size,
        repeat_period: Some(period),
        ..OceanConfig::default()
    };
    OceanState::new(spectrum, config).unwrap()
}

#[test]
fn a_four_second_loop_of_the_default_sea_freezes_nothing() {
    // The case that froze 88 % of the energy when ω was rounded down.
    let ocean = looping_ocean(4.0, 128);
    let (mut energy, mut frozen) = (0.0f64, 0.0f64);
    let (mut worst, mut weighted) = (0.0f64, 0.0f64);
    for cascade in ocean.cascades() {
        let n = cascade.size();
        let dk = f64::from(cascade.delta_k());
        for j in 0..n {
            for i in 0..n {
                let e = f64::from(cascade.h0()[j * n + i].norm_sqr());
                if e == 0.0 {
                    continue;
                }
                let omega = inspect::omega_at(cascade, i, j).unwrap();
                energy += e;
                if omega == 0.0 {
                    frozen += e;
                }
                // The error against ω = √(g k) computed here, independently of the crate.
                let m = |i: usize| {
                    if i < n / 2 {
                        i as f64
                    } else {
                        i as f64 - n as f64
                    }
                };
                let k = dk * m(i).hypot(m(j));
                let exact = Dispersion::Deep.omega(k as f32) as f64;
                let relative = (omega - exact).abs() / exact;
                worst = worst.max(relative);
                weighted += e * relative;
            }
        }
    }
    assert_eq!(frozen, 0.0, "frozen share {}", frozen / energy);
    let error = ocean.diagnostics().loop_error().unwrap();
    // Δk in f32 and ω in f32 here against the crate's f64: 1e-6 relative agreement.
    assert!(
        (error.max_relative / worst - 1.0).abs() < 1e-5,
        "{error:?} vs {worst}"
    );
    assert!(
        (error.mean_relative / (weighted / energy) - 1.0).abs() < 1e-5,
        "{error:?} vs {}",
        weighted / energy
    );
    assert!((error.variance / (2.0 * energy) - 1.0).abs() < 1e-9);
    // Most of the default sea's energy sits in waves of 3–8 s, a few cycles per 4 s loop, so
    // the energy-weighted error is tens of per cent, and the longest waves (periods near
    // 25 s, sped up to one cycle per 4 s) are several times too fast.
    assert!(
        error.mean_relative > 0.01 && error.mean_relative < 0.5,
        "{error:?}"
    );
    assert!(error.max_relative > 2.0, "{error:?}");
}

#[test]
fn longer_loops_cost_less_and_no_loop_costs_nothing() {
    let errors: Vec<f64> = [4.0, 16.0, 64.0, 256.0]
        .iter()
        .map(|&t| {
            looping_ocean(t, 64)
                .diagnostics()
                .loop_error()
                .unwrap()
                .mean_relative
        })
        .collect();
    for pair in errors.windows(2) {
        assert!(pair[1] < pair[0], "{errors:?}");
    }
    // At T = 256 s every wave keeps its frequency within 1/(2T) Hz: at most π/T rad/s off.
    let ocean = looping_ocean(256.0, 64);
    let bound = std::f64::consts::PI / 256.0;
    for cascade in ocean.cascades() {
        let n = cascade.size();
        for j in 0..n {
            for i in 0..n {
                if cascade.h0()[j * n + i].norm_sqr() == 0.0 {
                    continue;
                }
                let omega = inspect::omega_at(cascade, i, j).unwrap();
                let m = |i: usize| {
                    if i < n / 2 {
                        i as f64
                    } else {
                        i as f64 - n as f64
                    }
                };
                let k = f64::from(cascade.delta_k()) * m(i).hypot(m(j));
                let exact = (9.81 * k).sqrt();
                if exact > TAU / 256.0 {
                    assert!(
                        (omega - exact).abs() <= bound * (1.0 + 1e-4),
                        "{omega} vs {exact}"
                    );
                }
            }
        }
    }
    let spectrum = Spectrum::jonswap(10.0, 100_000.0).unwrap();
    let plain = OceanState::new(
        spectrum,
        OceanConfig {
            size: 32,
            ..OceanConfig::default()
        },
    )
    .unwrap();
    assert!(plain.diagnostics().loop_error().is_none());
}

#[test]
fn the_loop_repeats_exactly() {
    let mut ocean = looping_ocean(4.0, 64);
    ocean.set_time(1.25).unwrap();
    let first: Vec<f32> = ocean.cascades()[0].height().to_vec();
    ocean.set_time(1.25 + 4.0 * 3.0).unwrap();
    let later: Vec<f32> = ocean.cascades()[0].height().to_vec();
    let worst = first
        .iter()
        .zip(&later)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    // t mod T is reduced in f64, so the phases agree to rounding: 1e-6 m on metre waves.
    assert!(worst < 1e-5, "{worst} m");
}
