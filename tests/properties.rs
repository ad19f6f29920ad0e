//! Property tests: invariants of the joint law and of the solvers on
//! random inputs drawn by proptest.
//!
//! - the return mapping stays in the strength domain, its consistent tangent matches central
//!   finite differences, and unloading from a sliding state is elastic;
//! - every converged static step is in equilibrium (free dof) and the support reactions
//!   balance the applied loads;
//! - the same input gives bitwise the same output (static, and explicit on one thread);
//! - translating a wall changes nothing; mirroring a wall and its push gives the mirrored curve
//!   (both with associative joints: with psi = 0 the path is not unique and follows round-off).
//!
//! Case counts are kept small enough for `make test` (the whole file runs in well under a
//! minute in release mode); failures are shrunk by proptest and printed with the minimal input.

// matrices are written with their indices, as in the formulas
#![allow(clippy::needless_range_loop)]

mod common;

use masonry_dem::explicit::{self, ExplicitOptions};
use masonry_dem::geometry::{polygons, running_bond, FirstCourse, Rect, RunningBond};
use masonry_dem::joint::{admissible, return_map, JointLaw, MapOptions, JointState, Section, SLIDING};
use masonry_dem::model::{JointLaws, Model, ModelSpec, TopBeam};
use masonry_dem::results::{Results, Status};
use masonry_dem::limit::{limit_analysis, LimitOptions};
use masonry_dem::static_solver::{solve, solve_with, Control, StaticOptions, COLLAPSE_EVIDENCE};
use proptest::prelude::*;
use proptest::test_runner::{Config, TestCaseError, TestRunner};
use std::cell::Cell;

// ---------------------------------------------------------------------------------------------
// random inputs
// ---------------------------------------------------------------------------------------------

/// exp of a uniform draw: a positive value spread evenly over decades.
fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> + Clone {
    (lo.ln()..hi.ln()).prop_map(f64::exp)
}

/// Joint laws of every kind the crate accepts: dry, brittle mortar (c and ft lost at the first
/// failure) and softening mortar (both fracture energies > 0); non-associative (psi = 0),
/// associative (psi = phi) or in between; kT / kN from 0.05 to 2.
fn law_strategy() -> impl Strategy<Value = JointLaw> {
    (
        log_uniform(1e8, 1e11),
        log_uniform(0.05, 2.0),
        0.2f64..1.2,
        0u8..3,
        0.0f64..1.0,
        0u8..3,
        log_uniform(0.02e6, 2e6),
        log_uniform(0.02e6, 1e6),
        log_uniform(1.0, 500.0),
        log_uniform(10.0, 2000.0),
    )
        .prop_map(|(kn, ratio, mu, dil_kind, dil_frac, kind, c, ft, gf1, gf2)| {
            let dilatancy = match dil_kind {
                0 => 0.0,
                1 => mu,
                _ => dil_frac * mu,
            };
            let (cohesion, tensile_strength, gf1, gf2) = match kind {
                0 => (0.0, 0.0, 0.0, 0.0),
                1 => (c, ft, 0.0, 0.0),
                _ => (c, ft, gf1, gf2),
            };
            JointLaw {
                normal_stiffness: kn,
                shear_stiffness: ratio * kn,
                friction: mu,
                cohesion,
                tensile_strength,
                dilatancy,
                fracture_energy_tension: gf1,
                fracture_energy_shear: gf2,
                ..JointLaw::default()
            }
        })
}

fn section_strategy() -> impl Strategy<Value = Section> {
    (log_uniform(0.02, 1.5), log_uniform(0.05, 0.6)).prop_map(|(l, s)| Section::new(l, s))
}

/// Jump scales of a law and section: the jumps (dN, dT, dphi) that give a stress of 0.5 MPa
/// (or the joint's strength if larger) at the centre, resp. at the edges for dphi.
fn jump_scale(law: &JointLaw, sec: &Section) -> [f64; 3] {
    let sigma = 0.5e6f64.max(law.cohesion).max(law.tensile_strength);
    let en = sigma / law.normal_stiffness;
    [en, sigma / law.shear_stiffness, 2.0 * en / sec.length]
}

/// A jump component in units of the jump scale: random sign, magnitude spread over five decades
/// (deep inside the elastic range to far beyond the strength), or exactly zero.
fn unit_jump() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![
        1 => Just(0.0),
        8 => (any::<bool>(), -3.0f64..2.0).prop_map(|(neg, p)| if neg { -10f64.powf(p) } else { 10f64.powf(p) }),
    ]
}

fn jumps_strategy() -> impl Strategy<Value = [f64; 3]> {
    [unit_jump(), unit_jump(), unit_jump()]
}

/// A law, a section, a history reached by 0 to 3 committed random loadings (so that the
/// history is one the law can produce: a brittle joint with plastic slip is broken, a softening
/// joint has the opening and slip that its flow accumulated), and the trial jumps.
#[derive(Debug, Clone)]
struct JointCase {
    law: JointLaw,
    sec: Section,
    history: JointState,
    e: [f64; 3],
}

fn joint_case() -> impl Strategy<Value = JointCase> {
    (
        law_strategy(),
        section_strategy(),
        prop::collection::vec(jumps_strategy(), 0..4),
        jumps_strategy(),
    )
        .prop_map(|(law, sec, pre, e)| {
            let s = jump_scale(&law, &sec);
            let scaled = |u: [f64; 3]| [u[0] * s[0], u[1] * s[1], u[2] * s[2]];
            let mut history = JointState::default();
            for u in pre {
                history = return_map(&law, &sec, scaled(u), &history, &MapOptions::default()).0.state;
            }
            JointCase { law, sec, history, e: scaled(e) }
        })
}

fn elastic(law: &JointLaw, sec: &Section) -> [f64; 3] {
    [
        law.normal_stiffness * sec.area,
        law.shear_stiffness * sec.area,
        law.normal_stiffness * sec.inertia,
    ]
}

/// |N| + |T| + 2|M|/l of the elastic trial force plus the strengths c A + ft A: the size of the
/// numbers the return mapping works with.
fn force_size(case: &JointCase) -> f64 {
    let (law, sec, h, e) = (&case.law, &case.sec, &case.history, &case.e);
    let d = elastic(law, sec);
    (d[0] * (e[0] - h.plastic[0])).abs()
        + (d[1] * (e[1] - h.plastic[1])).abs()
        + (d[2] * (e[2] - h.plastic[2]) * 2.0 / sec.length).abs()
        + (law.cohesion + law.tensile_strength) * sec.area
}

fn runner(cases: u32) -> TestRunner {
    TestRunner::new(Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    })
}

/// Runs the property and panics with proptest's shrunk counterexample if it fails.
fn check<S: Strategy>(cases: u32, strategy: S, test: impl Fn(S::Value) -> Result<(), TestCaseError>)
where
    S::Value: std::fmt::Debug,
{
    if let Err(e) = runner(cases).run(&strategy, test) {
        panic!("{e}");
    }
}

// ---------------------------------------------------------------------------------------------
// a. the return mapping stays in the strength domain
// ---------------------------------------------------------------------------------------------

/// Round-off allowed on a face, relative to the size of the forces involved: the mapping solves
/// at most a 3 x 3 system `A D M dgamma = f(trial)` whose condition number grows with
/// kN / kT and mu (up to ~1e3 here); 1e3 times a few ulps of the trial force is below 1e-12 of
/// it, so 1e-10 leaves a margin of 100 and still catches any real violation (a missed face
/// or a wrong corner is off by a finite fraction of the force).
const DOMAIN_TOL: f64 = 1e-10;

#[test]
fn a_return_map_stays_in_the_strength_domain() {
    check(20_000, joint_case(), |case| {
        let JointCase { law, sec, history, e } = case;
        let r = return_map(&law, &sec, e, &history, &MapOptions::default()).0;
        prop_assert!(r.force.iter().all(|f| f.is_finite()), "non-finite force {:?}", r.force);
        // The domain of this step: after a brittle failure the dry domain (r.state is broken);
        // for softening joints the strengths of the committed history, which by design
        // (joint.rs) hold within a step.
        let domain_state = if law.is_softening() { history } else { r.state };
        let tol = DOMAIN_TOL * force_size(&case);
        prop_assert!(
            admissible(&law, &sec, &r.force, &domain_state, tol),
            "force {:?} outside the domain (flags {}, state {:?})",
            r.force,
            r.flags,
            r.state
        );
        // strengths never grow back
        let (c0, f0) = law.strengths(&history);
        let (c1, f1) = law.strengths(&r.state);
        prop_assert!(c1 <= c0 && f1 <= f0, "strengths grew: ({c0}, {f0}) -> ({c1}, {f1})");
        // the accumulated slip and largest opening never decrease
        prop_assert!(r.state.slip >= history.slip && r.state.opening >= history.opening);
        Ok(())
    });
}

// ---------------------------------------------------------------------------------------------
// b. the consistent tangent matches central finite differences
// ---------------------------------------------------------------------------------------------

/// Within a step the strengths are fixed and the faces are planes, so the mapping is piecewise
/// linear in the jumps, with kinks where the active set changes (and jumps where a brittle joint
/// fails). Detection of a change of active set near e: along each jump direction j the
/// one-sided differences over h and over 10 h, forward and backward, must agree; if any of the
/// four differs, a kink (or a jump) lies within 10 h of e and the sample is skipped. On a
/// linear stretch all four differences and the central one are exact up to round-off, some
/// ulps of |F| over h: h is 1e-7 of the jump's size, which counts the jump that a force of the
/// size of |F| would take in that direction (an open joint's force is its trial's, millions of
/// newtons, returned to zero up to 1e-7 N, whose sign can flip with a rotation of 1e-10: over
/// an h of that rotation's own scale, 1e-10, that would read as a slope), so round-off stays
/// ~1e-8 of the stiffness. The comparison with the tangent uses 1e-6 of the largest elastic
/// stiffness (in the units of the entry), far above round-off and far below any error of the
/// tangent formula (a wrong active set or a wrong term is off by O(1)).
const FD_TOL: f64 = 1e-6;

#[test]
fn b_tangent_matches_central_finite_differences() {
    let checked = Cell::new(0usize);
    let plastic = Cell::new(0usize);
    let skipped = Cell::new(0usize);
    check(6_000, joint_case(), |case| {
        let size = force_size(&case);
        let JointCase { law, sec, history, e } = case;
        let (r, set) = return_map(&law, &sec, e, &history, &MapOptions::default());
        let d = elastic(&law, &sec);
        let s = jump_scale(&law, &sec);
        let f = |x: [f64; 3]| {
            let (r, set) = return_map(&law, &sec, x, &history, &MapOptions::default());
            (r.force, set)
        };
        let mut fd = [[0.0; 3]; 3];
        // the jump a force of the case's size takes in each direction (a moment of |F| l / 2)
        let reach = [size / d[0], size / d[1], size * sec.length / (2.0 * d[2])];
        for j in 0..3 {
            let h = 1e-7 * (e[j].abs() + history.plastic[j].abs() + s[j] + reach[j]);
            let at = |t: f64| {
                let mut x = e;
                x[j] += t;
                f(x)
            };
            let ((p1, s1), (m1, s2), (p10, s3), (m10, s4)) = (at(h), at(-h), at(10.0 * h), at(-10.0 * h));
            // another active set within 10 h (the return's own answer): the tangent at e is
            // that of its set, which may hold in a band narrower than h (a strength of 1e-5 N
            // left by softening gives an elastic band of 1e-12 rad about a zero rotation)
            if [s1, s2, s3, s4].iter().any(|&x| x != set) {
                skipped.set(skipped.get() + 1);
                return Ok(());
            }
            for i in 0..3 {
                let scale = entry_scale(&d, &sec, i, j);
                let one_sided = [
                    (p1[i] - r.force[i]) / h,
                    (r.force[i] - m1[i]) / h,
                    (p10[i] - r.force[i]) / (10.0 * h),
                    (r.force[i] - m10[i]) / (10.0 * h),
                ];
                if one_sided.iter().any(|v| (v - one_sided[0]).abs() > FD_TOL * scale) {
                    skipped.set(skipped.get() + 1);
                    return Ok(()); // a change of active set within 10 h: the tangent is one-sided
                }
                fd[i][j] = (p1[i] - m1[i]) / (2.0 * h);
            }
        }
        for i in 0..3 {
            for j in 0..3 {
                let scale = entry_scale(&d, &sec, i, j);
                prop_assert!(
                    (fd[i][j] - r.tangent[i][j]).abs() <= FD_TOL * scale,
                    "tangent[{i}][{j}] = {:e}, finite difference {:e} (flags {})",
                    r.tangent[i][j],
                    fd[i][j],
                    r.flags
                );
            }
        }
        checked.set(checked.get() + 1);
        if r.flags != 0 {
            plastic.set(plastic.get() + 1);
        }
        Ok(())
    });
    let (c, p, s) = (checked.get(), plastic.get(), skipped.get());
    eprintln!("tangent: {c} samples checked ({p} at a face), {s} skipped near a change of active set");
    // a property that skips most of its samples proves nothing: demand real coverage
    assert!(s * 10 <= c + s, "{s} of {} samples skipped", c + s);
    assert!(p * 5 >= c, "only {p} of {c} checked samples were plastic");
}

/// Size of tangent entry (i, j): the largest elastic stiffness kmax A, times l for an entry
/// linking a force to a rotation or a moment to a jump, and l^2 for moment / rotation.
fn entry_scale(d: &[f64; 3], sec: &Section, i: usize, j: usize) -> f64 {
    let kmax = d[0].max(d[1]);
    kmax * if i == 2 { sec.length } else { 1.0 } * if j == 2 { sec.length } else { 1.0 }
}

// ---------------------------------------------------------------------------------------------
// c. unloading from a plastic (sliding) state is elastic
// ---------------------------------------------------------------------------------------------

/// After a step that slid (only a Coulomb face reached, history committed), a step back that
/// reduces |T|, adds compression and turns a little brings the elastic predictor inside the
/// domain: the force changes by exactly D times the jump increment and the history does not
/// change. (Rocking is excluded on purpose: by design an opening or a rocking gap is not
/// history, it closes without resistance, joint.rs.) The precondition — predictor inside the
/// domain of the committed state by a margin of 1e-6 of the force size — is checked, not
/// assumed; samples that miss it (a softening joint whose new, lower strength leaves the
/// predictor outside) are counted and must stay a minority.
#[test]
fn c_unloading_from_sliding_is_elastic() {
    let checked = Cell::new(0usize);
    let missed = Cell::new(0usize);
    let strategy = (joint_case(), 0.01f64..0.99, 0.0f64..1.0, -0.01f64..0.01);
    check(20_000, strategy, |(case, back, squeeze, turn)| {
        let JointCase { law, sec, history, e } = case.clone();
        let r1 = return_map(&law, &sec, e, &history, &MapOptions::default()).0;
        let d = elastic(&law, &sec);
        let yielded = r1.state.plastic != history.plastic;
        // Only the Coulomb flow is history: the step must have reached no rocking face, i.e. the
        // force is D (e - plastic) with the committed plastic jumps (up to round-off). The
        // flags alone do not tell: they measure faces relative to the force, and at the apex
        // of a dry joint every force is round-off.
        let stored = (0..3).all(|i| {
            (r1.force[i] - d[i] * (e[i] - r1.state.plastic[i])).abs()
                <= DOMAIN_TOL * force_size(&case) * if i == 2 { sec.length } else { 1.0 }
        });
        if r1.flags & SLIDING == 0 || !yielded || !stored {
            return Ok(()); // not a sliding step: nothing to unload
        }
        let (n1, t1, m1) = (r1.force[0], r1.force[1], r1.force[2]);
        // back along the slip by a fraction of |T| (at most 99%: short of sliding backwards),
        // more compression by up to |T| / mu, a small turn
        let de = [
            -squeeze * t1.abs() / (law.friction.max(0.2) * d[0]),
            -back * t1 / d[1],
            turn * (t1.abs() + n1.abs() + m1.abs()) / d[2] * 1e-2,
        ];
        let predictor = [n1 + d[0] * de[0], t1 + d[1] * de[1], m1 + d[2] * de[2]];
        // the size of the numbers involved: the force and the trial force of the first step
        // (at the apex of a dry joint the force is round-off of the trial force)
        let size = n1.abs() + t1.abs() + 2.0 * m1.abs() / sec.length + force_size(&case);
        if !admissible(&law, &sec, &predictor, &r1.state, -1e-6 * size) {
            missed.set(missed.get() + 1);
            return Ok(());
        }
        let e2 = [e[0] + de[0], e[1] + de[1], e[2] + de[2]];
        let r2 = return_map(&law, &sec, e2, &r1.state, &MapOptions::default()).0;
        for i in 0..3 {
            // round-off of two return mappings on forces of this size (see DOMAIN_TOL)
            prop_assert!(
                (r2.force[i] - predictor[i]).abs() <= DOMAIN_TOL * size * if i == 2 { sec.length } else { 1.0 },
                "component {i}: {} after unloading, elastic {}",
                r2.force[i],
                predictor[i]
            );
        }
        prop_assert_eq!(r2.state.plastic, r1.state.plastic);
        prop_assert_eq!(r2.state.slip, r1.state.slip);
        prop_assert_eq!(r2.state.broken, r1.state.broken);
        prop_assert_eq!(r2.tangent, [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]]);
        checked.set(checked.get() + 1);
        Ok(())
    });
    let (c, m) = (checked.get(), missed.get());
    eprintln!("unloading: {c} sliding states unloaded, {m} with the predictor outside (skipped)");
    assert!(c >= 500 && m <= c, "too few unloadings checked: {c} ({m} skipped)");
}

// ---------------------------------------------------------------------------------------------
// random walls
// ---------------------------------------------------------------------------------------------

#[derive(Debug, Clone)]
struct WallCase {
    blocks: Vec<Rect>,
    law: JointLaw,
    top: Option<TopBeam>,
}

impl WallCase {
    fn model(&self) -> Model {
        Model::new(ModelSpec {
            blocks: polygons(self.blocks.clone()),
            gravity: 10.0,
            joints: JointLaws::uniform(self.law),
            top: self.top,
            ..ModelSpec::default()
        })
        .unwrap()
    }
    fn shifted(&self, dx: f64, dy: f64) -> WallCase {
        WallCase {
            blocks: self
                .blocks
                .iter()
                .map(|r| Rect::new(r.x0 + dx, r.y0 + dy, r.x1 + dx, r.y1 + dy))
                .collect(),
            ..self.clone()
        }
    }
    /// x -> -x (block order kept, so block i of the mirror is the image of block i)
    fn mirrored(&self) -> WallCase {
        WallCase {
            blocks: self.blocks.iter().map(|r| Rect::new(-r.x1, r.y0, -r.x0, r.y1)).collect(),
            top: self.top.map(|t| TopBeam { force: [-t.force[0], t.force[1]], ..t }),
            ..self.clone()
        }
    }
}

/// Small running-bond walls: 1 to 4 courses of 1 to 3.5 blocks (the wall's end cuts blocks),
/// blocks 0.2-0.5 m long with height / length 0.3-1, dry joints (mu 0.4-0.9, associative or
/// not, k 1e8-1e10 N/m3), and in a third of the cases a rigid top beam with a precompression of
/// up to 5 kN.
fn wall_strategy() -> impl Strategy<Value = WallCase> {
    (
        0.2f64..0.5,
        0.3f64..1.0,
        1usize..=4,
        1usize..=3,
        any::<bool>(),
        any::<bool>(),
        0.4f64..0.9,
        any::<bool>(),
        log_uniform(1e8, 1e10),
        0u8..6,
        // a beam under no force is refused as a displacement-control point (nothing ties it)
        1.0f64..5e3,
    )
        .prop_map(|(bl, aspect, courses, n, half_more, half_first, mu, assoc, k, top_kind, p)| {
            let blocks = running_bond(&RunningBond {
                block_length: bl,
                block_height: aspect * bl,
                courses,
                height: None,
                length: bl * (n as f64 + if half_more { 0.5 } else { 0.0 }),
                first_course: if half_first { FirstCourse::Half } else { FirstCourse::Full },
                openings: vec![],
            })
            .unwrap();
            let top = match top_kind {
                0 => Some(TopBeam { rotation_fixed: true, force: [0.0, -p], vertical_held: false }),
                1 => Some(TopBeam { rotation_fixed: false, force: [0.0, -p], vertical_held: false }),
                _ => None,
            };
            WallCase {
                blocks,
                law: common::dry(mu, if assoc { mu } else { 0.0 }, k),
                top,
            }
        })
}

fn load_options() -> StaticOptions {
    StaticOptions { steps: 50, ..StaticOptions::default() }
}

fn disp_options(d: f64, control_block: Option<usize>) -> StaticOptions {
    StaticOptions {
        control: Control::Displacement { max_displacement: d },
        steps: 30,
        control_block,
        ..StaticOptions::default()
    }
}

// ---------------------------------------------------------------------------------------------
// d. every converged static step is in equilibrium, and the reactions balance the loads
// ---------------------------------------------------------------------------------------------

/// Relative tolerance of the equilibrium checks: the solver stops Newton at |r| <= 1e-9 |f|
/// (StaticOptions::residual_tolerance); 1e-8 leaves a factor 10 for the reported forces.
const EQ_TOL: f64 = 1e-8;

/// Checks the state of `r` (interrupted after its last converged step) at multiplier `lambda`.
fn check_equilibrium(model: &Model, r: &Results, lambda: f64) -> Result<(), TestCaseError> {
    let nb = model.n_blocks();
    let mut fint = vec![0.0; 3 * nb];
    model.internal_forces(&r.interface_forces, &mut fint);
    let (fd, fl, fixed) = (model.dead_load(), model.live_load(), model.fixed());
    let f: Vec<f64> = (0..3 * nb).map(|k| fd[k] + lambda * fl[k]).collect();
    let fnorm = f.iter().map(|v| v * v).sum::<f64>().sqrt();
    // free dof: internal forces equal the applied loads
    let res = (0..3 * nb)
        .filter(|&k| !fixed[k])
        .map(|k| (f[k] - fint[k]).powi(2))
        .sum::<f64>()
        .sqrt();
    prop_assert!(res <= EQ_TOL * fnorm, "free-dof residual {res:e} > {EQ_TOL:e} x {fnorm:e}");
    // supports: the reaction R on a fixed dof is what the support adds so that the block is in
    // equilibrium, R = f_int - f. Applied loads plus reactions must have zero resultant force and
    // zero resultant moment (about the origin, in the reference configuration, as the
    // small-displacement model). This also checks that the interface forces act equally and
    // oppositely on their two blocks (the B matrices are consistent with rigid motions).
    let mut total = [0.0; 3];
    let mut size = [0.0; 3];
    let rects = model.rects();
    for i in 0..nb {
        let [cx, cy] = rects[i].centroid();
        let mut g = [0.0; 3];
        for k in 0..3 {
            let dof = 3 * i + k;
            g[k] = f[dof] + if fixed[dof] { fint[dof] - f[dof] } else { 0.0 };
        }
        let m = g[2] + cx * g[1] - cy * g[0];
        total[0] += g[0];
        total[1] += g[1];
        total[2] += m;
        size[0] += g[0].abs() + g[1].abs();
        size[2] += g[2].abs() + (cx * g[1]).abs() + (cy * g[0]).abs();
    }
    size[1] = size[0];
    for k in 0..3 {
        prop_assert!(
            total[k].abs() <= EQ_TOL * size[k],
            "loads + reactions: resultant {k} = {:e} (scale {:e})",
            total[k],
            size[k]
        );
    }
    // the base's reactions against the wall's loads in closed form: the base takes the whole
    // horizontal live load and the whole weight (with the beam's precompression); a fixed beam
    // rotation only adds a moment
    if let Some(b) = model.base() {
        let rx = fint[3 * b] - f[3 * b];
        let ry = fint[3 * b + 1] - f[3 * b + 1];
        let (sx, sy) = (
            (0..nb).map(|i| f[3 * i]).sum::<f64>(),
            (0..nb).map(|i| f[3 * i + 1]).sum::<f64>(),
        );
        prop_assert!((rx + sx).abs() <= EQ_TOL * size[0], "base Rx {rx:e} against {sx:e}");
        prop_assert!((ry + sy).abs() <= EQ_TOL * size[0], "base Ry {ry:e} against {sy:e}");
    }
    Ok(())
}

/// Runs `opts` on `model` stopping after converged step `k` (the monitor's `false`).
fn run_until(model: &Model, opts: &StaticOptions, k: usize) -> Results {
    solve_with(model, opts, &mut |p| p.step < k).unwrap()
}

#[test]
fn d_every_converged_static_step_is_in_equilibrium() {
    let steps_checked = Cell::new(0usize);
    check(12, (wall_strategy(), any::<bool>()), |(wall, disp)| {
        let model = wall.model();
        let opts = if disp { disp_options(2e-3, None) } else { load_options() };
        let full = solve(&model, &opts).unwrap();
        if full.status == Status::Failed {
            // not this property's concern (the converged steps are checked all the same), but
            // reported: see the mirror test's note on displacement control
            eprintln!("equilibrium: the solver failed after {} steps: {:?}", full.steps, full.error);
        }
        let n = full.curve_multiplier.len();
        // every converged step, from the dead-load state on: stop the run right after it
        for k in 1..=n {
            let r = run_until(&model, &opts, k);
            let stopped_at = r.curve_multiplier.len();
            prop_assert_eq!(stopped_at, k);
            // the run up to step k is the full run's path (same steps, same multipliers)
            prop_assert_eq!(r.curve_multiplier[k - 1].to_bits(), full.curve_multiplier[k - 1].to_bits());
            check_equilibrium(&model, &r, r.curve_multiplier[k - 1])?;
            steps_checked.set(steps_checked.get() + 1);
        }
        Ok(())
    });
    eprintln!("equilibrium: {} converged steps checked", steps_checked.get());
}

// ---------------------------------------------------------------------------------------------
// e. determinism
// ---------------------------------------------------------------------------------------------

fn bits(r: &Results) -> Vec<u64> {
    let mut v: Vec<u64> = vec![r.collapse_multiplier.to_bits()];
    v.extend(r.curve_multiplier.iter().map(|x| x.to_bits()));
    v.extend(r.curve_displacement.iter().map(|x| x.to_bits()));
    for a in r.displacements.iter().chain(&r.mechanism).chain(&r.interface_forces) {
        v.extend(a.iter().map(|x| x.to_bits()));
    }
    v.extend(r.interface_states.iter().map(|&x| x as u64));
    v.push(r.iterations as u64);
    v
}

#[test]
fn e_same_input_same_bits_static() {
    check(8, (wall_strategy(), any::<bool>()), |(wall, disp)| {
        let model = wall.model();
        let opts = if disp { disp_options(2e-3, None) } else { load_options() };
        let (a, b) = (solve(&model, &opts).unwrap(), solve(&model, &opts).unwrap());
        prop_assert_eq!(a.status, b.status);
        prop_assert!(bits(&a) == bits(&b), "two runs of the same input differ");
        // a model built anew from the same input too
        let c = solve(&wall.model(), &opts).unwrap();
        prop_assert!(bits(&a) == bits(&c), "a rebuilt model gives other bits");
        Ok(())
    });
}

#[test]
fn e_same_input_same_bits_explicit_one_thread() {
    // small walls, soft joints (a long stable time step) and a coarse bracket keep it short
    let strategy = (wall_strategy(), any::<bool>()).prop_map(|(mut w, disp)| {
        w.blocks.retain(|r| r.y0 < 1e-9); // one course, no top beam
        w.top = None;
        w.law.normal_stiffness = 1e8;
        w.law.shear_stiffness = 1e8;
        (w, disp)
    });
    check(4, strategy, |(wall, disp)| {
        let model = wall.model();
        let opts = ExplicitOptions {
            threads: 1,
            steps: 20,
            tolerance: 1e-2,
            control: if disp { Control::Displacement { max_displacement: 1e-3 } } else { Control::Load },
            ..ExplicitOptions::default()
        };
        let a = explicit::solve(&model, &opts).unwrap();
        let b = explicit::solve(&model, &opts).unwrap();
        prop_assert_eq!(a.status, b.status);
        prop_assert!(bits(&a) == bits(&b), "two explicit runs of the same input differ");
        Ok(())
    });
}

// ---------------------------------------------------------------------------------------------
// f. translation invariance
// ---------------------------------------------------------------------------------------------

/// Translation by any vector, associative joints only. The static solver's displacement limit
/// once depended on the absolute coordinates (0.1 (max(x1, y1) - min(x0, y0))); a 12-block
/// wall (k = 1e8, mu = 0.573, psi = 0, free top beam with 4.67 kN) collapsed at 0.7085 at the
/// origin and at 0.7732 shifted by (-46.4, 44.3) m. It is now 0.1 `Model::size()`.
///
/// FINDING (static solver, not fixed): with psi = 0 the equilibrium path is not unique and
/// Newton's choice follows round-off: a 3-block wall (k = 3.94e9, mu = 0.4, fixed-rotation top
/// beam with 123 N) shifted by (-47.8, -47.8) m failed under displacement control ("no
/// equilibrium after 50 iterations") where the wall at the origin collapsed. So psi = 0 walls
/// are left out here.
#[test]
fn f_translating_a_wall_changes_nothing() {
    translation((wall_strategy(), -50.0f64..50.0, -50.0f64..50.0).prop_map(|(mut w, dx, dy)| {
        w.law.dilatancy = w.law.friction;
        (w, dx, dy)
    }));
}

fn translation(strategy: impl Strategy<Value = (WallCase, f64, f64)>) {
    check(10, strategy, |(wall, dx, dy)| {
        let opts = load_options();
        let a = solve(&wall.model(), &opts).unwrap();
        // The property is about a collapse found: on about 1 random wall in 100 the path stalls
        // 0.1-0.2% below the limit-analysis multiplier (status Stalled, an honest answer that is
        // no collapse); such a wall is drawn again.
        prop_assume!(a.status == Status::Collapse);
        let b = solve(&wall.shifted(dx, dy).model(), &opts).unwrap();
        prop_assert_eq!(b.status, Status::Collapse, "translated: {:?}", b.error);
        // The exact multiplier (limit analysis, to its tolerance) does not move with the wall, and
        // each collapse lies where one is claimed: at most COLLAPSE_EVIDENCE x tolerance below it.
        // Two runs may end anywhere in that band: translation moves the coordinates' round-off,
        // which may cut a step differently.
        // The reference is the program's optimum to its tolerance. Where its interior point
        // stalls short of it (rounding, a few walls in a thousand: the reduced accuracy its
        // certificate reports, and a multiplier up to 4e-8 off) the wall is drawn again.
        let lp = LimitOptions::default();
        let exact = |m: &Model| {
            let r = limit_analysis(m, &lp).unwrap();
            let c = r.certificate.as_ref().expect("limit analysis gives a certificate");
            (r.collapse_multiplier, c.primal_residual.max(c.dual_residual).max(c.duality_gap) <= lp.tolerance)
        };
        let ((ea, sure_a), (eb, sure_b)) = (exact(&wall.model()), exact(&wall.shifted(dx, dy).model()));
        prop_assume!(sure_a && sure_b);
        prop_assert!((ea - eb).abs() <= 2.0 * lp.tolerance * (1.0 + ea), "exact {ea} -> {eb} after a shift of ({dx}, {dy})");
        for (r, e) in [(&a, ea), (&b, eb)] {
            let l = r.collapse_multiplier;
            let claimed = e * (1.0 - COLLAPSE_EVIDENCE * opts.tolerance)..=e + lp.tolerance * (1.0 + e);
            prop_assert!(claimed.contains(&l), "collapse {l} against the exact {e}, shift ({dx}, {dy})");
        }
        // The displacement-controlled curve is a sequence of equilibria at prescribed control
        // displacements: the same up to the equilibrium tolerance. (With psi = 0 and u_limit
        // changed by the shift, the path is not: lambda at step 1 went 1.14638 -> 1.14629 for
        // dy = -2.7 m and to 0.768 for dx = -2.7 m on a 4-block wall: the equilibrium at a
        // given control displacement is not unique, and Newton's choice depends on u_limit.)
        let dopts = disp_options(2e-3, None);
        let a = solve(&wall.model(), &dopts).unwrap();
        let b = solve(&wall.shifted(dx, dy).model(), &dopts).unwrap();
        prop_assert_eq!(a.status, b.status, "{:?} / {:?}", a.error, b.error);
        // the peak of the curve, whatever the status (a path of 2 mm may end before collapse)
        let peak = a.last_equilibrium.abs();
        prop_assert!(
            (a.last_equilibrium - b.last_equilibrium).abs() <= CURVE_TOL * peak,
            "peak {} -> {} after a shift of ({dx}, {dy})",
            a.last_equilibrium,
            b.last_equilibrium
        );
        // Round-off may decide a step cut differently (seen: 36 and 33 steps for a shift of
        // -33 m, same peak to 1e-12), and then the curves sample different displacements; where
        // the prescribed displacements coincide, every point must.
        let same_path = a.curve_displacement.len() == b.curve_displacement.len()
            && a.curve_displacement.iter().zip(&b.curve_displacement).skip(1).all(|(x, y)| {
                (x - y).abs() <= CURVE_TOL * 2e-3
            });
        if same_path {
            for (k, (x, y)) in a.curve_multiplier.iter().zip(&b.curve_multiplier).enumerate() {
                prop_assert!(
                    (x - y).abs() <= CURVE_TOL * peak,
                    "step {k}: lambda {x} -> {y} after a shift of ({dx}, {dy})"
                );
            }
        }
        Ok(())
    });
}

/// Relative tolerance (of the peak) on the points of displacement-controlled curves of
/// equivalent inputs. Each point is an equilibrium at the same prescribed displacement; Newton
/// stops at |r| <= residual_tolerance |f|, and what is left in lambda is that residual over the
/// wall's stiffness in the live-load direction, amplified near the peak where the tangent
/// softens. Two equivalent runs differ by ~1e-9 of the peak (seen: 1.2e-9 and 1.7e-9, the
/// default residual tolerance; a tighter residual tolerance, 1e-12, is not reached by every
/// step and changes the step sequence). 1e-6 allows an amplification of the residual tolerance
/// of up to 1e3, while a real asymmetry (a joint in another state, a load on the wrong side, a
/// length-scale that depends on where the wall stands) moves lambda by percents.
const CURVE_TOL: f64 = 1e-6;

// ---------------------------------------------------------------------------------------------
// g. mirror symmetry
// ---------------------------------------------------------------------------------------------

/// The live load only pushes towards +x (LiveLoad has no direction) and load control only
/// raises lambda, but displacement control accepts a negative `max_displacement`: the control
/// block is pushed towards -x and lambda goes negative. So: the original wall pushed towards
/// -x and its mirror image pushed towards +x must follow mirrored curves (lambda -> -lambda),
/// and vice versa, with the same (mirrored) control block.
///
/// Associative joints only (psi = phi), as for translation (f) and in the Python mirror test.
/// With psi = 0 the property is not true of the problem, so no solver can satisfy it: the
/// equilibrium path at a prescribed displacement is not unique (non-associative friction), and
/// which branch Newton lands on, and where it then stops with "no equilibrium after 50
/// iterations", follows round-off. Mirroring only changes the round-off (x -> -x, head joints'
/// a and b swapped, so another assembly order; the return mapping is mirror-symmetric to 4e-13
/// of the trial force over 6e5 random calls, psi = 0 included). psi = 0 walls broke this test
/// in about 1 run in 12; in a sweep of 2,454 psi = 0 pushes (kept out of the suite) 13 mirror
/// pairs disagreed, 12 of them also between the wall and a copy of itself shifted by 1e-9 m or
/// 0.37 m or with its blocks in reverse order, and 31 more pushes disagreed with such a copy
/// while the mirror agreed (up to 15% on the peak). The walls found (`g_mirror_regressions`):
/// - 7 blocks (mu = 0.740, top beam of fixed rotation under 3.5 kN) pushed by -2 mm: peak
///   1.01833, mirror 1.02900; the wall itself in reverse block order or shifted by 1e-9 m
///   also peaks at 1.02900, and at 1.02251 with 37 steps instead of 30;
/// - 14 blocks, symmetric (mu = 0.482, beam of fixed rotation under 1 N): collapses after 70
///   steps pushed by -2 mm, stops after 5 ("no equilibrium", lambda 0.204) pushed by +2 mm,
///   or by -2 mm once shifted by 1e-9 m in x;
/// - 4 blocks in one course (mu = 0.842, beam of fixed rotation under 4.3 kN): peaks 2.54802
///   and 2.54887, both runs stopping at u = 4.9e-5 m.
///
/// With psi = phi the same walls give the same curves with 30 to 240 steps, and mirror.
///
/// The control block is the wall's top right block (its image in the mirror), also under a
/// top beam. A beam carries only its own force, and with a small one (28-89 N, rotation free)
/// its displacement does not fix the wall's state: at the same beam displacement a wall and
/// its mirror image gave lambda 0.684 and 0.698 at step 1 (2%), and the wall shifted by 1e-9
/// m moved step 1 by 0.2% under 100 N. The solver refuses a beam under no force for this
/// reason (8d4564f); wall blocks carry the live load. In a sweep of 3,000 associative walls
/// the beam as control block broke the property in 4 of 1,934 pushes, a wall block in none.
///
/// A push in which either run fails ("no equilibrium") is compared no further: with
/// associative joints displacement control fails where the control block's displacement
/// stops being a parameter of the path, and the last converged point, or whether a step
/// lands beyond a snap-back and the run goes on, depends on how the step was halved, not on
/// the wall (1 status disagreement in 4,066 beamless pushes). Load control, which follows
/// the path by the live load's work, shows it on the 12-block wall of `g_mirror_regressions`
/// pushed towards -x: the control block goes to 2.913e-5 m at lambda 0.4853, back to
/// 2.815e-5 m while lambda rises to 0.5001 (a snap-back), on to 1.007e-4 m at the collapse
/// load 0.50105, and no further (the mechanism leaves it behind). Displacement control stops
/// at the snap-back (peak 0.48446: the mirror image with 30 steps, the wall itself with 60 or
/// 120) or, if a step lands beyond it, near the end of the plateau (0.50104: the wall with 30
/// steps). That 3.3% broke this test once in 60 runs after psi = 0 was left out. Near the
/// end of a plateau the peaks of runs halved differently differ by ~3e-6. Not crossing a dry
/// wall's snap-back is the solver's (`g_displacement_control_crosses_a_dry_snap_back`).
/// The tolerances stay those of equivalent runs (CURVE_TOL). In a sweep of 8,000 pushes
/// (862 failed, always in both runs), one pair that both reached 2 mm differed by 8.7e-6 on
/// the peak, and one in 50 runs of this file by 4e-6 at 2 mm: a run whose first step was
/// halved against one whose was not (compared now only where the steps coincide, see
/// `mirror_property`).
#[test]
fn g_mirroring_a_wall_mirrors_its_curve() {
    let compared = Cell::new(0usize);
    let associative = wall_strategy().prop_map(|mut w| {
        w.law.dilatancy = w.law.friction;
        w
    });
    check(10, associative, |wall| {
        compared.set(compared.get() + mirror_property(&wall)?);
        Ok(())
    });
    eprintln!("mirror: {} of 20 pushes compared", compared.get());
    // a run fails in about 1 push in 10: all 20 failing would mean something else broke
    assert!(compared.get() > 0, "no push reached its displacement");
}

/// The mirror property of `wall` (see g): pushed both ways by its top right wall block, the
/// wall and its mirror image, where both reach the requested displacement, end with the same
/// status and, where they take the same steps, follow mirrored curves. Returns the number of
/// pushes (of 2) compared point by point.
fn mirror_property(wall: &WallCase) -> Result<usize, TestCaseError> {
    let model = wall.model();
    let mirror = wall.mirrored().model();
    let top_right = |r: &Rect| (r.y1, r.x1);
    let cb = (0..wall.blocks.len())
        .max_by(|&i, &j| top_right(&wall.blocks[i]).partial_cmp(&top_right(&wall.blocks[j])).unwrap())
        .unwrap();
    let mut compared = 0;
    for d in [2e-3, -2e-3] {
        let a = solve(&model, &disp_options(d, Some(cb))).unwrap();
        let b = solve(&mirror, &disp_options(-d, Some(cb))).unwrap();
        if a.status == Status::Failed || b.status == Status::Failed {
            continue; // where it stopped is not the wall's (see g)
        }
        prop_assert_eq!(a.status, b.status, "push {}", d);
        // As for translation, round-off may cut a step differently, and then the runs are two
        // discretizations of the path, not equivalent runs: on a plateau the slip accumulated
        // depends on the steps (seen: 4e-6 on the peak at 2 mm, one run with its first step
        // halved). CURVE_TOL holds where the prescribed displacements coincide (mirrored).
        let same_path = a.curve_displacement.len() == b.curve_displacement.len()
            && a.curve_displacement.iter().zip(&b.curve_displacement).skip(1).all(|(x, y)| {
                (x + y).abs() <= CURVE_TOL * d.abs()
            });
        if !same_path {
            continue;
        }
        compared += 1;
        let peak = a.curve_multiplier.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let peak_b = b.curve_multiplier.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        prop_assert!((peak - peak_b).abs() <= CURVE_TOL * peak, "push {d}: peak {peak}, mirror {peak_b}");
        for (k, (x, y)) in a.curve_multiplier.iter().zip(&b.curve_multiplier).enumerate() {
            prop_assert!(
                (x + y).abs() <= CURVE_TOL * peak,
                "push {d}: step {k}: lambda {x}, mirror {y}"
            );
        }
    }
    Ok(compared)
}

/// One course of blocks between the x breakpoints `xs`, from y0 to y1.
fn course(xs: &[f64], y0: f64, y1: f64) -> Vec<Rect> {
    xs.windows(2).map(|w| Rect::new(w[0], y0, w[1], y1)).collect()
}

/// Courses between the heights `ys`, the first, third... with the x breakpoints `a`, the
/// others with `b` (a running bond).
fn bond(a: &[f64], b: &[f64], ys: &[f64]) -> Vec<Rect> {
    ys.windows(2)
        .enumerate()
        .flat_map(|(k, y)| course(if k % 2 == 0 { a } else { b }, y[0], y[1]))
        .collect()
}

/// The walls (as proptest shrank them) on which the mirror property failed: three with
/// psi = 0, each with a top beam of fixed rotation, kept with associative joints, where the
/// property holds (see g for what psi = 0 did on them), and the associative 12-block wall of
/// the snap-back, whose pushes towards -x fail and are not compared.
#[test]
fn g_mirror_regressions() {
    let beam = |p: f64| Some(TopBeam { rotation_fixed: true, force: [0.0, -p], vertical_held: false });
    // peak 1.01833 / 1.02900 pushed by -2 mm with psi = 0
    let (a, b) = (
        [0.0, 0.398610237629231, 0.797220475258462, 1.1958307128876928],
        [0.0, 0.1993051188146155, 0.5979153564438464, 0.9965255940730774, 1.1958307128876928],
    );
    let y = [0.0, 0.36475760721783984, 0.7295152144356797];
    let seven = WallCase {
        blocks: bond(&a, &b, &y),
        law: common::dry(0.7399378017562555, 0.0, 5358997135.234735),
        top: beam(3513.873417439486),
    };
    // Collapse / Failed (no equilibrium after 50 iterations) pushed by -2 mm with psi = 0
    let (a, b) = (
        [0.0, 0.10679785583839528, 0.32039356751518583, 0.5339892791919764, 0.6407871350303717],
        [0.0, 0.21359571167679056, 0.4271914233535811, 0.6407871350303717],
    );
    let y = [0.0, 0.2114472890128573, 0.4228945780257146, 0.6343418670385719, 0.8457891560514292];
    let fourteen = WallCase {
        blocks: bond(&a, &b, &y),
        law: common::dry(0.4816940153701755, 0.0, 6260286909.773505),
        top: beam(1.0),
    };
    // peak 2.54802 / 2.54887 pushed by +2 mm with psi = 0
    let xs = [0.0, 0.14729123416224593, 0.4418737024867378, 0.7364561708112296, 0.8837474049734756];
    let four = WallCase {
        blocks: course(&xs, 0.0, 0.2396670211533179),
        law: common::dry(0.841621130428826, 0.0, 5494784580.722607),
        top: beam(4299.872586299624),
    };
    for (name, mut wall) in [("7 blocks", seven), ("14 blocks", fourteen), ("4 blocks", four)] {
        wall.law.dilatancy = wall.law.friction;
        match mirror_property(&wall) {
            Ok(n) => assert!(n > 0, "{name}: no push reached 2 mm with psi = phi"),
            Err(e) => panic!("{name}: {e}"),
        }
    }
    // peak 0.50104 / 0.48446 pushed by -2 mm (both runs failed): the pushes towards +x are
    // compared, those towards -x by status
    match mirror_property(&snap_back_wall()) {
        Ok(n) => assert_eq!(n, 1, "12 blocks: the push towards -x fails, the other not"),
        Err(e) => panic!("12 blocks: {e}"),
    }
}

/// An associative 12-block running-bond wall (4 courses, no top beam) whose path pushed
/// towards -x snaps back in the displacement of the control block (the top right block).
fn snap_back_wall() -> WallCase {
    let a = [0.0, 0.21207571876277026, 0.6362271562883108, 1.0603785938138512];
    let b = [0.0, 0.4241514375255405, 0.848302875051081, 1.0603785938138512];
    let y = [0.0, 0.30445832216103846, 0.6089166443220769, 0.9133749664831154, 1.2178332886441539];
    WallCase {
        blocks: bond(&a, &b, &y),
        law: common::dry(0.7056858811962229, 0.7056858811962229, 6586062465.386855),
        top: None,
    }
}

/// SOLVER ISSUE (static displacement control, not fixed). The wall of `snap_back_wall` pushed
/// towards -x: its path, as load
/// control follows it (on the mirror image, pushed towards +x), takes the control block to
/// 2.913e-5 m at lambda 0.4853, back to 2.815e-5 m while lambda rises to 0.5001, and on to
/// the collapse load 0.50105. Displacement control halves its step down to the minimum at
/// the limit point and reports "no equilibrium after 50 iterations" at lambda 0.4845, 3.3%
/// below the collapse load, unless a step happens to land beyond the snap-back (30 steps
/// do: 0.50104; 60 or 120 do not). A snap-back is crossed by dynamic relaxation only in
/// walls whose joints can lose strength (`can_lose_strength`); this dry, associative wall
/// snaps back all the same. Letting a dry wall jump too takes every run here (wall and
/// mirror image, 30 to 240 steps) to 0.50104-0.50105. Un-ignore once the solver crosses it.
#[test]
#[ignore = "solver issue: displacement control stops at a dry wall's snap-back"]
fn g_displacement_control_crosses_a_dry_snap_back() {
    let wall = snap_back_wall();
    let model = wall.model();
    let cb = model.default_control_block();
    // the collapse load towards -x: load control on the mirror image, bracketed to 1e-4
    let collapse = solve(&wall.mirrored().model(), &load_options()).unwrap();
    assert_eq!(collapse.status, Status::Collapse, "{:?}", collapse.error);
    let lambda_c = collapse.collapse_multiplier;
    for (name, m, d) in [("wall", &model, -2e-3), ("mirror", &wall.mirrored().model(), 2e-3)] {
        for steps in [30, 60, 120] {
            let r = solve(m, &StaticOptions { steps, ..disp_options(d, Some(cb)) }).unwrap();
            let peak = r.curve_multiplier.iter().fold(0.0f64, |p, x| p.max(x.abs()));
            // 1e-3: the solver's own test of a softened curve; the snap-back is 3.3% below
            assert!(
                peak >= (1.0 - 1e-3) * lambda_c,
                "{name}, {steps} steps: peak {peak} < collapse load {lambda_c} ({:?})",
                r.error
            );
        }
    }
}

/// Found by f in 1 of 100 runs of this file: on this associative 5-block wall load control
/// (50 steps) reported collapse at 0.324285, a plateau of its path, while displacement control
/// reaches an equilibrium at 0.329523 (1.6% higher; with associative joints every equilibrium
/// is a lower bound of the collapse load). The same wall shifted by 1e-9 m, or by (0, 3.38) m
/// as f drew it, gave 0.329523 by load control too, and with 200 steps every position gave
/// 0.324285. Load control now tries Newton at a fixed lambda just above a plateau before it
/// calls it the collapse, and goes on from the equilibrium found there.
#[test]
fn f_load_control_does_not_stop_below_an_equilibrium() {
    let (a, b) = ([0.0, 0.11623954432404907, 0.23247908864809813], [0.0, 0.23247908864809813]);
    let y = [0.0, 0.19682242897599464, 0.3936448579519893, 0.5904672869279839];
    let mu = 0.4235620298005757;
    let wall = WallCase {
        blocks: bond(&a, &b, &y),
        law: common::dry(mu, mu, 621320620.1970984),
        top: None,
    };
    let model = wall.model();
    let d = solve(&model, &disp_options(2e-3, None)).unwrap();
    assert_eq!(d.status, Status::Collapse, "{:?}", d.error);
    let reached = d.collapse_multiplier;
    for steps in [50, 200] {
        let opts = StaticOptions { steps, ..load_options() };
        let l = solve(&model, &opts).unwrap();
        assert_eq!(l.status, Status::Collapse, "{:?}", l.error);
        // load control brackets the collapse load to `tolerance` (relative)
        assert!(
            l.collapse_multiplier >= reached * (1.0 - opts.tolerance),
            "{steps} steps: collapse {} below the equilibrium at {reached}",
            l.collapse_multiplier
        );
    }
}
