//! Where two convex polygons touch: facing collinear edges that overlap over a positive length,
//! and how deep two polygons overlap.

use super::Polygon;

/// Two edges, one of each polygon, that face each other on one line (within the tolerance) and
/// overlap over a positive length: an interface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeContact {
    /// The edge of the first polygon (from its vertex k to vertex k + 1) and of the second.
    pub edges: [usize; 2],
    /// The unit normal from the first polygon into the second: the bisector of the edges'
    /// outward normals (the first's, and the second's reversed; one and the same on one line).
    pub n: [f64; 2],
    /// The overlap's two ends \[m\], each on the line midway between the two edges, in the
    /// order of the tangent `(n_y, -n_x)`.
    pub ends: [[f64; 2]; 2],
    /// The overlap's length \[m\].
    pub length: f64,
}

/// Every pair of an edge of `a` and an edge of `b` that face each other (opposite directions:
/// the polygons lie on either side) and overlap, along their common direction, over more than
/// `tol` \[m\], with each end of the overlap within `tol` of the other edge's line (a gap or an
/// overlap of either polygon into the other, CAD rounding, is closed). The overlap's ends are
/// the vertices that bound it, each moved half-way across the gap; for a rectangle on a
/// rectangle they are corners' coordinates, exactly. Polygons counter-clockwise (checked).
///
/// Two convex polygons that do not overlap meet along one segment at most: one contact; more
/// only where the tolerance joins edges that meet at a corner within it.
pub fn contacts(a: &Polygon, b: &Polygon, tol: f64) -> Vec<EdgeContact> {
    let (va, vb) = (a.vertices(), b.vertices());
    let mut out = Vec::new();
    for i in 0..va.len() {
        let (p0, p1) = (va[i], va[(i + 1) % va.len()]);
        let da = sub(p1, p0);
        for j in 0..vb.len() {
            let (q0, q1) = (vb[j], vb[(j + 1) % vb.len()]);
            if dot(da, sub(q1, q0)) >= 0.0 {
                continue; // not facing
            }
            if let Some(c) = edge_pair([p0, p1], [q0, q1], tol) {
                out.push(EdgeContact { edges: [i, j], ..c });
            }
        }
    }
    out
}

/// Where polygons `a` and `b` touch at a point (within `tol` \[m\]) rather than along a stretch of
/// edge: a vertex of one on the inside of an edge of the other (the normal that edge's), or a
/// vertex of each at one point whose facing edges there run the same way from it, as two blocks
/// turned about a common corner (the normal the bisector of the two edges' normals, as for
/// [`contacts`]). These are the contacts of blocks moved by finite rotations: a block turned
/// about its toe stands on the toe alone. Each is an [`EdgeContact`] of length 0 whose two ends
/// are the point, `edges` the edge of each polygon that gives the normal (for a vertex on an
/// edge, the vertex's first edge). Points of a stretch in `along` (the polygons' [`contacts`])
/// are not repeated.
pub fn corner_contacts(a: &Polygon, b: &Polygon, tol: f64, along: &[EdgeContact]) -> Vec<EdgeContact> {
    let (va, vb) = (a.vertices(), b.vertices());
    let covered = |x: [f64; 2]| along.iter().any(|c| on_segment(x, c.ends, tol));
    let mut out: Vec<EdgeContact> = Vec::new();
    // a vertex of `p` on the inside of an edge of `q`; `flip`: p is b (the normal from a into b)
    let on_edges = |p: &[[f64; 2]], q: &[[f64; 2]], flip: bool, out: &mut Vec<EdgeContact>| {
        for (i, &v) in p.iter().enumerate() {
            for j in 0..q.len() {
                let e = [q[j], q[(j + 1) % q.len()]];
                let (d, len) = (sub(e[1], e[0]), dist(e[0], e[1]));
                let m = outward(e);
                let gap = dot(sub(v, e[0]), m);
                let s = dot(sub(v, e[0]), d) / len;
                if gap.abs() > tol || s <= tol || s >= len - tol {
                    continue;
                }
                let x = [v[0] - 0.5 * gap * m[0], v[1] - 0.5 * gap * m[1]];
                if covered(x) {
                    continue;
                }
                let (n, edges) = if flip { (m, [j, i]) } else { ([-m[0], -m[1]], [i, j]) };
                out.push(EdgeContact { edges, n, ends: [x, x], length: 0.0 });
            }
        }
    };
    on_edges(va, vb, false, &mut out);
    on_edges(vb, va, true, &mut out);
    for (i, &v) in va.iter().enumerate() {
        for (k, &w) in vb.iter().enumerate() {
            if dist(v, w) > tol {
                continue;
            }
            let x = [0.5 * (v[0] + w[0]), 0.5 * (v[1] + w[1])];
            if covered(x) {
                continue;
            }
            // the edges at the common point that face each other and run the same way from it:
            // the pair whose directions are the most nearly opposite
            let ea = [(i + va.len() - 1) % va.len(), i];
            let eb = [(k + vb.len() - 1) % vb.len(), k];
            let edge = |vs: &[[f64; 2]], e: usize| [vs[e], vs[(e + 1) % vs.len()]];
            let mut best: Option<(f64, usize, usize)> = None;
            for &ja in &ea {
                for &jb in &eb {
                    let (p, q) = (edge(va, ja), edge(vb, jb));
                    let (dp, dq) = (sub(p[1], p[0]), sub(q[1], q[0]));
                    let cos = dot(dp, dq) / (dist(p[0], p[1]) * dist(q[0], q[1]));
                    // from the common point both edges go the same way along their bisector
                    let (fp, fq) = (far(p, x), far(q, x));
                    if cos < 0.0 && dot(sub(fp, x), sub(fq, x)) > 0.0 && best.map_or(true, |b| cos < b.0) {
                        best = Some((cos, ja, jb));
                    }
                }
            }
            if let Some((_, ja, jb)) = best {
                let (na, nb) = (outward(edge(va, ja)), outward(edge(vb, jb)));
                let n = unit([na[0] - nb[0], na[1] - nb[1]]);
                out.push(EdgeContact { edges: [ja, jb], n, ends: [x, x], length: 0.0 });
            }
        }
    }
    out
}

/// Two edges, one of each polygon, that face each other within an angle and lie near enough to
/// touch: the contacts of blocks in motion, which need not lie along one line (a block turning
/// about a corner, or landing tilted). The first polygon's edge (the one whose outward normal the
/// contact takes) is the edge against which the other's vertex bears at the closed end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Facing {
    /// Which polygon's edge gives the normal: 0 the first given, 1 the second.
    pub owner: usize,
    /// The edge of the owner and of the other polygon (from vertex k to vertex k + 1).
    pub edges: [usize; 2],
    /// The owner's edge's outward unit normal, from the owner into the other.
    pub n: [f64; 2],
    /// The overlap's centre on the owner's edge and on the other's edge line, at the same place
    /// along the owner's edge \[m\].
    pub at: [[f64; 2]; 2],
    /// The overlap's length along the other's edge \[m\] (over the overlap along the owner's edge).
    pub length: f64,
    /// The other's edge's distance from the owner's edge at the centre, along `n` (negative where
    /// they overlap) \[m\].
    pub gap: f64,
    /// The angle of the other's edge against the owner's, reversed, counter-clockwise \[rad\]:
    /// the point of the other's edge `s` from the centre along it lies `gap + s sin(angle)` from
    /// the owner's edge's line (`s` positive along the tangent `(n_y, -n_x)`).
    pub angle: f64,
}

/// Every pair of an edge of `a` and an edge of `b` whose outward normals are opposed within 60
/// degrees, that overlap along the owner's edge over more than `tol` \[m\], with the nearer end of
/// the overlap no farther apart than `gap` \[m\] and the farther end not inside the owner by more
/// than `gap` or half the depth of either polygon behind its edge (an edge that deep lies behind
/// the other edge, not on it) (see [`Facing`]). Two edges along one line make a contact of angle 0, as [`contacts`] does; a
/// vertex near an edge makes one with one of the two edges at the vertex (one of them faces the
/// edge within 60 degrees for any vertex of an interior angle of 60 degrees or more).
pub fn facing_edges(a: &Polygon, b: &Polygon, gap: f64, tol: f64) -> Vec<Facing> {
    let (va, vb) = (a.vertices(), b.vertices());
    // how far each polygon reaches behind each of its edges
    let depth = |v: &[[f64; 2]], k: usize| {
        let m = outward([v[k], v[(k + 1) % v.len()]]);
        v.iter().map(|&x| dot(sub(v[k], x), m)).fold(0.0, f64::max)
    };
    let mut out = Vec::new();
    for i in 0..va.len() {
        let p = [va[i], va[(i + 1) % va.len()]];
        for j in 0..vb.len() {
            let q = [vb[j], vb[(j + 1) % vb.len()]];
            if dot(outward(p), outward(q)) >= -0.5 {
                continue;
            }
            // an edge deeper into the other polygon than the gap, or than half of either, is
            // behind it, not on it: blocks that touch overlap by far less than the gap (they were
            // found within it before they closed), and in running bond the head joints of the
            // course below and above lie exactly half a block behind each other's
            let deep = gap.min(0.5 * depth(va, i).min(depth(vb, j)));
            let Some((f, from_owner)) = facing_pair(p, q, gap, deep, tol) else { continue };
            if from_owner {
                // the owner's vertex bears on the other's edge: the other's edge gives the normal
                if let Some((g, _)) = facing_pair(q, p, gap, deep, tol) {
                    out.push(Facing { owner: 1, edges: [j, i], ..g });
                    continue;
                }
            }
            out.push(Facing { owner: 0, edges: [i, j], ..f });
        }
    }
    out
}

/// The contact of edge `p` (the owner's) and edge `q`, facing, if they overlap along `p` and lie
/// near (see [`facing_edges`]), with whether its closed end is bounded by a vertex of `p` alone.
fn facing_pair(p: [[f64; 2]; 2], q: [[f64; 2]; 2], gap: f64, deep: f64, tol: f64) -> Option<(Facing, bool)> {
    let n = outward(p);
    let len_p = dist(p[0], p[1]);
    let ta = [(p[1][0] - p[0][0]) / len_p, (p[1][1] - p[0][1]) / len_p];
    let (s0, s1) = (dot(sub(q[0], p[0]), ta), dot(sub(q[1], p[0]), ta));
    let (h0, h1) = (dot(sub(q[0], p[0]), n), dot(sub(q[1], p[0]), n));
    let (lo_q, hi_q) = (s0.min(s1), s0.max(s1));
    let (lo, hi) = (lo_q.max(0.0), hi_q.min(len_p));
    if hi - lo <= tol {
        return None;
    }
    // the height of q's line over p's at s along p
    let h = |s: f64| h0 + (h1 - h0) * (s - s0) / (s1 - s0);
    let (h_lo, h_hi) = (h(lo), h(hi));
    if h_lo.min(h_hi) > gap || h_lo.max(h_hi) < -deep {
        return None;
    }
    // which end is closed, and whether p's own vertex bounds it (q's does not)
    let closed_lo = h_lo <= h_hi;
    let near = (h_lo - h_hi).abs() <= tol;
    let from_owner = !near && if closed_lo { lo_q < 0.0 } else { hi_q > len_p };
    let sc = 0.5 * (lo + hi);
    let on_p = [p[0][0] + sc * ta[0], p[0][1] + sc * ta[1]];
    let lam = (sc - s0) / (s1 - s0);
    let on_q = [q[0][0] + lam * (q[1][0] - q[0][0]), q[0][1] + lam * (q[1][1] - q[0][1])];
    let t = [n[1], -n[0]];
    let eq = sub(q[1], q[0]);
    let angle = (t[0] * eq[1] - t[1] * eq[0]).atan2(dot(t, eq));
    // the length along q: its ends then lie at the centre's distance +- length / 2 along q, whose
    // gaps are those of the joint's ends, gap +- length / 2 sin(angle)
    Some((Facing { owner: 0, edges: [0, 0], n, at: [on_p, on_q], length: (hi - lo) / angle.cos(), gap: dot(sub(on_q, on_p), n), angle }, from_owner))
}

/// The end of edge `e` farther from `x`.
fn far(e: [[f64; 2]; 2], x: [f64; 2]) -> [f64; 2] {
    if dist(e[0], x) >= dist(e[1], x) {
        e[0]
    } else {
        e[1]
    }
}

/// Whether `x` lies within `tol` of the segment `s`.
fn on_segment(x: [f64; 2], s: [[f64; 2]; 2], tol: f64) -> bool {
    let d = sub(s[1], s[0]);
    let l2 = dot(d, d);
    let t = if l2 > 0.0 { (dot(sub(x, s[0]), d) / l2).clamp(0.0, 1.0) } else { 0.0 };
    dist(x, [s[0][0] + t * d[0], s[0][1] + t * d[1]]) <= tol
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The contact of edge `p` of one polygon and edge `q` of another, running opposite ways.
fn edge_pair(p: [[f64; 2]; 2], q: [[f64; 2]; 2], tol: f64) -> Option<EdgeContact> {
    let (na, nb) = (outward(p), outward(q));
    let n = unit([na[0] - nb[0], na[1] - nb[1]]);
    let t = [n[1], -n[0]];
    // positions along t from p[0]: edge p runs from 0 down to s(p[1]), edge q up from s(q[0])
    let s = |x: [f64; 2]| dot(sub(x, p[0]), t);
    let (lo_from_p, hi_from_p) = (s(p[1]) >= s(q[0]), 0.0 <= s(q[1]));
    let lo = if lo_from_p { s(p[1]) } else { s(q[0]) };
    let hi = if hi_from_p { 0.0 } else { s(q[1]) };
    if hi - lo <= tol {
        return None; // apart along the line, or meeting at a corner
    }
    // an end of the overlap: its vertex, moved half-way towards the other edge's line
    let end = |from_p: bool, v: [f64; 2]| -> Option<[f64; 2]> {
        let (other, m) = if from_p { (q[0], nb) } else { (p[0], na) };
        let gap = dot(sub(v, other), m);
        (gap.abs() <= tol).then(|| [v[0] - 0.5 * gap * m[0], v[1] - 0.5 * gap * m[1]])
    };
    let e0 = end(lo_from_p, if lo_from_p { p[1] } else { q[0] })?;
    let e1 = end(hi_from_p, if hi_from_p { p[0] } else { q[1] })?;
    Some(EdgeContact { edges: [0, 0], n, ends: [e0, e1], length: dot(sub(e1, e0), t) })
}

/// How deep convex polygons `a` and `b` overlap \[m\]: over the edges of both, the least depth
/// of the other polygon into the edge's half-plane (zero or negative when they touch or are
/// apart: some edge's line separates them). It is at least the least translation that parts
/// them, and never more than zero when an edge's line parts them.
pub fn penetration(a: &Polygon, b: &Polygon) -> f64 {
    let mut depth = f64::INFINITY;
    for (p, q) in [(a, b), (b, a)] {
        let (vp, vq) = (p.vertices(), q.vertices());
        for i in 0..vp.len() {
            let m = outward([vp[i], vp[(i + 1) % vp.len()]]);
            let into = vq.iter().map(|&x| -dot(sub(x, vp[i]), m)).fold(f64::MIN, f64::max);
            depth = depth.min(into);
            if depth <= 0.0 {
                return depth;
            }
        }
    }
    depth
}

/// The outward unit normal of edge `e` of a counter-clockwise polygon.
fn outward(e: [[f64; 2]; 2]) -> [f64; 2] {
    let d = sub(e[1], e[0]);
    unit([d[1], -d[0]])
}

/// `v` over its length (`sqrt(x^2)` is `|x|` exactly: an axis-aligned vector stays exact).
fn unit(v: [f64; 2]) -> [f64; 2] {
    let l = (v[0] * v[0] + v[1] * v[1]).sqrt();
    [v[0] / l, v[1] / l]
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Rect;
    use proptest::prelude::*;

    const TOL: f64 = 1e-9;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Polygon {
        Polygon::from(Rect::new(x0, y0, x1, y1)).checked(TOL).unwrap()
    }

    fn turned(p: &Polygon, angle: f64, centre: [f64; 2]) -> Polygon {
        let (s, c) = angle.sin_cos();
        p.map(|v| {
            let (x, y) = (v[0] - centre[0], v[1] - centre[1]);
            [centre[0] + c * x - s * y, centre[1] + s * x + c * y]
        })
        .checked(TOL)
        .unwrap()
    }

    /// Two blocks of running bond, one course above the other and half a block along: they touch
    /// along the bed joint only. The right edge of the lower one and the left edge of the upper
    /// one face each other half a block apart, one behind the other, whatever small motion the
    /// wall makes (a gap of 2% of the block's height; the upper block raised, lowered, shifted
    /// by up to 1 mm): a head-edge pair of them is no contact.
    #[test]
    fn blocks_of_running_bond_touch_along_their_bed_joint_only() {
        let gap = 0.02 * 0.175;
        let below = rect(0.2, 0.0, 0.6, 0.175);
        for (dx, dy) in [(0.0, 0.0), (0.0, 1e-3), (0.0, -1e-3), (1e-3, 1e-3), (-1e-3, -1e-4)] {
            let above = rect(0.4 + dx, 0.175 + dy, 0.8 + dx, 0.35 + dy);
            let found = facing_edges(&below, &above, gap, TOL);
            assert_eq!(found.len(), 1, "({dx}, {dy}): {found:?}");
            let f = found[0];
            // the bed joint: horizontal, from the lower block's top edge (or the upper's bottom)
            assert!(f.n[0].abs() < 1e-12 && (f.n[1].abs() - 1.0).abs() < 1e-12, "({dx}, {dy}): {f:?}");
            assert!((f.length - (0.2 - dx)).abs() < 1e-9 && (f.gap - dy * f.n[1]).abs() < 1e-9, "({dx}, {dy}): {f:?}");
        }
    }

    #[test]
    fn rectangles_meet_over_their_common_stretch_exactly() {
        // a block on part of a longer one: the overlap's ends are corners' coordinates
        let (low, high) = (rect(0.0, 0.0, 1.0, 0.175), rect(0.4, 0.175, 1.4, 0.35));
        let c = contacts(&low, &high, TOL);
        assert_eq!(c.len(), 1);
        assert_eq!(c[0].n, [0.0, 1.0]);
        assert_eq!(c[0].ends, [[0.4, 0.175], [1.0, 0.175]]);
        assert_eq!(c[0].length, 1.0 - 0.4);
        // the other way round: the normal from the first into the second
        let c = contacts(&high, &low, TOL);
        assert_eq!(c[0].n, [0.0, -1.0]);
        assert_eq!(c[0].length, 1.0 - 0.4);
        // side by side: along the shorter side
        let c = contacts(&rect(0.0, 0.0, 0.4, 0.2), &rect(0.4, 0.1, 0.8, 0.5), TOL);
        assert_eq!((c[0].n, c[0].ends, c[0].length), ([1.0, 0.0], [[0.4, 0.2], [0.4, 0.1]], 0.2 - 0.1));
    }

    #[test]
    fn corners_and_gaps_make_no_contact() {
        let a = rect(0.0, 0.0, 1.0, 1.0);
        assert!(contacts(&a, &rect(1.0, 1.0, 2.0, 2.0), TOL).is_empty()); // a corner
        assert!(contacts(&a, &rect(0.0, 1.0 + 1e-6, 1.0, 2.0), TOL).is_empty()); // a gap
        assert!(contacts(&a, &rect(2.0, 0.0, 3.0, 1.0), TOL).is_empty()); // apart
        // a gap and an overlap within the tolerance are closed, the points half-way across
        let c = contacts(&a, &rect(0.5, 1.0 + 4e-10, 1.5, 2.0), TOL);
        assert_eq!(c.len(), 1);
        assert!((c[0].ends[0][1] - (1.0 + 2e-10)).abs() < 1e-15 && (c[0].length - 0.5).abs() < 1e-15);
        assert_eq!(contacts(&a, &rect(0.5, 1.0 - 4e-10, 1.5, 2.0), TOL).len(), 1);
    }

    #[test]
    fn overlapping_polygons_are_measured() {
        let a = rect(0.0, 0.0, 1.0, 1.0);
        assert_eq!(penetration(&a, &rect(0.5, 0.75, 1.5, 1.5)), 0.25);
        assert!(penetration(&a, &rect(1.0, 0.0, 2.0, 1.0)) <= 0.0); // side by side
        assert!(penetration(&a, &rect(3.0, 0.0, 4.0, 1.0)) < 0.0);
        // a triangle whose tip enters the square by 0.1
        let tri = Polygon::new(vec![[0.5, 0.9], [1.5, 2.0], [-0.5, 2.0]]).checked(TOL).unwrap();
        assert!((penetration(&a, &tri) - 0.1).abs() < 1e-12);
    }

    #[test]
    fn blocks_turned_about_a_corner_touch_at_a_point() {
        let base = rect(-1.0, -1.0, 2.0, 0.0);
        let block = rect(0.0, 0.0, 0.4, 1.0);
        // on the base along its bottom edge: a stretch, no point besides
        let along = contacts(&base, &block, TOL);
        assert_eq!(along.len(), 1);
        assert!(corner_contacts(&base, &block, TOL, &along).is_empty());
        // turned by 0.1 rad about its right toe (0.4, 0): the toe on the inside of the base's
        // top edge, the normal the edge's
        let turned_block = turned(&block, -0.1, [0.4, 0.0]);
        assert!(contacts(&base, &turned_block, TOL).is_empty());
        let c = corner_contacts(&base, &turned_block, TOL, &[]);
        assert_eq!(c.len(), 1);
        assert_eq!((c[0].n, c[0].length), ([0.0, 1.0], 0.0));
        assert!((c[0].ends[0][0] - 0.4).abs() < 1e-15 && c[0].ends[0][1].abs() < 1e-15 && c[0].ends[0] == c[0].ends[1]);
        // the other way round, the normal reversed
        let r = corner_contacts(&turned_block, &base, TOL, &[]);
        assert!(r.len() == 1 && r[0].n == [0.0, -1.0]);
        // on a base that ends at the toe: two vertices at one point, the normal the bisector
        let short = rect(0.0, -1.0, 0.4, 0.0);
        let c = corner_contacts(&short, &turned_block, TOL, &[]);
        assert_eq!(c.len(), 1);
        assert!((c[0].n[0] - 0.05f64.sin()).abs() < 1e-12 && (c[0].n[1] - 0.05f64.cos()).abs() < 1e-12, "{:?}", c[0].n);
        // blocks that meet corner to corner, diagonally, do not touch
        let a = rect(0.0, 0.0, 1.0, 1.0);
        assert!(corner_contacts(&a, &rect(1.0, 1.0, 2.0, 2.0), TOL, &[]).is_empty());
        // apart by more than the tolerance: nothing
        let lifted = turned_block.map(|v| [v[0], v[1] + 1e-6]).checked(TOL).unwrap();
        assert!(corner_contacts(&base, &lifted, TOL, &[]).is_empty());
    }

    proptest! {
        // a pair of touching blocks (a rectangle on a trapezoid's inclined top, the upper one
        // partly over it), turned about any point by any angle, meets over the same length,
        // with the normal turned and the overlap's ends on the common edge
        #[test]
        fn contacts_turn_with_the_blocks(angle in -3.2f64..3.2, cx in -5.0f64..5.0, cy in -5.0f64..5.0, shift in -0.3f64..0.3, beta in -0.6f64..0.6) {
            let (sb, cb) = beta.sin_cos();
            // the support: a trapezoid under the edge from (0, 0) along (cos b, sin b), 1 m long
            let support = Polygon::new(vec![[0.0, -1.0], [cb, -1.0], [cb, sb], [0.0, 0.0]]).checked(TOL).unwrap();
            // the block: 0.5 x 0.3 along the edge, starting `shift + 0.25` along it
            let s0 = 0.25 + shift;
            let along = |s: f64, h: f64| [s * cb - h * sb, s * sb + h * cb];
            let block = Polygon::new(vec![along(s0, 0.0), along(s0 + 0.5, 0.0), along(s0 + 0.5, 0.3), along(s0, 0.3)]).checked(TOL).unwrap();
            let want = (s0 + 0.5).min(1.0) - s0.max(0.0);
            let (sup, blk) = (turned(&support, angle, [cx, cy]), turned(&block, angle, [cx, cy]));
            let c = contacts(&sup, &blk, TOL);
            prop_assert_eq!(c.len(), 1);
            prop_assert!((c[0].length - want).abs() < 1e-12);
            let normal = [-(beta + angle).sin(), (beta + angle).cos()];
            prop_assert!((c[0].n[0] - normal[0]).abs() < 1e-12 && (c[0].n[1] - normal[1]).abs() < 1e-12);
            prop_assert!(penetration(&sup, &blk) <= 1e-12); // touching, not overlapping
            // the same pair the other way round
            let r = contacts(&blk, &sup, TOL);
            prop_assert!(r.len() == 1 && (r[0].length - want).abs() < 1e-12);
            prop_assert!((r[0].n[0] + normal[0]).abs() < 1e-12 && (r[0].n[1] + normal[1]).abs() < 1e-12);
        }
    }
}
