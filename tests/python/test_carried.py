"""Loads carried by blocks from Python and case files (``Model(carried=...)``, ``Model3D(carried=...)``,
``[[loads.carried]]``): the facade of the shared benchmark's hand check (section 4: a wall of 100 kN, t = 0.5 m,
h = 6 m, with a floor's 20 kN at its top 0.25 m from the hinge) turns at alpha0 = 30 / 420 by limit analysis in
the plane and in 3D, and its linear kinematic check takes the floor as a weight of its own at its point: M* g =
420^2 / 1620 kN, e* = M* g / 120 kN, a0* = alpha0 g / (e* FC), each to 1e-9; the same wall in two courses, the floor
on the upper one, by the linear check and the nonlinear one (theta0 where the weights' centroid stands over the
hinge); the keys' refusals name the key."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem import assessment as sa
from masonry_dem.case import load_case

G = 9.81
T, H = 0.5, 6.0
DENSITY = 100e3 / (T * H * G)  # a wall of 100 kN, 1 m long
ALPHA0 = 30.0 / 420.0  # (100 x 0.25 + 20 x 0.25) / (100 x 3 + 20 x 6)
JOINTS = {"default": {"friction": 2.0, "dilatancy": 2.0}}


def close(value: float, expected: float, tol: float) -> bool:
    return abs(value - expected) <= tol * abs(expected)


def facade_2d() -> Any:
    return md.Model([[0.0, 0.0, T, H]], density=DENSITY, gravity=G, joints=JOINTS, carried=[(0, [0.25, H], 20e3)])


def facade_3d(y: float = 0.5) -> Any:
    return md.Model3D([[0.0, 0.0, 0.0, T, 1.0, H]], density=DENSITY, gravity=G, joints=JOINTS,
                      carried=[(0, [0.25, y, H], 20e3)])


def _check_hand_values(model: Any) -> None:
    results = model.solve_limit(tolerance=1e-11)
    site = sa.AssessmentParameters(spectrum=sa.ec8_spectrum(0.25 * 9.80665, "B"), confidence_factor=1.35)
    check = sa.linear_check(model, results, site, gravity=G)
    # the hand check's sums: sum P_i dx_i = 100 x 3 + 20 x 6 = 420 and sum P_i dx_i^2 = 100 x 9 + 20 x 36 = 1620
    # [kN m, kN m2] per unit rotation about the hinge
    mstar_g = 420e3**2 / 1620e3
    e_star = mstar_g / 120e3
    assert close(check.alpha0, ALPHA0, 1e-9), check.alpha0
    assert close(check.participating_mass * G, mstar_g, 1e-9), check.participating_mass * G
    assert close(check.mass_fraction, e_star, 1e-9), check.mass_fraction
    assert close(check.a0_star, ALPHA0 * G / (e_star * 1.35), 1e-9), check.a0_star
    assert round(check.participating_mass * G / 1e3, 2) == 108.89 and round(check.mass_fraction, 4) == 0.9074
    assert round(check.a0_star, 4) == 0.5720
    assert check.moving_blocks == 1 and close(check.weight, 120e3, 1e-12)
    print(f"facade {model.dimension}D: alpha0 {check.alpha0:.12f}, M* g {check.participating_mass * G:.6f} N, "
          f"e* {check.mass_fraction:.12f}, a0* {check.a0_star:.12f} m/s2")


def test_the_facade_with_its_floor_in_the_plane() -> None:
    model = facade_2d()
    assert model.carried == [(0, [0.25, H], 20e3)]
    assert close(float(model.weights[0]), 120e3, 1e-12)
    # the centroid, where the dofs are, is the centre of mass of wall and floor
    assert close(float(model.centroids[0][1]), (100 * 3.0 + 20 * 6.0) / 120, 1e-12)
    _check_hand_values(model)


def test_the_facade_in_two_courses_with_its_floor_on_the_upper_one() -> None:
    # the wall in two courses of 50 kN (centroids at 1.5 and 4.5 m), the floor on the upper: the whole turns about
    # the toe (the upper course alone at (50 x 0.25 + 20 x 0.25) / (50 x 1.5 + 20 x 3) = 0.13), alpha0 = 30 / 420;
    # sum P_i dx_i = 50 x 1.5 + 50 x 4.5 + 20 x 6 = 420, sum P_i dx_i^2 = 50 x 1.5^2 + 50 x 4.5^2 + 20 x 6^2 = 1845
    model = md.Model([[0.0, 0.0, T, 3.0], [0.0, 3.0, T, H]], density=DENSITY, gravity=G, joints=JOINTS,
                     carried=[(1, [0.25, H], 20e3)])
    results = model.solve_limit(tolerance=1e-11)
    site = sa.AssessmentParameters(spectrum=sa.ec8_spectrum(0.25 * 9.80665, "B"))
    check = sa.linear_check(model, results, site, gravity=G)
    assert close(check.alpha0, ALPHA0, 1e-9) and check.moving_blocks == 2
    assert close(check.participating_mass * G, 420e3**2 / 1845e3, 1e-9), check.participating_mass * G
    # the nonlinear check: the weights' centroid G stands over the hinge (0.5, 0) at theta0 = atan(0.25 / 3.5), all
    # weights 0.25 m from it, G at (50 x 1.5 + 50 x 4.5 + 20 x 6) / 120 = 3.5 m
    nonlinear = sa.nonlinear_check(model, results, site, gravity=G)
    assert close(nonlinear.theta0, math.atan2(0.25, 3.5), 1e-9), nonlinear.theta0


@pytest.mark.parametrize("y", [0.5, 0.2])
def test_the_facade_with_its_floor_in_3d(y: float) -> None:
    model = facade_3d(y)
    assert close(float(model.weights[0]), 120e3, 1e-12)
    _check_hand_values(model)


def test_a_3d_time_history_takes_a_load_off_the_axes_of_its_box() -> None:
    # off the box's axes the load gives the box products of inertia, about whose principal axes the time history
    # turns it; over the box's centre the box's axes stay principal: both run
    assert facade_3d(0.2).simulate(0.01).error is None
    assert facade_3d(0.5).simulate(0.01).error is None


CASE_2D = """
format = 1

[geometry]
thickness = 1.0
density = {density}
blocks = [[0.0, 0.0, 0.5, 6.0]]

[joints]
friction = 2.0
dilatancy = 2.0

[loads]
gravity = 9.81
{carried}

[analysis]
method = "limit"
"""

FLOOR = '[[loads.carried]]\nblock = 0\npoint = ["250 mm", 6.0]\nweight = "20 kN"\n'


def _case(tmp_path: Path, carried: str) -> Path:
    path = tmp_path / "facade.toml"
    path.write_text(CASE_2D.format(density=DENSITY, carried=carried))
    return path


def test_a_case_file_reads_the_carried_loads(tmp_path: Path) -> None:
    case = load_case(_case(tmp_path, FLOOR))
    assert case.model.carried == [(0, [0.25, 6.0], 20e3)]
    r = case.build_model().solve_limit(tolerance=1e-11)
    assert close(r.collapse_multiplier, ALPHA0, 1e-9)


def test_a_3d_case_file_reads_the_carried_loads(tmp_path: Path) -> None:
    path = tmp_path / "facade3d.toml"
    path.write_text(f"""
format = 1

[geometry]
density = {DENSITY}
boxes = [[0.0, 0.0, 0.0, 0.5, 1.0, 6.0]]

[joints]
friction = 2.0
dilatancy = 2.0

[loads]
gravity = 9.81

[[loads.carried]]
block = 0
point = [0.25, 0.5, 6.0]
weight = 20e3
""")
    case = load_case(path)
    assert case.model.carried == [(0, [0.25, 0.5, 6.0], 20e3)]
    r = case.build_model().solve_limit(tolerance=1e-11)
    assert close(r.collapse_multiplier, ALPHA0, 1e-9)


@pytest.mark.parametrize("carried, key, words", [
    ('[[loads.carried]]\nblock = 0\npoint = [0.25, 6.0]\n', "loads.carried[0].weight", "missing key 'weight'"),
    ('[[loads.carried]]\nblock = 0\npoint = [0.25, 6.0]\nweight = -1.0\n', "loads.carried[0].weight", ">= 0"),
    ('[[loads.carried]]\nblock = 0\npoint = [0.25, 6.0]\nweight = "2 m"\n', "loads.carried[0].weight", "force"),
    ('[[loads.carried]]\nblock = 0\npoint = [0.25]\nweight = 1.0\n', "loads.carried[0].point", "2 numbers"),
    ('[[loads.carried]]\nblock = -1\npoint = [0.25, 6.0]\nweight = 1.0\n', "loads.carried[0].block", ">= 0"),
    ('[[loads.carried]]\nblock = 0\npoint = [0.25, 6.0]\nweight = 1.0\nmass = false\n', "loads.carried[0].mass",
     "unknown key"),
    ('carried = [1.0]\n', "loads.carried[0]", "expected a table"),
])
def test_bad_keys_are_refused_by_name(tmp_path: Path, carried: str, key: str, words: str) -> None:
    path = tmp_path / "bad.toml"
    path.write_text(CASE_2D.format(density=DENSITY, carried=carried))
    with pytest.raises(md.InputError, match=words) as e:
        load_case(path)
    assert e.value.key == key


@pytest.mark.parametrize("load, words", [
    ((1, [0.25, 6.0], 1.0), "block 1 is not a wall block"),
    ((0, [0.25, 6.5], 1.0), "outside block 0"),
    ((0, [0.25, 6.0], float("nan")), "weight must be finite"),
])
def test_the_model_refuses_bad_loads_naming_the_load(load: Any, words: str) -> None:
    with pytest.raises(md.InputError, match=words) as e:
        md.Model([[0.0, 0.0, T, H]], carried=[(0, [0.1, 1.0], 1.0), load])
    assert e.value.key == "loads.carried[1]"
    with pytest.raises(md.InputError, match=r"carried\[0\]: expected"):
        md.Model([[0.0, 0.0, T, H]], carried=[(0, [0.1, 1.0, 2.0], 1.0)])
    with pytest.raises(md.InputError, match=r"carried\[0\]: expected"):
        md.Model3D([[0.0, 0.0, 0.0, T, 1.0, H]], carried=[(0, [0.1, 1.0], 1.0)])


def test_a_case_without_loads_is_unchanged(tmp_path: Path) -> None:
    case = load_case(_case(tmp_path, ""))
    assert case.model.carried is None and "carried" not in case.model.arguments()
    model = case.build_model()
    assert model.carried == [] and np.allclose(model.weights[0], 100e3, rtol=1e-12)
