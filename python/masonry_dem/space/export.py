"""VTK exports of a 3D wall's analysis (meshio, as the 2D ones of :mod:`masonry_dem.export`), for ParaView:

* ``PREFIX-blocks.vtu``: every block (wall blocks, then the base, the top beam and the supports, as in
  ``Model3D.boxes``) as a hexahedron when every block is a box, else as a polyhedron cell of its own vertices and
  faces (``Model3D.block_vertices``, ``block_faces``; VTK mixes no polyhedra with other cells). Point data: ``mechanism``, the velocity of each corner in the collapse mechanism (v + w x r; the
  largest block translation is 1), and ``displacement`` [m] of each corner (zero for limit analysis), for
  ParaView's *Warp By Vector*. Cell data: ``displacement`` (ux, uy, uz) [m] and ``rotation`` (rx, ry, rz) [rad],
  ``mechanism`` (vx, vy, vz) and ``mechanism_rotation`` (wx, wy, wz) of the block, ``motion`` (its largest vertex
  motion in the mechanism, over the largest of all blocks: 0 at rest, 1 the most moving), ``kind`` (0 wall block,
  1 base or support, 2 top beam), ``block`` (index).
* ``PREFIX-interfaces.vtu``: every contact as its polygon (``Model3D.interface_polygons``): a quad between boxes,
  a triangle or a polygon of any number of corners between polyhedra, the cells in the contacts' order. Cell data:
  ``normal_force`` N [N] (tension > 0), ``shear_force_t1`` T1 and ``shear_force_t2`` T2 [N], ``torsion`` M_n,
  ``moment_t1`` M_t1 and ``moment_t2`` M_t2 [N m] (block b on block a, in the contact's axes), ``normal`` (a
  3-vector), ``area`` [m2], ``state`` (bit flags: 1 open, 2 sliding, 4 rocking; 0 elastic), ``broken``, ``family``
  (0 bed, 1 head, 2 base, 3 top), ``interface`` (index).

Both files are written atomically; a target that is not a regular file, or one of ``inputs``, is refused with
InputError (:func:`masonry_dem.export.write_vtk` calls :func:`write_vtk` for a 3D model).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Iterable, Tuple, Union

import numpy as np

from .._vtk import FAMILY_CODES, write_meshes
from .report import all_boxes, block_shapes, box_corners, contact_polygons, dof_points, vertex_motion

__all__ = ["block_mesh", "interface_mesh", "write_vtk"]

PathLike = Union[str, "os.PathLike[str]"]


def _rows(values: Any, n: int, width: int) -> np.ndarray:
    """``values`` as an (n, width) float array, or NaN of that shape when it has another size (no result)."""
    a = np.asarray(values, dtype=np.float64)
    return a.reshape(n, width) if a.size == n * width else np.full((n, width), np.nan)


def block_mesh(model: Any, results: Any) -> Any:
    """The blocks of a 3D wall as a :class:`meshio.Mesh` of hexahedra or polyhedra (see the module docstring for the
    fields)."""
    import meshio

    boxes = np.asarray(model.boxes, dtype=np.float64).reshape(-1, 6)
    n = len(boxes)
    centroids = dof_points(model)  # where the blocks' dofs are
    if all_boxes(model):  # hexahedra, their corners in VTK's order
        vertices = list(box_corners(boxes))
        cells: Any = [("hexahedron", np.arange(8 * n, dtype=np.int64).reshape(n, 8))]
    else:  # polyhedra (VTK takes no mix of them with other cells): each block's own vertices and faces
        shapes = block_shapes(model)
        vertices = [v for v, _ in shapes]
        first = np.cumsum([0] + [len(v) for v in vertices])
        cells = [meshio.CellBlock("polyhedron", [[np.asarray(f, dtype=np.int64) + first[i] for f in faces]
                                                 for i, (_, faces) in enumerate(shapes)])]
    owner = np.repeat(np.arange(n), [len(v) for v in vertices])
    points = np.concatenate(vertices) if n else np.zeros((0, 3))
    r = points - centroids[owner]
    disp, mech = _rows(results.displacements, n, 6), _rows(results.mechanism, n, 6)
    point_mech = mech[owner, :3] + np.cross(mech[owner, 3:], r)
    point_disp = disp[owner, :3] + np.cross(disp[owner, 3:], r)
    motion = vertex_motion(model, np.nan_to_num(mech))
    peak = float(motion.max()) if n else 0.0
    kind = np.zeros(n, dtype=np.int32)
    kind[int(model.n_blocks):] = 1  # the base and the supports
    if model.top_index is not None:
        kind[int(model.top_index)] = 2
    cell_data = {
        "displacement": [disp[:, :3].copy()],
        "rotation": [disp[:, 3:].copy()],
        "mechanism": [mech[:, :3].copy()],
        "mechanism_rotation": [mech[:, 3:].copy()],
        "motion": [motion / peak if peak > 0 else motion],
        "kind": [kind],
        "block": [np.arange(n, dtype=np.int32)],
    }
    return meshio.Mesh(points, cells, point_data={"mechanism": point_mech, "displacement": point_disp},
                       cell_data=cell_data)


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


def write_vtk(model: Any, results: Any, path_prefix: PathLike, *, inputs: Iterable[PathLike] = ()) -> Tuple[Path, Path]:
    """Write ``PATH_PREFIX-blocks.vtu`` and ``PATH_PREFIX-interfaces.vtu`` of a 3D wall's analysis (a trailing
    ``.vtu`` of the prefix is dropped; the folder is created if missing); return their paths."""
    prefix = str(path_prefix)
    if prefix.endswith(".vtu"):
        prefix = prefix[: -len(".vtu")]
    blocks_path, faces_path = Path(prefix + "-blocks.vtu"), Path(prefix + "-interfaces.vtu")
    meshes = [(blocks_path, block_mesh(model, results)), (faces_path, interface_mesh(model, results))]
    write_meshes(meshes, list(inputs))
    return blocks_path, faces_path
