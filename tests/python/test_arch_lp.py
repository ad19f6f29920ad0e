"""Limit analysis of arches against an independent linear program: the same static theorem written here from the
voussoirs' polygons alone and solved by HiGHS (scipy.optimize.linprog), not by the product's interior point.

The program, for the arch's voussoirs (convex polygons) on its two abutments (fixed polygons):
- the weight W_i = density x thickness x g x area of each voussoir, at its polygon's centroid (the shoelace formulas);
- the joints: every edge that two polygons share (the same two vertices, in opposite order), each carrying a force
  at each of its two ends: a normal component f_n >= 0 (compression, along the outward normal of the edge of the
  polygon that pushes; no tension) and a tangential one f_t with |f_t| <= mu f_n (Coulomb's law at a point, which
  in the plane is the two faces f_t - mu f_n <= 0 and -f_t - mu f_n <= 0: exact, no linearisation error);
- the equilibrium of each voussoir, forces and moment about its centroid, under its weight (0, -W_i) and the live
  load (lambda W_i, 0);
- maximise lambda.
With dry associative joints this is the collapse multiplier of the product's limit analysis, which writes each
joint's resultants (N, T, M) as the cone of the same two contact points' forces (limit/plane.rs). A backfill's weights
(loads carried by the voussoirs) enter the program as forces at their points, their moments about the centroids
written here."""

from __future__ import annotations

from typing import Any, Dict, List, Sequence, Tuple

import numpy as np
import pytest
from scipy.optimize import linprog

import masonry_dem as md

DENSITY, THICKNESS, GRAVITY = 2000.0, 1.0, 10.0


def area_centroid(polygon: np.ndarray) -> Tuple[float, np.ndarray]:
    """The area [m2] and centroid [m] of a polygon of vertices (k, 2) counter-clockwise (shoelace)."""
    x, y = polygon[:, 0], polygon[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    area = cross.sum() / 2
    return float(area), np.array([((x + xn) * cross).sum(), ((y + yn) * cross).sum()]) / (6 * area)


def shared_edges(polygons: List[np.ndarray]) -> List[Tuple[int, int, np.ndarray, np.ndarray]]:
    """Every edge two polygons share: (a, b, P, Q) with P -> Q an edge of polygon a (counter-clockwise, so that b lies
    to its right, along its outward normal) and Q -> P one of b, the ends equal to 1e-12 of the polygons' extent."""
    scale = max(float(np.abs(p).max()) for p in polygons)
    found = []
    for a, pa in enumerate(polygons):
        for b in range(a + 1, len(polygons)):
            pb = polygons[b]
            for i in range(len(pa)):
                p, q = pa[i], pa[(i + 1) % len(pa)]
                for j in range(len(pb)):
                    r, s = pb[j], pb[(j + 1) % len(pb)]
                    if np.abs(p - s).max() <= 1e-12 * scale and np.abs(q - r).max() <= 1e-12 * scale:
                        found.append((a, b, p, q))
    return found


def lp_multiplier(blocks: List[Any], supports: List[Any], friction: float, carried: Sequence[Any] = ()) -> float:
    """The largest lambda of the program of the module's docstring, by HiGHS; `blocks` the voussoirs, `supports`
    the fixed polygons, `carried` loads (block, [x, y], weight [N]): a weight at its point, pushed by lambda times
    it like the blocks' own."""
    movable = [np.asarray(b, dtype=np.float64) for b in blocks]
    polygons = movable + [np.asarray(s, dtype=np.float64) for s in supports]
    props = [area_centroid(p) for p in movable]
    assert all(a > 0 for a, _ in props), "counter-clockwise voussoirs"
    weights = [DENSITY * THICKNESS * GRAVITY * a for a, _ in props]
    joints = shared_edges(polygons)
    n_points = 2 * len(joints)
    # variables: (f_n, f_t) at each end of each joint, then lambda
    n_var = 2 * n_points + 1
    eq = np.zeros((3 * len(movable), n_var))
    ub: List[np.ndarray] = []
    for k, (a, b, p, q) in enumerate(joints):
        edge = q - p
        t = edge / np.linalg.norm(edge)
        n = np.array([t[1], -t[0]])  # outward of a (counter-clockwise): into b
        for e, point in enumerate((p, q)):
            col = 2 * (2 * k + e)
            for body, sign in ((b, 1.0), (a, -1.0)):  # a pushes b along n; b pushes a back
                if body >= len(movable):
                    continue  # an abutment: its reaction is free
                r = point - props[body][1]
                for v, direction in ((col, n), (col + 1, t)):
                    force = sign * direction
                    eq[3 * body:3 * body + 2, v] += force
                    eq[3 * body + 2, v] += r[0] * force[1] - r[1] * force[0]
            for side in (1.0, -1.0):  # side f_t - mu f_n <= 0
                row = np.zeros(n_var)
                row[col], row[col + 1] = -friction, side
                ub.append(row)
    rhs = np.zeros(3 * len(movable))
    for i, w in enumerate(weights):
        eq[3 * i, -1] = w  # the live load lambda W_i along +x
        rhs[3 * i + 1] = w  # the weight (0, -W_i) moved to the right-hand side
    for i, point, w in carried:  # (lambda W, -W) at the point: its moment about the centroid too
        r = np.asarray(point, dtype=np.float64) - props[i][1]
        eq[3 * i, -1] += w
        eq[3 * i + 2, -1] += -r[1] * w
        rhs[3 * i + 1] += w
        rhs[3 * i + 2] += r[0] * w  # the moment of (0, -W), r_x (-W), moved to the right-hand side
    c = np.zeros(n_var)
    c[-1] = -1.0
    bounds = [(0, None), (None, None)] * n_points + [(None, None)]
    result = linprog(c, A_ub=np.array(ub), b_ub=np.zeros(len(ub)), A_eq=eq, b_eq=rhs, bounds=bounds, method="highs",
                     options={"primal_feasibility_tolerance": 1e-10, "dual_feasibility_tolerance": 1e-10})
    assert result.status == 0, result.message
    return float(result.x[-1])


#: Arches on abutments, 20 to 80 voussoirs: (the generator's arguments, friction). Associative friction high enough
#: that no joint slides, and two that slide (the segmental arch's flat springings, the low friction of the
#: semicircular ring), where Coulomb's faces bind.
ARCHES: Dict[str, Tuple[Dict[str, Any], float]] = {
    "semicircular t/R 0.15": (dict(kind="semicircular", radius=1.0, thickness=0.15, voussoirs=40), 2.0),
    "semicircular t/R 0.20": (dict(kind="semicircular", radius=1.0, thickness=0.20, voussoirs=80), 2.0),
    "semicircular t/R 0.20, friction 0.4": (dict(kind="semicircular", radius=1.0, thickness=0.20, voussoirs=27), 0.4),
    "segmental": (dict(kind="segmental", span=4.0, rise=1.0, thickness=0.3, voussoirs=20), 2.0),
    "segmental, friction 0.3": (dict(kind="segmental", span=4.0, rise=1.0, thickness=0.3, voussoirs=20), 0.3),
    "pointed": (dict(kind="pointed", span=3.0, rise=2.2, thickness=0.25, voussoirs=30), 2.0),
    "elliptical": (dict(kind="elliptical", span=4.0, rise=1.2, thickness=0.3, voussoirs=25), 2.0),
}


@pytest.mark.parametrize("name", sorted(ARCHES))
def test_limit_analysis_of_an_arch_is_the_program_written_from_its_polygons(name: str) -> None:
    arguments, friction = ARCHES[name]
    made = md.arch(**arguments)
    expected = lp_multiplier(made["blocks"], made["supports"], friction)
    model = md.Model(made["blocks"], supports=made["supports"], thickness=THICKNESS, density=DENSITY, gravity=GRAVITY,
                     joints={"default": md.dry_joint(friction, dilatancy=friction)})
    # the same weights: the model's blocks are the polygons given
    assert np.asarray(model.weights)[:len(made["blocks"])] == pytest.approx(
        [DENSITY * THICKNESS * GRAVITY * area_centroid(np.asarray(b))[0] for b in made["blocks"]], rel=1e-12)
    results = model.solve_limit(tolerance=1e-10)
    assert results.status == "collapse", results.error
    assert 0 < expected < 2
    if friction < 1:  # Coulomb's faces bind: the same arch without sliding stands more
        assert lp_multiplier(made["blocks"], made["supports"], 2.0) > expected * 1.01
    assert results.collapse_multiplier == pytest.approx(expected, rel=1e-7)


def test_limit_analysis_of_a_backfilled_arch_is_the_program_with_the_fill_s_weights() -> None:
    # a semicircular ring of t/R 0.15 in 30 voussoirs under a fill of 1800 kg/m3 up to 1.4 m (0.325 m over the
    # extrados's crown), and a segmental arch filled to above its crown
    for arguments, level in ((dict(kind="semicircular", radius=1.0, thickness=0.15, voussoirs=30), 1.4),
                             (dict(kind="segmental", span=4.0, rise=1.0, thickness=0.3, voussoirs=20), 1.6)):
        made = md.arch(**arguments, backfill_level=level, backfill_density=1800.0, wall_thickness=THICKNESS,
                       gravity=GRAVITY)
        carried = made["carried"]
        assert [k for k, _, _ in carried] == list(range(len(made["blocks"])))
        expected = lp_multiplier(made["blocks"], made["supports"], 2.0, carried)
        bare = lp_multiplier(made["blocks"], made["supports"], 2.0)
        assert abs(expected - bare) > 0.01 * bare  # the fill counts
        model = md.Model(made["blocks"], supports=made["supports"], thickness=THICKNESS, density=DENSITY,
                         gravity=GRAVITY, joints={"default": md.dry_joint(2.0, dilatancy=2.0)}, carried=carried)
        results = model.solve_limit(tolerance=1e-10)
        assert results.status == "collapse", results.error
        assert results.collapse_multiplier == pytest.approx(expected, rel=1e-7)
