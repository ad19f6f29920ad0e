//! Conversions between Python values and the core's: rectangles, rows of three numbers, counts,
//! damping and joint laws, each error naming the argument or key.

use crate::*;

pub(crate) fn rects_from(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<Rect>> {
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

pub(crate) fn rows3<'py>(py: Python<'py>, v: &[[f64; 3]]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = v.iter().flatten().copied().collect();
    Array2::from_shape_vec((v.len(), 3), flat)
        .unwrap()
        .into_pyarray(py)
}

/// How the load is driven: "load", or "displacement" by `max_displacement` (left out: the
/// core's default, [`DEFAULT_MAX_DISPLACEMENT`]).
pub(crate) fn control_from(control: &str, max_displacement: Option<f64>) -> PyResult<Control> {
    match control {
        "load" => Ok(Control::Load),
        "displacement" => Ok(Control::Displacement { max_displacement: max_displacement.unwrap_or(DEFAULT_MAX_DISPLACEMENT) }),
        o => Err(InputError::new_err(format!("analysis.control must be \"load\" or \"displacement\", got {o:?}"))),
    }
}

/// The damping given by its kind and coefficient, each left out (None) taking the one of
/// `default` (the core's default options).
pub(crate) fn damping_over(kind: Option<&str>, coefficient: Option<f64>, default: Damping) -> PyResult<Damping> {
    let (default_kind, default_coefficient) = match default {
        Damping::None => ("none", 0.0),
        Damping::Local(c) => ("local", c),
        Damping::Viscous(c) => ("viscous", c),
    };
    damping_from(kind.unwrap_or(default_kind), coefficient.unwrap_or(default_coefficient))
}

pub(crate) fn damping_from(kind: &str, coefficient: f64) -> PyResult<Damping> {
    match kind {
        "local" => Ok(Damping::Local(coefficient)),
        "viscous" => Ok(Damping::Viscous(coefficient)),
        "none" => Ok(Damping::None),
        o => Err(InputError::new_err(format!("damping must be \"local\", \"viscous\" or \"none\", got {o:?}"))),
    }
}

pub(crate) fn rows3_from(obj: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Option<Vec<[f64; 3]>>> {
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

/// The keys of a joint law, for both the bindings and the case-file loader (`JOINT_LAW_KEYS`).
pub(crate) const LAW_KEYS: [&str; 8] = [
    "normal_stiffness",
    "shear_stiffness",
    "friction",
    "cohesion",
    "tensile_strength",
    "dilatancy",
    "fracture_energy_tension",
    "fracture_energy_shear",
];

pub(crate) fn law_from(d: &Bound<'_, PyAny>, base: JointLaw, what: &str) -> PyResult<JointLaw> {
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
