//! The joint law: elastic stiffness, the Mohr-Coulomb / tension cut-off / rocking strength
//! domain in resultants (N, T, M), and its return mapping with the consistent tangent.
//! Both solvers call [`return_map`]; there is no second copy of the law.
//!
//! Convention: N > 0 in tension (opening), T along the interface tangent, M the relative moment.
//! With area `A = l s` and `I = s l^3 / 12`, the strength domain is
//! - Coulomb: `|T| <= c A - mu N`
//! - rocking: `|M| <= (ft A - N) l / 2` (its two faces together give the cut-off `N <= ft A`)
//!
//! i.e. exactly the domain of two contact points at the interface ends. The elastic law is
//! `D = diag(kN A, kT A, kN I)`. Flow: sliding with dilatancy `tan(psi)` (non-associative unless
//! `dilatancy == friction`), rocking associative. A joint with cohesion or tensile strength loses
//! both at its first failure (brittle), and behaves as a dry joint afterwards.
//!
//! History: only the Coulomb flow (slip, and the opening that dilatancy couples to it) is
//! permanent. The flow on the rocking faces (opening, lifting about an edge) is recoverable:
//! a gap closes again without resistance, as at a no-tension contact, so a rocking block can
//! rock back.
//!
//! The return mapping is the exact multi-surface projection `sigma = sigma_trial - D M dgamma`
//! with the active set found by enumeration (Kuhn-Tucker conditions checked: dgamma >= 0, every
//! face satisfied), corners and the apex included. With associative flow it is the closest-point
//! projection in the D-metric. The faces are planes, so within an active set the consistent tangent
//! `D - D M (A D M)^-1 A D` is exact.
//!
//! ```
//! use masonry_dem::joint::{return_map, JointLaw, JointState, Section};
//! let law = JointLaw { friction: 0.6, ..JointLaw::default() };
//! let sec = Section::new(0.4, 1.0);
//! // compressed by a jump of -1e-6 m and slipped by 1e-5 m: the joint slides, |T| = mu |N|
//! let r = return_map(&law, &sec, [-1e-6, 1e-5, 0.0], &JointState::default());
//! assert!((r.force[1].abs() - 0.6 * r.force[0].abs()).abs() < 1e-6 * r.force[0].abs());
//! ```

use crate::error::{non_negative, positive, Error, Result};

/// State flag: the joint is open (at the tension cut-off, carrying nothing beyond ft A).
pub const OPEN: u8 = 1;
/// State flag: the joint is at the Coulomb limit.
pub const SLIDING: u8 = 2;
/// State flag: the joint is at the rocking (moment) limit on one edge.
pub const ROCKING: u8 = 4;

/// Parameters of a joint law (case format `[joints]`), SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointLaw {
    /// kN, normal stiffness per unit area [N/m3].
    pub normal_stiffness: f64,
    /// kT, shear stiffness per unit area [N/m3].
    pub shear_stiffness: f64,
    /// mu = tan(phi) [-].
    pub friction: f64,
    /// c [Pa]; lost at the first failure of the joint.
    pub cohesion: f64,
    /// ft [Pa]; lost at the first failure of the joint.
    pub tensile_strength: f64,
    /// tan(psi) [-], between 0 and `friction`; equal to `friction` means associative flow.
    pub dilatancy: f64,
    /// Mode-I fracture energy G_f^I [N/m]; with `fracture_energy_shear` > 0 the tensile strength
    /// softens as `ft exp(-ft w / G_f^I)` with the accumulated plastic opening w. 0: brittle
    /// (cohesion and tensile strength are lost at the first failure).
    pub fracture_energy_tension: f64,
    /// Mode-II fracture energy G_f^II [N/m]; the cohesion softens as `c exp(-c s / G_f^II)` with
    /// the accumulated plastic slip s. 0: brittle.
    pub fracture_energy_shear: f64,
}

impl Default for JointLaw {
    fn default() -> Self {
        JointLaw {
            normal_stiffness: 1e10,
            shear_stiffness: 1e10,
            friction: 0.65,
            cohesion: 0.0,
            tensile_strength: 0.0,
            dilatancy: 0.0,
            fracture_energy_tension: 0.0,
            fracture_energy_shear: 0.0,
        }
    }
}

/// The range of shear_stiffness / normal_stiffness a joint law may have: the one in which the
/// static and explicit solvers give wall 1's collapse multiplier within 1% in load and
/// displacement control (at 1e3, load control stopped 20% below it, non-associative).
pub const STIFFNESS_RATIO: (f64, f64) = (1e-3, 1e2);

/// The largest friction coefficient accepted (tan(phi) = 20, phi = 87.1 deg): masonry joints have
/// 0.3 to 1, a joint meant not to slide may be given 10, and a number above 20 is most likely a
/// friction angle in degrees (typically 25 to 45).
pub const MAX_FRICTION: f64 = 20.0;

impl JointLaw {
    /// Mortar-joint stiffnesses from the mortar's moduli and the joint thickness: kN = E/e, kT = G/e.
    pub fn mortar_stiffness(self, young: f64, shear: f64, joint_thickness: f64) -> Self {
        JointLaw {
            normal_stiffness: young / joint_thickness,
            shear_stiffness: shear / joint_thickness,
            ..self
        }
    }

    /// Checks every parameter; `what` prefixes the key names (e.g. "joints.bed").
    pub fn validate(&self, what: &str) -> Result<()> {
        positive(&format!("{what}.normal_stiffness"), self.normal_stiffness)?;
        positive(&format!("{what}.shear_stiffness"), self.shear_stiffness)?;
        let ratio = self.shear_stiffness / self.normal_stiffness;
        if !(STIFFNESS_RATIO.0..=STIFFNESS_RATIO.1).contains(&ratio) {
            return Err(Error::input(format!(
                "{what}.shear_stiffness / normal_stiffness = {ratio:.3e} is outside {:e} .. {:e}, the range in which the solvers give the collapse load of the reference walls (Ferris & Tin-Loi wall 1 at kT/kN = 1e3: 20% low); masonry joints have kT/kN of about 0.1 to 1",
                STIFFNESS_RATIO.0, STIFFNESS_RATIO.1
            )));
        }
        non_negative(&format!("{what}.friction"), self.friction)?;
        if self.friction > MAX_FRICTION {
            // most likely a friction angle in degrees
            let hint = if self.friction < 90.0 {
                format!("; a friction angle of {} deg is friction = {:.3}", self.friction, self.friction.to_radians().tan())
            } else {
                String::new()
            };
            return Err(Error::input(format!(
                "{what}.friction = {} is mu = tan(phi), a coefficient, and must be at most {MAX_FRICTION} (phi = {:.1} deg){hint}",
                self.friction,
                MAX_FRICTION.atan().to_degrees()
            )));
        }
        non_negative(&format!("{what}.cohesion"), self.cohesion)?;
        non_negative(&format!("{what}.tensile_strength"), self.tensile_strength)?;
        non_negative(&format!("{what}.dilatancy"), self.dilatancy)?;
        non_negative(&format!("{what}.fracture_energy_tension"), self.fracture_energy_tension)?;
        non_negative(&format!("{what}.fracture_energy_shear"), self.fracture_energy_shear)?;
        if (self.fracture_energy_tension > 0.0) != (self.fracture_energy_shear > 0.0) {
            return Err(Error::input(format!(
                "{what}.fracture_energy_tension and {what}.fracture_energy_shear must both be 0 (brittle joints) or both > 0 (softening), got {} and {}",
                self.fracture_energy_tension, self.fracture_energy_shear
            )));
        }
        if self.dilatancy > self.friction * (1.0 + 1e-12) {
            return Err(Error::input(format!(
                "{what}.dilatancy = {} exceeds {what}.friction = {}: tan(psi) must lie between 0 and tan(phi)",
                self.dilatancy, self.friction
            )));
        }
        Ok(())
    }

    /// Whether the joint has strength to lose (cohesion or tensile strength).
    pub fn is_strong(&self) -> bool {
        self.cohesion > 0.0 || self.tensile_strength > 0.0
    }

    /// Whether cohesion and tensile strength soften with the fracture energies.
    pub fn is_softening(&self) -> bool {
        self.is_strong() && self.fracture_energy_tension > 0.0 && self.fracture_energy_shear > 0.0
    }

    /// Current (cohesion [Pa], tensile strength [Pa]) of a joint with history `state`.
    pub fn strengths(&self, state: &JointState) -> (f64, f64) {
        if !self.is_strong() || (state.broken && !self.is_softening()) {
            (0.0, 0.0)
        } else if self.is_softening() {
            let c = self.cohesion * (-self.cohesion * state.slip / self.fracture_energy_shear).exp();
            let ft = self.tensile_strength * (-self.tensile_strength * state.opening / self.fracture_energy_tension).exp();
            (c, ft)
        } else {
            (self.cohesion, self.tensile_strength)
        }
    }
}

/// Geometric properties of an interface section.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// A = l s [m2]
    pub area: f64,
    /// I = s l^3 / 12 [m4]
    pub inertia: f64,
    /// l [m]
    pub length: f64,
}

impl Section {
    /// The section of an interface of length `l` in a wall of thickness `s`.
    pub fn new(length: f64, thickness: f64) -> Self {
        Section {
            area: length * thickness,
            inertia: thickness * length.powi(3) / 12.0,
            length,
        }
    }
}

/// History variables of one interface.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct JointState {
    /// Plastic jumps (dN, dT, dphi).
    pub plastic: [f64; 3],
    /// The joint has lost its cohesion and tensile strength (at its first failure if brittle;
    /// once both have softened below 0.1% of their initial values otherwise).
    pub broken: bool,
    /// Largest plastic opening (gap) reached on the cut-off and rocking faces [m] (drives the
    /// softening of the tensile strength).
    pub opening: f64,
    /// Accumulated plastic slip [m] (drives softening).
    pub slip: f64,
}

/// What the return mapping gives back.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Response {
    /// (N [N], T [N], M [N m])
    pub force: [f64; 3],
    /// The updated history (to be committed once the step has converged).
    pub state: JointState,
    /// OPEN | SLIDING | ROCKING bits, 0 when elastic.
    pub flags: u8,
    /// d force / d jumps (row-major), consistent with the mapping.
    pub tangent: [[f64; 3]; 3],
}

/// The four faces of the domain, each `a . sigma <= b`, with flow direction `m`.
/// Order: Coulomb +T, Coulomb -T, rocking +M, rocking -M (rocking faces divided by l/2).
/// The rows `a` and `m` are formed where they are used, not stored: the elastic check, the
/// common case, reads only `a` and `b`.
struct Faces {
    /// mu, tan(psi), 2 / l
    mu: f64,
    tp: f64,
    k: f64,
    b: [f64; 4],
}

impl Faces {
    /// The faces with cohesion `c` and tensile strength `ft` [Pa].
    #[inline(always)]
    fn new(law: &JointLaw, sec: &Section, c: f64, ft: f64) -> Self {
        let b = [c * sec.area, c * sec.area, ft * sec.area, ft * sec.area];
        Faces { mu: law.friction, tp: law.dilatancy, k: 2.0 / sec.length, b }
    }
    /// The normal of face `j`.
    #[inline(always)]
    fn a(&self, j: usize) -> [f64; 3] {
        match j {
            0 => [self.mu, 1.0, 0.0],
            1 => [self.mu, -1.0, 0.0],
            2 => [1.0, 0.0, self.k],
            _ => [1.0, 0.0, -self.k],
        }
    }
    /// The flow direction of face `j`.
    #[inline(always)]
    fn m(&self, j: usize) -> [f64; 3] {
        match j {
            0 => [self.tp, 1.0, 0.0],
            1 => [self.tp, -1.0, 0.0],
            _ => self.a(j),
        }
    }
    #[inline(always)]
    fn f(&self, j: usize, s: &[f64; 3]) -> f64 {
        dot(&self.a(j), s) - self.b[j]
    }
}

#[inline]
fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

// Active sets tried, smallest first: single faces, then edges, then corners
// (1, 2, 4, 8, 3, 5, 6, 9, 10, 12, 7, 11, 13, 14; bit j: face j), in `map`.

/// The factors of the leading k x k block of `g` (k <= 3, overwritten), None if it is
/// singular relative to its scale ([`factor_k`]).
#[inline(always)]
fn factor_small(g: &mut [[f64; 3]; 3], k: usize) -> Option<Lu> {
    // one unrolled copy per size: the return mapping eliminates up to 14 sets per plastic update
    match k {
        1 => factor_k::<1>(g),
        2 => factor_k::<2>(g),
        3 => factor_k::<3>(g),
        _ => unreachable!("at most 3 active faces"),
    }
}

/// The factors of a k x k system (k <= 3) by Gaussian elimination with partial pivoting: the
/// row swapped into place at each column, the multipliers, and the eliminated matrix (U on and
/// above its diagonal). Solving with them ([`Lu::apply_k`]) does to the right-hand side the
/// operations of the elimination in their order: the same numbers as eliminating both at once.
#[derive(Debug, Clone, Copy, Default)]
struct Lu {
    piv: [u8; 3],
    l: [[f64; 3]; 3],
    u: [[f64; 3]; 3],
}

/// The factors of the leading K x K block of `g` (overwritten), None if it is singular
/// relative to its scale.
#[inline(always)]
fn factor_k<const K: usize>(g: &mut [[f64; 3]; 3]) -> Option<Lu> {
    let mut scale: f64 = 0.0;
    for row in g.iter().take(K) {
        for x in row.iter().take(K) {
            scale = scale.max(x.abs());
        }
    }
    if scale == 0.0 {
        return None;
    }
    let mut lu = Lu::default();
    for col in 0..K {
        // the last row of largest magnitude, as `Iterator::max_by` picks it
        let mut p = col;
        for x in col + 1..K {
            if g[p][col].abs().total_cmp(&g[x][col].abs()) != std::cmp::Ordering::Greater {
                p = x;
            }
        }
        if g[p][col].abs() <= 1e-12 * scale {
            return None;
        }
        g.swap(col, p);
        lu.piv[col] = p as u8;
        for row in col + 1..K {
            let f = g[row][col] / g[col][col];
            let pivot_row = g[col];
            for (x, p) in g[row][col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= f * p;
            }
            lu.l[row][col] = f;
        }
    }
    lu.u = *g;
    Some(lu)
}

impl Lu {
    /// Solves in place with the factors of a K x K system.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // the indices of the elimination in `factor_k`
    fn apply_k<const K: usize>(&self, r: &mut [f64; 3]) {
        for col in 0..K {
            r.swap(col, self.piv[col] as usize);
            for row in col + 1..K {
                r[row] -= self.l[row][col] * r[col];
            }
        }
        for col in (0..K).rev() {
            let mut s = r[col];
            for c2 in col + 1..K {
                s -= self.u[col][c2] * r[c2];
            }
            r[col] = s / self.u[col][col];
        }
    }

    /// [`Lu::apply_k`] for a system of size `k`.
    #[inline(always)]
    fn apply(&self, r: &mut [f64; 3], k: usize) {
        match k {
            1 => self.apply_k::<1>(r),
            2 => self.apply_k::<2>(r),
            3 => self.apply_k::<3>(r),
            _ => unreachable!("at most 3 active faces"),
        }
    }
}

/// What the return mapping of one law on one section computes before it looks at the jumps and
/// the history: the elastic stiffnesses D, the columns D m_j, the products a_i . D m_j, and the
/// factors of every active set's system (None where it is singular). A solver that maps many
/// joints of few kinds builds one per kind ([`Prepared::new`]) and passes it to
/// [`return_map_forces_prepared`]: the same numbers, computed once.
#[derive(Debug, Clone)]
pub struct Prepared {
    d: [f64; 3],
    dm: [[f64; 3]; 4],
    g_all: [[f64; 4]; 4],
    /// by active set (bit j: face j)
    lu: [Option<Lu>; 16],
}

impl Prepared {
    /// The constants of `law` on `sec` (the faces' normals and flow do not depend on the
    /// strengths, which a history may soften).
    pub fn new(law: &JointLaw, sec: &Section) -> Self {
        let faces = Faces::new(law, sec, 0.0, 0.0);
        let d = stiffness(law, sec);
        let dm = flow_columns(&faces, &d);
        let g_all = face_products(&faces, &dm);
        let mut lu = [None; 16];
        for (mask, lu) in lu.iter_mut().enumerate().skip(1) {
            let mask = mask as u8;
            if mask.count_ones() <= 3 {
                let (act, n) = faces_of(mask);
                let mut g = set_matrix(&g_all, &act[..n]);
                *lu = factor_small(&mut g, n);
            }
        }
        Prepared { d, dm, g_all, lu }
    }
}

/// The kinds of many joints: the distinct pairs of law and section, each with its
/// [`Prepared`] constants, and the kind of each joint. A wall of equal blocks has a handful of
/// kinds however many joints it has.
#[derive(Debug, Clone, Default)]
pub struct Kinds {
    table: Vec<(Section, Prepared)>,
    of: Vec<u16>,
}

impl Kinds {
    /// The kind of a joint whose pair did not fit in the table: mapped without prepared
    /// constants (the same numbers, computed per mapping).
    pub const NONE: u16 = u16::MAX;

    /// The solvers' size of the table: 256 kinds, 0.7 MB at most.
    pub const MAX: usize = 256;

    /// The kinds of `joints`, each given as (an identifier of its law, the law, its section):
    /// equal identifiers must mean equal laws, sections are compared bit for bit. At most `max`
    /// kinds (each 2.6 kB) are kept, at most 65,535.
    pub fn new<'a>(joints: impl IntoIterator<Item = (u8, &'a JointLaw, &'a Section)>, max: usize) -> Self {
        let max = max.min(Self::NONE as usize);
        let (mut table, mut of, mut index) = (vec![], vec![], std::collections::HashMap::new());
        for (id, law, sec) in joints {
            let key = (id, [sec.area.to_bits(), sec.inertia.to_bits(), sec.length.to_bits()]);
            of.push(match index.get(&key) {
                Some(&i) => i,
                None if table.len() < max => {
                    table.push((*sec, Prepared::new(law, sec)));
                    index.insert(key, (table.len() - 1) as u16);
                    (table.len() - 1) as u16
                }
                None => Self::NONE,
            });
        }
        Kinds { table, of }
    }

    /// The kind of joint `k` ([`Kinds::NONE`] if not in the table).
    pub fn kind(&self, k: usize) -> u16 {
        self.of[k]
    }

    /// The section and constants of a kind, if it is in the table.
    pub fn get(&self, kind: u16) -> Option<&(Section, Prepared)> {
        self.table.get(kind as usize)
    }

    /// The prepared constants of joint `k`, if its kind is in the table.
    pub fn prepared(&self, k: usize) -> Option<&Prepared> {
        self.get(self.of[k]).map(|(_, p)| p)
    }

    /// The number of kinds in the table.
    pub fn len(&self) -> usize {
        self.table.len()
    }

    /// Whether the table is empty.
    pub fn is_empty(&self) -> bool {
        self.table.is_empty()
    }
}

/// D = diag(kN A, kT A, kN I).
#[inline(always)]
fn stiffness(law: &JointLaw, sec: &Section) -> [f64; 3] {
    [law.normal_stiffness * sec.area, law.shear_stiffness * sec.area, law.normal_stiffness * sec.inertia]
}

/// D m_j for every face
/// (array literals rather than `std::array::from_fn`, whose closure is not always inlined).
#[inline(always)]
fn flow_columns(faces: &Faces, d: &[f64; 3]) -> [[f64; 3]; 4] {
    let dmj = |j: usize| [d[0] * faces.m(j)[0], d[1] * faces.m(j)[1], d[2] * faces.m(j)[2]];
    [dmj(0), dmj(1), dmj(2), dmj(3)]
}

/// The products a_i . D m_j of every pair of faces.
#[inline(always)]
fn face_products(faces: &Faces, dm: &[[f64; 3]; 4]) -> [[f64; 4]; 4] {
    let g_row = |i: usize| {
        let a = faces.a(i);
        [dot(&a, &dm[0]), dot(&a, &dm[1]), dot(&a, &dm[2]), dot(&a, &dm[3])]
    };
    [g_row(0), g_row(1), g_row(2), g_row(3)]
}

/// The faces of an active set, in increasing order, and their number.
#[inline(always)]
fn faces_of(mask: u8) -> ([usize; 3], usize) {
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
fn set_matrix(g_all: &[[f64; 4]; 4], act: &[usize]) -> [[f64; 3]; 3] {
    let mut g = [[0.0; 3]; 3];
    for (p, &i) in act.iter().enumerate() {
        for (q, &j) in act.iter().enumerate() {
            g[p][q] = g_all[i][j];
        }
    }
    g
}

/// The return mapping: forces, updated history, state flags and consistent tangent for the total
/// jumps `e`, starting from the committed history `committed`.
pub fn return_map(law: &JointLaw, sec: &Section, e: [f64; 3], committed: &JointState) -> Response {
    return_map_with(law, sec, e, committed, MapOptions::default()).0
}

/// How [`return_map_with`] maps. The default is [`return_map`]'s: no prepared constants, no
/// warm set, the tangent.
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
    /// are those of [`return_map`] bit for bit. Without it the warm set is taken on the ordered
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

/// The set that [`return_map_with`] reports where no active set satisfies the Kuhn-Tucker
/// conditions (degenerate data) and the force is put at the apex of the domain.
pub const APEX: u8 = 0x10;

/// The same return mapping as [`return_map`] without its consistent tangent
/// (`Response::tangent` is left zero): for the explicit solver, which needs the forces only.
/// Forces, history and flags are those of [`return_map`], bit for bit.
#[inline]
pub fn return_map_forces(law: &JointLaw, sec: &Section, e: [f64; 3], committed: &JointState) -> Response {
    return_map_with(law, sec, e, committed, MapOptions { tangent: false, ..MapOptions::default() }).0
}

/// [`return_map_forces`] trying the active set `warm` first (bit j: face j; 0: none), e.g.
/// the one this joint ended on at the previous time step; also gives the active set accepted
/// (0 if the update is elastic, [`APEX`] if no set was). The warm set is accepted on the same
/// Kuhn-Tucker test as in the ordered enumeration, which follows if it fails. The force and
/// history are those of [`return_map_forces`] up to rounding: the Kuhn-Tucker point is unique
/// (see [`return_map_with`]).
#[inline]
pub fn return_map_forces_warm(law: &JointLaw, sec: &Section, e: [f64; 3], committed: &JointState, warm: u8) -> (Response, u8) {
    return_map_with(law, sec, e, committed, MapOptions { warm, tangent: false, ..MapOptions::default() })
}

/// [`return_map_forces_warm`] with the constants of `law` on `sec` computed beforehand
/// (`prep` must be `Prepared::new(law, sec)`): the same forces, history, flags and set, bit for
/// bit.
#[inline]
pub fn return_map_forces_prepared(
    law: &JointLaw,
    sec: &Section,
    prep: &Prepared,
    e: [f64; 3],
    committed: &JointState,
    warm: u8,
) -> (Response, u8) {
    return_map_with(law, sec, e, committed, MapOptions { prepared: Some(prep), warm, strict: false, tangent: false })
}

/// The return mapping with [`MapOptions`]: with its tangent if asked, trying the active set
/// `warm` first if not 0, with the prepared constants if given (computed here otherwise); also
/// the active set accepted (bit j: face j; 0: the update is elastic and the tangent D;
/// [`APEX`]: no set, the apex).
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
#[inline(always)]
pub fn return_map_with(law: &JointLaw, sec: &Section, e: [f64; 3], committed: &JointState, opts: MapOptions) -> (Response, u8) {
    let MapOptions { prepared: prep, warm, strict, tangent: want_tangent } = opts;
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
    let mut broken = committed.broken;
    let softening = law.is_softening();
    if law.is_strong() && !broken && !softening {
        // brittle: the first failure takes cohesion and tensile strength at once
        let intact = Faces::new(law, sec, law.cohesion, law.tensile_strength);
        let tol = 1e-12 * (scale + intact.b[0] + intact.b[2]);
        broken = (0..4).any(|j| intact.f(j, &trial) > tol);
    }
    // softening: the strengths of the committed history hold within the step
    let (c_now, ft_now) = law.strengths(&JointState { broken, ..*committed });
    let faces = Faces::new(law, sec, c_now, ft_now);
    let tol = kt_tolerance(scale, &faces);
    let elastic_tangent = if want_tangent { [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]] } else { [[0.0; 3]; 3] };
    // Only the Coulomb flow (slip and its dilatancy) is history: an opening or a rocking gap
    // closes again without resistance (no-tension contact), so the rocking faces' flow is not
    // stored. Within a step the mapping, and so its tangent, is the same.
    let finish = |force: [f64; 3], slip: [f64; 3], dk: [f64; 2], tangent: [[f64; 3]; 3]| -> Response {
        let plastic = [ep[0] + slip[0], ep[1] + slip[1], ep[2] + slip[2]];
        // the opening is recoverable, so dk[0] is the whole current plastic gap: the crack is
        // measured by the largest gap reached; the slip is history, so dk[1] is an increment
        let (opening, slip_acc) = (committed.opening.max(dk[0]), committed.slip + dk[1]);
        let broken = if softening {
            let (c, ft) = law.strengths(&JointState { plastic, broken: false, opening, slip: slip_acc });
            c <= 1e-3 * law.cohesion && ft <= 1e-3 * law.tensile_strength
        } else {
            broken
        };
        Response {
            force,
            state: JointState { plastic, broken, opening, slip: slip_acc },
            flags: flags(&faces, &force, sec, scale),
            tangent,
        }
    };
    if (0..4).all(|j| faces.f(j, &trial) <= tol) {
        return (finish(trial, [0.0; 3], [0.0; 2], elastic_tangent), 0);
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
    // eliminations); one exit for all, so that `finish` is inlined once
    let accepted = 'found: {
        macro_rules! try_set {
            ($mask:literal, $strict:expr) => {
                if let Some(a) = attempt::<$mask>(&faces, prep, &trial, &f_trial, g_all, dm, tol, $strict) {
                    break 'found Some((a, $mask));
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
            if let Some(a) = apex_return(warm_in, &faces, prep, &trial, &f_trial, g_all, dm, tol) {
                break 'found Some((a, warm_in));
            }
        }
        macro_rules! sets {
            ($($mask:literal),*) => {$(
                if strict || warm != $mask {
                    try_set!($mask, false);
                }
            )*};
        }
        // (the warm set, if tried, has failed: it would again, unless it failed only the
        // margins of a strict test)
        sets!(1, 2, 4, 8, 3, 5, 6, 9, 10, 12, 7, 11, 13, 14);
        None
    };
    if let Some((a, mask)) = accepted {
        let tangent = if want_tangent { set_tangent(mask, &faces, &d, dm, g_all, &a, tol) } else { [[0.0; 3]; 3] };
        return (finish(a.s, a.slip, a.dk, tangent), mask);
    }
    // No active set satisfied the conditions (degenerate data): fall back on the apex, the one
    // point of the domain that every face reaches, carrying nothing beyond the cut-off.
    let n_apex = if faces.a(0)[0] > 0.0 {
        faces.b[2].min(faces.b[0] / faces.a(0)[0])
    } else {
        faces.b[2]
    };
    (finish([n_apex, 0.0, 0.0], [0.0; 3], [0.0; 2], [[0.0; 3]; 3]), APEX)
}

/// The size of a trial force (N, T, M) in newtons, the moment as its rocking faces see it
/// (2 |M| / l).
#[inline(always)]
fn force_scale(trial: &[f64; 3], sec: &Section) -> f64 {
    trial[0].abs() + trial[1].abs() + (trial[2] * (2.0 / sec.length)).abs()
}

/// The tolerance of the Kuhn-Tucker tests of a trial of size `scale` on `faces`.
#[inline(always)]
fn kt_tolerance(scale: f64, faces: &Faces) -> f64 {
    1e-12 * (scale + faces.b[0] + faces.b[2]) + f64::MIN_POSITIVE
}

/// The elastic tangent D = diag(kN A, kT A, kN I) of `law` on `sec`: the tangent of an update
/// that [`return_map_with`] reports elastic (set 0), the same numbers.
pub fn elastic_tangent(law: &JointLaw, sec: &Section) -> [[f64; 3]; 3] {
    let d = stiffness(law, sec);
    [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]]
}

/// The return of one active set: the force, the Coulomb flow, the plastic (opening, slip)
/// increments, and for the tangent the set's faces.
struct Attempt {
    s: [f64; 3],
    slip: [f64; 3],
    dk: [f64; 2],
    act: [usize; 3],
    n: usize,
}

/// The return onto the faces of `MASK` (bit j: face j), if it satisfies the Kuhn-Tucker
/// conditions: multipliers >= 0 and every other face satisfied.
#[inline(always)]
#[allow(clippy::too_many_arguments)] // the constants of the mapping, passed as they are
fn attempt<const MASK: u8>(
    faces: &Faces,
    prep: Option<&Prepared>,
    trial: &[f64; 3],
    f_trial: &[f64; 4],
    g_all: &[[f64; 4]; 4],
    dm: &[[f64; 3]; 4],
    tol: f64,
    strict: bool,
) -> Option<Attempt> {
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
fn apex_set(a: &Attempt, g_all: &[[f64; 4]; 4], tol: f64) -> bool {
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
fn apex_return(
    set: u8,
    faces: &Faces,
    prep: Option<&Prepared>,
    trial: &[f64; 3],
    f_trial: &[f64; 4],
    g_all: &[[f64; 4]; 4],
    dm: &[[f64; 3]; 4],
    tol: f64,
) -> Option<Attempt> {
    let a = if set == 7 {
        attempt::<7>(faces, prep, trial, f_trial, g_all, dm, tol, false)
    } else {
        attempt::<11>(faces, prep, trial, f_trial, g_all, dm, tol, false)
    };
    a.filter(|a| apex_set(a, g_all, tol))
}

/// The margins of a strict warm set ([`MapOptions::strict`]), in units of the Kuhn-Tucker
/// test's tolerance (1e-12 of the force's scale).
const STRICT_MARGIN: f64 = 1e6;

/// The consistent tangent of the accepted set `mask`.
fn set_tangent(
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
    let pair = |m: u8| mask & m == m;
    let reached = |j: usize| faces.f(j, s) > -tol;
    let apex = (pair(0b1100) && (reached(0) || reached(1))) || (pair(0b0011) && (reached(2) || reached(3)));
    if apex {
        [[0.0; 3]; 3]
    } else {
        let act = &a.act[..a.n];
        active_tangent(faces, d, dm, act, &set_matrix(g_all, act)).unwrap_or([[0.0; 3]; 3])
    }
}

/// The consistent tangent `D - (D M) G^-1 (A D)` of the active faces `act`, with
/// `G = A D M` (k x k in `g`) and `dm` the columns `D m_j`; None if `G` is singular.
fn active_tangent(
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

/// The OPEN | SLIDING | ROCKING bits of a returned force `s`, from the trial of size
/// `trial_scale` ([`force_scale`]). A face counts as reached within 0.1% of the force's size: a
/// relaxed explicit state and a Newton-converged static state of the same collapse are then
/// classified alike. And within 1e-9 of the trial's: a joint without strength returned to its
/// apex carries nothing but rounding (some 1e-17 of the trial), whose signs would otherwise read
/// as sliding or rocking instead of open.
fn flags(faces: &Faces, s: &[f64; 3], sec: &Section, trial_scale: f64) -> u8 {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// [`return_map_with`], one copy for all the tests: inlined at each of their call sites (it
    /// is `inline(always)`), it made this module's test build take over nine minutes.
    #[inline(never)]
    fn map(law: &JointLaw, sec: &Section, e: [f64; 3], committed: &JointState, opts: MapOptions) -> (Response, u8) {
        return_map_with(law, sec, e, committed, opts)
    }

    /// A tiny xorshift generator: the same numbers on every run.
    fn rng(seed: u64) -> impl FnMut() -> f64 {
        let mut x = seed;
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        }
    }

    /// The laws of the mapping tests: dry, associative, dilatant, brittle, softening, with all
    /// four faces meeting at one point (c = mu ft), and with a stiffer shear.
    fn laws() -> [JointLaw; 7] {
        let base = JointLaw { friction: 0.65, ..JointLaw::default() };
        [
            base,
            JointLaw { dilatancy: 0.65, ..base },
            JointLaw { dilatancy: 0.3, ..base },
            JointLaw { cohesion: 2e4, tensile_strength: 1e4, dilatancy: 0.2, ..base },
            JointLaw { cohesion: 2e4, tensile_strength: 1e4, fracture_energy_tension: 10.0, fracture_energy_shear: 50.0, ..base },
            JointLaw { cohesion: 0.65e4, tensile_strength: 1e4, dilatancy: 0.65, ..base },
            JointLaw { shear_stiffness: 4e9, dilatancy: 0.4, ..base },
        ]
    }

    /// Random jumps of up to 1e-5 m (forces up to about 4e4 N against strengths of 4e3 to
    /// 8e3 N), some components zero, and a random plastic history.
    fn random_case(r: &mut impl FnMut() -> f64) -> ([f64; 3], JointState) {
        let mut e = [1e-5 * r(), 1e-5 * r(), 5e-5 * r()];
        for x in e.iter_mut() {
            if r() > 0.8 {
                *x = 0.0;
            }
        }
        (e, JointState { plastic: [1e-6 * r(), 1e-6 * r(), 0.0], ..JointState::default() })
    }

    #[test]
    fn a_warm_start_and_prepared_constants_give_the_force_and_history_of_the_ordered_enumeration() {
        let (laws, sec) = (laws(), Section::new(0.4, 1.0));
        let mut r = rng(7);
        let mut worst: [f64; 3] = [0.0; 3];
        for law in &laws {
            let prep = Prepared::new(law, &sec);
            for _ in 0..20000 {
                let (e, committed) = random_case(&mut r);
                let forces = MapOptions { tangent: false, ..MapOptions::default() };
                let (cold, set) = map(law, &sec, e, &committed, forces);
                let scale = cold.force[0].abs() + cold.force[1].abs() + cold.force[2].abs() * 5.0 + 1.0;
                for warm in 1..15u8 {
                    let (w, wset) = map(law, &sec, e, &committed, MapOptions { warm, ..forces });
                    // the prepared constants change nothing, bit for bit
                    let (wp, wpset) = return_map_forces_prepared(law, &sec, &prep, e, &committed, warm);
                    assert_eq!((wp.force.map(f64::to_bits), wp.state.plastic.map(f64::to_bits)), (w.force.map(f64::to_bits), w.state.plastic.map(f64::to_bits)));
                    assert_eq!((wp.state.opening.to_bits(), wp.state.slip.to_bits(), wp.state.broken, wp.flags, wpset), (w.state.opening.to_bits(), w.state.slip.to_bits(), w.state.broken, w.flags, wset));
                    let df = (0..3).map(|c| (w.force[c] - cold.force[c]).abs()).fold(0.0, f64::max) / scale;
                    let dp = (0..3).map(|c| (w.state.plastic[c] - cold.state.plastic[c]).abs()).fold(0.0, f64::max) / 1e-5;
                    let dk = ((w.state.opening - cold.state.opening).abs() + (w.state.slip - cold.state.slip).abs()) / 1e-5;
                    worst = [worst[0].max(df), worst[1].max(dp), worst[2].max(dk)];
                    if df > 1e-9 || dp > 1e-9 || dk > 1e-9 {
                        panic!("{law:?} e {e:?}: warm {warm} set {wset} {w:?} against set {set} {cold:?}");
                    }
                }
            }
        }
        println!("worst relative differences: force {:e} plastic {:e} opening/slip {:e}", worst[0], worst[1], worst[2]);
    }

    /// The bits of everything a mapping gives: force, history, flags, tangent and set.
    fn bits(r: &Response, set: u8) -> Vec<u64> {
        let mut v: Vec<u64> = r.force.iter().chain(&r.state.plastic).chain(r.tangent.iter().flatten()).map(|x| x.to_bits()).collect();
        v.extend([r.state.opening.to_bits(), r.state.slip.to_bits(), r.state.broken as u64, r.flags as u64, set as u64]);
        v
    }

    #[test]
    fn a_strict_warm_set_with_prepared_constants_gives_the_ordered_enumerations_bits_tangent_included() {
        let (laws, sec) = (laws(), Section::new(0.4, 1.0));
        let mut r = rng(11);
        for law in &laws {
            let kinds = Kinds::new([(0, law, &sec)], 1);
            let prep = kinds.prepared(0).unwrap();
            for _ in 0..20000 {
                let (e, committed) = random_case(&mut r);
                let (cold, set) = map(law, &sec, e, &committed, MapOptions::default());
                assert_eq!(bits(&cold, set), bits(&return_map(law, &sec, e, &committed), set));
                if set == 0 {
                    assert_eq!(elastic_tangent(law, &sec), cold.tangent);
                }
                for warm in 0..15u8 {
                    for prepared in [None, Some(prep)] {
                        let opts = MapOptions { prepared, warm, strict: true, tangent: true };
                        let (w, wset) = map(law, &sec, e, &committed, opts);
                        assert_eq!(bits(&w, wset), bits(&cold, set), "{law:?} e {e:?} warm {warm}");
                        // without the tangent: the same force, history, flags and set
                        let (f, fset) = map(law, &sec, e, &committed, MapOptions { tangent: false, ..opts });
                        assert_eq!(bits(&Response { tangent: cold.tangent, ..f }, fset), bits(&cold, set));
                    }
                    // the set found, given back as the warm set without margins, is taken again
                    if warm == set && set != 0 {
                        let (w, wset) = map(law, &sec, e, &committed, MapOptions { warm, ..MapOptions::default() });
                        assert_eq!(bits(&w, wset), bits(&cold, set));
                    }
                }
            }
        }
    }

    /// At the apex of a dry joint (tan psi > 0) the multipliers are not unique, and a warm set 7
    /// or 11 is taken only where it is the ordered enumeration's choice (`apex_set`): trials in
    /// the cone of the flow columns, generic and next to its rays, its faces and the planes of
    /// its pairs (down to 1e-15 of the trial), mapped with every warm set, strict or not, with
    /// and without prepared constants: the bits of the ordered enumeration, tangent included.
    #[test]
    fn a_warm_set_at_the_apex_is_taken_only_where_the_ordered_enumeration_takes_it() {
        let sec = Section::new(0.4, 1.0);
        let mut r = rng(23);
        let mut taken = 0;
        let mut total = 0;
        // the dry dilatant laws, and two with flow columns nearer each other: a small dilatancy
        // and a soft shear
        let base = JointLaw { friction: 0.65, ..JointLaw::default() };
        let extra = [JointLaw { dilatancy: 0.02, ..base }, JointLaw { dilatancy: 0.65, shear_stiffness: 1e7, ..base }];
        for law in laws().iter().filter(|l| l.dilatancy > 0.0 && !l.is_strong()).chain(&extra) {
            let prep = Prepared::new(law, &sec);
            let faces = Faces::new(law, &sec, 0.0, 0.0);
            let d = stiffness(law, &sec);
            for i in 0..20000 {
                // multipliers of the four flow columns: random, some near zero, some pairs near
                // equal (on the plane of g_2, g_3 where r_0 = r_1 in set 7's terms)
                let mut lam = [r().abs(), r().abs(), r().abs(), r().abs()];
                let tiny = [0.0, 1e-15, 1e-12, 1e-9, 1e-6, 1e-3][i % 6];
                match (i / 6) % 5 {
                    0 => {}
                    1 => lam[(i / 30) % 4] = tiny * r().abs(),
                    2 => {
                        lam[(i / 30) % 4] = tiny * r().abs();
                        lam[(i / 120) % 4] = tiny * r().abs();
                    }
                    3 => lam[1] = lam[0] * (1.0 + tiny * r()),
                    _ => {
                        lam[3] = tiny * r().abs();
                        lam[1] = lam[0] * (1.0 + tiny * r());
                    }
                }
                let t: [f64; 3] = std::array::from_fn(|c| (0..4).map(|j| 1e-6 * lam[j] * d[c] * faces.m(j)[c]).sum());
                let committed = JointState { plastic: [1e-6 * r(), 1e-6 * r(), 0.0], ..JointState::default() };
                let e: [f64; 3] = std::array::from_fn(|c| t[c] / d[c] + committed.plastic[c]);
                let (cold, set) = map(law, &sec, e, &committed, MapOptions::default());
                for warm in [7u8, 11, 13, 14, 3, 12, set] {
                    for strict in [false, true] {
                        for prepared in [None, Some(&prep)] {
                            let opts = MapOptions { prepared, warm, strict, tangent: true };
                            let (w, wset) = map(law, &sec, e, &committed, opts);
                            assert_eq!(bits(&w, wset), bits(&cold, set), "{law:?} lam {lam:?} warm {warm} strict {strict}");
                        }
                    }
                }
                // how often the shortcut is taken
                if set == 7 || set == 11 {
                    total += 1;
                    let tr: [f64; 3] = std::array::from_fn(|c| d[c] * (e[c] - committed.plastic[c]));
                    let tol = kt_tolerance(force_scale(&tr, &sec), &faces);
                    let ft: [f64; 4] = std::array::from_fn(|j| faces.f(j, &tr));
                    taken += apex_return(set, &faces, Some(&prep), &tr, &ft, &prep.g_all, &prep.dm, tol).is_some() as usize;
                }
            }
        }
        // the generic fifth of the cases at least
        assert!(taken * 5 > total, "the shortcut taken in {taken} of {total} returns to the apex");
        println!("shortcut taken in {taken} of {total} returns to the apex by set 7 or 11");
    }

}
