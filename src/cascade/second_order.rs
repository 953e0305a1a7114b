//! Second-order bound waves (`OceanConfig::second_order`): the group-scale correction that
//! the horizontal displacement lacks, formed from products of first-order fields and added to
//! the spectrum the update transforms (docs/theory.md, "Second-order waves").
//!
//! For the waves of the cascade with |k| < k_top (k_top = min(k_max, πN/2L)), with complex
//! amplitudes A(k, t) = h0(k) e^{−iω(k)t}, the update adds to η the field
//!
//! ```text
//! η₂(x) = Σ_a Σ_b 4 γ(k_a, k_b) A_a conj(A_b) e^{i(k_a − k_b)·x},   γ = ¼(|k_a| + |k_b|) − ¼|k_a − k_b|
//! ```
//!
//! keeping the wave vectors 0 < |k_a − k_b| < k_top, and its gradient to η_x, η_z. With
//! X = Σ 2A e^{ik·x} and Y = Σ 2|k| A e^{ik·x} (two complex inverse transforms) it is
//! ½ Re(Y conj X) − ¼ |K|[|X|²]: one forward transform of Re(Y conj X) + i|X|² and a
//! multiplier. The transforms run on an M×M grid, M ≥ 3·m_top + 1 with m_top the largest
//! wave index that takes part, so that no kept product wraps onto a kept wave vector.

use num_complex::Complex32;
use rayon::prelude::*;

use super::evolve::{fract_turns, sin_cos_turns};
use super::tables::EvolutionTable;
use super::Cascade;
use crate::error::{self, Error};
use crate::math::determinism::{with_math, Determinism, Math};
use crate::math::fft2d::{transpose_into, RowFft, ROWS_PER_TASK};
use crate::math::grid::wave_index;

/// Rows of the product grid one parallel task transforms at a time.
const ROWS: usize = ROWS_PER_TASK;

/// The product grid's side for wave indices up to `m_top`: the smallest 2^a or 3·2^a (sizes
/// rustfft transforms fastest) of at least 3·m_top + 1 and 4.
pub(crate) fn grid_size(m_top: usize) -> usize {
    let need = (3 * m_top + 1).max(4);
    let mut size = 4;
    loop {
        if size >= need {
            return size;
        }
        if size / 2 * 3 >= need {
            return size / 2 * 3;
        }
        size *= 2;
    }
}

/// The second-order state of one cascade: which waves take part, the product grid's
/// buffers and transforms, and the spectrum H(K) of the last update.
#[derive(Clone, Debug)]
pub(super) struct SecondOrder {
    n: usize,
    /// Side of the product grid.
    m: usize,
    /// Largest |wave index| (either component) of a wave vector with 0 < |k| < k_top.
    m_top: usize,
    /// Per evolution-table entry (i in 0..N/2, j in 0..N; index i·N + j): |k| in rad/m where
    /// 0 < |k| < k_top (the waves that take part, and the wave vectors H is kept on), else 0.
    k_in: Vec<f32>,
    inverse: RowFft,
    forward: RowFft,
    /// Spectra of X and Y in `[m_x][m_z]` order (rows beyond m_top stay zero), transformed
    /// along m_z in place.
    xs: Vec<Complex32>,
    ys: Vec<Complex32>,
    /// The fields X and Y in `[z][x]` order; then the product and its forward transform.
    wx: Vec<Complex32>,
    wy: Vec<Complex32>,
    scratch: Vec<Complex32>,
    /// H(K) per evolution-table entry (index i·N + j), zero outside the kept set.
    h: Vec<Complex32>,
}

impl SecondOrder {
    /// The state for an N grid of spacing `dk` (rad/m) whose waves below `k_top` (rad/m)
    /// interact. `None` if no wave vector of the grid lies below `k_top`.
    ///
    /// # Errors
    /// [`Error::OutOfMemory`] if the system refuses a buffer.
    pub(super) fn new<M: Math>(
        n: usize,
        dk: f64,
        k_top: f64,
        determinism: Determinism,
    ) -> Result<Option<Self>, Error> {
        let half = n / 2;
        let mut k_in = error::try_vec(half * n, 0.0f32)?;
        let mut m_top = 0usize;
        for i in 0..half {
            for j in 0..n {
                if j == half {
                    continue;
                }
                let (mx, mz) = (wave_index(i, n), wave_index(j, n));
                let k = M::hypot(f64::from(mx) * dk, f64::from(mz) * dk);
                if k > 0.0 && k < k_top {
                    k_in[i * n + j] = k as f32;
                    m_top = m_top.max(mx.unsigned_abs() as usize);
                    m_top = m_top.max(mz.unsigned_abs() as usize);
                }
            }
        }
        if m_top == 0 {
            return Ok(None);
        }
        let m = grid_size(m_top);
        let inverse = RowFft::new(m, determinism);
        let forward = RowFft::new_forward(m, determinism);
        let tasks = m.div_ceil(ROWS);
        let slot = inverse.scratch_len().max(forward.scratch_len());
        let points = m * m;
        Ok(Some(SecondOrder {
            n,
            m,
            m_top,
            k_in,
            xs: error::try_vec(points, Complex32::default())?,
            ys: error::try_vec(points, Complex32::default())?,
            wx: error::try_vec(points, Complex32::default())?,
            wy: error::try_vec(points, Complex32::default())?,
            scratch: error::try_vec(2 * tasks * slot, Complex32::default())?,
            h: error::try_vec(half * n, Complex32::default())?,
            inverse,
            forward,
        }))
    }

    /// Bytes the second-order state of an N grid holds at most (the product grid is at most
    /// 3N/4 + 2 on a side; its FFT scratch counted as one row per task).
    pub(crate) fn memory_bytes(n: usize) -> usize {
        let m = grid_size(n / 4);
        let complex = std::mem::size_of::<Complex32>();
        let half = n.saturating_mul(n) / 2;
        (4 * m * m + 2 * m.div_ceil(ROWS) * m)
            .saturating_mul(complex)
            .saturating_add(half.saturating_mul(complex + 4))
    }

    /// The side of the product grid.
    pub(super) fn grid(&self) -> usize {
        self.m
    }

    /// Table rows i (k_x index) up to this may hold a non-zero H.
    pub(super) fn top_row(&self) -> usize {
        self.m_top
    }

    /// H(K) of table row `i` (N values, by k_z index j).
    pub(super) fn row(&self, i: usize) -> &[Complex32] {
        &self.h[i * self.n..(i + 1) * self.n]
    }

    /// Computes H(K) at the phase time `t` (s) from the evolution table's p, q and
    /// frequencies. Allocates nothing.
    pub(super) fn compute(&mut self, table: &EvolutionTable, t: f64) {
        self.fill(table, t);
        self.fields();
        self.products();
        self.spectrum();
    }

    /// The spectra of X (2A at k, i.e. (p + iq)e^{−iφ}, and at −k (conj p + i conj q)e^{−iφ})
    /// and Y = |k|·X, for the waves with 0 < |k| < k_top, each written to its wave index
    /// modulo M. Rows beyond m_top are never written and stay zero.
    fn fill(&mut self, table: &EvolutionTable, t: f64) {
        let (n, m, top) = (self.n, self.m, self.m_top);
        let k_in = &self.k_in;
        let fill_row =
            |i: usize,
             plus: (&mut [Complex32], &mut [Complex32]),
             minus: Option<(&mut [Complex32], &mut [Complex32])>| {
                let (xp, yp) = plus;
                xp.fill(Complex32::default());
                yp.fill(Complex32::default());
                let mut minus = minus;
                if let Some((xm, ym)) = minus.as_mut() {
                    xm.fill(Complex32::default());
                    ym.fill(Complex32::default());
                }
                let row = table.get_row(i, n);
                for j in 0..n {
                    let k = k_in[i * n + j];
                    if k == 0.0 {
                        continue;
                    }
                    let e = row.get(j);
                    let (sin, cos) = sin_cos_turns(fract_turns(e.freq * t));
                    let rotate = Complex32::new(cos, -sin);
                    let i_q = Complex32::new(-e.q.im, e.q.re);
                    let plus_value = (e.p + i_q) * rotate;
                    let mz = wave_index(j, n);
                    let col = mz.rem_euclid(m as i32) as usize;
                    xp[col] = plus_value;
                    yp[col] = plus_value * k;
                    if let Some((xm, ym)) = minus.as_mut() {
                        let i_conj_q = Complex32::new(e.q.im, e.q.re);
                        let minus_value = (e.p.conj() + i_conj_q) * rotate;
                        let col = (-mz).rem_euclid(m as i32) as usize;
                        xm[col] = minus_value;
                        ym[col] = minus_value * k;
                    }
                }
            };
        let (x0, xrest) = self.xs.split_at_mut(m);
        let (y0, yrest) = self.ys.split_at_mut(m);
        // Row 0 (k_x = 0) holds both k and −k as entries of its own.
        fill_row(0, (x0, y0), None);
        let (xtop, xrest) = xrest.split_at_mut(top * m);
        let (ytop, yrest) = yrest.split_at_mut(top * m);
        let xbottom = &mut xrest[(m - 1 - 2 * top) * m..];
        let ybottom = &mut yrest[(m - 1 - 2 * top) * m..];
        xtop.par_chunks_mut(m)
            .zip(ytop.par_chunks_mut(m))
            .zip(xbottom.par_rchunks_mut(m).zip(ybottom.par_rchunks_mut(m)))
            .enumerate()
            .for_each(|(r, ((xp, yp), (xm, ym)))| fill_row(r + 1, (xp, yp), Some((xm, ym))));
    }

    /// X and Y on the product grid, in `[z][x]` order: the rows holding waves transformed
    /// along m_z, a tiled transpose, the rows transformed along m_x.
    fn fields(&mut self) {
        let (m, top) = (self.m, self.m_top);
        let s = self.inverse.scratch_len().max(self.forward.scratch_len());
        let inverse = &self.inverse;
        for (spectra, field) in [(&mut self.xs, &mut self.wx), (&mut self.ys, &mut self.wy)] {
            // Rows 0..=top and m − top..m hold waves; the others are zero and stay so.
            let (low, high) = spectra.split_at_mut((top + 1) * m);
            let high = &mut high[(m - 2 * top - 1) * m..];
            low.par_chunks_mut(ROWS * m)
                .chain(high.par_chunks_mut(ROWS * m))
                .zip(self.scratch.par_chunks_mut(s))
                .for_each(|(rows, scratch)| inverse.process(rows, scratch));
            transpose_rows(spectra, field, m, m);
            field
                .par_chunks_mut(ROWS * m)
                .zip(self.scratch.par_chunks_mut(s))
                .for_each(|(rows, scratch)| inverse.process(rows, scratch));
        }
    }

    /// Re(Y conj X) + i|X|² at every point, into `wx`.
    fn products(&mut self) {
        let m = self.m;
        self.wx
            .par_chunks_mut(m)
            .zip(self.wy.par_chunks(m))
            .for_each(|(x, y)| {
                for (x, y) in x.iter_mut().zip(y) {
                    let cross = y.re * x.re + y.im * x.im;
                    let square = x.re * x.re + x.im * x.im;
                    *x = Complex32::new(cross, square);
                }
            });
    }

    /// The forward transform of the products (along x, a transpose of the rows of kept K_x,
    /// along z), then H(K) = (½·Â − ¼|K|·B̂)/M² on the kept wave vectors, Â and B̂ the
    /// transforms of the real and imaginary parts.
    fn spectrum(&mut self) {
        let (n, m, top) = (self.n, self.m, self.m_top);
        let s = self.inverse.scratch_len().max(self.forward.scratch_len());
        let forward = &self.forward;
        self.wx
            .par_chunks_mut(ROWS * m)
            .zip(self.scratch.par_chunks_mut(s))
            .for_each(|(rows, scratch)| forward.process(rows, scratch));
        // wy[K_x][z] for the kept rows K_x = 0..=top and m − top..m.
        transpose_rows(&self.wx, &mut self.wy, m, top + 1);
        {
            let (_, high) = self.wy.split_at_mut((m - top) * m);
            let src = &self.wx[m - top..];
            transpose_into(src, m, high, m, top, m);
        }
        {
            let (low, high) = self.wy.split_at_mut((top + 1) * m);
            let high = &mut high[(m - 2 * top - 1) * m..];
            low.par_chunks_mut(ROWS * m)
                .chain(high.par_chunks_mut(ROWS * m))
                .zip(self.scratch.par_chunks_mut(s))
                .for_each(|(rows, scratch)| forward.process(rows, scratch));
        }
        let spectrum = &self.wy;
        let k_in = &self.k_in;
        let norm = 1.0 / (m as f32 * m as f32);
        self.h.par_chunks_mut(n).enumerate().for_each(|(i, row)| {
            for (j, h) in row.iter_mut().enumerate() {
                let k = k_in[i * n + j];
                if k == 0.0 {
                    *h = Complex32::default();
                    continue;
                }
                let mx = i as i32;
                let mz = wave_index(j, n);
                let at = |x: i32, z: i32| {
                    spectrum[x.rem_euclid(m as i32) as usize * m + z.rem_euclid(m as i32) as usize]
                };
                let (q, r) = (at(mx, mz), at(-mx, -mz).conj());
                let a = (q + r) * 0.5;
                let d = q - r;
                let b = Complex32::new(d.im * 0.5, -d.re * 0.5);
                *h = (a * 0.5 - b * (0.25 * k)) * norm;
            }
        });
    }
}

/// `dst[r][c] = src[c][r]` for the first `rows` rows of `dst` (M wide), in parallel blocks.
fn transpose_rows(src: &[Complex32], dst: &mut [Complex32], m: usize, rows: usize) {
    dst[..rows * m]
        .par_chunks_mut(ROWS * m)
        .enumerate()
        .for_each(|(b, block)| {
            let r0 = b * ROWS;
            let count = block.len() / m;
            transpose_into(&src[r0..], m, block, m, count, m);
        });
}

/// Adds H(K) of table row i (k_x = `kx` > 0) to the packed spectra of rows i (`upper`, at k)
/// and N − i (`lower`, at −k): H to η, i·k_x·H to η_x and i·k_z·H to η_z (transforms 0, 1
/// and 2; see `packed_pair`), and their conjugates at −k.
pub(super) fn add_to_row_pair(
    h: &[Complex32],
    kx: f32,
    kz: &[f32],
    upper: &mut [Complex32],
    lower: &mut [Complex32],
) {
    let n = kz.len();
    for (j, &value) in h.iter().enumerate() {
        if value.re == 0.0 && value.im == 0.0 {
            continue;
        }
        let partner = (n - j) % n;
        let (plus, minus) = terms(value, kx, kz[j]);
        for f in 0..3 {
            upper[f * n + j] += plus[f];
            lower[f * n + partner] += minus[f];
        }
    }
}

/// Adds H(K) of table row 0 (k_x = 0) to row 0, which holds both k (column j, 0 < j < N/2)
/// and −k (column N − j).
pub(super) fn add_to_row0(h: &[Complex32], kz: &[f32], row: &mut [Complex32]) {
    let n = kz.len();
    for j in 1..n / 2 {
        let value = h[j];
        if value.re == 0.0 && value.im == 0.0 {
            continue;
        }
        let (plus, minus) = terms(value, 0.0, kz[j]);
        for f in 0..3 {
            row[f * n + j] += plus[f];
            row[f * n + n - j] += minus[f];
        }
    }
}

/// The packed values H adds at k and at −k to transforms 0 (η, D_x), 1 (D_z, η_x) and
/// 2 (η_z, D_xx): H, i·(i k_x H) = −k_x H, i k_z H at k; conj H, k_x conj H, −i k_z conj H
/// at −k.
#[inline(always)]
fn terms(h: Complex32, kx: f32, kz: f32) -> ([Complex32; 3], [Complex32; 3]) {
    let c = h.conj();
    (
        [h, h * -kx, Complex32::new(-h.im * kz, h.re * kz)],
        [c, c * kx, Complex32::new(c.im * kz, -c.re * kz)],
    )
}

/// Checks that second-order terms of amplitudes whose fields are bounded by `bound` (the
/// cascade's amplitude bound, m) stay within f32 on a product grid of side `m` with waves
/// below `k_top` (rad/m): the products' transform sums M² products of fields.
pub(super) fn check_bound(bound: f64, k_top: f64, m: usize) -> Result<(), Error> {
    let limit = super::tables::AMPLITUDE_LIMIT;
    let second = bound * k_top.max(1.0) * m as f64;
    if second.is_nan() || second > limit {
        return Err(Error::AmplitudeTooLarge {
            bound: second,
            limit,
        });
    }
    Ok(())
}

impl Cascade {
    /// Turns on second-order bound waves for this cascade's waves below
    /// k_top = min(k_max, πN/2L) and recomputes the buffers at the current time. Nothing
    /// changes if it fails.
    ///
    /// # Errors
    /// [`Error::AmplitudeTooLarge`] if the second-order terms could overflow f32;
    /// [`Error::OutOfMemory`] if the system refuses a buffer.
    pub(crate) fn enable_second_order(&mut self) -> Result<(), Error> {
        let n = self.n;
        let length = f64::from(self.config.length);
        let dk = std::f64::consts::TAU / length;
        let k_top =
            f64::from(self.config.k_max).min(std::f64::consts::PI * n as f64 / length / 2.0);
        let determinism = self.config.determinism;
        let state = with_math!(determinism, M => SecondOrder::new::<M>(n, dk, k_top, determinism))?;
        if let Some(state) = &state {
            check_bound(self.amplitude_bound, k_top, state.grid())?;
        }
        self.second_order = state.map(Box::new);
        // Every row that may receive second-order terms is transformed.
        self.live_pairs = self.live_pairs.max(self.second_order_top_row());
        let t = self.time;
        self.update_checked(t, &mut []);
        Ok(())
    }

    /// The last table row that may receive second-order terms (0 when off).
    pub(super) fn second_order_top_row(&self) -> usize {
        self.second_order.as_deref().map_or(0, SecondOrder::top_row)
    }

    /// [`check_bound`] for new amplitudes bounded by `bound`, when second order is on.
    pub(super) fn check_second_order_bound(&self, bound: f64) -> Result<(), Error> {
        match &self.second_order {
            Some(state) => {
                let length = f64::from(self.config.length);
                let k_top = f64::from(self.config.k_max)
                    .min(std::f64::consts::PI * self.n as f64 / length / 2.0);
                check_bound(bound, k_top, state.grid())
            }
            None => Ok(()),
        }
    }
}
