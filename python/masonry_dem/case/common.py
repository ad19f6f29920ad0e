"""The tables a case file of either dimension reads alike: [base], [joints] (and its family sub-tables), [analysis]
and [reference], with their key lists. :mod:`.reader` reads a wall in the plane with them,
:mod:`masonry_dem.space.case` a 3D wall; the keys mean the same in both (docs/case-format.md).
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Tuple

from .. import _core
from .mapping import CORE_DEFAULTS, EXPLICIT_OPTIONS, METHODS, AnalysisParameters
from .table import _got, _non_negative, _open_unit, _positive, _quote, _Table

# Keys of a joint law, in the order of docs/case-format.md, and the interface families that may override them.
# the joint-law keys come from the core, which defines the law
LAW_KEYS = tuple(_core.JOINT_LAW_KEYS)
FAMILIES = ("bed", "head", "base", "top")

# Keys of [analysis]: those of the incremental methods (static and dynamic), then those of the explicit solver
# only. Limit analysis (method = "limit") has no load path: it uses none of them (they are checked, then ignored).
ANALYSIS_KEYS = ("method", "control", "control_point", "max_displacement", "steps", "tolerance")
# Keys of limit analysis along the mechanism (in the plane; refused for a 3D wall).
FOLLOW_KEYS = ("follow_mechanism", "follow_step", "follow_steps")
# Keys of a support's movement (in the plane; limit analysis along it or the explicit solver driving it).
MOVEMENT_KEYS = ("move_support", "move_direction")
MOVE_DIRECTIONS = ("+x", "-x", "+y", "-y")
DYNAMIC_KEYS = EXPLICIT_OPTIONS  # the explicit solver's options, by the same names
DAMPINGS = ("local", "viscous", "none")
# Keys of the optional [reference] table (a published or exact answer, checked by ``masonry-dem validate``).
REFERENCE_KEYS = ("collapse_multiplier", "tolerance", "source", "methods")

#: The kind of quantity of each joint-law key that also takes a string with its unit ("0.25 MPa"; the others
#: are dimensionless). docs/case-format.md, "Units", lists these and the other keys that take units.
LAW_UNITS = {
    "normal_stiffness": "stiffness",
    "shear_stiffness": "stiffness",
    "cohesion": "stress",
    "tensile_strength": "stress",
    "fracture_energy_tension": "fracture_energy",
    "fracture_energy_shear": "fracture_energy",
}
#: The relative tolerance of a [reference] that gives none (a default of the case file, not of the core).
DEFAULT_REFERENCE_TOLERANCE = 0.01


def _base(top: _Table) -> Optional[bool]:
    """[base]: whether the wall stands on a fixed foundation (None: left out)."""
    table = top.table("base", ("kind",))
    kind = None if table is None else table.string("kind", None, ("fixed", "none"))
    return None if kind is None else kind == "fixed"


def _joints(top: _Table) -> Optional[Dict[str, Dict[str, float]]]:
    """[joints] and its family sub-tables: {"default": law, family: law}, the keys given (None: none)."""
    table = top.table("joints", LAW_KEYS + FAMILIES)
    joints: Dict[str, Dict[str, float]] = {}
    if table is not None:
        default_law = _law(table)
        if default_law:
            joints["default"] = default_law
        for family in FAMILIES:
            family_table = table.table(family, LAW_KEYS)
            if family_table is not None:
                joints[family] = _law(family_table)
    return joints or None


def _law(table: _Table) -> Dict[str, float]:
    """The joint-law keys present in a [joints] or [joints.<family>] table."""
    # stiffnesses must be positive, every other parameter non-negative (the core checks the rest)
    positive = ("normal_stiffness", "shear_stiffness")
    return {
        key: table.number(key, check=_positive if key in positive else _non_negative, unit=LAW_UNITS.get(key))
        for key in LAW_KEYS
        if key in table
    }


def _analysis(top: _Table, default_method: str = "static") -> Tuple[str, AnalysisParameters]:
    """[analysis]: the method (``default_method`` when left out: "static"; a 3D wall's, "limit") and the
    solvers' options given."""
    table = top.table("analysis", ANALYSIS_KEYS + DYNAMIC_KEYS + FOLLOW_KEYS + MOVEMENT_KEYS)
    if table is None:
        return default_method, AnalysisParameters()
    method = table.string("method", default_method, METHODS)
    control = table.string("control", None, ("load", "displacement"))
    table.string("control_point", None, ("top",))
    options = dict(
        control=control,
        max_displacement=table.number("max_displacement", None, _positive, unit="length"),
        steps=table.integer("steps", None, minimum=1),
        tolerance=table.number("tolerance", None, _open_unit),
    )
    movement = _movement_options(table, method)
    return method, AnalysisParameters(**options, **_dynamic_options(table), **_follow_options(table, movement), **movement)


def _movement_options(table: _Table, method: str) -> Dict[str, Any]:
    """The keys of a support's movement, checked (None: left out): both or neither, with method "limit" or
    "dynamic"; the explicit solver's (method = "dynamic") needs max_displacement and displacement control."""
    support = table.integer("move_support", None, minimum=0)
    direction = table.string("move_direction", None, MOVE_DIRECTIONS)
    if support is None and direction is None:
        return dict(move_support=None, move_direction=None)
    if support is None:
        raise table.key_error("move_direction", "needs move_support (the support that moves, 0-based)")
    if direction is None:
        raise table.key_error("move_support", f"needs move_direction ({', '.join(_quote(d) for d in MOVE_DIRECTIONS)})")
    if method == "static":
        raise table.key_error("move_support", 'is taken by method = "limit" or "dynamic", not "static"')
    if method == "dynamic" and "max_displacement" not in table:
        raise table.key_error("move_support", "needs max_displacement with method = \"dynamic\" (how far the support moves)")
    if method == "dynamic" and table.string("control", None, ("load", "displacement")) == "load":
        raise table.key_error("control", 'must be "displacement" with move_support (the support is driven)')
    if table.boolean("follow_mechanism", None):
        raise table.key_error("follow_mechanism", "a support's movement is followed already: leave it out with move_support")
    return dict(move_support=support, move_direction=direction)


def _follow_options(table: _Table, movement: Dict[str, Any]) -> Dict[str, Any]:
    """The keys of limit analysis along the mechanism, checked (None: left out); follow_step and follow_steps
    only with follow_mechanism = true or a support's movement."""
    follow = table.boolean("follow_mechanism", None)
    step = table.number("follow_step", None, _positive, unit="length")
    steps = table.integer("follow_steps", None, minimum=1, maximum=_core.MAX_FOLLOW_STEPS)
    for key, value in (("follow_step", step), ("follow_steps", steps)):
        if value is not None and not follow and movement["move_support"] is None:
            raise table.key_error(key, "needs follow_mechanism = true (or move_support)")
    return dict(follow_mechanism=follow, follow_step=step, follow_steps=steps)


def _dynamic_options(table: _Table) -> Dict[str, Any]:
    """The explicit solver's keys of [analysis], checked (None: left out)."""
    damping = table.string("damping", None, DAMPINGS)
    coefficient = table.number("damping_coefficient", None, _non_negative)
    if coefficient is not None and (damping or CORE_DEFAULTS["damping"]) == "local" and coefficient >= 1:
        raise table.key_error(
            "damping_coefficient", f'must be < 1 with damping = "local" (alpha in [0, 1)), got {coefficient}'
        )
    return dict(
        damping=damping,
        damping_coefficient=coefficient,
        time_step=table.number("time_step", None, _positive, unit="time"),
        unbalanced_ratio=table.number("unbalanced_ratio", None, _open_unit),
        threads=table.integer("threads", None, minimum=0),
        large_rotations=table.boolean("large_rotations", None),
        contact_update=table.boolean("contact_update", None),
    )


def _reference(table: Optional[_Table], default_methods: Tuple[str, ...] = METHODS) -> Optional[Dict[str, Any]]:
    """The [reference] table, checked: collapse_multiplier (required), tolerance, source, and methods (the
    methods the reference applies to; ``default_methods`` by default: all, or a 3D wall's, limit analysis alone)."""
    if table is None:
        return None
    methods = table.array("methods", required=False)
    if methods is None:
        methods = list(default_methods)
    for i, m in enumerate(methods):
        if m not in METHODS:
            options = ", ".join(_quote(c) for c in METHODS)
            got = _quote(m) if isinstance(m, str) else _got(m)
            raise table.key_error("methods", f"entry {i}: expected one of {options}, got {got}")
    if not methods:
        raise table.key_error("methods", "must name at least one method")
    return {
        "collapse_multiplier": table.number("collapse_multiplier"),
        "tolerance": table.number("tolerance", DEFAULT_REFERENCE_TOLERANCE, _open_unit),
        "source": table.string("source", ""),
        "methods": tuple(methods),
    }


#: The keys of a load of [[loads.carried]].
CARRIED_KEYS = ("block", "point", "weight")


def _carried(table: _Table, dimension: int) -> Optional[List[Tuple[int, List[float], float]]]:
    """[[loads.carried]]: the loads carried by wall blocks, each (block, point, weight): the block's 0-based index,
    the point [m] (``dimension`` coordinates) and the weight [N]; None when the key is left out. The core checks
    the block and the point against the wall."""
    items = table.array("carried", required=False)
    if items is None:
        return None
    loads = []
    for k, item in enumerate(items):
        if not isinstance(item, dict):
            raise table.error(f"{table.where('carried')}[{k}]: expected a table with keys {', '.join(CARRIED_KEYS)} "
                              f"([[loads.carried]]), {_got(item)}", f"{table.where('carried')}[{k}]")
        load = _Table(item, f"{table.where('carried')}[{k}]", table.source, CARRIED_KEYS)
        coordinates = "[x, y]" if dimension == 2 else "[x, y, z]"
        point = load.numbers(load.where("point"), load.array("point"), dimension, f" {coordinates}", unit="length")
        weight = load.number("weight", check=_non_negative, unit="force")
        loads.append((load.integer("block", minimum=0), point, weight))
    return loads
