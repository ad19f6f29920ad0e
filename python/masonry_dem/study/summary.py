"""The summary of a study's rows: :func:`summary_text` (printed by ``masonry-dem study``) and
:func:`summary_figure`: the distribution of the collapse multiplier (histogram and empirical distribution
function), the multiplier against each varied parameter, and the mechanisms of the weakest analyses.

Only rows with status "collapse" have a multiplier: the others are counted, never plotted as collapses (the
estimates of a non-associative limit analysis, status "estimate", are summarised apart, as estimates).
The weakest analyses' mechanisms are not in the rows: they are computed again here, from the study, one
analysis each (the same case data, the same numbers).
"""

from __future__ import annotations

import math
import os
import textwrap
from collections import Counter
from typing import Any, List, Optional, Sequence, Tuple, Union

import numpy as np
import pandas as pd

from ..report import format_multiplier, multiplier_symbol
from .model import Study
from .worker import FAILED_STATUSES, solve

#: The mechanisms drawn (the weakest analyses) and the quantiles printed.
WEAKEST = 3
QUANTILES = (0.05, 0.5, 0.95)
_METHOD_COLOURS = {"static": "#1f77b4", "dynamic": "#ff7f0e", "limit": "#2ca02c"}


def _live(study: Study) -> str:
    base = study.base if isinstance(study.base, dict) else {}
    return str(base.get("loads", {}).get("live", "horizontal_weight"))


def collapses(frame: pd.DataFrame) -> pd.DataFrame:
    """The rows with status "collapse" (the only ones with a collapse multiplier)."""
    return frame[frame["status"] == "collapse"]


def weakest(frame: pd.DataFrame, n: int = WEAKEST) -> pd.DataFrame:
    """The ``n`` collapse rows of lowest multiplier."""
    return collapses(frame).nsmallest(n, "collapse_multiplier")


def _values_text(row: Any, study: Study) -> str:
    parts = [
        f"{name} {row[name]:.4g}" if isinstance(row[name], float) else f"{name} {row[name]}"
        for name in study.parameters
        if name != "direction"
    ]
    if "direction" in study.parameters:
        parts.append(str(row["direction"]))
    if study.texture is not None or study.random:
        parts.append(f"sample {row['sample']}")
    return ", ".join(parts)


def summary_text(frame: pd.DataFrame, study: Study) -> str:
    """The study in a few lines: the analyses and their statuses, the collapse multiplier's statistics per
    method, the weakest analyses."""
    live = _live(study)
    statuses = Counter(frame["status"])
    lines = [
        study.title,
        f"  analyses:            {len(frame):,} of {study.size:,} ({', '.join(study.methods)})",
        "  statuses:            " + ", ".join(f"{n:,} {s}" for s, n in statuses.most_common()),
    ]
    failed = int(sum(n for s, n in statuses.items() if s in FAILED_STATUSES))
    if failed:
        first = frame[frame["status"].isin(FAILED_STATUSES)].iloc[0]
        lines.append(f"  failed:              {failed:,}; the first, row {first['row']}: {first['error']}")
    for method in study.methods:
        rows = frame[frame["method"] == method]
        values = collapses(rows)["collapse_multiplier"].to_numpy()
        lines.append(f"  {method + ':':<21}{_statistics(values, live)}")
        estimates = rows[rows["status"] == "estimate"]["last_equilibrium"].to_numpy(dtype=float)
        if len(estimates):  # non-associative limit analysis: its numbers apart, as what they are
            lines.append(f"  {method + ' estimates:':<21}{_statistics(estimates, live, 'estimate')} "
                         "(non-associative: neither bound, not collapses)")
    for _, row in weakest(frame).iterrows():
        values = _values_text(row, study)
        shown = format_multiplier(row["collapse_multiplier"], live)
        text = f"row {row['row']} ({row['method']}): {shown}" + (f", {values}" if values else "")
        lines.append(f"  weakest:             {text}")
    return "\n".join(lines)


def _statistics(values: np.ndarray, live: str, what: str = "collapse") -> str:
    """The collapse multipliers' (or estimates') minimum, quantiles, mean and maximum, in one line."""
    if len(values) == 0:
        return f"no {what}"

    def shown(x: float) -> str:
        return format_multiplier(float(x), live)

    q = np.quantile(values, QUANTILES)
    symbol = multiplier_symbol(live) + "u"
    return (
        f"{symbol} min {shown(values.min())}, 5% {shown(q[0])}, median {shown(q[1])}, mean {shown(values.mean())}, "
        f"95% {shown(q[2])}, max {shown(values.max())} ({len(values):,} collapses)"
    )


def _plot_distribution(ax_hist: Any, ax_cdf: Any, frame: pd.DataFrame, study: Study, live: str) -> None:
    """Histogram and empirical distribution function of the collapse multiplier, one colour per method."""
    label, factor = _axis_label(live)
    rows = collapses(frame)
    if len(rows) == 0:
        return
    edges = np.histogram_bin_edges(
        rows["collapse_multiplier"] * factor, bins=min(50, max(5, int(math.sqrt(len(rows)))))
    )
    for method in study.methods:
        values = np.sort(rows[rows["method"] == method]["collapse_multiplier"].to_numpy()) * factor
        if len(values) == 0:
            continue
        colour = _METHOD_COLOURS.get(method, "black")
        ax_hist.hist(
            values,
            bins=edges,
            color=colour,
            alpha=0.45,
            histtype="stepfilled",
            edgecolor=colour,
            label=f"{method} ({len(values):,})",
        )
        ax_cdf.step(values, np.arange(1, len(values) + 1) / len(values), where="post", color=colour, label=method)
    ax_hist.set_xlabel(label)
    ax_hist.set_ylabel("analyses")
    ax_hist.set_title("collapse multiplier: histogram", fontsize=10)
    ax_hist.legend(fontsize=8)
    ax_cdf.set_xlabel(label)
    ax_cdf.set_ylabel("fraction of the collapses at or below")
    ax_cdf.set_ylim(0, 1)
    ax_cdf.grid(alpha=0.3)
    ax_cdf.set_title("empirical distribution function", fontsize=10)


def _axis_label(live: str) -> Tuple[str, float]:
    if live == "top_horizontal":
        return "peak horizontal force on the top beam H [kN]", 1e-3
    return "collapse multiplier λu", 1.0


def _plot_parameter(ax: Any, frame: pd.DataFrame, study: Study, name: str, live: str) -> None:
    """The collapse multiplier against one varied parameter (categories side by side for strings)."""
    label, factor = _axis_label(live)
    rows = collapses(frame)
    for method in study.methods:
        part = rows[rows["method"] == method]
        x = part[name]
        if x.dtype == object or isinstance(x.dtype, pd.StringDtype) or name == "direction":
            categories = sorted(frame[name].astype(str).unique())
            x = x.astype(str).map({c: i for i, c in enumerate(categories)}).astype(float)
            x = x + np.random.default_rng(0).uniform(-0.15, 0.15, len(x))
            ax.set_xticks(range(len(categories)), categories)
        ax.scatter(
            x,
            part["collapse_multiplier"] * factor,
            s=8,
            alpha=0.5,
            color=_METHOD_COLOURS.get(method, "black"),
            label=method,
        )
    ax.set_xlabel(name)
    ax.set_ylabel(label)
    ax.grid(alpha=0.3)


def _plot_weakest(axes: Sequence[Any], frame: pd.DataFrame, study: Study, live: str) -> None:
    """The mechanisms of the weakest analyses, each computed again from the study."""
    from ..plot import plot_mechanism

    for ax, (_, row) in zip(axes, weakest(frame, len(axes)).iterrows()):
        item = study.item(int(row["row"]))
        results, model, _ = solve(study, item)  # as the worker did: the same numbers
        plot_mechanism(ax, model, results)
        if item.values.get("direction") == "-x":
            _as_pushed_left(ax, np.asarray(model.rects)[: model.n_blocks])
        text = ax.get_title().split("\n")[-1]
        values = _values_text(row, study)
        shown = format_multiplier(float(row["collapse_multiplier"]), live, symbol=True)
        ax.set_title(
            f"row {row['row']} ({row['method']}): {shown}" + (f"\n{values}" if values else "") + f"\n{text}",
            fontsize=9,
        )


def _as_pushed_left(ax: Any, blocks: np.ndarray) -> None:
    """A mirrored wall (direction -x) drawn as the wall itself pushed towards -x: the x axis reversed, its
    labels the original x (x = s - x', s the sum of the wall's extremes)."""
    from matplotlib.ticker import FuncFormatter

    s = float(blocks[:, 0].min() + blocks[:, 2].max())
    ax.invert_xaxis()
    ax.xaxis.set_major_formatter(FuncFormatter(lambda x, _: f"{s - x:g}"))
    ax.set_xlabel("x [m] (pushed towards -x)")


def summary_figure(
    frame: pd.DataFrame,
    study: Study,
    path: Optional[Union[str, "os.PathLike[str]"]] = None,
    weakest_count: int = WEAKEST,
    dpi: int = 120,
) -> Any:
    """The summary figure of a study's rows; written as PNG (atomically) when ``path`` is given.

    First row: the histogram and the empirical distribution function of the collapse multiplier (collapse
    rows only; one colour per method). Then the multiplier against each varied parameter, three to a row.
    Last row: the mechanisms of the ``weakest_count`` weakest analyses, computed again from the study.
    """
    from ..plot.canvas import _new_figure, save_figure

    live = _live(study)
    parameters = [name for name in study.parameters]
    columns = 3
    parameter_rows = math.ceil(len(parameters) / columns)
    mechanisms = min(weakest_count, len(collapses(frame)))
    heights = [1.0] * (1 + parameter_rows) + ([1.1] if mechanisms else [])
    fig = _new_figure((13.0, 3.6 * sum(heights)), path is not None)
    grid = fig.add_gridspec(len(heights), columns, height_ratios=heights)
    _plot_distribution(fig.add_subplot(grid[0, 0:2]), fig.add_subplot(grid[0, 2]), frame, study, live)
    for k, name in enumerate(parameters):
        _plot_parameter(fig.add_subplot(grid[1 + k // columns, k % columns]), frame, study, name, live)
    if len(parameters) % columns:  # a free cell: the statuses and the statistics, as printed
        k = len(parameters)
        ax = fig.add_subplot(grid[1 + k // columns, k % columns :])
        ax.set_axis_off()
        lines = [
            line.strip()
            for line in summary_text(frame, study).splitlines()[1:]
            if not line.strip().startswith("weakest")
        ]
        wrapped = [textwrap.fill(line, 62, subsequent_indent="    ") for line in lines]
        ax.text(
            0.0, 1.0, "\n".join(wrapped), va="top", ha="left", fontsize=9, family="monospace", transform=ax.transAxes
        )
    if mechanisms:
        axes: List[Any] = [fig.add_subplot(grid[len(heights) - 1, k]) for k in range(mechanisms)]
        _plot_weakest(axes, frame, study, live)
    counts = Counter(frame["status"])
    fig.suptitle(f"{study.title}: {len(frame):,} analyses, {counts.get('collapse', 0):,} collapses", fontsize=13)
    if path is not None:
        save_figure(fig, path, dpi=dpi)
    return fig
