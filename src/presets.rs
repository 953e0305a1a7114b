//! Named sea states: a spectrum and an ocean configuration that suit it.

use crate::error::Error;
use crate::ocean::OceanConfig;
use crate::spectrum::{Spectrum, Spreading};

/// A named sea state, with a Beaufort-like wind and the fetch and depth that go with it.
///
/// [`SeaState::build`] gives the spectrum and an [`OceanConfig`] whose cascade lengths are
/// fitted to the sea ([`OceanConfig::with_fitted_lengths`]: the largest tile 12 peak
/// wavelengths, holding at least 97 % of its variance). The significant wave heights and peak periods of every preset
/// are listed in the guide (`docs/guide/spectra.md`).
///
/// ```
/// use ocean_fft::{OceanState, SeaState};
/// let (spectrum, mut config) = SeaState::FreshBreeze.build();
/// config.size = 64;
/// let ocean = OceanState::new(spectrum, config)?;
/// assert_eq!(ocean.cascades().len(), 3);
/// # Ok::<(), ocean_fft::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum SeaState {
    /// Beaufort 2, light breeze: U10 = 2.5 m/s, fully developed (H_s 0.17 m, T_p 1.8 s).
    /// Small wavelets.
    Calm,
    /// Beaufort 4: U10 = 6.5 m/s, fully developed (H_s 1.2 m, T_p 4.8 s). Small waves,
    /// fairly frequent white horses.
    ModerateBreeze,
    /// Beaufort 5: U10 = 9.5 m/s, fully developed (H_s 2.5 m, T_p 6.9 s). Moderate waves,
    /// many white horses.
    FreshBreeze,
    /// Beaufort 10: U10 = 26 m/s over 500 km, choppiness 1.2 (H_s 12.2 m, T_p 14.7 s). High
    /// waves, breaking crests.
    Storm,
    /// A long, narrow swell from a distant storm: JONSWAP from parameters with T_p = 12 s,
    /// α = 0.0025, γ = 5, Hasselmann spreading with Horvath's swell control at 1 (H_s 4.4 m).
    /// Its whitecaps are those of a light local breeze, `FoamConfig::wind_speed` 4 m/s (the
    /// swell's own fully developed wind, 16.4 m/s, blows far away).
    Swell,
    /// TMA: U10 = 8 m/s over 15 km in 4 m of water (H_s 0.55 m, T_p 3.1 s). Short, steep,
    /// depth-limited waves.
    ShallowBay,
}

impl SeaState {
    /// Every preset, calmest first (the swell and the bay last).
    pub const ALL: [SeaState; 6] = [
        SeaState::Calm,
        SeaState::ModerateBreeze,
        SeaState::FreshBreeze,
        SeaState::Storm,
        SeaState::Swell,
        SeaState::ShallowBay,
    ];

    /// Short lowercase name (for file names and menus).
    pub fn name(self) -> &'static str {
        match self {
            SeaState::Calm => "calm",
            SeaState::ModerateBreeze => "moderate_breeze",
            SeaState::FreshBreeze => "fresh_breeze",
            SeaState::Storm => "storm",
            SeaState::Swell => "swell",
            SeaState::ShallowBay => "shallow_bay",
        }
    }

    /// Wind speed U10 in m/s at 10 m above the sea (for the swell, the wind its peak implies).
    pub fn wind_speed(self) -> f32 {
        match self {
            SeaState::Calm => 2.5,
            SeaState::ModerateBreeze => 6.5,
            SeaState::FreshBreeze => 9.5,
            SeaState::Storm => 26.0,
            // The wind speed 0.877 g/ω_p that the swell's peak implies.
            SeaState::Swell => 16.43,
            SeaState::ShallowBay => 8.0,
        }
    }

    /// The spectrum and ocean configuration of this sea state (size 256, seed 0; change
    /// them freely).
    pub fn build(self) -> (Spectrum, OceanConfig) {
        // Every preset's parameters are constants inside the checked ranges (the crate's
        // tests build each one), so this cannot fail.
        self.try_build()
            .expect("preset parameters lie inside the checked ranges")
    }

    fn try_build(self) -> Result<(Spectrum, OceanConfig), Error> {
        let u = self.wind_speed();
        let (spectrum, choppiness) = match self {
            SeaState::Calm => (Spectrum::jonswap(u, 20_000.0)?, 0.8),
            SeaState::ModerateBreeze => (Spectrum::jonswap(u, 100_000.0)?, 1.0),
            SeaState::FreshBreeze => (Spectrum::jonswap(u, 300_000.0)?, 1.0),
            SeaState::Storm => (Spectrum::jonswap(u, 500_000.0)?, 1.2),
            SeaState::Swell => {
                let peak_omega = std::f32::consts::TAU / 12.0;
                let spectrum = Spectrum::jonswap_from_parameters(0.0025, peak_omega, 5.0)?
                    .with_spreading(Spreading::Hasselmann)?
                    .with_swell(1.0)?;
                (spectrum, 0.8)
            }
            SeaState::ShallowBay => (Spectrum::tma(u, 15_000.0, 4.0)?, 1.0),
        };
        let mut config = OceanConfig {
            choppiness,
            ..OceanConfig::default()
        }
        .with_fitted_lengths(&spectrum)?;
        if self == SeaState::Swell {
            config.foam.wind_speed = Some(4.0);
        }
        Ok((spectrum, config))
    }
}
