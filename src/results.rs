//! What an analysis returns.
//!
//! ```
//! use masonry_dem::joint::JointLaw;
//! use masonry_dem::limit::{limit_analysis, LimitOptions};
//! use masonry_dem::results::Status;
//! use masonry_dem::geometry::Rect;
//! use masonry_dem::model::{JointLaws, Model, ModelSpec};
//! // one block of 0.4 x 0.2 m on the base, its joint dry and associative
//! let law = JointLaw { friction: 0.65, dilatancy: 0.65, ..JointLaw::default() };
//! let blocks = vec![Rect::new(0.0, 0.0, 0.4, 0.2).into()];
//! let model = Model::new(ModelSpec { blocks: blocks.clone(), joints: JointLaws::uniform(law), ..ModelSpec::default() }).unwrap();
//! let r = limit_analysis(&model, &LimitOptions::default()).unwrap();
//! assert_eq!(r.status, Status::Collapse);
//! assert_eq!(r.status.as_str(), "collapse");
//! // the block slides at lambda = friction (0.65) before it rocks (at width / height = 2)
//! assert!((r.collapse_multiplier - 0.65).abs() < 1e-6);
//! // with dilatancy 0 the number is an estimate, not a collapse multiplier
//! let law = JointLaw { friction: 0.65, dilatancy: 0.0, ..JointLaw::default() };
//! let model = Model::new(ModelSpec { blocks, joints: JointLaws::uniform(law), ..ModelSpec::default() }).unwrap();
//! let r = limit_analysis(&model, &LimitOptions::default()).unwrap();
//! assert_eq!(r.status, Status::Estimate);
//! assert!(r.collapse_multiplier.is_nan() && (r.last_equilibrium - 0.65).abs() < 1e-6);
//! ```

use crate::joint::{OPEN, ROCKING, SLIDING};

/// How an analysis ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// A mechanism formed; `collapse_multiplier` is the last equilibrium (or the peak of the curve).
    Collapse,
    /// The requested path ended without collapse.
    Completed,
    /// The solver failed; `error` says why and the curve holds the converged steps.
    Failed,
    /// The wall cannot stand under its dead loads (limit analysis: the program is infeasible, or
    /// its largest multiplier is negative).
    NoEquilibrium,
    /// The live load finds no mechanism within the analysis's range of multipliers.
    Unbounded,
    /// The incremental path stopped converging below the limit-analysis collapse multiplier
    /// (exact for associative dry joints): not a collapse. The curve holds the path, `error`
    /// both numbers.
    Stalled,
    /// The path left the small-displacement model (block translations beyond a tenth of the
    /// wall's size) while lambda still rose: not a collapse. `last_equilibrium` holds the
    /// largest lambda reached.
    DisplacementLimit,
    /// The caller stopped the run (Ctrl-C from Python, or a progress callback returning false):
    /// the curve holds the converged steps, `error` says so.
    Interrupted,
    /// Limit analysis of joints with dilatancy below friction: `last_equilibrium` holds the
    /// non-associative sequence's multiplier, an estimate that is neither bound (no collapse
    /// multiplier); the certificate holds it, the associative upper bound and whether the
    /// sequence converged, and `error` says so in a line.
    Estimate,
}

impl Status {
    /// The status of a run ended by error `e`: [`Status::Interrupted`] when the caller stopped
    /// it, [`Status::Failed`] otherwise.
    pub fn failure(e: &crate::error::Error) -> Status {
        if matches!(e, crate::error::Error::Interrupted) {
            Status::Interrupted
        } else {
            Status::Failed
        }
    }

    /// The name of the status in result files and in Python ("collapse", "stalled", ...).
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Collapse => "collapse",
            Status::Completed => "completed",
            Status::Failed => "failed",
            Status::NoEquilibrium => "no_equilibrium",
            Status::Unbounded => "unbounded",
            Status::Stalled => "stalled",
            Status::DisplacementLimit => "displacement_limit",
            Status::Interrupted => "interrupted",
            Status::Estimate => "estimate",
        }
    }
}

/// Counts of interfaces by state at the last converged step. An interface that both slides and
/// rocks counts in both; an open one counts only as open.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct JointStateCounts {
    /// Interfaces within their strength domain.
    pub elastic: usize,
    /// Interfaces on a Coulomb face.
    pub sliding: usize,
    /// Interfaces on a rocking face (a hinge at one edge).
    pub rocking: usize,
    /// Interfaces open across their whole length.
    pub open: usize,
}

/// Results of an analysis. Block arrays cover all blocks (wall, base, top beam).
///
/// `V` is what a block and an interface carry: `[f64; 3]` in the plane (the default), `[f64; 6]`
/// in 3D, where a block's entries are (ux, uy, uz \[m\], rx, ry, rz \[rad\]) (small rotations
/// about its centroid) and an interface's are the force and moment (about the contact's
/// centroid) that block b exerts on block a in the contact's axes (n, t1, t2):
/// (N, T1, T2 \[N\], M_n, M_t1, M_t2 \[N m\]), N > 0 in tension.
#[derive(Debug, Clone, PartialEq)]
pub struct Results<V = [f64; 3]> {
    /// "static" or "dynamic".
    pub method: &'static str,
    /// How the run ended.
    pub status: Status,
    /// Why, where the status is not a success (the message of the error that ended the run).
    pub error: Option<String>,
    /// lambda at collapse (load control) or the peak of the curve (displacement control);
    /// NaN unless the status is `Collapse`: a number is a collapse only with its evidence.
    pub collapse_multiplier: f64,
    /// The largest lambda of an equilibrium the analysis found (load control: the last
    /// converged step; displacement control: the peak of the curve), whatever the status; NaN
    /// when none converged. Equal to `collapse_multiplier` on a collapse.
    pub last_equilibrium: f64,
    /// lambda at each converged step, from the dead-load state (lambda = 0) on.
    pub curve_multiplier: Vec<f64>,
    /// Horizontal displacement of the control block's centroid \[m\] at each converged step.
    pub curve_displacement: Vec<f64>,
    /// The block whose horizontal displacement makes the curve.
    pub control_block: usize,
    /// (u1 \[m\], u2 \[m\], phi \[rad\]) of every block at the last converged step.
    pub displacements: Vec<V>,
    /// The collapse mechanism (the last increment), scaled so that the largest block
    /// translation is 1.
    pub mechanism: Vec<V>,
    /// (N \[N\], T \[N\], M [N m]) of every interface at the last converged step; N > 0 in tension.
    pub interface_forces: Vec<V>,
    /// OPEN | SLIDING | ROCKING bits of every interface (0: elastic).
    pub interface_states: Vec<u8>,
    /// Interfaces that have lost their cohesion and tensile strength.
    pub broken: Vec<bool>,
    /// Equilibrium iterations in all.
    pub iterations: usize,
    /// Converged steps.
    pub steps: usize,
    /// Wall-clock time of the run \[s\].
    pub elapsed_s: f64,
    /// Explicit load control ending in a collapse: the bracket on the collapse multiplier, the
    /// highest level that settled (the collapse multiplier) and the lowest that ran away (None
    /// otherwise).
    pub bracket: Option<[f64; 2]>,
    /// The limit analysis's evidence: its own, or, for a static load-control analysis of a wall
    /// of associative dry joints, that of the limit analysis run as its check (None otherwise).
    pub certificate: Option<Certificate>,
}

/// What a limit analysis certifies: the interior point's residuals at its solution (scaled to
/// loads of order one) and, for joints with dilatancy below friction, the associative bound and
/// the non-associative sequence.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Certificate {
    /// The program's collapse multiplier (the associative one's, for the non-associative
    /// sequence see `upper_bound`); NaN when it has none.
    pub multiplier: f64,
    /// Largest violation of equilibrium or of a strength face, relative to the largest load.
    pub primal_residual: f64,
    /// Largest violation of the dual (mechanism) equations.
    pub dual_residual: f64,
    /// Relative difference of the primal and dual objectives.
    pub duality_gap: f64,
    /// Interior-point iterations in all.
    pub iterations: usize,
    /// The associative multiplier, an upper bound, when the joints are non-associative (NaN
    /// otherwise: the multiplier is then the program's own optimum).
    pub upper_bound: f64,
    /// Programs of the non-associative sequence after the associative one (0: none).
    pub sequence: usize,
    /// Whether the sequence's multiplier settled within its tolerance.
    pub sequence_converged: bool,
    /// Whether some joint has cohesion or tensile strength, taken at its peak (no softening).
    pub peak_strengths: bool,
}

impl<V> Results<V> {
    /// Interface counts by state.
    pub fn joint_states(&self) -> JointStateCounts {
        let mut c = JointStateCounts::default();
        for &f in &self.interface_states {
            if f & OPEN != 0 {
                c.open += 1;
            } else {
                if f & SLIDING != 0 {
                    c.sliding += 1;
                }
                if f & ROCKING != 0 {
                    c.rocking += 1;
                }
                if f == 0 {
                    c.elastic += 1;
                }
            }
        }
        c
    }
}

/// The peak of a load curve: the multiplier of largest magnitude, with its sign (a wall pushed
/// towards -x under displacement control has negative multipliers). NaN for an empty curve.
pub fn peak(curve: &[f64]) -> f64 {
    curve.iter().cloned().fold(f64::NAN, |p, x| if p.is_nan() || x.abs() > p.abs() { x } else { p })
}

/// The reason of an incremental path that ends `Unbounded`: lambda passed 1e3 times its natural
/// scale (the multiplier that the live load's size suggests) with the wall still standing.
pub fn unbounded_message(lambda: f64) -> String {
    format!(
        "lambda reached {lambda:.4e}, 1e3 times the load scale, with the wall still standing: the live load finds no mechanism within the range of multipliers (joints too strong for it, or supports that carry it)"
    )
}
