//! What the incremental analyses share: how the load is driven and what a run reports to its
//! monitor.

/// The default `max_displacement` of displacement control \[m\]: the path of the explicit
/// solver, and the first stretch of the static solver's when it goes on until collapse
/// (`StaticOptions::until_collapse`).
pub const DEFAULT_MAX_DISPLACEMENT: f64 = 0.002;

/// How the load of a quasi-static analysis (static or explicit) is driven.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Control {
    /// Raise lambda until collapse.
    Load,
    /// Drive the horizontal displacement of the control block by `max_displacement` \[m\].
    Displacement { max_displacement: f64 },
}

/// Reported to a run's monitor after each converged step (static), load level or stage (explicit)
/// and every few thousand time steps (time histories); the monitor returns `false` to stop the run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    pub step: usize,
    pub multiplier: f64,
    pub displacement: f64,
    /// Fraction of the requested path done, in \[0, 1\] (displacement control, time histories),
    /// or NaN where the path's length is not known.
    pub fraction: f64,
    /// True for a poll during a long computation (at most every 0.1 s, between Newton
    /// iterations), which repeats the figures of the last converged step: a display may skip
    /// it; returning false stops the run all the same.
    pub poll: bool,
}
