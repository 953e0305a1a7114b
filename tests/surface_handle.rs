//! `OceanState::surface`: a handle that keeps answering about one frame while the ocean
//! steps on, on another thread, always with the bits of exactly one frame.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

use ocean_fft::{OceanConfig, OceanState, Spectrum, Surface, SurfaceSample};

const DT: f64 = 1.0 / 30.0;
const FRAMES: usize = 40;

fn ocean() -> OceanState {
    let spectrum = Spectrum::jonswap(12.0, 200_000.0).unwrap();
    let config = OceanConfig {
        size: 64,
        ..OceanConfig::default()
    };
    OceanState::new(spectrum, config).unwrap()
}

fn points() -> Vec<[f64; 2]> {
    (0..48)
        .map(|i| {
            [
                f64::from(i) * 13.7 - 300.0,
                f64::from(i * i % 31) * 9.1 - 120.0,
            ]
        })
        .collect()
}

fn bits(values: &[f32]) -> Vec<u32> {
    values.iter().map(|v| v.to_bits()).collect()
}

/// The heights at `points` of every frame, from an ocean stepped alone and queried between
/// steps on this thread: (time, heights) for frames 0..=FRAMES.
fn reference(points: &[[f64; 2]]) -> Vec<(f64, Vec<f32>)> {
    let mut ocean = ocean();
    let mut frames = Vec::new();
    for frame in 0..=FRAMES {
        if frame > 0 {
            ocean.step(DT).unwrap();
        }
        let heights = points
            .iter()
            .map(|&[x, z]| ocean.water().height_at(x, z).unwrap())
            .collect();
        frames.push((ocean.time(), heights));
    }
    frames
}

#[test]
fn a_physics_thread_sees_whole_frames_while_the_ocean_steps() {
    let points = points();
    let expected = reference(&points);
    // The frames differ at every point, so a mix of two would show.
    for pair in expected.windows(2) {
        assert!(pair[0].1.iter().zip(&pair[1].1).all(|(a, b)| a != b));
    }
    let mut ocean = ocean();
    let latest = Mutex::new(ocean.surface());
    let done = AtomicBool::new(false);
    let seen = std::thread::scope(|scope| {
        let physics = scope.spawn(|| {
            let mut seen = vec![0usize; FRAMES + 1];
            let mut heights = vec![0.0f32; points.len()];
            loop {
                let finished = done.load(Ordering::Acquire);
                let surface: Surface = latest.lock().unwrap().clone();
                let frame = expected
                    .iter()
                    .position(|(t, _)| *t == surface.time())
                    .expect("the handle's time is one frame's");
                // A batch (spread over the pool) and single queries one by one, while the
                // main thread may be stepping: all the bits of that one frame.
                surface.water().heights_at(&points, &mut heights).unwrap();
                assert_eq!(bits(&heights), bits(&expected[frame].1), "frame {frame}");
                for (&[x, z], &y) in points.iter().zip(&expected[frame].1) {
                    assert_eq!(
                        surface.water().height_at(x, z).unwrap().to_bits(),
                        y.to_bits()
                    );
                }
                seen[frame] += 1;
                if finished {
                    return seen;
                }
            }
        });
        for (frame, (_, heights)) in expected.iter().enumerate().skip(1) {
            ocean.step(DT).unwrap();
            // The ocean's own answers between steps are that frame's too.
            let own: Vec<f32> = points
                .iter()
                .map(|&[x, z]| ocean.water().height_at(x, z).unwrap())
                .collect();
            assert_eq!(bits(&own), bits(heights), "frame {frame}");
            *latest.lock().unwrap() = ocean.surface();
            std::thread::sleep(std::time::Duration::from_millis(2));
        }
        done.store(true, Ordering::Release);
        physics.join().unwrap()
    });
    let frames_seen = seen.iter().filter(|&&n| n > 0).count();
    println!("queries per frame: {seen:?}");
    assert!(
        frames_seen >= 3,
        "the physics thread saw {frames_seen} frames"
    );
    assert!(seen[FRAMES] > 0, "the last frame was never seen");
}

#[test]
fn handles_kept_across_steps_keep_their_frame() {
    let points = points();
    let expected = reference(&points);
    let mut ocean = ocean();
    // Handles of frames 0, 1, 2, 5 kept while the ocean steps to 8: the third and later
    // frames held at once are new allocations, the answers never change.
    let mut kept: Vec<(usize, Surface)> = Vec::new();
    for frame in 0..=8 {
        if frame > 0 {
            ocean.step(DT).unwrap();
        }
        let surface = ocean.surface();
        if [0, 1, 2, 5].contains(&frame) {
            kept.push((frame, surface));
        }
        for (k, handle) in &kept {
            let mut heights = vec![0.0f32; points.len()];
            handle.water().heights_at(&points, &mut heights).unwrap();
            assert_eq!(
                bits(&heights),
                bits(&expected[*k].1),
                "frame {k} at {frame}"
            );
            assert_eq!(handle.time(), expected[*k].0);
        }
    }
}

#[test]
fn a_handle_answers_every_query_as_the_ocean_does() {
    let mut ocean = ocean();
    ocean.step(2.5).unwrap();
    // Some foam to interpolate.
    ocean.pre_roll(5.0, 0.1).unwrap();
    let surface = ocean.surface();
    let points = points();
    let mut a = vec![SurfaceSample::default(); points.len()];
    let mut b = a.clone();
    ocean.water().surfaces_at(&points, &mut a).unwrap();
    surface.water().surfaces_at(&points, &mut b).unwrap();
    assert_eq!(a, b);
    ocean.water().at_rest_many(&points, &mut a).unwrap();
    surface.water().at_rest_many(&points, &mut b).unwrap();
    assert_eq!(a, b);
    for &[x, z] in &points {
        assert_eq!(ocean.water().at_rest(x, z), surface.water().at_rest(x, z));
        assert_eq!(ocean.water().locate(x, z), surface.water().locate(x, z));
        assert_eq!(
            ocean.water().surface_at(x, z),
            surface.water().surface_at(x, z)
        );
    }
    // After clear_foam the ocean's foam is gone, the handle keeps what it saw.
    let before = surface.water().at_rest(10.0, 20.0).unwrap();
    ocean.clear_foam();
    assert_eq!(surface.water().at_rest(10.0, 20.0).unwrap(), before);
    assert_eq!(
        ocean.surface().water().at_rest(10.0, 20.0),
        ocean.water().at_rest(10.0, 20.0)
    );
    assert!(surface.water().height_at(f64::NAN, 0.0).is_err());
    let mut short = vec![0.0f32; 1];
    assert!(surface.water().heights_at(&points, &mut short).is_err());
}

#[test]
fn handles_are_send_and_sync() {
    fn check<T: Send + Sync + Clone + std::fmt::Debug>() {}
    check::<Surface>();
}
