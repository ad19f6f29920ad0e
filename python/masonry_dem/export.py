"""Exports of an analysis: VTK (.vtu, for ParaView) of the blocks and the interfaces, and CSV of the curve.

:func:`write_vtk` writes two unstructured-grid files (meshio):

* ``PREFIX-blocks.vtu``: every block (wall blocks, then the base and the top beam, as in ``Model.rects``)
  as a quad in the plane z = 0 [m]. Cell data: ``displacement`` (u1, u2, 0) [m] and ``rotation`` phi
  [rad] at the last converged step, ``mechanism`` (the last increment, scaled to max |u| = 1; 3-vector
  u1, u2, 0), ``kind`` (0 wall block, 1 base, 2 top beam), ``block`` (index). Point data:
  ``displacement`` of each corner (u + phi k x r, linearized) [m], for ParaView's *Warp By Vector*.
* ``PREFIX-interfaces.vtu``: every interface as a line from centroid - l/2 t to centroid + l/2 t, with
  the tangent t = (ny, -nx) of the normal (nx, ny) of ``Model.interface_geometry``. Cell data:
  ``normal_force`` N [N] (tension > 0), ``shear_force`` T [N], ``moment`` M [N m], ``state`` (bit flags:
  1 open, 2 sliding, 4 rocking; 0 elastic), ``broken`` (1 when the joint lost its cohesion and tensile
  strength), ``family`` (0 bed, 1 head, 2 base, 3 top), ``interface`` (index).

:func:`write_curve_csv` writes the load curve: a header ``multiplier,displacement_m`` and one row per
converged step (lambda, or the force in N for ``live = "top_horizontal"``; the horizontal displacement of
the control point in m). A limit analysis has no curve: its file is the header alone, and its blocks file has
zero ``displacement`` and ``rotation`` and the collapse velocities as ``mechanism``.

Every file is written atomically (:mod:`masonry_dem.atomic`): under a temporary name in its folder, synced,
then renamed, so that a reader never sees half a file; a target that is not a regular file (a folder, a
device, a FIFO) is refused with InputError.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Iterable, Tuple, Union

import numpy as np

from .atomic import atomic_file, atomic_path, check_target

__all__ = ["write_vtk", "write_curve_csv", "block_mesh", "interface_mesh", "CSV_HEADER", "FAMILY_CODES"]

PathLike = Union[str, "os.PathLike[str]"]

#: The header line of the curve CSV.
CSV_HEADER = "multiplier,displacement_m"

#: Codes of the interface families in the ``family`` field.
FAMILY_CODES = {"bed": 0, "head": 1, "base": 2, "top": 3}


def _field(values: Any, shape: Tuple[int, ...]) -> np.ndarray:
    """``values`` as a float array of ``shape``, or NaN of that shape when it has another (no result)."""
    a = np.asarray(values, dtype=np.float64)
    return a.reshape(shape) if a.size == int(np.prod(shape)) else np.full(shape, np.nan)


def block_mesh(model: Any, results: Any) -> Any:
    """The blocks as a :class:`meshio.Mesh` (see the module docstring for the fields)."""
    import meshio

    rects = np.asarray(model.rects, dtype=np.float64).reshape(-1, 4)
    n = len(rects)
    x0, y0, x1, y1 = rects.T
    corners = np.stack([np.c_[x0, y0], np.c_[x1, y0], np.c_[x1, y1], np.c_[x0, y1]], axis=1)  # (n, 4, 2)
    points = np.concatenate([corners.reshape(-1, 2), np.zeros((4 * n, 1))], axis=1)
    quads = np.arange(4 * n, dtype=np.int64).reshape(n, 4)

    disp = _field(results.displacements, (n, 3))
    mech = _field(results.mechanism, (n, 3))
    kind = np.zeros(n, dtype=np.int32)
    if model.base_index is not None:
        kind[int(model.base_index)] = 1
    if model.top_index is not None:
        kind[int(model.top_index)] = 2

    # corner displacements of the rigid blocks (linearized rotation about the centroid)
    centroid = 0.5 * np.c_[x0 + x1, y0 + y1]
    r = corners - centroid[:, None, :]
    phi = disp[:, 2][:, None]
    corner_u = np.stack([disp[:, 0][:, None] - phi * r[..., 1], disp[:, 1][:, None] + phi * r[..., 0]], axis=-1)
    point_disp = np.concatenate([corner_u.reshape(-1, 2), np.zeros((4 * n, 1))], axis=1)

    def vec(a: np.ndarray) -> np.ndarray:
        return np.c_[a[:, 0], a[:, 1], np.zeros(n)]

    return meshio.Mesh(
        points,
        [("quad", quads)],
        point_data={"displacement": point_disp},
        cell_data={
            "displacement": [vec(disp)],
            "rotation": [disp[:, 2].copy()],
            "mechanism": [vec(mech)],
            "kind": [kind],
            "block": [np.arange(n, dtype=np.int32)],
        },
    )


def interface_mesh(model: Any, results: Any) -> Any:
    """The interfaces as a :class:`meshio.Mesh` of lines (see the module docstring for the fields)."""
    import meshio

    geom = np.asarray(model.interface_geometry, dtype=np.float64).reshape(-1, 5)
    m = len(geom)
    cx, cy, nx, ny, length = geom.T
    tx, ty = ny * length / 2, -nx * length / 2  # half the interface along t = (ny, -nx)
    ends = np.stack([np.c_[cx - tx, cy - ty], np.c_[cx + tx, cy + ty]], axis=1).reshape(-1, 2)
    points = np.concatenate([ends, np.zeros((2 * m, 1))], axis=1)
    lines = np.arange(2 * m, dtype=np.int64).reshape(m, 2)

    forces = _field(results.interface_forces, (m, 3))
    states = np.asarray(results.interface_states, dtype=np.int64).reshape(-1)
    states = states.astype(np.int32) if len(states) == m else np.zeros(m, dtype=np.int32)
    broken = np.asarray(results.broken).reshape(-1)
    broken = broken.astype(np.int32) if len(broken) == m else np.zeros(m, dtype=np.int32)
    families = list(model.interface_family)
    family = np.array([FAMILY_CODES.get(f, -1) for f in families], dtype=np.int32).reshape(-1)
    if len(family) != m:
        family = np.full(m, -1, dtype=np.int32)

    return meshio.Mesh(
        points,
        [("line", lines)],
        cell_data={
            "normal_force": [forces[:, 0].copy()],
            "shear_force": [forces[:, 1].copy()],
            "moment": [forces[:, 2].copy()],
            "state": [states],
            "broken": [broken],
            "family": [family],
            "interface": [np.arange(m, dtype=np.int32)],
        },
    )


def write_vtk(
    model: Any, results: Any, path_prefix: PathLike, *, inputs: Iterable[PathLike] = ()
) -> Tuple[Path, Path]:
    """Write ``PATH_PREFIX-blocks.vtu`` and ``PATH_PREFIX-interfaces.vtu`` (VTK unstructured grids).

    Args:
        model: the :class:`masonry_dem.Model` analysed.
        results: its :class:`masonry_dem.Results` (the last converged step).
        path_prefix: the files' path without the ``-blocks.vtu`` / ``-interfaces.vtu`` ending; a trailing
            ``.vtu`` is dropped. The folder is created if missing.
        inputs: files that must not be overwritten (the case file): a target that is one of them, or
            that is not a regular file, is refused with InputError before either file is written.
    Returns:
        The paths of the blocks file and of the interfaces file.
    """
    prefix = str(path_prefix)
    if prefix.endswith(".vtu"):
        prefix = prefix[: -len(".vtu")]
    blocks_path, faces_path = Path(prefix + "-blocks.vtu"), Path(prefix + "-interfaces.vtu")
    inputs = list(inputs)
    for path in (blocks_path, faces_path):
        check_target(path, inputs)
    blocks_path.parent.mkdir(parents=True, exist_ok=True)
    for path, mesh in ((blocks_path, block_mesh(model, results)), (faces_path, interface_mesh(model, results))):
        atomic_path(path, lambda tmp, mesh=mesh: mesh.write(tmp, file_format="vtu"), inputs=inputs)
    return blocks_path, faces_path


def write_curve_csv(results: Any, path: PathLike, *, inputs: Iterable[PathLike] = ()) -> Path:
    """Write the load curve as CSV: header ``multiplier,displacement_m``, one row per converged step.

    ``multiplier`` is lambda (the force on the top beam in N with ``live = "top_horizontal"``),
    ``displacement_m`` the horizontal displacement of the control point [m]. Numbers are written with 17
    significant digits (they read back exactly); non-finite values as ``nan``. Read it back with
    ``numpy.loadtxt(path, delimiter=",", skiprows=1)``. A target that is not a regular file (``/dev/null``,
    a FIFO, a folder) or is one of ``inputs`` (the case file) is refused with InputError. Returns the path.
    """
    lam = np.asarray(results.curve_multiplier, dtype=np.float64).reshape(-1)
    disp = np.asarray(results.curve_displacement, dtype=np.float64).reshape(-1)
    if len(lam) != len(disp):
        raise ValueError(f"the curve has {len(lam)} multipliers but {len(disp)} displacements")
    path = Path(path)
    inputs = list(inputs)
    check_target(path, inputs)
    if str(path.parent):
        path.parent.mkdir(parents=True, exist_ok=True)

    with atomic_file(path, "w", encoding="ascii", newline="\n", inputs=inputs) as f:
        f.write(CSV_HEADER + "\n")
        for a, b in zip(lam, disp):
            f.write(f"{a:.17g},{b:.17g}\n")
    return path
