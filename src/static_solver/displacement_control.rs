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

    /// Displacement control: the control dof driven to `max_disp` from the dead state in steps
    /// (cut where Newton fails, grown back after a run of successes), across snap-backs. Going
    /// on until collapse (`until_collapse`), a path that ends with lambda still rising goes on
    /// by as much again, up to the small-displacement limit.
    pub(super) fn displacement_control(&mut self, max_disp: f64) -> Outcome {
        if let Err(e) = self.dead_state() {
            return (Status::failure(&e), Some(e));
        }
        let mut path = Stretch::new(self.u.clone(), self.lambda, self.control_dof, max_disp, self.opts.steps);
        loop {
            while (path.target - path.u_conv[path.cd]) * path.max_disp.signum() > 1e-12 * path.max_disp.abs() {
                if let Next::Stop(outcome) = self.disp_step(&mut path) {
                    return outcome;
                }
            }
            self.evaluate();
            let peak = crate::results::peak(&self.curve_l);
            if crate::analysis::displacement_collapse(path.lam_conv, peak, path.k0.unwrap_or(0.0), path.k_last) {
                return (Status::Collapse, None);
            }
            if !self.opts.until_collapse {
                return (Status::Completed, None);
            }
            // lambda still rises: go on by as much again, up to the small-displacement limit
            let limit = 0.1 * self.model.size();
            if 2.0 * path.max_disp.abs() > limit {
                return (
                    Status::DisplacementLimit,
                    Some(Error::Convergence(format!(
                        "the control block moved {:.3e} m, near the small-displacement limit ({limit:.3e} m, a tenth of the wall's size), with lambda = {:.6} still rising: not a collapse",
                        path.max_disp.abs(), path.lam_conv
                    ))),
                );
            }
            path.extend();
        }
    }

    /// One step of displacement control towards the stretch's target: predicted from the last
    /// increment, solved by Newton, halved where it fails; below the smallest step, a jump
    /// across a snap-back (joints with strength only) or the end. A converged step is
    /// committed.
    fn disp_step(&mut self, path: &mut Stretch) -> Next {
        let cd = path.cd;
        let remaining = path.target - path.u_conv[cd];
        let h = if path.step.abs() > remaining.abs() { remaining } else { path.step };
        // predictor: the previous increment, scaled to this step (exact on a plateau)
        if let Some((h_prev, lam_prev)) = path.last {
            let r = h / h_prev;
            for (d, e) in self.eq.iter().enumerate() {
                if e.is_some() {
                    self.u[d] = path.u_conv[d] + r * (path.u_conv[d] - self.u_prev[d]);
                }
            }
            self.lambda = path.lam_conv + r * (path.lam_conv - lam_prev);
        }
        self.u[cd] = path.u_conv[cd] + h;
        let jumped = match self.newton_disp() {
            Ok(_) => false,
            Err(Error::Interrupted) => return Next::Stop((Status::Interrupted, Some(Error::Interrupted))),
            Err(e) => {
                self.u.copy_from_slice(&path.u_conv);
                self.lambda = path.lam_conv;
                path.streak = 0;
                path.step *= 0.5;
                if path.step.abs() >= path.min_step {
                    return Next::Go;
                }
                // a snap-back: no equilibrium near the converged state at the next
                // displacement; follow the wall's jump by dynamic relaxation, then refine. Only
                // joints with cohesion or tensile strength can lose strength suddenly; in a dry
                // wall the failure is Newton's, and reported.
                let next = if path.base_step.abs() < remaining.abs() { path.base_step } else { remaining };
                match self.can_lose_strength().then(|| self.jump(path.u_conv[cd] + next)) {
                    Some(Ok(())) => true,
                    Some(Err(Error::Interrupted)) => {
                        return Next::Stop((Status::Interrupted, Some(Error::Interrupted)))
                    }
                    _ => {
                        self.u.copy_from_slice(&path.u_conv);
                        self.lambda = path.lam_conv;
                        self.evaluate();
                        return Next::Stop((Status::failure(&e), Some(e)));
                    }
                }
            }
        };
        path.converged(jumped, h, self.lambda);
        self.u_prev.copy_from_slice(&path.u_conv);
        path.u_conv.copy_from_slice(&self.u);
        path.lam_conv = self.lambda;
        // going on until collapse, the path's length is not known
        let frac = if self.opts.until_collapse { f64::NAN } else { (path.u_conv[cd] - path.u_start) / path.max_disp };
        if let Err(e) = self.commit(frac) {
            return Next::Stop((Status::failure(&e), Some(e)));
        }
        Next::Go
    }
}

/// Displacement control's path: the stretch it drives the control dof over, its steps, the
/// last converged state and the slopes of the curve.
struct Stretch {
    cd: usize,
    u_start: f64,
    /// the stretch (doubled each time the path goes on) and the control dof's target
    max_disp: f64,
    target: f64,
    /// the stretch's step, the step now, the smallest before a jump or the end
    base_step: f64,
    step: f64,
    min_step: f64,
    u_conv: Vec<f64>,
    lam_conv: f64,
    /// the first slope d lambda / d u, and the last
    k0: Option<f64>,
    k_last: f64,
    /// converged steps in a row since the last cut
    streak: usize,
    /// the previous step and the lambda before it
    last: Option<(f64, f64)>,
}

impl Stretch {
    fn new(u: Vec<f64>, lambda: f64, cd: usize, max_disp: f64, steps: usize) -> Stretch {
        let u_start = u[cd];
        let base_step = max_disp / steps as f64;
        Stretch {
            cd,
            u_start,
            max_disp,
            target: u_start + max_disp,
            base_step,
            step: base_step,
            min_step: base_step.abs() / 4096.0,
            u_conv: u,
            lam_conv: lambda,
            k0: None,
            k_last: f64::NAN,
            streak: 0,
            last: None,
        }
    }

    /// A step of length `h` converged at `lambda` (by a jump across a snap-back, or not).
    fn converged(&mut self, jumped: bool, h: f64, lambda: f64) {
        if jumped {
            // a jump is no increment to extrapolate, nor a slope
            self.last = None;
            self.step = self.base_step;
        } else {
            self.last = Some((h, self.lam_conv));
            let k = (lambda - self.lam_conv) / h;
            self.k0.get_or_insert(k);
            self.k_last = k;
            // grow back only after a run of successes: on a plateau a step that has just
            // failed tends to fail again
            self.streak += 1;
            if self.step.abs() < self.base_step.abs() && self.streak >= 4 {
                self.step *= 2.0;
                self.streak = 0;
            }
        }
    }

    /// The next stretch: as much again.
    fn extend(&mut self) {
        self.max_disp *= 2.0;
        self.target = self.u_start + self.max_disp;
        self.base_step *= 2.0;
        self.step = self.base_step;
        self.min_step = self.base_step.abs() / 4096.0;
    }
}
