//! The contact update of 3D time histories: contacts found again as blocks slide and topple on a
//! slope, new contacts where a block lands, and a wall whose contacts neither form nor break.

mod common;

use masonry_dem::explicit::{simulate_3d, DynamicOptions, Recording, TimeHistory};
use masonry_dem::joint::JointLaw;
use masonry_dem::model::JointLaws;
use masonry_dem::results::Status;
use masonry_dem::shape::Polyhedron;
use masonry_dem::space::{Model3, ModelSpec3};

/// A dry joint of friction angle `phi` (degrees) with the 3DEC verification's stiffnesses.
fn law(phi: f64) -> JointLaw {
    JointLaw { friction: phi.to_radians().tan(), normal_stiffness: 1e7, shear_stiffness: 1e7, cohesion: 0.0, tensile_strength: 0.0, ..JointLaw::default() }
}

/// The slope's axes in the world: down the slope, across it, and its upward normal, for a plane
/// inclined by `psi` (degrees) down towards the direction `beta` (degrees in plan from +x).
fn axes(psi: f64, beta: f64) -> [[f64; 3]; 3] {
    let (s, c) = psi.to_radians().sin_cos();
    let (sb, cb) = beta.to_radians().sin_cos();
    [[c * cb, c * sb, -s], [-sb, cb, 0.0], [s * cb, s * sb, c]]
}

fn world(ax: &[[f64; 3]; 3], p: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|k| p[0] * ax[0][k] + p[1] * ax[1][k] + p[2] * ax[2][k])
}

/// 3DEC's "Sliding and Toppling Blocks" in 3D: a block of section `section` (in the slope's axes:
/// along it, across it, from its corner `at` from the plane's top) and height `h` on a plane
/// inclined by `psi` down towards `beta` in plan, `length` long and 20 m wide; density 2000, g = 10,
/// joints of friction angle `phi`.
fn on_slope(section: &[[f64; 2]], h: f64, psi: f64, beta: f64, phi: f64, length: f64, at: f64) -> Model3 {
    let ax = axes(psi, beta);
    let slope = Polyhedron::hull(&[0.0, length].iter().flat_map(|&t| [-10.0, 10.0].into_iter().flat_map(move |s| [-10.0, 0.0].map(|n| [t, s, n]))).map(|p| world(&ax, p)).collect::<Vec<_>>(), 1e-9).unwrap();
    let pts: Vec<[f64; 3]> = section.iter().flat_map(|p| [0.0, h].map(|n| world(&ax, [at + p[0], p[1], n]))).collect();
    let block = Polyhedron::hull(&pts, 1e-9).unwrap();
    Model3::new(&ModelSpec3 { polyhedra: vec![block], supports: vec![slope], base: false, density: 2000.0, gravity: 10.0, joints: JointLaws::uniform(law(phi)), ..ModelSpec3::default() }).unwrap()
}

/// A `b` by `d` rectangle, centred across the slope.
fn rectangle(b: f64, d: f64) -> Vec<[f64; 2]> {
    vec![[0.0, -0.5 * d], [b, -0.5 * d], [b, 0.5 * d], [0.0, 0.5 * d]]
}

fn run(model: &Model3, duration: f64, update: bool, initial: Option<Vec<[f64; 6]>>) -> TimeHistory<[f64; 6]> {
    let opts = DynamicOptions { duration, record: Recording::Interval(0.01), contact_update: update, initial_displacement: initial, ..DynamicOptions::default() };
    simulate_3d(model, &opts).unwrap()
}

/// Block 0's displacement along the slope's axis `axis` at each record.
fn along(h: &TimeHistory<[f64; 6]>, axis: [f64; 3]) -> Vec<f64> {
    (0..h.times.len()).map(|k| (0..3).map(|r| h.displacement(k)[0][r] * axis[r]).sum()).collect()
}

/// The sliding block of `section` on a 40-degree slope of friction 20 degrees turned by `beta` in
/// plan: its acceleration along the slope, fitted from 0.5 s on, within 1% of `g (sin psi - tan
/// phi cos psi)`; it slides more than twice its length, straight down (across the slope less than
/// a millimetre), its contact taken again from the moved block as it goes, and at the end its one
/// contact lies on the slope under the block's bottom face's centroid, of the face's area: its
/// centre within the distance at which a contact is taken again (RETAKE gap tolerances, the gap
/// 2% of the least side of the block's box) plus the travel between two searches (half a gap)
/// along the slope, and half its overlap along the normal (to a millimetre: the block rocks a little),
/// of where the face's centroid is.
fn slides(section: &[[f64; 2]], beta: f64, duration: f64) {
    let (psi, phi) = (40.0f64, 20.0f64);
    let model = on_slope(section, 5.0, psi, beta, phi, 60.0, 2.0);
    let h = run(&model, duration, true, None);
    assert_eq!(h.status, Status::Completed, "{:?}", h.error);
    let ax = axes(psi, beta);
    let want = 10.0 * (psi.to_radians().sin() - phi.to_radians().tan() * psi.to_radians().cos());
    let s = along(&h, ax[0]);
    let pts: Vec<(f64, f64)> = h.times.iter().zip(&s).filter(|(t, _)| **t >= 0.5).map(|(t, s)| (*t, *s)).collect();
    let a = common::quadratic(&pts)[2] * 2.0;
    let last = h.times.len() - 1;
    let across = along(&h, ax[1])[last];
    eprintln!("beta {beta}: acceleration {a} against {want}, slid {} m, across {across:e} m, {} steps, searches {}, renewed {}, created {}, dropped {}, {:?}", s[last], h.steps, h.contact_searches, h.contacts_renewed, h.contacts_created, h.contacts_dropped, h.contacts_3d);
    assert!((a / want - 1.0).abs() < 0.01, "{a} against {want}");
    let size = section.iter().map(|p| p[0]).fold(0.0, f64::max);
    assert!(s[last] > 2.0 * size && across.abs() < 1e-3, "slid {} m, across {across} m", s[last]);
    assert!(h.contact_searches > 10 && h.contacts_renewed > 10, "{} searches, {} renewed", h.contact_searches, h.contacts_renewed);
    // the bottom face's centroid now: its centroid in the section, moved with the block
    let area: f64 = (0..section.len()).map(|i| section[i][0] * section[(i + 1) % section.len()][1] - section[(i + 1) % section.len()][0] * section[i][1]).sum::<f64>() / 2.0;
    let cx: f64 = (0..section.len()).map(|i| (section[i][0] + section[(i + 1) % section.len()][0]) * (section[i][0] * section[(i + 1) % section.len()][1] - section[(i + 1) % section.len()][0] * section[i][1])).sum::<f64>() / (6.0 * area);
    let cy: f64 = (0..section.len()).map(|i| (section[i][1] + section[(i + 1) % section.len()][1]) * (section[i][0] * section[(i + 1) % section.len()][1] - section[(i + 1) % section.len()][0] * section[i][1])).sum::<f64>() / (6.0 * area);
    let u = h.displacement(last)[0];
    let bottom = world(&ax, [2.0 + cx, cy, 0.0]);
    let bottom = [0, 1, 2].map(|r| bottom[r] + u[r]);
    assert_eq!(h.contacts_3d.len(), 1, "{:?}", h.contacts_3d);
    let c = h.contacts_3d[0];
    let d: Vec<f64> = (0..3).map(|r| c.centre[r] - bottom[r]).collect();
    let normal: f64 = (0..3).map(|r| d[r] * ax[2][r]).sum();
    let off = ((0..3).map(|r| d[r] * d[r]).sum::<f64>() - normal * normal).sqrt();
    let b = model.shapes()[0].aabb();
    let gap = masonry_dem::explicit::GAP_FRACTION * (0..3).map(|k| b.max[k] - b.min[k]).fold(f64::INFINITY, f64::min);
    let far = masonry_dem::explicit::RETAKE * gap + 0.5 * gap;
    assert!(off <= far && (normal + 0.5 * c.gap).abs() < 1e-3 && (c.area / area - 1.0).abs() < 1e-3, "{c:?} against {bottom:?}, area {area}");
}

#[test]
fn the_sliding_block_slides_with_the_closed_form_acceleration_its_contact_following_it() {
    slides(&rectangle(10.0, 10.0), 0.0, 3.5);
}

#[test]
fn a_slope_turned_in_plan_and_a_hexagonal_block_slide_alike() {
    slides(&rectangle(10.0, 10.0), 30.0, 3.5);
    // a hexagonal prism standing on a hexagon of 5 m sides, its corner down the slope
    let hexagon: Vec<[f64; 2]> = (0..6).map(|k| {
        let a = (60.0 * k as f64 + 180.0f64).to_radians();
        [5.0 + 5.0 * a.cos(), 5.0 * a.sin()]
    }).collect();
    slides(&hexagon, 0.0, 3.5);
}

/// The displacement at which the block of `b` along the slope, `d` across it and `h` high on a
/// plane inclined by `psi` (toward +x) rests on its joint elastically: the joint's centre moved
/// by the settlement and the shear of its weight, the block turned by the moment of the shear
/// about its joint's centre over the rectangle's bending stiffness `kN I`.
fn at_rest(model: &Model3, b: f64, d: f64, h: f64, psi: f64) -> Vec<[f64; 6]> {
    let (s, c) = psi.to_radians().sin_cos();
    let w = model.mass()[0] * model.gravity();
    let (kn, area, inertia) = (1e7, b * d, d * b.powi(3) / 12.0);
    let (dn, dt, theta) = (w * c / (kn * area), w * s / (kn * area), 0.5 * h * w * s / (kn * inertia));
    let ax = axes(psi, 0.0);
    let along = dt + theta * 0.5 * h;
    let u = world(&ax, [along, 0.0, -dn]);
    vec![[u[0], u[1], u[2], 0.0, theta, 0.0], [0.0; 6]]
}

/// The stable block (friction 40.1 degrees on a 40-degree plane, b / h = 1 > tan 40) from its
/// elastic rest stays: at rest after 3 s, slid by less than 5 cm (half a percent of its side;
/// measured 4.6 cm, the same without the update: the corners of its joint share its shear by
/// their shares, and the uphill ones, whose normal force the weight's moment takes away, slip
/// until the downhill ones carry the shear, at the friction's 0.4% margin). The toppling one (25 m high on a
/// 10 by 10 m base, friction 40 degrees on a 30-degree plane: b / h = 0.4 < tan 30) turns about its
/// downhill edge past the angle at which its centroid is beyond it, and falls over.
#[test]
fn the_stable_block_stays_and_the_toppling_one_topples() {
    let model = on_slope(&rectangle(10.0, 10.0), 10.0, 40.0, 0.0, 40.1, 60.0, 2.0);
    let h = run(&model, 3.0, true, Some(at_rest(&model, 10.0, 10.0, 10.0, 40.0)));
    assert_eq!(h.status, Status::Completed, "{:?}", h.error);
    let s = along(&h, axes(40.0, 0.0)[0]);
    let last = h.times.len() - 1;
    let v = h.velocity(last)[0];
    let speed = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    eprintln!("stable: slid {} m, speed {speed:e}, searches {}", s[last] - s[0], h.contact_searches);
    assert!((s[last] - s[0]).abs() < 0.05 && speed < 1e-4, "slid {} m, speed {speed}", s[last] - s[0]);
    let model = on_slope(&rectangle(10.0, 10.0), 25.0, 30.0, 0.0, 40.0, 80.0, 2.0);
    let h = run(&model, 8.0, true, None);
    assert_eq!(h.status, Status::Completed, "{:?}", h.error);
    let turn: Vec<f64> = (0..h.times.len()).map(|k| h.displacement(k)[0][4]).collect();
    let last = h.times.len() - 1;
    eprintln!("toppling: turned {} rad about y, searches {}, created {}, dropped {}, contacts {:?}", turn[last], h.contact_searches, h.contacts_created, h.contacts_dropped, h.contacts_3d);
    assert!(turn[last] > (10.0f64 / 25.0).atan() + 30f64.to_radians(), "{}", turn[last]);
}

/// A 0.4 m cube on a ledge 1 m above a lower step, its centroid 5 cm beyond the ledge's edge:
/// it tips over the edge and falls onto the step (friction 0.6, dry, density 2000).
fn ledge() -> Model3 {
    let cube = |lo: [f64; 3], hi: [f64; 3]| Polyhedron::cuboid(lo, hi);
    let law = JointLaw { friction: 0.6, normal_stiffness: 1e8, shear_stiffness: 1e8, cohesion: 0.0, tensile_strength: 0.0, ..JointLaw::default() };
    Model3::new(&ModelSpec3 {
        polyhedra: vec![cube([-0.15, -0.2, 1.0], [0.25, 0.2, 1.4])],
        supports: vec![cube([-2.0, -1.0, 0.0], [0.0, 1.0, 1.0]), cube([0.0, -1.0, -0.5], [3.0, 1.0, 0.0])],
        base: false,
        density: 2000.0,
        joints: JointLaws::uniform(law),
        ..ModelSpec3::default()
    })
    .unwrap()
}

/// The cube of [`ledge`] comes to rest on the step: its centroid half its side above the step,
/// beyond the ledge, still; the weight's work (the potential energy lost by the drop of its
/// centroid) is what the joints and dashpots dissipated and the elastic energy left, within 1%;
/// its contact with the step was created by the update and is closed. Without the update it
/// keeps its one joint with the ledge, whose plane runs on past the edge: it turns about the
/// edge until the run leaves the model's range, never lower than the ledge's top less its side.
#[test]
fn a_block_falling_off_a_ledge_comes_to_rest_on_the_step_below() {
    let model = ledge();
    let h = run(&model, 3.0, true, None);
    assert_eq!(h.status, Status::Completed, "{:?}", h.error);
    let last = h.times.len() - 1;
    let (u, v) = (h.displacement(last)[0], h.velocity(last)[0]);
    let g = model.centroids()[0];
    let at = [g[0] + u[0], g[1] + u[1], g[2] + u[2]];
    let speed = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let lost = h.gravity_work[last];
    let error = h.energy_error[last];
    eprintln!(
        "at rest at {at:?}, speed {speed:.2e}; potential lost {lost:.3} J, dissipated {:.3} J (friction {:.3}, impacts {:.3}, damping {:.3}), kinetic {:.2e} J, elastic {:.2e} J, error {error:.3e} J; {} steps, searches {}, created {}, dropped {}, renewed {}; {:?}",
        h.dissipated[last], h.friction_dissipation[last], h.impact_dissipation[last], h.damping_dissipation[last], h.kinetic_energy[last], h.elastic_energy[last],
        h.steps, h.contact_searches, h.contacts_created, h.contacts_dropped, h.contacts_renewed, h.contacts_3d
    );
    assert!((at[2] - 0.2).abs() < 1e-3 && at[0] > 0.2, "{at:?}");
    assert!(speed < 1e-3 && h.kinetic_energy[last] < 1e-4 * lost, "{v:?}");
    let weight = model.mass()[0] * model.gravity();
    assert!((lost / (weight * (g[2] - at[2])) - 1.0).abs() < 1e-9);
    let balance = h.dissipated[last] + h.elastic_energy[last] + h.kinetic_energy[last];
    assert!((balance / lost - 1.0).abs() < 0.01 && error.abs() < 0.01 * lost, "dissipated and stored {balance:.4} J against {lost:.4} J");
    assert!(h.contacts_created >= 1);
    let on_step: Vec<_> = h.contacts_3d.iter().filter(|c| c.blocks.contains(&2) && c.blocks.contains(&0)).collect();
    assert!(!on_step.is_empty() && on_step.iter().all(|c| c.gap < 0.0 && c.normal[2].abs() > 0.999), "{:?}", h.contacts_3d);
    let h = run(&model, 3.0, false, None);
    let lowest = (0..h.times.len()).map(|k| g[2] + h.displacement(k)[0][2]).fold(f64::INFINITY, f64::min);
    eprintln!("without the update: {:?} {:?}, the centroid's lowest z = {lowest}", h.status, h.error);
    assert_eq!(h.status, Status::Failed);
    assert!(h.error.as_deref().is_some_and(|e| e.contains("left the model's range")) && lowest > 0.6, "{lowest}");
}

/// A running-bond wall of boxes (2 m long, 1 m high, 0.2 m thick; blocks 0.4 x 0.2 m; dry joints
/// of friction 0.6) on its base, shaken along x and y by a sine pulse of 0.4 g (0.2 g along y) that
/// rocks it by millimetres, so that the contacts are searched again: no contact is created or dropped, and
/// the blocks' motion is that of the run without the update (at the same time step) to
/// 1e-9 of the largest translation (measured: identical).
#[test]
fn a_shaken_wall_keeps_its_contacts_and_its_response() {
    use masonry_dem::space::running_bond_3d;
    let blocks = running_bond_3d(2.0, 1.0, 0.2, 0.4, 0.2, 0.2).unwrap();
    let law = JointLaw { friction: 0.6, normal_stiffness: 1e9, shear_stiffness: 1e9, cohesion: 0.0, tensile_strength: 0.0, ..JointLaw::default() };
    let model = Model3::new(&ModelSpec3 { blocks, joints: JointLaws::uniform(law), ..ModelSpec3::default() }).unwrap();
    let t: Vec<f64> = (0..=100).map(|k| 0.005 * k as f64).collect();
    let a: Vec<f64> = t.iter().map(|t| 0.4 * 9.81 * (2.0 * std::f64::consts::PI * 2.0 * t).sin()).collect();
    let shake = |update: bool, time_step: Option<f64>| {
        let opts = DynamicOptions {
            duration: 1.0,
            time_step,
            record: Recording::Interval(0.01),
            base_acceleration: Some((t.clone(), a.clone())),
            base_acceleration_y: Some((t.clone(), a.iter().map(|a| 0.5 * a).collect())),
            contact_update: update,
            ..DynamicOptions::default()
        };
        simulate_3d(&model, &opts).unwrap()
    };
    let on = shake(true, None);
    let off = shake(false, Some(on.time_step));
    assert_eq!((on.status, off.status), (Status::Completed, Status::Completed));
    let peak = off.displacements.iter().map(|d| d[0].hypot(d[1]).hypot(d[2])).fold(0.0, f64::max);
    let diff = on.displacements.iter().zip(&off.displacements).map(|(a, b)| (0..6).map(|r| (a[r] - b[r]).abs()).fold(0.0, f64::max)).fold(0.0, f64::max);
    eprintln!("{} blocks: searches {}, created {}, dropped {}, renewed {}; largest translation {peak:e} m, difference {diff:e}; {} steps", model.n_wall(), on.contact_searches, on.contacts_created, on.contacts_dropped, on.contacts_renewed, on.steps);
    assert!(on.contact_searches >= 1, "{} searches", on.contact_searches);
    assert_eq!((on.contacts_created, on.contacts_dropped), (0, 0));
    assert!(peak > 2e-3 && diff <= 1e-9 * peak, "difference {diff:e} against the largest translation {peak:e} m");
}
