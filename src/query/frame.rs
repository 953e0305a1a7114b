//! What the world queries read about one frame (the spline coefficients, computed tile by tile on
//! first use, and, once a [`Surface`](super::surface::Surface) handle was taken, copies of the
//! fields), and the double buffer of frames that lets handles keep answering about time t while the
//! ocean steps on.

use std::sync::Arc;

use super::config::{Interpolation, QueryConfig};
use super::spline::{Source, Tiles};
use crate::cascade::Cascade;
use crate::coast::Coast;
use crate::error::Error;
use crate::foam::Foam;
use crate::math::determinism::Determinism;
use crate::math::periodic::{cell_on, periodic_bilinear, Period};
use crate::math::simd::Simd;
use crate::wake::Wakes;

/// One cascade's part of a frame.
#[derive(Debug, Clone)]
pub(crate) struct Grid {
    pub(crate) n: usize,
    /// The grid's side and cells per metre, for the wrap of a world point.
    pub(crate) period: Period,
    /// Cells per metre N/L, for the derivatives.
    pub(crate) per_metre: f32,
    /// Spline coefficients (none with bilinear queries).
    pub(crate) tiles: Option<Tiles>,
    /// Copies of the cascade's buffers for [`Surface`](super::surface::Surface) handles (empty
    /// until one is taken).
    height: Vec<f32>,
    displacement: Vec<[f32; 2]>,
    slope: Vec<[f32; 2]>,
}

/// The query data of one frame.
#[derive(Debug, Clone)]
pub(crate) struct Frame {
    /// Simulated time in seconds of the fields.
    pub(crate) time: f64,
    pub(crate) query: QueryConfig,
    /// The SIMD level the queries run at.
    pub(crate) simd: Simd,
    pub(crate) grids: Vec<Grid>,
    /// Whether the copies (the grids' and the foam's) hold this frame's fields.
    pub(super) detached: bool,
    /// Copy of the ocean's foam field for [`Surface`](super::surface::Surface) handles: its grid
    /// and side (metres).
    foam: Vec<f32>,
    foam_n: usize,
    foam_length: f32,
    /// The depth map's factors the queries scale the cascades by (none: the open sea).
    pub(crate) coast: Option<Coast>,
    /// The wake window's buffers at this frame's time (`None` without wakes): the ocean
    /// writes them after each move in time, and the queries add them.
    pub(crate) wake: Option<Wakes>,
}

impl Frame {
    /// The empty frame at `time` (s) of an ocean with queries `query`, determinism mode
    /// `determinism`, `cascades` and `foam` (no coefficient computed, nothing copied).
    pub(crate) fn new(
        query: QueryConfig,
        determinism: Determinism,
        cascades: &[Cascade],
        foam: &Foam,
        time: f64,
    ) -> Result<Frame, Error> {
        let cubic = query.interpolation == Interpolation::CubicBSpline;
        let grids = cascades
            .iter()
            .map(|c| {
                Ok(Grid {
                    n: c.size(),
                    period: Period::new(f64::from(c.length()), c.size()),
                    per_metre: c.size() as f32 / c.length(),
                    tiles: if cubic {
                        Some(Tiles::new(c.size())?)
                    } else {
                        None
                    },
                    height: Vec::new(),
                    displacement: Vec::new(),
                    slope: Vec::new(),
                })
            })
            .collect::<Result<Vec<_>, Error>>()?;
        Ok(Frame {
            time,
            query,
            simd: Simd::detect().for_queries(determinism),
            grids,
            detached: false,
            foam: Vec::new(),
            foam_n: foam.n,
            foam_length: foam.length,
            coast: None,
            wake: None,
        })
    }

    /// Forgets everything computed from the previous fields; the frame now stands for the
    /// ocean's fields at `time` (s), queried with `query`. Allocates nothing.
    fn reset(&mut self, time: f64, query: QueryConfig) {
        self.time = time;
        self.query = query;
        self.detached = false;
        for grid in &mut self.grids {
            if let Some(tiles) = &mut grid.tiles {
                tiles.reset();
            }
        }
    }

    /// Copies the fields the queries read from the ocean's `cascades` and `foam` (whose
    /// frame this is), reusing the copies' room.
    pub(super) fn detach(&mut self, cascades: &[Cascade], foam: &Foam) {
        fn copy<T: Copy>(to: &mut Vec<T>, from: &[T]) {
            to.clear();
            to.extend_from_slice(from);
        }
        for (grid, cascade) in self.grids.iter_mut().zip(cascades) {
            copy(&mut grid.height, cascade.height());
            copy(&mut grid.displacement, cascade.displacement());
            copy(&mut grid.slope, cascade.slope());
        }
        copy(&mut self.foam, &foam.total);
        self.detached = true;
    }
}

/// Where the queries of one frame read the fields: the ocean's own buffers, or a frame's
/// copies. One concrete type (not a trait with two implementations), so that every query is
/// compiled once per SIMD level rather than once per source as well.
#[derive(Clone, Copy)]
pub(crate) enum Fields<'a> {
    /// The queries of an [`OceanState`](crate::ocean::OceanState) between steps: its
    /// current frame, and its cascades' and foam's own buffers.
    Live {
        frame: &'a Frame,
        cascades: &'a [Cascade],
        foam: &'a Foam,
    },
    /// A frame's copies, read by a [`Surface`](super::surface::Surface) handle.
    Frame(&'a Frame),
}

impl Fields<'_> {
    /// The frame (coefficients, configuration).
    #[inline(always)]
    pub(crate) fn frame(&self) -> &Frame {
        match self {
            Fields::Live { frame, .. } => frame,
            Fields::Frame(frame) => frame,
        }
    }

    /// The samples of cascade `c`.
    #[inline(always)]
    pub(crate) fn source(&self, c: usize) -> Source<'_> {
        match self {
            Fields::Live { cascades, .. } => {
                let cascade = &cascades[c];
                Source {
                    height: cascade.height(),
                    displacement: cascade.displacement(),
                    slope: cascade.slope(),
                }
            }
            Fields::Frame(frame) => {
                let grid = &frame.grids[c];
                Source {
                    height: &grid.height,
                    displacement: &grid.displacement,
                    slope: &grid.slope,
                }
            }
        }
    }

    /// Foam coverage in [0, 1] at undisplaced world (x, z): the ocean's own foam lookup
    /// (`Foam::foam_at`), NaN included.
    #[inline(always)]
    #[allow(clippy::manual_clamp)]
    pub(crate) fn foam_at(&self, x: f64, z: f64) -> f32 {
        let (values, n, length) = self.foam_grid();
        let foam = periodic_bilinear(values, n, length, x, z).max(0.0).min(1.0);
        match &self.frame().coast {
            None => foam,
            Some(coast) => coast.foam(self.frame().time, x, z, foam),
        }
    }

    /// The foam field [`Fields::foam_at`] interpolates: its values on an N×N grid, N, and
    /// the grid's side in metres.
    #[inline(always)]
    pub(crate) fn foam_grid(&self) -> (&[f32], usize, f64) {
        match self {
            Fields::Live { foam, .. } => (&foam.total, foam.n, f64::from(foam.length)),
            Fields::Frame(frame) => (&frame.foam, frame.foam_n, f64::from(frame.foam_length)),
        }
    }
}

/// The cell of (x, z) on `grid`.
#[inline(always)]
pub(super) fn cell_in(grid: &Grid, x: f64, z: f64) -> (usize, f32, usize, f32) {
    cell_on(x, z, &grid.period)
}

/// The frames of an ocean: the current one, and the one before it while a
/// [`Surface`](super::surface::Surface) handle may still read it.
#[derive(Debug)]
pub(crate) struct Frames {
    pub(crate) current: Arc<Frame>,
    spare: Option<Arc<Frame>>,
}

impl Frames {
    pub(crate) fn new(frame: Frame) -> Frames {
        Frames {
            current: Arc::new(frame),
            spare: None,
        }
    }

    /// After the ocean's fields changed: makes the current frame stand for them. In place if
    /// no handle holds it; else the frame before it becomes current (the step waits for
    /// nothing), or, if a handle still holds that one too, a new frame is allocated (and the
    /// old one freed when its last handle drops).
    pub(crate) fn advance(&mut self, time: f64, query: QueryConfig) {
        let coast = self.current.coast.clone();
        if Arc::get_mut(&mut self.current).is_none() {
            let next = match self.spare.take() {
                // Handles never make weak references: a count of one means no handle.
                Some(spare) if Arc::strong_count(&spare) == 1 => spare,
                // Both held (or no spare yet): another frame, as big as the others.
                _ => Arc::new(self.current.as_ref().clone()),
            };
            self.spare = Some(std::mem::replace(&mut self.current, next));
        }
        if let Some(frame) = Arc::get_mut(&mut self.current) {
            frame.reset(time, query);
            frame.coast = coast;
        }
    }

    /// Makes the queries of the current frame (and those after it) read `coast`; handles
    /// taken before keep the coast they saw.
    pub(crate) fn set_coast(&mut self, coast: Option<Coast>) {
        Arc::make_mut(&mut self.current).coast = coast;
    }
}

impl Frames {
    /// Runs the queries at `simd` from now on (the tests force every level).
    #[cfg(test)]
    pub(crate) fn set_simd(&mut self, simd: Simd) {
        for frame in std::iter::once(&mut self.current).chain(&mut self.spare) {
            if let Some(frame) = Arc::get_mut(frame) {
                frame.simd = simd;
            }
        }
    }
}

impl Clone for Frames {
    /// A frame of its own for the clone (its coefficients recomputed as they are read, to
    /// the same bits), so that the clone never waits on or writes into the original's.
    fn clone(&self) -> Self {
        Frames::new(self.current.as_ref().clone())
    }
}
