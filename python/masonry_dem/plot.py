"""Plots of an analysis: the wall with its collapse mechanism and crack pattern, and the load curve.

:func:`plot_results` draws one figure with two panels:

* left, the wall: the undeformed block outlines; under them the blocks moved along
  ``Results.mechanism`` (a displacement increment, drawn exaggerated so that the largest corner
  motion is a visible fraction of the wall height; rotations about the block centroids), filled;
  the interfaces coloured by their state at the last converged step (open, sliding, rocking,
  sliding and rocking, elastic), thick where the mechanism cracks them (a slip or a gap across);
* right, the curve: load multiplier lambda against the horizontal displacement of the control point
  [mm], with the collapse multiplier marked.

:func:`plot_comparison` draws the static and the explicit (dynamic) analyses of one case side by side:
the two walls with their crack patterns, and the two curves overlaid.

Geometry in m; displacements plotted in mm. Matplotlib is imported when this module is.
"""

from __future__ import annotations

import os
from typing import Any, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt
from matplotlib.collections import LineCollection, PatchCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Polygon, Rectangle

from .report import (
    CRACK_TOLERANCE,
    MOVING_FRACTION,
    OPEN,
    ROCKING,
    SLIDING,
    _plural,
    corner_motion,
    deformed_corners,
    interface_jumps,
)

__all__ = ["plot_results", "plot_comparison", "interface_categories", "STATE_STYLES"]

#: Interface categories in drawing order: (name, colour, line width).
#: Cracked interfaces (a jump across them in the mechanism) are drawn 4 points wide.
STATE_STYLES: Tuple[Tuple[str, str, float], ...] = (
    ("elastic", "#9a9a9a", 0.6),
    ("open", "#1f77b4", 1.4),
    ("sliding", "#d62728", 1.4),
    ("rocking", "#2ca02c", 1.4),
    ("sliding + rocking", "#9467bd", 1.4),
)

#: The largest corner motion of the drawn mechanism, as a fraction of the wall height.
MECHANISM_FRACTION = 0.12


def interface_categories(states: npt.ArrayLike) -> List[str]:
    """The drawing category of each interface from its bit flags (1 open, 2 sliding, 4 rocking).

    An open interface carries nothing and is drawn as open whatever else is set.
    """
    out = []
    for s in np.asarray(states, dtype=np.int64):
        if s & OPEN:
            out.append("open")
        elif s & SLIDING and s & ROCKING:
            out.append("sliding + rocking")
        elif s & SLIDING:
            out.append("sliding")
        elif s & ROCKING:
            out.append("rocking")
        else:
            out.append("elastic")
    return out


def _outline(rect: Sequence[float]) -> np.ndarray:
    """(5, 2) closed outline of a rectangle [x0, y0, x1, y1] [m]."""
    x0, y0, x1, y1 = rect
    return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]], dtype=np.float64)


def _multiplier_label(live: str) -> Tuple[str, float, str]:
    """(axis label, factor applied to the multiplier, unit text) for the live load."""
    if live == "top_horizontal":
        return "horizontal force on the top beam H [kN]", 1e-3, " kN"
    return "load multiplier λ", 1.0, ""


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

    label, factor, unit = _multiplier_label(live)
    lam = float(results.collapse_multiplier)
    name = "H" if live == "top_horizontal" else "λ"
    lam_text = f"{name}u = {lam * factor:.4g}{unit}" if live == "top_horizontal" else f"{name}u = {lam:.4f}"
    if not np.isfinite(lam):
        lam_text = f"{name}u: none"
    head = f"{title} — " if title else ""
    fig.suptitle(f"{head}{results.method}, {results.status}, {lam_text}", fontsize=13)
    if path is not None:
        fig.savefig(path, dpi=dpi)
    return fig


def _new_figure(size: Tuple[float, float], to_file: bool) -> Figure:
    """A figure with constrained layout: on the Agg canvas for a file (pyplot's state untouched), else
    through pyplot (for ``plt.show()`` or a notebook)."""
    if to_file:
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        fig = Figure(figsize=size, layout="constrained")
        FigureCanvasAgg(fig)
        return fig
    import matplotlib.pyplot as plt

    return plt.figure(figsize=size, layout="constrained")


def _wall_limits(model: Any) -> Tuple[Tuple[float, float], Tuple[float, float]]:
    """((x_lo, x_hi), (y_lo, y_hi)) [m] of the wall panel: the blocks with room for the mechanism."""
    rects = np.asarray(model.rects, dtype=np.float64)
    wall = rects[: int(model.n_blocks)]
    height = float(wall[:, 3].max() - wall[:, 1].min())
    width = float(wall[:, 2].max() - wall[:, 0].min())
    pad = 0.05 * max(width, height) + MECHANISM_FRACTION * height
    x_lo, y_lo = rects[:, 0].min(), rects[:, 1].min()
    x_hi, y_hi = rects[:, 2].max(), rects[:, 3].max()
    return (x_lo - pad, x_hi + pad), (y_lo - 0.05 * height, y_hi + pad)


def _state_handles(counts: Optional[dict] = None) -> List[Any]:
    """Legend entries of the wall panel; with ``counts`` ({category: n, "cracked": n}) the numbers too."""

    def label(name: str, key: str) -> str:
        return f"{name} ({counts[key]})" if counts is not None else name

    handles: List[Any] = [
        Line2D([], [], color=color, linewidth=2.5, label=label(name, name)) for name, color, _ in STATE_STYLES
    ]
    handles.append(Patch(facecolor="#f4a259", edgecolor="#5a4a3a", label="moving blocks"))
    handles.append(Line2D([], [], color="#404040", linewidth=0.8, linestyle="--", label="undeformed"))
    handles.append(Line2D([], [], color="black", linewidth=3.5, label=label("cracked in the mechanism", "cracked")))
    return handles


def _draw_wall(ax: Any, model: Any, results: Any, legend: bool = True, heading: Optional[str] = None) -> None:
    """The wall panel; ``legend``: the legend under the panel; ``heading``: the panel title (default: the
    numbers of blocks and interfaces)."""
    rects = np.asarray(model.rects, dtype=np.float64)
    n_wall = int(model.n_blocks)
    base = model.base_index
    beam = model.top_index
    wall = rects[:n_wall]
    height = float(wall[:, 3].max() - wall[:, 1].min())

    mech = np.asarray(results.mechanism, dtype=np.float64)
    have_mech = mech.shape == (len(rects), 3) and np.all(np.isfinite(mech)) and np.any(mech != 0)
    if not have_mech:
        mech = np.zeros((len(rects), 3))
    motion = corner_motion(rects, mech)
    peak = float(motion.max()) if have_mech else 0.0
    scale = MECHANISM_FRACTION * height / peak if peak > 0 else 0.0
    moving = motion > MOVING_FRACTION * peak if peak > 0 else np.zeros(len(rects), dtype=bool)

    # The deformed (mechanism) shape, filled; the base stays where it is.
    fills, colors = [], []
    for i, rect in enumerate(rects):
        if i == base:
            ax.add_patch(
                Rectangle(
                    (rect[0], rect[1]),
                    rect[2] - rect[0],
                    rect[3] - rect[1],
                    facecolor="#d9d9d9",
                    edgecolor="#555555",
                    hatch="///",
                    linewidth=0.8,
                    zorder=1,
                )
            )
            continue
        fills.append(Polygon(deformed_corners(rect, mech[i], scale), closed=True))
        if i == beam:
            colors.append("#7f7f7f")
        else:
            colors.append("#f4a259" if moving[i] else "#efe3c8")
    ax.add_collection(
        PatchCollection(fills, facecolors=colors, edgecolors="#5a4a3a", linewidths=0.6, alpha=0.9, zorder=1)
    )

    # The undeformed outlines, over the fills.
    outlines = [_outline(r) for i, r in enumerate(rects) if i != base]
    ax.add_collection(LineCollection(outlines, colors="#404040", linewidths=0.5, linestyles="--", zorder=2))

    # Interfaces by state, at their undeformed place; those the mechanism cracks (a jump across them) thick.
    geom = np.asarray(model.interface_geometry, dtype=np.float64).reshape(-1, 5)
    states = np.asarray(results.interface_states, dtype=np.int64)
    cats = interface_categories(states) if len(states) == len(geom) else ["elastic"] * len(geom)
    if have_mech:
        jumps = interface_jumps(model, mech)
        cracked = (np.abs(jumps[:, 0]) > CRACK_TOLERANCE * peak) | (jumps[:, 1] > CRACK_TOLERANCE * peak)
    else:
        cracked = np.zeros(len(geom), dtype=bool)
    counts = {"cracked": int(cracked.sum())}
    for name, color, lw in STATE_STYLES:
        idx = [k for k, c in enumerate(cats) if c == name]
        counts[name] = len(idx)
        for crack in (False, True):
            segs = []
            for k in idx:
                if cracked[k] == crack:
                    cx, cy, nx, ny, length = geom[k]
                    tx, ty = -ny * length / 2, nx * length / 2
                    segs.append([(cx - tx, cy - ty), (cx + tx, cy + ty)])
            if segs:
                width = 4.0 if crack else lw
                ax.add_collection(LineCollection(segs, colors=color, linewidths=width, zorder=3 + crack))

    xlim, ylim = _wall_limits(model)
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    mech_note = "mechanism shape exaggerated" if have_mech else "no mechanism"
    if heading is None:
        heading = f"{_plural(n_wall, 'block')}, {_plural(len(geom), 'interface')}; {mech_note}"
    ax.set_title(heading, fontsize=10)
    if legend:
        ax.legend(
            handles=_state_handles(counts),
            loc="upper center",
            bbox_to_anchor=(0.5, -0.12),
            ncol=4,
            fontsize=8,
            frameon=False,
        )


def _draw_curve(ax: Any, results: Any, live: str) -> None:
    label, factor, unit = _multiplier_label(live)
    lam = np.asarray(results.curve_multiplier, dtype=np.float64) * factor
    disp = np.asarray(results.curve_displacement, dtype=np.float64) * 1e3
    if len(lam):
        ax.plot(disp, lam, "-o", color="#1f3b73", markersize=2.5, linewidth=1.3, label="equilibrium path")
    lam_u = float(results.collapse_multiplier) * factor
    if np.isfinite(lam_u):
        ax.axhline(lam_u, color="#d62728", linestyle=":", linewidth=1.2)
        if np.any(np.isfinite(lam)):
            k = int(np.nanargmin(np.abs(lam - lam_u)))  # the point of the curve at the collapse multiplier
            ax.plot([disp[k]], [lam[k]], "o", color="#d62728", markersize=7, zorder=5)
        what = "collapse" if results.status == "collapse" else "peak"
        text = f"{what}: H = {lam_u:.4g}{unit}" if live == "top_horizontal" else f"{what}: λu = {lam_u:.4f}"
        ax.annotate(
            text,
            xy=(0.02, lam_u),
            xycoords=("axes fraction", "data"),
            xytext=(0, 3),
            textcoords="offset points",
            ha="left",
            va="bottom",
            color="#d62728",
            fontsize=10,
        )
    if results.status == "failed" and results.error:
        ax.text(0.02, 0.02, f"failed: {results.error}", transform=ax.transAxes, fontsize=8, color="#d62728", wrap=True)
    ax.set_xlabel("horizontal displacement of the control point [mm]")
    ax.set_ylabel(label)
    values = [float(v) for v in lam if np.isfinite(v)] + ([lam_u] if np.isfinite(lam_u) else [])
    if values:
        lo, hi = min(0.0, min(values)), max(values)
        if hi > lo:
            ax.set_ylim(lo, hi + 0.12 * (hi - lo))  # room for the collapse label
    ax.grid(True, alpha=0.3)
    ax.set_title(f"{results.steps} steps, {results.iterations} iterations, {results.elapsed_s:.3g} s", fontsize=10)


#: Colour, marker, line width, opacity and drawing order of each method in :func:`plot_comparison`: the
#: dynamic curve wide and light under the static one, so that both show where they coincide.
METHOD_STYLES = {"static": ("#1f3b73", "o", 1.2, 1.0, 3), "dynamic": ("#e07b00", "s", 4.0, 0.55, 2)}


def plot_comparison(
    model: Any,
    static: Any,
    dynamic: Any,
    title: Optional[str] = None,
    path: Optional[Union[str, "os.PathLike[str]"]] = None,
    live: str = "horizontal_weight",
    dpi: int = 150,
) -> Figure:
    """The static and the explicit (dynamic) analysis of one model side by side; a PNG if ``path`` is given.

    The two walls with their mechanisms and joint states (as in :func:`plot_results`; one above the other
    for a wide wall, side by side for a tall one) under one legend, and the two curves overlaid, each
    collapse multiplier marked and given in the legend.
    The figure title gives the difference of the multipliers and how far the failed-joint patterns
    agree (see :func:`masonry_dem.compare.agreement`). Arguments as in :func:`plot_results`.
    """
    from .compare import agreement, format_difference

    agree = agreement(static, dynamic)
    (xl, xh), (yl, yh) = _wall_limits(model)
    aspect = float((xh - xl) / (yh - yl))
    to_file = path is not None
    if aspect > 1.1:
        # a wide wall: the two walls one above the other on the left, the curves on the right
        a = min(aspect, 4.0)
        fig = _new_figure((13.0, float(np.clip(2 * 7.0 / a + 2.6, 6.0, 11.0))), to_file)
        grid = fig.add_gridspec(3, 2, width_ratios=[1.25, 1.0], height_ratios=[1.0, 1.0, 0.09])
        wall_cells = [grid[0, 0], grid[1, 0]]
        curve_cell, legend_cell, legend_columns = grid[0:2, 1], grid[2, :], 8
    else:
        # a tall wall: the two walls and the curves side by side
        a = max(aspect, 0.4)
        fig = _new_figure((14.0, 6.5), to_file)
        grid = fig.add_gridspec(2, 3, width_ratios=[a, a, 1.7], height_ratios=[1.0, 0.09])
        wall_cells = [grid[0, 0], grid[0, 1]]
        curve_cell, legend_cell, legend_columns = grid[0, 2], grid[1, :2], 4
    name, factor, unit = _multiplier_label(live)
    symbol = "H" if live == "top_horizontal" else "λ"

    def lam_text(res: Any) -> str:
        lam = float(res.collapse_multiplier)
        if not np.isfinite(lam):
            return f"{symbol}u: none"
        return f"{symbol}u = {lam * factor:.4g}{unit}" if live == "top_horizontal" else f"{symbol}u = {lam:.4f}"

    for cell, (method, res) in zip(wall_cells, (("static", static), ("dynamic", dynamic))):
        n_failed = agree[f"failed_{method}"]
        failed = f"{n_failed} failed joint" + ("" if n_failed == 1 else "s")
        ax = fig.add_subplot(cell)
        _draw_wall(ax, model, res, legend=False, heading=f"{method}: {res.status}, {lam_text(res)}\n{failed}")

    ax_curve = fig.add_subplot(curve_cell)
    _draw_curve_overlay(ax_curve, (("static", static), ("dynamic", dynamic)), live)

    ax_legend = fig.add_subplot(legend_cell)
    ax_legend.axis("off")
    ax_legend.legend(handles=_state_handles(), loc="center", ncol=legend_columns, fontsize=8, frameon=False)

    diff = agree["multiplier_relative_difference"]
    diff_text = f"multipliers differ by {format_difference(diff)}" if diff is not None else "no multiplier to compare"
    head = f"{title} — " if title else ""
    fig.suptitle(
        f"{head}static vs dynamic: {diff_text}; failed joints {agree['failed_static']} and "
        f"{agree['failed_dynamic']}, {agree['failed_common']} in common (Jaccard {agree['jaccard']:.2f})",
        fontsize=12,
    )
    if path is not None:
        fig.savefig(path, dpi=dpi)
    return fig


def _draw_curve_overlay(ax: Any, runs: Sequence[Tuple[str, Any]], live: str) -> None:
    """Several curves on one axis, each with its collapse (or peak) point, labelled by method."""
    label, factor, unit = _multiplier_label(live)
    values: List[float] = []
    for method, res in runs:
        color, marker, width, alpha, order = METHOD_STYLES.get(method, ("#444444", "^", 1.2, 1.0, 3))
        lam = np.asarray(res.curve_multiplier, dtype=np.float64) * factor
        disp = np.asarray(res.curve_displacement, dtype=np.float64) * 1e3
        lam_u = float(res.collapse_multiplier) * factor
        if np.isfinite(lam_u):
            value = f"{lam_u:.4g}{unit}" if live == "top_horizontal" else f"{lam_u:.4f}"
            head = f"{method}: {'H' if live == 'top_horizontal' else 'λu'} = {value}"
        else:
            head = f"{method}: {res.status}"
        work = f"{res.iterations:,} {'time steps' if method == 'dynamic' else 'iterations'}"
        text = f"{head} ({work}, {res.elapsed_s:.3g} s)"
        markevery = max(1, len(lam) // 40)
        ax.plot(
            disp,
            lam,
            "-",
            marker=marker,
            markevery=markevery,
            color=color,
            alpha=alpha,
            markersize=3 if width < 2 else 5,
            linewidth=width,
            zorder=order,
            label=text,
        )
        if np.isfinite(lam_u) and np.any(np.isfinite(lam)):
            k = int(np.nanargmin(np.abs(lam - lam_u)))
            size = 8 if width < 2 else 12
            ax.plot([disp[k]], [lam[k]], marker, color=color, markersize=size, markerfacecolor="none", zorder=5)
        values += [float(v) for v in lam if np.isfinite(v)] + ([lam_u] if np.isfinite(lam_u) else [])
        if res.status == "failed" and res.error:
            ax.plot([], [], " ", label=f"{method} failed: {res.error}")
    if values:
        lo, hi = min(0.0, min(values)), max(values)
        if hi > lo:
            ax.set_ylim(lo, hi + 0.08 * (hi - lo))
    ax.set_xlabel("horizontal displacement of the control point [mm]")
    ax.set_ylabel(label)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)
    ax.set_title("load curves (open marker: collapse or peak)", fontsize=10)
