//! `Results` and `TimeHistory`: what the analyses return, as numpy arrays and dicts.

use crate::*;

/// What the core returns in either dimension: a wall in the plane carries [f64; 3] per block and
/// interface, a wall of boxes [f64; 6] (`P` and `S`: the core's Results, or its TimeHistory, of each).
pub(crate) enum Dimensioned<P, S> {
    Plane(P),
    Space(S),
}

impl<P, S> Dimensioned<P, S> {
    /// 2 in the plane, 3 in space.
    fn dimension(&self) -> usize {
        match self {
            Dimensioned::Plane(_) => 2,
            Dimensioned::Space(_) => 3,
        }
    }
}

impl From<Results> for PyResults {
    fn from(r: Results) -> Self {
        PyResults { inner: Dimensioned::Plane(r) }
    }
}

impl From<Results<[f64; 6]>> for PyResults {
    fn from(r: Results<[f64; 6]>) -> Self {
        PyResults { inner: Dimensioned::Space(r) }
    }
}

impl From<TimeHistory> for PyTimeHistory {
    fn from(h: TimeHistory) -> Self {
        PyTimeHistory { inner: Dimensioned::Plane(h) }
    }
}

impl From<TimeHistory<[f64; 6]>> for PyTimeHistory {
    fn from(h: TimeHistory<[f64; 6]>) -> Self {
        PyTimeHistory { inner: Dimensioned::Space(h) }
    }
}

/// `$body` evaluated on the core's Results (or TimeHistory) `$r` of either dimension (its fields that do not
/// depend on the dimension).
macro_rules! either {
    ($self:ident, $r:ident => $body:expr) => {
        match &$self.inner {
            Dimensioned::Plane($r) => $body,
            Dimensioned::Space($r) => $body,
        }
    };
}

/// A time history (Model.simulate, Model3D.simulate). Energy balance at each record: initial kinetic + elastic
/// energy + external_work = kinetic_energy + elastic_energy + dissipated + energy_error. One class for both
/// dimensions: the block arrays have 3 columns in the plane (dimension 2) and 6 in 3D (dimension 3).
#[pyclass(name = "TimeHistory", module = "masonry_dem._core")]
pub(crate) struct PyTimeHistory {
    pub(crate) inner: Dimensioned<TimeHistory, TimeHistory<[f64; 6]>>,
}

/// Records of `n_blocks` rows of `W` numbers each, flat and record-major, as a (k, n_blocks, W) array.
pub(crate) fn history_of<'py, const W: usize>(py: Python<'py>, v: &[[f64; W]], n_blocks: usize) -> Bound<'py, numpy::PyArray3<f64>> {
    let k = v.len().checked_div(n_blocks).unwrap_or(0);
    let flat: Vec<f64> = v[..k * n_blocks].iter().flatten().copied().collect();
    // the shape matches the data by construction: no panic can come from here
    numpy::ndarray::Array3::from_shape_vec((k, n_blocks, W), flat)
        .unwrap_or_else(|_| numpy::ndarray::Array3::zeros((0, n_blocks, W)))
        .into_pyarray(py)
}

#[pymethods]
impl PyTimeHistory {
    /// 2 for a wall in the plane (Model.simulate), 3 for a wall of boxes (Model3D.simulate): the block arrays have
    /// 3 or 6 columns.
    #[getter]
    fn dimension(&self) -> usize {
        self.inner.dimension()
    }
    /// How the run ended: "completed", "failed" or "interrupted".
    #[getter]
    fn status(&self) -> &'static str {
        either!(self, h => h.status.as_str())
    }
    /// Why, when the status is "failed" or "interrupted" (None otherwise).
    #[getter]
    fn error(&self) -> Option<String> {
        either!(self, h => h.error.clone())
    }
    /// The time step used [s].
    #[getter]
    fn time_step(&self) -> f64 {
        either!(self, h => h.time_step)
    }
    /// (k,) time of each record [s].
    #[getter]
    fn times<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        either!(self, h => h.times.clone().into_pyarray(py))
    }
    /// (k, n_all, 3): u1 [m], u2 [m], phi [rad], relative to the ground; in 3D (k, n_all, 6): ux, uy, uz [m] and
    /// rx, ry, rz [rad], the rotation vector of the block's orientation.
    #[getter]
    fn displacements<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray3<f64>> {
        either!(self, h => history_of(py, &h.displacements, h.n_blocks))
    }
    /// (k, n_all, 3): du1/dt [m/s], du2/dt [m/s], dphi/dt [rad/s], relative to the ground; in 3D (k, n_all, 6):
    /// vx, vy, vz [m/s] and the angular velocity wx, wy, wz [rad/s] in the world's axes.
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray3<f64>> {
        either!(self, h => history_of(py, &h.velocities, h.n_blocks))
    }
    /// (k, 2) the ground's (horizontal, vertical) acceleration [m/s2]; in 3D the horizontal one along x.
    #[getter]
    fn ground_acceleration<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        either!(self, h => rows_of(py, &h.ground_acceleration))
    }
    /// (k,) 3D: the ground's acceleration along y [m/s2]; (0,) in the plane.
    #[getter]
    fn ground_acceleration_y<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        either!(self, h => h.ground_acceleration_y.clone().into_pyarray(py))
    }
    /// (k,) horizontal force of the wall on its base [N] (+x positive).
    #[getter]
    fn base_shear<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        either!(self, h => h.base_shear.clone().into_pyarray(py))
    }
    /// (k,) 3D: the force of the wall on its base along y [N] (+y positive); (0,) in the plane.
    #[getter]
    fn base_shear_y<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        either!(self, h => h.base_shear_y.clone().into_pyarray(py))
    }
    /// (k,) kinetic energy of the blocks [J].
    #[getter]
    fn kinetic_energy<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        either!(self, h => h.kinetic_energy.clone().into_pyarray(py))
    }
    /// (k,) energy stored in the joints [J].
    #[getter]
    fn elastic_energy<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        either!(self, h => h.elastic_energy.clone().into_pyarray(py))
    }
    /// (k,) work of the external loads since t = 0 (weights, loads, base motion) [J].
    #[getter]
    fn external_work<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        either!(self, h => h.external_work.clone().into_pyarray(py))
    }
    /// (k,) the weights' part of external_work [J].
    #[getter]
    fn gravity_work<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        either!(self, h => h.gravity_work.clone().into_pyarray(py))
    }
    /// (k,) dissipated by friction and loss of strength in the joints [J].
    #[getter]
    fn friction_dissipation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        either!(self, h => h.friction_dissipation.clone().into_pyarray(py))
    }
    /// (k,) dissipated by the damping of the motion (local, viscous, Rayleigh) [J].
    #[getter]
    fn damping_dissipation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        either!(self, h => h.damping_dissipation.clone().into_pyarray(py))
    }
    /// (k,) dissipated by impacts (the joints' restitution) [J].
    #[getter]
    fn impact_dissipation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        either!(self, h => h.impact_dissipation.clone().into_pyarray(py))
    }
    /// (k,) the three dissipations together [J].
    #[getter]
    fn dissipated<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        either!(self, h => h.dissipated.clone().into_pyarray(py))
    }
    /// (k,) the balance's error [J].
    #[getter]
    fn energy_error<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        either!(self, h => h.energy_error.clone().into_pyarray(py))
    }
    /// Time steps computed.
    #[getter]
    fn steps(&self) -> usize {
        either!(self, h => h.steps)
    }
    /// Wall-clock time of the run [s].
    #[getter]
    fn elapsed_s(&self) -> f64 {
        either!(self, h => h.elapsed_s)
    }
    /// With the contact update (Model.simulate(contact_update=True), the default): the searches for contacts made,
    /// and the contacts created, dropped, and taken again from the moved blocks; zeros without it.
    #[getter]
    fn contact_counts(&self) -> (usize, usize, usize, usize) {
        either!(self, h => (h.contact_searches, h.contacts_created, h.contacts_dropped, h.contacts_renewed))
    }
    /// With the contact update: the ground plane's level [m], if the model has one (None otherwise).
    #[getter]
    fn ground_level(&self) -> Option<f64> {
        either!(self, h => h.ground_level)
    }
    /// With the contact update: every contact created, dropped or taken again, in order, as a dict of arrays (empty
    /// without it): "time" [s], "change" ("created", "dropped", "renewed"), "id" (the contact's number: the model's
    /// interfaces 0..m in their order, then each created contact in turn), "blocks" (n, 2) (a: the block whose edge
    /// gives the normal), "centre" (n, 2) [m] relative to block a's centroid and "normal" (n, 2) from a into b, both
    /// in a's position at rest (a block's displacement carries them), "length" [m]; a dropped contact has zero
    /// geometry. With Model.interface_blocks / interface_geometry they give the contacts at any time
    /// (masonry_dem.history.contacts_at).
    #[getter]
    fn contact_events<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let ev = either!(self, h => h.contact_events.clone());
        let d = PyDict::new(py);
        d.set_item("time", ev.iter().map(|e| e.time).collect::<Vec<_>>().into_pyarray(py))?;
        d.set_item("change", ev.iter().map(|e| e.change.as_str()).collect::<Vec<_>>())?;
        d.set_item("id", ev.iter().map(|e| e.id as i64).collect::<Vec<_>>().into_pyarray(py))?;
        let blocks: Vec<i64> = ev.iter().flat_map(|e| [e.blocks[0] as i64, e.blocks[1] as i64]).collect();
        // the shape matches the data by construction
        d.set_item("blocks", Array2::from_shape_vec((ev.len(), 2), blocks).unwrap_or_else(|_| Array2::zeros((0, 2))).into_pyarray(py))?;
        d.set_item("centre", rows_of(py, &ev.iter().map(|e| e.centre).collect::<Vec<_>>()))?;
        d.set_item("normal", rows_of(py, &ev.iter().map(|e| e.normal).collect::<Vec<_>>()))?;
        d.set_item("length", ev.iter().map(|e| e.length).collect::<Vec<_>>().into_pyarray(py))?;
        Ok(d)
    }
    fn __repr__(&self) -> String {
        let dim = if self.inner.dimension() == 3 { ", dimension=3" } else { "" };
        either!(self, h => format!(
            "TimeHistory(status={:?}, {} steps of {:.3e} s, {} records{dim})",
            h.status.as_str(),
            h.steps,
            h.time_step,
            h.times.len()
        ))
    }
}

/// The Results of a limit analysis stopped before its end: status "interrupted", no multiplier, no
/// mechanism, no certificate (as the other solvers report an interrupted run). `zero` is a block's
/// or an interface's row of zeros ([f64; 3] in the plane, [f64; 6] in 3D).
pub(crate) fn interrupted_limit<V: Copy>(blocks: usize, interfaces: usize, control_block: usize, zero: V, start: Instant) -> Results<V> {
    Results {
        method: "limit",
        status: Status::Interrupted,
        error: Some(Error::Interrupted.to_string()),
        collapse_multiplier: f64::NAN,
        last_equilibrium: f64::NAN,
        curve_multiplier: vec![],
        curve_displacement: vec![],
        control_block,
        displacements: vec![zero; blocks],
        mechanism: vec![zero; blocks],
        interface_forces: vec![zero; interfaces],
        interface_states: vec![0; interfaces],
        broken: vec![false; interfaces],
        iterations: 0,
        steps: 0,
        elapsed_s: start.elapsed().as_secs_f64(),
        bracket: None,
        certificate: None,
    }
}

/// The results of an analysis (Model.solve_static, solve_dynamic, solve_limit; Model3D.solve_dynamic, solve_limit):
/// the curve of the live load's multiplier lambda [-] against the control block's displacement [m], the
/// displacements [m, rad] and the joints' forces [N, N m] and states at the end, and the collapse multiplier. One
/// class for both dimensions: the block and interface arrays have 3 columns in the plane (dimension 2) and 6 in 3D
/// (dimension 3).
#[pyclass(name = "Results", module = "masonry_dem._core")]
pub(crate) struct PyResults {
    pub(crate) inner: Dimensioned<Results, Results<[f64; 6]>>,
}

#[pymethods]
impl PyResults {
    /// 2 for a wall in the plane (Model), 3 for a wall of boxes (Model3D): the block and interface arrays have 3 or
    /// 6 columns.
    #[getter]
    fn dimension(&self) -> usize {
        self.inner.dimension()
    }
    /// The solver: "static", "dynamic" or "limit".
    #[getter]
    fn method(&self) -> &'static str {
        either!(self, r => r.method)
    }
    /// How the analysis ended: "collapse", "completed", "failed", "interrupted", "unbounded", "no_equilibrium" or
    /// "estimate" (limit), "stalled" or "displacement_limit" (static).
    #[getter]
    fn status(&self) -> &'static str {
        either!(self, r => r.status.as_str())
    }
    /// Why, when the status is "failed", "no_equilibrium", "unbounded", "stalled" or "displacement_limit"; what the
    /// number is, with "estimate".
    #[getter]
    fn error(&self) -> Option<String> {
        either!(self, r => r.error.clone())
    }
    /// Lambda at collapse, or the peak of the curve; NaN unless the status is "collapse".
    #[getter]
    fn collapse_multiplier(&self) -> f64 {
        either!(self, r => r.collapse_multiplier)
    }
    /// The largest lambda found in equilibrium (load control: the last step), whatever the status (the estimate, with
    /// "estimate"); NaN if none.
    #[getter]
    fn last_equilibrium(&self) -> f64 {
        either!(self, r => r.last_equilibrium)
    }
    /// Explicit load control ending in a collapse: (highest level that settled, lowest that ran away), the collapse
    /// multiplier being the first; None otherwise.
    #[getter]
    fn bracket(&self) -> Option<(f64, f64)> {
        either!(self, r => r.bracket.map(|[a, b]| (a, b)))
    }
    /// (k,) lambda at each converged step, from 0 (empty for "limit").
    #[getter]
    fn curve_multiplier<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        either!(self, r => r.curve_multiplier.clone().into_pyarray(py))
    }
    /// (k,) horizontal displacement of the control point [m] (empty for "limit"); in 3D along x, or along y when the
    /// live load's direction is nearer y.
    #[getter]
    fn curve_displacement<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        either!(self, r => r.curve_displacement.clone().into_pyarray(py))
    }
    /// The block whose horizontal displacement the curve follows (Model.default_control_block unless given; in 3D the
    /// highest wall block unless given).
    #[getter]
    fn control_block(&self) -> usize {
        either!(self, r => r.control_block)
    }
    /// (n_all, 3): u1 [m], u2 [m], phi [rad] at the last converged step (zeros for "limit"); in 3D (n_all, 6): ux, uy,
    /// uz [m], rx, ry, rz [rad] (small rotations about the block's centroid).
    #[getter]
    fn displacements<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        either!(self, r => rows_of(py, &r.displacements))
    }
    /// (n_all, 3): last increment (limit: the block velocities), scaled so that max |u| is 1; in 3D (n_all, 6): the
    /// velocities (vx, vy, vz, wx, wy, wz) of the collapse mechanism (dynamic: the motion at the level that ran
    /// away), its largest block translation 1.
    #[getter]
    fn mechanism<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        either!(self, r => rows_of(py, &r.mechanism))
    }
    /// (m, 3): N [N] (tension > 0), T [N], M [N m] (limit: at collapse); in 3D (m, 6): N, T1, T2 [N], M_n, M_t1,
    /// M_t2 [N m], the force and moment (about the contact's centroid) of block b on block a in the contact's axes
    /// (normal, t1, t2), N > 0 in tension.
    #[getter]
    fn interface_forces<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        either!(self, r => rows_of(py, &r.interface_forces))
    }
    /// (m,) bit flags: 1 open, 2 sliding, 4 rocking; 0 elastic (limit: of the mechanism).
    #[getter]
    fn interface_states<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        either!(self, r => r.interface_states.iter().map(|&s| s as i64).collect::<Vec<_>>().into_pyarray(py))
    }
    /// (m,) bool: the joint lost its cohesion and tensile strength.
    #[getter]
    fn broken<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<bool>> {
        either!(self, r => r.broken.clone().into_pyarray(py))
    }
    /// Counts of the interfaces by state: {"elastic": n, "sliding": n, "rocking": n, "open": n}.
    #[getter]
    fn joint_states<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let c = either!(self, r => r.joint_states());
        let d = PyDict::new(py);
        d.set_item("elastic", c.elastic)?;
        d.set_item("sliding", c.sliding)?;
        d.set_item("rocking", c.rocking)?;
        d.set_item("open", c.open)?;
        Ok(d)
    }
    /// Total equilibrium iterations (static), time steps (dynamic), interior-point iterations (limit).
    #[getter]
    fn iterations(&self) -> usize {
        either!(self, r => r.iterations)
    }
    /// Converged steps (0 for "limit").
    #[getter]
    fn steps(&self) -> usize {
        either!(self, r => r.steps)
    }
    /// Wall-clock time of the analysis [s].
    #[getter]
    fn elapsed_s(&self) -> f64 {
        either!(self, r => r.elapsed_s)
    }
    /// What a limit analysis certifies, as a dict (keys: multiplier, primal_residual, dual_residual, duality_gap,
    /// iterations, upper_bound, sequence, sequence_converged, peak_strengths): a limit analysis's own, or that of the
    /// check of a static load-control run on associative dry joints; None otherwise.
    #[getter]
    fn certificate<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(c) = either!(self, r => r.certificate) else { return Ok(None) };
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
        let dim = match self.inner {
            Dimensioned::Plane(_) => "",
            Dimensioned::Space(_) => ", dimension=3",
        };
        either!(self, r => format!(
            "Results(method={:?}, status={:?}, collapse_multiplier={:.6}, steps={}{dim})",
            r.method,
            r.status.as_str(),
            r.collapse_multiplier,
            r.steps
        ))
    }
}
