//! The explicit solver in time, no damping: sliding on an inclined plane, Housner's rocking
//! block, and energy conservation with elastic joints (docs/references.md, section 1).

mod common;
use common::*;
use masonry_dem::explicit::{simulate, DynamicOptions, Recording};
use masonry_dem::geometry::Rect;
use masonry_dem::joint::JointLaw;
use masonry_dem::model::{JointLaws, Model, ModelSpec};

/// Least-squares slope of y against x.
fn slope(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

#[test]
fn block_slides_down_an_incline_at_g_sin_minus_mu_cos() {
    // the plane inclined at beta: gravity g cos(beta) normal to the joint and a constant live
    // load tan(beta) * W along it
    let (g, beta, mu) = (9.81_f64, 25f64.to_radians(), 0.3);
    let m = Model::new(ModelSpec {
        blocks: vec![Rect::new(0.0, 0.0, 0.4, 0.175).into()],
        gravity: g * beta.cos(),
        joints: JointLaws::uniform(dry(mu, 0.0, 1e10)),
        ..ModelSpec::default()
    })
    .unwrap();
    let h = simulate(&m, &DynamicOptions { duration: 0.4, live_multiplier: beta.tan(), record: Recording::Every(10), ..Default::default() }).unwrap();
    let (t, v): (Vec<f64>, Vec<f64>) = h.times.iter().enumerate().filter(|(_, t)| **t >= 0.05).map(|(k, t)| (*t, h.velocity(k)[0][0])).unzip();
    let a = slope(&t, &v);
    assert_close(a, g * (beta.sin() - mu * beta.cos()), 0.01, "sliding acceleration [m/s2]");
}

#[test]
fn housner_block_reaches_its_first_impact_at_0_3578_s() {
    // 0.4 x 1.0 m block released from rest at half its slenderness angle, tilted about its left toe
    let (b, hgt) = (0.4_f64, 1.0_f64);
    let m = Model::new(ModelSpec {
        blocks: vec![Rect::new(0.0, 0.0, b, hgt).into()],
        gravity: 9.81,
        joints: JointLaws::uniform(JointLaw { friction: 2.0, dilatancy: 0.0, ..dry(2.0, 0.0, 1e10) }),
        ..ModelSpec::default()
    })
    .unwrap();
    let alpha = (b / hgt).atan();
    let th0 = alpha / 2.0;
    let r = [b / 2.0, hgt / 2.0]; // centroid from the left toe (0, 0)
    let (c, s) = (th0.cos(), th0.sin());
    let u0 = [c * r[0] - s * r[1] - r[0], s * r[0] + c * r[1] - r[1], th0];
    let h = simulate(
        &m,
        &DynamicOptions { duration: 0.5, initial_displacement: Some(vec![u0, [0.0; 3]]), record: Recording::Every(1), ..Default::default() },
    )
    .unwrap();
    assert!(h.error.is_none(), "{:?}", h.error);
    // first time the rotation reaches zero (the impact on the right toe), interpolated
    let k = (0..h.times.len()).position(|k| h.displacement(k)[0][2] <= 0.0).expect("no impact within 0.5 s");
    let (p0, p1) = (h.displacement(k - 1)[0][2], h.displacement(k)[0][2]);
    let t1 = h.times[k - 1] + (h.times[k] - h.times[k - 1]) * p0 / (p0 - p1);
    assert_close(t1, 0.3578, 0.03, "time of the first impact [s]");
    let w = h.velocity(k)[0][2].abs();
    eprintln!("t1 = {t1:.4} s, angular velocity at impact {w:.3} rad/s (exact 1.209)");
}

#[test]
fn energy_is_conserved_with_elastic_joints_and_no_damping() {
    // wall 1 with joints that never yield, dropped under its own weight onto its joints and
    // left to vibrate: external work = kinetic + elastic energy; drift over 100,000 steps,
    // from the mean over the first 2,000 steps to the mean over the last 2,000 (the mean removes
    // the bounded oscillation of the Verlet energy)
    // (elastic impacts: no contact dashpot)
    let strong = JointLaw { cohesion: 1e15, tensile_strength: 1e15, restitution: 1.0, ..dry(0.65, 0.0, 1e9) };
    let m = ferris(6, strong);
    let dt = 0.5 * masonry_dem::explicit::critical_time_step(&m);
    let h = simulate(&m, &DynamicOptions { duration: 100_000.0 * dt, time_step: Some(dt), large_rotations: false, record: Recording::Every(1), ..Default::default() }).unwrap();
    assert!(h.steps >= 100_000);
    // nothing dissipates: the balance's error is what the joints' dissipation would be
    let worst = h.dissipated.iter().chain(&h.energy_error).fold(0.0f64, |a, x| a.max(x.abs()));
    let peak = h.elastic_energy.iter().cloned().fold(0.0, f64::max);
    assert!(worst < 1e-3 * peak, "dissipation or balance error {worst:.3e} J with elastic joints (peak elastic energy {peak:.3e} J)");
    let e: Vec<f64> = h.external_work.iter().zip(&h.kinetic_energy).zip(&h.elastic_energy).map(|((w, k), el)| k + el - w).collect();
    let scale = h.elastic_energy.iter().cloned().fold(0.0, f64::max);
    let mean = |s: &[f64]| s.iter().sum::<f64>() / s.len() as f64;
    let n = e.len();
    let drift = (mean(&e[n - 2000..]) - mean(&e[1..2001])).abs() / scale;
    eprintln!("energy drift over {} steps: {:.2e} of the peak elastic energy {scale:.3e} J", h.steps, drift);
    assert!(drift < 1e-3, "energy drift {drift:.2e} >= 0.1%");
}

#[test]
fn base_acceleration_beyond_friction_makes_the_block_slide_back() {
    // constant horizontal base acceleration a_g = 0.5 g, friction 0.3: relative to the base the
    // block accelerates at -(a_g - mu g)
    let (g, mu, ag) = (9.81_f64, 0.3, 0.5 * 9.81);
    let m = Model::new(ModelSpec {
        blocks: vec![Rect::new(0.0, 0.0, 0.4, 0.175).into()],
        gravity: g,
        joints: JointLaws::uniform(dry(mu, 0.0, 1e10)),
        ..ModelSpec::default()
    })
    .unwrap();
    let opts = DynamicOptions {
        duration: 0.4,
        base_acceleration: Some((vec![0.0, 10.0], vec![ag, ag])),
        record: Recording::Every(10),
        ..Default::default()
    };
    let h = simulate(&m, &opts).unwrap();
    let (t, v): (Vec<f64>, Vec<f64>) = h.times.iter().enumerate().filter(|(_, t)| **t >= 0.05).map(|(k, t)| (*t, h.velocity(k)[0][0])).unzip();
    assert_close(slope(&t, &v), -(ag - mu * g), 0.01, "relative sliding acceleration [m/s2]");
}

#[test]
fn rayleigh_damping_gives_its_damping_ratio_to_a_mode() {
    // a 0.4 x 0.175 m block's vertical vibration on its base joint (elastic impacts: no contact
    // dashpot), omega^2 = kN A / m, about its static settlement; Rayleigh damping set for 5% at
    // omega and 3% at 3 omega: the logarithmic decrement of the vibration gives 5%
    let (g, k) = (9.81, 1e10);
    let law = JointLaw { restitution: 1.0, ..dry(0.65, 0.0, k) };
    let m = Model::new(ModelSpec { blocks: vec![Rect::new(0.0, 0.0, 0.4, 0.175).into()], gravity: g, joints: JointLaws::uniform(law), ..ModelSpec::default() }).unwrap();
    let mass = 0.4 * 0.175 * 1000.0;
    let omega = (k * 0.4 / mass).sqrt();
    let (alpha, beta) = masonry_dem::modal::rayleigh_coefficients(omega, 3.0 * omega, 0.05, 0.03).unwrap();
    let settled = -mass * g / (k * 0.4);
    // a fine time step: the central difference's own error on the damping is of order omega dt
    let dt = 2.0 / omega / 200.0;
    let opts = DynamicOptions {
        duration: 12.0 * std::f64::consts::TAU / omega,
        time_step: Some(dt),
        damping: masonry_dem::explicit::Damping::Viscous(alpha),
        stiffness_damping: beta,
        initial_displacement: Some(vec![[0.0, settled, 0.0], [0.0; 3]]),
        initial_velocity: Some(vec![[0.0, 1e-4, 0.0], [0.0; 3]]),
        large_rotations: false,
        record: Recording::Every(1),
        ..Default::default()
    };
    let h = simulate(&m, &opts).unwrap();
    let y: Vec<f64> = (0..h.times.len()).map(|k| h.displacement(k)[0][1] - settled).collect();
    let peaks: Vec<f64> = (1..y.len() - 1).filter(|&k| y[k] > y[k - 1] && y[k] >= y[k + 1]).map(|k| y[k]).collect();
    assert!(peaks.len() >= 10, "{} peaks", peaks.len());
    let delta = (peaks[0] / peaks[9]).ln() / 9.0;
    let zeta = delta / (4.0 * std::f64::consts::PI.powi(2) + delta * delta).sqrt();
    eprintln!("damping ratio of the vertical mode: {zeta:.5} (set 0.05)");
    assert_close(zeta, 0.05, 0.02, "damping ratio");
}
