"""What the VTK exports of the two dimensions share (:mod:`masonry_dem.export` in the plane,
:mod:`masonry_dem.space.export` in 3D): the codes of the interface families, the writing of meshes as .vtu files,
atomically, and of a time series of them with its ParaView collection (.pvd). Below both exports; meshio is the
caller's (a mesh's own ``write``).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Callable, List, Optional, Tuple, Union

import numpy as np

from .atomic import atomic_file, atomic_path, check_target

PathLike = Union[str, "os.PathLike[str]"]

#: Codes of the interface families in the ``family`` field.
FAMILY_CODES = {"bed": 0, "head": 1, "base": 2, "top": 3}


def write_meshes(meshes: List[Tuple[Path, Any]], inputs: List[PathLike]) -> None:
    """Write each (path, mesh) as .vtu, atomically, after checking every target (the folders created)."""
    for path, _ in meshes:
        check_target(path, inputs)
    for path, mesh in meshes:
        path.parent.mkdir(parents=True, exist_ok=True)
        atomic_path(path, lambda tmp, mesh=mesh: mesh.write(tmp, file_format="vtu"), inputs=inputs)


def write_series(prefix: str, times: Any, mesh_of: Callable[[int], Any],
                 inputs: List[PathLike], contacts_of: Optional[Callable[[int], Any]] = None) -> Tuple[Path, List[Path]]:
    """A time series for ParaView: ``PREFIX-blocks-NNNN.vtu``, the mesh ``mesh_of(k)`` of each record k (numbered
    from 0, at least four digits), and ``PREFIX.pvd``, the collection listing them with their ``times`` [s]; with
    ``contacts_of``, ``PREFIX-contacts-NNNN.vtu`` too, each record's contacts, listed as the collection's part 1
    (the blocks are part 0). Every target checked first, each file written atomically. Returns the ``.pvd`` path
    and the blocks files' paths."""
    times = np.asarray(times, dtype=np.float64).reshape(-1)
    digits = max(4, len(str(len(times) - 1)))
    paths = [Path(f"{prefix}-blocks-{k:0{digits}d}.vtu") for k in range(len(times))]
    contact_paths = [Path(f"{prefix}-contacts-{k:0{digits}d}.vtu") for k in range(len(times))] if contacts_of else []
    pvd_path = Path(prefix + ".pvd")
    check_target(pvd_path, inputs)
    meshes = [(p, mesh_of(k)) for k, p in enumerate(paths)]
    if contacts_of is not None:
        meshes += [(p, contacts_of(k)) for k, p in enumerate(contact_paths)]
    write_meshes(meshes, inputs)
    lines = ['<?xml version="1.0"?>', '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">',
             "  <Collection>"]
    for part, files in enumerate((paths, contact_paths)):
        for t, p in zip(times, files):
            lines.append(f'    <DataSet timestep="{t:.17g}" group="" part="{part}" file="{_xml_attribute(p.name)}"/>')
    lines += ["  </Collection>", "</VTKFile>"]
    pvd_path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_file(pvd_path, "w", encoding="utf-8", newline="\n", inputs=inputs) as f:
        f.write("\n".join(lines) + "\n")
    return pvd_path, paths


def _xml_attribute(text: str) -> str:
    """``text`` as the value of a double-quoted XML attribute (``xml.sax.saxutils.escape`` with the quote:
    that module imports urllib and the email package, a tenth of a second at ``import masonry_dem``)."""
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")
