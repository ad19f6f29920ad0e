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
//! forces (Gilbert, Casapulla & Ahmed, 2006). That estimate is a heuristic, neither bound.
//!
//! The method: Mehrotra's predictor-corrector on the program scaled to forces of order one
//! (moments carried as `2 M / l`, rotation rows divided by a length), in standard form: each
//! interface's resultants are a point of its strength domain written with non-negative
//! variables (the four rays of two contact points, and the segment between the domain's two
//! vertices for joints with strength). Each iteration solves the normal equations
//! `A Theta A^T dy = r`, whose matrix is assembled exactly as the stiffness matrix is (one 3 x 3
//! block per interface, on the same pattern) and factorized by the crate's `linalg` module (LDL^T on the
//! sparse Cholesky's symbolic analysis, which is done once), each solve refined twice on the
//! exact operator. lambda, a free variable, borders the system: two solves with one
//! factorization. The dual variables of the equilibrium rows are the block velocities of the
//! collapse mechanism.
//!
//! ```
//! use masonry_dem::geometry::{running_bond, RunningBond, FirstCourse};
//! use masonry_dem::joint::JointLaw;
//! use masonry_dem::limit::{limit_analysis, LimitOptions};
//! use masonry_dem::model::{JointLaws, Model, ModelSpec};
//!
//! let blocks = running_bond(&RunningBond { block_length: 0.4, block_height: 0.175, courses: 6,
//!     length: 2.0, first_course: FirstCourse::Half, openings: vec![] }).unwrap();
//! let law = JointLaw { friction: 0.65, dilatancy: 0.65, ..JointLaw::default() };
//! let model = Model::new(ModelSpec { blocks, gravity: 10.0, joints: JointLaws::uniform(law),
//!     ..ModelSpec::default() }).unwrap();
//! let res = limit_analysis(&model, &LimitOptions::default()).unwrap();
//! assert!((res.collapse_multiplier - 0.642857).abs() < 1e-5);
//! ```

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
}

impl Default for LimitOptions {
    fn default() -> Self {
        LimitOptions { tolerance: 1e-8, max_iterations: 200, max_sequence: 50, sequence_tolerance: 1e-6 }
    }
}

/// Reported after each interior-point iteration; the callback returns `false` to stop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimitProgress {
    /// The program of the non-associative sequence (0: the associative one).
    pub program: usize,
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

/// Gondzio's centrality correctors per iteration, at most: more cut iterations but not time
/// (BENCHMARKS.md).
const CORRECTORS: usize = 1;

/// Steps of iterative refinement of a solve of the normal equations, at most.
const REFINEMENTS: usize = 2;

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
    model.check_analysis_memory("a limit analysis")?;
    model.check_strength_range()?;
    validate(opts)?;
    model.check_supports()?;
    let start = Instant::now();
    let mut lp = Program::new(model)?;
    let assoc = lp.solve(opts, 0, monitor)?;
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
        cert.upper_bound = lp.lambda_of(&sol);
        let mut prev = cert.upper_bound;
        for program in 1..=opts.max_sequence {
            // the normal forces of the last program fix each joint's shear capacity
            let normals: Vec<f64> = lp.resultants(&sol.x).iter().map(|s| s[0]).collect();
            lp.fix_shear_capacity(&normals);
            let next = lp.solve(opts, program, monitor)?;
            iterations += next.iterations;
            cert.sequence = program;
            if next.outcome != Outcome::Optimal {
                sol = next;
                break;
            }
            let lam = lp.lambda_of(&next);
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
    let mut res = lp.results(model, &sol, cert, start);
    if let Some(c) = res.certificate.as_mut() {
        c.multiplier = res.collapse_multiplier;
    }
    Ok(res)
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

/// The linear program of a model, scaled, in standard form: each interface's resultants are
/// `s = V + sum_j rho_j R_j + theta dV` with `rho >= 0`, `0 <= theta <= 1`: the strength
/// domain's recession cone has four rays `R_j = (-1, +-a, +-1)` (in (N, T, 2M/l); a: the Coulomb
/// slope; the rays of two contact points at the interface's ends), and its vertices are the
/// two ends `V`, `V + dV` of one segment (equal for joints without strength).
struct Program {
    m: usize,
    n: usize,
    /// equation of each dof, or None for a support
    eq: Vec<Option<usize>>,
    /// per interface: the 6 equations of its dofs (NO_EQ: a support)
    dofs: Vec<[u32; 6]>,
    /// per interface: its 6 x 3 block of the equilibrium matrix, scaled (columns N, T, 2M/l)
    cols: Vec<[[f64; 3]; 6]>,
    /// per interface: its 6 x 5 block of the standard form's equilibrium matrix (`columns`),
    /// kept while the faces do not change: the interior point's products read it many times
    acols: Vec<[[f64; NV]; 6]>,
    /// the value slots of each interface's 6 x 6 block in the normal matrix
    slots: Vec<[u32; 36]>,
    /// the faces' right-hand sides of each interface over the force scale: Coulomb (c A, or
    /// the capacity fixed in the non-associative sequence) and tension (ft A); the Coulomb slope
    hc: Vec<f64>,
    ht: Vec<f64>,
    slope: Vec<f64>,
    /// the strength domain's own (c A over the force scale, mu, tan(psi)) of each interface
    coulomb: Vec<(f64, f64, f64)>,
    f_dead: Vec<f64>,
    f_live: Vec<f64>,
    /// scales: forces, lengths (rotation rows), the live load
    force: f64,
    length: f64,
    live: f64,
    normal: SparseLu,
}

const NO_EQ: u32 = u32::MAX;

/// Variables per interface: four rays and the position on the vertices' segment.
const NV: usize = 5;

/// The vertex `V`, the segment `dV` and the four rays of a domain
/// `a N +- T <= hc`, `N +- 2M/l <= ht` (scaled).
fn generators(a: f64, hc: f64, ht: f64) -> [[f64; 3]; 6] {
    let (v, dv) = if a * ht <= hc {
        // the cut-off N = ht meets the Coulomb faces at T = +-(hc - a ht)
        let t = hc - a * ht;
        ([ht, -t, 0.0], [0.0, 2.0 * t, 0.0])
    } else {
        // the Coulomb faces meet at N = hc / a below the cut-off, M within the rocking faces
        let nc = hc / a;
        ([nc, 0.0, -(ht - nc)], [0.0, 0.0, 2.0 * (ht - nc)])
    };
    [v, dv, [-1.0, a, 1.0], [-1.0, -a, 1.0], [-1.0, a, -1.0], [-1.0, -a, -1.0]]
}

impl Program {
    fn new(model: &Model) -> Result<Self> {
        let nb = model.n_blocks();
        let mut support = model.fixed().to_vec();
        for &d in model.held_after_dead() {
            support[d] = true;
        }
        let mut eq = vec![None; 3 * nb];
        let mut n = 0;
        for (d, e) in eq.iter_mut().enumerate() {
            if !support[d] {
                *e = Some(n);
                n += 1;
            }
        }
        let its = model.interfaces();
        let m = its.len();
        // scales: the largest dead force, the mean interface length, the largest live force
        let (fd, fl) = (model.dead_load(), model.live_load());
        let trans = |v: &[f64]| (0..nb).flat_map(|i| [v[3 * i].abs(), v[3 * i + 1].abs()]).fold(0.0, f64::max);
        let live_max = trans(fl).max((0..nb).map(|i| fl[3 * i + 2].abs()).fold(0.0, f64::max));
        let mut force = trans(fd);
        if force <= 0.0 {
            force = if live_max > 0.0 { live_max } else { 1.0 };
        }
        let length = its.iter().map(|it| it.l).sum::<f64>() / m.max(1) as f64;
        let length = if length > 0.0 { length } else { 1.0 };
        let live = if live_max > 0.0 { live_max } else { 1.0 };
        let row_scale = |d: usize| if d % 3 == 2 { 1.0 / length } else { 1.0 };
        let (mut dofs, mut cols) = (Vec::with_capacity(m), Vec::with_capacity(m));
        let (mut hc, mut ht, mut coulomb) = (Vec::with_capacity(m), Vec::with_capacity(m), Vec::with_capacity(m));
        let sections = model.sections();
        for (k, it) in its.iter().enumerate() {
            let gd = it.dofs();
            let mut d6 = [NO_EQ; 6];
            let mut c6 = [[0.0; 3]; 6];
            for r in 0..6 {
                d6[r] = eq[gd[r]].map_or(NO_EQ, |e| e as u32);
                let s = row_scale(gd[r]);
                c6[r] = [it.b_mat[0][r] * s, it.b_mat[1][r] * s, it.b_mat[2][r] * s * 0.5 * it.l];
            }
            dofs.push(d6);
            cols.push(c6);
            let law = model.law(k);
            let (c, ft) = law.strengths(&JointState::default());
            let a = sections[k].area;
            hc.push(c * a / force);
            ht.push(ft * a / force);
            coulomb.push((c * a / force, law.friction, law.dilatancy));
        }
        // strengths beyond STRENGTH_CAP times the total load cannot be reached within lambda's
        // range: they are capped there (a glued joint), which keeps the program well scaled
        let total = (0..3 * nb).filter(|&d| eq[d].is_some()).map(|d| (fd[d] / force).abs() + (fl[d] / live).abs()).sum::<f64>();
        let cap = STRENGTH_CAP * total.max(1.0);
        hc.iter_mut().chain(ht.iter_mut()).for_each(|h| *h = h.min(cap));
        coulomb.iter_mut().for_each(|c| c.0 = c.0.min(cap));
        let free = |d: &usize| eq[*d].is_some();
        let f_dead = (0..3 * nb).filter(free).map(|d| fd[d] * row_scale(d) / force).collect();
        let f_live = (0..3 * nb).filter(free).map(|d| fl[d] * row_scale(d) / live).collect();
        let mut entries = Vec::with_capacity(36 * m);
        for d6 in &dofs {
            for &r in d6.iter().filter(|&&r| r != NO_EQ) {
                for &c in d6.iter().filter(|&&c| c != NO_EQ) {
                    entries.push((r as usize, c as usize));
                }
            }
        }
        let normal = SparseLu::new(n, entries)?;
        let slots = dofs
            .iter()
            .map(|d6| {
                let mut s = [u32::MAX; 36];
                for (i, &r) in d6.iter().enumerate() {
                    for (j, &c) in d6.iter().enumerate() {
                        if r != NO_EQ && c != NO_EQ {
                            s[6 * i + j] = normal.slot(r as usize, c as usize).expect("in the pattern") as u32;
                        }
                    }
                }
                s
            })
            .collect();
        let slope = coulomb.iter().map(|c| c.1).collect();
        let mut lp = Program { m, n, eq, dofs, cols, acols: vec![], slots, hc, ht, slope, coulomb, f_dead, f_live, force, length, live, normal };
        lp.acols = (0..m).map(|k| lp.columns(k).0).collect();
        Ok(lp)
    }

    /// lambda in its own units from a scaled solution.
    fn lambda_of(&self, s: &Solution) -> f64 {
        s.lambda * self.force / self.live
    }

    /// Fixes the Coulomb faces' capacity from normal forces (scaled), for the non-associative
    /// sequence: `|T| + tan(psi) N <= c A - (mu - tan(psi)) N_prev`.
    fn fix_shear_capacity(&mut self, normals: &[f64]) {
        for (k, &(ca, mu, tp)) in self.coulomb.iter().enumerate() {
            self.hc[k] = (ca - (mu - tp) * normals[k]).max(0.0);
            self.slope[k] = tp;
        }
        self.acols = (0..self.m).map(|k| self.columns(k).0).collect();
    }

    /// The columns of interface k in the scaled equilibrium matrix (6 rows x 5 variables), and
    /// its vertex's contribution `P V` (6 rows).
    #[inline]
    fn columns(&self, k: usize) -> ([[f64; NV]; 6], [f64; 6]) {
        let g = generators(self.slope[k], self.hc[k], self.ht[k]);
        let c6 = &self.cols[k];
        let mut a = [[0.0; NV]; 6];
        let mut pv = [0.0; 6];
        for r in 0..6 {
            let c = c6[r];
            let p = |v: [f64; 3]| c[0] * v[0] + c[1] * v[1] + c[2] * v[2];
            pv[r] = p(g[0]);
            a[r] = [p(g[2]), p(g[3]), p(g[4]), p(g[5]), p(g[1])];
        }
        (a, pv)
    }

    /// The interfaces' resultants (scaled) of the variables.
    fn resultants(&self, x: &[f64]) -> Vec<[f64; 3]> {
        (0..self.m)
            .map(|k| {
                let g = generators(self.slope[k], self.hc[k], self.ht[k]);
                let xk = &x[NV * k..NV * k + NV];
                let mut s = g[0];
                for (j, gj) in [g[2], g[3], g[4], g[5], g[1]].iter().enumerate() {
                    for i in 0..3 {
                        s[i] += xk[j] * gj[i];
                    }
                }
                s
            })
            .collect()
    }
}

fn norm_inf(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The largest step in (0, 1] that keeps `v + a dv >= 0`.
fn max_step(v: &[f64], dv: &[f64]) -> f64 {
    v.iter().zip(dv).fold(1.0, |a, (&x, &d)| if d < 0.0 { a.min(-x / d) } else { a })
}

/// The interior point's iterate. Variables: five per interface (the last, theta, bounded by
/// 1) and lambda (free); `t`, `v`: theta's upper bounds' slacks and multipliers.
struct Iterate {
    x: Vec<f64>,
    lam: f64,
    s: Vec<f64>,
    t: Vec<f64>,
    v: Vec<f64>,
    y: Vec<f64>,
}

/// A search direction.
struct Direction {
    dx: Vec<f64>,
    ds: Vec<f64>,
    dt: Vec<f64>,
    dv: Vec<f64>,
    dy: Vec<f64>,
    dlam: f64,
}

/// The residuals of an iterate: equilibrium, the variables' dual rows, theta's bounds, and
/// lambda's dual row.
struct Residuals {
    rb: Vec<f64>,
    rc: Vec<f64>,
    ru: Vec<f64>,
    rl: f64,
}

impl Program {
    /// The variable bounded by `t[i]`: interface i's theta.
    #[inline]
    fn bounded(&self, i: usize) -> usize {
        NV * i + 4
    }

    /// `A x + lam (-f_live)` (equilibrium of the variables) into `out`.
    fn apply(&self, x: &[f64], lam: f64, out: &mut [f64]) {
        for (o, f) in out.iter_mut().zip(&self.f_live) {
            *o = -f * lam;
        }
        for k in 0..self.m {
            let a = &self.acols[k];
            let xk = &x[NV * k..NV * k + NV];
            for (r, &d) in self.dofs[k].iter().enumerate() {
                if d != NO_EQ {
                    out[d as usize] += (0..NV).map(|j| a[r][j] * xk[j]).sum::<f64>();
                }
            }
        }
    }

    /// `A^T y` into `out` (lambda's row, `-f_live . y`, left out).
    fn apply_t(&self, y: &[f64], out: &mut [f64]) {
        for k in 0..self.m {
            let a = &self.acols[k];
            let o = &mut out[NV * k..NV * k + NV];
            o.fill(0.0);
            for (r, &d) in self.dofs[k].iter().enumerate() {
                if d != NO_EQ {
                    let yv = y[d as usize];
                    for j in 0..NV {
                        o[j] += a[r][j] * yv;
                    }
                }
            }
        }
    }

    /// Solves the scaled program by Mehrotra's predictor-corrector from a fixed start.
    fn solve(
        &mut self,
        opts: &LimitOptions,
        program: usize,
        monitor: &mut dyn FnMut(&LimitProgress) -> bool,
    ) -> Result<Solution> {
        let (m, n) = (self.m, self.n);
        let nx = NV * m;
        let range = LAMBDA_RANGE;
        // b = f_dead - sum P V; the cost is -lambda (lambda free, its own column -f_live)
        let mut b = self.f_dead.clone();
        for k in 0..m {
            let (_, pv) = self.columns(k);
            for (r, &d) in self.dofs[k].iter().enumerate() {
                if d != NO_EQ {
                    b[d as usize] -= pv[r];
                }
            }
        }
        let b_norm = norm_inf(&b);
        // the start: the rays of least norm that balance the dead loads at lambda = 0 (one
        // solve with Theta = 1), shifted inside the positive orthant; theta = 1/2; each
        // product x s, t v = 1
        let mut x = vec![1.0; nx];
        self.assemble(&x);
        let mut w = b.clone();
        if self.normal.factorize().is_ok() && self.normal.solve_in_place(&mut w).is_ok() {
            self.apply_t(&w, &mut x);
            let shift = (0.1 * norm_inf(&x)).max(1.0);
            x.iter_mut().for_each(|x| *x = x.max(0.0) + shift);
        } else {
            x.fill(1.0);
        }
        for k in 0..m {
            x[NV * k + 4] = 0.5;
        }
        let mut p = Iterate {
            s: x.iter().map(|x| 1.0 / x).collect(),
            v: vec![2.0; m],
            t: vec![0.5; m],
            x,
            lam: 0.0,
            y: vec![0.0; n],
        };
        let mut res = Residuals { rb: vec![0.0; n], rc: vec![0.0; nx], ru: vec![0.0; m], rl: 0.0 };
        let mut theta = vec![0.0; nx];
        let mut u = vec![0.0; n];
        let mut aty = vec![0.0; nx];
        let (mut best, mut since_best) = (f64::INFINITY, 0);
        let ncomp = (nx + m) as f64;
        for iter in 0..=opts.max_iterations {
            self.apply(&p.x, p.lam, &mut res.rb);
            for (r, b) in res.rb.iter_mut().zip(&b) {
                *r = b - *r;
            }
            self.apply_t(&p.y, &mut aty);
            for ((rc, a), s) in res.rc.iter_mut().zip(&aty).zip(&p.s) {
                *rc = -a - s;
            }
            for i in 0..m {
                let j = self.bounded(i);
                res.rc[j] += p.v[i];
                res.ru[i] = 1.0 - p.x[j] - p.t[i];
            }
            // lambda's dual row: -1 + f_live . y = 0
            res.rl = -1.0 + dot(&self.f_live, &p.y);
            let mu = (dot(&p.x, &p.s) + dot(&p.t, &p.v)) / ncomp;
            let lam = p.lam;
            let primal = (norm_inf(&res.rb) / (1.0 + b_norm)).max(norm_inf(&res.ru));
            let dual = norm_inf(&res.rc).max(res.rl.abs());
            // objectives: primal -lambda, dual b y - v (theta's bounds are 1)
            let dobj = dot(&b, &p.y) - p.v.iter().sum::<f64>();
            let gap = (-lam - dobj).abs() / (1.0 + lam.abs());
            let worst = primal.max(dual).max(gap);
            if !monitor(&LimitProgress { program, iteration: iter, multiplier: lam * self.force / self.live, residual: worst }) {
                return Err(Error::Interrupted);
            }
            // the dual iterates running away along a ray while equilibrium stays violated: the
            // sign of a program without a feasible point, if the iterations end here
            // lambda running away beyond its range: the live load finds no mechanism
            let failed = if norm_inf(&p.y) > 1e12 && primal > 1e-3 {
                Outcome::Infeasible
            } else if lam > range {
                Outcome::Unbounded
            } else {
                Outcome::NotConverged
            };
            let done = |outcome| Solution {
                outcome,
                x: p.x.clone(),
                lambda: lam,
                y: p.y.clone(),
                primal,
                dual,
                gap,
                iterations: iter,
            };
            if lam > range * range || (lam > range && primal <= opts.tolerance) {
                return Ok(done(Outcome::Unbounded));
            }
            if worst <= opts.tolerance {
                return Ok(done(Outcome::Optimal));
            }
            // a dual point of objective above the range bounds lambda below -range: no
            // multiplier in the range balances the dead loads
            if dual <= 1e-8 && dobj > range {
                return Ok(done(Outcome::Infeasible));
            }
            if worst < 0.5 * best {
                best = worst;
                since_best = 0;
            } else {
                since_best += 1;
            }
            // stalled: rounding bounds the residuals above the tolerance. Within
            // REDUCED_ACCURACY times it the solution stands (its certificate says how close it
            // is); a long stall or the last iteration far from it is a failure
            let near = worst <= REDUCED_ACCURACY * opts.tolerance;
            if near && since_best >= 5 {
                return Ok(done(Outcome::Optimal));
            }
            if iter == opts.max_iterations || since_best >= 30 || !worst.is_finite() {
                return Ok(done(if near { Outcome::Optimal } else { failed }));
            }
            // Theta = 1 / (s / x + v / t), and the normal matrix A Theta A^T (lambda's column
            // apart: the system is bordered)
            for ((th, s), x) in theta.iter_mut().zip(&p.s).zip(&p.x) {
                *th = s / x;
            }
            for i in 0..m {
                theta[self.bounded(i)] += p.v[i] / p.t[i];
            }
            theta.iter_mut().for_each(|t| *t = 1.0 / *t);
            self.assemble(&theta);
            // LDL^T on the Cholesky's analysis: the matrix is positive semi-definite, but near
            // the optimum Theta spans 1e-12 to 1e12 and rounding leaves pivots of either sign
            // that a Cholesky refuses (the solves' refinement corrects for them); where a pivot
            // is zero, or a solve not finite, LU with pivoting
            let mut solved = false;
            for lu in [false, true] {
                let ok = if lu { self.normal.factorize().is_ok() } else { self.normal.factorize_ldlt().is_ok() };
                u.copy_from_slice(&self.f_live);
                if ok && self.solve_normal(&theta, &mut u).is_some() {
                    solved = true;
                    break;
                }
            }
            if !solved {
                return Ok(done(failed));
            }
            let fu = dot(&self.f_live, &u);
            // predictor
            let rxs: Vec<f64> = p.x.iter().zip(&p.s).map(|(x, s)| -x * s).collect();
            let rtv: Vec<f64> = p.t.iter().zip(&p.v).map(|(t, v)| -t * v).collect();
            let Some(aff) = self.direction(&p, &res, &rxs, &rtv, &theta, &u, fu) else {
                return Ok(done(failed));
            };
            let ap = max_step(&p.x, &aff.dx).min(max_step(&p.t, &aff.dt));
            let ad = max_step(&p.s, &aff.ds).min(max_step(&p.v, &aff.dv));
            let comp = |a: &[f64], da: &[f64], b: &[f64], db: &[f64]| {
                a.iter().zip(da).zip(b.iter().zip(db)).map(|((a, da), (b, db))| (a + ap * da) * (b + ad * db)).sum::<f64>()
            };
            let mu_aff = (comp(&p.x, &aff.dx, &p.s, &aff.ds) + comp(&p.t, &aff.dt, &p.v, &aff.dv)) / ncomp;
            let sigma = (mu_aff / mu).powi(3).min(1.0);
            // corrector
            let rxs: Vec<f64> = (0..nx).map(|i| sigma * mu - p.x[i] * p.s[i] - aff.dx[i] * aff.ds[i]).collect();
            let rtv: Vec<f64> = (0..m).map(|i| sigma * mu - p.t[i] * p.v[i] - aff.dt[i] * aff.dv[i]).collect();
            let Some(mut d) = self.direction(&p, &res, &rxs, &rtv, &theta, &u, fu) else {
                return Ok(done(failed));
            };
            // Gondzio's centrality correctors: aim a longer step at products within [0.1, 10]
            // of the target, where the predictor-corrector's step left them outside; kept while
            // they lengthen the step (one solve each, against a factorization per iteration)
            let steps = |d: &Direction| {
                (max_step(&p.x, &d.dx).min(max_step(&p.t, &d.dt)), max_step(&p.s, &d.ds).min(max_step(&p.v, &d.dv)))
            };
            let (mut rxs, mut rtv) = (rxs, rtv);
            let target = sigma * mu;
            for _ in 0..CORRECTORS {
                let (ap, ad) = steps(&d);
                if ap.min(ad) >= 0.9 {
                    break;
                }
                let (ap_t, ad_t) = ((1.5 * ap + 0.1).min(1.0), (1.5 * ad + 0.1).min(1.0));
                let fix = |v: f64| {
                    let c = v.clamp(0.1 * target, 10.0 * target) - v;
                    c.max(-10.0 * target)
                };
                let rxs2: Vec<f64> = (0..nx).map(|i| rxs[i] + fix((p.x[i] + ap_t * d.dx[i]) * (p.s[i] + ad_t * d.ds[i]))).collect();
                let rtv2: Vec<f64> = (0..m).map(|i| rtv[i] + fix((p.t[i] + ap_t * d.dt[i]) * (p.v[i] + ad_t * d.dv[i]))).collect();
                let Some(d2) = self.direction(&p, &res, &rxs2, &rtv2, &theta, &u, fu) else {
                    break;
                };
                let (ap2, ad2) = steps(&d2);
                if ap2 + ad2 < 1.01 * (ap + ad) {
                    break;
                }
                d = d2;
                rxs = rxs2;
                rtv = rtv2;
            }
            let eta = 0.995;
            let ap = (eta * max_step(&p.x, &d.dx).min(max_step(&p.t, &d.dt))).min(1.0);
            let ad = (eta * max_step(&p.s, &d.ds).min(max_step(&p.v, &d.dv))).min(1.0);
            let step = |v: &mut [f64], dv: &[f64], a: f64| v.iter_mut().zip(dv).for_each(|(v, d)| *v += a * d);
            step(&mut p.x, &d.dx, ap);
            step(&mut p.t, &d.dt, ap);
            p.lam += ap * d.dlam;
            step(&mut p.s, &d.ds, ad);
            step(&mut p.v, &d.dv, ad);
            step(&mut p.y, &d.dy, ad);
        }
        unreachable!("the loop returns at its last iteration")
    }

    /// Assembles `sum_k A_k Theta_k A_k^T` (lambda's column left out).
    fn assemble(&mut self, theta: &[f64]) {
        self.normal.values_mut().fill(0.0);
        for k in 0..self.m {
            let a = &self.acols[k];
            let th = &theta[NV * k..NV * k + NV];
            let slots = self.slots[k];
            let vals = self.normal.values_mut();
            for i in 0..6 {
                if slots[6 * i + i] == u32::MAX {
                    continue;
                }
                let ai: [f64; NV] = std::array::from_fn(|j| a[i][j] * th[j]);
                for j in i..6 {
                    let s = slots[6 * i + j];
                    if s == u32::MAX {
                        continue;
                    }
                    let v: f64 = (0..NV).map(|q| ai[q] * a[j][q]).sum();
                    vals[s as usize] += v;
                    if j != i {
                        vals[slots[6 * j + i] as usize] += v;
                    }
                }
            }
        }
    }

    /// Solves `A Theta A^T z = r` in place with the factorization, refined on the exact operator
    /// (applied as `A (Theta (A^T z))`, without the matrix, for far less than a solve) while the
    /// residual exceeds 1e-10 of `r`, at most [`REFINEMENTS`] times: near the optimum rounding
    /// leaves tiny pivots, and the primal residual would stall without it.
    fn solve_normal(&mut self, theta: &[f64], r: &mut [f64]) -> Option<()> {
        let rhs = r.to_vec();
        let norm = norm_inf(&rhs);
        self.normal.solve_in_place(r).ok()?;
        let mut t = vec![0.0; theta.len()];
        let mut az = vec![0.0; self.n];
        for _ in 0..REFINEMENTS {
            self.apply_t(r, &mut t);
            t.iter_mut().zip(theta).for_each(|(t, th)| *t *= th);
            self.apply(&t, 0.0, &mut az);
            for (a, b) in az.iter_mut().zip(&rhs) {
                *a = b - *a;
            }
            if norm_inf(&az) <= 1e-10 * norm {
                break;
            }
            self.normal.solve_in_place(&mut az).ok()?;
            r.iter_mut().zip(&az).for_each(|(r, c)| *r += c);
        }
        Some(())
    }

    /// The Newton direction for the complementarity targets `rxs` (x s) and `rtv` (t v), with
    /// the normal matrix factorized and `u = M^-1 f_live`; None if a solve fails.
    ///
    /// With `Theta = 1 / (s / x + v / t)` and `xi = rc - rxs / x + (rtv - v ru) / t`:
    /// `dx = Theta (A^T dy - xi)`, `M dy - f_live dlam = rb + A Theta xi` (M = A Theta A^T) and
    /// lambda's dual row `-f_live . dy = rl`: `dy = M^-1 (q + f_live dlam)`, one solve and `u`.
    #[allow(clippy::too_many_arguments)]
    fn direction(
        &mut self,
        p: &Iterate,
        res: &Residuals,
        rxs: &[f64],
        rtv: &[f64],
        theta: &[f64],
        u: &[f64],
        fu: f64,
    ) -> Option<Direction> {
        let m = self.m;
        let nx = theta.len();
        let mut xi: Vec<f64> = (0..nx).map(|i| res.rc[i] - rxs[i] / p.x[i]).collect();
        for i in 0..m {
            xi[self.bounded(i)] += (rtv[i] - p.v[i] * res.ru[i]) / p.t[i];
        }
        let txi: Vec<f64> = theta.iter().zip(&xi).map(|(t, x)| t * x).collect();
        let mut q = vec![0.0; self.n];
        self.apply(&txi, 0.0, &mut q);
        for (q, r) in q.iter_mut().zip(&res.rb) {
            *q += r;
        }
        self.solve_normal(theta, &mut q)?;
        // -f . (q + u dlam) = rl
        let dlam = -(res.rl + dot(&self.f_live, &q)) / fu;
        let dy: Vec<f64> = q.iter().zip(u).map(|(q, u)| q + dlam * u).collect();
        let mut dx = vec![0.0; nx];
        self.apply_t(&dy, &mut dx);
        for i in 0..nx {
            dx[i] = theta[i] * (dx[i] - xi[i]);
        }
        let ds: Vec<f64> = (0..nx).map(|i| (rxs[i] - p.s[i] * dx[i]) / p.x[i]).collect();
        let dt: Vec<f64> = (0..m).map(|i| res.ru[i] - dx[self.bounded(i)]).collect();
        let dv: Vec<f64> = (0..m).map(|i| (rtv[i] - p.v[i] * dt[i]) / p.t[i]).collect();
        let ok = dx.iter().chain(&dy).chain(&ds).chain(&dv).all(|v| v.is_finite()) && dlam.is_finite();
        ok.then_some(Direction { dx, ds, dt, dv, dy, dlam })
    }
}

impl Program {
    /// The results of a solution: the multiplier, the forces at collapse, the mechanism from
    /// the duals and the joints it moves.
    fn results(&self, model: &Model, sol: &Solution, cert: Certificate, start: Instant) -> Results {
        let nb = model.n_blocks();
        let lam = self.lambda_of(sol);
        // lambda below zero beyond the program's precision: the dead state is not admissible
        let negative = lam < -1e-7 * (self.force / self.live);
        let (status, error) = match sol.outcome {
            Outcome::Optimal if negative => (
                Status::NoEquilibrium,
                Some(format!(
                    "no equilibrium under the dead loads: the largest admissible multiplier is {lam:.6e} < 0 (the wall stands only if pushed the other way)"
                )),
            ),
            Outcome::Optimal => (Status::Collapse, None),
            Outcome::Unbounded => (
                Status::Unbounded,
                Some(format!(
                    "lambda grows beyond {:e}, the analysis's range: the live load finds no mechanism (check the strengths and the supports: a support that holds a block's position, such as a top beam held vertically, forbids the dilatancy of associative sliding)",
                    LAMBDA_RANGE * self.force / self.live
                )),
            ),
            Outcome::Infeasible => (
                Status::NoEquilibrium,
                Some(format!(
                    "no equilibrium under the dead loads: no admissible interface forces balance them at any multiplier (the dual iterates grow along a ray; equilibrium residual {:.1e} of the loads)",
                    sol.primal
                )),
            ),
            Outcome::NotConverged => (
                Status::Failed,
                Some(format!(
                    "the interior point did not converge in {} iterations (scaled residuals: primal {:.1e}, dual {:.1e}, gap {:.1e})",
                    sol.iterations, sol.primal, sol.dual, sol.gap
                )),
            ),
        };
        let collapse = status == Status::Collapse;
        // block velocities from the duals of the equilibrium rows (scaled rows: one length for
        // the rotations), oriented so that the live load does positive work, largest block
        // translation 1
        let mut v = vec![0.0; 3 * nb];
        if collapse {
            for (dof, e) in self.eq.iter().enumerate() {
                if let Some(e) = e {
                    let s = if dof % 3 == 2 { 1.0 / self.length } else { 1.0 };
                    v[dof] = sol.y[*e] * s;
                }
            }
            let big = (0..nb).map(|i| v[3 * i].hypot(v[3 * i + 1])).fold(0.0, f64::max);
            let work = dot(&v, model.live_load());
            let scale = if big > 0.0 { work.signum() / big } else { 0.0 };
            v.iter_mut().for_each(|x| *x *= scale);
        }
        let sigma = self.resultants(&sol.x);
        let its = model.interfaces();
        let mut forces = Vec::with_capacity(self.m);
        let mut flags = Vec::with_capacity(self.m);
        for (k, it) in its.iter().enumerate() {
            let s = sigma[k];
            forces.push([s[0] * self.force, s[1] * self.force, s[2] * self.force * 0.5 * it.l]);
            flags.push(if collapse { mechanism_flags(it, &v, self.slope[k]) } else { 0 });
        }
        Results {
            method: "limit",
            status,
            error,
            collapse_multiplier: if collapse { lam } else { f64::NAN },
            last_equilibrium: if collapse { lam } else { f64::NAN },
            curve_multiplier: vec![],
            curve_displacement: vec![],
            control_block: model.default_control_block(),
            displacements: vec![[0.0; 3]; nb],
            mechanism: (0..nb).map(|i| [v[3 * i], v[3 * i + 1], v[3 * i + 2]]).collect(),
            interface_forces: forces,
            interface_states: flags,
            broken: vec![false; self.m],
            iterations: cert.iterations,
            steps: 0,
            elapsed_s: start.elapsed().as_secs_f64(),
            certificate: Some(cert),
        }
    }
}

/// The joint states that a mechanism's velocities `v` (largest block translation 1) give an
/// interface: open where both ends separate beyond the dilatancy of the slip, sliding where it
/// slips, rocking where its ends separate unequally; motions below 1e-6 are rest.
fn mechanism_flags(it: &crate::interface::Interface, v: &[f64], slope: f64) -> u8 {
    let dofs = it.dofs();
    let e: [f64; 3] = std::array::from_fn(|r| (0..6).map(|c| it.b_mat[r][c] * v[dofs[c]]).sum());
    let tol = 1e-6;
    let dil = slope * e[1].abs();
    let g1 = e[0] - 0.5 * it.l * e[2] - dil;
    let g2 = e[0] + 0.5 * it.l * e[2] - dil;
    if g1 > tol && g2 > tol {
        return OPEN;
    }
    let mut f = 0;
    if e[1].abs() > tol {
        f |= SLIDING;
    }
    if (g1 - g2).abs() > tol {
        f |= ROCKING;
    }
    f
}
