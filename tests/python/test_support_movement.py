"""A support's movement (``[analysis] move_support``, ``move_direction``; ``Model.solve_limit`` and ``solve_dynamic``'s
keywords; docs/case-format.md, "[analysis]"): the semicircular arch of examples/spreading-arch.toml on a spreading
abutment, from its case file, by limit analysis along the movement and by the explicit solver pushing the abutment;
the least thrust as built against the arch's line of thrust; the keys refused by name."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import masonry_dem as md

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "spreading-arch.toml"
R, T, N = 2.0, 0.3, 20  # the example's centreline radius [m], ring thickness [m] and voussoirs


def least_thrust(model: md.Model) -> float:
    """The least thrust of the arch as built, by its line of thrust, independent of the program: by symmetry the crown
    joint carries a horizontal force H, least at its extrados; the half arch above the joint at angle theta from the
    right springing turns about that joint's intrados point unless H (y_crown - y_j) >= sum W_i (x_j - x_i) over its
    voussoirs (those whose centroids lie above it); the least H is the largest of these over the joints."""
    ri, re = R - T / 2, R + T / 2
    c, w = np.asarray(model.centroids)[:N], np.asarray(model.weights)[:N]
    right = c[:, 0] > 0
    angle = np.arctan2(c[:, 1], c[:, 0])
    best = -math.inf
    for j in range(N // 2):
        theta = math.pi * j / N
        xj, yj = ri * math.cos(theta), ri * math.sin(theta)
        above = right & (angle > theta)
        best = max(best, float(np.sum(w[above] * (xj - c[above, 0]))) / (re - yj))
    return best


@pytest.fixture(scope="module")
def case() -> md.Case:
    return md.load_case(EXAMPLE)


@pytest.fixture(scope="module")
def limit(case: md.Case) -> md.Results:
    return case.solve(case.build_model(), "limit")


def test_limit_analysis_along_the_spread_from_the_case_file(case: md.Case, limit: md.Results) -> None:
    model = case.build_model()
    assert limit.status == "collapse", limit.error
    h_min = least_thrust(model)
    assert limit.collapse_multiplier == pytest.approx(h_min, rel=1e-6)
    assert limit.curve_multiplier[0] == pytest.approx(h_min, rel=1e-6)
    # three hinges, rocking: the crown's joint and the haunches'
    assert sum(1 for s in limit.interface_states if s) == 3
    d = np.asarray(limit.curve_displacement)
    assert np.all(np.diff(d) > 0)
    assert d[-1] == pytest.approx(0.2164, abs=5e-4)
    assert limit.control_block == model.support_indices[1]
    assert limit.last_equilibrium == limit.curve_multiplier[-1]


def test_the_explicit_solver_pushing_the_abutment_falls_at_the_same_spread(case: md.Case, limit: md.Results) -> None:
    r = case.solve(case.build_model(), "dynamic")
    assert r.status == "collapse", r.error
    below, above = r.bracket
    end = limit.curve_displacement[-1]
    assert abs(0.5 * (below + above) - end) <= 0.05 * end
    assert r.curve_displacement[-1] == below


def test_the_keys_of_a_movement_are_refused_by_name(case: md.Case) -> None:
    text = EXAMPLE.read_text()
    with pytest.raises(md.InputError, match="move_direction") as e:
        md.parse_case(text.replace('move_direction = "+x"', ""), source="a.toml")
    assert e.value.key == "analysis.move_support"
    with pytest.raises(md.InputError) as e:
        md.parse_case(text.replace('move_direction = "+x"', 'move_direction = "x"'), source="a.toml")
    assert e.value.key == "analysis.move_direction"
    with pytest.raises(md.InputError) as e:
        md.parse_case(text.replace('method = "limit"', 'method = "static"'), source="a.toml")
    assert e.value.key == "analysis.move_support"
    with pytest.raises(md.InputError) as e:
        case.check_method("static")
    assert e.value.key == "analysis.move_support"
    model = case.build_model()
    with pytest.raises(md.InputError, match="analysis.move_support"):
        model.solve_limit(move_support=2, move_direction="+x")
    with pytest.raises(md.InputError, match="move_direction"):
        model.solve_limit(move_support=1)
    with pytest.raises(md.InputError, match="max_displacement"):
        model.solve_dynamic(move_support=1, move_direction="+x")


def test_run_prints_the_spread_at_which_the_arch_falls(tmp_path: Path) -> None:
    png = tmp_path / "arch.png"
    out = subprocess.run([sys.executable, "-m", "masonry_dem", "run", str(EXAMPLE), "--plot", str(png)],
                         capture_output=True, text=True, check=True).stdout
    assert "falls at:            a movement of 0.2164 m" in out
    assert "hinges:              3:" in out
    assert png.stat().st_size > 0
