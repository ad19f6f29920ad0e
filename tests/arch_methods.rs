//! Arches under their own weight and a horizontal load proportional to it (lambda times each
//! voussoir's weight, at its centroid) by the three methods: the static path's collapse
//! multiplier within 0.1% of limit analysis, the explicit solver's within 2%. A semicircular arch
//! at t/R = 0.15 and 0.20 (R the centreline's radius), a segmental and a pointed arch, each on
//! its abutments, with associative friction high enough (2) that no joint slides: limit
//! analysis is then the exact collapse multiplier of the incremental model. Limit analysis
//! itself is checked against a program written from the polygons alone in
//! tests/python/test_arch_lp.py, and against the four-hinge mechanisms in test_arch.py.
//!
//! A semicircular arch with a backfill (loads carried by the voussoirs, `Arch::backfill`) goes
//! through the same three methods with the same tolerances.
//!
//! The explicit solver's bracket is 1e-3 wide (its default tolerance) and its levels relax to
//! 1e-5 of the applied forces; it runs at 20 voussoirs (its cost grows with the voussoirs: a
//! few hundred thousand to over a million time steps here), the static path and limit analysis
//! at 20 and 80.

use masonry_dem::explicit::{self, ExplicitOptions};
use masonry_dem::geometry::{arch, Arch, ArchKind, Springing};
use masonry_dem::joint::JointLaw;
use masonry_dem::limit::{limit_analysis, LimitOptions};
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::results::{Results, Status};
use masonry_dem::static_solver::{self, StaticOptions};

/// The arches: a name and the generator's parameters but the number of voussoirs (an even
/// number of them for the pointed arch).
fn arches() -> Vec<(&'static str, Arch)> {
    let on = |kind, span, radius, rise, thickness| Arch {
        kind,
        span,
        radius,
        rise,
        thickness,
        voussoirs: 0,
        springing: Springing::Abutments { width: None, height: None },
        backfill: None,
    };
    vec![
        ("semicircular, t/R = 0.15", on(ArchKind::Semicircular, None, Some(1.0), None, 0.15)),
        ("semicircular, t/R = 0.20", on(ArchKind::Semicircular, None, Some(1.0), None, 0.20)),
        ("segmental", on(ArchKind::Segmental, Some(4.0), None, Some(1.0), 0.3)),
        ("pointed", on(ArchKind::Pointed, Some(3.0), None, Some(2.2), 0.25)),
    ]
}

/// The model of `arch` with `n` voussoirs: friction 2 (associative), g = 10, the default
/// horizontal live load.
fn model(arch_: &Arch, n: usize) -> Model {
    let a = arch(&Arch { voussoirs: n, ..*arch_ }).unwrap();
    let law = JointLaw { friction: 2.0, dilatancy: 2.0, ..JointLaw::default() };
    Model::new(ModelSpec { blocks: a.blocks, supports: a.supports, base: false, joints: JointLaws::uniform(law), gravity: 10.0, ..ModelSpec::default() })
        .unwrap()
}

fn collapse(r: &Results, what: &str) -> f64 {
    assert_eq!(r.status, Status::Collapse, "{what}: {:?}", r.error);
    r.collapse_multiplier
}

fn limit(m: &Model, what: &str) -> f64 {
    collapse(&limit_analysis(m, &LimitOptions { tolerance: 1e-10, ..LimitOptions::default() }).unwrap(), what)
}

#[test]
fn the_static_path_of_an_arch_collapses_at_its_limit_multiplier() {
    for (name, a) in arches() {
        for n in [20, 80] {
            let what = format!("{name}, {n} voussoirs");
            let m = model(&a, n);
            let exact = limit(&m, &what);
            let path = collapse(&static_solver::solve(&m, &StaticOptions::default()).unwrap(), &what);
            assert!((path - exact).abs() <= 1e-3 * exact, "{what}: the static path's {path:.6} against {exact:.6}");
        }
    }
}

#[test]
fn the_explicit_solver_of_an_arch_collapses_at_its_limit_multiplier() {
    for (name, a) in arches() {
        let what = format!("{name}, 20 voussoirs");
        let m = model(&a, 20);
        let exact = limit(&m, &what);
        let relaxed = collapse(&explicit::solve(&m, &ExplicitOptions { threads: 1, ..ExplicitOptions::default() }).unwrap(), &what);
        assert!((relaxed - exact).abs() <= 0.02 * exact, "{what}: the explicit solver's {relaxed:.6} against {exact:.6}");
    }
}

/// The semicircular arch of t/R = 0.15 with `n` voussoirs and a backfill of the blocks' density
/// (1000 kg/m3) up to 1.3 m, 0.225 m over the extrados's crown; friction 2, g = 10.
fn backfilled(n: usize) -> Model {
    let (_, a) = arches().swap_remove(0);
    let a = arch(&Arch { voussoirs: n, backfill: Some(1.3), ..a }).unwrap();
    let spec = ModelSpec::default();
    let carried = a.fill_loads(spec.density, spec.thickness, 10.0).unwrap();
    assert_eq!(carried.len(), n);
    let law = JointLaw { friction: 2.0, dilatancy: 2.0, ..JointLaw::default() };
    Model::new(ModelSpec { blocks: a.blocks, supports: a.supports, base: false, joints: JointLaws::uniform(law), gravity: 10.0, carried, ..spec })
        .unwrap()
}

#[test]
fn a_backfilled_arch_collapses_alike_by_the_three_methods() {
    let m = backfilled(20);
    let what = "backfilled semicircular arch, 20 voussoirs";
    let exact = limit(&m, what);
    // the fill changes the arch's multiplier: its weight is carried, and it is pushed too
    let bare = limit(&model(&arches()[0].1, 20), "the same arch bare");
    assert!((exact - bare).abs() > 0.01 * bare, "{exact} against the bare arch's {bare}");
    let path = collapse(&static_solver::solve(&m, &StaticOptions::default()).unwrap(), what);
    assert!((path - exact).abs() <= 1e-3 * exact, "{what}: the static path's {path:.6} against {exact:.6}");
    let relaxed = collapse(&explicit::solve(&m, &ExplicitOptions { threads: 1, ..ExplicitOptions::default() }).unwrap(), what);
    assert!((relaxed - exact).abs() <= 0.02 * exact, "{what}: the explicit solver's {relaxed:.6} against {exact:.6}");
    let m = backfilled(80);
    let exact = limit(&m, "80 voussoirs");
    let path = collapse(&static_solver::solve(&m, &StaticOptions::default()).unwrap(), "80 voussoirs");
    assert!((path - exact).abs() <= 1e-3 * exact, "80 voussoirs: the static path's {path:.6} against {exact:.6}");
}
