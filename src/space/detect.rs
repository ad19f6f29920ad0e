//! Contact detection between convex polyhedra (boxes among them): the shape layer's grid
//! ([`crate::shape`]), as the 2D [`crate::interface::detect`], so that it costs O(n) for walls
//! of similar blocks, and its contact polygons of facing coplanar faces.

use super::{Box3, Contact};
use crate::error::{Error, Result};
use crate::interface::{BlockKind, Family};
use crate::shape::grid::for_each_pair;
use crate::shape::vec3::dot;
use crate::shape::{bisector, corner_contact, facing, penetration3, shared, upward, Aabb, FaceContact, Polyhedron, REL_TOL};

/// Finds every pair of boxes that share a rectangle of positive area (two faces with opposite
/// normals, coplanar within a tolerance), and refuses overlapping boxes (naming both).
///
/// Two faces count as coplanar when they are less than `1e-8` times the model's size apart, gap
/// or interpenetration (at least 1e-14 times its largest coordinate, above their rounding): a
/// model is the same at any size. A box whose smallest side is within ten times that tolerance
/// is refused (naming it): its faces could not be told apart. Boxes touching
/// along an edge or at a corner only share no area and make no contact; a base against a top
/// beam is not a joint of the wall and makes none either. `name` gives the label of a block for
/// messages; `poll` is called every few thousand blocks or grid cells, and `false` stops the
/// search ([`Error::Interrupted`]). The contacts are sorted by their blocks `(a, b)`.
///
/// ```
/// use masonry_dem::interface::{BlockKind, Family};
/// use masonry_dem::space::{detect, Box3};
/// // a block on another, offset: they share 0.3 x 0.1 m
/// let boxes = [Box3::new(0.0, 0.0, 0.0, 0.4, 0.1, 0.2), Box3::new(0.1, 0.0, 0.2, 0.5, 0.1, 0.4)];
/// let found = detect(&boxes, &[BlockKind::Wall; 2], |i| format!("block {i}"), &mut || true).unwrap();
/// assert_eq!(found.len(), 1);
/// assert_eq!((found[0].a, found[0].b, found[0].n, found[0].family), (0, 1, [0.0, 0.0, 1.0], Family::Bed));
/// assert!((found[0].area - 0.03).abs() < 1e-15);
/// ```
pub fn detect(
    boxes: &[Box3],
    kinds: &[BlockKind],
    name: impl Fn(usize) -> String,
    poll: &mut dyn FnMut() -> bool,
) -> Result<Vec<Contact>> {
    let shapes: Vec<Polyhedron> = boxes.iter().map(|b| b.polyhedron()).collect();
    detect_polyhedra(&shapes, kinds, name, poll)
}

/// [`detect`] on convex polyhedra: every pair of blocks with a face of each on one plane within
/// the tolerance, facing, that share a polygon of positive area
/// ([`crate::shape::face_contacts`]); blocks without such faces (whose planes would part them)
/// that overlap by more than the tolerance ([`penetration3`]) are refused, naming both.
/// A block narrower than ten times the tolerance across one of its faces is refused, naming it.
/// The normal is oriented up (from the lower block into the upper), or for a vertical contact
/// towards +x, or else +y (as between boxes); a contact is Bed when its normal is within 45 deg
/// of the vertical, else Head (or Base, Top as between boxes).
pub fn detect_polyhedra(
    shapes: &[Polyhedron],
    kinds: &[BlockKind],
    name: impl Fn(usize) -> String,
    poll: &mut dyn FnMut() -> bool,
) -> Result<Vec<Contact>> {
    let aabbs: Vec<Aabb<3>> = shapes.iter().map(Polyhedron::aabb).collect();
    detect_with(shapes, &aabbs, kinds, tolerance(&aabbs), false, name, poll)
}

/// [`detect_polyhedra`] with the tolerance `tol` \[m\] (faces this close, gap or overlap, touch),
/// and with `corners`, also the contacts along an edge or at a point of blocks that share no
/// polygon ([`corner_contact`]: contacts of area 0, the blocks of a moved model).
pub(crate) fn detect_with(
    shapes: &[Polyhedron],
    aabbs: &[Aabb<3>],
    kinds: &[BlockKind],
    tol: f64,
    corners: bool,
    name: impl Fn(usize) -> String,
    poll: &mut dyn FnMut() -> bool,
) -> Result<Vec<Contact>> {
    for (i, p) in shapes.iter().enumerate() {
        let side = width(p);
        if !(side > THINNEST * tol) {
            return Err(Error::input(format!(
                "{}: its smallest side, {side:e} m, is within {THINNEST} times the contact tolerance ({tol:e} m, 1e-8 of the model's size or 1e-14 of its largest coordinate): its faces cannot be told apart",
                name(i)
            )));
        }
    }
    let mut out = Vec::with_capacity(4 * shapes.len());
    for_each_pair(aabbs, tol, poll, |i, j| {
        if kinds[i] != BlockKind::Wall && kinds[j] != BlockKind::Wall {
            return Ok(()); // base or support against top beam or support: not a joint of the wall
        }
        let pairs = facing(&shapes[i], &shapes[j], tol);
        let found = out.len();
        if let Some(&[fi, fj]) = pairs.first() {
            let up = upward(bisector(&shapes[i], fi, &shapes[j], fj));
            let (a, b) = if up { (i, j) } else { (j, i) };
            for [fi, fj] in pairs {
                let (fa, fb) = if up { (fi, fj) } else { (fj, fi) };
                let Some(c) = shared(&shapes[a], fa, &shapes[b], fb, tol) else { continue };
                out.push(contact(a, b, family(kinds[a], kinds[b], c.n[2]), c));
            }
        } else {
            let depth = penetration3(&shapes[i], &shapes[j], tol);
            if depth > tol {
                let (p, q) = (&aabbs[i], &aabbs[j]);
                let how = match (shapes[i].as_box(), shapes[j].as_box()) {
                    (Some(_), Some(_)) => {
                        let w = p.overlap(q);
                        format!("intersection {:.6} x {:.6} x {:.6} m", w[0], w[1], w[2])
                    }
                    _ => format!("by {depth:.6} m"),
                };
                return Err(Error::input(format!("{} and {} overlap ({how})", name(i), name(j))));
            }
        }
        // blocks that share no polygon may meet along an edge or at a point
        if corners && out.len() == found {
            if let Some(c) = corner_contact(&shapes[i], &shapes[j], tol) {
                out.push(contact(i, j, family(kinds[i], kinds[j], c.n[2]), c));
            }
        }
        Ok(())
    })?;
    out.sort_by_key(|c| (c.a, c.b));
    Ok(out)
}

/// The family of a contact between blocks of kinds `a` and `b` whose normal's vertical part is
/// `nz`: Base or Top with the base (a support) or the top beam, else Bed within 45 deg of the
/// vertical, Head beyond.
fn family(a: BlockKind, b: BlockKind, nz: f64) -> Family {
    match (a, b) {
        (BlockKind::Base, _) | (_, BlockKind::Base) => Family::Base,
        (BlockKind::Top, _) | (_, BlockKind::Top) => Family::Top,
        _ if nz.abs() >= std::f64::consts::FRAC_1_SQRT_2 => Family::Bed,
        _ => Family::Head,
    }
}

/// The least width of `p` across its faces: for each face, how far the farthest vertex lies
/// behind its plane (a box's smallest side).
fn width(p: &Polyhedron) -> f64 {
    p.faces()
        .iter()
        .map(|f| p.vertices().iter().map(|&v| f.offset - dot(f.normal, v)).fold(0.0, f64::max))
        .fold(f64::INFINITY, f64::min)
}

/// The contact of blocks `a` and `b` from the polygon their faces share.
fn contact(a: usize, b: usize, family: Family, c: FaceContact) -> Contact {
    let uv = |p: &[f64; 3]| [dot(*p, c.t1), dot(*p, c.t2)];
    let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
    for p in &c.vertices {
        let q = uv(p);
        for k in 0..2 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    Contact {
        a,
        b,
        n: c.n,
        t1: c.t1,
        t2: c.t2,
        corners: c.vertices,
        dims: [hi[0] - lo[0], hi[1] - lo[1]],
        area: c.area,
        centroid: c.centroid,
        family,
    }
}

/// Convex polyhedra from vertex lists, each block the convex hull of its vertices \[m\]
/// ([`Polyhedron::hull`]), with the contact tolerance of the box around every finite vertex of
/// `lists` and `more` (the model's other blocks): the tolerance with which the model then finds
/// their contacts. `keys` names each list in the refusals (`"polyhedra"`, `"supports"`), and a
/// refusal names the block as `polyhedra[3]`: a coordinate not finite (with the vertex), fewer
/// than 4 vertices off one plane. The error's key is the list's.
///
/// ```
/// use masonry_dem::space::hulls;
/// let wedge = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [0.2, 0.2, 0.0]];
/// let made = hulls(&[(&[wedge][..], "polyhedra")], &[]).unwrap();
/// assert_eq!((made[0][0].vertices().len(), made[0][0].faces().len()), (4, 4)); // (0.2, 0.2, 0) is inside a face
/// let flat = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]];
/// let err = hulls(&[(&[flat][..], "supports")], &[]).unwrap_err();
/// assert_eq!(err.key(), Some("supports"));
/// assert!(err.to_string().starts_with("supports[0]: fewer than 4 vertices off one plane"));
/// ```
pub fn hulls(lists: &[(&[Vec<[f64; 3]>], &str)], more: &[Aabb<3>]) -> Result<Vec<Vec<Polyhedron>>> {
    let finite = lists.iter().flat_map(|(l, _)| l.iter().flatten()).filter(|p| p.iter().all(|v| v.is_finite()));
    let around = Aabb::around(finite);
    let mut every = more.to_vec();
    if around.min[0] <= around.max[0] {
        every.push(around); // not empty: some vertex is finite
    }
    let tol = tolerance(&every);
    let hull = |key: &str, i: usize, v: &[[f64; 3]]| {
        Polyhedron::hull(v, tol).map_err(|d| Error::input_at(key, format!("{key}[{i}]: {}", d.reason)))
    };
    lists.iter().map(|&(list, key)| list.iter().enumerate().map(|(i, v)| hull(key, i, v)).collect()).collect()
}

/// The contact tolerance is at least `10 REL_TOL` times this fraction of the largest coordinate:
/// a hundred times the rounding of coordinates (about 1e-16 of them), for a model small beside
/// its distance from the origin.
const REACH: f64 = 1e-6;

/// A box whose smallest side is not more than this many times the contact tolerance is refused:
/// its faces would be within the tolerance of each other.
const THINNEST: f64 = 10.0;

/// The contact tolerance of the boxes: `10 REL_TOL` of the model's size, relative at any size
/// (no floor in metres: a wall of boxes of 1e-8 m is the wall of 1 m scaled), and at least
/// `10 REL_TOL REACH` of its largest coordinate, above the rounding of coordinates.
pub(crate) fn tolerance(aabbs: &[Aabb<3>]) -> f64 {
    let around = aabbs.iter().fold(Aabb::around(&[]), |a, b| a.union(b));
    if aabbs.is_empty() {
        return 0.0;
    }
    let reach = (0..3).map(|k| around.min[k].abs().max(around.max[k].abs())).fold(0.0, f64::max);
    10.0 * REL_TOL * around.size().max(REACH * reach)
}
