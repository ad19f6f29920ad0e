//! Modal analysis (src/modal.rs) against closed forms: one block on its base (the vertical mode,
//! and the sliding-rocking pair of a 2 x 2 generalized eigenproblem written by hand), stacks of
//! equal blocks (the vertical modes of a chain of springs), the shapes' mass-orthonormality,
//! and Rayleigh damping. Tolerance: 0.5% (the target) on every frequency.

mod common;
use common::*;
use masonry_dem::geometry::{polygons, running_bond, FirstCourse, Rect, RunningBond};
use masonry_dem::joint::JointLaw;
use masonry_dem::modal::{modes, rayleigh_coefficients, Modes};
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::Error;
use std::f64::consts::PI;

const REL: f64 = 0.005;
const KN: f64 = 1e10;
const KT: f64 = 4e9;
const THICKNESS: f64 = 1.0;
const DENSITY: f64 = 1000.0;

fn law() -> JointLaw {
    JointLaw { normal_stiffness: KN, shear_stiffness: KT, ..JointLaw::default() }
}

/// Blocks b x h stacked `count` high on a fixed base.
fn stack(b: f64, h: f64, count: usize) -> Model {
    let blocks = (0..count).map(|k| Rect::new(0.0, k as f64 * h, b, (k + 1) as f64 * h)).map(Into::into).collect();
    Model::new(ModelSpec { blocks, thickness: THICKNESS, density: DENSITY, joints: JointLaws::uniform(law()), ..ModelSpec::default() }).unwrap()
}

/// The modes whose shapes lie along dof `dof` (0: u1, 1: u2, 2: phi) of the blocks: more than
/// 99.9% of `phi^T M phi` on that dof, in the order of their frequencies.
fn modes_along(m: &Modes, model: &Model, dof: usize) -> Vec<usize> {
    let share = |s: &[f64]| -> f64 {
        let mass = |g: usize| if g % 3 == 2 { model.inertia()[g / 3] } else { model.mass()[g / 3] };
        (0..s.len()).filter(|g| g % 3 == dof).map(|g| mass(g) * s[g] * s[g]).sum()
    };
    (0..m.shapes.len()).filter(|&k| share(&m.shapes[k]) > 0.999).collect()
}

fn check_orthonormal(m: &Modes, model: &Model) {
    let mass = |g: usize| if g % 3 == 2 { model.inertia()[g / 3] } else { model.mass()[g / 3] };
    for (i, a) in m.shapes.iter().enumerate() {
        for (j, b) in m.shapes.iter().enumerate() {
            let p: f64 = (0..a.len()).map(|g| a[g] * mass(g) * b[g]).sum();
            let want = if i == j { 1.0 } else { 0.0 };
            assert!((p - want).abs() < 1e-8, "phi_{i}^T M phi_{j} = {p:e}");
        }
    }
    for (k, r) in m.residuals.iter().enumerate() {
        assert!(*r < 1e-8, "residual of mode {k}: {r:e}");
    }
}

#[test]
fn one_block_on_its_base_matches_the_closed_form() {
    let (b, h) = (0.4, 1.0);
    let model = stack(b, h, 1);
    let m = modes(&model, 3, None).unwrap();
    let mass = DENSITY * b * h * THICKNESS;
    let inertia = mass * (b * b + h * h) / 12.0;
    let (area, second) = (b * THICKNESS, THICKNESS * b.powi(3) / 12.0);
    // vertical: the base joint's normal spring
    let vertical = (KN * area / mass).sqrt();
    // sliding and rocking, coupled through the lever arm h/2 of the shear at the base:
    // dT = u1 + phi h/2, dphi = phi; energy kT A dT^2 / 2 + kN I dphi^2 / 2
    let (k11, k12, k22) = (KT * area, KT * area * h / 2.0, KT * area * h * h / 4.0 + KN * second);
    let pair = eig2(k11, k12, k22, mass, inertia);
    let want = {
        let mut w = [pair[0].sqrt(), pair[1].sqrt(), vertical];
        w.sort_by(f64::total_cmp);
        w
    };
    for (k, &w) in want.iter().enumerate() {
        assert_close(m.angular[k], w, REL, &format!("omega_{k} [rad/s]"));
        assert_close(m.frequencies[k], w / (2.0 * PI), REL, &format!("f_{k} [Hz]"));
        eprintln!("one block, mode {k}: {:.6} rad/s against {w:.6}, relative error {:.2e}", m.angular[k], (m.angular[k] / w - 1.0).abs());
    }
    // the vertical one is the mode along u2
    let v = modes_along(&m, &model, 1);
    assert_eq!(v.len(), 1);
    assert_close(m.angular[v[0]], vertical, REL, "vertical omega [rad/s]");
    check_orthonormal(&m, &model);
    // three modes of three dofs: the effective masses add up to the block's mass
    let (mx, my): (f64, f64) = (m.effective_mass.iter().map(|e| e[0]).sum(), m.effective_mass.iter().map(|e| e[1]).sum());
    assert_close(mx, mass, 1e-9, "effective mass along x [kg]");
    assert_close(my, mass, 1e-9, "effective mass along y [kg]");
    // the base is fixed: zero in every shape
    let base = model.base().unwrap();
    assert!(m.shapes.iter().all(|s| s[3 * base..3 * base + 3] == [0.0; 3]));
}

#[test]
fn two_stacked_blocks_vertical_modes_match_the_chain_of_springs() {
    let (b, h) = (0.4, 0.5);
    let model = stack(b, h, 2);
    let m = modes(&model, 6, None).unwrap();
    let (k, mass) = (KN * b * THICKNESS, DENSITY * b * h * THICKNESS);
    // K = k [[2, -1], [-1, 1]], M = m I
    let want = eig2(2.0 * k, -k, k, mass, mass).map(f64::sqrt);
    let v = modes_along(&m, &model, 1);
    assert_eq!(v.len(), 2, "two vertical modes among {:?}", m.angular);
    for (i, &mode) in v.iter().enumerate() {
        assert_close(m.angular[mode], want[i], REL, &format!("vertical omega_{i} [rad/s]"));
        eprintln!("two blocks, vertical mode {i}: relative error {:.2e}", (m.angular[mode] / want[i] - 1.0).abs());
    }
    check_orthonormal(&m, &model);
}

#[test]
fn three_stacked_blocks_vertical_modes_match_the_chain_of_springs() {
    let (b, h, count) = (0.4, 0.3, 3);
    let model = stack(b, h, count);
    let m = modes(&model, 9, None).unwrap();
    let (k, mass) = (KN * b * THICKNESS, DENSITY * b * h * THICKNESS);
    // a chain of N equal masses and springs, fixed at one end and free at the other:
    // omega_j = 2 sqrt(k/m) sin((2j - 1) pi / (2 (2N + 1)))
    let v = modes_along(&m, &model, 1);
    assert_eq!(v.len(), count);
    for (i, &mode) in v.iter().enumerate() {
        let j = (i + 1) as f64;
        let want = 2.0 * (k / mass).sqrt() * ((2.0 * j - 1.0) * PI / (2.0 * (2.0 * count as f64 + 1.0))).sin();
        assert_close(m.angular[mode], want, REL, &format!("vertical omega_{i} [rad/s]"));
        eprintln!("three blocks, vertical mode {i}: relative error {:.2e}", (m.angular[mode] / want - 1.0).abs());
    }
    check_orthonormal(&m, &model);
}

/// A running-bond wall of `courses` courses, `length` m long, on its base.
fn wall(courses: usize, length: f64) -> Model {
    let blocks = running_bond(&RunningBond {
        block_length: 0.4,
        block_height: 0.175,
        courses,
        height: None,
        length,
        first_course: FirstCourse::Half,
        openings: vec![],
    })
    .unwrap();
    Model::new(ModelSpec { blocks: polygons(blocks), joints: JointLaws::uniform(law()), ..ModelSpec::default() }).unwrap()
}

#[test]
fn the_lowest_modes_of_a_wall_are_those_of_the_whole_spectrum() {
    // 6 courses of 2 m: 33 blocks, 99 free dofs; every mode (the basis spans every dof) against
    // the lowest 8 alone
    let model = wall(6, 2.0);
    let nf = model.fixed().iter().filter(|f| !**f).count();
    let all = modes(&model, nf, None).unwrap();
    let low = modes(&model, 8, None).unwrap();
    assert!(low.basis < nf, "the 8 lowest modes took the whole space ({} vectors)", low.basis);
    for k in 0..8 {
        assert_close(low.angular[k], all.angular[k], 1e-10, &format!("omega_{k} [rad/s]"));
    }
    check_orthonormal(&low, &model);
    assert!(all.angular.windows(2).all(|w| w[0] <= w[1]));
    // the effective masses over every mode add up to the wall's mass
    let wall_mass: f64 = model.mass()[..model.n_wall()].iter().sum();
    let mx: f64 = all.effective_mass.iter().map(|e| e[0]).sum();
    assert_close(mx, wall_mass, 1e-8, "sum of the effective masses along x [kg]");
    assert_close(all.free_mass[0], wall_mass, 1e-12, "mass free along x [kg]");
    assert_close(all.free_mass[1], wall_mass, 1e-12, "mass free along y [kg]");
    // a shift between modes 3 and 4 finds the 4 modes nearest it
    let sigma = 0.5 * (all.eigenvalues[3] + all.eigenvalues[4]);
    let near = modes(&model, 4, Some(sigma)).unwrap();
    let mut nearest = all.eigenvalues.clone();
    nearest.sort_by(|a, b| (a - sigma).abs().total_cmp(&(b - sigma).abs()));
    nearest.truncate(4);
    nearest.sort_by(f64::total_cmp);
    for (k, l) in near.eigenvalues.iter().enumerate() {
        assert_close(*l, nearest[k], 1e-10, &format!("omega^2 {k} near the shift [rad2/s2]"));
    }
    assert!(near.residuals.iter().all(|r| *r < 1e-8), "{:?}", near.residuals);
}

#[test]
fn two_identical_piers_give_each_frequency_twice() {
    // two separate piers of 8 stacked blocks on one base: every frequency is double; the 6
    // lowest from a basis smaller than the 48 dofs
    let pier = |x: f64| (0..8).map(move |k| Rect::new(x, 0.25 * k as f64, x + 0.4, 0.25 * (k + 1) as f64));
    let blocks = pier(0.0).chain(pier(1.0)).map(Into::into).collect();
    let model = Model::new(ModelSpec { blocks, joints: JointLaws::uniform(law()), ..ModelSpec::default() }).unwrap();
    let m = modes(&model, 6, None).unwrap();
    assert!(m.basis < 48, "basis {}", m.basis);
    for k in 0..3 {
        assert_close(m.angular[2 * k + 1], m.angular[2 * k], 1e-10, &format!("the pair of frequencies {k} [rad/s]"));
    }
    check_orthonormal(&m, &model);
}

#[test]
fn a_free_floating_pair_has_three_rigid_modes_and_the_relative_vertical_one() {
    // two blocks stacked, no base and no support: K is singular (3 rigid-body modes); the
    // default shift, slightly negative, keeps K - shift M positive definite
    let (b, h) = (0.4, 0.5);
    let blocks = vec![Rect::new(0.0, 0.0, b, h), Rect::new(0.0, h, b, 2.0 * h)];
    let model = Model::new(ModelSpec { blocks: polygons(blocks), base: false, joints: JointLaws::uniform(law()), ..ModelSpec::default() }).unwrap();
    let m = modes(&model, 6, None).unwrap();
    for k in 0..3 {
        assert!(m.angular[k] < 1e-4 * m.angular[3], "rigid mode {k}: omega = {:e} rad/s", m.angular[k]);
    }
    // the blocks moving apart vertically: omega^2 = k (1/m + 1/m)
    let (k, mass) = (KN * b * THICKNESS, DENSITY * b * h * THICKNESS);
    let v = modes_along(&m, &model, 1);
    let relative: Vec<usize> = v.into_iter().filter(|&i| i >= 3).collect();
    assert_eq!(relative.len(), 1, "{:?}", m.angular);
    assert_close(m.angular[relative[0]], (2.0 * k / mass).sqrt(), REL, "relative vertical omega [rad/s]");
    check_orthonormal(&m, &model);
}

#[test]
fn a_large_wall_converges() {
    // about 10,000 blocks: 100 courses of 40 m
    let model = wall(100, 40.0);
    let start = std::time::Instant::now();
    let m = modes(&model, 10, None).unwrap();
    let t = start.elapsed().as_secs_f64();
    eprintln!(
        "{} blocks, {} free dofs: 10 modes in {t:.3} s (basis {}), f = {:.3?} Hz, largest residual {:.1e}",
        model.n_wall(),
        3 * model.n_wall(),
        m.basis,
        m.frequencies,
        m.residuals.iter().copied().fold(0.0, f64::max)
    );
    check_orthonormal(&m, &model);
    assert!(m.frequencies.windows(2).all(|w| w[0] <= w[1]));
}

#[test]
fn bad_input_is_refused() {
    let model = stack(0.4, 1.0, 1);
    for (n, shift) in [(0, None), (4, None), (1, Some(f64::NAN))] {
        let e = modes(&model, n, shift).unwrap_err();
        assert!(matches!(e, Error::Input { .. }), "n = {n}, shift = {shift:?}: {e}");
    }
    // every dof fixed
    let mut fixed = model.clone();
    for dof in 0..3 {
        fixed.fix(0, dof, 0.0).unwrap();
    }
    assert!(matches!(modes(&fixed, 1, None), Err(Error::Input { .. })));
}

#[test]
fn rayleigh_coefficients_reproduce_the_two_ratios() {
    for (w1, w2, z1, z2) in [(10.0, 50.0, 0.05, 0.05), (3.0, 40.0, 0.02, 0.04), (80.0, 5.0, 0.03, 0.02)] {
        let (alpha, beta) = rayleigh_coefficients(w1, w2, z1, z2).unwrap();
        let zeta = |w: f64| alpha / (2.0 * w) + beta * w / 2.0;
        assert_close(zeta(w1), z1, 1e-12, "zeta at omega1");
        assert_close(zeta(w2), z2, 1e-12, "zeta at omega2");
    }
    for (w1, w2, z1, z2) in [
        (10.0, 10.0, 0.05, 0.05),
        (0.0, 10.0, 0.05, 0.05),
        (-1.0, 10.0, 0.05, 0.05),
        (f64::INFINITY, 10.0, 0.05, 0.05),
        (1.0, f64::NAN, 0.05, 0.05),
        (1.0, 10.0, -0.05, 0.05),
        (1.0, 10.0, 0.05, f64::NAN),
        (1.0, 10.0, 0.05, 0.001),
    ] {
        assert!(matches!(rayleigh_coefficients(w1, w2, z1, z2), Err(Error::Input { .. })), "{w1} {w2} {z1} {z2}");
    }
}
