//! What the world queries return: the surface at a point ([`SurfaceSample`]) and where the
//! water at a point comes from ([`Location`]).

use glam::{Vec2, Vec3};

/// The surface at one undisplaced world point, summed over the cascades.
///
/// `#[repr(C)]`: nine `f32` in the order of the fields, without padding (36 bytes). With the
/// `bytemuck` feature it is `bytemuck::Pod` and `bytemuck::Zeroable`, so
/// `bytemuck::cast_slice` views a `&[SurfaceSample]` as `&[f32]` (or as a GPU buffer of
/// structs with the same layout) without copying.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
#[repr(C)]
pub struct SurfaceSample {
    /// Height η in metres.
    pub height: f32,
    /// Horizontal displacement `[x, z]` in metres (already × choppiness): the water at the
    /// undisplaced point sits at that point plus this.
    pub displacement: [f32; 2],
    /// Slope `[∂y/∂x, ∂y/∂z]` of the displaced surface, dimensionless: the sum of the
    /// cascades' slopes.
    pub slope: [f32; 2],
    /// Unit normal `[x, y, z]` of the displaced surface (y up), from the summed slope.
    pub normal: [f32; 3],
    /// Foam coverage in [0, 1]: the ocean's one foam field
    /// ([`FoamView::total`](crate::FoamView::total), on cascade 0's grid) interpolated
    /// bilinearly, the fraction of the sea around the point that foam covers (the expectation
    /// of the foam itself, which [`FoamView::foam_at`](crate::FoamView::foam_at) gives
    /// patterned at the breaking scale); 0 from a range of cascades without cascade 0
    /// ([`Water::at_rest_cascades`](crate::Water::at_rest_cascades)), as cascade 0's
    /// textures carry the foam.
    pub foam: f32,
}

impl Default for SurfaceSample {
    /// Flat, still water: zero height, displacement and slope, the normal straight up, no
    /// foam.
    fn default() -> Self {
        SurfaceSample {
            height: 0.0,
            displacement: [0.0; 2],
            slope: [0.0; 2],
            normal: [0.0, 1.0, 0.0],
            foam: 0.0,
        }
    }
}

/// Where the water at a world point comes from: the result of
/// [`Water::locate`](crate::Water::locate).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Location {
    /// The undisplaced world point `[x, z]` in metres whose water lands on the query point
    /// (the best one found).
    pub undisplaced: [f64; 2],
    /// Distance in metres between the query point and where the water at `undisplaced`
    /// actually lands (0 for an exact inversion).
    pub miss: f32,
    /// Newton steps it took to reach `undisplaced` from the search's first guess (0: the
    /// first guess itself, one Newton step on the larger cascades from the query point less
    /// the smaller cascades' displacement there), at most
    /// [`QueryConfig::max_iterations`](crate::QueryConfig::max_iterations).
    pub iterations: usize,
    /// Whether `miss` is below [`QueryConfig::tolerance`](crate::QueryConfig::tolerance).
    pub converged: bool,
}

/// Unit normal (−s_x, 1, −s_z)/|…| of a surface with slope `slope`.
#[inline(always)]
pub(crate) fn normal_from_slope(slope: Vec2) -> Vec3 {
    Vec3::new(-slope.x, 1.0, -slope.y).normalize_or(Vec3::Y)
}

/// The [`SurfaceSample`] of summed fields and foam `foam` (as the single queries build it).
#[inline(always)]
pub(crate) fn surface(
    height: f32,
    displacement: [f32; 2],
    slope: [f32; 2],
    foam: f32,
) -> SurfaceSample {
    SurfaceSample {
        height,
        displacement,
        slope,
        normal: normal_from_slope(Vec2::from_array(slope)).to_array(),
        foam,
    }
}
