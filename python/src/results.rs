//! `Results` and `TimeHistory`: what the analyses return, as numpy arrays and dicts.

use crate::*;

/// A time history of the explicit solver (see _core.pyi).
#[pyclass(name = "TimeHistory", module = "masonry_dem._core")]
pub(crate) struct PyTimeHistory {
    pub(crate) inner: TimeHistory,
}

pub(crate) fn history3<'py>(py: Python<'py>, v: &[[f64; 3]], n_blocks: usize) -> Bound<'py, numpy::PyArray3<f64>> {
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
    /// (k, 2) the ground's acceleration (horizontal, vertical) at each record [m/s2].
    #[getter]
    fn ground_acceleration<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
        let rows: Vec<Vec<f64>> = self.inner.ground_acceleration.iter().map(|g| g.to_vec()).collect();
        if rows.is_empty() {
            return Ok(numpy::PyArray2::zeros(py, [0, 2], false));
        }
        Ok(numpy::PyArray2::from_vec2(py, &rows)?)
    }
    /// (k,) the horizontal force of the wall on its base [N] (+x positive).
    #[getter]
    fn base_shear<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.base_shear.clone().into_pyarray(py)
    }
    /// (k,) kinetic energy [J].
    #[getter]
    fn kinetic_energy<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.kinetic_energy.clone().into_pyarray(py)
    }
    /// (k,) elastic energy in the joints [J].
    #[getter]
    fn elastic_energy<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.elastic_energy.clone().into_pyarray(py)
    }
    /// (k,) work of the external loads since t = 0 (weights, loads, the base's motion) [J].
    #[getter]
    fn external_work<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.external_work.clone().into_pyarray(py)
    }
    /// (k,) the weights' part of external_work [J].
    #[getter]
    fn gravity_work<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.gravity_work.clone().into_pyarray(py)
    }
    /// (k,) dissipated in the joints by friction and loss of strength [J].
    #[getter]
    fn friction_dissipation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.friction_dissipation.clone().into_pyarray(py)
    }
    /// (k,) dissipated by the damping of the motion (local, viscous, stiffness-proportional) [J].
    #[getter]
    fn damping_dissipation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.damping_dissipation.clone().into_pyarray(py)
    }
    /// (k,) dissipated by the contact dashpots of impacts (joints' restitution) [J].
    #[getter]
    fn impact_dissipation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.impact_dissipation.clone().into_pyarray(py)
    }
    /// (k,) the three dissipations together [J].
    #[getter]
    fn dissipated<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.dissipated.clone().into_pyarray(py)
    }
    /// (k,) the balance's error: initial energy + external work - kinetic - elastic - dissipated [J].
    #[getter]
    fn energy_error<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.energy_error.clone().into_pyarray(py)
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

/// The Results of a limit analysis stopped before its end: status "interrupted", no multiplier, no
/// mechanism, no certificate (as the other solvers report an interrupted run).
pub(crate) fn interrupted_limit(model: &Model, start: Instant) -> Results {
    let nb = model.n_blocks();
    let m = model.interfaces().len();
    Results {
        method: "limit",
        status: Status::Interrupted,
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
pub(crate) struct PyResults {
    pub(crate) inner: Results,
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
