"""The line of thrust of a wall in the plane: where the resultant of each interface's forces crosses the joint, and
those points joined along the chains of blocks (the voussoirs of an arch, the blocks of a pier) into lines.

An interface carries a normal force N [N] (positive in tension), a shear force T [N] and a moment M [N m] about its
centroid c (``Results.interface_forces``), work-conjugate to the jumps of block b over block a (the normal n from a
to b, the tangent t = (n_y, -n_x); the moment to the relative rotation phi_b - phi_a, counter-clockwise positive).
The force of a on b is -(N n + T t) with the moment -M about c: its line of action crosses the joint at

    p = c + (M / N) t,

at the eccentricity e = M / N along t. Under compression (N < 0) this is the centre of pressure, inside the joint
(|e| <= l / 2) on dry joints and at an end when the joint rocks about it. A joint that carries no normal force
(|N| at most :data:`NO_FORCE` times the largest |N| of the wall) has no such point: its position is NaN, and a line
is broken there, rather than drawn through a point no force passes.

The chains: a block of the wall (or the top beam) with exactly two interfaces passes the line from one to the other;
a line runs from joint to joint through such blocks and ends at a block with one interface or three and more, at a
support or at the base. An arch on supports gives one line from springing to springing, through the piers too when
they are single blocks; a wall of courses, whose blocks touch more than two others, has no line (its joints' points
are given alone by :func:`resultant_points`).

Of a limit analysis the forces are those at collapse; of a static or explicit analysis those of its last converged
step (the state at the end of its path); the first step of a static path, lambda = 0, is the wall under its dead
loads alone. Lengths in m. No matplotlib here (the figure: :func:`masonry_dem.plot.plot_thrust`).
"""

from __future__ import annotations

from typing import Any, Dict, List

import numpy as np

from ._shapes import fixed_blocks

__all__ = ["NO_FORCE", "resultant_points", "thrust_chains", "thrust_lines"]

#: A joint carries no normal force when its |N| is at most this fraction of the largest |N| of the wall.
NO_FORCE = 1e-9


def _forces(model: Any, results: Any) -> np.ndarray:
    """(m, 3) N, T, M of each interface: ``results.interface_forces`` (Results), or an (m, 3) array itself."""
    forces = getattr(results, "interface_forces", results)
    f = np.asarray(forces, dtype=np.float64)
    m = int(model.n_interfaces)
    if f.shape != (m, 3):
        raise ValueError(f"the model has {m} interfaces, the forces are of shape {f.shape} (expected ({m}, 3))")
    return f


def resultant_points(model: Any, results: Any) -> np.ndarray:
    """(m, 2) where the resultant of each interface's forces crosses the joint [m]: c + (M / N) t, NaN on a joint
    that carries no normal force (see the module). ``results``: a :class:`masonry_dem.Results` of ``model`` (its
    ``interface_forces``) or an (m, 3) array of N [N], T [N], M [N m]."""
    f = _forces(model, results)
    geom = np.asarray(model.interface_geometry, dtype=np.float64).reshape(-1, 5)
    n_force, moment = f[:, 0], f[:, 2]
    largest = float(np.max(np.abs(n_force))) if len(f) else 0.0
    carries = np.abs(n_force) > NO_FORCE * largest
    e = np.full(len(f), np.nan)
    e[carries] = moment[carries] / n_force[carries]
    tangent = np.c_[geom[:, 3], -geom[:, 2]]
    return geom[:, :2] + e[:, None] * tangent  # type: ignore[no-any-return]


def thrust_chains(model: Any) -> List[List[int]]:
    """The chains of interfaces a line of thrust runs along (see the module), each the interfaces in order from one
    end to the other; the longest first, a chain of one interface left out."""
    pairs = np.asarray(model.interface_blocks, dtype=np.int64).reshape(-1, 2)
    joints: Dict[int, List[int]] = {}
    for k, (a, b) in enumerate(pairs):
        joints.setdefault(int(a), []).append(k)
        joints.setdefault(int(b), []).append(k)
    fixed = set(fixed_blocks(model))

    def passes(block: int) -> bool:  # the line goes through this block, from one joint to the other
        return block not in fixed and len(joints[block]) == 2

    chains, used = [], set()
    for start in range(len(pairs)):
        if start in used:
            continue
        # walk both ways from the interface while the blocks pass the line on
        chain = [start]
        for side in (0, 1):
            k, block = start, int(pairs[start][side])
            while passes(block):
                following = next(j for j in joints[block] if j != k)
                if following == start:  # a closed ring: every block passes the line on
                    break
                chain = [following] + chain if side == 0 else chain + [following]
                k = following
                block = int(pairs[k][1] if int(pairs[k][0]) == block else pairs[k][0])
        used.update(chain)
        if len(chain) > 1:
            chains.append(chain)
    chains.sort(key=len, reverse=True)
    return chains


def thrust_lines(model: Any, results: Any) -> List[np.ndarray]:
    """The lines of thrust of ``model`` under the forces of ``results`` (a :class:`masonry_dem.Results` or an (m, 3)
    array of N, T, M): for each chain of :func:`thrust_chains`, the points of :func:`resultant_points` in order, an
    (k, 2) array [m] with NaN rows where a joint carries no normal force (the line is broken there)."""
    points = resultant_points(model, results)
    return [points[chain] for chain in thrust_chains(model)]
