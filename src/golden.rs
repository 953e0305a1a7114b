//! Golden values of [`Determinism::CrossPlatform`]: hashes of every output buffer, h0 and a
//! few query results of three fixed configurations after fixed steps, compared with
//! constants committed here, on every SIMD level this CPU runs and at 1, 2 and 3 threads.
//!
//! The mode promises the same bits on every CPU and operating system, so these constants
//! hold everywhere: a change of CPU, operating system, toolchain, dependency (rustfft,
//! libm) or of the crate's own arithmetic that moves a single bit of the deterministic
//! waves fails here. A deliberate change of the model (a new foam model, another
//! formula) changes them too: then recompute them (the failure message prints the new
//! values), check that they agree on every level and thread count (the test does), and
//! say why in the commit.
//!
//! The constants were computed by this mode itself with every level the test runs (baseline
//! SSE2, AVX2, AVX-512) at 1, 2 and 3 threads, all of which gave the same values; a golden
//! test detects change, it does not verify correctness (the rest of the suite does that).
//! When a constant changes on purpose, the commit that changes it says why.
//!
//! The hash is [`BitHash`] (FNV-1a over the little-endian bytes of each value's bit pattern),
//! because std's `DefaultHasher` does not promise the same hashes across releases.

use crate::cascade::Cascade;
use crate::inspect::BitHash;
use crate::math::determinism::Determinism;
use crate::math::simd::Simd;
use crate::ocean::{OceanConfig, OceanState};
use crate::query::{Interpolation, QueryConfig};
use crate::spectrum::dispersion::Dispersion;
use crate::spectrum::{DepthFactor, Spectrum, Spreading};
use crate::wake::{Hull, WakeConfig};

/// One hash per buffer of a cascade: h0, height, displacement, slope, normal, Jacobian, and
/// the scalars computed once (expected variance, sub-grid slope variance, mean level).
fn cascade_hashes(cascade: &Cascade, out: &mut Vec<(String, u64)>, prefix: &str) {
    let mut add = |name: &str, f: &dyn Fn(&mut BitHash)| {
        let mut hash = BitHash::new();
        f(&mut hash);
        out.push((format!("{prefix}{name}"), hash.finish()));
    };
    add("h0", &|h| {
        h.f32s(cascade.h0().iter().flat_map(|c| [c.re, c.im]))
    });
    add("height", &|h| h.f32s(cascade.height().iter().copied()));
    add("displacement", &|h| {
        h.f32s(cascade.displacement().iter().flatten().copied())
    });
    add("slope", &|h| {
        h.f32s(cascade.slope().iter().flatten().copied())
    });
    add("normal", &|h| {
        h.f32s(cascade.normal().iter().flatten().copied())
    });
    add("jacobian", &|h| h.f32s(cascade.jacobian().iter().copied()));
    add("scalars", &|h| {
        let slope = cascade.subgrid_slope_variance();
        h.f64s([cascade.expected_variance()]);
        h.f32s([slope.along, slope.across, cascade.mean_level_offset()]);
    });
}

/// Every cascade's buffers, the foam, and queries at a few world points.
fn ocean_hashes(ocean: &OceanState) -> Vec<(String, u64)> {
    let mut out = Vec::new();
    for (c, cascade) in ocean.cascades().iter().enumerate() {
        cascade_hashes(cascade, &mut out, &format!("cascade {c} "));
    }
    let mut hash = BitHash::new();
    hash.f32s(ocean.foam_view().total().iter().copied());
    hash.f32s(ocean.foam_view().breaking().iter().copied());
    out.push(("foam".into(), hash.finish()));
    let points = [[0.0, 0.0], [12.5, -40.25], [-333.3, 517.9], [2048.0, 77.7]];
    let mut hash = BitHash::new();
    for [x, z] in points {
        let s = ocean.water().at_rest(x, z).unwrap();
        let surface = ocean.water().surface_at(x, z).unwrap();
        let location = ocean.water().locate(x, z).unwrap();
        for s in [s, surface] {
            hash.f32s([s.height, s.foam]);
            hash.f32s(s.displacement.into_iter().chain(s.slope).chain(s.normal));
        }
        hash.f32s([ocean.water().height_at(x, z).unwrap(), location.miss]);
        hash.f64s(location.undisplaced);
        hash.bytes(&(location.iterations as u64).to_le_bytes());
    }
    out.push(("queries".into(), hash.finish()));
    if let Some(coast) = ocean.textures().coast() {
        let mut hash = BitHash::new();
        hash.f32s(coast.factors().iter().copied());
        hash.f32s(coast.breaking().iter().copied());
        hash.f32s([coast.direction()]);
        let mut texels = vec![[0.0f32; 4]; coast.map().depth.len()];
        ocean.textures().pack_coast(&mut texels).unwrap();
        hash.f32s(texels.iter().flatten().copied());
        out.push(("coast".into(), hash.finish()));
    }
    if let Some(wakes) = ocean.wakes() {
        let mut hash = BitHash::new();
        hash.f64s(wakes.origin());
        hash.f32s(wakes.height().iter().copied());
        hash.f32s(wakes.slope().iter().flatten().copied());
        hash.f32s(wakes.foam().iter().copied());
        out.push(("wake".into(), hash.finish()));
    }
    out
}

/// The configurations: the default ocean's layout at 64² with JONSWAP and Donelan–Banner
/// spreading (cubic B-spline queries), a finite-depth ocean at 48² (a mixed-radix FFT
/// length) with TMA, Kitaigorodskii's depth factor, Mitsuyasu spreading, swell, a repeat
/// period and bilinear queries, and an Elfouhaily ocean of one 34² cascade (34 = 2·17: a
/// prime-length FFT path) with capillary dispersion, Hasselmann spreading and a short-wave
/// fade; each stepped through a fixed sequence of time steps (foam depends on it); and a 32²
/// ocean in the middle of a change of weather (`OceanState::set_spectrum`), one with wakes,
/// and one with a depth map in the middle of its blend.
fn oceans() -> Vec<(&'static str, OceanState, Vec<f64>)> {
    let deterministic = |config: OceanConfig| OceanConfig {
        determinism: Determinism::CrossPlatform,
        ..config
    };
    let jonswap = Spectrum::jonswap(10.0, 100_000.0)
        .unwrap()
        .with_wind_direction(0.3)
        .unwrap()
        .with_spreading(Spreading::DonelanBanner)
        .unwrap();
    let a = OceanState::new(
        jonswap,
        deterministic(OceanConfig {
            size: 64,
            ..OceanConfig::default()
        }),
    )
    .unwrap();
    let tma = Spectrum::tma(14.0, 250_000.0, 18.0)
        .unwrap()
        .with_depth_factor(DepthFactor::Kitaigorodskii)
        .unwrap()
        .with_spreading(Spreading::Mitsuyasu)
        .unwrap()
        .with_swell(0.4)
        .unwrap()
        .with_wind_direction(-2.0)
        .unwrap();
    let b = OceanState::new(
        tma,
        deterministic(OceanConfig {
            size: 48,
            lengths: vec![400.0, 90.0],
            choppiness: 1.4,
            seed: 123_456_789,
            repeat_period: Some(40.0),
            query: QueryConfig {
                interpolation: Interpolation::Bilinear,
                ..QueryConfig::default()
            },
            ..OceanConfig::default()
        }),
    )
    .unwrap();
    let elfouhaily = Spectrum::elfouhaily(7.0, 1.6)
        .unwrap()
        .with_dispersion(Dispersion::capillary(60.0).unwrap())
        .unwrap()
        .with_spreading(Spreading::Hasselmann)
        .unwrap()
        .with_short_wave_length(0.02)
        .unwrap();
    let c = OceanState::new(
        elfouhaily,
        deterministic(OceanConfig {
            size: 34,
            lengths: vec![25.0],
            choppiness: 0.8,
            seed: u64::MAX,
            ..OceanConfig::default()
        }),
    )
    .unwrap();
    // A change of weather half way: a calm sea turning into a storm from another direction,
    // stepped through the preparation of the new sea and into the blend.
    let mut d = OceanState::new(
        Spectrum::jonswap(6.0, 50_000.0).unwrap(),
        deterministic(OceanConfig {
            size: 32,
            ..OceanConfig::default()
        }),
    )
    .unwrap();
    let storm = Spectrum::pierson_moskowitz(18.0)
        .unwrap()
        .with_wind_direction(2.0)
        .unwrap();
    d.set_spectrum(storm.clone(), 1.0).unwrap();
    // Second-order waves, through a change of weather too.
    let mut e = OceanState::new(
        Spectrum::jonswap(12.0, 150_000.0).unwrap(),
        deterministic(OceanConfig {
            size: 48,
            lengths: vec![600.0, 140.0],
            second_order: true,
            ..OceanConfig::default()
        }),
    )
    .unwrap();
    e.set_spectrum(storm, 0.5).unwrap();
    // Wakes: two hulls crossing a 64² window in finite depth, the window moved once.
    let mut f = OceanState::new(
        Spectrum::tma(8.0, 80_000.0, 12.0).unwrap(),
        deterministic(OceanConfig {
            size: 32,
            wakes: Some(WakeConfig {
                size: 64,
                spacing: 1.0,
                substep: 0.05,
                ..WakeConfig::default()
            }),
            ..OceanConfig::default()
        }),
    )
    .unwrap();
    let hull = Hull {
        position: [-12.0, 4.0],
        velocity: [5.0, -0.5],
        heading: -0.1,
        ..Hull::default()
    };
    let tug = Hull {
        position: [6.0, -9.0],
        velocity: [0.0, 2.0],
        heading: 1.5,
        length: 7.0,
        beam: 3.0,
        draft: 0.8,
    };
    f.set_hulls(&[hull, tug]).unwrap();
    f.set_wake_centre(3.3, -1.2).unwrap();
    // A coast: a 1:20 beach under two of the query points (depth 20 m at x = −100 m to land
    // from x = 100 m), the map set at t = 0 and queried 1 s into its 2 s blend.
    let mut g = OceanState::new(
        Spectrum::jonswap(12.0, 120_000.0).unwrap(),
        deterministic(OceanConfig {
            size: 32,
            ..OceanConfig::default()
        }),
    )
    .unwrap();
    g.set_depth_map(Some(crate::coast::DepthMap {
        origin: [-100.0, -100.0],
        spacing: 5.0,
        size: [60, 40],
        depth: (0..60 * 40)
            .map(|c| 20.0 - (c % 60) as f32 * 5.0 / 20.0)
            .collect(),
    }))
    .unwrap();
    let steps = vec![1.0 / 60.0, 1.0 / 30.0, 0.5, 0.0, 1.0 / 60.0, 3.25];
    vec![
        ("jonswap 64²", a, steps.clone()),
        ("tma 48²", b, steps.clone()),
        ("elfouhaily 34²", c, steps),
        ("live 32²", d, vec![1.0 / 30.0; 30]),
        ("second order 48²", e, vec![1.0 / 30.0; 20]),
        ("wakes 32²", f, vec![1.0 / 30.0; 45]),
        ("coast 32²", g, vec![1.0 / 30.0; 30]),
    ]
}

/// (configuration, buffer, hash) after the steps.
const GOLDEN: &[(&str, &str, u64)] = &[
    ("jonswap 64²", "cascade 0 h0", 0xeac1cf8dd98d34b2),
    ("jonswap 64²", "cascade 0 height", 0x1bed5a0c27fab223),
    ("jonswap 64²", "cascade 0 displacement", 0xba50bb2ca4280d72),
    ("jonswap 64²", "cascade 0 slope", 0xd3d64be5c7db0656),
    ("jonswap 64²", "cascade 0 normal", 0x23a9ae3b932608b5),
    ("jonswap 64²", "cascade 0 jacobian", 0xad38eaf5199705b2),
    ("jonswap 64²", "cascade 0 scalars", 0x3f644fcd8e317d11),
    ("jonswap 64²", "cascade 1 h0", 0xa869eada8015ac8a),
    ("jonswap 64²", "cascade 1 height", 0xfffa94c8643c1eaa),
    ("jonswap 64²", "cascade 1 displacement", 0x224a418121521fc0),
    ("jonswap 64²", "cascade 1 slope", 0x556d3bc2963de2f7),
    ("jonswap 64²", "cascade 1 normal", 0x9d3836861eae9328),
    ("jonswap 64²", "cascade 1 jacobian", 0x65c3f08911c845da),
    ("jonswap 64²", "cascade 1 scalars", 0xe550ac85c131002f),
    ("jonswap 64²", "cascade 2 h0", 0x411b9f8165193582),
    ("jonswap 64²", "cascade 2 height", 0x5ad22e5775cf2d4c),
    ("jonswap 64²", "cascade 2 displacement", 0xd570b42047246468),
    ("jonswap 64²", "cascade 2 slope", 0x278281d7a8c77331),
    ("jonswap 64²", "cascade 2 normal", 0x2b4a3ec907133032),
    ("jonswap 64²", "cascade 2 jacobian", 0x8bb2cb9ad96ffc51),
    ("jonswap 64²", "cascade 2 scalars", 0xc3a8cef85c200326),
    ("jonswap 64²", "foam", 0xd04a66da45251f7d),
    ("jonswap 64²", "queries", 0xd163291f43f681a7),
    ("tma 48²", "cascade 0 h0", 0x15fd0b096725fe9a),
    ("tma 48²", "cascade 0 height", 0x2cf205b883b3496e),
    ("tma 48²", "cascade 0 displacement", 0x1cafb29a8c96925f),
    ("tma 48²", "cascade 0 slope", 0x9c12fd09ad398798),
    ("tma 48²", "cascade 0 normal", 0x9d51dc42e4006583),
    ("tma 48²", "cascade 0 jacobian", 0xfee4b0bd264ebae7),
    ("tma 48²", "cascade 0 scalars", 0xb00f63de125a50c6),
    ("tma 48²", "cascade 1 h0", 0x1e3c40bd7d069dad),
    ("tma 48²", "cascade 1 height", 0x9da046e4fc02c533),
    ("tma 48²", "cascade 1 displacement", 0x0a9e0e1ebdb724f2),
    ("tma 48²", "cascade 1 slope", 0xc46e7a44457557d9),
    ("tma 48²", "cascade 1 normal", 0x012fc34dde53c74e),
    ("tma 48²", "cascade 1 jacobian", 0x24fd723c5149eb7e),
    ("tma 48²", "cascade 1 scalars", 0x2164c8706aa127d2),
    ("tma 48²", "foam", 0xf39ddae40eaa4d5f),
    ("tma 48²", "queries", 0x54c2a9447bbaf4b9),
    ("elfouhaily 34²", "cascade 0 h0", 0x0a3c2a1c37fab219),
    ("elfouhaily 34²", "cascade 0 height", 0xa8a1ec35133c7e0a),
    (
        "elfouhaily 34²",
        "cascade 0 displacement",
        0x77859cbfa9567de2,
    ),
    ("elfouhaily 34²", "cascade 0 slope", 0x5386022373041d56),
    ("elfouhaily 34²", "cascade 0 normal", 0xa5879ef329e4911a),
    ("elfouhaily 34²", "cascade 0 jacobian", 0x11f4435a7448d439),
    ("elfouhaily 34²", "cascade 0 scalars", 0x66ac39c5a31a4153),
    ("elfouhaily 34²", "foam", 0xc2376bd0a8f5ac34),
    ("elfouhaily 34²", "queries", 0x095fcc696b7319b0),
    ("live 32²", "cascade 0 h0", 0x7b9d2a8fa94005a1),
    ("live 32²", "cascade 0 height", 0xba5b2b54b8cc2930),
    ("live 32²", "cascade 0 displacement", 0x40974e20d0065329),
    ("live 32²", "cascade 0 slope", 0x80927de3126c8e5d),
    ("live 32²", "cascade 0 normal", 0xefd228c733e5ace2),
    ("live 32²", "cascade 0 jacobian", 0x0c23a7cf2fa3824c),
    ("live 32²", "cascade 0 scalars", 0x9cd7f51ac815ceee),
    ("live 32²", "cascade 1 h0", 0x5e0b43e0ded95717),
    ("live 32²", "cascade 1 height", 0x223e1e4dd25cde22),
    ("live 32²", "cascade 1 displacement", 0x2dae2caab6beb2a2),
    ("live 32²", "cascade 1 slope", 0x08719e8c3e6f1f70),
    ("live 32²", "cascade 1 normal", 0x9202c17520e0b222),
    ("live 32²", "cascade 1 jacobian", 0x6745bcdaca5ec76f),
    ("live 32²", "cascade 1 scalars", 0x10ee0231e55b9b87),
    ("live 32²", "cascade 2 h0", 0xc14fa67bc31ff884),
    ("live 32²", "cascade 2 height", 0xddd2775de53aa47b),
    ("live 32²", "cascade 2 displacement", 0xc291d928f46382b3),
    ("live 32²", "cascade 2 slope", 0x7abfe23ef1faa18e),
    ("live 32²", "cascade 2 normal", 0x5b387ca780dbb74e),
    ("live 32²", "cascade 2 jacobian", 0x2618271222258828),
    ("live 32²", "cascade 2 scalars", 0xcc5409139c757465),
    ("live 32²", "foam", 0x1c5212828491cb71),
    ("live 32²", "queries", 0xb08c577ae303c38d),
    ("second order 48²", "cascade 0 h0", 0xa749435a6ad1c1a1),
    ("second order 48²", "cascade 0 height", 0x019d73931bf708a2),
    (
        "second order 48²",
        "cascade 0 displacement",
        0x8d72a628a8938a3c,
    ),
    ("second order 48²", "cascade 0 slope", 0x55d09cd0b468eaee),
    ("second order 48²", "cascade 0 normal", 0x5a7c17bf667bf1d5),
    ("second order 48²", "cascade 0 jacobian", 0xf8ff6651de4fcd68),
    ("second order 48²", "cascade 0 scalars", 0x6a30d1bf0c32ebb9),
    ("second order 48²", "cascade 1 h0", 0x5a2c96a58a4009b8),
    ("second order 48²", "cascade 1 height", 0x94a333764868daf6),
    (
        "second order 48²",
        "cascade 1 displacement",
        0xcfbc69f359fd9c79,
    ),
    ("second order 48²", "cascade 1 slope", 0xa866486abce83cfd),
    ("second order 48²", "cascade 1 normal", 0x59c79b7d240b0e64),
    ("second order 48²", "cascade 1 jacobian", 0xf051b76f25e5095b),
    ("second order 48²", "cascade 1 scalars", 0x5d402f7d4e26b4b1),
    ("second order 48²", "foam", 0xbc77167197e33bdc),
    ("second order 48²", "queries", 0x6bcdd19b83418b17),
    ("wakes 32²", "cascade 0 h0", 0x422e0575e1d5f01c),
    ("wakes 32²", "cascade 0 height", 0x942486e09c817997),
    ("wakes 32²", "cascade 0 displacement", 0xdf208c2a71892222),
    ("wakes 32²", "cascade 0 slope", 0x66e7f04e3c318ea2),
    ("wakes 32²", "cascade 0 normal", 0x736d53378ab4178a),
    ("wakes 32²", "cascade 0 jacobian", 0x552b519dd836c325),
    ("wakes 32²", "cascade 0 scalars", 0xabb5eaa32d7a1290),
    ("wakes 32²", "cascade 1 h0", 0x4089a30fabcaad6b),
    ("wakes 32²", "cascade 1 height", 0xa765fbdb23b02565),
    ("wakes 32²", "cascade 1 displacement", 0xa1ab29f5a7512d68),
    ("wakes 32²", "cascade 1 slope", 0xe71631728732f23a),
    ("wakes 32²", "cascade 1 normal", 0x5275fc80c8bdc799),
    ("wakes 32²", "cascade 1 jacobian", 0xaa1fb3b4acda797b),
    ("wakes 32²", "cascade 1 scalars", 0x3a7d8c41d6c7264e),
    ("wakes 32²", "cascade 2 h0", 0xd7ff0ca16f33f7c1),
    ("wakes 32²", "cascade 2 height", 0x0eda4fb4697de41b),
    ("wakes 32²", "cascade 2 displacement", 0xf26584760460dcb1),
    ("wakes 32²", "cascade 2 slope", 0x7f13d14926c970ff),
    ("wakes 32²", "cascade 2 normal", 0xd8f0ebbcdd66f05d),
    ("wakes 32²", "cascade 2 jacobian", 0xcd801cfd0ca610d0),
    ("wakes 32²", "cascade 2 scalars", 0xeacb18e709c43852),
    ("wakes 32²", "foam", 0x8b18672ae7cc3325),
    ("wakes 32²", "queries", 0xe35c09d279f7de53),
    ("wakes 32²", "wake", 0xe14db6f41a23f4a6),
    ("coast 32²", "cascade 0 h0", 0xbc3f785f365aca01),
    ("coast 32²", "cascade 0 height", 0x022730f9104c4a8c),
    ("coast 32²", "cascade 0 displacement", 0xc4a34e9d0881f260),
    ("coast 32²", "cascade 0 slope", 0x61e244cefc2e41e4),
    ("coast 32²", "cascade 0 normal", 0x9e547c49ab807f71),
    ("coast 32²", "cascade 0 jacobian", 0xcc2f73e4ddc86e11),
    ("coast 32²", "cascade 0 scalars", 0xee5496a7c7b23f88),
    ("coast 32²", "cascade 1 h0", 0x032b2bb6df10c260),
    ("coast 32²", "cascade 1 height", 0x02aae1e9f561c9c5),
    ("coast 32²", "cascade 1 displacement", 0x72e27c8969bb747f),
    ("coast 32²", "cascade 1 slope", 0x1465babb2c870f04),
    ("coast 32²", "cascade 1 normal", 0x31cb8e9419f5bac0),
    ("coast 32²", "cascade 1 jacobian", 0x23e9fb625afb4865),
    ("coast 32²", "cascade 1 scalars", 0x82eb6c0bd2d84fc7),
    ("coast 32²", "cascade 2 h0", 0xbcbe022d6ebfb126),
    ("coast 32²", "cascade 2 height", 0x23349be0c4e0332e),
    ("coast 32²", "cascade 2 displacement", 0xefaaf911c78901a3),
    ("coast 32²", "cascade 2 slope", 0x588579a8e7a9e5de),
    ("coast 32²", "cascade 2 normal", 0x31fff53e0c42e593),
    ("coast 32²", "cascade 2 jacobian", 0x72f034cdbf2bcaca),
    ("coast 32²", "cascade 2 scalars", 0xa9b6a87e3a0cca83),
    ("coast 32²", "foam", 0x7729b42e98658eb2),
    ("coast 32²", "queries", 0x5f16c9e5f92d3b1d),
    ("coast 32²", "coast", 0xaa34d1d9d141adb9),
];

#[test]
fn cross_platform_mode_gives_the_golden_bits_on_every_level_and_thread_count() {
    let levels = Simd::available();
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx512f") {
        // The project's machines: the test must run all three levels, or it would pass
        // with fewer paths than it claims.
        assert_eq!(levels.len(), 3, "levels {levels:?}");
    }
    let pools = crate::math::simd::test_pools();
    let mut reference: Option<Vec<(String, String, u64)>> = None;
    for &level in &levels {
        for (threads, pool) in &pools {
            let got: Vec<(String, String, u64)> = pool.install(|| {
                let mut all = Vec::new();
                for (name, mut ocean, steps) in oceans() {
                    for cascade in &mut ocean.cascades {
                        cascade.set_simd(level);
                    }
                    ocean.foam.set_simd(level);
                    ocean.frames.set_simd(level);
                    for dt in steps {
                        ocean.step(dt).unwrap();
                    }
                    all.extend(
                        ocean_hashes(&ocean)
                            .into_iter()
                            .map(|(buffer, hash)| (name.to_string(), buffer, hash)),
                    );
                }
                all
            });
            match &reference {
                None => reference = Some(got),
                Some(expected) => assert!(
                    &got == expected,
                    "{level:?} with {threads} threads differs from the first level and pool"
                ),
            }
        }
    }
    let got = reference.expect("at least one level");
    let golden: Vec<(String, String, u64)> = GOLDEN
        .iter()
        .map(|&(c, b, h)| (c.to_string(), b.to_string(), h))
        .collect();
    if got != golden {
        let mut listing = String::new();
        for (c, b, h) in &got {
            listing.push_str(&format!("    (\"{c}\", \"{b}\", {h:#018x}),\n"));
        }
        panic!(
            "the deterministic mode's bits changed (or GOLDEN is out of date). Computed on \
             {} levels × 3 pools, all equal:\n{listing}",
            levels.len()
        );
    }
}

/// How far, in units of the last place of `y`, the f64 `y` lies from the nearest point where
/// rounding to f32 changes (a midpoint between two f32 values).
fn margin_to_f32_rounding(y: f64) -> f64 {
    let f = y as f32;
    let (below, above) = (f.next_down(), f.next_up());
    // Both midpoints next to f are exact in f64 (an f32 has 29 fewer significand bits).
    let mid_low = 0.5 * (f64::from(below) + f64::from(f));
    let mid_high = 0.5 * (f64::from(f) + f64::from(above));
    let distance = (y - mid_low).abs().min((mid_high - y).abs());
    let ulp = f64::from_bits(y.abs().to_bits() + 1) - y.abs();
    distance / ulp
}

/// rustfft computes its f32 twiddle factors as cos and sin of (−2π/len)·index in f64 with
/// std's functions (the platform's C library), then rounds them to f32. Another platform's
/// cos may differ in the last f64 bit; that moves the f32 twiddle only if the value lies
/// within an ulp or two of an f32 rounding point. No twiddle of any length up to 4096, nor
/// of the Bluestein lengths up to 8192 (index² mod 2·len of len ≤ 4096, the prime factors an
/// even N ≤ 4096 can have), lies within 4 f64 ulps of one (with libm's cos and sin, which,
/// like the C libraries, are within an ulp of the exact values), so any two platforms whose
/// cos and sin are within 2 ulps round every twiddle to the same f32. This is what makes
/// rustfft's scalar FFT the same on every platform in spite of its std cos and sin.
#[test]
fn rustfft_twiddles_round_to_the_same_f32_on_every_platform() {
    let mut worst: (f64, usize, usize) = (f64::INFINITY, 0, 0);
    let mut check = |index: usize, len: usize| {
        let angle = -2.0 * std::f64::consts::PI / len as f64 * index as f64;
        for value in [libm::cos(angle), libm::sin(angle)] {
            // Values that are exact in f32 (0, ±1, ±½) or tiny round the same for any ulp.
            if value.abs() < 1e-30 || f64::from(value as f32) == value {
                continue;
            }
            let margin = margin_to_f32_rounding(value);
            if margin < worst.0 {
                worst = (margin, index, len);
            }
        }
    };
    for len in 1..=4096 {
        for index in 0..len {
            check(index, len);
        }
    }
    // Bluestein's chirp: twiddle(index² mod 2·len, 2·len) for its inner prime length.
    for len in 1..=4096usize {
        let twice = 2 * len;
        for i in 0..len {
            check((i * i) % twice, twice);
        }
    }
    assert!(
        worst.0 > 4.0,
        "twiddle {} of length {} lies {} ulps from an f32 rounding point",
        worst.1,
        worst.2,
        worst.0
    );
}
