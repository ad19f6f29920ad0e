//! The homogeneous self-dual interior point (Xu, Hung & Ye's simplified embedding, with
//! Mehrotra's predictor-corrector and Gondzio's correctors) on the normal equations, assembled
//! on the stiffness matrix's pattern and factorized by `linalg`.
//!
//! The program: minimise `-lambda` subject to `A x - f lambda = b`, `E x + t = 1` (the bounded
//! variables theta), `x, t >= 0`, lambda free. The embedding adds `tau, kappa >= 0`:
//!
//! ```text
//! A x - f lambda - b tau = 0            A^T y + s - E^T v = 0
//! E x + t - tau = 0                     -f . y + tau = 0
//! lambda + b . y - 1 . v - kappa = 0    x s = t v = tau kappa = mu
//! ```
//!
//! Its solution with `tau > 0` is the optimum over `tau`; with `kappa > 0` a certificate: a
//! dual ray (`b . y - 1 . v > 0`: no equilibrium at any lambda) or a primal one (`lambda > 0`
//! with `A x - f lambda = 0`: no mechanism). Each Newton step is the bordered normal system
//! solved twice (its residuals; the column of tau, once per iteration), combined through the
//! last row.

use super::*;
use std::ops::ControlFlow;

pub(super) fn norm_inf(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The largest step in (0, 1] that keeps `v + a dv >= 0`.
pub(super) fn max_step(v: &[f64], dv: &[f64]) -> f64 {
    v.iter().zip(dv).fold(1.0, |a, (&x, &d)| if d < 0.0 { a.min(-x / d) } else { a })
}

/// A solve of the bordered normal system is refined until its residual is below this
/// fraction of its right-hand side, or stops halving.
const REFINE_TO: f64 = 1e-15;

/// The fraction of the longest step to the boundary that an iteration takes.
const STEP_FRACTION: f64 = 0.99;

/// The interior point's iterate. Variables: five per interface (the last, theta, bounded by
/// 1) and lambda (free); `t`, `v`: theta's upper bounds' slacks and multipliers; `tau`,
/// `kappa`: the embedding's scale and its complement.
pub(super) struct Iterate {
    pub(super) x: Vec<f64>,
    pub(super) lam: f64,
    pub(super) s: Vec<f64>,
    pub(super) t: Vec<f64>,
    pub(super) v: Vec<f64>,
    pub(super) y: Vec<f64>,
    pub(super) tau: f64,
    pub(super) kappa: f64,
}

/// A search direction.
pub(super) struct Direction {
    pub(super) dx: Vec<f64>,
    pub(super) ds: Vec<f64>,
    pub(super) dt: Vec<f64>,
    pub(super) dv: Vec<f64>,
    pub(super) dy: Vec<f64>,
    pub(super) dlam: f64,
    pub(super) dtau: f64,
    pub(super) dkappa: f64,
}

impl Direction {
    /// `self + a d` (kappa's part apart).
    fn add(mut self, a: f64, d: &Direction) -> Direction {
        let axpy = |u: &mut [f64], v: &[f64]| u.iter_mut().zip(v).for_each(|(u, v)| *u += a * v);
        axpy(&mut self.dx, &d.dx);
        axpy(&mut self.ds, &d.ds);
        axpy(&mut self.dt, &d.dt);
        axpy(&mut self.dv, &d.dv);
        axpy(&mut self.dy, &d.dy);
        self.dlam += a * d.dlam;
        self.dtau += a * d.dtau;
        self
    }
}

/// The right-hand side of the normal system: equilibrium, the variables' dual rows, theta's
/// bounds, lambda's dual row (the embedding's residuals of an iterate, or tau's column).
pub(super) struct Residuals {
    pub(super) rb: Vec<f64>,
    pub(super) rc: Vec<f64>,
    pub(super) ru: Vec<f64>,
    pub(super) rl: f64,
}

impl Iterate {
    /// The longest step in (0, 1] along `d` that keeps every non-negative variable so.
    fn max_step(&self, d: &Direction) -> f64 {
        let mut a = max_step(&self.x, &d.dx).min(max_step(&self.t, &d.dt));
        a = a.min(max_step(&self.s, &d.ds)).min(max_step(&self.v, &d.dv));
        a.min(max_step(&[self.tau, self.kappa], &[d.dtau, d.dkappa]))
    }

    /// The mean complementarity product after a step `a` along `d`.
    fn mu_after(&self, d: &Direction, a: f64, ncomp: f64) -> f64 {
        let comp = |p: &[f64], dp: &[f64], q: &[f64], dq: &[f64]| {
            p.iter().zip(dp).zip(q.iter().zip(dq)).map(|((p, dp), (q, dq))| (p + a * dp) * (q + a * dq)).sum::<f64>()
        };
        let tk = (self.tau + a * d.dtau) * (self.kappa + a * d.dkappa);
        (comp(&self.x, &d.dx, &self.s, &d.ds) + comp(&self.t, &d.dt, &self.v, &d.dv) + tk) / ncomp
    }

    /// Moves along `d` by [`STEP_FRACTION`] of the longest step that keeps the variables
    /// non-negative, at most 1: one step for all (the embedding ties the primal and dual
    /// residuals through tau).
    fn step(&mut self, d: &Direction) {
        let a = (STEP_FRACTION * self.max_step(d)).min(1.0);
        let step = |v: &mut [f64], dv: &[f64]| v.iter_mut().zip(dv).for_each(|(v, d)| *v += a * d);
        step(&mut self.x, &d.dx);
        step(&mut self.t, &d.dt);
        step(&mut self.s, &d.ds);
        step(&mut self.v, &d.dv);
        step(&mut self.y, &d.dy);
        self.lam += a * d.dlam;
        self.tau += a * d.dtau;
        self.kappa += a * d.dkappa;
    }
}

/// An iterate's distance from the optimum, over tau: the mean complementarity product,
/// lambda (scaled), the scaled primal and dual residuals, the relative duality gap, the worst
/// of the three, and the embedding's gap row's residual (`kappa - lambda - b . y + 1 . v`).
struct Measures {
    mu: f64,
    lam: f64,
    primal: f64,
    dual: f64,
    gap: f64,
    worst: f64,
    rg: f64,
}

/// The interior point under way: the right-hand side and its norm, the iterate and its
/// residuals, the work arrays of the normal equations (Theta, `u = M^-1 f_live`,
/// `A^T y`), the smallest worst residual so far and the iterations since it last halved, and
/// the number of complementarity products.
struct Ipm {
    b: Vec<f64>,
    b_norm: f64,
    p: Iterate,
    res: Residuals,
    theta: Vec<f64>,
    u: Vec<f64>,
    aty: Vec<f64>,
    best: f64,
    since_best: usize,
    ncomp: f64,
}

impl Ipm {
    /// Whether the iterations end at this iterate, measured by `q`, and how: lambda beyond its
    /// range or a primal ray, the tolerance met, a dual ray, or a stall (near the tolerance
    /// the solution stands; far from it, or at the last iteration, it is `NotConverged`).
    fn verdict(&mut self, opts: &LimitOptions, q: &Measures, iter: usize) -> Option<Outcome> {
        let range = LAMBDA_RANGE;
        if q.lam > range * range || (q.lam > range && q.primal <= opts.tolerance) {
            return Some(Outcome::Unbounded);
        }
        if q.worst <= opts.tolerance {
            return Some(Outcome::Optimal);
        }
        let p = &self.p;
        // a primal ray: lambda > 0 with A x - f lambda = 0 and theta = 0 (t = 0) to the tolerance
        if p.lam > 0.0 {
            let ray_b = self.res.rb.iter().zip(&self.b).map(|(r, b)| (b * p.tau - r).abs()).fold(0.0, f64::max);
            let ray_u = self.res.ru.iter().map(|r| (p.tau - r).abs()).fold(0.0, f64::max);
            if ray_b.max(ray_u) <= opts.tolerance * p.lam {
                return Some(Outcome::Unbounded);
            }
        }
        // a dual ray: b . y - 1 . v > 0 with A^T y + s - E^T v = 0 and f . y = 0 to the
        // tolerance: no admissible forces balance the dead loads at any lambda
        let dray = dot(&self.b, &p.y) - p.v.iter().sum::<f64>();
        if dray > 0.0 {
            let fy = (self.res.rl + p.tau).abs();
            if norm_inf(&self.res.rc).max(fy) <= opts.tolerance * dray {
                return Some(Outcome::Infeasible);
            }
        }
        if q.worst < 0.5 * self.best {
            self.best = q.worst;
            self.since_best = 0;
        } else {
            self.since_best += 1;
        }
        // stalled: rounding bounds the residuals above the tolerance. Within
        // REDUCED_ACCURACY times it the solution stands (its certificate says how close it
        // is); a long stall or the last iteration far from it is a failure
        let near = q.worst <= REDUCED_ACCURACY * opts.tolerance;
        if near && self.since_best >= 5 {
            return Some(Outcome::Optimal);
        }
        if iter == opts.max_iterations || self.since_best >= 30 || !q.worst.is_finite() {
            return Some(if near {
                Outcome::Optimal
            } else if q.lam > range {
                Outcome::Unbounded
            } else {
                Outcome::NotConverged
            });
        }
        None
    }

    /// The solution at the iterate (over tau), measured by `q`, after `iter` iterations.
    fn solution(&self, outcome: Outcome, q: &Measures, iter: usize) -> Solution {
        let tau = self.p.tau;
        Solution {
            outcome,
            x: self.p.x.iter().map(|x| x / tau).collect(),
            lambda: q.lam,
            y: self.p.y.iter().map(|y| y / tau).collect(),
            primal: q.primal,
            dual: q.dual,
            gap: q.gap,
            iterations: iter,
        }
    }
}

/// The corrector's direction, its complementarity targets (x s, t v, tau kappa) and `sigma mu`.
struct Corrected {
    d: Direction,
    rxs: Vec<f64>,
    rtv: Vec<f64>,
    rtk: f64,
    target: f64,
}

/// The change of the gap row `lambda + b . y - 1 . v` along `d`.
fn gap_row(b: &[f64], d: &Direction) -> f64 {
    d.dlam + dot(b, &d.dy) - d.dv.iter().sum::<f64>()
}

/// Tau's direction of an iteration (the normal system solved for tau's column, `dtau = 1`)
/// and its change of the gap row.
struct Hsd {
    d1: Direction,
    g1: f64,
}

impl Hsd {
    /// The embedding's direction from `d0`, the normal system's solution at `dtau = 0`: dtau
    /// from the gap row (residual `rg`) with kappa's from its product with tau (target
    /// `tau kappa + rtk`); None if it is not finite.
    fn combine(&self, p: &Iterate, b: &[f64], d0: Direction, rg: f64, rtk: f64) -> Option<Direction> {
        let den = self.g1 + p.kappa / p.tau;
        let dtau = (rg + rtk / p.tau - gap_row(b, &d0)) / den;
        if !dtau.is_finite() {
            return None;
        }
        let mut d = d0.add(dtau, &self.d1);
        d.dkappa = (rtk - p.kappa * dtau) / p.tau;
        Some(d)
    }
}

impl Program {
    /// The variable bounded by `t[i]`: interface i's theta.
    #[inline]
    pub(super) fn bounded(&self, i: usize) -> usize {
        NV * i + 4
    }

    /// `A x + lam (-f_live)` (equilibrium of the variables) into `out`.
    pub(super) fn apply(&self, x: &[f64], lam: f64, out: &mut [f64]) {
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
    pub(super) fn apply_t(&self, y: &[f64], out: &mut [f64]) {
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

    /// Solves the scaled program by the homogeneous self-dual interior point.
    pub(super) fn solve(
        &mut self,
        opts: &LimitOptions,
        program: usize,
        monitor: &mut dyn FnMut(&LimitProgress) -> bool,
    ) -> Result<Solution> {
        let mut ipm = self.start();
        for iter in 0..=opts.max_iterations {
            if let ControlFlow::Break(end) = self.iteration(&mut ipm, opts, program, iter, monitor) {
                return end;
            }
        }
        unreachable!("the loop returns at its last iteration")
    }

    /// The interior point at its start: the right-hand side `b = f_dead - sum P V` (the cost is
    /// -lambda, lambda free with its own column -f_live), tau's column of the normal system,
    /// and the embedding's start: every variable 1 with its multiplier (theta and its slack
    /// 1/2, their multipliers 2), y = 0, lambda = 0, tau = kappa = 1.
    fn start(&mut self) -> Ipm {
        let (m, n) = (self.m, self.n);
        let nx = NV * m;
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
        let mut x = vec![1.0; nx];
        for k in 0..m {
            x[NV * k + 4] = 0.5;
        }
        let s: Vec<f64> = x.iter().map(|x| 1.0 / x).collect();
        let p = Iterate { x, s, v: vec![2.0; m], t: vec![0.5; m], lam: 0.0, y: vec![0.0; n], tau: 1.0, kappa: 1.0 };
        Ipm {
            b,
            b_norm,
            p,
            res: Residuals { rb: vec![0.0; n], rc: vec![0.0; nx], ru: vec![0.0; m], rl: 0.0 },
            theta: vec![0.0; nx],
            u: vec![0.0; n],
            aty: vec![0.0; nx],
            best: f64::INFINITY,
            since_best: 0,
            ncomp: (nx + m + 1) as f64,
        }
    }

    /// Iteration `iter` of program `program`: the iterate's residuals, the monitor, and either
    /// the end (the solution with its outcome, or `Error::Interrupted` when the monitor says
    /// stop) or a step of the predictor-corrector.
    fn iteration(
        &mut self,
        ipm: &mut Ipm,
        opts: &LimitOptions,
        program: usize,
        iter: usize,
        monitor: &mut dyn FnMut(&LimitProgress) -> bool,
    ) -> ControlFlow<Result<Solution>> {
        let q = self.measure(ipm);
        if !monitor(&LimitProgress { program, iteration: iter, multiplier: q.lam * self.force / self.live, residual: q.worst }) {
            return ControlFlow::Break(Err(Error::Interrupted));
        }
        if let Some(outcome) = ipm.verdict(opts, &q, iter) {
            return ControlFlow::Break(Ok(ipm.solution(outcome, &q, iter)));
        }
        if self.newton_step(ipm, &q).is_none() {
            let failed = if q.lam > LAMBDA_RANGE { Outcome::Unbounded } else { Outcome::NotConverged };
            return ControlFlow::Break(Ok(ipm.solution(failed, &q, iter)));
        }
        ControlFlow::Continue(())
    }

    /// The embedding's residuals of the iterate (into `ipm.res`) and how far the iterate over
    /// tau is from the optimum.
    fn measure(&self, ipm: &mut Ipm) -> Measures {
        let (p, res) = (&ipm.p, &mut ipm.res);
        let tau = p.tau;
        self.apply(&p.x, p.lam, &mut res.rb);
        for (r, b) in res.rb.iter_mut().zip(&ipm.b) {
            *r = b * tau - *r;
        }
        self.apply_t(&p.y, &mut ipm.aty);
        for ((rc, a), s) in res.rc.iter_mut().zip(&ipm.aty).zip(&p.s) {
            *rc = -a - s;
        }
        for i in 0..self.m {
            let j = self.bounded(i);
            res.rc[j] += p.v[i];
            res.ru[i] = tau - p.x[j] - p.t[i];
        }
        // lambda's dual row: -tau + f_live . y = 0
        res.rl = -tau + dot(&self.f_live, &p.y);
        let mu = (dot(&p.x, &p.s) + dot(&p.t, &p.v) + p.tau * p.kappa) / ipm.ncomp;
        let vsum = p.v.iter().sum::<f64>();
        let by = dot(&ipm.b, &p.y);
        let rg = p.kappa - p.lam - by + vsum;
        // over tau: the program's own residuals and objectives (primal -lambda, dual b y - 1 v)
        let lam = p.lam / tau;
        let primal = (norm_inf(&res.rb) / (1.0 + ipm.b_norm)).max(norm_inf(&res.ru)) / tau;
        let dual = norm_inf(&res.rc).max(res.rl.abs()) / tau;
        let dobj = (by - vsum) / tau;
        let gap = (-lam - dobj).abs() / (1.0 + lam.abs());
        let worst = primal.max(dual).max(gap);
        Measures { mu, lam, primal, dual, gap, worst, rg }
    }

    /// One step from the iterate: the normal matrix at its Theta, factorized, tau's column,
    /// the predictor and the corrector, Gondzio's correctors, and the step along the
    /// direction; None where the normal equations cannot be factorized or solved.
    fn newton_step(&mut self, ipm: &mut Ipm, q: &Measures) -> Option<()> {
        self.normal_matrix(ipm);
        if !self.factorize_normal(ipm) {
            return None;
        }
        let fu = dot(&self.f_live, &ipm.u);
        let (p, theta, u) = (&ipm.p, &ipm.theta, &ipm.u);
        let mut d1 = self.tau_direction(p, &ipm.res, theta, u, fu)?;
        d1.dtau = 1.0;
        let hsd = Hsd { g1: gap_row(&ipm.b, &d1), d1 };
        let pc = self.predictor_corrector(ipm, &hsd, q)?;
        let d = self.centrality_correctors(ipm, &hsd, q, pc, fu);
        ipm.p.step(&d);
        Some(())
    }

    /// Tau's direction: the normal system for tau's column (`b`, 1 on theta's bounds, -1 on
    /// lambda's dual row; complementarity 0). Solved as the iterate over tau plus the
    /// direction for the iterate's residuals over tau and products `-2 x s / tau`: the same
    /// solution, but a right-hand side of the predictor's structure, which the normal
    /// equations solve to the residuals' precision (solved for `b` itself, the error along the
    /// nearly singular directions near the optimum is 1e-5 of `b`, and it sets a floor on the
    /// primal residual).
    fn tau_direction(&mut self, p: &Iterate, res: &Residuals, theta: &[f64], u: &[f64], fu: f64) -> Option<Direction> {
        let it = 1.0 / p.tau;
        let rxs: Vec<f64> = p.x.iter().zip(&p.s).map(|(x, s)| -2.0 * x * s * it).collect();
        let rtv: Vec<f64> = p.t.iter().zip(&p.v).map(|(t, v)| -2.0 * t * v * it).collect();
        let mut d = self.direction(p, res, it, &rxs, &rtv, theta, u, fu)?;
        let add = |d: &mut [f64], z: &[f64]| d.iter_mut().zip(z).for_each(|(d, z)| *d += z * it);
        add(&mut d.dx, &p.x);
        add(&mut d.ds, &p.s);
        add(&mut d.dt, &p.t);
        add(&mut d.dv, &p.v);
        add(&mut d.dy, &p.y);
        d.dlam += p.lam * it;
        Some(d)
    }

    /// Theta = 1 / (s / x + v / t) into `ipm.theta`, and the normal matrix A Theta A^T
    /// (lambda's column apart: the system is bordered).
    fn normal_matrix(&mut self, ipm: &mut Ipm) {
        let (p, theta) = (&ipm.p, &mut ipm.theta);
        for ((th, s), x) in theta.iter_mut().zip(&p.s).zip(&p.x) {
            *th = s / x;
        }
        for i in 0..self.m {
            theta[self.bounded(i)] += p.v[i] / p.t[i];
        }
        theta.iter_mut().for_each(|t| *t = 1.0 / *t);
        self.assemble(theta);
    }

    /// Factorizes the normal matrix and solves `u = M^-1 f_live` (into `ipm.u`): whether it
    /// could. LDL^T on the Cholesky's analysis: the matrix is positive semi-definite, but near
    /// the optimum Theta spans 1e-12 to 1e12 and rounding leaves pivots of either sign that a
    /// Cholesky refuses (the solves' refinement corrects for them); where a pivot is zero, or a
    /// solve not finite, LU with pivoting.
    fn factorize_normal(&mut self, ipm: &mut Ipm) -> bool {
        for lu in [false, true] {
            let ok = if lu { self.normal.factorize().is_ok() } else { self.normal.factorize_ldlt().is_ok() };
            ipm.u.copy_from_slice(&self.f_live);
            if ok && self.solve_normal(&ipm.theta, &mut ipm.u).is_some() {
                return true;
            }
        }
        false
    }

    /// Mehrotra's predictor (the affine direction) and corrector (residuals reduced by
    /// `1 - sigma`, products centred at `sigma mu`, with sigma from the predictor's
    /// complementarity): the corrector's direction, its complementarity targets (x s, t v,
    /// tau kappa) and `sigma mu`; None if a solve fails.
    fn predictor_corrector(&mut self, ipm: &Ipm, hsd: &Hsd, q: &Measures) -> Option<Corrected> {
        let (p, res, theta, u) = (&ipm.p, &ipm.res, &ipm.theta, &ipm.u);
        let (m, nx) = (self.m, theta.len());
        let fu = dot(&self.f_live, u);
        // predictor
        let rxs: Vec<f64> = p.x.iter().zip(&p.s).map(|(x, s)| -x * s).collect();
        let rtv: Vec<f64> = p.t.iter().zip(&p.v).map(|(t, v)| -t * v).collect();
        let d0 = self.direction(p, res, 1.0, &rxs, &rtv, theta, u, fu)?;
        let aff = hsd.combine(p, &ipm.b, d0, q.rg, -p.tau * p.kappa)?;
        let a = p.max_step(&aff);
        let mu_aff = p.mu_after(&aff, a, ipm.ncomp);
        let sigma = (mu_aff / q.mu).powi(3).min(1.0);
        // corrector
        let smu = sigma * q.mu;
        let rxs: Vec<f64> = (0..nx).map(|i| smu - p.x[i] * p.s[i] - aff.dx[i] * aff.ds[i]).collect();
        let rtv: Vec<f64> = (0..m).map(|i| smu - p.t[i] * p.v[i] - aff.dt[i] * aff.dv[i]).collect();
        let rtk = smu - p.tau * p.kappa - aff.dtau * aff.dkappa;
        let eta = 1.0 - sigma;
        let d0 = self.direction(p, res, eta, &rxs, &rtv, theta, u, fu)?;
        let d = hsd.combine(p, &ipm.b, d0, eta * q.rg, rtk)?;
        Some(Corrected { d, rxs, rtv, rtk, target: smu })
    }

    /// Gondzio's centrality correctors on the corrector's direction: aim a longer step at products within [0.1, 10] of `target`, where the
    /// predictor-corrector's step left them outside; kept while they lengthen the step (one
    /// solve each, against a factorization per iteration), at most [`CORRECTORS`].
    #[allow(clippy::too_many_arguments)]
    fn centrality_correctors(&mut self, ipm: &Ipm, hsd: &Hsd, q: &Measures, pc: Corrected, fu: f64) -> Direction {
        let (p, res, theta, u) = (&ipm.p, &ipm.res, &ipm.theta, &ipm.u);
        let (m, nx) = (self.m, theta.len());
        let Corrected { d, rxs, rtv, rtk, target } = pc;
        let eta = 1.0 - target / q.mu;
        let (mut d, mut rxs, mut rtv, mut rtk) = (d, rxs, rtv, rtk);
        for _ in 0..CORRECTORS {
            let a = p.max_step(&d);
            if a >= 0.9 {
                break;
            }
            let at = (1.5 * a + 0.1).min(1.0);
            let fix = |v: f64| {
                let c = v.clamp(0.1 * target, 10.0 * target) - v;
                c.max(-10.0 * target)
            };
            let rxs2: Vec<f64> = (0..nx).map(|i| rxs[i] + fix((p.x[i] + at * d.dx[i]) * (p.s[i] + at * d.ds[i]))).collect();
            let rtv2: Vec<f64> = (0..m).map(|i| rtv[i] + fix((p.t[i] + at * d.dt[i]) * (p.v[i] + at * d.dv[i]))).collect();
            let rtk2 = rtk + fix((p.tau + at * d.dtau) * (p.kappa + at * d.dkappa));
            let Some(d2) = self.direction(p, res, eta, &rxs2, &rtv2, theta, u, fu) else {
                break;
            };
            let Some(d2) = hsd.combine(p, &ipm.b, d2, eta * q.rg, rtk2) else {
                break;
            };
            if p.max_step(&d2) < 1.01 * a {
                break;
            }
            d = d2;
            rxs = rxs2;
            rtv = rtv2;
            rtk = rtk2;
        }
        d
    }

    /// Assembles `sum_k A_k Theta_k A_k^T` (lambda's column left out).
    pub(super) fn assemble(&mut self, theta: &[f64]) {
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
    pub(super) fn solve_normal(&mut self, theta: &[f64], r: &mut [f64]) -> Option<()> {
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

    /// Solves the bordered system `M dy - f_live dlam = r`, `-f_live . dy = rl` (M = A Theta
    /// A^T, factorized; `u = M^-1 f_live`, `fu = f_live . u`): `dy = M^-1 r + dlam u`, refined
    /// on the exact operator while its residual exceeds 1e-10 of `r`, at most [`REFINEMENTS`]
    /// times. Near the optimum the live load's direction turns nearly singular (the mechanism),
    /// `u` grows, and the solves' errors along it no longer cancel.
    fn bordered_solve(&mut self, theta: &[f64], r: Vec<f64>, rl: f64, u: &[f64], fu: f64) -> Option<(Vec<f64>, f64)> {
        let norm = norm_inf(&r).max(rl.abs());
        let mut z = r.clone();
        self.solve_normal(theta, &mut z)?;
        let mut dlam = -(rl + dot(&self.f_live, &z)) / fu;
        let mut dy: Vec<f64> = z.iter().zip(u).map(|(z, u)| z + dlam * u).collect();
        let mut t = vec![0.0; theta.len()];
        let mut e = vec![0.0; self.n];
        let mut last = f64::INFINITY;
        for _ in 0..REFINEMENTS {
            // e = r - (M dy - f dlam), el = rl + f . dy
            self.apply_t(&dy, &mut t);
            t.iter_mut().zip(theta).for_each(|(t, th)| *t *= th);
            self.apply(&t, dlam, &mut e);
            e.iter_mut().zip(&r).for_each(|(e, r)| *e = r - *e);
            let el = rl + dot(&self.f_live, &dy);
            let err = norm_inf(&e).max(el.abs());
            if err <= REFINE_TO * norm || err > 0.5 * last {
                break;
            }
            last = err;
            self.solve_normal(theta, &mut e)?;
            let c = -(el + dot(&self.f_live, &e)) / fu;
            dlam += c;
            dy.iter_mut().zip(e.iter().zip(u)).for_each(|(d, (e, u))| *d += e + c * u);
        }
        Some((dy, dlam))
    }

    /// The Newton direction at `dtau = 0` for the residuals `res` times `eta` and the
    /// complementarity targets `rxs` (x s) and `rtv` (t v), with the normal matrix factorized
    /// and `u = M^-1 f_live`; None if a solve fails.
    ///
    /// With `Theta = 1 / (s / x + v / t)` and `xi = rc - rxs / x + (rtv - v ru) / t`:
    /// `dx = Theta (A^T dy - xi)`, `M dy - f_live dlam = rb + A Theta xi` (M = A Theta A^T) and
    /// lambda's dual row `-f_live . dy = rl`: `dy = M^-1 (q + f_live dlam)`, one solve and `u`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn direction(
        &mut self,
        p: &Iterate,
        res: &Residuals,
        eta: f64,
        rxs: &[f64],
        rtv: &[f64],
        theta: &[f64],
        u: &[f64],
        fu: f64,
    ) -> Option<Direction> {
        let m = self.m;
        let nx = theta.len();
        let mut xi: Vec<f64> = (0..nx).map(|i| eta * res.rc[i] - rxs[i] / p.x[i]).collect();
        for i in 0..m {
            xi[self.bounded(i)] += (rtv[i] - p.v[i] * eta * res.ru[i]) / p.t[i];
        }
        let txi: Vec<f64> = theta.iter().zip(&xi).map(|(t, x)| t * x).collect();
        let mut q = vec![0.0; self.n];
        self.apply(&txi, 0.0, &mut q);
        for (q, r) in q.iter_mut().zip(&res.rb) {
            *q += eta * r;
        }
        let (dy, dlam) = self.bordered_solve(theta, q, eta * res.rl, u, fu)?;
        let mut dx = vec![0.0; nx];
        self.apply_t(&dy, &mut dx);
        for i in 0..nx {
            dx[i] = theta[i] * (dx[i] - xi[i]);
        }
        let ds: Vec<f64> = (0..nx).map(|i| (rxs[i] - p.s[i] * dx[i]) / p.x[i]).collect();
        let dt: Vec<f64> = (0..m).map(|i| eta * res.ru[i] - dx[self.bounded(i)]).collect();
        let dv: Vec<f64> = (0..m).map(|i| (rtv[i] - p.v[i] * dt[i]) / p.t[i]).collect();
        let ok = dx.iter().chain(&dy).chain(&ds).chain(&dv).all(|v| v.is_finite()) && dlam.is_finite();
        ok.then_some(Direction { dx, ds, dt, dv, dy, dlam, dtau: 0.0, dkappa: 0.0 })
    }
}
