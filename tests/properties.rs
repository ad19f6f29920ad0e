//! Property tests (issue 6, robustness): invariants of the joint law and of the solvers on
//! random inputs drawn by proptest.
//!
//! - the return mapping stays in the strength domain, its consistent tangent matches central
//!   finite differences, and unloading from a sliding state is elastic;
//! - every converged static step is in equilibrium (free dof) and the support reactions
//!   balance the applied loads;
//! - the same input gives bitwise the same output (static, and explicit on one thread);
//! - translating a wall changes nothing; mirroring a wall and its push gives the mirrored curve.
//!
//! Case counts are kept small enough for `make test` (the whole file runs in well under a
//! minute in release mode); failures are shrunk by proptest and printed with the minimal input.

mod common;

use masonry_dem::explicit::{self, ExplicitOptions, QsControl};
use masonry_dem::geometry::{running_bond, FirstCourse, Rect, RunningBond};
use masonry_dem::joint::{admissible, return_map, JointLaw, JointState, Section, SLIDING};
use masonry_dem::model::{JointLaws, Model, ModelSpec, TopBeam};
use masonry_dem::results::{Results, Status};
use masonry_dem::static_solver::{solve, solve_with, Control, StaticOptions};
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
                history = return_map(&law, &sec, scaled(u), &history).state;
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
        let r = return_map(&law, &sec, e, &history);
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
/// linear stretch all four differences and the central one are exact up to round-off, which is
/// ~1e-16 |F| / h = ~1e-9 of the stiffness here; the comparison with the tangent uses 1e-6 of
/// the largest elastic stiffness (in the units of the entry), far above round-off and far below
/// any error of the tangent formula (a wrong active set or a wrong term is off by O(1)).
const FD_TOL: f64 = 1e-6;

#[test]
fn b_tangent_matches_central_finite_differences() {
    let checked = Cell::new(0usize);
    let plastic = Cell::new(0usize);
    let skipped = Cell::new(0usize);
    check(6_000, joint_case(), |case| {
        let JointCase { law, sec, history, e } = case;
        let r = return_map(&law, &sec, e, &history);
        let d = elastic(&law, &sec);
        let s = jump_scale(&law, &sec);
        let f = |x: [f64; 3]| return_map(&law, &sec, x, &history).force;
        let mut fd = [[0.0; 3]; 3];
        for j in 0..3 {
            let h = 1e-7 * (e[j].abs() + history.plastic[j].abs() + s[j]);
            let at = |t: f64| {
                let mut x = e;
                x[j] += t;
                f(x)
            };
            let (p1, m1, p10, m10) = (at(h), at(-h), at(10.0 * h), at(-10.0 * h));
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
        let r1 = return_map(&law, &sec, e, &history);
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
        let r2 = return_map(&law, &sec, e2, &r1.state);
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
            blocks: self.blocks.clone(),
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
            control: if disp { QsControl::Displacement { max_displacement: 1e-3 } } else { QsControl::Load },
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
        let b = solve(&wall.shifted(dx, dy).model(), &opts).unwrap();
        prop_assert_eq!(a.status, Status::Collapse, "original: {:?}", a.error);
        prop_assert_eq!(b.status, Status::Collapse, "translated: {:?}", b.error);
        // Load control brackets the collapse multiplier: both runs stop with the true value
        // within [lambda, lambda (1 + tolerance)], so two correct runs differ by at most
        // `tolerance` relative (translation moves the coordinates' round-off, which may decide
        // one bisection step differently; it may not move the bracket).
        let (la, lb) = (a.collapse_multiplier, b.collapse_multiplier);
        prop_assert!(
            (la - lb).abs() <= opts.tolerance * la.abs().max(lb.abs()),
            "collapse multiplier {la} -> {lb} after a shift of ({dx}, {dy})"
        );
        // The displacement-controlled curve is a sequence of equilibria at prescribed control
        // displacements: the same up to the equilibrium tolerance. (With psi = 0 and u_limit
        // changed by the shift, the path is not: lambda at step 1 went 1.14638 -> 1.14629 for
        // dy = -2.7 m and to 0.768 for dx = -2.7 m on a 4-block wall: the equilibrium at a
        // given control displacement is not unique, and Newton's choice depends on u_limit.)
        let dopts = disp_options(2e-3, None);
        let a = solve(&wall.model(), &dopts).unwrap();
        let b = solve(&wall.shifted(dx, dy).model(), &dopts).unwrap();
        prop_assert_eq!(a.status, b.status, "{:?} / {:?}", a.error, b.error);
        let peak = a.collapse_multiplier.abs();
        prop_assert!(
            (a.collapse_multiplier - b.collapse_multiplier).abs() <= CURVE_TOL * peak,
            "peak {} -> {} after a shift of ({dx}, {dy})",
            a.collapse_multiplier,
            b.collapse_multiplier
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
#[test]
fn g_mirroring_a_wall_mirrors_its_curve() {
    check(10, wall_strategy(), |wall| {
        let model = wall.model();
        let mirror = wall.mirrored().model();
        let cb = model.default_control_block();
        for d in [2e-3, -2e-3] {
            let a = solve(&model, &disp_options(d, Some(cb))).unwrap();
            let b = solve(&mirror, &disp_options(-d, Some(cb))).unwrap();
            // A failed run must fail in the mirror too, at the mirrored step: the curves are
            // compared as far as they go. (Found: with a fixed-rotation top beam and psi = 0,
            // displacement control can fail with "no equilibrium after 50 iterations" in one
            // direction of push; the mirror fails identically, so symmetry holds.)
            prop_assert_eq!(a.status, b.status, "{:?} / {:?}", a.error, b.error);
            let peak = a.curve_multiplier.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let peak_b = b.curve_multiplier.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            prop_assert!((peak - peak_b).abs() <= CURVE_TOL * peak, "push {d}: peak {peak}, mirror {peak_b}");
            // as for translation, round-off may cut a step differently; where the prescribed
            // displacements coincide (mirrored), every point must
            let same_path = a.curve_displacement.len() == b.curve_displacement.len()
                && a.curve_displacement.iter().zip(&b.curve_displacement).skip(1).all(|(x, y)| {
                    (x + y).abs() <= CURVE_TOL * d.abs()
                });
            if same_path {
                for (k, (x, y)) in a.curve_multiplier.iter().zip(&b.curve_multiplier).enumerate() {
                    prop_assert!(
                        (x + y).abs() <= CURVE_TOL * peak,
                        "push {d}: step {k}: lambda {x}, mirror {y}"
                    );
                }
            }
        }
        Ok(())
    });
}
