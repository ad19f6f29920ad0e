//! PyO3 bindings: the module `masonry_dem._core`. A thin layer: argument conversion, the error
//! mapping, the GIL released during analyses and model building, Ctrl-C polled there and raised
//! as KeyboardInterrupt with the partial results, panics caught.
//!
//! Here: the exceptions and the module. `convert` turns Python values into the core's, `walls`
//! binds the wall generators and those of polygons (arch, gable, stone wall), `model` the Model and its analyses, `space` the 3D Model3D with its
//! generators and analyses (limit, explicit), `results` what they return (one Results and one
//! TimeHistory for both dimensions),
//! `run` runs an analysis in a thread of its own while Ctrl-C is watched.

use masonry_dem::error::Error;
use masonry_dem::geometry::{self, Arch, ArchKind, FirstCourse, Gable, Rect, RunningBond, Springing, StoneWall};
use masonry_dem::joint::JointLaw;
use masonry_dem::model::{CarriedLoad, JointLaws, Model, ModelSpec, SupportMovement, TopBeam};
use masonry_dem::shape::Polygon;
use masonry_dem::limit::{self, LimitOptions};
use masonry_dem::results::{Results, Status};
use masonry_dem::analysis::Control;
use masonry_dem::interface::Family;
use masonry_dem::explicit::{self, Damping, DynamicOptions, Recording, ExplicitOptions, TimeHistory};
use masonry_dem::static_solver::{self, StaticOptions};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray2};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc, Mutex};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::time::{Duration, Instant};

/// The exceptions are Python classes of `masonry_dem.errors` (each subclasses the standard
/// exception it is a kind of: `InputError(MasonryError, ValueError)`); the core raises them by name.
fn py_error(class: &'static str, message: String, key: Option<String>) -> PyErr {
    Python::attach(|py| {
        let made = py
            .import("masonry_dem.errors")
            .and_then(|m| m.getattr(class))
            .and_then(|c| c.call1((message.clone(), key)));
        match made {
            Ok(e) => PyErr::from_value(e),
            Err(import_error) => import_error,
        }
    })
}

macro_rules! py_exception {
    ($name:ident) => {
        /// Raises `masonry_dem.errors.
        #[doc = stringify!($name)]
        /// `.
        pub(crate) struct $name;
        impl $name {
            pub(crate) fn new_err(message: impl Into<String>) -> PyErr {
                py_error(stringify!($name), message.into(), None)
            }
        }
    };
}
py_exception!(MasonryError);
py_exception!(InputError);

/// The Python exception of a core error, matched by kind.
fn to_py(e: Error) -> PyErr {
    let message = e.to_string();
    match e {
        Error::Input { key, reason } => py_error("InputError", reason, key),
        Error::Mechanism(m) => py_error("MechanismError", m, None),
        Error::Convergence(m) => py_error("ConvergenceError", m, None),
        Error::Interrupted => pyo3::exceptions::PyKeyboardInterrupt::new_err(message),
        Error::OutOfMemory { .. } => pyo3::exceptions::PyMemoryError::new_err(message),
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
mod modal;
mod space;
mod vaults;

use convert::*;
use walls::*;
use model::*;
use results::*;
use run::*;
use space::*;
use vaults::*;

/// The core's defaults of the arguments Python shows when they are left out (the Rust
/// `Default`s: `ModelSpec`, `TopBeam`'s constants, `StaticOptions`, `ExplicitOptions`): Python
/// reads them here instead of stating them again.
fn defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let (spec, stat, expl) = (ModelSpec::default(), StaticOptions::default(), ExplicitOptions::default());
    let d = PyDict::new(py);
    d.set_item("thickness", spec.thickness)?;
    d.set_item("density", spec.density)?;
    d.set_item("base", spec.base)?;
    d.set_item("supports", py.None())?;
    d.set_item("carried", py.None())?;
    d.set_item("gravity_direction", spec.gravity_direction.to_vec())?;
    d.set_item("top_rotation", py.None())?;
    d.set_item("top_force", TopBeam::DEFAULT_FORCE.to_vec())?;
    d.set_item("joints", py.None())?;
    d.set_item("gravity", spec.gravity)?;
    d.set_item("live", spec.live.as_str())?;
    d.set_item("top_vertical", TopBeam::DEFAULT_VERTICAL)?;
    d.set_item("control", stat.control.name())?;
    d.set_item("steps", stat.steps)?;
    d.set_item("max_displacement", py.None())?;
    d.set_item("control_block", py.None())?;
    d.set_item("damping", expl.damping.kind())?;
    Ok(d)
}

/// The core's defaults of the arguments of `Model3D` (`ModelSpec3::default()`) that Python shows.
fn defaults_3d(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let spec = masonry_dem::space::ModelSpec3::default();
    let d = PyDict::new(py);
    d.set_item("density", spec.density)?;
    d.set_item("base", spec.base)?;
    d.set_item("top", py.None())?;
    d.set_item("joints", py.None())?;
    d.set_item("gravity", spec.gravity)?;
    let (live, direction) = match spec.live {
        masonry_dem::space::LiveLoad3::HorizontalWeight { direction } => ("horizontal_weight", Some(direction)),
        masonry_dem::space::LiveLoad3::None => ("none", None),
    };
    d.set_item("live", live)?;
    d.set_item("direction", direction)?;
    d.set_item("carried", py.None())?;
    for shapes in ["boxes", "polyhedra", "supports"] {
        d.set_item(shapes, py.None())?;
    }
    Ok(d)
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("JOINT_LAW_KEYS", JointLaw::KEYS.to_vec())?;
    m.add("MAX_FOLLOW_STEPS", limit::MAX_FOLLOW_STEPS)?;
    m.add("DEFAULTS", defaults(py)?)?;
    m.add("DEFAULTS_3D", defaults_3d(py)?)?;
    let errors = py.import("masonry_dem.errors")?;
    for name in ["MasonryError", "InputError", "ConvergenceError", "MechanismError"] {
        m.add(name, errors.getattr(name)?)?;
    }
    m.add_function(wrap_pyfunction!(running_bond, m)?)?;
    m.add_function(wrap_pyfunction!(pattern, m)?)?;
    m.add_function(wrap_pyfunction!(cut_openings, m)?)?;
    m.add_function(wrap_pyfunction!(arch, m)?)?;
    m.add_function(wrap_pyfunction!(gable, m)?)?;
    m.add_function(wrap_pyfunction!(stone_wall, m)?)?;
    m.add_function(wrap_pyfunction!(running_bond_3d, m)?)?;
    m.add_function(wrap_pyfunction!(u_wall, m)?)?;
    m.add_function(wrap_pyfunction!(buttressed_wall, m)?)?;
    m.add_function(wrap_pyfunction!(corner_wall, m)?)?;
    m.add_function(wrap_pyfunction!(cut_openings_3d, m)?)?;
    m.add_function(wrap_pyfunction!(convex_hulls, m)?)?;
    m.add_function(wrap_pyfunction!(barrel_vault, m)?)?;
    m.add_function(wrap_pyfunction!(cross_vault, m)?)?;
    m.add_function(wrap_pyfunction!(dome, m)?)?;
    m.add_class::<PyModel>()?;
    m.add_class::<PyModel3D>()?;
    m.add_class::<PyResults>()?;
    m.add_class::<PyTimeHistory>()?;
    modal::register(m)?;
    Ok(())
}
