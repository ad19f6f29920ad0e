//! A support given a movement, followed to where no equilibrium exists: a semicircular arch on
//! a spreading abutment, by limit analysis along the movement.

use masonry_dem::geometry::{arch, Arch, ArchKind, Springing};
use masonry_dem::joint::{JointLaw, ROCKING};
use masonry_dem::limit::{follow_movement, FollowOptions, LimitOptions};
use masonry_dem::model::{Direction, JointLaws, Model, ModelSpec, SupportMovement};
use masonry_dem::results::Status;
use std::f64::consts::PI;

/// Centreline radius \[m\], thickness \[m\] (t/R = 0.15) and voussoirs of the arch.
const R: f64 = 2.0;
const T: f64 = 0.3;
const N: usize = 20;

/// The semicircular arch on abutments, friction 1 (associative): it does not slide.
fn semicircular() -> Model {
    let a = arch(&Arch { kind: ArchKind::Semicircular, span: None, radius: Some(R), rise: None, thickness: T, voussoirs: N,
        springing: Springing::Abutments { width: None, height: None }, backfill: None }).unwrap();
    let law = JointLaw { friction: 1.0, dilatancy: 1.0, ..JointLaw::default() };
    Model::new(ModelSpec { blocks: a.blocks, supports: a.supports, base: false, joints: JointLaws::uniform(law), ..ModelSpec::default() }).unwrap()
}

/// The least thrust of the arch as built, by its line of thrust: by symmetry the crown joint
/// carries a horizontal force H, least at its extrados; the half arch above the joint at angle
/// theta from the springing (the voussoirs whose centroids lie above it) turns about that joint's
/// intrados point unless H (y_crown - y_j) >= sum W_i (x_j - x_i). The least H is the largest
/// of these over the joints, and the joint of the largest is the haunch's hinge (its index from
/// the springing returned). The right half: x > 0.
fn least_thrust(model: &Model) -> (f64, usize) {
    let (ri, re) = (R - 0.5 * T, R + 0.5 * T);
    let blocks: Vec<usize> = (0..model.n_wall()).filter(|&i| model.centroids()[i][0] > 0.0).collect();
    (0..N / 2)
        .map(|j| {
            let theta = PI * j as f64 / N as f64;
            let (xj, yj) = (ri * theta.cos(), ri * theta.sin());
            let moment: f64 = blocks
                .iter()
                .filter(|&&i| model.centroids()[i][1].atan2(model.centroids()[i][0]) > theta)
                .map(|&i| model.weight()[i] * (xj - model.centroids()[i][0]))
                .sum();
            (moment / (re - yj), j)
        })
        .fold((f64::MIN, 0), |a, b| if b.0 > a.0 { b } else { a })
}

/// The interfaces between voussoirs `k - 1` and `k` (counted from the left springing).
fn joint(model: &Model, k: usize) -> usize {
    model.interfaces().iter().position(|it| (it.a.min(it.b), it.a.max(it.b)) == (k - 1, k)).unwrap()
}

/// The right abutment spreading (+x): the thrust at delta = 0 is the least of the arch as built
/// (its line of thrust, independent of the program, to 1e-6); the mechanism has three hinges,
/// at the crown and at the haunches' joints where that line touches the intrados, rocking
/// (nothing slides); the thrust rises as the abutment spreads (3234 N to 4265 N, flat at the
/// end), and the walk ends where the arch has no equilibrium (0.2164 m), at the same spread
/// (within 0.1%) with steps of 4 and 2 mm.
#[test]
fn a_semicircular_arch_on_a_spreading_abutment_falls_at_a_spread() {
    let model = semicircular();
    let (h_min, haunch) = least_thrust(&model);
    let spread = SupportMovement { support: 1, direction: Direction::PlusX };
    let run = |step: f64| follow_movement(&model, &spread, &LimitOptions::default(), &FollowOptions { step, max_steps: 20_000 }, &mut |_| true).unwrap();
    let r = run(0.004);
    assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
    assert!(r.error.is_none());
    assert_eq!(r.control_block, model.supports().start + 1);
    assert!((r.collapse_multiplier - h_min).abs() <= 1e-6 * h_min, "{} against {h_min}", r.collapse_multiplier);
    assert_eq!(r.curve_multiplier[0], r.collapse_multiplier);
    // three hinges: the crown's joint and the haunches', symmetric
    let hinges: Vec<usize> = (0..r.interface_states.len()).filter(|&k| r.interface_states[k] != 0).collect();
    let mut expected = vec![joint(&model, haunch), joint(&model, N / 2), joint(&model, N - haunch)];
    expected.sort();
    assert_eq!(hinges, expected, "haunch at joint {haunch}");
    assert!(hinges.iter().all(|&k| r.interface_states[k] == ROCKING));
    // the thrust rises with the spread, the support moving out by positive steps
    assert!(r.curve_displacement.windows(2).all(|w| w[1] > w[0]));
    // (to the program's precision: it flattens at the end)
    assert!(r.curve_multiplier.windows(2).all(|w| w[1] > w[0] - 1e-6 * w[0]));
    assert!(r.last_equilibrium > 1.2 * r.collapse_multiplier);
    let end = r.curve_displacement[r.steps];
    assert_eq!(r.last_equilibrium, r.curve_multiplier[r.steps]);
    assert!((r.displacements[r.control_block][0] - end).abs() < 1e-12);
    let finer = run(0.002);
    assert_eq!(finer.status, Status::Collapse, "{:?}", finer.error);
    let end_finer = finer.curve_displacement[finer.steps];
    assert!((end - end_finer).abs() <= 1e-3 * end, "{end} against {end_finer}");
    // the left abutment moving out (-x) is the same arch's spread, mirrored: one step of it
    let left = SupportMovement { support: 0, direction: Direction::MinusX };
    let l = follow_movement(&model, &left, &LimitOptions::default(), &FollowOptions { step: 0.004, max_steps: 1 }, &mut |_| true).unwrap();
    assert_eq!(l.status, Status::Completed, "{:?}", l.error);
    assert!(l.collapse_multiplier.is_nan() && l.error.as_deref().is_some_and(|e| e.contains("the steps ran out")));
    assert!((l.curve_multiplier[0] - h_min).abs() <= 1e-6 * h_min);
    assert!(l.curve_displacement[1] > 0.0 && l.displacements[model.supports().start][0] < 0.0);
}

/// A support that does not exist, and follow options out of range, are refused naming the key.
#[test]
fn a_movement_of_no_support_is_refused_naming_the_key() {
    let model = semicircular();
    let e = follow_movement(&model, &SupportMovement { support: 2, direction: Direction::PlusX }, &LimitOptions::default(), &FollowOptions::default(), &mut |_| true).unwrap_err();
    assert!(e.to_string().contains("analysis.move_support"), "{e}");
    let e = follow_movement(&model, &SupportMovement { support: 1, direction: Direction::PlusX }, &LimitOptions::default(), &FollowOptions { step: -1.0, max_steps: 10 }, &mut |_| true).unwrap_err();
    assert!(e.to_string().contains("analysis.follow_step"), "{e}");
    let e = "x".parse::<Direction>().unwrap_err();
    assert!(e.to_string().contains("analysis.move_direction"), "{e}");
}

/// The limit analysis's curve (`d`, `h`) at `x`, linear between its points.
fn at(d: &[f64], h: &[f64], x: f64) -> f64 {
    let k = d.partition_point(|&v| v < x).clamp(1, d.len() - 1);
    h[k - 1] + (h[k] - h[k - 1]) * (x - d[k - 1]) / (d[k] - d[k - 1])
}

/// The same spread by the explicit solver with finite rotations, the abutment pushed 0.25 m in
/// 50 stages: the arch falls (a stage at which a voussoir moves more than 1% of the model's size
/// once the abutment is held) between two stages around the limit analysis's spread, their
/// midpoint within 5% of it, and the thrust measured at the stages that settled follows the
/// least thrust on the moved geometry within 1% (from the first stage on: the dead state's is
/// the elastic arch's, above the least).
#[test]
fn the_explicit_solver_pushing_the_abutment_finds_the_same_spread() {
    use masonry_dem::explicit::{solve_movement, Control, ExplicitOptions};
    let model = semicircular();
    let spread = SupportMovement { support: 1, direction: Direction::PlusX };
    let lim = follow_movement(&model, &spread, &LimitOptions::default(), &FollowOptions { step: 0.004, max_steps: 20_000 }, &mut |_| true).unwrap();
    assert_eq!(lim.status, Status::Collapse);
    let end = lim.curve_displacement[lim.steps];
    let opts = ExplicitOptions { control: Control::Displacement { max_displacement: 0.25 }, steps: 50, large_rotations: true, ..ExplicitOptions::default() };
    let r = solve_movement(&model, &spread, &opts, &mut |_| true).unwrap();
    assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
    let [below, above] = r.bracket.unwrap();
    assert_eq!(below, *r.curve_displacement.last().unwrap());
    assert!(((below + above) / 2.0 - end).abs() <= 0.05 * end, "fell between {below} and {above}, limit analysis {end}");
    assert!(r.curve_multiplier[0] > lim.collapse_multiplier);
    for (d, h) in r.curve_displacement.iter().zip(&r.curve_multiplier).skip(1) {
        let least = at(&lim.curve_displacement, &lim.curve_multiplier, *d);
        assert!((h - least).abs() <= 0.01 * least, "{h} against {least} at {d}");
    }
    assert_eq!(r.last_equilibrium, *r.curve_multiplier.last().unwrap());
    assert_eq!(r.collapse_multiplier, r.last_equilibrium);
}
