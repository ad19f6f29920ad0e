//! The running-bond walls of the benchmarks (`static_scaling`, `explicit_step`) and of
//! `examples/static_collapse.rs`: 0.4 x 0.175 m blocks on a fixed base, g = 10, included by
//! `#[path]` in each (a directory, so that cargo does not take it for a benchmark). Not every includer uses every function.
#![allow(dead_code)]

use masonry_dem::geometry::{polygons, running_bond, FirstCourse, RunningBond};
use masonry_dem::joint::JointLaw;
use masonry_dem::model::{JointLaws, ModelSpec};

/// `courses` courses of `per_course` blocks (courses starting with a half block have one more),
/// with the default joints.
pub fn spec(courses: usize, per_course: usize) -> ModelSpec {
    let blocks = running_bond(&RunningBond {
        block_length: 0.4,
        block_height: 0.175,
        courses,
        height: None,
        length: 0.4 * per_course as f64,
        first_course: FirstCourse::Half,
        openings: vec![],
    })
    .expect("a valid running-bond wall");
    ModelSpec { blocks: polygons(blocks), gravity: 10.0, ..ModelSpec::default() }
}

/// A square wall (`courses` courses of `courses` blocks) of dry associative joints, mu = psi =
/// 0.65: the wall of the static benchmarks.
pub fn associative(courses: usize) -> ModelSpec {
    let law = JointLaw { friction: 0.65, dilatancy: 0.65, ..JointLaw::default() };
    ModelSpec { joints: JointLaws::uniform(law), ..spec(courses, courses) }
}
