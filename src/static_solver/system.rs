//! The solver's state and its linear systems: the sparse pattern of the tangent, its assembly
//! from the joints' tangents, the residual, and when a factorization can be reused.

use super::*;

/// One static analysis: the model, its options, the converged and trial states, the joints'
/// histories and the linear systems (the load-control one and the bordered one of displacement
/// control), each factorized only when its tangents have changed.
pub(super) struct Solver<'a, 'm> {
    pub(super) model: &'a Model,
    /// called after each converged step, and polled between Newton iterations
    pub(super) monitor: Box<dyn FnMut(&Progress) -> bool + 'm>,
    pub(super) last_report: Instant,
    /// the monitor asked to stop: every later poll stops too
    pub(super) interrupted: bool,
    pub(super) opts: StaticOptions,
    pub(super) control_dof: usize,
    /// equation of each dof (None: fixed)
    pub(super) eq: Vec<Option<usize>>,
    pub(super) n_eq: usize,
    pub(super) u: Vec<f64>,
    pub(super) lambda: f64,
    pub(super) committed: Vec<JointState>,
    pub(super) trial: Vec<JointState>,
    pub(super) forces: Vec<[f64; 3]>,
    pub(super) flags: Vec<u8>,
    /// the joints' kinds, with the return mapping's constants of each
    pub(super) kinds: Kinds,
    /// the active set each joint's return mapping accepted at the last evaluation, tried first
    /// (with margins) at the next
    pub(super) sets: Vec<u8>,
    /// the joint tangents, of the last evaluation if `tangents_current`: they are computed
    /// only when a Newton iteration needs them, not at every trial of the line search
    pub(super) tangents: Vec<[[f64; 3]; 3]>,
    pub(super) tangents_current: bool,
    pub(super) fint: Vec<f64>,
    pub(super) rhs: Vec<f64>,
    pub(super) load_sys: Option<(SparseLu, Slots)>,
    pub(super) disp_sys: Option<DispSystem>,
    /// the joint tangents and the system (displacement control or not, stabilization) of the
    /// last factorization: Newton refactorizes only when one of them has changed
    pub(super) fact_tangents: Vec<[[f64; 3]; 3]>,
    pub(super) fact_key: Option<(bool, u64)>,
    /// force scale for the residual test
    pub(super) iterations: usize,
    pub(super) steps: usize,
    pub(super) curve_l: Vec<f64>,
    pub(super) curve_u: Vec<f64>,
    pub(super) u_prev: Vec<f64>,
    /// the reference state of the live load's work (the dead state)
    pub(super) u_ref: Vec<f64>,
    /// the dead state (load control)
    pub(super) dead: Option<Saved>,
    pub(super) mechanism: Option<Vec<f64>>,
    /// how far the last failed load step had gone from the converged state
    pub(super) diverged: Option<Vec<f64>>,
    /// fraction of the dead loads applied (1 but while the dead state is being found)
    pub(super) dead_factor: f64,
    pub(super) u_limit: f64,
}

pub(super) const NONE: u32 = u32::MAX;

/// A converged state of the load-control path.
pub(super) struct Saved {
    pub(super) u: Vec<f64>,
    pub(super) committed: Vec<JointState>,
    pub(super) lambda: f64,
    /// the live load's work from the dead state
    pub(super) work: f64,
    /// length of the curve up to this state
    pub(super) curve: usize,
}

/// What Newton holds fixed besides the dead loads.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Drive {
    /// lambda
    Load,
    /// the horizontal displacement of the control block (lambda unknown)
    Disp,
    /// the work of the live load from the reference state (lambda unknown)
    Work(f64),
}

/// The largest `max_iterations` accepted (Newton iterations of one step before it is cut).
pub const MAX_ITERATIONS: usize = 100_000;

/// Fraction of the elastic joint stiffness added to every joint's tangent in the Newton matrix
/// (never to the residual, so converged states are exact). Joints that carry nothing (open)
/// have a zero tangent; on a wall with openings and corbels (LACT3) the unstabilized matrix
/// reads as a mechanism from the dead-load state and every load step failed. Near collapse
/// the wall's softest modes are as soft as the stabilization, and Newton converges only
/// linearly: on the work path of load control, at 1e-6, at 0.77 per iteration on a 1,040-block
/// wall (30 iterations a step, 4,425 in all, 20.7 s); at 1e-8, 1,194 iterations and 6.9 s, the
/// same multiplier. Displacement control and Newton at fixed lambda keep
/// [`NEWTON_STABILIZATION_FIXED`].
pub(super) const NEWTON_STABILIZATION: f64 = 1e-8;

/// The stabilization of displacement control and of Newton at a fixed lambda (the dead state,
/// the first load step, the search above a stalled path): 1e-6 changes no reference multiplier
/// by more than 0.1%, and the paths of displacement control were measured with it.
pub(super) const NEWTON_STABILIZATION_FIXED: f64 = 1e-6;

impl<'a, 'm> Solver<'a, 'm> {
    pub(super) fn new(
        model: &'a Model,
        opts: &StaticOptions,
        monitor: Box<dyn FnMut(&Progress) -> bool + 'm>,
    ) -> Result<Self, Error> {
        opts.validate()?;
        crate::analysis::check_displacement_range(model, opts.control)?;
        model.check_supports()?;
        let nb = model.n_blocks();
        let control_block = crate::analysis::control_block(model, opts.control_block)?;
        let control_dof = 3 * control_block;
        check_drivable(model, opts.control, control_block)?;
        let fixed = model.fixed();
        let mut eq = vec![None; 3 * nb];
        let mut n_eq = 0;
        for (d, e) in eq.iter_mut().enumerate() {
            if !fixed[d] {
                *e = Some(n_eq);
                n_eq += 1;
            }
        }
        if n_eq == 0 {
            return Err(Error::input(
                "every dof of the model is fixed: nothing to solve",
            ));
        }
        let m = model.interfaces().len();
        let mut u_limit = 0.1 * model.size();
        if let Control::Displacement { max_displacement } = opts.control {
            u_limit = u_limit.max(10.0 * max_displacement.abs());
        }
        Ok(Solver {
            model,
            monitor,
            last_report: Instant::now(),
            interrupted: false,
            opts: *opts,
            control_dof,
            eq,
            n_eq,
            u: model.prescribed().to_vec(),
            lambda: 0.0,
            committed: vec![JointState::default(); m],
            trial: vec![JointState::default(); m],
            forces: vec![[0.0; 3]; m],
            flags: vec![0; m],
            kinds: model.joint_kinds(),
            sets: vec![0; m],
            tangents: vec![[[0.0; 3]; 3]; m],
            tangents_current: false,
            fint: vec![0.0; 3 * nb],
            rhs: vec![0.0; n_eq],
            load_sys: None,
            disp_sys: None,
            fact_tangents: vec![],
            fact_key: None,
            iterations: 0,
            steps: 0,
            curve_l: vec![],
            curve_u: vec![],
            u_prev: model.prescribed().to_vec(),
            u_ref: model.prescribed().to_vec(),
            dead: None,
            mechanism: None,
            diverged: None,
            dead_factor: 1.0,
            u_limit,
        })
    }

    /// Slot map of every interface's 6 x 6 block for a system whose column of `col_skip` is
    /// not an unknown.
    pub(super) fn slots(&self, sys: &SparseLu, col_skip: Option<usize>) -> Vec<[u32; 36]> {
        self.model
            .interfaces()
            .iter()
            .map(|it| {
                let d = it.dofs();
                let mut s = [NONE; 36];
                for i in 0..6 {
                    for j in 0..6 {
                        if let (Some(r), Some(c)) = (self.eq[d[i]], self.eq[d[j]]) {
                            if Some(d[j]) != col_skip {
                                s[6 * i + j] = sys.slot(r, c).expect("pattern entry") as u32;
                            }
                        }
                    }
                }
                s
            })
            .collect()
    }

    pub(super) fn pattern(&self, col_skip: Option<usize>) -> Vec<(usize, usize)> {
        let mut e = Vec::with_capacity(36 * self.model.interfaces().len());
        for it in self.model.interfaces() {
            let d = it.dofs();
            for &di in &d {
                for &dj in &d {
                    if let (Some(r), Some(c)) = (self.eq[di], self.eq[dj]) {
                        if Some(dj) != col_skip {
                            e.push((r, c));
                        }
                    }
                }
            }
        }
        e
    }

    pub(super) fn ensure_load_sys(&mut self) -> Result<(), Error> {
        if self.load_sys.is_none() {
            let sys = SparseLu::new(self.n_eq, self.pattern(None))?;
            let slots = self.slots(&sys, None);
            self.load_sys = Some((sys, slots));
        }
        Ok(())
    }

    pub(super) fn ensure_disp_sys(&mut self) -> Result<(), Error> {
        if self.disp_sys.is_none() {
            let cd = self.control_dof;
            let lam_col = self.eq[cd].expect("free control dof");
            let live = self.model.live_load();
            let live_rows: Vec<usize> = (0..live.len())
                .filter(|&d| live[d] != 0.0 && self.eq[d].is_some())
                .collect();
            let mut entries = self.pattern(Some(cd));
            entries.extend(live_rows.iter().map(|&d| (self.eq[d].unwrap(), lam_col)));
            let sys = SparseLu::new(self.n_eq, entries)?;
            let slots = self.slots(&sys, Some(cd));
            let lam_slots = live_rows
                .iter()
                .map(|&d| (d, sys.slot(self.eq[d].unwrap(), lam_col).unwrap() as u32))
                .collect();
            self.disp_sys = Some((sys, slots, lam_slots));
        }
        Ok(())
    }

    /// Joint forces, trial histories, tangents and internal forces at the current `u`.
    pub(super) fn evaluate(&mut self) {
        let model = self.model;
        for (k, it) in model.interfaces().iter().enumerate() {
            let e = it.jumps(&self.u);
            // the last set first, taken only with margins: the numbers of the ordered
            // enumeration, bit for bit (see `MapOptions::strict`)
            let opts = MapOptions { prepared: self.kinds.prepared(k), warm: self.sets[k], strict: true, tangent: false };
            let (r, set) = return_map_inlined(model.law(k), &model.sections()[k], e, &self.committed[k], &opts);
            self.forces[k] = r.force;
            self.trial[k] = r.state;
            self.flags[k] = r.flags;
            self.sets[k] = set;
        }
        self.tangents_current = false;
        model.internal_forces(&self.forces, &mut self.fint);
    }

    /// The joint tangents of the last evaluation, if not computed yet: D where it was elastic,
    /// elsewhere each joint's mapping again, its accepted set tried first (taken at once: the
    /// same test on the same numbers), with the tangent.
    pub(super) fn update_tangents(&mut self) {
        if self.tangents_current {
            return;
        }
        let model = self.model;
        for (k, it) in model.interfaces().iter().enumerate() {
            if self.sets[k] == 0 {
                self.tangents[k] = elastic_tangent(model.law(k), &model.sections()[k]);
                continue;
            }
            let e = it.jumps(&self.u);
            let opts = MapOptions { prepared: self.kinds.prepared(k), warm: self.sets[k], strict: false, tangent: true };
            self.tangents[k] = return_map_inlined(model.law(k), &model.sections()[k], e, &self.committed[k], &opts).0.tangent;
        }
        self.tangents_current = true;
    }

    /// Residual on the equations (external minus internal); returns its norm and the norm of
    /// the applied forces.
    pub(super) fn residual(&mut self) -> (f64, f64) {
        let (fd, fl) = (self.model.dead_load(), self.model.live_load());
        let (mut rn, mut fnorm) = (0.0, 0.0);
        for (d, e) in self.eq.iter().enumerate() {
            let f = self.dead_factor * fd[d] + self.lambda * fl[d];
            fnorm += f * f;
            if let Some(k) = *e {
                let r = f - self.fint[d];
                self.rhs[k] = r;
                rn += r * r;
            }
        }
        (rn.sqrt(), fnorm.sqrt())
    }

    /// Adds the interface stiffnesses B^T (D_t + eps D) B to the values of `sys` through `slots`
    /// (`eps`: the Newton stabilization, 0 for the exact tangent).
    pub(super) fn assemble(
        model: &Model,
        eps: f64,
        tangents: &[[[f64; 3]; 3]],
        sys: &mut SparseLu,
        slots: &[[u32; 36]],
    ) {
        let vals = sys.values_mut();
        vals.fill(0.0);
        for (k, ((it, dt0), sl)) in model.interfaces().iter().zip(tangents).zip(slots).enumerate() {
            let b = &it.b_mat;
            let mut dt = *dt0;
            let (law, sec) = (model.law(k), &model.sections()[k]);
            dt[0][0] += eps * law.normal_stiffness * sec.area;
            dt[1][1] += eps * law.shear_stiffness * sec.area;
            dt[2][2] += eps * law.normal_stiffness * sec.inertia;
            // B's third row is (0, 0, -1, 0, 0, 1) (`Interface::new`): its terms are formed as
            // the negation, the value and nothing, the numbers of the products (x * -1 == -x,
            // x * 1 == x, and a zero term leaves a non-zero sum as it is) for a third fewer
            debug_assert_eq!(b[2], [0.0, 0.0, -1.0, 0.0, 0.0, 1.0]);
            let third = |c: usize, x: f64, y: f64| match c {
                2 => x - y,
                5 => x + y,
                _ => x,
            };
            // DB = D_t B (3 x 6)
            let mut db = [[0.0; 6]; 3];
            for r in 0..3 {
                for c in 0..6 {
                    db[r][c] = third(c, dt[r][0] * b[0][c] + dt[r][1] * b[1][c], dt[r][2]);
                }
            }
            for i in 0..6 {
                for j in 0..6 {
                    let s = sl[6 * i + j];
                    if s != NONE {
                        vals[s as usize] += third(i, b[0][i] * db[0][j] + b[1][i] * db[1][j], db[2][j]);
                    }
                }
            }
        }
    }

    /// The largest block translation component of `u` \[m\].
    pub(super) fn max_translation(&self, u: &[f64]) -> f64 {
        (0..self.model.n_blocks())
            .map(|i| u[3 * i].abs().max(u[3 * i + 1].abs()))
            .fold(0.0, f64::max)
    }

    pub(super) fn check_u(&self) -> Result<(), Error> {
        let big = self.u.iter().map(|v| v.abs()).fold(0.0, f64::max);
        if !big.is_finite() {
            return Err(Error::Convergence("non-finite displacement".into()));
        }
        let tmax = self.max_translation(&self.u);
        if tmax > self.u_limit {
            return Err(Error::Convergence(format!(
                "displacements grew beyond {:.3e} m (the small-displacement model no longer holds)",
                self.u_limit
            )));
        }
        Ok(())
    }

    /// Whether the system (`disp`: the bordered one of displacement control) still holds the
    /// factorization of the current tangents with stabilization `eps`; if not, records them as
    /// those of the factorization about to be made. The law is piecewise linear, so the last
    /// iteration of a step often sees the tangents of the one before.
    pub(super) fn reuse_factorization(&mut self, disp: bool, eps: f64) -> bool {
        self.update_tangents();
        let key = Some((disp, eps.to_bits()));
        if self.fact_key == key && self.fact_tangents == self.tangents {
            return true;
        }
        self.fact_key = key;
        self.fact_tangents.clone_from(&self.tangents);
        false
    }
}

impl StaticOptions {
    /// Refuses options out of range; the error names the key.
    pub fn validate(&self) -> Result<(), Error> {
        crate::analysis::check_path_options(self.steps, self.tolerance, self.control)?;
        if !(self.residual_tolerance > 0.0 && self.residual_tolerance < 1.0) {
            return Err(Error::input(format!(
                "residual tolerance must lie in (0, 1), got {}",
                self.residual_tolerance
            )));
        }
        if self.max_iterations == 0 {
            return Err(Error::input("max_iterations must be at least 1"));
        }
        if self.max_iterations > MAX_ITERATIONS {
            return Err(Error::input(format!(
                "max_iterations = {} is more than the limit of {MAX_ITERATIONS}",
                self.max_iterations
            )));
        }
        Ok(())
    }
}

/// Under displacement control, refuses a control block that carries no load at all (one whose
/// horizontal dof is fixed is refused by [`crate::analysis::control_block`]).
fn check_drivable(model: &Model, control: Control, control_block: usize) -> Result<(), Error> {
    if !matches!(control, Control::Displacement { .. }) {
        return Ok(());
    }
    let control_dof = 3 * control_block;
    // a block with no load of its own (a weightless top beam under no force) rests on the wall
    // with no contact force: nothing ties it to the wall, and driving it gives an arbitrary
    // answer
    let (fd, fl) = (model.dead_load(), model.live_load());
    if fl[control_dof] == 0.0 && fd[control_dof..control_dof + 3].iter().all(|&f| f == 0.0) {
        return Err(Error::input(format!(
            "the control block ({}) carries no load, so nothing ties it to the wall: give the top beam a force (top.force) or put the live load on it (loads.live = \"top_horizontal\")",
            model.block_name(control_block)
        )));
    }
    Ok(())
}
