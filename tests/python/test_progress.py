"""The progress bar (tqdm, optional) and the agreement measures of `masonry-dem compare`, without solving."""

from __future__ import annotations

import builtins
import io
import json
import time
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem import progress as progress_module
from masonry_dem.compare import agreement, comparison_dict, comparison_text, failed_interfaces, format_difference
from masonry_dem.progress import NullProgress, ProgressBar, progress_bar, progress_text

NAN = float("nan")


# --------------------------------------------------------------------------------------------------
# Progress bar
# --------------------------------------------------------------------------------------------------


def test_progress_text() -> None:
    assert progress_text(12345, 0.64251, 1e-4, NAN) == "λ = 0.6425, 12,345 steps"
    assert progress_text(7, 0.2, 0.00125, 0.5) == "λ = 0.2000, u = 1.25 mm, 7 steps"
    assert progress_text(3, 56900.0, NAN, NAN, live="top_horizontal") == "H = 56.9 kN, 3 steps"
    assert progress_text(0, NAN, NAN, NAN) == "λ = -, 0 steps"
    assert progress_text(1, 0.0, -5.7e-23, 0.0) == "λ = 0.0000, u = 0 mm, 1 steps"


def test_bar_load_control() -> None:
    import tqdm  # noqa: F401  (a declared dependency: its absence is a failure, not a skip)
    out = io.StringIO()
    bar = ProgressBar("dynamic", file=out, interval=0.0, leave=True)
    bar(1000, 0.25, 1e-5, NAN)
    bar(2000, 0.5, 2e-5, NAN)
    bar.close()
    text = out.getvalue()
    assert "dynamic: λ = 0.5000, 2,000 steps" in text
    assert "%" not in text  # no end known under load control: no percentage
    assert bar.calls == 2 and bar.last is not None and bar.last[:3] == (2000, 0.5, 2e-5)


def test_bar_with_fraction_shows_a_percentage() -> None:
    import tqdm  # noqa: F401  (a declared dependency: its absence is a failure, not a skip)
    out = io.StringIO()
    with ProgressBar("static", file=out, interval=0.0, leave=True) as bar:
        bar(10, 0.1, 1e-3, NAN)
        bar(50, 0.4, 1.5e-3, 0.42)
    text = out.getvalue()
    assert " 42%|" in text
    assert "static: λ = 0.4000, u = 1.5 mm, 50 steps" in text


def test_bar_follows_the_latest_fraction() -> None:
    """A fraction, then none (e.g. the dead-load state reported as 0 done, then load control): the
    percentage goes away again."""
    import tqdm  # noqa: F401  (a declared dependency: its absence is a failure, not a skip)
    out = io.StringIO()
    with ProgressBar("static", file=out, interval=0.0) as bar:
        bar(1, 0.0, 0.0, 0.0)
        assert " 0%|" in out.getvalue().split("\r")[-1]
        bar(2, 0.3, 1e-5, NAN)
        assert out.getvalue().split("\r")[-1].startswith("static: λ = 0.3000, 2 steps [")


def test_bar_is_cheap_and_throttled() -> None:
    """The callback only stores the numbers between redraws: a million calls take well under a second."""
    import tqdm  # noqa: F401  (a declared dependency: its absence is a failure, not a skip)
    out = io.StringIO()
    bar = ProgressBar("dynamic", file=out, interval=60.0)
    draws: list = []
    original = bar._draw

    def counting_draw() -> None:
        draws.append(1)
        original()

    bar._draw = counting_draw  # type: ignore[method-assign]
    n = 200_000
    start = time.perf_counter()
    for i in range(n):
        bar(i, 0.5, 0.0, NAN)
    per_call = (time.perf_counter() - start) / n
    bar.close()
    assert len(draws) == 1  # the first call draws, the others wait for the interval
    assert bar.calls == n
    assert per_call < 5e-6, per_call


def test_bar_never_raises_into_the_solver() -> None:
    import tqdm  # noqa: F401  (a declared dependency: its absence is a failure, not a skip)
    bar = ProgressBar("static", file=io.StringIO(), interval=0.0)
    bar("not a step", object(), None, "x")  # type: ignore[arg-type]  # drawing fails: the bar turns off
    bar(1, 0.5, 0.0, NAN)
    bar.close()


def test_progress_bar_falls_back_without_tqdm(monkeypatch: pytest.MonkeyPatch) -> None:
    real_import = builtins.__import__

    def no_tqdm(name: str, *args: Any, **kwargs: Any) -> Any:
        if name == "tqdm" or name.startswith("tqdm."):
            raise ImportError("No module named 'tqdm'")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_tqdm)
    with progress_bar("static", file=io.StringIO()) as bar:
        assert isinstance(bar, NullProgress)
        assert not bar and (bar or None) is None
        bar(1, 0.5, 0.0, NAN)


def test_progress_bar_disabled() -> None:
    bar = progress_bar("static", enabled=False)
    assert isinstance(bar, NullProgress) and not bar


def test_progress_module_imports_tqdm_lazily() -> None:
    source = open(progress_module.__file__, encoding="utf-8").read()
    head = source.split("class NullProgress")[0]
    assert "import tqdm" not in head and "from tqdm" not in head


# --------------------------------------------------------------------------------------------------
# Agreement of two results
# --------------------------------------------------------------------------------------------------


def fake(method: str, lam: float, states: list, iterations: int, elapsed: float, status: str = "collapse") -> Any:
    return SimpleNamespace(
        method=method,
        status=status,
        error=None if status != "failed" else "no convergence",
        collapse_multiplier=lam,
        curve_multiplier=np.array([0.0, lam]),
        curve_displacement=np.array([0.0, 1e-4]),
        interface_states=np.array(states, dtype=np.int64),
        joint_states={"elastic": 1, "sliding": 1, "rocking": 1, "open": 1},
        iterations=iterations,
        steps=2,
        elapsed_s=elapsed,
    )


MODEL = SimpleNamespace(n_blocks=3, n_interfaces=6)


def test_failed_interfaces() -> None:
    # bits: 1 open, 2 sliding, 4 rocking; rocking alone is not a failure
    res = fake("static", 0.5, [0, 1, 2, 4, 6, 7], 10, 0.01)
    assert failed_interfaces(res).tolist() == [1, 2, 4, 5]


def test_agreement() -> None:
    static = fake("static", 0.640, [2, 2, 1, 4, 0, 0], 120, 0.02)
    dynamic = fake("dynamic", 0.6432, [2, 0, 1, 4, 2, 0], 45678, 1.0)
    agree = agreement(static, dynamic)
    assert agree["multiplier_relative_difference"] == pytest.approx(0.0032 / 0.640)
    assert agree["failed_static"] == 3 and agree["failed_dynamic"] == 3
    assert agree["failed_common"] == 2
    assert agree["jaccard"] == pytest.approx(2 / 4)
    assert agree["failed_interfaces_static"] == [0, 1, 2]
    assert agree["failed_interfaces_dynamic"] == [0, 2, 4]
    assert agree["iterations_static"] == 120 and agree["time_steps_dynamic"] == 45678
    assert agree["elapsed_ratio"] == pytest.approx(50.0)


def test_agreement_degenerate() -> None:
    static = fake("static", NAN, [0, 0], 0, 0.0, status="failed")
    dynamic = fake("dynamic", 0.3, [0, 4], 10, 0.5)
    agree = agreement(static, dynamic)
    assert agree["multiplier_relative_difference"] is None
    assert agree["elapsed_ratio"] is None
    assert agree["failed_common"] == 0 and agree["jaccard"] == 1.0  # neither has a failed joint
    data = comparison_dict(static, dynamic, MODEL, "t")
    json.dumps(data, allow_nan=False)  # no NaN anywhere
    assert data["static"]["status"] == "failed" and data["static"]["collapse_multiplier"] is None
    text = comparison_text(static, dynamic, MODEL, "t")
    assert "static failed: no convergence" in text
    assert "difference -" in text


def test_comparison_text_columns() -> None:
    static = fake("static", 1 / 3, [4], 37, 0.004)
    dynamic = fake("dynamic", 0.3331, [4], 12345, 0.2)
    lines = comparison_text(static, dynamic, MODEL, "Rocking").splitlines()
    assert lines[0] == "Rocking: static and explicit (dynamic) solvers"
    header = next(line for line in lines if line.strip().startswith("static"))
    row = next(line for line in lines if "collapse multiplier:" in line)
    # the values line up under their column heads
    assert row.index("0.3333") == header.index("static")
    assert row.index("0.3331") == header.index("dynamic")
    assert "difference -0.07%" in row
    work = next(line for line in lines if "work:" in line)
    assert "37 iterations" in work and "12,345 time steps" in work
    assert "dynamic / static = 50" in next(line for line in lines if "elapsed:" in line)
    top = comparison_text(
        fake("static", 56900.0, [2], 1, 1.0), fake("dynamic", 57000.0, [2], 1, 1.0), MODEL, "J4D", live="top_horizontal"
    )
    assert "peak horizontal force:" in top and "56.9 kN" in top


def test_format_difference() -> None:
    assert format_difference(None) == "-"
    assert format_difference(0.0012) == "+0.12%"
    assert format_difference(-0.0012) == "-0.12%"
    assert format_difference(-1e-6) == "0.00%"


def test_an_exception_in_the_callback_is_raised_again() -> None:
    """A bug in the user's callback surfaces as its own exception, not as an interrupted run."""
    model = md.Model(md.running_bond(0.4, 0.175, 3, 1.2), gravity=10.0)

    def wrong_signature(step):  # the callback receives 4 arguments
        return None

    class Stop(Exception):
        pass

    def stop(*args):
        raise Stop("from the callback")

    for solve in (model.solve_static, model.solve_dynamic):
        with pytest.raises(TypeError):
            solve(progress=wrong_signature)
        with pytest.raises(Stop, match="from the callback"):
            solve(progress=stop)
    with pytest.raises(Stop):
        model.simulate(duration=0.5, progress=stop)  # the monitor runs every 4,096 steps or 0.1 s
