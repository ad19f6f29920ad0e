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
    let dt = masonry_dem::explicit::history_time_step_limit(&m, 0.0) * 0.5;
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
