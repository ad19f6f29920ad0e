//! Second-order cones of three dimensions, `Q = {x : x0 >= |(x1, x2)|}`, in the interior point:
//! Nesterov and Todd's scaling, Jordan's product and the step to a cone's boundary (the forms of
//! Vandenberghe's "The CVXOPT linear and quadratic cone program solvers", 2010, sec. 4.2).
//!
//! With the primal `x` and dual `s` of a cone both inside it, the scaling `W` (symmetric,
//! positive definite) maps them to one point, `W s = W^-1 x = lam`; the complementarity
//! `x o s = mu e` (e = (1, 0, 0)) is linearized in the scaled space,
//! `lam o (W ds + W^-1 dx) = r`. The orthant is the cone of one dimension, with `W = sqrt(x / s)`.

/// `J = diag(1, -1, -1)` applied to `v`.
#[inline]
fn jv(v: [f64; 3]) -> [f64; 3] {
    [v[0], -v[1], -v[2]]
}

#[inline]
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `v^T J v`: positive inside the cone; as `(v0 - r) (v0 + r)`, exact to rounding near its
/// boundary. (`sqrt`, not `hypot`: hypot took 6% of an analysis.)
#[inline]
fn jnorm2(v: [f64; 3]) -> f64 {
    let r = (v[1] * v[1] + v[2] * v[2]).sqrt();
    (v[0] - r) * (v[0] + r)
}

/// `v^T J v` of a point inside the cone, at least a rounding's worth of `v0^2`: a point that a
/// step left inside may be found on the boundary, or out by an ulp, by the rounding of
/// `v0 - |(v1, v2)|` (its scaling was then not finite, and the factorization failed, on a
/// 47-block U-wall).
#[inline]
fn jnorm2_inside(v: [f64; 3]) -> f64 {
    jnorm2(v).max(4.0 * f64::EPSILON * v[0] * v[0])
}

/// Jordan's product `u o v = (u . v, u0 v1 + v0 u1, u0 v2 + v0 u2)`.
#[inline]
pub(super) fn jordan(u: [f64; 3], v: [f64; 3]) -> [f64; 3] {
    [dot(u, v), u[0] * v[1] + v[0] * u[1], u[0] * v[2] + v[0] * u[2]]
}

/// The scaling of a pair `(x, s)` inside the cone: `W = beta (2 w w^T - J)`, the scaled
/// point `lam = W s`, and `lam^T J lam` (`sqrt(x^T J x s^T J s)`, without the cancellation of
/// computing it from lam).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Nt {
    pub(super) w: [f64; 3],
    pub(super) beta: f64,
    pub(super) lam: [f64; 3],
    lam_j: f64,
}

impl Nt {
    /// The scaling of `x` and `s`, both strictly inside the cone.
    pub(super) fn new(x: [f64; 3], s: [f64; 3]) -> Nt {
        let (xn, sn) = (jnorm2_inside(x).sqrt(), jnorm2_inside(s).sqrt());
        let xh = x.map(|v| v / xn);
        let sh = s.map(|v| v / sn);
        let gamma = ((1.0 + dot(xh, sh)) / 2.0).sqrt();
        let js = jv(sh);
        // the scaling point wb (wb^T J wb = 1), and w its square root in the cone's algebra
        let wb: [f64; 3] = std::array::from_fn(|i| (xh[i] + js[i]) / (2.0 * gamma));
        let root = (2.0 * (wb[0] + 1.0)).sqrt();
        let w = [(wb[0] + 1.0) / root, wb[1] / root, wb[2] / root];
        let beta = (xn / sn).sqrt();
        let mut nt = Nt { w, beta, lam: [0.0; 3], lam_j: xn * sn };
        nt.lam = nt.apply(s);
        nt
    }

    /// `W v`.
    #[inline]
    pub(super) fn apply(&self, v: [f64; 3]) -> [f64; 3] {
        let c = 2.0 * dot(self.w, v);
        let j = jv(v);
        std::array::from_fn(|i| self.beta * (c * self.w[i] - j[i]))
    }

    /// `W^-1 v = (2 J w w^T J - J) v / beta`.
    #[inline]
    pub(super) fn apply_inv(&self, v: [f64; 3]) -> [f64; 3] {
        let jw = jv(self.w);
        let c = 2.0 * dot(jw, v);
        let j = jv(v);
        std::array::from_fn(|i| (c * jw[i] - j[i]) / self.beta)
    }

    /// `W^2` as a matrix (the cone's block of the normal equations' Theta).
    pub(super) fn theta(&self) -> [[f64; 3]; 3] {
        let cols: [[f64; 3]; 3] = std::array::from_fn(|c| {
            let mut e = [0.0; 3];
            e[c] = 1.0;
            self.theta_mul(e)
        });
        std::array::from_fn(|r| std::array::from_fn(|c| cols[c][r]))
    }

    /// `W^2 v`, as `W (W v)`: the product of the matrix `W^2`, whose entries grow with the
    /// square of W's, with a vector loses more to cancellation (the dual residual then grew
    /// to 1e7 on a 3,980-block wall).
    #[inline]
    pub(super) fn theta_mul(&self, v: [f64; 3]) -> [f64; 3] {
        self.apply(self.apply(v))
    }


    /// `h` with `lam o h = r`.
    #[inline]
    pub(super) fn lam_div(&self, r: [f64; 3]) -> [f64; 3] {
        let l = self.lam;
        let h0 = (l[0] * r[0] - l[1] * r[1] - l[2] * r[2]) / self.lam_j;
        [h0, (r[1] - h0 * l[1]) / l[0], (r[2] - h0 * l[2]) / l[0]]
    }
}

/// The largest step in (0, `upto`] that keeps `v + a d` in the cone: `upto` where `v + upto d`
/// is in it (the steps that do form an interval from 0), else [`cone_step`]. The check costs
/// no root: most cones do not limit the step, and the root took 6% of an analysis.
#[inline]
pub(super) fn cone_step_upto(v: [f64; 3], d: [f64; 3], upto: f64) -> f64 {
    let u: [f64; 3] = std::array::from_fn(|i| v[i] + upto * d[i]);
    if u[0] >= 0.0 && u[0] * u[0] >= u[1] * u[1] + u[2] * u[2] {
        upto
    } else {
        cone_step(v, d).min(upto)
    }
}

/// The largest step `a` (infinity where there is no bound) that keeps `v + a d` in the cone,
/// `v` inside it: the first positive root of `(v + a d)^T J (v + a d) = 0`, and at most the
/// step at which `v0 + a d0` turns negative. Through the apex the two roots are one: rounding
/// then makes the discriminant negative, which is taken as zero (a direction through the apex
/// of a cone with `|(v1, v2)|` 1e-20 and `v0` 4e-12 found no root, and the step left the cone).
#[inline]
pub(super) fn cone_step(v: [f64; 3], d: [f64; 3]) -> f64 {
    let apex = if d[0] < 0.0 { -v[0] / d[0] } else { f64::INFINITY };
    let (a, b, c) = (d[0] * d[0] - d[1] * d[1] - d[2] * d[2], dot(v, jv(d)), jnorm2(v).max(0.0));
    // roots of a t^2 + 2 b t + c
    if a == 0.0 {
        return if b < 0.0 { (-c / (2.0 * b)).min(apex) } else { apex };
    }
    let disc = (b * b - a * c).max(0.0);
    let q = -(b + b.signum() * disc.sqrt());
    let roots = [q / a, if q != 0.0 { c / q } else { f64::INFINITY }];
    roots.iter().filter(|&&t| t > 0.0).fold(apex, |m, &t| m.min(t))
}

/// The largest step in (0, 1] that keeps each triple of `v + a dv` in the cone.
pub(super) fn max_cone_step(v: &[f64], dv: &[f64]) -> f64 {
    v.chunks_exact(3)
        .zip(dv.chunks_exact(3))
        .fold(1.0f64, |m, (v, d)| cone_step_upto([v[0], v[1], v[2]], [d[0], d[1], d[2]], m))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
        a.iter().zip(&b).all(|(a, b)| (a - b).abs() <= tol * (1.0 + b.abs()))
    }

    #[test]
    fn the_scaling_maps_both_points_to_one() {
        let (x, s) = ([2.0, 0.3, -1.1], [1.5, -0.9, 0.4]);
        let nt = Nt::new(x, s);
        assert!(close(nt.apply(s), nt.apply_inv(x), 1e-14), "{:?} {:?}", nt.apply(s), nt.apply_inv(x));
        // W^2 s = x, and W^-1 W = 1
        let th = nt.theta();
        let ths: [f64; 3] = std::array::from_fn(|r| dot(th[r], s));
        assert!(close(ths, x, 1e-14));
        assert!(close(nt.apply_inv(nt.apply([0.3, 0.7, -0.2])), [0.3, 0.7, -0.2], 1e-14));
        // lam o lam's first entry is x . s
        assert!((jordan(nt.lam, nt.lam)[0] - dot(x, s)).abs() <= 1e-14);
        assert!((jnorm2(nt.lam) - nt.lam_j).abs() <= 1e-14 * nt.lam_j);
    }

    #[test]
    fn lam_div_inverts_the_jordan_product() {
        let nt = Nt::new([2.0, 0.3, -1.1], [1.5, -0.9, 0.4]);
        let h = [0.4, -2.0, 0.7];
        assert!(close(nt.lam_div(jordan(nt.lam, h)), h, 1e-13));
    }

    #[test]
    fn the_step_stops_on_the_cone_boundary() {
        // from (1, 0, 0) along (0, 1, 0): the boundary at a = 1
        assert!((cone_step([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]) - 1.0).abs() < 1e-15);
        // along the axis inwards: no bound; outwards through the apex at a = 1
        assert_eq!(cone_step([1.0, 0.0, 0.0], [1.0, 0.0, 0.0]), f64::INFINITY);
        assert!((cone_step([1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]) - 1.0).abs() < 1e-15);
        // through the apex, with tangential parts at rounding's scale: at v0 / -d0
        let a = cone_step([3.8376036505409715e-12, -4.729144459343692e-20, -2.2403605061383504e-20], [-4.844997192572745e-12, 4.9162942227555135e-20, 1.991386891828132e-20]);
        assert!((a - 3.8376036505409715 / 4.844997192572745).abs() < 1e-9, "{a}");
        // from (2, 1, 0) along (-1, 1, 1): (2 - a)^2 = (1 + a)^2 + a^2 at a = 2 sqrt 3 - 3
        let a = cone_step([2.0, 1.0, 0.0], [-1.0, 1.0, 1.0]);
        assert!((a - (2.0 * 3.0f64.sqrt() - 3.0)).abs() < 1e-14, "{a}");
    }
}
