"""VTK exports of a 3D wall's analysis (meshio, as the 2D ones of :mod:`masonry_dem.export`), for ParaView:

* ``PREFIX-blocks.vtu``: every block (wall blocks, then the base, the top beam and the supports, as in
  ``Model3D.boxes``) as a hexahedron when every block is a box, else as a polyhedron cell of its own vertices and
  faces (``Model3D.block_vertices``, ``block_faces``; VTK mixes no polyhedra with other cells). Point data:
  ``mechanism``, the velocity of each vertex in the collapse mechanism (v + w x r; the largest block translation is
  1), and ``displacement`` [m] of each vertex (zero for limit analysis), for ParaView's *Warp By Vector*. Cell data:
  ``displacement`` (ux, uy, uz) [m] and ``rotation`` (rx, ry, rz) [rad], ``mechanism`` (vx, vy, vz) and
  ``mechanism_rotation`` (wx, wy, wz) of the block, ``motion`` (its largest vertex motion in the mechanism, over the
  largest of all blocks: 0 at rest, 1 the most moving), ``kind`` (0 wall block, 1 base, 2 top beam, 3 support),
  ``block`` (index).
* ``PREFIX-interfaces.vtu``: every contact as its polygon (``Model3D.interface_polygons``): a quad between boxes,
  a triangle or a polygon of any number of corners between polyhedra, the cells in the contacts' order. Cell data:
  ``normal_force`` N [N] (tension > 0), ``shear_force_t1`` T1 and ``shear_force_t2`` T2 [N], ``torsion`` M_n,
  ``moment_t1`` M_t1 and ``moment_t2`` M_t2 [N m] (block b on block a, in the contact's axes), ``normal`` (a
  3-vector), ``area`` [m2], ``state`` (bit flags: 1 open, 2 sliding, 4 rocking; 0 elastic), ``broken``, ``family``
  (0 bed, 1 head, 2 base, 3 top), ``interface`` (index).
* of a time history (``Model3D.simulate``), a series for ParaView instead: ``PREFIX-blocks-NNNN.vtu`` per record
  (:func:`history_block_mesh`) and ``PREFIX.pvd``, the collection listing them with their times [s] (open that one).

Every file is written atomically; a target that is not a regular file, or one of ``inputs``, is refused with
InputError (:func:`masonry_dem.export.write_vtk` calls :func:`write_vtk` for a 3D model).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Iterable, Tuple, Union

import numpy as np

from .._vtk import FAMILY_CODES, write_meshes, write_series
from .report import all_boxes, block_shapes, box_corners, contact_polygons, dof_points, moved_vertices, vertex_motion

__all__ = ["block_mesh", "history_block_mesh", "interface_mesh", "write_vtk"]

PathLike = Union[str, "os.PathLike[str]"]


def _rows(values: Any, n: int, width: int) -> np.ndarray:
    """``values`` as an (n, width) float array, or NaN of that shape when it has another size (no result)."""
    a = np.asarray(values, dtype=np.float64)
    return a.reshape(n, width) if a.size == n * width else np.full((n, width), np.nan)


def _solids(model: Any) -> Tuple[np.ndarray, Any, np.ndarray]:
    """(the blocks' vertices at rest (p, 3) [m], the cells, the block of each vertex (p,)): hexahedra of the boxes'
    corners in VTK's order when every block is a box, else a polyhedron cell of each block's own vertices and faces
    (VTK takes no mix of polyhedra with other cells)."""
    import meshio

    boxes = np.asarray(model.boxes, dtype=np.float64).reshape(-1, 6)
    n = len(boxes)
    if all_boxes(model):
        vertices = list(box_corners(boxes))
        cells: Any = [("hexahedron", np.arange(8 * n, dtype=np.int64).reshape(n, 8))]
    else:
        shapes = block_shapes(model)
        vertices = [v for v, _ in shapes]
        first = np.cumsum([0] + [len(v) for v in vertices])
        cells = [meshio.CellBlock("polyhedron", [[np.asarray(f, dtype=np.int64) + first[i] for f in faces]
                                                 for i, (_, faces) in enumerate(shapes)])]
    owner = np.repeat(np.arange(n), [len(v) for v in vertices])
    return (np.concatenate(vertices) if n else np.zeros((0, 3))), cells, owner


def _kinds(model: Any, n: int) -> np.ndarray:
    """(n,) the ``kind`` of each block: 0 wall block, 1 base, 2 top beam, 3 support (the plane's codes)."""
    kind = np.zeros(n, dtype=np.int32)
    kind[int(model.n_blocks):] = 3  # the fixed blocks after the wall's: the supports, the base among them
    if model.base_index is not None:
        kind[int(model.base_index)] = 1
    if model.top_index is not None:
        kind[int(model.top_index)] = 2
    return kind


def block_mesh(model: Any, results: Any) -> Any:
    """The blocks of a 3D wall as a :class:`meshio.Mesh` of hexahedra or polyhedra (see the module docstring for the
    fields)."""
    import meshio

    points, cells, owner = _solids(model)
    n = len(np.asarray(model.boxes).reshape(-1, 6))
    r = points - dof_points(model)[owner]  # from where the blocks' dofs are
    disp, mech = _rows(results.displacements, n, 6), _rows(results.mechanism, n, 6)
    point_mech = mech[owner, :3] + np.cross(mech[owner, 3:], r)
    point_disp = disp[owner, :3] + np.cross(disp[owner, 3:], r)
    motion = vertex_motion(model, np.nan_to_num(mech))
    peak = float(motion.max()) if n else 0.0
    cell_data = {
        "displacement": [disp[:, :3].copy()],
        "rotation": [disp[:, 3:].copy()],
        "mechanism": [mech[:, :3].copy()],
        "mechanism_rotation": [mech[:, 3:].copy()],
        "motion": [motion / peak if peak > 0 else motion],
        "kind": [_kinds(model, n)],
        "block": [np.arange(n, dtype=np.int32)],
    }
    return meshio.Mesh(points, cells, point_data={"mechanism": point_mech, "displacement": point_disp},
                       cell_data=cell_data)


def history_block_mesh(model: Any, history: Any, k: int) -> Any:
    """The blocks at the ``k``-th record of a 3D time history (``Model3D.simulate``) as a :class:`meshio.Mesh`,
    at rest with the vertices' ``displacement`` [m] (point data) from the undeformed wall, the rotation vector
    applied exactly (a block turns far in a time history), for ParaView's *Warp By Vector*. Cell data:
    ``displacement`` (ux, uy, uz) [m], ``rotation`` (rx, ry, rz) [rad], ``velocity`` [m/s], ``angular_velocity``
    [rad/s], ``kind``, ``block``."""
    import meshio

    points, cells, owner = _solids(model)
    n = len(np.asarray(model.boxes).reshape(-1, 6))
    disp = _rows(np.asarray(history.displacements, dtype=np.float64)[k], n, 6)
    vel = _rows(np.asarray(history.velocities, dtype=np.float64)[k], n, 6)
    moved = np.concatenate(moved_vertices(model, disp, 1.0)) if n else points
    cell_data = {
        "displacement": [disp[:, :3].copy()],
        "rotation": [disp[:, 3:].copy()],
        "velocity": [vel[:, :3].copy()],
        "angular_velocity": [vel[:, 3:].copy()],
        "kind": [_kinds(model, n)],
        "block": [np.arange(n, dtype=np.int32)],
    }
    return meshio.Mesh(points, cells, point_data={"displacement": moved - points}, cell_data=cell_data)


def interface_mesh(model: Any, results: Any) -> Any:
    """The contacts of a 3D wall as a :class:`meshio.Mesh` of their polygons (see the module docstring for the
    fields)."""
    import meshio

    polygons = contact_polygons(model)
    m = len(polygons)
    forces = _rows(results.interface_forces, m, 6)
    states = np.asarray(results.interface_states, dtype=np.int64).reshape(-1)
    states = states.astype(np.int32) if len(states) == m else np.zeros(m, dtype=np.int32)
    broken = np.asarray(results.broken).reshape(-1)
    broken = broken.astype(np.int32) if len(broken) == m else np.zeros(m, dtype=np.int32)
    family = np.array([FAMILY_CODES.get(str(f), -1) for f in model.interface_family], dtype=np.int32).reshape(-1)
    names = ("normal_force", "shear_force_t1", "shear_force_t2", "torsion", "moment_t1", "moment_t2")
    cell_data = {name: [forces[:, k].copy()] for k, name in enumerate(names)}
    cell_data.update({
        "normal": [np.asarray(model.interface_normals, dtype=np.float64).reshape(m, 3)],
        "area": [np.asarray(model.interface_areas, dtype=np.float64).reshape(m)],
        "state": [states],
        "broken": [broken],
        "family": [family if len(family) == m else np.full(m, -1, dtype=np.int32)],
        "interface": [np.arange(m, dtype=np.int32)],
    })
    # the polygons in runs of equal numbers of corners, in order: quads between boxes, triangles and polygons
    sizes = [len(p) for p in polygons]
    runs = [k for k in range(m) if k == 0 or sizes[k] != sizes[k - 1]] + [m]
    first = np.cumsum([0] + sizes)
    names = {3: "triangle", 4: "quad"}
    cells = [(names.get(sizes[a], "polygon"), np.arange(first[a], first[b], dtype=np.int64).reshape(b - a, sizes[a]))
             for a, b in zip(runs, runs[1:])]
    split = {name: [values[0][a:b] for a, b in zip(runs, runs[1:])] for name, values in cell_data.items()}
    points = np.concatenate(polygons) if m else np.zeros((0, 3))
    return meshio.Mesh(points, cells, cell_data=split)


def write_vtk(model: Any, results: Any, path_prefix: PathLike, *,
              inputs: Iterable[PathLike] = ()) -> Tuple[Path, Any]:
    """Write ``PATH_PREFIX-blocks.vtu`` and ``PATH_PREFIX-interfaces.vtu`` of a 3D wall's analysis (a trailing
    ``.vtu`` of the prefix is dropped; the folder is created if missing); return their paths. Of a time history
    (``Model3D.simulate``), a time series instead: ``PATH_PREFIX-blocks-NNNN.vtu`` per record
    (:func:`history_block_mesh`) and ``PATH_PREFIX.pvd``, the ParaView collection listing them with their times;
    return the ``.pvd`` path and the list of the blocks files."""
    prefix = str(path_prefix)
    for ending in (".vtu", ".pvd"):
        if prefix.endswith(ending):
            prefix = prefix[: -len(ending)]
    if hasattr(results, "times"):  # a time history: no interface forces or states, no interfaces file
        return write_series(prefix, results.times, lambda k: history_block_mesh(model, results, k), list(inputs))
    blocks_path, faces_path = Path(prefix + "-blocks.vtu"), Path(prefix + "-interfaces.vtu")
    meshes = [(blocks_path, block_mesh(model, results)), (faces_path, interface_mesh(model, results))]
    write_meshes(meshes, list(inputs))
    return blocks_path, faces_path
