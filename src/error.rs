//! The one error type of the crate. Every message names the key, block or interface at fault.

/// Errors of model building and analysis.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// Bad input: a non-finite or out-of-range number, a degenerate or overlapping block,
    /// a block that touches nothing, a wall with no support. The message names the culprit.
    #[error("{0}")]
    Input(String),
    /// The model is a mechanism before any load is applied (no equilibrium under dead load).
    #[error("{0}")]
    Mechanism(String),
    /// An analysis did not converge.
    #[error("{0}")]
    Convergence(String),
    /// The run was stopped by the caller (Ctrl-C from Python, or a progress callback).
    #[error("interrupted by the user")]
    Interrupted,
}

impl Error {
    pub(crate) fn input(msg: impl Into<String>) -> Self {
        Error::Input(msg.into())
    }
}

/// Result alias of the crate.
pub type Result<T> = std::result::Result<T, Error>;

/// Check that `value` is finite and strictly positive; the error names `what`.
pub(crate) fn positive(what: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::input(format!(
            "{what} must be a finite number > 0, got {value}"
        )))
    }
}

/// Check that `value` is finite and >= 0; the error names `what`.
pub(crate) fn non_negative(what: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::input(format!(
            "{what} must be a finite number >= 0, got {value}"
        )))
    }
}

/// The largest number of increments (`analysis.steps`) a solver accepts. Each step stores a point
/// of the curve and costs at least one solve; larger requests are refused before anything is
/// allocated.
pub const MAX_STEPS: usize = 1_000_000;

/// Check that `analysis.steps` lies in `1..=MAX_STEPS`.
pub(crate) fn check_steps(steps: usize) -> Result<()> {
    if steps == 0 {
        return Err(Error::input("analysis.steps must be at least 1"));
    }
    if steps > MAX_STEPS {
        return Err(Error::input(format!(
            "analysis.steps = {steps} is more than the limit of {MAX_STEPS} increments"
        )));
    }
    Ok(())
}
