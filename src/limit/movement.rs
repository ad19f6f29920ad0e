//! Limit analysis along a support's movement: how far a support may move (an arch's abutment
//! spreading, a pier settling) before the wall has no equilibrium.
//!
//! The moving support's dof along its movement is made free and a unit force along the
//! movement is its live load ([`Model::with_movement`]); lambda, of either sign, is the force
//! applied to the support, and in equilibrium the wall pushes the support along the movement
//! with `F = -lambda`. Maximising lambda finds the least F of every admissible state: the least
//! thrust of an arch on a spreading abutment. That least state is the one the wall takes as the
//! support moves: the program's dual is a mechanism in which the support moves along its
//! movement (the live load does work 1 on it), and by complementary slackness the optimal forces
//! are those of that mechanism (each hinge's force at its edge, each sliding joint's on its
//! Coulomb face); a state of larger F has a wall's force that does less work than the
//! mechanism's dissipation and weight take (the duality gap of a non-optimal point), so no
//! admissible state with the support moving has any other F. This is the minimum-thrust state
//! of Heyman and Ochsendorf, without the interior point changed: only lambda's sign is let go.
//!
//! The mechanism is then followed as [`super::follow_mechanism`] follows a collapse (finite
//! steps, blocks turned about their instantaneous centres, interfaces found again, a step that
//! fails halved), the support carried along its movement by the mechanism, F found again on
//! each moved geometry. The force does not fall to zero here: the walk ends where the moved
//! geometry has no equilibrium at any force on the support.

use super::follow::{check, walk, End, Path};
use super::{analyse, FollowOptions, LimitOptions, LimitProgress};
use crate::error::Result;
use crate::model::{Model, SupportMovement};
use crate::results::{Results, Status};
use std::time::Instant;

/// The default step of a support movement: the model's size over this. Finer than a collapse's
/// (over 200): on a semicircular arch of 20 voussoirs (R = 2 m, t/R = 0.15) the steps of a
/// two-hundredth drift from the three-hinge mechanism's path (its hinges at the springings touch
/// and the steps shrink to a 256th), which steps of a thousandth follow to the end.
const STEPS_ACROSS: f64 = 1000.0;

/// Limit analysis of `model` with `movement`'s support moving, followed along its mechanism to
/// where no equilibrium remains (see the module's text). The result is the first analysis's
/// (the mechanism, the forces and the certificate at delta = 0), where lambda is the force `F`
/// the wall exerts on the moving support along its movement \[N\] (the thrust of an arch on a
/// spreading abutment): `collapse_multiplier` F at delta = 0, the least of every admissible
/// state, `curve_displacement` the movement delta \[m\] (the support's displacement along its
/// direction) and `curve_multiplier` F on the moved geometry at each step, `last_equilibrium` F
/// at the curve's last point, `control_block` the support, `displacements` the blocks' finite
/// motion there and `steps` the steps taken.
///
/// The step (`follow.step`, the largest displacement of a vertex in one step) is the model's
/// size over 1000 when 0.
///
/// Status: `Collapse` where every step past the curve's last point failed, halved 30 times
/// (the end is found within 2^-30 of a step), and a moved geometry within one step beyond it
/// was proved to have no equilibrium at any force on the support (its program infeasible, by a
/// dual ray; or, where the interior point stalls on a program infeasible by a hair, the wall
/// with the support held there not standing under its own weight: [`Model::with_live_along_gravity`]):
/// the path of equilibria ends there, the wall falls if the support moves further.
/// `Completed` where the steps ran out first (`error` says so); `Failed` where the steps past
/// the last point failed with no such proof (a program that does not converge, blocks refused),
/// or the mechanism stopped moving: no evidence of a collapse (`error` says why). A first analysis
/// that is no collapse (joints with dilatancy below friction give an estimate; a wall that does
/// not stand at all has no equilibrium) is returned as it is, its lambda turned into F.
pub fn follow_movement(
    model: &Model,
    movement: &SupportMovement,
    opts: &LimitOptions,
    follow: &FollowOptions,
    monitor: &mut dyn FnMut(&LimitProgress) -> bool,
) -> Result<Results> {
    check(follow)?;
    let moving = model.with_movement(movement)?;
    let (block, dof) = movement.dof(model)?;
    let (axis, sign) = movement.direction.axis();
    let start = Instant::now();
    let first = analyse(&moving, opts, monitor, true)?;
    if first.status != Status::Collapse {
        return Ok(as_force(first));
    }
    let along = move |t: &[[f64; 3]]| sign * t[block][axis];
    let step = if follow.step > 0.0 { follow.step } else { model.size() / STEPS_ACROSS };
    let path = Path { signed: true, along: &along, to_zero: false, held: Some((block, dof % 3)), step };
    let (mut res, end) = walk(&moving, first, opts, follow, &path, monitor)?;
    res.control_block = block;
    res.last_equilibrium = res.curve_multiplier[res.steps];
    let reached = res.curve_displacement[res.steps];
    let (status, why) = match end {
        End::Exhausted { proved: Some(p), .. } if p - reached <= step => (Status::Collapse, None),
        End::Exhausted { smallest, failure, proved } => (
            Status::Failed,
            Some(format!(
                "every step past it, down to {smallest:.1e} m, failed, {}: no evidence of a collapse; on the last step, {}",
                match proved {
                    Some(p) => format!("the nearest moved geometry proved to have no equilibrium lying {:.3e} m further, beyond a step", p - reached),
                    None => "none proved to have no equilibrium".into(),
                },
                failure.why()
            )),
        ),
        End::StepsOut => (Status::Completed, Some(format!("the steps ran out (follow_steps = {}) with the wall still standing", follow.max_steps))),
        End::Stopped => (Status::Failed, Some("the mechanism has stopped moving".into())),
        End::Zero => unreachable!("a support movement's walk does not end at lambda = 0"),
    };
    res.status = status;
    res.error = why.map(|why| {
        format!(
            "the support's movement was followed {} steps, to {:.6e} m where the force on it is {:.6e} N: {why}",
            res.steps,
            res.curve_displacement[res.steps],
            -res.curve_multiplier[res.steps]
        )
    });
    if status != Status::Collapse {
        res.collapse_multiplier = f64::NAN;
    }
    let mut res = as_force(res);
    res.elapsed_s = start.elapsed().as_secs_f64();
    Ok(res)
}

/// The results of a support movement's program with lambda (the force applied to the support)
/// turned into the force the wall exerts on it, `-lambda`.
fn as_force(mut res: Results) -> Results {
    res.collapse_multiplier = -res.collapse_multiplier;
    res.last_equilibrium = -res.last_equilibrium;
    res.curve_multiplier.iter_mut().for_each(|l| *l = -*l);
    if let Some(c) = res.certificate.as_mut() {
        c.multiplier = -c.multiplier;
        c.upper_bound = -c.upper_bound;
    }
    res
}
