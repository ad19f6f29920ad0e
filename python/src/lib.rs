//! PyO3 bindings: the module `masonry_dem._core`. A thin layer: argument conversion, the error
//! mapping, the GIL released during analyses and model building, Ctrl-C polled there and raised
//! as KeyboardInterrupt with the partial results, panics caught.
//!
//! Here: the exceptions and the module. `convert` turns Python values into the core's, `walls`
//! binds the wall generators, `model` the Model and its analyses, `results` what they return,
//! `run` runs an analysis in a thread of its own while Ctrl-C is watched.

use masonry_dem::error::Error;
use masonry_dem::geometry::{self, FirstCourse, Rect, RunningBond};
use masonry_dem::joint::JointLaw;
use masonry_dem::model::{JointLaws, LiveLoad, Model, ModelSpec, TopBeam};
use masonry_dem::limit::{self, LimitOptions};
use masonry_dem::results::{Results, Status};
use masonry_dem::analysis::{Control, DEFAULT_MAX_DISPLACEMENT};
use masonry_dem::explicit::{self, Damping, DynamicOptions, ExplicitOptions, TimeHistory};
use masonry_dem::static_solver::{self, StaticOptions};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray2};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc, Mutex};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::time::{Duration, Instant};

create_exception!(
    _core,
    MasonryError,
    PyException,
    "Base class of every error raised by masonry_dem."
);
create_exception!(
    _core,
    InputError,
    MasonryError,
    "Bad input: the message names the key, block or interface."
);
create_exception!(
    _core,
    ConvergenceError,
    MasonryError,
    "A solver did not converge."
);
create_exception!(
    _core,
    MechanismError,
    MasonryError,
    "The model is a mechanism before any load."
);

fn to_py(e: Error) -> PyErr {
    match e {
        Error::Input(m) => InputError::new_err(m),
        Error::Mechanism(m) => MechanismError::new_err(m),
        Error::Convergence(m) => ConvergenceError::new_err(m),
        Error::Interrupted => MasonryError::new_err("interrupted by the user"),
        Error::OutOfMemory(m) => pyo3::exceptions::PyMemoryError::new_err(m),
    }
}

/// Runs `f` and turns a panic into a MasonryError, so that no panic crosses into Python.
fn guarded<T>(f: impl FnOnce() -> Result<T, Error>) -> PyResult<T> {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)) {
        Ok(r) => r.map_err(to_py),
        Err(p) => {
            let msg = p
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| p.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown".into());
            Err(MasonryError::new_err(format!(
                "internal error (please report it): {msg}"
            )))
        }
    }
}

mod convert;
mod walls;
mod model;
mod results;
mod run;

use convert::*;
use walls::*;
use model::*;
use results::*;
use run::*;

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("JOINT_LAW_KEYS", LAW_KEYS.to_vec())?;
    m.add("MasonryError", py.get_type::<MasonryError>())?;
    m.add("InputError", py.get_type::<InputError>())?;
    m.add("ConvergenceError", py.get_type::<ConvergenceError>())?;
    m.add("MechanismError", py.get_type::<MechanismError>())?;
    m.add_function(wrap_pyfunction!(running_bond, m)?)?;
    m.add_function(wrap_pyfunction!(pattern, m)?)?;
    m.add_class::<PyModel>()?;
    m.add_class::<PyResults>()?;
    m.add_class::<PyTimeHistory>()?;
    Ok(())
}
