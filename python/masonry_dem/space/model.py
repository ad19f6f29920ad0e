"""The user-facing 3D model and generators: :class:`Model3D` and ``running_bond_3d``, ``u_wall``,
``corner_wall``, ``cut_openings`` (the core's, in ``masonry_dem._core``), with a wrong argument type reported as
:class:`masonry_dem.InputError` naming the function and the argument, as :mod:`masonry_dem._checked` does in 2D.
"""

from __future__ import annotations

import inspect
from typing import Any

import numpy as np

from .. import _core
from .._checked import input_errors
from .._core import InputError

__all__ = ["Model3D", "running_bond_3d", "u_wall", "corner_wall", "cut_openings"]


def _real_boxes(func: str, boxes: Any) -> None:
    """Refuse boxes that are booleans or complex numbers (which the core would take as numbers), or none."""
    if boxes is None:
        return
    try:
        array = np.asarray(boxes)
    except (ValueError, TypeError):  # ragged rows: the core says which
        return
    if array.dtype.kind in "bc":
        raise InputError(f"{func}: boxes must be real numbers [m], got an array of {array.dtype}")
    if array.dtype == object and any(isinstance(x, (bool, np.bool_, complex, np.complexfloating)) for x in array.ravel()):
        raise InputError(f"{func}: boxes must be real numbers [m], got booleans or complex numbers")
    if array.size == 0:
        raise InputError(f"{func}: no boxes: give at least one box [x0, y0, z0, x1, y1, z1]")


running_bond_3d = input_errors(_core.running_bond_3d, "running_bond_3d")
u_wall = input_errors(_core.u_wall, "u_wall")
corner_wall = input_errors(_core.corner_wall, "corner_wall")
cut_openings = input_errors(_core.cut_openings_3d, "cut_openings")


class Model3D(_core.Model3D):
    __doc__ = _core.Model3D.__doc__
    __module__ = "masonry_dem"

    def __new__(cls, *args: Any, **kwargs: Any) -> "Model3D":
        _real_boxes("Model3D", args[0] if args else kwargs.get("boxes"))
        return input_errors(_core.Model3D.__new__, "Model3D")(cls, *args, **kwargs)  # type: ignore[no-any-return]

    def __init__(self, *args: Any, **kwargs: Any) -> None:  # built by __new__ (the core's constructor)
        pass


# The constructor's signature as help() and inspect show it: the core's, not (*args, **kwargs).
Model3D.__signature__ = inspect.signature(_core.Model3D)  # type: ignore[attr-defined]
Model3D.solve_limit = input_errors(_core.Model3D.solve_limit, "Model3D.solve_limit")  # type: ignore[method-assign]
