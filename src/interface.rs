//! Interface detection (every shared stretch of boundary between two blocks) and the
//! kinematics of an interface: generalized jumps `e = (dN, dT, dphi) = B q`.
//!
//! Detection hands the blocks' boxes to the shape layer's grid, which tests only pairs that
//! share a cell, so it costs O(n) for walls of similar blocks, never O(n^2).
//!
//! ```
//! use masonry_dem::geometry::Rect;
//! use masonry_dem::interface::{detect, BlockKind, Family};
//! // two blocks side by side on a third
//! let rects = [Rect::new(0.0, 0.0, 0.4, 0.2), Rect::new(0.4, 0.0, 0.8, 0.2), Rect::new(0.0, -0.2, 0.8, 0.0)];
//! let kinds = [BlockKind::Wall, BlockKind::Wall, BlockKind::Base];
//! let found = detect(&rects, &kinds, |i| format!("block {i}"), &mut || true).unwrap();
//! let families: Vec<Family> = found.iter().map(|it| it.family).collect();
//! assert_eq!(families, [Family::Head, Family::Base, Family::Base]);
//! assert_eq!(found[0].l, 0.2); // the shared edge [m]
//! ```

use crate::error::{Error, Result};
use crate::geometry::{Rect, REL_TOL};
use crate::shape::grid::for_each_pair;
use crate::shape::Aabb;

/// Which kind of joint an interface is; each family may have its own joint law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Family {
    /// Horizontal joint between two wall blocks.
    Bed,
    /// Vertical joint between two wall blocks.
    Head,
    /// Joint between a wall block and the base.
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
    /// The first block (below, or to the left).
    pub a: usize,
    /// The second block (above, or to the right).
    pub b: usize,
    /// Centroid of the shared segment \[m\].
    pub c: [f64; 2],
    /// Unit normal from a to b: (0, 1) for a bed joint, (1, 0) for a head joint.
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

    /// Jumps with finite rotations in the current configuration, for the explicit solver.
    /// Measured in the frame of block a rotated with it: the normal gap at `c`, the slip at the
    /// point where the normal force acts (`c + e t`, `e` the eccentricity M/N of the previous
    /// force, within the interface) and `sin` of the relative rotation, so that the gaps at
    /// both ends of the interface are exact (`dN +- l/2 dphi`): a block turning about its edge
    /// neither penetrates nor slips there. To first order this is `B q`.
    /// `ga`, `gb`: the blocks' reference centroids; `ua`, `ub`: their (u1, u2, phi); `csa`,
    /// `csb`: (cos, sin) of their rotations.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn large_kinematics(
        &self,
        ga: [f64; 2],
        gb: [f64; 2],
        ua: &[f64],
        ub: &[f64],
        csa: [f64; 2],
        csb: [f64; 2],
        e: f64,
    ) -> LargeKinematics {
        let rot = |cs: [f64; 2], v: [f64; 2]| [cs[0] * v[0] - cs[1] * v[1], cs[1] * v[0] + cs[0] * v[1]];
        let ra = rot(csa, [self.c[0] - ga[0], self.c[1] - ga[1]]);
        let rb = rot(csb, [self.c[0] - gb[0], self.c[1] - gb[1]]);
        let n = rot(csa, self.n);
        let t = [n[1], -n[0]];
        let gap = [
            ub[0] + gb[0] + rb[0] - (ua[0] + ga[0] + ra[0]),
            ub[1] + gb[1] + rb[1] - (ua[1] + ga[1] + ra[1]),
        ];
        // relative rotation: cos and sin of (phi_b - phi_a)
        let rel = [csb[0] * csa[0] + csb[1] * csa[1], csb[1] * csa[0] - csb[0] * csa[1]];
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

/// Current-configuration kinematics of an interface (see [`Interface::large_kinematics`]).
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
    /// The fixed foundation.
    Base,
    /// The rigid top beam.
    Top,
}

pub(crate) use crate::shape::grid::POLL_EVERY;

/// Finds every pair of blocks that share a stretch of boundary of positive length, and refuses
/// overlapping blocks (naming both). `names` gives the label of a block for messages; `poll` is
/// called every few thousand blocks or cells, and `false` stops the search
/// ([`Error::Interrupted`]).
pub fn detect(
    rects: &[Rect],
    kinds: &[BlockKind],
    name: impl Fn(usize) -> String,
    poll: &mut dyn FnMut() -> bool,
) -> Result<Vec<Interface>> {
    let boxes: Vec<Aabb<2>> = rects.iter().map(|r| Aabb { min: [r.x0, r.y0], max: [r.x1, r.y1] }).collect();
    let scale = boxes.iter().fold(Aabb::around(&[]), |a, b| a.union(b)).size();
    let tol = REL_TOL * scale.max(1.0) * 10.0;
    let mut out = Vec::new();
    for_each_pair(&boxes, tol, poll, |i, j| {
        match pair(rects, kinds, i, j, tol) {
            Pair::None => {}
            Pair::Joint(it) => out.push(it),
            Pair::Overlap(w, h) => {
                return Err(Error::input(format!(
                    "{} and {} overlap (intersection {:.6} x {:.6} m)",
                    name(i),
                    name(j),
                    w,
                    h
                )))
            }
        }
        Ok(())
    })?;
    out.sort_by_key(|p| (p.a, p.b));
    Ok(out)
}

/// What two blocks are to each other.
enum Pair {
    /// Apart, touching at a corner, or base against top beam.
    None,
    /// Their intersection \[m\] x \[m\]: refused.
    Overlap(f64, f64),
    Joint(Interface),
}

/// Blocks `i` and `j`: their joint if they share a segment.
fn pair(rects: &[Rect], kinds: &[BlockKind], i: usize, j: usize, tol: f64) -> Pair {
    let (ri, rj) = (&rects[i], &rects[j]);
    let ix0 = ri.x0.max(rj.x0);
    let ix1 = ri.x1.min(rj.x1);
    let iy0 = ri.y0.max(rj.y0);
    let iy1 = ri.y1.min(rj.y1);
    let (w, h) = (ix1 - ix0, iy1 - iy0);
    if w < -tol || h < -tol {
        return Pair::None; // apart
    }
    if w > tol && h > tol {
        return Pair::Overlap(w, h);
    }
    let (lo, hi, c, n, l) = if w > tol {
        // horizontal contact: the lower block is a
        let (lo, hi) = if ri.y0 < rj.y0 { (i, j) } else { (j, i) };
        (lo, hi, [0.5 * (ix0 + ix1), 0.5 * (rects[lo].y1 + rects[hi].y0)], [0.0, 1.0], w)
    } else if h > tol {
        let (lo, hi) = if ri.x0 < rj.x0 { (i, j) } else { (j, i) };
        (lo, hi, [0.5 * (rects[lo].x1 + rects[hi].x0), 0.5 * (iy0 + iy1)], [1.0, 0.0], h)
    } else {
        return Pair::None; // corner touch only
    };
    let family = match (kinds[lo], kinds[hi]) {
        (BlockKind::Base, _) | (_, BlockKind::Base) => Family::Base,
        (BlockKind::Top, _) | (_, BlockKind::Top) => Family::Top,
        _ if n[1] == 1.0 => Family::Bed,
        _ => Family::Head,
    };
    if kinds[lo] != BlockKind::Wall && kinds[hi] != BlockKind::Wall {
        return Pair::None; // base against top beam: not a joint of the wall
    }
    Pair::Joint(Interface::new(lo, hi, rects[lo].centroid(), rects[hi].centroid(), c, n, l, family))
}
