//! Read-only views of a cascade for verification and tools (public as [`crate::inspect`]):
//! the evolved spectrum, ω per wave vector, single fields and the raw packed transforms.
//! These allocate.

use std::f64::consts::TAU;

use num_complex::Complex32;

use super::tables::Evolution;
use super::{check_time, row_stride, Cascade, Field, TRANSFORMS};
use crate::error::{self, Error};
use crate::math::determinism::{with_math, Math};
use crate::math::fft2d::transpose_into;

impl Cascade {
    /// The evolved spectrum h̃(k, t) = h0(k)e^{−iωt} + conj(h0(−k))e^{iωt} in m, in the grid's
    /// FFT order, computed afresh in f64 at time `t` in seconds (for verification and tools;
    /// allocates).
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for `t` outside
    /// ±[`MAX_TIME`](Self::MAX_TIME), as [`Cascade::update`].
    pub(crate) fn wave_spectrum(&self, t: f64) -> Result<Vec<Complex32>, Error> {
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
                let (sin, cos) = with_math!(self.config.determinism, M => M::sin_cos(phase));
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
    pub(crate) fn omega_at(&self, i: usize, j: usize) -> Result<f64, Error> {
        error::index("i", i, self.n)?;
        error::index("j", j, self.n)?;
        Ok(self.frequency(i, j) * TAU)
    }

    /// The frequency ω/2π in cycles per second the update evolves spectral index (i, j) with
    /// (i, j < N; quantised when looping, 0 on the Nyquist row and column).
    pub(crate) fn frequency(&self, i: usize, j: usize) -> f64 {
        self.evolution_entry(i, j).0.freq
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
    pub(crate) fn field(&self, field: Field) -> Vec<f32> {
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
    pub(crate) fn packed_transform(&self, transform: usize) -> Result<Vec<Complex32>, Error> {
        error::index("transform", transform, TRANSFORMS)?;
        Ok(self.finish_transform(transform))
    }
}
