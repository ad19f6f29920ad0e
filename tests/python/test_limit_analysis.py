"""The static solver's collapse multiplier against limit analysis, on walls of dry associative joints.

With dilatancy equal to friction the joints are associative and the static theorem of limit analysis gives the exact
collapse multiplier: the optimum of a linear program (benches/limit_analysis.py, solved by SciPy's HiGHS), written
from the model's blocks and interfaces alone, independently of the solvers. Every converged state of the static
solver is an equilibrium within the strength domain, so its multiplier cannot exceed the optimum (up to the two
solvers' round-off, 1e-9 here); from below it must reach the exact value within the tolerance of the reference tests
for exact values (test_reference.py: 0.5%). The walls: Ferris & Tin-Loi's wall 1 and running-bond walls of other
slenderness, friction, bond and with an opening, 33 to 105 blocks.
"""

import importlib.util
from pathlib import Path

import pytest

import masonry_dem as md

# the linear program of the benchmark script (it needs SciPy, which `make test` installs)
_spec = importlib.util.spec_from_file_location(
    "limit_analysis", Path(__file__).resolve().parents[2] / "benches" / "limit_analysis.py")
limit_analysis = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(limit_analysis)

# courses, length [m], first course, friction = dilatancy, openings (0.4 x 0.175 m blocks, g = 10)
WALLS = [
    (6, 2.0, "half", 0.65, None),  # Ferris & Tin-Loi's wall 1
    (8, 1.6, "full", 0.5, None),
    (4, 3.2, "half", 0.4, None),
    (12, 1.2, "full", 0.65, None),
    (10, 4.0, "half", 0.8, None),
    (8, 3.2, "half", 0.65, [[1.2, 0.35, 2.0, 1.05]]),
]


@pytest.mark.parametrize("courses,length,first,mu,openings", WALLS)
def test_static_collapse_is_the_limit_analysis_multiplier(courses, length, first, mu, openings):
    blocks = md.running_bond(0.4, 0.175, courses, length, first_course=first, openings=openings)
    model = md.Model(blocks, gravity=10.0, joints={"default": {"friction": mu, "dilatancy": mu}})
    exact, message = limit_analysis.collapse_multiplier(model, mu)
    assert exact > 0.0, message
    res = model.solve_static(control="load")
    assert res.status == "collapse", res.error
    lam = res.collapse_multiplier
    # the static theorem: an equilibrium within the domain is a lower bound
    assert lam <= exact * (1.0 + 1e-9), f"{model.n_blocks} blocks: {lam} above the limit load {exact}"
    assert lam >= exact * (1.0 - 0.005), f"{model.n_blocks} blocks: {lam} below the limit load {exact} by more than 0.5%"
