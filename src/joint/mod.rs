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
//! use masonry_dem::joint::{return_map, JointLaw, JointState, MapOptions, Section};
//! let law = JointLaw { friction: 0.6, ..JointLaw::default() };
//! let sec = Section::new(0.4, 1.0);
//! // compressed by a jump of -1e-6 m and slipped by 1e-5 m: the joint slides, |T| = mu |N|
//! let (r, _set) = return_map(&law, &sec, [-1e-6, 1e-5, 0.0], &JointState::default(), &MapOptions::default());
//! assert!((r.force[1].abs() - 0.6 * r.force[0].abs()).abs() < 1e-6 * r.force[0].abs());
//! ```
//!
//! Here: the law, the section, the state and the response. The strength domain and the elastic
//! stiffness are in `domain`, the return mapping and its tangent in `mapping`, the interfaces'
//! kinds with their prepared constants in `kinds`, the small dense LU in `lu`.

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
    /// c \[Pa\]; lost at the first failure of the joint.
    pub cohesion: f64,
    /// ft \[Pa\]; lost at the first failure of the joint.
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
    /// e_n, the coefficient of restitution of an impact at the joint [-], in
    /// [[`MIN_RESTITUTION`], 1]: the ratio of the velocities of separation and approach of a mass
    /// striking the joint. Time histories only: the explicit solver puts a dashpot at each end of
    /// a closed interface, of the damping ratio that gives this restitution (see
    /// [`crate::explicit::contact`]); 1 is an elastic impact (no dashpot). Quasi-static analyses do
    /// not read it.
    pub restitution: f64,
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
            restitution: DEFAULT_RESTITUTION,
        }
    }
}

/// The default coefficient of restitution of the joints ([`JointLaw::restitution`]): the value
/// with which a rigid block rocking on its base loses, at each impact, the energy Housner's
/// model of the impact gives it (angular momentum conserved about the new pivot); see
/// [`crate::explicit::contact`].
pub const DEFAULT_RESTITUTION: f64 = 0.3;

/// The smallest coefficient of restitution accepted: that of a critically damped dashpot
/// (exp(-2)), below which the stable time step of the explicit solver would shrink without
/// bound.
pub const MIN_RESTITUTION: f64 = 0.135_335_283_236_612_7;

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
        if !(MIN_RESTITUTION..=1.0).contains(&self.restitution) {
            return Err(Error::input(format!(
                "{what}.restitution = {} must lie in [{MIN_RESTITUTION:.4}, 1] (the coefficient of restitution of an impact: 1 is elastic, {MIN_RESTITUTION:.4} a critically damped contact)",
                self.restitution
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

    /// Current (cohesion \[Pa\], tensile strength \[Pa\]) of a joint with history `state`.
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
    /// A = l s \[m2\]
    pub area: f64,
    /// I = s l^3 / 12 \[m4\]
    pub inertia: f64,
    /// l \[m\]
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
    /// Largest plastic opening (gap) reached on the cut-off and rocking faces \[m\] (drives the
    /// softening of the tensile strength).
    pub opening: f64,
    /// Accumulated plastic slip \[m\] (drives softening).
    pub slip: f64,
}

/// What the return mapping gives back.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Response {
    /// (N \[N\], T \[N\], M [N m])
    pub force: [f64; 3],
    /// The updated history (to be committed once the step has converged).
    pub state: JointState,
    /// OPEN | SLIDING | ROCKING bits, 0 when elastic.
    pub flags: u8,
    /// d force / d jumps (row-major), consistent with the mapping.
    pub tangent: [[f64; 3]; 3],
}

mod domain;
mod kinds;
mod lu;
mod mapping;
mod point;
#[cfg(test)]
mod tests;

pub use domain::*;
pub use kinds::Prepared;
pub(crate) use kinds::Kinds;
use lu::*;
pub use mapping::*;
pub use point::{corner_map, corner_shares, CornerLaw, MAX_POINTS};
