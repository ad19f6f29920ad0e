//! Loads carried by blocks (`ModelSpec::carried`, `ModelSpec3::carried`) against closed forms: a
//! block with a load on top at an offset overturns about its toe at lambda0 = sum W_i x_i /
//! sum W_i y_i (the arms from the toe) by limit analysis, the static path and the explicit
//! solver; the facade of the assessment benchmark's hand check (a wall of 100 kN with a floor of 20 kN at
//! its top, 0.25 m from the hinge: 30 / 420) in the plane and in 3D; the masses in modal
//! analysis (the vertical mode sqrt(k / (m + W / g)) and the sliding-rocking pair about the
//! centre of mass of block and load); in time histories, the fall of a loaded block released
//! tilted (the rigid body's energy, the load a point mass) and the ground acceleration that tips
//! it (its multiplier times g); the refusals of bad loads, each naming the load.

mod common;
use common::*;
use masonry_dem::explicit::{self, ExplicitOptions};
use masonry_dem::geometry::Rect;
use masonry_dem::limit::{limit_analysis, limit_analysis_3d, LimitOptions};
use masonry_dem::modal::modes;
use masonry_dem::model::{CarriedLoad, JointLaws, Model, ModelSpec};
use masonry_dem::results::{Results, Status};
use masonry_dem::space::{Box3, LiveLoad3, Model3, ModelSpec3};
use masonry_dem::static_solver::{self, StaticOptions};

const G: f64 = 10.0;

/// A block [0, b] x [0, h] (density 1000, thickness 1) on its base with `carried` loads,
/// friction and dilatancy `mu`.
fn block(b: f64, h: f64, carried: Vec<CarriedLoad>, mu: f64) -> Model {
    Model::new(ModelSpec {
        blocks: vec![Rect::new(0.0, 0.0, b, h).into()],
        gravity: G,
        joints: JointLaws::uniform(dry(mu, mu, 1e10)),
        carried,
        ..ModelSpec::default()
    })
    .unwrap()
}

/// The block of the overturning tests: 0.4 x 1.2 m (4800 N) with 2000 N on top, 0.1 m from its
/// left side; and its closed form about the toe (0.4, 0): (4800 x 0.2 + 2000 x 0.3) / (4800 x 0.6
/// + 2000 x 1.2) = 1560 / 5280.
fn loaded_block() -> (Model, f64) {
    let m = block(0.4, 1.2, vec![CarriedLoad { block: 0, point: [0.1, 1.2], weight: 2000.0 }], 1.0);
    let want = (4800.0 * 0.2 + 2000.0 * 0.3) / (4800.0 * 0.6 + 2000.0 * 1.2);
    (m, want)
}

fn collapse<B>(r: Results<B>) -> f64 {
    assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
    r.collapse_multiplier
}

#[test]
fn a_loaded_block_overturns_at_the_closed_form_by_limit_analysis() {
    let (m, want) = loaded_block();
    // the dead and live loads are the block's and the load's weights together
    assert_close(-m.dead_load()[1], 6800.0, 1e-15, "dead load [N]");
    assert_close(m.live_load()[0], 6800.0, 1e-15, "live load [N]");
    let got = collapse(limit_analysis(&m, &LimitOptions { tolerance: 1e-11, ..LimitOptions::default() }).unwrap());
    eprintln!("loaded block, limit analysis: {got:.12} against {want:.12} ({:.2e})", (got / want - 1.0).abs());
    assert_close(got, want, 1e-9, "limit analysis");
}

#[test]
fn a_loaded_block_overturns_at_the_closed_form_by_the_static_path() {
    let (m, want) = loaded_block();
    let got = collapse(static_solver::solve(&m, &StaticOptions { tolerance: 1e-8, ..StaticOptions::default() }).unwrap());
    eprintln!("loaded block, static path: {got:.9} against {want:.9} ({:.2e})", (got / want - 1.0).abs());
    assert_close(got, want, 1e-6, "static path");
}

#[test]
fn a_loaded_block_overturns_at_the_closed_form_by_the_explicit_solver() {
    let (m, want) = loaded_block();
    let got = collapse(explicit::solve(&m, &ExplicitOptions { threads: 1, ..ExplicitOptions::default() }).unwrap());
    eprintln!("loaded block, explicit: {got:.6} against {want:.6} ({:.2e})", (got / want - 1.0).abs());
    assert_close(got, want, 0.01, "explicit solver");
}

/// The facade of the benchmark's hand check: t = 0.5 m, h = 6 m, 100 kN (1 m long, the density
/// that gives it), a floor of 20 kN at its top 0.25 m from the hinge (the toe at x = 0.5):
/// alpha0 = (100 x 0.25 + 20 x 0.25) / (100 x 3 + 20 x 6) = 30 / 420.
const FACADE: f64 = 30.0 / 420.0;
const FACADE_DENSITY: f64 = 100e3 / (0.5 * 6.0 * 9.81);

#[test]
fn the_facade_with_its_floor_turns_at_the_hand_value_in_the_plane() {
    let m = Model::new(ModelSpec {
        blocks: vec![Rect::new(0.0, 0.0, 0.5, 6.0).into()],
        density: FACADE_DENSITY,
        gravity: 9.81,
        joints: JointLaws::uniform(dry(2.0, 2.0, 1e10)),
        carried: vec![CarriedLoad { block: 0, point: [0.25, 6.0], weight: 20e3 }],
        ..ModelSpec::default()
    })
    .unwrap();
    assert_close(m.weight()[0], 120e3, 1e-12, "weight of wall and floor [N]");
    let got = collapse(limit_analysis(&m, &LimitOptions { tolerance: 1e-11, ..LimitOptions::default() }).unwrap());
    eprintln!("facade in the plane: alpha0 {got:.12} against {FACADE:.12} ({:.2e})", (got / FACADE - 1.0).abs());
    assert_close(got, FACADE, 1e-9, "alpha0 of the facade");
}

fn facade_3d(point: [f64; 3]) -> Model3 {
    Model3::new(&ModelSpec3 {
        blocks: vec![Box3::new(0.0, 0.0, 0.0, 0.5, 1.0, 6.0)],
        density: FACADE_DENSITY,
        gravity: 9.81,
        joints: JointLaws::uniform(dry(2.0, 2.0, 1e10)),
        live: LiveLoad3::HorizontalWeight { direction: 0.0 },
        carried: vec![CarriedLoad { block: 0, point, weight: 20e3 }],
        ..ModelSpec3::default()
    })
    .unwrap()
}

#[test]
fn the_facade_with_its_floor_turns_at_the_hand_value_in_3d() {
    // the floor's reaction off the box's mid-plane (y = 0.2): the same multiplier
    for y in [0.5, 0.2] {
        let m = facade_3d([0.25, y, 6.0]);
        assert_close(-m.dead_load()[2], 120e3, 1e-12, "weight of wall and floor [N]");
        let got = collapse(limit_analysis_3d(&m, &LimitOptions { tolerance: 1e-11, ..LimitOptions::default() }).unwrap());
        eprintln!("facade in 3D, floor at y = {y}: alpha0 {got:.12} against {FACADE:.12} ({:.2e})", (got / FACADE - 1.0).abs());
        assert_close(got, FACADE, 1e-9, "alpha0 of the 3D facade");
    }
}

#[test]
fn a_loaded_box_overturns_at_the_closed_form_by_the_explicit_solver_in_3d() {
    // 0.4 x 0.6 x 1.0 m (density 2000, g = 10: 4800 N) with 2000 N on top at (0.1, 0.45), pushed
    // along +x: (4800 x 0.2 + 2000 x 0.3) / (4800 x 0.5 + 2000 x 1.0)
    let m = Model3::new(&ModelSpec3 {
        blocks: vec![Box3::new(0.0, 0.0, 0.0, 0.4, 0.6, 1.0)],
        gravity: G,
        joints: JointLaws::uniform(dry(2.0, 2.0, 1e9)),
        carried: vec![CarriedLoad { block: 0, point: [0.1, 0.45, 1.0], weight: 2000.0 }],
        ..ModelSpec3::default()
    })
    .unwrap();
    let want = (4800.0 * 0.2 + 2000.0 * 0.3) / (4800.0 * 0.5 + 2000.0 * 1.0);
    let got = collapse(explicit::solve_3d(&m, &ExplicitOptions { tolerance: 2e-4, ..ExplicitOptions::default() }).unwrap());
    eprintln!("loaded box, explicit 3D: {got:.6} against {want:.6} ({:.2e})", (got / want - 1.0).abs());
    assert_close(got, want, 0.01, "explicit solver in 3D");
    // a time history turns the box about its principal axes, which the load's products of
    // inertia turn: it runs, and the box released onto its base tilts on its joint's springs by
    // at most twice the static tilt of its eccentric weight (a load applied at once), W e /
    // (kN I) about x and y (its products of inertia couple a small turn about z to those)
    let h = explicit::simulate_3d(&m, &explicit::DynamicOptions { duration: 0.05, ..Default::default() }).unwrap();
    assert!(h.error.is_none(), "{:?}", h.error);
    let (w, c) = (6800.0, m.centroids()[0]);
    let tilt = [w * (c[1] - 0.3) / (1e9 * 0.4 * 0.6f64.powi(3) / 12.0), w * (0.2 - c[0]) / (1e9 * 0.6 * 0.4f64.powi(3) / 12.0)];
    for k in 0..h.times.len() {
        let u = h.displacement(k)[0];
        assert!(u[3].abs() <= 2.0 * tilt[0].abs() && u[4].abs() <= 2.0 * tilt[1].abs(), "the loaded box at rest turned by {:?}, static tilts {tilt:?}", &u[3..]);
    }
}

#[test]
fn a_load_over_the_centre_of_a_box_adds_its_mass_and_the_parallel_axis_terms_in_3d() {
    // a 1 x 1 x 1 m box of 2000 kg with 1000 kg (10 kN at g = 10) on its top face's centre:
    // the centre of mass rises from 0.5 to (2000 x 0.5 + 1000 x 1) / 3000 m, the moments about
    // x and y take 2000 x (0.5 - zc)^2 + 1000 x (1 - zc)^2, the one about z nothing
    let m = Model3::new(&ModelSpec3 {
        blocks: vec![Box3::new(0.0, 0.0, 0.0, 1.0, 1.0, 1.0)],
        gravity: G,
        carried: vec![CarriedLoad { block: 0, point: [0.5, 0.5, 1.0], weight: 10e3 }],
        ..ModelSpec3::default()
    })
    .unwrap();
    let zc = 2.0 / 3.0;
    assert_close(m.mass()[0], 3000.0, 1e-15, "mass [kg]");
    assert_close(m.centroids()[0][2], zc, 1e-15, "height of the centre of mass [m]");
    let own = 2000.0 * 2.0 / 12.0;
    let shift = 2000.0 * (0.5 - zc).powi(2) + 1000.0 * (1.0 - zc).powi(2);
    let j = m.inertia()[0];
    assert_close(j[0], own + shift, 1e-14, "moment about x [kg m2]");
    assert_close(j[1], own + shift, 1e-14, "moment about y [kg m2]");
    assert_close(j[2], own, 1e-14, "moment about z [kg m2]");
}

const KN: f64 = 1e10;
const KT: f64 = 4e9;

#[test]
fn modal_analysis_takes_the_loads_mass() {
    // 0.4 x 1.0 m (400 kg) with 2000 N (200 kg at g = 10) on top over its centre
    let (b, h, w) = (0.4, 1.0, 2000.0);
    let model = Model::new(ModelSpec {
        blocks: vec![Rect::new(0.0, 0.0, b, h).into()],
        gravity: G,
        joints: JointLaws::uniform(masonry_dem::joint::JointLaw { normal_stiffness: KN, shear_stiffness: KT, ..Default::default() }),
        carried: vec![CarriedLoad { block: 0, point: [b / 2.0, h], weight: w }],
        ..ModelSpec::default()
    })
    .unwrap();
    let m = modes(&model, 3, None).unwrap();
    let (own, load) = (1000.0 * b * h, w / G);
    let mass = own + load;
    let area = b;
    // vertical: the base joint's spring under block and load
    let vertical = (KN * area / mass).sqrt();
    // sliding and rocking about the centre of mass at yc: dT = u1 + phi yc, and the rotary
    // inertia about it with the parallel-axis terms of block and load
    let yc = (own * h / 2.0 + load * h) / mass;
    let inertia = own * (b * b + h * h) / 12.0 + own * (h / 2.0 - yc).powi(2) + load * (h - yc).powi(2);
    let (k11, k12, k22) = (KT * area, KT * area * yc, KT * area * yc * yc + KN * b.powi(3) / 12.0);
    // det(K - l M) = 0 with M = diag(mass, inertia)
    let (qa, qb, qc) = (mass * inertia, -(k11 * inertia + k22 * mass), k11 * k22 - k12 * k12);
    let big = (-qb + (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa);
    let mut want = [(qc / (qa * big)).sqrt(), big.sqrt(), vertical];
    want.sort_by(f64::total_cmp);
    for (k, &w) in want.iter().enumerate() {
        eprintln!("loaded block, mode {k}: {:.9} rad/s against {w:.9} ({:.2e})", m.angular[k], (m.angular[k] / w - 1.0).abs());
        assert_close(m.angular[k], w, 1e-9, &format!("omega_{k} [rad/s]"));
    }
}

#[test]
fn bad_loads_are_refused_naming_the_load() {
    let spec = |l: CarriedLoad| ModelSpec {
        blocks: vec![Rect::new(0.0, 0.0, 0.4, 1.0).into()],
        carried: vec![CarriedLoad { block: 0, point: [0.2, 1.0], weight: 1.0 }, l],
        ..ModelSpec::default()
    };
    let refused = |l: CarriedLoad, says: &str| {
        let e = Model::new(spec(l)).unwrap_err();
        assert_eq!(e.key(), Some("loads.carried[1]"), "{e}");
        assert!(e.to_string().starts_with("loads.carried[1]: ") && e.to_string().contains(says), "{e}");
    };
    refused(CarriedLoad { block: 1, point: [0.2, 1.0], weight: 1.0 }, "block 1 is not a wall block");
    refused(CarriedLoad { block: 0, point: [0.2, 1.01], weight: 1.0 }, "outside block 0");
    refused(CarriedLoad { block: 0, point: [-0.001, 0.5], weight: 1.0 }, "outside block 0");
    refused(CarriedLoad { block: 0, point: [0.2, 1.0], weight: -1.0 }, "weight must be finite and not negative");
    refused(CarriedLoad { block: 0, point: [0.2, 1.0], weight: f64::INFINITY }, "weight must be finite");
    refused(CarriedLoad { block: 0, point: [0.2, f64::NAN], weight: 1.0 }, "must be finite");
    // on a corner, within the contact tolerance: taken
    assert!(Model::new(spec(CarriedLoad { block: 0, point: [0.4, 1.0 + 1e-9], weight: 1.0 })).is_ok());
    // in 3D: the base is not a wall block, a point off the box is refused
    let spec3 = |l: CarriedLoad<3>| ModelSpec3 { blocks: vec![Box3::new(0.0, 0.0, 0.0, 0.4, 0.6, 1.0)], carried: vec![l], ..ModelSpec3::default() };
    let e = Model3::new(&spec3(CarriedLoad { block: 1, point: [0.2, 0.3, 1.0], weight: 1.0 })).unwrap_err();
    assert!(e.key() == Some("loads.carried[0]") && e.to_string().contains("block 1 is not a wall block"), "{e}");
    let e = Model3::new(&spec3(CarriedLoad { block: 0, point: [0.2, 0.7, 1.0], weight: 1.0 })).unwrap_err();
    assert!(e.key() == Some("loads.carried[0]") && e.to_string().contains("outside block 0"), "{e}");
}

/// The rocking block of the time-history tests: 0.4 x 1.0 m (400 kg, g = 9.81) with 2000 N on
/// top at x = 0.3 m, on a stiff base, friction 2 (it rocks without sliding); and its centre of
/// mass (x, y) [m] and total mass [kg].
fn rocking_block() -> (Model, [f64; 2], f64) {
    let law = masonry_dem::joint::JointLaw { friction: 2.0, ..Default::default() };
    let m = Model::new(ModelSpec {
        blocks: vec![Rect::new(0.0, 0.0, 0.4, 1.0).into()],
        gravity: 9.81,
        joints: JointLaws::uniform(law),
        carried: vec![CarriedLoad { block: 0, point: [0.3, 1.0], weight: 2000.0 }],
        ..ModelSpec::default()
    })
    .unwrap();
    let (own, load) = (400.0, 2000.0 / 9.81);
    let total = own + load;
    (m, [(own * 0.2 + load * 0.3) / total, (own * 0.5 + load * 1.0) / total], total)
}

#[test]
fn a_loaded_block_rocks_back_in_the_time_of_the_rigid_bodys_energy() {
    use masonry_dem::explicit::{simulate, DynamicOptions, Recording};
    // released at rest turned by theta0 about its left toe (0, 0), it falls back to theta = 0 in
    // t1 = integral from 0 to theta0 of d theta / sqrt(2 W R (cos(alpha - theta0) - cos(alpha - theta)) / I_O),
    // with R, alpha the centre of mass's distance from the toe and its angle from the vertical and
    // I_O = J + M R^2 the inertia about the toe: block and load as point masses, the cross terms in
    let (m, c, total) = rocking_block();
    let (r, alpha) = (c[0].hypot(c[1]), c[0].atan2(c[1]));
    let (own, load) = (400.0, 2000.0 / 9.81);
    let j_toe = own * (0.4f64.powi(2) + 1.0) / 12.0 + own * (0.2f64.powi(2) + 0.25) + load * (0.3f64.powi(2) + 1.0);
    assert_close(m.inertia()[0] + total * r * r, j_toe, 1e-12, "inertia about the toe [kg m2]");
    let th0 = 0.5 * alpha;
    let k = 2.0 * total * 9.81 * r / j_toe;
    // theta = theta0 - s^2: a smooth integrand, by the midpoint rule
    let n = 20_000;
    let top = th0.sqrt();
    let t1: f64 = (0..n)
        .map(|i| {
            let s = (i as f64 + 0.5) * top / n as f64;
            2.0 * s / (k * ((alpha - th0).cos() - (alpha - th0 + s * s).cos())).sqrt() * top / n as f64
        })
        .sum();
    let (cs, sn) = (th0.cos(), th0.sin());
    let d = [cs * c[0] - sn * c[1] - c[0], sn * c[0] + cs * c[1] - c[1]];
    let opts = DynamicOptions { duration: 1.3 * t1, initial_displacement: Some(vec![[d[0], d[1], th0], [0.0; 3]]), record: Recording::Every(1), ..Default::default() };
    let h = simulate(&m, &opts).unwrap();
    assert!(h.error.is_none(), "{:?}", h.error);
    let phi: Vec<f64> = (0..h.times.len()).map(|k| h.displacement(k)[0][2]).collect();
    let first = (1..phi.len()).find(|&k| phi[k] <= 0.0).expect("it falls back");
    let t = h.times[first - 1] + (h.times[first] - h.times[first - 1]) * phi[first - 1] / (phi[first - 1] - phi[first]);
    eprintln!("loaded block, first impact at {t:.7} s against {t1:.7} s ({:+.2e})", t / t1 - 1.0);
    // the joints' compliance alone parts them: within 1e-4
    assert_close(t, t1, 1e-4, "time to the first impact [s]");
}

#[test]
fn a_steady_ground_acceleration_tips_the_loaded_block_at_its_multiplier() {
    use masonry_dem::explicit::{simulate, DynamicOptions, Recording};
    // a ground acceleration a along +x pushes block and load by -m a: about the left toe the block
    // tips when a / g exceeds (W_b 0.2 + W 0.3) / (W_b 0.5 + W 1.0), and stays put below it (the
    // acceleration ramped up over 0.2 s, slowly against the block's periods on its joints, then held)
    let (m, c, _) = rocking_block();
    let lambda = c[0] / c[1];
    let run = |f: f64| {
        let a = f * lambda * 9.81;
        let ramp = Some((vec![0.0, 0.2, 1.0], vec![0.0, a, a]));
        let opts = DynamicOptions { duration: 0.6, base_acceleration: ramp, record: Recording::Every(10), ..Default::default() };
        let h = simulate(&m, &opts).unwrap();
        assert!(h.error.is_none(), "{:?}", h.error);
        (0..h.times.len()).map(|k| h.displacement(k)[0][2].abs()).fold(0.0, f64::max)
    };
    let (below, above) = (run(0.97), run(1.03));
    eprintln!("loaded block under a steady ground acceleration: largest rotation {below:.2e} rad at 0.97 lambda0 g, {above:.2e} rad at 1.03");
    // below: the joints' elastic rotation, about M / (kN b^3 / 12) = 1200 / 5.3e7 = 2e-5 rad; above: it turns
    assert!(below < 1e-4 && above > 1e-3, "rotation {below:e} rad below the multiplier, {above:e} rad above it");
}
