//! Limit analysis along a mechanism: the large-displacement capacity curve lambda(d). From the
//! collapse mechanism the blocks are moved by a finite step of it (each block turned exactly
//! about its instantaneous centre), the interfaces are found again where the blocks now touch
//! (along edges or at points: [`Model::moved`]), and the limit analysis is solved again on the
//! moved geometry, its mechanism giving the next step, until no equilibrium remains (lambda
//! has reached zero) or the steps run out. A step that fails is halved: the curve's end is
//! found within a small fraction of a step.

use super::{limit_analysis_with, LimitOptions, LimitProgress};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::results::{Results, Status};
use std::time::Instant;

/// How a mechanism is followed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FollowOptions {
    /// The step: the largest displacement of a vertex of a moving block in one step \[m\]; 0:
    /// the model's size over 200.
    pub step: f64,
    /// Steps at most (the halvings of the last step, which find where lambda reaches zero, not
    /// counted).
    pub max_steps: usize,
}

impl Default for FollowOptions {
    fn default() -> Self {
        FollowOptions { step: 0.0, max_steps: 1000 }
    }
}

/// Where lambda is taken to have reached zero: below this fraction of the first multiplier.
const ZERO: f64 = 1e-3;

/// Blocks apart by no more than this fraction of the step touch on the moved geometry: the
/// mechanism of an interior point is a velocity field accurate to its tolerance and, where
/// several mechanisms share the optimum, a blend of them, whose hinges open by a small fraction
/// of the step.
const GAP: f64 = 1e-3;

/// Halvings of the last step, at most, to find where no equilibrium begins.
const HALVINGS: usize = 30;

/// Where the steps' halvings end with lambda above this fraction of the first multiplier, the
/// curve has not reached zero: the equilibrium is lost to a change of mechanism.
const ZERO_SNAP: f64 = 1e-2;

/// The largest `max_steps` accepted.
pub const MAX_FOLLOW_STEPS: usize = 100_000;

/// Limit analysis of `model`, then its mechanism followed by finite steps (see the module's
/// text): the result is the first analysis's (the collapse multiplier, the mechanism and the
/// forces at collapse, with the certificate), with the curve filled: `curve_displacement` the
/// control block's horizontal displacement \[m\] and `curve_multiplier` the multiplier on the
/// moved geometry at each step, from (0, lambda_0); `displacements` the blocks' finite motion at
/// the curve's last point (u1, u2 of the centre of mass \[m\], phi \[rad\]); `steps` the steps
/// taken. Where a step fails (no equilibrium on the moved geometry, a program that does not
/// converge, blocks that would overlap or lose their support), it is halved, at most 30 times,
/// and the following steps grow back: the curve ends where lambda reaches zero (within 1e-3 of
/// lambda_0). The status is the first analysis's; a curve that stops short of zero (the steps
/// ran out; every step failed with lambda above 1e-2 of lambda_0, where the mechanism changes in
/// a way the steps do not follow) says why in `error`.
pub fn follow_mechanism(
    model: &Model,
    opts: &LimitOptions,
    follow: &FollowOptions,
    monitor: &mut dyn FnMut(&LimitProgress) -> bool,
) -> Result<Results> {
    if !(follow.step.is_finite() && follow.step >= 0.0) {
        return Err(Error::input_at("analysis.follow_step", format!("analysis.follow_step must be a length >= 0 m (0: the model's size over 200), got {}", follow.step)));
    }
    if follow.max_steps == 0 || follow.max_steps > MAX_FOLLOW_STEPS {
        return Err(Error::input_at("analysis.follow_steps", format!("analysis.follow_steps must lie in 1..={MAX_FOLLOW_STEPS}, got {}", follow.max_steps)));
    }
    let start = Instant::now();
    let mut res = limit_analysis_with(model, opts, monitor)?;
    if res.status != Status::Collapse {
        return Ok(res);
    }
    let nb = model.n_blocks();
    let control = res.control_block;
    let h = model.horizontal();
    let step = if follow.step > 0.0 { follow.step } else { model.size() / 200.0 };
    let lambda0 = res.collapse_multiplier;
    res.curve_displacement = vec![0.0];
    res.curve_multiplier = vec![lambda0];
    let mut total = vec![[0.0; 3]; nb];
    let mut current = model.clone();
    let mut mechanism = res.mechanism.clone();
    let mut iterations = res.iterations;
    let mut fraction = 1.0;
    let mut steps = 0;
    // why the last step tried failed, while its halvings go on
    let mut failure = String::new();
    let end = loop {
        if steps >= follow.max_steps {
            break Some(format!("the steps ran out (follow_steps = {}) before lambda reached zero", follow.max_steps));
        }
        let Some(mut motion) = step_motion(&current, &mechanism, fraction * step) else {
            break Some("the mechanism has stopped moving".into());
        };
        close_contacts(&current, &mechanism, &mut motion);
        // the full step's gap: the contacts a longer step left open by up to it are kept
        let next = match current.moved(&motion, GAP * step) {
            Ok(m) => Ok(m),
            Err(e @ Error::Input { .. }) => Err(format!("moved blocks were refused: {e}")),
            Err(e) => return Err(e),
        };
        let analysed = match next {
            Ok(next) => match limit_analysis_with(&next, opts, monitor) {
                Ok(r) => Ok((next, r)),
                Err(e @ Error::Input { .. }) => Err(format!("moved blocks were refused: {e}")),
                Err(e) => return Err(e),
            },
            Err(why) => Err(why),
        };
        let outcome = match analysed {
            Ok((next, r)) => {
                iterations += r.iterations;
                if r.status == Status::Collapse {
                    Ok((next, r))
                } else {
                    Err(format!("limit analysis ended {}: {}", r.status.as_str(), r.error.unwrap_or_default()))
                }
            }
            Err(why) => Err(why),
        };
        match outcome {
            Ok((next, r)) => {
                steps += 1;
                for (t, m) in total.iter_mut().zip(&motion) {
                    t[0] += m[0];
                    t[1] += m[1];
                    t[2] += m[2];
                }
                res.curve_displacement.push(total[control][0] * h[0] + total[control][1] * h[1]);
                res.curve_multiplier.push(r.collapse_multiplier);
                if r.collapse_multiplier <= ZERO * lambda0 {
                    break None;
                }
                current = next;
                mechanism = r.mechanism;
                fraction = (2.0 * fraction).min(1.0);
            }
            // no equilibrium, or blocks that would meet, within this step: it is halved until
            // the last point is within a 2^-HALVINGS fraction of the step of where that begins
            Err(why) if fraction >= 0.5f64.powi(HALVINGS as i32) => {
                failure = why;
                fraction *= 0.5;
            }
            // lambda reached zero there: the curve's end
            Err(_) if res.curve_multiplier[steps] <= ZERO_SNAP * lambda0 => break None,
            Err(_) => {
                break Some(format!(
                    "every step past it, down to {:.1e} m, failed, with lambda still {:.3} of the first multiplier: the \
                     mechanism changes there in a way that limit analysis along it does not follow (a sudden change, \
                     such as blocks that turn back until they meet others, has no equilibrium at any lambda in \
                     between); on the last step, {failure}",
                    fraction * step,
                    res.curve_multiplier[steps] / lambda0
                ))
            }
        }
    };
    res.displacements = total;
    res.steps = steps;
    res.iterations = iterations;
    res.error = end.map(|why| {
        let (d, l) = (res.curve_displacement[steps], res.curve_multiplier[steps]);
        format!("the mechanism was followed {steps} steps, to a displacement of {d:.6e} m where lambda = {l:.6}: {why}")
    });
    res.elapsed_s = start.elapsed().as_secs_f64();
    Ok(res)
}

/// The finite motion of each block of `model` over one step of `mechanism` (block velocities,
/// any scale) whose largest vertex displacement is `length` \[m\]: each moving block turned about
/// its instantaneous centre by its share of the step (translated where it does not turn), as
/// (u1, u2, phi) of its centroid; None where nothing moves.
fn step_motion(model: &Model, mechanism: &[[f64; 3]], length: f64) -> Option<Vec<[f64; 3]>> {
    let (polygons, centroids) = (model.polygons(), model.centroids());
    let mut vmax = 0.0f64;
    for (i, m) in mechanism.iter().enumerate() {
        let c = centroids[i];
        for v in polygons[i].vertices() {
            let (dx, dy) = (v[0] - c[0], v[1] - c[1]);
            vmax = vmax.max((m[0] - m[2] * dy).hypot(m[1] + m[2] * dx));
        }
    }
    if !(vmax > 0.0 && vmax.is_finite()) {
        return None;
    }
    let s = length / vmax;
    let motion = mechanism
        .iter()
        .map(|m| {
            let (u, v, w) = (m[0] * s, m[1] * s, m[2] * s);
            if w == 0.0 {
                return [u, v, 0.0];
            }
            // turned by w about the instantaneous centre (where u + w k x r is zero), the
            // centroid moves by (u S - v C, v S + u C), S = sin(w) / w, C = (1 - cos w) / w
            let (sinc, cosc) = (w.sin() / w, 2.0 * (0.5 * w).sin().powi(2) / w);
            [u * sinc - v * cosc, v * sinc + u * cosc, w]
        })
        .collect();
    Some(motion)
}

/// A point where two blocks touch, that a step of the mechanism keeps closed: blocks `a`, `b`,
/// the point in the configuration before the step, and whether the mechanism keeps it from
/// slipping as well (a hinge) or only from opening (sliding).
struct Kept {
    a: usize,
    b: usize,
    p: [f64; 2],
    n: [f64; 2],
    hinge: bool,
}

/// Relative velocities at a contact point below this fraction of the mechanism's largest keep
/// it closed (normal) or stuck (tangential).
const CLOSED: f64 = 1e-6;

/// Sweeps of the projection at most, and the fraction of the contact tolerance it stops at.
const SWEEPS: usize = 200;

/// Moves `motion` (one step of `mechanism` on `model`) the least onto the motions that keep
/// closed the contact points the mechanism keeps closed: each block turned about its own
/// instantaneous centre moves the point it shares with another moving block along two different
/// circles, which part by about theta^2 L in a step of rotation theta (a four-hinge arch's
/// hinges open by a fifth of the step's tolerance in one step and are lost in a few). The
/// projection is a nonlinear Gauss-Seidel over the kept points (each correction the least that
/// closes one point, shared by its two blocks, the fixed ones not moved), until every kept point
/// is closed within a hundredth of the contact tolerance.
fn close_contacts(model: &Model, mechanism: &[[f64; 3]], motion: &mut [[f64; 3]]) {
    let (centroids, polygons) = (model.centroids(), model.polygons());
    let fixed = model.fixed();
    let free = |i: usize| !(fixed[3 * i] || fixed[3 * i + 1] || fixed[3 * i + 2]);
    let velocity = |i: usize, p: [f64; 2]| {
        let (m, c) = (mechanism[i], centroids[i]);
        [m[0] - m[2] * (p[1] - c[1]), m[1] + m[2] * (p[0] - c[0])]
    };
    let vmax = (0..polygons.len())
        .flat_map(|i| polygons[i].vertices().iter().map(move |&v| (i, v)))
        .map(|(i, v)| {
            let w = velocity(i, v);
            w[0].hypot(w[1])
        })
        .fold(0.0f64, f64::max);
    let mut kept = Vec::new();
    for it in model.interfaces() {
        if !(free(it.a) || free(it.b)) {
            continue;
        }
        let t = it.t();
        let ends = [[it.c[0] - 0.5 * it.l * t[0], it.c[1] - 0.5 * it.l * t[1]], [it.c[0] + 0.5 * it.l * t[0], it.c[1] + 0.5 * it.l * t[1]]];
        for p in ends.iter().take(if it.l > 0.0 { 2 } else { 1 }) {
            let (va, vb) = (velocity(it.a, *p), velocity(it.b, *p));
            let rel = [vb[0] - va[0], vb[1] - va[1]];
            let (rn, rt) = (rel[0] * it.n[0] + rel[1] * it.n[1], rel[0] * t[0] + rel[1] * t[1]);
            if rn.abs() <= CLOSED * vmax {
                kept.push(Kept { a: it.a, b: it.b, p: *p, n: it.n, hinge: rt.abs() <= CLOSED * vmax });
            }
        }
    }
    let tol = 0.01 * crate::shape::contact_tolerance(model.size());
    let turn = |v: [f64; 2], phi: f64| {
        let (s, co) = phi.sin_cos();
        [co * v[0] - s * v[1], s * v[0] + co * v[1]]
    };
    // where point p of block i goes under motion m, and the arm from its moved centroid
    let place = |i: usize, m: [f64; 3], p: [f64; 2]| {
        let c = centroids[i];
        let r = turn([p[0] - c[0], p[1] - c[1]], m[2]);
        ([c[0] + m[0] + r[0], c[1] + m[1] + r[1]], r)
    };
    // block i moved by g along d, turned by g j, if it is free
    let nudge = |m: &mut [f64; 3], free: bool, g: f64, d: [f64; 2], j: f64| {
        if free {
            m[0] += g * d[0];
            m[1] += g * d[1];
            m[2] += g * j;
        }
    };
    for _ in 0..SWEEPS {
        let mut worst = 0.0f64;
        for k in &kept {
            let (pa, ra) = place(k.a, motion[k.a], k.p);
            let (pb, rb) = place(k.b, motion[k.b], k.p);
            let gap = [pb[0] - pa[0], pb[1] - pa[1]];
            let n = turn(k.n, motion[k.a][2]);
            let dirs: &[[f64; 2]] = if k.hinge { &[n, [n[1], -n[0]]] } else { &[n] };
            let (fa, fb) = (free(k.a), free(k.b));
            for &d in dirs {
                let c = gap[0] * d[0] + gap[1] * d[1];
                worst = worst.max(c.abs());
                // the gradient of c: -(d, ra x d) on a's (u, phi), +(d, rb x d) on b's
                let (ja, jb) = (ra[0] * d[1] - ra[1] * d[0], rb[0] * d[1] - rb[1] * d[0]);
                let norm = if fa { 1.0 + ja * ja } else { 0.0 } + if fb { 1.0 + jb * jb } else { 0.0 };
                if norm == 0.0 {
                    continue;
                }
                let g = c / norm;
                nudge(&mut motion[k.a], fa, g, d, ja);
                nudge(&mut motion[k.b], fb, -g, d, jb);
            }
        }
        if worst <= tol {
            break;
        }
    }
}
