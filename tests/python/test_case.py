"""The case-file loader: every validation path, and the mapping of a case onto the core's arguments."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem.case import case_from_dict, load_case, parse_case
from masonry_dem.default_case import DEFAULT_CASE_TOML, default_case

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

# A minimal valid case; tests append tables or replace lines.
MINIMAL = """\
format = 1
title = "one block"

[geometry]
blocks = [[0.0, 0.0, 0.4, 0.175]]
"""

RUNNING_BOND = """\
format = 1
title = "wall"

[geometry]
thickness = 1.0
density = 1000.0

[geometry.running_bond]
block_length = 0.4
block_height = 0.175
courses = 6
length = 2.0
first_course = "half"
"""


def load_text(tmp_path: Path, text: str, name: str = "case.toml") -> md.Case:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return load_case(path)


def input_error(tmp_path: Path, text: str, name: str = "case.toml") -> str:
    """The message of the InputError raised by loading ``text``; it must start with the file path."""
    with pytest.raises(md.InputError) as info:
        load_text(tmp_path, text, name)
    message = str(info.value)
    assert message.startswith(f"{tmp_path / name}: "), message
    assert "\n" not in message
    return message


# --------------------------------------------------------------------------------------------------
# Valid cases
# --------------------------------------------------------------------------------------------------


def test_examples_load() -> None:
    files = sorted(EXAMPLES.glob("*.toml"))
    names = {f.name for f in files}
    assert {
        "ferris-tinloi-wall1.toml",
        "ferris-tinloi-wall2.toml",
        "single-block-sliding.toml",
        "single-block-rocking.toml",
        "stack-3-blocks.toml",
    } <= names
    for f in files:
        case = load_case(f)
        assert case.title
        text = f.read_text()
        assert "Reference" in text and "docs/references.md" in text, f.name
        if case.dimension == 3:  # a 3D wall: limit analysis, boxes or polyhedra (tests/python/test_space*.py)
            assert case.method == "limit"
            boxes = case.model_kwargs["boxes"]
            solids = case.model_kwargs["polyhedra"] or []
            assert len(solids) >= 1 or (boxes.ndim == 2 and boxes.shape[1] == 6 and len(boxes) >= 1), f.name
            assert all(len(b) >= 4 and all(len(v) == 3 for v in b) for b in solids)
            continue
        # in the plane the static solver, or limit analysis along the mechanism (the rocking portal frame) or along a
        # support's movement (the spreading arch)
        along = case.analysis.follow_mechanism or case.analysis.move_support is not None
        assert case.method == "static" or (case.method == "limit" and along), f.name
        blocks = case.model_kwargs["blocks"]
        if isinstance(blocks, list):  # polygons (an arch): each a list of vertices [x, y]
            assert len(blocks) >= 1 and all(len(b) >= 3 and all(len(v) == 2 for v in b) for b in blocks)
        else:
            assert blocks.ndim == 2 and blocks.shape[1] == 4 and len(blocks) >= 1
        # every example states its reference answer and where it comes from, and lists the optional keys
        for key in ("tolerance", "damping", "damping_coefficient", "time_step", "unbalanced_ratio", "threads"):
            assert f"# {key} = " in text, (f.name, key)


def test_example_block_counts() -> None:
    assert len(load_case(EXAMPLES / "ferris-tinloi-wall1.toml").model_kwargs["blocks"]) == 33
    assert len(load_case(EXAMPLES / "ferris-tinloi-wall2.toml").model_kwargs["blocks"]) == 55
    assert len(load_case(EXAMPLES / "stack-3-blocks.toml").model_kwargs["blocks"]) == 3
    # J4D: 16 courses of 4.5 blocks, each course one half block and four whole ones
    assert len(load_case(EXAMPLES / "j4d-shear-wall.toml").model_kwargs["blocks"]) == 80


def test_default_case_is_wall1() -> None:
    demo = default_case()
    wall1 = load_case(EXAMPLES / "ferris-tinloi-wall1.toml")
    assert demo.title == wall1.title == "Ferris & Tin-Loi wall 1"
    assert demo.source == "demo"
    np.testing.assert_array_equal(demo.model_kwargs["blocks"], wall1.model_kwargs["blocks"])
    rest = {k: v for k, v in demo.model_kwargs.items() if k != "blocks"}
    assert rest == {k: v for k, v in wall1.model_kwargs.items() if k != "blocks"}
    assert demo.analysis_kwargs == wall1.analysis_kwargs
    assert "0.6429" in DEFAULT_CASE_TOML
    law = demo.model_kwargs["joints"]["default"]
    assert law["friction"] == law["dilatancy"] == 0.65
    assert demo.model_kwargs["gravity"] == 10.0


def test_minimal_case_defaults(tmp_path: Path) -> None:
    case = load_text(tmp_path, MINIMAL)
    kw = case.model_kwargs
    np.testing.assert_array_equal(kw["blocks"], [[0.0, 0.0, 0.4, 0.175]])
    assert kw["blocks"].dtype == np.float64
    assert kw["thickness"] == 1.0 and kw["density"] == 1000.0
    assert kw["base"] is True
    assert kw["top_rotation"] is None
    assert kw["joints"] is None
    assert kw["gravity"] == 9.81 and kw["live"] == "horizontal_weight"
    # no max_displacement: the static solver goes on until collapse, the explicit one takes its own default
    assert case.analysis_kwargs == {"control": "load", "steps": 200, "max_displacement": None, "control_block": None}
    assert "max_displacement" not in case.solver_kwargs("dynamic")
    assert case.method == "static"


def test_title_defaults_to_file_stem(tmp_path: Path) -> None:
    case = load_text(tmp_path, MINIMAL.replace('title = "one block"\n', ""), name="my-wall.toml")
    assert case.title == "my-wall"


def test_full_mapping(tmp_path: Path) -> None:
    text = (
        RUNNING_BOND
        + """\
openings = [[0.6, 0.525, 1.0, 1.4]]

[base]
kind = "none"

[top]
rotation = "free"
force = [0.0, -29700]

[joints]
normal_stiffness = 82e9
shear_stiffness = 36e9
friction = 0.75
cohesion = 0.35e6
tensile_strength = 0.25e6
dilatancy = 0

[joints.bed]
friction = 0.6

[joints.base]
cohesion = 0.0
tensile_strength = 0.0

[loads]
gravity = 10
live = "top_horizontal"

[analysis]
method = "static"
control = "displacement"
control_point = "top"
max_displacement = 0.003
steps = 150
"""
    )
    case = load_text(tmp_path, text)
    kw = case.model_kwargs
    assert kw["base"] is False
    assert kw["top_rotation"] == "free"
    assert kw["top_force"] == [0.0, -29700.0]
    assert kw["joints"] == {
        "default": {
            "normal_stiffness": 82e9,
            "shear_stiffness": 36e9,
            "friction": 0.75,
            "cohesion": 0.35e6,
            "tensile_strength": 0.25e6,
            "dilatancy": 0.0,
        },
        "bed": {"friction": 0.6},
        "base": {"cohesion": 0.0, "tensile_strength": 0.0},
    }
    assert all(isinstance(v, float) for law in kw["joints"].values() for v in law.values())
    assert kw["gravity"] == 10.0 and isinstance(kw["gravity"], float)
    assert kw["live"] == "top_horizontal"
    assert case.analysis_kwargs == {
        "control": "displacement",
        "steps": 150,
        "max_displacement": 0.003,
        "control_block": None,
    }
    # the opening removes the blocks whose centroid is inside it
    blocks = kw["blocks"]
    cx, cy = (blocks[:, 0] + blocks[:, 2]) / 2, (blocks[:, 1] + blocks[:, 3]) / 2
    assert not np.any((cx > 0.6) & (cx < 1.0) & (cy > 0.525) & (cy < 1.4))
    assert len(blocks) < 33


def test_joint_families_only(tmp_path: Path) -> None:
    case = load_text(tmp_path, MINIMAL + "[joints.head]\nfriction = 0.5\n[joints.top]\nfriction = 0.4\n")
    assert case.model_kwargs["joints"] == {"head": {"friction": 0.5}, "top": {"friction": 0.4}}


def test_pattern(tmp_path: Path) -> None:
    text = MINIMAL.replace(
        "blocks = [[0.0, 0.0, 0.4, 0.175]]",
        "[geometry.pattern]\nblock_length = 0.3\nblock_height = 0.5\nrows = [[1, -0.5, 1], [1]]",
    )
    blocks = load_text(tmp_path, text).model_kwargs["blocks"]
    assert blocks.shape == (3, 4)


def test_parse_case_and_case_from_dict() -> None:
    case = parse_case(MINIMAL, source="inline")
    assert case.source == "inline"
    with pytest.raises(md.InputError, match=r"^inline: unknown key 'x' at the top level"):
        parse_case("x = 1\n" + MINIMAL, source="inline")
    with pytest.raises(md.InputError, match=r"^d: \[geometry\] needs exactly one"):
        case_from_dict({"format": 1, "geometry": {}}, source="d")


# --------------------------------------------------------------------------------------------------
# Errors: unknown keys
# --------------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "extra, key, where",
    [
        ("titel = 'x'\n", "titel", "at the top level"),
        ("[joints.bed]\nfrictoin = 0.6\n", "frictoin", "in [joints.bed]"),
        ("[joints]\nfriction_angle = 30\n", "friction_angle", "in [joints]"),
        ("[joints.beds]\nfriction = 0.6\n", "beds", "in [joints]"),
        ("[loads]\ngravty = 9.81\n", "gravty", "in [loads]"),
        ("[analysis]\nstep = 10\n", "step", "in [analysis]"),
        ("[base]\ntype = 'fixed'\n", "type", "in [base]"),
        ("[top]\nrotaion = 'fixed'\n", "rotaion", "in [top]"),
        ("[output]\npng = 'x.png'\n", "output", "at the top level"),
    ],
)
def test_unknown_key_is_named(tmp_path: Path, extra: str, key: str, where: str) -> None:
    text = extra + MINIMAL if extra.startswith("titel") else MINIMAL + extra
    message = input_error(tmp_path, text)
    assert f"unknown key '{key}' {where}" in message


def test_unknown_key_in_geometry_tables(tmp_path: Path) -> None:
    message = input_error(tmp_path, RUNNING_BOND + "courses_count = 3\n")
    assert "unknown key 'courses_count' in [geometry.running_bond]" in message
    message = input_error(tmp_path, RUNNING_BOND.replace("thickness = 1.0", "thickness = 1.0\nthicknes = 1.0"))
    assert "unknown key 'thicknes' in [geometry] (did you mean 'thickness'?)" in message


def test_unknown_key_suggests(tmp_path: Path) -> None:
    message = input_error(tmp_path, MINIMAL + "[joints.bed]\nfrictoin = 0.6\n")
    assert message.endswith("unknown key 'frictoin' in [joints.bed] (did you mean 'friction'?)")
    message = input_error(tmp_path, MINIMAL + "[loads]\nzzz = 1\n")
    assert "(allowed: gravity, live, direction, carried)" in message


# --------------------------------------------------------------------------------------------------
# Errors: types
# --------------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "old, new, expected",
    [
        ("courses = 6", 'courses = "6"', "geometry.running_bond.courses: expected an integer, got string"),
        ("courses = 6", "courses = 6.0", "geometry.running_bond.courses: expected an integer, got float"),
        ("courses = 6", "courses = true", "geometry.running_bond.courses: expected an integer, got boolean"),
        ("length = 2.0", "length = true", "geometry.running_bond.length: expected a number, got boolean"),
        ("length = 2.0", 'length = "2.0"', "geometry.running_bond.length: expected a number, got string"),
        ("length = 2.0", "length = [2.0]", "geometry.running_bond.length: expected a number, got array"),
        ("thickness = 1.0", "thickness = {a = 1}", "geometry.thickness: expected a number, got table"),
        ("density = 1000.0", "density = 1979-05-27", "geometry.density: expected a number, got date"),
        (
            'first_course = "half"',
            "first_course = 1",
            "geometry.running_bond.first_course: expected a string, got integer",
        ),
        ('title = "wall"', "title = 3", "title: expected a string, got integer"),
        ("format = 1", 'format = "1"', "format: expected an integer, got string"),
        ("format = 1", "format = true", "format: expected an integer, got boolean"),
    ],
)
def test_wrong_type_is_named(tmp_path: Path, old: str, new: str, expected: str) -> None:
    assert old in RUNNING_BOND
    message = input_error(tmp_path, RUNNING_BOND.replace(old, new, 1))
    assert expected in message, message


@pytest.mark.parametrize(
    "extra, expected",
    [
        ("[joints]\nfriction = true\n", "joints.friction: expected a number, got boolean"),
        ("[joints.head]\ncohesion = '0'\n", "joints.head.cohesion: expected a number, got string"),
        ("[joints]\nbed = 0.5\n", "joints.bed: expected a table, got float"),
        ("[loads]\ngravity = false\n", "loads.gravity: expected a number, got boolean"),
        ("[loads]\nlive = 1\n", "loads.live: expected a string, got integer"),
        ("[analysis]\nsteps = 10.5\n", "analysis.steps: expected an integer, got float"),
        ("[analysis]\nmax_displacement = 'two mm'\n", "analysis.max_displacement: expected a number, got string"),
        ("[analysis]\nmethod = true\n", "analysis.method: expected a string, got boolean"),
        ("[base]\nkind = false\n", "base.kind: expected a string, got boolean"),
        ("[top]\nforce = 5.0\n", "top.force: expected an array, got float"),
        ("[top]\nforce = [1.0]\n", "top.force: expected 2 numbers [Fx, Fy], got 1"),
        ("[top]\nforce = [1.0, 'a']\n", "top.force[1]: expected a number, got string"),
    ],
)
def test_wrong_type_in_tables(tmp_path: Path, extra: str, expected: str) -> None:
    message = input_error(tmp_path, MINIMAL + extra)
    assert expected in message, message


def test_top_level_table_type(tmp_path: Path) -> None:
    message = input_error(tmp_path, "format = 1\ngeometry = 3\n")
    assert "geometry: expected a table, got integer" in message
    message = input_error(tmp_path, "format = 1\n[geometry]\nrunning_bond = 3\n")
    assert "geometry.running_bond: expected a table, got integer" in message
    message = input_error(tmp_path, "loads = [1]\n" + MINIMAL)
    assert "loads: expected a table, got array" in message


@pytest.mark.parametrize(
    "blocks, expected",
    [
        ("blocks = 1", "geometry.blocks: expected an array, got integer"),
        ("blocks = []", "geometry.blocks: expected at least one block"),
        ("blocks = [[0, 0, 1]]", "geometry.blocks[0]: expected 4 numbers [x0, y0, x1, y1], got 3"),
        (
            "blocks = [[0, 0, 1, 1], 5]",
            "geometry.blocks[1]: expected an array of 4 numbers [x0, y0, x1, y1], got integer",
        ),
        ("blocks = [[0, 0, 1, 1], [1, 0, 2, true]]", "geometry.blocks[1][3]: expected a number, got boolean"),
        ("blocks = [[0, 0, 1, 'a']]", "geometry.blocks[0][3]: expected a number, got string"),
        ("blocks = [[1, 0, 0, 1]]", "geometry.blocks[0]: expected x1 > x0 and y1 > y0"),
        ("blocks = [[0, 0, 1, nan]]", "geometry.blocks[0][3]: expected a finite number, got nan"),
    ],
)
def test_explicit_blocks(tmp_path: Path, blocks: str, expected: str) -> None:
    message = input_error(tmp_path, MINIMAL.replace("blocks = [[0.0, 0.0, 0.4, 0.175]]", blocks))
    assert expected in message, message


def test_openings_and_rows(tmp_path: Path) -> None:
    message = input_error(tmp_path, RUNNING_BOND + "openings = [[0.6, 0.5, 1.0]]\n")
    assert "geometry.running_bond.openings[0]: expected 4 numbers [x0, y0, x1, y1], got 3" in message
    message = input_error(tmp_path, RUNNING_BOND + "openings = 'none'\n")
    assert "geometry.running_bond.openings: expected an array, got string" in message
    pattern = MINIMAL.replace(
        "blocks = [[0.0, 0.0, 0.4, 0.175]]", "[geometry.pattern]\nblock_length = 0.4\nblock_height = 0.2\nrows = ROWS"
    )
    message = input_error(tmp_path, pattern.replace("ROWS", "[[1, 'x']]"))
    assert "geometry.pattern.rows[0][1]: expected a number, got string" in message
    message = input_error(tmp_path, pattern.replace("ROWS", "[1, 2]"))
    assert "geometry.pattern.rows[0]: expected an array of numbers, got integer" in message
    message = input_error(tmp_path, pattern.replace("ROWS", "[[1, 0]]"))
    assert "geometry.pattern.rows[0][1]: must not be 0" in message
    message = input_error(tmp_path, pattern.replace("rows = ROWS", ""))
    assert "missing key 'rows' in [geometry.pattern]" in message


# --------------------------------------------------------------------------------------------------
# Errors: geometry choice, required keys, format, enums, ranges, syntax
# --------------------------------------------------------------------------------------------------


def test_missing_geometry(tmp_path: Path) -> None:
    message = input_error(tmp_path, "format = 1\n")
    assert "missing key 'geometry' at the top level" in message
    message = input_error(tmp_path, "format = 1\n[geometry]\nthickness = 1.0\n")
    assert "[geometry] needs exactly one of running_bond, pattern, blocks, dxf; none is given" in message


def test_two_geometries(tmp_path: Path) -> None:
    message = input_error(
        tmp_path, RUNNING_BOND.replace("[geometry.running_bond]", "blocks = [[0, 0, 1, 1]]\n[geometry.running_bond]")
    )
    assert (
        "[geometry] needs exactly one of running_bond, pattern, blocks, dxf; running_bond and blocks are both given"
        in message
    )
    three = RUNNING_BOND.replace("[geometry.running_bond]", "blocks = [[0, 0, 1, 1]]\n[geometry.running_bond]")
    three += "[geometry.pattern]\nblock_length = 0.4\nblock_height = 0.2\nrows = [[1]]\n"
    assert "all three are given" in input_error(tmp_path, three)


@pytest.mark.parametrize("key", ["block_length", "block_height", "courses", "length"])
def test_missing_required_key(tmp_path: Path, key: str) -> None:
    text = re.sub(rf"^{key} = .*\n", "", RUNNING_BOND, flags=re.M)
    message = input_error(tmp_path, text)
    assert f"missing key '{key}' in [geometry.running_bond]" in message


@pytest.mark.parametrize(
    "text, expected",
    [
        (MINIMAL.replace("format = 1", "format = 2"), "format: expected 1, got 2"),
        (MINIMAL.replace("format = 1", "format = 0"), "format: expected 1, got 0"),
        (MINIMAL.replace("format = 1\n", ""), "missing key 'format' at the top level"),
        (MINIMAL.replace("format = 1", "format = 1.0"), "format: expected an integer, got float"),
    ],
)
def test_bad_format(tmp_path: Path, text: str, expected: str) -> None:
    assert expected in input_error(tmp_path, text)


@pytest.mark.parametrize(
    "extra, expected",
    [
        ("[base]\nkind = 'free'\n", 'base.kind: expected one of "fixed", "none", got "free"'),
        ("[top]\nrotation = 'pinned'\n", 'top.rotation: expected one of "fixed", "free", got "pinned"'),
        ("[loads]\nlive = 'wind'\n", 'loads.live: expected one of "horizontal_weight", "top_horizontal", got "wind"'),
        ("[analysis]\nmethod = 'explicit'\n", 'analysis.method: expected one of "static", "dynamic", "limit", got "explicit"'),
        (
            "[analysis]\ncontrol = 'arc-length'\n",
            'analysis.control: expected one of "load", "displacement", got "arc-length"',
        ),
        ("[analysis]\ncontrol_point = 'middle'\n", 'analysis.control_point: expected one of "top", got "middle"'),
        ("[analysis]\ncontrol_point = 3\n", "analysis.control_point: expected a string, got integer"),
    ],
)
def test_bad_enum(tmp_path: Path, extra: str, expected: str) -> None:
    assert expected in input_error(tmp_path, MINIMAL + extra)


def test_bad_first_course(tmp_path: Path) -> None:
    message = input_error(tmp_path, RUNNING_BOND.replace('first_course = "half"', 'first_course = "Half"'))
    assert 'geometry.running_bond.first_course: expected one of "half", "full", got "Half"' in message


@pytest.mark.parametrize(
    "old, new, expected",
    [
        ("thickness = 1.0", "thickness = 0", "geometry.thickness: must be > 0, got 0"),
        ("density = 1000.0", "density = -1.0", "geometry.density: must be > 0, got -1.0"),
        ("courses = 6", "courses = 0", "geometry.running_bond.courses: must be >= 1, got 0"),
        ("courses = 6", "courses = 100000000000", "geometry.running_bond.courses: must be <= 2147483647"),
        ("length = 2.0", "length = inf", "geometry.running_bond.length: expected a finite number, got inf"),
        ("block_height = 0.175", "block_height = -0.175", "geometry.running_bond.block_height: must be > 0"),
    ],
)
def test_out_of_range(tmp_path: Path, old: str, new: str, expected: str) -> None:
    assert expected in input_error(tmp_path, RUNNING_BOND.replace(old, new, 1))


@pytest.mark.parametrize(
    "extra, expected",
    [
        ("[joints]\nfriction = -0.1\n", "joints.friction: must be >= 0, got -0.1"),
        ("[joints.bed]\nnormal_stiffness = 0\n", "joints.bed.normal_stiffness: must be > 0, got 0"),
        ("[joints]\ncohesion = nan\n", "joints.cohesion: expected a finite number, got nan"),
        ("[analysis]\nsteps = 0\n", "analysis.steps: must be >= 1, got 0"),
        ("[analysis]\nmax_displacement = 0.0\n", "analysis.max_displacement: must be > 0, got 0.0"),
        ("[loads]\ngravity = -9.81\n", "loads.gravity: must be >= 0, got -9.81"),
    ],
)
def test_out_of_range_in_tables(tmp_path: Path, extra: str, expected: str) -> None:
    assert expected in input_error(tmp_path, MINIMAL + extra)


def test_top_horizontal_needs_top(tmp_path: Path) -> None:
    message = input_error(tmp_path, MINIMAL + "[loads]\nlive = 'top_horizontal'\n")
    assert 'loads.live: "top_horizontal" pushes the top beam: add a [top] table' in message


def test_invalid_toml(tmp_path: Path) -> None:
    message = input_error(tmp_path, MINIMAL + "[joints\nfriction = 0.6\n")
    assert "invalid TOML" in message and "line" in message
    message = input_error(tmp_path, "title = 'again'\n" + MINIMAL)
    assert "invalid TOML" in message


def test_not_utf8(tmp_path: Path) -> None:
    path = tmp_path / "latin1.toml"
    path.write_bytes(MINIMAL.replace("one block", "bl\xf6ck").encode("latin-1"))
    with pytest.raises(md.InputError, match=r"latin1\.toml: not a UTF-8 text file"):
        load_case(path)


def test_missing_file_is_oserror(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError):
        load_case(tmp_path / "nope.toml")


def test_message_starts_with_path_as_given(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "rel.toml").write_text(MINIMAL + "bogus = 1\n")
    monkeypatch.chdir(tmp_path)
    with pytest.raises(md.InputError) as info:
        load_case("rel.toml")
    assert str(info.value).startswith("rel.toml: unknown key 'bogus'")


def test_input_error_is_a_masonry_error(tmp_path: Path) -> None:
    with pytest.raises(md.MasonryError):
        load_text(tmp_path, MINIMAL + "bogus = 1\n")


# --------------------------------------------------------------------------------------------------
# Method
# --------------------------------------------------------------------------------------------------


DYNAMIC_KEYS = """\
[analysis]
method = "dynamic"
tolerance = 2e-3
damping = "viscous"
damping_coefficient = 5
time_step = 1e-5
unbalanced_ratio = 1e-4
threads = 1
"""


def test_dynamic_keys_mapping(tmp_path: Path) -> None:
    case = load_text(tmp_path, MINIMAL + DYNAMIC_KEYS)
    assert case.method == "dynamic"
    assert case.analysis_kwargs == {
        "control": "load",
        "steps": 200,
        "max_displacement": None,
        "control_block": None,
        "tolerance": 2e-3,
    }
    assert case.dynamic_kwargs == {
        "damping": "viscous",
        "damping_coefficient": 5.0,
        "time_step": 1e-5,
        "unbalanced_ratio": 1e-4,
        "threads": 1,
    }
    assert isinstance(case.dynamic_kwargs["damping_coefficient"], float)
    # the static solver gets the common keys (tolerance included), the explicit one all of them
    # (an absent max_displacement is left out: each solver's own default)
    common = {k: v for k, v in case.analysis_kwargs.items() if k != "max_displacement"}
    assert case.solver_kwargs("static") == common
    assert case.solver_kwargs("dynamic") == {**common, **case.dynamic_kwargs}
    assert case.solver_kwargs() == case.solver_kwargs("dynamic")


def test_dynamic_keys_are_optional(tmp_path: Path) -> None:
    case = load_text(tmp_path, MINIMAL + "[analysis]\nmethod = 'dynamic'\n")
    assert case.dynamic_kwargs == {}
    assert "tolerance" not in case.analysis_kwargs  # each solver keeps its own default
    case = load_text(tmp_path, MINIMAL + "[analysis]\ndamping = 'none'\ndamping_coefficient = 3.0\n")
    assert case.dynamic_kwargs == {"damping": "none", "damping_coefficient": 3.0}


@pytest.mark.parametrize(
    "line, expected",
    [
        ("damping = 'cundall'", 'analysis.damping: expected one of "local", "viscous", "none", got "cundall"'),
        ("damping = 0.8", "analysis.damping: expected a string, got float"),
        ("damping_coefficient = -0.1", "analysis.damping_coefficient: must be >= 0, got -0.1"),
        ("damping_coefficient = 'high'", "analysis.damping_coefficient: expected a number, got string"),
        ("damping_coefficient = 1.0", 'analysis.damping_coefficient: must be < 1 with damping = "local"'),
        ("damping = 'local'\ndamping_coefficient = 1.5", "analysis.damping_coefficient: must be < 1 with damping"),
        ("time_step = 0", "analysis.time_step: must be > 0, got 0"),
        ("time_step = -1e-5", "analysis.time_step: must be > 0, got -1e-05"),
        ("time_step = inf", "analysis.time_step: expected a finite number, got inf"),
        ("time_step = true", "analysis.time_step: expected a number, got boolean"),
        ("unbalanced_ratio = 0", "analysis.unbalanced_ratio: must lie in (0, 1), got 0"),
        ("unbalanced_ratio = 1", "analysis.unbalanced_ratio: must lie in (0, 1), got 1"),
        ("unbalanced_ratio = '1e-5'", "analysis.unbalanced_ratio: expected a number, got string"),
        ("threads = -1", "analysis.threads: must be >= 0, got -1"),
        ("threads = 2.0", "analysis.threads: expected an integer, got float"),
        ("threads = 'all'", "analysis.threads: expected an integer, got string"),
        ("tolerance = 0.0", "analysis.tolerance: must lie in (0, 1), got 0.0"),
        ("tolerance = 1.5", "analysis.tolerance: must lie in (0, 1), got 1.5"),
        ("tolerance = nan", "analysis.tolerance: expected a finite number, got nan"),
    ],
)
def test_dynamic_keys_validation(tmp_path: Path, line: str, expected: str) -> None:
    message = input_error(tmp_path, MINIMAL + "[analysis]\n" + line + "\n")
    assert expected in message, message


@pytest.mark.parametrize(
    "typo, suggestion",
    [("dampin", "damping"), ("time_stp", "time_step"), ("thread", "threads"), ("tolerence", "tolerance")],
)
def test_dynamic_key_typos_are_named(tmp_path: Path, typo: str, suggestion: str) -> None:
    message = input_error(tmp_path, MINIMAL + f"[analysis]\n{typo} = 1\n")
    assert f"unknown key '{typo}' in [analysis] (did you mean '{suggestion}'?)" in message


def test_dynamic_method_runs_the_explicit_solver(tmp_path: Path) -> None:
    """method = "dynamic" runs Model.solve_dynamic: the single sliding block collapses at mu = 0.65."""
    text = (EXAMPLES / "single-block-sliding.toml").read_text().replace('method = "static"', 'method = "dynamic"')
    case = load_text(tmp_path, text)
    res = case.run()
    assert res.method == "dynamic"
    assert res.status == "collapse", res.error
    assert res.collapse_multiplier == pytest.approx(0.65, rel=0.02)
    # the method argument overrides the file's, both ways
    assert case.run(method="static").method == "static"
    assert load_case(EXAMPLES / "single-block-sliding.toml").run(method="dynamic").method == "dynamic"


def test_core_input_error_in_solver_names_the_file(tmp_path: Path) -> None:
    """A time step above the stability limit passes the loader but the core refuses it; the message
    starts with the file name."""
    case = load_text(tmp_path, MINIMAL + "[analysis]\nmethod = 'dynamic'\ntime_step = 10.0\n")
    with pytest.raises(md.InputError) as info:
        case.run()
    assert str(info.value).startswith(f"{tmp_path / 'case.toml'}: "), str(info.value)


def test_unknown_method_argument(tmp_path: Path) -> None:
    with pytest.raises(md.InputError, match='method: expected one of "static", "dynamic", "limit", got "fem"'):
        load_text(tmp_path, MINIMAL).run(method="fem")


def test_package_exports() -> None:
    for name in (
        "Model",
        "Results",
        "TimeHistory",
        "running_bond",
        "pattern",
        "MasonryError",
        "InputError",
        "ConvergenceError",
        "MechanismError",
        "__version__",
        "load_case",
        "run_case",
    ):
        assert hasattr(md, name), name
    assert issubclass(md.InputError, md.MasonryError)
    assert (Path(md.__file__).parent / "py.typed").exists()


def test_run_case(tmp_path: Path) -> None:
    results = md.run_case(EXAMPLES / "single-block-sliding.toml")
    assert results.method == "static"
    assert results.status in ("collapse", "completed", "failed")


def test_top_vertical(tmp_path: Path) -> None:
    top = '\n[top]\nrotation = "fixed"\nforce = [0.0, -1000.0]\n'
    assert load_text(tmp_path, MINIMAL + top).model_kwargs["top_vertical"] == "free"
    case = load_text(tmp_path, MINIMAL + top + 'vertical = "held"\n')
    assert case.model_kwargs["top_vertical"] == "held"
    case.build_model()  # accepted by the core
    message = input_error(tmp_path, MINIMAL + top + 'vertical = "fixed"\n')
    assert "vertical" in message and "held" in message, message


def test_held_beam_needs_a_beam_and_no_time_history() -> None:
    with pytest.raises(md.InputError, match="top.vertical"):
        md.Model([[0, 0, 1, 1]], top_vertical="held")
    model = md.Model([[0, 0, 1, 1]], top_rotation="fixed", top_force=(0, -1e3), top_vertical="held")
    with pytest.raises(md.InputError, match="held"):
        model.simulate(duration=0.01)
