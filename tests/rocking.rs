//! Rocking of a rigid block against Housner's model (1963): free rocking from a tilt, the
//! energy balance, and the overturning of one-sine pulses.

mod common;

use masonry_dem::explicit::{simulate, DynamicOptions, Recording, TimeHistory};
use masonry_dem::geometry::Rect;
use masonry_dem::joint::JointLaw;
use masonry_dem::model::{JointLaws, Model, ModelSpec};

const G: f64 = 9.81;
const B: f64 = 0.4;
const H: f64 = 1.0;

/// The 0.4 x 1.0 m block on a rigid base, friction high enough that it rocks without sliding.
fn block(restitution: f64) -> Model {
    Model::new(ModelSpec {
        blocks: vec![Rect::new(0.0, 0.0, B, H).into()],
        gravity: G,
        joints: JointLaws::uniform(JointLaw { friction: 2.0, restitution, ..JointLaw::default() }),
        ..ModelSpec::default()
    })
    .unwrap()
}

/// Housner's rigid block: slenderness alpha, frequency parameter p, and the ratio of the angular
/// velocities after and before an impact, 1 - 1.5 sin^2(alpha) (angular momentum kept about the
/// new pivot).
struct Housner {
    alpha: f64,
    p: f64,
}

impl Housner {
    fn new() -> Self {
        let r = 0.5 * (B * B + H * H).sqrt();
        Housner { alpha: (B / H).atan(), p: (3.0 * G / (4.0 * r)).sqrt() }
    }

    fn restitution(&self) -> f64 {
        1.0 - 1.5 * self.alpha.sin().powi(2)
    }

    /// The exact rocking equation under a horizontal ground acceleration `ag` (positive along +x:
    /// it tips the block about its left toe, theta > 0): theta'' = -p^2 (sin(alpha s - theta) -
    /// s' ag/g cos(alpha s - theta)) with s the side of the pivot; a block at rest stays so while
    /// |ag| <= g tan(alpha).
    fn accel(&self, th: f64, w: f64, ag: f64) -> f64 {
        let s = if th != 0.0 { th.signum() } else if w != 0.0 { w.signum() } else { ag.signum() };
        if th == 0.0 && w == 0.0 && ag.abs() <= G * self.alpha.tan() {
            return 0.0;
        }
        let a = self.alpha * s - th;
        -self.p * self.p * (a.sin() - ag / G * a.cos())
    }

    /// Impact times and the angular velocity just before each, from (theta0, omega0), with
    /// restitution `r`, under the ground acceleration `ag(t)`, to time `t_end` (RK4, step h);
    /// and whether the block overturned (|theta| beyond 2 alpha).
    fn run(&self, th0: f64, w0: f64, r: f64, ag: &dyn Fn(f64) -> f64, t_end: f64, h: f64) -> (Vec<(f64, f64)>, bool) {
        let (mut t, mut th, mut w) = (0.0, th0, w0);
        let mut impacts = vec![];
        while t < t_end {
            let f = |t: f64, th: f64, w: f64| self.accel(th, w, ag(t));
            let k1 = (w, f(t, th, w));
            let k2 = (w + 0.5 * h * k1.1, f(t + 0.5 * h, th + 0.5 * h * k1.0, w + 0.5 * h * k1.1));
            let k3 = (w + 0.5 * h * k2.1, f(t + 0.5 * h, th + 0.5 * h * k2.0, w + 0.5 * h * k2.1));
            let k4 = (w + h * k3.1, f(t + h, th + h * k3.0, w + h * k3.1));
            let th1 = th + h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            let w1 = w + h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
            if th != 0.0 && th1 * th <= 0.0 {
                // the impact, by linear interpolation; the new pivot from there
                let s = th / (th - th1);
                let (ti, wi) = (t + s * h, w + s * (w1 - w));
                impacts.push((ti, wi));
                (t, th, w) = (ti, 0.0, r * wi);
                continue;
            }
            (t, th, w) = (t + h, th1, w1);
            if th.abs() > 2.0 * self.alpha {
                return (impacts, true);
            }
        }
        (impacts, false)
    }
}

/// The initial state of the block tilted by `th0` about its left toe, at rest.
fn tilted(th0: f64) -> [f64; 3] {
    let r = [B / 2.0, H / 2.0];
    let (c, s) = (th0.cos(), th0.sin());
    [c * r[0] - s * r[1] - r[0], s * r[0] + c * r[1] - r[1], th0]
}

/// The times at which the block's rotation changes sign (interpolated), each with the angular
/// velocity `delta` before and after it (from the records).
fn impacts(h: &TimeHistory, delta: f64) -> Vec<(f64, f64, f64)> {
    let phi = |k: usize| h.displacement(k)[0][2];
    let w_at = |t: f64| {
        let k = h.times.partition_point(|&x| x < t).min(h.times.len() - 1);
        h.velocity(k)[0][2]
    };
    let mut out = vec![];
    for k in 1..h.times.len() {
        if phi(k - 1) != 0.0 && phi(k - 1) * phi(k) < 0.0 {
            let t = h.times[k - 1] + (h.times[k] - h.times[k - 1]) * phi(k - 1) / (phi(k - 1) - phi(k));
            if t + delta < *h.times.last().unwrap() {
                out.push((t, w_at(t - delta), w_at(t + delta)));
            }
        }
    }
    out
}

/// The angular velocity at which the block passes its upright position with the amplitude
/// `theta_max` of the half-cycle (energy kept between impacts): omega^2 = 2 p^2 (cos(alpha -
/// theta_max) - cos(alpha)).
fn upright_velocity(hs: &Housner, theta_max: f64) -> f64 {
    (2.0 * hs.p * hs.p * ((hs.alpha - theta_max.abs()).cos() - hs.alpha.cos())).max(0.0).sqrt()
}

/// The ratio of the angular velocities after and before each impact, from the amplitudes of the
/// half-cycles on either side of it (the largest |phi| between sign changes; the first
/// half-cycle is the release, its amplitude the initial tilt).
fn amplitude_restitutions(h: &TimeHistory, hs: &Housner) -> Vec<f64> {
    let mut peaks = vec![];
    let mut peak = 0.0f64;
    for k in 0..h.times.len() {
        let phi = h.displacement(k)[0][2];
        if k > 0 && phi * h.displacement(k - 1)[0][2] < 0.0 {
            peaks.push(peak);
            peak = 0.0;
        }
        peak = peak.max(phi.abs());
    }
    // the last half-cycle counts only if it turned back (its peak is behind it)
    peaks.windows(2).map(|w| upright_velocity(hs, w[1]) / upright_velocity(hs, w[0])).collect()
}

#[test]
#[ignore = "calibration of the default restitution: run with --ignored --nocapture"]
fn calibrate_the_restitution_on_housners_impact() {
    let hs = Housner::new();
    let th0 = hs.alpha / 2.0;
    for e in [1.0, 0.8, 0.6, 0.5, 0.4, 0.3, 0.2, 0.15] {
        let m = block(e);
        let opts = DynamicOptions { duration: 1.6, initial_displacement: Some(vec![tilted(th0), [0.0; 3]]), record: Recording::Every(1), ..Default::default() };
        let h = simulate(&m, &opts).unwrap();
        let imp = impacts(&h, 2e-3);
        let r = amplitude_restitutions(&h, &hs);
        let ratios: Vec<String> = imp.iter().take(5).zip(r.iter().chain([f64::NAN; 5].iter())).map(|((t, _, _), r)| format!("t {t:.4} r {r:.3}")).collect();
        eprintln!("e_n {e}: dt {:.2e}, {} ; Housner r = {:.3}", h.time_step, ratios.join(", "), hs.restitution());
    }
}


/// The measured restitutions of the free rocking from half the slenderness.
fn free_rocking(duration: f64) -> (TimeHistory, Housner) {
    let hs = Housner::new();
    let m = block(JointLaw::default().restitution);
    let opts = DynamicOptions { duration, initial_displacement: Some(vec![tilted(hs.alpha / 2.0), [0.0; 3]]), record: Recording::Every(1), ..Default::default() };
    (simulate(&m, &opts).unwrap(), hs)
}

#[test]
fn free_rocking_follows_housner_impacts_and_keeps_its_energy_balance() {
    let (h, hs) = free_rocking(1.7);
    assert!(h.error.is_none(), "{:?}", h.error);
    // Housner's model from the same release, exact equation, its own restitution
    let (reference, _) = hs.run(hs.alpha / 2.0, 0.0, hs.restitution(), &|_| 0.0, 1.7, 1e-5);
    let got = impacts(&h, 0.0);
    assert!(got.len() >= 5 && reference.len() >= 5, "impacts: {} and Housner's {}", got.len(), reference.len());
    for k in 0..5 {
        let (t, t_ref) = (got[k].0, reference[k].0);
        eprintln!("impact {}: t = {t:.4} s, Housner {t_ref:.4} s ({:+.2}%)", k + 1, 100.0 * (t / t_ref - 1.0));
        assert!((t / t_ref - 1.0).abs() < 0.02, "impact {} at {t:.4} s, Housner's at {t_ref:.4} s", k + 1);
    }
    let r = amplitude_restitutions(&h, &hs);
    for (k, r) in r.iter().take(4).enumerate() {
        eprintln!("impact {}: restitution {r:.4}, Housner {:.4}", k + 1, hs.restitution());
        assert!((r / hs.restitution() - 1.0).abs() < 0.05, "impact {}: restitution {r:.4}, Housner's {:.4}", k + 1, hs.restitution());
    }
    // the energy balance: the initial energy is the potential energy of the tilt
    let e0 = B * H * 1000.0 * G * tilted(hs.alpha / 2.0)[1];
    let worst = h.energy_error.iter().fold(0.0f64, |a, e| a.max(e.abs()));
    let backwards = h.dissipated.windows(2).map(|w| w[0] - w[1]).fold(0.0f64, f64::max);
    eprintln!("initial energy {e0:.2} J, dissipated {:.2} J, worst balance error {worst:.2e} J, largest step back of the dissipation {backwards:.2e} J", h.dissipated.last().unwrap());
    assert!(worst < 0.01 * e0, "energy balance off by {worst:.3e} J of {e0:.3e} J");
    assert!(backwards <= 1e-4 * e0, "the dissipated energy decreased by {backwards:.3e} J");
}

/// A one-sine pulse of amplitude `a` \[m/s2\] and period `tp` \[s\], sampled finely.
fn one_sine(a: f64, tp: f64) -> (Vec<f64>, Vec<f64>) {
    let n = 2000;
    (0..=n).map(|k| {
        let t = tp * k as f64 / n as f64;
        (t, a * (2.0 * std::f64::consts::PI * t / tp).sin())
    }).unzip()
}

/// The smallest amplitude in `[lo, hi]` (as multiples of g tan(alpha)) that overturns, by
/// bisection to `tol`, given `overturns` (true at `hi`, false at `lo`).
fn threshold(mut lo: f64, mut hi: f64, tol: f64, overturns: &dyn Fn(f64) -> bool) -> f64 {
    assert!(!overturns(lo) && overturns(hi), "no overturning threshold in [{lo}, {hi}]");
    while hi - lo > tol * hi {
        let mid = 0.5 * (lo + hi);
        if overturns(mid) { hi = mid } else { lo = mid }
    }
    0.5 * (lo + hi)
}

#[test]
fn one_sine_pulse_overturning_matches_housner_with_the_same_restitution() {
    // the restitution of the model's impacts, measured on its free rocking
    let (h, hs) = free_rocking(1.7);
    let r = amplitude_restitutions(&h, &hs);
    let r = r.iter().take(4).sum::<f64>() / 4.0;
    let m = block(JointLaw::default().restitution);
    let unit = G * hs.alpha.tan();
    // (friction 2: the block does not slide below 5 g tan(alpha))
    let phi_limit = 2.0 * hs.alpha;
    for tp in [0.4, 0.5, 0.6, 0.8, 1.0, 1.4] {
        let duration = tp + 3.0;
        let dem = |x: f64| {
            let opts = DynamicOptions { duration, base_acceleration: Some(one_sine(x * unit, tp)), record: Recording::Interval(2e-3), ..Default::default() };
            let h = simulate(&m, &opts).unwrap();
            (0..h.times.len()).any(|k| h.displacement(k)[0][2].abs() > phi_limit)
        };
        let housner = |x: f64| {
            let ag = |t: f64| if t <= tp { x * unit * (2.0 * std::f64::consts::PI * t / tp).sin() } else { 0.0 };
            hs.run(0.0, 0.0, r, &ag, duration, 2e-5).1
        };
        let (a, a_ref) = (threshold(1.0, 4.5, 2e-3, &dem), threshold(1.0, 4.5, 2e-3, &housner));
        eprintln!("period {tp} s: overturned from {a:.3} g tan(alpha), Housner {a_ref:.3} ({:+.2}%)", 100.0 * (a / a_ref - 1.0));
        assert!((a / a_ref - 1.0).abs() < 0.03, "period {tp} s: {a:.3} against Housner's {a_ref:.3} g tan(alpha)");
    }
}
