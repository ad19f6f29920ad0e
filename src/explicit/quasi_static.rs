//! Quasi-static analyses by damped relaxation: load control (each level relaxed, the collapse
//! multiplier bracketed) and displacement control, and the relaxations the static solver
//! borrows (the dead state, a jump at a prescribed displacement).

use super::*;
use std::ops::ControlFlow;

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
    let (mut last, every) = (Instant::now(), s.clock_every());
    for k in 0..max_steps {
        s.step(&mut set_ext, None);
        if k % 16 == 15 {
            if s.unbalanced_ratio(None) <= 1e-7 {
                let states = s.states();
                return Ok((s.m.u, states));
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
        if monitor_due(k, every, &mut last) {
            let p = Progress { step: k + 1, multiplier: 0.0, displacement: f64::NAN, fraction: f64::NAN, poll: false, time: f64::NAN };
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
                return Ok((s.m.u, states, lam.get()));
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
    let control_block = check_options(model, opts)?;
    let (s, setting) = integrator(model, opts)?;
    let mut run = QuasiStatic::new(s, setting, opts, control_block, start);
    let end = match run.settle_dead_loads(monitor) {
        ControlFlow::Break(end) => end,
        ControlFlow::Continue((dead_steps, limits)) => match opts.control {
            Control::Load => run.load_control(&limits, monitor),
            Control::Displacement { max_displacement } => run.displacement_control(max_displacement, dead_steps, monitor),
        },
    };
    let res = run.finish(end);
    if res.status == Status::Collapse && crate::static_solver::exact_by_limit_analysis(model) {
        return super::evidence::check_collapse(model, opts, res, monitor);
    }
    Ok(res)
}

/// The integrator of a quasi-static run of `model` with `opts` (finite rotations, the contact
/// update) and what its levels read of the model, its time step checked against the
/// relaxation's needs.
pub(super) fn integrator<'m>(model: &'m Model, opts: &ExplicitOptions) -> Result<(Integrator<'m>, Setting), Error> {
    // with the update, a time step also stable for a block touching along every edge
    let dt = match opts.contact_update {
        true => Some(checked_time_step(update::critical_time_step_moving(model), opts.time_step, opts.safety, opts.damping).map_err(|e| match opts.time_step {
            Some(_) => Error::input(format!("{e} with its contacts updated (a block may touch along every edge); or set contact_update = false")),
            None => e,
        })?),
        false => opts.time_step,
    };
    let mut s = Integrator::new(model, dt, opts.safety, opts.damping, opts.threads)?;
    s.set_large(opts.large_rotations);
    if opts.contact_update {
        s.update = Some(Box::new(update::Update::new(&s)));
        update::search(&mut s);
    }
    let setting = Setting::of_plane(model);
    check_relaxation(setting.period, s.dt, opts.time_step.is_some(), opts.max_steps_per_level)?;
    Ok((s, setting))
}

/// Checks the options of a quasi-static run against the model, in the order their errors are
/// reported, before anything is allocated for the run: the control block (the model's default
/// unless given).
fn check_options(model: &Model, opts: &ExplicitOptions) -> Result<usize, Error> {
    check_run_options(model, opts)?;
    let control_block = crate::analysis::control_block(model, opts.control_block)?;
    let cd = 3 * control_block;
    if let Control::Displacement { .. } = opts.control {
        if model.fixed()[cd] || model.live_load()[cd] == 0.0 {
            return Err(Error::input(format!(
                "the control block ({}) must be free to move horizontally and carry live load",
                model.block_name(control_block)
            )));
        }
    }
    Ok(control_block)
}

/// The checks of [`check_options`] that do not read the control block.
pub(super) fn check_run_options(model: &Model, opts: &ExplicitOptions) -> Result<(), Error> {
    crate::analysis::check_path_options(opts.steps, opts.tolerance, opts.control)?;
    if !(opts.unbalanced_ratio > 0.0 && opts.unbalanced_ratio < 1.0) {
        return Err(Error::input(format!("analysis.unbalanced_ratio must lie in (0, 1), got {}", opts.unbalanced_ratio)));
    }
    if opts.max_steps_per_level == 0 {
        return Err(Error::input("max_steps_per_level must be at least 1"));
    }
    if opts.contact_update && !opts.large_rotations {
        return Err(Error::input("analysis.contact_update needs analysis.large_rotations = true: with the linearized kinematics the blocks keep the contacts of the wall as built"));
    }
    if opts.contact_update && opts.control == Control::Load {
        return Err(Error::input("analysis.contact_update needs analysis.control = \"displacement\": under load control a load level that runs away is undone, and the contacts found meanwhile could not be"));
    }
    crate::analysis::check_displacement_range(model, opts.control)?;
    model.check_supports()
}

/// How a quasi-static run ends: its status, the error that says why, and the mechanism (an
/// increment of the displacements) when the run saw one.
pub(super) struct End {
    status: Status,
    error: Option<Error>,
    mechanism: Option<Vec<f64>>,
}

impl End {
    /// The monitor stopped the run.
    fn interrupted(mechanism: Option<Vec<f64>>) -> End {
        End { status: Status::Interrupted, error: Some(Error::Interrupted), mechanism }
    }

    /// Error `e` ended the run (its status: [`Status::failure`]).
    fn failed(e: Error, mechanism: Option<Vec<f64>>) -> End {
        End { status: Status::failure(&e), error: Some(e), mechanism }
    }
}

/// A state to go back to: the displacements, the joint histories and the broken flags (a load
/// level that runs away is undone to the last settled one; displacement control measures each
/// stage's mechanism from the previous stage's).
struct Snapshot {
    u: Vec<f64>,
    hist: Vec<f64>,
    broken: Vec<bool>,
}

impl Snapshot {
    /// The state of `s` now.
    fn of<K: Kernel>(s: &K) -> Snapshot {
        let (hist, broken) = s.history();
        Snapshot { u: s.u.clone(), hist: hist.to_vec(), broken: broken.to_vec() }
    }

    /// Puts `s` back in this state, at rest.
    fn restore<K: Kernel>(&self, s: &mut K) {
        s.u.copy_from_slice(&self.u);
        let (hist, broken) = s.history_mut();
        hist.copy_from_slice(&self.hist);
        broken.copy_from_slice(&self.broken);
        s.v.fill(0.0);
        s.a.fill(0.0);
    }
}

/// When a level runs away. A block moving up to `elastic` from where the level started is the
/// wall's response to the step of load. Beyond it the wall may still be creeping towards an
/// equilibrium (near the collapse multiplier joints slip and hinges open as the forces
/// redistribute, over many time steps), and the level runs away only with evidence that it will
/// not settle: over successive windows of `window` time steps, the peak kinetic energy of each
/// at least the one before (the wall is not slowing down) while the unbalanced ratio falls too
/// slowly to reach `ratio` within `max_steps`, extrapolated from the lowest ratio of the window
/// against either
/// - the lowest of the window before, [`STRIKES`] windows in a row (a ratio that falls too
///   slowly, or rises), or
/// - the lowest of all the level's windows before, [`STALLS`] windows in a row: a ratio on a
///   plateau. A wall that runs away (wall 1 above its collapse) keeps its ratio on a plateau
///   whose lowest values go up and down by a few percent from one window to the next; the
///   first test reads each dip below the window before as a fall fast enough to settle, and
///   waits for a run of windows that happen to rise (on wall 1, 26,624 and 49,152 time steps
///   to call lambda = 0.645 a runaway, from 0.64 and from 0.6425). The second alone would call
///   a creeping wall whose ratio jumps up and falls back a runaway if it took three windows to
///   fall below its lowest again, hence the longer run (on the walls of
///   `tests/explicit_openings.rs`, seeds 0 to 59, the 1,730 levels that settle give at most two
///   windows in a row of the first test and four of the second).
///
/// A block moving more than `u_max` (or a motion that is not finite) runs away at once.
#[derive(Debug, Clone, Copy)]
pub(super) struct Limits {
    elastic: f64,
    u_max: f64,
    window: usize,
    ratio: f64,
    max_steps: usize,
}

/// Successive windows of evidence that make a runaway, the ratio's fall measured over the last
/// window (see [`Limits`]).
const STRIKES: usize = 3;
/// Successive windows of evidence that make a runaway, the ratio's fall measured from its
/// lowest in the level (see [`Limits`]).
const STALLS: usize = 5;

/// What [`Limits::ran_away`] remembers of a level's motion: the peak kinetic energy and the
/// lowest unbalanced ratio of the window so far and of the last one, the lowest ratio of the
/// windows before, and how many windows in a row gave evidence of a runaway by each test.
struct Trend {
    peak: f64,
    low: f64,
    last_peak: f64,
    last_low: f64,
    best: f64,
    strikes: usize,
    stalls: usize,
}

impl Default for Trend {
    fn default() -> Self {
        // the first window has none before it to compare with
        Trend { peak: 0.0, low: f64::INFINITY, last_peak: f64::INFINITY, last_low: f64::NAN, best: f64::NAN, strikes: 0, stalls: 0 }
    }
}

impl Limits {
    /// No limit (displacement control: the drive sets the motion).
    const NONE: Limits = Limits { elastic: f64::INFINITY, u_max: f64::INFINITY, window: usize::MAX, ratio: 0.0, max_steps: 0 };

    /// A block moving more than `u` runs away at once, whatever the trend.
    fn at(u: f64) -> Limits {
        Limits { elastic: u, u_max: u, window: usize::MAX, ratio: 0.0, max_steps: 0 }
    }

    /// Whether the level runs away after `k` time steps (a multiple of 16), a block having
    /// moved at most `moved`, with the wall's kinetic energy `ke` and unbalanced ratio `ratio`
    /// (`trend`: the level's so far).
    fn ran_away(&self, trend: &mut Trend, k: usize, moved: f64, ke: f64, ratio: f64) -> bool {
        if !moved.is_finite() || moved > self.u_max {
            return true;
        }
        trend.peak = trend.peak.max(ke);
        trend.low = trend.low.min(ratio);
        if k % self.window != 0 {
            return false;
        }
        // whether, at the rate the ratio fell from `from` over this window, it would not reach
        // `ratio` within the steps allowed (none: it did not fall)
        let late = |from: f64| {
            let fell = from - trend.low;
            let needed = if fell > 0.0 { (trend.low - self.ratio) / fell } else { f64::INFINITY };
            k as f64 + needed * self.window as f64 > self.max_steps as f64
        };
        let running = moved > self.elastic && trend.peak >= trend.last_peak;
        trend.strikes = if running && late(trend.last_low) { trend.strikes + 1 } else { 0 };
        trend.stalls = if running && late(trend.best) { trend.stalls + 1 } else { 0 };
        // (the first window sets `best`: f64::min takes the number over NaN)
        (trend.last_peak, trend.last_low, trend.best) = (trend.peak, trend.low, trend.best.min(trend.low));
        (trend.peak, trend.low) = (0.0, f64::INFINITY);
        trend.strikes >= STRIKES || trend.stalls >= STALLS
    }
}

/// Load control between levels: the scale of the loads, the next step of lambda, the last
/// lambda at which the wall settled and its state, and the last mechanism seen (the motion of
/// the last level that ran away).
struct LoadSteps {
    scale: f64,
    dl: f64,
    lam_conv: f64,
    saved: Snapshot,
    mechanism: Option<Vec<f64>>,
}

/// Displacement control between stages: where the control dof started and how far it goes, in
/// how many stages, the time steps the dead state took to settle (the drives' pace), lambda,
/// and the state at the end of the previous stage.
struct Stages {
    u_start: f64,
    max_displacement: f64,
    count: usize,
    dead_steps: usize,
    lam: f64,
    prev: Snapshot,
}

/// What a quasi-static run reads of its model, whatever the dimension: the dead and live loads
/// (per dof), the wall's size \[m\] and the scale of lambda.
pub(super) struct Setting {
    pub(super) fd: Vec<f64>,
    pub(super) fl: Vec<f64>,
    pub(super) size: f64,
    pub(super) scale: f64,
    /// the control block's dof the curve follows (0: the first)
    pub(super) offset: usize,
    /// a lower bound of the period of the wall's slowest vibration \[s\] ([`vertical_period`])
    pub(super) period: f64,
}

impl Setting {
    fn of_plane(model: &Model) -> Setting {
        let free = (0..model.n_blocks()).filter(|&i| !model.fixed()[3 * i + 1]).map(|i| model.mass()[i]);
        let period = vertical_period(free.sum(), model.base_stiffness());
        Setting { fd: model.dead_load().to_vec(), fl: model.live_load().to_vec(), size: model.size(), scale: crate::analysis::lambda_scale(model), offset: 0, period }
    }
}

/// The period of a wall of mass `mass` \[kg\] (its blocks free to move vertically) on base
/// joints of normal stiffness `base_stiffness` \[N/m\] moving as one body, `2 pi sqrt(mass / K)`
/// (infinite without a base): by Rayleigh's principle no longer than the period of the wall's
/// slowest vibration, whatever its joints above the base.
pub(super) fn vertical_period(mass: f64, base_stiffness: f64) -> f64 {
    2.0 * std::f64::consts::PI * (mass / base_stiffness).sqrt()
}

/// Refuses a time step `dt` given by the caller on which a wall whose slowest vibration is at
/// least `period` long cannot settle under its dead loads within the `max_steps` time steps a
/// level may take (it would end in "no equilibrium under the dead loads alone"): the
/// relaxations of the dead loads took at least 6.6 of those periods on the walls measured (a
/// leaf; 7.5 a cube, 9 the plane's walls, 31 a column of 20 blocks, 36 a U wall), one is the
/// least any can take.
pub(super) fn check_relaxation(period: f64, dt: f64, given: bool, max_steps: usize) -> Result<(), Error> {
    let needed = period / dt;
    if given && needed > max_steps as f64 {
        return Err(Error::input_at("analysis.time_step", format!(
            "analysis.time_step = {dt:.3e} s is too small to relax the wall: its weight on its base joints vibrates with a period of at least {period:.3e} s (2 pi sqrt(mass / the base joints' normal stiffness)), and settling under the dead loads alone takes more than one period, at least {needed:.3e} time steps of this one, more than the {max_steps} a load level may take; leave time_step out (the stability limit's) or take at least {:.3e} s",
            period / max_steps as f64
        )));
    }
    Ok(())
}

/// A quasi-static run: the integrator (of either dimension), what each level reads (the
/// options, the control dof, the dead and live loads), and the curve so far.
pub(super) struct QuasiStatic<'a, K: Kernel> {
    opts: &'a ExplicitOptions,
    s: K,
    nb: usize,
    cd: usize,
    control_block: usize,
    fd: Vec<f64>,
    fl: Vec<f64>,
    size: f64,
    scale: f64,
    curve_l: Vec<f64>,
    curve_u: Vec<f64>,
    /// The lowest load level that ran away above the highest that settled (NaN before one
    /// does): the bracket's upper end.
    ran_away_at: f64,
    start: Instant,
}

impl<'a, K: Kernel> QuasiStatic<'a, K> {
    /// The run on integrator `s` (at rest) of a model read as `setting`, with `opts` (already
    /// checked), with an empty curve.
    pub(super) fn new(s: K, setting: Setting, opts: &'a ExplicitOptions, control_block: usize, start: Instant) -> Self {
        let Setting { fd, fl, size, scale, offset, .. } = setting;
        QuasiStatic {
            opts,
            nb: fd.len() / K::DOF,
            s,
            cd: K::DOF * control_block + offset,
            control_block,
            fd,
            fl,
            size,
            scale,
            curve_l: vec![],
            curve_u: vec![],
            ran_away_at: f64::NAN,
            start,
        }
    }

    /// Relaxes the wall at multiplier `lam` (or, with `drive`, with the control dof held at
    /// that value and lambda from its equation) until the unbalanced-force ratio is below the
    /// options', calling the monitor when due. The level runs away as `limits` judge it
    /// ([`Limits::ran_away`]), or when it does not settle within the options' steps per level.
    fn relax(&mut self, lam: &mut f64, drive: Option<f64>, limits: &Limits, monitor: &mut dyn FnMut(&Progress) -> bool) -> Level {
        let (opts, nb, cd, fd, fl) = (self.opts, self.nb, self.cd, &self.fd, &self.fl);
        let s = &mut self.s;
        let u0 = s.u.clone();
        let lam_cell = std::cell::Cell::new(*lam);
        let loads = |f: &mut [f64], l: f64| {
            for d in 0..f.len() {
                f[d] = fd[d] + l * fl[d];
            }
        };
        // a level of load control: the loads set once, for all its time steps (each step would
        // set them to the same numbers)
        if drive.is_none() {
            loads(&mut s.f_ext, *lam);
        }
        let mut set_ext = |f: &mut [f64], fint: &[f64]| {
            if drive.is_some() {
                lam_cell.set((fint[cd] - fd[cd]) / fl[cd]);
                loads(f, lam_cell.get());
            }
        };
        let mut trend = Trend::default();
        let (mut last, every) = (Instant::now(), s.clock_every());
        for k in 0..opts.max_steps_per_level {
            s.step(&mut set_ext, drive.map(|x| (cd, x)));
            *lam = lam_cell.get();
            if k % 16 == 15 {
                let ratio = s.unbalanced_ratio(drive.map(|_| cd));
                if ratio <= opts.unbalanced_ratio {
                    return Level::Settled;
                }
                let moved = (0..nb).map(|i| K::translation(&s.u, Some(&u0), i)).fold(0.0, f64::max);
                if limits.ran_away(&mut trend, k + 1, moved, s.kinetic_energy(), ratio) {
                    return Level::RanAway;
                }
            }
            if monitor_due(k, every, &mut last) {
                let p = Progress { step: s.steps, multiplier: *lam, displacement: s.u[cd], fraction: f64::NAN, poll: false, time: f64::NAN };
                if !monitor(&p) {
                    return Level::Stopped;
                }
            }
        }
        Level::RanAway
    }

    /// Relaxes the wall under its dead loads (a block moving more than 1% of the wall's size
    /// means it does not stand), then holds the dofs held after them and starts the curve at
    /// lambda = 0: the time steps the dead state took, and the limits of the motion of a load
    /// level after it.
    pub(super) fn settle_dead_loads(&mut self, monitor: &mut dyn FnMut(&Progress) -> bool) -> ControlFlow<End, (usize, Limits)> {
        let size = self.size;
        let mut lam = 0.0;
        let steps_before = self.s.steps;
        match self.relax(&mut lam, None, &Limits::at(1e-2 * size), monitor) {
            Level::Settled => {}
            Level::Stopped => return ControlFlow::Break(End::interrupted(None)),
            Level::RanAway => {
                let e = Error::Mechanism("no equilibrium under the dead loads alone (the wall does not settle)".into());
                return ControlFlow::Break(End::failed(e, None));
            }
        }
        let dead_steps = self.s.steps - steps_before;
        let s = &mut self.s;
        s.v.fill(0.0);
        s.hold();
        self.curve_l.push(0.0);
        self.curve_u.push(s.u[self.cd]);
        // displacements beyond 20 x the settlement under dead load (at least 1e-4 of the wall) are
        // no elastic response: a mechanism, running or creeping; beyond 1% of the wall, as under
        // the dead loads, one that does not stop. The windows of its trend: the time the dead
        // state took to settle (at least 1,024 time steps), a multiple of 16 steps.
        let settle = (0..self.nb).map(|i| K::translation(&s.u, None, i)).fold(0.0, f64::max);
        let window = dead_steps.max(1024).div_ceil(16) * 16;
        let (ratio, max_steps) = (self.opts.unbalanced_ratio, self.opts.max_steps_per_level);
        let limits = Limits { elastic: (20.0 * settle).max(1e-4 * size), u_max: 1e-2 * size, window, ratio, max_steps };
        ControlFlow::Continue((dead_steps, limits))
    }

    /// Load control: levels of lambda, each relaxed until the wall settles; a level at which it
    /// runs away (as `limits` judge it) is undone and the step halved, until the bracket on the
    /// collapse multiplier is within the tolerance.
    pub(super) fn load_control(&mut self, limits: &Limits, monitor: &mut dyn FnMut(&Progress) -> bool) -> End {
        let scale = self.scale;
        let dl = 4.0 * scale / self.opts.steps as f64;
        let mut steps = LoadSteps { scale, dl, lam_conv: 0.0, saved: Snapshot::of(&self.s), mechanism: None };
        let max_levels = 100 * self.opts.steps + 1000;
        for _ in 0..max_levels {
            if let ControlFlow::Break(end) = self.load_level(&mut steps, limits, monitor) {
                return end;
            }
        }
        let e = Error::Convergence(format!("no collapse bracket after {max_levels} load levels"));
        End::failed(e, steps.mechanism)
    }

    /// One level of load control, at the last settled lambda plus the step. Settled, it extends
    /// the curve (the run ends if the monitor says stop or lambda leaves its range); run away,
    /// it is undone and the step halved (the run ends with a collapse once the bracket is
    /// within the tolerance).
    fn load_level(&mut self, st: &mut LoadSteps, limits: &Limits, monitor: &mut dyn FnMut(&Progress) -> bool) -> ControlFlow<End> {
        let mut l = st.lam_conv + st.dl;
        match self.relax(&mut l, None, limits, monitor) {
            Level::Settled => {
                // a level that ran away below one that settles was no evidence of a collapse
                // (the wall crept on from a state nearer its equilibrium): the bracket's upper
                // end is a level above the highest that settled
                if l >= self.ran_away_at {
                    self.ran_away_at = f64::NAN;
                }
                st.lam_conv = l;
                st.saved = Snapshot::of(&self.s);
                self.s.v.fill(0.0);
                self.curve_l.push(l);
                self.curve_u.push(self.s.u[self.cd]);
                let p = Progress { step: self.s.steps, multiplier: l, displacement: self.s.u[self.cd], fraction: f64::NAN, poll: false, time: f64::NAN };
                if !monitor(&p) {
                    return ControlFlow::Break(End::interrupted(None));
                }
                if st.lam_conv > crate::analysis::UNBOUNDED * st.scale {
                    let e = Error::Convergence(crate::results::unbounded_message(st.lam_conv));
                    return ControlFlow::Break(End { status: Status::Unbounded, error: Some(e), mechanism: None });
                }
            }
            Level::Stopped => {
                st.saved.restore(&mut self.s);
                return ControlFlow::Break(End::interrupted(None));
            }
            Level::RanAway => {
                self.ran_away_at = self.ran_away_at.min(l);
                st.mechanism = Some(self.s.u.iter().zip(&st.saved.u).map(|(a, b)| a - b).collect::<Vec<f64>>());
                st.saved.restore(&mut self.s);
                st.dl *= 0.5;
                if 2.0 * st.dl <= self.opts.tolerance * st.lam_conv.abs().max(1e-3 * st.scale) {
                    self.s.interface_forces();
                    return ControlFlow::Break(End { status: Status::Collapse, error: None, mechanism: st.mechanism.take() });
                }
            }
        }
        ControlFlow::Continue(())
    }

    /// Displacement control: the control dof driven to `max_displacement` from where the dead
    /// loads left it, in stages, lambda from the control dof's equation.
    pub(super) fn displacement_control(&mut self, max_displacement: f64, dead_steps: usize, monitor: &mut dyn FnMut(&Progress) -> bool) -> End {
        let mut st = Stages {
            u_start: self.s.u[self.cd],
            max_displacement,
            count: self.opts.steps,
            dead_steps,
            // every drive sets lambda before it is read
            lam: 0.0,
            prev: Snapshot::of(&self.s),
        };
        for k in 1..=st.count {
            if let ControlFlow::Break(end) = self.stage(&mut st, k, monitor) {
                return end;
            }
        }
        unreachable!("the loop returns at its last stage")
    }

    /// Stage `k` of displacement control: the control dof driven to its target, the wall
    /// relaxed holding it there, and the curve extended. The run ends if the monitor says stop,
    /// and at the last stage (see [`QuasiStatic::displacement_status`]); the mechanism is the
    /// stage's increment.
    fn stage(&mut self, st: &mut Stages, k: usize, monitor: &mut dyn FnMut(&Progress) -> bool) -> ControlFlow<End> {
        let target = st.u_start + st.max_displacement * k as f64 / st.count as f64;
        self.drive(target, st.dead_steps, &mut st.lam);
        match self.relax(&mut st.lam, Some(target), &Limits::NONE, monitor) {
            Level::Settled | Level::RanAway => {}
            Level::Stopped => return ControlFlow::Break(End::interrupted(None)),
        }
        let mech: Vec<f64> = self.s.u.iter().zip(&st.prev.u).map(|(a, b)| a - b).collect();
        st.prev = Snapshot::of(&self.s);
        self.curve_l.push(st.lam);
        self.curve_u.push(self.s.u[self.cd]);
        let fraction = k as f64 / st.count as f64;
        let p = Progress { step: self.s.steps, multiplier: st.lam, displacement: self.s.u[self.cd], fraction, poll: false, time: f64::NAN };
        if !monitor(&p) {
            return ControlFlow::Break(End::interrupted(Some(mech)));
        }
        if k == st.count {
            let status = self.displacement_status(st.lam);
            return ControlFlow::Break(End { status, error: None, mechanism: Some(mech) });
        }
        ControlFlow::Continue(())
    }

    /// A support's movement: the control dof (a support's, held by the model: only the drive
    /// moves it) driven by `max_displacement` from where it is, in the options' stages, each
    /// relaxed with the support held at its target, lambda from its equation (from the force
    /// the support takes under the dead loads, where the curve starts). The first stage
    /// at which the wall does not settle ends the run as a collapse, the wall fallen between the
    /// stage before and it: a block moves more than `fall` \[m\] from where the drive left it,
    /// or the unbalanced ratio stays above the options' within their steps per level. The curve
    /// holds the stages that settled; the mechanism is the fallen stage's motion.
    pub(super) fn movement_control(&mut self, max_displacement: f64, dead_steps: usize, fall: f64, monitor: &mut dyn FnMut(&Progress) -> bool) -> End {
        let (u_start, count) = (self.s.u[self.cd], self.opts.steps);
        // the support is held under the dead loads: the curve starts at the force it takes there
        let cd = self.cd;
        let mut lam = (self.s.f_int[cd] - self.fd[cd]) / self.fl[cd];
        self.curve_l[0] = lam;
        for k in 1..=count {
            let before = Snapshot::of(&self.s);
            let target = u_start + max_displacement * k as f64 / count as f64;
            self.drive(target, dead_steps, &mut lam);
            match self.relax(&mut lam, Some(target), &Limits::at(fall), monitor) {
                Level::Settled => {}
                Level::Stopped => return End::interrupted(None),
                Level::RanAway => {
                    let mech = self.s.u.iter().zip(&before.u).map(|(a, b)| a - b).collect();
                    return End { status: Status::Collapse, error: None, mechanism: Some(mech) };
                }
            }
            self.s.v.fill(0.0);
            self.curve_l.push(lam);
            self.curve_u.push(self.s.u[self.cd]);
            let p = Progress { step: self.s.steps, multiplier: lam, displacement: self.s.u[self.cd], fraction: k as f64 / count as f64, poll: false, time: f64::NAN };
            if !monitor(&p) {
                return End::interrupted(None);
            }
        }
        let e = Error::Convergence(format!("the wall stood at every stage, up to the movement's end ({max_displacement:e} m): no collapse"));
        End { status: Status::Completed, error: Some(e), mechanism: None }
    }

    /// Drives the control dof from where it is to `target` over a few hundred time steps or
    /// more, lambda (into `lam`) from its equation, before a stage's relaxation.
    fn drive(&mut self, target: f64, dead_steps: usize, lam: &mut f64) {
        let (cd, fd, fl) = (self.cd, &self.fd, &self.fl);
        let s = &mut self.s;
        let from = s.u[cd];
        // slowly, over five times the dead state's settling time: a fast drive makes the
        // control block slip locally against the inertia of the rest of the wall (wall 1:
        // peak 0.595 over 200 steps, 0.635 over 2,000, 0.641 over 10,000)
        let n_drive = (5 * dead_steps).max(200);
        let mut set_ext = |f: &mut [f64], fint: &[f64]| {
            *lam = (fint[cd] - fd[cd]) / fl[cd];
            for d in 0..f.len() {
                f[d] = fd[d] + *lam * fl[d];
            }
        };
        for j in 1..=n_drive {
            let x = from + (target - from) * j as f64 / n_drive as f64;
            s.step(&mut set_ext, Some((cd, x)));
        }
    }

    /// How displacement control ends, at lambda `lam` after its last stage: a collapse if lambda
    /// has fallen from its peak or the curve has flattened
    /// ([`crate::analysis::displacement_collapse`], as the static solver's), else completed; and
    /// completed where the contact update has made contacts the wall as built did not have: the
    /// curve has met them (a block leaning on another, an impact), its peak is no collapse
    /// multiplier.
    fn displacement_status(&self, lam: f64) -> Status {
        if self.s.contacts_created() > 0 {
            return Status::Completed;
        }
        let (curve_l, curve_u) = (&self.curve_l, &self.curve_u);
        let peak = crate::results::peak(curve_l);
        let n = curve_l.len();
        let k0 = (curve_l[1] - curve_l[0]) / (curve_u[1] - curve_u[0]);
        let kl = (curve_l[n - 1] - curve_l[n - 2]) / (curve_u[n - 1] - curve_u[n - 2]);
        if crate::analysis::displacement_collapse(lam, peak, k0, kl) {
            Status::Collapse
        } else {
            Status::Completed
        }
    }

    /// The results of the run, ended by `end`: the curve, the state reached, and the mechanism
    /// scaled to a largest block translation of 1 and oriented so that the live load does
    /// positive work on it (zero without one).
    pub(super) fn finish(self, end: End) -> Results<K::V> {
        let End { status, error: err, mechanism } = end;
        let (s, curve_l, curve_u) = (self.s, self.curve_l, self.curve_u);
        let nb = self.nb;
        let curve_l_len = curve_l.len();
        let mech = mechanism.unwrap_or_else(|| vec![0.0; K::DOF * nb]);
        let scale = (0..nb).map(|i| K::translation(&mech, None, i)).fold(0.0, f64::max);
        let work: f64 = mech.iter().zip(&self.fl).map(|(v, f)| v * f).sum();
        let scale = if scale > 0.0 { work.signum() / scale } else { 0.0 };
        // the largest lambda at which the wall settled; a collapse multiplier only with a collapse
        let last_equilibrium = crate::results::peak(&curve_l);
        let collapse_multiplier = if status == Status::Collapse { last_equilibrium } else { f64::NAN };
        // load control: the highest level that settled and the lowest that ran away
        let bracket = (status == Status::Collapse && self.ran_away_at.is_finite()).then_some([last_equilibrium, self.ran_away_at]);
        let mech: Vec<f64> = mech.iter().map(|x| x * scale).collect();
        let steps = s.steps;
        let displacements = (0..nb).map(|i| K::block(&s.u, i)).collect();
        let (interface_forces, interface_states, broken) = s.into_contacts();
        Results {
            method: "dynamic",
            status,
            error: err.map(|e| e.to_string()),
            collapse_multiplier,
            last_equilibrium,
            curve_multiplier: curve_l,
            curve_displacement: curve_u,
            control_block: self.control_block,
            displacements,
            mechanism: (0..nb).map(|i| K::block(&mech, i)).collect(),
            interface_forces,
            interface_states,
            broken,
            iterations: steps,
            steps: curve_l_len,
            elapsed_s: self.start.elapsed().as_secs_f64(),
            bracket,
            certificate: None,
        }
    }
}
