"""The figures of a seismic assessment (matplotlib): the capacity in ADRS form against the demand spectrum
(:func:`plot_adrs`), the mechanism's displaced shape used for M* (:func:`plot_displaced_shape`), and both on one
page (:func:`assessment_figure`)."""

from __future__ import annotations

import math
import os
from typing import Any, Optional, Union

import numpy as np

from .._shapes import shapes
from ..plot.canvas import _finish, _new_figure
from .verdict import Assessment

__all__ = ["plot_adrs", "plot_displaced_shape", "assessment_figure"]


def plot_adrs(ax: Any, assessment: Assessment, periods: Optional[np.ndarray] = None) -> None:
    """The demand spectrum in ADRS form (S_a [m/s2] against S_d [mm], T from 0 to 4 s) with the capacity: the N2
    method's capacity curve of the equivalent system, its bilinear and the performance point (d*_t); the linear
    check's a0* and its demand as levels."""
    s = assessment.parameters.spectrum
    top = 4.0 if s.code != "file" else min(4.0, float(s.periods[-1]))
    T = np.linspace(0.0, top, 400) if periods is None else periods
    ax.plot(1e3 * np.asarray(s.displacement(T)), s.acceleration(T), color="0.3", label="elastic demand spectrum")
    for t in (0.5, 1.0, 2.0):  # a few periods as radial lines
        if t <= top:
            d = float(s.displacement(t))
            ax.plot([0, 1e3 * d], [0, float(s.acceleration(t))], color="0.85", lw=0.8, zorder=0)
            ax.annotate(f"T = {t:g} s", (1e3 * d, float(s.acceleration(t))), fontsize=7, color="0.5")
    n2 = assessment.n2
    if n2 is not None:
        yield_sa = n2.F_y / n2.m_star
        ax.plot(1e3 * n2.curve_displacement / n2.gamma, n2.curve_force / n2.gamma / n2.m_star, color="C0", lw=1.0,
                label="capacity curve F* / m* (N2)")
        end = max(float(n2.curve_displacement[-1]) / n2.gamma, n2.d_t_star)
        ax.plot([0, 1e3 * n2.d_y, 1e3 * end], [0, yield_sa, yield_sa], color="C0", ls="--", lw=1.0,
                label="equal-energy bilinear")
        at_target = min(yield_sa, n2.d_t_star / n2.d_y * yield_sa)
        ax.plot([1e3 * n2.d_t_star], [at_target], "o", color="C3",
                label=f"performance point d*_t = {1e3 * n2.d_t_star:.3g} mm")
        ax.plot([1e3 * n2.d_et], [n2.Se], "x", color="C3", label="elastic demand at T*")
    nl = assessment.nonlinear
    if nl is not None:
        ax.plot(1e3 * nl.d_star, nl.a_star, color="C4", lw=1.2, label="mechanism's curve a*(d*) (finite rotation)")
        ax.axvline(1e3 * nl.du_star, color="C4", ls="--", lw=0.8, label=f"d*_u = {1e3 * nl.du_star:.3g} mm")
        ax.plot([1e3 * nl.demand_ground], [float(s.acceleration(nl.Ts))], "s", color="C4",
                label=f"demand S_De(T_s), T_s = {nl.Ts:.3g} s")
    lin = assessment.linear
    if lin is not None:
        ax.axhline(lin.a0_star, color="C2", ls="--", lw=1.2, label=f"a0* = {lin.a0_star:.3g} m/s2 (mechanism)")
        ax.axhline(lin.demand, color="C1", ls=":", lw=1.2, label=f"demand / q = {lin.demand:.3g} m/s2")
    ax.set_xlabel("spectral displacement S_d [mm]")
    ax.set_ylabel("spectral acceleration S_a [m/s2]")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=7, loc="best")
    ax.set_title("capacity and demand (ADRS)", fontsize=10)


def plot_displaced_shape(ax: Any, model: Any, assessment: Assessment) -> None:
    """The mechanism's weights and their virtual displacements: in the plane the wall with the moving blocks
    coloured by dx_i and an arrow of dx_i at each centroid; in 3D the profile dx_i against the centroids' height."""
    m = assessment.mechanism
    if m is None:
        ax.text(0.5, 0.5, "no collapse mechanism", ha="center", va="center", transform=ax.transAxes)
        ax.set_axis_off()
        return
    from matplotlib.collections import PatchCollection
    from matplotlib.patches import Polygon

    if int(getattr(model, "dimension", 2)) == 3:
        ax.scatter(m.dx, m.points[:, 2], c=m.dx, cmap="viridis", s=12)
        ax.set_xlabel("virtual displacement dx_i along the live load [-]")
        ax.set_ylabel("height of the block's centroid [m]")
        ax.grid(True, lw=0.3)
    else:
        blocks = shapes(model)  # convex polygons: rectangles among them
        n = int(model.n_blocks)
        still = [Polygon(blocks.polygon(i), closed=True) for i in range(len(blocks))
                 if i not in set(m.blocks.tolist()) and (i < n or i == model.top_index)]
        ax.add_collection(PatchCollection(still, facecolor="0.92", edgecolor="0.6", lw=0.4))
        first = np.unique(m.blocks, return_index=True)[1]  # a block's own weight, before its loads'
        moving = [Polygon(blocks.polygon(int(m.blocks[k])), closed=True) for k in first]
        patches = PatchCollection(moving, cmap="viridis", edgecolor="0.2", lw=0.5)
        patches.set_array(np.asarray(m.dx)[first])
        patches.set_clim(min(0.0, float(np.min(m.dx))), 1.0)
        ax.add_collection(patches)
        rects = blocks.bounds
        size = float(max(np.ptp(rects[:, [0, 2]]), np.ptp(rects[:, [1, 3]])))
        ax.quiver(m.points[:, 0], m.points[:, 1], m.dx, np.zeros_like(m.dx), angles="xy", scale_units="xy",
                  scale=1.0 / (0.08 * size), width=0.004, color="C3")
        lo, hi = rects[:, :2].min(axis=0), rects[:, 2:].max(axis=0)
        pad = 0.05 * size
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
        ax.set_aspect("equal", adjustable="box")
        ax.figure.colorbar(patches, ax=ax, shrink=0.7, label="dx_i (largest 1)")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
    lin = assessment.linear
    extra = f"\ne* = {lin.mass_fraction:.3f}, M* = {lin.participating_mass:.4g} kg" if lin is not None else ""
    moved = np.unique(m.blocks).size
    count = f"{moved} block{'s' if moved > 1 else ''}"
    ax.set_title(f"displaced shape used for M* ({count}){extra}", fontsize=10)


def assessment_figure(model: Any, assessment: Assessment, title: str = "",
                      path: Optional[Union[str, "os.PathLike[str]"]] = None, dpi: int = 150) -> Any:
    """The assessment on one page: the ADRS plot beside the displaced shape; written to ``path`` if given (then on
    the Agg canvas, pyplot untouched). Returns the figure."""
    fig = _new_figure((13.0, 5.5), path is not None)
    left, right = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.0, 1.2]})
    plot_adrs(left, assessment)
    plot_displaced_shape(right, model, assessment)
    verdict = assessment.verdict
    heading = f"{title + ': ' if title else ''}seismic assessment, verdict {verdict}"
    lin = assessment.linear
    if lin is not None and math.isfinite(lin.ratio):
        heading += f" (a0* / demand = {lin.ratio:.3g})"
    return _finish(fig, heading, path, dpi)
