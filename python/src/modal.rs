//! Modal analysis: `modes` (the natural frequencies and shapes of a model's elastic joints, as a
//! `Modes` of numpy arrays) and `rayleigh` (Rayleigh damping coefficients from two frequencies).

use crate::*;
use masonry_dem::modal::{self, Modes};

/// The natural modes of a model's elastic joints (``modes``), lowest frequency first.
#[pyclass(name = "Modes", module = "masonry_dem._core", frozen)]
pub(crate) struct PyModes {
    inner: Modes,
    n_blocks: usize,
    /// 2 for a wall in the plane, 3 for a 3D model
    dimension: usize,
}

#[pymethods]
impl PyModes {
    /// (n,) natural frequencies [Hz].
    #[getter]
    fn frequencies_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.frequencies.clone().into_pyarray(py)
    }
    /// (n,) angular frequencies [rad/s]; 0 for a mode of no stiffness (a mechanism).
    #[getter]
    fn angular_frequencies<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.angular.clone().into_pyarray(py)
    }
    /// (n,) omega^2 as computed [rad2/s2].
    #[getter]
    fn eigenvalues<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.eigenvalues.clone().into_pyarray(py)
    }
    /// (n, n_all, 3): u1, u2, phi of every block (as Model.rects); in 3D (n, n_all, 6): ux, uy, uz, rx, ry,
    /// rz. phi^T M phi = 1, fixed dofs 0.
    #[getter]
    fn shapes<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray3<f64>> {
        if self.dimension == 3 {
            let rows: Vec<[f64; 6]> = self.inner.shapes.iter().flat_map(|s| s.chunks_exact(6).map(|c| std::array::from_fn(|k| c[k]))).collect();
            return history_of(py, &rows, self.n_blocks);
        }
        let rows: Vec<[f64; 3]> = self.inner.shapes.iter().flat_map(|s| s.chunks_exact(3).map(|c| [c[0], c[1], c[2]])).collect();
        history_of(py, &rows, self.n_blocks)
    }
    /// 2 for the modes of a wall in the plane (Model), 3 for those of a 3D model (Model3D).
    #[getter]
    fn dimension(&self) -> usize {
        self.dimension
    }
    /// (n,) ||K phi - omega^2 M phi|| / ||K phi||.
    #[getter]
    fn residuals<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.residuals.clone().into_pyarray(py)
    }
    /// (n, 2) effective modal masses along x and y [kg]; in 3D (n, 3), along x, y and z.
    #[getter]
    fn effective_mass<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let d = self.dimension;
        let flat: Vec<f64> = self.inner.effective_mass.iter().flatten().copied().collect();
        // the shape matches the data by construction: no panic can come from here
        Array2::from_shape_vec((self.inner.effective_mass.len(), d), flat)
            .unwrap_or_else(|_| Array2::zeros((0, d)))
            .into_pyarray(py)
    }
    /// The mass free to move along x and y [kg] (in 3D along x, y and z): the effective masses' sum over all
    /// modes.
    #[getter]
    fn free_mass<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, pyo3::types::PyTuple>> {
        pyo3::types::PyTuple::new(py, &self.inner.free_mass)
    }
    /// The shift sigma of the operator (K - sigma M)^-1 M [rad2/s2].
    #[getter]
    fn shift(&self) -> f64 {
        self.inner.shift
    }
    /// Size of the Lanczos basis.
    #[getter]
    fn basis(&self) -> usize {
        self.inner.basis
    }
    fn __len__(&self) -> usize {
        self.inner.frequencies.len()
    }
    fn __repr__(&self) -> String {
        let f: Vec<String> = self.inner.frequencies.iter().take(6).map(|f| format!("{f:.3}")).collect();
        let more = if self.inner.frequencies.len() > 6 { ", ..." } else { "" };
        format!("Modes({} modes, f = [{}{more}] Hz)", self.inner.frequencies.len(), f.join(", "))
    }
}

/// The n lowest natural modes of the model's elastic joints (K phi = omega^2 M phi on the free dofs), or
/// with a shift [rad2/s2] the n whose omega^2 are nearest to it; the model a Model or a Model3D. Releases the
/// GIL.
#[pyfunction]
#[pyo3(signature = (model, n, shift=None))]
pub(crate) fn modes(py: Python<'_>, model: &Bound<'_, PyAny>, n: i64, shift: Option<f64>) -> PyResult<PyModes> {
    let n = count("n", n, 1)?;
    if let Ok(m) = model.cast::<PyModel3D>() {
        let model = Arc::clone(&m.borrow().inner);
        let inner = py.detach(|| guarded(|| modal::modes_3d(&model, n, shift)))?;
        return Ok(PyModes { inner, n_blocks: model.n_blocks(), dimension: 3 });
    }
    let m = model.cast::<PyModel>().map_err(|_| {
        let kind = model.get_type().name().map(|n| n.to_string()).unwrap_or_else(|_| "object".into());
        InputError::new_err(format!("modes: model must be a Model or a Model3D, got {kind}"))
    })?;
    let model = Arc::clone(&m.borrow().inner);
    let inner = py.detach(|| guarded(|| modal::modes(&model, n, shift)))?;
    Ok(PyModes { inner, n_blocks: model.n_blocks(), dimension: 2 })
}

/// Rayleigh damping C = alpha M + beta K: (alpha [1/s], beta [s]) giving the damping ratio zeta1 at f1_hz
/// and zeta2 (default zeta1) at f2_hz [Hz].
#[pyfunction]
#[pyo3(signature = (f1_hz, f2_hz, zeta1, zeta2=None))]
pub(crate) fn rayleigh(f1_hz: f64, f2_hz: f64, zeta1: f64, zeta2: Option<f64>) -> PyResult<(f64, f64)> {
    // the frequencies checked here, so that the messages speak of hertz
    for (name, f) in [("f1_hz", f1_hz), ("f2_hz", f2_hz)] {
        if !(f.is_finite() && f > 0.0) {
            return Err(InputError::new_err(format!("rayleigh: {name} must be a finite frequency > 0 Hz, got {f}")));
        }
    }
    if f1_hz == f2_hz {
        return Err(InputError::new_err(format!("rayleigh: f1_hz and f2_hz are equal ({f1_hz} Hz): two different frequencies fix alpha and beta")));
    }
    let w = |f: f64| 2.0 * std::f64::consts::PI * f;
    guarded(|| modal::rayleigh_coefficients(w(f1_hz), w(f2_hz), zeta1, zeta2.unwrap_or(zeta1)))
}

/// Adds the modal analysis's functions and class to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(modes, m)?)?;
    m.add_function(wrap_pyfunction!(rayleigh, m)?)?;
    m.add_class::<PyModes>()
}
