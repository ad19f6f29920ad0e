"""The static solver, the explicit (dynamic) one and limit analysis on one case, side by side:
``masonry-dem compare``.

:func:`agreement` measures how far the results agree: the relative difference of their collapse
multipliers, and their failed-joint patterns. An interface is *failed* at collapse (at the last converged
step; for limit analysis, in its collapse mechanism) when its state has the open (1) or the sliding (2) bit;
the patterns are compared by their counts, the number in common and the Jaccard index |S ∩ D| / |S ∪ D|
(1 when neither has a failed joint). The static run is the one the others are compared with.
:func:`comparison_dict` is the comparison file (JSON), :func:`comparison_text` the table printed by the
command line. The limit analysis is optional in every function (``limit=None``: the two incremental
solvers only, as before).

The comparison file::

    {"format": 1, "title": "...",
     "static": <result file of the static run>, "dynamic": <result file of the explicit run>,
     "limit": <result file of the limit analysis, with its certificate>,
     "agreement": {"multiplier_relative_difference": (dynamic - static) / |static|,
                   "failed_static": n, "failed_dynamic": n, "failed_common": n, "jaccard": x,
                   "failed_interfaces_static": [indices], "failed_interfaces_dynamic": [indices],
                   "iterations_static": n, "time_steps_dynamic": n,
                   "elapsed_ratio": dynamic elapsed_s / static elapsed_s,
                   # with the limit analysis:
                   "multiplier_relative_difference_limit": (limit - static) / |static|,
                   "failed_limit": n, "failed_common_limit": n (with the static run), "jaccard_limit": x,
                   "failed_interfaces_limit": [indices], "iterations_limit": n (interior point),
                   "elapsed_ratio_limit": limit elapsed_s / static elapsed_s}}

Numbers that cannot be computed (a NaN multiplier, a zero time) are null.

The comparison of a 3D wall (a :class:`masonry_dem.Model3D`) is its limit analysis alone in this version
(:func:`limit_only_text`, :func:`limit_only_dict`: ``{"format": 1, "title", "dimension": 3, "limit": <result
file>, "note": "..."}``), the static and explicit solvers named as not run (:data:`LIMIT_ONLY_NOTE`: the static
solver is the plane's; the explicit one runs with ``masonry-dem run --method dynamic``).
"""

from __future__ import annotations

import math
import os
from typing import Any, Dict, Iterable, List, Optional, Union

import numpy as np

from .case.result_file import ERROR_STATUSES, FORMAT, NOTE_STATUSES, UNFINISHED_STATUSES, result_dict, write_json
from .report import OPEN, SLIDING, _plural, certificate_text, format_multiplier

__all__ = [
    "FAILED",
    "failed_interfaces",
    "agreement",
    "comparison_dict",
    "write_comparison_json",
    "comparison_text",
    "format_difference",
    "LIMIT_ONLY_NOTE",
    "limit_only_dict",
    "limit_only_text",
]

#: What the comparison of a 3D wall says about the methods not run.
LIMIT_ONLY_NOTE = ("compare runs limit analysis alone on a 3D wall in this version: the static solver is the plane's, "
                   "and the explicit one runs with masonry-dem run --method dynamic")

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


def _multiplier_cell(results: Any, live: str) -> str:
    """The collapse multiplier of a run, or with status "estimate" its estimate marked as one (``~``)."""
    if str(results.status) == "estimate":
        return "~" + format_multiplier(float(results.last_equilibrium), live) + " (estimate)"
    return format_multiplier(float(results.collapse_multiplier), live)


def _difference(static: Any, other: Any) -> Optional[float]:
    """(other - static) / |static| of the collapse multipliers, None when one is not finite."""
    ls, lo = float(static.collapse_multiplier), float(other.collapse_multiplier)
    return _ratio(lo - ls, abs(ls)) if math.isfinite(ls) and math.isfinite(lo) else None


def agreement(static: Any, dynamic: Any, limit: Any = None) -> Dict[str, Any]:
    """How far the results of the methods agree (see the module docstring for the keys); the keys of the
    limit analysis only when ``limit`` is given."""
    diff = _difference(static, dynamic)
    fs = {int(k) for k in failed_interfaces(static)}
    fd = {int(k) for k in failed_interfaces(dynamic)}
    common, union = len(fs & fd), len(fs | fd)
    out = {
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
    if limit is not None:
        fl = {int(k) for k in failed_interfaces(limit)}
        common_l, union_l = len(fs & fl), len(fs | fl)
        out.update({
            "multiplier_relative_difference_limit": _difference(static, limit),
            "failed_limit": len(fl),
            "failed_common_limit": common_l,
            "jaccard_limit": common_l / union_l if union_l else 1.0,
            "failed_interfaces_limit": sorted(fl),
            "iterations_limit": int(limit.iterations),
            "elapsed_ratio_limit": _ratio(limit.elapsed_s, static.elapsed_s),
        })
    return out


def comparison_dict(static: Any, dynamic: Any, model: Any, title: str, limit: Any = None) -> Dict[str, Any]:
    """The comparison file as a dict, ready for ``json.dump`` (no NaN: null instead); "limit" only when
    ``limit`` is given."""
    out: Dict[str, Any] = {
        "format": FORMAT,
        "title": title,
        "static": result_dict(static, model, title),
        "dynamic": result_dict(dynamic, model, title),
    }
    if limit is not None:
        out["limit"] = result_dict(limit, model, title)
    out["agreement"] = agreement(static, dynamic, limit)
    return out


def write_comparison_json(
    path: Union[str, "os.PathLike[str]"],
    static: Any,
    dynamic: Any,
    model: Any,
    title: str,
    limit: Any = None,
    *,
    inputs: Iterable[Union[str, "os.PathLike[str]"]] = (),
) -> Dict[str, Any]:
    """Write the comparison file to ``path`` atomically (refused if not a regular file or one of
    ``inputs``, see :mod:`masonry_dem.atomic`), as the result file is written; return the dict written."""
    data = comparison_dict(static, dynamic, model, title, limit)
    write_json(path, data, inputs=inputs)
    return data


def format_difference(diff: Optional[float]) -> str:
    """A relative difference as a signed percentage with 2 decimals ("+0.12%", "0.00%"; "-" for None)."""
    if diff is None:
        return "-"
    if round(diff * 100, 2) == 0:
        return "0.00%"
    return f"{diff:+.2%}"


def _seconds(value: float) -> str:
    return f"{value:.3g} s" if math.isfinite(value) else "-"


def comparison_text(
    static: Any, dynamic: Any, model: Any, title: str, live: str = "horizontal_weight", limit: Any = None
) -> str:
    """The side-by-side table printed by ``masonry-dem compare`` (several lines, no trailing newline);
    a column for the limit analysis when ``limit`` is given."""
    agree = agreement(static, dynamic, limit)
    diff = agree["multiplier_relative_difference"]
    ratio = agree["elapsed_ratio"]
    what = "peak horizontal force" if live == "top_horizontal" else "collapse multiplier"
    runs = [("static", static), ("dynamic", dynamic)] + ([("limit", limit)] if limit is not None else [])
    results = [res for _, res in runs]
    ratio_l = agree.get("elapsed_ratio_limit")
    ratios = [f"dynamic / static = {ratio:.3g}" if ratio is not None else ""]
    failed = [str(agree["failed_static"]), str(agree["failed_dynamic"])]
    work = [f"{agree['iterations_static']:,} iterations", f"{agree['time_steps_dynamic']:,} time steps"]
    common = f"{agree['failed_common']} in common, Jaccard index {agree['jaccard']:.2f}"
    if limit is None:
        difference = "difference " + format_difference(diff)
        head = f"{title}: static and explicit (dynamic) solvers"
    else:
        difference = (f"difference from static: dynamic {format_difference(diff)}, "
                      f"limit {format_difference(agree['multiplier_relative_difference_limit'])}")
        common = (f"with static: dynamic {common}; "
                  f"limit {agree['failed_common_limit']} in common, Jaccard index {agree['jaccard_limit']:.2f}")
        ratios.append(f"limit / static = {ratio_l:.3g}" if ratio_l is not None else "")
        failed.append(str(agree["failed_limit"]))
        work.append(f"{agree['iterations_limit']:,} iterations")
        head = f"{title}: static and explicit (dynamic) solvers and limit analysis"
    rows = [
        ("", *(name for name, _ in runs), ""),
        ("status:", *(str(r.status) for r in results), ""),
        (f"{what}:", *(_multiplier_cell(r, live) for r in results), difference),
        ("failed joints:", *failed, common),
        ("work:", *work, ""),
        ("elapsed:", *(_seconds(float(r.elapsed_s)) for r in results), ", ".join(r for r in ratios if r)),
    ]
    columns = len(rows[0]) - 1
    widths = [max(len(r[i]) for r in rows) + 2 for i in range(columns)]
    lines: List[str] = [
        head,
        f"  {_plural(int(model.n_blocks), 'block')}, {_plural(int(model.n_interfaces), 'interface')}; "
        "failed joints are open or sliding at the last converged step"
        + (" (limit: in the collapse mechanism)" if limit is not None else ""),
    ]
    for row in rows:
        cells = "".join(cell.ljust(w) for cell, w in zip(row[:columns], widths)) + row[columns]
        lines.append(("  " + cells).rstrip())
    for name, res in runs:
        if res.status in UNFINISHED_STATUSES:
            lines.append(f"  {name} failed: {res.error or 'unknown reason'}")
        elif res.status in ERROR_STATUSES or res.status in NOTE_STATUSES:
            lines.append(f"  {name}: {res.status}: {res.error or 'no reason given'}")
    if limit is not None:
        for k, text in enumerate(certificate_text(limit, live)):
            lines.append(f"  {'limit certificate:' if k == 0 else '':<19}{text}")
    return "\n".join(lines)


def limit_only_dict(limit: Any, model: Any, title: str) -> Dict[str, Any]:
    """The comparison file of a 3D wall: its limit analysis alone (:data:`LIMIT_ONLY_NOTE`)."""
    return {"format": FORMAT, "title": title, "dimension": 3, "limit": result_dict(limit, model, title),
            "note": LIMIT_ONLY_NOTE}


def limit_only_text(limit: Any, model: Any, title: str, live: str = "horizontal_weight") -> str:
    """What ``masonry-dem compare`` prints for a 3D wall: its limit analysis (status, collapse multiplier, failed
    joints, work, time, certificate) and a line saying that the other methods are not run."""
    lines = [
        f"{title}: limit analysis (3D)",
        f"  {_plural(int(model.n_blocks), 'block')}, {_plural(int(model.n_interfaces), 'interface')}; "
        "failed joints are open or sliding in the collapse mechanism",
        f"  status:              {limit.status}",
        f"  collapse multiplier: {_multiplier_cell(limit, live)}",
        f"  failed joints:       {len(failed_interfaces(limit))}",
        f"  work:                {int(limit.iterations):,} interior-point iterations",
        f"  elapsed:             {_seconds(float(limit.elapsed_s))}",
        f"  static, dynamic:     not run ({LIMIT_ONLY_NOTE.split(':')[0]})",
    ]
    if limit.status in UNFINISHED_STATUSES:
        lines.append(f"  limit failed: {limit.error or 'unknown reason'}")
    elif limit.status in ERROR_STATUSES or limit.status in NOTE_STATUSES:
        lines.append(f"  limit: {limit.status}: {limit.error or 'no reason given'}")
    for k, text in enumerate(certificate_text(limit, live)):
        lines.append(f"  {'limit certificate:' if k == 0 else '':<21}{text}")
    return "\n".join(lines)
