//! The 3D model on its blocks moved: every block carried by a finite rigid motion, the contacts
//! found again (over polygons, along edges and at points), everything else kept.

use super::Model3;
use crate::error::{Error, Result};
use crate::shape::vec3::{apply, rotation};
use crate::shape::{Aabb, Polyhedron};
use crate::space::detect::{detect_with, tolerance};
use crate::space::Box3;

impl Model3 {
    /// The model with block `i` moved by the finite rigid motion `motion[i]` = (u1, u2, u3 \[m\],
    /// r1, r2, r3 \[rad\]): turned about its centroid (its centre of mass, where its dofs are) by
    /// the rotation vector r (the angle |r| about the axis r) and translated by u, the loads it
    /// carries with it, its inertia tensor turned with it. Masses, weights, loads, supports and
    /// joint laws are kept (and the products of inertia of [`Model3::carried_products`], which
    /// no analysis of a moved model reads); the contacts are found again on the moved blocks,
    /// over shared polygons as [`Model3::new`] finds them and also along an edge or at a point
    /// ([`crate::shape::corner_contact`]: contacts of area 0, no area for cohesion or tension),
    /// with the tolerance of the moved model or `gap` \[m\], the larger: blocks apart by no more
    /// than it touch (a mechanism's motion may open its hinges by a small fraction of the step).
    /// Blocks that overlap after the motion are refused naming both; a block left touching
    /// nothing is allowed (it has lost its support: the analyses say so). A moved block's box
    /// ([`Model3::boxes`]) is the box around it.
    pub fn moved(&self, motion: &[[f64; 6]], gap: f64) -> Result<Model3> {
        if motion.len() != self.n_blocks() {
            return Err(Error::input(format!("a motion of {} blocks given for a model of {}", motion.len(), self.n_blocks())));
        }
        if let Some(i) = motion.iter().position(|m| !m.iter().all(|v| v.is_finite())) {
            return Err(Error::input(format!("the motion of {} is not finite", self.block_name(i))));
        }
        let mut out = self.clone();
        for (i, m) in motion.iter().enumerate() {
            if *m == [0.0; 6] {
                continue;
            }
            let r = rotation([m[3], m[4], m[5]]);
            let c = self.centroids[i];
            let carry = |p: [f64; 3]| {
                let x = apply(&r, [p[0] - c[0], p[1] - c[1], p[2] - c[2]]);
                std::array::from_fn(|k| c[k] + m[k] + x[k])
            };
            out.shapes[i] = self.shapes[i].map(carry);
            let b = out.shapes[i].aabb();
            out.boxes[i] = Box3 { min: b.min, max: b.max };
            out.is_box[i] = false;
            out.centroids[i] = carry(c);
            for l in out.carried.iter_mut().filter(|l| l.block == i) {
                l.point = carry(l.point);
            }
            // R T R^T
            let t = self.tensor[i];
            out.tensor[i] = std::array::from_fn(|a| std::array::from_fn(|b| (0..3).map(|k| (0..3).map(|l| r[a][k] * t[k][l] * r[b][l]).sum::<f64>()).sum()));
            out.inertia[i] = [out.tensor[i][0][0], out.tensor[i][1][1], out.tensor[i][2][2]];
        }
        let aabbs: Vec<Aabb<3>> = out.shapes.iter().map(Polyhedron::aabb).collect();
        let tol = tolerance(&aabbs).max(gap);
        let name = |i: usize| out.block_name(i);
        out.contacts = detect_with(&out.shapes, &aabbs, &out.kinds, tol, true, name, &mut || true)?;
        Ok(out)
    }

    /// The tolerance of the contacts \[m\]: faces this close, gap or overlap, touch.
    pub(crate) fn contact_tolerance(&self) -> f64 {
        tolerance(&self.shapes.iter().map(Polyhedron::aabb).collect::<Vec<_>>())
    }
}
