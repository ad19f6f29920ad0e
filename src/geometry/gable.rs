//! Gable walls: a running bond under a sloping top, its blocks cut at the rakes.
//!
//! The top rises in a straight line from the eaves at x = 0 (`eaves_height`) to the ridge at
//! x = `ridge_x` (`ridge_height`) and falls again to the eaves at x = `length`: a gable. A ridge
//! at either end (`ridge_x` = 0 or `length`) makes a single slope (a lean-to). The courses are
//! those of [`running_bond`](super::running_bond) (alternating half-block and whole-block
//! starts), each block cut by the top: the intersection of a rectangle with the convex region
//! under the rakes is a convex polygon (a rectangle, a pentagon with a corner cut off, a
//! trapezoid or a triangle), so every block is convex.
//!
//! Slivers: a cut block whose area is less than [`SLIVER`] of a whole block's is merged with its
//! neighbour in the course, the one towards the ridge (the merged block is the cut of the two
//! blocks' rectangles together, convex again), until none is left; nothing is dropped, so the
//! blocks tile the gable exactly. The course at the ridge is cut to the ridge: if less than
//! [`SLIVER`] of a course would be left above the last whole course, the course below reaches up
//! to the ridge instead. A course of a single block (the gable's tip) is kept whatever its area.
//!
//! ```
//! use masonry_dem::geometry::{gable, FirstCourse, Gable};
//! // a gable 2 m long, 1 m at the eaves and 1.6 m at the ridge, of 0.4 x 0.2 m blocks
//! let blocks = gable(&Gable { block_length: 0.4, block_height: 0.2, length: 2.0, eaves_height: 1.0,
//!     ridge_height: 1.6, ridge_x: None, first_course: FirstCourse::Half }).unwrap();
//! let area: f64 = blocks.iter().map(|b| b.area_properties().area).sum();
//! assert!((area - (2.0 * 1.0 + 0.5 * 2.0 * 0.6)).abs() < 1e-12);
//! ```

use super::{coord, running_bond, FirstCourse, Rect, RunningBond};
use crate::error::{non_negative, positive, Error, Result};
use crate::shape::{contact_tolerance, Polygon};

/// The least area of a block cut at a rake, as a fraction of a whole block's (25%): a smaller
/// piece is merged with its neighbour towards the ridge; and the least height of the course at the
/// ridge, as a fraction of `block_height`: a lower one is joined to the course below.
pub const SLIVER: f64 = 0.25;

/// Parameters of a gable wall (case format `[geometry.gable]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gable {
    /// Length of a whole block \[m\].
    pub block_length: f64,
    /// Height of a course \[m\].
    pub block_height: f64,
    /// Length of the wall \[m\].
    pub length: f64,
    /// Height of the wall at both ends, where the rakes start \[m\] (0: a triangular gable).
    pub eaves_height: f64,
    /// Height of the wall at the ridge \[m\], above `eaves_height`.
    pub ridge_height: f64,
    /// Where the ridge stands, from x = 0 \[m\], in `0..=length` (0 or `length`: a single
    /// slope); `None`: mid-length.
    pub ridge_x: Option<f64>,
    /// Which block starts the lowest course.
    pub first_course: FirstCourse,
}

impl Gable {
    /// `geometry.gable.first_course`: "half" or "full".
    pub fn first_course(s: &str) -> Result<FirstCourse> {
        s.parse().map_err(|e| rename(e, "geometry.running_bond", "geometry.gable"))
    }

    /// The ridge's x \[m\].
    pub fn ridge(&self) -> f64 {
        self.ridge_x.unwrap_or(0.5 * self.length)
    }

    /// The wall's height at `x` \[m\] (0 <= x <= length): the top's piecewise-linear line.
    pub fn top(&self, x: f64) -> f64 {
        let (xr, e, r) = (self.ridge(), self.eaves_height, self.ridge_height);
        if x < xr {
            e + (r - e) * x / xr
        } else if xr == self.length {
            r
        } else {
            r - (r - e) * (x - xr) / (self.length - xr)
        }
    }

    /// The wall's area \[m2\], exactly the blocks' together.
    pub fn area(&self) -> f64 {
        0.5 * (self.eaves_height + self.ridge_height) * self.length
    }
}

/// The blocks of a gable wall standing on y = 0 from x = 0 to `length`, course by course bottom
/// to top, left to right in each course; counter-clockwise from the lowest vertex. Refusals name
/// the key (`geometry.gable.*`).
pub fn gable(p: &Gable) -> Result<Vec<Polygon>> {
    let bl = positive("geometry.gable.block_length", p.block_length)?;
    let bh = positive("geometry.gable.block_height", p.block_height)?;
    let l = positive("geometry.gable.length", p.length)?;
    non_negative("geometry.gable.eaves_height", p.eaves_height)?;
    let r = positive("geometry.gable.ridge_height", p.ridge_height)?;
    if r <= p.eaves_height {
        return Err(Error::input_at(
            "geometry.gable.ridge_height",
            format!(
                "geometry.gable.ridge_height = {} m must exceed eaves_height = {} m (a wall of one height is a running bond)",
                coord(r),
                coord(p.eaves_height)
            ),
        ));
    }
    let xr = p.ridge();
    if !(0.0..=l).contains(&xr) {
        return Err(Error::input_at(
            "geometry.gable.ridge_x",
            format!("geometry.gable.ridge_x = {} m must lie in 0..={} m (the wall's length)", coord(xr), coord(l)),
        ));
    }
    // the courses: the whole ones below the ridge, and one cut to it unless it would be a sliver
    let tol = crate::shape::REL_TOL * r.max(bh);
    let mut courses = ((r + tol) / bh).floor() as usize;
    let rest = r - courses as f64 * bh;
    if rest > SLIVER * bh || courses == 0 {
        courses += 1;
    }
    let rects = running_bond(&RunningBond {
        block_length: bl,
        block_height: bh,
        courses,
        height: None,
        length: l,
        first_course: p.first_course,
        openings: vec![],
    })
    .map_err(|e| rename(e, "geometry.running_bond", "geometry.gable"))?;
    let size = l.max(r);
    let snap = contact_tolerance(size);
    // the rakes as half-planes a.x <= c, their outward normals a (not unit: exact for any slope)
    let (e, rise) = (p.eaves_height, r - p.eaves_height);
    let mut rakes: Vec<([f64; 2], f64)> = vec![];
    if xr > 0.0 {
        rakes.push(([-rise, xr], xr * e)); // y xr - rise x <= e xr
    }
    if xr < l {
        rakes.push(([rise, l - xr], rise * l + (l - xr) * e)); // rise x + (l - xr) y <= rise l + (l - xr) e
    }
    let whole = bl * bh;
    let mut out = Vec::with_capacity(rects.len());
    let mut start = 0;
    while start < rects.len() {
        let y0 = rects[start].y0;
        let end = start + rects[start..].iter().take_while(|b| b.y0 == y0).count();
        let top_course = end == rects.len();
        // the course's blocks as x ranges, the top course reaching up to the ridge
        let y1 = if top_course { r } else { rects[start].y1 };
        let cut_at = |x0: f64, x1: f64| cut(Rect::new(x0, y0, x1, y1), &rakes, snap);
        let mut pieces: Vec<Piece> = rects[start..end]
            .iter()
            .filter_map(|b| cut_at(b.x0, b.x1).map(|outline| Piece { x0: b.x0, x1: b.x1, outline }))
            .collect();
        // merge slivers, the farthest from the ridge first, each into its neighbour towards it
        loop {
            let mid = |k: usize| 0.5 * (pieces[k].x0 + pieces[k].x1);
            let sliver = (0..pieces.len())
                .filter(|&i| pieces.len() > 1 && crate::shape::Area::of(&pieces[i].outline).area < SLIVER * whole)
                .max_by(|&i, &j| (mid(i) - xr).abs().total_cmp(&(mid(j) - xr).abs()));
            let Some(i) = sliver else { break };
            let towards = if mid(i) < xr { i + 1 } else { i.wrapping_sub(1) };
            let j = if towards < pieces.len() { towards } else if i + 1 < pieces.len() { i + 1 } else { i - 1 };
            let (a, b) = (i.min(j), i.max(j));
            let (x0, x1) = (pieces[a].x0, pieces[b].x1);
            // the two rectangles together hold the piece's outline: their cut is not empty
            let outline = cut_at(x0, x1).expect("a merged piece holds its parts");
            pieces[a] = Piece { x0, x1, outline };
            pieces.remove(b);
        }
        for piece in pieces {
            let polygon = Polygon::new(piece.outline).checked(snap).map_err(|d| {
                Error::input(format!("geometry.gable: a block cut at the rake is degenerate ({}): the wall is too small for its blocks", d.reason))
            })?;
            out.push(polygon);
        }
        start = end;
        if top_course {
            break;
        }
    }
    Ok(out)
}

/// A block of a course, the x range of its rectangle and its outline cut at the rakes.
struct Piece {
    x0: f64,
    x1: f64,
    outline: Vec<[f64; 2]>,
}

/// The error `e` with its key prefix `from` named `to` (the running bond's checks of a gable's keys).
fn rename(e: Error, from: &str, to: &str) -> Error {
    match e {
        Error::Input { reason, key } => Error::Input {
            reason: reason.replace(from, to),
            key: key.map(|k| k.replace(from, to)),
        },
        other => other,
    }
}

/// The rectangle `b` cut by the half-planes `a.x <= c` (Sutherland-Hodgman on a convex polygon):
/// its vertices counter-clockwise, or None when less than a polygon is left. A vertex within
/// `snap` \[m\] of a line stays as it is (no new vertex a rounding away from it).
fn cut(b: Rect, planes: &[([f64; 2], f64)], snap: f64) -> Option<Vec<[f64; 2]>> {
    let mut v: Vec<[f64; 2]> = vec![[b.x0, b.y0], [b.x1, b.y0], [b.x1, b.y1], [b.x0, b.y1]];
    for &(a, c) in planes {
        let norm = a[0].hypot(a[1]);
        let s = |p: [f64; 2]| (a[0] * p[0] + a[1] * p[1] - c) / norm;
        let mut next = Vec::with_capacity(v.len() + 1);
        for k in 0..v.len() {
            let (p, q) = (v[k], v[(k + 1) % v.len()]);
            let (sp, sq) = (s(p), s(q));
            if sp <= snap {
                next.push(p);
            }
            if (sp < -snap && sq > snap) || (sp > snap && sq < -snap) {
                let t = sp / (sp - sq);
                next.push([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]);
            }
        }
        if next.len() < 3 {
            return None;
        }
        v = next;
    }
    let twice: f64 = (0..v.len()).map(|k| {
        let (p, q) = (v[k], v[(k + 1) % v.len()]);
        p[0] * q[1] - p[1] * q[0]
    }).sum();
    (twice > 0.0).then_some(v)
}
