//! The linear program in the form the interior point solves, the same in both dimensions:
//! maximise lambda subject to `sum_k (P_k + A_k x_k) = f_dead + lambda f_live` over the free
//! dofs, `x >= 0`, and in the plane one variable of each interface also bounded by 1.
//!
//! Each interface (an element of the program) contributes a block `A_k` of `rows` equations
//! (the dofs of its two blocks) by `nv` variables, and a constant `P_k` (the contribution of a
//! vertex of its strength domain). How the variables describe the strength domain is the
//! dimension's business ([`super::plane`], [`super::space`]); the interior point sees only
//! these blocks. The normal matrix `sum_k A_k Theta_k A_k^T` has the pattern of the stiffness
//! matrix: one `rows x rows` block per interface, analysed once.

use super::*;

/// A dof held by a support: no equation.
pub(super) const NO_EQ: u32 = u32::MAX;

/// The program, scaled to forces of order one.
pub(super) struct Lp {
    /// Elements (interfaces) and equations.
    pub(super) m: usize,
    pub(super) n: usize,
    /// Equations per element (the dofs of its two blocks) and variables per element.
    pub(super) rows: usize,
    pub(super) nv: usize,
    /// The element's variable that is also bounded above by 1, if any.
    pub(super) bounded: Option<usize>,
    /// The equation of each dof, or None for a support.
    pub(super) eq: Vec<Option<usize>>,
    /// Per element: the equations of its dofs ([`NO_EQ`] for a support), `rows` each.
    pub(super) dofs: Vec<u32>,
    /// Per element: `A_k`, `rows x nv` row-major.
    pub(super) acols: Vec<f64>,
    /// Per element: `P_k`, `rows` each.
    pub(super) pv: Vec<f64>,
    /// Per element: the value slot of each entry of its `rows x rows` block in the normal
    /// matrix (`u32::MAX` for a support's row or column).
    pub(super) slots: Vec<u32>,
    pub(super) f_dead: Vec<f64>,
    pub(super) f_live: Vec<f64>,
    /// Scales: forces, lengths (rotation rows are divided by it), the live load.
    pub(super) force: f64,
    pub(super) length: f64,
    pub(super) live: f64,
    pub(super) normal: SparseLu,
}

impl Lp {
    /// The program's frame: `eq` (the equation of each dof), each element's dofs' equations
    /// (`rows` each), `nv` variables per element, the loads (scaled, one per equation) and the
    /// scales; the normal matrix's pattern analysed once. The blocks `A_k`, `P_k` start at
    /// zero: the dimension fills them.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn new(
        eq: Vec<Option<usize>>,
        n: usize,
        rows: usize,
        nv: usize,
        bounded: Option<usize>,
        dofs: Vec<u32>,
        f_dead: Vec<f64>,
        f_live: Vec<f64>,
        (force, length, live): (f64, f64, f64),
    ) -> Result<Lp> {
        let m = dofs.len() / rows;
        let (normal, slots) = normal_pattern(n, rows, &dofs)?;
        Ok(Lp {
            m,
            n,
            rows,
            nv,
            bounded,
            eq,
            dofs,
            acols: vec![0.0; m * rows * nv],
            pv: vec![0.0; m * rows],
            slots,
            f_dead,
            f_live,
            force,
            length,
            live,
            normal,
        })
    }

    /// Variables bounded by 1: one per element, or none.
    #[inline]
    pub(super) fn n_bounded(&self) -> usize {
        if self.bounded.is_some() {
            self.m
        } else {
            0
        }
    }

    /// The variable bounded by `t[i]`: element i's bounded one.
    #[inline]
    pub(super) fn bounded_var(&self, i: usize) -> usize {
        self.nv * i + self.bounded.unwrap_or(0)
    }

    /// lambda in its own units from a scaled solution.
    pub(super) fn lambda_of(&self, s: &Solution) -> f64 {
        s.lambda * self.force / self.live
    }

    /// The block velocities (`dofs_per_block` per block, in dof order) of the duals of the
    /// equilibrium rows, rotations unscaled: the mechanism before its normalization.
    pub(super) fn velocities(&self, sol: &Solution, dofs_per_block: usize) -> Vec<f64> {
        let half = dofs_per_block / 2;
        let rot = |dof: usize| {
            if dofs_per_block == 3 {
                dof % 3 == 2
            } else {
                dof % dofs_per_block >= half
            }
        };
        self.eq
            .iter()
            .enumerate()
            .map(|(dof, e)| e.map_or(0.0, |e| sol.y[e] * if rot(dof) { 1.0 / self.length } else { 1.0 }))
            .collect()
    }
}

/// The normal matrix's pattern on `n` equations (each element's `rows x rows` block among the
/// equations of its dofs, analysed once) and the value slot of each entry of each block
/// (`u32::MAX` for a support's row or column).
fn normal_pattern(n: usize, rows: usize, dofs: &[u32]) -> Result<(SparseLu, Vec<u32>)> {
    let mut entries = Vec::with_capacity(rows * dofs.len());
    for d in dofs.chunks_exact(rows) {
        for &r in d.iter().filter(|&&r| r != NO_EQ) {
            for &c in d.iter().filter(|&&c| c != NO_EQ) {
                entries.push((r as usize, c as usize));
            }
        }
    }
    let normal = SparseLu::new(n, entries)?;
    let mut slots = Vec::with_capacity(rows * dofs.len());
    for d in dofs.chunks_exact(rows) {
        for &r in d {
            for &c in d {
                slots.push(if r != NO_EQ && c != NO_EQ {
                    normal.slot(r as usize, c as usize).expect("in the pattern") as u32
                } else {
                    u32::MAX
                });
            }
        }
    }
    Ok((normal, slots))
}
