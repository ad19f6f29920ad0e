//! Displacement control: the control block driven step by step through the peak and after
//! it, across snap-backs by a jump that the explicit relaxation finds.

use super::*;

impl<'a, 'm> Solver<'a, 'm> {
    /// Whether some joint has cohesion or tensile strength: it can lose strength suddenly, and
    /// the equilibrium path can snap back.
    pub(super) fn can_lose_strength(&self) -> bool {
        (0..self.model.interfaces().len()).any(|k| {
            let l = self.model.law(k);
            l.cohesion > 0.0 || l.tensile_strength > 0.0
        })
    }

    /// Crosses a snap-back: the equilibrium at control displacement `target` that the damped
    /// motion of the wall reaches from the converged state, refined by Newton. On success `u`,
    /// `lambda` and `trial` hold it.
    pub(super) fn jump(&mut self, target: f64) -> Result<(), Error> {
        let cd = self.control_dof;
        let (u, states, lam) =
            crate::explicit::relax_at_displacement(self.model, &self.u, &self.committed, cd, target)?;
        let saved = self.committed.clone();
        self.u.copy_from_slice(&u);
        self.lambda = lam;
        self.committed.copy_from_slice(&states);
        match self.newton_disp() {
            Ok(_) => Ok(()),
            Err(e) => {
                self.committed.copy_from_slice(&saved);
                Err(e)
            }
        }
    }

    pub(super) fn displacement_control(
        &mut self,
        max_disp: f64,
    ) -> Outcome {
        if let Err(e) = self.dead_state() {
            return (Status::failure(&e), Some(e));
        }
        let cd = self.control_dof;
        let u_start = self.u[cd];
        let mut max_disp = max_disp;
        let mut target = u_start + max_disp;
        let mut base_step = max_disp / self.opts.steps as f64;
        let mut step = base_step;
        let mut min_step = base_step.abs() / 4096.0;
        let mut u_conv = self.u.clone();
        let mut lam_conv = self.lambda;
        let mut k0: Option<f64> = None; // initial stiffness d lambda / d u
        let mut k_last = f64::NAN;
        let mut streak = 0;
        let mut last: Option<(f64, f64)> = None; // previous step and the lambda before it
        loop {
            while (target - u_conv[cd]) * max_disp.signum() > 1e-12 * max_disp.abs() {
                let remaining = target - u_conv[cd];
                let h = if step.abs() > remaining.abs() {
                    remaining
                } else {
                    step
                };
                // predictor: the previous increment, scaled to this step (exact on a plateau)
                if let Some((h_prev, lam_prev)) = last {
                    let r = h / h_prev;
                    for (d, e) in self.eq.iter().enumerate() {
                        if e.is_some() {
                            self.u[d] = u_conv[d] + r * (u_conv[d] - self.u_prev[d]);
                        }
                    }
                    self.lambda = lam_conv + r * (lam_conv - lam_prev);
                }
                self.u[cd] = u_conv[cd] + h;
                let jumped = match self.newton_disp() {
                    Ok(_) => false,
                    Err(Error::Interrupted) => return (Status::Interrupted, Some(Error::Interrupted)),
                    Err(e) => {
                        self.u.copy_from_slice(&u_conv);
                        self.lambda = lam_conv;
                        streak = 0;
                        step *= 0.5;
                        if step.abs() >= min_step {
                            continue;
                        }
                        // a snap-back: no equilibrium near the converged state at the next
                        // displacement; follow the wall's jump by dynamic relaxation, then refine.
                        // Only joints with cohesion or tensile strength can lose strength suddenly;
                        // in a dry wall the failure is Newton's, and reported.
                        let next = if base_step.abs() < remaining.abs() { base_step } else { remaining };
                        match self.can_lose_strength().then(|| self.jump(u_conv[cd] + next)) {
                            Some(Ok(())) => true,
                            Some(Err(Error::Interrupted)) => {
                                return (Status::Interrupted, Some(Error::Interrupted))
                            }
                            _ => {
                                self.u.copy_from_slice(&u_conv);
                                self.lambda = lam_conv;
                                self.evaluate();
                                return (Status::failure(&e), Some(e));
                            }
                        }
                    }
                };
                if jumped {
                    // a jump is no increment to extrapolate, nor a slope
                    last = None;
                    step = base_step;
                } else {
                    last = Some((h, lam_conv));
                    let k = (self.lambda - lam_conv) / h;
                    k0.get_or_insert(k);
                    k_last = k;
                    // grow back only after a run of successes: on a plateau a step that has just
                    // failed tends to fail again
                    streak += 1;
                    if step.abs() < base_step.abs() && streak >= 4 {
                        step *= 2.0;
                        streak = 0;
                    }
                }
                self.u_prev.copy_from_slice(&u_conv);
                u_conv.copy_from_slice(&self.u);
                lam_conv = self.lambda;
                // going on until collapse, the path's length is not known
                let frac = if self.opts.until_collapse { f64::NAN } else { (u_conv[cd] - u_start) / max_disp };
                if let Err(e) = self.commit(frac) {
                    return (Status::failure(&e), Some(e));
                }
            }
            self.evaluate();
            let peak = crate::results::peak(&self.curve_l);
            let softened = lam_conv.abs() < peak.abs() * (1.0 - 1e-3);
            let flat = match k0 {
                Some(k0) if k0 != 0.0 => (k_last / k0).abs() < 1e-3,
                _ => false,
            };
            if softened || flat {
                return (Status::Collapse, None);
            }
            if !self.opts.until_collapse {
                return (Status::Completed, None);
            }
            // lambda still rises: go on by as much again, up to the small-displacement limit
            let limit = 0.1 * self.model.size();
            if 2.0 * max_disp.abs() > limit {
                return (
                    Status::DisplacementLimit,
                    Some(Error::Convergence(format!(
                        "the control block moved {:.3e} m, near the small-displacement limit ({limit:.3e} m, a tenth of the wall's size), with lambda = {lam_conv:.6} still rising: not a collapse",
                        max_disp.abs()
                    ))),
                );
            }
            max_disp *= 2.0;
            target = u_start + max_disp;
            base_step *= 2.0;
            step = base_step;
            min_step = base_step.abs() / 4096.0;
        }
    }
}
