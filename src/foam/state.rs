//! The foam's state and its three-pass step: active and residual foam, the breaking
//! intensity, the total foam and its coverage, and the buffers of the transport, all
//! allocated once.

use num_complex::Complex32;
use rayon::prelude::*;

use std::ops::Bound::Included;

use crate::cascade::Cascade;
use crate::coast::Coast;
use crate::error::{self, Error};
use crate::math::determinism::{with_math, Determinism, Math};
use crate::math::exp::exp;
use crate::math::fft2d::{transpose_into, RowFft, ROWS_PER_TASK};
use crate::math::simd::Simd;

use super::detail::{Detail, DETAIL_BYTES};
use super::intensity::Params;
use super::model::{FoamChange, FoamSea, Model};
use super::rows::{pack_rows, repack_halves, total_row, unpack_halves};
use super::transport::Transport;
use super::{FoamCalibration, FoamConfig, FoamCoverage};

/// Rows of the foam grid one parallel task handles in every pass (the split depends only on
/// N, never on the number of threads): as many as a task of the transforms' second pass
/// gathers, so that the row pass, the column pass and the last pass share one scratch per
/// task.
const ROWS: usize = ROWS_PER_TASK;

/// Fewest grid points one rayon task of a foam pass works through, so that grids below 64²
/// do not pay a fork and join per block of a few hundred points; from 64² on every block of
/// [`ROWS`] rows is its own task, which keeps both threads busy (docs/performance.md, "The
/// foam").
const MIN_TASK_POINTS: usize = 1024;

/// Blocks of [`ROWS`] rows one rayon task takes at least, for a grid of side `n`.
fn min_tasks(n: usize) -> usize {
    MIN_TASK_POINTS.div_ceil(ROWS * n).max(1)
}

/// Residual foam below this after a transport step is set to zero: the rounding of the two
/// FFTs (about 1e-7 of the largest value) would otherwise leave a faint haze everywhere.
pub(super) const FLUSH: f32 = 1e-6;

/// The foam of an ocean: its state (active and residual foam), the breaking intensity at the
/// current time, the total foam and the coverage, the calibration, and the buffers of the
/// transport step (all allocated once).
#[derive(Debug, Clone)]
pub(crate) struct Foam {
    pub(crate) n: usize,
    /// Side of the foam grid's tile, L of cascade 0, in metres.
    pub(crate) length: f32,
    pub(super) active: Vec<f32>,
    pub(super) residual: Vec<f32>,
    pub(crate) total: Vec<f32>,
    pub(super) breaking: Vec<f32>,
    pub(super) coverage: FoamCoverage,
    pub(super) calibration: FoamCalibration,
    pub(super) params: Params,
    pub(super) transport: Transport,
    /// The transport's drift factors (see `Transport::fill_tables`) for a step of
    /// `tables_dt` seconds (NaN: not filled yet), kept while the step stays the same.
    pub(super) tables: Vec<Complex32>,
    pub(super) tables_dt: f64,
    /// The transport's grid in space order (row z, column x or m_x): the residual foam
    /// transformed along x, and in the last pass each task's gathered rows.
    pub(super) spatial: Vec<Complex32>,
    /// The transport's grid transposed (row m_x, column m_z or z), for m_x = 0 … N/2 only.
    pub(super) spectral: Vec<Complex32>,
    /// The inverse FFT of length N both axes use (the plan `Fft2d` would make).
    pub(super) fft: RowFft,
    /// FFT scratch, one slice per task of [`ROWS`] rows.
    pub(super) scratch: Vec<Complex32>,
    pub(super) row_sums: Vec<[f64; 3]>,
    /// The displacement gradient `[D_xx, D_zz, D_xz]` at unit choppiness of the foam's source
    /// cascade (cascade 0) at the current time, written by its update
    /// ([`update_source`](Self::update_source)).
    pub(super) gradient: Vec<[f32; 3]>,
    /// The settings the foam was built or last set with.
    pub(super) config: FoamConfig,
    /// What the foam's model reads from the sea (a blend during a change of weather).
    pub(super) sea: FoamSea,
    /// A change of weather in progress.
    pub(super) change: Option<FoamChange>,
    /// The determinism mode of the ocean, whose functions the transport's tables use.
    pub(super) determinism: Determinism,
    /// The SIMD level of the element loops.
    pub(super) simd: Simd,
    /// Where inside a cell the foam lies (`detail.rs`).
    pub(super) detail: Detail,
}

/// Bytes the foam of an ocean of size `n` holds: active, residual,
/// total and breaking (4 bytes each per point), the transport's complex grid (8 bytes per
/// point) and its transposed half (N/2 + 1 rows of N, 8 bytes each), FFT scratch for one
/// task per block of rows, small tables, and the displacement gradient cascade 0 keeps for
/// it (12 bytes per point, see [`Foam::update_source`]), and the detail's tables.
pub(crate) fn memory_bytes(n: usize, determinism: Determinism) -> usize {
    let points = n.saturating_mul(n);
    let scratch = if n <= crate::math::grid::MAX_SIZE {
        crate::math::fft2d::RowFft::new(n, determinism).scratch_len()
    } else {
        n
    };
    let tasks = n.div_ceil(crate::math::fft2d::ROWS_PER_TASK);
    let tables = n.saturating_mul(2 * 8 + 24);
    let half = (n / 2 + 1).saturating_mul(n);
    points
        .saturating_mul(4 * 4 + 8 + 12)
        .saturating_add(half.saturating_mul(8))
        .saturating_add(tasks.saturating_mul(scratch).saturating_mul(8))
        .saturating_add(tables)
        .saturating_add(DETAIL_BYTES)
}

impl Foam {
    /// The foam of an ocean with these (updated) cascades: no foam, the breaking intensity
    /// of the cascades' time, the threshold calibrated for their amplitudes.
    pub(crate) fn new(
        cascades: &mut [Cascade],
        config: &FoamConfig,
        spectrum: &crate::spectrum::Spectrum,
    ) -> Result<Foam, Error> {
        let determinism = cascades[0].config().determinism;
        with_math!(determinism, M => Self::new_with::<M>(cascades, config, spectrum))
    }

    /// [`Foam::new`] with the functions of `M`, the determinism mode of the cascades.
    fn new_with<M: Math>(
        cascades: &mut [Cascade],
        config: &FoamConfig,
        spectrum: &crate::spectrum::Spectrum,
    ) -> Result<Foam, Error> {
        let first = &cascades[0];
        let determinism = first.config().determinism;
        let n = first.size();
        let length = first.length();
        let sea = FoamSea::of::<M>(cascades, |c| c.h0(), spectrum);
        let Model {
            calibration,
            params,
            transport,
        } = Model::new::<M>(&sea, config, length);
        let points = n * n;
        let fft = RowFft::new(n, determinism);
        let mut foam = Foam {
            n,
            length,
            active: error::try_vec(points, 0.0)?,
            residual: error::try_vec(points, 0.0)?,
            total: error::try_vec(points, 0.0)?,
            breaking: error::try_vec(points, 0.0)?,
            coverage: FoamCoverage::default(),
            calibration,
            params,
            transport,
            tables: error::try_vec(2 * n, Complex32::default())?,
            tables_dt: f64::NAN,
            spatial: error::try_vec(points, Complex32::default())?,
            spectral: error::try_vec((n / 2 + 1) * n, Complex32::default())?,
            scratch: error::try_vec(n.div_ceil(ROWS) * fft.scratch_len(), Complex32::default())?,
            fft,
            row_sums: error::try_vec(n, [0.0; 3])?,
            gradient: error::try_vec(points, [0.0; 3])?,
            config: *config,
            sea,
            change: None,
            determinism,
            simd: Simd::detect(),
            detail: Detail::new::<M>(cascades, sea.wind_direction(), sea.peak_wavelength()),
        };
        cascades[0].fill_gradient(&mut foam.gradient);
        foam.refresh();
        Ok(foam)
    }

    /// Recomputes the breaking intensity from the cascades as they are now (after a jump in
    /// time or a restore), and the total foam and coverage from the state
    /// ([`finish`](Self::finish)). Not on the per-frame path (a step with dt > 0 computes
    /// the intensity in its first pass), so the intensity has a pass of its own.
    pub(crate) fn refresh(&mut self) {
        let n = self.n;
        let params = self.params;
        let simd = self.simd;
        self.breaking
            .par_chunks_mut(ROWS * n)
            .zip(self.gradient.par_chunks(ROWS * n))
            .with_min_len(min_tasks(n))
            .for_each(|(breaking, gradient)| {
                for (s, gradient) in breaking.chunks_mut(n).zip(gradient.chunks(n)) {
                    simd.run(
                        #[inline(always)]
                        || params.intensity_row(gradient, s),
                    );
                }
            });
        self.finish();
    }

    /// Integrates the foam over `dt` seconds up to the cascades' (new) time.
    ///
    /// Three passes over the grid, each one parallel loop over blocks of [`ROWS`] rows:
    /// 1. per row z: the new intensity, the aging of a and r, and r transformed along x, two
    ///    rows in one complex transform (or, with no transport, the total foam and the row
    ///    sums straight away);
    /// 2. per block of m_x = 0 … N/2 (r is real, so its transform at −m_x is the conjugate of
    ///    that at m_x): the block gathered by a tiled transpose, transformed along z, the
    ///    factor M(k) of the transport (see `transport.rs`), and transformed back along z;
    /// 3. per block of z: gathered back, transformed along x, two rows in one complex
    ///    transform, the residual foam (clamped to [0, 1], flushed below [`FLUSH`]), the
    ///    total foam and the row sums.
    ///
    /// The forward transform is the conjugate of the inverse transform of the real r. Packing
    /// two real rows in one complex row and transforming half the columns halves the
    /// transforms, transposes and factors of a complex transport, to the same result within
    /// the transforms' rounding (tested against two plain `Fft2d` transforms). Active foam
    /// stays where its wave broke (the grid already follows the water's orbital motion; the
    /// drift moves it less than a metre in its lifetime).
    pub(crate) fn advance(&mut self, dt: f64) {
        if dt <= 0.0 {
            // The same time: the intensity is recomputed (bit for bit the same), nothing
            // else changes.
            self.refresh();
            return;
        }
        let n = self.n;
        for (offset, drift) in self.detail.offset.iter_mut().zip(self.transport.drift) {
            *offset += drift * dt;
        }
        let moving = self.transport.is_active();
        if moving {
            // A game steps by the same dt frame after frame: the tables (2N sines and cosines
            // in f64, a few per cent of the foam at 64²) are a function of dt alone.
            if dt.to_bits() != self.tables_dt.to_bits() {
                let (transport, tables) = (&self.transport, &mut self.tables);
                with_math!(self.determinism, M => transport.fill_tables::<M>(dt, n, tables));
                self.tables_dt = dt;
            }
        }
        let Foam {
            active,
            residual,
            breaking,
            total,
            row_sums,
            spatial,
            spectral,
            fft,
            scratch,
            tables,
            transport,
            params,
            gradient,
            simd,
            ..
        } = self;
        let (params, simd, fft) = (*params, *simd, &*fft);
        let step = params.step(dt as f32);
        let block = ROWS * n;
        let s = fft.scratch_len();
        let min_len = min_tasks(n);
        // 1. Intensity and aging row by row; r transformed along x.
        (
            active.par_chunks_mut(block),
            residual.par_chunks_mut(block),
            breaking.par_chunks_mut(block),
            total.par_chunks_mut(block),
            row_sums.par_chunks_mut(ROWS),
            spatial.par_chunks_mut(block),
            scratch.par_chunks_mut(s),
            gradient.par_chunks(block),
        )
            .into_par_iter()
            .with_min_len(min_len)
            .for_each(
                |(active, residual, breaking, total, sums, work, scratch, gradient)| {
                    let rows = active
                        .chunks_mut(n)
                        .zip(residual.chunks_mut(n))
                        .zip(breaking.chunks_mut(n))
                        .zip(work.chunks_mut(n))
                        .zip(total.chunks_mut(n).zip(sums.iter_mut()))
                        .zip(gradient.chunks(n));
                    for (((((a, rr), s), w), (f, sum)), gradient) in rows {
                        simd.run(
                            #[inline(always)]
                            || {
                                params.react_row(&step, gradient, a, rr, s, w);
                                if !moving {
                                    *sum = total_row(a, rr, f);
                                }
                            },
                        );
                    }
                    if moving {
                        for pair in work.chunks_exact_mut(2 * n) {
                            let (a, b) = pair.split_at_mut(n);
                            simd.run(
                                #[inline(always)]
                                || pack_rows(a, b),
                            );
                            fft.process(a, scratch);
                            simd.run(
                                #[inline(always)]
                                || unpack_halves(a, b),
                            );
                        }
                    }
                },
            );
        if !moving {
            self.sum_rows();
            return;
        }
        // 2. Columns: along z, the transport's factor, back along z. The block's rows are
        // m_x = j0 … j0 + ROWS − 1, its columns m_z (then z).
        let [ca, cb, cc] = transport.exponent(dt);
        let tables = &*tables;
        let source = &*spatial;
        let half = n / 2 + 1;
        spectral
            .par_chunks_mut(block)
            .zip(scratch.par_chunks_mut(s))
            .with_min_len(min_len)
            .enumerate()
            .for_each(|(b, (rows, scratch))| {
                let j0 = b * ROWS;
                let height = rows.len() / n;
                transpose_into(&source[j0..], n, rows, n, height, n);
                fft.process(rows, scratch);
                let shifts = &tables[n..2 * n];
                for (r, row) in rows.chunks_mut(n).enumerate() {
                    let ix = j0 + r;
                    let mx = crate::math::grid::wave_index(ix, n) as f32;
                    let shift_x = tables[ix];
                    let (ax, bx) = (ca * mx * mx, 2.0 * cb * mx);
                    simd.run(
                        #[inline(always)]
                        || {
                            for (iz, (g, shift_z)) in row.iter_mut().zip(shifts).enumerate() {
                                let mz = crate::math::grid::wave_index(iz, n) as f32;
                                let decay = exp(-(ax + mz * (bx + cc * mz)));
                                *g = g.conj() * (shift_x * shift_z) * decay;
                            }
                        },
                    );
                }
                fft.process(rows, scratch);
            });
        // 3. Rows again: gathered, along x, and the residual foam, the total foam and the row
        // sums of `finish` while the row is in cache.
        let scale = 1.0 / (n * n) as f32;
        let flush = |v: f32| if v < FLUSH { 0.0 } else { v.min(1.0) };
        let source = &*spectral;
        (
            spatial.par_chunks_mut(block),
            scratch.par_chunks_mut(s),
            residual.par_chunks_mut(block),
            active.par_chunks(block),
            total.par_chunks_mut(block),
            row_sums.par_chunks_mut(ROWS),
        )
            .into_par_iter()
            .with_min_len(min_len)
            .enumerate()
            .for_each(|(b, (work, scratch, residual, active, total, sums))| {
                let j0 = b * ROWS;
                let height = work.len() / n;
                transpose_into(&source[j0..], n, work, n, height, half);
                let rows = residual
                    .chunks_mut(2 * n)
                    .zip(work.chunks_exact_mut(2 * n))
                    .zip(active.chunks(2 * n))
                    .zip(total.chunks_mut(2 * n))
                    .zip(sums.chunks_mut(2));
                for ((((r, pair), a), f), sums) in rows {
                    let (v, w) = pair.split_at_mut(n);
                    simd.run(
                        #[inline(always)]
                        || repack_halves(v, w),
                    );
                    fft.process(v, scratch);
                    let (r0, r1) = r.split_at_mut(n);
                    let (a0, a1) = a.split_at(n);
                    let (f0, f1) = f.split_at_mut(n);
                    simd.run(
                        #[inline(always)]
                        || {
                            for ((r0, r1), v) in r0.iter_mut().zip(r1.iter_mut()).zip(&*v) {
                                *r0 = flush(v.re * scale);
                                *r1 = flush(v.im * scale);
                            }
                            sums[0] = total_row(a0, r0, f0);
                            sums[1] = total_row(a1, r1, f1);
                        },
                    );
                }
            });
        self.sum_rows();
    }

    /// The total foam a + r(1 − a) and the coverage: each row summed in f64 in [`LANES`](super::rows::LANES)
    /// interleaved partial sums (column i into sum i mod `LANES`, so that the loop vectorises
    /// and its order is fixed by the code, not by the SIMD level), those added in order, and
    /// the rows added in order.
    pub(super) fn finish(&mut self) {
        let n = self.n;
        let simd = self.simd;
        (
            self.active.par_chunks(ROWS * n),
            self.residual.par_chunks(ROWS * n),
            self.total.par_chunks_mut(ROWS * n),
            self.row_sums.par_chunks_mut(ROWS),
        )
            .into_par_iter()
            .with_min_len(min_tasks(n))
            .for_each(|(active, residual, total, sums)| {
                let rows = active
                    .chunks(n)
                    .zip(residual.chunks(n))
                    .zip(total.chunks_mut(n));
                for (((a, r), f), sum) in rows.zip(sums.iter_mut()) {
                    *sum = simd.run(
                        #[inline(always)]
                        || total_row(a, r, f),
                    );
                }
            });
        self.sum_rows();
    }

    /// The coverage from the row sums of [`finish`](Self::finish), added in order.
    fn sum_rows(&mut self) {
        let n = self.n;
        let mut sum = [0.0f64; 3];
        for row in &self.row_sums {
            for k in 0..3 {
                sum[k] += row[k];
            }
        }
        let points = (n * n) as f64;
        self.coverage = FoamCoverage {
            active: (sum[0] / points) as f32,
            residual: (sum[1] / points) as f32,
            total: (sum[2] / points) as f32,
        };
    }

    /// Runs the element loops at `simd` from now on (the tests force every level).
    #[cfg(test)]
    pub(crate) fn set_simd(&mut self, simd: Simd) {
        self.simd = simd;
    }

    /// Removes all foam (the breaking intensity, a function of the time, stays).
    pub(crate) fn clear(&mut self) {
        self.clear_state();
        self.finish();
    }

    /// Updates the foam's source, cascade 0 (`cascade`), to the checked time `t`, and with it
    /// the displacement gradient the foam reads.
    pub(crate) fn update_source(&mut self, cascade: &mut Cascade, t: f64) {
        cascade.update_checked(t, &mut self.gradient);
    }

    /// Active foam a on the foam grid.
    pub(crate) fn active(&self) -> &[f32] {
        &self.active
    }

    /// Residual foam r on the foam grid.
    pub(crate) fn residual(&self) -> &[f32] {
        &self.residual
    }

    /// The total foam a + r(1 − a) on the foam grid.
    pub(crate) fn total(&self) -> &[f32] {
        &self.total
    }

    /// The breaking intensity in 1/s on the foam grid.
    pub(crate) fn breaking(&self) -> &[f32] {
        &self.breaking
    }

    /// The coverage at the last change.
    pub(crate) fn coverage(&self) -> FoamCoverage {
        self.coverage
    }

    /// The whitecap calibration.
    pub(crate) fn calibration(&self) -> FoamCalibration {
        self.calibration
    }

    /// Checks a foam state (active and residual foam, one value per grid point in [0, 1], as
    /// [`active`](Self::active) and [`residual`](Self::residual) give them) for
    /// [`set_state`](Self::set_state); the names are the parameters the errors name.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless both hold one value per grid point;
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for a value outside [0, 1].
    pub(crate) fn check_state(
        &self,
        (active_name, active): (&'static str, &[f32]),
        (residual_name, residual): (&'static str, &[f32]),
    ) -> Result<(), Error> {
        let points = self.n * self.n;
        error::length(active_name, active.len(), points)?;
        error::length(residual_name, residual.len(), points)?;
        for (name, values) in [(active_name, active), (residual_name, residual)] {
            for &value in values {
                error::in_range(name, value, Included(0.0), Included(1.0))?;
            }
        }
        Ok(())
    }

    /// Replaces the foam's state with one [`check_state`](Self::check_state) accepted. The
    /// breaking intensity, the total and the coverage follow at the next
    /// [`refresh`](Self::refresh) or step.
    pub(crate) fn set_state(&mut self, active: &[f32], residual: &[f32]) {
        self.active.copy_from_slice(active);
        self.residual.copy_from_slice(residual);
    }

    /// The streak field of the foam's detail as a renderer samples it.
    pub(crate) fn streaks(&self) -> super::FoamStreaks<'_> {
        self.detail.streaks()
    }

    /// How far the streak field of the foam's detail has drifted, `[x, z]` m.
    pub(crate) fn drift_offset(&self) -> [f64; 2] {
        self.detail.offset
    }

    /// Sets the streak field's drift (a restored snapshot's).
    pub(crate) fn set_drift_offset(&mut self, offset: [f64; 2]) {
        self.detail.offset = offset;
    }

    /// Removes all foam from the state; the total and the coverage follow at the next
    /// [`refresh`](Self::refresh) or step.
    pub(crate) fn clear_state(&mut self) {
        self.active.fill(0.0);
        self.residual.fill(0.0);
    }

    /// The breaking intensity in 1/s at undisplaced world (x, z).
    pub(crate) fn breaking_at(&self, x: f64, z: f64) -> f32 {
        self.interpolate(&self.breaking, x, z)
    }

    /// Periodic bilinear interpolation of `values` (a foam-grid buffer) at world (x, z), at
    /// least 0.
    #[inline(always)]
    fn interpolate(&self, values: &[f32], x: f64, z: f64) -> f32 {
        let length = f64::from(self.length);
        crate::math::periodic::periodic_bilinear(values, self.n, length, x, z).max(0.0)
    }
}

impl Foam {
    /// The foam at undisplaced world (x, z) with its detail: the coarse fractions a and r
    /// interpolated bilinearly from the foam grid, placed by the compression of `cascades` ≥ 1
    /// (the ocean's, whose cascade 0 is the foam's grid) and by the streak field.
    pub(crate) fn detail_at(
        &self,
        cascades: &[Cascade],
        x: f64,
        z: f64,
        coast: Option<(&Coast, f64)>,
    ) -> FoamCoverage {
        let length = f64::from(self.length);
        let coarse = |values: &[f32]| {
            // NaN becomes 0, as the coarse lookup always made it.
            let v = crate::math::periodic::periodic_bilinear(values, self.n, length, x, z);
            if v.is_nan() {
                0.0
            } else {
                v.clamp(0.0, 1.0)
            }
        };
        let (a, r) = (coarse(&self.active), coarse(&self.residual));
        // Over a depth map: the surf's coarse fractions (`Coast::surf`), patterned alike.
        let (a, r) = match coast {
            Some((coast, t)) => coast.surf(t, x, z, a, r),
            None => (a, r),
        };
        let variance = self.sea.unresolved_compression();
        let u = self.detail.compression_at(cascades, variance, x, z);
        self.detail.foam(a, r, u, self.detail.streak_at(x, z))
    }
}
