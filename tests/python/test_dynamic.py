"""The explicit solver from Python: progress callbacks, time histories (Model.simulate) and their arrays.

Small models only (one block, the 3-block stack): each test takes well under a second or two.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Callable, List, Tuple

import numpy as np

from masonry_dem.history import ENERGIES
import pytest

import masonry_dem as md

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
G = 9.81


def single_block(**kwargs: object) -> md.Model:
    """The squat block of examples/single-block-sliding.toml: 0.4 x 0.175 m on a fixed base."""
    return md.Model(np.array([[0.0, 0.0, 0.4, 0.175]]), **kwargs)  # type: ignore[arg-type]


def stack() -> md.Model:
    return md.Model(md.pattern(0.3, 0.5, [[1], [1], [1]]), gravity=G)


Call = Tuple[int, float, float, float]


Progress = Callable[[int, float, float, float], None]


def recorder() -> Tuple[List[Call], Progress]:
    calls: List[Call] = []

    def progress(step: int, multiplier: float, displacement: float, fraction: float) -> None:
        calls.append((step, multiplier, displacement, fraction))

    return calls, progress


def check_calls(calls: List[Call]) -> None:
    assert len(calls) >= 1
    for step, multiplier, displacement, fraction in calls:
        assert isinstance(step, int)
        assert isinstance(multiplier, float) and isinstance(displacement, float) and isinstance(fraction, float)
        assert math.isnan(fraction) or 0.0 <= fraction <= 1.0
    steps = [c[0] for c in calls]
    assert steps == sorted(steps)


def test_solve_dynamic_calls_progress() -> None:
    calls, progress = recorder()
    res = single_block(gravity=G).solve_dynamic(progress=progress)
    assert res.method == "dynamic" and res.status == "collapse", res.error
    assert res.collapse_multiplier == pytest.approx(0.65, rel=0.02)
    check_calls(calls)
    assert calls[-1][0] <= res.iterations  # steps reported are time steps


def test_solve_dynamic_displacement_control_reports_fractions() -> None:
    calls, progress = recorder()
    res = single_block(gravity=G).solve_dynamic(
        control="displacement", max_displacement=0.001, steps=20, progress=progress
    )
    assert res.status in ("completed", "collapse"), res.error
    check_calls(calls)
    fractions = [c[3] for c in calls]
    assert all(math.isfinite(f) for f in fractions)
    assert fractions == sorted(fractions)


def test_solve_static_calls_progress() -> None:
    calls, progress = recorder()
    res = single_block(gravity=G).solve_static(progress=progress)
    assert res.status == "collapse"
    check_calls(calls)


def test_progress_none_and_errors() -> None:
    """progress=None is no callback; a callback that raises stops the run without crashing Python."""
    model = single_block(gravity=G)
    assert model.solve_dynamic(progress=None).status == "collapse"

    def boom(*args: object) -> None:
        raise RuntimeError("boom")

    try:
        res = model.solve_dynamic(progress=boom)
    except RuntimeError:
        return  # the core may pass the exception on ...
    assert res.status in ("failed", "collapse")  # ... or stop and say so


def test_critical_time_step() -> None:
    model = single_block(gravity=G)
    dt = model.critical_time_step()
    assert math.isfinite(dt) and dt > 0
    # a stiffer joint lowers the limit as 1/sqrt(k)
    stiff = single_block(gravity=G, joints={"default": {"normal_stiffness": 4e10, "shear_stiffness": 4e10}})
    assert stiff.critical_time_step() == pytest.approx(dt / 2, rel=0.05)


def test_time_history_shapes() -> None:
    model = stack()
    n_all = len(model.rects)
    th = model.simulate(0.01, record_every=5)
    assert th.status == "completed", th.error
    assert th.error is None
    assert th.time_step == pytest.approx(0.8 * model.critical_time_step(time_history=True))
    assert model.critical_time_step(time_history=True) < model.critical_time_step()
    k = len(th.times)
    assert k >= 2
    assert th.times.shape == (k,)
    assert th.displacements.shape == (k, n_all, 3)
    assert th.velocities.shape == (k, n_all, 3)
    for name in ENERGIES + ("base_shear",):
        assert getattr(th, name).shape == (k,), name
    assert th.ground_acceleration.shape == (k, 2)
    for name in ("times", "displacements", "velocities", "kinetic_energy"):
        assert getattr(th, name).dtype == np.float64, name
    assert th.times[0] == 0.0
    assert np.all(np.diff(th.times) > 0)
    assert np.diff(th.times)[0] == pytest.approx(5 * th.time_step)
    assert th.times[-1] == pytest.approx(0.01, abs=th.time_step)
    # every 5th step is recorded, and the last one
    assert th.times[-1] == pytest.approx(th.steps * th.time_step)
    assert 5 * (k - 2) < th.steps <= 5 * (k - 1)
    assert th.elapsed_s >= 0
    # the balance: initial energy + external work = kinetic + elastic + dissipated + error, the dissipated
    # energy the sum of its three parts
    e0 = th.kinetic_energy[0] + th.elastic_energy[0]
    np.testing.assert_allclose(e0 + th.external_work - th.kinetic_energy - th.elastic_energy - th.dissipated,
                               th.energy_error, atol=1e-9)
    np.testing.assert_allclose(th.dissipated, th.friction_dissipation + th.damping_dissipation + th.impact_dissipation,
                               atol=1e-12)
    # the base does not move
    base = model.base_index
    assert base is not None and np.all(th.displacements[:, base] == 0)


def test_simulate_rejects_bad_arrays() -> None:
    model = stack()
    with pytest.raises(md.InputError):
        model.simulate(0.01, initial_displacements=np.zeros((2, 3)))
    with pytest.raises(md.InputError):
        model.simulate(0.01, time_step=10 * model.critical_time_step())


def test_block_sliding_down_an_inclined_plane() -> None:
    """No damping: a block on a plane inclined at beta > atan(mu) slides with g (sin beta - mu cos beta).

    The plane is modelled by tilting gravity: gravity g cos(beta) normal to the joint and a constant live
    load tan(beta) W = m g sin(beta) along it. The block starts at rest, settled on its joint."""
    beta, mu = math.radians(25.0), 0.3
    model = single_block(gravity=G * math.cos(beta), joints={"default": {"friction": mu}})
    u0 = np.zeros((len(model.rects), 3))
    weight = float(model.weights[0])
    u0[0, 1] = -weight / (1e10 * 0.4 * 1.0)  # the elastic settlement under self-weight: no bouncing start
    calls, progress = recorder()
    th = model.simulate(
        0.4,
        live_multiplier=math.tan(beta),
        initial_displacements=u0,
        damping="none",
        record_every=10,
        progress=progress,
    )
    assert th.status == "completed", th.error
    # progress every few thousand steps, with the fraction of the duration done
    assert th.steps > 5000
    check_calls(calls)
    assert all(0.0 < c[3] <= 1.0 for c in calls)
    window = (th.times >= 0.05) & (th.times <= 0.4)
    assert window.sum() > 20
    slope = np.polyfit(th.times[window], th.velocities[window, 0, 0], 1)[0]
    exact = G * (math.sin(beta) - mu * math.cos(beta))
    assert slope == pytest.approx(exact, rel=0.01), (slope, exact)
    # it slides without turning over or lifting off
    assert np.max(np.abs(th.displacements[:, 0, 2])) < 1e-3
