"""The running-bond generator on a real wall: `height=` instead of a number of courses (the last course cut to
fit, a sliver of a course refused with the nearest fits), openings cut out of the blocks with exactly their area,
and the case file's `height` key."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem.case import load_case
from masonry_dem.study.model import Texture, texture_blocks

# 0.25 x 0.12 m blocks, a wall 4 m long; a 1.2 x 0.9 m window whose edges fall inside blocks (whole-block
# removal took 1.05 of its 1.08 m2)
WALL = dict(block_length=0.25, block_height=0.12, length=4.0)
WINDOW = [1.1, 0.9, 2.3, 1.8]


def area(blocks: np.ndarray) -> float:
    return float(np.sum((blocks[:, 2] - blocks[:, 0]) * (blocks[:, 3] - blocks[:, 1])))


def test_height_gives_the_wall_asked_for() -> None:
    blocks = md.running_bond(**WALL, height=2.5)
    assert blocks[:, 3].max() == 2.5  # not 2.52 (21 courses)
    last = blocks[blocks[:, 1] > 2.39]
    assert np.allclose(last[:, 3] - last[:, 1], 0.1, rtol=0, atol=1e-12)
    whole = md.running_bond(**WALL, courses=20)
    assert np.array_equal(blocks[: len(whole)], whole)
    assert area(blocks) == pytest.approx(4.0 * 2.5, rel=1e-12)
    # positional callers are unchanged
    assert np.array_equal(md.running_bond(0.4, 0.175, 6, 2.0), md.running_bond(0.4, 0.175, courses=6, length=2.0))


def test_a_sliver_of_a_course_is_refused_with_the_nearest_fits() -> None:
    with pytest.raises(md.InputError) as info:
        md.running_bond(**WALL, height=2.42)
    message = str(info.value)
    assert message.startswith("geometry.running_bond.height = 2.42 m"), message
    assert "use height = 2.4 m (20 courses) or 2.52 m (21 courses)" in message
    assert "block_height = 0.121 m (20 courses) or 0.115238 m (21 courses)" in message


@pytest.mark.parametrize(
    "arguments,words",
    [
        (dict(courses=6, height=2.5), "exactly one of courses and height"),
        (dict(), "exactly one of courses and height; neither"),
        (dict(height=-1.0), "geometry.running_bond.height"),
        (dict(courses=0), "geometry.running_bond.courses must be at least 1"),
    ],
)
def test_courses_and_height_are_checked(arguments: dict, words: str) -> None:
    with pytest.raises(md.InputError, match=words):
        md.running_bond(**WALL, **arguments)


def test_length_is_required() -> None:
    with pytest.raises(md.InputError, match="geometry.running_bond.length is required"):
        md.running_bond(0.25, 0.12, 6)


def test_a_window_removes_exactly_its_area() -> None:
    solid = md.running_bond(**WALL, height=2.5)
    blocks = md.running_bond(**WALL, height=2.5, openings=[WINDOW])
    assert area(solid) - area(blocks) == pytest.approx(1.2 * 0.9, rel=1e-9)
    x0, y0, x1, y1 = WINDOW
    inside_w = np.minimum(blocks[:, 2], x1) - np.maximum(blocks[:, 0], x0)
    inside_h = np.minimum(blocks[:, 3], y1) - np.maximum(blocks[:, 1], y0)
    assert np.all((inside_w <= 1e-12) | (inside_h <= 1e-12)), "a block reaches into the window"
    for x in (x0, x1):  # straight jambs: no block astride them
        astride = (blocks[:, 0] < x) & (blocks[:, 2] > x) & (blocks[:, 1] < y1 - 1e-9) & (blocks[:, 3] > y0 + 1e-9)
        assert not astride.any(), blocks[astride]
    model = md.Model(blocks, gravity=10.0, joints={"default": {"friction": 0.6, "dilatancy": 0.6}})
    result = model.solve_limit()
    assert result.status == "collapse" and np.isfinite(result.collapse_multiplier) and result.collapse_multiplier > 0


def test_a_texture_cuts_openings_as_the_case_does() -> None:
    rb = dict(WALL, courses=20, first_course="half", openings=[WINDOW])
    plain = np.array(texture_blocks(rb, Texture(), np.random.default_rng(0)))
    assert np.allclose(plain, md.running_bond(**rb))


CASE = """\
format = 1
title = "a real wall"

[geometry.running_bond]
block_length = 0.25
block_height = 0.12
length = 4.0
"""


def load(tmp_path: Path, text: str) -> md.Case:
    path = tmp_path / "case.toml"
    path.write_text(text, encoding="utf-8")
    return load_case(path)


def test_the_case_file_takes_a_height(tmp_path: Path) -> None:
    case = load(tmp_path, CASE + "height = 2.5\nopenings = [[1.1, 0.9, 2.3, 1.8]]\n")
    blocks = np.asarray(case.model.blocks)
    assert np.array_equal(blocks, md.running_bond(**WALL, height=2.5, openings=[WINDOW]))
    assert blocks[:, 3].max() == 2.5
    assert 4.0 * 2.5 - area(blocks) == pytest.approx(1.08, rel=1e-9)


@pytest.mark.parametrize(
    "extra,key,words",
    [
        ("courses = 20\nheight = 2.5\n", "geometry.running_bond.height", "height: give exactly one of courses and height; both"),
        ("", "geometry.running_bond.courses", "missing key 'courses' in [geometry.running_bond] (or height"),
        ("height = 0\n", "geometry.running_bond.height", "geometry.running_bond.height"),
        ("height = 'tall'\n", "geometry.running_bond.height", "geometry.running_bond.height"),
        ("height = 2.42\n", None, "use height = 2.4 m (20 courses) or 2.52 m (21 courses)"),
    ],
)
def test_the_case_file_height_key_is_checked(tmp_path: Path, extra: str, key: str, words: str) -> None:
    with pytest.raises(md.InputError) as info:
        load(tmp_path, CASE + extra)
    message = str(info.value)
    assert message.startswith(f"{tmp_path / 'case.toml'}: ") and words in message, message
    if key is not None:
        assert info.value.key == key
