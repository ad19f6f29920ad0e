"""The explicit solver's collapse multiplier against the exact one on seeded random walls of dry associative
joints (benches/limit_analysis.py's random_wall): the explicit multiplier is the highest load level that settled,
so it should never lie above the exact value.

    .venv/bin/python benches/explicit_vs_limit.py            # seeds 1 to 20, after `make develop`
    .venv/bin/python benches/explicit_vs_limit.py 3 5 12     # some seeds

The exact value is limit analysis's (Model.solve_limit); where its interior point gives no collapse, the linear
program solved by SciPy's HiGHS (limit_analysis.collapse_multiplier). Default options of the explicit solver (bracket
1e-3, unbalanced-force ratio 1e-5), one thread. A run that its check against limit analysis turns "stalled" (its
collapse more than 10 x the bracket below the exact value) has no collapse multiplier and is listed as such.
Prints one line per wall and the largest explicit - exact difference of the collapses."""

import importlib.util
import math
import sys
import time
from pathlib import Path

_spec = importlib.util.spec_from_file_location("limit_analysis", Path(__file__).resolve().parent / "limit_analysis.py")
limit_analysis = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(limit_analysis)


def main(seeds):
    worst = -math.inf
    for seed in seeds:
        model, mu = limit_analysis.random_wall(seed)
        lim = model.solve_limit()
        exact, source = lim.collapse_multiplier, "limit analysis"
        if lim.status != "collapse":
            exact, source = limit_analysis.collapse_multiplier(model, mu)[0], f"HiGHS (limit analysis {lim.status})"
        start = time.perf_counter()
        res = model.solve_dynamic(threads=1)
        elapsed = time.perf_counter() - start
        line = f"seed {seed:3d}, {model.n_blocks:4d} blocks: exact {exact:.7f} ({source}); explicit {res.status}"
        if res.status == "collapse":
            diff = res.collapse_multiplier - exact
            worst = max(worst, diff)
            low, high = res.bracket
            line += f" {res.collapse_multiplier:.7f}, bracket [{low:.7f}, {high:.7f}], explicit - exact {diff:+.2e}"
        else:
            line += f" ({' '.join((res.error or '').split())[:100]})"
        print(line + f"; {elapsed:.1f} s", flush=True)
    print(f"largest explicit - exact over the collapses: {worst:+.3e}")


if __name__ == "__main__":
    main([int(s) for s in sys.argv[1:]] or range(1, 21))
