#![allow(dead_code)]
//! Builders of the reference cases of docs/references.md.

use masonry_dem::geometry::{polygons, running_bond, FirstCourse, Rect, RunningBond};
use masonry_dem::joint::JointLaw;
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::results::Status;

/// Dry joints with friction mu and dilatancy psi (tan), stiffness k (N/m3) normal and shear.
pub fn dry(mu: f64, psi: f64, k: f64) -> JointLaw {
    JointLaw { normal_stiffness: k, shear_stiffness: k, friction: mu, dilatancy: psi, ..JointLaw::default() }
}

/// Blocks listed explicitly, on a fixed base, g = 10, density 1000, thickness 1.
pub fn blocks_model(blocks: Vec<Rect>, law: JointLaw) -> Model {
    Model::new(ModelSpec { blocks: polygons(blocks), gravity: 10.0, joints: JointLaws::uniform(law), ..ModelSpec::default() }).unwrap()
}

/// Ferris & Tin-Loi wall with `courses` courses (6: wall 1, 10: wall 2).
pub fn ferris(courses: usize, law: JointLaw) -> Model {
    blocks_model(ferris_blocks(courses), law)
}

/// The blocks of [`ferris`].
pub fn ferris_blocks(courses: usize) -> Vec<Rect> {
    running_bond(&RunningBond {
        block_length: 0.4,
        block_height: 0.175,
        courses,
        height: None,
        length: 2.0,
        first_course: FirstCourse::Half,
        openings: vec![],
    })
    .unwrap()
}

/// Whether a limit analysis with the live load along gravity says the blocks stand under their
/// weight (`Unbounded`: any multiple of it) or not (`NoEquilibrium`); any other status fails.
pub fn stands(status: Status) -> bool {
    match status {
        Status::Unbounded => true,
        Status::NoEquilibrium => false,
        s => panic!("{s:?}"),
    }
}

/// |got - want| <= rel * |want|, with a message.
pub fn assert_close(got: f64, want: f64, rel: f64, what: &str) {
    let err = (got - want).abs() / want.abs();
    assert!(err <= rel, "{what}: got {got:.6}, reference {want:.6}, error {:.3}% > {:.3}%", 100.0 * err, 100.0 * rel);
}

/// The blocks of examples/lact3-tilting-wall.toml (its lines `  [x0, y0, x1, y1],`): a dry
/// wall with two openings and a lintel, friction tan 26 deg, g = 9.81.
pub fn lact3_blocks() -> Vec<Rect> {
    include_str!("../../examples/lact3-tilting-wall.toml")
        .lines()
        .filter(|l| l.starts_with("  ["))
        .map(|l| {
            let v: Vec<f64> = l
                .trim()
                .trim_matches(|c| c == '[' || c == ']' || c == ',')
                .split(',')
                .map(|s| s.trim().parse().unwrap())
                .collect();
            Rect::new(v[0], v[1], v[2], v[3])
        })
        .collect()
}

/// Ferris & Tin-Loi's wall 5 (61 blocks, two windows one block wide), course by course as in
/// tests/python/test_limit_analysis.py, on a fixed base, g = 10.
pub fn ferris_wall5_blocks() -> Vec<Rect> {
    let (e, u) = (vec![0.5, 1.0, 1.0, 0.5], vec![1.0; 3]);
    let (we, wu) = (vec![0.5, 0.5, -1.0, 0.5, 0.5], vec![1.0, -1.0, 1.0]);
    let window = [&wu, &we, &wu, &we, &wu];
    let mut rows: Vec<Vec<f64>> = vec![];
    for part in 0..3 {
        rows.extend([e.clone(), u.clone(), e.clone()]);
        if part < 2 {
            rows.extend(window.iter().map(|r| (*r).clone()));
        }
    }
    masonry_dem::geometry::pattern(0.4, 0.175, &rows).unwrap()
}

/// A b x d x h box standing on a slope rising towards +x at `alpha` degrees (its base along the
/// slope), on a fixed wedge under the slope, no base: dry associative joints of friction
/// `friction`, g = 10, pushed at `direction` degrees in plan.
pub fn on_slope(alpha: f64, b: f64, d: f64, h: f64, friction: f64, direction: f64) -> masonry_dem::space::Model3 {
    use masonry_dem::shape::Polyhedron;
    use masonry_dem::space::{LiveLoad3, Model3, ModelSpec3};
    let (sa, ca) = alpha.to_radians().sin_cos();
    let (s, n) = ([ca, 0.0, sa], [-sa, 0.0, ca]);
    let at = |u: f64, v: f64, w: f64| -> [f64; 3] { std::array::from_fn(|k| 2.0 + u * s[k] + w * n[k] + if k == 1 { v } else { 0.0 }) };
    let block: Vec<[f64; 3]> = (0..8).map(|i| at(if i & 1 == 1 { b } else { 0.0 }, if i & 2 == 2 { d } else { 0.0 }, if i & 4 == 4 { h } else { 0.0 })).collect();
    let block = Polyhedron::hull(&block, 1e-9).unwrap();
    // the wedge: the slope from 0.5 m before the block to 0.5 m past it, down to 1 m below its foot
    let (lo, hi) = (at(-0.5, 0.0, 0.0), at(b + 0.5, 0.0, 0.0));
    let floor = lo[2] - 1.0;
    let mut wedge = vec![];
    for y in [1.5, 2.0 + d + 0.5] {
        wedge.extend([[lo[0], y, lo[2]], [hi[0], y, hi[2]], [hi[0], y, floor], [lo[0], y, floor]]);
    }
    let wedge = Polyhedron::hull(&wedge, 1e-9).unwrap();
    Model3::new(&ModelSpec3 {
        polyhedra: vec![block],
        supports: vec![wedge],
        base: false,
        gravity: 10.0,
        joints: JointLaws::uniform(dry(friction, friction, 1e9)),
        live: LiveLoad3::HorizontalWeight { direction },
        ..ModelSpec3::default()
    })
    .unwrap()
}

/// The times at which a rotation record changes sign (interpolated).
pub fn sign_changes(times: &[f64], rot: &[f64]) -> Vec<f64> {
    (1..times.len())
        .filter(|&k| rot[k - 1] != 0.0 && rot[k - 1] * rot[k] < 0.0)
        .map(|k| times[k - 1] + (times[k] - times[k - 1]) * rot[k - 1] / (rot[k - 1] - rot[k]))
        .collect()
}

/// The two roots of det(K - lambda M) = 0 of a symmetric 2 x 2 K and diagonal M, ascending.
pub fn eig2(k11: f64, k12: f64, k22: f64, m1: f64, m2: f64) -> [f64; 2] {
    // m1 m2 l^2 - (k11 m2 + k22 m1) l + (k11 k22 - k12^2) = 0
    let (a, b, c) = (m1 * m2, -(k11 * m2 + k22 * m1), k11 * k22 - k12 * k12);
    let disc = (b * b - 4.0 * a * c).sqrt();
    // the smaller root from the product of the roots, without cancellation
    let big = (-b + disc) / (2.0 * a);
    [c / (a * big), big]
}

/// A vault's model (blocks and supports from a generator): on its supports, or on the base if it
/// has none (on piers), dry joints of friction `mu`, g = 10, pushed at `direction` deg in plan.
pub fn vault_model(v: masonry_dem::space::Vaulted, mu: f64, direction: f64) -> masonry_dem::space::Model3 {
    use masonry_dem::space::{LiveLoad3, Model3, ModelSpec3};
    let base = v.supports.is_empty();
    Model3::new(&ModelSpec3 {
        polyhedra: v.blocks,
        supports: v.supports,
        base,
        gravity: 10.0,
        joints: JointLaws::uniform(dry(mu, mu, 1e9)),
        live: LiveLoad3::HorizontalWeight { direction },
        ..ModelSpec3::default()
    })
    .unwrap()
}

/// The coefficients (c0, c1, c2) of the least-squares quadratic through `pts`.
pub fn quadratic(pts: &[(f64, f64)]) -> [f64; 3] {
    let mut m = [[0.0; 4]; 3];
    for &(t, y) in pts {
        let p = [1.0, t, t * t];
        for i in 0..3 {
            for j in 0..3 {
                m[i][j] += p[i] * p[j];
            }
            m[i][3] += p[i] * y;
        }
    }
    for i in 0..3 {
        let pivot = m[i];
        for (r, row) in m.iter_mut().enumerate() {
            if r != i {
                let f = row[i] / pivot[i];
                for (x, p) in row.iter_mut().zip(pivot) {
                    *x -= f * p;
                }
            }
        }
    }
    [m[0][3] / m[0][0], m[1][3] / m[1][1], m[2][3] / m[2][2]]
}
