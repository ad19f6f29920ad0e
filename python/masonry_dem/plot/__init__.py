"""Plots of an analysis: the wall, its deformed shape, crack pattern and collapse mechanism, and the load curve.

Panels, each drawn on a matplotlib ``Axes`` given by the caller:

* :func:`plot_wall` (ax, model): the block outlines; the base hatched, the top beam grey.
* :func:`plot_deformed` (ax, model, results, scale=None): the blocks at the last converged step
  (``Results.displacements``), magnified by ``scale`` (default: the largest displacement drawn as 5% of
  the wall height; the factor is in the panel title), over the dashed undeformed outlines.
* :func:`plot_cracks` (ax, model, results): the interfaces coloured by state at the last converged step
  (open, sliding, rocking, sliding + rocking, elastic; :data:`STATE_STYLES`) with a legend; wide where
  the mechanism cracks them.
* :func:`plot_mechanism` (ax, model, results): the blocks moved along ``Results.mechanism`` (the last
  increment, exaggerated), the moving ones orange, the cracked interfaces black.
* :func:`plot_thrust` (ax, model, results): the line of thrust, each joint's centre of pressure joined along the
  chains of blocks of an arch or a pier (:mod:`masonry_dem.thrust`), over the undeformed wall.
* :func:`plot_curve` (ax, *results, labels=None): load multiplier lambda (or the top-beam force in kN)
  against the horizontal displacement of the control point [mm]; several results overlaid. A limit
  analysis (method "limit") has no curve: its multiplier is drawn as a horizontal line.
* :func:`plot_response` (ax, model, history, quantity="displacement", mark=None, motion=None): a time
  history's (``Model.simulate``) response against time [s]: the control block's horizontal displacement
  [mm] or rotation [rad], the drift [%] (its displacement over the wall height), the base shear [kN] or the
  ground acceleration [m/s²]; displacements relative to the ground (the frame of the base), from the
  undeformed wall.
* :func:`plot_energy` (history, ax=None): a time history's energy balance [J] against time: the energy
  dissipated by friction, damping and impacts, the elastic and the kinetic energy stacked, the external work
  over them, and the balance error.

Figures (written as PNG with the Agg canvas when a ``path`` is given, else made through pyplot):

* :func:`report_figure`: one page with the crack pattern, the mechanism, the deformed shape and the curve
  (``masonry-dem run --plot``); of a :class:`masonry_dem.TimeHistory`, :func:`history_figure`.
* :func:`history_figure`: a time history's response: the control block's displacement and rotation against
  time (or other quantities of :func:`plot_response`), and the deformed wall at the record of the largest
  displacement.
* :func:`response_figure`: the response to a ground motion (``masonry-dem simulate --plot``): rotation, drift,
  base shear and the ground acceleration against time, and the deformed wall (the mechanism) at the largest
  drift. :func:`energy_figure`: the energy balance on its own.
* :func:`write_animation` (model, history, path): the blocks moving over time, as a GIF (Pillow) or an MP4
  (ffmpeg), with the drift against time under them (:mod:`.animation`).
* :func:`plot_results`: the wall (mechanism and joint states in one panel) and the curve.
* :func:`plot_comparison`: the static and the explicit (dynamic) analyses of one case side by side, and
  optionally its limit analysis: the walls with their crack patterns, and the curves overlaid, the limit
  multiplier as a horizontal line (``masonry-dem compare --plot``).

A limit analysis's result has a mechanism (the collapse velocities) and a crack pattern (the joint states of
that mechanism) but no load path: no curve, no deformed shape (its panels say so instead of drawing one).

A figure's file is :func:`figure_path` of the ``path`` given (".png" added when it has no suffix, as matplotlib
does), written atomically (:mod:`masonry_dem.atomic`) by :func:`save_figure`.

The panels are in :mod:`.panels` (:mod:`.time_panels` those of a time history), the figures in :mod:`.figures`,
what every figure shares (of both dimensions: the 3D ones are :mod:`masonry_dem.space.plot`'s) in :mod:`.canvas`,
the figure of the modes in :mod:`.modes`. Geometry in m; displacements plotted in mm. Matplotlib is imported with
the first of these names used (the package imports its modules on first use, :mod:`masonry_dem._lazy`).
"""

from typing import TYPE_CHECKING

from .._lazy import lazy_package

if TYPE_CHECKING:  # what the names below resolve to (type checkers, IDEs); imported on first use at run time
    from ..report import interface_categories
    from .animation import write_animation
    from .canvas import figure_path, save_figure
    from .figures import (
        RESPONSE_PANELS as RESPONSE_PANELS,
        energy_figure,
        history_figure,
        plot_comparison,
        plot_results,
        report_figure,
        response_figure,
    )
    from .panels import (
        DEFORMED_FRACTION as DEFORMED_FRACTION,
        EXTRA_STYLES as EXTRA_STYLES,
        MECHANISM_FRACTION as MECHANISM_FRACTION,
        METHOD_STYLES as METHOD_STYLES,
        STATE_STYLES,
        plot_cracks,
        plot_curve,
        plot_deformed,
        plot_mechanism,
        plot_thrust,
        plot_wall,
    )
    from .time_panels import plot_energy, plot_response

__all__ = [
    "plot_wall",
    "plot_deformed",
    "plot_cracks",
    "plot_mechanism",
    "plot_thrust",
    "plot_curve",
    "plot_response",
    "plot_energy",
    "report_figure",
    "history_figure",
    "response_figure",
    "energy_figure",
    "write_animation",
    "plot_results",
    "plot_comparison",
    "figure_path",
    "save_figure",
    "interface_categories",
    "STATE_STYLES",
]

# Where each name lives, imported when first asked for (see masonry_dem._lazy): matplotlib loads with the first
# figure or panel, and a module of this package (canvas, for the 3D figures of masonry_dem.space.plot) is imported
# without the others.
_LAZY = {
    "interface_categories": "..report",
    "write_animation": ".animation",
    **dict.fromkeys(("figure_path", "save_figure"), ".canvas"),
    **dict.fromkeys(("RESPONSE_PANELS", "energy_figure", "history_figure", "plot_comparison", "plot_results",
                     "report_figure", "response_figure"), ".figures"),
    **dict.fromkeys(("DEFORMED_FRACTION", "EXTRA_STYLES", "MECHANISM_FRACTION", "METHOD_STYLES", "STATE_STYLES",
                     "plot_cracks", "plot_curve", "plot_deformed", "plot_mechanism", "plot_thrust", "plot_wall"),
                    ".panels"),
    **dict.fromkeys(("plot_energy", "plot_response"), ".time_panels"),
}

__getattr__, __dir__ = lazy_package(__name__, _LAZY, __all__)
