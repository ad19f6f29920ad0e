//! The explicit ("molecular dynamics") solver: velocity-Verlet integration of the blocks'
//! equations of motion `M a = f_ext(t) - f_int(u) - f_damp`, with a diagonal mass (m, m, J).
//! It never assembles or factorizes a matrix. Interface forces come from the same joint law as
//! the static solver ([`crate::joint::return_map`]), applied to the increments of each time step
//! (histories are committed at every step).
//!
//! - Time step: `safety * 2 / omega_max`, with `omega_max` bounded from above by Gershgorin's
//!   theorem on the elastic interface stiffnesses (so the step is stable), unless given.
//! - Damping: local non-viscous (Cundall: `-alpha |f| sign(v)` per dof; the default of
//!   quasi-static runs) or mass-proportional viscous (`-c m v`).
//! - Quasi-static load control: each load level is relaxed until the unbalanced-force ratio is
//!   below a tolerance; a level at which the wall runs away (or does not settle) is a failure,
//!   and the collapse multiplier is bracketed by halving the load step, as in the static solver.
//! - Quasi-static displacement control: the control dof is driven; lambda follows from the
//!   control dof's own equation (the condition of the static solver's bordered system).
//! - Time histories: free motion from initial conditions, or a horizontal base acceleration
//!   (inertial forces `-m a_g(t)` in the frame of the base).
//!
//! The interface loop is the hot path: flat arrays, no allocation per step, parallel over
//! parts of the interfaces with rayon (each interface writes only its own slot, and each part
//! the force sums of the blocks whose interfaces are all in it; a gather forms the others).

use crate::error::{check_steps, Error};
use crate::interface::{Family, Interface};
use crate::joint::{return_map_forces_prepared, return_map_forces_warm, JointLaw, JointState, Kinds, Response, Section, APEX};
use crate::model::{LiveLoad, Model};
use crate::results::{Results, Status};
use rayon::prelude::*;
use std::time::Instant;

/// Damping of the explicit solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Damping {
    None,
    /// Local non-viscous damping (Cundall): a force `-alpha |f| sign(v)` on each dof, `alpha` in [0, 1).
    Local(f64),
    /// Mass-proportional viscous damping `-c m v` [1/s].
    Viscous(f64),
}

/// How the quasi-static analysis is driven.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum QsControl {
    Load,
    Displacement { max_displacement: f64 },
}

/// The largest number of threads of the interface loop (`analysis.threads`).
pub const MAX_THREADS: usize = 1024;
/// The largest number of time steps of one time history ([`simulate`]).
pub const MAX_TIME_STEPS: usize = 1_000_000_000_000;
/// The largest number of values a time history may record (displacements and velocities: 6 per
/// block and record, 8 bytes each); larger requests are refused before allocating.
pub const MAX_RECORDED_VALUES: usize = 250_000_000;

/// Options of the quasi-static explicit analysis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExplicitOptions {
    pub control: QsControl,
    /// Load levels or displacement stages (a hint, as for the static solver).
    pub steps: usize,
    /// Relative width of the bracket on the collapse multiplier.
    pub tolerance: f64,
    /// A level is settled when |unbalanced forces| <= ratio * |applied forces|.
    pub unbalanced_ratio: f64,
    pub damping: Damping,
    /// Time step [s]; None: automatic.
    pub time_step: Option<f64>,
    /// Fraction of the stability limit used by the automatic time step.
    pub safety: f64,
    /// Time steps allowed to settle one level before it counts as not settling.
    pub max_steps_per_level: usize,
    /// Threads of the interface loop; 0: all cores.
    pub threads: usize,
    pub control_block: Option<usize>,
}

impl Default for ExplicitOptions {
    fn default() -> Self {
        ExplicitOptions {
            control: QsControl::Load,
            steps: 200,
            tolerance: 1e-3,
            unbalanced_ratio: 1e-5,
            damping: Damping::Local(0.8),
            time_step: None,
            safety: 0.8,
            max_steps_per_level: 200_000,
            threads: 0,
            control_block: None,
        }
    }
}

/// Options of a dynamic time history.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicOptions {
    /// Duration [s].
    pub duration: f64,
    pub time_step: Option<f64>,
    pub safety: f64,
    pub damping: Damping,
    /// Initial (u1, u2, phi) of every block; None: zero.
    pub initial_displacement: Option<Vec<[f64; 3]>>,
    /// Initial velocities of every block; None: zero.
    pub initial_velocity: Option<Vec<[f64; 3]>>,
    /// Horizontal base acceleration history: times [s] and accelerations [m/s2], linear between
    /// samples, zero outside.
    pub base_acceleration: Option<(Vec<f64>, Vec<f64>)>,
    /// Live load multiplier held constant during the run.
    pub live_multiplier: f64,
    /// Record every n-th step.
    pub record_every: usize,
    /// Finite rotations of the blocks (rocking); false: the linearized kinematics.
    pub large_rotations: bool,
    pub threads: usize,
}

impl Default for DynamicOptions {
    fn default() -> Self {
        DynamicOptions {
            duration: 1.0,
            time_step: None,
            safety: 0.8,
            damping: Damping::None,
            initial_displacement: None,
            initial_velocity: None,
            base_acceleration: None,
            live_multiplier: 0.0,
            record_every: 1,
            large_rotations: true,
            threads: 0,
        }
    }
}

/// A recorded time history.
#[derive(Debug, Clone, PartialEq)]
pub struct TimeHistory {
    pub status: Status,
    pub error: Option<String>,
    pub time_step: f64,
    pub times: Vec<f64>,
    /// Blocks in each record.
    pub n_blocks: usize,
    /// (u1, u2, phi) of every block at each recorded time, flat and record-major: record k is
    /// `displacements[k * n_blocks..(k + 1) * n_blocks]` (see [`TimeHistory::displacement`]).
    pub displacements: Vec<[f64; 3]>,
    /// Velocities, laid out as `displacements`.
    pub velocities: Vec<[f64; 3]>,
    /// Kinetic energy [J] at each recorded time.
    pub kinetic_energy: Vec<f64>,
    /// Elastic energy stored in the joints [J].
    pub elastic_energy: Vec<f64>,
    /// Work done on the blocks by the external loads (dead, live, base inertia) [J].
    pub external_work: Vec<f64>,
    /// Energy dissipated by damping and joint plasticity [J].
    pub dissipated: Vec<f64>,
    pub steps: usize,
    pub elapsed_s: f64,
}

impl TimeHistory {
    /// (u1, u2, phi) of every block at record `k`.
    pub fn displacement(&self, k: usize) -> &[[f64; 3]] {
        &self.displacements[k * self.n_blocks..(k + 1) * self.n_blocks]
    }
    /// Velocities of every block at record `k`.
    pub fn velocity(&self, k: usize) -> &[[f64; 3]] {
        &self.velocities[k * self.n_blocks..(k + 1) * self.n_blocks]
    }
}

/// Whether the monitor is due at step `k`: every 4,096 steps, or when 0.1 s of wall time have
/// passed since it was last called (on a large wall 4,096 steps take minutes, and Ctrl-C must
/// stop a run within half a second).
fn monitor_due(k: usize, last: &mut Instant) -> bool {
    if k % 4096 == 4095 || last.elapsed().as_secs_f64() >= 0.1 {
        *last = Instant::now();
        true
    } else {
        false
    }
}

/// Progress reported to a monitor; it returns false to stop the run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    pub step: usize,
    pub multiplier: f64,
    pub displacement: f64,
    /// Fraction of the run done (NaN if unknown).
    pub fraction: f64,
}

/// The stable time step of the model: `2 / omega_max` with a Gershgorin bound on `omega_max`.
pub fn critical_time_step(model: &Model) -> f64 {
    let nb = model.n_blocks();
    let mut row = vec![0.0; 3 * nb];
    for (k, it) in model.interfaces().iter().enumerate() {
        let law = model.law(k);
        let s = &model.sections()[k];
        let d = [law.normal_stiffness * s.area, law.shear_stiffness * s.area, law.normal_stiffness * s.inertia];
        let dofs = it.dofs();
        let b = &it.b_mat;
        for i in 0..6 {
            for j in 0..6 {
                let kij = d[0] * b[0][i] * b[0][j] + d[1] * b[1][i] * b[1][j] + d[2] * b[2][i] * b[2][j];
                row[dofs[i]] += kij.abs();
            }
        }
    }
    let fixed = model.fixed();
    let mut w2: f64 = 0.0;
    for i in 0..nb {
        let mm = [model.mass()[i], model.mass()[i], model.inertia()[i]];
        for k in 0..3 {
            if !fixed[3 * i + k] {
                w2 = w2.max(row[3 * i + k] / mm[k]);
            }
        }
    }
    if w2 > 0.0 {
        2.0 / w2.sqrt()
    } else {
        f64::INFINITY
    }
}

/// Blocks per task of the block passes: a few hundred microseconds of work per task at most,
/// about a hundred tasks at 10^5 blocks.
const GRAIN_BLOCKS: usize = 1024;
/// Below this many interfaces a step runs on one thread whatever is asked: the two hand-offs to
/// the pool per step (some 10-20 us each) cost more than the second thread gives back.
const PAR_MIN_INTERFACES: usize = 2048;
/// Interfaces per part of the interface pass on the pool (at least two parts per thread).
const PART_INTERFACES: usize = 32768;

/// What the interface loop reads of an interface, packed in 12 bytes (the model's
/// [`crate::interface::Interface`] takes 208): the two blocks, each with a bit that tells if
/// the interface loop sums the block's forces (see [`Integrator::parts`]), and the index of
/// its [`Shape`] in the integrator's table of the distinct shapes (a few thousand on a wall of
/// 10^5 blocks: its interfaces repeat a handful of lever arms, normals, families and sections).
#[derive(Debug, Clone, Copy)]
struct Geo {
    a: u32,
    b: u32,
    shape: u32,
}

/// The bit of [`Geo::a`] and [`Geo::b`] set when the interface loop sums the block's forces.
const SUMMED: u32 = 1 << 31;
/// The block's index in [`Geo::a`] and [`Geo::b`].
const BLOCK: u32 = SUMMED - 1;

impl Geo {
    #[inline(always)]
    fn a(&self) -> usize {
        (self.a & BLOCK) as usize
    }
    #[inline(always)]
    fn b(&self) -> usize {
        (self.b & BLOCK) as usize
    }
}

/// What interfaces of one shape share: the four entries of `B` that are not +-n, +-t or +-1,
/// the normal, the family and the kind (an index into the integrator's table of the distinct
/// pairs of law and section). `B`'s rows are (-n, -n.ra, n, n.rb), (-t, -t.ra, t, t.rb) and
/// (0, 0, -1, 0, 0, 1), with t = (n_y, -n_x); [`Shape::b_mat`] rebuilds them bit for bit.
#[derive(Debug, Clone, Copy)]
struct Shape {
    /// b_mat[0][2], b_mat[0][5], b_mat[1][2], b_mat[1][5]
    r: [f64; 4],
    n: [f64; 2],
    /// [`Kinds::NONE`] for an interface whose kind did not fit in the table
    kind: u16,
    family: u8,
}

impl Shape {
    /// The shape of `it`, of kind `kind` (bit for bit).
    fn new(it: &Interface, kind: u16) -> Self {
        let b = &it.b_mat;
        Shape { r: [b[0][2], b[0][5], b[1][2], b[1][5]], n: it.n, kind, family: family_index(it.family) }
    }

    /// The bits that tell two shapes apart.
    fn key(&self) -> ([u64; 4], [u64; 2], u16, u8) {
        (self.r.map(f64::to_bits), self.n.map(f64::to_bits), self.kind, self.family)
    }

    /// The generalized forces `B^T s` on side `sb` (0: block a, 1: block b) of an interface
    /// of this shape carrying `s` = (N, T, M): the side's three columns of `B` (see
    /// [`Shape::b_mat`]), picked without a branch, (-+n0, -+n1, 0), (-+n1, +-n0, 0) and
    /// (r, r', -+1), each dotted with `s` (a product by -1 is the negation: the same numbers).
    #[inline(always)]
    fn side_force(&self, s: &[f64; 3], sb: usize) -> [f64; 3] {
        let sg = [-1.0, 1.0][sb];
        let [n0, n1] = self.n;
        let cols = [[sg * n0, sg * n1, 0.0], [sg * n1, -sg * n0, 0.0], [self.r[sb], self.r[2 + sb], sg]];
        let dot = |b: &[f64; 3]| b[0] * s[0] + b[1] * s[1] + b[2] * s[2];
        [dot(&cols[0]), dot(&cols[1]), dot(&cols[2])]
    }

    /// What the force sums of blocks a and b add for an interface of this shape carrying `s`:
    /// [`Shape::side_force`] of both sides in fewer operations, the same sums bit for bit. The
    /// force on b is t = (n0 N + n1 T, n1 N - n0 T) and on a -t; the moments are r N + r' T -+
    /// M. `side_force` also adds the products 0 M to the forces, and sums the negated products
    /// for a: its terms differ only where they are zero, and then only in the sign of the zero
    /// (rounding is symmetric, and x + 0 M == x for x != 0 when M is finite), which a force sum
    /// does not see: it starts from +0.0, so it is never -0.0, and x + -0.0 == x + 0.0 == x for
    /// every other x. With M not finite (0 M is NaN), `side_force` itself.
    #[inline(always)]
    fn side_sums(&self, s: &[f64; 3]) -> [[f64; 3]; 2] {
        if !s[2].is_finite() {
            return [self.side_force(s, 0), self.side_force(s, 1)];
        }
        let ([n0, n1], r) = (self.n, &self.r);
        let t = [n0 * s[0] + n1 * s[1], n1 * s[0] - n0 * s[1]];
        [[-t[0], -t[1], r[0] * s[0] + r[2] * s[1] - s[2]], [t[0], t[1], r[1] * s[0] + r[3] * s[1] + s[2]]]
    }

    #[inline(always)]
    fn b_mat(&self) -> [[f64; 6]; 3] {
        let ([n0, n1], r) = (self.n, self.r);
        [[-n0, -n1, r[0], n0, n1, r[1]], [-n1, n0, r[2], n1, -n0, r[3]], [0.0, 0.0, -1.0, 0.0, 0.0, 1.0]]
    }
}

/// The return mapping of an interface whose kind is not in the table (out of line: the loop
/// keeps one inlined copy, for the table's kinds).
#[inline(never)]
fn map_unprepared(law: &JointLaw, sec: &Section, e: [f64; 3], st: &JointState, warm: u8) -> (Response, u8) {
    return_map_forces_warm(law, sec, e, st, warm)
}

/// A committed joint history from its packed form (`h`: the plastic jumps, then the opening and
/// the slip if stored; not stored they are zero, which no law that does not soften reads).
#[inline(always)]
fn unpack(h: &[f64], broken: bool) -> JointState {
    let (opening, slip) = if h.len() == 5 { (h[3], h[4]) } else { (0.0, 0.0) };
    JointState { plastic: [h[0], h[1], h[2]], broken, opening, slip }
}

/// The packed form of a history (see [`unpack`]).
#[inline(always)]
fn pack(st: &JointState, h: &mut [f64]) {
    h[..3].copy_from_slice(&st.plastic);
    if h.len() == 5 {
        h[3] = st.opening;
        h[4] = st.slip;
    }
}

/// A part of the interface pass: the interfaces from `k0` (their histories, forces, flags and
/// warm sets), the force sums of the blocks from `b0`, and the terms from `t0`.
struct Part<'s> {
    k0: usize,
    b0: usize,
    t0: usize,
    hist: &'s mut [f64],
    broken: &'s mut [bool],
    forces: &'s mut [[f64; 3]],
    flags: &'s mut [u8],
    warm: &'s mut [u8],
    /// the forces on the blocks whose sums the pass does not form, in the order of
    /// [`Straddlers::slots`]
    terms: &'s mut [[f64; 3]],
    f_int: &'s mut [f64],
}

impl<'s> Part<'s> {
    /// The part before interface `k`, block `blk` and term `t`, and the part from them.
    fn split(self, (k, blk, t): (usize, usize, usize), hw: usize) -> (Part<'s>, Part<'s>) {
        let (kk, bb) = (k - self.k0, blk - self.b0);
        let (h0, h1) = self.hist.split_at_mut(hw * kk);
        let (br0, br1) = self.broken.split_at_mut(kk);
        let (f0, f1) = self.forces.split_at_mut(kk);
        let (fl0, fl1) = self.flags.split_at_mut(kk);
        let (w0, w1) = self.warm.split_at_mut(kk);
        let (t0, t1) = self.terms.split_at_mut(t - self.t0);
        let (s0, s1) = self.f_int.split_at_mut(3 * bb);
        (
            Part { k0: self.k0, b0: self.b0, t0: self.t0, hist: h0, broken: br0, forces: f0, flags: fl0, warm: w0, terms: t0, f_int: s0 },
            Part { k0: k, b0: blk, t0: t, hist: h1, broken: br1, forces: f1, flags: fl1, warm: w1, terms: t1, f_int: s1 },
        )
    }
}

/// Runs `work` on the parts of `p` cut at `bounds` (interface, block, term; the first and the last
/// are `p`'s own start and end), in parallel on the current rayon pool.
fn run_parts<F: Fn(Part) + Sync>(p: Part, bounds: &[(usize, usize, usize)], hw: usize, work: &F) {
    if bounds.len() <= 2 {
        work(p);
    } else {
        let mid = bounds.len() / 2;
        let (l, r) = p.split(bounds[mid], hw);
        rayon::join(|| run_parts(l, &bounds[..=mid], hw, work), || run_parts(r, &bounds[mid..], hw, work));
    }
}

/// What the parts of the interface pass read.
struct Pass<'a> {
    model: &'a Model,
    u: &'a [f64],
    geo: &'a [Geo],
    shapes: &'a [Shape],
    laws: &'a [JointLaw; 4],
    kinds: &'a Kinds,
    /// with finite rotations only: the blocks' reference centroids and (cos, sin) of their
    /// rotations
    centroids: &'a [[f64; 2]],
    cs: &'a [[f64; 2]],
}

impl Pass<'_> {
    /// The return mapping of interface `k` of shape `gk` for the jumps `e`, with its kind's
    /// constants, its results stored (each arm stores its own: no copy of the response
    /// between them); inlined in the loop of [`Pass::part`].
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn update(&self, k: usize, gk: &Shape, e: [f64; 3], h: &mut [f64], br: &mut bool, f: &mut [f64; 3], fl: &mut u8, ws: &mut u8) {
        let law = &self.laws[gk.family as usize];
        let st = &unpack(h, *br);
        let store = |(r, set): (Response, u8), h: &mut [f64], br: &mut bool, f: &mut [f64; 3], fl: &mut u8, ws: &mut u8| {
            // an elastic update or the apex of degenerate data keeps the last set
            if set != 0 && set != APEX {
                *ws = set;
            }
            pack(&r.state, h);
            *br = r.state.broken;
            *f = r.force;
            *fl = r.flags;
        };
        match self.kinds.get(gk.kind) {
            Some((sec, prep)) => store(return_map_forces_prepared(law, sec, prep, e, st, *ws), h, br, f, fl, ws),
            None => store(map_unprepared(law, &self.model.sections()[k], e, st, *ws), h, br, f, fl, ws),
        }
    }

    /// The interface pass over part `p`, with histories of `HW` numbers and finite rotations
    /// if `LARGE` (one copy of the loop for each).
    fn part<const HW: usize, const LARGE: bool>(&self, p: Part) {
        let Part { k0, b0, hist, broken, forces, flags, warm, terms, f_int, .. } = p;
        let (u, shapes) = (self.u, self.shapes);
        // every sum starts from +0.0, as the gather's
        f_int.fill(0.0);
        // adds x to the block's sum if it is one of the part's (`side`: the block's field of
        // Geo), else stores it as the next term
        let mut terms = terms.iter_mut();
        let mut sum = |side: u32, blk: usize, x: [f64; 3]| {
            if side & SUMMED != 0 {
                if let Some([s0, s1, s2]) = blk.checked_sub(b0).and_then(|i| f_int.get_mut(3 * i..3 * i + 3)) {
                    *s0 += x[0];
                    *s1 += x[1];
                    *s2 += x[2];
                }
            } else if let Some(t) = terms.next() {
                *t = x;
            }
        };
        let geo = &self.geo[k0..k0 + broken.len()];
        for (i, (((((h, br), f), fl), ws), ik)) in hist
            .chunks_exact_mut(HW)
            .zip(broken.iter_mut())
            .zip(forces.iter_mut())
            .zip(flags.iter_mut())
            .zip(warm.iter_mut())
            .zip(geo)
            .enumerate()
        {
            let k = k0 + i;
            let gk = &shapes[ik.shape as usize];
            if LARGE {
                let it = &self.model.interfaces()[k];
                let (a, b, g, cs) = (it.a, it.b, self.centroids, self.cs);
                // the normal force's eccentricity at the previous step, within the interface
                let ecc = if f[0] < 0.0 { (f[2] / f[0]).clamp(-0.5 * it.l, 0.5 * it.l) } else { 0.0 };
                let kin = it.large_kinematics(g[a], g[b], &u[3 * a..3 * a + 3], &u[3 * b..3 * b + 3], cs[a], cs[b], ecc);
                self.update(k, gk, kin.jumps, h, br, f, fl, ws);
                let x = kin.forces(*f);
                sum(ik.a, a, [x[0], x[1], x[2]]);
                sum(ik.b, b, [x[3], x[4], x[5]]);
            } else {
                let (a, b) = (ik.a(), ik.b());
                let (ua, ub) = (&u[3 * a..3 * a + 3], &u[3 * b..3 * b + 3]);
                let q = [ua[0], ua[1], ua[2], ub[0], ub[1], ub[2]];
                let bm = gk.b_mat();
                // as Interface::jumps, term by term (`Iterator::sum` of f64 starts from
                // -0.0, and -0.0 + x == x: the sum is the terms added left to right)
                let row = |r: usize| {
                    let b = &bm[r];
                    b[0] * q[0] + b[1] * q[1] + b[2] * q[2] + b[3] * q[3] + b[4] * q[4] + b[5] * q[5]
                };
                let e = [row(0), row(1), row(2)];
                self.update(k, gk, e, h, br, f, fl, ws);
                let [xa, xb] = gk.side_sums(f);
                sum(ik.a, a, xa);
                sum(ik.b, b, xb);
            }
        }
    }

    /// [`Pass::part`] for `hw` and `large`.
    fn run(&self, p: Part, hw: usize, large: bool) {
        match (hw, large) {
            (3, false) => self.part::<3, false>(p),
            (3, true) => self.part::<3, true>(p),
            (_, false) => self.part::<5, false>(p),
            (_, true) => self.part::<5, true>(p),
        }
    }
}

/// The blocks whose interfaces lie in more than one part of the interface pass, and where
/// the pass leaves their interfaces' forces on them: `slots[start[j]..start[j + 1]]` for
/// `blocks[j]`, increasing in k, index the terms, which the pass fills in the order of the
/// interfaces (a before b).
#[derive(Default)]
struct Straddlers {
    blocks: Vec<u32>,
    start: Vec<u32>,
    slots: Vec<u32>,
}

/// The interface pass in `n_parts` parts of about as many interfaces (see
/// [`Integrator::parts`]), the blocks whose forces the pass sums marked [`SUMMED`] in `geo`,
/// and the others. Any order of the interfaces gives the same sums; the model's, by block a,
/// makes most blocks' interfaces fall in one part.
fn partition(nb: usize, geo: &mut [Geo], n_parts: usize) -> (Vec<(usize, usize, usize)>, Straddlers) {
    let m = geo.len();
    let n_parts = n_parts.clamp(1, m.max(1));
    let mut parts = vec![(0, 0, 0)];
    for p in 1..n_parts {
        let k = (p as u64 * m as u64 / n_parts as u64) as usize;
        // the blocks from the part's first interface's a on (nondecreasing)
        let b0 = parts[p - 1].1;
        parts.push((k, geo[k].a().clamp(b0, nb), 0));
    }
    parts.push((m, nb, 0));
    // each block's first and last interface
    let mut span = vec![(u32::MAX, 0u32); nb];
    for (k, g) in geo.iter().enumerate() {
        for blk in [g.a(), g.b()] {
            span[blk] = (span[blk].0.min(k as u32), k as u32);
        }
    }
    let mut summed = vec![false; nb];
    for w in parts.windows(2) {
        let ((k0, b0, _), (k1, b1, _)) = (w[0], w[1]);
        for (s, &(first, last)) in summed[b0..b1].iter_mut().zip(&span[b0..b1]) {
            *s = first == u32::MAX || (first as usize >= k0 && (last as usize) < k1);
        }
    }
    for g in geo.iter_mut() {
        for side in [&mut g.a, &mut g.b] {
            if summed[(*side & BLOCK) as usize] {
                *side |= SUMMED;
            }
        }
    }
    // the other blocks' interfaces, by counting sort: in increasing k within each block
    let blocks: Vec<u32> = (0..nb).filter(|&i| !summed[i]).map(|i| i as u32).collect();
    let mut index = vec![u32::MAX; nb];
    for (j, &i) in blocks.iter().enumerate() {
        index[i as usize] = j as u32;
    }
    let mut start = vec![0u32; blocks.len() + 1];
    for g in geo.iter() {
        for blk in [g.a(), g.b()] {
            if index[blk] != u32::MAX {
                start[index[blk] as usize + 1] += 1;
            }
        }
    }
    for j in 0..blocks.len() {
        start[j + 1] += start[j];
    }
    // the terms in the order the pass fills them, and where each part's start
    let mut next = start.clone();
    let mut slots = vec![0u32; start[blocks.len()] as usize];
    let (mut n, mut p) = (0u32, 0);
    for (k, g) in geo.iter().enumerate() {
        while p < parts.len() && parts[p].0 == k {
            parts[p].2 = n as usize;
            p += 1;
        }
        for blk in [g.a(), g.b()] {
            if let Some(j) = index.get(blk).filter(|&&j| j != u32::MAX) {
                slots[next[*j as usize] as usize] = n;
                next[*j as usize] += 1;
                n += 1;
            }
        }
    }
    for part in &mut parts[p..] {
        part.2 = n as usize;
    }
    (parts, Straddlers { blocks, start, slots })
}

/// Index of a family in the integrator's table of four laws.
fn family_index(f: Family) -> u8 {
    match f {
        Family::Bed => 0,
        Family::Head => 1,
        Family::Base => 2,
        Family::Top => 3,
    }
}

/// The integrator's state and work arrays (flat, allocated once).
///
/// Per interface: the packed geometry (12 bytes: the blocks and the index of the shape, whose
/// table holds the lever arms, the normal, the family and the kind), the history (24: the
/// plastic jumps, and 16 more, the opening and the slip, only if a law softens; `JointState`
/// takes 48), the broken flag (1), the force (24), the flags (1) and the warm set (1); sections
/// and laws are read from the model (a table of four laws, one per family). With finite
/// rotations also, per block, the centroid and the rotation's (cos, sin). One step is: a pass
/// over the blocks (velocity half-step and positions), a pass over the interfaces in parts
/// (return mapping, and each interface's forces on its blocks added to their sums at once, for
/// the blocks whose interfaces are all in one part: in interface order, so the sums do not
/// depend on the number of threads; for the others (a course of blocks at each boundary of
/// parts) the forces are stored and a gather sums them after the pass, in the same order), the
/// external forces, and a pass over the blocks (accelerations and velocity half-step). Each pass
/// is split into independent chunks on the thread pool.
struct Integrator<'a> {
    model: &'a Model,
    geo: Vec<Geo>,
    /// the distinct shapes of interface (see [`Geo`])
    shapes: Vec<Shape>,
    /// the kinds of interface (see [`Shape`])
    kinds: Kinds,
    laws: [JointLaw; 4],
    /// The interface pass in parts (one unless the passes go to the pool): part p maps the
    /// interfaces `parts[p].0..parts[p + 1].0` and adds their forces to the blocks'
    /// `parts[p].1..parts[p + 1].1` whose interfaces are all among them (marked [`SUMMED`] in
    /// [`Geo`]), in increasing k: the sums of the gather below, with no pass of their own.
    parts: Vec<(usize, usize, usize)>,
    /// the other blocks, whose sums a gather after the pass forms from the terms the pass
    /// leaves them (`parts[p].2..parts[p + 1].2` from part p), and the sums
    straddlers: Straddlers,
    terms: Vec<[f64; 3]>,
    straddler_sums: Vec<[f64; 3]>,
    inv_mass: Vec<f64>,
    mass: Vec<f64>,
    free: Vec<bool>,
    u: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    f_int: Vec<f64>,
    f_ext: Vec<f64>,
    /// the committed joint histories, `hw` numbers an interface: the plastic jumps, then (only
    /// if a law softens, `hw` = 5) the opening and the slip, which no other law reads
    hist: Vec<f64>,
    hw: usize,
    broken: Vec<bool>,
    forces: Vec<[f64; 3]>,
    flags: Vec<u8>,
    /// the active set each interface's return mapping accepted at its last plastic update
    /// (bit j: face j; 0: none yet), tried first at the next ([`return_map_forces_warm`])
    warm: Vec<u8>,
    dt: f64,
    damping: Damping,
    pool: std::sync::Arc<rayon::ThreadPool>,
    /// whether the passes go to the pool (more than one thread and enough interfaces)
    par: bool,
    steps: usize,
    /// finite rotations (time histories) or the linearized kinematics of the static solver
    large: bool,
    /// reference centroids and (cos, sin) of the current rotation of each block
    centroids: Vec<[f64; 2]>,
    cs: Vec<[f64; 2]>,
}

impl<'a> Integrator<'a> {
    fn new(model: &'a Model, dt: Option<f64>, safety: f64, damping: Damping, threads: usize) -> Result<Self, Error> {
        let crit = critical_time_step(model);
        let dt = match dt {
            Some(dt) => {
                if !(dt.is_finite() && dt > 0.0) {
                    return Err(Error::input(format!("analysis.time_step must be a finite number > 0, got {dt}")));
                }
                if dt > crit {
                    return Err(Error::input(format!(
                        "analysis.time_step = {dt:.3e} s exceeds the stability limit of this model, {crit:.3e} s"
                    )));
                }
                dt
            }
            None => {
                if !(safety > 0.0 && safety <= 1.0) {
                    return Err(Error::input(format!("safety must lie in (0, 1], got {safety}")));
                }
                if !crit.is_finite() {
                    return Err(Error::input("no stiffness holds the model: no stable time step"));
                }
                safety * crit
            }
        };
        match damping {
            Damping::Local(a) if !(0.0..1.0).contains(&a) => {
                return Err(Error::input(format!("analysis.damping_coefficient (local damping) must lie in [0, 1), got {a}")))
            }
            Damping::Viscous(c) if !(c.is_finite() && c >= 0.0) => {
                return Err(Error::input(format!("analysis.damping_coefficient (viscous damping) must be finite and >= 0, got {c}")))
            }
            _ => {}
        }
        if threads > MAX_THREADS {
            return Err(Error::input(format!("analysis.threads = {threads} is more than the limit of {MAX_THREADS}")));
        }
        let nb = model.n_blocks();
        let m = model.interfaces().len();
        if nb > BLOCK as usize || 2 * m >= u32::MAX as usize {
            return Err(Error::input(format!("{nb} blocks and {m} interfaces: the explicit solver takes fewer than 2^31 blocks and 2^31 interfaces")));
        }
        let fixed = model.fixed();
        let mut mass = vec![0.0; 3 * nb];
        let mut inv_mass = vec![0.0; 3 * nb];
        for i in 0..nb {
            let mm = [model.mass()[i], model.mass()[i], model.inertia()[i]];
            for k in 0..3 {
                mass[3 * i + k] = mm[k];
                if !fixed[3 * i + k] {
                    inv_mass[3 * i + k] = 1.0 / mm[k];
                }
            }
        }
        // the laws by family index (see `family_index`)
        let laws = [Family::Bed, Family::Head, Family::Base, Family::Top].map(|f| *model.laws().of(f));
        let kinds = model.joint_kinds();
        let mut shapes: Vec<Shape> = vec![];
        let mut shape_of = std::collections::HashMap::new();
        let mut geo = Vec::with_capacity(m);
        for (k, it) in model.interfaces().iter().enumerate() {
            let shape = Shape::new(it, kinds.kind(k));
            // at most one shape per interface: fewer than 2^31
            let index = *shape_of.entry(shape.key()).or_insert_with(|| {
                shapes.push(shape);
                (shapes.len() - 1) as u32
            });
            geo.push(Geo { a: it.a as u32, b: it.b as u32, shape: index });
        }
        let hw = if laws.iter().any(|l| l.is_softening()) { 5 } else { 3 };
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| Error::input(format!("cannot start {threads} threads: {e}")))?;
        let par = pool.current_num_threads() > 1 && m >= PAR_MIN_INTERFACES;
        let n_parts = if par { (2 * pool.current_num_threads()).max(m.div_ceil(PART_INTERFACES)) } else { 1 };
        let pool = std::sync::Arc::new(pool);
        let mut it = Integrator {
            model,
            geo,
            shapes,
            kinds,
            laws,
            parts: vec![],
            straddler_sums: vec![],
            terms: vec![],
            straddlers: Straddlers::default(),
            inv_mass,
            mass,
            free: fixed.iter().map(|f| !f).collect(),
            u: model.prescribed().to_vec(),
            v: vec![0.0; 3 * nb],
            a: vec![0.0; 3 * nb],
            f_int: vec![0.0; 3 * nb],
            f_ext: vec![0.0; 3 * nb],
            hist: vec![0.0; hw * m],
            hw,
            broken: vec![false; m],
            forces: vec![[0.0; 3]; m],
            flags: vec![0; m],
            warm: vec![0; m],
            dt,
            damping,
            pool,
            par,
            steps: 0,
            large: false,
            centroids: vec![],
            cs: vec![],
        };
        it.set_parts(n_parts);
        Ok(it)
    }

    /// The interface pass in `n_parts` parts (see [`partition`]), with the terms and sums of
    /// the blocks that straddle them.
    fn set_parts(&mut self, n_parts: usize) {
        for g in &mut self.geo {
            g.a &= BLOCK;
            g.b &= BLOCK;
        }
        let (parts, straddlers) = partition(self.model.n_blocks(), &mut self.geo, n_parts);
        self.terms = vec![[0.0; 3]; straddlers.slots.len()];
        self.straddler_sums = vec![[0.0; 3]; straddlers.blocks.len()];
        (self.parts, self.straddlers) = (parts, straddlers);
    }

    /// Finite rotations (time histories) or the linearized kinematics (the default); the
    /// arrays only the finite rotations need are allocated here.
    fn set_large(&mut self, large: bool) {
        self.large = large;
        if large && self.cs.is_empty() {
            let nb = self.model.n_blocks();
            self.centroids = self.model.rects().iter().map(|r| r.centroid()).collect();
            self.cs = vec![[1.0, 0.0]; nb];
        }
    }

    /// A damped integrator (local damping 0.8, one thread) started from a static state: the
    /// displacements `u` and joint histories `states` of a state past the dead loads, with the
    /// dofs held after them held. The static solver's explicit by-products start from it.
    fn damped_from(model: &'a Model, u: &[f64], states: &[JointState]) -> Result<Self, Error> {
        let mut s = Integrator::new(model, None, 0.8, Damping::Local(0.8), 1)?;
        s.u.copy_from_slice(u);
        s.set_states(states);
        s.hold();
        Ok(s)
    }

    /// Fixes the dofs the model holds once the dead loads are on, where they are now.
    fn hold(&mut self) {
        for &d in self.model.held_after_dead() {
            self.free[d] = false;
            self.inv_mass[d] = 0.0;
            self.v[d] = 0.0;
            self.a[d] = 0.0;
        }
    }

    /// The law of interface `k`.
    #[inline(always)]
    fn law(&self, k: usize) -> &JointLaw {
        &self.laws[self.shapes[self.geo[k].shape as usize].family as usize]
    }

    /// The committed history of interface `k`.
    fn state(&self, k: usize) -> JointState {
        unpack(&self.hist[self.hw * k..self.hw * (k + 1)], self.broken[k])
    }

    /// Every committed history.
    fn states(&self) -> Vec<JointState> {
        (0..self.broken.len()).map(|k| self.state(k)).collect()
    }

    fn set_states(&mut self, states: &[JointState]) {
        for (k, st) in states.iter().enumerate() {
            pack(st, &mut self.hist[self.hw * k..self.hw * (k + 1)]);
            self.broken[k] = st.broken;
        }
    }

    /// Interface forces at the current `u` from the committed histories, which are updated
    /// (each time step is an increment), then gathered into `f_int`.
    fn interface_forces(&mut self) {
        if self.par {
            let pool = self.pool.clone();
            pool.install(|| self.interface_forces_in(true));
        } else {
            self.interface_forces_in(false);
        }
    }

    /// [`Integrator::interface_forces`], on the current rayon pool if `par`.
    fn interface_forces_in(&mut self, par: bool) {
        if self.large {
            let u = &self.u;
            let rot = |i0: usize, cs: &mut [[f64; 2]]| {
                for (i, cs) in cs.iter_mut().enumerate() {
                    let (s, c) = u[3 * (i0 + i) + 2].sin_cos();
                    *cs = [c, s];
                }
            };
            if par {
                self.cs.par_chunks_mut(GRAIN_BLOCKS).enumerate().for_each(|(c, cs)| rot(c * GRAIN_BLOCKS, cs));
            } else {
                rot(0, &mut self.cs);
            }
        }
        let pass = Pass {
            model: self.model,
            u: &self.u,
            geo: &self.geo,
            shapes: &self.shapes,
            laws: &self.laws,
            kinds: &self.kinds,
            centroids: &self.centroids,
            cs: &self.cs,
        };
        let (large, hw) = (self.large, self.hw);
        let work = |p: Part| pass.run(p, hw, large);
        let all = Part {
            k0: 0,
            b0: 0,
            t0: 0,
            hist: &mut self.hist,
            broken: &mut self.broken,
            forces: &mut self.forces,
            flags: &mut self.flags,
            warm: &mut self.warm,
            terms: &mut self.terms,
            f_int: &mut self.f_int,
        };
        if par {
            run_parts(all, &self.parts, hw, &work);
        } else {
            // the parts one after the other: the same sums
            work(all);
        }
        // the blocks whose interfaces span parts: each sums its interfaces' forces in
        // increasing k, as a serial scatter in interface order would
        let (st, terms) = (&self.straddlers, &self.terms);
        if st.blocks.is_empty() {
            return;
        }
        let gather = |j0: usize, out: &mut [[f64; 3]]| {
            for (j, out) in out.iter_mut().enumerate() {
                let j = j0 + j;
                let mut acc = [0.0; 3];
                for &t in &st.slots[st.start[j] as usize..st.start[j + 1] as usize] {
                    let x = &terms[t as usize];
                    acc[0] += x[0];
                    acc[1] += x[1];
                    acc[2] += x[2];
                }
                *out = acc;
            }
        };
        let sums = &mut self.straddler_sums;
        if par {
            sums.par_chunks_mut(GRAIN_BLOCKS).enumerate().for_each(|(c, out)| gather(c * GRAIN_BLOCKS, out));
        } else {
            gather(0, sums);
        }
        for (&i, x) in st.blocks.iter().zip(sums.iter()) {
            self.f_int[3 * i as usize..3 * i as usize + 3].copy_from_slice(x);
        }
    }

    /// Accelerations from the current forces, with damping against the current velocity; then,
    /// with `kick`, the velocity half-step `v += kick * a` on the free dofs.
    fn accelerations_kick(&mut self, kick: Option<f64>) {
        let damping = self.damping;
        let (f_ext, f_int, free, inv_mass, mass) = (&self.f_ext, &self.f_int, &self.free, &self.inv_mass, &self.mass);
        // one dof: the same operations for every kind of damping; the mass is read only by
        // viscous damping (local damping and none do not touch it: 8 bytes a dof less per step)
        #[inline(always)]
        #[allow(clippy::too_many_arguments)]
        fn dof(damping: Damping, kick: Option<f64>, a: &mut f64, v: &mut f64, free: bool, fe: f64, fi: f64, im: f64, m: impl FnOnce() -> f64) {
            if !free {
                *a = 0.0;
                return;
            }
            let mut f = fe - fi;
            let vd = *v;
            let fd = match damping {
                Damping::None => 0.0,
                Damping::Local(alpha) => {
                    if vd != 0.0 {
                        -alpha * f.abs() * vd.signum()
                    } else {
                        0.0
                    }
                }
                Damping::Viscous(c) => -c * m() * vd,
            };
            f += fd;
            *a = f * im;
            if let Some(h) = kick {
                *v += h * *a;
            }
        }
        let work = |d0: usize, a: &mut [f64], v: &mut [f64]| {
            // the chunk's slices, zipped: no bounds check per dof
            let r = d0..d0 + a.len();
            let dofs = free[r.clone()].iter().zip(&f_ext[r.clone()]).zip(&f_int[r.clone()]).zip(&inv_mass[r.clone()]);
            if let Damping::Viscous(_) = damping {
                for ((a, v), ((((&free, &fe), &fi), &im), &m)) in a.iter_mut().zip(v.iter_mut()).zip(dofs.zip(&mass[r])) {
                    dof(damping, kick, a, v, free, fe, fi, im, || m);
                }
            } else {
                for ((a, v), (((&free, &fe), &fi), &im)) in a.iter_mut().zip(v.iter_mut()).zip(dofs) {
                    dof(damping, kick, a, v, free, fe, fi, im, || 0.0);
                }
            }
        };
        if self.par {
            const G: usize = 3 * GRAIN_BLOCKS;
            let (a, v) = (&mut self.a, &mut self.v);
            self.pool.install(|| a.par_chunks_mut(G).zip(v.par_chunks_mut(G)).enumerate().for_each(|(c, (a, v))| work(c * G, a, v)));
        } else {
            work(0, &mut self.a, &mut self.v);
        }
    }

    /// Accelerations from the current forces, with damping against the current velocity.
    fn accelerations(&mut self) {
        self.accelerations_kick(None);
    }

    /// The first half of a velocity-Verlet step: `v += dt/2 a`, `u += dt v` on the free dofs,
    /// then the prescribed dof; on the current rayon pool if `par`.
    fn drift_in(&mut self, prescribed: Option<(usize, f64)>, par: bool) {
        let dt = self.dt;
        let (a, free) = (&self.a, &self.free);
        let drift = |d0: usize, u: &mut [f64], v: &mut [f64]| {
            let r = d0..d0 + u.len();
            for ((u, v), (&free, &a)) in u.iter_mut().zip(v.iter_mut()).zip(free[r.clone()].iter().zip(&a[r])) {
                if free {
                    *v += 0.5 * dt * a;
                    *u += dt * *v;
                }
            }
        };
        if par {
            const G: usize = 3 * GRAIN_BLOCKS;
            self.u.par_chunks_mut(G).zip(self.v.par_chunks_mut(G)).enumerate().for_each(|(c, (u, v))| drift(c * G, u, v));
        } else {
            drift(0, &mut self.u, &mut self.v);
        }
        if let Some((d, val)) = prescribed {
            self.v[d] = (val - self.u[d]) / dt;
            self.u[d] = val;
        }
    }

    /// One velocity-Verlet step; `f_ext` must hold the external forces at the new time.
    /// `prescribed`: dof driven to a value (displacement control).
    fn step(&mut self, set_ext: &mut dyn FnMut(&mut [f64], &[f64]), prescribed: Option<(usize, f64)>) {
        if self.par {
            // one hand-off to the pool for the positions and the interface forces
            let pool = self.pool.clone();
            pool.install(|| {
                self.drift_in(prescribed, true);
                self.interface_forces_in(true);
            });
        } else {
            self.drift_in(prescribed, false);
            self.interface_forces_in(false);
        }
        set_ext(&mut self.f_ext, &self.f_int);
        self.accelerations_kick(Some(0.5 * self.dt));
        if let Some((d, _)) = prescribed {
            self.a[d] = 0.0;
        }
        self.steps += 1;
    }

    /// |unbalanced forces| / |applied forces| on the free dofs, dof `skip` left out.
    fn unbalanced_ratio(&self, skip: Option<usize>) -> f64 {
        let (mut r, mut f) = (0.0, 0.0);
        for d in 0..self.u.len() {
            if self.free[d] && Some(d) != skip {
                let x = self.f_ext[d] - self.f_int[d];
                r += x * x;
                f += self.f_ext[d] * self.f_ext[d];
            }
        }
        (r / f.max(f64::MIN_POSITIVE)).sqrt()
    }

    fn kinetic_energy(&self) -> f64 {
        0.5 * (0..self.u.len()).filter(|&d| self.free[d]).map(|d| self.mass[d] * self.v[d] * self.v[d]).sum::<f64>()
    }

    fn elastic_energy(&self) -> f64 {
        let mut e = 0.0;
        for (k, f) in self.forces.iter().enumerate() {
            let (law, s) = (self.law(k), &self.model.sections()[k]);
            e += 0.5
                * (f[0] * f[0] / (law.normal_stiffness * s.area)
                    + f[1] * f[1] / (law.shear_stiffness * s.area)
                    + f[2] * f[2] / (law.normal_stiffness * s.inertia));
        }
        e
    }
}

/// A bare time stepper over the integrator of [`simulate`], for benchmarks and profiling (not
/// part of the supported API): the model under its dead loads plus `live_multiplier` times its
/// live loads, from rest, with the automatic time step (safety 0.8). [`Stepper::run`] does
/// `k` time steps and nothing else: no records, no energy, no checks.
///
/// ```
/// use masonry_dem::explicit::{Damping, Stepper};
/// use masonry_dem::geometry::Rect;
/// use masonry_dem::model::{Model, ModelSpec};
/// let model = Model::new(ModelSpec { blocks: vec![Rect::new(0.0, 0.0, 0.4, 0.2)], ..ModelSpec::default() }).unwrap();
/// let mut s = Stepper::new(&model, 0.0, Damping::Local(0.8), false, 1).unwrap();
/// s.run(10);
/// assert_eq!(s.n_interfaces(), 1);
/// assert!(s.displacements()[1] < 0.0); // the block settles onto the base
/// ```
#[doc(hidden)]
pub struct Stepper<'a> {
    s: Integrator<'a>,
    f: Vec<f64>,
}

impl<'a> Stepper<'a> {
    /// The integrator of `model` (linearized kinematics unless `large_rotations`) on `threads`
    /// threads (0: all cores).
    pub fn new(model: &'a Model, live_multiplier: f64, damping: Damping, large_rotations: bool, threads: usize) -> Result<Self, Error> {
        let mut s = Integrator::new(model, None, 0.8, damping, threads)?;
        s.set_large(large_rotations);
        let f: Vec<f64> = model.dead_load().iter().zip(model.live_load()).map(|(d, l)| d + live_multiplier * l).collect();
        s.f_ext.copy_from_slice(&f);
        s.interface_forces();
        s.accelerations();
        Ok(Stepper { s, f })
    }

    /// `k` time steps.
    pub fn run(&mut self, k: usize) {
        let f = &self.f;
        let mut set_ext = |fe: &mut [f64], _: &[f64]| fe.copy_from_slice(f);
        for _ in 0..k {
            self.s.step(&mut set_ext, None);
        }
    }

    pub fn n_interfaces(&self) -> usize {
        self.s.model.interfaces().len()
    }

    pub fn time_step(&self) -> f64 {
        self.s.dt
    }

    /// (u1, u2, phi) of every block, flat.
    pub fn displacements(&self) -> &[f64] {
        &self.s.u
    }

    /// The interface forces (N, T, M) of the last step.
    pub fn interface_forces(&self) -> &[[f64; 3]] {
        &self.s.forces
    }
}

/// Outcome of relaxing one load level.
enum Level {
    Settled,
    RanAway,
    Stopped,
}

/// The state under the dead loads alone found by damped relaxation (local damping 0.8): the
/// displacements and the joint histories, or an error if the wall does not settle. The static
/// solver starts from it where Newton cannot find the dead state from the unloaded wall.
/// A block moving more than 1% of the wall's size (or the wall's motion ceasing to be finite)
/// means the wall does not stand: the relaxation stops there instead of running its step limit.
/// `monitor` is called every 4,096 steps or 0.1 s (return false to stop: `Error::Interrupted`).
pub(crate) fn relax_dead_state(
    model: &Model,
    monitor: &mut dyn FnMut(&Progress) -> bool,
) -> Result<(Vec<f64>, Vec<JointState>), Error> {
    let mut s = Integrator::new(model, None, 0.8, Damping::Local(0.8), 1)?;
    let fd = model.dead_load().to_vec();
    let mut set_ext = |f: &mut [f64], _: &[f64]| f.copy_from_slice(&fd);
    let limit = 1e-2 * model.size();
    let nb = model.n_blocks();
    let max_steps = 2_000_000;
    let mut last = Instant::now();
    for k in 0..max_steps {
        s.step(&mut set_ext, None);
        if k % 16 == 15 {
            if s.unbalanced_ratio(None) <= 1e-7 {
                let states = s.states();
                return Ok((s.u, states));
            }
            let (i, moved) = (0..nb)
                .map(|i| (i, s.u[3 * i].hypot(s.u[3 * i + 1])))
                .fold((0, 0.0), |a, b| if b.1 > a.1 || b.1.is_nan() { b } else { a });
            if !(moved <= limit) {
                return Err(Error::Mechanism(format!(
                    "the wall does not stand under the dead loads alone: {} moves off (explicit relaxation)",
                    model.block_name(i)
                )));
            }
        }
        if monitor_due(k, &mut last) {
            let p = Progress { step: k + 1, multiplier: 0.0, displacement: f64::NAN, fraction: f64::NAN };
            if !monitor(&p) {
                return Err(Error::Interrupted);
            }
        }
    }
    Err(Error::Mechanism(format!("the wall does not settle under the dead loads alone (explicit relaxation, {max_steps} steps)")))
}

/// An equilibrium state with dof `cd` held at `target`, found by damped relaxation (local
/// damping 0.8) from displacements `u` and joint histories `states` (the dofs held after the
/// dead state held too), with lambda from the equation of `cd`: the displacements, the joint
/// histories and lambda. The static solver's displacement control crosses a snap-back with it:
/// where the equilibrium path turns back in the control displacement, no state near the last
/// converged one exists at the next displacement, and the wall jumps (dynamically, in a test)
/// to a state of lower force; the relaxation follows that jump.
pub(crate) fn relax_at_displacement(
    model: &Model,
    u: &[f64],
    states: &[JointState],
    cd: usize,
    target: f64,
) -> Result<(Vec<f64>, Vec<JointState>, f64), Error> {
    let mut s = Integrator::damped_from(model, u, states)?;
    let (fd, fl) = (model.dead_load(), model.live_load());
    if fl[cd] == 0.0 {
        return Err(Error::input("the control dof carries no live load"));
    }
    let lam = std::cell::Cell::new(0.0);
    let mut set_ext = |f: &mut [f64], fint: &[f64]| {
        let l = (fint[cd] - fd[cd]) / fl[cd];
        lam.set(l);
        for d in 0..f.len() {
            f[d] = fd[d] + l * fl[d];
        }
    };
    // bounded: a by-product of one static step (J4D's jumps settle in a few thousand steps)
    let max_steps = 200_000;
    for k in 0..max_steps {
        s.step(&mut set_ext, Some((cd, target)));
        if k % 16 == 15 {
            if s.u.iter().any(|x| !x.is_finite()) {
                break;
            }
            if s.unbalanced_ratio(Some(cd)) <= 1e-7 {
                let states = s.states();
                return Ok((s.u, states, lam.get()));
            }
        }
    }
    Err(Error::Convergence(format!(
        "no equilibrium at the control displacement {target:.4e} m by dynamic relaxation either ({max_steps} steps)"
    )))
}

/// Runs a quasi-static analysis with the explicit solver; same results as the static solver.
pub fn solve(model: &Model, opts: &ExplicitOptions) -> Result<Results, Error> {
    solve_with(model, opts, &mut |_| true)
}

/// As [`solve`], calling `monitor` after each settled level (return false to stop).
pub fn solve_with(model: &Model, opts: &ExplicitOptions, monitor: &mut dyn FnMut(&Progress) -> bool) -> Result<Results, Error> {
    model.check_analysis_memory("an explicit analysis")?;
    model.check_strength_range()?;
    let start = Instant::now();
    check_steps(opts.steps)?;
    if !(opts.tolerance > 0.0 && opts.tolerance < 1.0) {
        return Err(Error::input(format!("analysis.tolerance must lie in (0, 1), got {}", opts.tolerance)));
    }
    if !(opts.unbalanced_ratio > 0.0 && opts.unbalanced_ratio < 1.0) {
        return Err(Error::input(format!("analysis.unbalanced_ratio must lie in (0, 1), got {}", opts.unbalanced_ratio)));
    }
    if opts.max_steps_per_level == 0 {
        return Err(Error::input("max_steps_per_level must be at least 1"));
    }
    model.check_supports()?;
    let nb = model.n_blocks();
    let control_block = opts.control_block.unwrap_or_else(|| model.default_control_block());
    if control_block >= nb {
        return Err(Error::input(format!("control block {control_block} does not exist (the model has {nb} blocks)")));
    }
    let cd = 3 * control_block;
    if let QsControl::Displacement { max_displacement } = opts.control {
        if !(max_displacement.is_finite() && max_displacement != 0.0) {
            return Err(Error::input(format!("analysis.max_displacement must be a finite non-zero length, got {max_displacement}")));
        }
        if model.fixed()[cd] || model.live_load()[cd] == 0.0 {
            return Err(Error::input(format!(
                "the control block ({}) must be free to move horizontally and carry live load",
                model.block_name(control_block)
            )));
        }
    }
    let mut s = Integrator::new(model, opts.time_step, opts.safety, opts.damping, opts.threads)?;
    let size = model.size();
    let mut curve_l = vec![];
    let mut curve_u = vec![];
    let fd = model.dead_load().to_vec();
    let fl = model.live_load().to_vec();

    // relax at multiplier `lam` (or, with `drive`, with the control dof held at a value and
    // lambda from its equation); the run counts as running away when a block moves more than
    // `u_fail` from the start of the level
    let relax = |s: &mut Integrator,
                 lam: &mut f64,
                 drive: Option<f64>,
                 u_fail: f64,
                 monitor: &mut dyn FnMut(&Progress) -> bool|
     -> Level {
        let u0 = s.u.clone();
        let lam_cell = std::cell::Cell::new(*lam);
        let mut set_ext = |f: &mut [f64], fint: &[f64]| {
            if drive.is_some() {
                lam_cell.set((fint[cd] - fd[cd]) / fl[cd]);
            }
            let l = lam_cell.get();
            for d in 0..f.len() {
                f[d] = fd[d] + l * fl[d];
            }
        };
        let mut last = Instant::now();
        for k in 0..opts.max_steps_per_level {
            s.step(&mut set_ext, drive.map(|x| (cd, x)));
            *lam = lam_cell.get();
            if k % 16 == 15 {
                if s.unbalanced_ratio(drive.map(|_| cd)) <= opts.unbalanced_ratio {
                    return Level::Settled;
                }
                let moved = (0..nb).map(|i| (s.u[3 * i] - u0[3 * i]).hypot(s.u[3 * i + 1] - u0[3 * i + 1])).fold(0.0, f64::max);
                if moved > u_fail || !moved.is_finite() {
                    return Level::RanAway;
                }
            }
            if monitor_due(k, &mut last) {
                let p = Progress { step: s.steps, multiplier: *lam, displacement: s.u[cd], fraction: f64::NAN };
                if !monitor(&p) {
                    return Level::Stopped;
                }
            }
        }
        Level::RanAway
    };

    // dead load
    let mut lam = 0.0;
    let steps_before = s.steps;
    let u_fail0 = 1e-2 * size;
    match relax(&mut s, &mut lam, None, u_fail0, monitor) {
        Level::Settled => {}
        Level::Stopped => return Ok(finish(model, s, Status::Failed, Some(Error::Interrupted), curve_l, curve_u, None, control_block, start)),
        Level::RanAway => {
            let e = Error::Mechanism("no equilibrium under the dead loads alone (the wall does not settle)".into());
            return Ok(finish(model, s, Status::Failed, Some(e), curve_l, curve_u, None, control_block, start));
        }
    }
    let dead_steps = s.steps - steps_before;
    s.v.fill(0.0);
    s.hold();
    curve_l.push(0.0);
    curve_u.push(s.u[cd]);
    // displacements beyond 20 x the settlement under dead load (at least 1e-4 of the wall) are
    // a running mechanism, not an elastic response
    let settle = (0..nb).map(|i| s.u[3 * i].hypot(s.u[3 * i + 1])).fold(0.0, f64::max);
    let u_fail = (20.0 * settle).max(1e-4 * size);
    let save = |s: &Integrator| (s.u.clone(), s.hist.clone(), s.broken.clone());
    let restore = |s: &mut Integrator, st: &(Vec<f64>, Vec<f64>, Vec<bool>)| {
        s.u.copy_from_slice(&st.0);
        s.hist.copy_from_slice(&st.1);
        s.broken.copy_from_slice(&st.2);
        s.v.fill(0.0);
        s.a.fill(0.0);
    };
    match opts.control {
        QsControl::Load => {
            let scale = match model.live() {
                LiveLoad::HorizontalWeight => 1.0,
                LiveLoad::TopHorizontal => (model.weight().iter().sum::<f64>() + fd.iter().map(|x| x.abs()).sum::<f64>()).max(1.0),
            };
            let mut dl = 4.0 * scale / opts.steps as f64;
            let mut lam_conv = 0.0;
            let mut saved = save(&s);
            let mut mechanism = None;
            let max_levels = 100 * opts.steps + 1000;
            for _ in 0..max_levels {
                let mut l = lam_conv + dl;
                match relax(&mut s, &mut l, None, u_fail, monitor) {
                    Level::Settled => {
                        lam_conv = l;
                        saved = save(&s);
                        s.v.fill(0.0);
                        curve_l.push(l);
                        curve_u.push(s.u[cd]);
                        let p = Progress { step: s.steps, multiplier: l, displacement: s.u[cd], fraction: f64::NAN };
                        if !monitor(&p) {
                            return Ok(finish(model, s, Status::Failed, Some(Error::Interrupted), curve_l, curve_u, None, control_block, start));
                        }
                        if lam_conv > 1e3 * scale {
                            let e = Error::Convergence(crate::results::unbounded_message(lam_conv));
                            return Ok(finish(model, s, Status::Unbounded, Some(e), curve_l, curve_u, None, control_block, start));
                        }
                    }
                    Level::Stopped => {
                        restore(&mut s, &saved);
                        return Ok(finish(model, s, Status::Failed, Some(Error::Interrupted), curve_l, curve_u, None, control_block, start));
                    }
                    Level::RanAway => {
                        mechanism = Some(s.u.iter().zip(&saved.0).map(|(a, b)| a - b).collect::<Vec<f64>>());
                        restore(&mut s, &saved);
                        dl *= 0.5;
                        if 2.0 * dl <= opts.tolerance * lam_conv.abs().max(1e-3 * scale) {
                            s.interface_forces();
                            return Ok(finish(model, s, Status::Collapse, None, curve_l, curve_u, mechanism, control_block, start));
                        }
                    }
                }
            }
            let e = Error::Convergence(format!("no collapse bracket after {max_levels} load levels"));
            Ok(finish(model, s, Status::Failed, Some(e), curve_l, curve_u, mechanism, control_block, start))
        }
        QsControl::Displacement { max_displacement } => {
            let u_start = s.u[cd];
            let stages = opts.steps;
            let mut prev = save(&s);
            for k in 1..=stages {
                let target = u_start + max_displacement * k as f64 / stages as f64;
                // drive the control dof there over a few hundred steps, then relax holding it
                let from = s.u[cd];
                // slowly, over five times the dead state's settling time: a fast drive makes the
                // control block slip locally against the inertia of the rest of the wall (wall 1:
                // peak 0.595 over 200 steps, 0.635 over 2,000, 0.641 over 10,000)
                let n_drive = (5 * dead_steps).max(200);
                let mut set_ext = |f: &mut [f64], fint: &[f64]| {
                    lam = (fint[cd] - fd[cd]) / fl[cd];
                    for d in 0..f.len() {
                        f[d] = fd[d] + lam * fl[d];
                    }
                };
                for j in 1..=n_drive {
                    let x = from + (target - from) * j as f64 / n_drive as f64;
                    s.step(&mut set_ext, Some((cd, x)));
                }
                match relax(&mut s, &mut lam, Some(target), f64::INFINITY, monitor) {
                    Level::Settled | Level::RanAway => {}
                    Level::Stopped => {
                        return Ok(finish(model, s, Status::Failed, Some(Error::Interrupted), curve_l, curve_u, None, control_block, start))
                    }
                }
                let mech: Vec<f64> = s.u.iter().zip(&prev.0).map(|(a, b)| a - b).collect();
                prev = save(&s);
                curve_l.push(lam);
                curve_u.push(s.u[cd]);
                let p = Progress { step: s.steps, multiplier: lam, displacement: s.u[cd], fraction: k as f64 / stages as f64 };
                if !monitor(&p) {
                    return Ok(finish(model, s, Status::Failed, Some(Error::Interrupted), curve_l, curve_u, Some(mech), control_block, start));
                }
                if k == stages {
                    let peak = crate::results::peak(&curve_l);
                    let n = curve_l.len();
                    let k0 = (curve_l[1] - curve_l[0]) / (curve_u[1] - curve_u[0]);
                    let kl = (curve_l[n - 1] - curve_l[n - 2]) / (curve_u[n - 1] - curve_u[n - 2]);
                    let collapsed = lam.abs() < peak.abs() * (1.0 - 1e-3) || (kl / k0).abs() < 1e-2;
                    let status = if collapsed { Status::Collapse } else { Status::Completed };
                    return Ok(finish(model, s, status, None, curve_l, curve_u, Some(mech), control_block, start));
                }
            }
            unreachable!("the loop returns at its last stage")
        }
    }
}

#[allow(clippy::too_many_arguments)]
fn finish(
    model: &Model,
    s: Integrator,
    status: Status,
    err: Option<Error>,
    curve_l: Vec<f64>,
    curve_u: Vec<f64>,
    mechanism: Option<Vec<f64>>,
    control_block: usize,
    start: Instant,
) -> Results {
    let nb = model.n_blocks();
    let curve_l_len = curve_l.len();
    let mech = mechanism.unwrap_or_else(|| vec![0.0; 3 * nb]);
    let scale = (0..nb).map(|i| mech[3 * i].hypot(mech[3 * i + 1])).fold(0.0, f64::max);
    let work: f64 = mech.iter().zip(model.live_load()).map(|(v, f)| v * f).sum();
    let scale = if scale > 0.0 { work.signum() / scale } else { 0.0 };
    // the largest lambda at which the wall settled; a collapse multiplier only with a collapse
    let last_equilibrium = crate::results::peak(&curve_l);
    let collapse_multiplier = if status == Status::Collapse { last_equilibrium } else { f64::NAN };
    Results {
        method: "dynamic",
        status,
        error: err.map(|e| e.to_string()),
        collapse_multiplier,
        last_equilibrium,
        curve_multiplier: curve_l,
        curve_displacement: curve_u,
        control_block,
        displacements: (0..nb).map(|i| [s.u[3 * i], s.u[3 * i + 1], s.u[3 * i + 2]]).collect(),
        mechanism: (0..nb).map(|i| [mech[3 * i] * scale, mech[3 * i + 1] * scale, mech[3 * i + 2] * scale]).collect(),
        interface_forces: s.forces,
        interface_states: s.flags,
        broken: s.broken,
        iterations: s.steps,
        steps: curve_l_len,
        elapsed_s: start.elapsed().as_secs_f64(),
        certificate: None,
    }
}

/// Integrates the equations of motion in time (free motion, base acceleration).
pub fn simulate(model: &Model, opts: &DynamicOptions) -> Result<TimeHistory, Error> {
    simulate_with(model, opts, &mut |_| true)
}

/// As [`simulate`], calling `monitor` every few thousand steps (return false to stop).
pub fn simulate_with(model: &Model, opts: &DynamicOptions, monitor: &mut dyn FnMut(&Progress) -> bool) -> Result<TimeHistory, Error> {
    model.check_analysis_memory("a time history")?;
    let start = Instant::now();
    if !(opts.duration.is_finite() && opts.duration > 0.0) {
        return Err(Error::input(format!("duration must be a finite number > 0, got {}", opts.duration)));
    }
    if opts.record_every == 0 {
        return Err(Error::input("record_every must be at least 1"));
    }
    if !opts.live_multiplier.is_finite() {
        return Err(Error::input("live_multiplier must be finite"));
    }
    let nb = model.n_blocks();
    if let Some((t, a)) = &opts.base_acceleration {
        if t.len() != a.len() || t.is_empty() {
            return Err(Error::input(format!(
                "base_acceleration: times and accelerations must be non-empty and of equal length (got {} and {})",
                t.len(),
                a.len()
            )));
        }
        if t.iter().chain(a).any(|x| !x.is_finite()) || t.windows(2).any(|w| w[1] <= w[0]) {
            return Err(Error::input("base_acceleration: times must increase and every value must be finite"));
        }
    }
    for (what, init) in [("initial_displacement", &opts.initial_displacement), ("initial_velocity", &opts.initial_velocity)] {
        if let Some(v) = init {
            if v.len() != nb {
                return Err(Error::input(format!("{what}: expected {nb} rows (one per block), got {}", v.len())));
            }
            if v.iter().flatten().any(|x| !x.is_finite()) {
                return Err(Error::input(format!("{what}: every value must be finite")));
            }
        }
    }
    model.check_supports()?;
    if !model.held_after_dead().is_empty() {
        return Err(Error::input(
            "top.vertical = \"held\" is for quasi-static analyses (held once the dead loads are on); a time history loads the beam with its force: use top.vertical = \"free\"",
        ));
    }
    let mut s = Integrator::new(model, opts.time_step, opts.safety, opts.damping, opts.threads)?;
    s.set_large(opts.large_rotations);
    let fixed = model.fixed();
    if let Some(u0) = &opts.initial_displacement {
        for i in 0..nb {
            for k in 0..3 {
                if !fixed[3 * i + k] {
                    s.u[3 * i + k] = u0[i][k];
                }
            }
        }
    }
    if let Some(v0) = &opts.initial_velocity {
        for i in 0..nb {
            for k in 0..3 {
                if !fixed[3 * i + k] {
                    s.v[3 * i + k] = v0[i][k];
                }
            }
        }
    }
    let fd = model.dead_load().to_vec();
    let fl = model.live_load().to_vec();
    let lam = opts.live_multiplier;
    let mass = s.mass.clone();
    let base = opts.base_acceleration.clone();
    let ag = move |t: f64| -> f64 {
        match &base {
            None => 0.0,
            Some((ts, a)) => {
                if t < ts[0] || t > ts[ts.len() - 1] {
                    return 0.0;
                }
                let k = ts.partition_point(|&x| x <= t).clamp(1, ts.len() - 1);
                let (t0, t1) = (ts[k - 1], ts[k]);
                a[k - 1] + (a[k] - a[k - 1]) * (t - t0) / (t1 - t0)
            }
        }
    };
    let ext = |f: &mut [f64], t: f64| {
        let g = ag(t);
        for d in 0..f.len() {
            f[d] = fd[d] + lam * fl[d] - if d % 3 == 0 { mass[d] * g } else { 0.0 };
        }
    };
    ext(&mut s.f_ext, 0.0);
    s.interface_forces();
    s.accelerations();
    let n_steps_f = (opts.duration / s.dt).ceil();
    if !(n_steps_f <= MAX_TIME_STEPS as f64) {
        return Err(Error::input(format!(
            "duration = {} s with a time step of {:.3e} s is {n_steps_f:.0} time steps, more than the limit of {MAX_TIME_STEPS}",
            opts.duration, s.dt
        )));
    }
    let n_steps = n_steps_f as usize;
    let cap = n_steps / opts.record_every + 2;
    // two histories (displacements, velocities) of 3 values per block and record
    let stored = 6.0 * cap as f64 * nb as f64;
    if stored > MAX_RECORDED_VALUES as f64 {
        return Err(Error::input(format!(
            "recording {cap} states of {nb} blocks (duration {} s, time step {:.3e} s, record_every {}) stores {stored:.0} numbers, more than the limit of {MAX_RECORDED_VALUES}: raise record_every or shorten the duration",
            opts.duration, s.dt, opts.record_every
        )));
    }
    let mut h = TimeHistory {
        status: Status::Completed,
        error: None,
        time_step: s.dt,
        times: Vec::with_capacity(cap),
        n_blocks: nb,
        // reserved once: recording does not allocate inside the time loop
        displacements: Vec::with_capacity(cap * nb),
        velocities: Vec::with_capacity(cap * nb),
        kinetic_energy: Vec::with_capacity(cap),
        elastic_energy: Vec::with_capacity(cap),
        external_work: Vec::with_capacity(cap),
        dissipated: Vec::with_capacity(cap),
        steps: 0,
        elapsed_s: 0.0,
    };
    // work of the external forces, by the trapezoidal rule on each step
    let mut work = 0.0;
    let mut f_prev = s.f_ext.clone();
    let mut u_prev = s.u.clone();
    let record = |h: &mut TimeHistory, s: &Integrator, t: f64, work: f64| {
        h.times.push(t);
        h.displacements.extend((0..nb).map(|i| [s.u[3 * i], s.u[3 * i + 1], s.u[3 * i + 2]]));
        h.velocities.extend((0..nb).map(|i| [s.v[3 * i], s.v[3 * i + 1], s.v[3 * i + 2]]));
        let ke = s.kinetic_energy();
        let ee = s.elastic_energy();
        h.kinetic_energy.push(ke);
        h.elastic_energy.push(ee);
        h.external_work.push(work);
        h.dissipated.push(work - ke - ee);
    };
    record(&mut h, &s, 0.0, 0.0);
    let mut last = Instant::now();
    for n in 1..=n_steps {
        let t = n as f64 * s.dt;
        let mut set_ext = |f: &mut [f64], _: &[f64]| ext(f, t);
        s.step(&mut set_ext, None);
        for d in 0..s.u.len() {
            work += 0.5 * (s.f_ext[d] + f_prev[d]) * (s.u[d] - u_prev[d]);
        }
        f_prev.copy_from_slice(&s.f_ext);
        u_prev.copy_from_slice(&s.u);
        if s.u.iter().any(|x| !x.is_finite()) {
            h.status = Status::Failed;
            h.error = Some(format!("non-finite displacement at t = {t:.6} s (step {n})"));
            break;
        }
        if n % opts.record_every == 0 || n == n_steps {
            record(&mut h, &s, t, work);
        }
        if monitor_due(n - 1, &mut last) {
            let p = Progress { step: n, multiplier: lam, displacement: f64::NAN, fraction: n as f64 / n_steps as f64 };
            if !monitor(&p) {
                h.status = Status::Failed;
                h.error = Some(Error::Interrupted.to_string());
                break;
            }
        }
    }
    h.steps = s.steps;
    h.elapsed_s = start.elapsed().as_secs_f64();
    Ok(h)
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)] // matrices with their indices, as in the formulas
mod tests {
    use super::*;
    use crate::geometry::{running_bond, FirstCourse, Rect, RunningBond};
    use crate::model::ModelSpec;

    #[test]
    fn prepared_kinds_change_no_result() {
        // a stack of blocks of 300 widths: more kinds than the table holds
        let stack: Vec<Rect> = (0..300)
            .map(|i| {
                let (w, y) = (0.4 + 1e-3 * i as f64, 0.1 * i as f64);
                Rect::new(-0.5 * w, y, 0.5 * w, y + 0.1)
            })
            .collect();
        let wall = running_bond(&RunningBond {
            block_length: 0.4,
            block_height: 0.175,
            courses: 6,
            length: 2.0,
            first_course: FirstCourse::Half,
            openings: vec![],
        })
        .unwrap();
        for (blocks, overflow) in [(stack, true), (wall, false)] {
            let model = Model::new(ModelSpec { blocks, ..ModelSpec::default() }).unwrap();
            for large in [false, true] {
                // under a horizontal load that makes joints slide and open
                let run = |prepared: bool| {
                    let mut s = Stepper::new(&model, 0.4, Damping::Local(0.8), large, 1).unwrap();
                    assert_eq!(s.s.shapes.iter().any(|g| g.kind == Kinds::NONE), overflow);
                    assert_eq!(s.s.kinds.len() == Kinds::MAX, overflow);
                    if !prepared {
                        s.s.kinds = Kinds::default();
                    }
                    s.run(400);
                    let u: Vec<u64> = s.displacements().iter().map(|x| x.to_bits()).collect();
                    let f: Vec<u64> = s.interface_forces().iter().flatten().map(|x| x.to_bits()).collect();
                    assert!(s.s.flags.iter().any(|&fl| fl != 0), "no joint reached its strength");
                    (u, f)
                };
                assert!(run(true) == run(false), "{} blocks, large rotations {large}", model.n_blocks());
            }
        }
    }

    #[test]
    fn parts_change_no_result() {
        // a wall with an opening, under a horizontal load that makes joints slide and open
        let blocks = running_bond(&RunningBond {
            block_length: 0.4,
            block_height: 0.175,
            courses: 8,
            length: 3.0,
            first_course: FirstCourse::Half,
            openings: vec![Rect::new(1.0, 0.4, 1.8, 1.0)],
        })
        .unwrap();
        let model = Model::new(ModelSpec { blocks, ..ModelSpec::default() }).unwrap();
        for large in [false, true] {
            // the pass in `n_parts` parts, on the pool if `par` (whatever the wall's size)
            let run = |n_parts: usize, par: bool| {
                let mut s = Stepper::new(&model, 0.4, Damping::Local(0.8), large, 2).unwrap();
                s.s.set_parts(n_parts);
                assert_eq!(s.s.straddlers.blocks.is_empty(), n_parts == 1);
                s.s.par = par;
                s.run(300);
                let u: Vec<u64> = s.displacements().iter().map(|x| x.to_bits()).collect();
                let f: Vec<u64> = s.interface_forces().iter().flatten().map(|x| x.to_bits()).collect();
                (u, f)
            };
            let one = run(1, false);
            for (n_parts, par) in [(3, false), (3, true), (8, true), (40, true), (1000, true)] {
                assert!(run(n_parts, par) == one, "{n_parts} parts, on the pool {par}, large rotations {large}");
            }
        }
    }

    #[test]
    fn packed_geometry_rebuilds_b_bit_for_bit() {
        let blocks = running_bond(&RunningBond {
            block_length: 0.4,
            block_height: 0.175,
            courses: 5,
            length: 2.0,
            first_course: FirstCourse::Half,
            openings: vec![],
        })
        .unwrap();
        let model = Model::new(ModelSpec { blocks, ..ModelSpec::default() }).unwrap();
        for it in model.interfaces() {
            let b = Shape::new(it, 0).b_mat();
            for r in 0..3 {
                for j in 0..6 {
                    assert_eq!(b[r][j].to_bits(), it.b_mat[r][j].to_bits(), "{it:?} B[{r}][{j}]");
                }
            }
        }
    }
}
