//! The second stage of the data flow, from a spectrum to waves: one N×N patch of ocean, h0(k)
//! made once, h̃(k, t) evolved and turned into eight real fields by four packed complex inverse
//! FFTs on every [`Cascade::update`]. The foam, the world queries and the GPU upload read those
//! fields.

mod config;
mod evolve;
mod field;
mod inspect;
mod live;
mod outputs;
mod second_order;
mod tables;
#[cfg(test)]
mod tests;
mod update;

use std::f64::consts::TAU;
use std::ops::Bound::Included;

use num_complex::Complex32;

use crate::error::{self, Error};
use crate::math::determinism::{Determinism, Libm, Math, Std};
use crate::math::fft2d::{RowFft, TILE};
use crate::math::grid::{self, wave_index};
use crate::math::simd::Simd;
use crate::spectrum::{SlopeVariance, Spectrum};

pub(crate) use config::check_band;
#[cfg(feature = "serde")]
pub(crate) use config::default_memory_limit;

pub use config::CascadeConfig;
pub use field::Field;

pub use tables::LoopError;
use tables::{check_amplitude, Amplitudes, EvolutionTable};
use update::{RowPruning, Tasks};

/// One N×N patch of ocean surface of side L: the wave amplitudes h0(k) drawn once from a
/// [`Spectrum`], and after every [`Cascade::update`] the height, horizontal displacement,
/// slope, normal and Jacobian of the surface at time t.
///
/// Buffers are row-major with z as the row: sample (i, j) at x = i·L/N, z = j·L/N is at
/// index `j * N + i`.
///
/// ```
/// use ocean_fft::{Cascade, CascadeConfig, Spectrum};
/// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
/// let config = CascadeConfig { size: 64, length: 250.0, ..CascadeConfig::default() };
/// let mut cascade = Cascade::new(&spectrum, config)?;
/// cascade.update(12.5)?;                          // t in seconds
/// let eta = cascade.height()[3 * 64 + 5];        // m, at x = 5·L/N, z = 3·L/N
/// assert!(eta.is_finite());
/// # Ok::<(), ocean_fft::Error>(())
/// ```
///
/// `Clone` copies every table and buffer ([`CascadeConfig::memory_bytes`], about 123·N²
/// bytes): the copy updates to the same bits as the original.
#[derive(Clone)]
pub struct Cascade {
    config: CascadeConfig,
    n: usize,
    dk: f32,
    time: f64,
    expected_variance: f64,
    /// Σ 2|h0| · max(1, k_grid_max): a bound on every synthesised field's magnitude.
    amplitude_bound: f64,
    /// How far looping moved the frequencies (None without a repeat period).
    loop_error: Option<LoopError>,
    /// 2 Σ |k| |h0(k)|² in m: the mean-level correction per unit choppiness.
    mean_level: f64,
    /// The correction in m the buffers were last computed with (λ · `mean_level`).
    mean_level_offset: f32,
    /// Slope variance the spectrum holds above this cascade's band (to the cut-off).
    subgrid_slope: SlopeVariance,
    h0: Vec<Complex32>,
    /// Evolution table, transposed layout: rows are k_x index i in 0..N/2, columns k_z
    /// index j.
    evolution: EvolutionTable,
    /// k_z = Δk·m(j) of spectral column j.
    kz: Vec<f32>,
    rows: RowFft,
    /// The SIMD level of the element loops (the widest the CPU has; the tests force each).
    simd: Simd,
    tasks: Tasks,
    /// Band pruning, per table row i in 0..N/2: which evolution blocks hold no wave.
    pruning: Vec<RowPruning>,
    /// Row pairs 1..=`live_pairs` are evolved and transformed; the pairs beyond hold no wave
    /// (p = q = 0 in their whole table row), so their spectral rows stay zero from
    /// construction on and pass 2 writes zeros for them without reading them.
    live_pairs: usize,
    /// Pass-1 buffer, layout `[i][transform][j]` (k_x row, k_z column → after the FFT, z).
    spectral: Vec<Complex32>,
    /// Pass-2 block buffers, one per pass-2 task, each
    /// [`ROWS_PER_TASK`](crate::math::fft2d::ROWS_PER_TASK) rows of layout `[j][transform][i]` (z
    /// row, x column) once transformed.
    blocks: Vec<Complex32>,
    /// FFT scratch, one slot per task of the pass running (the passes run one after the
    /// other and share it).
    scratch: Vec<Complex32>,
    height: Vec<f32>,
    displacement: Vec<[f32; 2]>,
    slope: Vec<[f32; 2]>,
    normal: Vec<[f32; 3]>,
    jacobian: Vec<f32>,
    /// A live change of amplitudes (empty buffers until the first).
    change: live::AmplitudeChange,
    /// Second-order bound waves, when enabled (see `OceanConfig::second_order`).
    second_order: Option<Box<second_order::SecondOrder>>,
}

impl std::fmt::Debug for Cascade {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Cascade")
            .field("config", &self.config)
            .field("time", &self.time)
            .field("expected_variance", &self.expected_variance)
            .finish_non_exhaustive()
    }
}

/// Most cascades an ocean sums ([`OceanConfig::MAX_CASCADES`](crate::OceanConfig::MAX_CASCADES)):
/// the length of the arrays that hold one entry per cascade.
pub(crate) const MAX_CASCADES: usize = 8;

/// Number of packed complex transforms per update.
const TRANSFORMS: usize = 4;

/// Values between the starts of two rows of the pass-1 buffer and of a pass-2 block: the
/// row's four transforms and one cache line of padding. Without it rows lie a power of two
/// of bytes apart (32·N), so the lines a transpose tile reads or writes at once, one per
/// row, all fall into the same cache set and evict each other.
pub(crate) fn row_stride(n: usize) -> usize {
    (TRANSFORMS * n).saturating_add(TILE)
}

/// Bytes the second-order state of an N grid holds at most.
pub(crate) fn second_order_memory_bytes(n: usize) -> usize {
    second_order::SecondOrder::memory_bytes(n)
}

/// Checks a simulation time `name`: finite, |t| ≤ [`Cascade::MAX_TIME`].
pub(crate) fn check_time(name: &'static str, t: f64) -> Result<f64, Error> {
    error::in_range_f64(
        name,
        t,
        Included(-Cascade::MAX_TIME),
        Included(Cascade::MAX_TIME),
    )
}

/// Bytes a cascade of size `n` holds: its buffers, tables, FFT plan and scratch (planned
/// for a valid size; for larger ones the scratch is estimated at N per task).
pub(crate) fn memory_bytes(n: usize, determinism: Determinism) -> usize {
    let points = n.saturating_mul(n);
    let complex = std::mem::size_of::<Complex32>();
    let scratch_len = if n <= grid::MAX_SIZE {
        RowFft::new(n, determinism).scratch_len()
    } else {
        n
    };
    let tasks = Tasks::new(n);
    let per_point = [
        complex,            // h0
        4 + 2 * 8 + 12 + 4, // height, displacement, slope, normal, jacobian
    ];
    let spectral = n.saturating_mul(row_stride(n)).saturating_mul(complex);
    let evolution_entry = 4 * 4 + 8 + 4; // p, q, freq, 1/|k|, for half the points
    let pruning = std::mem::size_of::<RowPruning>();
    let tables = (points / 2)
        .saturating_mul(evolution_entry)
        .saturating_add(n.saturating_mul(4 + pruning));
    let scratch = tasks
        .scratch_slots()
        .saturating_mul(scratch_len)
        .saturating_mul(complex);
    let blocks = tasks.block_values(n).saturating_mul(complex);
    per_point.iter().fold(
        tables
            .saturating_add(scratch)
            .saturating_add(blocks)
            .saturating_add(spectral),
        |sum, &bytes| sum.saturating_add(points.saturating_mul(bytes)),
    )
}

/// 2 Σ_k |k| |h0(k)|² in m over the grid's wave vectors (h0 in FFT order, index j·N + i at
/// k = Δk·(m(i), m(j))): the time-averaged Σ_k |k| |h̃(k, t)|², since |h̃(k)|² averages to
/// |h0(k)|² + |h0(−k)|².
pub(super) fn mean_level_per_choppiness<M: Math>(h0: &[Complex32], n: usize, dk: f64) -> f64 {
    let mut sum = 0.0;
    for j in 0..n {
        let kz = f64::from(wave_index(j, n)) * dk;
        for i in 0..n {
            let kx = f64::from(wave_index(i, n)) * dk;
            let h = h0[j * n + i];
            if h.re == 0.0 && h.im == 0.0 {
                // Adds nothing (skipped: most of a band-limited grid).
                continue;
            }
            // In f64: |h0|² of an extreme (but accepted) spectrum can overflow f32, while
            // λ Σ|k||h0|² stays below the square of the amplitude bound (≤ 1e30).
            let (re, im) = (f64::from(h.re), f64::from(h.im));
            sum += M::hypot(kx, kz) * (re * re + im * im);
        }
    }
    2.0 * sum
}

impl Cascade {
    /// Largest |t| accepted by [`Cascade::update`], in seconds (about 31.7 years). Up to here
    /// the f64 phase ω·t keeps an error below 1e-5 rad.
    pub const MAX_TIME: f64 = 1e9;

    /// Largest bound on the fields' magnitude that [`Cascade::new`] accepts (see
    /// [`Error::AmplitudeTooLarge`]): far enough below f32::MAX that squares and cross
    /// products of the fields stay finite.
    pub const MAX_AMPLITUDE: f64 = tables::AMPLITUDE_LIMIT;

    /// Draws h0(k) = ½(ξ_r + iξ_i)·√S(k)·Δk for every wave vector of the grid with
    /// `k_min` ≤ |k| < `k_max` (zero elsewhere, and on k = 0 and the Nyquist row and column),
    /// ξ standard normals drawn from (seed, m_x, m_z); tabulates ω(k) of the spectrum's
    /// dispersion; allocates every buffer the updates use. The fields are those of t = 0.
    ///
    /// # Errors
    /// Those of [`CascadeConfig::validate`]; [`Error::EmptyBand`] if the band holds no wave
    /// vector of the grid; [`Error::AmplitudeTooLarge`] if the spectrum is so strong at this
    /// grid and choppiness that the fields could overflow f32; [`Error::OutOfMemory`] if the
    /// system refuses an allocation.
    pub fn new(spectrum: &Spectrum, config: CascadeConfig) -> Result<Cascade, Error> {
        config.validate()?;
        match config.determinism {
            Determinism::SameMachine => Self::new_with::<Std>(spectrum, config),
            Determinism::CrossPlatform => Self::new_with::<Libm>(spectrum, config),
        }
    }

    /// [`Cascade::new`] for a checked config, with the functions of its determinism mode.
    fn new_with<M: Math>(spectrum: &Spectrum, config: CascadeConfig) -> Result<Cascade, Error> {
        let n = config.size;
        let dk64 = TAU / f64::from(config.length);
        let dk = dk64 as f32;
        let Amplitudes {
            h0,
            expected_variance,
            amplitude_bound,
        } = Amplitudes::draw::<M>(spectrum, &config)?;
        check_amplitude(amplitude_bound, config.choppiness)?;
        let looping = config.repeat_period.map(f64::from);
        let evolution = EvolutionTable::new::<M>(&h0, n, dk64, spectrum.dispersion(), looping);
        let loop_error =
            looping.map(|period| LoopError::new::<M>(&h0, n, dk64, spectrum.dispersion(), period));
        let kz = (0..n).map(|j| wave_index(j, n) as f32 * dk).collect();
        let mean_level = mean_level_per_choppiness::<M>(&h0, n, dk64);
        let nyquist = std::f64::consts::PI * n as f64 / f64::from(config.length);
        let band_top = f64::from(config.k_max).min(nyquist);
        let subgrid_slope =
            spectrum.slope_variance_with::<M>(band_top, f64::from(SlopeVariance::DEFAULT_CUTOFF));
        let rows = RowFft::new(n, config.determinism);
        let tasks = Tasks::new(n);
        let pruning = RowPruning::of(&evolution, n);
        let live_pairs = (1..n / 2).rev().find(|&i| !pruning[i].empty).unwrap_or(0);
        let points = n * n;
        let mut cascade = Cascade {
            config,
            n,
            dk,
            time: 0.0,
            expected_variance,
            amplitude_bound,
            loop_error,
            mean_level,
            mean_level_offset: 0.0,
            subgrid_slope,
            h0,
            evolution,
            kz,
            spectral: error::try_vec(n * row_stride(n), Complex32::default())?,
            blocks: error::try_vec(tasks.block_values(n), Complex32::default())?,
            scratch: error::try_vec(
                tasks.scratch_slots() * rows.scratch_len(),
                Complex32::default(),
            )?,
            rows,
            simd: Simd::detect(),
            tasks,
            pruning,
            live_pairs,
            height: error::try_vec(points, 0.0)?,
            displacement: error::try_vec(points, [0.0; 2])?,
            slope: error::try_vec(points, [0.0; 2])?,
            normal: error::try_vec(points, [0.0, 1.0, 0.0])?,
            jacobian: error::try_vec(points, 1.0)?,
            change: live::AmplitudeChange::default(),
            second_order: None,
        };
        cascade.update(0.0)?;
        Ok(cascade)
    }

    /// The configuration this cascade was built with (choppiness as last set).
    pub fn config(&self) -> &CascadeConfig {
        &self.config
    }

    /// Grid size N.
    pub fn size(&self) -> usize {
        self.n
    }

    /// Side L of the patch in metres.
    pub fn length(&self) -> f32 {
        self.config.length
    }

    /// Grid spacing Δk = 2π/L of the wave vectors, in rad/m.
    pub fn delta_k(&self) -> f32 {
        self.dk
    }

    /// Time in seconds of the last [`Cascade::update`] (0 after construction).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Changes the choppiness λ (dimensionless, ≥ 0). Takes effect at the next
    /// [`Cascade::update`].
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] for a negative or non-finite
    /// `choppiness`; [`Error::AmplitudeTooLarge`] if the fields could overflow f32 at this
    /// choppiness. The choppiness is then unchanged.
    pub fn set_choppiness(&mut self, choppiness: f32) -> Result<(), Error> {
        let lambda = self.check_choppiness(choppiness)?;
        self.set_choppiness_checked(lambda);
        Ok(())
    }

    /// Sets a choppiness [`Cascade::check_choppiness`] accepted.
    pub(crate) fn set_choppiness_checked(&mut self, choppiness: f32) {
        self.config.choppiness = choppiness;
    }

    /// The checks of [`Cascade::set_choppiness`] without the change.
    pub(crate) fn check_choppiness(&self, choppiness: f32) -> Result<f32, Error> {
        let lambda = error::non_negative("choppiness", choppiness)?;
        check_amplitude(self.amplitude_bound, lambda)?;
        Ok(lambda)
    }

    /// How far the repeat period moved the waves' frequencies from the dispersion relation
    /// (`None` without one): every ω becomes the nearest whole number of cycles per loop, at
    /// least one, so waves longer than the loop speed up and none stands still.
    pub fn loop_error(&self) -> Option<LoopError> {
        self.loop_error
    }

    /// Expected variance of η in m²: Σ S(k) Δk² over the wave vectors of the grid in the
    /// band. 16 times this is the expected square of the simulated H_s.
    pub fn expected_variance(&self) -> f64 {
        self.expected_variance
    }

    /// The mean-level correction in metres that the last update added to every height:
    /// λ · 2 Σ_k |k| |h0(k)|², the time average of λ Σ_k |k| |h̃(k, t)|².
    ///
    /// Horizontal displacement moves water toward the crests (J < 1 there), so without it
    /// the Eulerian mean of the displaced surface, the mean of η·J over the undisplaced grid,
    /// would sit λ ∫ k S(k) d²k below still water (Nouguier, Guérin & Chapron 2009; the
    /// mean-level term of Guérin et al.'s 2019 improved choppy wave model): to first order
    /// ⟨η J⟩ = λ⟨η ∇·D⟩ = −λ Σ_k |k| |h̃(k)|², and the second-order term of J adds a third
    /// moment of a Gaussian field, zero on average. Adding this constant to η puts the
    /// mean water level back at y = 0 for any λ; it is 0 at λ = 0. The height buffer, the
    /// texels and vertices packed from it and every world query include it. See
    /// docs/theory.md.
    pub fn mean_level_offset(&self) -> f32 {
        self.mean_level_offset
    }

    /// Slope variance along and across the wind that the spectrum holds between the top of
    /// this cascade's band (min(`k_max`, πN/L)) and [`SlopeVariance::DEFAULT_CUTOFF`]: the
    /// slopes too short for this grid, computed once at construction by
    /// [`Spectrum::slope_variance`]. A renderer that draws this cascade and the larger ones
    /// adds it as BRDF roughness; it is the alpha channel of
    /// [`TexelLayout::Normal`](crate::gpu::TexelLayout::Normal).
    pub fn subgrid_slope_variance(&self) -> SlopeVariance {
        self.subgrid_slope
    }

    /// Height η in metres at every grid point (undisplaced positions), including the
    /// [mean-level correction](Self::mean_level_offset).
    pub fn height(&self) -> &[f32] {
        &self.height
    }

    /// Horizontal displacement λ·(D_x, D_z) in metres, as `[x, z]`: grid point x₀ moves to
    /// x₀ + this.
    pub fn displacement(&self) -> &[[f32; 2]] {
        &self.displacement
    }

    /// Slope (∂y/∂x, ∂y/∂z) of the displaced surface at each grid point's displaced position,
    /// (−n_x/n_y, −n_z/n_y) as `[x, z]`, dimensionless. n_y = J is kept at least 1e-4·|n|, so
    /// where the surface is vertical or folds (J ≤ 0) the slope stays finite (magnitude
    /// ≤ 1e4).
    pub fn slope(&self) -> &[[f32; 2]] {
        &self.slope
    }

    /// Unit normal of the displaced surface, (T_z × T_x)/|T_z × T_x|; it points down where
    /// the surface folds over itself (J < 0). `[x, y, z]`, y up.
    pub fn normal(&self) -> &[[f32; 3]] {
        &self.normal
    }

    /// Jacobian J = (1 + λD_xx)(1 + λD_zz) − λ²D_xz² of the horizontal displacement map,
    /// dimensionless: below 1 at crests, negative where the surface folds (foam).
    pub fn jacobian(&self) -> &[f32] {
        &self.jacobian
    }

    /// The initial amplitudes h0(k) in m, in the grid's FFT order (index j·N + i holds
    /// k = Δk·(m(i), m(j))).
    pub fn h0(&self) -> &[Complex32] {
        &self.h0
    }
}
