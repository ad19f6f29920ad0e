//! A 3D block: a convex polyhedron, from its vertices (their convex hull) or from its faces.

use super::vec3::{cross, dot, norm, sub, unit};
use super::{Aabb, Defect, Volume};

/// A face of a [`Polyhedron`]: its vertices (indices into the polyhedron's), counter-clockwise
/// seen from outside, with no two closer than the tolerance and none on the line through its
/// neighbours; its outward unit normal and its plane's offset (`normal . x = offset` on it).
#[derive(Debug, Clone, PartialEq)]
pub struct Face {
    /// The face's vertices, indices into [`Polyhedron::vertices`], counter-clockwise seen from
    /// outside.
    pub vertices: Vec<usize>,
    /// The outward unit normal.
    pub normal: [f64; 3],
    /// `normal . x` on the face's plane \[m\].
    pub offset: f64,
}

/// A block in space: a convex polyhedron, its vertices \[m\] and its faces.
///
/// Made by [`Polyhedron::hull`] (the convex hull of vertices), [`Polyhedron::from_faces`] (faces
/// given as vertex lists, checked planar and on the hull) or [`Polyhedron::cuboid`] (a box with
/// sides along the axes, whose faces are made directly: exact normals and offsets). Every face
/// is counter-clockwise seen from outside.
#[derive(Debug, Clone, PartialEq)]
pub struct Polyhedron {
    vertices: Vec<[f64; 3]>,
    faces: Vec<Face>,
}

/// The faces of a cuboid as vertex indices (bit 0 of an index: x max, bit 1: y max, bit 2: z
/// max), each counter-clockwise seen from outside, with their outward axis: -z, +z, -x, +x, -y, +y.
/// The most points [`Polyhedron::hull`] takes (a block's vertices, given or those of its faces):
/// 100 points take it about 0.07 s, 200 about 1.2 s.
pub const MAX_HULL_POINTS: usize = 100;

const CUBOID_FACES: [([usize; 4], usize, bool); 6] = [
    ([0, 2, 3, 1], 2, false),
    ([4, 5, 7, 6], 2, true),
    ([0, 4, 6, 2], 0, false),
    ([1, 3, 7, 5], 0, true),
    ([0, 1, 5, 4], 1, false),
    ([2, 6, 7, 3], 1, true),
];

impl Polyhedron {
    /// The box from corner `min` to corner `max` \[m\] (not checked: the caller's box is).
    pub fn cuboid(min: [f64; 3], max: [f64; 3]) -> Polyhedron {
        let vertices = (0..8)
            .map(|i| std::array::from_fn(|k| if i >> k & 1 == 1 { max[k] } else { min[k] }))
            .collect();
        let faces = CUBOID_FACES
            .iter()
            .map(|&(v, axis, plus)| {
                let mut normal = [0.0; 3];
                normal[axis] = if plus { 1.0 } else { -1.0 };
                let offset = if plus { max[axis] } else { -min[axis] };
                Face { vertices: v.to_vec(), normal, offset }
            })
            .collect();
        Polyhedron { vertices, faces }
    }

    /// The prism of the convex polygon `section` of the plane (x, z) (its vertices
    /// counter-clockwise with x to the right and z up, as a [`super::Polygon`]'s (x, y)) between
    /// the planes y = `y[0]` and y = `y[1]` \[m\] (not checked: the caller's polygon and y0 < y1
    /// are): an arch's voussoir extruded along the arch's axis. Its faces are made directly: the
    /// two ends, normal to y exactly, then one side per edge of the section, in its order.
    pub fn prism(section: &[[f64; 2]], y: [f64; 2]) -> Polyhedron {
        let n = section.len();
        let vertices: Vec<[f64; 3]> = y.iter().flat_map(|&y| section.iter().map(move |v| [v[0], y, v[1]])).collect();
        // seen from -y the section turns counter-clockwise: the end at y0 keeps its order
        let mut rings: Vec<Vec<usize>> = vec![(0..n).collect(), (n..2 * n).rev().collect()];
        rings.extend((0..n).map(|k| vec![k, n + k, n + (k + 1) % n, (k + 1) % n]));
        Polyhedron::from_rings(vertices, rings)
    }

    /// The convex polyhedron of `vertices` \[m\] whose faces are `rings` (indices into the
    /// vertices, each counter-clockwise seen from outside), their normals and offsets computed
    /// (not checked: the generators' blocks, convex by construction).
    pub(crate) fn from_rings(vertices: Vec<[f64; 3]>, rings: Vec<Vec<usize>>) -> Polyhedron {
        let faces = rings.into_iter().map(|r| face(&vertices, r)).collect();
        Polyhedron { vertices, faces }
    }

    /// The convex hull of `points` \[m\], or why there is none. `tol` \[m\] (the model's contact
    /// tolerance): points within `tol` of one another are one vertex, points within `tol` of a
    /// face's plane lie on it, and a point inside the hull or on a face or an edge between its
    /// corners is no vertex. Refused: a coordinate not finite (naming the point), fewer than 4
    /// points not on one plane.
    ///
    /// Each face is the plane through three of the points that has every point on one side
    /// (within `tol`): O(n^4) in the number of points, for the few points of a block; more than
    /// [`MAX_HULL_POINTS`] points are refused.
    pub fn hull(points: &[[f64; 3]], tol: f64) -> Result<Polyhedron, Defect> {
        if points.len() > MAX_HULL_POINTS {
            return Err(Defect {
                vertex: None,
                reason: format!(
                    "{} vertices: a block takes at most {MAX_HULL_POINTS} (its hull is found by the planes through triples of them, in a time that grows as their number to the fourth power); give its corners, not a cloud of points",
                    points.len()
                ),
            });
        }
        for (k, p) in points.iter().enumerate() {
            if let Some(v) = p.iter().find(|v| !v.is_finite()) {
                return Err(Defect { vertex: Some(k), reason: format!("vertex {k} {}: coordinate {v} is not finite", point(*p)) });
            }
        }
        let mut distinct: Vec<[f64; 3]> = Vec::with_capacity(points.len());
        for &p in points {
            if distinct.iter().all(|&q| norm(sub(p, q)) > tol) {
                distinct.push(p);
            }
        }
        solid(&distinct, tol).map_err(|reason| Defect { vertex: None, reason: format!("{reason} ({} distinct of the {} given)", distinct.len(), points.len()) })?;
        let p = &distinct;
        let n = p.len();
        // candidate faces: the points on each supporting plane, and its outward normal
        let mut faces: Vec<(Vec<usize>, [f64; 3])> = vec![];
        for i in 0..n {
            for j in i + 1..n {
                for k in j + 1..n {
                    if faces.iter().any(|(on, _)| on.contains(&i) && on.contains(&j) && on.contains(&k)) {
                        continue;
                    }
                    let c = cross(sub(p[j], p[i]), sub(p[k], p[i]));
                    let longest = [norm(sub(p[j], p[i])), norm(sub(p[k], p[i])), norm(sub(p[k], p[j]))].into_iter().fold(0.0, f64::max);
                    if norm(c) <= 2.0 * tol * longest {
                        continue; // a triangle thinner than the tolerance has no plane
                    }
                    let u = unit(c);
                    let d = dot(u, p[i]);
                    let (lo, hi) = p.iter().map(|&q| dot(u, q) - d).fold((0.0f64, 0.0f64), |(lo, hi), s| (lo.min(s), hi.max(s)));
                    let outward = if hi <= tol {
                        u
                    } else if lo >= -tol {
                        u.map(|v| -v)
                    } else {
                        continue; // points on both sides: not a face
                    };
                    let on: Vec<usize> = (0..n).filter(|&q| (dot(u, p[q]) - d).abs() <= tol).collect();
                    // the same face from another triple, its plane tilted within the tolerance
                    if let Some(f) = faces.iter_mut().find(|(g, m)| dot(*m, outward) > 0.0 && on.iter().filter(|q| g.contains(q)).count() >= 3) {
                        for q in on {
                            if !f.0.contains(&q) {
                                f.0.push(q);
                            }
                        }
                    } else {
                        faces.push((on, outward));
                    }
                }
            }
        }
        let mut used = vec![usize::MAX; n];
        let mut vertices = vec![];
        let mut out = Vec::with_capacity(faces.len());
        for (on, normal) in faces {
            let ring = ring(p, &on, normal, tol);
            if ring.len() < 3 {
                continue;
            }
            let ring: Vec<usize> = ring
                .into_iter()
                .map(|q| {
                    if used[q] == usize::MAX {
                        used[q] = vertices.len();
                        vertices.push(p[q]);
                    }
                    used[q]
                })
                .collect();
            out.push(face(&vertices, ring));
        }
        Ok(Polyhedron { vertices, faces: out })
    }

    /// The convex polyhedron whose faces are `faces` (each a list of its vertices \[m\], either
    /// way round), or why there is none: a coordinate not finite, a face of fewer than 3
    /// vertices, without area or not planar within `tol` (naming the face and its vertex
    /// farthest from the plane), vertices with no volume, or a face that is not on the convex
    /// hull of all the vertices (the block is not convex).
    pub fn from_faces(faces: &[Vec<[f64; 3]>], tol: f64) -> Result<Polyhedron, Defect> {
        let defect = |reason: String| Defect { vertex: None, reason };
        for (f, vs) in faces.iter().enumerate() {
            if let Some((k, v)) = vs.iter().enumerate().find_map(|(k, p)| p.iter().find(|v| !v.is_finite()).map(|v| (k, v))) {
                return Err(defect(format!("face {f}, vertex {k} {}: coordinate {v} is not finite", point(vs[k]))));
            }
            if vs.len() < 3 {
                return Err(defect(format!("face {f} has {} vertices: a face needs 3 at least", vs.len())));
            }
            let n = fan_normal(vs);
            let size = vs.iter().map(|&q| norm(sub(q, vs[0]))).fold(0.0, f64::max);
            if norm(n) <= tol * size {
                return Err(defect(format!("face {f} has no area: its vertices lie on one line")));
            }
            let u = unit(n);
            let (k, off) = vs.iter().enumerate().map(|(k, &q)| (k, dot(u, sub(q, vs[0])).abs())).fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
            if off > tol {
                return Err(defect(format!(
                    "face {f} is not planar: its vertex {k} {} is {off:e} m off the plane of the face (tolerance {tol:e} m)",
                    point(vs[k])
                )));
            }
        }
        let all: Vec<[f64; 3]> = faces.iter().flatten().copied().collect();
        let hull = Polyhedron::hull(&all, tol)?;
        for (f, vs) in faces.iter().enumerate() {
            let u = unit(fan_normal(vs));
            let on_hull = hull.faces.iter().any(|h| dot(h.normal, u).abs() > 0.5 && vs.iter().all(|&q| (dot(h.normal, q) - h.offset).abs() <= tol));
            if !on_hull {
                return Err(defect(format!("face {f} is not on the convex hull of the vertices: the block is not convex")));
            }
        }
        Ok(hull)
    }

    /// The box, if the polyhedron is one with sides along the axes (six faces whose normals are
    /// the axes).
    pub fn as_box(&self) -> Option<Aabb<3>> {
        let axial = |n: [f64; 3]| n.iter().filter(|&&v| v == 0.0).count() == 2;
        (self.faces.len() == 6 && self.vertices.len() == 8 && self.faces.iter().all(|f| axial(f.normal))).then(|| self.aabb())
    }

    /// The vertices \[m\].
    pub fn vertices(&self) -> &[[f64; 3]] {
        &self.vertices
    }

    /// The faces, each counter-clockwise seen from outside.
    pub fn faces(&self) -> &[Face] {
        &self.faces
    }

    /// The vertices of face `f` \[m\], counter-clockwise seen from outside.
    pub fn face_points(&self, f: usize) -> impl Iterator<Item = [f64; 3]> + '_ {
        self.faces[f].vertices.iter().map(|&v| self.vertices[v])
    }

    /// The box around the polyhedron.
    pub fn aabb(&self) -> Aabb<3> {
        Aabb::around(&self.vertices)
    }

    /// Volume, centroid and second moments ([`Volume::of`]).
    pub fn volume_properties(&self) -> Volume {
        Volume::of(self)
    }

    /// The polyhedron with every vertex moved by `f`, a rigid motion (a rotation and a
    /// translation: the faces keep their order, their normals and offsets follow).
    pub fn map(&self, f: impl Fn([f64; 3]) -> [f64; 3]) -> Polyhedron {
        let vertices: Vec<[f64; 3]> = self.vertices.iter().map(|&v| f(v)).collect();
        let faces = self.faces.iter().map(|g| face(&vertices, g.vertices.clone())).collect();
        Polyhedron { vertices, faces }
    }

    /// The part of the polyhedron on the side `normal . x <= offset` of a plane (`normal` need
    /// not be a unit vector; `offset` is in its units times metres), or `None` if nothing with a
    /// volume is left. `tol` \[m\] (the model's contact tolerance): a vertex within `tol` of the
    /// plane lies on it. A plane that leaves every vertex on the kept side (within `tol`: it
    /// misses the block or touches it) gives the block itself, unchanged; one that leaves every
    /// vertex on the other side (within `tol`), or a part thinner than `tol`, gives `None`.
    /// Otherwise the part is the convex hull ([`Polyhedron::hull`]) of the kept vertices and of
    /// the points where the plane crosses the edges: its volume, centroid and inertia follow
    /// exactly, and the cut face lies on the plane (its vertices within rounding of it), so that
    /// two blocks cut by one plane from either side share that face.
    pub fn clip(&self, normal: [f64; 3], offset: f64, tol: f64) -> Option<Polyhedron> {
        let scale = norm(normal);
        let side: Vec<f64> = self.vertices.iter().map(|&v| (dot(normal, v) - offset) / scale).collect();
        if side.iter().all(|&s| s <= tol) {
            return Some(self.clone());
        }
        if side.iter().all(|&s| s >= -tol) {
            return None;
        }
        let mut points: Vec<[f64; 3]> = self.vertices.iter().zip(&side).filter(|(_, &s)| s <= tol).map(|(&v, _)| v).collect();
        for f in &self.faces {
            let ring = &f.vertices;
            for (k, &a) in ring.iter().enumerate() {
                let b = ring[(k + 1) % ring.len()];
                // each edge once (it is in two faces, once each way), where it crosses the plane
                if a < b && (side[a] < -tol && side[b] > tol || side[a] > tol && side[b] < -tol) {
                    let t = side[a] / (side[a] - side[b]);
                    let (p, q) = (self.vertices[a], self.vertices[b]);
                    points.push(std::array::from_fn(|i| p[i] + t * (q[i] - p[i])));
                }
            }
        }
        Polyhedron::hull(&points, tol).ok()
    }

    /// The polyhedron for messages: "(polyhedron of 8 vertices: (x, y, z), (x, y, z), ...)".
    pub fn label(&self) -> String {
        let shown: Vec<String> = self.vertices.iter().take(2).map(|&v| point(v)).collect();
        let more = if self.vertices.len() > 2 { ", ..." } else { "" };
        format!("(polyhedron of {} vertices: {}{more})", self.vertices.len(), shown.join(", "))
    }
}

/// "(x, y, z)" for messages.
fn point(p: [f64; 3]) -> String {
    let c = p.map(crate::geometry::coord);
    format!("({}, {}, {})", c[0], c[1], c[2])
}

/// Why points `p` (distinct) bound no volume, if they do not: fewer than 4 of them off one plane.
fn solid(p: &[[f64; 3]], tol: f64) -> Result<(), String> {
    let none = "fewer than 4 vertices off one plane: it has no volume";
    let farthest = |d: &dyn Fn([f64; 3]) -> f64| p.iter().map(|&q| (d(q), q)).fold((0.0, p[0]), |a, b| if b.0 > a.0 { b } else { a });
    if p.len() < 4 {
        return Err(none.into());
    }
    let (d1, p1) = farthest(&|q| norm(sub(q, p[0])));
    let e = unit(sub(p1, p[0]));
    let (d2, p2) = farthest(&|q| norm(cross(sub(q, p[0]), e)));
    let n = unit(cross(sub(p1, p[0]), sub(p2, p[0])));
    let (d3, _) = farthest(&|q| dot(sub(q, p[0]), n).abs());
    if d1 <= tol || d2 <= tol || d3 <= tol {
        return Err(none.into());
    }
    Ok(())
}

/// The sum of the fan's cross products from the first vertex: twice the area times the unit
/// normal of a planar polygon (counter-clockwise about it). Zero components stay zero for a
/// face normal to an axis.
fn fan_normal(v: &[[f64; 3]]) -> [f64; 3] {
    let mut n = [0.0; 3];
    for w in v[1..].windows(2) {
        let c = cross(sub(w[0], v[0]), sub(w[1], v[0]));
        (0..3).for_each(|k| n[k] += c[k]);
    }
    n
}

/// The face of `vertices` on the ring `ring` (counter-clockwise from outside): its normal from
/// the fan, its offset the largest of its vertices' (each within the tolerance of it).
fn face(vertices: &[[f64; 3]], ring: Vec<usize>) -> Face {
    let pts: Vec<[f64; 3]> = ring.iter().map(|&v| vertices[v]).collect();
    let normal = unit(fan_normal(&pts));
    let offset = pts.iter().map(|&q| dot(normal, q)).fold(f64::MIN, f64::max);
    Face { vertices: ring, normal, offset }
}

/// The points `on` of one face, counter-clockwise about `normal`: their convex hull in the
/// face's plane (Andrew's monotone chain), corners within `tol` of the line through their
/// neighbours dropped.
fn ring(p: &[[f64; 3]], on: &[usize], normal: [f64; 3], tol: f64) -> Vec<usize> {
    let (t1, t2) = frame(normal);
    let uv = |q: usize| [dot(p[q], t1), dot(p[q], t2)];
    let mut idx = on.to_vec();
    idx.sort_by(|&a, &b| uv(a).partial_cmp(&uv(b)).expect("finite"));
    // how far c lies to the left of the line from a to b
    let left = |a: usize, b: usize, c: usize| {
        let (a, b, c) = (uv(a), uv(b), uv(c));
        let d = [b[0] - a[0], b[1] - a[1]];
        let l = d[0].hypot(d[1]);
        (d[0] * (c[1] - a[1]) - d[1] * (c[0] - a[0])) / l
    };
    let mut hull: Vec<usize> = Vec::with_capacity(2 * idx.len());
    for pass in 0..2 {
        let floor = hull.len();
        let seq: Vec<usize> = if pass == 0 { idx.clone() } else { idx.iter().rev().copied().collect() };
        for q in seq {
            while hull.len() >= floor + 2 && left(hull[hull.len() - 2], hull[hull.len() - 1], q) <= tol {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

/// Two unit tangents of the plane normal to `n` (a unit vector), with `t1 x t2 = n`: `t1`
/// horizontal (`e_z x n` over its length) unless `n` is within 1e-6 of vertical, then `e_x`
/// less its part along `n`. For an axis: +x under +z, +y beside +x, -x beside +y, exactly.
pub(crate) fn frame(n: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let t1 = if n[0].hypot(n[1]) > 1e-6 { unit([-n[1], n[0], 0.0]) } else { unit([1.0 - n[0] * n[0], -n[0] * n[1], -n[0] * n[2]]) };
    (t1, cross(n, t1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const TOL: f64 = 1e-9;

    fn corners(min: [f64; 3], max: [f64; 3]) -> Vec<[f64; 3]> {
        Polyhedron::cuboid(min, max).vertices().to_vec()
    }

    /// Every face's vertices lie on its plane, every vertex on the inner side of every face,
    /// and each face turns counter-clockwise about its outward normal.
    fn well_formed(p: &Polyhedron) {
        for f in p.faces() {
            let pts: Vec<[f64; 3]> = f.vertices.iter().map(|&v| p.vertices()[v]).collect();
            assert!(pts.iter().all(|&q| (dot(f.normal, q) - f.offset).abs() < 1e-9), "{f:?}");
            assert!(p.vertices().iter().all(|&q| dot(f.normal, q) <= f.offset + 1e-9));
            assert!(dot(fan_normal(&pts), f.normal) > 0.0);
        }
    }

    #[test]
    fn a_box_from_its_corners_is_the_cuboid() {
        let (min, max) = ([0.1, -0.3, 2.0], [0.5, 0.2, 2.175]);
        let hull = Polyhedron::hull(&corners(min, max), TOL).unwrap();
        well_formed(&hull);
        assert_eq!(hull.vertices().len(), 8);
        assert_eq!(hull.faces().len(), 6);
        // the normals are the axes and the offsets the coordinates, exactly
        let mut planes: Vec<([f64; 3], f64)> = hull.faces().iter().map(|f| (f.normal, f.offset)).collect();
        let mut exact: Vec<([f64; 3], f64)> = Polyhedron::cuboid(min, max).faces().iter().map(|f| (f.normal, f.offset)).collect();
        planes.sort_by(|a, b| a.partial_cmp(b).unwrap());
        exact.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(planes, exact);
        well_formed(&Polyhedron::cuboid(min, max));
    }

    #[test]
    fn a_prism_is_the_hull_of_its_section_at_both_ends() {
        // a voussoir-like pentagon of the (x, z) plane, 0.25 m deep along y
        let section = [[1.0, 0.0], [1.4, 0.1], [1.3, 0.5], [1.0, 0.6], [0.9, 0.3]];
        let prism = Polyhedron::prism(&section, [-0.1, 0.15]);
        well_formed(&prism);
        let ends: Vec<[f64; 3]> = [-0.1, 0.15].iter().flat_map(|&y| section.iter().map(move |v| [v[0], y, v[1]])).collect();
        let hull = Polyhedron::hull(&ends, TOL).unwrap();
        let (a, b) = (prism.volume_properties(), hull.volume_properties());
        let area = crate::shape::Area::of(&section);
        assert!((a.volume - 0.25 * area.area).abs() < 1e-15, "{} against {}", a.volume, 0.25 * area.area);
        assert!((a.volume - b.volume).abs() < 1e-15 && (0..3).all(|k| (a.centroid[k] - b.centroid[k]).abs() < 1e-15));
        assert!((a.centroid[0] - area.centroid[0]).abs() < 1e-15 && (a.centroid[2] - area.centroid[1]).abs() < 1e-15);
        assert_eq!(prism.faces()[0].normal, [0.0, -1.0, 0.0]);
        assert_eq!(prism.faces()[1].normal, [0.0, 1.0, 0.0]);
    }

    #[test]
    fn points_on_faces_and_edges_inside_or_repeated_are_no_vertices() {
        let mut pts = corners([0.0; 3], [1.0, 2.0, 3.0]);
        pts.extend([[0.5, 1.0, 1.5], [0.5, 0.0, 0.0], [0.5, 1.0, 3.0], [1.0, 1.0, 1.0], [1.0 + 1e-11, 2.0, 3.0], [0.0, 0.0, 3e-10]]);
        let hull = Polyhedron::hull(&pts, TOL).unwrap();
        well_formed(&hull);
        assert_eq!((hull.vertices().len(), hull.faces().len()), (8, 6));
        assert!(hull.faces().iter().all(|f| f.vertices.len() == 4));
    }

    #[test]
    fn near_degenerate_boxes_keep_six_faces() {
        // each corner moved by up to a tenth of the tolerance: still a box of six quadrilaterals
        let mut pts = corners([0.0; 3], [0.4, 0.1, 0.2]);
        for (i, p) in pts.iter_mut().enumerate() {
            p[i % 3] += 1e-10 * ((i * 7 % 5) as f64 - 2.0) / 2.0;
        }
        let hull = Polyhedron::hull(&pts, TOL).unwrap();
        well_formed(&hull);
        assert_eq!(hull.faces().len(), 6);
        assert!(hull.faces().iter().all(|f| f.vertices.len() == 4));
        // a box thinner than the tolerance has no volume
        let flat = Polyhedron::hull(&corners([0.0; 3], [1.0, 1.0, 5e-10]), TOL).unwrap_err();
        assert!(flat.reason.contains("fewer than 4 vertices off one plane"), "{}", flat.reason);
    }

    #[test]
    fn what_is_no_solid_is_refused_by_name() {
        let e = Polyhedron::hull(&[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], TOL).unwrap_err();
        assert!(e.reason.starts_with("fewer than 4 vertices off one plane: it has no volume (3 distinct of the 3 given)"), "{}", e.reason);
        let square = [[0.0; 3], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [0.5, 0.5, 0.0]];
        assert!(Polyhedron::hull(&square, TOL).unwrap_err().reason.contains("no volume"));
        let e = Polyhedron::hull(&[[0.0; 3], [1.0, 0.0, 0.0], [0.0, f64::NAN, 0.0], [0.0, 0.0, 1.0]], TOL).unwrap_err();
        assert_eq!(e.vertex, Some(2));
        assert_eq!(e.reason, "vertex 2 (0, NaN, 0): coordinate NaN is not finite");
        // more points than the hull takes, before any is read
        let cloud: Vec<[f64; 3]> = (0..=MAX_HULL_POINTS).map(|k| [k as f64, (k * k) as f64, f64::NAN]).collect();
        let e = Polyhedron::hull(&cloud, TOL).unwrap_err();
        assert!(e.reason.starts_with("101 vertices: a block takes at most 100 "), "{}", e.reason);
        assert_eq!(e.vertex, None);
    }

    #[test]
    fn faces_are_checked_planar_and_convex() {
        let cube = Polyhedron::cuboid([0.0; 3], [1.0; 3]);
        let faces: Vec<Vec<[f64; 3]>> = (0..6).map(|f| cube.face_points(f).collect()).collect();
        let p = Polyhedron::from_faces(&faces, TOL).unwrap();
        well_formed(&p);
        assert_eq!(p.faces().len(), 6);
        // the top face warped: its third vertex 1 mm up
        let mut warped = faces.clone();
        warped[1][2][2] += 1e-3;
        let e = Polyhedron::from_faces(&warped, TOL).unwrap_err();
        assert!(e.reason.starts_with("face 1 is not planar: its vertex "), "{}", e.reason);
        // a face through the inside: not on the hull
        let mut inside = faces.clone();
        inside.push(vec![[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, 1.0, 1.0], [0.0, 0.0, 1.0]]);
        let e = Polyhedron::from_faces(&inside, TOL).unwrap_err();
        assert_eq!(e.reason, "face 6 is not on the convex hull of the vertices: the block is not convex");
        let e = Polyhedron::from_faces(&[vec![[0.0; 3], [1.0, 0.0, 0.0]]], TOL).unwrap_err();
        assert_eq!(e.reason, "face 0 has 2 vertices: a face needs 3 at least");
        let mut nan = faces;
        nan[3][1][0] = f64::INFINITY;
        assert_eq!(Polyhedron::from_faces(&nan, TOL).unwrap_err().reason, "face 3, vertex 1 (inf, 1, 0): coordinate inf is not finite");
    }

    #[test]
    fn frames_of_the_axes_are_exact() {
        assert_eq!(frame([0.0, 0.0, 1.0]), ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]));
        assert_eq!(frame([1.0, 0.0, 0.0]), ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0]));
        assert_eq!(frame([0.0, 1.0, 0.0]), ([-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]));
    }

    #[test]
    fn a_box_cut_by_a_diagonal_plane_is_the_prism_of_a_triangle() {
        // the box [0, 2] x [0, 1] x [0, 3] cut by the vertical plane x + 2 y = 2 (through its
        // corners (2, 0) and (0, 1) in plan): kept, the triangle (0, 0), (2, 0), (0, 1) in plan
        // times the height, volume 1 x 3, centroid (2/3, 1/3, 3/2)
        let b = Polyhedron::cuboid([0.0; 3], [2.0, 1.0, 3.0]);
        let cut = b.clip([1.0, 2.0, 0.0], 2.0, TOL).unwrap();
        well_formed(&cut);
        assert!(closed(&cut));
        assert_eq!((cut.vertices().len(), cut.faces().len()), (6, 5));
        let v = cut.volume_properties();
        assert!((v.volume - 3.0).abs() < 1e-14, "{}", v.volume);
        for (got, want) in v.centroid.iter().zip([2.0 / 3.0, 1.0 / 3.0, 1.5]) {
            assert!((got - want).abs() < 1e-14, "{:?}", v.centroid);
        }
        // the other side: the complementary prism, and the two share the cut face
        let other = b.clip([-1.0, -2.0, 0.0], -2.0, TOL).unwrap();
        let w = other.volume_properties();
        assert!((w.volume - 3.0).abs() < 1e-14);
        for (got, want) in w.centroid.iter().zip([4.0 / 3.0, 2.0 / 3.0, 1.5]) {
            assert!((got - want).abs() < 1e-14, "{:?}", w.centroid);
        }
        assert_eq!(crate::shape::face_contacts(&cut, &other, TOL).len(), 1);
        // the inertia of the prism: a right triangle's polar moments times the height, plus the
        // height's: about the vertical axis through the centroid, (area/18)(a^2 + b^2) h for
        // legs a = 2, b = 1 (per unit density)
        let izz = 3.0 / 18.0 * (4.0 + 1.0);
        assert!((v.inertia[2][2] - izz).abs() < 1e-13, "{} against {izz}", v.inertia[2][2]);
        // a tilted cut through the box's top edge x = 2, z = 3 and the bottom edge x = 0, z = 0:
        // half the box
        let half = b.clip([3.0, 0.0, -2.0], 0.0, TOL).unwrap();
        assert!((half.volume_properties().volume - 3.0).abs() < 1e-14);
    }

    #[test]
    fn a_cut_that_misses_keeps_the_block_and_one_that_removes_all_gives_none() {
        let b = Polyhedron::cuboid([0.0; 3], [1.0, 1.0, 1.0]);
        assert_eq!(b.clip([1.0, 0.0, 0.0], 1.5, TOL), Some(b.clone()));
        // touching a face (within the tolerance) keeps it too
        assert_eq!(b.clip([0.0, 0.0, 1.0], 1.0 - 1e-10, TOL), Some(b.clone()));
        assert_eq!(b.clip([1.0, 0.0, 0.0], -0.5, TOL), None);
        // the plane on the face: nothing with a volume is left, nor a sliver thinner than tol
        assert_eq!(b.clip([1.0, 0.0, 0.0], 0.0, TOL), None);
        assert_eq!(b.clip([1.0, 0.0, 0.0], 5e-10, TOL), None);
        // through a corner only: a tetrahedron of volume 1/6
        let tet = b.clip([1.0, 1.0, 1.0], 1.0, TOL).unwrap();
        assert_eq!(tet.vertices().len(), 4);
        assert!((tet.volume_properties().volume - 1.0 / 6.0).abs() < 1e-15);
    }

    /// Euler's V - E + F = 2 of a closed convex surface, each edge shared by two faces.
    fn closed(p: &Polyhedron) -> bool {
        let e2: usize = p.faces().iter().map(|f| f.vertices.len()).sum();
        e2 % 2 == 0 && p.vertices().len() + p.faces().len() == e2 / 2 + 2
    }

    proptest! {
        // random clouds, and box corners jittered by a tenth of the tolerance (each face planar
        // within it): a closed, well-formed surface with every point inside it (within the
        // tolerance). (Jittered by half the tolerance, a face's four corners may lie 2 tol off
        // one plane: it is then two triangles, as the hull of those points is.)
        #[test]
        fn hulls_of_clouds_are_closed_and_hold_every_point(
            cloud in proptest::collection::vec(proptest::array::uniform3(-1.0f64..1.0), 4..40),
            jitter in proptest::collection::vec(proptest::array::uniform3(-1e-10f64..1e-10), 8),
        ) {
            if let Ok(p) = Polyhedron::hull(&cloud, TOL) {
                well_formed(&p);
                prop_assert!(closed(&p), "{:?}", p);
                prop_assert!(cloud.iter().all(|&q| p.faces().iter().all(|f| dot(f.normal, q) <= f.offset + 2.0 * TOL)));
            }
            let corners: Vec<[f64; 3]> = corners([0.0; 3], [0.4, 0.1, 0.2]).iter().zip(&jitter).map(|(c, j)| std::array::from_fn(|k| c[k] + j[k])).collect();
            let p = Polyhedron::hull(&corners, TOL).unwrap();
            well_formed(&p);
            prop_assert!(closed(&p));
            prop_assert_eq!((p.vertices().len(), p.faces().len()), (8, 6));
        }

        // a prism over a regular polygon, turned and moved: its faces are the k sides and the
        // two ends, every one well formed, whatever the order of the points
        #[test]
        fn hulls_of_prisms_have_their_faces(k in 3usize..12, r in 0.05f64..5.0, h in 0.05f64..5.0, a in 0.0f64..6.3, b in 0.0f64..6.3, shift in 0usize..30) {
            let mut pts: Vec<[f64; 3]> = (0..2 * k)
                .map(|i| {
                    let t = a + 2.0 * std::f64::consts::PI * (i % k) as f64 / k as f64;
                    let (x, y, z) = (r * t.cos(), r * t.sin(), if i < k { 0.0 } else { h });
                    // turned by b about x, then moved
                    [x + 3.0, y * b.cos() - z * b.sin() - 1.0, y * b.sin() + z * b.cos() + 10.0]
                })
                .collect();
            let len = pts.len();
            pts.rotate_left(shift % len);
            let p = Polyhedron::hull(&pts, TOL).unwrap();
            well_formed(&p);
            prop_assert_eq!(p.vertices().len(), 2 * k);
            prop_assert_eq!(p.faces().len(), k + 2);
        }
    }
}
