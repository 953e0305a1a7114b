//! The viewer's shader checked by naga, the WGSL front end and validator wgpu compiles it
//! with: ocean_common.wgsl with ocean.wgsl parse and validate, the entry points and bindings
//! are those the viewer binds, the uniform struct has the Rust struct's layout, and every
//! entry point translates to GLSL. (The render layer's tests check ocean_common.wgsl alone.)

use naga::valid::{Capabilities, ValidationFlags, Validator};
use naga::{AddressSpace, ImageClass, ImageDimension, ScalarKind, ShaderStage, TypeInner};

use crate::gpu::{Globals, SHADER};

/// Parses and validates `source` with the capabilities every wgpu adapter has (no optional
/// feature), failing with naga's own message.
fn validate(name: &str, source: &str) -> (naga::Module, naga::valid::ModuleInfo) {
    let module = naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("{name} does not parse:\n{}", e.emit_to_string(source)));
    let info = Validator::new(ValidationFlags::all(), Capabilities::empty())
        .validate(&module)
        .unwrap_or_else(|e| panic!("{name} does not validate:\n{}", e.emit_to_string(source)));
    (module, info)
}

#[test]
fn the_reference_shader_validates_with_the_viewers_entry_points() {
    let (module, _) = validate("ocean_common.wgsl + ocean.wgsl", SHADER);
    let mut entries: Vec<(String, ShaderStage)> = module
        .entry_points
        .iter()
        .map(|e| (e.name.clone(), e.stage))
        .collect();
    entries.sort_by(|a, b| a.0.cmp(&b.0));
    let expected = [
        ("fs_body", ShaderStage::Fragment),
        ("fs_ocean", ShaderStage::Fragment),
        ("fs_sky", ShaderStage::Fragment),
        ("fs_terrain", ShaderStage::Fragment),
        ("vs_body", ShaderStage::Vertex),
        ("vs_ocean", ShaderStage::Vertex),
        ("vs_sky", ShaderStage::Vertex),
        ("vs_terrain", ShaderStage::Vertex),
    ];
    assert_eq!(
        entries,
        expected.map(|(n, s)| (n.to_string(), s)).to_vec(),
        "entry points"
    );
}

#[test]
fn the_bindings_and_the_uniform_layout_are_the_viewers() {
    let (module, _) = validate("ocean_common.wgsl + ocean.wgsl", SHADER);
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).expect("layouts");
    let mut seen = [false; 9];
    for (_, global) in module.global_variables.iter() {
        let binding = global.binding.as_ref().expect("every global is bound");
        assert_eq!(binding.group, 0, "{:?}", global.name);
        let inner = &module.types[global.ty].inner;
        match binding.binding {
            0 => {
                assert_eq!(global.space, AddressSpace::Uniform);
                let TypeInner::Struct { members, span } = inner else {
                    panic!("binding 0 is not a struct");
                };
                // The WGSL struct's size and member offsets as naga lays them out must be the
                // Rust struct's, computed independently by rustc.
                assert_eq!(
                    *span as usize,
                    std::mem::size_of::<Globals>(),
                    "Globals size"
                );
                let rust_offsets = [
                    std::mem::offset_of!(Globals, view_proj),
                    std::mem::offset_of!(Globals, inverse_view_proj),
                    std::mem::offset_of!(Globals, eye),
                    std::mem::offset_of!(Globals, levels),
                    std::mem::offset_of!(Globals, ocean),
                ];
                assert_eq!(members.len(), rust_offsets.len(), "Globals members");
                for (member, rust) in members.iter().zip(rust_offsets) {
                    assert_eq!(member.offset as usize, rust, "offset of {:?}", member.name);
                }
                assert_eq!(layouter[global.ty].size, *span);
            }
            1 | 2 | 8 => {
                let TypeInner::Image {
                    dim,
                    arrayed,
                    class,
                } = inner
                else {
                    panic!("binding {} is not a texture", binding.binding);
                };
                assert_eq!(*dim, ImageDimension::D2);
                assert!(*arrayed, "a layer per cascade, two for the coast");
                assert!(matches!(
                    class,
                    ImageClass::Sampled {
                        kind: ScalarKind::Float,
                        multi: false
                    }
                ));
            }
            5 | 7 => {
                let TypeInner::Image { dim, arrayed, .. } = inner else {
                    panic!("binding {} is not a texture", binding.binding);
                };
                assert_eq!(*dim, ImageDimension::D2);
                assert!(
                    !*arrayed,
                    "the wake window and the streaks are one texture each"
                );
            }
            3 | 4 | 6 => assert!(matches!(inner, TypeInner::Sampler { comparison: false })),
            other => panic!("unexpected binding {other}"),
        }
        seen[binding.binding as usize] = true;
    }
    assert_eq!(seen, [true; 9], "bindings 0–8");
}

/// Every entry point translates to GLSL 4.50 with naga's GLSL back end (the route to Godot's
/// shading language and to OpenGL), so nothing in the shader is WGSL-only.
#[test]
fn the_reference_shader_translates_to_glsl() {
    let (module, info) = validate("ocean_common.wgsl + ocean.wgsl", SHADER);
    for entry in &module.entry_points {
        let options = naga::back::glsl::Options {
            version: naga::back::glsl::Version::Desktop(450),
            ..Default::default()
        };
        let pipeline = naga::back::glsl::PipelineOptions {
            shader_stage: entry.stage,
            entry_point: entry.name.clone(),
            multiview: None,
        };
        let mut out = String::new();
        let mut writer = naga::back::glsl::Writer::new(
            &mut out,
            &module,
            &info,
            &options,
            &pipeline,
            naga::proc::BoundsCheckPolicies::default(),
        )
        .unwrap_or_else(|e| panic!("{}: {e}", entry.name));
        writer
            .write()
            .unwrap_or_else(|e| panic!("{}: {e}", entry.name));
        assert!(out.contains("void main()"), "{}", entry.name);
    }
}
