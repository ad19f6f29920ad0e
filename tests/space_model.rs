//! The 3D model on generated walls: the generators' counts and volumes, the bond of the
//! corners, the contacts against the 2D detection of the same wall, the loads' totals and the
//! openings.

use masonry_dem::geometry::{polygons, running_bond, FirstCourse, RunningBond, MIN_PART};
use masonry_dem::interface::Family;
use masonry_dem::model::{Model, ModelSpec};
use masonry_dem::space::{corner, cut_openings, running_bond_3d, u_wall, Box3, LiveLoad3, Model3, ModelSpec3};
use masonry_dem::Error;

fn volume(blocks: &[Box3]) -> f64 {
    blocks.iter().map(Box3::volume).sum()
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs())
}

fn input_message<T: std::fmt::Debug>(r: Result<T, Error>) -> (Option<String>, String) {
    match r {
        Err(Error::Input { key, reason }) => (key, reason),
        other => panic!("expected an input error, got {other:?}"),
    }
}

#[test]
fn running_bond_counts_and_volume() {
    // 4 m of 0.4 m blocks, 10 courses of 0.2 m: half-block starts give 11 + 10 blocks a pair of
    // courses, whole-block starts 10 + 11
    for (offset, first) in [(0.2, 11), (0.0, 10)] {
        let blocks = running_bond_3d(4.0, 2.0, 0.1, 0.4, 0.2, offset).unwrap();
        assert_eq!(blocks.len(), 105);
        let lowest = blocks.iter().filter(|b| b.min[2] == 0.0).count();
        assert_eq!(lowest, first);
        assert!(close(volume(&blocks), 4.0 * 2.0 * 0.1, 1e-14));
    }
    // lengths and heights off the module: end blocks and a last course cut to fit, no sliver
    for (length, height) in [(4.1, 2.1), (4.01, 2.0), (3.3, 0.35)] {
        for offset in [0.0, 0.2, 0.1] {
            let blocks = running_bond_3d(length, height, 0.25, 0.4, 0.2, offset).unwrap();
            assert!(close(volume(&blocks), length * height * 0.25, 1e-13), "{length} x {height}, offset {offset}");
            let shortest = blocks.iter().map(|b| b.size()[0]).fold(f64::MAX, f64::min);
            assert!(shortest >= MIN_PART * 0.4, "a sliver of {shortest} m");
            let model = Model3::new(&ModelSpec3 { blocks, ..ModelSpec3::default() }).unwrap();
            assert!(model.n_blocks() > 0);
        }
    }
    let (key, msg) = input_message(running_bond_3d(4.0, 2.0, 0.1, 0.4, 0.2, 0.4));
    assert_eq!(key.as_deref(), Some("running_bond_3d.first_course_offset"), "{msg}");
    let (key, _) = input_message(running_bond_3d(-4.0, 2.0, 0.1, 0.4, 0.2, 0.0));
    assert_eq!(key.as_deref(), Some("running_bond_3d.length"));
    let (_, msg) = input_message(running_bond_3d(4.0, 2.02, 0.1, 0.4, 0.2, 0.0));
    assert!(msg.starts_with("running_bond_3d.height = 2.02 m"), "{msg}");
}

/// A leaf of the 3D generator has the contacts of the 2D wall it extrudes: the same pairs, of
/// the same families, each rectangle the 2D segment times the thickness.
#[test]
fn a_leaf_has_the_contacts_of_its_2d_wall() {
    let (length, courses, t) = (3.2, 8, 0.3);
    let rects = running_bond(&RunningBond {
        block_length: 0.4,
        block_height: 0.175,
        courses,
        height: None,
        length,
        first_course: FirstCourse::Half,
        openings: vec![],
    })
    .unwrap();
    let flat = Model::new(ModelSpec { blocks: polygons(rects.clone()), thickness: t, ..ModelSpec::default() }).unwrap();
    let blocks = running_bond_3d(length, courses as f64 * 0.175, t, 0.4, 0.175, 0.2).unwrap();
    assert_eq!(blocks.len(), rects.len());
    for (b, r) in blocks.iter().zip(&rects) {
        assert!((b.min[0] - r.x0).abs() < 1e-12 && (b.max[2] - r.y1).abs() < 1e-12);
    }
    let solid = Model3::new(&ModelSpec3 { blocks, ..ModelSpec3::default() }).unwrap();
    assert_eq!(solid.contacts().len(), flat.interfaces().len());
    for (c, it) in solid.contacts().iter().zip(flat.interfaces()) {
        assert_eq!((c.a, c.b, c.family), (it.a, it.b, it.family));
        assert!(close(c.area, it.l * t, 1e-12));
        assert!((c.centroid[0] - it.c[0]).abs() < 1e-12 && (c.centroid[2] - it.c[1]).abs() < 1e-12);
        assert!((c.centroid[1] - 0.5 * t).abs() < 1e-12);
        assert_eq!([c.n[0], c.n[2]], it.n);
    }
}

/// Whether `b` is a block of the facade (y in [0, t]) rather than of a return wall.
fn on_facade(b: &Box3, t: f64) -> bool {
    b.min[1].abs() < 1e-12 && (b.max[1] - t).abs() < 1e-12
}

#[test]
fn u_wall_volume_and_bonded_corners() {
    let (f, h, r, t, l, bh) = (3.0, 1.6, 1.5, 0.2, 0.4, 0.2);
    let blocks = u_wall(f, h, r, t, l, bh).unwrap();
    assert!(close(volume(&blocks), (f + 2.0 * (r - t)) * t * h, 1e-13));
    let n_wall = blocks.len();
    let model = Model3::new(&ModelSpec3 { blocks: blocks.clone(), top: Some(0.2), ..ModelSpec3::default() }).unwrap();
    let courses = (h / bh).round() as usize;
    for k in 0..courses {
        let z = (k as f64 + 0.5) * bh;
        for x in [0.5 * t, f - 0.5 * t] {
            // the block over this corner in course k
            let c = (0..n_wall)
                .find(|&i| {
                    let b = &blocks[i];
                    b.min[0] < x && x < b.max[0] && b.min[1] < 0.5 * t && 0.5 * t < b.max[1] && b.min[2] < z && z < b.max[2]
                })
                .unwrap_or_else(|| panic!("no block over the corner x = {x} in course {k}"));
            // the facade's in the even courses, the return's in the odd ones, past the corner
            assert_eq!(on_facade(&blocks[c], t), k % 2 == 0, "course {k}, x = {x}: {:?}", blocks[c]);
            assert!(blocks[c].size()[0].max(blocks[c].size()[1]) > t + MIN_PART * l);
            // bed joints with blocks of both walls below and above (base and top beam aside)
            for below in [true, false] {
                if (below && k == 0) || (!below && k + 1 == courses) {
                    continue;
                }
                let others: Vec<usize> = model
                    .contacts_of(c)
                    .into_iter()
                    .map(|j| &model.contacts()[j])
                    .filter(|ct| ct.family == Family::Bed && (ct.b == c) == below)
                    .map(|ct| if ct.a == c { ct.b } else { ct.a })
                    .collect();
                let facade = others.iter().filter(|&&o| on_facade(&blocks[o], t)).count();
                assert!(facade >= 1 && others.len() > facade, "course {k}, x = {x}, below {below}: {others:?}");
            }
        }
    }
    // each wall block touches; the top beam carries the highest course, the base the lowest
    let base = model.contacts().iter().filter(|c| c.family == Family::Base).count();
    let lowest = blocks.iter().filter(|b| b.min[2] == 0.0).count();
    assert_eq!(base, lowest);
    let top = model.contacts().iter().filter(|c| c.family == Family::Top).count();
    assert_eq!(top, blocks.iter().filter(|b| (b.max[2] - h).abs() < 1e-12).count());
    let (key, _) = input_message(u_wall(f, h, r, 0.4, l, bh));
    assert_eq!(key.as_deref(), Some("u_wall.thickness"));
    let (key, _) = input_message(u_wall(f, h, 0.2, t, l, bh));
    assert_eq!(key.as_deref(), Some("u_wall.returns"));
}

#[test]
fn corner_is_one_return_of_the_u() {
    let (f, h, r, t, l, bh) = (2.0, 1.0, 1.2, 0.15, 0.4, 0.2);
    let l_blocks = corner(f, h, r, t, l, bh).unwrap();
    assert!(close(volume(&l_blocks), (f + r - t) * t * h, 1e-13));
    assert!(l_blocks.iter().all(|b| b.max[0] <= f && b.min[0] >= 0.0));
    assert!(l_blocks.iter().all(|b| !(b.min[0] > t && b.min[1] > 0.0)), "nothing but the facade and the return at x = 0");
    let model = Model3::new(&ModelSpec3 { blocks: l_blocks, ..ModelSpec3::default() }).unwrap();
    assert!(model.contacts().iter().any(|c| c.family == Family::Head && c.n == [0.0, 1.0, 0.0]));
}

#[test]
fn dead_load_is_the_weight_and_live_load_its_direction() {
    let blocks = u_wall(2.4, 1.2, 1.2, 0.2, 0.4, 0.2).unwrap();
    let (rho, g, beam) = (1800.0, 9.81, 0.3);
    let spec = ModelSpec3 {
        blocks: blocks.clone(),
        density: rho,
        gravity: g,
        top: Some(beam),
        live: LiveLoad3::HorizontalWeight { direction: 90.0 },
        ..ModelSpec3::default()
    };
    let m = Model3::new(&spec).unwrap();
    let wall = rho * g * volume(&blocks);
    let beam_weight = rho * g * 2.4 * 1.2 * beam;
    let total = |f: &[f64], k: usize| -> f64 { f.iter().skip(k).step_by(6).sum() };
    let dead = m.dead_load();
    assert!(close(total(dead, 2), -(wall + beam_weight), 1e-12));
    for k in [0, 1, 3, 4, 5] {
        assert_eq!(total(dead, k), 0.0);
    }
    let live = m.live_load();
    assert_eq!(total(live, 0), 0.0);
    assert!(close(total(live, 1), wall + beam_weight, 1e-12), "the live load is on every weight, the top beam's too");
    for k in 2..6 {
        assert_eq!(total(live, k), 0.0);
    }
    let none = Model3::new(&ModelSpec3 { live: LiveLoad3::None, ..spec }).unwrap();
    assert!(none.live_load().iter().all(|&f| f == 0.0));
}

#[test]
fn openings_remove_exactly_their_volume() {
    // a window and a door whose edges fall inside blocks, away from their edges
    let (w, h, t) = (4.0, 2.4, 0.1);
    let wall = running_bond_3d(w, h, t, 0.4, 0.2, 0.2).unwrap();
    let openings = [[1.1, 0.9, 2.3, 1.7], [2.9, 0.0, 3.5, 1.9]];
    let cut = cut_openings(wall.clone(), &openings).unwrap();
    let removed: f64 = openings.iter().map(|o| (o[2] - o[0]) * (o[3] - o[1]) * t).sum();
    assert!(close(volume(&cut), w * h * t - removed, 1e-13));
    for b in &cut {
        for o in &openings {
            let inside = b.min[0] < o[2] && o[0] < b.max[0] && b.min[2] < o[3] && o[1] < b.max[2];
            assert!(!inside, "{b:?} in the opening {o:?}");
        }
    }
    Model3::new(&ModelSpec3 { blocks: cut, ..ModelSpec3::default() }).unwrap();
    // an edge 4 mm from a joint (less than 5% of the block) is snapped onto it: no sliver
    let cut = cut_openings(wall.clone(), &[[1.204, 0.8, 2.0, 1.6]]).unwrap();
    // (snapped in the odd courses, whose joint is at 1.2 m, cut at 1.204 m in the even ones)
    assert!(close(volume(&cut), w * h * t - (2.0 * 0.796 + 2.0 * 0.8) * 0.2 * t, 1e-13));
    assert!(cut.iter().all(|b| b.size()[0] >= 0.02 - 1e-12));
    // the facade of a U: the returns keep their blocks; an opening over a corner is refused
    let (f, r, tu) = (3.0, 1.2, 0.2);
    let u = u_wall(f, 1.6, r, tu, 0.4, 0.2).unwrap();
    let cut = cut_openings(u.clone(), &[[1.1, 0.5, 1.9, 1.3]]).unwrap();
    assert!(close(volume(&cut), volume(&u) - 0.8 * 0.8 * tu, 1e-13));
    let (key, msg) = input_message(cut_openings(u, &[[0.1, 0.5, 0.9, 1.3]]));
    assert_eq!(key.as_deref(), Some("openings"));
    assert!(msg.contains("clear of the corners"), "{msg}");
    let (_, msg) = input_message(cut_openings(wall, &[[1.0, 0.5, 0.9, 1.3]]));
    assert!(msg.starts_with("openings[0]"), "{msg}");
}

/// An opening wholly outside the facade (or only touching its edge) is refused by its index and
/// coordinates, where it used to be dropped without a word; one partly outside cuts the part
/// within, as the 2D running bond does (the same wall's faces); openings that remove every
/// block are refused by the openings' name.
#[test]
fn openings_outside_the_wall_are_refused_and_partly_outside_cut_the_part_within() {
    let (length, height, t) = (2.0, 1.0, 0.1);
    let wall = running_bond_3d(length, height, t, 0.4, 0.2, 0.2).unwrap();
    for outside in [[5.0, 0.2, 6.0, 0.5], [-1.0, 0.2, 0.0, 0.5], [0.5, 1.0, 1.5, 2.0], [0.5, -2.0, 1.5, -1.0]] {
        let (key, msg) = input_message(cut_openings(wall.clone(), &[[0.2, 0.2, 0.6, 0.6], outside]));
        assert_eq!(key.as_deref(), Some("openings[1]"), "{msg}");
        assert!(msg.starts_with("openings[1] [x0, z0, x1, z1] = [") && msg.contains("lies outside the wall"), "{msg}");
        assert!(msg.contains("x from 0 to 2 m, z from 0 to 1 m"), "{msg}");
    }
    // a door from below the ground and a notch past the end: the parts within are cut, as in 2D
    let openings = [[0.5, -1.0, 0.9, 0.6], [1.7, 0.4, 3.0, 0.8]];
    let cut = cut_openings(wall, &openings).unwrap();
    let removed = (0.4 * 0.6 + 0.3 * 0.4) * t;
    assert!(close(volume(&cut), length * height * t - removed, 1e-13));
    let plane = running_bond(&RunningBond {
        block_length: 0.4,
        block_height: 0.2,
        courses: 5,
        height: None,
        length,
        first_course: FirstCourse::Half,
        openings: openings.iter().map(|o| masonry_dem::geometry::Rect::new(o[0], o[1], o[2], o[3])).collect(),
    })
    .unwrap();
    let key = |x0: f64, z0: f64| ((z0 * 1e6).round() as i64, (x0 * 1e6).round() as i64);
    let mut faces: Vec<_> = cut.iter().map(|b| (key(b.min[0], b.min[2]), key(b.max[0], b.max[2]))).collect();
    let mut rects: Vec<_> = plane.iter().map(|r| (key(r.x0, r.y0), key(r.x1, r.y1))).collect();
    faces.sort_unstable();
    rects.sort_unstable();
    assert_eq!(faces, rects);
    // over the whole leaf
    let (key, msg) = input_message(cut_openings(running_bond_3d(length, height, t, 0.4, 0.2, 0.2).unwrap(), &[[-1.0, -1.0, 3.0, 3.0]]));
    assert_eq!(key.as_deref(), Some("openings"));
    assert!(msg.contains("remove every block of the wall"), "{msg}");
    // an opening's own size, in the facade's coordinates
    let (_, msg) = input_message(cut_openings(running_bond_3d(length, height, t, 0.4, 0.2, 0.2).unwrap(), &[[0.5, 0.6, 0.9, 0.6]]));
    assert!(msg.contains("need x0 < x1 and z0 < z1"), "{msg}");
}

/// A lone box without a base touches nothing because nothing holds it: the refusal says so, as it
/// does for two boxes without a base.
#[test]
fn a_wall_without_a_base_has_no_support_whatever_its_blocks() {
    for blocks in [vec![Box3::new(0.0, 0.0, 0.0, 0.4, 0.6, 1.0)], vec![Box3::new(0.0, 0.0, 0.0, 0.4, 0.6, 1.0), Box3::new(0.0, 0.0, 1.0, 0.4, 0.6, 2.0)]] {
        let spec = ModelSpec3 { blocks, base: false, ..ModelSpec3::default() };
        let (_, msg) = input_message(Model3::new(&spec).and_then(|m| m.check_supports()));
        assert!(msg.starts_with("the wall has no support"), "{msg}");
    }
}

/// A wall whose weight is too small for the solvers' products of forces is refused by its
/// density before any method runs (limit analysis alone used to answer, the explicit solver to
/// fail with "no collapse bracket").
#[test]
fn a_weight_below_the_solvers_range_is_refused_by_its_density() {
    use masonry_dem::error::MIN_WEIGHT;
    let blocks = vec![Box3::new(0.0, 0.0, 0.0, 0.4, 0.6, 1.0)];
    for density in [1e-300, 1e-160] {
        let (key, msg) = input_message(Model3::new(&ModelSpec3 { blocks: blocks.clone(), density, ..ModelSpec3::default() }));
        assert_eq!(key.as_deref(), Some("geometry.density"), "{msg}");
        assert!(msg.contains("below the 1.5e-154 N"), "{msg}");
    }
    // the weight just above the limit builds (0.24 m3 at 9.81 m/s2)
    let density = 1.01 * MIN_WEIGHT / (0.24 * 9.81);
    Model3::new(&ModelSpec3 { blocks, density, ..ModelSpec3::default() }).unwrap();
}

/// The explicit solver refuses a control block held along the axis its curve follows (the base):
/// its curve would be zeros.
#[test]
fn a_held_control_block_is_refused_in_3d() {
    use masonry_dem::explicit::{solve_3d, ExplicitOptions};
    let model = Model3::new(&ModelSpec3 {
        blocks: vec![Box3::new(0.0, 0.0, 0.0, 0.4, 0.6, 1.0)],
        live: LiveLoad3::HorizontalWeight { direction: 90.0 },
        ..ModelSpec3::default()
    })
    .unwrap();
    let base = model.base().unwrap();
    let (_, msg) = input_message(solve_3d(&model, &ExplicitOptions { control_block: Some(base), ..ExplicitOptions::default() }));
    assert!(msg.contains("control block 1 (the base) is held along y"), "{msg}");
}

/// A stack of `n` cubes of side `s` whose lowest face is at `z0`, with `law` everywhere and
/// gravity `g`.
fn stack(n: usize, s: f64, z0: f64, law: masonry_dem::joint::JointLaw, g: f64) -> Result<Model3, Error> {
    let blocks = (0..n).map(|i| Box3::new(0.0, 0.0, z0 + i as f64 * s, s, s, z0 + (i + 1) as f64 * s)).collect();
    Model3::new(&ModelSpec3 { blocks, gravity: g, joints: masonry_dem::model::JointLaws::uniform(law), ..ModelSpec3::default() })
}

#[test]
fn joints_too_soft_for_the_dead_loads_are_refused_when_the_model_is_built() {
    use masonry_dem::joint::JointLaw;
    // a leaf 2 m long, 1.05 m high (density 2000, g 9.81: 20.6 kPa at its base): kN = 1e5 N/m3 would sink
    // it 0.21 m, more than 0.01 of its 2 m; so would kN = 1e-300 and gravity 1e12 (the explicit solver
    // found no equilibrium under the dead loads alone); 1e8 sinks it 0.2 mm and is taken
    let leaf = |kn: f64, g: f64| {
        let law = JointLaw { normal_stiffness: kn, shear_stiffness: kn, friction: 0.7, dilatancy: 0.7, ..JointLaw::default() };
        let blocks = running_bond_3d(2.0, 1.05, 0.1, 0.4, 0.175, 0.2).unwrap();
        Model3::new(&ModelSpec3 { blocks, gravity: g, joints: masonry_dem::model::JointLaws::uniform(law), ..ModelSpec3::default() })
    };
    for (kn, g) in [(1e5, 9.81), (1e-300, 9.81), (1e10, 1e12)] {
        let (key, reason) = input_message(leaf(kn, g));
        assert_eq!(key, None);
        assert!(reason.starts_with("under its dead loads ("), "{reason}");
        assert!(
            reason.contains("m into its base joints (joints' normal_stiffness x base area = ")
                && reason.contains("more than 0.01 of its size (2.000e0 m): the small-displacement model does not hold; check gravity, density and the joints' normal_stiffness"),
            "{reason}"
        );
    }
    let sinks = |r: &str| r.split("sink about ").nth(1).and_then(|t| t.split(' ').next()).and_then(|v| v.parse::<f64>().ok()).unwrap();
    let (_, reason) = input_message(leaf(1e5, 9.81));
    // the weight over the base's stiffness: 2000 x 9.81 x 1.05 Pa over 1e5 N/m3
    assert!(close(sinks(&reason), 2000.0 * 9.81 * 1.05 / 1e5, 1e-3), "{reason}");
    assert!(leaf(1e8, 9.81).is_ok());
    // a stiffness whose product with a contact's area overflows: named with its blocks and key
    let law = JointLaw { normal_stiffness: 1e300, shear_stiffness: 1e300, ..JointLaw::default() };
    let (_, reason) = input_message(stack(1, 1e5, 0.0, law, 9.81));
    assert!(
        reason.starts_with("the contact of the base and block 0 [0, 0, 0, 100000, 100000, 100000]: its stiffness (joints.normal_stiffness or shear_stiffness times its area, 1e10 m2) is not finite"),
        "{reason}"
    );
}

#[test]
fn boxes_of_any_size_find_their_contacts() {
    use masonry_dem::joint::JointLaw;
    // a stack of three cubes on the base is the same model at 1e-10 m, 1 m and 1e6 m (the contact
    // tolerance 1e-8 of the model's size: at least 1e-8 m, it took boxes of 1e-8 m for apart), and
    // far from the origin (the tolerance at least 1e-14 of the largest coordinate)
    for (s, z0) in [(1e-10, 0.0), (1e-8, 0.0), (1.0, 0.0), (1e6, 0.0), (1e-6, 1e3)] {
        let m = stack(3, s, z0, JointLaw::default(), 9.81).unwrap_or_else(|e| panic!("cubes of {s} m at {z0} m: {e}"));
        let bases = m.contacts().iter().filter(|c| c.family == Family::Base).count();
        assert_eq!((m.contacts().len(), bases), (3, 1), "cubes of {s} m at {z0} m");
        assert!(m.contacts().iter().all(|c| close(c.area, s * s, 1e-9)), "cubes of {s} m");
    }
    // a box whose smallest side is within ten times the tolerance: refused by name
    let blocks = vec![Box3::new(0.0, 0.0, 0.0, 1.0, 1.0, 1.0), Box3::new(0.0, 0.0, 1.0, 1.0, 1.0, 1.0 + 5e-8)];
    let (_, reason) = input_message(Model3::new(&ModelSpec3 { blocks, ..ModelSpec3::default() }));
    assert!(reason.starts_with("block 1 [0, 0, 1, 1, 1, 1.00000005]: its smallest side, "), "{reason}");
    assert!(reason.ends_with("its faces cannot be told apart"), "{reason}");
}
