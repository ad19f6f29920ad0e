//! The contact update of time histories in the plane: contacts found again as the blocks move,
//! and a ground plane for the blocks that fall.
//!
//! - **When**: the contacts are searched again whenever some block has moved, since the last
//!   search, by more than the travel tolerance `gap / 2` at some point of it (its centroid's
//!   translation plus its rotation times its farthest vertex's distance from the centroid). Two
//!   blocks close on each other by at most `gap` between two searches, so none passes into
//!   another unseen. The check costs one pass over the blocks per time step; the search itself
//!   (the grid of the model's detection, [`for_each_pair`], and [`facing_edges`] on the moved
//!   blocks) allocates, rarely.
//! - **Gap tolerance**: [`GAP_FRACTION`] of the least side of the smallest wall block's box.
//!   Two edges whose outward normals are opposed within 60 degrees, overlapping along one of them,
//!   the nearer end of the overlap within `gap`, are in contact: open (no force) until they
//!   close. A contact whose edges are no longer so is dropped.
//! - **History**: a contact found again (the same two edges) keeps its joint history, its
//!   contact dashpot and what the dashpot dissipated; its geometry is kept as it was while its
//!   points and its length are off by at most [`RETAKE`] gap tolerances from those found on the
//!   moved blocks, and taken again from them otherwise (its elastic slip kept: the plastic slip is shifted by the change of
//!   the slip jump). A new contact is dry (no cohesion, no tensile strength: a joint that was
//!   not there has no mortar), starts with no shear force, and has the contact dashpot of its
//!   joint's restitution, as the others do (so impacts on it lose the energy they do on the
//!   model's joints).
//! - **Ground**: a fixed horizontal plane at the top of the base (where the wall stands), or,
//!   without a base, at the lowest point of the model; it reaches beyond the box around every
//!   block by [`GROUND_REACH`] times the model's size on both sides. With a base it is the base
//!   widened so (as deep); without one, a rectangle as deep as that box is high, carried by the
//!   first support's dofs
//!   (with neither, no ground). Its joints are base joints. Gravity along -y only: with gravity
//!   turned the model has no ground.

use super::*;
use crate::interface::BlockKind;
use crate::shape::grid::for_each_pair;
use crate::shape::{contact_tolerance, facing_edges, Aabb, Facing, Polygon};
use std::collections::HashMap;

/// The gap tolerance as a fraction of the least side of the smallest wall block's box.
pub const GAP_FRACTION: f64 = 0.02;

/// A contact found again keeps its geometry until a point of it, or its length, is off by more
/// than this many gap tolerances from the contact found on the moved blocks: its force then acts
/// at most that far (4% of the smallest block's least side) from where the blocks now touch. At
/// half a gap, Ferris & Tin-Loi's wall 1 under El Centro scaled by 3 had 15 contacts taken again
/// in 31 s as their blocks slid along them, and its response moved by 0.45 mm against a peak of
/// 9.9 mm (one gap: 6, 0.12 mm; two: none, the run identical to the one without the update).
pub const RETAKE: f64 = 2.0;

/// How far the ground reaches beyond the box around all the blocks on each side, in multiples of
/// the model's size (the larger side of that box): the debris of a collapsing arch flies out.
pub const GROUND_REACH: f64 = 5.0;

/// Two bodies and an edge (in 3D a face) of each, in increasing order of the bodies: what a
/// contact is, from one search to the next.
pub(super) type Key = ([u32; 2], [u32; 2]);

pub(super) fn key(bodies: [usize; 2], edges: [usize; 2]) -> Key {
    if bodies[0] <= bodies[1] {
        ([bodies[0] as u32, bodies[1] as u32], [edges[0] as u32, edges[1] as u32])
    } else {
        ([bodies[1] as u32, bodies[0] as u32], [edges[1] as u32, edges[0] as u32])
    }
}

/// What the contact update keeps besides the integrator's arrays, in either dimension: `B` a
/// body's shape (a polygon, a polyhedron).
pub(crate) struct Update<B = Polygon> {
    /// the bodies in their reference positions: the model's blocks, then the ground's pieces
    pub(super) bodies: Vec<B>,
    /// the block whose dofs carry each body, and what each body is
    pub(super) block: Vec<usize>,
    pub(super) kind: Vec<BlockKind>,
    /// each block's largest distance from its centroid to a vertex \[m\]
    pub(super) radius: Vec<f64>,
    /// each interface's bodies and edges (faces)
    pub(super) keys: Vec<Key>,
    /// the gap tolerance, the travel tolerance and the contact tolerance \[m\]
    pub(super) gap: f64,
    pub(super) travel: f64,
    pub(super) tol: f64,
    /// the displacements at the last search
    pub(super) u_ref: Vec<f64>,
    /// in 3D, each block's rotation matrix at the last search (empty in the plane)
    pub(super) rot_ref: Vec<[f64; 9]>,
    /// searches made, contacts created, dropped, and taken again from the moved blocks
    pub(super) searches: usize,
    pub(super) created: usize,
    pub(super) dropped: usize,
    pub(super) renewed: usize,
    /// what the dashpots of dropped contacts dissipated: impacts, stiffness-proportional \[J\]
    pub(super) dropped_dissipation: (f64, f64),
    /// each interface's number (see [`ContactEvent`]), and the next new contact's
    pub(super) ids: Vec<usize>,
    pub(super) next_id: usize,
    /// the contacts created, dropped and taken again, in order
    pub(super) events: Vec<ContactEvent>,
    /// the ground's level \[m\], if the model has one
    pub(super) ground: Option<f64>,
    /// a time history's: each interface has its contact dashpot
    pub(super) dashpots: bool,
}

impl<B> Update<B> {
    /// The update of a model of blocks `bodies` of kinds `kinds` with its ground (its body, the
    /// block that carries it, whether it replaces that block (the base widened), its level),
    /// each block's radius, the keys of its interfaces (of the bodies, the ground in place), the
    /// gap and contact tolerances, the displacements (and in 3D the rotation matrices) now, and
    /// whether the interfaces have dashpots.
    #[allow(clippy::type_complexity)]
    pub(super) fn assemble(
        (mut bodies, mut kind, ground): (Vec<B>, Vec<BlockKind>, Option<(B, usize, bool, f64)>),
        radius: Vec<f64>,
        keys: impl FnOnce(&[B]) -> Vec<Key>,
        (gap, tol): (f64, f64),
        u_ref: Vec<f64>,
        rot_ref: Vec<[f64; 9]>,
        dashpots: bool,
    ) -> Self {
        let mut block: Vec<usize> = (0..bodies.len()).collect();
        let ground = ground.map(|(body, anchor, widened, level)| {
            if widened {
                bodies[anchor] = body;
            } else {
                bodies.push(body);
                block.push(anchor);
                kind.push(BlockKind::Base);
            }
            level
        });
        let keys = keys(&bodies);
        let n = keys.len();
        Update {
            bodies,
            block,
            kind,
            radius,
            keys,
            gap,
            travel: 0.5 * gap,
            tol,
            u_ref,
            rot_ref,
            searches: 0,
            created: 0,
            dropped: 0,
            renewed: 0,
            dropped_dissipation: (0.0, 0.0),
            ids: (0..n).collect(),
            next_id: n,
            events: vec![],
            ground,
            dashpots,
        }
    }

    /// What the update adds to history `h` at the end of the run: its counts and the ground's level.
    pub(super) fn report<V>(&self, h: &mut TimeHistory<V>) {
        (h.contact_searches, h.contacts_created, h.contacts_dropped, h.contacts_renewed) = (self.searches, self.created, self.dropped, self.renewed);
        h.ground_level = self.ground;
    }

    /// Whether block `i`, translated by `t` and turned so that a point at unit distance from its
    /// centroid moved by `turn`, has some point beyond the travel tolerance.
    #[inline(always)]
    pub(super) fn beyond(&self, i: usize, t: f64, turn: f64) -> bool {
        t + turn * self.radius[i] > self.travel
    }

    /// What `facing` finds between each two bodies of boxes `boxes` (where the displacements carry
    /// them) within the gap of each other, a wall block among them, on the grid of the model's
    /// detection: each with the body that owns its normal (`owner`: 0 the first of the two given),
    /// then the other.
    pub(super) fn near<const D: usize, F>(&self, boxes: &[Aabb<D>], facing: impl Fn(usize, usize) -> Vec<F>, owner: impl Fn(&F) -> usize) -> Vec<(usize, usize, F)> {
        let mut found = vec![];
        let kinds = &self.kind;
        let _ = for_each_pair(boxes, self.gap, &mut || true, |i, j| {
            if kinds[i] != BlockKind::Wall && kinds[j] != BlockKind::Wall {
                return Ok(());
            }
            for f in facing(i, j) {
                let (oa, ob) = if owner(&f) == 0 { (i, j) } else { (j, i) };
                found.push((oa, ob, f));
            }
            Ok(())
        });
        found
    }

    /// The old contacts by their keys.
    pub(super) fn by_key(&self) -> HashMap<Key, usize> {
        self.keys.iter().enumerate().map(|(k, &key)| (key, k)).collect()
    }
}

/// The box of the ground under blocks within `all` (the vertical the last axis): `all` widened in
/// plan by [`GROUND_REACH`] times the model's size `size` on each side.
pub(super) fn ground_reach<const D: usize>(all: &Aabb<D>, size: f64) -> Aabb<D> {
    let reach = GROUND_REACH * size;
    let mut b = *all;
    for k in 0..D - 1 {
        b.min[k] -= reach;
        b.max[k] += reach;
    }
    b
}

/// The gap tolerance of the wall blocks whose boxes are `boxes` (see [`GAP_FRACTION`]).
pub(super) fn gap_of<const D: usize>(boxes: impl Iterator<Item = Aabb<D>>) -> f64 {
    GAP_FRACTION * boxes.map(|b| (0..D).map(|k| b.max[k] - b.min[k]).fold(f64::INFINITY, f64::min)).fold(f64::INFINITY, f64::min)
}

/// The largest distance from `g` to one of `vertices` \[m\].
pub(super) fn radius_of<const D: usize>(g: [f64; D], vertices: &[[f64; D]]) -> f64 {
    vertices.iter().map(|v| (0..D).map(|k| (v[k] - g[k]) * (v[k] - g[k])).sum::<f64>().sqrt()).fold(0.0, f64::max)
}

/// The law of a new contact between bodies of kinds `ka` and `kb`: a base's or a support's,
/// the top beam's, else a bed joint's where `bed` (the normal within 45 degrees of the
/// vertical), a head joint's otherwise.
pub(super) fn new_family(ka: BlockKind, kb: BlockKind, bed: bool) -> Family {
    match (ka, kb) {
        (BlockKind::Base | BlockKind::Support, _) | (_, BlockKind::Base | BlockKind::Support) => Family::Base,
        (BlockKind::Top, _) | (_, BlockKind::Top) => Family::Top,
        _ if bed => Family::Bed,
        _ => Family::Head,
    }
}

/// The range of a time history's state (see `out_of_range`): how far a block may move, in
/// multiples of the model's size, and turn \[rad\] (`large`: finite rotations), and the words of
/// the first; with the contact update a block may fall and tumble: only one that has left the
/// ground is out.
pub(super) fn range(updating: bool, large: bool) -> (f64, f64, &'static str) {
    if updating {
        (2.0 + GROUND_REACH, f64::INFINITY, "seven times the model's size")
    } else if large {
        (1.0, std::f64::consts::FRAC_PI_2, "the wall's size")
    } else {
        (1.0, 1.0, "the wall's size")
    }
}

/// The ground of `model` (see the module's notes): its rectangle, the block that carries it,
/// whether it is that block (the base, widened) or a body of its own, and its level \[m\].
pub(super) fn ground(model: &Model) -> Option<(Polygon, usize, bool, f64)> {
    if model.gravity_direction() != [0.0, -1.0] {
        return None;
    }
    let all = model.polygons().iter().fold(Aabb::around(&[]), |b, p| b.union(&p.aabb()));
    let h = all.max[1] - all.min[1];
    let wide = ground_reach(&all, model.size());
    let (x0, x1) = (wide.min[0], wide.max[0]);
    let rect = |bottom: f64, top: f64| Polygon::new(vec![[x0, bottom], [x1, bottom], [x1, top], [x0, top]]);
    if let Some(base) = model.base() {
        let bb = model.polygons()[base].aabb();
        Some((rect(bb.min[1], bb.max[1]), base, true, bb.max[1]))
    } else {
        let anchor = model.supports().next()?;
        Some((rect(all.min[1] - h, all.min[1]), anchor, false, all.min[1]))
    }
}

/// The gap tolerance of `model` (see [`GAP_FRACTION`]).
pub(super) fn gap_tolerance(model: &Model) -> f64 {
    gap_of(model.polygons()[..model.n_wall()].iter().map(Polygon::aabb))
}

/// The stable time step of `model` once its blocks may touch anything along every edge: the
/// Gershgorin bound of [`critical_time_step`] with, on each wall block, an interface along each
/// of its edges with a fixed body, of the stiffest of the joint laws (a block fallen on its long
/// side, debris in a heap); the smaller of that and the model's own.
pub(super) fn critical_time_step_moving(model: &Model) -> f64 {
    let mut bound = Gershgorin::new(&integrator::masses(model), model.fixed());
    let laws = [Family::Bed, Family::Head, Family::Base, Family::Top].map(|f| *model.laws().of(f));
    for i in 0..model.n_wall() {
        let (g, v) = (model.centroids()[i], model.polygons()[i].vertices());
        let dofs = [3 * i, 3 * i + 1, 3 * i + 2];
        for k in 0..v.len() {
            let (p, q) = (v[k], v[(k + 1) % v.len()]);
            let l = (q[0] - p[0]).hypot(q[1] - p[1]);
            let n = [(p[1] - q[1]) / l, (q[0] - p[0]) / l];
            let c = [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])];
            // the block as b of an interface with a fixed a: its three columns of B
            let it = Interface::new(i, i, g, g, c, n, l, Family::Base);
            let b: [[f64; 3]; 3] = std::array::from_fn(|r| [it.b_mat[r][3], it.b_mat[r][4], it.b_mat[r][5]]);
            let sec = Section::new(l, model.thickness());
            let d = laws.iter().map(|law| crate::joint::stiffness(law, &sec)).fold([0.0; 3], |a, d| std::array::from_fn(|j| f64::max(a[j], d[j])));
            bound.add(&dofs, &b, d);
        }
    }
    bound.step().min(critical_time_step(model))
}

impl Update<Polygon> {
    /// The contact update of `s` (finite rotations) at its current state, the model's
    /// interfaces matched to their edges.
    pub(super) fn new(s: &Integrator) -> Update {
        let model = s.model;
        let radius = (0..model.n_blocks()).map(|i| radius_of(model.centroids()[i], model.polygons()[i].vertices())).collect();
        let tol = contact_tolerance(model.size());
        let keys = |bodies: &[Polygon]| model.interfaces().iter().map(|it| key([it.a, it.b], [edge_at(&bodies[it.a], it.c, it.n, tol), edge_at(&bodies[it.b], it.c, [-it.n[0], -it.n[1]], tol)])).collect();
        Update::assemble((model.polygons().to_vec(), model.kinds().to_vec(), ground(model)), radius, keys, (gap_tolerance(model), tol), s.u.clone(), vec![], !s.dynm.is_empty())
    }

    /// Whether some block has moved by more than the travel tolerance since the last search.
    #[inline]
    pub(super) fn due(&self, u: &[f64]) -> bool {
        let r = &self.u_ref;
        (0..self.radius.len()).any(|i| {
            let d = 3 * i;
            self.beyond(i, (u[d] - r[d]).hypot(u[d + 1] - r[d + 1]), (u[d + 2] - r[d + 2]).abs())
        })
    }

    /// Body `k` where the displacements `u` carry it.
    fn moved(&self, model: &Model, u: &[f64], k: usize) -> Polygon {
        let i = self.block[k];
        let (g, d) = (model.centroids()[i], &u[3 * i..3 * i + 3]);
        let (sn, cs) = d[2].sin_cos();
        self.bodies[k].map(|x| {
            let (x, y) = (x[0] - g[0], x[1] - g[1]);
            [g[0] + d[0] + cs * x - sn * y, g[1] + d[1] + sn * x + cs * y]
        })
    }
}

/// The edge of `p` whose outward normal is `n` and whose line passes through `c` (the first
/// such; `usize::MAX` if none).
fn edge_at(p: &Polygon, c: [f64; 2], n: [f64; 2], tol: f64) -> usize {
    let v = p.vertices();
    (0..v.len())
        .find(|&k| {
            let (a, b) = (v[k], v[(k + 1) % v.len()]);
            let l = (b[0] - a[0]).hypot(b[1] - a[1]);
            let m = [(b[1] - a[1]) / l, (a[0] - b[0]) / l];
            m[0] * n[0] + m[1] * n[1] > 1.0 - 1e-9 && ((c[0] - a[0]) * m[0] + (c[1] - a[1]) * m[1]).abs() <= 10.0 * tol.max(1e-12 * l)
        })
        .unwrap_or(usize::MAX)
}

/// The arm of a contact found as `f` between blocks `a` (the owner of the normal) and `b`, at
/// the displacements `u`: its points and normal carried back to the blocks' reference positions.
fn arm_of(model: &Model, u: &[f64], a: usize, b: usize, f: &Facing) -> Arm {
    let back = |i: usize, x: [f64; 2]| {
        let (g, d) = (model.centroids()[i], &u[3 * i..3 * i + 3]);
        let (sn, cs) = d[2].sin_cos();
        let (x, y) = (x[0] - g[0] - d[0], x[1] - g[1] - d[1]);
        [cs * x + sn * y, -sn * x + cs * y]
    };
    let (sn, cs) = u[3 * a + 2].sin_cos();
    let n = [cs * f.n[0] + sn * f.n[1], -sn * f.n[0] + cs * f.n[1]];
    let theta0 = (u[3 * b + 2] - u[3 * a + 2]) - f.angle;
    Arm { ra: back(a, f.at[0]), rb: back(b, f.at[1]), n, rel0: [theta0.cos(), theta0.sin()], l: f.length }
}

/// The jumps of a contact of arm `arm` between blocks `a` and `b` at the displacements `u`
/// (the slip point at the centre).
fn jumps(model: &Model, u: &[f64], a: usize, b: usize, arm: &Arm) -> ([f64; 3], f64) {
    let g = model.centroids();
    let cs = |i: usize| {
        let (s, c) = u[3 * i + 2].sin_cos();
        [c, s]
    };
    let kin = arm.large_kinematics(g[a], g[b], &u[3 * a..3 * a + 3], &u[3 * b..3 * b + 3], cs(a), cs(b), 0.0);
    (kin.jumps, kin.rel[0])
}

/// The centre of a contact of arm `arm` between blocks `a` and `b` at the displacements `u`:
/// half-way between its points on the two blocks.
fn centre(model: &Model, u: &[f64], a: usize, b: usize, arm: &Arm) -> [f64; 2] {
    let (pa, pb) = points(model, u, a, b, arm);
    [0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])]
}

/// The points of a contact of arm `arm` on blocks `a` and `b` at the displacements `u`.
fn points(model: &Model, u: &[f64], a: usize, b: usize, arm: &Arm) -> ([f64; 2], [f64; 2]) {
    let at = |i: usize, r: [f64; 2]| {
        let (g, d) = (model.centroids()[i], &u[3 * i..3 * i + 3]);
        let (sn, cs) = d[2].sin_cos();
        [g[0] + d[0] + cs * r[0] - sn * r[1], g[1] + d[1] + sn * r[0] + cs * r[1]]
    };
    (at(a, arm.ra), at(b, arm.rb))
}

/// One contact after a search, before the integrator's arrays are rebuilt: the index of the
/// contact it continues, if any, and its geometry if new or renewed.
struct Next {
    a: usize,
    b: usize,
    key: Key,
    old: Option<usize>,
    arm: Option<(Arm, Family)>,
}

/// Searches the contacts of `s` again at its current displacements (see the module's notes) and
/// rebuilds the integrator's arrays of interfaces.
pub(super) fn search(s: &mut Integrator) {
    let Some(mut up) = s.update.take() else { return };
    let model = s.model;
    let u = &s.m.u;
    let polygons: Vec<Polygon> = (0..up.bodies.len()).map(|k| up.moved(model, u, k)).collect();
    let boxes: Vec<Aabb<2>> = polygons.iter().map(Polygon::aabb).collect();
    let found = up.near(&boxes, |i, j| facing_edges(&polygons[i], &polygons[j], up.gap, up.tol), |f| f.owner);
    let old = up.by_key();
    let mut kept = vec![false; up.keys.len()];
    let up_dir = [-model.gravity_direction()[0], -model.gravity_direction()[1]];
    let mut next: Vec<Next> = found
        .iter()
        .map(|(oa, ob, f)| {
            let k = key([*oa, *ob], f.edges);
            let (a, b) = (up.block[*oa], up.block[*ob]);
            let fresh = || {
                let bed = (f.n[0] * up_dir[0] + f.n[1] * up_dir[1]).abs() >= (f.n[0] * up_dir[1] - f.n[1] * up_dir[0]).abs();
                let family = new_family(up.kind[*oa], up.kind[*ob], bed);
                Some((arm_of(model, u, a, b, f), family))
            };
            match old.get(&k) {
                Some(&o) if !kept[o] => {
                    kept[o] = true;
                    let g = &s.geo[o];
                    let arm = &s.arms[o];
                    // the contact's points on its two blocks now, against those found
                    let (pa, pb) = points(model, u, g.a(), g.b(), arm);
                    let (fa, fb) = if g.a() == a { (f.at[0], f.at[1]) } else { (f.at[1], f.at[0]) };
                    let retake = RETAKE * up.gap;
                    let near = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]) <= retake;
                    let same = near(pa, fa) && near(pb, fb) && (arm.l - f.length).abs() <= retake;
                    let (a, b) = if same { (g.a(), g.b()) } else { (a, b) };
                    let family = s.shapes[g.shape as usize].family;
                    let arm = if same { None } else { fresh().map(|(arm, _)| (arm, family_of(family))) };
                    Next { a, b, key: k, old: Some(o), arm }
                }
                _ => Next { a, b, key: k, old: None, arm: fresh() },
            }
        })
        .collect();
    next.sort_by_key(|n| (n.a, n.b, n.key));
    rebuild(s, &mut up, &next, &kept);
    up.u_ref.copy_from_slice(&s.m.u);
    up.searches += 1;
    s.update = Some(up);
}

/// A family from its index in the integrator's table of laws (see [`family_index`]).
fn family_of(i: u8) -> Family {
    [Family::Bed, Family::Head, Family::Base, Family::Top][i as usize]
}

/// The integrator's arrays of interfaces rebuilt for the contacts `next` (`kept`: which old
/// interfaces go on).
fn rebuild(s: &mut Integrator, up: &mut Update, next: &[Next], kept: &[bool]) {
    let model = s.model;
    let hw = s.hw;
    let time = s.m.steps as f64 * s.m.dt;
    let event = |change, id, blocks: [usize; 2], arm: Option<&Arm>| ContactEvent {
        time,
        change,
        id,
        blocks,
        centre: arm.map_or([0.0; 2], |a| a.ra),
        normal: arm.map_or([0.0; 2], |a| a.n),
        length: arm.map_or(0.0, |a| a.l),
    };
    for (o, &k) in kept.iter().enumerate() {
        if !k {
            up.events.push(event(ContactChange::Dropped, up.ids[o], [s.geo[o].a(), s.geo[o].b()], None));
            up.dropped += 1;
            if let Some(d) = s.dynm.get(o) {
                up.dropped_dissipation.0 += d.damped;
                up.dropped_dissipation.1 += d.stiffness_damped;
            }
        }
    }
    let m = next.len();
    let mut shape_of: HashMap<_, u32> = s.shapes.iter().enumerate().map(|(i, sh)| (sh.key(), i as u32)).collect();
    let (mut geo, mut arms, mut sections, mut hist, mut broken, mut forces, mut flags, mut warm, mut dynm, mut keys) =
        (Vec::with_capacity(m), Vec::with_capacity(m), Vec::with_capacity(m), Vec::with_capacity(hw * m), Vec::with_capacity(m), Vec::with_capacity(m), Vec::with_capacity(m), Vec::with_capacity(m), Vec::with_capacity(m), Vec::with_capacity(m));
    let mut fresh = vec![];
    let mut ids = Vec::with_capacity(m);
    for nx in next {
        keys.push(nx.key);
        let id = nx.old.map_or_else(
            || {
                up.next_id += 1;
                up.next_id - 1
            },
            |o| up.ids[o],
        );
        ids.push(id);
        match (nx.old, &nx.arm) {
            (Some(o), None) => {
                geo.push(Geo { a: nx.a as u32, b: nx.b as u32, shape: s.geo[o].shape });
                arms.push(s.arms[o]);
                sections.push(s.sections[o]);
                hist.extend_from_slice(&s.hist[hw * o..hw * (o + 1)]);
                broken.push(s.broken[o]);
                forces.push(s.forces[o]);
                flags.push(s.flags[o]);
                warm.push(s.warm[o]);
                if up.dashpots {
                    dynm.push(s.dynm[o]);
                }
            }
            (old, Some((arm, family))) => {
                let shape = Shape { r: [0.0; 4], n: [0.0; 2], kind: Kinds::NONE, family: family_index(*family) };
                let next_index = shape_of.len() as u32;
                let index = *shape_of.entry(shape.key()).or_insert_with(|| {
                    s.shapes.push(shape);
                    next_index
                });
                geo.push(Geo { a: nx.a as u32, b: nx.b as u32, shape: index });
                arms.push(*arm);
                sections.push(Section::new(arm.l, model.thickness()));
                let (e, _) = jumps(model, &s.m.u, nx.a, nx.b, arm);
                let mut h = [0.0; 5];
                match old {
                    Some(o) => {
                        // the same contact on its moved geometry: its history, the elastic slip kept
                        let g = &s.geo[o];
                        let (e_old, _) = jumps(model, &s.m.u, g.a(), g.b(), &s.arms[o]);
                        h[..hw].copy_from_slice(&s.hist[hw * o..hw * (o + 1)]);
                        h[1] += e[1] - e_old[1];
                        let f = s.forces[o];
                        if g.a() == nx.a {
                            forces.push(f);
                            warm.push(s.warm[o]);
                        } else {
                            // the blocks swapped: the relative rotation and the moment change sign
                            h[2] = -h[2];
                            forces.push([f[0], f[1], -f[2]]);
                            warm.push(0);
                        }
                        broken.push(s.broken[o]);
                        flags.push(s.flags[o]);
                        up.events.push(event(ContactChange::Renewed, id, [nx.a, nx.b], Some(arm)));
                        up.renewed += 1;
                    }
                    None => {
                        // a new contact: dry, no shear force
                        h[1] = e[1];
                        broken.push(true);
                        forces.push([0.0; 3]);
                        flags.push(0);
                        warm.push(0);
                        up.events.push(event(ContactChange::Created, id, [nx.a, nx.b], Some(arm)));
                        up.created += 1;
                    }
                }
                hist.extend_from_slice(&h[..hw]);
                fresh.push((geo.len() - 1, old));
                // its dashpot is made from the integrator's arrays, so once they are in place (the
                // loop over `fresh` below); the slot keeps the arrays' order meanwhile
                if up.dashpots {
                    dynm.push(Dyn::default());
                }
            }
            (None, None) => unreachable!("a new contact has its geometry"),
        }
    }
    let old_dynm = std::mem::take(&mut s.dynm);
    (s.geo, s.arms, s.sections, s.hist, s.broken, s.forces, s.flags, s.warm, s.dynm) = (geo, arms, sections, hist, broken, forces, flags, warm, dynm);
    up.keys = keys;
    up.ids = ids;
    if up.dashpots {
        for (k, old) in fresh {
            let mut d = s.dashpot_of(k);
            if let Some(o) = old {
                (d.damped, d.stiffness_damped) = (old_dynm[o].damped, old_dynm[o].stiffness_damped);
            }
            let (g, arm) = (&s.geo[k], &s.arms[k]);
            let (e, cos) = jumps(model, &s.m.u, g.a(), g.b(), arm);
            (d.jumps, d.cos) = (e, cos);
            s.dynm[k] = d;
        }
    }
    let n_parts = s.parts.len().saturating_sub(1).max(1);
    s.set_parts(n_parts);
}

/// The contacts of `s` at its current displacements (see [`ContactAt`]).
pub(super) fn contacts(s: &Integrator) -> Vec<ContactAt> {
    let (model, u) = (s.model, &s.m.u);
    s.geo
        .iter()
        .zip(&s.arms)
        .map(|(g, arm)| {
            let (a, b) = (g.a(), g.b());
            let (sn, cs) = u[3 * a + 2].sin_cos();
            let normal = [cs * arm.n[0] - sn * arm.n[1], sn * arm.n[0] + cs * arm.n[1]];
            let (e, _) = jumps(model, u, a, b, arm);
            ContactAt { blocks: [a, b], centre: centre(model, u, a, b, arm), normal, length: arm.l, gap: e[0] }
        })
        .collect()
}
