//! Quasi-static analyses by damped relaxation: load control (each level relaxed, the collapse
//! multiplier bracketed) and displacement control, and the relaxations the static solver
//! borrows (the dead state, a jump at a prescribed displacement).

use super::*;

/// Outcome of relaxing one load level.
pub(super) enum Level {
    Settled,
    RanAway,
    Stopped,
}

/// The state under the dead loads alone found by damped relaxation (local damping 0.8): the
/// displacements and the joint histories, or an error if the wall does not settle. The static
/// solver starts from it where Newton cannot find the dead state from the unloaded wall.
/// A block moving more than 1% of the wall's size (or the wall's motion ceasing to be finite)
/// means the wall does not stand: the relaxation stops there instead of running its step limit.
/// `monitor` is called every 4,096 steps or 0.1 s (return false to stop: `Error::Interrupted`).
pub(crate) fn relax_dead_state(
    model: &Model,
    monitor: &mut dyn FnMut(&Progress) -> bool,
) -> Result<(Vec<f64>, Vec<JointState>), Error> {
    let mut s = Integrator::new(model, None, SAFETY, Damping::Local(LOCAL_DAMPING), 1)?;
    let fd = model.dead_load().to_vec();
    let mut set_ext = |f: &mut [f64], _: &[f64]| f.copy_from_slice(&fd);
    let limit = 1e-2 * model.size();
    let nb = model.n_blocks();
    let max_steps = 2_000_000;
    let mut last = Instant::now();
    for k in 0..max_steps {
        s.step(&mut set_ext, None);
        if k % 16 == 15 {
            if s.unbalanced_ratio(None) <= 1e-7 {
                let states = s.states();
                return Ok((s.u, states));
            }
            let (i, moved) = (0..nb)
                .map(|i| (i, s.u[3 * i].hypot(s.u[3 * i + 1])))
                .fold((0, 0.0), |a, b| if b.1 > a.1 || b.1.is_nan() { b } else { a });
            if !(moved <= limit) {
                return Err(Error::Mechanism(format!(
                    "the wall does not stand under the dead loads alone: {} moves off (explicit relaxation)",
                    model.block_name(i)
                )));
            }
        }
        if monitor_due(k, &mut last) {
            let p = Progress { step: k + 1, multiplier: 0.0, displacement: f64::NAN, fraction: f64::NAN, poll: false };
            if !monitor(&p) {
                return Err(Error::Interrupted);
            }
        }
    }
    Err(Error::Mechanism(format!("the wall does not settle under the dead loads alone (explicit relaxation, {max_steps} steps)")))
}

/// An equilibrium state with dof `cd` held at `target`, found by damped relaxation (local
/// damping 0.8) from displacements `u` and joint histories `states` (the dofs held after the
/// dead state held too), with lambda from the equation of `cd`: the displacements, the joint
/// histories and lambda. The static solver's displacement control crosses a snap-back with it:
/// where the equilibrium path turns back in the control displacement, no state near the last
/// converged one exists at the next displacement, and the wall jumps (dynamically, in a test)
/// to a state of lower force; the relaxation follows that jump.
pub(crate) fn relax_at_displacement(
    model: &Model,
    u: &[f64],
    states: &[JointState],
    cd: usize,
    target: f64,
) -> Result<(Vec<f64>, Vec<JointState>, f64), Error> {
    let mut s = Integrator::damped_from(model, u, states)?;
    let (fd, fl) = (model.dead_load(), model.live_load());
    if fl[cd] == 0.0 {
        return Err(Error::input("the control dof carries no live load"));
    }
    let lam = std::cell::Cell::new(0.0);
    let mut set_ext = |f: &mut [f64], fint: &[f64]| {
        let l = (fint[cd] - fd[cd]) / fl[cd];
        lam.set(l);
        for d in 0..f.len() {
            f[d] = fd[d] + l * fl[d];
        }
    };
    // bounded: a by-product of one static step (J4D's jumps settle in a few thousand steps)
    let max_steps = 200_000;
    for k in 0..max_steps {
        s.step(&mut set_ext, Some((cd, target)));
        if k % 16 == 15 {
            if s.u.iter().any(|x| !x.is_finite()) {
                break;
            }
            if s.unbalanced_ratio(Some(cd)) <= 1e-7 {
                let states = s.states();
                return Ok((s.u, states, lam.get()));
            }
        }
    }
    Err(Error::Convergence(format!(
        "no equilibrium at the control displacement {target:.4e} m by dynamic relaxation either ({max_steps} steps)"
    )))
}

/// Runs a quasi-static analysis with the explicit solver; same results as the static solver.
pub fn solve(model: &Model, opts: &ExplicitOptions) -> Result<Results, Error> {
    solve_with(model, opts, &mut |_| true)
}

/// As [`solve`], calling `monitor` after each settled level (return false to stop).
pub fn solve_with(model: &Model, opts: &ExplicitOptions, monitor: &mut dyn FnMut(&Progress) -> bool) -> Result<Results, Error> {
    model.check_analysis_memory("an explicit analysis")?;
    model.check_strength_range()?;
    let start = Instant::now();
    check_steps(opts.steps)?;
    if !(opts.tolerance > 0.0 && opts.tolerance < 1.0) {
        return Err(Error::input(format!("analysis.tolerance must lie in (0, 1), got {}", opts.tolerance)));
    }
    if !(opts.unbalanced_ratio > 0.0 && opts.unbalanced_ratio < 1.0) {
        return Err(Error::input(format!("analysis.unbalanced_ratio must lie in (0, 1), got {}", opts.unbalanced_ratio)));
    }
    if opts.max_steps_per_level == 0 {
        return Err(Error::input("max_steps_per_level must be at least 1"));
    }
    model.check_supports()?;
    let nb = model.n_blocks();
    let control_block = opts.control_block.unwrap_or_else(|| model.default_control_block());
    if control_block >= nb {
        return Err(Error::input(format!("control block {control_block} does not exist (the model has {nb} blocks)")));
    }
    let cd = 3 * control_block;
    if let Control::Displacement { max_displacement } = opts.control {
        if !(max_displacement.is_finite() && max_displacement != 0.0) {
            return Err(Error::input(format!("analysis.max_displacement must be a finite non-zero length, got {max_displacement}")));
        }
        if model.fixed()[cd] || model.live_load()[cd] == 0.0 {
            return Err(Error::input(format!(
                "the control block ({}) must be free to move horizontally and carry live load",
                model.block_name(control_block)
            )));
        }
    }
    let mut s = Integrator::new(model, opts.time_step, opts.safety, opts.damping, opts.threads)?;
    let size = model.size();
    let mut curve_l = vec![];
    let mut curve_u = vec![];
    let fd = model.dead_load().to_vec();
    let fl = model.live_load().to_vec();

    // relax at multiplier `lam` (or, with `drive`, with the control dof held at a value and
    // lambda from its equation); the run counts as running away when a block moves more than
    // `u_fail` from the start of the level
    let relax = |s: &mut Integrator,
                 lam: &mut f64,
                 drive: Option<f64>,
                 u_fail: f64,
                 monitor: &mut dyn FnMut(&Progress) -> bool|
     -> Level {
        let u0 = s.u.clone();
        let lam_cell = std::cell::Cell::new(*lam);
        let mut set_ext = |f: &mut [f64], fint: &[f64]| {
            if drive.is_some() {
                lam_cell.set((fint[cd] - fd[cd]) / fl[cd]);
            }
            let l = lam_cell.get();
            for d in 0..f.len() {
                f[d] = fd[d] + l * fl[d];
            }
        };
        let mut last = Instant::now();
        for k in 0..opts.max_steps_per_level {
            s.step(&mut set_ext, drive.map(|x| (cd, x)));
            *lam = lam_cell.get();
            if k % 16 == 15 {
                if s.unbalanced_ratio(drive.map(|_| cd)) <= opts.unbalanced_ratio {
                    return Level::Settled;
                }
                let moved = (0..nb).map(|i| (s.u[3 * i] - u0[3 * i]).hypot(s.u[3 * i + 1] - u0[3 * i + 1])).fold(0.0, f64::max);
                if moved > u_fail || !moved.is_finite() {
                    return Level::RanAway;
                }
            }
            if monitor_due(k, &mut last) {
                let p = Progress { step: s.steps, multiplier: *lam, displacement: s.u[cd], fraction: f64::NAN, poll: false };
                if !monitor(&p) {
                    return Level::Stopped;
                }
            }
        }
        Level::RanAway
    };

    // dead load
    let mut lam = 0.0;
    let steps_before = s.steps;
    let u_fail0 = 1e-2 * size;
    match relax(&mut s, &mut lam, None, u_fail0, monitor) {
        Level::Settled => {}
        Level::Stopped => return Ok(finish(model, s, Status::Interrupted, Some(Error::Interrupted), curve_l, curve_u, None, control_block, start)),
        Level::RanAway => {
            let e = Error::Mechanism("no equilibrium under the dead loads alone (the wall does not settle)".into());
            return Ok(finish(model, s, Status::failure(&e), Some(e), curve_l, curve_u, None, control_block, start));
        }
    }
    let dead_steps = s.steps - steps_before;
    s.v.fill(0.0);
    s.hold();
    curve_l.push(0.0);
    curve_u.push(s.u[cd]);
    // displacements beyond 20 x the settlement under dead load (at least 1e-4 of the wall) are
    // a running mechanism, not an elastic response
    let settle = (0..nb).map(|i| s.u[3 * i].hypot(s.u[3 * i + 1])).fold(0.0, f64::max);
    let u_fail = (20.0 * settle).max(1e-4 * size);
    let save = |s: &Integrator| (s.u.clone(), s.hist.clone(), s.broken.clone());
    let restore = |s: &mut Integrator, st: &(Vec<f64>, Vec<f64>, Vec<bool>)| {
        s.u.copy_from_slice(&st.0);
        s.hist.copy_from_slice(&st.1);
        s.broken.copy_from_slice(&st.2);
        s.v.fill(0.0);
        s.a.fill(0.0);
    };
    match opts.control {
        Control::Load => {
            let scale = match model.live() {
                LiveLoad::HorizontalWeight => 1.0,
                LiveLoad::TopHorizontal => (model.weight().iter().sum::<f64>() + fd.iter().map(|x| x.abs()).sum::<f64>()).max(1.0),
            };
            let mut dl = 4.0 * scale / opts.steps as f64;
            let mut lam_conv = 0.0;
            let mut saved = save(&s);
            let mut mechanism = None;
            let max_levels = 100 * opts.steps + 1000;
            for _ in 0..max_levels {
                let mut l = lam_conv + dl;
                match relax(&mut s, &mut l, None, u_fail, monitor) {
                    Level::Settled => {
                        lam_conv = l;
                        saved = save(&s);
                        s.v.fill(0.0);
                        curve_l.push(l);
                        curve_u.push(s.u[cd]);
                        let p = Progress { step: s.steps, multiplier: l, displacement: s.u[cd], fraction: f64::NAN, poll: false };
                        if !monitor(&p) {
                            return Ok(finish(model, s, Status::Interrupted, Some(Error::Interrupted), curve_l, curve_u, None, control_block, start));
                        }
                        if lam_conv > 1e3 * scale {
                            let e = Error::Convergence(crate::results::unbounded_message(lam_conv));
                            return Ok(finish(model, s, Status::Unbounded, Some(e), curve_l, curve_u, None, control_block, start));
                        }
                    }
                    Level::Stopped => {
                        restore(&mut s, &saved);
                        return Ok(finish(model, s, Status::Interrupted, Some(Error::Interrupted), curve_l, curve_u, None, control_block, start));
                    }
                    Level::RanAway => {
                        mechanism = Some(s.u.iter().zip(&saved.0).map(|(a, b)| a - b).collect::<Vec<f64>>());
                        restore(&mut s, &saved);
                        dl *= 0.5;
                        if 2.0 * dl <= opts.tolerance * lam_conv.abs().max(1e-3 * scale) {
                            s.interface_forces();
                            return Ok(finish(model, s, Status::Collapse, None, curve_l, curve_u, mechanism, control_block, start));
                        }
                    }
                }
            }
            let e = Error::Convergence(format!("no collapse bracket after {max_levels} load levels"));
            Ok(finish(model, s, Status::failure(&e), Some(e), curve_l, curve_u, mechanism, control_block, start))
        }
        Control::Displacement { max_displacement } => {
            let u_start = s.u[cd];
            let stages = opts.steps;
            let mut prev = save(&s);
            for k in 1..=stages {
                let target = u_start + max_displacement * k as f64 / stages as f64;
                // drive the control dof there over a few hundred steps, then relax holding it
                let from = s.u[cd];
                // slowly, over five times the dead state's settling time: a fast drive makes the
                // control block slip locally against the inertia of the rest of the wall (wall 1:
                // peak 0.595 over 200 steps, 0.635 over 2,000, 0.641 over 10,000)
                let n_drive = (5 * dead_steps).max(200);
                let mut set_ext = |f: &mut [f64], fint: &[f64]| {
                    lam = (fint[cd] - fd[cd]) / fl[cd];
                    for d in 0..f.len() {
                        f[d] = fd[d] + lam * fl[d];
                    }
                };
                for j in 1..=n_drive {
                    let x = from + (target - from) * j as f64 / n_drive as f64;
                    s.step(&mut set_ext, Some((cd, x)));
                }
                match relax(&mut s, &mut lam, Some(target), f64::INFINITY, monitor) {
                    Level::Settled | Level::RanAway => {}
                    Level::Stopped => {
                        return Ok(finish(model, s, Status::Interrupted, Some(Error::Interrupted), curve_l, curve_u, None, control_block, start))
                    }
                }
                let mech: Vec<f64> = s.u.iter().zip(&prev.0).map(|(a, b)| a - b).collect();
                prev = save(&s);
                curve_l.push(lam);
                curve_u.push(s.u[cd]);
                let p = Progress { step: s.steps, multiplier: lam, displacement: s.u[cd], fraction: k as f64 / stages as f64, poll: false };
                if !monitor(&p) {
                    return Ok(finish(model, s, Status::Interrupted, Some(Error::Interrupted), curve_l, curve_u, Some(mech), control_block, start));
                }
                if k == stages {
                    let peak = crate::results::peak(&curve_l);
                    let n = curve_l.len();
                    let k0 = (curve_l[1] - curve_l[0]) / (curve_u[1] - curve_u[0]);
                    let kl = (curve_l[n - 1] - curve_l[n - 2]) / (curve_u[n - 1] - curve_u[n - 2]);
                    let collapsed = lam.abs() < peak.abs() * (1.0 - 1e-3) || (kl / k0).abs() < 1e-2;
                    let status = if collapsed { Status::Collapse } else { Status::Completed };
                    return Ok(finish(model, s, status, None, curve_l, curve_u, Some(mech), control_block, start));
                }
            }
            unreachable!("the loop returns at its last stage")
        }
    }
}

#[allow(clippy::too_many_arguments)]
pub(super) fn finish(
    model: &Model,
    s: Integrator,
    status: Status,
    err: Option<Error>,
    curve_l: Vec<f64>,
    curve_u: Vec<f64>,
    mechanism: Option<Vec<f64>>,
    control_block: usize,
    start: Instant,
) -> Results {
    let nb = model.n_blocks();
    let curve_l_len = curve_l.len();
    let mech = mechanism.unwrap_or_else(|| vec![0.0; 3 * nb]);
    let scale = (0..nb).map(|i| mech[3 * i].hypot(mech[3 * i + 1])).fold(0.0, f64::max);
    let work: f64 = mech.iter().zip(model.live_load()).map(|(v, f)| v * f).sum();
    let scale = if scale > 0.0 { work.signum() / scale } else { 0.0 };
    // the largest lambda at which the wall settled; a collapse multiplier only with a collapse
    let last_equilibrium = crate::results::peak(&curve_l);
    let collapse_multiplier = if status == Status::Collapse { last_equilibrium } else { f64::NAN };
    Results {
        method: "dynamic",
        status,
        error: err.map(|e| e.to_string()),
        collapse_multiplier,
        last_equilibrium,
        curve_multiplier: curve_l,
        curve_displacement: curve_u,
        control_block,
        displacements: (0..nb).map(|i| [s.u[3 * i], s.u[3 * i + 1], s.u[3 * i + 2]]).collect(),
        mechanism: (0..nb).map(|i| [mech[3 * i] * scale, mech[3 * i + 1] * scale, mech[3 * i + 2] * scale]).collect(),
        interface_forces: s.forces,
        interface_states: s.flags,
        broken: s.broken,
        iterations: s.steps,
        steps: curve_l_len,
        elapsed_s: start.elapsed().as_secs_f64(),
        certificate: None,
    }
}
