//! Stone walls: courses of random convex stones with inclined joints, seeded and reproducible.
//!
//! The wall stands on y = 0 from x = 0 to `length`, its top at y = `height`: a flat base and a
//! flat top. Its courses are the strips between straight bed joints across the whole wall; the
//! stones of a course are the quadrilaterals between its head joints, each a straight segment
//! from the course's lower bed joint to its upper one. A stone's edges on a bed joint lie on the
//! same line as those of the stones beyond it, and the two stones either side of a head joint
//! share its two ends (the same numbers): every joint is a shared edge, without gap or overlap.
//!
//! - Courses: `round(height / stone_height)` of them (at least one), their heights drawn
//!   uniformly in `stone_height (1 +- irregularity)`, then scaled to fill `height` exactly.
//! - Bed joints: the base and the top horizontal; each joint between two courses through its
//!   level at mid-length with a slope drawn uniformly within `+-tan(bed_angle)`, and less where
//!   the courses either side would be left less than half their height at the wall's ends (the
//!   slope is then at most the lower of the two courses' heights over twice the length).
//! - Head joints: along each course from x = 0, a stone's length at the course's mid-line drawn
//!   uniformly in `stone_length (1 +- irregularity)`, its joint through that point at an angle
//!   from the vertical drawn uniformly within `+-head_angle`. A joint that would leave a stone
//!   shorter than [`MIN_STONE`] of `stone_length` along a bed joint (the two joints leaning
//!   towards each other) is made vertical, and moved along the course if it still would. A joint
//!   whose lower end would lie less than [`MIN_STONE`] of `stone_length` from the upper end of a
//!   joint of the course below, along their bed joint, is moved along the course past it (a
//!   bond: no head joint runs on through two courses, and no interface is a sliver). The course's
//!   last stone runs to x = `length`: no joint is placed less than half a mean stone from the end.
//!
//! Stones are convex: two segments across a strip that do not cross bound a convex
//! quadrilateral with the strip's two lines. The numbers come from a SplitMix64 generator seeded
//! with `seed` and from additions, multiplications and divisions alone (the tangents of the
//! angles are summed as series, not taken from the platform's library): the same parameters give
//! the same wall, bit for bit, on any machine.
//!
//! ```
//! use masonry_dem::geometry::{stone_wall, StoneWall};
//! let p = StoneWall { length: 3.0, height: 1.5, stone_length: 0.4, stone_height: 0.25,
//!     irregularity: 0.3, head_angle: 20.0, bed_angle: 3.0, seed: 7 };
//! let stones = stone_wall(&p).unwrap();
//! let area: f64 = stones.iter().map(|s| s.area_properties().area).sum();
//! assert!((area - 4.5).abs() < 1e-12);
//! assert_eq!(stones, stone_wall(&p).unwrap()); // the same seed, the same wall
//! ```

use super::{check_count, coord};
use crate::error::{non_negative, positive, Error, Result};
use crate::shape::{contact_tolerance, Polygon};

/// The shortest stone along a bed joint, and the least distance between the head joints of two
/// courses along the bed joint between them, as a fraction of `stone_length` (25%).
pub const MIN_STONE: f64 = 0.25;

/// The largest `irregularity`.
pub const MAX_IRREGULARITY: f64 = 0.5;

/// The largest bound on the head joints' inclination from the vertical \[degrees\].
pub const MAX_HEAD_ANGLE: f64 = 30.0;

/// The largest bound on the bed joints' inclination from the horizontal \[degrees\].
pub const MAX_BED_ANGLE: f64 = 10.0;

/// Parameters of a stone wall (case format `[geometry.stone_wall]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StoneWall {
    /// Length of the wall \[m\].
    pub length: f64,
    /// Height of the wall \[m\].
    pub height: f64,
    /// Mean length of a stone along its course \[m\].
    pub stone_length: f64,
    /// Mean height of a course \[m\].
    pub stone_height: f64,
    /// Relative spread of the stones' lengths and the courses' heights, in 0..=0.5: each drawn
    /// uniformly within the mean times (1 +- irregularity).
    pub irregularity: f64,
    /// Bound on the head joints' inclination from the vertical \[degrees\], in 0..=30.
    pub head_angle: f64,
    /// Bound on the bed joints' inclination from the horizontal \[degrees\], in 0..=10 (0: the
    /// courses horizontal).
    pub bed_angle: f64,
    /// The random generator's seed.
    pub seed: u64,
}

/// SplitMix64 (Steele, Lea and Flood 2014; the seeding generator of the xoshiro family): a
/// 64-bit state advanced by a constant, its output mixed by two multiply-xorshifts.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [-1, 1): the top 53 bits as a fraction, exact.
    fn symmetric(&mut self) -> f64 {
        let u = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        2.0 * u - 1.0
    }
}

/// tan(`deg` degrees) for |deg| <= 30, by the series of sine and cosine: additions,
/// multiplications and divisions only, the same bits on every machine.
fn tan_degrees(deg: f64) -> f64 {
    let x = deg * (std::f64::consts::PI / 180.0);
    let (mut sin, mut cos, mut term_s, mut term_c) = (0.0, 0.0, x, 1.0);
    for k in 0..12 {
        sin += term_s;
        cos += term_c;
        let (a, b) = ((2 * k + 2) as f64, (2 * k + 3) as f64);
        term_s = -term_s * x * x / (a * b);
        term_c = -term_c * x * x / ((a - 1.0) * a);
    }
    sin / cos
}

/// A straight bed joint: y = level + slope (x - mid).
#[derive(Clone, Copy)]
struct Bed {
    level: f64,
    slope: f64,
}

/// The point where the head joint through `(x, y)` with dx/dy = `t` meets bed `b` (at mid-length `mid`).
fn meet(x: f64, y: f64, t: f64, b: Bed, mid: f64) -> [f64; 2] {
    let yb = (b.level + b.slope * (x - mid - t * y)) / (1.0 - b.slope * t);
    [x + t * (yb - y), yb]
}

/// The stones of a stone wall, course by course bottom to top, left to right in each course,
/// counter-clockwise from the lowest vertex. Refusals name the key (`geometry.stone_wall.*`).
pub fn stone_wall(p: &StoneWall) -> Result<Vec<Polygon>> {
    let l = positive("geometry.stone_wall.length", p.length)?;
    let h = positive("geometry.stone_wall.height", p.height)?;
    let sl = positive("geometry.stone_wall.stone_length", p.stone_length)?;
    let sh = positive("geometry.stone_wall.stone_height", p.stone_height)?;
    let bounded = |key: &str, v: f64, max: f64, unit: &str| -> Result<f64> {
        let name = format!("geometry.stone_wall.{key}");
        non_negative(&name, v)?;
        if v > max {
            return Err(Error::input_at(&name, format!("{name} must lie in 0..={max}{unit}, got {}", coord(v))));
        }
        Ok(v)
    };
    let irr = bounded("irregularity", p.irregularity, MAX_IRREGULARITY, "")?;
    let head = bounded("head_angle", p.head_angle, MAX_HEAD_ANGLE, " degrees")?;
    let bed = bounded("bed_angle", p.bed_angle, MAX_BED_ANGLE, " degrees")?;
    if l < sl {
        return Err(Error::input_at(
            "geometry.stone_wall.length",
            format!("geometry.stone_wall.length = {} m is less than one stone (stone_length = {} m)", coord(l), coord(sl)),
        ));
    }
    let courses = (h / sh).round().max(1.0);
    check_count("geometry.stone_wall", courses * (l / sl + 2.0))?;
    let courses = courses as usize;
    let mut rng = SplitMix64(p.seed);
    // the courses' heights, scaled to the wall's; the levels with the top exactly at `height`
    let drawn: Vec<f64> = (0..courses).map(|_| sh * (1.0 + irr * rng.symmetric())).collect();
    let total: f64 = drawn.iter().sum();
    let mut levels = Vec::with_capacity(courses + 1);
    let mut sum = 0.0;
    levels.push(0.0);
    for d in &drawn[..courses - 1] {
        sum += d;
        levels.push(h * (sum / total));
    }
    levels.push(h);
    let mid = 0.5 * l;
    let tan_bed = tan_degrees(bed);
    let beds: Vec<Bed> = (0..=courses)
        .map(|k| {
            let slope = if k == 0 || k == courses {
                0.0
            } else {
                let least = (levels[k] - levels[k - 1]).min(levels[k + 1] - levels[k]);
                let bound = tan_bed.min(least / (2.0 * l));
                bound * rng.symmetric()
            };
            Bed { level: levels[k], slope }
        })
        .collect();
    let tan_head = tan_degrees(head);
    let w_min = MIN_STONE * sl;
    let tol = contact_tolerance(l.max(h));
    let mut out = Vec::new();
    // the upper ends' x of the head joints of the course below, along this course's lower bed joint
    let mut below: Vec<f64> = vec![];
    for k in 0..courses {
        let (lo, hi) = (beds[k], beds[k + 1]);
        let on = |b: Bed, x: f64| b.level + b.slope * (x - mid);
        // the previous joint's ends on the lower and upper bed joints
        let (mut b0, mut t0) = ([0.0, on(lo, 0.0)], [0.0, on(hi, 0.0)]);
        let mut xc = 0.0;
        let mut tops = vec![];
        // a length within rounding of w_min is w_min (a joint moved to w_min from another)
        let apart = |a: f64, b: f64| b - a >= w_min * (1.0 - 1e-9);
        loop {
            let w = sl * (1.0 + irr * rng.symmetric());
            let mut t = tan_head * rng.symmetric();
            xc += w;
            // the joint through (xc, the course's mid-line) at dx/dy = t: moved along the course
            // past a joint of the course below that it would meet, made vertical and moved where
            // it would leave a stone too short; none less than half a stone from the end
            let placed = loop {
                if l - xc < 0.5 * sl {
                    break None;
                }
                let ym = 0.5 * (on(lo, xc) + on(hi, xc));
                let (b1, t1) = (meet(xc, ym, t, lo, mid), meet(xc, ym, t, hi, mid));
                if let Some(&x) = below.iter().find(|&&x| !apart(x, b1[0]) && !apart(b1[0], x)) {
                    xc += x + w_min - b1[0];
                    continue;
                }
                if !(apart(b0[0], b1[0]) && apart(t0[0], t1[0]) && apart(b1[0], l) && apart(t1[0], l)) {
                    t = 0.0;
                    xc = xc.max(b0[0] + w_min).max(t0[0] + w_min);
                    if !apart(xc, l) {
                        break None;
                    }
                    continue;
                }
                break Some((b1, t1));
            };
            let Some((b1, t1)) = placed else { break };
            out.push(stone(b0, b1, t1, t0, tol)?);
            tops.push(t1[0]);
            (b0, t0) = (b1, t1);
        }
        out.push(stone(b0, [l, on(lo, l)], [l, on(hi, l)], t0, tol)?);
        below = tops;
    }
    Ok(out)
}

/// The stone of corners `b0`, `b1` (on its lower bed joint, left to right) and `t1`, `t0` (on
/// its upper one), checked.
fn stone(b0: [f64; 2], b1: [f64; 2], t1: [f64; 2], t0: [f64; 2], tol: f64) -> Result<Polygon> {
    Polygon::new(vec![b0, b1, t1, t0])
        .checked(tol)
        .map_err(|d| Error::input(format!("geometry.stone_wall: a stone is degenerate ({}): the wall is too small for its stones", d.reason)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitmix64_gives_the_reference_sequence() {
        // the first outputs of the reference implementation (Vigna's splitmix64.c) seeded with 1234567
        let mut g = SplitMix64(1_234_567);
        let got: Vec<u64> = (0..3).map(|_| g.next_u64()).collect();
        assert_eq!(got, [6_457_827_717_110_365_317, 3_203_168_211_198_807_973, 9_817_491_932_198_370_423]);
    }

    #[test]
    fn the_series_tangent_is_the_libraries_to_the_last_bits() {
        for deg in [0.0, 1.0, 5.0, 10.0, 17.5, 29.0, 30.0, -30.0] {
            let want = f64::tan(deg * (std::f64::consts::PI / 180.0));
            assert!((tan_degrees(deg) - want).abs() <= 4.0 * f64::EPSILON * want.abs().max(1e-300), "{deg}: {} against {want}", tan_degrees(deg));
        }
    }
}
