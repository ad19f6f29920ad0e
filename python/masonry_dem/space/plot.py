"""Plots of a 3D wall's analysis, limit or explicit (matplotlib's mplot3d, imported with this module):

* :func:`plot_mechanism_3d` (ax, model, results, scale=None, field="mechanism"): on a 3D ``Axes``, the blocks moved
  along the collapse mechanism (``Results.mechanism``, rigidly: each block turned exactly about its centroid; or the
  deformed shape, ``field="displacements"``), scaled so that the largest vertex motion is
  :data:`MECHANISM_FRACTION_3D` of the wall's height, each block with its own faces (a box's six, a polyhedron's),
  coloured by how far it moves (relative to the largest), over the faint outlines of the wall at rest; the base and
  the supports grey, the live load's direction an arrow over the wall; equal axes.
* :func:`mechanism_figure` (model, results, title=None, path=None): two views of the mechanism (one across the load,
  one along it) with a colour bar, and a title with the collapse multiplier and the load's direction;
  :func:`report_figure_3d` (model, results, title=None, path=None), the page ``masonry-dem run --plot`` draws for a
  3D case: those two views above, the contacts by state and the load curve below.
* :func:`plot_mode_3d` (ax, model, modes, i): mode ``i`` of :func:`masonry_dem.modes` of a 3D model, its blocks
  moved along the shape as the mechanism's; :func:`modes_figure_3d` (model, modes, index, path=None): a panel per
  mode (``masonry_dem.plot_modes`` of a 3D model).
* :func:`plot_contacts_3d` (ax, model, results): each contact's polygon where it lies at rest, filled by its state
  (open, sliding, rocking: the plane's colours); :func:`contacts_figure` (model, results, title=None, path=None): a
  page of it beside the mechanism (or the deformed shape).

Geometry in m. Without a ``path`` the figure goes through pyplot (for ``plt.show()`` or a notebook); with one it is
written atomically as the 2D figures are (:func:`masonry_dem.plot.save_figure`, of :mod:`masonry_dem.plot.canvas`,
what the figures of both dimensions share).
"""

from __future__ import annotations

import math
import os
from typing import Any, List, Optional, Sequence, Tuple, Union

import numpy as np
from matplotlib import colormaps
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

from .._core import InputError
from ..plot.canvas import _finish, _new_figure
from ..plot.panels import STATE_STYLES, _followed
from ..report import format_multiplier, interface_categories
from .report import block_shapes, contact_polygons, direction_text, moved_vertices, vertex_motion

__all__ = ["MECHANISM_FRACTION_3D", "MOTION_COLORMAP", "plot_mechanism_3d", "mechanism_figure", "plot_contacts_3d",
           "contacts_figure", "report_figure_3d", "plot_mode_3d", "modes_figure_3d"]

#: The largest corner motion of the drawn mechanism, as a fraction of the wall's height.
MECHANISM_FRACTION_3D = 0.15
#: The colour map of the blocks' motion (0: at rest, 1: the largest motion).
MOTION_COLORMAP = "turbo"

# The six faces of a box, as indices of its corners (box_corners' order)
_FACES = ((0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7))
# The twelve edges of a box
_EDGES = ((0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7))


def _mechanism(model: Any, results: Any, field: str = "mechanism") -> Tuple[np.ndarray, np.ndarray, float]:
    """(the mechanism (n_all, 6) (or the displacements, ``field``), each block's vertex motion over the largest
    (n_all,), the largest [per unit mechanism]); zeros when there is none (no collapse)."""
    boxes = np.asarray(model.boxes, dtype=np.float64).reshape(-1, 6)
    mech = np.asarray(getattr(results, field), dtype=np.float64)
    if mech.shape != (len(boxes), 6) or not np.all(np.isfinite(mech)):
        mech = np.zeros((len(boxes), 6))
    motion = vertex_motion(model, mech)
    motion[_fixed(model)] = 0.0
    peak = float(motion.max()) if len(motion) else 0.0
    return mech, (motion / peak if peak > 0 else motion), peak


def _fixed(model: Any) -> List[int]:
    """The blocks that never move: the base and the supports (after the wall's blocks, but the top beam)."""
    n_all = len(np.asarray(model.boxes).reshape(-1, 6))
    return [i for i in range(int(model.n_blocks), n_all) if i != model.top_index]


def _faces(shapes: List[Tuple[np.ndarray, List[List[int]]]], i: int, boxed: bool) -> Sequence[Sequence[int]]:
    """The faces of block i to draw: a box's in this module's order, a polyhedron's own."""
    return _FACES if boxed else shapes[i][1]


def _edges(shapes: List[Tuple[np.ndarray, List[List[int]]]], i: int, boxed: bool) -> Sequence[Tuple[int, int]]:
    """The edges of block i: a box's twelve, a polyhedron's those of its faces, each once."""
    if boxed:
        return _EDGES
    pairs = {tuple(sorted((f[k], f[(k + 1) % len(f)]))) for f in shapes[i][1] for k in range(len(f))}
    return sorted(pairs)  # type: ignore[arg-type]


def _wall_height(boxes: np.ndarray, n_wall: int) -> float:
    wall = boxes[:n_wall]
    return float(wall[:, 5].max() - wall[:, 2].min())


def plot_mechanism_3d(ax: Any, model: Any, results: Any, scale: Optional[float] = None, colorbar: bool = False,
                      field: str = "mechanism", arrow: bool = True) -> Any:
    """Draw the collapse mechanism of a 3D wall on the 3D axes ``ax`` (see the module docstring), each block with
    its own faces (a box's six, a polyhedron's); ``scale``: the factor on the mechanism [m per unit] (default: its
    largest vertex motion drawn as :data:`MECHANISM_FRACTION_3D` of the wall's height). ``field="displacements"``
    draws the deformed shape instead (``Results.displacements``, the explicit solver's last step), on the same
    scale rule. ``arrow``: the live load's arrow (not over a mode shape). Returns the ScalarMappable of the colours
    (for a colour bar; drawn on ``ax``'s figure when ``colorbar``). Raises InputError when ``ax`` is not a 3D axes
    or ``field`` is another."""
    if not hasattr(ax, "add_collection3d"):
        raise InputError(f"plot_mechanism_3d: ax must be a 3D axes (fig.add_subplot(projection=\"3d\")), got "
                         f"{type(ax).__name__}")
    if field not in ("mechanism", "displacements"):
        raise InputError(f'plot_mechanism_3d: field must be "mechanism" or "displacements", got {field!r}')
    boxes = np.asarray(model.boxes, dtype=np.float64).reshape(-1, 6)
    n_wall = int(model.n_blocks)
    mech, rel, peak = _mechanism(model, results, field)
    height = _wall_height(boxes, n_wall)
    if scale is None:
        scale = MECHANISM_FRACTION_3D * height / peak if peak > 0 else 0.0
    fixed = _fixed(model)
    shapes = block_shapes(model)
    boxed = list(getattr(model, "block_is_box", None) or [True] * len(boxes))
    at_rest = [vertices for vertices, _ in shapes]
    moved = moved_vertices(model, mech, scale)

    # the wall at rest: its blocks' edges, faint
    edges = [at_rest[i][[p, q]] for i in range(len(boxes)) if i not in fixed for p, q in _edges(shapes, i, boxed[i])]
    ax.add_collection3d(Line3DCollection(edges, colors="#9a9a9a", linewidths=0.35, alpha=0.55))
    # the base and the supports: grey, they do not move; supports (any shape, beside the blocks they carry) are drawn
    # first and the blocks over them, as mplot3d's depth order of whole collections may not
    if any(i != model.base_index for i in fixed):
        ax.computed_zorder = False
    if fixed:
        slab = [at_rest[i][list(f)] for i in fixed for f in _faces(shapes, i, boxed[i])]
        ax.add_collection3d(Poly3DCollection(slab, facecolors="#d9d9d9", edgecolors="#a0a0a0", linewidths=0.4,
                                             alpha=0.6))
    # the blocks moved along the mechanism, coloured by their motion
    cmap, norm = colormaps[MOTION_COLORMAP], Normalize(0.0, 1.0)
    faces, colours = [], []
    for i in range(len(boxes)):
        if i in fixed:
            continue
        colour = cmap(norm(rel[i])) if peak > 0 else (0.82, 0.82, 0.82, 1.0)
        for f in _faces(shapes, i, boxed[i]):
            faces.append(moved[i][list(f)])
            colours.append(colour)
    ax.add_collection3d(Poly3DCollection(faces, facecolors=colours, edgecolors="#202020", linewidths=0.3,
                                         alpha=0.95))
    # the live load's direction: an arrow over the wall
    direction = getattr(model, "direction", None) if arrow else None
    everything = np.concatenate(at_rest + moved)
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


def _mechanism_views(fig: Any, cells: Sequence[Any], model: Any, results: Any) -> Tuple[List[Any], Any]:
    """The mechanism (:func:`plot_mechanism_3d`) seen from two sides in ``cells`` of ``fig``: obliquely from the side
    the load comes from, and in profile across the load (without perspective). Returns the axes and the
    ScalarMappable of the colours."""
    direction = getattr(model, "direction", None)
    d = 0.0 if direction is None else float(direction)
    views = ((22.0, d - 130.0, "seen from the side the load comes from"),
             (0.0, d - 90.0, "profile, seen across the load (no perspective)"))
    mappable = None
    axes = []
    for k, (elev, azim, label) in enumerate(views):
        ax = fig.add_subplot(cells[k], projection="3d")
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
    return axes, mappable


def _motion_colorbar(fig: Any, model: Any, results: Any, axes: List[Any], mappable: Any) -> float:
    """The colour bar of the blocks' motion under ``axes`` when there is a mechanism; returns its largest motion."""
    _, _, peak = _mechanism(model, results)
    if peak > 0:
        fig.colorbar(mappable, ax=axes, shrink=0.55, location="bottom", aspect=40,
                     label="block motion in the mechanism, over the largest (the drawing is exaggerated: the largest "
                           f"is drawn as {MECHANISM_FRACTION_3D:.0%} of the wall's height)")
    return peak


def _heading(model: Any, results: Any, peak: float) -> str:
    """The method, the status, the collapse multiplier and the load's direction (and "no mechanism drawn")."""
    direction = getattr(model, "direction", None)
    status = str(results.status)
    if status == "estimate":
        lam = "~" + format_multiplier(float(results.last_equilibrium)) + " (estimate, neither bound)"
    else:
        lam = format_multiplier(float(results.collapse_multiplier), symbol=True)
    load = f"load towards {direction_text(direction)}" if direction is not None else "no live load"
    heading = f"{results.method}, {status}, {lam}, {load}"
    if peak <= 0:
        heading += " — no mechanism drawn"
    return heading


def mechanism_figure(
    model: Any,
    results: Any,
    title: Optional[str] = None,
    path: Optional[Union[str, "os.PathLike[str]"]] = None,
    dpi: int = 150,
) -> Figure:
    """The collapse mechanism of a 3D wall's analysis (:func:`plot_mechanism_3d`) seen from two sides, one across
    the live load and one along it, a colour bar of the blocks' motion, and a title with the status, the collapse
    multiplier and the load's direction. Written to ``path`` (a PNG, atomically) when given, else made through
    pyplot. Returns the figure."""
    fig = _new_figure((14.0, 7.5), path is not None)
    grid = fig.add_gridspec(1, 2, width_ratios=[1.6, 1.0])
    axes, mappable = _mechanism_views(fig, [grid[0, 0], grid[0, 1]], model, results)
    peak = _motion_colorbar(fig, model, results, axes, mappable)
    heading = _heading(model, results, peak)
    return _finish(fig, f"{title} — {heading}" if title else heading, path, dpi)


def report_figure_3d(
    model: Any,
    results: Any,
    title: Optional[str] = None,
    path: Optional[Union[str, "os.PathLike[str]"]] = None,
    dpi: int = 150,
) -> Figure:
    """The page ``masonry-dem run --plot`` draws for a 3D case (``masonry_dem.plot.report_figure`` of a
    :class:`masonry_dem.Model3D`), the plane's report where it has a meaning in 3D: above, the collapse mechanism
    seen from two sides (:func:`mechanism_figure`'s views, with their colour bar); below, the contacts by state at
    rest (:func:`plot_contacts_3d`, the plane's crack pattern) with the count of each state, and the load curve
    (the plane's :func:`masonry_dem.plot.plot_curve`: the explicit pushover's path of the control block, the
    highest wall block, along x or y; limit analysis's multiplier alone, or, along its mechanism
    (``follow_mechanism``), lambda on the moved geometry against the control block's displacement along the live
    load's direction). The mechanism's views are the collapse mechanism's, also when it was followed. A title with
    the status, the collapse multiplier and the load's direction. Written to ``path`` (a PNG, atomically) when given,
    else made through pyplot. Returns the figure."""
    from ..plot.panels import plot_curve

    fig = _new_figure((14.0, 13.5), path is not None)
    grid = fig.add_gridspec(2, 2, width_ratios=[1.4, 1.0], height_ratios=[1.0, 0.9])
    axes, mappable = _mechanism_views(fig, [grid[0, 0], grid[0, 1]], model, results)
    peak = _motion_colorbar(fig, model, results, axes, mappable)
    direction = getattr(model, "direction", None)
    _contacts_panel(fig, grid[1, 0], model, results)
    curve = fig.add_subplot(grid[1, 1])
    plot_curve(curve, results)
    if _followed(results):  # along the live load's direction in plan
        axis = f"the load, towards {direction_text(direction)}"
    else:
        axis = "y" if direction is not None and abs(math.sin(math.radians(direction))) > abs(math.cos(math.radians(direction))) else "x"
    curve.set_xlabel(f"displacement of the control block along {axis} [mm]")
    curve.set_box_aspect(0.8)
    heading = _heading(model, results, peak)
    return _finish(fig, f"{title} — {heading}" if title else heading, path, dpi)


def plot_contacts_3d(ax: Any, model: Any, results: Any) -> dict:
    """Draw the contacts of a 3D wall on the 3D axes ``ax``, each its own polygon (a rectangle between boxes, any
    convex polygon between polyhedra) where it lies at rest, filled by its state in ``results.interface_states``
    (the colours of the plane's figures, :data:`masonry_dem.plot.panels.STATE_STYLES`: open, sliding, rocking,
    sliding + rocking; the elastic ones faint), among the faint edges of the blocks. Returns the count of each
    state. Raises InputError when ``ax`` is not a 3D axes."""
    if not hasattr(ax, "add_collection3d"):
        raise InputError(f"plot_contacts_3d: ax must be a 3D axes (fig.add_subplot(projection=\"3d\")), got "
                         f"{type(ax).__name__}")
    boxes = np.asarray(model.boxes, dtype=np.float64).reshape(-1, 6)
    shapes = block_shapes(model)
    boxed = list(getattr(model, "block_is_box", None) or [True] * len(boxes))
    fixed = _fixed(model)
    edges = [shapes[i][0][[p, q]] for i in range(len(boxes)) if i not in fixed for p, q in _edges(shapes, i, boxed[i])]
    ax.add_collection3d(Line3DCollection(edges, colors="#9a9a9a", linewidths=0.35, alpha=0.5))
    polygons = contact_polygons(model)
    states = np.asarray(results.interface_states, dtype=np.int64).reshape(-1)
    categories = interface_categories(states) if len(states) == len(polygons) else ["elastic"] * len(polygons)
    counts = {}
    for name, colour, _ in STATE_STYLES:
        chosen = [p for p, c in zip(polygons, categories) if c == name]
        counts[name] = len(chosen)
        if chosen:
            faint = name == "elastic"
            ax.add_collection3d(Poly3DCollection(chosen, facecolors=colour, edgecolors="#303030",
                                                 linewidths=0.2 if faint else 0.5, alpha=0.15 if faint else 0.9))
    points = np.concatenate([v for v, _ in shapes] + polygons) if polygons else boxes.reshape(-1, 3)
    _equal_axes(ax, points.min(axis=0), points.max(axis=0))
    from matplotlib.ticker import MaxNLocator

    for axis, label in ((ax.xaxis, "x"), (ax.yaxis, "y"), (ax.zaxis, "z")):
        axis.set_major_locator(MaxNLocator(nbins=4))
        axis.set_label_text(f"{label} [m]")
    return counts


def _contacts_panel(fig: Any, cell: Any, model: Any, results: Any) -> Any:
    """The contacts by state at rest (:func:`plot_contacts_3d`) on a 3D axes of ``fig`` at ``cell`` (a subplot spec,
    or the (rows, columns, index) of ``add_subplot``), seen from the side the load comes from, with a legend of
    the states and their counts. Returns the axes."""
    from matplotlib.patches import Patch

    direction = getattr(model, "direction", None)
    ax = fig.add_subplot(*(cell if isinstance(cell, tuple) else (cell,)), projection="3d")
    ax.view_init(elev=22.0, azim=(0.0 if direction is None else float(direction)) - 130.0)
    counts = plot_contacts_3d(ax, model, results)
    ax.set_title("contacts by state, at rest", fontsize=10)
    handles = [Patch(facecolor=colour, edgecolor="#303030", alpha=0.15 if name == "elastic" else 0.9,
                     label=f"{name} ({counts[name]})") for name, colour, _ in STATE_STYLES]
    ax.legend(handles=handles, loc="upper left", fontsize=8, frameon=False)
    return ax


def contacts_figure(
    model: Any,
    results: Any,
    title: Optional[str] = None,
    path: Optional[Union[str, "os.PathLike[str]"]] = None,
    dpi: int = 150,
) -> Figure:
    """A page of a 3D wall's analysis beside :func:`mechanism_figure`: its contacts by state
    (:func:`plot_contacts_3d`), seen from the side the load comes from, and the blocks moved along the mechanism (or
    the explicit solver's deformed shape, when it has no mechanism) from above; a legend of the states with their
    counts. Written to ``path`` (a PNG, atomically) when given, else made through pyplot. Returns the figure."""
    fig = _new_figure((14.0, 7.0), path is not None)
    direction = getattr(model, "direction", None)
    d = 0.0 if direction is None else float(direction)
    _contacts_panel(fig, (1, 2, 1), model, results)
    _, _, peak = _mechanism(model, results)
    field = "mechanism" if peak > 0 else "displacements"
    other = fig.add_subplot(1, 2, 2, projection="3d")
    other.view_init(elev=35.0, azim=d - 60.0)
    plot_mechanism_3d(other, model, results, field=field, colorbar=True)
    other.set_title("the mechanism" if field == "mechanism" else "the deformed shape (exaggerated)", fontsize=10)
    heading = f"{results.method}, {results.status}, contacts of {model.n_blocks} blocks"
    return _finish(fig, f"{title} — {heading}" if title else heading, path, dpi)


def plot_mode_3d(ax: Any, model: Any, modes: Any, i: int, scale: Optional[float] = None) -> Any:
    """Draw mode ``i`` of ``modes`` (:func:`masonry_dem.modes` of the 3D ``model``) on the 3D axes ``ax``: the blocks
    moved along its mass-normalized shape (:func:`plot_mechanism_3d`'s drawing, coloured by their motion over the
    largest, without the live load's arrow), scaled so that the largest vertex motion is
    :data:`MECHANISM_FRACTION_3D` of the wall's height unless ``scale`` is given; a title with the frequency, the
    period and the effective masses along x, y and z (fractions of the free mass). Returns the ScalarMappable."""
    from types import SimpleNamespace

    shape = np.asarray(modes.shapes[i], dtype=np.float64)
    mappable = plot_mechanism_3d(ax, model, SimpleNamespace(mechanism=shape), scale=scale, arrow=False)
    f = float(modes.frequencies_hz[i])
    free = np.asarray(modes.free_mass, dtype=np.float64)
    share = np.divide(np.asarray(modes.effective_mass[i], dtype=np.float64), free, out=np.zeros(len(free)),
                      where=free > 0)
    period = f"T = {1.0 / f:.4g} s" if f > 0 else "rigid-body mode"
    masses = ", ".join(f"{axis} {s:.1%}" for axis, s in zip("xyz", share))
    ax.set_title(f"mode {i + 1}: f = {f:.4g} Hz, {period}\neffective mass {masses}", fontsize=10)
    return mappable


def modes_figure_3d(
    model: Any,
    modes: Any,
    index: Sequence[int],
    scale: Optional[float] = None,
    path: Optional[Union[str, "os.PathLike[str]"]] = None,
    dpi: int = 150,
) -> Figure:
    """The modes ``index`` of a 3D model (:func:`masonry_dem.plot_modes` of a :class:`masonry_dem.Model3D`): a 3D
    panel per mode (:func:`plot_mode_3d`), two to a row, with a colour bar of the blocks' motion. Written to
    ``path`` (a PNG, atomically) when given, else made through pyplot. Returns the figure."""
    columns = min(len(index), 2)
    rows = math.ceil(len(index) / columns)
    fig = _new_figure((7.0 * columns + 0.4, 6.0 * rows + 1.0), path is not None)
    direction = getattr(model, "direction", None)
    d = 0.0 if direction is None else float(direction)
    axes, mappable = [], None
    for n, i in enumerate(index):
        ax = fig.add_subplot(rows, columns, n + 1, projection="3d")
        ax.view_init(elev=22.0, azim=d - 130.0)
        mappable = plot_mode_3d(ax, model, modes, i, scale)
        axes.append(ax)
    fig.colorbar(mappable, ax=axes, shrink=0.55, location="bottom", aspect=40,
                 label="block motion in the mode, over the largest (the drawing is exaggerated: the largest is drawn "
                       f"as {MECHANISM_FRACTION_3D:.0%} of the wall's height)")
    walls = int(model.n_blocks)
    heading = f"Natural modes of {walls} block{'s' if walls != 1 else ''} in 3D (elastic joints; shapes magnified)"
    return _finish(fig, heading, path, dpi)
