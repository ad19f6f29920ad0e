"""Benchmarks of studies (masonry_dem.study) on Ferris & Tin-Loi wall 1 (33 blocks):

1. the per-analysis overhead of the study machinery, against the analysis itself:
   - in the worker: the row's time (``task_s``: the case table with the row's values, checking it, building the
     model, solving, the row) less the solver's own (``elapsed_s``), median over the rows;
   - end to end: a study of N analyses on one local worker (the cluster already up: Dask's scheduling, the
     tasks' data, the rows' Parquet parts and the final file included) against the same N analyses run in a
     plain loop in one process (``case.build_model(); case.solve(model)``);
2. N = 1,000 analyses of wall 1 on 2 local workers against 1 (the cluster already up; the friction drawn
   from N(0.65, 0.05), associative);
3. the example, examples/studies/wall1-fragility.toml (1,000 samples), end to end with the command line
   (cluster start, the rows, the Parquet file and the summary figure included).

    .venv/bin/python benches/study_scaling.py [--analyses 1000] [--repeat 2]

Each timing is the best of ``--repeat`` runs. On the project's machine (2 cores, shared; 2026-11-24):

    method  analysis [ms]  in-worker overhead [ms]  (% of the analysis)
    static  3.9            0.14                     (3.6 %)
    limit   0.70           0.12                     (17 %)
    end to end, 1 worker, 1,000 analyses: static 4.37 s against 4.19 s in a plain loop: +0.18 ms an analysis (4.3 %)
    1,000 analyses of wall 1: static 1 worker 4.38 s, 2 workers 2.31 s: 1.90 x
    the example (1,000 samples, static, 2 workers), command line end to end: 6.0 s

(Re-run it and replace these lines when the core or the study machinery changes.)
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


def best(repeat: int, run: Callable[[], Any]) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return min(times)


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


def on_workers(study: Any, workers: int, repeat: int, out: Path) -> float:
    """The study on a local cluster of ``workers`` processes, already up, its rows written to ``out``."""

    def run() -> None:
        out.unlink(missing_ok=True)
        run_study(study, out, scheduler=client)

    with connect(None, workers) as client:
        run()  # warm the workers (imports)
        return best(repeat, run)


def example_end_to_end(tmp: Path) -> float:
    out, plot = tmp / "example.parquet", tmp / "example.png"
    for p in (out, plot):
        p.unlink(missing_ok=True)
    command = [str(Path(sys.executable).parent / "masonry-dem"), "study", str(EXAMPLE), "--out", str(out), "--plot", str(plot), "-q"]
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--analyses", type=int, default=1000)
    parser.add_argument("--repeat", type=int, default=2)
    args = parser.parse_args()
    n = args.analyses
    tmp = ROOT / "out" / "bench-study"
    tmp.mkdir(parents=True, exist_ok=True)
    print("in the worker, per analysis (medians): the analysis (model and solver), the case from the study's data, the rest of the row")
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
    serial = best(args.repeat, lambda: plain_loop(cases, methods))
    one = on_workers(study, 1, args.repeat, tmp / "one.parquet")
    print(
        f"end to end, 1 worker, {n:,} analyses written to Parquet: static {one:.3g} s against {serial:.3g} s for the "
        f"analyses alone in a plain loop: {1e3 * (one - serial) / n:+.2g} ms an analysis ({100 * (one - serial) / serial:+.2g} %)",
        flush=True,
    )
    two = on_workers(study, 2, args.repeat, tmp / "two.parquet")
    print(f"{n:,} analyses of wall 1: static 1 worker {one:.3g} s, 2 workers {two:.3g} s: {one / two:.3g} x", flush=True)
    print(f"the example (1,000 samples), command line end to end: {example_end_to_end(tmp):.3g} s")


if __name__ == "__main__":
    main()
