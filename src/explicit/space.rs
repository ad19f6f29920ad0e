//! The explicit solver in 3D: what differs from the plane's integrator, on the same loop
//! ([`Motion`]) and the same drivers (quasi-static levels, time histories).
//!
//! - Contacts are points: the corners of a contact polygon, any number of them, with the joint
//!   law at its corners ([`crate::joint::corner_map`]): normal forces that do not pull beyond
//!   the contact's tensile strength, with the polygon's elastic stiffness in translation and
//!   rotation, and a shear vector within Coulomb's cone at each; cohesion and tensile strength
//!   shared by the corners' tributary areas and lost at the contact's first failure. Torsion
//!   and biaxial bending come from the corners' positions, as in limit analysis. The points lie
//!   in flat arrays, each contact's from its offset: the pass allocates nothing.
//! - Blocks have 6 dof: (ux, uy, uz) at the centroid and a rotation. Quasi-static runs use small
//!   rotations (rx, ry, rz) about x, y and z, the kinematics of limit analysis, with the
//!   diagonal of the inertia tensor as the rotations' masses (relaxation finds the same
//!   equilibrium with any masses). Time histories take each block's full inertia tensor: its
//!   rotation dofs are about its principal axes (those of a box are x, y, z: the same dofs),
//!   with the principal moments as masses; with finite rotations each block's orientation is a
//!   unit quaternion (nalgebra), the angular velocity in the block's principal axes, and Euler's
//!   equations (the gyroscopic term `omega x I omega` with the forces); the rotation dofs then
//!   accumulate the body-frame increments `omega dt`, and results report the rotation vector
//!   of the quaternion.
//! - The contact pass runs on rayon in parts of contacts, each writing its own contact's forces
//!   on its two blocks; a gather sums them per block in contact order, so the sums do not depend
//!   on the number of threads.

use super::quasi_static::{QuasiStatic, Setting};
use super::*;
use crate::joint::{corner_map, corner_shares, CornerLaw, OPEN, ROCKING, SLIDING};
use crate::space::Model3;
use nalgebra::{Matrix3, SymmetricEigen, UnitQuaternion, Vector3};

/// Contacts per task of the contact pass.
const GRAIN_CONTACTS: usize = 512;
/// Below this many contacts a step runs on one thread.
const PAR_MIN_CONTACTS: usize = 1024;
// the most corners a contact may have (the pass's buffers on the stack, as the joint law's)
use crate::joint::MAX_POINTS as MAX_CORNERS;

/// A contact as the pass reads it: its blocks, its law (by family) and its frame (n, t1, t2).
#[derive(Debug, Clone, Copy)]
pub(super) struct Ct {
    a: u32,
    b: u32,
    frame: [[f64; 3]; 3],
}

/// A contact point: its position from the centroids of blocks a and b \[m\] (in their
/// reference orientations), and what the jump of b's point from a's adds to its motion since the
/// start: zero for the model's contacts, whose two points were one; for a contact the update
/// found, the centroids' and the points' positions then (`c_b - c_a - ra + rb`, so that the jump
/// is the points' distance).
#[derive(Debug, Clone, Copy)]
pub(super) struct Pt {
    ra: [f64; 3],
    rb: [f64; 3],
    off: [f64; 3],
}

/// A time history's contact dashpot at a point (see [`super::contact`]): its coefficients
/// (normal, shear) \[N s/m\], the jumps of the last step, its force then, and the energy it
/// dissipated.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Dash {
    c: [f64; 2],
    jumps: [f64; 3],
    force: [f64; 3],
    damped: f64,
}

/// The 3D integrator: the motion, the contacts and their points, the joint histories.
pub(super) struct Integrator3<'a> {
    pub(super) model: &'a Model3,
    pub(super) m: Motion,
    cts: Vec<Ct>,
    /// each contact's first point, then the number of points: contact k's are `at[k]..at[k + 1]`
    at: Vec<u32>,
    /// the points, each contact's in the order of its corners
    pts: Vec<Pt>,
    /// each point's share of its contact
    shares: Vec<f64>,
    /// the law at the corners of each contact (its family's, at its area)
    laws: Vec<CornerLaw>,
    /// the plastic jumps (p_n, p_t1, p_t2) of each point
    pub(super) hist: Vec<[f64; 3]>,
    /// each contact's loss of its strength
    broken: Vec<bool>,
    /// (N, T1, T2) of each point \[N\]
    pub(super) forces: Vec<[f64; 3]>,
    /// each contact's state (OPEN, SLIDING, ROCKING)
    pub(super) flags: Vec<u8>,
    /// each contact's family (its joint law)
    families: Vec<crate::interface::Family>,
    /// each contact's forces and moments on its blocks: a's (f, m) then b's
    terms: Vec<[f64; 12]>,
    /// per block, the slots (2 k + side) of the terms on it, in increasing k
    start: Vec<u32>,
    slots: Vec<u32>,
    /// finite rotations: each block's orientation and its matrix (row-major)
    pub(super) large: bool,
    q: Vec<UnitQuaternion<f64>>,
    rot: Vec<[f64; 9]>,
    /// the moments of inertia of each block about its rotation dofs' axes
    inertia: Vec<[f64; 3]>,
    /// time histories (principal axes): per block its principal axes where they are not x, y,
    /// z (the columns of the matrix, row-major, a rotation); quasi-static runs: empty
    axes: Vec<Option<[f64; 9]>>,
    /// time histories only (else empty): per point, its dashpot
    pub(super) dash: Vec<Dash>,
    prime: bool,
    /// the contact update of a time history, if on (see [`update`])
    update: Option<Box<super::update::Update<crate::shape::Polyhedron>>>,
}

mod update;
pub use update::critical_time_step_moving_3d;

impl std::ops::Deref for Integrator3<'_> {
    type Target = Motion;
    fn deref(&self) -> &Motion {
        &self.m
    }
}

impl std::ops::DerefMut for Integrator3<'_> {
    fn deref_mut(&mut self) -> &mut Motion {
        &mut self.m
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline(always)]
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

#[inline(always)]
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
fn mat(r: &[f64; 9], x: [f64; 3]) -> [f64; 3] {
    [r[0] * x[0] + r[1] * x[1] + r[2] * x[2], r[3] * x[0] + r[4] * x[1] + r[5] * x[2], r[6] * x[0] + r[7] * x[1] + r[8] * x[2]]
}

#[inline(always)]
fn mat_t(r: &[f64; 9], x: [f64; 3]) -> [f64; 3] {
    [r[0] * x[0] + r[3] * x[1] + r[6] * x[2], r[1] * x[0] + r[4] * x[1] + r[7] * x[2], r[2] * x[0] + r[5] * x[1] + r[8] * x[2]]
}

/// `x` (a rotation's components about block i's dofs' axes) in x, y, z: `axes[i] x` where the
/// block's axes are turned.
#[inline(always)]
pub(crate) fn to_world(axes: &[Option<[f64; 9]>], i: usize, x: [f64; 3]) -> [f64; 3] {
    match axes.get(i) {
        Some(Some(q)) => mat(q, x),
        _ => x,
    }
}

/// `x` (in x, y, z) about block i's dofs' axes.
#[inline(always)]
fn to_axes(axes: &[Option<[f64; 9]>], i: usize, x: [f64; 3]) -> [f64; 3] {
    match axes.get(i) {
        Some(Some(q)) => mat_t(q, x),
        _ => x,
    }
}

/// The rows of the map from the 12 dofs of a contact's blocks (a's, then b's) to the jumps of a
/// point along each axis of `frame`: `(-w, -(ra x w), w, rb x w)`, the rotations' about the
/// blocks' dofs' axes (`axes`, see [`principal_axes`]).
pub(crate) fn jump_rows(ra: [f64; 3], rb: [f64; 3], frame: &[[f64; 3]; 3], axes: [Option<&[f64; 9]>; 2]) -> [[f64; 12]; 3] {
    frame.map(|w| {
        let turn = |q: Option<&[f64; 9]>, v: [f64; 3]| q.map_or(v, |q| mat_t(q, v));
        let (ma, mb) = (turn(axes[0], cross(ra, w)), turn(axes[1], cross(rb, w)));
        [-w[0], -w[1], -w[2], -ma[0], -ma[1], -ma[2], w[0], w[1], w[2], mb[0], mb[1], mb[2]]
    })
}

/// Each block's principal axes of inertia and moments: `None` and the tensor's diagonal where
/// it has no products of inertia (a box), else the eigenvectors as the columns of a rotation
/// (row-major) and the eigenvalues.
pub(crate) fn principal_axes(model: &Model3) -> (Vec<Option<[f64; 9]>>, Vec<[f64; 3]>) {
    model
        .inertia_tensor()
        .iter()
        .zip(model.inertia())
        .map(|(t, &diag)| {
            if t[0][1] == 0.0 && t[0][2] == 0.0 && t[1][2] == 0.0 {
                return (None, diag);
            }
            let e = SymmetricEigen::new(Matrix3::from_fn(|r, c| t[r][c]));
            let mut q = e.eigenvectors;
            if q.determinant() < 0.0 {
                q.column_mut(2).neg_mut();
            }
            let v = e.eigenvalues;
            (Some(std::array::from_fn(|k| q[(k / 3, k % 3)])), [v[0], v[1], v[2]])
        })
        .unzip()
}

/// The stable time step of a 3D model's time history: `2 / omega_max`, with a Gershgorin bound
/// on `omega_max` from the points' elastic stiffnesses and the blocks' full inertia (about
/// their principal axes).
pub fn critical_time_step_3d(model: &Model3) -> f64 {
    time_step_bound(model, true)
}

/// [`critical_time_step_3d`], about the blocks' principal axes (`principal`, a time history's
/// dofs) or x, y and z with the tensor's diagonal (a quasi-static run's).
fn time_step_bound(model: &Model3, principal: bool) -> f64 {
    let (axes, inertia) = if principal { principal_axes(model) } else { (vec![None; model.n_blocks()], model.inertia().to_vec()) };
    let mut bound = Gershgorin::new(&masses_3d(model, &inertia), model.fixed());
    for (k, c) in model.contacts().iter().enumerate() {
        // each corner springs of kN A w_i (K <= max(alpha, 1) kN A W) and kT A w_i: an upper bound
        let (w, alpha) = corner_shares(&c.corners, c.centroid, c.n);
        let law = CornerLaw::new(model.law(k), c.area, alpha);
        let frame = [c.n, c.t1, c.t2];
        let dofs: Vec<usize> = (0..12).map(|j| if j < 6 { 6 * c.a + j } else { 6 * c.b + j - 6 }).collect();
        for (x, wi) in c.corners.iter().zip(w) {
            let (ra, rb) = (sub(*x, model.centroids()[c.a]), sub(*x, model.centroids()[c.b]));
            bound.add(&dofs, &jump_rows(ra, rb, &frame, [axes[c.a].as_ref(), axes[c.b].as_ref()]), [alpha.max(1.0) * law.kn * wi, law.kt * wi, law.kt * wi]);
        }
    }
    bound.step()
}

/// The mass of each dof (m, m, m, then the moments of inertia `inertia` of each block).
fn masses_3d(model: &Model3, inertia: &[[f64; 3]]) -> Vec<f64> {
    (0..model.n_blocks())
        .flat_map(|i| {
            let (m, j) = (model.mass()[i], inertia[i]);
            [m, m, m, j[0], j[1], j[2]]
        })
        .collect()
}

/// A part of the contact pass: contacts `k0..` with their points from `p0`, and what the pass
/// writes of them.
struct Part<'s> {
    k0: usize,
    p0: usize,
    hist: &'s mut [[f64; 3]],
    forces: &'s mut [[f64; 3]],
    dash: &'s mut [Dash],
    broken: &'s mut [bool],
    flags: &'s mut [u8],
    terms: &'s mut [[f64; 12]],
}

impl<'s> Part<'s> {
    /// The part cut before its contact `k0 + kk`, whose first point is `at`.
    fn split(self, kk: usize, at: usize) -> (Part<'s>, Part<'s>) {
        let pp = at - self.p0;
        let (h0, h1) = self.hist.split_at_mut(pp);
        let (f0, f1) = self.forces.split_at_mut(pp);
        let (d0, d1) = self.dash.split_at_mut(if self.dash.is_empty() { 0 } else { pp });
        let (b0, b1) = self.broken.split_at_mut(kk);
        let (l0, l1) = self.flags.split_at_mut(kk);
        let (t0, t1) = self.terms.split_at_mut(kk);
        (
            Part { k0: self.k0, p0: self.p0, hist: h0, forces: f0, dash: d0, broken: b0, flags: l0, terms: t0 },
            Part { k0: self.k0 + kk, p0: at, hist: h1, forces: f1, dash: d1, broken: b1, flags: l1, terms: t1 },
        )
    }
}

/// `work` on `part`, halved on rayon while it holds more than [`GRAIN_CONTACTS`] contacts.
fn run_parts(part: Part<'_>, at: &[u32], work: &(dyn Fn(Part<'_>) + Sync)) {
    let n = part.flags.len();
    if n <= GRAIN_CONTACTS {
        return work(part);
    }
    let kk = n / 2;
    let cut = at[part.k0 + kk] as usize;
    let (a, b) = part.split(kk, cut);
    rayon::join(|| run_parts(a, at, work), || run_parts(b, at, work));
}

impl<'a> Integrator3<'a> {
    /// The integrator of `model` at rest, with time step `dt` (None: `safety` times the
    /// stability limit), `damping`, and the contact pass on `threads` threads (0: all cores);
    /// the rotation dofs about the blocks' principal axes (`principal`: a time history) or
    /// about x, y and z.
    pub(super) fn new(model: &'a Model3, dt: Option<f64>, safety: f64, damping: Damping, threads: usize, principal: bool) -> Result<Self, Error> {
        let dt = checked_time_step(time_step_bound(model, principal), dt, safety, damping)?;
        let nb = model.n_blocks();
        let contacts = model.contacts();
        let m = contacts.len();
        let np: usize = contacts.iter().map(|c| c.corners.len()).sum();
        if nb >= u32::MAX as usize / 2 || 2 * m >= u32::MAX as usize || np >= u32::MAX as usize {
            return Err(Error::input(format!("{nb} blocks and {m} contacts: the explicit solver takes fewer than 2^31 of each")));
        }
        let (mut axes, inertia) = if principal { principal_axes(model) } else { (vec![], model.inertia().to_vec()) };
        if axes.iter().all(Option::is_none) {
            // every block's axes are x, y, z (boxes): none to turn
            axes.clear();
        }
        let (pool, par, _) = start_pool(threads, m, PAR_MIN_CONTACTS)?;
        let motion = Motion::new(6, masses_3d(model, &inertia), model.fixed(), vec![0.0; 6 * nb], dt, damping, pool, par)?;
        let cen = model.centroids();
        let mut cts = Vec::with_capacity(m);
        let mut at = Vec::with_capacity(m + 1);
        let mut pts = Vec::with_capacity(np);
        let mut shares = Vec::with_capacity(np);
        let mut laws = Vec::with_capacity(m);
        let families = contacts.iter().map(|c| c.family).collect();
        for (k, c) in contacts.iter().enumerate() {
            if c.corners.len() > MAX_CORNERS {
                return Err(Error::input(format!(
                    "the contact of {} and {} has {} corners: the explicit solver takes at most {MAX_CORNERS}",
                    model.block_name(c.a),
                    model.block_name(c.b),
                    c.corners.len()
                )));
            }
            at.push(pts.len() as u32);
            cts.push(Ct { a: c.a as u32, b: c.b as u32, frame: [c.n, c.t1, c.t2] });
            let (w, alpha) = corner_shares(&c.corners, c.centroid, c.n);
            laws.push(CornerLaw::new(model.law(k), c.area, alpha));
            shares.extend(w);
            for x in &c.corners {
                pts.push(Pt { ra: sub(*x, cen[c.a]), rb: sub(*x, cen[c.b]), off: [0.0; 3] });
            }
        }
        at.push(pts.len() as u32);
        let (start, slots) = slots_of(nb, &cts);
        Ok(Integrator3 {
            model,
            m: motion,
            cts,
            at,
            pts,
            shares,
            laws,
            hist: vec![[0.0; 3]; np],
            broken: vec![false; m],
            forces: vec![[0.0; 3]; np],
            flags: vec![0; m],
            families,
            terms: vec![[0.0; 12]; m],
            start,
            slots,
            large: false,
            q: vec![],
            rot: vec![],
            inertia,
            axes,
            dash: vec![],
            prime: false,
            update: None,
        })
    }

    /// Number of contact points.
    pub(super) fn n_points(&self) -> usize {
        self.pts.len()
    }

    /// Finite rotations (time histories) or small rotations (the default).
    pub(super) fn set_large(&mut self, large: bool) {
        self.large = large;
        if large && self.q.is_empty() {
            let nb = self.model.n_blocks();
            self.q = vec![UnitQuaternion::identity(); nb];
            self.rot = vec![[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]; nb];
        }
    }

    /// Sets block `i`'s rotation to the rotation vector `r` \[rad\] in x, y, z: its orientation
    /// (finite rotations) and its rotation dofs.
    pub(super) fn set_rotation(&mut self, i: usize, r: [f64; 3]) {
        let d = to_axes(&self.axes, i, r);
        self.m.u[6 * i + 3..6 * i + 6].copy_from_slice(&d);
        if self.large {
            self.q[i] = UnitQuaternion::from_scaled_axis(Vector3::from(r));
            self.rot[i] = matrix(&self.q[i]);
        }
    }

    /// Sets block `i`'s angular velocity to `w` \[rad/s\] in x, y, z (with finite rotations,
    /// in the block's axes).
    pub(super) fn set_angular_velocity(&mut self, i: usize, w: [f64; 3]) {
        let w = if self.large { mat_t(&self.rot[i], w) } else { w };
        let d = to_axes(&self.axes, i, w);
        self.m.v[6 * i + 3..6 * i + 6].copy_from_slice(&d);
    }

    /// Block `i`'s dofs for results: the translation and the rotation vector (of the
    /// quaternion with finite rotations, else the small rotations) in x, y, z.
    pub(super) fn block_state(&self, i: usize) -> [f64; 6] {
        let u = &self.m.u[6 * i..6 * i + 6];
        let r = if self.large {
            let r = self.q[i].scaled_axis();
            [r[0], r[1], r[2]]
        } else {
            to_world(&self.axes, i, [u[3], u[4], u[5]])
        };
        [u[0], u[1], u[2], r[0], r[1], r[2]]
    }

    /// Block `i`'s angular velocity in the world's axes (finite rotations: from the body's).
    pub(super) fn block_velocity(&self, i: usize) -> [f64; 6] {
        let v = &self.m.v[6 * i..6 * i + 6];
        let w = to_world(&self.axes, i, [v[3], v[4], v[5]]);
        let w = if self.large { mat(&self.rot[i], w) } else { w };
        [v[0], v[1], v[2], w[0], w[1], w[2]]
    }

    /// The orientations after the drift (finite rotations): each free block turned by its
    /// body-frame angular velocity times the time step.
    fn rotate(&mut self) {
        let (v, dt, free, axes) = (&self.m.v, self.m.dt, &self.m.free, &self.axes);
        let turn = |i0: usize, q: &mut [UnitQuaternion<f64>], rot: &mut [[f64; 9]]| {
            for (j, (q, rot)) in q.iter_mut().zip(rot.iter_mut()).enumerate() {
                let i = i0 + j;
                if free[6 * i + 3] || free[6 * i + 4] || free[6 * i + 5] {
                    let w = to_world(axes, i, [v[6 * i + 3], v[6 * i + 4], v[6 * i + 5]]);
                    *q *= UnitQuaternion::from_scaled_axis(Vector3::from(w) * dt);
                    *rot = matrix(q);
                }
            }
        };
        if self.m.par {
            let (q, rot) = (&mut self.q, &mut self.rot);
            self.m.pool.install(|| q.par_chunks_mut(GRAIN_BLOCKS).zip(rot.par_chunks_mut(GRAIN_BLOCKS)).enumerate().for_each(|(c, (q, r))| turn(c * GRAIN_BLOCKS, q, r)));
        } else {
            turn(0, &mut self.q, &mut self.rot);
        }
    }

    /// The contact forces at the current displacements (the committed histories updated: each
    /// time step is an increment), gathered into `f_int`; with finite rotations the moments in
    /// the blocks' axes plus the gyroscopic term.
    pub(super) fn interface_forces(&mut self) {
        let (u, cts, pts, laws, shares, at, axes) = (&self.m.u, &self.cts, &self.pts, &self.laws, &self.shares, &self.at, &self.axes);
        let (large, rot, dt, prime) = (self.large, &self.rot, self.m.dt, self.prime);
        let ident = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
        let dyn_on = !self.dash.is_empty();
        let work = |part: Part<'_>| {
            let Part { k0, p0, hist, forces, dash, broken, flags, terms } = part;
            // the points of one contact at a time, on the stack
            let mut es = [[0.0; 3]; MAX_CORNERS];
            let mut xs = [[[0.0; 3]; 2]; MAX_CORNERS];
            let mut states = [0u8; MAX_CORNERS];
            let mut tot = [[0.0; 3]; MAX_CORNERS];
            for (j, ((term, flag), broken)) in terms.iter_mut().zip(flags.iter_mut()).zip(broken.iter_mut()).enumerate() {
                let k = k0 + j;
                let c = &cts[k];
                let (a, b) = (c.a as usize, c.b as usize);
                let (ra_m, rb_m) = if large { (&rot[a], &rot[b]) } else { (&ident, &ident) };
                let frame = if large { c.frame.map(|w| mat(ra_m, w)) } else { c.frame };
                let ua = [u[6 * a], u[6 * a + 1], u[6 * a + 2]];
                let ub = [u[6 * b], u[6 * b + 1], u[6 * b + 2]];
                let (ta, tb) = if large {
                    ([0.0; 3], [0.0; 3])
                } else {
                    (to_world(axes, a, [u[6 * a + 3], u[6 * a + 4], u[6 * a + 5]]), to_world(axes, b, [u[6 * b + 3], u[6 * b + 4], u[6 * b + 5]]))
                };
                let law = &laws[k];
                let (q0, q1) = (at[k] as usize, at[k + 1] as usize);
                let np = q1 - q0;
                let (l0, l1) = (q0 - p0, q1 - p0);
                let mut t = [0.0; 12];
                let (mut open, mut slide) = (0usize, false);
                for (p, pt) in pts[q0..q1].iter().enumerate() {
                    // the jump of b's point from a's, and the lever arms now
                    let (xa, xb, d) = if large {
                        let (xa, xb) = (mat(ra_m, pt.ra), mat(rb_m, pt.rb));
                        (xa, xb, [0, 1, 2].map(|r| ub[r] - ua[r] + xb[r] - pt.rb[r] - xa[r] + pt.ra[r] + pt.off[r]))
                    } else {
                        let (wa, wb) = (cross(ta, pt.ra), cross(tb, pt.rb));
                        (pt.ra, pt.rb, [0, 1, 2].map(|r| ub[r] + wb[r] - ua[r] - wa[r] + pt.off[r]))
                    };
                    es[p] = [dot(frame[0], d), dot(frame[1], d), dot(frame[2], d)];
                    xs[p] = [xa, xb];
                }
                let fs = &mut forces[l0..l1];
                corner_map(law, &shares[q0..q1], &es[..np], &mut hist[l0..l1], broken, fs, &mut states[..np]);
                for &s in &states[..np] {
                    if s & OPEN != 0 {
                        open += 1;
                    }
                    slide |= s & SLIDING != 0;
                }
                if dyn_on {
                    let ds = &mut dash[l0..l1];
                    for p in 0..np {
                        let x = if prime { [0.0; 3] } else { dashpot(&ds[p], law.friction, es[p], fs[p], dt) };
                        let (e, d) = (es[p], &mut ds[p]);
                        d.damped = if prime { 0.0 } else { d.damped + 0.5 * (0..3).map(|r| (d.force[r] + x[r]) * (e[r] - d.jumps[r])).sum::<f64>() };
                        d.jumps = e;
                        d.force = x;
                        // the terms take the joint's force and the dashpot's
                        tot[p] = [fs[p][0] + x[0], fs[p][1] + x[1], fs[p][2] + x[2]];
                    }
                }
                for p in 0..np {
                    let (f, [xa, xb]) = (if dyn_on { tot[p] } else { fs[p] }, xs[p]);
                    let fw = [0, 1, 2].map(|r| f[0] * frame[0][r] + f[1] * frame[1][r] + f[2] * frame[2][r]);
                    let (ma, mb) = (cross(xa, fw), cross(xb, fw));
                    for r in 0..3 {
                        t[r] -= fw[r];
                        t[3 + r] -= ma[r];
                        t[6 + r] += fw[r];
                        t[9 + r] += mb[r];
                    }
                }
                *term = t;
                *flag = if open == np {
                    OPEN
                } else {
                    (if slide { SLIDING } else { 0 }) | (if open > 0 { ROCKING } else { 0 })
                };
            }
        };
        let part = Part { k0: 0, p0: 0, hist: &mut self.hist, forces: &mut self.forces, dash: &mut self.dash, broken: &mut self.broken, flags: &mut self.flags, terms: &mut self.terms };
        if self.m.par {
            self.m.pool.install(|| run_parts(part, at, &work));
        } else {
            work(part);
        }
        self.prime = false;
        self.gather();
    }

    /// Each block's sum of its contacts' terms into `f_int`, in increasing k, its moment about
    /// its dofs' axes: with finite rotations turned into the block's axes, plus
    /// `omega x I omega`.
    fn gather(&mut self) {
        let (start, slots, terms) = (&self.start, &self.slots, &self.terms);
        let (large, rot, inertia, axes) = (self.large, &self.rot, &self.inertia, &self.axes);
        let v = &self.m.v;
        let sum = |i0: usize, out: &mut [f64]| {
            for (j, f) in out.chunks_exact_mut(6).enumerate() {
                let i = i0 + j;
                let mut acc = [0.0; 6];
                for &s in &slots[start[i] as usize..start[i + 1] as usize] {
                    let t = &terms[s as usize / 2];
                    let side = 6 * (s as usize % 2);
                    for r in 0..6 {
                        acc[r] += t[side + r];
                    }
                }
                if large {
                    let m = to_axes(axes, i, mat_t(&rot[i], [acc[3], acc[4], acc[5]]));
                    let w = [v[6 * i + 3], v[6 * i + 4], v[6 * i + 5]];
                    let jw = [inertia[i][0] * w[0], inertia[i][1] * w[1], inertia[i][2] * w[2]];
                    let g = cross(w, jw);
                    acc[3] = m[0] + g[0];
                    acc[4] = m[1] + g[1];
                    acc[5] = m[2] + g[2];
                } else if let Some(Some(q)) = axes.get(i) {
                    let m = mat_t(q, [acc[3], acc[4], acc[5]]);
                    acc[3..6].copy_from_slice(&m);
                }
                f.copy_from_slice(&acc);
            }
        };
        if self.m.par {
            let f_int = &mut self.m.f_int;
            self.m.pool.install(|| f_int.par_chunks_mut(6 * GRAIN_BLOCKS).enumerate().for_each(|(c, f)| sum(c * GRAIN_BLOCKS, f)));
        } else {
            sum(0, &mut self.m.f_int);
        }
    }

    /// One velocity-Verlet step (see [`Kernel::step`]).
    pub(super) fn step(&mut self, set_ext: &mut dyn FnMut(&mut [f64], &[f64]), prescribed: Option<(usize, f64)>) {
        let par = self.m.par;
        if par {
            let pool = self.m.pool.clone();
            pool.install(|| self.m.drift_in(prescribed, true));
        } else {
            self.m.drift_in(prescribed, false);
        }
        if self.large {
            self.rotate();
        }
        self.interface_forces();
        self.m.finish_step(set_ext, prescribed);
        if self.update.as_ref().is_some_and(|up| up.due3(&self.m.u, &self.rot)) {
            update::search(self);
        }
    }

    /// Starts the contact dashpots of a time history: each point's from its law's restitution
    /// and the reduced mass of its blocks (its share of the contact's, see [`super::contact`]).
    pub(super) fn start_dynamics(&mut self) {
        let model = self.model;
        let mut dash = Vec::with_capacity(self.pts.len());
        for (k, c) in model.contacts().iter().enumerate() {
            let cf = self.dashpot_of(model.law(k), c.area, c.a, c.b);
            for &w in &self.shares[self.at[k] as usize..self.at[k + 1] as usize] {
                dash.push(Dash { c: [w * cf[0], w * cf[1]], ..Dash::default() });
            }
        }
        self.dash = dash;
        self.prime = true;
        self.m.track_damping = !matches!(self.m.damping, Damping::None);
    }

    /// The contact dashpot's coefficients (normal, shear) of a contact of law `law` and area
    /// `area` between blocks `a` and `b` (see [`super::contact`]), from the reduced mass of its
    /// free blocks.
    fn dashpot_of(&self, law: &crate::joint::JointLaw, area: f64, a: usize, b: usize) -> [f64; 2] {
        let free_mass = |i: usize| if (0..3).any(|r| self.m.free[6 * i + r]) { self.model.mass()[i] } else { f64::INFINITY };
        let reduced = 1.0 / (1.0 / free_mass(a) + 1.0 / free_mass(b));
        let cf = super::contact::coefficients(law, area, 0.0, reduced);
        [cf[0], cf[1]]
    }

    /// Energy dissipated by the contact dashpots \[J\], those the contact update dropped included.
    pub(super) fn impact_dissipation(&self) -> f64 {
        let dropped = self.update.as_ref().map_or(0.0, |up| up.dropped_dissipation.0);
        self.dash.iter().map(|d| d.damped).sum::<f64>() + dropped
    }

    /// Elastic energy stored in the contact points \[J\].
    pub(super) fn elastic_energy(&self) -> f64 {
        let range = |k: usize| self.at[k] as usize..self.at[k + 1] as usize;
        self.laws.iter().enumerate().map(|(k, law)| law.energy(&self.shares[range(k)], &self.forces[range(k)])).sum()
    }

    /// The rotation angle of block `i` from the start (finite rotations: the quaternion's) \[rad\].
    pub(super) fn rotation_angle(&self, i: usize) -> f64 {
        if self.large {
            self.q[i].angle()
        } else {
            let u = &self.m.u[6 * i + 3..6 * i + 6];
            (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt()
        }
    }
}

/// The rotation matrix of `q`, row-major.
fn matrix(q: &UnitQuaternion<f64>) -> [f64; 9] {
    let m = q.to_rotation_matrix();
    let m = m.matrix();
    [m[(0, 0)], m[(0, 1)], m[(0, 2)], m[(1, 0)], m[(1, 1)], m[(1, 2)], m[(2, 0)], m[(2, 1)], m[(2, 2)]]
}

/// The dashpot force of a contact point (its dashpot `d`) at jumps `e` after the last step's,
/// with the joint's force `f` and friction `mu` (see [`super::contact`]): its share of the
/// contact's dashpot (a rectangle's corner a quarter, as each end of the plane's interface has
/// half of it), on its own closing rate, cut so that the point does not pull; and on its slip
/// rate, kept within the friction of its damped normal force. Its power is never negative.
#[inline(always)]
fn dashpot(d: &Dash, mu: f64, e: [f64; 3], f: [f64; 3], dt: f64) -> [f64; 3] {
    let c = d.c;
    // a point carries a share of N where it is closed
    if !(f[0] < 0.0) || (c[0] == 0.0 && c[1] == 0.0) {
        return [0.0; 3];
    }
    let inv = 1.0 / dt;
    let rate = [0, 1, 2].map(|r| (e[r] - d.jumps[r]) * inv);
    let dn = (c[0] * rate[0]).min(-f[0]);
    let n = f[0] + dn;
    if n >= 0.0 {
        return [dn, 0.0, 0.0];
    }
    let t = [f[1] + c[1] * rate[1], f[2] + c[1] * rate[2]];
    let cap = f[1].hypot(f[2]).max(-mu * n);
    let tn = t[0].hypot(t[1]);
    let s = if tn > cap { cap / tn } else { 1.0 };
    [dn, t[0] * s - f[1], t[1] * s - f[2]]
}

impl Kernel for Integrator3<'_> {
    const DOF: usize = 6;
    type V = [f64; 6];
    fn step(&mut self, set_ext: &mut dyn FnMut(&mut [f64], &[f64]), prescribed: Option<(usize, f64)>) {
        Integrator3::step(self, set_ext, prescribed)
    }
    fn interface_forces(&mut self) {
        Integrator3::interface_forces(self)
    }
    fn hold(&mut self) {}
    fn clock_every(&self) -> usize {
        if self.m.par {
            1
        } else {
            16
        }
    }
    fn history(&self) -> (&[f64], &[bool]) {
        (self.hist.as_flattened(), &self.broken)
    }
    fn history_mut(&mut self) -> (&mut [f64], &mut [bool]) {
        (self.hist.as_flattened_mut(), &mut self.broken)
    }
    #[inline]
    fn translation(u: &[f64], from: Option<&[f64]>, i: usize) -> f64 {
        let d = |r: usize| u[6 * i + r] - from.map_or(0.0, |u0| u0[6 * i + r]);
        (d(0) * d(0) + d(1) * d(1) + d(2) * d(2)).sqrt()
    }
    fn block(u: &[f64], i: usize) -> [f64; 6] {
        [u[6 * i], u[6 * i + 1], u[6 * i + 2], u[6 * i + 3], u[6 * i + 4], u[6 * i + 5]]
    }
    /// Per contact, its resultants at its centroid (N, T1, T2, M_n, M_t1, M_t2) from its points'
    /// forces, as limit analysis reports them.
    fn into_contacts(self) -> (Vec<[f64; 6]>, Vec<u8>, Vec<bool>) {
        let model = self.model;
        let forces = model
            .contacts()
            .iter()
            .enumerate()
            .map(|(k, c)| {
                let mut s = [0.0; 6];
                for (p, x) in c.corners.iter().enumerate() {
                    let f = self.forces[self.at[k] as usize + p];
                    let fw = [0, 1, 2].map(|r| f[0] * c.n[r] + f[1] * c.t1[r] + f[2] * c.t2[r]);
                    let m = cross(sub(*x, c.centroid), fw);
                    s[0] += f[0];
                    s[1] += f[1];
                    s[2] += f[2];
                    s[3] += dot(m, c.n);
                    s[4] += dot(m, c.t1);
                    s[5] += dot(m, c.t2);
                }
                s
            })
            .collect();
        (forces, self.flags, self.broken)
    }
    fn contacts_created(&self) -> usize {
        0
    }
}

/// Runs a quasi-static analysis of a 3D model with the explicit solver (load control: levels
/// relaxed until they settle, the collapse multiplier bracketed between the highest level that
/// settled and the lowest that ran away).
pub fn solve_3d(model: &Model3, opts: &ExplicitOptions) -> Result<Results<[f64; 6]>, Error> {
    solve_3d_with(model, opts, &mut |_| true)
}

/// As [`solve_3d`], calling `monitor` after each settled level and every 0.1 s (return false to
/// stop).
pub fn solve_3d_with(model: &Model3, opts: &ExplicitOptions, monitor: &mut dyn FnMut(&Progress) -> bool) -> Result<Results<[f64; 6]>, Error> {
    let start = Instant::now();
    crate::analysis::check_path_options(opts.steps, opts.tolerance, opts.control)?;
    if !(opts.unbalanced_ratio > 0.0 && opts.unbalanced_ratio < 1.0) {
        return Err(Error::input(format!("analysis.unbalanced_ratio must lie in (0, 1), got {}", opts.unbalanced_ratio)));
    }
    if opts.max_steps_per_level == 0 {
        return Err(Error::input("max_steps_per_level must be at least 1"));
    }
    if opts.control != Control::Load {
        return Err(Error::input("3D explicit analyses are load-controlled (analysis.control = \"load\")"));
    }
    if opts.large_rotations || opts.contact_update {
        let key = if opts.large_rotations { "large_rotations" } else { "contact_update" };
        return Err(Error::input(format!("analysis.{key}: the pushovers of 3D models are on the wall as built in this version (linearized kinematics, the contacts found once)")));
    }
    check_brittle(model)?;
    model.check_live("the explicit solver's pushover")?;
    model.check_supports()?;
    if model.n_wall() == 0 {
        return Err(Error::input("the model has no wall blocks"));
    }
    // the curve follows the control block along the horizontal axis nearer the load's direction
    let offset = match model.live() {
        crate::space::LiveLoad3::HorizontalWeight { direction } if direction.to_radians().sin().abs() > direction.to_radians().cos().abs() => 1,
        _ => 0,
    };
    let control_block = match opts.control_block {
        Some(i) if i >= model.n_blocks() => return Err(Error::input(format!("control_block {i} is out of range (the model has {} blocks)", model.n_blocks()))),
        Some(i) if model.fixed()[6 * i + offset] => {
            return Err(Error::input(crate::analysis::held_control_block(i, &model.block_name(i), ["x", "y"][offset])))
        }
        Some(i) => i,
        None => highest_block(model),
    };
    let s = Integrator3::new(model, opts.time_step, opts.safety, opts.damping, opts.threads, false)?;
    let free = (0..model.n_blocks()).filter(|&i| !model.fixed()[6 * i + 2]).map(|i| model.mass()[i]);
    let period = super::quasi_static::vertical_period(free.sum(), model.base_stiffness());
    let setting = Setting { fd: model.dead_load().to_vec(), fl: model.live_load().to_vec(), size: model.size(), scale: 1.0, offset, period };
    super::quasi_static::check_relaxation(period, s.dt, opts.time_step.is_some(), opts.max_steps_per_level)?;
    let mut run = QuasiStatic::new(s, setting, opts, control_block, start);
    let end = match run.settle_dead_loads(monitor) {
        std::ops::ControlFlow::Break(end) => end,
        std::ops::ControlFlow::Continue((_, limits)) => run.load_control(&limits, monitor),
    };
    let res = run.finish(end);
    // dry associative joints: limit analysis is exact, and the collapse is checked against it
    let associative = (0..model.contacts().len()).all(|k| model.law(k).dilatancy == model.law(k).friction && !model.law(k).is_strong());
    if res.status != Status::Collapse || !associative {
        return Ok(res);
    }
    let last = Progress { step: res.iterations, multiplier: res.last_equilibrium, displacement: f64::NAN, fraction: f64::NAN, poll: true, time: f64::NAN };
    let mut polled = Instant::now();
    let mut poll = |_: &crate::limit::LimitProgress| {
        if polled.elapsed().as_secs_f64() < 0.1 {
            return true;
        }
        polled = Instant::now();
        monitor(&last)
    };
    let lp = crate::limit::limit_analysis_3d_with(model, &crate::limit::LimitOptions::default(), &mut poll)?;
    Ok(super::evidence::judge(opts, res, lp))
}

/// The wall block whose top is highest (the first of them): the default control block, whose
/// displacement the pushover curve follows.
fn highest_block(model: &Model3) -> usize {
    let boxes = model.boxes();
    (0..model.n_wall()).fold(0, |best, i| if boxes[i].max[2] > boxes[best].max[2] { i } else { best })
}

impl super::time_history::Recorded for Integrator3<'_> {
    fn record_block(&self, i: usize) -> ([f64; 6], [f64; 6]) {
        (self.block_state(i), self.block_velocity(i))
    }
    fn base_shear(&self) -> [f64; 2] {
        self.model.base().map_or([0.0; 2], |b| [-self.m.f_int[6 * b], -self.m.f_int[6 * b + 1]])
    }
    fn gravity_work(&self, u0: &[f64]) -> f64 {
        let fd = self.model.dead_load();
        (0..self.model.n_blocks()).map(|i| fd[6 * i + 2] * (self.m.u[6 * i + 2] - u0[6 * i + 2])).sum()
    }
    fn elastic_energy(&self) -> f64 {
        Integrator3::elastic_energy(self)
    }
    fn dashpot_dissipation(&self) -> (f64, f64) {
        (self.impact_dissipation(), 0.0)
    }
    fn out_of_range(&self, u0: &[f64]) -> Option<String> {
        let model = self.model;
        let (times, max_angle, what) = super::update::range(self.update.is_some(), self.large);
        let size = times * model.size();
        for i in 0..model.n_blocks() {
            let moved = <Self as Kernel>::translation(&self.m.u, Some(u0), i);
            if moved > size {
                return Some(format!("{} moved {moved:.3e} m, more than {what} ({size:.3e} m)", model.block_name(i)));
            }
            let angle = self.rotation_angle(i);
            if angle > max_angle {
                return Some(format!("{} rotated {angle:.3e} rad, more than {max_angle:.4} rad", model.block_name(i)));
            }
        }
        None
    }
    fn ground_axis(d: usize) -> u8 {
        [0, 1, 2, 3, 3, 3][d % 6]
    }
    fn finish(&self, h: &mut TimeHistory<[f64; 6]>) {
        let Some(up) = &self.update else { return };
        up.report(h);
        h.contacts_3d = update::contacts(self);
    }
}

/// Per block, the first of its slots in `slots` (then the end), and the slots (2 k + side) of
/// the terms of contacts `cts` on it, in increasing k.
fn slots_of(nb: usize, cts: &[Ct]) -> (Vec<u32>, Vec<u32>) {
    let mut count = vec![0u32; nb + 1];
    for c in cts {
        count[c.a as usize + 1] += 1;
        count[c.b as usize + 1] += 1;
    }
    for i in 0..nb {
        count[i + 1] += count[i];
    }
    let start = count.clone();
    let mut slots = vec![0u32; 2 * cts.len()];
    let mut fill = count;
    for (k, c) in cts.iter().enumerate() {
        for (side, blk) in [(0, c.a), (1, c.b)] {
            slots[fill[blk as usize] as usize] = (2 * k + side) as u32;
            fill[blk as usize] += 1;
        }
    }
    (start, slots)
}

/// The stable time step of a time history of a 3D model \[s\]: [`critical_time_step_3d`] lowered
/// for the contact dashpots of its joints' restitution (as the plane's
/// [`history_time_step_limit`](super::history_time_step_limit)).
/// With the contact update (`contact_update`, a time history's default) the limit is that of a
/// model whose blocks may touch along every face ([`critical_time_step_moving_3d`]), lower or
/// equal.
pub fn history_time_step_limit_3d(model: &Model3, contact_update: bool) -> f64 {
    dashpot_limit_3d(model, if contact_update { critical_time_step_moving_3d(model) } else { critical_time_step_3d(model) })
}

/// The stability limit `crit` lowered for the contact dashpots of the joints of `model`.
fn dashpot_limit_3d(model: &Model3, crit: f64) -> f64 {
    crit * super::contact::stability_factor(3.0 * super::time_history::max_damping_ratio(model.laws()))
}

/// The time step of a time history of `model` under `opts` (as the plane's).
fn history_time_step_3d(model: &Model3, opts: &DynamicOptions<[f64; 6]>) -> Result<f64, Error> {
    super::time_history::updated_time_step(|| critical_time_step_3d(model), || critical_time_step_moving_3d(model), |crit| dashpot_limit_3d(model, crit), opts)
}

/// The bytes a time history of a 3D `model` under `opts` will hold, and its number of records
/// (as the plane's [`super::record_size`]): per record, the displacements and velocities of
/// every block (96 bytes a block) and 15 numbers (times, the ground's accelerations, the base
/// shears, energies). Checks the options as [`simulate_3d`] does before it builds the integrator.
pub fn record_size_3d(model: &Model3, opts: &DynamicOptions<[f64; 6]>) -> Result<(usize, f64), Error> {
    super::time_history::check_common(opts, model.n_blocks())?;
    let dt = history_time_step_3d(model, opts)?;
    let n_steps = super::time_history::count_time_steps(opts.duration, dt)?;
    let records = super::record_count(opts.record, dt, n_steps);
    Ok((records, records as f64 * (96.0 * model.n_blocks() as f64 + 8.0 * 15.0)))
}

/// Integrates the equations of motion of a 3D model in time: free motion from initial
/// conditions, base accelerations along x, y and z; finite rotations (unit quaternions) unless
/// `large_rotations` is false. Dry joints; no stiffness-proportional damping.
pub fn simulate_3d(model: &Model3, opts: &DynamicOptions<[f64; 6]>) -> Result<TimeHistory<[f64; 6]>, Error> {
    simulate_3d_with(model, opts, &mut |_| true)
}

/// As [`simulate_3d`], calling `monitor` every few thousand steps (return false to stop).
pub fn simulate_3d_with(model: &Model3, opts: &DynamicOptions<[f64; 6]>, monitor: &mut dyn FnMut(&Progress) -> bool) -> Result<TimeHistory<[f64; 6]>, Error> {
    let start = Instant::now();
    let nb = model.n_blocks();
    super::time_history::check_common(opts, nb)?;
    if opts.stiffness_damping != 0.0 {
        return Err(Error::input("stiffness_damping (beta): stiffness-proportional damping is the plane's only; 3D time histories take mass-proportional or local damping"));
    }
    check_brittle(model)?;
    model.check_supports()?;
    let dt = history_time_step_3d(model, opts)?;
    let mut s = Integrator3::new(model, Some(dt), opts.safety, opts.damping, opts.threads, true)?;
    s.set_large(opts.large_rotations);
    let fixed = model.fixed();
    if let Some(u0) = &opts.initial_displacement {
        for i in 0..nb {
            if fixed[6 * i] {
                continue;
            }
            s.m.u[6 * i..6 * i + 3].copy_from_slice(&u0[i][..3]);
            s.set_rotation(i, [u0[i][3], u0[i][4], u0[i][5]]);
        }
    }
    if let Some(v0) = &opts.initial_velocity {
        for i in (0..nb).filter(|&i| !fixed[6 * i]) {
            s.m.v[6 * i..6 * i + 3].copy_from_slice(&v0[i][..3]);
            s.set_angular_velocity(i, [v0[i][3], v0[i][4], v0[i][5]]);
        }
    }
    s.start_dynamics();
    if super::time_history::updating(opts) {
        s.update = Some(Box::new(update::Update::new3(&s)));
        update::search(&mut s);
    }
    let loads = super::time_history::Loads::new(model.dead_load(), model.live_load(), opts, &s);
    super::time_history::run_history(s, loads, opts, nb, start, monitor)
}

/// Refuses joints whose strengths soften (fracture energies): the joint law at 3D contacts
/// takes dry joints and brittle ones, which lose cohesion and tensile strength at their first
/// failure.
fn check_brittle(model: &Model3) -> Result<(), Error> {
    for (k, c) in model.contacts().iter().enumerate() {
        if model.law(k).is_softening() {
            return Err(Error::input_at(
                format!("{}.fracture_energy_tension", crate::model::law_key(model.laws(), c.family)),
                "the explicit solver in 3D takes brittle joints (fracture energies 0: cohesion and tensile strength lost at the first failure); softening joints are the plane's",
            ));
        }
    }
    Ok(())
}
