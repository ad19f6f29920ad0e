"""The line of thrust (masonry_dem.thrust, masonry_dem.plot.plot_thrust): each joint's centre of pressure against
closed forms, and the chains of blocks it runs along."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem.thrust import resultant_points, thrust_chains, thrust_lines

DRY = {"default": md.dry_joint(0.65, dilatancy=0.65)}


class _Stop(Exception):
    pass


def dead_load_state(model: md.Model) -> md.Results:
    """The first state of the static path, lambda = 0: the wall under its dead loads alone (the path stopped by its
    progress callback after that step; the exception carries the results so far)."""

    def stop(step: int, multiplier: float, displacement: float, fraction: float) -> None:
        raise _Stop()

    with pytest.raises(_Stop) as info:
        model.solve_static(progress=stop)
    results = info.value.results
    assert list(results.curve_multiplier) == [0.0]
    return results


def test_under_its_weight_alone_the_resultant_is_on_the_centroid_s_vertical() -> None:
    b, h = 0.4, 1.2
    model = md.Model([[0.0, 0.0, b, h]], thickness=1.0, joints=DRY)
    p = resultant_points(model, dead_load_state(model))
    assert p.tolist() == [pytest.approx([b / 2, 0.0], abs=1e-9)]
    # two blocks, the upper one overhanging: under the upper block's joint its own centroid (x = 0.7), under the
    # lower block's the centroid of both, (1 * 0.5 + 0.8 * 0.7) / 1.8 (areas 1 and 0.8 m2, one density)
    stack = md.Model([[0.0, 0.0, 1.0, 1.0], [0.3, 1.0, 1.1, 2.0]], thickness=1.0, joints=DRY)
    results = dead_load_state(stack)
    pairs = stack.interface_blocks.tolist()
    p = resultant_points(stack, results)
    assert p[pairs.index([0, 1])] == pytest.approx([0.7, 1.0], abs=1e-9)
    assert p[pairs.index([stack.base_index, 0])] == pytest.approx([(0.5 + 0.8 * 0.7) / 1.8, 0.0], abs=1e-9)
    # one line, from the base up through the lower block to the upper one's joint
    lines = thrust_lines(stack, results)
    assert len(lines) == 1
    np.testing.assert_allclose(lines[0], [[(0.5 + 0.8 * 0.7) / 1.8, 0.0], [0.7, 1.0]], atol=1e-9)


@pytest.mark.parametrize("method", ["limit", "static"])
def test_at_its_overturning_multiplier_the_resultant_is_at_the_toe(method: str) -> None:
    b, h = 0.4, 1.2
    model = md.Model([[0.0, 0.0, b, h]], thickness=1.0, joints=DRY)
    results = model.solve_limit() if method == "limit" else model.solve_static()
    assert results.status == "collapse"
    assert results.collapse_multiplier == pytest.approx(b / h, rel=1e-9)  # tan(alpha) = b / h
    # pushed towards +x, the block turns about its right bottom corner, the toe (b, 0)
    assert resultant_points(model, results).tolist() == [pytest.approx([b, 0.0], abs=1e-9)]


def test_a_joint_without_normal_force_has_no_centre_of_pressure() -> None:
    model = md.Model([[0.0, 0.0, 1.0, 1.0], [0.0, 1.0, 1.0, 2.0], [0.0, 2.0, 1.0, 3.0]], joints=DRY)
    chain = thrust_chains(model)
    assert len(chain) == 1 and len(chain[0]) == 3  # base - 0 - 1 - 2: three joints in a line
    pairs = model.interface_blocks.tolist()
    assert [pairs[k] for k in chain[0]] in ([[model.base_index, 0], [0, 1], [1, 2]], [[1, 2], [0, 1],
                                                                                       [model.base_index, 0]])
    forces = np.zeros((model.n_interfaces, 3))
    forces[:, 0] = -1000.0
    forces[pairs.index([0, 1])] = [1e-10, 5.0, 2.0]  # next to nothing: no resultant on the joint
    forces[pairs.index([1, 2])] = [-1000.0, 0.0, -250.0]  # e = M / N = 0.25 along t = +x
    p = resultant_points(model, forces)
    assert np.isnan(p[pairs.index([0, 1])]).all()
    assert p[pairs.index([1, 2])].tolist() == [0.75, 2.0]
    line = thrust_lines(model, forces)[0]
    assert np.isnan(line).any(axis=1).sum() == 1  # the line broken at that joint
    with pytest.raises(ValueError, match=r"the model has 3 interfaces, the forces are of shape \(2, 3\)"):
        resultant_points(model, forces[:2])


def test_a_wall_of_courses_has_no_chain_but_every_joint_its_point() -> None:
    model = md.Model(md.running_bond(0.4, 0.2, courses=4, length=1.2), joints=DRY)
    results = model.solve_limit()
    assert thrust_chains(model) == []
    p = resultant_points(model, results)
    n_force = results.interface_forces[:, 0]
    carries = np.abs(n_force) > 1e-9 * np.abs(n_force).max()
    assert 0 < carries.sum() < model.n_interfaces  # joints opened by the mechanism carry nothing
    assert p.shape == (model.n_interfaces, 2) and np.array_equal(np.isfinite(p).all(axis=1), carries)


def test_the_line_of_thrust_is_drawn(tmp_path: Path) -> None:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from masonry_dem.plot import plot_thrust, report_figure

    model = md.Model([[0.0, 0.0, 1.0, 1.0], [0.3, 1.0, 1.1, 2.0]], thickness=1.0, joints=DRY)
    results = model.solve_limit()
    fig = Figure()
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    assert plot_thrust(ax, model, results) == 1
    assert ax.get_title().startswith("line of thrust at collapse\n1 line")
    line = [l for l in ax.get_lines() if l.get_linestyle() == "-"]
    np.testing.assert_allclose(np.c_[line[0].get_xdata(), line[0].get_ydata()], thrust_lines(model, results)[0])
    static = model.solve_static()
    ax = fig.add_subplot(1, 2, 2)
    plot_thrust(ax, model, static)
    assert ax.get_title().startswith(f"line of thrust at the last converged step, λ = "
                                     f"{static.last_equilibrium:.4f}")
    path = report_figure(model, results, title="stack", path=tmp_path / "stack.png", dpi=50, thrust=True)
    assert "line of thrust" in path.axes[0].get_title() and (tmp_path / "stack.png").stat().st_size > 0


#: A parallelogram leaning right: its bed [0, 1] at y = 0, its top [0.3, 1.3] at y = 1; centroid (0.65, 0.5).
LEANING = [[0.0, 0.0], [1.0, 0.0], [1.3, 1.0], [0.3, 1.0]]


def test_a_leaning_block_s_resultant_is_on_its_centroid_s_vertical_not_its_joint_s_centre() -> None:
    model = md.Model([LEANING], thickness=1.0, joints=DRY)
    assert model.centroids[0] == pytest.approx([0.65, 0.5], abs=1e-15)
    (p,) = resultant_points(model, dead_load_state(model))
    assert p == pytest.approx([0.65, 0.0], abs=1e-9)  # the joint's centre is at x = 0.5


@pytest.mark.parametrize("method", ["limit", "static"])
def test_a_leaning_block_overturns_about_its_toe(method: str) -> None:
    from masonry_dem.report import hinges

    # it turns about its toe (1, 0): lambda W y_c = W (1 - x_c), lambda = (1 - 0.65) / 0.5 = 0.7 (friction 2: no
    # sliding)
    model = md.Model([LEANING], thickness=1.0, joints={"default": md.dry_joint(2.0, dilatancy=2.0)})
    results = model.solve_limit() if method == "limit" else model.solve_static()
    assert results.status == "collapse" and results.collapse_multiplier == pytest.approx(0.7, rel=1e-9)
    assert resultant_points(model, results).tolist() == [pytest.approx([1.0, 0.0], abs=1e-9)]
    assert [(h.end, h.point.tolist()) for h in hinges(model, results.mechanism)] == [("right", [1.0, 0.0])]
