//! Interface detection (every shared stretch of boundary between two blocks) and the
//! kinematics of an interface: generalized jumps `e = (dN, dT, dphi) = B q`.
//!
//! Detection asks the shape layer ([`crate::shape`]) for the pairs of blocks that may touch (a
//! grid over their bounding boxes, O(n) for walls of similar blocks, never O(n^2)) and for where
//! they touch (facing collinear edges), then orients each interface and names its family.
//!
//! ```
//! use masonry_dem::geometry::Rect;
//! use masonry_dem::interface::{detect, BlockKind, Family};
//! use masonry_dem::shape::Polygon;
//! // two blocks side by side on a third
//! let rects = [Rect::new(0.0, 0.0, 0.4, 0.2), Rect::new(0.4, 0.0, 0.8, 0.2), Rect::new(0.0, -0.2, 0.8, 0.0)];
//! let polygons: Vec<Polygon> = rects.iter().map(|&r| Polygon::from(r)).collect();
//! let centroids: Vec<[f64; 2]> = rects.iter().map(|r| r.centroid()).collect();
//! let kinds = [BlockKind::Wall, BlockKind::Wall, BlockKind::Base];
//! let found = detect(&polygons, &centroids, &kinds, [0.0, -1.0], 1e-8, |i| format!("block {i}"), &mut || true).unwrap();
//! let families: Vec<Family> = found.iter().map(|it| it.family).collect();
//! assert_eq!(families, [Family::Head, Family::Base, Family::Base]);
//! assert_eq!(found[0].l, 0.2); // the shared edge [m]
//! ```

use crate::error::{Error, Result};
use crate::shape::grid::for_each_pair;
use crate::shape::{contacts, corner_contacts, penetration, Aabb, Polygon};

/// Which kind of joint an interface is; each family may have its own joint law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Family {
    /// Joint between two wall blocks whose normal is within 45 degrees of the vertical (a
    /// horizontal joint between rectangles).
    Bed,
    /// Joint between two wall blocks whose normal is more than 45 degrees from the vertical (a
    /// vertical joint between rectangles).
    Head,
    /// Joint between a wall block and the base or a support.
    Base,
    /// Joint between a wall block and the top beam.
    Top,
}

impl Family {
    /// The case file's word for the family ("bed", "head", "base", "top").
    pub fn name(self) -> &'static str {
        match self {
            Family::Bed => "bed",
            Family::Head => "head",
            Family::Base => "base",
            Family::Top => "top",
        }
    }
}

/// One interface: blocks `a` and `b`, the normal `n` points from `a` to `b`.
#[derive(Debug, Clone, PartialEq)]
pub struct Interface {
    /// The first block (below, or behind along the horizontal live load: to the left).
    pub a: usize,
    /// The second block (above, or ahead: to the right).
    pub b: usize,
    /// Centroid of the shared segment \[m\].
    pub c: [f64; 2],
    /// Unit normal from a to b: (0, 1) for a bed joint between rectangles, (1, 0) for a head
    /// joint.
    pub n: [f64; 2],
    /// Length of the shared segment \[m\].
    pub l: f64,
    /// Which joints of the wall it belongs to (and so its joint law).
    pub family: Family,
    /// `B` (3 x 6, row-major): jumps (dN, dT, dphi) from the dof (u1, u2, phi) of a then b.
    pub b_mat: [[f64; 6]; 3],
}

impl Interface {
    /// Tangent unit vector `t = (n_y, -n_x)`: +x on a bed joint, -y on a head joint.
    pub fn t(&self) -> [f64; 2] {
        [self.n[1], -self.n[0]]
    }

    /// Builds the interface and its `B` matrix from the two blocks' centroids.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        a: usize,
        b: usize,
        ga: [f64; 2],
        gb: [f64; 2],
        c: [f64; 2],
        n: [f64; 2],
        l: f64,
        family: Family,
    ) -> Self {
        let t = [n[1], -n[0]];
        // point velocity of block B at c: u + phi * k x (c - g) = (u1 - phi (cy - gy), u2 + phi (cx - gx))
        let ra = [-(c[1] - ga[1]), c[0] - ga[0]];
        let rb = [-(c[1] - gb[1]), c[0] - gb[0]];
        let row = |v: [f64; 2]| -> [f64; 6] {
            [
                -v[0],
                -v[1],
                -(v[0] * ra[0] + v[1] * ra[1]),
                v[0],
                v[1],
                v[0] * rb[0] + v[1] * rb[1],
            ]
        };
        let b_mat = [row(n), row(t), [0.0, 0.0, -1.0, 0.0, 0.0, 1.0]];
        Interface {
            a,
            b,
            c,
            n,
            l,
            family,
            b_mat,
        }
    }

    /// The six global dof indices (a's u1, u2, phi then b's).
    pub fn dofs(&self) -> [usize; 6] {
        let (a, b) = (3 * self.a, 3 * self.b);
        [a, a + 1, a + 2, b, b + 1, b + 2]
    }

    /// Jumps `e = B q` from the global displacement vector `u` (3 per block).
    #[inline]
    pub fn jumps(&self, u: &[f64]) -> [f64; 3] {
        let d = self.dofs();
        let mut e = [0.0; 3];
        for (r, row) in self.b_mat.iter().enumerate() {
            e[r] = (0..6).map(|k| row[k] * u[d[k]]).sum();
        }
        e
    }
}

/// Where an interface lies on its two blocks in their reference positions, for the kinematics
/// with finite rotations: the interface's point on each block (from the block's centroid; one
/// point of both where the interface was found on the blocks as given, two points facing each
/// other across a gap where it was found on moved blocks), the normal (of block a), the length,
/// and the relative rotation of the blocks at which the two faces are parallel (its cos and sin:
/// (1, 0) for an interface of the blocks as given).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Arm {
    pub ra: [f64; 2],
    pub rb: [f64; 2],
    pub n: [f64; 2],
    pub rel0: [f64; 2],
    pub l: f64,
}

impl Arm {
    /// The jumps of an interface at this arm with finite rotations in the current
    /// configuration, for the explicit solver. Measured in the frame of block a rotated with it: the normal gap at `c`, the slip at the
    /// point where the normal force acts (`c + e t`, `e` the eccentricity M/N of the previous
    /// force, within the interface) and `sin` of the relative rotation, so that the gaps at
    /// both ends of the interface are exact (`dN +- l/2 dphi`): a block turning about its edge
    /// neither penetrates nor slips there. To first order this is `B q`.
    /// `ga`, `gb`: the blocks' reference centroids; `ua`, `ub`: their (u1, u2, phi); `csa`,
    /// `csb`: (cos, sin) of their rotations.
    /// The relative rotation is measured from `rel0`.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn large_kinematics(&self, ga: [f64; 2], gb: [f64; 2], ua: &[f64], ub: &[f64], csa: [f64; 2], csb: [f64; 2], e: f64) -> LargeKinematics {
        let rot = |cs: [f64; 2], v: [f64; 2]| [cs[0] * v[0] - cs[1] * v[1], cs[1] * v[0] + cs[0] * v[1]];
        let ra = rot(csa, self.ra);
        let rb = rot(csb, self.rb);
        let n = rot(csa, self.n);
        let t = [n[1], -n[0]];
        let gap = [
            ub[0] + gb[0] + rb[0] - (ua[0] + ga[0] + ra[0]),
            ub[1] + gb[1] + rb[1] - (ua[1] + ga[1] + ra[1]),
        ];
        // relative rotation: cos and sin of (phi_b - phi_a), from rel0
        let raw = [csb[0] * csa[0] + csb[1] * csa[1], csb[1] * csa[0] - csb[0] * csa[1]];
        let r0 = self.rel0;
        let rel = [raw[0] * r0[0] + raw[1] * r0[1], raw[1] * r0[0] - raw[0] * r0[1]];
        LargeKinematics {
            jumps: [
                n[0] * gap[0] + n[1] * gap[1],
                t[0] * gap[0] + t[1] * gap[1] + e * (rel[0] - 1.0),
                rel[1],
            ],
            n,
            t,
            ra,
            rb,
            rel,
            e,
        }
    }
}

/// Current-configuration kinematics of an interface (see [`Arm::large_kinematics`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LargeKinematics {
    /// The relative displacements (normal, tangential \[m\], rotation \[rad\]) of b against a.
    pub jumps: [f64; 3],
    /// The unit normal, from a to b, rotated with the blocks.
    pub n: [f64; 2],
    /// The unit tangent, rotated with the blocks.
    pub t: [f64; 2],
    /// Arms from the centroids of a and b to the interface point, rotated \[m\].
    pub ra: [f64; 2],
    /// (See `ra`.)
    pub rb: [f64; 2],
    /// cos and sin of the relative rotation.
    pub rel: [f64; 2],
    /// Eccentricity of the slip point along t \[m\].
    pub e: f64,
}

impl LargeKinematics {
    /// Generalized internal forces on (a's u1, u2, phi, b's u1, u2, phi) of force (N, T, M).
    #[inline]
    pub fn forces(&self, s: [f64; 3]) -> [f64; 6] {
        let f = [s[0] * self.n[0] + s[1] * self.t[0], s[0] * self.n[1] + s[1] * self.t[1]];
        let cross = |r: [f64; 2]| r[0] * f[1] - r[1] * f[0];
        // work-conjugate of the relative rotation: d(sin)/dphi = cos, and the slip point's
        // d(e (cos - 1))/dphi = -e sin
        let m = s[2] * self.rel[0] - s[1] * self.e * self.rel[1];
        [-f[0], -f[1], -cross(self.ra) - m, f[0], f[1], cross(self.rb) + m]
    }
}

/// What kind a block is, for naming families.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BlockKind {
    /// A block of the wall.
    Wall,
    /// A fixed block given by the user: an abutment, a springer, an inclined plane.
    Support,
    /// The fixed foundation.
    Base,
    /// The rigid top beam.
    Top,
}

impl BlockKind {
    /// The word for the kind in Python ("wall", "support", "base", "top").
    pub fn name(self) -> &'static str {
        match self {
            BlockKind::Wall => "wall",
            BlockKind::Support => "support",
            BlockKind::Base => "base",
            BlockKind::Top => "top",
        }
    }
}

/// Finds every stretch of boundary of positive length that two blocks share (an edge of each,
/// facing on one line within `tol` \[m\], see [`contacts`]), and refuses blocks that overlap by
/// more than `tol` (naming both). The blocks are checked polygons with their centroids
/// (`centroids`, for the `B` matrices) and kinds; `gravity` is the direction of gravity (a unit
/// vector), which says which way is up:
///
/// - each interface's normal points from `a` to `b`, `a` the block below (the normal has an
///   upward component), or the one behind along the horizontal live load (`gravity` turned by
///   +90 degrees: +x when gravity is -y) when the normal is horizontal;
/// - its family is `Base` with the base or a support, `Top` with the top beam, else `Bed` when
///   the normal is within 45 degrees of the vertical (a tie goes to bed) and `Head` otherwise;
/// - two blocks neither of which is a wall block (a support on the base, the base against the
///   top beam) make no interface.
///
/// `name` gives the label of a block for messages; `poll` is called every few thousand blocks
/// or grid cells, and `false` stops the search ([`Error::Interrupted`]). The interfaces are
/// sorted by their blocks (a, b).
#[allow(clippy::too_many_arguments)]
pub fn detect(
    polygons: &[Polygon],
    centroids: &[[f64; 2]],
    kinds: &[BlockKind],
    gravity: [f64; 2],
    tol: f64,
    name: impl Fn(usize) -> String,
    poll: &mut dyn FnMut() -> bool,
) -> Result<Vec<Interface>> {
    detect_with(polygons, centroids, kinds, gravity, tol, false, name, poll)
}

/// [`detect`], with `corners`: also where two blocks touch at a point ([`corner_contacts`]: a
/// vertex on an edge, or two vertices at one point): interfaces of length 0, for blocks moved by
/// finite rotations. A wall as built has none of these (its blocks meet along edges).
#[allow(clippy::too_many_arguments)]
pub(crate) fn detect_with(
    polygons: &[Polygon],
    centroids: &[[f64; 2]],
    kinds: &[BlockKind],
    gravity: [f64; 2],
    tol: f64,
    corners: bool,
    name: impl Fn(usize) -> String,
    poll: &mut dyn FnMut() -> bool,
) -> Result<Vec<Interface>> {
    let boxes: Vec<Aabb<2>> = polygons.iter().map(Polygon::aabb).collect();
    let up = [-gravity[0], -gravity[1]];
    let side = [-gravity[1], gravity[0]];
    // what makes each interface, sorted before the interfaces (and their B) are made: a sort of
    // these small records, not of the interfaces, which is most of the search's time
    let mut found: Vec<Found> = Vec::with_capacity(3 * polygons.len());
    for_each_pair(&boxes, tol, poll, |i, j| {
        let (pi, pj) = (&polygons[i], &polygons[j]);
        if boxes[i].overlap(&boxes[j]).iter().all(|&w| w > tol) {
            // an overlap is refused in the first cell that sees the pair, before anything else
            let depth = penetration(pi, pj);
            if depth > tol {
                return Err(Error::input(format!(
                    "{} and {} overlap (by {depth:.6} m, more than the contact tolerance {tol:.1e} m)",
                    name(i),
                    name(j)
                )));
            }
        }
        if kinds[i] != BlockKind::Wall && kinds[j] != BlockKind::Wall {
            return Ok(()); // base against top beam, a support on the base: not a joint of the wall
        }
        let mut touching = contacts(pi, pj, tol);
        if corners {
            let points = corner_contacts(pi, pj, tol, &touching);
            touching.extend(points);
        }
        for c in touching {
            let (n_up, n_side) = (dot(c.n, up), dot(c.n, side));
            let (a, b, n) = if n_up > 0.0 || (n_up == 0.0 && n_side > 0.0) {
                (i, j, c.n)
            } else {
                (j, i, [-c.n[0], -c.n[1]])
            };
            let family = match (kinds[a], kinds[b]) {
                (BlockKind::Base | BlockKind::Support, _) | (_, BlockKind::Base | BlockKind::Support) => Family::Base,
                (BlockKind::Top, _) | (_, BlockKind::Top) => Family::Top,
                _ if n_up.abs() >= n_side.abs() => Family::Bed,
                _ => Family::Head,
            };
            let centre = [0.5 * (c.ends[0][0] + c.ends[1][0]), 0.5 * (c.ends[0][1] + c.ends[1][1])];
            found.push(Found { a, b, c: centre, n, l: c.length, family });
        }
        Ok(())
    })?;
    found.sort_by_key(|f| (f.a, f.b));
    Ok(found.into_iter().map(|f| Interface::new(f.a, f.b, centroids[f.a], centroids[f.b], f.c, f.n, f.l, f.family)).collect())
}

/// An interface found, before its `B` is made (see [`Interface`]).
struct Found {
    a: usize,
    b: usize,
    c: [f64; 2],
    n: [f64; 2],
    l: f64,
    family: Family,
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}
