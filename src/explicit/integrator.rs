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
    /// the blocks' motion, dof by dof (the loop both dimensions share); its fields read as the
    /// integrator's own (`Deref`)
    pub(super) m: Motion,
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
    /// each interface's section: the model's, then those of the contacts the update finds
    pub(super) sections: Vec<Section>,
    /// finite rotations only (else empty): where each interface lies on its blocks
    pub(super) arms: Vec<Arm>,
    /// the contact update of a time history, if on (see [`super::update`])
    pub(super) update: Option<Box<super::update::Update>>,
    /// stiffness-proportional damping beta \[s\] of the dashpots (time histories)
    pub(super) beta: f64,
}

impl std::ops::Deref for Integrator<'_> {
    type Target = Motion;
    fn deref(&self) -> &Motion {
        &self.m
    }
}

impl std::ops::DerefMut for Integrator<'_> {
    fn deref_mut(&mut self) -> &mut Motion {
        &mut self.m
    }
}

impl<'a> Integrator<'a> {
    /// The integrator of `model` at rest at its prescribed displacements, with time step `dt`
    /// (None: `safety` times the stability limit), `damping`, and the interface pass on
    /// `threads` threads (0: all cores); bad values are refused with the option they come from.
    pub(super) fn new(model: &'a Model, dt: Option<f64>, safety: f64, damping: Damping, threads: usize) -> Result<Self, Error> {
        let dt = checked_time_step(critical_time_step(model), dt, safety, damping)?;
        let nb = model.n_blocks();
        let m = model.interfaces().len();
        if nb > BLOCK as usize || 2 * m >= u32::MAX as usize {
            return Err(Error::input(format!("{nb} blocks and {m} interfaces: the explicit solver takes fewer than 2^31 blocks and 2^31 interfaces")));
        }
        let fixed = model.fixed();
        let mass = masses(model);
        // the laws by family index (see `family_index`)
        let laws = [Family::Bed, Family::Head, Family::Base, Family::Top].map(|f| *model.laws().of(f));
        let kinds = model.joint_kinds();
        let (shapes, geo) = shape_table(model, &kinds);
        let hw = if laws.iter().any(|l| l.is_softening()) { 5 } else { 3 };
        let (pool, par, n_parts) = start_pool(threads, m, PAR_MIN_INTERFACES)?;
        let motion = Motion::new(3, mass, fixed, model.prescribed().to_vec(), dt, damping, pool, par)?;
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
            m: motion,
            hist: vec![0.0; hw * m],
            hw,
            broken: vec![false; m],
            forces: vec![[0.0; 3]; m],
            flags: vec![0; m],
            warm: vec![0; m],
            large: false,
            centroids: vec![],
            cs: vec![],
            dynm: vec![],
            prime: false,
            sections: model.sections().to_vec(),
            arms: vec![],
            update: None,
            beta: 0.0,
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
            self.centroids = self.model.centroids().to_vec();
            self.cs = vec![[1.0, 0.0]; nb];
            let g = &self.centroids;
            self.arms = self.model.interfaces().iter().map(|it| Arm { ra: [it.c[0] - g[it.a][0], it.c[1] - g[it.a][1]], rb: [it.c[0] - g[it.b][0], it.c[1] - g[it.b][1]], n: it.n, rel0: [1.0, 0.0], l: it.l }).collect();
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
        self.m.hold(self.model.held_after_dead());
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
            sections: &self.sections,
            arms: &self.arms,
            u: &self.m.u,
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
            f_int: &mut self.m.f_int,
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
        let u = &self.m.u;
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
            self.m.f_int[3 * i as usize..3 * i as usize + 3].copy_from_slice(x);
        }
    }

    /// One velocity-Verlet step; `f_ext` must hold the external forces at the new time.
    /// `prescribed`: dof driven to a value (displacement control).
    pub(super) fn step(&mut self, set_ext: &mut dyn FnMut(&mut [f64], &[f64]), prescribed: Option<(usize, f64)>) {
        if self.par {
            // one hand-off to the pool for the positions and the interface forces
            let pool = self.pool.clone();
            pool.install(|| {
                self.m.drift_in(prescribed, true);
                self.interface_forces_in(true);
            });
        } else {
            self.m.drift_in(prescribed, false);
            self.interface_forces_in(false);
        }
        self.m.finish_step(set_ext, prescribed);
        if self.update.as_ref().is_some_and(|up| up.due(&self.m.u)) {
            super::update::search(self);
        }
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

    /// Starts the energy accounting and the contact dashpots of a time history: each interface's
    /// dashpot from its law's restitution and the reduced mass of its blocks (see
    /// [`super::contact`]), plus `beta` times its elastic stiffness (stiffness-proportional
    /// damping); the next interface pass takes the jumps.
    pub(super) fn start_dynamics(&mut self, beta: f64) {
        self.beta = beta;
        self.dynm = (0..self.geo.len()).map(|k| self.dashpot_of(k)).collect();
        self.prime = true;
        self.track_damping = !matches!(self.damping, Damping::None);
    }

    /// The contact dashpot of interface `k` (see [`Integrator::start_dynamics`]), nothing
    /// dissipated yet.
    pub(super) fn dashpot_of(&self, k: usize) -> Dyn {
        let model = self.model;
        let free_mass = |i: usize| {
            if self.free[3 * i] || self.free[3 * i + 1] {
                model.mass()[i]
            } else {
                f64::INFINITY
            }
        };
        let (sec, g) = (&self.sections[k], &self.geo[k]);
        let reduced = 1.0 / (1.0 / free_mass(g.a()) + 1.0 / free_mass(g.b()));
        let impacts = super::contact::coefficients(self.law(k), sec.area, sec.length, reduced);
        let d = crate::joint::stiffness(self.law(k), sec);
        let c: [f64; 3] = std::array::from_fn(|j| impacts[j] + self.beta * d[j]);
        let share = std::array::from_fn(|j| if c[j] > 0.0 { impacts[j] / c[j] } else { 1.0 });
        Dyn { c, share, half: 0.5 * sec.length, ..Dyn::default() }
    }

    pub(super) fn elastic_energy(&self) -> f64 {
        let mut e = 0.0;
        for (k, f) in self.forces.iter().enumerate() {
            let d = crate::joint::stiffness(self.law(k), &self.sections[k]);
            e += 0.5 * (f[0] * f[0] / d[0] + f[1] * f[1] / d[1] + f[2] * f[2] / d[2]);
        }
        e
    }
}

/// The mass of each dof (m, m, J per block).
pub(super) fn masses(model: &Model) -> Vec<f64> {
    (0..model.n_blocks()).flat_map(|i| [model.mass()[i], model.mass()[i], model.inertia()[i]]).collect()
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

impl Kernel for Integrator<'_> {
    const DOF: usize = 3;
    type V = [f64; 3];
    fn step(&mut self, set_ext: &mut dyn FnMut(&mut [f64], &[f64]), prescribed: Option<(usize, f64)>) {
        Integrator::step(self, set_ext, prescribed)
    }
    fn interface_forces(&mut self) {
        Integrator::interface_forces(self)
    }
    fn hold(&mut self) {
        Integrator::hold(self)
    }
    fn clock_every(&self) -> usize {
        Integrator::clock_every(self)
    }
    fn history(&self) -> (&[f64], &[bool]) {
        (&self.hist, &self.broken)
    }
    fn history_mut(&mut self) -> (&mut [f64], &mut [bool]) {
        (&mut self.hist, &mut self.broken)
    }
    #[inline]
    fn translation(u: &[f64], from: Option<&[f64]>, i: usize) -> f64 {
        match from {
            Some(u0) => (u[3 * i] - u0[3 * i]).hypot(u[3 * i + 1] - u0[3 * i + 1]),
            None => u[3 * i].hypot(u[3 * i + 1]),
        }
    }
    fn block(u: &[f64], i: usize) -> [f64; 3] {
        [u[3 * i], u[3 * i + 1], u[3 * i + 2]]
    }
    fn into_contacts(self) -> (Vec<[f64; 3]>, Vec<u8>, Vec<bool>) {
        (self.forces, self.flags, self.broken)
    }
    fn contacts_created(&self) -> usize {
        self.update.as_ref().map_or(0, |up| up.created)
    }
}
