//! Unit tests of the 3D model: boxes, contact detection, the model's masses and loads.

use super::*;
use crate::interface::BlockKind;

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn walls(boxes: &[Box3]) -> Result<Vec<Contact>> {
    detect(boxes, &vec![BlockKind::Wall; boxes.len()], |i| format!("block {i}"), &mut || true)
}

/// The frame is right-handed and orthonormal, the corners lie on the plane through the
/// centroid, turn counter-clockwise about n and enclose `area`.
fn check_contact(c: &Contact) {
    assert_eq!(cross(c.t1, c.t2), c.n, "t1 x t2 = n");
    assert_eq!(c.corners.len(), 4);
    let mut twice_area = 0.0;
    for k in 0..4 {
        let (p, q, r) = (c.corners[k], c.corners[(k + 1) % 4], c.corners[(k + 2) % 4]);
        assert!(dot(sub(p, c.centroid), c.n).abs() < 1e-12, "corner off the plane");
        assert!(dot(cross(sub(q, p), sub(r, q)), c.n) > 0.0, "corners not counter-clockwise about n: {c:?}");
        twice_area += dot(cross(sub(p, c.centroid), sub(q, c.centroid)), c.n);
    }
    assert!((0.5 * twice_area - c.area).abs() < 1e-12 * c.area.max(1.0));
    assert!((c.dims[0] * c.dims[1] - c.area).abs() < 1e-15);
}

#[test]
fn box_volume_centroid_and_model_inertia() {
    let b = Box3::new(1.0, 2.0, 3.0, 1.4, 2.1, 3.2);
    assert!((b.volume() - 0.4 * 0.1 * 0.2).abs() < 1e-15);
    let g = b.centroid();
    assert!((g[0] - 1.2).abs() < 1e-15 && (g[1] - 2.05).abs() < 1e-15 && (g[2] - 3.1).abs() < 1e-15);
    let spec = ModelSpec3 { blocks: vec![b], density: 1000.0, ..ModelSpec3::default() };
    let m = Model3::new(&spec).unwrap();
    let mass = 1000.0 * b.volume();
    assert!((m.mass()[0] - mass).abs() < 1e-12);
    let [ix, iy, iz] = m.inertia()[0];
    assert!((ix - mass * (0.01 + 0.04) / 12.0).abs() < 1e-15);
    assert!((iy - mass * (0.16 + 0.04) / 12.0).abs() < 1e-15);
    assert!((iz - mass * (0.16 + 0.01) / 12.0).abs() < 1e-15);
    assert_eq!(m.centroids()[0], g);
}

#[test]
fn two_stacked_boxes_share_one_bed_rectangle() {
    // the upper box listed first: a = the lower one all the same, n = +z from a into b
    let boxes = [Box3::new(0.1, 0.0, 0.2, 0.5, 0.1, 0.4), Box3::new(0.0, 0.0, 0.0, 0.4, 0.1, 0.2)];
    let found = walls(&boxes).unwrap();
    assert_eq!(found.len(), 1);
    let c = &found[0];
    assert_eq!((c.a, c.b, c.family), (1, 0, crate::interface::Family::Bed));
    assert_eq!((c.n, c.t1, c.t2), ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]));
    assert!((c.area - 0.3 * 0.1).abs() < 1e-15);
    assert!((c.centroid[0] - 0.25).abs() < 1e-15 && (c.centroid[1] - 0.05).abs() < 1e-15 && c.centroid[2] == 0.2);
    assert_eq!(c.corners, vec![[0.1, 0.0, 0.2], [0.4, 0.0, 0.2], [0.4, 0.1, 0.2], [0.1, 0.1, 0.2]]);
    check_contact(c);
    // the normal points from a into b: from a's centroid across the plane to b's
    let (ga, gb) = (boxes[c.a].centroid(), boxes[c.b].centroid());
    assert!(dot(sub(c.centroid, ga), c.n) > 0.0 && dot(sub(gb, c.centroid), c.n) > 0.0);
}

#[test]
fn side_contacts_have_a_horizontal_t1_and_t2_up() {
    // a block with a neighbour along +x and one along +y
    let boxes = [
        Box3::new(0.0, 0.0, 0.0, 0.4, 0.1, 0.2),
        Box3::new(0.4, 0.0, 0.0, 0.8, 0.1, 0.2),
        Box3::new(0.0, 0.1, 0.05, 0.1, 0.5, 0.2),
    ];
    let found = walls(&boxes).unwrap();
    assert_eq!(found.len(), 2);
    for c in &found {
        assert_eq!(c.family, crate::interface::Family::Head);
        assert_eq!(c.t2, [0.0, 0.0, 1.0]);
        check_contact(c);
        let (ga, gb) = (boxes[c.a].centroid(), boxes[c.b].centroid());
        assert!(dot(sub(gb, ga), c.n) > 0.0);
    }
    assert_eq!((found[0].a, found[0].b, found[0].n, found[0].t1), (0, 1, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]));
    assert!((found[0].area - 0.1 * 0.2).abs() < 1e-15);
    assert_eq!((found[1].a, found[1].b, found[1].n, found[1].t1), (0, 2, [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]));
    assert!((found[1].area - 0.1 * 0.15).abs() < 1e-15);
    assert_eq!(found[1].dims, [0.1, 0.2 - 0.05]);
}

#[test]
fn touching_along_an_edge_or_at_a_corner_is_no_contact() {
    let a = Box3::new(0.0, 0.0, 0.0, 1.0, 1.0, 1.0);
    let edge = Box3::new(1.0, 0.0, 1.0, 2.0, 1.0, 2.0); // shares the edge x = 1, z = 1
    let point = Box3::new(1.0, 1.0, 1.0, 2.0, 2.0, 2.0); // shares the corner (1, 1, 1)
    let apart = Box3::new(0.0, 0.0, 1.001, 1.0, 1.0, 2.0);
    assert!(walls(&[a, edge]).unwrap().is_empty());
    assert!(walls(&[a, point]).unwrap().is_empty());
    assert!(walls(&[a, apart]).unwrap().is_empty());
    // faces a rounding error apart (gap or interpenetration) are in contact
    for dz in [1e-12, -1e-12] {
        let found = walls(&[a, Box3::new(0.5, 0.5, 1.0 + dz, 1.5, 1.5, 2.0)]).unwrap();
        assert_eq!(found.len(), 1);
        assert!((found[0].area - 0.25).abs() < 1e-12);
    }
}

#[test]
fn overlapping_blocks_are_refused_by_name() {
    let blocks = vec![
        Box3::new(0.0, 0.0, 0.0, 0.4, 0.1, 0.2),
        Box3::new(0.4, 0.0, 0.0, 0.8, 0.1, 0.2),
        Box3::new(0.7, 0.05, 0.1, 1.0, 0.2, 0.3),
    ];
    let e = Model3::new(&ModelSpec3 { blocks, ..ModelSpec3::default() }).unwrap_err();
    let msg = e.to_string();
    assert!(msg.starts_with("block 1 [0.4, 0, 0, 0.8, 0.1, 0.2] and block 2 [0.7, 0.05, 0.1, 1, 0.2, 0.3] overlap"), "{msg}");
    assert!(msg.contains("0.100000 x 0.050000 x 0.100000 m"), "{msg}");
}

#[test]
fn base_and_top_beam_frame_the_wall() {
    let blocks = vec![Box3::new(0.0, 0.0, 0.0, 0.4, 0.1, 0.2), Box3::new(0.4, 0.0, 0.0, 0.8, 0.1, 0.3)];
    let spec = ModelSpec3 { blocks, top: Some(0.1), live: LiveLoad3::HorizontalWeight { direction: 90.0 }, ..ModelSpec3::default() };
    let m = Model3::new(&spec).unwrap();
    assert_eq!((m.n_wall(), m.n_blocks(), m.base(), m.top()), (2, 4, Some(2), Some(3)));
    assert_eq!(m.boxes()[2], Box3::new(0.0, 0.0, -0.3, 0.8, 0.1, 0.0)); // as deep as the tallest block
    assert_eq!(m.boxes()[3], Box3::new(0.0, 0.0, 0.3, 0.8, 0.1, 0.4));
    assert_eq!(m.block_name(2), "the base");
    assert_eq!(m.block_name(3), "the top beam");
    assert_eq!(m.block_name(0), "block 0 [0, 0, 0, 0.4, 0.1, 0.2]");
    use crate::interface::Family::*;
    let fam: Vec<_> = m.contacts().iter().map(|c| (c.a, c.b, c.family)).collect();
    // the lower block does not reach the top beam; the base and the beam do not touch
    assert_eq!(fam, [(0, 1, Head), (1, 3, Top), (2, 0, Base), (2, 1, Base)]);
    assert_eq!(&m.fixed()[12..18], &[true; 6]);
    assert!(m.fixed()[..12].iter().chain(&m.fixed()[18..]).all(|f| !f));
    // the beam weighs, the base does not; the live load is on what weighs
    let w_top = m.mass()[3] * 9.81;
    assert!((m.dead_load()[6 * 3 + 2] + w_top).abs() < 1e-9);
    assert_eq!(m.dead_load()[6 * 2 + 2], 0.0);
    assert_eq!(&m.live_load()[12..18], &[0.0; 6]);
    assert!((m.live_load()[6 * 3 + 1] - w_top).abs() < 1e-9);
    assert!((m.live_load()[1] - m.mass()[0] * 9.81).abs() < 1e-9 && m.live_load()[0] == 0.0);
    assert!((m.size() - 0.8).abs() < 1e-15);
    assert_eq!(m.law(0), &m.laws().default);
}

#[test]
fn refusals_name_the_field_or_block() {
    let one = vec![Box3::new(0.0, 0.0, 0.0, 0.4, 0.1, 0.2)];
    let spec = |f: &dyn Fn(&mut ModelSpec3)| {
        let mut s = ModelSpec3 { blocks: one.clone(), ..ModelSpec3::default() };
        f(&mut s);
        Model3::new(&s).unwrap_err().to_string()
    };
    assert_eq!(spec(&|s| s.density = 0.0), "density must be a finite number > 0, got 0");
    assert_eq!(spec(&|s| s.top = Some(f64::NAN)), "top must be a finite number > 0, got NaN");
    assert!(spec(&|s| s.live = LiveLoad3::HorizontalWeight { direction: f64::INFINITY }).starts_with("live.direction"));
    assert!(spec(&|s| s.blocks[0].max[2] = -1.0).starts_with("block 0 [0, 0, 0, 0.4, 0.1, -1] has zero or negative size"));
    assert!(spec(&|s| s.blocks.clear()).contains("no blocks"));
    // a block in the air, away from the base
    let msg = spec(&|s| s.blocks.push(Box3::new(0.0, 0.0, 1.0, 0.4, 0.1, 1.2)));
    assert_eq!(msg, "block 1 [0, 0, 1, 0.4, 0.1, 1.2] touches no other block");
}

#[test]
fn live_load_direction_in_plan() {
    let blocks = vec![Box3::new(0.0, 0.0, 0.0, 1.0, 1.0, 1.0)];
    for (d, want) in [(0.0, [1.0, 0.0]), (90.0, [0.0, 1.0]), (-90.0, [0.0, -1.0]), (540.0, [-1.0, 0.0])] {
        let spec = ModelSpec3 { blocks: blocks.clone(), density: 1.0, gravity: 10.0, live: LiveLoad3::HorizontalWeight { direction: d }, ..ModelSpec3::default() };
        let m = Model3::new(&spec).unwrap();
        assert_eq!(&m.live_load()[..6], &[10.0 * want[0], 10.0 * want[1], 0.0, 0.0, 0.0, 0.0], "{d} deg");
    }
    let spec = ModelSpec3 { blocks, live: LiveLoad3::HorizontalWeight { direction: 30.0 }, ..ModelSpec3::default() };
    let m = Model3::new(&spec).unwrap();
    let w = m.mass()[0] * 9.81;
    assert!((m.live_load()[0] - w * 0.75f64.sqrt()).abs() < 1e-9 * w && (m.live_load()[1] - 0.5 * w).abs() < 1e-9 * w);
}

#[test]
fn a_false_poll_interrupts_the_search() {
    let blocks = crate::space::running_bond_3d(40.0, 40.0, 0.1, 0.4, 0.2, 0.0).unwrap();
    assert!(blocks.len() > crate::shape::grid::POLL_EVERY);
    let e = Model3::new_with(&ModelSpec3 { blocks, ..ModelSpec3::default() }, &mut || false).unwrap_err();
    assert_eq!(e, crate::error::Error::Interrupted);
}

#[test]
fn hulls_take_the_tolerance_of_the_whole_model_and_name_the_block_refused() {
    // a corner of a tetrahedron given twice, 1.7e-7 m apart: two vertices in a model of 1 m (tolerance 1e-8 m), one
    // in a model 100 m wide (its other blocks given as boxes: tolerance 1e-6 m), the first given kept
    let off = -1e-7;
    let tet = vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [off, off, off]];
    let lists = [tet];
    let alone = hulls(&[(&lists[..], "polyhedra")], &[]).unwrap();
    assert_eq!(alone[0][0].vertices().len(), 4);
    assert!(alone[0][0].vertices().contains(&[off; 3]) && !alone[0][0].vertices().contains(&[0.0; 3]));
    let far = crate::shape::Aabb { min: [0.0; 3], max: [100.0, 1.0, 1.0] };
    let wide = hulls(&[(&lists[..], "polyhedra")], &[far]).unwrap();
    assert!(wide[0][0].vertices().contains(&[0.0; 3]) && !wide[0][0].vertices().contains(&[off; 3]));
    // the refusal names the list, the block and the vertex, and carries the list's key
    let bad = [vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, f64::INFINITY, 0.0], [0.0, 0.0, 1.0]]];
    let err = hulls(&[(&lists[..], "polyhedra"), (&bad[..], "supports")], &[]).unwrap_err();
    assert_eq!(err.key(), Some("supports"));
    assert_eq!(err.to_string(), "supports[0]: vertex 2 (0, inf, 0): coordinate inf is not finite");
}

#[test]
fn a_polyhedron_after_the_boxes_carries_a_load() {
    // a box, then a cube given as a polyhedron (block 1) carrying 1 kN on its top: its mass takes it, block 2 (the
    // base) is refused as the wall's blocks are two
    let cube = Box3::new(1.0, 0.0, 0.0, 2.0, 1.0, 1.0).polyhedron();
    let load = |block: usize| crate::model::CarriedLoad { block, point: [1.5, 0.5, 1.0], weight: 1000.0 };
    let spec = ModelSpec3 { blocks: vec![Box3::new(0.0, 0.0, 0.0, 1.0, 1.0, 1.0)], polyhedra: vec![cube], ..ModelSpec3::default() };
    let m = Model3::new(&ModelSpec3 { carried: vec![load(1)], ..spec.clone() }).unwrap();
    assert!((m.mass()[1] - (2000.0 + 1000.0 / 9.81)).abs() < 1e-9);
    let err = Model3::new(&ModelSpec3 { carried: vec![load(2)], ..spec }).unwrap_err();
    assert!(err.to_string().contains("block 2 is not a wall block (the wall has 2"), "{err}");
}
