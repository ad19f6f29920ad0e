//! Bad input is refused with a message that names the key or block.

use masonry_dem::geometry::{pattern, running_bond, FirstCourse, Rect, RunningBond};
use masonry_dem::joint::JointLaw;
use masonry_dem::model::{JointLaws, LiveLoad, Model, ModelSpec};
use masonry_dem::static_solver::{solve, StaticOptions};
use masonry_dem::Error;

fn refused(spec: ModelSpec, needle: &str) {
    match Model::new(spec) {
        Err(Error::Input(m)) => {
            assert!(m.contains(needle), "message {m:?} does not name {needle:?}")
        }
        other => panic!("expected an input error naming {needle:?}, got {other:?}"),
    }
}

fn one(blocks: Vec<Rect>) -> ModelSpec {
    ModelSpec {
        blocks,
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
        Err(Error::Input(msg)) => assert!(msg.contains("no support"), "{msg}"),
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
            length: 2.0,
            first_course: FirstCourse::Half,
            openings: vec![],
        };
        f(&mut p);
        running_bond(&p)
    };
    assert!(
        matches!(rb(|p| p.block_length = -1.0), Err(Error::Input(m)) if m.contains("block_length"))
    );
    assert!(matches!(rb(|p| p.courses = 0), Err(Error::Input(m)) if m.contains("courses")));
    assert!(matches!(rb(|p| p.length = 1e12), Err(Error::Input(m)) if m.contains("blocks")));
    assert!(
        matches!(pattern(0.4, 0.2, &[vec![1.0, 0.0]]), Err(Error::Input(m)) if m.contains("rows[0][1]"))
    );
}

#[test]
fn generators_give_the_documented_walls() {
    let p = RunningBond {
        block_length: 0.4,
        block_height: 0.175,
        courses: 10,
        length: 2.0,
        first_course: FirstCourse::Half,
        openings: vec![],
    };
    assert_eq!(running_bond(&p).unwrap().len(), 55); // Ferris & Tin-Loi wall 2
    let with_opening = RunningBond {
        openings: vec![Rect::new(0.6, 0.525, 1.0, 1.4)],
        ..p
    };
    assert!(running_bond(&with_opening).unwrap().len() < 55);
    let b = pattern(0.4, 0.175, &[vec![0.5, 1.0, -1.0, 1.0], vec![1.0, 1.0]]).unwrap();
    assert_eq!(b.len(), 5);
    // half block [0, 0.2], block [0.2, 0.6], gap [0.6, 1.0], block [1.0, 1.4]
    assert!(
        (b[2].x0 - 1.0).abs() < 1e-12 && (b[2].x1 - 1.4).abs() < 1e-12,
        "{:?}",
        b[2]
    );
}
