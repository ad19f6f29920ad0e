"""The static and the explicit (dynamic) solver on one case, side by side: ``masonry-dem compare``.

:func:`agreement` measures how far two results agree: the relative difference of their collapse
multipliers, and their failed-joint patterns. An interface is *failed* at collapse (at the last converged
step) when its state has the open (1) or the sliding (2) bit; the patterns are compared by their counts,
the number in common and the Jaccard index |S ∩ D| / |S ∪ D| (1 when neither has a failed joint).
:func:`comparison_dict` is the comparison file (JSON), :func:`comparison_text` the table printed by the
command line.

The comparison file::

    {"format": 1, "title": "...",
     "static": <result file of the static run>, "dynamic": <result file of the explicit run>,
     "agreement": {"multiplier_relative_difference": (dynamic - static) / |static|,
                   "failed_static": n, "failed_dynamic": n, "failed_common": n, "jaccard": x,
                   "failed_interfaces_static": [indices], "failed_interfaces_dynamic": [indices],
                   "iterations_static": n, "time_steps_dynamic": n,
                   "elapsed_ratio": dynamic elapsed_s / static elapsed_s}}

Numbers that cannot be computed (a NaN multiplier, a zero time) are null.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any, Dict, List, Optional, Union

import numpy as np

from .case import FORMAT, result_dict
from .report import OPEN, SLIDING, _plural

__all__ = [
    "FAILED",
    "failed_interfaces",
    "agreement",
    "comparison_dict",
    "write_comparison_json",
    "comparison_text",
    "format_difference",
]

#: The state bits of a failed interface: open or sliding.
FAILED = OPEN | SLIDING


def failed_interfaces(results: Any) -> np.ndarray:
    """Indices (sorted) of the interfaces that are open or sliding at the last converged step."""
    states = np.asarray(results.interface_states, dtype=np.int64).reshape(-1)
    return np.flatnonzero(states & FAILED)


def _ratio(num: float, den: float) -> Optional[float]:
    num, den = float(num), float(den)
    if not (math.isfinite(num) and math.isfinite(den)) or den == 0:
        return None
    return num / den


def agreement(static: Any, dynamic: Any) -> Dict[str, Any]:
    """How far the results of the two methods agree (see the module docstring for the keys)."""
    ls, ld = float(static.collapse_multiplier), float(dynamic.collapse_multiplier)
    diff = _ratio(ld - ls, abs(ls)) if math.isfinite(ls) and math.isfinite(ld) else None
    fs = {int(k) for k in failed_interfaces(static)}
    fd = {int(k) for k in failed_interfaces(dynamic)}
    common, union = len(fs & fd), len(fs | fd)
    return {
        "multiplier_relative_difference": diff,
        "failed_static": len(fs),
        "failed_dynamic": len(fd),
        "failed_common": common,
        "jaccard": common / union if union else 1.0,
        "failed_interfaces_static": sorted(fs),
        "failed_interfaces_dynamic": sorted(fd),
        "iterations_static": int(static.iterations),
        "time_steps_dynamic": int(dynamic.iterations),
        "elapsed_ratio": _ratio(dynamic.elapsed_s, static.elapsed_s),
    }


def comparison_dict(static: Any, dynamic: Any, model: Any, title: str) -> Dict[str, Any]:
    """The comparison file as a dict, ready for ``json.dump`` (no NaN: null instead)."""
    return {
        "format": FORMAT,
        "title": title,
        "static": result_dict(static, model, title),
        "dynamic": result_dict(dynamic, model, title),
        "agreement": agreement(static, dynamic),
    }


def write_comparison_json(
    path: Union[str, "os.PathLike[str]"], static: Any, dynamic: Any, model: Any, title: str
) -> Dict[str, Any]:
    """Write the comparison file to ``path``; return the dict written."""
    data = comparison_dict(static, dynamic, model, title)
    Path(path).write_text(json.dumps(data, indent=2, allow_nan=False) + "\n", encoding="utf-8")
    return data


def format_difference(diff: Optional[float]) -> str:
    """A relative difference as a signed percentage with 2 decimals ("+0.12%", "0.00%"; "-" for None)."""
    if diff is None:
        return "-"
    if round(diff * 100, 2) == 0:
        return "0.00%"
    return f"{diff:+.2%}"


def _multiplier(value: float, live: str) -> str:
    if not math.isfinite(value):
        return "none"
    if live == "top_horizontal":
        return f"{value / 1e3:.3f} kN"
    return f"{value:.4f}"


def _seconds(value: float) -> str:
    return f"{value:.3g} s" if math.isfinite(value) else "-"


def comparison_text(static: Any, dynamic: Any, model: Any, title: str, live: str = "horizontal_weight") -> str:
    """The side-by-side table printed by ``masonry-dem compare`` (several lines, no trailing newline)."""
    agree = agreement(static, dynamic)
    diff = agree["multiplier_relative_difference"]
    ratio = agree["elapsed_ratio"]
    what = "peak horizontal force" if live == "top_horizontal" else "collapse multiplier"
    rows = [
        ("", "static", "dynamic", ""),
        ("status:", str(static.status), str(dynamic.status), ""),
        (
            f"{what}:",
            _multiplier(float(static.collapse_multiplier), live),
            _multiplier(float(dynamic.collapse_multiplier), live),
            "difference " + format_difference(diff),
        ),
        (
            "failed joints:",
            str(agree["failed_static"]),
            str(agree["failed_dynamic"]),
            f"{agree['failed_common']} in common, Jaccard index {agree['jaccard']:.2f}",
        ),
        (
            "work:",
            f"{agree['iterations_static']:,} iterations",
            f"{agree['time_steps_dynamic']:,} time steps",
            "",
        ),
        (
            "elapsed:",
            _seconds(float(static.elapsed_s)),
            _seconds(float(dynamic.elapsed_s)),
            f"dynamic / static = {ratio:.3g}" if ratio is not None else "",
        ),
    ]
    widths = [max(len(r[i]) for r in rows) + 2 for i in range(3)]
    lines: List[str] = [
        f"{title}: static and explicit (dynamic) solvers",
        f"  {_plural(int(model.n_blocks), 'block')}, {_plural(int(model.n_interfaces), 'interface')}; "
        "failed joints are open or sliding at the last converged step",
    ]
    for row in rows:
        cells = "".join(cell.ljust(w) for cell, w in zip(row[:3], widths)) + row[3]
        lines.append(("  " + cells).rstrip())
    for name, res in (("static", static), ("dynamic", dynamic)):
        if res.status == "failed":
            lines.append(f"  {name} failed: {res.error or 'unknown reason'}")
    return "\n".join(lines)
