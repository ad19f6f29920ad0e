//! Blocks of any convex polygon: rectangles through the polygon code give the model of
//! rectangles (interfaces, B matrices, masses, inertias, multipliers); polygons are checked and
//! named; supports, the family rule, the block order and the direction of gravity.

mod common;
use common::*;
use masonry_dem::geometry::{polygons, Rect};
use masonry_dem::interface::{BlockKind, Family, Interface};
use masonry_dem::limit::{limit_analysis, LimitOptions};
use masonry_dem::model::{JointLaws, Model, ModelSpec, TopBeam};
use masonry_dem::results::Status;
use masonry_dem::shape::Polygon;
use masonry_dem::Error;

fn spec(blocks: Vec<Polygon>) -> ModelSpec {
    ModelSpec { blocks, gravity: 10.0, joints: JointLaws::uniform(dry(0.65, 0.65, 1e10)), ..ModelSpec::default() }
}

/// The interfaces of a wall of rectangles by the rules of a rectangle model, pair by pair (an
/// independent reference, O(n^2)): a shared horizontal stretch is a bed joint (the lower block
/// first, at the mid-point of the stretch), a vertical one a head joint (the left block first);
/// the base and the top beam name the family; the tolerance is that of the model.
fn rectangle_interfaces(rects: &[Rect], kinds: &[BlockKind], tol: f64) -> Vec<Interface> {
    let mut out = vec![];
    for i in 0..rects.len() {
        for j in i + 1..rects.len() {
            let (p, q) = (rects[i], rects[j]);
            let (x0, x1, y0, y1) = (p.x0.max(q.x0), p.x1.min(q.x1), p.y0.max(q.y0), p.y1.min(q.y1));
            let (w, h) = (x1 - x0, y1 - y0);
            if w < -tol || h < -tol || (w <= tol && h <= tol) || (kinds[i] != BlockKind::Wall && kinds[j] != BlockKind::Wall) {
                continue;
            }
            assert!(w <= tol || h <= tol, "overlap");
            let (lo, hi, c, n, l) = if w > tol {
                let (lo, hi) = if p.y0 < q.y0 { (i, j) } else { (j, i) };
                (lo, hi, [0.5 * (x0 + x1), 0.5 * (rects[lo].y1 + rects[hi].y0)], [0.0, 1.0], w)
            } else {
                let (lo, hi) = if p.x0 < q.x0 { (i, j) } else { (j, i) };
                (lo, hi, [0.5 * (rects[lo].x1 + rects[hi].x0), 0.5 * (y0 + y1)], [1.0, 0.0], h)
            };
            let family = match (kinds[lo], kinds[hi]) {
                (BlockKind::Base, _) | (_, BlockKind::Base) => Family::Base,
                (BlockKind::Top, _) | (_, BlockKind::Top) => Family::Top,
                _ if n[1] == 1.0 => Family::Bed,
                _ => Family::Head,
            };
            out.push(Interface::new(lo, hi, rects[lo].centroid(), rects[hi].centroid(), c, n, l, family));
        }
    }
    out.sort_by_key(|it| (it.a, it.b));
    out
}

fn near(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-12 * scale
}

/// The model of `blocks` against the rectangle model's masses, inertias, centroids and
/// interfaces, to 1e-12 of the wall's size (B's rotation columns) or of each number.
fn assert_rectangle_model(model: &Model) {
    let rects = model.rects();
    let size = model.size();
    let tol = masonry_dem::shape::contact_tolerance(size);
    for (i, r) in rects.iter().enumerate() {
        let m = 1000.0 * r.area();
        assert!(near(model.mass()[i], m, m), "mass of {i}");
        let j = m * (r.width().powi(2) + r.height().powi(2)) / 12.0;
        assert!(near(model.inertia()[i], j, j), "inertia of {i}: {} against {j}", model.inertia()[i]);
        let c = r.centroid();
        assert!(near(model.centroids()[i][0], c[0], size) && near(model.centroids()[i][1], c[1], size), "centroid of {i}");
    }
    let want = rectangle_interfaces(&rects, model.kinds(), tol);
    let got = model.interfaces();
    assert_eq!(got.len(), want.len());
    for (g, w) in got.iter().zip(&want) {
        assert_eq!((g.a, g.b, g.family, g.n), (w.a, w.b, w.family, w.n));
        assert!(near(g.l, w.l, size) && near(g.c[0], w.c[0], size) && near(g.c[1], w.c[1], size), "{g:?} against {w:?}");
        for (rg, rw) in g.b_mat.iter().zip(&w.b_mat) {
            assert!(rg.iter().zip(rw).all(|(x, y)| near(*x, *y, size)), "B of {g:?} against {w:?}");
        }
    }
}

#[test]
fn rectangles_give_the_rectangle_model() {
    // Ferris & Tin-Loi's wall 2, the LACT3 wall (openings, a lintel over several blocks, blocks
    // on part of a longer one) and wall 1 under a top beam, far from the origin
    let far: Vec<Rect> =
        ferris_blocks(6).iter().map(|r| Rect::new(r.x0 + 1234.5, r.y0 - 678.25, r.x1 + 1234.5, r.y1 - 678.25)).collect();
    let top = Some(TopBeam { rotation_fixed: true, force: [0.0, -1e3], vertical_held: false });
    for (blocks, top) in [(ferris_blocks(10), None), (lact3_blocks(), None), (far, top)] {
        let model = Model::new(ModelSpec { top, ..spec(polygons(blocks)) }).unwrap();
        assert_rectangle_model(&model);
    }
}

#[test]
fn rectangles_as_vertex_lists_either_way_round_give_the_same_model() {
    let rects = lact3_blocks();
    let from_rects = Model::new(spec(polygons(rects.clone()))).unwrap();
    let corners = |r: &Rect| vec![[r.x0, r.y0], [r.x1, r.y0], [r.x1, r.y1], [r.x0, r.y1]];
    // counter-clockwise from another corner each, and clockwise
    let ccw: Vec<Polygon> = rects
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let mut v = corners(r);
            v.rotate_left(i % 4);
            Polygon::new(v)
        })
        .collect();
    let cw: Vec<Polygon> = rects
        .iter()
        .map(|r| {
            let mut v = corners(r);
            v.reverse();
            Polygon::new(v)
        })
        .collect();
    let law = JointLaws::uniform(dry(std::f64::consts::FRAC_PI_4.tan() * 0.5, 0.5, 1e10));
    let lam = |m: &Model| {
        let r = limit_analysis(m, &LimitOptions::default()).unwrap();
        assert_eq!(r.status, Status::Collapse);
        r.collapse_multiplier
    };
    let reference = Model::new(ModelSpec { joints: law, ..spec(polygons(rects.clone())) }).unwrap();
    for blocks in [ccw, cw] {
        let model = Model::new(spec(blocks.clone())).unwrap();
        assert_eq!(model.interfaces(), from_rects.interfaces());
        assert_eq!(model.mass(), from_rects.mass());
        assert_eq!(model.inertia(), from_rects.inertia());
        assert_eq!(model.centroids(), from_rects.centroids());
        assert_eq!(model.polygons(), from_rects.polygons());
        assert_eq!((model.dead_load(), model.live_load()), (from_rects.dead_load(), from_rects.live_load()));
        assert_eq!((0..model.n_blocks()).map(|i| model.block_name(i)).collect::<Vec<_>>(),
            (0..model.n_blocks()).map(|i| from_rects.block_name(i)).collect::<Vec<_>>());
        let model = Model::new(ModelSpec { joints: law, ..spec(blocks) }).unwrap();
        assert_eq!(lam(&model), lam(&reference));
    }
}

fn refused(spec: ModelSpec, words: &[&str]) {
    match Model::new(spec) {
        Err(Error::Input { reason, .. }) => {
            for w in words {
                assert!(reason.contains(w), "{reason:?} does not say {w:?}");
            }
            assert!(!reason.contains('\n'));
        }
        other => panic!("expected a refusal saying {words:?}, got {other:?}"),
    }
}

fn poly(v: &[[f64; 2]]) -> Polygon {
    Polygon::new(v.to_vec())
}

#[test]
fn blocks_that_are_not_convex_polygons_are_refused_by_name() {
    let plinth = Rect::new(0.0, 0.0, 2.0, 0.5).into();
    let l = poly(&[[0.0, 0.5], [2.0, 0.5], [2.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]]);
    refused(
        spec(vec![plinth, l]),
        &["block 1 (polygon of 6 vertices: (0, 0.5), (2, 0.5), (2, 1), ...)", "vertex 3 (1, 1)", "re-entrant", "convex parts"],
    );
    refused(spec(vec![poly(&[[0.0, 0.0], [1.0, 0.0]])]), &["block 0", "2 vertices"]);
    refused(spec(vec![poly(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]])]), &["block 0", "one line"]);
    refused(spec(vec![poly(&[[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [0.0, 0.0]])]), &["block 0", "fewer than 3 distinct"]);
    refused(spec(vec![poly(&[[0.0, 0.0], [1.0, 0.0], [f64::NAN, 1.0]])]), &["block 0", "vertex 2 (NaN, 1) is not finite"]);
    refused(spec(vec![poly(&[[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]])]), &["block 0", "crosses itself"]);
    // a support, named as one
    let bad = ModelSpec { supports: vec![poly(&[[0.0, 0.0], [1.0, 0.0]])], ..spec(vec![Rect::new(0.0, 0.0, 1.0, 1.0).into()]) };
    refused(bad, &["support 0", "2 vertices"]);
}

#[test]
fn overlapping_polygons_are_refused_naming_both() {
    let a = poly(&[[0.0, 0.0], [1.0, 0.0], [0.5, 1.0]]);
    let b = poly(&[[0.4, 0.5], [1.4, 0.5], [0.9, 1.5]]);
    refused(spec(vec![a.clone(), b]), &["block 0 (polygon of 3 vertices: (0, 0), (1, 0), (0.5, 1))", "block 1 (polygon of 3", "overlap"]);
    // a support overlapping a block
    let s = ModelSpec { supports: vec![poly(&[[0.0, -1.0], [1.0, -1.0], [1.0, 0.1], [0.0, 0.1]])], base: false, ..spec(vec![a]) };
    refused(s, &["block 0 (polygon", "support 0 [0, -1, 1, 0.1]", "overlap"]);
    // an overlap within the tolerance (rounding) is closed: an interface
    let under = poly(&[[0.0, -1.0], [1.0, -1.0], [1.0, 3e-10], [0.0, 3e-10]]);
    let m = Model::new(ModelSpec { supports: vec![under], base: false, ..spec(vec![poly(&[[0.0, 0.0], [1.0, 0.0], [0.5, 1.0]])]) }).unwrap();
    assert_eq!(m.interfaces().len(), 1);
    assert!((m.interfaces()[0].c[1] - 1.5e-10).abs() < 1e-18 && (m.interfaces()[0].l - 1.0).abs() < 1e-15);
    // a larger gap is no contact: the block touches nothing
    let apart = poly(&[[0.0, -1.0], [1.0, -1.0], [1.0, -1e-6], [0.0, -1e-6]]);
    let s = ModelSpec { supports: vec![apart], base: false, ..spec(vec![poly(&[[0.0, 0.0], [1.0, 0.0], [0.5, 1.0]])]) };
    refused(s, &["block 0 (polygon of 3 vertices", "touches no other block"]);
}

/// Blocks in order, supports after them, the base and the top beam last; a joint with a support
/// is of the base family; no base with supports unless asked.
#[test]
fn supports_come_after_the_wall_and_carry_it() {
    // a triangle between two inclined abutments (a wedge in a notch), no base
    let wedge = poly(&[[-0.5, 1.0], [0.0, 0.0], [0.5, 1.0]]);
    let left = poly(&[[-1.0, 0.0], [0.0, 0.0], [-0.5, 1.0], [-1.0, 1.0]]);
    let right = poly(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.5, 1.0]]);
    let m = Model::new(ModelSpec { supports: vec![left, right], base: false, ..spec(vec![wedge]) }).unwrap();
    assert_eq!(m.kinds(), [BlockKind::Wall, BlockKind::Support, BlockKind::Support]);
    assert_eq!((m.supports(), m.base(), m.top()), (1..3, None, None));
    assert!(m.fixed()[3..].iter().all(|&f| f) && !m.fixed()[..3].iter().any(|&f| f));
    assert_eq!(m.weight()[1..], [0.0, 0.0]);
    assert_eq!(m.block_name(1), "support 0 (polygon of 4 vertices: (-1, 0), (0, 0), (-0.5, 1), ...)");
    let its = m.interfaces();
    assert_eq!(its.len(), 2);
    assert!(its.iter().all(|it| it.family == Family::Base && it.a != 0 && it.b == 0)); // the wedge is above both
    // each interface the whole face, sqrt(0.5^2 + 1) long
    assert!(its.iter().all(|it| (it.l - 1.25f64.sqrt()).abs() < 1e-15));
    // with supports and a base, both
    let m = Model::new(ModelSpec {
        supports: vec![poly(&[[2.0, 0.0], [3.0, 0.0], [3.0, 1.0], [2.0, 1.0]])],
        ..spec(vec![Rect::new(0.0, 0.0, 2.0, 1.0).into()])
    })
    .unwrap();
    assert_eq!(m.kinds(), [BlockKind::Wall, BlockKind::Support, BlockKind::Base]);
    let families: Vec<(usize, usize, Family)> = m.interfaces().iter().map(|it| (it.a, it.b, it.family)).collect();
    assert_eq!(families, [(0, 1, Family::Base), (2, 0, Family::Base)]);
}

/// A joint within 45 degrees of the horizontal is a bed joint, its lower block first; steeper,
/// a head joint, the block behind first (along the live load, +x).
#[test]
fn joints_are_bed_or_head_by_their_slope() {
    for (slope, family) in [(0.9, Family::Bed), (1.1, Family::Head), (-0.9, Family::Bed), (-1.1, Family::Head)] {
        // a block under the line through (1, 0.5) of slope `slope` and one over it, over x in
        // [0.75, 1.25], on a support
        let y = |x: f64| 0.5 + slope * (x - 1.0);
        let under = poly(&[[0.75, -1.0], [1.25, -1.0], [1.25, y(1.25)], [0.75, y(0.75)]]);
        let over = poly(&[[0.75, y(0.75)], [1.25, y(1.25)], [1.25, 2.0], [0.75, 2.0]]);
        let floor = poly(&[[0.0, -2.0], [2.0, -2.0], [2.0, -1.0], [0.0, -1.0]]);
        let m = Model::new(ModelSpec { base: false, supports: vec![floor], ..spec(vec![under, over]) }).unwrap();
        let it = m.interfaces().iter().find(|it| it.family != Family::Base).unwrap();
        assert_eq!(it.family, family, "slope {slope}");
        // the normal from a to b points up (a is below), or along +x for a vertical joint
        assert!(it.n[1] > 0.0);
        let want = [-slope / (1.0 + slope * slope).sqrt(), 1.0 / (1.0 + slope * slope).sqrt()];
        assert!((it.n[0] - want[0]).abs() < 1e-15 && (it.n[1] - want[1]).abs() < 1e-15);
        assert_eq!((it.a, it.b), (0, 1));
    }
    // a vertical joint: the left block first, normal +x
    let m = Model::new(spec(vec![Rect::new(1.0, 0.0, 2.0, 1.0).into(), Rect::new(0.0, 0.0, 1.0, 1.0).into()])).unwrap();
    let head = m.interfaces().iter().find(|it| it.family == Family::Head).unwrap();
    assert_eq!((head.a, head.b, head.n), (1, 0, [1.0, 0.0]));
}

#[test]
fn gravity_turns_the_loads_and_the_rules() {
    // a block on a support, gravity along +x: the support is "below" on the left
    let block = poly(&[[0.0, 0.0], [1.0, 0.0], [1.0, 0.4], [0.0, 0.4]]);
    let support = poly(&[[1.0, -1.0], [2.0, -1.0], [2.0, 1.0], [1.0, 1.0]]);
    let m = Model::new(ModelSpec { base: false, supports: vec![support], gravity_direction: [2.0, 0.0], ..spec(vec![block]) }).unwrap();
    assert_eq!(m.gravity_direction(), [1.0, 0.0]);
    assert_eq!(m.horizontal(), [0.0, 1.0]);
    let w = m.weight()[0];
    assert_eq!(&m.dead_load()[..3], &[w, 0.0, 0.0]);
    assert_eq!(&m.live_load()[..3], &[0.0, w, 0.0]);
    let it = &m.interfaces()[0];
    // the normal from the lower block (the support, along gravity) up into the block
    assert_eq!((it.a, it.b, it.n, it.family), (1, 0, [-1.0, 0.0], Family::Base));
    refused(ModelSpec { gravity_direction: [0.0, 0.0], ..spec(vec![Rect::new(0.0, 0.0, 1.0, 1.0).into()]) }, &["loads.gravity_direction"]);
    refused(ModelSpec { gravity_direction: [f64::NAN, 1.0], ..spec(vec![Rect::new(0.0, 0.0, 1.0, 1.0).into()]) }, &["loads.gravity_direction"]);
}

#[test]
fn a_block_on_part_of_a_longer_one_and_one_on_two() {
    // a triangle on part of a long block, a long block on two
    let long = Rect::new(0.0, 0.0, 3.0, 0.5);
    let tri = poly(&[[0.5, 0.5], [1.5, 0.5], [1.0, 1.2]]);
    let m = Model::new(spec(vec![long.into(), tri])).unwrap();
    let it = m.interfaces().iter().find(|it| it.a == 0 && it.b == 1).unwrap();
    assert_eq!((it.c, it.n, it.l, it.family), ([1.0, 0.5], [0.0, 1.0], 1.0, Family::Bed));
    let m = Model::new(spec(vec![Rect::new(0.0, 0.0, 1.0, 1.0).into(), Rect::new(2.0, 0.0, 3.0, 1.0).into(), Rect::new(0.0, 1.0, 3.0, 1.5).into()])).unwrap();
    let on_two: Vec<(usize, usize, f64)> = m.interfaces().iter().filter(|it| it.b == 2).map(|it| (it.a, it.b, it.l)).collect();
    assert_eq!(on_two, [(0, 2, 1.0), (1, 2, 1.0)]);
}
