//! The out-of-plane (3D) model: walls of rigid blocks, axis-aligned boxes or convex polyhedra
//! ([`crate::shape::Polyhedron`]; a box is one), their contacts, masses, supports and loads. No solver here: limit analysis and the incremental solvers in 3D read a
//! [`Model3`] (blocks with 6 dof, contacts as polygons with a frame).
//!
//! Coordinates are metres with z up. Each block has 6 dof at its centroid: ux, uy, uz \[m\], then
//! rx, ry, rz \[rad\], small rotations about the x, y, z axes through the centroid; the global dof
//! index of dof k of block i is `6 i + k`. Blocks are numbered as in 2D: the user's blocks
//! `0..n_wall` in the order given, then the base (if any), then the top beam (if any).
//!
//! A contact is the convex polygon shared by two facing coplanar faces (between boxes a
//! rectangle, the intersection of two rectangles): its corners, normal and tangents are what a
//! solver needs to put contact points with a normal force and a shear vector at its corners (the
//! design's "Out of plane (3D)").
//!
//! ```
//! use masonry_dem::space::{running_bond_3d, Model3, ModelSpec3};
//! use masonry_dem::interface::Family;
//! // a 2 m long, 1.05 m high, 0.1 m thick leaf of 0.4 x 0.175 m blocks on a base
//! let blocks = running_bond_3d(2.0, 1.05, 0.1, 0.4, 0.175, 0.2).unwrap();
//! assert_eq!(blocks.len(), 33);
//! let model = Model3::new(&ModelSpec3 { blocks, ..ModelSpec3::default() }).unwrap();
//! assert_eq!(model.n_blocks(), 34); // the base is the last block
//! let base = model.contacts().iter().filter(|c| c.family == Family::Base).count();
//! assert_eq!(base, 6); // the lowest course: a half block, four whole ones and a half
//! let weight: f64 = model.dead_load().iter().skip(2).step_by(6).sum();
//! assert!((weight + 2000.0 * 2.0 * 1.05 * 0.1 * 9.81).abs() < 1e-6);
//! ```

mod detect;
mod model;
mod vaults;
mod walls;

#[cfg(test)]
mod tests;

pub use detect::{detect, detect_polyhedra, hulls};
pub use model::Model3;
pub use vaults::{barrel_vault, cross_vault, dome, BarrelVault, CrossVault, Dome, DomeKind, Vaulted};
pub use walls::{buttressed_wall, corner, cut_openings, running_bond_3d, u_wall, ButtressedWall};

use crate::error::{Error, Result};
use crate::interface::Family;
use crate::model::JointLaws;
use crate::shape::Polyhedron;

/// An axis-aligned box `[min, max]` \[m\], z up: a block of the wall (or the base, the top beam).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Box3 {
    /// The corner of the smallest x, y, z \[m\].
    pub min: [f64; 3],
    /// The corner of the largest x, y, z \[m\].
    pub max: [f64; 3],
}

impl Box3 {
    /// The box from corner (x0, y0, z0) to corner (x1, y1, z1) \[m\].
    pub fn new(x0: f64, y0: f64, z0: f64, x1: f64, y1: f64, z1: f64) -> Self {
        Box3 { min: [x0, y0, z0], max: [x1, y1, z1] }
    }
    /// The centre \[m\].
    pub fn centroid(&self) -> [f64; 3] {
        [0, 1, 2].map(|k| 0.5 * (self.min[k] + self.max[k]))
    }
    /// The sides along x, y, z \[m\].
    pub fn size(&self) -> [f64; 3] {
        [0, 1, 2].map(|k| self.max[k] - self.min[k])
    }
    /// The box as a convex polyhedron (its faces made directly: exact normals and offsets).
    pub fn polyhedron(&self) -> Polyhedron {
        Polyhedron::cuboid(self.min, self.max)
    }
    /// The product of the sides \[m3\].
    pub fn volume(&self) -> f64 {
        let s = self.size();
        s[0] * s[1] * s[2]
    }
    /// "[x0, y0, z0, x1, y1, z1]" for messages, very large or small coordinates in exponent notation.
    pub fn label(&self) -> String {
        let c: Vec<String> = self.min.iter().chain(&self.max).map(|&v| coord(v)).collect();
        format!("[{}]", c.join(", "))
    }
    /// Checks that the corners are finite and the sides positive; `what` names the block.
    pub fn validate(&self, what: &str) -> Result<()> {
        if let Some(v) = self.min.iter().chain(&self.max).find(|v| !v.is_finite()) {
            return Err(Error::input(format!("{what} {}: coordinate {v} is not finite", self.label())));
        }
        if (0..3).any(|k| !(self.max[k] > self.min[k])) {
            return Err(Error::input(format!(
                "{what} {} has zero or negative size (need x0 < x1, y0 < y1 and z0 < z1)",
                self.label()
            )));
        }
        Ok(())
    }
}

/// A coordinate for messages: as written for ordinary numbers, in exponent notation beyond 1e15
/// or below 1e-4 (as the 2D [`crate::geometry::Rect::label`]).
pub(crate) fn coord(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e15).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// One contact (interface): the convex polygon shared by a face of block `a` and a face of block
/// `b` on one plane, facing, of positive area (blocks touching along an edge or at a corner have
/// none); between boxes a rectangle.
///
/// The detection puts `a` on the side the normal leaves: `n` points up, or on a vertical contact
/// towards +x (else +y); between boxes `n` is +x, +y or +z, and `a` is the block below (or at
/// smaller x, y). Solvers should rely only on "n points from a into b".
#[derive(Debug, Clone, PartialEq)]
pub struct Contact {
    /// The block the normal leaves.
    pub a: usize,
    /// The block the normal enters.
    pub b: usize,
    /// Unit normal from `a` into `b`.
    pub n: [f64; 3],
    /// First unit tangent: +x on a horizontal contact, the horizontal tangent on a vertical one
    /// (+y when n = +x, -x when n = +y).
    pub t1: [f64; 3],
    /// Second unit tangent, `n x t1` (so that `t1 x t2 = n`): +y on a horizontal contact, +z on a
    /// vertical one.
    pub t2: [f64; 3],
    /// The polygon's corners \[m\] (3 or more), counter-clockwise seen from the tip of `n`, from
    /// the one of least `t1 + t2` coordinate (a rectangle's along the tangents: (-,-), (+,-),
    /// (+,+), (-,+)).
    pub corners: Vec<[f64; 3]>,
    /// The polygon's extent along `t1` and `t2` \[m\] (a rectangle's sides).
    pub dims: [f64; 2],
    /// Area \[m2\].
    pub area: f64,
    /// The polygon's centroid \[m\], on the plane midway between the two faces.
    pub centroid: [f64; 3],
    /// Bed (horizontal, wall-wall), Head (vertical, wall-wall), Base (with the base) or Top (with
    /// the top beam); the contact's joint law is that family's.
    pub family: Family,
}

/// The live load pattern, scaled by the load multiplier lambda.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LiveLoad3 {
    /// No live load (dead loads only).
    None,
    /// A horizontal force lambda * W_i on every block that weighs (the wall's and the top
    /// beam's; the top beam weighs in 3D, unlike the plane's), `direction` \[deg\] in plan from
    /// +x towards +y: 0 pushes towards +x, 90 towards +y (out of the plane of a facade along x).
    HorizontalWeight {
        /// The force's direction in plan \[deg\], from +x towards +y.
        direction: f64,
    },
}

/// Everything needed to build a [`Model3`]. SI units.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelSpec3 {
    /// Wall blocks.
    pub blocks: Vec<Box3>,
    /// Wall blocks of any convex shape, after `blocks`.
    pub polyhedra: Vec<Polyhedron>,
    /// Fixed rigid supports of any convex shape (beside the base, or instead of it).
    pub supports: Vec<Polyhedron>,
    /// Density of the blocks (and of the top beam) \[kg/m3\].
    pub density: f64,
    /// A fixed rigid foundation under the wall's footprint: the box around the blocks in plan,
    /// from the lowest block's bottom down by the tallest block's height (as in 2D); the wall's
    /// lowest blocks stand on it.
    pub base: bool,
    /// A rigid top beam of this height \[m\] (free, of the blocks' density) over the box around
    /// the blocks in plan, resting on the highest blocks; `None`: no beam.
    pub top: Option<f64>,
    /// The joint law of each family.
    pub joints: JointLaws,
    /// Acceleration of gravity \[m/s2\], along -z.
    pub gravity: f64,
    /// The live load, scaled by lambda.
    pub live: LiveLoad3,
    /// Loads carried by wall blocks (a floor's reaction at a point (x, y, z) of a box), with
    /// their masses, as the plane's [`ModelSpec::carried`](crate::model::ModelSpec::carried):
    /// each loaded block's centroid, where its dofs are, is its centre of mass with its loads.
    pub carried: Vec<crate::model::CarriedLoad<3>>,
}

impl Default for ModelSpec3 {
    /// No blocks, 2000 kg/m3, a base, no top beam, the default joint law, g = 9.81 m/s2, the
    /// horizontal-weight load towards +x (`direction` 0, as in the case file).
    fn default() -> Self {
        ModelSpec3 {
            blocks: vec![],
            polyhedra: vec![],
            supports: vec![],
            density: 2000.0,
            base: true,
            top: None,
            joints: JointLaws::default(),
            gravity: 9.81,
            live: LiveLoad3::HorizontalWeight { direction: 0.0 },
            carried: vec![],
        }
    }
}
