"""Joint-law helpers and conversions of a :class:`masonry_dem.Results`. SI units: m, N, Pa, s.

Joint laws (dicts for ``Model(joints={family: law})``):

* :func:`mortar_joint` derives the interface stiffnesses of a mortar joint from the mortar's Young's
  modulus E [Pa], its shear modulus G [Pa] (or Poisson's ratio nu) and the joint thickness e [m]:
  normal_stiffness = E / e and shear_stiffness = G / e [N/m3], with G = E / (2 (1 + nu)).
* :func:`dry_joint` is a dry (cohesionless, no tensile strength) joint with one stiffness.

>>> import masonry_dem as md
>>> law = md.mortar_joint(young=1.0e9, thickness=0.01, poisson=0.25, cohesion=0.1e6)
>>> law["normal_stiffness"], law["shear_stiffness"]
(100000000000.0, 40000000000.0)

Conversions (the compiled ``Results`` cannot be subclassed, so these are plain functions):

* :func:`to_dict`: everything in a Results as plain Python (lists, ints, floats; NaN becomes None), ready
  for ``json.dumps``; with the model also the block rectangles and the interface geometry and families.
* :func:`to_json`: the result file of docs/case-format.md (:func:`masonry_dem.result_dict`), written under a
  temporary name and renamed.
* :func:`to_dataframe` / :func:`interfaces_dataframe`: pandas DataFrames of the curve and of the
  interfaces, when pandas is installed (the extra "pandas": ``pip install 'masonry-dem[pandas]'``; without it
  they raise ImportError saying so). :func:`curve_columns` / :func:`interface_columns` give the same columns as NumPy arrays.

Ground motions for ``Model.simulate`` (:mod:`masonry_dem.ground_motion`; times in s, accelerations in m/s2):
:class:`GroundMotion` (``.scaled(f)``, ``.peak``, ``.duration``, ``.as_tuple()`` for ``base_acceleration=``),
:func:`read_ground_motion` (a two-column CSV in g or m/s2, or a PEER NGA .AT2 file in g, by its suffix),
:func:`read_at2`, and the pulses :func:`one_sine` and :func:`ricker`.
"""

from __future__ import annotations

import math
import numbers
import os
from typing import Any, Dict, List, Optional, Union

import numpy as np

from ._core import InputError
from ._shapes import shapes
from .case.result_file import JOINT_STATE_KEYS, certificate_dict, json_float as _float, write_result_json
from .ground_motion import GroundMotion, one_sine, read_at2, ricker
from .ground_motion import read as read_ground_motion
from .space.report import block_shapes, contact_polygons
from .units import (
    GPa, J_per_m2, MN, MN_per_m3, MPa, N, N_per_m, N_per_m3, N_per_mm, N_per_mm3, Pa, cm, kg, kg_per_m3, km, kN,
    kN_per_m3, kPa, m, m_per_s2, mm, ms, parse_quantity, s, t_per_m3,
)

__all__ = [
    "mortar_joint",
    "dry_joint",
    "to_dict",
    "to_json",
    "to_dataframe",
    "interfaces_dataframe",
    "curve_columns",
    "interface_columns",
    "GroundMotion",
    "read_ground_motion",
    "read_at2",
    "one_sine",
    "ricker",
    # units (masonry_dem.units): SI values of the units, and values read with their unit
    "parse_quantity",
    "m",
    "cm",
    "mm",
    "km",
    "s",
    "ms",
    "kg",
    "N",
    "kN",
    "MN",
    "Pa",
    "kPa",
    "MPa",
    "GPa",
    "N_per_m3",
    "kN_per_m3",
    "MN_per_m3",
    "N_per_mm3",
    "N_per_m",
    "N_per_mm",
    "J_per_m2",
    "kg_per_m3",
    "t_per_m3",
    "m_per_s2",
    "CURVE_COLUMNS",
    "INTERFACE_COLUMNS",
    "INTERFACE_COLUMNS_3D",
]

PathLike = Union[str, "os.PathLike[str]"]

#: Columns of :func:`to_dataframe` (lambda, or the force in N for live = "top_horizontal"; m).
CURVE_COLUMNS = ("multiplier", "displacement_m")

#: Columns of :func:`interfaces_dataframe`.
INTERFACE_COLUMNS = (
    "a", "b", "family", "x", "y", "nx", "ny", "length_m", "N_N", "T_N", "M_Nm", "state", "broken",
)
#: Columns of :func:`interfaces_dataframe` of a 3D wall (:class:`masonry_dem.Model3D`): the centroid, the normal and
#: the area of each contact, its force and moment in the contact's axes (normal, t1, t2).
INTERFACE_COLUMNS_3D = (
    "a", "b", "family", "x", "y", "z", "nx", "ny", "nz", "area_m2", "N_N", "T1_N", "T2_N", "Mn_Nm", "Mt1_Nm",
    "Mt2_Nm", "state", "broken",
)


# --------------------------------------------------------------------------------------------------
# Joint laws
# --------------------------------------------------------------------------------------------------


def _number(func: str, name: str, value: Any, minimum: Optional[float] = None, strict: bool = False,
            maximum: Optional[float] = None, unit: str = "") -> float:
    """``value`` as a finite float, checked against bounds; InputError naming ``func`` and ``name``."""
    bounds = []
    if minimum is not None:
        bounds.append(f"{'>' if strict else '>='} {minimum:g}")
    if maximum is not None:
        bounds.append(f"<= {maximum:g}")
    want = "a finite number" + (" " + " and ".join(bounds) if bounds else "") + (f" [{unit}]" if unit else "")
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise InputError(f"{func}: {name} must be {want}, got {type(value).__name__} {value!r}")
    x = float(value)
    ok = math.isfinite(x)
    if ok and minimum is not None:
        ok = x > minimum if strict else x >= minimum
    if ok and maximum is not None:
        ok = x <= maximum
    if not ok:
        raise InputError(f"{func}: {name} must be {want}, got {x!r}")
    return x


def mortar_joint(
    young: float,
    thickness: float,
    shear: Optional[float] = None,
    poisson: Optional[float] = None,
    friction: float = 0.75,
    cohesion: float = 0.0,
    tensile_strength: float = 0.0,
    dilatancy: float = 0.0,
) -> Dict[str, float]:
    """The joint law of a mortar joint, for ``Model(joints={family: law})``.

    The mortar layer of thickness e is lumped into a zero-thickness interface with
    ``normal_stiffness = E / e`` and ``shear_stiffness = G / e`` [N/m3].

    young: Young's modulus E of the mortar [Pa], > 0.
    thickness: joint thickness e [m], > 0.
    shear: shear modulus G of the mortar [Pa], > 0; or
    poisson: Poisson's ratio nu of the mortar [-], -1 < nu <= 0.5, giving G = E / (2 (1 + nu)).
        Give exactly one of shear and poisson.
    friction: friction coefficient mu = tan(phi) [-], >= 0.
    cohesion: c [Pa], >= 0. tensile_strength: f_t [Pa], >= 0. dilatancy: tan(psi) [-], >= 0.

    Returns a dict with the six keys of a joint law (normal_stiffness, shear_stiffness, friction,
    cohesion, tensile_strength, dilatancy). Raises InputError naming the argument on bad input.
    """
    f = "mortar_joint"
    e_mod = _number(f, "young", young, 0.0, strict=True, unit="Pa")
    e = _number(f, "thickness", thickness, 0.0, strict=True, unit="m")
    if (shear is None) == (poisson is None):
        raise InputError(f"{f}: give exactly one of shear [Pa] and poisson [-], got "
                         + ("neither" if shear is None else "both"))
    if shear is not None:
        g_mod = _number(f, "shear", shear, 0.0, strict=True, unit="Pa")
    else:
        nu = _number(f, "poisson", poisson, -1.0, strict=True, maximum=0.5)
        g_mod = e_mod / (2.0 * (1.0 + nu))
    law = {
        "normal_stiffness": e_mod / e,
        "shear_stiffness": g_mod / e,
        "friction": _number(f, "friction", friction, 0.0),
        "cohesion": _number(f, "cohesion", cohesion, 0.0, unit="Pa"),
        "tensile_strength": _number(f, "tensile_strength", tensile_strength, 0.0, unit="Pa"),
        "dilatancy": _number(f, "dilatancy", dilatancy, 0.0),
    }
    for key, name in (("normal_stiffness", "young"), ("shear_stiffness", "shear" if shear is not None else "young")):
        if not (math.isfinite(law[key]) and law[key] > 0.0):
            raise InputError(f"{f}: {key} = {name} / thickness is {law[key]!r}; check {name} and thickness")
    return law


def dry_joint(friction: float, stiffness: float = 1e10, dilatancy: float = 0.0) -> Dict[str, float]:
    """A dry joint: no cohesion, no tensile strength, the same normal and shear stiffness.

    friction: mu = tan(phi) [-], >= 0. stiffness: normal and shear stiffness [N/m3], > 0.
    dilatancy: tan(psi) [-], >= 0. Raises InputError naming the argument on bad input.
    """
    f = "dry_joint"
    k = _number(f, "stiffness", stiffness, 0.0, strict=True, unit="N/m3")
    return {
        "normal_stiffness": k,
        "shear_stiffness": k,
        "friction": _number(f, "friction", friction, 0.0),
        "cohesion": 0.0,
        "tensile_strength": 0.0,
        "dilatancy": _number(f, "dilatancy", dilatancy, 0.0),
    }


# --------------------------------------------------------------------------------------------------
# Conversions of a Results
# --------------------------------------------------------------------------------------------------


def _floats(a: Any) -> List[Any]:
    """A float array as nested lists, non-finite entries as None."""
    arr = np.asarray(a, dtype=float)
    if arr.ndim == 0:
        return _float(arr)  # type: ignore[return-value]
    return [_floats(row) if arr.ndim > 1 else _float(row) for row in arr]


def _dimension(obj: Any) -> int:
    """2 for a wall in the plane (Model and its Results), 3 for a wall of boxes (Model3D and its Results)."""
    return int(getattr(obj, "dimension", 2))


def check_model(func: str, results: Any, model: Any) -> None:
    """InputError when ``model`` does not match ``results`` (dimension, numbers of blocks and interfaces)."""
    if _dimension(model) != _dimension(results):
        raise InputError(f"{func}: model does not match results: a {_dimension(model)}D model and "
                         f"{_dimension(results)}D results")
    n_all = len(np.asarray(model.boxes if _dimension(model) == 3 else model.rects))
    m = int(model.n_interfaces)
    disp = np.asarray(results.displacements)
    forces = np.asarray(results.interface_forces)
    if len(disp) != n_all or len(forces) != m:
        raise InputError(
            f"{func}: model does not match results: the model has {n_all} blocks (with base and top beam) "
            f"and {m} interfaces, the results {len(disp)} blocks and {len(forces)} interfaces"
        )


def to_dict(results: Any, model: Any = None, title: Optional[str] = None) -> Dict[str, Any]:
    """Everything in a Results as plain Python values (lists, ints, floats, str, None), for json.dumps.

    Keys: method, status, error (None unless failed), collapse_multiplier (None unless the status is
    "collapse"), last_equilibrium (the largest multiplier of an equilibrium found, None if none), curve
    {multiplier, displacement [m]}, control_block, displacements ((n_all, 3) u1 [m], u2 [m], phi [rad]),
    mechanism ((n_all, 3)), interface_forces ((m, 3) N [N], T [N], M [N m]), interface_states (bit flags:
    1 open, 2 sliding, 4 rocking; 0 elastic), broken, joint_states {elastic, sliding, rocking, open},
    iterations, steps, elapsed_s [s], certificate (a limit analysis's certificate, see
    :data:`masonry_dem.case.CERTIFICATE_KEYS`; None for the other methods); title when given. With ``model`` also: blocks and interfaces
    (counts, as in the result file), base_index, top_index, block_rects ((n_all, 4) [x0, y0, x1, y1] m: each
    block's bounding box, the block itself for a rectangle), block_polygons (every block's vertices [[x, y], ...] m,
    counter-clockwise), weights [N], interface_blocks ((m, 2) a, b), interface_geometry ((m, 5) x, y [m], nx, ny,
    l [m]), interface_family. Non-finite numbers become None.

    The results of a 3D wall (``Results.dimension`` 3, a :class:`masonry_dem.Model3D`) have the same keys with
    ``"dimension": 3``: displacements and mechanism (n_all, 6) ux, uy, uz [m], rx, ry, rz [rad] (the mechanism's
    velocities), interface_forces (m, 6) N, T1, T2 [N], M_n, M_t1, M_t2 [N m] in the contact's axes; with ``model``
    block_boxes ((n_all, 6) [x0, y0, z0, x1, y1, z1] m: each block's bounding box, the block itself for a box)
    instead of block_rects, block_vertices (every block's vertices [[x, y, z], ...] m) and block_faces (every
    block's faces, each the indices of its vertices counter-clockwise seen from outside) instead of block_polygons,
    and interface_centroids ((m, 3) [m]), interface_normals ((m, 3)), interface_areas ((m,) [m2]) and
    interface_polygons (every contact's corners [[x, y, z], ...] m, counter-clockwise about its normal) instead of
    interface_geometry.
    """
    states = getattr(results, "joint_states", None) or {}
    out: Dict[str, Any] = {}
    if title is not None:
        out["title"] = str(title)
    if _dimension(results) == 3:
        out["dimension"] = 3
    out.update({
        "method": str(results.method),
        "status": str(results.status),
        "error": str(results.error) if results.error else None,
        "collapse_multiplier": _float(results.collapse_multiplier),
        "last_equilibrium": _float(getattr(results, "last_equilibrium", float("nan"))),
        "curve": {
            "multiplier": _floats(results.curve_multiplier),
            "displacement": _floats(results.curve_displacement),
        },
        "control_block": int(results.control_block),
        "displacements": _floats(results.displacements),
        "mechanism": _floats(results.mechanism),
        "interface_forces": _floats(results.interface_forces),
        "interface_states": [int(s) for s in np.asarray(results.interface_states)],
        "broken": [bool(b) for b in np.asarray(results.broken)],
        "joint_states": {key: int(states.get(key, 0)) for key in JOINT_STATE_KEYS},
        "iterations": int(results.iterations),
        "steps": int(results.steps),
        "elapsed_s": _float(results.elapsed_s),
        "certificate": certificate_dict(getattr(results, "certificate", None)),
    })
    if model is not None:
        check_model("to_dict", results, model)
        space = _dimension(model) == 3
        out.update({
            "blocks": int(model.n_blocks),
            "interfaces": int(model.n_interfaces),
            "base_index": None if model.base_index is None else int(model.base_index),
            "top_index": None if model.top_index is None else int(model.top_index),
            "block_boxes" if space else "block_rects": _floats(model.boxes if space else model.rects),
            **({} if space else {"block_polygons": [_floats(p) for p in shapes(model).polygons()]}),
            "weights": _floats(model.weights),
            "interface_blocks": [[int(a), int(b)] for a, b in np.asarray(model.interface_blocks).reshape(-1, 2)],
        })
        if space:
            solids = block_shapes(model)
            out.update({
                "block_vertices": [_floats(v) for v, _ in solids],
                "block_faces": [[[int(k) for k in f] for f in faces] for _, faces in solids],
                "interface_centroids": _floats(np.asarray(model.interface_centroids).reshape(-1, 3)),
                "interface_normals": _floats(np.asarray(model.interface_normals).reshape(-1, 3)),
                "interface_areas": _floats(model.interface_areas),
                "interface_polygons": [_floats(p) for p in contact_polygons(model)],
            })
        else:
            out["interface_geometry"] = _floats(np.asarray(model.interface_geometry).reshape(-1, 5))
        out["interface_family"] = [str(s) for s in model.interface_family]
    return out


def to_json(results: Any, path: PathLike, model: Any, title: Optional[str] = None) -> Dict[str, Any]:
    """Write the result file of docs/case-format.md (see :func:`masonry_dem.result_dict`) to ``path``.

    ``model`` is the Model the results came from (numbers of blocks and interfaces); ``title`` defaults
    to "untitled". The file is written atomically (:mod:`masonry_dem.atomic`): under a temporary name in
    its folder, then renamed. Returns the dict written. The same as :func:`masonry_dem.write_result_json`.
    """
    return write_result_json(path, results, model, "untitled" if title is None else str(title))


def _pandas(func: str, alternative: str) -> Any:
    try:
        import pandas
    except ImportError as exc:
        raise ImportError(
            f"masonry_dem.{func} needs pandas, which is not installed here (masonry-dem's extra "
            f"\"pandas\"): pip install 'masonry-dem[pandas]'; or use masonry_dem.{alternative} "
            f"for the same columns as NumPy arrays"
        ) from exc
    return pandas


def curve_columns(results: Any) -> Dict[str, np.ndarray]:
    """The curve as columns: multiplier (lambda, or the force [N] for live = "top_horizontal") and
    displacement_m (horizontal displacement of the control point [m]), one entry per converged step."""
    return {
        "multiplier": np.asarray(results.curve_multiplier, dtype=float).copy(),
        "displacement_m": np.asarray(results.curve_displacement, dtype=float).copy(),
    }


def interface_columns(results: Any, model: Any) -> Dict[str, np.ndarray]:
    """One entry per interface: a, b (block indices; the normal points from a to b), family, x, y
    (centroid [m]), nx, ny (normal), length_m [m], N_N (normal force [N], tension > 0), T_N (shear force
    [N]), M_Nm (moment [N m]), state (bit flags: 1 open, 2 sliding, 4 rocking; 0 elastic), broken.

    Of a 3D wall (:class:`masonry_dem.Model3D`), the columns of :data:`INTERFACE_COLUMNS_3D`: a, b, family, x, y, z
    (centroid [m]), nx, ny, nz (normal), area_m2 [m2], N_N, T1_N, T2_N [N] and Mn_Nm, Mt1_Nm, Mt2_Nm [N m] (the
    force and moment of block b on block a in the contact's axes: normal, t1, t2; tension > 0), state, broken."""
    check_model("interface_columns", results, model)
    m = int(model.n_interfaces)
    if _dimension(model) == 3:
        ab = np.asarray(model.interface_blocks, dtype=np.int64).reshape(m, 2)
        centre = np.asarray(model.interface_centroids, dtype=float).reshape(m, 3)
        normal = np.asarray(model.interface_normals, dtype=float).reshape(m, 3)
        forces = np.asarray(results.interface_forces, dtype=float).reshape(m, 6)
        names = ("N_N", "T1_N", "T2_N", "Mn_Nm", "Mt1_Nm", "Mt2_Nm")
        return {
            "a": ab[:, 0].copy(),
            "b": ab[:, 1].copy(),
            "family": np.asarray([str(s) for s in model.interface_family], dtype=object),
            **{k: centre[:, i].copy() for i, k in enumerate(("x", "y", "z"))},
            **{k: normal[:, i].copy() for i, k in enumerate(("nx", "ny", "nz"))},
            "area_m2": np.asarray(model.interface_areas, dtype=float).reshape(m).copy(),
            **{k: forces[:, i].copy() for i, k in enumerate(names)},
            "state": np.asarray(results.interface_states, dtype=np.int64).copy(),
            "broken": np.asarray(results.broken, dtype=bool).copy(),
        }
    ab = np.asarray(model.interface_blocks, dtype=np.int64).reshape(m, 2)
    geo = np.asarray(model.interface_geometry, dtype=float).reshape(m, 5)
    forces = np.asarray(results.interface_forces, dtype=float).reshape(m, 3)
    return {
        "a": ab[:, 0].copy(),
        "b": ab[:, 1].copy(),
        "family": np.asarray([str(s) for s in model.interface_family], dtype=object),
        "x": geo[:, 0].copy(),
        "y": geo[:, 1].copy(),
        "nx": geo[:, 2].copy(),
        "ny": geo[:, 3].copy(),
        "length_m": geo[:, 4].copy(),
        "N_N": forces[:, 0].copy(),
        "T_N": forces[:, 1].copy(),
        "M_Nm": forces[:, 2].copy(),
        "state": np.asarray(results.interface_states, dtype=np.int64).copy(),
        "broken": np.asarray(results.broken, dtype=bool).copy(),
    }


def to_dataframe(results: Any, model: Any = None) -> Any:
    """The curve as a pandas DataFrame with columns multiplier and displacement_m [m] (see
    :func:`curve_columns`), one row per converged step. ``df.attrs`` holds method, status and
    collapse_multiplier, and with ``model`` the numbers of blocks and interfaces.

    Raises ImportError (naming pandas) when pandas is not installed."""
    pd = _pandas("to_dataframe", "curve_columns")
    df = pd.DataFrame(curve_columns(results), columns=list(CURVE_COLUMNS))
    df.attrs.update({
        "method": str(results.method),
        "status": str(results.status),
        "collapse_multiplier": _float(results.collapse_multiplier),
    })
    if model is not None:
        check_model("to_dataframe", results, model)
        df.attrs.update({"blocks": int(model.n_blocks), "interfaces": int(model.n_interfaces)})
    return df


def interfaces_dataframe(results: Any, model: Any) -> Any:
    """The interfaces as a pandas DataFrame, one row per interface, with the columns of
    :func:`interface_columns` (a, b, family, x, y, nx, ny, length_m, N_N, T_N, M_Nm, state, broken).

    Raises ImportError (naming pandas) when pandas is not installed."""
    pd = _pandas("interfaces_dataframe", "interface_columns")
    columns = INTERFACE_COLUMNS_3D if _dimension(model) == 3 else INTERFACE_COLUMNS
    return pd.DataFrame(interface_columns(results, model), columns=list(columns))
