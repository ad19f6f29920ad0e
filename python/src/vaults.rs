//! The generators of vaults and domes of convex polyhedra, `barrel_vault`, `cross_vault` and `dome`.

use crate::*;
use masonry_dem::shape::Polyhedron;
use masonry_dem::space::{self, BarrelVault, CrossVault, Dome, DomeKind, Vaulted};

/// The dict of a vault or dome made: "polyhedra" (its blocks, each a list of vertices [x, y, z], m) and "supports"
/// (its fixed supports, the same way).
fn vaulted_to_py<'py>(py: Python<'py>, v: &Vaulted) -> PyResult<Bound<'py, PyDict>> {
    let lists = |ps: &[Polyhedron]| -> Vec<Vec<[f64; 3]>> { ps.iter().map(|p| p.vertices().to_vec()).collect() };
    let d = PyDict::new(py);
    d.set_item("polyhedra", lists(&v.blocks))?;
    d.set_item("supports", lists(&v.supports))?;
    Ok(d)
}

/// A barrel vault, as a dict: "polyhedra" (its blocks, each a list of vertices [x, y, z], m) and "supports" (the two
/// abutments; empty on walls). Model3D(polyhedra=..., supports=..., base=False) is the vault on abutments,
/// Model3D(polyhedra=...) the vault on walls (they stand on the base).
///
/// Its cross-section is arch()'s (kind, thickness, voussoirs, span, radius, rise, abutment_width, abutment_height,
/// pier_width, pier_height, pier_courses: the same meaning, the same defaults) in the plane (x, z), z up, the
/// springing line z = 0; the piers become walls along the axis. The axis is y, from 0 to length [m]. block_length [m]:
/// each course (a voussoir, or a course of a wall, extruded) is cut into blocks this long along the axis, every other
/// course starting with a half block (the joints staggered by half a block; no piece shorter than 5% of a block);
/// left out: the arch extruded one block deep, each course a single block.
#[pyfunction]
#[pyo3(signature = (kind, thickness, voussoirs, length, block_length=None, span=None, radius=None, rise=None, abutment_width=None, abutment_height=None, pier_width=None, pier_height=None, pier_courses=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn barrel_vault<'py>(
    py: Python<'py>,
    kind: &str,
    thickness: f64,
    voussoirs: i64,
    length: f64,
    block_length: Option<f64>,
    span: Option<f64>,
    radius: Option<f64>,
    rise: Option<f64>,
    abutment_width: Option<f64>,
    abutment_height: Option<f64>,
    pier_width: Option<f64>,
    pier_height: Option<f64>,
    pier_courses: Option<i64>,
) -> PyResult<Bound<'py, PyDict>> {
    let what = "geometry.barrel_vault";
    let arch = arch_from(what, kind, thickness, voussoirs, [span, radius, rise], [abutment_width, abutment_height, pier_width, pier_height], pier_courses)?;
    let made = guarded(|| space::barrel_vault(&BarrelVault { arch, length, block_length }))?;
    vaulted_to_py(py, &made)
}

/// A cross (groin) vault, as a dict: "polyhedra" (its voussoirs, then the piers' blocks if on piers, each a list of
/// vertices [x, y, z], m) and "supports" (four fixed blocks under the corners; empty on piers).
/// Model3D(polyhedra=..., supports=..., base=False) is the vault on its corner supports, Model3D(polyhedra=...) the
/// vault on piers (they stand on the base).
///
/// Two barrels of one section cross at right angles over a square bay: arch()'s (kind "semicircular" or "pointed",
/// thickness, voussoirs, span, radius, rise, abutment_width, abutment_height, pier_width, pier_height, pier_courses:
/// the same meaning, the same defaults) in the plane (x, z), springing at z = 0, along y, and the same along x. The
/// bay is |x|, |y| <= a, a the extrados's half span at the springing. Each barrel is kept where its tunnel is the
/// higher (|x| <= |y| for the one along y): each voussoir of each of the four webs is one block from the bay's side
/// to the groins, the diagonal vertical planes x = y and x = -y. The blocks: the web over y > 0 (the arch's voussoirs
/// left to right), then the same web turned by 90, 180 and 270 degrees about z. The arch's right abutment, or its
/// right pier's courses, stand under each corner as squares in plan (|x| and |y| from the intrados's half span out
/// to its width): four fixed supports, or four piers of free blocks on the base listed after the vault's blocks,
/// corner by corner (+x +y, -x +y, -x -y, +x -y), each bottom to top.
#[pyfunction]
#[pyo3(signature = (kind, thickness, voussoirs, span=None, radius=None, rise=None, abutment_width=None, abutment_height=None, pier_width=None, pier_height=None, pier_courses=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn cross_vault<'py>(
    py: Python<'py>,
    kind: &str,
    thickness: f64,
    voussoirs: i64,
    span: Option<f64>,
    radius: Option<f64>,
    rise: Option<f64>,
    abutment_width: Option<f64>,
    abutment_height: Option<f64>,
    pier_width: Option<f64>,
    pier_height: Option<f64>,
    pier_courses: Option<i64>,
) -> PyResult<Bound<'py, PyDict>> {
    let what = "geometry.cross_vault";
    if !matches!(kind, "semicircular" | "pointed") {
        return Err(py_error("InputError", format!("{what}.kind must be \"semicircular\" or \"pointed\", got {kind:?}"), Some(format!("{what}.kind"))));
    }
    let arch = arch_from(what, kind, thickness, voussoirs, [span, radius, rise], [abutment_width, abutment_height, pier_width, pier_height], pier_courses)?;
    let made = guarded(|| space::cross_vault(&CrossVault { arch }))?;
    vaulted_to_py(py, &made)
}

/// A dome, as a dict: "polyhedra" (its voussoirs ring by ring from the springing up, each a list of vertices
/// [x, y, z], m) and "supports" (empty: it stands on the base). Model3D(polyhedra=...) is the dome on the base.
///
/// kind: "hemispherical" (give radius, the middle surface's [m], or span, the intrados's diameter [m]) or "pointed"
/// (span and rise, the intrados's, rise >= span / 2). Its meridian is the right half of arch()'s of 2 parallels
/// voussoirs (radial joints) revolved about the z axis, the springing at z = 0; thickness [m] along the joints;
/// meridians (3 at least): the voussoirs of each ring, at equal angles; parallels: the rings. Each voussoir is the
/// convex hull of its corners (planar faces: chords of the intrados and extrados), the crown's ring of wedges
/// meeting on the axis; the meridian joints run through every ring.
#[pyfunction]
#[pyo3(signature = (kind, thickness, meridians, parallels, span=None, radius=None, rise=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn dome<'py>(
    py: Python<'py>,
    kind: &str,
    thickness: f64,
    meridians: i64,
    parallels: i64,
    span: Option<f64>,
    radius: Option<f64>,
    rise: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let kind: DomeKind = kind.parse().map_err(to_py)?;
    let meridians = count("geometry.dome.meridians", meridians, 3)?;
    let parallels = count("geometry.dome.parallels", parallels, 1)?;
    let made = guarded(|| space::dome(&Dome { kind, span, radius, rise, thickness, meridians, parallels }))?;
    vaulted_to_py(py, &made)
}
