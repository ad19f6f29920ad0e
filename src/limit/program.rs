//! The linear program in the form the interior point solves, the same in both dimensions:
//! maximise lambda subject to `sum_k (P_k + A_k x_k) = f_dead + lambda f_live` over the free
//! dofs, `x >= 0`, and in the plane one variable of each interface also bounded by 1.
//!
//! Each interface (an element of the program) contributes a block `A_k` of `rows` equations
//! (the dofs of its two blocks) by `nv` variables, and a constant `P_k` (the contribution of a
//! vertex of its strength domain). How the variables describe the strength domain is the
//! dimension's business ([`super::plane`], [`super::space`]); the interior point sees only
//! these blocks. The normal matrix `sum_k A_k Theta_k A_k^T` has the pattern of the stiffness
//! matrix: one `rows x rows` block per interface, analysed once.

use super::cone::Nt;
use super::*;
use rayon::prelude::*;

/// A dof held by a support: no equation.
pub(super) const NO_EQ: u32 = u32::MAX;

/// The program, scaled to forces of order one.
pub(super) struct Lp {
    /// Elements (interfaces) and equations.
    pub(super) m: usize,
    pub(super) n: usize,
    /// Equations per element (the dofs of its two blocks) and variables per element (in
    /// [`Corners`] form, where contacts have their own numbers of corners: unused, 0).
    pub(super) rows: usize,
    pub(super) nv: usize,
    /// The element's variable that is also bounded above by 1, if any.
    pub(super) bounded: Option<usize>,
    /// The equation of each dof, or None for a support.
    pub(super) eq: Vec<Option<usize>>,
    /// Per element: the equations of its dofs ([`NO_EQ`] for a support), `rows` each.
    pub(super) dofs: Vec<u32>,
    /// Per element: `A_k`, `rows x nv` row-major (empty when the program is in [`Corners`]
    /// form).
    pub(super) acols: Vec<f64>,
    /// The blocks `A_k` in factored form, where they are forces at contact points (3D).
    pub(super) corners: Option<Corners>,
    /// The threads of the passes over contacts and cones, where there is more than one.
    pub(super) par: Option<Par>,
    /// The dimension of the cones the variables lie in, in groups of that many: 1 (the
    /// orthant, `x >= 0`) or 3 (second-order cones `x0 >= |(x1, x2)|`).
    pub(super) cone: usize,
    /// Per element: `P_k`, `rows` each.
    pub(super) pv: Vec<f64>,
    /// Per element: the value slot of each entry of its `rows x rows` block in the normal
    /// matrix (`u32::MAX` for a support's row or column).
    pub(super) slots: Vec<u32>,
    pub(super) f_dead: Vec<f64>,
    pub(super) f_live: Vec<f64>,
    /// Scales: forces, lengths (rotation rows are divided by it), the live load.
    pub(super) force: f64,
    pub(super) length: f64,
    pub(super) live: f64,
    pub(super) normal: SparseLu,
    /// The normal matrix's diagonal slots, where it is regularized ([`Lp::regularize_frictionless`]).
    pub(super) diagonal: Option<Vec<u32>>,
    /// Whether lambda is a force of either sign (a support movement's, [`super::follow_movement`]):
    /// an optimum below zero is then no failure of the dead state.
    pub(super) signed: bool,
}

impl Lp {
    /// The program's frame: `eq` (the equation of each dof), each element's dofs' equations
    /// (`rows` each), `nv` variables per element, the loads (scaled, one per equation) and the
    /// scales; the normal matrix's pattern analysed once. The blocks `A_k`, `P_k` start at
    /// zero (`P_k`) or empty (`A_k`): the dimension sets them.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn new(
        eq: Vec<Option<usize>>,
        n: usize,
        rows: usize,
        nv: usize,
        bounded: Option<usize>,
        dofs: Vec<u32>,
        f_dead: Vec<f64>,
        f_live: Vec<f64>,
        (force, length, live): (f64, f64, f64),
    ) -> Result<Lp> {
        let m = dofs.len() / rows;
        let (normal, slots) = normal_pattern(n, rows, &dofs)?;
        Ok(Lp {
            m,
            n,
            rows,
            nv,
            bounded,
            eq,
            dofs,
            acols: vec![],
            corners: None,
            par: None,
            cone: 1,
            pv: crate::error::try_filled("the program's vertices", m * rows, 0.0)?,
            slots,
            f_dead,
            f_live,
            force,
            length,
            live,
            normal,
            diagonal: None,
            signed: false,
        })
    }

    /// Regularizes the normal matrix where joints have no friction (`frictionless`): the
    /// mechanisms that slide on them meet no resistance, the normal matrix is singular along
    /// them, and where the live load works on them its solves fail (the plane's wall 1 of
    /// friction 0 was said to have no equilibrium under its dead loads, a leaf in 3D not to
    /// converge; the answer is lambda = 0, the wall sliding). [`REGULARIZATION`] times its
    /// largest diagonal entry added to its diagonal makes it definite; the directions'
    /// corrections (against the equations, not the normal matrix) keep the iterates to the
    /// tolerance, as their certificate shows.
    pub(super) fn regularize_frictionless(&mut self, frictionless: bool) {
        self.diagonal = frictionless.then(|| (0..self.n).map(|r| self.normal.slot(r, r).expect("the diagonal is in the pattern") as u32).collect());
    }

    /// Variables bounded by 1: one per element, or none.
    #[inline]
    pub(super) fn n_bounded(&self) -> usize {
        if self.bounded.is_some() {
            self.m
        } else {
            0
        }
    }

    /// The variable bounded by `t[i]`: element i's bounded one.
    #[inline]
    pub(super) fn bounded_var(&self, i: usize) -> usize {
        self.nv * i + self.bounded.unwrap_or(0)
    }

    /// The number of variables: `nv` per element, or in [`Corners`] form `sides` per corner and
    /// three per disc.
    pub(super) fn n_vars(&self) -> usize {
        match &self.corners {
            Some(cf) => cf.sides * cf.start[self.m] + 3 * cf.discs.corner.len(),
            None => self.nv * self.m,
        }
    }

    /// lambda in its own units from a scaled solution.
    pub(super) fn lambda_of(&self, s: &Solution) -> f64 {
        s.lambda * self.force / self.live
    }

    /// The block velocities (`dofs_per_block` per block, in dof order) of the duals of the
    /// equilibrium rows, rotations unscaled: the mechanism before its normalization.
    pub(super) fn velocities(&self, sol: &Solution, dofs_per_block: usize) -> Vec<f64> {
        let half = dofs_per_block / 2;
        let rot = |dof: usize| {
            if dofs_per_block == 3 {
                dof % 3 == 2
            } else {
                dof % dofs_per_block >= half
            }
        };
        self.eq
            .iter()
            .enumerate()
            .map(|(dof, e)| e.map_or(0.0, |e| sol.y[e] * if rot(dof) { 1.0 / self.length } else { 1.0 }))
            .collect()
    }
}

/// The blocks of a program whose variables are the weights of generators of forces at the
/// corners of contacts between two rigid bodies (3D: six equations per body, forces then
/// moments), stored factored: `A_k = C_k G_k`, with `G_k` each corner's generators (the same at
/// every corner of a contact) and `C_k` what a force at a corner does to the two bodies (minus
/// it and its moment on b, plus on a). Per contact of 4 corners 33 numbers where `A_k` has 144:
/// the interior point's products stream memory. Each contact has its own number of corners
/// (the vertices of its polygon, 3 or more), its variables one after the other's.
///
/// Contacts with cohesion add at some corners a disc of shear forces of a bounded radius
/// ([`Discs`]): a cone `(z0, z1, z2)`, its force `z1 t1 + z2 t2` at the corner, and `z0` held
/// at the radius by an equation of its own, which the element's rows after its twelve dofs'
/// hold.
pub(super) struct Corners {
    /// The first corner of each contact, then the number of corners: contact k's corners are
    /// `start[k]..start[k + 1]`.
    pub(super) start: Vec<usize>,
    /// Generators per corner.
    pub(super) sides: usize,
    /// Per contact, its generators (3 each, global axes).
    pub(super) gens: Vec<[f64; 3]>,
    /// Per corner, its position from a's centroid then from b's, over the length scale (the
    /// moment rows are scaled by it).
    pub(super) arms: Vec<[[f64; 3]; 2]>,
    /// The discs of cohesion (none for dry joints).
    pub(super) discs: Discs,
}

/// The discs of shear forces of bounded radius that cohesion adds at contact corners: their
/// variables follow every corner's, three per disc, in the order of the contacts; disc `q` of
/// contact k (`start[k] + q`) has its radius's equation at the element's row `12 + q`.
#[derive(Default)]
pub(super) struct Discs {
    /// The first disc of each contact, then the number of discs (empty: none).
    pub(super) start: Vec<usize>,
    /// Per disc, its corner.
    pub(super) corner: Vec<usize>,
    /// Per disc, its contact.
    pub(super) contact: Vec<u32>,
    /// Per contact with discs, its tangents (t1, t2) in global axes (empty: none).
    pub(super) tangents: Vec<[[f64; 3]; 2]>,
}

impl Discs {
    /// The discs of contact k.
    #[inline]
    pub(super) fn of(&self, k: usize) -> std::ops::Range<usize> {
        if self.start.is_empty() {
            0..0
        } else {
            self.start[k]..self.start[k + 1]
        }
    }
}

impl Corners {
    /// The corners of contact k, as indices of corners.
    #[inline]
    pub(super) fn of(&self, k: usize) -> std::ops::Range<usize> {
        self.start[k]..self.start[k + 1]
    }

    /// The variables of corner c start at `sides c`.
    #[inline]
    pub(super) fn var(&self, c: usize) -> usize {
        self.sides * c
    }

    /// The variables of disc d start here, after every corner's.
    #[inline]
    pub(super) fn disc_var(&self, d: usize) -> usize {
        self.sides * self.start[self.start.len() - 1] + 3 * d
    }
}

/// The twelve rows (a's force and moment, then b's) of a force `f` at a corner of arms `ra`,
/// `rb`: what it does to the two bodies.
#[inline(always)]
fn force_rows(f: [f64; 3], ra: [f64; 3], rb: [f64; 3]) -> [f64; 12] {
    let (ma, mb) = (cross(ra, f), cross(rb, f));
    [f[0], f[1], f[2], ma[0], ma[1], ma[2], -f[0], -f[1], -f[2], -mb[0], -mb[1], -mb[2]]
}

/// Contacts per task of the parallel passes over contacts.
const GRAIN_CONTACTS: usize = 1024;

/// From this many contacts the passes of a program in corner form run on several threads: about
/// there the hand-offs cost what the second thread saves (U walls: 2,292 contacts 0.20-0.21 s on
/// one thread and on two; 3,610 contacts 0.350-0.362 s on two against 0.354-0.374 s on one).
const PAR_MIN_CONTACTS: usize = 2000;

/// The threads of a program in corner form and how its passes split among them. The products
/// `A x` and the normal matrix's assembly add each contact's part into the equations of its two
/// bodies: the equations are cut into one range per thread, and each part adds, in the contacts'
/// order, what its contacts put into its own range (a contact across a cut is computed by both
/// parts). Each sum is then made in the same order as on one thread: the results are the same to
/// the bit whatever the number of threads.
pub(super) struct Par {
    pub(super) pool: std::sync::Arc<rayon::ThreadPool>,
    /// the parts' first equations, then the number of equations
    eqs: Vec<usize>,
    /// the parts' first value slots in the normal matrix (its values are stored by column), then
    /// the number of values
    slots: Vec<usize>,
    /// per part, the contacts with an equation in its range, in order
    contacts: Vec<Vec<u32>>,
}

impl Par {
    /// `v` cut at `bounds` (the first 0, the last `v`'s length) into one slice per part.
    fn cut<'a>(v: &'a mut [f64], bounds: &[usize]) -> Vec<&'a mut [f64]> {
        let mut rest = v;
        let mut parts = Vec::with_capacity(bounds.len() - 1);
        for w in bounds.windows(2) {
            let (part, tail) = rest.split_at_mut(w[1] - w[0]);
            parts.push(part);
            rest = tail;
        }
        parts
    }
}

impl Lp {
    /// Runs the passes of a program in corner form on `threads` threads (0: all cores), where it
    /// has at least [`PAR_MIN_CONTACTS`] contacts; an error if the threads cannot be started.
    pub(super) fn start_threads(&mut self, threads: usize) -> Result<()> {
        if self.corners.is_none() || self.m < PAR_MIN_CONTACTS || threads == 1 {
            return Ok(());
        }
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| Error::input(format!("cannot start {threads} threads: {e}")))?;
        let parts = pool.current_num_threads();
        if parts < 2 {
            return Ok(());
        }
        let eqs: Vec<usize> = (0..=parts).map(|i| i * self.n / parts).collect();
        let slots = eqs.iter().map(|&e| self.normal.column_start(e)).collect();
        let mut contacts = vec![vec![]; parts];
        for (k, d) in self.dofs.chunks_exact(self.rows).enumerate() {
            for (p, list) in contacts.iter_mut().enumerate() {
                if d.iter().any(|&e| e != NO_EQ && (eqs[p]..eqs[p + 1]).contains(&(e as usize))) {
                    list.push(k as u32);
                }
            }
        }
        self.par = Some(Par { pool: std::sync::Arc::new(pool), eqs, slots, contacts });
        Ok(())
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

impl Lp {
    /// `out[dofs] += A_k x_k` for a program in corner form (on the threads, each part adding into
    /// its own equations).
    pub(super) fn apply_corners(&self, cf: &Corners, x: &[f64], out: &mut [f64]) {
        // contact k's forces added into `out`, whose first equation is `e0`
        let contact = |k: usize, out: &mut [f64], e0: usize| {
            let d = &self.dofs[self.rows * k..self.rows * (k + 1)];
            let g = &cf.gens[cf.sides * k..cf.sides * (k + 1)];
            // a support's NO_EQ wraps beyond every range
            let mut add = |e: u32, v: f64| {
                if let Some(o) = out.get_mut((e as usize).wrapping_sub(e0)) {
                    *o += v;
                }
            };
            for c in cf.of(k) {
                let xq = &x[cf.var(c)..cf.var(c) + cf.sides];
                let mut f = [0.0; 3];
                for (gj, xj) in g.iter().zip(xq) {
                    (0..3).for_each(|i| f[i] += xj * gj[i]);
                }
                let [ra, rb] = cf.arms[c];
                for (&e, v) in d.iter().zip(force_rows(f, ra, rb)) {
                    add(e, v);
                }
            }
            for (q, dd) in cf.discs.of(k).enumerate() {
                let xq = &x[cf.disc_var(dd)..cf.disc_var(dd) + 3];
                let [t1, t2] = cf.discs.tangents[k];
                let f: [f64; 3] = std::array::from_fn(|i| xq[1] * t1[i] + xq[2] * t2[i]);
                let [ra, rb] = cf.arms[cf.discs.corner[dd]];
                for (&e, v) in d.iter().zip(force_rows(f, ra, rb)) {
                    add(e, v);
                }
                add(d[12 + q], xq[0]);
            }
        };
        match &self.par {
            None => (0..self.m).for_each(|k| contact(k, out, 0)),
            Some(p) => {
                let parts = Par::cut(out, &p.eqs);
                p.pool.install(|| {
                    parts.into_par_iter().zip(&p.contacts).zip(&p.eqs).for_each(|((o, ks), &e0)| ks.iter().for_each(|&k| contact(k as usize, o, e0)))
                });
            }
        }
    }

    /// `A^T y` for a program in corner form: each generator's dot product with the velocity
    /// jump at its corner (on the threads, in chunks of contacts).
    pub(super) fn apply_t_corners(&self, cf: &Corners, y: &[f64], out: &mut [f64]) {
        // contacts k0..k1 into their variables `out`
        let contacts = |k0: usize, k1: usize, out: &mut [f64]| {
            let v0 = cf.var(cf.start[k0]);
            for k in k0..k1 {
                let o = &mut out[cf.var(cf.start[k]) - v0..cf.var(cf.start[k + 1]) - v0];
                let yv = self.dual_of(k, y);
                let g = &cf.gens[cf.sides * k..cf.sides * (k + 1)];
                for (q, c) in cf.of(k).enumerate() {
                    let [ra, rb] = cf.arms[c];
                    // (r x g) . w = g . (w x r)
                    let (wa, wb) = (cross([yv[3], yv[4], yv[5]], ra), cross([yv[9], yv[10], yv[11]], rb));
                    let jump: [f64; 3] = std::array::from_fn(|i| yv[i] + wa[i] - yv[6 + i] - wb[i]);
                    let o = &mut o[cf.sides * q..cf.sides * (q + 1)];
                    for (o, gj) in o.iter_mut().zip(g) {
                        *o = gj[0] * jump[0] + gj[1] * jump[1] + gj[2] * jump[2];
                    }
                }
            }
        };
        let (out, discs) = out.split_at_mut(cf.disc_var(0));
        // the discs d0.. into their variables `out`: (the radius's equation's dual, the jump at
        // the disc's corner along t1 and t2)
        let disc = |d0: usize, out: &mut [f64]| {
            for (j, o) in out.chunks_exact_mut(3).enumerate() {
                let d = d0 + j;
                let k = cf.discs.contact[d] as usize;
                let yv = self.dual_of(k, y);
                let [ra, rb] = cf.arms[cf.discs.corner[d]];
                let (wa, wb) = (cross([yv[3], yv[4], yv[5]], ra), cross([yv[9], yv[10], yv[11]], rb));
                let jump: [f64; 3] = std::array::from_fn(|i| yv[i] + wa[i] - yv[6 + i] - wb[i]);
                let e = self.dofs[self.rows * k + 12 + d - cf.discs.start[k]];
                let [t1, t2] = cf.discs.tangents[k];
                o[0] = if e == NO_EQ { 0.0 } else { y[e as usize] };
                o[1] = t1[0] * jump[0] + t1[1] * jump[1] + t1[2] * jump[2];
                o[2] = t2[0] * jump[0] + t2[1] * jump[1] + t2[2] * jump[2];
            }
        };
        match &self.par {
            None => {
                contacts(0, self.m, out);
                disc(0, discs);
            }
            Some(p) => {
                let firsts: Vec<usize> = (0..self.m).step_by(GRAIN_CONTACTS).chain([self.m]).collect();
                let bounds: Vec<usize> = firsts.iter().map(|&k| cf.var(cf.start[k])).collect();
                let parts = Par::cut(out, &bounds);
                p.pool.install(|| {
                    parts.into_par_iter().zip(firsts.par_windows(2)).for_each(|(o, w)| contacts(w[0], w[1], o));
                    discs.par_chunks_mut(3 * GRAIN_CONTACTS).enumerate().for_each(|(c, o)| disc(c * GRAIN_CONTACTS, o));
                })
            }
        }
    }

    /// The duals of contact k's twelve dof rows (0 at a support's).
    #[inline(always)]
    fn dual_of(&self, k: usize, y: &[f64]) -> [f64; 12] {
        let d = &self.dofs[self.rows * k..self.rows * k + 12];
        std::array::from_fn(|r| if d[r] == NO_EQ { 0.0 } else { y[d[r] as usize] })
    }

    /// `sum_k A_k Theta_k A_k^T` for a program in corner form, each corner's variables a
    /// second-order cone: per corner, `M = G W^2 G^T` (G's columns the cone's generators)
    /// carried to the 12 rows of the two bodies by `C = [I; Ra; -I; -Rb]` (`R v = r x v`),
    /// block by block: `C M C^T` has the blocks M, `P^T = (Ra M)^T`, `Ra P^T`, and with
    /// `Q = Rb M`, `Q^T`, `Ra Q^T`, `Rb Q^T` (a third of the products of the dense 12 x 3 form).
    pub(super) fn assemble_corners(&mut self, cf: &Corners, nt: &[Nt]) {
        // the 3 x 3 matrix whose column j is r x (column j of m), and r x (row j of m)
        let cross_cols = |r: [f64; 3], m: &[[f64; 3]; 3]| -> [[f64; 3]; 3] {
            let c: [[f64; 3]; 3] = std::array::from_fn(|j| cross(r, [m[0][j], m[1][j], m[2][j]]));
            std::array::from_fn(|i| std::array::from_fn(|j| c[j][i]))
        };
        let cross_rows = |r: [f64; 3], m: &[[f64; 3]; 3]| -> [[f64; 3]; 3] {
            let c: [[f64; 3]; 3] = std::array::from_fn(|j| cross(r, m[j]));
            std::array::from_fn(|i| std::array::from_fn(|j| c[j][i]))
        };
        let all_slots = &self.slots;
        let rows = self.rows;
        // contact k's block added into `vals`, whose first slot is `s0`
        let contact = |k: usize, vals: &mut [f64], s0: usize| {
            let slots = &all_slots[rows * rows * k..rows * rows * (k + 1)];
            let mut block = [[0.0; 12]; 12];
            let mut add = |bi: usize, bj: usize, m: &[[f64; 3]; 3], sign: f64| {
                for i in 0..3 {
                    for j in 0..3 {
                        block[3 * bi + i][3 * bj + j] += sign * m[i][j];
                    }
                }
            };
            // each corner's cone, then each disc's (its generators (0, t1, t2) on the dofs' rows)
            let t = cf.discs.tangents.get(k).copied().unwrap_or_default();
            let disc_gens = [[0.0; 3], t[0], t[1]];
            let cones = cf.of(k).map(|c| (c, cf.var(c), &cf.gens[cf.sides * k..cf.sides * (k + 1)]));
            let discs = cf.discs.of(k).map(|d| (cf.discs.corner[d], cf.disc_var(d), &disc_gens[..]));
            for (c, var, g) in cones.chain(discs) {
                let th = nt[var / 3].theta();
                let gt: [[f64; 3]; 3] =
                    std::array::from_fn(|i| std::array::from_fn(|b| g[0][i] * th[0][b] + g[1][i] * th[1][b] + g[2][i] * th[2][b]));
                let m: [[f64; 3]; 3] =
                    std::array::from_fn(|i| std::array::from_fn(|l| gt[i][0] * g[0][l] + gt[i][1] * g[1][l] + gt[i][2] * g[2][l]));
                let [ra, rb] = cf.arms[c];
                let (p, qm) = (cross_cols(ra, &m), cross_cols(rb, &m));
                let t = |a: &[[f64; 3]; 3]| -> [[f64; 3]; 3] { std::array::from_fn(|i| std::array::from_fn(|j| a[j][i])) };
                let qt = t(&qm);
                add(0, 0, &m, 1.0);
                add(0, 1, &t(&p), 1.0);
                add(0, 2, &m, -1.0);
                add(0, 3, &qt, -1.0);
                add(1, 1, &cross_rows(ra, &p), 1.0);
                add(1, 2, &p, -1.0);
                add(1, 3, &cross_rows(ra, &qm), -1.0);
                add(2, 2, &m, 1.0);
                add(2, 3, &qt, 1.0);
                add(3, 3, &cross_rows(rb, &qm), 1.0);
            }
            // a support's u32::MAX wraps beyond every range
            let mut put = |slot: u32, v: f64| {
                if let Some(o) = vals.get_mut((slot as usize).wrapping_sub(s0)) {
                    *o += v;
                }
            };
            for r in 0..12 {
                for s in r..12 {
                    let slot = slots[rows * r + s];
                    if slot != u32::MAX {
                        put(slot, block[r][s]);
                        if s != r {
                            put(slots[rows * s + r], block[r][s]);
                        }
                    }
                }
            }
            // each disc's radius's row: W^2_00 on its diagonal, and against the dofs' rows the
            // force W^2_01 t1 + W^2_02 t2 at its corner
            for (q, d) in cf.discs.of(k).enumerate() {
                let th = nt[cf.disc_var(d) / 3].theta();
                let f: [f64; 3] = std::array::from_fn(|i| th[0][1] * t[0][i] + th[0][2] * t[1][i]);
                let [ra, rb] = cf.arms[cf.discs.corner[d]];
                let e = 12 + q;
                put(slots[rows * e + e], th[0][0]);
                for (r, v) in force_rows(f, ra, rb).into_iter().enumerate() {
                    if slots[rows * e + r] != u32::MAX {
                        put(slots[rows * e + r], v);
                        put(slots[rows * r + e], v);
                    }
                }
            }
        };
        let vals = self.normal.values_mut();
        match &self.par {
            None => {
                vals.fill(0.0);
                (0..self.m).for_each(|k| contact(k, vals, 0));
            }
            Some(p) => {
                let parts = Par::cut(vals, &p.slots);
                p.pool.install(|| {
                    parts.into_par_iter().zip(&p.contacts).zip(&p.slots).for_each(|((v, ks), &s0)| {
                        v.fill(0.0);
                        ks.iter().for_each(|&k| contact(k as usize, v, s0));
                    })
                });
            }
        }
    }
}

/// The normal matrix's pattern on `n` equations (each element's `rows x rows` block among the
/// equations of its dofs, analysed once) and the value slot of each entry of each block
/// (`u32::MAX` for a support's row or column).
fn normal_pattern(n: usize, rows: usize, dofs: &[u32]) -> Result<(SparseLu, Vec<u32>)> {
    // the entries streamed to the pattern, not gathered first: in 3D they would be 144 pairs of
    // indices a contact (2.3 kB), more than the rest of the program
    let entries = dofs.chunks_exact(rows).flat_map(|d| {
        let real = move |r: &&u32| **r != NO_EQ;
        d.iter().filter(real).flat_map(move |&r| d.iter().filter(real).map(move |&c| (r as usize, c as usize)))
    });
    let normal = SparseLu::new(n, entries)?;
    let mut slots = crate::error::try_with_capacity("the normal matrix's slots", rows * dofs.len())?;
    for d in dofs.chunks_exact(rows) {
        for &r in d {
            for &c in d {
                slots.push(if r != NO_EQ && c != NO_EQ {
                    normal.slot(r as usize, c as usize).expect("in the pattern") as u32
                } else {
                    u32::MAX
                });
            }
        }
    }
    Ok((normal, slots))
}
