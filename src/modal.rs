//! Modal analysis of the elastic model: the lowest natural frequencies and mode shapes,
//! `K phi = omega^2 M phi` on the free dofs.
//!
//! - `K`: the elastic stiffness of every interface, `B^T D B` with `D = diag(kN A, kT A, kN I)`
//!   ([`crate::joint::stiffness`]) and `B` the interface's kinematics ([`Interface::b_mat`]):
//!   every joint closed and elastic, as in the undeformed wall (no joint open, no gravity
//!   stiffness).
//! - `M`: the diagonal mass, `(m, m, J)` per block ([`Model::mass`], [`Model::inertia`]).
//! - Fixed dofs ([`Model::fixed`]: the base, the supports) are left out, and are zero in the
//!   shapes.
//!
//! Method: shift-invert Lanczos with full reorthogonalization, in the mass inner product, on
//! the sparse Cholesky of `K - sigma M` (`sigma` slightly negative by default, so that the
//! matrix is positive definite even when some block is nearly free). The basis starts from
//! [`BLOCK`] vectors and the operator is applied to [`BLOCK`] vectors at a time (block Lanczos:
//! one pass over the factor for all of them, and modes of equal frequency, such as those of
//! identical parts of a wall, are in the Krylov space with their multiplicity up to [`BLOCK`]
//! without relying on rounding errors to bring them in). The modes are the Ritz pairs of
//! `K` on the basis (`V^T K V`, `V` M-orthonormal) nearest the shift: read from the stiffness
//! itself, they keep their accuracy when the operator's solves do not (a model with a
//! mechanism, where `K - sigma M` is as ill-conditioned as the shift is small). The basis grows
//! until every wanted mode's residual `||K phi - omega^2 M phi|| / ||K phi||` is below
//! [`TOLERANCE`]; the residual of each mode is returned.
//!
//! [`Interface::b_mat`]: crate::interface::Interface::b_mat
//!
//! ```
//! use masonry_dem::geometry::Rect;
//! use masonry_dem::modal::modes;
//! use masonry_dem::model::{Model, ModelSpec};
//! // one block 0.4 x 1.0 m on its base (thickness 1 m, 1000 kg/m3, kN = 1e10 N/m3)
//! let model = Model::new(ModelSpec { blocks: vec![Rect::new(0.0, 0.0, 0.4, 1.0).into()], ..ModelSpec::default() }).unwrap();
//! let m = modes(&model, 3, None).unwrap();
//! // the vertical mode: omega^2 = kN b s / m
//! let vertical = (1e10 * 0.4 * 1.0 / 400.0_f64).sqrt();
//! assert!(m.angular.iter().any(|w| (w - vertical).abs() < 1e-9 * vertical));
//! assert!(m.residuals.iter().all(|r| *r < 1e-8));
//! ```

use crate::error::{check_memory, Error, Result};
use crate::linalg::{symmetric_eigen, SparseLu};
use crate::model::Model;

/// The natural modes of a model, lowest frequency first.
#[derive(Debug, Clone, PartialEq)]
pub struct Modes {
    /// Natural frequencies `f = omega / (2 pi)` \[Hz\].
    pub frequencies: Vec<f64>,
    /// Angular frequencies `omega` \[rad/s\]; a mode of zero stiffness (a mechanism, a model
    /// without supports) is 0 even when its computed `omega^2` is a rounding error below 0.
    pub angular: Vec<f64>,
    /// The eigenvalues `omega^2` as computed \[rad2/s2\].
    pub eigenvalues: Vec<f64>,
    /// The mode shapes, 3 numbers per block (u1, u2 \[m\], phi \[rad\] at index `3 i + k`, as
    /// the model's dofs), scaled so that `phi^T M phi = 1` (each value per square root of a
    /// kilogram); fixed dofs are 0. The sign makes the largest entry positive.
    pub shapes: Vec<Vec<f64>>,
    /// `||K phi - omega^2 M phi|| / ||K phi||` of each mode (Euclidean norms over the free
    /// dofs); the denominator is at least [`SOFT`] times `lambda_max ||M phi||`, `lambda_max`
    /// the largest `K_ii / M_ii` (a bound of the highest `omega^2`), so that a mode of no
    /// stiffness (a mechanism, a model without supports) is measured against the model's scale
    /// instead of against its own rounding errors.
    pub residuals: Vec<f64>,
    /// The effective modal mass of each mode for a ground motion along x and along y \[kg\]:
    /// `(phi^T M r)^2` with `r` the unit translation of every block. Over all the modes they add
    /// up to the mass of the blocks free to move in that direction.
    pub effective_mass: Vec<[f64; 2]>,
    /// The mass free to move along x and along y \[kg\]: what the effective masses of all the
    /// modes add up to.
    pub free_mass: [f64; 2],
    /// The shift `sigma` the operator `(K - sigma M)^-1 M` was built with \[rad2/s2\].
    pub shift: f64,
    /// The size of the Lanczos basis the modes were extracted from.
    pub basis: usize,
}

/// The block size of the Lanczos basis: its number of start vectors, the vectors solved for at
/// once, and the largest multiplicity of a frequency sure to be found whole. 10 modes of a
/// 10,050-block wall (30,150 dofs), on a loaded machine: 1.3 s one vector at a time, 0.5 s
/// three at a time (the factor is read once for three solves).
pub const BLOCK: usize = 3;

/// The residual `||K phi - omega^2 M phi|| / ||K phi||` every mode must reach before the basis
/// stops growing.
pub const TOLERANCE: f64 = 1e-8;

/// The largest residual accepted when the basis has reached its largest size: beyond it
/// [`modes`] fails with [`Error::Convergence`].
pub const ACCEPTABLE: f64 = 1e-6;

/// The smallest denominator of a mode's residual, as a fraction of `lambda_max ||M phi||`
/// (see [`Modes::residuals`]): rounding alone leaves `K phi` at about 1e-16 of
/// `lambda_max ||M phi||` on a mode of no stiffness.
pub const SOFT: f64 = 1e-6;

/// The default shift, as a fraction of the largest `K_ii / M_ii` (an upper bound of the model's
/// highest `omega^2`), taken negative: `K - sigma M` is then positive definite with a condition
/// number of at most 1e10, even for a model with a mechanism.
pub const SHIFT_FRACTION: f64 = 1e-10;

/// The lowest `n` natural modes of the elastic model, or with a `shift` \[rad2/s2\] the `n` whose
/// `omega^2` are nearest to it (see the [module docs](self)); `None` takes a shift slightly
/// below zero ([`SHIFT_FRACTION`]).
///
/// Errors: [`Error::Input`] for `n = 0`, `n` above the number of free dofs, a model with every
/// dof fixed or without stiffness on its free dofs, a non-finite shift, or a shift at which
/// `K - shift M` is singular (a shift of 0 on a model with a mechanism);
/// [`Error::Convergence`] if some mode's residual stays above [`ACCEPTABLE`].
pub fn modes(model: &Model, n: usize, shift: Option<f64>) -> Result<Modes> {
    if n == 0 {
        return Err(Error::input("modal analysis: the number of modes must be at least 1"));
    }
    let problem = Problem::new(model)?;
    let nf = problem.dofs.len();
    if n > nf {
        return Err(Error::input(format!(
            "modal analysis: {n} modes asked for, but the model has only {nf} free dofs (3 per block not fixed)"
        )));
    }
    let sigma = match shift {
        Some(s) if !s.is_finite() => return Err(Error::input(format!("modal analysis: the shift must be a finite number, got {s}"))),
        Some(s) => s,
        None => -SHIFT_FRACTION * problem.lambda_max,
    };
    let cap = nf.min(4 * n + 100);
    check_memory(&format!("the modal analysis's basis of {cap} vectors of {nf} dofs"), (cap * nf) as f64 * 8.0)?;
    let mut matrix = problem.matrix(sigma)?;
    matrix.factorize().map_err(|e| singular(sigma, e))?;
    // (K - sigma M)^-1 M applied to a block of vectors at once: one pass over the factor
    let mut op = |vs: &[Vec<f64>]| -> Result<Vec<Vec<f64>>> {
        let mut x: Vec<f64> = vs.iter().flat_map(|v| v.iter().zip(&problem.mass).map(|(v, m)| v * m)).collect();
        matrix.solve_many_in_place(&mut x, vs.len()).map_err(|e| singular(sigma, e))?;
        Ok(x.chunks(nf).map(<[f64]>::to_vec).collect())
    };
    let stiffness = |x: &[f64]| problem.stiffness_times(x);
    let mut krylov = Krylov::new(&problem.mass);
    let mut target = nf.min(2 * n + 20);
    loop {
        krylov.extend(&mut op, &stiffness, target)?;
        let pairs = problem.ritz_pairs(&krylov, n, sigma)?;
        let exhausted = krylov.basis.len() == nf;
        let worst = pairs.iter().map(|p| p.residual).fold(0.0, f64::max);
        if worst <= TOLERANCE || exhausted || krylov.processed >= cap {
            if !(worst <= ACCEPTABLE) && !exhausted {
                return Err(Error::Convergence(format!(
                    "modal analysis: after a basis of {} vectors a mode's residual is still {worst:.2e} (more than {ACCEPTABLE:e}); ask for fewer modes, or give a shift near the frequencies wanted",
                    krylov.basis.len()
                )));
            }
            return Ok(problem.modes(pairs, sigma, krylov.basis.len()));
        }
        target = cap.min(target + (n / 2).max(10));
    }
}

/// The error of a singular `K - sigma M`.
fn singular(sigma: f64, e: Error) -> Error {
    match e {
        Error::Convergence(m) => Error::input(format!(
            "modal analysis: K - shift M is singular at shift = {sigma:e} rad2/s2 ({m}): the shift is a natural omega^2 of the model (a shift of 0 on a model with a mechanism); give another, or none"
        )),
        e => e,
    }
}

/// Rayleigh damping `C = alpha M + beta K` that gives the damping ratio `zeta1` at the angular
/// frequency `omega1` and `zeta2` at `omega2` \[rad/s\]: returns (alpha \[1/s\], beta \[s\]), the
/// ratio at any `omega` being `zeta = alpha / (2 omega) + beta omega / 2`.
///
/// Errors ([`Error::Input`]): a frequency not finite and > 0, equal frequencies, a ratio not
/// finite and >= 0, or ratios that would need a negative coefficient (a ratio that falls
/// faster than `1 / omega` or rises faster than `omega` between the two frequencies: some
/// modes would be negatively damped).
///
/// ```
/// use masonry_dem::modal::rayleigh_coefficients;
/// let (alpha, beta) = rayleigh_coefficients(10.0, 50.0, 0.05, 0.05).unwrap();
/// let zeta = |w: f64| alpha / (2.0 * w) + beta * w / 2.0;
/// assert!((zeta(10.0) - 0.05).abs() < 1e-12 && (zeta(50.0) - 0.05).abs() < 1e-12);
/// ```
pub fn rayleigh_coefficients(omega1: f64, omega2: f64, zeta1: f64, zeta2: f64) -> Result<(f64, f64)> {
    for (name, w) in [("omega1", omega1), ("omega2", omega2)] {
        if !(w.is_finite() && w > 0.0) {
            return Err(Error::input(format!("Rayleigh damping: {name} must be a finite angular frequency > 0 rad/s, got {w}")));
        }
    }
    for (name, z) in [("zeta1", zeta1), ("zeta2", zeta2)] {
        if !(z.is_finite() && z >= 0.0) {
            return Err(Error::input(format!("Rayleigh damping: {name} must be a finite damping ratio >= 0, got {z}")));
        }
    }
    if omega1 == omega2 {
        return Err(Error::input(format!(
            "Rayleigh damping: the two frequencies are equal ({omega1} rad/s): two different ones fix alpha and beta"
        )));
    }
    // alpha + beta omega_i^2 = 2 zeta_i omega_i, i = 1, 2
    let den = omega2 * omega2 - omega1 * omega1;
    let beta = 2.0 * (zeta2 * omega2 - zeta1 * omega1) / den;
    let alpha = 2.0 * omega1 * omega2 * (zeta1 * omega2 - zeta2 * omega1) / den;
    if alpha < 0.0 || beta < 0.0 {
        return Err(Error::input(format!(
            "Rayleigh damping: zeta1 = {zeta1} at {omega1} rad/s and zeta2 = {zeta2} at {omega2} rad/s need alpha = {alpha:.3e} 1/s and beta = {beta:.3e} s, and a negative coefficient damps some modes negatively; give closer ratios"
        )));
    }
    Ok((alpha, beta))
}

/// A converged Ritz pair: `omega^2`, the shape on the free dofs, its residual.
struct Pair {
    lambda: f64,
    shape: Vec<f64>,
    residual: f64,
}

/// The model's elastic problem on its free dofs (its equations).
struct Problem<'a> {
    model: &'a Model,
    /// the global dof of each equation, and the equation of each global dof
    dofs: Vec<usize>,
    eq: Vec<Option<usize>>,
    /// the diagonal mass of each equation \[kg or kg m2\]
    mass: Vec<f64>,
    /// each interface's elastic stiffness D (its diagonal)
    d: Vec<[f64; 3]>,
    /// the largest `K_ii / M_ii` of the free dofs [1/s2]
    lambda_max: f64,
}

impl<'a> Problem<'a> {
    fn new(model: &'a Model) -> Result<Self> {
        let fixed = model.fixed();
        let mut eq = vec![None; fixed.len()];
        let mut dofs = vec![];
        for (g, e) in eq.iter_mut().enumerate() {
            if !fixed[g] {
                *e = Some(dofs.len());
                dofs.push(g);
            }
        }
        if dofs.is_empty() {
            return Err(Error::input("modal analysis: every dof of the model is fixed: nothing vibrates"));
        }
        let stiff = model.interfaces().iter().any(|it| it.dofs().iter().any(|&g| eq[g].is_some()));
        if !stiff {
            return Err(Error::input("modal analysis: no interface acts on a free dof: the model has no stiffness"));
        }
        let mass = dofs.iter().map(|&g| if g % 3 == 2 { model.inertia()[g / 3] } else { model.mass()[g / 3] }).collect();
        let d = (0..model.interfaces().len()).map(|k| crate::joint::stiffness(model.law(k), &model.sections()[k])).collect();
        let mut problem = Problem { model, dofs, eq, mass, d, lambda_max: 0.0 };
        problem.lambda_max = problem.largest_ratio();
        Ok(problem)
    }

    /// Entry (i, j) of interface k's elastic stiffness `B^T D B` (local dofs 0..6).
    fn entry(&self, k: usize, i: usize, j: usize) -> f64 {
        let (b, d) = (&self.model.interfaces()[k].b_mat, &self.d[k]);
        d[0] * b[0][i] * b[0][j] + d[1] * b[1][i] * b[1][j] + d[2] * b[2][i] * b[2][j]
    }

    /// The largest `K_ii / M_ii` of the free dofs [1/s2].
    fn largest_ratio(&self) -> f64 {
        let mut diag = vec![0.0; self.dofs.len()];
        for (k, it) in self.model.interfaces().iter().enumerate() {
            for (i, &g) in it.dofs().iter().enumerate() {
                if let Some(e) = self.eq[g] {
                    diag[e] += self.entry(k, i, i);
                }
            }
        }
        diag.iter().zip(&self.mass).map(|(k, m)| k / m).fold(0.0, f64::max)
    }

    /// The sparse matrix `K - sigma M` on the free dofs (assembled, not factorized).
    fn matrix(&self, sigma: f64) -> Result<SparseLu> {
        let its = self.model.interfaces();
        let free = |g: &usize| self.eq[*g];
        let pattern = its.iter().flat_map(|it| {
            let e: Vec<usize> = it.dofs().iter().filter_map(free).collect();
            e.iter().flat_map(|&r| e.iter().map(move |&c| (r, c))).collect::<Vec<_>>()
        });
        let mut a = SparseLu::new(self.dofs.len(), pattern)?;
        let mut slots = vec![];
        for (k, it) in its.iter().enumerate() {
            let d = it.dofs();
            for i in 0..6 {
                for j in 0..6 {
                    if let (Some(r), Some(c)) = (self.eq[d[i]], self.eq[d[j]]) {
                        // the upper entry's value on both sides: the matrix is symmetric exactly
                        let v = self.entry(k, i.min(j), i.max(j));
                        slots.push((a.slot(r, c).expect("pattern entry"), v));
                    }
                }
            }
        }
        for (e, m) in self.mass.iter().enumerate() {
            slots.push((a.slot(e, e).expect("diagonal entry"), -sigma * m));
        }
        let values = a.values_mut();
        values.fill(0.0);
        for (s, v) in slots {
            values[s] += v;
        }
        Ok(a)
    }

    /// `K x` on the free dofs, through the interfaces' jumps and forces.
    fn stiffness_times(&self, x: &[f64]) -> Vec<f64> {
        let mut u = vec![0.0; self.eq.len()];
        for (&g, v) in self.dofs.iter().zip(x) {
            u[g] = *v;
        }
        let forces: Vec<[f64; 3]> = self
            .model
            .interfaces()
            .iter()
            .zip(&self.d)
            .map(|(it, d)| {
                let e = it.jumps(&u);
                [d[0] * e[0], d[1] * e[1], d[2] * e[2]]
            })
            .collect();
        let mut f = vec![0.0; self.eq.len()];
        self.model.internal_forces(&forces, &mut f);
        self.dofs.iter().map(|&g| f[g]).collect()
    }

    /// The `n` Ritz pairs of the basis nearest the shift (the lowest `n` for a shift below
    /// them), from `V^T K V` (the basis is M-orthonormal), with their residuals.
    fn ritz_pairs(&self, krylov: &Krylov, n: usize, sigma: f64) -> Result<Vec<Pair>> {
        let q = krylov.basis.len();
        let (lambda, s) = symmetric_eigen(q, &krylov.projected())?;
        let mut order: Vec<usize> = (0..q).collect();
        order.sort_by(|&a, &b| (lambda[a] - sigma).abs().total_cmp(&(lambda[b] - sigma).abs()));
        order.truncate(n);
        let pairs = order
            .into_iter()
            .map(|k| {
                let shape = krylov.combine(&s[k * q..(k + 1) * q]);
                let residual = self.residual(&shape, lambda[k]);
                Pair { lambda: lambda[k], shape, residual }
            })
            .collect();
        Ok(pairs)
    }

    /// `||K x - lambda M x|| / ||K x||` ([`SOFT`] `lambda_max ||M x||` as the denominator when
    /// that is the larger: a mode of no stiffness).
    fn residual(&self, x: &[f64], lambda: f64) -> f64 {
        let kx = self.stiffness_times(x);
        let norm = |v: &mut dyn Iterator<Item = f64>| v.map(|a| a * a).sum::<f64>().sqrt();
        let r = norm(&mut kx.iter().zip(x).zip(&self.mass).map(|((k, x), m)| k - lambda * m * x));
        let mx = norm(&mut x.iter().zip(&self.mass).map(|(x, m)| x * m));
        let den = norm(&mut kx.iter().copied()).max(SOFT * self.lambda_max * mx);
        if den > 0.0 {
            r / den
        } else {
            r
        }
    }

    /// The modes of the pairs, sorted by frequency, with their full shapes and effective masses.
    fn modes(&self, mut pairs: Vec<Pair>, sigma: f64, basis: usize) -> Modes {
        pairs.sort_by(|a, b| a.lambda.total_cmp(&b.lambda));
        let mut out = Modes {
            frequencies: vec![],
            angular: vec![],
            eigenvalues: vec![],
            shapes: vec![],
            residuals: vec![],
            effective_mass: vec![],
            free_mass: [0, 1].map(|dir| self.dofs.iter().zip(&self.mass).filter(|(&g, _)| g % 3 == dir).map(|(_, m)| m).sum()),
            shift: sigma,
            basis,
        };
        for p in pairs {
            let w = p.lambda.max(0.0).sqrt();
            // the sign that makes the largest entry positive (the first of equal ones)
            let big = p.shape.iter().copied().fold(0.0, |a: f64, v| if v.abs() > a.abs() { v } else { a });
            let sign = if big < 0.0 { -1.0 } else { 1.0 };
            let mut full = vec![0.0; self.eq.len()];
            for (&g, v) in self.dofs.iter().zip(&p.shape) {
                full[g] = sign * v;
            }
            let participation = |dir: usize| -> f64 {
                self.dofs.iter().zip(&self.mass).filter(|(&g, _)| g % 3 == dir).map(|(&g, m)| m * full[g]).sum()
            };
            out.effective_mass.push([participation(0).powi(2), participation(1).powi(2)]);
            out.frequencies.push(w / (2.0 * std::f64::consts::PI));
            out.angular.push(w);
            out.eigenvalues.push(p.lambda);
            out.shapes.push(full);
            out.residuals.push(p.residual);
        }
        out
    }
}

/// The operator `(K - sigma M)^-1 M` applied to a block of vectors.
type Operator<'a> = dyn FnMut(&[Vec<f64>]) -> Result<Vec<Vec<f64>>> + 'a;

/// The Lanczos basis, M-orthonormal, grown one vector at a time from [`BLOCK`] start vectors:
/// the operator applied to each vector in turn, the result orthogonalized against the whole
/// basis twice (full reorthogonalization) and appended. With each vector the basis keeps the
/// projection of the stiffness, `V^T K V`, from which the modes are extracted.
struct Krylov<'m> {
    mass: &'m [f64],
    basis: Vec<Vec<f64>>,
    /// the vectors the operator has been applied to
    processed: usize,
    /// row j of `V^T K V` up to its diagonal: `v_i^T K v_j`, i <= j
    stiffness: Vec<Vec<f64>>,
    seed: u64,
}

impl<'m> Krylov<'m> {
    fn new(mass: &'m [f64]) -> Self {
        Krylov { mass, basis: vec![], processed: 0, stiffness: vec![], seed: 0x9E37_79B9_7F4A_7C15 }
    }

    fn dot(&self, x: &[f64], y: &[f64]) -> f64 {
        x.iter().zip(y).zip(self.mass).map(|((x, y), m)| x * m * y).sum()
    }

    /// A pseudo-random vector (xorshift, the same every run) with entries in (-1, 1).
    fn random(&mut self) -> Vec<f64> {
        (0..self.mass.len())
            .map(|_| {
                self.seed ^= self.seed << 13;
                self.seed ^= self.seed >> 7;
                self.seed ^= self.seed << 17;
                (self.seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
            })
            .collect()
    }

    /// Orthogonalizes `w` against the basis (two passes) and appends it, normalized, with its
    /// row of `V^T K V`, unless it lies in the basis already (or the basis is complete).
    fn append(&mut self, mut w: Vec<f64>, stiffness: &dyn Fn(&[f64]) -> Vec<f64>) {
        let before = self.dot(&w, &w).sqrt();
        for _ in 0..2 {
            let c: Vec<f64> = self.basis.iter().map(|v| self.dot(v, &w)).collect();
            for (v, c) in self.basis.iter().zip(&c) {
                w.iter_mut().zip(v).for_each(|(w, v)| *w -= c * v);
            }
        }
        let after = self.dot(&w, &w).sqrt();
        if after > 1e-8 * before && self.basis.len() < self.mass.len() {
            w.iter_mut().for_each(|w| *w /= after);
            let kw = stiffness(&w);
            let euclid = |x: &[f64]| x.iter().zip(&kw).map(|(x, k)| x * k).sum::<f64>();
            let mut row: Vec<f64> = self.basis.iter().map(|v| euclid(v)).collect();
            row.push(euclid(&w));
            self.stiffness.push(row);
            self.basis.push(w);
        }
    }

    /// Grows the basis until the operator has been applied to `target` vectors (or the basis
    /// spans every dof), up to [`BLOCK`] vectors at a time. A block the operator maps into the
    /// basis (an invariant subspace) lets a fresh random vector carry on.
    fn extend(
        &mut self,
        op: &mut Operator<'_>,
        stiffness: &dyn Fn(&[f64]) -> Vec<f64>,
        target: usize,
    ) -> Result<()> {
        let n = self.mass.len();
        while self.basis.len() < BLOCK.min(n) {
            let r = self.random();
            self.append(r, stiffness);
        }
        while self.processed < target && self.processed < self.basis.len() {
            let end = self.basis.len().min(self.processed + BLOCK).min(target);
            for w in op(&self.basis[self.processed..end])? {
                self.append(w, stiffness);
            }
            self.processed = end;
            while self.processed == self.basis.len() && self.basis.len() < n {
                let r = self.random();
                self.append(r, stiffness);
            }
        }
        Ok(())
    }

    /// `V^T K V` over the whole basis, column-major.
    fn projected(&self) -> Vec<f64> {
        let q = self.basis.len();
        let mut t = vec![0.0; q * q];
        for (j, row) in self.stiffness.iter().enumerate() {
            for (i, &v) in row.iter().enumerate() {
                t[j * q + i] = v;
                t[i * q + j] = v;
            }
        }
        t
    }

    /// `sum_k s_k v_k` over the basis.
    fn combine(&self, s: &[f64]) -> Vec<f64> {
        let mut x = vec![0.0; self.mass.len()];
        for (v, c) in self.basis.iter().zip(s) {
            x.iter_mut().zip(v).for_each(|(x, v)| *x += c * v);
        }
        x
    }
}
