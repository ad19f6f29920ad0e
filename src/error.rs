//! The one error type of the crate. Every message names the key, block or interface at fault.
//!
//! ```
//! use masonry_dem::error::Error;
//! use masonry_dem::model::{Model, ModelSpec};
//! let e = Model::new(ModelSpec { thickness: -1.0, ..ModelSpec::default() }).unwrap_err();
//! assert!(matches!(e, Error::Input { .. }));
//! assert_eq!(e.key(), Some("geometry.thickness"));
//! assert_eq!(e.to_string(), "geometry.thickness must be a finite number > 0, got -1");
//! ```

/// Errors of model building and analysis.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// Bad input: a non-finite or out-of-range number, a degenerate or overlapping block,
    /// a block that touches nothing, a wall with no support.
    #[error("{reason}")]
    Input {
        /// The case-file key at fault ("geometry.thickness", "joints.bed.friction"), when the
        /// error concerns one key; `None` for errors about blocks, interfaces or the whole wall.
        key: Option<String>,
        /// The message, a sentence that names the key, block or interface at fault.
        reason: String,
    },
    /// The model is a mechanism before any load is applied (no equilibrium under dead load).
    #[error("{0}")]
    Mechanism(String),
    /// An analysis did not converge.
    #[error("{0}")]
    Convergence(String),
    /// The run was stopped by the caller (Ctrl-C from Python, or a progress callback).
    #[error("interrupted by the user")]
    Interrupted,
    /// The memory a model or an analysis needs cannot be allocated (checked before allocating).
    #[error("{what} needs about {}, more memory than this machine (or this process) can allocate", format_bytes(*.bytes))]
    OutOfMemory {
        /// What needed it ("a model of 1892685 blocks", "static analysis of 10000 blocks").
        what: String,
        /// The estimated size \[bytes\].
        bytes: f64,
    },
}

impl Error {
    /// Bad input not tied to one key (a block, an interface, the whole wall).
    pub(crate) fn input(reason: impl Into<String>) -> Self {
        Error::Input { key: None, reason: reason.into() }
    }

    /// Bad input at case-file key `key`; `reason` is the whole sentence (it names the key too).
    pub(crate) fn input_at(key: impl Into<String>, reason: impl Into<String>) -> Self {
        Error::Input { key: Some(key.into()), reason: reason.into() }
    }

    /// The same error with the key prefix `from` (a generator's, "geometry.arch") read as `to`
    /// in its key and message: a generator called by another names the caller's keys.
    pub fn renamed(self, from: &str, to: &str) -> Self {
        match self {
            Error::Input { key, reason } => Error::Input { key: key.map(|k| k.replace(from, to)), reason: reason.replace(from, to) },
            e => e,
        }
    }

    /// The case-file key of an input error, if it concerns one.
    pub fn key(&self) -> Option<&str> {
        match self {
            Error::Input { key, .. } => key.as_deref(),
            _ => None,
        }
    }
}

/// Result alias of the crate.
pub type Result<T> = std::result::Result<T, Error>;

/// Check that `value` is finite and strictly positive; the error names `what`.
pub(crate) fn positive(what: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::input_at(what, format!(
            "{what} must be a finite number > 0, got {value}"
        )))
    }
}

/// Check that `value` is finite and >= 0; the error names `what`.
pub(crate) fn non_negative(what: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::input_at(what, format!(
            "{what} must be a finite number >= 0, got {value}"
        )))
    }
}

/// The smallest weight of a wall \[N\] the solvers compute with: the square root of the smallest
/// normal `f64`. The explicit solver's norms and the static solver's work are products of forces
/// (and of forces and displacements); below this weight they underflow, and the solvers would
/// fail or see no load at all (limit analysis, which scales its program, would still answer).
pub const MIN_WEIGHT: f64 = 1.4916681462400413e-154;

/// Refuses a wall whose total `weight` \[N\] (`density` \[kg/m3\] times `gravity` \[m/s2\]
/// times its volume) is above zero but below [`MIN_WEIGHT`], naming the density, so that every
/// method refuses it alike. A weight of zero (no gravity) is not refused here.
pub(crate) fn check_weight(weight: f64, density: f64, gravity: f64) -> Result<()> {
    if weight > 0.0 && weight < MIN_WEIGHT {
        return Err(Error::input_at("geometry.density", format!(
            "geometry.density = {density:e} kg/m3 (with loads.gravity = {gravity} m/s2) gives the wall a weight of {weight:.3e} N, below the {MIN_WEIGHT:.1e} N the solvers compute with (their products of forces would underflow): give the density in kg/m3 (masonry: about 2000)"
        )));
    }
    Ok(())
}

/// The largest number of increments (`analysis.steps`) a solver accepts. Each step stores a point
/// of the curve and costs at least one solve; larger requests are refused before anything is
/// allocated.
pub const MAX_STEPS: usize = 1_000_000;

/// Check that `analysis.steps` lies in `1..=MAX_STEPS`.
pub(crate) fn check_steps(steps: usize) -> Result<()> {
    if steps == 0 {
        return Err(Error::input_at("analysis.steps", "analysis.steps must be at least 1"));
    }
    if steps > MAX_STEPS {
        return Err(Error::input_at("analysis.steps", format!(
            "analysis.steps = {steps} is more than the limit of {MAX_STEPS} increments"
        )));
    }
    Ok(())
}

/// Memory a model takes per block (rectangles, interfaces, loads), in bytes, measured on
/// running-bond walls (about 3 interfaces a block).
pub const MODEL_BYTES_PER_BLOCK: f64 = 1.2e3;

/// Memory an analysis takes per block (solver state, sparse matrix and its factorization),
/// in bytes, measured on running-bond walls: an order of magnitude for messages and checks.
pub const ANALYSIS_BYTES_PER_BLOCK: f64 = 1.0e4;

/// Memory a limit analysis in 3D takes per block (the program, the normal matrix's pattern and
/// factorization, the interior point's iterates), in bytes: the growth of the peak address space
/// of leaves of 4,000 to 64,000 blocks came to 35 to 40 kB a block (the resident set 30 to 37 kB).
pub const LIMIT_3D_BYTES_PER_BLOCK: f64 = 4.0e4;

/// A size in bytes for people ("2.4 GB").
pub fn format_bytes(bytes: f64) -> String {
    if bytes >= 1e9 {
        format!("{:.1} GB", bytes / 1e9)
    } else {
        format!("{:.0} MB", (bytes / 1e6).max(1.0))
    }
}

/// An empty vector with room for `n` values, or, where they cannot be allocated, an
/// [`Error::OutOfMemory`] naming `what` (instead of an abort).
pub(crate) fn try_with_capacity<T>(what: &str, n: usize) -> Result<Vec<T>> {
    let mut v = Vec::new();
    match v.try_reserve_exact(n) {
        Ok(()) => Ok(v),
        Err(_) => Err(Error::OutOfMemory { what: what.to_string(), bytes: n as f64 * std::mem::size_of::<T>() as f64 }),
    }
}

/// `n` copies of `value`, or an [`Error::OutOfMemory`] naming `what` (see [`try_with_capacity`]).
pub(crate) fn try_filled<T: Clone>(what: &str, n: usize, value: T) -> Result<Vec<T>> {
    let mut v = try_with_capacity(what, n)?;
    v.resize(n, value);
    Ok(v)
}

/// Checks, before allocating, that `bytes` of memory can be had at all: asks the allocator for
/// them at once and gives them back untouched (the operating system maps pages only when
/// written). A refusal (more than the machine's memory and swap, or the process's address-space
/// limit) is an [`Error::OutOfMemory`] that names `what` and the size, instead of an abort in
/// the middle of the work.
pub fn check_memory(what: &str, bytes: f64) -> Result<()> {
    let n = if bytes.is_finite() && bytes > 0.0 { bytes.min(isize::MAX as f64) as usize } else { 0 };
    let mut probe: Vec<u8> = Vec::new();
    if probe.try_reserve_exact(n).is_err() {
        return Err(Error::OutOfMemory { what: what.to_string(), bytes });
    }
    Ok(())
}
