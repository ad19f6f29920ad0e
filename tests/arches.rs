//! The arch generator: the voussoirs' area against the closed form of a ring cut by chords,
//! symmetry, the joints' directions, and the interfaces of the model it makes (every pair of
//! neighbouring voussoirs and both springings); the backfill over the extrados against the
//! closed form of its area and a strip's centroid by hand, and its refusals.

use masonry_dem::geometry::{arch, Arch, ArchGeometry, ArchKind, Springing};
use masonry_dem::interface::Family;
use masonry_dem::model::{Model, ModelSpec};
use masonry_dem::shape::{Area, Polygon};
use masonry_dem::Error;
use std::f64::consts::PI;

const ABUTMENTS: Springing = Springing::Abutments { width: None, height: None };

fn make(kind: ArchKind, span: Option<f64>, radius: Option<f64>, rise: Option<f64>, t: f64, n: usize, springing: Springing) -> ArchGeometry {
    arch(&Arch { kind, span, radius, rise, thickness: t, voussoirs: n, springing, backfill: None }).unwrap()
}

fn area(blocks: &[Polygon]) -> f64 {
    blocks.iter().map(|p| Area::of(p.vertices()).area).sum()
}

/// The area of a ring of radii `ri` < `re` over the angle `total`, cut into `n` equal voussoirs
/// whose intrados and extrados are chords: the annular sector, less the `n` segments the
/// extrados's chords cut off, plus the `n` segments the intrados's chords add (each segment of
/// angle d and radius r: r^2 (d - sin d) / 2).
fn chorded_ring(ri: f64, re: f64, total: f64, n: usize) -> f64 {
    let d = total / n as f64;
    let segments = n as f64 * (d - d.sin()) / 2.0;
    (re * re - ri * ri) * total / 2.0 - re * re * segments + ri * ri * segments
}

#[test]
fn circular_voussoirs_have_the_area_of_the_ring_cut_by_chords() {
    // semicircular, by radius (centreline 2 m, 0.3 m thick) and by span; odd and even counts
    for n in [2, 3, 7, 20, 81] {
        let a = make(ArchKind::Semicircular, None, Some(2.0), None, 0.3, n, ABUTMENTS);
        let want = chorded_ring(1.85, 2.15, PI, n);
        assert!((area(&a.blocks) - want).abs() <= 1e-13 * want, "n = {n}: {} against {want}", area(&a.blocks));
        let b = make(ArchKind::Semicircular, Some(3.7), None, None, 0.3, n, ABUTMENTS);
        assert!((area(&b.blocks) - want).abs() <= 1e-13 * want);
    }
    // segmental: span 4 m, rise 1 m: intrados radius (4 + 1) / 2 = 2.5 m, over 2 atan2(2, 1.5)
    let a = make(ArchKind::Segmental, Some(4.0), None, Some(1.0), 0.4, 15, ABUTMENTS);
    let total = 2.0 * 2f64.atan2(1.5);
    let want = chorded_ring(2.5, 2.9, total, 15);
    assert!((area(&a.blocks) - want).abs() <= 1e-13 * want, "{} against {want}", area(&a.blocks));
    // the same arch by its centreline radius (2.7 m) and rise: the same voussoirs
    let b = make(ArchKind::Segmental, None, Some(2.7), Some(1.0), 0.4, 15, ABUTMENTS);
    for (p, q) in a.blocks.iter().zip(&b.blocks) {
        assert!(p.vertices().iter().zip(q.vertices()).all(|(u, v)| (u[0] - v[0]).abs() < 1e-14 && (u[1] - v[1]).abs() < 1e-14));
    }
}

fn all_kinds() -> Vec<ArchGeometry> {
    let piers = Springing::Piers { width: 0.8, height: 2.0, courses: 4 };
    vec![
        make(ArchKind::Semicircular, None, Some(2.0), None, 0.3, 21, ABUTMENTS),
        make(ArchKind::Semicircular, Some(3.0), None, None, 0.3, 20, piers),
        make(ArchKind::Segmental, Some(4.0), None, Some(1.0), 0.4, 15, Springing::Abutments { width: Some(1.0), height: Some(0.5) }),
        make(ArchKind::Segmental, Some(4.0), None, Some(1.0), 0.4, 16, piers),
        make(ArchKind::Pointed, Some(3.0), None, Some(2.6), 0.35, 18, ABUTMENTS),
        make(ArchKind::Pointed, Some(3.0), None, Some(1.5), 0.35, 12, piers),
        make(ArchKind::Elliptical, Some(5.0), None, Some(1.5), 0.4, 25, ABUTMENTS),
        make(ArchKind::Elliptical, Some(3.0), None, Some(2.0), 0.3, 10, piers),
    ]
}

#[test]
fn arches_are_symmetric_to_the_last_bit() {
    for a in all_kinds() {
        let mirror = |p: &Polygon| {
            let mut v: Vec<[f64; 2]> = p.vertices().iter().map(|v| [-v[0], v[1]]).collect();
            v.sort_by(|p, q| p.partial_cmp(q).unwrap());
            v
        };
        let sorted = |p: &Polygon| {
            let mut v = p.vertices().to_vec();
            v.sort_by(|p, q| p.partial_cmp(q).unwrap());
            v
        };
        let nv = a.extrados.len() - 1; // the voussoirs
        for k in 0..nv {
            assert_eq!(mirror(&a.blocks[k]), sorted(&a.blocks[nv - 1 - k]), "voussoir {k}");
        }
        // the piers (left courses, then right) and the abutments
        let piers = &a.blocks[nv..];
        let half = piers.len() / 2;
        for k in 0..half {
            assert_eq!(mirror(&piers[k]), sorted(&piers[half + k]));
        }
        if !a.supports.is_empty() {
            assert_eq!(mirror(&a.supports[0]), sorted(&a.supports[1]));
        }
        let e = &a.extrados;
        assert!((0..e.len()).all(|k| e[k] == [-e[e.len() - 1 - k][0], e[e.len() - 1 - k][1]]));
    }
}

/// The voussoirs tile the ring: their areas add up to the area of its outline (extrados
/// polyline, springing joints, intrados polyline), for every kind.
#[test]
fn voussoirs_tile_the_ring() {
    for a in all_kinds() {
        let nv = a.extrados.len() - 1;
        let mut outline: Vec<[f64; 2]> = a.intrados.clone();
        outline.extend(a.extrados.iter().rev());
        let ring = Area::of(&outline).area.abs();
        let sum = area(&a.blocks[..nv]);
        assert!((sum - ring).abs() <= 1e-12 * ring, "{sum} against {ring}");
    }
}

#[test]
fn joints_are_radial_or_normal_to_the_intrados() {
    // segmental: each joint's line passes through the centre (0, rise - r)
    let a = make(ArchKind::Segmental, Some(4.0), None, Some(1.0), 0.4, 15, ABUTMENTS);
    for (i, e) in a.intrados.iter().zip(&a.extrados) {
        let cross = (i[0] - 0.0) * (e[1] - (1.0 - 2.5)) - (i[1] - (1.0 - 2.5)) * (e[0] - 0.0);
        assert!(cross.abs() < 1e-12);
        assert!(((e[0] - i[0]).hypot(e[1] - i[1]) - 0.4).abs() < 1e-14);
    }
    // elliptical: each joint along the intrados's normal (a^2 y, b^2 x)-wise: (x / a^2, y / b^2)
    let (a2, b2) = (2.5f64 * 2.5, 1.5f64 * 1.5);
    let e = make(ArchKind::Elliptical, Some(5.0), None, Some(1.5), 0.4, 25, ABUTMENTS);
    for (i, x) in e.intrados.iter().zip(&e.extrados) {
        assert!((i[0] * i[0] / a2 + i[1] * i[1] / b2 - 1.0).abs() < 1e-14, "on the ellipse");
        let normal = [i[0] / a2, i[1] / b2];
        let joint = [x[0] - i[0], x[1] - i[1]];
        assert!((normal[0] * joint[1] - normal[1] * joint[0]).abs() < 1e-14 * normal[0].hypot(normal[1]));
        assert!((joint[0].hypot(joint[1]) - 0.4).abs() < 1e-14);
    }
    // pointed: the crown's joint vertical at x = 0, from the apex at the rise
    let p = make(ArchKind::Pointed, Some(3.0), None, Some(2.6), 0.35, 18, ABUTMENTS);
    assert_eq!(p.intrados[9], [0.0, 2.6]);
    assert_eq!(p.extrados[9][0], 0.0);
}

/// The model of each arch: an interface between every two neighbouring voussoirs, at each
/// springing, and between the courses of the piers (with the base under them); each joint of the
/// ring as long as the ring is thick (the pointed arch's crown joint longer).
#[test]
fn every_joint_of_the_ring_and_both_springings_are_interfaces() {
    for a in all_kinds() {
        let nv = a.extrados.len() - 1;
        let piers = a.blocks.len() - nv;
        let m = Model::new(ModelSpec { blocks: a.blocks.clone(), supports: a.supports.clone(), base: a.supports.is_empty(), ..ModelSpec::default() }).unwrap();
        let its = m.interfaces();
        for k in 0..nv - 1 {
            let found: Vec<_> = its.iter().filter(|it| (it.a.min(it.b), it.a.max(it.b)) == (k, k + 1)).collect();
            assert_eq!(found.len(), 1, "joint {k}");
        }
        // the springings: voussoir 0 and voussoir nv - 1 on an abutment or a pier's top course
        let (left, right) = if piers == 0 { (nv, nv + 1) } else { (nv + piers / 2 - 1, nv + piers - 1) };
        for (v, s) in [(0, left), (nv - 1, right)] {
            let it = its.iter().find(|it| (it.a.min(it.b), it.a.max(it.b)) == (v.min(s), v.max(s))).expect("springing");
            assert_eq!(it.b, v, "the voussoir above its springing");
            assert_eq!(it.family, if piers == 0 { Family::Base } else { Family::Bed });
        }
        // ring joints n - 1, springings 2, and with piers their courses' joints and the base's two
        let want = nv + 1 + if piers == 0 { 0 } else { piers - 2 + 2 };
        assert_eq!(its.len(), want);
    }
    // the joints' lengths: the thickness (radial and normal joints)
    let a = make(ArchKind::Elliptical, Some(5.0), None, Some(1.5), 0.4, 25, ABUTMENTS);
    let m = Model::new(ModelSpec { blocks: a.blocks, supports: a.supports, base: false, ..ModelSpec::default() }).unwrap();
    assert!(m.interfaces().iter().all(|it| (it.l - 0.4).abs() < 1e-13));
}

fn refused(p: Arch, key: &str) {
    match arch(&p) {
        Err(Error::Input { key: Some(k), reason }) => {
            assert_eq!(k, key, "{reason}");
            assert!(reason.contains(key), "{reason}");
        }
        other => panic!("expected a refusal naming {key}, got {other:?}"),
    }
}

#[test]
fn bad_arches_are_refused_naming_their_key() {
    let base = Arch { kind: ArchKind::Semicircular, span: None, radius: Some(2.0), rise: None, thickness: 0.3, voussoirs: 10, springing: ABUTMENTS, backfill: None };
    refused(Arch { thickness: 0.0, ..base }, "geometry.arch.thickness");
    refused(Arch { voussoirs: 1, ..base }, "geometry.arch.voussoirs");
    refused(Arch { radius: Some(0.1), ..base }, "geometry.arch.radius");
    refused(Arch { radius: None, ..base }, "geometry.arch.span");
    refused(Arch { span: Some(3.0), ..base }, "geometry.arch.radius");
    refused(Arch { rise: Some(1.0), ..base }, "geometry.arch.rise");
    refused(Arch { kind: ArchKind::Segmental, ..base }, "geometry.arch.rise");
    refused(Arch { kind: ArchKind::Segmental, rise: Some(3.0), ..base }, "geometry.arch.rise");
    let pointed = Arch { kind: ArchKind::Pointed, radius: None, span: Some(3.0), rise: Some(2.0), ..base };
    refused(Arch { voussoirs: 11, ..pointed }, "geometry.arch.voussoirs");
    refused(Arch { rise: Some(1.0), ..pointed }, "geometry.arch.rise");
    refused(Arch { radius: Some(2.0), ..pointed }, "geometry.arch.radius");
    refused(Arch { springing: Springing::Abutments { width: Some(0.1), height: None }, ..base }, "geometry.arch.abutment_width");
    refused(Arch { springing: Springing::Piers { width: 1.0, height: -1.0, courses: 2 }, ..base }, "geometry.arch.pier_height");
    refused(Arch { springing: Springing::Piers { width: 1.0, height: 1.0, courses: 0 }, ..base }, "geometry.arch.pier_courses");
}

/// A semicircular arch of extrados radius `re` in `n` voussoirs with its fill up to `level`.
fn filled(re: f64, t: f64, n: usize, level: f64) -> ArchGeometry {
    let a = Arch { kind: ArchKind::Semicircular, span: Some(2.0 * (re - t)), radius: None, rise: None, thickness: t, voussoirs: n, springing: ABUTMENTS, backfill: Some(level) };
    arch(&a).unwrap()
}

#[test]
fn the_fill_over_a_semicircular_arch_is_the_rectangle_less_the_extrados_polygon() {
    // the fill from the extrados's springing points up to `level` >= its crown: the rectangle
    // 2 re x level less the polygon under the extrados chords, n triangles of apex the centre,
    // each 1/2 re^2 sin(pi / n)
    for n in [2, 7, 20, 81] {
        for level in [2.5, 3.0, 4.75] {
            let (re, t) = (2.5, 0.4);
            let a = filled(re, t, n, level);
            let want = 2.0 * re * level - 0.5 * n as f64 * re * re * (PI / n as f64).sin();
            let got: f64 = a.fill.iter().map(|s| s.area).sum();
            assert!((got - want).abs() <= 1e-9 * want, "{n} voussoirs, level {level}: {got} against {want}");
            assert_eq!(a.fill.len(), n, "every voussoir carries fill");
            // the weights: density x thickness x g x area, on the voussoir under each strip
            let loads = a.fill_loads(1800.0, 0.5, 9.81).unwrap();
            let total: f64 = loads.iter().map(|l| l.weight).sum();
            assert!((total - 1800.0 * 0.5 * 9.81 * want).abs() <= 1e-9 * total);
            assert!(loads.iter().enumerate().all(|(k, l)| l.block == k));
        }
    }
}

#[test]
fn a_fill_strip_rests_under_its_centroid_by_hand() {
    // 4 voussoirs, extrados radius 2: the right-hand one's extrados chord from (sqrt 2, sqrt 2)
    // to (2, 0); the fill up to 3 m over it is a trapezoid of heights h0 = 3 - sqrt 2 and
    // h1 = 3 over the width w = 2 - sqrt 2: area w (h0 + h1) / 2, centroid
    // x = x0 + w (h0 + 2 h1) / (3 (h0 + h1)), y = the mean of L - h(x) / 2 weighted by h(x)
    let a = filled(2.0, 0.5, 4, 3.0);
    let s = a.fill[3];
    let (x0, y0) = (2f64.sqrt(), 2f64.sqrt());
    let (w, h0, h1) = (2.0 - x0, 3.0 - y0, 3.0);
    let area = w * (h0 + h1) / 2.0;
    let xc = x0 + w * (h0 + 2.0 * h1) / (3.0 * (h0 + h1));
    // y of the centroid: integral of (L + chord(x)) / 2 * h(x) dx / area, chord linear from y0 to 0:
    // with h = h0 + (h1 - h0) s over s in [0, 1] and chord = L - h, (L + chord) / 2 = L - h / 2,
    // integral of (L - h / 2) h ds = L (h0 + h1) / 2 - (h0^2 + h0 h1 + h1^2) / 6
    let yc = (3.0 * (h0 + h1) / 2.0 - (h0 * h0 + h0 * h1 + h1 * h1) / 6.0) / ((h0 + h1) / 2.0);
    let point = [xc, y0 * (2.0 - xc) / w];
    assert_eq!(s.block, 3);
    assert!((s.area - area).abs() <= 1e-12 * area, "{} against {area}", s.area);
    for (got, want) in [(s.centroid[0], xc), (s.centroid[1], yc), (s.point[0], point[0]), (s.point[1], point[1])] {
        assert!((got - want).abs() <= 1e-12, "{got} against {want}");
    }
    // a level below the crown, 1.9 m: the crown's voussoirs (their chords from (0, 2) down to
    // (sqrt 2, sqrt 2)) carry the triangle between the chord's crossing of the level and their
    // lower end; x of the crossing on the chord from (sqrt 2, sqrt 2) to (0, 2)
    let a = filled(2.0, 0.5, 4, 1.9);
    let s = a.fill[2];
    let cross = x0 * (2.0 - 1.9) / (2.0 - y0);
    let want_area = 0.5 * (x0 - cross) * (1.9 - y0);
    assert!((s.area - want_area).abs() <= 1e-12, "{} against {want_area}", s.area);
    assert!((s.centroid[0] - (cross + 2.0 * x0) / 3.0).abs() <= 1e-12);
}

#[test]
fn bad_backfills_are_refused_naming_their_key() {
    let base = Arch { kind: ArchKind::Semicircular, span: None, radius: Some(2.0), rise: None, thickness: 0.3, voussoirs: 10, springing: ABUTMENTS, backfill: None };
    let key = "geometry.arch.backfill.level";
    for level in [-1.0, 0.0, f64::NAN, f64::INFINITY] {
        refused(Arch { backfill: Some(level), ..base }, key);
    }
    // a segmental arch's extrados springs 0.18 m up (its centre 1.5 m below the springing line,
    // its radius 2.8 m, at sin 0.6): a level under it leaves no fill on the arch
    let segmental = Arch { kind: ArchKind::Segmental, radius: None, span: Some(4.0), rise: Some(1.0), ..base };
    let lowest = arch(&segmental).unwrap().extrados[0][1];
    assert!(lowest > 0.1);
    refused(Arch { backfill: Some(0.5 * lowest), ..segmental }, key);
    let a = arch(&Arch { backfill: Some(3.0), ..base }).unwrap();
    for (d, t, g, key) in [(-1.0, 1.0, 9.81, "geometry.arch.backfill.density"), (f64::NAN, 1.0, 9.81, "geometry.arch.backfill.density"), (1800.0, 0.0, 9.81, "geometry.thickness"), (1800.0, 1.0, 0.0, "loads.gravity")] {
        match a.fill_loads(d, t, g) {
            Err(Error::Input { key: Some(k), reason }) => assert!(k == key && reason.contains(key), "{reason}"),
            other => panic!("expected a refusal naming {key}, got {other:?}"),
        }
    }
}
