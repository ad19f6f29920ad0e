//! The explicit solver against the references (docs/references.md, sections 1 and 2) and against the
//! static solver: quasi-static collapse multipliers within 2%.

mod common;
use common::*;
use masonry_dem::explicit::{solve, ExplicitOptions};
use masonry_dem::geometry::Rect;
use masonry_dem::results::Status;
use masonry_dem::static_solver;

fn collapse(model: &masonry_dem::Model) -> f64 {
    let t = std::time::Instant::now();
    let r = solve(model, &ExplicitOptions::default()).unwrap();
    eprintln!("explicit: {:?} {} in {:?}, {} time steps", r.status, r.collapse_multiplier, t.elapsed(), r.iterations);
    assert_eq!(r.status, Status::Collapse, "status {:?}, error {:?}", r.status, r.error);
    r.collapse_multiplier
}

fn agrees_with_static(model: &masonry_dem::Model, lam: f64) {
    let s = static_solver::solve(model, &static_solver::StaticOptions::default()).unwrap();
    assert_close(lam, s.collapse_multiplier, 0.02, "explicit against static");
}

#[test]
fn single_block_slides_at_mu() {
    let m = blocks_model(vec![Rect::new(0.0, 0.0, 0.4, 0.175)], dry(0.65, 0.0, 1e10));
    let l = collapse(&m);
    assert_close(l, 0.65, 0.02, "sliding block (explicit)");
    agrees_with_static(&m, l);
}

#[test]
fn single_block_rocks_at_b_over_h() {
    let m = blocks_model(vec![Rect::new(0.0, 0.0, 0.2, 0.6)], dry(0.65, 0.0, 1e10));
    let l = collapse(&m);
    assert_close(l, 1.0 / 3.0, 0.02, "rocking block (explicit)");
    agrees_with_static(&m, l);
}

#[test]
fn ferris_wall1_associative() {
    let m = ferris(6, dry(0.65, 0.65, 1e10));
    let l = collapse(&m);
    assert_close(l, 0.6429, 0.02, "wall 1 associative (explicit)");
    agrees_with_static(&m, l);
}

#[test]
fn ferris_wall2_associative() {
    let m = ferris(10, dry(0.65, 0.65, 1e10));
    let l = collapse(&m);
    assert_close(l, 0.5800, 0.02, "wall 2 associative (explicit)");
    agrees_with_static(&m, l);
}

#[test]
fn ferris_wall2_non_associative() {
    let m = ferris(10, dry(0.65, 0.0, 1e10));
    let l = collapse(&m);
    assert_close(l, 0.563, 0.02, "wall 2 non-associative (explicit)");
    agrees_with_static(&m, l);
}

#[test]
fn displacement_control_of_wall1_peaks_at_the_collapse_multiplier() {
    use masonry_dem::explicit::Control;
    let m = ferris(6, dry(0.65, 0.65, 1e10));
    let opts = ExplicitOptions { control: Control::Displacement { max_displacement: 0.002 }, steps: 40, threads: 1, ..Default::default() };
    let r = solve(&m, &opts).unwrap();
    assert_ne!(r.status, Status::Failed, "{:?}", r.error);
    assert_close(r.collapse_multiplier, 0.6429, 0.02, "wall 1 peak, explicit displacement control");
    assert!((r.curve_displacement.last().unwrap() - 0.002).abs() < 1e-9);
}
