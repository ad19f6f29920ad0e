//! Impacts in time histories: the contact dashpot of a closed interface, set from the joint's
//! coefficient of restitution ([`JointLaw::restitution`]).
//!
//! An interface of length l is, for its normal force N and moment M, two contact points at its
//! ends carrying `N/2 -+ M/l` (the joint law's rocking faces say neither may pull when the joint
//! has no tensile strength). Each end in contact gets a dashpot on its normal closing rate, half
//! of `c_N = 2 zeta sqrt(kN A m)` with m the reduced mass of the two blocks; so the interface
//! has `c_N` on its normal jump and `c_N l^2 / 4` on its rotation. The dashpot never makes an
//! end pull: its force is cut where the end's force would turn to tension (a contact that lets
//! go). A closed interface also gets `c_T = 2 zeta sqrt(kT A m)` on its slip rate, never taking
//! the shear force beyond the friction limit of the damped normal force.
//!
//! The damping ratio `zeta` is the one with which a mass striking such a dashpot and spring
//! (cut, as here, when its force turns to tension) rebounds with the velocity ratio
//! `restitution` ([`restitution_of`], [`damping_ratio`]): 1 is elastic (no dashpot), and the
//! smallest value, [`MIN_RESTITUTION`] = exp(-2), is the
//! critically damped contact.
//!
//! The default restitution of the joints ([`DEFAULT_RESTITUTION`](crate::joint::DEFAULT_RESTITUTION))
//! is the one with which a rigid block rocking on its base loses at each impact the energy of
//! Housner's impact (angular momentum kept about the new pivot: the angular velocity falls by
//! `1 - 1.5 sin^2(alpha)` for a block of slenderness `alpha`).
//!
//! ```
//! use masonry_dem::explicit::contact::{damping_ratio, restitution_of};
//! assert_eq!(restitution_of(0.0), 1.0);
//! let zeta = damping_ratio(0.5);
//! assert!((restitution_of(zeta) - 0.5).abs() < 1e-12);
//! ```

use crate::joint::{JointLaw, MIN_RESTITUTION};

/// The velocity ratio of the rebound of a mass from a spring and dashpot of damping ratio
/// `zeta` in [0, 1], the contact letting go when its force turns to tension (closed form of the
/// damped oscillation: the force `k x + c x'` vanishes at `omega_d t = phi`).
pub fn restitution_of(zeta: f64) -> f64 {
    let zeta = zeta.clamp(0.0, 1.0);
    if zeta >= 1.0 {
        return MIN_RESTITUTION;
    }
    let s = (1.0 - zeta * zeta).sqrt();
    // tan(phi) = -2 zeta s / (1 - 2 zeta^2), phi in (0, pi]
    let phi = (2.0 * zeta * s).atan2(-(1.0 - 2.0 * zeta * zeta));
    -(-zeta * phi / s).exp() * (phi.cos() - zeta / s * phi.sin())
}

/// The damping ratio whose rebound has the velocity ratio `restitution` (in
/// [[`MIN_RESTITUTION`], 1]): the inverse of [`restitution_of`], by bisection (it decreases).
pub fn damping_ratio(restitution: f64) -> f64 {
    if restitution >= 1.0 {
        return 0.0;
    }
    if restitution <= MIN_RESTITUTION {
        return 1.0;
    }
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if restitution_of(mid) > restitution {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The factor on the stable time step of a dashpot of damping ratio `zeta`: the central
/// difference on `m x'' + c x' + k x = 0` is stable for `omega dt <= 2 (sqrt(1 + zeta^2) - zeta)`.
pub fn stability_factor(zeta: f64) -> f64 {
    (1.0 + zeta * zeta).sqrt() - zeta
}

/// The dashpot coefficients (c_N \[N s/m\], c_T \[N s/m\], c_M \[N m s\]) of an interface of law
/// `law`, area `area` \[m2\] and length `length` \[m\] between blocks of reduced mass `mass` \[kg\]
/// (zero where the law's impacts are elastic or the mass is not finite).
pub fn coefficients(law: &JointLaw, area: f64, length: f64, mass: f64) -> [f64; 3] {
    let zeta = damping_ratio(law.restitution);
    if zeta == 0.0 || !(mass.is_finite() && mass > 0.0) {
        return [0.0; 3];
    }
    let cn = 2.0 * zeta * (law.normal_stiffness * area * mass).sqrt();
    let ct = 2.0 * zeta * (law.shear_stiffness * area * mass).sqrt();
    [cn, ct, cn * length * length / 4.0]
}

/// The dashpot force (N, T, M) of an interface with coefficients `c`, half length `half` \[m\],
/// friction `mu`, jump rates `rate` and joint force `f` (the law's, N > 0 in tension): on each
/// end in contact, the normal dashpot cut so that the end does not pull; on a closed interface,
/// the shear dashpot cut at the friction limit. Its power `d . rate` is never negative.
#[inline(always)]
pub(crate) fn dashpot(c: &[f64; 3], half: f64, mu: f64, rate: [f64; 3], f: [f64; 3]) -> [f64; 3] {
    let [n, t, m] = f;
    let inv_l = 0.5 / half;
    let (dn, dm) = (c[0] * rate[0], c[2] * rate[2]);
    // the ends' forces and dashpots: N/2 -+ M/l
    let ends = [0.5 * n - m * inv_l, 0.5 * n + m * inv_l];
    let mut d = [0.5 * dn - dm * inv_l, 0.5 * dn + dm * inv_l];
    // an end carries a share of N where it is closed; on the rocking face the open end's force is
    // zero but for rounding (the face's |M| = -N l/2 to a few ulps of N)
    let closed = -1e-9 * n.abs();
    for j in 0..2 {
        d[j] = if ends[j] < closed { d[j].min(-ends[j]) } else { 0.0 };
    }
    let dn = d[0] + d[1];
    let dm = (d[1] - d[0]) * half;
    let n_total = n + dn;
    let dt = if n_total < 0.0 {
        let cap = t.abs().max(-mu * n_total);
        (t + c[1] * rate[1]).clamp(-cap, cap) - t
    } else {
        0.0
    };
    [dn, dt, dm]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rebound of a unit mass on a unit spring and dashpot cut in tension, integrated finely.
    fn rebound(zeta: f64) -> f64 {
        let (mut x, mut v, h) = (0.0f64, -1.0f64, 1e-5);
        let acc = |x: f64, v: f64| {
            let f = -x - 2.0 * zeta * v; // compression positive for x < 0
            if f > 0.0 { f } else { 0.0 }
        };
        loop {
            // velocity Verlet
            let a = acc(x, v);
            x += h * v + 0.5 * h * h * a;
            let a1 = acc(x, v + h * a);
            v += 0.5 * h * (a + a1);
            if x < 0.0 && acc(x, v) == 0.0 && v > 0.0 {
                return v;
            }
            if x >= 0.0 && v > 0.0 {
                return v;
            }
        }
    }

    #[test]
    fn the_closed_form_is_the_rebound() {
        for zeta in [0.0, 0.05, 0.2, 0.5, 0.7, 0.9, 0.999] {
            let want = rebound(zeta);
            assert!((restitution_of(zeta) - want).abs() < 1e-3, "zeta {zeta}: {} against {want}", restitution_of(zeta));
        }
        assert!((restitution_of(1.0) - (-2.0f64).exp()).abs() < 1e-15);
    }

    #[test]
    fn the_dashpot_dissipates_and_never_pulls() {
        let c = [3.0, 2.0, 0.5];
        for rate in [[1.0, 0.5, 2.0], [-1.0, -0.5, -2.0], [0.3, -2.0, -4.0]] {
            for f in [[-10.0, 1.0, 2.0], [-1.0, 0.6, 0.5], [0.0, 0.0, 0.0]] {
                let d = dashpot(&c, 0.5, 0.6, rate, f);
                assert!(d[0] * rate[0] + d[1] * rate[1] + d[2] * rate[2] >= 0.0);
                let (n, m) = (f[0] + d[0], f[2] + d[2]);
                assert!(0.5 * n + m.abs() <= 1e-12, "{f:?} {rate:?} {d:?}");
            }
        }
    }
}
