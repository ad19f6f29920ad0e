//! Arches of voussoirs: semicircular, segmental, pointed and elliptical, on abutments or on
//! piers.
//!
//! The intrados stands on the springing line y = 0, symmetric about x = 0. Each voussoir is the
//! quadrilateral between two joints, its intrados and extrados the straight chords between the
//! joints' ends (the ends lie on the curves; the voussoirs' area is the curved ring's less the
//! segments the chords cut off the extrados, plus those they add under the intrados). Joints:
//!
//! - circular arches (semicircular, segmental, each half of a pointed arch): radial, the
//!   extrados concentric with the intrados, `thickness` further out; a pointed arch has a
//!   vertical joint at its crown (an even number of voussoirs: its intrados comes to a point
//!   there, which no convex keystone could follow);
//! - elliptical arches: normal to the intrados (an ellipse of semi-axes span / 2 and rise), at
//!   equal steps of the ellipse's parametric angle, the extrados the intrados offset by
//!   `thickness` along them (a parallel curve, not an ellipse).
//!
//! The joints divide each circular arc into equal angles. The arch stands on two abutments
//! (fixed supports whose top is the springing joint, then horizontal out to their width) or on
//! two piers of wall blocks in courses (the top course's top the springing joint, then
//! horizontal), standing on the base.
//!
//! A backfill ([`Arch::backfill`], its top a level above the springing line) is a dead load over
//! the extrados: each voussoir carries the fill in the vertical strip over its extrados chord, up
//! to the level, as a [`CarriedLoad`] ([`ArchGeometry::fill_loads`]) on the vertical through the
//! strip's centroid, at the extrados there. It models the fill's weight and its mass, which moves
//! with the voussoir under it (so it takes the horizontal live load and a ground motion as the
//! voussoir's own weight does); not the fill's lateral pressure, its strength, its spreading of
//! the load, nor the fill over the abutments or piers.
//!
//! ```
//! use masonry_dem::geometry::{arch, Arch, ArchKind, Springing};
//! use masonry_dem::model::{Model, ModelSpec};
//! // a semicircular arch of 20 voussoirs, centreline radius 2 m, 0.3 m thick, on abutments
//! let a = arch(&Arch { kind: ArchKind::Semicircular, span: None, radius: Some(2.0), rise: None,
//!     thickness: 0.3, voussoirs: 20, springing: Springing::Abutments { width: None, height: None },
//!     backfill: None }).unwrap();
//! assert_eq!((a.blocks.len(), a.supports.len()), (20, 2));
//! let model = Model::new(ModelSpec { blocks: a.blocks, supports: a.supports, base: false, ..ModelSpec::default() }).unwrap();
//! assert_eq!(model.interfaces().len(), 21); // 19 joints between voussoirs and two springings
//! ```

use crate::error::{positive, Error, Result};
use crate::model::CarriedLoad;
use crate::shape::{Area, Polygon};
use std::f64::consts::PI;

/// The shape of an arch's intrados.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArchKind {
    /// A half circle: rise = span / 2.
    Semicircular,
    /// An arc of a circle less than a half, springing from inclined joints (skewbacks).
    Segmental,
    /// Two arcs of equal radius meeting at the crown (rise at least span / 2).
    Pointed,
    /// A half ellipse of semi-axes span / 2 and rise.
    Elliptical,
}

impl std::str::FromStr for ArchKind {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "semicircular" => Ok(ArchKind::Semicircular),
            "segmental" => Ok(ArchKind::Segmental),
            "pointed" => Ok(ArchKind::Pointed),
            "elliptical" => Ok(ArchKind::Elliptical),
            _ => Err(Error::input_at(
                "geometry.arch.kind",
                format!("geometry.arch.kind must be \"semicircular\", \"segmental\", \"pointed\" or \"elliptical\", got {s:?}"),
            )),
        }
    }
}

/// What an arch stands on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Springing {
    /// Two fixed supports: each from the intrados's springing point out to `width` \[m\]
    /// (horizontally; at least the springing joint's extent, which `None` gives), `height`
    /// \[m\] deep below it (`None`: the arch's thickness).
    Abutments {
        /// Horizontal extent from the intrados's springing point outwards \[m\].
        width: Option<f64>,
        /// Depth below the intrados's springing point \[m\].
        height: Option<f64>,
    },
    /// Two piers of wall blocks on the base, from the intrados's springing point out to `width`
    /// \[m\], `height` \[m\] from the ground to it, in `courses` courses of equal height (1: a
    /// single block each).
    Piers {
        /// Horizontal extent from the intrados's springing point outwards \[m\].
        width: f64,
        /// From the ground to the intrados's springing point \[m\].
        height: f64,
        /// Courses of each pier.
        courses: usize,
    },
}

/// Parameters of an arch (case format `[geometry.arch]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arch {
    /// The intrados's shape.
    pub kind: ArchKind,
    /// The clear span between the intrados's springing points \[m\]; or give `radius`
    /// (semicircular and segmental arches).
    pub span: Option<f64>,
    /// The radius of the centreline, midway between intrados and extrados \[m\] (semicircular and
    /// segmental arches), instead of `span`.
    pub radius: Option<f64>,
    /// The intrados's rise above the springing line \[m\]: segmental, pointed and elliptical
    /// arches (a semicircular arch's is span / 2).
    pub rise: Option<f64>,
    /// The ring's thickness, along the joints \[m\].
    pub thickness: f64,
    /// The number of voussoirs: at least 2 (a segmental arch: 1), even for a pointed arch.
    pub voussoirs: usize,
    /// Abutments or piers.
    pub springing: Springing,
    /// The level of a backfill's top \[m\], above the springing line (y = 0): the fill lies
    /// over the extrados up to it (and the voussoirs whose extrados rises above it carry none
    /// there); `None`, no fill.
    pub backfill: Option<f64>,
}

/// The fill over one voussoir: the part of the vertical strip over its extrados chord below the
/// backfill's level.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FillStrip {
    /// The voussoir (its index among the blocks).
    pub block: usize,
    /// The strip's area in the arch's plane \[m2\].
    pub area: f64,
    /// The strip's centroid \[m\].
    pub centroid: [f64; 2],
    /// Where its weight rests: the extrados chord's point under the centroid \[m\].
    pub point: [f64; 2],
}

/// An arch made: its blocks and supports, and the curves they follow.
#[derive(Debug, Clone, PartialEq)]
pub struct ArchGeometry {
    /// The voussoirs, from the left springing to the right, then the piers' blocks (the left
    /// pier's courses bottom to top, then the right's); counter-clockwise.
    pub blocks: Vec<Polygon>,
    /// The two abutments (left, right), or none on piers.
    pub supports: Vec<Polygon>,
    /// The joints' intrados ends, left to right (with the crown's apex of a pointed arch) \[m\].
    pub intrados: Vec<[f64; 2]>,
    /// The joints' extrados ends, left to right \[m\].
    pub extrados: Vec<[f64; 2]>,
    /// The backfill over each voussoir that has any, left to right (empty without a backfill).
    pub fill: Vec<FillStrip>,
}

impl ArchGeometry {
    /// The backfill's weights as loads carried by the voussoirs: each strip's area times
    /// `density` \[kg/m3\], the wall's out-of-plane `thickness` \[m\] and `gravity` \[m/s2\]
    /// (the model's: its mass is then the fill's, density times volume), at the strip's point.
    pub fn fill_loads(&self, density: f64, thickness: f64, gravity: f64) -> Result<Vec<CarriedLoad>> {
        let density = positive("geometry.arch.backfill.density", density)?;
        let thickness = positive("geometry.thickness", thickness)?;
        let gravity = positive("loads.gravity", gravity)?;
        Ok(self.fill.iter().map(|s| CarriedLoad { block: s.block, point: s.point, weight: density * thickness * gravity * s.area }).collect())
    }
}

/// The most voussoirs an arch may have.
pub const MAX_VOUSSOIRS: usize = 100_000;

/// Makes an arch: checks the parameters (each refusal names its key, `geometry.arch.*`), lays
/// the joints out and cuts the voussoirs, abutments or piers.
pub fn arch(p: &Arch) -> Result<ArchGeometry> {
    let t = positive("geometry.arch.thickness", p.thickness)?;
    // a half circle or a half ellipse in one voussoir would be flat: two at least
    let least = if p.kind == ArchKind::Segmental { 1 } else { 2 };
    if !(least..=MAX_VOUSSOIRS).contains(&p.voussoirs) {
        return Err(Error::input_at(
            "geometry.arch.voussoirs",
            format!("geometry.arch.voussoirs of a {} arch must lie in {least}..={MAX_VOUSSOIRS}, got {}", kind_name(p.kind), p.voussoirs),
        ));
    }
    let joints = match p.kind {
        ArchKind::Semicircular | ArchKind::Segmental => circular(p, t)?,
        ArchKind::Pointed => pointed(p, t)?,
        ArchKind::Elliptical => elliptical(p, t)?,
    };
    let n = joints.len() - 1;
    let mut blocks: Vec<Polygon> = (0..n)
        .map(|k| {
            let ([i0, e0], [i1, e1]) = (joints[k], joints[k + 1]);
            Polygon::new(vec![i0, i1, e1, e0]) // counter-clockwise
        })
        .collect();
    let intrados: Vec<[f64; 2]> = joints.iter().map(|j| j[0]).collect();
    let extrados: Vec<[f64; 2]> = joints.iter().map(|j| j[1]).collect();
    let fill = match p.backfill {
        Some(level) => backfill(&extrados, level)?,
        None => vec![],
    };
    // the left side's blocks: the right's mirrored, counter-clockwise again
    let mirror = |q: &Polygon| Polygon::new(q.vertices().iter().rev().map(|v| [-v[0], v[1]]).collect());
    let right = joints[n]; // [intrados, extrados] of the right springing
    let supports = match p.springing {
        Springing::Abutments { width, height } => {
            let x1 = reach(right, width, "geometry.arch.abutment_width")?;
            let h = match height {
                Some(h) => positive("geometry.arch.abutment_height", h)?,
                None => t,
            };
            let abutment = skewback(right, x1, right[0][1] - h);
            vec![mirror(&abutment), abutment]
        }
        Springing::Piers { width, height, courses } => {
            let x1 = reach(right, Some(width), "geometry.arch.pier_width")?;
            let h = positive("geometry.arch.pier_height", height)?;
            if !(1..=MAX_VOUSSOIRS).contains(&courses) {
                return Err(Error::input_at(
                    "geometry.arch.pier_courses",
                    format!("geometry.arch.pier_courses must lie in 1..={MAX_VOUSSOIRS}, got {courses}"),
                ));
            }
            let (x0, y_top) = (right[0][0], right[0][1]);
            let level = |k: usize| if k == courses { y_top } else { y_top - h + h * k as f64 / courses as f64 };
            let pier: Vec<Polygon> = (0..courses)
                .map(|k| {
                    if k + 1 == courses {
                        skewback(right, x1, level(k))
                    } else {
                        Polygon::new(vec![[x0, level(k)], [x1, level(k)], [x1, level(k + 1)], [x0, level(k + 1)]])
                    }
                })
                .collect();
            blocks.extend(pier.iter().map(mirror));
            blocks.extend(pier);
            vec![]
        }
    };
    Ok(ArchGeometry { blocks, supports, intrados, extrados, fill })
}

/// The fill up to `level` over each chord of the `extrados` (the joints' ends, left to right):
/// the strip between the chord and the level, cut where the chord rises above the level.
fn backfill(extrados: &[[f64; 2]], level: f64) -> Result<Vec<FillStrip>> {
    let key = "geometry.arch.backfill.level";
    let level = positive(key, level)?;
    let lowest = extrados.iter().map(|e| e[1]).fold(f64::INFINITY, f64::min);
    if !(level > lowest) {
        return Err(Error::input_at(
            key,
            format!("{key} = {level} m does not reach the extrados, whose lowest point is {lowest:.6} m above the springing line: no fill would rest on the arch"),
        ));
    }
    Ok(extrados
        .windows(2)
        .enumerate()
        .filter_map(|(block, chord)| {
            let [e0, e1] = [chord[0], chord[1]];
            // the strip counter-clockwise (along the chord, up, back along the level), cut at y = level
            let strip = [e0, e1, [e1[0], level], [e0[0], level]];
            let below = below_level(&strip, level);
            let Area { area, centroid, .. } = Area::of(&below);
            if below.len() < 3 || !(area > 0.0) {
                return None;
            }
            let s = (centroid[0] - e0[0]) / (e1[0] - e0[0]);
            let point = [centroid[0], e0[1] + s * (e1[1] - e0[1])];
            Some(FillStrip { block, area, centroid, point })
        })
        .collect())
}

/// The part of the polygon `v` on or below y = `level` (the polygon cut by the line; convex
/// stays convex).
fn below_level(v: &[[f64; 2]], level: f64) -> Vec<[f64; 2]> {
    let mut out = Vec::with_capacity(v.len() + 1);
    for (i, &p) in v.iter().enumerate() {
        let q = v[(i + 1) % v.len()];
        if p[1] <= level {
            out.push(p);
        }
        if (p[1] - level) * (q[1] - level) < 0.0 {
            let s = (level - p[1]) / (q[1] - p[1]);
            out.push([p[0] + s * (q[0] - p[0]), level]);
        }
    }
    out
}

/// The outer face's x of a support under the right springing joint `joint` ([intrados end,
/// extrados end]), `width` out from the intrados end: at least the joint's extent, which `None`
/// gives (the extrados end's x itself).
fn reach(joint: [[f64; 2]; 2], width: Option<f64>, key: &str) -> Result<f64> {
    let least = joint[1][0] - joint[0][0];
    match width {
        None => Ok(joint[1][0]),
        Some(w) => {
            positive(key, w)?;
            if w < least * (1.0 - 1e-12) {
                return Err(Error::input_at(
                    key,
                    format!("{key} = {w} m is less than the springing joint's horizontal extent, {least:.6} m: the support would not carry the whole joint"),
                ));
            }
            Ok((joint[0][0] + w).max(joint[1][0]))
        }
    }
}

/// The block under a right springing joint `joint` ([intrados end, extrados end]): its top the
/// joint, then horizontal out to `x1`, its sides vertical, its bottom at `bottom`.
fn skewback(joint: [[f64; 2]; 2], x1: f64, bottom: f64) -> Polygon {
    let [inner, outer] = joint;
    let mut v = vec![[inner[0], bottom], [x1, bottom], [x1, outer[1]]];
    if x1 > outer[0] {
        v.push(outer);
    }
    v.push(inner);
    Polygon::new(v)
}

/// The value of key `geometry.arch.<key>`, required for this kind of arch.
fn required(p: &Arch, key: &str, value: Option<f64>) -> Result<f64> {
    let name = format!("geometry.arch.{key}");
    match value {
        Some(v) => positive(&name, v),
        None => Err(Error::input_at(&name, format!("{name} is required for a {} arch", kind_name(p.kind)))),
    }
}

fn kind_name(k: ArchKind) -> &'static str {
    match k {
        ArchKind::Semicircular => "semicircular",
        ArchKind::Segmental => "segmental",
        ArchKind::Pointed => "pointed",
        ArchKind::Elliptical => "elliptical",
    }
}

fn no_key(p: &Arch, key: &str, given: bool) -> Result<()> {
    if given {
        return Err(Error::input_at(
            format!("geometry.arch.{key}"),
            format!("geometry.arch.{key} is not taken by a {} arch", kind_name(p.kind)),
        ));
    }
    Ok(())
}

/// The joints of a semicircular or segmental arch, left to right: [intrados end, extrados end].
fn circular(p: &Arch, t: f64) -> Result<Vec<[[f64; 2]; 2]>> {
    // the intrados's radius r and the half span s
    let (r, s) = match (p.span, p.radius) {
        (Some(_), Some(_)) => {
            return Err(Error::input_at("geometry.arch.radius", "geometry.arch.radius and geometry.arch.span are both given: give one"))
        }
        (None, Some(rc)) => {
            let rc = positive("geometry.arch.radius", rc)?;
            if rc <= 0.5 * t {
                return Err(Error::input_at(
                    "geometry.arch.radius",
                    format!("geometry.arch.radius = {rc} m (the centreline's) must exceed half the thickness, {} m", 0.5 * t),
                ));
            }
            (rc - 0.5 * t, None)
        }
        (Some(s), None) => (f64::NAN, Some(0.5 * positive("geometry.arch.span", s)?)),
        (None, None) => {
            return Err(Error::input_at("geometry.arch.span", "geometry.arch.span (or geometry.arch.radius) is required"))
        }
    };
    let (r, centre_y, start) = match p.kind {
        ArchKind::Semicircular => {
            no_key(p, "rise", p.rise.is_some())?;
            (s.unwrap_or(r), 0.0, 0.0)
        }
        _ => {
            let f = required(p, "rise", p.rise)?;
            // the half span from the radius, or the radius from the half span
            let (r, s) = match s {
                Some(s) => ((s * s + f * f) / (2.0 * f), s),
                None => (r, (f * (2.0 * r - f)).max(0.0).sqrt()),
            };
            if !(f < r) || s.is_nan() {
                return Err(Error::input_at(
                    "geometry.arch.rise",
                    format!("geometry.arch.rise = {f} m must be less than the intrados's radius ({r:.6} m): a segment less than a half circle (a half circle is semicircular)"),
                ));
            }
            (r, f - r, (r - f).atan2(s))
        }
    };
    let n = p.voussoirs;
    let (ri, re) = (r, r + t);
    Ok(symmetric(n, |k| {
        // from the crown (angle pi / 2, k = n / 2) to the right springing (angle `start`)
        let a = PI - start - (PI - 2.0 * start) * k as f64 / n as f64;
        let (sa, ca) = if 2 * k == n { (1.0, 0.0) } else { a.sin_cos() };
        [[ri * ca, centre_y + ri * sa], [re * ca, centre_y + re * sa]]
    }))
}

/// The joints of a pointed arch: each half an arc of the intrados's radius about a centre on
/// the springing line, the crown's joint vertical.
fn pointed(p: &Arch, t: f64) -> Result<Vec<[[f64; 2]; 2]>> {
    no_key(p, "radius", p.radius.is_some())?;
    let s = 0.5 * required(p, "span", p.span)?;
    let f = required(p, "rise", p.rise)?;
    if f < s {
        return Err(Error::input_at(
            "geometry.arch.rise",
            format!("geometry.arch.rise = {f} m of a pointed arch must be at least half its span ({s} m)"),
        ));
    }
    if p.voussoirs % 2 == 1 {
        return Err(Error::input_at(
            "geometry.arch.voussoirs",
            format!("geometry.arch.voussoirs = {} for a pointed arch must be even: its crown is a joint", p.voussoirs),
        ));
    }
    // the right half's arc: centre (-d, 0), radius r through (s, 0) and (0, f)
    let r = (s * s + f * f) / (2.0 * s);
    let d = r - s;
    let (n, half) = (p.voussoirs, p.voussoirs / 2);
    let apex = (d / r).acos();
    Ok(symmetric(n, |k| {
        if k == half {
            return [[0.0, f], [0.0, ((r + t) * (r + t) - d * d).sqrt()]];
        }
        let a = apex * (n - k) as f64 / half as f64;
        let (sa, ca) = a.sin_cos();
        [[-d + r * ca, r * sa], [-d + (r + t) * ca, (r + t) * sa]]
    }))
}

/// The joints of an elliptical arch: normal to the intrados, at equal steps of its parametric
/// angle, the extrados `t` out along them.
fn elliptical(p: &Arch, t: f64) -> Result<Vec<[[f64; 2]; 2]>> {
    no_key(p, "radius", p.radius.is_some())?;
    let a = 0.5 * required(p, "span", p.span)?;
    let b = required(p, "rise", p.rise)?;
    let n = p.voussoirs;
    Ok(symmetric(n, |k| {
        let th = PI - PI * k as f64 / n as f64;
        let (s, c) = if 2 * k == n { (1.0, 0.0) } else { th.sin_cos() };
        let (x, y) = (a * c, b * s);
        let (nx, ny) = (b * c, a * s);
        let l = nx.hypot(ny);
        [[x, y], [x + t * nx / l, y + t * ny / l]]
    }))
}

/// The `n + 1` joints of an arch of `n` voussoirs, left to right: `right(k)` for the crown and
/// the right half (`2 k >= n`), their mirror images about x = 0 on the left, so that the arch is
/// symmetric to the last bit.
fn symmetric(n: usize, right: impl Fn(usize) -> [[f64; 2]; 2]) -> Vec<[[f64; 2]; 2]> {
    let m = |v: [f64; 2]| [-v[0], v[1]];
    (0..=n)
        .map(|k| {
            if 2 * k < n {
                let j = right(n - k);
                [m(j[0]), m(j[1])]
            } else {
                right(k)
            }
        })
        .collect()
}
