//! The static incremental solver (the "static solution method" of Baraldi & Cecchi 2016).
//!
//! Equilibrium `f_int(u) = f_dead + lambda f_live` is solved step by step with full Newton
//! iterations on the consistent tangent of the return-mapped joint law (exact within an active
//! set, since the faces of the strength domain are planes). The tangent is assembled into a
//! sparse matrix of fixed pattern (every interface kept in the pattern, also at zero stiffness)
//! and factorized by sparse LU: symbolic analysis once per analysis, numeric refactorization at
//! each iteration.
//!
//! - **Load control** raises lambda until collapse, following the equilibrium path in steps of
//!   the live load's work (an arc length; lambda is the unknown in its place, solved by two
//!   solves with one factorization of the tangent). Steps grow as the wall approaches its
//!   mechanism; collapse is the peak or the plateau of lambda, to `tolerance` (relative).
//! - **Displacement control** prescribes the horizontal displacement of the control block and
//!   takes lambda as the unknown in its place (the matrix gets a column `-f_live`), so the path is
//!   followed through the peak and after it.
//!
//! - **A collapse is checked** on walls of associative dry joints, where limit analysis gives the
//!   exact multiplier ([`exact_by_limit_analysis`]): a load-control path that stops converging
//!   more than [`COLLAPSE_EVIDENCE`] `tolerance` below it goes on at fixed multipliers, and is
//!   reported `Stalled`, not `Collapse`, if it cannot reach it (a displacement-control path that
//!   peaks below it: at once). The limit analysis's certificate and mechanism come with the
//!   result.
//! - **Other ends are not a collapse**: a path that leaves the small-displacement model with
//!   lambda still rising ends `DisplacementLimit`, one that passes 1e3 times the load scale
//!   `Unbounded`, a displacement-control path that reaches `max_displacement` rising
//!   `Completed`; `collapse_multiplier` is then NaN and `last_equilibrium` the largest lambda.
//!
//! Joint histories are committed only at converged steps, so a failed step leaves no trace.

use crate::error::{check_steps, Error};
use crate::joint::{elastic_tangent, return_map_with, JointState, Kinds, MapOptions};
use crate::linalg::SparseLu;
use crate::model::{LiveLoad, Model};
use crate::results::{Results, Status};
use std::time::Instant;

/// How the load is driven.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Control {
    /// Raise lambda until collapse.
    Load,
    /// Drive the horizontal displacement of the control block by `max_displacement` [m].
    Displacement { max_displacement: f64 },
}

/// Options of the static solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticOptions {
    pub control: Control,
    /// Number of increments (a hint: the solver cuts steps where needed).
    pub steps: usize,
    /// Relative precision of the collapse multiplier (load control): a peak is located within
    /// it, and a plateau is reached when the multiplier would rise by less than this fraction
    /// over as much work of the live load again and Newton finds no equilibrium 5 to 10 times
    /// this fraction above it.
    pub tolerance: f64,
    /// Newton iterations before a step is cut.
    pub max_iterations: usize,
    /// Equilibrium is reached when |residual| <= residual_tolerance * |applied forces|.
    pub residual_tolerance: f64,
    /// Block whose horizontal centroid displacement is the curve's abscissa (and the driven
    /// dof under displacement control); default [`Model::default_control_block`].
    pub control_block: Option<usize>,
    /// Displacement control: where the path reaches `max_displacement` with lambda still
    /// rising, go on by as much again (the same number of steps), until a peak or a plateau,
    /// or status `DisplacementLimit` at a tenth of the wall's size. Off: the path ends at
    /// `max_displacement` with status `Completed`.
    pub until_collapse: bool,
}

impl Default for StaticOptions {
    fn default() -> Self {
        StaticOptions {
            control: Control::Load,
            steps: 200,
            tolerance: 1e-4,
            max_iterations: 50,
            residual_tolerance: 1e-9,
            control_block: None,
            until_collapse: false,
        }
    }
}

/// Reported after each converged step; the callback returns `false` to stop the run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    pub step: usize,
    pub multiplier: f64,
    pub displacement: f64,
    /// Fraction of the requested path done, in [0, 1] (displacement control), or NaN.
    pub fraction: f64,
    /// True for a poll during a long computation (at most every 0.1 s, between Newton
    /// iterations), which repeats the figures of the last converged step: a display may skip
    /// it; returning false stops the run all the same.
    pub poll: bool,
}

/// Newton at a fixed lambda stops when the residual has not fallen for this many iterations in
/// a row. Each such iteration tries all 12 step lengths of the line search. With 5, the probe
/// above wall 1's plateau (33 blocks) ended with 5 flat iterations, each with the same residual
/// to 4 digits. With 2, five of six small walls (walls 1 and 2 with psi = 0.65, 0.3 and 0, one
/// with soft joints) take 3 iterations fewer and the sixth as many, with the same curves bit
/// for bit, and the 1,041-block wall takes the same 753 iterations.
const FLAT_ITERATIONS: usize = 2;

/// Along the work path (load control), Newton stops when the residual has not halved in this
/// many iterations.
const STALL_ITERATIONS: usize = 8;

/// Fixed-multiplier attempts of [`Solver::check_collapse`] to reach the exact collapse.
const REACH_ATTEMPTS: usize = 20;

/// A load-control path is still rising when the last step's slope would raise lambda by more
/// than this many tolerances over as much work again (the plateau test uses one).
const RISING: f64 = 10.0;

/// A path that stops converging with block translations beyond this fraction of the
/// small-displacement limit, lambda still rising, ends at that limit (not a collapse).
const NEAR_LIMIT: f64 = 0.25;

/// The shortest wall time between two polls of the monitor within a step [s].
const POLL_INTERVAL: f64 = 0.1;

/// Runs a static analysis. Bad options or an unsupported model are an `Err`; a solver failure
/// is a `Results` with status `Failed`, its reason and the converged part of the curve.
pub fn solve(model: &Model, opts: &StaticOptions) -> Result<Results, Error> {
    solve_with(model, opts, &mut |_| true)
}

/// Runs a static analysis, calling `monitor` after each converged step (return `false` to stop).
pub fn solve_with(
    model: &Model,
    opts: &StaticOptions,
    monitor: &mut dyn FnMut(&Progress) -> bool,
) -> Result<Results, Error> {
    model.check_analysis_memory("a static analysis")?;
    model.check_strength_range()?;
    let start = Instant::now();
    let mut s = Solver::new(model, opts, Box::new(|p: &Progress| monitor(p)))?;
    let mut outcome = match opts.control {
        Control::Load => s.load_control(),
        Control::Displacement { max_displacement } => s.displacement_control(max_displacement),
    };
    let mut evidence = None;
    let checked = matches!(outcome.0, Status::Collapse | Status::DisplacementLimit);
    if checked && exact_by_limit_analysis(model) {
        match s.check_collapse(outcome) {
            Ok((checked, lp)) => {
                outcome = checked;
                evidence = lp;
            }
            Err(e) => outcome = (Status::Failed, Some(e)),
        }
    }
    let mut res = s.finish(outcome, start);
    if let Some(lp) = evidence {
        // the mechanism of the exact collapse, and its certificate as the evidence
        if res.status == Status::Collapse {
            res.mechanism = lp.mechanism;
        }
        res.certificate = lp.certificate;
    }
    Ok(res)
}

/// Whether the limit analysis's multiplier is the exact collapse multiplier of the model:
/// every joint dry (no cohesion, no tensile strength) and associative (dilatancy = friction).
pub fn exact_by_limit_analysis(model: &Model) -> bool {
    (0..model.interfaces().len()).all(|k| {
        let l = model.law(k);
        !l.is_strong() && l.dilatancy == l.friction
    })
}

/// How far below the limit-analysis multiplier, relative to it and in units of `tolerance`,
/// load control may end and still be called a collapse: the plateau test locates the collapse
/// within a few times `tolerance` (walls that creep to collapse end 1e-4 to 5e-4 below the
/// exact value at the default 1e-4).
pub const COLLAPSE_EVIDENCE: f64 = 10.0;

/// Outcome of a run: status, and the reason when it failed.
type Outcome = (Status, Option<Error>);

/// Where each interface's 6 x 6 block of the tangent goes in the sparse matrix's values.
type Slots = Vec<[u32; 36]>;

/// The bordered system of displacement control: its factorization, the interfaces' slots, and
/// the (dof, slot) of each entry of the live load's column (lambda's, in place of the control dof).
type DispSystem = (SparseLu, Slots, Vec<(usize, u32)>);

struct Solver<'a, 'm> {
    model: &'a Model,
    /// called after each converged step, and polled between Newton iterations
    monitor: Box<dyn FnMut(&Progress) -> bool + 'm>,
    last_report: Instant,
    /// the monitor asked to stop: every later poll stops too
    interrupted: bool,
    opts: StaticOptions,
    control_dof: usize,
    /// equation of each dof (None: fixed)
    eq: Vec<Option<usize>>,
    n_eq: usize,
    u: Vec<f64>,
    lambda: f64,
    committed: Vec<JointState>,
    trial: Vec<JointState>,
    forces: Vec<[f64; 3]>,
    flags: Vec<u8>,
    /// the joints' kinds, with the return mapping's constants of each
    kinds: Kinds,
    /// the active set each joint's return mapping accepted at the last evaluation, tried first
    /// (with margins) at the next
    sets: Vec<u8>,
    /// the joint tangents, of the last evaluation if `tangents_current`: they are computed
    /// only when a Newton iteration needs them, not at every trial of the line search
    tangents: Vec<[[f64; 3]; 3]>,
    tangents_current: bool,
    fint: Vec<f64>,
    rhs: Vec<f64>,
    load_sys: Option<(SparseLu, Slots)>,
    disp_sys: Option<DispSystem>,
    /// the joint tangents and the system (displacement control or not, stabilization) of the
    /// last factorization: Newton refactorizes only when one of them has changed
    fact_tangents: Vec<[[f64; 3]; 3]>,
    fact_key: Option<(bool, u64)>,
    /// force scale for the residual test
    iterations: usize,
    steps: usize,
    curve_l: Vec<f64>,
    curve_u: Vec<f64>,
    u_prev: Vec<f64>,
    /// the reference state of the live load's work (the dead state)
    u_ref: Vec<f64>,
    /// the dead state (load control)
    dead: Option<Saved>,
    mechanism: Option<Vec<f64>>,
    /// how far the last failed load step had gone from the converged state
    diverged: Option<Vec<f64>>,
    /// fraction of the dead loads applied (1 but while the dead state is being found)
    dead_factor: f64,
    u_limit: f64,
}

const NONE: u32 = u32::MAX;

/// A converged state of the load-control path.
struct Saved {
    u: Vec<f64>,
    committed: Vec<JointState>,
    lambda: f64,
    /// the live load's work from the dead state
    work: f64,
    /// length of the curve up to this state
    curve: usize,
}

/// What Newton holds fixed besides the dead loads.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Drive {
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
const NEWTON_STABILIZATION: f64 = 1e-8;

/// The stabilization of displacement control and of Newton at a fixed lambda (the dead state,
/// the first load step, the search above a stalled path): 1e-6 changes no reference multiplier
/// by more than 0.1%, and the paths of displacement control were measured with it.
const NEWTON_STABILIZATION_FIXED: f64 = 1e-6;

impl<'a, 'm> Solver<'a, 'm> {
    fn new(
        model: &'a Model,
        opts: &StaticOptions,
        monitor: Box<dyn FnMut(&Progress) -> bool + 'm>,
    ) -> Result<Self, Error> {
        check_steps(opts.steps)?;
        if !(opts.tolerance > 0.0 && opts.tolerance < 1.0) {
            return Err(Error::input(format!(
                "analysis.tolerance must lie in (0, 1), got {}",
                opts.tolerance
            )));
        }
        if !(opts.residual_tolerance > 0.0 && opts.residual_tolerance < 1.0) {
            return Err(Error::input(format!(
                "residual tolerance must lie in (0, 1), got {}",
                opts.residual_tolerance
            )));
        }
        if opts.max_iterations == 0 {
            return Err(Error::input("max_iterations must be at least 1"));
        }
        if opts.max_iterations > MAX_ITERATIONS {
            return Err(Error::input(format!(
                "max_iterations = {} is more than the limit of {MAX_ITERATIONS}",
                opts.max_iterations
            )));
        }
        if let Control::Displacement { max_displacement } = opts.control {
            if !(max_displacement.is_finite() && max_displacement != 0.0) {
                return Err(Error::input(format!(
                    "analysis.max_displacement must be a finite non-zero length, got {max_displacement}"
                )));
            }
        }
        model.check_supports()?;
        let nb = model.n_blocks();
        let control_block = opts
            .control_block
            .unwrap_or_else(|| model.default_control_block());
        if control_block >= nb {
            return Err(Error::input(format!(
                "control block {control_block} does not exist (the model has {nb} blocks)"
            )));
        }
        let control_dof = 3 * control_block;
        let fixed = model.fixed();
        if matches!(opts.control, Control::Displacement { .. }) && fixed[control_dof] {
            return Err(Error::input(format!(
                "the horizontal displacement of the control block ({}) is fixed: it cannot be driven",
                model.block_name(control_block)
            )));
        }
        // a block with no load of its own (a weightless top beam under no force) rests on the
        // wall with no contact force: nothing ties it to the wall, and driving it gives an
        // arbitrary answer (a shift of 1e-5 m moved the first step of a property test by 3%)
        let (fd, fl) = (model.dead_load(), model.live_load());
        if matches!(opts.control, Control::Displacement { .. })
            && fl[control_dof] == 0.0
            && fd[control_dof..control_dof + 3].iter().all(|&f| f == 0.0)
        {
            return Err(Error::input(format!(
                "the control block ({}) carries no load, so nothing ties it to the wall: give the top beam a force (top.force) or put the live load on it (loads.live = \"top_horizontal\")",
                model.block_name(control_block)
            )));
        }
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
    fn slots(&self, sys: &SparseLu, col_skip: Option<usize>) -> Vec<[u32; 36]> {
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

    fn pattern(&self, col_skip: Option<usize>) -> Vec<(usize, usize)> {
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

    fn ensure_load_sys(&mut self) -> Result<(), Error> {
        if self.load_sys.is_none() {
            let sys = SparseLu::new(self.n_eq, self.pattern(None))?;
            let slots = self.slots(&sys, None);
            self.load_sys = Some((sys, slots));
        }
        Ok(())
    }

    fn ensure_disp_sys(&mut self) -> Result<(), Error> {
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
    fn evaluate(&mut self) {
        let model = self.model;
        for (k, it) in model.interfaces().iter().enumerate() {
            let e = it.jumps(&self.u);
            // the last set first, taken only with margins: the numbers of the ordered
            // enumeration, bit for bit (see `MapOptions::strict`)
            let opts = MapOptions { prepared: self.kinds.prepared(k), warm: self.sets[k], strict: true, tangent: false };
            let (r, set) = return_map_with(model.law(k), &model.sections()[k], e, &self.committed[k], opts);
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
    fn update_tangents(&mut self) {
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
            self.tangents[k] = return_map_with(model.law(k), &model.sections()[k], e, &self.committed[k], opts).0.tangent;
        }
        self.tangents_current = true;
    }

    /// Residual on the equations (external minus internal); returns its norm and the norm of
    /// the applied forces.
    fn residual(&mut self) -> (f64, f64) {
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
    fn assemble(
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

    /// The largest block translation component of `u` [m].
    fn max_translation(&self, u: &[f64]) -> f64 {
        (0..self.model.n_blocks())
            .map(|i| u[3 * i].abs().max(u[3 * i + 1].abs()))
            .fold(0.0, f64::max)
    }

    fn check_u(&self) -> Result<(), Error> {
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
    fn reuse_factorization(&mut self, disp: bool, eps: f64) -> bool {
        self.update_tangents();
        let key = Some((disp, eps.to_bits()));
        if self.fact_key == key && self.fact_tangents == self.tangents {
            return true;
        }
        self.fact_key = key;
        self.fact_tangents.clone_from(&self.tangents);
        false
    }

    /// Newton iterations at fixed lambda. `u` and `trial` hold the result.
    fn newton_load(&mut self) -> Result<usize, Error> {
        self.ensure_load_sys()?;
        self.newton(Drive::Load)
    }

    /// Newton iterations with the control dof prescribed and lambda unknown.
    fn newton_disp(&mut self) -> Result<usize, Error> {
        self.ensure_disp_sys()?;
        self.newton(Drive::Disp)
    }

    /// Newton iterations with the work of the live load prescribed, `f_live . (u - u_ref) =
    /// work`, and lambda unknown (load control).
    fn newton_work(&mut self, work: f64) -> Result<usize, Error> {
        self.ensure_load_sys()?;
        self.newton(Drive::Work(work))
    }

    /// The work of the live load on the displacements from the reference state.
    fn work(&self) -> f64 {
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
    fn newton(&mut self, drive: Drive) -> Result<usize, Error> {
        let disp = drive == Drive::Disp;
        let cd = self.control_dof;
        let lam_eq = self.eq[cd].unwrap_or(usize::MAX);
        self.evaluate();
        let (mut rn, mut fnorm) = self.residual();
        let mut u0 = vec![0.0; self.u.len()];
        let mut delta = vec![0.0; self.n_eq];
        let live_eq: Vec<f64> = match drive {
            Drive::Work(_) => {
                let fl = self.model.live_load();
                let mut g = vec![0.0; self.n_eq];
                for (d, e) in self.eq.iter().enumerate() {
                    if let Some(k) = *e {
                        g[k] = fl[d];
                    }
                }
                g
            }
            _ => vec![],
        };
        // K^-1 f_live of the work path, solved into this buffer with each new factorization
        let mut b = vec![0.0; live_eq.len()];
        let mut b_solved = false;
        let mut flat = 0;
        // the residuals of the work path's last iterations, the one before the first included:
        // that after iteration `it` at `(it + 1) % (STALL_ITERATIONS + 1)`
        let mut history = [rn; STALL_ITERATIONS + 1];
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
                    dlam = self.rhs[lam_eq];
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
                if !(reused && b_solved) {
                    let (sys, _) = self.load_sys.as_mut().unwrap();
                    b.copy_from_slice(&live_eq);
                    sys.solve_in_place(&mut b)?;
                    b_solved = true;
                }
                let fb: f64 = live_eq.iter().zip(&b).map(|(f, b)| f * b).sum();
                let fa: f64 = live_eq.iter().zip(&self.rhs).map(|(f, a)| f * a).sum();
                if !(fb.abs() > 0.0) {
                    return Err(Error::Convergence(
                        "the live load does no work on the tangent's displacements".into(),
                    ));
                }
                dlam = (off.unwrap_or(0.0) - fa) / fb;
                for (a, b) in self.rhs.iter_mut().zip(&b) {
                    *a += dlam * b;
                }
            }
            delta.copy_from_slice(&self.rhs);
            u0.copy_from_slice(&self.u);
            let lam0 = self.lambda;
            let moves = |d: usize| !(disp && d == cd);
            // keep a single iterate within a tenth of the displacement limit
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
                for (d, e) in self.eq.iter().enumerate() {
                    if let Some(k) = *e {
                        if moves(d) {
                            self.u[d] = u0[d] + alpha * delta[k];
                        }
                    }
                }
                self.lambda = lam0 + alpha * dlam;
                self.evaluate();
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
                alpha = best_alpha;
                for (d, e) in self.eq.iter().enumerate() {
                    if let Some(k) = *e {
                        if moves(d) {
                            self.u[d] = u0[d] + alpha * delta[k];
                        }
                    }
                }
                self.lambda = lam0 + alpha * dlam;
                self.evaluate();
            }
            let (r, f) = self.residual();
            // at fixed lambda, a wall past its collapse load flows plastically: the line
            // search finds no step that lowers the residual, which stays put or creeps up while
            // the displacements keep moving (a block past its sliding or rocking load: 50
            // iterations, all alike, before this test). Not under displacement control, where
            // such a stall can pass (psi = 0) and a failure cuts the step: a mirror property
            // test saw the paths of a wall and its mirror image part there.
            if drive == Drive::Load && r >= rn * (1.0 - 1e-10) {
                flat += 1;
                if flat >= FLAT_ITERATIONS {
                    return Err(Error::Convergence(format!(
                        "no equilibrium: the residual did not fall for {FLAT_ITERATIONS} iterations (at {:.3e} of the applied forces) while the wall moved",
                        r / f.max(f64::MIN_POSITIVE)
                    )));
                }
            } else {
                flat = 0;
            }
            // along the work path, a step that has not halved its residual in STALL_ITERATIONS
            // iterations has stalled (the line search crawls between active sets): a shorter
            // step is cheaper than the rest of max_iterations
            if let Drive::Work(_) = drive {
                let before = history[(it + 2) % (STALL_ITERATIONS + 1)];
                history[(it + 1) % (STALL_ITERATIONS + 1)] = r;
                if it + 1 >= STALL_ITERATIONS && r > 0.5 * before {
                    return Err(Error::Convergence(format!(
                        "no equilibrium: the residual did not halve in {STALL_ITERATIONS} iterations (at {:.3e} of the applied forces)",
                        r / f.max(f64::MIN_POSITIVE)
                    )));
                }
            }
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

    fn commit(&mut self, fraction: f64) -> Result<(), Error> {
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
        };
        self.report(&p)
    }

    fn report(&mut self, p: &Progress) -> Result<(), Error> {
        self.last_report = Instant::now();
        if self.interrupted || !(self.monitor)(p) {
            self.interrupted = true;
            return Err(Error::Interrupted);
        }
        Ok(())
    }

    /// Polls the monitor if 0.1 s have passed since it was last called (Ctrl-C from Python).
    fn poll(&mut self) -> Result<(), Error> {
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
        };
        self.report(&p)
    }

    /// The state under dead load alone.
    fn dead_state(&mut self) -> Result<(), Error> {
        self.lambda = 0.0;
        // all at once; where Newton cannot take the whole self-weight in one step (many joints
        // change state at once), in growing fractions of it, each step committed
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
        if self.interrupted {
            return Err(Error::Interrupted);
        }
        if outcome.is_err() {
            // Newton from the unloaded wall cycles between the states of joints that start with
            // no force (a corbel that only stands by arching, say): start from the explicit
            // solver's damped relaxation, and refine
            let (steps, model) = (self.steps, self.model);
            let monitor = &mut self.monitor;
            let interrupted = &mut self.interrupted;
            let mut relay = |_: &crate::explicit::Progress| {
                let p = Progress { step: steps, multiplier: 0.0, displacement: f64::NAN, fraction: f64::NAN, poll: true };
                *interrupted |= !monitor(&p);
                !*interrupted
            };
            match crate::explicit::relax_dead_state(model, &mut relay) {
                Ok((u, states)) => {
                    self.u.copy_from_slice(&u);
                    self.committed.copy_from_slice(&states);
                    outcome = self.newton_load();
                }
                // the wall moves off, or the user stopped: that is the answer
                Err(e @ (Error::Mechanism(_) | Error::Interrupted)) => outcome = Err(e),
                Err(_) => {}
            }
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

    /// Fixes the dofs the model holds once the dead loads are on, where they are: they leave
    /// the system of equations, which is renumbered.
    fn hold(&mut self) {
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

    /// A natural scale of lambda: 1 for the seismic coefficient, the dead loads for a force.
    fn lambda_scale(&self) -> f64 {
        match self.model.live() {
            LiveLoad::HorizontalWeight => 1.0,
            LiveLoad::TopHorizontal => {
                let w: f64 = self.model.weight().iter().sum();
                let fd = self.model.dead_load();
                let t = self.model.top().unwrap();
                (w + fd[3 * t].abs() + fd[3 * t + 1].abs()).max(1.0)
            }
        }
    }

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
    fn load_control(&mut self) -> Outcome {
        if let Err(e) = self.dead_state() {
            return (Status::Failed, Some(e));
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
            Err(e) => return (Status::Failed, Some(e)),
        };
        if let Err(e) = self.commit(f64::NAN) {
            return (Status::Failed, Some(e));
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
                            Err(e) => return (Status::Failed, Some(e)),
                        }
                    }
                    let increment = self.u.iter().zip(&conv.u).map(|(a, b)| a - b).collect();
                    if let Err(e) = self.commit(f64::NAN) {
                        return (Status::Failed, Some(e));
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
                                    return (Status::Failed, Some(e));
                                }
                                continue;
                            }
                            Ok(false) => {
                                self.evaluate();
                                self.mechanism = Some(increment);
                                return (Status::Collapse, None);
                            }
                            Err(e) => return (Status::Failed, Some(e)),
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
                Err(Error::Interrupted) => return (Status::Failed, Some(Error::Interrupted)),
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
                                return (Status::Failed, Some(e));
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
                        Err(e) => return (Status::Failed, Some(e)),
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
    fn restart_path(
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
    fn snap(&self) -> Saved {
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
    fn check_collapse(&mut self, outcome: Outcome) -> Result<(Outcome, Option<Results>), Error> {
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

    fn restore(&mut self, s: &Saved) {
        self.u.copy_from_slice(&s.u);
        self.committed.copy_from_slice(&s.committed);
        self.lambda = s.lambda;
    }

    /// Newton at a fixed lambda above the state `from`, by `rise`, halved until it converges
    /// or is within `floor`. True if it converged (`u`, `lambda` and `trial` hold the result);
    /// false with `from` restored.
    fn above(&mut self, from: &Saved, rise: f64, floor: f64) -> Result<bool, Error> {
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

    /// Whether some joint has cohesion or tensile strength: it can lose strength suddenly, and
    /// the equilibrium path can snap back.
    fn can_lose_strength(&self) -> bool {
        (0..self.model.interfaces().len()).any(|k| {
            let l = self.model.law(k);
            l.cohesion > 0.0 || l.tensile_strength > 0.0
        })
    }

    /// Crosses a snap-back: the equilibrium at control displacement `target` that the damped
    /// motion of the wall reaches from the converged state, refined by Newton. On success `u`,
    /// `lambda` and `trial` hold it.
    fn jump(&mut self, target: f64) -> Result<(), Error> {
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

    fn displacement_control(
        &mut self,
        max_disp: f64,
    ) -> Outcome {
        if let Err(e) = self.dead_state() {
            return (Status::Failed, Some(e));
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
                    Err(Error::Interrupted) => return (Status::Failed, Some(Error::Interrupted)),
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
                                return (Status::Failed, Some(Error::Interrupted))
                            }
                            _ => {
                                self.u.copy_from_slice(&u_conv);
                                self.lambda = lam_conv;
                                self.evaluate();
                                return (Status::Failed, Some(e));
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
                    return (Status::Failed, Some(e));
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

    fn finish(mut self, outcome: Outcome, start: Instant) -> Results {
        let (status, err) = outcome;
        let model = self.model;
        let nb = model.n_blocks();
        // the converged state: committed histories with the last converged displacements
        let mech = self.mechanism.take().unwrap_or_else(|| {
            self.u
                .iter()
                .zip(&self.u_prev)
                .map(|(a, b)| a - b)
                .collect()
        });
        let scale = (0..nb)
            .map(|i| mech[3 * i].hypot(mech[3 * i + 1]))
            .fold(0.0, f64::max);
        // oriented so that the live load does positive work on it
        let work: f64 = mech.iter().zip(model.live_load()).map(|(v, f)| v * f).sum();
        let scale = if scale > 0.0 {
            work.signum() / scale
        } else {
            0.0
        };
        let last_equilibrium = match self.opts.control {
            Control::Load => self.curve_l.last().copied().unwrap_or(f64::NAN),
            Control::Displacement { .. } => crate::results::peak(&self.curve_l),
        };
        Results {
            method: "static",
            status,
            error: err.map(|e| e.to_string()),
            collapse_multiplier: if status == Status::Collapse { last_equilibrium } else { f64::NAN },
            last_equilibrium,
            curve_multiplier: self.curve_l,
            curve_displacement: self.curve_u,
            control_block: self.control_dof / 3,
            displacements: (0..nb)
                .map(|i| [self.u[3 * i], self.u[3 * i + 1], self.u[3 * i + 2]])
                .collect(),
            mechanism: (0..nb)
                .map(|i| {
                    [
                        mech[3 * i] * scale,
                        mech[3 * i + 1] * scale,
                        mech[3 * i + 2] * scale,
                    ]
                })
                .collect(),
            interface_forces: self.forces,
            interface_states: self.flags,
            broken: self.committed.iter().map(|s| s.broken).collect(),
            iterations: self.iterations,
            steps: self.steps,
            elapsed_s: start.elapsed().as_secs_f64(),
            certificate: None,
        }
    }
}

/// The stages of a static analysis, one at a time, for benchmarks (`benches/static_scaling.rs`).
/// Not a stable API.
#[doc(hidden)]
pub mod stages {
    use super::*;

    /// A static solver on `model` at rest (every joint elastic), with its load system built
    /// (pattern and slots; the symbolic analysis comes with the first factorization).
    pub struct Stages<'a>(Solver<'a, 'static>);

    impl<'a> Stages<'a> {
        pub fn new(model: &'a Model) -> Result<Self, Error> {
            let mut s = Solver::new(model, &StaticOptions::default(), Box::new(|_: &Progress| true))?;
            s.ensure_load_sys()?;
            s.evaluate();
            Ok(Stages(s))
        }
        /// Joint forces, histories and tangents of every interface, and the internal forces.
        pub fn evaluate(&mut self) {
            self.0.evaluate();
        }
        /// The tangent's values into the sparse matrix.
        pub fn assemble(&mut self) {
            let s = &mut self.0;
            s.update_tangents();
            let (sys, slots) = s.load_sys.as_mut().unwrap();
            Solver::assemble(s.model, NEWTON_STABILIZATION, &s.tangents, sys, slots);
        }
        /// The numeric factorization of the assembled matrix.
        pub fn factorize(&mut self) -> Result<(), Error> {
            self.0.load_sys.as_mut().unwrap().0.factorize()
        }
        /// The number of equations.
        pub fn n_eq(&self) -> usize {
            self.0.n_eq
        }
    }
}
