//! Time histories: free motion from initial conditions, or a horizontal base acceleration.

use super::*;

/// Integrates the equations of motion in time (free motion, base acceleration).
pub fn simulate(model: &Model, opts: &DynamicOptions) -> Result<TimeHistory, Error> {
    simulate_with(model, opts, &mut |_| true)
}

/// As [`simulate`], calling `monitor` every few thousand steps (return false to stop).
pub fn simulate_with(model: &Model, opts: &DynamicOptions, monitor: &mut dyn FnMut(&Progress) -> bool) -> Result<TimeHistory, Error> {
    model.check_analysis_memory("a time history")?;
    let start = Instant::now();
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
    let mut s = Integrator::new(model, opts.time_step, opts.safety, opts.damping, opts.threads)?;
    s.set_large(opts.large_rotations);
    let fixed = model.fixed();
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
    let fd = model.dead_load().to_vec();
    let fl = model.live_load().to_vec();
    let lam = opts.live_multiplier;
    let mass = s.mass.clone();
    let base = opts.base_acceleration.clone();
    let ag = move |t: f64| -> f64 {
        match &base {
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
    };
    let ext = |f: &mut [f64], t: f64| {
        let g = ag(t);
        for d in 0..f.len() {
            f[d] = fd[d] + lam * fl[d] - if d % 3 == 0 { mass[d] * g } else { 0.0 };
        }
    };
    ext(&mut s.f_ext, 0.0);
    s.interface_forces();
    s.accelerations();
    let n_steps_f = (opts.duration / s.dt).ceil();
    if !(n_steps_f <= MAX_TIME_STEPS as f64) {
        return Err(Error::input(format!(
            "duration = {} s with a time step of {:.3e} s is {n_steps_f:.0} time steps, more than the limit of {MAX_TIME_STEPS}",
            opts.duration, s.dt
        )));
    }
    let n_steps = n_steps_f as usize;
    let cap = n_steps / opts.record_every + 2;
    // two histories (displacements, velocities) of 3 values per block and record
    let stored = 6.0 * cap as f64 * nb as f64;
    if stored > MAX_RECORDED_VALUES as f64 {
        return Err(Error::input(format!(
            "recording {cap} states of {nb} blocks (duration {} s, time step {:.3e} s, record_every {}) stores {stored:.0} numbers, more than the limit of {MAX_RECORDED_VALUES}: raise record_every or shorten the duration",
            opts.duration, s.dt, opts.record_every
        )));
    }
    let mut h = TimeHistory {
        status: Status::Completed,
        error: None,
        time_step: s.dt,
        times: Vec::with_capacity(cap),
        n_blocks: nb,
        // reserved once: recording does not allocate inside the time loop
        displacements: Vec::with_capacity(cap * nb),
        velocities: Vec::with_capacity(cap * nb),
        kinetic_energy: Vec::with_capacity(cap),
        elastic_energy: Vec::with_capacity(cap),
        external_work: Vec::with_capacity(cap),
        dissipated: Vec::with_capacity(cap),
        steps: 0,
        elapsed_s: 0.0,
    };
    // work of the external forces, by the trapezoidal rule on each step
    let mut work = 0.0;
    let mut f_prev = s.f_ext.clone();
    let mut u_prev = s.u.clone();
    let record = |h: &mut TimeHistory, s: &Integrator, t: f64, work: f64| {
        h.times.push(t);
        h.displacements.extend((0..nb).map(|i| [s.u[3 * i], s.u[3 * i + 1], s.u[3 * i + 2]]));
        h.velocities.extend((0..nb).map(|i| [s.v[3 * i], s.v[3 * i + 1], s.v[3 * i + 2]]));
        let ke = s.kinetic_energy();
        let ee = s.elastic_energy();
        h.kinetic_energy.push(ke);
        h.elastic_energy.push(ee);
        h.external_work.push(work);
        h.dissipated.push(work - ke - ee);
    };
    record(&mut h, &s, 0.0, 0.0);
    let mut last = Instant::now();
    for n in 1..=n_steps {
        let t = n as f64 * s.dt;
        let mut set_ext = |f: &mut [f64], _: &[f64]| ext(f, t);
        s.step(&mut set_ext, None);
        for d in 0..s.u.len() {
            work += 0.5 * (s.f_ext[d] + f_prev[d]) * (s.u[d] - u_prev[d]);
        }
        f_prev.copy_from_slice(&s.f_ext);
        u_prev.copy_from_slice(&s.u);
        if s.u.iter().any(|x| !x.is_finite()) {
            h.status = Status::Failed;
            h.error = Some(format!("non-finite displacement at t = {t:.6} s (step {n})"));
            break;
        }
        if n % opts.record_every == 0 || n == n_steps {
            record(&mut h, &s, t, work);
        }
        if monitor_due(n - 1, &mut last) {
            let p = Progress { step: n, multiplier: lam, displacement: f64::NAN, fraction: n as f64 / n_steps as f64, poll: false };
            if !monitor(&p) {
                h.status = Status::Interrupted;
                h.error = Some(Error::Interrupted.to_string());
                break;
            }
        }
    }
    h.steps = s.steps;
    h.elapsed_s = start.elapsed().as_secs_f64();
    Ok(h)
}
