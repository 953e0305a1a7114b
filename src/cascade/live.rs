//! A live change of a cascade's amplitudes (see `OceanState::set_spectrum`): the new
//! spectrum's amplitudes drawn a few rows at a time as `Cascade::new` draws them, then blended
//! with the old ones by energy, every wave keeping its random phase, and installed exactly at
//! the end. The blend is a function of its weight alone: the old amplitudes are kept, so a
//! weight of 0 shows them again bit for bit.

use num_complex::Complex32;
use rayon::prelude::*;

use super::tables::{self, check_amplitude, LoopError};
use super::update::RowPruning;
use super::{mean_level_per_choppiness, row_stride, Cascade};
use crate::error::{self, Error};
use crate::math::determinism::{with_math, Math};
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
    /// The amplitudes the blend starts from (N×N, FFT order), kept throughout.
    from: Vec<Complex32>,
    from_stats: Option<AmplitudeStats>,
    /// The amplitude bound of `from`.
    from_bound: f64,
    /// The new amplitudes, rows `0..rows_drawn` drawn so far.
    target: Vec<Complex32>,
    /// Σ S(k)Δk² of each drawn row.
    variance_rows: Vec<f64>,
    /// Wave vectors of the band in each grid row (what drawing the row costs).
    band_rows: Vec<u32>,
    /// Whether grid column i holds a wave vector of the band.
    band_columns: Vec<bool>,
    /// Per point the energy of the smaller side relative to the larger one, the reference,
    /// negative when the reference is the new side (see [`Cascade::blend_change`]).
    coef: Vec<f32>,
    /// Whether `coef` is computed for the new amplitudes.
    formed: bool,
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
        change.from_bound = self.amplitude_bound;
        change.rows_drawn = 0;
        change.radial_rows = 0;
        change.drawn = None;
        change.formed = false;
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

    /// Whether the blend's form of a change (its `coef`) is computed.
    pub(crate) fn change_formed(&self) -> bool {
        self.change.formed
    }

    /// What preparing a change costs here (after [`reserve_change`](Self::reserve_change)),
    /// in wave vectors drawn: the calls of [`draw_change`](Self::draw_change) with `budget`,
    /// then [`finish_change`](Self::finish_change) and [`form_change`](Self::form_change).
    pub(crate) fn change_cost(&self, budget: usize) -> usize {
        let (n, half) = (self.n, self.n / 2);
        let mut cost = self.finish_cost() + self.form_cost();
        let mut start = 0;
        while start <= half {
            let end = radial_end(start, half, budget);
            cost += radial_cost(start, end);
            start = end;
        }
        let mut start = 0;
        while start < n {
            let (end, work) = rows_end(&self.change.band_rows, start, budget);
            cost += work;
            start = end;
        }
        cost
    }

    /// What [`finish_change`](Self::finish_change) costs, in wave vectors drawn (a few
    /// passes over the grid).
    pub(crate) fn finish_cost(&self) -> usize {
        self.n * self.n / 4
    }

    /// What [`form_change`](Self::form_change) costs, in wave vectors drawn (a division a
    /// point).
    pub(crate) fn form_cost(&self) -> usize {
        self.n * self.n / 8
    }

    /// Draws the next part of the new amplitudes of `spectrum`, as `Cascade::new` draws
    /// them: first the radial table (each entry counted as [`RADIAL_COST`] wave vectors), then
    /// grid rows, until the work holds at least `budget` wave vectors of the band (at least
    /// one row; a fixed amount of work, whatever the machine). Returns that work.
    pub(crate) fn draw_change<M: Math>(&mut self, spectrum: &Spectrum, budget: usize) -> usize {
        let n = self.n;
        let change = &mut self.change;
        if !change.active || change.rows_drawn == n {
            return 0;
        }
        let half = n / 2;
        if change.radial_rows <= half {
            let start = change.radial_rows;
            let end = radial_end(start, half, budget);
            tables::fill_radial::<M>(spectrum, &self.config, start..end, &mut change.radial);
            change.radial_rows = end;
            return radial_cost(start, end);
        }
        let start = change.rows_drawn;
        let (end, work) = rows_end(&change.band_rows, start, budget);
        tables::draw_rows::<M>(
            spectrum,
            &self.config,
            start..end,
            &change.radial,
            &mut change.target,
            &mut change.variance_rows[start..end],
        );
        change.rows_drawn = end;
        work
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

    /// Once the new amplitudes and what follows from them are drawn, puts the blend in a form
    /// a step evaluates in a few operations a point: per point the smaller side's energy
    /// relative to the larger one's, the reference r, c = |h0_new|²/|r|² (sign bit clear)
    /// where r is the old amplitude and −|h0_old|²/|r|² (sign bit set, −0 for a wave the old
    /// sea lacks) where it is the new one. The amplitudes themselves are kept as they are.
    pub(crate) fn form_change(&mut self) {
        let n = self.n;
        let change = &mut self.change;
        if !change.active || change.drawn.is_none() || change.formed {
            return;
        }
        let AmplitudeChange {
            from, target, coef, ..
        } = change;
        coef.par_chunks_mut(n)
            .zip(from.par_chunks(n).zip(target.par_chunks(n)))
            .for_each(|(coef, (from, target))| {
                for ((c, &a), &b) in coef.iter_mut().zip(from).zip(target) {
                    *c = reference_coef(a, b);
                }
            });
        change.formed = true;
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
    /// `w` in [0, 1] on the new (all drawn, the blend formed): every wave keeps its phase (old
    /// and new share their random draw) and |h0|² = (1 − w)|h0_old|² + w|h0_new|², so the
    /// variance, the mean level and every second moment move linearly from the old sea's to
    /// the new sea's. The result depends on `w` alone, whatever weights came before: at w ≤ 0
    /// the old amplitudes and their statistics come back exactly; at w = 1 the new ones are
    /// installed exactly, with everything `Cascade::new` derives from them, and the change
    /// ends: the cascade is then the one `Cascade::new` builds for the new spectrum. In
    /// between, h0 = r·√((1 − w)·c_old + w·c_new) with the reference r and the coefficients of
    /// [`form_change`](Self::form_change). Allocates nothing.
    pub(crate) fn blend_change(&mut self, w: f64) {
        let n = self.n;
        let Some(drawn) = self.change.drawn else {
            return;
        };
        if !self.change.formed {
            return;
        }
        let from_stats = self.change.from_stats.unwrap_or(drawn.stats);
        let (stats, class) = if w >= 1.0 {
            self.h0.copy_from_slice(&self.change.target);
            self.amplitude_bound = drawn.amplitude_bound;
            self.loop_error = drawn.loop_error;
            self.change.active = false;
            (drawn.stats, 2)
        } else if w <= 0.0 {
            self.h0.copy_from_slice(&self.change.from);
            self.amplitude_bound = self.change.from_bound;
            (from_stats, 0)
        } else {
            let (old, new) = ((1.0 - w) as f32, w as f32);
            let AmplitudeChange {
                from,
                target,
                coef,
                band_rows,
                ..
            } = &self.change;
            self.h0
                .par_chunks_mut(n)
                .zip(from.par_chunks(n).zip(target.par_chunks(n)))
                .zip(coef.par_chunks(n))
                .enumerate()
                // Rows without a wave vector of the band are zero on both sides.
                .filter(|(j, _)| band_rows[*j] > 0)
                .for_each(|(_, ((h0, (from, target)), coef))| {
                    for (((h, &a), &b), &c) in h0.iter_mut().zip(from).zip(target).zip(coef) {
                        // The sign bit says which side is the reference (−0 for a new wave).
                        let (r, c_old, c_new) = if c.is_sign_negative() {
                            (b, -c, 1.0)
                        } else {
                            (a, 1.0, c)
                        };
                        *h = r * (old * c_old + new * c_new).sqrt();
                    }
                });
            // The blend of two bounds is within their larger (each |h0| is).
            self.amplitude_bound = self.change.from_bound.max(drawn.amplitude_bound);
            (from_stats.blend(&drawn.stats, w), 1)
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

/// The blend's coefficient of an old amplitude `a` and a new one `b` (which share their
/// phase: the same random draw times two non-negative reals): the smaller one's energy
/// relative to the larger one's, negative when the larger is the new one (see
/// [`Cascade::form_change`]).
fn reference_coef(a: Complex32, b: Complex32) -> f32 {
    let (na, nb) = (f64::from(a.norm_sqr()), f64::from(b.norm_sqr()));
    if na == 0.0 && nb == 0.0 {
        0.0
    } else if na >= nb {
        (nb / na) as f32
    } else {
        -(na / nb) as f32
    }
}

/// The end of the radial table's rows that one call of [`Cascade::draw_change`] fills from
/// row `start` (of `0..=half`) with `budget`.
fn radial_end(start: usize, half: usize, budget: usize) -> usize {
    let mut end = start;
    while end <= half && (end == start || radial_cost(start, end) < budget) {
        end += 1;
    }
    end
}

/// The work of the radial table's rows `start..end`: row a holds a + 1 lengths.
fn radial_cost(start: usize, end: usize) -> usize {
    (end * (end + 1) / 2 - start * (start + 1) / 2) * RADIAL_COST
}

/// The end of the grid rows that one call of [`Cascade::draw_change`] draws from row `start`
/// with `budget`, and their wave vectors of the band.
fn rows_end(band_rows: &[u32], start: usize, budget: usize) -> (usize, usize) {
    let mut end = start;
    let mut work = 0usize;
    while end < band_rows.len() && (end == start || work < budget) {
        work += band_rows[end] as usize;
        end += 1;
    }
    (end, work)
}
