//! What the world queries read about one frame (the spline coefficients, computed tile by
//! tile on first use, and, once a [`Surface`] handle was taken, copies of the fields), and
//! the double buffer of frames that lets handles keep answering about time t while the
//! ocean steps on.

use std::sync::Arc;

use super::query::{self, HeightAt, Locate, Sample, SurfaceAt};
use super::spline::{Source, Tiles};
use super::{Interpolation, Location, OceanConfig, OceanState, QueryConfig, SurfaceSample};
use crate::cascade::Cascade;
use crate::error::Error;
use crate::foam::Foam;
use crate::math::periodic::{periodic_bilinear, Period};
use crate::math::simd::Simd;

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
    /// Copies of the cascade's buffers for [`Surface`] handles (empty until one is taken).
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
    detached: bool,
    /// Copy of the ocean's foam field for [`Surface`] handles: its grid and side (metres).
    foam: Vec<f32>,
    foam_n: usize,
    foam_length: f32,
}

impl Frame {
    /// The empty frame at `time` (s) of an ocean with `config`, `cascades` and `foam` (no
    /// coefficient computed, nothing copied).
    pub(crate) fn new(
        config: &OceanConfig,
        cascades: &[Cascade],
        foam: &Foam,
        time: f64,
    ) -> Result<Frame, Error> {
        let cubic = config.query.interpolation == Interpolation::CubicBSpline;
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
            query: config.query,
            simd: Simd::detect().for_queries(config.determinism),
            grids,
            detached: false,
            foam: Vec::new(),
            foam_n: foam.n,
            foam_length: foam.length,
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
    fn detach(&mut self, cascades: &[Cascade], foam: &Foam) {
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
    /// The queries of an [`OceanState`] between steps: its buffers and current frame.
    Live(&'a OceanState),
    /// A frame's copies, read by a [`Surface`] handle.
    Frame(&'a Frame),
}

impl Fields<'_> {
    /// The frame (coefficients, configuration).
    #[inline(always)]
    pub(crate) fn frame(&self) -> &Frame {
        match self {
            Fields::Live(ocean) => &ocean.frames.current,
            Fields::Frame(frame) => frame,
        }
    }

    /// The samples of cascade `c`.
    #[inline(always)]
    pub(crate) fn source(&self, c: usize) -> Source<'_> {
        match self {
            Fields::Live(ocean) => {
                let cascade = &ocean.cascades[c];
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
        periodic_bilinear(values, n, length, x, z).max(0.0).min(1.0)
    }

    /// The foam field [`Fields::foam_at`] interpolates: its values on an N×N grid, N, and
    /// the grid's side in metres.
    #[inline(always)]
    pub(crate) fn foam_grid(&self) -> (&[f32], usize, f64) {
        match self {
            Fields::Live(ocean) => {
                let foam = &ocean.foam;
                (&foam.total, foam.n, f64::from(foam.length))
            }
            Fields::Frame(frame) => (&frame.foam, frame.foam_n, f64::from(frame.foam_length)),
        }
    }
}

/// The frames of an ocean: the current one, and the one before it while a [`Surface`]
/// handle may still read it.
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
        }
    }

    /// A handle on the current frame, copying the fields into it first if no handle did.
    pub(crate) fn surface(&mut self, cascades: &[Cascade], foam: &Foam) -> Surface {
        if !self.current.detached {
            if Arc::get_mut(&mut self.current).is_none() {
                // Only a handle shares a frame, and handles detach it first; kept for safety.
                self.current = Arc::new(self.current.as_ref().clone());
            }
            if let Some(frame) = Arc::get_mut(&mut self.current) {
                frame.detach(cascades, foam);
            }
        }
        Surface(Arc::clone(&self.current))
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

/// A handle on the water of one frame: the ocean's fields at the time
/// [`OceanState::surface`] was called, answering the same world queries as the ocean
/// ([`Surface::height_at`], [`Surface::heights_at`], …) with the same bits, from any thread
/// and while the ocean steps on.
///
/// `Send + Sync + Clone` (an [`Arc`]: cloning costs an atomic increment). The ocean keeps
/// two frames: a step writes the one no handle reads and makes it current, so taking a
/// handle every frame and dropping it within the next step costs no allocation and never
/// makes the step wait. A handle kept across two steps makes the second one allocate a third
/// frame (as large as the query data of every cascade: about 24·N² bytes per cascade and
/// the fields' 20·N²); the old frame is freed when its last handle drops.
///
/// ```
/// use ocean_fft::{OceanConfig, OceanState, Spectrum};
/// let spectrum = Spectrum::jonswap(10.0, 100_000.0)?;
/// let mut ocean = OceanState::new(spectrum, OceanConfig { size: 32, ..Default::default() })?;
/// ocean.step(1.0 / 60.0)?;
/// let surface = ocean.surface();                  // the water at t = 1/60 s
/// let physics = std::thread::spawn(move || surface.height_at(3.0, 4.0));
/// let y = ocean.height_at(3.0, 4.0)?;             // m
/// ocean.step(1.0 / 60.0)?;                        // the handle still answers about 1/60 s
/// assert_eq!(physics.join().unwrap()?, y);
/// # Ok::<(), ocean_fft::Error>(())
/// ```
#[derive(Clone)]
pub struct Surface(pub(crate) Arc<Frame>);

impl std::fmt::Debug for Surface {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Surface")
            .field("time", &self.0.time)
            .field("cascades", &self.0.grids.len())
            .finish_non_exhaustive()
    }
}

impl Surface {
    /// Simulated time in seconds of the water this handle answers about.
    pub fn time(&self) -> f64 {
        self.0.time
    }

    /// As [`OceanState::sample`], for this frame.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn sample(&self, x: f64, z: f64) -> Result<SurfaceSample, Error> {
        query::check_point(x, z)?;
        Ok(query::run(
            &Fields::Frame(&self.0),
            Sample(0..self.0.grids.len()),
            x,
            z,
        ))
    }

    /// As [`OceanState::locate`], for this frame.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn locate(&self, x: f64, z: f64) -> Result<Location, Error> {
        query::check_point(x, z)?;
        Ok(query::run(&Fields::Frame(&self.0), Locate, x, z))
    }

    /// As [`OceanState::surface_at`], for this frame.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn surface_at(&self, x: f64, z: f64) -> Result<SurfaceSample, Error> {
        query::check_point(x, z)?;
        Ok(query::run(&Fields::Frame(&self.0), SurfaceAt, x, z))
    }

    /// Water height y in metres at world point (`x`, `z`) after horizontal displacement, as
    /// [`OceanState::height_at`], for this frame.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite coordinate.
    pub fn height_at(&self, x: f64, z: f64) -> Result<f32, Error> {
        query::check_point(x, z)?;
        Ok(query::run(&Fields::Frame(&self.0), HeightAt, x, z))
    }

    /// As [`OceanState::heights_at`], for this frame: water heights in metres at world
    /// points (x, z), into `out`.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] unless `out` is as long as `points`; [`Error::NonFinite`]
    /// for a NaN or infinite coordinate. Nothing is written then.
    pub fn heights_at(&self, points: &[[f64; 2]], out: &mut [f32]) -> Result<(), Error> {
        query::check_batch(points, out.len())?;
        query::for_each_point(&Fields::Frame(&self.0), points, out, HeightAt);
        Ok(())
    }

    /// As [`OceanState::surfaces_at`], for this frame.
    ///
    /// # Errors
    /// As [`Surface::heights_at`].
    pub fn surfaces_at(&self, points: &[[f64; 2]], out: &mut [SurfaceSample]) -> Result<(), Error> {
        query::check_batch(points, out.len())?;
        query::for_each_point(&Fields::Frame(&self.0), points, out, SurfaceAt);
        Ok(())
    }

    /// As [`OceanState::sample_many`], for this frame.
    ///
    /// # Errors
    /// As [`Surface::heights_at`].
    pub fn sample_many(&self, points: &[[f64; 2]], out: &mut [SurfaceSample]) -> Result<(), Error> {
        query::check_batch(points, out.len())?;
        query::for_each_point(
            &Fields::Frame(&self.0),
            points,
            out,
            Sample(0..self.0.grids.len()),
        );
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::math::simd::{test_pools, Simd};
    use crate::{OceanConfig, OceanState, Spectrum, SurfaceSample};

    /// Batch, grid and single queries, the ocean's and a handle's, give the same bits at every
    /// SIMD level this CPU runs and at 1, 2 and 3 threads; at the baseline level of a CPU
    /// without FMA (products added unfused, forced here) batches still give their single
    /// queries' bits, and results close to the fused ones.
    #[test]
    fn queries_give_the_same_bits_at_every_level_and_thread_count() {
        let spectrum = Spectrum::jonswap(14.0, 150_000.0).unwrap();
        let config = OceanConfig {
            size: 64,
            ..OceanConfig::default()
        };
        // 300 points, then a few beyond 2²⁹ periods of every cascade, where the wrap takes
        // its other path (in some lanes of a group only).
        let points: Vec<[f64; 2]> = (0..300)
            .map(|i| {
                [
                    f64::from(i) * 7.3 - 900.0,
                    f64::from(i * i % 89) * 11.1 - 400.0,
                ]
            })
            .chain([[7.3e11, -2.1e12], [12.5, -9.9e14], [-5.0e17, 3.0e16]])
            .collect();
        let mut reference: Option<(Vec<u32>, Vec<SurfaceSample>)> = None;
        let unfused = Simd::Baseline { fused: false };
        for level in Simd::available().into_iter().chain([unfused]) {
            for (threads, pool) in test_pools() {
                let mut ocean = OceanState::new(spectrum.clone(), config.clone()).unwrap();
                ocean.frames.set_simd(level);
                let (heights, surfaces, singles, handle) = pool.install(|| {
                    ocean.step(3.0).unwrap();
                    let mut heights = vec![0.0f32; points.len()];
                    let mut surfaces = vec![SurfaceSample::default(); points.len()];
                    ocean.heights_at(&points, &mut heights).unwrap();
                    ocean.surfaces_at(&points, &mut surfaces).unwrap();
                    let singles: Vec<f32> = points
                        .iter()
                        .map(|&[x, z]| ocean.height_at(x, z).unwrap())
                        .collect();
                    let mut handle = vec![0.0f32; points.len()];
                    ocean.surface().heights_at(&points, &mut handle).unwrap();
                    // The other batches against their single queries too (groups of points
                    // interleaved, the last one partial).
                    for (&[x, z], batch) in points.iter().zip(&surfaces) {
                        assert_eq!(ocean.surface_at(x, z).unwrap(), *batch);
                    }
                    let mut samples = vec![SurfaceSample::default(); points.len()];
                    ocean.sample_many(&points, &mut samples).unwrap();
                    for (&[x, z], batch) in points.iter().zip(&samples) {
                        assert_eq!(ocean.sample(x, z).unwrap(), *batch);
                    }
                    // Grids in lanes too, rows ending in a partial group of eight, one far
                    // out where the wrap takes its other path.
                    let grids = [
                        ([-300.0, 50.0], 1.7, [21, 4]),
                        ([7.3e11, -2.1e12], 0.37, [21, 4]),
                        // Rows of eleven: a last group of three, queried one point at a time.
                        ([40.0, -75.0], 2.9, [11, 3]),
                    ];
                    for (origin, spacing, [columns, rows]) in grids {
                        let mut grid = vec![SurfaceSample::default(); columns * rows];
                        ocean
                            .sample_grid(origin, spacing, [columns, rows], &mut grid)
                            .unwrap();
                        for (i, sample) in grid.iter().enumerate() {
                            let x = origin[0] + (i % columns) as f64 * spacing;
                            let z = origin[1] + (i / columns) as f64 * spacing;
                            assert_eq!(ocean.sample(x, z).unwrap(), *sample, "grid point {i}");
                        }
                    }
                    // Batches too small for lanes (queried one point at a time) and the
                    // smallest in lanes.
                    for n in 1..=4 {
                        let points = &points[100..100 + n];
                        let mut small = vec![0.0f32; n];
                        let mut small_surfaces = vec![SurfaceSample::default(); n];
                        let mut small_samples = vec![SurfaceSample::default(); n];
                        ocean.heights_at(points, &mut small).unwrap();
                        ocean.surfaces_at(points, &mut small_surfaces).unwrap();
                        ocean.sample_many(points, &mut small_samples).unwrap();
                        for (i, &[x, z]) in points.iter().enumerate() {
                            let height = ocean.height_at(x, z).unwrap();
                            assert_eq!(small[i].to_bits(), height.to_bits(), "{n} points");
                            assert_eq!(small_surfaces[i], ocean.surface_at(x, z).unwrap());
                            assert_eq!(small_samples[i], ocean.sample(x, z).unwrap());
                        }
                    }
                    (heights, surfaces, singles, handle)
                });
                let bits = |v: &[f32]| v.iter().map(|h| h.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(&heights),
                    bits(&singles),
                    "{level:?}, {threads} threads"
                );
                assert_eq!(
                    bits(&heights),
                    bits(&handle),
                    "{level:?}, {threads} threads"
                );
                match &reference {
                    None => reference = Some((bits(&heights), surfaces)),
                    Some((h, s)) if !matches!(level, Simd::Baseline { fused: false }) => {
                        assert_eq!(&bits(&heights), h, "{level:?}, {threads} threads");
                        assert_eq!(&surfaces, s, "{level:?}, {threads} threads");
                    }
                    Some((h, _)) => {
                        // Sums rounded twice instead of once move a height by ulps of the
                        // ~1 m sums, and a search may end on another iterate within the
                        // tolerance (1e-4 m) of the same point: the height moves by the
                        // slope (below 1 here) times at most twice that.
                        for (&fused, &unfused) in h.iter().zip(&heights) {
                            let fused = f32::from_bits(fused);
                            assert!((fused - unfused).abs() < 3e-4, "{fused} against {unfused}");
                        }
                    }
                }
            }
        }
    }
}
