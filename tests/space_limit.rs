//! Limit analysis in 3D against closed forms and the plane: a box that slides or overturns in
//! any direction in plan, Ferris and Tin-Loi's wall 1 extruded, a free-standing leaf that
//! overturns about its base edge.

mod common;

use common::{dry, ferris, ferris_blocks};
use masonry_dem::joint::JointLaw;
use masonry_dem::limit::{limit_analysis, limit_analysis_3d, LimitOptions};
use masonry_dem::model::JointLaws;
use masonry_dem::results::Status;
use masonry_dem::space::{running_bond_3d, Box3, LiveLoad3, Model3, ModelSpec3};

/// The limit multiplier of a 3D model; asserts a collapse.
fn lambda(model: &Model3) -> f64 {
    let r = limit_analysis_3d(model, &LimitOptions::default()).unwrap();
    assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
    r.collapse_multiplier
}

fn model(blocks: Vec<Box3>, law: JointLaw, direction: f64) -> Model3 {
    Model3::new(&ModelSpec3 {
        blocks,
        gravity: 10.0,
        joints: JointLaws::uniform(law),
        live: LiveLoad3::HorizontalWeight { direction },
        ..ModelSpec3::default()
    })
    .unwrap()
}

fn close(got: f64, want: f64, rel: f64, what: &str) {
    assert!((got - want).abs() <= rel * want.abs(), "{what}: got {got:.9}, closed form {want:.9}");
}

#[test]
fn a_box_overturns_about_its_edges_in_any_direction_in_plan() {
    // a x b x h = 0.4 x 0.6 x 1.0 m, friction strong enough: lambda = min(a / (h cos phi), b / (h sin phi))
    let (a, b, h) = (0.4, 0.6, 1.0);
    for phi in [0.0_f64, 30.0, 56.3, 90.0, 135.0, 200.0] {
        let m = model(vec![Box3::new(0.0, 0.0, 0.0, a, b, h)], dry(2.0, 2.0, 1e9), phi);
        let (c, s) = (phi.to_radians().cos().abs(), phi.to_radians().sin().abs());
        let want = (a / (h * c)).min(b / (h * s));
        close(lambda(&m), want, 1e-6, &format!("overturning at {phi} deg"));
    }
}

#[test]
fn a_box_slides_at_the_friction_coefficient_in_any_direction_in_plan() {
    // a squat box: sliding (mu = 0.3) comes before overturning (>= 2)
    for phi in [0.0, 22.5, 45.0, 90.0, 157.0] {
        let m = model(vec![Box3::new(0.0, 0.0, 0.0, 1.0, 1.2, 0.5)], dry(0.3, 0.3, 1e9), phi);
        close(lambda(&m), 0.3, 1e-6, &format!("sliding at {phi} deg"));
    }
}

#[test]
fn ferris_tin_loi_wall_1_extruded_equals_the_plane() {
    let law = dry(0.65, 0.65, 1e9);
    let rects = ferris_blocks(6);
    let plane = ferris(6, law);
    let l2 = limit_analysis(&plane, &LimitOptions::default()).unwrap().collapse_multiplier;
    let t = 0.3;
    let boxes = rects.iter().map(|r| Box3::new(r.x0, 0.0, r.y0, r.x1, t, r.y1)).collect();
    let l3 = lambda(&model(boxes, law, 0.0));
    close(l3, l2, 1e-6, "wall 1 extruded");
    close(l3, 0.642857, 1e-5, "wall 1 extruded against the published 0.6429");
}

#[test]
fn a_free_standing_leaf_overturns_about_its_base_edge_at_t_over_h() {
    // 2 m x 1.05 m, 0.1 m thick, running bond, pushed out of its plane: lambda = t / H
    let (t, h) = (0.1, 1.05);
    let blocks = running_bond_3d(2.0, h, t, 0.4, 0.175, 0.2).unwrap();
    let r = limit_analysis_3d(&model(blocks, dry(0.7, 0.7, 1e9), 90.0), &LimitOptions::default()).unwrap();
    close(r.collapse_multiplier, t / h, 1e-6, "leaf out of plane");
    // the mechanism: every block turns about the x axis alike, the base edge at rest
    let rx: Vec<f64> = r.mechanism.iter().take(r.mechanism.len() - 1).map(|v| v[3]).collect();
    assert!(rx.iter().all(|w| (w - rx[0]).abs() <= 1e-6 * rx[0].abs() && w.abs() > 0.0), "{rx:?}");
}
