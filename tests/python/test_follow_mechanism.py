"""Limit analysis along the mechanism from Python and from case files (``Model.solve_limit(follow_mechanism=True)``,
``Model3D.solve_limit(...)``, ``[analysis] follow_mechanism``, docs/case-format.md): the rocking portal frame's
capacity curve, in the plane and built of boxes in 3D, against its closed form lambda(theta) = tan(alpha - theta)
(docs/references.md, section 1), the result file's curve and note, the report's lines, the 3D report page's curve,
and the refusals of the keys, one line each."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem.case.result_file import result_dict
from masonry_dem.report import summary

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
FRAME = EXAMPLES / "rocking-portal-frame.toml"
FRAME_3D = EXAMPLES / "rocking-portal-frame-3d.toml"  # the same frame of boxes
B, H = 0.4, 2.0  # the frame's columns [m]
ALPHA = math.atan(B / H)


def rotation_of(d: float, b: float, h: float) -> float:
    """The rotation theta of a block b x h about its toe that moves its centroid by d along x:
    d = b/2 (1 - cos theta) + h/2 sin theta, increasing on [0, pi/2], inverted by bisection."""
    lo, hi = 0.0, math.pi / 2
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if 0.5 * b * (1 - math.cos(mid)) + 0.5 * h * math.sin(mid) > d else (mid, hi)
    return 0.5 * (lo + hi)


def test_the_example_follows_the_rocking_frame_to_zero() -> None:
    case = md.load_case(FRAME)
    model = case.build_model()
    r = case.solve(model)
    assert r.status == "collapse" and r.error is None
    assert r.collapse_multiplier == pytest.approx(B / H, abs=1e-9)
    lam = np.asarray(r.curve_multiplier)
    d = np.asarray(r.curve_displacement)
    assert len(lam) >= 11 and r.steps == len(lam) - 1
    # the control block: a column's centroid, or the lintel's, which moves as a column's top inner corner
    lintel = r.control_block == 2
    theta = [rotation_of(x, 2 * B if lintel else B, 2 * H if lintel else H) for x in d]
    np.testing.assert_allclose(lam, np.tan(ALPHA - np.asarray(theta)), rtol=0, atol=1e-6)
    assert lam[-1] <= 1e-3 * lam[0] and theta[-1] == pytest.approx(ALPHA, abs=1e-3)
    # the finite motion at the curve's end: both columns turned clockwise by theta, the lintel translated
    disp = np.asarray(r.displacements)
    np.testing.assert_allclose(disp[:2, 2], -theta[-1], atol=1e-6)
    assert abs(disp[2, 2]) < 1e-6
    # the same run from Python, keyword for key: the same numbers to the last digit
    same = model.solve_limit(follow_mechanism=True, follow_step=0.02)
    assert list(same.curve_multiplier) == list(r.curve_multiplier)
    assert list(same.curve_displacement) == list(r.curve_displacement)
    # the result file's curve is the Results', and no note: the curve reached zero
    out = result_dict(r, model, case.title)
    assert out["curve"]["multiplier"] == list(lam) and out["curve"]["displacement"] == list(d)
    assert "note" not in out and out["status"] == "collapse"


@pytest.mark.parametrize("example", [FRAME, FRAME_3D], ids=["plane", "3d"])
def test_a_curve_that_stops_short_says_why(example: Path) -> None:
    case = md.parse_case(example.read_text().replace("# follow_steps = 1000", "follow_steps = 3"), source="frame.toml")
    model = case.build_model()
    r = case.solve(model)
    assert r.status == "collapse" and r.steps == 3 and len(r.curve_multiplier) == 4
    assert "the steps ran out (follow_steps = 3) before lambda reached zero" in r.error
    out = result_dict(r, model, case.title)
    assert out["note"] == r.error and "error" not in out
    text = summary(case.title, model, r)
    assert "along the mechanism: λ from 0.2000 to" in text and "in 3 steps" in text
    assert f"stopped short:       {r.error}" in text


def test_without_the_keyword_the_curve_stays_empty() -> None:
    model = md.load_case(FRAME).build_model()
    r = model.solve_limit()
    assert len(r.curve_multiplier) == 0 and r.steps == 0


@pytest.mark.parametrize(
    "analysis, key, message",
    [
        ('method = "limit"\nfollow_step = 0.02', "follow_step", "needs follow_mechanism = true"),
        ('method = "limit"\nfollow_steps = 5', "follow_steps", "needs follow_mechanism = true"),
        ('method = "limit"\nfollow_mechanism = 1', "follow_mechanism", "expected true or false"),
        ('method = "limit"\nfollow_mechanism = true\nfollow_step = -0.1', "follow_step", "-0.1"),
        ('method = "limit"\nfollow_mechanism = true\nfollow_steps = 0', "follow_steps", ">= 1"),
        ('method = "limit"\nfollow_mechanism = true\nfollow_steps = 1000000', "follow_steps", "<= 100000"),
    ],
)
def test_the_keys_are_refused_by_name(analysis: str, key: str, message: str) -> None:
    text = FRAME.read_text().split("[analysis]")[0] + "[analysis]\n" + analysis + "\n"
    with pytest.raises(md.InputError) as info:
        md.parse_case(text, source="frame.toml")
    line = str(info.value)
    assert "\n" not in line and line.startswith("frame.toml: ") and f"analysis.{key}" in line and message in line, line


def test_the_3d_example_follows_the_rocking_frame_of_boxes_to_zero(tmp_path: Path) -> None:
    case = md.load_case(FRAME_3D)
    model = case.build_model()
    r = case.solve(model)
    assert r.dimension == 3 and r.status == "collapse" and r.error is None
    assert r.collapse_multiplier == pytest.approx(B / H, abs=1e-7)
    lam = np.asarray(r.curve_multiplier)
    d = np.asarray(r.curve_displacement)
    assert len(lam) >= 11 and r.steps == len(lam) - 1
    # the control block is the lintel (the highest wall block): it moves as the columns' top inner edges, along x
    assert r.control_block == 2
    theta = np.asarray([rotation_of(x, 2 * B, 2 * H) for x in d])
    np.testing.assert_allclose(lam, np.tan(ALPHA - theta), rtol=0, atol=1e-6)
    assert lam[-1] <= 1e-3 * lam[0] and theta[-1] == pytest.approx(ALPHA, abs=1e-3)
    # the finite motion at the curve's end: both columns turned by theta about +y (towards +x), the lintel not turned
    disp = np.asarray(r.displacements)
    assert disp.shape == (model.n_blocks + 1, 6)  # the wall's blocks and the base, at rest
    np.testing.assert_allclose(disp[:2, 3:], [[0.0, theta[-1], 0.0]] * 2, atol=1e-6)
    np.testing.assert_allclose(disp[2, 3:], 0.0, atol=1e-6)
    # the same run from Python, keyword for key: the same numbers to the last digit
    same = model.solve_limit(follow_mechanism=True, follow_step=0.02)
    assert list(same.curve_multiplier) == list(r.curve_multiplier)
    assert list(same.curve_displacement) == list(r.curve_displacement)
    # the result file's curve is the Results', and no note: the curve reached zero
    out = result_dict(r, model, case.title)
    assert out["curve"]["multiplier"] == list(lam) and out["curve"]["displacement"] == list(d)
    assert "note" not in out and out["status"] == "collapse" and out["dimension"] == 3
    # the report's line, and the report page's curve: lambda against the control block's displacement along the load
    text = summary(case.title, model, r)
    assert "along the mechanism: λ from 0.2000 to" in text and f"in {r.steps} steps" in text
    from masonry_dem.space.plot import report_figure_3d

    fig = report_figure_3d(model, r, title=case.title, path=tmp_path / "frame.png")
    curve = next(ax for ax in fig.axes if ax.get_xlabel().startswith("displacement of the control block"))
    assert curve.get_xlabel() == "displacement of the control block along the load, towards +x (0°) [mm]"
    drawn = curve.lines[0]
    np.testing.assert_allclose(drawn.get_xdata(), d * 1e3)
    np.testing.assert_allclose(drawn.get_ydata(), lam)
    assert (tmp_path / "frame.png").stat().st_size > 0


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(follow_step=0.1), "follow_step and follow_steps are options of follow_mechanism=True"),
        (dict(follow_mechanism=True, follow_step=-1.0), "follow_step must be a length > 0 m"),
        (dict(follow_mechanism=True, follow_steps=0), "follow_steps must be at least 1"),
        (dict(follow_mechanism=True, along_gravity=True), "not with along_gravity=True"),
    ],
)
def test_the_3d_keywords_are_refused(kwargs: dict, message: str) -> None:
    model = md.load_case(FRAME_3D).build_model()
    with pytest.raises(md.InputError, match=message) as info:
        model.solve_limit(**kwargs)
    assert "\n" not in str(info.value)


def test_the_3d_keys_are_refused_by_name() -> None:
    text = FRAME_3D.read_text().replace("follow_mechanism = true ", "follow_mechanism = false")
    with pytest.raises(md.InputError) as info:
        md.parse_case(text, source="frame3d.toml")
    line = str(info.value)
    assert "\n" not in line and "analysis.follow_step" in line and "needs follow_mechanism = true" in line, line


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(follow_step=0.1), "follow_step and follow_steps are options of follow_mechanism=True"),
        (dict(follow_mechanism=True, follow_step=0.0), "follow_step must be a length > 0 m"),
        (dict(follow_mechanism=True, follow_step=math.nan), "follow_step must be a length > 0 m"),
        (dict(follow_mechanism=True, follow_steps=0), "follow_steps must be at least 1"),
        (dict(follow_mechanism=True, follow_steps=md._core.MAX_FOLLOW_STEPS + 1), "follow_steps must be at most"),
    ],
)
def test_the_keywords_are_refused(kwargs: dict, message: str) -> None:
    model = md.load_case(FRAME).build_model()
    with pytest.raises(md.InputError, match=message):
        model.solve_limit(**kwargs)
