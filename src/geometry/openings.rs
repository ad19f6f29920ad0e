//! Openings cut out of a generated wall.

use super::Rect;
use crate::error::Result;

/// The thinnest part of a block [`cut_openings`] makes, as a fraction of the whole block's size
/// (5%: of `block_length` across, of `block_height` up): an opening's edge closer than this to a
/// block's edge is moved onto it, so no sliver of a block is left, nor a sliver taken off one.
pub const MIN_PART: f64 = 0.05;

/// `blocks` with the rectangles `openings` \[m\] cut out. A block partly inside an opening is cut at
/// the opening's edges into the parts outside it: the part left of the opening and the part right
/// of it, each the block's full height, and between them the parts below and above the opening. A
/// block wholly inside is removed; one beside it is kept as it is. The jambs, the sill and the
/// lintel are therefore straight, and a block straddling a jamb becomes a partial block ending at
/// it.
///
/// Snapping: an opening's edge closer to one of a block's edges than `snap` \[m\] (`[across, up]`)
/// is moved onto that edge for that block, so that no part thinner than `snap` is made or cut off;
/// a block that an opening crosses over less than `snap` (a thin opening) is left whole.
/// The area removed is then exactly the area of the openings' union within the wall, except where
/// an edge was snapped: there it differs by at most the snap distance times the edge's length.
/// [`running_bond`](super::running_bond) snaps at [`MIN_PART`] of its block's length and height.
///
/// Each opening is checked (finite, positive size); `what` names the list in the messages.
///
/// ```
/// use masonry_dem::geometry::{cut_openings, Rect};
/// let block = Rect::new(0.0, 0.0, 0.4, 0.2);
/// // a window whose left jamb crosses the block: its left 0.1 m is kept
/// let cut = cut_openings(vec![block], &[Rect::new(0.1, -1.0, 2.0, 1.0)], [0.02, 0.01], "openings").unwrap();
/// assert_eq!(cut, vec![Rect::new(0.0, 0.0, 0.1, 0.2)]);
/// // a sill 5 mm above the block's bottom (less than the 1 cm snap): the block is removed whole
/// let cut = cut_openings(vec![block], &[Rect::new(-1.0, 0.005, 2.0, 1.0)], [0.02, 0.01], "openings").unwrap();
/// assert!(cut.is_empty());
/// ```
pub fn cut_openings(
    blocks: Vec<Rect>,
    openings: &[Rect],
    snap: [f64; 2],
    what: &str,
) -> Result<Vec<Rect>> {
    for (i, o) in openings.iter().enumerate() {
        o.validate(&format!("{what}[{i}]"))?;
    }
    let mut out = blocks;
    for o in openings {
        let mut next = Vec::with_capacity(out.len() + 8);
        for b in out {
            cut(b, o, snap, &mut next);
        }
        out = next;
    }
    Ok(out)
}

/// Pushes onto `out` the parts of block `b` outside opening `o`, left to right (left, below, above,
/// right), the opening's edges snapped onto the block's within `snap`.
fn cut(b: Rect, o: &Rect, snap: [f64; 2], out: &mut Vec<Rect>) {
    let x0 = snapped(o.x0, b.x0, b.x1, snap[0]);
    let x1 = snapped(o.x1, b.x0, b.x1, snap[0]);
    let y0 = snapped(o.y0, b.y0, b.y1, snap[1]);
    let y1 = snapped(o.y1, b.y0, b.y1, snap[1]);
    let (mx0, mx1) = (x0.max(b.x0), x1.min(b.x1));
    if mx1 - mx0 < snap[0].max(f64::MIN_POSITIVE)
        || y1.min(b.y1) - y0.max(b.y0) < snap[1].max(f64::MIN_POSITIVE)
    {
        // beside the opening, touching it, or crossed by a part of it thinner than the snap (no
        // sliver is cut out)
        out.push(b);
        return;
    }
    if x0 > b.x0 {
        out.push(Rect::new(b.x0, b.y0, x0, b.y1));
    }
    if y0 > b.y0 {
        out.push(Rect::new(mx0, b.y0, mx1, y0));
    }
    if y1 < b.y1 {
        out.push(Rect::new(mx0, y1, mx1, b.y1));
    }
    if x1 < b.x1 {
        out.push(Rect::new(x1, b.y0, b.x1, b.y1));
    }
}

/// `v` moved onto `lo` or `hi` if it lies within `snap` of it.
fn snapped(v: f64, lo: f64, hi: f64, snap: f64) -> f64 {
    if (v - lo).abs() < snap {
        lo
    } else if (v - hi).abs() < snap {
        hi
    } else {
        v
    }
}
