//! Limit analysis along a mechanism: the large-displacement capacity curve lambda(d). From the
//! collapse mechanism the blocks are moved by a finite step of it (in the plane each block turned
//! exactly about its instantaneous centre, in 3D by the screw motion of its velocities: turned
//! about its instantaneous axis and slid along it), the interfaces are found again where the
//! blocks now touch (in the plane along edges or at points: [`Model::moved`]; in 3D over
//! polygons, along edges or at points: [`Model3::moved`]), and the limit analysis is solved
//! again on the moved geometry, its mechanism giving the next step, until no equilibrium remains
//! (lambda has reached zero) or the steps run out. A step that fails is halved: the curve's end
//! is found within a small fraction of a step.
//!
//! The loop is written once (`follow_with`) over what differs between the dimensions ([`Followed`]:
//! the analysis, a step of the mechanism, the moved model, the control displacement); `plane`
//! and `space` hold each dimension's step.

use super::{limit_analysis_3d_with, limit_analysis_with, LimitOptions, LimitProgress};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::results::{Results, Status};
use crate::space::Model3;
use std::time::Instant;

mod plane;
mod space;

/// What limit analysis along a mechanism asks of a model, in either dimension.
pub(super) trait Followed: Clone {
    /// A block's motion, or its velocity: (u1, u2, phi) in the plane, (u1, u2, u3, r1, r2, r3)
    /// in 3D (the centroid's displacement, then the rotation vector: the angle about the axis).
    type Motion: Copy + Default;
    /// The limit analysis of the model, lambda of either sign when `signed` (a force on a
    /// moving support: the plane's only).
    fn analyse(&self, opts: &LimitOptions, monitor: &mut dyn FnMut(&LimitProgress) -> bool, signed: bool) -> Result<Results<Self::Motion>>;
    /// Why a moved model's program failed (`why`), with a support movement's dof `held` (see
    /// [`stands`]; the plane's only).
    fn stands(&self, held: (usize, usize), opts: &LimitOptions, monitor: &mut dyn FnMut(&LimitProgress) -> bool, why: String) -> Result<Failure>;
    /// The model's size \[m\].
    fn extent(&self) -> f64;
    /// The finite motion of each block over one step of `mechanism` (block velocities, any
    /// scale) whose largest vertex displacement is `length` \[m\], the contacts the mechanism
    /// keeps closed kept closed; None where nothing moves.
    fn step(&self, mechanism: &[Self::Motion], length: f64) -> Option<Vec<Self::Motion>>;
    /// The model on its blocks moved by `motion`, its contacts found again within `gap` \[m\].
    fn moved_by(&self, motion: &[Self::Motion], gap: f64) -> Result<Self>;
    /// The motion `total` followed by `step`.
    fn compose(total: Self::Motion, step: Self::Motion) -> Self::Motion;
    /// The displacement the curve follows of a block moved by `motion`: its centroid's along
    /// the horizontal direction of the model's live load \[m\].
    fn horizontal(&self, motion: Self::Motion) -> f64;
}

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

/// Relative velocities at a contact point below this fraction of the mechanism's largest keep
/// it closed (normal) or stuck (tangential).
const CLOSED: f64 = 1e-6;

/// Sweeps of the projection at most, and the fraction of the contact tolerance it stops at.
const SWEEPS: usize = 200;

/// The largest `max_steps` accepted.
pub const MAX_FOLLOW_STEPS: usize = 100_000;

/// Limit analysis of `model`, a wall in the plane, then its mechanism followed by finite steps
/// (see the module's text): the result is the first analysis's (the collapse multiplier, the mechanism and the
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
    follow_with(model, opts, follow, monitor)
}

/// [`follow_mechanism`] in 3D: the limit analysis of `model` ([`limit_analysis_3d_with`]), its
/// mechanism followed by finite steps, each block moved by the screw motion of its velocities
/// (the exact rotation about its instantaneous axis, and the slide along it: a block turning
/// about a hinge edge turns exactly about it), the contacts found again ([`Model3::moved`]: over
/// polygons, along edges, at points). The same steps, halvings, ends and notes as in the plane;
/// `curve_displacement` is the control block's displacement along the live load's direction in
/// plan, `displacements` the blocks' finite motion at the curve's last point (u1, u2, u3 of the
/// centre of mass \[m\], then the rotation vector r1, r2, r3 \[rad\]: the angle about its
/// axis).
pub fn follow_mechanism_3d(
    model: &Model3,
    opts: &LimitOptions,
    follow: &FollowOptions,
    monitor: &mut dyn FnMut(&LimitProgress) -> bool,
) -> Result<Results<[f64; 6]>> {
    follow_with(model, opts, follow, monitor)
}

/// [`follow_mechanism`] in either dimension: the walk along the collapse mechanism down to
/// lambda = 0, with its note where it stops short.
fn follow_with<M: Followed>(
    model: &M,
    opts: &LimitOptions,
    follow: &FollowOptions,
    monitor: &mut dyn FnMut(&LimitProgress) -> bool,
) -> Result<Results<M::Motion>> {
    check(follow)?;
    let start = Instant::now();
    let res = model.analyse(opts, monitor, false)?;
    if res.status != Status::Collapse {
        return Ok(res);
    }
    let control = res.control_block;
    let along = move |t: &[M::Motion]| model.horizontal(t[control]);
    let step = if follow.step > 0.0 { follow.step } else { model.extent() / 200.0 };
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
pub(super) struct Path<'a, V> {
    pub(super) signed: bool,
    pub(super) along: &'a dyn Fn(&[V]) -> f64,
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
pub(super) fn walk<M: Followed>(
    model: &M,
    first: Results<M::Motion>,
    opts: &LimitOptions,
    follow: &FollowOptions,
    path: &Path<M::Motion>,
    monitor: &mut dyn FnMut(&LimitProgress) -> bool,
) -> Result<(Results<M::Motion>, End)> {
    let mut res = first;
    let step = path.step;
    let lambda0 = res.collapse_multiplier;
    res.curve_displacement = vec![0.0];
    res.curve_multiplier = vec![lambda0];
    let mut total = vec![M::Motion::default(); res.mechanism.len()];
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
        let Some(motion) = current.step(&mechanism, fraction * step) else {
            break End::Stopped;
        };
        // the full step's gap: the contacts a longer step left open by up to it are kept
        let next = match current.moved_by(&motion, GAP * step) {
            Ok(m) => Ok(m),
            Err(e @ Error::Input { .. }) => Err(Failure::Other(format!("moved blocks were refused: {e}"))),
            Err(e) => return Err(e),
        };
        let analysed = match next {
            Ok(next) => match next.analyse(opts, monitor, path.signed) {
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
                    (_, Some(held)) => Err(next.stands(held, opts, monitor, why)?),
                    _ => Err(Failure::Other(why)),
                }
            }
            Err(why) => Err(why),
        };
        match outcome {
            Ok((next, r)) => {
                steps += 1;
                for (t, m) in total.iter_mut().zip(&motion) {
                    *t = M::compose(*t, *m);
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
                    let tried: Vec<M::Motion> = total.iter().zip(&motion).map(|(t, m)| M::compose(*t, *m)).collect();
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

impl Followed for Model {
    type Motion = [f64; 3];
    fn analyse(&self, opts: &LimitOptions, monitor: &mut dyn FnMut(&LimitProgress) -> bool, signed: bool) -> Result<Results> {
        super::analyse(self, opts, monitor, signed)
    }
    fn stands(&self, held: (usize, usize), opts: &LimitOptions, monitor: &mut dyn FnMut(&LimitProgress) -> bool, why: String) -> Result<Failure> {
        stands(self, held, opts, monitor, why)
    }
    fn extent(&self) -> f64 {
        self.size()
    }
    fn step(&self, mechanism: &[[f64; 3]], length: f64) -> Option<Vec<[f64; 3]>> {
        let mut motion = plane::step_motion(self, mechanism, length)?;
        plane::close_contacts(self, mechanism, &mut motion);
        Some(motion)
    }
    fn moved_by(&self, motion: &[[f64; 3]], gap: f64) -> Result<Model> {
        self.moved(motion, gap)
    }
    fn compose(total: [f64; 3], step: [f64; 3]) -> [f64; 3] {
        [total[0] + step[0], total[1] + step[1], total[2] + step[2]]
    }
    fn horizontal(&self, motion: [f64; 3]) -> f64 {
        let h = Model::horizontal(self);
        motion[0] * h[0] + motion[1] * h[1]
    }
}

impl Followed for Model3 {
    type Motion = [f64; 6];
    fn analyse(&self, opts: &LimitOptions, monitor: &mut dyn FnMut(&LimitProgress) -> bool, _signed: bool) -> Result<Results<[f64; 6]>> {
        // a support movement is the plane's: no signed program in 3D
        limit_analysis_3d_with(self, opts, monitor)
    }
    fn stands(&self, _held: (usize, usize), _opts: &LimitOptions, _monitor: &mut dyn FnMut(&LimitProgress) -> bool, why: String) -> Result<Failure> {
        Ok(Failure::Other(why))
    }
    fn extent(&self) -> f64 {
        self.size()
    }
    fn step(&self, mechanism: &[[f64; 6]], length: f64) -> Option<Vec<[f64; 6]>> {
        let mut motion = space::step_motion(self, mechanism, length)?;
        space::close_contacts(self, mechanism, &mut motion);
        Some(motion)
    }
    fn moved_by(&self, motion: &[[f64; 6]], gap: f64) -> Result<Model3> {
        self.moved(motion, gap)
    }
    fn compose(total: [f64; 6], step: [f64; 6]) -> [f64; 6] {
        space::compose(total, step)
    }
    fn horizontal(&self, motion: [f64; 6]) -> f64 {
        let h = Model3::horizontal(self);
        motion[0] * h[0] + motion[1] * h[1]
    }
}
