//! The integrator's loop that does not depend on the dimension: the blocks' motion as flat
//! arrays of dofs (3 per block in the plane, 6 in 3D), velocity-Verlet half-steps with the kinds
//! of damping, the unbalanced-force ratio, the kinetic energy and the damping's power. The plane's
//! [`Integrator`] and the 3D [`super::space::Integrator3`] each hold one [`Motion`] and add what
//! differs: the interface pass (contact geometry, the joint law's form) and the rotations.

use super::*;

/// The blocks' motion, dof by dof: displacements, velocities, accelerations, internal and
/// external forces, the mass of each dof and its inverse (zero on a fixed dof, which the forces
/// then do not move), the time step, the damping and the thread pool of the passes.
pub(super) struct Motion {
    pub(super) u: Vec<f64>,
    pub(super) v: Vec<f64>,
    pub(super) a: Vec<f64>,
    pub(super) f_int: Vec<f64>,
    pub(super) f_ext: Vec<f64>,
    pub(super) mass: Vec<f64>,
    pub(super) inv_mass: Vec<f64>,
    pub(super) free: Vec<bool>,
    /// per dof, what its force counts for in the unbalanced ratio: 1 for a translation, and for a
    /// rotation, whose force is a moment, one over its block's radius of gyration about that axis
    /// where that is more than a metre (see [`Motion::unbalanced_ratio`])
    pub(super) weight: Vec<f64>,
    pub(super) dt: f64,
    pub(super) damping: Damping,
    pub(super) pool: std::sync::Arc<rayon::ThreadPool>,
    /// whether the passes go to the pool (more than one thread and enough interfaces)
    pub(super) par: bool,
    pub(super) steps: usize,
    /// energy dissipated by the damping of the motion (local or viscous) \[J\], summed only
    /// with `track_damping`
    pub(super) damping_work: f64,
    pub(super) track_damping: bool,
}

/// Dofs per task of the block passes (a thousand blocks of the plane).
const GRAIN_DOFS: usize = 3 * GRAIN_BLOCKS;

impl Motion {
    /// The motion of blocks of `dof` dofs each (3 in the plane, the last a rotation; 6 in 3D,
    /// the last three), with dof masses `mass` (the fixed dofs marked in `fixed`) at rest at
    /// displacements `u`, time step `dt`, `damping` (checked), and a pool of `threads` threads
    /// (0: all cores) used when `par`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn new(dof: usize, mass: Vec<f64>, fixed: &[bool], u: Vec<f64>, dt: f64, damping: Damping, pool: std::sync::Arc<rayon::ThreadPool>, par: bool) -> Result<Motion, Error> {
        check_damping(damping)?;
        let n = mass.len();
        let rotations = dof / 3;
        let weight = (0..n)
            .map(|d| {
                let (block, k) = (d / dof, d % dof);
                if k < dof - rotations {
                    1.0
                } else {
                    1.0 / (mass[d] / mass[dof * block]).sqrt().max(1.0)
                }
            })
            .collect();
        let inv_mass = mass.iter().zip(fixed).map(|(&m, &f)| if f { 0.0 } else { 1.0 / m }).collect();
        Ok(Motion {
            u,
            v: vec![0.0; n],
            a: vec![0.0; n],
            f_int: vec![0.0; n],
            f_ext: vec![0.0; n],
            mass,
            inv_mass,
            free: fixed.iter().map(|f| !f).collect(),
            weight,
            dt,
            damping,
            pool,
            par,
            steps: 0,
            damping_work: 0.0,
            track_damping: false,
        })
    }

    /// Fixes dofs `dofs` where they are now, at rest.
    pub(super) fn hold(&mut self, dofs: &[usize]) {
        for &d in dofs {
            self.free[d] = false;
            self.inv_mass[d] = 0.0;
            self.v[d] = 0.0;
            self.a[d] = 0.0;
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
            let (a, v) = (&mut self.a, &mut self.v);
            self.pool.install(|| a.par_chunks_mut(GRAIN_DOFS).zip(v.par_chunks_mut(GRAIN_DOFS)).enumerate().for_each(|(c, (a, v))| work(c * GRAIN_DOFS, a, v)));
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
            self.u.par_chunks_mut(GRAIN_DOFS).zip(self.v.par_chunks_mut(GRAIN_DOFS)).enumerate().for_each(|(c, (u, v))| drift(c * GRAIN_DOFS, u, v));
        } else {
            drift(0, &mut self.u, &mut self.v);
        }
        if let Some((d, val)) = prescribed {
            self.v[d] = (val - self.u[d]) / dt;
            self.u[d] = val;
        }
    }

    /// The second half of a velocity-Verlet step, after the interface pass: the external forces
    /// set by `set_ext` (from the internal ones, for a driven dof), the damping's work if it is
    /// tracked, and the accelerations and velocity half-step; the prescribed dof does not
    /// accelerate.
    pub(super) fn finish_step(&mut self, set_ext: &mut dyn FnMut(&mut [f64], &[f64]), prescribed: Option<(usize, f64)>) {
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

    /// |unbalanced forces| / |applied forces| on the free dofs, dof `skip` left out, a moment
    /// counted as the force that gives it at its block's radius of gyration where that is more
    /// than a metre. Counted as the force at a metre everywhere, the moments of large blocks
    /// outweighed their forces in proportion to their size: each level of a quasi-static run
    /// took more time steps the larger the model (on a cube of 1 km 45,984 time steps in all, of
    /// 1,000 km 50,512); on blocks of a metre or less, moments are counted as they always were.
    pub(super) fn unbalanced_ratio(&self, skip: Option<usize>) -> f64 {
        let (mut r, mut f) = (0.0, 0.0);
        for d in 0..self.u.len() {
            if self.free[d] && Some(d) != skip {
                let w = self.weight[d];
                let x = (self.f_ext[d] - self.f_int[d]) * w;
                r += x * x;
                f += self.f_ext[d] * w * (self.f_ext[d] * w);
            }
        }
        (r / f.max(f64::MIN_POSITIVE)).sqrt()
    }

    /// The power the damping of the motion takes from it at the current forces and velocities
    /// (those of the next kick: the mid-step velocities) \[W\], never negative.
    pub(super) fn damping_power(&self) -> f64 {
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

    pub(super) fn kinetic_energy(&self) -> f64 {
        0.5 * (0..self.u.len()).filter(|&d| self.free[d]).map(|d| self.mass[d] * self.v[d] * self.v[d]).sum::<f64>()
    }
}

/// Gershgorin's bound on `omega_max^2`, the largest eigenvalue of `M^-1 K` over the free dofs,
/// summed interface by interface: the smaller of two. The first is the largest row sum of
/// absolute values of `M^-1 K` itself, which mixes the units of translations and rotations (a
/// translation's row adds the coupling to a rotation, `k L` in N/rad, to `k`): on blocks beyond
/// a few metres it stops falling with their size, where `omega_max^2` falls as `1 / size`, the
/// time step stopped growing, and a level of a quasi-static run took time steps in proportion to
/// the square root of the size (a box of 1e6 m 3.9 million, of 1 m 31,760). The second,
/// [`SCALED_BOUND`] times the row sums of `M^-1/2 K M^-1/2`, is the same in any units.
pub(super) struct Gershgorin {
    /// per dof: `sum_j |k_ij|` and `sum_j |k_ij| w_j`
    plain: Vec<f64>,
    scaled: Vec<f64>,
    /// per dof: its mass, and `w = 1 / sqrt(m)` on a free dof, 0 on a fixed one
    mass: Vec<f64>,
    w: Vec<f64>,
}

impl Gershgorin {
    /// No stiffness yet, over dofs of masses `mass`, those of `fixed` left out.
    pub(super) fn new(mass: &[f64], fixed: &[bool]) -> Gershgorin {
        let w = mass.iter().zip(fixed).map(|(&m, &f)| if f { 0.0 } else { 1.0 / m.sqrt() }).collect();
        Gershgorin { plain: vec![0.0; mass.len()], scaled: vec![0.0; mass.len()], mass: mass.to_vec(), w }
    }

    /// Adds an interface's share of the stiffness matrix, `B^T diag(d) B` on its dofs `dofs`.
    pub(super) fn add<const N: usize>(&mut self, dofs: &[usize], b: &[[f64; N]; 3], d: [f64; 3]) {
        for i in 0..N {
            for j in 0..N {
                let kij = (d[0] * b[0][i] * b[0][j] + d[1] * b[1][i] * b[1][j] + d[2] * b[2][i] * b[2][j]).abs();
                self.plain[dofs[i]] += kij;
                self.scaled[dofs[i]] += kij * self.w[dofs[j]];
            }
        }
    }

    /// The stable time step `2 / omega_max` (infinite where no stiffness holds a free dof).
    pub(super) fn step(&self) -> f64 {
        let (mut plain, mut scaled) = (0.0f64, 0.0f64);
        for (d, &w) in self.w.iter().enumerate() {
            if w > 0.0 {
                plain = plain.max(self.plain[d] / self.mass[d]);
                scaled = scaled.max(self.scaled[d] * w);
            }
        }
        let w2 = plain.min(SCALED_BOUND * scaled);
        if w2 > 0.0 {
            2.0 / w2.sqrt()
        } else {
            f64::INFINITY
        }
    }
}

/// How far above the row sums of `M^-1/2 K M^-1/2` (a tight bound: a block of the plane's walls,
/// 0.4 x 0.175 m, gives a time step 0.96 of its exact limit) the bound on `omega_max^2` is taken.
/// On blocks of tenths of a metre to metres the first bound lies 2.6 to 8 times above that sum
/// (that block 3.4, the plane's running bond of them 5.5, a leaf 7.0, a U wall 7.8, cubes of 1
/// and 10 m 2.8 and 2.6), so their time steps are the first bound's, those the explicit
/// solver's relaxations were made and tested with; they rely on them: at 0.8 of the tight
/// limit, local damping lets that block of friction 0.65 creep at lambda = 0.02, and it is said
/// to collapse at lambda = 0. With 8 the time step is never more than 0.8 / sqrt(8) = 0.28 of
/// the exact limit, as on the leaf (0.30), at any size.
pub(super) const SCALED_BOUND: f64 = 8.0;

/// The time step: `dt` if given (finite, positive and within the stability limit `crit`), else
/// `safety` (in (0, 1]) times that limit, which some stiffness must bound; and `damping`
/// checked (its range, and viscous damping stable at that time step: see
/// [`check_viscous_stability`]).
pub(super) fn checked_time_step(crit: f64, dt: Option<f64>, safety: f64, damping: Damping) -> Result<f64, Error> {
    let dt = match dt {
        Some(dt) => {
            if !(dt.is_finite() && dt > 0.0) {
                return Err(Error::input(format!("analysis.time_step must be a finite number > 0, got {dt}")));
            }
            if dt > crit {
                return Err(Error::input(format!(
                    "analysis.time_step = {dt:.3e} s exceeds the stability limit of this model, {crit:.3e} s"
                )));
            }
            dt
        }
        None => {
            if !(safety > 0.0 && safety <= 1.0) {
                return Err(Error::input(format!("safety must lie in (0, 1], got {safety}")));
            }
            if !crit.is_finite() {
                return Err(Error::input("no stiffness holds the model: no stable time step"));
            }
            safety * crit
        }
    };
    check_damping(damping)?;
    check_viscous_stability(damping, dt, crit)?;
    Ok(dt)
}

/// Refuses viscous damping `c` that the integrator cannot carry at time step `dt` (stability
/// limit `crit`, `2 / omega_max`). Velocity Verlet with the damping force `-c m v` at the
/// half-step velocity takes, on a dof of frequency omega, `v' = (1 - c dt) v - omega^2 dt x`,
/// `x' = x + dt v'`: its step matrix has determinant `1 - c dt` and trace `2 - c dt - omega^2
/// dt^2`, and stays stable while `c dt / 2 + (omega dt / 2)^2 <= 1` (Jury's conditions). Beyond
/// it the motion grows at every step (at c dt above 2 even a dof without stiffness), and a
/// relaxation ended in "no equilibrium under the dead loads alone".
fn check_viscous_stability(damping: Damping, dt: f64, crit: f64) -> Result<(), Error> {
    if let Damping::Viscous(c) = damping {
        let r = dt / crit;
        let measure = 0.5 * c * dt + r * r;
        if measure > 1.0 {
            return Err(Error::input_at("analysis.damping_coefficient", format!(
                "analysis.damping_coefficient (viscous damping) = {c:e} 1/s is unstable at the time step {dt:.3e} s (the stability limit {crit:.3e} s): the integrator needs c dt / 2 + (dt / limit)^2 <= 1, here {measure:.3e}; at this time step c may be at most {:.3e} 1/s",
                2.0 * (1.0 - r * r) / dt
            )));
        }
    }
    Ok(())
}

/// Refuses a damping coefficient out of its range: local damping in [0, 1), viscous damping
/// finite and non-negative.
pub(super) fn check_damping(damping: Damping) -> Result<(), Error> {
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

/// The thread pool of `threads` threads (0: all cores) for `m` interfaces, whether the passes
/// go to it (more than one thread and at least `par_min` interfaces, enough to pay for the
/// hand-offs), and the parts of the interface pass (one unless they do; else at least two per
/// thread).
pub(super) fn start_pool(threads: usize, m: usize, par_min: usize) -> Result<(std::sync::Arc<rayon::ThreadPool>, bool, usize), Error> {
    if threads > MAX_THREADS {
        return Err(Error::input(format!("analysis.threads = {threads} is more than the limit of {MAX_THREADS}")));
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| Error::input(format!("cannot start {threads} threads: {e}")))?;
    let par = pool.current_num_threads() > 1 && m >= par_min;
    let n_parts = if par { (2 * pool.current_num_threads()).max(m.div_ceil(PART_INTERFACES)) } else { 1 };
    Ok((std::sync::Arc::new(pool), par, n_parts))
}

/// An integrator of either dimension as the drivers (quasi-static levels, time histories) see
/// it: its [`Motion`] (through `Deref`) and what the dimension decides.
pub(super) trait Kernel: std::ops::DerefMut<Target = Motion> {
    /// Dofs per block: 3 in the plane (u1, u2, phi), 6 in 3D (ux, uy, uz, rx, ry, rz).
    const DOF: usize;
    /// A block's (and a contact's) vector in [`Results`].
    type V: Copy;
    /// One velocity-Verlet step; `set_ext` sets the external forces at the new time (from the
    /// internal ones for a driven dof); `prescribed`: a dof driven to a value.
    fn step(&mut self, set_ext: &mut dyn FnMut(&mut [f64], &[f64]), prescribed: Option<(usize, f64)>);
    /// The interface forces at the current displacements, gathered into `f_int`.
    fn interface_forces(&mut self);
    /// Fixes the dofs the model holds once the dead loads are on.
    fn hold(&mut self);
    /// How often a loop of steps reads the clock (a power of two).
    fn clock_every(&self) -> usize;
    /// The committed joint histories and broken flags (a level that runs away is undone to them).
    fn history(&self) -> (&[f64], &[bool]);
    fn history_mut(&mut self) -> (&mut [f64], &mut [bool]);
    /// The length of block `i`'s translation in `u` (from `from`, if given) \[m\].
    fn translation(u: &[f64], from: Option<&[f64]>, i: usize) -> f64;
    /// Block `i`'s dofs in `u` as a vector of [`Results`].
    fn block(u: &[f64], i: usize) -> Self::V;
    /// The contacts' forces, states and broken flags, for [`Results`].
    fn into_contacts(self) -> (Vec<Self::V>, Vec<u8>, Vec<bool>);
    /// The contacts the contact update has created so far (zero without it).
    fn contacts_created(&self) -> usize;
}
