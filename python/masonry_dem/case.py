"""Case files (TOML, format 1) and result files (JSON, format 1).

The keys are a public contract, described in ``docs/case-format.md``; this module follows it exactly:

* :func:`load_case` reads a case file, :func:`parse_case` a TOML string, :func:`case_from_dict` an
  already parsed table. Every key and type is checked by name before anything is computed; a bad
  case raises :class:`masonry_dem.InputError` with a one-line message that starts with the file name
  and names the key with its table path, e.g. ``wall.toml: unknown key 'frictoin' in [joints.bed]``.
* :class:`Case` maps the case onto the core: ``build_model()`` gives a :class:`masonry_dem.Model`,
  ``run()`` the :class:`masonry_dem.Results` of the analysis, with the static solver
  (``Model.solve_static``), the explicit one (``Model.solve_dynamic``) or limit analysis
  (``Model.solve_limit``).
* :func:`result_dict` / :func:`write_result_json` produce the result file.

Units are SI throughout: m, N, Pa, kg, s.
"""

from __future__ import annotations

import difflib
import json
import math
import os
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Sequence, Union

import numpy as np

from . import _core
from ._core import InputError, MasonryError

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python < 3.11 only
    import tomli as tomllib

__all__ = [
    "FORMAT",
    "METHODS",
    "CERTIFICATE_KEYS",
    "Case",
    "load_case",
    "parse_case",
    "case_from_dict",
    "run_case",
    "result_dict",
    "certificate_dict",
    "write_result_json",
]

#: The version of the case-file and result-file format this module reads and writes.
FORMAT = 1

PathLike = Union[str, "os.PathLike[str]"]

# Keys of a joint law, in the order of docs/case-format.md, and the interface families that may override them.
# the joint-law keys come from the core, which defines the law
LAW_KEYS = tuple(_core.JOINT_LAW_KEYS)
FAMILIES = ("bed", "head", "base", "top")
GEOMETRY_KINDS = ("running_bond", "pattern", "blocks")
METHODS = ("static", "dynamic", "limit")
# Keys of [analysis]: those of the incremental methods (static and dynamic), then those of the explicit solver
# only. Limit analysis (method = "limit") has no load path: it uses none of them (they are checked, then ignored).
ANALYSIS_KEYS = ("method", "control", "control_point", "max_displacement", "steps", "tolerance")
DYNAMIC_KEYS = ("damping", "damping_coefficient", "time_step", "unbalanced_ratio", "threads")
DAMPINGS = ("local", "viscous", "none")
# Keys of the optional [reference] table (a published or exact answer, checked by ``masonry-dem validate``).
REFERENCE_KEYS = ("collapse_multiplier", "tolerance", "source", "methods")
DEFAULT_REFERENCE_TOLERANCE = 0.01


# --------------------------------------------------------------------------------------------------
# Validation helpers
# --------------------------------------------------------------------------------------------------


def _type_name(value: Any) -> str:
    """The TOML name of the type of a parsed value (for error messages)."""
    if isinstance(value, bool):
        return "boolean"
    if isinstance(value, int):
        return "integer"
    if isinstance(value, float):
        return "float"
    if isinstance(value, str):
        return "string"
    if isinstance(value, list):
        return "array"
    if isinstance(value, dict):
        return "table"
    return type(value).__name__  # datetime, date, time


def _is_number(value: Any) -> bool:
    """True for TOML integers and floats; booleans are not numbers."""
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _quote(value: Any) -> str:
    return json.dumps(value) if isinstance(value, str) else repr(value)


def _int_text(value: int) -> str:
    """An integer for a message: its digits, or how many there are when it is long."""
    return str(value) if abs(value) < 10**30 else f"an integer of {len(str(abs(value)))} digits"


def _got(value: Any) -> str:
    """'got <type> <value>' for a type error: the TOML type, and the value itself when it is short."""
    name = _type_name(value)
    if isinstance(value, (str, bool)) or (_is_number(value) and not isinstance(value, int)):
        shown = _quote(value) if not isinstance(value, bool) else ("true" if value else "false")
    elif isinstance(value, int):
        shown = _int_text(value)
    else:
        return f"got {name}"
    if len(shown) > 40:
        shown = shown[:37] + "..."
    return f"got {name} {shown}"


def _positive(x: float) -> Optional[str]:
    return None if x > 0 else "must be > 0"


def _non_negative(x: float) -> Optional[str]:
    return None if x >= 0 else "must be >= 0"


def _open_unit(x: float) -> Optional[str]:
    return None if 0 < x < 1 else "must lie in (0, 1)"


class _Table:
    """A parsed TOML table with its path, for key-by-key validation with precise messages.

    ``path`` is the dotted table path ("" for the top level, "joints.bed", ...). The constructor
    refuses keys outside ``allowed`` at once, so that a typo is reported as an unknown key rather
    than as a missing one.
    """

    def __init__(self, data: Mapping[str, Any], path: str, source: str, allowed: Sequence[str]) -> None:
        self.data = data
        self.path = path
        self.source = source
        for key in data:
            if key not in allowed:
                where = f"in [{path}]" if path else "at the top level"
                close = difflib.get_close_matches(key, allowed, n=1)
                hint = f" (did you mean '{close[0]}'?)" if close else f" (allowed: {', '.join(allowed)})"
                raise self.error(f"unknown key '{_short(key)}' {where}{hint}")

    # -- messages ----------------------------------------------------------------------------------

    def error(self, message: str) -> InputError:
        """An InputError whose message starts with the file name."""
        return InputError(f"{self.source}: {message}")

    def where(self, key: str) -> str:
        """The dotted key, 'path.key' (or just 'key' at the top level), the prefix of a message about one value."""
        return f"{self.path}.{key}" if self.path else key

    def key_error(self, key: str, message: str) -> InputError:
        return self.error(f"{self.where(key)}: {message}")

    def missing(self, key: str) -> InputError:
        where = f"in [{self.path}]" if self.path else "at the top level"
        return self.error(f"missing key '{key}' {where}")

    # -- typed getters -----------------------------------------------------------------------------

    def __contains__(self, key: str) -> bool:
        return key in self.data

    def _get(self, key: str, required: bool) -> Any:
        if key not in self.data:
            if required:
                raise self.missing(key)
            return None
        return self.data[key]

    def number(
        self,
        key: str,
        default: Optional[float] = None,
        check: Optional[Callable[[float], Optional[str]]] = None,
    ) -> float:
        """A finite float (TOML integer or float, not boolean); required when ``default`` is None."""
        value = self._get(key, default is None)
        if value is None:
            return float(default)  # type: ignore[arg-type]
        return self._number_value(self.where(key), value, check)

    def _number_value(self, label: str, value: Any, check: Optional[Callable[[float], Optional[str]]] = None) -> float:
        if not _is_number(value):
            raise self.error(f"{label}: expected a number, {_got(value)}")
        try:
            x = float(value)
        except OverflowError:  # an integer beyond the range of a float
            raise self.error(f"{label}: expected a finite number, {_got(value)}") from None
        if not math.isfinite(x):
            raise self.error(f"{label}: expected a finite number, got {value}")
        if check is not None:
            problem = check(x)
            if problem:
                raise self.error(f"{label}: {problem}, got {_int_text(value) if isinstance(value, int) else value}")
        return x

    def integer(
        self, key: str, default: Optional[int] = None, minimum: Optional[int] = None, maximum: int = 2**31 - 1
    ) -> int:
        """An integer (not a float, not a boolean) in [minimum, maximum]; required when ``default`` is None."""
        value = self._get(key, default is None)
        if value is None:
            return int(default)  # type: ignore[arg-type]
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.key_error(key, f"expected an integer, {_got(value)}")
        if minimum is not None and value < minimum:
            raise self.key_error(key, f"must be >= {minimum}, got {_int_text(value)}")
        if value > maximum:
            raise self.key_error(key, f"must be <= {maximum}, got {_int_text(value)}")
        return value

    def string(self, key: str, default: Optional[str] = None, choices: Optional[Sequence[str]] = None) -> str:
        """A string, one of ``choices`` if given; required when ``default`` is None."""
        value = self._get(key, default is None)
        if value is None:
            return str(default)
        if not isinstance(value, str):
            raise self.key_error(key, f"expected a string, {_got(value)}")
        if choices is not None and value not in choices:
            options = ", ".join(_quote(c) for c in choices)
            raise self.key_error(key, f"expected one of {options}, got {_quote(value)}")
        return value

    def table(self, key: str, allowed: Sequence[str], required: bool = False) -> Optional["_Table"]:
        """A sub-table (checked for unknown keys), or None when absent and not required."""
        value = self._get(key, required)
        if value is None:
            return None
        if not isinstance(value, dict):
            raise self.key_error(key, f"expected a table, got {_type_name(value)}")
        path = f"{self.path}.{key}" if self.path else key
        return _Table(value, path, self.source, allowed)

    def array(self, key: str, required: bool = True) -> Optional[List[Any]]:
        value = self._get(key, required)
        if value is None:
            return None
        if not isinstance(value, list):
            raise self.key_error(key, f"expected an array, got {_type_name(value)}")
        return value

    def numbers(self, label: str, value: Any, length: Optional[int] = None, what: str = "") -> List[float]:
        """An array of finite numbers (of ``length`` entries if given); ``label`` names it in messages."""
        if not isinstance(value, list):
            expected = f"an array of {length} numbers{what}" if length else "an array of numbers"
            raise self.error(f"{label}: expected {expected}, got {_type_name(value)}")
        if length is not None and len(value) != length:
            raise self.error(f"{label}: expected {length} numbers{what}, got {len(value)}")
        return [self._number_value(f"{label}[{i}]", v) for i, v in enumerate(value)]

    def rectangles(self, key: str, required: bool = True) -> Optional[List[List[float]]]:
        """An array of rectangles [x0, y0, x1, y1] [m] with x1 > x0 and y1 > y0."""
        items = self.array(key, required)
        if items is None:
            return None
        rects = []
        for i, item in enumerate(items):
            label = f"{self.where(key)}[{i}]"
            x0, y0, x1, y1 = self.numbers(label, item, 4, " [x0, y0, x1, y1]")
            if not (x1 > x0 and y1 > y0):
                raise self.error(f"{label}: expected x1 > x0 and y1 > y0, got {item}")
            rects.append([x0, y0, x1, y1])
        return rects


# --------------------------------------------------------------------------------------------------
# The case
# --------------------------------------------------------------------------------------------------


@dataclass
class Case:
    """One wall and one analysis, as read from a case file.

    Attributes:
        title: the case title.
        model_kwargs: keyword arguments of :class:`masonry_dem.Model` (``blocks`` as an (n, 4) array
            of rectangles [x0, y0, x1, y1] in m, thickness [m], density [kg/m3], base, top_rotation,
            top_force [N], joints, gravity [m/s2], live).
        analysis_kwargs: keyword arguments common to :meth:`masonry_dem.Model.solve_static` and
            :meth:`masonry_dem.Model.solve_dynamic` (control, steps, max_displacement [m],
            control_block, and tolerance when the case gives it); limit analysis
            (:meth:`masonry_dem.Model.solve_limit`) ignores them.
        dynamic_kwargs: keyword arguments of :meth:`masonry_dem.Model.solve_dynamic` only, those the
            case gives (damping, damping_coefficient, time_step [s], unbalanced_ratio, threads); the
            static solver ignores them.
        method: "static", "dynamic" or "limit".
        source: where the case came from (file name), the first word of every error message.
        reference: the optional [reference] table, or None: ``{"collapse_multiplier": float,
            "tolerance": float, "source": str}`` (the multiplier is a force in N with
            live = "top_horizontal"; tolerance is relative, default 0.01; source may be "").
            ``masonry-dem validate`` checks the case against it.
    """

    title: str
    model_kwargs: Dict[str, Any]
    analysis_kwargs: Dict[str, Any] = field(default_factory=dict)
    method: str = "static"
    source: str = "<case>"
    dynamic_kwargs: Dict[str, Any] = field(default_factory=dict)
    reference: Optional[Dict[str, Any]] = None

    def build_model(self) -> "_core.Model":
        """Build the model; errors of the core are re-raised with the file name in front."""
        try:
            return _core.Model(**self.model_kwargs)
        except MasonryError as exc:
            raise type(exc)(f"{self.source}: {exc}") from exc

    def check_method(self, method: Optional[str] = None) -> str:
        """The method to use, ``method`` ("static" | "dynamic" | "limit") overriding the case's.

        Raises:
            masonry_dem.InputError: an unknown method.
        """
        method = self.method if method is None else method
        if method not in METHODS:
            expected = ", ".join(_quote(m) for m in METHODS)
            raise InputError(f"{self.source}: method: expected one of {expected}, got {_quote(method)}")
        return method

    def solver_kwargs(self, method: Optional[str] = None) -> Dict[str, Any]:
        """The keyword arguments of the solver of ``method`` (default: the case's), without ``progress``.

        Limit analysis takes none of the case's [analysis] keys (they describe a load path: control,
        steps, max_displacement, and tolerance, the precision of the incremental solvers' multiplier);
        ``Model.solve_limit`` runs with its own defaults."""
        method = self.check_method(method)
        if method == "limit":
            return {}
        kwargs = {k: v for k, v in self.analysis_kwargs.items() if not (k == "max_displacement" and v is None)}
        if method == "dynamic":
            kwargs.update(self.dynamic_kwargs)
        return kwargs

    def solve(
        self,
        model: "_core.Model",
        method: Optional[str] = None,
        progress: Optional[Callable[[int, float, float, float], None]] = None,
    ) -> "_core.Results":
        """Run the analysis of this case on ``model`` (built by :meth:`build_model`).

        ``method`` overrides the case's [analysis] method: "static" calls ``Model.solve_static``,
        "dynamic" ``Model.solve_dynamic``, "limit" ``Model.solve_limit``. ``progress``, if given, is the
        solvers' progress callback ``(step, multiplier, displacement, fraction)`` (limit analysis: the
        interior-point iteration, the current multiplier, NaN, NaN). The solvers never raise for a solver failure:
        check ``Results.status`` and ``Results.error``. Errors of the core about the input (e.g. a
        time_step above the stability limit) are re-raised with the file name in front.
        """
        method = self.check_method(method)
        kwargs = self.solver_kwargs(method)
        if progress is not None:
            kwargs["progress"] = progress
        solver = {"static": model.solve_static, "dynamic": model.solve_dynamic, "limit": model.solve_limit}[method]
        try:
            return solver(**kwargs)
        except MasonryError as exc:
            raise type(exc)(f"{self.source}: {exc}") from exc

    def run(
        self,
        method: Optional[str] = None,
        progress: Optional[Callable[[int, float, float, float], None]] = None,
    ) -> "_core.Results":
        """Build the model and run the analysis; ``method`` overrides the case's method."""
        method = self.check_method(method)
        return self.solve(self.build_model(), method, progress)


def load_case(path: PathLike) -> Case:
    """Read and check a case file (TOML, format 1).

    The keys are those of ``docs/case-format.md``. [analysis] also takes these optional keys:

    ========================  ===================================================================
    ``tolerance``             0 < x < 1: relative precision of the collapse multiplier, for both
                              incremental methods (default 1e-4 static, 1e-3 dynamic; limit
                              analysis ignores it).
    ``damping``               explicit solver: "local" (Cundall, the default), "viscous"
                              (mass-proportional) or "none".
    ``damping_coefficient``   explicit solver, >= 0: alpha in [0, 1) for "local" (default 0.8),
                              c [1/s] for "viscous".
    ``time_step``             explicit solver, > 0 [s]: default 0.8 x the stability limit
                              (``Model.critical_time_step()``); a step above the limit is refused.
    ``unbalanced_ratio``      explicit solver, 0 < x < 1: a load level is in equilibrium when
                              |unbalanced forces| <= x |applied forces| (default 1e-5).
    ``threads``               explicit solver, integer >= 0: threads of the interface loop
                              (0, the default: all cores).
    ========================  ===================================================================

    The static solver ignores the explicit solver's keys, so one case runs with either method
    (``masonry-dem run --method``, ``masonry-dem compare``). Limit analysis (``method = "limit"``) has
    no load path and ignores every other [analysis] key (they are still checked).

    An optional [reference] table gives a published or exact answer, checked by ``masonry-dem validate``:
    ``collapse_multiplier`` (number, required in the table; a force in N with live = "top_horizontal"),
    ``tolerance`` (relative, 0 < x < 1, default 0.01) and ``source`` (string).

    Raises:
        OSError: the file cannot be read.
        masonry_dem.InputError: the file is not valid TOML or not a valid case; the message starts
            with the file name (as given) and names the key.
    """
    source = os.fspath(path)
    with open(path, "rb") as f:
        data = f.read(MAX_CASE_BYTES + 1)  # never more: /dev/zero or a huge file is refused, not read
    if len(data) > MAX_CASE_BYTES:
        raise InputError(f"{source}: larger than the limit of {MAX_CASE_BYTES // 2**20} MiB for a case file")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"{source}: not a UTF-8 text file ({exc.reason} at byte {exc.start})") from None
    # a byte-order mark, as some editors write at the start of UTF-8 files, is not part of the TOML
    text = text[1:] if text.startswith("\ufeff") else text
    return parse_case(text, source=source, default_title=Path(path).stem)


#: The largest case file read [bytes]: a wall of 10^5 blocks listed one per line takes about 5 MB.
MAX_CASE_BYTES = 64 * 2**20


def _short(name: str, limit: int = 60) -> str:
    """A key for a message: itself, or its start and its length when it is long (a message must not echo
    a megabyte back)."""
    return name if len(name) <= limit else f"{name[:limit]}... ({len(name):,} characters)"


def _duplicate_key(text: str, message: str) -> Optional[str]:
    """The message for TOML's refusal of a key given twice ("Cannot overwrite a value (at line L, column
    C)", "Cannot declare ... twice"), naming the key and its line; None for other errors."""
    if "overwrite" not in message and "twice" not in message:
        return None
    found = re.search(r"at line (\d+)", message)
    if not found:
        return None
    line_no = int(found.group(1))
    lines = text.splitlines()
    line = lines[line_no - 1].strip() if 0 < line_no <= len(lines) else ""
    name = line.strip("[]").strip() if line.startswith("[") else line.split("=", 1)[0].strip()
    if not name:
        return None
    return f"duplicate key '{_short(name)}' (line {line_no}): a key or table may be given only once"


def parse_case(text: str, source: str = "<string>", default_title: str = "untitled") -> Case:
    """Check a case given as TOML text; ``source`` names it in error messages."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        duplicate = _duplicate_key(text, str(exc))
        if duplicate:
            raise InputError(f"{source}: invalid TOML: {duplicate}") from None
        raise InputError(f"{source}: invalid TOML: {exc}") from None
    except ValueError as exc:  # tomllib lets int() refuse integers of more than 4300 digits
        raise InputError(f"{source}: invalid TOML: {exc}") from None
    except RecursionError:  # arrays or inline tables nested a thousand deep
        raise InputError(f"{source}: invalid TOML: arrays or tables nested too deep") from None
    return case_from_dict(data, source=source, default_title=default_title)


def case_from_dict(data: Mapping[str, Any], source: str = "<case>", default_title: str = "untitled") -> Case:
    """Check a parsed case (nested dicts as from ``tomllib``) and map it onto the core's arguments.

    Every key is checked before the core is called (the core then generates the geometry).
    """
    top = _Table(
        data, "", source, ("format", "title", "geometry", "base", "top", "joints", "loads", "analysis", "reference")
    )

    if "format" not in top:
        raise top.error("missing key 'format' at the top level (expected format = 1)")
    fmt = top.integer("format")
    if fmt != FORMAT:
        raise top.key_error(
            "format", f"expected {FORMAT}, got {fmt} (this version of masonry-dem reads format {FORMAT})"
        )
    title = top.string("title", default=default_title)

    # [geometry]
    geo = top.table("geometry", ("thickness", "density") + GEOMETRY_KINDS, required=True)
    assert geo is not None
    thickness = geo.number("thickness", 1.0, _positive)
    density = geo.number("density", 1000.0, _positive)
    given = [k for k in GEOMETRY_KINDS if k in geo]
    if not given:
        raise geo.error("[geometry] needs exactly one of running_bond, pattern, blocks; none is given")
    if len(given) > 1:
        raise geo.error(
            f"[geometry] needs exactly one of running_bond, pattern, blocks; {' and '.join(given)} are both given"
            if len(given) == 2
            else "[geometry] needs exactly one of running_bond, pattern, blocks; all three are given"
        )
    kind = given[0]
    geometry: Dict[str, Any]
    if kind == "running_bond":
        rb = geo.table(
            "running_bond", ("block_length", "block_height", "courses", "length", "first_course", "openings")
        )
        assert rb is not None
        geometry = dict(
            block_length=rb.number("block_length", check=_positive),
            block_height=rb.number("block_height", check=_positive),
            courses=rb.integer("courses", minimum=1),
            length=rb.number("length", check=_positive),
            first_course=rb.string("first_course", "half", ("half", "full")),
            openings=rb.rectangles("openings", required=False),
        )
    elif kind == "pattern":
        pt = geo.table("pattern", ("block_length", "block_height", "rows"))
        assert pt is not None
        block_length = pt.number("block_length", check=_positive)
        block_height = pt.number("block_height", check=_positive)
        rows_in = pt.array("rows")
        assert rows_in is not None
        rows = []
        for i, row in enumerate(rows_in):
            label = f"{pt.where('rows')}[{i}]"
            entries = pt.numbers(label, row)
            for j, x in enumerate(entries):
                if x == 0:
                    raise pt.error(f"{label}[{j}]: must not be 0 (a block or a gap has a length)")
            rows.append(entries)
        geometry = dict(block_length=block_length, block_height=block_height, rows=rows)
    else:
        rects = geo.rectangles("blocks")
        assert rects is not None
        if not rects:
            raise geo.key_error("blocks", "expected at least one block [x0, y0, x1, y1]")
        geometry = dict(blocks=rects)

    # [base]
    base_t = top.table("base", ("kind",))
    base = True if base_t is None else base_t.string("kind", "fixed", ("fixed", "none")) == "fixed"

    # [top]
    top_t = top.table("top", ("rotation", "force", "vertical"))
    top_rotation: Optional[str] = None
    top_force = [0.0, 0.0]
    top_vertical = "free"
    if top_t is not None:
        top_rotation = top_t.string("rotation", "fixed", ("fixed", "free"))
        top_vertical = top_t.string("vertical", "free", ("free", "held"))
        force = top_t.array("force", required=False)
        if force is not None:
            top_force = top_t.numbers(top_t.where("force"), force, 2, " [Fx, Fy]")

    # [joints]
    joints_t = top.table("joints", LAW_KEYS + FAMILIES)
    joints: Dict[str, Dict[str, float]] = {}
    if joints_t is not None:
        default_law = _law(joints_t)
        if default_law:
            joints["default"] = default_law
        for family in FAMILIES:
            fam_t = joints_t.table(family, LAW_KEYS)
            if fam_t is not None:
                joints[family] = _law(fam_t)

    # [loads]
    loads_t = top.table("loads", ("gravity", "live"))
    gravity, live = 9.81, "horizontal_weight"
    if loads_t is not None:
        gravity = loads_t.number("gravity", 9.81, _non_negative)
        live = loads_t.string("live", "horizontal_weight", ("horizontal_weight", "top_horizontal"))
        if live == "top_horizontal" and top_rotation is None:
            raise loads_t.key_error("live", '"top_horizontal" pushes the top beam: add a [top] table')

    # [analysis]
    an_t = top.table("analysis", ANALYSIS_KEYS + DYNAMIC_KEYS)
    method, control, steps = "static", "load", 200
    max_disp: Optional[float] = None  # static: until collapse; dynamic: the core's default
    tolerance: Dict[str, float] = {}
    dynamic: Dict[str, Any] = {}
    if an_t is not None:
        method = an_t.string("method", "static", METHODS)
        control = an_t.string("control", "load", ("load", "displacement"))
        an_t.string("control_point", "top", ("top",))
        if "max_displacement" in an_t:
            max_disp = an_t.number("max_displacement", check=_positive)
        steps = an_t.integer("steps", 200, minimum=1)
        if "tolerance" in an_t:
            tolerance["tolerance"] = an_t.number("tolerance", check=_open_unit)
        dynamic = _dynamic_options(an_t)

    # [reference]
    reference = _reference(top.table("reference", REFERENCE_KEYS))

    # All keys are valid: map them onto the core (the generators may still refuse a geometry).
    try:
        if kind == "running_bond":
            blocks = _core.running_bond(**geometry)
        elif kind == "pattern":
            blocks = _core.pattern(**geometry)
        else:
            blocks = np.asarray(geometry["blocks"], dtype=np.float64)
    except MasonryError as exc:
        raise type(exc)(f"{source}: {exc}") from exc  # the core names the key (geometry.<kind>.<key>)

    model_kwargs: Dict[str, Any] = dict(
        blocks=blocks,
        thickness=thickness,
        density=density,
        base=base,
        top_rotation=top_rotation,
        top_force=top_force,
        joints=joints or None,
        gravity=gravity,
        live=live,
        top_vertical=top_vertical,
    )
    analysis_kwargs: Dict[str, Any] = dict(control=control, steps=steps, max_displacement=max_disp, control_block=None)
    analysis_kwargs.update(tolerance)
    return Case(
        title=title,
        model_kwargs=model_kwargs,
        analysis_kwargs=analysis_kwargs,
        method=method,
        source=source,
        dynamic_kwargs=dynamic,
        reference=reference,
    )


def _reference(table: Optional[_Table]) -> Optional[Dict[str, Any]]:
    """The [reference] table, checked: collapse_multiplier (required), tolerance, source, and methods (the
    methods the reference applies to; all by default)."""
    if table is None:
        return None
    methods = table.array("methods", required=False)
    if methods is None:
        methods = list(METHODS)
    for i, m in enumerate(methods):
        if m not in METHODS:
            options = ", ".join(_quote(c) for c in METHODS)
            raise table.key_error("methods", f"entry {i}: expected one of {options}, got {_quote(m) if isinstance(m, str) else _got(m)}")
    if not methods:
        raise table.key_error("methods", "must name at least one method")
    return {
        "collapse_multiplier": table.number("collapse_multiplier"),
        "tolerance": table.number("tolerance", DEFAULT_REFERENCE_TOLERANCE, _open_unit),
        "source": table.string("source", ""),
        "methods": tuple(methods),
    }


def _dynamic_options(table: _Table) -> Dict[str, Any]:
    """The explicit solver's keys present in [analysis], checked, as keyword arguments of solve_dynamic."""
    out: Dict[str, Any] = {}
    damping = table.string("damping", "local", DAMPINGS)
    if "damping" in table:
        out["damping"] = damping
    if "damping_coefficient" in table:
        coefficient = table.number("damping_coefficient", check=_non_negative)
        if damping == "local" and coefficient >= 1:
            raise table.key_error(
                "damping_coefficient", f'must be < 1 with damping = "local" (alpha in [0, 1)), got {coefficient}'
            )
        out["damping_coefficient"] = coefficient
    if "time_step" in table:
        out["time_step"] = table.number("time_step", check=_positive)
    if "unbalanced_ratio" in table:
        out["unbalanced_ratio"] = table.number("unbalanced_ratio", check=_open_unit)
    if "threads" in table:
        out["threads"] = table.integer("threads", minimum=0)
    return out


def _law(table: _Table) -> Dict[str, float]:
    """The joint-law keys present in a [joints] or [joints.<family>] table."""
    # stiffnesses must be positive, every other parameter non-negative (the core checks the rest)
    positive = ("normal_stiffness", "shear_stiffness")
    return {
        key: table.number(key, check=_positive if key in positive else _non_negative)
        for key in LAW_KEYS
        if key in table
    }


def run_case(
    path: PathLike,
    method: Optional[str] = None,
    progress: Optional[Callable[[int, float, float, float], None]] = None,
) -> "_core.Results":
    """Load a case file and run it; ``method`` ("static" | "dynamic" | "limit") overrides the file's.

    ``progress``: the solvers' optional callback ``(step, multiplier, displacement, fraction)``, e.g. a
    :class:`masonry_dem.progress.ProgressBar`.
    """
    return load_case(path).run(method, progress)


# --------------------------------------------------------------------------------------------------
# Result file
# --------------------------------------------------------------------------------------------------

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
ERROR_STATUSES = ("failed", "no_equilibrium", "unbounded", "stalled", "displacement_limit")


def _json_float(x: Any) -> Optional[float]:
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

    A limit analysis (method "limit": its curve is empty) also gets ``certificate``: an object with the
    keys of :data:`CERTIFICATE_KEYS` (``upper_bound`` null unless some joint is non-associative), or null
    when the run was interrupted; so does a static load-control analysis of associative dry joints, whose
    collapse is checked against limit analysis (its certificate is the evidence). ``error`` is written with
    the statuses that have a reason: "failed", "no_equilibrium", "unbounded", "stalled" and
    "displacement_limit". ``collapse_multiplier`` is null unless the status is "collapse";
    ``last_equilibrium`` is the largest multiplier at which the wall was found in equilibrium (equal to
    ``collapse_multiplier`` on a collapse; null when none was found).
    """
    states = getattr(results, "joint_states", None) or {}
    out: Dict[str, Any] = {
        "format": FORMAT,
        "title": title,
        "method": str(results.method),
        "status": str(results.status),
        "blocks": int(model.n_blocks),
        "interfaces": int(model.n_interfaces),
        "collapse_multiplier": _json_float(results.collapse_multiplier),
        "last_equilibrium": _json_float(getattr(results, "last_equilibrium", math.nan)),
        "curve": {
            "multiplier": [_json_float(x) for x in np.asarray(results.curve_multiplier, dtype=float)],
            "displacement": [_json_float(x) for x in np.asarray(results.curve_displacement, dtype=float)],
        },
        "joint_states": {key: int(states.get(key, 0)) for key in JOINT_STATE_KEYS},
        "elapsed_s": _json_float(results.elapsed_s),
    }
    if out["method"] == "limit" or getattr(results, "certificate", None) is not None:
        out["certificate"] = certificate_dict(getattr(results, "certificate", None))
    if out["status"] in ERROR_STATUSES:
        out["error"] = str(results.error) if results.error else "unknown error"
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
            out[key] = None if value is None else _json_float(value)
    return out


def write_result_json(
    path: PathLike, results: Any, model: Any, title: str, *, inputs: Iterable[PathLike] = ()
) -> Dict[str, Any]:
    """Write the result file (see :func:`result_dict`) to ``path``; return the dict written.

    The file is written atomically (:func:`masonry_dem.atomic.write_text`): a target that is not a regular
    file, or is one of ``inputs`` (the case file), is refused with InputError."""
    from .atomic import write_text

    data = result_dict(results, model, title)
    text = json.dumps(data, indent=2, allow_nan=False)
    write_text(path, text + "\n", inputs=inputs)
    return data
