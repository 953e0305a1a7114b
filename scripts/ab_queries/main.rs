//! The harness of `scripts/ab_queries.sh`: `old` and `new` are two versions of ocean-fft.
//! Arguments: threads, rounds.

use std::time::Instant;

// The criterion benches' points (benches/common/points.rs, copied beside this file).
mod points;
use points::scattered;

/// The default ocean of one version, stepped once.
macro_rules! ocean {
    ($m:ident) => {{
        let spectrum = $m::Spectrum::jonswap(10.0, 100_000.0).expect("valid spectrum");
        let mut state =
            $m::OceanState::new(spectrum, $m::OceanConfig::default()).expect("valid ocean");
        state.step(3.0).expect("valid step");
        state
    }};
}

/// ns a point of the fastest and the first-quartile batch.
fn summary(mut times: Vec<f64>, count: usize) -> (f64, f64) {
    times.sort_by(f64::total_cmp);
    let ns = |t: f64| t * 1e9 / count as f64;
    (ns(times[0]), ns(times[times.len() / 4]))
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let threads: usize = args.get(1).map_or(1, |s| s.parse().expect("threads"));
    let rounds: usize = args.get(2).map_or(15, |s| s.parse().expect("rounds"));
    let (a, b) = (ocean!(old), ocean!(new));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool");
    println!("{threads} thread(s), {rounds} rounds; ns a point: fastest, first quartile");
    pool.install(|| {
        for surfaces in [false, true] {
            let name = if surfaces { "surfaces_at" } else { "heights_at" };
            for count in [100usize, 1000, 10_000, 100_000] {
                let points = scattered(count);
                let (mut ha, mut hb) = (vec![0f32; count], vec![0f32; count]);
                let mut sa = vec![old::SurfaceSample::default(); count];
                let mut sb = vec![new::SurfaceSample::default(); count];
                // The first query after a step computes what the later ones read.
                a.heights_at(&points, &mut ha).expect("old batch");
                b.heights_at(&points, &mut hb).expect("new batch");
                let inner = (100_000 / count).clamp(1, 100);
                let (mut ta, mut tb) = (vec![], vec![]);
                for _ in 0..rounds {
                    let t = Instant::now();
                    for _ in 0..inner {
                        if surfaces {
                            a.surfaces_at(&points, &mut sa).expect("old batch");
                        } else {
                            a.heights_at(&points, &mut ha).expect("old batch");
                        }
                    }
                    ta.push(t.elapsed().as_secs_f64() / inner as f64);
                    let t = Instant::now();
                    for _ in 0..inner {
                        if surfaces {
                            b.surfaces_at(&points, &mut sb).expect("new batch");
                        } else {
                            b.heights_at(&points, &mut hb).expect("new batch");
                        }
                    }
                    tb.push(t.elapsed().as_secs_f64() / inner as f64);
                }
                let (old_min, old_q1) = summary(ta, count);
                let (new_min, new_q1) = summary(tb, count);
                println!(
                    "{name:<11} {count:>6} points: old {old_min:7.1} {old_q1:7.1}  new {new_min:7.1} {new_q1:7.1}  old/new {:.2} {:.2}",
                    old_min / new_min,
                    old_q1 / new_q1
                );
            }
        }
    });
}
