"""Plots and the plain-text report (mechanism description)."""

from __future__ import annotations

import math
import re
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem.plot import interface_categories, plot_results
from masonry_dem.report import corner_motion, deformed_corners, describe_mechanism, format_multiplier, summary

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
PNG = b"\x89PNG\r\n\x1a\n"


def test_interface_categories() -> None:
    assert interface_categories([0, 1, 2, 4, 6, 3, 7]) == [
        "elastic",
        "open",
        "sliding",
        "rocking",
        "sliding + rocking",
        "open",
        "open",
    ]


def test_deformed_corners() -> None:
    rect = [0.0, 0.0, 2.0, 1.0]
    np.testing.assert_allclose(
        deformed_corners(rect, [0.1, 0.2, 0.0], 2.0), [[0.2, 0.4], [2.2, 0.4], [2.2, 1.4], [0.2, 1.4]]
    )
    # a quarter turn about the centroid (1, 0.5)
    np.testing.assert_allclose(
        deformed_corners(rect, [0.0, 0.0, math.pi / 2], 1.0),
        [[1.5, -0.5], [1.5, 1.5], [0.5, 1.5], [0.5, -0.5]],
        atol=1e-12,
    )


def test_corner_motion() -> None:
    rects = np.array([[0.0, 0.0, 2.0, 1.0]])
    assert corner_motion(rects, np.array([[0.3, 0.4, 0.0]]))[0] == pytest.approx(0.5)
    assert corner_motion(rects, np.array([[0.0, 0.0, 0.1]]))[0] == pytest.approx(0.1 * math.hypot(1.0, 0.5))


def synthetic(mechanism: np.ndarray, states: list[int], families: list[str]) -> tuple[SimpleNamespace, SimpleNamespace]:
    """Two blocks side by side on a base, as a model-like and a results-like object."""
    model = SimpleNamespace(
        rects=np.array([[0.0, 0.0, 1.0, 1.0], [1.0, 0.0, 2.0, 1.0], [0.0, -0.2, 2.0, 0.0]]),
        n_blocks=2,
        n_interfaces=len(states),
        base_index=2,
        top_index=None,
        interface_family=families,
        interface_blocks=np.array([[2, 0], [2, 1], [0, 1]]),
        interface_geometry=np.array([[0.5, 0.0, 0.0, 1.0, 1.0], [1.5, 0.0, 0.0, 1.0, 1.0], [1.0, 0.5, 1.0, 0.0, 1.0]]),
    )
    results = SimpleNamespace(
        method="static",
        status="collapse",
        error=None,
        collapse_multiplier=0.5,
        curve_multiplier=np.array([0.0, 0.25, 0.5]),
        curve_displacement=np.array([0.0, 1e-5, 3e-5]),
        mechanism=mechanism,
        interface_states=np.array(states),
        joint_states={"elastic": 1, "sliding": 1, "rocking": 1, "open": 0},
        steps=2,
        iterations=5,
        elapsed_s=0.01,
    )
    return model, results


def test_describe_rotation_about_toe() -> None:
    # both blocks turn clockwise as one body about (2, 0): u = phi k x (c - p)
    phi = -1.0
    mech = np.array([[-phi * 0.5, phi * (0.5 - 2.0), phi], [-phi * 0.5, phi * (1.5 - 2.0), phi], [0, 0, 0]])
    mech /= np.abs(mech[:, :2]).max()
    model, results = synthetic(mech, [1, 4, 0], ["base", "base", "head"])
    text = describe_mechanism(model, results)
    assert text.startswith("2 of 2 blocks move as one part, turning clockwise about (2.00, 0.00) m;"), text
    # the base lifts under the left block and hinges at the toe under the right one; the head joint stays closed
    assert text.endswith("the crack runs through 2 interfaces: 1 separate (1 base), 1 rock (1 base)"), text


def test_describe_sliding_and_parts() -> None:
    mech = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0, 0, 0]])
    model, results = synthetic(mech, [0, 2, 1], ["base", "base", "head"])
    text = describe_mechanism(model, results)
    assert text == (
        "1 of 2 blocks moves as one part, sliding at +0 deg from +x; "
        "the crack runs through 2 interfaces: 1 slip (1 base), 1 separate (1 head)"
    ), text
    mech = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 0.5], [0, 0, 0]])
    model, results = synthetic(mech, [2, 4, 1], ["base", "base", "head"])
    text = describe_mechanism(model, results)
    assert text.startswith("2 of 2 blocks move in 2 parts:"), text
    assert "1 block sliding at +0 deg from +x" in text
    assert "1 block turning counterclockwise about (1.50, 0.50) m" in text


def test_describe_no_mechanism() -> None:
    model, results = synthetic(np.full((3, 3), np.nan), [0, 0, 0], ["base", "base", "head"])
    assert describe_mechanism(model, results) == "none (no displacement increment)"


def test_format_multiplier() -> None:
    assert format_multiplier(0.642913) == "0.6429"
    assert format_multiplier(float("nan")) == "none"
    assert format_multiplier(56912.34, "top_horizontal") == "56.91 kN"
    assert format_multiplier(0.642913, symbol=True) == "λu = 0.6429"
    assert format_multiplier(float("nan"), "top_horizontal", symbol=True) == "Hu: none"


def test_plot_synthetic(tmp_path: Path) -> None:
    mech = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0, 0, 0]])
    model, results = synthetic(mech, [0, 2, 1], ["base", "base", "head"])
    fig = plot_results(model, results, title="two blocks", path=tmp_path / "s.png")
    assert (tmp_path / "s.png").read_bytes().startswith(PNG)
    assert "two blocks" in fig._suptitle.get_text()
    assert len(fig.axes) == 2
    # no mechanism and an empty curve still plot
    results.mechanism = np.full((3, 3), np.nan)
    results.curve_multiplier = results.curve_displacement = np.array([])
    results.collapse_multiplier = float("nan")
    results.status, results.error = "failed", "singular tangent at the first step"
    plot_results(model, results, path=tmp_path / "f.png", live="top_horizontal")
    assert (tmp_path / "f.png").read_bytes().startswith(PNG)


@pytest.mark.parametrize("name", ["stack-3-blocks.toml", "ferris-tinloi-wall1.toml"])
def test_plot_real(tmp_path: Path, name: str) -> None:
    case = md.load_case(EXAMPLES / name)
    model = case.build_model()
    results = case.solve(model)
    path = tmp_path / "wall.png"
    fig = plot_results(model, results, title=case.title, path=path)
    assert path.read_bytes().startswith(PNG)
    assert path.stat().st_size > 10_000
    title = fig._suptitle.get_text()
    assert case.title in title and results.status in title
    text = summary(case.title, model, results)
    assert text.splitlines()[0] == case.title
    assert "mechanism:" in text
    # the joint states add up to the interfaces, those that slide and rock counted once
    line = next(l for l in text.splitlines() if "joint states:" in l)
    counts = {k: int(v) for v, k in re.findall(r"(\d+) (elastic|sliding|rocking|open)\b", line)}
    both = re.search(r"\((\d+) both sliding and rocking\)", line)
    twice = int(both.group(1)) if both else 0
    assert sum(counts.values()) - twice == model.n_interfaces, line


def test_describe_top_beam_only() -> None:
    mech = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0, 0, 0], [1.0, 0.0, 0.0]])
    model, results = synthetic(mech, [0, 0, 0, 2], ["base", "base", "head", "top"])
    model.rects = np.vstack([model.rects, [[0.0, 1.0, 2.0, 1.1]]])
    model.top_index = 3
    model.interface_blocks = np.array([[2, 0], [2, 1], [0, 1], [0, 3]])
    model.interface_geometry = np.vstack([model.interface_geometry, [[0.5, 1.0, 0.0, 1.0, 1.0]]])
    text = describe_mechanism(model, results)
    assert text == (
        "only the top beam moves as one part, sliding at +0 deg from +x; "
        "the crack runs through 1 interface: 1 slip (1 top)"
    ), text


# --- the panel functions and the one-page report -------------------------------------------------------------


@pytest.fixture(scope="module")
def wall1() -> tuple:
    case = md.load_case(EXAMPLES / "ferris-tinloi-wall1.toml")
    model = case.build_model()
    return case, model, case.solve(model)


def _agg_axes(size: tuple = (6.0, 4.0)) -> tuple:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=size, layout="constrained")
    FigureCanvasAgg(fig)
    return fig, fig.add_subplot()


def _pixels_near(image: np.ndarray, color: str, tolerance: float = 0.03) -> int:
    """The number of pixels of ``image`` (RGB(A) floats in [0, 1]) within ``tolerance`` of ``color``."""
    from matplotlib.colors import to_rgb

    rgb = np.asarray(to_rgb(color))
    return int(np.sum(np.all(np.abs(image[..., :3] - rgb) <= tolerance, axis=-1)))


def test_plot_cracks_colours(tmp_path: Path, wall1: tuple) -> None:
    """The crack-pattern PNG shows every state present, in its colour."""
    import matplotlib.image as mpimg

    from masonry_dem.plot import STATE_STYLES, plot_cracks

    _, model, results = wall1
    fig, ax = _agg_axes((8.0, 5.0))
    counts = plot_cracks(ax, model, results)
    path = tmp_path / "cracks.png"
    fig.savefig(path, dpi=100)
    image = mpimg.imread(path)
    cats = interface_categories(results.interface_states)
    assert {"elastic", "open", "sliding", "rocking"} <= set(cats)  # the wall collapses with joints of every state
    for name, color, _ in STATE_STYLES:
        assert counts[name] == cats.count(name)
        if counts[name]:
            assert _pixels_near(image, color) > 30, f"no {name} ({color}) pixels in the crack pattern"
    assert counts["cracked"] > 0
    # a colour that is not drawn is not found
    assert _pixels_near(image, "#00ff00") == 0


def test_panels(wall1: tuple) -> None:
    from masonry_dem.plot import plot_curve, plot_deformed, plot_mechanism, plot_wall

    _, model, results = wall1
    height = float(model.rects[: model.n_blocks, 3].max() - model.rects[: model.n_blocks, 1].min())
    fig, ax = _agg_axes()
    plot_wall(ax, model)
    assert "33 blocks" in ax.get_title()
    fig, ax = _agg_axes()
    scale = plot_deformed(ax, model, results)
    peak = float(corner_motion(model.rects, results.displacements).max())
    assert scale * peak == pytest.approx(0.05 * height)  # the largest displacement drawn as 5% of the height
    assert "×" in ax.get_title()
    fig, ax = _agg_axes()
    assert plot_deformed(ax, model, results, scale=10.0) == 10.0
    assert "×10" in ax.get_title()
    fig, ax = _agg_axes()
    assert plot_mechanism(ax, model, results)
    assert "moving block" in ax.get_title()
    fig, ax = _agg_axes()
    plot_curve(ax, results)
    assert len(ax.lines) >= 1
    fig, ax = _agg_axes()
    plot_curve(ax, results, results, labels=["static", "again"])
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    assert texts[0].startswith("static") and texts[1].startswith("again")
    with pytest.raises(ValueError):
        plot_curve(ax, results, labels=["a", "b"])


def test_report_figure(tmp_path: Path, wall1: tuple) -> None:
    from masonry_dem.plot import report_figure

    case, model, results = wall1
    path = tmp_path / "report.png"
    fig = report_figure(model, results, title=case.title, path=path)
    assert path.read_bytes().startswith(PNG)
    assert case.title in fig._suptitle.get_text()
    assert len(fig.axes) == 4
    # both methods overlaid (here the same result twice) and a tall wall (one row)
    fig = report_figure(model, results, title=case.title, other=results, path=tmp_path / "two.png")
    assert len(fig.axes[3].get_legend().get_texts()) == 2
    mech = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0, 0, 0]])
    tall, res = synthetic(mech, [0, 2, 1], ["base", "base", "head"])
    res.displacements = np.zeros((3, 3))
    tall.rects = np.array([[0.0, 0.0, 0.2, 1.0], [0.2, 0.0, 0.4, 1.0], [0.0, -0.2, 0.4, 0.0]])
    report_figure(tall, res, title="tall", path=tmp_path / "tall.png", live="top_horizontal")
    assert (tmp_path / "tall.png").read_bytes().startswith(PNG)
