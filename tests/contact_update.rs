//! The contact update of time histories in the plane: contacts found again as blocks slide,
//! topple and fall, new contacts where they land, and the ground plane under a collapse.

use masonry_dem::explicit::{simulate, DynamicOptions, Recording, TimeHistory};
use masonry_dem::joint::JointLaw;
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::shape::Polygon;

/// A dry joint of friction angle `phi` (degrees) with the 3DEC verification's stiffnesses.
fn law(phi: f64) -> JointLaw {
    JointLaw { friction: phi.to_radians().tan(), normal_stiffness: 1e7, shear_stiffness: 1e7, cohesion: 0.0, tensile_strength: 0.0, ..JointLaw::default() }
}

/// 3DEC's "Sliding and Toppling Blocks": a block `b` wide and `h` high on a plane inclined by
/// `psi` (degrees) down towards +x, `length` long, the block's uphill corner `at` from the
/// plane's top; density 2000, g = 10, joints of friction angle `phi`.
fn on_slope(b: f64, h: f64, psi: f64, phi: f64, length: f64, at: f64) -> Model {
    let (s, c) = psi.to_radians().sin_cos();
    let d = [c, -s];
    let up = [s, c];
    let p = |t: f64, n: f64| [t * d[0] + n * up[0], t * d[1] + n * up[1]];
    let slope = Polygon::new(vec![p(0.0, -10.0), p(length, -10.0), p(length, 0.0), p(0.0, 0.0)]);
    let block = Polygon::new(vec![p(at, 0.0), p(at + b, 0.0), p(at + b, h), p(at, h)]);
    Model::new(ModelSpec { blocks: vec![block], supports: vec![slope], base: false, density: 2000.0, gravity: 10.0, joints: JointLaws::uniform(law(phi)), ..ModelSpec::default() }).unwrap()
}

fn run(model: &Model, duration: f64, update: bool) -> TimeHistory {
    let opts = DynamicOptions { duration, record: Recording::Interval(0.01), contact_update: update, ..DynamicOptions::default() };
    simulate(model, &opts).unwrap()
}

/// The block's displacement along the slope (down positive) at each record.
fn along(h: &TimeHistory, psi: f64) -> Vec<f64> {
    let (s, c) = psi.to_radians().sin_cos();
    (0..h.times.len()).map(|k| h.displacement(k)[0][0] * c - h.displacement(k)[0][1] * s).collect()
}

#[test]
fn the_sliding_block_slides_with_the_closed_form_acceleration_its_contact_following_it() {
    let (psi, phi) = (40.0f64, 20.0f64);
    let model = on_slope(10.0, 5.0, psi, phi, 60.0, 2.0);
    let h = run(&model, 3.5, true);
    assert_eq!(h.status, masonry_dem::results::Status::Completed, "{:?}", h.error);
    let want = 10.0 * (psi.to_radians().sin() - phi.to_radians().tan() * psi.to_radians().cos());
    // the acceleration: a quadratic fitted by least squares to the slide from 0.5 s on
    let s = along(&h, psi);
    let pts: Vec<(f64, f64)> = h.times.iter().zip(&s).filter(|(t, _)| **t >= 0.5).map(|(t, s)| (*t, *s)).collect();
    let a = quadratic(&pts)[2] * 2.0;
    eprintln!("acceleration {a} against {want}, slid {} m, searches {}, renewed {}, created {}, dropped {}", s[s.len() - 1], h.contact_searches, h.contacts_renewed, h.contacts_created, h.contacts_dropped);
    assert!((a / want - 1.0).abs() < 0.01, "{a} against {want}");
    assert!(s[s.len() - 1] > 2.0 * 10.0, "slid {} m", s[s.len() - 1]);
    // its one contact, on the slope, under the block's bottom edge's centre
    let u = h.displacement(h.times.len() - 1)[0];
    let (sn, cs) = psi.to_radians().sin_cos();
    let bottom = [(2.0 + 5.0) * cs + u[0], -(2.0 + 5.0) * sn + u[1]];
    assert_eq!(h.contacts.len(), 1, "{:?}", h.contacts);
    let c = h.contacts[0].centre;
    assert!((c[0] - bottom[0]).hypot(c[1] - bottom[1]) < 0.1, "{c:?} against {bottom:?}");
    assert!((h.contacts[0].length - 10.0).abs() < 0.1);
}

/// The coefficients (c0, c1, c2) of the least-squares quadratic through `pts`.
fn quadratic(pts: &[(f64, f64)]) -> [f64; 3] {
    let mut m = [[0.0; 4]; 3];
    for &(t, y) in pts {
        let p = [1.0, t, t * t];
        for i in 0..3 {
            for j in 0..3 {
                m[i][j] += p[i] * p[j];
            }
            m[i][3] += p[i] * y;
        }
    }
    for i in 0..3 {
        for r in 0..3 {
            if r != i {
                let f = m[r][i] / m[i][i];
                for j in 0..4 {
                    m[r][j] -= f * m[i][j];
                }
            }
        }
    }
    [m[0][3] / m[0][0], m[1][3] / m[1][1], m[2][3] / m[2][2]]
}
