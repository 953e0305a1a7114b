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
