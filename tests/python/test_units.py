"""Units: the SI constants, parse_quantity, and case-file keys written with their units."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem.units import KINDS, UNITS, parse_quantity

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[2]
J4D = ROOT / "examples" / "j4d-shear-wall.toml"


# --------------------------------------------------------------------------------------------------
# Constants and parse_quantity
# --------------------------------------------------------------------------------------------------


def test_constants_are_si() -> None:
    assert md.MPa * 0.25 == 250000.0
    assert (md.mm, md.cm, md.m, md.km) == (0.001, 0.01, 1.0, 1000.0)
    assert (md.N, md.kN, md.MN) == (1.0, 1000.0, 1.0e6)
    assert (md.Pa, md.kPa, md.MPa, md.GPa) == (1.0, 1.0e3, 1.0e6, 1.0e9)
    assert md.N_per_mm3 == 1.0e9 and md.N_per_m3 == 1.0 and md.MN_per_m3 == 1.0e6
    assert md.N_per_mm == 1000.0 and md.N_per_m == md.J_per_m2 == 1.0
    assert md.kg_per_m3 == 1.0 and md.t_per_m3 == 1000.0 and md.m_per_s2 == 1.0
    assert md.parse_quantity is parse_quantity


@pytest.mark.parametrize(
    "text, kind, expected",
    [
        ("0.25 MPa", "stress", 250000.0),
        ("0.35MPa", "stress", 350000.0),
        ("250 kPa", "stress", 250000.0),
        ("0.25 N/mm2", "stress", 250000.0),
        ("82 N/mm3", "stiffness", 82.0e9),
        ("62.9 N/mm3", "stiffness", 62.9e9),
        ("62.9 N/mm^3", "stiffness", 62.9e9),
        ("62.9 N/mm³", "stiffness", 62.9e9),
        ("1e10 N/m3", "stiffness", 1e10),
        ("2.5 m", "length", 2.5),
        ("175 mm", "length", 0.175),
        ("17.5 cm", "length", 0.175),
        ("10 kN", "force", 10000.0),
        ("-29.7 kN", "force", -29700.0),
        ("18 N/m", "fracture_energy", 18.0),
        ("0.018 N/mm", "fracture_energy", 18.0),
        ("1900 kg/m3", "density", 1900.0),
        ("1.9 t/m3", "density", 1900.0),
        ("9.81 m/s2", "acceleration", 9.81),
        ("9.81 m/s^2", "acceleration", 9.81),
        ("0.25 g", "acceleration", 2.4516625),  # the standard gravity, 9.80665 m/s2
        ("0.5 s", "time", 0.5),
        ("20 ms", "time", 0.02),
        (3, "length", 3.0),
    ],
)
def test_parse_quantity(text: object, kind: str, expected: float) -> None:
    # exactly the float of the decimal value in SI, as TOML reads a number in SI
    assert parse_quantity(text, kind) == expected


def test_parse_quantity_wrong_dimension() -> None:
    with pytest.raises(md.InputError) as info:
        parse_quantity("0.25 m", "stress", what="joints.tensile_strength")
    assert str(info.value) == (
        "'0.25 m' is a length; joints.tensile_strength is a stress (Pa, kPa, MPa, GPa, N/mm2)"
    )
    with pytest.raises(md.InputError, match=r"'82 N/mm3' is a joint stiffness .*; x is a force \(N, kN, MN\)"):
        parse_quantity("82 N/mm3", "force", what="x")


@pytest.mark.parametrize(
    "text, pattern",
    [
        ("0.25 mpa", r"unknown unit 'mpa' .*did you mean 'MPa'\? units are case sensitive"),
        ("0.25", r"without a unit"),
        ("MPa", r"expected a number, got string \"MPa\""),
        ("", r"expected a number, got string"),
        ("0.25 furlongs", r"unknown unit 'furlongs'"),
        ("1e999 MPa", r"beyond the range of a float"),
    ],
)
def test_parse_quantity_refuses(text: str, pattern: str) -> None:
    with pytest.raises(md.InputError, match=pattern):
        parse_quantity(text, "stress", what="joints.cohesion")


def test_parse_quantity_tiny_exponent_is_quick() -> None:
    assert parse_quantity("1e-99999999 m", "length") == 0.0  # not an exact fraction of 10^99999999 digits
    assert parse_quantity("0." + "1" * 5000 + " m", "length") == pytest.approx(0.1111111111111111)
    with pytest.raises(md.InputError, match="beyond the range of a float"):
        parse_quantity("1" * 5000 + " m", "length")


def test_every_unit_has_a_known_kind() -> None:
    assert {kind for kind, _ in UNITS.values()} == set(KINDS)
    with pytest.raises(ValueError, match="unknown kind"):
        parse_quantity("1 m", "area")


# --------------------------------------------------------------------------------------------------
# Case files
# --------------------------------------------------------------------------------------------------

# the J4D example's SI values (left) written as an engineer would (right)
J4D_WITH_UNITS = [
    ("thickness = 0.1 ", 'thickness = "100 mm" '),
    ("density = 1900.0 ", 'density = "1900 kg/m3" '),
    ("block_length = 0.22 ", 'block_length = "220 mm" '),
    ("block_height = 0.062 ", 'block_height = "62 mm" '),
    ("length = 0.99 ", 'length = "990 mm" '),
    ("force = [0.0, -29700.0] ", 'force = [0.0, "-29.7 kN"] '),
    ("normal_stiffness = 62.9e9 ", 'normal_stiffness = "62.9 N/mm3" '),
    ("shear_stiffness = 27.5e9 ", 'shear_stiffness = "27.5 N/mm3" '),
    ("cohesion = 0.35e6 ", 'cohesion = "0.35 MPa" '),
    ("tensile_strength = 0.25e6 ", 'tensile_strength = "0.25 MPa" '),
    ("fracture_energy_tension = 18.0 ", 'fracture_energy_tension = "0.018 N/mm" '),
    ("fracture_energy_shear = 125.0 ", 'fracture_energy_shear = "125 N/m" '),
    ("normal_stiffness = 39.4e9", 'normal_stiffness = "39.4 N/mm3"'),
    ("shear_stiffness = 17.2e9", 'shear_stiffness = "17.2 N/mm3"'),
    ("gravity = 9.81 ", 'gravity = "9.81 m/s2" '),
    ("max_displacement = 0.004 ", 'max_displacement = "4 mm" '),
]


def test_j4d_with_units_is_the_same_case() -> None:
    text = J4D.read_text()
    with_units = text
    for old, new in J4D_WITH_UNITS:
        assert with_units.count(old) == 1, old
        with_units = with_units.replace(old, new)
    si = md.parse_case(text, source="si.toml")
    units = md.parse_case(with_units, source="units.toml")
    assert units.model_kwargs.keys() == si.model_kwargs.keys()
    for key, value in si.model_kwargs.items():
        if isinstance(value, np.ndarray):
            assert np.array_equal(units.model_kwargs[key], value), key
        else:
            assert units.model_kwargs[key] == value, key  # the very same floats, not nearly
    assert units.analysis == si.analysis
    assert units.model.joints["default"]["tensile_strength"] == 0.25e6
    assert units.model.joints["head"]["normal_stiffness"] == 39.4e9


CASE = """
format = 1
[geometry]
thickness = 1.0
[geometry.running_bond]
block_length = 0.4
block_height = 0.2
courses = 2
length = 1.2
[joints]
friction = 0.65
"""


def _error(text: str) -> md.InputError:
    with pytest.raises(md.InputError) as info:
        md.parse_case(text, source="wall.toml")
    return info.value


def test_wrong_unit_names_the_key() -> None:
    error = _error(CASE + 'tensile_strength = "0.25 m"\n')
    assert str(error) == (
        "wall.toml: '0.25 m' is a length; joints.tensile_strength is a stress (Pa, kPa, MPa, GPa, N/mm2)"
    )
    assert error.key == "joints.tensile_strength"
    error = _error(CASE.replace("block_height = 0.2", 'block_height = "0.2 MPa"'))
    assert error.key == "geometry.running_bond.block_height"
    assert "'0.2 MPa' is a stress; geometry.running_bond.block_height is a length (m, cm, mm)" in str(error)


def test_unit_value_is_checked_in_si() -> None:
    error = _error(CASE + 'cohesion = "-0.1 MPa"\n')
    assert str(error) == 'wall.toml: joints.cohesion: must be >= 0, got "-0.1 MPa"'
    assert error.key == "joints.cohesion"


def test_dimensionless_key_takes_no_unit() -> None:
    error = _error(CASE.replace("friction = 0.65", 'friction = "0.65 MPa"'))
    assert "joints.friction: expected a number, got string" in str(error)
    assert "(this key takes no unit)" in str(error)
    assert error.key == "joints.friction"


def test_units_in_blocks_openings_and_times() -> None:
    text = CASE.replace("length = 1.2", 'length = "1200 mm"\nopenings = [["300 mm", "0 mm", "0.5 m", "20 cm"]]')
    text += '[ground_motion]\npulse = "one-sine"\namplitude = "2 m/s2"\nperiod = "500 ms"\n'
    text += '[time_history]\nduration = "1.5 s"\nrecord_interval = "10 ms"\n'
    case = md.parse_case(text)
    si = md.parse_case(CASE.replace("length = 1.2", "length = 1.2\nopenings = [[0.3, 0.0, 0.5, 0.2]]"))
    b = np.asarray(si.model.blocks)
    wall = (b[:, 2].max() - b[:, 0].min()) * (b[:, 3].max() - b[:, 1].min())
    # the opening is cut out of the blocks: its 0.2 x 0.2 m are missing from the wall
    assert ((b[:, 2] - b[:, 0]) * (b[:, 3] - b[:, 1])).sum() == pytest.approx(wall - 0.04, rel=1e-12)
    assert np.array_equal(case.model.blocks, si.model.blocks)
    assert case.ground_motion.period == 0.5 and case.time_history.duration == 1.5
    assert case.time_history.record_interval == 0.01
    blocks = md.parse_case(
        'format = 1\n[geometry]\nblocks = [["0 mm", "0 mm", "400 mm", "175 mm"]]\n'
    ).model.blocks
    assert blocks.tolist() == [[0.0, 0.0, 0.4, 0.175]]


def test_every_example_still_reads() -> None:
    for path in sorted((ROOT / "examples").glob("*.toml")):
        data = tomllib.loads(path.read_text())
        assert md.load_case(path).title == data.get("title", path.stem)


def test_documented_units() -> None:
    """docs/case-format.md's Units section names every unit kind's units that a message suggests."""
    doc = (ROOT / "docs" / "case-format.md").read_text()
    section = re.search(r"## Units\n(.*?)\n## ", doc, re.S)
    assert section, "docs/case-format.md has a '## Units' section"
    for unit in ("MPa", "N/mm3", "mm", "kN", "N/mm", "kg/m3", "m/s2", "ms"):
        assert f"`{unit}`" in section.group(1) or unit in section.group(1), unit


def test_study_texture_reads_lengths_with_units() -> None:
    """A study's random texture reads the running bond's lengths as the case does (it used float())."""
    from masonry_dem.study.model import Texture, texture_blocks

    si = {"block_length": 0.4, "block_height": 0.2, "courses": 3, "length": 1.2, "openings": [[0.3, 0.0, 0.5, 0.2]]}
    units = dict(si, block_length="400 mm", block_height="20 cm", length="1.2 m",
                 openings=[["300 mm", "0 m", "0.5 m", "200 mm"]])
    texture = Texture(length_std=0.1, height_std=0.05)
    expected = texture_blocks(si, texture, np.random.default_rng(1))
    assert texture_blocks(units, texture, np.random.default_rng(1)) == expected
