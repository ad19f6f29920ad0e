"""Plain-text reports of a 3D wall's analysis (limit or explicit): the one-line description of its collapse mechanism
(:func:`describe_mechanism`, what ``masonry-dem run`` prints for a 3D case) and the kinematic helpers the plots share
(:func:`vertex_motion`, :func:`moved_vertices`, the blocks' faces and the contacts' polygons). No matplotlib here.
Lengths in m, rotations in rad, directions in plan in degrees from +x towards +y.
"""

from __future__ import annotations

import math
from typing import Any, List, Optional, Sequence, Tuple

import numpy as np

from .._mechanism import CRACK_TOLERANCE, MOVING_FRACTION, connected_parts as _connected_parts, mechanism_text

__all__ = ["box_corners", "block_shapes", "all_boxes", "own_centroids", "contact_polygons", "padded_polygons",
           "corner_motion", "vertex_motion", "dof_points", "contact_motion", "moved_vertices",
           "contact_jumps", "describe_mechanism", "direction_text"]

# The six faces of a box, as indices of its corners (box_corners' order), counter-clockwise seen from outside
BOX_FACES = ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7))


def box_corners(boxes: np.ndarray) -> np.ndarray:
    """(n, 8, 3) corners [m] of boxes (n, 6) [x0, y0, z0, x1, y1, z1]: the bottom face counter-clockwise seen from
    above, then the top face (VTK's order of a hexahedron)."""
    b = np.asarray(boxes, dtype=np.float64).reshape(-1, 6)
    x0, y0, z0, x1, y1, z1 = b.T
    xs = np.stack([x0, x1, x1, x0, x0, x1, x1, x0], axis=1)
    ys = np.stack([y0, y0, y1, y1, y0, y0, y1, y1], axis=1)
    zs = np.stack([z0, z0, z0, z0, z1, z1, z1, z1], axis=1)
    return np.stack([xs, ys, zs], axis=-1)


def all_boxes(model: Any) -> bool:
    """Whether every block of ``model`` is a box with sides along the axes (a model without ``block_is_box``:
    a wall of boxes)."""
    flags = getattr(model, "block_is_box", None)
    return flags is None or all(flags)


def block_shapes(model: Any) -> List[Tuple[np.ndarray, List[List[int]]]]:
    """Each block's shape: (its vertices (k, 3) [m], its faces, each a list of indices into them counter-clockwise
    seen from outside), in the order of ``model.boxes``; a box's vertices are its corners in :func:`box_corners`'
    order, with :data:`BOX_FACES`."""
    boxes = np.asarray(model.boxes, dtype=np.float64).reshape(-1, 6)
    corners = box_corners(boxes)
    flags = getattr(model, "block_is_box", None)
    if flags is None or all(flags):
        return [(corners[i], [list(f) for f in BOX_FACES]) for i in range(len(boxes))]
    vertices, faces = model.block_vertices, model.block_faces
    return [(corners[i], [list(f) for f in BOX_FACES]) if flags[i]
            else (np.asarray(vertices[i], dtype=np.float64).reshape(-1, 3), [list(f) for f in faces[i]])
            for i in range(len(boxes))]


def contact_polygons(model: Any) -> List[np.ndarray]:
    """Each contact's polygon (k, 3) [m], k >= 3 corners counter-clockwise seen from the tip of its normal
    (``model.interface_polygons``; a model without it: the rectangles of ``interface_corners``)."""
    polygons = getattr(model, "interface_polygons", None)
    if polygons is None:
        return list(np.asarray(model.interface_corners, dtype=np.float64).reshape(-1, 4, 3))
    return [np.asarray(p, dtype=np.float64).reshape(-1, 3) for p in polygons]


def padded_polygons(model: Any) -> np.ndarray:
    """(m, k, 3) the contacts' polygons (:func:`contact_polygons`) padded to the most corners k by repeating each
    polygon's first corner (which changes no largest or smallest value over the corners): the rectangles of
    boxes as they are."""
    polygons = contact_polygons(model)
    k = max((len(p) for p in polygons), default=4)
    out = np.empty((len(polygons), k, 3))
    for i, p in enumerate(polygons):
        out[i, : len(p)] = p
        out[i, len(p):] = p[0]
    return out


def _centroids(boxes: np.ndarray, centroids: Any = None) -> np.ndarray:
    """(n, 3) the points where the blocks' dofs are [m]: ``centroids`` (a model's, which a block's carried loads
    move off its box's centre) when given, else the boxes' centres."""
    if centroids is not None:
        return np.asarray(centroids, dtype=np.float64).reshape(-1, 3)
    b = np.asarray(boxes, dtype=np.float64).reshape(-1, 6)
    return 0.5 * (b[:, :3] + b[:, 3:])


def dof_points(model: Any) -> np.ndarray:
    """(n_all, 3) where each block's dofs are [m]: ``model.centroids`` (its centre of mass, moved off the box's
    centre by the loads it carries), else the boxes' centres."""
    return _centroids(model.boxes, getattr(model, "centroids", None))


def own_centroids(model: Any, boxes_centres: np.ndarray) -> np.ndarray:
    """(n_all, 3) each block's own centroid [m], without the loads it carries: a box's centre (``boxes_centres``),
    a polyhedron's from the model's centre of mass with its loads (``model.centroids``, ``model.mass``) less the
    loads' (each weight / g at its point)."""
    out = np.array(boxes_centres, dtype=np.float64).reshape(-1, 3)
    centroids = np.asarray(model.centroids, dtype=np.float64).reshape(-1, 3)
    mass = np.asarray(model.mass, dtype=np.float64)
    moment = mass[:, None] * centroids
    own = mass.copy()
    g = float(model.gravity)
    for block, point, weight in getattr(model, "carried", None) or []:
        moment[block] -= weight / g * np.asarray(point, dtype=np.float64)
        own[block] -= weight / g
    flags = getattr(model, "block_is_box", None) or [True] * len(out)
    shaped = ~np.asarray(flags, dtype=bool)
    out[shaped] = moment[shaped] / own[shaped, None]
    return out


def corner_motion(boxes: np.ndarray, motion: np.ndarray, centroids: Any = None) -> np.ndarray:
    """(n,) largest corner motion [m] of each box for the small motion (ux, uy, uz, rx, ry, rz) at its centroid
    (``centroids``, the model's, or the boxes' centres)."""
    corners = box_corners(boxes)
    r = corners - _centroids(boxes, centroids)[:, None, :]
    m = np.asarray(motion, dtype=np.float64).reshape(-1, 6)
    u = m[:, None, :3] + np.cross(m[:, None, 3:], r)
    return np.linalg.norm(u, axis=-1).max(axis=1)  # type: ignore[no-any-return]


def vertex_motion(model: Any, motion: np.ndarray) -> np.ndarray:
    """(n_all,) largest motion [m] of each block at its vertices (a box's corners, a polyhedron's vertices) for the
    small motion (ux, uy, uz, rx, ry, rz) at its centroid (the model's dofs): :func:`corner_motion` of any shape."""
    if all_boxes(model):
        return corner_motion(model.boxes, motion, dof_points(model))
    centroid = dof_points(model)
    m = np.asarray(motion, dtype=np.float64).reshape(-1, 6)
    out = np.empty(len(m))
    for i, (vertices, _) in enumerate(block_shapes(model)):
        u = m[i, :3] + np.cross(m[i, 3:], vertices - centroid[i])
        out[i] = np.linalg.norm(u, axis=-1).max()
    return out


def contact_motion(model: Any, motion: np.ndarray) -> np.ndarray:
    """(n_all,) largest motion [m] of each block at the corners of its contacts, where it touches the others, for
    the small motion (ux, uy, uz, rx, ry, rz) at its centroid (0 for a block without contacts). Unlike
    :func:`corner_motion`, a block's far corners do not count: a tall top beam turning with the wall moves its top
    corners far more than it moves where it rests on the wall, and would make the wall's own motion look like rest."""
    boxes = np.asarray(model.boxes, dtype=np.float64).reshape(-1, 6)
    centroid = dof_points(model)
    m = np.asarray(motion, dtype=np.float64).reshape(-1, 6)
    pairs = np.asarray(model.interface_blocks, dtype=np.int64).reshape(-1, 2)
    corners = padded_polygons(model)
    out = np.zeros(len(boxes))
    for side in (0, 1):
        i = pairs[:, side]
        u = m[i, None, :3] + np.cross(m[i, None, 3:], corners - centroid[i, None, :])
        np.maximum.at(out, i, np.linalg.norm(u, axis=-1).max(axis=1, initial=0.0))
    return out


def contact_jumps(model: Any, motion: np.ndarray) -> np.ndarray:
    """(m, 3) jumps of a motion (n_all, 6) of the blocks across each contact, over its corners: the largest
    slip [m] (the jump along the contact's plane), and the largest and the smallest normal gap [m] (positive
    opens). With the normal n from block a to block b, the jump at a corner p is u_b(p) - u_a(p)."""
    boxes = np.asarray(model.boxes, dtype=np.float64).reshape(-1, 6)
    centroid = dof_points(model)
    m = np.asarray(motion, dtype=np.float64).reshape(-1, 6)
    pairs = np.asarray(model.interface_blocks, dtype=np.int64).reshape(-1, 2)
    corners = padded_polygons(model)
    normals = np.asarray(model.interface_normals, dtype=np.float64).reshape(-1, 3)
    a, b = pairs[:, 0], pairs[:, 1]

    def at(i: np.ndarray) -> np.ndarray:
        return m[i, None, :3] + np.cross(m[i, None, 3:], corners - centroid[i, None, :])

    jump = at(b) - at(a)  # (m, k, 3)
    gap = np.einsum("kqi,ki->kq", jump, normals)
    slip = np.linalg.norm(jump - gap[..., None] * normals[:, None, :], axis=-1)
    return np.stack([slip.max(axis=1), gap.max(axis=1), gap.min(axis=1)], axis=1)  # type: ignore[no-any-return]


def _rotation(w: np.ndarray) -> np.ndarray:
    """The rotation matrix of the rotation vector ``w`` [rad] (Rodrigues): the drawn box keeps its shape."""
    angle = float(np.linalg.norm(w))
    if angle == 0.0:
        return np.eye(3)
    k = w / angle
    kx = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + math.sin(angle) * kx + (1.0 - math.cos(angle)) * kx @ kx  # type: ignore[no-any-return]


def moved_vertices(model: Any, motion: np.ndarray, scale: float) -> List[np.ndarray]:
    """Each block's vertices (:func:`block_shapes`) [m] moved by ``scale`` times (ux, uy, uz) and turned by ``scale``
    times the rotation (rx, ry, rz) about its centroid (the model's dofs), the rotation applied exactly."""
    centroid = dof_points(model)
    m = np.asarray(motion, dtype=np.float64).reshape(-1, 6)
    return [centroid[i] + scale * m[i, :3] + (vertices - centroid[i]) @ _rotation(scale * m[i, 3:]).T
            for i, (vertices, _) in enumerate(block_shapes(model))]


def direction_text(direction: Optional[float]) -> str:
    """A direction in plan [deg] for people: "+y (90°)", "30° from +x towards +y"."""
    if direction is None or not math.isfinite(direction):
        return "none"
    d = direction % 360.0
    axes = {0.0: "+x", 90.0: "+y", 180.0: "-x", 270.0: "-y"}
    if d in axes:
        return f"{axes[d]} ({direction:g}°)"
    return f"{direction:g}° from +x towards +y"


def _axis_words(axis: np.ndarray) -> str:
    """A unit axis for people: "x", "y", "z" (within a degree) or its components."""
    for k, name in enumerate("xyz"):
        if abs(abs(axis[k]) - 1.0) < 2e-4:
            return name
    return "(" + ", ".join(f"{v:.2f}" for v in axis) + ")"


def _describe_part(boxes: np.ndarray, motion: np.ndarray, part: Sequence[int], centroids: np.ndarray) -> str:
    """The volume-weighted rigid motion of one part: "sliding towards +y (90°)", or "turning about an axis along x
    through y = 0.10, z = 0.00 m"."""
    b = np.asarray(boxes, dtype=np.float64)
    volume = np.prod(b[part, 3:] - b[part, :3], axis=1)
    r = (volume[:, None] * _centroids(b[part])).sum(axis=0) / volume.sum()
    cents = centroids[part]  # where the motions are: the dofs
    m = np.asarray(motion, dtype=np.float64)[part]
    # each block's motion carried to r: v + w x (r - c)
    v = m[:, :3] + np.cross(m[:, 3:], r - cents)
    v = (volume[:, None] * v).sum(axis=0) / volume.sum()
    w = (volume[:, None] * m[:, 3:]).sum(axis=0) / volume.sum()
    size = float(np.linalg.norm(b[part, 3:].max(axis=0) - b[part, :3].min(axis=0)))
    speed, spin = float(np.linalg.norm(v)), float(np.linalg.norm(w))
    if spin * 5.0 * size < speed:  # the axis is far away: a translation
        angle = math.degrees(math.atan2(v[1], v[0]))
        if abs(v[2]) > 0.5 * speed:
            return f"moving {'up' if v[2] > 0 else 'down'}"
        return f"sliding towards {direction_text(round(angle, 0) % 360.0)}"
    axis = w / spin
    point = r + np.cross(w, v) / spin**2  # the point of the instantaneous axis nearest to r
    named = _axis_words(axis)
    if named in ("x", "y"):
        other = "yx"["xy".index(named)]
        where = f"{other} = {point['xyz'.index(other)]:.2f}, z = {point[2]:.2f} m"
    elif named == "z":
        where = f"x = {point[0]:.2f}, y = {point[1]:.2f} m"
    else:
        where = f"({point[0]:.2f}, {point[1]:.2f}, {point[2]:.2f}) m"
    return f"turning about an axis along {named} through {where}"


def _crack(jumps: np.ndarray, tol: float) -> Tuple[List[int], List[int], List[int]]:
    """The contacts that open (a gap beyond ``tol`` at every corner), slide (a slip beyond it, closed) and rock (a
    gap beyond it at some corners only), from :func:`contact_jumps`."""
    opens = [k for k, (_, _, g_min) in enumerate(jumps) if g_min > tol]
    slips = [k for k, (slip, _, g_min) in enumerate(jumps) if slip > tol and g_min <= tol]
    rocks = [k for k, (_, g_max, g_min) in enumerate(jumps) if g_max > tol >= g_min]
    return opens, slips, rocks


def describe_mechanism(model: Any, results: Any) -> str:
    """One line on the collapse mechanism of a 3D wall (``Results.mechanism``: the collapse velocities): how many
    wall blocks move, the parts they form (blocks held together by contacts the crack does not cross), each sliding
    or turning about an axis, and the crack: the contacts across which the mechanism opens (a gap at every corner),
    slides (a slip, closed) or rocks (a gap at some corners only), counted by family (:func:`contact_jumps`,
    jumps beyond 5% of the largest corner motion). A block moves when its largest corner motion exceeds 1% of the
    largest; the top beam's motion is taken where it rests on the wall (:func:`contact_motion`), not at its top
    corners, so that a tall, heavy beam turning with the wall does not make the wall's motion and cracks look like
    rest."""
    boxes = np.asarray(model.boxes, dtype=np.float64).reshape(-1, 6)
    n = int(model.n_blocks)
    mech = np.asarray(results.mechanism, dtype=np.float64)
    if mech.shape != (len(boxes), 6) or not np.all(np.isfinite(mech)):
        return "none (no collapse)"
    top = model.top_index
    bodies = list(range(n)) + ([int(top)] if top is not None else [])
    cm = vertex_motion(model, mech)
    if top is not None:  # the top beam's motion where it rests on the wall: its top corners may be far above it
        cm[int(top)] = contact_motion(model, mech)[int(top)]
    peak = float(max(cm[i] for i in bodies))
    if not peak > 0:
        return "none (no collapse)"
    moving = [i for i in bodies if cm[i] > MOVING_FRACTION * peak]
    n_moving = sum(1 for i in moving if i < n)
    beam = " and the top beam" if top is not None and int(top) in moving else ""

    # the crack: the contacts across which the mechanism has a jump (a slip, or a gap at some corners)
    families = list(model.interface_family)
    jumps = contact_jumps(model, mech)
    opens, slips, rocks = _crack(jumps, CRACK_TOLERANCE * peak)
    if not (opens or slips or rocks):
        # blocks move, so some contact must crack: the mechanism is spread thinner than the tolerance over many
        # contacts (a mechanism within the solver's tolerance of several others, as under a beam thousands of
        # times taller than the wall, whose hinge height hardly changes the multiplier): its largest jumps are it
        largest = float(np.max(jumps[:, :2], initial=0.0))
        opens, slips, rocks = _crack(jumps, CRACK_TOLERANCE * largest)
    cracked = np.zeros(len(jumps), dtype=bool)
    cracked[opens + slips + rocks] = True
    parts = _connected_parts(moving, np.asarray(model.interface_blocks).reshape(-1, 2), list(cracked))
    parts.sort(key=len, reverse=True)
    crack = ((opens, "open"), (slips, "slide"), (rocks, "rock"))
    describe = lambda part: _describe_part(boxes, mech, part, dof_points(model))  # noqa: E731
    return mechanism_text(n_moving, n, beam, parts, describe, crack, families, "contact")
