//! Second moments of the displacement gradient (D_xx, D_zz, D_xz) and of its rate, from a
//! cascade's amplitudes: what the whitecap calibration and the breaking intensity need to
//! know about the cascades the foam grid does not resolve.

use std::f64::consts::TAU;

use num_complex::Complex32;

use crate::cascade::Cascade;
use crate::math::determinism::Math;

/// Covariances of the displacement gradient (D_xx, D_zz, D_xz) at unit choppiness over space
/// and time, and of its time derivative, from a cascade's amplitudes: for each field pair
/// Σ_k M_a(k) M_b(k) · 2|h0(k)|² (and the same times ω(k)²), the time average of the realised
/// field's spatial mean square (Parseval).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct GradientMoments {
    /// E[g_a g_b] for g = (D_xx, D_zz, D_xz).
    pub(crate) value: [[f64; 3]; 3],
    /// E[ġ_a ġ_b], in 1/s².
    pub(crate) rate: [[f64; 3]; 3],
}

impl GradientMoments {
    /// The moments of amplitudes `h0` (the cascade's own, or new ones of a change of weather)
    /// on `cascade`'s grid, with the frequencies it evolves them with (quantised when
    /// looping), with the functions of `M`. Serial, in index order.
    pub(crate) fn of_amplitudes<M: Math>(cascade: &Cascade, h0: &[Complex32]) -> GradientMoments {
        let n = cascade.size();
        let dk = f64::from(cascade.delta_k());
        let mut moments = GradientMoments::default();
        for j in 0..n {
            let kz = f64::from(crate::math::grid::wave_index(j, n)) * dk;
            for i in 0..n {
                let weight = 2.0 * f64::from(h0[j * n + i].norm_sqr());
                if weight == 0.0 {
                    continue;
                }
                let kx = f64::from(crate::math::grid::wave_index(i, n)) * dk;
                let k = M::hypot(kx, kz);
                if k == 0.0 {
                    continue;
                }
                let m = [-kx * kx / k, -kz * kz / k, -kx * kz / k];
                let omega = cascade.frequency(i, j) * TAU;
                let omega2 = omega * omega;
                for (a, row) in m.iter().enumerate() {
                    for (b, column) in m.iter().enumerate() {
                        let v = weight * row * column;
                        moments.value[a][b] += v;
                        moments.rate[a][b] += v * omega2;
                    }
                }
            }
        }
        moments
    }

    /// (1 − w)·`self` + w·`other`: the moments of the energy blend of two sets of amplitudes
    /// (they are sums of energies).
    pub(crate) fn blend(&self, other: &GradientMoments, w: f64) -> GradientMoments {
        let lerp = |a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]| {
            std::array::from_fn(|i| std::array::from_fn(|j| (1.0 - w) * a[i][j] + w * b[i][j]))
        };
        GradientMoments {
            value: lerp(&self.value, &other.value),
            rate: lerp(&self.rate, &other.rate),
        }
    }

    /// The moments of a sum of independent fields (cascades with their own seeds and
    /// disjoint bands): the sums of the moments.
    pub(crate) fn add(&mut self, other: &GradientMoments) {
        for a in 0..3 {
            for b in 0..3 {
                self.value[a][b] += other.value[a][b];
                self.rate[a][b] += other.rate[a][b];
            }
        }
    }
}

#[cfg(test)]
// Matrix arithmetic reads best with its indices.
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;
    use crate::cascade::{Cascade, CascadeConfig};
    use crate::inspect::Field;
    use crate::math::determinism::Std;
    use crate::spectrum::Spectrum;

    /// The gradient an update writes holds the same numbers as the public, copying `field`: if the
    /// packing of the transforms ever changes, this fails rather than the foam silently
    /// reading the wrong field.
    #[test]
    fn gradient_rows_match_the_fields() {
        let spectrum = Spectrum::jonswap(12.0, 50_000.0).unwrap();
        let config = CascadeConfig {
            size: 16,
            length: 120.0,
            ..CascadeConfig::default()
        };
        let mut cascade = Cascade::new(&spectrum, config).unwrap();
        let mut gradient = vec![[f32::NAN; 3]; 16 * 16];
        cascade.update_checked(3.7, &mut gradient);
        let xx = cascade.field(Field::DisplacementXX);
        let zz = cascade.field(Field::DisplacementZZ);
        let xz = cascade.field(Field::DisplacementXZ);
        let mut nonzero = 0;
        for j in 0..16 {
            for i in 0..16 {
                let k = j * 16 + i;
                assert_eq!(gradient[k], [xx[k], zz[k], xz[k]], "({i}, {j})");
                nonzero += usize::from(xx[k] != 0.0);
            }
        }
        assert!(nonzero > 200);
    }

    /// The moments against the fields themselves: the spatial mean of g_a·g_b over the grid,
    /// averaged over many times, approaches the time-averaged Parseval sum (the cross term
    /// h0(k)·h0(−k) oscillates at 2ω and averages out).
    #[test]
    fn gradient_moments_match_the_fields_mean_squares() {
        let spectrum = Spectrum::jonswap(12.0, 50_000.0).unwrap();
        let config = CascadeConfig {
            size: 16,
            length: 60.0,
            ..CascadeConfig::default()
        };
        let mut cascade = Cascade::new(&spectrum, config).unwrap();
        let mut gradient = vec![[0.0f32; 3]; 16 * 16];
        let moments = GradientMoments::of_amplitudes::<Std>(&cascade, cascade.h0());
        let mut sums = [[0.0f64; 3]; 3];
        let times = 4000;
        for step in 0..times {
            // Irregular times over 400 s: far longer than every period on this grid.
            let t = f64::from(step) * 0.1 + 0.013 * f64::from(step % 7);
            cascade.update_checked(t, &mut gradient);
            for j in 0..16 {
                for i in 0..16 {
                    let g = gradient[j * 16 + i].map(f64::from);
                    for a in 0..3 {
                        for b in 0..3 {
                            sums[a][b] += g[a] * g[b];
                        }
                    }
                }
            }
        }
        let scale = moments.value[0][0] + moments.value[1][1];
        for a in 0..3 {
            for b in 0..3 {
                let measured = sums[a][b] / f64::from(times * 256);
                // The time average over 4000 irregular samples leaves a few per cent of the
                // scale from the slowest waves (periods of 6 s here: about 70 cycles).
                assert!(
                    (measured - moments.value[a][b]).abs() < 0.05 * scale,
                    "({a}, {b}): measured {measured}, moments {}",
                    moments.value[a][b]
                );
            }
        }
    }
}
