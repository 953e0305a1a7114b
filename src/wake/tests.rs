//! Unit tests of the wake layer's parts.

use num_complex::Complex32;

use super::fft::Fft;
use crate::math::determinism::Determinism;

#[test]
fn forward_then_inverse_is_n_squared_times_identity() {
    for determinism in [Determinism::SameMachine, Determinism::CrossPlatform] {
        let n = 32;
        let input: Vec<Complex32> = (0..n * n)
            .map(|v| Complex32::new(((v * 7) % 13) as f32 - 6.0, ((v * 5) % 3) as f32))
            .collect();
        let mut fft = Fft::new(n, determinism).unwrap();
        let (mut a, mut b) = (input.clone(), vec![Complex32::default(); n * n]);
        fft.run(false, &mut a, &mut b);
        fft.run(true, &mut b, &mut a);
        for (got, want) in a.iter().zip(&input) {
            let got = got / (n * n) as f32;
            assert!((got - want).norm() < 1e-4, "{got} {want}");
        }
    }
}

#[test]
fn the_real_inverse_gives_the_complex_inverse_of_a_real_field() {
    for determinism in [Determinism::SameMachine, Determinism::CrossPlatform] {
        let n = 64;
        // A real field: its forward transform is Hermitian.
        let input: Vec<Complex32> = (0..n * n)
            .map(|v| Complex32::new((((v * 37) % 101) as f32 - 50.0) / 7.0, 0.0))
            .collect();
        let mut fft = Fft::new(n, determinism).unwrap();
        let (mut a, mut spectrum) = (input.clone(), vec![Complex32::default(); n * n]);
        fft.run(false, &mut a, &mut spectrum);
        let (mut full, mut out) = (spectrum.clone(), vec![Complex32::default(); n * n]);
        fft.run(true, &mut full, &mut out);
        let mut packed = vec![Complex32::default(); n * n];
        fft.inverse_real(&mut spectrum, &mut packed);
        let scale = (n * n) as f32;
        for z in 0..n {
            for x in 0..n {
                let pair = packed[(z / 2) * n + x];
                let got = if z % 2 == 0 { pair.re } else { pair.im } / scale;
                let want = input[z * n + x].re;
                // Round-off of two transforms of 64 points of size ~7: 1e-4 relative.
                assert!((got - want).abs() < 1e-4 * 7.0, "({x}, {z}): {got} {want}");
                assert!((got - out[z * n + x].re / scale).abs() < 1e-4 * 7.0);
            }
        }
    }
}
