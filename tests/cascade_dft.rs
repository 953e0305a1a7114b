//! The cascade's eight fields, its packed transforms and its derived outputs against a naive
//! O(N⁴) inverse DFT in f64 of `wave_spectrum(t)` times multipliers written out in the test;
//! `wave_spectrum` itself against the evolution formula computed here from `h0()` and ω.
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]
// Index loops over several parallel buffers read more plainly than zipped iterators here.
#![allow(clippy::needless_range_loop)]

mod common;

use std::f64::consts::TAU;

use common::*;
use ocean_fft::inspect;
use ocean_fft::{Cascade, CascadeConfig, Error, Spectrum, GRAVITY};

/// Powers of two, 24 (not a power of two), and 6, 10, 18, 34 (N/2 odd; 34 also not a
/// multiple of the 16-row task blocks).
const SIZES: [usize; 8] = [6, 8, 10, 16, 18, 24, 32, 34];
/// Including a negative time and one near `MAX_TIME` (1e9 s).
const TIMES: [f64; 6] = [0.0, 1.3, 17.9, 1000.25, -7.5, 9.9e8];
const LENGTH: f32 = 200.0;
const LAMBDA: f32 = 0.8;

fn spectra() -> Vec<(&'static str, Spectrum)> {
    vec![
        ("JONSWAP θw=0.4", jonswap(0.4)),
        ("Phillips θw=-1.1", phillips(-1.1)),
    ]
}

fn cascade(spectrum: &Spectrum, n: usize) -> Cascade {
    Cascade::new(
        spectrum,
        CascadeConfig {
            size: n,
            length: LENGTH,
            choppiness: LAMBDA,
            seed: 7,
            ..CascadeConfig::default()
        },
    )
    .unwrap()
}

/// Tolerance on a field, relative to the field's largest |value|.
///
/// The cascade works in f32: h̃ is rounded to f32 (6e-8 relative), its phase uses an f32
/// sin/cos good to 5e-7, the multipliers are formed in f32 (a few 1e-7), and an f32 FFT adds
/// roughly ε·log2(N) of the L2 norm of its input per value, ε = 6e-8, i.e. a few 1e-7·log2 N
/// relative to the field's RMS ≤ its maximum. The FFT error is relative to the norm of the
/// packed pair, so the smaller field of a pair (η_x next to D_z) sees a larger relative error:
/// measured worst 1.2e-6 for η_x (Phillips, N = 10, where k_max·|D_z| ≈ 0.16·|D_z|), 1.1e-7–2.7e-7
/// for the others. 1e-6·log2 N (2.6e-6 at N = 6, 3.3e-6 at N = 10) leaves a margin of ≥ 2.7
/// at every size here (the worst errors are printed with --nocapture).
fn tolerance(n: usize) -> f64 {
    1e-6 * (n as f64).log2()
}

/// Reference fields for one cascade at time t: the naive DFT of h̃(k, t)·multiplier for each
/// of the eight fields (real parts; the imaginary residue is checked to be ~0).
fn reference_fields(cascade: &Cascade, t: f64) -> Vec<Vec<f64>> {
    let n = cascade.size();
    let h = inspect::wave_spectrum(cascade, t).unwrap();
    FIELDS
        .iter()
        .map(|&field| {
            let spectrum = field_spectrum(&h, n, f64::from(LENGTH), field);
            let values = naive_idft(&spectrum, n);
            let scale = values.iter().fold(0.0f64, |a, v| a.max(cabs(*v)));
            let residue = values.iter().fold(0.0f64, |a, v| a.max(v.1.abs()));
            // Hermitian input: the imaginary parts cancel pairwise up to f64 rounding of
            // N² terms (~1e-16·N² ≈ 1e-13 relative); 1e-10 is far below any real error.
            assert!(
                residue <= 1e-10 * scale,
                "{field:?} N={n} t={t}: imaginary residue {residue:e} of max {scale:e}"
            );
            values.iter().map(|v| v.0).collect()
        })
        .collect()
}

#[test]
fn fields_equal_naive_dft_of_wave_spectrum_times_multiplier() {
    for (name, spectrum) in spectra() {
        for n in SIZES {
            let mut cascade = cascade(&spectrum, n);
            let mut worst = [0.0f64; 8];
            for t in TIMES {
                cascade.update(t).unwrap();
                let reference = reference_fields(&cascade, t);
                for (f, &field) in FIELDS.iter().enumerate() {
                    let got = inspect::field(&cascade, field);
                    assert_eq!(got.len(), n * n);
                    let scale = max_abs(&reference[f]);
                    assert!(
                        scale > 0.0,
                        "{name} {field:?} N={n}: reference field is zero"
                    );
                    let err = got
                        .iter()
                        .zip(&reference[f])
                        .fold(0.0f64, |a, (&g, &r)| a.max((f64::from(g) - r).abs()));
                    let rel = err / scale;
                    worst[f] = worst[f].max(rel);
                    assert!(
                        rel <= tolerance(n),
                        "{name} {field:?} N={n} t={t}: max error {err:e} = {rel:e} of max |value| {scale:e}"
                    );
                }
            }
            let worst: Vec<String> = worst.iter().map(|w| format!("{w:.2e}")).collect();
            println!("{name} N={n}: worst error / max |value| per field {worst:?}");
        }
    }
}

#[test]
fn packed_transforms_equal_naive_dft_of_a_plus_i_b() {
    for (name, spectrum) in spectra() {
        for n in SIZES {
            let mut cascade = cascade(&spectrum, n);
            for t in [0.0, 17.9] {
                cascade.update(t).unwrap();
                let h = inspect::wave_spectrum(&cascade, t).unwrap();
                for p in 0..4 {
                    // The two fields of transform p per `Field::packing`: 2p real, 2p + 1
                    // imaginary; check the packing claim itself too.
                    let (a_field, b_field) = (FIELDS[2 * p], FIELDS[2 * p + 1]);
                    assert_eq!(a_field.packing(), (p, false));
                    assert_eq!(b_field.packing(), (p, true));
                    let a = field_spectrum(&h, n, f64::from(LENGTH), a_field);
                    let b = field_spectrum(&h, n, f64::from(LENGTH), b_field);
                    // A + iB = (a.re − b.im) + i (a.im + b.re).
                    let packed: Vec<C64> = a
                        .iter()
                        .zip(&b)
                        .map(|(a, b)| (a.0 - b.1, a.1 + b.0))
                        .collect();
                    let reference = naive_idft(&packed, n);
                    let got = inspect::packed_transform(&cascade, p).unwrap();
                    assert_eq!(got.len(), n * n);
                    let scale = reference.iter().fold(0.0f64, |s, v| s.max(cabs(*v)));
                    let err = got.iter().zip(&reference).fold(0.0f64, |s, (g, r)| {
                        let g = to64(*g);
                        s.max((g.0 - r.0).hypot(g.1 - r.1))
                    });
                    // Same error sources as the single fields (tolerance() comment).
                    assert!(
                        err <= tolerance(n) * scale,
                        "{name} N={n} t={t} transform {p}: error {err:e} of max {scale:e}"
                    );
                    // Real part is field 2p, imaginary part field 2p + 1, as `field` says.
                    let fa = inspect::field(&cascade, a_field);
                    let fb = inspect::field(&cascade, b_field);
                    for idx in 0..n * n {
                        assert_eq!(got[idx].re.to_bits(), fa[idx].to_bits());
                        assert_eq!(got[idx].im.to_bits(), fb[idx].to_bits());
                    }
                }
            }
            assert_eq!(
                inspect::packed_transform(&cascade, 4).unwrap_err(),
                Error::IndexOutOfRange {
                    name: "transform",
                    index: 4,
                    len: 4
                }
            );
        }
    }
}

/// λ · 2 Σ_k |k| |h0(k)|² in f64 over the grid's wave vectors: the time average of
/// λ Σ_k |k| |h̃(k, t)|², which the cascade adds to every height.
fn mean_level(cascade: &Cascade, lambda: f64) -> f64 {
    let n = cascade.size();
    let dk = f64::from(cascade.delta_k());
    let index = |i: usize| {
        if i < n / 2 {
            i as f64
        } else {
            i as f64 - n as f64
        }
    };
    let mut sum = 0.0;
    for (idx, h) in cascade.h0().iter().enumerate() {
        let (kx, kz) = (index(idx % n) * dk, index(idx / n) * dk);
        let (re, im) = (f64::from(h.re), f64::from(h.im));
        sum += kx.hypot(kz) * (re * re + im * im);
    }
    2.0 * lambda * sum
}

#[test]
fn derived_outputs_match_reference_fields() {
    let lambda = f64::from(LAMBDA);
    for (name, spectrum) in spectra() {
        for n in SIZES {
            let mut cascade = cascade(&spectrum, n);
            let level = mean_level(&cascade, lambda);
            assert!(
                (f64::from(cascade.mean_level_offset()) - level).abs() <= 1e-6 * level,
                "{name} N={n}: offset {} vs λ·2Σ|k||h0|² = {level}",
                cascade.mean_level_offset()
            );
            let mut worst = [0.0f64; 5];
            let mut slope_points = 0;
            for t in TIMES {
                cascade.update(t).unwrap();
                let r = reference_fields(&cascade, t);
                let tol = tolerance(n);
                // Absolute error allowance of each input field (see tolerance()).
                let e: Vec<f64> = r.iter().map(|f| tol * max_abs(f)).collect();
                let (e_eta, e_dx, e_dz, e_ex, e_ez, e_xx, e_zz, e_xz) =
                    (e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7]);
                for idx in 0..n * n {
                    let (eta, dx, dz) = (r[0][idx], r[1][idx], r[2][idx]);
                    let (ex, ez) = (r[3][idx], r[4][idx]);
                    let (dxx, dzz, dxz) = (r[5][idx], r[6][idx], r[7][idx]);
                    let jxx = 1.0 + lambda * dxx;
                    let jzz = 1.0 + lambda * dzz;
                    let jxz = lambda * dxz;
                    let j_ref = jxx * jzz - jxz * jxz;
                    // n = T_z × T_x, T_x = (jxx, η_x, jxz), T_z = (jxz, η_z, jzz).
                    let tx = [jxx, ex, jxz];
                    let tz = [jxz, ez, jzz];
                    let raw = [
                        tz[1] * tx[2] - tz[2] * tx[1],
                        tz[2] * tx[0] - tz[0] * tx[2],
                        tz[0] * tx[1] - tz[1] * tx[0],
                    ];
                    let len = (raw[0] * raw[0] + raw[1] * raw[1] + raw[2] * raw[2]).sqrt();

                    // First-order propagation of the input allowances, plus f32 rounding of
                    // the few products and the normalisation (1e-6 of the magnitudes).
                    let d_j = lambda * e_xx * jzz.abs()
                        + lambda * e_zz * jxx.abs()
                        + 2.0 * lambda * lambda * dxz.abs() * e_xz
                        + 1e-6 * (jxx.abs() * jzz.abs() + jxz * jxz);
                    let d_rx = e_ez * jxz.abs()
                        + ez.abs() * lambda * e_xz
                        + lambda * e_zz * ex.abs()
                        + jzz.abs() * e_ex;
                    let d_rz = lambda * e_xz * ex.abs()
                        + jxz.abs() * e_ex
                        + e_ez * jxx.abs()
                        + ez.abs() * lambda * e_xx;
                    let d_raw = (d_rx * d_rx + d_j * d_j + d_rz * d_rz).sqrt() + 1e-6 * len;

                    // The height buffer carries the mean-level correction λ·2Σ|k||h0(k)|²
                    // (Cascade::mean_level_offset), computed here from h0 in f64.
                    let h = f64::from(cascade.height()[idx]) - level;
                    let d = cascade.displacement()[idx];
                    let jac = f64::from(cascade.jacobian()[idx]);
                    let nrm = cascade.normal()[idx];
                    let errs = [
                        (h - eta).abs() / e_eta,
                        ((f64::from(d[0]) - lambda * dx).abs()
                            / (lambda * e_dx + 1e-7 * lambda * dx.abs()))
                        .max(
                            (f64::from(d[1]) - lambda * dz).abs()
                                / (lambda * e_dz + 1e-7 * lambda * dz.abs()),
                        ),
                        (jac - j_ref).abs() / d_j,
                        {
                            let dn = [
                                f64::from(nrm[0]) - raw[0] / len,
                                f64::from(nrm[1]) - raw[1] / len,
                                f64::from(nrm[2]) - raw[2] / len,
                            ];
                            (dn[0] * dn[0] + dn[1] * dn[1] + dn[2] * dn[2]).sqrt()
                                / (2.0 * d_raw / len + 1e-6)
                        },
                        0.0,
                    ];
                    let mut errs = errs;
                    // Slope of the displaced surface, (−n_x/n_y, −n_z/n_y), where J > 0 and
                    // well away from the documented clamp of n_y at 1e-4·|n|.
                    if j_ref > 1e-2 * len {
                        slope_points += 1;
                        let s_ref = [-raw[0] / raw[1], -raw[2] / raw[1]];
                        let s = cascade.slope()[idx];
                        let ds = [
                            (d_rx + s_ref[0].abs() * d_j) / j_ref,
                            (d_rz + s_ref[1].abs() * d_j) / j_ref,
                        ];
                        errs[4] = ((f64::from(s[0]) - s_ref[0]).abs()
                            / (2.0 * ds[0] + 1e-6 * s_ref[0].abs()))
                        .max(
                            (f64::from(s[1]) - s_ref[1]).abs()
                                / (2.0 * ds[1] + 1e-6 * s_ref[1].abs()),
                        );
                    }
                    for (w, e) in worst.iter_mut().zip(errs) {
                        *w = w.max(e);
                    }
                    assert!(
                        errs.iter().all(|&e| e <= 1.0),
                        "{name} N={n} t={t} idx={idx}: errors / allowance (height, displacement, J, normal, slope) = {errs:?}"
                    );
                }
            }
            assert!(slope_points > 0);
            println!(
                "{name} N={n}: worst error / allowance (height, displacement, J, normal, slope) {worst:.2?}"
            );
        }
    }
}

#[test]
fn wave_spectrum_is_hermitian_and_follows_the_evolution_formula() {
    for (name, spectrum) in spectra() {
        for n in SIZES {
            let cascade = cascade(&spectrum, n);
            let h0 = cascade.h0();
            for t in TIMES {
                let h = inspect::wave_spectrum(&cascade, t).unwrap();
                let scale = h.iter().fold(0.0f64, |a, c| a.max(cabs(to64(*c))));
                for j in 0..n {
                    for i in 0..n {
                        let idx = j * n + i;
                        let neg = neg_index(i, j, n);
                        if i == n / 2 || j == n / 2 || (i == 0 && j == 0) {
                            assert_eq!(h[idx], ocean_fft::inspect::Complex32::new(0.0, 0.0));
                            assert_eq!(h0[idx], ocean_fft::inspect::Complex32::new(0.0, 0.0));
                            continue;
                        }
                        // Hermitian: h̃(−k) = conj h̃(k), to f32 rounding of the value.
                        let (a, b) = (to64(h[idx]), to64(h[neg]));
                        assert!(
                            (a.0 - b.0).abs() <= 1e-6 * scale && (a.1 + b.1).abs() <= 1e-6 * scale,
                            "{name} N={n} t={t} ({i},{j}): not Hermitian {a:?} vs {b:?}"
                        );
                        // h̃ = h0(k) e^{−iωt} + conj(h0(−k)) e^{iωt}, in f64 here.
                        let omega = inspect::omega_at(&cascade, i, j).unwrap();
                        let phase = (omega * t).rem_euclid(TAU);
                        let (s, c) = phase.sin_cos();
                        let p = to64(h0[idx]);
                        let q = to64(h0[neg]);
                        let q = (q.0, -q.1);
                        let expected = (
                            p.0 * c + p.1 * s + q.0 * c - q.1 * s,
                            p.1 * c - p.0 * s + q.1 * c + q.0 * s,
                        );
                        // The cascade rounds h0(k) + conj h0(−k) and its rotation to f32
                        // (≤ 3 roundings of 6e-8 of |h0(k)| + |h0(−k)|) and uses ω·t reduced
                        // in f64 (1000 s · 1e-16 relative ω: negligible).
                        let allow = 1e-6 * (cabs(p) + cabs(q)) + 1e-30;
                        let err = (a.0 - expected.0).hypot(a.1 - expected.1);
                        assert!(
                            err <= allow,
                            "{name} N={n} t={t} ({i},{j}): h̃ {a:?} expected {expected:?}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn omega_is_deep_water_dispersion() {
    // ω = √(g|k|), g = 9.81 m/s² as the crate's f32 constant (9.8100004…); against the
    // literal 9.81 the relative difference is 2e-8, so 1e-7 covers both.
    let g = f64::from(GRAVITY);
    for (name, spectrum) in spectra() {
        for n in SIZES {
            let cascade = cascade(&spectrum, n);
            let dk = TAU / f64::from(LENGTH);
            for j in 0..n {
                for i in 0..n {
                    if i == n / 2 || j == n / 2 || (i == 0 && j == 0) {
                        continue;
                    }
                    let k = dk * (m(i, n) as f64).hypot(m(j, n) as f64);
                    let omega = inspect::omega_at(&cascade, i, j).unwrap();
                    assert!(
                        (omega - (g * k).sqrt()).abs() <= 1e-12 * omega,
                        "{name} N={n} ({i},{j}): ω {omega} vs √(gk) {}",
                        (g * k).sqrt()
                    );
                    assert!((omega - (9.81 * k).sqrt()).abs() <= 1e-7 * omega);
                }
            }
        }
    }
}

#[test]
fn set_choppiness_changes_displacement_and_jacobian_at_next_update() {
    let spectrum = jonswap(0.4);
    let n = 16;
    let mut cascade = cascade(&spectrum, n);
    cascade.set_choppiness(1.7).unwrap();
    assert_eq!(cascade.config().choppiness, 1.7);
    cascade.update(5.0).unwrap();
    let r = reference_fields(&cascade, 5.0);
    let lambda = 1.7f64;
    let tol = tolerance(n);
    for idx in 0..n * n {
        let d = cascade.displacement()[idx];
        assert!(
            (f64::from(d[0]) - lambda * r[1][idx]).abs() <= 2.0 * lambda * tol * max_abs(&r[1])
        );
        assert!(
            (f64::from(d[1]) - lambda * r[2][idx]).abs() <= 2.0 * lambda * tol * max_abs(&r[2])
        );
        let j_ref = (1.0 + lambda * r[5][idx]) * (1.0 + lambda * r[6][idx])
            - lambda * lambda * r[7][idx] * r[7][idx];
        // Same propagation as derived_outputs_match_reference_fields, bounded crudely by 10
        // times the largest input allowance times (1 + λ)².
        let allow = 10.0
            * tol
            * (1.0 + lambda).powi(2)
            * max_abs(&r[5])
                .max(max_abs(&r[6]))
                .max(max_abs(&r[7]))
                .max(1.0);
        assert!((f64::from(cascade.jacobian()[idx]) - j_ref).abs() <= allow);
    }
}

#[test]
fn looping_cascade_fields_equal_naive_dft_of_its_wave_spectrum() {
    // With a repeat period the cascade must still synthesise exactly wave_spectrum(t) (whose
    // ω are the quantised ones), including negative and large t.
    for n in [10, 24] {
        let mut cascade = Cascade::new(
            &jonswap(0.4),
            CascadeConfig {
                size: n,
                length: LENGTH,
                choppiness: LAMBDA,
                seed: 7,
                repeat_period: Some(13.0),
                ..CascadeConfig::default()
            },
        )
        .unwrap();
        for t in [2.0, -7.5, 1000.25, 9.9e8] {
            cascade.update(t).unwrap();
            let reference = reference_fields(&cascade, t);
            for (f, &field) in FIELDS.iter().enumerate() {
                let got = inspect::field(&cascade, field);
                let scale = max_abs(&reference[f]);
                let err = got
                    .iter()
                    .zip(&reference[f])
                    .fold(0.0f64, |a, (&g, &r)| a.max((f64::from(g) - r).abs()));
                assert!(
                    err <= tolerance(n) * scale,
                    "looping N={n} t={t} {field:?}: error {err:e} of {scale:e}"
                );
            }
        }
    }
}

#[test]
fn omega_follows_finite_depth_and_capillary_dispersion() {
    // ω² = g k tanh(k h) (TMA, depth 5 m) and ω² = (g k + (σ/ρ) k³) tanh(k h) (capillary,
    // σ = 0.074 N/m, ρ = 1000 kg/m³, depth 50 m), evaluated here in f64 on a fine grid
    // (L = 2 m, N = 32: k up to 70 rad/m, where the capillary term is 40 % of gk).
    let g = f64::from(GRAVITY);
    // σ/ρ from the crate's f32 constants (0.074 as f32 is 0.0740000009…): the literal would
    // differ by 1.3e-8 relative.
    let tension = f64::from(ocean_fft::inspect::SURFACE_TENSION)
        / f64::from(ocean_fft::inspect::WATER_DENSITY);
    assert!((tension - 0.074 / 1000.0).abs() < 2e-8 * tension);
    type Omega = Box<dyn Fn(f64) -> f64>;
    let cases: [(Spectrum, f32, Omega); 2] = [
        (
            Spectrum::tma(10.0, 100_000.0, 5.0).unwrap(),
            200.0,
            Box::new(move |k: f64| (g * k * (k * 5.0).tanh()).sqrt()),
        ),
        (
            jonswap(0.4)
                .with_dispersion(ocean_fft::Dispersion::Capillary { depth: 50.0 })
                .unwrap(),
            2.0,
            Box::new(move |k: f64| ((g * k + tension * k * k * k) * (k * 50.0).tanh()).sqrt()),
        ),
    ];
    for (spectrum, length, omega_of) in cases {
        let n = 32;
        let cascade = Cascade::new(
            &spectrum,
            CascadeConfig {
                size: n,
                length,
                ..CascadeConfig::default()
            },
        )
        .unwrap();
        let dk = TAU / f64::from(length);
        for j in 0..n {
            for i in 0..n {
                if i == n / 2 || j == n / 2 || (i == 0 && j == 0) {
                    continue;
                }
                let k = dk * (m(i, n) as f64).hypot(m(j, n) as f64);
                let expected = omega_of(k);
                let omega = inspect::omega_at(&cascade, i, j).unwrap();
                // Both in f64 from the same constants: only rounding differs.
                assert!(
                    (omega - expected).abs() <= 1e-10 * expected,
                    "L={length} ({i},{j}) k={k}: ω {omega} vs {expected}"
                );
            }
        }
    }
}

#[test]
fn crate_multipliers_agree_with_the_design_table() {
    // Field::multiplier (public API, f32) against the table written out in common/mod.rs.
    for &(kx, kz) in &[
        (0.3f32, -0.7f32),
        (-2.0, 0.0),
        (0.0, 5.5),
        (1e-3, 2e-3),
        (0.0, 0.0),
    ] {
        for field in FIELDS {
            let got = to64(field.multiplier([kx, kz]));
            let want = multiplier(field, f64::from(kx), f64::from(kz));
            let scale = cabs(want).max(1e-30);
            assert!(
                (got.0 - want.0).abs() <= 1e-6 * scale && (got.1 - want.1).abs() <= 1e-6 * scale,
                "{field:?} at ({kx}, {kz}): {got:?} vs {want:?}"
            );
        }
    }
}

#[test]
fn fields_at_larger_sizes_equal_a_separable_f64_dft() {
    // The reference at sizes beyond the naive O(N⁴) DFT's reach: the same sums evaluated
    // separably (common::separable_idft), itself checked against the naive form at N = 24.
    {
        let cascade = cascade(&jonswap(0.4), 24);
        let h = inspect::wave_spectrum(&cascade, 3.0).unwrap();
        let c = field_spectrum(
            &h,
            24,
            f64::from(LENGTH),
            ocean_fft::inspect::Field::DisplacementXZ,
        );
        let (a, b) = (naive_idft(&c, 24), separable_idft(&c, 24));
        let scale = a.iter().fold(0.0f64, |s, v| s.max(cabs(*v)));
        for (x, y) in a.iter().zip(&b) {
            assert!((x.0 - y.0).hypot(x.1 - y.1) < 1e-12 * scale);
        }
    }
    // 50 and 66: not multiples of the 16-row task blocks (and 66/2 = 33 odd); 130: N/2 odd;
    // 256: the default size; 300: above 256, where the evolution stages its values on the
    // stack before copying them into the rows (`STRAIGHT_MAX` in src/cascade/evolve.rs). Larger
    // N also has larger k, so the slope fields are no longer the small member of their
    // packed pair.
    for (n, length, times) in [
        (50usize, 300.0f32, &[0.0, 41.7][..]),
        (66, 300.0, &[12.25][..]),
        (130, 600.0, &[5.5][..]),
        (256, 1000.0, &[100.0][..]),
        (300, 1200.0, &[7.5][..]),
    ] {
        for spectrum in [jonswap(0.4), phillips(-1.1)] {
            let mut cascade = Cascade::new(
                &spectrum,
                CascadeConfig {
                    size: n,
                    length,
                    choppiness: LAMBDA,
                    seed: 5,
                    ..CascadeConfig::default()
                },
            )
            .unwrap();
            for &t in times {
                cascade.update(t).unwrap();
                let h = inspect::wave_spectrum(&cascade, t).unwrap();
                let mut worst = 0.0f64;
                for field in FIELDS {
                    let c = field_spectrum(&h, n, f64::from(length), field);
                    let reference: Vec<f64> = separable_idft(&c, n).iter().map(|v| v.0).collect();
                    let got = inspect::field(&cascade, field);
                    let scale = max_abs(&reference);
                    let err = got
                        .iter()
                        .zip(&reference)
                        .fold(0.0f64, |a, (&g, &r)| a.max((f64::from(g) - r).abs()));
                    worst = worst.max(err / scale);
                    // Same error model as tolerance() (ε·log2 N of the packed pair's norm).
                    assert!(
                        err <= tolerance(n) * scale,
                        "N={n} t={t} {field:?}: error {err:e} = {:e} of max {scale:e}",
                        err / scale
                    );
                }
                println!("N={n} t={t}: worst field error {worst:.2e} of max |value|");
            }
        }
    }
}
