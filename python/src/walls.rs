//! The wall generators: `running_bond` and `pattern`.

use crate::*;

/// Blocks [x0, y0, x1, y1] (shape (n, 4), m) of a running-bond wall standing at y = 0 from x = 0.
///
/// block_length, block_height: a whole block's size [m]; length: the wall's length [m] (required).
/// Exactly one of courses (whole courses) and height (the wall's height [m]): with height, the whole
/// courses that fit and, if more is left, a last course cut to the remainder; a remainder under 25%
/// of block_height is refused, the message naming the nearest heights and block heights that fit.
/// Courses alternate between starting with a half block ("half") and a whole block ("full");
/// a block that would cross x = length is cut there. Openings [x0, y0, x1, y1] (in m) are cut out:
/// a block partly inside one is cut at its edges into the parts outside it (straight jambs, sill
/// and lintel; exactly the opening's area removed), an edge within 5% of a block's size of a joint
/// being moved onto the joint so that no sliver of a block is made.
#[pyfunction]
#[pyo3(signature = (block_length, block_height, courses=None, length=None, first_course=None, openings=None, *, height=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn running_bond<'py>(
    py: Python<'py>,
    block_length: f64,
    block_height: f64,
    courses: Option<i64>,
    length: Option<f64>,
    first_course: Option<&str>,
    openings: Option<&Bound<'py, PyAny>>,
    height: Option<f64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let first_course = first_course.map_or(Ok(FirstCourse::default()), str::parse).map_err(to_py)?;
    let Some(length) = length else {
        return Err(InputError::new_err(
            "geometry.running_bond.length is required: the length of the wall [m]",
        ));
    };
    let courses = match (courses, height) {
        (Some(n), _) if n < 1 => {
            return Err(InputError::new_err(format!(
                "geometry.running_bond.courses must be at least 1, got {n}"
            )))
        }
        (None, None) => {
            return Err(InputError::new_err(
                "geometry.running_bond needs exactly one of courses and height; neither is given",
            ))
        }
        (Some(n), _) => n as usize,
        (None, Some(_)) => 0, // from the height
    };
    let openings = match openings {
        Some(o) if !o.is_none() => rects_from(o, "geometry.running_bond.openings")?,
        _ => vec![],
    };
    let p = RunningBond {
        block_length,
        block_height,
        courses,
        height,
        length,
        first_course,
        openings,
    };
    let blocks = guarded(|| geometry::running_bond(&p))?;
    if blocks.is_empty() {
        return Err(InputError::new_err(format!(
            "geometry.running_bond: no block fits in a wall of length {length:e} m (block length {block_length:e} m, height {:?}): no wall to build",
            p.height
        )));
    }
    Ok(rects_to_py(py, &blocks))
}

/// Blocks [x0, y0, x1, y1] (shape (n, 4), m) from courses listed bottom to top; each entry is a
/// length in units of block_length, a negative entry is a gap of that length.
#[pyfunction]
pub(crate) fn pattern<'py>(
    py: Python<'py>,
    block_length: f64,
    block_height: f64,
    rows: Vec<Vec<f64>>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let blocks = guarded(|| geometry::pattern(block_length, block_height, &rows))?;
    if blocks.is_empty() {
        return Err(InputError::new_err(
            "geometry.pattern.rows hold no block (every course is empty or a gap): no wall to build",
        ));
    }
    Ok(rects_to_py(py, &blocks))
}

/// `blocks` [x0, y0, x1, y1] (m) with `openings` cut out as `running_bond` cuts them: a block partly
/// inside an opening becomes its parts outside it, an opening's edge within 5% of `block_length`
/// (across) or `block_height` (up) of a block's edge being moved onto it.
#[pyfunction]
pub(crate) fn cut_openings<'py>(
    py: Python<'py>,
    blocks: &Bound<'py, PyAny>,
    openings: &Bound<'py, PyAny>,
    block_length: f64,
    block_height: f64,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let blocks = rects_from(blocks, "blocks")?;
    let openings = rects_from(openings, "geometry.running_bond.openings")?;
    let snap = [geometry::MIN_PART * block_length, geometry::MIN_PART * block_height];
    let cut = guarded(|| geometry::cut_openings(blocks, &openings, snap, "geometry.running_bond.openings"))?;
    Ok(rects_to_py(py, &cut))
}
