"""3D time histories from case files ([ground_motion], [time_history] on a case of polyhedra and supports): the run
from the case file is the run from Python to the last digit, a block on a slope under a steady ground acceleration
stays at rest below the closed form's threshold and slides above it at the closed form's acceleration (within 1%),
the ground motion's direction in plan, the command line's outputs, and the refusals."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem import cli

ALPHA, MU, G = 10.0, 0.5, 10.0  # the slope [deg], the friction, gravity [m/s2]
B, D, H = 0.4, 0.3, 0.5  # the block along the slope, across it, its height [m]
AG = 5.0  # the steady ground acceleration of the record [m/s2]
DURATION = 0.5  # [s]


def slope_geometry() -> tuple:
    """(the block, the wedge under it): the block on a slope rising along +x at ALPHA, the wedge a support."""
    a = math.radians(ALPHA)
    s, n = (math.cos(a), 0.0, math.sin(a)), (-math.sin(a), 0.0, math.cos(a))

    def at(u: float, v: float, w: float) -> list:
        return [2.0 + u * s[k] + w * n[k] + (v if k == 1 else 0.0) for k in range(3)]

    block = [at(u, v, w) for w in (0.0, H) for v in (0.0, D) for u in (0.0, B)]
    lo, hi = at(-0.5, 0.0, 0.0), at(B + 0.5, 0.0, 0.0)
    floor = lo[2] - 1.0
    wedge = []
    for y in (1.5, 2.0 + D + 0.5):
        wedge += [[lo[0], y, lo[2]], [hi[0], y, hi[2]], [hi[0], y, floor], [lo[0], y, floor]]
    return block, wedge


JOINTS = {"default": {"friction": MU, "dilatancy": 0.0, "normal_stiffness": 1e9, "shear_stiffness": 1e9}}


def write_case(folder: Path, ground: str = "", history: str = "") -> Path:
    block, wedge = slope_geometry()
    listed = lambda vs: "[" + ", ".join("[" + ", ".join(repr(float(x)) for x in v) + "]" for v in vs) + "]"  # noqa: E731
    (folder / "steady.csv").write_text(f"time,acceleration\n0.0,{AG}\n1.0,{AG}\n")
    text = f"""format = 1
title = "a block on a slope, shaken"

[geometry]
density = 2000.0
polyhedra = [{listed(block)}]
supports = [{listed(wedge)}]

[joints]
friction = {MU}
dilatancy = 0.0
normal_stiffness = 1e9
shear_stiffness = 1e9

[loads]
gravity = {G}

[ground_motion]
file = "steady.csv"
units = "m/s2"
{ground}
[time_history]
duration = {DURATION}
record_interval = 0.01
{history}"""
    path = folder / "slope.toml"
    path.write_text(text)
    return path


def python_model() -> md.Model3D:
    block, wedge = slope_geometry()
    return md.Model3D(polyhedra=[block], supports=[wedge], base=False, density=2000.0, joints=JOINTS, gravity=G)


def slide_acceleration(history: md.TimeHistory) -> float:
    """The block's acceleration along its path [m/s2]: twice the quadratic term of the distance its centroid has
    moved, fitted over the records after 0.1 s (the first settle the block on its springs)."""
    t = np.asarray(history.times)
    u = np.linalg.norm(np.asarray(history.displacements)[:, 0, :3], axis=1)
    keep = t >= 0.1
    return 2.0 * float(np.polyfit(t[keep], u[keep], 2)[0])


def along_slope(a_g: float) -> float:
    """The closed form: a block on a slope of ALPHA under a ground acceleration a_g along +x (the slope rising
    along +x): in the frame of the ground the inertial force -m a_g pushes it down the slope by a_g cos(alpha) and
    off it by a_g sin(alpha); sliding at g sin + a_g cos - mu (g cos - a_g sin), at rest where that is <= 0."""
    a = math.radians(ALPHA)
    return G * math.sin(a) + a_g * math.cos(a) - MU * (G * math.cos(a) - a_g * math.sin(a))


def test_the_case_file_runs_what_python_runs(tmp_path: Path) -> None:
    c = md.load_case(write_case(tmp_path))
    assert c.dimension == 3
    model = c.build_model()
    from_file = c.simulate(model)
    t = np.array([0.0, 1.0])
    direct = python_model().simulate(DURATION, base_acceleration=(t, np.full(2, AG)), record_interval=0.01)
    assert from_file.status == direct.status == "completed"
    for name in ("times", "displacements", "velocities", "base_shear", "kinetic_energy", "friction_dissipation",
                 "energy_error"):
        assert np.array_equal(np.asarray(getattr(from_file, name)), np.asarray(getattr(direct, name))), name


def test_a_block_on_a_slope_slides_at_the_closed_form_and_rests_below_it(tmp_path: Path) -> None:
    c = md.load_case(write_case(tmp_path))
    model = c.build_model()
    slides = c.simulate(model)
    want = along_slope(AG)
    got = slide_acceleration(slides)
    assert got == pytest.approx(want, rel=0.01), (got, want)
    # down the slope: towards -x
    assert np.asarray(slides.displacements)[-1, 0, 0] < -0.1
    # the threshold a_g = g (mu cos - sin) / (cos + mu sin); half of it: the block stays where it is (elastic only)
    a = math.radians(ALPHA)
    threshold = G * (MU * math.cos(a) - math.sin(a)) / (math.cos(a) + MU * math.sin(a))
    assert along_slope(threshold) == pytest.approx(0.0, abs=1e-12)
    rests = c.simulate(model, scale=0.5 * threshold / AG)
    assert float(np.abs(np.asarray(rests.displacements)[:, 0, :3]).max()) < 1e-4


def test_the_ground_motion_across_the_slope(tmp_path: Path) -> None:
    # direction 90: the ground shakes along y, across the slope; the block slides along the resultant of gravity's
    # pull down the slope and the inertial force -m a_g in the slope's plane, against mu N, N = m g cos(alpha)
    scale = 1.2
    c = md.load_case(write_case(tmp_path, ground="direction = 90\n"))
    kwargs = c.simulate_kwargs(scale=scale)
    assert "base_acceleration" not in kwargs and np.array_equal(kwargs["base_acceleration_y"][1], [AG * scale] * 2)
    history = c.simulate(c.build_model(), scale=scale)
    a = math.radians(ALPHA)
    want = math.hypot(G * math.sin(a), AG * scale) - MU * G * math.cos(a)
    assert slide_acceleration(history) == pytest.approx(want, rel=0.01)
    assert np.asarray(history.displacements)[-1, 0, 1] < -0.05  # along -y, away from the ground's acceleration
    # at 30 degrees the record is split along x and y
    c = md.load_case(write_case(tmp_path, ground="direction = 30\n"))
    kwargs = c.simulate_kwargs()
    assert kwargs["base_acceleration"][1][0] == pytest.approx(AG * math.cos(math.radians(30)), rel=1e-15)
    assert kwargs["base_acceleration_y"][1][0] == pytest.approx(AG * 0.5, rel=1e-15)


def test_the_contact_update_from_a_case_file_and_from_python(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    # [time_history] contact_update = true (the default) runs Model3D.simulate(contact_update=True) to the last
    # digit; the block
    # slides by the closed form with its contact taken again from the moved block as it goes (the wedge is the
    # block's length beyond it on each side: it slides off its top face's middle within the run)
    path = write_case(tmp_path, history="contact_update = true\n")
    c = md.load_case(path)
    from_file = c.simulate(c.build_model())
    t = np.array([0.0, 1.0])
    direct = python_model().simulate(DURATION, base_acceleration=(t, np.full(2, AG)), record_interval=0.01,
                                     contact_update=True)
    assert from_file.status == direct.status == "completed"
    for name in ("times", "displacements", "velocities", "kinetic_energy", "friction_dissipation", "energy_error"):
        assert np.array_equal(np.asarray(getattr(from_file, name)), np.asarray(getattr(direct, name))), name
    assert slide_acceleration(from_file) == pytest.approx(along_slope(AG), rel=0.01)
    searches, created, dropped, renewed = from_file.contact_counts
    assert searches > 1 and renewed > 0 and (created, dropped) == (0, 0), from_file.contact_counts
    assert from_file.ground_level is not None
    (tmp_path / "off").mkdir()
    off = md.load_case(write_case(tmp_path / "off", history="contact_update = false\n")).simulate(python_model())
    assert off.contact_counts == (0, 0, 0, 0) and off.ground_level is None
    # the summary and the JSON say what the update did
    out = tmp_path / "out.json"
    assert cli.main(["simulate", str(path), "--json", str(out)]) == 0
    printed = capsys.readouterr().out
    assert f"contact update:      {searches:,} searches; 0 contacts created, 0 dropped" in printed, printed
    assert json.loads(out.read_text())["contact_update"]["renewed"] == renewed


def test_the_command_line_simulates_a_3d_case(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    path = write_case(tmp_path)
    out = tmp_path / "out.json"
    assert cli.main(["simulate", str(path), "--json", str(out), "--vtk", str(tmp_path / "motion"), "--quiet"]) == 0
    printed = capsys.readouterr().out
    assert "control block 0" in printed and "completed" in printed
    data = json.loads(out.read_text())
    history = md.load_case(path).simulate(python_model())
    u = np.asarray(history.displacements)[:, 0]
    # the control block's horizontal displacement, as run from Python
    assert np.array_equal(data["records"]["displacement"], np.hypot(u[:, 0], u[:, 1]).tolist())
    assert len(data["records"]["base_shear_y"]) == len(data["records"]["times"])
    assert (tmp_path / "motion.pvd").exists()


def test_refusals_of_3d_time_histories(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    path = write_case(tmp_path, history='damping = "rayleigh"\ndamping_ratio = 0.05\n')
    with pytest.raises(md.InputError, match='time_history.damping: "rayleigh" is refused in 3D') as info:
        md.load_case(path)
    assert info.value.key == "time_history.damping"
    plane = tmp_path / "plane.toml"
    plane.write_text('format = 1\n[geometry]\nblocks = [[0, 0, 0.4, 1.0]]\n[ground_motion]\npulse = "ricker"\n'
                     'amplitude = 1.0\nperiod = 0.2\ndirection = 90\n')
    with pytest.raises(md.InputError, match="ground_motion.direction: belongs to a 3D case"):
        md.load_case(plane)
    path = write_case(tmp_path)
    for option in ("--plot", "--csv", "--gif"):
        suffix = {"--plot": "png", "--csv": "csv", "--gif": "gif"}[option]
        assert cli.main(["simulate", str(path), option, str(tmp_path / f"x.{suffix}")]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and f"simulate {option}: the figures" in err[0], err
