//! The wake window's state and its ticks: linear free-surface waves on an N×N grid, each
//! Fourier mode advanced exactly over a tick by the ocean's dispersion with the hulls'
//! pressure held at its value at the tick's middle, an absorbing border applied in physical
//! space, and the moves of the window by whole cells. See docs/theory.md, "Wakes".
//!
//! State: the elevation η on the grid (physical space, after the border's damping) and the
//! scaled surface potential ψ̂(k) = ϕ̂(k)·k tanh(kh)/ω(k) in wave-number space (η's units).
//! With the pressure head P = p/(ρg) held over a tick of length τ, each mode rotates about
//! its equilibrium η* = −G(k)·P̂(k), G = g/(g + (σ/ρ)k²) (1 without surface tension):
//!
//! ```text
//! η̂' = η* + cos(ωτ)(η̂ − η*) + sin(ωτ) ψ̂
//! ψ̂' =    − sin(ωτ)(η̂ − η*) + cos(ωτ) ψ̂
//! ```

use num_complex::Complex32;
use rayon::prelude::*;

use super::bump;
use super::config::{Hull, WakeConfig};
use super::fft::Fft;
use super::foam::{crest_tick, hull_row, shift_grid, TrailClock};
use super::window::Wakes;
use crate::error::{self, Error};
use crate::math::determinism::{with_math, Determinism, Math};
use crate::math::fft2d::ROWS_PER_TASK;
use crate::math::grid::wave_index;
use crate::spectrum::dispersion::{Dispersion, GRAVITY, SURFACE_TENSION, WATER_DENSITY};

/// A hull as placed by `set_hulls`, with its heading's unit vector.
#[derive(Debug, Clone, Copy)]
struct Placed {
    hull: Hull,
    /// (cos θ, sin θ) of the heading.
    bow: [f32; 2],
    /// Radius in metres of the circle around the centre that holds the waterplane.
    radius: f32,
}

/// The wake layer's simulation (its public face is [`Wakes`], the buffers it writes).
#[derive(Debug, Clone)]
pub(crate) struct WakeSim {
    n: usize,
    spacing: f64,
    substep: f64,
    fft: Fft,
    /// η in physical space (`[z][x]`, the real parts), between ticks; the pressure head is
    /// written into the imaginary parts at the start of a tick.
    field: Vec<Complex32>,
    /// The transforms' other buffer.
    work: Vec<Complex32>,
    /// ψ̂ in wave-number space, transposed (`[k_x][k_z]`), normalised (its unnormalised
    /// inverse transform is ψ).
    psi: Vec<Complex32>,
    /// Per mode (|m_x|, |m_z|), (N/2 + 1)² of them (a mode's rotation depends on |k| alone):
    /// cos ωτ, sin ωτ, (1 − cos ωτ)·G, sin ωτ·G; all zero for the mean and the Nyquist
    /// row and column.
    modes: Vec<[f32; 4]>,
    /// Per index along an axis: the border's damping factor over one tick.
    sponge: Vec<f32>,
    /// Per index along an axis: the weight of the wake in the queries (0 at the edges).
    fade: Vec<f32>,
    /// The hulls' pressure head p/(ρg) in metres at the last tick's middle (`[z][x]`): the
    /// static dip the crests of the foam are measured from.
    head: Vec<f32>,
    /// Whether `head` holds anything (a hull pressed at the last tick).
    pressed: bool,
    /// The foam trail's coverage in [0, 1] (`[z][x]`), and room for its moves.
    foam: Vec<f32>,
    foam_work: Vec<f32>,
    clock: TrailClock,
    hulls: Vec<Placed>,
    /// Simulated time in seconds at which the hulls were at their positions.
    hull_time: f64,
    /// Cell indices (x, z) of sample (0, 0).
    origin: [i64; 2],
    /// Ticks done: the state stands for the time `ticks · substep`.
    ticks: i64,
}

impl WakeSim {
    /// A still window of `config` centred on the world origin, with `dispersion`, at time
    /// `time` (s), its foam lasting `foam_lifetime` s (> 0).
    pub(crate) fn new(
        config: &WakeConfig,
        dispersion: Dispersion,
        determinism: Determinism,
        time: f64,
        foam_lifetime: f32,
    ) -> Result<WakeSim, Error> {
        config.validate()?;
        let n = config.size;
        let zero = Complex32::default();
        let spacing = f64::from(config.spacing);
        let substep = f64::from(config.substep);
        let modes = with_math!(determinism, M => mode_table::<M>(n, spacing, substep, dispersion))?;
        let border = config.border_cells();
        let (sponge, fade) = with_math!(determinism, M => border_tables::<M>(
            n, border, f64::from(config.damping) * substep
        ));
        let mut sim = WakeSim {
            n,
            spacing,
            substep,
            fft: Fft::new(n, determinism)?,
            field: error::try_vec(n * n, zero)?,
            work: error::try_vec(n * n, zero)?,
            psi: error::try_vec(n * n, zero)?,
            modes,
            sponge,
            fade,
            head: error::try_vec(n * n, 0.0)?,
            pressed: false,
            foam: error::try_vec(n * n, 0.0)?,
            foam_work: error::try_vec(n * n, 0.0)?,
            clock: TrailClock::new(substep, foam_lifetime, determinism),
            hulls: Vec::with_capacity(WakeConfig::MAX_HULLS),
            hull_time: time,
            origin: [0; 2],
            ticks: 0,
        };
        sim.origin = sim.origin_for(0.0, 0.0);
        sim.jump(time);
        Ok(sim)
    }

    /// The cell indices of sample (0, 0) of a window centred on (x, z) (m).
    fn origin_for(&self, x: f64, z: f64) -> [i64; 2] {
        let half = (self.n / 2) as i64;
        [x, z].map(|v| (v / self.spacing).round() as i64 - half)
    }

    /// An empty output window of this simulation's grid.
    pub(crate) fn new_output(&self) -> Result<Wakes, Error> {
        Wakes::new(self.n, self.spacing)
    }

    /// Places `hulls` (checked) at the time `time` (s); they press on the water from the
    /// next tick on. Allocates nothing.
    pub(crate) fn set_hulls(&mut self, hulls: &[Hull], time: f64, determinism: Determinism) {
        self.hulls.clear();
        self.hulls.extend(hulls.iter().map(|&hull| {
            let (sin, cos) = with_math!(determinism, M => M::sin_cos(f64::from(hull.heading)));
            Placed {
                hull,
                bow: [cos as f32, sin as f32],
                radius: 0.5 * (hull.length * hull.length + hull.beam * hull.beam).sqrt(),
            }
        }));
        self.hull_time = time;
    }

    /// Sets the foam trail's lifetime to `seconds` (> 0); the foam on the water is kept.
    pub(crate) fn set_foam_lifetime(&mut self, seconds: f32, determinism: Determinism) {
        self.clock = TrailClock::new(self.substep, seconds, determinism);
    }

    /// The tick whose start is the last at or before time `t` (s).
    fn tick_at(&self, t: f64) -> i64 {
        (t / self.substep).floor() as i64
    }

    /// Advances the waves to time `t` (s): every tick that ends at or before `t`.
    pub(crate) fn advance(&mut self, t: f64) {
        let target = self.tick_at(t);
        while self.ticks < target {
            self.tick(self.ticks);
            self.ticks += 1;
        }
    }

    /// A jump to time `t` (s) with no history: the waves are kept as they are.
    pub(crate) fn jump(&mut self, t: f64) {
        self.ticks = self.tick_at(t);
    }

    /// Tick `index`: from `index·τ` to `(index + 1)·τ`.
    fn tick(&mut self, index: i64) {
        let n = self.n;
        let middle = (index as f64 + 0.5) * self.substep;
        self.press(middle);
        self.fft.run(false, &mut self.field, &mut self.work);
        // The modes: η̂ and the pressure head P̂ unpacked from the transform of η + iP (each
        // the Hermitian part of a real field), then rotated with ψ̂.
        let scale = 0.5 / (n * n) as f32;
        let (work, modes) = (&self.work, &self.modes);
        let half = n / 2 + 1;
        self.field
            .par_chunks_mut(n)
            .zip(self.psi.par_chunks_mut(n))
            .enumerate()
            .with_min_len(ROWS_PER_TASK)
            .for_each(|(a, (out, psi))| {
                let row = &work[a * n..(a + 1) * n];
                let mirror = &work[((n - a) % n) * n..][..n];
                let modes = &modes[a.min(n - a) * half..][..half];
                // Mode b's mirror is n − b (0's is 0), its table entry min(b, n − b): in
                // straight slices, without an index computed per mode.
                let mirrors = std::iter::once(&mirror[0]).chain(mirror[1..].iter().rev());
                let entries = modes[..=n / 2].iter().chain(modes[1..n / 2].iter().rev());
                let cells = out.iter_mut().zip(psi.iter_mut()).zip(row);
                for (((out, psi), &f), (&m, &[c, s, g1, g2])) in cells.zip(mirrors.zip(entries)) {
                    let m = m.conj();
                    let eta = (f + m) * scale;
                    let d = f - m;
                    let head = Complex32::new(d.im, -d.re) * scale;
                    let p = *psi;
                    *out = eta * c + p * s - head * g1;
                    *psi = p * c - eta * s - head * g2;
                }
            });
        self.fft.inverse_real(&mut self.field, &mut self.work);
        // The field's rows out of their pairs, with the absorbing border (the imaginary
        // parts cleared for the next pressure).
        let sponge = &self.sponge;
        self.field
            .par_chunks_mut(2 * n)
            .zip(self.work.par_chunks(n))
            .zip(sponge.par_chunks(2))
            .with_min_len(ROWS_PER_TASK / 2)
            .for_each(|((rows, pair), sz)| {
                let (even, odd) = rows.split_at_mut(n);
                let cells = even.iter_mut().zip(odd.iter_mut()).zip(pair).zip(sponge);
                for (((even, odd), value), &sx) in cells {
                    *even = Complex32::new(value.re * (sx * sz[0]), 0.0);
                    *odd = Complex32::new(value.im * (sx * sz[1]), 0.0);
                }
            });
        crest_tick(
            &mut self.foam,
            &self.field,
            &self.head,
            n,
            self.spacing,
            self.clock,
        );
    }

    /// Writes the hulls' pressure head p/(ρg) in metres at time `t` (s) into the imaginary
    /// parts of the field (which are zero) and into `head`, and their bow and stern foam
    /// over the tick into the trail.
    fn press(&mut self, t: f64) {
        if self.hulls.is_empty() && !self.pressed {
            return;
        }
        self.pressed = !self.hulls.is_empty();
        let (n, spacing, origin) = (self.n, self.spacing, self.origin);
        let (hulls, since, tick) = (&self.hulls, t - self.hull_time, self.clock.tick);
        let first_x = origin[0] as f64 * spacing;
        self.field
            .par_chunks_mut(n)
            .zip(self.head.par_chunks_mut(n))
            .zip(self.foam.par_chunks_mut(n))
            .enumerate()
            .with_min_len(ROWS_PER_TASK)
            .for_each(|(j, ((row, heads), foam))| {
                heads.fill(0.0);
                let z = (origin[1] + j as i64) as f64 * spacing;
                for placed in hulls {
                    let hull = &placed.hull;
                    let cx = hull.position[0] + f64::from(hull.velocity[0]) * since;
                    let cz = hull.position[1] + f64::from(hull.velocity[1]) * since;
                    let [vx, vz] = hull.velocity;
                    hull_row(
                        foam,
                        z,
                        first_x,
                        spacing,
                        [cx, cz],
                        placed.bow,
                        [hull.length, hull.beam, hull.draft],
                        (vx * vx + vz * vz).sqrt(),
                        tick,
                    );
                    let dz = (z - cz) as f32;
                    let r = placed.radius;
                    if dz.abs() > r {
                        continue;
                    }
                    let first = ((cx - f64::from(r)) / spacing).ceil() as i64 - origin[0];
                    let last = ((cx + f64::from(r)) / spacing).floor() as i64 - origin[0];
                    let first = first.clamp(0, n as i64) as usize;
                    let last = (last + 1).clamp(0, n as i64) as usize;
                    let [cos, sin] = placed.bow;
                    let (half_l, half_b) = (2.0 / hull.length, 2.0 / hull.beam);
                    let cells = row.iter_mut().zip(heads.iter_mut());
                    for (i, (value, head)) in cells.enumerate().take(last).skip(first) {
                        let x = (origin[0] + i as i64) as f64 * spacing;
                        let dx = (x - cx) as f32;
                        let u = (dx * cos + dz * sin) * half_l;
                        let v = (dz * cos - dx * sin) * half_b;
                        let pressure = hull.draft * bump(u) * bump(v);
                        value.im += pressure;
                        *head += pressure;
                    }
                }
            });
    }

    /// Moves the window so that it is centred on (x, z) (m, checked finite), by whole cells;
    /// keeps the waves it still covers, still water where it is new. Returns whether it
    /// moved.
    pub(crate) fn move_to(&mut self, x: f64, z: f64) -> bool {
        let origin = self.origin_for(x, z);
        let shift = [origin[0] - self.origin[0], origin[1] - self.origin[1]];
        if shift == [0, 0] {
            return false;
        }
        self.origin = origin;
        let n = self.n;
        let scale = 1.0 / (n * n) as f32;
        shift_grid(&self.field, &mut self.work, n, shift, real);
        std::mem::swap(&mut self.field, &mut self.work);
        shift_grid(&self.foam, &mut self.foam_work, n, shift, |v| v);
        std::mem::swap(&mut self.foam, &mut self.foam_work);
        // ψ to physical space, moved, and back.
        self.work.copy_from_slice(&self.psi);
        self.fft.run(true, &mut self.work, &mut self.psi);
        shift_grid(&self.psi, &mut self.work, n, shift, real);
        self.fft.run(false, &mut self.work, &mut self.psi);
        self.psi.par_iter_mut().for_each(|value| *value *= scale);
        true
    }

    /// Writes what the queries read (the faded height, its slope and foam, the origin and
    /// the time `time` (s)) into `out`. Allocates nothing.
    pub(crate) fn write(&self, out: &mut Wakes, time: f64) {
        let n = self.n;
        out.origin = self.origin.map(|cell| cell as f64 * self.spacing);
        out.time = time;
        let (field, fade) = (&self.field, &self.fade);
        let trail = &self.foam;
        // The faded height and foam, row by row (loops the compiler vectorises).
        out.height
            .par_chunks_mut(n)
            .zip(out.foam.par_chunks_mut(n))
            .enumerate()
            .with_min_len(ROWS_PER_TASK)
            .for_each(|(j, (heights, foams))| {
                let (row, trail, fj) = (&field[j * n..][..n], &trail[j * n..][..n], fade[j]);
                for ((h, value), &f) in heights.iter_mut().zip(row).zip(fade) {
                    *h = value.re * (f * fj);
                }
                for ((foam, &value), &f) in foams.iter_mut().zip(trail).zip(fade) {
                    *foam = value * (f * fj);
                }
            });
        // Central differences of the faded height, 0 outside the grid.
        let per = (0.5 / self.spacing) as f32;
        let height = &out.height;
        out.slope
            .par_chunks_mut(n)
            .enumerate()
            .with_min_len(ROWS_PER_TASK)
            .for_each(|(j, slopes)| {
                let row = &height[j * n..][..n];
                let down = j.checked_sub(1).map(|d| &height[d * n..][..n]);
                let up = (j + 1 < n).then(|| &height[(j + 1) * n..][..n]);
                // The window has at least 16 samples a side.
                slopes[0][0] = (row[1] - 0.0) * per;
                slopes[n - 1][0] = (0.0 - row[n - 2]) * per;
                let inner = slopes[1..n - 1]
                    .iter_mut()
                    .zip(&row[2..])
                    .zip(&row[..n - 2]);
                for ((slope, &right), &left) in inner {
                    slope[0] = (right - left) * per;
                }
                match (down, up) {
                    (Some(down), Some(up)) => {
                        for ((slope, &u), &d) in slopes.iter_mut().zip(up).zip(down) {
                            slope[1] = (u - d) * per;
                        }
                    }
                    (None, Some(up)) => {
                        for (slope, &u) in slopes.iter_mut().zip(up) {
                            slope[1] = (u - 0.0) * per;
                        }
                    }
                    (Some(down), None) => {
                        for (slope, &d) in slopes.iter_mut().zip(down) {
                            slope[1] = (0.0 - d) * per;
                        }
                    }
                    (None, None) => {}
                }
            });
    }
}

/// A field value's real part, as a complex number (the shifted fields are real).
fn real(v: Complex32) -> Complex32 {
    Complex32::new(v.re, 0.0)
}

/// The rotation of each mode (|m_x|, |m_z|) over a tick of `substep` s (see
/// [`WakeSim::modes`]).
fn mode_table<M: Math>(
    n: usize,
    spacing: f64,
    substep: f64,
    dispersion: Dispersion,
) -> Result<Vec<[f32; 4]>, Error> {
    let dk = std::f64::consts::TAU / (n as f64 * spacing);
    let nyquist = -((n / 2) as i32);
    let half = n / 2 + 1;
    let mut modes = error::try_vec(half * half, [0.0f32; 4])?;
    let g = f64::from(GRAVITY);
    let tension = f64::from(SURFACE_TENSION) / f64::from(WATER_DENSITY);
    for (a, row) in modes.chunks_mut(half).enumerate() {
        let mx = wave_index(a, n);
        for (b, mode) in row.iter_mut().enumerate() {
            let mz = wave_index(b, n);
            if mx == nyquist || mz == nyquist || (mx == 0 && mz == 0) {
                continue;
            }
            let (kx, kz) = (f64::from(mx) * dk, f64::from(mz) * dk);
            let k = (kx * kx + kz * kz).sqrt();
            let omega = dispersion.omega_with::<M>(k);
            let (s, c) = M::sin_cos(omega * substep);
            let gain = match dispersion {
                Dispersion::Capillary { .. } => g / (g + tension * k * k),
                _ => 1.0,
            };
            *mode = [c, s, (1.0 - c) * gain, s * gain].map(|v| v as f32);
        }
    }
    Ok(modes)
}

/// The border's damping factor over one tick and the queries' fade, per index along an axis,
/// for a border of `border` cells and a damping of `rate_tick` (damping rate · tick) at the
/// edge.
fn border_tables<M: Math>(n: usize, border: usize, rate_tick: f64) -> (Vec<f32>, Vec<f32>) {
    let depth = |i: usize| {
        let w = border as f64;
        let from_low = w - i as f64;
        let from_high = i as f64 - (n - 1) as f64 + w;
        (from_low.max(from_high) / w).clamp(0.0, 1.0)
    };
    let sponge = (0..n)
        .map(|i| M::exp(-rate_tick * depth(i) * depth(i)) as f32)
        .collect();
    let fade = (0..n)
        .map(|i| {
            let t = ((1.0 - depth(i)) * 2.0).min(1.0);
            (t * t * (3.0 - 2.0 * t)) as f32
        })
        .collect();
    (sponge, fade)
}
