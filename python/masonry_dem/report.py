"""Plain-text reports of an analysis: the summary printed by the command line and a one-line
description of the collapse mechanism, derived from ``Results.mechanism`` and the joint states.

Also the kinematic helpers shared with :mod:`masonry_dem.plot` (no matplotlib here). :func:`summary` reads both
dimensions: a 3D wall's mechanism is described by :mod:`masonry_dem.space.report` (what the two share is in
:mod:`masonry_dem._mechanism`, below both).
Lengths in m, rotations in rad; a positive rotation is counterclockwise.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Mapping, NamedTuple, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

from ._shapes import Shapes, centroids as block_centroids, moved_vertices, rect_vertices, shapes
from ._mechanism import CRACK_TOLERANCE, MOVING_FRACTION, connected_parts as _connected_parts, mechanism_text, plural as _plural

__all__ = [
    "OPEN",
    "SLIDING",
    "ROCKING",
    "corner_motion",
    "deformed_corners",
    "describe_mechanism",
    "hinges",
    "describe_hinges",
    "interface_categories",
    "interface_jumps",
    "format_multiplier",
    "multiplier_symbol",
    "format_status",
    "certificate_text",
    "summary",
]

#: Bit flags of Results.interface_states (0 is elastic).
OPEN, SLIDING, ROCKING = 1, 2, 4


def interface_categories(states: npt.ArrayLike) -> List[str]:
    """The drawing category of each interface from its bit flags (1 open, 2 sliding, 4 rocking).

    An open interface carries nothing and is drawn as open whatever else is set.
    """
    out = []
    for s in np.asarray(states, dtype=np.int64):
        if s & OPEN:
            out.append("open")
        elif s & SLIDING and s & ROCKING:
            out.append("sliding + rocking")
        elif s & SLIDING:
            out.append("sliding")
        elif s & ROCKING:
            out.append("rocking")
        else:
            out.append("elastic")
    return out


def _as_shapes(blocks: Any) -> Shapes:
    """``blocks`` as :class:`masonry_dem._shapes.Shapes`: those themselves, or rectangles (n, 4) [x0, y0, x1, y1]."""
    return blocks if isinstance(blocks, Shapes) else Shapes.from_rects(blocks)


def corner_motion(blocks: Any, motion: np.ndarray) -> np.ndarray:
    """(n,) largest vertex displacement [m] of each block for the small motion (u1, u2, phi) at its centroid.
    ``blocks``: the blocks' :class:`masonry_dem._shapes.Shapes` (:func:`masonry_dem._shapes.shapes` of a model), or
    rectangles (n, 4) [x0, y0, x1, y1]."""
    return _as_shapes(blocks).vertex_motion(motion)


def deformed_corners(block: Sequence[Any], motion: Sequence[float], scale: float, centroid: Any = None) -> np.ndarray:
    """(k, 2) vertices [m] of a block moved by ``scale`` * (u1, u2) [m] and turned by ``scale`` * phi [rad]
    about its centroid. ``block``: a rectangle [x0, y0, x1, y1] (its 4 corners counter-clockwise from (x0, y0)) or
    the vertices (k, 2) of a polygon; ``centroid``: the block's (by default the area's). The rotation is applied
    exactly, so the drawn block keeps its shape."""
    b = np.asarray(block, dtype=np.float64)
    vertices = rect_vertices(b) if b.shape == (4,) else b
    return moved_vertices(vertices, motion, scale, centroid)


def interface_jumps(model: Any, motion: np.ndarray) -> np.ndarray:
    """(m, 3) jumps of a motion (n_all, 3) of the blocks across each interface: slip [m] (along the
    tangent), and the normal gaps [m] at the two ends of the interface, largest first (positive opens).

    With the interface normal n from block a to block b and ``[u] = u_b(c) - u_a(c)`` at the interface
    centroid c: slip = t.[u], gaps = n.[u] +/- (phi_b - phi_a) l / 2.
    """
    j = _end_jumps(model, motion)
    return np.c_[j[:, 0], np.maximum(j[:, 1], j[:, 2]), np.minimum(j[:, 1], j[:, 2])]  # type: ignore[no-any-return]


def _end_jumps(model: Any, motion: np.ndarray) -> np.ndarray:
    """(m, 3) jumps of a motion across each interface: slip [m] along the tangent t = (n_y, -n_x), and the normal
    gaps [m] at the ends c - l/2 t and c + l/2 t, n.[u] - (phi_b - phi_a) l / 2 and n.[u] + (phi_b - phi_a) l / 2
    (the jump of b over a at c + s t is [u] at c + (phi_b - phi_a) s k x t, and k x t = n)."""
    cents = block_centroids(model)
    pairs = np.asarray(model.interface_blocks, dtype=np.int64).reshape(-1, 2)
    geom = np.asarray(model.interface_geometry, dtype=np.float64).reshape(-1, 5)
    out = np.zeros((len(pairs), 3))
    for k, ((a, b), (cx, cy, nx, ny, length)) in enumerate(zip(pairs, geom)):
        c = np.array([cx, cy])
        ua = _transport(motion[a], cents[a], c)
        ub = _transport(motion[b], cents[b], c)
        du = ub[:2] - ua[:2]
        dn, dt = nx * du[0] + ny * du[1], -ny * du[0] + nx * du[1]
        turn = (ub[2] - ua[2]) * length / 2
        out[k] = (dt, dn - turn, dn + turn)
    return out


def _transport(motion: np.ndarray, src: np.ndarray, dst: np.ndarray) -> np.ndarray:
    """The rigid motion (u1, u2, phi) given at point ``src`` expressed at point ``dst``."""
    u1, u2, phi = motion
    d = dst - src
    return np.array([u1 - phi * d[1], u2 + phi * d[0], phi])


def _describe_part(blocks: Shapes, motion: np.ndarray, part: Sequence[int]) -> str:
    """'turning clockwise about (x, y) m' or 'sliding at +43 deg from +x': the area-weighted mean rigid
    motion of one part."""
    areas = blocks.areas[list(part)]
    cents = blocks.centroids[list(part)]
    r = (areas[:, None] * cents).sum(axis=0) / areas.sum()
    at_r = np.array([_transport(motion[i], cents[k], r) for k, i in enumerate(part)])
    u1, u2, phi = (areas[:, None] * at_r).sum(axis=0) / areas.sum()
    box = blocks.bounds[list(part)]
    lo, hi = box[:, :2].min(axis=0), box[:, 2:].max(axis=0)
    size = float(np.hypot(*(hi - lo)))
    speed = math.hypot(u1, u2)
    if abs(phi) * 5.0 * size < speed:  # the centre of rotation is far away: a translation
        angle = math.degrees(math.atan2(u2, u1))
        return f"sliding at {angle:+.0f} deg from +x"
    sense = "counterclockwise" if phi > 0 else "clockwise"
    px, py = r[0] - u2 / phi, r[1] + u1 / phi
    return f"turning {sense} about ({px:.2f}, {py:.2f}) m"


def describe_mechanism(model: Any, results: Any) -> str:
    """One line on the mechanism (``Results.mechanism``: the last displacement increment, or the collapse
    velocities of a limit analysis).

    It says how many wall blocks move; the parts they form (blocks held together by interfaces
    that the crack does not cross), each turning (clockwise or not, about its instantaneous centre
    [m]) or sliding; and the crack: the interfaces across which the mechanism slips, separates (a gap at
    both ends), or rocks (a gap at one end only), counted by family. An interface may both slip and
    separate. ("open" is kept for the joint states: an interface at its tension cut-off, carrying nothing.)"""
    blocks = shapes(model)
    n = int(model.n_blocks)
    mech = np.asarray(results.mechanism, dtype=np.float64)
    # a limit analysis has no increments: its mechanism is the collapse velocities, zero without a collapse
    nothing = "none (no collapse)" if str(getattr(results, "method", "")) == "limit" else "none (no displacement increment)"
    if mech.shape != (len(blocks), 3) or not np.all(np.isfinite(mech)):
        return nothing
    # The bodies that may move: the wall blocks and the top beam (not the base, nor the supports).
    top = model.top_index
    bodies = list(range(n)) + ([int(top)] if top is not None else [])
    cm = blocks.vertex_motion(mech)
    peak = float(max(cm[i] for i in bodies))
    if not peak > 0:
        return nothing
    moving = [i for i in bodies if cm[i] > MOVING_FRACTION * peak]
    n_moving = sum(1 for i in moving if i < n)
    beam = " and the top beam" if top is not None and int(top) in moving else ""  # the beam is no wall block

    # The crack: the interfaces across which the mechanism has a jump.
    families = list(model.interface_family)
    jumps = interface_jumps(model, mech)
    tol = CRACK_TOLERANCE * peak
    slips = [k for k, (slip, _, _) in enumerate(jumps) if abs(slip) > tol]
    opens = [k for k, (_, _, g_min) in enumerate(jumps) if g_min > tol]
    rocks = [k for k, (_, g_max, g_min) in enumerate(jumps) if g_max > tol >= g_min]
    cracked = np.zeros(len(jumps), dtype=bool)
    cracked[slips + opens + rocks] = True

    # The parts: moving blocks held together by uncracked interfaces.
    parts = _connected_parts(moving, np.asarray(model.interface_blocks), list(cracked))
    parts.sort(key=len, reverse=True)
    crack = ((slips, "slip"), (opens, "separate"), (rocks, "rock"))
    describe = lambda part: _describe_part(blocks, mech, part)  # noqa: E731
    return mechanism_text(n_moving, n, beam, parts, describe, crack, families, "interface")


class Hinge(NamedTuple):
    """A hinge of a mechanism: the interface ``interface`` opens by rotation about its end ``point`` [m] (x, y);
    ``end``: which end, "intrados" or "extrados" on an arch's joint, else "left" or "right" on a joint within 45
    degrees of the horizontal, "bottom" or "top" on a steeper one."""

    interface: int
    point: np.ndarray
    end: str


def hinges(model: Any, motion: np.ndarray, arch: Optional[Mapping[str, Any]] = None) -> List[Hinge]:
    """The hinges of the mechanism ``motion`` ((n_all, 3): u1, u2, phi of each block): every interface that opens
    by rotation, a gap at one end and none at the other (a "rock" of :func:`describe_mechanism`), with the end it
    turns about, left to right (then bottom to top).

    The gap at the end c + s t of an interface (s = +/- l/2 along its tangent t) is n.[u] at c + (phi_b - phi_a) s:
    the interface turns about the end whose gap is the smaller. ``arch``: the arch's ``intrados`` and
    ``extrados`` (the arch generator's curves, each a list of points (x, y) in m): an end nearer the intrados than the
    extrados is "intrados", else "extrados" (on an arch's joint, the end nearer its centre, or farther). Without it, an
    end is named by its side."""
    mech = np.asarray(motion, dtype=np.float64)
    cm = shapes(model).vertex_motion(mech)
    peak = float(cm.max()) if len(cm) else 0.0
    if not peak > 0:
        return []
    tol = CRACK_TOLERANCE * peak
    geom = np.asarray(model.interface_geometry, dtype=np.float64).reshape(-1, 5)
    jumps = _end_jumps(model, mech)
    gaps = np.sort(jumps[:, 1:], axis=1)
    curves = None if arch is None else [np.asarray(arch[k], dtype=np.float64).reshape(-1, 2) for k in ("intrados",
                                                                                                       "extrados")]
    out = []
    for k in np.flatnonzero((gaps[:, 1] > tol) & (gaps[:, 0] <= tol)):
        cx, cy, nx, ny, length = geom[k]
        ends = [np.array([cx + s * ny, cy - s * nx]) for s in (-length / 2, length / 2)]  # c + s t, t = (ny, -nx)
        shut = 0 if jumps[k, 1] <= jumps[k, 2] else 1  # the end of the smaller gap: the hinge
        point, other = ends[shut], ends[1 - shut]
        if curves is not None:
            end = "intrados" if _distance(point, curves[0]) < _distance(point, curves[1]) else "extrados"
        elif abs(ny) >= abs(nx):
            end = "left" if point[0] < other[0] else "right"
        else:
            end = "bottom" if point[1] < other[1] else "top"
        out.append(Hinge(int(k), point, end))
    out.sort(key=lambda h: (round(float(h.point[0]), 9), round(float(h.point[1]), 9)))
    return out


def _distance(point: np.ndarray, curve: np.ndarray) -> float:
    """The distance [m] from a point to a polyline (its segments; a point alone for a curve of one point)."""
    if len(curve) == 1:
        return float(np.hypot(*(point - curve[0])))
    a, d = curve[:-1], np.diff(curve, axis=0)
    t = np.clip(((point - a) * d).sum(axis=1) / np.maximum((d * d).sum(axis=1), 1e-300), 0.0, 1.0)
    return float(np.hypot(*(a + t[:, None] * d - point).T).min())


#: The most hinges :func:`describe_hinges` lists one by one.
HINGES_LISTED = 6


def describe_hinges(model: Any, results: Any, arch: Optional[Mapping[str, Any]] = None) -> str:
    """The hinges of the mechanism (``Results.mechanism``, :func:`hinges`) in a line: "4: the intrados of a bed joint
    at (x, y) m, the extrados of a bed joint at (x, y) m, ..." (on a wall: "the right end of a base joint at ..."),
    left to right, at most
    :data:`HINGES_LISTED` of them; "none" when no interface opens by rotation. ``arch`` as in :func:`hinges`."""
    mech = np.asarray(results.mechanism, dtype=np.float64)
    if mech.shape != (len(block_centroids(model)), 3) or not np.all(np.isfinite(mech)):
        return "none"
    found = hinges(model, mech, arch)
    if not found:
        return "none"
    families = list(model.interface_family)
    shown = [f"the {h.end}{'' if arch is not None else ' end'} of a {families[h.interface]} joint at "
             f"({h.point[0]:.2f}, {h.point[1]:.2f}) m" for h in found[:HINGES_LISTED]]
    more = f", {len(found) - HINGES_LISTED} more" if len(found) > HINGES_LISTED else ""
    return f"{len(found)}: " + ", ".join(shown) + more


def multiplier_symbol(live: str = "horizontal_weight") -> str:
    """The symbol of the load multiplier: λ, or H (the horizontal force on the top beam) with
    ``live = "top_horizontal"``."""
    return "H" if live == "top_horizontal" else "λ"


def format_multiplier(value: float, live: str = "horizontal_weight", symbol: bool = False) -> str:
    """A load multiplier for people, the package's one formatter of it (summaries, tables, plots, progress):
    lambda with 4 decimals, or with ``live = "top_horizontal"`` the horizontal force on the beam in kN (4
    significant digits); "none" when it is not finite. ``symbol``: its symbol in front, "λu = 0.6429" or
    "Hu = 56.9 kN" ("λu: none")."""
    top = live == "top_horizontal"
    if not math.isfinite(value):
        text = None
    else:
        text = f"{value / 1e3:.4g} kN" if top else f"{value:.4f}"
    if not symbol:
        return text or "none"
    name = multiplier_symbol(live) + "u"
    return f"{name} = {text}" if text else f"{name}: none"


#: Statuses that come with a reason in ``Results.error``, and what they mean in a word.
STATUS_NOTES = {
    "failed": "the solver failed",
    "interrupted": "stopped by the user",
    "no_equilibrium": "the wall cannot stand under its dead loads",
    "unbounded": "the live load finds no mechanism",
    "stalled": "the path stopped below the limit-analysis collapse multiplier",
    "displacement_limit": "the path left the small-displacement model with lambda still rising",
    "estimate": "a non-associative estimate of limit analysis, neither bound: not a collapse multiplier",
}


def format_status(results: Any) -> str:
    """The status for people: ``collapse``, or ``no_equilibrium (<reason>)`` for the statuses that have a
    reason (:data:`STATUS_NOTES`: failed, interrupted, no_equilibrium / unbounded / estimate of a limit
    analysis, stalled, displacement_limit)."""
    status = str(results.status)
    if status in STATUS_NOTES:
        reason = " ".join(str(results.error or STATUS_NOTES[status]).split())
        return f"{status} ({reason})"
    return status


def _sci(x: Any) -> str:
    return "-" if x is None or not math.isfinite(float(x)) else f"{float(x):.1e}"


def certificate_text(results: Any, live: str = "horizontal_weight") -> List[str]:
    """The lines on a limit analysis's certificate (empty for the other methods, or without one): the
    residuals and the gap of the interior point, the associative upper bound and the non-associative
    sequence when the joints are non-associative, and a note when cohesion or tensile strength were taken
    at their peak."""
    cert = getattr(results, "certificate", None)
    if not cert:
        return []
    lines = [
        f"primal residual {_sci(cert.get('primal_residual'))}, dual residual {_sci(cert.get('dual_residual'))}, "
        f"duality gap {_sci(cert.get('duality_gap'))} ({int(cert.get('iterations') or 0)} interior-point iterations)"
    ]
    bound = cert.get("upper_bound")
    if bound is not None and math.isfinite(float(bound)):
        n = int(cert.get("sequence") or 0)
        settled = "converged" if cert.get("sequence_converged") else "not converged"
        lines.append(
            f"non-associative joints: the multiplier is an estimate from {_plural(n, 'program')} after the "
            f"associative one ({settled}); associative upper bound {format_multiplier(float(bound), live)}"
        )
    if cert.get("peak_strengths"):
        lines.append("cohesion and tensile strength taken at their peak (no softening, no loss at failure)")
    return lines


def movement_text(results: Any, movement: Tuple[int, str]) -> List[str]:
    """The lines of a support's movement's result (``movement``: the support, 0-based, and its direction): where the
    wall falls (limit analysis: the end of the path of equilibria, no equilibrium within a step beyond; the explicit
    solver: between the last stage that settled and the first that did not) or how far it stood, and the force the
    wall exerts on the support along its movement (an arch's thrust against a spread)."""
    support, direction = movement
    d = np.asarray(results.curve_displacement, dtype=float)
    force = np.asarray(results.curve_multiplier, dtype=float)
    lines = [f"  support movement:    support {support} along {direction}"]
    collapse = str(results.status) == "collapse"
    bracket = getattr(results, "bracket", None)
    if collapse and bracket is not None:
        lines.append(f"  falls at:            a movement between {bracket[0]:.4g} m and {bracket[1]:.4g} m (the last stage "
                     "that settled .. the first that did not)")
    elif collapse:
        lines.append(f"  falls at:            a movement of {d[-1]:.4g} m (the path of equilibria ends there: no "
                     "equilibrium at any force on the support within a step beyond)")
    elif d.size:
        lines.append(f"  stood up to:         a movement of {d[-1]:.4g} m (no collapse)")
    if not collapse and results.error:
        lines.append(f"  why:                 {results.error}")
    if force.size:
        lines.append(f"  force on support:    {force[0] / 1e3:.4g} kN at the start"
                     + (" (the least of every admissible state)" if str(results.method) == "limit" else "")
                     + f", {force[-1] / 1e3:.4g} kN at {d[-1]:.4g} m, in {_plural(max(d.size - 1, 0), 'step')}")
    return lines


def summary(
    title: str, model: Any, results: Any, live: str = "horizontal_weight", arch: Optional[Mapping[str, Any]] = None,
    movement: Optional[Tuple[int, str]] = None,
) -> str:
    """The short human summary printed by ``masonry-dem run`` (several lines, no trailing newline).

    A limit analysis (method "limit") has no load path: its joint states are those of the collapse
    mechanism, and a ``certificate`` line (or lines) replaces the count of steps; one that followed its mechanism
    gets an ``along the mechanism`` line (the curve's ends and steps) and, when the curve stopped short of
    lambda = 0, a ``stopped short`` line with the reason. A static or explicit run checked
    against limit analysis (associative dry joints) gets a ``checked against`` line with the exact value (in 3D a
    lower bound). A 3D wall (a :class:`masonry_dem.Model3D`) gets a line with the live load's direction in plan, and
    its mechanism is described in 3D (:func:`masonry_dem.space.report.describe_mechanism`). A wall in the plane's
    collapse mechanism that opens joints by rotation gets a ``hinges`` line (:func:`describe_hinges`; ``arch``: the
    arch generator's intrados and extrados, ``Case.arch``, to name an arch's hinges by them). A support's movement
    (``movement``: the support and its direction) replaces the multiplier's lines with :func:`movement_text`'s."""
    describe = describe_mechanism
    three_d = int(getattr(model, "dimension", 2)) == 3
    if three_d:
        from .space.report import describe_mechanism as describe, direction_text
    states: Dict[str, int] = dict(results.joint_states)
    joint_text = ", ".join(f"{int(states.get(k, 0))} {k}" for k in ("elastic", "sliding", "rocking", "open"))
    # an interface that slides and rocks at once counts in both (the result file's convention): say how many,
    # so that the counts add up to the interfaces
    both = interface_categories(getattr(results, "interface_states", ())).count("sliding + rocking")
    if both:
        joint_text += f" ({both} both sliding and rocking)"
    limit = str(results.method) == "limit"
    collapse = str(results.status) == "collapse"
    lines = [
        title,
        f"  blocks:              {model.n_blocks}",
        f"  interfaces:          {model.n_interfaces}",
        f"  method:              {results.method}" + (" (limit analysis)" if limit else ""),
    ]
    if three_d:
        direction = getattr(model, "direction", None)
        load = f"λ times each block's weight, horizontal, towards {direction_text(direction)}" if direction is not None \
            else "none"
        lines.append(f"  live load:           {load}")
    lines.append(f"  status:              {format_status(results)}")
    if movement is not None:
        lines += movement_text(results, movement)
    else:
        lines.append(f"  collapse multiplier: {format_multiplier(float(results.collapse_multiplier), live)}"
                     + (" (peak horizontal force on the top beam)" if live == "top_horizontal" and collapse else ""))
    last = float(getattr(results, "last_equilibrium", math.nan))
    if movement is not None:
        pass
    elif str(results.status) == "estimate" and math.isfinite(last):
        lines.append(f"  estimate:            {format_multiplier(last, live)} (neither bound: not a collapse)")
    elif not collapse and math.isfinite(last):
        # no collapse shown: the largest multiplier at which the wall was found in equilibrium, for what it is
        lines.append(f"  last equilibrium:    {format_multiplier(last, live)} (not a collapse)")
    bracket = getattr(results, "bracket", None)
    if collapse and bracket is not None and movement is None:
        # explicit load control: the collapse multiplier is the bracket's lower end, the last level that settled
        lines.append(f"  bracket:             {format_multiplier(float(bracket[0]), live)} .. "
                     f"{format_multiplier(float(bracket[1]), live)} (the highest level that settled .. the lowest that "
                     "did not)")
    if limit:
        lines.append(f"  joint states:        {joint_text}" + ("; of the collapse mechanism" if collapse else ""))
    else:
        lines.append(f"  joint states:        {joint_text}; at the last equilibrium")
    # a mechanism is a claim of collapse too: none without one
    lines.append(f"  mechanism:           {describe(model, results) if collapse else 'none (no collapse)'}")
    if collapse and not three_d:
        hinge_text = describe_hinges(model, results, arch)
        if hinge_text != "none":
            lines.append(f"  hinges:              {hinge_text}")
    if limit:
        for k, text in enumerate(certificate_text(results, live)):
            lines.append(f"  {'certificate:' if k == 0 else '':<21}{text}")
        curve = np.asarray(results.curve_multiplier, dtype=float)
        if collapse and curve.size > 1 and movement is None:  # the mechanism followed on the moved geometry
            d = float(np.asarray(results.curve_displacement, dtype=float)[-1])
            lines.append(f"  along the mechanism: λ from {format_multiplier(float(curve[0]), live)} to "
                         f"{format_multiplier(float(curve[-1]), live)} at a displacement of {d:.4g} m of the control "
                         f"point, in {results.steps} steps")
            if results.error:
                lines.append(f"  stopped short:       {results.error}")
        lines.append(f"  elapsed:             {results.elapsed_s:.3g} s ({results.iterations} interior-point iterations)")
    else:
        cert = getattr(results, "certificate", None)
        if cert and cert.get("multiplier") is not None:
            # a run checked against limit analysis (associative dry joints: the exact multiplier, in either
            # dimension)
            exact = "exact for these associative dry joints"
            lines.append(
                f"  checked against:     limit analysis, {format_multiplier(float(cert['multiplier']), live)} "
                f"({exact}; duality gap {_sci(cert.get('duality_gap'))})"
            )
        lines.append(
            f"  elapsed:             {results.elapsed_s:.3g} s ({results.steps} steps, {results.iterations} iterations)"
        )
    return "\n".join(lines)
