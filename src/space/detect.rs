//! Contact detection between axis-aligned boxes: a uniform grid, as the 2D
//! [`crate::interface::detect`], so that it costs O(n) for walls of similar blocks.

use super::{Box3, Contact};
use crate::error::{Error, Result};
use crate::geometry::REL_TOL;
use crate::interface::{BlockKind, Family, POLL_EVERY};

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
    if boxes.is_empty() {
        return Ok(vec![]);
    }
    let grid = Grid::new(boxes);
    for (i, b) in boxes.iter().enumerate() {
        let side = b.size().into_iter().fold(f64::INFINITY, f64::min);
        if !(side > THINNEST * grid.tol) {
            return Err(Error::input(format!(
                "{}: its smallest side, {side:e} m, is within {THINNEST} times the contact tolerance ({:e} m, 1e-8 of the model's size or 1e-14 of its largest coordinate): its faces cannot be told apart",
                name(i),
                grid.tol
            )));
        }
    }
    let entries = grid.entries(boxes, poll)?;
    let mut out = Vec::with_capacity(4 * boxes.len());
    let mut start = 0;
    let mut visited = 0usize;
    while start < entries.len() {
        let key = entries[start].0;
        let end = start + entries[start..].iter().take_while(|e| e.0 == key).count();
        visited += 1;
        if visited % POLL_EVERY == 0 && !poll() {
            return Err(Error::Interrupted);
        }
        let members = &entries[start..end];
        for (p, &(_, i)) in members.iter().enumerate() {
            for &(_, j) in &members[p + 1..] {
                match grid.pair(boxes, kinds, i, j, key) {
                    Pair::None => {}
                    Pair::Contact(c) => out.push(c),
                    Pair::Overlap(w) => {
                        return Err(Error::input(format!(
                            "{} and {} overlap (intersection {:.6} x {:.6} x {:.6} m)",
                            name(i.min(j)),
                            name(i.max(j)),
                            w[0],
                            w[1],
                            w[2]
                        )))
                    }
                }
            }
        }
        start = end;
    }
    out.sort_by_key(|c| (c.a, c.b));
    Ok(out)
}

/// What two boxes of a cell are to each other.
enum Pair {
    /// Apart, touching along an edge or at a corner, seen in another cell, or base against top
    /// beam.
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

/// A uniform grid of cells over the boxes (each axis its own cell size, about twice the mean
/// side along it), each box entered in the cells within `tol` of it.
struct Grid {
    lo: [f64; 3],
    cell: [f64; 3],
    tol: f64,
}

impl Grid {
    fn new(boxes: &[Box3]) -> Grid {
        let (mut lo, mut hi, mut sum) = ([f64::MAX; 3], [f64::MIN; 3], [0.0; 3]);
        for b in boxes {
            for k in 0..3 {
                lo[k] = lo[k].min(b.min[k]);
                hi[k] = hi[k].max(b.max[k]);
                sum[k] += b.max[k] - b.min[k];
            }
        }
        let scale = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        let reach = (0..3).map(|k| lo[k].abs().max(hi[k].abs())).fold(0.0, f64::max);
        let tol = 10.0 * REL_TOL * scale.max(REACH * reach);
        let nb = boxes.len() as f64;
        let mut grid = Grid { lo, cell: [0, 1, 2].map(|k| (2.0 * sum[k] / nb).max(tol * 10.0)), tol };
        // A few boxes much larger than the mean would each cover very many cells: coarsen the
        // grid until it holds O(n) entries (as in 2D), so memory stays linear in the boxes.
        while grid.count(boxes) > 16.0 * nb + 1024.0 {
            grid.cell = grid.cell.map(|c| 2.0 * c);
        }
        grid
    }

    /// The number of (cell, box) entries, as a float (it may be huge before coarsening).
    fn count(&self, boxes: &[Box3]) -> f64 {
        let span = |b: &Box3, k: usize| {
            ((b.max[k] + self.tol - self.lo[k]) / self.cell[k]).floor()
                - ((b.min[k] - self.tol - self.lo[k]) / self.cell[k]).floor()
                + 1.0
        };
        boxes.iter().map(|b| span(b, 0) * span(b, 1) * span(b, 2)).sum()
    }

    fn cell_of(&self, x: f64, k: usize) -> i64 {
        ((x - self.lo[k]) / self.cell[k]).floor() as i64
    }

    /// Every (cell, box) pair, sorted by cell: the boxes of one cell are consecutive.
    fn entries(&self, boxes: &[Box3], poll: &mut dyn FnMut() -> bool) -> Result<Vec<([i64; 3], usize)>> {
        let mut out = Vec::with_capacity(4 * boxes.len());
        let t = self.tol;
        for (i, b) in boxes.iter().enumerate() {
            if i % POLL_EVERY == POLL_EVERY - 1 && !poll() {
                return Err(Error::Interrupted);
            }
            let r = |k: usize| self.cell_of(b.min[k] - t, k)..=self.cell_of(b.max[k] + t, k);
            for cx in r(0) {
                for cy in r(1) {
                    for cz in r(2) {
                        out.push(([cx, cy, cz], i));
                    }
                }
            }
        }
        out.sort_unstable();
        Ok(out)
    }

    /// Boxes `i` and `j`, both in cell `key`: their contact if they share a rectangle and this
    /// cell holds the lowest corner of their intersection (each pair is seen once).
    fn pair(&self, boxes: &[Box3], kinds: &[BlockKind], i: usize, j: usize, key: [i64; 3]) -> Pair {
        let tol = self.tol;
        let (p, q) = (&boxes[i], &boxes[j]);
        let lo = [0, 1, 2].map(|k| p.min[k].max(q.min[k]));
        let hi = [0, 1, 2].map(|k| p.max[k].min(q.max[k]));
        let w = [0, 1, 2].map(|k| hi[k] - lo[k]);
        if w.iter().any(|&v| v < -tol) {
            return Pair::None; // apart
        }
        // an overlap is refused in the first cell that sees it (before the test below: the
        // copies of one box would otherwise be paired in every cell they share)
        if w.iter().all(|&v| v > tol) {
            return Pair::Overlap(w);
        }
        if [0, 1, 2].map(|k| self.cell_of(lo[k], k)) != key {
            return Pair::None;
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
