"""The cost of the contact update in a time history: a wall of about 10^3 blocks shaken by the El Centro record,
with contact_update on and off, side by side (a run that forms no new contact: the cost of the check per step).

Run, from the repository's root, in a venv where `make develop` built masonry_dem:

    python benches/contact_update.py [--duration 2.0] [--repeats 3] [--scale 1.0] [--threads 1]

The wall: Ferris & Tin-Loi's blocks (0.4 x 0.175 m, dry joints of friction 0.65, 1e10 N/m3) in running bond, 20 m
long and 40 courses (2,020 blocks), on a fixed base; the record examples/elcentro-1940-ns.csv (in g at 0.02 s)
times --scale, its first --duration seconds. Each repeat runs the two one after the other (on, off); the medians
of the solver's own wall-clock time (TimeHistory.elapsed_s) are printed with their ratio, and the largest
difference of the two runs' displacements. With the update on the time step is also stable for a block touching
along every edge: the steps of the two runs are printed too.
"""

from __future__ import annotations

import argparse
import statistics
from pathlib import Path
from typing import Any, Callable, Optional

import numpy as np

import masonry_dem as md

RECORD = Path(__file__).resolve().parents[1] / "examples" / "elcentro-1940-ns.csv"
JOINTS = {"default": {"friction": 0.65, "cohesion": 0.0, "tensile_strength": 0.0, "dilatancy": 0.0,
                      "normal_stiffness": 1e10, "shear_stiffness": 1e10}}


def record(duration: float, scale: float) -> tuple[np.ndarray, np.ndarray]:
    """The record's first `duration` seconds [s] and accelerations [m/s2] times `scale`."""
    rows = [line.split(",") for line in RECORD.read_text().splitlines() if line and line[0].isdigit()]
    t = np.array([float(r[0]) for r in rows])
    a = np.array([float(r[1]) for r in rows]) * 9.81 * scale
    keep = t <= duration + 0.02
    return t[keep], a[keep]


def side_by_side(run: Callable[[bool, Optional[float]], Any], repeats: int) -> tuple[float, float, dict, float]:
    """`run(update, time_step)` `repeats` times with the update on, then off, `time_step` the first run's (None
    for it): the medians of the solver's own wall-clock time (TimeHistory.elapsed_s) on and off, the last runs
    by update, and the largest difference of their displacements."""
    times: dict[bool, list[float]] = {True: [], False: []}
    runs = {}
    step = None
    for _ in range(repeats):
        for update in (True, False):
            h = run(update, step)
            step = h.time_step
            times[update].append(h.elapsed_s)
            runs[update] = h
    diff = float(np.max(np.abs(np.asarray(runs[True].displacements) - np.asarray(runs[False].displacements))))
    return statistics.median(times[True]), statistics.median(times[False]), runs, diff


def arguments(doc: str, duration: float) -> argparse.Namespace:
    """The command line's --duration (default `duration` [s]), --repeats, --scale and --threads, the script's
    docstring `doc` its help."""
    parser = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    parser.add_argument("--duration", type=float, default=duration)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--scale", type=float, default=1.0)
    parser.add_argument("--threads", type=int, default=1)
    return parser.parse_args()


def main() -> None:
    args = arguments(__doc__, 2.0)
    blocks = md.running_bond(0.4, 0.175, courses=40, length=20.0, first_course="half")
    model = md.Model(blocks, thickness=1.0, density=1000.0, joints=JOINTS)
    ground = record(args.duration, args.scale)
    on, off, runs, diff = side_by_side(lambda update, step: model.simulate(
        args.duration, base_acceleration=ground, record_interval=0.01, threads=args.threads, contact_update=update),
        args.repeats)
    print(f"{len(blocks)} blocks, {args.duration} s of El Centro x {args.scale}, {args.threads} thread(s), "
          f"{args.repeats} repeats")
    print(f"update on:  median {on:.3f} s ({runs[True].steps} steps of {runs[True].time_step:.3e} s)")
    print(f"update off: median {off:.3f} s ({runs[False].steps} steps of {runs[False].time_step:.3e} s)")
    print(f"ratio on / off: {on / off:.3f}; largest difference of the displacements {diff:.3e} m")


if __name__ == "__main__":
    main()
