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

#[test]
fn on_joints_without_friction_every_block_slides_at_lambda_zero() {
    // friction 0 everywhere: the base takes no horizontal force, so no multiplier but 0 balances
    // a horizontal live load (lambda W = 0), and the weights stand on the frictionless joints:
    // the wall slides at lambda = 0, whatever the direction in plan (the interior point stopped
    // at its first iteration: "did not converge in 1 iterations")
    let frictionless = dry(0.0, 0.0, 1e9);
    let leaf = running_bond_3d(2.0, 1.05, 0.1, 0.4, 0.175, 0.2).unwrap();
    for (name, blocks) in [("a box", vec![Box3::new(0.0, 0.0, 0.0, 0.4, 0.1, 0.2)]), ("a leaf", leaf.clone())] {
        for phi in [0.0_f64, 30.0, 90.0] {
            let r = limit_analysis_3d(&model(blocks.clone(), frictionless, phi), &LimitOptions::default()).unwrap();
            assert_eq!(r.status, Status::Collapse, "{name} at {phi} deg: {:?}", r.error);
            assert!(r.collapse_multiplier.abs() <= 1e-8, "{name} at {phi} deg: {}", r.collapse_multiplier);
            let c = r.certificate.unwrap();
            assert!(c.primal_residual <= 1e-8 && c.dual_residual <= 1e-8 && c.duality_gap <= 1e-8, "{c:?}");
            // a mechanism on which the live load works (the box's: sliding along it; a leaf's is one
            // of many, every motion that slides on the joints costing nothing)
            let (cos, sin) = (phi.to_radians().cos(), phi.to_radians().sin());
            let work: f64 = r.mechanism.iter().take(blocks.len()).map(|v| v[0] * cos + v[1] * sin).sum();
            assert!(work > 0.0, "{name} at {phi} deg: {:?}", r.mechanism);
            if blocks.len() == 1 {
                let v = r.mechanism[0];
                assert!((v[0] - cos).abs() <= 1e-6 && (v[1] - sin).abs() <= 1e-6 && v[2].abs() <= 1e-6, "{phi} deg: {v:?}");
            }
        }
    }
    // friction on the base alone, 0 above it: the wall above its lowest bed joints slides at 0
    // too; friction 1e-6 everywhere slides at 1e-6 (the answer is continuous at 0)
    let mut laws = JointLaws::uniform(frictionless);
    laws.base = Some(dry(0.6, 0.6, 1e9));
    let m = Model3::new(&ModelSpec3 { blocks: leaf.clone(), gravity: 10.0, joints: laws, ..ModelSpec3::default() }).unwrap();
    let r = limit_analysis_3d(&m, &LimitOptions::default()).unwrap();
    assert!(r.status == Status::Collapse && r.collapse_multiplier.abs() <= 1e-8, "{:?} {}", r.error, r.collapse_multiplier);
    close(lambda(&model(leaf, dry(1e-6, 1e-6, 1e9), 0.0)), 1e-6, 1e-4, "a leaf of friction 1e-6");
}

#[test]
fn without_a_live_load_the_analyses_that_raise_lambda_are_refused_by_name() {
    // live = "none": limit analysis and the explicit pushover have no multiplier to raise (the
    // pushover took 21,000 levels of zero load before it gave up, "no collapse bracket", and
    // limit analysis said its interior point "did not converge in 0 iterations")
    let m = Model3::new(&ModelSpec3 { blocks: vec![Box3::new(0.0, 0.0, 0.0, 0.4, 0.4, 0.2)], live: LiveLoad3::None, ..ModelSpec3::default() }).unwrap();
    let limit = limit_analysis_3d(&m, &LimitOptions::default()).map(|_| ());
    let pushover = masonry_dem::explicit::solve_3d(&m, &masonry_dem::explicit::ExplicitOptions::default()).map(|_| ());
    for (what, r) in [("limit analysis", limit), ("the explicit solver's pushover", pushover)] {
        match r {
            Err(masonry_dem::Error::Input { key, reason }) => {
                assert_eq!(key.as_deref(), Some("live"), "{reason}");
                assert!(reason.starts_with(&format!("live = \"none\": {what} raises lambda, the multiplier of the live load, and this model has none")), "{reason}");
            }
            other => panic!("{what}: expected an input error, got {other:?}"),
        }
    }
    // a time history takes the model: no multiplier is raised
    let h = masonry_dem::explicit::simulate_3d(&m, &masonry_dem::explicit::DynamicOptions { duration: 0.01, ..Default::default() }).unwrap();
    assert_eq!(h.status, Status::Completed);
}
