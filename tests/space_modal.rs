//! Modal analysis in 3D (`modal::modes_3d`) against closed forms: one box on its base (the
//! vertical and torsional modes, the two sliding-rocking pairs of 2 x 2 eigenproblems written
//! here), the same box turned in plan (a polyhedron with products of inertia: the same
//! frequencies), a wall of boxes extruded from a wall in the plane (its in-plane modes the
//! plane's modal analysis's), the shapes' orthonormality in the full inertia tensor and the
//! effective masses. Tolerance 1e-9 on every frequency (the basis spans every dof: the modes
//! are exact but for rounding).

mod common;

use common::{assert_close, eig2};
use masonry_dem::geometry::{polygons, Rect};
use masonry_dem::joint::JointLaw;
use masonry_dem::modal::{modes, modes_3d, Modes};
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::shape::Polyhedron;
use masonry_dem::space::{Box3, Model3, ModelSpec3};
use masonry_dem::Error;

const REL: f64 = 1e-9;
const KN: f64 = 1e10;
const KT: f64 = 4e9;
const DENSITY: f64 = 1000.0;

fn law() -> JointLaw {
    JointLaw { normal_stiffness: KN, shear_stiffness: KT, ..JointLaw::default() }
}

fn spec3(boxes: Vec<Box3>, polyhedra: Vec<Polyhedron>) -> ModelSpec3 {
    ModelSpec3 { blocks: boxes, polyhedra, density: DENSITY, joints: JointLaws::uniform(law()), ..ModelSpec3::default() }
}

/// `phi_i^T M phi_j = delta_ij` with each block's full inertia tensor (the shapes' rotations
/// about x, y, z), and every residual below 1e-8.
fn check_orthonormal(m: &Modes, model: &Model3) {
    let product = |a: &[f64], b: &[f64]| -> f64 {
        (0..model.n_blocks())
            .map(|i| {
                let t = model.inertia_tensor()[i];
                let trans: f64 = (0..3).map(|r| model.mass()[i] * a[6 * i + r] * b[6 * i + r]).sum();
                let rot: f64 = (0..3).flat_map(|r| (0..3).map(move |c| (r, c))).map(|(r, c)| a[6 * i + 3 + r] * t[r][c] * b[6 * i + 3 + c]).sum();
                trans + rot
            })
            .sum()
    };
    for (i, a) in m.shapes.iter().enumerate() {
        for (j, b) in m.shapes.iter().enumerate() {
            let want = if i == j { 1.0 } else { 0.0 };
            let p = product(a, b);
            assert!((p - want).abs() < 1e-8, "phi_{i}^T M phi_{j} = {p:e}");
        }
    }
    assert!(m.residuals.iter().all(|r| *r < 1e-8), "{:?}", m.residuals);
}

/// The closed forms of a box bx x by x h on springs at its base's four corners, ascending
/// [rad/s]: vertical `kN A / m`; torsion `kT A (bx^2 + by^2) / 4` (each corner's shear spring
/// kT A / 4 at its distance from the centre) over `m (bx^2 + by^2) / 12`; sliding along x with
/// rocking about y, coupled through the lever arm h / 2 of the shear at the base (rotational
/// stiffness `kN I_y = kN A bx^2 / 12`), and along y with rocking about x.
fn one_box_closed_form(bx: f64, by: f64, h: f64) -> Vec<f64> {
    let m = DENSITY * bx * by * h;
    let a = bx * by;
    let mut w = vec![KN * a / m, KT * a * (bx * bx + by * by) / 4.0 / (m * (bx * bx + by * by) / 12.0)];
    for b in [bx, by] {
        let (k11, k12, k22) = (KT * a, KT * a * h / 2.0, KT * a * h * h / 4.0 + KN * a * b * b / 12.0);
        w.extend(eig2(k11, k12, k22, m, m * (b * b + h * h) / 12.0));
    }
    let mut w: Vec<f64> = w.into_iter().map(f64::sqrt).collect();
    w.sort_by(f64::total_cmp);
    w
}

#[test]
fn one_box_on_its_base_matches_the_closed_forms() {
    let (bx, by, h) = (0.6, 0.4, 1.5);
    let model = Model3::new(&spec3(vec![Box3::new(0.0, 0.0, 0.0, bx, by, h)], vec![])).unwrap();
    let m = modes_3d(&model, 6, None).unwrap();
    let want = one_box_closed_form(bx, by, h);
    for (k, w) in want.iter().enumerate() {
        assert_close(m.angular[k], *w, REL, &format!("omega_{k} [rad/s]"));
        eprintln!("one box, mode {k}: {:.9} rad/s against {w:.9}, relative error {:.1e}", m.angular[k], (m.angular[k] / w - 1.0).abs());
    }
    check_orthonormal(&m, &model);
    // six modes of six dofs: the effective masses add up to the block's mass along x, y and z
    let mass = DENSITY * bx * by * h;
    for dir in 0..3 {
        let sum: f64 = m.effective_mass.iter().map(|e| e[dir]).sum();
        assert_close(sum, mass, 1e-9, &format!("effective mass along axis {dir} [kg]"));
        assert_close(m.free_mass[dir], mass, 1e-12, "free mass [kg]");
    }
    // the vertical mode is pure uz
    let vertical = (KN * bx * by / mass).sqrt();
    let k = m.angular.iter().position(|w| (w - vertical).abs() < 1e-9 * vertical).unwrap();
    assert!((m.shapes[k][2] - 1.0 / mass.sqrt()).abs() < 1e-9 / mass.sqrt(), "{:?}", m.shapes[k]);
    // the base is fixed: zero in every shape
    let base = model.base().unwrap();
    assert!(m.shapes.iter().all(|s| s[6 * base..6 * base + 6] == [0.0; 6]));
}

#[test]
fn a_box_turned_in_plan_has_the_frequencies_of_the_box() {
    // the box as a polyhedron turned about the vertical: its inertia tensor has products of
    // inertia in x, y, z (its rotation dofs about its principal axes) and its contact with the
    // base is the turned rectangle; the frequencies are the unturned box's
    let (bx, by, h) = (0.6, 0.4, 1.5);
    let want = one_box_closed_form(bx, by, h);
    for deg in [45.0f64, 30.0, 100.0] {
        let (s, c) = deg.to_radians().sin_cos();
        let block = Box3::new(-bx / 2.0, -by / 2.0, 0.0, bx / 2.0, by / 2.0, h).polyhedron().map(|v| [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]]);
        let model = Model3::new(&spec3(vec![], vec![block])).unwrap();
        let t = model.inertia_tensor()[0];
        assert!(t[0][1].abs() > 1e-3 * t[0][0], "the turned box has a product of inertia");
        let m = modes_3d(&model, 6, None).unwrap();
        for (k, w) in want.iter().enumerate() {
            assert_close(m.angular[k], *w, REL, &format!("turned by {deg} deg, omega_{k} [rad/s]"));
        }
        check_orthonormal(&m, &model);
        eprintln!("turned by {deg} deg: worst relative error {:.1e}", want.iter().zip(&m.angular).map(|(w, g)| (g / w - 1.0).abs()).fold(0.0, f64::max));
    }
}

#[test]
fn a_wall_of_boxes_extruded_from_the_plane_has_its_in_plane_modes() {
    // two courses in running bond, 0.25 m thick: the plane's wall and its boxes one block deep
    let t = 0.25;
    let rects = vec![
        Rect::new(0.0, 0.0, 0.4, 0.2),
        Rect::new(0.4, 0.0, 0.8, 0.2),
        Rect::new(0.0, 0.2, 0.2, 0.4),
        Rect::new(0.2, 0.2, 0.6, 0.4),
        Rect::new(0.6, 0.2, 0.8, 0.4),
    ];
    let boxes = rects.iter().map(|r| Box3::new(r.x0, 0.0, r.y0, r.x1, t, r.y1)).collect();
    let plane = Model::new(ModelSpec { blocks: polygons(rects), thickness: t, density: DENSITY, joints: JointLaws::uniform(law()), ..ModelSpec::default() }).unwrap();
    let space = Model3::new(&spec3(boxes, vec![])).unwrap();
    let m2 = modes(&plane, 15, None).unwrap();
    let m3 = modes_3d(&space, 30, None).unwrap();
    // the 3D modes in the plane x-z: no uy, rx or rz
    let in_plane: Vec<f64> = (0..m3.shapes.len())
        .filter(|&k| {
            let s = &m3.shapes[k];
            let out: f64 = (0..s.len()).filter(|g| [1, 3, 5].contains(&(g % 6))).map(|g| s[g].abs()).fold(0.0, f64::max);
            let all = s.iter().map(|v| v.abs()).fold(0.0, f64::max);
            out < 1e-9 * all
        })
        .map(|k| m3.angular[k])
        .collect();
    assert_eq!(in_plane.len(), 15, "{:?}", m3.angular);
    for (k, (w3, w2)) in in_plane.iter().zip(&m2.angular).enumerate() {
        assert_close(*w3, *w2, REL, &format!("in-plane omega_{k} [rad/s]"));
    }
    let worst = in_plane.iter().zip(&m2.angular).map(|(a, b)| (a / b - 1.0).abs()).fold(0.0, f64::max);
    eprintln!("extruded wall: 15 in-plane modes, worst relative difference {worst:.1e}");
    check_orthonormal(&m3, &space);
}

#[test]
fn bad_requests_are_refused_naming_the_count() {
    let model = Model3::new(&spec3(vec![Box3::new(0.0, 0.0, 0.0, 0.4, 0.4, 1.0)], vec![])).unwrap();
    let e = modes_3d(&model, 7, None).unwrap_err();
    assert!(matches!(&e, Error::Input { .. }) && e.to_string().contains("only 6 free dofs (6 per block not fixed)"), "{e}");
    assert!(matches!(modes_3d(&model, 0, None), Err(Error::Input { .. })));
    assert!(matches!(modes_3d(&model, 3, Some(f64::NAN)), Err(Error::Input { .. })));
}
