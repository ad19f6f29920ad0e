"""3D walls: walls of rigid blocks (axis-aligned boxes and convex polyhedra, z up) joined by dry Mohr-Coulomb
contacts, analysed by limit analysis and the explicit solver (the out-of-plane collapse of a leaf, a facade with its
return walls; their motion in time). The package's 2D side is a wall in the plane (:class:`masonry_dem.Model`); this
one is its counterpart in space, with the same joint laws, the same :class:`masonry_dem.Results` and
:class:`masonry_dem.TimeHistory` (``dimension`` 3: arrays of 6 columns where the plane has 3) and the same case
files, command line and result file.

* :class:`Model3D` (``masonry_dem.Model3D``): the model, from an (n, 6) array of boxes [x0, y0, z0, x1, y1, z1] (m)
  and lists of the vertices of convex polyhedra (``polyhedra``, and fixed ones: ``supports``);
  ``Model3D.solve_limit()`` is its limit analysis, ``Model3D.solve_dynamic()`` the explicit solver's quasi-static
  pushover (load control) and ``Model3D.simulate()`` a time history (initial conditions, base accelerations along
  x, y and z), with the names and keywords of ``Model``'s.
* Generators, each returning an (n, 6) array of boxes [m]: :func:`running_bond_3d` (a single leaf in running bond),
  :func:`u_wall` (a facade with two bonded return walls), :func:`corner_wall` (with one), :func:`buttressed_wall`
  (a wall with buttresses, bonded to it or not), :func:`cut_openings`
  (openings [x0, z0, x1, z1] through a facade); and of convex polyhedra, each returning a dict of ``polyhedra`` and
  ``supports`` (vertex lists [m], ``Model3D(polyhedra=..., supports=...)``): :func:`barrel_vault` (the plane's arch
  extruded along its axis in staggered courses, on abutments or walls), :func:`cross_vault` (two barrels crossing
  over a square bay, their voussoirs cut at the groins, on four corner supports), :func:`dome` (of meridian and
  parallel joints).
* :mod:`.case`: the case files' 3D tables (``[geometry] boxes``, ``polyhedra``, ``supports``, ``[geometry.leaf]``,
  ``[geometry.u_wall]``, ``[geometry.corner]``, ``[geometry.buttressed_wall]``, ``[geometry.barrel_vault]``,
  ``[geometry.cross_vault]``, ``[geometry.dome]``, ``[top] height``, ``[loads] direction``, ``[ground_motion]
  direction``; docs/case-format.md, "3D walls").
* :mod:`.plot` (matplotlib's mplot3d, imported on first use): :func:`plot_mechanism_3d` (the mechanism or the
  deformed shape), :func:`mechanism_figure`, :func:`plot_contacts_3d` (the contacts by state), :func:`contacts_figure`,
  :func:`plot_mode_3d` and :func:`modes_figure_3d` (the natural modes, ``masonry_dem.plot_modes`` of a 3D model).
* :mod:`.export` (meshio, on first use): :func:`write_vtk` (the blocks as hexahedra, or polyhedra, the contacts as
  their polygons; a time history as a ParaView series).
* :mod:`.report`: :func:`describe_mechanism`, the one-line description of a 3D mechanism.

In this version a 3D wall takes dry joints, and no static (Newton) solver; its explicit pushover is load-controlled,
and its time histories run from Python (``Model3D.simulate``) and from case files ([ground_motion], [time_history];
``masonry-dem simulate``).

>>> import masonry_dem as md
>>> boxes = md.running_bond_3d(2.0, 1.05, 0.1, 0.4, 0.175)   # a 2 m x 1.05 m x 0.1 m leaf
>>> model = md.Model3D(boxes, joints={"default": md.dry_joint(0.7, dilatancy=0.7)}, direction=90)
>>> round(model.solve_limit().collapse_multiplier, 6)         # overturning out of plane: t / H
0.095238
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from .model import (
    Model3D,
    barrel_vault,
    buttressed_wall,
    corner_wall,
    cross_vault,
    cut_openings,
    dome,
    running_bond_3d,
    u_wall,
)

if TYPE_CHECKING:
    from .export import write_vtk
    from .plot import contacts_figure, mechanism_figure, modes_figure_3d, plot_contacts_3d, plot_mechanism_3d, plot_mode_3d
    from .report import describe_mechanism

__all__ = [
    "Model3D",
    "running_bond_3d",
    "u_wall",
    "corner_wall",
    "buttressed_wall",
    "cut_openings",
    "barrel_vault",
    "cross_vault",
    "dome",
    "plot_mechanism_3d",
    "mechanism_figure",
    "plot_contacts_3d",
    "contacts_figure",
    "plot_mode_3d",
    "modes_figure_3d",
    "write_vtk",
    "describe_mechanism",
]

# Where the names of __all__ not imported above live: imported when first asked for (matplotlib and meshio load
# only when a plot or a VTK file is made)
_LAZY = {
    "plot_mechanism_3d": ".plot",
    "mechanism_figure": ".plot",
    "plot_contacts_3d": ".plot",
    "contacts_figure": ".plot",
    "plot_mode_3d": ".plot",
    "modes_figure_3d": ".plot",
    "write_vtk": ".export",
    "describe_mechanism": ".report",
}


def __getattr__(name: str):  # type: ignore[no-untyped-def]
    import importlib

    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name], __name__), name)
        globals()[name] = value
        return value
    if name in ("case", "export", "model", "plot", "report"):
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'masonry_dem.space' has no attribute {name!r}")
