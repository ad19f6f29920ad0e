"""Blocks as convex polygons in the Python front: the shapes every figure, export and report reads
(masonry_dem._shapes), drawn, exported and described for walls of polygons and of rectangles alike."""

from __future__ import annotations

import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem._shapes import Shapes, area_centroid, fixed_blocks, moved_vertices, polygon_problem, shapes
from masonry_dem.report import corner_motion, deformed_corners, describe_mechanism, interface_jumps

# --------------------------------------------------------------------------------------------------
# The shapes of a model
# --------------------------------------------------------------------------------------------------

#: A trapezoid, its area and centroid in closed form: bases a (at y = 0) and b (at y = h), the top centred.
A, B, H = 2.0, 1.0, 1.5
TRAPEZOID = [[0.0, 0.0], [A, 0.0], [(A + B) / 2, H], [(A - B) / 2, H]]
TRAPEZOID_AREA = (A + B) / 2 * H
TRAPEZOID_CENTROID = (A / 2, H * (A + 2 * B) / (3 * (A + B)))


def test_a_rectangle_model_reads_as_four_vertex_polygons() -> None:
    model = md.Model(md.running_bond(0.4, 0.2, courses=2, length=1.0), top_rotation="free")
    blocks = shapes(model)
    rects = np.asarray(model.rects)
    assert len(blocks) == len(rects) and list(blocks.counts) == [4] * len(rects)
    for i, (x0, y0, x1, y1) in enumerate(rects):
        assert blocks.polygon(i).tolist() == [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]  # counter-clockwise
    assert np.array_equal(blocks.bounds, rects)
    assert np.array_equal(blocks.centroids, 0.5 * (rects[:, :2] + rects[:, 2:]))
    np.testing.assert_allclose(blocks.areas, (rects[:, 2] - rects[:, 0]) * (rects[:, 3] - rects[:, 1]), rtol=1e-14)
    assert fixed_blocks(model) == [model.base_index]


def test_polygon_area_and_centroid_closed_forms() -> None:
    assert area_centroid(TRAPEZOID) == pytest.approx(TRAPEZOID_CENTROID, abs=1e-15)
    assert area_centroid(TRAPEZOID[::-1]) == pytest.approx(TRAPEZOID_CENTROID, abs=1e-15)  # either orientation
    far = np.array(TRAPEZOID) + [1e4, -3e3]  # far from the origin: the centroid keeps its digits
    assert area_centroid(far) == pytest.approx(np.array(TRAPEZOID_CENTROID) + [1e4, -3e3], abs=1e-11)
    triangle = [[0.0, 0.0], [3.0, 0.0], [0.0, 2.0]]
    blocks = Shapes.from_polygons([TRAPEZOID, triangle])
    assert blocks.areas == pytest.approx([TRAPEZOID_AREA, 3.0], rel=1e-14)
    assert blocks.centroids[1] == pytest.approx([1.0, 2.0 / 3.0], abs=1e-15)
    assert blocks.bounds.tolist() == [[0.0, 0.0, A, H], [0.0, 0.0, 3.0, 2.0]]


def test_vertex_motion_and_moved_vertices_of_a_triangle() -> None:
    triangle = np.array([[0.0, 0.0], [3.0, 0.0], [0.0, 3.0]])  # centroid (1, 1)
    blocks = Shapes.from_polygons([triangle])
    # a turn phi about the centroid moves each vertex by phi |r|: the farthest vertices are sqrt(5) away
    assert blocks.vertex_motion([[0.0, 0.0, 0.01]])[0] == pytest.approx(0.01 * math.sqrt(5.0), rel=1e-14)
    assert corner_motion(blocks, np.array([[0.3, -0.4, 0.0]]))[0] == pytest.approx(0.5, rel=1e-15)
    # a quarter turn about (1, 1), then a translation: (x, y) -> (1 - (y - 1), 1 + (x - 1)) + (2, 0)
    quarter = moved_vertices(triangle, [2.0, 0.0, math.pi / 2], 1.0)
    np.testing.assert_allclose(quarter, [[4.0, 0.0], [4.0, 3.0], [1.0, 0.0]], atol=1e-15)
    np.testing.assert_allclose(deformed_corners(triangle, [2.0, 0.0, math.pi / 2], 1.0), quarter, atol=0)
    # scaled: half the motion
    np.testing.assert_allclose(blocks.moved(np.array([[4.0, 0.0, math.pi]]), 0.5), quarter, atol=1e-15)
    # the displacements of the vertices, exact and linearized
    exact = blocks.displacements([[0.0, 0.0, math.pi / 2]], exact=True)
    np.testing.assert_allclose(triangle + exact, [[2.0, 0.0], [2.0, 3.0], [-1.0, 0.0]], atol=1e-15)
    small = blocks.displacements([[0.1, 0.2, 1e-3]], exact=False)
    r = triangle - [1.0, 1.0]
    np.testing.assert_allclose(small, np.c_[0.1 - 1e-3 * r[:, 1], 0.2 + 1e-3 * r[:, 0]], rtol=1e-15)


# --------------------------------------------------------------------------------------------------
# A wall of polygons, as the core describes one (Model.polygons, centroids, support_indices)
# --------------------------------------------------------------------------------------------------


def gable() -> SimpleNamespace:
    """A gable wall as the core's Model would give it: a square block under a triangular one (the gable), a
    pentagon leaning on the square's right side and resting on an inclined support; the base under all. Block
    order: wall blocks, the support, the base."""
    polygons = [
        np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]),  # 0: the square
        np.array([[0.0, 1.0], [1.0, 1.0], [0.5, 1.6]]),  # 1: the gable
        np.array([[1.0, 0.5], [1.5, 0.0], [2.0, 0.0], [2.0, 0.8], [1.0, 1.0]]),  # 2: a pentagon
        np.array([[1.0, 0.0], [1.5, 0.0], [1.0, 0.5]]),  # 3: the support, a triangle
        np.array([[0.0, -0.2], [2.0, -0.2], [2.0, 0.0], [0.0, 0.0]]),  # 4: the base
    ]
    centroids = np.array([area_centroid(p) for p in polygons])
    lo = np.array([p.min(axis=0) for p in polygons])
    hi = np.array([p.max(axis=0) for p in polygons])
    s = 1 / math.sqrt(2.0)
    # interfaces: square-gable (bed), square-pentagon (head), support-pentagon (base), base-square, base-pentagon
    blocks = [[0, 1], [0, 2], [3, 2], [4, 0], [4, 2]]
    geometry = [[0.5, 1.0, 0.0, 1.0, 1.0], [1.0, 0.75, 1.0, 0.0, 0.5], [1.25, 0.25, s, s, math.hypot(0.5, 0.5)],
                [0.5, 0.0, 0.0, 1.0, 1.0], [1.75, 0.0, 0.0, 1.0, 0.5]]
    return SimpleNamespace(
        polygons=polygons,
        centroids=centroids,
        rects=np.c_[lo, hi],
        n_blocks=3,
        n_interfaces=len(blocks),
        base_index=4,
        top_index=None,
        support_indices=[3],
        block_kinds=["wall", "wall", "wall", "support", "base"],
        interface_blocks=np.array(blocks),
        interface_geometry=np.array(geometry),
        interface_family=["bed", "head", "base", "base", "base"],
        weights=np.ones(5),
        dimension=2,
    )


def rocking_gable_results(model: SimpleNamespace) -> SimpleNamespace:
    """A mechanism of the gable: the triangle turning clockwise about the square's right top corner (1, 1)."""
    mech = np.zeros((5, 3))
    c = model.centroids[1]
    phi = -1.0
    mech[1] = [-phi * (c[1] - 1.0), phi * (c[0] - 1.0), phi]  # the velocity at the centroid of a turn about (1, 1)
    return SimpleNamespace(
        method="limit", status="collapse", collapse_multiplier=0.3, last_equilibrium=0.3, mechanism=mech,
        displacements=np.zeros((5, 3)), interface_states=np.array([4, 0, 0, 0, 0]),
        interface_forces=np.zeros((5, 3)), broken=np.zeros(5, dtype=bool), iterations=10, steps=0,
        elapsed_s=0.01, error=None, curve_multiplier=np.zeros(0), curve_displacement=np.zeros(0),
        joint_states={"elastic": 4, "rocking": 1, "sliding": 0, "open": 0}, certificate=None,
    )


def test_the_mechanism_of_a_wall_of_polygons_is_described() -> None:
    model = gable()
    results = rocking_gable_results(model)
    text = describe_mechanism(model, results)
    assert text.startswith("1 of 3 blocks moves as one part, turning clockwise about (1.00, 1.00) m")
    assert "1 rock (1 bed)" in text
    jumps = interface_jumps(model, results.mechanism)
    # the bed joint under the gable opens at its left end by phi l = 1 and stays shut at its right end
    assert jumps[0].tolist() == pytest.approx([0.0, 1.0, 0.0], abs=1e-14)
    assert not np.any(jumps[1:])


def test_a_wall_of_polygons_is_drawn(tmp_path: Path) -> None:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.patches import Polygon

    from masonry_dem.plot import plot_mechanism, plot_wall, report_figure

    model = gable()
    results = rocking_gable_results(model)
    fig = Figure()
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    plot_wall(ax, model)
    hatched = [p for p in ax.patches if isinstance(p, Polygon) and p.get_hatch()]
    # the support and the base, hatched, with their own vertices
    assert [p.get_xy()[:-1].tolist() for p in hatched] == [model.polygons[3].tolist(), model.polygons[4].tolist()]
    fills = ax.collections[0].get_paths()
    assert [len(p.vertices) - 1 for p in fills] == [4, 3, 5]  # the wall blocks, closed
    ax = fig.add_subplot(1, 2, 2)
    assert plot_mechanism(ax, model, results)
    moved = ax.collections[0].get_paths()[1].vertices[:-1]
    # the gable turned clockwise about (1, 1) by the angle a drawn (exactly, its centroid moved along the
    # mechanism's velocity): its corner (1, 1) stays within a^2 / 2 |r| of its place, r its arm from the centroid
    turned = moved[1] - moved[0]
    a = math.atan2(turned[1], turned[0])
    assert -0.5 < a < 0
    arm = math.hypot(*(np.array([1.0, 1.0]) - model.centroids[1]))
    assert math.hypot(*(moved[1] - [1.0, 1.0])) <= 0.5 * a * a * arm * (1 + 1e-9)
    assert math.hypot(*(moved[2] - [0.5, 1.6])) == pytest.approx(abs(a) * math.hypot(0.5, 0.6), rel=0.1)
    assert "1 moving block, 1 cracked joint" in ax.get_title()
    report_figure(model, results, title="gable", path=tmp_path / "gable.png", dpi=50)
    assert (tmp_path / "gable.png").stat().st_size > 0


def test_a_wall_of_polygons_is_exported_as_polygon_cells() -> None:
    from masonry_dem.export import block_mesh

    model = gable()
    results = rocking_gable_results(model)
    results.displacements = results.mechanism * 1e-3
    mesh = block_mesh(model, results)
    assert [(c.type, c.data.shape) for c in mesh.cells] == [("quad", (1, 4)), ("triangle", (1, 3)),
                                                           ("polygon", (1, 5)), ("triangle", (1, 3)),
                                                           ("quad", (1, 4))]
    cells = [row for c in mesh.cells for row in c.data]
    for i, row in enumerate(cells):  # each cell the block's vertices, in order
        assert mesh.points[row, :2].tolist() == model.polygons[i].tolist()
    assert np.concatenate(mesh.cell_data["kind"]).tolist() == [0, 0, 0, 3, 1]
    assert np.concatenate(mesh.cell_data["block"]).tolist() == [0, 1, 2, 3, 4]
    rotation = np.concatenate(mesh.cell_data["rotation"])
    assert rotation.tolist() == [0.0, -1e-3, 0.0, 0.0, 0.0]
    # the vertices of the gable move by u + phi k x r (linearized): its corner at (1, 1) stays put
    vertex_u = mesh.point_data["displacement"][cells[1], :2]
    assert vertex_u[1] == pytest.approx([0.0, 0.0], abs=1e-15)
    assert vertex_u[0] == pytest.approx([0.0, 1e-3], abs=1e-15)  # (0, 1) turns about (1, 1): upwards


def test_to_dict_gives_every_block_s_polygon() -> None:
    model = md.Model(md.running_bond(0.4, 0.2, courses=2, length=1.0), top_rotation="free")
    results = model.solve_limit()
    d = md.to_dict(results, model)
    rects = np.asarray(model.rects)
    assert len(d["block_polygons"]) == len(rects)
    for poly, (x0, y0, x1, y1) in zip(d["block_polygons"], rects):
        assert poly == [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
    assert d["block_rects"] == rects.tolist()


# --------------------------------------------------------------------------------------------------
# The checks of an outline
# --------------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "vertices, problem",
    [
        ([[0, 0], [1, 0]], "has 2 vertices: a block has at least 3"),
        ([[0, 0], [1, 0], [1, 0], [0, 1]], "vertex 2 (1, 0) repeats vertex 1"),
        ([[0, 0], [1, 0], [2, 0]], "has all its vertices on a line: (0, 0), (1, 0), (2, 0)"),
        ([[0, 0], [2, 0], [1, 0], [1, 1]], "turns back on itself at vertex 1 (2, 0)"),
        ([[0, 0], [1, 1], [1, 0], [0, 1]], "crosses itself"),
        ([[0, 0], [2, 0], [2, 2], [1, 1], [0, 2]],
         "is not convex: it turns the other way at vertex 3 (1, 1) (a block is a convex polygon)"),
        ([[0, 2], [1, 1], [2, 2], [2, 0], [0, 0]], "is not convex: it turns the other way at vertex 1 (1, 1)"),
        # a pentagram: every turn the same way, twice round
        ([[0, 1], [0.588, -0.809], [-0.951, 0.309], [0.951, 0.309], [-0.588, -0.809]], "crosses itself"),
    ],
)
def test_outlines_refused(vertices: list, problem: str) -> None:
    message = polygon_problem(vertices)
    assert message is not None and message.startswith(problem)


def test_outlines_accepted() -> None:
    assert polygon_problem(TRAPEZOID) is None
    assert polygon_problem(TRAPEZOID[::-1]) is None  # clockwise
    assert polygon_problem(TRAPEZOID + TRAPEZOID[:1]) is None  # closed by its first vertex again
    assert polygon_problem([[0, 0], [1, 0], [2, 0], [2, 1], [0, 1]]) is None  # a vertex on an edge
    assert polygon_problem([[0, 0], [1, 1e-12], [2, 0], [2, 1], [0, 1]]) is None  # within the tolerance
    assert polygon_problem([[0, 0], [1, -1e-3], [2, 0], [2, 1], [0, 1]]) is None  # convex, barely
    assert polygon_problem([[0, 0], [1, 1e-3], [2, 0], [2, 1], [0, 1]]) is not None
