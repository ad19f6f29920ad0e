"""Time histories (:class:`masonry_dem.TimeHistory`, from ``Model.simulate``) as results: the response of the
control block, shared by the exports (:mod:`masonry_dem.export`) and the figures (:mod:`masonry_dem.plot`).
The response (:func:`default_control_block`, :func:`control_response`) reads either dimension; the figures, the
animation and the curve's CSV read a wall in the plane's: a 3D wall's time history (``Model3D.simulate``,
``TimeHistory.dimension`` 3) is refused there with :func:`check_plane`.

Displacements of a time history (``TimeHistory.displacements``, (k, n_all, 3): u1 [m], u2 [m], phi [rad]) are
relative to the ground: the blocks move in the frame of the base (a base acceleration acts as the inertial
forces -m a_g(t)), and they are measured from the undeformed wall (the geometry of ``Model.polygons``), as the
``initial_displacements`` given to ``Model.simulate`` are. The base's rows are zero.
"""

from __future__ import annotations

from types import SimpleNamespace
from typing import Any, Dict, Iterable, Iterator, Tuple

import numpy as np

from ._core import InputError, TimeHistory

__all__ = [
    "ENERGIES",
    "is_time_history",
    "check_plane",
    "default_control_block",
    "control_response",
    "largest_translation",
    "peak_record",
    "record",
    "contact_sets",
    "contacts_at",
]

#: The energies a time history holds ((k,) arrays [J]), in the order the exports write them: initial energy +
#: external work = kinetic + elastic + dissipated (friction, damping, impacts) + the balance's error.
ENERGIES = (
    "kinetic_energy",
    "elastic_energy",
    "external_work",
    "gravity_work",
    "friction_dissipation",
    "damping_dissipation",
    "impact_dissipation",
    "dissipated",
    "energy_error",
)


def is_time_history(results: Any) -> bool:
    """Whether ``results`` is a :class:`masonry_dem.TimeHistory` (else a :class:`masonry_dem.Results`)."""
    return isinstance(results, TimeHistory)


def check_plane(model: Any, what: str = "this output of a time history") -> None:
    """Refuse a 3D wall's time history (``model`` a :class:`masonry_dem.Model3D`) where only the plane's is read
    (the exports, the figures and the response of this module's users), with InputError naming ``what``."""
    if int(getattr(model, "dimension", 2)) == 3:
        raise InputError(f"{what}: a 3D wall's time history (Model3D.simulate) is not drawn or written as a curve in "
                         "this version: read its TimeHistory's arrays (displacements (k, n_all, 6), base_shear, "
                         "base_shear_y, the energies), or write its VTK series (write_vtk)")


def default_control_block(model: Any) -> int:
    """The model's default control block, the solvers' own (``Model.default_control_block``); of a 3D model
    (:class:`masonry_dem.Model3D`) the highest wall block (the top of its bounding box, the first of equal ones),
    the 3D explicit pushover's."""
    if int(getattr(model, "dimension", 2)) == 3:
        boxes = np.asarray(model.boxes, dtype=np.float64).reshape(-1, 6)[: int(model.n_blocks)]
        return int(np.argmax(boxes[:, 5]))
    return int(model.default_control_block)


def control_response(model: Any, history: Any) -> Tuple[np.ndarray, np.ndarray]:
    """((k,) horizontal displacement u1 [m], (k,) rotation phi [rad]) of the default control block at each
    recorded time, relative to the ground (see the module docstring). Of a 3D model: the length of the control
    block's horizontal displacement sqrt(ux^2 + uy^2) [m] and of its rotation vector [rad] (both >= 0)."""
    disp = np.asarray(history.displacements, dtype=np.float64)
    c = default_control_block(model)
    if int(getattr(model, "dimension", 2)) == 3:
        return np.hypot(disp[:, c, 0], disp[:, c, 1]), np.linalg.norm(disp[:, c, 3:6], axis=-1)
    return disp[:, c, 0].copy(), disp[:, c, 2].copy()


def largest_translation(history: Any) -> np.ndarray:
    """(k,) the largest translation sqrt(u1^2 + u2^2) [m] of any block's centroid at each recorded time (of a 3D
    history, sqrt(ux^2 + uy^2 + uz^2))."""
    disp = np.asarray(history.displacements, dtype=np.float64)
    if disp.size == 0:
        return np.zeros(len(np.asarray(history.times)))
    if disp.shape[-1] == 6:
        return np.asarray(np.linalg.norm(disp[..., :3], axis=-1).max(axis=1))
    return np.asarray(np.hypot(disp[..., 0], disp[..., 1]).max(axis=1))


def peak_record(model: Any, history: Any) -> int:
    """The index of the record with the largest |horizontal displacement| of the control block (the first
    such; 0 for an empty or motionless history)."""
    u, _ = control_response(model, history)
    return int(np.argmax(np.abs(u))) if len(u) else 0


def record(history: Any, k: int) -> SimpleNamespace:
    """The ``k``-th record as a result the panels and the VTK writer read: ``displacements`` and
    ``velocities`` ((n_all, 3)), ``time`` [s], ``method`` "dynamic" and the history's ``status``."""
    return SimpleNamespace(
        displacements=np.asarray(history.displacements, dtype=np.float64)[k],
        velocities=np.asarray(history.velocities, dtype=np.float64)[k],
        time=float(np.asarray(history.times)[k]),
        method="dynamic",
        status=history.status,
    )


def _rotate(phi: np.ndarray, v: np.ndarray) -> np.ndarray:
    """(n, 2) vectors ``v`` turned by the angles ``phi`` (n,) [rad]."""
    c, s = np.cos(phi), np.sin(phi)
    return np.stack([c * v[:, 0] - s * v[:, 1], s * v[:, 0] + c * v[:, 1]], axis=1)


def contact_sets(model: Any, history: Any, records: Iterable[int], scale: float = 1.0) -> Iterator[SimpleNamespace]:
    """The contacts of a time history in the plane at each of ``records`` (increasing record indices), as its
    contact update left them (``TimeHistory.contact_events``; without the update, the model's interfaces at every
    record), each a namespace of ``ends`` (n, 2, 2): the two ends of each contact [m] where block a's displacement
    at that record carries them, ``ids`` (n,): the contacts' numbers (the model's interfaces 0..m, then the created
    ones), ``blocks`` (n, 2), ``created`` (n,): made by the update (not one of the model's interfaces), and
    ``dropped``: how many contacts the update has dropped up to that record. The events of a search are applied
    to the records at or after its time. ``scale`` magnifies the displacements (and rotations) that carry the
    contacts, as the animation's blocks are."""
    check_plane(model, "contact_sets")
    geom = np.asarray(model.interface_geometry, dtype=np.float64).reshape(-1, 5)
    pairs = np.asarray(model.interface_blocks, dtype=np.int64).reshape(-1, 2)
    centroids = np.asarray(model.centroids, dtype=np.float64).reshape(-1, 2)
    # id -> (a, b, centre relative to a's centroid, normal, length) in a's position at rest
    alive: Dict[int, Tuple[int, int, np.ndarray, np.ndarray, float]] = {
        i: (int(a), int(b), geom[i, :2] - centroids[a], geom[i, 2:4], float(geom[i, 4]))
        for i, (a, b) in enumerate(pairs)
    }
    m = len(pairs)
    ev = history.contact_events
    ev_time = np.asarray(ev["time"], dtype=np.float64)
    change = list(ev["change"])
    times = np.asarray(history.times, dtype=np.float64)
    disp = np.asarray(history.displacements, dtype=np.float64)
    j, dropped = 0, 0
    for k in records:
        while j < len(ev_time) and ev_time[j] <= times[k]:
            i = int(ev["id"][j])
            if change[j] == "dropped":
                alive.pop(i, None)
                dropped += 1
            else:
                a, b = (int(x) for x in ev["blocks"][j])
                alive[i] = (a, b, np.asarray(ev["centre"][j], dtype=np.float64),
                            np.asarray(ev["normal"][j], dtype=np.float64), float(ev["length"][j]))
            j += 1
        ids = np.array(sorted(alive), dtype=np.int64)
        rows = [alive[int(i)] for i in ids]
        a = np.array([r[0] for r in rows], dtype=np.int64)
        blocks = np.array([[r[0], r[1]] for r in rows], dtype=np.int64).reshape(-1, 2)
        centre = np.array([r[2] for r in rows], dtype=np.float64).reshape(-1, 2)
        normal = np.array([r[3] for r in rows], dtype=np.float64).reshape(-1, 2)
        length = np.array([r[4] for r in rows], dtype=np.float64)
        u = scale * disp[k][a] if len(a) else np.zeros((0, 3))
        mid = centroids[a] + u[:, :2] + _rotate(u[:, 2], centre)
        n = _rotate(u[:, 2], normal)
        half = np.stack([n[:, 1], -n[:, 0]], axis=1) * (0.5 * length)[:, None]
        yield SimpleNamespace(ends=np.stack([mid - half, mid + half], axis=1), ids=ids, blocks=blocks,
                              created=ids >= m, dropped=dropped)


def contacts_at(model: Any, history: Any, k: int) -> SimpleNamespace:
    """The contacts at record ``k`` (see :func:`contact_sets`)."""
    return next(contact_sets(model, history, [k]))
