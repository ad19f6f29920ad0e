"""Property tests through the Python API (issue 6, robustness), drawn by hypothesis.

- translating a wall changes neither its collapse multiplier nor its pushover curve;
- mirroring a wall (x -> -x) and pushing it the other way mirrors the curve;
- the same input gives bitwise the same output;
- no Results array holds a NaN, at any converged step (the curve and the progress reports).

Example counts are small (deadline=None: the first call builds solver state) so that the file
runs in well under 30 s.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import masonry_dem as md

# Where a static collapse of associative dry joints is claimed: at most 10 x tolerance (1e-4,
# solve_static's default) below the limit-analysis multiplier (docs/case-format.md, "Analyses
# checked against limit analysis"). Two correct runs of equivalent inputs can end anywhere in it:
# a path's step cuts follow round-off.
EVIDENCE_BAND = 10 * 1e-4
# Limit analysis's multiplier is known to its tolerance (1e-8 of 1 + lambda, the duality gap).
LIMIT_ACCURACY = 1e-8
# Points of a displacement-controlled curve are equilibria at the same prescribed displacements,
# converged to |residual| <= 1e-9 |applied forces|; what is left in lambda is that residual
# amplified by the tangent's conditioning near the peak (seen: ~1e-9 of the peak). 1e-6 allows
# an amplification of 1e3; a real asymmetry moves lambda by percents.
CURVE_TOL = 1e-6
SETTINGS = settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@st.composite
def walls(draw: st.DrawFn) -> dict:
    """Small running-bond walls of dry joints: 1-3 courses of 1-3.5 blocks, optionally under a
    free top beam with a precompression of 100 N to 5 kN."""
    bl = draw(st.floats(0.2, 0.5))
    n = draw(st.integers(1, 3)) + draw(st.sampled_from([0.0, 0.5]))
    blocks = md.running_bond(
        bl,
        draw(st.floats(0.3, 1.0)) * bl,
        courses=draw(st.integers(1, 3)),
        length=bl * n,
        first_course=draw(st.sampled_from(["half", "full"])),
    )
    mu = draw(st.floats(0.4, 0.9))
    law = md.dry_joint(mu, dilatancy=draw(st.sampled_from([0.0, mu])))
    top = draw(st.booleans())
    return {
        "blocks": np.asarray(blocks),
        "joints": {"default": law},
        "top_rotation": "free" if top else None,
        # at least 100 N on a beam: a weightless beam under no force is the default control
        # point of displacement control, yet nothing ties it to the wall; the answer is then
        # arbitrary (found: a shift of 1e-5 m moved the first step from 0.3853 to 0.3736)
        "top_force": (0.0, -draw(st.floats(100.0, 5e3))) if top else (0.0, 0.0),
    }


def model(w: dict, blocks: np.ndarray | None = None) -> md.Model:
    b = w["blocks"] if blocks is None else blocks
    return md.Model(b, joints=w["joints"], top_rotation=w["top_rotation"], top_force=w["top_force"], gravity=10.0)


def shifted(blocks: np.ndarray, dx: float, dy: float) -> np.ndarray:
    return blocks + np.array([dx, dy, dx, dy])


def mirrored(blocks: np.ndarray) -> np.ndarray:
    """x -> -x, block order kept: block i of the mirror is the image of block i."""
    return np.column_stack([-blocks[:, 2], blocks[:, 1], -blocks[:, 0], blocks[:, 3]])


@SETTINGS
@given(walls(), st.floats(-50.0, 50.0), st.floats(-50.0, 50.0))
def test_translation_invariance(w: dict, dx: float, dy: float) -> None:
    # Any shift: the static solver's displacement limit was 0.1 (max(x1, y1) - min(x0, y0)) over
    # absolute coordinates, so only diagonal shifts left it as it was; it is now 0.1 of the
    # wall's size (Model::size in the core).
    # Associative joints only: with psi = 0 the equilibrium path is not unique, and Newton's
    # choice follows round-off: a wall shifted by (1, 1) m collapsed in one run and failed
    # ("no equilibrium after 50 iterations") in the other, and displacement-control peaks moved
    # by 4e-6 (a finding, reported; the Rust tests cover psi = 0 with softer joints).
    w = dict(w, joints={"default": dict(w["joints"]["default"], dilatancy=w["joints"]["default"]["friction"])})
    a = model(w).solve_static(steps=50)
    b = model(w, shifted(w["blocks"], dx, dy)).solve_static(steps=50)
    assert a.status == b.status == "collapse", (a.error, b.error)
    # the exact multiplier does not move with the wall, and each collapse lies where one is claimed
    exact = [model(w, blocks).solve_limit().collapse_multiplier for blocks in (w["blocks"], shifted(w["blocks"], dx, dy))]
    assert abs(exact[0] - exact[1]) <= 2 * LIMIT_ACCURACY * (1.0 + exact[0]), exact
    for r, e in zip((a, b), exact):
        assert e * (1.0 - EVIDENCE_BAND) <= r.collapse_multiplier <= e + LIMIT_ACCURACY * (1.0 + e), (r.collapse_multiplier, e)
    a = model(w).solve_static(control="displacement", steps=30)
    b = model(w, shifted(w["blocks"], dx, dy)).solve_static(control="displacement", steps=30)
    assert a.status == b.status, (a.error, b.error)
    # the peak of the curve, whatever the status (collapse_multiplier is NaN but for a collapse: found, a
    # 9-block wall whose displacement-controlled path peaks 0.45% below limit analysis, "stalled" both times)
    peak = abs(a.last_equilibrium)
    assert abs(a.last_equilibrium - b.last_equilibrium) <= CURVE_TOL * peak
    # round-off may cut a step differently; where the prescribed displacements coincide, every
    # point of the curve must
    if len(a.curve_displacement) == len(b.curve_displacement) and np.allclose(
        a.curve_displacement[1:], b.curve_displacement[1:], rtol=0, atol=CURVE_TOL * 2e-3
    ):
        np.testing.assert_allclose(b.curve_multiplier, a.curve_multiplier, rtol=0, atol=CURVE_TOL * peak)


@SETTINGS
@given(walls())
def test_mirror_symmetry(w: dict) -> None:
    # The live load only pushes towards +x and load control only raises lambda, but displacement
    # control takes a negative max_displacement: the wall pushed towards -x and its mirror image
    # pushed towards +x (the same, mirrored, control block) follow mirrored curves.
    # Associative joints only: with psi = 0 the path follows round-off (as for translation).
    # Found: a 9-block wall (0.24 x 0.12 m blocks, mu = 0.71875, psi = 0) pushed towards -x
    # failed at step 5 at -0.4709 while its mirror image failed at step 4 at 0.6331.
    w = dict(w, joints={"default": dict(w["joints"]["default"], dilatancy=w["joints"]["default"]["friction"])})
    m, mm = model(w), model(w, mirrored(w["blocks"]))
    cb = m.solve_static(control="displacement", steps=1).control_block  # the default control block
    a = m.solve_static(control="displacement", max_displacement=-2e-3, steps=30, control_block=cb)
    b = mm.solve_static(control="displacement", max_displacement=2e-3, steps=30, control_block=cb)
    # a failed run (displacement control can fail with psi = 0) must fail in the mirror too
    assert a.status == b.status, (a.error, b.error)
    peak = float(np.max(np.abs(a.curve_multiplier)))
    # the mirror's peak towards +x is the original's peak towards -x (whatever the status: a collapse, or
    # a path that ended below the limit-analysis multiplier)
    assert abs(b.last_equilibrium + float(np.min(a.curve_multiplier))) <= CURVE_TOL * peak
    assert abs(b.last_equilibrium + a.last_equilibrium) <= CURVE_TOL * peak
    if len(a.curve_displacement) == len(b.curve_displacement) and np.allclose(
        b.curve_displacement[1:], -a.curve_displacement[1:], rtol=0, atol=CURVE_TOL * 2e-3
    ):
        np.testing.assert_allclose(b.curve_multiplier, -a.curve_multiplier, rtol=0, atol=CURVE_TOL * peak)


def _arrays(r: md.Results) -> dict[str, np.ndarray]:
    return {
        "curve_multiplier": r.curve_multiplier,
        "curve_displacement": r.curve_displacement,
        "displacements": r.displacements,
        "mechanism": r.mechanism,
        "interface_forces": r.interface_forces,
        "interface_states": r.interface_states,
        "broken": r.broken,
    }


@SETTINGS
@given(walls(), st.sampled_from(["load", "displacement"]))
def test_determinism(w: dict, control: str) -> None:
    a = model(w).solve_static(control=control, steps=30)
    b = model(w).solve_static(control=control, steps=30)
    assert a.status == b.status and a.iterations == b.iterations
    assert np.array([a.collapse_multiplier]).tobytes() == np.array([b.collapse_multiplier]).tobytes()
    for (name, x), y in zip(_arrays(a).items(), _arrays(b).values()):
        assert x.tobytes() == y.tobytes(), name  # the bits, NaN included


@SETTINGS
@given(walls(), st.sampled_from(["load", "displacement"]))
def test_no_nan_at_any_converged_step(w: dict, control: str) -> None:
    reports: list[tuple[int, float, float, float]] = []
    max_displacement = 0.002 if control == "displacement" else None  # a path of known length: a fraction
    r = model(w).solve_static(control=control, steps=30, max_displacement=max_displacement, progress=lambda *p: reports.append(p))
    # A run may fail (found: a block under a free 1 N beam, the beam driven with the live load on
    # the block's weight: Newton fails at the first displacement step); it must then say why,
    # and what it kept must be finite.
    if r.status == "failed":
        assert r.error, "a failed run without a reason"
    assert len(reports) == len(r.curve_multiplier) == r.steps
    for step, lam, u, fraction in reports:
        assert math.isfinite(lam) and math.isfinite(u), (step, lam, u)
        # fraction is NaN by contract under load control (the path's length is unknown)
        assert math.isnan(fraction) if control == "load" else 0.0 <= fraction <= 1.0
    for name, x in _arrays(r).items():
        assert not np.isnan(np.asarray(x, dtype=float)).any(), name
    assert math.isfinite(r.last_equilibrium)
    # a collapse multiplier only with a collapse
    assert math.isfinite(r.collapse_multiplier) == (r.status == "collapse"), (r.status, r.collapse_multiplier)
