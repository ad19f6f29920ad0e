"""Walls of convex polygons against walls of rectangles, and this build against another (main before polygons).

Two benchmarks, each a median of alternated runs in one process tree:

``stones``: limit analysis of a stone wall of 10,053 stones (``masonry_dem.stone_wall``: 40 m x 17.5 m, stones
0.36 x 0.175 m on average, irregularity 0.3, head joints within 20 degrees, bed joints within 3 degrees, seed 1; the
bond makes the stones longer than drawn, 0.398 m on average) against the square running bond of as many rectangles
(100 courses of 0.4 x 0.175 m blocks, 40 m: 10,050 blocks),
dry associative joints mu = 0.65, g = 10; the two analyses alternate, ``--reps`` each, the models built once, the
solver's call timed. With ``--paths`` the static path and the explicit solver run once each on the stone wall too.

``builds``: the same three analyses by two builds of the package (two Python environments, e.g. this worktree's
and one of main before polygons landed), each analysis run in a fresh interpreter of one build then of the other,
alternately, ``--reps`` times: Ferris and Tin-Loi's wall 1 by the explicit solver (examples/ferris-tinloi-wall1.toml,
method "dynamic"), wall 2 by the static solver (examples/ferris-tinloi-wall2.toml), and limit analysis of the
10,050-block running bond above. Each child times the analysis alone (the case read and the model built first; wall
2's static analysis, tens of milliseconds, ten times in a row, the child's median).

    .venv/bin/python benches/stone_wall.py stones --reps 5 [--paths]
    .venv/bin/python benches/stone_wall.py builds --before ../stones-before/.venv/bin/python --reps 7
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path
from typing import Any, Callable, Dict, List

ROOT = Path(__file__).resolve().parents[1]
MU = 0.65


def joints() -> Dict[str, Any]:
    return {"default": {"friction": MU, "dilatancy": MU}}


def rectangles() -> Any:
    import masonry_dem as md

    return md.Model(md.running_bond(0.4, 0.175, 100, 40.0), gravity=10.0, joints=joints())


def stones() -> Any:
    import masonry_dem as md

    blocks = md.stone_wall(40.0, 17.5, 0.36, 0.175, irregularity=0.3, head_angle=20.0, bed_angle=3.0, seed=1)
    return md.Model(blocks, gravity=10.0, joints=joints())


def timed(run: Callable[[], Any]) -> tuple[float, Any]:
    start = time.perf_counter()
    result = run()
    return time.perf_counter() - start, result


def alternate(models: Dict[str, Any], reps: int) -> Dict[str, float]:
    """Limit analysis of each model in turn, ``reps`` rounds, each run printed: the median time of each [s]."""
    times: Dict[str, List[float]] = {name: [] for name in models}
    for rep in range(reps):
        for name, model in models.items():
            seconds, result = timed(model.solve_limit)
            times[name].append(seconds)
            print(f"  rep {rep} {name}: {seconds:.3f} s, lambda {result.collapse_multiplier:.6f} ({result.status}, "
                  f"{result.iterations} iterations)", flush=True)
    return {name: statistics.median(t) for name, t in times.items()}


def bench_stones(reps: int, paths: bool) -> None:
    models = {"rectangles": rectangles(), "stones": stones()}
    for name, model in models.items():
        print(f"{name}: {model.n_blocks} blocks", flush=True)
    medians = alternate(models, reps)
    print(f"medians: rectangles {medians['rectangles']:.3f} s, stones {medians['stones']:.3f} s, "
          f"ratio {medians['stones'] / medians['rectangles']:.3f}", flush=True)
    if paths:
        model = models["stones"]
        for method, run in (("static", model.solve_static), ("explicit", model.solve_dynamic)):
            seconds, result = timed(run)
            print(f"stones by the {method} solver: {seconds:.1f} s, lambda {result.collapse_multiplier:.6f} "
                  f"({result.status})", flush=True)


def child(task: str) -> None:
    """One analysis in this interpreter, its time printed as JSON."""
    import masonry_dem as md

    if task == "limit":
        model = rectangles()
        seconds, result = timed(model.solve_limit)
    else:
        case = md.load_case(ROOT / "examples" / {"explicit": "ferris-tinloi-wall1.toml",
                                                  "static": "ferris-tinloi-wall2.toml"}[task])
        # wall 2's static analysis takes tens of milliseconds: the median of ten in a row
        runs = [timed(lambda: case.run("dynamic" if task == "explicit" else "static"))
                for _ in range(10 if task == "static" else 1)]
        seconds, result = statistics.median(r[0] for r in runs), runs[-1][1]
    print(json.dumps({"seconds": seconds, "lambda": result.collapse_multiplier, "status": result.status}))


def bench_builds(before: str, after: str, reps: int) -> None:
    pythons = {"before": before, "after": after}
    tasks = ("explicit", "static", "limit")
    times: Dict[str, Dict[str, List[float]]] = {t: {b: [] for b in pythons} for t in tasks}
    for rep in range(reps):
        for task in tasks:
            for build, python in pythons.items():
                out = subprocess.run([python, __file__, "child", task], check=True, capture_output=True, text=True,
                                     env={**os.environ, "PYTHONDONTWRITEBYTECODE": "1"})
                row = json.loads(out.stdout.strip().splitlines()[-1])
                times[task][build].append(row["seconds"])
                print(f"  rep {rep} {task} {build}: {row['seconds']:.4f} s, lambda {row['lambda']:.6f} "
                      f"({row['status']})", flush=True)
    for task in tasks:
        med = {b: statistics.median(t) for b, t in times[task].items()}
        print(f"{task}: median before {med['before']:.4f} s, after {med['after']:.4f} s, "
              f"ratio {med['after'] / med['before']:.3f}", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="bench", required=True)
    s = sub.add_parser("stones")
    s.add_argument("--reps", type=int, default=5)
    s.add_argument("--paths", action="store_true")
    b = sub.add_parser("builds")
    b.add_argument("--before", required=True, help="the Python of the other build")
    b.add_argument("--after", default=sys.executable, help="the Python of this build (default: this one)")
    b.add_argument("--reps", type=int, default=7)
    c = sub.add_parser("child")
    c.add_argument("task", choices=("explicit", "static", "limit"))
    args = parser.parse_args()
    if args.bench == "stones":
        bench_stones(args.reps, args.paths)
    elif args.bench == "builds":
        bench_builds(args.before, args.after, args.reps)
    else:
        child(args.task)


if __name__ == "__main__":
    main()
