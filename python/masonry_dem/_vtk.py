"""What the VTK exports of the two dimensions share (:mod:`masonry_dem.export` in the plane,
:mod:`masonry_dem.space.export` in 3D): the codes of the interface families and the writing of meshes as .vtu
files, atomically. Below both exports; meshio is the caller's (a mesh's own ``write``).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, List, Tuple, Union

from .atomic import atomic_path, check_target

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
