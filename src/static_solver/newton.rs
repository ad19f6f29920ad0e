//! Newton's iterations (at a fixed lambda, at a prescribed displacement, or along the live
//! load's work), committing a converged step, polling the monitor, and the dead state.

use super::*;

impl<'a, 'm> Solver<'a, 'm> {
    /// Newton iterations at fixed lambda. `u` and `trial` hold the result.
    pub(super) fn newton_load(&mut self) -> Result<usize, Error> {
        self.ensure_load_sys()?;
        self.newton(Drive::Load)
    }

    /// Newton iterations with the control dof prescribed and lambda unknown.
    pub(super) fn newton_disp(&mut self) -> Result<usize, Error> {
        self.ensure_disp_sys()?;
        self.newton(Drive::Disp)
    }

    /// Newton iterations with the work of the live load prescribed, `f_live . (u - u_ref) =
    /// work`, and lambda unknown (load control).
    pub(super) fn newton_work(&mut self, work: f64) -> Result<usize, Error> {
        self.ensure_load_sys()?;
        self.newton(Drive::Work(work))
    }

    /// The work of the live load on the displacements from the reference state.
    pub(super) fn work(&self) -> f64 {
        let fl = self.model.live_load();
        self.eq
            .iter()
            .enumerate()
            .filter(|(_, e)| e.is_some())
            .map(|(d, _)| fl[d] * (self.u[d] - self.u_ref[d]))
            .sum()
    }

    /// Newton on the consistent tangent with a backtracking line search on the residual norm
    /// (the law is piecewise linear: full steps can cycle between active sets near a mechanism).
    ///
    /// Under [`Drive::Work`] each iteration solves the tangent twice, `K a = r` and `K b =
    /// f_live`, and takes `du = a + dlambda b` with dlambda such that the work constraint holds
    /// (a bordered system by two solves with one factorization: the tangent keeps its symmetry,
    /// and a symmetric one goes to Cholesky). An iteration that starts off the constraint (the
    /// first, from a tangent predictor) takes its full step; every later one keeps the
    /// constraint, so the line search does too.
    pub(super) fn newton(&mut self, drive: Drive) -> Result<usize, Error> {
        self.evaluate();
        let (mut rn, mut fnorm) = self.residual();
        let mut u0 = vec![0.0; self.u.len()];
        let mut delta = vec![0.0; self.n_eq];
        let mut path = WorkPath::new(self, drive);
        let mut stall = Stall { flat: 0, history: [rn; STALL_ITERATIONS + 1] };
        for it in 0..self.opts.max_iterations {
            let off = match drive {
                Drive::Work(w) => {
                    let c = w - self.work();
                    (c.abs() > 1e-12 * w.abs().max(f64::MIN_POSITIVE)).then_some(c)
                }
                _ => None,
            };
            if off.is_none() && rn <= self.opts.residual_tolerance * fnorm.max(f64::MIN_POSITIVE) {
                return Ok(it);
            }
            self.poll()?;
            self.iterations += 1;
            let dlam = self.newton_direction(drive, &mut path, off)?;
            delta.copy_from_slice(&self.rhs);
            u0.copy_from_slice(&self.u);
            self.line_search(drive == Drive::Disp, &u0, &delta, dlam, off, rn);
            let (r, f) = self.residual();
            stall.check(drive, it, r, rn, f)?;
            rn = r;
            fnorm = f;
            if !self.lambda.is_finite() {
                return Err(Error::Convergence("non-finite load multiplier".into()));
            }
            self.check_u()?;
        }
        Err(Error::Convergence(format!(
            "no equilibrium after {} iterations",
            self.opts.max_iterations
        )))
    }

    /// One Newton direction into `rhs` (factorizing the tangent unless the last factorization
    /// serves), and the change of lambda that goes with it: the control dof's row under
    /// [`Drive::Disp`], the work constraint's under [`Drive::Work`] (`off`: how far the
    /// iterate is from it), 0 at a fixed lambda.
    fn newton_direction(&mut self, drive: Drive, path: &mut WorkPath, off: Option<f64>) -> Result<f64, Error> {
        let mut dlam = 0.0;
        let reused;
        match drive {
            Drive::Disp => {
                reused = self.reuse_factorization(true, NEWTON_STABILIZATION_FIXED)
                    && self.disp_sys.as_ref().is_some_and(|s| s.0.is_factorized());
                let (sys, slots, lam_slots) = self.disp_sys.as_mut().unwrap();
                if !reused {
                    Self::assemble(self.model, NEWTON_STABILIZATION_FIXED, &self.tangents, sys, slots);
                    let live = self.model.live_load();
                    let vals = sys.values_mut();
                    for &(d, s) in lam_slots.iter() {
                        vals[s as usize] -= live[d];
                    }
                    sys.factorize()?;
                }
                sys.solve_in_place(&mut self.rhs)?;
                dlam = self.rhs[self.eq[self.control_dof].unwrap_or(usize::MAX)];
            }
            Drive::Load | Drive::Work(_) => {
                let eps = if drive == Drive::Load { NEWTON_STABILIZATION_FIXED } else { NEWTON_STABILIZATION };
                reused = self.reuse_factorization(false, eps)
                    && self.load_sys.as_ref().is_some_and(|s| s.0.is_factorized());
                let (sys, slots) = self.load_sys.as_mut().unwrap();
                if !reused {
                    Self::assemble(self.model, eps, &self.tangents, sys, slots);
                    sys.factorize()?;
                }
                sys.solve_in_place(&mut self.rhs)?;
            }
        }
        if let Drive::Work(_) = drive {
            // K^-1 f_live, solved again only with a new factorization
            if !(reused && path.b_solved) {
                let (sys, _) = self.load_sys.as_mut().unwrap();
                path.b.copy_from_slice(&path.live_eq);
                sys.solve_in_place(&mut path.b)?;
                path.b_solved = true;
            }
            let fb: f64 = path.live_eq.iter().zip(&path.b).map(|(f, b)| f * b).sum();
            let fa: f64 = path.live_eq.iter().zip(&self.rhs).map(|(f, a)| f * a).sum();
            if !(fb.abs() > 0.0) {
                return Err(Error::Convergence(
                    "the live load does no work on the tangent's displacements".into(),
                ));
            }
            dlam = (off.unwrap_or(0.0) - fa) / fb;
            for (a, b) in self.rhs.iter_mut().zip(&path.b) {
                *a += dlam * b;
            }
        }
        Ok(dlam)
    }

    /// The backtracking line search along `delta` (and `dlam`) from `u0` and the current
    /// lambda: the first step that lowers the residual norm `rn` enough, or the best of 12
    /// halvings; a single iterate stays within a tenth of the displacement limit. An iterate
    /// off the work constraint (`off`) takes its full step. `disp`: the control dof is
    /// prescribed and does not move.
    fn line_search(&mut self, disp: bool, u0: &[f64], delta: &[f64], dlam: f64, off: Option<f64>, rn: f64) {
        let cd = self.control_dof;
        let lam0 = self.lambda;
        let moves = |d: usize| !(disp && d == cd);
        let big = self
            .eq
            .iter()
            .enumerate()
            .filter_map(|(d, e)| e.filter(|_| d % 3 != 2 && moves(d)).map(|k| delta[k].abs()))
            .fold(0.0, f64::max);
        let mut alpha: f64 = if big > 0.1 * self.u_limit && off.is_none() {
            0.1 * self.u_limit / big
        } else {
            1.0
        };
        let (mut best_alpha, mut best_rn) = (alpha, f64::INFINITY);
        let trials = if off.is_some() { 1 } else { 12 };
        for trial in 0..trials {
            self.place(disp, u0, delta, alpha, lam0 + alpha * dlam);
            let (r, _) = self.residual();
            if r < best_rn {
                best_rn = r;
                best_alpha = alpha;
            }
            if r <= (1.0 - 1e-4 * alpha) * rn || trial + 1 == trials {
                break;
            }
            alpha *= 0.5;
        }
        if alpha != best_alpha {
            self.place(disp, u0, delta, best_alpha, lam0 + best_alpha * dlam);
        }
    }

    /// Sets `u = u0 + alpha delta` (the prescribed control dof kept under `disp`) and lambda,
    /// and evaluates the joints there.
    fn place(&mut self, disp: bool, u0: &[f64], delta: &[f64], alpha: f64, lambda: f64) {
        let cd = self.control_dof;
        for (d, e) in self.eq.iter().enumerate() {
            if let Some(k) = *e {
                if !(disp && d == cd) {
                    self.u[d] = u0[d] + alpha * delta[k];
                }
            }
        }
        self.lambda = lambda;
        self.evaluate();
    }

    pub(super) fn commit(&mut self, fraction: f64) -> Result<(), Error> {
        self.committed.copy_from_slice(&self.trial);
        self.curve_l.push(self.lambda);
        self.curve_u.push(self.u[self.control_dof]);
        self.steps += 1;
        let p = Progress {
            step: self.steps,
            multiplier: self.lambda,
            displacement: self.u[self.control_dof],
            fraction,
            poll: false,
            time: f64::NAN,
        };
        self.report(&p)
    }

    pub(super) fn report(&mut self, p: &Progress) -> Result<(), Error> {
        self.last_report = Instant::now();
        if self.interrupted || !(self.monitor)(p) {
            self.interrupted = true;
            return Err(Error::Interrupted);
        }
        Ok(())
    }

    /// Polls the monitor if 0.1 s have passed since it was last called (Ctrl-C from Python).
    pub(super) fn poll(&mut self) -> Result<(), Error> {
        if self.interrupted {
            return Err(Error::Interrupted);
        }
        if self.last_report.elapsed().as_secs_f64() < POLL_INTERVAL {
            return Ok(());
        }
        let p = Progress {
            step: self.steps,
            multiplier: self.curve_l.last().copied().unwrap_or(0.0),
            displacement: self.curve_u.last().copied().unwrap_or(f64::NAN),
            fraction: f64::NAN,
            poll: true,
            time: f64::NAN,
        };
        self.report(&p)
    }

    /// The state under dead load alone.
    pub(super) fn dead_state(&mut self) -> Result<(), Error> {
        self.lambda = 0.0;
        let mut outcome = self.dead_in_fractions();
        if self.interrupted {
            return Err(Error::Interrupted);
        }
        if outcome.is_err() {
            outcome = self.dead_from_relaxation().unwrap_or(outcome);
        }
        outcome.map_err(|e| match e {
            Error::Convergence(why) => Error::Mechanism(format!(
                "no equilibrium under the dead loads alone: {why}"
            )),
            e => e,
        })?;
        self.hold();
        self.u_prev.copy_from_slice(&self.u);
        // the fraction of the path is known under displacement control only
        let fraction = match self.opts.control {
            Control::Load => f64::NAN,
            Control::Displacement { .. } => 0.0,
        };
        self.commit(fraction)
    }

    /// Newton under the whole self-weight at once; where it cannot take it in one step (many
    /// joints change state at once), in growing fractions of it, each step committed.
    fn dead_in_fractions(&mut self) -> Result<usize, Error> {
        let u0 = self.u.clone();
        let mut outcome = self.newton_load();
        if outcome.is_err() {
            self.u.copy_from_slice(&u0);
            let (mut f, mut df) = (0.0_f64, 0.05_f64);
            outcome = Ok(0);
            while f < 1.0 {
                let u_conv = self.u.clone();
                self.dead_factor = (f + df).min(1.0);
                match self.newton_load() {
                    Ok(_) => {
                        f = self.dead_factor;
                        self.committed.copy_from_slice(&self.trial);
                        df *= 1.5;
                    }
                    Err(e) => {
                        self.u.copy_from_slice(&u_conv);
                        df *= 0.5;
                        if df < 1e-4 {
                            outcome = Err(e);
                            break;
                        }
                    }
                }
            }
            self.dead_factor = 1.0;
        }
        outcome
    }

    /// Newton from the unloaded wall cycles between the states of joints that start with no
    /// force (a corbel that only stands by arching, say): start from the explicit solver's
    /// damped relaxation, and refine. `None` where the relaxation finds nothing either (the
    /// first outcome stands); a mechanism or an interruption is the answer.
    fn dead_from_relaxation(&mut self) -> Option<Result<usize, Error>> {
        let (steps, model) = (self.steps, self.model);
        let monitor = &mut self.monitor;
        let interrupted = &mut self.interrupted;
        let mut relay = |_: &crate::explicit::Progress| {
            let p = Progress { step: steps, multiplier: 0.0, displacement: f64::NAN, fraction: f64::NAN, poll: true, time: f64::NAN };
            *interrupted |= !monitor(&p);
            !*interrupted
        };
        match crate::explicit::relax_dead_state(model, &mut relay) {
            Ok((u, states)) => {
                self.u.copy_from_slice(&u);
                self.committed.copy_from_slice(&states);
                Some(self.newton_load())
            }
            Err(e @ (Error::Mechanism(_) | Error::Interrupted)) => Some(Err(e)),
            Err(_) => None,
        }
    }

    /// Fixes the dofs the model holds once the dead loads are on, where they are: they leave
    /// the system of equations, which is renumbered.
    pub(super) fn hold(&mut self) {
        let held = self.model.held_after_dead();
        if held.is_empty() {
            return;
        }
        for &d in held {
            self.eq[d] = None;
        }
        let mut n = 0;
        for e in self.eq.iter_mut().flatten() {
            *e = n;
            n += 1;
        }
        self.n_eq = n;
        self.rhs = vec![0.0; n];
        self.load_sys = None;
        self.disp_sys = None;
        self.fact_key = None;
    }
}

/// What the work path's Newton iterations keep between them: the live load on the equations,
/// and `K^-1 f_live` for the current factorization.
pub(super) struct WorkPath {
    live_eq: Vec<f64>,
    b: Vec<f64>,
    b_solved: bool,
}

impl WorkPath {
    fn new(solver: &Solver<'_, '_>, drive: Drive) -> WorkPath {
        let live_eq: Vec<f64> = match drive {
            Drive::Work(_) => {
                let fl = solver.model.live_load();
                let mut g = vec![0.0; solver.n_eq];
                for (d, e) in solver.eq.iter().enumerate() {
                    if let Some(k) = *e {
                        g[k] = fl[d];
                    }
                }
                g
            }
            _ => vec![],
        };
        WorkPath { b: vec![0.0; live_eq.len()], live_eq, b_solved: false }
    }
}

/// How Newton's residual has gone: the iterations in a row it did not fall (at a fixed lambda),
/// and the residuals of the work path's last iterations (the one before the first included:
/// that after iteration `it` at `(it + 1) % (STALL_ITERATIONS + 1)`).
struct Stall {
    flat: usize,
    history: [f64; STALL_ITERATIONS + 1],
}

impl Stall {
    /// An error when the iterations have stopped getting anywhere: residual `r` after iteration
    /// `it`, `rn` before it, `f` the size of the applied forces.
    fn check(&mut self, drive: Drive, it: usize, r: f64, rn: f64, f: f64) -> Result<(), Error> {
        // at fixed lambda, a wall past its collapse load flows plastically: the line search
        // finds no step that lowers the residual, which stays put or creeps up while the
        // displacements keep moving (a block past its sliding or rocking load). Not under
        // displacement control, where such a stall can pass (psi = 0) and a failure cuts the
        // step: the paths of a wall and of its mirror image would part there.
        if drive == Drive::Load && r >= rn * (1.0 - 1e-10) {
            self.flat += 1;
            if self.flat >= FLAT_ITERATIONS {
                return Err(Error::Convergence(format!(
                    "no equilibrium: the residual did not fall for {FLAT_ITERATIONS} iterations (at {:.3e} of the applied forces) while the wall moved",
                    r / f.max(f64::MIN_POSITIVE)
                )));
            }
        } else {
            self.flat = 0;
        }
        // along the work path, a step that has not halved its residual in STALL_ITERATIONS
        // iterations has stalled (the line search crawls between active sets): a shorter step
        // is cheaper than the rest of max_iterations
        if let Drive::Work(_) = drive {
            let before = self.history[(it + 2) % (STALL_ITERATIONS + 1)];
            self.history[(it + 1) % (STALL_ITERATIONS + 1)] = r;
            if it + 1 >= STALL_ITERATIONS && r > 0.5 * before {
                return Err(Error::Convergence(format!(
                    "no equilibrium: the residual did not halve in {STALL_ITERATIONS} iterations (at {:.3e} of the applied forces)",
                    r / f.max(f64::MIN_POSITIVE)
                )));
            }
        }
        Ok(())
    }
}
