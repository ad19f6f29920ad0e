"""Whole static analyses to collapse on running-bond walls of growing size, and the cost of a call from Python.

For each size: the time of `Model.solve_static(control="load")` (median of --repeat runs), the solver's own
elapsed time, Newton iterations, load steps and the peak memory of the process. Then the overhead of the Python
call on Ferris & Tin-Loi wall 1 (33 blocks): the call's wall time against the solver's `elapsed_s`.

    .venv/bin/python benches/scaling.py [--sizes 10 32] [--repeat 3] [--calls 40] [--rounds 3]
    .venv/bin/python benches/scaling.py --sizes        # only the Python call

A size is a number of courses c: c courses of about c blocks (10: 105 blocks, 32: 1,040, 100: 10,050); the
fixed base comes on top of these.
"""

from __future__ import annotations

import argparse
import resource
import statistics
import time

import masonry_dem as md


def wall(courses: int) -> md.Model:
    blocks = md.running_bond(0.4, 0.175, courses, 0.4 * courses)
    return md.Model(blocks, gravity=10.0, joints={"default": {"friction": 0.65, "dilatancy": 0.65}})


def peak_rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", type=int, nargs="*", default=[10, 32],
                    help="courses (about as many blocks each); none: only the Python call")
    ap.add_argument("--repeat", type=int, default=3, help="runs per size (the median is shown)")
    ap.add_argument("--calls", type=int, default=40, help="calls on wall 1 per round (the median is shown)")
    ap.add_argument("--rounds", type=int, default=3, help="rounds of calls on wall 1")
    a = ap.parse_args()
    if a.sizes:
        print(f"{'blocks':>7s} {'interfaces':>10s} {'median s':>9s} {'solver s':>9s} {'steps':>6s} {'iterations':>10s} "
              f"{'lambda':>7s} {'peak RSS MB':>11s}")
    for c in a.sizes:
        t_build = time.perf_counter()
        model = wall(c)
        t_build = time.perf_counter() - t_build
        runs = []
        for _ in range(a.repeat):
            t0 = time.perf_counter()
            r = model.solve_static(control="load")
            runs.append((time.perf_counter() - t0, r))
        med = statistics.median(t for t, _ in runs)
        r = runs[-1][1]
        print(f"{model.n_blocks:7d} {model.n_interfaces:10d} {med:9.3f} {r.elapsed_s:9.3f} {r.steps:6d} "
              f"{r.iterations:10d} {r.collapse_multiplier:7.4f} {peak_rss_mb():11.0f}   (model {t_build:.3f} s)")

    # the Python call on a 33-block wall: its wall time against the solver's own time
    w1 = md.Model(md.running_bond(0.4, 0.175, 6, 2.0), gravity=10.0,
                  joints={"default": {"friction": 0.65, "dilatancy": 0.65}})
    print()
    for _ in range(a.rounds):
        calls = []
        for _ in range(a.calls):
            t0 = time.perf_counter()
            r = w1.solve_static(control="load")
            calls.append((time.perf_counter() - t0, r.elapsed_s))
        call = statistics.median(t for t, _ in calls)
        fastest = min(t for t, _ in calls)
        inner = statistics.median(e for _, e in calls)
        print(f"wall 1 (33 blocks) from Python, median of {a.calls}: call {call * 1e3:.2f} ms (fastest "
              f"{fastest * 1e3:.2f} ms), solver {inner * 1e3:.2f} ms, overhead {(call - inner) * 1e3:.3f} ms")


if __name__ == "__main__":
    main()
