//! The simulation side of a bake: frame f's state as a pure function of the sea and f.
//!
//! Waves are a closed-form function of time, so only the foam has a history. It is made a
//! function of the frame alone by a fixed pre-roll:
//!
//! - **No loop.** Frames are grouped in blocks of K = `--anchor-every` frames; block b
//!   starts at its anchor frame a = b·K. The foam of any frame f in the block is that of an
//!   ocean pre-rolled (`OceanState::pre_roll`) over the P frames before a
//!   (P = ⌈W·fps⌉, W = (τ_A + τ_R)·ln(1/ε)) in steps of whole frames up to 0.1 s, then
//!   advanced with `step_to` to every frame time i/fps, i = a + 1, …, f. Two solutions of
//!   the foam equations with the same surface forget their difference: the active foam's
//!   at least as e^{−t/τ_A}, the residual foam's as e^{−t/τ_R} plus what the active
//!   difference feeds it (the clamp to [0, 1] and the transport do not widen it), so after
//!   W seconds the foam is within about ε of that of any longer history, in particular of
//!   an ocean simulated forever. Across an anchor the foam jumps by at most about 2ε.
//! - **Loop of F frames.** Frame f shows phase p = f mod F at time p/fps. The foam starts
//!   at zero at phase 0 and whole loops are simulated (steps to i/fps, i = 1..=F, then back
//!   to t = 0 with the foam kept) until one loop changes no foam value by more than
//!   ε·(1 − q) (or after [`Preroll::max_loops`](crate::setup::Preroll::max_loops)), where
//!   q = e^{−T/τ_R} (τ_R the slower decay) is about how much one loop contracts a difference
//!   of foam. The changes of later loops then sum to at most q·ε: the foam of phase 0 is
//!   within ε of the loop's periodic steady state, and it meets the end of the loop within
//!   q·ε(1 − q) — frame F (= frame 0) follows frame F − 1 as continuously as any two frames.

use half::f16;
use ocean_fft::gpu::TexelLayout;
use ocean_fft::{OceanSnapshot, OceanState};

use crate::error::CliError;
use crate::setup::Sea;

/// A texel component the library packs: f32
/// ([`Textures::pack`](ocean_fft::gpu::Textures::pack)) or f16
/// ([`Textures::pack_f16`](ocean_fft::gpu::Textures::pack_f16), which rounds to nearest and
/// saturates to ±65504).
pub trait Component: Copy + Default + Send + 'static {
    /// Packs cascade `cascade` of `ocean` in `layout` into `out` (N² texels).
    ///
    /// # Errors
    /// The library's, on a wrong cascade index or buffer length (a bug here).
    fn pack(
        ocean: &OceanState,
        cascade: usize,
        layout: TexelLayout,
        out: &mut [[Self; 4]],
    ) -> Result<(), ocean_fft::Error>;
}

impl Component for f32 {
    fn pack(
        ocean: &OceanState,
        cascade: usize,
        layout: TexelLayout,
        out: &mut [[f32; 4]],
    ) -> Result<(), ocean_fft::Error> {
        ocean.textures().pack(cascade, layout, out)
    }
}

impl Component for f16 {
    fn pack(
        ocean: &OceanState,
        cascade: usize,
        layout: TexelLayout,
        out: &mut [[f16; 4]],
    ) -> Result<(), ocean_fft::Error> {
        ocean.textures().pack_f16(cascade, layout, out)
    }
}

/// Every channel of one cascade at one frame, as the library packs them (texel (i, j) at
/// index j·N + i, the library's conventions), in f16 for the EXR files and f32 for the PNGs.
/// The tool decides nothing about the values: which cascade carries the foam, and how f16
/// rounds and saturates, is the library's packing.
#[derive(Debug, Clone, PartialEq)]
pub struct Texels<T> {
    /// Grid size N.
    pub size: usize,
    /// `[D_x, η, D_z, foam]` per texel ([`TexelLayout::DisplacementFoam`]: the foam is the
    /// ocean's on cascade 0 and 0 on the others).
    pub displacement_foam: Vec<[T; 4]>,
    /// `[n_x, n_y, n_z, J]` per texel: RGB of [`TexelLayout::Normal`], A the Jacobian, the A
    /// of [`TexelLayout::DisplacementJacobian`] (the normal layout's own A, the cascade's
    /// sub-grid mean-square slope σ², is one number per cascade and not baked).
    pub normal_jacobian: Vec<[T; 4]>,
}

impl<T: Component> Texels<T> {
    /// Zeroed buffers for an N×N cascade.
    pub fn new(size: usize) -> Texels<T> {
        let points = size * size;
        Texels {
            size,
            displacement_foam: vec![[T::default(); 4]; points],
            normal_jacobian: vec![[T::default(); 4]; points],
        }
    }

    /// Packs every channel of cascade `cascade` into these buffers.
    ///
    /// # Errors
    /// Only on a bug (wrong buffer sizes).
    pub fn capture(&mut self, ocean: &OceanState, cascade: usize) -> Result<(), CliError> {
        let internal =
            |e: ocean_fft::Error| CliError::new(crate::error::Kind::Internal, e.to_string());
        // The Jacobian passes through the displacement buffer, which the displacement and
        // foam then overwrite.
        let (df, nj) = (&mut self.displacement_foam, &mut self.normal_jacobian);
        T::pack(ocean, cascade, TexelLayout::DisplacementJacobian, df).map_err(internal)?;
        T::pack(ocean, cascade, TexelLayout::Normal, nj).map_err(internal)?;
        for (texel, dj) in nj.iter_mut().zip(df.iter()) {
            texel[3] = dj[3];
        }
        T::pack(ocean, cascade, TexelLayout::DisplacementFoam, df).map_err(internal)
    }
}

/// Where the simulator stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Position {
    /// Nothing simulated yet.
    Fresh,
    /// In the block anchored at frame `anchor`, at frame `frame` (no loop).
    Block { anchor: i64, frame: i64 },
    /// At phase `phase` of the loop (the steady state restored or stepped from).
    Loop { phase: i64 },
}

/// How the loop's foam converged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoopConvergence {
    /// Whole loops simulated before the steady state.
    pub loops: u32,
    /// The largest change of any foam value over the last of them.
    pub last_change: f64,
    /// A bound on the foam's jump from frame F − 1 to frame F (= frame 0): q·`last_change`,
    /// q = e^{−T/τ}.
    pub seam_bound: f64,
}

/// Steps an ocean to frames so that each frame's state depends only on the sea and the
/// frame.
pub struct Simulator<'a> {
    sea: &'a Sea,
    ocean: OceanState,
    position: Position,
    /// The loop's steady state at phase 0.
    steady: Option<OceanSnapshot>,
    /// How it converged.
    convergence: Option<LoopConvergence>,
    /// Simulation steps taken (pre-roll included).
    pub steps: u64,
}

fn internal(e: ocean_fft::Error) -> CliError {
    CliError::new(crate::error::Kind::Internal, format!("simulation: {e}"))
}

impl<'a> Simulator<'a> {
    /// Builds the ocean (h0 of every cascade).
    ///
    /// # Errors
    /// The library's refusal of the config (kind `Config`).
    pub fn new(sea: &'a Sea) -> Result<Simulator<'a>, CliError> {
        let ocean = OceanState::new(sea.spectrum.clone(), sea.config.clone()).map_err(|e| {
            // Tiles that cannot hold the sea: say which would.
            let advice = match (&e, sea.config.clone().with_fitted_lengths(&sea.spectrum)) {
                (ocean_fft::Error::SeaDoesNotFit { .. }, Ok(fitted)) => format!(
                    "; use --lengths {}",
                    crate::warnings::lengths_text(&fitted.lengths)
                ),
                _ => String::new(),
            };
            CliError::config(format!("the sea's configuration: {e}{advice}"))
        })?;
        Ok(Simulator {
            sea,
            ocean,
            position: Position::Fresh,
            steady: None,
            convergence: None,
            steps: 0,
        })
    }

    /// The ocean, at the last frame advanced to.
    pub fn ocean(&self) -> &OceanState {
        &self.ocean
    }

    /// The loop's convergence, once [`advance_to`](Self::advance_to) pre-rolled it.
    pub fn convergence(&self) -> Option<LoopConvergence> {
        self.convergence
    }

    fn step_to_frame(&mut self, index: i64) -> Result<(), CliError> {
        self.ocean.step_to(self.sea.time(index)).map_err(internal)?;
        self.steps += 1;
        Ok(())
    }

    /// Brings the ocean to frame `frame`: its waves and its foam as the module's docs
    /// define them, whatever was simulated before.
    ///
    /// # Errors
    /// Only on a bug.
    pub fn advance_to(&mut self, frame: u32) -> Result<(), CliError> {
        let frame = i64::from(frame);
        match self.sea.looping {
            None => {
                let k = i64::from(self.sea.preroll.anchor_every);
                let anchor = frame - frame % k;
                let from = match self.position {
                    Position::Block {
                        anchor: a,
                        frame: f,
                    } if a == anchor && f <= frame => f,
                    _ => {
                        let preroll = self.sea.preroll;
                        self.ocean
                            .set_time(self.sea.time(anchor))
                            .map_err(internal)?;
                        let start = self.sea.time(anchor - i64::from(preroll.frames));
                        let seconds = self.ocean.time() - start;
                        self.ocean
                            .pre_roll(seconds, preroll.step)
                            .map_err(internal)?;
                        self.steps += (seconds / preroll.step).ceil() as u64;
                        anchor
                    }
                };
                for i in from + 1..=frame {
                    self.step_to_frame(i)?;
                }
                self.position = Position::Block { anchor, frame };
            }
            Some(looping) => {
                let phase = frame % i64::from(looping.frames);
                let from = match self.position {
                    Position::Loop { phase: p } if p <= phase => p,
                    _ => {
                        self.restore_steady()?;
                        0
                    }
                };
                for i in from + 1..=phase {
                    self.step_to_frame(i)?;
                }
                self.position = Position::Loop { phase };
            }
        }
        Ok(())
    }

    /// Restores the loop's steady state at phase 0, pre-rolling it the first time.
    fn restore_steady(&mut self) -> Result<(), CliError> {
        if self.steady.is_none() {
            self.preroll_loops()?;
        }
        let steady = self.steady.as_ref().expect("pre-rolled above");
        self.ocean.restore(steady).map_err(internal)?;
        Ok(())
    }

    /// Whole loops from no foam until one loop changes the foam by at most ε.
    fn preroll_loops(&mut self) -> Result<(), CliError> {
        let looping = self.sea.looping.expect("only for loops");
        let preroll = self.sea.preroll;
        self.ocean.set_time(0.0).map_err(internal)?;
        self.ocean.clear_foam();
        // The ocean's one foam field (cascade 0's texels carry it, the others carry none).
        let mut before = self.ocean.foam_view().total().to_vec();
        let mut loops = 0;
        let mut change = f64::INFINITY;
        let needed = self.sea.config.foam.coverage > 0.0;
        while needed && loops < preroll.max_loops && change > preroll.loop_change {
            for i in 1..=i64::from(looping.frames) {
                self.step_to_frame(i)?;
            }
            // Back to phase 0 with the foam kept: the waves at T equal those at 0.
            self.ocean.set_time(0.0).map_err(internal)?;
            loops += 1;
            change = 0.0;
            for (b, &a) in before.iter_mut().zip(self.ocean.foam_view().total()) {
                change = change.max(f64::from((*b - a).abs()));
                *b = a;
            }
        }
        if !needed {
            change = 0.0;
        }
        let q = (-f64::from(looping.period) / slowest_decay(self.sea)).exp();
        self.convergence = Some(LoopConvergence {
            loops,
            last_change: change,
            seam_bound: q * change,
        });
        self.steady = Some(self.ocean.snapshot());
        Ok(())
    }
}

/// The slower of the foam's two decay times in seconds: what bounds how fast a loop forgets.
pub fn slowest_decay(sea: &Sea) -> f64 {
    let foam = &sea.config.foam;
    f64::from(foam.active_decay.max(foam.residual_decay))
}
