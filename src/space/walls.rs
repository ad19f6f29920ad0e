//! Generators of 3D walls of boxes: a single leaf in running bond, a U (a facade with two
//! return walls) and an L (a facade with one return), bonded at the corners, a wall with
//! buttresses, and openings cut out of a facade.
//!
//! Every course is laid along its wall with head joints every `block_length`, half a block
//! apart from one course to the next. No piece thinner than [`MIN_PART`] of a block is made: a
//! joint that would fall closer than that to the end of a course is left out, so the block at
//! that end is longer by as much (at most `block_length` + [`MIN_PART`] of it; at a bonded
//! corner, by the wall's thickness more).

use super::{coord, Box3};
use crate::error::{positive, Error, Result};
use crate::geometry::{courses_for_height, too_many_blocks, Rect, MAX_BLOCKS, MIN_PART, REL_TOL};

/// A single leaf in running bond: along x from x = 0 to `length`, y in `[0, thickness]`, z
/// from 0 to `height` \[m\], of blocks `block_length` x `thickness` x `block_height` \[m\].
///
/// `first_course_offset` \[m\], in `[0, block_length)`, shifts the lowest course's joints to
/// the left: 0 starts it with a whole block at x = 0, half a block starts it with a half block;
/// each course above is shifted by half a block more than the one below, so that the courses
/// alternate and the ends of every other course are half blocks (as the 2D
/// [`crate::geometry::running_bond`], whose `FirstCourse::Half` is an offset of half a block).
/// A height that is not a whole number of courses gets a last course cut to fit, as in 2D
/// ([`courses_for_height`]: a last course under a quarter of `block_height` is refused).
///
/// ```
/// use masonry_dem::space::running_bond_3d;
/// let blocks = running_bond_3d(1.2, 0.4, 0.1, 0.4, 0.2, 0.0).unwrap();
/// assert_eq!(blocks.len(), 3 + 4); // 3 whole blocks, then a half, 2 whole and a half
/// let volume: f64 = blocks.iter().map(|b| b.volume()).sum();
/// assert!((volume - 1.2 * 0.4 * 0.1).abs() < 1e-15);
/// ```
pub fn running_bond_3d(
    length: f64,
    height: f64,
    thickness: f64,
    block_length: f64,
    block_height: f64,
    first_course_offset: f64,
) -> Result<Vec<Box3>> {
    let what = "running_bond_3d";
    let l = positive(&format!("{what}.block_length"), block_length)?;
    positive(&format!("{what}.length"), length)?;
    positive(&format!("{what}.height"), height)?;
    positive(&format!("{what}.thickness"), thickness)?;
    positive(&format!("{what}.block_height"), block_height)?;
    let o = first_course_offset;
    if !(o.is_finite() && o >= 0.0 && o < l) {
        return Err(Error::input_at(
            format!("{what}.first_course_offset"),
            format!("{what}.first_course_offset must lie in [0, block_length = {l}) m (0 or half a block), got {o}"),
        ));
    }
    check_count(what, (length / l + 2.0) * (height / block_height + 1.0))?;
    let m = MIN_PART * l;
    let mut out = vec![];
    for (k, (z0, z1)) in courses(what, height, block_height)?.into_iter().enumerate() {
        let shift = if k % 2 == 0 { o } else { (o + 0.5 * l).rem_euclid(l) };
        for (x0, x1) in pieces(0.0, length, l, -shift, m, m) {
            out.push(Box3::new(x0, 0.0, z0, x1, thickness, z1));
        }
    }
    Ok(out)
}

/// A U of three walls one block thick: a facade along x (x in `[0, facade]`, y in
/// `[0, thickness]`) and two return walls along +y at its ends (x in `[0, thickness]` and
/// `[facade - thickness, facade]`, y up to `returns`), `height` high, so the U's outside is
/// `facade` x `returns` in plan \[m\].
///
/// The corners are bonded as real ones: in the even courses (the lowest is course 0) the facade's
/// end block runs over the corner and the return walls start against it; in the odd courses the
/// returns' end blocks run over the corner and the facade starts against them. Each corner block
/// thus lies on, and carries, blocks of both walls. Within each wall the courses are in running
/// bond (joints half a block apart); `block_length` must exceed `thickness` by [`MIN_PART`] of a
/// block at least, so that a corner block reaches past the corner.
///
/// ```
/// use masonry_dem::space::u_wall;
/// let blocks = u_wall(2.0, 0.4, 1.0, 0.2, 0.4, 0.2).unwrap();
/// let volume: f64 = blocks.iter().map(|b| b.volume()).sum();
/// assert!((volume - (2.0 + 2.0 * 0.8) * 0.2 * 0.4).abs() < 1e-12);
/// ```
pub fn u_wall(
    facade: f64,
    height: f64,
    returns: f64,
    thickness: f64,
    block_length: f64,
    block_height: f64,
) -> Result<Vec<Box3>> {
    bonded("u_wall", [facade, height, returns, thickness, block_length, block_height], true)
}

/// An L of two walls one block thick: a facade along x (x in `[0, facade]`, y in
/// `[0, thickness]`) and one return wall along +y at x = 0 (x in `[0, thickness]`, y up to
/// `returns`), `height` high \[m\], the corner bonded as in [`u_wall`]; the facade's far end is
/// free.
///
/// ```
/// use masonry_dem::space::corner;
/// let blocks = corner(1.6, 0.4, 1.0, 0.2, 0.4, 0.2).unwrap();
/// let volume: f64 = blocks.iter().map(|b| b.volume()).sum();
/// assert!((volume - (1.6 + 0.8) * 0.2 * 0.4).abs() < 1e-12);
/// ```
pub fn corner(
    facade: f64,
    height: f64,
    returns: f64,
    thickness: f64,
    block_length: f64,
    block_height: f64,
) -> Result<Vec<Box3>> {
    bonded("corner", [facade, height, returns, thickness, block_length, block_height], false)
}

/// The facade with a bonded return wall at x = 0 and, if `right`, another at x = `facade`.
fn bonded(what: &str, args: [f64; 6], right: bool) -> Result<Vec<Box3>> {
    let names = ["facade", "height", "returns", "thickness", "block_length", "block_height"];
    for (name, v) in names.iter().zip(args) {
        positive(&format!("{what}.{name}"), v)?;
    }
    let [f, height, r, t, l, bh] = args;
    let m = MIN_PART * l;
    if t > l - m {
        return Err(Error::input_at(
            format!("{what}.thickness"),
            format!("{what}.thickness = {t} m must be less than block_length = {l} m by {MIN_PART} of it at least: a corner block must reach past the corner to bond the two walls"),
        ));
    }
    if r - t < m {
        return Err(Error::input_at(
            format!("{what}.returns"),
            format!("{what}.returns = {r} m must exceed thickness = {t} m by {MIN_PART} of block_length at least (it is the return walls' length from the facade's outer face)"),
        ));
    }
    let ends = if right { 2.0 } else { 1.0 };
    if f - ends * t < m {
        return Err(Error::input_at(
            format!("{what}.facade"),
            format!("{what}.facade = {f} m must exceed {ends} x thickness = {t} m by {MIN_PART} of block_length at least"),
        ));
    }
    let walls = 1.0 + ends;
    check_count(what, walls * ((f.max(r)) / l + 3.0) * (height / bh + 1.0))?;
    let mut out = vec![];
    for (k, (z0, z1)) in courses(what, height, bh)?.into_iter().enumerate() {
        let facade_owns = k % 2 == 0;
        let (phase, start) = if facade_owns { (0.0, 0.0) } else { (0.5 * l, t) };
        let (keep0, keep1) = if facade_owns { (t + m, if right { t + m } else { m }) } else { (m, m) };
        let end = if right && !facade_owns { f - t } else { f };
        for (x0, x1) in pieces(start, end, l, phase, keep0, keep1) {
            out.push(Box3::new(x0, 0.0, z0, x1, t, z1));
        }
        let (phase, start, keep0) = if facade_owns { (0.5 * l, t, m) } else { (0.0, 0.0, t + m) };
        for (y0, y1) in pieces(start, r, l, phase, keep0, m) {
            out.push(Box3::new(0.0, y0, z0, t, y1, z1));
            if right {
                out.push(Box3::new(f - t, y0, z0, f, y1, z1));
            }
        }
    }
    Ok(out)
}

/// Parameters of a buttressed wall (case format `[geometry.buttressed_wall]`), lengths in m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ButtressedWall {
    /// The wall along x, from x = 0.
    pub length: f64,
    /// The wall's and the buttresses' height (courses as [`running_bond_3d`]'s).
    pub height: f64,
    /// The wall's thickness, y in `[0, thickness]`.
    pub thickness: f64,
    /// A whole block's length along the wall.
    pub block_length: f64,
    /// A course's height.
    pub block_height: f64,
    /// The buttresses' spacing, axis to axis: their axes at x = `spacing` (k + 1/2).
    pub spacing: f64,
    /// A buttress's width along the wall.
    pub buttress_width: f64,
    /// A buttress's depth out of the wall's face y = 0, y in `[-buttress_depth, 0]`.
    pub buttress_depth: f64,
    /// Bonded: in every other course (the lowest, the third, ...) the buttress's block runs
    /// through the wall (y from `-buttress_depth` to `thickness`) and the wall's course stops
    /// against it; in the others the wall's course runs on behind the buttress. Not bonded: the
    /// buttresses are columns of blocks against the wall's face.
    pub bonded: bool,
}

/// A wall in running bond (as [`running_bond_3d`]'s: the lowest course starts with a whole
/// block at x = 0, the next with a half) with buttresses against its face y = 0, each a column
/// of one block per course, `buttress_width` x `buttress_depth`, their axes at x = `spacing`
/// (k + 1/2) for every k whose buttress ends 5% of a block ([`MIN_PART`]) short of the wall's
/// end at least; bonded to the wall or not ([`ButtressedWall::bonded`]). The blocks course by
/// course from the bottom, each course the wall's pieces along +x, then the buttresses'.
/// Refusals name their key, `buttressed_wall.*`: a length not positive, a spacing less than
/// the buttress's width and 10% of a block (the wall between two buttresses, or at an end, is
/// a piece 5% of a block long at least), a wall too short for one buttress.
///
/// ```
/// use masonry_dem::space::{buttressed_wall, ButtressedWall};
/// let p = ButtressedWall { length: 2.4, height: 0.6, thickness: 0.2, block_length: 0.4, block_height: 0.2,
///     spacing: 1.2, buttress_width: 0.4, buttress_depth: 0.4, bonded: true };
/// let blocks = buttressed_wall(&p).unwrap();
/// let volume: f64 = blocks.iter().map(|b| b.volume()).sum();
/// assert!((volume - (2.4 * 0.2 + 2.0 * 0.4 * 0.4) * 0.6).abs() < 1e-12);
/// ```
pub fn buttressed_wall(p: &ButtressedWall) -> Result<Vec<Box3>> {
    let what = "buttressed_wall";
    let names = ["length", "height", "thickness", "block_length", "block_height", "spacing", "buttress_width", "buttress_depth"];
    let args = [p.length, p.height, p.thickness, p.block_length, p.block_height, p.spacing, p.buttress_width, p.buttress_depth];
    for (name, v) in names.iter().zip(args) {
        positive(&format!("{what}.{name}"), v)?;
    }
    let [length, height, t, l, bh, s, bw, d] = args;
    let m = MIN_PART * l;
    if s < bw + 2.0 * m {
        return Err(Error::input_at(
            format!("{what}.spacing"),
            format!("{what}.spacing = {s} m must exceed buttress_width = {bw} m by {} of block_length at least (the wall between two buttresses)", 2.0 * MIN_PART),
        ));
    }
    check_count(what, (length / l + 2.0 + 2.0 * length / s) * (height / bh + 1.0))?;
    let axes: Vec<f64> = (0..).map(|k| s * (k as f64 + 0.5)).take_while(|&a| a + 0.5 * bw + m <= length).collect();
    if axes.is_empty() {
        return Err(Error::input_at(
            format!("{what}.length"),
            format!("{what}.length = {length} m holds no buttress: the first, at x = spacing / 2 = {} m, ends at {} m, not 5% of a block short of the wall's end", 0.5 * s, 0.5 * (s + bw)),
        ));
    }
    let mut out = vec![];
    for (k, (z0, z1)) in courses(what, height, bh)?.into_iter().enumerate() {
        let through = p.bonded && k % 2 == 0;
        let phase = if k % 2 == 0 { 0.0 } else { 0.5 * l };
        // the wall's stretches: between the buttresses where they run through it, else whole
        let mut ends = vec![0.0];
        if through {
            ends.extend(axes.iter().flat_map(|&a| [a - 0.5 * bw, a + 0.5 * bw]));
        }
        ends.push(length);
        for w in ends.chunks(2) {
            for (x0, x1) in pieces(w[0], w[1], l, phase, m, m) {
                out.push(Box3::new(x0, 0.0, z0, x1, t, z1));
            }
        }
        let back = if through { t } else { 0.0 };
        out.extend(axes.iter().map(|&a| Box3::new(a - 0.5 * bw, -d, z0, a + 0.5 * bw, back, z1)));
    }
    Ok(out)
}

/// The pieces of a course from `s0` to `s1` \[m\]: joints at `phase + j l` for every integer
/// `j`, except those within `keep0` of `s0` or `keep1` of `s1` (the end pieces are that long at
/// least).
pub(super) fn pieces(s0: f64, s1: f64, l: f64, phase: f64, keep0: f64, keep1: f64) -> Vec<(f64, f64)> {
    let mut cuts = vec![s0];
    let mut j = ((s0 + keep0 - phase) / l).floor() as i64;
    loop {
        let p = phase + j as f64 * l;
        j += 1;
        if p <= s0 + keep0 {
            continue;
        }
        if p >= s1 - keep1 {
            break;
        }
        cuts.push(p);
    }
    cuts.push(s1);
    cuts.windows(2).map(|w| (w[0], w[1])).collect()
}

/// The courses (z0, z1) of a wall `height` high of courses `block_height` high \[m\]: the whole
/// ones, then a last one cut to fit, as in 2D; `what` names the generator in the refusal.
fn courses(what: &str, height: f64, block_height: f64) -> Result<Vec<(f64, f64)>> {
    // the 2D fit's message names the 2D generator's keys: name this one's
    let fit = courses_for_height(block_height, height).map_err(|e| e.renamed("geometry.running_bond", what))?;
    let mut out: Vec<(f64, f64)> =
        (0..fit.whole).map(|k| (k as f64 * block_height, (k + 1) as f64 * block_height)).collect();
    if fit.last.is_some() {
        out.push((fit.whole as f64 * block_height, height));
    }
    Ok(out)
}

/// Refuses a wall of about `estimate` blocks, more than [`MAX_BLOCKS`], before laying it.
fn check_count(what: &str, estimate: f64) -> Result<()> {
    if !(estimate <= MAX_BLOCKS as f64) {
        return Err(too_many_blocks(what, estimate));
    }
    Ok(())
}

/// `blocks` with the facade's openings cut out. An opening `[x0, z0, x1, z1]` \[m\] is a hole
/// through the facade: the blocks whose outer face is the facade's (the smallest y of all the
/// blocks, y = 0 for the generators here) are cut over their whole depth in y, as the 2D
/// [`crate::geometry::cut_openings`] cuts rectangles in (x, z): a block partly inside is cut at
/// the opening's edges into the parts outside it (straight jambs, sill and lintel), a block wholly
/// inside is removed, and no part thinner than [`MIN_PART`] of the block (across and up) is made
/// or cut off (the opening's edge is snapped onto the block's there). Exactly the opening's
/// volume is removed where no edge was snapped.
///
/// An opening partly outside the facade cuts the part of it that lies within, as in 2D (a door
/// from below the ground, a notch at an end of the wall); one that lies wholly outside the facade
/// (the box around its blocks in x and z), or only touches its edge, is refused, naming it by its
/// index and coordinates: it would remove nothing. So are openings that remove every block, and
/// an opening that reaches a block deeper in y than the facade (a return wall's block running
/// over a corner): openings belong in the facade, clear of the corners.
///
/// ```
/// use masonry_dem::space::{cut_openings, running_bond_3d};
/// let wall = running_bond_3d(2.0, 1.2, 0.1, 0.4, 0.2, 0.2).unwrap();
/// let cut = cut_openings(wall, &[[0.5, 0.3, 1.3, 1.0]]).unwrap();
/// let volume: f64 = cut.iter().map(|b| b.volume()).sum();
/// assert!((volume - (2.0 * 1.2 - 0.8 * 0.7) * 0.1).abs() < 1e-12);
/// ```
pub fn cut_openings(blocks: Vec<Box3>, openings: &[[f64; 4]]) -> Result<Vec<Box3>> {
    let rects: Vec<Rect> = openings.iter().map(|o| Rect::new(o[0], o[1], o[2], o[3])).collect();
    for (i, r) in rects.iter().enumerate() {
        check_opening(i, r)?;
    }
    if rects.is_empty() || blocks.is_empty() {
        return Ok(blocks);
    }
    let (mut ymin, mut scale) = (f64::MAX, 0.0f64);
    for b in &blocks {
        ymin = ymin.min(b.min[1]);
        scale = scale.max(b.min.iter().chain(&b.max).fold(0.0, |a, v| a.max(v.abs())));
    }
    let tol = REL_TOL * scale.max(1.0);
    let on_facade = |b: &Box3| (b.min[1] - ymin).abs() <= tol;
    // the facade's extent in (x, z): an opening must overlap it
    let facade = blocks.iter().filter(|b| on_facade(b)).fold([f64::MAX, f64::MAX, f64::MIN, f64::MIN], |e, b| {
        [e[0].min(b.min[0]), e[1].min(b.min[2]), e[2].max(b.max[0]), e[3].max(b.max[2])]
    });
    for (i, r) in rects.iter().enumerate() {
        if r.x1.min(facade[2]) - r.x0.max(facade[0]) <= tol || r.y1.min(facade[3]) - r.y0.max(facade[1]) <= tol {
            return Err(Error::input_at(format!("openings[{i}]"), format!(
                "openings[{i}] [x0, z0, x1, z1] = {} lies outside the wall (its facade spans x from {} to {} m, z from {} to {} m): an opening must overlap the wall",
                r.label(),
                rounded(facade[0]),
                rounded(facade[2]),
                rounded(facade[1]),
                rounded(facade[3])
            )));
        }
    }
    let depth = blocks.iter().filter(|b| on_facade(b)).map(|b| b.max[1] - b.min[1]).fold(f64::MAX, f64::min);
    let mut out = Vec::with_capacity(blocks.len() + 8 * rects.len());
    for (i, b) in blocks.into_iter().enumerate() {
        if !on_facade(&b) {
            out.push(b);
            continue;
        }
        let r = Rect::new(b.min[0], b.min[2], b.max[0], b.max[2]);
        let snap = [MIN_PART * r.width(), MIN_PART * r.height()];
        let parts = crate::geometry::cut_openings(vec![r], &rects, snap, "openings")?;
        if parts == [r] {
            out.push(b);
            continue;
        }
        if b.max[1] - b.min[1] > depth + tol {
            return Err(Error::input_at("openings", format!(
                "openings: block {i} {} runs {} m deep from the facade (a return wall's block over a corner), deeper than the facade's {depth} m: keep the openings in the facade, clear of the corners",
                b.label(),
                b.max[1] - b.min[1]
            )));
        }
        out.extend(parts.into_iter().map(|p| Box3::new(p.x0, b.min[1], p.y0, p.x1, b.max[1], p.y1)));
    }
    if out.is_empty() {
        return Err(Error::input_at("openings", "openings: the openings remove every block of the wall: keep some wall around them"));
    }
    Ok(out)
}

/// A coordinate summed from blocks (1.0499999999999998) for messages, to 10 significant digits.
fn rounded(v: f64) -> String {
    coord(format!("{v:.9e}").parse().unwrap_or(v))
}

/// Checks opening `i` `[x0, z0, x1, z1]` alone: finite, with x1 > x0 and z1 > z0.
fn check_opening(i: usize, r: &Rect) -> Result<()> {
    let what = format!("openings[{i}] [x0, z0, x1, z1] = {}", r.label());
    if [r.x0, r.y0, r.x1, r.y1].iter().any(|v| !v.is_finite()) {
        return Err(Error::input_at(format!("openings[{i}]"), format!("{what}: a coordinate is not finite")));
    }
    if r.x1 <= r.x0 || r.y1 <= r.y0 {
        return Err(Error::input_at(
            format!("openings[{i}]"),
            format!("{what} has zero or negative size (need x0 < x1 and z0 < z1)"),
        ));
    }
    Ok(())
}
