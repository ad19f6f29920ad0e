//! The cross (groin) vault of [`masonry_dem::space::cross_vault`]: its volume against the
//! closed form of the groin vault of the same section, its multiplier pushed along x and along
//! y (a square bay: the same), and its self-weight: it stands where the shell is thick enough
//! and not where it is very thin, and the groins carry it thinner than the barrel vault of the
//! same arch. (tests/python/test_vault_lp.py checks the same blocks against an independent
//! linear program.)

mod common;

use common::{stands, vault_model};
use masonry_dem::geometry::{Arch, ArchKind, Springing};
use masonry_dem::limit::{limit_analysis_3d, LimitOptions};
use masonry_dem::results::Status;
use masonry_dem::space::{barrel_vault, cross_vault, BarrelVault, CrossVault, Model3, Vaulted};
use std::f64::consts::PI;

const ABUTMENTS: Springing = Springing::Abutments { width: None, height: None };

fn arch(t: f64, n: usize, springing: Springing) -> Arch {
    Arch { kind: ArchKind::Semicircular, span: None, radius: Some(1.0), rise: None, thickness: t, voussoirs: n, springing, backfill: None }
}

/// The semicircular cross vault of centreline radius 1 m on its corner supports.
fn semicircular(t: f64, n: usize) -> CrossVault {
    CrossVault { arch: arch(t, n, ABUTMENTS) }
}

/// The vault on its supports, or on the base if it has none (on piers).
fn model(v: Vaulted, mu: f64, direction: f64) -> Model3 {
    vault_model(v, mu, direction)
}

/// The section's right half (x >= 0) as a polygon, for `n` even voussoirs of a semicircular
/// arch of radii `ri`, `re`: the joints' ends at angles pi k / n, the chords between them.
fn right_half(ri: f64, re: f64, n: usize) -> Vec<[f64; 2]> {
    let at = |r: f64, k: usize| {
        let a = PI * k as f64 / n as f64;
        [r * a.cos(), r * a.sin()]
    };
    let mut p: Vec<[f64; 2]> = (0..=n / 2).map(|k| at(re, k)).collect();
    p.extend((0..=n / 2).rev().map(|k| at(ri, k)));
    p
}

#[test]
fn a_cross_vault_has_the_volume_of_the_groin_vault_of_its_section() {
    // each web's voussoir runs along its barrel from the groin |x| = y to the bay's side y = a:
    // the vault's volume is 4 (a A - integral of |x| over the section) = 8 (a A_h - M_h), with
    // A_h and M_h the area of the section's right half and its first moment about x = 0
    // (shoelace, written here); the curved vault's, 2 pi a (re^2 - ri^2) - 8 (re^3 - ri^3) / 3,
    // is larger by the chords' loss, of order (pi / n)^2
    let (ri, re) = (0.9, 1.1);
    for n in [8, 16, 40] {
        let v = cross_vault(&semicircular(0.2, n)).unwrap();
        assert_eq!((v.blocks.len(), v.supports.len()), (4 * n, 4));
        let got: f64 = v.blocks.iter().map(|b| b.volume_properties().volume).sum();
        let p = right_half(ri, re, n);
        let (mut area, mut moment) = (0.0, 0.0);
        for k in 0..p.len() {
            let ([x0, y0], [x1, y1]) = (p[k], p[(k + 1) % p.len()]);
            let c = x0 * y1 - x1 * y0;
            area += 0.5 * c;
            moment += (x0 + x1) * c / 6.0;
        }
        let (area, moment) = (area.abs(), moment.abs());
        let want = 8.0 * (re * area - moment);
        assert!((got - want).abs() <= 1e-12 * want, "n = {n}: {got:.15} against {want:.15}");
        let curved = 2.0 * PI * re * (re * re - ri * ri) - 8.0 / 3.0 * (re.powi(3) - ri.powi(3));
        let d = PI / n as f64;
        assert!(got < curved && curved - got < d * d / 3.0 * curved, "n = {n}: {got} against the curved vault's {curved}");
        // the supports: the corner squares under the springing voussoirs
        let s: f64 = v.supports.iter().map(|b| b.volume_properties().volume).sum();
        assert!((s - 4.0 * 0.2 * 0.2 * 0.2).abs() < 1e-14);
    }
}

#[test]
fn a_cross_vault_s_contacts_are_its_joints_groins_and_springings() {
    let n = 9;
    let m = model(cross_vault(&semicircular(0.2, n)).unwrap(), 0.6, 0.0);
    assert_eq!(m.n_wall(), 4 * n);
    // in each web n - 1 joints; at each groin the voussoirs of one half of each of the two webs
    // and the keystones, face to face (4 x (n + 1) / 2); two springings on supports per web
    assert_eq!(m.contacts().len(), 4 * (n - 1) + 4 * n.div_ceil(2) + 4 * 2);
    // across a groin the two faces are the same polygon: the contact is the whole face, 4 corners
    assert!(m.contacts().iter().all(|c| (3..=4).contains(&c.corners.len())));
}

#[test]
fn a_square_cross_vault_pushed_along_x_or_y_has_one_multiplier() {
    let opts = LimitOptions { tolerance: 1e-10, ..LimitOptions::default() };
    for (t, n, mu) in [(0.2, 9, 0.6), (0.15, 12, 0.8)] {
        let lam = |d: f64| {
            let r = limit_analysis_3d(&model(cross_vault(&semicircular(t, n)).unwrap(), mu, d), &opts).unwrap();
            assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
            r.collapse_multiplier
        };
        let x = lam(0.0);
        assert!(x > 0.0);
        for d in [90.0, 180.0, 270.0] {
            let y = lam(d);
            assert!((y - x).abs() <= 1e-7 * x, "t = {t}, n = {n}: pushed at {d} deg {y:.12}, along x {x:.12}");
        }
    }
}

#[test]
fn a_cross_vault_stands_thinner_than_its_barrel_and_not_when_very_thin() {
    // friction 10: no joint slides. The plane's semicircular arch of 20 voussoirs (Milankovitch's
    // ring) stands from 0.1075 R (tests/arch_thickness.rs), and so does the barrel vault of
    // that arch (tests/space_vaults.rs); the cross vault's webs, each course of voussoirs held
    // at the groins by the crossing web, stand thinner. At 0.04 R no equilibrium: the least
    // thickness is about 0.07 R (of 16 voussoirs, friction 10: 0.069 R, between the inscribed and
    // circumscribed pyramids of the independent program, tests/python/test_vault_lp.py)
    let barrel = barrel_vault(&BarrelVault { arch: arch(0.1, 20, ABUTMENTS), length: 0.3, block_length: None }).unwrap();
    let r = limit_analysis_3d(&model(barrel, 10.0, 0.0).with_live_along_gravity(), &LimitOptions::default()).unwrap();
    assert!(!stands(r.status));
    for (t, want) in [(0.1, true), (0.04, false), (0.15, true), (0.02, false)] {
        let m = model(cross_vault(&semicircular(t, 20)).unwrap(), 10.0, 0.0).with_live_along_gravity();
        let r = limit_analysis_3d(&m, &LimitOptions::default()).unwrap();
        assert_eq!(stands(r.status), want, "t = {t}");
    }
}

#[test]
fn a_cross_vault_on_piers_that_stay_put_has_the_multiplier_on_fixed_supports() {
    // squat piers (0.6 m square out from the intrados, 0.3 m high, friction 0.6): they neither
    // slide nor rock at the vault's multiplier, and their tops carry the springing voussoirs on
    // the same triangles as the fixed supports: the same program's optimum. Slenderer piers (0.4 m
    // square, 1.2 m high in 4 courses) give way first, along x as along y
    let opts = LimitOptions { tolerance: 1e-10, ..LimitOptions::default() };
    let lam = |springing: Springing, d: f64| {
        let m = model(cross_vault(&CrossVault { arch: arch(0.2, 9, springing) }).unwrap(), 0.6, d);
        let r = limit_analysis_3d(&m, &opts).unwrap();
        assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
        (r.collapse_multiplier, m.n_wall())
    };
    let (fixed, n) = lam(ABUTMENTS, 0.0);
    assert_eq!(n, 36);
    let (on_piers, n) = lam(Springing::Piers { width: 0.6, height: 0.3, courses: 1 }, 0.0);
    assert_eq!(n, 36 + 4);
    assert!((on_piers - fixed).abs() <= 1e-7 * fixed, "on piers {on_piers:.12}, on fixed supports {fixed:.12}");
    let tall = Springing::Piers { width: 0.4, height: 1.2, courses: 4 };
    let ((x, n), (y, _)) = (lam(tall, 0.0), lam(tall, 90.0));
    assert_eq!(n, 36 + 16);
    assert!(x < 0.9 * fixed && (x - y).abs() <= 1e-7 * x, "along x {x:.12}, along y {y:.12}, on fixed supports {fixed:.12}");
}

#[test]
fn bad_cross_vault_parameters_are_refused_by_key() {
    let refused = |a: Arch| cross_vault(&CrossVault { arch: a }).unwrap_err().to_string();
    let e = refused(Arch { kind: ArchKind::Segmental, rise: Some(0.5), ..arch(0.2, 9, ABUTMENTS) });
    assert!(e.starts_with("geometry.cross_vault.kind must be"), "{e}");
    let e = refused(arch(0.2, 9, Springing::Abutments { width: None, height: Some(-1.0) }));
    assert!(e.starts_with("geometry.cross_vault.abutment_height"), "{e}");
    let e = refused(arch(0.2, 1, ABUTMENTS));
    assert!(e.starts_with("geometry.cross_vault.voussoirs"), "{e}");
    let e = refused(arch(2.5, 9, ABUTMENTS));
    assert!(e.starts_with("geometry.cross_vault.radius"), "{e}");
    let e = refused(arch(f64::NAN, 9, ABUTMENTS));
    assert!(e.starts_with("geometry.cross_vault.thickness"), "{e}");
    let e = refused(arch(0.2, 9, Springing::Piers { width: 0.1, height: 1.0, courses: 2 }));
    assert!(e.starts_with("geometry.cross_vault.pier_width"), "{e}");
    let e = refused(arch(0.2, 9, Springing::Piers { width: 0.3, height: 1.0, courses: 0 }));
    assert!(e.starts_with("geometry.cross_vault.pier_courses must lie in 1..="), "{e}");
    let e = refused(Arch { backfill: Some(1.0), ..arch(0.2, 9, ABUTMENTS) });
    assert!(e.starts_with("geometry.cross_vault: a backfill"), "{e}");
}
