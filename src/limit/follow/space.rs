//! A step of a mechanism in 3D: each block moved by the screw motion of its velocities (turned
//! about its instantaneous axis, slid along it), the points the mechanism keeps closed kept closed.

use super::{CLOSED, SWEEPS};
use crate::shape::vec3::{cross, dot, norm, sub};
use crate::space::Model3;
use nalgebra::{UnitQuaternion, Vector3};

/// The velocity of point `p` of a block of centroid `c` and velocities `m` (v, omega).
fn velocity(m: &[f64; 6], c: [f64; 3], p: [f64; 3]) -> [f64; 3] {
    let w = cross([m[3], m[4], m[5]], sub(p, c));
    [m[0] + w[0], m[1] + w[1], m[2] + w[2]]
}

/// The largest speed of a vertex of a block of `model` under `mechanism`.
fn fastest(model: &Model3, mechanism: &[[f64; 6]]) -> f64 {
    let (shapes, centroids) = (model.shapes(), model.centroids());
    mechanism
        .iter()
        .enumerate()
        .flat_map(|(i, m)| shapes[i].vertices().iter().map(move |&p| norm(velocity(m, centroids[i], p))))
        .fold(0.0, f64::max)
}

/// The finite motion of each block of `model` over one step of `mechanism` (block velocities,
/// any scale) whose largest vertex displacement is `length` \[m\] (at the step's start): each
/// block moved by [`screw`]; None where nothing moves.
pub(super) fn step_motion(model: &Model3, mechanism: &[[f64; 6]], length: f64) -> Option<Vec<[f64; 6]>> {
    let vmax = fastest(model, mechanism);
    if !(vmax > 0.0 && vmax.is_finite()) {
        return None;
    }
    let s = length / vmax;
    Some(mechanism.iter().map(|m| screw(m, s)).collect())
}

/// The finite motion of a block whose velocities `m` (v at the centroid, omega) are kept for the
/// time `s`: the screw motion, a rotation by theta = |omega| s about the instantaneous axis
/// (through the centroid plus omega x v / |omega|^2, along omega) and a slide along it of
/// (v . k) s, k = omega / |omega|; a point on the axis stays on it, so that a block turning
/// about a hinge edge turns exactly about it. As (u, r): the centroid's displacement
/// `s (sinc v_perp + cosc k x v + (v . k) k)`, sinc = sin(theta) / theta, cosc = (1 -
/// cos theta) / theta, v_perp the part of v across k (the plane's formula about every axis), and
/// the rotation vector omega s.
fn screw(m: &[f64; 6], s: f64) -> [f64; 6] {
    let v = [m[0], m[1], m[2]];
    let w = [m[3] * s, m[4] * s, m[5] * s];
    let theta = norm(w);
    if theta == 0.0 {
        return [v[0] * s, v[1] * s, v[2] * s, 0.0, 0.0, 0.0];
    }
    let k = w.map(|x| x / theta);
    let along = dot(v, k);
    let kv = cross(k, v);
    let (sinc, cosc) = (theta.sin() / theta, 2.0 * (0.5 * theta).sin().powi(2) / theta);
    let u: [f64; 3] = std::array::from_fn(|i| s * (sinc * (v[i] - along * k[i]) + cosc * kv[i] + along * k[i]));
    [u[0], u[1], u[2], w[0], w[1], w[2]]
}

/// A rotation vector as a unit quaternion.
fn quaternion(m: &[f64; 6]) -> UnitQuaternion<f64> {
    UnitQuaternion::from_scaled_axis(Vector3::new(m[3], m[4], m[5]))
}

/// The motion `total` followed by `step`: the centroid's displacements add, the rotations compose
/// (the step's after the total's).
pub(super) fn compose(total: [f64; 6], step: [f64; 6]) -> [f64; 6] {
    let r = (quaternion(&step) * quaternion(&total)).scaled_axis();
    [total[0] + step[0], total[1] + step[1], total[2] + step[2], r.x, r.y, r.z]
}

/// A corner of a contact that a step of the mechanism keeps closed: blocks `a`, `b`, the point
/// in the configuration before the step, the contact's axes (n, t1, t2), and whether the
/// mechanism keeps it from slipping as well (a hinge) or only from opening (sliding).
struct Kept {
    a: usize,
    b: usize,
    p: [f64; 3],
    axes: [[f64; 3]; 3],
    hinge: bool,
}

/// Moves `motion` (one step of `mechanism` on `model`) the least onto the motions that keep
/// closed the contact corners the mechanism keeps closed, as the plane's `close_contacts`: two
/// blocks each moved by its own screw part at the corners they share by about theta^2 L a step.
/// A nonlinear Gauss-Seidel over the kept corners (each correction the least translation and
/// rotation that closes one corner along one axis, shared by its two blocks, the fixed ones not
/// moved), until every kept corner is closed within a hundredth of the contact tolerance.
pub(super) fn close_contacts(model: &Model3, mechanism: &[[f64; 6]], motion: &mut [[f64; 6]]) {
    let centroids = model.centroids();
    let fixed = model.fixed();
    let free = |i: usize| !fixed[6 * i..6 * i + 6].iter().any(|&f| f);
    let vmax = fastest(model, mechanism);
    let mut kept = Vec::new();
    for c in model.contacts() {
        if !(free(c.a) || free(c.b)) {
            continue;
        }
        for &p in &c.corners {
            let rel = sub(velocity(&mechanism[c.b], centroids[c.b], p), velocity(&mechanism[c.a], centroids[c.a], p));
            let rn = dot(rel, c.n);
            if rn.abs() <= CLOSED * vmax {
                let slip = norm(std::array::from_fn(|j| rel[j] - rn * c.n[j]));
                kept.push(Kept { a: c.a, b: c.b, p, axes: [c.n, c.t1, c.t2], hinge: slip <= CLOSED * vmax });
            }
        }
    }
    if kept.is_empty() {
        return;
    }
    let tol = 0.01 * model.contact_tolerance();
    // the rotations as unit quaternions while they are corrected
    let mut turns: Vec<UnitQuaternion<f64>> = motion.iter().map(quaternion).collect();
    let turn = |q: &UnitQuaternion<f64>, x: [f64; 3]| {
        let y = q.transform_vector(&Vector3::from(x));
        [y.x, y.y, y.z]
    };
    for _ in 0..SWEEPS {
        let mut worst = 0.0f64;
        for k in &kept {
            // where p of block i goes, and the arm from its moved centroid
            let place = |i: usize, q: &UnitQuaternion<f64>, m: &[f64; 6]| {
                let c = centroids[i];
                let r = turn(q, sub(k.p, c));
                (std::array::from_fn::<f64, 3, _>(|j| c[j] + m[j] + r[j]), r)
            };
            let (pa, ra) = place(k.a, &turns[k.a], &motion[k.a]);
            let (pb, rb) = place(k.b, &turns[k.b], &motion[k.b]);
            let gap = sub(pb, pa);
            let (fa, fb) = (free(k.a), free(k.b));
            let dirs = if k.hinge { 3 } else { 1 };
            for axis in &k.axes[..dirs] {
                let d = turn(&turns[k.a], *axis);
                let c = dot(gap, d);
                worst = worst.max(c.abs());
                // the gradient of c: -(d, ra x d) on a's (u, rotation), +(d, rb x d) on b's
                let (ja, jb) = (cross(ra, d), cross(rb, d));
                let norm = if fa { 1.0 + dot(ja, ja) } else { 0.0 } + if fb { 1.0 + dot(jb, jb) } else { 0.0 };
                if norm == 0.0 {
                    continue;
                }
                let g = c / norm;
                for (i, sign, j, go) in [(k.a, g, ja, fa), (k.b, -g, jb, fb)] {
                    if go {
                        (0..3).for_each(|r| motion[i][r] += sign * d[r]);
                        turns[i] = UnitQuaternion::from_scaled_axis(Vector3::from(j) * sign) * turns[i];
                    }
                }
            }
        }
        if worst <= tol {
            break;
        }
    }
    for (m, q) in motion.iter_mut().zip(&turns) {
        let r = q.scaled_axis();
        m[3..].copy_from_slice(&[r.x, r.y, r.z]);
    }
}
