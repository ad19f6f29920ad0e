"""A parsed TOML table checked key by key (:class:`_Table`), and the checks and message pieces it uses; the
format version (:data:`FORMAT`) of case files and result files.

Every message is one line that starts with the file name and names the key with its table path, e.g.
``wall.toml: unknown key 'frictoin' in [joints.bed]`` or ``wall.toml: geometry.thickness: must be > 0, got 0``.
"""

from __future__ import annotations

import difflib
import json
import math
from typing import Any, Callable, List, Mapping, Optional, Sequence

from .._core import InputError
from .._shapes import polygon_problem
from ..units import KINDS, parse_quantity, unit_names

#: The version of the case-file and result-file format this package reads and writes (their top-level key
#: ``format``; :mod:`.reader` checks it, :mod:`.result_file` writes it).
FORMAT = 1

#: A check of a number: None when it is fine, else what is wrong ("must be > 0").
Check = Callable[[float], Optional[str]]

#: The default of a getter whose key is required (a default of None makes the key optional: None when absent).
REQUIRED: Any = object()

# The TOML name of each type a parsed value may have, in the order they are tried (a bool is an int).
_TOML_TYPES = ((bool, "boolean"), (int, "integer"), (float, "float"), (str, "string"), (list, "array"), (dict, "table"))


def _type_name(value: Any) -> str:
    """The TOML name of the type of a parsed value (for error messages)."""
    for kind, name in _TOML_TYPES:
        if isinstance(value, kind):
            return name
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


def _short(name: str, limit: int = 60) -> str:
    """A key for a message: itself, or its start and its length when it is long (a message must not echo
    a megabyte back)."""
    return name if len(name) <= limit else f"{name[:limit]}... ({len(name):,} characters)"


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

    The typed getters take a ``default``: :data:`REQUIRED` (the default of most) makes the key required,
    None makes it optional (None when absent: left to the core's default), any other value is returned
    when the key is absent.
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
                raise self.error(f"unknown key '{_short(key)}' {where}{hint}", self.where(str(key)))

    # -- messages ----------------------------------------------------------------------------------

    def error(self, message: str, key: Optional[str] = None) -> InputError:
        """An InputError whose message starts with the file name; ``key``: the dotted key at fault."""
        return InputError(f"{self.source}: {message}", key)

    def where(self, key: str) -> str:
        """The dotted key, 'path.key' (or just 'key' at the top level), the prefix of a message about one value."""
        return f"{self.path}.{key}" if self.path else key

    def key_error(self, key: str, message: str) -> InputError:
        """An InputError about the value of ``key`` in this table."""
        return self.error(f"{self.where(key)}: {message}", self.where(key))

    def missing(self, key: str) -> InputError:
        """An InputError for the required ``key`` missing from this table."""
        where = f"in [{self.path}]" if self.path else "at the top level"
        return self.error(f"missing key '{key}' {where}", self.where(key))

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
        self, key: str, default: Any = REQUIRED, check: Optional[Check] = None, unit: Optional[str] = None
    ) -> Any:
        """A finite float (TOML integer or float, not boolean), or ``default`` when absent (see the class).

        ``unit``: the kind of quantity (a key of :data:`masonry_dem.units.KINDS`, e.g. "stress") when the key
        also takes a string with its unit ("0.25 MPa"), read into SI; a plain number is SI as it is.
        """
        value = self._get(key, default is REQUIRED)
        if value is None:
            return None if default is None else float(default)
        return self._number_value(self.where(key), value, check, unit)

    def _number_value(self, label: str, value: Any, check: Optional[Check] = None, unit: Optional[str] = None) -> float:
        if unit is not None and isinstance(value, str):
            return self._quantity(label, value, check, unit)
        if not _is_number(value):
            if unit is not None:
                extra = f" ({KINDS[unit]} in SI, or a string with its unit: {unit_names(unit)})"
            else:
                extra = " (this key takes no unit)" if isinstance(value, str) else ""
            raise self.error(f"{label}: expected a number, {_got(value)}{extra}", label)
        try:
            x = float(value)
        except OverflowError:  # an integer beyond the range of a float
            raise self.error(f"{label}: expected a finite number, {_got(value)}", label) from None
        if not math.isfinite(x):
            raise self.error(f"{label}: expected a finite number, got {value}", label)
        if check is not None:
            problem = check(x)
            if problem:
                raise self.error(f"{label}: {problem}, got {_int_text(value) if isinstance(value, int) else value}", label)
        return x

    def _quantity(self, label: str, text: str, check: Optional[Check], unit: str) -> float:
        """A string with its unit ("0.25 MPa") read into SI (:func:`masonry_dem.units.parse_quantity`)."""
        try:
            x = parse_quantity(text, unit, what=label)
        except InputError as exc:
            raise self.error(str(exc), label) from None
        problem = check(x) if check is not None else None
        if problem:
            raise self.error(f"{label}: {problem}, got {_quote(text)}", label)
        return x

    def integer(
        self, key: str, default: Any = REQUIRED, minimum: Optional[int] = None, maximum: int = 2**31 - 1
    ) -> Any:
        """An integer (not a float, not a boolean) in [minimum, maximum], or ``default`` when absent."""
        value = self._get(key, default is REQUIRED)
        if value is None:
            return None if default is None else int(default)
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.key_error(key, f"expected an integer, {_got(value)}")
        if minimum is not None and value < minimum:
            raise self.key_error(key, f"must be >= {minimum}, got {_int_text(value)}")
        if value > maximum:
            raise self.key_error(key, f"must be <= {maximum}, got {_int_text(value)}")
        return value

    def boolean(self, key: str, default: Any = REQUIRED) -> Any:
        """true or false, or ``default`` when absent."""
        value = self._get(key, default is REQUIRED)
        if value is None:
            return default
        if not isinstance(value, bool):
            raise self.key_error(key, f"expected true or false, {_got(value)}")
        return value

    def string(self, key: str, default: Any = REQUIRED, choices: Optional[Sequence[str]] = None) -> Any:
        """A string, one of ``choices`` if given, or ``default`` when absent."""
        value = self._get(key, default is REQUIRED)
        if value is None:
            return None if default is None else str(default)
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

    def numbers(
        self, label: str, value: Any, length: Optional[int] = None, what: str = "", unit: Optional[str] = None
    ) -> List[float]:
        """An array of finite numbers (of ``length`` entries if given); ``label`` names it in messages;
        ``unit``: the kind of quantity of every entry when an entry may be a string with its unit."""
        if not isinstance(value, list):
            expected = f"an array of {length} numbers{what}" if length else "an array of numbers"
            raise self.error(f"{label}: expected {expected}, got {_type_name(value)}", label)
        if length is not None and len(value) != length:
            raise self.error(f"{label}: expected {length} numbers{what}, got {len(value)}", label)
        return [self._number_value(f"{label}[{i}]", v, unit=unit) for i, v in enumerate(value)]

    def rectangles(self, key: str, required: bool = True) -> Optional[List[List[float]]]:
        """An array of rectangles [x0, y0, x1, y1] (m) with x1 > x0 and y1 > y0 (each a number [m] or a
        length with its unit, "175 mm")."""
        items = self.array(key, required)
        if items is None:
            return None
        rects = []
        for i, item in enumerate(items):
            label = f"{self.where(key)}[{i}]"
            x0, y0, x1, y1 = self.numbers(label, item, 4, " [x0, y0, x1, y1]", unit="length")
            if not (x1 > x0 and y1 > y0):
                raise self.error(f"{label}: expected x1 > x0 and y1 > y0, got {item}", label)
            rects.append([x0, y0, x1, y1])
        return rects

    def polygons(self, key: str, what: str = "block", dimension: int = 2) -> Optional[List[List[List[float]]]]:
        """An array of at least one convex polygon, each an array of vertices [x, y] (m; each a number [m] or a
        length with its unit), in either orientation; an outline that is no block (:func:`masonry_dem._shapes.
        polygon_problem`: fewer than 3 distinct vertices, all on a line, turning back, concave or crossing itself) is
        refused naming the polygon and the vertex at fault. ``what``: the word for one polygon in the messages. None when
        the key is absent. ``dimension`` 3: an array of convex polyhedra, each an array of vertices [x, y, z], checked
        here as numbers only (the core makes each the convex hull of its vertices, and refuses those that are none)."""
        items = self.array(key, required=False)
        if items is None:
            return None
        names = "[x, y]" if dimension == 2 else "[x, y, z]"
        if not items:
            raise self.key_error(key, f"expected at least one {what}, each an array of vertices {names} (or leave the "
                                      "key out)")
        polygons = []
        for i, item in enumerate(items):
            label = f"{self.where(key)}[{i}]"
            if not isinstance(item, list):
                raise self.error(f"{label}: expected an array of vertices {names}, got {_type_name(item)}", label)
            vertices = [self.numbers(f"{label}[{j}]", v, dimension, f" {names}", unit="length")
                        for j, v in enumerate(item)]
            problem = polygon_problem(vertices) if dimension == 2 else None
            if problem:
                raise self.error(f"{label}: {problem}", label)
            polygons.append(vertices)
        return polygons
