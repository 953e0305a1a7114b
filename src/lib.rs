//! # ocean-fft
//!
//! A pure-CPU simulation of the open-ocean surface with Tessendorf's statistical FFT method and
//! calibrated oceanographic spectra: build an [`OceanState`] once, call
//! [`OceanState::step`] every frame, then read each cascade's buffers or query the water at a
//! world point.
//!
//! ```
//! use ocean_fft::{OceanConfig, OceanState, Spectrum, Spreading};
//!
//! let spectrum = Spectrum::jonswap(10.0, 100_000.0)?   // U10 [m/s], fetch [m]
//!     .with_wind_direction(0.3)?                       // rad, toward which the wind blows
//!     .with_spreading(Spreading::DonelanBanner)?;
//! let hs = spectrum.significant_wave_height();         // m
//! assert!(hs > 2.0 && hs < 2.3);
//!
//! let config = OceanConfig { size: 64, ..OceanConfig::default() };   // 3 cascades
//! let mut ocean = OceanState::new(spectrum, config)?;
//! for _frame in 0..3 {
//!     ocean.step(1.0 / 60.0)?;                         // s
//! }
//! let heights = ocean.cascades()[0].height();          // m, N×N, index j·N + i
//! let y = ocean.water().height_at(25.0, -130.0)?;      // m, water height at world (x, z)
//! assert!(heights.len() == 64 * 64 && y.abs() < 5.0);
//! # Ok::<(), ocean_fft::Error>(())
//! ```
//!
//! The parts, in the order data flows through them:
//!
//! - [`Spectrum`]: S(k) in m⁴ from JONSWAP, Pierson–Moskowitz, TMA or Phillips with a
//!   directional [`Spreading`] and a [`Dispersion`]; [`SeaState`] presets.
//! - [`Cascade`]: one N×N patch; h0(k) drawn once, then every [`Cascade::update`] evolves
//!   h̃(k, t) and runs four packed complex inverse FFTs for height, displacement, slope,
//!   normal and Jacobian.
//! - [`OceanState`]: several cascades on disjoint wave-number bands, the time, the foam (one
//!   field for the whole ocean with whitecaps calibrated against measurements, residual foam
//!   drawn into streaks and a breaking intensity: [`FoamView::total`],
//!   [`OceanState::foam_view`], [`FoamConfig`]), and the world queries of its [`Water`]
//!   ([`OceanState::water`]: [`Water::height_at`] at a world point, [`Water::at_rest`] at a
//!   rest point), also from other threads through a [`Surface`] handle.
//! - GPU upload into buffers you own ([`gpu`]): [`Cascade::pack_texels`] and
//!   [`OceanState::textures`] ([`gpu::Textures::pack`]) interleave the buffers into RGBA32F texels of a
//!   [`gpu::TexelLayout`] (RGBA16F with the `half` feature), [`Cascade::write_vertices`]
//!   writes a [`gpu::Vertex`] array with [`Cascade::triangle_indices`], and
//!   [`Cascade::write_normal_map`] an RGBA8 tangent-space normal map with OpenGL- or
//!   DirectX-style green ([`gpu::NormalMapGreen`]); [`gpu::Engine`] maps the crate's axes
//!   and units to those of common engines.
//! - Verification and tooling ([`inspect`]): the crate's FFT on its own, a cascade's evolved
//!   spectrum, frequencies and single fields, and the diagnostics some methods return.
//!
//! # Conventions
//!
//! - Right-handed, **y up**; the sea surface is the (x, z) plane. Buffers and query results
//!   are plain arrays: horizontal vectors are `[f32; 2]` holding **`[x, z]`**, 3-vectors are
//!   `[f32; 3]` holding `[x, y, z]`. No math library appears in the API, so any engine's
//!   vector types read them (`glam::Vec3::from_array`, or zero-copy with `bytemuck`).
//! - Angles in radians. A direction θ is the unit vector (cos θ, sin θ) in (x, z). The wind
//!   direction is the direction the wind blows **toward**; waves travel downwind.
//! - SI units: metres, seconds, rad/s, m/s; g = 9.81 m/s² ([`GRAVITY`]). Time is f64.
//! - Spectra: S(ω) in m²·s/rad, D(ω, θ) in 1/rad with ∫D dθ = 1, S(k) in m⁴ with
//!   ∫∫S(k) d²k the surface variance and H_s = 4√m0. A cascade's h0 is calibrated so that the
//!   simulated variance is Σ S(k) Δk².
//! - Grids: N×N over a patch of side L; sample (i, j) at x = i·L/N, z = j·L/N is at index
//!   `j * N + i` (z is the row). Spectral index (i, j) holds k = Δk·(m(i), m(j)) in plain FFT
//!   order.
//! - Textures: texel (i, j) is grid sample (i, j), row j = z with row 0 first; a cascade's
//!   textures tile the world with period L (wrap mode repeat): texel (i, j) ↔ world
//!   (x₀ + i·L/N, z₀ + j·L/N) for any tile origin (x₀, z₀) on a multiple of L.
//!
//! # Errors, threads, allocation
//!
//! Every constructor, setter and query checks its input and returns [`Error`] rather than
//! panicking; no NaN reaches an output buffer. The FFT rows, h0 generation and batch queries
//! run on rayon's pool (or the pool you `install`); results are bit-identical whatever the
//! number of threads and SIMD level. By default that holds on one machine and build; with
//! [`Determinism::CrossPlatform`] in the config, every buffer, h0 and query result is the
//! same bits on every CPU and operating system (see [`Determinism`]). [`Cascade::update`] and [`OceanState::step`] allocate nothing inside a
//! rayon pool; called from a thread outside every pool, rayon's own job queue allocates one
//! 1.5 KiB block per 63 calls.
//!
//! # Performance
//!
//! Each [`Cascade::update`] runs four packed complex 2D inverse FFTs plus the evolution and
//! output passes around them; `cargo bench -p ocean-fft-benches --bench cascade` (run in the
//! repository) measures it beside the four bare transforms of [`inspect::Fft2d`] in the same process,
//! and `cargo bench -p ocean-fft-benches --bench ocean` a step of the default ocean beside its
//! twelve bare transforms. The repository's `docs/benchmarks.md` holds the measured ratios with
//! the CPU, commit and toolchain they were measured with (`bench-table` generates it), and
//! `docs/performance.md` explains them.
//!
//! # Features
//!
//! The crate always builds the whole simulation, with rayon for threads. Optional features,
//! all off by default:
//!
//! - **`half`**: RGBA16F texel packing, `Cascade::pack_texels_f16` and
//!   `gpu::Textures::pack_f16`, into `[half::f16; 4]` texels of the `half` crate (2.x,
//!   re-exported as `ocean_fft::half`). Each channel is rounded to the nearest f16 (ties to
//!   even) and values beyond the f16 range saturate to ±65504, never ±∞ or NaN.
//! - **`serde`**: `Serialize` and `Deserialize` for [`Spectrum`], [`Spreading`],
//!   [`DepthFactor`], [`Dispersion`], [`CascadeConfig`], [`OceanConfig`], [`FoamConfig`] and
//!   [`SeaState`], to save and load sea configurations. Deserialising a [`Spectrum`] (or a
//!   [`Dispersion`] or [`Spreading`]) re-runs the checks of its constructors and `with_*`
//!   setters, so a loaded spectrum is as valid as a built one; invalid data (a negative wind,
//!   NaN, γ ≤ 0, swell outside [0, 1], a depth ≤ 0, …) is a deserialisation error naming the
//!   parameter. In human-readable formats those three also read `null` or a string such as
//!   `"NaN"` as the non-finite number, only to reject it by name. The configs are passive
//!   data, loaded as they are and checked by [`Cascade::new`] and [`OceanState::new`] like
//!   any other. Their `k_max` may be +∞, which JSON cannot hold: +∞ is written as `null`
//!   (and a missing `k_max` reads as +∞); a NaN or −∞ `k_max` cannot be saved.
//!
//! ```
//! # #[cfg(feature = "serde")] {
//! use ocean_fft::{OceanConfig, SeaState, Spectrum};
//!
//! let (spectrum, config) = SeaState::FreshBreeze.build();
//! let saved = serde_json::to_string(&(&spectrum, &config)).unwrap();
//! let loaded: (Spectrum, OceanConfig) = serde_json::from_str(&saved).unwrap();
//! assert_eq!(loaded, (spectrum, config));
//!
//! let tampered = saved.replace("\"swell\":0.0", "\"swell\":2.0");
//! let error = serde_json::from_str::<(Spectrum, OceanConfig)>(&tampered).unwrap_err();
//! assert!(error.to_string().contains("parameter `swell` = 2 is out of range"));
//! # }
//! # Ok::<(), ocean_fft::Error>(())
//! ```
//!
//! - **`bytemuck`**: `bytemuck::Pod` and `bytemuck::Zeroable` (derived) for
//!   [`SurfaceSample`] and [`gpu::Vertex`] (and `half`'s f16 when `half` is on too), so that
//!   `bytemuck::cast_slice` gives a vertex array's bytes to upload and views the results of
//!   [`Water::surfaces_at`] as `&[f32]`, or as any `#[repr(C)]` struct of the same nine
//!   `f32`, without copying. The cascade buffers need no feature: they are `&[f32]`,
//!   `&[[f32; 2]]` and `&[[f32; 3]]`, which bytemuck already casts to an engine's `Vec2` and
//!   `Vec3` whatever its version (glam's with its own `bytemuck` feature, for example).
//!
//! ```
//! # #[cfg(feature = "bytemuck")] {
//! use ocean_fft::{OceanConfig, OceanState, Spectrum, SurfaceSample};
//!
//! let config = OceanConfig { size: 16, ..OceanConfig::default() };
//! let mut ocean = OceanState::new(Spectrum::jonswap(10.0, 100_000.0)?, config)?;
//! ocean.step(1.0 / 60.0)?;
//! let mut samples = [SurfaceSample::default(); 3];
//! ocean.water().surfaces_at(&[[0.0, 0.0], [10.0, -4.0], [250.0, 80.0]], &mut samples)?;
//!
//! let floats: &[f32] = bytemuck::cast_slice(&samples);   // 9 f32 a sample, no copy
//! assert_eq!(floats.as_ptr(), samples.as_ptr().cast::<f32>());
//! assert_eq!(floats.len(), 3 * 9);
//! assert_eq!(floats[9], samples[1].height);
//! assert_eq!(floats[9 + 5..9 + 8], samples[1].normal);
//! # }
//! # Ok::<(), ocean_fft::Error>(())
//! ```
//!
//! There is no `mint` feature, as it would add nothing to the arrays: `mint::Vector2<f32>`
//! and `mint::Vector3<f32>` implement `From<[f32; 2]>` and `From<[f32; 3]>`, so
//! `mint::Vector3::from(cascade.normal()[i])` (or `.into()`) converts a buffer element, as the
//! same `From` does for glam's, nalgebra's and cgmath's vectors.
//!
//! The formulas, their sources and the choices made where sources differ are in the
//! repository's `docs/theory.md`; how to pick parameters and embed the crate in a game is in
//! its user guide, `docs/guide/` (start with `docs/guide/getting-started.md`).
#![warn(missing_docs)]
#![warn(clippy::missing_errors_doc)]

mod cascade;
pub mod coast;
mod error;
mod foam;
#[cfg(test)]
mod golden;
pub mod gpu;
pub mod inspect;
mod math;
mod ocean;
mod presets;
mod query;
#[cfg(feature = "serde")]
mod serde_impls;
mod spectrum;
mod wake;

pub use cascade::{Cascade, CascadeConfig};
pub use coast::{CoastField, DepthMap};
pub use error::Error;
pub use foam::{FoamConfig, FoamCoverage, FoamView};
/// The `half` crate (with the `half` feature), whose `f16` the `pack_texels_f16` functions
/// write: `ocean_fft::half::f16` is the version this crate was built with.
#[cfg(feature = "half")]
pub use half;
pub use math::determinism::Determinism;
pub use ocean::{limits, Diagnostics, OceanConfig, OceanSnapshot, OceanState, SeaFit};
pub use presets::SeaState;
pub use query::{Interpolation, Location, QueryConfig, Surface, SurfaceSample, Water};
pub use spectrum::dispersion::{Dispersion, GRAVITY};
pub use spectrum::{DepthFactor, SlopeVariance, Spectrum, SpectrumKind, SpectrumParams, Spreading};
pub use wake::{Hull, WakeConfig, Wakes};

// The Rust blocks of the guide's chapters (docs/guide/) are doc-tests when every optional
// feature is on (the serde block of spectra.md needs `serde`), as CI runs them:
// `cargo test --release --doc --all-features`. A `rust,ignore` block there is a verbatim copy of
// code compiled in clients/ or says why it is not compiled; tests/guide.rs checks both. One
// item per chapter that holds Rust blocks, so a failure names the chapter.
#[cfg(all(doctest, feature = "serde", feature = "half", feature = "bytemuck"))]
mod guide_doc_tests {
    #[doc = include_str!("../docs/guide/getting-started.md")]
    struct GettingStarted;
    #[doc = include_str!("../docs/guide/spectra.md")]
    struct Spectra;
    #[doc = include_str!("../docs/guide/foam.md")]
    struct Foam;
    #[doc = include_str!("../docs/guide/rendering.md")]
    struct Rendering;
    #[doc = include_str!("../docs/guide/baking.md")]
    struct Baking;
    #[doc = include_str!("../docs/guide/errors.md")]
    struct Errors;
    #[doc = include_str!("../docs/guide/weather.md")]
    struct Weather;
    #[doc = include_str!("../docs/guide/cascades.md")]
    struct Cascades;
    #[doc = include_str!("../docs/guide/wakes.md")]
    struct Wakes;
}

// The README's example is a doc-test with or without features.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDocTests;
