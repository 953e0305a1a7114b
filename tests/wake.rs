//! Wakes (issue 40) against closed forms: Kelvin's transverse wavelength 2πU²/g and cusp
//! angle (with the stationary-phase offset of the envelope's maximum at a finite distance),
//! still water ahead of the bow, the steady dip of a hull at rest, amplitude against draft and
//! beam, the independence of the step partition, bad input, and what queries see.
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

use std::sync::OnceLock;

use ocean_fft::{
    Determinism, Dispersion, Error, Hull, OceanConfig, OceanState, Spectrum, WakeConfig,
};

const G: f64 = 9.81;

/// An ocean whose own waves are tiny (a light breeze on a small grid) with a wake window.
fn ocean(wakes: WakeConfig) -> OceanState {
    ocean_with(Spectrum::jonswap(2.0, 1000.0).unwrap(), wakes)
}

fn ocean_with(spectrum: Spectrum, wakes: WakeConfig) -> OceanState {
    let config = OceanConfig {
        size: 16,
        wakes: Some(wakes),
        ..OceanConfig::default()
    }
    .with_fitted_lengths(&spectrum)
    .unwrap();
    OceanState::new(spectrum, config).unwrap()
}

/// A straight run: the wake's height buffer and window after `seconds`.
struct Run {
    height: Vec<f32>,
    origin: [f64; 2],
    size: usize,
    spacing: f64,
    /// The hull's centre at the end, world x (z = 0), moving towards +x.
    hull_x: f64,
    speed: f64,
    hull: Hull,
}

impl Run {
    /// The wake's height at world (x, z), bilinear.
    fn at(&self, x: f64, z: f64) -> f64 {
        if !self.inside(x, z) {
            return 0.0;
        }
        let gx = (x - self.origin[0]) / self.spacing;
        let gz = (z - self.origin[1]) / self.spacing;
        let (ix, iz) = (gx.floor() as usize, gz.floor() as usize);
        let (fx, fz) = (gx - ix as f64, gz - iz as f64);
        let h = |i: usize, j: usize| f64::from(self.height[j * self.size + i]);
        (1.0 - fz) * ((1.0 - fx) * h(ix, iz) + fx * h(ix + 1, iz))
            + fz * ((1.0 - fx) * h(ix, iz + 1) + fx * h(ix + 1, iz + 1))
    }
}

impl Run {
    /// Whether world (x, z) lies inside the window, within `margin` metres of no edge.
    fn inside(&self, x: f64, z: f64) -> bool {
        let side = (self.size - 1) as f64 * self.spacing;
        let (gx, gz) = (x - self.origin[0], z - self.origin[1]);
        (0.0..side).contains(&gx) && (0.0..side).contains(&gz)
    }

    /// The largest |η| over the window's samples for which `keep(x, z)` (world metres).
    fn max_where(&self, keep: impl Fn(f64, f64) -> bool) -> f64 {
        let mut most: f64 = 0.0;
        for j in 0..self.size {
            for i in 0..self.size {
                let x = self.origin[0] + i as f64 * self.spacing;
                let z = self.origin[1] + j as f64 * self.spacing;
                if keep(x, z) {
                    most = most.max(f64::from(self.height[j * self.size + i]).abs());
                }
            }
        }
        most
    }

    /// The largest |η| more than one hull length behind the stern.
    fn wake_amplitude(&self) -> f64 {
        let stern = self.hull_x - 0.5 * f64::from(self.hull.length);
        self.max_where(|x, _| x < stern - f64::from(self.hull.length))
    }
}

/// A hull at `speed` m/s along +x for `seconds`, the window following it with the hull
/// `ahead` of the window's centre (a fraction of its side).
fn straight_run(
    spectrum: Spectrum,
    wakes: WakeConfig,
    hull: Hull,
    speed: f64,
    seconds: f64,
    dt: f64,
    ahead: f64,
) -> Run {
    let side = wakes.size as f64 * f64::from(wakes.spacing);
    let mut ocean = ocean_with(spectrum, wakes);
    let hull = Hull {
        velocity: [speed as f32, 0.0],
        ..hull
    };
    ocean.set_hulls(&[hull]).unwrap();
    let steps = (seconds / dt).round() as usize;
    let ahead = ahead * side;
    for step in 1..=steps {
        ocean.step_to(step as f64 * dt).unwrap();
        let x = hull.position[0] + speed * ocean.time();
        ocean.set_wake_centre(x - ahead, 0.0).unwrap();
    }
    let wakes = ocean.wakes().unwrap();
    Run {
        height: wakes.height().to_vec(),
        origin: wakes.origin(),
        size: wakes.size(),
        spacing: f64::from(wakes.spacing()),
        hull_x: hull.position[0] + speed * ocean.time(),
        speed,
        hull,
    }
}

const SPEED: f64 = 6.0;

/// The deep-water run both Kelvin tests read: a 20 m × 5 m hull at 6 m/s (length Froude
/// number 0.43) in a 256 m window.
fn kelvin() -> &'static Run {
    static RUN: OnceLock<Run> = OnceLock::new();
    RUN.get_or_init(|| {
        let wakes = WakeConfig {
            size: 512,
            spacing: 0.5,
            substep: 0.05,
            ..WakeConfig::default()
        };
        straight_run(
            Spectrum::jonswap(2.0, 1000.0).unwrap(),
            wakes,
            Hull::default(),
            SPEED,
            70.0,
            0.05,
            0.3,
        )
    })
}

/// Zero crossings (upward) of the centre-line profile from `from` to `to` metres behind the
/// hull's centre, their mean spacing in metres.
fn centre_line_wavelength(run: &Run, from: f64, to: f64) -> (f64, usize) {
    let step = 0.05;
    let mut ups = Vec::new();
    let mut previous: Option<(f64, f64)> = None;
    let mut d = from;
    while d <= to {
        let x = run.hull_x - d;
        let h = run.at(x, 0.0);
        if let Some((x0, h0)) = previous {
            // Rising towards the hull: h below zero further back, above nearer.
            if h < 0.0 && h0 >= 0.0 {
                ups.push(x0 + (x - x0) * h0 / (h0 - h));
            }
        }
        previous = Some((x, h));
        d += step;
    }
    let count = ups.len();
    ((ups[0] - ups[count - 1]) / (count - 1) as f64, count)
}

#[test]
fn transverse_waves_have_the_wavelength_2_pi_u2_over_g() {
    let run = kelvin();
    let expected = std::f64::consts::TAU * SPEED * SPEED / G;
    let (measured, crossings) = centre_line_wavelength(run, 20.0, 150.0);
    let error = (measured - expected) / expected;
    println!("transverse wavelength {measured:.3} m over {crossings} crossings, 2πU²/g = {expected:.3} m, error {:.2} %", 100.0 * error);
    assert!(error.abs() < 0.05);
}

/// The angle from the track at which the wave envelope peaks on the arc of radius `r`
/// behind the hull's centre (each angle's envelope: the largest |η| over one wavelength of
/// radii around r), in degrees, one side at a time, averaged.
fn envelope_peak_angle(run: &Run, r: f64) -> f64 {
    let wavelength = std::f64::consts::TAU * run.speed * run.speed / G;
    let mut sides = Vec::new();
    for side in [-1.0, 1.0] {
        let mut best = (0.0, 0.0);
        let mut angle: f64 = 8.0;
        while angle <= 35.0 {
            let a = angle.to_radians();
            let mut envelope: f64 = 0.0;
            let mut rr = r - 0.5 * wavelength;
            while rr <= r + 0.5 * wavelength {
                let h = run.at(run.hull_x - rr * a.cos(), side * rr * a.sin());
                envelope = envelope.max(h.abs());
                rr += 0.1;
            }
            if envelope > best.1 {
                best = (angle, envelope);
            }
            angle += 0.1;
        }
        sides.push(best.0);
    }
    println!("sides {sides:?}");
    0.5 * (sides[0] + sides[1])
}

/// Where the envelope peaks near Kelvin's cusp at radius `r` (m) for speed `u` (m/s), in
/// degrees: inside the cusp line (19.47°) by the first maximum of |Ai| (at −1.0188) of the
/// stationary-phase expansion of the phase k₀ r sec²ψ cos(ψ − α) about the cusp
/// (docs/theory.md, "Wakes").
fn predicted_peak_angle(u: f64, r: f64) -> f64 {
    let phase = |psi: f64, alpha: f64| (psi - alpha).cos() / (psi.cos() * psi.cos());
    let psi = (0.5f64).sqrt().atan();
    let alpha = -(1.0f64 / 3.0).asin();
    let h = 1e-3;
    let mixed = (phase(psi + h, alpha + h) - phase(psi + h, alpha - h) - phase(psi - h, alpha + h)
        + phase(psi - h, alpha - h))
        / (4.0 * h * h);
    let third = (phase(psi + 2.0 * h, alpha) - 2.0 * phase(psi + h, alpha)
        + 2.0 * phase(psi - h, alpha)
        - phase(psi - 2.0 * h, alpha))
        / (2.0 * h * h * h);
    let k0r = G / (u * u) * r;
    let offset = 1.0188 / (k0r * mixed.abs() * (2.0 / (k0r * third.abs())).cbrt());
    (-alpha - offset).to_degrees()
}

#[test]
fn the_wake_peaks_at_kelvins_cusp_line() {
    let run = kelvin();
    for r in [60.0, 80.0, 100.0] {
        let measured = envelope_peak_angle(run, r);
        let predicted = predicted_peak_angle(SPEED, r);
        println!(
            "r = {r} m: envelope peak at {measured:.2}°, predicted {predicted:.2}° (cusp line 19.47°)"
        );
        assert!((measured - predicted).abs() < 2.0);
        // And never outside the cusp line.
        assert!(measured < 19.47);
    }
}

#[test]
fn the_water_ahead_of_the_bow_stays_still_for_minutes() {
    // Three minutes at 6 m/s: the hull crosses its 256 m window four times over, the window
    // following it, so any wave faster than the hull or wrapped around would show ahead.
    let wakes = WakeConfig {
        size: 256,
        spacing: 1.0,
        substep: 0.1,
        ..WakeConfig::default()
    };
    let spectrum = Spectrum::jonswap(2.0, 1000.0).unwrap();
    let run = straight_run(spectrum, wakes, Hull::default(), SPEED, 180.0, 0.1, 0.0);
    let length = f64::from(run.hull.length);
    let bow = run.hull_x + 0.5 * length;
    let border = 32.0;
    let side = run.size as f64 * run.spacing;
    let ahead = run.max_where(|x, z| {
        x > bow + length
            && (x - run.origin[0]) > border
            && x < run.origin[0] + side - border
            && (z - run.origin[1]) > border
            && (z - run.origin[1]) < side - border
    });
    let behind = run.wake_amplitude();
    let near = run.max_where(|x, _| x > bow && x < bow + length);
    println!("just ahead of the bow (one length) {near:.2e} m");
    println!(
        "ahead of the bow {ahead:.2e} m, wake {behind:.3} m, ratio {:.2e}",
        ahead / behind
    );
    assert!(behind > 0.01);
    assert!(ahead < 0.01 * behind);
}

#[test]
fn finite_depth_widens_the_wedge() {
    // Depth Froude number U/√(gh) = 0.9: Havelock's wedge is wider than Kelvin's.
    let depth = (SPEED / 0.9).powi(2) / G;
    let spectrum = Spectrum::tma(2.0, 1000.0, depth as f32).unwrap();
    assert!(matches!(
        spectrum.dispersion(),
        Dispersion::FiniteDepth { .. }
    ));
    let wakes = WakeConfig {
        size: 512,
        spacing: 0.5,
        substep: 0.05,
        ..WakeConfig::default()
    };
    let shallow = straight_run(spectrum, wakes, Hull::default(), SPEED, 70.0, 0.05, 0.3);
    let deep = kelvin();
    let wedge = |run: &Run| {
        // The widest angle at which the wake reaches a tenth of its largest amplitude, on the
        // arc of radius 80 m.
        let most = run.wake_amplitude();
        let mut widest: f64 = 0.0;
        let mut angle: f64 = 1.0;
        while angle < 60.0 {
            let a = angle.to_radians();
            for step in 0..200 {
                let r = 70.0 + 0.1 * f64::from(step);
                let h = run.at(run.hull_x - r * a.cos(), r * a.sin()).abs();
                if h > 0.1 * most {
                    widest = widest.max(angle);
                }
            }
            angle += 0.5;
        }
        widest
    };
    let (deep_angle, shallow_angle) = (wedge(deep), wedge(&shallow));
    println!(
        "wedge half-angle at 80 m: deep {deep_angle:.1}°, depth Froude 0.9 {shallow_angle:.1}°"
    );
    assert!(shallow_angle > deep_angle + 5.0);
}

#[test]
fn amplitude_grows_with_draft_and_beam() {
    let wakes = WakeConfig {
        size: 256,
        spacing: 1.0,
        substep: 0.1,
        ..WakeConfig::default()
    };
    let run = |draft: f32, beam: f32| {
        let spectrum = Spectrum::jonswap(2.0, 1000.0).unwrap();
        let hull = Hull {
            draft,
            beam,
            ..Hull::default()
        };
        straight_run(spectrum, wakes.clone(), hull, SPEED, 30.0, 0.1, 0.3).wake_amplitude()
    };
    let base = run(0.5, 5.0);
    let deeper = run(1.0, 5.0);
    let wider = run(0.5, 10.0);
    println!(
        "wake amplitude: {base:.4} m; twice the draft {deeper:.4} m; twice the beam {wider:.4} m"
    );
    // Linear waves: twice the pressure, twice the wake.
    assert!((deeper / base - 2.0).abs() < 0.01);
    assert!(wider > 1.2 * base);
}

#[test]
fn a_hull_at_rest_makes_a_steady_dip_and_no_waves() {
    let wakes = WakeConfig {
        size: 128,
        spacing: 1.0,
        substep: 0.1,
        ..WakeConfig::default()
    };
    let mut ocean = ocean(wakes);
    let hull = Hull::default();
    ocean.set_hulls(&[hull]).unwrap();
    ocean.step(300.0).unwrap();
    let wakes = ocean.wakes().unwrap();
    // In any depth the static response is hydrostatic: the water under the hull is pressed
    // down by its draft, and the waterplane's shape is the dip's.
    let centre = wakes.height_at(0.0, 0.0);
    let radius = 0.5 * f64::from(hull.length.hypot(hull.beam));
    let mut outside: f32 = 0.0;
    for (index, &h) in wakes.height().iter().enumerate() {
        let x = wakes.origin()[0] + (index % wakes.size()) as f64 * f64::from(wakes.spacing());
        let z = wakes.origin()[1] + (index / wakes.size()) as f64 * f64::from(wakes.spacing());
        if x.hypot(z) > radius + 2.0 {
            outside = outside.max(h.abs());
        }
    }
    println!(
        "dip at the centre {centre:.4} m (draft {}), largest |η| outside the hull {outside:.2e} m",
        hull.draft
    );
    assert!((centre + hull.draft).abs() < 0.02 * hull.draft);
    assert!(outside < 0.01 * hull.draft);
}

/// A small window with two hulls crossing it, stepped through `times` (s), the window moved
/// once; its wake buffers and a few queries at the end.
fn crossing(config: OceanConfig, times: &[f64]) -> (Vec<f32>, Vec<[f32; 2]>, Vec<f32>) {
    let mut ocean = OceanState::new(Spectrum::jonswap(5.0, 10_000.0).unwrap(), config).unwrap();
    let hulls = [
        Hull {
            position: [-20.0, 3.0],
            velocity: [5.0, 0.5],
            ..Hull::default()
        },
        Hull {
            position: [10.0, -15.0],
            velocity: [-1.0, 4.0],
            heading: 1.8,
            length: 8.0,
            beam: 3.0,
            draft: 0.6,
        },
    ];
    ocean.set_hulls(&hulls).unwrap();
    for &t in times {
        ocean.step_to(t).unwrap();
        if t == 1.5 {
            ocean.set_wake_centre(7.3, -2.1).unwrap();
        }
    }
    let points: Vec<[f64; 2]> = (0..100)
        .map(|i| [f64::from(i) * 0.77 - 30.0, f64::from(i % 7) * 3.1 - 10.0])
        .collect();
    let mut heights = vec![0.0; points.len()];
    ocean.water().heights_at(&points, &mut heights).unwrap();
    let wakes = ocean.wakes().unwrap();
    (wakes.height().to_vec(), wakes.slope().to_vec(), heights)
}

fn small_config() -> OceanConfig {
    OceanConfig {
        size: 32,
        wakes: Some(WakeConfig {
            size: 64,
            spacing: 1.0,
            substep: 0.05,
            ..WakeConfig::default()
        }),
        ..OceanConfig::default()
    }
}

#[test]
fn one_long_step_and_many_short_ones_draw_the_same_wake() {
    let fine: Vec<f64> = (1..=60).map(|k| f64::from(k) * 0.05).collect();
    let ragged = [0.013, 0.4, 0.41, 1.5, 1.52, 2.2, 2.999, 3.0];
    let coarse = [1.5, 3.0];
    let reference = crossing(small_config(), &fine);
    assert!(reference.0.iter().any(|&h| h.abs() > 0.01));
    assert_eq!(crossing(small_config(), &ragged), reference);
    assert_eq!(crossing(small_config(), &coarse), reference);
}

#[test]
fn bit_identical_at_any_thread_count_in_both_modes() {
    for determinism in [Determinism::SameMachine, Determinism::CrossPlatform] {
        let config = OceanConfig {
            determinism,
            ..small_config()
        };
        let times = [0.7, 1.5, 3.0];
        let results: Vec<_> = [1, 2, 3]
            .into_iter()
            .map(|threads| {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                pool.install(|| crossing(config.clone(), &times))
            })
            .collect();
        assert_eq!(results[0], results[1], "{determinism:?}");
        assert_eq!(results[0], results[2], "{determinism:?}");
    }
}

#[test]
fn queries_include_the_wake_inside_the_window_only() {
    let spectrum = Spectrum::jonswap(5.0, 10_000.0).unwrap();
    let with = small_config();
    let without = OceanConfig {
        wakes: None,
        ..with.clone()
    };
    let mut ocean = OceanState::new(spectrum.clone(), with).unwrap();
    let mut plain = OceanState::new(spectrum, without).unwrap();
    assert!(plain.wakes().is_none());
    ocean.set_hulls(&[Hull::default()]).unwrap();
    ocean.step(2.0).unwrap();
    plain.step(2.0).unwrap();
    let wakes = ocean.wakes().unwrap().clone();
    let handle = ocean.surface();
    let (water, plain, surface) = (ocean.water(), plain.water(), handle.water());
    // Inside: the sum, with the wake's height at the query point; outside (the window is
    // 64 m wide around the origin): the same bits as without wakes.
    for [x, z] in [
        [0.5, 0.25],
        [3.0, -1.7],
        [-9.2, 2.0],
        [100.0, 3.0],
        [-5.0, 70.0],
    ] {
        let (h, slope) = wakes.at(x, z);
        let inside = x.abs() < 30.0 && z.abs() < 30.0;
        assert_eq!(h != 0.0, inside, "({x}, {z})");
        let both = water.height_at(x, z).unwrap();
        let alone = plain.height_at(x, z).unwrap();
        assert_eq!(both, alone + h, "({x}, {z})");
        assert_eq!(surface.height_at(x, z).unwrap(), both);
        let s = water.surface_at(x, z).unwrap();
        let p = plain.surface_at(x, z).unwrap();
        assert_eq!(s.height, p.height + h);
        assert_eq!(s.slope, [p.slope[0] + slope[0], p.slope[1] + slope[1]]);
        assert_eq!(surface.surface_at(x, z).unwrap(), s);
        let sample = water.at_rest(x, z).unwrap();
        let base = plain.at_rest(x, z).unwrap();
        let (landed, _) = wakes.at(
            x + f64::from(base.displacement[0]),
            z + f64::from(base.displacement[1]),
        );
        assert_eq!(sample.height, base.height + landed);
        assert_eq!(surface.at_rest(x, z).unwrap(), sample);
        // Cascade 0 carries the wake, as it carries the foam: a range without it has none.
        let first = water.at_rest_cascades(x, z, 0..1).unwrap();
        let first_alone = plain.at_rest_cascades(x, z, 0..1).unwrap();
        assert_eq!(first.height - first_alone.height, {
            let d = first_alone.displacement;
            wakes.at(x + f64::from(d[0]), z + f64::from(d[1])).0
        });
        assert_eq!(
            water.at_rest_cascades(x, z, 1..2).unwrap(),
            plain.at_rest_cascades(x, z, 1..2).unwrap()
        );
        // Locating the water is horizontal: the wake moves no water sideways.
        assert_eq!(water.locate(x, z).unwrap(), plain.locate(x, z).unwrap());
        if !inside {
            assert_eq!(s, p);
            assert_eq!(sample, base);
        }
    }
    // Under the hull the water is pressed down.
    assert!(water.height_at(0.0, 0.0).unwrap() < plain.height_at(0.0, 0.0).unwrap() - 0.5);
    // Batches and grids give the single queries' bits, on the ocean and on the handle.
    let points: Vec<[f64; 2]> = (0..300)
        .map(|i| [f64::from(i) * 0.31 - 40.0, f64::from(i % 13) - 6.0])
        .collect();
    for view in [water, surface] {
        let mut heights = vec![0.0; points.len()];
        view.heights_at(&points, &mut heights).unwrap();
        let mut surfaces = vec![Default::default(); points.len()];
        view.surfaces_at(&points, &mut surfaces).unwrap();
        let mut samples = vec![Default::default(); points.len()];
        view.at_rest_many(&points, &mut samples).unwrap();
        for (k, &[x, z]) in points.iter().enumerate() {
            assert_eq!(heights[k], water.height_at(x, z).unwrap());
            assert_eq!(surfaces[k], water.surface_at(x, z).unwrap());
            assert_eq!(samples[k], water.at_rest(x, z).unwrap());
        }
        // 19 columns: two full lanes of eight and a ragged three.
        let mut grid = vec![Default::default(); 19 * 7];
        view.at_rest_grid([-40.0, -10.0], 4.3, [19, 7], &mut grid)
            .unwrap();
        for (k, got) in grid.iter().enumerate() {
            let (c, r) = ((k % 19) as f64, (k / 19) as f64);
            assert_eq!(
                *got,
                water.at_rest(-40.0 + c * 4.3, -10.0 + r * 4.3).unwrap()
            );
        }
    }
}

#[test]
fn bad_input_is_refused_by_name_and_changes_nothing() {
    let spectrum = Spectrum::jonswap(5.0, 10_000.0).unwrap();
    let name = |error: Error| match error {
        Error::NonFinite { name }
        | Error::OutOfRange { name, .. }
        | Error::InvalidSize { name, .. }
        | Error::CountOutOfRange { name, .. }
        | Error::NotApplicable { name, .. } => name,
        other => panic!("{other:?}"),
    };
    // The window.
    for (wakes, expected) in [
        (
            WakeConfig {
                size: 100,
                ..WakeConfig::default()
            },
            "wakes.size",
        ),
        (
            WakeConfig {
                size: 8,
                ..WakeConfig::default()
            },
            "wakes.size",
        ),
        (
            WakeConfig {
                spacing: 0.0,
                ..WakeConfig::default()
            },
            "wakes.spacing",
        ),
        (
            WakeConfig {
                spacing: -1.0,
                ..WakeConfig::default()
            },
            "wakes.spacing",
        ),
        (
            WakeConfig {
                spacing: f32::NAN,
                ..WakeConfig::default()
            },
            "wakes.spacing",
        ),
        (
            WakeConfig {
                substep: 0.0,
                ..WakeConfig::default()
            },
            "wakes.substep",
        ),
        (
            WakeConfig {
                border: 0.5,
                ..WakeConfig::default()
            },
            "wakes.border",
        ),
        (
            WakeConfig {
                damping: f32::INFINITY,
                ..WakeConfig::default()
            },
            "wakes.damping",
        ),
    ] {
        let config = OceanConfig {
            size: 16,
            wakes: Some(wakes),
            ..OceanConfig::default()
        };
        let error = OceanState::new(spectrum.clone(), config).unwrap_err();
        assert_eq!(name(error), expected);
    }
    // The hulls.
    let mut ocean = OceanState::new(spectrum.clone(), small_config()).unwrap();
    let mut reference = OceanState::new(spectrum.clone(), small_config()).unwrap();
    let good = Hull {
        velocity: [3.0, 0.0],
        ..Hull::default()
    };
    ocean.set_hulls(&[good]).unwrap();
    reference.set_hulls(&[good]).unwrap();
    let inner = small_config().wakes.unwrap().inner_side();
    for (hull, expected) in [
        (
            Hull {
                position: [f64::NAN, 0.0],
                ..good
            },
            "hull.position",
        ),
        (
            Hull {
                position: [0.0, f64::INFINITY],
                ..good
            },
            "hull.position",
        ),
        (
            Hull {
                velocity: [f32::NAN, 0.0],
                ..good
            },
            "hull.velocity",
        ),
        (
            Hull {
                velocity: [0.0, 1e6],
                ..good
            },
            "hull.velocity",
        ),
        (
            Hull {
                heading: f32::INFINITY,
                ..good
            },
            "hull.heading",
        ),
        (
            Hull {
                length: 0.0,
                ..good
            },
            "hull.length",
        ),
        (
            Hull {
                length: inner + 1.0,
                ..good
            },
            "hull.length",
        ),
        (Hull { beam: -2.0, ..good }, "hull.beam"),
        (
            Hull {
                beam: inner * 2.0,
                ..good
            },
            "hull.beam",
        ),
        (Hull { draft: 0.0, ..good }, "hull.draft"),
        (
            Hull {
                draft: f32::NAN,
                ..good
            },
            "hull.draft",
        ),
    ] {
        assert_eq!(name(ocean.set_hulls(&[good, hull]).unwrap_err()), expected);
    }
    let many = vec![good; WakeConfig::MAX_HULLS + 1];
    assert_eq!(name(ocean.set_hulls(&many).unwrap_err()), "hulls");
    assert!(ocean.set_hulls(&many[1..]).is_ok());
    ocean.set_hulls(&[good]).unwrap();
    assert_eq!(name(ocean.set_wake_centre(f64::NAN, 0.0).unwrap_err()), "x");
    assert_eq!(name(ocean.set_wake_centre(0.0, 1e300).unwrap_err()), "z");
    // Nothing changed: the same wake as an ocean that saw no bad input.
    ocean.step(1.0).unwrap();
    reference.step(1.0).unwrap();
    assert_eq!(ocean.wakes(), reference.wakes());
    // An ocean without wakes.
    let mut plain = OceanState::new(
        spectrum,
        OceanConfig {
            size: 16,
            ..OceanConfig::default()
        },
    )
    .unwrap();
    assert_eq!(name(plain.set_hulls(&[good]).unwrap_err()), "wakes");
    assert_eq!(name(plain.set_wake_centre(0.0, 0.0).unwrap_err()), "wakes");
}
