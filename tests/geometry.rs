//! The running-bond generator on a real wall: a height instead of a number of courses (the last
//! course cut to fit, a sliver refused with the nearest fits), and openings cut out of the blocks
//! (straight jambs, exactly the opening's area removed) on a wall whose analysis still runs.

mod common;

use common::dry;
use masonry_dem::error::Error;
use masonry_dem::geometry::{
    courses_for_height, cut_openings, polygons, running_bond, FirstCourse, Rect, RunningBond, MIN_PART,
};
use masonry_dem::limit::{limit_analysis, LimitOptions};
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::results::Status;

/// The wall of the issue: 0.25 x 0.12 m blocks, 4 m long, 2.5 m high.
fn wall(openings: Vec<Rect>) -> RunningBond {
    RunningBond {
        block_length: 0.25,
        block_height: 0.12,
        courses: 0,
        height: Some(2.5),
        length: 4.0,
        first_course: FirstCourse::Half,
        openings,
    }
}

/// A 1.2 x 0.9 m window whose edges fall inside blocks (its sill mid-course, its jambs off the
/// joints of both kinds of course); whole-block removal took 1.05 of its 1.08 m2.
const WINDOW: Rect = Rect {
    x0: 1.1,
    y0: 0.9,
    x1: 2.3,
    y1: 1.8,
};

fn input_message(r: Result<Vec<Rect>, Error>) -> String {
    match r {
        Err(Error::Input { reason, .. }) => reason,
        other => panic!("expected an input error, got {other:?}"),
    }
}

fn top(blocks: &[Rect]) -> f64 {
    blocks.iter().map(|b| b.y1).fold(f64::MIN, f64::max)
}

#[test]
fn a_height_gives_whole_courses_and_a_last_one_cut_to_fit() {
    let blocks = running_bond(&wall(vec![])).unwrap();
    assert_eq!(top(&blocks), 2.5, "the wall is as high as asked");
    let last: Vec<_> = blocks.iter().filter(|b| b.y0 > 2.39).collect();
    assert!(!last.is_empty());
    for b in &last {
        assert!(
            (b.y0 - 2.4).abs() < 1e-12 && (b.height() - 0.1).abs() < 1e-12,
            "{b:?}"
        );
    }
    // the 20 whole courses are those of courses = 20
    let whole = running_bond(&RunningBond {
        courses: 20,
        height: None,
        ..wall(vec![])
    })
    .unwrap();
    assert_eq!(&blocks[..whole.len()], &whole[..]);
    // an exact fit (2.52 / 0.12 = 21.000000000000004) is 21 whole courses, nothing cut
    let fit = courses_for_height(0.12, 2.52).unwrap();
    assert_eq!((fit.whole, fit.last), (21, None));
    let exact = running_bond(&RunningBond {
        height: Some(2.52),
        ..wall(vec![])
    })
    .unwrap();
    assert_eq!(
        exact,
        running_bond(&RunningBond {
            courses: 21,
            height: None,
            ..wall(vec![])
        })
        .unwrap()
    );
    // a wall lower than one course but above the sliver limit is one cut course
    let low = running_bond(&RunningBond {
        height: Some(0.05),
        ..wall(vec![])
    })
    .unwrap();
    assert!(low.iter().all(|b| b.y0 == 0.0 && b.y1 == 0.05));
}

#[test]
fn a_sliver_of_a_last_course_is_refused_with_the_nearest_fits() {
    // 2.42 m: 20 courses (2.4 m) leave 0.02 m, under 25% of 0.12 m
    let m = input_message(running_bond(&RunningBond {
        height: Some(2.42),
        ..wall(vec![])
    }));
    assert!(
        m.starts_with("geometry.running_bond.height = 2.42 m"),
        "{m}"
    );
    assert!(
        m.contains("20 courses (2.4 m) leave a last course of 0.02 m"),
        "{m}"
    );
    assert!(m.contains("lower than 25% of block_height (0.03 m)"), "{m}");
    assert!(
        m.contains("use height = 2.4 m (20 courses) or 2.52 m (21 courses)"),
        "{m}"
    );
    assert!(
        m.contains("or block_height = 0.121 m (20 courses) or 0.115238 m (21 courses)"),
        "{m}"
    );
    // the fits proposed are taken
    for h in [2.4, 2.52] {
        assert!(running_bond(&RunningBond {
            height: Some(h),
            ..wall(vec![])
        })
        .is_ok());
    }
    let b = running_bond(&RunningBond {
        block_height: 0.121,
        height: Some(2.42),
        ..wall(vec![])
    })
    .unwrap();
    assert_eq!(top(&b), 20.0 * 0.121);
    // lower than a quarter course: only one course can fit
    let m = input_message(running_bond(&RunningBond {
        height: Some(0.02),
        ..wall(vec![])
    }));
    assert!(
        m.contains("use height = 0.12 m (1 course), or block_height = 0.02 m (1 course)"),
        "{m}"
    );
}

#[test]
fn courses_and_height_are_exclusive_and_checked() {
    let both = input_message(running_bond(&RunningBond {
        courses: 6,
        ..wall(vec![])
    }));
    assert!(
        both.contains("give exactly one of courses and height"),
        "{both}"
    );
    let neither = input_message(running_bond(&RunningBond {
        height: None,
        ..wall(vec![])
    }));
    assert!(
        neither.contains("geometry.running_bond.courses must be at least 1"),
        "{neither}"
    );
    assert!(
        neither.contains("geometry.running_bond.height"),
        "{neither}"
    );
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let m = input_message(running_bond(&RunningBond {
            height: Some(bad),
            ..wall(vec![])
        }));
        assert!(m.contains("geometry.running_bond.height"), "{bad}: {m}");
    }
    let m = input_message(running_bond(&RunningBond {
        block_height: 1e-300,
        ..wall(vec![])
    }));
    assert!(m.contains("geometry.running_bond"), "{m}");
}

#[test]
fn a_window_removes_exactly_its_area() {
    let solid: f64 = running_bond(&wall(vec![]))
        .unwrap()
        .iter()
        .map(Rect::area)
        .sum();
    assert!((solid - 4.0 * 2.5).abs() < 1e-9 * 10.0);
    let blocks = running_bond(&wall(vec![WINDOW])).unwrap();
    let removed = solid - blocks.iter().map(Rect::area).sum::<f64>();
    assert!(
        (removed - 1.08).abs() <= 1e-9 * 1.08,
        "removed {removed} m2 of a 1.08 m2 window"
    );
    for b in &blocks {
        b.validate("block").unwrap();
        let overlap_w = b.x1.min(WINDOW.x1) - b.x0.max(WINDOW.x0);
        let overlap_h = b.y1.min(WINDOW.y1) - b.y0.max(WINDOW.y0);
        assert!(
            overlap_w <= 1e-12 || overlap_h <= 1e-12,
            "{b:?} reaches into the window"
        );
    }
}

#[test]
fn the_jambs_are_straight() {
    let blocks = running_bond(&wall(vec![WINDOW])).unwrap();
    let beside = |b: &&Rect| b.y0 < WINDOW.y1 - 1e-9 && b.y1 > WINDOW.y0 + 1e-9;
    // in every course the window crosses, a block ends exactly at the left jamb and one starts at
    // the right jamb, and no block crosses either
    let courses: Vec<f64> = {
        let mut y: Vec<f64> = blocks.iter().filter(beside).map(|b| b.y0).collect();
        y.sort_by(f64::total_cmp);
        y.dedup();
        y
    };
    assert_eq!(
        courses.len(),
        8,
        "0.9 m from mid-course 7 to the joint of course 15: {courses:?}"
    );
    for y0 in courses {
        let course: Vec<&Rect> = blocks
            .iter()
            .filter(beside)
            .filter(|b| b.y0 == y0)
            .collect();
        assert!(
            course.iter().any(|b| b.x1 == WINDOW.x0),
            "course at {y0}: no block ends at the left jamb"
        );
        assert!(
            course.iter().any(|b| b.x0 == WINDOW.x1),
            "course at {y0}: no block starts at the right jamb"
        );
        for b in course {
            for x in [WINDOW.x0, WINDOW.x1] {
                assert!(!(b.x0 < x && b.x1 > x), "{b:?} crosses the jamb x = {x}");
            }
        }
    }
    // the sill course is cut mid-height: its blocks under the window end at the sill
    assert!(blocks
        .iter()
        .any(|b| b.y1 == WINDOW.y0 && b.x0 >= WINDOW.x0 && b.x1 <= WINDOW.x1));
}

#[test]
fn an_edge_near_a_joint_snaps_to_it() {
    let snap = [MIN_PART * 0.25, MIN_PART * 0.12];
    let block = Rect::new(1.0, 0.0, 1.25, 0.12);
    // the opening's left edge 5 mm right of the block's left edge (under the 12.5 mm snap): no
    // 5 mm sliver is left, the block is removed whole
    let cut = cut_openings(vec![block], &[Rect::new(1.005, -1.0, 3.0, 1.0)], snap, "o").unwrap();
    assert!(cut.is_empty(), "{cut:?}");
    // 5 mm into the block from the right: nothing is taken off
    let cut = cut_openings(vec![block], &[Rect::new(1.245, -1.0, 3.0, 1.0)], snap, "o").unwrap();
    assert_eq!(cut, vec![block]);
    // 2 cm in: cut there
    let cut = cut_openings(vec![block], &[Rect::new(1.02, -1.0, 3.0, 1.0)], snap, "o").unwrap();
    assert_eq!(cut, vec![Rect::new(1.0, 0.0, 1.02, 0.12)]);
    // an opening thinner than the snap does not cut a 1 cm strip out of the block
    let cut = cut_openings(vec![block], &[Rect::new(1.1, -1.0, 1.11, 1.0)], snap, "o").unwrap();
    assert_eq!(cut, vec![block]);
    let cut = cut_openings(vec![block], &[Rect::new(0.0, 0.05, 3.0, 0.055)], snap, "o").unwrap();
    assert_eq!(cut, vec![block]);
    // up: a sill 3 mm above a bed joint (under the 6 mm snap) is moved onto it
    let cut = cut_openings(vec![block], &[Rect::new(0.0, 0.003, 3.0, 1.0)], snap, "o").unwrap();
    assert!(cut.is_empty(), "{cut:?}");
    // on the wall: jambs 5 mm from the joints of the courses starting with a whole block (1.0 and
    // 2.25) are moved onto them there (no 5 mm slivers), and cut where they are in the others; the
    // area removed then differs from the opening's by at most the snap times the jambs' height
    let near = Rect::new(1.005, 0.9, 2.245, 1.8);
    let blocks = running_bond(&wall(vec![near])).unwrap();
    assert!(
        blocks.iter().all(|b| b.width() >= MIN_PART * 0.25 - 1e-12),
        "a sliver was made"
    );
    assert!(
        blocks.iter().any(|b| b.x1 == 1.005) && blocks.iter().any(|b| b.x1 == 1.0 && b.y0 > 0.9)
    );
    let removed = 10.0 - blocks.iter().map(Rect::area).sum::<f64>();
    assert!(
        (removed - near.area()).abs() <= 2.0 * 0.005 * 0.9 + 1e-9,
        "removed {removed}"
    );
}

#[test]
fn blocks_astride_a_window_corner_and_several_openings() {
    // a block astride the window's lower-left corner: its part left of the jamb (full height) and
    // its part under the sill
    let snap = [0.0125, 0.006];
    let block = Rect::new(1.0, 0.84, 1.25, 0.96);
    let cut = cut_openings(vec![block], &[WINDOW], snap, "o").unwrap();
    assert_eq!(
        cut,
        vec![
            Rect::new(1.0, 0.84, 1.1, 0.96),
            Rect::new(1.1, 0.84, 1.25, 0.9)
        ]
    );
    // two windows: twice the area; a window poking out of the wall: the part inside the wall
    let two = vec![WINDOW, Rect::new(2.6, 0.3, 3.4, 1.1)];
    let solid = 10.0;
    let blocks = running_bond(&wall(two)).unwrap();
    let removed = solid - blocks.iter().map(Rect::area).sum::<f64>();
    assert!(
        (removed - (1.08 + 0.64)).abs() <= 1e-9 * 1.72,
        "removed {removed}"
    );
    let door = Rect::new(0.4, -0.5, 1.3, 2.1); // a door through the base: 0.9 x 2.1 m inside the wall
    let blocks = running_bond(&wall(vec![door])).unwrap();
    let removed = solid - blocks.iter().map(Rect::area).sum::<f64>();
    assert!(
        (removed - 0.9 * 2.1).abs() <= 1e-9 * 1.89,
        "removed {removed}"
    );
    let bad = input_message(running_bond(&wall(vec![Rect::new(1.0, 1.0, 0.5, 2.0)])));
    assert!(bad.contains("geometry.running_bond.openings[0]"), "{bad}");
}

#[test]
fn a_wall_with_a_window_has_its_interfaces_and_a_collapse_multiplier() {
    let blocks = running_bond(&wall(vec![WINDOW])).unwrap();
    let law = dry(0.6, 0.6, 1e9);
    let model = Model::new(ModelSpec {
        blocks: polygons(blocks.clone()),
        gravity: 10.0,
        joints: JointLaws::uniform(law),
        ..ModelSpec::default()
    })
    .unwrap();
    // every block of the wall, cut or not, has interfaces with its neighbours: the cut blocks
    // beside and under the window, and the lintel course resting on the jamb blocks
    let mut count = vec![0usize; model.n_blocks()];
    for it in model.interfaces() {
        count[it.a] += 1;
        count[it.b] += 1;
    }
    for (i, b) in blocks.iter().enumerate() {
        assert!(count[i] >= 2, "block {i} {b:?} has {} interfaces", count[i]);
    }
    let at = |y: f64, v: f64| (y - v).abs() < 1e-12;
    let lintel = blocks
        .iter()
        .position(|b| at(b.y0, WINDOW.y1) && b.x0 < WINDOW.x0 && b.x1 > WINDOW.x0);
    let lintel = lintel.expect("a block of the course above the window over its left jamb");
    let rests_on_jamb = model.interfaces().iter().any(|it| {
        it.b == lintel
            && blocks
                .get(it.a)
                .is_some_and(|b| b.x1 <= WINDOW.x0 && at(b.y1, WINDOW.y1))
    });
    assert!(
        rests_on_jamb,
        "the lintel block {:?} does not rest on the left jamb",
        blocks[lintel]
    );
    let res = limit_analysis(&model, &LimitOptions::default()).unwrap();
    assert_eq!(res.status, Status::Collapse, "{:?}", res.error);
    assert!(res.collapse_multiplier.is_finite() && res.collapse_multiplier > 0.0);
    // the window weakens the wall
    let solid = Model::new(ModelSpec {
        blocks: polygons(running_bond(&wall(vec![])).unwrap()),
        gravity: 10.0,
        joints: JointLaws::uniform(law),
        ..ModelSpec::default()
    })
    .unwrap();
    let full = limit_analysis(&solid, &LimitOptions::default()).unwrap();
    assert!(res.collapse_multiplier < full.collapse_multiplier);
}
