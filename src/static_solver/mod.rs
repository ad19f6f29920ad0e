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
//!   more than half of [`COLLAPSE_EVIDENCE`] `tolerance` below it goes on at fixed multipliers,
//!   in rises sized by the distance to it, each by Newton and, where Newton cycles, by
//!   **pseudo-transient continuation** (`(K_T + D / dtau) du = r`, `D` the tangent's diagonal,
//!   `dtau` grown by switched evolution relaxation; on these walls each step lowers the convex
//!   potential energy, so it cannot cycle). It is reported `Stalled`, not `Collapse`, with both
//!   numbers, if it cannot come within [`COLLAPSE_EVIDENCE`] `tolerance` (a displacement-control
//!   path that peaks below it: at once). The multiplier is always the path's own converged
//!   equilibrium, never the limit analysis's; its certificate and mechanism come with the
//!   result.
//! - **Other ends are not a collapse**: a path that leaves the small-displacement model with
//!   lambda still rising ends `DisplacementLimit`, one that passes 1e3 times the load scale
//!   `Unbounded`, a displacement-control path that reaches `max_displacement` rising
//!   `Completed`; `collapse_multiplier` is then NaN and `last_equilibrium` the largest lambda.
//!
//! Joint histories are committed only at converged steps, so a failed step leaves no trace.
//!
//! Here: the options, the entry points and the results. The solver's state and its systems are
//! in `system`, Newton's iterations and the dead state in `newton`, the pseudo-transient
//! continuation in `continuation`, the two path-following strategies in `load_control` (with
//! the check against limit analysis) and `displacement_control`.
//!
//! ```
//! use masonry_dem::static_solver::{solve, Control, StaticOptions};
//! use masonry_dem::geometry::Rect;
//! use masonry_dem::model::{Model, ModelSpec};
//! // one block of 0.4 x 0.2 m on the base
//! let model = Model::new(ModelSpec { blocks: vec![Rect::new(0.0, 0.0, 0.4, 0.2).into()], ..ModelSpec::default() }).unwrap();
//! // displacement control: the block pushed 1 mm, then lambda stays at the friction coefficient
//! let opts = StaticOptions { control: Control::Displacement { max_displacement: 1e-3 }, ..StaticOptions::default() };
//! let r = solve(&model, &opts).unwrap();
//! assert!((r.last_equilibrium - 0.65).abs() < 1e-3);
//! ```

use crate::error::Error;
use crate::joint::{elastic_tangent, return_map_inlined, JointState, Kinds, MapOptions};
use crate::linalg::SparseLu;
use crate::model::Model;
use crate::results::{Results, Status};
use std::time::Instant;

pub use crate::analysis::{Control, Progress};


/// Options of the static solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticOptions {
    /// How the load is driven.
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

/// The first rise of [`Solver::check_collapse`]'s attempts, as a fraction of the distance to
/// the exact value.
const REACH_FIRST: f64 = 0.25;

/// A load-control path is still rising when the last step's slope would raise lambda by more
/// than this many tolerances over as much work again (the plateau test uses one).
const RISING: f64 = 10.0;

/// A path that stops converging with block translations beyond this fraction of the
/// small-displacement limit, lambda still rising, ends at that limit (not a collapse).
const NEAR_LIMIT: f64 = 0.25;

/// The shortest wall time between two polls of the monitor within a step \[s\].
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
            Err(e) => outcome = (Status::failure(&e), Some(e)),
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

/// What a step of a path leads to: the next step, or the end with its outcome.
enum Next {
    Go,
    Stop(Outcome),
}

/// Where each interface's 6 x 6 block of the tangent goes in the sparse matrix's values.
type Slots = Vec<[u32; 36]>;

/// The bordered system of displacement control: its factorization, the interfaces' slots, and
/// the (dof, slot) of each entry of the live load's column (lambda's, in place of the control dof).
type DispSystem = (SparseLu, Slots, Vec<(usize, u32)>);

mod continuation;
mod displacement_control;
mod load_control;
mod newton;
mod system;

use system::*;

impl<'a, 'm> Solver<'a, 'm> {
    pub(super) fn finish(mut self, outcome: Outcome, start: Instant) -> Results {
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
            bracket: None,
            certificate: None,
        }
    }
}

/// The stages of a static analysis, one at a time, for benchmarks (`benches/static_scaling.rs`).
/// Not a stable API: behind the `bench-internals` feature.
#[cfg(feature = "bench-internals")]
pub mod stages {
    use super::*;

    /// A static solver on `model` at rest (every joint elastic), with its load system built
    /// (pattern and slots; the symbolic analysis comes with the first factorization).
    pub struct Stages<'a>(Solver<'a, 'static>);

    impl<'a> Stages<'a> {
        /// The solver of `model` at rest, its load system built.
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
