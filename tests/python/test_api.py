"""The Python API helpers: joint laws from mortar properties, and the conversions of a Results."""

from __future__ import annotations

import json
import math
import os
import sys
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem import api
from masonry_dem.case import result_dict

LAW_KEYS = {"normal_stiffness", "shear_stiffness", "friction", "cohesion", "tensile_strength", "dilatancy"}

# One block 0.4 m x 0.2 m x 1 m on a fixed base: it slides (at mu + c A / W) long before it overturns (b/h = 2).
BLOCK = [[0.0, 0.0, 0.4, 0.2]]
COHESION = 10.0  # [Pa], small against W / A


def _block(law: dict) -> md.Model:
    return md.Model(BLOCK, thickness=1.0, density=1000.0, joints={"default": law})


@pytest.fixture(scope="module")
def single() -> tuple:
    model = _block(md.mortar_joint(young=1.0e7, thickness=0.01, poisson=0.25, friction=0.75, cohesion=COHESION))
    return model, model.solve_static()


@pytest.fixture(scope="module")
def wall() -> tuple:
    blocks = md.running_bond(0.4, 0.2, courses=3, length=1.2)
    model = md.Model(blocks, joints={"default": md.dry_joint(0.65)}, top_rotation="free", top_force=(0.0, -500.0))
    return model, model.solve_static()


# --------------------------------------------------------------------------------------------------
# Joint laws
# --------------------------------------------------------------------------------------------------


def test_mortar_joint_stiffnesses() -> None:
    law = md.mortar_joint(young=1.0e9, thickness=0.01, poisson=0.25)
    assert set(law) == LAW_KEYS
    assert law["normal_stiffness"] == pytest.approx(1.0e11)
    assert law["shear_stiffness"] == pytest.approx(1.0e9 / 2.5 / 0.01)
    assert (law["friction"], law["cohesion"], law["tensile_strength"], law["dilatancy"]) == (0.75, 0.0, 0.0, 0.0)
    law = md.mortar_joint(2.0e9, 0.02, shear=0.5e9, friction=0.6, cohesion=1e5, tensile_strength=5e4, dilatancy=0.1)
    assert law == {
        "normal_stiffness": pytest.approx(1.0e11),
        "shear_stiffness": pytest.approx(2.5e10),
        "friction": 0.6,
        "cohesion": 1e5,
        "tensile_strength": 5e4,
        "dilatancy": 0.1,
    }
    assert all(type(v) is float for v in law.values())
    # numpy scalars and ints are numbers too
    law = md.mortar_joint(np.float64(1e9), 1, poisson=np.float32(0.0))
    assert law["shear_stiffness"] == pytest.approx(0.5e9)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"young": 0.0, "thickness": 0.01, "poisson": 0.2}, "young"),
        ({"young": float("nan"), "thickness": 0.01, "poisson": 0.2}, "young"),
        ({"young": "1e9", "thickness": 0.01, "poisson": 0.2}, "young"),
        ({"young": True, "thickness": 0.01, "poisson": 0.2}, "young"),
        ({"young": 1e9, "thickness": -0.01, "poisson": 0.2}, "thickness"),
        ({"young": 1e9, "thickness": float("inf"), "poisson": 0.2}, "thickness"),
        ({"young": 1e9, "thickness": 0.01, "shear": 0.0}, "shear"),
        ({"young": 1e9, "thickness": 0.01, "shear": None, "poisson": -1.0}, "poisson"),
        ({"young": 1e9, "thickness": 0.01, "poisson": 0.6}, "poisson"),
        ({"young": 1e9, "thickness": 0.01}, "shear"),
        ({"young": 1e9, "thickness": 0.01, "shear": 4e8, "poisson": 0.25}, "poisson"),
        ({"young": 1e9, "thickness": 0.01, "poisson": 0.2, "friction": -0.1}, "friction"),
        ({"young": 1e9, "thickness": 0.01, "poisson": 0.2, "cohesion": -1.0}, "cohesion"),
        ({"young": 1e9, "thickness": 0.01, "poisson": 0.2, "tensile_strength": float("nan")}, "tensile_strength"),
        ({"young": 1e9, "thickness": 0.01, "poisson": 0.2, "dilatancy": -0.2}, "dilatancy"),
        ({"young": 1e300, "thickness": 1e-300, "poisson": 0.2}, "young"),
    ],
)
def test_mortar_joint_rejects(kwargs: dict, name: str) -> None:
    with pytest.raises(md.InputError, match=name):
        md.mortar_joint(**kwargs)


def test_dry_joint() -> None:
    law = md.dry_joint(0.6)
    assert law == {"normal_stiffness": 1e10, "shear_stiffness": 1e10, "friction": 0.6,
                   "cohesion": 0.0, "tensile_strength": 0.0, "dilatancy": 0.0}
    assert md.dry_joint(0.5, stiffness=2e9, dilatancy=0.5)["shear_stiffness"] == 2e9
    for kwargs, name in [({"friction": -1}, "friction"), ({"friction": 0.6, "stiffness": 0}, "stiffness"),
                         ({"friction": 0.6, "dilatancy": float("inf")}, "dilatancy"),
                         ({"friction": None}, "friction")]:
        with pytest.raises(md.InputError, match=name):
            md.dry_joint(**kwargs)


def test_mortar_joint_gives_a_working_model(single: tuple) -> None:
    model, results = single
    weight = float(model.weights[0])
    area = 0.4 * 1.0
    assert results.status == "collapse"
    expected = 0.75 + COHESION * area / weight
    assert results.collapse_multiplier == pytest.approx(expected, rel=1e-3)
    assert results.collapse_multiplier > 0.75 + 0.5 * COHESION * area / weight  # the cohesion counts
    assert results.joint_states["sliding"] == 1
    # a dry joint of the same friction collapses at mu
    dry = _block(md.dry_joint(0.75)).solve_static()
    assert dry.collapse_multiplier == pytest.approx(0.75, rel=1e-3)


# --------------------------------------------------------------------------------------------------
# Conversions
# --------------------------------------------------------------------------------------------------


def test_to_dict_without_model(single: tuple) -> None:
    model, results = single
    d = md.to_dict(results)
    for key in ("method", "status", "error", "collapse_multiplier", "curve", "control_block", "displacements",
                "mechanism", "interface_forces", "interface_states", "broken", "joint_states", "iterations",
                "steps", "elapsed_s"):
        assert key in d, key
    assert "title" not in d and "block_rects" not in d and "blocks" not in d
    assert d["method"] == "static" and d["status"] == "collapse" and d["error"] is None
    assert d["collapse_multiplier"] == results.collapse_multiplier
    assert d["curve"]["multiplier"] == pytest.approx(list(results.curve_multiplier))
    assert d["curve"]["displacement"] == pytest.approx(list(results.curve_displacement))
    assert np.allclose(np.array(d["displacements"], dtype=float), results.displacements, equal_nan=True)
    assert np.array(d["interface_forces"]).shape == (model.n_interfaces, 3)
    assert d["interface_states"] == [int(s) for s in results.interface_states]
    assert d["broken"] == [bool(b) for b in results.broken]
    assert d["joint_states"] == {k: results.joint_states.get(k, 0) for k in ("elastic", "sliding", "rocking", "open")}
    assert (d["iterations"], d["steps"]) == (results.iterations, results.steps)
    assert type(d["iterations"]) is int and type(d["broken"][0]) is bool
    json.dumps(d, allow_nan=False)  # plain Python, no NaN


def test_to_dict_with_model(wall: tuple) -> None:
    model, results = wall
    d = md.to_dict(results, model, title="three courses")
    assert d["title"] == "three courses"
    assert (d["blocks"], d["interfaces"]) == (model.n_blocks, model.n_interfaces)
    assert d["base_index"] == model.base_index and d["top_index"] == model.top_index
    assert np.allclose(d["block_rects"], model.rects)
    assert np.allclose(d["weights"], model.weights)
    assert d["interface_blocks"] == model.interface_blocks.tolist()
    assert np.allclose(d["interface_geometry"], model.interface_geometry)
    assert d["interface_family"] == list(model.interface_family)
    assert len(d["displacements"]) == len(model.rects)
    # the same values as the result file wherever the two share a key
    ref = result_dict(results, model, "three courses")
    for key in set(ref) - {"format"}:
        assert d[key] == ref[key], key
    json.loads(json.dumps(d, allow_nan=False))


def test_to_dict_nan_and_failed() -> None:
    fake = SimpleNamespace(
        method="dynamic", status="failed", error="did not converge", collapse_multiplier=float("nan"),
        curve_multiplier=np.array([0.0, float("nan")]), curve_displacement=np.array([0.0, 1e-4]),
        control_block=0, displacements=np.full((1, 3), np.nan), mechanism=np.zeros((1, 3)),
        interface_forces=np.zeros((0, 3)), interface_states=np.zeros(0, dtype=np.int64),
        broken=np.zeros(0, dtype=bool), joint_states={}, iterations=3, steps=1, elapsed_s=0.5,
    )
    d = md.to_dict(fake)
    assert d["collapse_multiplier"] is None and d["error"] == "did not converge"
    assert d["curve"]["multiplier"] == [0.0, None]
    assert d["displacements"] == [[None, None, None]]
    assert d["interface_forces"] == [] and d["joint_states"] == {"elastic": 0, "sliding": 0, "rocking": 0, "open": 0}
    json.dumps(d, allow_nan=False)


def test_model_mismatch(single: tuple, wall: tuple) -> None:
    with pytest.raises(md.InputError, match="model does not match"):
        md.to_dict(single[1], wall[0])
    with pytest.raises(md.InputError, match="model does not match"):
        md.interface_columns(single[1], wall[0])


def test_to_json(wall: tuple, tmp_path: Path) -> None:
    model, results = wall
    path = tmp_path / "out.json"
    data = md.to_json(results, path, model, "three courses")
    assert json.loads(path.read_text(encoding="utf-8")) == data == result_dict(results, model, "three courses")
    assert data["format"] == 1 and data["title"] == "three courses"
    assert sorted(os.listdir(tmp_path)) == ["out.json"]  # the temporary file was renamed
    assert md.to_json(results, str(path), model)["title"] == "untitled"  # overwrites
    assert sorted(os.listdir(tmp_path)) == ["out.json"]
    with pytest.raises(OSError):
        md.to_json(results, tmp_path / "missing" / "out.json", model, "x")
    assert sorted(os.listdir(tmp_path)) == ["out.json"]


def test_columns(wall: tuple) -> None:
    model, results = wall
    curve = md.curve_columns(results)
    assert list(curve) == list(api.CURVE_COLUMNS)
    assert np.array_equal(curve["multiplier"], results.curve_multiplier)
    assert np.array_equal(curve["displacement_m"], results.curve_displacement)
    cols = md.interface_columns(results, model)
    assert list(cols) == list(api.INTERFACE_COLUMNS)
    m = model.n_interfaces
    assert all(len(v) == m for v in cols.values())
    assert np.array_equal(np.stack([cols["a"], cols["b"]], axis=1), model.interface_blocks)
    geo = np.stack([cols[k] for k in ("x", "y", "nx", "ny", "length_m")], axis=1)
    assert np.array_equal(geo, model.interface_geometry)
    forces = np.stack([cols[k] for k in ("N_N", "T_N", "M_Nm")], axis=1)
    assert np.array_equal(forces, results.interface_forces)
    assert list(cols["family"]) == list(model.interface_family)
    assert np.array_equal(cols["state"], results.interface_states)
    assert np.array_equal(cols["broken"], results.broken)


def _have_pandas() -> Any:
    try:
        import pandas
    except ImportError:
        return None
    return pandas


def test_dataframes(wall: tuple) -> None:
    """Without pandas: ImportError naming pandas; with it: the frames."""
    model, results = wall
    pd = _have_pandas()
    if pd is None:
        with pytest.raises(ImportError, match="pandas"):
            md.to_dataframe(results, model)
        with pytest.raises(ImportError, match="pandas"):
            md.interfaces_dataframe(results, model)
        return
    df = md.to_dataframe(results, model)
    assert list(df.columns) == ["multiplier", "displacement_m"] and len(df) == len(results.curve_multiplier)
    assert np.array_equal(df["multiplier"].to_numpy(), results.curve_multiplier)
    assert df.attrs["status"] == results.status and df.attrs["interfaces"] == model.n_interfaces
    assert list(md.to_dataframe(results).columns) == ["multiplier", "displacement_m"]
    idf = md.interfaces_dataframe(results, model)
    assert list(idf.columns) == list(api.INTERFACE_COLUMNS) and len(idf) == model.n_interfaces
    assert np.array_equal(idf["N_N"].to_numpy(), results.interface_forces[:, 0])
    assert list(idf["family"]) == list(model.interface_family)


def test_dataframes_without_pandas(wall: tuple, monkeypatch: pytest.MonkeyPatch) -> None:
    """The ImportError path, whether or not pandas is installed here."""
    model, results = wall
    monkeypatch.setitem(sys.modules, "pandas", None)  # makes `import pandas` raise ImportError
    for call in (lambda: md.to_dataframe(results), lambda: md.interfaces_dataframe(results, model)):
        with pytest.raises(ImportError, match="pandas") as info:
            call()
        assert "pip install 'masonry-dem[pandas]'" in str(info.value)  # the extra of pyproject.toml


def test_exports() -> None:
    for name in api.__all__:
        if not name.isupper():
            assert getattr(md, name) is getattr(api, name)
            assert name in md.__all__
    assert math.isfinite(md.mortar_joint(1e9, 0.01, shear=4e8)["shear_stiffness"])
