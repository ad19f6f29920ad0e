//! The contact update of time histories in the plane: contacts found again as blocks slide,
//! topple and fall, new contacts where they land, and the ground plane under a collapse.

mod common;

use masonry_dem::explicit::{simulate, DynamicOptions, Recording, TimeHistory, RETAKE};
use masonry_dem::joint::JointLaw;
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::shape::Polygon;

/// A dry joint of friction angle `phi` (degrees) with the 3DEC verification's stiffnesses.
fn law(phi: f64) -> JointLaw {
    JointLaw { friction: phi.to_radians().tan(), normal_stiffness: 1e7, shear_stiffness: 1e7, cohesion: 0.0, tensile_strength: 0.0, ..JointLaw::default() }
}

/// 3DEC's "Sliding and Toppling Blocks": a block `b` wide and `h` high on a plane inclined by
/// `psi` (degrees) down towards +x, `length` long, the block's uphill corner `at` from the
/// plane's top; density 2000, g = 10, joints of friction angle `phi`.
fn on_slope(b: f64, h: f64, psi: f64, phi: f64, length: f64, at: f64) -> Model {
    let (s, c) = psi.to_radians().sin_cos();
    let d = [c, -s];
    let up = [s, c];
    let p = |t: f64, n: f64| [t * d[0] + n * up[0], t * d[1] + n * up[1]];
    let slope = Polygon::new(vec![p(0.0, -10.0), p(length, -10.0), p(length, 0.0), p(0.0, 0.0)]);
    let block = Polygon::new(vec![p(at, 0.0), p(at + b, 0.0), p(at + b, h), p(at, h)]);
    Model::new(ModelSpec { blocks: vec![block], supports: vec![slope], base: false, density: 2000.0, gravity: 10.0, joints: JointLaws::uniform(law(phi)), ..ModelSpec::default() }).unwrap()
}

fn run(model: &Model, duration: f64, update: bool) -> TimeHistory {
    let opts = DynamicOptions { duration, record: Recording::Interval(0.01), contact_update: update, ..DynamicOptions::default() };
    simulate(model, &opts).unwrap()
}

/// The block of [`on_slope`] at rest: at the displacement at which its joint with the plane
/// carries its weight, elastically (the normal force's resultant under the block's centroid),
/// from where the time history starts.
fn at_rest(model: &Model, b: f64, h: f64, psi: f64) -> Vec<[f64; 3]> {
    let (s, c) = psi.to_radians().sin_cos();
    let w = model.weight()[0];
    let (kn, area, inertia) = (1e7, b * 1.0, b.powi(3) / 12.0);
    let (dn, dt, phi) = (w * c / (kn * area), w * s / (kn * area), -(0.5 * h) * w * s / (kn * inertia));
    // along the plane (t, down) and its normal (n, up): the joint's centre moved by (dt, -dn),
    // the block turned by phi about it
    let along = dt - phi * 0.5 * h;
    vec![[along * c + dn * -s, -along * s - dn * c, phi], [0.0; 3]]
}

/// The block's displacement along the slope (down positive) at each record.
fn along(h: &TimeHistory, psi: f64) -> Vec<f64> {
    let (s, c) = psi.to_radians().sin_cos();
    (0..h.times.len()).map(|k| h.displacement(k)[0][0] * c - h.displacement(k)[0][1] * s).collect()
}

#[test]
fn the_sliding_block_slides_with_the_closed_form_acceleration_its_contact_following_it() {
    let (psi, phi) = (40.0f64, 20.0f64);
    let model = on_slope(10.0, 5.0, psi, phi, 60.0, 2.0);
    let h = run(&model, 3.5, true);
    assert_eq!(h.status, masonry_dem::results::Status::Completed, "{:?}", h.error);
    let want = 10.0 * (psi.to_radians().sin() - phi.to_radians().tan() * psi.to_radians().cos());
    // the acceleration: a quadratic fitted by least squares to the slide from 0.5 s on
    let s = along(&h, psi);
    let pts: Vec<(f64, f64)> = h.times.iter().zip(&s).filter(|(t, _)| **t >= 0.5).map(|(t, s)| (*t, *s)).collect();
    let a = common::quadratic(&pts)[2] * 2.0;
    eprintln!("acceleration {a} against {want}, slid {} m, searches {}, renewed {}, created {}, dropped {}", s[s.len() - 1], h.contact_searches, h.contacts_renewed, h.contacts_created, h.contacts_dropped);
    assert!((a / want - 1.0).abs() < 0.01, "{a} against {want}");
    assert!(s[s.len() - 1] > 2.0 * 10.0, "slid {} m", s[s.len() - 1]);
    // its one contact, on the slope, under the block's bottom edge's centre
    let u = h.displacement(h.times.len() - 1)[0];
    let (sn, cs) = psi.to_radians().sin_cos();
    let bottom = [(2.0 + 5.0) * cs + u[0], -(2.0 + 5.0) * sn + u[1]];
    assert_eq!(h.contacts.len(), 1, "{:?}", h.contacts);
    let c = h.contacts[0].centre;
    assert!((c[0] - bottom[0]).hypot(c[1] - bottom[1]) < 0.1, "{c:?} against {bottom:?}");
    assert!((h.contacts[0].length - 10.0).abs() < 0.1);
}

#[test]
fn the_stable_block_stays_and_the_toppling_one_topples() {
    // stable: h = 10 m, friction 40.1 degrees on a 40-degree plane (b / h = 1 > tan 40)
    let model = on_slope(10.0, 10.0, 40.0, 40.1, 60.0, 2.0);
    let opts = DynamicOptions { duration: 3.0, record: Recording::Interval(0.01), initial_displacement: Some(at_rest(&model, 10.0, 10.0, 40.0)), contact_update: true, ..DynamicOptions::default() };
    let h = simulate(&model, &opts).unwrap();
    let s = along(&h, 40.0);
    let last = h.times.len() - 1;
    let v = h.velocity(last)[0];
    eprintln!("stable: slid {} m, speed {}", s[last] - s[0], v[0].hypot(v[1]));
    assert!((s[last] - s[0]).abs() < 1e-3 && v[0].hypot(v[1]) < 1e-6, "slid {} m", s[last] - s[0]);
    // toppling: h = 25 m, friction 40 degrees on a 30-degree plane (b / h = 0.4 < tan 30): it turns
    // about its downhill toe, without sliding first, and falls over
    let model = on_slope(10.0, 25.0, 30.0, 40.0, 80.0, 2.0);
    let h = run(&model, 8.0, true);
    assert_eq!(h.status, masonry_dem::results::Status::Completed, "{:?}", h.error);
    let phi: Vec<f64> = (0..h.times.len()).map(|k| h.displacement(k)[0][2]).collect();
    let s = along(&h, 30.0);
    // the toe at rest on the plane while the block turns by a tenth of a radian
    let k = phi.iter().position(|p| *p < -0.1).expect("it turns");
    eprintln!("toppling: turned {} rad at the end, slid {} m at 0.1 rad, searches {}, contacts {:?}, speed {:?}", phi[last_of(&h)], s[k], h.contact_searches, h.contacts, h.velocity(last_of(&h))[0]);
    assert!(phi[last_of(&h)] < -(10.0f64 / 25.0).atan() - 30f64.to_radians(), "{}", phi[last_of(&h)]);
}

fn last_of(h: &TimeHistory) -> usize {
    h.times.len() - 1
}

/// A 0.4 m square block on a ledge 1 m above a lower step, its centroid 5 cm beyond the ledge's
/// edge: it tips over the edge and falls onto the step (friction 0.6, dry, density 2000).
fn ledge() -> Model {
    let rect = |x0: f64, y0: f64, x1: f64, y1: f64| Polygon::new(vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]]);
    let law = JointLaw { friction: 0.6, normal_stiffness: 1e8, shear_stiffness: 1e8, cohesion: 0.0, tensile_strength: 0.0, ..JointLaw::default() };
    Model::new(ModelSpec {
        blocks: vec![rect(-0.15, 1.0, 0.25, 1.4)],
        supports: vec![rect(-2.0, 0.0, 0.0, 1.0), rect(0.0, -0.5, 3.0, 0.0)],
        base: false,
        density: 2000.0,
        joints: JointLaws::uniform(law),
        ..ModelSpec::default()
    })
    .unwrap()
}

#[test]
fn a_block_falling_off_a_ledge_comes_to_rest_on_the_step_below() {
    let model = ledge();
    let h = run(&model, 4.0, true);
    assert_eq!(h.status, masonry_dem::results::Status::Completed, "{:?}", h.error);
    let last = last_of(&h);
    let (u, v) = (h.displacement(last)[0], h.velocity(last)[0]);
    let g = model.centroids()[0];
    let at = [g[0] + u[0], g[1] + u[1]];
    // the energy balance: the weight's work (the potential energy lost) is the kinetic and
    // elastic energies plus what the joints, the dashpots and the damping dissipated, to the
    // integrator's error
    let lost = h.gravity_work[last];
    let error = h.energy_error[last];
    eprintln!(
        "at rest at {at:?} turned {:.4} rad, speed {:.2e}; potential lost {lost:.2} J, dissipated {:.2} J (friction {:.2}, impacts {:.2}), kinetic {:.2e} J, elastic {:.2e} J, error {error:.3e} J; searches {}, created {}, dropped {}, renewed {}; {:?}",
        u[2], v[0].hypot(v[1]), h.dissipated[last], h.friction_dissipation[last], h.impact_dissipation[last], h.kinetic_energy[last], h.elastic_energy[last],
        h.contact_searches, h.contacts_created, h.contacts_dropped, h.contacts_renewed, h.contacts
    );
    // on the step: its centroid half its side above the step's top, beyond the ledge, at rest
    assert!((at[1] - 0.2).abs() < 1e-3 && at[0] > 0.2, "{at:?}");
    assert!(v[0].hypot(v[1]) < 1e-3 && h.kinetic_energy[last] < 1e-4 * lost, "{v:?}");
    // the drop of its centroid, 1 m, is the potential energy lost
    assert!((lost / (model.weight()[0] * (g[1] - at[1])) - 1.0).abs() < 1e-9);
    assert!(error.abs() < 0.01 * lost, "energy balance off by {error:.3e} J of {lost:.3e} J");
    // its contact with the step (support 1, block 2) was made by the update, closed
    assert!(h.contacts_created >= 1);
    let on_step: Vec<_> = h.contacts.iter().filter(|c| c.blocks.contains(&2) && c.blocks.contains(&0)).collect();
    assert!(!on_step.is_empty() && on_step.iter().all(|c| c.gap < 0.0 && c.normal[1].abs() > 0.999), "{:?}", h.contacts);
    // without the update the block keeps its one joint, with the ledge, whose line runs on past
    // the ledge's edge, and has none with the step: it turns about the edge past a right angle
    // and the run leaves the model's range, the step never reached
    let h = run(&model, 4.0, false);
    let lowest = (0..h.times.len()).map(|k| g[1] + h.displacement(k)[0][1]).fold(f64::INFINITY, f64::min);
    eprintln!("without the update: {:?}, the centroid's lowest y = {lowest}", h.error);
    assert_eq!(h.status, masonry_dem::results::Status::Failed);
    assert!(h.error.as_deref().is_some_and(|e| e.contains("left the model's range")) && lowest > 0.5, "{lowest}");
}

/// Gilbert, Casapulla & Ahmed's ring (27 radial voussoirs, centreline radius 10 m) `t` m thick
/// on its abutments, dry joints of friction `mu` (no dilatancy), g = 10.
fn gilbert(t: f64, mu: f64) -> Model {
    use masonry_dem::geometry::{arch, Arch, ArchKind, Springing};
    let a = arch(&Arch { kind: ArchKind::Semicircular, span: None, radius: Some(10.0), rise: None, thickness: t, voussoirs: 27, springing: Springing::Abutments { width: None, height: None }, backfill: None }).unwrap();
    let law = JointLaw { friction: mu, dilatancy: 0.0, cohesion: 0.0, tensile_strength: 0.0, normal_stiffness: 1e9, shear_stiffness: 1e9, ..JointLaw::default() };
    Model::new(ModelSpec { blocks: a.blocks, supports: a.supports, base: false, joints: JointLaws::uniform(law), gravity: 10.0, ..ModelSpec::default() }).unwrap()
}

/// Gilbert, Casapulla & Ahmed's ring from rest, at three frictions against the least thickness
/// tabled for each (../shared/benchmarks/arches-and-assessment.md, section 1: 1.07 m for mu =
/// 0.6, 1.26 at 0.375, 1.51 at 0.35): 20% thicker it stays (its weight put on at once, the
/// joints near their friction limit slip by centimetres while the ring settles, but no block
/// moves by a tenth of the thickness, and after 4 s each is within a twentieth of it of where it
/// started); 10% thinner it collapses (the crown falls to the ground) and its debris comes
/// to rest on the ground, heaped no higher than three thicknesses.
#[test]
fn gilberts_ring_from_rest_stands_above_its_least_thickness_and_falls_below_it() {
    for (mu, least) in [(0.6, 1.07), (0.375, 1.26), (0.35, 1.51)] {
        for (t, stands) in [(1.2 * least, true), (0.9 * least, false)] {
            let model = gilbert(t, mu);
            let h = run(&model, if stands { 4.0 } else { 25.0 }, true);
            let last = last_of(&h);
            assert_eq!(h.status, masonry_dem::results::Status::Completed, "mu {mu}, t {t}: {:?}", h.error);
            let u = h.displacement(last);
            let moved = (0..27).map(|i| u[i][0].hypot(u[i][1])).fold(0.0, f64::max);
            let speed = (0..27).map(|i| h.velocity(last)[i][0].hypot(h.velocity(last)[i][1])).fold(0.0, f64::max);
            let ground = h.ground_level.expect("a ground under the abutments");
            let heap = (0..27).map(|i| model.centroids()[i][1] + u[i][1] - ground).fold(0.0, f64::max);
            eprintln!("mu {mu}, t {t:.4} m: moved {moved:.4} m, speed {speed:.2e} m/s, heap {heap:.3} m; {} steps of {:.2e} s, {} searches, {} contacts created, {:.2} s", h.steps, h.time_step, h.contact_searches, h.contacts_created, h.elapsed_s);
            if stands {
                // its elastic settling at the end, and never more than a tenth of its thickness
                // on the way (the weights come on at once: the ring vibrates about its settling)
                let most = (0..h.times.len()).flat_map(|k| h.displacement(k).iter().map(|d| d[0].hypot(d[1]))).fold(0.0, f64::max);
                eprintln!("  at most {most:.4} m");
                assert!(moved < 0.05 * t && most < 0.1 * t, "mu {mu}, t {t}: moved {moved} m, at most {most} m");
            } else {
                assert!(-u[13][1] > 5.0, "mu {mu}, t {t}: the crown fell {} m", -u[13][1]);
                assert!(speed < 1e-2 && heap < 3.0 * t, "mu {mu}, t {t}: speed {speed}, heap {heap} m");
            }
        }
    }
}

/// Ferris & Tin-Loi's wall 1 (dry, friction 0.65, g = 10) under the first `duration` seconds
/// of El Centro 1940 NS scaled by 3, with the contact update on or off.
fn wall1_el_centro(duration: f64, update: bool) -> TimeHistory {
    let model = common::ferris(6, common::dry(0.65, 0.0, 1e10));
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/elcentro-1940-ns.csv")).unwrap();
    let (mut t, mut a) = (vec![], vec![]);
    for line in text.lines().filter(|l| !l.starts_with('#') && !l.starts_with("time")) {
        let mut cols = line.split(',').map(|c| c.trim().parse::<f64>().unwrap());
        t.push(cols.next().unwrap());
        a.push(3.0 * 10.0 * cols.next().unwrap());
    }
    let opts = DynamicOptions {
        duration,
        record: Recording::Interval(0.01),
        base_acceleration: Some((t, a)),
        large_rotations: true,
        contact_update: update,
        ..DynamicOptions::default()
    };
    simulate(&model, &opts).unwrap()
}

/// A wall of running bond shaken hard enough that its blocks slide and rock by millimetres, the
/// contacts searched again many times: no contact is created or dropped (the head joints of the
/// courses below and above, half a block behind each other, are no contacts), none has slid far
/// enough along its joint to be taken again ([`RETAKE`] gap tolerances), and the response is
/// that of the run without the update, to 1e-9 of the largest translation (over the whole 31 s
/// record: 16 searches, the same to the last bit).
#[test]
fn a_shaken_running_bond_wall_keeps_its_contacts() {
    let (on, off) = (wall1_el_centro(4.0, true), wall1_el_centro(4.0, false));
    assert!(on.contact_searches >= 5, "{} searches", on.contact_searches);
    assert_eq!((on.contacts_created, on.contacts_dropped, on.contacts_renewed), (0, 0, 0), "at {RETAKE} gaps");
    let peak = off.displacements.iter().map(|d| d[0].hypot(d[1])).fold(0.0, f64::max);
    let diff = on.displacements.iter().zip(&off.displacements).map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1])).fold(0.0, f64::max);
    assert!(peak > 1e-3 && diff <= 1e-9 * peak, "difference {diff:e} m against the largest translation {peak:e} m");
}

/// The update in a pushover (displacement control, finite rotations): a block b x h rocking
/// about its toe towards a fixed step of height `hs` standing `g` to its right. Without the
/// update the block never meets the step: lambda follows tan(alpha - theta) down (within 2% of
/// it). With it, the contact with the step, open at first, closes when the block's face has
/// turned onto the step's corner (theta = g / hs): from there the block leans on the step,
/// and lambda, which had fallen to tan(alpha - g / hs), climbs back above lambda0 = b / h by
/// the end, 1.5 times that rotation: the run ends completed, not a collapse.
#[test]
fn a_pushover_with_the_update_meets_a_step_the_wall_as_built_does_not_have() {
    use masonry_dem::analysis::Control;
    use masonry_dem::explicit::{solve, ExplicitOptions};
    use masonry_dem::geometry::Rect;
    let (b, h, hs, g): (f64, f64, f64, f64) = (0.4, 1.0, 0.5, 0.005);
    let alpha = (b / h).atan();
    let dry = JointLaws::uniform(JointLaw { friction: 5.0, dilatancy: 0.0, ..JointLaw::default() });
    let spec = ModelSpec { blocks: vec![Rect::new(0.0, 0.0, b, h).into()], supports: vec![Rect::new(b + g, 0.0, b + g + 0.5, hs).into()], joints: dry, ..ModelSpec::default() };
    let model = Model::new(spec).unwrap();
    assert_eq!(model.interfaces().len(), 1, "only the base joint as built");
    // the centroid's travel when the block has turned by 1.5 g / hs about its toe
    let theta_end = 1.5 * g / hs;
    let d_end = 0.5 * b * (1.0 - theta_end.cos()) + 0.5 * h * theta_end.sin();
    let opts = ExplicitOptions { control: Control::Displacement { max_displacement: d_end }, steps: 200, large_rotations: true, ..ExplicitOptions::default() };
    let without = solve(&model, &opts).unwrap();
    let with = solve(&model, &ExplicitOptions { contact_update: true, ..opts }).unwrap();
    let end = |r: &masonry_dem::results::Results| *r.curve_multiplier.last().unwrap();
    let free = (alpha - theta_end).tan();
    assert!((end(&without) - free).abs() < 0.02 * free, "{} against {free}", end(&without));
    let touching = (alpha - g / hs).tan();
    let least = with.curve_multiplier[1..].iter().copied().fold(f64::INFINITY, f64::min);
    assert!((least - touching).abs() < 0.02 * touching, "least {least} against {touching}");
    assert!(end(&with) > b / h, "{}", end(&with));
    // the curve met a contact the wall as built did not have: no collapse is claimed
    assert_eq!(with.status, masonry_dem::results::Status::Completed);
    assert!(with.collapse_multiplier.is_nan());
}
