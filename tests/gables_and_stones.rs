//! The gable and stone-wall generators (src/geometry/gable.rs, src/geometry/stone_wall.rs): their
//! blocks tile the wall (areas to 1e-12), are convex and valid, and their contacts cover every
//! joint; a stone wall is the same for the same seed; a gable column's multiplier against the
//! closed form of its overturning; the static path and the explicit solver on both; the modes of
//! a polygon on an inclined support.

mod common;
use common::*;
use masonry_dem::explicit::{self, ExplicitOptions};
use masonry_dem::geometry::{gable, stone_wall, FirstCourse, Gable, StoneWall, MIN_STONE, SLIVER};
use masonry_dem::interface::{BlockKind, Family};
use masonry_dem::limit::{limit_analysis, LimitOptions};
use masonry_dem::modal::modes;
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::results::Status;
use masonry_dem::shape::{contact_tolerance, Polygon};
use masonry_dem::static_solver::{self, StaticOptions};

fn gable_of(length: f64, eaves: f64, ridge: f64, ridge_x: Option<f64>, first: FirstCourse) -> Gable {
    Gable { block_length: 0.4, block_height: 0.2, length, eaves_height: eaves, ridge_height: ridge, ridge_x, first_course: first }
}

/// Gables of every kind: symmetric, off-centre, a single slope either way, a triangle (no
/// eaves), eaves and ridge between course levels.
fn gables() -> Vec<Gable> {
    vec![
        gable_of(2.0, 1.0, 1.6, None, FirstCourse::Half),
        gable_of(3.3, 0.9, 2.15, Some(1.1), FirstCourse::Full),
        gable_of(2.2, 0.5, 1.37, Some(0.0), FirstCourse::Half),
        gable_of(2.2, 0.5, 1.37, Some(2.2), FirstCourse::Half),
        gable_of(4.0, 0.0, 1.9, None, FirstCourse::Half),
        gable_of(5.0, 1.13, 1.21, Some(3.7), FirstCourse::Full),
    ]
}

fn stones() -> Vec<StoneWall> {
    let p = StoneWall { length: 3.0, height: 1.6, stone_length: 0.4, stone_height: 0.25, irregularity: 0.3, head_angle: 20.0, bed_angle: 4.0, seed: 1 };
    vec![
        p,
        StoneWall { seed: 2, irregularity: 0.5, head_angle: 30.0, bed_angle: 10.0, ..p },
        StoneWall { seed: 3, irregularity: 0.0, head_angle: 0.0, bed_angle: 0.0, ..p },
        StoneWall { seed: 4, length: 0.5, height: 0.3, ..p },
        StoneWall { seed: u64::MAX, length: 7.3, height: 2.9, stone_length: 0.55, stone_height: 0.31, ..p },
    ]
}

fn area(blocks: &[Polygon]) -> f64 {
    blocks.iter().map(|b| b.area_properties().area).sum()
}

fn perimeter(v: &[[f64; 2]]) -> f64 {
    (0..v.len()).map(|k| {
        let (p, q) = (v[k], v[(k + 1) % v.len()]);
        (q[0] - p[0]).hypot(q[1] - p[1])
    }).sum()
}

fn model(blocks: Vec<Polygon>, mu: f64) -> Model {
    Model::new(ModelSpec { blocks, gravity: 10.0, joints: JointLaws::uniform(dry(mu, mu, 1e10)), ..ModelSpec::default() }).unwrap()
}

/// Checks the blocks of a wall of area `wall_area` and outline perimeter `outline`: the areas
/// add up to the wall's to 1e-12; each block is a valid convex polygon as given (checking it
/// again changes nothing); the interfaces between blocks are as long as the joints together
/// (each joint is counted twice in the blocks' perimeters, the outline once), and the base
/// interfaces as the wall's length.
fn tiles(blocks: &[Polygon], wall_area: f64, outline: f64, length: f64, what: &str) {
    let got = area(blocks);
    assert!((got - wall_area).abs() <= 1e-12 * wall_area, "{what}: area {got} against {wall_area}");
    let size = blocks.iter().fold(0.0f64, |s, b| s.max(b.aabb().size()));
    for (i, b) in blocks.iter().enumerate() {
        assert_eq!(b.checked(contact_tolerance(size)).as_ref(), Ok(b), "{what}: block {i} is not a checked convex polygon");
    }
    let joints = 0.5 * (blocks.iter().map(|b| perimeter(b.vertices())).sum::<f64>() - outline);
    let m = model(blocks.to_vec(), 0.6);
    let wall = |k: usize| m.kinds()[k] == BlockKind::Wall;
    let between: f64 = m.interfaces().iter().filter(|it| wall(it.a) && wall(it.b)).map(|it| it.l).sum();
    let base: f64 = m.interfaces().iter().filter(|it| !(wall(it.a) && wall(it.b))).map(|it| it.l).sum();
    assert!((between - joints).abs() <= 1e-9 * joints, "{what}: interfaces {between} m against joints {joints} m");
    assert!((base - length).abs() <= 1e-12 * length, "{what}: base {base} m against {length} m");
}

#[test]
fn gable_blocks_tile_the_gable_and_touch_along_every_joint() {
    for p in gables() {
        let blocks = gable(&p).unwrap();
        let what = format!("{p:?}");
        let (l, xr, e, r) = (p.length, p.ridge(), p.eaves_height, p.ridge_height);
        let rakes = xr.hypot(r - e) + (l - xr).hypot(r - e);
        tiles(&blocks, p.area(), l + 2.0 * e + rakes, l, &what);
        // under the top; no sliver but a course's only block
        let whole = p.block_length * p.block_height;
        for (i, b) in blocks.iter().enumerate() {
            assert!(b.vertices().iter().all(|v| v[1] <= p.top(v[0]) + 1e-12), "{what}: block {i} above the top");
            let y0 = b.vertices()[0][1];
            let in_course = blocks.iter().filter(|c| c.vertices()[0][1] == y0).count();
            assert!(b.area_properties().area >= SLIVER * whole || in_course == 1, "{what}: block {i} is a sliver");
        }
    }
}

#[test]
fn stone_walls_tile_the_wall_and_touch_along_every_joint() {
    for p in stones() {
        let blocks = stone_wall(&p).unwrap();
        tiles(&blocks, p.length * p.height, 2.0 * (p.length + p.height), p.length, &format!("{p:?}"));
        // a bond: the joints' ends along a bed joint at least MIN_STONE of a stone apart, so no
        // interface between two courses is shorter
        let m = model(blocks.clone(), 0.6);
        let least = m.interfaces().iter().filter(|it| it.family == Family::Bed).map(|it| it.l).fold(f64::MAX, f64::min);
        assert!(least >= MIN_STONE * p.stone_length * (1.0 - 1e-9), "{p:?}: a bed interface {least} m long");
        // a flat base and a flat top
        let (lo, hi) = blocks.iter().flat_map(|b| b.vertices()).fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v[1]), hi.max(v[1])));
        assert_eq!((lo, hi), (0.0, p.height));
    }
}

#[test]
fn a_stone_wall_is_the_same_for_the_same_seed_and_another_for_another() {
    let p = stones()[0];
    assert_eq!(stone_wall(&p).unwrap(), stone_wall(&p).unwrap());
    assert_ne!(stone_wall(&p).unwrap(), stone_wall(&StoneWall { seed: 99, ..p }).unwrap());
    // the same bits on any machine: the coordinates' bits hashed (FNV-1a), as first computed
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for v in stone_wall(&p).unwrap().iter().flat_map(|b| b.vertices().to_vec()) {
        for x in v {
            hash = (hash ^ x.to_bits()).wrapping_mul(0x100_0000_01b3);
        }
    }
    assert_eq!(hash, GOLDEN_HASH, "the wall of seed 1 changed");
}

/// The FNV-1a hash of the coordinates of the stone wall of seed 1 ([`stones`]), as first made
/// (on x86-64 Linux): any machine gives these bits.
const GOLDEN_HASH: u64 = 17_112_593_130_022_451_549;

/// Area and centroid of the part of the single-slope gable column `0 <= x <= b`, from `y` up
/// to the top `e + s x` (s > 0: rising towards +x): a trapezoid below the eaves (a rectangle
/// and the triangle over it), a triangle above them.
fn above(b: f64, e: f64, s: f64, y: f64) -> (f64, [f64; 2]) {
    let r = e + s * b;
    let tri = |p: [[f64; 2]; 3]| {
        let a = 0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]));
        (a, [(p[0][0] + p[1][0] + p[2][0]) / 3.0, (p[0][1] + p[1][1] + p[2][1]) / 3.0])
    };
    if y >= e {
        return tri([[(y - e) / s, y], [b, y], [b, r]]);
    }
    let (a1, c1) = (b * (e - y), [0.5 * b, 0.5 * (e + y)]);
    let (a2, c2) = tri([[0.0, e], [b, e], [b, r]]);
    let a = a1 + a2;
    (a, [(a1 * c1[0] + a2 * c2[0]) / a, (a1 * c1[1] + a2 * c2[1]) / a])
}

#[test]
fn a_gable_column_overturns_at_its_closed_form() {
    // a column of single blocks (the wall half a block long), its top rising towards the load
    // (ridge at x = b) or falling (ridge at x = 0: the column mirrored). The column is
    // statically determinate: each bed joint carries the weight W of the part above and lambda W
    // across, through that part's centroid; tension-free and with friction mu above lambda, the
    // joint at y_k holds until the resultant reaches its toe, the joint's end towards +x:
    // lambda_k = (x_toe - x_c) / (y_c - y_k). The least over the joints (the base too) is exact.
    let (b, e, r, bh) = (0.5, 1.0, 1.55, 0.25);
    for ridge_x in [b, 0.0] {
        let p = Gable { block_length: 2.0 * b, block_height: bh, length: b, eaves_height: e, ridge_height: r, ridge_x: Some(ridge_x), first_course: FirstCourse::Half };
        let blocks = gable(&p).unwrap();
        let levels: Vec<f64> = blocks.iter().map(|q| q.vertices()[0][1]).collect();
        assert_eq!(levels.len(), 6, "one block per course: {levels:?}");
        let want = levels
            .iter()
            .map(|&y| {
                let (_, c) = above(b, e, (r - e) / b, y);
                // mirrored when the ridge is at x = 0: the part's centroid at b - x_c, the
                // joint's right end (its toe) at b - (y - e) / s above the eaves
                let s = (r - e) / b;
                let (xc, toe) = if ridge_x == 0.0 { (b - c[0], b - (y - e).max(0.0) / s) } else { (c[0], b) };
                (toe - xc) / (c[1] - y)
            })
            .fold(f64::MAX, f64::min);
        assert!(want < 0.9);
        let res = limit_analysis(&model(blocks, 0.9), &LimitOptions { tolerance: 1e-11, ..LimitOptions::default() }).unwrap();
        assert_eq!(res.status, Status::Collapse, "{:?}", res.error);
        assert_close(res.collapse_multiplier, want, 1e-9, &format!("gable column, ridge at x = {ridge_x}"));
    }
}

/// The limit multiplier of `m` and the static path's, which must lie within `rel` below it.
fn static_reaches_limit(m: &Model, rel: f64, what: &str) -> f64 {
    let exact = limit_analysis(m, &LimitOptions { tolerance: 1e-11, ..LimitOptions::default() }).unwrap();
    assert_eq!(exact.status, Status::Collapse, "{what}: {:?}", exact.error);
    let r = static_solver::solve(m, &StaticOptions::default()).unwrap();
    assert_eq!(r.status, Status::Collapse, "{what}: {:?}", r.error);
    let (lam, exact) = (r.collapse_multiplier, exact.collapse_multiplier);
    assert!(lam <= exact * (1.0 + 1e-9), "{what}: {lam} above the limit load {exact}");
    assert!(lam >= exact * (1.0 - rel), "{what}: {lam}, {:.4}% below {exact}", 100.0 * (exact - lam) / exact);
    exact
}

#[test]
fn the_static_path_of_a_gable_reaches_its_limit_load() {
    // associative dry joints: limit analysis is exact, the path's peak within 0.1% below it
    let m = model(gable(&gables()[0]).unwrap(), 0.65);
    static_reaches_limit(&m, 1e-3, "gable");
}

#[test]
fn a_stone_wall_by_the_static_path_and_the_explicit_solver() {
    let p = StoneWall { length: 1.6, height: 1.0, stone_length: 0.4, stone_height: 0.25, irregularity: 0.3, head_angle: 20.0, bed_angle: 4.0, seed: 5 };
    let m = model(stone_wall(&p).unwrap(), 0.65);
    let exact = static_reaches_limit(&m, 1e-3, "stone wall");
    let r = explicit::solve(&m, &ExplicitOptions { threads: 1, ..ExplicitOptions::default() }).unwrap();
    assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
    // the explicit solver's bracket, 1e-3 wide, on a relaxed equilibrium: within 1%
    assert_close(r.collapse_multiplier, exact, 0.01, "stone wall, explicit");
}

/// A gable block (a house-shaped pentagon, `b` wide, `h` to the eaves, `f` more to the ridge)
/// on a support whose top edge is inclined at `beta`, turned with its gravity; no base.
fn pentagon_on_support(beta: f64, b: f64, h: f64, f: f64) -> Model {
    let (s, c) = beta.sin_cos();
    let turn = |v: [f64; 2]| [c * v[0] - s * v[1], s * v[0] + c * v[1]];
    let block = Polygon::new(vec![[0.0, 0.0], [b, 0.0], [b, h], [0.5 * b, h + f], [0.0, h]]).map(turn);
    let support = Polygon::new(vec![[-0.5, -0.4], [b + 0.5, -0.4], [b + 0.5, 0.0], [-0.5, 0.0]]).map(turn);
    let law = masonry_dem::joint::JointLaw { normal_stiffness: 1e9, shear_stiffness: 4e8, ..masonry_dem::joint::JointLaw::default() };
    Model::new(ModelSpec {
        blocks: vec![block],
        supports: vec![support],
        base: false,
        gravity: 10.0,
        gravity_direction: [s, -c],
        joints: JointLaws::uniform(law),
        ..ModelSpec::default()
    })
    .unwrap()
}

#[test]
fn a_polygon_on_an_inclined_support_has_the_modes_of_the_flat_one() {
    let (b, h, f) = (0.6, 0.5, 0.3);
    let flat = modes(&pentagon_on_support(0.0, b, h, f), 3, None).unwrap();
    // symmetric about its joint's centre: the vertical mode alone, omega^2 = kn b t / m
    let mass = 1000.0 * (b * h + 0.5 * b * f);
    let vertical = (1e9 * b / mass).sqrt();
    let near = flat.angular.iter().map(|w| (w - vertical).abs() / vertical).fold(f64::MAX, f64::min);
    assert!(near <= 1e-9, "no mode at sqrt(kn A / m) = {vertical}: {:?}", flat.angular);
    for beta in [10f64.to_radians(), -25f64.to_radians()] {
        let turned = modes(&pentagon_on_support(beta, b, h, f), 3, None).unwrap();
        for (w, v) in turned.angular.iter().zip(&flat.angular) {
            assert!((w - v).abs() <= 1e-9 * v, "beta {beta}: {w} against {v}");
        }
    }
}

/// The stone pier of examples/stone-wall.toml: a wall one stone long, each course a single
/// stone between inclined bed joints.
fn stone_pier() -> StoneWall {
    StoneWall { length: 0.6, height: 2.4, stone_length: 0.6, stone_height: 0.3, irregularity: 0.3, head_angle: 15.0, bed_angle: 8.0, seed: 2026 }
}

/// The multiplier of a column of blocks (bottom to top) on a fixed base, tension-free joints of
/// friction `mu`, each carrying the weight of the part above it and lambda times it across: the
/// column is statically determinate, so each joint's normal force N, shear T and centre of
/// pressure follow from the statics of the part above; the joint holds while |T| <= mu N and the
/// centre of pressure lies on the joint. The largest such lambda of each joint (by bisection, to
/// the last bits), the least over the joints.
fn column_multiplier(blocks: &[Polygon], mu: f64) -> f64 {
    let mut least = f64::MAX;
    for k in 0..blocks.len() {
        // the joint under block k: its bottom edge, from x = 0 to the far side
        let v = blocks[k].vertices();
        let lowest_at = |x: f64| v.iter().filter(|p| p[0] == x).map(|p| p[1]).fold(f64::MAX, f64::min);
        let right = v.iter().map(|p| p[0]).fold(f64::MIN, f64::max);
        let (p0, p1) = ([0.0, lowest_at(0.0)], [right, lowest_at(right)]);
        let len = (p1[0] - p0[0]).hypot(p1[1] - p0[1]);
        let t = [(p1[0] - p0[0]) / len, (p1[1] - p0[1]) / len];
        let n = [-t[1], t[0]];
        let (mut a, mut m) = (0.0, [0.0, 0.0]);
        for b in &blocks[k..] {
            let p = b.area_properties();
            a += p.area;
            m = [m[0] + p.area * p.centroid[0], m[1] + p.area * p.centroid[1]];
        }
        let c = [m[0] / a, m[1] / a];
        let holds = |lam: f64| {
            let f = [lam * a, -a]; // the loads on the part above
            let dot = |u: [f64; 2], w: [f64; 2]| u[0] * w[0] + u[1] * w[1];
            let (normal, shear) = (-dot(f, n), -dot(f, t));
            // where the loads' line through c crosses the joint, along it from p0
            let tau = -dot([c[0] - p0[0], c[1] - p0[1]], n) / dot(f, n);
            let s = dot([c[0] - p0[0] + tau * f[0], c[1] - p0[1] + tau * f[1]], t);
            normal > 0.0 && shear.abs() <= mu * normal && (0.0..=len).contains(&s)
        };
        assert!(holds(0.0), "joint {k} does not hold the weight");
        let (mut lo, mut hi) = (0.0, 10.0);
        while hi - lo > 1e-15 * hi {
            let mid = 0.5 * (lo + hi);
            if holds(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        least = least.min(lo);
    }
    least
}

#[test]
fn a_stone_pier_fails_at_its_statics_and_the_example_says_so() {
    let blocks = stone_wall(&stone_pier()).unwrap();
    assert_eq!(blocks.len(), 8);
    assert!(blocks.iter().all(|b| b.vertices().len() == 4));
    // friction 0.3: the pier neither overturns on its base (0.25) nor slides on a horizontal
    // joint (0.3) first, but slides along a bed joint falling towards the load
    let want = column_multiplier(&blocks, 0.3);
    assert!(want < 0.25 * (1.0 - 1e-3), "{want}");
    let res = limit_analysis(&model(blocks, 0.3), &LimitOptions { tolerance: 1e-11, ..LimitOptions::default() }).unwrap();
    assert_eq!(res.status, Status::Collapse, "{:?}", res.error);
    assert_close(res.collapse_multiplier, want, 1e-9, "stone pier");
    // the example's reference, to its printed digits
    let example = include_str!("../examples/stone-wall.toml");
    let line = example.lines().find(|l| l.starts_with("collapse_multiplier")).expect("a [reference]");
    let printed: f64 = line.split('=').nth(1).unwrap().split('#').next().unwrap().trim().parse().unwrap();
    assert_close(printed, want, 5e-5, "the example's reference");
}
