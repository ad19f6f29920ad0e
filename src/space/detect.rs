//! Contact detection between axis-aligned boxes: the shape layer's grid
//! ([`crate::shape`]), as the 2D [`crate::interface::detect`], so that it costs O(n) for walls
//! of similar blocks.

use super::{Box3, Contact};
use crate::error::{Error, Result};
use crate::interface::{BlockKind, Family};
use crate::shape::grid::for_each_pair;
use crate::shape::{Aabb, REL_TOL};

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
    let aabbs: Vec<Aabb<3>> = boxes.iter().map(|b| Aabb { min: b.min, max: b.max }).collect();
    let tol = tolerance(&aabbs);
    for (i, b) in boxes.iter().enumerate() {
        let side = b.size().into_iter().fold(f64::INFINITY, f64::min);
        if !(side > THINNEST * tol) {
            return Err(Error::input(format!(
                "{}: its smallest side, {side:e} m, is within {THINNEST} times the contact tolerance ({tol:e} m, 1e-8 of the model's size or 1e-14 of its largest coordinate): its faces cannot be told apart",
                name(i)
            )));
        }
    }
    let mut out = Vec::with_capacity(4 * boxes.len());
    for_each_pair(&aabbs, tol, poll, |i, j| {
        match pair(boxes, kinds, i, j, tol) {
            Pair::None => {}
            Pair::Contact(c) => out.push(c),
            Pair::Overlap(w) => {
                return Err(Error::input(format!(
                    "{} and {} overlap (intersection {:.6} x {:.6} x {:.6} m)",
                    name(i),
                    name(j),
                    w[0],
                    w[1],
                    w[2]
                )))
            }
        }
        Ok(())
    })?;
    out.sort_by_key(|c| (c.a, c.b));
    Ok(out)
}

/// What two boxes are to each other.
enum Pair {
    /// Apart, touching along an edge or at a corner, or base against top beam.
    None,
    /// Their intersection along x, y, z \[m\]: refused.
    Overlap([f64; 3]),
    Contact(Contact),
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
fn tolerance(aabbs: &[Aabb<3>]) -> f64 {
    let around = aabbs.iter().fold(Aabb::around(&[]), |a, b| a.union(b));
    if aabbs.is_empty() {
        return 0.0;
    }
    let reach = (0..3).map(|k| around.min[k].abs().max(around.max[k].abs())).fold(0.0, f64::max);
    10.0 * REL_TOL * around.size().max(REACH * reach)
}

/// Boxes `i` and `j`: their contact if they share a rectangle.
fn pair(boxes: &[Box3], kinds: &[BlockKind], i: usize, j: usize, tol: f64) -> Pair {
    let (p, q) = (&boxes[i], &boxes[j]);
    let lo = [0, 1, 2].map(|k| p.min[k].max(q.min[k]));
    let hi = [0, 1, 2].map(|k| p.max[k].min(q.max[k]));
    let w = [0, 1, 2].map(|k| hi[k] - lo[k]);
    if w.iter().any(|&v| v < -tol) {
        return Pair::None; // apart
    }
    if w.iter().all(|&v| v > tol) {
        return Pair::Overlap(w);
    }
    let mut thin = (0..3).filter(|&k| w[k] <= tol);
    let k = thin.next().expect("one side is thin, or the boxes overlap");
    if thin.next().is_some() {
        return Pair::None; // along an edge or at a corner only
    }
    let (a, b) = if p.min[k] < q.min[k] { (i, j) } else { (j, i) };
    if kinds[a] != BlockKind::Wall && kinds[b] != BlockKind::Wall {
        return Pair::None; // base against top beam: not a joint of the wall
    }
    let family = match (kinds[a], kinds[b]) {
        (BlockKind::Base, _) | (_, BlockKind::Base) => Family::Base,
        (BlockKind::Top, _) | (_, BlockKind::Top) => Family::Top,
        _ if k == 2 => Family::Bed,
        _ => Family::Head,
    };
    let plane = 0.5 * (boxes[a].max[k] + boxes[b].min[k]);
    Pair::Contact(rectangle(a, b, k, plane, lo, hi, family))
}

/// The contact of blocks `a` and `b` on the plane `x_k = plane`, over `[lo, hi]` along the two
/// other axes, normal `+e_k`.
fn rectangle(a: usize, b: usize, k: usize, plane: f64, lo: [f64; 3], hi: [f64; 3], family: Family) -> Contact {
    // t1 = s1 e_u, t2 = e_v with t1 x t2 = e_k: (x, y) under z, (y, z) beside x, (-x, z) beside y
    let (u, s1, v) = match k {
        2 => (0, 1.0, 1),
        0 => (1, 1.0, 2),
        _ => (0, -1.0, 2),
    };
    let unit = |axis: usize, s: f64| {
        let mut e = [0.0; 3];
        e[axis] = s;
        e
    };
    let point = |plus1: bool, plus2: bool| {
        let mut c = [0.0; 3];
        c[k] = plane;
        c[u] = if plus1 == (s1 > 0.0) { hi[u] } else { lo[u] };
        c[v] = if plus2 { hi[v] } else { lo[v] };
        c
    };
    let dims = [hi[u] - lo[u], hi[v] - lo[v]];
    let mut centroid = [0.0; 3];
    centroid[k] = plane;
    centroid[u] = 0.5 * (lo[u] + hi[u]);
    centroid[v] = 0.5 * (lo[v] + hi[v]);
    Contact {
        a,
        b,
        n: unit(k, 1.0),
        t1: unit(u, s1),
        t2: unit(v, 1.0),
        corners: vec![point(false, false), point(true, false), point(true, true), point(false, true)],
        dims,
        area: dims[0] * dims[1],
        centroid,
        family,
    }
}
