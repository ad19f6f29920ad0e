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
        let scale = self.lambda_scale();
        let max_lambda = 1e3 * scale;
        let tol = self.opts.tolerance;
        let dl0 = 4.0 * scale / self.opts.steps as f64;
        self.u_ref.copy_from_slice(&self.u);
        let dead = self.snap();
        self.dead = Some(self.snap());
        // the first step at fixed lambda (halved until it converges): its work sets the scale
        // of the steps
        let mut conv = dead;
        let k0 = match self.above(&conv, dl0, tol * 1e-3 * scale) {
            Ok(true) => {
                let w = self.work();
                if !(w > 0.0) {
                    return (
                        Status::Failed,
                        Some(Error::Convergence(format!(
                            "the live load does no work on the wall's displacements under lambda = {:.4e}",
                            self.lambda
                        ))),
                    );
                }
                self.lambda / w
            }
            Ok(false) => {
                // the wall stands under its dead loads and no more
                self.evaluate();
                return (Status::Collapse, None);
            }
            Err(e) => return (Status::failure(&e), Some(e)),
        };
        if let Err(e) = self.commit(f64::NAN) {
            return (Status::failure(&e), Some(e));
        }
        let mut ds = self.work();
        // the state before the last converged one (the secant predictor), the last converged
        // one, the one of largest lambda and the slope of the step that reached it
        let mut prev: Option<Saved> = Some(conv);
        conv = self.snap();
        let mut best = self.snap();
        let (mut k_last, mut k_best) = (k0, k0);
        let mut fails = 0usize;
        let max_attempts = 100 * self.opts.steps + 1000;
        for _ in 0..max_attempts {
            let floor = tol * best.lambda.abs().max(1e-3 * scale);
            // predictor: the last increment, scaled to this step (exact on a plateau)
            if let Some(p) = &prev {
                let r = ds / (conv.work - p.work);
                for (d, e) in self.eq.iter().enumerate() {
                    if e.is_some() {
                        self.u[d] = conv.u[d] + r * (conv.u[d] - p.u[d]);
                    }
                }
                self.lambda = conv.lambda + r * (conv.lambda - p.lambda);
            }
            match self.newton_work(conv.work + ds) {
                Ok(iters) => {
                    let (lam, w) = (self.lambda, self.work());
                    let broke = self.trial.iter().zip(&self.committed).any(|(t, c)| t.broken && !c.broken);
                    if broke && k_last.max(0.0) * ds > floor {
                        self.restore(&conv);
                        ds *= 0.25;
                        continue;
                    }
                    if lam < best.lambda - 1e-12 * scale {
                        // past a peak: refine the step that crossed it, or stop there
                        let past = self.u.iter().zip(&best.u).map(|(a, b)| a - b).collect();
                        let dw = w - best.work;
                        self.restore(&best);
                        self.curve_l.truncate(best.curve);
                        self.curve_u.truncate(best.curve);
                        self.steps = best.curve;
                        conv = self.snap();
                        prev = None;
                        if k_best.max(0.0) * dw > floor {
                            ds = 0.25 * dw;
                            continue;
                        }
                        match self.above(&conv, dl0, floor) {
                            Ok(true) => {}
                            Ok(false) => {
                                self.mechanism = Some(past);
                                self.evaluate();
                                return (Status::Collapse, None);
                            }
                            Err(e) => return (Status::failure(&e), Some(e)),
                        }
                    }
                    let increment = self.u.iter().zip(&conv.u).map(|(a, b)| a - b).collect();
                    if let Err(e) = self.commit(f64::NAN) {
                        return (Status::failure(&e), Some(e));
                    }
                    let last = std::mem::replace(&mut conv, self.snap());
                    prev = Some(last);
                    k_last = (conv.lambda - prev.as_ref().unwrap().lambda)
                        / (conv.work - prev.as_ref().unwrap().work);
                    if conv.lambda >= best.lambda {
                        best = self.snap();
                        k_best = k_last;
                    }
                    if conv.lambda > max_lambda {
                        let e = Error::Convergence(crate::results::unbounded_message(conv.lambda));
                        return (Status::Unbounded, Some(e));
                    }
                    if k_last.max(0.0) * conv.work <= tol * conv.lambda.abs().max(1e-3 * scale) {
                        // a plateau of the path need not be the collapse: the state of a wall at
                        // a fixed lambda depends on its path, and an associative 5-block wall
                        // flowed at 0.324285 on it while it stands at 0.329523 (displacement
                        // control, or load control from a position 1e-9 m away). Two attempts
                        // just above (10 and 5 times the tolerance) cost wall 1 13 iterations
                        // (90 -> 103); where one converges, the path goes on from there.
                        match self.above(&conv, 10.0 * floor, 5.0 * floor) {
                            Ok(true) => {
                                if let Err(e) = self.restart_path(&mut conv, &mut prev, &mut best, &mut k_best, &mut ds) {
                                    return (Status::failure(&e), Some(e));
                                }
                                continue;
                            }
                            Ok(false) => {
                                self.evaluate();
                                self.mechanism = Some(increment);
                                return (Status::Collapse, None);
                            }
                            Err(e) => return (Status::failure(&e), Some(e)),
                        }
                    }
                    // longer steps while Newton finds them easy (a cap on the rise of lambda per
                    // step, as the first step's, cost a wall of 33 blocks twice as many steps in
                    // its elastic range, where the path is straight)
                    if iters <= 4 && fails == 0 {
                        ds *= 2.0;
                    } else if iters > 10 {
                        ds *= 0.5;
                    }
                    fails = fails.saturating_sub(1);
                }
                Err(Error::Interrupted) => return (Status::Interrupted, Some(Error::Interrupted)),
                Err(_) => {
                    if self.u.iter().all(|v| v.is_finite()) {
                        self.diverged = Some(self.u.iter().zip(&conv.u).map(|(a, b)| a - b).collect());
                    }
                    self.restore(&conv);
                    ds *= 0.5;
                    fails = 4;
                    if k0 * ds > 0.1 * floor {
                        continue;
                    }
                    // no equilibrium on the path a step within the tolerance on (or none within
                    // the small-displacement limit). The state of a wall at a fixed lambda
                    // depends on its path, and there may be one above, off this path:
                    // - non-associative joints can stall on the path (8 blocks, psi = 0:
                    //   0.2593, against 0.318 found by the explicit solver and by longer steps);
                    // - wall 2 with soft joints (kN = kT = 1e8) creeps up to its plateau of
                    //   0.5800 on the path, dilating, beyond the displacement limit at 0.5730;
                    //   at a fixed lambda it is at 0.5800 within it.
                    match self.above(&conv, dl0, floor) {
                        Ok(true) => {
                            if let Err(e) = self.restart_path(&mut conv, &mut prev, &mut best, &mut k_best, &mut ds) {
                                return (Status::failure(&e), Some(e));
                            }
                        }
                        Ok(false) => {
                            self.mechanism = self.diverged.take().or_else(|| {
                                prev.as_ref().map(|p| conv.u.iter().zip(&p.u).map(|(a, b)| a - b).collect())
                            });
                            self.evaluate();
                            // a wall of soft joints can creep to the small-displacement limit
                            // with lambda still rising: the path ends there, not at a collapse
                            let rising = k_last.max(0.0) * conv.work > RISING * tol * conv.lambda.abs().max(1e-3 * scale);
                            if rising && self.max_translation(&conv.u) > NEAR_LIMIT * self.u_limit {
                                return (
                                    Status::DisplacementLimit,
                                    Some(Error::Convergence(format!(
                                        "the path reached the small-displacement limit ({:.3e} m of block translation) at lambda = {:.6} with lambda still rising: not a collapse",
                                        self.u_limit, conv.lambda
                                    ))),
                                );
                            }
                            return (Status::Collapse, None);
                        }
                        Err(e) => return (Status::failure(&e), Some(e)),
                    }
                }
            }
        }
        (
            Status::Failed,
            Some(Error::Convergence(format!(
                "no collapse after {max_attempts} steps"
            ))),
        )
    }

    /// Makes the equilibrium that [`Solver::above`] found off the path, above `conv`, the
    /// path's new start: committed, the next step as long as the jump to it, no secant
    /// predictor (the jump is not a step of the path), and the largest lambda so far.
    pub(super) fn restart_path(
        &mut self,
        conv: &mut Saved,
        prev: &mut Option<Saved>,
        best: &mut Saved,
        k_best: &mut f64,
        ds: &mut f64,
    ) -> Result<(), Error> {
        *ds = self.work() - conv.work;
        *prev = None;
        self.commit(f64::NAN)?;
        *conv = self.snap();
        *best = self.snap();
        *k_best = 0.0;
        Ok(())
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
    /// analysis, whose multiplier is then exact. A path that stopped converging more than
    /// [`COLLAPSE_EVIDENCE`] `tolerance` below it goes on: Newton at fixed multipliers up to it
    /// from the last converged state, each rise halved until it converges, then from the dead
    /// state (the equilibrium at a fixed lambda depends on the path: soft joints creep up to
    /// their plateau beyond the small-displacement limit on the path and stand within it at a
    /// fixed lambda). Reaching the band below the exact value is the collapse; otherwise the status is `Stalled`, with both
    /// numbers. The limit analysis's result is returned as the evidence.
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
        let lp = {
            let mut polled = Instant::now();
            let last = Progress {
                step: self.steps,
                multiplier: self.lambda,
                displacement: self.u[self.control_dof],
                fraction: f64::NAN,
                poll: true,
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
            })?
        };
        if lp.status != Status::Collapse {
            return Ok((outcome, None));
        }
        let exact = lp.collapse_multiplier;
        let band = exact * (1.0 - COLLAPSE_EVIDENCE * self.opts.tolerance);
        let found = match self.opts.control {
            Control::Load => self.curve_l.last().copied().unwrap_or(f64::NAN),
            Control::Displacement { .. } => crate::results::peak(&self.curve_l).abs(),
        };
        if found >= band {
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
        // go on towards the exact value at fixed multipliers, from the last converged state
        let target = exact * (1.0 - 0.5 * COLLAPSE_EVIDENCE * self.opts.tolerance);
        let floor = self.opts.tolerance * exact;
        let mut conv = self.snap();
        conv.lambda = found;
        let mut reached = found;
        for _ in 0..REACH_ATTEMPTS {
            if reached >= band || target - conv.lambda <= floor {
                break;
            }
            let previous = conv.u.clone();
            if !self.above(&conv, target - conv.lambda, floor)? {
                break;
            }
            self.mechanism = Some(self.u.iter().zip(&previous).map(|(a, b)| a - b).collect());
            self.commit(f64::NAN)?;
            conv = self.snap();
            reached = conv.lambda;
        }
        // and from the dead state, at the target and halfway down to the band
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

    pub(super) fn restore(&mut self, s: &Saved) {
        self.u.copy_from_slice(&s.u);
        self.committed.copy_from_slice(&s.committed);
        self.lambda = s.lambda;
    }

    /// Newton at a fixed lambda above the state `from`, by `rise`, halved until it converges
    /// or is within `floor`. True if it converged (`u`, `lambda` and `trial` hold the result);
    /// false with `from` restored.
    pub(super) fn above(&mut self, from: &Saved, rise: f64, floor: f64) -> Result<bool, Error> {
        let mut dl = rise;
        while dl > floor {
            self.restore(from);
            self.lambda = from.lambda + dl;
            match self.newton_load() {
                Ok(_) => return Ok(true),
                Err(Error::Interrupted) => return Err(Error::Interrupted),
                Err(_) => dl *= 0.5,
            }
        }
        self.restore(from);
        Ok(false)
    }
}
