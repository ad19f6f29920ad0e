"""A table of bad case files: each is refused by ``masonry-dem run`` with exit status 2 and one line on
stderr (no traceback) that names the key, block or interface at fault.

Each case starts from a small valid wall (``BASE``) and changes one thing. Some are caught by the case
loader (types, unknown keys), the others by the Rust core (ranges, geometry, solver options), so the
table checks that both paths reach the user the same way.
"""

from __future__ import annotations

import copy
import os
import subprocess
import sys
import time
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Tuple, Union

import numpy as np
import pytest

import masonry_dem as md


class Raw(str):
    """A TOML value written as is (nan, inf, a 400-digit integer)."""


BASE: Dict[str, Any] = {
    "format": 1,
    "title": "bad input",
    "geometry": {
        "thickness": 1.0,
        "density": 1000.0,
        "running_bond": {"block_length": 0.4, "block_height": 0.2, "courses": 2, "length": 0.8},
    },
    "joints": {"friction": 0.6},
    "analysis": {"steps": 10},
}


def _value(v: Any) -> str:
    if isinstance(v, Raw):
        return str(v)
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return '"' + v + '"'
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    raise TypeError(v)


def to_toml(data: Dict[str, Any], path: str = "") -> str:
    """A small TOML writer: scalars and arrays first, then sub-tables."""
    lines = [f"[{path}]"] if path else []
    for key, v in data.items():
        if not isinstance(v, dict):
            lines.append(f"{key} = {_value(v)}")
    text = "\n".join(lines) + "\n"
    for key, v in data.items():
        if isinstance(v, dict):
            text += "\n" + to_toml(v, f"{path}.{key}" if path else key)
    return text


Edit = Callable[[Dict[str, Any]], None]


def setting(dotted: str, value: Any) -> Edit:
    """Set (or, with value None, delete) the key ``a.b.c`` of the case."""

    def edit(case: Dict[str, Any]) -> None:
        *tables, key = dotted.split(".")
        t = case
        for name in tables:
            t = t.setdefault(name, {})
        if value is None:
            del t[key]
        else:
            t[key] = value

    return edit


def blocks(rects: List[List[Any]]) -> Edit:
    def edit(case: Dict[str, Any]) -> None:
        case["geometry"].pop("running_bond")
        case["geometry"]["blocks"] = rects

    return edit


def pattern(rows: List[List[Any]]) -> Edit:
    def edit(case: Dict[str, Any]) -> None:
        case["geometry"].pop("running_bond")
        case["geometry"]["pattern"] = {"block_length": 0.4, "block_height": 0.2, "rows": rows}

    return edit


def several(*edits: Edit) -> Edit:
    def edit(case: Dict[str, Any]) -> None:
        for e in edits:
            e(case)

    return edit


# (id, an edit of BASE or the file's whole text or bytes, words the message must contain)
CASES: List[Tuple[str, Union[Edit, str, bytes], Tuple[str, ...]]] = [
    # [geometry]
    ("thickness-zero", setting("geometry.thickness", 0), ("geometry.thickness",)),
    ("thickness-negative", setting("geometry.thickness", -0.3), ("geometry.thickness",)),
    ("density-nan", setting("geometry.density", Raw("nan")), ("geometry.density",)),
    ("density-string", setting("geometry.density", "heavy"), ("geometry.density", "number")),
    ("density-overflows-mass", several(setting("geometry.density", 1e300), setting("geometry.thickness", 1e10)), ("block 0",)),
    ("block-length-zero", setting("geometry.running_bond.block_length", 0.0), ("geometry.running_bond.block_length",)),
    ("block-height-inf", setting("geometry.running_bond.block_height", Raw("inf")), ("geometry.running_bond.block_height",)),
    ("courses-zero", setting("geometry.running_bond.courses", 0), ("geometry.running_bond.courses",)),
    ("courses-string", setting("geometry.running_bond.courses", "ten"), ("geometry.running_bond.courses", "integer")),
    ("courses-float", setting("geometry.running_bond.courses", 2.5), ("geometry.running_bond.courses", "integer")),
    ("billion-blocks", setting("geometry.running_bond.length", 4e8), ("geometry.running_bond",)),
    ("wall-too-high", several(setting("geometry.running_bond.block_height", 1e305), setting("geometry.running_bond.courses", 10**4)), ("geometry.running_bond",)),
    ("first-course-unknown", setting("geometry.running_bond.first_course", "third"), ("geometry.running_bond.first_course",)),
    ("opening-inverted", setting("geometry.running_bond.openings", [[1.0, 0.0, 0.0, 1.0]]), ("geometry.running_bond.openings[0]",)),
    ("running-bond-typo", setting("geometry.running_bond.block_lenght", 0.4), ("block_lenght",)),
    ("two-geometries", setting("geometry.blocks", [[0, 0, 1, 1]]), ("running_bond", "blocks")),
    ("no-geometry", setting("geometry.running_bond", None), ("geometry",)),
    ("pattern-zero-entry", pattern([[1, 0]]), ("geometry.pattern.rows[0][1]",)),
    ("pattern-overflow", pattern([[1e308] * 5]), ("geometry.pattern.rows[0][4]",)),
    ("blocks-overlap", blocks([[0, 0, 1, 1], [0.5, 0.5, 1.5, 1.5]]), ("block 0 [0, 0, 1, 1]", "block 1 [0.5, 0.5, 1.5, 1.5]")),
    ("block-touches-nothing", blocks([[0, 0, 1, 1], [0, 2, 1, 3]]), ("block 1 [0, 2, 1, 3]",)),
    ("block-zero-width", blocks([[0, 0, 0, 1]]), ("geometry.blocks[0]",)),
    ("block-three-numbers", blocks([[0, 0, 1]]), ("geometry.blocks[0]",)),
    ("block-huge-integer", blocks([[0, 0, Raw("1" + "0" * 400), 1]]), ("geometry.blocks[0][2]",)),
    ("block-area-underflows", blocks([[0, 0, 1e-170, 1e-170]]), ("block 0",)),
    (
        "ten-million-blocks",
        several(setting("geometry.running_bond.courses", 10_000), setting("geometry.running_bond.length", 400.0)),
        ("limit of 2000000", "GB"),
    ),
    ("thickness-overflows-stiffness", setting("geometry.thickness", 1e300), ("stiffness", "geometry.thickness")),
    ("density-sinks-the-wall", setting("geometry.density", 1e300), ("sink", "small-displacement", "geometry.density")),
    ("gravity-sinks-the-wall", setting("loads.gravity", 1e300), ("sink", "small-displacement", "loads.gravity")),
    # [base], [top]
    ("no-support", setting("base.kind", "none"), ("no support",)),
    ("base-kind-unknown", setting("base.kind", "floating"), ("base.kind",)),
    ("top-rotation-unknown", setting("top.rotation", "pinned"), ("top.rotation",)),
    ("top-force-nan", setting("top.force", [0.0, Raw("nan")]), ("top.force[1]",)),
    ("top-force-one-number", setting("top.force", [1.0]), ("top.force",)),
    (
        "driven-beam-without-load",
        several(setting("top.rotation", "free"), setting("analysis.control", "displacement")),
        ("top beam", "top.force"),
    ),
    # [joints]
    ("friction-negative", setting("joints.friction", -0.1), ("joints.friction",)),
    ("friction-in-degrees", setting("joints.friction", 35), ("joints.friction = 35", "tan(phi)", "friction = 0.700")),
    ("bed-normal-stiffness-zero", setting("joints.bed.normal_stiffness", 0), ("joints.bed.normal_stiffness",)),
    ("base-shear-stiffness-inf", setting("joints.base.shear_stiffness", Raw("inf")), ("joints.base.shear_stiffness",)),
    ("head-dilatancy-above-friction", setting("joints.head.dilatancy", 0.9), ("joints.head.dilatancy",)),
    ("cohesion-negative", setting("joints.cohesion", -1.0), ("joints.cohesion",)),
    ("tensile-strength-string", setting("joints.tensile_strength", "strong"), ("joints.tensile_strength", "number")),
    ("fracture-energy-alone", setting("joints.fracture_energy_tension", 10.0), ("joints.fracture_energy_tension",)),
    ("joints-typo", setting("joints.frictoin", 0.6), ("frictoin",)),
    ("stiffness-ratio-1e3", setting("joints.shear_stiffness", 1e13), ("shear_stiffness / normal_stiffness", "1e-3 .. 1e2")),
    ("cohesion-unbreakable", setting("joints.cohesion", 1e14), ("joints.cohesion = 1e14", "own weight", "1e3 times")),
    ("tensile-strength-1e300", setting("joints.tensile_strength", 1e300), ("joints.tensile_strength", "own weight")),
    ("bed-cohesion-unbreakable", setting("joints.bed.cohesion", 1e20), ("joints.bed.cohesion",)),
    ("joints-unknown-family", setting("joints.corner", {"friction": 0.5}), ("corner",)),
    # [loads]
    ("gravity-negative", setting("loads.gravity", -9.81), ("loads.gravity",)),
    ("gravity-zero-with-weight-load", setting("loads.gravity", 0.0), ("gravity",)),
    ("gravity-overflows-weight", several(setting("loads.gravity", 1e305), setting("geometry.density", 1e10)), ("loads.gravity",)),
    ("live-top-without-beam", setting("loads.live", "top_horizontal"), ("loads.live",)),
    # [analysis]
    ("steps-zero", setting("analysis.steps", 0), ("analysis.steps",)),
    ("steps-string", setting("analysis.steps", "ten"), ("analysis.steps", "integer")),
    ("steps-trillion", setting("analysis.steps", 10**12), ("analysis.steps",)),
    ("steps-above-core-limit", setting("analysis.steps", 2_000_000), ("analysis.steps",)),
    ("max-displacement-zero", setting("analysis.max_displacement", 0.0), ("analysis.max_displacement",)),
    ("method-unknown", setting("analysis.method", "fem"), ("analysis.method",)),
    ("control-unknown", setting("analysis.control", "arc-length"), ("analysis.control",)),
    ("tolerance-above-one", setting("analysis.tolerance", 1.5), ("analysis.tolerance",)),
    ("time-step-unstable", several(setting("analysis.method", "dynamic"), setting("analysis.time_step", 10.0)), ("analysis.time_step",)),
    ("threads-absurd", several(setting("analysis.method", "dynamic"), setting("analysis.threads", 100_000)), ("analysis.threads",)),
    ("local-damping-one", several(setting("analysis.method", "dynamic"), setting("analysis.damping_coefficient", 1.5)), ("analysis.damping_coefficient",)),
    ("unbalanced-ratio-zero", setting("analysis.unbalanced_ratio", 0.0), ("analysis.unbalanced_ratio",)),
    # the file as a whole
    ("format-two", setting("format", 2), ("format",)),
    ("format-missing", setting("format", None), ("format",)),
    ("title-number", setting("title", 5), ("title",)),
    ("unknown-table", setting("loading.gravity", 9.81), ("loading",)),
    ("reference-tolerance", several(setting("reference.collapse_multiplier", 0.5), setting("reference.tolerance", 2.0)), ("reference.tolerance",)),
    ("invalid-toml", "format = 1\n[geometry\n", ("invalid TOML",)),
    ("nested-too-deep", "format = 1\nx = " + "[" * 5000 + "]" * 5000 + "\n", ("invalid TOML",)),
    ("integer-too-long", "format = 1\nx = " + "9" * 5000 + "\n", ("invalid TOML",)),
    ("not-utf8", b"format = 1\ntitle = \"caf\xe9\"\n", ("UTF-8",)),
]


def run_cli(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "masonry_dem.cli", *args], cwd=cwd, capture_output=True, text=True, timeout=300
    )


def write_case(tmp_path: Path, source: Union[Edit, str, bytes]) -> Path:
    path = tmp_path / "bad.toml"
    if isinstance(source, bytes):
        path.write_bytes(source)
    elif isinstance(source, str):
        path.write_text(source)
    else:
        case = copy.deepcopy(BASE)
        source(case)
        path.write_text(to_toml(case))
    return path


def test_the_table_is_long_enough() -> None:
    assert len(CASES) >= 30
    assert len({name for name, _, _ in CASES}) == len(CASES)


def test_the_base_case_runs(tmp_path: Path) -> None:
    """The cases differ from BASE by one thing, so BASE itself must be good."""
    path = write_case(tmp_path, lambda case: None)
    proc = run_cli("run", str(path), "--quiet", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr


@pytest.mark.parametrize("source, needles", [(s, n) for _, s, n in CASES], ids=[name for name, _, _ in CASES])
def test_bad_input_is_refused(tmp_path: Path, source: Union[Edit, str, bytes], needles: Tuple[str, ...]) -> None:
    path = write_case(tmp_path, source)
    proc = run_cli("run", str(path), "--quiet", cwd=tmp_path)
    assert proc.returncode == 2, (proc.returncode, proc.stdout, proc.stderr)
    assert "Traceback" not in proc.stderr, proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith("masonry-dem: error: "), lines[0]
    for needle in needles:
        assert needle in lines[0], f"{needle!r} not named in {lines[0]!r}"


def test_a_missing_file_is_named(tmp_path: Path) -> None:
    proc = run_cli("run", "no-such-case.toml", cwd=tmp_path)
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and "no-such-case.toml" in lines[0] and "Traceback" not in proc.stderr


# --------------------------------------------------------------------------------------------------
# Files and arguments that used to give long or cryptic messages
# --------------------------------------------------------------------------------------------------

WALL1_CASE = Path(__file__).resolve().parents[2] / "examples" / "ferris-tinloi-wall1.toml"


def test_an_argument_error_is_one_line() -> None:
    proc = subprocess.run([sys.executable, "-m", "masonry_dem", "run"], capture_output=True, text=True)
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and "CASE.toml" in lines[0] and "--help" in lines[0], proc.stderr


def test_a_byte_order_mark_is_accepted(tmp_path: Path) -> None:
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + WALL1_CASE.read_bytes())
    assert md.load_case(path).title == md.load_case(WALL1_CASE).title


def test_a_long_unknown_key_is_not_echoed_whole(tmp_path: Path) -> None:
    path = tmp_path / "long.toml"
    key = "k" * 100_000
    path.write_text(WALL1_CASE.read_text().replace("[geometry]", f"[geometry]\n{key} = 1", 1))
    with pytest.raises(md.InputError) as err:
        md.load_case(path)
    assert len(str(err.value)) < 500 and "100,000 characters" in str(err.value)


@pytest.mark.parametrize(
    "text, name, line",
    [("format = 1\nformat = 1\n", "format", 2), ("[geometry]\nthickness = 1\n[geometry]\n", "geometry", 3)],
)
def test_a_duplicate_key_is_named(text: str, name: str, line: int) -> None:
    with pytest.raises(md.InputError, match=rf"duplicate key '{name}' \(line {line}\)"):
        md.parse_case(text)


def test_a_case_file_beyond_the_size_limit_is_refused_unread(tmp_path) -> None:
    # /dev/zero never ends: read whole, it took the machine's memory; it is no file to read
    with pytest.raises(md.InputError, match="a device, not a regular file"):
        md.load_case("/dev/zero")
    # a file above the limit is refused from its size, before it is read (a sparse file: nothing written)
    big = tmp_path / "big.toml"
    with open(big, "wb") as f:
        f.truncate(md.case.MAX_CASE_BYTES + 1)
    start = time.monotonic()
    with pytest.raises(md.InputError, match=r"big.toml: 16,777,217 bytes, larger than the limit of 16 MiB"):
        md.load_case(big)
    assert time.monotonic() - start < 1.0


def _in_time(func, seconds=10.0):
    """Run ``func`` in a thread; fail (rather than hang) if it has not returned within ``seconds``."""
    import threading

    out = {}

    def run():
        try:
            out["value"] = func()
        except BaseException as exc:  # noqa: BLE001 - handed to the test
            out["error"] = exc

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    thread.join(seconds)
    assert not thread.is_alive(), f"{func} still runs after {seconds} s (a FIFO opened?)"
    return out


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs")
@pytest.mark.parametrize("reader", ["case", "csv", "at2", "study"])
def test_a_fifo_is_refused_unopened(tmp_path, reader) -> None:
    from masonry_dem import ground_motion

    fifo = tmp_path / ("f.toml" if reader in ("case", "study") else f"f.{reader}")
    os.mkfifo(fifo)
    call = {
        "case": lambda: md.load_case(fifo),
        "csv": lambda: ground_motion.read_csv(fifo, units="g"),
        "at2": lambda: ground_motion.read_at2(fifo),
        "study": lambda: __import__("masonry_dem.study", fromlist=["load_study"]).load_study(fifo),
    }[reader]
    out = _in_time(call)
    assert isinstance(out.get("error"), md.InputError), out
    assert "it is a FIFO, not a regular file" in str(out["error"]) and str(fifo) in str(out["error"])


def test_a_record_beyond_the_size_limit_is_refused_unread(tmp_path) -> None:
    from masonry_dem import ground_motion

    big = tmp_path / "big.csv"
    with open(big, "wb") as f:
        f.truncate(ground_motion.MAX_RECORD_BYTES + 1)
    with pytest.raises(md.InputError, match="larger than the limit of 256 MiB for a record"):
        ground_motion.read_csv(big, units="g")


@pytest.mark.parametrize(
    "call, needles",
    [
        (lambda: md.running_bond("a", 0.175, 6, 2.0), ("running_bond", "'block_length' = 'a'", "real number")),
        (lambda: md.running_bond(0.4, 0.175, 6.5, 2.0), ("running_bond", "'courses' = 6.5", "integer")),
        (lambda: md.running_bond(0.4, 0.175, 2**70, 2.0), ("running_bond", "'courses'", "out of range")),
        (lambda: md.Model(md.running_bond(0.4, 0.175, 6, 2.0), thickness="thick"), ("Model", "'thickness'")),
        (lambda: WALL().solve_static(steps="ten"), ("Model.solve_static", "'steps' = 'ten'")),
        (lambda: WALL().solve_static(steps=10**30), ("Model.solve_static", "'steps'", "out of range")),
        (lambda: WALL().solve_static(control=1), ("Model.solve_static", "'control' = 1")),
        (lambda: WALL().solve_dynamic(tolerance=[1e-3]), ("Model.solve_dynamic", "'tolerance'")),
        (lambda: WALL().solve_limit(max_iterations=1.5), ("Model.solve_limit", "'max_iterations' = 1.5")),
        (lambda: WALL().simulate("1 s"), ("Model.simulate", "'duration' = '1 s'")),
        (lambda: WALL().fix(-1, 0), ("Model.fix", "'block' = -1", "out of range")),
    ],
)
def test_a_wrong_argument_type_in_the_api_is_an_input_error(call: Any, needles: Tuple[str, ...]) -> None:
    """The API raises InputError (not TypeError or OverflowError) naming the function and the argument."""
    with pytest.raises(md.InputError) as info:
        call()
    for needle in needles:
        assert needle in str(info.value), (needle, str(info.value))


def WALL() -> md.Model:
    return md.Model(md.running_bond(0.4, 0.175, 6, 2.0), gravity=10.0)


def test_an_exception_of_the_progress_callback_is_not_turned_into_an_input_error() -> None:
    def progress(*args: Any) -> None:
        raise TypeError("the user's own")

    with pytest.raises(TypeError, match="the user's own") as info:
        WALL().solve_static(progress=progress)
    assert info.value.results.status == "interrupted"  # type: ignore[attr-defined]


def test_many_identical_blocks_are_refused_at_once() -> None:
    # every copy of a block shares all its grid cells with the others: the pairs of a cell were all
    # compared before the overlap was reported (200,000 blocks: minutes)
    rects = np.tile([[0.0, 0.0, 1.0, 1.0]], (200_000, 1))
    with pytest.raises(md.InputError, match=r"block 0 \[0, 0, 1, 1\] and block 1 \[0, 0, 1, 1\] overlap"):
        md.Model(rects)


def test_a_time_history_accepts_joints_meant_never_to_fail() -> None:
    # the strength range limits the analyses that raise lambda to collapse, not a free vibration
    model = md.Model(md.running_bond(0.4, 0.175, 2, 0.8), gravity=10.0,
                     joints={"default": {"friction": 0.65, "cohesion": 1e15, "tensile_strength": 1e15}})
    assert model.simulate(0.001).status == "completed"
    with pytest.raises(md.InputError, match="own weight"):
        model.solve_static()


def test_a_model_beyond_the_memory_is_a_memory_error() -> None:
    """Under an address-space limit (ulimit -v) a model that needs more is refused with MemoryError before
    it allocates, with the memory it needs, instead of the process aborting."""
    script = """
import resource
resource.setrlimit(resource.RLIMIT_AS, (2_000_000_000, resource.RLIM_INFINITY))
import masonry_dem as md
blocks = md.running_bond(0.4, 0.175, 870, 870.0)  # 1.9 million blocks: about 2.3 GB as a model
try:
    md.Model(blocks)
except MemoryError as exc:
    print("MemoryError:", exc)
"""
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert "MemoryError: a model of 1892685 blocks needs about 2.3 GB" in proc.stdout, (proc.stdout, proc.stderr)


def test_errors_are_standard_exceptions_that_name_their_key() -> None:
    """InputError is a ValueError (code that knows nothing of masonry_dem catches it) of module masonry_dem,
    and carries the case-file key it concerns, from the core and from the case-file reader alike."""
    assert issubclass(md.InputError, ValueError) and issubclass(md.InputError, md.MasonryError)
    assert issubclass(md.ConvergenceError, md.MasonryError) and issubclass(md.MechanismError, md.MasonryError)
    assert md.InputError.__module__ == "masonry_dem" and md.MasonryError.__module__ == "masonry_dem"
    blocks = md.running_bond(0.4, 0.2, 2, 1.2)
    for kwargs, key in [({"thickness": -1.0}, "geometry.thickness"), ({"live": "sideways"}, "loads.live"),
                        ({"top_vertical": "held"}, "top.vertical")]:
        with pytest.raises(ValueError) as info:
            md.Model(blocks, **kwargs)
        assert isinstance(info.value, md.InputError) and info.value.key == key, (kwargs, info.value)
    text = 'format = 1\ntitle = "t"\n[geometry]\nthickness = -1.0\n[geometry.running_bond]\n' \
           'block_length = 0.4\nblock_height = 0.2\ncourses = 2\nlength = 1.2\n'
    with pytest.raises(md.InputError) as info:
        md.parse_case(text)
    assert info.value.key == "geometry.thickness"
    with pytest.raises(md.InputError) as info:
        md.Model(blocks, joints={"default": {"friction": 0.6}, "side": {}})
    assert info.value.key == "joints" and "unknown family" in str(info.value)


def test_the_defaults_python_shows_are_the_cores() -> None:
    """Case files show the defaults of the keys they leave out from the core's own (``_core.DEFAULTS``): a
    model built with them is the model built with nothing said."""
    from masonry_dem import _core
    d = _core.DEFAULTS
    blocks = md.running_bond(0.4, 0.2, 2, 1.2)
    said = md.Model(blocks, thickness=d["thickness"], density=d["density"], base=d["base"], gravity=d["gravity"],
                    live=d["live"], top_rotation="fixed", top_force=d["top_force"], top_vertical=d["top_vertical"])
    unsaid = md.Model(blocks, top_rotation="fixed")
    assert said.live == unsaid.live == d["live"]
    np.testing.assert_array_equal(said.rects, unsaid.rects)
    a, b = said.solve_static(steps=d["steps"], control=d["control"]), unsaid.solve_static()
    assert a.collapse_multiplier == b.collapse_multiplier and a.steps == b.steps
