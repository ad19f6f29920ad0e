//! A block under a rigid top beam (rotation fixed), pushed by a horizontal force on the beam
//! (`top_horizontal`), with a much rougher top joint (family override): the block slides on
//! its base at H = mu_base (P + W). Rocking would need H = (2P + W) b / (2h), far above.

mod common;
use common::*;
use masonry_dem::geometry::Rect;
use masonry_dem::model::{JointLaws, LiveLoad, Model, ModelSpec, TopBeam};
use masonry_dem::results::Status;
use masonry_dem::static_solver::{solve, Control, StaticOptions};

fn model() -> Model {
    let laws = JointLaws { default: dry(0.5, 0.0, 1e10), top: Some(dry(10.0, 0.0, 1e10)), ..JointLaws::default() };
    Model::new(ModelSpec {
        blocks: vec![Rect::new(0.0, 0.0, 0.4, 0.2)],
        gravity: 10.0,
        top: Some(TopBeam { rotation_fixed: true, force: [0.0, -10_000.0] }),
        live: LiveLoad::TopHorizontal,
        joints: laws,
        ..ModelSpec::default()
    })
    .unwrap()
}

const H: f64 = 0.5 * (10_000.0 + 800.0); // N

#[test]
fn load_control() {
    let r = solve(&model(), &StaticOptions::default()).unwrap();
    assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
    assert_close(r.collapse_multiplier, H, 0.005, "horizontal force on the beam at collapse [N]");
}

#[test]
fn displacement_control_of_the_beam() {
    let opts = StaticOptions { control: Control::Displacement { max_displacement: 1e-4 }, steps: 40, ..Default::default() };
    let m = model();
    let r = solve(&m, &opts).unwrap();
    assert_eq!(r.control_block, m.top().unwrap(), "the default control point is the beam");
    assert_ne!(r.status, Status::Failed, "{:?}", r.error);
    assert_close(r.collapse_multiplier, H, 0.005, "peak horizontal force [N]");
    assert_close(*r.curve_multiplier.last().unwrap(), H, 0.005, "force on the sliding plateau [N]");
}
