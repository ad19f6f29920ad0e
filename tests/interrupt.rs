//! Stopping a run from the monitor: between Newton iterations the static solver polls the
//! monitor (at most every 0.1 s, `Progress::poll`), so a long step can be stopped; a stop is
//! final, and polls are not steps.

use masonry_dem::geometry::{polygons, running_bond, FirstCourse, RunningBond};
use masonry_dem::joint::JointLaw;
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::results::Status;
use masonry_dem::static_solver::{solve_with, StaticOptions};
use masonry_dem::Error;

#[test]
fn a_poll_that_says_stop_stops_the_static_solver() {
    // 1,040 blocks: a step near collapse takes tenths of a second, so polls come
    let blocks = running_bond(&RunningBond {
        block_length: 0.4,
        block_height: 0.175,
        courses: 32,
        height: None,
        length: 12.8,
        first_course: FirstCourse::Half,
        openings: vec![],
    })
    .unwrap();
    let law = JointLaw { friction: 0.65, dilatancy: 0.65, ..JointLaw::default() };
    let model = Model::new(ModelSpec { blocks: polygons(blocks), gravity: 10.0, joints: JointLaws::uniform(law), ..ModelSpec::default() }).unwrap();
    let (mut steps, mut polls) = (0, 0);
    let r = solve_with(&model, &StaticOptions::default(), &mut |p| {
        if p.poll {
            polls += 1;
            false
        } else {
            steps += 1;
            true
        }
    })
    .unwrap();
    assert_eq!(polls, 1, "the stop is final: no poll after it");
    assert_eq!(r.status, Status::Interrupted);
    assert_eq!(r.error.as_deref(), Some(Error::Interrupted.to_string().as_str()));
    assert_eq!(steps, r.steps, "every converged step reported once, polls aside");
    assert_eq!(r.curve_multiplier.len(), r.steps);
}
