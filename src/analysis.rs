//! What the incremental analyses share: how the load is driven and what a run reports to its
//! monitor, the scale of lambda and when a displacement-controlled path has collapsed.
//!
//! ```
//! use masonry_dem::analysis::{displacement_collapse, lambda_scale, Control};
//! use masonry_dem::geometry::Rect;
//! use masonry_dem::model::{Model, ModelSpec};
//! // one block of 0.4 x 0.2 m on the base
//! let model = Model::new(ModelSpec { blocks: vec![Rect::new(0.0, 0.0, 0.4, 0.2).into()], ..ModelSpec::default() }).unwrap();
//! assert_eq!(lambda_scale(&model), 1.0); // lambda is a seismic coefficient
//! let control = Control::from_keys(Some("displacement"), Some(0.01), Control::Load).unwrap();
//! assert_eq!(control, Control::Displacement { max_displacement: 0.01 });
//! assert!(displacement_collapse(0.5, 0.6, 1.0, 0.9)); // fallen from its peak
//! ```

use crate::error::{check_steps, Error, Result};
use crate::model::{LiveLoad, Model};

/// The default `max_displacement` of displacement control \[m\]: the path of the explicit
/// solver, and the first stretch of the static solver's when it goes on until collapse
/// (`StaticOptions::until_collapse`).
pub const DEFAULT_MAX_DISPLACEMENT: f64 = 0.002;

/// A path whose lambda passes this many times [`lambda_scale`] is reported
/// [`Status::Unbounded`](crate::results::Status::Unbounded): the live load finds no mechanism.
pub const UNBOUNDED: f64 = 1e3;

/// Displacement control ends in a collapse when lambda has fallen from its peak by more than
/// this fraction of it ...
pub const SOFTENING: f64 = 1e-3;

/// ... or when the curve's last slope is less than this fraction of its first (a plateau).
pub const PLATEAU_SLOPE: f64 = 1e-3;

/// The natural scale of lambda, which steps, tolerances and [`UNBOUNDED`] are relative to: 1
/// for the horizontal-weight live load (lambda is a seismic coefficient), the dead loads for a
/// force on the top beam (the wall's weight plus the beam's dead force |Fx| + |Fy| \[N\], at
/// least 1 N).
pub fn lambda_scale(model: &Model) -> f64 {
    match model.live() {
        LiveLoad::HorizontalWeight => 1.0,
        LiveLoad::TopHorizontal => {
            let w: f64 = model.weight().iter().sum();
            let fd = model.dead_load();
            let t = model.top().expect("a top-horizontal live load has a top beam");
            (w + fd[3 * t].abs() + fd[3 * t + 1].abs()).max(1.0)
        }
    }
}

/// Whether a displacement-controlled curve ends in a collapse: its `last` lambda fell from its
/// `peak` by more than [`SOFTENING`], or its last slope is less than [`PLATEAU_SLOPE`] of its
/// first (a zero first slope tells nothing).
pub fn displacement_collapse(last: f64, peak: f64, first_slope: f64, last_slope: f64) -> bool {
    let softened = last.abs() < peak.abs() * (1.0 - SOFTENING);
    let flat = first_slope != 0.0 && (last_slope / first_slope).abs() < PLATEAU_SLOPE;
    softened || flat
}

/// How the load of a quasi-static analysis (static or explicit) is driven.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Control {
    /// Raise lambda until collapse.
    Load,
    /// Drive the horizontal displacement of the control block by `max_displacement` \[m\].
    Displacement {
        /// The displacement to reach, from the dead state \[m\] (negative: towards -x).
        max_displacement: f64,
    },
}

/// Reported to a run's monitor after each converged step (static), load level or stage (explicit)
/// and every few thousand time steps (time histories); the monitor returns `false` to stop the run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Converged steps (static), load levels or stages (explicit), time steps (time histories) so far.
    pub step: usize,
    /// The load multiplier lambda of the last converged state.
    pub multiplier: f64,
    /// The control block's horizontal displacement there \[m\] (NaN where there is none).
    pub displacement: f64,
    /// Fraction of the requested path done, in \[0, 1\] (displacement control, time histories),
    /// or NaN where the path's length is not known.
    pub fraction: f64,
    /// True for a poll during a long computation (at most every 0.1 s, between Newton
    /// iterations), which repeats the figures of the last converged step: a display may skip
    /// it; returning false stops the run all the same.
    pub poll: bool,
    /// The time reached \[s\] (time histories; NaN elsewhere).
    pub time: f64,
}

/// The checks every quasi-static analysis makes of its options: `analysis.steps`,
/// `analysis.tolerance` in (0, 1), and a finite non-zero `analysis.max_displacement`.
pub(crate) fn check_path_options(steps: usize, tolerance: f64, control: Control) -> Result<()> {
    check_steps(steps)?;
    if !(tolerance > 0.0 && tolerance < 1.0) {
        return Err(Error::input_at(
            "analysis.tolerance",
            format!("analysis.tolerance must lie in (0, 1), got {tolerance}"),
        ));
    }
    if let Control::Displacement { max_displacement } = control {
        if !(max_displacement.is_finite() && max_displacement != 0.0) {
            return Err(Error::input_at(
                "analysis.max_displacement",
                format!("analysis.max_displacement must be a finite non-zero length, got {max_displacement}"),
            ));
        }
    }
    Ok(())
}

/// The largest `max_displacement` of displacement control, as a fraction of the wall's size
/// ([`Model::size`]): the small-displacement model's range, where a path ends
/// `DisplacementLimit`.
pub const MAX_DISPLACEMENT_FRACTION: f64 = 0.1;

/// Refuses a displacement control whose `max_displacement` lies beyond the small-displacement
/// model's range, [`MAX_DISPLACEMENT_FRACTION`] of the wall's size: the model has no answer
/// there (a curve driven that far is an artefact of small rotations, not a collapse).
pub(crate) fn check_displacement_range(model: &Model, control: Control) -> Result<()> {
    if let Control::Displacement { max_displacement } = control {
        let limit = MAX_DISPLACEMENT_FRACTION * model.size();
        if max_displacement.abs() > limit {
            return Err(Error::input_at(
                "analysis.max_displacement",
                format!(
                    "analysis.max_displacement = {max_displacement:e} m lies beyond the small-displacement model's range: at most a tenth of the wall's size, {limit:.4e} m"
                ),
            ));
        }
    }
    Ok(())
}

/// The control block: `given`, or the model's default ([`Model::default_control_block`]),
/// checked to exist.
pub(crate) fn control_block(model: &Model, given: Option<usize>) -> Result<usize> {
    let nb = model.n_blocks();
    let block = given.unwrap_or_else(|| model.default_control_block());
    if block >= nb {
        return Err(Error::input_at(
            "analysis.control_point",
            format!("control block {block} does not exist (the model has {nb} blocks)"),
        ));
    }
    Ok(block)
}
