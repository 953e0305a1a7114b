//! The engine-independent side of docs/guide/rendering.md's section "Using ocean-fft from
//! Bevy, wgpu, macroquad and Godot": the functions that section shows, compiled here on glam 0.33 (the
//! glam of Bevy 0.20), so that the calls the Bevy and Godot code makes into ocean-fft are
//! compiled by CI even though those engines are not. `clients/engines-wgpu` calls them too.
//!
//! The guide quotes the code between the `// guide:` markers verbatim; the root crate's test
//! `tests/guide.rs` fails if the two drift apart.

// guide: OceanTexels
use glam::Vec3;
use ocean_fft::gpu::{Engine, TexelLayout};
use ocean_fft::half::f16;
use ocean_fft::{Cascade, Error, OceanState};

/// Two RGBA16F textures per cascade, allocated once and refilled every frame:
/// `displacement[c]` holds cascade c's `DisplacementFoam` texels (D_x, η, D_z, foam),
/// `slope[c]` its `SlopeJacobianFoam` texels (∂y/∂x, ∂y/∂z, J, foam); N×N, row j = z.
pub struct OceanTexels {
    pub displacement: Vec<Vec<[f16; 4]>>,
    pub slope: Vec<Vec<[f16; 4]>>,
}

impl OceanTexels {
    pub fn new(ocean: &OceanState) -> OceanTexels {
        let texels = |c: &Cascade| vec![[f16::ZERO; 4]; c.size() * c.size()];
        OceanTexels {
            displacement: ocean.cascades().iter().map(texels).collect(),
            slope: ocean.cascades().iter().map(texels).collect(),
        }
    }

    /// One frame of simulation: step by `dt` seconds, then pack every cascade. Allocates
    /// nothing inside a rayon pool.
    pub fn step_and_pack(&mut self, ocean: &mut OceanState, dt: f64) -> Result<(), Error> {
        ocean.step(dt)?;
        for c in 0..ocean.cascades().len() {
            ocean.textures().pack_f16(
                c,
                TexelLayout::DisplacementFoam,
                &mut self.displacement[c],
            )?;
            ocean
                .textures()
                .pack_f16(c, TexelLayout::SlopeJacobianFoam, &mut self.slope[c])?;
        }
        Ok(())
    }

    /// Cascade `c`'s two textures as the bytes a GPU API uploads: views, not copies.
    pub fn bytes(&self, c: usize) -> [&[u8]; 2] {
        [
            bytemuck::cast_slice(&self.displacement[c]),
            bytemuck::cast_slice(&self.slope[c]),
        ]
    }
}
// guide: end

// guide: water_point_under
/// The water surface under (or over) `position`, both in `engine`'s frame and units, and
/// whether the search for it converged (false on a folding crest: the point is then the best
/// one found, and a game may keep last frame's value instead).
pub fn water_point_under(
    ocean: &OceanState,
    engine: Engine,
    position: [f64; 3],
) -> Result<([f64; 3], bool), Error> {
    let [x, _, z] = engine.position_to_crate(position);
    let found = ocean.water().locate(x, z)?; // the undisplaced point whose water lands on (x, z)
    let [x0, z0] = found.undisplaced;
    let height = ocean.water().at_rest(x0, z0)?.height; // = ocean.water().height_at(x, z)
    Ok((engine.position([x, f64::from(height), z]), found.converged))
}
// guide: end

// guide: float_on_water
/// A buoy in Bevy: `translation` (a `Transform`'s, glam 0.33 `Vec3`, y up, metres) moved up or
/// down onto the water, or left where it is if the search did not converge.
pub fn float_on_water(ocean: &OceanState, translation: Vec3) -> Result<Vec3, Error> {
    let position = translation.as_dvec3().to_array();
    let (water, converged) = water_point_under(ocean, Engine::Bevy, position)?;
    Ok(if converged {
        Vec3::new(translation.x, water[1] as f32, translation.z)
    } else {
        translation
    })
}
// guide: end

// guide: engine_types
/// A buffer read with an engine's own types (glam 0.33 here, with its `bytemuck` feature; the
/// same cast gives Bevy's `Vec3`, whatever its glam version): one value, the whole buffer
/// without a copy, and a mint vector for nalgebra, cgmath and other mint users.
pub fn engine_types(cascade: &Cascade) -> (Vec3, &[Vec3], mint::Vector3<f32>) {
    let normals: &[[f32; 3]] = cascade.normal();
    let one = Vec3::from_array(normals[0]);
    let all: &[Vec3] = bytemuck::cast_slice(normals); // zero-copy: the same memory
    let mint: mint::Vector3<f32> = normals[0].into();
    (one, all, mint)
}
// guide: end
