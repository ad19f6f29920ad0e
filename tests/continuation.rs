//! The static path reaches the collapse where Newton stops converging below it: the
//! pseudo-transient continuation at fixed multipliers (src/static_solver/continuation.rs), on
//! walls of associative dry joints whose path used to end `Stalled` or short of the exact
//! multiplier (limit analysis, exact for these joints, computed here for each wall).

mod common;

use common::{blocks_model, dry, ferris_wall5_blocks, lact3_blocks};
use masonry_dem::geometry::polygons;
use masonry_dem::limit::{limit_analysis, LimitOptions};
use masonry_dem::model::{Model, ModelSpec, JointLaws};
use masonry_dem::results::Status;
use masonry_dem::static_solver::{solve, StaticOptions};

/// Load control to collapse, within `rel` below the limit-analysis multiplier and not above it.
fn reaches_limit(model: &Model, rel: f64, what: &str) {
    let exact = limit_analysis(model, &LimitOptions::default()).unwrap();
    assert_eq!(exact.status, Status::Collapse, "{what}: limit analysis {:?}", exact.error);
    let exact = exact.collapse_multiplier;
    let r = solve(model, &StaticOptions::default()).unwrap();
    assert_eq!(r.status, Status::Collapse, "{what}: {:?}", r.error);
    let lam = r.collapse_multiplier;
    // a converged equilibrium within the domain: a lower bound (to the solvers' round-off)
    assert!(lam <= exact * (1.0 + 1e-9), "{what}: {lam} above the limit load {exact}");
    assert!(lam >= exact * (1.0 - rel), "{what}: {lam}, {:.4}% below {exact}", 100.0 * (exact - lam) / exact);
}

/// The LACT3 wall (openings, a lintel; 182 blocks) with dilatancy = friction: its path stopped
/// converging 0.14% below the exact multiplier (status `Stalled`).
#[test]
fn lact3_associative_reaches_the_collapse() {
    let mu = 0.487733;
    let model = Model::new(ModelSpec {
        blocks: polygons(lact3_blocks()),
        gravity: 9.81,
        joints: JointLaws::uniform(dry(mu, mu, 1e10)),
        ..ModelSpec::default()
    })
    .unwrap();
    assert_eq!(model.n_wall(), 182);
    reaches_limit(&model, 5e-4, "LACT3 associative");
}

/// Ferris & Tin-Loi's wall 5 (two windows), associative: its path ended 0.07% below.
#[test]
fn ferris_wall5_associative_reaches_the_collapse() {
    let blocks = ferris_wall5_blocks();
    assert_eq!(blocks.len(), 61);
    reaches_limit(&blocks_model(blocks, dry(0.65, 0.65, 1e10)), 5e-4, "wall 5 associative");
}
