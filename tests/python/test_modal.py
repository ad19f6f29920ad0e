"""Modal analysis through Python: the closed form of one block on its base, the arrays' shapes, Rayleigh damping,
the figure, and bad input raised as InputError."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import masonry_dem as md

B, H = 0.4, 1.0  # [m]
KN, KT = 1.0e10, 4.0e9  # [N/m3]
DENSITY, THICKNESS = 1000.0, 1.0


@pytest.fixture(scope="module")
def block() -> md.Model:
    law = {"normal_stiffness": KN, "shear_stiffness": KT, "friction": 0.6}
    return md.Model([[0.0, 0.0, B, H]], thickness=THICKNESS, density=DENSITY, joints={"default": law})


def closed_form() -> list:
    """The three angular frequencies [rad/s] of a block on its base joint, ascending: the vertical one
    (kN b s / m) and the sliding-rocking pair (2 x 2 eigenproblem, shear lever arm h/2)."""
    m = DENSITY * B * H * THICKNESS
    j = m * (B * B + H * H) / 12.0
    area, inertia = B * THICKNESS, THICKNESS * B**3 / 12.0
    k11, k12, k22 = KT * area, KT * area * H / 2, KT * area * H * H / 4 + KN * inertia
    # det(K - l M) = 0: m j l^2 - (k11 j + k22 m) l + (k11 k22 - k12^2) = 0
    a, b, c = m * j, -(k11 * j + k22 * m), k11 * k22 - k12 * k12
    big = (-b + math.sqrt(b * b - 4 * a * c)) / (2 * a)
    return sorted([math.sqrt(c / (a * big)), math.sqrt(big), math.sqrt(KN * area / m)])


def test_single_block_matches_the_closed_form(block: md.Model) -> None:
    m = md.modes(block, 3)
    want = closed_form()
    assert m.angular_frequencies == pytest.approx(want, rel=5e-3)
    assert m.frequencies_hz == pytest.approx([w / (2 * math.pi) for w in want], rel=5e-3)
    assert np.all(m.residuals < 1e-8)
    assert m.effective_mass.sum(axis=0) == pytest.approx(list(m.free_mass), rel=1e-9)
    assert m.free_mass == pytest.approx((DENSITY * B * H * THICKNESS,) * 2)


def test_shapes_and_arrays() -> None:
    blocks = md.running_bond(0.4, 0.2, courses=4, length=1.6)
    model = md.Model(blocks, thickness=THICKNESS, density=DENSITY)
    m = md.modes(model, 5)
    n_all = len(model.rects)
    assert len(m) == 5
    assert m.shapes.shape == (5, n_all, 3)
    assert m.frequencies_hz.shape == m.angular_frequencies.shape == m.residuals.shape == (5,)
    assert m.effective_mass.shape == (5, 2)
    assert np.all(np.diff(m.frequencies_hz) >= 0)
    assert np.all(m.shapes[:, model.base_index, :] == 0.0)
    # mass-orthonormal: phi_i^T M phi_j = delta_ij with M = (m, m, J) per block
    rects = np.asarray(model.rects)
    w, h = rects[:, 2] - rects[:, 0], rects[:, 3] - rects[:, 1]
    mass = DENSITY * w * h * THICKNESS  # [kg] (the base's row of the shapes is zero)
    inertia = mass * (w * w + h * h) / 12.0
    diag = np.stack([mass, mass, inertia], axis=1).reshape(-1)
    phi = m.shapes.reshape(5, -1)
    assert (phi * diag) @ phi.T == pytest.approx(np.eye(5), abs=1e-8)
    assert "Modes(5 modes" in repr(m)


def test_rayleigh_damping(block: md.Model) -> None:
    alpha, beta = md.rayleigh_damping((2.0, 10.0), 0.05, 0.03)
    zeta = lambda f: alpha / (2 * 2 * math.pi * f) + beta * 2 * math.pi * f / 2  # noqa: E731
    assert zeta(2.0) == pytest.approx(0.05, rel=1e-12)
    assert zeta(10.0) == pytest.approx(0.03, rel=1e-12)
    m = md.modes(block, 3)
    a2, b2 = md.rayleigh_damping(m, 0.05, pair=(0, 2))
    w = m.angular_frequencies
    for k in (0, 2):
        assert a2 / (2 * w[k]) + b2 * w[k] / 2 == pytest.approx(0.05, rel=1e-12)
    assert md.rayleigh_damping(block, 0.05) == pytest.approx(md.rayleigh_damping(m, 0.05))


@pytest.mark.parametrize(
    "args",
    [((1.0, 1.0), 0.05), ((0.0, 1.0), 0.05), ((1.0, float("nan")), 0.05), ((1.0, 10.0), -0.01), ("x", 0.05), ((1.0, 10.0), 0.05, 0.0001)],
)
def test_rayleigh_damping_rejects(args: tuple) -> None:
    with pytest.raises(md.InputError):
        md.rayleigh_damping(*args)


@pytest.mark.parametrize("n", [0, -1, 4, 10**30, 2.5, "3"])
def test_bad_n_raises_input_error(block: md.Model, n: object) -> None:
    with pytest.raises(md.InputError):
        md.modes(block, n)  # type: ignore[arg-type]


def test_bad_shift_raises_input_error(block: md.Model) -> None:
    with pytest.raises(md.InputError):
        md.modes(block, 1, shift=float("inf"))


def test_plot_writes_a_png(tmp_path: Path) -> None:
    model = md.Model(md.running_bond(0.4, 0.175, courses=6, length=2.0))
    m = md.modes(model, 4)
    out = tmp_path / "modes.png"
    fig = md.plot_modes(model, m, path=out)
    assert out.stat().st_size > 10_000
    assert len(fig.axes) == 4
    titles = [ax.get_title() for ax in fig.axes]
    assert all(f"{f:.4g} Hz" in t for f, t in zip(m.frequencies_hz, titles))
    # one mode on a given axes
    from matplotlib.figure import Figure

    ax = Figure().subplots()
    md.plot_modes(model, m, k=2, ax=ax)
    assert ax.get_title().startswith("mode 3:")
    with pytest.raises(md.InputError):
        md.plot_modes(model, m, k=7)


def test_rayleigh_damping_runs_in_a_time_history() -> None:
    """Rayleigh coefficients from two modes go into Model.simulate; damping and rayleigh together are refused."""
    model = md.Model([[0.0, 0.0, 0.4, 0.175]], gravity=9.81, joints={"default": {"restitution": 1.0}})
    alpha, beta = md.rayleigh_damping(model, 0.05)
    history = model.simulate(0.002, rayleigh=(alpha, beta), initial_velocities=[[0.0, 1e-4, 0.0], [0.0, 0.0, 0.0]])
    assert history.status == "completed", history.error
    assert history.damping_dissipation[-1] > 0 and history.impact_dissipation[-1] == 0
    with pytest.raises(md.InputError, match="not both"):
        model.simulate(0.001, rayleigh=(alpha, beta), damping="viscous")


BX, BY, BZ = 0.6, 0.4, 1.5  # a box in 3D [m]


def box_3d(turned: float = 0.0) -> md.Model3D:
    """The box BX x BY x BZ on its base as a polyhedron, turned by ``turned`` degrees about the vertical."""
    c, s = math.cos(math.radians(turned)), math.sin(math.radians(turned))
    corners = [[x, y, z] for z in (0.0, BZ) for x, y in ((-BX / 2, -BY / 2), (BX / 2, -BY / 2), (BX / 2, BY / 2),
                                                         (-BX / 2, BY / 2))]
    vertices = [[c * x - s * y, s * x + c * y, z] for x, y, z in corners]
    law = {"normal_stiffness": KN, "shear_stiffness": KT, "friction": 0.6}
    return md.Model3D(polyhedra=[vertices], density=DENSITY, joints={"default": law})


def closed_form_3d() -> list:
    """The six angular frequencies [rad/s] of a box on springs at its base's corners, ascending: vertical
    (kN A / m), torsion (each corner's kT A / 4 at (BX^2 + BY^2) / 4 over m (BX^2 + BY^2) / 12: 3 kT A / m) and the
    two sliding-rocking pairs (2 x 2 eigenproblems, shear lever arm h / 2, rocking stiffness kN A b^2 / 12)."""
    m, area = DENSITY * BX * BY * BZ, BX * BY
    out = [KN * area / m, 3.0 * KT * area / m]
    for b in (BX, BY):
        j = m * (b * b + BZ * BZ) / 12.0
        k11, k12, k22 = KT * area, KT * area * BZ / 2, KT * area * BZ * BZ / 4 + KN * area * b * b / 12.0
        a, bb, c = m * j, -(k11 * j + k22 * m), k11 * k22 - k12 * k12
        big = (-bb + math.sqrt(bb * bb - 4 * a * c)) / (2 * a)
        out += [c / (a * big), big]
    return sorted(math.sqrt(v) for v in out)


@pytest.mark.parametrize("turned", [0.0, 45.0])
def test_a_box_in_3d_matches_the_closed_form(turned: float) -> None:
    model = box_3d(turned)
    m = md.modes(model, 6)
    assert m.dimension == 3
    np.testing.assert_allclose(m.angular_frequencies, closed_form_3d(), rtol=1e-9)
    assert m.shapes.shape == (6, 2, 6) and m.effective_mass.shape == (6, 3) and len(m.free_mass) == 3
    mass = DENSITY * BX * BY * BZ
    np.testing.assert_allclose(m.effective_mass.sum(axis=0), [mass] * 3, rtol=1e-9)
    assert np.all(m.shapes[:, 1] == 0.0)  # the base is fixed
    alpha, beta = md.rayleigh_damping(model, 0.05)
    w1, w2 = closed_form_3d()[:2]
    assert alpha / (2 * w1) + beta * w1 / 2 == pytest.approx(0.05, rel=1e-9)
    assert alpha / (2 * w2) + beta * w2 / 2 == pytest.approx(0.05, rel=1e-9)


def test_modes_of_anything_else_are_refused() -> None:
    with pytest.raises(md.InputError, match="model must be a Model or a Model3D, got str"):
        md.modes("wall", 3)  # type: ignore[arg-type]
    with pytest.raises(md.InputError, match="only 6 free dofs"):
        md.modes(box_3d(), 7)


def test_plot_of_3d_modes_writes_a_png(tmp_path: Path, block: md.Model) -> None:
    model = box_3d(30.0)
    m = md.modes(model, 6)
    out = tmp_path / "modes3d.png"
    md.plot_modes(model, m, k=[0, 1, 2, 3], path=out)
    assert out.stat().st_size > 10_000 and out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with pytest.raises(md.InputError, match="not of this model"):
        md.plot_modes(block, m, path=tmp_path / "wrong.png")
