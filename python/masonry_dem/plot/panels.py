"""The panels of the figures, each drawn on a matplotlib ``Axes`` given by the caller: the wall
(:func:`plot_wall`), its deformed shape (:func:`plot_deformed`), crack pattern (:func:`plot_cracks`),
collapse mechanism (:func:`plot_mechanism`) and line of thrust (:func:`plot_thrust`), and the load curve
(:func:`plot_curve`, several results overlaid). Geometry in m; displacements plotted in mm.
"""

from __future__ import annotations

import math
from typing import Any, List, Optional, Sequence, Tuple

import numpy as np
from matplotlib.collections import LineCollection, PatchCollection
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Polygon

from .._shapes import fixed_blocks, shapes
from ..history import default_control_block
from ..response import wall_height
from ..thrust import resultant_points, thrust_lines
from ..report import (
    STATUS_NOTES,
    CRACK_TOLERANCE,
    MOVING_FRACTION,
    _plural,
    format_multiplier,
    interface_categories,
    multiplier_symbol,
    interface_jumps,
)

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


def _multiplier_label(live: str) -> Tuple[str, float]:
    """(axis label, factor applied to the multiplier) for the live load."""
    if live == "top_horizontal":
        return "horizontal force on the top beam H [kN]", 1e-3
    return "load multiplier λ", 1.0


def _lam_text(results: Any, live: str) -> str:
    """The collapse multiplier of ``results`` with its symbol (:func:`masonry_dem.report.format_multiplier`); a
    limit analysis's estimate (status "estimate") marked as one, never as a collapse multiplier."""
    if str(getattr(results, "status", "")) == "estimate":
        return "~" + format_multiplier(float(results.last_equilibrium), live) + " (estimate, neither bound)"
    return format_multiplier(float(results.collapse_multiplier), live, symbol=True)


def _segments(geom: np.ndarray) -> List[List[Tuple[float, float]]]:
    """The interfaces of rows (x, y, nx, ny, length) of ``Model.interface_geometry`` as line segments [m]."""
    segments = []
    for cx, cy, nx, ny, length in geom:
        tx, ty = -ny * length / 2, nx * length / 2
        segments.append([(cx - tx, cy - ty), (cx + tx, cy + ty)])
    return segments


def _wall_limits(model: Any) -> Tuple[Tuple[float, float], Tuple[float, float]]:
    """((x_lo, x_hi), (y_lo, y_hi)) [m] of the wall panel: the blocks with room for the mechanism."""
    box = shapes(model).bounds
    wall = box[: int(model.n_blocks)]
    height = float(wall[:, 3].max() - wall[:, 1].min())
    width = float(wall[:, 2].max() - wall[:, 0].min())
    pad = 0.05 * max(width, height) + MECHANISM_FRACTION * height
    x_lo, y_lo = box[:, 0].min(), box[:, 1].min()
    x_hi, y_hi = box[:, 2].max(), box[:, 3].max()
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


def _draw_blocks(
    ax: Any,
    model: Any,
    motion: Optional[np.ndarray],
    scale: float,
    moving: Optional[np.ndarray] = None,
    undeformed: bool = True,
) -> None:
    """The blocks moved by ``scale`` * ``motion`` ((n_all, 3): u1, u2 [m], phi [rad]; None: at rest), filled; the
    base and the supports (the fixed blocks) hatched where they are; the top beam grey; wall blocks orange where
    ``moving`` is set, else beige. With ``undeformed`` the undeformed outlines are drawn dashed over the fills. A
    support given a movement is drawn moved with the rest."""
    blocks = shapes(model)
    beam = model.top_index
    fixed = set(fixed_blocks(model))
    moved = blocks.polygons() if motion is None else blocks.polygons(blocks.moved(motion, scale))
    for i in sorted(fixed):
        ax.add_patch(Polygon(moved[i], closed=True, facecolor="#d9d9d9", edgecolor="#555555", hatch="///",
                             linewidth=0.8, zorder=1))
    fills, colors = [], []
    for i, vertices in enumerate(moved):
        if i in fixed:
            continue
        fills.append(Polygon(vertices, closed=True))
        if i == beam:
            colors.append("#7f7f7f")
        else:
            colors.append("#f4a259" if moving is not None and moving[i] else "#efe3c8")
    ax.add_collection(
        PatchCollection(fills, facecolors=colors, edgecolors="#5a4a3a", linewidths=0.6, alpha=0.9, zorder=1)
    )
    if undeformed:
        outlines = [np.vstack([p, p[:1]]) for i, p in enumerate(blocks.polygons()) if i not in fixed]
        ax.add_collection(LineCollection(outlines, colors="#404040", linewidths=0.5, linestyles="--", zorder=2))


def _draw_interfaces(
    ax: Any, model: Any, results: Any, cracked: Optional[np.ndarray] = None, state_width: Optional[float] = None
) -> dict:
    """The interfaces at their undeformed place, coloured by state (:data:`STATE_STYLES`); those set in
    ``cracked`` 4 points wide; ``state_width``: the width of the non-elastic ones (default: the style's).
    Returns the count of each category."""
    geom = np.asarray(model.interface_geometry, dtype=np.float64).reshape(-1, 5)
    states = np.asarray(results.interface_states, dtype=np.int64).reshape(-1)
    cats = interface_categories(states) if len(states) == len(geom) else ["elastic"] * len(geom)
    if cracked is None:
        cracked = np.zeros(len(geom), dtype=bool)
    counts = {"cracked": int(cracked.sum())}
    for name, color, lw in STATE_STYLES:
        idx = [k for k, c in enumerate(cats) if c == name]
        counts[name] = len(idx)
        if state_width is not None and name != "elastic":
            lw = state_width
        for crack in (False, True):
            segs = _segments(geom[[k for k in idx if cracked[k] == crack]])
            if segs:
                width = 4.0 if crack else lw
                ax.add_collection(LineCollection(segs, colors=color, linewidths=width, zorder=3 + crack))
    return counts


def _wall_axes(ax: Any, model: Any) -> None:
    """Limits, equal aspect and labels of a wall panel."""
    xlim, ylim = _wall_limits(model)
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")


def _mechanism(model: Any, results: Any) -> Tuple[np.ndarray, bool, float, float, np.ndarray]:
    """(motion, have_mech, peak corner motion, drawing scale, moving) of ``Results.mechanism``; the scale
    draws the largest corner motion as :data:`MECHANISM_FRACTION` of the wall height."""
    blocks = shapes(model)
    n = len(blocks)
    mech = np.asarray(results.mechanism, dtype=np.float64)
    have = mech.shape == (n, 3) and bool(np.all(np.isfinite(mech))) and bool(np.any(mech != 0))
    if not have:
        mech = np.zeros((n, 3))
    motion = blocks.vertex_motion(mech)
    peak = float(motion.max()) if have else 0.0
    scale = MECHANISM_FRACTION * wall_height(model) / peak if peak > 0 else 0.0
    moving = motion > MOVING_FRACTION * peak if peak > 0 else np.zeros(n, dtype=bool)
    return mech, have, peak, scale, moving


def _cracked(model: Any, mech: np.ndarray, have: bool, peak: float) -> np.ndarray:
    """The interfaces the mechanism cracks: a slip or a gap across them above CRACK_TOLERANCE * peak."""
    if not have:
        return np.zeros(len(np.asarray(model.interface_geometry).reshape(-1, 5)), dtype=bool)
    jumps = interface_jumps(model, mech)
    return np.asarray((np.abs(jumps[:, 0]) > CRACK_TOLERANCE * peak) | (jumps[:, 1] > CRACK_TOLERANCE * peak))


def _draw_wall(ax: Any, model: Any, results: Any, legend: bool = True, heading: Optional[str] = None) -> None:
    """The wall panel; ``legend``: the legend under the panel; ``heading``: the panel title (default: the
    numbers of blocks and interfaces)."""
    n_wall = int(model.n_blocks)
    mech, have_mech, peak, scale, moving = _mechanism(model, results)
    _draw_blocks(ax, model, mech, scale, moving)
    counts = _draw_interfaces(ax, model, results, _cracked(model, mech, have_mech, peak))
    _wall_axes(ax, model)
    n_faces = len(np.asarray(model.interface_geometry).reshape(-1, 5))
    mech_note = "mechanism shape exaggerated" if have_mech else "no mechanism"
    if heading is None:
        heading = f"{_plural(n_wall, 'block')}, {_plural(n_faces, 'interface')}; {mech_note}"
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


# --- one panel each: the wall, the deformed shape, the crack pattern, the mechanism, the curve ----------------

#: The largest displacement of the deformed shape, as a fraction of the wall height (default scale).
DEFORMED_FRACTION = 0.05


def plot_wall(ax: Any, model: Any) -> None:
    """Draw the wall on ``ax``: block outlines (wall blocks beige, the base hatched, the top beam grey),
    coordinates in m, equal aspect."""
    _draw_blocks(ax, model, None, 0.0, undeformed=False)
    _wall_axes(ax, model)
    n_faces = len(np.asarray(model.interface_geometry).reshape(-1, 5))
    ax.set_title(f"{_plural(int(model.n_blocks), 'block')}, {_plural(n_faces, 'interface')}", fontsize=10)


def plot_deformed(ax: Any, model: Any, results: Any, scale: Optional[float] = None) -> float:
    """Draw the deformed shape at the last converged step (``Results.displacements``) on ``ax``.

    Each block is moved by ``scale`` * (u1, u2) and turned by ``scale`` * phi about its centroid, over the
    dashed undeformed outlines. ``scale`` [-]: the magnification; default: the largest corner
    displacement is drawn as :data:`DEFORMED_FRACTION` (5%) of the wall height. The panel title gives the
    factor and the largest displacement [mm]. Returns the scale used (0 when nothing moved).
    """
    blocks = shapes(model)
    disp = np.asarray(results.displacements, dtype=np.float64)
    if disp.shape != (len(blocks), 3) or not np.all(np.isfinite(disp)):
        disp = np.zeros((len(blocks), 3))
    peak = float(blocks.vertex_motion(disp).max()) if len(blocks) else 0.0
    followed = _followed(results)
    if scale is None:
        # a mechanism followed moves the blocks by finite motions: drawn as they are
        scale = 1.0 if followed else DEFORMED_FRACTION * wall_height(model) / peak if peak > 0 else 0.0
    _draw_blocks(ax, model, disp, float(scale))
    _wall_axes(ax, model)
    if followed:
        # the limits widened to the moved blocks, which may leave the wall's box
        vertices = np.concatenate([np.asarray(v) for v in blocks.polygons(blocks.moved(disp, float(scale)))])
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        pad = 0.05 * wall_height(model)
        ax.set_xlim(min(x0, vertices[:, 0].min() - pad), max(x1, vertices[:, 0].max() + pad))
        ax.set_ylim(min(y0, vertices[:, 1].min() - pad), max(y1, vertices[:, 1].max() + pad))
        factor = "true scale" if scale == 1.0 else f"×{scale:.3g}"
        ax.set_title(f"at the curve's end ({factor})\nlargest displacement {peak * 1e3:.3g} mm", fontsize=10)
        return float(scale)
    if _is_limit(results):
        ax.set_title("no deformed shape\n(limit analysis: rigid blocks, no load path)", fontsize=10)
        return float(scale)
    factor = f"{scale:,.0f}" if scale >= 100 else f"{scale:.3g}"
    ax.set_title(f"deformed shape ×{factor}\nlargest displacement {peak * 1e3:.3g} mm", fontsize=10)
    return float(scale)


def _is_limit(results: Any) -> bool:
    """Whether ``results`` come from a limit analysis (no curve, no displacements, unless it followed its
    mechanism: :func:`_followed`)."""
    return str(getattr(results, "method", "")) == "limit"


def _followed(results: Any) -> bool:
    """Whether ``results`` come from a limit analysis that followed its mechanism (``follow_mechanism``): a curve
    of lambda on the moved geometry, and the blocks' finite motion at its end."""
    return _is_limit(results) and len(np.asarray(getattr(results, "curve_multiplier", ()))) > 1


def plot_cracks(
    ax: Any, model: Any, results: Any, legend: bool = True, legend_columns: int = 5, thrust: bool = False
) -> dict:
    """Draw the crack pattern on ``ax``: the undeformed wall with every interface coloured by its state at
    the last converged step (:data:`STATE_STYLES`: open, sliding, rocking, sliding + rocking, elastic);
    the interfaces that the mechanism cracks (a slip or a gap across them in ``Results.mechanism``) drawn
    wide, so the crack itself stands out among the joints merely at their limit. With ``legend`` a legend
    with the count of each state under the panel; with ``thrust`` the line of thrust over it (as
    :func:`plot_thrust` draws it). Returns the counts ({state: n, "cracked": n})."""
    _draw_blocks(ax, model, None, 0.0, undeformed=False)
    mech, have, peak, _, _ = _mechanism(model, results)
    counts = _draw_interfaces(ax, model, results, _cracked(model, mech, have, peak), state_width=1.8)
    if thrust:
        _draw_thrust(ax, model, results)
    _wall_axes(ax, model)
    ax.set_title(
        f"crack pattern (joint states{'; line of thrust' if thrust else ''})\nwide: cracked in the mechanism "
        f"({counts['cracked']})",
        fontsize=10,
    )
    if legend:
        handles = [
            Line2D([], [], color=color, linewidth=3.0, label=f"{name} ({counts[name]})")
            for name, color, _ in STATE_STYLES
        ] + (_thrust_handles() if thrust else [])
        ax.legend(
            handles=handles,
            loc="upper center",
            bbox_to_anchor=(0.5, -0.15 if legend_columns >= 5 else -0.08),
            ncol=legend_columns + (1 if thrust and legend_columns >= 5 else 0),
            fontsize=8,
            frameon=False,
        )
    return counts


#: The colour of the line of thrust and of the joints' centres of pressure.
THRUST_COLOR = "#1a1a1a"


def _draw_thrust(ax: Any, model: Any, results: Any) -> int:
    """The line of thrust of ``results`` over a wall panel (:mod:`masonry_dem.thrust`): each joint's centre of
    pressure a dot, the chains' lines through them. Returns the number of lines."""
    points = resultant_points(model, results)
    shown = points[np.all(np.isfinite(points), axis=1)]
    ax.plot(shown[:, 0], shown[:, 1], "o", color=THRUST_COLOR, markersize=2.5, zorder=6)
    lines = thrust_lines(model, results)
    for line in lines:
        ax.plot(line[:, 0], line[:, 1], "-", color=THRUST_COLOR, linewidth=1.6, zorder=6)
    return len(lines)


def _thrust_handles() -> List[Any]:
    """Legend entries of the line of thrust."""
    return [Line2D([], [], color=THRUST_COLOR, linewidth=1.6, marker="o", markersize=3, label="line of thrust")]


def plot_thrust(ax: Any, model: Any, results: Any, live: str = "horizontal_weight") -> int:
    """Draw the line of thrust on ``ax``: the undeformed wall, each joint's centre of pressure (where the resultant
    of its forces crosses it, :func:`masonry_dem.thrust.resultant_points`) a dot, joined along the chains of blocks
    (the voussoirs of an arch, the blocks of a pier: :func:`masonry_dem.thrust.thrust_lines`). The forces are those
    of ``results``: at collapse of a limit analysis, at the last converged step of a static or explicit one (its
    multiplier in the title; ``live`` as in :func:`plot_curve`). A joint that carries no normal force has no dot,
    and a line is broken there. Returns the number of lines drawn (0: no chain of blocks, the dots alone)."""
    _draw_blocks(ax, model, None, 0.0, undeformed=False)
    geom = np.asarray(model.interface_geometry, dtype=np.float64).reshape(-1, 5)
    ax.add_collection(LineCollection(_segments(geom), colors="#9a9a9a", linewidths=0.6, zorder=3))
    count = _draw_thrust(ax, model, results)
    _wall_axes(ax, model)
    if _is_limit(results):
        when = "at collapse" if str(results.status) == "collapse" else f"of the limit analysis ({results.status})"
    else:
        lam = float(getattr(results, "last_equilibrium", np.nan))
        when = (f"at the last converged step, {multiplier_symbol(live)} = {format_multiplier(lam, live)}"
                if np.isfinite(lam) else "(no equilibrium found)")
    ax.set_title(f"line of thrust {when}\n{_plural(count, 'line')} through the chains of blocks", fontsize=10)
    return count


def plot_mechanism(ax: Any, model: Any, results: Any) -> bool:
    """Draw the collapse mechanism on ``ax``: the blocks moved along ``Results.mechanism`` (the last
    increment; the largest corner motion drawn as :data:`MECHANISM_FRACTION` of the wall height), the
    moving blocks orange, over the dashed undeformed outlines; the interfaces the mechanism cracks (a slip
    or a gap across them) drawn black. Returns whether there was a mechanism to draw."""
    mech, have, peak, scale, moving = _mechanism(model, results)
    _draw_blocks(ax, model, mech, scale, moving)
    cracked = _cracked(model, mech, have, peak)
    geom = np.asarray(model.interface_geometry, dtype=np.float64).reshape(-1, 5)
    segs = _segments(geom[cracked])
    if segs:
        ax.add_collection(LineCollection(segs, colors="black", linewidths=2.5, zorder=3))
    _wall_axes(ax, model)
    limit = _is_limit(results)
    if have:
        n_moving = int(np.sum(moving[: int(model.n_blocks)]))
        what = ("estimated velocities" if str(results.status) == "estimate" else "collapse velocities") if limit \
            else "last increment"
        text = (
            f"mechanism ({what}, exaggerated)\n{_plural(n_moving, 'moving block')}, "
            f"{_plural(len(segs), 'cracked joint')}"
        )
    else:
        text = "no mechanism\n" + (f"({results.status})" if limit else "(no displacement increment)")
    ax.set_title(text, fontsize=10)
    return have


def plot_curve(
    ax: Any, *results: Any, labels: Optional[Sequence[str]] = None, live: str = "horizontal_weight"
) -> None:
    """Draw the load curve(s) on ``ax``: lambda (or the force on the top beam in kN, ``live =
    "top_horizontal"``) against the horizontal displacement of the control point [mm], the collapse (or
    peak) point marked. One result: its curve with the multiplier and the work done; several (e.g. the
    static and the dynamic run of one case): overlaid, labelled by ``labels`` (default: their methods)."""
    if not results:
        raise TypeError("plot_curve needs at least one Results")
    if len(results) == 1 and labels is None:
        _draw_curve(ax, results[0], live)
        return
    names = list(labels) if labels is not None else [str(r.method) for r in results]
    if len(names) != len(results):
        raise ValueError(f"{len(results)} results but {len(names)} labels")
    _draw_curve_overlay(ax, list(zip(names, results)), live)


def movement_end(results: Any) -> float:
    """Where a support's movement's wall falls [m]: the end of limit analysis's path of equilibria, or the middle of
    the explicit solver's bracket (the last stage that settled .. the first that did not); NaN without a
    collapse."""
    if str(results.status) != "collapse":
        return math.nan
    bracket = getattr(results, "bracket", None)
    if bracket is not None:
        return 0.5 * (float(bracket[0]) + float(bracket[1]))
    return float(np.asarray(results.curve_displacement, dtype=np.float64)[-1])


def plot_movement_curve(ax: Any, results: Any) -> None:
    """Draw a support's movement's curve on ``ax``: the force the wall exerts on the support against its movement
    [kN] (an arch's thrust against a spread) against the support's movement [mm], where it falls marked."""
    force = np.asarray(results.curve_multiplier, dtype=np.float64) / 1e3
    d = np.asarray(results.curve_displacement, dtype=np.float64) * 1e3
    if len(force):
        ax.plot(d, force, "-", color="#1f3b73", linewidth=1.5, label="force on the support")
    end = movement_end(results) * 1e3
    if np.isfinite(end):
        ax.axvline(end, color="#d62728", linestyle=":", linewidth=1.2)
        ax.annotate(f"falls at {end:.1f} mm", xy=(end, 0.05), xycoords=("data", "axes fraction"), xytext=(-4, 0),
                    textcoords="offset points", ha="right", color="#d62728", fontsize=10)
    elif str(results.status) in STATUS_NOTES or results.error:
        reason = results.error or STATUS_NOTES[str(results.status)]
        ax.text(0.02, 0.02, f"{results.status}: {reason}", transform=ax.transAxes, fontsize=8, color="#d62728",
                wrap=True)
    ax.set_xlabel("movement of the support [mm]")
    ax.set_ylabel("force of the wall on the support [kN]")
    if len(force):
        ax.set_ylim(0.0, 1.1 * float(np.nanmax(force)))
    ax.grid(True, alpha=0.3)


def _draw_curve(ax: Any, results: Any, live: str) -> None:
    label, factor = _multiplier_label(live)
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
        what = "limit analysis" if _is_limit(results) else "collapse" if results.status == "collapse" else "peak"
        text = f"{what}: {_lam_text(results, live)}"
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
    if str(results.status) in STATUS_NOTES:
        reason = results.error or STATUS_NOTES[str(results.status)]
        ax.text(0.02, 0.02, f"{results.status}: {reason}", transform=ax.transAxes, fontsize=8, color="#d62728",
                wrap=True)
    ax.set_xlabel("horizontal displacement of the control point [mm]")
    ax.set_ylabel(label)
    values = [float(v) for v in lam if np.isfinite(v)] + ([lam_u] if np.isfinite(lam_u) else [])
    if values:
        lo, hi = min(0.0, min(values)), max(values)
        if hi > lo:
            ax.set_ylim(lo, hi + 0.12 * (hi - lo))  # room for the collapse label
    ax.grid(True, alpha=0.3)
    if _followed(results):
        if results.error:
            ax.text(0.02, 0.02, f"stopped short: {results.error}", transform=ax.transAxes, fontsize=8,
                    color="#d62728", wrap=True)
        ax.set_title(
            f"limit analysis along the mechanism: {results.steps} steps\n{results.iterations} interior-point "
            f"iterations, {results.elapsed_s:.3g} s",
            fontsize=10,
        )
        return
    if _is_limit(results):
        ax.set_xticks([])
        ax.set_xlabel("no load path: the limit multiplier")
        ax.set_title(
            f"limit analysis: no load path\n{results.iterations} interior-point iterations, {results.elapsed_s:.3g} s",
            fontsize=10,
        )
        return
    ax.set_title(f"{results.steps} steps, {results.iterations} iterations, {results.elapsed_s:.3g} s", fontsize=10)


#: Colour, marker, line width, opacity and drawing order of each method in :func:`plot_comparison`: the
#: dynamic curve wide and light under the static one, so that both show where they coincide.
#: A limit analysis (no curve) is a horizontal dashed line at its multiplier.
METHOD_STYLES = {
    "static": ("#1f3b73", "o", 1.2, 1.0, 3),
    "dynamic": ("#e07b00", "s", 4.0, 0.55, 2),
    "limit": ("#2ca02c", "", 1.6, 0.9, 4),
}

#: Styles of further curves in an overlay (other labels, or a method drawn twice).
EXTRA_STYLES: Tuple[Tuple[str, str, float, float, int], ...] = (
    ("#2ca02c", "^", 1.2, 1.0, 3),
    ("#9467bd", "v", 1.2, 1.0, 3),
    ("#8c564b", "D", 1.2, 1.0, 3),
)


def _draw_curve_overlay(ax: Any, runs: Sequence[Tuple[str, Any]], live: str) -> None:
    """Several curves on one axis, each with its collapse (or peak) point, labelled (by method by default).

    The style of a curve is its label's in :data:`METHOD_STYLES`, else its method's, else (or when that
    style is taken) one of :data:`EXTRA_STYLES`."""
    label, factor = _multiplier_label(live)
    values: List[float] = []
    used: List[Tuple[str, str, float, float, int]] = []
    extra = iter(EXTRA_STYLES * (1 + len(runs)))
    for method, res in runs:
        style = METHOD_STYLES.get(method) or METHOD_STYLES.get(str(getattr(res, "method", "")))
        if style is None or style in used:
            style = next(extra)
        used.append(style)
        color, marker, width, alpha, order = style
        lam = np.asarray(res.curve_multiplier, dtype=np.float64) * factor
        disp = np.asarray(res.curve_displacement, dtype=np.float64) * 1e3
        lam_u = float(res.collapse_multiplier) * factor
        if np.isfinite(lam_u):
            head = f"{method}: {_lam_text(res, live)}"
        else:
            head = f"{method}: {res.status}"
        kind = {"dynamic": "time steps", "limit": "interior-point iterations"}.get(str(res.method), "iterations")
        work = f"{res.iterations:,} {kind}"
        text = f"{head} ({work}, {res.elapsed_s:.3g} s)"
        if not len(lam):  # no load path (a limit analysis): its multiplier across the plot
            if np.isfinite(lam_u):
                ax.axhline(lam_u, color=color, linestyle="--", linewidth=width, alpha=alpha, zorder=order, label=text)
                values.append(lam_u)
            else:
                ax.plot([], [], "--", color=color, linewidth=width, label=text)
            if str(res.status) in STATUS_NOTES and res.error:
                ax.plot([], [], " ", label=f"{method} {res.status}: {res.error}")
            continue
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
        if str(res.status) in STATUS_NOTES and res.error:
            ax.plot([], [], " ", label=f"{method} {res.status}: {res.error}")
    if values:
        lo, hi = min(0.0, min(values)), max(values)
        if hi > lo:
            ax.set_ylim(lo, hi + 0.08 * (hi - lo))
    ax.set_xlabel("horizontal displacement of the control point [mm]")
    ax.set_ylabel(label)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)
    limits = any(not len(np.asarray(res.curve_multiplier)) for _, res in runs)
    ax.set_title(
        "load curves (open marker: collapse or peak" + ("; dashed: limit analysis)" if limits else ")"), fontsize=10
    )
