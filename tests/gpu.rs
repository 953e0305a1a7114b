//! GPU upload: packed texels, vertex arrays, triangle indices and normal maps, each checked
//! against the source buffers, `half`'s own conversion, hand-computed encodings or an analytic
//! single wave; errors leave the caller's buffer untouched; results are bit-identical at any
//! thread count.
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

mod common;

use std::f64::consts::{FRAC_PI_2, TAU};

use common::*;
use ocean_fft::gpu::{NormalMapGreen, TexelLayout, Vertex};
use ocean_fft::{
    Cascade, CascadeConfig, Error, FoamConfig, OceanConfig, OceanState, Spectrum, Spreading,
};

/// A 64² ocean of a rough sea stepped for 2 s, with foam on some grid points (five times the
/// calibrated whitecaps).
fn foamy_ocean(size: usize) -> OceanState {
    let spectrum = Spectrum::jonswap(14.0, 300_000.0)
        .and_then(|s| s.with_wind_direction(0.4))
        .unwrap();
    let config = OceanConfig {
        size,
        choppiness: 1.5,
        foam: FoamConfig {
            coverage: 5.0,
            ..FoamConfig::default()
        },
        ..OceanConfig::default()
    };
    let mut ocean = OceanState::new(spectrum, config).unwrap();
    for _ in 0..60 {
        ocean.step(1.0 / 30.0).unwrap();
    }
    ocean
}

/// The four channels a texel of `layout` must hold at grid index `k`, from the source
/// buffers as their docs describe them (`foam`: the ocean's foam for cascade 0, zeros for the
/// others).
fn expected_texel(cascade: &Cascade, foam: &[f32], layout: TexelLayout, k: usize) -> [f32; 4] {
    let (eta, d, s, n, j) = (
        cascade.height()[k],
        cascade.displacement()[k],
        cascade.slope()[k],
        cascade.normal()[k],
        cascade.jacobian()[k],
    );
    match layout {
        TexelLayout::DisplacementJacobian => [d[0], eta, d[1], j],
        TexelLayout::DisplacementFoam => [d[0], eta, d[1], foam[k]],
        TexelLayout::SlopeJacobianFoam => [s[0], s[1], j, foam[k]],
        TexelLayout::Normal => [n[0], n[1], n[2], cascade.subgrid_slope_variance().total()],
        other => panic!("no expectation written for {other:?}"),
    }
}

#[test]
fn layouts_list_and_foam() {
    assert_eq!(TexelLayout::ALL.len(), 4);
    let with_foam: Vec<_> = TexelLayout::ALL.iter().filter(|l| l.has_foam()).collect();
    assert_eq!(
        with_foam,
        [
            &TexelLayout::DisplacementFoam,
            &TexelLayout::SlopeJacobianFoam
        ]
    );
    assert_eq!(std::mem::size_of::<Vertex>(), 24);
    assert_eq!(
        Vertex::default(),
        Vertex {
            position: [0.0; 3],
            normal: [0.0, 1.0, 0.0]
        }
    );
}

#[test]
fn every_layout_copies_its_source_buffers_bit_for_bit() {
    let ocean = foamy_ocean(64);
    let mut foamy_texels = 0;
    for (c, cascade) in ocean.cascades().iter().enumerate() {
        let n = cascade.size();
        let zeros = vec![0.0; n * n];
        let foam = if c == 0 {
            ocean.foam_view().total()
        } else {
            &zeros
        };
        foamy_texels += foam.iter().filter(|&&f| f > 0.01).count();
        for &layout in TexelLayout::ALL {
            let mut texels = vec![[f32::NAN; 4]; n * n];
            ocean.textures().pack(c, layout, &mut texels).unwrap();
            let mut bare = vec![[f32::NAN; 4]; n * n];
            let bare_result = cascade.pack_texels(layout, &mut bare);
            assert_eq!(bare_result.is_ok(), !layout.has_foam(), "{layout:?}");
            for (k, texel) in texels.iter().enumerate() {
                let expected = expected_texel(cascade, foam, layout, k).map(f32::to_bits);
                assert_eq!(
                    texel.map(f32::to_bits),
                    expected,
                    "cascade {c}, {layout:?}, texel {k}"
                );
                if bare_result.is_ok() {
                    assert_eq!(bare[k].map(f32::to_bits), expected, "bare {layout:?}");
                }
            }
        }
    }
    assert!(foamy_texels > 20, "the test needs foam: {foamy_texels}");
}

#[cfg(feature = "half")]
mod f16_packing {
    use super::*;
    use ocean_fft::half::f16;

    /// What an f16 channel must hold for `value`: `half`'s own round-to-nearest conversion
    /// inside the f16 range, ±65504 (f16::MAX) beyond it.
    fn expected_f16(value: f32) -> f16 {
        if value > 65504.0 {
            f16::MAX
        } else if value < -65504.0 {
            f16::MIN
        } else {
            f16::from_f32(value)
        }
    }

    fn check_f16(texels: &[[f16; 4]], expected: impl Fn(usize) -> [f32; 4], what: &str) -> usize {
        let mut saturated = 0;
        for (k, texel) in texels.iter().enumerate() {
            for (channel, (&got, value)) in texel.iter().zip(expected(k)).enumerate() {
                let want = expected_f16(value);
                assert!(
                    got.is_finite(),
                    "{what}: texel {k} channel {channel} = {got}"
                );
                assert_eq!(
                    got.to_bits(),
                    want.to_bits(),
                    "{what}: texel {k} channel {channel}: {value} packed as {got}, expected {want}"
                );
                // Within half an f16 ulp of the value (inside the range).
                if value.abs() <= 65504.0 {
                    let ulp = f16::from_bits(want.to_bits() | 1).to_f32()
                        - f16::from_bits(want.to_bits() & !1).to_f32();
                    assert!((got.to_f32() - value).abs() <= 0.5 * ulp.abs());
                } else {
                    saturated += 1;
                }
            }
        }
        saturated
    }

    #[test]
    fn f16_texels_are_halfs_rounding_of_the_f32_texels() {
        let ocean = foamy_ocean(64);
        for (c, cascade) in ocean.cascades().iter().enumerate() {
            let n = cascade.size();
            let zeros = vec![0.0; n * n];
            let foam = if c == 0 {
                ocean.foam_view().total()
            } else {
                &zeros
            };
            for &layout in TexelLayout::ALL {
                let mut texels = vec![[f16::NAN; 4]; n * n];
                ocean.textures().pack_f16(c, layout, &mut texels).unwrap();
                let what = format!("cascade {c}, {layout:?}");
                check_f16(&texels, |k| expected_texel(cascade, foam, layout, k), &what);
                if !layout.has_foam() {
                    let mut bare = vec![[f16::NAN; 4]; n * n];
                    cascade.pack_texels_f16(layout, &mut bare).unwrap();
                    assert!(bare
                        .iter()
                        .zip(&texels)
                        .all(|(a, b)| a.map(f16::to_bits) == b.map(f16::to_bits)));
                }
            }
        }
    }

    #[test]
    fn f16_texels_saturate_at_65504_beyond_the_f16_range() {
        // One huge wave: η and D_x reach about 2e5 m and J about −2e4·… (folding heavily),
        // far beyond f16's 65504.
        let cascade = single_wave(1e9, 1.0, 0.0, 0.0);
        let n = cascade.size();
        assert!(cascade.height().iter().any(|h| h.abs() > 65504.0));
        let mut saturated = 0;
        for layout in [TexelLayout::DisplacementJacobian, TexelLayout::Normal] {
            let mut texels = vec![[f16::NAN; 4]; n * n];
            cascade.pack_texels_f16(layout, &mut texels).unwrap();
            let expected = |k| expected_texel(&cascade, &[], layout, k);
            saturated += check_f16(&texels, expected, &format!("{layout:?}"));
        }
        assert!(saturated > n * n / 4, "only {saturated} channels saturated");
    }
}

/// A cascade of one wave: L = 100 m, N = 64, the band [0.99, 1.01)·2Δk holds only
/// (±2, 0) and (0, ±2), and a Phillips spectrum with cos^50 spreading and no upwind waves
/// toward `direction` (0 or π/2) keeps only the one along it (as in
/// tests/cascade_conventions.rs).
fn single_wave(amplitude: f32, choppiness: f32, direction: f64, t: f64) -> Cascade {
    let length = 100.0f32;
    let k = 2.0 * TAU / f64::from(length);
    let spectrum = Spectrum::phillips(10.0, amplitude)
        .and_then(|s| s.with_wind_direction(direction as f32))
        .and_then(|s| {
            s.with_spreading(Spreading::Cosine {
                exponent: 50.0,
                upwind: 0.0,
            })
        })
        .unwrap();
    let mut cascade = Cascade::new(
        &spectrum,
        CascadeConfig {
            size: 64,
            length,
            k_min: (0.99 * k) as f32,
            k_max: (1.01 * k) as f32,
            choppiness,
            seed: 2,
            ..CascadeConfig::default()
        },
    )
    .unwrap();
    cascade.update(t).unwrap();
    cascade
}

/// ⌊127.5·(c + 1) + 0.5⌋ in f64, saturated to 0..=255.
fn encode(c: f64) -> i32 {
    (127.5 * (c + 1.0) + 0.5).floor().clamp(0.0, 255.0) as i32
}

#[test]
fn normal_map_encodes_a_single_wave_as_documented() {
    // With choppiness 0 the surface is η = a cos(k·x + φ0) at t = 0 (a = 2|c|, φ0 = arg c of
    // the one nonzero h0 c), so its normal is (−∂η/∂x, 1, −∂η/∂z)/|…| analytically.
    let n = 64usize;
    let k = 2.0 * TAU / 100.0;
    for (direction, axis) in [(0.0, [1.0, 0.0]), (FRAC_PI_2, [0.0, 1.0])] {
        let cascade = single_wave(0.14, 0.0, direction, 0.0);
        let (nonzero, c) = cascade
            .h0()
            .iter()
            .enumerate()
            .find(|(_, c)| c.norm() > 0.0)
            .map(|(index, &c)| (index, to64(c)))
            .unwrap();
        // (i, j) = (2, 0) for the wave along +x, (0, 2) along +z.
        assert_eq!(nonzero, if direction == 0.0 { 2 } else { 2 * n });
        let (a, phi0) = (2.0 * cabs(c), c.1.atan2(c.0));
        assert!(a * k > 0.1, "the wave should be steep: ka = {}", a * k);
        let mut maps = Vec::new();
        for green in [NormalMapGreen::OpenGl, NormalMapGreen::DirectX] {
            let mut pixels = vec![[7u8; 4]; n * n];
            cascade.write_normal_map(green, &mut pixels).unwrap();
            let mut leaning = 0;
            for j in 0..n {
                for i in 0..n {
                    let (x, z) = (i as f64 * 100.0 / 64.0, j as f64 * 100.0 / 64.0);
                    let theta = k * (axis[0] * x + axis[1] * z) + phi0;
                    let (eta_x, eta_z) = (
                        -a * k * theta.sin() * axis[0],
                        -a * k * theta.sin() * axis[1],
                    );
                    let norm = (1.0 + eta_x * eta_x + eta_z * eta_z).sqrt();
                    let normal = [-eta_x / norm, 1.0 / norm, -eta_z / norm];
                    // Green up the image (−z) for OpenGL, down (+z) for DirectX.
                    let g = match green {
                        NormalMapGreen::OpenGl => -normal[2],
                        NormalMapGreen::DirectX => normal[2],
                    };
                    let want = [encode(normal[0]), encode(g), encode(normal[1]), 255];
                    let got = pixels[j * n + i].map(i32::from);
                    for ch in 0..4 {
                        assert!(
                            (got[ch] - want[ch]).abs() <= 1,
                            "{green:?}, direction {direction}, pixel ({i}, {j}): {got:?}, expected {want:?}"
                        );
                    }
                    // In words: where the surface rises toward +z (down the image), the
                    // normal leans up the image, toward −z: OpenGL's green above 128,
                    // DirectX's below. Where it rises toward +x, red is below 128.
                    if eta_z > 0.05 {
                        leaning += 1;
                        match green {
                            NormalMapGreen::OpenGl => assert!(got[1] > 128),
                            NormalMapGreen::DirectX => assert!(got[1] < 128),
                        }
                    }
                    if eta_x > 0.05 {
                        leaning += 1;
                        assert!(got[0] < 128);
                    }
                }
            }
            assert!(
                leaning > n * n / 4,
                "{green:?}: only {leaning} tilted pixels"
            );
            maps.push(pixels);
        }
        // The two conventions differ in green only, mirrored about 127.5 (255 − G, up to
        // the rounding of an exact 127.5).
        for (gl, dx) in maps[0].iter().zip(&maps[1]) {
            assert_eq!([gl[0], gl[2], gl[3]], [dx[0], dx[2], dx[3]]);
            assert!((i32::from(gl[1]) + i32::from(dx[1]) - 255).abs() <= 1);
        }
    }
}

#[test]
fn normal_map_pixels_are_the_documented_formula_of_the_normal_buffer() {
    // A steep, very choppy sea, so that some of the surface folds over (n_y < 0).
    let config = CascadeConfig {
        size: 64,
        length: 80.0,
        choppiness: 4.0,
        seed: 3,
        ..CascadeConfig::default()
    };
    let cascade = Cascade::new(&jonswap(0.2), config).unwrap();
    let n = cascade.size();
    let mut folded = 0;
    for green in [NormalMapGreen::OpenGl, NormalMapGreen::DirectX] {
        let mut pixels = vec![[0u8; 4]; n * n];
        cascade.write_normal_map(green, &mut pixels).unwrap();
        for (k, (pixel, normal)) in pixels.iter().zip(cascade.normal()).enumerate() {
            let [x, y, z] = normal.map(f64::from);
            let g = if green == NormalMapGreen::OpenGl {
                -z
            } else {
                z
            };
            let want = [encode(x), encode(g), encode(y), 255];
            // The f64 formula may round an exact half differently from f32: ±1 at most.
            for ch in 0..4 {
                assert!(
                    (i32::from(pixel[ch]) - want[ch]).abs() <= 1,
                    "{green:?} pixel {k}: {pixel:?}, expected {want:?}"
                );
            }
            folded += usize::from(y < 0.0);
        }
    }
    let min_j = cascade.jacobian().iter().fold(f32::MAX, |a, &b| a.min(b));
    assert!(
        folded > 0,
        "the test should see folded water (n_y < 0): min J {min_j}"
    );
}

#[test]
fn vertices_are_grid_points_plus_displacement_and_the_normal() {
    for (size, length) in [(64usize, 250.0f32), (24, 333.3)] {
        let spectrum = jonswap(0.7);
        let config = CascadeConfig {
            size,
            length,
            choppiness: 1.4,
            seed: 5,
            ..CascadeConfig::default()
        };
        let mut cascade = Cascade::new(&spectrum, config).unwrap();
        cascade.update(4.25).unwrap();
        let n = size;
        let mut vertices = vec![Vertex::default(); n * n];
        cascade.write_vertices(&mut vertices).unwrap();
        for j in 0..n {
            for i in 0..n {
                let k = j * n + i;
                let v = vertices[k];
                let d = cascade.displacement()[k];
                // The f32 nearest to x₀ + D_x (x₀ = i·L/N exact in f64 to 1e-16): within half
                // an f32 ulp, plus a hair for the f64 rounding before it.
                let x = i as f64 * f64::from(length) / n as f64 + f64::from(d[0]);
                let z = j as f64 * f64::from(length) / n as f64 + f64::from(d[1]);
                for (got, want) in [(v.position[0], x), (v.position[2], z)] {
                    let half_ulp =
                        0.5 * f64::from(f32::EPSILON) * f64::from(got.abs()).max(f64::MIN_POSITIVE);
                    let err = (f64::from(got) - want).abs();
                    assert!(
                        err <= half_ulp * (1.0 + 1e-6) + 1e-30,
                        "N={n} ({i}, {j}): {got} vs {want}"
                    );
                }
                assert_eq!(v.position[1].to_bits(), cascade.height()[k].to_bits());
                assert_eq!(
                    v.normal.map(f32::to_bits),
                    cascade.normal()[k].map(f32::to_bits)
                );
            }
        }
    }
}

#[test]
fn triangle_indices_cover_every_cell_counter_clockwise_from_above() {
    let spectrum = jonswap(0.0);
    for n in [4usize, 24, 64] {
        let cascade = Cascade::new(
            &spectrum,
            CascadeConfig {
                size: n,
                length: 100.0,
                ..CascadeConfig::default()
            },
        )
        .unwrap();
        let triangles = cascade.triangle_indices();
        assert_eq!(triangles.len(), 2 * (n - 1) * (n - 1));
        let triangles: Vec<[u32; 3]> = triangles.collect();
        assert_eq!(triangles.len(), 2 * (n - 1) * (n - 1));
        // Undisplaced positions of vertex index j·N + i.
        let point = |index: u32| {
            let (i, j) = (index as usize % n, index as usize / n);
            [i as f64, 0.0, j as f64]
        };
        let mut covered = vec![0u32; (n - 1) * (n - 1)];
        for t in &triangles {
            assert!(t.iter().all(|&v| (v as usize) < n * n));
            let [p0, p1, p2] = t.map(point);
            let (e1, e2) = (
                [p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]],
                [p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]],
            );
            let normal = [
                e1[1] * e2[2] - e1[2] * e2[1],
                e1[2] * e2[0] - e1[0] * e2[2],
                e1[0] * e2[1] - e1[1] * e2[0],
            ];
            // Half a cell's area, facing +y.
            assert_eq!(normal, [0.0, 1.0, 0.0], "triangle {t:?}");
            // Every corner within one cell: the cell is the smallest (i, j) of the three.
            let i0 = t.iter().map(|&v| v as usize % n).min().unwrap();
            let j0 = t.iter().map(|&v| v as usize / n).min().unwrap();
            for &v in t {
                let (i, j) = (v as usize % n, v as usize / n);
                assert!(i - i0 <= 1 && j - j0 <= 1);
            }
            covered[j0 * (n - 1) + i0] += 1;
        }
        assert!(
            covered.iter().all(|&c| c == 2),
            "N={n}: two triangles per cell"
        );
    }
}

#[test]
fn bad_lengths_indices_and_layouts_are_errors_that_write_nothing() {
    let ocean = foamy_ocean(32);
    let cascade = &ocean.cascades()[0];
    let n2 = 32 * 32;
    let sentinel = [-7.25f32; 4];
    for len in [0, n2 - 1, n2 + 1, 4 * n2] {
        let mismatch = Error::LengthMismatch {
            name: "out",
            expected: n2,
            got: len,
        };
        let mut texels = vec![sentinel; len];
        for &layout in TexelLayout::ALL {
            assert_eq!(
                ocean.textures().pack(0, layout, &mut texels),
                Err(mismatch.clone())
            );
            if !layout.has_foam() {
                assert_eq!(
                    cascade.pack_texels(layout, &mut texels),
                    Err(mismatch.clone())
                );
            }
        }
        assert!(texels.iter().all(|t| *t == sentinel));
        let mut vertices = vec![
            Vertex {
                position: [9.0; 3],
                normal: [9.0; 3]
            };
            len
        ];
        assert_eq!(cascade.write_vertices(&mut vertices), Err(mismatch.clone()));
        assert!(vertices
            .iter()
            .all(|v| v.position == [9.0; 3] && v.normal == [9.0; 3]));
        let mut pixels = vec![[3u8; 4]; len];
        for green in [NormalMapGreen::OpenGl, NormalMapGreen::DirectX] {
            assert_eq!(
                cascade.write_normal_map(green, &mut pixels),
                Err(mismatch.clone())
            );
        }
        assert!(pixels.iter().all(|p| *p == [3u8; 4]));
    }
    // A cascade index past the last: named `cascade`, checked before the length.
    let cascades = ocean.cascades().len();
    for index in [cascades, cascades + 5, usize::MAX] {
        for len in [n2, 0] {
            let mut texels = vec![sentinel; len];
            assert_eq!(
                ocean
                    .textures()
                    .pack(index, TexelLayout::Normal, &mut texels),
                Err(Error::IndexOutOfRange {
                    name: "cascade",
                    index,
                    len: cascades
                })
            );
            assert!(texels.iter().all(|t| *t == sentinel));
        }
    }
    // A foam layout on a bare cascade: named `layout`, whatever the buffer.
    for &layout in TexelLayout::ALL.iter().filter(|l| l.has_foam()) {
        for len in [n2, 1] {
            let mut texels = vec![sentinel; len];
            let error = cascade.pack_texels(layout, &mut texels).unwrap_err();
            assert!(
                matches!(error, Error::NotApplicable { name: "layout", .. }),
                "{error:?}"
            );
            assert!(texels.iter().all(|t| *t == sentinel));
        }
    }
    #[cfg(feature = "half")]
    {
        use ocean_fft::half::f16;
        let sentinel = [f16::from_f32(-7.25); 4];
        let same = |texels: &[[f16; 4]]| {
            texels
                .iter()
                .all(|t| t.map(f16::to_bits) == sentinel.map(f16::to_bits))
        };
        for len in [0, n2 - 1, n2 + 1] {
            let mut texels = vec![sentinel; len];
            let mismatch = Err(Error::LengthMismatch {
                name: "out",
                expected: n2,
                got: len,
            });
            assert_eq!(
                ocean
                    .textures()
                    .pack_f16(1, TexelLayout::DisplacementFoam, &mut texels),
                mismatch
            );
            assert_eq!(
                cascade.pack_texels_f16(TexelLayout::Normal, &mut texels),
                mismatch
            );
            assert!(same(&texels));
        }
        let mut texels = vec![sentinel; n2];
        assert!(matches!(
            ocean
                .textures()
                .pack_f16(cascades, TexelLayout::Normal, &mut texels),
            Err(Error::IndexOutOfRange {
                name: "cascade",
                ..
            })
        ));
        assert!(matches!(
            cascade.pack_texels_f16(TexelLayout::SlopeJacobianFoam, &mut texels),
            Err(Error::NotApplicable { name: "layout", .. })
        ));
        assert!(same(&texels));
    }
}

/// Bit patterns of every pack of every cascade of `ocean`.
fn pack_fingerprint(ocean: &OceanState) -> Vec<Vec<u32>> {
    let mut out = Vec::new();
    for (c, cascade) in ocean.cascades().iter().enumerate() {
        let n = cascade.size();
        for &layout in TexelLayout::ALL {
            let mut texels = vec![[0.0f32; 4]; n * n];
            ocean.textures().pack(c, layout, &mut texels).unwrap();
            out.push(texels.iter().flat_map(|t| t.map(f32::to_bits)).collect());
            #[cfg(feature = "half")]
            {
                let mut texels = vec![[ocean_fft::half::f16::ZERO; 4]; n * n];
                ocean.textures().pack_f16(c, layout, &mut texels).unwrap();
                out.push(
                    texels
                        .iter()
                        .flat_map(|t| t.map(|h| u32::from(h.to_bits())))
                        .collect(),
                );
            }
        }
        let mut vertices = vec![Vertex::default(); n * n];
        cascade.write_vertices(&mut vertices).unwrap();
        out.push(
            vertices
                .iter()
                .flat_map(|v| v.position.into_iter().chain(v.normal).map(f32::to_bits))
                .collect(),
        );
        for green in [NormalMapGreen::OpenGl, NormalMapGreen::DirectX] {
            let mut pixels = vec![[0u8; 4]; n * n];
            cascade.write_normal_map(green, &mut pixels).unwrap();
            out.push(pixels.iter().map(|p| u32::from_le_bytes(*p)).collect());
        }
    }
    out
}

#[test]
fn packs_are_bit_identical_for_1_2_and_3_threads() {
    let pools: Vec<rayon::ThreadPool> = [1, 2, 3]
        .into_iter()
        .map(|threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
        })
        .collect();
    for size in [24, 64, 256] {
        let ocean = foamy_ocean(size);
        let results: Vec<Vec<Vec<u32>>> = pools
            .iter()
            .map(|pool| pool.install(|| pack_fingerprint(&ocean)))
            .collect();
        for (threads, result) in [2, 3].iter().zip(&results[1..]) {
            assert_eq!(result.len(), results[0].len());
            for (index, (a, b)) in result.iter().zip(&results[0]).enumerate() {
                let first = a.iter().zip(b).position(|(x, y)| x != y);
                assert!(
                    first.is_none(),
                    "N={size}: pack {index} differs between 1 and {threads} threads at {first:?}"
                );
            }
        }
    }
}
