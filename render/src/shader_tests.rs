//! shaders/ocean_common.wgsl checked by naga (the WGSL front end and validator wgpu and Bevy
//! compile it with): it parses and validates alone, holds no bindings and no entry points,
//! offers the functions the engines call, and its `OceanUniforms` has the Rust struct's
//! layout.

use naga::valid::{Capabilities, ValidationFlags, Validator};
use naga::TypeInner;

use crate::OceanUniforms;

const COMMON: &str = include_str!("../../shaders/ocean_common.wgsl");

/// Parses and validates `source` with the capabilities every wgpu adapter has (no optional
/// feature), failing with naga's own message.
fn validate(name: &str, source: &str) -> naga::Module {
    let module = naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("{name} does not parse:\n{}", e.emit_to_string(source)));
    Validator::new(ValidationFlags::all(), Capabilities::empty())
        .validate(&module)
        .unwrap_or_else(|e| panic!("{name} does not validate:\n{}", e.emit_to_string(source)));
    module
}

#[test]
fn the_shading_functions_stand_alone() {
    let module = validate("ocean_common.wgsl", COMMON);
    assert!(
        module.entry_points.is_empty(),
        "the library file has no entry points"
    );
    assert!(
        module.global_variables.is_empty(),
        "the library file has no bindings"
    );
    // The functions docs/guide/shader.md tells an engine to call.
    let names: Vec<&str> = module
        .functions
        .iter()
        .filter_map(|(_, f)| f.name.as_deref())
        .collect();
    for wanted in [
        "ocean_uv",
        "ocean_vertex_lod",
        "ocean_tiling_offset",
        "ocean_tiling_weights",
        "ocean_normal",
        "ocean_sky",
        "ocean_haze_colour",
        "ocean_sky_irradiance",
        "ocean_fresnel",
        "ocean_glitter",
        "ocean_whitecap_rank",
        "ocean_noise_gradient",
        "ocean_rotate",
        "ocean_detail_slope",
        "ocean_shade",
        "ocean_tone_map",
        "ocean_light",
        "ocean_morph",
        "ocean_displacement",
        "ocean_unresolved_variance",
        "ocean_water_surface",
        "ocean_varying",
        "ocean_wake_uv",
        "ocean_add_wake_displacement",
        "ocean_add_wake_surface",
        "ocean_streak_uv",
        "ocean_streak",
        "ocean_foam_layers",
        "ocean_foam_surface",
        "ocean_dither",
        "ocean_coast_uv",
        "ocean_coast",
        "ocean_coast_factor",
        "ocean_coast_displacement",
        "ocean_coast_water_surface",
        "ocean_coast_foam_surface",
    ] {
        assert!(
            names.contains(&wanted),
            "{wanted} is missing from ocean_common.wgsl"
        );
    }
}

/// The WGSL struct's size and member offsets as naga lays them out for a uniform buffer are
/// the Rust struct's, computed independently by rustc.
#[test]
fn the_uniforms_have_the_rust_layout() {
    let module = validate("ocean_common.wgsl", COMMON);
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).expect("layouts");
    let (handle, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some("OceanUniforms"))
        .expect("OceanUniforms is declared");
    let TypeInner::Struct { members, span } = &ty.inner else {
        panic!("OceanUniforms is not a struct");
    };
    assert_eq!(*span as usize, std::mem::size_of::<OceanUniforms>());
    assert_eq!(layouter[handle].size, *span);
    let rust = [
        ("sun", std::mem::offset_of!(OceanUniforms, sun)),
        (
            "sun_colour",
            std::mem::offset_of!(OceanUniforms, sun_colour),
        ),
        ("zenith", std::mem::offset_of!(OceanUniforms, zenith)),
        ("horizon", std::mem::offset_of!(OceanUniforms, horizon)),
        ("deep", std::mem::offset_of!(OceanUniforms, deep)),
        (
            "subsurface",
            std::mem::offset_of!(OceanUniforms, subsurface),
        ),
        ("wind", std::mem::offset_of!(OceanUniforms, wind)),
        ("tiling", std::mem::offset_of!(OceanUniforms, tiling)),
        ("table", std::mem::offset_of!(OceanUniforms, table)),
        ("cascades", std::mem::offset_of!(OceanUniforms, cascades)),
        ("origins", std::mem::offset_of!(OceanUniforms, origins)),
        (
            "slope_table",
            std::mem::offset_of!(OceanUniforms, slope_table),
        ),
        ("wake", std::mem::offset_of!(OceanUniforms, wake)),
        ("streaks", std::mem::offset_of!(OceanUniforms, streaks)),
        (
            "streak_scale",
            std::mem::offset_of!(OceanUniforms, streak_scale),
        ),
        ("coast", std::mem::offset_of!(OceanUniforms, coast)),
        (
            "coast_size",
            std::mem::offset_of!(OceanUniforms, coast_size),
        ),
    ];
    assert_eq!(members.len(), rust.len(), "members");
    for (member, (name, offset)) in members.iter().zip(rust) {
        assert_eq!(member.name.as_deref(), Some(name));
        assert_eq!(member.offset as usize, offset, "offset of {name}");
    }
}
