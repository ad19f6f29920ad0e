//! Limit analysis along a mechanism: the large-displacement capacity curve lambda(d) against
//! closed forms.

use masonry_dem::geometry::Rect;
use masonry_dem::joint::JointLaw;
use masonry_dem::limit::{follow_mechanism, FollowOptions, LimitOptions};
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::results::{Results, Status};
use masonry_dem::shape::Polygon;

fn law(friction: f64) -> JointLaws {
    JointLaws::uniform(JointLaw { friction, dilatancy: friction, ..JointLaw::default() })
}

/// The rotation theta (clockwise) of a block of base b and height h about its right toe that
/// moves its centroid by `d` along x: d = b/2 (1 - cos theta) + h/2 sin theta, increasing on
/// [0, pi/2], inverted by bisection.
fn rotation_of(d: f64, b: f64, h: f64) -> f64 {
    let f = |t: f64| 0.5 * b * (1.0 - t.cos()) + 0.5 * h * t.sin() - d;
    let (mut lo, mut hi) = (0.0, std::f64::consts::FRAC_PI_2);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            hi = mid
        } else {
            lo = mid
        }
    }
    0.5 * (lo + hi)
}

/// The model of `spec` analysed along its mechanism by steps of `step` \[m\]: a collapse at
/// `lambda0` (to 1e-9) whose curve reaches its end, in at least ten steps.
fn followed(spec: ModelSpec, step: f64, lambda0: f64) -> Results {
    let model = Model::new(spec).unwrap();
    let follow = FollowOptions { step, max_steps: 1000 };
    let r = follow_mechanism(&model, &LimitOptions::default(), &follow, &mut |_| true).unwrap();
    assert_eq!(r.status, Status::Collapse);
    assert!(r.error.is_none(), "{:?}", r.error);
    assert!((r.collapse_multiplier - lambda0).abs() < 1e-9);
    assert!(r.curve_multiplier.len() >= 11, "{} points", r.curve_multiplier.len());
    r
}

/// One block pushed at its centroid by lambda times its weight turns about its toe:
/// lambda(theta) = tan(alpha - theta), alpha = atan(b / h), on the geometry moved by theta
/// (the toe a point contact). On the base (the toe at the base's corner: two vertices at one
/// point) and on a wider support (the toe on the inside of its top edge).
#[test]
fn a_block_turning_about_its_toe_follows_tan_alpha_minus_theta() {
    let (b, h): (f64, f64) = (0.4, 1.0);
    let alpha = (b / h).atan();
    let block: Polygon = Rect::new(0.0, 0.0, b, h).into();
    let on_base = ModelSpec { blocks: vec![block.clone()], joints: law(5.0), ..ModelSpec::default() };
    let on_support = ModelSpec {
        blocks: vec![block],
        supports: vec![Rect::new(-1.0, -0.5, 2.0, 0.0).into()],
        base: false,
        joints: law(5.0),
        ..ModelSpec::default()
    };
    for spec in [on_base, on_support] {
        // steps of at most 0.03 m at the block's farthest vertex: about 2.4 degrees
        let r = followed(spec, 0.03, b / h);
        let n = r.curve_multiplier.len();
        for (&d, &lam) in r.curve_displacement.iter().zip(&r.curve_multiplier) {
            let theta = rotation_of(d, b, h);
            assert!((lam - (alpha - theta).tan()).abs() < 1e-6, "d = {d}: lambda {lam} against {}", (alpha - theta).tan());
        }
        // the curve ends where lambda reaches zero: theta = alpha
        let last = rotation_of(r.curve_displacement[n - 1], b, h);
        assert!(r.curve_multiplier[n - 1] <= 1e-3 * r.collapse_multiplier && (last - alpha).abs() < 1e-3);
        // the block's own rotation at the end, clockwise
        assert!((r.displacements[0][2] + last).abs() < 1e-9);
    }
}

/// A portal frame: two columns b x h on the base and a lintel resting on them, pushed by lambda
/// times each block's weight. The columns rock about their toes and the lintel rides, without
/// turning, on their top inner corners: every block's centroid moves as a point of a column at
/// the angle alpha from the toe's vertical, so lambda(theta) = tan(alpha - theta) as for one
/// column, whatever the lintel's weight (the rocking frame of Makris and Vassiliou 2013). Three
/// blocks and four point hinges, found again at each step.
#[test]
fn a_rocking_portal_frame_follows_tan_alpha_minus_theta() {
    let (b, h, span): (f64, f64, f64) = (0.4, 2.0, 2.0);
    let alpha = (b / h).atan();
    let blocks: Vec<Polygon> =
        vec![Rect::new(0.0, 0.0, b, h).into(), Rect::new(span - b, 0.0, span, h).into(), Rect::new(0.0, h, span, h + 0.4).into()];
    let r = followed(ModelSpec { blocks, joints: law(5.0), ..ModelSpec::default() }, 0.04, b / h);
    let n = r.curve_multiplier.len();
    // the control block's horizontal displacement against theta: a column's centroid, or the
    // lintel's, which moves as the column's top inner corner
    let theta_of = |d: f64| if r.control_block == 2 { rotation_of(d, 2.0 * b, 2.0 * h) } else { rotation_of(d, b, h) };
    for (&d, &lam) in r.curve_displacement.iter().zip(&r.curve_multiplier) {
        let theta = theta_of(d);
        assert!((lam - (alpha - theta).tan()).abs() < 1e-6, "d = {d}: lambda {lam} against {}", (alpha - theta).tan());
    }
    let last = theta_of(r.curve_displacement[n - 1]);
    assert!(r.curve_multiplier[n - 1] <= 1e-3 * r.collapse_multiplier && (last - alpha).abs() < 1e-3);
    // both columns turned clockwise by theta, the lintel not turned
    for (i, turn) in [(0, -last), (1, -last), (2, 0.0)] {
        assert!((r.displacements[i][2] - turn).abs() < 1e-6, "block {i}: {:?}", r.displacements[i]);
    }
}

/// The same block pushed by the explicit solver under displacement control with finite
/// rotations (dry joints, no dilatancy): its quasi-static curve on the moved geometry follows
/// lambda(theta) = tan(alpha - theta) within 2% of lambda(theta) at every stage up to theta =
/// 0.9 alpha (theta from the centroid's travel about the toe, and the block's own rotation
/// at the end within 1% of it); with the linearized kinematics it stays at lambda0.
#[test]
fn the_explicit_solver_pushing_one_block_follows_tan_alpha_minus_theta() {
    use masonry_dem::analysis::Control;
    use masonry_dem::explicit::{solve, ExplicitOptions};
    let (b, h): (f64, f64) = (0.4, 1.0);
    let alpha = (b / h).atan();
    let dry = JointLaws::uniform(JointLaw { friction: 5.0, dilatancy: 0.0, ..JointLaw::default() });
    let spec = ModelSpec { blocks: vec![Rect::new(0.0, 0.0, b, h).into()], joints: dry, ..ModelSpec::default() };
    let model = Model::new(spec).unwrap();
    // the centroid's travel at theta = 0.9 alpha, in 40 stages
    let theta_end = 0.9 * alpha;
    let d_end = 0.5 * b * (1.0 - theta_end.cos()) + 0.5 * h * theta_end.sin();
    let opts = ExplicitOptions { control: Control::Displacement { max_displacement: d_end }, steps: 200, large_rotations: true, ..ExplicitOptions::default() };
    let r = solve(&model, &opts).unwrap();
    assert_eq!(r.curve_multiplier.len(), 201);
    let mut worst: f64 = 0.0;
    for (&d, &lam) in r.curve_displacement.iter().zip(&r.curve_multiplier).skip(1) {
        let exact = (alpha - rotation_of(d, b, h)).tan();
        worst = worst.max((lam - exact).abs() / exact);
    }
    eprintln!("worst relative difference {worst:.3e}; end rotation {} against {theta_end}", -r.displacements[0][2]);
    assert!(worst < 0.02, "worst relative difference {worst}");
    assert!((-r.displacements[0][2] - theta_end).abs() < 0.01 * theta_end);
    // the linearized kinematics: lambda stays at b / h
    let small = solve(&model, &ExplicitOptions { large_rotations: false, ..opts }).unwrap();
    let last = *small.curve_multiplier.last().unwrap();
    assert!((last - b / h).abs() < 0.02 * b / h, "{last}");
}
