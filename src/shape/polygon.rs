//! A 2D block: a convex polygon.

use super::{Aabb, Area};
use crate::geometry::{coord, Rect};
use std::f64::consts::PI;

/// A block's outline in the plane: its vertices \[m\], in order around it.
///
/// [`Polygon::new`] keeps the vertices as given (either orientation, any first vertex);
/// [`Polygon::checked`] refuses what is not a convex polygon and gives the polygon every model
/// holds: counter-clockwise, from its lowest vertex (the leftmost of the lowest), with no two
/// vertices closer than the tolerance and no vertex on the line through its neighbours. A
/// rectangle is a polygon of four vertices ([`From<Rect>`]), and goes through the same code.
#[derive(Debug, Clone, PartialEq)]
pub struct Polygon {
    vertices: Vec<[f64; 2]>,
}

/// Why a vertex list is not a convex polygon, and the vertex where it shows (its index in the
/// list as given), if one does.
#[derive(Debug, Clone, PartialEq)]
pub struct Defect {
    /// The vertex at fault, an index into the vertices as given.
    pub vertex: Option<usize>,
    /// What is wrong, a clause that follows the block's name and a colon ("vertex 3 (1, 1) is a
    /// re-entrant corner: ...").
    pub reason: String,
}

impl From<Rect> for Polygon {
    /// The rectangle's corners, counter-clockwise from (x0, y0).
    fn from(r: Rect) -> Polygon {
        Polygon { vertices: vec![[r.x0, r.y0], [r.x1, r.y0], [r.x1, r.y1], [r.x0, r.y1]] }
    }
}

impl Polygon {
    /// The polygon of `vertices` \[m\], as given (see [`Polygon::checked`]).
    pub fn new(vertices: Vec<[f64; 2]>) -> Polygon {
        Polygon { vertices }
    }

    /// The vertices \[m\]: counter-clockwise from the lowest once [`Polygon::checked`].
    pub fn vertices(&self) -> &[[f64; 2]] {
        &self.vertices
    }

    /// The box around the polygon.
    pub fn aabb(&self) -> Aabb<2> {
        Aabb::around(&self.vertices)
    }

    /// Area, centroid and polar second moment ([`Area::of`]), of a checked polygon.
    pub fn area_properties(&self) -> Area {
        Area::of(&self.vertices)
    }

    /// The polygon with every vertex moved by `f` (a rotation, a translation, a mirror: check
    /// it again after a mirror, which reverses it).
    pub fn map(&self, f: impl Fn([f64; 2]) -> [f64; 2]) -> Polygon {
        Polygon { vertices: self.vertices.iter().map(|&v| f(v)).collect() }
    }

    /// The rectangle, if the polygon is one with sides along the axes (four vertices whose
    /// edges are horizontal and vertical in turn, either way round, from any corner).
    pub fn as_rect(&self) -> Option<Rect> {
        let v = &self.vertices;
        if v.len() != 4 {
            return None;
        }
        let flat = |k: usize, axis: usize| v[k][axis] == v[(k + 1) % 4][axis];
        let turns = |first: usize| (0..4).all(|k| flat(k, if k % 2 == 0 { first } else { 1 - first }));
        if !(turns(0) || turns(1)) {
            return None;
        }
        let b = self.aabb();
        Some(Rect::new(b.min[0], b.min[1], b.max[0], b.max[1]))
    }

    /// The polygon for messages: "[x0, y0, x1, y1]" for a rectangle with sides along the axes
    /// (as [`Rect::label`]), else "(polygon of 5 vertices: (x, y), (x, y), (x, y), ...)".
    pub fn label(&self) -> String {
        if let Some(r) = self.as_rect() {
            return r.label();
        }
        let shown: Vec<String> =
            self.vertices.iter().take(3).map(|v| format!("({}, {})", coord(v[0]), coord(v[1]))).collect();
        let more = if self.vertices.len() > 3 { ", ..." } else { "" };
        format!("(polygon of {} vertices: {}{more})", self.vertices.len(), shown.join(", "))
    }

    /// The convex polygon of these vertices, counter-clockwise from the lowest (the leftmost of
    /// the lowest), or why there is none. `tol` \[m\] (the model's contact tolerance, see
    /// [`super::contact_tolerance`]): a vertex within `tol` of the one before it is the same
    /// vertex (the last and the first too), a vertex within `tol` of the line through its
    /// neighbours is dropped (a straight outline), so that CAD rounding makes no corner.
    /// Refused: fewer than 3 vertices, or fewer than 3 distinct; a coordinate not finite; all
    /// the vertices on one line; an outline that turns back on itself, turns the other way at a
    /// corner (not convex) or winds round more than once (crosses itself).
    pub fn checked(&self, tol: f64) -> Result<Polygon, Defect> {
        self.check_finite()?;
        let v = &self.vertices;
        let defect = |vertex: Option<usize>, reason: String| Defect { vertex, reason };
        // the distinct vertices, as indices into v
        let mut idx: Vec<usize> = Vec::with_capacity(v.len());
        for k in 0..v.len() {
            if idx.last().map_or(true, |&j| dist(v[j], v[k]) > tol) {
                idx.push(k);
            }
        }
        while idx.len() > 1 && dist(v[idx[0]], v[idx[idx.len() - 1]]) <= tol {
            idx.pop();
        }
        if idx.len() < 3 {
            return Err(defect(None, format!("fewer than 3 distinct vertices ({} of the {} given)", idx.len(), v.len())));
        }
        if collinear(v, &idx, tol) {
            return Err(defect(None, "all its vertices lie on one line: it has no area".into()));
        }
        let twice_area: f64 = (0..idx.len()).map(|k| cross(v[idx[k]], v[idx[(k + 1) % idx.len()]])).sum();
        if twice_area < 0.0 {
            idx.reverse();
        }
        let at = |k: usize| format!("vertex {k} ({}, {})", coord(v[k][0]), coord(v[k][1]));
        straighten(v, &mut idx, tol).map_err(|(k, reason)| defect(Some(k), format!("{} {reason}", at(k))))?;
        if let Some(k) = winds_twice(v, &idx) {
            return Err(defect(
                Some(k),
                format!("the outline winds round past its start at {}: it crosses itself (a block is one convex polygon)", at(k)),
            ));
        }
        let lowest = (0..idx.len())
            .min_by(|&i, &j| {
                let (p, q) = (v[idx[i]], v[idx[j]]);
                (p[1], p[0]).partial_cmp(&(q[1], q[0])).expect("finite")
            })
            .expect("at least 3 vertices");
        idx.rotate_left(lowest);
        Ok(Polygon { vertices: idx.iter().map(|&k| v[k]).collect() })
    }

    /// Refuses fewer than 3 vertices and a coordinate that is not finite: what must hold before
    /// the polygon is measured (the model's size, and so its tolerance, come from its box).
    pub fn check_finite(&self) -> Result<(), Defect> {
        let v = &self.vertices;
        if v.len() < 3 {
            return Err(Defect { vertex: None, reason: format!("{} vertices: a block needs at least 3", v.len()) });
        }
        if let Some(k) = v.iter().position(|p| !(p[0].is_finite() && p[1].is_finite())) {
            let reason = format!("vertex {k} ({}, {}) is not finite", coord(v[k][0]), coord(v[k][1]));
            return Err(Defect { vertex: Some(k), reason });
        }
        Ok(())
    }
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    dot(sub(a, b), sub(a, b)).sqrt()
}

/// Whether the vertices `idx` of `v` lie within `tol` of one line: the line through the first
/// and the vertex farthest from it.
fn collinear(v: &[[f64; 2]], idx: &[usize], tol: f64) -> bool {
    let p = v[idx[0]];
    let far2 = |q: [f64; 2]| dot(sub(q, p), sub(q, p));
    let far = idx.iter().map(|&k| v[k]).fold(p, |f, q| if far2(q) > far2(f) { q } else { f });
    let (u, len) = (sub(far, p), dist(far, p));
    idx.iter().all(|&k| (cross(u, sub(v[k], p)) / len).abs() <= tol)
}

/// Drops from the counter-clockwise outline `idx` each vertex within `tol` of the line through
/// its neighbours, where the outline goes straight on; a vertex where it turns back, or turns
/// clockwise by more than `tol`, is refused (its index in `v`, and why).
fn straighten(v: &[[f64; 2]], idx: &mut Vec<usize>, tol: f64) -> Result<(), (usize, &'static str)> {
    let mut pos = 0;
    let mut unchanged = 0;
    while unchanged < idx.len() && idx.len() >= 3 {
        let m = idx.len();
        let (a, b, c) = (v[idx[(pos + m - 1) % m]], v[idx[pos]], v[idx[(pos + 1) % m]]);
        // b's distance from the line a -> c, positive on its right: a corner of a convex outline
        let off = cross(sub(b, a), sub(c, a)) / dist(c, a);
        if off.abs() <= tol {
            if dot(sub(b, a), sub(c, b)) < 0.0 {
                return Err((idx[pos], "turns the outline back on itself"));
            }
            idx.remove(pos);
            pos %= idx.len();
            unchanged = 0;
        } else if off < 0.0 {
            return Err((
                idx[pos],
                "is a re-entrant corner: the outline is not convex or crosses itself (a concave stone is given as convex parts)",
            ));
        } else {
            pos = (pos + 1) % m;
            unchanged += 1;
        }
    }
    Ok(())
}

/// The vertex (index into `v`) at which an outline of left turns only has turned round more
/// than once, if it does (a star: it crosses itself).
fn winds_twice(v: &[[f64; 2]], idx: &[usize]) -> Option<usize> {
    let m = idx.len();
    let mut turned = 0.0;
    for pos in 0..m {
        let (a, b, c) = (v[idx[pos]], v[idx[(pos + 1) % m]], v[idx[(pos + 2) % m]]);
        let (e, f) = (sub(b, a), sub(c, b));
        turned += cross(e, f).atan2(dot(e, f));
        if turned > 2.0 * PI * (1.0 + 1e-9) {
            return Some(idx[(pos + 1) % m]);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const TOL: f64 = 1e-9;

    fn poly(v: &[[f64; 2]]) -> Polygon {
        Polygon::new(v.to_vec())
    }

    fn refused(v: &[[f64; 2]], vertex: Option<usize>, words: &str) {
        match poly(v).checked(TOL) {
            Err(d) => {
                assert_eq!(d.vertex, vertex, "{d:?}");
                assert!(d.reason.contains(words), "{:?} does not say {words:?}", d.reason);
            }
            Ok(p) => panic!("{v:?} accepted as {p:?}"),
        }
    }

    #[test]
    fn either_orientation_gives_the_same_polygon() {
        let ccw = [[0.0, 0.0], [2.0, 0.0], [3.0, 1.0], [1.0, 2.0]];
        let cw: Vec<[f64; 2]> = ccw.iter().rev().copied().collect();
        let a = poly(&ccw).checked(TOL).unwrap();
        let b = poly(&cw).checked(TOL).unwrap();
        assert_eq!(a, b);
        assert_eq!(a.vertices(), &ccw);
        assert!(a.area_properties().area > 0.0);
        // started from another vertex: the same, from the lowest
        let turned = poly(&[ccw[2], ccw[3], ccw[0], ccw[1]]).checked(TOL).unwrap();
        assert_eq!(turned, a);
    }

    #[test]
    fn a_rectangle_is_a_polygon_from_its_lowest_left_corner() {
        let r = Rect::new(0.4, 0.175, 0.8, 0.35);
        let p = Polygon::from(r).checked(TOL).unwrap();
        assert_eq!(p.vertices(), &[[0.4, 0.175], [0.8, 0.175], [0.8, 0.35], [0.4, 0.35]]);
        assert_eq!(p.as_rect(), Some(r));
        assert_eq!(p.label(), "[0.4, 0.175, 0.8, 0.35]");
        assert_eq!(p.area_properties().area, r.area());
        // clockwise and from another corner: the same rectangle, named the same
        let cw = poly(&[[0.8, 0.35], [0.8, 0.175], [0.4, 0.175], [0.4, 0.35]]);
        assert_eq!(cw.label(), r.label());
        assert_eq!(cw.checked(TOL).unwrap(), p);
    }

    #[test]
    fn a_polygon_is_named_by_its_first_vertices() {
        let p = poly(&[[0.0, 0.0], [1.0, 0.0], [1.5, 0.5], [1.0, 1.0], [0.0, 1.0]]);
        assert_eq!(p.label(), "(polygon of 5 vertices: (0, 0), (1, 0), (1.5, 0.5), ...)");
        assert_eq!(poly(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1e-5]]).label(), "(polygon of 3 vertices: (0, 0), (1, 0), (0, 1e-5))");
    }

    #[test]
    fn collinear_and_repeated_vertices_are_dropped() {
        // a rectangle with a vertex mid-way along its bottom, its first corner repeated at the
        // end and one corner given twice, a rounding apart
        let v = [[0.0, 0.0], [0.5, 0.0], [1.0, 0.0], [1.0, 1.0], [1.0 + 1e-12, 1.0], [0.0, 1.0], [0.0, 0.0]];
        let p = poly(&v).checked(TOL).unwrap();
        assert_eq!(p.vertices(), &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
        // a corner dented inwards by less than the tolerance is straight
        let p = poly(&[[0.0, 0.0], [0.5, 1e-12], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]).checked(TOL).unwrap();
        assert_eq!(p.vertices().len(), 4);
    }

    #[test]
    fn what_is_not_a_convex_polygon_is_refused_with_its_vertex() {
        refused(&[[0.0, 0.0], [1.0, 0.0]], None, "2 vertices: a block needs at least 3");
        refused(&[[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [0.0, 0.0]], None, "fewer than 3 distinct vertices");
        refused(&[[0.0, 0.0], [1.0, 0.0], [f64::NAN, 1.0]], Some(2), "vertex 2 (NaN, 1) is not finite");
        refused(&[[0.0, 0.0], [1.0, 0.0], [1.0, f64::INFINITY]], Some(2), "not finite");
        refused(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0], [3.0, 3.0]], None, "lie on one line");
        // an L: the corner at (1, 1) turns the other way
        let l = [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]];
        refused(&l, Some(3), "vertex 3 (1, 1) is a re-entrant corner");
        refused(&l, Some(3), "a concave stone is given as convex parts");
        // the same L clockwise: the same corner named, by its index as given
        let l_cw: Vec<[f64; 2]> = l.iter().rev().copied().collect();
        refused(&l_cw, Some(2), "re-entrant corner");
        // a bow tie crosses itself: a corner turns the other way
        refused(&[[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]], Some(1), "crosses itself");
        // a spike: the outline goes out along a line and back
        refused(&[[0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 1.0]], Some(1), "turns the outline back on itself");
        // a pentagram turns left at every corner but winds round twice
        let star: Vec<[f64; 2]> = (0..5)
            .map(|i| {
                let a = 0.5 * PI + 4.0 * PI * i as f64 / 5.0;
                [a.cos(), a.sin()]
            })
            .collect();
        match poly(&star).checked(TOL) {
            Err(d) => assert!(d.reason.contains("crosses itself") && d.vertex.is_some(), "{d:?}"),
            Ok(p) => panic!("a star accepted: {p:?}"),
        }
    }

    proptest! {
        // a convex polygon (points on a circle, any orientation and first vertex) is accepted
        // whole, counter-clockwise from its lowest vertex, with the area of its closed form
        #[test]
        fn convex_polygons_are_accepted_and_ordered(k in 3usize..24, phase in 0.0f64..6.3, start in 0usize..24, reverse in any::<bool>(), r in 0.05f64..10.0) {
            let mut v: Vec<[f64; 2]> = (0..k)
                .map(|i| {
                    let a = phase + 2.0 * PI * i as f64 / k as f64;
                    [r * a.cos(), r * a.sin()]
                })
                .collect();
            v.rotate_left(start % k);
            if reverse {
                v.reverse();
            }
            let p = poly(&v).checked(TOL).unwrap();
            prop_assert_eq!(p.vertices().len(), k);
            let area = 0.5 * k as f64 * r * r * (2.0 * PI / k as f64).sin();
            prop_assert!((p.area_properties().area - area).abs() <= 1e-12 * area);
            let w = p.vertices();
            prop_assert!(w.iter().all(|q| (q[1], q[0]) >= (w[0][1], w[0][0])));
        }
    }
}
