"""Arches and other chains of blocks against the four-hinge mechanisms: the limit analysis of a chain of rigid
blocks between fixed ends (an arch on its abutments, a portal on its base) with friction high enough to exclude
sliding is the least multiplier of the mechanisms with four hinges, each hinge at an end of a joint of the chain.
The enumeration below computes that least multiplier by virtual work alone, independently of the linear program."""

from __future__ import annotations

import itertools
import math
from typing import Any, List, Optional, Tuple

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem._shapes import centroids
from masonry_dem.thrust import thrust_chains

#: Friction high enough that no mechanism slides (associative: dilatancy = friction).
STICKY = {"default": md.dry_joint(2.0, dilatancy=2.0)}


def _cross(a: np.ndarray, b: np.ndarray) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def four_hinge_multiplier(model: Any) -> Tuple[float, Optional[List[Tuple[int, np.ndarray]]]]:
    """(the least multiplier of the four-hinge mechanisms of the model's one chain of blocks, its hinges as
    (interface, point)), by virtual work: with hinges at the ends A, B, C, D of joints j1 < j2 < j3 < j4 of the chain,
    the blocks between A and B turn about A (omega_1 = 1), those between C and D about D (omega_3), those between B
    and C move rigidly (omega_2, u_2), the rest stay; the velocities agree at B and C. The multiplier is the power of
    the weights over that of the live load, lambda = sum W v_y / sum W v_x (with sum W v_x > 0); a mechanism counts
    when every hinge opens its joint (the joint's other end separates)."""
    chains = thrust_chains(model)
    assert len(chains) == 1, "one chain of blocks"
    chain = chains[0]
    pairs = np.asarray(model.interface_blocks).reshape(-1, 2)
    geom = np.asarray(model.interface_geometry, dtype=np.float64).reshape(-1, 5)
    cents = centroids(model)
    weights = np.asarray(model.weights, dtype=np.float64)
    # the blocks in the order of the chain: the block after joint j is shared by joints j and j + 1
    first = set(pairs[chain[0]]) - set(pairs[chain[1]])
    order = [int(first.pop())]
    for k in chain:
        a, b = (int(i) for i in pairs[k])
        order.append(b if a == order[-1] else a)
    # each joint's two ends, and its normal from the block before it (in the chain) to the block after it
    ends, normals = [], []
    for j, k in enumerate(chain):
        cx, cy, nx, ny, length = geom[k]
        c, t = np.array([cx, cy]), np.array([ny, -nx])
        ends.append((c - length / 2 * t, c + length / 2 * t))
        n = np.array([nx, ny])
        normals.append(n if int(pairs[k][0]) == order[j] else -n)
    best, hinges = math.inf, None
    m = len(chain)
    for joints in itertools.combinations(range(m), 4):
        for sides in itertools.product((0, 1), repeat=4):
            A, B, C, D = (ends[j][s] for j, s in zip(joints, sides))
            # omega_2 (B - C) + omega_3 (C - D) = omega_1 (B - A), omega_1 = 1
            matrix = np.array([B - C, C - D]).T
            if abs(np.linalg.det(matrix)) < 1e-12 * np.abs(matrix).max() ** 2:
                continue
            w2, w3 = np.linalg.solve(matrix, B - A)
            u2 = np.array([-(B - A)[1], (B - A)[0]]) - w2 * np.array([-B[1], B[0]])  # v1(B) - w2 k x B

            def velocity(body: int, p: np.ndarray) -> np.ndarray:
                if body == 1:
                    return np.array([-(p - A)[1], (p - A)[0]])
                if body == 2:
                    return u2 + w2 * np.array([-p[1], p[0]])
                return w3 * np.array([-(p - D)[1], (p - D)[0]])

            j1, j2, j3, j4 = joints
            power_x = power_y = 0.0
            for position in range(j1 + 1, j4 + 1):  # the blocks after joint j1 up to joint j4
                body = 1 if position <= j2 else 2 if position <= j3 else 3
                v = velocity(body, cents[order[position]])
                power_x += weights[order[position]] * v[0]
                power_y += weights[order[position]] * v[1]
            if abs(power_x) < 1e-12 * max(abs(power_y), 1.0):
                continue
            sign = 1.0 if power_x > 0 else -1.0
            omegas = sign * np.array([0.0, 1.0, w2, w3, 0.0])  # the fixed part, bodies 1, 2, 3, the fixed part
            opens = True
            for h, (j, s) in enumerate(zip(joints, sides)):
                turn = omegas[h + 1] - omegas[h]  # of the block after the joint over the block before it
                other = ends[j][1 - s] - ends[j][s]
                if not turn * float(normals[j] @ np.array([-other[1], other[0]])) > 1e-12 * np.abs(other).max():
                    opens = False
                    break
            if not opens:
                continue
            multiplier = power_y / power_x
            if 0 < multiplier < best:
                best = multiplier
                hinges = [(chain[j], ends[j][s]) for j, s in zip(joints, sides)]
    return best, hinges


def test_a_portal_sways_at_b_over_h() -> None:
    b, h = 0.3, 1.2
    # two piers b x h on the base, a lintel resting on them: the sway mechanism, four hinges, lambda = b / h
    model = md.Model([[0.0, 0.0, b, h], [1.0, 0.0, 1.0 + b, h], [0.0, h, 1.0 + b, h + 0.25]], joints=STICKY)
    assert len(thrust_chains(model)[0]) == 4
    multiplier, hinges = four_hinge_multiplier(model)
    assert multiplier == pytest.approx(b / h, rel=1e-12)
    results = model.solve_limit()
    assert results.status == "collapse" and results.collapse_multiplier == pytest.approx(b / h, rel=1e-7)
    # the piers turn about their right toes, the lintel about the piers' top left corners
    assert sorted(tuple(p.round(12)) for _, p in hinges) == [(0.0, h), (b, 0.0), (1.0, h), (1.0 + b, 0.0)]
    found = md.report.hinges(model, results.mechanism)
    assert sorted(tuple(h.point.round(9)) for h in found) == sorted(tuple(p.round(9)) for _, p in hinges)
