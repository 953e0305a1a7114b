//! Wakes (issue 40) against closed forms: Kelvin's transverse wavelength 2πU²/g and cusp
//! angle (with the stationary-phase offset of the envelope's maximum at a finite distance),
//! still water ahead of the bow, the steady dip of a hull at rest, amplitude against draft and
//! beam, the independence of the step partition, bad input, and what queries see.
// Reference computations in the standard library's maths: tests are not simulation code.
#![allow(clippy::disallowed_methods)]

use std::sync::OnceLock;

use ocean_fft::{Dispersion, Error, Hull, OceanConfig, OceanState, Spectrum, WakeConfig};

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
        let gx = (x - self.origin[0]) / self.spacing;
        let gz = (z - self.origin[1]) / self.spacing;
        let (ix, iz) = (gx.floor() as usize, gz.floor() as usize);
        let (fx, fz) = (gx - ix as f64, gz - iz as f64);
        let h = |i: usize, j: usize| f64::from(self.height[j * self.size + i]);
        (1.0 - fz) * ((1.0 - fx) * h(ix, iz) + fx * h(ix + 1, iz))
            + fz * ((1.0 - fx) * h(ix, iz + 1) + fx * h(ix + 1, iz + 1))
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
) -> Run {
    let side = wakes.size as f64 * f64::from(wakes.spacing);
    let mut ocean = ocean_with(spectrum, wakes);
    let hull = Hull {
        velocity: [speed as f32, 0.0],
        ..hull
    };
    ocean.set_hulls(&[hull]).unwrap();
    let steps = (seconds / dt).round() as usize;
    let ahead = 0.3 * side;
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
        println!("r = {r} m: envelope peak at {measured:.2}°, predicted {predicted:.2}° (cusp line 19.47°)");
    }
}
