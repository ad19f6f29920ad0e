"""masonry-dem's limit analysis (`Model.solve_limit`) against two general LP solvers on the same program, side by side.

The program is that of benches/limit_analysis.py (the static theorem for dry associative joints: equilibrium of every
block under the dead loads plus lambda times the live load, two contact points per interface with c >= 0 and
|s| <= mu c; maximise lambda), written once from the model's blocks and interfaces (numpy, "LP build" below) and
given to
  - SciPy's HiGHS, interior point with crossover, feasibility tolerances 1e-10 (as benches/limit_analysis.py);
  - Clarabel (Python package, interior point for conic programs), its default settings (output off): the equalities
    as the zero cone, the friction rows and c >= 0 as the nonnegative cone, P = 0.
masonry-dem's `solve_limit()` builds its own program from the model (its time includes that); it is timed by its
Results.elapsed_s and by the wall time of the Python call. The LP solvers' times are their calls' wall times
(HiGHS: `linprog`; Clarabel: solver set-up and solve), without the LP build, which is shown apart.

    make develop && .venv/bin/python benches/limit_vs_lp.py [--sizes 6 10 32 100] [--repeat N] [--time-limit S]

A size is a number of courses c of the benchmarks' square running-bond wall (benches/limit_analysis.py's `wall`:
0.4 x 0.175 m blocks, mu = psi = 0.65, g = 10; 6: 39 blocks, 10: 105, 32: 1,040, 100: 10,050). Times are medians
over --repeat runs (default 3, and 1 for sizes >= 100); each lambda is that of the last run. Ratios are the LP
solver's wall time over solve_limit's wall time, and lambda's relative difference from HiGHS's. --time-limit stops
HiGHS and Clarabel after that many seconds each (default 1800; 0: none): on the 10,050-block wall HiGHS's interior
point ended "imprecise" after 17 min (objective 0.426753, relative gap 2.3e-6), its crossover too, and the dual
simplex it then starts from scratch was still in phase 1 at 30 min. If the installed package has no `solve_limit`
yet, its columns read n/a and the two LP solvers are timed alone.

Clarabel at its default tolerances (1e-8) stops short of the optimum on these programs while reporting "Solved": by
8e-5 on the 1,040-block wall and 3e-3 on the 10,050-block one (and, with the forces in newtons rather than in units
of the largest block weight, by 35% on the 410-block wall). Its column is a timing at its defaults, not a reference.
"""

from __future__ import annotations

import argparse
import statistics
import time
from typing import Optional

import clarabel
import numpy as np
import scipy.sparse as sp

import masonry_dem as md
from limit_analysis import MU, LimitProgram, limit_program, solve_highs, wall


def solve_clarabel(lp: LimitProgram, time_limit: Optional[float] = None) -> tuple[float, str, float]:
    """lambda of a program of `limit_program` by Clarabel with its default settings (output off); (lambda, status,
    Clarabel's own solve time [s]). lambda is NaN unless the status is Solved or AlmostSolved."""
    n_var = len(lp.obj)
    lower, upper = lp.bounds[:, 0], lp.bounds[:, 1]
    lo = np.flatnonzero(np.isfinite(lower))
    up = np.flatnonzero(np.isfinite(upper))
    # bounds as rows of the nonnegative cone: -x_i + s = -lower_i and x_i + s = upper_i, s >= 0
    a_lo = sp.csr_matrix((-np.ones(len(lo)), (np.arange(len(lo)), lo)), shape=(len(lo), n_var))
    a_up = sp.csr_matrix((np.ones(len(up)), (np.arange(len(up)), up)), shape=(len(up), n_var))
    a = sp.vstack([lp.a_eq, lp.a_ub, a_lo, a_up], format="csc")
    b = np.concatenate([lp.b_eq, lp.b_ub, -lower[lo], upper[up]])
    cones = [clarabel.ZeroConeT(lp.a_eq.shape[0]), clarabel.NonnegativeConeT(lp.a_ub.shape[0] + len(lo) + len(up))]
    settings = clarabel.DefaultSettings()
    settings.verbose = False
    if time_limit is not None:
        settings.time_limit = float(time_limit)
    solver = clarabel.DefaultSolver(sp.csc_matrix((n_var, n_var)), lp.obj, a, b, cones, settings)
    sol = solver.solve()
    status = str(sol.status)
    lam = float(sol.x[-1]) if status in ("Solved", "AlmostSolved") else float("nan")
    return lam, status, float(sol.solve_time)


def timed(fn, *args):
    t0 = time.perf_counter()
    out = fn(*args)
    return out, time.perf_counter() - t0


def fmt_t(t: float) -> str:
    return "n/a" if not np.isfinite(t) else (f"{t:.4f}" if t < 1.0 else f"{t:.2f}")


def fmt_ratio(num: float, den: float) -> str:
    return f"{num / den:.1f}x" if np.isfinite(num) and np.isfinite(den) and den > 0 else "n/a"


def fmt_lam(lam: float, width: int, digits: int) -> str:
    return f"{lam:{width}.{digits}f}" if np.isfinite(lam) else f"{'n/a':>{width}s}"


def fmt_rel(lam: float, ref: float) -> str:
    return f"{(lam - ref) / abs(ref):+.1e}" if np.isfinite(lam) and np.isfinite(ref) and ref != 0 else "n/a"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", type=int, nargs="+", default=[6, 10, 32, 100], help="courses of the square wall")
    ap.add_argument("--repeat", type=int, default=None,
                    help="runs per size (default 3, and 1 for sizes >= 100); times are medians")
    ap.add_argument("--time-limit", type=float, default=1800.0,
                    help="seconds for HiGHS and for Clarabel, each (default 1800; 0: none)")
    a = ap.parse_args()
    time_limit = a.time_limit if a.time_limit > 0 else None
    has_limit = hasattr(md.Model, "solve_limit")
    if not has_limit:
        print("masonry_dem.Model has no solve_limit in this build: its columns read n/a", flush=True)
    print(f"{'blocks':>7s} {'interf.':>7s} {'runs':>4s} | {'lambda: solve_limit':>19s} {'HiGHS':>10s} "
          f"{'Clarabel':>10s} | {'time [s]: limit':>15s} {'(wall)':>8s} {'LP build':>8s} {'HiGHS':>8s} "
          f"{'Clarabel':>8s} {'(own)':>8s} | {'HiGHS/limit':>11s} {'Clar./limit':>11s} | "
          f"{'limit-HiGHS':>11s} {'Clar.-HiGHS':>11s}  status")
    for courses in a.sizes:
        runs = a.repeat if a.repeat is not None else (1 if courses >= 100 else 3)
        model = wall(courses)
        t_el, t_lim, t_build, t_hi, t_cl, t_cl_own = [], [], [], [], [], []
        lam_lim = lam_hi = lam_cl = float("nan")
        notes = []
        for _ in range(runs):
            if has_limit:
                res, t = timed(model.solve_limit)
                t_lim.append(t)
                t_el.append(res.elapsed_s)
                lam_lim = res.collapse_multiplier
                limit_status = res.status
            lp, t = timed(limit_program, model, MU)
            t_build.append(t)
            (lam_hi, msg_hi), t = timed(solve_highs, lp, time_limit)
            t_hi.append(t)
            (lam_cl, status_cl, own), t = timed(solve_clarabel, lp, time_limit)
            t_cl.append(t)
            t_cl_own.append(own)
        if has_limit and limit_status != "collapse":
            notes.append(f"solve_limit: {limit_status}")
        if not np.isfinite(lam_hi):
            notes.append(f"HiGHS: {msg_hi}")
        if status_cl != "Solved":
            notes.append(f"Clarabel: {status_cl}")
        med = {k: (statistics.median(v) if v else float("nan"))
               for k, v in dict(el=t_el, lim=t_lim, build=t_build, hi=t_hi, cl=t_cl, own=t_cl_own).items()}
        print(f"{model.n_blocks:7d} {model.n_interfaces:7d} {runs:4d} | {fmt_lam(lam_lim, 19, 9)} {fmt_lam(lam_hi, 10, 7)} "
              f"{fmt_lam(lam_cl, 10, 7)} | "
              f"{fmt_t(med['el']):>15s} {fmt_t(med['lim']):>8s} {fmt_t(med['build']):>8s} {fmt_t(med['hi']):>8s} "
              f"{fmt_t(med['cl']):>8s} {fmt_t(med['own']):>8s} | {fmt_ratio(med['hi'], med['lim']):>11s} "
              f"{fmt_ratio(med['cl'], med['lim']):>11s} | {fmt_rel(lam_lim, lam_hi):>11s} {fmt_rel(lam_cl, lam_hi):>11s}"
              f"  {'; '.join(notes) or 'ok'}", flush=True)


if __name__ == "__main__":
    main()
