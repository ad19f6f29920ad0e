//! Supports: the dofs a user fixes, the dofs held after the dead loads, and the check that every
//! block hangs on a support.

use super::Model;
use crate::error::{Error, Result};

impl Model {
    /// Dofs held, at the position they reach under the dead loads, from then on (the top beam's
    /// vertical dof when it is held). Both solvers fix them once the dead state is found.
    pub fn held_after_dead(&self) -> &[usize] {
        &self.held
    }

    /// Fixes dof `dof` (0: u1, 1: u2, 2: phi) of block `block` at `value` [m or rad].
    pub fn fix(&mut self, block: usize, dof: usize, value: f64) -> Result<()> {
        if block >= self.polygons.len() {
            return Err(Error::input(format!(
                "fix: block {block} does not exist (the model has {} blocks)",
                self.polygons.len()
            )));
        }
        if dof > 2 {
            return Err(Error::input(format!(
                "fix: dof {dof} of block {block} must be 0 (u1), 1 (u2) or 2 (phi)"
            )));
        }
        if !value.is_finite() {
            return Err(Error::input(format!(
                "fix: value of dof {dof} of block {block} must be finite, got {value}"
            )));
        }
        self.fixed[3 * block + dof] = true;
        self.prescribed[3 * block + dof] = value;
        Ok(())
    }

    /// Refuses a model in which some wall block is not connected, through interfaces, to a block
    /// with a fixed dof (the base, or a user support).
    pub fn check_supports(&self) -> Result<()> {
        let nb = self.polygons.len();
        let held: Vec<bool> = (0..nb).map(|i| self.fixed[3 * i..3 * i + 3].iter().any(|&f| f)).collect();
        if !held.iter().any(|&s| s) {
            return Err(Error::input(
                "the wall has no support: no base ([base] kind = \"none\") and no fixed dof",
            ));
        }
        let loose = unsupported(held, self.interfaces.iter().map(|it| (it.a, it.b)));
        if !loose.is_empty() {
            let names: Vec<String> = loose.iter().take(5).map(|&i| self.block_name(i)).collect();
            return Err(Error::input(format!(
                "{} block(s) not connected to any support: {}{}",
                loose.len(),
                names.join(", "),
                if loose.len() > 5 { ", ..." } else { "" }
            )));
        }
        Ok(())
    }
}

/// The blocks that no chain of interfaces `pairs` joins to a block of `held` (a block with a
/// fixed dof), in increasing order: the plane's and the 3D model's check of their supports.
pub(crate) fn unsupported(held: Vec<bool>, pairs: impl Iterator<Item = (usize, usize)>) -> Vec<usize> {
    let nb = held.len();
    let mut adj: Vec<Vec<usize>> = vec![vec![]; nb];
    for (a, b) in pairs {
        adj[a].push(b);
        adj[b].push(a);
    }
    let mut seen = held;
    let mut stack: Vec<usize> = (0..nb).filter(|&i| seen[i]).collect();
    while let Some(i) = stack.pop() {
        for &j in &adj[i] {
            if !seen[j] {
                seen[j] = true;
                stack.push(j);
            }
        }
    }
    (0..nb).filter(|&i| !seen[i]).collect()
}
