//! The foam's streak field as an engine draws it: the library's `FoamStreaks` texels in
//! R16F ([`StreakTexels`], uploaded once per ocean) and where they lie each frame
//! (`OceanInfo::streaks`, `OceanUniforms::streaks`).

use ocean_fft::gpu::FoamStreaks;
use ocean_fft::half::f16;
use ocean_fft::OceanState;

/// The streak field's texels (mean 0, variance 1), R16F, `across` texels a row and `along`
/// rows (texel (i across, j along) at `j * across + i`); upload to a texture with repeat
/// addressing and linear filtering when [`fingerprint`](Self::fingerprint) changes (a new
/// ocean). Packing copies only when the field changed.
#[derive(Debug, Clone, Default)]
pub struct StreakTexels {
    /// The texels (empty before the first pack).
    pub texels: Vec<f16>,
    /// Texels across the wind (the texture's width) and along it (its height).
    pub across: usize,
    pub along: usize,
    /// A fingerprint of the field held (its sizes and 16 texels' bits, hashed; 0: none), the
    /// same in every frame that holds the same field.
    pub fingerprint: u64,
}

/// The fingerprint of a streak field: its sizes and 16 of its texels' bits, FNV-1a hashed
/// (never 0; allocates nothing).
fn fingerprint(streaks: &FoamStreaks<'_>) -> u64 {
    let t = streaks.texels;
    let mut words = [0u32; 18];
    words[0] = t.len() as u32;
    words[1] = streaks.across_texels as u32;
    if !t.is_empty() {
        for (k, word) in words[2..].iter_mut().enumerate() {
            *word = t[k * (t.len() - 1) / 15].to_bits();
        }
    }
    let hash = words.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, w| {
        (h ^ u64::from(*w)).wrapping_mul(0x0100_0000_01b3)
    });
    hash.max(1)
}

impl StreakTexels {
    /// Copies `ocean`'s streak field when it differs from the one held (allocates then).
    pub fn pack(&mut self, ocean: &OceanState) {
        let streaks = ocean.textures().foam_streaks();
        let fingerprint = fingerprint(&streaks);
        if fingerprint == self.fingerprint {
            return;
        }
        self.fingerprint = fingerprint;
        self.texels = streaks.texels.iter().map(|&v| f16::from_f32(v)).collect();
        self.across = streaks.across_texels;
        self.along = streaks.along_texels;
    }
}

/// `OceanUniforms::streaks` and `streak_scale` for the field's placement now: (a₀, a₁, the
/// origin across and along, m) and (1/(spacing·texels) across and along, 1/m; the texels
/// across and along).
pub fn streak_uniforms(streaks: &FoamStreaks<'_>) -> ([f32; 4], [f32; 4]) {
    let (na, nl) = (streaks.across_texels as f32, streaks.along_texels as f32);
    (
        [
            streaks.axis[0],
            streaks.axis[1],
            streaks.origin[0],
            streaks.origin[1],
        ],
        [
            1.0 / (streaks.spacing[0] * na),
            1.0 / (streaks.spacing[1] * nl),
            na,
            nl,
        ],
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use ocean_fft::SeaState;

    /// The texels are the library's in f16, packed once per field: a second pack of the same
    /// ocean keeps the fingerprint, a new ocean's field changes it.
    #[test]
    fn packs_once_per_field() {
        let (spectrum, mut config) = SeaState::FreshBreeze.build();
        config.size = 32;
        let ocean = OceanState::new(spectrum.clone(), config.clone()).unwrap();
        let mut texels = StreakTexels::default();
        texels.pack(&ocean);
        let first = texels.fingerprint;
        assert_ne!(first, 0);
        let field = ocean.textures().foam_streaks();
        assert_eq!(
            (texels.across, texels.along),
            (field.across_texels, field.along_texels)
        );
        assert_eq!(texels.texels.len(), field.texels.len());
        for (a, b) in texels.texels.iter().zip(field.texels) {
            assert_eq!(*a, f16::from_f32(*b));
        }
        texels.pack(&ocean);
        assert_eq!(texels.fingerprint, first);
        config.seed += 1;
        let other = OceanState::new(spectrum, config).unwrap();
        texels.pack(&other);
        assert_ne!(texels.fingerprint, first);
        let (place, scale) = streak_uniforms(&other.textures().foam_streaks());
        assert_eq!(place[..2], other.textures().foam_streaks().axis[..]);
        assert!((scale[0] * 0.25 * scale[2] - 1.0).abs() < 1e-6, "{scale:?}");
    }
}
