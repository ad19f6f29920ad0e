//! The area properties of a convex polygon: area, centroid and polar second moment, exact (the
//! closed forms of a polygon, summed edge by edge).

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
}
