//! The streak field of the foam's detail as a renderer samples it ([`FoamStreaks`],
//! re-exported from `gpu`).

/// The field that places the residual foam's streaks (docs/theory.md §15.8), laid out for a
/// texture: what [`Textures::foam_streaks`](crate::gpu::Textures::foam_streaks) returns. A shader
/// draws the residual foam where this field, sampled at the rest point, exceeds the threshold
/// that the coarse residual fraction sets — the same soft threshold
/// [`FoamView::foam_at`](crate::FoamView::foam_at) applies.
///
/// The texels never change: upload them once (one channel, f32, repeat addressing, linear
/// filtering). Only [`origin`](Self::origin) moves with the water each step.
///
/// Sampling at world rest point (x, z) in metres, as `foam_at` does: along = x·a₀ + z·a₁ −
/// origin\[1\], across = z·a₀ − x·a₁ − origin\[0\] with (a₀, a₁) = [`axis`](Self::axis);
/// texture coordinates (across / (spacing\[0\]·across_texels) + ½/across_texels, along /
/// (spacing\[1\]·along_texels) + ½/along_texels), the ½ texel putting texel i's value at
/// i·spacing. Divide the filtered value by √(k(f₀, ρ₀)·k(f₁, ρ₁)), k(f, ρ) = (1 − f)² + f² +
/// 2f(1 − f)ρ, f the fraction across the texel on each axis and ρ =
/// [`neighbour_correlation`](Self::neighbour_correlation), to keep unit variance between
/// texels (or skip it: the variance dips by at most (1 − ρ)/2 between them).
#[derive(Debug, Clone, Copy)]
pub struct FoamStreaks<'a> {
    /// The field, mean 0 and variance 1 over its texels: texel (i across, j along) at
    /// `texels[j * across_texels + i]`.
    pub texels: &'a [f32],
    /// Texels across the wind (a row's width).
    pub across_texels: usize,
    /// Texels along the wind (the number of rows).
    pub along_texels: usize,
    /// Spacing of the texels across and along the wind, m: `[across, along]`.
    pub spacing: [f32; 2],
    /// The wind's axis in the world's x–z plane, the unit vector (cos θ, sin θ) of the
    /// direction the wind blows toward.
    pub axis: [f32; 2],
    /// Where texel (0, 0) lies now, `[across, along]` m in the wind's frame, wrapped into
    /// one tile of the field (so f32 keeps its precision): the drift of the water's surface
    /// layer since the foam was made.
    pub origin: [f32; 2],
    /// Correlation of neighbouring texels, `[across, along]`, dimensionless: how much
    /// variance bilinear filtering keeps between them (see above).
    pub neighbour_correlation: [f32; 2],
}
