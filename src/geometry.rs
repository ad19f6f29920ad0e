//! Axis-aligned rectangular blocks and the wall generators of the case format
//! (running bond with openings, pattern rows, explicit lists), and the generators of convex
//! polygons: the arches of voussoirs ([`arch`]), gable walls (a running bond cut at the rakes,
//! [`gable`]) and stone walls (courses of random convex stones, [`stone_wall`]).
//!
//! ```
//! use masonry_dem::geometry::{running_bond, RunningBond, FirstCourse};
//! // Ferris & Tin-Loi wall 1: 6 courses of 0.4 x 0.175 m blocks, 2 m long.
//! let blocks = running_bond(&RunningBond {
//!     block_length: 0.4, block_height: 0.175, courses: 6, height: None, length: 2.0,
//!     first_course: FirstCourse::Half, openings: vec![],
//! }).unwrap();
//! assert_eq!(blocks.len(), 33);
//! ```
//!
//! A wall of a given height instead of a number of courses, with a window cut out of it:
//!
//! ```
//! use masonry_dem::geometry::{running_bond, Rect, RunningBond, FirstCourse};
//! // 2.5 m of 0.12 m courses: 20 whole courses (2.4 m) and a last course cut to 0.1 m.
//! let blocks = running_bond(&RunningBond {
//!     block_length: 0.25, block_height: 0.12, courses: 0, height: Some(2.5), length: 4.0,
//!     first_course: FirstCourse::Half, openings: vec![Rect::new(1.0, 0.9, 2.2, 1.8)],
//! }).unwrap();
//! let top = blocks.iter().map(|b| b.y1).fold(0.0, f64::max);
//! assert!((top - 2.5).abs() < 1e-12);
//! // the blocks at the window's edges are cut there: exactly its 1.08 m2 is removed
//! let area: f64 = blocks.iter().map(|b| b.area()).sum();
//! assert!((4.0 * 2.5 - area - 1.2 * 0.9).abs() < 1e-9);
//! ```

use crate::error::{positive, Error, Result};

mod arch;
mod fit;
mod gable;
mod openings;
mod stone_wall;

pub use arch::{arch, Arch, ArchGeometry, ArchKind, FillStrip, Springing, MAX_VOUSSOIRS};
pub use fit::{courses_for_height, CourseFit, MIN_LAST_COURSE};
pub use gable::{gable, Gable, SLIVER};
pub use stone_wall::{stone_wall, StoneWall, MAX_BED_ANGLE, MAX_HEAD_ANGLE, MAX_IRREGULARITY, MIN_STONE};
pub use openings::{cut_openings, MIN_PART};

/// An axis-aligned rectangle `[x0, x1] x [y0, y1]` in metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rect {
    /// Left edge \[m\].
    pub x0: f64,
    /// Bottom edge \[m\].
    pub y0: f64,
    /// Right edge \[m\].
    pub x1: f64,
    /// Top edge \[m\].
    pub y1: f64,
}

impl Rect {
    /// The rectangle from corner (x0, y0) to corner (x1, y1) \[m\].
    pub fn new(x0: f64, y0: f64, x1: f64, y1: f64) -> Self {
        Rect { x0, y0, x1, y1 }
    }
    /// x1 - x0 \[m\].
    pub fn width(&self) -> f64 {
        self.x1 - self.x0
    }
    /// y1 - y0 \[m\].
    pub fn height(&self) -> f64 {
        self.y1 - self.y0
    }
    /// Width times height \[m2\].
    pub fn area(&self) -> f64 {
        self.width() * self.height()
    }
    /// The centre \[m\].
    pub fn centroid(&self) -> [f64; 2] {
        [0.5 * (self.x0 + self.x1), 0.5 * (self.y0 + self.y1)]
    }
    /// Whether the point lies strictly inside.
    pub fn contains_strictly(&self, p: [f64; 2]) -> bool {
        p[0] > self.x0 && p[0] < self.x1 && p[1] > self.y0 && p[1] < self.y1
    }
    /// "[x0, y0, x1, y1]" for messages, very large or small coordinates in exponent notation.
    pub fn label(&self) -> String {
        format!(
            "[{}, {}, {}, {}]",
            coord(self.x0),
            coord(self.y0),
            coord(self.x1),
            coord(self.y1)
        )
    }
    /// Checks that the corners are finite and the sizes positive; `what` names the block.
    pub fn validate(&self, what: &str) -> Result<()> {
        for v in [self.x0, self.y0, self.x1, self.y1] {
            if !v.is_finite() {
                return Err(Error::input(format!(
                    "{what} {}: coordinate {v} is not finite",
                    self.label()
                )));
            }
        }
        if self.x1 <= self.x0 || self.y1 <= self.y0 {
            return Err(Error::input(format!(
                "{what} {} has zero or negative size (need x0 < x1 and y0 < y1)",
                self.label()
            )));
        }
        Ok(())
    }
}

/// A coordinate for messages: as written for ordinary numbers (`0.175`), in exponent notation
/// beyond 1e15 or below 1e-4 (`1e300`, not three hundred digits).
pub(crate) fn coord(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e15).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// The rectangles as polygons, the blocks of a [`crate::model::ModelSpec`].
pub fn polygons(rects: Vec<Rect>) -> Vec<crate::shape::Polygon> {
    rects.into_iter().map(Into::into).collect()
}

/// Which block starts the lowest course of a running bond.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FirstCourse {
    /// The lowest course starts at x = 0 with a half block.
    #[default]
    Half,
    /// The lowest course starts at x = 0 with a whole block.
    Full,
}

/// Parameters of a running-bond wall (case format `[geometry.running_bond]`).
#[derive(Debug, Clone, PartialEq)]
pub struct RunningBond {
    /// Length of a whole block \[m\].
    pub block_length: f64,
    /// Height of a course \[m\].
    pub block_height: f64,
    /// Number of courses; 0 when `height` gives the wall's height instead (exactly one of the two).
    pub courses: usize,
    /// Height of the wall \[m\], instead of `courses` (which must then be 0): the whole courses that
    /// fit and, if some height is left, a last course cut to it; see [`courses_for_height`] (a
    /// last course lower than [`MIN_LAST_COURSE`] of `block_height` is refused, with the nearest fits).
    /// `None`: `courses` whole courses.
    pub height: Option<f64>,
    /// Length of the wall \[m\]; each course's end blocks are cut to it.
    pub length: f64,
    /// Which block starts the lowest course.
    pub first_course: FirstCourse,
    /// Rectangles `[x0, y0, x1, y1]` \[m\] cut out of the wall: a block partly inside one is cut at
    /// its edges into the parts outside it, so that the jambs, sill and lintel are straight and
    /// exactly the opening's area is removed, except that no part thinner than [`MIN_PART`] of the
    /// block is made (see [`cut_openings`]).
    pub openings: Vec<Rect>,
}

pub(crate) use crate::shape::REL_TOL;

/// The blocks of a running-bond wall standing on y = 0 and starting at x = 0.
/// Courses alternate between a half-block start and a whole-block start; a block that
/// would cross the end of the wall is cut there.
pub fn running_bond(p: &RunningBond) -> Result<Vec<Rect>> {
    positive("geometry.running_bond.block_length", p.block_length)?;
    positive("geometry.running_bond.block_height", p.block_height)?;
    positive("geometry.running_bond.length", p.length)?;
    let fit = course_fit(p)?;
    let courses = fit.whole + usize::from(fit.last.is_some());
    let estimate = (p.length / p.block_length + 2.0) * courses as f64;
    check_count("geometry.running_bond", estimate)?;
    check_height("geometry.running_bond", p.block_height, courses)?;
    let tol = REL_TOL * p.length.max(p.block_length);
    let mut out = Vec::with_capacity(estimate as usize);
    for k in 0..courses {
        let y0 = k as f64 * p.block_height;
        let y1 = match (k < fit.whole, p.height) {
            (false, Some(h)) => h, // the last course, cut to the wall's height
            _ => (k + 1) as f64 * p.block_height,
        };
        let half_start = (p.first_course == FirstCourse::Half) == (k % 2 == 0);
        let mut x = 0.0;
        let mut first = true;
        while x < p.length - tol {
            let w = if first && half_start {
                0.5 * p.block_length
            } else {
                p.block_length
            };
            first = false;
            let x1 = if x + w > p.length - tol {
                p.length
            } else {
                x + w
            };
            out.push(Rect::new(x, y0, x1, y1));
            x = x1;
        }
    }
    let snap = [MIN_PART * p.block_length, MIN_PART * p.block_height];
    cut_openings(out, &p.openings, snap, "geometry.running_bond.openings")
}

/// The courses of `p`: `courses` whole ones, or those of `height` (exactly one of the two given).
fn course_fit(p: &RunningBond) -> Result<CourseFit> {
    match (p.courses, p.height) {
        (0, None) => Err(Error::input(
            "geometry.running_bond.courses must be at least 1 (or give geometry.running_bond.height instead)",
        )),
        (n, None) => Ok(CourseFit { whole: n, last: None }),
        (0, Some(h)) => {
            positive("geometry.running_bond.height", h)?;
            courses_for_height(p.block_height, h)
        }
        (n, Some(h)) => Err(Error::input(format!(
            "geometry.running_bond: give exactly one of courses and height, not both (courses = {n}, height = {} m)",
            coord(h)
        ))),
    }
}

/// The blocks of a wall given course by course, bottom to top. Each entry is a length in units
/// of `block_length`; a negative entry is a gap of that length.
pub fn pattern(block_length: f64, block_height: f64, rows: &[Vec<f64>]) -> Result<Vec<Rect>> {
    positive("geometry.pattern.block_length", block_length)?;
    positive("geometry.pattern.block_height", block_height)?;
    if rows.is_empty() {
        return Err(Error::input(
            "geometry.pattern.rows is empty: give at least one course",
        ));
    }
    check_count("geometry.pattern", rows.iter().map(|r| r.len() as f64).sum())?;
    check_height("geometry.pattern", block_height, rows.len())?;
    let mut out = Vec::new();
    for (k, row) in rows.iter().enumerate() {
        let y0 = k as f64 * block_height;
        let mut x = 0.0;
        for (j, &e) in row.iter().enumerate() {
            if !e.is_finite() || e == 0.0 {
                return Err(Error::input(format!(
                    "geometry.pattern.rows[{k}][{j}] must be a finite non-zero length, got {e}"
                )));
            }
            let w = e.abs() * block_length;
            if !(x + w).is_finite() {
                return Err(Error::input(format!(
                    "geometry.pattern.rows[{k}][{j}]: course {k} is longer than the largest finite number"
                )));
            }
            if e > 0.0 {
                out.push(Rect::new(x, y0, x + w, y0 + block_height));
            }
            x += w;
        }
    }
    Ok(out)
}

/// The largest number of blocks a model may have; larger requests are refused before allocating.
/// A model of this size takes about 2.4 GB and an analysis of it about 20 GB more.
pub const MAX_BLOCKS: usize = 2_000_000;

/// The refusal of `count` blocks, above [`MAX_BLOCKS`], with the memory they would need.
pub(crate) fn too_many_blocks(what: &str, count: f64) -> Error {
    use crate::error::{format_bytes, ANALYSIS_BYTES_PER_BLOCK, MODEL_BYTES_PER_BLOCK};
    Error::input(format!(
        "{what}: about {count:.0} blocks, more than the limit of {MAX_BLOCKS} (the model would take about {} of memory, an analysis about {} more)",
        format_bytes(count * MODEL_BYTES_PER_BLOCK),
        format_bytes(count * ANALYSIS_BYTES_PER_BLOCK)
    ))
}

/// Refuses walls whose height `courses * block_height` is not a finite number.
fn check_height(what: &str, block_height: f64, courses: usize) -> Result<()> {
    if !(block_height * courses as f64).is_finite() {
        return Err(Error::input(format!(
            "{what}: {courses} courses of block_height {block_height} m make a wall higher than the largest finite number"
        )));
    }
    Ok(())
}

pub(crate) fn check_count(what: &str, estimate: f64) -> Result<()> {
    if !(estimate <= MAX_BLOCKS as f64) {
        return Err(too_many_blocks(what, estimate));
    }
    Ok(())
}
