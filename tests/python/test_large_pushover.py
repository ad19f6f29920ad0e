"""The explicit solver's pushover with finite rotations (``[analysis] large_rotations``, ``contact_update``;
``Model.solve_dynamic(large_rotations=, contact_update=)``, docs/case-format.md, keys of the explicit solver): one
block pushed at its centroid under displacement control rocks about its toe, and its curve on the moved geometry
follows lambda(theta) = tan(alpha - theta) (docs/references.md, section 1) within 2%; the keys refused by name."""

from __future__ import annotations

import math

import numpy as np
import pytest

import masonry_dem as md
from test_follow_mechanism import rotation_of  # the rotation about the toe that moves the centroid by d

B, H = 0.4, 1.0  # the block [m]
ALPHA = math.atan(B / H)

# one dry block (no dilatancy: a rocking toe does not lift) on a fixed base, driven to theta = 0.9 alpha
THETA_END = 0.9 * ALPHA
D_END = 0.5 * B * (1 - math.cos(THETA_END)) + 0.5 * H * math.sin(THETA_END)
CASE = f"""
format = 1
title = "One block rocking about its toe"
[geometry]
thickness = 1.0
density = 2000.0
blocks = [[0.0, 0.0, {B}, {H}]]
[base]
kind = "fixed"
[joints]
normal_stiffness = 1e10
shear_stiffness = 1e10
friction = 5.0
dilatancy = 0.0
[loads]
gravity = 9.81
live = "horizontal_weight"
[analysis]
method = "dynamic"
control = "displacement"
max_displacement = {D_END!r}
steps = 200
large_rotations = true
"""


def test_the_block_follows_tan_alpha_minus_theta_from_the_case_file() -> None:
    case = md.parse_case(CASE, source="block.toml")
    model = case.build_model()
    r = case.solve(model)
    lam = np.asarray(r.curve_multiplier)[1:]
    d = np.asarray(r.curve_displacement)[1:]
    assert len(lam) == 200
    exact = np.tan(ALPHA - np.array([rotation_of(x, B, H) for x in d]))
    assert np.max(np.abs(lam - exact) / exact) < 0.02
    # the block's own rotation at the end, clockwise, within 1% of the rotation its centroid's travel gives
    assert -r.displacements[0][2] == pytest.approx(THETA_END, rel=0.01)
    # the same run from Python, keyword for key
    same = model.solve_dynamic(control="displacement", max_displacement=D_END, steps=200, large_rotations=True)
    assert list(same.curve_multiplier) == list(r.curve_multiplier)


def test_contact_update_needs_large_rotations() -> None:
    model = md.parse_case(CASE, source="block.toml").build_model()
    with pytest.raises(md.InputError, match="contact_update needs analysis.large_rotations = true"):
        model.solve_dynamic(contact_update=True)
    with pytest.raises(md.InputError, match='contact_update needs analysis.control = "displacement"'):
        model.solve_dynamic(large_rotations=True, contact_update=True)
    text = CASE.replace("large_rotations = true", "large_rotations = false\ncontact_update = true")
    case = md.parse_case(text, source="block.toml")
    with pytest.raises(md.InputError) as info:
        case.solve(case.build_model())
    assert "\n" not in str(info.value) and "analysis.contact_update" in str(info.value)


@pytest.mark.parametrize("key", ["large_rotations", "contact_update"])
def test_the_keys_must_be_booleans(key: str) -> None:
    text = CASE.replace("large_rotations = true", f"{key} = 1")
    with pytest.raises(md.InputError) as info:
        md.parse_case(text, source="block.toml")
    line = str(info.value)
    assert "\n" not in line and f"analysis.{key}" in line and "expected true or false" in line, line


@pytest.mark.parametrize("key", ["large_rotations", "contact_update"])
def test_a_3d_pushover_refuses_them(key: str) -> None:
    model = md.Model3D(boxes=[[0.0, 0.0, 0.0, 0.4, 0.4, 1.0]])
    with pytest.raises(md.InputError, match=f"analysis.{key}: the pushovers of 3D models are on the wall as built"):
        model.solve_dynamic(**{key: True})
