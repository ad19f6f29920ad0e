//! The primal-dual interior point (Mehrotra's predictor-corrector, Gondzio's correctors) on the
//! normal equations, assembled on the stiffness matrix's pattern and factorized by `linalg`.
//! The variables lie in the orthant (the plane's program) or in second-order cones of three
//! dimensions (3D: Coulomb's cone at each contact corner), with Nesterov and Todd's scaling
//! ([`super::cone`]); one loop, the cones' directions and steps apart.

use super::cone::{cone_step_upto, jordan, max_cone_step, Nt};
use super::*;
use rayon::prelude::*;
use std::ops::ControlFlow;

/// Cones per task of the parallel passes over cones.
const GRAIN_CONES: usize = 2048;

/// A pass over the cones: `work(first cone, a, b)` on chunks of `a` (three values per cone) and
/// of `b` (as many per cone in each chunk; `b` may be empty), on the program's threads where it
/// has them, else at once; the chunks' results folded by `fold`, which must not depend on their
/// order (a minimum, not a sum: the results are the same whatever the number of threads).
fn cones<R: Send + Sync + Clone>(
    par: Option<&Par>,
    a: &mut [f64],
    b: &mut [f64],
    id: R,
    fold: impl Fn(R, R) -> R + Sync + Send,
    work: impl Fn(usize, &mut [f64], &mut [f64]) -> R + Sync + Send,
) -> R {
    let nc = a.len() / 3;
    let per = b.len().checked_div(nc).unwrap_or(0);
    let chunks = nc.div_ceil(GRAIN_CONES);
    let bs: Vec<&mut [f64]> = if per == 0 { (0..chunks).map(|_| Default::default()).collect() } else { b.chunks_mut(per * GRAIN_CONES).collect() };
    // one thread: the same chunks in order (the same results)
    let Some(p) = par else {
        let mut r = id;
        for (c, (a, b)) in a.chunks_mut(3 * GRAIN_CONES).zip(bs).enumerate() {
            r = fold(r, work(c * GRAIN_CONES, a, b));
        }
        return r;
    };
    p.pool.install(|| {
        a.par_chunks_mut(3 * GRAIN_CONES)
            .zip(bs.into_par_iter())
            .enumerate()
            .map(|(c, (a, b))| work(c * GRAIN_CONES, a, b))
            .reduce(|| id.clone(), &fold)
    })
}

/// Cone `c`'s three values in `v`.
#[inline]
fn tri(v: &[f64], c: usize) -> [f64; 3] {
    [v[3 * c], v[3 * c + 1], v[3 * c + 2]]
}

/// [`max_cone_step`] on the program's threads where it has them.
fn max_cone_step_on(par: Option<&Par>, v: &[f64], dv: &[f64]) -> f64 {
    let g = 3 * GRAIN_CONES;
    match par {
        None => v.chunks(g).zip(dv.chunks(g)).map(|(v, d)| max_cone_step(v, d)).fold(1.0, f64::min),
        Some(p) => p.pool.install(|| v.par_chunks(g).zip(dv.par_chunks(g)).map(|(v, d)| max_cone_step(v, d)).reduce(|| 1.0, f64::min)),
    }
}

pub(super) fn norm_inf(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The largest step in (0, 1] that keeps `v + a dv >= 0`. Eight running minima, one per lane,
/// so that the compiler vectorizes the divisions (one minimum is a chain of dependent steps:
/// 9% of an analysis in 3D).
pub(super) fn max_step(v: &[f64], dv: &[f64]) -> f64 {
    const LANES: usize = 8;
    let ratio = |x: f64, d: f64| if d < 0.0 { -x / d } else { 1.0 };
    let mut lanes = [1.0f64; LANES];
    let (vc, dc) = (v.chunks_exact(LANES), dv.chunks_exact(LANES));
    let (vr, dr) = (vc.remainder(), dc.remainder());
    for (x, d) in vc.zip(dc) {
        for k in 0..LANES {
            lanes[k] = lanes[k].min(ratio(x[k], d[k]));
        }
    }
    let rest = vr.iter().zip(dr).fold(1.0f64, |a, (&x, &d)| a.min(ratio(x, d)));
    lanes.iter().fold(rest, |a, &l| a.min(l))
}

/// The interior point's iterate. Variables: `nv` per element (in the plane the last, theta,
/// bounded by 1) and lambda (free); `t`, `v`: the upper bounds' slacks and multipliers.
#[derive(Clone)]
pub(super) struct Iterate {
    pub(super) x: Vec<f64>,
    pub(super) lam: f64,
    pub(super) s: Vec<f64>,
    pub(super) t: Vec<f64>,
    pub(super) v: Vec<f64>,
    pub(super) y: Vec<f64>,
}

/// A search direction.
pub(super) struct Direction {
    pub(super) dx: Vec<f64>,
    pub(super) ds: Vec<f64>,
    pub(super) dt: Vec<f64>,
    pub(super) dv: Vec<f64>,
    pub(super) dy: Vec<f64>,
    pub(super) dlam: f64,
}

/// The residuals of an iterate: equilibrium, the variables' dual rows, theta's bounds, and
/// lambda's dual row.
pub(super) struct Residuals {
    pub(super) rb: Vec<f64>,
    pub(super) rc: Vec<f64>,
    pub(super) ru: Vec<f64>,
    pub(super) rl: f64,
}

impl Iterate {
    /// The longest steps in (0, 1] along `d` that keep the primal variables (x, t) and the
    /// dual ones (s, v) in their cones (of dimension `cone`: 1, the orthant, or 3).
    fn max_steps(&self, d: &Direction, cone: usize, par: Option<&Par>) -> (f64, f64) {
        let along = |v: &[f64], dv: &[f64]| if cone == 3 { max_cone_step_on(par, v, dv) } else { max_step(v, dv) };
        (along(&self.x, &d.dx).min(max_step(&self.t, &d.dt)), along(&self.s, &d.ds).min(max_step(&self.v, &d.dv)))
    }

    /// Moves along `d`: the primal variables (x, t, lambda) and the dual ones (s, v, y) each by
    /// 0.995 of the longest step that keeps them in their cones, at most 1.
    fn step(&mut self, d: &Direction, cone: usize, par: Option<&Par>) {
        let eta = 0.995;
        let (ap, ad) = self.max_steps(d, cone, par);
        let (ap, ad) = ((eta * ap).min(1.0), (eta * ad).min(1.0));
        let step = |v: &mut [f64], dv: &[f64], a: f64| v.iter_mut().zip(dv).for_each(|(v, d)| *v += a * d);
        step(&mut self.x, &d.dx, ap);
        step(&mut self.t, &d.dt, ap);
        self.lam += ap * d.dlam;
        step(&mut self.s, &d.ds, ad);
        step(&mut self.v, &d.dv, ad);
        step(&mut self.y, &d.dy, ad);
    }
}

/// `u = M^-1 f_live` and `f_live . u` for a direction's bordered solve: known, or to be solved
/// with the direction (the first of an iteration), one pass over the factor for both.
pub(super) enum Live<'a> {
    Known(&'a [f64], f64),
    Solve(&'a mut [f64], &'a mut f64),
}

/// An iterate's distance from the optimum: the mean complementarity product, lambda (scaled),
/// the scaled primal and dual residuals, the dual objective, the relative duality gap, and the
/// worst of the residuals and the gap.
#[derive(Clone, Copy)]
struct Measures {
    mu: f64,
    lam: f64,
    primal: f64,
    dual: f64,
    dobj: f64,
    gap: f64,
    worst: f64,
}

/// The interior point under way: the right-hand side and its norm, the iterate and its
/// residuals, the work arrays of the normal equations (Theta, `u = M^-1 f_live`, `A^T y`), the
/// smallest worst residual so far and the iterations since it last halved, and the number of
/// complementarity products.
struct Ipm {
    b: Vec<f64>,
    b_norm: f64,
    p: Iterate,
    res: Residuals,
    theta: Vec<f64>,
    /// the scalings of the cones, where the variables are in second-order cones (`theta` then
    /// unused)
    nt: Vec<Nt>,
    /// `u = M^-1 f_live` and `f_live . u`, solved with each iteration's predictor
    u: Vec<f64>,
    fu: f64,
    aty: Vec<f64>,
    best: f64,
    since_best: usize,
    /// the best iterate within [`REDUCED_ACCURACY`] times the tolerance so far, measured, and
    /// its iteration: what the iterations give if rounding spoils those after it
    near: Option<(Iterate, Measures, usize)>,
    /// the worst residual of the iterate before
    previous: f64,
    /// an iterate within the tolerance was reached (it is `near`): the next one ends the
    /// iterations
    polishing: bool,
    ncomp: f64,
}

impl Ipm {
    /// Whether the iterations end at this iterate, measured by `q`, and with which solution:
    /// lambda beyond its range, the tolerance met, a dual ray proving infeasibility, or a stall.
    /// Stalled, rounding bounds the residuals above the tolerance: the best iterate within
    /// [`REDUCED_ACCURACY`] times it stands (its certificate says how close it is), even where
    /// the iterations after it grew worse; a long stall or the last iteration with none such
    /// is a failure.
    fn verdict(&mut self, opts: &LimitOptions, q: &Measures, failed: Outcome, iter: usize) -> Option<Solution> {
        let range = LAMBDA_RANGE;
        if q.lam > range * range || (q.lam > range && q.primal <= opts.tolerance) {
            // after an iterate near the optimum, lambda running away is rounding's breakdown,
            // not a program without a bound (a near-optimal point bounds it): that iterate stands
            // (a single sliding block near its optimum, its normal matrix singular to rounding,
            // was sent to lambda = 1e13 and said unbounded)
            return Some(self.near_solution().unwrap_or_else(|| self.solution(Outcome::Unbounded, q, iter)));
        }
        // The iteration after the first iterate within the tolerance: the better of the two
        // stands. An iterate just within it may hold a multiplier a few times the tolerance from
        // the optimum (3.6e-8 below at 1e-8 on small walls: the residuals are scaled, the
        // multiplier is not); one step more, near the optimum, costs one factorization of a
        // program's 20-40 and brings it far closer.
        if self.polishing {
            if q.worst.is_finite() && q.worst < self.near.as_ref().map_or(f64::INFINITY, |n| n.1.worst) {
                return Some(self.solution(Outcome::Optimal, q, iter));
            }
            return self.near_solution();
        }
        if q.worst <= opts.tolerance {
            if iter == opts.max_iterations {
                return Some(self.solution(Outcome::Optimal, q, iter));
            }
            self.near = Some((self.p.clone(), *q, iter));
            self.polishing = true;
            return None;
        }
        // a dual point of objective above the range bounds lambda below -range: no
        // multiplier in the range balances the dead loads
        if q.dual <= 1e-8 && q.dobj > range {
            return Some(self.solution(Outcome::Infeasible, q, iter));
        }
        if q.worst < 0.5 * self.best {
            self.best = q.worst;
            self.since_best = 0;
        } else {
            self.since_best += 1;
        }
        let near = q.worst <= REDUCED_ACCURACY * opts.tolerance;
        if near && self.near.as_ref().map_or(true, |n| q.worst < n.1.worst) {
            self.near = Some((self.p.clone(), *q, iter));
        }
        // stalled near the tolerance, or gone astray since an iterate near it
        let last = iter == opts.max_iterations || self.since_best >= 30 || !q.worst.is_finite();
        // (not while the iterate gains on the one before: after a detour, those near the optimum
        // converge as fast as at first, and one of them was taken for a stall)
        let gaining = q.worst < 0.5 * self.previous;
        self.previous = q.worst;
        let stalled = !gaining && ((near && self.since_best >= 5) || self.since_best >= 15);
        if self.near.is_some() && (stalled || last) {
            return self.near_solution();
        }
        last.then(|| self.solution(failed, q, iter))
    }

    /// The best iterate near the tolerance as an optimal solution, if there is one.
    fn near_solution(&self) -> Option<Solution> {
        self.near.as_ref().map(|(p, q, iter)| solution_of(p, Outcome::Optimal, q, *iter))
    }

    /// The solution at the iterate, measured by `q`, after `iter` iterations.
    fn solution(&self, outcome: Outcome, q: &Measures, iter: usize) -> Solution {
        solution_of(&self.p, outcome, q, iter)
    }
}

/// The solution at iterate `p`, measured by `q`, after `iter` iterations.
fn solution_of(p: &Iterate, outcome: Outcome, q: &Measures, iter: usize) -> Solution {
    Solution {
        outcome,
        x: p.x.clone(),
        lambda: q.lam,
        y: p.y.clone(),
        primal: q.primal,
        dual: q.dual,
        gap: q.gap,
        iterations: iter,
    }
}

impl Lp {
    /// `A x + lam (-f_live)` (equilibrium of the variables) into `out`.
    pub(super) fn apply(&self, x: &[f64], lam: f64, out: &mut [f64]) {
        for (o, f) in out.iter_mut().zip(&self.f_live) {
            *o = -f * lam;
        }
        if let Some(cf) = &self.corners {
            return self.apply_corners(cf, x, out);
        }
        let (rows, nv) = (self.rows, self.nv);
        for k in 0..self.m {
            let xk = &x[nv * k..nv * k + nv];
            for (r, &d) in self.dofs[rows * k..rows * k + rows].iter().enumerate() {
                if d != NO_EQ {
                    let a = &self.acols[(rows * k + r) * nv..(rows * k + r + 1) * nv];
                    out[d as usize] += a.iter().zip(xk).map(|(a, x)| a * x).sum::<f64>();
                }
            }
        }
    }

    /// `A^T y` into `out` (lambda's row, `-f_live . y`, left out).
    pub(super) fn apply_t(&self, y: &[f64], out: &mut [f64]) {
        if let Some(cf) = &self.corners {
            return self.apply_t_corners(cf, y, out);
        }
        let (rows, nv) = (self.rows, self.nv);
        for k in 0..self.m {
            let o = &mut out[nv * k..nv * k + nv];
            o.fill(0.0);
            for (r, &d) in self.dofs[rows * k..rows * k + rows].iter().enumerate() {
                if d != NO_EQ {
                    let yv = y[d as usize];
                    let a = &self.acols[(rows * k + r) * nv..(rows * k + r + 1) * nv];
                    o.iter_mut().zip(a).for_each(|(o, a)| *o += a * yv);
                }
            }
        }
    }

    /// Solves the scaled program by Mehrotra's predictor-corrector from a fixed start.
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
    /// -lambda, lambda free with its own column -f_live), and Mehrotra's starting point: the
    /// variables of least norm that balance the dead loads at lambda = 0 and the dual of least
    /// norm that meets lambda's row (`y = u / (f_live . u)`, `s = -A^T y`, two solves with
    /// Theta = 1), each shifted inside the positive orthant and then towards the other's scale
    /// so that the products x s are alike; the bounded variables 1/2 with their products at the
    /// same mean. And the work arrays.
    ///
    /// Why: from `y = 0`, `s = 1 / x` the first steps threw the dual objective to -10^4 (10^4
    /// blocks) and the next three only undid it. Iterations from this start against that one
    /// (sigma at most 0.2 in both): 40 blocks 10 / 13, 1,041 18 / 20, 10^4 36 / 37, 10^5
    /// 56 / 64; in 3D 115 blocks 18 / 19, 1,785 30 / 35, 3,980 34 / 41, 9,331 93 / 104.
    fn start(&mut self) -> Ipm {
        let (n, nbd) = (self.n, self.n_bounded());
        let nx = self.n_vars();
        let mut b = self.f_dead.clone();
        for (&d, &pv) in self.dofs.iter().zip(&self.pv) {
            if d != NO_EQ {
                b[d as usize] -= pv;
            }
        }
        let b_norm = norm_inf(&b);
        let cone = self.cone;
        // e, the centre of the orthant or of each cone ((1, 0, 0)), where the solves below
        // cannot be made (a singular normal matrix: joints without friction); the cones' start
        // was (1, 1, 1), outside them, and the first step along any direction was nil
        let e: Vec<f64> = (0..nx).map(|i| if i % cone == 0 { 1.0 } else { 0.0 }).collect();
        let (mut x, mut s, mut y) = (e.clone(), e, vec![0.0; n]);
        // Theta = 1: in the cones, the scaling of e with itself
        let mut nt = vec![Nt::new([1.0, 0.0, 0.0], [1.0, 0.0, 0.0]); if cone == 3 { nx / 3 } else { 0 }];
        self.assemble(&x, &nt);
        self.regularize();
        let (mut w, mut u) = (b.clone(), self.f_live.clone());
        let solved = self.normal.factorize().is_ok()
            && self.normal.solve_in_place(&mut w).is_ok()
            && self.normal.solve_in_place(&mut u).is_ok()
            && w.iter().chain(&u).all(|v| v.is_finite());
        let fu = dot(&self.f_live, &u);
        if solved && fu > 0.0 {
            self.apply_t(&w, &mut x);
            y.iter_mut().zip(&u).for_each(|(y, u)| *y = u / fu);
            self.apply_t(&y, &mut s);
            s.iter_mut().for_each(|s| *s = -*s);
            // into the cones' interior (along e: 1 in the orthant, (1, 0, 0) in a cone), then
            // each shifted by half the products over the other's sum along e
            let lowest = |v: &[f64]| {
                if cone == 3 {
                    v.chunks_exact(3).fold(f64::INFINITY, |a, c| a.min(c[0] - (c[1] * c[1] + c[2] * c[2]).sqrt()))
                } else {
                    v.iter().fold(f64::INFINITY, |a, &b| a.min(b))
                }
            };
            let shift = |v: &mut [f64], d: f64| v.iter_mut().step_by(cone).for_each(|v| *v += d);
            let esum = |v: &[f64]| v.iter().step_by(cone).sum::<f64>();
            let (lx, ls) = (lowest(&x), lowest(&s));
            shift(&mut x, (-1.5 * lx).max(0.0));
            shift(&mut s, (-1.5 * ls).max(0.0));
            let xs = dot(&x, &s);
            let (dx, ds) = (0.5 * xs / esum(&s), 0.5 * xs / esum(&x));
            shift(&mut x, dx);
            shift(&mut s, ds);
        }
        nt.clear();
        // the bounded variables midway, their products x s and t v at the others' mean
        let mu = (dot(&x, &s) / nx.max(1) as f64).max(f64::MIN_POSITIVE);
        for i in 0..nbd {
            x[self.bounded_var(i)] = 0.5;
            s[self.bounded_var(i)] = 2.0 * mu;
        }
        let p = Iterate { s, v: vec![2.0 * mu; nbd], t: vec![0.5; nbd], x, lam: 0.0, y };
        Ipm {
            b,
            b_norm,
            p,
            res: Residuals { rb: vec![0.0; n], rc: vec![0.0; nx], ru: vec![0.0; nbd], rl: 0.0 },
            theta: vec![0.0; nx],
            nt,
            u: vec![0.0; n],
            fu: 0.0,
            aty: vec![0.0; nx],
            best: f64::INFINITY,
            since_best: 0,
            near: None,
            polishing: false,
            previous: f64::INFINITY,
            ncomp: (nx / cone + nbd) as f64,
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
        let q = self.on_pool(|lp| lp.measure(ipm));
        let lam = q.lam;
        if !monitor(&LimitProgress {
            program,
            iteration: iter,
            multiplier: lam * self.force / self.live,
            residual: q.worst,
        }) {
            return ControlFlow::Break(Err(Error::Interrupted));
        }
        // the dual iterates running away along a ray while equilibrium stays violated: the
        // sign of a program without a feasible point, if the iterations end here
        // lambda running away beyond its range: the live load finds no mechanism
        let failed = if norm_inf(&ipm.p.y) > 1e12 && q.primal > 1e-3 {
            Outcome::Infeasible
        } else if lam > LAMBDA_RANGE {
            Outcome::Unbounded
        } else {
            Outcome::NotConverged
        };
        if let Some(solution) = ipm.verdict(opts, &q, failed, iter) {
            return ControlFlow::Break(Ok(solution));
        }
        if self.on_pool(|lp| lp.newton_step(ipm, q.mu)).is_none() {
            return ControlFlow::Break(Ok(ipm.near_solution().unwrap_or_else(|| ipm.solution(failed, &q, iter))));
        }
        ControlFlow::Continue(())
    }

    /// `f(self)` on a thread of the program's pool where it has one (else here). There the
    /// passes' tasks that the pool's other threads, asleep, do not take up at once are taken
    /// back by this thread; a pass started from outside the pool would wait for them, and a
    /// sleeping thread can take milliseconds to wake (3 ms on a 2-core virtual machine, where
    /// passes started from outside ran slower on two threads than on one below 10^4 blocks).
    fn on_pool<R: Send>(&mut self, f: impl FnOnce(&mut Self) -> R + Send) -> R {
        match self.par.as_ref().map(|p| std::sync::Arc::clone(&p.pool)) {
            Some(pool) => pool.install(|| f(self)),
            None => f(self),
        }
    }

    /// The residuals of the iterate (into `ipm.res`) and how far it is from the optimum.
    fn measure(&self, ipm: &mut Ipm) -> Measures {
        let (p, res) = (&ipm.p, &mut ipm.res);
        self.apply(&p.x, p.lam, &mut res.rb);
        for (r, b) in res.rb.iter_mut().zip(&ipm.b) {
            *r = b - *r;
        }
        self.apply_t(&p.y, &mut ipm.aty);
        for ((rc, a), s) in res.rc.iter_mut().zip(&ipm.aty).zip(&p.s) {
            *rc = -a - s;
        }
        for i in 0..self.n_bounded() {
            let j = self.bounded_var(i);
            res.rc[j] += p.v[i];
            res.ru[i] = 1.0 - p.x[j] - p.t[i];
        }
        // lambda's dual row: -1 + f_live . y = 0
        res.rl = -1.0 + dot(&self.f_live, &p.y);
        let mu = (dot(&p.x, &p.s) + dot(&p.t, &p.v)) / ipm.ncomp;
        let lam = p.lam;
        let primal = (norm_inf(&res.rb) / (1.0 + ipm.b_norm)).max(norm_inf(&res.ru));
        let dual = norm_inf(&res.rc).max(res.rl.abs());
        // objectives: primal -lambda, dual b y - v (theta's bounds are 1)
        let dobj = dot(&ipm.b, &p.y) - p.v.iter().sum::<f64>();
        let gap = (-lam - dobj).abs() / (1.0 + lam.abs());
        let worst = primal.max(dual).max(gap);
        Measures { mu, lam, primal, dual, dobj, gap, worst }
    }

    /// One step of the predictor-corrector from the iterate: the normal matrix at its Theta,
    /// factorized, the predictor and the corrector, Gondzio's correctors, and the step along
    /// the direction; None where the normal equations cannot be factorized or solved.
    ///
    /// LDL^T on the Cholesky's analysis: the matrix is positive semi-definite, but near the
    /// optimum Theta spans 1e-12 to 1e12 and rounding leaves pivots of either sign that a
    /// Cholesky refuses (the direction's correction makes up for them); where the LDL^T fails
    /// (non-finite entries) or the predictor's solve is not finite, LU with pivoting.
    fn newton_step(&mut self, ipm: &mut Ipm, mu: f64) -> Option<()> {
        self.normal_matrix(ipm);
        let mut first = None;
        for lu in [false, true] {
            let ok = if lu { self.normal.factorize().is_ok() } else { self.normal.factorize_ldlt().is_ok() };
            first = if ok { self.predictor_corrector(ipm, mu) } else { None };
            if first.is_some() {
                break;
            }
        }
        let (d, rxs, rtv, steps, target) = first?;
        let fu = ipm.fu;
        let (mut d, rxs, rtv) = self.centrality_correctors(ipm, d, rxs, rtv, steps, target, fu);
        self.refine(ipm, &mut d, &rxs, &rtv, fu)?;
        ipm.p.step(&d, self.cone, self.par.as_ref());
        Some(())
    }

    /// Theta = 1 / (s / x + v / t) into `ipm.theta` (in the cones, their scalings into
    /// `ipm.nt`, Theta = W^2), and the normal matrix A Theta A^T (lambda's column apart: the
    /// system is bordered).
    fn normal_matrix(&mut self, ipm: &mut Ipm) {
        if self.cone == 3 {
            let p = &ipm.p;
            // in place: the scalings' vector is as long at every iteration
            ipm.nt.resize(p.x.len() / 3, Nt::default());
            let fill = |c0: usize, nt: &mut [Nt]| nt.iter_mut().enumerate().for_each(|(j, w)| *w = Nt::new(tri(&p.x, c0 + j), tri(&p.s, c0 + j)));
            match &self.par {
                None => fill(0, &mut ipm.nt),
                Some(par) => par.pool.install(|| ipm.nt.par_chunks_mut(GRAIN_CONES).enumerate().for_each(|(c, nt)| fill(c * GRAIN_CONES, nt))),
            }
            self.assemble(&[], &ipm.nt);
            return self.regularize();
        }
        let (p, theta) = (&ipm.p, &mut ipm.theta);
        for ((th, s), x) in theta.iter_mut().zip(&p.s).zip(&p.x) {
            *th = s / x;
        }
        for i in 0..self.n_bounded() {
            theta[self.bounded_var(i)] += p.v[i] / p.t[i];
        }
        theta.iter_mut().for_each(|t| *t = 1.0 / *t);
        self.assemble(theta, &[]);
        self.regularize();
    }

    /// Adds [`REGULARIZATION`] times the largest diagonal entry to the normal matrix's diagonal,
    /// where the program has joints without friction (see [`Lp::diagonal`]).
    fn regularize(&mut self) {
        let Some(diagonal) = &self.diagonal else { return };
        let vals = self.normal.values_mut();
        let largest = diagonal.iter().map(|&s| vals[s as usize].abs()).fold(0.0, f64::max);
        for &s in diagonal {
            vals[s as usize] += REGULARIZATION * largest;
        }
    }

    /// Mehrotra's predictor (the affine direction) and corrector (centred at `sigma mu`, with
    /// sigma from the predictor's complementarity, at most [`SIGMA_MAX`]): the corrector's
    /// direction, its complementarity targets, the longest steps along it and `sigma mu`; None
    /// if a solve fails. The predictor's solve also gives `u = M^-1 f_live` and `f_live . u`
    /// (into `ipm.u`, `ipm.fu`).
    #[allow(clippy::type_complexity)]
    fn predictor_corrector(&mut self, ipm: &mut Ipm, mu: f64) -> Option<(Direction, Vec<f64>, Vec<f64>, (f64, f64), f64)> {
        if self.cone == 3 {
            return self.predictor_corrector_cones(ipm, mu);
        }
        let Ipm { p, res, theta, u, fu, ncomp, .. } = ipm;
        let (m, nx) = (self.n_bounded(), theta.len());
        // predictor
        let rxs: Vec<f64> = p.x.iter().zip(&p.s).map(|(x, s)| -x * s).collect();
        let rtv: Vec<f64> = p.t.iter().zip(&p.v).map(|(t, v)| -t * v).collect();
        let (aff, (ap, ad)) = self.direction(p, res, &rxs, &rtv, theta, Live::Solve(u, fu))?;
        let comp = |a: &[f64], da: &[f64], b: &[f64], db: &[f64]| {
            a.iter().zip(da).zip(b.iter().zip(db)).map(|((a, da), (b, db))| (a + ap * da) * (b + ad * db)).sum::<f64>()
        };
        let mu_aff = (comp(&p.x, &aff.dx, &p.s, &aff.ds) + comp(&p.t, &aff.dt, &p.v, &aff.dv)) / *ncomp;
        let sigma = (mu_aff / mu).powi(3).min(SIGMA_MAX);
        // corrector
        let rxs: Vec<f64> = (0..nx).map(|i| sigma * mu - p.x[i] * p.s[i] - aff.dx[i] * aff.ds[i]).collect();
        let rtv: Vec<f64> = (0..m).map(|i| sigma * mu - p.t[i] * p.v[i] - aff.dt[i] * aff.dv[i]).collect();
        let (d, steps) = self.direction(p, res, &rxs, &rtv, theta, Live::Known(u, *fu))?;
        Some((d, rxs, rtv, steps, sigma * mu))
    }

    /// Gondzio's centrality correctors on direction `d` (of complementarity targets `rxs`,
    /// `rtv`): aim a longer step at products within [0.1, 10] of `target`, where the
    /// predictor-corrector's step left them outside; kept while they lengthen the step (one
    /// solve each, against a factorization per iteration), at most [`CORRECTORS`] (one below
    /// [`CORRECTORS_FROM`] equations). `steps`: the longest steps along `d`. The direction
    /// kept, with its targets.
    #[allow(clippy::too_many_arguments)]
    fn centrality_correctors(
        &mut self,
        ipm: &Ipm,
        d: Direction,
        rxs: Vec<f64>,
        rtv: Vec<f64>,
        steps: (f64, f64),
        target: f64,
        fu: f64,
    ) -> (Direction, Vec<f64>, Vec<f64>) {
        let (p, res, theta, u, nt) = (&ipm.p, &ipm.res, &ipm.theta, &ipm.u, &ipm.nt);
        let (m, nx) = (self.n_bounded(), p.x.len());
        let (mut d, mut rxs, mut rtv, mut steps) = (d, rxs, rtv, steps);
        // near the optimum of a tight tolerance the target (sigma times the mean product) may
        // round to zero or below: no centre to correct towards, the direction stands
        let most = if !(target > 0.0) {
            0
        } else if self.n < CORRECTORS_FROM {
            1
        } else {
            CORRECTORS
        };
        for _ in 0..most {
            let (ap, ad) = steps;
            if ap.min(ad) >= 0.9 {
                break;
            }
            let (ap_t, ad_t) = ((1.5 * ap + 0.1).min(1.0), (1.5 * ad + 0.1).min(1.0));
            // the products kept within [0.1, 10] of the target; the cones' eigenvalues within
            // [0.02, 50]: iterations in 3D with [0.1, 10] / [0.02, 50], 45 / 38 (9,331 blocks),
            // 32 / 26 (3,749), 20 / 19 (3,980). (In the plane the counts with 0.01 to 0.05 spread
            // over 29-38 at 10^4 blocks, about 36 with 0.1: no signal above the rounding's.)
            let (lo, hi) = if self.cone == 3 { (0.02, 50.0) } else { (0.1, 10.0) };
            let fix = |v: f64| {
                let c = v.clamp(lo * target, hi * target) - v;
                c.max(-10.0 * target)
            };
            let (rxs2, rtv2, next) = if self.cone == 3 {
                // in the scaled space, the trial point's product (lam + ap W^-1 dx) o (lam + ad W ds),
                // its two eigenvalues (v0 +- |v1, v2|) each brought within the bounds
                let mut rxs2 = rxs.clone();
                cones(self.par.as_ref(), &mut rxs2, &mut [], (), |_, _| (), |c0, rxs2, _| {
                    for (j, t) in rxs2.chunks_exact_mut(3).enumerate() {
                        let (c, w) = (c0 + j, &nt[c0 + j]);
                        let (a, b) = (w.apply_inv(tri(&d.dx, c)), w.apply(tri(&d.ds, c)));
                        let v = jordan(std::array::from_fn(|i| w.lam[i] + ap_t * a[i]), std::array::from_fn(|i| w.lam[i] + ad_t * b[i]));
                        let r = (v[1] * v[1] + v[2] * v[2]).sqrt();
                        let (f1, f2) = (fix(v[0] + r), fix(v[0] - r));
                        let (u1, u2) = if r > 0.0 { (v[1] / r, v[2] / r) } else { (1.0, 0.0) };
                        t[0] += 0.5 * (f1 + f2);
                        t[1] += 0.5 * (f1 - f2) * u1;
                        t[2] += 0.5 * (f1 - f2) * u2;
                    }
                });
                let next = self.direction_cones(p, res, &rxs2, nt, Live::Known(u, fu));
                (rxs2, vec![], next)
            } else {
                let rxs2: Vec<f64> =
                    (0..nx).map(|i| rxs[i] + fix((p.x[i] + ap_t * d.dx[i]) * (p.s[i] + ad_t * d.ds[i]))).collect();
                let rtv2: Vec<f64> =
                    (0..m).map(|i| rtv[i] + fix((p.t[i] + ap_t * d.dt[i]) * (p.v[i] + ad_t * d.dv[i]))).collect();
                let next = self.direction(p, res, &rxs2, &rtv2, theta, Live::Known(u, fu));
                (rxs2, rtv2, next)
            };
            let Some((d2, (ap2, ad2))) = next else {
                break;
            };
            if ap2 + ad2 < 1.01 * (ap + ad) {
                break;
            }
            steps = (ap2, ad2);
            d = d2;
            rxs = rxs2;
            rtv = rtv2;
        }
        (d, rxs, rtv)
    }

    /// Assembles `sum_k A_k Theta_k A_k^T` (lambda's column left out): Theta diagonal, or
    /// where the variables are in second-order cones, `W^2` of each cone's scaling in `nt`.
    pub(super) fn assemble(&mut self, theta: &[f64], nt: &[Nt]) {
        if let Some(cf) = self.corners.take() {
            self.assemble_corners(&cf, nt);
            self.corners = Some(cf);
            return;
        }
        let (rows, nv) = (self.rows, self.nv);
        self.normal.values_mut().fill(0.0);
        let mut ai = vec![0.0; nv];
        for k in 0..self.m {
            let a = &self.acols[rows * nv * k..rows * nv * (k + 1)];
            let th = &theta[nv * k..nv * k + nv];
            let slots = &self.slots[rows * rows * k..rows * rows * (k + 1)];
            let vals = self.normal.values_mut();
            for i in 0..rows {
                if slots[rows * i + i] == u32::MAX {
                    continue;
                }
                let a_i = &a[nv * i..nv * i + nv];
                ai.iter_mut().zip(a_i.iter().zip(th)).for_each(|(o, (a, t))| *o = a * t);
                for j in i..rows {
                    let s = slots[rows * i + j];
                    if s == u32::MAX {
                        continue;
                    }
                    let v: f64 = ai.iter().zip(&a[nv * j..nv * j + nv]).map(|(p, q)| p * q).sum();
                    vals[s as usize] += v;
                    if j != i {
                        vals[slots[rows * j + i] as usize] += v;
                    }
                }
            }
        }
    }

    /// Solves `A Theta A^T z = r` in place with the factorization; None if the solution is not
    /// finite.
    pub(super) fn solve_normal(&mut self, r: &mut [f64]) -> Option<()> {
        self.normal.solve_in_place(r).ok()
    }

    /// Corrects direction `d` (of complementarity targets `rxs`, `rtv`) until it meets the
    /// primal equation `A dx - f_live dlam = rb` and lambda's dual row `-f_live . dy = rl` to
    /// [`DIRECTION_ACCURACY`] (or [`DIRECTION_FRACTION`] of the residual), at most
    /// [`REFINEMENTS`] times: the bordered system solved for the
    /// residuals `(r, r_l)` gives `(z, dl)`, and `dy += z`, `dlam += dl`, `dx += Theta A^T z`
    /// (which keeps the dual rows), with ds, dt and dv following dx. `fu = f_live . u`.
    ///
    /// Why the residuals of the equations and not of the normal equations: near the optimum
    /// Theta spans 1e-12 to 1e12, and `dx = Theta (A^T dy - xi)` loses to cancellation what a
    /// large Theta multiplies, however exact dy is (primal residuals of 1e-4 at 10^4 blocks,
    /// and no convergence on a 9,331-block wall in 3D); the correction, small itself, is
    /// computed without that loss. None if a solve fails.
    fn refine(&mut self, ipm: &Ipm, d: &mut Direction, rxs: &[f64], rtv: &[f64], fu: f64) -> Option<()> {
        let (p, res, theta, u) = (&ipm.p, &ipm.res, &ipm.theta, &ipm.u);
        let mut r = vec![0.0; self.n];
        let mut c = vec![0.0; theta.len()];
        // a fraction of the residual where it is far above the tolerance
        let fraction = |r: f64, scale: f64| if r > DIRECTION_FRACTION_ABOVE * scale { DIRECTION_FRACTION * r } else { 0.0 };
        let accuracy = (DIRECTION_ACCURACY * (1.0 + ipm.b_norm)).max(fraction(norm_inf(&res.rb), 1.0 + ipm.b_norm));
        let acc_l = DIRECTION_ACCURACY.max(fraction(res.rl.abs(), 1.0));
        let residual = |lp: &Self, d: &Direction, r: &mut [f64]| {
            lp.apply(&d.dx, d.dlam, r);
            r.iter_mut().zip(&res.rb).for_each(|(r, b)| *r = b - *r);
            let r_l = res.rl + dot(&lp.f_live, &d.dy);
            ((norm_inf(r) / accuracy).max(r_l.abs() / acc_l), r_l)
        };
        let (mut worst, mut r_l) = residual(self, d, &mut r);
        for _ in 0..REFINEMENTS {
            if worst <= 1.0 {
                break;
            }
            let kept = (d.dx.clone(), d.dy.clone(), d.dlam);
            self.solve_normal(&mut r)?;
            let dl = -(r_l + dot(&self.f_live, &r)) / fu;
            r.iter_mut().zip(u).for_each(|(z, u)| *z += dl * u);
            d.dy.iter_mut().zip(&r).for_each(|(dy, z)| *dy += z);
            d.dlam += dl;
            self.apply_t(&r, &mut c);
            if self.cone == 3 {
                let (nt, c) = (&ipm.nt, &c);
                cones(self.par.as_ref(), &mut d.dx, &mut [], (), |_, _| (), |c0, dx, _| {
                    for (j, dx) in dx.chunks_exact_mut(3).enumerate() {
                        let wc = nt[c0 + j].theta_mul(tri(c, c0 + j));
                        (0..3).for_each(|i| dx[i] += wc[i]);
                    }
                });
            } else {
                d.dx.iter_mut().zip(theta.iter().zip(&c)).for_each(|(dx, (t, c))| *dx += t * c);
            }
            let (now, now_l) = residual(self, d, &mut r);
            if now >= worst {
                // the factorization is too poor for the correction to converge: the direction
                // before it is the better one
                (d.dx, d.dy, d.dlam) = kept;
                break;
            }
            (worst, r_l) = (now, now_l);
        }
        (d.ds, d.dt, d.dv) = if self.cone == 3 {
            (duals_of_cones(self.par.as_ref(), &ipm.nt, rxs, &d.dx), vec![], vec![])
        } else {
            self.duals_of(p, res, rxs, rtv, &d.dx)
        };
        let ok = d.dx.iter().chain(&d.dy).chain(&d.ds).chain(&d.dv).all(|v| v.is_finite()) && d.dlam.is_finite();
        ok.then_some(())
    }

    /// The rest of a direction given its `dx`: ds from the complementarity targets `rxs`, and
    /// the bounds' dt and dv (targets `rtv`).
    fn duals_of(&self, p: &Iterate, res: &Residuals, rxs: &[f64], rtv: &[f64], dx: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let m = self.n_bounded();
        let ds: Vec<f64> = (0..dx.len()).map(|i| (rxs[i] - p.s[i] * dx[i]) / p.x[i]).collect();
        let dt: Vec<f64> = (0..m).map(|i| res.ru[i] - dx[self.bounded_var(i)]).collect();
        let dv: Vec<f64> = (0..m).map(|i| (rtv[i] - p.v[i] * dt[i]) / p.t[i]).collect();
        (ds, dt, dv)
    }

    /// The Newton direction for the complementarity targets `rxs` (x s) and `rtv` (t v), with
    /// the normal matrix factorized and `u = M^-1 f_live`, and the longest steps along it
    /// ([`Iterate::max_steps`]); None if a solve fails or the direction is not finite.
    ///
    /// With `Theta = 1 / (s / x + v / t)` and `xi = rc - rxs / x + (rtv - v ru) / t`:
    /// `dx = Theta (A^T dy - xi)`, `M dy - f_live dlam = rb + A Theta xi` (M = A Theta A^T) and
    /// lambda's dual row `-f_live . dy = rl`: `dy = M^-1 (q + f_live dlam)`, one solve and `u`.
    /// dx, ds, the step lengths and the check that they are finite come out of one pass over
    /// the variables (in 3D they are 15 times the equations, and each pass streams memory).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn direction(
        &mut self,
        p: &Iterate,
        res: &Residuals,
        rxs: &[f64],
        rtv: &[f64],
        theta: &[f64],
        live: Live,
    ) -> Option<(Direction, (f64, f64))> {
        const LANES: usize = 8;
        let m = self.n_bounded();
        let nx = theta.len();
        let mut xi: Vec<f64> = (0..nx).map(|i| res.rc[i] - rxs[i] / p.x[i]).collect();
        for i in 0..m {
            xi[self.bounded_var(i)] += (rtv[i] - p.v[i] * res.ru[i]) / p.t[i];
        }
        // Theta xi, whose buffer then takes dx
        let mut dx: Vec<f64> = theta.iter().zip(&xi).map(|(t, x)| t * x).collect();
        let (dy, dlam) = self.dual_direction(res, &mut dx, live)?;
        let mut ds = vec![0.0; nx];
        // per lane: the primal and dual step lengths, and a sum that is NaN if a value is not
        // finite
        let ratio = |v: f64, d: f64| if d < 0.0 { -v / d } else { 1.0 };
        let (mut lp, mut ld, mut nan) = ([1.0f64; LANES], [1.0f64; LANES], [0.0f64; LANES]);
        let whole = nx - nx % LANES;
        for c in (0..whole).step_by(LANES) {
            for k in 0..LANES {
                let i = c + k;
                let d = theta[i] * (dx[i] - xi[i]);
                let e = (rxs[i] - p.s[i] * d) / p.x[i];
                dx[i] = d;
                ds[i] = e;
                lp[k] = lp[k].min(ratio(p.x[i], d));
                ld[k] = ld[k].min(ratio(p.s[i], e));
                nan[k] += 0.0 * (d + e);
            }
        }
        // the rest, the same body in lane 0 (one closure for both loops ran 2-5% slower in 3D:
        // the lanes no longer vectorized)
        for i in whole..nx {
            let d = theta[i] * (dx[i] - xi[i]);
            let e = (rxs[i] - p.s[i] * d) / p.x[i];
            dx[i] = d;
            ds[i] = e;
            lp[0] = lp[0].min(ratio(p.x[i], d));
            ld[0] = ld[0].min(ratio(p.s[i], e));
            nan[0] += 0.0 * (d + e);
        }
        let dt: Vec<f64> = (0..m).map(|i| res.ru[i] - dx[self.bounded_var(i)]).collect();
        let dv: Vec<f64> = (0..m).map(|i| (rtv[i] - p.v[i] * dt[i]) / p.t[i]).collect();
        let fold = |l: [f64; LANES]| l.iter().fold(1.0f64, |a, &b| a.min(b));
        let ap = fold(lp).min(max_step(&p.t, &dt));
        let ad = fold(ld).min(max_step(&p.v, &dv));
        let finite = nan.iter().sum::<f64>() == 0.0 && dv.iter().all(|v| v.is_finite());
        finite.then_some((Direction { dx, ds, dt, dv, dy, dlam }, (ap, ad)))
    }

    /// The direction's dy and dlam from `Theta xi` (in `txi`, which then takes `A^T dy`):
    /// `M dy - f_live dlam = rb + A Theta xi` and lambda's dual row `-f_live . dy = rl`, so
    /// `dy = q + u dlam` with `q = M^-1 (rb + A Theta xi)`; None if the solve fails or dlam is
    /// not finite.
    fn dual_direction(&mut self, res: &Residuals, txi: &mut [f64], live: Live) -> Option<(Vec<f64>, f64)> {
        let n = self.n;
        let mut q = vec![0.0; n];
        self.apply(txi, 0.0, &mut q);
        for (q, r) in q.iter_mut().zip(&res.rb) {
            *q += r;
        }
        let (u, fu) = match live {
            Live::Known(u, fu) => {
                self.solve_normal(&mut q)?;
                (u, fu)
            }
            Live::Solve(u, fu) => {
                // f_live and q in one pass over the factor
                let mut both = Vec::with_capacity(2 * n);
                both.extend_from_slice(&self.f_live);
                both.extend_from_slice(&q);
                self.normal.solve_columns_in_place(&mut both, 2).ok()?;
                u.copy_from_slice(&both[..n]);
                q.copy_from_slice(&both[n..]);
                *fu = dot(&self.f_live, u);
                (&*u, *fu)
            }
        };
        // -f . (q + u dlam) = rl; q (finite after a solve) becomes dy
        let dlam = -(res.rl + dot(&self.f_live, &q)) / fu;
        if !dlam.is_finite() {
            return None;
        }
        q.iter_mut().zip(u).for_each(|(q, u)| *q += dlam * u);
        self.apply_t(&q, txi);
        Some((q, dlam))
    }

    /// Mehrotra's predictor and corrector where the variables are in second-order cones (see
    /// [`Self::predictor_corrector`]): the targets in the scaled space, `-lam o lam` and
    /// `sigma mu e - lam o lam - (W^-1 dx) o (W ds)` of the predictor's direction.
    #[allow(clippy::type_complexity)]
    fn predictor_corrector_cones(&mut self, ipm: &mut Ipm, mu: f64) -> Option<(Direction, Vec<f64>, Vec<f64>, (f64, f64), f64)> {
        let Ipm { p, res, u, fu, nt, ncomp, .. } = ipm;
        let mut r = vec![0.0; p.x.len()];
        cones(self.par.as_ref(), &mut r, &mut [], (), |_, _| (), |c0, r, _| {
            for (w, r) in nt[c0..].iter().zip(r.chunks_exact_mut(3)) {
                let ll = jordan(w.lam, w.lam);
                (0..3).for_each(|i| r[i] = -ll[i]);
            }
        });
        let (aff, (ap, ad)) = self.direction_cones(p, res, &r, nt, Live::Solve(u, fu))?;
        let comp = p.x.iter().zip(&aff.dx).zip(p.s.iter().zip(&aff.ds)).map(|((x, dx), (s, ds))| (x + ap * dx) * (s + ad * ds)).sum::<f64>();
        let sigma = (comp / *ncomp / mu).powi(3).min(SIGMA_MAX);
        cones(self.par.as_ref(), &mut r, &mut [], (), |_, _| (), |c0, r, _| {
            for (j, r) in r.chunks_exact_mut(3).enumerate() {
                let (c, w) = (c0 + j, &nt[c0 + j]);
                let so = jordan(w.apply_inv(tri(&aff.dx, c)), w.apply(tri(&aff.ds, c)));
                let ll = jordan(w.lam, w.lam);
                r[0] = sigma * mu - ll[0] - so[0];
                r[1] = -ll[1] - so[1];
                r[2] = -ll[2] - so[2];
            }
        });
        let (d, steps) = self.direction_cones(p, res, &r, nt, Live::Known(u, *fu))?;
        Some((d, r, vec![], steps, sigma * mu))
    }

    /// The Newton direction where the variables are in second-order cones, for the targets `r`
    /// of `lam o (W ds + W^-1 dx)`, and the longest steps along it: as
    /// [`Self::direction`] with `Theta = W^2` and `xi = rc - W^-1 (lam \ r)`, and
    /// `ds = W^-1 (lam \ r - W^-1 dx)`.
    fn direction_cones(
        &mut self,
        p: &Iterate,
        res: &Residuals,
        r: &[f64],
        nt: &[Nt],
        live: Live,
    ) -> Option<(Direction, (f64, f64))> {
        let nx = p.x.len();
        // per cone xi and h = lam \ r (for ds), and W^2 xi, whose buffer then takes dx
        let (mut dx, mut xh) = (vec![0.0; nx], vec![0.0; 2 * nx]);
        cones(self.par.as_ref(), &mut dx, &mut xh, (), |_, _| (), |c0, dx, xh| {
            for (j, (dx, xh)) in dx.chunks_exact_mut(3).zip(xh.chunks_exact_mut(6)).enumerate() {
                let (c, w) = (c0 + j, &nt[c0 + j]);
                let hc = w.lam_div(tri(r, c));
                let g = w.apply_inv(hc);
                let x: [f64; 3] = std::array::from_fn(|i| res.rc[3 * c + i] - g[i]);
                xh[..3].copy_from_slice(&x);
                xh[3..].copy_from_slice(&hc);
                dx.copy_from_slice(&w.theta_mul(x));
            }
        });
        let (dy, dlam) = self.dual_direction(res, &mut dx, live)?;
        // one pass: dx = W^2 (A^T dy - xi), ds = W^-1 (h - W^-1 dx), the steps, finiteness
        let mut ds = vec![0.0; nx];
        let xh = &xh;
        let min3 = |a: (f64, f64, f64), b: (f64, f64, f64)| (a.0.min(b.0), a.1.min(b.1), a.2 + b.2);
        let (ap, ad, nan) = cones(self.par.as_ref(), &mut dx, &mut ds, (1.0, 1.0, 0.0), min3, |c0, dx, ds| {
            let (mut ap, mut ad, mut nan) = (1.0f64, 1.0f64, 0.0);
            for (j, (dxc, dsc)) in dx.chunks_exact_mut(3).zip(ds.chunks_exact_mut(3)).enumerate() {
                let (c, w) = (c0 + j, &nt[c0 + j]);
                let d = w.theta_mul(std::array::from_fn(|i| dxc[i] - xh[6 * c + i]));
                let v = w.apply_inv(d);
                let e = w.apply_inv(std::array::from_fn(|i| xh[6 * c + 3 + i] - v[i]));
                ap = cone_step_upto(tri(&p.x, c), d, ap);
                ad = cone_step_upto(tri(&p.s, c), e, ad);
                dxc.copy_from_slice(&d);
                dsc.copy_from_slice(&e);
                nan += 0.0 * (d[0] + d[1] + d[2] + e[0] + e[1] + e[2]);
            }
            (ap, ad, nan)
        });
        let finite = nan == 0.0;
        finite.then_some((Direction { dx, ds, dt: vec![], dv: vec![], dy, dlam }, (ap, ad)))
    }
}

/// The dual direction of the cones' primal `dx` for the targets `r`: `ds = W^-1 (lam \ r - W^-1 dx)`.
fn duals_of_cones(par: Option<&Par>, nt: &[Nt], r: &[f64], dx: &[f64]) -> Vec<f64> {
    let mut ds = vec![0.0; dx.len()];
    cones(par, &mut ds, &mut [], (), |_, _| (), |c0, ds, _| {
        for (j, o) in ds.chunks_exact_mut(3).enumerate() {
            let (c, w) = (c0 + j, &nt[c0 + j]);
            let h = w.lam_div(tri(r, c));
            let v = w.apply_inv(tri(dx, c));
            o.copy_from_slice(&w.apply_inv(std::array::from_fn(|i| h[i] - v[i])));
        }
    });
    ds
}

