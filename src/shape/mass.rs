//! The mass properties of the shapes, exact: a convex polygon's area, centroid and polar second
//! moment (the closed forms of a polygon, summed edge by edge), a convex polyhedron's volume,
//! centroid and inertia tensor (those of tetrahedra, summed face by face).

use super::vec3::{cross, dot, sub};
use super::Polyhedron;

/// The area properties of a polygon (per unit thickness: a block's mass is density times
/// thickness times `area`, its rotary inertia density times thickness times `polar`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Area {
    /// Area \[m2\].
    pub area: f64,
    /// Centroid \[m\].
    pub centroid: [f64; 2],
    /// Polar second moment about the centroid, `integral of |x - centroid|^2 dA` \[m4\].
    pub polar: f64,
}

impl Area {
    /// The properties of the polygon of `vertices`, counter-clockwise (clockwise gives a negative
    /// area). Sums over the edges, with each vertex taken from the first one (for the area and
    /// the centroid) and from the centroid (for the polar moment), so that a polygon far from
    /// the origin loses no digits: for an edge from `p` to `q` (relative coordinates) and
    /// `c = p x q`, `A = sum c / 2`, `A g = sum (p + q) c / 6`,
    /// `J = sum c (p.p + p.q + q.q) / 12`.
    pub fn of(vertices: &[[f64; 2]]) -> Area {
        let n = vertices.len();
        if n == 0 {
            return Area { area: 0.0, centroid: [f64::NAN; 2], polar: 0.0 };
        }
        let edges = |o: [f64; 2]| {
            (0..n).map(move |i| {
                let (p, q) = (vertices[i], vertices[(i + 1) % n]);
                let p = [p[0] - o[0], p[1] - o[1]];
                let q = [q[0] - o[0], q[1] - o[1]];
                (p, q, p[0] * q[1] - q[0] * p[1])
            })
        };
        let o = vertices[0];
        let (mut twice, mut gx, mut gy) = (0.0, 0.0, 0.0);
        for (p, q, c) in edges(o) {
            twice += c;
            gx += (p[0] + q[0]) * c;
            gy += (p[1] + q[1]) * c;
        }
        let area = 0.5 * twice;
        let centroid = [o[0] + gx / (3.0 * twice), o[1] + gy / (3.0 * twice)];
        let polar = edges(centroid)
            .map(|(p, q, c)| c * (p[0] * p[0] + p[0] * q[0] + q[0] * q[0] + p[1] * p[1] + p[1] * q[1] + q[1] * q[1]))
            .sum::<f64>()
            / 12.0;
        Area { area, centroid, polar }
    }
}

/// The volume properties of a polyhedron (per unit density: a block's mass is density times
/// `volume`, its inertia tensor density times `inertia`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Volume {
    /// Volume \[m3\].
    pub volume: f64,
    /// Centroid \[m\].
    pub centroid: [f64; 3],
    /// The second moments about the centroid, `integral of (x - g)(x - g)^T dV` \[m5\].
    pub second: [[f64; 3]; 3],
    /// The inertia tensor about the centroid per unit density, `trace(second) I - second` \[m5\].
    pub inertia: [[f64; 3]; 3],
}

impl Volume {
    /// The properties of `p`: the tetrahedra from a point to the triangles of each face's fan
    /// (faces counter-clockwise seen from outside), from its first vertex for the volume and the
    /// centroid, then from the centroid for the second moments, so that a block far from the
    /// origin loses no digits. For a tetrahedron of edges `a`, `b`, `c` from its apex and
    /// `d = a . (b x c)`: `V = d / 6`, `V g = d (a + b + c) / 24`,
    /// `integral of x x^T = d (a a^T + b b^T + c c^T + s s^T) / 120` with `s = a + b + c`.
    pub fn of(p: &Polyhedron) -> Volume {
        let tets = |o: [f64; 3]| {
            let v = p.vertices();
            p.faces().iter().flat_map(move |f| {
                let r = &f.vertices;
                (1..r.len().saturating_sub(1)).map(move |i| {
                    let (a, b, c) = (sub(v[r[0]], o), sub(v[r[i]], o), sub(v[r[i + 1]], o));
                    (a, b, c, dot(a, cross(b, c)))
                })
            })
        };
        let o = p.vertices()[0];
        let (mut six, mut g) = (0.0, [0.0; 3]);
        for (a, b, c, d) in tets(o) {
            six += d;
            (0..3).for_each(|k| g[k] += d * (a[k] + b[k] + c[k]));
        }
        let volume = six / 6.0;
        let centroid: [f64; 3] = std::array::from_fn(|k| o[k] + g[k] / (4.0 * six));
        let mut second = [[0.0; 3]; 3];
        for (a, b, c, d) in tets(centroid) {
            let s: [f64; 3] = std::array::from_fn(|k| a[k] + b[k] + c[k]);
            for (i, row) in second.iter_mut().enumerate() {
                for (j, e) in row.iter_mut().enumerate() {
                    *e += d * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + s[i] * s[j]) / 120.0;
                }
            }
        }
        let trace = second[0][0] + second[1][1] + second[2][2];
        let inertia = std::array::from_fn(|i| std::array::from_fn(|j| if i == j { trace - second[i][j] } else { -second[i][j] }));
        Volume { volume, centroid, second, inertia }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs().max(1e-300)
    }

    #[test]
    fn a_rectangle_has_its_closed_forms() {
        let (x0, y0, x1, y1) = (0.4, 0.175, 0.8, 0.35);
        let r = Area::of(&[[x0, y0], [x1, y0], [x1, y1], [x0, y1]]);
        let (w, h) = (x1 - x0, y1 - y0);
        // the area is the product itself, to the last bit
        assert_eq!(r.area, w * h);
        assert!(close(r.centroid[0], 0.5 * (x0 + x1), 1e-15) && close(r.centroid[1], 0.5 * (y0 + y1), 1e-15));
        assert!(close(r.polar, w * h * (w * w + h * h) / 12.0, 1e-14));
    }

    #[test]
    fn a_right_triangle_has_its_closed_forms() {
        // legs b along x and h along y: A = b h / 2, centroid (b/3, h/3), J = A (b^2 + h^2) / 18
        let (b, h) = (3.0, 2.0);
        let t = Area::of(&[[0.0, 0.0], [b, 0.0], [0.0, h]]);
        assert!(close(t.area, 3.0, 1e-15));
        assert!(close(t.centroid[0], 1.0, 1e-15) && close(t.centroid[1], 2.0 / 3.0, 1e-15));
        assert!(close(t.polar, 3.0 * (b * b + h * h) / 18.0, 1e-14));
    }

    #[test]
    fn clockwise_vertices_give_a_negative_area() {
        let r = Area::of(&[[0.0, 0.0], [0.0, 1.0], [2.0, 1.0], [2.0, 0.0]]);
        assert_eq!(r.area, -2.0);
    }

    proptest! {
        // a regular polygon of k sides and circumradius r: A = k r^2 sin(2 pi / k) / 2 and
        // J = A r^2 (2 + cos(2 pi / k)) / 6, its centroid the centre; anywhere, turned any way
        #[test]
        fn regular_polygons_have_their_closed_forms(k in 3usize..40, r in 0.01f64..100.0, phase in 0.0f64..6.3, cx in -1e3f64..1e3, cy in -1e3f64..1e3) {
            let v: Vec<[f64; 2]> = (0..k)
                .map(|i| {
                    let a = phase + 2.0 * std::f64::consts::PI * i as f64 / k as f64;
                    [cx + r * a.cos(), cy + r * a.sin()]
                })
                .collect();
            let p = Area::of(&v);
            let th = 2.0 * std::f64::consts::PI / k as f64;
            let area = 0.5 * k as f64 * r * r * th.sin();
            prop_assert!(close(p.area, area, 1e-9), "area {} against {}", p.area, area);
            prop_assert!((p.centroid[0] - cx).abs() <= 1e-9 * (r + cx.abs()) && (p.centroid[1] - cy).abs() <= 1e-9 * (r + cy.abs()));
            prop_assert!(close(p.polar, area * r * r * (2.0 + th.cos()) / 6.0, 1e-8));
        }

        // a rectangle anywhere, given from any of its corners: the closed forms
        #[test]
        fn rectangles_have_their_closed_forms(x0 in -1e3f64..1e3, y0 in -1e3f64..1e3, w in 1e-3f64..10.0, h in 1e-3f64..10.0, start in 0usize..4) {
            let c = [[x0, y0], [x0 + w, y0], [x0 + w, y0 + h], [x0, y0 + h]];
            let v: Vec<[f64; 2]> = (0..4).map(|i| c[(i + start) % 4]).collect();
            let p = Area::of(&v);
            let (w, h) = (c[1][0] - c[0][0], c[2][1] - c[1][1]);
            prop_assert!(close(p.area, w * h, 1e-12));
            prop_assert!((p.centroid[0] - (x0 + 0.5 * w)).abs() <= 1e-12 * (x0.abs() + w));
            prop_assert!((p.centroid[1] - (y0 + 0.5 * h)).abs() <= 1e-12 * (y0.abs() + h));
            prop_assert!(close(p.polar, w * h * (w * w + h * h) / 12.0, 1e-9));
        }
    }

    /// `|a - b| <= rel |b|` entry by entry, relative to the largest entry of `b`.
    fn close_tensor(a: [[f64; 3]; 3], b: [[f64; 3]; 3], rel: f64) -> bool {
        let big = b.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        (0..3).all(|i| (0..3).all(|j| (a[i][j] - b[i][j]).abs() <= rel * big))
    }

    fn diag(d: [f64; 3]) -> [[f64; 3]; 3] {
        std::array::from_fn(|i| std::array::from_fn(|j| if i == j { d[i] } else { 0.0 }))
    }

    #[test]
    fn a_box_has_its_closed_forms() {
        let (min, max) = ([0.4, -1.2, 10.0], [0.8, -1.1, 10.175]);
        let v = Volume::of(&Polyhedron::cuboid(min, max));
        let [a, b, c] = [0, 1, 2].map(|k| max[k] - min[k]);
        let vol = a * b * c;
        assert!(close(v.volume, vol, 1e-14));
        assert!((0..3).all(|k| (v.centroid[k] - 0.5 * (min[k] + max[k])).abs() <= 1e-14 * 10.0));
        let j = diag([vol * (b * b + c * c) / 12.0, vol * (a * a + c * c) / 12.0, vol * (a * a + b * b) / 12.0]);
        assert!(close_tensor(v.inertia, j, 1e-12), "{:?} against {j:?}", v.inertia);
    }

    #[test]
    fn a_tetrahedron_has_its_closed_forms() {
        // the corner tetrahedron of legs a, b, c: V = a b c / 6, centroid (a, b, c) / 4; about
        // the centroid, integral x^2 = V 3 a^2 / 80, integral x y = -V a b / 80
        let (a, b, c) = (1.0, 2.0, 3.0);
        let pts = [[0.0; 3], [a, 0.0, 0.0], [0.0, b, 0.0], [0.0, 0.0, c]];
        let v = Volume::of(&Polyhedron::hull(&pts, 1e-9).unwrap());
        let vol = a * b * c / 6.0;
        assert!(close(v.volume, vol, 1e-14));
        assert!((0..3).all(|k| (v.centroid[k] - [a, b, c][k] / 4.0).abs() <= 1e-15));
        let l = [a, b, c];
        let second: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| vol * l[i] * l[j] * if i == j { 3.0 } else { -1.0 } / 80.0));
        assert!(close_tensor(v.second, second, 1e-12), "{:?} against {second:?}", v.second);
        // the regular tetrahedron of edge e: J = m e^2 / 20 about every axis through its centroid
        let e = 0.7;
        let s = e / 2f64.sqrt();
        let reg = [[s, s, s], [s, -s, -s], [-s, s, -s], [-s, -s, s]].map(|p| p.map(|x| 0.5 * x + 3.0));
        let v = Volume::of(&Polyhedron::hull(&reg, 1e-9).unwrap());
        assert!(close(v.volume, e * e * e / (6.0 * 2f64.sqrt()), 1e-14));
        assert!(close_tensor(v.inertia, diag([v.volume * e * e / 20.0; 3]), 1e-12), "{:?}", v.inertia);
    }

    #[test]
    fn a_triangular_prism_has_its_closed_forms() {
        // equilateral triangle of side a along z, length l: about its axis J = m a^2 / 12, across
        // it J = m (a^2 / 24 + l^2 / 12)
        let (a, l) = (0.6, 1.5);
        let h = a * 3f64.sqrt() / 2.0;
        let tri = [[0.0, 0.0], [a, 0.0], [0.5 * a, h]];
        let pts: Vec<[f64; 3]> = [0.0, l].iter().flat_map(|&z| tri.iter().map(move |p| [p[0], p[1], z])).collect();
        let v = Volume::of(&Polyhedron::hull(&pts, 1e-9).unwrap());
        let vol = 0.5 * a * h * l;
        assert!(close(v.volume, vol, 1e-14));
        assert!((v.centroid[0] - 0.5 * a).abs() <= 1e-15 && (v.centroid[1] - h / 3.0).abs() <= 1e-15 && (v.centroid[2] - 0.5 * l).abs() <= 1e-15);
        let across = vol * (a * a / 24.0 + l * l / 12.0);
        assert!(close_tensor(v.inertia, diag([across, across, vol * a * a / 12.0]), 1e-12), "{:?}", v.inertia);
    }

    proptest! {
        // a block turned and moved: its volume is the same, its centroid moves with it and its
        // inertia tensor turns, R J R^T
        #[test]
        fn volume_properties_follow_a_rigid_motion(ax in -1.0f64..1.0, ay in -1.0f64..1.0, az in -1.0f64..1.0, angle in 0.0f64..6.3, t in proptest::array::uniform3(-100.0f64..100.0), k in 3usize..9) {
            let len = (ax * ax + ay * ay + az * az).sqrt();
            prop_assume!(len > 0.1);
            let u = [ax / len, ay / len, az / len];
            let (s, c) = angle.sin_cos();
            // Rodrigues' rotation matrix
            let r: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| {
                let eps = |i: usize, j: usize, k: usize| -> f64 { ((i as i64 - j as i64) * (j as i64 - k as i64) * (k as i64 - i as i64)) as f64 / 2.0 };
                let cross_ij: f64 = (0..3).map(|k| -eps(i, j, k) * u[k]).sum();
                (if i == j { c } else { 0.0 }) + (1.0 - c) * u[i] * u[j] + s * cross_ij
            }));
            let turn = |p: [f64; 3]| -> [f64; 3] { std::array::from_fn(|i| (0..3).map(|j| r[i][j] * p[j]).sum::<f64>() + t[i]) };
            // a pyramid over a regular k-gon, off centre
            let mut pts: Vec<[f64; 3]> = (0..k).map(|i| { let a = 2.0 * std::f64::consts::PI * i as f64 / k as f64; [0.3 + a.cos(), -0.2 + 0.8 * a.sin(), 0.1] }).collect();
            pts.push([0.5, 0.4, 1.3]);
            let block = Polyhedron::hull(&pts, 1e-9).unwrap();
            let (v0, v1) = (Volume::of(&block), Volume::of(&block.map(turn)));
            prop_assert!(close(v1.volume, v0.volume, 1e-12));
            let g = turn(v0.centroid);
            prop_assert!((0..3).all(|i| (v1.centroid[i] - g[i]).abs() <= 1e-12 * 100.0));
            let rjrt: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|a| (0..3).map(|b| r[i][a] * v0.inertia[a][b] * r[j][b]).sum::<f64>()).sum()));
            prop_assert!(close_tensor(v1.inertia, rjrt, 1e-10), "{:?} against {:?}", v1.inertia, rjrt);
        }
    }
}
