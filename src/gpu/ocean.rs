//! What a renderer reads from a whole ocean ([`Textures`]): every cascade's texels with the
//! ocean's foam in cascade 0's, and the sub-grid slope variance for the sun's glitter.

use rayon::prelude::*;

use super::{FoamStreaks, Sources, TexelLayout};
use crate::cascade::Cascade;
use crate::coast::CoastField;
use crate::error::{self, Error};
use crate::ocean::OceanState;
use crate::spectrum::SlopeVariance;

/// What a renderer reads from an ocean each frame: what
/// [`OceanState::textures`] returns. The cascades' texels with the ocean's foam
/// ([`pack`](Self::pack), `pack_f16` with the `half` feature) and the
/// slope variance the grids cannot show ([`subgrid_slope_variance`](Self::subgrid_slope_variance)).
/// Borrows the ocean; `Copy`; allocates nothing.
///
/// ```
/// use ocean_fft::gpu::TexelLayout;
/// use ocean_fft::{OceanConfig, OceanState, Spectrum};
/// let config = OceanConfig { size: 32, ..OceanConfig::default() };
/// let mut ocean = OceanState::new(Spectrum::jonswap(10.0, 100_000.0)?, config)?;
/// ocean.step(1.0 / 60.0)?;
/// let mut texels = vec![[0.0f32; 4]; 32 * 32];
/// for cascade in 0..ocean.cascades().len() {
///     ocean.textures().pack(cascade, TexelLayout::DisplacementFoam, &mut texels)?;
///     // upload `texels` to this cascade's texture
/// }
/// let glitter = ocean.textures().subgrid_slope_variance().total();   // σ², dimensionless
/// assert!(glitter > 0.0);
/// # Ok::<(), ocean_fft::Error>(())
/// ```
#[derive(Clone, Copy)]
pub struct Textures<'a> {
    ocean: &'a OceanState,
}

impl std::fmt::Debug for Textures<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Textures")
            .field("cascades", &self.ocean.cascades().len())
            .finish_non_exhaustive()
    }
}

impl OceanState {
    /// What a renderer reads each frame: every cascade's texels with the ocean's foam
    /// ([`Textures::pack`]) and the slope variance the grids cannot show
    /// ([`Textures::subgrid_slope_variance`]). Costs nothing.
    #[inline]
    pub fn textures(&self) -> Textures<'_> {
        Textures { ocean: self }
    }

    /// Deprecated: [`Textures::pack`] through [`OceanState::textures`].
    ///
    /// # Errors
    /// As [`Textures::pack`].
    #[deprecated(
        since = "0.4.0",
        note = "use `ocean.textures().pack(cascade, layout, out)`"
    )]
    #[doc(hidden)]
    pub fn pack_texels(
        &self,
        cascade: usize,
        layout: TexelLayout,
        out: &mut [[f32; 4]],
    ) -> Result<(), Error> {
        self.textures().pack(cascade, layout, out)
    }

    /// Deprecated: [`Textures::pack_f16`] through [`OceanState::textures`].
    ///
    /// # Errors
    /// As [`Textures::pack_f16`].
    #[cfg(feature = "half")]
    #[deprecated(
        since = "0.4.0",
        note = "use `ocean.textures().pack_f16(cascade, layout, out)`"
    )]
    #[doc(hidden)]
    pub fn pack_texels_f16(
        &self,
        cascade: usize,
        layout: TexelLayout,
        out: &mut [[half::f16; 4]],
    ) -> Result<(), Error> {
        self.textures().pack_f16(cascade, layout, out)
    }

    /// Deprecated: [`Textures::subgrid_slope_variance`] through [`OceanState::textures`].
    #[deprecated(
        since = "0.4.0",
        note = "use `ocean.textures().subgrid_slope_variance()`"
    )]
    #[doc(hidden)]
    pub fn subgrid_slope_variance(&self) -> SlopeVariance {
        self.textures().subgrid_slope_variance()
    }
}

impl<'a> Textures<'a> {
    /// Packs cascade `cascade` (0 the largest) into interleaved RGBA32F texels of `layout`
    /// (see [`TexelLayout`]), texel (i, j) of that cascade's N×N grid at `out[j * N + i]`.
    /// The ocean's one foam field lives on cascade 0's grid ([`FoamView::total`](crate::FoamView::total)), so the
    /// layouts with foam carry it in cascade 0's texels and 0 in every other cascade's (a
    /// shader that sums the foam channels, or combines them as 1 − Π(1 − f), gets the foam).
    /// Copies the values bit for bit. Row blocks in parallel; allocates nothing inside a
    /// rayon pool; the result does not depend on the number of threads.
    ///
    /// # Errors
    /// [`Error::IndexOutOfRange`] naming `cascade` unless it is below the number of cascades;
    /// [`Error::LengthMismatch`] naming `out` unless `out.len()` is that cascade's N².
    /// Nothing is written then.
    pub fn pack(
        &self,
        cascade: usize,
        layout: TexelLayout,
        out: &mut [[f32; 4]],
    ) -> Result<(), Error> {
        let (sources, n) = self.sources(cascade, out.len())?;
        sources.pack_f32(n, layout, out);
        Ok(())
    }

    /// [`pack`](Self::pack) into RGBA16F texels (with the `half` feature), rounded and
    /// saturated as [`Cascade::pack_texels_f16`] says: nearest f16, ties to even, ±65504
    /// beyond the f16 range (never ±∞ or NaN).
    ///
    /// # Errors
    /// As [`pack`](Self::pack); nothing is written then.
    #[cfg(feature = "half")]
    pub fn pack_f16(
        &self,
        cascade: usize,
        layout: TexelLayout,
        out: &mut [[half::f16; 4]],
    ) -> Result<(), Error> {
        let (sources, n) = self.sources(cascade, out.len())?;
        sources.pack_f16(n, layout, out);
        Ok(())
    }

    /// Slope variance along and across the wind that the spectrum holds above the finest
    /// cascade's band, up to [`SlopeVariance::DEFAULT_CUTOFF`]: the roughness the grids
    /// cannot show, which widens the sun's glitter (the last cascade's
    /// [`Cascade::subgrid_slope_variance`]; a cascade `c` reports what lies above its own
    /// band). For another cut-off use
    /// [`Spectrum::slope_variance`](crate::Spectrum::slope_variance) from the top of the
    /// last band.
    pub fn subgrid_slope_variance(&self) -> SlopeVariance {
        self.ocean
            .cascades()
            .last()
            .map(Cascade::subgrid_slope_variance)
            .unwrap_or_default()
    }

    /// Packs the wake window ([`OceanState::wakes`]) into interleaved RGBA32F texels
    /// `[η, ∂y/∂x, ∂y/∂z, foam]` — the wake's height in metres (y up), its slope
    /// (dimensionless) and its foam coverage in [0, 1] — texel (i, j) of the window's N×N
    /// grid at `out[j * N + i]`, for world (x₀ + i·Δ, z₀ + j·Δ) with (x₀, z₀) =
    /// [`Wakes::origin`](crate::Wakes::origin) and Δ = [`Wakes::spacing`](crate::Wakes::spacing)
    /// (upload them with the texture; the window
    /// moves by whole cells). A shader adds the height and slope to the cascades' sums, and
    /// combines the foam f with the ocean's as f_ocean + f·(1 − f_ocean), as the queries do.
    /// The texels are zero outside the window: sample with clamp-to-border (or clamp to the
    /// edge: the wake is faded to zero there). Copies the values bit for bit; rows in
    /// parallel; allocates nothing inside a rayon pool.
    ///
    /// # Errors
    /// [`Error::NotApplicable`] naming `wakes` without
    /// [`OceanConfig::wakes`](crate::OceanConfig::wakes); [`Error::LengthMismatch`] naming
    /// `out` unless `out.len()` is N². Nothing is written then.
    pub fn pack_wakes(&self, out: &mut [[f32; 4]]) -> Result<(), Error> {
        let wakes = self.ocean.wakes().ok_or(Error::NotApplicable {
            name: "wakes",
            reason: "the ocean was built without `OceanConfig::wakes`",
        })?;
        let n = wakes.size();
        error::length("out", out.len(), n * n)?;
        let (height, slope, foam) = (wakes.height(), wakes.slope(), wakes.foam());
        out.par_chunks_mut(n)
            .zip(height.par_chunks(n))
            .zip(slope.par_chunks(n).zip(foam.par_chunks(n)))
            .for_each(|((texels, height), (slope, foam))| {
                let cells = texels.iter_mut().zip(height).zip(slope.iter().zip(foam));
                for ((texel, &h), (&[sx, sz], &f)) in cells {
                    *texel = [h, sx, sz, f];
                }
            });
        Ok(())
    }

    /// The waves over the ocean's depth map
    /// ([`OceanState::set_depth_map`](crate::OceanState::set_depth_map); `None` without
    /// one): the amplitude factor of each cascade and the fraction of breaking waves Q_b at
    /// each cell of the map, what a renderer uploads as textures over the map. Costs nothing.
    pub fn coast(&self) -> Option<&'a CoastField> {
        self.ocean.coast_field()
    }

    /// Packs the coast's field over the depth map
    /// ([`OceanState::set_depth_map`](crate::OceanState::set_depth_map)) into interleaved
    /// RGBA32F texels `[f₀, f₁, f₂, Q_b]`: the amplitude factors (no unit, 1 the open sea,
    /// 0 land) of cascades 0, 1 and 2 (1 where the ocean has fewer cascades) and the fraction
    /// of waves breaking on the bottom Q_b in [0, 1], texel (i, j) of the map's
    /// `size[0]` × `size[1]` cells at `out[j * size[0] + i]`, for world (x₀ + i·Δ,
    /// z₀ + j·Δ) with (x₀, z₀) = [`DepthMap::origin`](crate::DepthMap::origin) and Δ =
    /// [`DepthMap::spacing`](crate::DepthMap::spacing) in metres. A shader multiplies each
    /// cascade's displacement, height and slope by its factor at the point, sampled
    /// bilinearly at texel coordinates (p − origin)/Δ + ½ (the queries' interpolation), and
    /// uses (1, 1, 1, 0) outside the map; the factors reach 1 and Q_b 0 at the map's edge.
    /// Q_b is the surf's coarse foam coverage (it lays the surf over the whitecaps as
    /// [`FoamView::foam_at`](crate::FoamView::foam_at) does). An ocean with more than three
    /// cascades reads the others' factors from [`coast`](Self::coast).
    ///
    /// The values are those the queries use at the ocean's time: while a replaced map blends
    /// in ([`coast::BLEND_SECONDS`](crate::coast::BLEND_SECONDS) of simulated time after
    /// `set_depth_map`) they change, and a renderer repacks each frame; otherwise once per
    /// map. Rows in parallel; allocates nothing inside a rayon pool.
    ///
    /// # Errors
    /// [`Error::NotApplicable`] naming `depth_map` if the ocean has no depth map;
    /// [`Error::LengthMismatch`] naming `out` unless `out.len()` is `size[0] * size[1]`.
    /// Nothing is written then.
    pub fn pack_coast(&self, out: &mut [[f32; 4]]) -> Result<(), Error> {
        let not_set = Error::NotApplicable {
            name: "depth_map",
            reason: "the ocean has no depth map (`OceanState::set_depth_map`)",
        };
        let (Some(coast), Some(field)) = (self.ocean.coast_state(), self.ocean.coast_field())
        else {
            return Err(not_set);
        };
        let map = field.map();
        let [nx, nz] = map.size;
        error::length("out", out.len(), nx * nz)?;
        let (t, spacing, origin) = (self.ocean.time(), f64::from(map.spacing), map.origin);
        out.par_chunks_mut(nx).enumerate().for_each(|(j, row)| {
            let z = origin[1] + j as f64 * spacing;
            for (i, texel) in row.iter_mut().enumerate() {
                let x = origin[0] + i as f64 * spacing;
                let f = coast.factors(t, x, z);
                *texel = [f[0], f[1], f[2], coast.breaking(t, x, z)];
            }
        });
        Ok(())
    }

    /// The streak field of the foam's detail and where it lies now ([`FoamStreaks`]): the
    /// texels to upload once, the placement to set each frame. Costs nothing.
    pub fn foam_streaks(&self) -> FoamStreaks<'a> {
        self.ocean.foam.streaks()
    }

    /// Checks a pack of cascade `cascade` into a buffer of `len` texels; its sources and N.
    fn sources(&self, cascade: usize, len: usize) -> Result<(Sources<'_>, usize), Error> {
        let cascades = self.ocean.cascades();
        error::index("cascade", cascade, cascades.len())?;
        let c = &cascades[cascade];
        error::length("out", len, c.size() * c.size())?;
        let foam = (cascade == 0).then(|| self.ocean.foam.total());
        Ok((Sources::new(c, foam), c.size()))
    }
}
