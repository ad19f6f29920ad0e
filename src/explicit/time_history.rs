//! Time histories: free motion from initial conditions, or a horizontal base acceleration.

use super::*;
use std::ops::ControlFlow;

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
    let mut s = Integrator::new(model, opts.time_step, opts.safety, opts.damping, opts.threads)?;
    s.set_large(opts.large_rotations);
    set_initial_state(&mut s, opts);
    let loads = Loads::new(model, opts, &s);
    loads.apply(&mut s.f_ext, 0.0);
    s.interface_forces();
    s.accelerations();
    let n_steps = count_time_steps(opts, s.dt)?;
    let h = TimeHistory::reserved(opts, s.dt, n_steps, nb)?;
    // work of the external forces, by the trapezoidal rule on each step
    let (f_prev, u_prev) = (s.f_ext.clone(), s.u.clone());
    let mut run = Run { s, loads, h, n_steps, record_every: opts.record_every, work: 0.0, f_prev, u_prev };
    run.h.record(&run.s, 0.0, 0.0);
    run.integrate(monitor);
    let Run { s, mut h, .. } = run;
    h.steps = s.steps;
    h.elapsed_s = start.elapsed().as_secs_f64();
    Ok(h)
}

/// Checks the options of a time history against the model, in the order their errors are
/// reported, before the integrator is built.
fn check_options(model: &Model, opts: &DynamicOptions) -> Result<(), Error> {
    if !(opts.duration.is_finite() && opts.duration > 0.0) {
        return Err(Error::input(format!("duration must be a finite number > 0, got {}", opts.duration)));
    }
    if opts.record_every == 0 {
        return Err(Error::input("record_every must be at least 1"));
    }
    if !opts.live_multiplier.is_finite() {
        return Err(Error::input("live_multiplier must be finite"));
    }
    let nb = model.n_blocks();
    if let Some((t, a)) = &opts.base_acceleration {
        if t.len() != a.len() || t.is_empty() {
            return Err(Error::input(format!(
                "base_acceleration: times and accelerations must be non-empty and of equal length (got {} and {})",
                t.len(),
                a.len()
            )));
        }
        if t.iter().chain(a).any(|x| !x.is_finite()) || t.windows(2).any(|w| w[1] <= w[0]) {
            return Err(Error::input("base_acceleration: times must increase and every value must be finite"));
        }
    }
    for (what, init) in [("initial_displacement", &opts.initial_displacement), ("initial_velocity", &opts.initial_velocity)] {
        if let Some(v) = init {
            if v.len() != nb {
                return Err(Error::input(format!("{what}: expected {nb} rows (one per block), got {}", v.len())));
            }
            if v.iter().flatten().any(|x| !x.is_finite()) {
                return Err(Error::input(format!("{what}: every value must be finite")));
            }
        }
    }
    model.check_supports()?;
    if !model.held_after_dead().is_empty() {
        return Err(Error::input(
            "top.vertical = \"held\" is for quasi-static analyses (held once the dead loads are on); a time history loads the beam with its force: use top.vertical = \"free\"",
        ));
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
fn count_time_steps(opts: &DynamicOptions, dt: f64) -> Result<usize, Error> {
    let n_steps_f = (opts.duration / dt).ceil();
    if !(n_steps_f <= MAX_TIME_STEPS as f64) {
        return Err(Error::input(format!(
            "duration = {} s with a time step of {dt:.3e} s is {n_steps_f:.0} time steps, more than the limit of {MAX_TIME_STEPS}",
            opts.duration
        )));
    }
    Ok(n_steps_f as usize)
}

/// The external forces of a time history: the dead loads, the live loads times a constant
/// multiplier, and the inertial forces `-m a_g(t)` of a horizontal base acceleration (the
/// blocks move in the frame of the base).
struct Loads {
    fd: Vec<f64>,
    fl: Vec<f64>,
    lam: f64,
    mass: Vec<f64>,
    base: Option<(Vec<f64>, Vec<f64>)>,
}

impl Loads {
    /// The loads of `model` under `opts`, with the masses of `s`.
    fn new(model: &Model, opts: &DynamicOptions, s: &Integrator) -> Loads {
        Loads {
            fd: model.dead_load().to_vec(),
            fl: model.live_load().to_vec(),
            lam: opts.live_multiplier,
            mass: s.mass.clone(),
            base: opts.base_acceleration.clone(),
        }
    }

    /// The base acceleration at time `t`: linear between the samples, zero outside them.
    fn base_acceleration(&self, t: f64) -> f64 {
        match &self.base {
            None => 0.0,
            Some((ts, a)) => {
                if t < ts[0] || t > ts[ts.len() - 1] {
                    return 0.0;
                }
                let k = ts.partition_point(|&x| x <= t).clamp(1, ts.len() - 1);
                let (t0, t1) = (ts[k - 1], ts[k]);
                a[k - 1] + (a[k] - a[k - 1]) * (t - t0) / (t1 - t0)
            }
        }
    }

    /// The external forces at time `t`, into `f`.
    fn apply(&self, f: &mut [f64], t: f64) {
        let (fd, fl, lam, mass) = (&self.fd, &self.fl, self.lam, &self.mass);
        let g = self.base_acceleration(t);
        for d in 0..f.len() {
            f[d] = fd[d] + lam * fl[d] - if d % 3 == 0 { mass[d] * g } else { 0.0 };
        }
    }
}

impl TimeHistory {
    /// An empty history with room for every record of `n_steps` time steps of `dt` (one every
    /// `record_every`, the first and the last), reserved once so that recording does not
    /// allocate inside the time loop; refused beyond [`MAX_RECORDED_VALUES`].
    fn reserved(opts: &DynamicOptions, dt: f64, n_steps: usize, nb: usize) -> Result<TimeHistory, Error> {
        let cap = n_steps / opts.record_every + 2;
        // two histories (displacements, velocities) of 3 values per block and record
        let stored = 6.0 * cap as f64 * nb as f64;
        if stored > MAX_RECORDED_VALUES as f64 {
            return Err(Error::input(format!(
                "recording {cap} states of {nb} blocks (duration {} s, time step {dt:.3e} s, record_every {}) stores {stored:.0} numbers, more than the limit of {MAX_RECORDED_VALUES}: raise record_every or shorten the duration",
                opts.duration, opts.record_every
            )));
        }
        Ok(TimeHistory {
            status: Status::Completed,
            error: None,
            time_step: dt,
            times: Vec::with_capacity(cap),
            n_blocks: nb,
            displacements: Vec::with_capacity(cap * nb),
            velocities: Vec::with_capacity(cap * nb),
            kinetic_energy: Vec::with_capacity(cap),
            elastic_energy: Vec::with_capacity(cap),
            external_work: Vec::with_capacity(cap),
            dissipated: Vec::with_capacity(cap),
            steps: 0,
            elapsed_s: 0.0,
        })
    }

    /// Records the state of `s` at time `t`, with the external forces' work so far and the
    /// energy dissipated (that work less the kinetic and elastic energies).
    fn record(&mut self, s: &Integrator, t: f64, work: f64) {
        let nb = self.n_blocks;
        self.times.push(t);
        self.displacements.extend((0..nb).map(|i| [s.u[3 * i], s.u[3 * i + 1], s.u[3 * i + 2]]));
        self.velocities.extend((0..nb).map(|i| [s.v[3 * i], s.v[3 * i + 1], s.v[3 * i + 2]]));
        let ke = s.kinetic_energy();
        let ee = s.elastic_energy();
        self.kinetic_energy.push(ke);
        self.elastic_energy.push(ee);
        self.external_work.push(work);
        self.dissipated.push(work - ke - ee);
    }
}

/// A time history being integrated: the integrator, its loads, the history so far, and the
/// external forces' work with the forces and displacements of the last step (the work of a
/// step by the trapezoidal rule).
struct Run<'a> {
    s: Integrator<'a>,
    loads: Loads,
    h: TimeHistory,
    n_steps: usize,
    record_every: usize,
    work: f64,
    f_prev: Vec<f64>,
    u_prev: Vec<f64>,
}

impl Run<'_> {
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

    /// Time step `n`: the step, its work, the record if one is due (every `record_every`-th
    /// step and the last) and the monitor if due; stops on a non-finite displacement or when
    /// the monitor says so.
    fn time_step(&mut self, n: usize, last: &mut Instant, monitor: &mut dyn FnMut(&Progress) -> bool) -> ControlFlow<(Status, String)> {
        let (s, loads) = (&mut self.s, &self.loads);
        let t = n as f64 * s.dt;
        let mut set_ext = |f: &mut [f64], _: &[f64]| loads.apply(f, t);
        s.step(&mut set_ext, None);
        for d in 0..s.u.len() {
            self.work += 0.5 * (s.f_ext[d] + self.f_prev[d]) * (s.u[d] - self.u_prev[d]);
        }
        self.f_prev.copy_from_slice(&s.f_ext);
        self.u_prev.copy_from_slice(&s.u);
        if s.u.iter().any(|x| !x.is_finite()) {
            return ControlFlow::Break((Status::Failed, format!("non-finite displacement at t = {t:.6} s (step {n})")));
        }
        if n % self.record_every == 0 || n == self.n_steps {
            self.h.record(s, t, self.work);
        }
        if monitor_due(n - 1, last) {
            let fraction = n as f64 / self.n_steps as f64;
            let p = Progress { step: n, multiplier: loads.lam, displacement: f64::NAN, fraction, poll: false };
            if !monitor(&p) {
                return ControlFlow::Break((Status::Interrupted, Error::Interrupted.to_string()));
            }
        }
        ControlFlow::Continue(())
    }
}
