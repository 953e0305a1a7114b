//! The end of the data flow, what a renderer needs: the layouts of the RGBA texels that
//! [`Cascade::pack_texels`] and [`Textures::pack`] interleave a cascade's buffers into
//! (f32, and f16 with the `half` feature), the [`Vertex`] of a cascade mesh with its triangle
//! indices, the green channel of tangent-space normal maps ([`NormalMapGreen`]), and each engine's
//! axes and units ([`Engine`]).
//!
//! Everything here writes into caller-owned buffers of N² elements in the grids' order
//! (texel, vertex or pixel (i, j) at index `j * N + i`, z the row), row blocks in parallel on
//! rayon's pool with no reduction, so the bits do not depend on the number of threads and
//! nothing is allocated inside a pool.

mod engine;
mod ocean;

use rayon::prelude::*;

pub use crate::foam::FoamStreaks;
pub use engine::Engine;
pub use ocean::Textures;

use crate::cascade::Cascade;
use crate::error::{self, Error};
#[cfg(doc)]
use crate::ocean::OceanState;

/// What the four channels of a packed RGBA texel hold. Texel (i, j) (index `j * N + i`)
/// describes the cascade's grid point (x, z) = (i·L/N, j·L/N) in metres; the textures tile
/// the plane with period L = [`Cascade::length`] (wrap mode *repeat*), so texel (i, j) stands
/// for every world point (x₀ + i·L/N, z₀ + j·L/N) with (x₀, z₀) on a multiple of L, and a
/// shader reads world point (x, z) at uv = (x/L + 0.5/N, z/L + 0.5/N) (texel centres at
/// (i + ½)/N, v = 0 at row 0). Horizontal displacements and heights are in metres; slopes,
/// normals, Jacobians and foam are dimensionless.
///
/// | layout | R | G | B | A | on a bare [`Cascade`] |
/// |---|---|---|---|---|---|
/// | [`DisplacementJacobian`](Self::DisplacementJacobian) | D_x | η | D_z | J | yes |
/// | [`DisplacementFoam`](Self::DisplacementFoam) | D_x | η | D_z | foam | no |
/// | [`SlopeJacobianFoam`](Self::SlopeJacobianFoam) | ∂y/∂x | ∂y/∂z | J | foam | no |
/// | [`Normal`](Self::Normal) | n_x | n_y | n_z | σ² sub-grid | yes |
///
/// The layouts with foam take the foam an [`OceanState`] holds, so they are packed with
/// [`Textures::pack`]; [`Cascade::pack_texels`] refuses them with
/// [`Error::NotApplicable`] naming `layout`. The foam is one field for the whole ocean on
/// cascade 0's grid: cascade 0's texels carry it, the other cascades' foam channel is 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum TexelLayout {
    /// `[D_x, η, D_z, J]`: the displaced surface point relative to its grid point, in metres
    /// with y up (the water of texel (i, j) sits at (i·L/N, 0, j·L/N) + RGB), and the
    /// Jacobian J (dimensionless, < 0 where the surface folds).
    DisplacementJacobian,
    /// `[D_x, η, D_z, foam]`: RGB as in [`DisplacementJacobian`](Self::DisplacementJacobian),
    /// A the foam coverage in [0, 1]. Only through [`Textures::pack`] ([`OceanState::textures`]).
    DisplacementFoam,
    /// `[∂y/∂x, ∂y/∂z, J, foam]`: the slope of the displaced surface (dimensionless), the
    /// Jacobian J and the foam coverage in [0, 1]. Slopes of cascades add, so a shader may
    /// sum the RG of every cascade and take the normal of the sum as
    /// normalize(−s_x, 1, −s_z). Only through [`Textures::pack`] ([`OceanState::textures`]).
    SlopeJacobianFoam,
    /// `[n_x, n_y, n_z, σ²]`: the unit normal of the displaced surface (y up; n_y < 0 where
    /// the surface folds), and in alpha the **sub-grid mean-square slope** σ² (dimensionless,
    /// linear, not squared again or remapped): the slope variance, along plus across the
    /// wind, that the spectrum holds between the top of this cascade's band and
    /// [`SlopeVariance::DEFAULT_CUTOFF`](crate::inspect::SlopeVariance::DEFAULT_CUTOFF)
    /// ([`Cascade::subgrid_slope_variance`]). It is the same in every texel of a cascade.
    /// A renderer that draws cascades 0..=c takes cascade c's σ² as the roughness of its
    /// specular lobe: a Beckmann or GGX slope variance, i.e. α² = σ² for Beckmann and
    /// α ≈ √(σ²) for GGX (Bruneton, Neyret & Holzschuch 2010 add it per axis; the split
    /// along and across the wind is on [`Cascade::subgrid_slope_variance`]). Typical values
    /// are 0.01–0.05; f16 keeps them to about 2.5·10⁻⁵.
    Normal,
}

impl TexelLayout {
    /// Every layout, in declaration order.
    pub const ALL: &'static [TexelLayout] = &[
        TexelLayout::DisplacementJacobian,
        TexelLayout::DisplacementFoam,
        TexelLayout::SlopeJacobianFoam,
        TexelLayout::Normal,
    ];

    /// Whether the layout holds foam, and so can be packed only through
    /// [`Textures::pack`].
    pub fn has_foam(self) -> bool {
        matches!(
            self,
            TexelLayout::DisplacementFoam | TexelLayout::SlopeJacobianFoam
        )
    }
}

/// One vertex of a cascade mesh, as [`Cascade::write_vertices`] writes it: 24 bytes,
/// `#[repr(C)]`, six `f32` with no padding (with the `bytemuck` feature it is `Pod`, so
/// `bytemuck::cast_slice(&vertices)` gives the bytes to upload).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct Vertex {
    /// Displaced position `[x, y, z]` in metres in the patch's local frame (y up): the grid
    /// point (i·L/N, 0, j·L/N) plus (D_x, η, D_z).
    pub position: [f32; 3],
    /// Unit normal `[x, y, z]` of the displaced surface (dimensionless, y up).
    pub normal: [f32; 3],
}

impl Default for Vertex {
    /// At the origin with the normal straight up.
    fn default() -> Self {
        Vertex {
            position: [0.0; 3],
            normal: [0.0, 1.0, 0.0],
        }
    }
}

/// Which way the green channel of a tangent-space normal map points, for
/// [`Cascade::write_normal_map`]. The image's column i runs along +x (u, to the right) and
/// its row j along +z, with row 0 stored first (the top of the image): seen from above (from
/// +y) the image is the surface as it lies. Red is the normal's x, blue its y (the surface's
/// up).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NormalMapGreen {
    /// Green points up the image (toward row 0, i.e. −z): G encodes −n_z. The "Y+" maps of
    /// OpenGL, Bevy, Blender, Godot, Unity and Maya (a right-handed tangent frame, T × B = N).
    OpenGl,
    /// Green points down the image (toward larger rows, i.e. +z): G encodes +n_z. The "Y−"
    /// maps of DirectX, Unreal, 3ds Max and Substance's DirectX preset.
    DirectX,
}

/// Texels one parallel task writes (whole rows; at least one row per task). The split depends
/// only on N, never on the number of threads.
const TEXELS_PER_TASK: usize = 8192;

/// Rows of an N×N grid one task handles.
fn rows_per_task(n: usize) -> usize {
    (TEXELS_PER_TASK / n).max(1)
}

/// The buffers a texel is packed from: one cascade's, and the foam on its grid (`None` where
/// the cascade carries none: its foam channel is 0; a bare cascade's layouts with foam are
/// refused before any packing).
struct Sources<'a> {
    height: &'a [f32],
    displacement: &'a [[f32; 2]],
    slope: &'a [[f32; 2]],
    normal: &'a [[f32; 3]],
    jacobian: &'a [f32],
    foam: Option<&'a [f32]>,
    /// The sub-grid mean-square slope of the cascade (alpha of the normal layout).
    roughness: f32,
}

impl<'a> Sources<'a> {
    fn new(cascade: &'a Cascade, foam: Option<&'a [f32]>) -> Sources<'a> {
        Sources {
            height: cascade.height(),
            displacement: cascade.displacement(),
            slope: cascade.slope(),
            normal: cascade.normal(),
            jacobian: cascade.jacobian(),
            foam,
            roughness: cascade.subgrid_slope_variance().total(),
        }
    }

    /// The f32 texels of `layout` for grid indices `start..start + out.len()`.
    fn fill(&self, layout: TexelLayout, start: usize, out: &mut [[f32; 4]]) {
        let range = start..start + out.len();
        let height = &self.height[range.clone()];
        let displacement = &self.displacement[range.clone()];
        let jacobian = &self.jacobian[range.clone()];
        match layout {
            TexelLayout::DisplacementJacobian => {
                for (texel, ((&eta, d), &j)) in out
                    .iter_mut()
                    .zip(height.iter().zip(displacement).zip(jacobian))
                {
                    *texel = [d[0], eta, d[1], j];
                }
            }
            TexelLayout::DisplacementFoam => match self.foam {
                Some(foam) => {
                    for (texel, ((&eta, d), &f)) in out
                        .iter_mut()
                        .zip(height.iter().zip(displacement).zip(&foam[range]))
                    {
                        *texel = [d[0], eta, d[1], f];
                    }
                }
                None => {
                    for (texel, (&eta, d)) in out.iter_mut().zip(height.iter().zip(displacement)) {
                        *texel = [d[0], eta, d[1], 0.0];
                    }
                }
            },
            TexelLayout::SlopeJacobianFoam => {
                let slope = &self.slope[range.clone()];
                match self.foam {
                    Some(foam) => {
                        for (texel, ((s, &j), &f)) in out
                            .iter_mut()
                            .zip(slope.iter().zip(jacobian).zip(&foam[range]))
                        {
                            *texel = [s[0], s[1], j, f];
                        }
                    }
                    None => {
                        for (texel, (s, &j)) in out.iter_mut().zip(slope.iter().zip(jacobian)) {
                            *texel = [s[0], s[1], j, 0.0];
                        }
                    }
                }
            }
            TexelLayout::Normal => {
                let roughness = self.roughness;
                for (texel, n) in out.iter_mut().zip(&self.normal[range]) {
                    *texel = [n[0], n[1], n[2], roughness];
                }
            }
        }
    }

    /// RGBA32F texels of `layout` into `out` (N² long), row blocks in parallel.
    fn pack_f32(&self, n: usize, layout: TexelLayout, out: &mut [[f32; 4]]) {
        let block = rows_per_task(n) * n;
        out.par_chunks_mut(block)
            .enumerate()
            .for_each(|(b, texels)| self.fill(layout, b * block, texels));
    }

    /// RGBA16F texels of `layout` into `out` (N² long), row blocks in parallel: each block
    /// packed in f32 on the stack, saturated to ±[`F16_MAX`], then converted by `half`'s
    /// slice conversion (round to nearest, ties to even; F16C or the Arm fp16 instructions
    /// where the CPU has them).
    #[cfg(feature = "half")]
    fn pack_f16(&self, n: usize, layout: TexelLayout, out: &mut [[half::f16; 4]]) {
        use half::slice::HalfFloatSliceExt;
        const STACK: usize = 256;
        let block = rows_per_task(n) * n;
        out.par_chunks_mut(block)
            .enumerate()
            .for_each(|(b, texels)| {
                let mut buffer = [[0.0f32; 4]; STACK];
                for (c, chunk) in texels.chunks_mut(STACK).enumerate() {
                    let values = &mut buffer[..chunk.len()];
                    self.fill(layout, b * block + c * STACK, values);
                    let flat = values.as_flattened_mut();
                    for v in flat.iter_mut() {
                        *v = saturate_f16(*v);
                    }
                    chunk.as_flattened_mut().convert_from_f32_slice(flat);
                }
            });
    }
}

/// Largest finite f16, 65504.
#[cfg(feature = "half")]
const F16_MAX: f32 = 65504.0;

/// `value` clamped to ±[`F16_MAX`] (a NaN, which no buffer holds, would give −65504).
#[cfg(feature = "half")]
#[inline]
// Not `clamp`: max/min return the other operand for a NaN, so the result is never NaN.
#[allow(clippy::manual_clamp)]
fn saturate_f16(value: f32) -> f32 {
    value.max(-F16_MAX).min(F16_MAX)
}

/// Refuses a layout with foam on a bare cascade.
fn check_cascade_layout(layout: TexelLayout) -> Result<(), Error> {
    if layout.has_foam() {
        return Err(Error::NotApplicable {
            name: "layout",
            reason:
                "a bare Cascade holds no foam: pack this layout with OceanState::textures().pack",
        });
    }
    Ok(())
}

/// One row of vertices at z₀ = `z0` (m) from its sources: a function of its own, indexed
/// over slices of one length, so that the loop needs no bounds checks.
#[inline(never)]
fn vertex_row(
    z0: f64,
    spacing: f64,
    height: &[f32],
    displacement: &[[f32; 2]],
    normal: &[[f32; 3]],
    out: &mut [Vertex],
) {
    let len = out.len();
    let (height, displacement, normal) = (&height[..len], &displacement[..len], &normal[..len]);
    for i in 0..len {
        let x0 = f64::from(i as u32) * spacing;
        let d = displacement[i];
        out[i] = Vertex {
            position: [
                (x0 + f64::from(d[0])) as f32,
                height[i],
                (z0 + f64::from(d[1])) as f32,
            ],
            normal: normal[i],
        };
    }
}

/// Encodes one component c ∈ [−1, 1] as the integer nearest to 127.5·(c + 1), ties to even,
/// clamped to 0..=255, as a u32 (0 for a NaN, which no normal holds).
#[inline]
#[allow(clippy::manual_clamp)] // max/min, not clamp: a NaN becomes 0
fn unorm8(c: f32) -> u32 {
    const ROUNDER: f32 = 8_388_608.0; // 2²³: adding it rounds to an integer, ties to even
    let x = ((c + 1.0) * 127.5).max(0.0).min(255.0);
    // 2²³ + x has x's rounded value in the low mantissa bits (without a float-to-int
    // conversion, so that the loop vectorises).
    (x + ROUNDER).to_bits() - ROUNDER.to_bits()
}

impl Cascade {
    /// Packs the buffers into interleaved RGBA32F texels of `layout` (see [`TexelLayout`] for
    /// each channel's meaning and units), texel (i, j) at `out[j * N + i]`. Copies the
    /// buffers' values bit for bit. Row blocks in parallel; allocates nothing inside a rayon
    /// pool; the result does not depend on the number of threads.
    ///
    /// # Errors
    /// [`Error::NotApplicable`] naming `layout` for a layout with foam (a bare cascade has
    /// none: use [`Textures::pack`]); [`Error::LengthMismatch`] naming `out` unless
    /// `out.len()` is N². Nothing is written then.
    pub fn pack_texels(&self, layout: TexelLayout, out: &mut [[f32; 4]]) -> Result<(), Error> {
        check_cascade_layout(layout)?;
        error::length("out", out.len(), self.n_squared())?;
        Sources::new(self, None).pack_f32(self.size(), layout, out);
        Ok(())
    }

    /// [`Cascade::pack_texels`] into RGBA16F texels (with the `half` feature): each channel
    /// rounded to the nearest f16 (ties to even, as `half::f16::from_f32`), and values beyond
    /// the f16 range **saturate** to ±65504 (never ±∞ or NaN). f16 keeps 11 significant bits:
    /// a relative step of 2⁻¹¹ ≈ 4.9e-4 (a displacement of 10 m to within 4 mm, a slope of 1
    /// to within 2.5e-4).
    ///
    /// # Errors
    /// As [`Cascade::pack_texels`]; nothing is written then.
    #[cfg(feature = "half")]
    pub fn pack_texels_f16(
        &self,
        layout: TexelLayout,
        out: &mut [[half::f16; 4]],
    ) -> Result<(), Error> {
        check_cascade_layout(layout)?;
        error::length("out", out.len(), self.n_squared())?;
        Sources::new(self, None).pack_f16(self.size(), layout, out);
        Ok(())
    }

    /// Writes the cascade as a vertex array: vertex (i, j) at `out[j * N + i]` has position
    /// (i·L/N + D_x, η, j·L/N + D_z) in metres in the patch's local frame (y up; the grid
    /// point computed and displaced in f64 and rounded once to f32) and the unit normal of
    /// the displaced surface. The N×N vertices span [0, (N−1)·L/N] on each axis before
    /// displacement; [`Cascade::triangle_indices`] gives the triangles between them. Row
    /// blocks in parallel; allocates nothing inside a rayon pool; the result does not depend
    /// on the number of threads.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] naming `out` unless `out.len()` is N²; nothing is written
    /// then.
    pub fn write_vertices(&self, out: &mut [Vertex]) -> Result<(), Error> {
        error::length("out", out.len(), self.n_squared())?;
        let n = self.size();
        let spacing = f64::from(self.length()) / n as f64;
        let (height, displacement, normal) = (self.height(), self.displacement(), self.normal());
        let rows = rows_per_task(n);
        out.par_chunks_mut(rows * n)
            .enumerate()
            .for_each(|(b, block)| {
                for (r, row) in block.chunks_mut(n).enumerate() {
                    let j = b * rows + r;
                    // Through u32 (N ≤ 4096): a u32 converts to f64 in one instruction.
                    let z0 = f64::from(j as u32) * spacing;
                    let range = j * n..(j + 1) * n;
                    vertex_row(
                        z0,
                        spacing,
                        &height[range.clone()],
                        &displacement[range.clone()],
                        &normal[range],
                        row,
                    );
                }
            });
        Ok(())
    }

    /// The triangles of the mesh [`Cascade::write_vertices`] writes: two per grid cell
    /// between vertices (i, j) and (i + 1, j + 1) for i, j < N − 1, 2·(N − 1)² triangles of
    /// vertex indices `j * N + i`, cell by cell in row order. Each is counter-clockwise seen
    /// from above (+y), so its face normal (p₁ − p₀) × (p₂ − p₀) points up on an undisplaced
    /// grid: cell (i, j) gives [a, c, b] and [b, c, d] with a = (i, j), b = (i + 1, j),
    /// c = (i, j + 1), d = (i + 1, j + 1). The mesh does not wrap: tiles placed L apart leave
    /// one cell between them, which the caller closes (for example with the next tile's first
    /// row and column).
    pub fn triangle_indices(&self) -> impl ExactSizeIterator<Item = [u32; 3]> + Send {
        let n = self.size();
        let cells = n - 1;
        // N ≤ 4096, so every index fits u32.
        (0..2 * cells * cells).map(move |t| {
            let cell = t / 2;
            let (i, j) = (cell % cells, cell / cells);
            let a = (j * n + i) as u32;
            let (b, c, d) = (a + 1, a + n as u32, a + n as u32 + 1);
            if t % 2 == 0 {
                [a, c, b]
            } else {
                [b, c, d]
            }
        })
    }

    /// Writes a tangent-space normal map of the normals as RGBA8: pixel (i, j) at
    /// `out[j * N + i]` is column i (+x, to the right) and row j (+z, down the image, row 0
    /// first), with
    ///
    /// R = round(127.5·(n_x + 1)), G = round(127.5·(g + 1)), B = round(127.5·(n_y + 1)),
    /// A = 255,
    ///
    /// where g = −n_z for [`NormalMapGreen::OpenGl`] (green up the image) and g = +n_z for
    /// [`NormalMapGreen::DirectX`] (green down the image), and round() the nearest integer,
    /// ties to even (clamped to 0..=255). Flat water is (128, 128, 255, 255).
    /// The normal of texel (i, j) is that of the water displaced from grid point (i, j), as
    /// for the other textures. Where the surface folds, n_y < 0 and B < 128. Row blocks in
    /// parallel; allocates nothing inside a rayon pool; the result does not depend on the
    /// number of threads.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] naming `out` unless `out.len()` is N²; nothing is written
    /// then.
    pub fn write_normal_map(
        &self,
        green: NormalMapGreen,
        out: &mut [[u8; 4]],
    ) -> Result<(), Error> {
        error::length("out", out.len(), self.n_squared())?;
        let block = rows_per_task(self.size()) * self.size();
        let sign = match green {
            NormalMapGreen::OpenGl => -1.0f32,
            NormalMapGreen::DirectX => 1.0,
        };
        let normal = self.normal();
        out.par_chunks_mut(block)
            .enumerate()
            .for_each(|(b, pixels)| {
                let start = b * block;
                let normals = &normal[start..start + pixels.len()];
                for (pixel, n) in pixels.iter_mut().zip(normals) {
                    let rgba =
                        unorm8(n[0]) | unorm8(sign * n[2]) << 8 | unorm8(n[1]) << 16 | 255 << 24;
                    *pixel = rgba.to_le_bytes();
                }
            });
        Ok(())
    }

    fn n_squared(&self) -> usize {
        self.size() * self.size()
    }
}

#[cfg(all(test, feature = "half"))]
mod tests {
    use super::*;
    use half::f16;

    #[test]
    fn f16_saturates_beyond_its_range_and_rounds_to_nearest_within() {
        let cases = [
            (0.0f32, f16::from_f32(0.0)),
            (1.0, f16::ONE),
            (65504.0, f16::MAX),
            (65519.0, f16::MAX),
            (65520.0, f16::MAX),
            (1e6, f16::MAX),
            (f32::MAX, f16::MAX),
            (f32::INFINITY, f16::MAX),
            (-65520.0, f16::MIN),
            (-f32::MAX, f16::MIN),
            (f32::NEG_INFINITY, f16::MIN),
        ];
        for (value, expected) in cases {
            let got = f16::from_f32(saturate_f16(value));
            assert_eq!(got.to_bits(), expected.to_bits(), "{value}");
        }
        // Beyond the clamp the plain conversion overflows: the clamp is what saves it.
        assert!(f16::from_f32(65520.0).is_infinite());
        assert!(!f16::from_f32(saturate_f16(f32::NAN)).is_nan());
    }
}
