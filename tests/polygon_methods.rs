//! Every method on polygons: a block on an inclined support against its closed forms (limit
//! analysis, the static path, the explicit solver), and the limit multiplier of a wall turned
//! with its gravity.

mod common;
use common::*;
use masonry_dem::explicit::{self, ExplicitOptions};
use masonry_dem::geometry::polygons;
use masonry_dem::limit::{limit_analysis, LimitOptions};
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::results::{Results, Status};
use masonry_dem::shape::Polygon;
use masonry_dem::static_solver::{self, StaticOptions};
use proptest::prelude::*;

/// A block of `b` along the slope by `h` across it, its lower edge from 1 m up the slope, on a
/// support whose top edge rises at `beta` towards +x (falls where beta < 0); no base; dry
/// associative joints of friction `mu`, g = 10.
fn inclined(beta: f64, b: f64, h: f64, mu: f64) -> Model {
    let (s, c) = beta.sin_cos();
    let at = |u: f64, v: f64| [u * c - v * s, u * s + v * c];
    let support = Polygon::new(vec![[0.0, -2.0], [3.0 * c, -2.0], at(3.0, 0.0), [0.0, 0.0]]);
    let block = Polygon::new(vec![at(1.0, 0.0), at(1.0 + b, 0.0), at(1.0 + b, h), at(1.0, h)]);
    Model::new(ModelSpec {
        blocks: vec![block],
        supports: vec![support],
        base: false,
        gravity: 10.0,
        joints: JointLaws::uniform(dry(mu, mu, 1e10)),
        ..ModelSpec::default()
    })
    .unwrap()
}

/// The horizontal multiplier of a block on a slope rising at `beta` towards the load (pushed
/// uphill; downhill for beta < 0): the forces on the joint per unit weight are, along the slope
/// uphill, `lambda cos(beta) - sin(beta)`, and across it (pressing), `cos(beta) + lambda
/// sin(beta)`. It slides when their ratio reaches mu = tan(phi): lambda = tan(phi + beta); it
/// turns about its downhill-of-the-load toe when the resultant through the centroid (b/2 from
/// the toe along the slope, h/2 across) reaches the toe: `lambda (h cos(beta) - b sin(beta)) =
/// b cos(beta) + h sin(beta)`, lambda = tan(alpha + beta) with tan(alpha) = b / h. The smaller
/// governs (the two faces of the joint's domain are reached independently).
fn closed_form(beta: f64, b: f64, h: f64, mu: f64) -> (f64, &'static str) {
    let slide = (mu.atan() + beta).tan();
    let turn = ((b / h).atan() + beta).tan();
    if slide < turn {
        (slide, "slides")
    } else {
        (turn, "turns")
    }
}

/// beta 10 degrees up and down the slope; a squat block (it slides) and a slender one (it
/// turns); mu = 0.6.
fn cases() -> Vec<(f64, f64, f64, &'static str)> {
    let beta = 10f64.to_radians();
    vec![(beta, 1.0, 0.5, "slides"), (-beta, 1.0, 0.5, "slides"), (beta, 0.3, 1.2, "turns"), (-beta, 0.3, 1.2, "turns")]
}

/// Each case's multiplier by `solve` against its closed form, within `tol` (relative).
fn at_closed_forms(tol: f64, solve: impl Fn(&Model) -> Results) {
    for (beta, b, h, how) in cases() {
        let (want, mode) = closed_form(beta, b, h, 0.6);
        assert_eq!(mode, how);
        let r = solve(&inclined(beta, b, h, 0.6));
        assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
        assert!((r.collapse_multiplier - want).abs() <= tol * want, "beta {beta}, {how}: {} against {want}", r.collapse_multiplier);
    }
}

#[test]
fn a_block_on_an_incline_by_limit_analysis() {
    // the exact multiplier of the program (an interior point run to 1e-11), to 1e-9
    at_closed_forms(1e-9, |m| limit_analysis(m, &LimitOptions { tolerance: 1e-11, ..LimitOptions::default() }).unwrap());
}

#[test]
fn a_block_on_an_incline_by_the_static_path() {
    // load control to collapse, its multiplier located to 1e-8: the closed form to 1e-6 (the
    // joints' penalty stiffness, 1e10 N/m3, makes the path's elastic part, not its peak)
    at_closed_forms(1e-6, |m| static_solver::solve(m, &StaticOptions { tolerance: 1e-8, ..StaticOptions::default() }).unwrap());
}

#[test]
fn a_block_on_an_incline_by_the_explicit_solver() {
    // load control by relaxation, its bracket 1e-3 wide: the closed form within 1%
    at_closed_forms(0.01, |m| explicit::solve(m, &ExplicitOptions { threads: 1, ..ExplicitOptions::default() }).unwrap());
}

#[test]
fn a_block_on_a_slope_steeper_than_its_friction_has_no_equilibrium() {
    // tan(beta) > mu: it slides down under its own weight, pushed either way or not at all
    let r = limit_analysis(&inclined(-35f64.to_radians(), 1.0, 0.5, 0.6), &LimitOptions::default()).unwrap();
    assert_eq!(r.status, Status::NoEquilibrium, "{:?}", r.error);
}

/// Ferris & Tin-Loi's wall 1 with its base as a support polygon, turned by `angle` about
/// (`cx`, `cy`) with its gravity (and so the live load, gravity turned by +90 degrees).
fn turned_wall1(angle: f64, cx: f64, cy: f64) -> Model {
    let (s, c) = angle.sin_cos();
    let turn = |v: [f64; 2]| [cx + c * (v[0] - cx) - s * (v[1] - cy), cy + s * (v[0] - cx) + c * (v[1] - cy)];
    let blocks: Vec<Polygon> = polygons(ferris_blocks(6)).iter().map(|p| p.map(turn)).collect();
    let base = Polygon::new(vec![[0.0, -0.175], [2.0, -0.175], [2.0, 0.0], [0.0, 0.0]]).map(turn);
    Model::new(ModelSpec {
        blocks,
        supports: vec![base],
        base: false,
        gravity: 10.0,
        gravity_direction: [s, -c],
        joints: JointLaws::uniform(dry(0.65, 0.65, 1e10)),
        ..ModelSpec::default()
    })
    .unwrap()
}

fn wall1_multiplier(model: &Model) -> f64 {
    let r = limit_analysis(model, &LimitOptions { tolerance: 1e-11, ..LimitOptions::default() }).unwrap();
    assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
    r.collapse_multiplier
}

#[test]
fn wall1_on_a_support_polygon_is_wall1_on_its_base() {
    // the base as a support gives the model's own base, and wall 1's exact multiplier 0.6429
    // (docs/references.md, section 2)
    let on_base = wall1_multiplier(&ferris(6, dry(0.65, 0.65, 1e10)));
    let on_support = wall1_multiplier(&turned_wall1(0.0, 0.0, 0.0));
    assert!((on_support - on_base).abs() <= 1e-9 * on_base, "{on_support} against {on_base}");
    assert_close(on_base, 0.6429, 1e-4, "wall 1");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]
    // wall 1 turned by any angle about any point, with its supports, gravity and live load:
    // the same multiplier to 1e-9
    #[test]
    fn a_turned_wall_has_the_same_multiplier(angle in -3.2f64..3.2, cx in -10.0f64..10.0, cy in -10.0f64..10.0) {
        let want = wall1_multiplier(&turned_wall1(0.0, 0.0, 0.0));
        let got = wall1_multiplier(&turned_wall1(angle, cx, cy));
        prop_assert!((got - want).abs() <= 1e-9 * want, "turned by {angle}: {got} against {want}");
    }
}
