//! The contact update of 3D time histories: the plane's ([`crate::explicit`]'s notes, and the
//! module `update` beside this one, whose tolerances, travel check, keys, counts and ground this
//! shares), with faces for edges and rotation matrices for angles.
//!
//! - **When**: a search runs once some block has moved, since the last search, by more than
//!   the travel tolerance `gap / 2` at some point of it: its centroid's translation plus its
//!   radius (the farthest vertex from the centroid) times `2 sin(theta / 2)`, theta the angle of
//!   its rotation since then (from the rotation matrices: `|R - R_ref|_F / sqrt 2`).
//! - **Contacts**: two faces whose outward normals are opposed within 60 degrees, whose
//!   projections along the owner's normal share a polygon, the other's face within the gap of
//!   the owner's at some corner of it ([`facing_faces`]); the owner is the lower block (as the
//!   model's detection orients its contacts). The contact's corners are the polygon's, each a
//!   point on the owner's face and one on the other's face's plane along the normal: their
//!   distance is the corner's gap (open until it closes). A contact found again (the same two
//!   faces) keeps its history, its state and its dashpot, and its geometry while the outline of
//!   its points now and that of the polygon found are within [`RETAKE`](crate::explicit::RETAKE)
//!   gap tolerances of each other (every corner of either within that of the other's edges,
//!   slivers of a turned block aside, as the plane's ends and length); otherwise its
//!   geometry is taken again from the moved blocks: the law's area-proportional constants
//!   follow the new area, each new corner gets the old corners' mean plastic normal jump, and
//!   the contact's mean elastic slip (so its shear force is kept), and its dashpot what it
//!   dissipated. A new contact is dry, starts with no shear force, and has its joint's contact
//!   dashpot (restitution).
//! - **Ground**: gravity is along -z; a fixed horizontal plane at the top of the base (without
//!   a base, at the model's lowest point, carried by the first support), reaching beyond the box
//!   around every block in plan by [`GROUND_REACH`](crate::explicit::GROUND_REACH) times the model's size on every side: with
//!   a base, the base widened so (as deep); without, a slab as deep as that box is high. Its
//!   contacts are base joints.
//! - **Cost**: the check is one pass over the blocks per time step; a search (the grid of the
//!   detection on the moved blocks) allocates, and the arrays of the contact pass are rebuilt
//!   after it, rarely.

pub(super) use super::super::update::Update;
use super::super::update::{gap_of, ground_reach, key, new_family, radius_of, Key, RETAKE};
use super::*;
use crate::interface::{BlockKind, Family};
use crate::shape::{contact_tolerance, face_patch, facing_faces, Aabb, FaceFacing, Polyhedron};
use std::f64::consts::FRAC_1_SQRT_2;

/// The ground of `model` (see the module's notes): its box, the block that carries it, whether
/// it is that block (the base, widened) or a body of its own, and its level \[m\].
fn ground(model: &Model3) -> Option<(Polyhedron, usize, bool, f64)> {
    let all = model.shapes().iter().fold(Aabb::around(&[]), |b, p| b.union(&p.aabb()));
    let wide = ground_reach(&all, model.size());
    let slab = |bottom: f64, top: f64| Polyhedron::cuboid([wide.min[0], wide.min[1], bottom], [wide.max[0], wide.max[1], top]);
    if let Some(base) = model.base() {
        let bb = model.shapes()[base].aabb();
        Some((slab(bb.min[2], bb.max[2]), base, true, bb.max[2]))
    } else {
        let anchor = (0..model.n_blocks()).find(|&i| model.kinds()[i] == BlockKind::Base)?;
        Some((slab(all.min[2] - (all.max[2] - all.min[2]), all.min[2]), anchor, false, all.min[2]))
    }
}

/// The face of `p` whose outward normal is `n` and whose plane passes through `c` (the first
/// such; `usize::MAX` if none).
fn face_at(p: &Polyhedron, c: [f64; 3], n: [f64; 3], tol: f64) -> usize {
    p.faces().iter().position(|f| dot(f.normal, n) > 1.0 - 1e-6 && (dot(f.normal, c) - f.offset).abs() <= 10.0 * tol).unwrap_or(usize::MAX)
}

/// The stable time step of a 3D `model`'s time history once its blocks may touch anything along
/// every face: the Gershgorin bound of [`critical_time_step_3d`] with, on each wall block, a
/// contact over each of its faces with a fixed body, of the stiffest of the joint laws (a block
/// fallen on any face, debris in a heap); the smaller of that and the model's own.
pub fn critical_time_step_moving_3d(model: &Model3) -> f64 {
    let (axes, inertia) = principal_axes(model);
    let mut bound = Gershgorin::new(&masses_3d(model, &inertia), model.fixed());
    let laws = [Family::Bed, Family::Head, Family::Base, Family::Top].map(|f| *model.laws().of(f));
    let stiffest = |k: fn(&crate::joint::JointLaw) -> f64| laws.iter().map(k).fold(0.0, f64::max);
    let (kn, kt) = (stiffest(|l| l.normal_stiffness), stiffest(|l| l.shear_stiffness));
    for (i, ax) in axes.iter().enumerate().take(model.n_wall()) {
        let (p, g) = (&model.shapes()[i], model.centroids()[i]);
        let dofs: [usize; 6] = std::array::from_fn(|j| 6 * i + j);
        for (f, face) in p.faces().iter().enumerate() {
            let (corners, area, centroid) = face_patch(p, f);
            let (w, alpha) = corner_shares(&corners, centroid, face.normal);
            let (t1, t2) = crate::shape::frame(face.normal);
            let frame = [face.normal, t1, t2];
            for (x, wi) in corners.iter().zip(w) {
                // the block as b of a contact with a fixed a: its six columns of the rows
                let r = sub(*x, g);
                let rows = jump_rows(r, r, &frame, [None, ax.as_ref()]);
                let b: [[f64; 6]; 3] = rows.map(|row| std::array::from_fn(|j| row[6 + j]));
                bound.add(&dofs, &b, [alpha.max(1.0) * kn * area * wi, kt * area * wi, kt * area * wi]);
            }
        }
    }
    bound.step().min(critical_time_step_3d(model))
}

impl Update<Polyhedron> {
    /// The contact update of `s` (finite rotations) at its current state, the model's contacts
    /// matched to their faces.
    pub(super) fn new3(s: &Integrator3) -> Self {
        let model = s.model;
        let radius = (0..model.n_blocks()).map(|i| radius_of(model.centroids()[i], model.shapes()[i].vertices())).collect();
        let tol = contact_tolerance(model.size());
        let keys = |bodies: &[Polyhedron]| {
            let face = |i: usize, c: [f64; 3], n: [f64; 3]| face_at(&bodies[i], c, n, tol);
            model.contacts().iter().map(|c| key([c.a, c.b], [face(c.a, c.centroid, c.n), face(c.b, c.centroid, c.n.map(|v| -v))])).collect()
        };
        let gap = gap_of(model.shapes()[..model.n_wall()].iter().map(Polyhedron::aabb));
        Update::assemble((model.shapes().to_vec(), model.kinds().to_vec(), ground(model)), radius, keys, (gap, tol), s.m.u.clone(), s.rot.clone(), !s.dash.is_empty())
    }

    /// Whether some block has moved by more than the travel tolerance since the last search (at
    /// the displacements `u` and rotation matrices `rot`).
    #[inline]
    pub(super) fn due3(&self, u: &[f64], rot: &[[f64; 9]]) -> bool {
        let (r, r0) = (&self.u_ref, &self.rot_ref);
        let near = 0.5 * self.travel * self.travel;
        (0..self.radius.len()).any(|i| {
            let d = 6 * i;
            let t2 = (u[d] - r[d]).powi(2) + (u[d + 1] - r[d + 1]).powi(2) + (u[d + 2] - r[d + 2]).powi(2);
            let f2 = (0..9).map(|k| (rot[i][k] - r0[i][k]).powi(2)).sum::<f64>();
            // (t + turn rad)^2 <= 2 (t^2 + turn^2 rad^2): most blocks are that near, without a root
            let rad = self.radius[i];
            !(t2 + 0.5 * f2 * rad * rad <= near) && self.beyond(i, t2.sqrt(), f2.sqrt() * FRAC_1_SQRT_2)
        })
    }

    /// Body `k` where block `i`'s displacements and rotation carry it.
    fn moved3(&self, s: &Integrator3, k: usize) -> Polyhedron {
        let i = self.block[k];
        let (g, u, r) = (s.model.centroids()[i], &s.m.u[6 * i..6 * i + 3], &s.rot[i]);
        self.bodies[k].map(|x| {
            let y = mat(r, sub(x, g));
            [g[0] + u[0] + y[0], g[1] + u[1] + y[1], g[2] + u[2] + y[2]]
        })
    }
}

/// Where point `r` of block `i` (from its centroid, in its reference orientation) is now.
fn now(s: &Integrator3, i: usize, r: [f64; 3]) -> [f64; 3] {
    let (g, u, y) = (s.model.centroids()[i], &s.m.u[6 * i..6 * i + 3], mat(&s.rot[i], r));
    [g[0] + u[0] + y[0], g[1] + u[1] + y[1], g[2] + u[2] + y[2]]
}

/// The midpoints of contact `k`'s points on its two blocks now.
fn midpoints<'s>(s: &'s Integrator3<'_>, k: usize) -> impl Iterator<Item = [f64; 3]> + 's {
    let c = s.cts[k];
    s.pts[s.at[k] as usize..s.at[k + 1] as usize].iter().map(move |p| {
        let (pa, pb) = (now(s, c.a as usize, p.ra), now(s, c.b as usize, p.rb));
        [0, 1, 2].map(|r| 0.5 * (pa[r] + pb[r]))
    })
}

/// A contact's geometry found by a search between blocks `a` (the owner of the normal) and `b`,
/// carried back to the blocks' reference positions: its frame (in a's), its points, their
/// shares, its law at its corners, its area and family.
struct Found {
    frame: [[f64; 3]; 3],
    pts: Vec<Pt>,
    shares: Vec<f64>,
    alpha: f64,
    area: f64,
    family: Family,
}

fn found(s: &Integrator3, a: usize, b: usize, f: &FaceFacing, family: Family) -> Found {
    let cen = s.model.centroids();
    let (ra_m, rb_m) = (&s.rot[a], &s.rot[b]);
    let back = |i: usize, m: &[f64; 9], x: [f64; 3]| {
        let u = &s.m.u[6 * i..6 * i + 3];
        mat_t(m, [x[0] - cen[i][0] - u[0], x[1] - cen[i][1] - u[1], x[2] - cen[i][2] - u[2]])
    };
    let offset = sub(cen[b], cen[a]);
    let pts = f
        .corners
        .iter()
        .map(|[xa, xb]| {
            let (ra, rb) = (back(a, ra_m, *xa), back(b, rb_m, *xb));
            Pt { ra, rb, off: [0, 1, 2].map(|r| offset[r] - ra[r] + rb[r]) }
        })
        .collect();
    let mid: Vec<[f64; 3]> = f.corners.iter().map(|[p, _]| *p).collect();
    let (shares, alpha) = corner_shares(&mid, f.centroid, f.n);
    Found { frame: [f.n, f.t1, f.t2].map(|w| mat_t(ra_m, w)), pts, shares, alpha, area: f.area, family }
}

/// One contact after a search: its blocks and key, the contact it continues, if any, and its
/// geometry if new or renewed.
struct Next {
    a: usize,
    b: usize,
    key: Key,
    old: Option<usize>,
    geo: Option<Found>,
}

/// Searches the contacts of `s` again at its current state (see the module's notes) and
/// rebuilds the contact pass's arrays.
pub(super) fn search(s: &mut Integrator3) {
    let Some(mut up) = s.update.take() else { return };
    let shapes: Vec<Polyhedron> = (0..up.bodies.len()).map(|k| up.moved3(s, k)).collect();
    let boxes: Vec<Aabb<3>> = shapes.iter().map(Polyhedron::aabb).collect();
    let hits = up.near(&boxes, |i, j| facing_faces(&shapes[i], &shapes[j], up.gap, up.tol), |f: &FaceFacing| f.owner);
    let old = up.by_key();
    let mut kept = vec![false; up.keys.len()];
    let mut next: Vec<Next> = hits
        .iter()
        .map(|(oa, ob, f)| {
            let k = key([*oa, *ob], f.faces);
            let (a, b) = (up.block[*oa], up.block[*ob]);
            match old.get(&k) {
                Some(&o) if !kept[o] => {
                    kept[o] = true;
                    // the same contact while its outline is where its points' now is, within
                    // RETAKE gap tolerances both ways (the blocks turned a little, the polygons may
                    // differ by slivers, with corners of their own)
                    let mids: Vec<[f64; 3]> = midpoints(s, o).collect();
                    let corners: Vec<[f64; 3]> = f.corners.iter().map(|[p, q]| [0, 1, 2].map(|r| 0.5 * (p[r] + q[r]))).collect();
                    let retake = RETAKE * up.gap;
                    let same = within(&corners, &mids, retake) && within(&mids, &corners, retake);
                    if same {
                        let c = s.cts[o];
                        Next { a: c.a as usize, b: c.b as usize, key: k, old: Some(o), geo: None }
                    } else {
                        Next { a, b, key: k, old: Some(o), geo: Some(found(s, a, b, f, s.families[o])) }
                    }
                }
                _ => {
                    let family = new_family(up.kind[*oa], up.kind[*ob], f.n[2].abs() >= FRAC_1_SQRT_2);
                    Next { a, b, key: k, old: None, geo: Some(found(s, a, b, f, family)) }
                }
            }
        })
        .collect();
    next.sort_by_key(|n| (n.a, n.b, n.key));
    rebuild(s, &mut up, next, &kept);
    up.u_ref.copy_from_slice(&s.m.u);
    up.rot_ref.copy_from_slice(&s.rot);
    up.searches += 1;
    s.update = Some(up);
}

/// Whether every point of `points` lies within `d` of the outline of the polygon `outline`.
fn within(points: &[[f64; 3]], outline: &[[f64; 3]], d: f64) -> bool {
    let n = outline.len();
    points.iter().all(|&x| {
        (0..n).any(|i| {
            let (p, q) = (outline[i], outline[(i + 1) % n]);
            let e = sub(q, p);
            let l2 = dot(e, e);
            let t = if l2 > 0.0 { (dot(sub(x, p), e) / l2).clamp(0.0, 1.0) } else { 0.0 };
            let y = [0, 1, 2].map(|r| p[r] + t * e[r] - x[r]);
            dot(y, y) <= d * d
        })
    })
}

/// The contact pass's arrays rebuilt for the contacts `next` (`kept`: which old contacts go on).
fn rebuild(s: &mut Integrator3, up: &mut Update<Polyhedron>, next: Vec<Next>, kept: &[bool]) {
    let model = s.model;
    for (o, &k) in kept.iter().enumerate() {
        if !k {
            up.dropped += 1;
            if up.dashpots {
                up.dropped_dissipation.0 += s.dash[s.at[o] as usize..s.at[o + 1] as usize].iter().map(|d| d.damped).sum::<f64>();
            }
        }
    }
    let m = next.len();
    let mut cts = Vec::with_capacity(m);
    let mut at = Vec::with_capacity(m + 1);
    let (mut pts, mut shares, mut hist, mut forces, mut dash) = (vec![], vec![], vec![], vec![], vec![]);
    let (mut laws, mut broken, mut flags, mut families) = (Vec::with_capacity(m), Vec::with_capacity(m), Vec::with_capacity(m), Vec::with_capacity(m));
    let mut keys = Vec::with_capacity(m);
    for nx in next {
        keys.push(nx.key);
        at.push(pts.len() as u32);
        match (nx.old, nx.geo) {
            (Some(o), None) => {
                let r = s.at[o] as usize..s.at[o + 1] as usize;
                cts.push(s.cts[o]);
                pts.extend_from_slice(&s.pts[r.clone()]);
                shares.extend_from_slice(&s.shares[r.clone()]);
                hist.extend_from_slice(&s.hist[r.clone()]);
                forces.extend_from_slice(&s.forces[r.clone()]);
                if up.dashpots {
                    dash.extend_from_slice(&s.dash[r]);
                }
                laws.push(s.laws[o]);
                broken.push(s.broken[o]);
                flags.push(s.flags[o]);
                families.push(s.families[o]);
            }
            (old, Some(g)) => {
                let law = model.laws().of(g.family);
                let (a, b) = (nx.a, nx.b);
                cts.push(Ct { a: a as u32, b: b as u32, frame: g.frame });
                let np = g.pts.len();
                // the jumps of the new points now: the gaps, no slip
                let (mut pn, mut slip, mut total) = (0.0, [0.0; 3], [0.0; 4]);
                match old {
                    Some(o) => {
                        // the same contact on its moved geometry: its mean plastic normal jump,
                        // its mean elastic slip (in the world's axes), its state and what its
                        // dashpot dissipated
                        let r = s.at[o] as usize..s.at[o + 1] as usize;
                        let c = s.cts[o];
                        let frame = c.frame.map(|w| mat(&s.rot[c.a as usize], w));
                        let es = point_jumps(s, o);
                        for (((p, w), e), f) in s.hist[r.clone()].iter().zip(&s.shares[r.clone()]).zip(&es).zip(&s.forces[r.clone()]) {
                            pn += w * p[0];
                            total[0] += f[0];
                            for k in 0..3 {
                                slip[k] += w * ((e[1] - p[1]) * frame[1][k] + (e[2] - p[2]) * frame[2][k]);
                                total[1 + k] += f[1] * frame[1][k] + f[2] * frame[2][k];
                            }
                        }
                        // the blocks swapped: the slip of b on a reverses
                        if c.a as usize != a {
                            slip = slip.map(|v| -v);
                            total = [total[0], -total[1], -total[2], -total[3]];
                        }
                        broken.push(s.broken[o]);
                        flags.push(s.flags[o]);
                        up.renewed += 1;
                    }
                    None => {
                        broken.push(true);
                        flags.push(0);
                        up.created += 1;
                    }
                }
                let world = g.frame.map(|w| mat(&s.rot[a], w));
                let (s1, s2) = (dot(slip, world[1]), dot(slip, world[2]));
                hist.extend(std::iter::repeat([pn, -s1, -s2]).take(np));
                // the forces until the next step's pass: the old ones shared by the new shares
                // (the elastic energy of the records)
                let t = [total[1], total[2], total[3]];
                forces.extend(g.shares.iter().map(|w| [w * total[0], w * dot(t, world[1]), w * dot(t, world[2])]));
                if up.dashpots {
                    let cf = s.dashpot_of(law, g.area, a, b);
                    let damped = old.map_or(0.0, |o| s.dash[s.at[o] as usize..s.at[o + 1] as usize].iter().map(|d| d.damped).sum());
                    // the dashpots start from the jumps now (no rate at the first step)
                    for (j, (w, p)) in g.shares.iter().zip(&g.pts).enumerate() {
                        let e = jump_of(s, a, b, &g.frame, p);
                        dash.push(Dash { c: [w * cf[0], w * cf[1]], jumps: e, force: [0.0; 3], damped: if j == 0 { damped } else { 0.0 } });
                    }
                }
                pts.extend(g.pts);
                shares.extend(g.shares);
                laws.push(CornerLaw::new(law, g.area, g.alpha));
                families.push(g.family);
            }
            (None, None) => unreachable!("a new contact has its geometry"),
        }
    }
    at.push(pts.len() as u32);
    let (start, slots) = slots_of(model.n_blocks(), &cts);
    s.terms = vec![[0.0; 12]; cts.len()];
    (s.cts, s.at, s.pts, s.shares, s.hist, s.forces, s.dash, s.laws, s.broken, s.flags, s.families) = (cts, at, pts, shares, hist, forces, dash, laws, broken, flags, families);
    (s.start, s.slots) = (start, slots);
    up.keys = keys;
}

/// The jumps (normal, t1, t2) of point `p` of a contact between blocks `a` and `b` of frame
/// `frame` (in a's reference orientation) at the current state.
fn jump_of(s: &Integrator3, a: usize, b: usize, frame: &[[f64; 3]; 3], p: &Pt) -> [f64; 3] {
    let (pa, pb) = (now(s, a, p.ra), now(s, b, p.rb));
    let d = sub(pb, pa);
    let f = frame.map(|w| mat(&s.rot[a], w));
    [dot(f[0], d), dot(f[1], d), dot(f[2], d)]
}

/// The jumps of contact `k`'s points at the current state.
fn point_jumps(s: &Integrator3, k: usize) -> Vec<[f64; 3]> {
    let c = s.cts[k];
    s.pts[s.at[k] as usize..s.at[k + 1] as usize].iter().map(|p| jump_of(s, c.a as usize, c.b as usize, &c.frame, p)).collect()
}

/// The contacts of `s` at its current state (see [`ContactAt3`]).
pub(super) fn contacts(s: &Integrator3) -> Vec<ContactAt3> {
    (0..s.cts.len())
        .map(|k| {
            let c = s.cts[k];
            let w = &s.shares[s.at[k] as usize..s.at[k + 1] as usize];
            let centre = midpoints(s, k).zip(w).fold([0.0; 3], |acc, (m, w)| [0, 1, 2].map(|r| acc[r] + w * m[r]));
            let gap = point_jumps(s, k).iter().zip(w).map(|(e, w)| w * e[0]).sum();
            let area = s.laws[k].kn / s.model.laws().of(s.families[k]).normal_stiffness;
            ContactAt3 { blocks: [c.a as usize, c.b as usize], centre, normal: mat(&s.rot[c.a as usize], c.frame[0]), area, gap }
        })
        .collect()
}
