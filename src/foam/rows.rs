//! Row kernels of the foam's passes: the total foam and its row sums, and the packing of two
//! real rows into one complex transform (and back) for the transport.

use num_complex::Complex32;

/// Partial sums per row in [`Foam::finish`](super::Foam::finish).
pub(super) const LANES: usize = 8;

/// The total foam a + r(1 − a) of a row into `f`, and the row's sums of a, r(1 − a) and the
/// total in f64 (see [`Foam::finish`](super::Foam::finish)): column i goes into partial sum i mod [`LANES`], and
/// the partial sums are added in order at the end. Written over whole arrays of [`LANES`]
/// values (one 512-bit register of f64), so that the conversions and additions vectorise at
/// every SIMD level; the order of the additions is the code's, whatever the level. Inlined
/// into its caller's [`Simd::run`](crate::math::simd::Simd::run).
#[inline(always)]
pub(super) fn total_row(a: &[f32], r: &[f32], f: &mut [f32]) -> [f64; 3] {
    let mut sum_a = [0.0f64; LANES];
    let mut sum_r = [0.0f64; LANES];
    let mut sum_f = [0.0f64; LANES];
    let whole = a.len() / LANES * LANES;
    let chunks = a[..whole]
        .chunks_exact(LANES)
        .zip(r[..whole].chunks_exact(LANES))
        .zip(f[..whole].chunks_exact_mut(LANES));
    for ((a, r), f) in chunks {
        let a: &[f32; LANES] = a.try_into().expect("LANES values");
        let r: &[f32; LANES] = r.try_into().expect("LANES values");
        let rest: [f32; LANES] = std::array::from_fn(|k| r[k] * (1.0 - a[k]));
        let total: [f32; LANES] = std::array::from_fn(|k| a[k] + rest[k]);
        f.copy_from_slice(&total);
        for k in 0..LANES {
            sum_a[k] += f64::from(a[k]);
            sum_r[k] += f64::from(rest[k]);
            sum_f[k] += f64::from(total[k]);
        }
    }
    for (k, ((&a, &r), f)) in a[whole..]
        .iter()
        .zip(&r[whole..])
        .zip(&mut f[whole..])
        .enumerate()
    {
        let rest = r * (1.0 - a);
        *f = a + rest;
        sum_a[k] += f64::from(a);
        sum_r[k] += f64::from(rest);
        sum_f[k] += f64::from(*f);
    }
    [sum_a, sum_r, sum_f].map(|lane| lane.iter().sum())
}

/// Packs two real rows (the real parts of `a` and `b`) into `a` as one complex row a + ib,
/// so that one complex transform does both.
#[inline(always)]
pub(super) fn pack_rows(a: &mut [Complex32], b: &[Complex32]) {
    for (a, b) in a.iter_mut().zip(b) {
        a.im = b.re;
    }
}

/// From W, the transform of a + ib for two real rows a and b (in `w`), the transforms of a
/// and b at m = 0 … N/2 (the rest follows from their Hermitian symmetry) into `w` and `b`:
/// A\[m\] = (W\[m\] + conj W\[N − m\])/2 and B\[m\] = (W\[m\] − conj W\[N − m\])/(2i). Each m reads
/// W\[m\] and W\[N − m\] before writing index m, and N − m > N/2 for 0 < m < N/2, so `w` can
/// take A in place.
#[inline(always)]
pub(super) fn unpack_halves(w: &mut [Complex32], b: &mut [Complex32]) {
    let n = w.len();
    let half = n / 2;
    // (x − y)/(2i) = −i(x − y)/2.
    let split = |x: Complex32, y: Complex32| {
        (
            Complex32::new(0.5 * (x.re + y.re), 0.5 * (x.im + y.im)),
            Complex32::new(0.5 * (x.im - y.im), -0.5 * (x.re - y.re)),
        )
    };
    (w[0], b[0]) = split(w[0], w[0].conj());
    (w[half], b[half]) = split(w[half], w[half].conj());
    let (low, high) = w.split_at_mut(half);
    // m = 1 … N/2 − 1 pairs with N − m = N − 1 … N/2 + 1.
    for ((x, b), y) in low[1..]
        .iter_mut()
        .zip(b[1..half].iter_mut())
        .zip(high[1..].iter().rev())
    {
        (*x, *b) = split(*x, y.conj());
    }
}

/// The inverse of [`unpack_halves`] before the last transform: from the half spectra Y_a
/// (in `v`) and Y_b (in `w`) at m = 0 … N/2 of two rows whose transforms are real, the row
/// Y_a + iY_b over all m in `v`, extended by Y\[N − m\] = conj Y\[m\]; at m = 0 and N/2, where
/// Y is its own partner, only its real part is kept (what taking the real part of a complex
/// result keeps there).
#[inline(always)]
pub(super) fn repack_halves(v: &mut [Complex32], w: &[Complex32]) {
    let n = v.len();
    let half = n / 2;
    let join = |a: Complex32, b: Complex32| Complex32::new(a.re - b.im, a.im + b.re);
    let (low, high) = v.split_at_mut(half + 1);
    // m = N/2 + 1 … N − 1 from N − m = N/2 − 1 … 1.
    for ((y, a), b) in high
        .iter_mut()
        .zip(low[1..half].iter().rev())
        .zip(w[1..half].iter().rev())
    {
        *y = join(a.conj(), b.conj());
    }
    for (a, b) in low[1..half].iter_mut().zip(&w[1..half]) {
        *a = join(*a, *b);
    }
    for m in [0, half] {
        v[m] = Complex32::new(v[m].re, w[m].re);
    }
}
