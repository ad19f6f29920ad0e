"""Limit analysis on walls of dry associative joints: the static solver and `Model.solve_limit` against a linear program.

With dilatancy equal to friction the joints are associative and the static theorem of limit analysis gives the exact
collapse multiplier: the optimum of a linear program (benches/limit_analysis.py, solved by SciPy's HiGHS), written
from the model's blocks and interfaces alone, independently of the solvers.

The static solver: every converged state is an equilibrium within the strength domain, so its multiplier cannot
exceed the optimum (up to the two solvers' round-off, 1e-9 here); from below it must reach the exact value within the
tolerance of the reference tests for exact values (test_reference.py: 0.5%). The walls: Ferris & Tin-Loi's wall 1
and running-bond walls of other slenderness, friction, bond and with an opening, 33 to 105 blocks.

`Model.solve_limit` solves the same program (its own interior point in the core): its multiplier must equal HiGHS's
to 1e-6 relative, and never exceed it by more than 1e-6 (above the optimum would not be an equilibrium within the
domain), with status "collapse", on Ferris & Tin-Loi's walls 1 to 6 and on 19 seeded random walls of 10 to 500 blocks
(benches/limit_analysis.py's `random_wall`, seeds 1 to 19); on the random walls that cannot stand (HiGHS: infeasible;
seeds 0 and 263) its status must be "no_equilibrium".

Ferris & Tin-Loi's walls (Int. J. Mech. Sci. 43, 2001, 209-224): 1 and 2 are the case files of examples/. The
geometry of 3 to 6 is taken from the public re-run of the six walls in HybriDFEM (github.com/thlgrs/HybriDFEM-3.1,
Legacy/Examples/F&TL Walls (WCEE 2024)/Lin_Geom/Ferris&Tin-Loi_Wall3..6/Pushover_F&TL-*.py), courses of whole and
half blocks (0.4 x 0.175 m) and openings one block wide; wall 6 has 146 blocks, as the paper's widest wall is
described. The paper itself was not available to check them against.
"""

import importlib.util
import math
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


# Ferris & Tin-Loi walls 3 to 6 as courses of md.pattern (bottom to top; lengths in block lengths, negative: a gap)
_W3 = {"e": [1, 1, 1, 1], "u": [0.5, 1, 1, 1, 0.5], "we": [1, 0.5, -1, 0.5, 1], "wu": [0.5, 1, -1, 1, 0.5]}
_W4 = {"e": [0.5, 1, 1, 1, 1, 0.5], "u": [1] * 5, "we": [0.5, 0.5, -1, 0.5, 0.5, -1, 0.5, 0.5], "wu": [1, -1, 1, -1, 1]}
_W5 = {"e": [0.5, 1, 1, 0.5], "u": [1] * 3, "we": [0.5, 0.5, -1, 0.5, 0.5], "wu": [1, -1, 1]}
_W6 = {"e": [0.5] + [1] * 6 + [0.5], "u": [1] * 7, "we": [1, 0.5, -1, 0.5, 1, 0.5, -1, 0.5, 1],
       "wu": [0.5, 1, -1, 1, 1, -1, 1, 0.5]}
_WINDOW = ["wu", "we", "wu", "we", "wu"]
FERRIS_TINLOI_PATTERNS = {
    # wall: (courses, block count)
    3: ([_W3[c] for c in ["e", "u", "e", "wu", "we", "wu", "we", "wu", "e", "u", "e"]], 46),
    4: ([_W4[c] for c in ["e", "u", "e", "wu", "we", "wu", "we", "wu", "e", "u", "e"]], 55),
    5: ([_W5[c] for c in ["e", "u", "e", *_WINDOW, "e", "u", "e", *_WINDOW, "e", "u", "e"]], 61),
    6: ([_W6[c] for c in ["e", "u", "e", "u", *_WINDOW, "u", "e", "u", *_WINDOW, "u", "e", "u", "e"]], 146),
}
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def ferris_tinloi_wall(number):
    """Ferris & Tin-Loi's wall `number` (1 to 6), mu = 0.65, associative (dilatancy = friction)."""
    if number in (1, 2):
        case = md.load_case(EXAMPLES / f"ferris-tinloi-wall{number}.toml")
        kwargs = dict(case.model_kwargs)
        joints = {family: dict(law) for family, law in kwargs["joints"].items()}
        for law in joints.values():
            if "friction" in law:
                law["dilatancy"] = law["friction"]
        kwargs["joints"] = joints
        model = md.Model(**kwargs)
        return model, joints["default"]["friction"]
    rows, n_blocks = FERRIS_TINLOI_PATTERNS[number]
    blocks = md.pattern(0.4, 0.175, rows)
    assert len(blocks) == n_blocks
    return md.Model(blocks, gravity=10.0, joints={"default": {"friction": 0.65, "dilatancy": 0.65}}), 0.65


def check_limit_against_lp(model, mu):
    exact, message = limit_analysis.collapse_multiplier(model, mu)
    assert exact > 0.0, message  # NaN (no optimum) fails too
    res = model.solve_limit()
    assert res.status == "collapse", res.error
    lam = res.collapse_multiplier
    assert isinstance(res.certificate, dict)
    assert lam <= exact * (1.0 + 1e-6), f"{model.n_blocks} blocks: {lam} above the limit load {exact}"
    assert abs(lam - exact) <= 1e-6 * exact, f"{model.n_blocks} blocks: {lam} against the limit load {exact}"


def test_rounding_after_a_near_optimum_is_not_called_unbounded():
    """One block sliding on its base at lambda = mu (examples/single-block-sliding.toml with this friction): near
    its optimum the normal matrix is singular to rounding, and the iterations after a near-optimal one once sent
    lambda to 1e13, said "unbounded". The near-optimal iterate stands, and its certificate says how near."""
    mu = 0.39758711488893983
    case = md.load_case(Path(__file__).resolve().parents[2] / "examples" / "single-block-sliding.toml")
    kwargs = dict(case.model_kwargs)
    kwargs["joints"] = {"default": {**kwargs["joints"]["default"], "friction": mu, "dilatancy": mu}}
    res = md.Model(**kwargs).solve_limit()
    assert res.status == "collapse", res.error
    assert abs(res.collapse_multiplier - mu) <= 1e-6 * mu


@pytest.mark.parametrize("number", [1, 2, 3, 4, 5, 6])
def test_solve_limit_on_ferris_tinloi_walls(number):
    check_limit_against_lp(*ferris_tinloi_wall(number))


@pytest.mark.parametrize("seed", range(1, 21))
def test_solve_limit_on_random_walls(seed):
    check_limit_against_lp(*limit_analysis.random_wall(seed))


# seed 263: a lintel course of 0.3 m blocks over a 0.7 m opening, friction 0.35, too weakly held by its ends;
# seed 0: a 1.04 m opening (2.1 blocks of 0.49 m) three courses under the top, friction 0.32 (since openings cut
# the blocks at their edges its jambs are straight; whole-block removal left corbelled jambs that held it)
@pytest.mark.parametrize("seed", [0, 263])
def test_solve_limit_on_a_random_wall_that_cannot_stand(seed):
    model, mu = limit_analysis.random_wall(seed)
    exact, message = limit_analysis.collapse_multiplier(model, mu)
    assert "infeasible" in message.lower(), (exact, message)
    assert model.solve_limit().status == "no_equilibrium"


def ferris_tinloi_wall_non_associative(number):
    """Ferris & Tin-Loi's wall `number` (1 to 6), mu = 0.65, dilatancy 0."""
    model, _ = ferris_tinloi_wall(number)
    if number in (1, 2):
        case = md.load_case(EXAMPLES / f"ferris-tinloi-wall{number}.toml")
        kwargs = dict(case.model_kwargs)
        kwargs["joints"] = {f: dict(law, dilatancy=0.0) if "friction" in law else dict(law)
                            for f, law in kwargs["joints"].items()}
        return md.Model(**kwargs)
    rows, _ = FERRIS_TINLOI_PATTERNS[number]
    return md.Model(md.pattern(0.4, 0.175, rows), gravity=10.0, joints={"default": {"friction": 0.65, "dilatancy": 0.0}})


@pytest.mark.parametrize("number", [1, 2, 3, 4, 5, 6])
def test_non_associative_limit_analysis_is_an_estimate(number):
    """With dilatancy 0 the sequence's number is a heuristic (on walls 3 to 6 it lies 2% to 18% above the static
    solver's collapse, converged or not): status "estimate", never "collapse", its value in last_equilibrium, the
    associative bound and the sequence's convergence in the certificate."""
    res = ferris_tinloi_wall_non_associative(number).solve_limit()
    assert res.status == "estimate", res.error
    assert math.isnan(res.collapse_multiplier)
    cert = res.certificate
    assert cert["multiplier"] == res.last_equilibrium > 0.0
    # each program's multiplier is known to the interior point's tolerance, 1e-8 of 1 + lambda (its duality gap)
    assert res.last_equilibrium <= cert["upper_bound"] + 2e-8 * (1.0 + cert["upper_bound"])
    assert isinstance(cert["sequence_converged"], bool) and cert["sequence"] >= 1
    assert ("not converged" in res.error) != cert["sequence_converged"]
    assert f"{cert['upper_bound']:.6f}" in res.error and "neither a lower nor an upper bound" in res.error
    data = md.result_dict(res, ferris_tinloi_wall_non_associative(number), "wall")
    assert data["status"] == "estimate" and data["collapse_multiplier"] is None and data["note"] == res.error


# seeds of limit_analysis.random_wall whose explicit run takes a second or less
@pytest.mark.parametrize("seed", [3, 5])
def test_explicit_collapse_is_never_above_limit_analysis(seed):
    """On dry associative joints the explicit collapse multiplier is the highest level that settled, at or below
    the exact (limit-analysis) multiplier, and its bracket holds that level and the lowest one that ran away."""
    model, _ = limit_analysis.random_wall(seed)
    exact = model.solve_limit()
    res = model.solve_dynamic(threads=1)
    assert exact.status == res.status == "collapse", res.error
    assert res.collapse_multiplier <= exact.collapse_multiplier
    low, high = res.bracket
    assert low == res.collapse_multiplier == max(res.curve_multiplier) and high > low
