"""The user-facing 3D model and generators: :class:`Model3D` and ``running_bond_3d``, ``u_wall``,
``corner_wall``, ``buttressed_wall``, ``cut_openings``, ``barrel_vault``, ``cross_vault``, ``dome`` (the core's, in ``masonry_dem._core``), with a wrong
argument type reported as :class:`masonry_dem.InputError` naming the function and the argument, as
:mod:`masonry_dem._checked` does in 2D.

``Model3D``'s analyses are the core's methods, each wrapped the same way: ``solve_limit`` (limit analysis),
``solve_dynamic`` (the explicit solver's quasi-static pushover, load control) and ``simulate`` (time histories), with
the names and keywords of :class:`masonry_dem.Model`'s (``simulate`` adds ``base_acceleration_y``).

Also what a case of a 3D wall hands the model (:mod:`masonry_dem.space.case` reads it, a
:class:`masonry_dem.case.Case` holds it): :class:`ModelParameters3D`, the core's defaults of its arguments
(:data:`CORE_DEFAULTS_3D`), the methods it takes (:data:`METHODS_3D`) and the words of what it refuses
(:data:`IN_3D`, :data:`LOAD_CONTROL_3D`).
"""

from __future__ import annotations

import inspect
from dataclasses import dataclass, fields
from types import MappingProxyType
from typing import Any, ClassVar, Dict, List, Mapping, Optional, Tuple

import numpy as np

from .. import _core
from .._checked import input_errors, refuse_booleans
from .._core import InputError

__all__ = ["Model3D", "running_bond_3d", "u_wall", "corner_wall", "buttressed_wall", "cut_openings", "barrel_vault",
           "cross_vault", "dome"]

#: The methods of a case that a 3D wall takes: limit analysis and the explicit solver (quasi-static, load control).
METHODS_3D = ("limit", "dynamic")
#: The words of the refusals of a method the 3D model does not take in this version (the static solver).
IN_3D = 'the 3D model takes limit analysis and the explicit solver (method "limit" or "dynamic") in this version'
#: The words of the refusal of displacement control in 3D (the explicit solver's pushover is load-controlled).
LOAD_CONTROL_3D = 'the explicit solver in 3D is load-controlled in this version (analysis.control = "load")'
#: The core's defaults of ``Model3D``'s arguments (``ModelSpec3::default()``), for those a case leaves out.
CORE_DEFAULTS_3D: Mapping[str, Any] = MappingProxyType(dict(_core.DEFAULTS_3D))


def _real_boxes(func: str, boxes: Any, others: bool = False) -> None:
    """Refuse boxes that are booleans or complex numbers (which the core would take as numbers), or none unless
    ``others`` (polyhedra are given)."""
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
    if array.size == 0 and not others:
        raise InputError(f"{func}: no boxes: give at least one box [x0, y0, z0, x1, y1, z1] (or polyhedra)")


running_bond_3d = input_errors(_core.running_bond_3d, "running_bond_3d")
u_wall = input_errors(_core.u_wall, "u_wall")
corner_wall = input_errors(_core.corner_wall, "corner_wall")
buttressed_wall = input_errors(_core.buttressed_wall, "buttressed_wall")
cut_openings = input_errors(_core.cut_openings_3d, "cut_openings")
barrel_vault = input_errors(_core.barrel_vault, "barrel_vault")
cross_vault = input_errors(_core.cross_vault, "cross_vault")
dome = input_errors(_core.dome, "dome")


class Model3D(_core.Model3D):
    __doc__ = _core.Model3D.__doc__
    __module__ = "masonry_dem"

    def __new__(cls, *args: Any, **kwargs: Any) -> "Model3D":
        _real_boxes("Model3D", args[0] if args else kwargs.get("boxes"), kwargs.get("polyhedra") is not None)
        refuse_booleans("Model3D", _MODEL3D_SIGNATURE, args, kwargs)
        return input_errors(_core.Model3D.__new__, "Model3D")(cls, *args, **kwargs)  # type: ignore[no-any-return]

    def __init__(self, *args: Any, **kwargs: Any) -> None:  # built by __new__ (the core's constructor)
        pass


# The constructor's signature as help() and inspect show it: the core's, not (*args, **kwargs).
_MODEL3D_SIGNATURE = inspect.signature(_core.Model3D)
Model3D.__signature__ = _MODEL3D_SIGNATURE  # type: ignore[attr-defined]
for _name in ("solve_limit", "solve_dynamic", "simulate"):
    setattr(Model3D, _name, input_errors(getattr(_core.Model3D, _name), f"Model3D.{_name}"))
del _name


@dataclass(frozen=True, eq=False)
class ModelParameters3D:
    """The 3D wall of a case, as the arguments of :class:`masonry_dem.Model3D`.

    ``boxes`` is an (n, 6) array of boxes [x0, y0, z0, x1, y1, z1] (m; None when the case gives polyhedra only);
    the others are those the case gives, None when it leaves them out (the core's default, :data:`CORE_DEFAULTS_3D`;
    for top: no top beam; for joints: the default law everywhere): density [kg/m3], base, top (the top beam's
    height [m]), joints, gravity [m/s2], live, direction [deg], carried (the loads carried by wall blocks: (block,
    [x, y, z] m, weight N)), polyhedra and supports (convex blocks, free and fixed, each a list of its vertices
    [x, y, z] m: given, or a vault's or a dome's).
    """

    dimension: ClassVar[int] = 3

    boxes: Optional[np.ndarray]
    density: Optional[float] = None
    base: Optional[bool] = None
    top: Optional[float] = None
    joints: Optional[Dict[str, Dict[str, float]]] = None
    gravity: Optional[float] = None
    live: Optional[str] = None
    direction: Optional[float] = None
    carried: Optional[List[Tuple[int, List[float], float]]] = None
    polyhedra: Optional[List[List[List[float]]]] = None
    supports: Optional[List[List[List[float]]]] = None

    def arguments(self) -> Dict[str, Any]:
        """The keyword arguments of ``Model3D``: boxes and the parameters given."""
        values = ((f.name, getattr(self, f.name)) for f in fields(self))
        return {name: value for name, value in values if value is not None}
