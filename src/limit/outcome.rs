//! From the program's solution to the Results: the multiplier, the forces at collapse, the
//! mechanism from the duals and the crack pattern from its jumps.

use super::*;

impl Plane {
    /// The results of a solution: the multiplier, the forces at collapse, the mechanism from
    /// the duals and the joints it moves.
    pub(super) fn results(&self, model: &Model, sol: &Solution, cert: Certificate, start: Instant) -> Results {
        let nb = model.n_blocks();
        let lam = self.lp.lambda_of(sol);
        let (status, error) = self.lp.status(sol, lam);
        let collapse = status == Status::Collapse;
        let v = if collapse { self.mechanism(model, sol) } else { vec![0.0; 3 * nb] };
        let (forces, flags) = self.interface_forces(model, sol, &v, collapse);
        Results {
            method: "limit",
            status,
            error,
            collapse_multiplier: if collapse { lam } else { f64::NAN },
            last_equilibrium: if collapse { lam } else { f64::NAN },
            curve_multiplier: vec![],
            curve_displacement: vec![],
            control_block: model.default_control_block(),
            displacements: vec![[0.0; 3]; nb],
            mechanism: (0..nb).map(|i| [v[3 * i], v[3 * i + 1], v[3 * i + 2]]).collect(),
            interface_forces: forces,
            interface_states: flags,
            broken: vec![false; self.lp.m],
            iterations: cert.iterations,
            steps: 0,
            elapsed_s: start.elapsed().as_secs_f64(),
            bracket: None,
            certificate: Some(cert),
        }
    }

    /// The collapse mechanism: block velocities from the duals of the equilibrium rows (scaled
    /// rows: one length for the rotations), oriented so that the live load does positive work,
    /// largest block translation 1.
    fn mechanism(&self, model: &Model, sol: &Solution) -> Vec<f64> {
        let nb = model.n_blocks();
        let mut v = self.lp.velocities(sol, 3);
        let big = (0..nb).map(|i| v[3 * i].hypot(v[3 * i + 1])).fold(0.0, f64::max);
        let work = dot(&v, model.live_load());
        let scale = if big > 0.0 { work.signum() / big } else { 0.0 };
        v.iter_mut().for_each(|x| *x *= scale);
        v
    }

    /// Each interface's forces (N, T, M) in the solution, in their own units, and with a
    /// `collapse`, the joint states the mechanism `v` gives it (else none).
    fn interface_forces(&self, model: &Model, sol: &Solution, v: &[f64], collapse: bool) -> (Vec<[f64; 3]>, Vec<u8>) {
        let sigma = self.resultants(&sol.x);
        let its = model.interfaces();
        let mut forces = Vec::with_capacity(self.lp.m);
        let mut flags = Vec::with_capacity(self.lp.m);
        for (k, it) in its.iter().enumerate() {
            let s = sigma[k];
            let f = self.lp.force;
            forces.push([s[0] * f, s[1] * f, s[2] * f * 0.5 * it.l]);
            flags.push(if collapse { mechanism_flags(it, v, self.slope[k]) } else { 0 });
        }
        (forces, flags)
    }
}

impl Lp {
    /// The status of a solution of multiplier `lam` (in its own units), and the error that
    /// says why when it is not a collapse.
    pub(super) fn status(&self, sol: &Solution, lam: f64) -> (Status, Option<String>) {
        // lambda below zero beyond the program's precision: the dead state is not admissible
        // (a signed lambda, a force on a moving support, may take either sign)
        let negative = !self.signed && lam < -1e-7 * (self.force / self.live);
        match sol.outcome {
            Outcome::Optimal if negative => (
                Status::NoEquilibrium,
                Some(format!(
                    "no equilibrium under the dead loads: the largest admissible multiplier is {lam:.6e} < 0 (the wall stands only if pushed the other way)"
                )),
            ),
            Outcome::Optimal => (Status::Collapse, None),
            Outcome::Unbounded => (
                Status::Unbounded,
                Some(format!(
                    "lambda grows beyond {:e}, the analysis's range: the live load finds no mechanism (check the strengths and the supports: a support that holds a block's position, such as a top beam held vertically, forbids the dilatancy of associative sliding)",
                    LAMBDA_RANGE * self.force / self.live
                )),
            ),
            Outcome::Infeasible => (
                Status::NoEquilibrium,
                Some(format!(
                    "no equilibrium under the dead loads: no admissible interface forces balance them at any multiplier (the dual iterates grow along a ray; equilibrium residual {:.1e} of the loads)",
                    sol.primal
                )),
            ),
            Outcome::NotConverged => (
                Status::Failed,
                Some(format!(
                    "the interior point did not converge in {} iterations (scaled residuals: primal {:.1e}, dual {:.1e}, gap {:.1e})",
                    sol.iterations, sol.primal, sol.dual, sol.gap
                )),
            ),
        }
    }
}

/// The joint states that a mechanism's velocities `v` (largest block translation 1) give an
/// interface: open where both ends separate beyond the dilatancy of the slip, sliding where it
/// slips, rocking where its ends separate unequally; motions below 1e-6 are rest.
pub(super) fn mechanism_flags(it: &crate::interface::Interface, v: &[f64], slope: f64) -> u8 {
    let dofs = it.dofs();
    let e: [f64; 3] = std::array::from_fn(|r| (0..6).map(|c| it.b_mat[r][c] * v[dofs[c]]).sum());
    let tol = 1e-6;
    let dil = slope * e[1].abs();
    let g1 = e[0] - 0.5 * it.l * e[2] - dil;
    let g2 = e[0] + 0.5 * it.l * e[2] - dil;
    if g1 > tol && g2 > tol {
        return OPEN;
    }
    let mut f = 0;
    if e[1].abs() > tol {
        f |= SLIDING;
    }
    if (g1 - g2).abs() > tol {
        f |= ROCKING;
    }
    f
}
