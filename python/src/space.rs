//! The 3D walls: `Model3D` (the core's `Model3`, walls of axis-aligned boxes) with its limit
//! analysis and its explicit ones (quasi-static, time histories), and the generators
//! `running_bond_3d`, `u_wall`, `corner_wall`, `buttressed_wall` and `cut_openings_3d`.

use crate::*;
use masonry_dem::space::{self, Box3, LiveLoad3, Model3, ModelSpec3};

/// Boxes [x0, y0, z0, x1, y1, z1] from an (n, 6) array or a list of rows; `what` names them.
pub(crate) fn boxes_from(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<Box3>> {
    let rows: Vec<Vec<f64>> = if let Ok(a) = obj.extract::<PyReadonlyArray2<f64>>() {
        a.as_array().rows().into_iter().map(|r| r.to_vec()).collect()
    } else {
        obj.extract::<Vec<Vec<f64>>>().map_err(|_| {
            InputError::new_err(format!("{what}: expected a list of [x0, y0, z0, x1, y1, z1] rows of numbers"))
        })?
    };
    rows.iter()
        .enumerate()
        .map(|(i, r)| match r[..] {
            [x0, y0, z0, x1, y1, z1] => Ok(Box3::new(x0, y0, z0, x1, y1, z1)),
            _ => Err(InputError::new_err(format!(
                "{what}[{i}]: expected 6 numbers [x0, y0, z0, x1, y1, z1], got {}",
                r.len()
            ))),
        })
        .collect()
}

/// Convex blocks as vertex lists: a list whose items are each a (k, 3) array or a list of
/// [x, y, z] rows (None: none); `what` names them (`polyhedra`, `supports`).
fn vertex_lists(obj: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Vec<Vec<[f64; 3]>>> {
    let Some(obj) = obj.filter(|o| !o.is_none()) else { return Ok(vec![]) };
    let items: Vec<Bound<'_, PyAny>> = obj
        .extract()
        .map_err(|_| InputError::new_err(format!("{what}: expected a list of blocks, each a list of [x, y, z] vertices")))?;
    items
        .iter()
        .enumerate()
        .map(|(i, item)| {
            let rows: Vec<Vec<f64>> = if let Ok(a) = item.extract::<PyReadonlyArray2<f64>>() {
                a.as_array().rows().into_iter().map(|r| r.to_vec()).collect()
            } else {
                item.extract().map_err(|_| {
                    InputError::new_err(format!("{what}[{i}]: expected a list of [x, y, z] vertices of numbers"))
                })?
            };
            rows.iter()
                .enumerate()
                .map(|(k, v)| match v[..] {
                    [x, y, z] => Ok([x, y, z]),
                    _ => Err(InputError::new_err(format!(
                        "{what}[{i}][{k}]: expected a vertex [x, y, z] of 3 numbers, got {}",
                        v.len()
                    ))),
                })
                .collect()
        })
        .collect()
}

/// Boxes as an (n, 6) array [x0, y0, z0, x1, y1, z1].
fn boxes_to_py<'py>(py: Python<'py>, boxes: &[Box3]) -> Bound<'py, PyArray2<f64>> {
    let rows: Vec<[f64; 6]> = boxes
        .iter()
        .map(|b| [b.min[0], b.min[1], b.min[2], b.max[0], b.max[1], b.max[2]])
        .collect();
    rows_of(py, &rows)
}

/// Openings [x0, z0, x1, z1] of a facade (None: none); `what` names them (`running_bond_3d.openings`).
fn openings_from(obj: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Vec<[f64; 4]>> {
    match obj {
        Some(o) if !o.is_none() => {
            Ok(rects_named(o, what, "[x0, z0, x1, z1]")?.iter().map(|r| [r.x0, r.y0, r.x1, r.y1]).collect())
        }
        _ => Ok(vec![]),
    }
}

/// `blocks` with `openings` cut out of the facade, as an (n, 6) array; the core's refusals, which
/// name `openings`, name them as `what` does (`running_bond_3d.openings[2]`).
fn with_openings<'py>(
    py: Python<'py>,
    blocks: Vec<Box3>,
    openings: &[[f64; 4]],
    what: &str,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let named = |text: String| match text.strip_prefix("openings") {
        Some(rest) => format!("{what}{rest}"),
        None => text,
    };
    let cut = guarded(|| {
        space::cut_openings(blocks, openings).map_err(|e| match e {
            Error::Input { key, reason } => Error::Input { key: key.map(named), reason: named(reason) },
            e => e,
        })
    })?;
    Ok(boxes_to_py(py, &cut))
}

/// Boxes [x0, y0, z0, x1, y1, z1] (shape (n, 6), m) of a single leaf in running bond: along x from x = 0 to
/// length, y from 0 to thickness, z from 0 to height [m], of blocks block_length x thickness x block_height [m].
///
/// first_course: how the lowest course starts at x = 0: "half" (the default: with a half block), "full" (with a
/// whole block) or an offset [m] in [0, block_length) by which its joints are shifted to the left; each course above
/// is shifted by half a block more. A height that is not a whole number of courses gets a last course cut to fit
/// (one under 25% of block_height is refused, as in running_bond). A joint that would fall closer than 5% of a block
/// to a course's end is left out (the end block is longer by as much). openings: [x0, z0, x1, z1] (m), holes through
/// the leaf, cut as cut_openings_3d cuts them.
#[pyfunction]
#[pyo3(signature = (length, height, thickness, block_length, block_height, first_course=None, openings=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn running_bond_3d<'py>(
    py: Python<'py>,
    length: f64,
    height: f64,
    thickness: f64,
    block_length: f64,
    block_height: f64,
    first_course: Option<&Bound<'py, PyAny>>,
    openings: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let offset = match first_course {
        None => 0.5 * block_length,
        Some(v) if v.is_none() => 0.5 * block_length,
        Some(v) if v.is_instance_of::<pyo3::types::PyBool>() => {
            return Err(InputError::new_err("running_bond_3d.first_course: expected \"half\", \"full\" or an offset [m], got a boolean"))
        }
        Some(v) => match v.extract::<String>() {
            Ok(s) if s == "half" => 0.5 * block_length,
            Ok(s) if s == "full" => 0.0,
            Ok(s) => {
                return Err(InputError::new_err(format!(
                    "running_bond_3d.first_course: expected \"half\", \"full\" or an offset [m], got {s:?}"
                )))
            }
            Err(_) => v.extract::<f64>().map_err(|_| {
                InputError::new_err("running_bond_3d.first_course: expected \"half\", \"full\" or an offset [m]")
            })?,
        },
    };
    let what = "running_bond_3d.openings";
    let openings = openings_from(openings, what)?;
    let blocks = guarded(|| space::running_bond_3d(length, height, thickness, block_length, block_height, offset))?;
    with_openings(py, blocks, &openings, what)
}

/// Boxes [x0, y0, z0, x1, y1, z1] (shape (n, 6), m) of a U of three walls one block thick: a facade along x (x in
/// [0, facade], y in [0, thickness]) and two return walls along +y at its ends, returns long from the facade's outer
/// face, height high [m]; blocks block_length x thickness x block_height [m].
///
/// The corners are bonded: in the even courses the facade's end blocks run over the corners, in the odd ones the
/// returns' do; within each wall the courses are in running bond. block_length must exceed thickness by 5% of a
/// block. openings: [x0, z0, x1, z1] (m), holes through the facade, clear of the corners (cut_openings_3d).
#[pyfunction]
#[pyo3(signature = (facade, height, returns, thickness, block_length, block_height, openings=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn u_wall<'py>(
    py: Python<'py>,
    facade: f64,
    height: f64,
    returns: f64,
    thickness: f64,
    block_length: f64,
    block_height: f64,
    openings: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let what = "u_wall.openings";
    let openings = openings_from(openings, what)?;
    let blocks = guarded(|| space::u_wall(facade, height, returns, thickness, block_length, block_height))?;
    with_openings(py, blocks, &openings, what)
}

/// Boxes [x0, y0, z0, x1, y1, z1] (shape (n, 6), m) of a wall with buttresses: the wall along x (x in [0, length], y in
/// [0, thickness]), height high, in running bond of blocks block_length x thickness x block_height (the lowest course
/// starting with a whole block at x = 0, the next with a half), and buttresses against its face y = 0, each a column
/// of one block per course, buttress_width along x by buttress_depth (y in [-buttress_depth, 0]) [m], their axes at
/// x = spacing (k + 1/2) for each k whose buttress ends 5% of a block short of the wall's end at least. bonded (the
/// default): in the lowest course and every other one above it the buttress's block runs through the wall (to y =
/// thickness) and the wall's course stops against it; not bonded: the buttresses stand against the wall's face.
/// spacing must exceed buttress_width by 10% of a block. The blocks course by course from the bottom, the wall's
/// along +x, then the buttresses'.
#[pyfunction]
#[pyo3(signature = (length, height, thickness, block_length, block_height, spacing, buttress_width, buttress_depth, bonded=true))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn buttressed_wall<'py>(
    py: Python<'py>,
    length: f64,
    height: f64,
    thickness: f64,
    block_length: f64,
    block_height: f64,
    spacing: f64,
    buttress_width: f64,
    buttress_depth: f64,
    bonded: bool,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let p = space::ButtressedWall { length, height, thickness, block_length, block_height, spacing, buttress_width, buttress_depth, bonded };
    let blocks = guarded(|| space::buttressed_wall(&p))?;
    Ok(boxes_to_py(py, &blocks))
}

/// Boxes [x0, y0, z0, x1, y1, z1] (shape (n, 6), m) of an L of two walls one block thick: a facade along x (x in
/// [0, facade], y in [0, thickness]) and one return wall along +y at x = 0, returns long from the facade's outer
/// face, height high [m], the corner bonded as in u_wall; the facade's far end is free. openings: [x0, z0, x1, z1]
/// (m), holes through the facade, clear of the corner (cut_openings_3d).
#[pyfunction]
#[pyo3(signature = (facade, height, returns, thickness, block_length, block_height, openings=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn corner_wall<'py>(
    py: Python<'py>,
    facade: f64,
    height: f64,
    returns: f64,
    thickness: f64,
    block_length: f64,
    block_height: f64,
    openings: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let what = "corner.openings";
    let openings = openings_from(openings, what)?;
    let blocks = guarded(|| space::corner(facade, height, returns, thickness, block_length, block_height))?;
    with_openings(py, blocks, &openings, what)
}

/// `boxes` [x0, y0, z0, x1, y1, z1] (m) with `openings` [x0, z0, x1, z1] (m) cut through the facade (the blocks of
/// the smallest y) over its depth: a block partly inside an opening becomes its parts outside it (straight jambs,
/// sill and lintel), no part thinner than 5% of the block being made; an opening that reaches a block deeper than
/// the facade (a return wall's block over a corner) is refused.
#[pyfunction]
pub(crate) fn cut_openings_3d<'py>(
    py: Python<'py>,
    boxes: &Bound<'py, PyAny>,
    openings: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let blocks = boxes_from(boxes, "boxes")?;
    let openings = openings_from(Some(openings), "openings")?;
    with_openings(py, blocks, &openings, "openings")
}

/// A convex block for Python: its vertices (k, 3) [m] and its faces, each the indices of its vertices.
type Hull<'py> = (Bound<'py, PyArray2<f64>>, Vec<Vec<usize>>);

/// The convex hull of each block's vertices: a list of (vertices (k, 3) [m], faces, each a list of indices into
/// them counter-clockwise seen from outside), as Model3D makes its polyhedra (the contact tolerance of the box around
/// every vertex given). blocks: a list of vertex lists (each a (k, 3) array or a list of [x, y, z] rows [m]); key:
/// the name of the list in the refusals, which name the block (`polyhedra[3]: fewer than 4 vertices off one plane:
/// it has no volume ...`, `polyhedra[0]: vertex 2 (...): coordinate NaN is not finite`) and carry the key.
#[pyfunction]
#[pyo3(signature = (blocks, key="polyhedra"))]
pub(crate) fn convex_hulls<'py>(
    py: Python<'py>,
    blocks: &Bound<'py, PyAny>,
    key: &str,
) -> PyResult<Vec<Hull<'py>>> {
    let lists = vertex_lists(Some(blocks), key)?;
    let made = space::hulls(&[(&lists[..], key)], &[]).map_err(to_py)?;
    Ok(made[0]
        .iter()
        .map(|p| (rows_of(py, p.vertices()), p.faces().iter().map(|f| f.vertices.clone()).collect()))
        .collect())
}

/// A wall of rigid blocks in 3D (axis-aligned boxes and convex polyhedra), z up, joined by dry Mohr-Coulomb contacts
/// (limit analysis, the explicit solver and time histories).
///
/// boxes: (n, 6) array of boxes [x0, y0, z0, x1, y1, z1] in m (running_bond_3d, u_wall, corner_wall); None or
///     left out with polyhedra only.
/// density [kg/m3] of the blocks and the top beam (default 2000).
/// base: True (the default) puts a fixed rigid foundation under the wall's footprint (the box around the blocks in
///     plan, as deep as the tallest block); the lowest blocks stand on it.
/// top: None (the default: no top beam) or the height [m] of a rigid top beam of the blocks' density over the box
///     around the blocks in plan, resting on the highest blocks, free to move; it weighs and takes the live load.
/// joints: as Model's, {family: law} with family in "default", "bed", "head", "base", "top"; the 3D analyses take
///     joints with cohesion and tensile_strength too (brittle: fracture energies 0; shared by a contact's corners by
///     tributary area): limit analysis reads their strengths, friction and dilatancy, the explicit solver the
///     stiffnesses too (and restitution, in time histories).
/// gravity [m/s2], along -z (default 9.81); live: "horizontal_weight" (the default: lambda * W_i on every block
///     that weighs, horizontal) or "none"; direction: the live load's direction in plan [deg], from +x towards +y
///     (default 0: towards +x; 90 pushes a facade along x out of its plane, towards +y).
/// carried: loads carried by wall blocks (a floor's reaction), a list of (block, [x, y, z], weight): a weight [N]
///     along -z resting at a point [m] of the box (0-based), whose mass weight / gravity moves with it, as Model's.
///     A time history refuses a load off the box's axes through its centroid (its products of inertia).
/// polyhedra: wall blocks of any convex shape after the boxes, a list of vertex lists (each a (k, 3) array or a
///     list of [x, y, z] rows [m]): each block the convex hull of its vertices (at least 4 off one plane).
/// supports: fixed blocks of any convex shape, vertex lists as polyhedra (an abutment, an inclined plane); with
///     supports the default base is False (no foundation unless base=True).
/// Block indices: the boxes in the order given, then the polyhedra, then the base, then the top beam, then the
/// supports. Raises InputError naming the key or block on bad input (`polyhedra[3]: ...` for a list that makes no
/// convex block; two overlapping blocks are both named).
#[pyclass(name = "Model3D", module = "masonry_dem._core", subclass)]
pub(crate) struct PyModel3D {
    pub(crate) inner: Arc<Model3>,
}

/// The live load of `live` ("horizontal_weight" or "none") and `direction` [deg].
fn live_from(live: Option<&str>, direction: Option<f64>) -> PyResult<LiveLoad3> {
    match live.unwrap_or("horizontal_weight") {
        "horizontal_weight" => Ok(LiveLoad3::HorizontalWeight { direction: direction.unwrap_or(0.0) }),
        "none" if direction.is_some() => Err(InputError::new_err(
            "direction applies to the horizontal-weight live load; with live = \"none\" there is no live load to turn",
        )),
        "none" => Ok(LiveLoad3::None),
        other => Err(InputError::new_err(format!(
            "live: expected \"horizontal_weight\" or \"none\" in 3D, got {other:?}"
        ))),
    }
}

/// An (m, 3) array of a vector of each contact.
fn contact_vectors<'py>(py: Python<'py>, model: &Model3, f: impl Fn(&space::Contact) -> [f64; 3]) -> Bound<'py, PyArray2<f64>> {
    let rows: Vec<[f64; 3]> = model.contacts().iter().map(f).collect();
    rows_of(py, &rows)
}

#[pymethods]
impl PyModel3D {
    #[new]
    #[pyo3(signature = (boxes=None, density=None, base=None, top=None, joints=None, gravity=None, live=None, direction=None, carried=None, polyhedra=None, supports=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        boxes: Option<&Bound<'_, PyAny>>,
        density: Option<f64>,
        base: Option<bool>,
        top: Option<f64>,
        joints: Option<&Bound<'_, PyDict>>,
        gravity: Option<f64>,
        live: Option<&str>,
        direction: Option<f64>,
        carried: Option<&Bound<'_, PyAny>>,
        polyhedra: Option<&Bound<'_, PyAny>>,
        supports: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let d = ModelSpec3::default();
        let blocks = match boxes {
            Some(b) if !b.is_none() => boxes_from(b, "boxes")?,
            _ => vec![],
        };
        let (given, fixed) = (vertex_lists(polyhedra, "polyhedra")?, vertex_lists(supports, "supports")?);
        let around: Vec<_> = blocks.iter().map(|b| masonry_dem::shape::Aabb { min: b.min, max: b.max }).collect();
        let made = space::hulls(&[(&given[..], "polyhedra"), (&fixed[..], "supports")], &around).map_err(to_py)?;
        let [polyhedra, supports]: [Vec<_>; 2] = made.try_into().expect("two lists");
        let spec = ModelSpec3 {
            blocks,
            polyhedra,
            base: base.unwrap_or(supports.is_empty()),
            supports,
            density: density.unwrap_or(d.density),
            top,
            joints: laws_from(joints)?,
            gravity: gravity.unwrap_or(d.gravity),
            live: live_from(live, direction)?,
            carried: carried_from(carried)?,
        };
        // the GIL released, polling Ctrl-C in this thread
        let mut raised = None;
        let built = py.detach(|| {
            guarded(|| {
                Model3::new_with(&spec, &mut || match Python::attach(|py| py.check_signals()) {
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
        Ok(PyModel3D { inner: Arc::new(built?) })
    }

    /// 3: a wall of boxes in 3D (Model's is 2).
    #[getter]
    fn dimension(&self) -> usize {
        3
    }
    /// The loads carried by wall blocks: a list of (block, [x, y, z], weight [N]).
    #[getter]
    fn carried(&self) -> Vec<(usize, [f64; 3], f64)> {
        carried_to_py(self.inner.carried())
    }

    /// The live load: "horizontal_weight" (lambda times each block's weight, horizontal, along direction) or "none".
    #[getter]
    fn live(&self) -> &'static str {
        match self.inner.live() {
            LiveLoad3::HorizontalWeight { .. } => "horizontal_weight",
            LiveLoad3::None => "none",
        }
    }
    /// The live load's direction in plan [deg], from +x towards +y; None without a live load.
    #[getter]
    fn direction(&self) -> Option<f64> {
        match self.inner.live() {
            LiveLoad3::HorizontalWeight { direction } => Some(direction),
            LiveLoad3::None => None,
        }
    }
    /// Acceleration of gravity [m/s2], along -z.
    #[getter]
    fn gravity(&self) -> f64 {
        self.inner.gravity()
    }
    /// Number of wall blocks (base and top beam not counted), as Model.n_blocks.
    #[getter]
    fn n_blocks(&self) -> usize {
        self.inner.n_wall()
    }
    /// Number of interfaces (the contacts between blocks, and with the base and the top beam).
    #[getter]
    fn n_interfaces(&self) -> usize {
        self.inner.contacts().len()
    }
    /// Index of the base (the fixed foundation) among the blocks; None without one.
    #[getter]
    fn base_index(&self) -> Option<usize> {
        self.inner.base()
    }
    /// Index of the top beam among the blocks; None without one.
    #[getter]
    fn top_index(&self) -> Option<usize> {
        self.inner.top()
    }
    /// (n_all, 6) boxes [x0, y0, z0, x1, y1, z1] of all blocks [m], wall blocks first, then base, then top beam, then
    /// supports; a polyhedron's is the box around it (block_vertices and block_faces give its shape).
    #[getter]
    fn boxes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        boxes_to_py(py, self.inner.boxes())
    }
    /// (n_all, 3) centroid of each block [m] (where its dofs are and its moments are taken): its centre of mass (the box's centre, moved by the loads it carries).
    #[getter]
    fn centroids<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows_of(py, self.inner.centroids())
    }
    /// (n_all,) mass of each block [kg], with the loads it carries (the base's too, though it is fixed).
    #[getter]
    fn mass<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.mass().to_vec().into_pyarray(py)
    }
    /// (n_all,) weight of each block [N], with the loads it carries (the wall's and the top beam's; 0 for the base).
    #[getter]
    fn weights<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let f = self.inner.dead_load();
        (0..self.inner.n_blocks()).map(|i| -f[6 * i + 2]).collect::<Vec<_>>().into_pyarray(py)
    }
    /// (m, 2) block indices (a, b) of each interface; the normal points from a to b.
    #[getter]
    fn interface_blocks<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        let c = self.inner.contacts();
        let flat: Vec<i64> = c.iter().flat_map(|k| [k.a as i64, k.b as i64]).collect();
        Array2::from_shape_vec((c.len(), 2), flat).unwrap().into_pyarray(py)
    }
    /// (m, 3) unit normal of each interface, from block a into block b (+x, +y or +z).
    #[getter]
    fn interface_normals<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        contact_vectors(py, &self.inner, |c| c.n)
    }
    /// (m, 3) first unit tangent t1 of each interface: +x on a horizontal one, the horizontal tangent on a vertical one.
    #[getter]
    fn interface_t1<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        contact_vectors(py, &self.inner, |c| c.t1)
    }
    /// (m, 3) second unit tangent t2 = normal x t1 of each interface (+y on a horizontal one, +z on a vertical one).
    #[getter]
    fn interface_t2<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        contact_vectors(py, &self.inner, |c| c.t2)
    }
    /// (m, 3) centroid of each interface [m].
    #[getter]
    fn interface_centroids<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        contact_vectors(py, &self.inner, |c| c.centroid)
    }
    /// (m, 4, 3) corners of each interface's rectangle [m], counter-clockwise seen from the tip of its normal (a
    /// polygon of other than four corners padded with NaN or cut to four: interface_polygons gives them all).
    #[getter]
    fn interface_corners<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray3<f64>> {
        let c = self.inner.contacts();
        let flat: Vec<f64> = c
            .iter()
            .flat_map(|k| (0..4).flat_map(move |q| k.corners.get(q).copied().unwrap_or([f64::NAN; 3])))
            .collect();
        numpy::ndarray::Array3::from_shape_vec((c.len(), 4, 3), flat).unwrap().into_pyarray(py)
    }
    /// Each interface's polygon [m]: a list of (k, 3) arrays, its k >= 3 corners counter-clockwise seen from the tip
    /// of its normal (between boxes the rectangle of interface_corners; between polyhedra any convex polygon, whose
    /// corners interface_corners cuts to four).
    #[getter]
    fn interface_polygons<'py>(&self, py: Python<'py>) -> Vec<Bound<'py, PyArray2<f64>>> {
        self.inner.contacts().iter().map(|c| rows_of(py, &c.corners)).collect()
    }
    /// Each block's vertices [m] (wall blocks, base, top beam, supports, as boxes): a list of (k, 3) arrays.
    #[getter]
    fn block_vertices<'py>(&self, py: Python<'py>) -> Vec<Bound<'py, PyArray2<f64>>> {
        self.inner.shapes().iter().map(|p| rows_of(py, p.vertices())).collect()
    }
    /// Each block's faces: per block a list of faces, each the indices of its vertices in block_vertices,
    /// counter-clockwise seen from outside.
    #[getter]
    fn block_faces(&self) -> Vec<Vec<Vec<usize>>> {
        self.inner.shapes().iter().map(|p| p.faces().iter().map(|f| f.vertices.clone()).collect()).collect()
    }
    /// Whether each block is a box with sides along the axes (its row of boxes is the block itself, not the box
    /// around it).
    #[getter]
    fn block_is_box(&self) -> Vec<bool> {
        self.inner.shapes().iter().map(|p| p.as_box().is_some()).collect()
    }
    /// (m,) area of each interface [m2].
    #[getter]
    fn interface_areas<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.contacts().iter().map(|c| c.area).collect::<Vec<_>>().into_pyarray(py)
    }
    /// Family of each interface: "bed", "head", "base" or "top".
    #[getter]
    fn interface_family(&self) -> Vec<&'static str> {
        self.inner.contacts().iter().map(|c| c.family.name()).collect()
    }

    /// Limit analysis in 3D (the static theorem): the largest lambda for which contact forces inside the joints'
    /// strength domains balance the dead loads plus lambda times the live load, a second-order cone program solved
    /// by the interior point of Model.solve_limit. Each corner of a contact carries a force in Coulomb's cone
    /// (|T| <= mu N, the same in every direction of sliding, as in solve_dynamic); torsion and biaxial bending come
    /// from the corners' positions. Mortar joints (cohesion, tensile_strength) enter with their peak strengths. Refused
    /// a wall that nothing holds (no base, or blocks that no chain of contacts joins to it). Exact for dry associative joints (dilatancy = friction), status
    /// "collapse"; for dilatancy below friction the associative optimum, an upper bound, with status "estimate".
    ///
    /// tolerance: the interior point's stopping tolerance (0 < tolerance < 0.01; default 1e-8); max_iterations:
    /// interior-point iterations (default 200). Returns Results with dimension 3, method "limit": the mechanism's
    /// block velocities (vx, vy, vz, wx, wy, wz; largest block translation 1) in `mechanism`, the contact forces at
    /// collapse (N, T1, T2, M_n, M_t1, M_t2) in interface_forces, the crack pattern in interface_states; statuses as
    /// Model.solve_limit. Releases the GIL; Ctrl-C stops it between iterations and raises KeyboardInterrupt, whose
    /// `results` attribute is a Results with status "interrupted" (no multiplier, no certificate).
    /// threads: threads of the interior point's passes over contacts from 2,000 contacts (below, one; default 0: all
    /// cores); the results are the same to the bit with any number.
    /// progress: optional callable(iteration, multiplier, nan, nan) called after each interior-point iteration; an
    /// exception raised by it stops the analysis and is raised again.
    /// along_gravity: True takes lambda times the weights along gravity as the live load instead of the model's (lambda
    /// a factor on the self-weight): the wall stands under its own weight if the status is "unbounded", and not if it
    /// is "no_equilibrium" (near a least thickness better posed than the sign of the horizontal multiplier).
    /// follow_mechanism=True: the collapse mechanism is then followed to the end, as Model.solve_limit's: the blocks
    /// moved by finite steps of it (each by the screw motion of its velocities: turned exactly about its
    /// instantaneous axis, a hinge edge's rotation exact), the contacts found again (over polygons, along edges and at
    /// points) and the limit analysis solved again on the moved geometry. `curve_displacement` is the control block's
    /// (the highest wall block's) displacement along the live load's direction in plan [m], `curve_multiplier` lambda on
    /// the moved geometry, `displacements` the blocks' finite motion at the curve's end (ux, uy, uz [m], then the
    /// rotation vector rx, ry, rz [rad]: the angle about its axis), `steps` the steps taken; a curve that stops short of
    /// zero says why in Results.error. follow_step [m] and follow_steps as in Model.solve_limit; refused with
    /// along_gravity.
    #[pyo3(signature = (tolerance=None, max_iterations=None, threads=None, progress=None, along_gravity=false, follow_mechanism=false, follow_step=None, follow_steps=None))]
    #[allow(clippy::too_many_arguments)]
    fn solve_limit(
        &self,
        py: Python<'_>,
        tolerance: Option<f64>,
        max_iterations: Option<i64>,
        threads: Option<i64>,
        progress: Option<Py<PyAny>>,
        along_gravity: bool,
        follow_mechanism: bool,
        follow_step: Option<f64>,
        follow_steps: Option<i64>,
    ) -> PyResult<Py<PyResults>> {
        let defaults = LimitOptions::default();
        let opts = LimitOptions {
            tolerance: tolerance.unwrap_or(defaults.tolerance),
            max_iterations: max_iterations.map_or(Ok(defaults.max_iterations), |v| count("max_iterations", v, 1))?,
            threads: threads.map_or(Ok(defaults.threads), |v| count("threads", v, 0))?,
            ..defaults
        };
        let follow = crate::model::follow_options(follow_mechanism, follow_step, follow_steps)?;
        if along_gravity && follow.is_some() {
            return Err(InputError::new_err("follow_mechanism follows the mechanism of the model's live load: not with along_gravity=True"));
        }
        self.inner.check_supports().map_err(to_py)?;
        let model = if along_gravity { Arc::new(self.inner.with_live_along_gravity()) } else { self.inner.clone() };
        limit_run(
            py,
            &model,
            progress,
            move |model, monitor| match follow {
                Some(follow) => limit::follow_mechanism_3d(model, &opts, &follow, monitor),
                None => limit::limit_analysis_3d_with(model, &opts, monitor),
            },
            |model, start| {
                let c = model.centroids();
                let top = (0..model.n_wall()).fold(0, |best, i| if c[i][2] > c[best][2] { i } else { best });
                interrupted_limit(model.n_blocks(), model.contacts().len(), top, [0.0; 6], start)
            },
        )
    }

    /// Quasi-static analysis in 3D with the explicit solver: Model.solve_dynamic's on the wall of boxes, with the same
    /// options (and defaults) and Results of dimension 3, method "dynamic", `iterations` = time steps. Each corner of a
    /// contact is a point with the joint law (a normal force that never pulls, with the rectangle's elastic stiffness,
    /// and a shear force within Coulomb's cone);
    /// the blocks' rotations are small, as in limit analysis. Load control only: each load level is relaxed until
    /// |unbalanced| <= unbalanced_ratio * |applied|, and the collapse multiplier is bracketed to `tolerance`
    /// (Results.bracket: the highest level that settled, the lowest that ran away); control="displacement" is
    /// refused (InputError), and so is a wall that nothing holds; joints with strength are brittle (fracture energies 0).
    /// The curve follows control_block (default: the highest wall block) along x, or along y when the live load's
    /// direction is nearer y; a control block held along that axis (the base) is refused. damping,
    /// damping_coefficient, time_step [s], safety, unbalanced_ratio, threads: as in Model.solve_dynamic
    /// (Model3D.critical_time_step gives the stability limit); large_rotations=True and contact_update=True are
    /// refused (InputError): a 3D pushover is on the wall as built. Releases the GIL; Ctrl-C raises KeyboardInterrupt
    /// with the partial Results as its `results` attribute. progress: as in Model.solve_dynamic.
    #[pyo3(signature = (control=None, steps=None, max_displacement=None, control_block=None, tolerance=None, unbalanced_ratio=None, damping=None, damping_coefficient=None, time_step=None, safety=None, threads=None, large_rotations=None, contact_update=None, progress=None))]
    #[allow(clippy::too_many_arguments)]
    fn solve_dynamic(
        &self,
        py: Python<'_>,
        control: Option<&str>,
        steps: Option<i64>,
        max_displacement: Option<f64>,
        control_block: Option<usize>,
        tolerance: Option<f64>,
        unbalanced_ratio: Option<f64>,
        damping: Option<&str>,
        damping_coefficient: Option<f64>,
        time_step: Option<f64>,
        safety: Option<f64>,
        threads: Option<i64>,
        large_rotations: Option<bool>,
        contact_update: Option<bool>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Py<PyResults>> {
        let opts = explicit_options(
            (control, steps, max_displacement, control_block, tolerance),
            (unbalanced_ratio, damping, damping_coefficient),
            (time_step, safety, threads),
            (large_rotations, contact_update),
        )?;
        self.inner.check_supports().map_err(to_py)?;
        analyse(py, &self.inner, progress, move |model, monitor| {
            explicit::solve_3d_with(model, &opts, monitor).map(PyResults::from)
        })
    }

    /// Time history of the wall of boxes with the explicit solver: Model.simulate's options (and defaults), in 3D.
    /// Free motion from initial conditions (initial_displacements / initial_velocities: (n_all, 6) arrays of ux, uy,
    /// uz [m] and a rotation vector rx, ry, rz [rad], and their rates: the angular velocity in the world's axes
    /// [rad/s]) and/or the ground's motion: base_acceleration (along x), base_acceleration_y (along y) and
    /// vertical_acceleration (upwards), each (times [s], accelerations [m/s2]), linear between samples and zero
    /// outside them; the blocks move in the frame of the base. Finite rotations (unit quaternions, Euler's
    /// equations) unless large_rotations is False. Impacts lose energy by the joints' restitution (the time step is
    /// lowered for the contact dashpots this takes). Joints with strength are brittle (fracture energies 0);
    /// damping "local", "viscous" or "none": stiffness-proportional damping is the plane's only (rayleigh takes
    /// beta = 0 only). Returns a TimeHistory of dimension 3, with the ground's acceleration and the base shear along
    /// y too. Releases the GIL; Ctrl-C stops it and raises KeyboardInterrupt, with the TimeHistory computed so far
    /// as its `results` attribute. progress: optional callable(step, time [s], nan, fraction done).
    /// contact_update (default True, with large_rotations; False: the contacts of the wall as built): the contacts
    /// found again as the blocks move (faces
    /// facing within the gap tolerance; new contacts dry, with the joints' restitution; a contact found again keeps
    /// its history) and a ground plane at the top of the base (without a base, at the lowest point), reaching five
    /// model sizes beyond the blocks in plan, onto which falling blocks come to rest.
    #[pyo3(signature = (duration, time_step=None, safety=None, damping=None, damping_coefficient=None, initial_displacements=None, initial_velocities=None, base_acceleration=None, live_multiplier=None, record_every=None, large_rotations=None, threads=None, progress=None, vertical_acceleration=None, record_interval=None, rayleigh=None, base_acceleration_y=None, contact_update=None))]
    #[allow(clippy::too_many_arguments)]
    fn simulate(
        &self,
        py: Python<'_>,
        duration: f64,
        time_step: Option<f64>,
        safety: Option<f64>,
        damping: Option<&str>,
        damping_coefficient: Option<f64>,
        initial_displacements: Option<&Bound<'_, PyAny>>,
        initial_velocities: Option<&Bound<'_, PyAny>>,
        base_acceleration: Option<&Bound<'_, PyAny>>,
        live_multiplier: Option<f64>,
        record_every: Option<i64>,
        large_rotations: Option<bool>,
        threads: Option<i64>,
        progress: Option<Py<PyAny>>,
        vertical_acceleration: Option<&Bound<'_, PyAny>>,
        record_interval: Option<f64>,
        rayleigh: Option<(f64, f64)>,
        base_acceleration_y: Option<&Bound<'_, PyAny>>,
        contact_update: Option<bool>,
    ) -> PyResult<Py<PyTimeHistory>> {
        let mut opts = dynamic_options::<6>(
            duration,
            time_step,
            safety,
            (damping, damping_coefficient, rayleigh),
            (initial_displacements, initial_velocities),
            (base_acceleration, base_acceleration_y, vertical_acceleration),
            live_multiplier,
            (record_every, record_interval),
            large_rotations,
            threads,
        )?;
        opts.contact_update = contact_update.unwrap_or(opts.contact_update);
        analyse(py, &self.inner, progress, move |model, monitor| {
            explicit::simulate_3d_with(model, &opts, monitor).map(PyTimeHistory::from)
        })
    }

    /// (records, bytes) that Model3D.simulate with these options would hold (its time step as simulate chooses
    /// it), as Model.record_size; refuses what simulate refuses of them.
    #[pyo3(signature = (duration, time_step=None, record_every=None, record_interval=None))]
    fn record_size(&self, duration: f64, time_step: Option<f64>, record_every: Option<i64>, record_interval: Option<f64>) -> PyResult<(usize, f64)> {
        let opts = DynamicOptions::<[f64; 6]> { duration, time_step, record: recording(record_every, record_interval)?, ..DynamicOptions::default() };
        explicit::record_size_3d(&self.inner, &opts).map_err(to_py)
    }

    /// The stability limit of the explicit solver's time step in 3D [s] (Gershgorin bound on the contact points'
    /// elastic stiffnesses), as Model.critical_time_step(); with time_history=True, that of Model3D.simulate:
    /// lowered for the contact dashpots of the joints' restitution and, with contact_update (True, simulate's
    /// default), for a block touching fixed bodies along every face.
    #[pyo3(signature = (time_history=false, contact_update=true))]
    fn critical_time_step(&self, time_history: bool, contact_update: bool) -> f64 {
        if time_history {
            explicit::history_time_step_limit_3d(&self.inner, contact_update)
        } else {
            explicit::critical_time_step_3d(&self.inner)
        }
    }

    fn __repr__(&self) -> String {
        format!("Model3D({} blocks, {} interfaces)", self.inner.n_wall(), self.inner.contacts().len())
    }
}
