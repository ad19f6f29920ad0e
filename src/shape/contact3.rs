//! Where two convex polyhedra touch: facing coplanar faces that overlap over a positive area (the
//! intersection of the two faces, a convex polygon), and how deep two polyhedra overlap.

use super::polyhedron::frame;
use super::vec3::{cross, dot, norm, sub, unit};
use super::{Area, Polyhedron};

/// Two faces, one of each polyhedron, on one plane (within the tolerance), facing each other,
/// and the convex polygon they share: a contact.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceContact {
    /// The face of the first polyhedron and of the second.
    pub faces: [usize; 2],
    /// The unit normal from the first polyhedron into the second: the bisector of the faces'
    /// outward normals (the first's, and the second's reversed).
    pub n: [f64; 3],
    /// The unit tangents, `t1 x t2 = n`: `t1` horizontal unless the contact is (within 1e-6)
    /// horizontal, then along x. For a normal along an axis: (+x, +y) under +z, (+y, +z) beside
    /// +x, (-x, +z) beside +y.
    pub t1: [f64; 3],
    /// See `t1`.
    pub t2: [f64; 3],
    /// The shared polygon's vertices \[m\], on the plane midway between the faces,
    /// counter-clockwise seen from the tip of `n`, from the one of least `t1 + t2` (the
    /// (-, -) corner of a rectangle along the tangents).
    pub vertices: Vec<[f64; 3]>,
    /// Area \[m2\].
    pub area: f64,
    /// Centroid \[m\], on the plane midway between the faces.
    pub centroid: [f64; 3],
}

/// Every pair of a face of `a` and a face of `b` whose outward normals are opposite (their
/// dot product below -1/2) and whose vertices each lie within `tol` of the other face's plane,
/// gap or overlap, and that share a polygon of area more than `tol` times its diameter (faces
/// that meet along an edge or at a corner share none).
///
/// The shared polygon is face `a` clipped by each edge of face `b` in the plane of the tangents
/// (Sutherland-Hodgman): a point within `tol` of an edge's line is on it, and a cut on a line
/// along a tangent takes the line's coordinate, so that boxes give the coordinates of their
/// corners exactly. Points within `tol` of the one before are merged, and points within `tol`
/// of the line through their neighbours dropped.
pub fn face_contacts(a: &Polyhedron, b: &Polyhedron, tol: f64) -> Vec<FaceContact> {
    facing(a, b, tol).into_iter().filter_map(|[fa, fb]| shared(a, fa, b, fb, tol)).collect()
}

/// The pairs of a face of `a` and a face of `b` that face each other on one plane within `tol`
/// (see [`face_contacts`]), whether they share a polygon or not.
pub fn facing(a: &Polyhedron, b: &Polyhedron, tol: f64) -> Vec<[usize; 2]> {
    let mut out = vec![];
    let near = |p: &Polyhedron, f: usize, n: [f64; 3], off: f64| p.face_points(f).all(|q| (dot(n, q) - off).abs() <= tol);
    for (fa, ga) in a.faces().iter().enumerate() {
        for (fb, gb) in b.faces().iter().enumerate() {
            if dot(ga.normal, gb.normal) < -0.5 && near(b, fb, ga.normal, ga.offset) && near(a, fa, gb.normal, gb.offset) {
                out.push([fa, fb]);
            }
        }
    }
    out
}

/// The unit normal of a contact between face `fa` of `a` and face `fb` of `b`, from `a` into
/// `b`: the bisector of their outward normals (the first's, the second's reversed).
pub fn bisector(a: &Polyhedron, fa: usize, b: &Polyhedron, fb: usize) -> [f64; 3] {
    let (na, nb) = (a.faces()[fa].normal, b.faces()[fb].normal);
    if na == nb.map(|v| -v) {
        na
    } else {
        unit(sub(na, nb))
    }
}

/// The polygon shared by face `fa` of `a` and face `fb` of `b` (facing, coplanar: see
/// [`facing`]), if it has an area (see [`face_contacts`]).
pub fn shared(a: &Polyhedron, fa: usize, b: &Polyhedron, fb: usize, tol: f64) -> Option<FaceContact> {
    let (ga, gb) = (&a.faces()[fa], &b.faces()[fb]);
    let n = bisector(a, fa, b, fb);
    let (t1, t2) = frame(n);
    let (poly, props) = overlap(a, fa, b, fb, [t1, t2], tol)?;
    let plane = 0.5 * (dot(n, a.vertices()[ga.vertices[0]]) + dot(n, b.vertices()[gb.vertices[0]]));
    let lift = |p: [f64; 2]| -> [f64; 3] { std::array::from_fn(|k| n[k] * plane + p[0] * t1[k] + p[1] * t2[k]) };
    let first = (0..poly.len())
        .min_by(|&i, &j| (poly[i][0] + poly[i][1], poly[i][0]).partial_cmp(&(poly[j][0] + poly[j][1], poly[j][0])).expect("finite"))
        .expect("3 vertices at least");
    let vertices = (0..poly.len()).map(|i| lift(poly[(first + i) % poly.len()])).collect();
    Some(FaceContact { faces: [fa, fb], n, t1, t2, vertices, area: props.area, centroid: lift(props.centroid) })
}

/// The polygon face `fa` of `a` and face `fb` of `b` (facing) share seen along the normal of the
/// tangents `t` (coordinates along them), counter-clockwise about `t1 x t2`, with its area and
/// centroid, if it has an area of more than `tol` times its diameter.
fn overlap(a: &Polyhedron, fa: usize, b: &Polyhedron, fb: usize, t: [[f64; 3]; 2], tol: f64) -> Option<(Vec<[f64; 2]>, Area)> {
    let uv = |q: [f64; 3]| [dot(q, t[0]), dot(q, t[1])];
    // face a counter-clockwise about n, face b too once reversed (it is so about -n)
    let mut poly: Vec<[f64; 2]> = a.face_points(fa).map(uv).collect();
    let mut clip: Vec<[f64; 2]> = b.face_points(fb).map(uv).collect();
    clip.reverse();
    let mut next = Vec::with_capacity(poly.len() + clip.len());
    for i in 0..clip.len() {
        let (q0, q1) = (clip[i], clip[(i + 1) % clip.len()]);
        cut(&poly, q0, q1, tol, &mut next);
        std::mem::swap(&mut poly, &mut next);
        if poly.len() < 3 {
            return None;
        }
    }
    let poly = tidy(poly, tol);
    if poly.len() < 3 {
        return None;
    }
    let props = Area::of(&poly);
    let diameter = poly.iter().flat_map(|p| poly.iter().map(move |q| dist2(*p, *q))).fold(0.0, f64::max).sqrt();
    (props.area > tol * diameter).then_some((poly, props))
}

/// Whether `n` points up, or lies (within 1e-9) horizontal and points towards +x, or along y
/// and towards +y: the direction of the normal of a contact, from the block it leaves (the
/// lower one) into the other.
pub(crate) fn upward(n: [f64; 3]) -> bool {
    let e = 1e-9;
    if n[2].abs() > e {
        n[2] > 0.0
    } else if n[0].abs() > e {
        n[0] > 0.0
    } else {
        n[1] > 0.0
    }
}

/// A face of one polyhedron near a face of another, facing it, as they move (see
/// [`facing_faces`]): the polygon of the owner's face over which the other's lies, and where the
/// other's face's plane lies along the normal at its corners.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceFacing {
    /// Which polyhedron's face gives the normal: 0 the first given, 1 the second.
    pub owner: usize,
    /// The face of the first polyhedron and of the second.
    pub faces: [usize; 2],
    /// The owner's face's outward unit normal, from the owner into the other.
    pub n: [f64; 3],
    /// The unit tangents of [`FaceContact`] for `n`.
    pub t1: [f64; 3],
    /// See `t1`.
    pub t2: [f64; 3],
    /// Each corner of the polygon on the owner's face, and the point of the other's face's plane
    /// along `n` from it \[m\] (their distance along `n`: the gap there, negative where they
    /// overlap), counter-clockwise about `n`.
    pub corners: Vec<[[f64; 3]; 2]>,
    /// The polygon's area \[m2\] (on the owner's face).
    pub area: f64,
    /// The polygon's centroid on the owner's face \[m\].
    pub centroid: [f64; 3],
}

/// Every pair of a face of `a` and a face of `b` whose outward normals are opposed within 60
/// degrees, whose projections along the owner's normal share a polygon of area more than `tol`
/// times its diameter, with the other's face no farther than `gap` from the owner's at some
/// corner of it and not inside the owner by more than `gap` or half the depth of either
/// polyhedron behind its face at every corner (a face that deep lies behind the other face, not
/// on it), as [`crate::shape::facing_edges`] in the plane. The owner is the polyhedron the
/// normal leaves as [`crate::space::detect`] orients it (the bisector of the two normals
/// `upward`: the lower one, or the one at smaller x, y). Faces on one plane, facing, give the
/// polygon of [`shared`] (seen along the owner's normal, not their bisector).
pub fn facing_faces(a: &Polyhedron, b: &Polyhedron, gap: f64, tol: f64) -> Vec<FaceFacing> {
    // how far each polyhedron reaches behind each of its faces
    let depth = |p: &Polyhedron, f: usize| {
        let g = &p.faces()[f];
        p.vertices().iter().map(|&v| g.offset - dot(g.normal, v)).fold(0.0, f64::max)
    };
    let mut out = vec![];
    for (fa, ga) in a.faces().iter().enumerate() {
        for (fb, gb) in b.faces().iter().enumerate() {
            if dot(ga.normal, gb.normal) >= -0.5 {
                continue;
            }
            let owner = usize::from(!upward(sub(ga.normal, gb.normal)));
            let ((p, fp), (q, fq)) = if owner == 0 { ((a, fa), (b, fb)) } else { ((b, fb), (a, fa)) };
            let (n, gq) = (p.faces()[fp].normal, &q.faces()[fq]);
            let (t1, t2) = frame(n);
            let Some((poly, props)) = overlap(p, fp, q, fq, [t1, t2], tol) else { continue };
            let off = p.faces()[fp].offset;
            let lift = |x: [f64; 2]| -> [f64; 3] { std::array::from_fn(|k| n[k] * off + x[0] * t1[k] + x[1] * t2[k]) };
            let slope = dot(gq.normal, n);
            let corners: Vec<[[f64; 3]; 2]> = poly
                .iter()
                .map(|&x| {
                    let on = lift(x);
                    let s = (gq.offset - dot(gq.normal, on)) / slope;
                    [on, std::array::from_fn(|k| on[k] + s * n[k])]
                })
                .collect();
            let gaps = corners.iter().map(|[o, x]| dot(sub(*x, *o), n));
            let (lo, hi) = gaps.fold((f64::MAX, f64::MIN), |(lo, hi), s| (lo.min(s), hi.max(s)));
            let deep = gap.min(0.5 * depth(p, fp).min(depth(q, fq)));
            if lo > gap || hi < -deep {
                continue;
            }
            let faces = if owner == 0 { [fa, fb] } else { [fb, fa] };
            out.push(FaceFacing { owner, faces, n, t1, t2, corners, area: props.area, centroid: lift(props.centroid) });
        }
    }
    out
}

/// Face `f` of `p` as a contact polygon with a body beyond it: its corners (counter-clockwise
/// from outside), its area \[m2\] and its centroid \[m\].
pub fn face_patch(p: &Polyhedron, f: usize) -> (Vec<[f64; 3]>, f64, [f64; 3]) {
    let g = &p.faces()[f];
    let (t1, t2) = frame(g.normal);
    let uv: Vec<[f64; 2]> = p.face_points(f).map(|q| [dot(q, t1), dot(q, t2)]).collect();
    let props = Area::of(&uv);
    let c = props.centroid;
    (p.face_points(f).collect(), props.area, std::array::from_fn(|k| g.normal[k] * g.offset + c[0] * t1[k] + c[1] * t2[k]))
}

/// The convex polygon `poly` (counter-clockwise) less what lies right of the line from `q0` to
/// `q1`, beyond `tol`: a point within `tol` of the line is kept; an edge is cut only where its
/// ends lie beyond `tol` on either side, the cut clamped between them, and on a line along an
/// axis of the plane the cut takes the line's coordinate.
fn cut(poly: &[[f64; 2]], q0: [f64; 2], q1: [f64; 2], tol: f64, out: &mut Vec<[f64; 2]>) {
    let e = [q1[0] - q0[0], q1[1] - q0[1]];
    let len = dist2(q0, q1).sqrt();
    let side = |p: [f64; 2]| (e[0] * (p[1] - q0[1]) - e[1] * (p[0] - q0[0])) / len;
    out.clear();
    for i in 0..poly.len() {
        let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
        let (sp, sq) = (side(p), side(q));
        if sp >= -tol {
            out.push(p);
        }
        if (sp > tol && sq < -tol) || (sp < -tol && sq > tol) {
            let t = (sp / (sp - sq)).clamp(0.0, 1.0);
            let mut x = [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])];
            if e[0] == 0.0 {
                x[0] = q0[0];
            } else if e[1] == 0.0 {
                x[1] = q0[1];
            }
            out.push(x);
        }
    }
}

/// The square of the distance from `p` to `q`.
fn dist2(p: [f64; 2], q: [f64; 2]) -> f64 {
    (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1])
}

/// `poly` with points within `tol` of the one before merged (the last and the first too) and
/// points within `tol` of the line through their neighbours dropped.
fn tidy(poly: Vec<[f64; 2]>, tol: f64) -> Vec<[f64; 2]> {
    let dist = |p: [f64; 2], q: [f64; 2]| dist2(p, q).sqrt();
    let mut v: Vec<[f64; 2]> = Vec::with_capacity(poly.len());
    for p in poly {
        if v.last().map_or(true, |&q| dist(p, q) > tol) {
            v.push(p);
        }
    }
    while v.len() > 1 && dist(v[0], v[v.len() - 1]) <= tol {
        v.pop();
    }
    let mut i = 0;
    while v.len() >= 3 && i < v.len() {
        let k = v.len();
        let (p, q, r) = (v[(i + k - 1) % k], v[i], v[(i + 1) % k]);
        let l = dist(p, r);
        let off = ((r[0] - p[0]) * (q[1] - p[1]) - (r[1] - p[1]) * (q[0] - p[0])).abs() / l;
        if l <= tol || off <= tol {
            v.remove(i);
            i = i.saturating_sub(1);
        } else {
            i += 1;
        }
    }
    v
}

/// Where `a` and `b` touch along an edge or at a point (within `tol` \[m\]) rather than over a
/// polygon: an edge or a vertex of one on a face of the other, the face's plane parting the two
/// (every vertex of the other on its outer side, within `tol`). These are the contacts of blocks
/// moved by finite rotations: a box turned about its toe stands on the toe's edge alone. The
/// contact is a [`FaceContact`] of area 0: its normal the face's (from `a` into `b`), its
/// vertices the ends of the edge clipped to the face (two) or the point (one), on the face's
/// plane; `faces` the face that gives the normal and `usize::MAX` for the other's. Two convex
/// blocks that touch meet in one convex set: the first such face is the contact (an edge of
/// each crossing the other's, at a point, is not found). Where an edge or a vertex of each lies
/// on a face of the other (two edges along one line, as two blocks turned about a common edge),
/// the normal is the bisector of the two faces' outward normals (the first's, the second's
/// reversed), as for two polygons' corners at one point in the plane, and `faces` names both.
/// Faces that share a polygon ([`face_contacts`]) are not looked at here.
pub fn corner_contact(a: &Polyhedron, b: &Polyhedron, tol: f64) -> Option<FaceContact> {
    let turned = |c: FaceContact, n: [f64; 3], faces: [usize; 2]| {
        let (t1, t2) = frame(n);
        FaceContact { faces, n, t1, t2, ..c }
    };
    match (on_face(a, b, tol), on_face(b, a, tol)) {
        (Some(c), None) => Some(c),
        (None, Some(c)) => {
            let (n, fb) = (c.n.map(|v| -v), c.faces[0]);
            Some(turned(c, n, [usize::MAX, fb]))
        }
        (Some(c), Some(d)) => {
            let n = if c.n == d.n.map(|v| -v) { c.n } else { unit(sub(c.n, d.n)) };
            let fa = c.faces[0];
            Some(turned(c, n, [fa, d.faces[0]]))
        }
        (None, None) => None,
    }
}

/// An edge or a vertex of `b` on a face of `a` whose plane parts them (see [`corner_contact`]),
/// the normal the face's.
fn on_face(a: &Polyhedron, b: &Polyhedron, tol: f64) -> Option<FaceContact> {
    for (fa, g) in a.faces().iter().enumerate() {
        let gap = |v: [f64; 3]| dot(g.normal, v) - g.offset;
        if b.vertices().iter().any(|&v| gap(v) < -tol) {
            continue;
        }
        let (t1, t2) = frame(g.normal);
        let uv = |q: [f64; 3]| [dot(q, t1), dot(q, t2)];
        let near: Vec<[f64; 2]> = b.vertices().iter().filter(|&&v| gap(v) <= tol).map(|&v| uv(v)).collect();
        // the two points of b's feature farthest apart: its edge's ends, or its vertex twice
        let Some((p, q)) = near.iter().flat_map(|&p| near.iter().map(move |&q| (p, q))).max_by(|x, y| dist2(x.0, x.1).total_cmp(&dist2(y.0, y.1))) else {
            continue;
        };
        let len = dist2(p, q).sqrt();
        let off_line = |r: [f64; 2]| ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])).abs() / len;
        if len > tol && near.iter().any(|&r| off_line(r) > tol) {
            continue; // a face of b: it shares a polygon or nothing
        }
        // the segment p..q clipped to the face (counter-clockwise about its normal): where each
        // edge's side of it, linear along the segment, is at least -tol
        let ring: Vec<[f64; 2]> = a.face_points(fa).map(uv).collect();
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for i in 0..ring.len() {
            let (e0, e1) = (ring[i], ring[(i + 1) % ring.len()]);
            let e = [e1[0] - e0[0], e1[1] - e0[1]];
            let el = dist2(e0, e1).sqrt();
            let side = |r: [f64; 2]| (e[0] * (r[1] - e0[1]) - e[1] * (r[0] - e0[0])) / el + tol;
            let (sp, sq) = (side(p), side(q));
            if sp < 0.0 && sq < 0.0 {
                lo = 1.0;
                hi = 0.0;
                break;
            }
            if sp < 0.0 {
                lo = lo.max(sp / (sp - sq));
            } else if sq < 0.0 {
                hi = hi.min(sp / (sp - sq));
            }
        }
        if lo > hi {
            continue;
        }
        let at = |t: f64| [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])];
        let lift = |r: [f64; 2]| -> [f64; 3] { std::array::from_fn(|k| g.normal[k] * g.offset + r[0] * t1[k] + r[1] * t2[k]) };
        let (r0, r1) = (at(lo), at(hi));
        let vertices = if (hi - lo) * len > tol { vec![lift(r0), lift(r1)] } else { vec![lift(at(0.5 * (lo + hi)))] };
        let centroid = lift([0.5 * (r0[0] + r1[0]), 0.5 * (r0[1] + r1[1])]);
        return Some(FaceContact { faces: [fa, usize::MAX], n: g.normal, t1, t2, vertices, area: 0.0, centroid });
    }
    None
}

/// How deep convex polyhedra `a` and `b` overlap \[m\]: over the separating axes (the faces'
/// normals of both, and the cross products of an edge of each), the least depth (zero or
/// negative when they touch or are apart: some plane parts them). It stops at the first axis
/// whose depth is at most `stop`.
pub fn penetration(a: &Polyhedron, b: &Polyhedron, stop: f64) -> f64 {
    let span = |p: &Polyhedron, n: [f64; 3]| p.vertices().iter().fold((f64::MAX, f64::MIN), |(lo, hi), &v| (lo.min(dot(n, v)), hi.max(dot(n, v))));
    let depth_along = |n: [f64; 3]| {
        let ((alo, ahi), (blo, bhi)) = (span(a, n), span(b, n));
        (ahi - blo).min(bhi - alo)
    };
    let mut depth = f64::INFINITY;
    for f in a.faces().iter().chain(b.faces()) {
        depth = depth.min(depth_along(f.normal));
        if depth <= stop {
            return depth;
        }
    }
    let (ea, eb) = (edges(a), edges(b));
    for &da in &ea {
        for &db in &eb {
            let c = cross(da, db);
            if norm(c) > 1e-9 {
                depth = depth.min(depth_along(unit(c)));
                if depth <= stop {
                    return depth;
                }
            }
        }
    }
    depth
}

/// The unit directions of the edges of `p` (each face's, so each edge twice).
fn edges(p: &Polyhedron) -> Vec<[f64; 3]> {
    let v = p.vertices();
    p.faces()
        .iter()
        .flat_map(|f| (0..f.vertices.len()).map(move |i| unit(sub(v[f.vertices[(i + 1) % f.vertices.len()]], v[f.vertices[i]]))))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const TOL: f64 = 1e-9;

    #[test]
    fn a_box_turned_about_its_toe_stands_on_an_edge_and_a_pyramid_on_its_apex() {
        // a box 0.6 x 0.4 x 1.5 turned by 0.2 rad about its toe edge (the y axis through (0.6, 0,
        // 0)) on a plinth [-1, 2] x [-1, 1] x [-1, 0]: the toe's edge on the plinth's top face,
        // two corners, the normal +z from the plinth into the box; not the plinth's side faces
        let (s, c) = 0.2f64.sin_cos();
        let toe = |p: [f64; 3]| [0.6 + c * (p[0] - 0.6) + s * p[2], p[1], -s * (p[0] - 0.6) + c * p[2]];
        let block = Polyhedron::cuboid([0.0; 3], [0.6, 0.4, 1.5]).map(toe);
        let plinth = Polyhedron::cuboid([-1.0, -1.0, -1.0], [2.0, 1.0, 0.0]);
        assert!(face_contacts(&plinth, &block, TOL).is_empty());
        let found = corner_contact(&plinth, &block, TOL).unwrap();
        assert_eq!((found.n, found.area), ([0.0, 0.0, 1.0], 0.0));
        let mut ends: Vec<[f64; 3]> = found.vertices.clone();
        ends.sort_by(|p, q| p[1].total_cmp(&q[1]));
        for (got, want) in ends.iter().zip([[0.6, 0.0, 0.0], [0.6, 0.4, 0.0]]) {
            assert!((0..3).all(|k| (got[k] - want[k]).abs() < 1e-12), "{got:?}");
        }
        // the other way round: the normal from the box into the plinth
        let back = corner_contact(&block, &plinth, TOL).unwrap();
        assert_eq!(back.n, [0.0, 0.0, -1.0]);
        assert_eq!(back.faces[0], usize::MAX);
        // on a plinth flush with the box's toe, the plinth's edge lies on the box's bottom face
        // too: the normal the bisector of +z and the bottom face's normal turned, tilted by 0.1 rad
        let flush = Polyhedron::cuboid([-1.0, -1.0, -1.0], [0.6, 1.0, 0.0]);
        let both = corner_contact(&flush, &block, TOL).unwrap();
        let (s2, c2) = 0.1f64.sin_cos();
        assert!((both.n[0] - s2).abs() < 1e-12 && both.n[1] == 0.0 && (both.n[2] - c2).abs() < 1e-12, "{:?}", both.n);
        assert_eq!(both.vertices.len(), 2);
        // a pyramid on its apex: one corner; lifted by more than the tolerance: none
        let apex = |dz: f64| Polyhedron::hull(&[[0.5, 0.0, dz], [0.0, -0.5, 1.0], [1.0, -0.5, 1.0], [1.0, 0.5, 1.0], [0.0, 0.5, 1.0]], TOL).unwrap();
        let point = corner_contact(&plinth, &apex(0.0), TOL).unwrap();
        assert_eq!((point.vertices.len(), point.centroid), (1, [0.5, 0.0, 0.0]));
        assert!(corner_contact(&plinth, &apex(1e-6), TOL).is_none());
    }

    fn cube(min: [f64; 3], side: f64) -> Polyhedron {
        Polyhedron::cuboid(min, min.map(|v| v + side))
    }

    /// `p` turned by `angle` about the vertical through `c`.
    fn turned(p: &Polyhedron, angle: f64, c: [f64; 2]) -> Polyhedron {
        let (s, co) = angle.sin_cos();
        p.map(|v| [c[0] + co * (v[0] - c[0]) - s * (v[1] - c[1]), c[1] + s * (v[0] - c[0]) + co * (v[1] - c[1]), v[2]])
    }

    #[test]
    fn cubes_offset_on_a_face_share_their_rectangle_exactly() {
        let (low, high) = (cube([0.0; 3], 1.0), cube([0.3, 0.2, 1.0], 1.0));
        let found = face_contacts(&low, &high, TOL);
        assert_eq!(found.len(), 1);
        let c = &found[0];
        assert_eq!((c.n, c.t1, c.t2), ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]));
        assert_eq!(c.vertices, vec![[0.3, 0.2, 1.0], [1.0, 0.2, 1.0], [1.0, 1.0, 1.0], [0.3, 1.0, 1.0]]);
        assert!((c.area - 0.7 * 0.8).abs() < 1e-15);
        assert!((0..3).all(|k| (c.centroid[k] - [0.65, 0.6, 1.0][k]).abs() < 1e-15));
        // the other way round: the same polygon, the normal down
        let back = face_contacts(&high, &low, TOL);
        assert_eq!(back.len(), 1);
        assert_eq!(back[0].n, [0.0, 0.0, -1.0]);
        assert!((back[0].area - 0.56).abs() < 1e-15);
        // beside each other along y, with a gap within the tolerance
        let side = face_contacts(&cube([0.0; 3], 1.0), &cube([0.5, 1.0 + 1e-10, 0.25], 1.0), TOL);
        assert_eq!(side.len(), 1);
        assert_eq!((side[0].n, side[0].t1, side[0].t2), ([0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]));
        assert!((side[0].area - 0.5 * 0.75).abs() < 1e-15);
        assert_eq!(side[0].vertices[0], [1.0, 1.0 + 0.5e-10, 0.25]);
    }

    #[test]
    fn a_box_on_a_turned_box_shares_an_octagon() {
        // two unit squares, one turned by 45 deg about their common centre: a regular octagon
        // of area 2 (sqrt 2 - 1), whose vertices lie on both squares' sides
        let low = cube([0.0; 3], 1.0);
        let high = turned(&cube([0.0, 0.0, 1.0], 1.0), std::f64::consts::FRAC_PI_4, [0.5, 0.5]);
        let found = face_contacts(&low, &high, TOL);
        assert_eq!(found.len(), 1);
        let c = &found[0];
        assert_eq!(c.vertices.len(), 8);
        let exact = 2.0 * (2f64.sqrt() - 1.0);
        assert!((c.area - exact).abs() < 1e-14, "{} against {exact}", c.area);
        assert!((0..3).all(|k| (c.centroid[k] - [0.5, 0.5, 1.0][k]).abs() < 1e-15));
        // a 3 x 1 plank turned by 30 deg on a 2 x 2 slab, both centred: a hexagon, the slab
        // less two right triangles at opposite corners (legs 1 and 2 cos 30 deg; the plank's edge
        // -x sin 30 + y cos 30 = 1/2 meets x = -1 at y = 0 and y = 1 at x = 2 cos 30 - 1):
        // 4 - 2 cos 30 deg = 4 - sqrt 3
        let slab = Polyhedron::cuboid([-1.0, -1.0, -0.5], [1.0, 1.0, 0.0]);
        let plank = turned(&Polyhedron::cuboid([-1.5, -0.5, 0.0], [1.5, 0.5, 0.5]), std::f64::consts::FRAC_PI_6, [0.0, 0.0]);
        let found = face_contacts(&slab, &plank, TOL);
        assert_eq!(found.len(), 1);
        assert_eq!(found[0].vertices.len(), 6);
        let exact = 4.0 - 3f64.sqrt();
        assert!((found[0].area - exact).abs() < 1e-14, "{} against {exact}", found[0].area);
    }

    #[test]
    fn a_tetrahedron_on_a_cube_shares_its_triangle() {
        let block = cube([0.0; 3], 1.0);
        let tet = Polyhedron::hull(&[[0.2, 0.1, 1.0], [0.9, 0.3, 1.0], [0.4, 0.8, 1.0], [0.5, 0.4, 1.6]], TOL).unwrap();
        let found = face_contacts(&block, &tet, TOL);
        assert_eq!(found.len(), 1);
        let c = &found[0];
        assert_eq!(c.vertices.len(), 3);
        // half the cross product of two sides
        let exact = 0.5 * ((0.9 - 0.2) * (0.8 - 0.1) - (0.3 - 0.1) * (0.4 - 0.2));
        assert!((c.area - exact).abs() < 1e-15, "{} against {exact}", c.area);
        assert!((0..2).all(|k| (c.centroid[k] - [0.5, 0.4][k]).abs() < 1e-15) && c.centroid[2] == 1.0);
        // over the cube's edge, half of it off: the triangle clipped
        let over = tet.map(|p| [p[0] + 0.5, p[1], p[2]]);
        let c = &face_contacts(&block, &over, TOL)[0];
        assert!(c.area < exact && c.vertices.iter().all(|v| v[0] <= 1.0));
    }

    #[test]
    fn edges_corners_and_gaps_make_no_contact() {
        let a = cube([0.0; 3], 1.0);
        // along an edge, at a corner, beyond the tolerance
        assert!(face_contacts(&a, &cube([1.0, 0.0, 1.0], 1.0), TOL).is_empty());
        assert!(face_contacts(&a, &cube([1.0, 1.0, 1.0], 1.0), TOL).is_empty());
        assert!(face_contacts(&a, &cube([0.0, 0.0, 1.0 + 1e-8], 1.0), TOL).is_empty());
        // a sliver narrower than the tolerance
        assert!(face_contacts(&a, &cube([1.0 - 1e-10, 0.0, 1.0], 1.0), TOL).is_empty());
        // tilted beyond the tolerance over the face
        let tilted = cube([0.0, 0.0, 1.0], 1.0).map(|p| [p[0], p[1], p[2] + 1e-6 * p[0]]);
        assert!(face_contacts(&a, &tilted, TOL).is_empty());
    }

    #[test]
    fn overlap_is_measured_and_touching_is_not() {
        let a = cube([0.0; 3], 1.0);
        assert!((penetration(&a, &cube([0.7, 0.2, 0.1], 1.0), f64::MIN) - 0.3).abs() < 1e-15);
        assert!(penetration(&a, &cube([1.0, 0.0, 0.0], 1.0), f64::MIN).abs() < 1e-15);
        assert!(penetration(&a, &cube([1.5, 0.0, 0.0], 1.0), f64::MIN) < -0.4);
        // two unit cubes on edge, ridge across ridge 0.01 apart: no face's normal parts them,
        // the cross product of the ridges does
        let r = 0.5 * 2f64.sqrt();
        let ridge_up = Polyhedron::hull(
            &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, r, r], [1.0, r, r], [0.0, -r, r], [1.0, -r, r], [0.0, 0.0, 2.0 * r], [1.0, 0.0, 2.0 * r]],
            TOL,
        )
        .unwrap();
        // turned a quarter about z and upside down (a proper rotation: (x, y, z) -> (y, x, -z))
        let ridge_down = ridge_up.map(|p| [0.5 + p[1], p[0] - 0.5 + 0.0, 4.0 * r + 0.01 - p[2]]);
        let d = penetration(&ridge_up, &ridge_down, f64::MIN);
        assert!((d + 0.01).abs() < 1e-12, "{d}");
        let into = ridge_down.map(|p| [p[0], p[1], p[2] - 0.03]);
        assert!((penetration(&ridge_up, &into, f64::MIN) - 0.02).abs() < 1e-12);
    }
}
