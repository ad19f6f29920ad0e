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
//! - In 3D ([`modes_3d`], a [`Model3`] of boxes and polyhedra): 6 dofs per block, `K` each
//!   contact's elastic stiffness at its corners as the 3D explicit solver has it
//!   ([`crate::joint::corner_map`]: `kN A (alpha W + (1 - alpha) w w^T)` on the corners' normal
//!   jumps, `W` the diagonal of their shares `w`, and `kT A w_i` on each corner's slip along
//!   both tangents), `M` each block's mass and full inertia tensor. The rotation dofs are about
//!   each block's principal axes of inertia (as in a time history), where the mass is
//!   diagonal; the shapes give the rotations about x, y and z.
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
use crate::explicit::jump_rows;
use crate::joint::{corner_shares, CornerLaw};
use crate::linalg::{symmetric_eigen, SparseLu};
use crate::model::Model;
use crate::space::Model3;

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
    /// The mode shapes, 3 numbers per block in the plane (u1, u2 \[m\], phi \[rad\] at index
    /// `3 i + k`, as the model's dofs), 6 in 3D (ux, uy, uz \[m\], then the rotations about x,
    /// y, z \[rad\] at index `6 i + k`), scaled so that `phi^T M phi = 1` (each value per square
    /// root of a kilogram; in 3D with the full inertia tensor); fixed dofs are 0. The sign makes
    /// the largest entry positive.
    pub shapes: Vec<Vec<f64>>,
    /// `||K phi - omega^2 M phi|| / ||K phi||` of each mode (Euclidean norms over the free
    /// dofs); the denominator is at least [`SOFT`] times `lambda_max ||M phi||`, `lambda_max`
    /// the largest `K_ii / M_ii` (a bound of the highest `omega^2`), so that a mode of no
    /// stiffness (a mechanism, a model without supports) is measured against the model's scale
    /// instead of against its own rounding errors.
    pub residuals: Vec<f64>,
    /// The effective modal mass of each mode for a ground motion along x and along y (the
    /// plane), or along x, y and z (3D) \[kg\]: `(phi^T M r)^2` with `r` the unit translation of
    /// every block. Over all the modes they add up to the mass of the blocks free to move in
    /// that direction.
    pub effective_mass: Vec<Vec<f64>>,
    /// The mass free to move along each direction of [`Modes::effective_mass`] \[kg\]: what the
    /// effective masses of all the modes add up to.
    pub free_mass: Vec<f64>,
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
    check_count(n)?;
    solve(&Problem::plane(model)?, n, shift)
}

/// The lowest `n` natural modes of a 3D model ([`Model3`]: boxes and polyhedra), or with a
/// `shift` the `n` nearest it, as [`modes`] in the plane: 6 dofs per block, the mass with each
/// block's full inertia tensor, the stiffness of the contacts' corners as the 3D explicit
/// solver's elastic law (see the [module docs](self)). The same errors as [`modes`].
pub fn modes_3d(model: &Model3, n: usize, shift: Option<f64>) -> Result<Modes> {
    check_count(n)?;
    solve(&Problem::space(model)?, n, shift)
}

fn check_count(n: usize) -> Result<()> {
    if n == 0 {
        return Err(Error::input("modal analysis: the number of modes must be at least 1"));
    }
    Ok(())
}

/// The modes of a problem (see [`modes`]).
fn solve(problem: &Problem, n: usize, shift: Option<f64>) -> Result<Modes> {
    let nf = problem.dofs.len();
    if n > nf {
        return Err(Error::input(format!(
            "modal analysis: {n} modes asked for, but the model has only {nf} free dofs ({} per block not fixed)",
            problem.per
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

/// A model's elastic problem on its free dofs (its equations), in either dimension: the
/// stiffness as dense element matrices (an interface's 6 x 6 in the plane, a contact's 12 x 12
/// in 3D) on their global dofs, and a diagonal mass.
struct Problem {
    /// dofs per block: 3 in the plane, 6 in 3D (of which 2 or 3 translations)
    per: usize,
    /// the global dof of each equation, and the equation of each global dof
    dofs: Vec<usize>,
    eq: Vec<Option<usize>>,
    /// the diagonal mass of each equation \[kg or kg m2\]
    mass: Vec<f64>,
    /// the number of dofs of an element, each element's global dofs (`width` each) and its
    /// stiffness (`width^2` each, row-major, symmetric exactly)
    width: usize,
    el_dofs: Vec<usize>,
    el_k: Vec<f64>,
    /// 3D: each block's principal axes where they are not x, y, z (its rotation dofs are about
    /// them, which makes the mass diagonal); the plane: empty
    axes: Vec<Option<[f64; 9]>>,
    /// the largest `K_ii / M_ii` of the free dofs [1/s2]
    lambda_max: f64,
}

impl Problem {
    /// The plane's problem: each interface's `B^T D B`, the blocks' `(m, m, J)`.
    fn plane(model: &Model) -> Result<Self> {
        let its = model.interfaces();
        let mut el_dofs = Vec::with_capacity(6 * its.len());
        let mut el_k = Vec::with_capacity(36 * its.len());
        for (k, it) in its.iter().enumerate() {
            let d = crate::joint::stiffness(model.law(k), &model.sections()[k]);
            let b = &it.b_mat;
            el_dofs.extend(it.dofs());
            let mut kk = [0.0; 36];
            for i in 0..6 {
                for j in i..6 {
                    let v = d[0] * b[0][i] * b[0][j] + d[1] * b[1][i] * b[1][j] + d[2] * b[2][i] * b[2][j];
                    kk[6 * i + j] = v;
                    kk[6 * j + i] = v;
                }
            }
            el_k.extend(kk);
        }
        let mass = (0..3 * model.n_blocks()).map(|g| if g % 3 == 2 { model.inertia()[g / 3] } else { model.mass()[g / 3] }).collect();
        Problem::new(3, model.fixed(), mass, 6, el_dofs, el_k, vec![])
    }

    /// The 3D problem: each contact's elastic stiffness at its corners, the 3D explicit solver's
    /// ([`crate::joint::corner_map`]: `kN A (alpha W + (1 - alpha) w w^T)` on the corners'
    /// normal jumps, `kT A w_i` on each corner's slip along both tangents), and each block's
    /// mass and principal moments of inertia, the rotation dofs about its principal axes (those
    /// of a time history).
    fn space(model: &Model3) -> Result<Self> {
        let (axes, inertia) = crate::explicit::principal_axes(model);
        let contacts = model.contacts();
        check_memory(&format!("the modal analysis's stiffness of {} contacts", contacts.len()), contacts.len() as f64 * 156.0 * 8.0)?;
        let mut el_dofs = Vec::with_capacity(12 * contacts.len());
        let mut el_k = Vec::with_capacity(144 * contacts.len());
        let cen = model.centroids();
        for (k, c) in contacts.iter().enumerate() {
            let (w, alpha) = corner_shares(&c.corners, c.centroid, c.n);
            let law = CornerLaw::new(model.law(k), c.area, alpha);
            let frame = [c.n, c.t1, c.t2];
            let turned = [axes[c.a].as_ref(), axes[c.b].as_ref()];
            let mut kk = [0.0; 144];
            // the shares' mean of the corners' normal rows: the contact's normal jump
            let mut mean = [0.0; 12];
            let add = |kk: &mut [f64; 144], s: f64, r: &[f64; 12]| {
                for i in 0..12 {
                    for j in i..12 {
                        kk[12 * i + j] += s * r[i] * r[j];
                    }
                }
            };
            for (x, wi) in c.corners.iter().zip(&w) {
                let rel = |o: [f64; 3]| [x[0] - o[0], x[1] - o[1], x[2] - o[2]];
                let rows = jump_rows(rel(cen[c.a]), rel(cen[c.b]), &frame, turned);
                add(&mut kk, law.alpha * law.kn * wi, &rows[0]);
                add(&mut kk, law.kt * wi, &rows[1]);
                add(&mut kk, law.kt * wi, &rows[2]);
                mean.iter_mut().zip(&rows[0]).for_each(|(m, r)| *m += wi * r);
            }
            add(&mut kk, (1.0 - law.alpha) * law.kn, &mean);
            for i in 0..12 {
                for j in 0..i {
                    kk[12 * i + j] = kk[12 * j + i];
                }
            }
            el_dofs.extend((0..6).map(|j| 6 * c.a + j).chain((0..6).map(|j| 6 * c.b + j)));
            el_k.extend(kk);
        }
        let mass = (0..model.n_blocks())
            .flat_map(|i| {
                let (m, j) = (model.mass()[i], inertia[i]);
                [m, m, m, j[0], j[1], j[2]]
            })
            .collect();
        Problem::new(6, model.fixed(), mass, 12, el_dofs, el_k, axes)
    }

    /// The problem of `per` dofs per block, the dofs `fixed`, `mass` of every dof, and the
    /// elements of `width` dofs.
    fn new(
        per: usize,
        fixed: &[bool],
        mass: Vec<f64>,
        width: usize,
        el_dofs: Vec<usize>,
        el_k: Vec<f64>,
        axes: Vec<Option<[f64; 9]>>,
    ) -> Result<Self> {
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
        if !el_dofs.iter().any(|&g| eq[g].is_some()) {
            return Err(Error::input("modal analysis: no interface acts on a free dof: the model has no stiffness"));
        }
        let mass = dofs.iter().map(|&g| mass[g]).collect();
        let mut problem = Problem { per, dofs, eq, mass, width, el_dofs, el_k, axes, lambda_max: 0.0 };
        problem.lambda_max = problem.largest_ratio();
        Ok(problem)
    }

    /// The elements: each one's global dofs and its stiffness (row-major).
    fn elements(&self) -> impl Iterator<Item = (&[usize], &[f64])> {
        self.el_dofs.chunks_exact(self.width).zip(self.el_k.chunks_exact(self.width * self.width))
    }

    /// The largest `K_ii / M_ii` of the free dofs [1/s2].
    fn largest_ratio(&self) -> f64 {
        let mut diag = vec![0.0; self.dofs.len()];
        for (d, k) in self.elements() {
            for (i, &g) in d.iter().enumerate() {
                if let Some(e) = self.eq[g] {
                    diag[e] += k[i * self.width + i];
                }
            }
        }
        diag.iter().zip(&self.mass).map(|(k, m)| k / m).fold(0.0, f64::max)
    }

    /// The sparse matrix `K - sigma M` on the free dofs (assembled, not factorized).
    fn matrix(&self, sigma: f64) -> Result<SparseLu> {
        let free = |g: &usize| self.eq[*g];
        let pattern = self.el_dofs.chunks_exact(self.width).flat_map(|d| {
            let e: Vec<usize> = d.iter().filter_map(free).collect();
            e.iter().flat_map(|&r| e.iter().map(move |&c| (r, c))).collect::<Vec<_>>()
        });
        let mut a = SparseLu::new(self.dofs.len(), pattern)?;
        let mut slots = vec![];
        for (d, k) in self.elements() {
            for i in 0..self.width {
                for j in 0..self.width {
                    if let (Some(r), Some(c)) = (self.eq[d[i]], self.eq[d[j]]) {
                        slots.push((a.slot(r, c).expect("pattern entry"), k[i * self.width + j]));
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

    /// `K x` on the free dofs, element by element.
    fn stiffness_times(&self, x: &[f64]) -> Vec<f64> {
        let mut u = vec![0.0; self.eq.len()];
        for (&g, v) in self.dofs.iter().zip(x) {
            u[g] = *v;
        }
        let mut f = vec![0.0; self.eq.len()];
        for (d, k) in self.elements() {
            for (i, &gi) in d.iter().enumerate() {
                f[gi] += k[i * self.width..(i + 1) * self.width].iter().zip(d).map(|(k, &gj)| k * u[gj]).sum::<f64>();
            }
        }
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

    /// The modes of the pairs, sorted by frequency, with their full shapes (rotations about x,
    /// y, z) and effective masses.
    fn modes(&self, mut pairs: Vec<Pair>, sigma: f64, basis: usize) -> Modes {
        pairs.sort_by(|a, b| a.lambda.total_cmp(&b.lambda));
        let per = self.per;
        // the translations: x, y in the plane, x, y, z in 3D
        let directions = if per == 3 { 2 } else { 3 };
        let mut out = Modes {
            frequencies: vec![],
            angular: vec![],
            eigenvalues: vec![],
            shapes: vec![],
            residuals: vec![],
            effective_mass: vec![],
            free_mass: (0..directions).map(|dir| self.dofs.iter().zip(&self.mass).filter(|(&g, _)| g % per == dir).map(|(_, m)| m).sum()).collect(),
            shift: sigma,
            basis,
        };
        for p in pairs {
            let w = p.lambda.max(0.0).sqrt();
            let mut full = vec![0.0; self.eq.len()];
            for (&g, v) in self.dofs.iter().zip(&p.shape) {
                full[g] = *v;
            }
            // the rotations about a block's principal axes, about x, y and z
            for (i, q) in self.axes.iter().enumerate() {
                if q.is_some() {
                    let r = crate::explicit::to_world(&self.axes, i, [full[6 * i + 3], full[6 * i + 4], full[6 * i + 5]]);
                    full[6 * i + 3..6 * i + 6].copy_from_slice(&r);
                }
            }
            // the sign that makes the largest entry positive (the first of equal ones)
            let big = full.iter().copied().fold(0.0, |a: f64, v| if v.abs() > a.abs() { v } else { a });
            if big < 0.0 {
                full.iter_mut().for_each(|v| *v = -*v);
            }
            let participation = |dir: usize| -> f64 {
                self.dofs.iter().zip(&self.mass).filter(|(&g, _)| g % per == dir).map(|(&g, m)| m * full[g]).sum()
            };
            out.effective_mass.push((0..directions).map(|dir| participation(dir).powi(2)).collect());
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
