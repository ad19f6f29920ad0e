"""Reading a case file: :func:`load_case` (a file), :func:`parse_case` (TOML text), :func:`case_from_dict`
(an already parsed table). Every table is checked key by key (:class:`~masonry_dem.case.table._Table`)
before the core is called; the key lists of each table are here.
"""

from __future__ import annotations

import os
import re
import sys
from dataclasses import replace
from pathlib import Path
from typing import Any, Callable, Dict, Mapping, Optional, Tuple, Union

from .. import _core
from .._core import InputError
from .._files import read_bytes
from .. import ground_motion as _gm
from ..assessment.parameters import ASSESSMENT_KEYS, read_assessment
from .common import (
    ANALYSIS_KEYS as ANALYSIS_KEYS,
    DAMPINGS,
    DEFAULT_REFERENCE_TOLERANCE as DEFAULT_REFERENCE_TOLERANCE,
    DYNAMIC_KEYS as DYNAMIC_KEYS,
    FAMILIES as FAMILIES,
    LAW_KEYS as LAW_KEYS,
    LAW_UNITS as LAW_UNITS,
    REFERENCE_KEYS,
    _analysis,
    _base,
    _carried,
    _joints,
    _reference,
)
from .mapping import (
    CORE_DEFAULTS,
    Case,
    GroundMotionParameters,
    ModelParameters,
    TimeHistoryParameters,
    generate_arch,
    generate_blocks,
)
from .table import FORMAT, _non_negative, _positive, _short, _Table

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python < 3.11 only
    import tomli as tomllib

PathLike = Union[str, "os.PathLike[str]"]

TOP_KEYS = (
    "format", "title", "geometry", "base", "top", "joints", "loads", "analysis", "reference", "ground_motion",
    "time_history", "assessment",
)
GEOMETRY_KINDS = ("running_bond", "pattern", "blocks", "dxf", "polygons", "arch", "gable", "stone_wall")
# The forms of a wall of rectangles, which the messages name first
RECTANGLE_KINDS = GEOMETRY_KINDS[:4]
# Keys of [geometry] that may stand beside a wall's form: the supports (fixed blocks: abutments, springers, an
# inclined plane), as polygons
SUPPORT_KEYS = ("supports",)
# The [geometry] forms of a 3D wall (masonry_dem.space.case): any of them makes the case 3D
GEOMETRY_KINDS_3D = ("boxes", "leaf", "u_wall", "corner", "buttressed_wall", "polyhedra", "barrel_vault", "cross_vault",
                     "dome")
# Keys of [geometry] besides its kinds: the wall's, and the options of a drawing (dxf)
DXF_KEYS = ("dxf_layer", "dxf_units")
RUNNING_BOND_KEYS = ("block_length", "block_height", "courses", "height", "length", "first_course", "openings")
#: The kinds of arch of [geometry.arch] (the core's generator, ``masonry_dem.arch``).
ARCH_KINDS = ("semicircular", "segmental", "pointed", "elliptical")
# Keys of [geometry.arch]: its lengths [m], then its counts
ARCH_LENGTHS = ("span", "radius", "rise", "thickness", "abutment_width", "abutment_height", "pier_width", "pier_height")
ARCH_COUNTS = ("voussoirs", "pier_courses")
# Keys of [geometry.gable] (the core's generator, ``masonry_dem.gable``): its lengths [m] (eaves_height and ridge_x may
# be 0), then how the lowest course starts
GABLE_LENGTHS = ("block_length", "block_height", "length", "ridge_height")
GABLE_KEYS = GABLE_LENGTHS + ("eaves_height", "ridge_x", "first_course")
# Keys of [geometry.stone_wall] (``masonry_dem.stone_wall``): its lengths [m], the spread and the angles' bounds
# [degrees], and the seed
STONE_WALL_LENGTHS = ("length", "height", "stone_length", "stone_height")
STONE_WALL_KEYS = STONE_WALL_LENGTHS + ("irregularity", "head_angle", "bed_angle", "seed")
# Keys of the optional [ground_motion] table: a record file (and a vertical one), or a built-in pulse.
GROUND_MOTION_KEYS = (
    "file", "units", "scale", "vertical_file", "vertical_scale", "pulse", "amplitude", "amplitude_g", "period",
    "direction",
)
#: The built-in pulses of [ground_motion] pulse.
PULSES = ("one-sine", "ricker")
# Keys of the optional [time_history] table (``masonry-dem simulate``).
TIME_HISTORY_KEYS = (
    "duration", "record_interval", "damping", "damping_coefficient", "damping_ratio", "time_step", "large_rotations", "contact_update",
)
#: The kinds of damping of a time history: those of the quasi-static explicit solver and Rayleigh damping.
TIME_HISTORY_DAMPINGS = DAMPINGS + ("rayleigh",)

#: The largest case file read [bytes], refused from its size before it is read: a wall of 10^5 blocks listed one
#: per line takes about 5 MB, which TOML parses in seconds (a larger wall: a generator, a pattern or a drawing).
MAX_CASE_BYTES = 16 * 2**20


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
                              (0, the default: all cores); in 3D limit analysis's too.
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
    return parse_case(read_text(path), source=source, default_title=Path(path).stem, base_dir=Path(path).parent)


def read_text(path: PathLike, what: str = "case file") -> str:
    """The text of a TOML file (a case file, a study file): at most :data:`MAX_CASE_BYTES`, UTF-8, without
    a byte-order mark. Raises OSError when it cannot be read, InputError (starting with the file name) when
    it is not a regular file (a FIFO, a device, a folder), too large (from its size, before reading) or not
    UTF-8."""
    source = os.fspath(path)
    # a FIFO, /dev/zero or a huge file is refused before it is opened, from its type and size
    data = read_bytes(path, MAX_CASE_BYTES, what)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"{source}: not a UTF-8 text file ({exc.reason} at byte {exc.start})") from None
    # a byte-order mark, as some editors write at the start of UTF-8 files, is not part of the TOML
    return text[1:] if text.startswith("\ufeff") else text


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


def parse_case(
    text: str, source: str = "<string>", default_title: str = "untitled", base_dir: Optional[PathLike] = None
) -> Case:
    """Check a case given as TOML text; ``source`` names it in error messages; ``base_dir``: the folder the
    record files of [ground_motion] are relative to (default: the current folder)."""
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
    return case_from_dict(data, source=source, default_title=default_title, base_dir=base_dir)


#: The top-level keys of a study file that a case file does not have (docs/study-format.md).
STUDY_KEYS = ("case", "study", "vary")


def is_study(data: Mapping[str, Any]) -> bool:
    """Whether parsed TOML ``data`` is a study file rather than a case file: a study's keys, and no [geometry]."""
    return "geometry" not in data and any(key in data for key in STUDY_KEYS)


def case_from_dict(
    data: Mapping[str, Any],
    source: str = "<case>",
    default_title: str = "untitled",
    base_dir: Optional[PathLike] = None,
) -> Case:
    """Check a parsed case (nested dicts as from ``tomllib``) and map it onto the core's arguments.

    Every key is checked before the core is called (the core then generates the geometry). A key left out
    is left out of the core's arguments too (None in :class:`ModelParameters` and
    :class:`AnalysisParameters`): the core's default applies. The record files of [ground_motion] are read
    here, relative to ``base_dir`` (default: the current folder).
    """
    if is_study(data):
        raise InputError(f"{source}: a study file (its keys case, study, vary), not a case file: run it with "
                         "masonry-dem study (docs/study-format.md)", "case")
    top = _Table(data, "", source, TOP_KEYS)
    title = _title(top, default_title)
    kind, geometry, wall = _geometry(top, base_dir)
    table = top.table("assessment", ASSESSMENT_KEYS)
    assessment = read_assessment(table, base_dir) if table is not None else None
    if kind in GEOMETRY_KINDS_3D:  # a wall of boxes: its tables read by masonry_dem.space.case
        from ..space.case import case_from_tables

        case = case_from_tables(top, title, kind, geometry, wall["density"])
        case.assessment = assessment
        case.time_history = _time_history(top.table("time_history", TIME_HISTORY_KEYS), three=True)
        gravity = case.model.gravity if case.model.gravity is not None else float(_core.DEFAULTS_3D["gravity"])
        case.ground_motion = _ground_motion(top.table("ground_motion", GROUND_MOTION_KEYS), gravity, base_dir,
                                            three=True)
        return case  # type: ignore[no-any-return]
    base = _base(top)
    if base is None and wall["supports"] is not None:
        base = False  # a wall on supports has no foundation unless a [base] table puts one
    wall.update(base=base, **_top_beam(top))
    wall.update(joints=_joints(top), **_loads(top, beam=wall["top_rotation"] is not None))
    method, analysis = _analysis(top)
    reference = _reference(top.table("reference", REFERENCE_KEYS))
    time_history = _time_history(top.table("time_history", TIME_HISTORY_KEYS))
    gravity = wall["gravity"] if wall["gravity"] is not None else float(CORE_DEFAULTS["gravity"])
    motion = _ground_motion(top.table("ground_motion", GROUND_MOTION_KEYS), gravity, base_dir)
    # All keys are valid: map them onto the core (the generators may still refuse a geometry).
    arch = None
    if kind == "arch":
        thickness = wall["thickness"] if wall["thickness"] is not None else float(CORE_DEFAULTS["thickness"])
        arch = generate_arch({**geometry, "wall_thickness": thickness, "gravity": gravity}, source)
        blocks: Any = arch.pop("blocks")
        fill = arch.pop("carried")
        if fill:  # the backfill's weights, after the loads [[loads.carried]] gives
            wall["carried"] = (wall["carried"] or []) + fill
        if arch["supports"]:  # the abutments, then the supports [geometry] gives
            wall["supports"] = arch["supports"] + (wall["supports"] or [])
            if wall["base"] is None:
                wall["base"] = False
    else:
        blocks = generate_blocks(kind, geometry, source)
    return Case(
        title=title,
        model=ModelParameters(blocks=blocks, **wall),
        analysis=analysis,
        method=method,
        source=source,
        reference=reference,
        ground_motion=motion,
        time_history=time_history,
        assessment=assessment,
        arch=arch,
    )


def _title(top: _Table, default_title: str) -> str:
    """The title, after checking that the case is of the format this version reads."""
    if "format" not in top:
        raise top.error("missing key 'format' at the top level (expected format = 1)")
    fmt = top.integer("format")
    if fmt != FORMAT:
        raise top.key_error(
            "format", f"expected {FORMAT}, got {fmt} (this version of masonry-dem reads format {FORMAT})"
        )
    return str(top.string("title", default=default_title))


def _geometry(top: _Table, base_dir: Optional[PathLike]) -> Tuple[str, Dict[str, Any], Dict[str, Any]]:
    """[geometry]: its kind, the arguments of the core's generator of that kind, and the wall's thickness
    and density (None when left out). A drawing (dxf) is read here, relative to ``base_dir``, and becomes
    a block list (kind "blocks")."""
    every = GEOMETRY_KINDS + GEOMETRY_KINDS_3D
    geo = top.table("geometry", ("thickness", "density") + every + DXF_KEYS + SUPPORT_KEYS, required=True)
    assert geo is not None
    given = [k for k in every if k in geo]
    # blocks and polygons: one list; boxes and polyhedra too
    forms = [k for k in given if not (k == "polygons" and "blocks" in given or k == "polyhedra" and "boxes" in given)]
    if not forms:
        raise geo.error(f"[geometry] needs exactly one of {', '.join(RECTANGLE_KINDS)}; none is given (polygons "
                        "also make a wall, alone or beside blocks, [geometry.arch] an arch, [geometry.gable] a gable "
                        "wall and [geometry.stone_wall] a stone wall; a 3D wall: one of "
                        f"{', '.join(GEOMETRY_KINDS_3D)})")
    if len(forms) > 1:
        # the forms of a wall of rectangles, of polygons too, or with a 3D one given, all of them
        kinds = ", ".join(RECTANGLE_KINDS if all(k in RECTANGLE_KINDS for k in given) else GEOMETRY_KINDS
                          if all(k in GEOMETRY_KINDS for k in given) else every)
        count = {3: "all three", 4: "all four"}.get(len(given), ", ".join(given))
        named = f"{' and '.join(given)} are both given" if len(given) == 2 else f"{count} are given"
        both = (" (blocks and polygons may be given together)" if "polygons" in given else
                " (boxes and polyhedra may be given together)" if "polyhedra" in given else "")
        raise geo.error(f"[geometry] needs exactly one of {kinds}{both}; {named}")
    kind = "blocks" if "blocks" in given else "boxes" if "boxes" in given else forms[0]
    for key in DXF_KEYS:
        if key in geo and kind != "dxf":
            raise geo.key_error(key, f"applies to a drawing (dxf), not to {kind}")
    if kind in GEOMETRY_KINDS_3D:  # its supports polyhedra
        from ..space.case import read_geometry

        return kind, read_geometry(geo, kind), {"density": geo.number("density", None, _positive, unit="density")}
    wall = {
        "thickness": geo.number("thickness", None, _positive, unit="length"),
        "density": geo.number("density", None, _positive, unit="density"),
        "supports": geo.polygons("supports", "support"),
    }
    if kind == "dxf":
        return "blocks", _drawing(geo, base_dir), wall
    read = {"running_bond": _running_bond, "pattern": _pattern, "blocks": _block_list, "polygons": _block_list,
            "arch": _arch, "gable": _gable, "stone_wall": _stone_wall}[kind]
    return "blocks" if kind == "polygons" else kind, read(geo), wall


def _running_bond(geo: _Table) -> Dict[str, Any]:
    rb = geo.table("running_bond", RUNNING_BOND_KEYS)
    assert rb is not None
    if ("courses" in rb) == ("height" in rb):  # exactly one: whole courses, or a height [m]
        if "courses" in rb:
            raise rb.key_error("height", "give exactly one of courses and height; both are given")
        message = f"missing key 'courses' in [{rb.path}] (or height: exactly one of courses and height)"
        raise rb.error(message, rb.where("courses"))
    return dict(
        block_length=rb.number("block_length", check=_positive, unit="length"),
        block_height=rb.number("block_height", check=_positive, unit="length"),
        courses=rb.integer("courses", None, minimum=1),
        height=rb.number("height", None, _positive, unit="length"),
        length=rb.number("length", check=_positive, unit="length"),
        first_course=rb.string("first_course", None, ("half", "full")),
        openings=rb.rectangles("openings", required=False),
    )


def _arch(geo: _Table) -> Dict[str, Any]:
    """[geometry.arch]: the arguments of the core's arch generator (``masonry_dem.arch``), each checked alone (a
    length > 0, with its unit or not; a count >= 1; the kind); how they go together (span or radius, abutments or
    piers, a rise that fits) is the generator's to check, its messages naming the key."""
    table = geo.table("arch", ("kind", "backfill") + ARCH_LENGTHS + ARCH_COUNTS)
    assert table is not None
    args: Dict[str, Any] = {"kind": table.string("kind", choices=ARCH_KINDS)}
    args.update({key: table.number(key, None, _positive, unit="length") for key in ARCH_LENGTHS})
    args.update({key: table.integer(key, None, minimum=1) for key in ARCH_COUNTS})
    for key in ("thickness", "voussoirs"):
        if args[key] is None:
            raise table.missing(key)
    fill = table.table("backfill", ("level", "density"))
    if fill is not None:  # whether the level reaches the extrados is the generator's to check
        args["backfill_level"] = fill.number("level", check=_positive, unit="length")
        args["backfill_density"] = fill.number("density", check=_positive, unit="density")
    return args


def _gable(geo: _Table) -> Dict[str, Any]:
    """[geometry.gable]: the arguments of the core's gable generator (``masonry_dem.gable``), each checked alone;
    how they go together (a ridge above the eaves, within the wall's length) is the generator's to check, its
    messages naming the key."""
    table = geo.table("gable", GABLE_KEYS)
    assert table is not None
    args: Dict[str, Any] = {key: table.number(key, check=_positive, unit="length") for key in GABLE_LENGTHS}
    args["eaves_height"] = table.number("eaves_height", check=_non_negative, unit="length")
    args["ridge_x"] = table.number("ridge_x", None, _non_negative, unit="length")
    args["first_course"] = table.string("first_course", None, ("half", "full"))
    return args


def _stone_wall(geo: _Table) -> Dict[str, Any]:
    """[geometry.stone_wall]: the arguments of the core's stone-wall generator (``masonry_dem.stone_wall``), each
    checked alone (the bounds of the spread and the angles are the generator's, its messages naming the key)."""
    table = geo.table("stone_wall", STONE_WALL_KEYS)
    assert table is not None
    args: Dict[str, Any] = {key: table.number(key, check=_positive, unit="length") for key in STONE_WALL_LENGTHS}
    args.update({key: table.number(key, None, _non_negative) for key in ("irregularity", "head_angle", "bed_angle")})
    args["seed"] = table.integer("seed", None, minimum=0, maximum=2**63 - 1)
    return args


def _pattern(geo: _Table) -> Dict[str, Any]:
    pt = geo.table("pattern", ("block_length", "block_height", "rows"))
    assert pt is not None
    block_length = pt.number("block_length", check=_positive, unit="length")
    block_height = pt.number("block_height", check=_positive, unit="length")
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
    return dict(block_length=block_length, block_height=block_height, rows=rows)


def _block_list(geo: _Table) -> Dict[str, Any]:
    """``blocks`` (rectangles) and ``polygons``, either or both: the rectangles first, then the polygons, in the
    order given."""
    rects = geo.rectangles("blocks", required="polygons" not in geo)
    if rects is not None and not rects:
        raise geo.key_error("blocks", "expected at least one block [x0, y0, x1, y1]")
    return dict(blocks=rects or [], polygons=geo.polygons("polygons"))


def _drawing(geo: _Table, base_dir: Optional[PathLike]) -> Dict[str, Any]:
    """``dxf``: the blocks of a drawing (:func:`masonry_dem.dxf.read_dxf_blocks`: rectangles along x and y, and
    convex polygons), relative to ``base_dir``, on
    the layer ``dxf_layer`` (all layers when left out) and in ``dxf_units`` (the drawing's $INSUNITS when left
    out); its errors name the key and the file."""
    from .. import dxf as _dxf  # ezdxf is imported when a case has a drawing only

    name = geo.string("dxf")
    if not name:
        raise geo.key_error("dxf", "expected the name of a drawing (.dxf), got an empty string")
    layer = geo.string("dxf_layer", None)
    units = geo.string("dxf_units", None, tuple(_dxf.UNITS))
    path = Path(name)
    if base_dir is not None and not path.is_absolute():
        path = Path(base_dir) / path
    try:
        blocks = _dxf.read_dxf_blocks(path, layer=layer, units=units)
    except OSError as exc:
        raise geo.key_error("dxf", f"cannot read {path}: {exc.strerror or exc}") from None
    except (InputError, ImportError) as exc:
        raise geo.key_error("dxf", str(exc)) from None
    if isinstance(blocks, list):  # polygons among them
        return dict(blocks=[], polygons=blocks)
    return dict(blocks=blocks.tolist())


def _top_beam(top: _Table) -> Dict[str, Any]:
    """[top]: the top beam's rotation (None: no beam; "fixed" when the table leaves it out), vertical
    restraint and dead force (None: left out)."""
    table = top.table("top", ("rotation", "force", "vertical", "height"))
    beam: Dict[str, Any] = dict(top_rotation=None, top_vertical=None, top_force=None)
    if table is not None:
        if "height" in table:
            raise table.key_error("height", "is the height of a 3D wall's top beam ([geometry] boxes, leaf, u_wall or "
                                            "corner); the top beam of a wall in the plane has none")
        beam["top_rotation"] = table.string("rotation", "fixed", ("fixed", "free"))
        beam["top_vertical"] = table.string("vertical", None, ("free", "held"))
        force = table.array("force", required=False)
        if force is not None:
            beam["top_force"] = table.numbers(table.where("force"), force, 2, " [Fx, Fy]", unit="force")
    return beam


def _loads(top: _Table, beam: bool) -> Dict[str, Any]:
    """[loads]: gravity and the live load (None: left out); ``beam``: whether the case has a top beam."""
    table = top.table("loads", ("gravity", "live", "direction", "carried"))
    if table is None:
        return dict(gravity=None, live=None, carried=None)
    gravity = table.number("gravity", None, _non_negative, unit="acceleration")
    live = table.string("live", None, ("horizontal_weight", "top_horizontal"))
    direction = table.number("direction", None)
    if direction is not None and direction != 0:
        raise table.key_error("direction", f"got {direction:g}: a wall in the plane is pushed along +x (direction 0); "
                                           "a direction in plan applies to a 3D wall ([geometry] boxes, leaf, u_wall "
                                           "or corner)")
    if live == "top_horizontal" and not beam:
        raise table.key_error("live", '"top_horizontal" pushes the top beam: add a [top] table')
    return dict(gravity=gravity, live=live, carried=_carried(table, 2))


def _ground_motion(table: Optional[_Table], gravity: float, base_dir: Optional[PathLike],
                   three: bool = False) -> Optional[GroundMotionParameters]:
    """[ground_motion]: a record file (``file``, ``units``, and optionally ``vertical_file``) or a built-in
    ``pulse`` (``amplitude`` or ``amplitude_g``, ``period``), and the factors ``scale`` / ``vertical_scale``; of
    a 3D case (``three``) the horizontal component's ``direction`` in plan [deg]. The files are read now (relative
    to ``base_dir``); values in g are converted with ``gravity`` [m/s2], the case's."""
    if table is None:
        return None
    direction = None
    if "direction" in table:
        if not three:
            raise table.key_error("direction", "belongs to a 3D case (the direction in plan of the ground's "
                                               "horizontal motion); a wall in the plane shakes along x")
        direction = table.number("direction")
    if ("file" in table) == ("pulse" in table):
        raise table.error("[ground_motion] needs exactly one of file (a record) and pulse (a built-in pulse); "
                          + ("both are given" if "file" in table else "neither is given"), table.where("file"))
    scale = table.number("scale", 1.0)
    vertical_scale = table.number("vertical_scale", None)
    if "pulse" in table:
        pulse = table.string("pulse", choices=PULSES)
        for key in ("units", "vertical_file", "vertical_scale"):
            if key in table:
                raise table.key_error(key, f'applies to a record file, not to pulse = "{pulse}"')
        if ("amplitude" in table) == ("amplitude_g" in table):
            raise table.error(f"[ground_motion] pulse = \"{pulse}\" needs exactly one of amplitude [m/s2] and "
                              f"amplitude_g [g]; {'both are' if 'amplitude' in table else 'neither is'} given",
                              table.where("amplitude"))
        if "amplitude" in table:
            amplitude = table.number("amplitude", unit="acceleration")
        else:
            _need_gravity(table, "amplitude_g", gravity)
            amplitude = table.number("amplitude_g") * gravity
        period = table.number("period", check=_positive, unit="time")
        build = _gm.one_sine if pulse == "one-sine" else _gm.ricker
        motion = build(amplitude, period)
        if gravity > 0:
            motion = replace(motion, gravity=gravity)  # its peak in g told against the case's gravity
        return GroundMotionParameters(horizontal=motion, scale=scale, pulse=pulse, period=period, direction=direction)
    for key in ("amplitude", "amplitude_g", "period"):
        if key in table:
            raise table.key_error(key, "applies to a pulse, not to a record file")
    if vertical_scale is not None and "vertical_file" not in table:
        raise table.key_error("vertical_scale", "needs vertical_file (the vertical record it scales)")
    units = table.string("units", None, _gm.UNITS)
    horizontal, path = _record(table, "file", units, gravity, base_dir)
    vertical, files = None, (path,)
    if "vertical_file" in table:
        vertical, vertical_path = _record(table, "vertical_file", units, gravity, base_dir)
        files += (vertical_path,)
    return GroundMotionParameters(
        horizontal=horizontal, scale=scale, vertical=vertical, vertical_scale=vertical_scale, files=files,
        direction=direction,
    )


def _need_gravity(table: _Table, key: str, gravity: float) -> None:
    if not gravity > 0:
        raise table.key_error(key, f"a value in g needs gravity > 0 ([loads] gravity is {gravity:g})")


def _record(
    table: _Table, key: str, units: Optional[str], gravity: float, base_dir: Optional[PathLike]
) -> Tuple[_gm.GroundMotion, Path]:
    """The record file of ``key``, read (:func:`masonry_dem.ground_motion.read`); its errors name the key."""
    name = table.string(key)
    if not name:
        raise table.key_error(key, "expected the name of a record file (.csv or .AT2), got an empty string")
    path = Path(name)
    if base_dir is not None and not path.is_absolute():
        path = Path(base_dir) / path
    suffix = path.suffix.lower()
    if suffix not in _gm.SUFFIXES:
        raise table.key_error(key, f"{name!r}: unknown record format {path.suffix!r} (expected .csv, .txt, .dat or .AT2)")
    if _gm.SUFFIXES[suffix] == "at2":
        if units not in (None, "g"):
            raise table.key_error("units", f'an AT2 record ({name}) is in g, got "{units}"')
    if units in (None, "g"):
        _need_gravity(table, "units" if units else key, gravity)
    try:
        return _gm.read(path, units=units, g=gravity if gravity > 0 else _gm.G), path
    except OSError as exc:
        raise table.key_error(key, f"cannot read {path}: {exc.strerror or exc}") from None
    except InputError as exc:
        raise table.key_error(key, str(exc)) from None


def _time_history(table: Optional[_Table], three: bool = False) -> TimeHistoryParameters:
    """[time_history]: the options of ``Model.simulate`` given (None: left out); of a 3D case (``three``),
    ``Model3D.simulate``'s, which has no Rayleigh damping."""
    if table is None:
        return TimeHistoryParameters()
    damping = table.string("damping", None, TIME_HISTORY_DAMPINGS)
    if three and damping == "rayleigh":
        raise table.key_error("damping", '"rayleigh" is refused in 3D: its stiffness-proportional part is the '
                                         'plane\'s only (a 3D case takes "none", "viscous" or "local")')
    coefficient = table.number("damping_coefficient", None, _non_negative)
    ratio = table.number("damping_ratio", None, _non_negative)
    if (damping == "rayleigh") != (ratio is not None):
        if damping == "rayleigh":
            raise table.key_error("damping_ratio", 'is needed with damping = "rayleigh" (e.g. 0.05 for 5%)')
        raise table.key_error("damping_ratio", 'belongs to damping = "rayleigh"')
    if damping == "rayleigh" and coefficient is not None:
        raise table.key_error("damping_coefficient", 'does not apply to damping = "rayleigh" (give damping_ratio)')
    if coefficient is not None:
        if damping is None or damping == "none":
            raise table.key_error(
                "damping_coefficient", 'needs damping = "local" or "viscous" (a time history is undamped by default)'
            )
        if damping == "local" and coefficient >= 1:
            raise table.key_error(
                "damping_coefficient", f'must be < 1 with damping = "local" (alpha in [0, 1)), got {coefficient}'
            )
    large = table.boolean("large_rotations", None)
    update = table.boolean("contact_update", None)
    return TimeHistoryParameters(
        duration=table.number("duration", None, _positive, unit="time"),
        record_interval=table.number("record_interval", None, _positive, unit="time"),
        damping=damping,
        damping_coefficient=coefficient,
        damping_ratio=ratio,
        time_step=table.number("time_step", None, _positive, unit="time"),
        large_rotations=large,
        contact_update=update,
    )
