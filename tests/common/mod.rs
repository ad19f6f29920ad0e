#![allow(dead_code)]
//! Builders of the reference cases of docs/references.md.

use masonry_dem::geometry::{polygons, running_bond, FirstCourse, Rect, RunningBond};
use masonry_dem::joint::JointLaw;
use masonry_dem::model::{JointLaws, Model, ModelSpec};

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
