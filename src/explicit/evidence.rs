//! The explicit solver's collapse checked against limit analysis, whose multiplier is exact for
//! dry associative joints.

use super::*;

/// How far above the limit analysis's multiplier, relative to it, a settled level may lie
/// whatever the bracket's tolerance: a level counts as settled at an unbalanced ratio of 1e-5,
/// and the limit analysis solves to 1e-8 (wall 1 at tolerance 1e-6 settles at 0.642889 against
/// 0.642859, 4.6e-5 above).
const SETTLED_ABOVE: f64 = 1e-4;

/// Checks an explicit collapse of a wall of associative dry joints against limit analysis,
/// whose multiplier is then exact (as the static solver does): under load control, a collapse
/// more than [`COLLAPSE_EVIDENCE`](crate::static_solver::COLLAPSE_EVIDENCE) `tolerance` below it
/// is `Stalled` (under displacement control the peak is the stages' sample of the curve, as low
/// as they are coarse); one more than `tolerance` (at least [`SETTLED_ABOVE`]) above it is `Failed` (a level was judged settled that is
/// not an equilibrium: the unbalanced forces of one small block can be too small against the
/// wall's to be seen). One above it by less is no equilibrium either: the levels above the exact
/// multiplier are dropped ([`below_exact`]) and the collapse is the highest level at or below it,
/// `Stalled` only if more than [`SETTLED_ABOVE`] (at least the above) below it, the resolution of
/// the levels' settling. The limit analysis's certificate is kept as the evidence.
pub(super) fn check_collapse(model: &Model, opts: &ExplicitOptions, res: Results, monitor: &mut dyn FnMut(&Progress) -> bool) -> Result<Results, Error> {
    let reversed = matches!(opts.control, Control::Displacement { max_displacement } if max_displacement < 0.0);
    let flipped;
    let model = if reversed {
        flipped = model.with_live_reversed();
        &flipped
    } else {
        model
    };
    let last = Progress { step: res.iterations, multiplier: res.last_equilibrium, displacement: f64::NAN, fraction: f64::NAN, poll: true, time: f64::NAN };
    let mut polled = Instant::now();
    let lp = crate::limit::limit_analysis_with(model, &crate::limit::LimitOptions::default(), &mut |_| {
        if polled.elapsed().as_secs_f64() < 0.1 {
            return true;
        }
        polled = Instant::now();
        monitor(&last)
    })?;
    Ok(judge(opts, res, lp))
}

/// The explicit collapse `res` judged against the limit analysis `lp` of the same model (see
/// [`check_collapse`]): either dimension (in 3D limit analysis takes Coulomb's cone itself, as
/// the explicit solver does, and is exact as in the plane).
pub(super) fn judge<V: Clone>(opts: &ExplicitOptions, mut res: Results<V>, lp: Results<V>) -> Results<V> {
    if lp.status != Status::Collapse {
        return res;
    }
    let exact = lp.collapse_multiplier;
    // levels dropped as above the exact multiplier: the bracket is pinned no closer than a level's settling
    let mut below = crate::static_solver::COLLAPSE_EVIDENCE * opts.tolerance;
    let above = opts.tolerance.max(SETTLED_ABOVE);
    if opts.control == Control::Load && res.collapse_multiplier > exact && (res.collapse_multiplier - exact) <= above * exact {
        below = below.max(SETTLED_ABOVE);
        below_exact(&mut res, exact, below);
    }
    let found = res.collapse_multiplier.abs();
    let gap = (found - exact) / exact;
    let what = format!("the collapse multiplier of limit analysis, {exact:.6} (exact for these associative dry joints)");
    let message = if gap < -below && opts.control == Control::Load {
        res.status = Status::Stalled;
        format!("the explicit solver's collapse at lambda = {found:.6} is {:.2}% below {what}: not a collapse", -100.0 * gap)
    } else if gap > above {
        res.status = Status::Failed;
        format!("the explicit solver settled at lambda = {found:.6}, {:.2}% above {what}: a level it judged settled is not an equilibrium (a small block's unbalance is too small against the wall's forces to be seen)", 100.0 * gap)
    } else {
        res.certificate = lp.certificate;
        return res;
    };
    res.error = Some(Error::Convergence(message).to_string());
    res.collapse_multiplier = f64::NAN;
    // the bracket is one on a collapse, which this is not
    res.bracket = None;
    res.certificate = lp.certificate;
    res
}

/// Load control whose highest settled levels lie above the exact multiplier `exact`, by less
/// than a level's settling accuracy: those levels are no equilibrium (none exists above it),
/// however small their unbalance. The curve ends at the highest level at or below `exact`, the
/// collapse multiplier, and the bracket's upper end is the lowest level dropped (or the level
/// that ran away, if lower); the displacements and forces stay those of the last level run. Only
/// when that level lies within `resolution` (relative) of `exact`: a level far below (the load
/// steps were coarse there) would make a collapse of a number the run did not pin, and the
/// result is then left as it is (within the tolerance above `exact`, as the check accepts).
fn below_exact<V>(res: &mut Results<V>, exact: f64, resolution: f64) {
    let keep = res.curve_multiplier.iter().take_while(|&&l| l <= exact).count();
    if keep == 0 || keep == res.curve_multiplier.len() || res.curve_multiplier[keep - 1] < exact * (1.0 - resolution) {
        return;
    }
    let dropped = res.curve_multiplier[keep];
    res.curve_multiplier.truncate(keep);
    res.curve_displacement.truncate(keep);
    res.steps = keep;
    let lower = res.curve_multiplier[keep - 1];
    res.collapse_multiplier = lower;
    res.last_equilibrium = lower;
    let upper = res.bracket.map_or(dropped, |b| b[1].min(dropped));
    res.bracket = Some([lower, upper]);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Rect;
    use crate::model::ModelSpec;

    #[test]
    fn levels_above_the_exact_multiplier_are_dropped() {
        // a block of 0.2 x 0.6 m rocks at lambda = 1/3; its explicit curve, with the exact multiplier put
        // between its last two levels: the last level is then no equilibrium
        let model = Model::new(ModelSpec { blocks: vec![Rect::new(0.0, 0.0, 0.2, 0.6).into()], ..ModelSpec::default() }).unwrap();
        let mut res = super::super::solve(&model, &ExplicitOptions { threads: 1, ..ExplicitOptions::default() }).unwrap();
        assert_eq!(res.status, Status::Collapse);
        let n = res.curve_multiplier.len();
        let [low, high] = res.bracket.unwrap();
        assert_eq!(low, res.collapse_multiplier);
        assert_eq!(low, res.curve_multiplier[n - 1]);
        assert!(high > low);
        let (below, last) = (res.curve_multiplier[n - 2], res.curve_multiplier[n - 1]);
        let exact = 0.5 * (below + last);
        let mut far = res.clone();
        below_exact(&mut far, exact, 1e-12); // the level below lies farther than that: nothing changes
        assert_eq!(far, res);
        below_exact(&mut res, exact, 0.5);
        assert_eq!(res.collapse_multiplier, below);
        assert_eq!(res.last_equilibrium, below);
        assert_eq!(res.curve_multiplier.len(), n - 1);
        assert_eq!(res.curve_displacement.len(), n - 1);
        assert_eq!(res.bracket, Some([below, last.min(high)]));
        assert!(res.collapse_multiplier <= exact);
    }
}
