"""The figures, made of the panels of :mod:`.panels`: :func:`report_figure` (the one-page report),
:func:`plot_results` and :func:`plot_comparison`; written as PNG with the Agg canvas when a ``path`` is
given (:func:`save_figure`, atomically, to :func:`figure_path`), else made through pyplot.
"""

from __future__ import annotations

import os
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np
from matplotlib.figure import Figure

from ..history import check_plane, default_control_block, is_time_history, peak_record, record
from .._shapes import shapes
from ..report import _plural
from ..response import wall_height
from .canvas import _finish, _new_figure, figure_path as figure_path, save_figure as save_figure
from .panels import (
    DEFORMED_FRACTION,
    plot_wall,
    _draw_curve,
    _draw_curve_overlay,
    _draw_wall,
    _lam_text,
    movement_end,
    plot_movement_curve,
    _state_handles,
    _wall_limits,
    plot_cracks,
    plot_curve,
    plot_deformed,
    plot_mechanism,
)
from .time_panels import plot_energy, plot_response


def plot_results(
    model: Any,
    results: Any,
    title: Optional[str] = None,
    path: Optional[Union[str, "os.PathLike[str]"]] = None,
    live: str = "horizontal_weight",
    dpi: int = 150,
) -> Figure:
    """Draw the wall with its mechanism and joint states, and the load curve; write a PNG if ``path`` is given.

    Args:
        model: the :class:`masonry_dem.Model` analysed.
        results: its :class:`masonry_dem.Results`.
        title: the case title (the figure title adds the status and the collapse multiplier).
        path: output file (PNG); written with the Agg canvas, without touching pyplot's state.
            Without a path the figure is created through pyplot (for ``plt.show()`` or a notebook).
        live: the live load of the model, "horizontal_weight" (lambda dimensionless) or
            "top_horizontal" (lambda is a force in N, plotted in kN).
        dpi: resolution of the PNG.
    Returns:
        The figure.
    """
    fig = _new_figure((13.0, 6.0), path is not None)
    ax_wall, ax_curve = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.45, 1.0]})
    _draw_wall(ax_wall, model, results)
    _draw_curve(ax_curve, results, live)
    return _finish(fig, _with_title(title, _result_heading(results, live)), path, dpi)


def _with_title(title: Optional[str], text: str) -> str:
    """A figure's heading: the case title, if any, then ``text``."""
    return f"{title} — {text}" if title else text


def _result_heading(results: Any, live: str) -> str:
    """The method, the status and the collapse multiplier of a result, for a figure's heading."""
    return f"{results.method}, {results.status}, {_lam_text(results, live)}"


def _aspect(model: Any) -> float:
    """Width over height of the wall panel (:func:`_wall_limits`)."""
    (xl, xh), (yl, yh) = _wall_limits(model)
    return float((xh - xl) / (yh - yl))


def report_figure(
    model: Any,
    results: Any,
    title: Optional[str] = None,
    other: Any = None,
    path: Optional[Union[str, "os.PathLike[str]"]] = None,
    live: str = "horizontal_weight",
    dpi: int = 150,
    thrust: bool = False,
    movement: bool = False,
) -> Figure:
    """A one-page report: the crack pattern, the collapse mechanism, the deformed shape and the load curve;
    of a time history, its response (:func:`history_figure`); of a 3D wall (a :class:`masonry_dem.Model3D`), its
    collapse mechanism in 3D, its contacts by state and its load curve
    (:func:`masonry_dem.space.plot.report_figure_3d`).

    Args:
        model: the :class:`masonry_dem.Model` analysed.
        results: its :class:`masonry_dem.Results` (the wall panels show this one), or a
            :class:`masonry_dem.TimeHistory` (``Model.simulate``; ``other`` and ``live`` are then ignored).
        title: the case title (the figure title adds the method, status and collapse multiplier).
        other: optionally the result of the other method on the same model: its curve is overlaid.
        path: output file (PNG), written with the Agg canvas; without it the figure goes through pyplot.
        live: the live load, "horizontal_weight" or "top_horizontal" (lambda in N, plotted in kN).
        dpi: resolution of the PNG.
        thrust: draw the line of thrust (:func:`masonry_dem.plot.plot_thrust`: each joint's centre of pressure,
            joined along the chains of blocks of an arch or a pier) over the crack pattern, from the forces of
            ``results`` (at collapse, or at the last converged step). A wall in the plane's results only.
        movement: ``results`` are a support's movement's: the curve is the force the wall exerts on the support
            against its movement (:func:`masonry_dem.plot.panels.plot_movement_curve`).
    Returns:
        The figure.
    """
    if is_time_history(results):
        return history_figure(model, results, title=title, path=path, dpi=dpi)
    if int(getattr(model, "dimension", 2)) == 3:  # a 3D wall: its mechanism, contacts and curve in 3D
        from ..space.plot import report_figure_3d

        return report_figure_3d(model, results, title=title, path=path, dpi=dpi)
    aspect = _aspect(model)
    if aspect > 1.1:
        # a wide wall: two rows, the crack pattern and the mechanism above, the deformed shape and the curve
        cell_w = 6.2
        cell_h = float(np.clip(cell_w / min(aspect, 4.0) + 1.1, 3.6, 8.0))
        fig = _new_figure((2 * cell_w + 0.6, 2 * cell_h + 0.8), path is not None)
        grid = fig.add_gridspec(2, 2)
        cells, columns = [grid[0, 0], grid[0, 1], grid[1, 0], grid[1, 1]], 5
    else:
        # a tall wall: the three wall panels and the curve in one row
        a = max(aspect, 0.6)
        fig = _new_figure((16.0, 7.0), path is not None)
        grid = fig.add_gridspec(1, 4, width_ratios=[a, a, a, 1.6])
        cells, columns = [grid[0, 0], grid[0, 1], grid[0, 2], grid[0, 3]], 2
    plot_cracks(fig.add_subplot(cells[0]), model, results, legend_columns=columns, thrust=thrust)
    plot_mechanism(fig.add_subplot(cells[1]), model, results)
    plot_deformed(fig.add_subplot(cells[2]), model, results)
    ax_curve = fig.add_subplot(cells[3])
    if movement:
        plot_movement_curve(ax_curve, results)
        heading = f"{results.method}, {results.status}, falls at a movement of {movement_end(results) * 1e3:.1f} mm"
        return _finish(fig, _with_title(title, heading), path, dpi)
    if other is not None:
        plot_curve(ax_curve, results, other, live=live)
    else:
        plot_curve(ax_curve, results, live=live)
    return _finish(fig, _with_title(title, _result_heading(results, live)), path, dpi)


#: The panels of :func:`response_figure`, top to bottom (quantities of :func:`plot_response`).
RESPONSE_PANELS = ("rotation", "drift", "base_shear", "ground_acceleration")


def history_figure(
    model: Any,
    history: Any,
    title: Optional[str] = None,
    path: Optional[Union[str, "os.PathLike[str]"]] = None,
    dpi: int = 150,
    quantities: Tuple[str, ...] = ("displacement", "rotation"),
    motion: Any = None,
    at: Optional[float] = None,
) -> Figure:
    """The response to a time history (``Model.simulate``): quantities of the response against time, one panel
    each, above one another (by default the horizontal displacement [mm] and the rotation [rad] of the control
    block: the model's default, the top beam, else the highest wall block at the right end), and the deformed
    wall at the record of the largest |displacement| of the control block, i.e. of the largest drift (marked
    on the curves). Displacements are relative to the ground (the frame of the base), from the undeformed wall;
    the wall is drawn at true scale when its largest displacement is at least 5% of its height, else magnified.

    Args:
        model: the :class:`masonry_dem.Model` simulated.
        history: its :class:`masonry_dem.TimeHistory`.
        title: the case title (the figure title adds the status, the steps and the time step).
        path: output file (PNG), written with the Agg canvas; without it the figure goes through pyplot.
        dpi: resolution of the PNG.
        quantities: the panels, quantities of :func:`plot_response` ("displacement", "rotation", "drift",
            "base_shear", "ground_acceleration"), top to bottom.
        motion: the horizontal ground motion (:class:`masonry_dem.ground_motion.GroundMotion`), drawn when the
            history does not carry its ``ground_acceleration``.
        at: draw the wall at the first record at or after this time [s] (e.g. a collapse) instead of the
            largest drift.
    Returns:
        The figure.
    """
    check_plane(model, "the figure of a time history")
    a = float(np.clip(_aspect(model), 0.35, 2.5))
    n = max(1, len(quantities))
    fig = _new_figure((5.0 * a + 7.5, max(6.5, 2.0 * n + 1.0)), path is not None)
    grid = fig.add_gridspec(n, 2, width_ratios=[max(a, 0.6), 1.3])
    ax_wall = fig.add_subplot(grid[:, 0])
    axes = [fig.add_subplot(grid[0, 1])]
    axes += [fig.add_subplot(grid[k, 1], sharex=axes[0]) for k in range(1, n)]
    times = np.asarray(history.times, dtype=np.float64)
    peak = peak_record(model, history)
    which = "largest drift" if "drift" in quantities else "largest control displacement"
    if at is not None and len(times):
        peak = int(min(np.searchsorted(times, float(at)), len(times) - 1))
        which = "the time given"
    if len(times):
        shown = record(history, peak)
        blocks = shapes(model)
        largest = float(blocks.vertex_motion(shown.displacements).max()) if len(blocks) else 0.0
        true_scale = largest >= DEFORMED_FRACTION * wall_height(model)
        plot_deformed(ax_wall, model, shown, scale=1.0 if true_scale else None)
        if true_scale:
            _include_blocks(ax_wall, model, shown.displacements)
        ax_wall.set_title(f"{ax_wall.get_title()}\nat t = {shown.time:.4g} s ({which})", fontsize=10)
    else:
        plot_wall(ax_wall, model)
    for ax, quantity in zip(axes, quantities):
        plot_response(ax, model, history, quantity, mark=peak if len(times) else None, motion=motion)
    for ax in axes[:-1]:
        ax.set_xlabel("")
    axes[0].set_title(f"control block {default_control_block(model)}, relative to the ground", fontsize=10)
    return _finish(fig, _with_title(title, _history_heading(history)), path, dpi)


def _include_blocks(ax: Any, model: Any, disp: np.ndarray) -> None:
    """Widen the limits of a wall panel to take in the blocks moved by ``disp`` at true scale (a block thrown
    off the wall stays in view)."""
    from .animation import moved_extent

    (x_lo, x_hi), (y_lo, y_hi) = moved_extent(model, np.asarray(disp, dtype=np.float64)[None])
    pad = 0.05 * wall_height(model)
    xl, xh = ax.get_xlim()
    yl, yh = ax.get_ylim()
    ax.set_xlim(min(xl, x_lo - pad), max(xh, x_hi + pad))
    ax.set_ylim(min(yl, y_lo - pad), max(yh, y_hi + pad))


def response_figure(
    model: Any,
    history: Any,
    motion: Any = None,
    title: Optional[str] = None,
    path: Optional[Union[str, "os.PathLike[str]"]] = None,
    dpi: int = 150,
    at: Optional[float] = None,
) -> Figure:
    """The response of a wall to a ground motion (``masonry-dem simulate --plot``): :func:`history_figure` with
    the panels of :data:`RESPONSE_PANELS`, the control block's rotation [rad], the drift [%] (its horizontal
    displacement over the wall height), the base shear [kN] and the ground acceleration [m/s²] under them,
    against time [s], and the deformed wall (the mechanism) at the largest drift, or at time ``at`` [s].
    ``motion``: the horizontal :class:`masonry_dem.ground_motion.GroundMotion`, drawn when the history does not
    carry its input. Other arguments as in :func:`history_figure`."""
    return history_figure(model, history, title=title, path=path, dpi=dpi, quantities=RESPONSE_PANELS, motion=motion,
                          at=at)


def energy_figure(
    history: Any,
    title: Optional[str] = None,
    path: Optional[Union[str, "os.PathLike[str]"]] = None,
    dpi: int = 150,
) -> Figure:
    """The energy balance of a time history on one panel (:func:`plot_energy`); a PNG if ``path`` is given
    (Agg canvas), else through pyplot. ``title``: the case title, before the status in the heading."""
    fig = _new_figure((9.0, 5.0), path is not None)
    plot_energy(history, ax=fig.add_subplot(1, 1, 1))
    return _finish(fig, _with_title(title, _history_heading(history)), path, dpi, fontsize=12)


def _history_heading(history: Any) -> str:
    """The status, the steps and the time step of a time history, for a figure's heading."""
    text = f"time history, {history.status}, {_plural(int(history.steps), 'step')} of {history.time_step:.3g} s"
    if history.error:
        text += f" ({' '.join(str(history.error).split())})"
    return text


def plot_comparison(
    model: Any,
    static: Any,
    dynamic: Any,
    title: Optional[str] = None,
    path: Optional[Union[str, "os.PathLike[str]"]] = None,
    live: str = "horizontal_weight",
    dpi: int = 150,
    limit: Any = None,
) -> Figure:
    """The static and the explicit (dynamic) analysis of one model side by side, and its limit analysis when
    ``limit`` is given; a PNG if ``path`` is given.

    The walls with their mechanisms and joint states (as in :func:`plot_results`; one above the other for a
    wide wall, side by side for a tall one) under one legend, and the curves overlaid, each collapse
    multiplier marked and given in the legend; the limit analysis, which has no curve, as a horizontal
    dashed line at its multiplier. The figure title gives the differences of the multipliers from the
    static one and how far the failed-joint patterns agree (see :func:`masonry_dem.compare.agreement`).
    Arguments as in :func:`plot_results`.
    """
    from ..compare import agreement

    agree = agreement(static, dynamic, limit)
    runs = [("static", static), ("dynamic", dynamic)] + ([("limit", limit)] if limit is not None else [])
    fig, wall_cells, curve_cell, legend_cell, legend_columns = _comparison_grid(model, len(runs), path is not None)
    for cell, (method, res) in zip(wall_cells, runs):
        failed = _plural(agree[f"failed_{method}"], "failed joint")
        if method == "limit":
            failed += " in the collapse mechanism"
        ax = fig.add_subplot(cell)
        _draw_wall(ax, model, res, legend=False, heading=f"{method}: {res.status}, {_lam_text(res, live)}\n{failed}")

    ax_curve = fig.add_subplot(curve_cell)
    _draw_curve_overlay(ax_curve, runs, live)

    ax_legend = fig.add_subplot(legend_cell)
    ax_legend.axis("off")
    ax_legend.legend(handles=_state_handles(), loc="center", ncol=legend_columns, fontsize=8, frameon=False)
    return _finish(fig, _with_title(title, _comparison_heading(agree, limit is not None)), path, dpi, fontsize=12)


def _comparison_grid(model: Any, n_walls: int, to_file: bool) -> Tuple[Figure, List[Any], Any, Any, int]:
    """The figure of :func:`plot_comparison` and its cells: one a wall, the curves' and the legend's, and the
    legend's number of columns. A wide wall: the walls one above the other on the left, the curves on the
    right; a tall one: the walls and the curves side by side."""
    aspect = _aspect(model)
    if aspect > 1.1:
        a = min(aspect, 4.0)
        height = float(np.clip(n_walls * 7.0 / a + 2.6, 6.0, 11.0 if n_walls == 2 else 15.0))
        fig = _new_figure((13.0, height), to_file)
        grid = fig.add_gridspec(n_walls + 1, 2, width_ratios=[1.25, 1.0], height_ratios=[1.0] * n_walls + [0.09])
        wall_cells = [grid[k, 0] for k in range(n_walls)]
        return fig, wall_cells, grid[0:n_walls, 1], grid[n_walls, :], 8
    a = max(aspect, 0.4)
    fig = _new_figure((14.0 if n_walls == 2 else 18.0, 6.5), to_file)
    grid = fig.add_gridspec(2, n_walls + 1, width_ratios=[a] * n_walls + [1.7], height_ratios=[1.0, 0.09])
    wall_cells = [grid[0, k] for k in range(n_walls)]
    return fig, wall_cells, grid[0, n_walls], grid[1, :n_walls], 4


def _comparison_heading(agree: Dict[str, Any], limit: bool) -> str:
    """How far the methods agree (:func:`masonry_dem.compare.agreement`): the differences of the multipliers
    from the static one and the failed joints in common; the limit analysis's on a second line."""
    from ..compare import format_difference

    def differ(diff: Optional[float]) -> str:
        return f"multipliers differ by {format_difference(diff)}" if diff is not None else "no multiplier to compare"

    text = (
        f"static vs dynamic: {differ(agree['multiplier_relative_difference'])}; failed joints "
        f"{agree['failed_static']} and {agree['failed_dynamic']}, {agree['failed_common']} in common "
        f"(Jaccard {agree['jaccard']:.2f})"
    )
    if limit:
        text += (
            f"\nlimit analysis vs static: {differ(agree['multiplier_relative_difference_limit'])}; failed joints "
            f"{agree['failed_limit']}, {agree['failed_common_limit']} in common with static "
            f"(Jaccard {agree['jaccard_limit']:.2f})"
        )
    return text
