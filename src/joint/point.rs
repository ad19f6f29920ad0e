//! The joint law at the corners of a contact polygon, the form 3D contacts take: the plane's
//! law, whose domain is "exactly the domain of two contact points at the interface ends", with
//! the two ends made the polygon's N corners and the shear a vector.
//!
//! - Shares: each corner stands for a share `w_i` of the contact (its tributary area over the
//!   polygon's): the polygon is cut into triangles from its centroid, and each triangle's area
//!   goes half to each of its two corners. The shares sum to 1 and their centroid is the
//!   polygon's (`sum w_i x_i = g`), which makes the strength of the corners, a tension cut-off
//!   `N_i <= ft A w_i` each, the polygon's under a uniform tensile strength in N and in bending
//!   about both axes (a rectangle's corners take a quarter each, the plane's two ends a half).
//! - Normal forces: `N = K (e_n - p_n)` with `K = kN A (alpha W + (1 - alpha) w w^T)`, `W` the
//!   diagonal of the shares: `kN A` on the shares' mean of the corners' normal jumps (the
//!   contact's normal jump), and `alpha` chosen so that the polar moment of the stiffness in
//!   rotation is the polygon's `kN I_p` (`alpha = I_p / (A sum w_i r_i^2)`, `r_i` from the
//!   centroid): a rectangle's, triangle's or regular polygon's `kN I` about every axis (for a
//!   rectangle `alpha = 1/3`: `kN A a^2 / 12` where four springs of `kN A / 4` would give
//!   `kN A a^2 / 4`), another polygon's to within its own anisotropy. No corner pulls beyond
//!   its strength: where the trial forces do, the forces are their closest point in the metric
//!   of `K^-1` among forces that do not (the plane's rocking faces). With `K` diagonal plus one
//!   rank, the corners at the cut-off are those whose excess per share lies above one
//!   threshold: N candidates, each checked. As in the plane, the opening is recoverable: a gap
//!   closes again without resistance, so a block rocks back.
//! - Shear: each corner a spring of `kT A w_i` on its slip, the shear vector within Coulomb's
//!   cone of its normal force, `|T| <= c A w_i - mu N` (the cone of limit analysis in 3D too).
//!   Flow: slip along `T` (permanent), with the normal jump opening by `tan(psi)` times it
//!   (non-associative unless `dilatancy == friction`), taken into the normal forces at the
//!   next call. An open corner slips to `T = 0`.
//! - Strength: the law's cohesion and tensile strength, shared by the corners, hold until the
//!   contact's first failure (a trial force of a corner outside its intact domain), when the
//!   whole contact loses both at once and is mapped as a dry one (the plane's brittle joint).
//!   The cut-off is `min(ft, c / mu)`: beyond `c / mu` Coulomb's cone closes first.
//!
//! ```
//! use masonry_dem::joint::{corner_map, corner_shares, CornerLaw, JointLaw, OPEN, SLIDING};
//! // a 0.2 m x 0.2 m contact, friction 0.6
//! let corners = [[0.0, 0.0, 0.0], [0.2, 0.0, 0.0], [0.2, 0.2, 0.0], [0.0, 0.2, 0.0]];
//! let (w, alpha) = corner_shares(&corners, [0.1, 0.1, 0.0], [0.0, 0.0, 1.0]);
//! assert!(w.iter().all(|&w| (w - 0.25).abs() < 1e-15) && (alpha - 1.0 / 3.0).abs() < 1e-15);
//! let law = CornerLaw::new(&JointLaw { friction: 0.6, ..JointLaw::default() }, 0.04, alpha);
//! let (mut f, mut flags, mut broken) = ([[0.0; 3]; 4], [0u8; 4], false);
//! // pressed by -1e-6 m and slipped by 1e-5 m along both tangents: every corner slides, |T| = mu |N|
//! corner_map(&law, &w, &[[-1e-6, 1e-5, 1e-5]; 4], &mut [[0.0; 3]; 4], &mut broken, &mut f, &mut flags);
//! assert!((f[0][1].hypot(f[0][2]) - 0.6 * f[0][0].abs()).abs() < 1e-9 * f[0][0].abs());
//! assert_eq!(flags, [SLIDING; 4]);
//! // lifted at two corners: they open, the others carry the contact
//! let e = [[-1e-6, 0.0, 0.0], [-1e-6, 0.0, 0.0], [1e-6, 0.0, 0.0], [1e-6, 0.0, 0.0]];
//! corner_map(&law, &w, &e, &mut [[0.0; 3]; 4], &mut broken, &mut f, &mut flags);
//! assert_eq!((f[2][0], f[3][0], flags[2]), (0.0, 0.0, OPEN));
//! assert!(f[0][0] < 0.0 && f[1][0] < 0.0);
//! ```

use super::{JointLaw, OPEN, SLIDING};

/// The most corners a contact may have in [`corner_map`] (its buffers on the stack).
pub const MAX_POINTS: usize = 64;

/// A joint law at the corners of a contact of area `A`: `kN A`, the share of it in the
/// corners' own stiffness (`alpha`), `kT A`, friction, dilatancy, and the contact's strengths
/// `c A` and `ft A`, which the corners share by their shares.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CornerLaw {
    /// kN A, the contact's normal stiffness \[N/m\].
    pub kn: f64,
    /// alpha: `K = kN A (alpha W + (1 - alpha) w w^T)` (1/3 for a rectangle).
    pub alpha: f64,
    /// kT A, the contact's shear stiffness \[N/m\] (a corner's: times its share).
    pub kt: f64,
    /// mu = tan(phi).
    pub friction: f64,
    /// tan(psi).
    pub dilatancy: f64,
    /// c A \[N\], lost at the contact's first failure.
    pub cohesion: f64,
    /// ft A \[N\], lost at the contact's first failure.
    pub tension: f64,
}

/// Each corner's share of a contact polygon (`corners`, counter-clockwise about `normal`, of
/// centroid `centroid`) and the law's `alpha` (see the module): the shares by tributary area,
/// from triangles fanned from the centroid.
pub fn corner_shares(corners: &[[f64; 3]], centroid: [f64; 3], normal: [f64; 3]) -> (Vec<f64>, f64) {
    let n = corners.len();
    let rel: Vec<[f64; 3]> = corners.iter().map(|p| [0, 1, 2].map(|r| p[r] - centroid[r])).collect();
    let (mut w, mut area, mut polar) = (vec![0.0; n], 0.0, 0.0);
    for i in 0..n {
        let (p, q) = (rel[i], rel[(i + 1) % n]);
        let c = [p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]];
        let t = 0.5 * (c[0] * normal[0] + c[1] * normal[1] + c[2] * normal[2]).abs();
        w[i] += 0.5 * t;
        w[(i + 1) % n] += 0.5 * t;
        area += t;
        // the triangle's polar moment about the centroid (a vertex): A / 6 (p.p + p.q + q.q)
        polar += t / 6.0 * (dot(p, p) + dot(p, q) + dot(q, q));
    }
    w.iter_mut().for_each(|w| *w /= area);
    let spread: f64 = w.iter().zip(&rel).map(|(w, r)| w * dot(*r, *r)).sum();
    (w, polar / area / spread)
}

#[inline(always)]
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl CornerLaw {
    /// The law `law` at the corners of a contact of area `area` \[m2\] and `alpha` (from
    /// [`corner_shares`]), at its peak strengths.
    pub fn new(law: &JointLaw, area: f64, alpha: f64) -> CornerLaw {
        CornerLaw {
            kn: law.normal_stiffness * area,
            alpha,
            kt: law.shear_stiffness * area,
            friction: law.friction,
            dilatancy: law.dilatancy,
            cohesion: law.cohesion * area,
            tension: law.tensile_strength * area,
        }
    }

    /// Whether the contact has strength to lose.
    pub fn is_strong(&self) -> bool {
        self.cohesion > 0.0 || self.tension > 0.0
    }

    /// The contact's tension cut-off \[N\] at cohesion `c` and tensile strength `ft` (c A, ft A):
    /// `ft A`, or `c A / mu` where Coulomb's cone closes below it.
    #[inline(always)]
    pub fn cut_off(&self, c: f64, ft: f64) -> f64 {
        if self.friction * ft > c {
            c / self.friction
        } else {
            ft
        }
    }

    /// The elastic energy of corner forces `f` (N, T1, T2 each) of shares `w` \[J\]:
    /// `N^T K^-1 N / 2` plus the shear springs'.
    pub fn energy(&self, w: &[f64], f: &[[f64; 3]]) -> f64 {
        let (a, b) = (self.alpha * self.kn, (1.0 - self.alpha) * self.kn);
        let (mut sum, mut sq, mut shear) = (0.0, 0.0, 0.0);
        for (x, &wi) in f.iter().zip(w) {
            sum += x[0];
            sq += x[0] * x[0] / wi;
            shear += (x[1] * x[1] + x[2] * x[2]) / wi;
        }
        // K^-1 = W^-1 / a - b / (a (a + b)) 1 1^T
        0.5 * (sq / a - b / (a * self.kn) * sum * sum) + 0.5 * shear / self.kt
    }
}

/// The corners' normal forces at trial forces `t` (the law's `K e`, in `f`) with cut-offs
/// `h w_i`: the closest forces in the metric of `K^-1` that do not pull beyond them. The
/// corners at the cut-off (`OPEN` in `flags`) are those whose excess per share
/// `r_i = (t_i - h w_i) / w_i` lies at or above `b sigma`, `sigma = sum_S (t_i - h w_i) / (a + b
/// W_S)` over them (`W_S` their shares): each corner's excess is a candidate threshold.
#[inline(always)]
fn normals(a: f64, b: f64, h: f64, w: &[f64], f: &mut [[f64; 3]], flags: &mut [u8]) {
    let n = w.len();
    // the common case, every corner within its cut-off: no division
    if (0..n).all(|i| !(f[i][0] > h * w[i])) {
        return;
    }
    // the excesses per share, once (the buffer's tail unused)
    let mut r = [0.0; MAX_POINTS];
    let mut scale = 0.0f64;
    for i in 0..n {
        r[i] = f[i][0] / w[i] - h;
        scale = scale.max(r[i].abs());
    }
    let r = &r[..n];
    let tol = 1e-12 * scale;
    for &rk in r {
        if !(rk > 0.0) {
            continue;
        }
        let (mut excess, mut share) = (0.0, 0.0);
        for i in 0..n {
            if r[i] >= rk {
                excess += f[i][0] - h * w[i];
                share += w[i];
            }
        }
        let tau = b * excess / (a + b * share);
        let fits = r.iter().all(|&ri| if ri >= rk { ri >= tau - tol } else { ri <= tau + tol });
        if fits {
            for i in 0..n {
                if r[i] >= rk {
                    f[i][0] = h * w[i];
                    flags[i] = OPEN;
                } else {
                    f[i][0] -= w[i] * tau;
                }
            }
            return;
        }
    }
    // rounding alone can leave no candidate exact: the trial forces cut at the cut-off
    for i in 0..n {
        if f[i][0] > h * w[i] {
            f[i][0] = h * w[i];
            flags[i] = OPEN;
        }
    }
}

/// The forces (N, T1, T2) of a contact's corners of shares `w` with jumps `e` (normal opening,
/// slip along t1, slip along t2 at each corner) \[m\] and committed plastic jumps `p` (updated:
/// each call is an increment), into `out`, with each corner's state in `flags` ([`OPEN`],
/// [`SLIDING`] or 0: stuck). `broken`: whether the contact has lost its strength (set at its
/// first failure). No allocation: every slice holds one entry per corner, at most
/// [`MAX_POINTS`].
#[inline(always)]
pub fn corner_map(law: &CornerLaw, w: &[f64], e: &[[f64; 3]], p: &mut [[f64; 3]], broken: &mut bool, out: &mut [[f64; 3]], flags: &mut [u8]) {
    let n = w.len();
    let (a, b) = (law.alpha * law.kn, (1.0 - law.alpha) * law.kn);
    // the trial forces: K (e_n - p_n), the shear springs
    let mut mean = 0.0;
    for i in 0..n {
        mean += w[i] * (e[i][0] - p[i][0]);
    }
    for i in 0..n {
        let kt = law.kt * w[i];
        out[i] = [w[i] * (a * (e[i][0] - p[i][0]) + b * mean), kt * (e[i][1] - p[i][1]), kt * (e[i][2] - p[i][2])];
        flags[i] = 0;
    }
    let mu = law.friction;
    if !*broken && law.is_strong() {
        // the contact fails where a corner's trial force leaves its intact domain
        let (c, h) = (law.cohesion, law.cut_off(law.cohesion, law.tension));
        let tol = 1e-12 * (law.kn * mean.abs() + c + law.tension);
        let fails = (0..n).any(|i| {
            let f = out[i];
            f[0] > h * w[i] + tol || f[1].hypot(f[2]) > c * w[i] - mu * f[0] + tol
        });
        if !fails {
            return;
        }
        *broken = true;
    }
    let (c, h) = if *broken || !law.is_strong() { (0.0, 0.0) } else { (law.cohesion, law.cut_off(law.cohesion, law.tension)) };
    normals(a, b, h, w, out, flags);
    for i in 0..n {
        let (e, p, f) = (&e[i], &mut p[i], &mut out[i]);
        if flags[i] == OPEN || !(f[0] < h * w[i]) {
            // open: no shear; the shear spring follows the slip
            p[1] = e[1];
            p[2] = e[2];
            *f = [f[0].min(h * w[i]), 0.0, 0.0];
            flags[i] = OPEN;
            continue;
        }
        let tn = f[1].hypot(f[2]);
        let cap = c * w[i] - mu * f[0];
        if tn <= cap {
            continue;
        }
        // slip dl along t / |t| back to the cone; the normal jump opens by tan(psi) dl
        let kt = law.kt * w[i];
        let dl = (tn - cap) / kt;
        let (c0, c1) = (f[1] / tn, f[2] / tn);
        p[0] += law.dilatancy * dl;
        p[1] += dl * c0;
        p[2] += dl * c1;
        f[1] = cap * c0;
        f[2] = cap * c1;
        flags[i] = SLIDING;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SQUARE: [[f64; 3]; 4] = [[0.0, 0.0, 0.0], [0.4, 0.0, 0.0], [0.4, 0.2, 0.0], [0.0, 0.2, 0.0]];

    fn law(mu: f64, psi: f64) -> (CornerLaw, Vec<f64>) {
        let (w, alpha) = corner_shares(&SQUARE, [0.2, 0.1, 0.0], [0.0, 0.0, 1.0]);
        (CornerLaw::new(&JointLaw { friction: mu, dilatancy: psi, normal_stiffness: 2e9, shear_stiffness: 1e9, ..JointLaw::default() }, 0.08, alpha), w)
    }

    fn map(l: &CornerLaw, w: &[f64], e: &[[f64; 3]], p: &mut [[f64; 3]]) -> (Vec<[f64; 3]>, Vec<u8>) {
        let n = w.len();
        let (mut f, mut s, mut broken) = (vec![[0.0; 3]; n], vec![0u8; n], false);
        corner_map(l, w, e, p, &mut broken, &mut f, &mut s);
        (f, s)
    }

    fn rnd(seed: &mut u64) -> f64 {
        *seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (*seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    }

    #[test]
    fn the_shares_are_tributary_areas_with_the_polygons_centroid() {
        // a trapezoid and a pentagon: the shares sum to 1 and their centroid is the polygon's
        for poly in [vec![[0.0, 0.0], [3.0, 0.0], [2.0, 1.0], [0.5, 1.0]], vec![[0.0, 0.0], [2.0, -0.5], [3.0, 1.0], [1.5, 2.5], [-0.5, 1.5]]] {
            let pts: Vec<[f64; 3]> = poly.iter().map(|p| [p[0], p[1], 1.0]).collect();
            // the centroid of the polygon
            let (mut a, mut cx, mut cy) = (0.0, 0.0, 0.0);
            for i in 0..poly.len() {
                let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
                let cr = p[0] * q[1] - q[0] * p[1];
                a += 0.5 * cr;
                cx += (p[0] + q[0]) * cr / 6.0;
                cy += (p[1] + q[1]) * cr / 6.0;
            }
            let g = [cx / a, cy / a, 1.0];
            let (w, alpha) = corner_shares(&pts, g, [0.0, 0.0, 1.0]);
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            for r in 0..2 {
                let m: f64 = w.iter().zip(&pts).map(|(w, p)| w * p[r]).sum();
                assert!((m - g[r]).abs() < 1e-13, "{m} {}", g[r]);
            }
            assert!(alpha > 0.0 && alpha < 1.0, "{alpha}");
        }
    }

    /// Among all forces that do not pull, none is closer to the trial in the metric `K^-1`
    /// than the law's, on a square and on a pentagon.
    #[test]
    fn the_normal_forces_are_the_closest_that_do_not_pull() {
        let pent = [[0.0, 0.0, 0.0], [2.0, -0.5, 0.0], [3.0, 1.0, 0.0], [1.5, 2.5, 0.0], [-0.5, 1.5, 0.0]];
        let mut seed = 12345u64;
        for poly in [&SQUARE[..], &pent[..]] {
            let g: [f64; 3] = [0, 1, 2].map(|r| poly.iter().map(|p| p[r]).sum::<f64>() / poly.len() as f64);
            let (w, alpha) = corner_shares(poly, g, [0.0, 0.0, 1.0]);
            let l = CornerLaw::new(&JointLaw { normal_stiffness: 2e9, ..JointLaw::default() }, 0.08, alpha);
            let n = w.len();
            let dist = |f: &[f64], t: &[f64]| {
                let (mut s, mut q) = (0.0, 0.0);
                for i in 0..n {
                    let d = f[i] - t[i];
                    s += d;
                    q += d * d / w[i];
                }
                let (a, b) = (l.alpha * l.kn, (1.0 - l.alpha) * l.kn);
                q / a - b / (a * l.kn) * s * s
            };
            for _ in 0..2000 {
                let e: Vec<[f64; 3]> = (0..n).map(|_| [rnd(&mut seed) * 1e-6, 0.0, 0.0]).collect();
                let (f, _) = map(&l, &w, &e, &mut vec![[0.0; 3]; n]);
                let f: Vec<f64> = f.iter().map(|x| x[0]).collect();
                assert!(f.iter().all(|&x| x <= 0.0), "{e:?} {f:?}");
                let mean: f64 = (0..n).map(|i| w[i] * e[i][0]).sum();
                let t: Vec<f64> = (0..n).map(|i| w[i] * l.kn * (l.alpha * e[i][0] + (1.0 - l.alpha) * mean)).collect();
                let best = dist(&f, &t);
                for _ in 0..50 {
                    let g: Vec<f64> = f.iter().map(|x| (x + rnd(&mut seed) * 1e-3 * l.kn * 1e-6).min(0.0)).collect();
                    assert!(dist(&g, &t) >= best - 1e-9 * best.abs().max(1e-30), "{e:?}: {f:?} beaten by {g:?}");
                }
            }
        }
    }

    #[test]
    fn the_rectangle_stiffness_in_translation_and_rotation() {
        let (l, w) = law(0.6, 0.0);
        // a uniform closure: N = kN A e
        let (f, _) = map(&l, &w, &[[-1e-6, 0.0, 0.0]; 4], &mut [[0.0; 3]; 4]);
        let n: f64 = f.iter().map(|x| x[0]).sum();
        assert!((n + l.kn * 1e-6).abs() < 1e-9 * l.kn * 1e-6);
        // a rotation theta about either axis of the 0.4 x 0.2 m contact, closed throughout:
        // M = kN A s^2 / 12 theta, the rectangle's kN I
        for (axis, s) in [(0, 0.4), (1, 0.2)] {
            let theta = 1e-6;
            let x: Vec<f64> = SQUARE.iter().map(|p| p[axis] - 0.5 * s).collect();
            let e: Vec<[f64; 3]> = x.iter().map(|x| [-1e-6 + theta * x, 0.0, 0.0]).collect();
            let (f, _) = map(&l, &w, &e, &mut [[0.0; 3]; 4]);
            let m: f64 = (0..4).map(|j| f[j][0] * x[j]).sum();
            assert!((m - l.kn * s * s / 12.0 * theta).abs() < 1e-9 * m.abs(), "{m}");
        }
    }

    #[test]
    fn the_shear_returns_to_the_cone_along_the_flow() {
        for (mu, psi) in [(0.6, 0.0), (0.6, 0.6), (0.8, 0.3)] {
            let (l, w) = law(mu, psi);
            for dir in [0.0f64, 0.4, 1.3, 2.5, 4.0] {
                let mut p = [[0.0; 3]; 4];
                let e = [[-1e-5, 3e-5 * dir.cos(), 3e-5 * dir.sin()]; 4];
                let (f, s) = map(&l, &w, &e, &mut p);
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

    #[test]
    fn a_strong_contact_holds_tension_and_shear_until_it_fails_then_is_dry() {
        let (w, alpha) = corner_shares(&SQUARE, [0.2, 0.1, 0.0], [0.0, 0.0, 1.0]);
        let joint = JointLaw { friction: 0.6, cohesion: 1e5, tensile_strength: 5e4, normal_stiffness: 2e9, shear_stiffness: 1e9, ..JointLaw::default() };
        let l = CornerLaw::new(&joint, 0.08, alpha);
        let (mut f, mut s, mut broken) = ([[0.0; 3]; 4], [0u8; 4], false);
        // a pull of 90% of ft A: held, elastic
        let e = 0.9 * 5e4 / 2e9;
        corner_map(&l, &w, &[[e, 0.0, 0.0]; 4], &mut [[0.0; 3]; 4], &mut broken, &mut f, &mut s);
        assert!(!broken && s == [0; 4]);
        assert!((f.iter().map(|x| x[0]).sum::<f64>() - 0.9 * 5e4 * 0.08).abs() < 1e-6);
        // a shear of 90% of c A: held
        let t = 0.9 * 1e5 / 1e9;
        corner_map(&l, &w, &[[0.0, t, 0.0]; 4], &mut [[0.0; 3]; 4], &mut broken, &mut f, &mut s);
        assert!(!broken && s == [0; 4]);
        // a pull beyond ft A: the contact breaks and opens, dry from then on
        corner_map(&l, &w, &[[2.0 * e, 0.0, 0.0]; 4], &mut [[0.0; 3]; 4], &mut broken, &mut f, &mut s);
        assert!(broken && s == [OPEN; 4] && f.iter().all(|x| x[0] == 0.0));
        corner_map(&l, &w, &[[0.5 * e, 0.0, 0.0]; 4], &mut [[0.0; 3]; 4], &mut broken, &mut f, &mut s);
        assert!(s == [OPEN; 4] && f.iter().all(|x| x[0] == 0.0));
    }
}
