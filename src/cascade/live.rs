//! A live change of a cascade's amplitudes (see `OceanState::set_spectrum`): the new
//! spectrum's amplitudes drawn a few rows at a time as `Cascade::new` draws them, then blended
//! with the old ones by energy, every wave keeping its random phase, and installed exactly at
//! the end.

use num_complex::Complex32;
use rayon::prelude::*;

use super::tables::{self, check_amplitude, LoopError};
use super::update::RowPruning;
use super::{mean_level_per_choppiness, row_stride, Cascade};
use crate::determinism::{with_math, Math};
use crate::error::{self, Error};
use crate::spectrum::{SlopeVariance, Spectrum};

/// What one entry of the radial table costs to compute, in wave vectors drawn with it (the
/// omnidirectional spectrum, dispersion and spreading shape against a direction and a draw).
const RADIAL_COST: usize = 4;

/// What a cascade knows about one set of amplitudes besides the amplitudes themselves.
#[derive(Debug, Clone, Copy)]
pub(crate) struct AmplitudeStats {
    /// Σ S(k) Δk², m².
    pub(crate) expected_variance: f64,
    /// 2 Σ |k| |h0|², m (the mean-level correction per unit choppiness).
    pub(crate) mean_level: f64,
    /// The spectrum's slope variance above the band.
    pub(crate) subgrid_slope: SlopeVariance,
}

impl AmplitudeStats {
    /// The statistics of the energy blend (1 − w)·`self` + w·`other`: all three are sums of
    /// energies.
    fn blend(&self, other: &AmplitudeStats, w: f64) -> AmplitudeStats {
        let lerp = |a: f64, b: f64| (1.0 - w) * a + w * b;
        let lerp32 = |a: f32, b: f32| lerp(f64::from(a), f64::from(b)) as f32;
        AmplitudeStats {
            expected_variance: lerp(self.expected_variance, other.expected_variance),
            mean_level: lerp(self.mean_level, other.mean_level),
            subgrid_slope: SlopeVariance {
                along: lerp32(self.subgrid_slope.along, other.subgrid_slope.along),
                across: lerp32(self.subgrid_slope.across, other.subgrid_slope.across),
            },
        }
    }
}

/// The new amplitudes once every row is drawn, with everything `Cascade::new` derives from
/// them.
#[derive(Debug, Clone, Copy)]
struct Drawn {
    stats: AmplitudeStats,
    amplitude_bound: f64,
    loop_error: Option<LoopError>,
}

/// A change of amplitudes in progress (the buffers are kept between changes).
#[derive(Debug, Clone, Default)]
pub(crate) struct AmplitudeChange {
    /// Whether a change is in progress.
    active: bool,
    /// The amplitudes the blend starts from (N×N, FFT order).
    from: Vec<Complex32>,
    from_stats: Option<AmplitudeStats>,
    /// The new amplitudes, rows `0..rows_drawn` drawn so far.
    target: Vec<Complex32>,
    /// Σ S(k)Δk² of each drawn row.
    variance_rows: Vec<f64>,
    /// Wave vectors of the band in each grid row (what drawing the row costs).
    band_rows: Vec<u32>,
    /// Whether grid column i holds a wave vector of the band.
    band_columns: Vec<bool>,
    /// Once the blend has begun, per point the energy of the side `from` no longer holds
    /// relative to the one it holds (see [`Cascade::blend_change`]).
    coef: Vec<f32>,
    /// Whether `from` and `coef` hold the blend's form.
    blending: bool,
    /// Which points are zero in the blend as the band pruning last saw it: 0 the old
    /// amplitudes' (w = 0), 1 either side's (0 < w < 1), 2 the new ones' (w = 1).
    pruned_for: u8,
    rows_drawn: usize,
    /// The radial parts of the new spectrum per wave-vector length (see
    /// `tables::RadialEntry`), rows `0..radial_rows` filled so far.
    radial: Vec<tables::RadialEntry>,
    radial_rows: usize,
    drawn: Option<Drawn>,
}

impl Cascade {
    /// Allocates the buffers of a change of amplitudes (16 bytes a point) if this cascade has
    /// none yet.
    ///
    /// # Errors
    /// [`Error::OutOfMemory`] if the system refuses them.
    pub(crate) fn reserve_change(&mut self) -> Result<(), Error> {
        let points = self.n * self.n;
        if self.change.from.len() != points {
            let n = self.n;
            let config = &self.config;
            let mut band_rows = error::try_vec(n, 0u32)?;
            let mut band_columns = error::try_vec(n, false)?;
            with_math!(config.determinism, M => {
                for (j, count) in band_rows.iter_mut().enumerate() {
                    for (i, column) in band_columns.iter_mut().enumerate() {
                        if tables::in_band::<M>(config, i, j).is_some() {
                            *count += 1;
                            *column = true;
                        }
                    }
                }
            });
            self.change.from = error::try_vec(points, Complex32::default())?;
            self.change.target = error::try_vec(points, Complex32::default())?;
            self.change.variance_rows = error::try_vec(n, 0.0)?;
            self.change.coef = error::try_vec(points, 0.0)?;
            self.change.band_rows = band_rows;
            self.change.band_columns = band_columns;
            self.change.radial =
                error::try_vec(tables::radial_entries(n), tables::RadialEntry::NONE)?;
        }
        Ok(())
    }

    /// Starts a change to new amplitudes (after [`reserve_change`](Self::reserve_change)):
    /// the current ones (a blend, if a change was in progress) become those the blend starts
    /// from, and none of the new ones is drawn yet.
    pub(crate) fn begin_change(&mut self) {
        let change = &mut self.change;
        change.from.copy_from_slice(&self.h0);
        change.from_stats = Some(AmplitudeStats {
            expected_variance: self.expected_variance,
            mean_level: self.mean_level,
            subgrid_slope: self.subgrid_slope,
        });
        change.rows_drawn = 0;
        change.radial_rows = 0;
        change.drawn = None;
        change.blending = false;
        change.pruned_for = 0;
        change.active = true;
    }

    /// Checks that `spectrum`'s amplitudes would keep this cascade's fields within f32 at the
    /// current choppiness, as [`Cascade::new`] checks. A bound from the band's variance
    /// settles it for any sea a million times below the limit in variance (by Cauchy–Schwarz,
    /// Σ|h0| ≤ ½·max|ξ|·√(N²·Σ S Δk²), with max|ξ| ≤ 40 for every draw the generators can
    /// make, and the grid's sum taken as at most a million times the band's integral); beyond
    /// that the amplitudes are drawn (into a buffer of their own) and checked exactly.
    ///
    /// # Errors
    /// [`Error::AmplitudeTooLarge`] as [`Cascade::new`]; [`Error::OutOfMemory`] if the exact
    /// check's buffer is refused.
    pub(crate) fn check_amplitudes_for(&self, spectrum: &Spectrum) -> Result<(), Error> {
        let n = self.n;
        let config = &self.config;
        let variance = spectrum.band_variance_f64(f64::from(config.k_min), f64::from(config.k_max));
        let points = (n * n) as f64;
        let dk64 = std::f64::consts::TAU / f64::from(config.length);
        let k_grid_max = dk64 * (n as f64 / 2.0) * std::f64::consts::SQRT_2;
        let bound = 2.0 * 20.0 * (points * variance * 1e6).sqrt() * k_grid_max.max(1.0);
        if check_amplitude(bound, config.choppiness).is_ok() {
            return Ok(());
        }
        let drawn =
            with_math!(config.determinism, M => tables::Amplitudes::draw::<M>(spectrum, config))?;
        check_amplitude(drawn.amplitude_bound, config.choppiness)
    }

    /// Whether a change begun with [`begin_change`](Self::begin_change) has all its new
    /// amplitudes and what follows from them.
    pub(crate) fn change_drawn(&self) -> bool {
        self.change.drawn.is_some()
    }

    /// Whether every row of the new amplitudes is drawn (what follows from them may not be).
    pub(crate) fn change_rows_drawn(&self) -> bool {
        self.change.rows_drawn == self.n
    }

    /// Draws the next part of the new amplitudes of `spectrum`, as `Cascade::new` draws
    /// them: first the radial table (each entry counted as [`RADIAL_COST`] wave vectors), then
    /// grid rows, until the work holds at least `budget` wave vectors of the band (at least
    /// one row; a fixed amount of work, whatever the machine).
    pub(crate) fn draw_change<M: Math>(&mut self, spectrum: &Spectrum, budget: usize) {
        let n = self.n;
        let change = &mut self.change;
        if !change.active || change.rows_drawn == n {
            return;
        }
        let half = n / 2;
        if change.radial_rows <= half {
            let start = change.radial_rows;
            let mut end = start;
            // Row a of the table holds a + 1 lengths.
            while end <= half
                && (end == start
                    || (end * (end + 1) / 2 - start * (start + 1) / 2) * RADIAL_COST < budget)
            {
                end += 1;
            }
            tables::fill_radial::<M>(spectrum, &self.config, start..end, &mut change.radial);
            change.radial_rows = end;
            return;
        }
        let start = change.rows_drawn;
        let mut end = start;
        let mut work = 0usize;
        while end < n && (end == start || work < budget) {
            work += change.band_rows[end] as usize;
            end += 1;
        }
        tables::draw_rows::<M>(
            spectrum,
            &self.config,
            start..end,
            &change.radial,
            &mut change.target,
            &mut change.variance_rows[start..end],
        );
        change.rows_drawn = end;
    }

    /// Once every row is drawn, derives from the new amplitudes what [`Cascade::new`] derives
    /// from them (variance, mean level, slope variance above the band, amplitude bound, loop
    /// error).
    pub(crate) fn finish_change<M: Math>(&mut self, spectrum: &Spectrum) {
        let n = self.n;
        let change = &mut self.change;
        if !change.active || change.rows_drawn != n || change.drawn.is_some() {
            return;
        }
        let h0 = &change.target;
        let dk64 = std::f64::consts::TAU / f64::from(self.config.length);
        let looping = self.config.repeat_period.map(f64::from);
        let nyquist = std::f64::consts::PI * n as f64 / f64::from(self.config.length);
        let band_top = f64::from(self.config.k_max).min(nyquist);
        change.drawn = Some(Drawn {
            stats: AmplitudeStats {
                expected_variance: change.variance_rows.iter().sum(),
                mean_level: mean_level_per_choppiness::<M>(h0, n, dk64),
                subgrid_slope: spectrum
                    .slope_variance_with::<M>(band_top, f64::from(SlopeVariance::DEFAULT_CUTOFF)),
            },
            amplitude_bound: tables::amplitude_bound::<M>(h0, &self.config),
            loop_error: looping
                .map(|period| LoopError::new::<M>(h0, n, dk64, spectrum.dispersion(), period)),
        });
    }

    /// Checks that the new amplitudes, all drawn, keep the fields within f32 at the current
    /// choppiness (see [`Cascade::MAX_AMPLITUDE`]).
    ///
    /// # Errors
    /// [`Error::AmplitudeTooLarge`] if they do not.
    pub(crate) fn check_change(&self) -> Result<(), Error> {
        match self.change.drawn {
            Some(drawn) => {
                check_amplitude(drawn.amplitude_bound, self.config.choppiness)?;
                self.check_second_order_bound(drawn.amplitude_bound)
            }
            None => Ok(()),
        }
    }

    /// The new amplitudes once all are drawn.
    pub(crate) fn change_target(&self) -> Option<&[Complex32]> {
        self.change.drawn.map(|_| &self.change.target[..])
    }

    /// Abandons the change in progress, keeping the amplitudes as they are.
    pub(crate) fn cancel_change(&mut self) {
        self.change.active = false;
    }

    /// Sets the amplitudes to the energy blend of the change's old and new ones with weight
    /// `w` in [0, 1] on the new (all drawn): every wave keeps its phase (old and new share
    /// their random draw) and |h0|² = (1 − w)|h0_old|² + w|h0_new|², so the variance, the
    /// mean level and every second moment move linearly from the old sea's to the new sea's.
    /// At w = 1 the new amplitudes are installed exactly, with everything `Cascade::new`
    /// derives from them, and the change ends: the cascade is then the one `Cascade::new`
    /// builds for the new spectrum. Allocates nothing.
    ///
    /// The first call puts the blend in a form a step evaluates in a few operations a point:
    /// `from` holds the larger of the two amplitudes (the reference r) and `coef` the other's
    /// energy relative to it, c = |h0_new|²/|r|² (sign bit clear) where r is the old one and
    /// −|h0_old|²/|r|² (sign bit set, −0 for a wave the old sea lacks) where it is the new
    /// one; then h0 = r·√((1 − w)·c_old + w·c_new).
    pub(crate) fn blend_change(&mut self, w: f64) {
        let n = self.n;
        let Some(drawn) = self.change.drawn else {
            return;
        };
        if !self.change.blending {
            self.change.blending = true;
            let AmplitudeChange {
                from, target, coef, ..
            } = &mut self.change;
            from.par_chunks_mut(n)
                .zip(target.par_chunks(n).zip(coef.par_chunks_mut(n)))
                .for_each(|(from, (target, coef))| {
                    for ((a, &b), c) in from.iter_mut().zip(target).zip(coef) {
                        (*a, *c) = reference_form(*a, b);
                    }
                });
        }
        let from_stats = self.change.from_stats.unwrap_or(drawn.stats);
        let (stats, class) = if w >= 1.0 {
            self.h0.copy_from_slice(&self.change.target);
            self.amplitude_bound = drawn.amplitude_bound;
            self.loop_error = drawn.loop_error;
            self.change.active = false;
            (drawn.stats, 2)
        } else {
            let (old, new) = ((1.0 - w) as f32, w as f32);
            let (reference, coef) = (&self.change.from, &self.change.coef);
            let band_rows = &self.change.band_rows;
            self.h0
                .par_chunks_mut(n)
                .zip(reference.par_chunks(n).zip(coef.par_chunks(n)))
                .enumerate()
                // Rows without a wave vector of the band are zero on both sides.
                .filter(|(j, _)| band_rows[*j] > 0)
                .for_each(|(_, (h0, (reference, coef)))| {
                    for ((h, &r), &c) in h0.iter_mut().zip(reference).zip(coef) {
                        // The sign bit says which side is the reference (−0 for a new wave).
                        let (c_old, c_new) = if c.is_sign_negative() {
                            (-c, 1.0)
                        } else {
                            (1.0, c)
                        };
                        *h = r * (old * c_old + new * c_new).sqrt();
                    }
                });
            // The blend of two bounds is within their larger (each |h0| is).
            self.amplitude_bound = self.amplitude_bound.max(drawn.amplitude_bound);
            (from_stats.blend(&drawn.stats, w), u8::from(w > 0.0))
        };
        self.expected_variance = stats.expected_variance;
        self.mean_level = stats.mean_level;
        self.subgrid_slope = stats.subgrid_slope;
        // Table row i reads grid columns i and N − i.
        let columns = &self.change.band_columns;
        self.evolution
            .set_amplitudes(&self.h0, n, |i| columns[i] || columns[(n - i) % n]);
        if class != self.change.pruned_for || class == 2 {
            self.change.pruned_for = class;
            self.update_pruning();
        }
    }

    /// Recomputes the band pruning from the evolution table, and zeroes the spectral rows
    /// the update stops writing (it writes only live rows and relies on the others staying
    /// zero). Allocates nothing.
    fn update_pruning(&mut self) {
        let n = self.n;
        let stride = row_stride(n);
        // Rows that may receive second-order terms are written whatever their waves.
        let second_top = self.second_order_top_row();
        // Which row pairs the update wrote so far, one bit each (N/2 ≤ 2048).
        let mut written = [0u64; 32];
        for i in 1..n / 2 {
            if i <= self.live_pairs && (!self.pruning[i].empty || i <= second_top) {
                written[i / 64] |= 1 << (i % 64);
            }
        }
        for i in 0..n / 2 {
            self.pruning[i] = RowPruning::of_row(&self.evolution, i, n);
        }
        let live = (1..n / 2)
            .rev()
            .find(|&i| !self.pruning[i].empty)
            .unwrap_or(0)
            .max(second_top);
        for i in 1..n / 2 {
            let was_written = written[i / 64] & (1 << (i % 64)) != 0;
            if was_written && (i > live || (self.pruning[i].empty && i > second_top)) {
                for row in [i, n - i] {
                    self.spectral[row * stride..(row + 1) * stride].fill(Complex32::default());
                }
            }
        }
        self.live_pairs = live;
    }
}

/// The blend's form of an old amplitude `a` and a new one `b` (which share their phase: the
/// same random draw times two non-negative reals): the larger, and the other's energy
/// relative to it, negative when the larger is the new one (see [`Cascade::blend_change`]).
fn reference_form(a: Complex32, b: Complex32) -> (Complex32, f32) {
    let (na, nb) = (f64::from(a.norm_sqr()), f64::from(b.norm_sqr()));
    if na == 0.0 && nb == 0.0 {
        (Complex32::default(), 0.0)
    } else if na >= nb {
        (a, (nb / na) as f32)
    } else {
        (b, -(na / nb) as f32)
    }
}
