//! What a shader needs to know about the ocean besides its textures ([`OceanInfo`]), and the
//! table of the slope variance its pixels do not resolve, kept while the sea stays the same.

use ocean_fft::{Error, OceanConfig, OceanState, Spectrum};

/// Most cascades the reference shader takes (the size of its per-cascade arrays).
pub const MAX_CASCADES: usize = 8;
/// Entries of the table of unresolved slope variance ([`OceanInfo::slope_table`]).
pub const SLOPE_TABLE: usize = 32;

/// What the shader needs about the ocean besides its textures, for the frame they hold.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct OceanInfo {
    /// Sea time of the textures, s.
    pub time: f64,
    /// Number of cascades the textures hold (at most [`MAX_CASCADES`]).
    pub cascades: usize,
    /// Side L of each cascade's tile, m (0 past `cascades`).
    pub lengths: [f32; MAX_CASCADES],
    /// Grid size N of every cascade (texels a side).
    pub size: usize,
    /// Mip levels of every layer ([`mip_levels`](crate::mip_levels) of `size`).
    pub mip_levels: usize,
    /// Unit vector the wind blows toward, (x, z).
    pub wind: [f32; 2],
    /// Slope variance below the finest cascade's grid, along and across the wind
    /// (dimensionless; `OceanState::subgrid_slope_variance`).
    pub subgrid: [f32; 2],
    /// Standard deviation of the summed height, m.
    pub height_sd: f32,
    /// Standard deviation of the summed J − 1 (dimensionless), measured on the textures.
    pub jacobian_sd: f32,
    /// Entry i: a wave number k_i (rad/m, geometric from the lowest to the highest band
    /// limit) and the slope variance (along, across the wind) of the simulated waves above it.
    pub slope_table: [[f32; 3]; SLOPE_TABLE],
    /// Significant wave height of the spectrum, m.
    pub significant_wave_height: f32,
    /// Wavelength of the spectrum's peak, m.
    pub peak_wavelength: f32,
    /// Foam coverage of the whole sea (active + residual), area fraction in [0, 1].
    pub foam_total: f32,
    /// The share of that coverage that is active whitecaps (the rest residual foam), in
    /// [0, 1].
    pub foam_active_share: f32,
    /// Weight ŵ_c of each cascade's compression in the whitecaps' placement
    /// (`FoamView::whitecap_weights`; dimensionless, 0 past `cascades`).
    pub whitecap_weights: [f32; MAX_CASCADES],
    /// The streak field's placement now ([`streak_uniforms`](crate::streak_uniforms)).
    pub streaks: [f32; 4],
    pub streak_scale: [f32; 4],
}

/// The slope-variance table and the spectrum and grids it was computed for: 32 integrals of
/// the spectrum, computed again only when they change (so a frame allocates nothing).
#[derive(Debug, Clone, Default)]
pub struct SlopeTable {
    key: Option<(Spectrum, OceanConfig)>,
    table: [[f32; 3]; SLOPE_TABLE],
}

impl SlopeTable {
    /// The table of `ocean`'s sea (computed, and allocating, only if its spectrum or
    /// configuration changed since the last call).
    ///
    /// # Errors
    /// The crate's, for a configuration whose bands it cannot give.
    pub fn of(&mut self, ocean: &OceanState) -> Result<&[[f32; 3]; SLOPE_TABLE], Error> {
        let spectrum = ocean.spectrum();
        let config = ocean.config();
        let fresh = self
            .key
            .as_ref()
            .is_some_and(|(s, c)| s == spectrum && c == config);
        if !fresh {
            let bands = config.bands()?;
            let (bottom, top) = (bands[0].0.max(1e-3), bands[bands.len() - 1].1);
            for (i, entry) in self.table.iter_mut().enumerate() {
                let k = bottom * (top / bottom).powf(i as f32 / (SLOPE_TABLE - 1) as f32);
                let v = spectrum.slope_variance(k, top);
                *entry = [k, v.along, v.across];
            }
            self.key = Some((spectrum.clone(), config.clone()));
        }
        Ok(&self.table)
    }
}

impl OceanInfo {
    /// Everything but [`jacobian_sd`](Self::jacobian_sd) (which [`Texels::pack`](crate::Texels::pack)
    /// measures) from `ocean` as it is now, the slope table through `slopes`.
    ///
    /// # Errors
    /// The crate's, for a configuration whose bands it cannot give; `self` is unchanged then.
    pub fn update(&mut self, ocean: &OceanState, slopes: &mut SlopeTable) -> Result<(), Error> {
        let table = *slopes.of(ocean)?;
        let config = ocean.config();
        let spectrum = ocean.spectrum();
        self.time = ocean.time();
        self.cascades = ocean.cascades().len().min(MAX_CASCADES);
        self.lengths = [0.0; MAX_CASCADES];
        for (length, cascade) in self.lengths.iter_mut().zip(ocean.cascades()) {
            *length = cascade.length();
        }
        self.size = config.size;
        self.mip_levels = crate::mip_levels(config.size);
        self.wind = spectrum.wind_vector();
        let subgrid = ocean.textures().subgrid_slope_variance();
        self.subgrid = [subgrid.along, subgrid.across];
        self.height_sd = ocean.diagnostics().expected_variance().sqrt() as f32;
        self.slope_table = table;
        self.significant_wave_height = spectrum.significant_wave_height();
        let peak_k = spectrum.peak_omega().powi(2) / ocean_fft::GRAVITY;
        self.peak_wavelength = std::f32::consts::TAU / peak_k;
        let coverage = ocean.foam_view().coverage();
        self.foam_total = coverage.total;
        self.foam_active_share = if coverage.total > 0.0 {
            (coverage.active / coverage.total).clamp(0.0, 1.0)
        } else {
            1.0
        };
        let weights = ocean.foam_view().whitecap_weights();
        self.whitecap_weights = [0.0; MAX_CASCADES];
        for (out, w) in self.whitecap_weights.iter_mut().zip(weights) {
            *out = w;
        }
        (self.streaks, self.streak_scale) =
            crate::streak_uniforms(&ocean.textures().foam_streaks());
        Ok(())
    }
}
