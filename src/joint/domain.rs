//! The strength domain in resultants: its four faces (Coulomb and rocking, the cut-off between
//! them), the elastic stiffness D = diag(kN A, kT A, kN I), the flow directions, and the state
//! flags of a force.

use super::*;

/// The four faces of the domain, each `a . sigma <= b`, with flow direction `m`.
/// Order: Coulomb +T, Coulomb -T, rocking +M, rocking -M (rocking faces divided by l/2).
/// The rows `a` and `m` are formed where they are used, not stored: the elastic check, the
/// common case, reads only `a` and `b`.
pub(super) struct Faces {
    /// mu, tan(psi), 2 / l
    pub(super) mu: f64,
    pub(super) tp: f64,
    pub(super) k: f64,
    pub(super) b: [f64; 4],
}

impl Faces {
    /// The faces with cohesion `c` and tensile strength `ft` \[Pa\].
    #[inline(always)]
    pub(super) fn new(law: &JointLaw, sec: &Section, c: f64, ft: f64) -> Self {
        let b = [c * sec.area, c * sec.area, ft * sec.area, ft * sec.area];
        Faces { mu: law.friction, tp: law.dilatancy, k: 2.0 / sec.length, b }
    }
    /// The normal of face `j`.
    #[inline(always)]
    pub(super) fn a(&self, j: usize) -> [f64; 3] {
        match j {
            0 => [self.mu, 1.0, 0.0],
            1 => [self.mu, -1.0, 0.0],
            2 => [1.0, 0.0, self.k],
            _ => [1.0, 0.0, -self.k],
        }
    }
    /// The flow direction of face `j`.
    #[inline(always)]
    pub(super) fn m(&self, j: usize) -> [f64; 3] {
        match j {
            0 => [self.tp, 1.0, 0.0],
            1 => [self.tp, -1.0, 0.0],
            _ => self.a(j),
        }
    }
    #[inline(always)]
    pub(super) fn f(&self, j: usize, s: &[f64; 3]) -> f64 {
        dot(&self.a(j), s) - self.b[j]
    }
}

#[inline]
pub(super) fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

// Active sets tried, smallest first: single faces, then edges, then corners
// (1, 2, 4, 8, 3, 5, 6, 9, 10, 12, 7, 11, 13, 14; bit j: face j), in `map`.

/// The elastic stiffness of an interface, `D = diag(kN A, kT A, kN I)` (its diagonal): the one
/// place it is written, for the joint law and every solver.
#[inline(always)]
pub fn stiffness(law: &JointLaw, sec: &Section) -> [f64; 3] {
    [law.normal_stiffness * sec.area, law.shear_stiffness * sec.area, law.normal_stiffness * sec.inertia]
}

/// D m_j for every face
/// (array literals rather than `std::array::from_fn`, whose closure is not always inlined).
#[inline(always)]
pub(super) fn flow_columns(faces: &Faces, d: &[f64; 3]) -> [[f64; 3]; 4] {
    let dmj = |j: usize| [d[0] * faces.m(j)[0], d[1] * faces.m(j)[1], d[2] * faces.m(j)[2]];
    [dmj(0), dmj(1), dmj(2), dmj(3)]
}

/// The products a_i . D m_j of every pair of faces.
#[inline(always)]
pub(super) fn face_products(faces: &Faces, dm: &[[f64; 3]; 4]) -> [[f64; 4]; 4] {
    let g_row = |i: usize| {
        let a = faces.a(i);
        [dot(&a, &dm[0]), dot(&a, &dm[1]), dot(&a, &dm[2]), dot(&a, &dm[3])]
    };
    [g_row(0), g_row(1), g_row(2), g_row(3)]
}

/// The faces of an active set, in increasing order, and their number.
#[inline(always)]
pub(super) fn faces_of(mask: u8) -> ([usize; 3], usize) {
    let mut act = [0usize; 3];
    let mut n = 0;
    for j in 0..4 {
        if mask & (1 << j) != 0 {
            act[n] = j;
            n += 1;
        }
    }
    (act, n)
}

/// The system `G = A D M` of the active faces `act`.
#[inline(always)]
pub(super) fn set_matrix(g_all: &[[f64; 4]; 4], act: &[usize]) -> [[f64; 3]; 3] {
    let mut g = [[0.0; 3]; 3];
    for (p, &i) in act.iter().enumerate() {
        for (q, &j) in act.iter().enumerate() {
            g[p][q] = g_all[i][j];
        }
    }
    g
}

/// The size of a trial force (N, T, M) in newtons, the moment as its rocking faces see it
/// (2 |M| / l).
#[inline(always)]
pub(super) fn force_scale(trial: &[f64; 3], sec: &Section) -> f64 {
    trial[0].abs() + trial[1].abs() + (trial[2] * (2.0 / sec.length)).abs()
}

/// The tolerance of the Kuhn-Tucker tests of a trial of size `scale` on `faces`.
#[inline(always)]
pub(super) fn kt_tolerance(scale: f64, faces: &Faces) -> f64 {
    1e-12 * (scale + faces.b[0] + faces.b[2]) + f64::MIN_POSITIVE
}

/// The elastic tangent D = diag(kN A, kT A, kN I) of `law` on `sec`: the tangent of an update
/// that [`return_map`] reports elastic (set 0), the same numbers.
pub fn elastic_tangent(law: &JointLaw, sec: &Section) -> [[f64; 3]; 3] {
    let d = stiffness(law, sec);
    [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]]
}

/// The OPEN | SLIDING | ROCKING bits of a returned force `s`, from the trial of size
/// `trial_scale` ([`force_scale`]). A face counts as reached within 0.1% of the force's size: a
/// relaxed explicit state and a Newton-converged static state of the same collapse are then
/// classified alike. And within 1e-9 of the trial's: a joint without strength returned to its
/// apex carries nothing but rounding (some 1e-17 of the trial), whose signs would otherwise read
/// as sliding or rocking instead of open.
pub(super) fn flags(faces: &Faces, s: &[f64; 3], sec: &Section, trial_scale: f64) -> u8 {
    let scale = force_scale(s, sec) + faces.b[0] + faces.b[2];
    let tol = 1e-3 * scale + 1e-9 * trial_scale + f64::MIN_POSITIVE;
    let at = |j: usize| faces.f(j, s) >= -tol;
    if at(2) && at(3) {
        OPEN
    } else {
        let mut fl = 0;
        if at(0) || at(1) {
            fl |= SLIDING;
        }
        if at(2) || at(3) {
            fl |= ROCKING;
        }
        fl
    }
}

/// Whether a force (N, T, M) lies in the domain of `law` with the strengths of history
/// `state`, each face satisfied to within `tol` newtons (rocking faces measured as N + 2|M|/l).
pub fn admissible(law: &JointLaw, sec: &Section, force: &[f64; 3], state: &JointState, tol: f64) -> bool {
    let (c, ft) = law.strengths(state);
    let faces = Faces::new(law, sec, c, ft);
    (0..4).all(|j| faces.f(j, force) <= tol)
}
