"""Validation against reference answers: ``masonry-dem validate``.

Every case file of a folder that carries a ``[reference]`` table (see :mod:`masonry_dem.case`) is run with
the static solver, the explicit (dynamic) one and limit analysis (or some of them), and its collapse
multiplier is compared with the reference::

    relative error = |lambda - lambda_ref| / |lambda_ref|

A case *passes* when every method run on it ended without failure (a limit analysis's "no_equilibrium" or
"unbounded" counts as one), gave a finite multiplier, and its relative error is within the case's tolerance. Case files without a ``[reference]`` table are skipped
(and listed as such).

:func:`collect` reads the folder, :func:`validate_case` runs one case, :func:`table_header`,
:func:`table_row` and :func:`table_footer` print the table row by row (so a long run shows its progress),
:func:`validate_folder` does it all and returns the rows. :func:`default_folder` is the folder validated when
none is given: the example cases shipped in the package (``masonry_dem/examples``; in the repository a symbolic
link to its ``examples/``), so ``masonry-dem validate`` works from an installed wheel, from any directory.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

from .case import METHODS, UNFINISHED_STATUSES, Case, load_case
from .report import format_multiplier

__all__ = [
    "METHOD_CHOICES",
    "ValidationRow",
    "PACKAGED_EXAMPLES",
    "collect",
    "default_folder",
    "methods_of",
    "validate_case",
    "validate_folder",
    "table_header",
    "table_row",
    "table_footer",
]

PathLike = Union[str, "os.PathLike[str]"]
#: The values of ``--method``: which solvers validate runs ("both": static and dynamic; "all": the three).
METHOD_CHOICES = METHODS + ("both", "all")
#: The column name of each method (the table's columns are in the order of METHODS).
COLUMN_NAMES = {"static": "static", "dynamic": "explicit", "limit": "limit"}
#: Statuses that count as a failed run ("interrupted": stopped by the user).
FAILED_STATUSES = ("failed", "interrupted", "no_equilibrium", "unbounded", "stalled")

#: The example case files shipped in the package: ``masonry_dem/examples`` (a wheel holds a copy; in the
#: repository it is a symbolic link to the top-level examples/, which maturin follows when it builds a wheel).
PACKAGED_EXAMPLES = Path(__file__).resolve().parent / "examples"
#: The repository's examples/, when the package runs from a checkout whose link above was not made (a checkout
#: with ``core.symlinks = false``, where the link is a small text file).
_REPOSITORY_EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

#: A solver call: (case, model, method) -> Results.
Solve = Callable[[Case, Any, str], Any]


def methods_of(choice: str) -> Tuple[str, ...]:
    """The methods run for a ``--method`` choice: "static", "dynamic", "limit", "both" (static and dynamic)
    or "all" (the three)."""
    if choice not in METHOD_CHOICES:
        raise ValueError(f"method: expected one of {', '.join(METHOD_CHOICES)}, got {choice!r}")
    if choice == "both":
        return ("static", "dynamic")
    if choice == "all":
        return METHODS
    return (choice,)


@dataclass
class ValidationRow:
    """The validation of one case.

    Attributes:
        name: the case file name without ``.toml``.
        title: the case title.
        reference: the reference collapse multiplier (a force in N with live = "top_horizontal").
        tolerance: the relative tolerance.
        live: the live load of the case ("horizontal_weight" or "top_horizontal").
        multipliers: {method: collapse multiplier} of the methods run (NaN when none).
        elapsed: {method: elapsed_s} [s].
        errors: {method: relative error} (NaN when the multiplier is not finite).
        failures: {method: reason} for the runs whose status is one of :data:`FAILED_STATUSES` ("failed",
            "interrupted", "stalled", or for limit analysis "no_equilibrium" or "unbounded").
        estimates: {method: what the number is} for the runs whose status is "estimate" (a limit analysis of
            joints with dilatancy below friction): their multiplier is its estimate, shown as ``~value``.
        methods: the methods the reference applies to (its [reference] methods).
    """

    name: str
    title: str
    reference: float
    tolerance: float
    live: str = "horizontal_weight"
    multipliers: Dict[str, float] = field(default_factory=dict)
    elapsed: Dict[str, float] = field(default_factory=dict)
    errors: Dict[str, float] = field(default_factory=dict)
    failures: Dict[str, str] = field(default_factory=dict)
    estimates: Dict[str, str] = field(default_factory=dict)
    methods: Tuple[str, ...] = METHODS

    @property
    def error(self) -> float:
        """The largest relative error of the methods run (NaN if one of them has none)."""
        values = list(self.errors.values())
        if not values or any(not math.isfinite(e) for e in values):
            return math.nan
        return max(values)

    @property
    def passed(self) -> bool:
        """True when every method ran without failure and within the tolerance."""
        return bool(self.errors) and not self.failures and math.isfinite(self.error) and self.error <= self.tolerance

    @property
    def ran(self) -> bool:
        """Whether some method was run: a case whose reference applies to none of the methods asked for (a 3D
        case, whose reference is limit analysis's, under ``--method static``) is not run, neither passed nor
        failed."""
        return bool(self.errors) or bool(self.failures)

    def verdict(self) -> str:
        """ "pass", "not run" (no method asked for applies to its reference), or "FAIL" with the reason (a failed
        run, or outside the tolerance)."""
        if self.passed:
            return "pass"
        if not self.ran:
            return "not run"
        if self.failures:
            return "FAIL (" + "; ".join(f"{m} failed" for m in self.failures) + ")"
        if not math.isfinite(self.error):
            return "FAIL (no collapse multiplier)"
        return f"FAIL (> {_percent(self.tolerance)})"


def default_folder() -> Path:
    """The folder ``masonry-dem validate`` runs without an argument: the examples shipped in the package
    (:data:`PACKAGED_EXAMPLES`, resolved: in the repository, its examples/), else the repository's examples/
    when the package runs from a checkout without the link. It does not depend on the current directory.
    When neither is a folder, the packaged one (``collect`` then reports it missing)."""
    for folder in (PACKAGED_EXAMPLES, _REPOSITORY_EXAMPLES):
        if folder.is_dir():
            return folder.resolve()
    return PACKAGED_EXAMPLES


def collect(directory: PathLike) -> Tuple[List[Tuple[Path, Case]], List[Path]]:
    """The case files (``*.toml``, sorted by name) of ``directory``, or the case file ``directory`` itself: those
    with a [reference], and the others.

    Raises:
        FileNotFoundError: no such folder or file.
        masonry_dem.InputError: a case file is invalid (the message names the file and the key).
    """
    folder = Path(directory)
    if not folder.exists():
        raise FileNotFoundError(f"no such folder or case file: {folder}")
    with_reference: List[Tuple[Path, Case]] = []
    without: List[Path] = []
    for path in sorted(folder.glob("*.toml")) if folder.is_dir() else [folder]:
        case = load_case(path)
        if case.reference is None:
            without.append(path)
        else:
            with_reference.append((path, case))
    return with_reference, without


def _default_solve(case: Case, model: Any, method: str) -> Any:
    return case.solve(model, method)


def _relative_error(value: float, reference: float) -> float:
    if not math.isfinite(value):
        return math.nan
    return abs(value - reference) / abs(reference) if reference != 0 else abs(value)


def validate_case(
    path: PathLike, case: Case, methods: Sequence[str] = METHODS, solve: Optional[Solve] = None
) -> ValidationRow:
    """Run ``case`` (which has a reference) with each of ``methods`` and compare it with its reference.

    ``solve(case, model, method)`` runs one analysis (default: :meth:`Case.solve`; the command line passes
    one that draws a progress bar).
    """
    assert case.reference is not None, f"{case.source}: no [reference] table"
    solve = solve or _default_solve
    ref = case.reference
    model = case.build_model()
    row = ValidationRow(
        name=Path(path).stem,
        title=case.title,
        reference=float(ref["collapse_multiplier"]),
        tolerance=float(ref["tolerance"]),
        live=case.live_load(model),
        methods=tuple(ref.get("methods", METHODS)),
    )
    for method in methods:
        if method not in ref.get("methods", METHODS):
            continue  # the reference does not apply to this method (shown as "-")
        results = solve(case, model, method)
        lam = float(results.collapse_multiplier)
        if results.status == "estimate":
            # a non-associative limit analysis: its number is compared, shown and counted as an estimate
            lam = float(results.last_equilibrium)
            row.estimates[method] = " ".join(str(results.error or "an estimate, neither bound").split())
        row.multipliers[method] = lam
        row.elapsed[method] = float(results.elapsed_s)
        row.errors[method] = _relative_error(lam, row.reference)
        if results.status in FAILED_STATUSES:
            reason = str(results.error or "unknown reason")
            row.failures[method] = reason if results.status in UNFINISHED_STATUSES else f"{results.status}: {reason}"
    return row


# --------------------------------------------------------------------------------------------------
# The table
# --------------------------------------------------------------------------------------------------

_HEAD = ("case", "reference", "static", "explicit", "limit", "error", "time", "verdict")
_TIME = 6  # the column of the times


def _percent(x: float) -> str:
    if not math.isfinite(x):
        return "-"
    return f"{100 * x:.2f}%" if x < 0.1 else f"{100 * x:.1f}%"


def _value(x: Optional[float], live: str) -> str:
    if x is None:
        return "-"
    return format_multiplier(x, live)


def _cell(row: ValidationRow, method: str) -> str:
    """A method's multiplier in the table: ``~value`` for an estimate, "-" when not run."""
    text = _value(row.multipliers.get(method), row.live)
    return "~" + text if method in row.estimates else text


def _time(row: ValidationRow, methods: Sequence[str]) -> str:
    return " / ".join(_seconds(row.elapsed[m]) for m in methods if m in row.elapsed)


def _seconds(t: float) -> str:
    if not math.isfinite(t):
        return "-"
    return f"{t:.3f} s" if t < 1 else f"{t:.1f} s"


def _time_head(methods: Sequence[str]) -> str:
    return "time (" + " / ".join(COLUMN_NAMES.get(m, m) for m in methods) + ")"


def _widths(names: Sequence[str], methods: Sequence[str]) -> List[int]:
    time_width = 9 * len(methods) + 3 * (len(methods) - 1)
    widths = [max([len(_HEAD[0])] + [len(n) for n in names]), 16, 10, 10, 10, 8, max(time_width, 4), 7]
    widths[_TIME] = max(widths[_TIME], len(_time_head(methods)))
    return widths


def table_header(names: Sequence[str], methods: Sequence[str]) -> str:
    """The header of the table (two lines) for cases named ``names`` run with ``methods``."""
    widths = _widths(names, methods)
    head = list(_HEAD)
    head[_TIME] = _time_head(methods)
    line = "  ".join(h.ljust(w) for h, w in zip(head, widths)).rstrip()
    return line + "\n" + "-" * len(line)


def table_row(row: ValidationRow, names: Sequence[str], methods: Sequence[str]) -> str:
    """One line of the table: case, reference (± tolerance), static, explicit, limit, error, time, verdict
    ("-" for a method not run)."""
    widths = _widths(names, methods)
    cells = [
        row.name,
        f"{_value(row.reference, row.live)} ±{_percent(row.tolerance)}",
        _cell(row, "static"),
        _cell(row, "dynamic"),
        _cell(row, "limit"),
        _percent(row.error),
        _time(row, methods),
        row.verdict(),
    ]
    return "  ".join(c.ljust(w) for c, w in zip(cells, widths)).rstrip()


def table_footer(rows: Sequence[ValidationRow], skipped: Sequence[Path]) -> str:
    """The closing lines: how many passed, the failures' reasons, the skipped files."""
    passed = sum(r.passed for r in rows)
    idle = [r for r in rows if not r.ran]
    lines = [f"{len(rows)} case{'s' if len(rows) != 1 else ''} with a reference: {passed} passed, "
             f"{len(rows) - passed - len(idle)} failed" + (f", {len(idle)} not run" if idle else "")]
    for r in rows:
        for method, reason in r.failures.items():
            lines.append(f"  {r.name}: {method} failed: {' '.join(reason.split())}")
        for method, note in r.estimates.items():
            lines.append(f"  {r.name}: {COLUMN_NAMES.get(method, method)}: estimate: {note}")
    for r in idle:
        lines.append(f"  {r.name}: not run: its reference applies to {', '.join(r.methods)} only")
    for path in skipped:
        lines.append(f"  skipped {path.name}: no [reference] table")
    return "\n".join(lines)


def validate_folder(
    directory: PathLike,
    method: str = "all",
    solve: Optional[Solve] = None,
    echo: Optional[Callable[[str], None]] = None,
) -> Tuple[List[ValidationRow], List[Path]]:
    """Validate every case of ``directory`` (a folder, or one case file) that has a [reference]; return the rows
    and the skipped files.

    ``method``: "static", "dynamic", "limit", "both" (static and dynamic) or "all". ``echo`` (e.g. ``print``) receives the table line by line
    as the cases run.
    """
    methods = methods_of(method)
    cases, skipped = collect(directory)
    names = [p.stem for p, _ in cases]
    out = echo or (lambda _line: None)
    out(table_header(names, methods))
    rows = []
    for path, case in cases:
        row = validate_case(path, case, methods, solve)
        rows.append(row)
        out(table_row(row, names, methods))
    out(table_footer(rows, skipped))
    return rows, skipped
