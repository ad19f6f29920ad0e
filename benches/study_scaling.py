"""Benchmarks of studies (masonry_dem.study) on Ferris & Tin-Loi wall 1 (33 blocks):

1. the per-analysis overhead of the study machinery, against the analysis itself (the model built from a
   ready case, and solved):
   - in the worker: the case made from the study's data (the row's values set in the case table, the case
     checked) and the rest of a row (``run_item`` less the case and the analysis), medians over 300 rows;
   - end to end: a study of N analyses on a local cluster of one worker (up: Dask's scheduling, the tasks'
     data, the cases, the rows, their Parquet parts and the final file included) against the same N analyses
     in a plain loop in one process (``case.solve(case.build_model())`` on cases made beforehand);
2. N = 1,000 analyses of wall 1 (the friction drawn from N(0.65, 0.05), associative; the static solver) on a
   local cluster of 2 workers against 1;
3. the example, examples/studies/wall1-fragility.toml (1,000 samples), end to end with the command line
   (cluster start, the rows, the Parquet file and the summary figure included).

    .venv/bin/python benches/study_scaling.py [--analyses 1000] [--repeat 5]

The plain loop, the study on one worker and on two take turns ``--repeat`` times (each cluster started for its
turn, timed on its second run); each timing is the median. The figures are in BENCHMARKS.md (Studies).
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path
from typing import Any, Callable, Dict, List

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))

from masonry_dem.study import run_study, study_from_dict  # noqa: E402
from masonry_dem.study.runner import connect  # noqa: E402
from masonry_dem.study.worker import run_item  # noqa: E402

WALL1 = ROOT / "examples" / "ferris-tinloi-wall1.toml"
EXAMPLE = ROOT / "examples" / "studies" / "wall1-fragility.toml"


def wall1_study(method: str, n: int) -> Any:
    return study_from_dict(
        {
            "format": 1,
            "case": str(WALL1),
            "study": {"methods": [method], "samples": n, "seed": 3},
            "vary": {"friction": {"distribution": "normal", "mean": 0.65, "std": 0.05, "associative": True}},
        }
    )


def median_ms(times: List[float]) -> float:
    return float(np.median(times)) * 1e3


def in_worker_overhead(method: str, n: int) -> Dict[str, float]:
    """Per analysis, medians [ms]: the analysis (the model built from a ready case, and solved), the case
    made from the study's data (the row's values set, the case checked), and the rest of a row (the row
    in the worker, ``run_item``, less the case and the analysis, measured on the same analysis just before)."""
    study = wall1_study(method, n)
    case_s, analysis_s, rest_s = [], [], []
    for item in study.items():
        start = time.perf_counter()
        case = study.case(item)
        middle = time.perf_counter()
        case.solve(case.build_model(), method)
        end = time.perf_counter()
        run_item(study, item)
        rest_s.append(time.perf_counter() - end - (end - start))
        case_s.append(middle - start)
        analysis_s.append(end - middle)
    return {"analysis_ms": median_ms(analysis_s), "case_ms": median_ms(case_s), "rest_ms": median_ms(rest_s)}


def plain_loop(cases: List[Any], methods: List[str]) -> None:
    for case, method in zip(cases, methods):
        case.solve(case.build_model(), method)


def on_cluster(study: Any, workers: int, out: Path) -> float:
    """The time [s] of the study on a local cluster of ``workers`` processes already up (a first run warms the
    workers), its rows written to ``out``; the cluster is closed afterwards."""
    with connect(None, workers) as client:
        for _ in range(2):
            out.unlink(missing_ok=True)
            start = time.perf_counter()
            run_study(study, out, scheduler=client)
            elapsed = time.perf_counter() - start
    return elapsed


def interleaved(repeat: int, runs: Dict[str, Callable[[], float]]) -> Dict[str, float]:
    """The median of each run's time [s], the runs taking turns ``repeat`` times (so that the drift of a
    shared machine weighs on each alike)."""
    times: Dict[str, List[float]] = {name: [] for name in runs}
    for _ in range(repeat):
        for name, run in runs.items():
            times[name].append(run())
    return {name: float(np.median(t)) for name, t in times.items()}


def timed(run: Callable[[], Any]) -> Callable[[], float]:
    def measured() -> float:
        start = time.perf_counter()
        run()
        return time.perf_counter() - start

    return measured


def example_end_to_end(tmp: Path) -> float:
    out, plot = tmp / "example.parquet", tmp / "example.png"
    for p in (out, plot):
        p.unlink(missing_ok=True)
    command = [
        str(Path(sys.executable).parent / "masonry-dem"),
        "study",
        str(EXAMPLE),
        "--out",
        str(out),
        "--plot",
        str(plot),
        "-q",
    ]
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--analyses", type=int, default=1000)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    n = args.analyses
    tmp = ROOT / "out" / "bench-study"
    tmp.mkdir(parents=True, exist_ok=True)
    print(
        "in the worker, per analysis (medians): the analysis (model and solver), the case from the study's data, the rest of the row"
    )
    for method in ("static", "limit"):
        o = in_worker_overhead(method, 300)
        extra = o["case_ms"] + o["rest_ms"]
        print(
            f"  {method:<7} analysis {o['analysis_ms']:.3g} ms; case {o['case_ms']:.2g} ms, rest {o['rest_ms']:+.2g} ms: "
            f"{extra:.2g} ms ({100 * extra / o['analysis_ms']:.2g} % of the analysis)",
            flush=True,
        )
    study = wall1_study("static", n)
    items = list(study.items())
    cases, methods = [study.case(item) for item in items], [item.method for item in items]
    runs = {
        "plain loop": timed(lambda: plain_loop(cases, methods)),
        "1 worker": lambda: on_cluster(study, 1, tmp / "one.parquet"),
        "2 workers": lambda: on_cluster(study, 2, tmp / "two.parquet"),
    }
    t = interleaved(args.repeat, runs)
    serial, one, two = t["plain loop"], t["1 worker"], t["2 workers"]
    print(
        f"end to end, 1 worker, {n:,} analyses written to Parquet: static {one:.3g} s against {serial:.3g} s for the "
        f"analyses alone in a plain loop: {1e3 * (one - serial) / n:+.2g} ms an analysis ({100 * (one - serial) / serial:+.2g} %)",
        flush=True,
    )
    print(
        f"{n:,} analyses of wall 1: static 1 worker {one:.3g} s, 2 workers {two:.3g} s: {one / two:.3g} x", flush=True
    )
    print(f"the example (1,000 samples), command line end to end: {example_end_to_end(tmp):.3g} s")


if __name__ == "__main__":
    main()
