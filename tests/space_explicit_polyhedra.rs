//! The explicit solver in 3D on convex polyhedra: a box turned in plan on its base and a box on
//! an inclined support against their closed forms, a leaning block whose inertia tensor has
//! products of inertia rocking about its edge against the energy integral, and arches of the
//! plane's generator extruded one block deep against the plane's limit analysis.

mod common;

use common::{dry, on_slope, sign_changes};
use masonry_dem::explicit::{simulate_3d, solve_3d, DynamicOptions, ExplicitOptions, Recording};
use masonry_dem::geometry::{arch, Arch, ArchKind, Springing};
use masonry_dem::joint::JointLaw;
use masonry_dem::limit::{limit_analysis, LimitOptions};
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::results::Status;
use masonry_dem::shape::Polyhedron;
use masonry_dem::space::{Box3, LiveLoad3, Model3, ModelSpec3};

/// The explicit collapse multiplier of a 3D model (bracket 1e-3 wide, the default); asserts a
/// collapse.
fn explicit(model: &Model3) -> f64 {
    let r = solve_3d(model, &ExplicitOptions::default()).unwrap();
    assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
    eprintln!("lambda {:.6} bracket {:?}, {} steps, {:.2} s", r.collapse_multiplier, r.bracket, r.iterations, r.elapsed_s);
    r.collapse_multiplier
}

fn close(got: f64, want: f64, rel: f64, what: &str) {
    assert!((got - want).abs() <= rel * want.abs(), "{what}: got {got:.6}, against {want:.6} ({:+.3}%)", 100.0 * (got / want - 1.0));
}

fn spec(polyhedra: Vec<Polyhedron>, supports: Vec<Polyhedron>, law: JointLaw, direction: f64) -> ModelSpec3 {
    ModelSpec3 {
        polyhedra,
        supports,
        base: false,
        gravity: 10.0,
        joints: JointLaws::uniform(law),
        live: LiveLoad3::HorizontalWeight { direction },
        ..ModelSpec3::default()
    }
}

#[test]
fn a_box_turned_in_plan_overturns_where_the_resultant_leaves_its_footprint() {
    // b x d x h = 0.6 x 0.4 x 1.5 m turned about z by an angle drawn once (seeded), on the base,
    // pushed along +x: lambda = 2 r / h, r = min(b / (2 |cos theta|), d / (2 |sin theta|)) the
    // ray from the centroid to the footprint's edge (friction 1: it does not slide)
    let (b, d, h) = (0.6, 0.4, 1.5);
    let mut seed = 44u64;
    seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
    let theta = 180.0 * (seed >> 11) as f64 / (1u64 << 53) as f64;
    let (s, c) = theta.to_radians().sin_cos();
    let block = Box3::new(0.0, 0.0, 0.0, b, d, h).polyhedron().map(|v| {
        let (x, y) = (v[0] - 0.5 * b, v[1] - 0.5 * d);
        [c * x - s * y, s * x + c * y, v[2]]
    });
    let m = Model3::new(&ModelSpec3 { base: true, ..spec(vec![block], vec![], dry(1.0, 1.0, 1e9), 0.0) }).unwrap();
    assert!(m.inertia_tensor()[0][0][1].abs() > 1e-3 * m.inertia()[0][0], "the turned box has products of inertia");
    let r = (0.5 * b / c.abs()).min(0.5 * d / s.abs());
    close(explicit(&m), 2.0 * r / h, 1e-2, &format!("overturning turned by {theta:.3} deg"));
}

#[test]
fn a_box_on_an_inclined_support_slides_and_overturns_at_the_closed_forms() {
    // a squat block (b / h = 4) of friction 0.6 on a 12 deg slope: it slides up the slope at
    // tan(alpha + phi) and down it at tan(phi - alpha), phi = atan(mu)
    let (alpha, mu) = (12.0f64, 0.6f64);
    let (a, phi) = (alpha.to_radians(), mu.atan());
    close(explicit(&on_slope(alpha, 1.2, 0.8, 0.3, mu, 0.0)), (a + phi).tan(), 1e-2, "sliding up the slope");
    close(explicit(&on_slope(alpha, 1.2, 0.8, 0.3, mu, 180.0)), (phi - a).tan(), 1e-2, "sliding down the slope");
    // a tall block (b / h = tan beta = 0.25) of friction 3 on an 8 deg slope overturns about its
    // upper edge at tan(alpha + beta), about its lower edge at tan(beta - alpha)
    let (alpha, b, h) = (8.0f64, 0.4f64, 1.6);
    let (a, beta) = (alpha.to_radians(), (b / h).atan());
    close(explicit(&on_slope(alpha, b, 0.5, h, 3.0, 0.0)), (a + beta).tan(), 1e-2, "overturning up the slope");
    close(explicit(&on_slope(alpha, b, 0.5, h, 3.0, 180.0)), (beta - a).tan(), 1e-2, "overturning down the slope");
}

#[test]
fn a_leaning_block_with_products_of_inertia_rocks_about_its_edge_as_the_energy_integral_says() {
    // a parallelepiped on its base: footprint b x d, height h, its top shifted by s along y (its
    // inertia tensor has a product yz), released at rest turned by psi0 about its toe, the edge
    // x = 0, z = 0 along y. It turns about that edge alone (its centroid lies between the edge's
    // ends), with the moment of inertia about it I = m (b^2 + h^2) / 12 + m R^2 (the shear along y
    // moves no mass in x or z), R the centroid's distance to the edge; its time to the first
    // impact is the energy integral's, `t = int dpsi / psi'`, `I psi'^2 / 2 = m g R (sin(beta0 +
    // psi0) - sin(beta0 + psi))`, beta0 = atan(h / b)
    let (b, d, h, s, g): (f64, f64, f64, f64, f64) = (0.4, 0.6, 1.0, 0.3, 9.81);
    let pts: Vec<[f64; 3]> = (0..8)
        .map(|i| {
            let z = if i & 4 == 4 { h } else { 0.0 };
            [if i & 1 == 1 { b } else { 0.0 }, (if i & 2 == 2 { d } else { 0.0 }) + s * z / h, z]
        })
        .collect();
    let block = Polyhedron::hull(&pts, 1e-9).unwrap();
    let law = JointLaw { friction: 2.0, ..JointLaw::default() };
    let m = Model3::new(&ModelSpec3 { polyhedra: vec![block], gravity: g, joints: JointLaws::uniform(law), ..ModelSpec3::default() }).unwrap();
    let t = m.inertia_tensor()[0];
    assert!(t[1][2].abs() > 0.1 * t[1][1], "the block has a product of inertia yz: {t:?}");
    let psi0 = 0.5 * (b / h).atan();
    let r = [b / 2.0, h / 2.0];
    let (c, sn) = (psi0.cos(), psi0.sin());
    let dx = [c * r[0] - sn * r[1] - r[0], sn * r[0] + c * r[1] - r[1]];
    let u0 = [dx[0], 0.0, dx[1], 0.0, -psi0, 0.0];
    let opts = DynamicOptions { duration: 0.6, initial_displacement: Some(vec![u0, [0.0; 6]]), record: Recording::Every(1), ..Default::default() };
    let hist = simulate_3d(&m, &opts).unwrap();
    assert!(hist.error.is_none(), "{:?}", hist.error);
    let ry: Vec<f64> = (0..hist.times.len()).map(|k| -hist.displacement(k)[0][4]).collect();
    let t3 = sign_changes(&hist.times, &ry);
    assert!(!t3.is_empty(), "no impact");
    // the energy integral by Simpson's rule in u, psi = psi0 - u^2 (no singularity at the start)
    let mass = 2000.0 * b * d * h;
    let big_r = r[0].hypot(r[1]);
    let inertia = mass * (b * b + h * h) / 12.0 + mass * big_r * big_r;
    let beta0 = (h / b).atan();
    let rate = |psi: f64| (2.0 * mass * g * big_r * ((beta0 + psi0).sin() - (beta0 + psi).sin()) / inertia).sqrt();
    let n = 20_000;
    let top = psi0.sqrt();
    let f = |u: f64| if u == 0.0 { 2.0 / (2.0 * mass * g * big_r * (beta0 + psi0).cos() / inertia).sqrt() } else { 2.0 * u / rate(psi0 - u * u) };
    let hstep = top / n as f64;
    let want = hstep / 3.0 * (0..=n).map(|i| f(i as f64 * hstep) * if i == 0 || i == n { 1.0 } else if i % 2 == 1 { 4.0 } else { 2.0 }).sum::<f64>();
    eprintln!("first impact at {:.5} s, the energy integral's {want:.5} s", t3[0]);
    close(t3[0], want, 1e-2, "the first impact");
    // it turns about the edge alone: no turn about x or z beyond 1% of psi0 before the impact
    let off = (0..hist.times.len())
        .filter(|&k| hist.times[k] < t3[0])
        .map(|k| hist.displacement(k)[0])
        .fold(0.0f64, |a, u| a.max(u[3].abs()).max(u[5].abs()));
    assert!(off < 1e-2 * psi0, "turned about x or z by {off:.3e} rad");
    // the energy balance within 1% of the initial potential energy
    let e0 = mass * g * dx[1];
    let worst = hist.energy_error.iter().fold(0.0f64, |a, e| a.max(e.abs()));
    eprintln!("initial energy {e0:.2} J, worst balance error {worst:.2e} J");
    assert!(worst < 0.01 * e0, "energy balance off by {worst:.3e} J of {e0:.3e} J");
}

#[test]
fn arches_extruded_one_block_deep_collapse_at_the_planes_limit_multiplier() {
    // a semicircular and a pointed arch of the plane's generator on their abutments, friction 2
    // (associative: no joint slides, limit analysis is exact), pushed by lambda times their
    // weight along +x: the explicit solver in 3D within 1% of the plane's limit analysis
    let on = |kind, span, radius, rise, thickness, voussoirs| Arch {
        kind,
        span,
        radius,
        rise,
        thickness,
        voussoirs,
        springing: Springing::Abutments { width: None, height: None },
        backfill: None,
    };
    let law = JointLaw { friction: 2.0, dilatancy: 2.0, ..JointLaw::default() };
    for (name, a) in [("semicircular", on(ArchKind::Semicircular, None, Some(1.0), None, 0.15, 12)), ("pointed", on(ArchKind::Pointed, Some(3.0), None, Some(2.2), 0.25, 12))] {
        let geo = arch(&a).unwrap();
        let plane = Model::new(ModelSpec {
            blocks: geo.blocks.clone(),
            supports: geo.supports.clone(),
            base: false,
            joints: JointLaws::uniform(law),
            gravity: 10.0,
            ..ModelSpec::default()
        })
        .unwrap();
        let lp = limit_analysis(&plane, &LimitOptions { tolerance: 1e-10, ..LimitOptions::default() }).unwrap();
        assert_eq!(lp.status, Status::Collapse);
        let depth = 0.5;
        let space = Model3::new(&spec(
            geo.blocks.iter().map(|p| Polyhedron::prism(p.vertices(), [0.0, depth])).collect(),
            geo.supports.iter().map(|p| Polyhedron::prism(p.vertices(), [0.0, depth])).collect(),
            law,
            0.0,
        ))
        .unwrap();
        close(explicit(&space), lp.collapse_multiplier, 1e-2, &format!("the {name} arch extruded"));
    }
}
