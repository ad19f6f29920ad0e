//! The integrator: velocity-Verlet steps of the blocks' motion with the kinds of damping, its
//! state apart from its work arrays, and [`Stepper`], stepping from outside the crate.

use super::*;

/// The integrator's state and work arrays (flat, allocated once).
///
/// Per interface: the packed geometry (12 bytes: the blocks and the index of the shape, whose
/// table holds the lever arms, the normal, the family and the kind), the history (24: the
/// plastic jumps, and 16 more, the opening and the slip, only if a law softens; `JointState`
/// takes 48), the broken flag (1), the force (24), the flags (1) and the warm set (1); sections
/// and laws are read from the model (a table of four laws, one per family). With finite
/// rotations also, per block, the centroid and the rotation's (cos, sin). One step is: a pass
/// over the blocks (velocity half-step and positions), a pass over the interfaces in parts
/// (return mapping, and each interface's forces on its blocks added to their sums at once, for
/// the blocks whose interfaces are all in one part: in interface order, so the sums do not
/// depend on the number of threads; for the others (a course of blocks at each boundary of
/// parts) the forces are stored and a gather sums them after the pass, in the same order), the
/// external forces, and a pass over the blocks (accelerations and velocity half-step). Each pass
/// is split into independent chunks on the thread pool.
pub(super) struct Integrator<'a> {
    pub(super) model: &'a Model,
    pub(super) geo: Vec<Geo>,
    /// the distinct shapes of interface (see [`Geo`])
    pub(super) shapes: Vec<Shape>,
    /// the kinds of interface (see [`Shape`])
    pub(super) kinds: Kinds,
    pub(super) laws: [JointLaw; 4],
    /// The interface pass in parts (one unless the passes go to the pool): part p maps the
    /// interfaces `parts[p].0..parts[p + 1].0` and adds their forces to the blocks'
    /// `parts[p].1..parts[p + 1].1` whose interfaces are all among them (marked [`SUMMED`] in
    /// [`Geo`]), in increasing k: the sums of the gather below, with no pass of their own.
    pub(super) parts: Vec<(usize, usize, usize)>,
    /// the other blocks, whose sums a gather after the pass forms from the terms the pass
    /// leaves them (`parts[p].2..parts[p + 1].2` from part p), and the sums
    pub(super) straddlers: Straddlers,
    pub(super) terms: Vec<[f64; 3]>,
    pub(super) straddler_sums: Vec<[f64; 3]>,
    pub(super) inv_mass: Vec<f64>,
    pub(super) mass: Vec<f64>,
    pub(super) free: Vec<bool>,
    pub(super) u: Vec<f64>,
    pub(super) v: Vec<f64>,
    pub(super) a: Vec<f64>,
    pub(super) f_int: Vec<f64>,
    pub(super) f_ext: Vec<f64>,
    /// the committed joint histories, `hw` numbers an interface: the plastic jumps, then (only
    /// if a law softens, `hw` = 5) the opening and the slip, which no other law reads
    pub(super) hist: Vec<f64>,
    pub(super) hw: usize,
    pub(super) broken: Vec<bool>,
    pub(super) forces: Vec<[f64; 3]>,
    pub(super) flags: Vec<u8>,
    /// the active set each interface's return mapping accepted at its last plastic update
    /// (bit j: face j; 0: none yet), tried first at the next ([`return_map`](crate::joint::return_map) with `MapOptions::warm`)
    pub(super) warm: Vec<u8>,
    pub(super) dt: f64,
    pub(super) damping: Damping,
    pub(super) pool: std::sync::Arc<rayon::ThreadPool>,
    /// whether the passes go to the pool (more than one thread and enough interfaces)
    pub(super) par: bool,
    pub(super) steps: usize,
    /// finite rotations (time histories) or the linearized kinematics of the static solver
    pub(super) large: bool,
    /// reference centroids and (cos, sin) of the current rotation of each block
    pub(super) centroids: Vec<[f64; 2]>,
    pub(super) cs: Vec<[f64; 2]>,
    /// time histories only (else empty): per interface, the jumps, the contact dashpot and the
    /// energies (see [`Dyn`])
    pub(super) dynm: Vec<Dyn>,
    /// the next interface pass primes `dynm` (takes the jumps, damps nothing)
    pub(super) prime: bool,
    /// energy dissipated by the damping of the motion (local or viscous) \[J\], summed only
    /// with `track_damping`
    pub(super) damping_work: f64,
    pub(super) track_damping: bool,
}

impl<'a> Integrator<'a> {
    /// The integrator of `model` at rest at its prescribed displacements, with time step `dt`
    /// (None: `safety` times the stability limit), `damping`, and the interface pass on
    /// `threads` threads (0: all cores); bad values are refused with the option they come from.
    pub(super) fn new(model: &'a Model, dt: Option<f64>, safety: f64, damping: Damping, threads: usize) -> Result<Self, Error> {
        let dt = time_step(model, dt, safety)?;
        check_damping(damping)?;
        if threads > MAX_THREADS {
            return Err(Error::input(format!("analysis.threads = {threads} is more than the limit of {MAX_THREADS}")));
        }
        let nb = model.n_blocks();
        let m = model.interfaces().len();
        if nb > BLOCK as usize || 2 * m >= u32::MAX as usize {
            return Err(Error::input(format!("{nb} blocks and {m} interfaces: the explicit solver takes fewer than 2^31 blocks and 2^31 interfaces")));
        }
        let fixed = model.fixed();
        let (mass, inv_mass) = masses(model);
        // the laws by family index (see `family_index`)
        let laws = [Family::Bed, Family::Head, Family::Base, Family::Top].map(|f| *model.laws().of(f));
        let kinds = model.joint_kinds();
        let (shapes, geo) = shape_table(model, &kinds);
        let hw = if laws.iter().any(|l| l.is_softening()) { 5 } else { 3 };
        let (pool, par, n_parts) = start_pool(threads, m)?;
        let mut it = Integrator {
            model,
            geo,
            shapes,
            kinds,
            laws,
            parts: vec![],
            straddler_sums: vec![],
            terms: vec![],
            straddlers: Straddlers::default(),
            inv_mass,
            mass,
            free: fixed.iter().map(|f| !f).collect(),
            u: model.prescribed().to_vec(),
            v: vec![0.0; 3 * nb],
            a: vec![0.0; 3 * nb],
            f_int: vec![0.0; 3 * nb],
            f_ext: vec![0.0; 3 * nb],
            hist: vec![0.0; hw * m],
            hw,
            broken: vec![false; m],
            forces: vec![[0.0; 3]; m],
            flags: vec![0; m],
            warm: vec![0; m],
            dt,
            damping,
            pool,
            par,
            steps: 0,
            large: false,
            centroids: vec![],
            cs: vec![],
            dynm: vec![],
            prime: false,
            damping_work: 0.0,
            track_damping: false,
        };
        it.set_parts(n_parts);
        Ok(it)
    }

    /// The interface pass in `n_parts` parts (see [`partition`]), with the terms and sums of
    /// the blocks that straddle them.
    pub(super) fn set_parts(&mut self, n_parts: usize) {
        for g in &mut self.geo {
            g.a &= BLOCK;
            g.b &= BLOCK;
        }
        let (parts, straddlers) = partition(self.model.n_blocks(), &mut self.geo, n_parts);
        self.terms = vec![[0.0; 3]; straddlers.slots.len()];
        self.straddler_sums = vec![[0.0; 3]; straddlers.blocks.len()];
        (self.parts, self.straddlers) = (parts, straddlers);
    }

    /// Finite rotations (time histories) or the linearized kinematics (the default); the
    /// arrays only the finite rotations need are allocated here.
    pub(super) fn set_large(&mut self, large: bool) {
        self.large = large;
        if large && self.cs.is_empty() {
            let nb = self.model.n_blocks();
            self.centroids = self.model.rects().iter().map(|r| r.centroid()).collect();
            self.cs = vec![[1.0, 0.0]; nb];
        }
    }

    /// A damped integrator (local damping 0.8, one thread) started from a static state: the
    /// displacements `u` and joint histories `states` of a state past the dead loads, with the
    /// dofs held after them held. The static solver's explicit by-products start from it.
    pub(super) fn damped_from(model: &'a Model, u: &[f64], states: &[JointState]) -> Result<Self, Error> {
        let mut s = Integrator::new(model, None, SAFETY, Damping::Local(LOCAL_DAMPING), 1)?;
        s.u.copy_from_slice(u);
        s.set_states(states);
        s.hold();
        Ok(s)
    }

    /// Fixes the dofs the model holds once the dead loads are on, where they are now.
    pub(super) fn hold(&mut self) {
        for &d in self.model.held_after_dead() {
            self.free[d] = false;
            self.inv_mass[d] = 0.0;
            self.v[d] = 0.0;
            self.a[d] = 0.0;
        }
    }

    /// The law of interface `k`.
    #[inline(always)]
    pub(super) fn law(&self, k: usize) -> &JointLaw {
        &self.laws[self.shapes[self.geo[k].shape as usize].family as usize]
    }

    /// The committed history of interface `k`.
    pub(super) fn state(&self, k: usize) -> JointState {
        unpack(&self.hist[self.hw * k..self.hw * (k + 1)], self.broken[k])
    }

    /// Every committed history.
    pub(super) fn states(&self) -> Vec<JointState> {
        (0..self.broken.len()).map(|k| self.state(k)).collect()
    }

    pub(super) fn set_states(&mut self, states: &[JointState]) {
        for (k, st) in states.iter().enumerate() {
            pack(st, &mut self.hist[self.hw * k..self.hw * (k + 1)]);
            self.broken[k] = st.broken;
        }
    }

    /// Interface forces at the current `u` from the committed histories, which are updated
    /// (each time step is an increment), then gathered into `f_int`.
    pub(super) fn interface_forces(&mut self) {
        if self.par {
            let pool = self.pool.clone();
            pool.install(|| self.interface_forces_in(true));
        } else {
            self.interface_forces_in(false);
        }
    }

    /// [`Integrator::interface_forces`], on the current rayon pool if `par`.
    pub(super) fn interface_forces_in(&mut self, par: bool) {
        if self.large {
            self.rotations_in(par);
        }
        let pass = Pass {
            model: self.model,
            u: &self.u,
            geo: &self.geo,
            shapes: &self.shapes,
            laws: &self.laws,
            kinds: &self.kinds,
            centroids: &self.centroids,
            cs: &self.cs,
            dt: self.dt,
            prime: self.prime,
        };
        let (large, hw) = (self.large, self.hw);
        let work = |p: Part| pass.run(p, hw, large);
        let all = Part {
            k0: 0,
            b0: 0,
            t0: 0,
            hist: &mut self.hist,
            broken: &mut self.broken,
            forces: &mut self.forces,
            flags: &mut self.flags,
            warm: &mut self.warm,
            dynm: &mut self.dynm,
            terms: &mut self.terms,
            f_int: &mut self.f_int,
        };
        if par {
            run_parts(all, &self.parts, hw, &work);
        } else {
            // the parts one after the other: the same sums
            work(all);
        }
        self.prime = false;
        self.gather_in(par);
    }

    /// The (cos, sin) of each block's rotation at the current `u` (finite rotations), on the
    /// current rayon pool if `par`.
    fn rotations_in(&mut self, par: bool) {
        let u = &self.u;
        let rot = |i0: usize, cs: &mut [[f64; 2]]| {
            for (i, cs) in cs.iter_mut().enumerate() {
                let (s, c) = u[3 * (i0 + i) + 2].sin_cos();
                *cs = [c, s];
            }
        };
        if par {
            self.cs.par_chunks_mut(GRAIN_BLOCKS).enumerate().for_each(|(c, cs)| rot(c * GRAIN_BLOCKS, cs));
        } else {
            rot(0, &mut self.cs);
        }
    }

    /// After the interface pass, the force sums of the blocks whose interfaces span parts,
    /// into `f_int`: each sums the terms the pass left it in increasing k, as a serial scatter
    /// in interface order would; on the current rayon pool if `par`.
    fn gather_in(&mut self, par: bool) {
        let (st, terms) = (&self.straddlers, &self.terms);
        if st.blocks.is_empty() {
            return;
        }
        let gather = |j0: usize, out: &mut [[f64; 3]]| {
            for (j, out) in out.iter_mut().enumerate() {
                let j = j0 + j;
                let mut acc = [0.0; 3];
                for &t in &st.slots[st.start[j] as usize..st.start[j + 1] as usize] {
                    let x = &terms[t as usize];
                    acc[0] += x[0];
                    acc[1] += x[1];
                    acc[2] += x[2];
                }
                *out = acc;
            }
        };
        let sums = &mut self.straddler_sums;
        if par {
            sums.par_chunks_mut(GRAIN_BLOCKS).enumerate().for_each(|(c, out)| gather(c * GRAIN_BLOCKS, out));
        } else {
            gather(0, sums);
        }
        for (&i, x) in st.blocks.iter().zip(sums.iter()) {
            self.f_int[3 * i as usize..3 * i as usize + 3].copy_from_slice(x);
        }
    }

    /// Accelerations from the current forces, with damping against the current velocity; then,
    /// with `kick`, the velocity half-step `v += kick * a` on the free dofs.
    pub(super) fn accelerations_kick(&mut self, kick: Option<f64>) {
        let damping = self.damping;
        let (f_ext, f_int, free, inv_mass, mass) = (&self.f_ext, &self.f_int, &self.free, &self.inv_mass, &self.mass);
        // one dof: the same operations for every kind of damping; the mass is read only by
        // viscous damping (local damping and none do not touch it: 8 bytes a dof less per step).
        // Without a branch on the dof (each value chosen, not jumped to: the loop can run on
        // vectors): a fixed dof's acceleration is zero and its velocity kept.
        #[inline(always)]
        #[allow(clippy::too_many_arguments)]
        fn dof(damping: Damping, kick: Option<f64>, a: &mut f64, v: &mut f64, free: bool, fe: f64, fi: f64, im: f64, m: impl FnOnce() -> f64) {
            let f = fe - fi;
            let vd = *v;
            let fd = match damping {
                Damping::None => 0.0,
                Damping::Local(alpha) => {
                    if vd != 0.0 {
                        -alpha * f.abs() * vd.signum()
                    } else {
                        0.0
                    }
                }
                Damping::Viscous(c) => -c * m() * vd,
            };
            let acc = (f + fd) * im;
            *a = if free { acc } else { 0.0 };
            if let Some(h) = kick {
                *v = if free { vd + h * acc } else { vd };
            }
        }
        let work = |d0: usize, a: &mut [f64], v: &mut [f64]| {
            // the chunk's slices, zipped: no bounds check per dof
            let r = d0..d0 + a.len();
            let dofs = free[r.clone()].iter().zip(&f_ext[r.clone()]).zip(&f_int[r.clone()]).zip(&inv_mass[r.clone()]);
            if let (Damping::Local(alpha), Some(h)) = (damping, kick) {
                // the step of quasi-static runs: `dof` with its constants known, which the
                // compiler turns into a loop on vectors
                for ((a, v), (((&free, &fe), &fi), &im)) in a.iter_mut().zip(v.iter_mut()).zip(dofs) {
                    dof(Damping::Local(alpha), Some(h), a, v, free, fe, fi, im, || 0.0);
                }
            } else if let Damping::Viscous(_) = damping {
                for ((a, v), ((((&free, &fe), &fi), &im), &m)) in a.iter_mut().zip(v.iter_mut()).zip(dofs.zip(&mass[r])) {
                    dof(damping, kick, a, v, free, fe, fi, im, || m);
                }
            } else {
                for ((a, v), (((&free, &fe), &fi), &im)) in a.iter_mut().zip(v.iter_mut()).zip(dofs) {
                    dof(damping, kick, a, v, free, fe, fi, im, || 0.0);
                }
            }
        };
        if self.par {
            const G: usize = 3 * GRAIN_BLOCKS;
            let (a, v) = (&mut self.a, &mut self.v);
            self.pool.install(|| a.par_chunks_mut(G).zip(v.par_chunks_mut(G)).enumerate().for_each(|(c, (a, v))| work(c * G, a, v)));
        } else {
            work(0, &mut self.a, &mut self.v);
        }
    }

    /// Accelerations from the current forces, with damping against the current velocity.
    pub(super) fn accelerations(&mut self) {
        self.accelerations_kick(None);
    }

    /// The first half of a velocity-Verlet step: `v += dt/2 a`, `u += dt v` on the free dofs,
    /// then the prescribed dof; on the current rayon pool if `par`.
    pub(super) fn drift_in(&mut self, prescribed: Option<(usize, f64)>, par: bool) {
        let dt = self.dt;
        let (a, free) = (&self.a, &self.free);
        let drift = |d0: usize, u: &mut [f64], v: &mut [f64]| {
            let r = d0..d0 + u.len();
            for ((u, v), (&free, &a)) in u.iter_mut().zip(v.iter_mut()).zip(free[r.clone()].iter().zip(&a[r])) {
                if free {
                    *v += 0.5 * dt * a;
                    *u += dt * *v;
                }
            }
        };
        if par {
            const G: usize = 3 * GRAIN_BLOCKS;
            self.u.par_chunks_mut(G).zip(self.v.par_chunks_mut(G)).enumerate().for_each(|(c, (u, v))| drift(c * G, u, v));
        } else {
            drift(0, &mut self.u, &mut self.v);
        }
        if let Some((d, val)) = prescribed {
            self.v[d] = (val - self.u[d]) / dt;
            self.u[d] = val;
        }
    }

    /// One velocity-Verlet step; `f_ext` must hold the external forces at the new time.
    /// `prescribed`: dof driven to a value (displacement control).
    pub(super) fn step(&mut self, set_ext: &mut dyn FnMut(&mut [f64], &[f64]), prescribed: Option<(usize, f64)>) {
        if self.par {
            // one hand-off to the pool for the positions and the interface forces
            let pool = self.pool.clone();
            pool.install(|| {
                self.drift_in(prescribed, true);
                self.interface_forces_in(true);
            });
        } else {
            self.drift_in(prescribed, false);
            self.interface_forces_in(false);
        }
        set_ext(&mut self.f_ext, &self.f_int);
        if self.track_damping {
            self.damping_work += self.dt * self.damping_power();
        }
        self.accelerations_kick(Some(0.5 * self.dt));
        if let Some((d, _)) = prescribed {
            self.a[d] = 0.0;
        }
        self.steps += 1;
    }

    /// How often a loop of steps reads the clock for its monitor ([`monitor_due`]): every 16
    /// steps when a step is short (fewer interfaces than the passes take threads for, a
    /// millisecond at most: 16 steps add little to the 0.1 s between calls), else at every step.
    /// A clock read costs some 30 ns, 1% of a step of wall 1 (83 interfaces).
    pub(super) fn clock_every(&self) -> usize {
        if self.geo.len() < PAR_MIN_INTERFACES {
            16
        } else {
            1
        }
    }

    /// |unbalanced forces| / |applied forces| on the free dofs, dof `skip` left out.
    pub(super) fn unbalanced_ratio(&self, skip: Option<usize>) -> f64 {
        let (mut r, mut f) = (0.0, 0.0);
        for d in 0..self.u.len() {
            if self.free[d] && Some(d) != skip {
                let x = self.f_ext[d] - self.f_int[d];
                r += x * x;
                f += self.f_ext[d] * self.f_ext[d];
            }
        }
        (r / f.max(f64::MIN_POSITIVE)).sqrt()
    }

    /// The power the damping of the motion takes from it at the current forces and velocities
    /// (those of the next kick: the mid-step velocities) \[W\], never negative.
    fn damping_power(&self) -> f64 {
        let mut p = 0.0;
        for d in 0..self.u.len() {
            if !self.free[d] {
                continue;
            }
            let v = self.v[d];
            p += match self.damping {
                Damping::None => 0.0,
                Damping::Local(alpha) => alpha * (self.f_ext[d] - self.f_int[d]).abs() * v.abs(),
                Damping::Viscous(c) => c * self.mass[d] * v * v,
            };
        }
        p
    }

    /// Starts the energy accounting and the contact dashpots of a time history: each interface's
    /// dashpot from its law's restitution and the reduced mass of its blocks (see
    /// [`super::contact`]), plus `beta` times its elastic stiffness (stiffness-proportional
    /// damping); the next interface pass takes the jumps.
    pub(super) fn start_dynamics(&mut self, beta: f64) {
        let model = self.model;
        let free_mass = |i: usize| {
            if self.free[3 * i] || self.free[3 * i + 1] {
                model.mass()[i]
            } else {
                f64::INFINITY
            }
        };
        self.dynm = model
            .interfaces()
            .iter()
            .enumerate()
            .map(|(k, it)| {
                let sec = &model.sections()[k];
                let reduced = 1.0 / (1.0 / free_mass(it.a) + 1.0 / free_mass(it.b));
                let impacts = super::contact::coefficients(self.law(k), sec.area, sec.length, reduced);
                let d = crate::joint::stiffness(self.law(k), sec);
                let c: [f64; 3] = std::array::from_fn(|j| impacts[j] + beta * d[j]);
                let share = std::array::from_fn(|j| if c[j] > 0.0 { impacts[j] / c[j] } else { 1.0 });
                Dyn { c, share, half: 0.5 * sec.length, ..Dyn::default() }
            })
            .collect();
        self.prime = true;
        self.track_damping = !matches!(self.damping, Damping::None);
    }

    pub(super) fn kinetic_energy(&self) -> f64 {
        0.5 * (0..self.u.len()).filter(|&d| self.free[d]).map(|d| self.mass[d] * self.v[d] * self.v[d]).sum::<f64>()
    }

    pub(super) fn elastic_energy(&self) -> f64 {
        let mut e = 0.0;
        for (k, f) in self.forces.iter().enumerate() {
            let d = crate::joint::stiffness(self.law(k), &self.model.sections()[k]);
            e += 0.5 * (f[0] * f[0] / d[0] + f[1] * f[1] / d[1] + f[2] * f[2] / d[2]);
        }
        e
    }
}

/// The time step: `dt` if given (finite, positive and within the stability limit of `model`),
/// else `safety` (in (0, 1]) times that limit, which some stiffness must bound.
fn time_step(model: &Model, dt: Option<f64>, safety: f64) -> Result<f64, Error> {
    let crit = critical_time_step(model);
    match dt {
        Some(dt) => {
            if !(dt.is_finite() && dt > 0.0) {
                return Err(Error::input(format!("analysis.time_step must be a finite number > 0, got {dt}")));
            }
            if dt > crit {
                return Err(Error::input(format!(
                    "analysis.time_step = {dt:.3e} s exceeds the stability limit of this model, {crit:.3e} s"
                )));
            }
            Ok(dt)
        }
        None => {
            if !(safety > 0.0 && safety <= 1.0) {
                return Err(Error::input(format!("safety must lie in (0, 1], got {safety}")));
            }
            if !crit.is_finite() {
                return Err(Error::input("no stiffness holds the model: no stable time step"));
            }
            Ok(safety * crit)
        }
    }
}

/// Refuses a damping coefficient out of its range: local damping in [0, 1), viscous damping
/// finite and non-negative.
fn check_damping(damping: Damping) -> Result<(), Error> {
    match damping {
        Damping::Local(a) if !(0.0..1.0).contains(&a) => {
            Err(Error::input(format!("analysis.damping_coefficient (local damping) must lie in [0, 1), got {a}")))
        }
        Damping::Viscous(c) if !(c.is_finite() && c >= 0.0) => {
            Err(Error::input(format!("analysis.damping_coefficient (viscous damping) must be finite and >= 0, got {c}")))
        }
        _ => Ok(()),
    }
}

/// The mass of each dof (m, m, J per block) and its inverse, zero on the fixed dofs (which the
/// forces then do not move).
fn masses(model: &Model) -> (Vec<f64>, Vec<f64>) {
    let nb = model.n_blocks();
    let fixed = model.fixed();
    let mut mass = vec![0.0; 3 * nb];
    let mut inv_mass = vec![0.0; 3 * nb];
    for i in 0..nb {
        let mm = [model.mass()[i], model.mass()[i], model.inertia()[i]];
        for k in 0..3 {
            mass[3 * i + k] = mm[k];
            if !fixed[3 * i + k] {
                inv_mass[3 * i + k] = 1.0 / mm[k];
            }
        }
    }
    (mass, inv_mass)
}

/// The distinct shapes of the interfaces of `model` (of the kinds `kinds`), in the order they
/// first appear, and each interface's packed geometry pointing into them.
fn shape_table(model: &Model, kinds: &Kinds) -> (Vec<Shape>, Vec<Geo>) {
    let m = model.interfaces().len();
    let mut shapes: Vec<Shape> = vec![];
    let mut shape_of = std::collections::HashMap::new();
    let mut geo = Vec::with_capacity(m);
    for (k, it) in model.interfaces().iter().enumerate() {
        let shape = Shape::new(it, kinds.kind(k));
        // at most one shape per interface: fewer than 2^31
        let index = *shape_of.entry(shape.key()).or_insert_with(|| {
            shapes.push(shape);
            (shapes.len() - 1) as u32
        });
        geo.push(Geo { a: it.a as u32, b: it.b as u32, shape: index });
    }
    (shapes, geo)
}

/// The thread pool of `threads` threads (0: all cores) for `m` interfaces, whether the passes
/// go to it (more than one thread and enough interfaces to pay for the hand-offs), and the
/// parts of the interface pass (one unless they do; else at least two per thread).
fn start_pool(threads: usize, m: usize) -> Result<(std::sync::Arc<rayon::ThreadPool>, bool, usize), Error> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| Error::input(format!("cannot start {threads} threads: {e}")))?;
    let par = pool.current_num_threads() > 1 && m >= PAR_MIN_INTERFACES;
    let n_parts = if par { (2 * pool.current_num_threads()).max(m.div_ceil(PART_INTERFACES)) } else { 1 };
    Ok((std::sync::Arc::new(pool), par, n_parts))
}
