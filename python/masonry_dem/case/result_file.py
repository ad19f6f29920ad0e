"""The result file (JSON, format 1 of docs/case-format.md): :func:`result_dict` and its one writer,
:func:`write_result_json` (atomic, through :mod:`masonry_dem.atomic`)."""

from __future__ import annotations

import json
import math
import os
from typing import Any, Dict, Iterable, Mapping, Optional, Union

import numpy as np

from ..atomic import write_text
from .table import FORMAT as FORMAT  # the version of the case-file and result-file format

PathLike = Union[str, "os.PathLike[str]"]

JOINT_STATE_KEYS = ("elastic", "sliding", "rocking", "open")
#: The keys of a limit analysis's certificate (``Results.certificate``), in the result file's order.
CERTIFICATE_KEYS = (
    "multiplier",
    "primal_residual",
    "dual_residual",
    "duality_gap",
    "iterations",
    "upper_bound",
    "sequence",
    "sequence_converged",
    "peak_strengths",
)
#: The statuses that come with a reason in ``Results.error`` (and an ``error`` key in the result file).
#: "interrupted": stopped by the user (Ctrl-C); a core before that status reports it as "failed".
ERROR_STATUSES = ("failed", "interrupted", "no_equilibrium", "unbounded", "stalled", "displacement_limit")
#: The statuses of a run that did not end: the solver failed, or the user stopped it. Their reason
#: (``Results.error``) says which, so the messages give it alone, without the status.
UNFINISHED_STATUSES = ("failed", "interrupted")
#: The statuses of a run that ended with a number that is not a collapse multiplier, and a line that says
#: what it is (``Results.error``; a ``note`` key in the result file): "estimate", the non-associative limit
#: analysis, whose value is ``last_equilibrium``.
NOTE_STATUSES = ("estimate",)


def json_float(x: Any) -> Optional[float]:
    """A float for JSON, or None (null) when not finite: JSON has no NaN."""
    x = float(x)
    return x if math.isfinite(x) else None


def result_dict(results: Any, model: Any, title: str) -> Dict[str, Any]:
    """The result file of docs/case-format.md as a dict, ready for ``json.dump``.

    ``results`` is a :class:`masonry_dem.Results`, ``model`` the :class:`masonry_dem.Model` it came
    from (for the numbers of blocks and interfaces). Non-finite numbers become None (JSON null): a
    ``collapse_multiplier`` that is NaN (no collapse: a failed run, or a limit analysis whose status is
    "no_equilibrium" or "unbounded") is written as null. ``curve.displacement`` and ``elapsed_s`` are in m
    and s.

    A limit analysis (method "limit": its curve is empty unless it followed the mechanism) also gets
    ``certificate``: an object with the keys of :data:`CERTIFICATE_KEYS` (``upper_bound`` null unless some joint is
    non-associative), or null
    when the run was interrupted; so does a static load-control analysis of associative dry joints, whose
    collapse is checked against limit analysis (its certificate is the evidence). ``error`` is written with
    the statuses that have a reason: "failed", "interrupted", "no_equilibrium", "unbounded", "stalled" and
    "displacement_limit"; ``note`` with "estimate" (a limit analysis of joints with dilatancy below friction:
    what the number in ``last_equilibrium`` is), and with a collapse whose mechanism was followed
    (``follow_mechanism``) when its curve stopped short of lambda = 0 (why). ``bracket`` (explicit load control
    ending in a collapse): the highest level that settled and the lowest that ran away. ``collapse_multiplier`` is null unless the
    status is "collapse";
    ``last_equilibrium`` is the largest multiplier at which the wall was found in equilibrium (equal to
    ``collapse_multiplier`` on a collapse; null when none was found). The results of a 3D wall (a
    :class:`masonry_dem.Model3D`, ``Results.dimension`` 3) get ``"dimension": 3`` after the title; a wall in the
    plane's file has no such key.
    """
    states = getattr(results, "joint_states", None) or {}
    out: Dict[str, Any] = {"format": FORMAT, "title": title}
    if int(getattr(results, "dimension", 2)) == 3:
        out["dimension"] = 3  # a wall of boxes (left out for a wall in the plane: a file without it is 2D)
    out.update({
        "method": str(results.method),
        "status": str(results.status),
        "blocks": int(model.n_blocks),
        "interfaces": int(model.n_interfaces),
        "collapse_multiplier": json_float(results.collapse_multiplier),
        "last_equilibrium": json_float(getattr(results, "last_equilibrium", math.nan)),
        "curve": {
            "multiplier": [json_float(x) for x in np.asarray(results.curve_multiplier, dtype=float)],
            "displacement": [json_float(x) for x in np.asarray(results.curve_displacement, dtype=float)],
        },
        "joint_states": {key: int(states.get(key, 0)) for key in JOINT_STATE_KEYS},
        "elapsed_s": json_float(results.elapsed_s),
    })
    if out["method"] == "limit" or getattr(results, "certificate", None) is not None:
        out["certificate"] = certificate_dict(getattr(results, "certificate", None))
    if out["status"] in ERROR_STATUSES:
        out["error"] = str(results.error) if results.error else "unknown error"
    if out["status"] in NOTE_STATUSES:
        out["note"] = str(results.error or "")
    elif out["status"] not in ERROR_STATUSES and getattr(results, "error", None):
        # limit analysis along the mechanism: why its curve stopped short; a support's movement that stood to the
        # end of its steps: so
        out["note"] = str(results.error)
    bracket = getattr(results, "bracket", None)
    if bracket is not None:
        out["bracket"] = [json_float(bracket[0]), json_float(bracket[1])]
    return out


def certificate_dict(certificate: Optional[Mapping[str, Any]]) -> Optional[Dict[str, Any]]:
    """A limit analysis's certificate (``Results.certificate``) with plain JSON values, or None.

    Floats that are not finite (or missing) become None, counts ints, flags bools."""
    if certificate is None:
        return None
    out: Dict[str, Any] = {}
    for key in CERTIFICATE_KEYS:
        value = certificate.get(key)
        if key in ("iterations", "sequence"):
            out[key] = None if value is None else int(value)
        elif key in ("sequence_converged", "peak_strengths"):
            out[key] = None if value is None else bool(value)
        else:
            out[key] = None if value is None else json_float(value)
    return out


def write_json(path: PathLike, data: Any, inputs: Iterable[PathLike] = ()) -> None:
    """Write ``data`` as indented JSON (no NaN) to ``path`` atomically (:func:`masonry_dem.atomic.write_text`):
    the result file here, the comparison file of :mod:`masonry_dem.compare`."""
    write_text(path, json.dumps(data, indent=2, allow_nan=False) + "\n", inputs=inputs)


def write_result_json(
    path: PathLike, results: Any, model: Any, title: str, *, inputs: Iterable[PathLike] = ()
) -> Dict[str, Any]:
    """Write the result file (see :func:`result_dict`) to ``path``; return the dict written.

    The file is written atomically (:func:`masonry_dem.atomic.write_text`): a target that is not a regular
    file, or is one of ``inputs`` (the case file), is refused with InputError."""
    data = result_dict(results, model, title)
    write_json(path, data, inputs=inputs)
    return data
