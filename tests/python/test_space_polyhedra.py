"""3D walls of convex polyhedra from Python and from case files: ``Model3D(polyhedra=..., supports=...)``, the case
keys ``[geometry] polyhedra`` and ``supports`` (docs/case-format.md, "3D walls") and their refusals, one line each, and
the outputs that carry each block's faces and each contact's polygon (plots, VTK, ``to_dict``); boxes give the files
they gave before."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path
from typing import Any, List

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem import assessment as sa
from masonry_dem.space import export as space_export
from masonry_dem.space.plot import contacts_figure, mechanism_figure
from masonry_dem.space.report import box_corners, describe_mechanism

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
SLOPE = EXAMPLES / "wedges-on-a-slope.toml"
PNG = b"\x89PNG\r\n\x1a\n"
MU, ALPHA = 0.8, math.radians(10.0)  # the example's friction and slope


def cube(x: float, y: float, z: float, a: float) -> List[List[float]]:
    """The eight corners of the cube of side a from (x, y, z)."""
    return [[x + a * (i & 1), y + a * (i >> 1 & 1), z + a * (i >> 2 & 1)] for i in range(8)]


def slope_model() -> Any:
    return md.load_case(SLOPE).build_model()


# --------------------------------------------------------------------------------------------------
# The model from vertex lists
# --------------------------------------------------------------------------------------------------


def test_polyhedra_and_supports_from_vertex_lists() -> None:
    model = slope_model()
    assert model.n_blocks == 2 and model.base_index is None and model.top_index is None  # supports: no base
    assert list(model.block_is_box) == [False, False, False]
    # the stone: a prism of 1 m along y whose section is the trapezoid (0, 0), (1, tan 10), (1, 0.5), (0, 0.5); the
    # turned block: 0.9 x 0.9 x 0.5 m; density 2400 kg/m3
    t = math.tan(ALPHA)
    assert model.mass[0] == pytest.approx(2400.0 * (0.5 - 0.5 * t), rel=1e-12)
    assert model.mass[1] == pytest.approx(2400.0 * 0.405, rel=1e-12)
    x_stone = (0.5 * 0.5 - t / 3.0) / (0.5 - 0.5 * t)  # the trapezoid: its rectangle less a triangle (x = 2 / 3)
    assert model.centroids[0][0] == pytest.approx(x_stone, rel=1e-12)
    assert model.centroids[1] == pytest.approx([0.5, 0.5, 0.75], rel=1e-12)
    # each block keeps its eight corners and six faces, each face counter-clockwise seen from outside
    for vertices, faces in zip(model.block_vertices, model.block_faces):
        assert len(vertices) == 8 and len(faces) == 6
        centre = vertices.mean(axis=0)
        for face in faces:
            p = vertices[face]
            normal = np.cross(p[1] - p[0], p[2] - p[1])
            assert normal @ (p[0] - centre) > 0
    # the turned block stands on an octagon of the stone's top (the square's corners cut off), the stone on the slope
    polygons = model.interface_polygons
    assert [len(p) for p in polygons] == [8, 4]
    assert list(model.interface_family) == ["bed", "base"]
    half = 0.45 * math.sqrt(2.0)  # the turned square's half diagonal: its corners 0.136 m past the stone's sides
    octagon = 1.0 - 2.0 * (1.0 - half) ** 2  # the unit square less four corner triangles of legs 1 - half
    assert model.interface_areas[0] == pytest.approx(octagon, rel=1e-12)
    assert model.interface_areas[1] == pytest.approx(1.0 / math.cos(ALPHA), rel=1e-12)
    # interface_corners keeps its shape (m, 4, 3): a polygon of eight corners is cut to four there
    assert np.asarray(model.interface_corners).shape == (2, 4, 3)


def test_blocks_slide_down_the_slope_at_the_closed_form() -> None:
    model = slope_model()
    results = model.solve_limit(tolerance=1e-12)
    assert results.status == "collapse"
    want = (MU - math.tan(ALPHA)) / (1.0 + MU * math.tan(ALPHA))  # tan(phi - alpha)
    assert results.collapse_multiplier == pytest.approx(want, rel=1e-9)
    # both blocks translate together, down the slope and off it at phi (associative sliding): at phi - alpha to x
    mech = np.asarray(results.mechanism)[:2]
    assert np.allclose(mech[0], mech[1], atol=1e-8)
    v = mech[0, :3]
    assert abs(v[1]) < 1e-8 and v[0] < 0
    assert math.atan2(v[2], -v[0]) == pytest.approx(math.atan(MU) - ALPHA, rel=1e-7)
    assert "2 of 2 blocks move as one part, sliding towards -x" in describe_mechanism(model, results)
    # the linear kinematic check: every weight moves alike, e* = 1 and M* is the blocks' mass
    check = sa.linear_check(model, results, sa.ec8_spectrum(0.25 * 9.80665, "B"))
    assert check.moving_blocks == 2
    assert check.mass_fraction == pytest.approx(1.0, rel=1e-9)
    assert check.participating_mass == pytest.approx(model.mass[0] + model.mass[1], rel=1e-9)


def test_a_model_of_boxes_and_polyhedra_numbers_them_in_that_order() -> None:
    # a box, and a cube given by its corners beside it on the base: the same block, the polyhedron after the box
    model = md.Model3D([[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]], polyhedra=[cube(1.0, 0.0, 0.0, 1.0)], joints={
        "default": md.dry_joint(0.7, dilatancy=0.7)})
    assert model.n_blocks == 2 and model.base_index == 2  # boxes given: the base by default
    assert list(model.block_is_box) == [True, True, True]  # the hull of a cube's corners is a box
    assert [len(p) for p in model.interface_polygons] == [4, 4, 4]
    results = model.solve_limit(tolerance=1e-12)
    # the two cubes slide together on the base (lambda = mu = 0.7), below their turning as one (b / h = 2)
    assert results.collapse_multiplier == pytest.approx(0.7, rel=1e-9)


def test_convex_hulls_drop_inner_and_repeated_vertices() -> None:
    wedge = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [0.2, 0.2, 0.0], [0.1, 0.1, 0.1], [1, 0, 0]]
    (vertices, faces), = md._core.convex_hulls([wedge])
    assert len(vertices) == 4 and len(faces) == 4


@pytest.mark.parametrize("polyhedra, words", [
    ([[[0, 0, 0], [1, 0, 0], [0, 1, 0]]], "polyhedra[0]: fewer than 4 vertices off one plane"),
    ([cube(0, 0, 0, 1), [[0, 0, 1], [1, 0, 1], [0, 1, 1], [1, 1, 1], [0.5, 0.5, 1.0]]],
     "polyhedra[1]: fewer than 4 vertices off one plane: it has no volume (5 distinct of the 5 given)"),
    ([[[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, float("nan")]]], "polyhedra[0]: vertex 3 (0, 0, NaN): coordinate NaN is "
                                                                 "not finite"),
    ([[[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0]]], "polyhedra[0][3]: expected a vertex [x, y, z] of 3 numbers, got 2"),
    ([cube(0, 0, 0, 1), cube(0, 0, 1, 1) + [[0.5, 0.5, 1.5]] * 100],
     "polyhedra[1]: 108 vertices: a block takes at most 100 (its hull is found by the planes"),
    ([cube(0, 0, 0, 1), cube(0.5, 0.5, 0.5, 1)], "block 0 (polyhedron of 8 vertices"),
])
def test_refusals_name_the_block(polyhedra: Any, words: str) -> None:
    with pytest.raises(md.InputError) as info:
        md.Model3D(polyhedra=polyhedra)
    text = str(info.value)
    assert "\n" not in text and words in text, text
    if "overlap" in text or words.startswith("block 0"):
        assert "and block 1 (polyhedron of 8 vertices" in text and "overlap" in text


def test_a_support_that_makes_no_block_is_refused() -> None:
    with pytest.raises(md.InputError, match=r"^supports\[0\]: fewer than 4 vertices off one plane") as info:
        md.Model3D(polyhedra=[cube(0, 0, 0, 1)], supports=[[[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]])
    assert info.value.key == "supports"


# --------------------------------------------------------------------------------------------------
# Case files
# --------------------------------------------------------------------------------------------------

CASE = """format = 1
[geometry]
{geometry}
[joints]
friction = 0.7
dilatancy = 0.7
"""


def test_case_keys_polyhedra_and_supports() -> None:
    case = md.load_case(SLOPE)
    assert case.dimension == 3 and case.model.base is False and len(case.model.polyhedra) == 2
    assert len(case.model.supports) == 1 and case.model.boxes.shape == (0, 6)
    # boxes beside polyhedra, and a base asked for beside supports
    text = CASE.format(geometry="boxes = [[0, 0, 0, 1, 1, 1]]\npolyhedra = [" + str(cube(1, 0, 0, 1)) + "]\n"
                       "supports = [" + str(cube(0, 0, -1, 2)) + "]") + '[base]\nkind = "fixed"\n'
    both = md.parse_case(text, source="c.toml")
    assert both.model.base is True and both.model.boxes.shape == (1, 6) and len(both.model.polyhedra) == 1
    # coordinates are lengths: a unit may be given
    units = md.parse_case(CASE.format(geometry='polyhedra = [[[0, 0, 0], ["1000 mm", 0, 0], [0, "100 cm", 0], '
                                               '[0, 0, 1]]]'), source="c.toml")
    assert units.model.polyhedra == [[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]]


@pytest.mark.parametrize("geometry, words", [
    ("polyhedra = [[[0, 0, 0], [1, 0, 0], [0, 1, 0]]]",
     "c.toml: geometry.polyhedra[0]: fewer than 4 vertices off one plane"),
    ("polyhedra = [[[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, nan]]]", "c.toml: geometry.polyhedra[0][3]"),
    ("polyhedra = [[[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0]]]", "c.toml: geometry.polyhedra[0][3]"),
    ("polyhedra = []", "c.toml: geometry.polyhedra: expected at least one block"),
    ("polyhedra = [[[0, 0, 1], [1, 0, 1], [0, 1, 1], [0, 0, 2]]]\nsupports = [[[0, 0, 0], [1, 0, 0], [0, 1, 0]]]",
     "c.toml: geometry.supports[0]: fewer than 4 vertices off one plane"),
    ("polyhedra = [[[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]]\n[geometry.leaf]\nlength = 1\nheight = 1\n"
     "thickness = 0.1\nblock_length = 0.5\nblock_height = 0.25", "(boxes and polyhedra may be given together); leaf and polyhedra are both given"),
])
def test_case_refusals_name_the_key(geometry: str, words: str) -> None:
    with pytest.raises(md.InputError) as info:
        md.parse_case(CASE.format(geometry=geometry), source="c.toml")
    assert words in str(info.value) and "\n" not in str(info.value), str(info.value)


def test_command_line_refuses_overlapping_polyhedra_in_one_line(tmp_path: Path) -> None:
    case = tmp_path / "overlap.toml"
    case.write_text(CASE.format(geometry=f"polyhedra = [{cube(0, 0, 0, 1)}, {cube(0.5, 0.5, 0.5, 1)}]"))
    proc = subprocess.run([sys.executable, "-m", "masonry_dem", "run", str(case)], cwd=tmp_path, capture_output=True,
                          text=True, timeout=600)
    assert proc.returncode == 2 and proc.stdout == ""
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in proc.stderr, proc.stderr
    assert "block 0 (polyhedron of 8 vertices" in lines[0] and "block 1 (polyhedron" in lines[0]
    assert "overlap" in lines[0]


# --------------------------------------------------------------------------------------------------
# Outputs
# --------------------------------------------------------------------------------------------------


def test_the_example_runs_with_its_figures_and_vtk(tmp_path: Path) -> None:
    out = tmp_path / "slope"
    proc = subprocess.run([sys.executable, "-m", "masonry_dem", "run", str(SLOPE), "--plot", str(out) + ".png",
                           "--vtk", str(out), "--json", str(out) + ".json"], cwd=tmp_path, capture_output=True,
                          text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    assert "collapse multiplier: 0.5466" in proc.stdout
    assert (tmp_path / "slope.png").read_bytes().startswith(PNG)
    import meshio

    blocks = meshio.read(tmp_path / "slope-blocks.vtu")
    model = slope_model()
    # one polyhedron cell per block (the support too), of its own eight vertices and six faces
    assert [c.type for c in blocks.cells] == ["polyhedron8"] and len(blocks.cells[0].data) == 3
    assert all(len(cell) == 6 for cell in blocks.cells[0].data)
    assert np.allclose(blocks.points, np.concatenate(model.block_vertices))
    assert list(blocks.cell_data["kind"][0]) == [0, 0, 3]  # the support: 3, as in the plane
    faces = meshio.read(tmp_path / "slope-interfaces.vtu")
    assert [(c.type, len(c.data[0])) for c in faces.cells] == [("polygon", 8), ("quad", 4)]
    assert np.allclose(faces.points, np.concatenate(model.interface_polygons))
    assert [list(d) for d in faces.cell_data["interface"]] == [[0], [1]]


def test_vtk_cells_keep_the_contacts_order_in_runs_of_equal_corners() -> None:
    # a turned cube on a box, and a box beside it on the base: an octagon, quads, then the quads with the base
    turned = [[1.5 + 0.45 * math.sqrt(2) * math.cos(a), 0.5 + 0.45 * math.sqrt(2) * math.sin(a), z]
              for a in np.radians([0, 90, 180, 270]) for z in (1.0, 1.5)]
    model = md.Model3D([[1, 0, 0, 2, 1, 1], [0, 0, 0, 1, 1, 1]], polyhedra=[turned],
                       joints={"default": md.dry_joint(0.7, dilatancy=0.7)})
    results = model.solve_limit()
    mesh = space_export.interface_mesh(model, results)
    sizes = [len(p) for p in model.interface_polygons]
    assert sorted(sizes) != sizes or len(set(sizes)) > 1
    got = [len(row) for block in mesh.cells for row in block.data]
    assert got == sizes
    assert list(np.concatenate(mesh.cell_data["interface"])) == list(range(len(sizes)))
    states = np.concatenate(mesh.cell_data["state"])
    assert list(states) == [int(s) for s in np.asarray(results.interface_states)]


def test_boxes_give_the_meshes_they_gave_before() -> None:
    # the U wall: hexahedra of the boxes' corners in VTK's order, quads of the contacts' rectangles, as before
    case = md.load_case(EXAMPLES / "u-wall.toml")
    model = case.build_model()
    results = model.solve_limit()
    blocks = space_export.block_mesh(model, results)
    boxes = np.asarray(model.boxes)
    corners = box_corners(boxes)
    n = len(boxes)
    assert [c.type for c in blocks.cells] == ["hexahedron"]
    assert np.array_equal(blocks.cells[0].data, np.arange(8 * n).reshape(n, 8))
    assert np.array_equal(blocks.points, corners.reshape(-1, 3))
    mech = np.asarray(results.mechanism)
    r = corners - np.asarray(model.centroids)[:, None, :]
    want = (mech[:, None, :3] + np.cross(mech[:, None, 3:], r)).reshape(-1, 3)
    assert np.array_equal(blocks.point_data["mechanism"], want)
    faces = space_export.interface_mesh(model, results)
    m = model.n_interfaces
    assert [c.type for c in faces.cells] == ["quad"]
    assert np.array_equal(faces.cells[0].data, np.arange(4 * m).reshape(m, 4))
    assert np.array_equal(faces.points, np.asarray(model.interface_corners).reshape(-1, 3))


def test_figures_of_polyhedra(tmp_path: Path) -> None:
    model = slope_model()
    results = model.solve_limit()
    for make, name in ((mechanism_figure, "mechanism.png"), (contacts_figure, "contacts.png")):
        make(model, results, title="slope", path=tmp_path / name)
        assert (tmp_path / name).read_bytes().startswith(PNG)
    # the explicit solver's deformed shape on the same page when there is no mechanism to draw
    from matplotlib.figure import Figure

    fig = Figure()
    ax = fig.add_subplot(projection="3d")
    counts = md.space.plot.plot_contacts_3d(ax, model, results)
    assert counts["sliding"] == 1 and counts["elastic"] == 1
    with pytest.raises(md.InputError, match="field"):
        md.space.plot.plot_mechanism_3d(fig.add_subplot(projection="3d"), model, results, field="velocity")


def test_to_dict_carries_the_faces_and_polygons() -> None:
    model = slope_model()
    out = md.to_dict(model.solve_limit(), model=model)
    assert [len(v) for v in out["block_vertices"]] == [8, 8, 8]
    assert [len(f) for f in out["block_faces"]] == [6, 6, 6]
    assert [len(p) for p in out["interface_polygons"]] == [8, 4]
    assert out["block_boxes"] and out["interface_areas"]  # the keys of before are kept


def test_a_3d_time_history_is_a_vtk_series(tmp_path: Path) -> None:
    # a block rocking from an initial rotation rate: one blocks file per record, the vertices' displacement the
    # rigid motion of the record (the rotation vector applied exactly), and the .pvd listing them with their times
    model = md.Model3D([[0.0, 0.0, 0.0, 0.4, 0.3, 1.2]], joints={"default": md.dry_joint(0.7)})
    history = model.simulate(0.05, initial_velocities=[[0, 0, 0, 0, 0.5, 0], [0] * 6], record_every=200)
    pvd, paths = md.write_vtk(model, history, tmp_path / "rock")
    assert pvd == tmp_path / "rock.pvd" and len(paths) == len(history.times) >= 3
    text = pvd.read_text()
    assert text.count("<DataSet ") == len(paths) and f'file="{paths[-1].name}"' in text
    import meshio

    last = meshio.read(paths[-1])
    u = np.asarray(history.displacements)[-1]
    assert np.allclose(last.cell_data["rotation"][0], u[:, 3:])
    angle = np.linalg.norm(u[0, 3:])
    assert angle > 1e-3
    # a vertex's displacement: the centroid's plus (R - I) r, R the rotation by angle about u[0, 3:]
    axis = u[0, 3:] / angle
    r = last.points[:8] - np.asarray(model.centroids)[0]
    turned = r * math.cos(angle) + np.cross(axis, r) * math.sin(angle) + np.outer(r @ axis, axis) * (1 - math.cos(angle))
    assert np.allclose(last.point_data["displacement"][:8], u[0, :3] + turned - r, atol=1e-12)
    assert list(last.cell_data["kind"][0]) == [0, 1]
    with pytest.raises(md.InputError, match="^write_vtk: model does not match results"):
        md.write_vtk(slope_model(), history, tmp_path / "other")


def test_supports_are_kind_3_as_in_the_plane() -> None:
    model = md.Model3D(polyhedra=[cube(0, 0, 0, 1)], supports=[cube(1, 0, 0, 1)], base=True, top=0.2,
                       joints={"default": md.dry_joint(0.7, dilatancy=0.7)})
    mesh = space_export.block_mesh(model, model.solve_limit())
    assert model.base_index == 1 and model.top_index == 2
    assert list(mesh.cell_data["kind"][0]) == [0, 1, 2, 3]


def test_a_polyhedron_carries_a_load_and_the_check_weighs_it_apart() -> None:
    # the example's turned block carries a floor's 5 kN over a corner of the stone: its mass and centre of mass take
    # it, and the linear check weighs the block at its own centroid and the load at its point
    plain = slope_model()
    case = md.load_case(SLOPE)
    case.model_kwargs["carried"] = [(1, [0.8, 0.5, 1.0], 5000.0)]
    loaded = case.build_model()
    g = loaded.gravity
    assert loaded.mass[1] == pytest.approx(plain.mass[1] + 5000.0 / g, rel=1e-12)
    want = (plain.mass[1] * np.asarray(plain.centroids[1]) + 5000.0 / g * np.array([0.8, 0.5, 1.0])) / loaded.mass[1]
    assert np.allclose(loaded.centroids[1], want, rtol=1e-12)
    lumped = sa.mechanism_weights(loaded, loaded.solve_limit(tolerance=1e-11))
    assert list(lumped.blocks) == [0, 1, 1]
    assert np.allclose(lumped.points, [plain.centroids[0], plain.centroids[1], [0.8, 0.5, 1.0]], atol=1e-12)
    assert np.allclose(lumped.weights, [plain.weights[0], plain.weights[1], 5000.0], rtol=1e-12)
