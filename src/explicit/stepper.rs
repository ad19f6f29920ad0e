//! [`Stepper`]: time steps of the integrator from outside the crate (benchmarks, profiling), with
//! the `bench-internals` feature; the crate's own unit tests use it without.

use super::*;

/// Puts `s` under `dead + live_multiplier live` at rest (its interface forces and
/// accelerations with them): those loads, for [`run`].
fn loaded<K: Kernel>(s: &mut K, dead: &[f64], live: &[f64], live_multiplier: f64) -> Vec<f64> {
    let f: Vec<f64> = dead.iter().zip(live).map(|(d, l)| d + live_multiplier * l).collect();
    s.f_ext.copy_from_slice(&f);
    s.interface_forces();
    s.accelerations();
    f
}

/// `k` time steps of `s` under the fixed loads `f`.
fn run<K: Kernel>(s: &mut K, f: &[f64], k: usize) {
    let mut set_ext = |fe: &mut [f64], _: &[f64]| fe.copy_from_slice(f);
    for _ in 0..k {
        s.step(&mut set_ext, None);
    }
}

/// A bare time stepper over the integrator of [`simulate`], for benchmarks and profiling (not
/// part of the supported API): the model under its dead loads plus `live_multiplier` times its
/// live loads, from rest, with the automatic time step (safety 0.8). [`Stepper::run`] does
/// `k` time steps and nothing else: no records, no energy, no checks.
///
/// ```
/// use masonry_dem::explicit::{Damping, Stepper};
/// use masonry_dem::geometry::Rect;
/// use masonry_dem::model::{Model, ModelSpec};
/// let model = Model::new(ModelSpec { blocks: vec![Rect::new(0.0, 0.0, 0.4, 0.2).into()], ..ModelSpec::default() }).unwrap();
/// let mut s = Stepper::new(&model, 0.0, Damping::Local(0.8), false, 1).unwrap();
/// s.run(10);
/// assert_eq!(s.n_interfaces(), 1);
/// assert!(s.displacements()[1] < 0.0); // the block settles onto the base
/// ```
pub struct Stepper<'a> {
    pub(super) s: Integrator<'a>,
    pub(super) f: Vec<f64>,
}

impl<'a> Stepper<'a> {
    /// The integrator of `model` (linearized kinematics unless `large_rotations`) on `threads`
    /// threads (0: all cores).
    pub fn new(model: &'a Model, live_multiplier: f64, damping: Damping, large_rotations: bool, threads: usize) -> Result<Self, Error> {
        let mut s = Integrator::new(model, None, 0.8, damping, threads)?;
        s.set_large(large_rotations);
        let f = loaded(&mut s, model.dead_load(), model.live_load(), live_multiplier);
        Ok(Stepper { s, f })
    }

    /// `k` time steps.
    pub fn run(&mut self, k: usize) {
        run(&mut self.s, &self.f, k);
    }

    /// Number of interfaces.
    pub fn n_interfaces(&self) -> usize {
        self.s.model.interfaces().len()
    }

    /// The time step \[s\].
    pub fn time_step(&self) -> f64 {
        self.s.dt
    }

    /// (u1, u2, phi) of every block, flat.
    pub fn displacements(&self) -> &[f64] {
        &self.s.u
    }

    /// The interface forces (N, T, M) of the last step.
    pub fn interface_forces(&self) -> &[[f64; 3]] {
        &self.s.forces
    }
}

/// The 3D counterpart of [`Stepper`]: bare time steps of the 3D integrator (small rotations
/// unless `large_rotations`), for benchmarks and profiling (not part of the supported API).
///
/// ```
/// use masonry_dem::explicit::{Damping, Stepper3};
/// use masonry_dem::space::{Box3, Model3, ModelSpec3};
/// let model = Model3::new(&ModelSpec3 { blocks: vec![Box3::new(0.0, 0.0, 0.0, 0.4, 0.4, 0.2)], ..ModelSpec3::default() }).unwrap();
/// let mut s = Stepper3::new(&model, 0.0, Damping::Local(0.8), false, 1).unwrap();
/// s.run(10);
/// assert_eq!(s.n_points(), 4);
/// assert!(s.displacements()[2] < 0.0); // the block settles onto the base
/// ```
pub struct Stepper3<'a> {
    pub(super) s: super::space::Integrator3<'a>,
    pub(super) f: Vec<f64>,
}

impl<'a> Stepper3<'a> {
    /// The integrator of `model` on `threads` threads (0: all cores).
    pub fn new(model: &'a crate::space::Model3, live_multiplier: f64, damping: Damping, large_rotations: bool, threads: usize) -> Result<Self, Error> {
        let mut s = super::space::Integrator3::new(model, None, 0.8, damping, threads, large_rotations)?;
        s.set_large(large_rotations);
        let f = loaded(&mut s, model.dead_load(), model.live_load(), live_multiplier);
        Ok(Stepper3 { s, f })
    }

    /// `k` time steps.
    pub fn run(&mut self, k: usize) {
        run(&mut self.s, &self.f, k);
    }

    /// Number of contact points (a contact's corners).
    pub fn n_points(&self) -> usize {
        self.s.n_points()
    }

    /// The time step \[s\].
    pub fn time_step(&self) -> f64 {
        self.s.m.dt
    }

    /// The 6 dofs of every block, flat.
    pub fn displacements(&self) -> &[f64] {
        &self.s.m.u
    }
}
