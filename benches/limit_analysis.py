"""The collapse multiplier of a wall of dry joints by limit analysis (a linear program), against the static solver.

For associative joints (dilatancy = friction) the static theorem of limit analysis gives the exact collapse
multiplier: the largest lambda for which the blocks can be in equilibrium under the dead loads plus lambda times the
live load, with every interface's forces in its strength domain. masonry-dem's domain in resultants (no tension,
Mohr-Coulomb, rocking about the interface's ends) is exactly that of two contact points at the interface's ends, each
with a compressive normal force c >= 0 and a shear |s| <= mu c: this script writes that linear program from the
model's blocks and interfaces and solves it with SciPy's HiGHS. It is a check of the incremental solver's collapse
load (which must agree, within the solver's tolerance, on associative walls) and a measure of what a direct
limit-analysis method would cost at scale. It does not replace the incremental solver: with non-associative joints
(psi < phi) limit analysis is not exact, and it gives neither the pushover curve nor the joint states.

    make develop && .venv/bin/python benches/limit_analysis.py [--sizes 6 10 32 100] [--static 6 10 32]

SciPy is in the test extra (pyproject.toml) and the development environment, not a dependency of the package.
tests/python/test_limit_analysis.py checks the static solver and masonry-dem's own limit analysis
(`Model.solve_limit`) against this linear program, the latter also on the seeded random walls of `random_wall`;
benches/limit_vs_lp.py times `solve_limit` against this program under HiGHS and Clarabel.

A size is a number of courses c of the benchmarks' square running-bond wall (0.4 x 0.175 m blocks, mu = psi = 0.65,
g = 10; 32: 1,040 blocks, 100: 10,050); --static lists the sizes on which the static solver runs too.
"""

from __future__ import annotations

import argparse
import time
from typing import NamedTuple, Optional

import numpy as np
import scipy.sparse as sp
from scipy.optimize import linprog

import masonry_dem as md

MU = 0.65


def wall(courses: int) -> md.Model:
    blocks = md.running_bond(0.4, 0.175, courses, 0.4 * courses)
    return md.Model(blocks, gravity=10.0, joints={"default": {"friction": MU, "dilatancy": MU}})


def random_wall(seed: int, toothed: bool = False) -> tuple[md.Model, float]:
    """A seeded random running-bond wall of dry associative joints on a fixed base, and its friction mu.

    Drawn from numpy's default_rng(seed), so a seed gives the same wall on every machine: 10 to 500 blocks, block
    aspect ratio (length / height) 1.5 to 4, blocks 0.1 to 0.3 m high, wall height / length 0.3 to 3 (the length a
    whole number of half blocks, so that no course ends in a sliver), first course "half" or "full", friction 0.3 to
    0.9 with dilatancy = friction, g = 10, and 0 to 2 openings inside the wall: 1 to 2.5 block lengths wide, 2 to 6
    courses high, at least one block length from the ends and from each other, at least one course above the base
    and below the top (20 placements tried; a wall too small keeps fewer openings). A draw that md.Model refuses (a
    block cut off from the base) or whose block count falls outside 10..500 is drawn again from the same generator.
    The wall may not stand under its dead load (a lintel course too long for its friction: seed 263, for one).
    toothed: the openings are left toothed instead of cut, as masonry is built: the blocks whose centroid lies in an
    opening are left out, the others kept whole (the same draws; a draw whose toothed wall md.Model refuses is drawn
    again, so a seed's toothed wall may come from a later draw than its cut one)."""
    rng = np.random.default_rng(seed)
    while True:
        height = rng.uniform(0.1, 0.3)
        block_length = rng.uniform(1.5, 4.0) * height
        mu = float(rng.uniform(0.3, 0.9))
        first = "half" if rng.random() < 0.5 else "full"
        n_target = np.exp(rng.uniform(np.log(10.0), np.log(500.0)))
        slender = np.exp(rng.uniform(np.log(0.3), np.log(3.0)))  # wall height / length
        # n ~ (L / block_length) (H / height) with H = slender L
        length = np.sqrt(n_target * block_length * height / slender)
        length = 0.5 * block_length * max(2, round(2.0 * length / block_length))
        courses = max(2, round(slender * length / height))
        wall_height = courses * height
        openings: list[list[float]] = []
        wanted = rng.integers(0, 3)
        for _ in range(20):  # placements tried; a wall too small for the openings wanted keeps fewer
            if len(openings) == wanted:
                break
            w = rng.uniform(1.0, 2.5) * block_length
            h = rng.integers(2, 7) * height
            x_lo, x_hi = block_length, length - block_length - w
            y_lo, y_hi = height, wall_height - height - h
            if x_hi <= x_lo or y_hi <= y_lo:
                continue
            x0, y0 = rng.uniform(x_lo, x_hi), rng.uniform(y_lo, y_hi)
            if all(x0 >= o[2] + block_length or x0 + w <= o[0] - block_length for o in openings):
                openings.append([x0, y0, x0 + w, y0 + h])
        blocks = md.running_bond(block_length, height, courses, length, first_course=first,
                                 openings=None if toothed else (openings or None))
        if toothed and openings:
            centre = 0.5 * (blocks[:, :2] + blocks[:, 2:])
            inside = np.zeros(len(blocks), dtype=bool)
            for x0, y0, x1, y1 in openings:
                inside |= (centre[:, 0] > x0) & (centre[:, 0] < x1) & (centre[:, 1] > y0) & (centre[:, 1] < y1)
            blocks = blocks[~inside]
        if not 10 <= len(blocks) <= 500:
            continue
        try:
            model = md.Model(blocks, gravity=10.0, joints={"default": {"friction": mu, "dilatancy": mu}})
        except md.MasonryError:
            continue
        return model, mu


class LimitProgram(NamedTuple):
    """The static theorem's linear program: minimise obj @ x (that is, maximise lambda = x[-1]) subject to
    a_ub @ x <= b_ub, a_eq @ x == b_eq and bounds[:, 0] <= x <= bounds[:, 1] (+-inf for none). The contact forces
    x[:-1] are in units of the largest block weight."""

    obj: np.ndarray
    a_ub: sp.csr_matrix
    b_ub: np.ndarray
    a_eq: sp.csr_matrix
    b_eq: np.ndarray
    bounds: np.ndarray


def limit_program(model: md.Model, mu: float) -> LimitProgram:
    """The linear program of `collapse_multiplier` (see there), for any LP solver."""
    if model.top_index is not None:
        raise ValueError("limit analysis here: a wall on its base without a top beam")
    rects = np.asarray(model.rects)
    weights = np.asarray(model.weights)
    n_free = model.n_blocks  # the wall's blocks come first, then the base
    centre = 0.5 * (rects[:, :2] + rects[:, 2:])
    ab = np.asarray(model.interface_blocks)
    geo = np.asarray(model.interface_geometry)
    c, n, half = geo[:, :2], geo[:, 2:4], 0.5 * geo[:, 4]
    t = np.column_stack([-n[:, 1], n[:, 0]])
    m = len(ab)
    # variables: for each interface k and end e (0, 1): normal force c (column 4k + 2e) and shear s (4k + 2e + 1),
    # in units of the largest block weight, then lambda (the last column). The force on block b is c n + s t, on block a its opposite.
    rows, cols, vals = [], [], []
    for e, sign in enumerate((-1.0, 1.0)):
        p = c + sign * half[:, None] * t
        for var, direction in ((0, n), (1, t)):
            col = 4 * np.arange(m) + 2 * e + var
            for blk, s_blk in ((ab[:, 1], 1.0), (ab[:, 0], -1.0)):
                keep = blk < n_free
                f = s_blk * direction[keep]
                r = p[keep] - centre[blk[keep]]
                moment = r[:, 0] * f[:, 1] - r[:, 1] * f[:, 0]
                for comp, v in ((0, f[:, 0]), (1, f[:, 1]), (2, moment)):
                    rows.append(3 * blk[keep] + comp)
                    cols.append(col[keep])
                    vals.append(v)
    n_var = 4 * m + 1
    # forces in units of the largest block weight: in newtons (forces to 1e5 N, duals to 1e-4) HiGHS at these
    # tolerances stopped 2.3e-6 short on the 410-block wall (0.5032201 against 0.5032212, which its interior point
    # and dual simplex both reach, to 3e-10, in these units) and Clarabel at its defaults 35% short
    unit = float(np.max(weights[:n_free]))
    rows.append(3 * np.arange(n_free))
    cols.append(np.full(n_free, n_var - 1))
    vals.append(weights[:n_free] / unit)
    a_eq = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(3 * n_free, n_var))
    b_eq = np.zeros(3 * n_free)
    b_eq[1::3] = weights[:n_free] / unit  # the interfaces carry the weight: sum of forces + (0, -W) = 0
    # |s| <= mu c at each end: s - mu c <= 0 and -s - mu c <= 0
    k = np.arange(2 * m)
    r_ub = np.concatenate([2 * k, 2 * k + 1, 2 * k, 2 * k + 1])
    c_ub = np.concatenate([2 * k + 1, 2 * k + 1, 2 * k, 2 * k])
    v_ub = np.concatenate([np.ones(2 * m), -np.ones(2 * m), -mu * np.ones(2 * m), -mu * np.ones(2 * m)])
    a_ub = sp.csr_matrix((v_ub, (r_ub, c_ub)), shape=(4 * m, n_var))
    bounds = np.zeros((n_var, 2))
    bounds[:, 1] = np.inf
    bounds[1:4 * m:2, 0] = -np.inf  # the shears are free (within the friction rows)
    bounds[-1] = (-np.inf, np.inf)
    obj = np.zeros(n_var)
    obj[-1] = -1.0
    return LimitProgram(obj, a_ub, np.zeros(4 * m), a_eq, b_eq, bounds)


def collapse_multiplier(model: md.Model, mu: float, time_limit: Optional[float] = None) -> tuple[float, str]:
    """The largest lambda in equilibrium: dead load W_i down, live load lambda W_i along +x, at each block's centroid
    (the model's default loads), the base fixed. Only such walls: no top beam, no forces on blocks, no other fixed
    blocks (the Python model does not expose its loads and supports, so they are not checked, except the top beam).
    Returns (lambda, HiGHS's message); lambda is NaN if HiGHS did not reach an optimum (infeasible: the wall cannot
    stand; or time_limit [s] reached)."""
    return solve_highs(limit_program(model, mu), time_limit)


def solve_highs(lp: LimitProgram, time_limit: Optional[float] = None) -> tuple[float, str]:
    """lambda of a program of `limit_program` by HiGHS, as in `collapse_multiplier`."""
    options = {"primal_feasibility_tolerance": 1e-10, "dual_feasibility_tolerance": 1e-10}
    if time_limit is not None:
        options["time_limit"] = float(time_limit)
    # HiGHS's interior point with crossover and feasibility tolerances of 1e-10: on the 410-block wall its dual simplex
    # stopped at 0.50267 and the interior point at the default tolerances (1e-7) at 0.50320, both "optimal" but below
    # an equilibrium of the static solver (0.503167, checked admissible to 5e-13 of the forces); with these, 0.503220
    res = linprog(lp.obj, A_ub=lp.a_ub, b_ub=lp.b_ub, A_eq=lp.a_eq, b_eq=lp.b_eq, bounds=lp.bounds,
                  method="highs-ipm", options=options)
    return (float(res.x[-1]) if res.success else float("nan")), res.message


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", type=int, nargs="+", default=[6, 10, 20, 32], help="courses of the square wall")
    ap.add_argument("--static", type=int, nargs="*", default=[6, 10, 20, 32],
                    help="sizes also run by the static solver")
    a = ap.parse_args()
    print(f"{'blocks':>7s} {'interfaces':>10s} {'LP lambda':>10s} {'LP s':>8s} {'static lambda':>13s} {'static s':>9s} "
          f"{'relative gap':>12s}")
    for courses in a.sizes:
        model = wall(courses)
        t0 = time.perf_counter()
        lam, msg = collapse_multiplier(model, MU)
        t_lp = time.perf_counter() - t0
        line = f"{model.n_blocks:7d} {model.n_interfaces:10d} {lam:10.5f} {t_lp:8.2f}"
        if courses in a.static:
            r = model.solve_static(control="load")
            gap = (r.collapse_multiplier - lam) / lam
            line += f" {r.collapse_multiplier:13.5f} {r.elapsed_s:9.3f} {gap:12.2e}"
        print(line + ("" if np.isfinite(lam) else f"   ({msg})"), flush=True)


if __name__ == "__main__":
    main()
