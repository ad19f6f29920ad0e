"""Time histories (Model.simulate) as results: the CSV, the VTK time series and the report figure, each checked
against the TimeHistory's own arrays; the Results paths of the same functions are unchanged (test_export.py,
test_plot.py)."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any, Tuple

import meshio
import numpy as np
import pytest
from matplotlib.figure import Figure

import masonry_dem as md
from masonry_dem.export import CSV_HEADER, HISTORY_CSV_HEADER
from masonry_dem.history import ENERGIES, default_control_block, peak_record
from masonry_dem.plot import report_figure

G = 9.81


def rocking_block() -> md.Model:
    """A 0.4 x 1.0 m block on a fixed base (the README's rocking example)."""
    return md.Model(np.array([[0.0, 0.0, 0.4, 1.0]]), gravity=G, joints={"default": {"friction": 2.0}})


@pytest.fixture(scope="module")
def rocking() -> Tuple[md.Model, Any]:
    """The block released from rest tilted by 0.1 rad about its left toe: it rocks back (a few records)."""
    model = rocking_block()
    tilt = 0.1
    u0 = np.zeros((len(model.rects), 3))
    u0[0] = [0.2 * math.cos(tilt) - 0.5 * math.sin(tilt) - 0.2, 0.2 * math.sin(tilt) + 0.5 * math.cos(tilt) - 0.5, tilt]
    history = model.simulate(0.12, initial_displacements=u0, record_interval=0.015)
    assert history.status == "completed", history.error
    assert 4 <= len(history.times) <= 12
    return model, history


@pytest.fixture(scope="module")
def at_rest() -> Tuple[md.Model, Any]:
    """A squat block under a small live load (lambda 0.1, below friction and rocking): it stays put."""
    model = md.Model(np.array([[0.0, 0.0, 0.4, 0.175]]), gravity=G)
    history = model.simulate(0.005, live_multiplier=0.1, record_every=20)
    assert history.status == "completed", history.error
    assert len(history.times) >= 2
    return model, history


def expected_rows(model: md.Model, history: Any) -> np.ndarray:
    c = default_control_block(model)
    disp = history.displacements
    columns = [history.times, disp[:, c, 0], disp[:, c, 2], np.hypot(disp[..., 0], disp[..., 1]).max(axis=1)]
    return np.column_stack(columns + [getattr(history, name) for name in ENERGIES])


def test_default_control_block_is_the_solvers() -> None:
    wall = md.Model(md.pattern(0.3, 0.25, [[1, 1], [1, 1]]), gravity=G)
    beam = md.Model(md.pattern(0.3, 0.25, [[1, 1], [1, 1]]), gravity=G, top_rotation="fixed", live="top_horizontal")
    for model in (wall, beam, rocking_block()):
        res = model.solve_static(control="displacement", max_displacement=1e-5, steps=2)
        assert default_control_block(model) == res.control_block
    assert default_control_block(beam) == beam.top_index
    assert default_control_block(wall) == 3  # the upper right block


@pytest.mark.parametrize("case", ["rocking", "at_rest"])
def test_curve_csv_of_a_time_history(tmp_path: Path, case: str, request: pytest.FixtureRequest) -> None:
    model, history = request.getfixturevalue(case)
    path = md.write_curve_csv(history, tmp_path / "sub" / "h.csv", model=model)
    assert path == tmp_path / "sub" / "h.csv"
    lines = path.read_text(encoding="ascii").splitlines()
    assert lines[0] == HISTORY_CSV_HEADER
    assert lines[0].split(",") == [
        "time_s", "displacement_m", "rotation_rad", "max_translation_m",
        "kinetic_energy_J", "elastic_energy_J", "external_work_J", "gravity_work_J", "friction_dissipation_J",
        "damping_dissipation_J", "impact_dissipation_J", "dissipated_J", "energy_error_J",
    ]
    rows = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    # one row per recorded time, every number read back exactly
    np.testing.assert_array_equal(rows, expected_rows(model, history))


def test_curve_csv_of_a_time_history_needs_the_model(tmp_path: Path, rocking: Tuple[md.Model, Any]) -> None:
    _, history = rocking
    with pytest.raises(TypeError, match="model="):
        md.write_curve_csv(history, tmp_path / "h.csv")
    assert not (tmp_path / "h.csv").exists()


def test_rocking_csv_moves(tmp_path: Path, rocking: Tuple[md.Model, Any]) -> None:
    """The released block turns back towards upright: the rotation column falls from the tilt."""
    model, history = rocking
    rows = np.loadtxt(md.write_curve_csv(history, tmp_path / "h.csv", model=model), delimiter=",", skiprows=1)
    assert rows[0, 2] == 0.1 and rows[-1, 2] < 0.1
    assert rows[-1, 4] > 0  # kinetic energy gained


def test_vtk_series_of_a_time_history(tmp_path: Path, rocking: Tuple[md.Model, Any]) -> None:
    model, history = rocking
    k = len(history.times)
    pvd, blocks = md.write_vtk(model, history, tmp_path / "out" / "r.vtu")
    assert pvd == tmp_path / "out" / "r.pvd"
    assert blocks == [tmp_path / "out" / f"r-blocks-{i:04d}.vtu" for i in range(k)]
    # with the contact update (simulate's default), a contacts file per record too
    contacts = [f"r-contacts-{i:04d}.vtu" for i in range(k)]
    assert history.contact_counts[0] > 0
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == sorted([pvd.name] + [b.name for b in blocks] + contacts)

    root = ET.parse(pvd).getroot()
    assert root.tag == "VTKFile" and root.get("type") == "Collection"
    datasets = root.findall("./Collection/DataSet")
    assert [d.get("file") for d in datasets] == [b.name for b in blocks] + contacts
    assert [d.get("part") for d in datasets] == ["0"] * k + ["1"] * k
    np.testing.assert_array_equal([float(d.get("timestep", "nan")) for d in datasets[:k]], history.times)
    np.testing.assert_array_equal([float(d.get("timestep", "nan")) for d in datasets[k:]], history.times)

    rects = np.asarray(model.rects)
    n = len(rects)
    kind = np.zeros(n, dtype=int)
    kind[model.base_index] = 1
    for i, path in enumerate(blocks):
        mesh = meshio.read(path)
        assert mesh.cells[0].type == "quad" and mesh.cells[0].data.shape == (n, 4)
        data = {name: values[0] for name, values in mesh.cell_data.items()}
        assert set(data) == {"displacement", "rotation", "velocity", "angular_velocity", "kind", "block"}
        np.testing.assert_array_equal(data["displacement"][:, :2], history.displacements[i, :, :2])
        np.testing.assert_array_equal(data["rotation"], history.displacements[i, :, 2])
        np.testing.assert_array_equal(data["velocity"][:, :2], history.velocities[i, :, :2])
        np.testing.assert_array_equal(data["angular_velocity"], history.velocities[i, :, 2])
        assert np.all(data["displacement"][:, 2] == 0) and np.all(data["velocity"][:, 2] == 0)
        np.testing.assert_array_equal(data["kind"], kind)
        # the corners moved as a rigid body: rotated exactly about the centroid
        u1, u2, phi = history.displacements[i, 0]
        x0, y0, x1, y1 = rects[0]
        centroid = np.array([(x0 + x1) / 2, (y0 + y1) / 2])
        r = mesh.points[mesh.cells[0].data[0], :2] - centroid
        rot = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
        moved = centroid + np.array([u1, u2]) + r @ rot.T
        corner_u = mesh.point_data["displacement"][mesh.cells[0].data[0], :2]
        np.testing.assert_allclose(mesh.points[mesh.cells[0].data[0], :2] + corner_u, moved, atol=1e-12)


def test_vtk_series_refuses_an_input(tmp_path: Path, at_rest: Tuple[md.Model, Any]) -> None:
    model, history = at_rest
    case = tmp_path / "r.pvd"
    case.write_text("keep")
    with pytest.raises(md.InputError):
        md.write_vtk(model, history, tmp_path / "r", inputs=[case])
    assert case.read_text() == "keep"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.pvd"]


def test_report_figure_of_a_time_history(tmp_path: Path, rocking: Tuple[md.Model, Any]) -> None:
    model, history = rocking
    fig = report_figure(model, history, title="rocking block", path=tmp_path / "r")
    assert isinstance(fig, Figure)
    assert (tmp_path / "r.png").stat().st_size > 10_000
    assert "time history, completed" in fig.get_suptitle() and "rocking block" in fig.get_suptitle()
    wall, ax_u, ax_phi = fig.axes
    k = peak_record(model, history)
    assert k == int(np.argmax(np.abs(history.displacements[:, 0, 0])))
    assert f"t = {history.times[k]:.4g} s" in wall.get_title()
    # the curves are the control block's displacement [mm] and rotation [rad] against time, the peak marked
    line_u, mark_u = ax_u.get_lines()[0], ax_u.get_lines()[-1]
    np.testing.assert_array_equal(line_u.get_xdata(), history.times)
    np.testing.assert_array_equal(line_u.get_ydata(), history.displacements[:, 0, 0] * 1e3)
    np.testing.assert_array_equal(mark_u.get_xdata(), [history.times[k]])
    line_phi = ax_phi.get_lines()[0]
    np.testing.assert_array_equal(line_phi.get_ydata(), history.displacements[:, 0, 2])
    assert "displacement [mm]" in ax_u.get_ylabel() and "rotation [rad]" in ax_phi.get_ylabel()


def test_results_paths_unchanged(tmp_path: Path) -> None:
    """A Results still gives its two .vtu files, its curve CSV and the four-panel report."""
    model = md.Model(md.pattern(0.3, 0.5, [[1], [1]]), gravity=G)
    res = model.solve_static(control="displacement", max_displacement=1e-4, steps=3)
    blocks, faces = md.write_vtk(model, res, tmp_path / "s")
    assert (blocks.name, faces.name) == ("s-blocks.vtu", "s-interfaces.vtu")
    assert "mechanism" in meshio.read(blocks).cell_data
    csv = md.write_curve_csv(res, tmp_path / "c.csv")
    lines = csv.read_text().splitlines()
    assert lines[0] == CSV_HEADER and len(lines) == 1 + len(res.curve_multiplier)
    rows = np.loadtxt(csv, delimiter=",", skiprows=1, ndmin=2)
    np.testing.assert_array_equal(rows, np.column_stack([res.curve_multiplier, res.curve_displacement]))
    fig = report_figure(model, res, path=tmp_path / "f.png")
    assert len(fig.axes) >= 4
