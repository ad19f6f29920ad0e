//! The shape layer: the blocks' shapes, their mass properties and where they touch. Nothing in
//! it knows about a model, a joint law or a solver; the model ([`crate::model`]) asks it for a
//! block's area, centroid and polar moment, its bounding box and the contacts of two blocks, and
//! the solvers above the model see only those numbers, never a shape.
//!
//! - [`Polygon`] (`polygon`): a 2D block, a convex polygon, checked and kept counter-clockwise;
//!   a rectangle is one ([`From<Rect>`](crate::geometry::Rect)) and goes through the same code;
//! - [`Area`] (`mass`): area, centroid and polar second moment of a polygon, exact;
//! - `contact2`: where two polygons touch: facing collinear edges overlapping over a positive
//!   length ([`EdgeContact`]), and how deep two polygons overlap (to refuse them);
//! - `grid`: the broad phase, a uniform grid over bounding boxes ([`Aabb`]) that hands each pair
//!   of boxes that may touch to the narrow phase once, in O(n). It and the tolerance
//!   ([`contact_tolerance`]) do not depend on the dimension: the 3D shapes share them.
//!
//! The 3D shapes beside them:
//!
//! - [`Polyhedron`] (`polyhedron`): a 3D block, a convex polyhedron from its vertices (their
//!   convex hull) or its faces, each face counter-clockwise seen from outside; a box is one
//!   ([`Polyhedron::cuboid`]);
//! - [`Volume`] (`mass`): volume, centroid and inertia tensor of a polyhedron, exact;
//! - `contact3`: where two polyhedra touch: facing coplanar faces sharing a convex polygon of
//!   positive area ([`FaceContact`], the faces clipped one by the other), and how deep two
//!   polyhedra overlap (to refuse them).
//!
//! ```
//! use masonry_dem::shape::{contacts, Polygon};
//! // a triangle standing on a rectangle, its base on part of the rectangle's top edge
//! let block = Polygon::new(vec![[0.2, 0.0], [0.6, 0.0], [0.4, 0.3]]).checked(1e-9).unwrap();
//! let plinth = Polygon::new(vec![[0.0, -0.2], [1.0, -0.2], [1.0, 0.0], [0.0, 0.0]]).checked(1e-9).unwrap();
//! let area = block.area_properties();
//! assert!((area.area - 0.06).abs() < 1e-15 && (area.centroid[1] - 0.1).abs() < 1e-15);
//! let found = contacts(&plinth, &block, 1e-9);
//! assert_eq!(found.len(), 1);
//! assert_eq!(found[0].n, [0.0, 1.0]); // from the plinth into the triangle
//! assert!((found[0].length - 0.4).abs() < 1e-15);
//! ```

mod contact2;
mod contact3;
pub(crate) mod grid;
mod mass;
mod polygon;
mod polyhedron;
pub(crate) mod vec3;

pub use contact2::{contacts, corner_contacts, facing_edges, penetration, EdgeContact, Facing};
pub use contact3::{bisector, corner_contact, face_contacts, face_patch, facing, facing_faces, penetration as penetration3, shared, FaceContact, FaceFacing};
pub(crate) use contact3::upward;
pub(crate) use polyhedron::frame;
pub use mass::{Area, Volume};
pub use polygon::{Defect, Polygon};
pub use polyhedron::{Face, Polyhedron, MAX_HULL_POINTS};

/// Relative tolerance on coordinates used by the generators and the contact search.
pub(crate) const REL_TOL: f64 = 1e-9;

/// The contact tolerance of a model of size `size` \[m\] (the larger side of the box around it):
/// two edges or faces this close, gap or overlap, touch; vertices this close to each other or
/// to the line through their neighbours are one vertex or none. `10 REL_TOL` of the size, at
/// least `1e-8` m.
pub fn contact_tolerance(size: f64) -> f64 {
    REL_TOL * size.max(1.0) * 10.0
}

/// An axis-aligned bounding box in `D` dimensions \[m\].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb<const D: usize> {
    /// The lowest corner.
    pub min: [f64; D],
    /// The highest corner.
    pub max: [f64; D],
}

impl<const D: usize> Aabb<D> {
    /// The box around `points` (an empty box, min above max, when there are none).
    pub fn around<'a>(points: impl IntoIterator<Item = &'a [f64; D]>) -> Self {
        let mut b = Aabb { min: [f64::MAX; D], max: [f64::MIN; D] };
        for p in points {
            b.include(p);
        }
        b
    }

    /// Grows the box to hold `p`.
    pub fn include(&mut self, p: &[f64; D]) {
        for (k, &x) in p.iter().enumerate() {
            self.min[k] = self.min[k].min(x);
            self.max[k] = self.max[k].max(x);
        }
    }

    /// The box around both.
    pub fn union(&self, other: &Self) -> Self {
        let mut b = *self;
        b.include(&other.min);
        b.include(&other.max);
        b
    }

    /// The larger side \[m\].
    pub fn size(&self) -> f64 {
        (0..D).map(|k| self.max[k] - self.min[k]).fold(0.0, f64::max)
    }

    /// The sides of the intersection with `other` along each axis (negative where they are apart).
    pub fn overlap(&self, other: &Self) -> [f64; D] {
        std::array::from_fn(|k| self.max[k].min(other.max[k]) - self.min[k].max(other.min[k]))
    }
}
