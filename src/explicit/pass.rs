//! The interface pass, the hot path: the blocks' geometry packed per interface, the joint
//! law applied to each interface's jumps, and the force sums of the blocks, in parts run on
//! rayon (each part writes only its own interfaces' slots and the sums of its own blocks).

use super::*;

/// Blocks per task of the block passes: a few hundred microseconds of work per task at most,
/// about a hundred tasks at 10^5 blocks.
pub(super) const GRAIN_BLOCKS: usize = 1024;
/// Below this many interfaces a step runs on one thread whatever is asked: the two hand-offs to
/// the pool per step (some 10-20 us each) cost more than the second thread gives back.
pub(super) const PAR_MIN_INTERFACES: usize = 2048;
/// Interfaces per part of the interface pass on the pool (at least two parts per thread).
pub(super) const PART_INTERFACES: usize = 32768;

/// What the interface loop reads of an interface, packed in 12 bytes (the model's
/// [`crate::interface::Interface`] takes 208): the two blocks, each with a bit that tells if
/// the interface loop sums the block's forces (see [`Integrator::parts`]), and the index of
/// its [`Shape`] in the integrator's table of the distinct shapes (a few thousand on a wall of
/// 10^5 blocks: its interfaces repeat a handful of lever arms, normals, families and sections).
#[derive(Debug, Clone, Copy)]
pub(super) struct Geo {
    pub(super) a: u32,
    pub(super) b: u32,
    pub(super) shape: u32,
}

/// The bit of [`Geo::a`] and [`Geo::b`] set when the interface loop sums the block's forces.
pub(super) const SUMMED: u32 = 1 << 31;
/// The block's index in [`Geo::a`] and [`Geo::b`].
pub(super) const BLOCK: u32 = SUMMED - 1;

impl Geo {
    #[inline(always)]
    pub(super) fn a(&self) -> usize {
        (self.a & BLOCK) as usize
    }
    #[inline(always)]
    pub(super) fn b(&self) -> usize {
        (self.b & BLOCK) as usize
    }
}

/// What interfaces of one shape share: the four entries of `B` that are not +-n, +-t or +-1,
/// the normal, the family and the kind (an index into the integrator's table of the distinct
/// pairs of law and section). `B`'s rows are (-n, -n.ra, n, n.rb), (-t, -t.ra, t, t.rb) and
/// (0, 0, -1, 0, 0, 1), with t = (n_y, -n_x); [`Shape::b_mat`] rebuilds them bit for bit.
#[derive(Debug, Clone, Copy)]
pub(super) struct Shape {
    /// b_mat[0][2], b_mat[0][5], b_mat[1][2], b_mat[1][5]
    pub(super) r: [f64; 4],
    pub(super) n: [f64; 2],
    /// [`Kinds::NONE`] for an interface whose kind did not fit in the table
    pub(super) kind: u16,
    pub(super) family: u8,
}

impl Shape {
    /// The shape of `it`, of kind `kind` (bit for bit).
    pub(super) fn new(it: &Interface, kind: u16) -> Self {
        let b = &it.b_mat;
        Shape { r: [b[0][2], b[0][5], b[1][2], b[1][5]], n: it.n, kind, family: family_index(it.family) }
    }

    /// The bits that tell two shapes apart.
    pub(super) fn key(&self) -> ([u64; 4], [u64; 2], u16, u8) {
        (self.r.map(f64::to_bits), self.n.map(f64::to_bits), self.kind, self.family)
    }

    /// The generalized forces `B^T s` on side `sb` (0: block a, 1: block b) of an interface
    /// of this shape carrying `s` = (N, T, M): the side's three columns of `B` (see
    /// [`Shape::b_mat`]), picked without a branch, (-+n0, -+n1, 0), (-+n1, +-n0, 0) and
    /// (r, r', -+1), each dotted with `s` (a product by -1 is the negation: the same numbers).
    #[inline(always)]
    pub(super) fn side_force(&self, s: &[f64; 3], sb: usize) -> [f64; 3] {
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
    pub(super) fn side_sums(&self, s: &[f64; 3]) -> [[f64; 3]; 2] {
        if !s[2].is_finite() {
            return [self.side_force(s, 0), self.side_force(s, 1)];
        }
        let ([n0, n1], r) = (self.n, &self.r);
        let t = [n0 * s[0] + n1 * s[1], n1 * s[0] - n0 * s[1]];
        [[-t[0], -t[1], r[0] * s[0] + r[2] * s[1] - s[2]], [t[0], t[1], r[1] * s[0] + r[3] * s[1] + s[2]]]
    }

    #[inline(always)]
    pub(super) fn b_mat(&self) -> [[f64; 6]; 3] {
        let ([n0, n1], r) = (self.n, self.r);
        [[-n0, -n1, r[0], n0, n1, r[1]], [-n1, n0, r[2], n1, -n0, r[3]], [0.0, 0.0, -1.0, 0.0, 0.0, 1.0]]
    }
}

/// The return mapping of an interface whose kind is not in the table (out of line: the loop
/// keeps one inlined copy, for the table's kinds).
#[inline(never)]
pub(super) fn map_unprepared(law: &JointLaw, sec: &Section, e: [f64; 3], st: &JointState, warm: u8) -> (Response, u8) {
    return_map_inlined(law, sec, e, st, &MapOptions { warm, tangent: false, ..MapOptions::default() })
}

/// A committed joint history from its packed form (`h`: the plastic jumps, then the opening and
/// the slip if stored; not stored they are zero, which no law that does not soften reads).
#[inline(always)]
pub(super) fn unpack(h: &[f64], broken: bool) -> JointState {
    let (opening, slip) = if h.len() == 5 { (h[3], h[4]) } else { (0.0, 0.0) };
    JointState { plastic: [h[0], h[1], h[2]], broken, opening, slip }
}

/// The packed form of a history (see [`unpack`]).
#[inline(always)]
pub(super) fn pack(st: &JointState, h: &mut [f64]) {
    h[..3].copy_from_slice(&st.plastic);
    if h.len() == 5 {
        h[3] = st.opening;
        h[4] = st.slip;
    }
}

/// What a time history keeps of an interface besides its joint history: the jumps of the last
/// step (their increment gives the rates of the dashpot), the contact dashpot (see
/// [`super::contact`]) and the energy it dissipated.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Dyn {
    /// the jumps, the slip without the slip point's term (see [`Pass::dynamics`])
    pub(super) jumps: [f64; 3],
    /// cos of the relative rotation (finite rotations)
    pub(super) cos: f64,
    /// c_N, c_T, c_M of the dashpot (zero: none)
    pub(super) c: [f64; 3],
    /// half the interface's length \[m\]
    pub(super) half: f64,
    /// the dashpot's force at the last step (its work over a step is trapezoidal, as the
    /// integrator's work of every force)
    pub(super) force: [f64; 3],
    /// the share of each dashpot that models impacts (the rest is stiffness-proportional damping)
    pub(super) share: [f64; 3],
    /// energy dissipated by the dashpots' impact share \[J\]
    pub(super) damped: f64,
    /// energy dissipated by their stiffness-proportional share \[J\]
    pub(super) stiffness_damped: f64,
}

/// A part of the interface pass: the interfaces from `k0` (their histories, forces, flags,
/// warm sets and, in a time history, their [`Dyn`]), the force sums of the blocks from `b0`,
/// and the terms from `t0`.
pub(super) struct Part<'s> {
    pub(super) k0: usize,
    pub(super) b0: usize,
    pub(super) t0: usize,
    pub(super) hist: &'s mut [f64],
    pub(super) broken: &'s mut [bool],
    pub(super) forces: &'s mut [[f64; 3]],
    pub(super) flags: &'s mut [u8],
    pub(super) warm: &'s mut [u8],
    /// empty outside time histories
    pub(super) dynm: &'s mut [Dyn],
    /// the forces on the blocks whose sums the pass does not form, in the order of
    /// [`Straddlers::slots`]
    pub(super) terms: &'s mut [[f64; 3]],
    pub(super) f_int: &'s mut [f64],
}

impl<'s> Part<'s> {
    /// The part before interface `k`, block `blk` and term `t`, and the part from them.
    pub(super) fn split(self, (k, blk, t): (usize, usize, usize), hw: usize) -> (Part<'s>, Part<'s>) {
        let (kk, bb) = (k - self.k0, blk - self.b0);
        let (h0, h1) = self.hist.split_at_mut(hw * kk);
        let (br0, br1) = self.broken.split_at_mut(kk);
        let (f0, f1) = self.forces.split_at_mut(kk);
        let (fl0, fl1) = self.flags.split_at_mut(kk);
        let (w0, w1) = self.warm.split_at_mut(kk);
        let (d0, d1) = self.dynm.split_at_mut(kk.min(self.dynm.len()));
        let (t0, t1) = self.terms.split_at_mut(t - self.t0);
        let (s0, s1) = self.f_int.split_at_mut(3 * bb);
        (
            Part { k0: self.k0, b0: self.b0, t0: self.t0, hist: h0, broken: br0, forces: f0, flags: fl0, warm: w0, dynm: d0, terms: t0, f_int: s0 },
            Part { k0: k, b0: blk, t0: t, hist: h1, broken: br1, forces: f1, flags: fl1, warm: w1, dynm: d1, terms: t1, f_int: s1 },
        )
    }
}

/// Runs `work` on the parts of `p` cut at `bounds` (interface, block, term; the first and the last
/// are `p`'s own start and end), in parallel on the current rayon pool.
pub(super) fn run_parts<F: Fn(Part) + Sync>(p: Part, bounds: &[(usize, usize, usize)], hw: usize, work: &F) {
    if bounds.len() <= 2 {
        work(p);
    } else {
        let mid = bounds.len() / 2;
        let (l, r) = p.split(bounds[mid], hw);
        rayon::join(|| run_parts(l, &bounds[..=mid], hw, work), || run_parts(r, &bounds[mid..], hw, work));
    }
}

/// What the parts of the interface pass read.
pub(super) struct Pass<'a> {
    /// each interface's section (the model's, and those of the contacts the update found)
    pub(super) sections: &'a [Section],
    /// with finite rotations only: where each interface lies on its blocks
    pub(super) arms: &'a [Arm],
    pub(super) u: &'a [f64],
    pub(super) geo: &'a [Geo],
    pub(super) shapes: &'a [Shape],
    pub(super) laws: &'a [JointLaw; 4],
    pub(super) kinds: &'a Kinds,
    /// with finite rotations only: the blocks' reference centroids and (cos, sin) of their
    /// rotations
    pub(super) centroids: &'a [[f64; 2]],
    pub(super) cs: &'a [[f64; 2]],
    /// the time step \[s\] (the rates of the dashpots)
    pub(super) dt: f64,
    /// the first pass of a time history: its [`Dyn`] take the jumps, and nothing is damped
    pub(super) prime: bool,
}

impl Pass<'_> {
    /// The return mapping of interface `k` of shape `gk` for the jumps `e`, with its kind's
    /// constants, its results stored (each arm stores its own: no copy of the response
    /// between them); inlined in the loop of [`Pass::part`].
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(super) fn update(&self, k: usize, gk: &Shape, e: [f64; 3], h: &mut [f64], br: &mut bool, f: &mut [f64; 3], fl: &mut u8, ws: &mut u8) {
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
            Some((sec, prep)) => store(return_map_inlined(law, sec, e, st, &MapOptions { prepared: Some(prep), warm: *ws, strict: false, tangent: false }), h, br, f, fl, ws),
            None => store(map_unprepared(law, &self.sections[k], e, st, *ws), h, br, f, fl, ws),
        }
    }

    /// The interface pass over part `p`, with histories of `HW` numbers and finite rotations
    /// if `LARGE` (one copy of the loop for each).
    pub(super) fn part<const HW: usize, const LARGE: bool>(&self, p: Part) {
        let Part { k0, b0, hist, broken, forces, flags, warm, dynm, terms, f_int, .. } = p;
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
                let arm = &self.arms[k];
                let (a, b, g, cs) = (ik.a(), ik.b(), self.centroids, self.cs);
                // the normal force's eccentricity at the previous step, within the interface
                let ecc = if f[0] < 0.0 { (f[2] / f[0]).clamp(-0.5 * arm.l, 0.5 * arm.l) } else { 0.0 };
                let kin = arm.large_kinematics(g[a], g[b], &u[3 * a..3 * a + 3], &u[3 * b..3 * b + 3], cs[a], cs[b], ecc);
                self.update(k, gk, kin.jumps, h, br, f, fl, ws);
                let total = self.dynamics(dynm.get_mut(i), gk, kin.jumps, (kin.e, kin.rel[0]), *f);
                let x = kin.forces(total);
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
                let total = self.dynamics(dynm.get_mut(i), gk, e, (0.0, 1.0), *f);
                let [xa, xb] = gk.side_sums(&total);
                sum(ik.a, a, xa);
                sum(ik.b, b, xb);
            }
        }
    }

    /// In a time history (`dy` given): the contact dashpot's force and dissipation over the
    /// jumps' increment up to `e`; the force on the blocks, the law's `f` plus the dashpot's.
    /// Outside time histories, `f`. With finite rotations the slip holds the slip point's term
    /// `ecc (cos - 1)` ([`crate::interface::Arm::large_kinematics`]), whose eccentricity
    /// follows the force of the last step: its increment is taken at this step's eccentricity
    /// (`(ecc, cos)`), so that a change of the eccentricity is not a slip.
    #[inline(always)]
    pub(super) fn dynamics(&self, dy: Option<&mut Dyn>, gk: &Shape, e: [f64; 3], (ecc, cos): (f64, f64), f: [f64; 3]) -> [f64; 3] {
        let Some(dy) = dy else { return f };
        let raw = [e[0], e[1] - ecc * (cos - 1.0), e[2]];
        if self.prime {
            (dy.jumps, dy.cos) = (raw, cos);
            return f;
        }
        let de = [raw[0] - dy.jumps[0], raw[1] - dy.jumps[1] + ecc * (cos - dy.cos), raw[2] - dy.jumps[2]];
        (dy.jumps, dy.cos) = (raw, cos);
        if dy.c == [0.0; 3] {
            return f;
        }
        let inv = 1.0 / self.dt;
        let mu = self.laws[gk.family as usize].friction;
        let d = super::contact::dashpot(&dy.c, dy.half, mu, [de[0] * inv, de[1] * inv, de[2] * inv], f);
        let p = dy.force;
        dy.force = d;
        let w = [0.5 * (p[0] + d[0]) * de[0], 0.5 * (p[1] + d[1]) * de[1], 0.5 * (p[2] + d[2]) * de[2]];
        let impacts = dy.share[0] * w[0] + dy.share[1] * w[1] + dy.share[2] * w[2];
        dy.damped += impacts;
        dy.stiffness_damped += w[0] + w[1] + w[2] - impacts;
        [f[0] + d[0], f[1] + d[1], f[2] + d[2]]
    }

    /// [`Pass::part`] for `hw` and `large`.
    pub(super) fn run(&self, p: Part, hw: usize, large: bool) {
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
pub(super) struct Straddlers {
    pub(super) blocks: Vec<u32>,
    pub(super) start: Vec<u32>,
    pub(super) slots: Vec<u32>,
}

/// The interface pass in `n_parts` parts of about as many interfaces (see
/// [`Integrator::parts`]), the blocks whose forces the pass sums marked [`SUMMED`] in `geo`,
/// and the others. Any order of the interfaces gives the same sums; the model's, by block a,
/// makes most blocks' interfaces fall in one part.
pub(super) fn partition(nb: usize, geo: &mut [Geo], n_parts: usize) -> (Vec<(usize, usize, usize)>, Straddlers) {
    let mut parts = part_bounds(nb, geo, n_parts);
    let summed = mark_summed(nb, geo, &parts);
    let straddlers = straddlers(nb, geo, &summed, &mut parts);
    (parts, straddlers)
}

/// Where the `n_parts` parts start (clamped to one per interface at most), with an end after
/// the last: each part's first interface and first block (the blocks from its first
/// interface's a on); the terms' starts are left zero for [`straddlers`].
fn part_bounds(nb: usize, geo: &[Geo], n_parts: usize) -> Vec<(usize, usize, usize)> {
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
    parts
}

/// Which blocks have all their interfaces in the part that owns them (or none at all): the
/// pass sums their forces itself, and they are marked [`SUMMED`] on both sides in `geo`.
fn mark_summed(nb: usize, geo: &mut [Geo], parts: &[(usize, usize, usize)]) -> Vec<bool> {
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
    summed
}

/// The blocks not `summed` and the slots of their interfaces' terms, numbered in the order the
/// pass fills them (by counting sort: in increasing k within each block), and where each
/// part's terms start (into `parts`).
fn straddlers(nb: usize, geo: &[Geo], summed: &[bool], parts: &mut [(usize, usize, usize)]) -> Straddlers {
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
    Straddlers { blocks, start, slots }
}

/// Index of a family in the integrator's table of four laws.
pub(super) fn family_index(f: Family) -> u8 {
    match f {
        Family::Bed => 0,
        Family::Head => 1,
        Family::Base => 2,
        Family::Top => 3,
    }
}
