//! Limit analysis: the collapse multiplier of a model as a linear program (the static theorem),
//! solved by a primal-dual interior point method on the stiffness matrix's sparsity pattern.
//!
//! Maximise lambda subject to equilibrium of every free dof,
//! `sum_k B_k^T s_k = f_dead + lambda f_live`, with every interface's resultants
//! `s_k = (N, T, M)` inside the joint law's strength domain: the four planes of
//! [`crate::joint`] (Coulomb `|T| <= c A - mu N`, rocking `|M| <= (ft A - N) l/2`; together they
//! imply the tension cut-off `N <= ft A`). Mortar joints enter with their peak strengths (no
//! softening, no loss of strength at failure). Fixed dofs and the dofs held after the dead
//! loads (the top beam's vertical position when it is held) are supports: their reactions are
//! free.
//!
//! For dry joints with associative flow (dilatancy = friction) the optimum is the exact collapse
//! multiplier of the incremental model; for other joints it is an upper bound of it. With
//! dilatancy below friction [`limit_analysis`] also gives a non-associative estimate: a
//! sequence of programs in which the shear capacity is fixed from the previous program's normal
//! forces (Gilbert, Casapulla & Ahmed, 2006). That estimate is a heuristic, neither bound: its
//! status is [`Status::Estimate`], never a collapse, converged or not.
//!
//! The method: Mehrotra's predictor-corrector on the program scaled to forces of order one
//! (moments carried as `2 M / l`, rotation rows divided by a length), in standard form: each
//! interface's resultants are a point of its strength domain written with non-negative
//! variables (the four rays of two contact points, and the segment between the domain's two
//! vertices for joints with strength). Each iteration solves the normal equations
//! `A Theta A^T dy = r`, whose matrix is assembled exactly as the stiffness matrix is (one 3 x 3
//! block per interface, on the same pattern) and factorized by the crate's `linalg` module (LDL^T on the
//! sparse Cholesky's symbolic analysis, which is done once). The direction kept is corrected
//! until it meets the primal equation and lambda's dual row. lambda, a free variable, borders
//! the system: two solves with one factorization. The dual variables of the equilibrium rows
//! are the block velocities of the collapse mechanism.
//!
//! ```
//! use masonry_dem::geometry::{polygons, running_bond, RunningBond, FirstCourse};
//! use masonry_dem::joint::JointLaw;
//! use masonry_dem::limit::{limit_analysis, LimitOptions};
//! use masonry_dem::model::{JointLaws, Model, ModelSpec};
//!
//! let blocks = running_bond(&RunningBond { block_length: 0.4, block_height: 0.175, courses: 6, height: None,
//!     length: 2.0, first_course: FirstCourse::Half, openings: vec![] }).unwrap();
//! let law = JointLaw { friction: 0.65, dilatancy: 0.65, ..JointLaw::default() };
//! let model = Model::new(ModelSpec { blocks: polygons(blocks), gravity: 10.0, joints: JointLaws::uniform(law),
//!     ..ModelSpec::default() }).unwrap();
//! let res = limit_analysis(&model, &LimitOptions::default()).unwrap();
//! assert!((res.collapse_multiplier - 0.642857).abs() < 1e-5);
//! ```
//!
//! Walls of 3D blocks ([`crate::space::Model3`]) go through the same interior point
//! ([`limit_analysis_3d`]): each corner of a contact carries a force in Coulomb's cone (the
//! point-contact form; joints with strength add a vertex at the tension cut-off and a disc of
//! cohesion, each corner its tributary share of the contact's), six equations per block. The program is then a
//! second-order cone program: its variables lie in cones `z0 >= |(z1, z2)|` rather than the
//! orthant, and Theta is the 3 x 3 block `W^2` of each cone's Nesterov-Todd scaling.
//!
//! Here: the options, the entry points and the non-associative sequence. The program the
//! interior point solves is `program` (the same in both dimensions), built for walls in the
//! plane in `plane` and in 3D in `space`, solved in `ipm`, and turned into Results in
//! `outcome` (the plane) and `space`.

use crate::error::{Error, Result};
use crate::joint::{JointState, OPEN, ROCKING, SLIDING};
use crate::linalg::SparseLu;
use crate::model::Model;
use crate::results::{Certificate, Results, Status};
use std::time::Instant;

/// Options of the limit analysis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimitOptions {
    /// The interior point stops when the scaled primal and dual residuals and the relative
    /// duality gap are all below this.
    pub tolerance: f64,
    /// Interior-point iterations of one linear program.
    pub max_iterations: usize,
    /// Programs of the non-associative sequence (joints with dilatancy below friction); 0
    /// skips the sequence and reports the associative bound only.
    pub max_sequence: usize,
    /// The sequence has converged when lambda changes by less than this fraction between two
    /// programs.
    pub sequence_tolerance: f64,
    /// Threads of the interior point's passes over contacts and cones in 3D, from 2,000
    /// contacts (below, one); 0: all cores. The results are the same to the bit with any
    /// number. The plane's program runs on one.
    pub threads: usize,
}

impl Default for LimitOptions {
    fn default() -> Self {
        LimitOptions { tolerance: 1e-8, max_iterations: 200, max_sequence: 50, sequence_tolerance: 1e-6, threads: 0 }
    }
}

/// Reported after each interior-point iteration; the callback returns `false` to stop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimitProgress {
    /// The program of the non-associative sequence (0: the associative one).
    pub program: usize,
    /// Interior-point iterations so far.
    pub iteration: usize,
    /// The current estimate of lambda.
    pub multiplier: f64,
    /// The largest of the scaled residuals and the relative gap.
    pub residual: f64,
}

/// lambda beyond this many times the scale of the loads is reported as unbounded (no mechanism
/// within the range).
const LAMBDA_RANGE: f64 = 1e4;

/// An interior point whose residuals stop decreasing within this factor of the tolerance
/// gives its solution, with the residuals in its certificate.
const REDUCED_ACCURACY: f64 = 100.0;

/// Joints' strengths are capped at this many times the total load (dead plus live at
/// lambda = 1), beyond which no multiplier in the range reaches them.
const STRENGTH_CAP: f64 = 1e4;

/// Gondzio's centrality correctors per iteration, at most: one solve each against a
/// factorization per iteration. From a few hundred blocks four take fewer iterations than one: in
/// the plane 37 against 53 at 10^4 blocks (3.4-3.7 against 4.2 s); in 3D 45 against 55 at 1,785
/// blocks in the same time, 118 against 135 at 9,331 in 41 against 35 s.
const CORRECTORS: usize = 4;

/// Below this many equations one corrector: on walls of tens of blocks more correctors cost
/// more than they save (Ferris & Tin-Loi wall 2: 1.35 against 1.58 ms, 11 iterations both).
const CORRECTORS_FROM: usize = 500;

/// The corrector's centring weight sigma at most. Mehrotra's `(mu_aff / mu)^3` nears 1 where
/// the predictor's step is short, which mid-path on these programs it often is (0.02-0.4 at
/// 10^4 blocks: a few products whose variables change from nearly zero to large), and the
/// iteration then only centres; capped, it still makes progress and Gondzio's correctors keep
/// the products centred. Iterations with sigma at most 1 / 0.3 / 0.2 / 0.1: 10^5 blocks 83 / 71
/// / 64 / 71; 10^4 37 / 36 / 37 / 38; in 3D the 9,331-block facade 118 / 97 / 104 / 105 and the
/// 3,980-block U wall 50 / 45 / 41 / 41 (counts move by about 5 from rounding alone).
const SIGMA_MAX: f64 = 0.2;

/// Corrections of a search direction, at most (one solve each).
const REFINEMENTS: usize = 2;

/// A search direction meets the primal equation to this, relative to the right-hand side's
/// scale, and lambda's dual row to this: far below the tolerance...
const DIRECTION_ACCURACY: f64 = 1e-12;

/// ... or, where the residual is far above the tolerance ([`DIRECTION_FRACTION_ABOVE`]), to this
/// fraction of it: a step of length a along such a direction still removes at least 0.9 a of
/// the residual, and in the first iterations the direction's correction, a solve, is not
/// needed. Iterations with it and without: in the plane 36 and 36 at 10^4 blocks; in 3D 37 and
/// 37 on the 9,331-block facade, 42 and 42 on the 10,047-block one.
const DIRECTION_FRACTION: f64 = 0.1;

/// The residual (scaled as the tolerance is) above which a direction may miss by
/// [`DIRECTION_FRACTION`] of it. Near the optimum every direction is corrected in full: the last
/// iterations, which make the certificate, are as accurate as the solves allow.
const DIRECTION_FRACTION_ABOVE: f64 = 1e-6;

/// What fraction of its largest diagonal entry is added to the normal matrix's diagonal where
/// joints have no friction ([`Lp::regularize_frictionless`]): far above the rounding of its
/// entries (1e-16 of the largest), far below them.
const REGULARIZATION: f64 = 1e-10;

/// The largest `max_iterations` accepted.
pub const MAX_ITERATIONS: usize = 100_000;

/// Runs a limit analysis. Bad options are an `Err`; a program that could not be solved is a
/// `Results` with a status that says why.
pub fn limit_analysis(model: &Model, opts: &LimitOptions) -> Result<Results> {
    limit_analysis_with(model, opts, &mut |_| true)
}

/// Runs a limit analysis, calling `monitor` after each interior-point iteration (return
/// `false` to stop: the result is then an `Err(Error::Interrupted)`).
pub fn limit_analysis_with(
    model: &Model,
    opts: &LimitOptions,
    monitor: &mut dyn FnMut(&LimitProgress) -> bool,
) -> Result<Results> {
    analyse(model, opts, monitor, false)
}

/// [`limit_analysis_with`], with lambda of either sign when `signed` (a force on a moving
/// support: its optimum below zero is then a collapse, not a dead state out of equilibrium).
fn analyse(model: &Model, opts: &LimitOptions, monitor: &mut dyn FnMut(&LimitProgress) -> bool, signed: bool) -> Result<Results> {
    model.check_analysis_memory("a limit analysis")?;
    model.check_strength_range()?;
    validate(opts)?;
    model.check_supports()?;
    let start = Instant::now();
    let mut plane = Plane::new(model)?;
    plane.lp.signed = signed;
    let assoc = plane.lp.solve(opts, 0, monitor)?;
    let mut iterations = assoc.iterations;
    let non_assoc = (0..model.interfaces().len()).any(|k| {
        let l = model.law(k);
        l.dilatancy < l.friction
    });
    let mut cert = Certificate {
        multiplier: f64::NAN,
        primal_residual: assoc.primal,
        dual_residual: assoc.dual,
        duality_gap: assoc.gap,
        iterations: assoc.iterations,
        upper_bound: f64::NAN,
        sequence: 0,
        sequence_converged: false,
        peak_strengths: model.laws_are_strong(),
    };
    let mut sol = assoc;
    if sol.outcome == Outcome::Optimal && non_assoc && opts.max_sequence > 0 {
        cert.upper_bound = plane.lp.lambda_of(&sol);
        let mut prev = cert.upper_bound;
        for program in 1..=opts.max_sequence {
            // the normal forces of the last program fix each joint's shear capacity
            let normals: Vec<f64> = plane.resultants(&sol.x).iter().map(|s| s[0]).collect();
            plane.fix_shear_capacity(&normals);
            let next = plane.lp.solve(opts, program, monitor)?;
            iterations += next.iterations;
            cert.sequence = program;
            if next.outcome != Outcome::Optimal {
                sol = next;
                break;
            }
            let lam = plane.lp.lambda_of(&next);
            sol = next;
            if (lam - prev).abs() <= opts.sequence_tolerance * prev.abs().max(1e-12) {
                cert.sequence_converged = true;
                break;
            }
            prev = lam;
        }
        cert.primal_residual = sol.primal;
        cert.dual_residual = sol.dual;
        cert.duality_gap = sol.gap;
    }
    cert.iterations = iterations;
    let mut res = plane.results(model, &sol, cert, start);
    if let Some(c) = res.certificate.as_mut() {
        c.multiplier = res.collapse_multiplier;
    }
    if non_assoc && res.status == Status::Collapse {
        mark_estimate(&mut res);
    }
    Ok(res)
}

/// Labels the optimum of joints with dilatancy below friction for what it is: an `Estimate`.
/// The associative optimum is then an upper bound of the collapse multiplier only, and the
/// non-associative sequence a heuristic that is neither bound, converged or not (on Ferris and
/// Tin-Loi's walls 3 to 6 it lies up to 10% above the static solver's collapse). The value
/// moves to `last_equilibrium` (the program's forces balance the loads within the strength
/// domain of its last shear capacities); `collapse_multiplier` is NaN, as for every status but
/// a collapse; `error` says what the number is, with the certificate's upper bound and
/// convergence.
fn mark_estimate<V>(res: &mut Results<V>) {
    let lam = res.collapse_multiplier;
    let Some(c) = res.certificate else { return };
    let how = if c.sequence == 0 {
        "the associative upper bound alone (no non-associative sequence was run)".to_string()
    } else {
        format!(
            "the non-associative sequence's value after {} program{} ({}; the associative upper bound is {:.6})",
            c.sequence,
            if c.sequence == 1 { "" } else { "s" },
            if c.sequence_converged { "converged" } else { "not converged" },
            c.upper_bound
        )
    };
    res.status = Status::Estimate;
    res.collapse_multiplier = f64::NAN;
    res.last_equilibrium = lam;
    res.error = Some(format!(
        "joints with dilatancy below friction: lambda = {lam:.6} is an estimate, {how}, neither a lower nor an upper bound of the collapse multiplier (run the static or explicit solver for it)"
    ));
}

fn validate(opts: &LimitOptions) -> Result<()> {
    if !(opts.tolerance.is_finite() && opts.tolerance > 0.0 && opts.tolerance < 1e-2) {
        return Err(Error::input(format!(
            "analysis.tolerance must lie in (0, 0.01) for a limit analysis, got {}",
            opts.tolerance
        )));
    }
    if opts.max_iterations == 0 || opts.max_iterations > MAX_ITERATIONS {
        return Err(Error::input(format!(
            "analysis.max_iterations must lie in 1..={MAX_ITERATIONS}, got {}",
            opts.max_iterations
        )));
    }
    if opts.threads > crate::explicit::MAX_THREADS {
        return Err(Error::input(format!(
            "analysis.threads = {} is more than the limit of {}",
            opts.threads,
            crate::explicit::MAX_THREADS
        )));
    }
    if !(opts.sequence_tolerance.is_finite() && opts.sequence_tolerance > 0.0) {
        return Err(Error::input(format!(
            "the sequence tolerance must be a finite number > 0, got {}",
            opts.sequence_tolerance
        )));
    }
    Ok(())
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Outcome {
    Optimal,
    /// lambda reached the top of its range
    Unbounded,
    /// no equilibrium under the dead loads at any lambda in range (a dual ray)
    Infeasible,
    /// the iterations ran out or stalled
    NotConverged,
}

/// An interior-point solution, in scaled units.
struct Solution {
    outcome: Outcome,
    /// the variables: five per interface (four rays, theta)
    x: Vec<f64>,
    lambda: f64,
    /// duals of the equilibrium rows (one per equation)
    y: Vec<f64>,
    primal: f64,
    dual: f64,
    gap: f64,
    iterations: usize,
}

mod cone;
mod follow;
mod ipm;
mod movement;
mod outcome;
mod plane;
mod program;
mod space;

use ipm::*;
use plane::*;
use program::*;
pub use follow::{follow_mechanism, follow_mechanism_3d, FollowOptions, MAX_FOLLOW_STEPS};
pub use movement::follow_movement;
pub use space::{limit_analysis_3d, limit_analysis_3d_with};
