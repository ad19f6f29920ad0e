//! The 3D model on convex polyhedra: limit analysis of blocks turned in plan, on an inclined
//! support and on a contact polygon of eight corners against closed forms, and the refusals of
//! overlapping polyhedra.

mod common;

use common::{dry, on_slope};
use masonry_dem::limit::{limit_analysis_3d, LimitOptions};
use masonry_dem::model::JointLaws;
use masonry_dem::results::Status;
use masonry_dem::shape::Polyhedron;
use masonry_dem::space::{Box3, LiveLoad3, Model3, ModelSpec3};

/// The limit multiplier, the interior point run to 1e-12 (its default 1e-8 holds the
/// multiplier to about 1e-7); asserts a collapse.
fn lambda(model: &Model3) -> f64 {
    let r = limit_analysis_3d(model, &LimitOptions { tolerance: 1e-12, ..LimitOptions::default() }).unwrap();
    assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
    r.collapse_multiplier
}

fn close(got: f64, want: f64, rel: f64, what: &str) {
    assert!((got - want).abs() <= rel * want.abs(), "{what}: got {got:.12}, closed form {want:.12}");
}

/// `p` turned by `deg` degrees about the vertical through `(cx, cy)`.
fn turned(p: &Polyhedron, deg: f64, c: [f64; 2]) -> Polyhedron {
    let (s, co) = deg.to_radians().sin_cos();
    p.map(|v| [c[0] + co * (v[0] - c[0]) - s * (v[1] - c[1]), c[1] + s * (v[0] - c[0]) + co * (v[1] - c[1]), v[2]])
}

fn spec(polyhedra: Vec<Polyhedron>, supports: Vec<Polyhedron>, friction: f64, direction: f64) -> ModelSpec3 {
    ModelSpec3 {
        polyhedra,
        supports,
        base: false,
        gravity: 10.0,
        joints: JointLaws::uniform(dry(friction, friction, 1e9)),
        live: LiveLoad3::HorizontalWeight { direction },
        ..ModelSpec3::default()
    }
}

#[test]
fn a_box_turned_in_plan_overturns_where_the_resultant_leaves_its_footprint() {
    // b x d x h = 0.6 x 0.4 x 1.5 m turned by theta about z on the base, pushed along +x: the
    // resultant of W and lambda W through the centroid (h / 2 up) meets the base at lambda h / 2
    // from the centre, and leaves the footprint at the ray's distance to its edge,
    // r = min(b / (2 |cos theta|), d / (2 |sin theta|)): lambda = 2 r / h (below mu = 1)
    let (b, d, h) = (0.6, 0.4, 1.5);
    for theta in [0.0f64, 17.0, 30.0, 60.0, 90.0, 100.0, 145.0] {
        let block = turned(&Box3::new(0.0, 0.0, 0.0, b, d, h).polyhedron(), theta, [0.5 * b, 0.5 * d]);
        let m = Model3::new(&ModelSpec3 { base: true, supports: vec![], ..spec(vec![block], vec![], 1.0, 0.0) }).unwrap();
        assert_eq!(m.contacts().len(), 1);
        assert_eq!(m.contacts()[0].corners.len(), 4);
        let (c, s) = (theta.to_radians().cos().abs(), theta.to_radians().sin().abs());
        let r = (0.5 * b / c).min(0.5 * d / s);
        close(lambda(&m), 2.0 * r / h, 1e-9, &format!("overturning turned by {theta} deg"));
    }
}

#[test]
fn a_box_on_an_inclined_support_slides_at_the_angles_closed_forms() {
    // a squat block (b / h = 4, overturning far off): pushed up the slope it slides at
    // tan(alpha + phi), pushed down it at tan(phi - alpha), phi = atan(mu)
    let (alpha, mu) = (12.0f64, 0.6f64);
    let (a, phi) = (alpha.to_radians(), mu.atan());
    let up = on_slope(alpha, 1.2, 0.8, 0.3, mu, 0.0);
    let c = &up.contacts()[0];
    assert_eq!((c.a, c.b, c.corners.len()), (1, 0, 4), "the support is a, the normal up into the block");
    assert!((c.n[0] + a.sin()).abs() < 1e-15 && (c.n[2] - a.cos()).abs() < 1e-15, "{:?}", c.n);
    close(lambda(&up), (a + phi).tan(), 1e-9, "sliding up the slope");
    close(lambda(&on_slope(alpha, 1.2, 0.8, 0.3, mu, 180.0)), (phi - a).tan(), 1e-9, "sliding down the slope");
}

#[test]
fn a_box_on_an_inclined_support_overturns_at_the_angles_closed_forms() {
    // a tall block (b / h = tan beta = 0.25) of friction 3: pushed up the slope it overturns about
    // its upper edge at tan(alpha + beta), pushed down about its lower edge at tan(beta - alpha)
    let (alpha, b, h) = (8.0f64, 0.4f64, 1.6);
    let (a, beta) = (alpha.to_radians(), (b / h).atan());
    close(lambda(&on_slope(alpha, b, 0.5, h, 3.0, 0.0)), (a + beta).tan(), 1e-9, "overturning up the slope");
    close(lambda(&on_slope(alpha, b, 0.5, h, 3.0, 180.0)), (beta - a).tan(), 1e-9, "overturning down the slope");
}

#[test]
fn a_cube_turned_on_a_cube_rocks_on_their_octagon() {
    // a unit cube turned by 45 deg on a fixed unit cube: they share a regular octagon of
    // apothem 1/2, whose edges face 0, 45, 90, ... deg and whose corners lie at 22.5 + k 45 deg,
    // 1 / (2 cos 22.5 deg) from the centre. Pushed at phi the resultant leaves it at
    // r = 1 / (2 cos(phi' )) (phi' the angle to the nearest edge's normal): lambda = 2 r / 1
    let support = Box3::new(0.0, 0.0, -1.0, 1.0, 1.0, 0.0).polyhedron();
    let cube = turned(&Box3::new(0.0, 0.0, 0.0, 1.0, 1.0, 1.0).polyhedron(), 45.0, [0.5, 0.5]);
    for phi in [0.0f64, 10.0, 22.5, 45.0, 200.0] {
        let m = Model3::new(&spec(vec![cube.clone()], vec![support.clone()], 2.0, phi)).unwrap();
        assert_eq!(m.contacts().len(), 1);
        let c = &m.contacts()[0];
        assert_eq!(c.corners.len(), 8);
        close(c.area, 2.0 * (2f64.sqrt() - 1.0), 1e-14, "the octagon's area");
        let off = (phi.rem_euclid(45.0) - 0.0).min(45.0 - phi.rem_euclid(45.0));
        let want = 1.0 / off.to_radians().cos();
        close(lambda(&m), want, 1e-9, &format!("rocking on the octagon at {phi} deg"));
    }
}

#[test]
fn overlapping_polyhedra_are_refused_naming_both() {
    let tet = Polyhedron::hull(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], 1e-9).unwrap();
    let into = tet.map(|p| [p[0] + 0.2, p[1] + 0.2, p[2] + 0.1]);
    let e = Model3::new(&ModelSpec3 { polyhedra: vec![tet, into], ..ModelSpec3::default() }).unwrap_err().to_string();
    assert!(e.starts_with("block 0 (polyhedron of 4 vertices: ") && e.contains(", ...) and block 1 (polyhedron of 4 vertices: "), "{e}");
    assert!(e.contains(" overlap (by "), "{e}");
    // a polyhedron into a box
    let e = Model3::new(&ModelSpec3 {
        blocks: vec![Box3::new(0.0, 0.0, 0.0, 1.0, 1.0, 1.0)],
        polyhedra: vec![Polyhedron::hull(&[[0.5, 0.5, 0.9], [1.5, 0.5, 1.0], [0.5, 1.5, 1.0], [0.5, 0.5, 2.0]], 1e-9).unwrap()],
        ..ModelSpec3::default()
    })
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("block 0 [0, 0, 0, 1, 1, 1] and block 1 (polyhedron of 4 vertices: "), "{e}");
    // a block on a support with another in the air: that one is named
    let cube = Box3::new(0.0, 0.0, 0.0, 1.0, 1.0, 1.0);
    let e = Model3::new(&ModelSpec3 { blocks: vec![cube, Box3::new(0.0, 0.0, 3.0, 1.0, 1.0, 4.0)], ..spec(vec![], vec![Box3::new(0.0, 0.0, -1.0, 1.0, 1.0, 0.0).polyhedron()], 0.6, 0.0) })
        .unwrap_err()
        .to_string();
    assert_eq!(e, "block 1 [0, 0, 3, 1, 1, 4] touches no other block");
}
