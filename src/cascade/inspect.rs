//! Read-only views of a cascade for verification and tools: the evolved spectrum, ω per
//! wave vector, single fields and the raw packed transforms. These allocate.

use std::f64::consts::TAU;

use num_complex::Complex32;

use super::tables::Evolution;
use super::{check_time, row_stride, Cascade, Field, TRANSFORMS};
use crate::error::{self, Error};
use crate::fft2d::transpose_into;

impl Cascade {
    /// The evolved spectrum h̃(k, t) = h0(k)e^{−iωt} + conj(h0(−k))e^{iωt} in m, in the grid's
    /// FFT order, computed afresh in f64 at time `t` in seconds (for verification and tools;
    /// allocates).
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for `t` outside
    /// ±[`MAX_TIME`](Self::MAX_TIME), as [`Cascade::update`].
    pub fn wave_spectrum(&self, t: f64) -> Result<Vec<Complex32>, Error> {
        let n = self.n;
        check_time("t", t)?;
        let t = match self.config.repeat_period {
            Some(period) => t.rem_euclid(f64::from(period)),
            None => t,
        };
        let mut out = vec![Complex32::default(); n * n];
        for j in 0..n {
            for i in 0..n {
                let (entry, conjugate) = self.evolution_entry(i, j);
                let phase = (entry.freq * t).fract() * TAU;
                let (sin, cos) = self.config.determinism.sin_cos(phase);
                let p = (f64::from(entry.p.re), f64::from(entry.p.im));
                let q = (f64::from(entry.q.re), f64::from(entry.q.im));
                let value = Complex32::new(
                    (p.0 * cos + q.0 * sin) as f32,
                    (p.1 * cos + q.1 * sin) as f32,
                );
                out[j * n + i] = if conjugate { value.conj() } else { value };
            }
        }
        Ok(out)
    }

    /// Angular frequency ω(k) in rad/s used for the wave vector at spectral index (i, j),
    /// k = Δk·(m(i), m(j)) (quantised when looping; 0 on the Nyquist row and column, which
    /// hold no wave).
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`] unless `i` and `j` are below N.
    pub fn omega_at(&self, i: usize, j: usize) -> Result<f64, Error> {
        error::index("i", i, self.n)?;
        error::index("j", j, self.n)?;
        Ok(self.evolution_entry(i, j).0.freq * TAU)
    }

    /// The table entry that evolves (i, j), and whether (i, j) is the conjugate partner.
    fn evolution_entry(&self, i: usize, j: usize) -> (Evolution, bool) {
        let n = self.n;
        let half = n / 2;
        if i == half || j == half {
            (Evolution::default(), false)
        } else if i < half {
            (self.evolution.get(i * n + j), false)
        } else {
            let (pi, pj) = ((n - i) % n, (n - j) % n);
            (self.evolution.get(pi * n + pj), true)
        }
    }

    /// One of the eight real fields at the last update, in metres or dimensionless as
    /// [`Field`] says, in buffer order (index j·N + i). Allocates; its packed transform is
    /// finished afresh from the update's first pass (N row FFTs), to the same bits the
    /// update's outputs were computed from.
    pub fn field(&self, field: Field) -> Vec<f32> {
        let (transform, imaginary) = field.packing();
        let packed = self.finish_transform(transform);
        packed
            .iter()
            .map(|c| if imaginary { c.im } else { c.re })
            .collect()
    }

    /// Packed transform `transform` at the last update in buffer order: the second pass of
    /// the update (transpose, then FFTs along x) redone for it alone. The update itself keeps
    /// only a few blocks of rows of its second pass at a time, not the whole grid.
    fn finish_transform(&self, transform: usize) -> Vec<Complex32> {
        let n = self.n;
        let mut out = vec![Complex32::default(); n * n];
        transpose_into(
            &self.spectral[transform * n..],
            row_stride(n),
            &mut out,
            n,
            n,
            n,
        );
        let mut scratch = vec![Complex32::default(); self.rows.scratch_len()];
        self.rows.process(&mut out, &mut scratch);
        out
    }

    /// The raw result of packed transform `transform` (0..4) at the last update, in buffer
    /// order: real part field 2·`transform`, imaginary part field 2·`transform` + 1 of
    /// [`Field::ALL`] (see [`Field::packing`]). For checking the packing, as the crate's own
    /// tests do; [`Cascade::field`] reads one field.
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`] unless `transform` < 4.
    pub fn packed_transform(&self, transform: usize) -> Result<Vec<Complex32>, Error> {
        error::index("transform", transform, TRANSFORMS)?;
        Ok(self.finish_transform(transform))
    }
}

/// One grid row of the displacement gradient (D_xx, D_zz, D_xz) at unit choppiness, kept by
/// the update of a cascade that [`Cascade::keep_gradient`] asked to: what the foam assembles
/// the Jacobian of the summed displacement from (see [`Cascade::gradient_row`]).
#[derive(Clone, Copy)]
pub(crate) struct GradientRow<'a> {
    row: &'a [[f32; 3]],
}

impl<'a> GradientRow<'a> {
    /// `[D_xx, D_zz, D_xz]` at column `i`, dimensionless.
    #[cfg(test)]
    pub(crate) fn get(&self, i: usize) -> [f32; 3] {
        self.row[i]
    }

    /// The whole row, `[D_xx, D_zz, D_xz]` per column.
    pub(crate) fn values(self) -> &'a [[f32; 3]] {
        self.row
    }
}

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

impl Cascade {
    /// Grid row `j` (< N) of the displacement gradient at the last update, allocation-free
    /// (the values [`Cascade::field`] computes for [`Field::DisplacementXX`],
    /// [`Field::DisplacementZZ`] and [`Field::DisplacementXZ`]). Only for a cascade that keeps
    /// its gradient ([`Cascade::keep_gradient`]; panics otherwise, a bug of the crate).
    pub(crate) fn gradient_row(&self, j: usize) -> GradientRow<'_> {
        let n = self.n;
        GradientRow {
            row: &self.gradient[j * n..][..n],
        }
    }

    /// The [`GradientMoments`] of this cascade's realised amplitudes (with the frequencies it
    /// evolves them with, quantised when looping). Serial, in index order.
    pub(crate) fn gradient_moments(&self) -> GradientMoments {
        let n = self.n;
        let mut moments = GradientMoments::default();
        for j in 0..n {
            let kz = f64::from(crate::grid::wave_index(j, n)) * f64::from(self.dk);
            for i in 0..n {
                let h = self.h0[j * n + i];
                let weight = 2.0 * f64::from(h.norm_sqr());
                if weight == 0.0 {
                    continue;
                }
                let kx = f64::from(crate::grid::wave_index(i, n)) * f64::from(self.dk);
                let k = kx.hypot(kz);
                if k == 0.0 {
                    continue;
                }
                let m = [-kx * kx / k, -kz * kz / k, -kx * kz / k];
                let omega = self.evolution_entry(i, j).0.freq * TAU;
                let omega2 = omega * omega;
                for a in 0..3 {
                    for b in 0..3 {
                        let v = weight * m[a] * m[b];
                        moments.value[a][b] += v;
                        moments.rate[a][b] += v * omega2;
                    }
                }
            }
        }
        moments
    }
}

#[cfg(test)]
// Matrix arithmetic reads best with its indices.
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;
    use crate::{CascadeConfig, Spectrum};

    /// The allocation-free rows read the same numbers as the public, copying `field`: if the
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
        cascade.keep_gradient().unwrap();
        cascade.update(3.7).unwrap();
        let xx = cascade.field(Field::DisplacementXX);
        let zz = cascade.field(Field::DisplacementZZ);
        let xz = cascade.field(Field::DisplacementXZ);
        let mut nonzero = 0;
        for j in 0..16 {
            let row = cascade.gradient_row(j);
            for i in 0..16 {
                let k = j * 16 + i;
                assert_eq!(row.get(i), [xx[k], zz[k], xz[k]], "({i}, {j})");
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
        cascade.keep_gradient().unwrap();
        let moments = cascade.gradient_moments();
        let mut sums = [[0.0f64; 3]; 3];
        let times = 4000;
        for step in 0..times {
            // Irregular times over 400 s: far longer than every period on this grid.
            cascade
                .update(f64::from(step) * 0.1 + 0.013 * f64::from(step % 7))
                .unwrap();
            for j in 0..16 {
                let row = cascade.gradient_row(j);
                for i in 0..16 {
                    let g = row.get(i).map(f64::from);
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
