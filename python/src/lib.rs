//! PyO3 bindings: the module `masonry_dem._core`. A thin layer: argument conversion, the error
//! mapping, the GIL released during analyses and model building, Ctrl-C polled there and raised
//! as KeyboardInterrupt with the partial results, panics caught.

use masonry_dem::error::Error;
use masonry_dem::geometry::{self, FirstCourse, Rect, RunningBond};
use masonry_dem::joint::JointLaw;
use masonry_dem::model::{JointLaws, LiveLoad, Model, ModelSpec, TopBeam};
use masonry_dem::limit::{self, LimitOptions};
use masonry_dem::results::{Results, Status};
use masonry_dem::explicit::{self, Damping, DynamicOptions, ExplicitOptions, QsControl, TimeHistory};
use masonry_dem::static_solver::{self, Control, StaticOptions};
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

fn rects_from(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<Rect>> {
    let rows: Vec<Vec<f64>> = if let Ok(a) = obj.extract::<PyReadonlyArray2<f64>>() {
        let a = a.as_array();
        a.rows().into_iter().map(|r| r.to_vec()).collect()
    } else {
        obj.extract::<Vec<Vec<f64>>>().map_err(|_| {
            InputError::new_err(format!(
                "{what}: expected a list of [x0, y0, x1, y1] rows of numbers"
            ))
        })?
    };
    rows.iter()
        .enumerate()
        .map(|(i, r)| {
            if r.len() != 4 {
                Err(InputError::new_err(format!(
                    "{what}[{i}]: expected 4 numbers [x0, y0, x1, y1], got {}",
                    r.len()
                )))
            } else {
                Ok(Rect::new(r[0], r[1], r[2], r[3]))
            }
        })
        .collect()
}

/// A count from Python (an int, possibly negative) as a usize of at least `min`; the error names
/// `what`.
fn count(what: &str, value: i64, min: i64) -> PyResult<usize> {
    if value < min {
        let bound = if min == 0 { ">= 0".to_string() } else { format!("at least {min}") };
        return Err(InputError::new_err(format!("{what} must be {bound}, got {value}")));
    }
    usize::try_from(value).map_err(|_| InputError::new_err(format!("{what} = {value} is too large")))
}

fn rects_to_py<'py>(py: Python<'py>, rects: &[Rect]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = rects
        .iter()
        .flat_map(|r| [r.x0, r.y0, r.x1, r.y1])
        .collect();
    Array2::from_shape_vec((rects.len(), 4), flat)
        .unwrap()
        .into_pyarray(py)
}

fn rows3<'py>(py: Python<'py>, v: &[[f64; 3]]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = v.iter().flatten().copied().collect();
    Array2::from_shape_vec((v.len(), 3), flat)
        .unwrap()
        .into_pyarray(py)
}

/// Displacement control without a max_displacement starts with this one [m] and goes on, as
/// much again each time, until collapse (`StaticOptions::until_collapse`).
const UNTIL_COLLAPSE_START: f64 = 0.002;

/// A run of the core in a thread of its own, while the calling thread, the GIL released, waits
/// for it and checks for Ctrl-C every [`SIGNAL_POLL`] (Python handles signals in its main thread
/// only). Ctrl-C, or an exception of the user's progress callback, sets `stop`, which the run's
/// monitor sees at its next poll (at most 0.1 s apart, but not within one sparse factorization
/// or ordering: seconds at 10^5 blocks); a run that has not stopped [`GRACE`] after Ctrl-C is
/// left to finish in the background, and the exception is raised without its results.
struct Run {
    progress: Option<Py<PyAny>>,
    raised: Mutex<Option<PyErr>>,
    stop: AtomicBool,
}

/// How often the waiting thread checks for Ctrl-C.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// How long the waiting thread waits, after Ctrl-C, for the run's partial results.
const GRACE: Duration = Duration::from_millis(300);

impl Run {
    fn new(progress: Option<Py<PyAny>>) -> Arc<Run> {
        Arc::new(Run { progress, raised: Mutex::new(None), stop: AtomicBool::new(false) })
    }

    /// Keeps the first exception that stops the run.
    fn raise(&self, e: PyErr) {
        let mut slot = self.raised.lock().unwrap_or_else(|p| p.into_inner());
        if slot.is_none() {
            *slot = Some(e);
        }
        self.stop.store(true, Ordering::SeqCst);
    }

    /// The run's monitor: false once stopped; otherwise, unless the call is a poll (a check
    /// within a long step), calls the user's progress callback (taking the GIL).
    fn report(&self, step: usize, multiplier: f64, displacement: f64, fraction: f64, poll: bool) -> bool {
        if self.stop.load(Ordering::SeqCst) {
            return false;
        }
        if poll {
            return true;
        }
        let Some(cb) = &self.progress else { return true };
        Python::attach(|py| match cb.call1(py, (step, multiplier, displacement, fraction)) {
            Ok(_) => true,
            Err(e) => {
                self.raise(e);
                false
            }
        })
    }

    /// Runs `work` in its own thread and waits for it, checking for Ctrl-C; None when it was
    /// left to finish in the background after Ctrl-C.
    fn execute<R: Send + 'static>(
        self: &Arc<Self>,
        py: Python<'_>,
        work: impl FnOnce(Arc<Run>) -> R + Send + 'static,
    ) -> PyResult<Option<R>> {
        let (tx, rx) = mpsc::channel();
        let run = Arc::clone(self);
        std::thread::Builder::new()
            .name("masonry-dem".into())
            .stack_size(64 << 20)
            .spawn(move || {
                let _ = tx.send(work(run));
            })
            .map_err(|e| MasonryError::new_err(format!("cannot start the analysis thread: {e}")))?;
        let this = &**self;
        Ok(py.detach(move || {
            let mut stopped: Option<Instant> = None;
            loop {
                match rx.recv_timeout(SIGNAL_POLL) {
                    Ok(r) => return Some(r),
                    Err(mpsc::RecvTimeoutError::Disconnected) => return None,
                    Err(mpsc::RecvTimeoutError::Timeout) => {}
                }
                match stopped {
                    Some(t) if t.elapsed() >= GRACE => return None,
                    Some(_) => {}
                    None => {
                        if let Some(e) = Python::attach(|py| py.check_signals().err()) {
                            this.raise(e);
                        }
                        if this.stop.load(Ordering::SeqCst) {
                            stopped = Some(Instant::now());
                        }
                    }
                }
            }
        }))
    }

    /// The outcome for Python: the value, or the exception that stopped the run (KeyboardInterrupt
    /// on Ctrl-C, or the progress callback's) with the partial results as its `results`
    /// attribute (None when the run was left to finish in the background).
    fn finish<T>(&self, py: Python<'_>, outcome: Option<PyResult<T>>) -> PyResult<Py<T>>
    where
        T: pyo3::PyClass + Into<pyo3::PyClassInitializer<T>>,
    {
        let raised = self.raised.lock().unwrap_or_else(|p| p.into_inner()).take();
        match (outcome, raised) {
            (Some(Ok(v)), None) => Py::new(py, v),
            (Some(Err(e)), None) => Err(e),
            (None, None) => Err(MasonryError::new_err("internal error (please report it): the analysis thread ended without a result")),
            (outcome, Some(e)) => {
                let partial = match outcome {
                    Some(Ok(v)) => Py::new(py, v)?.into_any(),
                    _ => py.None(),
                };
                // an exception whose instances take no attributes is raised as it is
                let _ = e.value(py).setattr("results", partial);
                Err(e)
            }
        }
    }
}

fn damping_from(kind: &str, coefficient: f64) -> PyResult<Damping> {
    match kind {
        "local" => Ok(Damping::Local(coefficient)),
        "viscous" => Ok(Damping::Viscous(coefficient)),
        "none" => Ok(Damping::None),
        o => Err(InputError::new_err(format!("damping must be \"local\", \"viscous\" or \"none\", got {o:?}"))),
    }
}

fn rows3_from(obj: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Option<Vec<[f64; 3]>>> {
    let Some(o) = obj.filter(|o| !o.is_none()) else { return Ok(None) };
    let rows: Vec<Vec<f64>> = if let Ok(a) = o.extract::<PyReadonlyArray2<f64>>() {
        a.as_array().rows().into_iter().map(|r| r.to_vec()).collect()
    } else {
        o.extract().map_err(|_| InputError::new_err(format!("{what}: expected an (n, 3) array of numbers")))?
    };
    rows.iter()
        .enumerate()
        .map(|(i, r)| {
            if r.len() == 3 {
                Ok([r[0], r[1], r[2]])
            } else {
                Err(InputError::new_err(format!("{what}[{i}]: expected 3 numbers (u1, u2, phi), got {}", r.len())))
            }
        })
        .collect::<PyResult<Vec<_>>>()
        .map(Some)
}

/// Blocks [x0, y0, x1, y1] (shape (n, 4), m) of a running-bond wall standing at y = 0 from x = 0.
#[pyfunction]
#[pyo3(signature = (block_length, block_height, courses, length, first_course="half", openings=None))]
fn running_bond<'py>(
    py: Python<'py>,
    block_length: f64,
    block_height: f64,
    courses: i64,
    length: f64,
    first_course: &str,
    openings: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let first_course = match first_course {
        "half" => FirstCourse::Half,
        "full" => FirstCourse::Full,
        o => {
            return Err(InputError::new_err(format!(
                "geometry.running_bond.first_course must be \"half\" or \"full\", got {o:?}"
            )))
        }
    };
    if courses < 1 {
        return Err(InputError::new_err(format!(
            "geometry.running_bond.courses must be at least 1, got {courses}"
        )));
    }
    let openings = match openings {
        Some(o) if !o.is_none() => rects_from(o, "geometry.running_bond.openings")?,
        _ => vec![],
    };
    let p = RunningBond {
        block_length,
        block_height,
        courses: courses as usize,
        length,
        first_course,
        openings,
    };
    let blocks = guarded(|| geometry::running_bond(&p))?;
    Ok(rects_to_py(py, &blocks))
}

/// Blocks [x0, y0, x1, y1] (shape (n, 4), m) from courses listed bottom to top.
#[pyfunction]
fn pattern<'py>(
    py: Python<'py>,
    block_length: f64,
    block_height: f64,
    rows: Vec<Vec<f64>>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let blocks = guarded(|| geometry::pattern(block_length, block_height, &rows))?;
    Ok(rects_to_py(py, &blocks))
}

/// The keys of a joint law, for both the bindings and the case-file loader (`JOINT_LAW_KEYS`).
const LAW_KEYS: [&str; 8] = [
    "normal_stiffness",
    "shear_stiffness",
    "friction",
    "cohesion",
    "tensile_strength",
    "dilatancy",
    "fracture_energy_tension",
    "fracture_energy_shear",
];

fn law_from(d: &Bound<'_, PyAny>, base: JointLaw, what: &str) -> PyResult<JointLaw> {
    let d = d
        .cast::<PyDict>()
        .map_err(|_| InputError::new_err(format!("{what}: expected a dict of joint parameters")))?;
    let mut law = base;
    for (k, v) in d.iter() {
        let key: String = k
            .extract()
            .map_err(|_| InputError::new_err(format!("{what}: keys must be strings")))?;
        if v.is_instance_of::<pyo3::types::PyBool>() {
            return Err(InputError::new_err(format!(
                "{what}.{key}: expected a number, got a boolean"
            )));
        }
        let x: f64 = v
            .extract()
            .map_err(|_| InputError::new_err(format!("{what}.{key}: expected a number")))?;
        match key.as_str() {
            "normal_stiffness" => law.normal_stiffness = x,
            "shear_stiffness" => law.shear_stiffness = x,
            "friction" => law.friction = x,
            "cohesion" => law.cohesion = x,
            "tensile_strength" => law.tensile_strength = x,
            "dilatancy" => law.dilatancy = x,
            "fracture_energy_tension" => law.fracture_energy_tension = x,
            "fracture_energy_shear" => law.fracture_energy_shear = x,
            _ => {
                return Err(InputError::new_err(format!(
                    "{what}: unknown key {key:?} (expected one of {})",
                    LAW_KEYS.join(", ")
                )))
            }
        }
    }
    Ok(law)
}

/// A wall of rigid blocks joined by zero-thickness Mohr-Coulomb interfaces (see _core.pyi).
#[pyclass(name = "Model", module = "masonry_dem._core", subclass)]
struct PyModel {
    inner: Arc<Model>,
}

#[pymethods]
impl PyModel {
    #[new]
    #[pyo3(signature = (blocks, thickness=1.0, density=1000.0, base=true, top_rotation=None, top_force=vec![0.0, 0.0], joints=None, gravity=9.81, live="horizontal_weight", top_vertical="free"))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        blocks: &Bound<'_, PyAny>,
        thickness: f64,
        density: f64,
        base: bool,
        top_rotation: Option<&str>,
        top_force: Vec<f64>,
        joints: Option<&Bound<'_, PyDict>>,
        gravity: f64,
        live: &str,
        top_vertical: &str,
    ) -> PyResult<Self> {
        let blocks = rects_from(blocks, "blocks")?;
        if top_force.len() != 2 {
            return Err(InputError::new_err(format!(
                "top.force: expected 2 numbers [Fx, Fy] in N, got {}",
                top_force.len()
            )));
        }
        let vertical_held = match top_vertical {
            "free" => false,
            "held" => true,
            o => {
                return Err(InputError::new_err(format!(
                    "top.vertical must be \"free\" or \"held\", got {o:?}"
                )))
            }
        };
        if vertical_held && top_rotation.is_none() {
            return Err(InputError::new_err(
                "top.vertical = \"held\" needs a top beam (top.rotation)",
            ));
        }
        let top = match top_rotation {
            None => None,
            Some(r @ ("fixed" | "free")) => Some(TopBeam {
                rotation_fixed: r == "fixed",
                force: [top_force[0], top_force[1]],
                vertical_held,
            }),
            Some(o) => {
                return Err(InputError::new_err(format!(
                    "top.rotation must be \"fixed\" or \"free\", got {o:?}"
                )))
            }
        };
        let live = match live {
            "horizontal_weight" => LiveLoad::HorizontalWeight,
            "top_horizontal" => LiveLoad::TopHorizontal,
            o => {
                return Err(InputError::new_err(format!(
                    "loads.live must be \"horizontal_weight\" or \"top_horizontal\", got {o:?}"
                )))
            }
        };
        let mut laws = JointLaws::default();
        if let Some(j) = joints {
            if let Some(d) = j.get_item("default")? {
                laws.default = law_from(&d, JointLaw::default(), "joints")?;
            }
            for (k, v) in j.iter() {
                let fam: String = k.extract()?;
                let slot = match fam.as_str() {
                    "default" => continue,
                    "bed" => &mut laws.bed,
                    "head" => &mut laws.head,
                    "base" => &mut laws.base,
                    "top" => &mut laws.top,
                    o => return Err(InputError::new_err(format!(
                        "joints: unknown family {o:?} (expected default, bed, head, base or top)"
                    ))),
                };
                *slot = Some(law_from(&v, laws.default, &format!("joints.{fam}"))?);
            }
        }
        let spec = ModelSpec {
            blocks,
            thickness,
            density,
            base,
            top,
            joints: laws,
            gravity,
            live,
        };
        // the GIL released (a million blocks take seconds), polling Ctrl-C in this thread
        let mut raised = None;
        let built = py.detach(|| {
            guarded(|| {
                Model::new_with(spec, &mut || match Python::attach(|py| py.check_signals()) {
                    Ok(()) => true,
                    Err(e) => {
                        raised = Some(e);
                        false
                    }
                })
            })
        });
        if let Some(e) = raised {
            return Err(e);
        }
        Ok(PyModel { inner: Arc::new(built?) })
    }

    /// Fix dof (0: u1 [m], 1: u2 [m], 2: phi [rad]) of a block at a prescribed value.
    #[pyo3(signature = (block, dof, value=0.0))]
    fn fix(&mut self, block: usize, dof: usize, value: f64) -> PyResult<()> {
        Arc::make_mut(&mut self.inner).fix(block, dof, value).map_err(to_py)
    }

    #[getter]
    fn n_blocks(&self) -> usize {
        self.inner.n_wall()
    }
    #[getter]
    fn n_interfaces(&self) -> usize {
        self.inner.interfaces().len()
    }
    #[getter]
    fn base_index(&self) -> Option<usize> {
        self.inner.base()
    }
    #[getter]
    fn top_index(&self) -> Option<usize> {
        self.inner.top()
    }
    #[getter]
    fn rects<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rects_to_py(py, self.inner.rects())
    }
    #[getter]
    fn weights<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.weight().to_vec().into_pyarray(py)
    }
    #[getter]
    fn interface_blocks<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        let it = self.inner.interfaces();
        let flat: Vec<i64> = it.iter().flat_map(|i| [i.a as i64, i.b as i64]).collect();
        Array2::from_shape_vec((it.len(), 2), flat)
            .unwrap()
            .into_pyarray(py)
    }
    #[getter]
    fn interface_geometry<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let it = self.inner.interfaces();
        let flat: Vec<f64> = it
            .iter()
            .flat_map(|i| [i.c[0], i.c[1], i.n[0], i.n[1], i.l])
            .collect();
        Array2::from_shape_vec((it.len(), 5), flat)
            .unwrap()
            .into_pyarray(py)
    }
    #[getter]
    fn interface_family(&self) -> Vec<&'static str> {
        self.inner
            .interfaces()
            .iter()
            .map(|i| i.family.name())
            .collect()
    }

    /// Static incremental analysis (see _core.pyi). Releases the GIL; Ctrl-C stops it within a
    /// step and raises KeyboardInterrupt with what was computed (status "failed", error
    /// "interrupted by the user") as its `results`.
    #[pyo3(signature = (control="load", steps=200, max_displacement=None, control_block=None, tolerance=1e-4, max_iterations=50, progress=None))]
    #[allow(clippy::too_many_arguments)]
    fn solve_static(
        &self,
        py: Python<'_>,
        control: &str,
        steps: i64,
        max_displacement: Option<f64>,
        control_block: Option<usize>,
        tolerance: f64,
        max_iterations: i64,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Py<PyResults>> {
        let control = match control {
            "load" => Control::Load,
            "displacement" => Control::Displacement {
                max_displacement: max_displacement.unwrap_or(UNTIL_COLLAPSE_START),
            },
            o => {
                return Err(InputError::new_err(format!(
                    "analysis.control must be \"load\" or \"displacement\", got {o:?}"
                )))
            }
        };
        let opts = StaticOptions {
            control,
            until_collapse: max_displacement.is_none(),
            steps: count("analysis.steps", steps, 1)?,
            tolerance,
            max_iterations: count("max_iterations", max_iterations, 1)?,
            control_block,
            ..StaticOptions::default()
        };
        let model = Arc::clone(&self.inner);
        let run = Run::new(progress);
        let res = run.execute(py, move |run| {
            guarded(|| {
                let mut monitor =
                    |p: &static_solver::Progress| run.report(p.step, p.multiplier, p.displacement, p.fraction, p.poll);
                static_solver::solve_with(&model, &opts, &mut monitor).map(|inner| PyResults { inner })
            })
        })?;
        run.finish(py, res)
    }

    /// Limit analysis: the collapse multiplier as a linear program (see _core.pyi). Releases the
    /// GIL; Ctrl-C stops it between interior-point iterations and raises KeyboardInterrupt whose
    /// `results` has status "failed" and error "interrupted by the user" (nothing of the
    /// unfinished program is kept).
    /// Options left out (None) take the core's defaults (`LimitOptions::default()`).
    #[pyo3(signature = (tolerance=None, max_iterations=None, max_sequence=None, progress=None))]
    fn solve_limit(
        &self,
        py: Python<'_>,
        tolerance: Option<f64>,
        max_iterations: Option<i64>,
        max_sequence: Option<i64>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Py<PyResults>> {
        let defaults = LimitOptions::default();
        let opts = LimitOptions {
            tolerance: tolerance.unwrap_or(defaults.tolerance),
            max_iterations: max_iterations.map_or(Ok(defaults.max_iterations), |v| count("max_iterations", v, 1))?,
            max_sequence: max_sequence.map_or(Ok(defaults.max_sequence), |v| count("max_sequence", v, 0))?,
            ..defaults
        };
        let model = Arc::clone(&self.inner);
        let run = Run::new(progress);
        let start = Instant::now();
        let res = run.execute(py, move |run| {
            guarded(|| {
                // the callback's step counts the interior-point iterations over all the programs
                let mut count = 0usize;
                let mut monitor = |p: &limit::LimitProgress| {
                    count += 1;
                    run.report(count, p.multiplier, f64::NAN, f64::NAN, false)
                };
                match limit::limit_analysis_with(&model, &opts, &mut monitor) {
                    // stopped by Ctrl-C or by the callback: an unfinished program certifies
                    // nothing, so the partial result holds no multiplier (attached to the
                    // exception that stopped it)
                    Err(Error::Interrupted) => Ok(interrupted_limit(&model, start)),
                    r => r,
                }
                .map(|inner| PyResults { inner })
            })
        })?;
        run.finish(py, res)
    }

    /// Quasi-static analysis with the explicit solver (see _core.pyi).
    #[pyo3(signature = (control="load", steps=200, max_displacement=0.002, control_block=None, tolerance=1e-3, unbalanced_ratio=1e-5, damping="local", damping_coefficient=0.8, time_step=None, safety=0.8, threads=0, progress=None))]
    #[allow(clippy::too_many_arguments)]
    fn solve_dynamic(
        &self,
        py: Python<'_>,
        control: &str,
        steps: i64,
        max_displacement: f64,
        control_block: Option<usize>,
        tolerance: f64,
        unbalanced_ratio: f64,
        damping: &str,
        damping_coefficient: f64,
        time_step: Option<f64>,
        safety: f64,
        threads: i64,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Py<PyResults>> {
        let control = match control {
            "load" => QsControl::Load,
            "displacement" => QsControl::Displacement { max_displacement },
            o => return Err(InputError::new_err(format!("analysis.control must be \"load\" or \"displacement\", got {o:?}"))),
        };
        if steps < 1 {
            return Err(InputError::new_err(format!("analysis.steps must be at least 1, got {steps}")));
        }
        if threads < 0 {
            return Err(InputError::new_err(format!("threads must be >= 0, got {threads}")));
        }
        let opts = ExplicitOptions {
            control,
            steps: steps as usize,
            tolerance,
            unbalanced_ratio,
            damping: damping_from(damping, damping_coefficient)?,
            time_step,
            safety,
            threads: threads as usize,
            control_block,
            ..ExplicitOptions::default()
        };
        let model = Arc::clone(&self.inner);
        let run = Run::new(progress);
        let res = run.execute(py, move |run| {
            guarded(|| {
                let mut monitor =
                    |p: &explicit::Progress| run.report(p.step, p.multiplier, p.displacement, p.fraction, false);
                explicit::solve_with(&model, &opts, &mut monitor).map(|inner| PyResults { inner })
            })
        })?;
        run.finish(py, res)
    }

    /// Time history with the explicit solver (see _core.pyi).
    #[pyo3(signature = (duration, time_step=None, safety=0.8, damping="none", damping_coefficient=0.0, initial_displacements=None, initial_velocities=None, base_acceleration=None, live_multiplier=0.0, record_every=1, large_rotations=true, threads=0, progress=None))]
    #[allow(clippy::too_many_arguments)]
    fn simulate(
        &self,
        py: Python<'_>,
        duration: f64,
        time_step: Option<f64>,
        safety: f64,
        damping: &str,
        damping_coefficient: f64,
        initial_displacements: Option<&Bound<'_, PyAny>>,
        initial_velocities: Option<&Bound<'_, PyAny>>,
        base_acceleration: Option<&Bound<'_, PyAny>>,
        live_multiplier: f64,
        record_every: i64,
        large_rotations: bool,
        threads: i64,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Py<PyTimeHistory>> {
        if record_every < 1 {
            return Err(InputError::new_err(format!("record_every must be at least 1, got {record_every}")));
        }
        if threads < 0 {
            return Err(InputError::new_err(format!("threads must be >= 0, got {threads}")));
        }
        let base_acceleration = match base_acceleration.filter(|o| !o.is_none()) {
            None => None,
            Some(o) => {
                let (t, a): (Vec<f64>, Vec<f64>) = o.extract().map_err(|_| {
                    InputError::new_err("base_acceleration: expected (times, accelerations), two sequences of numbers")
                })?;
                Some((t, a))
            }
        };
        let opts = DynamicOptions {
            duration,
            time_step,
            safety,
            damping: damping_from(damping, damping_coefficient)?,
            initial_displacement: rows3_from(initial_displacements, "initial_displacements")?,
            initial_velocity: rows3_from(initial_velocities, "initial_velocities")?,
            base_acceleration,
            live_multiplier,
            record_every: record_every as usize,
            large_rotations,
            threads: threads as usize,
        };
        let model = Arc::clone(&self.inner);
        let run = Run::new(progress);
        let h = run.execute(py, move |run| {
            guarded(|| {
                let mut monitor =
                    |p: &explicit::Progress| run.report(p.step, p.multiplier, p.displacement, p.fraction, false);
                explicit::simulate_with(&model, &opts, &mut monitor).map(|inner| PyTimeHistory { inner })
            })
        })?;
        run.finish(py, h)
    }

    /// The stability limit of the explicit solver's time step [s].
    fn critical_time_step(&self) -> f64 {
        explicit::critical_time_step(&self.inner)
    }

    fn __repr__(&self) -> String {
        format!(
            "Model({} blocks, {} interfaces)",
            self.inner.n_wall(),
            self.inner.interfaces().len()
        )
    }
}

/// A time history of the explicit solver (see _core.pyi).
#[pyclass(name = "TimeHistory", module = "masonry_dem._core")]
struct PyTimeHistory {
    inner: TimeHistory,
}

fn history3<'py>(py: Python<'py>, v: &[[f64; 3]], n_blocks: usize) -> Bound<'py, numpy::PyArray3<f64>> {
    let k = v.len().checked_div(n_blocks).unwrap_or(0);
    let flat: Vec<f64> = v[..k * n_blocks].iter().flatten().copied().collect();
    // the shape matches the data by construction: no panic can come from here
    numpy::ndarray::Array3::from_shape_vec((k, n_blocks, 3), flat)
        .unwrap_or_else(|_| numpy::ndarray::Array3::zeros((0, n_blocks, 3)))
        .into_pyarray(py)
}

#[pymethods]
impl PyTimeHistory {
    #[getter]
    fn status(&self) -> &'static str {
        self.inner.status.as_str()
    }
    #[getter]
    fn error(&self) -> Option<String> {
        self.inner.error.clone()
    }
    #[getter]
    fn time_step(&self) -> f64 {
        self.inner.time_step
    }
    #[getter]
    fn times<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.times.clone().into_pyarray(py)
    }
    #[getter]
    fn displacements<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray3<f64>> {
        history3(py, &self.inner.displacements, self.inner.n_blocks)
    }
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray3<f64>> {
        history3(py, &self.inner.velocities, self.inner.n_blocks)
    }
    #[getter]
    fn kinetic_energy<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.kinetic_energy.clone().into_pyarray(py)
    }
    #[getter]
    fn elastic_energy<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.elastic_energy.clone().into_pyarray(py)
    }
    #[getter]
    fn external_work<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.external_work.clone().into_pyarray(py)
    }
    #[getter]
    fn dissipated<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.dissipated.clone().into_pyarray(py)
    }
    #[getter]
    fn steps(&self) -> usize {
        self.inner.steps
    }
    #[getter]
    fn elapsed_s(&self) -> f64 {
        self.inner.elapsed_s
    }
    fn __repr__(&self) -> String {
        format!(
            "TimeHistory(status={:?}, {} steps of {:.3e} s, {} records)",
            self.inner.status.as_str(),
            self.inner.steps,
            self.inner.time_step,
            self.inner.times.len()
        )
    }
}

/// The Results of a limit analysis stopped before its end: status "failed", no multiplier, no
/// mechanism, no certificate (as the other solvers report an interrupted run).
fn interrupted_limit(model: &Model, start: Instant) -> Results {
    let nb = model.n_blocks();
    let m = model.interfaces().len();
    Results {
        method: "limit",
        status: Status::Failed,
        error: Some(Error::Interrupted.to_string()),
        collapse_multiplier: f64::NAN,
        last_equilibrium: f64::NAN,
        curve_multiplier: vec![],
        curve_displacement: vec![],
        control_block: model.default_control_block(),
        displacements: vec![[0.0; 3]; nb],
        mechanism: vec![[0.0; 3]; nb],
        interface_forces: vec![[0.0; 3]; m],
        interface_states: vec![0; m],
        broken: vec![false; m],
        iterations: 0,
        steps: 0,
        elapsed_s: start.elapsed().as_secs_f64(),
        certificate: None,
    }
}

/// Results of an analysis (see _core.pyi).
#[pyclass(name = "Results", module = "masonry_dem._core")]
struct PyResults {
    inner: Results,
}

#[pymethods]
impl PyResults {
    #[getter]
    fn method(&self) -> &'static str {
        self.inner.method
    }
    #[getter]
    fn status(&self) -> &'static str {
        self.inner.status.as_str()
    }
    #[getter]
    fn error(&self) -> Option<String> {
        self.inner.error.clone()
    }
    #[getter]
    fn collapse_multiplier(&self) -> f64 {
        self.inner.collapse_multiplier
    }
    #[getter]
    fn last_equilibrium(&self) -> f64 {
        self.inner.last_equilibrium
    }
    #[getter]
    fn curve_multiplier<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.curve_multiplier.clone().into_pyarray(py)
    }
    #[getter]
    fn curve_displacement<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.curve_displacement.clone().into_pyarray(py)
    }
    #[getter]
    fn control_block(&self) -> usize {
        self.inner.control_block
    }
    #[getter]
    fn displacements<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows3(py, &self.inner.displacements)
    }
    #[getter]
    fn mechanism<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows3(py, &self.inner.mechanism)
    }
    #[getter]
    fn interface_forces<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows3(py, &self.inner.interface_forces)
    }
    #[getter]
    fn interface_states<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        self.inner
            .interface_states
            .iter()
            .map(|&s| s as i64)
            .collect::<Vec<_>>()
            .into_pyarray(py)
    }
    #[getter]
    fn broken<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<bool>> {
        self.inner.broken.clone().into_pyarray(py)
    }
    #[getter]
    fn joint_states<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let c = self.inner.joint_states();
        let d = PyDict::new(py);
        d.set_item("elastic", c.elastic)?;
        d.set_item("sliding", c.sliding)?;
        d.set_item("rocking", c.rocking)?;
        d.set_item("open", c.open)?;
        Ok(d)
    }
    #[getter]
    fn iterations(&self) -> usize {
        self.inner.iterations
    }
    #[getter]
    fn steps(&self) -> usize {
        self.inner.steps
    }
    #[getter]
    fn elapsed_s(&self) -> f64 {
        self.inner.elapsed_s
    }
    /// The limit analysis's certificate as a dict: a limit analysis's own, or that of the check
    /// of a static load-control run on associative dry joints; None otherwise (and for an
    /// interrupted limit analysis).
    #[getter]
    fn certificate<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(c) = self.inner.certificate else { return Ok(None) };
        let d = PyDict::new(py);
        d.set_item("multiplier", if c.multiplier.is_nan() { None } else { Some(c.multiplier) })?;
        d.set_item("primal_residual", c.primal_residual)?;
        d.set_item("dual_residual", c.dual_residual)?;
        d.set_item("duality_gap", c.duality_gap)?;
        d.set_item("iterations", c.iterations)?;
        d.set_item("upper_bound", if c.upper_bound.is_nan() { None } else { Some(c.upper_bound) })?;
        d.set_item("sequence", c.sequence)?;
        d.set_item("sequence_converged", c.sequence_converged)?;
        d.set_item("peak_strengths", c.peak_strengths)?;
        Ok(Some(d))
    }
    fn __repr__(&self) -> String {
        format!(
            "Results(method={:?}, status={:?}, collapse_multiplier={:.6}, steps={})",
            self.inner.method,
            self.inner.status.as_str(),
            self.inner.collapse_multiplier,
            self.inner.steps
        )
    }
}

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
