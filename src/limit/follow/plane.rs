//! A step of a mechanism in the plane: each block turned exactly about its instantaneous centre,
//! the points the mechanism keeps closed kept closed.

use super::{CLOSED, SWEEPS};
use crate::model::Model;

/// The finite motion of each block of `model` over one step of `mechanism` (block velocities,
/// any scale) whose largest vertex displacement is `length` \[m\]: each moving block turned about
/// its instantaneous centre by its share of the step (translated where it does not turn), as
/// (u1, u2, phi) of its centroid; None where nothing moves.
pub(super) fn step_motion(model: &Model, mechanism: &[[f64; 3]], length: f64) -> Option<Vec<[f64; 3]>> {
    let (polygons, centroids) = (model.polygons(), model.centroids());
    let mut vmax = 0.0f64;
    for (i, m) in mechanism.iter().enumerate() {
        let c = centroids[i];
        for v in polygons[i].vertices() {
            let (dx, dy) = (v[0] - c[0], v[1] - c[1]);
            vmax = vmax.max((m[0] - m[2] * dy).hypot(m[1] + m[2] * dx));
        }
    }
    if !(vmax > 0.0 && vmax.is_finite()) {
        return None;
    }
    let s = length / vmax;
    let motion = mechanism
        .iter()
        .map(|m| {
            let (u, v, w) = (m[0] * s, m[1] * s, m[2] * s);
            if w == 0.0 {
                return [u, v, 0.0];
            }
            // turned by w about the instantaneous centre (where u + w k x r is zero), the
            // centroid moves by (u S - v C, v S + u C), S = sin(w) / w, C = (1 - cos w) / w
            let (sinc, cosc) = (w.sin() / w, 2.0 * (0.5 * w).sin().powi(2) / w);
            [u * sinc - v * cosc, v * sinc + u * cosc, w]
        })
        .collect();
    Some(motion)
}

/// A point where two blocks touch, that a step of the mechanism keeps closed: blocks `a`, `b`,
/// the point in the configuration before the step, and whether the mechanism keeps it from
/// slipping as well (a hinge) or only from opening (sliding).
struct Kept {
    a: usize,
    b: usize,
    p: [f64; 2],
    n: [f64; 2],
    hinge: bool,
}

/// Moves `motion` (one step of `mechanism` on `model`) the least onto the motions that keep
/// closed the contact points the mechanism keeps closed: each block turned about its own
/// instantaneous centre moves the point it shares with another moving block along two different
/// circles, which part by about theta^2 L in a step of rotation theta (a four-hinge arch's
/// hinges open by a fifth of the step's tolerance in one step and are lost in a few). The
/// projection is a nonlinear Gauss-Seidel over the kept points (each correction the least that
/// closes one point, shared by its two blocks, the fixed ones not moved), until every kept point
/// is closed within a hundredth of the contact tolerance.
pub(super) fn close_contacts(model: &Model, mechanism: &[[f64; 3]], motion: &mut [[f64; 3]]) {
    let (centroids, polygons) = (model.centroids(), model.polygons());
    let fixed = model.fixed();
    let free = |i: usize| !(fixed[3 * i] || fixed[3 * i + 1] || fixed[3 * i + 2]);
    let velocity = |i: usize, p: [f64; 2]| {
        let (m, c) = (mechanism[i], centroids[i]);
        [m[0] - m[2] * (p[1] - c[1]), m[1] + m[2] * (p[0] - c[0])]
    };
    let vmax = (0..polygons.len())
        .flat_map(|i| polygons[i].vertices().iter().map(move |&v| (i, v)))
        .map(|(i, v)| {
            let w = velocity(i, v);
            w[0].hypot(w[1])
        })
        .fold(0.0f64, f64::max);
    let mut kept = Vec::new();
    for it in model.interfaces() {
        if !(free(it.a) || free(it.b)) {
            continue;
        }
        let t = it.t();
        let ends = [[it.c[0] - 0.5 * it.l * t[0], it.c[1] - 0.5 * it.l * t[1]], [it.c[0] + 0.5 * it.l * t[0], it.c[1] + 0.5 * it.l * t[1]]];
        for p in ends.iter().take(if it.l > 0.0 { 2 } else { 1 }) {
            let (va, vb) = (velocity(it.a, *p), velocity(it.b, *p));
            let rel = [vb[0] - va[0], vb[1] - va[1]];
            let (rn, rt) = (rel[0] * it.n[0] + rel[1] * it.n[1], rel[0] * t[0] + rel[1] * t[1]);
            if rn.abs() <= CLOSED * vmax {
                kept.push(Kept { a: it.a, b: it.b, p: *p, n: it.n, hinge: rt.abs() <= CLOSED * vmax });
            }
        }
    }
    let tol = 0.01 * crate::shape::contact_tolerance(model.size());
    let turn = |v: [f64; 2], phi: f64| {
        let (s, co) = phi.sin_cos();
        [co * v[0] - s * v[1], s * v[0] + co * v[1]]
    };
    // where point p of block i goes under motion m, and the arm from its moved centroid
    let place = |i: usize, m: [f64; 3], p: [f64; 2]| {
        let c = centroids[i];
        let r = turn([p[0] - c[0], p[1] - c[1]], m[2]);
        ([c[0] + m[0] + r[0], c[1] + m[1] + r[1]], r)
    };
    // block i moved by g along d, turned by g j, if it is free
    let nudge = |m: &mut [f64; 3], free: bool, g: f64, d: [f64; 2], j: f64| {
        if free {
            m[0] += g * d[0];
            m[1] += g * d[1];
            m[2] += g * j;
        }
    };
    for _ in 0..SWEEPS {
        let mut worst = 0.0f64;
        for k in &kept {
            let (pa, ra) = place(k.a, motion[k.a], k.p);
            let (pb, rb) = place(k.b, motion[k.b], k.p);
            let gap = [pb[0] - pa[0], pb[1] - pa[1]];
            let n = turn(k.n, motion[k.a][2]);
            let dirs: &[[f64; 2]] = if k.hinge { &[n, [n[1], -n[0]]] } else { &[n] };
            let (fa, fb) = (free(k.a), free(k.b));
            for &d in dirs {
                let c = gap[0] * d[0] + gap[1] * d[1];
                worst = worst.max(c.abs());
                // the gradient of c: -(d, ra x d) on a's (u, phi), +(d, rb x d) on b's
                let (ja, jb) = (ra[0] * d[1] - ra[1] * d[0], rb[0] * d[1] - rb[1] * d[0]);
                let norm = if fa { 1.0 + ja * ja } else { 0.0 } + if fb { 1.0 + jb * jb } else { 0.0 };
                if norm == 0.0 {
                    continue;
                }
                let g = c / norm;
                nudge(&mut motion[k.a], fa, g, d, ja);
                nudge(&mut motion[k.b], fb, -g, d, jb);
            }
        }
        if worst <= tol {
            break;
        }
    }
}
