//! The linear program of a wall in the plane: each interface's resultants as a vertex, four rays and a
//! bounded segment of its strength domain, the equilibrium rows, and the resultants of a solution.

use super::*;

/// The program of a wall in the plane: the generic [`Lp`] (each interface one element of six
/// equations and [`NV`] variables, theta bounded by 1) and what its strength domains need:
/// each interface's resultants are `s = V + sum_j rho_j R_j + theta dV` with `rho >= 0`,
/// `0 <= theta <= 1`: the strength domain's recession cone has four rays
/// `R_j = (-1, +-a, +-1)` (in (N, T, 2M/l); a: the Coulomb slope; the rays of two contact
/// points at the interface's ends), and its vertices are the two ends `V`, `V + dV` of one
/// segment (equal for joints without strength).
pub(super) struct Plane {
    pub(super) lp: Lp,
    /// per interface: its 6 x 3 block of the equilibrium matrix, scaled (columns N, T, 2M/l)
    pub(super) cols: Vec<[[f64; 3]; 6]>,
    /// the faces' right-hand sides of each interface over the force scale: Coulomb (c A, or
    /// the capacity fixed in the non-associative sequence) and tension (ft A); the Coulomb slope
    pub(super) hc: Vec<f64>,
    pub(super) ht: Vec<f64>,
    pub(super) slope: Vec<f64>,
    /// the strength domain's own (c A over the force scale, mu, tan(psi)) of each interface
    pub(super) coulomb: Vec<(f64, f64, f64)>,
}

/// Variables per interface: four rays and the position on the vertices' segment.
pub(super) const NV: usize = 5;

/// The vertex `V`, the segment `dV` and the four rays of a domain
/// `a N +- T <= hc`, `N +- 2M/l <= ht` (scaled).
pub(super) fn generators(a: f64, hc: f64, ht: f64) -> [[f64; 3]; 6] {
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

/// The equation of each dof of `model` (None for a support: a fixed dof or one held after the
/// dead loads), numbered in dof order, and the number of equations.
fn equations(model: &Model) -> (Vec<Option<usize>>, usize) {
    let mut support = model.fixed().to_vec();
    for &d in model.held_after_dead() {
        support[d] = true;
    }
    let mut eq = vec![None; 3 * model.n_blocks()];
    let mut n = 0;
    for (d, e) in eq.iter_mut().enumerate() {
        if !support[d] {
            *e = Some(n);
            n += 1;
        }
    }
    (eq, n)
}

/// The program's scales: forces (the largest dead force, else the largest live one, else 1),
/// lengths (the mean interface length, else 1) and the live load (its largest force or
/// moment, else 1).
fn scales(model: &Model) -> (f64, f64, f64) {
    let nb = model.n_blocks();
    let its = model.interfaces();
    let m = its.len();
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
    (force, length, live)
}

/// The scale of dof `d`'s equation: rotation rows are divided by the length scale.
fn row_scale(d: usize, length: f64) -> f64 {
    if d % 3 == 2 {
        1.0 / length
    } else {
        1.0
    }
}

/// Per interface of `model`: the equations of its 6 dofs ([`NO_EQ`] for a support) and its
/// 6 x 3 block of the equilibrium matrix, scaled (columns N, T, 2M/l).
fn equilibrium_columns(model: &Model, eq: &[Option<usize>], length: f64) -> (Vec<[u32; 6]>, Vec<[[f64; 3]; 6]>) {
    let its = model.interfaces();
    let m = its.len();
    let (mut dofs, mut cols) = (Vec::with_capacity(m), Vec::with_capacity(m));
    for it in its {
        let gd = it.dofs();
        let mut d6 = [NO_EQ; 6];
        let mut c6 = [[0.0; 3]; 6];
        for r in 0..6 {
            d6[r] = eq[gd[r]].map_or(NO_EQ, |e| e as u32);
            let s = row_scale(gd[r], length);
            c6[r] = [it.b_mat[0][r] * s, it.b_mat[1][r] * s, it.b_mat[2][r] * s * 0.5 * it.l];
        }
        dofs.push(d6);
        cols.push(c6);
    }
    (dofs, cols)
}

/// Per interface, over the force scale: the Coulomb faces' right-hand side (c A), the tension
/// cut-off's (ft A), and the strength domain's own (c A, mu, tan(psi)).
struct Strengths {
    hc: Vec<f64>,
    ht: Vec<f64>,
    coulomb: Vec<(f64, f64, f64)>,
}

/// The [`Strengths`] of the interfaces of `model` at their peak, over the force scale `force`.
fn strengths(model: &Model, force: f64) -> Strengths {
    let m = model.interfaces().len();
    let (mut hc, mut ht, mut coulomb) = (Vec::with_capacity(m), Vec::with_capacity(m), Vec::with_capacity(m));
    for (k, section) in model.sections().iter().enumerate().take(m) {
        let law = model.law(k);
        let (c, ft) = law.strengths(&JointState::default());
        let a = section.area;
        hc.push(c * a / force);
        ht.push(ft * a / force);
        coulomb.push((c * a / force, law.friction, law.dilatancy));
    }
    Strengths { hc, ht, coulomb }
}

impl Plane {
    /// The program of `model`: its equations (one per free dof), scaled, each interface's
    /// columns and strengths, and the normal matrix's pattern with each interface's slots in it.
    pub(super) fn new(model: &Model) -> Result<Self> {
        let nb = model.n_blocks();
        let (eq, n) = equations(model);
        let (force, length, live) = scales(model);
        let (dofs, cols) = equilibrium_columns(model, &eq, length);
        let Strengths { mut hc, mut ht, mut coulomb } = strengths(model, force);
        let (fd, fl) = (model.dead_load(), model.live_load());
        // strengths beyond STRENGTH_CAP times the total load cannot be reached within lambda's
        // range: they are capped there (a glued joint), which keeps the program well scaled
        let total =
            (0..3 * nb).filter(|&d| eq[d].is_some()).map(|d| (fd[d] / force).abs() + (fl[d] / live).abs()).sum::<f64>();
        let cap = STRENGTH_CAP * total.max(1.0);
        hc.iter_mut().chain(ht.iter_mut()).for_each(|h| *h = h.min(cap));
        coulomb.iter_mut().for_each(|c| c.0 = c.0.min(cap));
        let free = |d: &usize| eq[*d].is_some();
        let f_dead = (0..3 * nb).filter(free).map(|d| fd[d] * row_scale(d, length) / force).collect();
        let f_live = (0..3 * nb).filter(free).map(|d| fl[d] * row_scale(d, length) / live).collect();
        let flat = dofs.iter().flatten().copied().collect();
        // dry associative joints: each domain is the cone of its four rays alone (the two
        // contact points' n +- mu t, Livesley's form); the segment's variable would have a zero
        // column, and the non-associative sequence, which moves the vertex, is not run
        let points = hc.iter().chain(&ht).all(|&h| h == 0.0) && coulomb.iter().all(|c| c.2 >= c.1);
        let (nv, bounded) = if points { (NV - 1, None) } else { (NV, Some(NV - 1)) };
        let lp = Lp::new(eq, n, 6, nv, bounded, flat, f_dead, f_live, (force, length, live))?;
        let slope = coulomb.iter().map(|c| c.1).collect();
        let mut plane = Plane { lp, cols, hc, ht, slope, coulomb };
        plane.lp.acols = vec![0.0; plane.lp.m * 6 * nv];
        // point contacts (blocks moved by finite rotations) carry no moment: a block on points
        // alone leaves its rotation row to the live load's column, and the normal matrix singular
        let points = model.interfaces().iter().any(|it| it.l == 0.0);
        plane.lp.regularize_frictionless(plane.slope.contains(&0.0) || points);
        plane.fill();
        Ok(plane)
    }

    /// Each interface's block `A_k` and vertex contribution `P_k` in the program, from its
    /// columns and strength domain.
    fn fill(&mut self) {
        for k in 0..self.lp.m {
            let (a, pv) = self.columns(k);
            let nv = self.lp.nv;
            for (r, row) in a.iter().enumerate() {
                self.lp.acols[(6 * k + r) * nv..(6 * k + r + 1) * nv].copy_from_slice(&row[..nv]);
            }
            self.lp.pv[6 * k..6 * k + 6].copy_from_slice(&pv);
        }
    }

    /// Fixes the Coulomb faces' capacity from normal forces (scaled), for the non-associative
    /// sequence: `|T| + tan(psi) N <= c A - (mu - tan(psi)) N_prev`.
    pub(super) fn fix_shear_capacity(&mut self, normals: &[f64]) {
        for (k, &(ca, mu, tp)) in self.coulomb.iter().enumerate() {
            self.hc[k] = (ca - (mu - tp) * normals[k]).max(0.0);
            self.slope[k] = tp;
        }
        self.fill();
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
    pub(super) fn resultants(&self, x: &[f64]) -> Vec<[f64; 3]> {
        (0..self.lp.m)
            .map(|k| {
                let g = generators(self.slope[k], self.hc[k], self.ht[k]);
                let nv = self.lp.nv;
                let xk = &x[nv * k..nv * k + nv];
                let mut s = g[0];
                for (j, gj) in [g[2], g[3], g[4], g[5], g[1]].iter().take(nv).enumerate() {
                    for i in 0..3 {
                        s[i] += xk[j] * gj[i];
                    }
                }
                s
            })
            .collect()
    }
}
