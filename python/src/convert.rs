//! Conversions between Python values and the core's: rectangles, polygons, boxes, rows of three
//! or six numbers (a block's dofs in the plane or in 3D), counts, damping and joint laws, each
//! error naming the argument or key.

use crate::*;

/// Blocks of the plane: an (n, 4) array of rectangles [x0, y0, x1, y1], or a list whose items
/// are each a rectangle [x0, y0, x1, y1] or a polygon (k >= 3 vertices [x, y]: a list of rows
/// or a (k, 2) array); a rectangle is checked as the core always has (x0 < x1, y0 < y1, named
/// "block i [x0, y0, x1, y1]", `noun` i), a polygon by the model. `what` names the argument.
pub(crate) fn polygons_from(obj: &Bound<'_, PyAny>, what: &str, noun: &str) -> PyResult<Vec<Polygon>> {
    let rect = |i: usize, r: &[f64]| -> PyResult<Polygon> {
        let r = Rect::new(r[0], r[1], r[2], r[3]);
        r.validate(&format!("{noun} {i}")).map_err(to_py)?;
        Ok(r.into())
    };
    if let Ok(a) = obj.extract::<PyReadonlyArray2<f64>>() {
        let a = a.as_array();
        if a.ncols() != 4 {
            return Err(InputError::new_err(format!(
                "{what}: an array of blocks has 4 columns [x0, y0, x1, y1], got shape ({}, {}) (give polygons as a list of vertex lists)",
                a.nrows(),
                a.ncols()
            )));
        }
        return a.rows().into_iter().enumerate().map(|(i, r)| rect(i, &r.to_vec())).collect();
    }
    let items: Vec<Bound<'_, PyAny>> = obj
        .extract()
        .map_err(|_| InputError::new_err(format!("{what}: expected a list of blocks: [x0, y0, x1, y1] rows or lists of [x, y] vertices")))?;
    items
        .iter()
        .enumerate()
        .map(|(i, item)| {
            if let Ok(r) = item.extract::<Vec<f64>>() {
                return match r.len() {
                    4 => rect(i, &r),
                    n => Err(InputError::new_err(format!(
                        "{what}[{i}]: expected 4 numbers [x0, y0, x1, y1] (or a list of [x, y] vertices), got {n}"
                    ))),
                };
            }
            let rows: Vec<Vec<f64>> = if let Ok(a) = item.extract::<PyReadonlyArray2<f64>>() {
                a.as_array().rows().into_iter().map(|r| r.to_vec()).collect()
            } else {
                item.extract().map_err(|_| {
                    InputError::new_err(format!(
                        "{what}[{i}]: expected [x0, y0, x1, y1] or a list of [x, y] vertices of numbers"
                    ))
                })?
            };
            rows.iter()
                .enumerate()
                .map(|(k, v)| match v.as_slice() {
                    &[x, y] => Ok([x, y]),
                    _ => Err(InputError::new_err(format!(
                        "{what}[{i}][{k}]: expected a vertex of 2 numbers [x, y], got {}",
                        v.len()
                    ))),
                })
                .collect::<PyResult<Vec<[f64; 2]>>>()
                .map(Polygon::new)
        })
        .collect()
}

/// Each polygon's vertices as a (k, 2) array, in a list.
pub(crate) fn polygons_to_py<'py>(py: Python<'py>, polygons: &[Polygon]) -> Vec<Bound<'py, PyArray2<f64>>> {
    polygons.iter().map(|p| rows_of(py, p.vertices())).collect()
}

/// Rectangles [x0, y0, x1, y1] from an (n, 4) array or a list of rows; `what` names them.
pub(crate) fn rects_from(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<Rect>> {
    rects_named(obj, what, "[x0, y0, x1, y1]")
}

/// Rectangles from an (n, 4) array or a list of rows, whose coordinates the messages call
/// `names` (`"[x0, z0, x1, z1]"` for a facade's openings in 3D); `what` names them.
pub(crate) fn rects_named(obj: &Bound<'_, PyAny>, what: &str, names: &str) -> PyResult<Vec<Rect>> {
    let rows: Vec<Vec<f64>> = if let Ok(a) = obj.extract::<PyReadonlyArray2<f64>>() {
        let a = a.as_array();
        a.rows().into_iter().map(|r| r.to_vec()).collect()
    } else {
        obj.extract::<Vec<Vec<f64>>>().map_err(|_| {
            InputError::new_err(format!(
                "{what}: expected a list of {names} rows of numbers"
            ))
        })?
    };
    rows.iter()
        .enumerate()
        .map(|(i, r)| {
            if r.len() != 4 {
                Err(InputError::new_err(format!(
                    "{what}[{i}]: expected 4 numbers {names}, got {}",
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
pub(crate) fn count(what: &str, value: i64, min: i64) -> PyResult<usize> {
    if value < min {
        let bound = if min == 0 { ">= 0".to_string() } else { format!("at least {min}") };
        return Err(InputError::new_err(format!("{what} must be {bound}, got {value}")));
    }
    usize::try_from(value).map_err(|_| InputError::new_err(format!("{what} = {value} is too large")))
}

pub(crate) fn rects_to_py<'py>(py: Python<'py>, rects: &[Rect]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = rects
        .iter()
        .flat_map(|r| [r.x0, r.y0, r.x1, r.y1])
        .collect();
    Array2::from_shape_vec((rects.len(), 4), flat)
        .unwrap()
        .into_pyarray(py)
}

/// Rows of `W` numbers as an (n, W) array: a block's or an interface's (3 in the plane, 6 in 3D).
pub(crate) fn rows_of<'py, const W: usize>(py: Python<'py>, v: &[[f64; W]]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = v.iter().flatten().copied().collect();
    Array2::from_shape_vec((v.len(), W), flat)
        .unwrap()
        .into_pyarray(py)
}

/// Rows of `W` numbers, one per block (a block's dofs: (u1, u2, phi) in the plane, W = 3; (ux, uy, uz, rx, ry,
/// rz) in 3D, W = 6), from an (n, W) array or a list of rows; None (or Python's None): left out. `what` names them.
pub(crate) fn rows_from<const W: usize>(obj: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Option<Vec<[f64; W]>>> {
    let Some(o) = obj.filter(|o| !o.is_none()) else { return Ok(None) };
    let rows: Vec<Vec<f64>> = if let Ok(a) = o.extract::<PyReadonlyArray2<f64>>() {
        a.as_array().rows().into_iter().map(|r| r.to_vec()).collect()
    } else {
        o.extract().map_err(|_| InputError::new_err(format!("{what}: expected an (n, {W}) array of numbers")))?
    };
    let names = if W == 3 { "u1, u2, phi" } else { "ux, uy, uz, rx, ry, rz" };
    rows.iter()
        .enumerate()
        .map(|(i, r)| {
            <[f64; W]>::try_from(r.as_slice())
                .map_err(|_| InputError::new_err(format!("{what}[{i}]: expected {W} numbers ({names}), got {}", r.len())))
        })
        .collect::<PyResult<Vec<_>>>()
        .map(Some)
}

/// The joint laws of the `joints` dict: "default" and the families' own, each a dict of
/// [`JointLaw::KEYS`] over the default law.
pub(crate) fn laws_from(joints: Option<&Bound<'_, PyDict>>) -> PyResult<JointLaws> {
    let mut laws = JointLaws::default();
    let Some(j) = joints else { return Ok(laws) };
    if let Some(d) = j.get_item("default")? {
        laws.default = law_from(&d, JointLaw::default(), "joints")?;
    }
    for (k, v) in j.iter() {
        let family: String = k.extract()?;
        if family == "default" {
            continue;
        }
        let f: Family = family.parse().map_err(to_py)?;
        *laws.family_mut(f) = Some(law_from(&v, laws.default, &format!("joints.{family}"))?);
    }
    Ok(laws)
}

/// A joint law: the dict's keys (checked by the core) over `base`.
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
        law.set(what, &key, x).map_err(to_py)?;
    }
    Ok(law)
}

/// The carried loads of `carried`: a list of (block, point, weight) with the point of `D`
/// coordinates [m] and the weight [N]; None (or Python's None): none.
pub(crate) fn carried_from<const D: usize>(carried: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<CarriedLoad<D>>> {
    let Some(o) = carried.filter(|o| !o.is_none()) else { return Ok(vec![]) };
    let shape = if D == 2 { "(block, [x, y], weight)" } else { "(block, [x, y, z], weight)" };
    let items: Vec<Bound<'_, PyAny>> =
        o.extract().map_err(|_| InputError::new_err(format!("carried: expected a list of {shape}")))?;
    items
        .iter()
        .enumerate()
        .map(|(k, item)| {
            let bad = || InputError::new_err(format!("carried[{k}]: expected {shape}: a block index, {D} numbers [m] and a weight [N]"));
            let (block, point, weight): (usize, Vec<f64>, f64) = item.extract().map_err(|_| bad())?;
            let point = <[f64; D]>::try_from(point.as_slice()).map_err(|_| bad())?;
            Ok(CarriedLoad { block, point, weight })
        })
        .collect()
}

/// The carried loads as a list of (block, point, weight), for Python.
pub(crate) fn carried_to_py<const D: usize>(loads: &[CarriedLoad<D>]) -> Vec<(usize, [f64; D], f64)> {
    loads.iter().map(|l| (l.block, l.point, l.weight)).collect()
}
