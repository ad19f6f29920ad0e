"""The result file (JSON, format 1): its shape, and no NaN in it."""

from __future__ import annotations

import json
import math
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem.case import result_dict, write_result_json

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
KEYS = [
    "format",
    "title",
    "method",
    "status",
    "blocks",
    "interfaces",
    "collapse_multiplier",
    "last_equilibrium",
    "curve",
    "joint_states",
    "elapsed_s",
]


def fake_results(**overrides: Any) -> SimpleNamespace:
    """An object with the attributes of Results that the writer reads."""
    values = dict(
        method="static",
        status="collapse",
        error=None,
        collapse_multiplier=0.6429,
        last_equilibrium=0.6429,
        curve_multiplier=np.array([0.0, 0.3, 0.6429]),
        curve_displacement=np.array([0.0, 1e-5, 4e-5]),
        joint_states={"open": 5, "rocking": 12, "sliding": 10, "elastic": 60},
        elapsed_s=0.004,
    )
    values.update(overrides)
    return SimpleNamespace(**values)


MODEL = SimpleNamespace(n_blocks=33, n_interfaces=83)


def test_shape() -> None:
    data = result_dict(fake_results(), MODEL, "Ferris & Tin-Loi wall 1")
    assert list(data) == KEYS
    assert data["format"] == 1
    assert data["title"] == "Ferris & Tin-Loi wall 1"
    assert data["method"] == "static" and data["status"] == "collapse"
    assert data["blocks"] == 33 and data["interfaces"] == 83
    assert data["collapse_multiplier"] == 0.6429 and data["last_equilibrium"] == 0.6429
    assert data["curve"] == {"multiplier": [0.0, 0.3, 0.6429], "displacement": [0.0, 1e-5, 4e-5]}
    assert list(data["joint_states"]) == ["elastic", "sliding", "rocking", "open"]
    assert data["joint_states"] == {"elastic": 60, "sliding": 10, "rocking": 12, "open": 5}
    assert data["elapsed_s"] == 0.004
    assert "error" not in data
    # plain Python types only
    text = json.dumps(data, allow_nan=False)
    assert json.loads(text) == data


def test_nan_becomes_null() -> None:
    results = fake_results(
        collapse_multiplier=float("nan"),
        curve_multiplier=np.array([0.0, np.nan, np.inf]),
        curve_displacement=np.array([0.0, np.nan, -np.inf]),
    )
    data = result_dict(results, MODEL, "t")
    assert data["collapse_multiplier"] is None
    assert data["curve"]["multiplier"] == [0.0, None, None]
    assert data["curve"]["displacement"] == [0.0, None, None]
    json.dumps(data, allow_nan=False)


def test_failed_has_error() -> None:
    data = result_dict(fake_results(status="failed", error="no convergence at step 7"), MODEL, "t")
    assert data["status"] == "failed"
    assert data["error"] == "no convergence at step 7"
    assert list(data) == KEYS + ["error"]
    data = result_dict(fake_results(status="failed", error=None), MODEL, "t")
    assert data["error"]


def test_write(tmp_path: Path) -> None:
    path = tmp_path / "r.json"
    written = write_result_json(path, fake_results(collapse_multiplier=math.nan), MODEL, "t")
    text = path.read_text()
    assert "NaN" not in text
    assert json.loads(text) == written


def test_real_run(tmp_path: Path) -> None:
    case = md.load_case(EXAMPLES / "single-block-sliding.toml")
    model = case.build_model()
    results = case.solve(model)
    path = tmp_path / "out.json"
    write_result_json(path, results, model, case.title)
    data = json.loads(path.read_text())
    assert list(data)[: len(KEYS)] == KEYS
    assert data["title"] == "Single block sliding (0.4 x 0.175 m)"
    assert data["method"] == "static"
    assert data["status"] in ("collapse", "completed", "failed")
    assert ("error" in data) == (data["status"] == "failed")
    assert data["blocks"] == 1
    assert data["interfaces"] == model.n_interfaces >= 1
    curve = data["curve"]
    assert len(curve["multiplier"]) == len(curve["displacement"]) >= 1
    assert curve["multiplier"][0] == pytest.approx(0.0)
    assert set(data["joint_states"]) == {"elastic", "sliding", "rocking", "open"}
    assert all(isinstance(v, int) for v in data["joint_states"].values())
    assert isinstance(data["elapsed_s"], float) and data["elapsed_s"] >= 0
