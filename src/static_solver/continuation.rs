//! Pseudo-transient continuation at a fixed lambda: where Newton stops converging near the
//! collapse (the tangent turns singular and joints switch state from one iteration to the
//! next, so that full Newton steps cycle), the equilibrium is sought as the end of an implicit
//! relaxation, `(K_T + D / dtau) du = r` with `D` the tangent's diagonal, `dtau` grown by
//! switched evolution relaxation (`dtau_{k+1} = dtau_k |r_{k-1}| / |r_k|`) as the residual
//! falls, up to a shift far below the tangent's stabilization: plain Newton. The implicit
//! counterpart of the explicit solver's damped relaxation at a fixed lambda: tens of
//! factorizations where the explicit one takes 10^5 steps.
//!
//! On walls of associative dry joints the state at a fixed lambda minimizes a convex potential
//! energy (each joint's part is the Moreau envelope of its strength cone), so every step is
//! accepted by the energy it lowers (a backtracking search), and the shift grows at least
//! twofold after a full step: the iterates cannot cycle. Elsewhere (psi < phi: no potential)
//! the search is on the residual's norm. Where there is no equilibrium the relaxation flows:
//! the residual does not fall while the pseudo-kinetic energy does not decay (the explicit
//! solver's runaway test), or the blocks leave the small-displacement model.

use super::*;

/// Factorizations of one continuation before it gives up.
const RELAX_ITERATIONS: usize = 200;

/// The runaway test's window (iterations) and the windows in a row that make a runaway.
const RELAX_WINDOW: usize = 6;
const RELAX_STRIKES: usize = 2;

/// The largest growth of `dtau` in one iteration, and the least after a full step that lowered
/// the potential energy (walls of associative dry joints).
const MAX_GROWTH: f64 = 10.0;
const MIN_GROWTH: f64 = 2.0;

/// The first `dtau` and the largest, in units of the one for which the shift equals `D`: the
/// first shift is 1e-4 of the diagonal (1e2, 1e4 and 1e6 took 225, 218 and 212 iterations on
/// Ferris & Tin-Loi's wall 5 and 492, 484 and 496 on the LACT3 wall, associative); the
/// smallest, 1e-12 of it, far below the tangent's stabilization: plain Newton.
const DTAU0: f64 = 1e4;
const MAX_DTAU: f64 = 1e12;

/// What the runaway test remembers: the lowest residual and the peak pseudo-kinetic energy of
/// the window so far and of the last one, and the strikes in a row.
struct Trend {
    low: f64,
    peak: f64,
    last_low: f64,
    last_peak: f64,
    strikes: usize,
}

impl Trend {
    /// Whether the relaxation runs away after iteration `it`, with residual `r` and
    /// pseudo-kinetic energy `ke`: over a window, the residual did not halve and the energy
    /// did not fall, [`RELAX_STRIKES`] windows in a row.
    fn ran_away(&mut self, it: usize, r: f64, ke: f64) -> bool {
        self.low = self.low.min(r);
        self.peak = self.peak.max(ke);
        if (it + 1) % RELAX_WINDOW != 0 {
            return false;
        }
        let strike = self.low > 0.5 * self.last_low && self.peak >= self.last_peak;
        self.strikes = if strike { self.strikes + 1 } else { 0 };
        (self.last_low, self.last_peak) = (self.low, self.peak);
        (self.low, self.peak) = (f64::INFINITY, 0.0);
        self.strikes >= RELAX_STRIKES
    }
}

impl<'a, 'm> Solver<'a, 'm> {
    /// Pseudo-transient continuation at the current lambda from the current displacements
    /// (joint histories: the committed ones). True if it reached equilibrium (`u` and `trial`
    /// hold it); false if the wall flows, leaves the small-displacement model or the
    /// iterations run out (the state is then wherever it went: the caller restores its own).
    pub(super) fn relax(&mut self) -> Result<bool, Error> {
        self.ensure_load_sys()?;
        let n = self.n_eq;
        let diag: Vec<usize> = {
            let sys = &self.load_sys.as_ref().unwrap().0;
            (0..n).map(|k| sys.slot(k, k).expect("diagonal in the pattern")).collect()
        };
        let potential = exact_by_limit_analysis(self.model);
        let (mut d, mut du, mut u0) = (vec![0.0; n], vec![0.0; n], self.u.clone());
        let mut dtau = DTAU0;
        let mut trend = Trend { low: f64::INFINITY, peak: 0.0, last_low: f64::INFINITY, last_peak: f64::INFINITY, strikes: 0 };
        self.evaluate();
        let (mut rn, mut fnorm) = self.residual();
        for it in 0..RELAX_ITERATIONS {
            if rn <= self.opts.residual_tolerance * fnorm.max(f64::MIN_POSITIVE) {
                return Ok(true);
            }
            self.poll()?;
            dtau = dtau.min(MAX_DTAU);
            self.iterations += 1;
            let slope: f64 = {
                self.shifted_solve(&diag, &mut d, dtau, &mut du)?;
                self.rhs.iter().zip(&du).map(|(r, v)| r * v).sum()
            };
            u0.copy_from_slice(&self.u);
            let alpha = self.relax_step(&u0, &du, slope, rn, potential);
            if self.check_u().is_err() {
                return Ok(false);
            }
            let (r, f) = self.residual();
            let ke = 0.5 * d.iter().zip(&du).map(|(dk, v)| dk * (alpha * v / dtau).powi(2)).sum::<f64>();
            if trend.ran_away(it, r, ke) {
                return Ok(false);
            }
            // switched evolution relaxation; a cut step says the shift was too small
            dtau *= match (alpha < 1.0, potential) {
                (true, _) => alpha,
                // the energy fell by a full step: the shift may shrink, whatever the residual did
                (false, true) => (rn / r).clamp(MIN_GROWTH, MAX_GROWTH),
                (false, false) => (rn / r).min(MAX_GROWTH),
            };
            (rn, fnorm) = (r, f);
        }
        Ok(rn <= self.opts.residual_tolerance * fnorm.max(f64::MIN_POSITIVE))
    }

    /// The step along `du` from `u0`: the first of 16 halvings that lowers the merit enough
    /// (Armijo), or the last; `u`, the joints and the residual at it. The merit: on walls of
    /// associative dry joints the potential energy (its gradient is the residual's negative,
    /// and the shifted tangent is positive definite, so the direction descends: the search
    /// cannot cycle), elsewhere the residual's norm `rn`. Returns the step's fraction.
    fn relax_step(&mut self, u0: &[f64], du: &[f64], slope: f64, rn: f64, potential: bool) -> f64 {
        let pi0 = if potential { self.potential_energy() } else { rn };
        let mut alpha = 1.0;
        for _ in 0..16 {
            for (dof, e) in self.eq.iter().enumerate() {
                if let Some(k) = *e {
                    self.u[dof] = u0[dof] + alpha * du[k];
                }
            }
            self.evaluate();
            let ok = if potential {
                self.potential_energy() <= pi0 - 1e-4 * alpha * slope
            } else {
                self.residual().0 <= (1.0 - 1e-4 * alpha) * rn
            };
            if ok {
                break;
            }
            alpha *= 0.5;
        }
        self.residual();
        alpha
    }

    /// The potential energy of the current state on walls of dry associative joints: each
    /// joint's `0.5 s^T D^-1 s` (the joint's part, the Moreau envelope of its strength cone,
    /// whose gradient is the return-mapped force) less the work of the applied forces.
    fn potential_energy(&self) -> f64 {
        let model = self.model;
        let joints: f64 = self
            .forces
            .iter()
            .enumerate()
            .map(|(k, s)| {
                let (l, sec) = (model.law(k), &model.sections()[k]);
                0.5 * (s[0] * s[0] / (l.normal_stiffness * sec.area)
                    + s[1] * s[1] / (l.shear_stiffness * sec.area)
                    + s[2] * s[2] / (l.normal_stiffness * sec.inertia))
            })
            .sum();
        let (fd, fl) = (model.dead_load(), model.live_load());
        let work: f64 = self
            .eq
            .iter()
            .enumerate()
            .filter(|(_, e)| e.is_some())
            .map(|(dof, _)| (self.dead_factor * fd[dof] + self.lambda * fl[dof]) * self.u[dof])
            .sum();
        joints - work
    }

    /// Solves `(K_T + D / dtau) du = r` (the residual in `rhs`; the tangent with the work path's
    /// stabilization, the shift keeping the matrix regular), `D` into `d`.
    fn shifted_solve(&mut self, diag: &[usize], d: &mut [f64], dtau: f64, du: &mut [f64]) -> Result<(), Error> {
        self.update_tangents();
        // the factorization is no longer that of the tangents alone
        self.fact_key = None;
        let (sys, slots) = self.load_sys.as_mut().unwrap();
        Self::assemble(self.model, NEWTON_STABILIZATION, &self.tangents, sys, slots);
        let vals = sys.values_mut();
        // D: the tangent's diagonal (with its stabilization, so positive). The lumped mass,
        // scaled to the same sum, took as many iterations (BENCHMARKS.md, static solver).
        for (dk, &s) in d.iter_mut().zip(diag) {
            *dk = vals[s].abs();
        }
        for (dk, &s) in d.iter().zip(diag) {
            vals[s] += dk / dtau;
        }
        sys.factorize()?;
        du.copy_from_slice(&self.rhs);
        sys.solve_in_place(du)
    }
}
