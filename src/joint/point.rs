//! The joint law at the four corners of a rectangular contact, the form 3D contacts take: the
//! plane's law, whose domain is "exactly the domain of two contact points at the interface
//! ends", with the two ends made four corners and the shear a vector.
//!
//! - Normal forces: the contact's elastic normal law is the rectangle's, as in the plane: a
//!   stiffness `kN A` on the mean of the corners' normal jumps (the contact's normal jump) and
//!   `kN I` on its rotations about both axes; four corners, each a spring of `kN A / 4`, would
//!   give the rotations three times that (`kN A l^2 / 4` against `kN A l^2 / 12`). So the corner
//!   forces are `N = K (e_n - p_n)` with `K = kN A / 4 (P + (I - P) / 3)`, `P` the mean. No corner
//!   pulls (dry joints): where the trial forces do, the forces are their closest point in the
//!   metric of `K^-1` among forces that do not (the plane's rocking faces, found by enumerating
//!   the corners at zero). As in the plane, the opening is recoverable: a gap closes again
//!   without resistance, so a block rocks back.
//! - Shear: each corner a spring of `kT A / 4` on its slip, the shear vector within Coulomb's
//!   cone of its normal force, `|T| <= -mu N` (the cone of limit analysis in 3D too). Flow:
//!   slip along `T` (permanent), with the normal jump opening by `tan(psi)` times it
//!   (non-associative unless `dilatancy == friction`), taken into the normal forces at the
//!   next call. An open corner slips to `T = 0`.
//!
//! ```
//! use masonry_dem::joint::{corner_map, CornerLaw, JointLaw, OPEN, SLIDING};
//! // a 0.2 m x 0.2 m contact, friction 0.6
//! let law = CornerLaw::new(&JointLaw { friction: 0.6, ..JointLaw::default() }, 0.04);
//! let mut p = [[0.0; 3]; 4];
//! // pressed by -1e-6 m and slipped by 1e-5 m along both tangents: every corner slides, |T| = mu |N|
//! let (f, flags) = corner_map(&law, &[[-1e-6, 1e-5, 1e-5]; 4], &mut p);
//! assert!((f[0][1].hypot(f[0][2]) - 0.6 * f[0][0].abs()).abs() < 1e-9 * f[0][0].abs());
//! assert_eq!(flags, [SLIDING; 4]);
//! // lifted at two corners: they open, the others carry the contact
//! let (f, flags) = corner_map(&law, &[[-1e-6, 0.0, 0.0], [-1e-6, 0.0, 0.0], [1e-6, 0.0, 0.0], [1e-6, 0.0, 0.0]], &mut [[0.0; 3]; 4]);
//! assert_eq!((f[2][0], f[3][0], flags[2]), (0.0, 0.0, OPEN));
//! assert!(f[0][0] < 0.0 && f[1][0] < 0.0);
//! ```

use super::{JointLaw, OPEN, SLIDING};

/// A joint law at the corners of a contact of area `A`: `kN A` and `kT A / 4` \[N/m\], friction
/// and dilatancy.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CornerLaw {
    /// kN A, the contact's normal stiffness \[N/m\].
    pub kn: f64,
    /// kT A / 4, a corner's shear stiffness \[N/m\].
    pub kt: f64,
    /// mu = tan(phi).
    pub friction: f64,
    /// tan(psi).
    pub dilatancy: f64,
}

impl CornerLaw {
    /// The law `law` at the corners of a contact of area `area` \[m2\].
    pub fn new(law: &JointLaw, area: f64) -> CornerLaw {
        CornerLaw { kn: law.normal_stiffness * area, kt: 0.25 * law.shear_stiffness * area, friction: law.friction, dilatancy: law.dilatancy }
    }

    /// The elastic energy of corner forces `f` (N, T1, T2 each) \[J\]: `N^T K^-1 N / 2` plus the
    /// shear springs'.
    pub fn energy(&self, f: &[[f64; 3]; 4]) -> f64 {
        let (mut sum, mut sq, mut shear) = (0.0, 0.0, 0.0);
        for x in f {
            sum += x[0];
            sq += x[0] * x[0];
            shear += x[1] * x[1] + x[2] * x[2];
        }
        // K^-1 = 4 / (kN A) (3 I - 2 P)
        2.0 / self.kn * (3.0 * sq - 0.5 * sum * sum) + 0.5 * shear / self.kt
    }
}

/// The normal forces of the corners at elastic normal jumps `e` (the law's `K e`, projected
/// where a corner would pull: see the module).
#[inline(always)]
fn normals(kn: f64, e: [f64; 4]) -> [f64; 4] {
    let mean = 0.25 * (e[0] + e[1] + e[2] + e[3]);
    let k = 0.25 * kn;
    let t = e.map(|x| k * (mean + (x - mean) / 3.0));
    if t.iter().all(|&x| x <= 0.0) {
        return t;
    }
    // the corners at zero: the subset whose projection meets the Kuhn-Tucker conditions, in the
    // metric C = 3 I - 2 P (K^-1 up to a factor), tried from the corners in tension up
    let tension = (0..4).fold(0u8, |m, j| if t[j] > 0.0 { m | 1 << j } else { m });
    for round in 0..2 {
        for s in 1u8..16 {
            // first the sets that hold every corner in tension, then the others
            if (round == 0) != (s & tension == tension) {
                continue;
            }
            let nf = 4 - s.count_ones() as usize;
            let s_sum: f64 = (0..4).filter(|&j| s & 1 << j != 0).map(|j| t[j]).sum();
            // the free corners: f_F = t_F - s_S / 6 (1 + beta nf), beta = 1 / (6 - nf)
            let shift = if nf > 0 { s_sum / 6.0 * (1.0 + nf as f64 / (6.0 - nf as f64)) } else { 0.0 };
            let mut f = [0.0; 4];
            let mut ok = true;
            let mut moved = 0.0;
            for j in 0..4 {
                if s & 1 << j == 0 {
                    f[j] = t[j] - shift;
                    ok &= f[j] <= 0.0;
                    moved += f[j] - t[j];
                }
            }
            // the multipliers of the corners at zero: -(C (f - t))_j >= 0
            for (j, &tj) in t.iter().enumerate() {
                if s & 1 << j != 0 {
                    let g = -3.0 * tj - 0.5 * (moved - s_sum);
                    ok &= g <= 1e-12 * kn * mean.abs().max(1e-300);
                }
            }
            if ok {
                return f;
            }
        }
    }
    // rounding alone can leave no set exact: the trial forces without their tension
    t.map(|x| x.min(0.0))
}

/// The forces (N, T1, T2) of a contact's four corners with jumps `e` (normal opening, slip
/// along t1, slip along t2 at each corner) \[m\] and committed plastic jumps `p` (updated: each
/// call is an increment), with each corner's state ([`OPEN`], [`SLIDING`] or 0: stuck).
#[inline(always)]
pub fn corner_map(law: &CornerLaw, e: &[[f64; 3]; 4], p: &mut [[f64; 3]; 4]) -> ([[f64; 3]; 4], [u8; 4]) {
    let n = normals(law.kn, [0, 1, 2, 3].map(|j| e[j][0] - p[j][0]));
    let mut out = [[0.0; 3]; 4];
    let mut flags = [0u8; 4];
    for j in 0..4 {
        let (e, p) = (&e[j], &mut p[j]);
        if !(n[j] < 0.0) {
            // open: no force; the shear spring follows the slip
            p[1] = e[1];
            p[2] = e[2];
            flags[j] = OPEN;
            continue;
        }
        let t = [law.kt * (e[1] - p[1]), law.kt * (e[2] - p[2])];
        let tn = t[0].hypot(t[1]);
        let cap = -law.friction * n[j];
        if tn <= cap {
            out[j] = [n[j], t[0], t[1]];
            continue;
        }
        // slip dl along t / |t| back to the cone; the normal jump opens by tan(psi) dl
        let dl = (tn - cap) / law.kt;
        let (c0, c1) = (t[0] / tn, t[1] / tn);
        p[0] += law.dilatancy * dl;
        p[1] += dl * c0;
        p[2] += dl * c1;
        out[j] = [n[j], cap * c0, cap * c1];
        flags[j] = SLIDING;
    }
    (out, flags)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law(mu: f64, psi: f64) -> CornerLaw {
        CornerLaw::new(&JointLaw { friction: mu, dilatancy: psi, normal_stiffness: 2e9, shear_stiffness: 1e9, ..JointLaw::default() }, 0.08)
    }

    /// `f^T C f / 2 - f^T e`-style check of the projection: among all forces that do not pull,
    /// none is closer to the trial in the metric C than the law's.
    #[test]
    fn the_normal_forces_are_the_closest_that_do_not_pull() {
        let l = law(0.6, 0.0);
        let dist = |f: &[f64; 4], t: &[f64; 4]| {
            let d: Vec<f64> = (0..4).map(|j| f[j] - t[j]).collect();
            let s: f64 = d.iter().sum();
            3.0 * d.iter().map(|x| x * x).sum::<f64>() - 0.5 * s * s
        };
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for _ in 0..2000 {
            let e = [rnd() * 1e-6, rnd() * 1e-6, rnd() * 1e-6, rnd() * 1e-6];
            let f = normals(l.kn, e);
            assert!(f.iter().all(|&x| x <= 0.0), "{e:?} {f:?}");
            let mean = 0.25 * e.iter().sum::<f64>();
            let t = e.map(|x| 0.25 * l.kn * (mean + (x - mean) / 3.0));
            let best = dist(&f, &t);
            // every other candidate that does not pull is no closer
            for _ in 0..50 {
                let g = f.map(|x| (x + rnd() * 1e-3 * l.kn * 1e-6).min(0.0));
                assert!(dist(&g, &t) >= best - 1e-9 * best.abs().max(1e-30), "{e:?}: {f:?} beaten by {g:?}");
            }
        }
    }

    #[test]
    fn the_rectangle_stiffness_in_translation_and_rotation() {
        let l = law(0.6, 0.0);
        // a uniform closure: N = kN A e
        let (f, _) = corner_map(&l, &[[-1e-6, 0.0, 0.0]; 4], &mut [[0.0; 3]; 4]);
        let n: f64 = f.iter().map(|x| x[0]).sum();
        assert!((n + l.kn * 1e-6).abs() < 1e-9 * l.kn * 1e-6);
        // a rotation theta about the t2 axis of a contact of side a (corners at +-a/2), closed
        // throughout: M = kN A a^2 / 12 theta, the rectangle's kN I
        let (a, theta, e0) = (0.2, 1e-6, -1e-6);
        let x = [-0.5 * a, 0.5 * a, 0.5 * a, -0.5 * a];
        let e = x.map(|x| [e0 + theta * x, 0.0, 0.0]);
        let (f, _) = corner_map(&l, &e, &mut [[0.0; 3]; 4]);
        let m: f64 = (0..4).map(|j| f[j][0] * x[j]).sum();
        assert!((m - l.kn * a * a / 12.0 * theta).abs() < 1e-9 * m.abs(), "{m}");
    }

    #[test]
    fn the_shear_returns_to_the_cone_along_the_flow() {
        for (mu, psi) in [(0.6, 0.0), (0.6, 0.6), (0.8, 0.3)] {
            let l = law(mu, psi);
            for dir in [0.0f64, 0.4, 1.3, 2.5, 4.0] {
                let mut p = [[0.0; 3]; 4];
                let e = [[-1e-5, 3e-5 * dir.cos(), 3e-5 * dir.sin()]; 4];
                let (f, s) = corner_map(&l, &e, &mut p);
                for j in 0..4 {
                    assert_eq!(s[j], SLIDING);
                    let tn = f[j][1].hypot(f[j][2]);
                    assert!((tn + mu * f[j][0]).abs() < 1e-9 * f[j][0].abs(), "mu {mu} psi {psi}: {f:?}");
                    // the shear keeps the trial's direction, and the slip opened by psi times it
                    assert!((f[j][1] * e[j][2] - f[j][2] * e[j][1]).abs() < 1e-9 * tn * 3e-5);
                    assert!((p[j][0] - psi * p[j][1].hypot(p[j][2])).abs() < 1e-15);
                }
            }
        }
    }
}
