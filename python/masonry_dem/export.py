"""Exports of an analysis: VTK (.vtu, for ParaView) of the blocks and the interfaces, and CSV of the curve.

:func:`write_vtk` writes two unstructured-grid files (meshio):

* ``PREFIX-blocks.vtu``: every block (wall blocks, then the supports, the base and the top beam, as in
  ``Model.polygons``) as a cell in the plane z = 0 [m], its vertices counter-clockwise: a quad of 4 vertices (every
  rectangle), a triangle of 3, a VTK polygon of more (the cells in the order of the blocks, in runs of one type).
  Cell data: ``displacement`` (u1, u2, 0) [m] and ``rotation`` phi [rad] at the last converged step, ``mechanism``
  (the last increment, scaled to max |u| = 1; 3-vector u1, u2, 0), ``kind`` (0 wall block, 1 base, 2 top beam, 3
  support), ``block`` (index). Point data: ``displacement`` of each vertex (u + phi k x r about the block's
  centroid, linearized) [m], for ParaView's *Warp By Vector*.
* ``PREFIX-interfaces.vtu``: every interface as a line from centroid - l/2 t to centroid + l/2 t, with
  the tangent t = (ny, -nx) of the normal (nx, ny) of ``Model.interface_geometry``. Cell data:
  ``normal_force`` N [N] (tension > 0), ``shear_force`` T [N], ``moment`` M [N m], ``state`` (bit flags:
  1 open, 2 sliding, 4 rocking; 0 elastic), ``broken`` (1 when the joint lost its cohesion and tensile
  strength), ``family`` (0 bed, 1 head, 2 base, 3 top), ``interface`` (index).

:func:`write_curve_csv` writes the load curve: a header ``multiplier,displacement_m`` and one row per
converged step (lambda, or the force in N for ``live = "top_horizontal"``; the horizontal displacement of
the control point in m). A limit analysis has no curve: its file is the header alone, and its blocks file has
zero ``displacement`` and ``rotation`` and the collapse velocities as ``mechanism``.

A time history (:class:`masonry_dem.TimeHistory`, ``Model.simulate``) is a result too: :func:`write_vtk` writes a
time series for ParaView, ``PREFIX-blocks-NNNN.vtu`` per recorded time (:func:`history_block_mesh`: the fields of
the blocks file with ``velocity`` (v1, v2, 0) [m/s] and ``angular_velocity`` [rad/s] instead of ``mechanism``)
and ``PREFIX.pvd``, the collection listing them with their times [s] (open that one); no interfaces file, a time
history has no interface forces. With the contact update (``Model.simulate``'s default) it writes
``PREFIX-contacts-NNNN.vtu`` too, the contacts of each record as lines (:func:`contact_mesh`: ``contact``, its number;
``created``, 1 for a contact the update made; ``block_a``, ``block_b``), the collection's part 1: the contacts
appear and vanish as the blocks move. :func:`write_curve_csv` (with ``model=``) writes its response, header
:data:`HISTORY_CSV_HEADER`, a row per recorded time. Its displacements are relative to the ground (the blocks
move in the frame of the base), from the undeformed wall (:mod:`masonry_dem.history`).

Every file is written atomically (:mod:`masonry_dem.atomic`): under a temporary name in its folder, synced,
then renamed, so that a reader never sees half a file; a target that is not a regular file (a folder, a
device, a FIFO) is refused with InputError.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Dict, Iterable, List, Tuple, Union

import numpy as np

from ._vtk import FAMILY_CODES as FAMILY_CODES, write_meshes as _write_meshes, write_series
from ._core import InputError
from ._shapes import Shapes, shapes, support_indices
from .api import check_model
from .atomic import atomic_file, check_target, prefix_problem
from .history import ENERGIES, check_plane, contact_sets, control_response, is_time_history, largest_translation, record

__all__ = [
    "write_vtk",
    "write_curve_csv",
    "block_mesh",
    "history_block_mesh",
    "contact_mesh",
    "interface_mesh",
    "CSV_HEADER",
    "HISTORY_CSV_HEADER",
    "FAMILY_CODES",
]

PathLike = Union[str, "os.PathLike[str]"]

#: The header line of the curve CSV.
CSV_HEADER = "multiplier,displacement_m"

#: The header line of a time history's CSV (units in the names: s, m, rad, J).
HISTORY_CSV_HEADER = "time_s,displacement_m,rotation_rad,max_translation_m," + ",".join(f"{e}_J" for e in ENERGIES)


def _field(values: Any, shape: Tuple[int, ...]) -> np.ndarray:
    """``values`` as a float array of ``shape``, or NaN of that shape when it has another (no result)."""
    a = np.asarray(values, dtype=np.float64)
    return a.reshape(shape) if a.size == int(np.prod(shape)) else np.full(shape, np.nan)


def block_mesh(model: Any, results: Any) -> Any:
    """The blocks as a :class:`meshio.Mesh` (see the module docstring for the fields)."""
    n = len(shapes(model))
    disp = _field(results.displacements, (n, 3))
    mech = _field(results.mechanism, (n, 3))
    return _blocks(model, disp, {"mechanism": _vec(mech)}, exact=False)


def history_block_mesh(model: Any, history: Any, k: int) -> Any:
    """The blocks at the ``k``-th record of a time history as a :class:`meshio.Mesh`: the fields of
    :func:`block_mesh` with ``velocity`` (v1, v2, 0) [m/s] and ``angular_velocity`` [rad/s] in place of
    ``mechanism``; the vertices' ``displacement`` with the rotation applied exactly (rocking turns far)."""
    n = len(shapes(model))
    rec = record(history, k)
    vel = _field(rec.velocities, (n, 3))
    fields = {"velocity": _vec(vel), "angular_velocity": vel[:, 2].copy()}
    return _blocks(model, _field(rec.displacements, (n, 3)), fields, exact=True)


def _vec(a: np.ndarray) -> np.ndarray:
    """(n, 3) rows (a1, a2, 0) of the translations of (n, 3) rows (a1, a2, phi)."""
    return np.c_[a[:, 0], a[:, 1], np.zeros(len(a))]


def _blocks(model: Any, disp: np.ndarray, fields: Dict[str, np.ndarray], exact: bool) -> Any:
    """The blocks moved by ``disp`` ((n_all, 3): u1, u2 [m], phi [rad]) as a mesh with the cell data
    ``displacement``, ``rotation``, then ``fields``, then ``kind`` and ``block``. The vertices' displacement
    turns them about the centroid by phi exactly if ``exact``, else linearized (u + phi k x r)."""
    import meshio

    blocks = shapes(model)
    n, p = len(blocks), len(blocks.points)
    points = np.concatenate([blocks.points, np.zeros((p, 1))], axis=1)

    kind = np.zeros(n, dtype=np.int32)
    kind[support_indices(model)] = 3
    if model.base_index is not None:
        kind[int(model.base_index)] = 1
    if model.top_index is not None:
        kind[int(model.top_index)] = 2

    # vertex displacements of the rigid blocks (rotation about the centroid)
    vertex_u = blocks.displacements(disp, exact)
    point_disp = np.concatenate([vertex_u, np.zeros((p, 1))], axis=1)

    cells, runs = _cells(blocks)
    cell_data = {"displacement": _vec(disp), "rotation": disp[:, 2].copy()}
    cell_data.update(fields)
    cell_data.update({"kind": kind, "block": np.arange(n, dtype=np.int32)})
    split = {name: np.split(values, runs) for name, values in cell_data.items()}
    return meshio.Mesh(points, cells, point_data={"displacement": point_disp}, cell_data=split)


#: The VTK cell of a block of 3 and of 4 vertices; a block of more is a "polygon".
_CELL_TYPES = {3: "triangle", 4: "quad"}


def _cells(blocks: Shapes) -> Tuple[List[Tuple[str, np.ndarray]], np.ndarray]:
    """The blocks as meshio cell blocks, in the order of the blocks: a run of blocks of one vertex count per cell
    block (every vertex of the wall a point, block after block); and where each run after the first starts."""
    counts = blocks.counts
    runs = np.flatnonzero(np.diff(counts)) + 1
    cells = []
    for lo, hi in zip(np.r_[0, runs], np.r_[runs, len(counts)]):
        k = int(counts[lo])
        cells.append((_CELL_TYPES.get(k, "polygon"), np.arange(blocks.starts[lo], blocks.starts[hi]).reshape(-1, k)))
    return cells, runs


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
) -> Tuple[Path, Any]:
    """Write ``PATH_PREFIX-blocks.vtu`` and ``PATH_PREFIX-interfaces.vtu`` (VTK unstructured grids); of a
    time history, a time series instead: ``PATH_PREFIX-blocks-NNNN.vtu`` per record and ``PATH_PREFIX.pvd``.

    Args:
        model: the :class:`masonry_dem.Model` analysed; a :class:`masonry_dem.Model3D` writes its blocks as
            hexahedra (polyhedra when some block is no box) and its contacts as their polygons, or the series of a
            time history (:func:`masonry_dem.space.export.write_vtk`).
        results: its :class:`masonry_dem.Results` (the last converged step), or a
            :class:`masonry_dem.TimeHistory` (``Model.simulate``): then one blocks file per recorded time
            (:func:`history_block_mesh`: displacements relative to the ground, from the undeformed wall,
            and velocities), numbered from 0, and a ParaView collection ``PATH_PREFIX.pvd`` listing them
            with their times [s]. A time history has no interface forces or states: no interfaces file.
        path_prefix: the files' path without the ``-blocks.vtu`` / ``-interfaces.vtu`` ending; a trailing
            ``.vtu`` (or ``.pvd``) is dropped. The folder is created if missing.
        inputs: files that must not be overwritten (the case file): a target that is one of them, or
            that is not a regular file, is refused with InputError before any file is written.
    Raises:
        InputError: results of another model (another dimension, or other numbers of blocks and
            interfaces), or a prefix that is a folder (``"out/"``: give ``"out/wall"``).
    Returns:
        The paths of the blocks file and of the interfaces file; of a time history, the path of the
        ``.pvd`` file and the list of the blocks files, in the order of the records.
    """
    prefix = str(path_prefix)
    for ending in (".vtu", ".pvd"):
        if prefix.endswith(ending):
            prefix = prefix[: -len(ending)]
    problem = prefix_problem(prefix)
    if problem:
        raise InputError(f"write_vtk: path_prefix: {problem}")
    space = int(getattr(model, "dimension", 2)) == 3
    if not is_time_history(results):
        check_model("write_vtk", results, model)
    elif int(getattr(results, "dimension", 2)) != int(getattr(model, "dimension", 2)) or (
            np.shape(results.displacements)[1:] != (len(np.asarray(model.boxes if space else model.rects)),
                                                    6 if space else 3)):
        raise InputError("write_vtk: model does not match results: the time history is of another model (another "
                         "dimension or number of blocks)")
    if space:  # a 3D wall: its blocks and contacts, or its time series
        from .space.export import write_vtk as write_vtk_3d

        return write_vtk_3d(model, results, prefix, inputs=inputs)
    if is_time_history(results):
        return _write_vtk_series(model, results, prefix, list(inputs))
    blocks_path, faces_path = Path(prefix + "-blocks.vtu"), Path(prefix + "-interfaces.vtu")
    meshes = [(blocks_path, block_mesh(model, results)), (faces_path, interface_mesh(model, results))]
    _write_meshes(meshes, list(inputs))
    return blocks_path, faces_path


def _write_vtk_series(model: Any, history: Any, prefix: str, inputs: List[PathLike]) -> Tuple[Path, List[Path]]:
    """The time series of :func:`write_vtk`: a blocks file per record, with the contact update a contacts file per
    record (:func:`contact_mesh`), and the ``.pvd`` collection."""
    contacts = None
    if history.contact_counts[0] > 0:
        meshes = [contact_mesh(c) for c in contact_sets(model, history, range(len(history.times)))]
        contacts = meshes.__getitem__
    return write_series(prefix, history.times, lambda k: history_block_mesh(model, history, k), inputs, contacts)


def contact_mesh(contacts: Any) -> Any:
    """The contacts of one record of a time history with the contact update (a namespace of
    :func:`masonry_dem.history.contact_sets`) as a :class:`meshio.Mesh` of lines, with the cell fields
    ``contact`` (the contact's number), ``created`` (1: made by the update) and ``block_a``, ``block_b``."""
    import meshio

    ends = np.asarray(contacts.ends, dtype=np.float64).reshape(-1, 2)
    m = len(ends) // 2
    points = np.concatenate([ends, np.zeros((2 * m, 1))], axis=1)
    blocks = np.asarray(contacts.blocks, dtype=np.int32).reshape(-1, 2)
    return meshio.Mesh(
        points,
        [("line", np.arange(2 * m, dtype=np.int64).reshape(m, 2))],
        cell_data={
            "contact": [np.asarray(contacts.ids, dtype=np.int32).reshape(-1)],
            "created": [np.asarray(contacts.created, dtype=np.int32).reshape(-1)],
            "block_a": [blocks[:, 0].copy()],
            "block_b": [blocks[:, 1].copy()],
        },
    )


def write_curve_csv(
    results: Any, path: PathLike, *, inputs: Iterable[PathLike] = (), model: Any = None
) -> Path:
    """Write the load curve as CSV: header ``multiplier,displacement_m``, one row per converged step; of a
    time history, its response: header :data:`HISTORY_CSV_HEADER`, one row per recorded time.

    ``multiplier`` is lambda (the force on the top beam in N with ``live = "top_horizontal"``),
    ``displacement_m`` the horizontal displacement of the control point [m]. Of a
    :class:`masonry_dem.TimeHistory` (``Model.simulate``): ``time_s`` [s]; ``displacement_m`` [m] and
    ``rotation_rad`` [rad] of the model's default control block (the top beam, else the highest wall block
    at the right end; :func:`masonry_dem.history.default_control_block`); ``max_translation_m`` the largest
    translation of any block [m]; and the energy balance [J] (:data:`masonry_dem.history.ENERGIES`: kinetic,
    elastic in the joints, work of the external loads since t = 0 and of the weights among them, dissipated by
    friction, by damping and by impacts, their sum, and the balance's error). Displacements are relative to the ground (the frame of the base), from
    the undeformed wall. Numbers are written with 17 significant digits (they read back exactly);
    non-finite values as ``nan``. Read it back with ``numpy.loadtxt(path, delimiter=",", skiprows=1)``. A
    target that is not a regular file (``/dev/null``, a FIFO, a folder) or is one of ``inputs`` (the case
    file) is refused with InputError. Returns the path.

    ``model``: the :class:`masonry_dem.Model` simulated, required with a time history (which does not
    know its blocks: the control block is the model's); ignored with Results.
    """
    if is_time_history(results):
        if model is None:
            raise TypeError("write_curve_csv of a TimeHistory needs model= (the Model simulated: its control block)")
        check_plane(model, "write_curve_csv")
        u, phi = control_response(model, results)
        energies = [np.asarray(getattr(results, name), dtype=np.float64).reshape(-1) for name in ENERGIES]
        columns = [np.asarray(results.times, dtype=np.float64).reshape(-1), u, phi, largest_translation(results)]
        return _write_columns(path, HISTORY_CSV_HEADER, columns + energies, list(inputs))
    lam = np.asarray(results.curve_multiplier, dtype=np.float64).reshape(-1)
    disp = np.asarray(results.curve_displacement, dtype=np.float64).reshape(-1)
    if len(lam) != len(disp):
        raise ValueError(f"the curve has {len(lam)} multipliers but {len(disp)} displacements")
    return _write_columns(path, CSV_HEADER, [lam, disp], list(inputs))


def _write_columns(path: PathLike, header: str, columns: List[np.ndarray], inputs: List[PathLike]) -> Path:
    """Write ``header`` and a row per entry of the (equally long) ``columns``, 17 significant digits, atomically."""
    path = Path(path)
    check_target(path, inputs)
    if str(path.parent):
        path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_file(path, "w", encoding="ascii", newline="\n", inputs=inputs) as f:
        f.write(header + "\n")
        for row in zip(*columns):
            f.write(",".join(f"{v:.17g}" for v in row) + "\n")
    return path
