//! The buttressed wall of [`masonry_dem::space::buttressed_wall`] pushed out of its plane, by
//! limit analysis, against the rigid overturning of the wall with its buttresses (sum of
//! moments about the toe).
//!
//! The joints are dry and associative (dilatancy = friction), limit analysis's assumption: a
//! joint that slips opens by the friction coefficient times the slip. With friction 2 and more
//! nothing slides, and the wall and its buttresses, bonded in running bond, turn as one body:
//! pushed towards the buttresses (-y) about the buttresses' toe, y = -d; pushed away from them
//! (+y) about the wall's toe, y = t, lifting the buttresses with it. Not bonded, the buttresses
//! cannot slide up or down the wall's face at that friction (the face would have to open by
//! twice the slip, more than the rotation opens it near the base), and the wall turns with them
//! as well.

mod common;

use common::dry;
use masonry_dem::limit::{limit_analysis_3d, LimitOptions};
use masonry_dem::model::JointLaws;
use masonry_dem::results::Status;
use masonry_dem::space::{buttressed_wall, ButtressedWall, LiveLoad3, Model3, ModelSpec3};

/// A wall 2.4 m x 1.2 m x 0.2 m of 0.4 m x 0.2 m blocks, two buttresses 0.4 m wide and deep at
/// x = 0.6 and 1.8 m.
fn wall(bonded: bool) -> ButtressedWall {
    ButtressedWall { length: 2.4, height: 1.2, thickness: 0.2, block_length: 0.4, block_height: 0.2, spacing: 1.2, buttress_width: 0.4, buttress_depth: 0.4, bonded }
}

fn lambda(p: &ButtressedWall, mu: f64, direction: f64) -> f64 {
    let m = Model3::new(&ModelSpec3 {
        blocks: buttressed_wall(p).unwrap(),
        gravity: 10.0,
        joints: JointLaws::uniform(dry(mu, mu, 1e9)),
        live: LiveLoad3::HorizontalWeight { direction },
        ..ModelSpec3::default()
    })
    .unwrap();
    let r = limit_analysis_3d(&m, &LimitOptions { tolerance: 1e-10, ..LimitOptions::default() }).unwrap();
    assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
    r.collapse_multiplier
}

#[test]
fn a_buttressed_wall_is_laid_in_courses_with_its_buttresses() {
    let bonded = buttressed_wall(&wall(true)).unwrap();
    let loose = buttressed_wall(&wall(false)).unwrap();
    // bonded: in the 3 even courses the wall stops at the buttresses (1 + 2 + 1 blocks, the
    // 0.4 m stretches and the 0.8 m between), in the 3 odd ones it runs on (7 blocks: a half,
    // 5, a half); 2 buttress blocks in every course
    assert_eq!(bonded.len(), 3 * (4 + 2) + 3 * (7 + 2));
    // not bonded: 6 whole blocks, then 7
    assert_eq!(loose.len(), 3 * (6 + 2) + 3 * (7 + 2));
    let volume = (2.4 * 0.2 + 2.0 * 0.4 * 0.4) * 1.2;
    for blocks in [&bonded, &loose] {
        let v: f64 = blocks.iter().map(|b| b.volume()).sum();
        assert!((v - volume).abs() < 1e-12, "{v} against {volume}");
    }
    // the through blocks of the even courses reach the wall's back face
    assert!(bonded.iter().filter(|b| b.min[1] == -0.4 && b.max[1] == 0.2).count() == 6);
}

#[test]
fn a_buttressed_wall_pushed_out_of_its_plane_overturns_whole_about_its_toe() {
    // by volumes (one density): the wall V_w = 2.4 x 0.2 x 1.2 (centroid y = 0.1), the
    // buttresses V_b = 2 x 0.4 x 0.4 x 1.2 (y = -0.2), both at z = 0.6. About the buttresses'
    // toe y = -0.4: lambda = (V_w 0.5 + V_b 0.2) / ((V_w + V_b) 0.6); about the wall's toe
    // y = 0.2: lambda = (V_w 0.1 + V_b 0.4) / ((V_w + V_b) 0.6)
    let (vw, vb) = (2.4 * 0.2 * 1.2, 2.0 * 0.4 * 0.4 * 1.2);
    let towards = (vw * 0.5 + vb * 0.2) / ((vw + vb) * 0.6);
    let away = (vw * 0.1 + vb * 0.4) / ((vw + vb) * 0.6);
    // the buttresses at least double the wall's own t / H = 1/6 either way
    assert!(towards > 2.0 / 6.0 && away > 2.0 / 6.0);
    for (bonded, mu) in [(true, 2.0), (true, 10.0), (false, 10.0)] {
        let p = wall(bonded);
        for (direction, want) in [(270.0, towards), (90.0, away)] {
            let got = lambda(&p, mu, direction);
            assert!((got - want).abs() <= 1e-7 * want, "bonded {bonded}, friction {mu}, pushed at {direction} deg: {got:.12} against {want:.12}");
        }
    }
}

#[test]
fn bad_buttressed_wall_parameters_are_refused_by_key() {
    let refused = |p: ButtressedWall| buttressed_wall(&p).unwrap_err().to_string();
    let e = refused(ButtressedWall { buttress_depth: 0.0, ..wall(true) });
    assert!(e.starts_with("buttressed_wall.buttress_depth"), "{e}");
    let e = refused(ButtressedWall { spacing: 0.41, ..wall(true) });
    assert!(e.starts_with("buttressed_wall.spacing = 0.41 m must exceed buttress_width = 0.4 m"), "{e}");
    let e = refused(ButtressedWall { length: 0.7, ..wall(true) });
    assert!(e.starts_with("buttressed_wall.length = 0.7 m holds no buttress"), "{e}");
    let e = refused(ButtressedWall { height: 1.21, ..wall(true) });
    assert!(e.contains("buttressed_wall"), "{e}");
    let e = refused(ButtressedWall { length: 2e6, block_length: 0.01, ..wall(true) });
    assert!(e.contains("buttressed_wall"), "{e}");
}
