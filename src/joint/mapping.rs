//! The return mapping: the active set by enumeration (corners and the apex included), the
//! projection `sigma = sigma_trial - D M dgamma`, and the consistent tangent of the set.

use super::*;

/// How [`return_map`] maps. The default: no prepared constants, no warm set, the tangent.
#[derive(Debug, Clone, Copy)]
pub struct MapOptions<'a> {
    /// the constants of the law on the section (`Prepared::new(law, sec)`), or None to compute
    /// them here: the same numbers
    pub prepared: Option<&'a Prepared>,
    /// an active set to try first (bit j: face j; 0: none), e.g. the one the joint ended on at
    /// the last evaluation
    pub warm: u8,
    /// take the warm set only with a margin: every multiplier and every inactive face's value
    /// beyond a millionth of the force's scale (a million times the tolerance of the test). The
    /// set is then the one the ordered enumeration finds (the return is unique, and a set off
    /// it by such margins is not near another), so that the force, history, flags and tangent
    /// are those of the default options bit for bit. Without it the warm set is taken on the ordered
    /// enumeration's own test, which can choose another set at a tie (a face reached with a
    /// zero multiplier): the same force and history to rounding, but another tangent.
    pub strict: bool,
    /// compute the consistent tangent (left zero otherwise)
    pub tangent: bool,
}

impl Default for MapOptions<'_> {
    fn default() -> Self {
        MapOptions { prepared: None, warm: 0, strict: false, tangent: true }
    }
}

/// The set that [`return_map`] reports where no active set satisfies the Kuhn-Tucker
/// conditions (degenerate data) and the force is put at the apex of the domain.
pub const APEX: u8 = 0x10;

/// The return mapping, the one entry to the joint law for every solver: the forces, updated
/// history, state flags and consistent tangent (if `opts.tangent`) for the total jumps `e`,
/// starting from the committed history `committed`; also the active set accepted (bit j: face
/// j; 0: the update is elastic and the tangent D; [`APEX`]: no set, the apex). `opts` may give
/// the law's constants on the section prepared beforehand and an active set to try first: the
/// same forces, history and flags (see [`MapOptions`]).
///
/// Why any set passing the Kuhn-Tucker test gives the same force and history, whichever is
/// tried first: the Coulomb flow `m_j = (tan psi, +-1, 0)` is `H a_j` scaled by `tan psi / mu`
/// with `H = diag(1, mu / tan psi, 1)`, the rocking flow is `a_j`: for tan psi > 0 the return is
/// the closest point to the trial force in the metric of `(D H)^-1` (diagonal, positive), unique
/// on the convex domain. For tan psi = 0, (N, M) is the projection onto the rocking faces in
/// the metric of D^-1 (the Coulomb flow leaves them alone) and T the nearest value in the
/// Coulomb bounds at that N: unique too. The multipliers, which make the history (slip,
/// dilatancy, opening), are unique too except where all four faces meet at the point (c =
/// mu ft, e.g. the apex of a dry joint) with tan psi > 0: there `m_0 + m_1 - tan psi (a_2 +
/// a_3) = 0`, and each 3-face set splits the flow differently; the ordered enumeration chooses
/// there, as without a warm start, and a warm 3-face set is taken only where it is that choice
/// by margins: set 7 or 11 at the apex of a joint without strength (`apex_set`). (With tan psi
/// = 0 the sets with both Coulomb faces are singular and never accepted.)
pub fn return_map(law: &JointLaw, sec: &Section, e: [f64; 3], committed: &JointState, opts: &MapOptions) -> (Response, u8) {
    return_map_inlined(law, sec, e, committed, opts)
}

/// [`return_map`] inlined into the solvers' loops (the interface pass, the tangent's assembly):
/// one copy of the mapping, with its fourteen active sets, in each of them. Callers outside the
/// crate get the one copy in [`return_map`].
#[inline(always)]
pub(crate) fn return_map_inlined(law: &JointLaw, sec: &Section, e: [f64; 3], committed: &JointState, opts: &MapOptions) -> (Response, u8) {
    let MapOptions { prepared: prep, warm, strict, tangent: want_tangent } = *opts;
    let warm_in = warm;
    let d = match prep {
        Some(p) => p.d,
        None => stiffness(law, sec),
    };
    let ep = committed.plastic;
    let trial = [
        d[0] * (e[0] - ep[0]),
        d[1] * (e[1] - ep[1]),
        d[2] * (e[2] - ep[2]),
    ];
    let scale = force_scale(&trial, sec);
    let (broken, faces) = faces_now(law, sec, committed, &trial, scale);
    let tol = kt_tolerance(scale, &faces);
    let elastic_tangent = if want_tangent { [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]] } else { [[0.0; 3]; 3] };
    if (0..4).all(|j| faces.f(j, &trial) <= tol) {
        return (respond(law, sec, committed, &faces, scale, broken, trial, [0.0; 3], [0.0; 2], elastic_tangent), 0);
    }
    // the values on the trial force and the products a_i . D m_j of every face, once: each
    // active set below picks its entries (the same numbers as computing them per set)
    let f_trial: [f64; 4] = [faces.f(0, &trial), faces.f(1, &trial), faces.f(2, &trial), faces.f(3, &trial)];
    let computed;
    let (dm, g_all) = match prep {
        Some(p) => (&p.dm, &p.g_all),
        None => {
            let dm = flow_columns(&faces, &d);
            computed = (dm, face_products(&faces, &dm));
            (&computed.0, &computed.1)
        }
    };
    // the warm set, unless it has three faces and all four faces meet at one point with
    // tan psi > 0 (the multipliers are not unique there: see above)
    let vertex = faces.tp > 0.0 && (faces.b[0] - faces.mu * faces.b[2]).abs() <= 1e-6 * (scale + faces.b[0] + faces.b[2]);
    // ... except a warm set 7 or 11 at the apex of a joint without strength (dry, or broken),
    // taken where it is the ordered enumeration's (see `apex_set`)
    let apex_warm = vertex && faces.b[0] == 0.0 && faces.b[2] == 0.0 && (warm == 7 || warm == 11);
    let warm = if warm.count_ones() == 3 && vertex { 0 } else { warm };
    // the warm set, then the active sets smallest first (the order above), each in its own copy of
    // `attempt` (the faces of a set known at compile time: no index lists, unrolled
    // eliminations); one exit for all, so that `respond` is inlined once for them
    let problem = Trial { faces: &faces, prep, trial: &trial, f_trial: &f_trial, g_all, dm, tol };
    let accepted = active_set(&problem, warm, strict, apex_warm, warm_in);
    if let Some((a, mask)) = accepted {
        let tangent = if want_tangent { set_tangent(mask, &faces, &d, dm, g_all, &a, tol) } else { [[0.0; 3]; 3] };
        return (respond(law, sec, committed, &faces, scale, broken, a.s, a.slip, a.dk, tangent), mask);
    }
    // No active set satisfied the conditions (degenerate data): fall back on the apex, the one
    // point of the domain that every face reaches, carrying nothing beyond the cut-off.
    let n_apex = if faces.a(0)[0] > 0.0 {
        faces.b[2].min(faces.b[0] / faces.a(0)[0])
    } else {
        faces.b[2]
    };
    (respond(law, sec, committed, &faces, scale, broken, [n_apex, 0.0, 0.0], [0.0; 3], [0.0; 2], [[0.0; 3]; 3]), APEX)
}

/// The response of a return (the force, the Coulomb flow `slip`, the plastic (opening, slip)
/// increments `dk`, the tangent) from the committed history, on the step's `faces` (`broken`:
/// whether the joint is broken within the step). A function, not a closure of
/// [`return_map_inlined`], so that it can be inlined (a closure's three calls were not: an
/// out-of-line call per interface and time step).
///
/// Only the Coulomb flow (slip and its dilatancy) is history: an opening or a rocking gap
/// closes again without resistance (no-tension contact), so the rocking faces' flow is not
/// stored. Within a step the mapping, and so its tangent, is the same.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn respond(
    law: &JointLaw,
    sec: &Section,
    committed: &JointState,
    faces: &Faces,
    scale: f64,
    broken: bool,
    force: [f64; 3],
    slip: [f64; 3],
    dk: [f64; 2],
    tangent: [[f64; 3]; 3],
) -> Response {
    let ep = committed.plastic;
    let plastic = [ep[0] + slip[0], ep[1] + slip[1], ep[2] + slip[2]];
    // the opening is recoverable, so dk[0] is the whole current plastic gap: the crack is
    // measured by the largest gap reached; the slip is history, so dk[1] is an increment
    let (opening, slip_acc) = (committed.opening.max(dk[0]), committed.slip + dk[1]);
    let broken = if law.is_softening() {
        let (c, ft) = law.strengths(&JointState { plastic, broken: false, opening, slip: slip_acc });
        c <= 1e-3 * law.cohesion && ft <= 1e-3 * law.tensile_strength
    } else {
        broken
    };
    Response {
        force,
        state: JointState { plastic, broken, opening, slip: slip_acc },
        flags: flags(faces, &force, sec, scale),
        tangent,
    }
}

/// The faces of the domain within this step, and whether the joint is broken: a brittle joint
/// with strength breaks at its first failure (the trial force outside the intact domain) and
/// loses cohesion and tensile strength at once; a softening one keeps the strengths of its
/// committed history within the step.
#[inline(always)]
fn faces_now(law: &JointLaw, sec: &Section, committed: &JointState, trial: &[f64; 3], scale: f64) -> (bool, Faces) {
    let mut broken = committed.broken;
    if law.is_strong() && !broken && !law.is_softening() {
        let intact = Faces::new(law, sec, law.cohesion, law.tensile_strength);
        let tol = 1e-12 * (scale + intact.b[0] + intact.b[2]);
        broken = (0..4).any(|j| intact.f(j, trial) > tol);
    }
    let (c_now, ft_now) = law.strengths(&JointState { broken, ..*committed });
    (broken, Faces::new(law, sec, c_now, ft_now))
}

/// The active set that satisfies the Kuhn-Tucker conditions, and its return: the warm set
/// first (`warm`, already cleared where it may not be taken; `apex_warm`: the set `warm_in` at
/// the apex of a joint without strength), then the sets smallest first, each in its own copy of
/// `attempt` (the faces of a set known at compile time: no index lists, unrolled eliminations).
/// `None`: no set (degenerate data).
#[inline(always)]
fn active_set(problem: &Trial, warm: u8, strict: bool, apex_warm: bool, warm_in: u8) -> Option<(Attempt, u8)> {
    macro_rules! try_set {
        ($mask:literal, $strict:expr) => {
            if let Some(a) = attempt::<$mask>(problem, $strict) {
                return Some((a, $mask));
            }
        };
    }
    macro_rules! warm_sets {
        ($($mask:literal),*) => {
            match warm {
                $($mask => try_set!($mask, strict),)*
                _ => {}
            }
        };
    }
    warm_sets!(1, 2, 4, 8, 3, 5, 6, 9, 10, 12, 7, 11, 13, 14);
    if apex_warm {
        if let Some(a) = apex_return(warm_in, problem) {
            return Some((a, warm_in));
        }
    }
    macro_rules! sets {
        ($($mask:literal),*) => {$(
            if strict || warm != $mask {
                try_set!($mask, false);
            }
        )*};
    }
    // (the warm set, if tried, has failed: it would again, unless it failed only the margins of
    // a strict test)
    sets!(1, 2, 4, 8, 3, 5, 6, 9, 10, 12, 7, 11, 13, 14);
    None
}

/// What every active set's return starts from: the faces of the domain, the prepared
/// constants (if any), the trial force and the faces' values on it, the products
/// `a_i . D m_j` of every pair of faces, the flow columns `D m_j`, and the Kuhn-Tucker test's
/// tolerance.
#[derive(Clone, Copy)]
pub(super) struct Trial<'a> {
    pub(super) faces: &'a Faces,
    pub(super) prep: Option<&'a Prepared>,
    pub(super) trial: &'a [f64; 3],
    pub(super) f_trial: &'a [f64; 4],
    pub(super) g_all: &'a [[f64; 4]; 4],
    pub(super) dm: &'a [[f64; 3]; 4],
    pub(super) tol: f64,
}

/// The return of one active set: the force, the Coulomb flow, the plastic (opening, slip)
/// increments, and for the tangent the set's faces.
pub(super) struct Attempt {
    pub(super) s: [f64; 3],
    pub(super) slip: [f64; 3],
    pub(super) dk: [f64; 2],
    pub(super) act: [usize; 3],
    pub(super) n: usize,
}

/// The return onto the faces of `MASK` (bit j: face j), if it satisfies the Kuhn-Tucker
/// conditions: multipliers >= 0 and every other face satisfied.
#[inline(always)]
pub(super) fn attempt<const MASK: u8>(problem: &Trial, strict: bool) -> Option<Attempt> {
    let Trial { faces, prep, trial, f_trial, g_all, dm, tol } = *problem;
    let mask = MASK;
    if mask.count_ones() == 1 {
        // a single face whose multiplier f_j(trial) / (a_j . D m_j) is negative is rejected
        // below: skip it without the elimination (most plastic updates end on one face or
        // two, so most single faces are skipped)
        let j = mask.trailing_zeros() as usize;
        if f_trial[j] / g_all[j][j] < 0.0 {
            return None;
        }
    }
    let (act_buf, n) = faces_of(mask);
    let act = &act_buf[..n];
    let mut r = [0.0; 3];
    for (p, &i) in act.iter().enumerate() {
        r[p] = f_trial[i];
    }
    let solved = match prep {
        Some(p) => match &p.lu[mask as usize] {
            Some(lu) => {
                lu.apply(&mut r, n);
                true
            }
            None => false,
        },
        None => factor_small(&mut set_matrix(g_all, act), n).map(|lu| lu.apply(&mut r, n)).is_some(),
    };
    if !solved {
        return None;
    }
    let gtol = 1e-12 * r[..n].iter().map(|x| x.abs()).fold(0.0, f64::max);
    if r[..n].iter().any(|&x| x < -gtol) {
        return None;
    }
    // the strict test's margin, in newtons: each multiplier moves its own face's value by at
    // least this much (r_j a_j . D m_j), every other face is at least this far inside
    let margin = STRICT_MARGIN * tol;
    if strict && act.iter().enumerate().any(|(p, &j)| r[p] * g_all[j][j] < margin) {
        return None;
    }
    let mut s = *trial;
    let mut slip = [0.0; 3];
    // plastic opening (cut-off and rocking faces) and slip increment (Coulomb faces)
    let mut dk = [0.0; 2];
    for (p, &j) in act.iter().enumerate() {
        for c in 0..3 {
            s[c] -= r[p] * dm[j][c];
            if j < 2 {
                slip[c] += r[p] * faces.m(j)[c];
            }
        }
        dk[if j < 2 { 1 } else { 0 }] += r[p];
    }
    // every other face satisfied (a plain loop: the test of every face is cheap, and an
    // iterator chain here is not always inlined)
    let limit = if strict { -margin } else { tol };
    let mut violated = false;
    for j in 0..4 {
        violated |= mask & (1 << j) == 0 && faces.f(j, &s) > limit;
    }
    if violated {
        return None;
    }
    Some(Attempt { s, slip, dk, act: act_buf, n })
}

/// Whether the return `a` of set 7 (faces 0, 1, 2) or 11 (faces 0, 1, 3), which passed the
/// Kuhn-Tucker test, is the set that the ordered enumeration accepts, at the apex of a joint
/// without strength (all four faces through the origin, tan psi > 0), so that a warm start
/// may take it at once: the same force, history, flags and tangent.
///
/// There the flow columns `g_j = D m_j` obey `g_0 + g_1 = tan psi (g_2 + g_3)`, and a trial in
/// the cone they span returns to the apex with multipliers that are not unique. The ordered
/// enumeration takes the first set that passes: a single face or a pair only if the trial lies
/// (to the test's tolerance) on a ray `g_j` or in the plane of a pair, else set 7 if the trial
/// lies on the side of g_2 of the plane of `g_0, g_1` (all its multipliers >= 0), else 11. Set
/// 7's or 11's return is that choice when the trial is off every ray and every pair's plane by
/// a margin: each of its three multipliers moves its face's value by [`STRICT_MARGIN`] times
/// the tolerance or more (off the planes of two of its columns, and so off the rays and the
/// planes of a column of the set with the fourth), and so does `r_0 - r_1` (off the plane of
/// `g_2, g_3`, the one left, where `r_0 = r_1`). For set 11 the plane of `g_0, g_1` separates
/// it from set 7, whose multiplier of face 2 is then `-r_3`: set 7 fails, and 11 is the first
/// to pass. A test maps trials generic and next to every ray and plane against the ordered
/// enumeration, bit for bit.
#[inline(always)]
pub(super) fn apex_set(a: &Attempt, g_all: &[[f64; 4]; 4], tol: f64) -> bool {
    let margin = STRICT_MARGIN * tol;
    // the multipliers from the increments: the slip's shear is r_0 - r_1 (m_0, m_1 = (tan psi,
    // +-1, 0)), dk = (r_2 or r_3, r_0 + r_1); to rounding, against margins of 1e6 tolerances
    let (r01, d01, r23) = (a.dk[1], a.slip[1], a.dk[0]);
    let third = a.act[2];
    0.5 * (r01 + d01) * g_all[0][0] >= margin
        && 0.5 * (r01 - d01) * g_all[1][1] >= margin
        && r23 * g_all[third][third] >= margin
        && d01.abs() * g_all[0][0] >= margin
}

/// The return of set 7 or 11 (`set`) at the apex of a joint without strength, if it passes the
/// Kuhn-Tucker test and is the ordered enumeration's choice there ([`apex_set`]).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn apex_return(set: u8, problem: &Trial) -> Option<Attempt> {
    let a = if set == 7 { attempt::<7>(problem, false) } else { attempt::<11>(problem, false) };
    a.filter(|a| apex_set(a, problem.g_all, problem.tol))
}

/// The margins of a strict warm set ([`MapOptions::strict`]), in units of the Kuhn-Tucker
/// test's tolerance (1e-12 of the force's scale).
pub(super) const STRICT_MARGIN: f64 = 1e6;

/// The consistent tangent of the accepted set `mask`.
pub(super) fn set_tangent(
    mask: u8,
    faces: &Faces,
    d: &[f64; 3],
    dm: &[[f64; 3]; 4],
    g_all: &[[f64; 4]; 4],
    a: &Attempt,
    tol: f64,
) -> [[f64; 3]; 3] {
    let s = &a.s;
    // Both faces of a pair active (the rocking pair: N = ft A, M = 0; the Coulomb pair:
    // T = 0, N = c A / mu) with a face of the other pair reached as well: the point is the
    // apex, and this set's region is degenerate (with c = ft = 0 the rocking pair holds only
    // where the trial slip is exactly 0, e.g. a pure opening). Any trial nearby returns to
    // the apex too, so the derivative is the apex's, zero; the set's own tangent would
    // give the free direction (the shear of an open joint) its elastic stiffness.
    // (Without strength, c = ft = 0, either pair is the apex itself: N = 0 leaves M no room, and
    // the other pair's faces are reached up to the rounding of N, which may exceed the tolerance.)
    let pair = |m: u8| mask & m == m;
    let reached = |j: usize| faces.f(j, s) > -tol;
    let strengthless = faces.b[0] == 0.0 && faces.b[2] == 0.0;
    let apex = (pair(0b1100) && (strengthless || reached(0) || reached(1))) || (pair(0b0011) && (strengthless || reached(2) || reached(3)));
    if apex {
        [[0.0; 3]; 3]
    } else {
        let act = &a.act[..a.n];
        active_tangent(faces, d, dm, act, &set_matrix(g_all, act)).unwrap_or([[0.0; 3]; 3])
    }
}

/// The consistent tangent `D - (D M) G^-1 (A D)` of the active faces `act`, with
/// `G = A D M` (k x k in `g`) and `dm` the columns `D m_j`; None if `G` is singular.
pub(super) fn active_tangent(
    faces: &Faces,
    d: &[f64; 3],
    dm: &[[f64; 3]; 4],
    act: &[usize],
    g: &[[f64; 3]; 3],
) -> Option<[[f64; 3]; 3]> {
    let mut tangent = [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]];
    // G factorized once for the three columns (the numbers of eliminating it with each)
    let mut g = *g;
    let lu = factor_small(&mut g, act.len())?;
    for col in 0..3 {
        // G^-1 (A D)[:, col]
        let mut rhs = [0.0; 3];
        for (p, &i) in act.iter().enumerate() {
            rhs[p] = faces.a(i)[col] * d[col];
        }
        lu.apply(&mut rhs, act.len());
        for row in 0..3 {
            for (p, &j) in act.iter().enumerate() {
                tangent[row][col] -= dm[j][row] * rhs[p];
            }
        }
    }
    Some(tangent)
}
