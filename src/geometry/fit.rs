//! The courses of a running-bond wall of a given height.

use super::{coord, REL_TOL};
use crate::error::{positive, Error, Result};

/// The lowest last course [`courses_for_height`] cuts, as a fraction of `block_height` (25%): a
/// lower one would be a sliver of a course (for 0.12 m courses, under 3 cm), so it is refused and
/// the nearest heights and block heights that fit are proposed instead.
pub const MIN_LAST_COURSE: f64 = 0.25;

/// The courses of a wall of a given height: `whole` courses of `block_height`, then, if `last` is
/// `Some(r)`, a last course `r` high (`MIN_LAST_COURSE * block_height <= r < block_height`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CourseFit {
    /// Courses of the full `block_height`.
    pub whole: usize,
    /// Height of the last course, cut to fit \[m\]; `None` when the whole courses fit exactly.
    pub last: Option<f64>,
}

/// The courses of a wall `height` high \[m\] built of courses `block_height` high \[m\]: as many
/// whole courses as fit, then, if more than a rounding error (1e-9 relative) is left, a last course
/// cut to that remainder. A remainder under [`MIN_LAST_COURSE`] of `block_height` is refused: the
/// message gives the nearest heights that fit (whole courses) and the block heights that divide
/// `height` into whole courses.
///
/// ```
/// use masonry_dem::geometry::courses_for_height;
/// let fit = courses_for_height(0.12, 2.5).unwrap(); // 20 courses (2.4 m) and one of 0.1 m
/// assert_eq!(fit.whole, 20);
/// assert!((fit.last.unwrap() - 0.1).abs() < 1e-12);
/// assert_eq!(courses_for_height(0.12, 2.52).unwrap().last, None); // 21 whole courses
/// let refused = courses_for_height(0.12, 2.42).unwrap_err().to_string(); // 0.02 m left
/// assert!(refused.contains("use height = 2.4 m (20 courses) or 2.52 m (21 courses)"), "{refused}");
/// ```
pub fn courses_for_height(block_height: f64, height: f64) -> Result<CourseFit> {
    positive("geometry.running_bond.block_height", block_height)?;
    positive("geometry.running_bond.height", height)?;
    let q = height / block_height;
    if !(q < 1e15) {
        return Err(Error::input(format!(
            "geometry.running_bond.height = {} m is {} courses of block_height = {} m, too many to count",
            coord(height),
            coord(q),
            coord(block_height)
        )));
    }
    // a quotient within rounding of a whole number is that number: 2.52 / 0.12 = 21.000000000000004
    let whole = (q * (1.0 + REL_TOL)).floor();
    let rest = height - whole * block_height;
    if rest <= REL_TOL * height {
        if whole >= 1.0 {
            return Ok(CourseFit {
                whole: whole as usize,
                last: None,
            });
        }
    } else if rest >= MIN_LAST_COURSE * block_height {
        return Ok(CourseFit {
            whole: whole as usize,
            last: Some(rest),
        });
    }
    Err(no_fit(block_height, height, whole as usize, rest))
}

/// The refusal of a last course `rest` high, below [`MIN_LAST_COURSE`], with the nearest fits.
fn no_fit(block_height: f64, height: f64, whole: usize, rest: f64) -> Error {
    let courses = |n: usize| {
        if n == 1 {
            "1 course".to_string()
        } else {
            format!("{n} courses")
        }
    };
    let (mut heights, mut sizes) = (vec![], vec![]);
    for n in [whole, whole + 1].into_iter().filter(|&n| n >= 1) {
        heights.push(format!(
            "{} m ({})",
            metres(n as f64 * block_height),
            courses(n)
        ));
        sizes.push(format!("{} m ({})", metres(height / n as f64), courses(n)));
    }
    Error::input(format!(
        "geometry.running_bond.height = {} m with block_height = {} m: {} ({} m) leave a last course of {} m, \
         lower than {}% of block_height ({} m); use height = {}, or block_height = {}",
        metres(height),
        metres(block_height),
        courses(whole),
        metres(whole as f64 * block_height),
        metres(rest.max(0.0)),
        MIN_LAST_COURSE * 100.0,
        metres(MIN_LAST_COURSE * block_height),
        heights.join(" or "),
        sizes.join(" or ")
    ))
}

/// A length for a message, to the micrometre (`2.4`, not `2.4000000000000004`).
fn metres(v: f64) -> String {
    if v.abs() < 1e9 && v.abs() >= 1e-4 {
        format!("{}", (v * 1e6).round() / 1e6)
    } else {
        coord(v)
    }
}
