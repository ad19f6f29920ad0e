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
    np.testing.assert_allclose(blocks.centroids, 0.5 * (rects[:, :2] + rects[:, 2:]), rtol=0, atol=1e-15)
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
        ([[0, 0], [1, 0]], "2 vertices: a block needs at least 3"),
        ([[0, 0], [1, 0], [1, 1e-12], [0, 0]], "fewer than 3 distinct vertices (2 of the 4 given)"),
        ([[0, 0], [1, 0], [2, 0]], "all its vertices lie on one line: it has no area"),
        ([[0, 0], [2, 0], [1, 0], [1, 1]], "vertex 1 (2, 0) turns the outline back on itself"),
        ([[0, 0], [1, 1], [1, 0], [0, 1]], "vertex 1 (1, 1) is a re-entrant corner: the outline is not convex or "
                                           "crosses itself"),
        ([[0, 0], [2, 0], [2, 2], [1, 1], [0, 2]],
         "vertex 3 (1, 1) is a re-entrant corner: the outline is not convex or crosses itself (a concave stone is "
         "given as convex parts)"),
        ([[0, 2], [1, 1], [2, 2], [2, 0], [0, 0]], "vertex 1 (1, 1) is a re-entrant corner"),
        # a pentagram: every turn the same way, twice round
        ([[0, 1], [0.588, -0.809], [-0.951, 0.309], [0.951, 0.309], [-0.588, -0.809]],
         "the outline winds round past its start at vertex 1 (0.588, -0.809): it crosses itself (a block is one convex "
         "polygon)"),
    ],
)
def test_outlines_refused(vertices: list, problem: str) -> None:
    message = polygon_problem(vertices)
    assert message is not None and message.startswith(problem)


def test_outlines_accepted() -> None:
    assert polygon_problem(TRAPEZOID) is None
    assert polygon_problem(TRAPEZOID[::-1]) is None  # clockwise
    assert polygon_problem(TRAPEZOID + TRAPEZOID[:1]) is None  # closed by its first vertex again
    assert polygon_problem([[0, 0], [1, 0], [1, 0], [0, 1]]) is None  # a vertex given twice is one vertex
    assert polygon_problem([[0, 0], [1, 0], [2, 0], [2, 1], [0, 1]]) is None  # a vertex on an edge
    assert polygon_problem([[0, 0], [1, 1e-12], [2, 0], [2, 1], [0, 1]]) is None  # within the tolerance
    assert polygon_problem([[0, 0], [1, -1e-3], [2, 0], [2, 1], [0, 1]]) is None  # convex, barely
    assert polygon_problem([[0, 0], [1, 1e-3], [2, 0], [2, 1], [0, 1]]) is not None


# --------------------------------------------------------------------------------------------------
# Case files: [geometry] polygons and supports
# --------------------------------------------------------------------------------------------------

GABLE_CASE = """format = 1
title = "gable"
[geometry]
thickness = 0.5
blocks = [[0, 0, 1, 1]]
polygons = [[[0, 1], [1, 1], ["500 mm", "1600 mm"]], [[2, 0], [2, 1], [1, 1], [1, 0.5], [1.5, 0]]]
supports = [[[1, 0], [1.5, 0], [1, 0.5]]]
[analysis]
method = "limit"
"""


def test_case_polygons_and_supports_are_read(tmp_path: Path) -> None:
    path = tmp_path / "gable.toml"
    path.write_text(GABLE_CASE)
    case = md.load_case(path)
    assert case.model.blocks == [[0.0, 0.0, 1.0, 1.0], [[0.0, 1.0], [1.0, 1.0], [0.5, 1.6]],
                                 [[2.0, 0.0], [2.0, 1.0], [1.0, 1.0], [1.0, 0.5], [1.5, 0.0]]]
    assert case.model.supports == [[[1.0, 0.0], [1.5, 0.0], [1.0, 0.5]]]
    assert case.model.base is False  # supports and no [base] table: no foundation
    assert case.model_kwargs["supports"] == case.model.supports and case.model_kwargs["base"] is False
    # a [base] table puts the foundation back under a wall on supports
    path.write_text(GABLE_CASE + '[base]\nkind = "fixed"\n')
    assert md.load_case(path).model.base is True
    # polygons alone; a wall of rectangles keeps its array, no supports, and the core's base
    path.write_text(GABLE_CASE.replace("blocks = [[0, 0, 1, 1]]\n", "").replace("supports", "# supports"))
    case = md.load_case(path)
    assert len(case.model.blocks) == 2 and case.model.supports is None and case.model.base is None
    path.write_text("format = 1\n[geometry]\nblocks = [[0, 0, 1, 1]]\n")
    case = md.load_case(path)
    assert isinstance(case.model.blocks, np.ndarray) and case.model.blocks.tolist() == [[0.0, 0.0, 1.0, 1.0]]
    assert case.model_kwargs["supports"] is None and case.model_kwargs["base"] is True  # the core's defaults


#: A case file of one polygon block on the base; {geometry} replaces its [geometry] keys.
POLYGON_CASE = """format = 1
[geometry]
{geometry}
"""


@pytest.mark.parametrize(
    "geometry, key, message",
    [
        ("polygons = []", "geometry.polygons", "geometry.polygons: expected at least one block, each an array of "
                                               "vertices [x, y] (or leave the key out)"),
        ("polygons = [3]", "geometry.polygons[0]", "geometry.polygons[0]: expected an array of vertices [x, y], got "
                                                   "integer"),
        ("polygons = [[0, 0, 1, 1]]", "geometry.polygons[0][0]", "geometry.polygons[0][0]: expected an array of 2 "
                                                                 "numbers [x, y], got integer"),
        ("polygons = 3", "geometry.polygons", "geometry.polygons: expected an array, got integer"),
        ("polygons = [[[0, 0], [1, 0], [1]]]", "geometry.polygons[0][2]",
         "geometry.polygons[0][2]: expected 2 numbers [x, y], got 1"),
        ('polygons = [[[0, 0], [1, 0], [1, "1 kN"]]]', "geometry.polygons[0][2][1]",
         "'1 kN' is a force; geometry.polygons[0][2][1] is a length (m, cm, mm)"),
        ("polygons = [[[0, 0], [1, 0], [0.5, 1]], [[0, 0], [1, 0]]]", "geometry.polygons[1]",
         "geometry.polygons[1]: 2 vertices: a block needs at least 3"),
        ("polygons = [[[0, 0], [1, 0], [1, 1], [0.9, 0.5], [0, 1]]]", "geometry.polygons[0]",
         "geometry.polygons[0]: vertex 3 (0.9, 0.5) is a re-entrant corner: the outline is not convex or crosses "
         "itself (a concave stone is given as convex parts)"),
        ("polygons = [[[0, 0], [1, 1], [1, 0], [0, 1]]]", "geometry.polygons[0]",
         "geometry.polygons[0]: vertex 1 (1, 1) is a re-entrant corner"),
        ("polygons = [[[0, 0], [1, 0], [2, 0]]]", "geometry.polygons[0]",
         "geometry.polygons[0]: all its vertices lie on one line: it has no area"),
        ("polygons = [[[0, 0], [1, 0], [1, 0], [0, 0]]]", "geometry.polygons[0]",
         "geometry.polygons[0]: fewer than 3 distinct vertices (2 of the 4 given)"),
        ("polygons = [[[0, 0], [1, 0], [0, 1]]]\nsupports = []", "geometry.supports",
         "geometry.supports: expected at least one support"),
        ("blocks = [[0, 0, 1, 1]]\nsupports = [[[1, 0], [2, 0], [1.5, 0], [1.5, 1]]]", "geometry.supports[0]",
         "geometry.supports[0]: vertex 1 (2, 0) turns the outline back on itself"),
        # a 3D wall's supports are polyhedra: vertices [x, y, z]
        ("boxes = [[0, 0, 0, 1, 1, 1]]\nsupports = [[[1, 0], [2, 0], [1.5, 1]]]", "geometry.supports[0][0]",
         "geometry.supports[0][0]: expected 3 numbers [x, y, z], got 2"),
        ("polygons = [[[0, 0], [1, 0], [0, 1]]]\ndxf = \"wall.dxf\"", None,
         "[geometry] needs exactly one of running_bond, pattern, blocks, dxf, polygons, arch, gable, stone_wall "
         "(blocks and polygons may be given together); dxf and polygons are both given"),
        ("supports = [[[0, 0], [1, 0], [0, 1]]]", None,
         "[geometry] needs exactly one of running_bond, pattern, blocks, dxf; none is given (polygons also make a "
         "wall, alone or beside blocks"),
    ],
)
def test_case_polygon_refusals(tmp_path: Path, capsys: pytest.CaptureFixture, geometry: str, key, message: str) -> None:
    from masonry_dem import cli

    path = tmp_path / "case.toml"
    path.write_text(POLYGON_CASE.format(geometry=geometry))
    with pytest.raises(md.InputError) as info:
        md.load_case(path)
    assert str(info.value).startswith(f"{path}: {message}") and info.value.key == key
    assert "\n" not in str(info.value)
    assert cli.main(["run", str(path), "--quiet"]) == 2  # the command line: status 2, the message on one line
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0] == f"masonry-dem: error: {info.value}"


def test_a_polygon_refusal_from_the_command_line(tmp_path: Path) -> None:
    import subprocess
    import sys

    path = tmp_path / "case.toml"
    path.write_text(POLYGON_CASE.format(geometry="polygons = [[[0, 0], [2, 0], [2, 2], [1, 1], [0, 2]]]"))
    proc = subprocess.run([sys.executable, "-m", "masonry_dem", "run", str(path)], capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr
    assert proc.stderr.strip() == (f"masonry-dem: error: {path}: geometry.polygons[0]: vertex 3 (1, 1) is a "
                                   "re-entrant corner: the outline is not convex or crosses itself (a concave stone is "
                                   "given as convex parts)")


# --------------------------------------------------------------------------------------------------
# Drawings: convex outlines
# --------------------------------------------------------------------------------------------------


def _drawing(tmp_path: Path, add, name: str = "arch.dxf") -> Path:
    import ezdxf

    doc = ezdxf.new(units=4)  # mm
    add(doc.modelspace())
    path = tmp_path / name
    doc.saveas(path)
    return path


def test_convex_outlines_of_a_drawing_are_polygon_blocks(tmp_path: Path) -> None:
    from masonry_dem.dxf import read_dxf, read_dxf_blocks, read_dxf_polygons

    def add(msp) -> None:
        msp.add_lwpolyline([(0, 0), (1000, 0), (1000, 1000), (0, 1000)], close=True)  # a rectangle, in mm
        msp.add_lwpolyline([(0, 1000), (1000, 1000), (500, 1600), (0, 1000)])  # a triangle closed by its first vertex
        msp.add_polyline2d([(2000, 0), (2000, 800), (1000, 1000), (1000, 500), (1500, 0)], close=True)  # clockwise
        msp.add_solid([(1000, 0), (1500, 0), (1000, 500)])  # a triangle SOLID

    path = _drawing(tmp_path, add)
    polygons = read_dxf_polygons(path)
    # bottom to top, left to right (by the lowest y, then the lowest x; a tie in the drawing's order); metres; the
    # drawing's vertices in its order
    assert [p.tolist() for p in polygons] == [
        [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        [[2.0, 0.0], [2.0, 0.8], [1.0, 1.0], [1.0, 0.5], [1.5, 0.0]],
        [[1.0, 0.0], [1.5, 0.0], [1.0, 0.5]],
        [[0.0, 1.0], [1.0, 1.0], [0.5, 1.6]],
    ]
    blocks = read_dxf_blocks(path)
    assert blocks[0] == [0.0, 0.0, 1.0, 1.0] and blocks[1:] == [p.tolist() for p in polygons[1:]]
    with pytest.raises(md.InputError, match=r"LWPOLYLINE \(handle \w+\) on layer '0' has 3 corners"):
        read_dxf(path)  # a wall of rectangles only
    rect_path = _drawing(tmp_path, lambda msp: msp.add_lwpolyline([(0, 0), (400, 0), (400, 175), (0, 175)], close=True),
                         "wall.dxf")
    assert isinstance(read_dxf_blocks(rect_path), np.ndarray)
    assert read_dxf_blocks(rect_path).tolist() == read_dxf(rect_path).tolist() == [[0.0, 0.0, 0.4, 0.175]]
    # a case reads the drawing's polygons
    case = tmp_path / "case.toml"
    case.write_text('format = 1\n[geometry]\ndxf = "arch.dxf"\n')
    assert md.load_case(case).model.blocks == [[0.0, 0.0, 1.0, 1.0]] + [p.tolist() for p in polygons[1:]]


@pytest.mark.parametrize(
    "add, problem",
    [
        (lambda msp: msp.add_lwpolyline([(0, 0, 0), (400, 0, 0.4), (400, 175, 0), (0, 175, 0)], format="xyb",
                                        close=True),
         r"has arcs \(bulges\): a block has straight sides; explode its arcs to straight segments in CAD \[mm\]"),
        (lambda msp: msp.add_polyline2d([(0, 0), (400, 0), (400, 175), (0, 175)], close=True,
                                        dxfattribs={"layer": "0"}).vertices[1].dxf.set("bulge", 0.3),
         r"has arcs \(bulges\)"),
        (lambda msp: msp.add_lwpolyline([(0, 0), (400, 0), (400, 400), (200, 300), (0, 400)], close=True),
         r"vertex 3 \(200, 300\) is a re-entrant corner: the outline is not convex or crosses itself \(a concave "
         r"stone is given as convex parts\) \[mm\]"),
        (lambda msp: msp.add_lwpolyline([(0, 0), (400, 175), (400, 0), (0, 175)], close=True),
         r"vertex 1 \(400, 175\) is a re-entrant corner: the outline is not convex or crosses itself"),
        (lambda msp: msp.add_lwpolyline([(0, 0), (400, 0), (400, 175), (0, 175)]), "is not closed"),
    ],
)
def test_drawing_outlines_refused(tmp_path: Path, add, problem: str) -> None:
    from masonry_dem.dxf import read_dxf_polygons

    path = _drawing(tmp_path, add)
    with pytest.raises(md.InputError, match=r"arch\.dxf: (LWPOLYLINE|POLYLINE) \(handle \w+\) on layer '0' " + problem):
        read_dxf_polygons(path)
    case = tmp_path / "case.toml"
    case.write_text('format = 1\n[geometry]\ndxf = "arch.dxf"\n')
    outline = r"geometry\.dxf: .*arch\.dxf: (LWPOLYLINE|POLYLINE) \(handle \w+\)"
    with pytest.raises(md.InputError, match=outline) as info:
        md.load_case(case)
    assert info.value.key == "geometry.dxf"


def test_a_polygon_drawn_twice_is_refused(tmp_path: Path) -> None:
    from masonry_dem.dxf import read_dxf_polygons

    def add(msp) -> None:
        msp.add_lwpolyline([(0, 0), (400, 0), (200, 300)], close=True)
        msp.add_lwpolyline([(400, 0), (200, 300), (0, 0)], close=True)

    with pytest.raises(md.InputError, match="is the same polygon as LWPOLYLINE .*: a block drawn twice"):
        read_dxf_polygons(_drawing(tmp_path, add))


def test_a_study_mirrors_polygons_and_supports() -> None:
    from masonry_dem.case import ModelParameters
    from masonry_dem.study.model import mirrored

    model = ModelParameters(blocks=[[0.0, 0.0, 1.0, 1.0], [[0.0, 1.0], [1.0, 1.0], [0.5, 1.6]]],
                            supports=[[[1.0, 0.0], [2.0, 0.0], [1.0, 0.5]]], top_force=[3.0, -4.0])
    flipped = mirrored(model)  # x -> 2 - x (the extremes 0 and 2), each polygon still counter-clockwise
    assert flipped.blocks == [[1.0, 0.0, 2.0, 1.0], [[1.5, 1.6], [1.0, 1.0], [2.0, 1.0]]]
    assert flipped.supports == [[[1.0, 0.5], [0.0, 0.0], [1.0, 0.0]]]
    assert flipped.top_force == [-3.0, -4.0]
    assert all(polygon_problem(p) is None for p in flipped.blocks[1:] + flipped.supports)
    assert Shapes.from_polygons(flipped.blocks[1:] + flipped.supports).areas.tolist() == pytest.approx([0.3, 0.25])


# --------------------------------------------------------------------------------------------------
# The hinges of a mechanism
# --------------------------------------------------------------------------------------------------


def test_a_block_overturning_turns_about_its_toe() -> None:
    from masonry_dem.report import describe_hinges, hinges, summary

    b, h = 0.4, 1.2
    model = md.Model([[0.0, 0.0, b, h]], joints={"default": md.dry_joint(0.65, dilatancy=0.65)})
    results = model.solve_limit()
    found = hinges(model, results.mechanism)
    assert len(found) == 1 and found[0].end == "right" and found[0].point.tolist() == [b, 0.0]
    assert describe_hinges(model, results) == "1: the right end of a base joint at (0.40, 0.00) m"
    line = "\n  hinges:              1: the right end of a base joint at (0.40, 0.00) m\n"
    assert line in summary("b", model, results)
    # pushed the other way (the block's motion mirrored): the left end
    mirrored = results.mechanism * [-1.0, 1.0, -1.0]
    assert [(h.end, h.point.tolist()) for h in hinges(model, mirrored)] == [("left", [0.0, 0.0])]
    # a head joint turns about its bottom or top end
    pair = md.Model([[0.0, 0.0, 1.0, 1.0], [1.0, 0.0, 2.0, 1.0]], base=False)
    motion = np.zeros((2, 3))
    motion[1] = [0.5, 0.5, 1.0]  # the right block turning counter-clockwise about (1, 1): the head joint's top end
    assert [(h.end, h.point.tolist()) for h in hinges(pair, motion)] == [("top", [1.0, 1.0])]
    assert describe_hinges(pair, SimpleNamespace(mechanism=np.zeros((2, 3)))) == "none"


def test_an_arch_s_hinges_are_named_by_its_intrados_and_extrados() -> None:
    from masonry_dem.report import describe_hinges, hinges

    model = gable()
    results = rocking_gable_results(model)
    # the gable turns about the right end (1, 1) of its bed joint
    assert [(h.interface, h.end, h.point.tolist()) for h in hinges(model, results.mechanism)] == [(0, "right",
                                                                                                  [1.0, 1.0])]
    # as the joint of an arch whose intrados passes by (1, 1) and extrados by (0, 1)
    arch = {"intrados": [[1.2, 0.0], [1.0, 1.05], [0.8, 2.0]], "extrados": [[0.0, 1.0]]}
    assert [h.end for h in hinges(model, results.mechanism, arch)] == ["intrados"]
    assert describe_hinges(model, results, arch) == "1: the intrados of a bed joint at (1.00, 1.00) m"
    arch = {"intrados": arch["extrados"], "extrados": arch["intrados"]}
    assert describe_hinges(model, results, arch) == "1: the extrados of a bed joint at (1.00, 1.00) m"


# --------------------------------------------------------------------------------------------------
# Walls of polygons built by the core
# --------------------------------------------------------------------------------------------------


def test_a_case_of_polygons_builds_the_model_it_gives(tmp_path: Path) -> None:
    from masonry_dem.export import block_mesh

    path = tmp_path / "gable.toml"
    path.write_text(GABLE_CASE + '[base]\nkind = "fixed"\n')
    case = md.load_case(path)
    model = case.build_model()
    assert list(model.block_kinds) == ["wall", "wall", "wall", "support", "base"]
    assert model.support_indices == [3] and model.base_index == 4 and model.n_blocks == 3
    blocks = shapes(model)
    # the model's polygons are the case's, counter-clockwise from the lowest vertex (the leftmost of the lowest)
    assert blocks.polygon(1).tolist() == [[0.0, 1.0], [1.0, 1.0], [0.5, 1.6]]
    assert blocks.polygon(2).tolist() == [[1.5, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0], [1.0, 0.5]]
    assert blocks.areas[:4] == pytest.approx([1.0, 0.3, 0.875, 0.125], rel=1e-14)
    assert fixed_blocks(model) == [3, 4]
    results = case.run()
    assert results.status in ("collapse", "estimate")
    mesh = block_mesh(model, results)
    assert [c.type for c in mesh.cells] == ["quad", "triangle", "polygon", "triangle", "quad"]
    assert np.concatenate(mesh.cell_data["kind"]).tolist() == [0, 0, 0, 3, 1]


def test_a_drawing_of_polygons_is_the_case_of_the_same_polygons(tmp_path: Path) -> None:
    def add(msp) -> None:
        msp.add_lwpolyline([(0, 0), (1000, 0), (1000, 1000), (0, 1000)], close=True)
        msp.add_lwpolyline([(0, 1000), (1000, 1000), (500, 1600)], close=True)

    _drawing(tmp_path, add)
    drawn = tmp_path / "drawn.toml"
    drawn.write_text('format = 1\n[geometry]\ndxf = "arch.dxf"\n[joints]\nfriction = 2.0\ndilatancy = 2.0\n'
                     '[analysis]\nmethod = "limit"\n')
    given = tmp_path / "given.toml"
    given.write_text('format = 1\n[geometry]\nblocks = [[0, 0, 1, 1]]\npolygons = [[[0, 1], [1, 1], [0.5, 1.6]]]\n'
                     '[joints]\nfriction = 2.0\ndilatancy = 2.0\n[analysis]\nmethod = "limit"\n')
    a, b = md.load_case(drawn), md.load_case(given)
    assert a.model.blocks == b.model.blocks
    # the gable on the square: the two turn together about the square's toe, lambda = (1 - x_c) / y_c of both
    x_c = (1.0 * 0.5 + 0.3 * 0.5) / 1.3
    y_c = (1.0 * 0.5 + 0.3 * 1.2) / 1.3
    assert a.run().collapse_multiplier == pytest.approx((1.0 - x_c) / y_c, rel=1e-7)
