//! The joint law at one contact point, the form 3D contacts take (each corner of a contact
//! rectangle is a point of a quarter of its area): the plane's law with its moment taken away
//! and its shear a vector. The plane's domain is "exactly the domain of two contact points at
//! the interface ends"; here each point carries
//! - a normal force `N = kN A (e_n - p_n)`, never tension (dry joints): a gap closes again
//!   without resistance, so a block rocks back;
//! - a shear vector `T = kT A (e_t - p_t)` (two components in the contact's tangents), within
//!   Coulomb's cone `|T| <= -mu N` (the cone itself, not the pyramid limit analysis uses);
//! - flow: slip along `T`, with the opening `tan(psi)` times the slip (non-associative unless
//!   `dilatancy == friction`). The slip is permanent; an open point slips to `T = 0`.
//!
//! The return mapping is the exact closest-point projection in the D-metric onto the cone (for
//! associative flow) or onto its surface along the flow (non-associative), its apex included.
//!
//! ```
//! use masonry_dem::joint::{point_map, PointLaw, JointLaw};
//! let law = PointLaw::new(&JointLaw { friction: 0.6, ..JointLaw::default() }, 0.01);
//! let mut p = [0.0; 3];
//! // compressed by a jump of -1e-6 m and slipped by 1e-5 m along both tangents: it slides,
//! // |T| = mu |N|
//! let (f, flags) = point_map(&law, [-1e-6, 1e-5, 1e-5], &mut p);
//! assert!((f[1].hypot(f[2]) - 0.6 * f[0].abs()).abs() < 1e-9 * f[0].abs());
//! assert_eq!(flags, masonry_dem::joint::SLIDING);
//! ```

use super::{JointLaw, OPEN, SLIDING};

/// A joint law at a point of tributary area `A`: its stiffnesses `kN A`, `kT A` \[N/m\], friction
/// and dilatancy.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointLaw {
    /// kN A \[N/m\].
    pub kn: f64,
    /// kT A \[N/m\].
    pub kt: f64,
    /// mu = tan(phi).
    pub friction: f64,
    /// tan(psi).
    pub dilatancy: f64,
}

impl PointLaw {
    /// The law `law` at a point of tributary area `area` \[m2\].
    pub fn new(law: &JointLaw, area: f64) -> PointLaw {
        PointLaw { kn: law.normal_stiffness * area, kt: law.shear_stiffness * area, friction: law.friction, dilatancy: law.dilatancy }
    }
}

/// The force (N, T1, T2) of a point with jumps `e` = (normal opening, slip along t1, slip
/// along t2) \[m\] and committed plastic jumps `p` (updated: each call is an increment), with its
/// state ([`OPEN`], [`SLIDING`] or 0: stuck).
#[inline(always)]
pub fn point_map(law: &PointLaw, e: [f64; 3], p: &mut [f64; 3]) -> ([f64; 3], u8) {
    let n = law.kn * (e[0] - p[0]);
    if n >= 0.0 {
        // open: no force; the shear spring follows the slip
        p[1] = e[1];
        p[2] = e[2];
        return ([0.0; 3], OPEN);
    }
    let t = [law.kt * (e[1] - p[1]), law.kt * (e[2] - p[2])];
    let tn = t[0].hypot(t[1]);
    let f = tn + law.friction * n;
    if f <= 0.0 {
        return ([n, t[0], t[1]], 0);
    }
    // slip dl along t / |t|, the normal jump opening by dilatancy * dl:
    // |t| - kT dl + mu (n - kN tan(psi) dl) = 0
    let dl = f / (law.kt + law.friction * law.kn * law.dilatancy);
    let n1 = n - law.kn * law.dilatancy * dl;
    if n1 >= 0.0 || tn <= 0.0 {
        // the flow opens the point (the apex): no force, the springs at the jumps
        *p = e;
        return ([0.0; 3], OPEN | SLIDING);
    }
    let (c0, c1) = (t[0] / tn, t[1] / tn);
    p[0] += law.dilatancy * dl;
    p[1] += dl * c0;
    p[2] += dl * c1;
    let s = tn - law.kt * dl;
    ([n1, s * c0, s * c1], SLIDING)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law(mu: f64, psi: f64) -> PointLaw {
        PointLaw::new(&JointLaw { friction: mu, dilatancy: psi, normal_stiffness: 2e9, shear_stiffness: 1e9, ..JointLaw::default() }, 0.02)
    }

    #[test]
    fn elastic_inside_the_cone_and_nothing_in_tension() {
        let l = law(0.6, 0.0);
        let mut p = [0.0; 3];
        let (f, s) = point_map(&l, [-1e-5, 1e-6, -2e-6], &mut p);
        assert_eq!(s, 0);
        assert_eq!(f, [-l.kn * 1e-5, l.kt * 1e-6, -l.kt * 2e-6]);
        assert_eq!(p, [0.0; 3]);
        let (f, s) = point_map(&l, [1e-6, 1e-3, 0.0], &mut p);
        assert_eq!((f, s), ([0.0; 3], OPEN));
        // the shear spring followed the slip: closing again, it starts from there
        let (f, _) = point_map(&l, [-1e-6, 1e-3, 0.0], &mut p);
        assert_eq!(f[1], 0.0);
    }

    #[test]
    fn the_return_lands_on_the_cone_along_the_flow() {
        for (mu, psi) in [(0.6, 0.0), (0.6, 0.6), (0.8, 0.3)] {
            let l = law(mu, psi);
            for dir in [0.0f64, 0.4, 1.3, 2.5, 4.0] {
                let mut p = [0.0; 3];
                let e = [-1e-5, 3e-5 * dir.cos(), 3e-5 * dir.sin()];
                let (f, s) = point_map(&l, e, &mut p);
                let tn = f[1].hypot(f[2]);
                if f[0] < 0.0 {
                    assert_eq!(s, SLIDING);
                    assert!((tn + mu * f[0]).abs() < 1e-9 * f[0].abs(), "mu {mu} psi {psi}: {f:?}");
                    // the shear keeps the trial's direction, and the slip opened by psi times it
                    assert!((f[1] * e[2] - f[2] * e[1]).abs() < 1e-9 * tn * 3e-5);
                    assert!((p[0] - psi * p[1].hypot(p[2])).abs() < 1e-15);
                } else {
                    assert!(s & OPEN != 0);
                }
                // the force is the springs' at the committed plastic jumps
                if s == SLIDING {
                    let again = point_map(&l, e, &mut p.clone()).0;
                    assert!((again[0] - f[0]).abs() < 1e-9 * f[0].abs() && (again[1] - f[1]).abs() < 1e-9 * tn.max(1.0));
                }
            }
        }
    }
}
