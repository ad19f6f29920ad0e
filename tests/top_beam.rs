//! A block under a rigid top beam (rotation fixed), pushed by a horizontal force on the beam
//! (`top_horizontal`), with a much rougher top joint (family override): the block slides on
//! its base at H = mu_base (P + W). Rocking would need H = (2P + W) b / (2h), far above.

mod common;
use common::*;
use masonry_dem::geometry::{polygons, Rect};
use masonry_dem::model::{JointLaws, LiveLoad, Model, ModelSpec, TopBeam};
use masonry_dem::results::Status;
use masonry_dem::static_solver::{solve, Control, StaticOptions};

fn model() -> Model {
    let laws = JointLaws { default: dry(0.5, 0.0, 1e10), top: Some(dry(10.0, 0.0, 1e10)), ..JointLaws::default() };
    Model::new(ModelSpec {
        blocks: vec![Rect::new(0.0, 0.0, 0.4, 0.2).into()],
        gravity: 10.0,
        top: Some(TopBeam { rotation_fixed: true, force: [0.0, -10_000.0], vertical_held: false }),
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

/// The block of `model()` with associative flow on its base (dilatancy = friction = 0.5): sliding
/// dilates the joint. With the beam free to rise, the vertical force stays P and the block slides
/// at H = mu (P + W). With the beam's vertical position held, the dilation compresses the block
/// between base and beam: the beam's reaction N grows with the slip, the block slides at every
/// step at H = mu (N + W), and the beam does not move vertically.
fn dilatant(vertical_held: bool) -> Model {
    let laws = JointLaws { default: dry(0.5, 0.5, 1e10), top: Some(dry(10.0, 0.0, 1e10)), ..JointLaws::default() };
    Model::new(ModelSpec {
        blocks: vec![Rect::new(0.0, 0.0, 0.4, 0.2).into()],
        gravity: 10.0,
        top: Some(TopBeam { rotation_fixed: true, force: [0.0, -10_000.0], vertical_held }),
        live: LiveLoad::TopHorizontal,
        joints: laws,
        ..ModelSpec::default()
    })
    .unwrap()
}

#[test]
fn a_held_beam_takes_the_dilation_of_a_sliding_joint() {
    // 20 um of slip: the elastic shear displacement at sliding is about 1.4 um
    let opts = StaticOptions { control: Control::Displacement { max_displacement: 2e-5 }, steps: 40, ..Default::default() };
    let free = solve(&dilatant(false), &opts).unwrap();
    assert_ne!(free.status, Status::Failed, "{:?}", free.error);
    assert_close(*free.curve_multiplier.last().unwrap(), H, 0.005, "sliding force, free beam [N]");

    let m = dilatant(true);
    let held = solve(&m, &opts).unwrap();
    assert_ne!(held.status, Status::Failed, "{:?}", held.error);
    let t = m.top().unwrap();
    let dead = solve(&m, &StaticOptions { control: Control::Displacement { max_displacement: 1e-15 }, steps: 1, ..Default::default() }).unwrap();
    assert_eq!(held.displacements[t][1], dead.displacements[t][1], "the held beam moved vertically");
    // the beam's reaction: the normal force of its joint with the block
    let n: f64 = m
        .interfaces()
        .iter()
        .zip(&held.interface_forces)
        .filter(|(it, _)| it.a == t || it.b == t)
        .map(|(_, f)| -f[0])
        .sum();
    assert!(n > 1.5 * 10_000.0, "the held beam's reaction {n} N has not grown with the dilation");
    let h = *held.curve_multiplier.last().unwrap();
    assert_close(h, 0.5 * (n + 800.0), 0.005, "sliding force on the base under the held beam [N]");
}

#[test]
fn the_explicit_solver_holds_the_beam_too() {
    use masonry_dem::explicit::{solve as solve_explicit, ExplicitOptions};
    let m = dilatant(true);
    let opts = ExplicitOptions { control: Control::Displacement { max_displacement: 2e-5 }, steps: 20, ..Default::default() };
    let r = solve_explicit(&m, &opts).unwrap();
    assert_ne!(r.status, Status::Failed, "{:?}", r.error);
    let t = m.top().unwrap();
    let n: f64 = m
        .interfaces()
        .iter()
        .zip(&r.interface_forces)
        .filter(|(it, _)| it.a == t || it.b == t)
        .map(|(_, f)| -f[0])
        .sum();
    assert!(n > 1.5 * 10_000.0, "the held beam's reaction {n} N has not grown with the dilation");
    // quasi-static to the unbalanced-force ratio 1e-5 of the explicit solver
    assert_close(*r.curve_multiplier.last().unwrap(), 0.5 * (n + 800.0), 0.01, "sliding force under the held beam, explicit [N]");
}

/// Found by a property test: three 1 m courses (blocks of 0.25, 0.5, 0.25 and 0.5, 0.5 m wide,
/// 0.5 m high), mu = 0.5, psi = 0, under a free beam of 1 N. The first load step fails; the
/// load stepping then never let the step grow again and crawled (steps = 30: "no collapse
/// bracket after 4,000 attempts"; steps = 200: 6,626 steps to a premature 0.2593). Static load
/// control must find the collapse that the explicit solver finds, independently, within 1%.
#[test]
fn load_steps_grow_again_after_an_early_cut() {
    use masonry_dem::explicit::{solve as solve_explicit, ExplicitOptions};
    let r = |x0: f64, y0: f64, x1: f64, y1: f64| Rect::new(x0, y0, x1, y1);
    let blocks = vec![
        r(0.0, 0.0, 0.25, 0.5),
        r(0.25, 0.0, 0.75, 0.5),
        r(0.75, 0.0, 1.0, 0.5),
        r(0.0, 0.5, 0.5, 1.0),
        r(0.5, 0.5, 1.0, 1.0),
        r(0.0, 1.0, 0.25, 1.5),
        r(0.25, 1.0, 0.75, 1.5),
        r(0.75, 1.0, 1.0, 1.5),
    ];
    let m = Model::new(ModelSpec {
        blocks: polygons(blocks),
        gravity: 9.81,
        top: Some(TopBeam { rotation_fixed: false, force: [0.0, -1.0], vertical_held: false }),
        joints: JointLaws::uniform(dry(0.5, 0.0, 1e10)),
        ..ModelSpec::default()
    })
    .unwrap();
    let e = solve_explicit(&m, &ExplicitOptions::default()).unwrap();
    assert_eq!(e.status, Status::Collapse, "{:?}", e.error);
    for steps in [30, 200] {
        let s = solve(&m, &StaticOptions { steps, ..Default::default() }).unwrap();
        assert_eq!(s.status, Status::Collapse, "steps = {steps}: {:?}", s.error);
        assert!(s.steps < 3000, "steps = {steps}: {} load steps", s.steps);
        assert_close(s.collapse_multiplier, e.collapse_multiplier, 0.01, "static against explicit collapse multiplier");
    }
}
