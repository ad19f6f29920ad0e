"""Ground motions: the record readers (two-column CSV, PEER NGA .AT2), the built-in pulses, scaling, the case
keys [ground_motion] and [time_history], ``masonry-dem simulate`` and its outputs (response figure, energy
plot, animation)."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path
from typing import Any, Tuple

import numpy as np
import pytest
from matplotlib.figure import Figure

import masonry_dem as md
from masonry_dem import ground_motion as gm
from masonry_dem.cli import main
from masonry_dem.history import default_control_block
from masonry_dem.plot import energy_figure, plot_energy, response_figure, write_animation

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"

# a slender block on a fixed base (b/h = 1/3: it rocks before it slides, friction 0.8), under a one-sine pulse
BLOCK_CASE = """\
format = 1
title = "rocking block"

[geometry]
blocks = [[0.0, 0.0, 0.2, 0.6]]

[joints]
friction = 0.8

[loads]
gravity = 9.81
"""

PULSE = """
[ground_motion]
pulse = "one-sine"
amplitude_g = 0.5
period = 0.2

[time_history]
duration = 0.3
record_interval = 0.005
"""


# --------------------------------------------------------------------------------------------------
# The readers
# --------------------------------------------------------------------------------------------------

AT2_VALUES = [0.0, 0.00123, -0.0045, 0.1, -0.25, 0.3125, 7e-5, -1.5e-3, 0.02, 0.0, -0.01, 0.001, 0.5]


def write_at2(path: Path, values: list, header: str, columns: int = 5, units: str = "G") -> Path:
    """A file in the PEER NGA format: 4 header lines, then the values in rows of ``columns``, Fortran style."""
    lines = [
        "PEER NGA STRONG MOTION DATABASE RECORD",
        "IMPERIAL VALLEY 05/19/40 0439, EL CENTRO ARRAY #9, 180",
        f"ACCELERATION TIME SERIES IN UNITS OF {units}",
        header,
    ]
    for i in range(0, len(values), columns):
        lines.append("".join(f"{v:15.7E}" for v in values[i : i + columns]))
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.mark.parametrize(
    "header, columns",
    [
        (f"NPTS=   {len(AT2_VALUES)}, DT=   .0050 SEC", 5),
        (f"  {len(AT2_VALUES)}    0.0050    NPTS, DT", 8),
    ],
)
def test_at2_reader(tmp_path: Path, header: str, columns: int) -> None:
    path = write_at2(tmp_path / "RSN6_IMPVALL.I_I-ELC180.AT2", AT2_VALUES, header, columns)
    motion = gm.read_at2(path)
    # the values recovered exactly, in g times G; the samples at 0, DT, 2 DT, ...
    np.testing.assert_array_equal(motion.acceleration, np.array(AT2_VALUES) * gm.G)
    np.testing.assert_array_equal(motion.times, np.arange(len(AT2_VALUES)) * 0.005)
    assert motion.time_step == pytest.approx(0.005, rel=1e-12)
    assert motion.peak == 0.5 * gm.G
    assert motion.duration == pytest.approx((len(AT2_VALUES) - 1) * 0.005)
    assert "IMPERIAL VALLEY" in motion.name and motion.source == str(path)
    # read() picks the reader by its suffix, whatever its case; another g
    again = gm.read(path, g=10.0)
    np.testing.assert_array_equal(again.acceleration, np.array(AT2_VALUES) * 10.0)


def test_at2_errors(tmp_path: Path) -> None:
    short = write_at2(tmp_path / "a.at2", AT2_VALUES[:-1], f"NPTS=   {len(AT2_VALUES)}, DT=   .0050 SEC")
    with pytest.raises(md.InputError, match=r"a\.at2: line 4 gives NPTS = 13, but the file holds 12 values"):
        gm.read_at2(short)
    bad_head = write_at2(tmp_path / "b.at2", AT2_VALUES, "POINTS 13 STEP 0.005")
    with pytest.raises(md.InputError, match=r"b\.at2, line 4: expected 'NPTS= n, DT= dt SEC'"):
        gm.read_at2(bad_head)
    cms = write_at2(tmp_path / "c.at2", AT2_VALUES, "NPTS=   13, DT=   .0050 SEC", units="CM/S/S")
    with pytest.raises(md.InputError, match=r"c\.at2, line 3: the values are in units of CM/S/S"):
        gm.read_at2(cms)
    text = write_at2(tmp_path / "d.at2", AT2_VALUES, "NPTS=   13, DT=   .0050 SEC").read_text()
    (tmp_path / "d.at2").write_text(text.replace("1.0000000E-01", "1.0000000X-01"))
    with pytest.raises(md.InputError, match=r"d\.at2, line 5: expected numbers"):
        gm.read_at2(tmp_path / "d.at2")
    with pytest.raises(md.InputError, match="an AT2 record is in g"):
        gm.read(tmp_path / "d.at2", units="m/s2")


def test_csv_reader(tmp_path: Path) -> None:
    path = tmp_path / "rec.csv"
    path.write_text("# a record\n# in g\ntime_s,acceleration_g\n0.0,0.0\n0.02,0.1\n\n# a comment\n0.04,-0.2\n0.06,0.05\n")
    motion = gm.read_csv(path)
    np.testing.assert_array_equal(motion.times, [0.0, 0.02, 0.04, 0.06])
    np.testing.assert_array_equal(motion.acceleration, np.array([0.0, 0.1, -0.2, 0.05]) * gm.G)
    assert motion.name == "rec" and motion.units.startswith("g")
    in_si = gm.read_csv(path, units="m/s2")
    np.testing.assert_array_equal(in_si.acceleration, [0.0, 0.1, -0.2, 0.05])
    # other columns, blank-separated, no header
    spaced = tmp_path / "spaced.txt"
    spaced.write_text("1 0.0 9.0\n2 0.5 8.0\n3 1.0 7.0\n")
    other = gm.read(spaced, units="m/s2", time_column=1, accel_column=2)
    np.testing.assert_array_equal(other.times, [0.0, 0.5, 1.0])
    np.testing.assert_array_equal(other.acceleration, [9.0, 8.0, 7.0])


@pytest.mark.parametrize(
    "text, message",
    [
        ("t,a\n0,0\n0.02,abc\n", r"rec\.csv, line 3: expected numbers in columns 1 \(time \[s\]\) and 2"),
        ("t,a\n0,0\n0.02\n", r"rec\.csv, line 3: expected numbers"),
        ("0,0\nt,a\n0.02,0\n", r"rec\.csv, line 2: expected numbers"),  # a header only before the rows
        ("0,0\n0.02,0.1\n0.02,0.2\n", r"rec\.csv, line 3: the time 0.02 s does not follow 0.02 s"),
        ("0,0\n0.02,nan\n", r"rec\.csv, line 2: expected finite numbers"),
        ("# only\nt,a\n0,1\n", r"rec\.csv: expected at least 2 rows"),
    ],
)
def test_csv_errors(tmp_path: Path, text: str, message: str) -> None:
    path = tmp_path / "rec.csv"
    path.write_text(text)
    with pytest.raises(md.InputError, match=message):
        gm.read_csv(path)


def test_read_refuses_unknown_formats_and_units(tmp_path: Path) -> None:
    path = tmp_path / "rec.xyz"
    path.write_text("0,0\n1,1\n")
    with pytest.raises(md.InputError, match=r"rec\.xyz: unknown record format '\.xyz'"):
        gm.read(path)
    with pytest.raises(md.InputError, match="units"):
        gm.read_csv(tmp_path / "rec.xyz", units="cm/s2")


def test_elcentro_example_record() -> None:
    """The example record is the benchmark's file, unchanged, with its header comment lines."""
    motion = gm.read(EXAMPLES / "elcentro-1940-ns.csv", units="g")
    raw = np.loadtxt(EXAMPLES / "elcentro-1940-ns.csv", delimiter=",", comments="#", skiprows=4)
    np.testing.assert_array_equal(motion.times, raw[:, 0])
    np.testing.assert_array_equal(motion.acceleration, raw[:, 1] * gm.G)
    assert (EXAMPLES / "elcentro-1940-ns.csv").read_text().startswith("# El Centro")


# --------------------------------------------------------------------------------------------------
# Pulses, scaling
# --------------------------------------------------------------------------------------------------


def test_one_sine() -> None:
    pulse = gm.one_sine(3.0, 0.4)
    assert pulse.times[0] == 0.0 and pulse.times[-1] == 0.4
    assert pulse.peak == pytest.approx(3.0, rel=1e-12)
    assert pulse.acceleration[int(np.argmax(pulse.acceleration))] == pytest.approx(3.0)
    assert pulse.times[int(np.argmax(pulse.acceleration))] == pytest.approx(0.1)  # at T / 4
    assert pulse.acceleration[-1] == 0.0
    np.testing.assert_array_equal(pulse.at([0.4, 0.41, 1.0, -0.1]), 0.0)  # zero after T (and before 0)
    assert pulse.at(0.3) == pytest.approx(-3.0, rel=1e-6)
    padded = gm.one_sine(3.0, 0.4, duration=1.2)
    assert padded.duration == 1.2 and padded.acceleration[-1] == 0.0
    with pytest.raises(md.InputError, match="period"):
        gm.one_sine(3.0, 0.0)


def test_ricker() -> None:
    T = 0.5
    wave = gm.ricker(2.0, period=T)
    k = int(np.argmax(wave.acceleration))
    assert wave.times[k] == 1.5 * T and wave.acceleration[k] == 2.0  # the peak A at t0 exactly
    # its known shape: zero at t0 +- 1 / (sqrt(2) pi f), troughs of -2 A exp(-3/2) at t0 +- sqrt(3/2) / (pi f)
    f = 1.0 / T
    zero = 1.5 * T + 1.0 / (math.sqrt(2.0) * math.pi * f)
    trough = 1.5 * T + math.sqrt(1.5) / (math.pi * f)
    assert abs(float(wave.at(zero))) < 2.0 * 1e-3
    assert float(np.min(wave.acceleration)) == pytest.approx(-2.0 * 2.0 * math.exp(-1.5), rel=1e-3)
    assert float(wave.at(trough)) == pytest.approx(-2.0 * 2.0 * math.exp(-1.5), rel=1e-3)
    assert wave.duration == pytest.approx(3.0 * T) and abs(wave.acceleration[0]) < 1e-7
    assert len(wave.times) >= 3 * gm.SAMPLES_PER_PERIOD
    same = gm.ricker(2.0, frequency=2.0, t0=0.6)
    assert same.times[int(np.argmax(same.acceleration))] == 0.6
    with pytest.raises(md.InputError, match="period .* or frequency"):
        gm.ricker(1.0, period=0.5, frequency=2.0)


def test_scaling_and_arguments() -> None:
    pulse = gm.one_sine(3.0, 0.4)
    double = pulse.scaled(2.0)
    np.testing.assert_array_equal(double.acceleration, pulse.acceleration * 2.0)
    np.testing.assert_array_equal(double.times, pulse.times)
    assert double.scale == 2.0 and double.scaled(1.5).scale == 3.0 and pulse.scale == 1.0
    assert double.peak == pytest.approx(6.0)
    times, acc = double.as_tuple()
    acc[0] = 99.0  # a copy: the motion is unchanged
    assert double.acceleration[0] == 0.0
    vertical = gm.ricker(1.0, period=0.2)
    kwargs = gm.simulate_arguments(double, vertical)
    assert set(kwargs) == {"base_acceleration", "vertical_acceleration"}
    np.testing.assert_array_equal(kwargs["vertical_acceleration"][1], vertical.acceleration)
    assert set(gm.simulate_arguments(double)) == {"base_acceleration"}
    with pytest.raises(md.InputError, match="scale"):
        pulse.scaled(float("nan"))
    with pytest.raises(md.InputError, match="times must increase"):
        gm.GroundMotion([0.0, 1.0, 1.0], [0.0, 1.0, 2.0], source="x")


def test_g_is_the_cores_default_gravity() -> None:
    assert gm.G == md.case.CORE_DEFAULTS["gravity"] == 9.81


# --------------------------------------------------------------------------------------------------
# Case keys
# --------------------------------------------------------------------------------------------------


def test_case_keys_pulse() -> None:
    case = md.parse_case(BLOCK_CASE + PULSE, source="block.toml")
    gmp = case.ground_motion
    assert gmp is not None and gmp.pulse == "one-sine" and gmp.period == 0.2 and gmp.scale == 1.0
    assert gmp.horizontal.peak == pytest.approx(0.5 * 9.81)
    kwargs = case.simulate_kwargs()
    assert kwargs["duration"] == 0.3 and kwargs["record_interval"] == 0.005
    np.testing.assert_array_equal(kwargs["base_acceleration"][1], gm.one_sine(0.5 * 9.81, 0.2).acceleration)
    scaled = case.simulate_kwargs(scale=2.0, duration=0.25)
    assert scaled["duration"] == 0.25
    np.testing.assert_array_equal(scaled["base_acceleration"][1], kwargs["base_acceleration"][1] * 2.0)
    # defaults: 3 periods of a pulse; the core's for the others (left out)
    bare = md.parse_case(BLOCK_CASE + '[ground_motion]\npulse = "ricker"\namplitude = 2.0\nperiod = 0.5\n')
    kwargs = bare.simulate_kwargs()
    assert kwargs["duration"] == pytest.approx(1.5)
    assert set(kwargs) == {"duration", "base_acceleration"}


def test_case_keys_record_files(tmp_path: Path) -> None:
    (tmp_path / "h.csv").write_text("t,a\n0,0\n0.1,0.2\n0.2,-0.1\n0.3,0\n")
    write_at2(tmp_path / "v.AT2", AT2_VALUES, f"NPTS=   {len(AT2_VALUES)}, DT=   .0100 SEC")
    text = BLOCK_CASE.replace("gravity = 9.81", "gravity = 10.0") + """
[ground_motion]
file = "h.csv"
units = "g"
scale = 1.5
vertical_file = "v.AT2"

[time_history]
damping = "viscous"
damping_coefficient = 0.3
time_step = 1e-5
large_rotations = false
"""
    case_file = tmp_path / "c.toml"
    case_file.write_text(text)
    case = md.load_case(case_file)  # the files relative to the case file
    gmp = case.ground_motion
    assert gmp is not None and gmp.files == (tmp_path / "h.csv", tmp_path / "v.AT2")
    # values in g converted with the case's gravity
    np.testing.assert_array_equal(gmp.horizontal.acceleration, np.array([0.0, 0.2, -0.1, 0.0]) * 10.0)
    kwargs = case.simulate_kwargs()
    np.testing.assert_array_equal(kwargs["base_acceleration"][1], gmp.horizontal.acceleration * 1.5)
    # the vertical follows the horizontal's scale unless vertical_scale is given
    np.testing.assert_array_equal(kwargs["vertical_acceleration"][1], np.array(AT2_VALUES) * 10.0 * 1.5)
    assert kwargs["duration"] == pytest.approx(0.3) and "record_interval" not in kwargs
    assert (kwargs["damping"], kwargs["damping_coefficient"], kwargs["time_step"], kwargs["large_rotations"]) == (
        "viscous", 0.3, 1e-5, False)
    with_vs = md.load_case(_write(tmp_path / "d.toml", text.replace('vertical_file = "v.AT2"',
                                                                   'vertical_file = "v.AT2"\nvertical_scale = 0.5')))
    np.testing.assert_array_equal(with_vs.simulate_kwargs(scale=3.0)["vertical_acceleration"][1],
                                  np.array(AT2_VALUES) * 10.0 * 0.5)


def _write(path: Path, text: str) -> Path:
    path.write_text(text)
    return path


@pytest.mark.parametrize(
    "table, key, message",
    [
        ('[ground_motion]\npulse = "one-sine"\namplitude = 1.0\nperiod = 0.2\nfile = "x.csv"',
         "ground_motion.file", "exactly one of file (a record) and pulse"),
        ("[ground_motion]\nscale = 2.0", "ground_motion.file", "exactly one of file (a record) and pulse"),
        ('[ground_motion]\npulse = "two-sine"\namplitude = 1.0\nperiod = 0.2', "ground_motion.pulse",
         'expected one of "one-sine", "ricker"'),
        ('[ground_motion]\npulse = "ricker"\nperiod = 0.2', "ground_motion.amplitude", "exactly one of amplitude"),
        ('[ground_motion]\npulse = "ricker"\namplitude = 1\namplitude_g = 0.1\nperiod = 0.2', "ground_motion.amplitude",
         "both are given"),
        ('[ground_motion]\npulse = "ricker"\namplitude = 1', "ground_motion.period", "missing key 'period'"),
        ('[ground_motion]\npulse = "ricker"\namplitude = 1\nperiod = -1', "ground_motion.period", "must be > 0"),
        ('[ground_motion]\npulse = "ricker"\namplitude = 1\nperiod = 1\nunits = "g"', "ground_motion.units",
         "applies to a record file"),
        ('[ground_motion]\npulse = "ricker"\namplitude = "big"\nperiod = 1', "ground_motion.amplitude",
         "expected a number"),
        ('[ground_motion]\npulse = "ricker"\namplitude = 1\nperiod = 1\nscael = 2', "ground_motion.scael",
         "did you mean 'scale'"),
        ('[ground_motion]\nfile = "missing.csv"', "ground_motion.file", "cannot read"),
        ('[ground_motion]\nfile = "rec.csv"\nunits = "cm/s2"', "ground_motion.units", 'expected one of "g", "m/s2"'),
        ('[ground_motion]\nfile = "rec.csv"\nperiod = 1.0', "ground_motion.period", "applies to a pulse"),
        ('[ground_motion]\nfile = "rec.csv"\nvertical_scale = 1.0', "ground_motion.vertical_scale",
         "needs vertical_file"),
        ('[ground_motion]\nfile = "rec.wav"', "ground_motion.file", "unknown record format"),
        ('[ground_motion]\nfile = "bad.csv"', "ground_motion.file", "bad.csv, line 2: expected numbers"),
        ("[time_history]\nduration = 0", "time_history.duration", "must be > 0"),
        ("[time_history]\nrecord_interval = -1", "time_history.record_interval", "must be > 0"),
        ('[time_history]\ndamping = "heavy"', "time_history.damping", "expected one of"),
        ("[time_history]\ndamping_coefficient = 0.1", "time_history.damping_coefficient", 'needs damping = "local"'),
        ('[time_history]\ndamping = "local"\ndamping_coefficient = 1.0', "time_history.damping_coefficient",
         "must be < 1"),
        ("[time_history]\nlarge_rotations = 1", "time_history.large_rotations", "expected true or false"),
        ("[time_history]\ntime_step = 0", "time_history.time_step", "must be > 0"),
        ('[time_history]\ndamping = "rayleigh"', "time_history.damping_ratio", 'is needed with damping = "rayleigh"'),
        ("[time_history]\ndamping_ratio = 0.05", "time_history.damping_ratio", 'belongs to damping = "rayleigh"'),
        ('[time_history]\ndamping = "rayleigh"\ndamping_ratio = 0.05\ndamping_coefficient = 1', "time_history.damping_coefficient",
         "does not apply"),
        ("[time_history]\nthreads = 2", "time_history.threads", "unknown key 'threads' in [time_history]"),
    ],
)
def test_case_key_errors(tmp_path: Path, table: str, key: str, message: str) -> None:
    (tmp_path / "rec.csv").write_text("0,0\n1,1\n")
    (tmp_path / "bad.csv").write_text("0,0\nx,1\n")
    with pytest.raises(md.InputError) as info:
        md.parse_case(BLOCK_CASE + table + "\n", source="wall.toml", base_dir=tmp_path)
    text = str(info.value)
    assert text.startswith("wall.toml: ") and message in text, text
    assert info.value.key == key
    assert "\n" not in text


def test_case_rayleigh_damping_is_set_from_the_models_modes() -> None:
    """damping = "rayleigh" with damping_ratio: Model.simulate gets rayleigh=(alpha, beta) for that ratio at the
    model's first two modes (masonry_dem.rayleigh_damping), and the run dissipates by damping."""
    case = md.parse_case(BLOCK_CASE + PULSE + 'damping = "rayleigh"\ndamping_ratio = 0.05\n', source="block.toml")
    model = case.build_model()
    with pytest.raises(md.InputError, match="needs model="):
        case.simulate_kwargs()
    kwargs = case.simulate_kwargs(model=model)
    assert "damping" not in kwargs
    assert kwargs["rayleigh"] == pytest.approx(md.rayleigh_damping(model, 0.05))
    history = case.simulate(model, duration=0.05)
    assert history.status == "completed" and history.damping_dissipation[-1] > 0


def test_simulate_needs_a_ground_motion() -> None:
    case = md.parse_case(BLOCK_CASE, source="wall.toml")
    assert case.ground_motion is None
    with pytest.raises(md.InputError, match=r"wall\.toml: no \[ground_motion\] table"):
        case.simulate_kwargs()


def test_example_case_reads_its_record() -> None:
    case = md.load_case(EXAMPLES / "ferris-tinloi-wall1-elcentro.toml")
    assert case.ground_motion is not None and case.reference is None and case.method == "static"
    assert case.ground_motion.files == (EXAMPLES / "elcentro-1940-ns.csv",)
    assert case.ground_motion.horizontal.duration == pytest.approx(31.18)
    assert case.simulate_kwargs()["duration"] == pytest.approx(31.18)


# --------------------------------------------------------------------------------------------------
# Runs: the CLI, the figures, the animation
# --------------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def rocked() -> Tuple[Any, Any, Any]:
    """The block under the pulse: (model, history, ground motion)."""
    case = md.parse_case(BLOCK_CASE + PULSE, source="block.toml")
    model = case.build_model()
    history = case.simulate(model)
    assert history.status == "completed", history.error
    return model, history, case.ground_motion.horizontal


def test_simulate_cli(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    case_file = _write(tmp_path / "block.toml", BLOCK_CASE + PULSE)
    out = tmp_path / "out"
    status = main(["simulate", str(case_file), "--scale", "1.2", "--json", str(out / "h.json"), "--csv",
                   str(out / "h.csv"), "--plot", str(out / "h.png"), "--gif", str(out / "h.gif"), "--vtk",
                   str(out / "h"), "-q"])
    text = capsys.readouterr().out
    assert status == 0, text
    for label in ("duration:", "status:              completed", "peak drift:", "peak rotation:",
                  "peak base shear:", "energy balance:"):
        assert label in text, text
    data = json.loads((out / "h.json").read_text())
    assert data["kind"] == "time_history" and data["status"] == "completed"
    assert data["ground_motion"]["scale"] == 1.2
    assert data["ground_motion"]["peak"] == pytest.approx(1.2 * 0.5 * 9.81)
    times = np.array(data["records"]["times"])
    assert times[-1] == pytest.approx(0.3, abs=0.006) and len(times) >= 50
    assert len(data["records"]["base_shear"]) == len(times)
    assert np.array(data["records"]["ground_acceleration"]).shape == (len(times), 2)
    rows = np.loadtxt(out / "h.csv", delimiter=",", skiprows=1)
    np.testing.assert_array_equal(rows[:, 0], times)
    assert (out / "h.png").stat().st_size > 10_000
    assert (out / "h.gif").read_bytes()[:6] in (b"GIF89a", b"GIF87a")
    assert (out / "h.pvd").exists() and (out / "h-blocks-0000.vtu").exists()
    # without -q the memory of the records is stated before the run, as the run holds them
    status = main(["simulate", str(case_file), "--duration", "0.1"])
    err = capsys.readouterr().err
    model = md.parse_case(BLOCK_CASE + PULSE).build_model()
    records, size = model.record_size(0.1, record_interval=0.005)
    assert status == 0 and f"recording {records:,} states of the 2 blocks: {size / 2**20:.1f} MB" in err, err


def test_simulate_cli_errors(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    no_motion = _write(tmp_path / "still.toml", BLOCK_CASE)
    assert main(["simulate", str(no_motion), "-q"]) == 2
    assert "no [ground_motion] table" in capsys.readouterr().err
    case_file = _write(tmp_path / "block.toml", BLOCK_CASE + PULSE)
    assert main(["simulate", str(case_file), "--gif", str(tmp_path / "a.png"), "-q"]) == 2
    assert "expected a .gif" in capsys.readouterr().err
    assert main(["simulate", str(case_file), "--csv", str(case_file), "-q"]) == 2  # never the case file
    assert case_file.read_text() == BLOCK_CASE + PULSE
    with pytest.raises(SystemExit) as info:
        main(["simulate", str(case_file), "--duration", "-1"])
    assert info.value.code == 2


def test_simulate_help() -> None:
    proc = subprocess.run([sys.executable, "-m", "masonry_dem", "simulate", "--help"], capture_output=True,
                          text=True, env={**os.environ, "COLUMNS": "120"})
    assert proc.returncode == 0
    for flag in ("--scale", "--duration", "--json", "--plot", "--csv", "--vtk", "--gif", "--quiet"):
        assert flag in proc.stdout


def test_response_figure(tmp_path: Path, rocked: Tuple[Any, Any, Any]) -> None:
    model, history, motion = rocked
    fig = response_figure(model, history, motion=motion, title="block", path=tmp_path / "r.png")
    assert isinstance(fig, Figure) and (tmp_path / "r.png").stat().st_size > 10_000
    wall, ax_rot, ax_drift, ax_shear, ax_ground = fig.axes
    assert "rotation [rad]" in ax_rot.get_ylabel() and "drift" in ax_drift.get_ylabel()
    assert "[%]" in ax_drift.get_ylabel() and "[kN]" in ax_shear.get_ylabel()
    assert "ground acceleration [m/s²]" in ax_ground.get_ylabel() and ax_ground.get_xlabel() == "time [s]"
    c = default_control_block(model)
    height = 0.6
    np.testing.assert_allclose(ax_drift.get_lines()[0].get_ydata(), history.displacements[:, c, 0] / height * 100)
    np.testing.assert_array_equal(ax_rot.get_lines()[0].get_ydata(), history.displacements[:, c, 2])
    np.testing.assert_array_equal(ax_shear.get_lines()[0].get_ydata(), np.asarray(history.base_shear) * 1e-3)
    np.testing.assert_array_equal(ax_ground.get_lines()[0].get_ydata(), np.asarray(history.ground_acceleration)[:, 0])
    # at=: the wall at the first record at or after that time (a collapse), not at the largest drift
    t = float(history.times[len(history.times) // 3])
    fig = response_figure(model, history, motion=motion, at=t)
    assert f"at t = {t:.4g} s (the time given)" in fig.axes[0].get_title()


def test_response_figure_draws_the_motion_when_the_history_lacks_it(tmp_path: Path, rocked: Tuple[Any, Any, Any]) -> None:
    """An input the history does not carry is sampled from the GroundMotion given."""
    from types import SimpleNamespace

    model, history, motion = rocked
    bare = SimpleNamespace(times=history.times, displacements=history.displacements, velocities=history.velocities,
                           status=history.status, error=history.error, steps=history.steps,
                           time_step=history.time_step)
    fig = response_figure(model, bare, motion=motion)
    ax_shear, ax_ground = fig.axes[3], fig.axes[4]
    np.testing.assert_array_equal(ax_ground.get_lines()[0].get_ydata(), motion.at(history.times))
    assert "no base shear" in ax_shear.texts[0].get_text()


def test_energy_plot(rocked: Tuple[Any, Any, Any]) -> None:
    _, history, _ = rocked
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    fig = Figure()
    FigureCanvasAgg(fig)
    ax = plot_energy(history, ax=fig.add_subplot(1, 1, 1))
    assert ax.get_xlabel() == "time [s]" and ax.get_ylabel() == "energy [J]"
    # the black line is the external work; the top of the stack is kinetic + elastic + dissipated
    work = [line for line in ax.get_lines() if line.get_label().startswith("work")][0]
    np.testing.assert_array_equal(work.get_ydata(), history.external_work)
    top = np.max([p.get_paths()[0].vertices[:, 1].max() for p in ax.collections])
    total = np.asarray(history.kinetic_energy) + np.asarray(history.elastic_energy) + np.asarray(history.dissipated)
    assert top == pytest.approx(float(total.max()), rel=1e-9)
    assert ax.get_legend() is not None


def test_energy_plot_split(tmp_path: Path, rocked: Tuple[Any, Any, Any]) -> None:
    """The dissipation split by friction, damping and impacts, and the balance error line."""
    _, history, _ = rocked
    fig = energy_figure(history, title="block", path=tmp_path / "e.png")
    ax = fig.axes[0]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    for label in ("dissipated by friction", "dissipated by damping", "dissipated by impacts", "elastic (joints)",
                  "kinetic", "balance error"):
        assert label in labels, labels
    error = [line for line in ax.get_lines() if line.get_label() == "balance error"][0]
    np.testing.assert_array_equal(error.get_ydata(), history.energy_error)
    assert (tmp_path / "e.png").stat().st_size > 10_000


def test_write_animation(tmp_path: Path, rocked: Tuple[Any, Any, Any]) -> None:
    model, history, _ = rocked
    path = write_animation(model, history, tmp_path / "a" / "r.gif", fps=10, every=10, title="block")
    assert path == tmp_path / "a" / "r.gif"
    from PIL import Image

    with Image.open(path) as im:
        frames = im.n_frames
    assert frames == len(range(0, len(history.times), 10)) + (0 if (len(history.times) - 1) % 10 == 0 else 1)
    assert sorted(p.name for p in (tmp_path / "a").iterdir()) == ["r.gif"]  # no temporary file left
    with pytest.raises(md.InputError, match="unknown format '.avi'"):
        write_animation(model, history, tmp_path / "r.avi")
    with pytest.raises(md.InputError, match="fps"):
        write_animation(model, history, tmp_path / "r.gif", fps=0)
    case_file = _write(tmp_path / "c.gif", "keep")
    with pytest.raises(md.InputError):
        write_animation(model, history, case_file, inputs=[case_file])
    assert case_file.read_text() == "keep"


def test_animation_frames() -> None:
    from masonry_dem.plot.animation import MAX_FRAMES, animation_frames

    times = np.arange(0, 10.0001, 0.01)  # 1001 records over 10 s
    frames = animation_frames(times, fps=25)
    assert frames[0] == 0 and frames[-1] == 1000 and len(frames) <= MAX_FRAMES + 1
    np.testing.assert_array_equal(animation_frames(times, fps=25, every=100), np.arange(0, 1001, 100))
    short = np.arange(0, 1.0001, 0.01)  # 1 s: 25 frames, real time
    assert len(animation_frames(short, fps=25)) in (26, 27)


def test_mp4_needs_ffmpeg(tmp_path: Path, rocked: Tuple[Any, Any, Any], monkeypatch: pytest.MonkeyPatch) -> None:
    """Without ffmpeg an MP4 is refused before anything is written (ffmpeg made missing whatever the machine has)."""
    from matplotlib import animation

    real = animation.writers.is_available
    monkeypatch.setattr(animation.writers, "is_available", lambda name: name != "ffmpeg" and real(name))
    model, history, _ = rocked
    with pytest.raises(md.InputError, match="MP4 needs ffmpeg"):
        write_animation(model, history, tmp_path / "r.mp4")
    assert not (tmp_path / "r.mp4").exists()


def test_peaks_of_a_block_moving_with_the_ground() -> None:
    """A squat block under a gentle pulse moves with the ground: the base shear is its mass times the ground's
    acceleration (the force of the block on its base, -m a_g), and the drift stays tiny."""
    from masonry_dem.response import peaks, summary_text

    model = md.Model(np.array([[0.0, 0.0, 0.4, 0.175]]), gravity=9.81, joints={"default": {"friction": 2.0}})
    pulse = gm.one_sine(0.1 * 9.81, 0.2)
    history = model.simulate(0.3, **gm.simulate_arguments(pulse), record_interval=0.002)
    assert history.status == "completed", history.error
    mass = 0.4 * 0.175 * 1000.0
    ground = np.asarray(history.ground_acceleration)[:, 0]
    np.testing.assert_allclose(ground, pulse.at(history.times), atol=1e-9)
    shear = np.asarray(history.base_shear)
    assert np.max(np.abs(shear + mass * ground)) < 0.05 * mass * pulse.peak
    p = peaks(model, history)
    # the pulse peaks at +a and -a: the peak base shear is -m a_g at whichever of the two records is the larger
    at = int(np.argmin(np.abs(np.asarray(history.times) - p["base_shear"]["time"])))
    assert abs(p["base_shear"]["value"]) == pytest.approx(mass * pulse.peak, rel=0.05)
    assert p["base_shear"]["value"] == pytest.approx(-mass * ground[at], rel=0.05)
    assert p["weight"] == pytest.approx(mass * 9.81)
    assert abs(p["drift"]["value"]) < 1e-4
    text = summary_text(model, history, "squat block", pulse)
    assert "x the weight" in text and "peak base shear" in text


def test_case_with_a_vertical_record_runs(tmp_path: Path) -> None:
    """Both components reach the solver: the history's ground acceleration is the records', scaled."""
    times = np.linspace(0.0, 0.1, 11)
    rows = "\n".join(f"{t:.3f},{0.2 * math.sin(20 * math.pi * t):.6f}" for t in times)
    (tmp_path / "h.csv").write_text("t,a\n" + rows + "\n")
    (tmp_path / "v.csv").write_text("t,a\n0,0\n0.05,0.1\n0.1,0\n")
    text = BLOCK_CASE + """
[ground_motion]
file = "h.csv"
vertical_file = "v.csv"
vertical_scale = 0.5

[time_history]
duration = 0.12
record_interval = 0.01
"""
    case = md.load_case(_write(tmp_path / "c.toml", text))
    model = case.build_model()
    history = case.simulate(model, scale=2.0)
    assert history.status == "completed", history.error
    horizontal, vertical = case.ground_motion.components(2.0)
    ground = np.asarray(history.ground_acceleration)
    np.testing.assert_allclose(ground[:, 0], horizontal.at(history.times), atol=1e-9)
    np.testing.assert_allclose(ground[:, 1], vertical.at(history.times), atol=1e-9)
    assert vertical.peak == pytest.approx(0.1 * 9.81 * 0.5) and horizontal.scale == 2.0
