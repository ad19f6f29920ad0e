"""Case files of 3D walls (docs/case-format.md, "3D walls"): the [geometry] forms that make a case 3D (``boxes``
and the tables ``leaf``, ``u_wall``, ``corner``, ``buttressed_wall``, ``barrel_vault``, ``cross_vault``, ``dome``),
the 3D keys of the other tables ([top] height, [loads] direction; [ground_motion] direction and [time_history], which
the reader reads), the methods a 3D case takes (:data:`METHODS_3D`: limit analysis, and the explicit solver's
quasi-static pushover with the [analysis] keys of 2D), the refusals of what the 3D model does not take in this
version (the static solver, displacement control, Rayleigh damping, limit analysis along the mechanism, the 2D keys
that have no meaning there), and :class:`ModelParameters3D`, the arguments of :class:`masonry_dem.Model3D` that a
:class:`masonry_dem.case.Case` of a 3D wall holds.

:mod:`masonry_dem.case.reader` reads every case file and hands a 3D one to :func:`case_from_tables` once its
[geometry] is read; the tables the two dimensions share ([base], [joints], [analysis], [reference]) are read with
:mod:`masonry_dem.case.common`, with the same meaning. :class:`ModelParameters3D`, :data:`METHODS_3D`, the words
of the refusals and :data:`CORE_DEFAULTS_3D` are named here and live with the 3D model
(:mod:`masonry_dem.space.model`), below the :class:`~masonry_dem.case.Case`, which holds, refuses and fills in by
them.
"""

from __future__ import annotations

import math
import re
from typing import Any, Dict, List, Mapping, Optional

import numpy as np

from .. import _core
from .._core import InputError, MasonryError
from ..case.common import REFERENCE_KEYS, _analysis, _base, _carried, _joints, _reference
from ..case.mapping import AnalysisParameters, Case
from ..case.table import _got, _non_negative, _positive, _quote, _Table
from .model import (
    CORE_DEFAULTS_3D as CORE_DEFAULTS_3D,
    IN_3D,
    LOAD_CONTROL_3D,
    METHODS_3D,
    ModelParameters3D,
)

__all__ = [
    "GEOMETRY_KINDS_3D",
    "SOLID_KEYS",
    "LEAF_KEYS",
    "BONDED_KEYS",
    "BUTTRESSED_KEYS",
    "METHODS_3D",
    "IN_3D",
    "LOAD_CONTROL_3D",
    "CORE_DEFAULTS_3D",
    "ModelParameters3D",
    "read_geometry",
    "generate_boxes",
    "check_hulls",
    "generate_polyhedra",
    "case_from_tables",
]

#: The [geometry] forms of a 3D wall: an explicit list of boxes, the generators' tables (of boxes, and of a vault's
#: or a dome's polyhedra), and a list of convex polyhedra (alone or beside boxes).
GEOMETRY_KINDS_3D = ("boxes", "leaf", "u_wall", "corner", "buttressed_wall", "polyhedra", "barrel_vault", "cross_vault",
                     "dome")
#: Keys of [geometry.leaf]: a single leaf in running bond.
LEAF_KEYS = ("length", "height", "thickness", "block_length", "block_height", "first_course", "openings")
#: Keys of [geometry.u_wall] and [geometry.corner]: a facade with two return walls, or one.
BONDED_KEYS = ("facade", "height", "returns", "thickness", "block_length", "block_height", "openings")
#: Keys of [geometry.buttressed_wall]: a wall with buttresses, its lengths [m], then whether they are bonded.
BUTTRESSED_KEYS = ("length", "height", "thickness", "block_length", "block_height", "spacing", "buttress_width",
                   "buttress_depth", "bonded")

#: The [geometry] keys of convex polyhedra given by their vertices: wall blocks, and fixed ones.
SOLID_KEYS = ("polyhedra", "supports")
#: Keys of [geometry.barrel_vault] (``masonry_dem.barrel_vault``), [geometry.cross_vault] (``masonry_dem.cross_vault``)
#: and [geometry.dome] (``masonry_dem.dome``): their lengths [m], then their counts.
VAULT_LENGTHS = {
    "barrel_vault": ("span", "radius", "rise", "thickness", "length", "block_length", "abutment_width",
                     "abutment_height", "pier_width", "pier_height"),
    "cross_vault": ("span", "radius", "rise", "thickness", "abutment_width", "abutment_height", "pier_width",
                    "pier_height"),
    "dome": ("span", "radius", "rise", "thickness"),
}
VAULT_COUNTS = {"barrel_vault": ("voussoirs", "pier_courses"), "cross_vault": ("voussoirs", "pier_courses"),
                "dome": ("meridians", "parallels")}
VAULT_KINDS = {"barrel_vault": ("semicircular", "segmental", "pointed", "elliptical"),
               "cross_vault": ("semicircular", "pointed"), "dome": ("hemispherical", "pointed")}

# The core's generator of each [geometry] table, and the name its messages give the table.
_GENERATORS = {"leaf": "running_bond_3d", "u_wall": "u_wall", "corner": "corner", "buttressed_wall": "buttressed_wall"}


# --------------------------------------------------------------------------------------------------
# [geometry]
# --------------------------------------------------------------------------------------------------


def read_geometry(geo: _Table, kind: str) -> Dict[str, Any]:
    """The checked arguments of the 3D [geometry] form ``kind`` (one of :data:`GEOMETRY_KINDS_3D`)."""
    if "thickness" in geo:
        raise geo.key_error(
            "thickness",
            f"is the out-of-plane thickness of a wall in the plane; a 3D wall ([geometry] {kind}) has its thickness in "
            "its boxes" + ("" if kind == "boxes" else f" or in [geometry.{kind}] thickness"),
        )
    # vertex lists: each block the convex hull of its vertices, made (and refused) by the core (check_hulls)
    named = (("polyhedra", "block"), ("supports", "support"))
    solids = {key: geo.polygons(key, what, dimension=3) for key, what in named if key in geo}
    if kind in ("boxes", "polyhedra"):
        return dict(boxes=_boxes(geo) if "boxes" in geo else [], **solids)
    if kind in VAULT_LENGTHS:
        return _vault(geo, kind)
    if kind == "buttressed_wall":
        table = geo.table(kind, BUTTRESSED_KEYS)
        assert table is not None
        args = {name: table.number(name, check=_positive, unit="length") for name in BUTTRESSED_KEYS[:-1]}
        bonded = table.data.get("bonded", True)
        if not isinstance(bonded, bool):
            raise table.key_error("bonded", f"expected true or false, {_got(bonded)}")
        return dict(args, bonded=bonded, **solids)
    if kind == "leaf":
        table = geo.table("leaf", LEAF_KEYS)
        assert table is not None
        names = ("length", "height", "thickness", "block_length", "block_height")
        args = {name: table.number(name, check=_positive, unit="length") for name in names}
        args["first_course"] = _first_course(table)
    else:
        table = geo.table(kind, BONDED_KEYS)
        assert table is not None
        names = ("facade", "height", "returns", "thickness", "block_length", "block_height")
        args = {name: table.number(name, check=_positive, unit="length") for name in names}
    args["openings"] = _openings(table)
    return dict(args, **solids)


def check_hulls(geometry: Mapping[str, Any], source: str) -> None:
    """The core's refusals of the vertex lists of ``polyhedra`` and ``supports`` (fewer than 4 vertices off one
    plane), named by their keys in the case file (``geometry.polyhedra[3]: ...``) after the file name."""
    for key in SOLID_KEYS:
        if geometry.get(key):
            try:
                _core.convex_hulls(geometry[key], f"geometry.{key}")
            except InputError as exc:
                raise InputError(f"{source}: {exc}", getattr(exc, "key", None)) from exc


def _vault(geo: _Table, kind: str) -> Dict[str, Any]:
    """[geometry.barrel_vault], [geometry.cross_vault] or [geometry.dome]: the arguments of the core's generator, each
    checked alone (a length > 0, with its unit or not; a count >= 1; the kind); how they go together is the
    generator's to check, its messages naming the key."""
    table = geo.table(kind, ("kind",) + VAULT_LENGTHS[kind] + VAULT_COUNTS[kind])
    assert table is not None
    args: Dict[str, Any] = {"kind": table.string("kind", choices=VAULT_KINDS[kind])}
    args.update({key: table.number(key, None, _positive, unit="length") for key in VAULT_LENGTHS[kind]})
    args.update({key: table.integer(key, None, minimum=1) for key in VAULT_COUNTS[kind]})
    required = {"barrel_vault": ("voussoirs", "length"), "cross_vault": ("voussoirs",)}.get(kind, VAULT_COUNTS[kind])
    for key in ("thickness",) + required:
        if args[key] is None:
            raise table.missing(key)
    return args


def generate_polyhedra(kind: str, arguments: Mapping[str, Any], source: str) -> Dict[str, Any]:
    """The polyhedra and supports (vertex lists) of a checked [geometry.barrel_vault], [geometry.cross_vault] or
    [geometry.dome]; the core's refusals get the file name in front."""
    given = {key: value for key, value in arguments.items() if value is not None}
    try:
        made = {"barrel_vault": _core.barrel_vault, "cross_vault": _core.cross_vault, "dome": _core.dome}[kind]
        return dict(made(**given))
    except MasonryError as exc:
        again = type(exc)(f"{source}: {exc}")
        if isinstance(exc, InputError):
            again.key = getattr(exc, "key", None) or f"geometry.{kind}"
        raise again from exc


def _boxes(geo: _Table) -> List[List[float]]:
    """``boxes``: at least one box [x0, y0, z0, x1, y1, z1] (m) with x1 > x0, y1 > y0 and z1 > z0."""
    items = geo.array("boxes")
    assert items is not None
    if not items:
        raise geo.key_error("boxes", "expected at least one box [x0, y0, z0, x1, y1, z1]")
    boxes = []
    for i, item in enumerate(items):
        label = f"{geo.where('boxes')}[{i}]"
        x0, y0, z0, x1, y1, z1 = geo.numbers(label, item, 6, " [x0, y0, z0, x1, y1, z1]", unit="length")
        if not (x1 > x0 and y1 > y0 and z1 > z0):
            raise geo.error(f"{label}: expected x1 > x0, y1 > y0 and z1 > z0, got {item}", label)
        boxes.append([x0, y0, z0, x1, y1, z1])
    return boxes


def _first_course(table: _Table) -> Any:
    """``first_course`` of a leaf: "half" or "full", or an offset [m] >= 0 of the lowest course's joints; None
    when left out (the generator's default, "half")."""
    value = table.data.get("first_course")
    if value is None:
        return None
    if isinstance(value, str) and value in ("half", "full"):
        return value
    if isinstance(value, str):
        try:  # a length with its unit, "200 mm"
            return table.number("first_course", check=lambda x: None if x >= 0 else "must be >= 0", unit="length")
        except InputError:
            pass
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        return table.number("first_course", check=lambda x: None if x >= 0 else "must be >= 0", unit="length")
    raise table.key_error("first_course", f'expected "half", "full" or an offset [m] of the lowest course, {_got(value)}')


def _openings(table: _Table) -> Optional[List[List[float]]]:
    """``openings``: rectangles [x0, z0, x1, z1] (m) through the facade, x1 > x0 and z1 > z0 (None: none)."""
    items = table.array("openings", required=False)
    if items is None:
        return None
    rects = []
    for i, item in enumerate(items):
        label = f"{table.where('openings')}[{i}]"
        x0, z0, x1, z1 = table.numbers(label, item, 4, " [x0, z0, x1, z1]", unit="length")
        if not (x1 > x0 and z1 > z0):
            raise table.error(f"{label}: expected x1 > x0 and z1 > z0, got {item}", label)
        rects.append([x0, z0, x1, z1])
    return rects


def generate_boxes(kind: str, arguments: Mapping[str, Any], source: str) -> np.ndarray:
    """The boxes of a checked 3D [geometry] of ``kind``; the core's refusals (a last course too thin, a return
    too short, an opening over a corner) get the file name in front and the case file's key names."""
    if kind in ("boxes", "polyhedra"):
        return np.asarray(arguments["boxes"], dtype=np.float64).reshape(-1, 6)
    given = {key: value for key, value in arguments.items() if value is not None and key not in SOLID_KEYS}
    make = {"leaf": _core.running_bond_3d, "u_wall": _core.u_wall, "corner": _core.corner_wall,
            "buttressed_wall": _core.buttressed_wall}[kind]
    try:
        return np.asarray(make(**given), dtype=np.float64).reshape(-1, 6)
    except MasonryError as exc:
        message, key = _renamed(str(exc), kind), getattr(exc, "key", None)
        again = type(exc)(f"{source}: {message}")
        if isinstance(exc, InputError):
            again.key = _renamed(key, kind) if key else f"geometry.{kind}"
        raise again from exc


def _renamed(text: str, kind: str) -> str:
    """A message (or key) of the core's generator with its names as the case file's: ``u_wall.returns`` is
    ``geometry.u_wall.returns``, ``openings`` is ``geometry.u_wall.openings``."""
    text = text.replace("first_course_offset", "first_course")
    text = re.sub(rf"(?<![\w.]){_GENERATORS[kind]}\.(?=[a-z])", f"geometry.{kind}.", text)
    if kind == "leaf":  # the leaf's generator's bare name (the corner's would match "the corner")
        text = re.sub(r"(?<![\w.])running_bond_3d(?!\w)", "geometry.leaf", text)
    # the openings' messages start with their name
    return re.sub(r"^(?:\w+\.)?openings(?=[\[:]|$)", f"geometry.{kind}.openings", text)


# --------------------------------------------------------------------------------------------------
# The case
# --------------------------------------------------------------------------------------------------


def case_from_tables(top: _Table, title: str, kind: str, geometry: Dict[str, Any], density: Optional[float]) -> Any:
    """The :class:`masonry_dem.case.Case` of a 3D wall: its [geometry] already read (``kind``, ``geometry``,
    ``density``), the other tables read here with the keys both dimensions share, and the refusals."""
    base = _base(top)
    if base is None and geometry.get("supports"):
        base = False  # a wall on supports has no foundation unless a [base] table puts one
    check_hulls(geometry, top.source)
    beam = _top_beam(top)
    joints = _joints(top)
    gravity, live, direction, carried = _loads(top)
    method, analysis = _analysis(top, default_method="limit")
    if method not in METHODS_3D:
        raise top.error(f'analysis.method = "{method}": {IN_3D} (this case is 3D: [geometry] {kind})',
                        "analysis.method")
    if method == "dynamic" and analysis.control == "displacement":
        raise top.error(f'analysis.control = "displacement": {LOAD_CONTROL_3D} (this case is 3D: [geometry] {kind})',
                        "analysis.control")
    if analysis.move_support is not None:
        raise top.error("analysis.move_support: a support's movement is in the plane only in this version (this "
                        f"case is 3D: [geometry] {kind})", "analysis.move_support")
    table = top.table("reference", REFERENCE_KEYS)
    reference = _reference(table, default_methods=("limit",))
    if reference is not None:
        others = [m for m in reference["methods"] if m not in METHODS_3D]
        if others:
            assert table is not None
            raise table.key_error("methods", f"{_quote(others[0])}: {IN_3D}")
    if kind in VAULT_LENGTHS:
        made = generate_polyhedra(kind, geometry, top.source)
        boxes, polyhedra, supports = None, made["polyhedra"], made["supports"]
        if supports and base is None:  # a vault on its abutments: no base unless [base] asks for one
            base = False
    else:
        boxes = generate_boxes(kind, geometry, top.source)
        polyhedra, supports = geometry.get("polyhedra"), geometry.get("supports")
    model = ModelParameters3D(boxes=boxes, density=density, base=base, top=beam, joints=joints, gravity=gravity,
                              live=live, direction=direction, carried=carried, polyhedra=polyhedra, supports=supports)
    assert isinstance(analysis, AnalysisParameters)
    return Case(title=title, model=model, analysis=analysis, method=method, source=top.source, reference=reference)


def _top_beam(top: _Table) -> Optional[float]:
    """[top] of a 3D wall: the beam's ``height`` [m] (required in the table); None without the table."""
    table = top.table("top", ("rotation", "force", "vertical", "height"))
    if table is None:
        return None
    for key in ("rotation", "force", "vertical"):
        if key in table:
            raise table.key_error(key, "belongs to the top beam of a wall in the plane; the top beam of a 3D wall is "
                                       "free and weighs: give its height [m] only")
    if "height" not in table:
        raise table.error("missing key 'height' in [top] (the top beam's height [m]: a 3D wall's beam has a size "
                          "and a weight)", table.where("height"))
    return float(table.number("height", check=_positive, unit="length"))


def _loads(top: _Table) -> Any:
    """[loads] of a 3D wall: gravity, live ("horizontal_weight" only), direction [deg] and the carried loads (None:
    left out)."""
    table = top.table("loads", ("gravity", "live", "direction", "carried"))
    if table is None:
        return None, None, None, None
    gravity = table.number("gravity", None, _non_negative, unit="acceleration")
    live = table.string("live", None, ("horizontal_weight", "top_horizontal"))
    if live == "top_horizontal":
        raise table.key_error("live", '"top_horizontal" pushes the top beam of a wall in the plane; a 3D wall takes '
                                      '"horizontal_weight" (in plan along direction)')
    direction = table.number("direction", None)
    if direction is not None and not math.isfinite(direction):  # pragma: no cover - number() refuses it
        raise table.key_error("direction", f"expected a finite angle [deg], got {direction}")
    return gravity, live, direction, _carried(table, 3)
