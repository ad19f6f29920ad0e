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
    check(follow)?;
    let start = Instant::now();
    let res = limit_analysis_with(model, opts, monitor)?;
    if res.status != Status::Collapse {
        return Ok(res);
    }
    let control = res.control_block;
    let h = model.horizontal();
    let along = move |t: &[[f64; 3]]| t[control][0] * h[0] + t[control][1] * h[1];
    let step = if follow.step > 0.0 { follow.step } else { model.size() / 200.0 };
    let path = Path { signed: false, along: &along, to_zero: true, held: None, step };
    let (mut res, end) = walk(model, res, opts, follow, &path, monitor)?;
    let lambda0 = res.curve_multiplier[0];
    let why = match end {
        End::Zero => None,
        End::StepsOut => Some(format!("the steps ran out (follow_steps = {}) before lambda reached zero", follow.max_steps)),
        End::Stopped => Some("the mechanism has stopped moving".into()),
        // lambda reached zero there: the curve's end
        End::Exhausted { .. } if res.curve_multiplier[res.steps] <= ZERO_SNAP * lambda0 => None,
        End::Exhausted { smallest, failure, .. } => Some(format!(
            "every step past it, down to {smallest:.1e} m, failed, with lambda still {:.3} of the first multiplier: the \
             mechanism changes there in a way that limit analysis along it does not follow (a sudden change, \
             such as blocks that turn back until they meet others, has no equilibrium at any lambda in \
             between); on the last step, {}",
            res.curve_multiplier[res.steps] / lambda0,
            failure.why()
        )),
    };
    res.error = why.map(|why| {
        let (d, l) = (res.curve_displacement[res.steps], res.curve_multiplier[res.steps]);
        format!("the mechanism was followed {} steps, to a displacement of {d:.6e} m where lambda = {l:.6}: {why}", res.steps)
    });
    res.elapsed_s = start.elapsed().as_secs_f64();
    Ok(res)
}

/// Refuses follow options out of range, naming their keys.
pub(super) fn check(follow: &FollowOptions) -> Result<()> {
    if !(follow.step.is_finite() && follow.step >= 0.0) {
        return Err(Error::input_at("analysis.follow_step", format!("analysis.follow_step must be a length >= 0 m (0: the model's size over 200), got {}", follow.step)));
    }
    if follow.max_steps == 0 || follow.max_steps > MAX_FOLLOW_STEPS {
        return Err(Error::input_at("analysis.follow_steps", format!("analysis.follow_steps must lie in 1..={MAX_FOLLOW_STEPS}, got {}", follow.max_steps)));
    }
    Ok(())
}

/// What a walk along a mechanism follows: whether lambda is a force of either sign (a support
/// movement's), the curve's abscissa from the blocks' total motion, and whether the walk ends
/// where lambda reaches zero (a live load that falls to zero; a support movement's force does
/// not: its walk ends where no equilibrium remains).
pub(super) struct Path<'a> {
    pub(super) signed: bool,
    pub(super) along: &'a dyn Fn(&[[f64; 3]]) -> f64,
    pub(super) to_zero: bool,
    /// A support movement's dof (block, dof of the block): where a step's program fails, the
    /// moved wall with the support held there is asked whether it stands at all
    /// ([`stands`]).
    pub(super) held: Option<(usize, usize)>,
    /// The step: the largest displacement of a vertex of a moving block in one step \[m\].
    pub(super) step: f64,
}

/// Why a step failed: the moved geometry has no equilibrium at any lambda (the program is
/// infeasible: a dual ray proves it), or something else (a program that does not converge,
/// blocks refused), which proves nothing.
pub(super) enum Failure {
    NoEquilibrium(String),
    Other(String),
}

impl Failure {
    pub(super) fn why(&self) -> &str {
        match self {
            Failure::NoEquilibrium(w) | Failure::Other(w) => w,
        }
    }
}

/// How a walk ended.
pub(super) enum End {
    /// lambda fell below [`ZERO`] of the first multiplier.
    Zero,
    /// The steps ran out.
    StepsOut,
    /// The mechanism stopped moving.
    Stopped,
    /// Every step past the last point failed, halved down to `smallest` \[m\], the last one
    /// tried (the shortest) for this reason; `proved`: the curve's abscissa on the last moved
    /// geometry of the walk that was proved to have no equilibrium, if any.
    Exhausted { smallest: f64, failure: Failure, proved: Option<f64> },
}

/// Follows the mechanism of `first` (a collapse of `model`'s limit analysis, signed as `path`
/// says) by finite steps (see the module's text): `first` with its curve filled (from (0,
/// lambda_0)), `displacements` the blocks' finite motion at its last point, `steps` and
/// `iterations`; and how the walk ended.
pub(super) fn walk(
    model: &Model,
    first: Results,
    opts: &LimitOptions,
    follow: &FollowOptions,
    path: &Path,
    monitor: &mut dyn FnMut(&LimitProgress) -> bool,
) -> Result<(Results, End)> {
    let mut res = first;
    let nb = model.n_blocks();
    let step = path.step;
    let lambda0 = res.collapse_multiplier;
    res.curve_displacement = vec![0.0];
    res.curve_multiplier = vec![lambda0];
    let mut total = vec![[0.0; 3]; nb];
    let mut current = model.clone();
    let mut mechanism = res.mechanism.clone();
    let mut iterations = res.iterations;
    let mut fraction = 1.0;
    let mut steps = 0;
    let mut proved = None;
    let end = loop {
        if steps >= follow.max_steps {
            break End::StepsOut;
        }
        let Some(mut motion) = step_motion(&current, &mechanism, fraction * step) else {
            break End::Stopped;
        };
        close_contacts(&current, &mechanism, &mut motion);
        // the full step's gap: the contacts a longer step left open by up to it are kept
        let next = match current.moved(&motion, GAP * step) {
            Ok(m) => Ok(m),
            Err(e @ Error::Input { .. }) => Err(Failure::Other(format!("moved blocks were refused: {e}"))),
            Err(e) => return Err(e),
        };
        let analysed = match next {
            Ok(next) => match super::analyse(&next, opts, monitor, path.signed) {
                Ok(r) => Ok((next, r)),
                Err(e @ Error::Input { .. }) => Err(Failure::Other(format!("moved blocks were refused: {e}"))),
                Err(e) => return Err(e),
            },
            Err(why) => Err(why),
        };
        let outcome = match analysed {
            Ok((next, r)) => {
                iterations += r.iterations;
                let why = format!("limit analysis ended {}: {}", r.status.as_str(), r.error.clone().unwrap_or_default());
                match (r.status, path.held) {
                    (Status::Collapse, _) => Ok((next, r)),
                    // no equilibrium: an infeasible program (signed, lambda's sign is no failure; unsigned,
                    // also a multiplier below zero, which only a signed walk would read as a proof)
                    (Status::NoEquilibrium, _) => Err(Failure::NoEquilibrium(why)),
                    (_, Some(held)) => Err(stands(&next, held, opts, monitor, why)?),
                    _ => Err(Failure::Other(why)),
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
                res.curve_displacement.push((path.along)(&total));
                res.curve_multiplier.push(r.collapse_multiplier);
                if path.to_zero && r.collapse_multiplier <= ZERO * lambda0 {
                    break End::Zero;
                }
                current = next;
                mechanism = r.mechanism;
                fraction = (2.0 * fraction).min(1.0);
            }
            // no equilibrium, or blocks that would meet, within this step: it is halved until
            // the last point is within a 2^-HALVINGS fraction of the step of where that begins
            Err(failure) => {
                if let Failure::NoEquilibrium(_) = failure {
                    let tried: Vec<[f64; 3]> = total.iter().zip(&motion).map(|(t, m)| [t[0] + m[0], t[1] + m[1], t[2] + m[2]]).collect();
                    proved = Some((path.along)(&tried));
                }
                if fraction < 0.5f64.powi(HALVINGS as i32) {
                    break End::Exhausted { smallest: fraction * step, failure, proved };
                }
                fraction *= 0.5;
            }
        }
    };
    res.displacements = total;
    res.steps = steps;
    res.iterations = iterations;
    Ok((res, end))
}

/// Why the program of a moved wall (`model`, its support movement's dof `held` free) failed
/// (`why`: it did not converge, or not within the tolerance): the same wall with the support
/// held is asked whether it stands under its own weight ([`Model::with_live_along_gravity`]:
/// a program whose every multiple of the weight is carried if it stands, and whose optimum is -1,
/// no load at all, if not; well posed where the movement's program is infeasible by a hair and
/// its interior point stalls). A wall of dry joints that does not stand has no equilibrium at
/// any force on the support ([`Failure::NoEquilibrium`]); otherwise, or with joints of strength
/// (whose equilibria do not scale with the weight), the failure proves nothing.
fn stands(model: &Model, held: (usize, usize), opts: &LimitOptions, monitor: &mut dyn FnMut(&LimitProgress) -> bool, why: String) -> Result<Failure> {
    if model.laws_are_strong() {
        return Ok(Failure::Other(why));
    }
    let mut fixed = model.clone();
    fixed.fix(held.0, held.1, 0.0)?;
    let r = limit_analysis_with(&fixed.with_live_along_gravity(), opts, monitor)?;
    Ok(match r.status {
        Status::NoEquilibrium => Failure::NoEquilibrium(format!(
            "{why}; with the support held there, the wall does not stand under its own weight (limit analysis of its weight: no equilibrium)"
        )),
        s => Failure::Other(format!("{why}; with the support held there, limit analysis of the wall's weight ends {}", s.as_str())),
    })
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
