//! Every cascade's texels with their mip chains, in the RGBA16F an engine uploads.

use ocean_fft::gpu::TexelLayout;
use ocean_fft::half::f16;
use ocean_fft::half::slice::HalfFloatSliceExt;
use ocean_fft::{Error, OceanState};
use rayon::prelude::*;

use crate::info::MAX_CASCADES;

/// Texels one parallel task of the box filter and the f16 conversion handles.
const CHUNK: usize = 4096;

/// Mip levels of an N×N texture whose side halves while it is even (at most 13: 4096²).
pub fn mip_levels(n: usize) -> usize {
    (n.trailing_zeros() as usize + 1).min(13)
}

/// One frame's textures: every cascade's `DisplacementFoam` (D_x, η, D_z, foam; m) and
/// `SlopeJacobianFoam` (∂y/∂x, ∂y/∂z, J, foam; dimensionless) texels, RGBA16F, with their
/// mip chains (2×2 box means), layer-major: layer c's level m starts at
/// `c * layer_len + level_offsets[m]`. Level 0 is the crate's own `pack_texels_f16`, bit for
/// bit. Buffers are kept from frame to frame: packing allocates only when the grid changed.
#[derive(Debug, Clone, Default)]
pub struct Texels {
    /// `DisplacementFoam` texels of every layer and level.
    pub displacement: Vec<[f16; 4]>,
    /// `SlopeJacobianFoam` texels of every layer and level.
    pub slope: Vec<[f16; 4]>,
    /// Texels of one layer's whole mip chain.
    pub layer_len: usize,
    /// Where each mip level starts inside a layer.
    pub level_offsets: Vec<usize>,
    /// Grid size N (level 0's side) and number of layers packed.
    pub size: usize,
    /// Cascades packed (at most [`MAX_CASCADES`]).
    pub cascades: usize,
    /// Standard deviation of the summed J − 1 over the grid (the bands are independent, so
    /// their variances add), dimensionless.
    pub jacobian_sd: f32,
    /// f32 scratch: one layer's mip chain.
    scratch: Vec<[f32; 4]>,
}

/// One mip level of one layer, ready for a texture upload.
#[derive(Debug, Clone, Copy)]
pub struct Level<'a> {
    /// The cascade (array layer).
    pub layer: usize,
    /// The mip level (0: N×N).
    pub level: usize,
    /// Texels a side (N >> level).
    pub side: usize,
    /// The level's `side × side` texels, row-major.
    pub texels: &'a [[f16; 4]],
}

impl Texels {
    /// Sizes the buffers for N = `n` and `cascades` layers (allocates only when they change).
    fn fit(&mut self, n: usize, cascades: usize) {
        let levels = mip_levels(n);
        let layer_len: usize = (0..levels).map(|m| (n >> m) * (n >> m)).sum();
        if self.layer_len == layer_len && self.displacement.len() == layer_len * cascades {
            return;
        }
        self.level_offsets = (0..levels)
            .map(|m| (0..m).map(|k| (n >> k) * (n >> k)).sum())
            .collect();
        self.layer_len = layer_len;
        self.displacement = vec![[f16::ZERO; 4]; layer_len * cascades];
        self.slope = vec![[f16::ZERO; 4]; layer_len * cascades];
        self.scratch = vec![[0.0; 4]; layer_len];
    }

    /// Packs every cascade of `ocean` (at most [`MAX_CASCADES`]) with its mip chains.
    ///
    /// # Errors
    /// The crate's from `pack_texels`; the buffers hold a partial frame then.
    pub fn pack(&mut self, ocean: &OceanState) -> Result<(), Error> {
        let n = ocean.config().size;
        let cascades = ocean.cascades().len().min(MAX_CASCADES);
        self.fit(n, cascades);
        self.size = n;
        self.cascades = cascades;
        let mut jacobian_variance = 0.0f64;
        for c in 0..cascades {
            for layout in [
                TexelLayout::DisplacementFoam,
                TexelLayout::SlopeJacobianFoam,
            ] {
                let chain = &mut self.scratch;
                ocean.textures().pack(c, layout, &mut chain[..n * n])?;
                if layout == TexelLayout::SlopeJacobianFoam {
                    jacobian_variance += channel_variance(&chain[..n * n], 2);
                }
                for m in 1..self.level_offsets.len() {
                    let (done, rest) = chain.split_at_mut(self.level_offsets[m]);
                    let side = n >> m;
                    downsample(
                        &done[self.level_offsets[m - 1]..],
                        &mut rest[..side * side],
                        side,
                    );
                }
                let out = match layout {
                    TexelLayout::DisplacementFoam => &mut self.displacement,
                    _ => &mut self.slope,
                };
                out[c * self.layer_len..(c + 1) * self.layer_len]
                    .par_chunks_mut(CHUNK)
                    .zip(chain.par_chunks(CHUNK))
                    .for_each(|(half, full)| {
                        half.as_flattened_mut()
                            .convert_from_f32_slice(full.as_flattened());
                    });
            }
        }
        self.jacobian_sd = jacobian_variance.sqrt() as f32;
        Ok(())
    }

    /// Every layer's every mip level of `texels` (this frame's `displacement` or `slope`),
    /// in upload order.
    pub fn levels<'a>(&'a self, texels: &'a [[f16; 4]]) -> impl Iterator<Item = Level<'a>> + 'a {
        (0..self.cascades).flat_map(move |layer| {
            self.level_offsets
                .iter()
                .enumerate()
                .map(move |(level, &offset)| {
                    let side = self.size >> level;
                    let first = layer * self.layer_len + offset;
                    Level {
                        layer,
                        level,
                        side,
                        texels: &texels[first..first + side * side],
                    }
                })
        })
    }
}

/// Variance of channel `k` of `texels` (sums in f64, in order, so the result does not depend
/// on the number of threads).
fn channel_variance(texels: &[[f32; 4]], k: usize) -> f64 {
    let (sum, sum2) = texels.iter().fold((0.0f64, 0.0f64), |(s, s2), t| {
        let v = f64::from(t[k]);
        (s + v, s2 + v * v)
    });
    let count = texels.len() as f64;
    let mean = sum / count;
    (sum2 / count - mean * mean).max(0.0)
}

/// Mip level of side `side` (in `target`) as 2×2 means of the level of side 2·side in
/// `source`.
fn downsample(source: &[[f32; 4]], target: &mut [[f32; 4]], side: usize) {
    let wide = 2 * side;
    let rows_per_block = (CHUNK / side).max(1);
    target
        .par_chunks_mut(rows_per_block * side)
        .enumerate()
        .for_each(|(block, rows)| {
            for (r, row) in rows.chunks_mut(side).enumerate() {
                let j = block * rows_per_block + r;
                let (top, bottom) = (&source[2 * j * wide..], &source[(2 * j + 1) * wide..]);
                for (i, texel) in row.iter_mut().enumerate() {
                    let (a, b, c, d) =
                        (top[2 * i], top[2 * i + 1], bottom[2 * i], bottom[2 * i + 1]);
                    *texel = std::array::from_fn(|k| 0.25 * (a[k] + b[k] + c[k] + d[k]));
                }
            }
        });
}

#[cfg(test)]
mod tests {
    use super::*;
    use ocean_fft::{OceanConfig, Spectrum};

    /// The mip chain's levels are 2×2 box means of the level above: checked against a direct
    /// mean over the 2^m × 2^m block of level 0 (in f64), for a random-looking field.
    #[test]
    fn mip_levels_are_block_means_of_level_zero() {
        let n = 16;
        let levels = mip_levels(n);
        assert_eq!(levels, 5);
        let mut chain = vec![[0.0f32; 4]; (0..levels).map(|m| (n >> m) * (n >> m)).sum()];
        for (index, texel) in chain[..n * n].iter_mut().enumerate() {
            let v = ((index * 7919) % 101) as f32 / 10.0 - 5.0;
            *texel = [v, -v, 0.5 * v, 1.0];
        }
        let mut offsets = vec![0];
        for m in 1..levels {
            offsets.push(offsets[m - 1] + (n >> (m - 1)) * (n >> (m - 1)));
        }
        for m in 1..levels {
            let side = n >> m;
            let (done, rest) = chain.split_at_mut(offsets[m]);
            downsample(&done[offsets[m - 1]..], &mut rest[..side * side], side);
        }
        for m in 0..levels {
            let side = n >> m;
            let block = 1 << m;
            for j in 0..side {
                for i in 0..side {
                    let mut mean = 0.0f64;
                    for y in 0..block {
                        for x in 0..block {
                            mean += f64::from(chain[(j * block + y) * n + i * block + x][0]);
                        }
                    }
                    mean /= (block * block) as f64;
                    let got = f64::from(chain[offsets[m] + j * side + i][0]);
                    // Pairwise f32 means of values below 5 in magnitude: a few ulps of 5.
                    assert!(
                        (got - mean).abs() < 1e-5,
                        "level {m} ({i}, {j}): {got} vs {mean}"
                    );
                }
            }
        }
    }

    /// Packed texels carry the crate's own f16 texels at level 0, bit for bit, in every
    /// layer, and `levels` walks every layer and level once with the right sizes.
    #[test]
    fn level_zero_is_the_crates_f16_packing() {
        let config = OceanConfig {
            size: 32,
            ..OceanConfig::default()
        };
        let spectrum = Spectrum::jonswap(12.0, 200_000.0).unwrap();
        let mut ocean = OceanState::new(spectrum, config).unwrap();
        ocean.step(0.5).unwrap();
        let mut texels = Texels::default();
        texels.pack(&ocean).unwrap();
        let mut expected = vec![[f16::ZERO; 4]; 32 * 32];
        for c in 0..ocean.cascades().len() {
            for (layout, buffer) in [
                (TexelLayout::DisplacementFoam, &texels.displacement),
                (TexelLayout::SlopeJacobianFoam, &texels.slope),
            ] {
                ocean.textures().pack_f16(c, layout, &mut expected).unwrap();
                let level = texels
                    .levels(buffer)
                    .find(|l| l.layer == c && l.level == 0)
                    .unwrap();
                let same = level
                    .texels
                    .iter()
                    .zip(&expected)
                    .all(|(a, b)| a.map(f16::to_bits) == b.map(f16::to_bits));
                assert!(same, "cascade {c}, {layout:?}");
            }
        }
        let levels: Vec<(usize, usize, usize)> = texels
            .levels(&texels.slope)
            .map(|l| (l.layer, l.level, l.side))
            .collect();
        assert_eq!(levels.len(), ocean.cascades().len() * 6);
        assert_eq!(levels[7], (1, 1, 16));
        assert_eq!(
            levels.iter().map(|l| l.2 * l.2).sum::<usize>(),
            texels.slope.len()
        );
    }
}
