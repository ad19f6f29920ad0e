"""Plots of a 3D wall's analysis, limit or explicit (matplotlib's mplot3d, imported with this module):

* :func:`plot_mechanism_3d` (ax, model, results, scale=None): on a 3D ``Axes``, the blocks moved along the
  collapse mechanism (``Results.mechanism``, rigidly: each box turned exactly about its centroid), scaled so that
  the largest corner motion is :data:`MECHANISM_FRACTION_3D` of the wall's height, their faces coloured by how far
  each block moves (relative to the largest), over the faint outlines of the wall at rest; the base a grey slab,
  the live load's direction an arrow over the wall; equal axes.
* :func:`mechanism_figure` (model, results, title=None, path=None): the page ``masonry-dem run --plot`` draws for a
  3D case: two views of the mechanism (one across the load, one along it) with a colour bar, and a title with the
  collapse multiplier and the load's direction.

Geometry in m. Without a ``path`` the figure goes through pyplot (for ``plt.show()`` or a notebook); with one it is
written atomically as the 2D figures are (:func:`masonry_dem.plot.save_figure`, of :mod:`masonry_dem.plot.canvas`,
what the figures of both dimensions share).
"""

from __future__ import annotations

import math
import os
from typing import Any, Optional, Tuple, Union

import numpy as np
from matplotlib import colormaps
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

from .._core import InputError
from ..plot.canvas import _finish, _new_figure
from ..report import format_multiplier
from .report import box_corners, corner_motion, direction_text, dof_points, moved_corners

__all__ = ["MECHANISM_FRACTION_3D", "MOTION_COLORMAP", "plot_mechanism_3d", "mechanism_figure"]

#: The largest corner motion of the drawn mechanism, as a fraction of the wall's height.
MECHANISM_FRACTION_3D = 0.15
#: The colour map of the blocks' motion (0: at rest, 1: the largest motion).
MOTION_COLORMAP = "turbo"

# The six faces of a box, as indices of its corners (box_corners' order)
_FACES = ((0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7))
# The twelve edges of a box
_EDGES = ((0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7))


def _mechanism(model: Any, results: Any) -> Tuple[np.ndarray, np.ndarray, float]:
    """(the mechanism (n_all, 6), each block's corner motion over the largest (n_all,), the largest [per unit
    mechanism]); zeros when there is none (no collapse)."""
    boxes = np.asarray(model.boxes, dtype=np.float64).reshape(-1, 6)
    mech = np.asarray(results.mechanism, dtype=np.float64)
    if mech.shape != (len(boxes), 6) or not np.all(np.isfinite(mech)):
        mech = np.zeros((len(boxes), 6))
    motion = corner_motion(boxes, mech, dof_points(model))
    base = model.base_index
    if base is not None:
        motion[int(base)] = 0.0
    peak = float(motion.max()) if len(motion) else 0.0
    return mech, (motion / peak if peak > 0 else motion), peak


def _wall_height(boxes: np.ndarray, n_wall: int) -> float:
    wall = boxes[:n_wall]
    return float(wall[:, 5].max() - wall[:, 2].min())


def plot_mechanism_3d(ax: Any, model: Any, results: Any, scale: Optional[float] = None, colorbar: bool = False) -> Any:
    """Draw the collapse mechanism of a 3D wall on the 3D axes ``ax`` (see the module docstring); ``scale``: the
    factor on the mechanism [m per unit] (default: its largest corner motion drawn as
    :data:`MECHANISM_FRACTION_3D` of the wall's height). Returns the ScalarMappable of the colours (for a colour
    bar; drawn on ``ax``'s figure when ``colorbar``). Raises InputError when ``ax`` is not a 3D axes."""
    if not hasattr(ax, "add_collection3d"):
        raise InputError(f"plot_mechanism_3d: ax must be a 3D axes (fig.add_subplot(projection=\"3d\")), got "
                         f"{type(ax).__name__}")
    boxes = np.asarray(model.boxes, dtype=np.float64).reshape(-1, 6)
    n_wall = int(model.n_blocks)
    mech, rel, peak = _mechanism(model, results)
    height = _wall_height(boxes, n_wall)
    if scale is None:
        scale = MECHANISM_FRACTION_3D * height / peak if peak > 0 else 0.0
    base = None if model.base_index is None else int(model.base_index)
    at_rest = box_corners(boxes)
    moved = moved_corners(boxes, mech, scale, dof_points(model))

    # the wall at rest: its blocks' edges, faint
    edges = [at_rest[i][[p, q]] for i in range(len(boxes)) if i != base for p, q in _EDGES]
    ax.add_collection3d(Line3DCollection(edges, colors="#9a9a9a", linewidths=0.35, alpha=0.55))
    # the base: a grey slab that does not move
    if base is not None:
        slab = [at_rest[base][list(f)] for f in _FACES]
        ax.add_collection3d(Poly3DCollection(slab, facecolors="#d9d9d9", edgecolors="#a0a0a0", linewidths=0.4,
                                             alpha=0.6))
    # the blocks moved along the mechanism, coloured by their motion
    cmap, norm = colormaps[MOTION_COLORMAP], Normalize(0.0, 1.0)
    faces, colours = [], []
    for i in range(len(boxes)):
        if i == base:
            continue
        colour = cmap(norm(rel[i])) if peak > 0 else (0.82, 0.82, 0.82, 1.0)
        for f in _FACES:
            faces.append(moved[i][list(f)])
            colours.append(colour)
    ax.add_collection3d(Poly3DCollection(faces, facecolors=colours, edgecolors="#202020", linewidths=0.3,
                                         alpha=0.95))
    # the live load's direction: an arrow over the wall
    direction = getattr(model, "direction", None)
    everything = np.concatenate([at_rest.reshape(-1, 3), moved.reshape(-1, 3)])
    lo, hi = everything.min(axis=0), everything.max(axis=0)
    if direction is not None:
        d = math.radians(direction)
        span = 0.3 * float(max(hi[0] - lo[0], hi[1] - lo[1], height))
        u = np.array([math.cos(d), math.sin(d), 0.0]) * span
        wall_lo, wall_hi = boxes[:n_wall, :3].min(axis=0), boxes[:n_wall, 3:].max(axis=0)
        start = np.array([0.5 * (wall_lo[0] + wall_hi[0]), 0.5 * (wall_lo[1] + wall_hi[1]), wall_hi[2] + 0.12 * height])
        start = start - 0.5 * u
        ax.quiver(*start, *u, color="#c0392b", linewidth=2.0, arrow_length_ratio=0.25)
        ax.text(*(start + u + 0.03 * span * np.array([0, 0, 1])), "λW", color="#c0392b", fontsize=10)
        lo, hi = np.minimum(lo, start + np.minimum(0, u)), np.maximum(hi, start + np.maximum(0, u) + [0, 0, 0.1 * height])
    _equal_axes(ax, lo, hi)
    from matplotlib.ticker import MaxNLocator

    for axis, name in ((ax.xaxis, "x"), (ax.yaxis, "y"), (ax.zaxis, "z")):
        axis.set_major_locator(MaxNLocator(nbins=4))
        axis.set_label_text(f"{name} [m]")
    mappable = _mappable(cmap, norm)
    if colorbar:
        ax.figure.colorbar(mappable, ax=ax, shrink=0.6, pad=0.1, label="block motion / the largest")
    return mappable


def _mappable(cmap: Any, norm: Normalize) -> Any:
    from matplotlib.cm import ScalarMappable

    mappable = ScalarMappable(norm=norm, cmap=cmap)
    mappable.set_array([])
    return mappable


def _equal_axes(ax: Any, lo: np.ndarray, hi: np.ndarray) -> None:
    """Limits around [lo, hi] with one scale on the three axes."""
    span = np.maximum(hi - lo, 1e-9)
    pad = 0.04 * float(span.max())
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_zlim(lo[2] - pad, hi[2] + pad)
    ax.set_box_aspect(tuple(float(s + 2 * pad) for s in span))


def mechanism_figure(
    model: Any,
    results: Any,
    title: Optional[str] = None,
    path: Optional[Union[str, "os.PathLike[str]"]] = None,
    dpi: int = 150,
) -> Figure:
    """The page of a 3D wall's analysis (``masonry-dem run --plot`` of a 3D case): the collapse mechanism
    (:func:`plot_mechanism_3d`) seen from two sides, one across the live load and one along it, a colour bar of the
    blocks' motion, and a title with the status, the collapse multiplier and the load's direction. Written to
    ``path`` (a PNG, atomically) when given, else made through pyplot. Returns the figure."""
    fig = _new_figure((14.0, 7.5), path is not None)
    grid = fig.add_gridspec(1, 2, width_ratios=[1.6, 1.0])
    direction = getattr(model, "direction", None)
    d = 0.0 if direction is None else float(direction)
    # the first view looks at the wall from the side the load comes from, obliquely; the second across the load,
    # without perspective: the mechanism's profile
    views = ((22.0, d - 130.0, "seen from the side the load comes from"),
             (0.0, d - 90.0, "profile, seen across the load (no perspective)"))
    mappable = None
    axes = []
    for k, (elev, azim, label) in enumerate(views):
        ax = fig.add_subplot(grid[0, k], projection="3d")
        ax.view_init(elev=elev, azim=azim)
        mappable = plot_mechanism_3d(ax, model, results)
        if k == 1:
            ax.set_proj_type("ortho")
            # the axis along the line of sight shows as a point: no ticks on it
            a = math.radians(azim)
            for axis, along in ((ax.xaxis, abs(math.cos(a))), (ax.yaxis, abs(math.sin(a)))):
                if along > 0.95:
                    axis.set_ticks([])
                    axis.set_label_text("")
        ax.set_title(label, fontsize=10)
        axes.append(ax)
    _, _, peak = _mechanism(model, results)
    if peak > 0:
        fig.colorbar(mappable, ax=axes, shrink=0.55, location="bottom", aspect=40,
                     label="block motion in the mechanism, over the largest (the drawing is exaggerated: the largest "
                           f"is drawn as {MECHANISM_FRACTION_3D:.0%} of the wall's height)")
    status = str(results.status)
    if status == "estimate":
        lam = "~" + format_multiplier(float(results.last_equilibrium)) + " (estimate, neither bound)"
    else:
        lam = format_multiplier(float(results.collapse_multiplier), symbol=True)
    load = f"load towards {direction_text(direction)}" if direction is not None else "no live load"
    heading = f"{results.method}, {status}, {lam}, {load}"
    if peak <= 0:
        heading += " — no mechanism drawn"
    return _finish(fig, f"{title} — {heading}" if title else heading, path, dpi)
