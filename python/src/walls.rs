//! The wall generators: `running_bond` and `pattern`.

use crate::*;

/// Blocks [x0, y0, x1, y1] (shape (n, 4), m) of a running-bond wall standing at y = 0 from x = 0.
#[pyfunction]
#[pyo3(signature = (block_length, block_height, courses, length, first_course=None, openings=None))]
pub(crate) fn running_bond<'py>(
    py: Python<'py>,
    block_length: f64,
    block_height: f64,
    courses: i64,
    length: f64,
    first_course: Option<&str>,
    openings: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let first_course = first_course.map_or(Ok(FirstCourse::default()), str::parse).map_err(to_py)?;
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
pub(crate) fn pattern<'py>(
    py: Python<'py>,
    block_length: f64,
    block_height: f64,
    rows: Vec<Vec<f64>>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let blocks = guarded(|| geometry::pattern(block_length, block_height, &rows))?;
    Ok(rects_to_py(py, &blocks))
}
