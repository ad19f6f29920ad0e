//! The explicit solver driving a support's movement: the support pushed slowly along its
//! movement by displacement control, the force on it measured, until the wall falls.

use super::quasi_static::{check_run_options, integrator, QuasiStatic};
use super::*;
use crate::model::SupportMovement;
use std::ops::ControlFlow;

/// A stage of a support's movement at which some block moves more than this fraction of the
/// model's size from where the drive left it has not settled: the wall is falling (as under the
/// dead loads, where a block moving 1% of the wall's size means it does not stand).
pub const FALL_FRACTION: f64 = 1e-2;

/// The explicit solver driving `movement`'s support by `opts.control`'s `max_displacement`
/// (\[m\], > 0, along the movement's direction) in `opts.steps` stages, each relaxed with the
/// support held at its target (the support stays held by the model; only the drive moves it):
/// lambda from the support's equation is the force applied to it, and the force the wall exerts
/// on it along the movement is `-lambda`. `opts.large_rotations` follows the equilibrium on the
/// moved geometry (needed for a support that moves by a fraction of the wall).
///
/// The wall falls at the first stage that does not settle: a block moves more than
/// [`FALL_FRACTION`] of the model's size from where the drive left it, or the unbalanced ratio
/// stays above `opts.unbalanced_ratio` within `opts.max_steps_per_level` time steps. The result:
/// `curve_displacement` the movement delta \[m\] (the support's displacement along its
/// direction) and `curve_multiplier` the force the wall exerts on the support along it \[N\] at
/// each stage that settled, from the dead state (delta = 0); `last_equilibrium` that force at
/// the last stage that settled; status `Collapse` where a stage did not settle, `bracket` then
/// the movement of the last stage that settled and of the first that did not (the wall falls
/// between them) and `collapse_multiplier` the force at the last that settled; `Completed`
/// where every stage settled (`error` says so); `control_block` the support.
pub fn solve_movement(model: &Model, movement: &SupportMovement, opts: &ExplicitOptions, monitor: &mut dyn FnMut(&Progress) -> bool) -> Result<Results, Error> {
    let Control::Displacement { max_displacement } = opts.control else {
        return Err(Error::input_at("analysis.control", "analysis.control must be \"displacement\" for a support's movement by the explicit solver (the support is driven)"));
    };
    if !(max_displacement > 0.0) {
        return Err(Error::input_at(
            "analysis.max_displacement",
            format!("analysis.max_displacement must be > 0 for a support's movement (how far the support moves along analysis.move_direction), got {max_displacement}"),
        ));
    }
    model.check_analysis_memory("an explicit analysis")?;
    model.check_strength_range()?;
    let start = Instant::now();
    let (block, dof) = movement.dof(model)?;
    let (axis, sign) = movement.direction.axis();
    // the live load a unit force on the support's dof, which stays held: the drive moves it
    let mut moving = model.with_movement(movement)?;
    moving.fix(block, axis, 0.0)?;
    check_run_options(&moving, opts)?;
    let (s, mut setting) = integrator(&moving, opts)?;
    setting.offset = axis;
    let mut run = QuasiStatic::new(s, setting, opts, block, start);
    let end = match run.settle_dead_loads(monitor) {
        ControlFlow::Break(end) => end,
        ControlFlow::Continue((dead_steps, _)) => run.movement_control(sign * max_displacement, dead_steps, FALL_FRACTION * moving.size(), monitor),
    };
    let mut res = run.finish(end);
    debug_assert_eq!(3 * res.control_block + axis, dof);
    let u0 = res.curve_displacement[0];
    res.curve_displacement.iter_mut().for_each(|u| *u = sign * (*u - u0));
    res.curve_multiplier.iter_mut().for_each(|l| *l = -*l);
    let last = *res.curve_multiplier.last().expect("the dead state starts the curve");
    res.last_equilibrium = last;
    res.bracket = None;
    if res.status == Status::Collapse {
        let reached = *res.curve_displacement.last().expect("the dead state starts the curve");
        res.bracket = Some([reached, reached + max_displacement / opts.steps as f64]);
        res.collapse_multiplier = last;
    } else {
        res.collapse_multiplier = f64::NAN;
    }
    Ok(res)
}
