"""Reading a study file (TOML, format 1 of docs/study-format.md): :func:`load_study` (a file),
:func:`parse_study` (TOML text), :func:`study_from_dict` (an already parsed table, or a Python
``Model`` builder as the base case).

Every key is checked by name before anything runs, with the case files' checker
(:class:`masonry_dem.case.table._Table`): a bad study raises :class:`masonry_dem.InputError` whose one-line
message starts with the file name and names the key (``study.toml: vary.friction.distribution: expected one
of "uniform", "normal", "lognormal", got "gauss"``). The base case is checked as a case file, and every grid
value is tried on it (a value the case file would refuse is refused here, with its key).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Tuple, Union

from .._core import InputError
from ..case import METHODS, case_from_dict, parse_case
from ..case.reader import FAMILIES, LAW_KEYS, is_study, read_text
from ..case.table import REQUIRED, _got, _non_negative, _positive, _quote, _Table
from .model import (
    DIRECTIONS,
    DISTRIBUTIONS,
    Study,
    Texture,
    Variation,
    apply_values,
)

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python < 3.11 only
    import tomli as tomllib

PathLike = Union[str, "os.PathLike[str]"]

#: The version of the study-file format this package reads.
STUDY_FORMAT = 1
TOP_KEYS = ("format", "title", "case", "study", "vary")
STUDY_KEYS = ("methods", "samples", "seed", "chunk")
#: The keys of a variation table ([vary.NAME]).
VARIATION_KEYS = (
    "values",
    "start",
    "stop",
    "count",
    "distribution",
    "min",
    "max",
    "mean",
    "std",
    "associative",
    "opening",
)
TEXTURE_KEYS = ("length_std", "height_std", "bond", "min_fraction")
BONDS = ("running", "random")
#: The parameters a [vary] table may name besides the joint-law keys (and the families' tables of them):
#: the wall's, the running-bond generator's, the loads', the top beam's and the openings'.
WALL_PARAMETERS = ("thickness", "density")
RUNNING_BOND_PARAMETERS = ("block_length", "block_height", "courses", "length")
OPENING_PARAMETERS = ("opening_x", "opening_y", "opening_width", "opening_height")
OTHER_PARAMETERS = ("gravity", "precompression") + OPENING_PARAMETERS
#: The parameters of the base case's [assessment] table a study may vary (a fragility by the PGA): its spectrum's a_g.
ASSESSMENT_PARAMETERS = ("ag",)
#: The most analyses one study may hold.
MAX_ANALYSES = 10_000_000


def load_study(path: PathLike) -> Study:
    """Read and check a study file (TOML, format 1, docs/study-format.md).

    A base case given by path (``case = "wall.toml"``) is read relative to the study file's folder.

    Raises:
        OSError: the file cannot be read.
        masonry_dem.InputError: not a valid study; the message starts with the file name and names the key.
    """
    source = os.fspath(path)
    text = read_text(path, "study file")
    return parse_study(text, source=source, base_dir=Path(path).parent, default_title=Path(path).stem)


def parse_study(text: str, source: str = "<string>", base_dir: PathLike = ".", default_title: str = "study") -> Study:
    """Check a study given as TOML text; ``source`` names it in messages, ``base_dir`` is the folder a base
    case given by path is read from."""
    try:
        data = tomllib.loads(text)
    except (tomllib.TOMLDecodeError, ValueError, RecursionError) as exc:
        raise InputError(f"{source}: invalid TOML: {exc}") from None
    return study_from_dict(data, source=source, base_dir=base_dir, default_title=default_title)


def study_from_dict(
    data: Mapping[str, Any], source: str = "<study>", base_dir: PathLike = ".", default_title: str = "study"
) -> Study:
    """Check a parsed study (nested dicts, as from ``tomllib``).

    ``data["case"]`` is the base case: a path (str, relative to ``base_dir``), a case table (a dict with the
    keys of a case file; its ``format`` may be left out), or, from Python only, a ``Model`` builder: a
    callable that takes the varied parameters as keyword arguments and returns a :class:`masonry_dem.Model`
    (it runs in the workers; its parameters may have any names, and the direction and textures, which
    rewrite a case's blocks, are refused).
    """
    top = _Table(data, "", source, TOP_KEYS)
    if "format" not in top:
        raise top.error(f"missing key 'format' at the top level (expected format = {STUDY_FORMAT})", "format")
    found = top.integer("format")
    if found != STUDY_FORMAT:
        reads = f"this version of masonry-dem reads format {STUDY_FORMAT}"
        raise top.key_error("format", f"expected {STUDY_FORMAT}, got {found} ({reads})")
    title = str(top.string("title", default_title))
    base, inputs = _base_case(top, Path(base_dir))
    options = top.table("study", STUDY_KEYS)
    methods = _methods(options, base)
    samples = 1 if options is None else options.integer("samples", 1, minimum=1, maximum=MAX_ANALYSES)
    # the count of analyses is checked as the grid is read, before any value is tried on the base case
    variations, texture = _vary(top, base, len(methods) * samples)
    study = Study(
        title=title,
        base=base,
        methods=methods,
        variations=tuple(variations),
        texture=texture,
        samples=samples,
        seed=0 if options is None else options.integer("seed", 0, minimum=0, maximum=2**63 - 1),
        chunk=0 if options is None else options.integer("chunk", 0, minimum=0),
        source=source,
        inputs=inputs,
    )
    if study.size > MAX_ANALYSES:
        raise top.error(f"the study holds {study.size:,} analyses, more than the limit of {MAX_ANALYSES:,}")
    return study


def _base_case(top: _Table, base_dir: Path) -> Tuple[Any, Tuple[str, ...]]:
    """The base case as plain data (a case table) or a builder, and the files it was read from."""
    if "case" not in top:
        raise top.missing("case")
    value = top.data["case"]
    if callable(value):
        return value, ()
    if isinstance(value, str):
        path = base_dir / value
        try:
            text = read_text(path)
            if _is_study_text(text):
                raise top.key_error("case", f"{_quote(value)} is a study file: the base case must be a case file "
                                            "(docs/case-format.md), not a study")
            case = parse_case(text, source=str(path), default_title=path.stem)  # every check of a case file
            data = tomllib.loads(text)
        except OSError as exc:
            raise top.key_error("case", f"cannot read {path}: {exc.strerror or exc}") from None
        _in_the_plane(top, case)
        return data, (str(path),)
    if not isinstance(value, dict):
        raise top.key_error("case", f"expected a case file's path or a [case] table, {_got(value)}")
    data = dict(value)
    data.setdefault("format", STUDY_FORMAT)
    _in_the_plane(top, case_from_dict(data, source=f"{top.source}: [case]", default_title="case"))
    return data, ()


def _is_study_text(text: str) -> bool:
    """Whether TOML ``text`` is a study file (:func:`masonry_dem.case.reader.is_study`); False when it is not TOML
    (parse_case says so)."""
    try:
        return is_study(tomllib.loads(text))
    except (tomllib.TOMLDecodeError, ValueError, RecursionError):
        return False


def _in_the_plane(top: Any, case: Any) -> None:
    """Refuse a 3D base case: a study varies and runs walls in the plane in this version."""
    if case.dimension == 3:
        raise top.key_error("case", "is a 3D wall: a study runs walls in the plane in this version (the 3D model "
                                    "takes one limit analysis at a time: masonry-dem run)")


def _methods(options: Optional[_Table], base: Any) -> Tuple[str, ...]:
    """[study] methods: one or several of METHODS (default: the base case's [analysis] method)."""
    value = None if options is None else options.data.get("methods")
    if value is None:
        if callable(base):
            return ("static",)
        return (str(base.get("analysis", {}).get("method", "static")),)
    assert options is not None
    names = [value] if isinstance(value, str) else value
    if not isinstance(names, list) or not names:
        raise options.key_error("methods", f"expected a method or an array of methods, {_got(value)}")
    for i, name in enumerate(names):
        if name not in METHODS:
            expected = ", ".join(_quote(m) for m in METHODS)
            raise options.key_error("methods", f"entry {i}: expected one of {expected}, got {_quote(name)}")
    if len(set(names)) != len(names):
        raise options.key_error("methods", "a method is given twice")
    return tuple(names)


def _check_size(table: _Table, size: int) -> None:
    """Refuses a study of ``size`` analyses beyond :data:`MAX_ANALYSES`."""
    if size > MAX_ANALYSES:
        raise table.error(f"the study holds {size:,} analyses, more than the limit of {MAX_ANALYSES:,}")


def _vary(top: _Table, base: Any, per_point: int = 1) -> Tuple[List[Variation], Optional[Texture]]:
    """The [vary] tables: the variations (grid and random, in the file's order) and the texture. The
    analyses (``per_point`` at each grid point: methods times samples) are counted as each grid is read,
    and a study beyond :data:`MAX_ANALYSES` refused before any value is tried on the base case."""
    builder = callable(base)
    data = top.data.get("vary", {})
    allowed = list(data) if builder and isinstance(data, dict) else _parameter_names()
    _check_size(top, per_point)
    vary = top.table("vary", allowed)
    if vary is None:
        return [], None
    variations: List[Variation] = []
    read: List[Tuple[_Table, Variation]] = []
    texture = None
    size = per_point
    for name in vary.data:
        if name == "texture" and not builder:
            texture = _texture(vary, base)
            continue
        if name in FAMILIES and not builder:
            family = vary.table(name, LAW_KEYS)
            assert family is not None
            keys = [(family, key, f"{name}.{key}") for key in family.data]
        else:
            keys = [(vary, name, name)]
        for parent, key, full in keys:
            table, variation = _variation(parent, key, full, lambda count, size=size: _check_size(top, size * count))
            size *= len(variation.values) if variation.values is not None else 1
            _check_size(top, size)
            read.append((table, variation))
            variations.append(variation)
    if not builder:
        for table, variation in read:
            _check_on_case(table, variation, base)
    for v in variations:
        if v.name == "direction" and builder:
            raise vary.key_error("direction", "a Model builder has no load direction (give a case to mirror)")
    return variations, texture


def _parameter_names() -> List[str]:
    """The names a [vary] table of a case may hold."""
    named = WALL_PARAMETERS + RUNNING_BOND_PARAMETERS + OTHER_PARAMETERS + ASSESSMENT_PARAMETERS + ("direction",
                                                                                                     "texture")
    return list(LAW_KEYS + FAMILIES + named)


def _variation(parent: _Table, key: str, name: str, check: Any = None) -> Tuple[_Table, Variation]:
    """One [vary.NAME] table: a grid (values, or start / stop / count) or a distribution; with the table
    (its values are tried on the base case afterwards, by :func:`_check_on_case`). ``check(count)`` is
    called with a grid's count before its values are made."""
    table = parent.table(key, VARIATION_KEYS, required=True)
    assert table is not None
    kinds = [k for k in ("values", "start", "distribution") if k in table]
    if len(kinds) != 1:
        got = "none" if not kinds else " and ".join(kinds)
        raise table.error(
            f"[{table.path}] needs exactly one of values, start (with stop and count), distribution; got {got}",
            table.path,
        )
    _check_options(table, name)
    options = dict(
        associative=_boolean(table, "associative"),
        opening=table.integer("opening", 0, minimum=0),
    )
    if name == "direction":
        variation = Variation(name, values=_directions(table))
    elif "distribution" in table:
        if name == "courses":
            raise table.key_error("distribution", "courses is an integer: give values")
        variation = Variation(name, **_distribution(table), **options)
    else:
        unit = "acceleration" if name in ASSESSMENT_PARAMETERS else None
        variation = Variation(name, values=_grid_values(table, integer=name == "courses", check=check, unit=unit),
                              **options)
    return table, variation


def _check_options(table: _Table, name: str) -> None:
    """associative only for friction, opening only for the openings' parameters."""
    if "associative" in table and name.split(".")[-1] != "friction":
        raise table.key_error("associative", "only a friction may take associative (dilatancy = friction)")
    if "opening" in table and name not in OPENING_PARAMETERS:
        raise table.key_error("opening", f"only {', '.join(OPENING_PARAMETERS)} take opening")


def _boolean(table: _Table, key: str) -> bool:
    value = table.data.get(key, False)
    if not isinstance(value, bool):
        raise table.key_error(key, f"expected true or false, {_got(value)}")
    return value


def _directions(table: _Table) -> Tuple[str, ...]:
    values = table.array("values")
    assert values is not None
    if not values or any(v not in DIRECTIONS for v in values) or len(set(values)) != len(values):
        expected = " and ".join(_quote(d) for d in DIRECTIONS)
        raise table.key_error("values", f"expected one or both of {expected}, each once, got {values!r}")
    return tuple(values)


def _grid_values(table: _Table, integer: bool, check: Any = None, unit: Optional[str] = None) -> Tuple[Any, ...]:
    """values = [...], or start, stop and count (count values evenly spaced, both ends included); ``unit``: the kind
    of quantity of a value given with its unit ("0.25 g" for an acceleration)."""
    if "values" in table:
        items = table.array("values")
        assert items is not None
        if not items:
            raise table.key_error("values", "expected at least one value")
        if integer:
            for i, v in enumerate(items):
                if isinstance(v, bool) or not isinstance(v, int):
                    raise table.error(
                        f"{table.where('values')}[{i}]: expected an integer, {_got(v)}", table.where("values")
                    )
            return tuple(items)
        return tuple(table.numbers(table.where("values"), items, unit=unit))
    if integer:
        raise table.key_error("start", "courses is an integer: give values")
    start, stop = table.number("start", unit=unit), table.number("stop", unit=unit)
    count = table.integer("count", minimum=2, maximum=MAX_ANALYSES)
    if check is not None:
        check(count)
    return tuple(start + (stop - start) * i / (count - 1) for i in range(count))


def _distribution(table: _Table) -> Dict[str, Any]:
    """distribution = "uniform" (min, max), "normal" or "lognormal" (mean, std; truncated by min and/or max)."""
    kind = table.string("distribution", REQUIRED, DISTRIBUTIONS)
    if "start" in table or "stop" in table or "count" in table:
        raise table.error(f"[{table.path}]: start, stop and count make a grid, not a distribution", table.path)
    low = table.number("min", REQUIRED if kind == "uniform" else None)
    high = table.number("max", REQUIRED if kind == "uniform" else None)
    if low is not None and high is not None and not low < high:
        raise table.key_error("max", f"must be > min = {low:g}, got {high:g}")
    if kind == "uniform":
        for key in ("mean", "std"):
            if key in table:
                raise table.key_error(key, "a uniform distribution takes min and max only")
        return dict(distribution=kind, low=low, high=high)
    mean = table.number("mean", check=_positive if kind == "lognormal" else None)
    std = table.number("std", check=_positive)
    if kind == "lognormal" and low is not None and low < 0:
        raise table.key_error("min", f"a lognormal variable is positive: must be >= 0, got {low:g}")
    a, b = Variation("", distribution=kind, low=low, high=high, mean=mean, std=std).window()
    if b - a < 1e-9:  # no value could be drawn
        raise table.key_error("min" if low is not None else "max", "the window [min, max] holds no probability")
    return dict(distribution=kind, low=low, high=high, mean=mean, std=std)


def _texture(vary: _Table, base: Mapping[str, Any]) -> Texture:
    """[vary.texture]: block lengths and course heights perturbed, and the courses' offsets."""
    table = vary.table("texture", TEXTURE_KEYS)
    assert table is not None
    if "running_bond" not in base.get("geometry", {}):
        raise table.error(
            "vary.texture: the base case's [geometry] must be a running_bond (a texture perturbs it)", "vary.texture"
        )
    if "height" in base["geometry"]["running_bond"]:
        raise table.error(
            "vary.texture: the base case's [geometry.running_bond] must give courses, not height (a texture draws"
            " each course's height)",
            "vary.texture",
        )
    fraction = table.number("min_fraction", 0.25, lambda x: None if 0 < x < 1 else "must lie in (0, 1)")
    return Texture(
        length_std=table.number("length_std", 0.0, _non_negative),
        height_std=table.number("height_std", 0.0, _non_negative),
        bond=table.string("bond", "running", BONDS),
        min_fraction=fraction,
    )


def _check_on_case(table: _Table, variation: Variation, base: Mapping[str, Any]) -> None:
    """The parameter must exist on the base case, and each grid value must make a valid case."""
    name = variation.name
    geometry = base.get("geometry", {})
    rb = geometry.get("running_bond") if isinstance(geometry, dict) else None
    if name in RUNNING_BOND_PARAMETERS + OPENING_PARAMETERS and not isinstance(rb, dict):
        raise table.error(f"{table.path}: the base case's [geometry] must be a running_bond to vary {name}", table.path)
    if name in OPENING_PARAMETERS and variation.opening >= len(rb.get("openings", [])):  # type: ignore[union-attr]
        raise table.key_error("opening", f"the base case has no opening {variation.opening} (they are numbered from 0)")
    if name in ASSESSMENT_PARAMETERS and not isinstance(base.get("assessment"), dict):
        raise table.error(f"{table.path}: {name} is the [assessment] spectrum's a_g: the base case needs an "
                          "[assessment] table", table.path)
    if name in ASSESSMENT_PARAMETERS and base["assessment"].get("spectrum", "ec8") not in ("ec8", "ntc2018"):
        raise table.error(f"{table.path}: {name} is the a_g of a code's spectrum: the base case's [assessment] "
                          "spectrum is a file", table.path)
    if name == "precompression" and "top" not in base:
        raise table.error(
            f"{table.path}: precompression is a force on the top beam: the base case needs a [top] table", table.path
        )
    for i, value in enumerate(variation.values or ()):
        if name == "direction":
            continue
        try:
            case_from_dict(apply_values(base, {name: value}, {name: variation}), source="x", default_title="x")
        except InputError as exc:
            reason = str(exc).split(": ", 1)[-1]
            raise table.error(f"{table.where('values')}[{i}] = {value!r}: {reason}", table.where("values")) from None
