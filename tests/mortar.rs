//! Mortar joints (cohesion): a block slides at mu + c A / W while that is below b / h, and the
//! joint that failed has lost its cohesion and tensile strength.

mod common;
use common::*;
use masonry_dem::geometry::Rect;
use masonry_dem::joint::JointLaw;
use masonry_dem::results::Status;
use masonry_dem::static_solver::{solve, StaticOptions};

#[test]
fn block_with_cohesion_slides_at_mu_plus_ca_over_w() {
    // 0.4 x 0.175 block, thickness 1, density 1000, g = 10: W = 700 N; base joint A = 0.4 m2.
    let c = 100.0; // Pa: c A / W = 40 / 700 = 0.0571
    let law = JointLaw {
        cohesion: c,
        tensile_strength: 0.0,
        ..dry(0.65, 0.0, 1e10)
    };
    let m = blocks_model(vec![Rect::new(0.0, 0.0, 0.4, 0.175)], law);
    let w = 0.4 * 0.175 * 1000.0 * 10.0;
    let expected = 0.65 + c * 0.4 / w;
    assert!(expected < 0.4 / 0.175, "the case must slide, not rock");
    let r = solve(&m, &StaticOptions::default()).unwrap();
    assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
    assert_close(
        r.collapse_multiplier,
        expected,
        0.005,
        "sliding with cohesion",
    );
    // at the last equilibrium the joint is still intact (it fails just beyond)
    assert!(!r.broken[0]);
}

#[test]
fn failed_joint_keeps_only_friction() {
    // A block pushed sideways past the failure of its base joint (displacement control): the
    // joint is broken and its shear capacity is mu |N|.
    let law = JointLaw {
        cohesion: 500.0,
        ..dry(0.65, 0.0, 1e10)
    };
    let m = blocks_model(vec![Rect::new(0.0, 0.0, 0.4, 0.175)], law);
    let r = solve(
        &m,
        &StaticOptions {
            control: masonry_dem::static_solver::Control::Displacement {
                max_displacement: 1e-4,
            },
            steps: 50,
            ..Default::default()
        },
    )
    .unwrap();
    assert_ne!(r.status, Status::Failed, "{:?}", r.error);
    assert!(r.broken[0], "the base joint should have failed");
    let [n, t, _] = r.interface_forces[0];
    assert_close(
        t.abs(),
        0.65 * n.abs(),
        1e-6,
        "shear of the failed joint against mu |N|",
    );
    // after the failure only friction is left (the brittle peak mu + cA/W is checked under
    // load control above: here the joint breaks within the first displacement step)
    assert_close(
        *r.curve_multiplier.last().unwrap(),
        0.65,
        0.005,
        "residual friction after failure",
    );
}
