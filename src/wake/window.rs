//! [`Wakes`]: the wake window's buffers as the queries and a renderer read them.

use crate::error::{self, Error};

/// The wake window of an ocean at its current time
/// ([`OceanState::wakes`](crate::OceanState::wakes)): where it lies and the wake's height,
/// slope and foam on its grid, which every world query adds to the ocean's inside the window.
///
/// Sample (i, j) sits at world (x₀ + i·spacing, z₀ + j·spacing), (x₀, z₀) =
/// [`origin`](Self::origin), at index `j * size + i` of each buffer (z the row, as the
/// cascades'). Outside the window the wake is zero; it fades to zero across the outer half of
/// the absorbing border, so the edges are seamless. The wake has no horizontal displacement.
#[derive(Debug, Clone, PartialEq)]
pub struct Wakes {
    pub(crate) origin: [f64; 2],
    pub(crate) size: usize,
    pub(crate) spacing: f32,
    pub(crate) time: f64,
    pub(crate) height: Vec<f32>,
    pub(crate) slope: Vec<[f32; 2]>,
    pub(crate) foam: Vec<f32>,
}

impl Wakes {
    /// A still window of `size`² samples `spacing` metres apart at the world origin.
    pub(crate) fn new(size: usize, spacing: f64) -> Result<Wakes, Error> {
        let n = size * size;
        Ok(Wakes {
            origin: [0.0; 2],
            size,
            spacing: spacing as f32,
            time: 0.0,
            height: error::try_vec(n, 0.0)?,
            slope: error::try_vec(n, [0.0; 2])?,
            foam: error::try_vec(n, 0.0)?,
        })
    }

    /// World `[x, z]` in metres of sample (0, 0).
    pub fn origin(&self) -> [f64; 2] {
        self.origin
    }

    /// Samples per side.
    pub fn size(&self) -> usize {
        self.size
    }

    /// Distance between samples in metres.
    pub fn spacing(&self) -> f32 {
        self.spacing
    }

    /// Side of the window in metres (`size · spacing`).
    pub fn side(&self) -> f64 {
        self.size as f64 * f64::from(self.spacing)
    }

    /// Simulated time in seconds of the buffers (the ocean's; the waves are those of the
    /// last wake tick at or before it, see [`WakeConfig::substep`](crate::WakeConfig::substep)).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The wake's height in metres at each sample (faded to zero at the edges).
    pub fn height(&self) -> &[f32] {
        &self.height
    }

    /// The wake's slope `[∂y/∂x, ∂y/∂z]` at each sample, dimensionless (central
    /// differences of [`height`](Self::height)).
    pub fn slope(&self) -> &[[f32; 2]] {
        &self.slope
    }

    /// The wake's foam coverage in [0, 1] at each sample (faded to zero at the edges): the
    /// trail of foam where hulls broke the water at their bow and stern and where the wake's
    /// crests broke, fading with
    /// [`FoamConfig::residual_decay`](crate::FoamConfig::residual_decay). The world queries
    /// add it to the ocean's foam f as f + w·(1 − f).
    pub fn foam(&self) -> &[f32] {
        &self.foam
    }

    /// The wake's foam coverage in [0, 1] at world (x, z) in metres, interpolated
    /// bilinearly; 0 outside the window (and for coordinates that are not finite).
    pub fn foam_at(&self, x: f64, z: f64) -> f32 {
        self.sample(x, z).2
    }

    /// The wake's height in metres and slope at world (x, z) in metres, interpolated
    /// bilinearly; 0 outside the window (and for coordinates that are not finite).
    pub fn at(&self, x: f64, z: f64) -> (f32, [f32; 2]) {
        let (height, slope, _) = self.sample(x, z);
        (height, slope)
    }

    /// [`at`](Self::at) and [`foam_at`](Self::foam_at) at once.
    #[inline(always)]
    pub(crate) fn sample(&self, x: f64, z: f64) -> (f32, [f32; 2], f32) {
        match self.cell(x, z) {
            Some((index, fx, fz)) => {
                let n = self.size;
                let w = [
                    (1.0 - fx) * (1.0 - fz),
                    fx * (1.0 - fz),
                    (1.0 - fx) * fz,
                    fx * fz,
                ];
                let at = [index, index + 1, index + n, index + n + 1];
                let mut height = 0.0;
                let mut slope = [0.0; 2];
                let mut foam = 0.0;
                for (w, i) in w.into_iter().zip(at) {
                    height += w * self.height[i];
                    slope[0] += w * self.slope[i][0];
                    slope[1] += w * self.slope[i][1];
                    foam += w * self.foam[i];
                }
                (height, slope, foam.clamp(0.0, 1.0))
            }
            None => (0.0, [0.0; 2], 0.0),
        }
    }

    /// The wake's height in metres at world (x, z) (see [`at`](Self::at)).
    pub fn height_at(&self, x: f64, z: f64) -> f32 {
        self.at(x, z).0
    }

    /// The index of the cell holding world (x, z) and the position in it, or `None` outside.
    #[inline(always)]
    fn cell(&self, x: f64, z: f64) -> Option<(usize, f32, f32)> {
        let spacing = f64::from(self.spacing);
        let gx = (x - self.origin[0]) / spacing;
        let gz = (z - self.origin[1]) / spacing;
        let last = (self.size - 1) as f64;
        if !(gx >= 0.0 && gx < last && gz >= 0.0 && gz < last) {
            return None;
        }
        let (ix, iz) = (gx.floor(), gz.floor());
        let index = iz as usize * self.size + ix as usize;
        Some((index, (gx - ix) as f32, (gz - iz) as f32))
    }
}
