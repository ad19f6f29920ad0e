"""The [reference] table of case files, ``masonry-dem validate``, ``--help`` epilogs and the script example."""

from __future__ import annotations

import math
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import masonry_dem as md
from masonry_dem import validate

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
SINGLE_BLOCKS = ("single-block-rocking.toml", "single-block-sliding.toml")

CASE = """
format = 1
[geometry]
blocks = [[0.0, 0.0, 0.4, 0.175]]
[joints]
friction = 0.65
"""


def masonry_dem(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "masonry_dem", *args], cwd=cwd, capture_output=True, text=True, timeout=300
    )


def assert_one_line_error(proc: subprocess.CompletedProcess, status: int) -> str:
    assert proc.returncode == status, (proc.stdout, proc.stderr)
    assert "Traceback" not in proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith("masonry-dem: error: "), lines[0]
    return lines[0]


def table_rows(stdout: str) -> dict:
    """{case name: cells} of the rows of a validation table."""
    rows = {}
    for line in stdout.splitlines():
        cells = re.split(r"\s{2,}", line.strip())
        if len(cells) >= 6 and cells[0] not in ("case",) and not set(cells[0]) <= {"-"}:
            rows[cells[0]] = cells
    return rows


# --------------------------------------------------------------------------------------------------
# The [reference] table
# --------------------------------------------------------------------------------------------------


def test_reference_table_parsed() -> None:
    case = md.parse_case(CASE + '[reference]\ncollapse_multiplier = 0.65\ntolerance = 0.005\nsource = "closed form"\n')
    every = ("static", "dynamic", "limit")
    assert case.reference == {"collapse_multiplier": 0.65, "tolerance": 0.005, "source": "closed form", "methods": every}
    case = md.parse_case(CASE + "[reference]\ncollapse_multiplier = 1\n")
    assert case.reference == {"collapse_multiplier": 1.0, "tolerance": 0.01, "source": "", "methods": every}
    case = md.parse_case(CASE + '[reference]\ncollapse_multiplier = 1\nmethods = ["static"]\n')
    assert case.reference["methods"] == ("static",)
    assert md.parse_case(CASE).reference is None


def test_a_reference_applies_to_its_methods_only(tmp_path) -> None:
    # J4D's reference (an experiment) names the static and explicit solvers: limit analysis is not run on it
    case = md.load_case(Path(__file__).resolve().parents[2] / "examples" / "j4d-shear-wall.toml")
    assert case.reference["methods"] == ("static", "dynamic")
    ran = []
    row = validate.validate_case("j4d", case, ("limit",), solve=lambda c, m, method: ran.append(method))
    assert ran == [] and "limit" not in row.multipliers


@pytest.mark.parametrize(
    "table, message",
    [
        ("collapse_multiplier = 0.65\ntolerence = 0.01", "unknown key 'tolerence' in [reference] (did you mean 'tolerance'?)"),
        ("tolerance = 0.01", "collapse_multiplier"),
        ('collapse_multiplier = "0.65"', "collapse_multiplier"),
        ("collapse_multiplier = 0.65\ntolerance = 1.5", "tolerance"),
        ("collapse_multiplier = 0.65\ntolerance = 0", "tolerance"),
        ('collapse_multiplier = 0.65\nmethods = ["exact"]', "methods"),
        ("collapse_multiplier = 0.65\nmethods = []", "methods"),
        ("collapse_multiplier = 0.65\nsource = 3", "source"),
    ],
)
def test_reference_table_checked(table: str, message: str) -> None:
    with pytest.raises(md.InputError) as info:
        md.parse_case(CASE + "[reference]\n" + table + "\n", source="wall.toml")
    text = str(info.value)
    assert text.startswith("wall.toml: ") and message in text, text


def test_examples_carry_their_references() -> None:
    expected = {
        "single-block-sliding": (0.65, 0.005),
        "single-block-rocking": (0.333333, 0.005),
        "stack-3-blocks": (0.2, 0.005),
        "ferris-tinloi-wall1": (0.6429, 0.01),
        "ferris-tinloi-wall2": (0.5800, 0.01),
        "j4d-shear-wall": (57000.0, 0.15),
        "leaf-out-of-plane": (0.0952381, 0.001),
        "semicircular-arch": (0.1276, 0.01),
        "barrel-vault": (0.1276, 0.01),
        "stone-wall": (0.21914, 0.01),
        "wedges-on-a-slope": (0.546573, 0.001),
        "rocking-portal-frame": (0.2, 0.005),
        "rocking-portal-frame-3d": (0.2, 0.005),
    }
    cases, skipped = validate.collect(EXAMPLES)
    found = {p.stem: (c.reference["collapse_multiplier"], c.reference["tolerance"]) for p, c in cases}
    assert found == expected
    assert all(c.reference["source"] for _, c in cases)
    assert [p.name for p in skipped] == ["cross-vault.toml", "ferris-tinloi-wall1-elcentro.toml",
                                         "lact3-tilting-wall.toml", "spreading-arch.toml", "u-wall.toml"]


# --------------------------------------------------------------------------------------------------
# The library side
# --------------------------------------------------------------------------------------------------


def test_validate_row_verdicts() -> None:
    row = validate.ValidationRow("a", "A", reference=0.5, tolerance=0.01)
    row.errors = {"static": 0.002, "dynamic": 0.008}
    assert row.error == 0.008 and row.passed and row.verdict() == "pass"
    row.errors["dynamic"] = 0.02
    assert not row.passed and row.verdict().startswith("FAIL (> 1")
    row.errors["dynamic"] = math.nan
    assert not row.passed and "no collapse multiplier" in row.verdict()
    row.errors["dynamic"] = 0.0
    row.failures["dynamic"] = "did not converge"
    assert not row.passed and "dynamic failed" in row.verdict()
    assert validate.methods_of("both") == ("static", "dynamic")
    with pytest.raises(ValueError):
        validate.methods_of("implicit")


def test_validate_folder_in_process(tmp_path: Path) -> None:
    shutil.copy(EXAMPLES / "stack-3-blocks.toml", tmp_path)
    lines: list = []
    rows, skipped = validate.validate_folder(tmp_path, "static", echo=lines.append)
    assert skipped == [] and len(rows) == 1
    (row,) = rows
    assert row.passed and set(row.multipliers) == {"static"}
    assert abs(row.multipliers["static"] - 0.2) < 0.001
    lines = "\n".join(lines).splitlines()
    assert lines[0].split()[:4] == ["case", "reference", "static", "explicit"]
    assert lines[2].startswith("stack-3-blocks") and lines[2].endswith("pass")
    assert lines[3].startswith("1 case with a reference: 1 passed, 0 failed")


# --------------------------------------------------------------------------------------------------
# The command line
# --------------------------------------------------------------------------------------------------


def test_validate_examples_static(tmp_path: Path) -> None:
    """The default folder is the examples shipped in the package (masonry_dem/examples, in the repository a link
    to its examples/), whatever the current directory: run from an empty one, as from an installed wheel."""
    proc = masonry_dem("validate", "--method", "static", cwd=tmp_path)
    assert proc.returncode == 0, (proc.stdout, proc.stderr)
    assert proc.stderr == ""
    first, header = proc.stdout.splitlines()[:2]
    assert first == f"cases of {EXAMPLES} (the examples shipped with masonry-dem)"
    for word in ("case", "reference", "static", "explicit", "error", "time", "verdict"):
        assert word in header
    rows = table_rows(proc.stdout)
    assert set(rows) == {
        "single-block-sliding",
        "single-block-rocking",
        "stack-3-blocks",
        "ferris-tinloi-wall1",
        "ferris-tinloi-wall2",
        "j4d-shear-wall",
        "leaf-out-of-plane",
        "semicircular-arch",
        "barrel-vault",
        "stone-wall",
        "wedges-on-a-slope",
        "rocking-portal-frame",
        "rocking-portal-frame-3d",
    }
    # the 3D walls' references are limit analysis's: not run, neither passed nor failed
    assert rows.pop("leaf-out-of-plane")[-1] == "not run"
    assert rows.pop("wedges-on-a-slope")[-1] == "not run"
    assert rows.pop("barrel-vault")[-1] == "not run"
    assert rows.pop("rocking-portal-frame-3d")[-1] == "not run"
    for name, cells in rows.items():
        assert cells[-1] == "pass", cells
        assert cells[3] == "-", cells  # the explicit solver was not run
    assert float(rows["ferris-tinloi-wall1"][2]) == pytest.approx(0.6429, rel=0.01)
    assert float(rows["ferris-tinloi-wall2"][2]) == pytest.approx(0.5800, rel=0.01)
    assert "13 cases with a reference: 9 passed, 0 failed, 4 not run" in proc.stdout
    assert "skipped lact3-tilting-wall.toml: no [reference] table" in proc.stdout


def test_validate_both_methods(tmp_path: Path) -> None:
    for name in SINGLE_BLOCKS:
        shutil.copy(EXAMPLES / name, tmp_path)
    text = (EXAMPLES / "single-block-sliding.toml").read_text()
    (tmp_path / "no-reference.toml").write_text(text.split("[reference]")[0])
    proc = masonry_dem("validate", str(tmp_path), "--quiet", "--method", "both")  # the default is all three
    assert proc.returncode == 0, (proc.stdout, proc.stderr)
    rows = table_rows(proc.stdout)
    assert set(rows) == {"single-block-rocking", "single-block-sliding"}
    for cells in rows.values():
        assert cells[-1] == "pass"
        assert cells[2] != "-" and cells[3] != "-" and cells[4] == "-"  # static and explicit, not limit
        assert cells[6].count(" / ") == 1  # a time for each
    assert float(rows["single-block-rocking"][3]) == pytest.approx(1 / 3, rel=0.005)
    assert "skipped no-reference.toml: no [reference] table" in proc.stdout


def test_validate_outside_tolerance_exits_1(tmp_path: Path) -> None:
    text = (EXAMPLES / "single-block-sliding.toml").read_text()
    (tmp_path / "wrong.toml").write_text(text.replace("collapse_multiplier = 0.65", "collapse_multiplier = 0.70"))
    shutil.copy(EXAMPLES / "single-block-rocking.toml", tmp_path)
    proc = masonry_dem("validate", str(tmp_path), "--method", "dynamic")
    assert proc.returncode == 1, (proc.stdout, proc.stderr)
    rows = table_rows(proc.stdout)
    assert rows["wrong"][-1].startswith("FAIL")
    assert rows["wrong"][2] == "-"  # static not run
    assert rows["single-block-rocking"][-1] == "pass"
    assert "2 cases with a reference: 1 passed, 1 failed" in proc.stdout


def test_validate_bad_input(tmp_path: Path) -> None:
    line = assert_one_line_error(masonry_dem("validate", str(tmp_path / "nowhere")), 2)
    assert "no such folder" in line and "nowhere" in line
    line = assert_one_line_error(masonry_dem("validate", str(tmp_path)), 2)
    assert "no case file with a [reference] table" in line
    (tmp_path / "bad.toml").write_text(CASE + "[reference]\ncollapse_multiplier = 0.65\ntolerance = 2\n")
    line = assert_one_line_error(masonry_dem("validate", str(tmp_path)), 2)
    assert "bad.toml" in line and "tolerance" in line
    proc = masonry_dem("validate", "--method", "implicit")
    assert proc.returncode == 2 and "invalid choice" in proc.stderr


@pytest.mark.parametrize("command", [(), ("run",), ("compare",), ("demo",), ("validate",)])
def test_help_ends_with_examples(command: tuple) -> None:
    proc = masonry_dem(*command, "--help")
    assert proc.returncode == 0, proc.stderr
    text = proc.stdout
    assert "\nexamples:\n" in text
    epilog = text[text.index("\nexamples:\n") :]
    assert "masonry-dem " in epilog
    # the epilog closes the help: no option is listed after it
    assert "options:" not in epilog and "positional arguments:" not in epilog
    if command == ("validate",):
        assert "--method" in text and "DIR" in text and "validate --method static" in epilog


# --------------------------------------------------------------------------------------------------
# The script example
# --------------------------------------------------------------------------------------------------


def test_script_example(tmp_path: Path) -> None:
    png = tmp_path / "wall1.png"
    proc = subprocess.run(
        [sys.executable, str(EXAMPLES / "script_example.py"), str(png)],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
        env={**__import__("os").environ, "MPLBACKEND": "Agg"},
    )
    assert proc.returncode == 0, (proc.stdout, proc.stderr)
    out = proc.stdout
    assert "33 blocks, 83 interfaces" in out
    lam = {m: float(v) for m, v in re.findall(r"^(static|explicit)\s*: collapse, lambda = ([0-9.]+)", out, re.M)}
    assert lam["static"] == pytest.approx(0.6429, rel=0.01)
    assert lam["explicit"] == pytest.approx(0.6429, rel=0.01)
    assert "difference" in out and "Jaccard" in out
    assert png.read_bytes().startswith(b"\x89PNG\r\n\x1a\n")


def test_a_limit_estimate_is_compared_and_shown_as_one() -> None:
    """Dilatancy 0: limit analysis gives an estimate, compared with the reference but shown as ~value, with a
    line that says what it is (never as a collapse multiplier)."""
    path = Path(__file__).resolve().parents[2] / "examples" / "single-block-rocking.toml"
    case = md.load_case(path)
    row = validate.validate_case(path, case, ("limit",))
    assert "limit" in row.estimates and "neither a lower nor an upper bound" in row.estimates["limit"]
    assert row.passed and row.multipliers["limit"] == pytest.approx(1 / 3, rel=1e-4)
    assert "~0.3333" in validate.table_row(row, [row.name], ("limit",))
    assert f"{row.name}: limit: estimate: " in validate.table_footer([row], [])
