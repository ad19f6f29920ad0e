"""The blocks of a wall in the plane as convex polygons: what every figure, export and report reads of a block's
shape, whatever the model was built from (rectangles, polygons, an arch).

:func:`shapes` reads a model's blocks: ``Model.polygons`` (every block's vertices, counter-clockwise) and
``Model.centroids`` when the core has them, else the rectangles of ``Model.rects`` as 4-vertex polygons (a
rectangle's centroid is its centre). The blocks come packed in a :class:`Shapes`, whose vertex arrays serve a wall of
10^5 blocks without a loop over the blocks in Python. :func:`polygon_problem` says what is wrong with an outline
given as vertices (a case file's polygon, a drawing's polyline), for the messages that name the vertex at fault.
Lengths in m, rotations in rad (counter-clockwise positive). No matplotlib, no meshio here.
"""

from __future__ import annotations

import math
from typing import Any, List, Optional, Sequence, Tuple

import numpy as np

__all__ = [
    "Shapes",
    "shapes",
    "rect_vertices",
    "area_centroid",
    "centroids",
    "fixed_blocks",
    "support_indices",
    "moved_vertices",
    "polygon_problem",
    "REL_TOL",
]

#: The relative tolerance of the outlines' checks (:func:`polygon_problem`): a vertex within this fraction of the
#: outline's size of the line through its neighbours is on that line (the core's tolerance of the geometry).
REL_TOL = 1e-9


def rect_vertices(rect: Sequence[float]) -> np.ndarray:
    """(4, 2) vertices of a rectangle [x0, y0, x1, y1], counter-clockwise from (x0, y0)."""
    x0, y0, x1, y1 = (float(v) for v in rect)
    return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])


def _signed_area2(p: np.ndarray) -> float:
    """Twice the signed area of a polygon (k, 2) (positive counter-clockwise), the shoelace formula."""
    x, y = p[:, 0], p[:, 1]
    return float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def area_centroid(vertices: Sequence[Sequence[float]]) -> np.ndarray:
    """(2,) the centroid [m] of the area of a simple polygon (k, 2) given in either orientation."""
    p = np.asarray(vertices, dtype=np.float64).reshape(-1, 2)
    origin = p[0]
    q = p - origin  # about a vertex: the products stay small for a block far from the origin
    x, y = q[:, 0], q[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    a2 = float(cross.sum())
    if a2 == 0.0:
        return p.mean(axis=0)  # type: ignore[no-any-return]
    return origin + np.array([((x + xn) * cross).sum(), ((y + yn) * cross).sum()]) / (3.0 * a2)


class Shapes:
    """Every block's polygon, packed: ``points`` (p, 2) the vertices of block 0, then of block 1, ...,
    counter-clockwise; ``starts`` (n + 1,) where each block's vertices start (block i's are ``points[starts[i]:
    starts[i + 1]]``); ``owner`` (p,) the block of each vertex; ``centroids`` (n, 2) [m] the blocks' centroids.

    Built from vertex arrays (:meth:`from_polygons`) or from rectangles (:meth:`from_rects`), or from a model by
    :func:`shapes`."""

    def __init__(self, points: np.ndarray, starts: np.ndarray, centroids: np.ndarray) -> None:
        self.points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        self.starts = np.asarray(starts, dtype=np.int64).reshape(-1)
        self.centroids = np.asarray(centroids, dtype=np.float64).reshape(-1, 2)
        self.counts = np.diff(self.starts)
        self.owner = np.repeat(np.arange(len(self.counts)), self.counts)

    @classmethod
    def from_rects(cls, rects: Any) -> "Shapes":
        """Rectangles (n, 4) [x0, y0, x1, y1] as 4-vertex polygons, each centroid its centre."""
        r = np.asarray(rects, dtype=np.float64).reshape(-1, 4)
        x0, y0, x1, y1 = r.T
        points = np.stack([np.c_[x0, y0], np.c_[x1, y0], np.c_[x1, y1], np.c_[x0, y1]], axis=1).reshape(-1, 2)
        return cls(points, np.arange(0, 4 * len(r) + 1, 4), 0.5 * np.c_[x0 + x1, y0 + y1])

    @classmethod
    def from_polygons(cls, polygons: Sequence[Any], centroids: Any = None) -> "Shapes":
        """Vertex arrays (k_i, 2), counter-clockwise; ``centroids`` (n, 2), by default the areas' centroids."""
        arrays = [np.asarray(p, dtype=np.float64).reshape(-1, 2) for p in polygons]
        starts = np.concatenate([[0], np.cumsum([len(p) for p in arrays], dtype=np.int64)])
        points = np.concatenate(arrays) if arrays else np.zeros((0, 2))
        if centroids is None:
            centroids = np.array([area_centroid(p) for p in arrays]).reshape(-1, 2)
        return cls(points, starts, centroids)

    def __len__(self) -> int:
        return len(self.counts)

    def polygon(self, i: int) -> np.ndarray:
        """(k, 2) the vertices of block ``i``."""
        return self.points[self.starts[i]: self.starts[i + 1]]

    def polygons(self, points: Optional[np.ndarray] = None) -> List[np.ndarray]:
        """Every block's vertices as a list of (k_i, 2) arrays; of ``points`` ((p, 2), e.g. moved) instead of the
        blocks' own when given."""
        return np.split(self.points if points is None else points, self.starts[1:-1])

    @property
    def bounds(self) -> np.ndarray:
        """(n, 4) x0, y0, x1, y1 [m]: each block's bounding box."""
        if not len(self):
            return np.zeros((0, 4))
        lo = np.minimum.reduceat(self.points, self.starts[:-1], axis=0)
        hi = np.maximum.reduceat(self.points, self.starts[:-1], axis=0)
        return np.c_[lo, hi]

    @property
    def areas(self) -> np.ndarray:
        """(n,) the blocks' areas [m2] (the shoelace formula about each block's centroid)."""
        if not len(self):
            return np.zeros(0)
        q = self.points - self.centroids[self.owner]
        nxt = np.arange(len(q)) + 1
        nxt[self.starts[1:] - 1] = self.starts[:-1]  # each block's last vertex closes on its first
        cross = q[:, 0] * q[nxt, 1] - q[nxt, 0] * q[:, 1]
        return 0.5 * np.add.reduceat(cross, self.starts[:-1])  # type: ignore[no-any-return]

    def arms(self) -> np.ndarray:
        """(p, 2) each vertex relative to its block's centroid [m]."""
        return self.points - self.centroids[self.owner]

    def vertex_motion(self, motion: Any) -> np.ndarray:
        """(n,) the largest displacement [m] of a vertex of each block for the small motion (n, 3) (u1, u2, phi)
        of the block at its centroid: |u + phi k x r| over its vertices r."""
        m = np.asarray(motion, dtype=np.float64).reshape(-1, 3)
        if not len(self):
            return np.zeros(0)
        r = self.arms()
        u1, u2, phi = m[self.owner, 0], m[self.owner, 1], m[self.owner, 2]
        d = np.hypot(u1 - phi * r[:, 1], u2 + phi * r[:, 0])
        return np.maximum.reduceat(d, self.starts[:-1])  # type: ignore[no-any-return]

    def moved(self, motion: Any, scale: float = 1.0) -> np.ndarray:
        """(..., p, 2) the vertices [m] of the blocks moved by ``scale`` * (u1, u2) and turned by ``scale`` * phi
        about their centroids, the rotation applied exactly (the blocks keep their shapes), for a motion (..., n, 3)
        (a leading axis: frames of a time history)."""
        d = scale * np.asarray(motion, dtype=np.float64)[..., self.owner, :]  # (..., p, 3)
        r = self.arms()
        c, s = np.cos(d[..., 2]), np.sin(d[..., 2])
        turned = np.stack([c * r[:, 0] - s * r[:, 1], s * r[:, 0] + c * r[:, 1]], axis=-1)
        return self.centroids[self.owner] + d[..., :2] + turned  # type: ignore[no-any-return]

    def displacements(self, motion: Any, exact: bool) -> np.ndarray:
        """(p, 2) the displacement [m] of each vertex for the motion (n, 3) (u1, u2, phi) of the blocks at their
        centroids: u + (R(phi) - I) r with the rotation applied exactly if ``exact``, else linearized, u + phi k x r."""
        d = np.asarray(motion, dtype=np.float64).reshape(-1, 3)[self.owner]
        r, phi = self.arms(), d[:, 2]
        if exact:
            c, s = np.cos(phi) - 1.0, np.sin(phi)
            turn = np.stack([c * r[:, 0] - s * r[:, 1], s * r[:, 0] + c * r[:, 1]], axis=-1)
        else:
            turn = np.stack([-phi * r[:, 1], phi * r[:, 0]], axis=-1)
        return d[:, :2] + turn  # type: ignore[no-any-return]


def shapes(model: Any) -> Shapes:
    """The blocks of ``model`` (a :class:`masonry_dem.Model`, wall blocks first, then the supports, the base and the
    top beam): ``Model.polygons`` and ``Model.centroids`` when it has them, else its rectangles ``Model.rects``."""
    polygons = getattr(model, "polygons", None)
    if polygons is None:
        return Shapes.from_rects(model.rects)
    return Shapes.from_polygons(polygons, getattr(model, "centroids", None))


def centroids(model: Any) -> np.ndarray:
    """(n_all, 2) the blocks' centroids [m]: ``Model.centroids``, else the centres of ``Model.rects``."""
    given = getattr(model, "centroids", None)
    if given is not None:
        return np.asarray(given, dtype=np.float64).reshape(-1, 2)
    if getattr(model, "polygons", None) is not None:
        return shapes(model).centroids
    r = np.asarray(model.rects, dtype=np.float64).reshape(-1, 4)
    return 0.5 * np.c_[r[:, 0] + r[:, 2], r[:, 1] + r[:, 3]]


def support_indices(model: Any) -> List[int]:
    """The indices of the supports (fixed blocks: abutments, springers; ``Model.support_indices``), none when the
    model has none or the core does not have them."""
    return [int(i) for i in (getattr(model, "support_indices", None) or ())]


def fixed_blocks(model: Any) -> List[int]:
    """The blocks that never move: the supports and the base."""
    base = getattr(model, "base_index", None)
    return support_indices(model) + ([int(base)] if base is not None else [])


def moved_vertices(vertices: Any, motion: Sequence[float], scale: float, centroid: Any = None) -> np.ndarray:
    """(k, 2) the vertices [m] of one block moved by ``scale`` * (u1, u2) [m] and turned by ``scale`` * phi [rad]
    about its centroid (``centroid``, by default the area's), the rotation applied exactly."""
    p = np.asarray(vertices, dtype=np.float64).reshape(-1, 2)
    c = area_centroid(p) if centroid is None else np.asarray(centroid, dtype=np.float64)
    one = Shapes(p, np.array([0, len(p)]), c.reshape(1, 2))
    return one.moved(np.asarray(motion, dtype=np.float64).reshape(1, 3), scale)


def polygon_problem(vertices: Sequence[Sequence[float]], tolerance: Optional[float] = None) -> Optional[str]:
    """What is wrong with an outline as a block, or None; the core's rules and words (its ``Polygon::checked``), for
    the messages that name the block by its key or its drawing's handle before any model is built.

    A vertex within ``tolerance`` [m] of the one before it is the same vertex (the last and the first too), and a
    vertex within it of the line through its neighbours is on a straight side (default: :data:`REL_TOL` times the
    outline's size). Refused: fewer than 3 vertices, or fewer than 3 distinct; all on one line; an outline that turns
    back on itself, turns the other way at a corner (not convex) or winds round more than once (crosses itself); the
    message names the vertex by its index as given (from 0) and its coordinates. Either orientation is a block."""
    p = np.asarray(vertices, dtype=np.float64).reshape(-1, 2)
    if len(p) < 3:
        return f"{len(p)} vertices: a block needs at least 3"
    # in units of the outline's size about its first vertex: the products below neither overflow nor underflow
    with np.errstate(over="ignore"):
        size = float(np.abs(p - p[0]).max())
    if not math.isfinite(size):
        return f"spans more than a float holds: {_points(p)}"
    scale = size if size > 0 else 1.0
    q = [((x - p[0, 0]) / scale, (y - p[0, 1]) / scale) for x, y in p]
    tol = REL_TOL if tolerance is None else float(tolerance) / scale
    idx: List[int] = []  # the distinct vertices, as indices into the vertices given
    for k in range(len(q)):
        if not idx or _dist(q[idx[-1]], q[k]) > tol:
            idx.append(k)
    while len(idx) > 1 and _dist(q[idx[0]], q[idx[-1]]) <= tol:
        idx.pop()
    if len(idx) < 3:
        return f"fewer than 3 distinct vertices ({len(idx)} of the {len(q)} given)"
    far = max(idx, key=lambda k: _dist(q[k], q[idx[0]]))
    u, length = _sub(q[far], q[idx[0]]), _dist(q[far], q[idx[0]])
    if all(abs(_cross(u, _sub(q[k], q[idx[0]]))) / length <= tol for k in idx):
        return "all its vertices lie on one line: it has no area"
    if sum(_cross(q[idx[k]], q[idx[(k + 1) % len(idx)]]) for k in range(len(idx))) < 0:
        idx.reverse()  # counter-clockwise
    at = lambda k: f"vertex {k} {_point(p[k])}"  # noqa: E731
    # each vertex within tol of the line through its neighbours is on a straight side, unless the outline turns back
    # there; a vertex where it turns clockwise is a re-entrant corner
    pos = unchanged = 0
    while unchanged < len(idx) and len(idx) >= 3:
        m = len(idx)
        a, b, c = q[idx[(pos + m - 1) % m]], q[idx[pos]], q[idx[(pos + 1) % m]]
        off = _cross(_sub(b, a), _sub(c, a)) / _dist(c, a)
        if abs(off) <= tol:
            if _dot(_sub(b, a), _sub(c, b)) < 0:
                return f"{at(idx[pos])} turns the outline back on itself"
            idx.pop(pos)
            pos %= len(idx)
            unchanged = 0
        elif off < 0:
            return (f"{at(idx[pos])} is a re-entrant corner: the outline is not convex or crosses itself (a concave "
                    "stone is given as convex parts)")
        else:
            pos = (pos + 1) % m
            unchanged += 1
    turned, m = 0.0, len(idx)
    for pos in range(m):
        a, b, c = q[idx[pos]], q[idx[(pos + 1) % m]], q[idx[(pos + 2) % m]]
        e, f = _sub(b, a), _sub(c, b)
        turned += math.atan2(_cross(e, f), _dot(e, f))
        if turned > 2.0 * math.pi * (1.0 + 1e-9):
            return (f"the outline winds round past its start at {at(idx[(pos + 1) % m])}: it crosses itself (a block "
                    "is one convex polygon)")
    return None


def _sub(a: Sequence[float], b: Sequence[float]) -> Tuple[float, float]:
    return a[0] - b[0], a[1] - b[1]


def _cross(a: Sequence[float], b: Sequence[float]) -> float:
    return a[0] * b[1] - a[1] * b[0]


def _dot(a: Sequence[float], b: Sequence[float]) -> float:
    return a[0] * b[0] + a[1] * b[1]


def _dist(a: Sequence[float], b: Sequence[float]) -> float:
    return math.hypot(a[0] - b[0], a[1] - b[1])


def _point(p: np.ndarray) -> str:
    return f"({p[0]:g}, {p[1]:g})"


def _points(p: np.ndarray) -> str:
    shown = ", ".join(_point(q) for q in p[:8])
    return shown + (f", ... ({len(p)} vertices)" if len(p) > 8 else "")
