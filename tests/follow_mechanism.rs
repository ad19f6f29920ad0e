//! Limit analysis along a mechanism: the large-displacement capacity curve lambda(d) against
//! closed forms, in the plane and in 3D (boxes and polyhedra turning about hinge edges).

use masonry_dem::geometry::Rect;
use masonry_dem::joint::JointLaw;
use masonry_dem::limit::{follow_mechanism, follow_mechanism_3d, FollowOptions, LimitOptions};
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::results::{Results, Status};
use masonry_dem::shape::{Polygon, Polyhedron};
use masonry_dem::space::{Box3, LiveLoad3, Model3, ModelSpec3};

fn law(friction: f64) -> JointLaws {
    JointLaws::uniform(JointLaw { friction, dilatancy: friction, ..JointLaw::default() })
}

/// The rotation theta (clockwise) of a block of base b and height h about its right toe that
/// moves its centroid by `d` along x (in 3D along the push): d = b/2 (1 - cos theta) + h/2 sin theta, increasing on
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

/// The model of `spec` analysed along its mechanism by steps of `step` \[m\]: a collapse at
/// `lambda0` (to 1e-7) whose curve reaches its end, in at least ten steps.
fn followed_3d(spec: &ModelSpec3, step: f64, lambda0: f64) -> (Model3, Results<[f64; 6]>) {
    let model = Model3::new(spec).unwrap();
    let follow = FollowOptions { step, max_steps: 1000 };
    let r = follow_mechanism_3d(&model, &LimitOptions::default(), &follow, &mut |_| true).unwrap();
    assert_eq!(r.status, Status::Collapse);
    assert!(r.error.is_none(), "{:?}", r.error);
    assert!((r.collapse_multiplier - lambda0).abs() < 1e-7, "{} against {lambda0}", r.collapse_multiplier);
    assert!(r.curve_multiplier.len() >= 11, "{} points", r.curve_multiplier.len());
    (model, r)
}

/// lambda(theta) = tan(alpha - theta) at every point of the curve, theta from the control
/// displacement by `theta_of`, to 1e-6; the curve's end at theta = alpha (1e-3); returns theta
/// at the end.
fn tan_alpha_minus_theta(r: &Results<[f64; 6]>, alpha: f64, theta_of: impl Fn(f64) -> f64) -> f64 {
    for (&d, &lam) in r.curve_displacement.iter().zip(&r.curve_multiplier) {
        let theta = theta_of(d);
        assert!((lam - (alpha - theta).tan()).abs() < 1e-6, "d = {d}: lambda {lam} against {}", (alpha - theta).tan());
    }
    let n = r.curve_multiplier.len();
    let last = theta_of(r.curve_displacement[n - 1]);
    assert!(r.curve_multiplier[n - 1] <= 1e-3 * r.collapse_multiplier && (last - alpha).abs() < 1e-3, "end at {last}");
    last
}

/// Rodrigues' rotation of `x` by the rotation vector `w`.
fn rotate(w: [f64; 3], x: [f64; 3]) -> [f64; 3] {
    let t = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
    if t == 0.0 {
        return x;
    }
    let k = w.map(|v| v / t);
    let kx = [k[1] * x[2] - k[2] * x[1], k[2] * x[0] - k[0] * x[2], k[0] * x[1] - k[1] * x[0]];
    let kd = k[0] * x[0] + k[1] * x[1] + k[2] * x[2];
    std::array::from_fn(|i| x[i] * t.cos() + kx[i] * t.sin() + k[i] * kd * (1.0 - t.cos()))
}

/// Each vertex of block `i` of `model` moved by its finite motion in `r` against the same vertex
/// turned by `theta` about the axis `axis` (a unit vector) through `toe`, to `tol`.
fn turned_about(model: &Model3, r: &Results<[f64; 6]>, i: usize, toe: [f64; 3], axis: [f64; 3], theta: f64, tol: f64) {
    let m = r.displacements[i];
    let c = model.centroids()[i];
    for &p in model.shapes()[i].vertices() {
        let arm = rotate([m[3], m[4], m[5]], [p[0] - c[0], p[1] - c[1], p[2] - c[2]]);
        let moved: [f64; 3] = std::array::from_fn(|k| c[k] + m[k] + arm[k]);
        let about = rotate(axis.map(|v| v * theta), [p[0] - toe[0], p[1] - toe[1], p[2] - toe[2]]);
        let exact: [f64; 3] = std::array::from_fn(|k| toe[k] + about[k]);
        let err = (0..3).map(|k| (moved[k] - exact[k]).abs()).fold(0.0, f64::max);
        assert!(err < tol, "block {i}, vertex {p:?}: {moved:?} against {exact:?}");
    }
}

/// One box b x w x h pushed at its centroid by lambda times its weight along x turns about its
/// toe edge: lambda(theta) = tan(alpha - theta), alpha = atan(b / h), on the geometry moved by
/// theta (the toe a contact along an edge, two corners), and the box's vertices turned exactly
/// about the toe edge (the y axis through (b, 0, 0)).
#[test]
fn a_box_turning_about_its_toe_edge_follows_tan_alpha_minus_theta() {
    let (b, w, h): (f64, f64, f64) = (0.6, 0.4, 1.5);
    let alpha = (b / h).atan();
    let spec = ModelSpec3 { blocks: vec![Box3::new(0.0, 0.0, 0.0, b, w, h)], joints: law(5.0), ..ModelSpec3::default() };
    // steps of at most 0.05 m at the box's farthest vertex: about 1.8 degrees
    let (model, r) = followed_3d(&spec, 0.05, b / h);
    let last = tan_alpha_minus_theta(&r, alpha, |d| rotation_of(d, b, h));
    turned_about(&model, &r, 0, [b, 0.0, 0.0], [0.0, 1.0, 0.0], last, 1e-9);
}

/// The same box turned by 30 degrees in plan (a polyhedron: the hull of its vertices) and pushed
/// at 30 degrees, across its toe edge: the same curve along the push, the box turned about its
/// toe edge; and a block with a gable top (a prism whose section is a pentagon), whose
/// centroid's height and offset from the toe give the closed form.
#[test]
fn a_turned_box_pushed_at_30_degrees_and_a_polyhedron_follow_their_closed_forms() {
    let (b, w, h): (f64, f64, f64) = (0.6, 0.4, 1.5);
    let alpha = (b / h).atan();
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let plan = |x: f64, y: f64| [c * x - s * y, s * x + c * y];
    let corners: Vec<[f64; 3]> = (0..8)
        .map(|k| {
            let p = plan(if k & 1 == 1 { b } else { 0.0 }, if k & 2 == 2 { w } else { 0.0 });
            [p[0], p[1], if k & 4 == 4 { h } else { 0.0 }]
        })
        .collect();
    let turned = Polyhedron::hull(&corners, 1e-9).unwrap();
    let spec = ModelSpec3 {
        polyhedra: vec![turned],
        joints: law(5.0),
        live: LiveLoad3::HorizontalWeight { direction: 30.0 },
        ..ModelSpec3::default()
    };
    let (model, r) = followed_3d(&spec, 0.05, b / h);
    let last = tan_alpha_minus_theta(&r, alpha, |d| rotation_of(d, b, h));
    let toe = plan(b, 0.0);
    let axis = plan(0.0, 1.0);
    turned_about(&model, &r, 0, [toe[0], toe[1], 0.0], [axis[0], axis[1], 0.0], last, 1e-9);

    // a prism along y whose section is the pentagon (0, 0), (b, 0), (b, h), (b/2, h + t), (0, h):
    // a block with a gable top, turning about its toe edge; its centroid at (xc, zc) from the
    // heel gives alpha = atan((b - xc) / zc) and d = (b - xc)(1 - cos theta) + zc sin theta
    let t = 0.3;
    let section = [[0.0, 0.0], [b, 0.0], [b, h], [0.5 * b, h + t], [0.0, h]];
    let gable = Polyhedron::prism(&section, [0.0, w]);
    let (area_r, area_t) = (b * h, 0.5 * b * t);
    let zc = (area_r * 0.5 * h + area_t * (h + t / 3.0)) / (area_r + area_t);
    let xc = 0.5 * b;
    let alpha = ((b - xc) / zc).atan();
    let spec = ModelSpec3 { polyhedra: vec![gable], joints: law(5.0), ..ModelSpec3::default() };
    let (model, r) = followed_3d(&spec, 0.05, (b - xc) / zc);
    let last = tan_alpha_minus_theta(&r, alpha, |d| rotation_of(d, 2.0 * (b - xc), 2.0 * zc));
    turned_about(&model, &r, 0, [b, 0.0, 0.0], [0.0, 1.0, 0.0], last, 1e-9);
}

/// A portal frame of boxes: two columns b x w x h on the base and a lintel resting on them,
/// pushed along x by lambda times each block's weight. The columns rock about their toe edges
/// and the lintel rides, without turning, on their top edges: lambda(theta) = tan(alpha - theta)
/// as for one column, whatever the lintel's weight (the plane's rocking frame in 3D). Three
/// blocks and four hinge edges, found again at each step.
#[test]
fn a_rocking_portal_frame_of_boxes_follows_tan_alpha_minus_theta() {
    let (b, w, h, span): (f64, f64, f64, f64) = (0.4, 0.5, 2.0, 2.0);
    let alpha = (b / h).atan();
    let blocks = vec![Box3::new(0.0, 0.0, 0.0, b, w, h), Box3::new(span - b, 0.0, 0.0, span, w, h), Box3::new(0.0, 0.0, h, span, w, h + 0.4)];
    let (model, r) = followed_3d(&ModelSpec3 { blocks, joints: law(5.0), ..ModelSpec3::default() }, 0.04, b / h);
    // the control block is the lintel: it moves as the columns' top inner corners
    assert_eq!(r.control_block, 2);
    let last = tan_alpha_minus_theta(&r, alpha, |d| rotation_of(d, 2.0 * b, 2.0 * h));
    // both columns turned about their toe edges by theta, the lintel translated without turning
    turned_about(&model, &r, 0, [b, 0.0, 0.0], [0.0, 1.0, 0.0], last, 1e-6);
    turned_about(&model, &r, 1, [span, 0.0, 0.0], [0.0, 1.0, 0.0], last, 1e-6);
    let lintel = r.displacements[2];
    assert!(lintel[3..].iter().all(|v| v.abs() < 1e-6), "the lintel turned: {lintel:?}");
    let ride = [h * last.sin() + b * (1.0 - last.cos()), h * (last.cos() - 1.0) + b * last.sin()];
    assert!((lintel[0] - ride[0]).abs() < 1e-6 && lintel[1].abs() < 1e-6 && (lintel[2] - ride[1]).abs() < 1e-6, "{lintel:?} against {ride:?}");
}

/// A leaf of 33 dry blocks in running bond (2 x 1.05 x 0.1 m) pushed out of its plane (along
/// +y): it overturns as one body about the leeward edge of its base, lambda(theta) = tan(alpha -
/// theta) with alpha = atan(t / H) from the wall's centroid, and its blocks move together (the
/// contacts between them stay polygons while the base's becomes the toe's edge).
#[test]
fn a_leaf_overturning_out_of_its_plane_follows_tan_alpha_minus_theta() {
    let (t, height) = (0.1, 1.05);
    let blocks = masonry_dem::space::running_bond_3d(2.0, height, t, 0.4, 0.175, 0.2).unwrap();
    let spec = ModelSpec3 { blocks, joints: law(0.7), live: LiveLoad3::HorizontalWeight { direction: 90.0 }, ..ModelSpec3::default() };
    let (model, r) = followed_3d(&spec, 0.01, t / height);
    // the control block, the highest (the first of them), turns about the toe edge with the wall:
    // its centroid t/2 behind the toe and zc above it
    let c = model.centroids()[r.control_block];
    let last = tan_alpha_minus_theta(&r, (t / height).atan(), |d| rotation_of(d, 2.0 * (t - c[1]), 2.0 * c[2]));
    for i in 0..model.n_wall() {
        turned_about(&model, &r, i, [0.0, t, 0.0], [-1.0, 0.0, 0.0], last, 1e-9);
    }
}
