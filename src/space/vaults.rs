//! Generators of vaults and domes of convex polyhedra, from the plane's arch
//! ([`crate::geometry::arch`]): a barrel vault (the arch extruded along its axis, in courses
//! with staggered joints, on abutments or on walls), a cross vault (two such barrels crossing
//! over a square bay, each web's voussoirs clipped by the groins, on corner supports or piers)
//! and a dome (the arch's half revolved about its axis, of meridian and parallel joints).
//!
//! The arch lies in the plane (x, z), z up, its springing line z = 0, symmetric about x = 0,
//! as the plane's arch in (x, y). A barrel vault's axis is y, from y = 0 to its length; a cross
//! vault's bay is centred on the z axis; a dome's axis is z.
//!
//! ```
//! use masonry_dem::geometry::{Arch, ArchKind, Springing};
//! use masonry_dem::space::{barrel_vault, BarrelVault, Model3, ModelSpec3};
//! // a semicircular vault of 9 voussoirs, 1.2 m long in courses of 0.4 m blocks, on abutments
//! let arch = Arch { kind: ArchKind::Semicircular, span: None, radius: Some(2.0), rise: None,
//!     thickness: 0.3, voussoirs: 9, springing: Springing::Abutments { width: None, height: None }, backfill: None };
//! let v = barrel_vault(&BarrelVault { arch, length: 1.2, block_length: Some(0.4) }).unwrap();
//! assert_eq!((v.blocks.len(), v.supports.len()), (5 * 3 + 4 * 4, 2)); // the odd courses start with a half
//! let m = Model3::new(&ModelSpec3 { polyhedra: v.blocks, supports: v.supports, base: false, ..ModelSpec3::default() }).unwrap();
//! assert_eq!(m.n_blocks(), 33);
//! ```

use super::walls::pieces;
use crate::error::{positive, Error, Result};
use crate::geometry::{arch, check_count, Arch, ArchKind, Springing, MAX_VOUSSOIRS, MIN_PART};
use crate::shape::{contact_tolerance, Polyhedron};
use std::f64::consts::PI;

/// Parameters of a barrel vault (case format `[geometry.barrel_vault]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BarrelVault {
    /// Its cross-section, an arch of the plane (x, z) on abutments or on piers (the piers become
    /// walls along the axis, in courses as the vault's).
    pub arch: Arch,
    /// Along the axis (y) \[m\].
    pub length: f64,
    /// The blocks' length along the axis \[m\]: each course (a voussoir of the arch, or a course
    /// of a pier, extruded) is cut into blocks this long, every other course starting with a half
    /// block (joints staggered by half a block, no piece shorter than
    /// [`MIN_PART`] of a block: a joint that would fall closer to an end is left out). `None`: the
    /// arch extruded one block deep, each course a single block the vault's length.
    pub block_length: Option<f64>,
}

/// A vault or a dome made: its blocks and fixed supports.
#[derive(Debug, Clone, PartialEq)]
pub struct Vaulted {
    /// The blocks: a barrel vault's course by course in the arch's order of blocks, each
    /// course along +y; a cross vault's web by web, then its piers' ([`cross_vault`]); a dome's
    /// ring by ring from the springing up, each ring counter-clockwise from +x.
    pub blocks: Vec<Polyhedron>,
    /// The fixed supports: a barrel vault's two abutments (the arch's, the vault's length), a
    /// cross vault's four under its corners; none on walls or piers or under a dome, which
    /// stand on the base.
    pub supports: Vec<Polyhedron>,
}

/// Makes a barrel vault: checks the parameters (each refusal names its key,
/// `geometry.barrel_vault.*`, the arch's as well), lays the arch out and extrudes it.
pub fn barrel_vault(p: &BarrelVault) -> Result<Vaulted> {
    let what = "geometry.barrel_vault";
    let length = positive(&format!("{what}.length"), p.length)?;
    let l = match p.block_length {
        Some(b) => positive(&format!("{what}.block_length"), b)?,
        None => length,
    };
    check_count(what, (p.arch.voussoirs as f64 + 2.0 * courses_of(&p.arch.springing) as f64) * (length / l + 2.0))?;
    let section = arch(&p.arch).map_err(|e| e.renamed("geometry.arch", what))?;
    let keep = MIN_PART * l;
    let mut blocks = vec![];
    for (k, q) in section.blocks.iter().enumerate() {
        // one block deep: a single piece; else every other course starts with a half block
        let spans = match p.block_length {
            None => vec![(0.0, length)],
            Some(_) => pieces(0.0, length, l, if k % 2 == 0 { 0.0 } else { 0.5 * l }, keep, keep),
        };
        blocks.extend(spans.into_iter().map(|(y0, y1)| Polyhedron::prism(q.vertices(), [y0, y1])));
    }
    let supports = section.supports.iter().map(|q| Polyhedron::prism(q.vertices(), [0.0, length])).collect();
    Ok(Vaulted { blocks, supports })
}

/// Parameters of a cross (groin) vault (case format `[geometry.cross_vault]`): two barrel
/// vaults of one arch crossing at right angles over a square bay.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrossVault {
    /// The barrels' section, an arch of the plane (x, z), semicircular or pointed (a horizontal
    /// springing joint), without backfill; its abutments become fixed supports under the four
    /// corners, its piers four corner piers.
    pub arch: Arch,
}

/// Makes a cross vault: the plane's arch in the plane (x, z), springing at z = 0, extruded along
/// y over the square bay `|x|, |y| <= a` (`a` the extrados's half span at the springing, so
/// that the bay's sides are the shell's outer faces), crossed by the same barrel along x; each
/// barrel is kept where its tunnel is the higher, `|x| <= |y|` for the barrel along y: each
/// voussoir of each of the four webs is the voussoir's prism from the bay's side to the centre
/// clipped by the two diagonal vertical planes `x = y` and `x = -y` (the groins), a convex
/// block. Across a groin a web's voussoir meets the crossing web's same voussoir face to face
/// (both faces are the arch's voussoir drawn on the diagonal plane). The blocks: the web over
/// y > 0 (the arch's voussoirs left to right), then the same web turned by 90, 180 and 270
/// degrees about z (over x < 0, y < 0, x > 0).
///
/// What the arch stands on stands under each corner, as a square in plan: the right abutment
/// (`|x|` and `|y|` from the intrados's half span out to the abutment's width) becomes four fixed
/// supports; the right pier's courses become four piers of free blocks on the base, listed
/// after the vault's, corner by corner in the order of the webs' turns (+x +y, -x +y, -x -y,
/// +x -y), each bottom to top. Refusals name their key, `geometry.cross_vault.*` (the arch's
/// as well).
pub fn cross_vault(p: &CrossVault) -> Result<Vaulted> {
    let what = "geometry.cross_vault";
    if !matches!(p.arch.kind, ArchKind::Semicircular | ArchKind::Pointed) {
        return Err(Error::input_at(format!("{what}.kind"), format!("{what}.kind must be \"semicircular\" or \"pointed\" (a horizontal springing joint on the corners)")));
    }
    if p.arch.backfill.is_some() {
        return Err(Error::input_at(format!("{what}.backfill"), format!("{what}: a backfill over the webs is not modelled")));
    }
    let piers = courses_of(&p.arch.springing);
    check_count(what, 4.0 * (p.arch.voussoirs + piers) as f64)?;
    let section = arch(&p.arch).map_err(|e| e.renamed("geometry.arch", what))?;
    let n = section.blocks.len() - 2 * piers;
    let a = section.extrados[0][0].abs();
    let tol = contact_tolerance(2.0 * a);
    // the web over y > 0: each voussoir's prism from the centre to the bay's side, clipped by
    // the groins (kept: y >= x and y >= -x)
    let mut web = Vec::with_capacity(n);
    for (k, q) in section.blocks[..n].iter().enumerate() {
        let prism = Polyhedron::prism(q.vertices(), [0.0, a]);
        let block = prism.clip([1.0, -1.0, 0.0], 0.0, tol).and_then(|b| b.clip([-1.0, -1.0, 0.0], 0.0, tol));
        web.push(block.ok_or_else(|| {
            Error::input_at(format!("{what}.voussoirs"), format!("{what}: voussoir {k} of a web has no volume between the groins: fewer voussoirs or a thicker shell"))
        })?);
    }
    // turned by quarter turns about z, exactly: (x, y) -> (-y, x)
    let turn = |b: &Polyhedron, quarters: usize| b.map(|v| (0..quarters).fold(v, |[x, y, z], _| [-y, x, z]));
    let mut blocks: Vec<Polyhedron> = (0..4).flat_map(|q| web.iter().map(move |b| turn(b, q))).collect();
    // the right abutment, or the right pier's courses, as squares at the corner +x +y
    let right = match p.arch.springing {
        Springing::Abutments { .. } => &section.supports[1..],
        Springing::Piers { .. } => &section.blocks[n + piers..],
    };
    let squares: Vec<Polyhedron> = right
        .iter()
        .map(|q| {
            let b = q.aabb();
            Polyhedron::cuboid([b.min[0], b.min[0], b.min[1]], [b.max[0], b.max[0], b.max[1]])
        })
        .collect();
    let corners = (0..4).flat_map(|q| squares.iter().map(move |b| turn(b, q)));
    if piers == 0 {
        return Ok(Vaulted { blocks, supports: corners.collect() });
    }
    blocks.extend(corners);
    Ok(Vaulted { blocks, supports: vec![] })
}

fn courses_of(s: &Springing) -> usize {
    match *s {
        Springing::Abutments { .. } => 0,
        Springing::Piers { courses, .. } => courses.min(MAX_VOUSSOIRS),
    }
}

/// The profile of a dome's meridian.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DomeKind {
    /// A hemisphere: the semicircular arch's half revolved.
    Hemispherical,
    /// The pointed arch's half revolved (rise at least half the span).
    Pointed,
}

impl std::str::FromStr for DomeKind {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "hemispherical" => Ok(DomeKind::Hemispherical),
            "pointed" => Ok(DomeKind::Pointed),
            _ => Err(Error::input_at("geometry.dome.kind", format!("geometry.dome.kind must be \"hemispherical\" or \"pointed\", got {s:?}"))),
        }
    }
}

/// Parameters of a dome (case format `[geometry.dome]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dome {
    /// The meridian's profile.
    pub kind: DomeKind,
    /// The intrados's diameter at the springing \[m\]; or give `radius` (hemispherical).
    pub span: Option<f64>,
    /// The radius of the middle surface, midway between intrados and extrados \[m\]
    /// (hemispherical), instead of `span`.
    pub radius: Option<f64>,
    /// The intrados's rise above the springing \[m\] (pointed).
    pub rise: Option<f64>,
    /// The shell's thickness, along the parallel joints \[m\].
    pub thickness: f64,
    /// The voussoirs of each ring: the meridian joints, at equal angles about the axis (3 at
    /// least).
    pub meridians: usize,
    /// The rings from the springing to the crown: the meridian's arc cut at equal angles (its
    /// half of the arch of `2 parallels` voussoirs); the crown's ring is of wedges meeting on the
    /// axis.
    pub parallels: usize,
}

/// Makes a dome: its meridian the right half of the plane's arch of `2 parallels` voussoirs
/// (semicircular or pointed: radial joints), revolved about z; each voussoir the convex hull of
/// its 8 corners (the ends of its two parallel joints on its two meridian planes; 6 in the
/// crown's ring, whose upper joint is on the axis), so that every face is planar: the meridian
/// joints are planes through the axis, the parallel joints the chords of cones, the intrados
/// and extrados the chords of the surfaces. The meridian joints run through every ring (a
/// staggered joint would not lie in the plane of the chord below it). The springing, z = 0,
/// stands on the base.
pub fn dome(p: &Dome) -> Result<Vaulted> {
    let what = "geometry.dome";
    let (n, m) = (p.parallels, p.meridians);
    if !(1..=MAX_VOUSSOIRS / 2).contains(&n) {
        return Err(Error::input_at(format!("{what}.parallels"), format!("{what}.parallels must lie in 1..={}, got {n}", MAX_VOUSSOIRS / 2)));
    }
    if !(3..=MAX_VOUSSOIRS).contains(&m) {
        return Err(Error::input_at(format!("{what}.meridians"), format!("{what}.meridians must lie in 3..={MAX_VOUSSOIRS}, got {m}")));
    }
    check_count(what, n as f64 * m as f64)?;
    let kind = match p.kind {
        DomeKind::Hemispherical => ArchKind::Semicircular,
        DomeKind::Pointed => ArchKind::Pointed,
    };
    let section = arch(&Arch {
        kind,
        span: p.span,
        radius: p.radius,
        rise: p.rise,
        thickness: p.thickness,
        voussoirs: 2 * n,
        springing: Springing::Abutments { width: None, height: None },
        backfill: None,
    })
    .map_err(|e| e.renamed("geometry.arch", what).renamed("semicircular arch", "hemispherical dome").renamed("pointed arch", "pointed dome"))?;
    // the joints from the right springing (index 2 n) up to the crown (n), [radius, z]
    let joint = |k: usize| [section.intrados[2 * n - k], section.extrados[2 * n - k]];
    let size = section.extrados.iter().map(|e| e[0].abs().max(e[1])).fold(0.0, f64::max);
    let tol = contact_tolerance(2.0 * size);
    let turns: Vec<(f64, f64)> = (0..m).map(|j| (2.0 * PI * j as f64 / m as f64).sin_cos()).collect();
    let mut blocks = Vec::with_capacity(n * m);
    for ring in 0..n {
        let (lower, upper) = (joint(ring), joint(ring + 1));
        for j in 0..m {
            let (s0, c0) = turns[j];
            let (s1, c1) = turns[(j + 1) % m];
            let corners: Vec<[f64; 3]> = [lower, upper]
                .iter()
                .flatten()
                .flat_map(|q| [[q[0] * c0, q[0] * s0, q[1]], [q[0] * c1, q[0] * s1, q[1]]])
                .collect();
            let block = Polyhedron::hull(&corners, tol).map_err(|d| {
                Error::input_at(
                    format!("{what}.meridians"),
                    format!("{what}: the voussoir of ring {ring}, meridian {j} has no volume ({}): fewer meridians or parallels, or a thicker shell", d.reason),
                )
            })?;
            blocks.push(block);
        }
    }
    Ok(Vaulted { blocks, supports: vec![] })
}
