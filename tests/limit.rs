//! Limit analysis against closed forms, the exact values of Ferris & Tin-Loi's walls
//! (docs/references.md, section 2: 0.6429 and 0.5800 with psi = phi), and the statuses of walls
//! that cannot stand or cannot fail. The comparison with an independent LP solver is in
//! tests/python/test_limit_analysis.py.

mod common;
use common::*;
use masonry_dem::geometry::Rect;
use masonry_dem::joint::JointLaw;
use masonry_dem::limit::{limit_analysis, LimitOptions};
use masonry_dem::results::Status;

fn limit(model: &masonry_dem::Model) -> masonry_dem::Results {
    limit_analysis(model, &LimitOptions::default()).unwrap()
}

fn collapse(model: &masonry_dem::Model) -> f64 {
    let r = limit(model);
    assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
    let c = r.certificate.unwrap();
    assert!(c.primal_residual <= 1e-8 && c.dual_residual <= 1e-8 && c.duality_gap <= 1e-8, "{c:?}");
    r.collapse_multiplier
}

#[test]
fn single_blocks_slide_at_mu_and_rock_at_b_over_h() {
    let slide = blocks_model(vec![Rect::new(0.0, 0.0, 0.4, 0.175)], dry(0.65, 0.65, 1e10));
    assert_close(collapse(&slide), 0.65, 1e-7, "sliding block");
    let rock = blocks_model(vec![Rect::new(0.0, 0.0, 0.2, 0.6)], dry(0.65, 0.65, 1e10));
    assert_close(collapse(&rock), 1.0 / 3.0, 1e-7, "rocking block");
}

#[test]
fn a_stack_turns_at_b_over_its_height() {
    let blocks = (0..3).map(|k| Rect::new(0.0, 0.5 * k as f64, 0.3, 0.5 * (k + 1) as f64)).collect();
    let m = blocks_model(blocks, dry(0.65, 0.65, 1e10));
    assert_close(collapse(&m), 0.2, 1e-7, "stack of three");
}

#[test]
fn cohesion_adds_c_a_over_w_to_sliding() {
    // 0.4 x 0.175 m block, 1000 kg/m3, g = 10: W = 700 N; c A = 100 Pa * 0.4 m2 = 40 N
    let law = JointLaw { cohesion: 100.0, ..dry(0.3, 0.3, 1e10) };
    let m = blocks_model(vec![Rect::new(0.0, 0.0, 0.4, 0.175)], law);
    let w = 1000.0 * 0.4 * 0.175 * 10.0;
    assert_close(collapse(&m), 0.3 + 40.0 / w, 1e-7, "cohesive sliding");
}

#[test]
fn ferris_tin_loi_walls_at_their_exact_multipliers() {
    assert_close(collapse(&ferris(6, dry(0.65, 0.65, 1e10))), 0.6429, 1e-4, "wall 1");
    assert_close(collapse(&ferris(10, dry(0.65, 0.65, 1e10))), 0.5800, 1e-4, "wall 2");
}

#[test]
fn the_non_associative_estimate_lies_below_the_associative_bound() {
    // dilatancy below friction: an estimate (neither bound), never a collapse; its value in last_equilibrium
    let r = limit(&ferris(6, dry(0.65, 0.0, 1e10)));
    assert_eq!(r.status, Status::Estimate, "{:?}", r.error);
    assert!(r.collapse_multiplier.is_nan());
    let c = r.certificate.unwrap();
    assert_close(c.upper_bound, 0.6429, 1e-4, "associative bound");
    assert!(c.sequence >= 1);
    assert_eq!(c.multiplier, r.last_equilibrium);
    // each program's lambda is known to the interior point's tolerance (its duality gap, relative to
    // 1 + lambda): on wall 1 the two agree to that, the estimate's mechanism being the bound's
    let accuracy = 2.0 * LimitOptions::default().tolerance * (1.0 + c.upper_bound);
    assert!(r.last_equilibrium <= c.upper_bound + accuracy, "{} above {}", r.last_equilibrium, c.upper_bound);
    assert!(r.error.unwrap().contains("is an estimate"));
}

#[test]
fn an_overhang_that_cannot_stand_has_no_equilibrium() {
    // the upper block's centroid lies beyond the edge of the block below it
    let blocks = vec![Rect::new(0.0, 0.0, 0.4, 0.2), Rect::new(0.3, 0.2, 0.9, 0.4)];
    let r = limit(&blocks_model(blocks, dry(0.65, 0.65, 1e10)));
    assert_eq!(r.status, Status::NoEquilibrium, "{:?} {}", r.error, r.collapse_multiplier);
    assert!(r.collapse_multiplier.is_nan());
}

#[test]
fn the_mechanism_moves_with_the_live_load_and_rests_on_the_base() {
    let r = limit(&ferris(6, dry(0.65, 0.65, 1e10)));
    let biggest = r.mechanism.iter().map(|v| v[0].hypot(v[1])).fold(0.0, f64::max);
    assert!((biggest - 1.0).abs() < 1e-12);
    let base = r.mechanism.len() - 1;
    assert_eq!(r.mechanism[base], [0.0; 3]);
    assert!(r.interface_states.iter().any(|&f| f != 0), "some joint opens, slides or rocks");
}

#[test]
fn a_block_wedged_under_a_held_beam_is_unbounded() {
    // sliding or rocking would lift the beam, held vertically: no mechanism at any lambda
    use masonry_dem::model::{JointLaws, Model, ModelSpec, TopBeam};
    let m = Model::new(ModelSpec {
        blocks: vec![Rect::new(0.0, 0.0, 0.4, 0.175).into()],
        gravity: 10.0,
        joints: JointLaws::uniform(dry(0.65, 0.65, 1e10)),
        top: Some(TopBeam { rotation_fixed: true, force: [0.0, -1000.0], vertical_held: true }),
        ..ModelSpec::default()
    })
    .unwrap();
    let r = limit(&m);
    assert_eq!(r.status, Status::Unbounded, "{:?} {}", r.error, r.collapse_multiplier);
    assert!(r.collapse_multiplier.is_nan());
}

#[test]
fn an_overhang_either_way_has_no_equilibrium_before_the_iteration_limit() {
    // no admissible forces balance the dead loads (pushing the upper block back would take
    // a shear of twice its weight against friction 0.65), whichever side it overhangs: the
    // interior point says so before its iteration limit
    for x0 in [0.3, -0.5] {
        let over = vec![Rect::new(0.0, 0.0, 0.4, 0.2), Rect::new(x0, 0.2, x0 + 0.6, 0.4)];
        let r = limit(&blocks_model(over, dry(0.65, 0.65, 1e10)));
        assert_eq!(r.status, Status::NoEquilibrium, "{x0}: {:?}", r.error);
        assert!(r.certificate.unwrap().iterations < 100, "{x0}: stopped by the iteration limit");
    }
}

#[test]
fn joints_without_friction_slide_at_lambda_zero() {
    // friction 0: the base takes no horizontal force and the weights stand on the frictionless
    // joints, so the wall slides at lambda = 0; Ferris & Tin-Loi's wall 1 was said to have no
    // equilibrium under its dead loads (its normal matrix singular along the courses' sliding)
    for m in [blocks_model(vec![Rect::new(0.0, 0.0, 0.4, 0.175)], dry(0.0, 0.0, 1e10)), ferris(6, dry(0.0, 0.0, 1e10))] {
        let lambda = collapse(&m);
        assert!(lambda.abs() <= 1e-8, "{lambda}");
    }
}
