"""Exports: VTK (.vtu) of the blocks and the interfaces, CSV of the curve, and the command-line options."""

from __future__ import annotations

from pathlib import Path

import meshio
import numpy as np
import pytest

import masonry_dem as md
from masonry_dem import cli
from masonry_dem.export import CSV_HEADER, write_curve_csv, write_vtk

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="module")
def stack() -> tuple:
    case = md.load_case(EXAMPLES / "stack-3-blocks.toml")
    model = case.build_model()
    return model, case.solve(model)


def test_vtk_blocks(tmp_path: Path, stack: tuple) -> None:
    model, results = stack
    blocks_path, faces_path = write_vtk(model, results, tmp_path / "out" / "s")
    assert blocks_path == tmp_path / "out" / "s-blocks.vtu"
    assert faces_path == tmp_path / "out" / "s-interfaces.vtu"
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["s-blocks.vtu", "s-interfaces.vtu"]

    mesh = meshio.read(blocks_path)
    rects = np.asarray(model.rects)
    n = len(rects)
    assert [c.type for c in mesh.cells] == ["quad"] and mesh.cells[0].data.shape == (n, 4)
    assert mesh.points.shape == (4 * n, 3)
    # each quad spans its rectangle, counterclockwise, at z = 0
    corners = mesh.points[mesh.cells[0].data]
    np.testing.assert_allclose(corners[:, 0, :2], rects[:, :2])
    np.testing.assert_allclose(corners[:, 2, :2], rects[:, 2:])
    assert np.all(corners[..., 2] == 0)
    data = {k: v[0] for k, v in mesh.cell_data.items()}
    assert set(data) >= {"displacement", "rotation", "mechanism", "kind"}
    assert data["displacement"].shape == (n, 3) and data["mechanism"].shape == (n, 3)
    assert data["rotation"].shape == (n,) and data["kind"].shape == (n,)
    np.testing.assert_allclose(data["displacement"][:, :2], results.displacements[:, :2])
    np.testing.assert_allclose(data["rotation"], results.displacements[:, 2])
    np.testing.assert_allclose(data["mechanism"][:, :2], results.mechanism[:, :2])
    assert np.all(data["displacement"][:, 2] == 0)
    kind = np.zeros(n, dtype=int)
    if model.base_index is not None:
        kind[model.base_index] = 1
    if model.top_index is not None:
        kind[model.top_index] = 2
    np.testing.assert_array_equal(data["kind"], kind)
    assert mesh.point_data["displacement"].shape == (4 * n, 3)


def test_vtk_interfaces(tmp_path: Path, stack: tuple) -> None:
    model, results = stack
    _, faces_path = write_vtk(model, results, str(tmp_path / "s.vtu"))  # a trailing .vtu is dropped
    assert faces_path.name == "s-interfaces.vtu"
    mesh = meshio.read(faces_path)
    geom = np.asarray(model.interface_geometry)
    m = len(geom)
    assert [c.type for c in mesh.cells] == ["line"] and mesh.cells[0].data.shape == (m, 2)
    ends = mesh.points[mesh.cells[0].data][..., :2]
    np.testing.assert_allclose(ends.mean(axis=1), geom[:, :2], atol=1e-12)  # centred on the centroid
    np.testing.assert_allclose(np.linalg.norm(ends[:, 1] - ends[:, 0], axis=1), geom[:, 4])  # length l
    t = np.c_[geom[:, 3], -geom[:, 2]]  # along t = (ny, -nx)
    np.testing.assert_allclose(ends[:, 1] - ends[:, 0], t * geom[:, 4:5], atol=1e-12)
    data = {k: v[0] for k, v in mesh.cell_data.items()}
    for key in ("normal_force", "shear_force", "moment", "state", "broken"):
        assert data[key].shape == (m,), key
    np.testing.assert_allclose(data["normal_force"], results.interface_forces[:, 0])
    np.testing.assert_allclose(data["shear_force"], results.interface_forces[:, 1])
    np.testing.assert_allclose(data["moment"], results.interface_forces[:, 2])
    np.testing.assert_array_equal(data["state"], results.interface_states)
    np.testing.assert_array_equal(data["broken"], np.asarray(results.broken, dtype=int))


def test_curve_csv(tmp_path: Path, stack: tuple) -> None:
    _, results = stack
    path = write_curve_csv(results, tmp_path / "c" / "curve.csv")
    assert path.read_text().splitlines()[0] == CSV_HEADER == "multiplier,displacement_m"
    table = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    assert table.shape == (len(results.curve_multiplier), 2)
    np.testing.assert_array_equal(table[:, 0], results.curve_multiplier)  # exact: 17 digits
    np.testing.assert_array_equal(table[:, 1], results.curve_displacement)
    names = np.genfromtxt(path, delimiter=",", names=True).dtype.names
    assert names == ("multiplier", "displacement_m")
    assert [p.name for p in (tmp_path / "c").iterdir()] == ["curve.csv"]  # no temporary file left


def test_failed_write_leaves_nothing(tmp_path: Path, stack: tuple, monkeypatch: pytest.MonkeyPatch) -> None:
    """A write that fails leaves neither a half file nor a temporary one; an old file stays as it was."""
    model, results = stack

    class Bad:
        curve_multiplier = np.array([0.0, 1.0])
        curve_displacement = np.array([0.0])

    with pytest.raises(ValueError):
        write_curve_csv(Bad(), tmp_path / "bad.csv")
    assert list(tmp_path.iterdir()) == []

    (tmp_path / "old.csv").write_text("old\n")

    def no_rename(src: str, dst: str) -> None:
        raise OSError(28, "No space left on device")

    monkeypatch.setattr("masonry_dem.export.os.replace", no_rename)
    with pytest.raises(OSError):
        write_curve_csv(results, tmp_path / "old.csv")
    with pytest.raises(OSError):
        write_vtk(model, results, tmp_path / "w")
    assert [p.name for p in tmp_path.iterdir()] == ["old.csv"]
    assert (tmp_path / "old.csv").read_text() == "old\n"


def test_cli_vtk_csv(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    prefix, csv, png = tmp_path / "v" / "rock", tmp_path / "rock.csv", tmp_path / "rock.png"
    status = cli.main(
        [
            "run",
            str(EXAMPLES / "single-block-rocking.toml"),
            "--vtk",
            str(prefix),
            "--csv",
            str(csv),
            "--plot",
            str(png),
            "--quiet",
        ]
    )
    assert status == 0
    out = capsys.readouterr().out
    for name in ("rock-blocks.vtu", "rock-interfaces.vtu", "rock.csv", "rock.png"):
        assert name in out
    assert len(meshio.read(tmp_path / "v" / "rock-blocks.vtu").cells[0].data) == 2  # the block and the base
    assert np.loadtxt(csv, delimiter=",", skiprows=1).shape[1] == 2
    assert png.read_bytes().startswith(b"\x89PNG")
