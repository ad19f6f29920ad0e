//! Bad input is refused with a message that names the key or block.

use masonry_dem::geometry::{polygons, pattern, running_bond, FirstCourse, Rect, RunningBond};
use masonry_dem::joint::JointLaw;
use masonry_dem::model::{JointLaws, LiveLoad, Model, ModelSpec};
use masonry_dem::static_solver::{solve, StaticOptions};
use masonry_dem::Error;

fn refused(spec: ModelSpec, needle: &str) {
    match Model::new(spec) {
        Err(Error::Input { reason: m, .. }) => {
            assert!(m.contains(needle), "message {m:?} does not name {needle:?}")
        }
        other => panic!("expected an input error naming {needle:?}, got {other:?}"),
    }
}

fn one(blocks: Vec<Rect>) -> ModelSpec {
    ModelSpec {
        blocks: polygons(blocks),
        ..ModelSpec::default()
    }
}

#[test]
fn overlapping_blocks_are_named() {
    refused(
        one(vec![
            Rect::new(0.0, 0.0, 1.0, 1.0),
            Rect::new(0.5, 0.5, 1.5, 1.5),
        ]),
        "block 0",
    );
    refused(
        one(vec![
            Rect::new(0.0, 0.0, 1.0, 1.0),
            Rect::new(0.5, 0.5, 1.5, 1.5),
        ]),
        "block 1",
    );
}

#[test]
fn a_block_touching_nothing_is_named() {
    refused(
        one(vec![
            Rect::new(0.0, 0.0, 1.0, 1.0),
            Rect::new(0.0, 2.0, 1.0, 3.0),
        ]),
        "block 1",
    );
}

#[test]
fn degenerate_and_non_finite_blocks_are_named() {
    refused(one(vec![Rect::new(0.0, 0.0, 0.0, 1.0)]), "block 0");
    refused(one(vec![Rect::new(0.0, 0.0, f64::NAN, 1.0)]), "block 0");
    refused(one(vec![]), "no blocks");
}

#[test]
fn bad_numbers_name_their_key() {
    let b = vec![Rect::new(0.0, 0.0, 1.0, 1.0)];
    refused(
        ModelSpec {
            thickness: 0.0,
            ..one(b.clone())
        },
        "thickness",
    );
    refused(
        ModelSpec {
            density: f64::INFINITY,
            ..one(b.clone())
        },
        "density",
    );
    refused(
        ModelSpec {
            gravity: -1.0,
            ..one(b.clone())
        },
        "gravity",
    );
    let bad = |law: JointLaw| ModelSpec {
        joints: JointLaws {
            bed: Some(law),
            ..JointLaws::default()
        },
        ..one(b.clone())
    };
    refused(
        bad(JointLaw {
            friction: -0.1,
            ..JointLaw::default()
        }),
        "joints.bed.friction",
    );
    // an angle in degrees given for tan(phi): refused, with the coefficient it most likely means
    refused(
        bad(JointLaw {
            friction: 35.0,
            ..JointLaw::default()
        }),
        "joints.bed.friction = 35 is mu = tan(phi), a coefficient, and must be at most 20 (phi = 87.1 deg); a friction angle of 35 deg is friction = 0.700",
    );
    refused(
        bad(JointLaw {
            normal_stiffness: 0.0,
            ..JointLaw::default()
        }),
        "joints.bed.normal_stiffness",
    );
    refused(
        bad(JointLaw {
            dilatancy: 0.9,
            ..JointLaw::default()
        }),
        "joints.bed.dilatancy",
    );
    refused(
        bad(JointLaw {
            cohesion: f64::NAN,
            ..JointLaw::default()
        }),
        "joints.bed.cohesion",
    );
    refused(
        ModelSpec {
            live: LiveLoad::TopHorizontal,
            ..one(b)
        },
        "top beam",
    );
}

#[test]
fn a_wall_without_support_is_refused() {
    let m = Model::new(ModelSpec {
        base: false,
        ..one(vec![
            Rect::new(0.0, 0.0, 1.0, 1.0),
            Rect::new(0.0, 1.0, 1.0, 2.0),
        ])
    })
    .unwrap();
    match solve(&m, &StaticOptions::default()) {
        Err(Error::Input { reason: msg, .. }) => assert!(msg.contains("no support"), "{msg}"),
        other => panic!("expected no support, got {other:?}"),
    }
}

#[test]
fn generators_refuse_bad_parameters() {
    let rb = |f: fn(&mut RunningBond)| {
        let mut p = RunningBond {
            block_length: 0.4,
            block_height: 0.2,
            courses: 2,
            height: None,
            length: 2.0,
            first_course: FirstCourse::Half,
            openings: vec![],
        };
        f(&mut p);
        running_bond(&p)
    };
    assert!(
        matches!(rb(|p| p.block_length = -1.0), Err(Error::Input { reason: m, .. }) if m.contains("block_length"))
    );
    assert!(matches!(rb(|p| p.courses = 0), Err(Error::Input { reason: m, .. }) if m.contains("courses")));
    assert!(matches!(rb(|p| p.length = 1e12), Err(Error::Input { reason: m, .. }) if m.contains("blocks")));
    assert!(
        matches!(pattern(0.4, 0.2, &[vec![1.0, 0.0]]), Err(Error::Input { reason: m, .. }) if m.contains("rows[0][1]"))
    );
}

#[test]
fn generators_give_the_documented_walls() {
    let p = RunningBond {
        block_length: 0.4,
        block_height: 0.175,
        courses: 10,
        height: None,
        length: 2.0,
        first_course: FirstCourse::Half,
        openings: vec![],
    };
    assert_eq!(running_bond(&p).unwrap().len(), 55); // Ferris & Tin-Loi wall 2
    let with_opening = RunningBond {
        openings: vec![Rect::new(0.6, 0.525, 1.0, 1.4)],
        ..p
    };
    let opened = running_bond(&with_opening).unwrap();
    assert!(opened.len() < 55);
    // the blocks astride the opening's edges are cut there: exactly its 0.4 x 0.875 m is removed
    let removed = 2.0 * 1.75 - opened.iter().map(Rect::area).sum::<f64>();
    assert!((removed - 0.35).abs() < 1e-12, "removed {removed} m2");
    let b = pattern(0.4, 0.175, &[vec![0.5, 1.0, -1.0, 1.0], vec![1.0, 1.0]]).unwrap();
    assert_eq!(b.len(), 5);
    // half block [0, 0.2], block [0.2, 0.6], gap [0.6, 1.0], block [1.0, 1.4]
    assert!(
        (b[2].x0 - 1.0).abs() < 1e-12 && (b[2].x1 - 1.4).abs() < 1e-12,
        "{:?}",
        b[2]
    );
}

#[test]
fn blocks_name_their_coordinates() {
    refused(one(vec![Rect::new(0.0, 0.0, 0.0, 1.0)]), "block 0 [0, 0, 0, 1]");
    refused(
        one(vec![Rect::new(0.0, 0.0, 1.0, 1.0), Rect::new(0.0, 1.0, f64::INFINITY, 2.0)]),
        "block 1 [0, 1, inf, 2]",
    );
}

#[test]
fn masses_that_overflow_or_underflow_are_refused() {
    // density * area * thickness overflows
    refused(
        ModelSpec {
            density: 1e300,
            thickness: 1e10,
            ..one(vec![Rect::new(0.0, 0.0, 1.0, 1.0)])
        },
        "block 0",
    );
    // a block of 1e-170 m: its area underflows to zero
    refused(one(vec![Rect::new(0.0, 0.0, 1e-170, 1e-170)]), "block 0");
    // the weight overflows
    refused(
        ModelSpec {
            gravity: 1e305,
            density: 1e10,
            ..one(vec![Rect::new(0.0, 0.0, 1.0, 1.0)])
        },
        "loads.gravity",
    );
}

fn a_model() -> Model {
    Model::new(one(vec![Rect::new(0.0, 0.0, 0.4, 0.2)])).unwrap()
}

fn input_message<T: std::fmt::Debug>(r: Result<T, Error>) -> String {
    match r {
        Err(Error::Input { reason: m, .. }) => m,
        other => panic!("expected an input error, got {other:?}"),
    }
}

#[test]
fn absurd_step_counts_are_refused_before_running() {
    use masonry_dem::error::MAX_STEPS;
    use masonry_dem::explicit::{self, ExplicitOptions};
    let m = a_model();
    for steps in [0usize, MAX_STEPS + 1, 1_000_000_000_000] {
        let msg = input_message(solve(&m, &StaticOptions { steps, ..StaticOptions::default() }));
        assert!(msg.contains("analysis.steps"), "{msg}");
        let msg = input_message(explicit::solve(&m, &ExplicitOptions { steps, ..ExplicitOptions::default() }));
        assert!(msg.contains("analysis.steps"), "{msg}");
    }
    let msg = input_message(solve(&m, &StaticOptions { steps: 1_000_000_000_000, ..StaticOptions::default() }));
    assert!(msg.contains("1000000000000"), "the message names the count: {msg}");
}

#[test]
fn solver_options_name_their_key() {
    use masonry_dem::explicit::{self, Damping, ExplicitOptions};
    use masonry_dem::static_solver::Control;
    let m = a_model();
    let st = |o: StaticOptions| input_message(solve(&m, &o));
    let d = StaticOptions::default();
    assert!(st(StaticOptions { tolerance: 0.0, ..d }).contains("analysis.tolerance"));
    assert!(st(StaticOptions { tolerance: f64::NAN, ..d }).contains("analysis.tolerance"));
    for x in [0.0, f64::NAN, f64::INFINITY] {
        let o = StaticOptions { control: Control::Displacement { max_displacement: x }, ..d };
        assert!(st(o).contains("analysis.max_displacement"));
    }
    let ex = |o: ExplicitOptions| input_message(explicit::solve(&m, &o));
    let e = ExplicitOptions::default();
    for dt in [0.0, -1.0, f64::NAN, 1e9] {
        assert!(ex(ExplicitOptions { time_step: Some(dt), ..e }).contains("analysis.time_step"));
    }
    assert!(ex(ExplicitOptions { damping: Damping::Local(1.0), ..e }).contains("analysis.damping_coefficient"));
    assert!(ex(ExplicitOptions { damping: Damping::Viscous(-1.0), ..e }).contains("analysis.damping_coefficient"));
    assert!(ex(ExplicitOptions { unbalanced_ratio: 2.0, ..e }).contains("analysis.unbalanced_ratio"));
    assert!(ex(ExplicitOptions { threads: 1 << 30, ..e }).contains("analysis.threads"));
}

#[test]
fn a_time_history_too_large_to_record_is_refused_before_allocating() {
    use masonry_dem::explicit::{simulate, DynamicOptions};
    let m = a_model();
    // about 1e16 time steps: refused by count
    let msg = input_message(simulate(&m, &DynamicOptions { duration: 1e12, ..DynamicOptions::default() }));
    assert!(msg.contains("time steps"), "{msg}");
    // recording every step of a long run would store too many numbers
    let dt = masonry_dem::explicit::history_time_step_limit(&m, 0.0, true) * 0.5;
    let msg = input_message(simulate(
        &m,
        &DynamicOptions { duration: 1e9 * dt, time_step: Some(dt), record: masonry_dem::explicit::Recording::Every(1), ..DynamicOptions::default() },
    ));
    assert!(msg.contains("record_every") && msg.contains("record_interval"), "{msg}");
}

#[test]
fn generator_keys_are_case_file_keys() {
    let p = RunningBond {
        block_length: 0.4,
        block_height: f64::NAN,
        courses: 2,
        height: None,
        length: 2.0,
        first_course: FirstCourse::Half,
        openings: vec![],
    };
    assert!(matches!(running_bond(&p), Err(Error::Input { reason: m, .. }) if m.contains("geometry.running_bond.block_height")));
    let tall = RunningBond { block_height: 1e300, courses: 1_000_000_000, length: 0.4, ..p.clone() };
    assert!(matches!(running_bond(&tall), Err(Error::Input { reason: m, .. }) if m.contains("geometry.running_bond")));
    let bad_opening = RunningBond { block_height: 0.2, openings: vec![Rect::new(1.0, 0.0, 0.0, 1.0)], ..p.clone() };
    assert!(matches!(running_bond(&bad_opening), Err(Error::Input { reason: m, .. }) if m.contains("geometry.running_bond.openings[0]")));
    // 10^9 blocks: refused by count before allocating
    let huge = RunningBond { block_height: 0.2, length: 4e8, courses: 1000, ..p };
    assert!(matches!(running_bond(&huge), Err(Error::Input { reason: m, .. }) if m.contains("blocks") && m.contains("limit")));
    assert!(
        matches!(pattern(0.4, 0.2, &[vec![1e308; 5]]), Err(Error::Input { reason: m, .. }) if m.contains("geometry.pattern.rows[0][4]"))
    );
}

#[test]
fn one_huge_block_over_many_small_ones_builds_in_linear_memory() {
    // 20,000 blocks of 1 mm under one block of 10 km: on a grid of cells the size of the mean
    // block, the large block alone would cover about 10^8 cells.
    let mut blocks: Vec<Rect> = (0..20_000)
        .map(|i| Rect::new(i as f64 * 1e-3, 0.0, (i + 1) as f64 * 1e-3, 1e-3))
        .collect();
    blocks.push(Rect::new(0.0, 1e-3, 1e4, 1e4));
    let start = std::time::Instant::now();
    let m = Model::new(one(blocks)).unwrap();
    assert_eq!(m.n_wall(), 20_001);
    assert!(start.elapsed().as_secs_f64() < 30.0, "{:?}", start.elapsed());
}

#[test]
fn driving_an_unloaded_top_beam_is_refused() {
    use masonry_dem::model::TopBeam;
    use masonry_dem::static_solver::Control;
    let model = Model::new(ModelSpec {
        blocks: vec![Rect::new(0.0, 0.0, 0.5, 0.5).into()],
        top: Some(TopBeam { rotation_fixed: false, force: [0.0, 0.0], vertical_held: false }),
        ..ModelSpec::default()
    })
    .unwrap();
    let opts = StaticOptions { control: Control::Displacement { max_displacement: 1e-3 }, ..Default::default() };
    match solve(&model, &opts) {
        Err(Error::Input { reason: m, .. }) => assert!(m.contains("top beam") && m.contains("top.force"), "{m}"),
        other => panic!("expected an input error, got {other:?}"),
    }
    // with a force on it the beam is tied to the wall by friction: accepted
    let loaded = Model::new(ModelSpec {
        blocks: vec![Rect::new(0.0, 0.0, 0.5, 0.5).into()],
        top: Some(TopBeam { rotation_fixed: false, force: [0.0, -1000.0], vertical_held: false }),
        ..ModelSpec::default()
    })
    .unwrap();
    assert!(solve(&loaded, &opts).is_ok());
}

/// A wall whose weight is too small for the solvers' products of forces is refused by its density
/// before any method runs: the static solver used to fail with "the live load does no work", the
/// explicit one with "no collapse bracket", where limit analysis answered.
#[test]
fn a_weight_below_the_solvers_range_is_refused_by_its_density() {
    for density in [1e-300, 1e-160] {
        let spec = ModelSpec { density, ..one(vec![Rect::new(0.0, 0.0, 0.4, 1.0)]) };
        match Model::new(spec) {
            Err(Error::Input { key, reason }) => {
                assert_eq!(key.as_deref(), Some("geometry.density"), "{reason}");
                assert!(reason.starts_with(&format!("geometry.density = {density:e} kg/m3")), "{reason}");
            }
            other => panic!("expected the density refused, got {other:?}"),
        }
    }
}

/// The solvers refuse a control block whose horizontal displacement is held (the base): the curve
/// they follow on it would be zeros.
#[test]
fn a_held_control_block_is_refused() {
    use masonry_dem::analysis::Control;
    use masonry_dem::explicit::{self, ExplicitOptions};
    let m = a_model();
    let base = m.base().unwrap();
    let msg = input_message(explicit::solve(&m, &ExplicitOptions { control_block: Some(base), ..ExplicitOptions::default() }));
    assert!(msg.contains("control block 1 (the base) is held along x"), "{msg}");
    for control in [Control::Load, Control::Displacement { max_displacement: 1e-3 }] {
        let msg = input_message(solve(&m, &StaticOptions { control, control_block: Some(base), ..StaticOptions::default() }));
        assert!(msg.contains("is held along x"), "{msg}");
    }
}

#[test]
fn settings_under_which_no_relaxation_settles_are_refused_by_name() {
    use masonry_dem::explicit::{critical_time_step, critical_time_step_3d, solve, solve_3d, Damping, ExplicitOptions};
    use masonry_dem::interface::Family;
    use masonry_dem::space::{running_bond_3d, LiveLoad3, Model3, ModelSpec3};
    // a refusal's key and message
    let refusal = |r: Result<masonry_dem::results::Results<[f64; 3]>, Error>| match r {
        Err(Error::Input { key, reason }) => (key, reason),
        other => panic!("expected an input error, got {other:?}"),
    };
    let refusal3 = |r: Result<masonry_dem::results::Results<[f64; 6]>, Error>| match r {
        Err(Error::Input { key, reason }) => (key, reason),
        other => panic!("expected an input error, got {other:?}"),
    };
    // the number after `after` in a message
    let number = |m: &str, after: &str| -> f64 { m.split(after).nth(1).and_then(|t| t.split(' ').next()).and_then(|v| v.parse().ok()).unwrap() };
    // Ferris & Tin-Loi's wall 1 and a leaf in 3D (the explicit solver found no equilibrium under
    // the dead loads alone with either setting)
    let plane = Model::new(ModelSpec {
        blocks: polygons(running_bond(&RunningBond { block_length: 0.4, block_height: 0.175, courses: 6, height: None, length: 2.0, first_course: FirstCourse::Half, openings: vec![] }).unwrap()),
        ..ModelSpec::default()
    })
    .unwrap();
    let leaf = Model3::new(&ModelSpec3 { blocks: running_bond_3d(2.0, 1.05, 0.1, 0.4, 0.175, 0.2).unwrap(), live: LiveLoad3::HorizontalWeight { direction: 90.0 }, ..ModelSpec3::default() }).unwrap();

    // viscous damping: Verlet with -c m v is stable while c dt / 2 + (dt / limit)^2 <= 1; at the
    // automatic step (0.8 of the limit) c dt <= 0.72
    let viscous = |c: f64| ExplicitOptions { damping: Damping::Viscous(c), ..ExplicitOptions::default() };
    let (crit2, crit3) = (critical_time_step(&plane), critical_time_step_3d(&leaf));
    for (name, crit, (key, m)) in [("plane", crit2, refusal(solve(&plane, &viscous(1e5)))), ("3D", crit3, refusal3(solve_3d(&leaf, &viscous(1e5))))] {
        assert_eq!(key.as_deref(), Some("analysis.damping_coefficient"), "{name}: {m}");
        assert!(m.starts_with("analysis.damping_coefficient (viscous damping) = 1e5 1/s is unstable at the time step"), "{name}: {m}");
        let most = number(&m, "c may be at most ");
        assert!((most - 0.72 / (0.8 * crit)).abs() <= 1e-3 * most, "{name}: {m}");
    }
    // a coefficient within the bound is taken: a block settles under it and slides
    let block = a_model();
    let dt = 0.8 * critical_time_step(&block);
    let r = solve(&block, &ExplicitOptions { tolerance: 1e-2, ..viscous(0.5 / dt) }).unwrap();
    assert!(r.curve_multiplier.len() > 1, "{:?} {:?}", r.status, r.error);

    // a time step far below the limit: the wall's weight on its base joints vibrates with a period
    // of at least T = 2 pi sqrt(M / K) (M the mass free to move, K the base joints' normal stiffness:
    // Rayleigh's quotient of a vertical translation), and the dead loads alone take more than one
    // to settle: T / dt time steps against the 200,000 a level may take
    let small = ExplicitOptions { time_step: Some(1e-9), ..ExplicitOptions::default() };
    let period = |mass: f64, k: f64| 2.0 * std::f64::consts::PI * (mass / k).sqrt();
    let k2: f64 = plane.interfaces().iter().enumerate().filter(|(_, it)| it.family == Family::Base).map(|(k, _)| 1e10 * plane.sections()[k].area).sum();
    let t2 = period(plane.mass()[..plane.n_wall()].iter().sum(), k2);
    let k3: f64 = leaf.contacts().iter().filter(|c| c.family == Family::Base).map(|c| 1e10 * c.area).sum();
    let t3 = period(leaf.mass()[..leaf.n_wall()].iter().sum(), k3);
    for (name, t, (key, m)) in [("plane", t2, refusal(solve(&plane, &small))), ("3D", t3, refusal3(solve_3d(&leaf, &small)))] {
        assert_eq!(key.as_deref(), Some("analysis.time_step"), "{name}: {m}");
        assert!(m.starts_with("analysis.time_step = 1.000e-9 s is too small to relax the wall"), "{name}: {m}");
        let needed = number(&m, "takes more than one period, at least ");
        assert!((needed - t / 1e-9).abs() <= 1e-3 * needed, "{name}: {needed} time steps, T / dt = {}", t / 1e-9);
        assert!(m.contains("more than the 200000 a load level may take"), "{name}: {m}");
        // the smallest time step it takes, T / 200,000, runs
        let least = number(&m, "or take at least ");
        assert!((least - t / 2e5).abs() <= 1e-3 * least, "{name}: {m}");
    }
}
