//! The model on its blocks moved: every block carried by a finite rigid motion, the interfaces
//! found again (where the blocks now touch, along edges or at points), everything else kept.

use super::Model;
use crate::error::{Error, Result};
use crate::interface::detect_with;
use crate::joint::Section;
use crate::shape::contact_tolerance;

impl Model {
    /// The model with block `i` moved by the finite rigid motion `motion[i]` = (u1, u2 \[m\],
    /// phi \[rad\]): turned by phi about its centroid (its centre of mass, where its dofs are)
    /// and translated by (u1, u2), the loads it carries with it. Masses, weights, loads,
    /// supports and joint laws are kept; the interfaces are found again on the moved blocks,
    /// along edges as [`Model::new`] finds them and also at points (a vertex on an edge, two
    /// vertices at one point: interfaces of length 0, with no moment and no area for cohesion or
    /// tension), with the tolerance of this model's size or `gap` \[m\], the larger: blocks
    /// apart by no more than it touch (a mechanism's motion may open its hinges by a small
    /// fraction of the step). Blocks that overlap after the motion
    /// are refused naming both; a block left touching nothing is allowed (it has lost its
    /// support: the analyses say so).
    pub fn moved(&self, motion: &[[f64; 3]], gap: f64) -> Result<Model> {
        if motion.len() != self.n_blocks() {
            return Err(Error::input(format!(
                "a motion of {} blocks given for a model of {}",
                motion.len(),
                self.n_blocks()
            )));
        }
        if let Some(i) = motion.iter().position(|m| !m.iter().all(|v| v.is_finite())) {
            return Err(Error::input(format!("the motion of {} is not finite", self.block_name(i))));
        }
        let tol = contact_tolerance(self.size()).max(gap);
        let mut out = self.clone();
        let carry = |i: usize, p: [f64; 2]| -> [f64; 2] {
            let [u1, u2, phi] = motion[i];
            let c = self.centroids[i];
            let (s, co) = phi.sin_cos();
            let (x, y) = (p[0] - c[0], p[1] - c[1]);
            [c[0] + u1 + co * x - s * y, c[1] + u2 + s * x + co * y]
        };
        for (i, m) in motion.iter().enumerate() {
            if *m == [0.0; 3] {
                continue;
            }
            let moved = self.polygons[i].map(|v| carry(i, v));
            out.polygons[i] = moved.checked(tol).map_err(|d| Error::input(format!("{} moved: {}", self.block_name(i), d.reason)))?;
            out.centroids[i] = carry(i, self.centroids[i]);
        }
        for l in &mut out.carried {
            l.point = carry(l.block, l.point);
        }
        let name = |i: usize| out.block_name(i);
        let interfaces = detect_with(&out.polygons, &out.centroids, &out.kinds, out.gravity_direction, tol, true, name, &mut || true)?;
        out.sections = interfaces.iter().map(|it| Section::new(it.l, out.thickness)).collect();
        out.interfaces = interfaces;
        Ok(out)
    }
}
