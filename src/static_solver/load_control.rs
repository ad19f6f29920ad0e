//! Load control: lambda raised until collapse along the live load's work, and the check of a
//! collapse against limit analysis.

use super::*;

impl<'a, 'm> Solver<'a, 'm> {
    /// Load control: lambda rises until collapse. The path is followed in steps of the live
    /// load's work on the displacements (an arc length that any collapse mechanism of positive
    /// multiplier increases), with lambda unknown: at a limit point the tangent is singular but
    /// the bordered system is not, so steps grow geometrically as the wall approaches its
    /// mechanism instead of being cut against it. Collapse is:
    /// - a plateau: the rise that the last step's slope would give over as much work again as
    ///   has been done is within the tolerance of lambda (exact on a perfectly plastic
    ///   mechanism, where the slope is zero; close on a wall whose joints open one after the
    ///   other, where lambda creeps up as the work grows), and Newton at a fixed lambda just
    ///   above it finds no equilibrium (where it finds one, the path goes on from there);
    /// - a peak: lambda falls after a step (the step that crossed it is refined until the rise
    ///   it could hide, at the slope before it, is within the tolerance), and there is no
    ///   equilibrium at a fixed lambda above it;
    /// - the same where no step converges on the path, however short, or the displacements
    ///   outgrow the small-displacement model.
    ///
    /// A step in which a joint breaks (loses cohesion and tensile strength at once) is refined
    /// the same way, so that the peak just before the break is found.
    ///
    /// The mechanism is the last increment (after a peak: from the peak to the next state).
    pub(super) fn load_control(&mut self) -> Outcome {
        if let Err(e) = self.dead_state() {
            return (Status::failure(&e), Some(e));
        }
        let mut path = match self.first_step() {
            Ok(path) => path,
            Err(outcome) => return outcome,
        };
        let max_attempts = 100 * self.opts.steps + 1000;
        for _ in 0..max_attempts {
            let floor = path.tol * path.best.lambda.abs().max(1e-3 * path.scale);
            // predictor: the last increment, scaled to this step (exact on a plateau)
            if let Some(p) = &path.prev {
                let r = path.ds / (path.conv.work - p.work);
                for (d, e) in self.eq.iter().enumerate() {
                    if e.is_some() {
                        self.u[d] = path.conv.u[d] + r * (path.conv.u[d] - p.u[d]);
                    }
                }
                self.lambda = path.conv.lambda + r * (path.conv.lambda - p.lambda);
            }
            let next = match self.newton_work(path.conv.work + path.ds) {
                Ok(iters) => self.converged_step(&mut path, iters, floor),
                Err(Error::Interrupted) => Next::Stop((Status::Interrupted, Some(Error::Interrupted))),
                Err(_) => self.failed_step(&mut path, floor),
            };
            if let Next::Stop(outcome) = next {
                return outcome;
            }
        }
        (
            Status::Failed,
            Some(Error::Convergence(format!(
                "no collapse after {max_attempts} steps"
            ))),
        )
    }

    /// The first step of load control, at a fixed lambda from the dead state (halved until it
    /// converges): its work sets the scale of the steps. The outcome where the wall stands
    /// under its dead loads and no more, or the step fails.
    fn first_step(&mut self) -> Result<Path, Outcome> {
        let scale = crate::analysis::lambda_scale(self.model);
        let tol = self.opts.tolerance;
        let dl0 = 4.0 * scale / self.opts.steps as f64;
        self.u_ref.copy_from_slice(&self.u);
        let dead = self.snap();
        self.dead = Some(self.snap());
        let k0 = match self.above(&dead, dl0, tol * 1e-3 * scale) {
            Ok(true) => {
                let w = self.work();
                if !(w > 0.0) {
                    return Err((
                        Status::Failed,
                        Some(Error::Convergence(format!(
                            "the live load does no work on the wall's displacements under lambda = {:.4e}",
                            self.lambda
                        ))),
                    ));
                }
                self.lambda / w
            }
            Ok(false) => {
                // the wall stands under its dead loads and no more
                self.evaluate();
                return Err((Status::Collapse, None));
            }
            Err(e) => return Err((Status::failure(&e), Some(e))),
        };
        if let Err(e) = self.commit(f64::NAN) {
            return Err((Status::failure(&e), Some(e)));
        }
        Ok(Path {
            ds: self.work(),
            prev: Some(dead),
            conv: self.snap(),
            best: self.snap(),
            k0,
            k_last: k0,
            k_best: k0,
            fails: 0,
            scale,
            tol,
            dl0,
        })
    }

    /// A step of the path converged (in `iters` iterations) to the state in `u`, `lambda`:
    /// refined if a joint broke in it or it crossed a peak, else committed; then the tests of
    /// collapse and of an unbounded path, and the next step's length.
    fn converged_step(&mut self, path: &mut Path, iters: usize, floor: f64) -> Next {
        let scale = path.scale;
        let (lam, w) = (self.lambda, self.work());
        let broke = self.trial.iter().zip(&self.committed).any(|(t, c)| t.broken && !c.broken);
        if broke && path.k_last.max(0.0) * path.ds > floor {
            self.restore(&path.conv);
            path.ds *= 0.25;
            return Next::Go;
        }
        if lam < path.best.lambda - 1e-12 * scale {
            if let Some(next) = self.past_peak(path, w, floor) {
                return next;
            }
        }
        let increment = self.u.iter().zip(&path.conv.u).map(|(a, b)| a - b).collect();
        if let Err(e) = self.commit(f64::NAN) {
            return Next::Stop((Status::failure(&e), Some(e)));
        }
        let last = std::mem::replace(&mut path.conv, self.snap());
        path.prev = Some(last);
        let prev = path.prev.as_ref().unwrap();
        path.k_last = (path.conv.lambda - prev.lambda) / (path.conv.work - prev.work);
        if path.conv.lambda >= path.best.lambda {
            path.best = self.snap();
            path.k_best = path.k_last;
        }
        if path.conv.lambda > crate::analysis::UNBOUNDED * scale {
            let e = Error::Convergence(crate::results::unbounded_message(path.conv.lambda));
            return Next::Stop((Status::Unbounded, Some(e)));
        }
        if path.k_last.max(0.0) * path.conv.work <= path.tol * path.conv.lambda.abs().max(1e-3 * scale) {
            // a plateau of the path need not be the collapse: the state of a wall at a fixed
            // lambda depends on its path, and an associative 5-block wall flows on its path at
            // a lambda where it stands when reached from a position 1e-9 m away. Two attempts
            // just above (10 and 5 times the tolerance); where one converges, the path goes on
            // from there.
            return match self.above(&path.conv, 10.0 * floor, 5.0 * floor) {
                Ok(true) => self.restart_path(path),
                Ok(false) => {
                    self.evaluate();
                    self.mechanism = Some(increment);
                    Next::Stop((Status::Collapse, None))
                }
                Err(e) => Next::Stop((Status::failure(&e), Some(e))),
            };
        }
        // longer steps while Newton finds them easy (a cap on the rise of lambda per step, as
        // the first step's, would take twice as many steps in the elastic range, where the
        // path is straight)
        if iters <= 4 && path.fails == 0 {
            path.ds *= 2.0;
        } else if iters > 10 {
            path.ds *= 0.5;
        }
        path.fails = path.fails.saturating_sub(1);
        Next::Go
    }

    /// The step ended below the largest lambda so far (at work `w`): the path is back at that
    /// state, and the step that crossed the peak is refined; where it is short enough, the
    /// peak is the collapse unless Newton finds an equilibrium at a fixed lambda above it.
    /// `None`: the equilibrium above was found and the step goes on as converged.
    fn past_peak(&mut self, path: &mut Path, w: f64, floor: f64) -> Option<Next> {
        let past = self.u.iter().zip(&path.best.u).map(|(a, b)| a - b).collect();
        let dw = w - path.best.work;
        self.restore(&path.best);
        self.curve_l.truncate(path.best.curve);
        self.curve_u.truncate(path.best.curve);
        self.steps = path.best.curve;
        path.conv = self.snap();
        path.prev = None;
        if path.k_best.max(0.0) * dw > floor {
            path.ds = 0.25 * dw;
            return Some(Next::Go);
        }
        match self.above(&path.conv, path.dl0, floor) {
            Ok(true) => None,
            Ok(false) => {
                self.mechanism = Some(past);
                self.evaluate();
                Some(Next::Stop((Status::Collapse, None)))
            }
            Err(e) => Some(Next::Stop((Status::failure(&e), Some(e)))),
        }
    }

    /// No equilibrium on the path a step on: the step is halved; once it is within the
    /// tolerance, there may still be an equilibrium above, off this path (the state of a wall
    /// at a fixed lambda depends on its path: non-associative joints can stall on it, and soft
    /// joints creep up to their plateau beyond the displacement limit on the path while they
    /// stand within it at a fixed lambda). Where there is none, the collapse, or the
    /// displacement limit if lambda was still rising.
    fn failed_step(&mut self, path: &mut Path, floor: f64) -> Next {
        let scale = path.scale;
        if self.u.iter().all(|v| v.is_finite()) {
            self.diverged = Some(self.u.iter().zip(&path.conv.u).map(|(a, b)| a - b).collect());
        }
        self.restore(&path.conv);
        path.ds *= 0.5;
        path.fails = 4;
        if path.k0 * path.ds > 0.1 * floor {
            return Next::Go;
        }
        match self.above(&path.conv, path.dl0, floor) {
            Ok(true) => self.restart_path(path),
            Ok(false) => {
                self.mechanism = self.diverged.take().or_else(|| {
                    path.prev.as_ref().map(|p| path.conv.u.iter().zip(&p.u).map(|(a, b)| a - b).collect())
                });
                self.evaluate();
                // a wall of soft joints can creep to the small-displacement limit with lambda
                // still rising: the path ends there, not at a collapse
                let conv = &path.conv;
                let rising = path.k_last.max(0.0) * conv.work > RISING * path.tol * conv.lambda.abs().max(1e-3 * scale);
                if rising && self.max_translation(&conv.u) > NEAR_LIMIT * self.u_limit {
                    return Next::Stop((
                        Status::DisplacementLimit,
                        Some(Error::Convergence(format!(
                            "the path reached the small-displacement limit ({:.3e} m of block translation) at lambda = {:.6} with lambda still rising: not a collapse",
                            self.u_limit, conv.lambda
                        ))),
                    ));
                }
                Next::Stop((Status::Collapse, None))
            }
            Err(e) => Next::Stop((Status::failure(&e), Some(e))),
        }
    }

    /// Makes the equilibrium that [`Solver::above`] found off the path, above `conv`, the
    /// path's new start: committed, the next step as long as the jump to it, no secant
    /// predictor (the jump is not a step of the path), and the largest lambda so far.
    fn restart_path(&mut self, path: &mut Path) -> Next {
        path.ds = self.work() - path.conv.work;
        path.prev = None;
        if let Err(e) = self.commit(f64::NAN) {
            return Next::Stop((Status::failure(&e), Some(e)));
        }
        path.conv = self.snap();
        path.best = self.snap();
        path.k_best = 0.0;
        Next::Go
    }

    /// The state to come back to.
    pub(super) fn snap(&self) -> Saved {
        Saved {
            u: self.u.clone(),
            committed: self.committed.clone(),
            lambda: self.lambda,
            work: self.work(),
            curve: self.curve_l.len(),
        }
    }

    /// Checks a load-control collapse of a wall of associative dry joints against limit
    /// analysis, whose multiplier is then exact. A load-control path that stopped converging
    /// more than half of [`COLLAPSE_EVIDENCE`] `tolerance` below it goes on ([`Solver::reach`]):
    /// Newton, or the pseudo-transient continuation where Newton cycles, at fixed multipliers up
    /// to it from the last converged state, in rises sized by the distance, then from the dead
    /// state (the equilibrium at a fixed lambda depends on the path: soft joints creep up to
    /// their plateau beyond the small-displacement limit on the path and stand within it at a
    /// fixed lambda). Reaching [`COLLAPSE_EVIDENCE`] `tolerance` below the exact value is the
    /// collapse; otherwise the status is `Stalled`, with both numbers. The limit analysis's result is returned as the evidence.
    pub(super) fn check_collapse(&mut self, outcome: Outcome) -> Result<(Outcome, Option<Results>), Error> {
        // a wall pushed towards -x (displacement control, negative max_displacement) is the
        // program of the reversed live load; its multipliers are negative on the curve
        let reversed = matches!(self.opts.control, Control::Displacement { max_displacement } if max_displacement < 0.0);
        let flipped;
        let model = if reversed {
            flipped = self.model.with_live_reversed();
            &flipped
        } else {
            self.model
        };
        let lp = self.limit_evidence(model)?;
        if lp.status != Status::Collapse {
            return Ok((outcome, None));
        }
        let exact = lp.collapse_multiplier;
        let band = exact * (1.0 - COLLAPSE_EVIDENCE * self.opts.tolerance);
        let found = match self.opts.control {
            Control::Load => self.curve_l.last().copied().unwrap_or(f64::NAN),
            Control::Displacement { .. } => crate::results::peak(&self.curve_l).abs(),
        };
        // load control goes on towards the exact value from half the band below it (the claim
        // stays the band: a path that cannot go on from inside it is still a collapse)
        let near = match self.opts.control {
            Control::Load => exact * (1.0 - 0.5 * COLLAPSE_EVIDENCE * self.opts.tolerance),
            Control::Displacement { .. } => band,
        };
        if found >= near {
            return Ok(((Status::Collapse, None), Some(lp)));
        }
        if let Control::Displacement { .. } = self.opts.control {
            // the path went through its peak: nothing to go on with at a fixed multiplier
            if outcome.0 == Status::DisplacementLimit {
                return Ok((outcome, Some(lp)));
            }
            let msg = format!(
                "the path peaked at |lambda| = {found:.6}, {:.2}% below the collapse multiplier of limit analysis, {exact:.6} (exact for these associative dry joints): not a collapse",
                100.0 * (exact - found) / exact
            );
            return Ok(((Status::Stalled, Some(Error::Convergence(msg))), Some(lp)));
        }
        // go on towards the exact value at fixed multipliers
        let target = exact * (1.0 - 0.25 * COLLAPSE_EVIDENCE * self.opts.tolerance);
        let reached = self.reach(found, target, near, exact)?.max(found);
        self.evaluate();
        if reached >= band {
            return Ok(((Status::Collapse, None), Some(lp)));
        }
        if outcome.0 == Status::DisplacementLimit {
            return Ok((outcome, Some(lp)));
        }
        let msg = format!(
            "Newton stopped converging at lambda = {reached:.6}, {:.2}% below the collapse multiplier of limit analysis, {exact:.6} (exact for these associative dry joints): not a collapse",
            100.0 * (exact - reached) / exact
        );
        Ok(((Status::Stalled, Some(Error::Convergence(msg))), Some(lp)))
    }

    /// Limit analysis of `model` (the solver's, or its mirror), polling the solver's monitor
    /// with the last converged step's figures.
    fn limit_evidence(&mut self, model: &Model) -> Result<Results, Error> {
        let mut polled = Instant::now();
        let last = Progress {
            step: self.steps,
            multiplier: self.lambda,
            displacement: self.u[self.control_dof],
            fraction: f64::NAN,
            poll: true,
            time: f64::NAN,
        };
        let (interrupted, monitor) = (&mut self.interrupted, &mut self.monitor);
        crate::limit::limit_analysis_with(model, &crate::limit::LimitOptions::default(), &mut |_| {
            if *interrupted {
                return false;
            }
            if polled.elapsed().as_secs_f64() < POLL_INTERVAL {
                return true;
            }
            polled = Instant::now();
            let go = monitor(&last);
            *interrupted |= !go;
            go
        })
    }

    /// Newton, and where it does not converge the pseudo-transient continuation, at fixed
    /// multipliers towards `target` (just under `exact`): from the last converged state at
    /// `found`, in rises sized by the distance to the target, each halved until it converges;
    /// then from the dead
    /// state, at the target and halfway down to `band`. The largest lambda reached in
    /// equilibrium (committed, the mechanism the last jump); below `band`, the state is back at
    /// the last converged one.
    fn reach(&mut self, found: f64, target: f64, band: f64, exact: f64) -> Result<f64, Error> {
        let floor = self.opts.tolerance * exact;
        let mut conv = self.snap();
        conv.lambda = found;
        let mut reached = found;
        // rises sized by the distance to the exact value: a quarter of it first, then twice
        // the last one that converged (the continuation's cost grows with the jump)
        let mut rise = REACH_FIRST * (target - found);
        for _ in 0..REACH_ATTEMPTS {
            if reached >= band || target - conv.lambda <= floor {
                break;
            }
            rise = rise.min(target - conv.lambda);
            let previous = conv.u.clone();
            if !self.above_relaxed(&conv, rise, floor)? {
                break;
            }
            rise = 2.0 * (self.lambda - conv.lambda);
            self.mechanism = Some(self.u.iter().zip(&previous).map(|(a, b)| a - b).collect());
            self.commit(f64::NAN)?;
            conv = self.snap();
            reached = conv.lambda;
        }
        if reached < band {
            if let Some(dead) = self.dead.take() {
                for lam in [target, 0.5 * (target + band)] {
                    self.restore(&dead);
                    self.lambda = lam;
                    match self.newton_load() {
                        Ok(_) => {
                            self.mechanism = Some(self.u.iter().zip(&conv.u).map(|(a, b)| a - b).collect());
                            self.commit(f64::NAN)?;
                            reached = lam;
                            break;
                        }
                        Err(Error::Interrupted) => return Err(Error::Interrupted),
                        Err(_) => {}
                    }
                }
                if reached < band {
                    self.restore(&conv);
                }
            }
        }
        Ok(reached)
    }

    pub(super) fn restore(&mut self, s: &Saved) {
        self.u.copy_from_slice(&s.u);
        self.committed.copy_from_slice(&s.committed);
        self.lambda = s.lambda;
    }

    /// As [`Solver::above`], with the pseudo-transient continuation ([`Solver::relax`]) at
    /// each lambda where Newton does not converge.
    fn above_relaxed(&mut self, from: &Saved, rise: f64, floor: f64) -> Result<bool, Error> {
        self.rise_from(from, rise, floor, true)
    }

    /// Newton at a fixed lambda above the state `from`, by `rise`, halved until it converges
    /// or is within `floor`. True if it converged (`u`, `lambda` and `trial` hold the result);
    /// false with `from` restored.
    pub(super) fn above(&mut self, from: &Saved, rise: f64, floor: f64) -> Result<bool, Error> {
        self.rise_from(from, rise, floor, false)
    }

    /// The rise of [`Solver::above`], with the continuation after each Newton that fails if
    /// `relax`.
    fn rise_from(&mut self, from: &Saved, rise: f64, floor: f64, relax: bool) -> Result<bool, Error> {
        let mut dl = rise;
        while dl > floor {
            self.restore(from);
            self.lambda = from.lambda + dl;
            match self.newton_load() {
                Ok(_) => return Ok(true),
                Err(Error::Interrupted) => return Err(Error::Interrupted),
                Err(_) => {}
            }
            if relax {
                self.restore(from);
                self.lambda = from.lambda + dl;
                if self.relax()? {
                    return Ok(true);
                }
            }
            dl *= 0.5;
        }
        self.restore(from);
        Ok(false)
    }
}

/// Load control's path: its last converged states, the largest lambda so far, the slopes
/// (lambda over the live load's work) and the length of the next step.
struct Path {
    /// the last converged state, the one before it (the secant predictor), the one of largest
    /// lambda
    conv: Saved,
    prev: Option<Saved>,
    best: Saved,
    /// the slopes of the first step, of the last one and of the step that reached `best`
    k0: f64,
    k_last: f64,
    k_best: f64,
    /// the next step's work, and the steps still to take at no more than its length after a
    /// failure
    ds: f64,
    fails: usize,
    /// the natural scale of lambda, the tolerance, the first step's rise of lambda
    scale: f64,
    tol: f64,
    dl0: f64,
}
