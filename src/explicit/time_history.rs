//! Time histories: free motion from initial conditions, or a horizontal base acceleration.

use super::*;
use std::ops::ControlFlow;
use crate::interface::Family;

/// Integrates the equations of motion in time (free motion, base acceleration).
pub fn simulate(model: &Model, opts: &DynamicOptions) -> Result<TimeHistory, Error> {
    simulate_with(model, opts, &mut |_| true)
}

/// As [`simulate`], calling `monitor` every few thousand steps (return false to stop).
pub fn simulate_with(model: &Model, opts: &DynamicOptions, monitor: &mut dyn FnMut(&Progress) -> bool) -> Result<TimeHistory, Error> {
    model.check_analysis_memory("a time history")?;
    let start = Instant::now();
    check_options(model, opts)?;
    let nb = model.n_blocks();
    let dt = history_time_step(model, opts)?;
    let mut s = Integrator::new(model, Some(dt), opts.safety, opts.damping, opts.threads)?;
    s.set_large(opts.large_rotations);
    set_initial_state(&mut s, opts);
    s.start_dynamics(opts.stiffness_damping);
    if updating(opts) {
        s.update = Some(Box::new(update::Update::new(&s)));
        update::search(&mut s);
    }
    let loads = Loads::new(model.dead_load(), model.live_load(), opts, &s);
    run_history(s, loads, opts, nb, start, monitor)
}

/// A time history on integrator `s` (its initial state and dashpots set) under `loads`: the
/// loop both dimensions share.
pub(super) fn run_history<V: Copy, K: Recorded<V = V>>(
    mut s: K,
    loads: Loads,
    opts: &DynamicOptions<V>,
    nb: usize,
    start: Instant,
    monitor: &mut dyn FnMut(&Progress) -> bool,
) -> Result<TimeHistory<V>, Error> {
    loads.apply(&mut s.f_ext, 0.0);
    s.interface_forces();
    s.accelerations();
    let n_steps = count_time_steps(opts.duration, s.dt)?;
    let h = TimeHistory::reserved(opts, s.dt, n_steps, nb, K::DOF == 6)?;
    // work of the external forces, by the trapezoidal rule on each step
    let (f_prev, fi_prev, u_prev) = (s.f_ext.clone(), s.f_int.clone(), s.u.clone());
    let (ke0, ee0, u0) = (s.kinetic_energy(), s.elastic_energy(), s.u.clone());
    let mut run = Run { s, loads, h, n_steps, record: opts.record, work: 0.0, joints: 0.0, f_prev, fi_prev, u_prev, ke0, ee0, u0 };
    run.record(0.0);
    run.integrate(monitor);
    let Run { s, mut h, .. } = run;
    s.finish(&mut h);
    h.steps = s.steps;
    h.elapsed_s = start.elapsed().as_secs_f64();
    Ok(h)
}

/// What a time history records of an integrator of either dimension, beyond its motion.
pub(super) trait Recorded: Kernel {
    /// Block `i`'s displacements and velocities for the records.
    fn record_block(&self, i: usize) -> (Self::V, Self::V);
    /// The force of the wall on its base along x and y \[N\].
    fn base_shear(&self) -> [f64; 2];
    /// The work of the weights since displacements `u0` \[J\].
    fn gravity_work(&self, u0: &[f64]) -> f64;
    fn elastic_energy(&self) -> f64;
    /// The energy the contact dashpots dissipated: their impacts' share and the
    /// stiffness-proportional damping's \[J\].
    fn dashpot_dissipation(&self) -> (f64, f64);
    /// Why the state lies beyond the model's range, if it does (see [`out_of_range`]).
    fn out_of_range(&self, u0: &[f64]) -> Option<String>;
    /// What the contact update has to add to the history at the end of the run.
    fn finish(&self, _h: &mut TimeHistory<Self::V>) {}
    /// The ground acceleration that acts on dof `d`: 0 along x, 1 along y, 2 vertical, 3 none.
    fn ground_axis(d: usize) -> u8;
}

impl Recorded for Integrator<'_> {
    fn record_block(&self, i: usize) -> ([f64; 3], [f64; 3]) {
        ([self.u[3 * i], self.u[3 * i + 1], self.u[3 * i + 2]], [self.v[3 * i], self.v[3 * i + 1], self.v[3 * i + 2]])
    }
    fn base_shear(&self) -> [f64; 2] {
        [self.model.base().map_or(0.0, |i| -self.f_int[3 * i]), 0.0]
    }
    fn gravity_work(&self, u0: &[f64]) -> f64 {
        let (model, g) = (self.model, self.model.gravity_direction());
        (0..model.n_blocks())
            .map(|i| model.weight()[i] * (g[0] * (self.u[3 * i] - u0[3 * i]) + g[1] * (self.u[3 * i + 1] - u0[3 * i + 1])))
            .sum()
    }
    fn elastic_energy(&self) -> f64 {
        Integrator::elastic_energy(self)
    }
    fn dashpot_dissipation(&self) -> (f64, f64) {
        let dropped = self.update.as_ref().map_or((0.0, 0.0), |up| up.dropped_dissipation);
        self.dynm.iter().fold(dropped, |(i, k), x| (i + x.damped, k + x.stiffness_damped))
    }
    fn finish(&self, h: &mut TimeHistory) {
        let Some(up) = &self.update else { return };
        up.report(h);
        h.contacts = update::contacts(self);
        h.contact_events = up.events.clone();
    }
    fn out_of_range(&self, u0: &[f64]) -> Option<String> {
        out_of_range(self, u0)
    }
    fn ground_axis(d: usize) -> u8 {
        [0, 2, 3][d % 3]
    }
}

/// The stable time step of a time history of `model` \[s\]: [`critical_time_step`] lowered for
/// the contact dashpots of its joints' restitution and for stiffness-proportional damping
/// `beta` \[s\] ([`contact::stability_factor`] of 3 zeta + beta omega_max / 2: a block rocking
/// on a dashpot of damping ratio zeta has up to 3 zeta, and beta K gives the fastest mode
/// beta omega_max / 2).
/// With the contact update (`contact_update`, a time history's default) the limit is that of a
/// model whose blocks may touch along every edge (see the module's notes on the contact update),
/// lower or equal.
pub fn history_time_step_limit(model: &Model, beta: f64, contact_update: bool) -> f64 {
    let crit = if contact_update { update::critical_time_step_moving(model) } else { critical_time_step(model) };
    dashpot_limit(model, crit, beta)
}

/// The stability limit `crit` lowered for the contact dashpots of the joints of `model` and for
/// stiffness-proportional damping `beta` (see [`history_time_step_limit`]).
fn dashpot_limit(model: &Model, crit: f64, beta: f64) -> f64 {
    crit * contact::stability_factor(3.0 * max_damping_ratio(model.laws()) + beta / crit)
}

/// The time step of a time history: the given one, or `safety` times the stability limit, both
/// within that limit lowered for the contact dashpots (see [`contact::stability_factor`]: the
/// rocking of a block on a dashpot of damping ratio zeta has up to 3 zeta).
fn history_time_step(model: &Model, opts: &DynamicOptions) -> Result<f64, Error> {
    updated_time_step(|| critical_time_step(model), || update::critical_time_step_moving(model), |crit| dashpot_limit(model, crit, opts.stiffness_damping), opts)
}

/// The time step of a time history of either dimension: the stability limit `crit` of its
/// model, or with the contact update `moving` (a block touching along every edge or face), each
/// lowered by `limit` for the dashpots; a given time step beyond the latter with the update on
/// is refused.
pub(super) fn updated_time_step<V>(crit: impl FnOnce() -> f64, moving: impl FnOnce() -> f64, limit: impl FnOnce(f64) -> f64, opts: &DynamicOptions<V>) -> Result<f64, Error> {
    let crit = if updating(opts) { moving() } else { crit() };
    let limit = limit(crit);
    match opts.time_step {
        Some(dt) if updating(opts) && dt.is_finite() && dt > limit => Err(Error::input(format!(
            "analysis.time_step = {dt:.3e} s exceeds the stability limit of this model with its contacts updated (a block may touch along every edge) and their dashpots, {limit:.3e} s; or set contact_update = false"
        ))),
        _ => dashpot_time_step(crit, limit, opts),
    }
}

/// Whether a time history under `opts` updates its contacts: asked, with finite rotations.
pub(super) fn updating<V>(opts: &DynamicOptions<V>) -> bool {
    opts.contact_update && opts.large_rotations
}

/// The largest damping ratio of the contact dashpots of the joints `laws`.
pub(super) fn max_damping_ratio(laws: &crate::model::JointLaws) -> f64 {
    [Family::Bed, Family::Head, Family::Base, Family::Top].iter().map(|&f| contact::damping_ratio(laws.of(f).restitution)).fold(0.0, f64::max)
}

/// The time step of a time history of stability limit `crit`, `limit` with its dashpots (see
/// [`history_time_step`]).
pub(super) fn dashpot_time_step<V>(crit: f64, limit: f64, opts: &DynamicOptions<V>) -> Result<f64, Error> {
    match opts.time_step {
        Some(dt) if dt.is_finite() && dt > limit && dt <= crit => Err(Error::input(format!(
            "analysis.time_step = {dt:.3e} s exceeds the stability limit of this model with its contact dashpots (restitution), {limit:.3e} s"
        ))),
        Some(dt) => Ok(dt),
        None if !(opts.safety > 0.0 && opts.safety <= 1.0) => Err(Error::input(format!("safety must lie in (0, 1], got {}", opts.safety))),
        None if !crit.is_finite() => Err(Error::input("no stiffness holds the model: no stable time step")),
        None => Ok(opts.safety * limit),
    }
}

/// Checks the options of a time history against the model, in the order their errors are
/// reported, before the integrator is built.
fn check_options(model: &Model, opts: &DynamicOptions) -> Result<(), Error> {
    check_common(opts, model.n_blocks())?;
    if opts.base_acceleration_y.is_some() {
        return Err(Error::input("base_acceleration_y: a plane model moves in x and z; the base acceleration along y is for 3D models"));
    }
    model.check_supports()?;
    let ground = opts.base_acceleration.is_some() || opts.vertical_acceleration.is_some();
    if ground && model.gravity_direction() != [0.0, -1.0] {
        return Err(Error::input_at(
            "loads.gravity_direction",
            "a ground motion acts along x and y: a time history under one takes gravity along -y (loads.gravity_direction = [0, -1]); turn the record, not the wall",
        ));
    }
    if !model.held_after_dead().is_empty() {
        return Err(Error::input(
            "top.vertical = \"held\" is for quasi-static analyses (held once the dead loads are on); a time history loads the beam with its force: use top.vertical = \"free\"",
        ));
    }
    Ok(())
}

/// Checks the options of a time history either dimension reads, for a model of `nb` blocks.
pub(super) fn check_common<V: AsRef<[f64]>>(opts: &DynamicOptions<V>, nb: usize) -> Result<(), Error> {
    if !(opts.duration.is_finite() && opts.duration > 0.0) {
        return Err(Error::input(format!("duration must be a finite number > 0, got {}", opts.duration)));
    }
    match opts.record {
        Recording::Every(0) => return Err(Error::input("record_every must be at least 1")),
        Recording::Interval(i) if !(i.is_finite() && i > 0.0) => {
            return Err(Error::input(format!("record_interval must be a finite number of seconds > 0, got {i}")))
        }
        _ => {}
    }
    if !(opts.stiffness_damping.is_finite() && opts.stiffness_damping >= 0.0) {
        return Err(Error::input(format!("stiffness_damping (beta) must be a finite number of seconds >= 0, got {}", opts.stiffness_damping)));
    }
    if !opts.live_multiplier.is_finite() {
        return Err(Error::input("live_multiplier must be finite"));
    }
    for (what, series) in [("base_acceleration", &opts.base_acceleration), ("base_acceleration_y", &opts.base_acceleration_y), ("vertical_acceleration", &opts.vertical_acceleration)] {
        if let Some((t, a)) = series {
            if t.len() != a.len() || t.is_empty() {
                return Err(Error::input(format!(
                    "{what}: times and accelerations must be non-empty and of equal length (got {} and {})",
                    t.len(),
                    a.len()
                )));
            }
            if t.iter().chain(a).any(|x| !x.is_finite()) || t.windows(2).any(|w| w[1] <= w[0]) {
                return Err(Error::input(format!("{what}: times must increase and every value must be finite")));
            }
        }
    }
    for (what, init) in [("initial_displacement", &opts.initial_displacement), ("initial_velocity", &opts.initial_velocity)] {
        if let Some(v) = init {
            if v.len() != nb {
                return Err(Error::input(format!("{what}: expected {nb} rows (one per block), got {}", v.len())));
            }
            if v.iter().flat_map(|x| x.as_ref()).any(|x| !x.is_finite()) {
                return Err(Error::input(format!("{what}: every value must be finite")));
            }
        }
    }
    Ok(())
}

/// Sets the options' initial displacements and velocities on the free dofs of `s`; the fixed
/// dofs keep the model's prescribed values, at rest.
fn set_initial_state(s: &mut Integrator, opts: &DynamicOptions) {
    let fixed = s.model.fixed();
    let nb = s.model.n_blocks();
    if let Some(u0) = &opts.initial_displacement {
        for i in 0..nb {
            for k in 0..3 {
                if !fixed[3 * i + k] {
                    s.u[3 * i + k] = u0[i][k];
                }
            }
        }
    }
    if let Some(v0) = &opts.initial_velocity {
        for i in 0..nb {
            for k in 0..3 {
                if !fixed[3 * i + k] {
                    s.v[3 * i + k] = v0[i][k];
                }
            }
        }
    }
}

/// The time steps that cover the options' duration at time step `dt`, refused beyond
/// [`MAX_TIME_STEPS`].
pub(super) fn count_time_steps(duration: f64, dt: f64) -> Result<usize, Error> {
    let n_steps_f = (duration / dt).ceil();
    if !(n_steps_f <= MAX_TIME_STEPS as f64) {
        return Err(Error::input(format!(
            "duration = {duration} s with a time step of {dt:.3e} s is {n_steps_f:.0} time steps, more than the limit of {MAX_TIME_STEPS}"
        )));
    }
    Ok(n_steps_f as usize)
}

/// The external forces of a time history: the dead loads, the live loads times a constant
/// multiplier, and the inertial forces `-m a_g(t)` of a horizontal base acceleration (the
/// blocks move in the frame of the base).
pub(super) struct Loads {
    fd: Vec<f64>,
    fl: Vec<f64>,
    lam: f64,
    mass: Vec<f64>,
    /// the ground acceleration on each dof (see [`Recorded::ground_axis`])
    axis: Vec<u8>,
    base: Option<(Vec<f64>, Vec<f64>)>,
    base_y: Option<(Vec<f64>, Vec<f64>)>,
    vertical: Option<(Vec<f64>, Vec<f64>)>,
}

impl Loads {
    /// The dead loads `fd` and live loads `fl` under `opts`, with the masses of `s`.
    pub(super) fn new<V, K: Recorded>(fd: &[f64], fl: &[f64], opts: &DynamicOptions<V>, s: &K) -> Loads {
        Loads {
            fd: fd.to_vec(),
            fl: fl.to_vec(),
            lam: opts.live_multiplier,
            mass: s.mass.clone(),
            axis: (0..fd.len()).map(K::ground_axis).collect(),
            base: opts.base_acceleration.clone(),
            base_y: opts.base_acceleration_y.clone(),
            vertical: opts.vertical_acceleration.clone(),
        }
    }

    /// The base acceleration (along x, along y, vertical) at time `t`.
    fn ground(&self, t: f64) -> [f64; 3] {
        [sample(&self.base, t), sample(&self.base_y, t), sample(&self.vertical, t)]
    }

    /// The external forces at time `t`, into `f`.
    fn apply(&self, f: &mut [f64], t: f64) {
        let (fd, fl, lam, mass) = (&self.fd, &self.fl, self.lam, &self.mass);
        let g = self.ground(t);
        let g = [g[0], g[1], g[2], 0.0];
        for d in 0..f.len() {
            let inertia = match self.axis[d] {
                3 => 0.0,
                k => mass[d] * g[k as usize],
            };
            f[d] = fd[d] + lam * fl[d] - inertia;
        }
    }
}

/// An acceleration history at time `t`: linear between the samples, zero outside them (and
/// zero without one).
pub(super) fn sample(series: &Option<(Vec<f64>, Vec<f64>)>, t: f64) -> f64 {
    let Some((ts, a)) = series else { return 0.0 };
    let n = ts.len();
    if n == 0 || t < ts[0] || t > ts[n - 1] {
        return 0.0;
    }
    if n == 1 {
        return a[0];
    }
    let k = ts.partition_point(|&x| x <= t).clamp(1, n - 1);
    let (t0, t1) = (ts[k - 1], ts[k]);
    a[k - 1] + (a[k] - a[k - 1]) * (t - t0) / (t1 - t0)
}

/// The records a time history of `n_steps` time steps of `dt` under `record` takes: one per
/// `record_every` steps or per interval, the first and the last (an upper bound).
pub fn record_count(record: Recording, dt: f64, n_steps: usize) -> usize {
    match record {
        Recording::Every(k) => n_steps / k.max(1) + 2,
        Recording::Interval(i) => ((n_steps as f64 * dt / i).floor() as usize).min(n_steps) + 2,
    }
}

/// The bytes a time history of `model` under `opts` will hold, and its number of records:
/// per record, the displacements and velocities of every block (48 bytes a block) and 12
/// numbers (times, ground, base shear, energies). Checks the options as [`simulate`] does.
pub fn record_size(model: &Model, opts: &DynamicOptions) -> Result<(usize, f64), Error> {
    check_options(model, opts)?;
    let dt = history_time_step(model, opts)?;
    let n_steps = count_time_steps(opts.duration, dt)?;
    let records = record_count(opts.record, dt, n_steps);
    Ok((records, records as f64 * (48.0 * model.n_blocks() as f64 + 8.0 * 13.0)))
}

impl<V> TimeHistory<V> {
    /// An empty history with room for every record of `n_steps` time steps of `dt` (see
    /// [`record_count`]), reserved once so that recording does not allocate inside the time
    /// loop; refused beyond [`MAX_RECORDED_VALUES`]. `space`: a 3D model's (the y components).
    fn reserved(opts: &DynamicOptions<V>, dt: f64, n_steps: usize, nb: usize, space: bool) -> Result<TimeHistory<V>, Error> {
        let cap = record_count(opts.record, dt, n_steps);
        // two histories (displacements, velocities) of 3 (6 in 3D) values per block and record
        let stored = (if space { 12.0 } else { 6.0 }) * cap as f64 * nb as f64;
        if stored > MAX_RECORDED_VALUES as f64 {
            return Err(Error::input(format!(
                "recording {cap} states of {nb} blocks (duration {} s, time step {dt:.3e} s, {}) stores {stored:.0} numbers ({:.1} GB), more than the limit of {MAX_RECORDED_VALUES}: raise record_interval (or record_every) or shorten the duration",
                opts.duration,
                match opts.record {
                    Recording::Every(k) => format!("record_every {k}"),
                    Recording::Interval(i) => format!("record_interval {i} s"),
                },
                stored * 8e-9
            )));
        }
        let series = || Vec::with_capacity(cap);
        Ok(TimeHistory {
            status: Status::Completed,
            error: None,
            time_step: dt,
            times: series(),
            n_blocks: nb,
            displacements: Vec::with_capacity(cap * nb),
            velocities: Vec::with_capacity(cap * nb),
            ground_acceleration: Vec::with_capacity(cap),
            ground_acceleration_y: if space { series() } else { vec![] },
            base_shear: series(),
            base_shear_y: if space { series() } else { vec![] },
            kinetic_energy: series(),
            elastic_energy: series(),
            external_work: series(),
            gravity_work: series(),
            friction_dissipation: series(),
            damping_dissipation: series(),
            impact_dissipation: series(),
            dissipated: series(),
            energy_error: series(),
            steps: 0,
            elapsed_s: 0.0,
            contact_searches: 0,
            contacts_created: 0,
            contacts_dropped: 0,
            contacts_renewed: 0,
            contacts: vec![],
            contacts_3d: vec![],
            contact_events: vec![],
            ground_level: None,
        })
    }
}

/// A time history being integrated: the integrator, its loads, the history so far, the work
/// of the external forces and of the joints' forces on the blocks (the trapezoidal rule on each
/// step: the forces and displacements of the last step are kept), and the initial energies and
/// displacements.
struct Run<V, K> {
    s: K,
    loads: Loads,
    h: TimeHistory<V>,
    n_steps: usize,
    record: Recording,
    work: f64,
    joints: f64,
    f_prev: Vec<f64>,
    fi_prev: Vec<f64>,
    u_prev: Vec<f64>,
    ke0: f64,
    ee0: f64,
    u0: Vec<f64>,
}

impl<V: Copy, K: Recorded<V = V>> Run<V, K> {
    /// Records the state at time `t`: displacements, velocities, the ground's acceleration, the
    /// base shear and the energy balance.
    fn record(&mut self, t: f64) {
        let (s, h) = (&self.s, &mut self.h);
        let nb = h.n_blocks;
        h.times.push(t);
        h.displacements.extend((0..nb).map(|i| s.record_block(i).0));
        h.velocities.extend((0..nb).map(|i| s.record_block(i).1));
        let g = self.loads.ground(t);
        h.ground_acceleration.push([g[0], g[2]]);
        let shear = s.base_shear();
        h.base_shear.push(shear[0]);
        if K::DOF == 6 {
            h.ground_acceleration_y.push(g[1]);
            h.base_shear_y.push(shear[1]);
        }
        let (ke, ee) = (s.kinetic_energy(), s.elastic_energy());
        let gravity = s.gravity_work(&self.u0);
        // what the joints' forces took from the blocks, less what the dashpots dissipated and
        // the elastic energy gained, the joints dissipated
        let (impacts, stiffness) = s.dashpot_dissipation();
        let damping = s.damping_work + stiffness;
        let friction = self.joints - impacts - stiffness - (ee - self.ee0);
        let dissipated = friction + damping + impacts;
        h.kinetic_energy.push(ke);
        h.elastic_energy.push(ee);
        h.external_work.push(self.work);
        h.gravity_work.push(gravity);
        h.friction_dissipation.push(friction);
        h.damping_dissipation.push(damping);
        h.impact_dissipation.push(impacts);
        h.dissipated.push(dissipated);
        h.energy_error.push(self.ke0 + self.ee0 + self.work - ke - ee - dissipated);
    }

    /// Time steps 1 to `n_steps`, calling `monitor` when due (see [`monitor_due`]). A
    /// non-finite displacement, or the monitor saying stop, ends the history there with its
    /// status and reason.
    fn integrate(&mut self, monitor: &mut dyn FnMut(&Progress) -> bool) {
        let mut last = Instant::now();
        for n in 1..=self.n_steps {
            if let ControlFlow::Break((status, error)) = self.time_step(n, &mut last, monitor) {
                self.h.status = status;
                self.h.error = Some(error);
                break;
            }
        }
    }

    /// Whether step `n` is recorded: every `record_every`-th step, or the first at or after each
    /// multiple of the interval, and the last.
    fn due(&self, n: usize) -> bool {
        n == self.n_steps
            || match self.record {
                Recording::Every(k) => n % k == 0,
                Recording::Interval(i) => {
                    let dt = self.s.dt;
                    (n as f64 * dt / i).floor() > ((n - 1) as f64 * dt / i).floor()
                }
            }
    }

    /// Time step `n`: the step, its work, the record if one is due and the monitor if due;
    /// stops on a non-finite displacement or when the monitor says so.
    fn time_step(&mut self, n: usize, last: &mut Instant, monitor: &mut dyn FnMut(&Progress) -> bool) -> ControlFlow<(Status, String)> {
        let (s, loads) = (&mut self.s, &self.loads);
        let t = n as f64 * s.dt;
        let mut set_ext = |f: &mut [f64], _: &[f64]| loads.apply(f, t);
        s.step(&mut set_ext, None);
        for d in 0..s.u.len() {
            let du = s.u[d] - self.u_prev[d];
            self.work += 0.5 * (s.f_ext[d] + self.f_prev[d]) * du;
            self.joints += 0.5 * (s.f_int[d] + self.fi_prev[d]) * du;
        }
        self.f_prev.copy_from_slice(&s.f_ext);
        self.fi_prev.copy_from_slice(&s.f_int);
        self.u_prev.copy_from_slice(&s.u);
        if s.u.iter().any(|x| !x.is_finite()) {
            return ControlFlow::Break((Status::Failed, format!("non-finite displacement at t = {t:.6} s (step {n})")));
        }
        if n % 16 == 0 || n == self.n_steps {
            if let Some(why) = s.out_of_range(&self.u0) {
                return ControlFlow::Break((Status::Failed, format!("the response left the model's range at t = {t:.6} s (step {n}): {why}; the wall has collapsed or the excitation lies beyond what the model represents")));
            }
        }
        if self.due(n) {
            self.record(t);
        }
        if monitor_due(n - 1, self.s.clock_every(), last) {
            let fraction = n as f64 / self.n_steps as f64;
            let p = Progress { step: n, multiplier: self.loads.lam, displacement: f64::NAN, fraction, poll: false, time: t };
            if !monitor(&p) {
                return ControlFlow::Break((Status::Interrupted, Error::Interrupted.to_string()));
            }
        }
        ControlFlow::Continue(())
    }
}

/// Why the state of `s` lies beyond the model's range, if it does: a block translated (from
/// its initial position `u0`) by more than the wall's size, or rotated by more than one radian
/// (the small-rotation model) or a right angle (large rotations: the block lies on its side).
fn out_of_range(s: &Integrator, u0: &[f64]) -> Option<String> {
    let model = s.model;
    let (times, max_phi, what) = update::range(s.update.is_some(), s.large);
    let size = times * model.size();
    for i in 0..model.n_blocks() {
        let moved = (s.u[3 * i] - u0[3 * i]).hypot(s.u[3 * i + 1] - u0[3 * i + 1]);
        if moved > size {
            return Some(format!("{} moved {moved:.3e} m, more than {what} ({size:.3e} m)", model.block_name(i)));
        }
        let phi = s.u[3 * i + 2] - u0[3 * i + 2];
        if phi.abs() > max_phi {
            return Some(format!("{} rotated {phi:.3e} rad, more than {max_phi:.4} rad", model.block_name(i)));
        }
    }
    None
}
