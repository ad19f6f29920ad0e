"""The time the linear kinematic check adds to a limit analysis of Ferris & Tin-Loi's wall 1 (33 blocks): the target
is under 1 ms. The check (masonry_dem.assessment.linear_check: the moving blocks, M*, e*, a0*, the demand at ground
level of an EN 1998-1 spectrum) is timed on the limit analysis's results, the best of many repeats, beside the
limit analysis itself. Then the nonlinear kinematic check (its capacity curve at finite rotation) of a mechanism of
1,000 blocks turning as one (a column of 1,000 blocks about its toe): the target is under 1 s.

    .venv/bin/python benches/assessment_checks.py [repeats]
"""

import sys
import time
from pathlib import Path

import masonry_dem as md
from masonry_dem import assessment

ROOT = Path(__file__).resolve().parents[1]


def best(run, repeats):
    """The shortest of ``repeats`` timings of ``run()`` [s]."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return min(times)


def main(repeats=200):
    case = md.load_case(ROOT / "examples" / "ferris-tinloi-wall1.toml")
    model = case.build_model()
    results = model.solve_limit()
    gravity = case.model_kwargs["gravity"]
    spectrum = assessment.ec8_spectrum(0.25 * 9.80665, "B")
    check = assessment.linear_check(model, results, spectrum, gravity=gravity)
    limit = best(model.solve_limit, max(5, repeats // 20))
    linear = best(lambda: assessment.linear_check(model, results, spectrum, gravity=gravity), repeats)
    print(f"wall 1: {model.n_blocks} blocks, alpha0 = {check.alpha0:.4f}, e* = {check.mass_fraction:.4f}, "
          f"a0* = {check.a0_star:.4f} m/s2, ratio {check.ratio:.3f} ({check.verdict})")
    print(f"limit analysis {limit * 1e3:.2f} ms; the linear check {linear * 1e3:.3f} ms (target < 1 ms: "
          f"{'met' if linear < 1e-3 else 'NOT met'})")
    column = md.Model([[0.0, 0.1 * i, 2.0, 0.1 * (i + 1)] for i in range(1000)], gravity=9.81,
                      joints={"default": md.dry_joint(1.0, dilatancy=1.0)})
    start = time.perf_counter()
    turning = column.solve_limit()
    solve = time.perf_counter() - start
    parameters = assessment.AssessmentParameters(spectrum=spectrum)
    nonlinear = best(lambda: assessment.nonlinear_check(column, turning, parameters, gravity=9.81), 5)
    check = assessment.nonlinear_check(column, turning, parameters, gravity=9.81)
    print(f"a column of 1,000 blocks turning about its toe: limit analysis {solve:.2f} s, theta_0 = {check.theta0:.4f} "
          f"rad; the nonlinear check {nonlinear * 1e3:.1f} ms (target < 1 s: {'met' if nonlinear < 1 else 'NOT met'})")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 200)
