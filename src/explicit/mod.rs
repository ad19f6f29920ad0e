//! The explicit ("molecular dynamics") solver: velocity-Verlet integration of the blocks'
//! equations of motion `M a = f_ext(t) - f_int(u) - f_damp`, with a diagonal mass (m, m, J).
//! It never assembles or factorizes a matrix. Interface forces come from the same joint law as
//! the static solver ([`crate::joint::return_map`]), applied to the increments of each time step
//! (histories are committed at every step).
//!
//! - Time step: `safety * 2 / omega_max`, with `omega_max` bounded from above by Gershgorin's
//!   theorem on the elastic interface stiffnesses (so the step is stable), unless given.
//! - Damping: local non-viscous (Cundall: `-alpha |f| sign(v)` per dof; the default of
//!   quasi-static runs) or mass-proportional viscous (`-c m v`).
//! - Quasi-static load control: each load level is relaxed until the unbalanced-force ratio is
//!   below a tolerance; a level at which the wall runs away (or does not settle) is a failure,
//!   and the collapse multiplier is bracketed by halving the load step, as in the static solver.
//!   A wall creeping towards an equilibrium near its collapse multiplier (moving well beyond its
//!   elastic response, but slowing down or with its unbalanced forces falling fast enough to
//!   settle within `max_steps_per_level`) keeps relaxing; a level runs away on evidence that it
//!   will not settle (over successive windows, neither), or when a block moves 1% of the wall's
//!   size.
//! - Quasi-static displacement control: the control dof is driven; lambda follows from the
//!   control dof's own equation (the condition of the static solver's bordered system).
//! - Time histories: free motion from initial conditions, or a horizontal base acceleration
//!   (inertial forces `-m a_g(t)` in the frame of the base).
//!
//! - Contact update (time histories of either dimension, with finite rotations, unless
//!   `contact_update` is false; pushovers in the plane when it is set; in 3D faces for edges,
//!   see `space::update`): the contacts are searched again, on the grid of the model's
//!   detection, whenever some block has moved by more than half the gap tolerance since the
//!   last search (a point of it: the centroid's translation plus the rotation times the
//!   block's radius). The gap tolerance is [`GAP_FRACTION`] of the least side of the smallest
//!   wall block's box: two edges whose outward normals are opposed within 60 degrees,
//!   overlapping along one of them with the nearer end within the gap, are a contact (open, no
//!   force, until they close); a contact whose edges no longer are is dropped. A contact found
//!   again keeps its joint history and dashpot (its geometry is taken again from the moved
//!   blocks once a point of it or its length is off by more than [`RETAKE`] gaps, its elastic
//!   slip kept); a new one is dry (no cohesion or tensile strength), starts without shear force and
//!   has its joint's contact dashpot (restitution). A ground plane, fixed, horizontal (gravity
//!   along -y), lies at the top of the base (without a base, at the lowest point of the model)
//!   and reaches beyond the box around all the blocks by [`GROUND_REACH`] times the model's
//!   size on each side: a block that leaves every contact falls onto it. With the update the
//!   time step is also stable for a block touching fixed bodies along every edge, and a run
//!   ends as out of the model's range only when a block has moved by more than seven times the
//!   model's size (off the ground).
//!
//! The interface loop is the hot path: flat arrays, no allocation per step, parallel over
//! parts of the interfaces with rayon (each interface writes only its own slot, and each part
//! the force sums of the blocks whose interfaces are all in it; a gather forms the others).
//!
//! Here: the options, the time history and the stability limit. The interface pass is in
//! `pass`, the integrator in `integrator`, the quasi-static drivers (and the relaxations the
//! static solver borrows) in `quasi_static`, time histories in `time_history`.
//!
//! ```
//! use masonry_dem::explicit::{simulate, Damping, DynamicOptions};
//! use masonry_dem::geometry::Rect;
//! use masonry_dem::model::{Model, ModelSpec};
//! // one block of 0.4 x 0.2 m on the base
//! let model = Model::new(ModelSpec { blocks: vec![Rect::new(0.0, 0.0, 0.4, 0.2).into()], ..ModelSpec::default() }).unwrap();
//! // a tenth of a second at rest on its base, damped: the block settles and stays
//! let opts = DynamicOptions { duration: 0.1, damping: Damping::Local(0.8), ..DynamicOptions::default() };
//! let h = simulate(&model, &opts).unwrap();
//! // the recorded states, n_blocks rows each: the block (0) in the last one
//! let settled = h.displacements[h.displacements.len() - h.n_blocks];
//! assert!(settled[0].abs() < 1e-9 && settled[1] < 0.0 && settled[1] > -1e-6);
//! ```

use crate::error::Error;
use crate::interface::{Arm, Family, Interface};
use crate::joint::{return_map_inlined, JointLaw, MapOptions, JointState, Kinds, Response, Section, APEX};
use crate::model::Model;
use crate::results::{Results, Status};
use rayon::prelude::*;

pub use crate::analysis::{Control, Progress};
use std::time::Instant;

/// Damping of the explicit solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Damping {
    /// No damping.
    None,
    /// Local non-viscous damping (Cundall): a force `-alpha |f| sign(v)` on each dof, `alpha` in [0, 1).
    Local(f64),
    /// Mass-proportional viscous damping `-c m v` [1/s].
    Viscous(f64),
}

/// The default fraction of the stability limit taken as the time step.
pub const SAFETY: f64 = 0.8;

/// The default coefficient of local damping (alpha) of quasi-static runs and relaxations.
pub const LOCAL_DAMPING: f64 = 0.8;

/// The largest number of threads of the interface loop (`analysis.threads`).
pub const MAX_THREADS: usize = 1024;
/// The largest number of time steps of one time history ([`simulate`]).
pub const MAX_TIME_STEPS: usize = 1_000_000_000_000;
/// The largest number of values a time history may record (displacements and velocities: 6 per
/// block and record, 8 bytes each); larger requests are refused before allocating.
pub const MAX_RECORDED_VALUES: usize = 250_000_000;

/// Options of the quasi-static explicit analysis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExplicitOptions {
    /// How the load is driven.
    pub control: Control,
    /// Load levels or displacement stages (a hint, as for the static solver).
    pub steps: usize,
    /// Relative width of the bracket on the collapse multiplier.
    pub tolerance: f64,
    /// A level is settled when |unbalanced forces| <= ratio * |applied forces|.
    pub unbalanced_ratio: f64,
    /// The damping of the motion.
    pub damping: Damping,
    /// Time step \[s\]; None: automatic.
    pub time_step: Option<f64>,
    /// Fraction of the stability limit used by the automatic time step.
    pub safety: f64,
    /// Time steps allowed to settle one level before it counts as not settling; a level whose
    /// unbalanced forces fall too slowly to settle within them, while the wall does not slow
    /// down, counts as running away before.
    pub max_steps_per_level: usize,
    /// Threads of the interface loop; 0: all cores.
    pub threads: usize,
    /// The block whose horizontal displacement is followed (and driven under displacement control); `None`: [`Model::default_control_block`](crate::model::Model::default_control_block).
    pub control_block: Option<usize>,
    /// Finite rotations of the blocks: the equilibrium on the moved geometry (the
    /// large-displacement capacity curve under displacement control); false (the default):
    /// the linearized kinematics, the equilibrium on the wall as built.
    pub large_rotations: bool,
    /// The contacts found again as the blocks move (see the contact update in this module's
    /// notes); with `large_rotations` only, in the plane only. Off by default.
    pub contact_update: bool,
}

impl Default for ExplicitOptions {
    fn default() -> Self {
        ExplicitOptions {
            control: Control::Load,
            steps: 200,
            tolerance: 1e-3,
            unbalanced_ratio: 1e-5,
            damping: Damping::Local(LOCAL_DAMPING),
            time_step: None,
            safety: SAFETY,
            max_steps_per_level: 200_000,
            threads: 0,
            control_block: None,
            large_rotations: false,
            contact_update: false,
        }
    }
}

/// Options of a dynamic time history; `V` is a block's dofs: `[f64; 3]` in the plane (the
/// default), `[f64; 6]` in 3D ([`simulate_3d`]).
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicOptions<V = [f64; 3]> {
    /// Duration \[s\].
    pub duration: f64,
    /// The time step \[s\]; `None`: `safety` times the stability limit.
    pub time_step: Option<f64>,
    /// The fraction of the stability limit taken as the time step when none is given.
    pub safety: f64,
    /// The damping of the motion.
    pub damping: Damping,
    /// beta \[s\], stiffness-proportional damping `beta K` at the closed interfaces (dashpots
    /// `beta (kN A, kT A, kN I)` on the jump rates, cut as the contact dashpots are): with
    /// `Damping::Viscous(alpha)`, Rayleigh damping `alpha M + beta K`
    /// ([`crate::modal::rayleigh_coefficients`]). 0: none. The plane's only.
    pub stiffness_damping: f64,
    /// Initial displacements of every block ((u1, u2, phi) in the plane; (ux, uy, uz, rx, ry,
    /// rz) in 3D, the rotation a rotation vector); None: zero.
    pub initial_displacement: Option<Vec<V>>,
    /// Initial velocities of every block (in 3D the angular velocity in the world's axes); None: zero.
    pub initial_velocity: Option<Vec<V>>,
    /// Horizontal base acceleration history (along x): times \[s\] and accelerations [m/s2],
    /// linear between samples, zero outside.
    pub base_acceleration: Option<(Vec<f64>, Vec<f64>)>,
    /// Base acceleration history along y, as `base_acceleration` (3D only).
    pub base_acceleration_y: Option<(Vec<f64>, Vec<f64>)>,
    /// Vertical base acceleration history (upwards positive), as `base_acceleration`.
    pub vertical_acceleration: Option<(Vec<f64>, Vec<f64>)>,
    /// Live load multiplier held constant during the run.
    pub live_multiplier: f64,
    /// Which states are recorded (the first and the last always are).
    pub record: Recording,
    /// Finite rotations of the blocks (rocking); false: the linearized kinematics.
    pub large_rotations: bool,
    /// Threads of the interface pass (0: all cores).
    pub threads: usize,
    /// The contacts found again as the blocks move, and a ground plane under the model (see the
    /// contact update in this module's notes), with finite rotations (`large_rotations`), in either
    /// dimension: with the linearized kinematics the contacts stay those of the wall as built.
    /// On by default.
    pub contact_update: bool,
}

impl<V> Default for DynamicOptions<V> {
    fn default() -> Self {
        DynamicOptions {
            duration: 1.0,
            time_step: None,
            safety: SAFETY,
            damping: Damping::None,
            stiffness_damping: 0.0,
            initial_displacement: None,
            initial_velocity: None,
            base_acceleration: None,
            base_acceleration_y: None,
            vertical_acceleration: None,
            live_multiplier: 0.0,
            record: Recording::Interval(DEFAULT_RECORD_INTERVAL),
            large_rotations: true,
            threads: 0,
            contact_update: true,
        }
    }
}

/// Which states of a time history are recorded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Recording {
    /// Every n-th time step.
    Every(usize),
    /// The first state at or after each multiple of this interval of time \[s\].
    Interval(f64),
}

/// The default interval between the recorded states of a time history \[s\] (1 kHz: finer
/// than any earthquake record's samples, and the impacts of a rocking block timed to 1 ms).
pub const DEFAULT_RECORD_INTERVAL: f64 = 1e-3;

/// A recorded time history; `V` as in [`DynamicOptions`].
#[derive(Debug, Clone, PartialEq)]
pub struct TimeHistory<V = [f64; 3]> {
    /// How the run ended.
    pub status: Status,
    /// Why, where the status is not a success (the message of the error that ended the run).
    pub error: Option<String>,
    /// The time step used \[s\].
    pub time_step: f64,
    /// The times of the recorded states \[s\].
    pub times: Vec<f64>,
    /// Blocks in each record.
    pub n_blocks: usize,
    /// The displacements of every block at each recorded time ((u1, u2, phi) in the plane;
    /// (ux, uy, uz, rx, ry, rz) in 3D, the rotation vector of the block's orientation), flat and
    /// record-major: record k is `displacements[k * n_blocks..(k + 1) * n_blocks]` (see
    /// [`TimeHistory::displacement`]).
    pub displacements: Vec<V>,
    /// Velocities, laid out as `displacements` (in 3D the angular velocity in the world's axes).
    pub velocities: Vec<V>,
    /// The ground's acceleration (horizontal along x, vertical) [m/s2] at each recorded time.
    pub ground_acceleration: Vec<[f64; 2]>,
    /// 3D: the ground's acceleration along y [m/s2] at each recorded time (empty in the plane).
    pub ground_acceleration_y: Vec<f64>,
    /// The horizontal force of the wall on its base \[N\] (positive along +x) at each recorded
    /// time: the joints' forces on the base block, their dashpots' included.
    pub base_shear: Vec<f64>,
    /// 3D: the force of the wall on its base along y \[N\] (empty in the plane).
    pub base_shear_y: Vec<f64>,
    /// The energy balance, at each recorded time \[J\]: the initial kinetic and elastic energies
    /// plus the external work are the kinetic and elastic energies, the dissipated energy and
    /// the balance's error. Kinetic energy.
    pub kinetic_energy: Vec<f64>,
    /// Elastic energy stored in the joints \[J\].
    pub elastic_energy: Vec<f64>,
    /// Work done on the blocks by the external loads since the start (weights, dead and live
    /// loads, the inertial forces of the base's motion) \[J\].
    pub external_work: Vec<f64>,
    /// The part of `external_work` done by the weights \[J\].
    pub gravity_work: Vec<f64>,
    /// Energy dissipated in the joints by friction and by the loss of strength \[J\].
    pub friction_dissipation: Vec<f64>,
    /// Energy dissipated by the damping of the motion (local, viscous, and stiffness-proportional) \[J\].
    pub damping_dissipation: Vec<f64>,
    /// Energy dissipated by the contact dashpots of impacts (see [`contact`]) \[J\].
    pub impact_dissipation: Vec<f64>,
    /// The sum of the three dissipations \[J\].
    pub dissipated: Vec<f64>,
    /// The balance's error: initial kinetic and elastic energies + external work - kinetic -
    /// elastic - dissipated \[J\] (the integrator's, of order time step squared).
    pub energy_error: Vec<f64>,
    /// Steps taken (time steps for a time history).
    pub steps: usize,
    /// Wall-clock time of the run \[s\].
    pub elapsed_s: f64,
    /// With the contact update: the searches for contacts made (zero without it).
    pub contact_searches: usize,
    /// With the contact update: the contacts created (zero without it).
    pub contacts_created: usize,
    /// With the contact update: the contacts dropped (zero without it).
    pub contacts_dropped: usize,
    /// With the contact update: the contacts whose geometry was taken again from the moved
    /// blocks (zero without it).
    pub contacts_renewed: usize,
    /// With the contact update: the contacts at the end of the run (empty without it).
    pub contacts: Vec<ContactAt>,
    /// With the contact update in 3D: the contacts at the end of the run (empty without it, and
    /// in the plane).
    pub contacts_3d: Vec<ContactAt3>,
    /// With the contact update: every contact created, dropped or taken again, in the order of
    /// the searches (empty without it; in 3D, empty: the counts only). With the model's
    /// interfaces, they give the contacts at any time (see [`ContactEvent`]).
    pub contact_events: Vec<ContactEvent>,
    /// With the contact update: the ground plane's level \[m\], if the model has one.
    pub ground_level: Option<f64>,
}

/// What happened to a contact at a search of the contact update.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactChange {
    /// A new contact: its edges came to face each other within the gap tolerance.
    Created,
    /// Its edges no longer face each other within the gap: it is gone.
    Dropped,
    /// Found again, its geometry taken again from the moved blocks (its history kept).
    Renewed,
}

impl ContactChange {
    /// "created", "dropped" or "renewed".
    pub fn as_str(self) -> &'static str {
        match self {
            ContactChange::Created => "created",
            ContactChange::Dropped => "dropped",
            ContactChange::Renewed => "renewed",
        }
    }
}

/// A change of the contacts of a time history with the contact update. A contact is numbered
/// once: the model's interfaces `0..n` in their order, then each contact the update creates, in
/// turn. Its geometry is given in block a's reference position (at rest, unturned): at a time
/// `t` block a's displacement (u1, u2, phi) carries its centre to `g_a + (u1, u2) + R(phi)
/// centre` and turns its normal by phi. The contacts at time `t` are the model's interfaces,
/// with each event up to `t` applied in order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactEvent {
    /// When \[s\].
    pub time: f64,
    /// What happened.
    pub change: ContactChange,
    /// The contact's number (see above).
    pub id: usize,
    /// Its two blocks (a: the one whose edge gives the normal); a dropped contact's last.
    pub blocks: [usize; 2],
    /// Its centre relative to block a's centroid, in a's reference position \[m\] (zero when
    /// dropped).
    pub centre: [f64; 2],
    /// Its unit normal from a into b, in a's reference position (zero when dropped).
    pub normal: [f64; 2],
    /// Its length \[m\] (zero when dropped).
    pub length: f64,
}

/// A contact at the end of a time history with the contact update: its two blocks (a: the one
/// whose edge gives the normal), its centre \[m\], its normal (from a into b), its length \[m\]
/// and the gap at its centre \[m\] (negative: closed).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactAt {
    /// The two blocks (a, b).
    pub blocks: [usize; 2],
    /// The centre \[m\].
    pub centre: [f64; 2],
    /// The unit normal from a into b.
    pub normal: [f64; 2],
    /// The length \[m\].
    pub length: f64,
    /// The gap at the centre \[m\] (negative: closed).
    pub gap: f64,
}

/// A contact at the end of a 3D time history with the contact update: its two blocks (a: the
/// one whose face gives the normal), its centroid \[m\], its normal (from a into b), its area
/// \[m2\] and the mean gap of its corners \[m\] (negative: closed).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactAt3 {
    /// The two blocks (a, b).
    pub blocks: [usize; 2],
    /// The centroid of its corners' shares \[m\], half-way between the blocks' faces.
    pub centre: [f64; 3],
    /// The unit normal from a into b.
    pub normal: [f64; 3],
    /// The area \[m2\].
    pub area: f64,
    /// The mean gap of its corners by their shares \[m\] (negative: closed).
    pub gap: f64,
}

impl<V> TimeHistory<V> {
    /// The displacements of every block at record `k`.
    pub fn displacement(&self, k: usize) -> &[V] {
        &self.displacements[k * self.n_blocks..(k + 1) * self.n_blocks]
    }
    /// Velocities of every block at record `k`.
    pub fn velocity(&self, k: usize) -> &[V] {
        &self.velocities[k * self.n_blocks..(k + 1) * self.n_blocks]
    }
}

/// Whether the monitor is due at step `k`: every 4,096 steps, or when 0.1 s of wall time have
/// passed since it was last called (on a large wall 4,096 steps take minutes, and Ctrl-C must
/// stop a run within half a second), the clock read every `every` steps (a power of two, see
/// [`Integrator::clock_every`]).
fn monitor_due(k: usize, every: usize, last: &mut Instant) -> bool {
    if k % 4096 == 4095 || (k % every == every - 1 && last.elapsed().as_secs_f64() >= 0.1) {
        *last = Instant::now();
        true
    } else {
        false
    }
}

/// The stable time step of the model: `2 / omega_max` with a Gershgorin bound on `omega_max`
/// (the smaller of the row sums of `M^-1 K` and of eight times those of `M^-1/2 K M^-1/2`: on
/// blocks beyond metres the first mixes the units of translations and rotations).
pub fn critical_time_step(model: &Model) -> f64 {
    let mut bound = Gershgorin::new(&integrator::masses(model), model.fixed());
    for (k, it) in model.interfaces().iter().enumerate() {
        let d = crate::joint::stiffness(model.law(k), &model.sections()[k]);
        bound.add(&it.dofs(), &it.b_mat, d);
    }
    bound.step()
}

pub mod contact;
mod evidence;
mod integrator;
mod motion;
mod movement;
mod pass;
mod quasi_static;
mod space;
#[cfg(any(test, feature = "bench-internals"))]
mod stepper;
#[cfg(test)]
mod tests;
mod time_history;
mod update;

use integrator::*;
use motion::*;
use pass::*;
#[cfg(any(test, feature = "bench-internals"))]
pub use stepper::{Stepper, Stepper3};
pub(crate) use quasi_static::{relax_at_displacement, relax_dead_state};
pub use movement::{solve_movement, FALL_FRACTION};
pub use quasi_static::{solve, solve_with};
// the modal analysis in 3D takes the same kinematics and rotation dofs as a time history
pub(crate) use space::{jump_rows, principal_axes, to_world};
pub use space::{critical_time_step_3d, critical_time_step_moving_3d, history_time_step_limit_3d, record_size_3d, simulate_3d, simulate_3d_with, solve_3d, solve_3d_with};
pub use update::{GAP_FRACTION, GROUND_REACH, RETAKE};
pub use time_history::{history_time_step_limit, record_count, record_size, simulate, simulate_with};
