//! The return mapping alone: the result lies in the domain, the plastic step is normal to the
//! domain in the D-metric when psi = phi (closest point), the tangent matches finite
//! differences, and a joint that failed has lost its cohesion and tensile strength.

// matrices are written with their indices, as in the formulas
#![allow(clippy::needless_range_loop)]

use masonry_dem::joint::{
    MapOptions, admissible, return_map, JointLaw, JointState, Section, OPEN, ROCKING, SLIDING,
};

fn laws() -> Vec<JointLaw> {
    let dry_assoc = JointLaw {
        normal_stiffness: 1e9,
        shear_stiffness: 4e8,
        friction: 0.65,
        dilatancy: 0.65,
        ..Default::default()
    };
    let dry_nonassoc = JointLaw {
        dilatancy: 0.0,
        ..dry_assoc
    };
    let mortar = JointLaw {
        cohesion: 0.35e6,
        tensile_strength: 0.25e6,
        friction: 0.75,
        dilatancy: 0.0,
        ..dry_assoc
    };
    let mortar_assoc = JointLaw {
        dilatancy: 0.75,
        ..mortar
    };
    vec![dry_assoc, dry_nonassoc, mortar, mortar_assoc]
}

/// A deterministic spread of trial jumps over every region (elastic, faces, edges, apex).
fn jumps() -> Vec<[f64; 3]> {
    let mut out = vec![];
    let mut s: u64 = 12345;
    let mut rnd = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    for _ in 0..4000 {
        let scale = 10f64.powf(-7.0 + 3.0 * rnd().abs());
        out.push([scale * rnd(), scale * rnd(), scale * 10.0 * rnd()]);
    }
    out
}

/// |N| + |T| + 2|M|/l of the elastic trial force of jumps e.
fn trial_size(law: &JointLaw, e: &[f64; 3]) -> f64 {
    (law.normal_stiffness * SEC.area * e[0]).abs()
        + (law.shear_stiffness * SEC.area * e[1]).abs()
        + (law.normal_stiffness * SEC.inertia * e[2] * 2.0 / SEC.length).abs()
}

const SEC: Section = Section {
    area: 0.4 * 0.1,
    inertia: 0.1 * 0.4 * 0.4 * 0.4 / 12.0,
    length: 0.4,
};

#[test]
fn result_lies_in_the_domain() {
    for law in laws() {
        for e in jumps() {
            let r = return_map(&law, &SEC, e, &JointState::default(), &MapOptions::default()).0;
            // round-off is measured against the size of the trial force
            let tol = 1e-12 * trial_size(&law, &e);
            assert!(
                admissible(&law, &SEC, &r.force, &r.state, tol),
                "{law:?} e={e:?} -> {:?}",
                r.force
            );
        }
    }
}

#[test]
fn associative_return_is_the_closest_point_in_the_d_metric() {
    // closest point: for every admissible point y, (trial - s)^T D^-1 (y - s) <= 0
    for law in [laws()[0], laws()[3]] {
        let d = [
            law.normal_stiffness * SEC.area,
            law.shear_stiffness * SEC.area,
            law.normal_stiffness * SEC.inertia,
        ];
        let probes: Vec<[f64; 3]> = jumps()
            .iter()
            .map(|e| return_map(&law, &SEC, *e, &JointState::default(), &MapOptions::default()).0.force)
            .collect();
        for e in jumps().iter().take(600) {
            let r = return_map(&law, &SEC, *e, &JointState::default(), &MapOptions::default()).0;
            if r.state.broken {
                continue; // a broken mortar joint projects on the dry domain, checked below
            }
            let trial = [d[0] * e[0], d[1] * e[1], d[2] * e[2]];
            let s = r.force;
            let g = [
                (trial[0] - s[0]) / d[0],
                (trial[1] - s[1]) / d[1],
                (trial[2] - s[2]) / d[2],
            ];
            let gn = (g[0] * g[0] * d[0] + g[1] * g[1] * d[1] + g[2] * g[2] * d[2]).sqrt();
            for y in &probes {
                let v = g[0] * (y[0] - s[0]) + g[1] * (y[1] - s[1]) + g[2] * (y[2] - s[2]);
                let yn = ((y[0] - s[0]).powi(2) / d[0]
                    + (y[1] - s[1]).powi(2) / d[1]
                    + (y[2] - s[2]).powi(2) / d[2])
                    .sqrt();
                // the probes are themselves returned forces: allow them 1e-9 N of round-off
                let noise = 1e-9 * (g[0].abs() + g[1].abs() + g[2].abs() * 2.0 / SEC.length);
                assert!(
                    v <= 1e-7 * gn * yn + noise,
                    "not the closest point: e={e:?} s={s:?} y={y:?} v={v:e}"
                );
            }
        }
    }
}

#[test]
fn tangent_matches_finite_differences() {
    let mut checked = 0;
    for law in laws() {
        for e in jumps().iter().take(1500) {
            let r = return_map(&law, &SEC, *e, &JointState::default(), &MapOptions::default()).0;
            let size = e.iter().map(|x| x.abs()).fold(0.0, f64::max);
            let h = 1e-7 * size;
            let mut fd = [[0.0; 3]; 3];
            let mut same_set = true;
            for j in 0..3 {
                let (mut ep, mut em) = (*e, *e);
                ep[j] += h;
                em[j] -= h;
                let rp = return_map(&law, &SEC, ep, &JointState::default(), &MapOptions::default()).0;
                let rm = return_map(&law, &SEC, em, &JointState::default(), &MapOptions::default()).0;
                same_set &= rp.flags == r.flags
                    && rm.flags == r.flags
                    && rp.state.broken == r.state.broken
                    && rm.state.broken == r.state.broken;
                for i in 0..3 {
                    fd[i][j] = (rp.force[i] - rm.force[i]) / (2.0 * h);
                }
            }
            if !same_set {
                continue; // on a boundary between active sets the tangent is one-sided
            }
            let kmax = law.normal_stiffness * SEC.area;
            for i in 0..3 {
                for j in 0..3 {
                    let scale = kmax
                        * if i == 2 || j == 2 { SEC.length } else { 1.0 }
                        * if i == 2 && j == 2 { SEC.length } else { 1.0 };
                    assert!(
                        (fd[i][j] - r.tangent[i][j]).abs() <= 1e-5 * scale,
                        "tangent [{i}][{j}] = {:e}, finite difference {:e} ({law:?}, e={e:?}, flags {})",
                        r.tangent[i][j],
                        fd[i][j],
                        r.flags
                    );
                }
            }
            checked += 1;
        }
    }
    assert!(checked > 2000, "only {checked} points checked");
}

#[test]
fn trial_in_tension_with_large_slip_returns_to_the_coulomb_face_with_dilatancy() {
    // DESIGN.md: with dilatancy, a tensile trial state with a large slip lands on the Coulomb
    // face in compression, not on the apex
    let law = laws()[0];
    let r = return_map(&law, &SEC, [1e-7, 1e-4, 0.0], &JointState::default(), &MapOptions::default()).0;
    assert!(r.force[0] < 0.0, "N = {} should be compressive", r.force[0]);
    assert!((r.force[1].abs() + law.friction * r.force[0]).abs() < 1e-9 * r.force[1].abs());
    assert_eq!(r.flags & SLIDING, SLIDING);
}

#[test]
fn pure_opening_is_open_and_carries_nothing() {
    let law = laws()[1];
    let r = return_map(&law, &SEC, [1e-5, 0.0, 0.0], &JointState::default(), &MapOptions::default()).0;
    assert_eq!(r.flags, OPEN);
    assert!(r.force.iter().all(|f| f.abs() < 1e-9));
}

/// A joint without strength (dry, or mortar that has failed) opened and slid at once returns to
/// the apex of its domain, where it carries nothing: its force is zero but for rounding. The crack
/// pattern must show it open, whatever the sign of that rounding.
#[test]
fn a_joint_that_carries_nothing_is_open() {
    let broken = JointState { broken: true, ..JointState::default() };
    let laws = laws();
    let cases = [(laws[0], JointState::default()), (laws[1], JointState::default()), (laws[2], broken), (laws[3], broken)];
    // opened by 10 um and slid by 10 um: no dilatancy closes that gap
    let r = return_map(&laws[1], &SEC, [1e-5, 1e-5, 0.0], &JointState::default(), &MapOptions::default()).0;
    assert!(r.force.iter().all(|f| f.abs() < 1e-9), "force {:?}", r.force);
    assert_eq!(r.flags, OPEN, "force {:?}", r.force);
    for (law, state) in &cases {
        let mut nothing = 0;
        for e in jumps() {
            let r = return_map(law, &SEC, e, state, &MapOptions::default()).0;
            let size = trial_size(law, &e);
            let carried = r.force[0].abs() + r.force[1].abs() + (r.force[2] * 2.0 / SEC.length).abs();
            if carried <= 1e-12 * size {
                nothing += 1;
                assert_eq!(r.flags, OPEN, "{law:?} e {e:?}: force {:?} of a trial of {size:e} N", r.force);
            }
        }
        println!("{nothing} of {} trials carried nothing", jumps().len());
        // a count, so that the test cannot pass empty
        assert!(nothing >= 100, "only {nothing} of the trials carried nothing ({law:?})");
    }
}

#[test]
fn rotation_under_compression_rocks_at_the_edge() {
    let law = laws()[1];
    // N = kN A dN = -4e4 N; the moment limit is |N| l / 2 = 8e3 N m
    let r = return_map(&law, &SEC, [-1e-6, 0.0, 1e-3], &JointState::default(), &MapOptions::default()).0;
    assert_eq!(r.flags & ROCKING, ROCKING);
    assert!(
        (r.force[2].abs() - r.force[0].abs() * SEC.length / 2.0).abs() < 1e-9 * r.force[2].abs()
    );
}

#[test]
fn unloading_from_a_plastic_state_is_elastic() {
    let law = laws()[1];
    let e1 = [-1e-6, 1e-5, 0.0];
    let r1 = return_map(&law, &SEC, e1, &JointState::default(), &MapOptions::default()).0;
    assert_ne!(r1.flags & SLIDING, 0);
    // back by 1e-7 m of slip (N = -40 N, T = 26 N: T drops by 1.6 N, 6%, beyond the 0.1%
    // within which a face counts as reached, and short of sliding back)
    let e2 = [-1e-6, 1e-5 - 1e-7, 0.0];
    let r2 = return_map(&law, &SEC, e2, &r1.state, &MapOptions::default()).0;
    assert_eq!(r2.flags, 0, "unloading must be elastic");
    assert_eq!(r2.state.plastic, r1.state.plastic);
    let k = law.shear_stiffness * SEC.area;
    assert!((r2.force[1] - (r1.force[1] - k * 1e-7)).abs() < 1e-9 * r1.force[1].abs());
}

#[test]
fn a_failed_mortar_joint_has_lost_cohesion_and_tensile_strength() {
    let law = laws()[2];
    // intact: a small tension below ft A is carried elastically
    let small = 0.5 * law.tensile_strength / law.normal_stiffness;
    let r0 = return_map(&law, &SEC, [small, 0.0, 0.0], &JointState::default(), &MapOptions::default()).0;
    assert!(!r0.state.broken && r0.flags == 0 && r0.force[0] > 0.0);
    // fail it in shear
    let r1 = return_map(&law, &SEC, [0.0, 1e-2, 0.0], &JointState::default(), &MapOptions::default()).0;
    assert!(r1.state.broken);
    assert!(
        r1.force[1].abs() < 1e-9 * law.cohesion * SEC.area,
        "no cohesion left: T = {}",
        r1.force[1]
    );
    // the same small tension is no longer carried
    let e = [r1.state.plastic[0] + small, r1.state.plastic[1], 0.0];
    let r2 = return_map(&law, &SEC, e, &r1.state, &MapOptions::default()).0;
    assert!(
        r2.force[0] <= 1e-9 && r2.flags == OPEN,
        "broken joint carried N = {}",
        r2.force[0]
    );
}

/// A softening joint driven in small committed increments (as the explicit solver does): the
/// work beyond friction over a long slip is the mode-II fracture energy times the area, and the
/// work of the tension over a long opening the mode-I energy times the area.
#[test]
fn softening_dissipates_the_fracture_energies() {
    let (gf1, gf2) = (18.0, 125.0); // N/m (J4D's mortar)
    let law = JointLaw {
        normal_stiffness: 82e9,
        shear_stiffness: 36e9,
        friction: 0.75,
        cohesion: 0.35e6,
        tensile_strength: 0.25e6,
        dilatancy: 0.0,
        fracture_energy_tension: gf1,
        fracture_energy_shear: gf2,
        ..JointLaw::default()
    };
    let a = SEC.area;
    // mode II: slip under a fixed compression of 10 kN
    let en = -1e4 / (law.normal_stiffness * a);
    let mut st = JointState::default();
    let (mut work, mut last_slip) = (0.0, 0.0);
    let n = 20_000;
    for k in 1..=n {
        let e = [en, 2e-2 * k as f64 / n as f64, 0.0];
        let r = return_map(&law, &SEC, e, &st, &MapOptions::default()).0;
        let ds = r.state.slip - last_slip;
        work += (r.force[1].abs() - law.friction * r.force[0].abs()) * ds;
        last_slip = r.state.slip;
        st = r.state;
    }
    assert_close(work, gf2 * a, 0.01, "mode II work beyond friction [J]");
    assert!(st.broken || law.strengths(&st).0 < 1e-3 * law.cohesion);
    // mode I: pure opening
    let mut st = JointState::default();
    let (mut work, mut last_open) = (0.0, 0.0);
    for k in 1..=n {
        let e = [2e-3 * k as f64 / n as f64, 0.0, 0.0];
        let r = return_map(&law, &SEC, e, &st, &MapOptions::default()).0;
        work += r.force[0] * (r.state.opening - last_open);
        last_open = r.state.opening;
        st = r.state;
    }
    assert_close(work, gf1 * a, 0.01, "mode I work [J]");
}

/// |got - want| <= rel * |want|
fn assert_close(got: f64, want: f64, rel: f64, what: &str) {
    assert!((got - want).abs() <= rel * want.abs(), "{what}: got {got:.6e}, expected {want:.6e}");
}
