"""The static solver's collapse multiplier against the exact one (limit analysis) on seeded random walls of dry
associative joints (benches/limit_analysis.py's random_wall), each with its openings cut (straight jambs) and, where
it has openings, toothed (the blocks whose centroid lies in an opening left out): the target is a collapse within
0.1% of the exact value on every wall of 50 to 500 blocks.

    .venv/bin/python benches/static_vs_limit.py            # the first 20 seeds from 1 of walls of 50-500 blocks
    .venv/bin/python benches/static_vs_limit.py 3 5 12     # some seeds

Default options of the static solver (load control along the live load's work, its continuation where Newton stops
converging below the bound). Prints one line per wall (walls outside 50-500 blocks are listed, not counted) and how
many of the counted walls collapse within 0.1%."""

import importlib.util
import sys
import time
from pathlib import Path

import numpy as np

_spec = importlib.util.spec_from_file_location("limit_analysis", Path(__file__).resolve().parent / "limit_analysis.py")
limit_analysis = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(limit_analysis)

TARGET = 1e-3


def default_seeds(count=20):
    """The first `count` seeds from 1 whose wall (openings cut) has 50 to 500 blocks."""
    seed = 0
    while count:
        seed += 1
        if 50 <= limit_analysis.random_wall(seed)[0].n_blocks <= 500:
            count -= 1
            yield seed


def main(seeds):
    counted, met = 0, 0
    for seed in seeds:
        cut, _ = limit_analysis.random_wall(seed)
        toothed, _ = limit_analysis.random_wall(seed, toothed=True)
        walls = [("cut", cut)]
        if not np.array_equal(toothed.rects, cut.rects):
            walls.append(("toothed", toothed))
        for kind, model in walls:
            lim = model.solve_limit()
            start = time.perf_counter()
            res = model.solve_static()
            elapsed = time.perf_counter() - start
            inside = 50 <= model.n_blocks <= 500
            line = f"seed {seed:3d} {kind:7s} {model.n_blocks:4d} blocks: exact {lim.collapse_multiplier:.7f}; static {res.status}"
            ok = False
            if res.status == "collapse":
                gap = (res.collapse_multiplier - lim.collapse_multiplier) / lim.collapse_multiplier
                # not above the exact value beyond its own accuracy (limit analysis's tolerance, 1e-8 of 1 + lambda)
                exact = lim.collapse_multiplier
                ok = exact * (1.0 - TARGET) <= res.collapse_multiplier <= exact + 1e-8 * (1.0 + exact)
                line += f" {res.collapse_multiplier:.7f} ({100 * gap:+.4f}%)"
            else:
                gap = (res.last_equilibrium - lim.collapse_multiplier) / lim.collapse_multiplier
                line += f" at {res.last_equilibrium:.7f} ({100 * gap:+.4f}%)"
            if inside:
                counted += 1
                met += ok
            print(line + f"; {elapsed:.2f} s" + ("" if inside else " (outside 50-500 blocks: not counted)"), flush=True)
    print(f"{met} of {counted} walls of 50-500 blocks collapse within {100 * TARGET:.1f}% of limit analysis")


if __name__ == "__main__":
    main([int(s) for s in sys.argv[1:]] or list(default_seeds()))
