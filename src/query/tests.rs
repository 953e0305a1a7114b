//! The queries' bits: every kind of query, single, grouped, in lanes and on a handle, at
//! every SIMD level and thread count.

use super::results::SurfaceSample;
use crate::coast::DepthMap;
use crate::math::simd::{test_pools, Simd};
use crate::ocean::{OceanConfig, OceanState};
use crate::spectrum::Spectrum;

/// Batch, grid and single queries, the ocean's and a handle's, give the same bits at every
/// SIMD level this CPU runs and at 1, 2 and 3 threads; at the baseline level of a CPU
/// without FMA (products added unfused, forced here) batches still give their single
/// queries' bits, and results close to the fused ones. Without and with a depth map.
#[test]
fn queries_give_the_same_bits_at_every_level_and_thread_count() {
    let spectrum = Spectrum::jonswap(14.0, 150_000.0).unwrap();
    let config = OceanConfig {
        size: 64,
        ..OceanConfig::default()
    };
    // 300 points, then a few beyond 2²⁹ periods of every cascade, where the wrap takes
    // its other path (in some lanes of a group only).
    let points: Vec<[f64; 2]> = (0..300)
        .map(|i| {
            [
                f64::from(i) * 7.3 - 900.0,
                f64::from(i * i % 89) * 11.1 - 400.0,
            ]
        })
        .chain([[7.3e11, -2.1e12], [12.5, -9.9e14], [-5.0e17, 3.0e16]])
        .collect();
    // With a depth map too (issue 41): a 1:33 beach under a third of the points, from 30 m
    // to land, replaced at t = 2 s by the same beach 1 m deeper (a tide), so that at t = 3 s
    // the queries blend the two maps' factors.
    let beach = |tide: f32| DepthMap {
        origin: [-600.0, -400.0],
        spacing: 8.0,
        size: [128, 128],
        depth: (0..128 * 128)
            .map(|c| 30.0 + tide - (c % 128) as f32 * 8.0 * 0.03)
            .collect(),
    };
    let mut open_sea: Option<Vec<u32>> = None;
    for coast in [false, true] {
        let mut reference: Option<(Vec<u32>, Vec<SurfaceSample>)> = None;
        let unfused = Simd::Baseline { fused: false };
        for level in Simd::available().into_iter().chain([unfused]) {
            for (threads, pool) in test_pools() {
                let mut ocean = OceanState::new(spectrum.clone(), config.clone()).unwrap();
                ocean.frames.set_simd(level);
                let (heights, surfaces, singles, handle) = pool.install(|| {
                    if coast {
                        ocean.set_depth_map(Some(beach(0.0))).unwrap();
                        ocean.step(2.0).unwrap();
                        ocean.set_depth_map(Some(beach(1.0))).unwrap();
                        ocean.step(1.0).unwrap();
                    } else {
                        ocean.step(3.0).unwrap();
                    }
                    let mut heights = vec![0.0f32; points.len()];
                    let mut surfaces = vec![SurfaceSample::default(); points.len()];
                    ocean.water().heights_at(&points, &mut heights).unwrap();
                    ocean.water().surfaces_at(&points, &mut surfaces).unwrap();
                    let singles: Vec<f32> = points
                        .iter()
                        .map(|&[x, z]| ocean.water().height_at(x, z).unwrap())
                        .collect();
                    let mut handle = vec![0.0f32; points.len()];
                    ocean
                        .surface()
                        .water()
                        .heights_at(&points, &mut handle)
                        .unwrap();
                    // The other batches against their single queries too (groups of points
                    // interleaved, the last one partial).
                    for (&[x, z], batch) in points.iter().zip(&surfaces) {
                        assert_eq!(ocean.water().surface_at(x, z).unwrap(), *batch);
                    }
                    let mut samples = vec![SurfaceSample::default(); points.len()];
                    ocean.water().at_rest_many(&points, &mut samples).unwrap();
                    for (&[x, z], batch) in points.iter().zip(&samples) {
                        assert_eq!(ocean.water().at_rest(x, z).unwrap(), *batch);
                    }
                    // Grids in lanes too, rows ending in a partial group of eight, one far
                    // out where the wrap takes its other path.
                    let grids = [
                        ([-300.0, 50.0], 1.7, [21, 4]),
                        ([7.3e11, -2.1e12], 0.37, [21, 4]),
                        // Rows of eleven: a last group of three, queried one point at a time.
                        ([40.0, -75.0], 2.9, [11, 3]),
                    ];
                    for (origin, spacing, [columns, rows]) in grids {
                        let mut grid = vec![SurfaceSample::default(); columns * rows];
                        ocean
                            .water()
                            .at_rest_grid(origin, spacing, [columns, rows], &mut grid)
                            .unwrap();
                        for (i, sample) in grid.iter().enumerate() {
                            let x = origin[0] + (i % columns) as f64 * spacing;
                            let z = origin[1] + (i / columns) as f64 * spacing;
                            assert_eq!(
                                ocean.water().at_rest(x, z).unwrap(),
                                *sample,
                                "grid point {i}"
                            );
                        }
                    }
                    // Batches too small for lanes (queried one point at a time) and the
                    // smallest in lanes.
                    for n in 1..=4 {
                        let points = &points[100..100 + n];
                        let mut small = vec![0.0f32; n];
                        let mut small_surfaces = vec![SurfaceSample::default(); n];
                        let mut small_samples = vec![SurfaceSample::default(); n];
                        ocean.water().heights_at(points, &mut small).unwrap();
                        ocean
                            .water()
                            .surfaces_at(points, &mut small_surfaces)
                            .unwrap();
                        ocean
                            .water()
                            .at_rest_many(points, &mut small_samples)
                            .unwrap();
                        for (i, &[x, z]) in points.iter().enumerate() {
                            let height = ocean.water().height_at(x, z).unwrap();
                            assert_eq!(small[i].to_bits(), height.to_bits(), "{n} points");
                            assert_eq!(small_surfaces[i], ocean.water().surface_at(x, z).unwrap());
                            assert_eq!(small_samples[i], ocean.water().at_rest(x, z).unwrap());
                        }
                    }
                    (heights, surfaces, singles, handle)
                });
                let bits = |v: &[f32]| v.iter().map(|h| h.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(&heights),
                    bits(&singles),
                    "{level:?}, {threads} threads"
                );
                assert_eq!(
                    bits(&heights),
                    bits(&handle),
                    "{level:?}, {threads} threads"
                );
                match &reference {
                    None => {
                        match &open_sea {
                            None => open_sea = Some(bits(&heights)),
                            Some(open) => {
                                // The map acts (its third of the points, x −600…416 m,
                                // changed), so the bits above are the coast's.
                                let changed =
                                    open.iter().zip(bits(&heights)).filter(|(a, b)| **a != *b);
                                assert!(changed.count() > 60, "the map changes the heights");
                            }
                        }
                        reference = Some((bits(&heights), surfaces));
                    }
                    Some((h, s)) if !matches!(level, Simd::Baseline { fused: false }) => {
                        assert_eq!(&bits(&heights), h, "{level:?}, {threads} threads");
                        assert_eq!(&surfaces, s, "{level:?}, {threads} threads");
                    }
                    Some((h, _)) => {
                        // Sums rounded twice instead of once move a height by ulps of the
                        // ~1 m sums, and a search may end on another iterate within the
                        // tolerance (1e-4 m) of the same point: the height moves by the
                        // slope (below 1 here) times at most twice that.
                        for (&fused, &unfused) in h.iter().zip(&heights) {
                            let fused = f32::from_bits(fused);
                            assert!((fused - unfused).abs() < 3e-4, "{fused} against {unfused}");
                        }
                    }
                }
            }
        }
    }
}
