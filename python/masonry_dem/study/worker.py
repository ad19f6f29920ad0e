"""What a worker runs: :func:`run_chunk`, a few analyses of a study, each built from the study's case data
in the worker and turned into one row (:func:`run_item`). No analysis raises: a bad sample or an error of
the machinery becomes a row with status "error" and the message, so that the study goes on.

A row holds the analysis's identity (row, method, direction, the varied parameters, sample, seed) and its
outcome: status, collapse_multiplier (NaN unless the status is "collapse"; with live = "top_horizontal" the
peak force on the top beam [N]), last_equilibrium, iterations, steps, blocks, elapsed_s (the solver's time
[s]), task_s (the row's time in the worker [s]: building the case and the model, solving, the row) and error.
A study whose base case has an [assessment] table checks each collapse against it (:data:`ASSESSMENT_COLUMNS`:
the verdict of every check made, the linear kinematic check's ratio a0* / demand, a0* and the demand [m/s2], and
the site's peak ground acceleration a_g S [m/s2]); a check that is refused leaves them empty and says why in error.
"""

from __future__ import annotations

import math
import time
from typing import Any, Dict, List, Sequence

from .._core import InputError
from ..case import ERROR_STATUSES
from .model import Item, Study

#: The statuses of the study's own rows, besides the core's (``Results.status``): "error", the analysis
#: raised (a sample that makes a bad model: the InputError's message); "lost", its worker died every time
#: it ran it.
STUDY_STATUSES = ("error", "lost")
#: The rows that reached no answer: the solver failed or stopped, or the analysis raised or was lost.
FAILED_STATUSES = ("failed", "stalled", "interrupted") + STUDY_STATUSES

#: The outcome columns of a row, in order, with their types ("float", "int", "str").
OUTCOME_COLUMNS = (
    ("status", "str"),
    ("collapse_multiplier", "float"),
    ("last_equilibrium", "float"),
    ("iterations", "int"),
    ("steps", "int"),
    ("blocks", "int"),
    ("elapsed_s", "float"),
    ("task_s", "float"),
    ("error", "str"),
)


#: The seismic check's columns of a study whose base case has an [assessment] table.
ASSESSMENT_COLUMNS = (
    ("verdict", "str"),
    ("ratio", "float"),
    ("a0_star", "float"),
    ("demand", "float"),
    ("pga", "float"),
)


def identity(study: Study, item: Item) -> Dict[str, Any]:
    """The columns that name an analysis: row, method, direction, the varied parameters, sample, seed."""
    row: Dict[str, Any] = {"row": item.row, "method": item.method, "direction": item.values.get("direction", "+x")}
    row.update((name, value) for name, value in item.values.items() if name != "direction")
    row.update(sample=item.sample, seed=study.seed)
    return row


def failed_row(study: Study, item: Item, status: str, error: str) -> Dict[str, Any]:
    """The row of an analysis that gave no results (status "error" or "lost")."""
    row = identity(study, item)
    row.update(
        status=status,
        collapse_multiplier=math.nan,
        last_equilibrium=math.nan,
        iterations=0,
        steps=0,
        blocks=0,
        elapsed_s=math.nan,
        task_s=math.nan,
        error=" ".join(error.split()),
    )
    if study.assesses:
        row.update(verdict=None, ratio=math.nan, a0_star=math.nan, demand=math.nan, pga=math.nan)
    return row


def solve(study: Study, item: Item) -> Any:
    """Build and solve one analysis: (results, model, case; None for a builder's)."""
    if callable(study.base):
        model = study.base(**item.values)
        # one thread per worker: the explicit solver, and limit analysis in 3D
        one_thread = item.method == "dynamic" or (item.method == "limit" and model.dimension == 3)
        options = {"threads": 1} if one_thread else {}
        return getattr(model, f"solve_{item.method}")(**options), model, None
    case = study.case(item)
    model = case.build_model()
    return case.solve(model, item.method), model, case


def check(row: Dict[str, Any], results: Any, model: Any, case: Any) -> None:
    """The seismic check's columns of ``row`` (:data:`ASSESSMENT_COLUMNS`) from the case's [assessment]: empty
    without a collapse, and with the refusal in ``error`` when a check refuses the mechanism or the curve."""
    from ..assessment.verdict import assess

    parameters = case.assessment
    row.update(verdict=None, ratio=math.nan, a0_star=math.nan, demand=math.nan,
               pga=parameters.spectrum.peak_ground_acceleration)
    if row["status"] != "collapse":
        return
    try:
        checked = assess(model, results, parameters, gravity=case.model_kwargs["gravity"])
    except InputError as exc:
        row["error"] = f"assessment: {' '.join(str(exc).split())}"
        return
    row["verdict"] = checked.verdict
    if checked.linear is not None:
        row.update(ratio=checked.linear.ratio, a0_star=checked.linear.a0_star, demand=checked.linear.demand)


def run_item(study: Study, item: Item) -> Dict[str, Any]:
    """One analysis as a row; an exception becomes a row with status "error"."""
    start = time.perf_counter()
    try:
        results, model, case = solve(study, item)
    except Exception as exc:  # a bad sample, or a builder's error: the study goes on
        row = failed_row(study, item, "error", f"{type(exc).__name__}: {exc}")
        row["task_s"] = time.perf_counter() - start
        return row
    status = str(results.status)
    row = identity(study, item)
    row.update(
        status=status,
        collapse_multiplier=float(results.collapse_multiplier) if status == "collapse" else math.nan,
        last_equilibrium=float(results.last_equilibrium),
        iterations=int(results.iterations),
        steps=int(results.steps),
        blocks=int(model.n_blocks),
        elapsed_s=float(results.elapsed_s),
        error=" ".join(str(results.error or "unknown reason").split()) if status in ERROR_STATUSES else None,
    )
    if study.assesses:
        check(row, results, model, case)
    row["task_s"] = time.perf_counter() - start
    return row


def run_chunk(study: Study, items: Sequence[Item]) -> List[Dict[str, Any]]:
    """The rows of a few analyses, run one after the other (a Dask task)."""
    return [run_item(study, item) for item in items]
