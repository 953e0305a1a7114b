//! Property-based tests of the whole public surface under adversarial input.
//!
//! Every public constructor, setter, step, time call, query and evaluation function is fed a
//! mix of ordinary values, edge values (0, −0, subnormals, `f32::MAX`, ±∞, NaN, huge sizes and
//! lengths) and values a few ulps either side of the crate's own limits. Each property asserts
//! the crate's promise: no panic; either `Err` or a finite result; after an `Err`, every buffer
//! and the time exactly as they were (compared bit for bit); serde round trips refused cleanly
//! or faithful.
//!
//! Run time: the strategies keep grids at N ≤ 32 and oceans at three cascades of N ≤ 16 (a
//! valid config that would be larger is given a small `memory_limit`, so the large sizes test
//! the refusal path without allocating gigabytes). The whole file runs in a few seconds in
//! release mode; the cases per property are fixed below and the seed is fixed, so CI sees the
//! same inputs every run. `PROPTEST_CASES` overrides the case count for a longer local search.
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

mod props;

use std::ops::Bound;

use ocean_fft::inspect;
use ocean_fft::inspect::{Fft2d, Field};
use ocean_fft::{
    Cascade, CascadeConfig, DepthFactor, Determinism, Dispersion, Error, FoamConfig, Interpolation,
    OceanConfig, OceanState, QueryConfig, SeaFit, SeaState, Spectrum, Spreading, Surface,
    SurfaceSample,
};
use proptest::prelude::*;
use proptest::test_runner::Config;

/// Cases per property, unless `PROPTEST_CASES` says otherwise.
const CASES: u32 = 256;

/// The fixed seed of every property.
const SEED: u64 = 0x0cea_4fff;

fn config() -> Config {
    props::config(CASES, SEED)
}

// ----------------------------------------------------------------------------------------
// Value strategies
// ----------------------------------------------------------------------------------------

/// Edge values every f32 parameter meets.
const EDGES_F32: [f32; 19] = [
    0.0,
    -0.0,
    1e-45,
    -1e-45,
    1e-40,
    1.1e-38,
    f32::MIN_POSITIVE,
    1e-30,
    1e-6,
    0.5,
    1.0,
    -1.0,
    1e30,
    f32::MAX,
    -f32::MAX,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::NAN,
    -f32::NAN,
];

/// The crate's own limits (and a few physical scales), for values a few ulps either side.
const LIMITS_F32: [f32; 19] = [
    CascadeConfig::MIN_LENGTH,
    CascadeConfig::MAX_LENGTH,
    CascadeConfig::MIN_REPEAT_PERIOD,
    CascadeConfig::MAX_REPEAT_PERIOD,
    Spectrum::MAX_WIND_SPEED,
    Spectrum::FULLY_DEVELOPED_FETCH,
    Spectrum::DEFAULT_GAMMA,
    Spreading::MAX_EXPONENT,
    FoamConfig::MAX_COVERAGE,
    FoamConfig::MAX_STREAK,
    FoamConfig::MAX_STREAK,
    FoamConfig::MIN_DECAY,
    FoamConfig::MAX_DECAY,
    OceanConfig::DEFAULT_BAND_SPLIT,
    std::f32::consts::PI,
    -std::f32::consts::PI,
    1.0,
    0.0,
    FoamConfig::MAX_DRIFT,
];

/// `value` moved by `ulps` units in the last place (through zero and to ±∞ as the bits go;
/// NaN stays NaN).
fn nudge(value: f32, ulps: i32) -> f32 {
    let mut v = value;
    for _ in 0..ulps.unsigned_abs() {
        v = step_f32(v, ulps > 0);
    }
    v
}

/// The next f32 above (`up`) or below `v` (what `f32::next_up`/`next_down` do, which are newer
/// than the crate's minimum Rust version).
fn step_f32(v: f32, up: bool) -> f32 {
    if v.is_nan() || (up && v == f32::INFINITY) || (!up && v == f32::NEG_INFINITY) {
        return v;
    }
    if v == 0.0 {
        let tiny = f32::from_bits(1);
        return if up { tiny } else { -tiny };
    }
    let bits = v.to_bits();
    let away_from_zero = (v > 0.0) == up;
    f32::from_bits(if away_from_zero { bits + 1 } else { bits - 1 })
}

/// The same for f64.
fn step_f64(v: f64, up: bool) -> f64 {
    if v.is_nan() || (up && v == f64::INFINITY) || (!up && v == f64::NEG_INFINITY) {
        return v;
    }
    if v == 0.0 {
        let tiny = f64::from_bits(1);
        return if up { tiny } else { -tiny };
    }
    let bits = v.to_bits();
    let away_from_zero = (v > 0.0) == up;
    f64::from_bits(if away_from_zero { bits + 1 } else { bits - 1 })
}

/// Any f32 a caller might pass: ordinary magnitudes, edges, every bit pattern, and values
/// next to the crate's limits.
fn any_f32() -> impl Strategy<Value = f32> {
    prop_oneof![
        3 => -1e3f32..1e3,
        2 => -2f32..2.0,
        2 => prop::sample::select(EDGES_F32.to_vec()),
        1 => any::<f32>(),
        2 => (prop::sample::select(LIMITS_F32.to_vec()), -2i32..=2)
            .prop_map(|(limit, ulps)| nudge(limit, ulps)),
    ]
}

/// A positive f32 of any scale (most constructors want one), with the edges mixed in.
fn scale_f32() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => (-8f32..8.0).prop_map(|e| 10f32.powf(e)),
        1 => any_f32(),
    ]
}

/// Edge values of times, steps and world coordinates (f64).
const EDGES_F64: [f64; 16] = [
    0.0,
    -0.0,
    5e-324,
    1e-300,
    1.0,
    -1.0,
    1e6,
    -1e6,
    1e300,
    -1e300,
    f64::MAX,
    f64::MIN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NAN,
    1.17e6,
];

fn any_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => -1e4f64..1e4,
        2 => prop::sample::select(EDGES_F64.to_vec()),
        1 => any::<f64>(),
        2 => (
            prop::sample::select(vec![Cascade::MAX_TIME, -Cascade::MAX_TIME, ocean_fft::limits::MAX_STEP]),
            -2i32..=2
        )
            .prop_map(|(limit, ulps)| {
                let mut v = limit;
                for _ in 0..ulps.unsigned_abs() {
                    v = step_f64(v, ulps > 0);
                }
                v
            }),
    ]
}

/// Grid sizes: valid small ones, invalid small ones, and huge ones.
fn any_size() -> impl Strategy<Value = usize> {
    prop_oneof![
        10 => prop::sample::select(vec![4usize, 6, 8, 10, 16, 24, 32]),
        2 => prop::sample::select(vec![0usize, 1, 2, 3, 5, 7, 33]),
        1 => prop::sample::select(vec![
            CascadeConfig::MAX_SIZE - 2,
            CascadeConfig::MAX_SIZE,
            CascadeConfig::MAX_SIZE + 1,
            CascadeConfig::MAX_SIZE + 2,
            1 << 20,
            usize::MAX / 2 + 1,
            usize::MAX,
        ]),
    ]
}

/// Indices and counts: small ones and huge ones.
fn any_index() -> impl Strategy<Value = usize> {
    prop_oneof![
        4 => 0usize..40,
        1 => prop::sample::select(vec![usize::MAX, usize::MAX - 1, 1 << 40]),
    ]
}

/// Memory limits: the default, small ones (including 0) and the whole address space.
fn any_memory_limit() -> impl Strategy<Value = usize> {
    prop_oneof![
        7 => Just(CascadeConfig::DEFAULT_MEMORY_LIMIT),
        1 => prop::sample::select(vec![0usize, 1, 1 << 16, 1 << 20, usize::MAX]),
    ]
}

/// A valid config never builds more than this many bytes in these tests.
const TEST_MEMORY_LIMIT: usize = 64 << 20;

// ----------------------------------------------------------------------------------------
// Checks
// ----------------------------------------------------------------------------------------

/// Every error carries a name, and its message is non-empty and mentions it (where the
/// variant has one).
fn check_error(error: &Error) {
    let text = error.to_string();
    assert!(!text.is_empty());
    let name = match error {
        Error::NonFinite { name }
        | Error::OutOfRange { name, .. }
        | Error::InvalidSize { name, .. }
        | Error::CountOutOfRange { name, .. }
        | Error::IndexOutOfRange { name, .. }
        | Error::LengthMismatch { name, .. }
        | Error::NotApplicable { name, .. }
        | Error::SeaDoesNotFit { name, .. }
        | Error::NotDecreasing { name, .. } => Some(*name),
        _ => None,
    };
    if let Error::SeaDoesNotFit { held, min, .. } = error {
        assert!(held < min && held.is_finite(), "{error:?}");
    }
    if let Some(name) = name {
        assert!(text.contains(name), "{text:?} does not name {name}");
    }
    if let Error::OutOfRange {
        value, min, max, ..
    } = error
    {
        assert!(value.is_finite(), "{error:?}");
        let inside = match min {
            Bound::Included(a) => *value >= *a,
            Bound::Excluded(a) => *value > *a,
            Bound::Unbounded => true,
        } && match max {
            Bound::Included(b) => *value <= *b,
            Bound::Excluded(b) => *value < *b,
            Bound::Unbounded => true,
        };
        assert!(
            !inside,
            "OutOfRange for a value inside its range: {error:?}"
        );
    }
}

fn finite(values: &[f32]) -> bool {
    values.iter().all(|v| v.is_finite())
}

fn finite_sample(s: &SurfaceSample) -> bool {
    finite(&[s.height, s.foam])
        && finite(&s.displacement)
        && finite(&s.slope)
        && finite(&s.normal)
        && (0.0..=1.0).contains(&s.foam)
}

/// Every output buffer of a cascade, bit for bit, with its time.
fn cascade_bits(cascade: &Cascade) -> Vec<u64> {
    let mut bits = vec![
        cascade.time().to_bits(),
        cascade.config().choppiness.to_bits() as u64,
    ];
    let flat = |v: &[f32], bits: &mut Vec<u64>| bits.extend(v.iter().map(|x| x.to_bits() as u64));
    flat(cascade.height(), &mut bits);
    flat(cascade.jacobian(), &mut bits);
    flat(cascade.displacement().as_flattened(), &mut bits);
    flat(cascade.slope().as_flattened(), &mut bits);
    flat(cascade.normal().as_flattened(), &mut bits);
    bits
}

fn ocean_bits(ocean: &OceanState) -> Vec<u64> {
    let mut bits = vec![ocean.time().to_bits()];
    for cascade in ocean.cascades() {
        bits.extend(cascade_bits(cascade));
    }
    for buffer in [
        ocean.foam_view().total(),
        ocean.foam_view().active(),
        ocean.foam_view().residual(),
        ocean.foam_view().breaking(),
    ] {
        bits.extend(buffer.iter().map(|x| x.to_bits() as u64));
    }
    let c = ocean.foam_view().coverage();
    bits.extend([c.active, c.residual, c.total].map(|x| x.to_bits() as u64));
    // What a change of weather or of the foam settings moves.
    bits.push(ocean.diagnostics().expected_variance().to_bits());
    bits.push(
        ocean
            .diagnostics()
            .transition_progress()
            .map_or(u64::MAX, f64::to_bits),
    );
    bits.push(ocean.foam_view().calibration().threshold.to_bits() as u64);
    bits
}

fn cascade_finite(cascade: &Cascade) -> bool {
    finite(cascade.height())
        && finite(cascade.jacobian())
        && finite(cascade.displacement().as_flattened())
        && finite(cascade.slope().as_flattened())
        && finite(cascade.normal().as_flattened())
}

fn ocean_finite(ocean: &OceanState) -> bool {
    let unit = |v: &f32| (0.0..=1.0).contains(v);
    let c = ocean.foam_view().coverage();
    let subgrid = ocean.textures().subgrid_slope_variance();
    ocean.cascades().iter().all(cascade_finite)
        && ocean.diagnostics().mean_level_offset().is_finite()
        && subgrid.along.is_finite()
        && subgrid.across.is_finite()
        && [
            ocean.foam_view().total(),
            ocean.foam_view().active(),
            ocean.foam_view().residual(),
        ]
        .iter()
        .all(|buffer| buffer.iter().all(unit))
        && ocean
            .foam_view()
            .breaking()
            .iter()
            .all(|s| s.is_finite() && *s >= 0.0)
        && [c.active, c.residual, c.total].iter().all(unit)
}

// ----------------------------------------------------------------------------------------
// Spectra
// ----------------------------------------------------------------------------------------

#[derive(Debug, Clone)]
enum Build {
    Jonswap(f32, f32),
    PiersonMoskowitz(f32),
    Tma(f32, f32, f32),
    Phillips(f32, f32),
    FromParameters(f32, f32, f32),
    Elfouhaily(f32, f32),
}

fn any_build() -> impl Strategy<Value = Build> {
    prop_oneof![
        (scale_f32(), scale_f32()).prop_map(|(u, f)| Build::Jonswap(u, f)),
        scale_f32().prop_map(Build::PiersonMoskowitz),
        (scale_f32(), scale_f32(), scale_f32()).prop_map(|(u, f, h)| Build::Tma(u, f, h)),
        (scale_f32(), scale_f32()).prop_map(|(u, a)| Build::Phillips(u, a)),
        (scale_f32(), scale_f32(), scale_f32())
            .prop_map(|(a, w, g)| Build::FromParameters(a, w, g)),
        (scale_f32(), prop_oneof![0.84f32..5.0, any_f32()])
            .prop_map(|(u, omega)| Build::Elfouhaily(u, omega)),
    ]
}

fn build(b: &Build) -> Result<Spectrum, Error> {
    match *b {
        Build::Jonswap(u, f) => Spectrum::jonswap(u, f),
        Build::PiersonMoskowitz(u) => Spectrum::pierson_moskowitz(u),
        Build::Tma(u, f, h) => Spectrum::tma(u, f, h),
        Build::Phillips(u, a) => Spectrum::phillips(u, a),
        Build::FromParameters(a, w, g) => Spectrum::jonswap_from_parameters(a, w, g),
        Build::Elfouhaily(u, omega) => Spectrum::elfouhaily(u, omega),
    }
}

#[derive(Debug, Clone)]
enum Setter {
    Gamma(f32),
    WindDirection(f32),
    Spreading(Spreading),
    Swell(f32),
    SpreadBlend(f32),
    ShortWaveLength(f32),
    Depth(f32),
    Dispersion(Dispersion),
    DepthFactor(DepthFactor),
}

fn any_spreading() -> impl Strategy<Value = Spreading> {
    prop_oneof![
        Just(Spreading::Mitsuyasu),
        Just(Spreading::Hasselmann),
        Just(Spreading::DonelanBanner),
        Just(Spreading::Flat),
        Just(Spreading::Cos2),
        Just(Spreading::Elfouhaily),
        any_f32().prop_map(|s| Spreading::Cos2s { s }),
        (any_f32(), any_f32())
            .prop_map(|(exponent, upwind)| Spreading::Cosine { exponent, upwind }),
    ]
}

/// Dispersions built directly from their public fields (unchecked depths included).
fn any_dispersion() -> impl Strategy<Value = Dispersion> {
    prop_oneof![
        Just(Dispersion::Deep),
        any_f32().prop_map(|depth| Dispersion::FiniteDepth { depth }),
        any_f32().prop_map(|depth| Dispersion::Capillary { depth }),
    ]
}

fn any_setter() -> impl Strategy<Value = Setter> {
    prop_oneof![
        any_f32().prop_map(Setter::Gamma),
        any_f32().prop_map(Setter::WindDirection),
        any_spreading().prop_map(Setter::Spreading),
        any_f32().prop_map(Setter::Swell),
        any_f32().prop_map(Setter::SpreadBlend),
        any_f32().prop_map(Setter::ShortWaveLength),
        scale_f32().prop_map(Setter::Depth),
        any_dispersion().prop_map(Setter::Dispersion),
        prop::sample::select(vec![
            DepthFactor::None,
            DepthFactor::Kitaigorodskii,
            DepthFactor::ThompsonVincent
        ])
        .prop_map(Setter::DepthFactor),
    ]
}

fn apply(spectrum: Spectrum, setter: &Setter) -> Result<Spectrum, Error> {
    match *setter {
        Setter::Gamma(v) => spectrum.with_gamma(v),
        Setter::WindDirection(v) => spectrum.with_wind_direction(v),
        Setter::Spreading(v) => spectrum.with_spreading(v),
        Setter::Swell(v) => spectrum.with_swell(v),
        Setter::SpreadBlend(v) => spectrum.with_spread_blend(v),
        Setter::ShortWaveLength(v) => spectrum.with_short_wave_length(v),
        Setter::Depth(v) => spectrum.with_depth(v),
        Setter::Dispersion(v) => spectrum.with_dispersion(v),
        Setter::DepthFactor(v) => spectrum.with_depth_factor(v),
    }
}

/// A spectrum built from any inputs, then changed by any setters (a failed setter leaves the
/// spectrum it was given, as a caller holding a clone would).
fn any_spectrum() -> impl Strategy<Value = Option<Spectrum>> {
    (any_build(), prop::collection::vec(any_setter(), 0..4)).prop_map(|(b, setters)| {
        let mut spectrum = build(&b).ok()?;
        for setter in &setters {
            if let Ok(changed) = apply(spectrum.clone(), setter) {
                spectrum = changed;
            }
        }
        Some(spectrum)
    })
}

/// The spectra the cascade and ocean properties draw from: valid, from gentle to extreme.
fn valid_spectrum() -> impl Strategy<Value = Spectrum> {
    prop_oneof![
        3 => Just(Spectrum::jonswap(10.0, 100_000.0).unwrap()),
        1 => Just(Spectrum::pierson_moskowitz(Spectrum::MAX_WIND_SPEED).unwrap()),
        1 => Just(Spectrum::phillips(30.0, f32::MAX).unwrap()),
        1 => Just(Spectrum::phillips(1e-3, 1e-30).unwrap()),
        1 => Just(Spectrum::tma(8.0, 15_000.0, 1e-3).unwrap()),
        1 => Just(
            Spectrum::jonswap_from_parameters(1e30, 1e-6, 1e30)
                .unwrap()
                .with_spreading(Spreading::Mitsuyasu)
                .unwrap()
        ),
        2 => any_spectrum().prop_filter_map("a valid spectrum", |s| s),
    ]
}

proptest! {
    #![proptest_config(config())]

    /// Constructors and setters give `Err` or a spectrum whose every evaluation is finite.
    #[test]
    fn spectra_evaluate_finitely(
        spectrum in any_spectrum(),
        probes in prop::collection::vec((any_f32(), any_f32()), 1..6),
    ) {
        let Some(spectrum) = spectrum else { return Ok(()) };
        prop_assert!(spectrum.significant_wave_height().is_finite());
        prop_assert!(spectrum.peak_omega().is_finite() && spectrum.peak_period().is_finite());
        prop_assert!(finite(&spectrum.wind_vector()));
        for &(a, b) in &probes {
            prop_assert!(spectrum.density([a, b]).is_finite(), "density at ({a}, {b})");
            prop_assert!(spectrum.omega_spectrum(a).is_finite(), "S(ω) at {a}");
            prop_assert!(spectrum.spreading(a, b).is_finite(), "D at ({a}, {b})");
            prop_assert!(spectrum.band_variance(a, b).is_finite(), "variance on [{a}, {b})");
            prop_assert!(spectrum.density([a, b]) >= 0.0);
            let slopes = spectrum.slope_variance(a, b);
            prop_assert!(
                slopes.along.is_finite() && slopes.across.is_finite()
                    && slopes.along >= 0.0 && slopes.across >= 0.0,
                "slope variance on [{a}, {b}): {slopes:?}"
            );
        }
    }

    /// Every constructor and setter error names its parameter and carries consistent bounds.
    #[test]
    fn spectrum_errors_are_well_formed(b in any_build(), setter in any_setter()) {
        match build(&b) {
            Err(error) => check_error(&error),
            Ok(spectrum) => {
                if let Err(error) = apply(spectrum, &setter) {
                    check_error(&error);
                }
            }
        }
    }

    /// Dispersion evaluation is finite for every depth (checked or not) and every k or ω.
    #[test]
    fn dispersion_evaluates_finitely(dispersion in any_dispersion(), x in any_f32()) {
        prop_assert!(dispersion.omega(x).is_finite(), "{dispersion:?} ω({x})");
        prop_assert!(dispersion.d_omega_dk(x).is_finite(), "{dispersion:?} dω/dk({x})");
        prop_assert!(dispersion.k_from_omega(x).is_finite(), "{dispersion:?} k({x})");
        if let Some(depth) = dispersion.depth() {
            prop_assert!(depth.is_finite() && depth > 0.0);
        }
        for made in [Dispersion::finite_depth(x), Dispersion::capillary(x)] {
            match made {
                Ok(d) => prop_assert!(d.validate().is_ok()),
                Err(error) => check_error(&error),
            }
        }
    }

    /// Field multipliers are finite at every wave vector.
    #[test]
    fn multipliers_are_finite(kx in any_f32(), kz in any_f32()) {
        for field in Field::ALL {
            let m = field.multiplier([kx, kz]);
            prop_assert!(m.re.is_finite() && m.im.is_finite(), "{field:?} at ({kx}, {kz})");
        }
    }
}

// ----------------------------------------------------------------------------------------
// Cascades
// ----------------------------------------------------------------------------------------

/// Mostly `usual`, sometimes anything: each config field is adversarial about one time in
/// eight, so that a fair share of configs is valid and the calls after construction run too.
fn mostly<T: std::fmt::Debug + Clone + 'static>(
    usual: impl Strategy<Value = T> + 'static,
    any: impl Strategy<Value = T> + 'static,
) -> BoxedStrategy<T> {
    prop_oneof![7 => usual, 1 => any].boxed()
}

fn any_cascade_config() -> impl Strategy<Value = CascadeConfig> {
    (
        any_size(),
        mostly(1f32..5000.0, any_f32()),
        mostly(Just(0.0f32), any_f32()),
        mostly(Just(f32::INFINITY), any_f32()),
        mostly(0f32..3.0, any_f32()),
        any::<u64>(),
        mostly(Just(None), any_f32().prop_map(Some)),
        any_memory_limit(),
        any_determinism(),
    )
        .prop_map(
            |(
                size,
                length,
                k_min,
                k_max,
                choppiness,
                seed,
                repeat_period,
                memory_limit,
                determinism,
            )| {
                // A valid large grid would allocate gigabytes: bound what these tests build.
                let memory_limit = if size > 32 {
                    memory_limit.min(TEST_MEMORY_LIMIT)
                } else {
                    memory_limit
                };
                CascadeConfig {
                    size,
                    length,
                    k_min,
                    k_max,
                    choppiness,
                    seed,
                    repeat_period,
                    memory_limit,
                    determinism,
                }
            },
        )
}

/// Either mode, half the time each.
fn any_determinism() -> impl Strategy<Value = Determinism> {
    prop::sample::select(vec![Determinism::SameMachine, Determinism::CrossPlatform])
}

#[derive(Debug, Clone)]
enum CascadeOp {
    Update(f64),
    SetChoppiness(f32),
    WaveSpectrum(f64),
    OmegaAt(usize, usize),
    PackedTransform(usize),
}

fn any_cascade_op() -> impl Strategy<Value = CascadeOp> {
    prop_oneof![
        3 => any_f64().prop_map(CascadeOp::Update),
        2 => any_f32().prop_map(CascadeOp::SetChoppiness),
        1 => any_f64().prop_map(CascadeOp::WaveSpectrum),
        1 => (any_index(), any_index()).prop_map(|(i, j)| CascadeOp::OmegaAt(i, j)),
        1 => any_index().prop_map(CascadeOp::PackedTransform),
    ]
}

proptest! {
    #![proptest_config(config())]

    /// A cascade is refused with a well-formed error, or built with finite buffers; every
    /// later call either succeeds with finite results or fails leaving the buffers bit for
    /// bit as they were.
    #[test]
    fn cascades_hold_under_any_input(
        spectrum in valid_spectrum(),
        config in any_cascade_config(),
        ops in prop::collection::vec(any_cascade_op(), 0..8),
    ) {
        let validated = config.validate();
        let built = Cascade::new(&spectrum, config);
        let mut cascade = match built {
            Err(error) => {
                check_error(&error);
                return Ok(());
            }
            Ok(cascade) => cascade,
        };
        prop_assert!(validated.is_ok(), "built a cascade its config's validate refused");
        prop_assert!(cascade_finite(&cascade));
        let n = cascade.size();
        for op in &ops {
            let before = cascade_bits(&cascade);
            let result = match *op {
                CascadeOp::Update(t) => cascade.update(t).map(|()| {
                    assert!(cascade_finite(&cascade), "non-finite buffer after update({t})");
                }),
                CascadeOp::SetChoppiness(lambda) => cascade.set_choppiness(lambda).map(|()| {
                    assert_eq!(cascade.config().choppiness, lambda);
                }),
                CascadeOp::WaveSpectrum(t) => inspect::wave_spectrum(&cascade, t).map(|h| {
                    assert_eq!(h.len(), n * n);
                    assert!(h.iter().all(|c| c.re.is_finite() && c.im.is_finite()));
                }),
                CascadeOp::OmegaAt(i, j) => inspect::omega_at(&cascade, i, j).map(|omega| {
                    assert!(i < n && j < n && omega.is_finite() && omega >= 0.0);
                }),
                CascadeOp::PackedTransform(p) => inspect::packed_transform(&cascade, p).map(|values| {
                    assert!(p < 4 && values.len() == n * n);
                    assert!(values.iter().all(|c| c.re.is_finite() && c.im.is_finite()));
                }),
            };
            match result {
                Ok(()) => {
                    if !matches!(op, CascadeOp::Update(_) | CascadeOp::SetChoppiness(_)) {
                        prop_assert_eq!(&before, &cascade_bits(&cascade), "{:?} changed state", op);
                    }
                }
                Err(error) => {
                    check_error(&error);
                    prop_assert_eq!(&before, &cascade_bits(&cascade), "failed {:?} changed state", op);
                }
            }
        }
        // A choppiness change shows at the next update, which must stay finite.
        if cascade.update(cascade.time()).is_ok() {
            prop_assert!(cascade_finite(&cascade));
        }
        for field in Field::ALL {
            prop_assert!(finite(&inspect::field(&cascade, field)));
        }
    }

    /// `Fft2d` refuses bad sizes, counts and lengths (and gigantic requests) with `Err`, never
    /// aborting, and transforms finite data to finite data.
    #[test]
    fn fft2d_holds_under_any_input(size in any_size(), count in any_index(), extra in 0usize..3) {
        match Fft2d::new(size, count) {
            Err(error) => check_error(&error),
            Ok(mut fft) => {
                let len = count * size * size;
                let mut wrong = vec![ocean_fft::inspect::Complex32::new(1.0, 0.0); len + extra];
                if extra > 0 {
                    let error = fft.process(&mut wrong).unwrap_err();
                    check_error(&error);
                    let named = matches!(error, Error::LengthMismatch { name: "data", .. });
                    prop_assert!(named, "{:?}", error);
                } else if len <= 1 << 16 {
                    let out = fft.process(&mut wrong).unwrap();
                    prop_assert!(out.iter().all(|c| c.re.is_finite() && c.im.is_finite()));
                }
            }
        }
    }
}

// ----------------------------------------------------------------------------------------
// Oceans
// ----------------------------------------------------------------------------------------

fn any_foam() -> impl Strategy<Value = FoamConfig> {
    (
        mostly(0f32..20.0, any_f32()),
        mostly(Just(None), any_f32().prop_map(Some)),
        mostly(0.01f32..100.0, any_f32()),
        mostly(0.01f32..100.0, any_f32()),
        mostly(0f32..0.2, any_f32()),
        mostly(0f32..2.0, any_f32()),
        mostly(0f32..0.5, any_f32()),
    )
        .prop_map(
            |(
                coverage,
                wind_speed,
                active_decay,
                residual_decay,
                drift,
                streak_length,
                streak_width,
            )| FoamConfig {
                coverage,
                wind_speed,
                active_decay,
                residual_decay,
                drift,
                streak_length,
                streak_width,
            },
        )
}

fn any_ocean_config() -> impl Strategy<Value = OceanConfig> {
    // Usually decreasing lengths a factor 2.5–6 apart (so each band holds grid vectors),
    // sometimes any list of any lengths.
    let decreasing =
        (10f32..3000.0, prop::collection::vec(2.5f32..6.0, 0..3)).prop_map(|(first, ratios)| {
            let mut lengths = vec![first];
            for ratio in ratios {
                lengths.push(lengths[lengths.len() - 1] / ratio);
            }
            lengths
        });
    (
        mostly(decreasing, prop::collection::vec(any_f32(), 0..10)),
        mostly(prop::sample::select(vec![8usize, 16]), any_size()),
        mostly(0f32..2.0, any_f32()),
        mostly(Just(0.0f32), any_f32()),
        mostly(Just(f32::INFINITY), any_f32()),
        mostly(0.2f32..1.0, any_f32()),
        any_foam(),
        mostly(Just(None), any_f32().prop_map(Some)),
        (
            mostly(1usize..40, any_index()),
            mostly(1e-6f32..1.0, any_f32()),
            any::<bool>(),
        ),
        any_memory_limit(),
        (any::<bool>(), any_determinism(), any::<bool>()),
    )
        .prop_map(
            |(
                lengths,
                size,
                choppiness,
                k_min,
                k_max,
                band_split,
                foam,
                repeat_period,
                (max_iterations, tolerance, bilinear),
                memory_limit,
                (parallel_cascades, determinism, second_order),
            )| {
                let memory_limit = if size > 16 {
                    memory_limit.min(TEST_MEMORY_LIMIT)
                } else {
                    memory_limit
                };
                OceanConfig {
                    lengths,
                    size,
                    choppiness,
                    seed: 7,
                    k_min,
                    k_max,
                    band_split,
                    foam,
                    repeat_period,
                    parallel_cascades,
                    query: QueryConfig {
                        max_iterations,
                        tolerance,
                        interpolation: if bilinear {
                            Interpolation::Bilinear
                        } else {
                            Interpolation::CubicBSpline
                        },
                    },
                    memory_limit,
                    determinism,
                    second_order,
                    wakes: None,
                }
            },
        )
}

#[derive(Debug, Clone)]
enum OceanOp {
    Step(f64),
    SetTime(f64),
    SetChoppiness(f32),
    Sample(f64, f64),
    SampleCascades(f64, f64, usize, usize),
    HeightAt(f64, f64),
    SurfaceAt(f64, f64),
    Locate(f64, f64),
    Batch(Vec<[f64; 2]>, usize),
    Grid([f64; 2], f64, [usize; 2], usize),
    BreakingAt(f64, f64),
    PreRoll(f64, f64),
    StepTo(f64),
    ClearFoam,
    Snapshot,
    Restore,
    SetSpectrum(Spectrum, f64),
    SetSpectrumUnfitted(Spectrum, f64),
    SetFoamConfig(FoamConfig),
    FoamAt(f64, f64),
    /// Takes a `Surface` handle and queries it at these points (and keeps it for the end).
    Surface(Vec<[f64; 2]>),
}

fn any_ocean_op() -> impl Strategy<Value = OceanOp> {
    prop_oneof![
        3 => prop_oneof![1 => Just(0.0), 3 => 0f64..0.1, 1 => any_f64()].prop_map(OceanOp::Step),
        1 => any_f64().prop_map(OceanOp::SetTime),
        1 => any_f32().prop_map(OceanOp::SetChoppiness),
        2 => (any_f64(), any_f64()).prop_map(|(x, z)| OceanOp::Sample(x, z)),
        1 => (any_f64(), any_f64(), 0usize..5, 0usize..5)
            .prop_map(|(x, z, a, b)| OceanOp::SampleCascades(x, z, a, b)),
        2 => (any_f64(), any_f64()).prop_map(|(x, z)| OceanOp::HeightAt(x, z)),
        1 => (any_f64(), any_f64()).prop_map(|(x, z)| OceanOp::SurfaceAt(x, z)),
        1 => (any_f64(), any_f64()).prop_map(|(x, z)| OceanOp::Locate(x, z)),
        1 => (
            (any_f64(), any_f64()),
            prop_oneof![3 => 0.1f64..100.0, 1 => any_f64()],
            (prop_oneof![3 => 1usize..12, 1 => any_index()], prop_oneof![3 => 1usize..12, 1 => any_index()]),
            0usize..2,
        )
            .prop_map(|((x, z), spacing, (c, r), extra)| OceanOp::Grid([x, z], spacing, [c, r], extra)),
        2 => prop_oneof![2 => -0.1f64..0.2, 1 => any_f64()].prop_map(OceanOp::StepTo),
        1 => Just(OceanOp::ClearFoam),
        1 => Just(OceanOp::Snapshot),
        1 => Just(OceanOp::Restore),
        1 => (prop::collection::vec((any_f64(), any_f64()).prop_map(|(x, z)| [x, z]), 0..80), 0usize..3)
            .prop_map(|(points, extra)| OceanOp::Batch(points, extra)),
        1 => (any_f64(), any_f64()).prop_map(|(x, z)| OceanOp::BreakingAt(x, z)),
        1 => (any_f64(), any_f64()).prop_map(|(x, z)| OceanOp::FoamAt(x, z)),
        1 => (
            valid_spectrum(),
            prop_oneof![2 => Just(0.0), 3 => 0f64..0.5, 1 => any_f64()],
        )
            .prop_map(|(spectrum, duration)| OceanOp::SetSpectrum(spectrum, duration)),
        1 => (
            valid_spectrum(),
            prop_oneof![2 => Just(0.0), 3 => 0f64..0.5, 1 => any_f64()],
        )
            .prop_map(|(spectrum, duration)| OceanOp::SetSpectrumUnfitted(spectrum, duration)),
        1 => any_foam().prop_map(OceanOp::SetFoamConfig),
        1 => prop::collection::vec((any_f64(), any_f64()).prop_map(|(x, z)| [x, z]), 0..20)
            .prop_map(OceanOp::Surface),
        1 => (
            prop_oneof![3 => 0f64..1.0, 1 => prop::sample::select(vec![-1.0, f64::NAN, f64::INFINITY, 1e300, 0.0])],
            prop_oneof![
                3 => 0.05f64..0.5,
                1 => prop::sample::select(vec![0.0, -0.1, 1e-300, f64::NAN, f64::INFINITY, ocean_fft::limits::MAX_STEP, ocean_fft::limits::MAX_STEP * (1.0 + 1e-15)]),
            ],
        )
            .prop_map(|(seconds, dt)| OceanOp::PreRoll(seconds, dt)),
    ]
}

/// Runs one query-style op: its result must be finite, or an error.
fn query(ocean: &OceanState, op: &OceanOp) -> Result<(), Error> {
    match *op {
        OceanOp::Sample(x, z) => ocean
            .water()
            .at_rest(x, z)
            .map(|s| assert!(finite_sample(&s), "{s:?}")),
        OceanOp::SampleCascades(x, z, a, b) => ocean
            .water()
            .at_rest_cascades(x, z, a..b)
            .map(|s| assert!(finite_sample(&s), "{s:?}")),
        OceanOp::HeightAt(x, z) => ocean
            .water()
            .height_at(x, z)
            .map(|y| assert!(y.is_finite())),
        OceanOp::SurfaceAt(x, z) => ocean
            .water()
            .surface_at(x, z)
            .map(|s| assert!(finite_sample(&s), "{s:?}")),
        OceanOp::Locate(x, z) => ocean.water().locate(x, z).map(|found| {
            let p = found.undisplaced;
            assert!(p[0].is_finite() && p[1].is_finite() && !found.miss.is_nan());
            assert_eq!(found.converged, found.miss < ocean.config().query.tolerance);
        }),
        OceanOp::Grid(origin, spacing, [columns, rows], extra) => {
            // Only allocate a buffer for windows of sane sizes; larger ones must fail on
            // the length check (or before).
            let len = columns.saturating_mul(rows).min(1 << 12) + extra;
            let mut out = vec![SurfaceSample::default(); len];
            let result = ocean
                .water()
                .at_rest_grid(origin, spacing, [columns, rows], &mut out);
            if result.is_ok() {
                assert!(out.iter().all(finite_sample));
                // A grid point is `sample` there (the first, a middle and the last).
                for i in [0, out.len() / 2, out.len() - 1] {
                    let x = origin[0] + (i % columns) as f64 * spacing;
                    let z = origin[1] + (i / columns) as f64 * spacing;
                    assert_eq!(ocean.water().at_rest(x, z), Ok(out[i]), "grid point {i}");
                }
            } else {
                assert!(
                    out.iter().all(|s| *s == SurfaceSample::default()),
                    "wrote on error"
                );
            }
            result
        }
        OceanOp::Batch(ref points, extra) => {
            let mut heights = vec![f32::NAN; points.len() + extra];
            let mut surfaces = vec![SurfaceSample::default(); points.len() + extra];
            let a = ocean.water().heights_at(points, &mut heights);
            if a.is_err() {
                assert!(
                    heights.iter().all(|h| h.is_nan()),
                    "heights_at wrote on error"
                );
            } else {
                assert!(finite(&heights));
            }
            let b = ocean.water().surfaces_at(points, &mut surfaces);
            let c = ocean.water().at_rest_many(points, &mut surfaces);
            if b.is_ok() && c.is_ok() {
                assert!(surfaces.iter().all(finite_sample));
            }
            assert_eq!(a.is_ok(), b.is_ok());
            assert_eq!(b.is_ok(), c.is_ok());
            a
        }
        OceanOp::BreakingAt(x, z) => ocean.foam_view().breaking_at(x, z).map(|s| {
            assert!(s.is_finite() && s >= 0.0, "{s}");
        }),
        OceanOp::FoamAt(x, z) => ocean.foam_view().foam_at(x, z).map(|c| {
            for v in [c.active, c.residual, c.total] {
                assert!((0.0..=1.0).contains(&v), "{c:?}");
            }
        }),
        _ => unreachable!("not a query"),
    }
}

proptest! {
    #![proptest_config(config())]

    /// An ocean is refused with a well-formed error or built finite; steps, time jumps,
    /// choppiness changes and every query either succeed with finite results or fail leaving
    /// the ocean bit for bit as it was.
    #[test]
    fn oceans_hold_under_any_input(
        spectrum in valid_spectrum(),
        config in any_ocean_config(),
        ops in prop::collection::vec(any_ocean_op(), 0..10),
    ) {
        match config.bands() {
            Ok(bands) => prop_assert_eq!(bands.len(), config.lengths.len()),
            Err(error) => check_error(&error),
        }
        let built = match OceanState::new(spectrum.clone(), config.clone()) {
            // Random tiles often miss a random sea: go on with tiles fitted to it, so that
            // the operations below still meet every kind of ocean.
            Err(Error::SeaDoesNotFit { .. }) => config
                .with_fitted_lengths(&spectrum)
                .and_then(|fitted| OceanState::new(spectrum, fitted)),
            other => other,
        };
        let mut ocean = match built {
            Err(error) => {
                check_error(&error);
                return Ok(());
            }
            Ok(ocean) => ocean,
        };
        prop_assert!(ocean_finite(&ocean));
        check_fit(&ocean.diagnostics().fit());
        prop_assert!(ocean.diagnostics().fit().held >= ocean_fft::limits::MIN_BUILD_SHARE);
        prop_assert!(ocean.config().choppiness <= ocean.diagnostics().max_choppiness());
        let mut saved = ocean.snapshot();
        // Handles taken by `OceanOp::Surface`, with the answers they gave then.
        let mut handles: Vec<Held> = Vec::new();
        for op in &ops {
            let before = ocean_bits(&ocean);
            let mutating = matches!(
                op,
                OceanOp::Step(_)
                    | OceanOp::SetTime(_)
                    | OceanOp::SetChoppiness(_)
                    | OceanOp::StepTo(_)
                    | OceanOp::ClearFoam
                    | OceanOp::Restore
                    | OceanOp::PreRoll(..)
                    | OceanOp::SetSpectrum(..)
                    | OceanOp::SetSpectrumUnfitted(..)
                    | OceanOp::SetFoamConfig(_)
            );
            let spectrum_before = ocean.spectrum().clone();
            let config_before = ocean.config().clone();
            let result = match *op {
                OceanOp::Step(dt) => ocean.step(dt),
                OceanOp::SetTime(t) => ocean.set_time(t),
                OceanOp::SetChoppiness(lambda) => ocean.set_choppiness(lambda),
                OceanOp::StepTo(offset) => ocean.step_to(ocean.time() + offset),
                OceanOp::PreRoll(seconds, dt) => {
                    let time = ocean.time();
                    ocean.pre_roll(seconds, dt).map(|()| assert_eq!(ocean.time(), time))
                }
                OceanOp::ClearFoam => {
                    ocean.clear_foam();
                    Ok(())
                }
                OceanOp::Snapshot => {
                    saved = ocean.snapshot();
                    Ok(())
                }
                OceanOp::Restore => ocean.restore(&saved).map(|()| {
                    assert_eq!(ocean.snapshot(), saved, "restore did not restore");
                }),
                OceanOp::SetSpectrum(ref spectrum, duration) => ocean
                    .set_spectrum(spectrum.clone(), duration)
                    .map(|()| {
                        assert_eq!(ocean.spectrum(), spectrum);
                        // Accepted only if the grids hold the share.
                        assert!(ocean.diagnostics().fit().held >= ocean_fft::limits::MIN_CHANGE_SHARE);
                    }),
                OceanOp::SetSpectrumUnfitted(ref spectrum, duration) => ocean
                    .set_spectrum_unfitted(spectrum.clone(), duration)
                    .map(|()| assert_eq!(ocean.spectrum(), spectrum)),
                OceanOp::SetFoamConfig(foam) => ocean
                    .set_foam_config(foam)
                    .map(|()| assert_eq!(ocean.config().foam, foam)),
                OceanOp::Surface(ref points) => {
                    let surface = ocean.surface();
                    prop_assert_eq!(surface.time(), ocean.time());
                    // Every query of the handle: the ocean's answer, or the same error.
                    let answers: Vec<_> = points
                        .iter()
                        .map(|&[x, z]| surface.water().surface_at(x, z))
                        .collect();
                    for (&[x, z], answer) in points.iter().zip(&answers) {
                        prop_assert_eq!(answer, &ocean.water().surface_at(x, z));
                        prop_assert_eq!(surface.water().at_rest(x, z), ocean.water().at_rest(x, z));
                        prop_assert_eq!(surface.water().locate(x, z), ocean.water().locate(x, z));
                        prop_assert_eq!(
                            surface.water().height_at(x, z).map(f32::to_bits),
                            ocean.water().height_at(x, z).map(f32::to_bits)
                        );
                    }
                    let mut a = vec![0.0f32; points.len()];
                    let mut b = vec![0.0f32; points.len()];
                    prop_assert_eq!(
                        surface.water().heights_at(points, &mut a),
                        ocean.water().heights_at(points, &mut b)
                    );
                    prop_assert_eq!(bits_of(&a), bits_of(&b));
                    let mut a = vec![SurfaceSample::default(); points.len()];
                    let mut b = a.clone();
                    prop_assert_eq!(
                        surface.water().surfaces_at(points, &mut a),
                        ocean.water().surfaces_at(points, &mut b)
                    );
                    prop_assert_eq!(&a, &b);
                    prop_assert_eq!(
                        surface.water().at_rest_many(points, &mut a),
                        ocean.water().at_rest_many(points, &mut b)
                    );
                    prop_assert_eq!(&a, &b);
                    handles.push((surface, points.clone(), answers));
                    Ok(())
                }
                _ => query(&ocean, op),
            };
            match result {
                Ok(()) => {
                    prop_assert!(ocean_finite(&ocean), "non-finite state after {:?}", op);
                    if !mutating {
                        prop_assert_eq!(&before, &ocean_bits(&ocean), "{:?} changed state", op);
                    }
                }
                Err(error) => {
                    check_error(&error);
                    prop_assert_eq!(&before, &ocean_bits(&ocean), "failed {:?} changed state", op);
                    prop_assert_eq!(&spectrum_before, ocean.spectrum(), "failed {:?}", op);
                    prop_assert_eq!(&config_before, ocean.config(), "failed {:?}", op);
                }
            }
        }
        check_fit(&ocean.diagnostics().fit());
        prop_assert!(ocean.diagnostics().max_choppiness() > 0.0);
        // The last choppiness set shows at the next step.
        if ocean.step(0.0).is_ok() {
            prop_assert!(ocean_finite(&ocean));
        }
        // Whatever happened to the ocean since, a handle answers as it did when taken.
        for (surface, points, answers) in &handles {
            for (&[x, z], answer) in points.iter().zip(answers) {
                prop_assert_eq!(&surface.water().surface_at(x, z), answer);
            }
        }
    }
}

/// A `SeaFit`'s fractions lie in [0, 1] and add up to 1 (to the quadratures' precision,
/// 1e-4 with room), its variance finite and not negative.
fn check_fit(fit: &SeaFit) {
    for share in [fit.held, fit.too_long, fit.too_short] {
        assert!((-1e-6..=1.0 + 1e-6).contains(&share), "{fit:?}");
    }
    assert!(fit.variance.is_finite() && fit.variance >= 0.0, "{fit:?}");
    if fit.variance > 0.0 {
        assert!(
            (fit.held + fit.too_long + fit.too_short - 1.0).abs() < 1e-3,
            "{fit:?}"
        );
    }
}

proptest! {
    #![proptest_config(config())]

    /// Grids fitted to any valid spectrum hold the fitted share and build an ocean (at 16²,
    /// to keep it quick), or the call fails with a well-formed error; `fit` of any config is
    /// well formed or its validation error.
    #[test]
    fn fitted_grids_hold_any_sea(spectrum in valid_spectrum(), config in any_ocean_config()) {
        match config.fit(&spectrum) {
            Ok(fit) => check_fit(&fit),
            Err(error) => check_error(&error),
        }
        match OceanConfig::fitted(&spectrum) {
            Ok(fitted) => {
                let fit = fitted.fit(&spectrum).unwrap();
                check_fit(&fit);
                prop_assert!(fit.held >= OceanConfig::FITTED_SHARE, "{:?}", fit);
                let small = OceanConfig { size: 16, ..fitted };
                if let Err(error) = OceanState::new(spectrum, small) {
                    check_error(&error);
                }
            }
            Err(error) => check_error(&error),
        }
    }
}

/// A handle, the points it was asked about and its answers then.
type Held = (Surface, Vec<[f64; 2]>, Vec<Result<SurfaceSample, Error>>);

fn bits_of(values: &[f32]) -> Vec<u32> {
    values.iter().map(|v| v.to_bits()).collect()
}

/// A value for a field whose valid range ends at the given limits: usually ordinary, often
/// an edge value or a value a few ulps from one of the limits.
fn near(usual: std::ops::Range<f32>, limits: &[f32]) -> BoxedStrategy<f32> {
    let limits = limits.to_vec();
    prop_oneof![
        2 => usual,
        1 => prop::sample::select(EDGES_F32.to_vec()),
        2 => (prop::sample::select(limits), -2i32..=2).prop_map(|(l, ulps)| nudge(l, ulps)),
    ]
    .boxed()
}

proptest! {
    #![proptest_config(config())]

    /// Validation, bands and memory accounting of any ocean config: no panic, well-formed
    /// errors, and bands that tile `[k_min, k_max)` in order when they exist.
    #[test]
    fn ocean_configs_validate_without_panic(config in any_ocean_config()) {
        let _ = config.memory_bytes();
        match (config.validate(), config.bands()) {
            (Ok(()), Ok(bands)) => {
                prop_assert_eq!(bands.len(), config.lengths.len());
                prop_assert_eq!(bands[0].0, config.k_min);
                for pair in bands.windows(2) {
                    prop_assert_eq!(pair[0].1, pair[1].0);
                }
                for &(lower, upper) in &bands {
                    prop_assert!(lower < upper && upper <= config.k_max);
                }
            }
            (Err(a), Err(b)) => {
                check_error(&a);
                prop_assert_eq!(a, b);
            }
            (a, b) => prop_assert!(false, "validate {:?} but bands {:?}", a, b),
        }
    }

    /// Any foam setting the checks accept keeps the foam in [0, 1], the breaking intensity in
    /// finite and nonnegative and every query finite on a folding sea, whatever the steps (including
    /// zero-length and the longest ones); a refused setting is refused by `OceanState::new`
    /// with the error of `validate`.
    #[test]
    fn accepted_foam_settings_stay_finite(
        coverage in near(0.0..20.0, &[FoamConfig::MAX_COVERAGE, 0.0]),
        wind in prop_oneof![
            1 => Just(None),
            2 => near(0.0..40.0, &[Spectrum::MAX_WIND_SPEED, 0.0]).prop_map(Some),
        ],
        active_decay in near(0.01..100.0, &[FoamConfig::MIN_DECAY, FoamConfig::MAX_DECAY, 0.0]),
        residual_decay in near(0.01..100.0, &[FoamConfig::MIN_DECAY, FoamConfig::MAX_DECAY]),
        drift in near(0.0..0.2, &[FoamConfig::MAX_DRIFT, 0.0]),
        (streak_length, cross_fraction) in (
            near(0.0..2.0, &[FoamConfig::MAX_STREAK, 0.0]),
            prop_oneof![3 => 0f32..=1.0, 1 => prop::sample::select(vec![0.0f32, 1.0, 1.0000001, -0.0, f32::NAN])],
        ),
        steps in prop::collection::vec(
            prop::sample::select(vec![0.0, 1e-300, 1.0 / 60.0, 0.5, 60.0, ocean_fft::limits::MAX_STEP]),
            1..6,
        ),
    ) {
        let foam = FoamConfig {
            coverage,
            wind_speed: wind,
            active_decay,
            residual_decay,
            drift,
            streak_length,
            streak_width: streak_length * cross_fraction,
        };
        let (spectrum, mut config) = SeaState::Storm.build();
        config.size = 8;
        config.lengths = vec![300.0, 60.0];
        config.choppiness = 3.0;
        config.foam = foam;
        let accepted = foam.validate();
        let mut ocean = match OceanState::new(spectrum, config) {
            Err(error) => {
                prop_assert_eq!(Err(error.clone()), accepted);
                check_error(&error);
                return Ok(());
            }
            Ok(ocean) => ocean,
        };
        prop_assert!(accepted.is_ok());
        let calibration = ocean.foam_view().calibration();
        prop_assert!(!calibration.threshold.is_nan() && calibration.threshold < 1.5);
        prop_assert!((0.0..=0.5).contains(&calibration.target));
        for dt in steps {
            ocean.step(dt).unwrap();
            prop_assert!(ocean_finite(&ocean), "foam {:?} after a step of {} s", foam, dt);
            for (x, z) in [(0.0, 0.0), (17.3, -120.9), (1e6, 3.5)] {
                prop_assert!(finite_sample(&ocean.water().at_rest(x, z).unwrap()));
                prop_assert!(finite_sample(&ocean.water().surface_at(x, z).unwrap()));
                let s = ocean.foam_view().breaking_at(x, z).unwrap();
                prop_assert!(s.is_finite() && s >= 0.0);
            }
        }
        ocean.pre_roll(1.0, 0.25).unwrap();
        prop_assert!(ocean_finite(&ocean));
    }
}

/// Presets build, and a preset at a small size steps and answers queries finitely.
#[test]
fn every_preset_builds_and_steps() {
    for state in SeaState::ALL {
        let (spectrum, mut config) = state.build();
        config.size = 16;
        let mut ocean = OceanState::new(spectrum, config).unwrap();
        ocean.step(1.0 / 30.0).unwrap();
        assert!(ocean_finite(&ocean), "{state:?}");
        assert!(finite_sample(&ocean.water().surface_at(3.0, -7.0).unwrap()));
    }
}

// ----------------------------------------------------------------------------------------
// Serde round trips
// ----------------------------------------------------------------------------------------

#[cfg(feature = "serde")]
mod serde_round_trips {
    use super::*;

    /// `value` written to JSON and read back: either refused cleanly (an error, no panic) at
    /// either end, or read back equal (bit for bit, NaN-free by construction of the checks).
    fn round_trip<T>(value: &T) -> Option<T>
    where
        T: serde::Serialize + serde::de::DeserializeOwned,
    {
        let text = serde_json::to_string(value).ok()?;
        serde_json::from_str(&text).ok()
    }

    proptest! {
        #![proptest_config(config())]

        /// A spectrum survives the round trip exactly (it is valid, so it must).
        #[test]
        fn spectra_round_trip(spectrum in any_spectrum()) {
            let Some(spectrum) = spectrum else { return Ok(()) };
            let back = round_trip(&spectrum);
            prop_assert_eq!(back.as_ref(), Some(&spectrum));
        }

        /// Configs are passive data: a round trip is refused, or gives back the same config,
        /// which its constructor then judges exactly as it judged the original.
        #[test]
        fn configs_round_trip(cascade in any_cascade_config(), ocean in any_ocean_config()) {
            if let Some(back) = round_trip(&cascade) {
                prop_assert_eq!(back, cascade);
                prop_assert_eq!(back.validate().is_ok(), cascade.validate().is_ok());
            }
            if let Some(back) = round_trip(&ocean) {
                prop_assert_eq!(back.validate().is_ok(), ocean.validate().is_ok());
                prop_assert_eq!(&back, &ocean);
            }
            if let Some(back) = round_trip(&ocean.foam) {
                prop_assert_eq!(back, ocean.foam);
            }
        }
    }
}

// ----------------------------------------------------------------------------------------
// Determinism modes
// ----------------------------------------------------------------------------------------

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

proptest! {
    #![proptest_config(config())]

    /// The two modes evaluate the same spectrum and dispersion, one with std's functions and
    /// one with libm's: where both build a cascade, the expected variance Σ S(k)Δk² and every
    /// tabulated ω agree to 1e-10 relative. (The functions agree to an ulp or two; a density
    /// chains a few dozen of them, and exponents up to 700 amplify a relative error of an
    /// argument by 700: about 1e-13, so 1e-10 leaves room and still catches a wrong formula.)
    /// The amplitudes differ (other Gaussian draws), so errors that depend on them
    /// (`AmplitudeTooLarge`) may differ; every other error is the same.
    #[test]
    fn both_modes_evaluate_the_same_spectrum(
        spectrum in valid_spectrum(),
        size in prop::sample::select(vec![4usize, 8, 16, 34]),
        length in 1f32..5000.0,
        seed in any::<u64>(),
    ) {
        let config = |determinism| CascadeConfig {
            size,
            length,
            seed,
            determinism,
            memory_limit: TEST_MEMORY_LIMIT,
            ..CascadeConfig::default()
        };
        let fast = Cascade::new(&spectrum, config(Determinism::SameMachine));
        let portable = Cascade::new(&spectrum, config(Determinism::CrossPlatform));
        match (fast, portable) {
            (Ok(fast), Ok(portable)) => {
                let (a, b) = (fast.expected_variance(), portable.expected_variance());
                prop_assert!((a - b).abs() <= 1e-10 * a.abs().max(b.abs()), "{} vs {}", a, b);
                for j in 0..size {
                    for i in 0..size {
                        let (a, b) = (inspect::omega_at(&fast, i, j).unwrap(), inspect::omega_at(&portable, i, j).unwrap());
                        prop_assert!((a - b).abs() <= 1e-10 * a.abs().max(b.abs()), "ω({}, {})", i, j);
                    }
                }
                prop_assert!(cascade_finite(&portable));
            }
            (Err(Error::AmplitudeTooLarge { .. }), _) | (_, Err(Error::AmplitudeTooLarge { .. })) => {}
            (fast, portable) => prop_assert_eq!(fast.err(), portable.err()),
        }
    }

    /// An ocean in the cross-platform mode gives the same bits in pools of 1 and 2 threads,
    /// with any spectrum, through steps, queries included.
    #[test]
    fn cross_platform_oceans_are_the_same_at_any_thread_count(
        spectrum in valid_spectrum(),
        size in prop::sample::select(vec![8usize, 16, 34]),
        choppiness in 0f32..2.0,
        steps in prop::collection::vec(0f64..2.0, 1..4),
    ) {
        let config = OceanConfig {
            size,
            choppiness,
            determinism: Determinism::CrossPlatform,
            memory_limit: TEST_MEMORY_LIMIT,
            ..OceanConfig::default()
        };
        let run = |threads: usize| {
            pool(threads).install(|| {
                let mut ocean = OceanState::new(spectrum.clone(), config.clone()).ok()?;
                let mut bits = Vec::new();
                for &dt in &steps {
                    ocean.step(dt).unwrap();
                    bits.extend(ocean_bits(&ocean));
                    let s = ocean.water().surface_at(31.7, -250.2).unwrap();
                    bits.extend([s.height, s.foam].iter().chain(&s.normal).map(|v| u64::from(v.to_bits())));
                }
                Some(bits)
            })
        };
        prop_assert_eq!(run(1), run(2));
    }
}
