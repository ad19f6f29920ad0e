"""Every ```python block of README.md runs (in a fresh namespace, from the repository root), and prints what the
README says it prints; every command of its ```sh blocks is run here, or (when it takes longer than the suite
affords, or needs a cluster) named with the test that runs it on a smaller input.

A ``print(...)`` statement with a trailing comment states its output: ``print(x)   # collapse 0.6429`` must print
exactly ``collapse 0.6429``; a comment holding "about NUMBER" (``# first impact, about 0.36 s``) is a statement
within NUMBER's precision: the printed number, rounded to as many decimals as NUMBER has, equals it. The output of
each print is attributed to its statement by the line it is called from (the block's ``print`` records it), so that
prints without a comment (a table) are left alone.
"""

from __future__ import annotations

import ast
import builtins
import io
import re
import sys
import tokenize
from pathlib import Path
from typing import Any, Dict, List, Optional, Tuple

import pytest

ROOT = Path(__file__).resolve().parents[2]
README = ROOT / "README.md"
FENCE = re.compile(r"^```python[ \t]*\n(.*?)^```[ \t]*$", re.S | re.M)
ABOUT = re.compile(r"\babout\s+([-+]?\d+(?:\.(\d+))?)")
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def python_blocks(text: Optional[str] = None) -> List[str]:
    return FENCE.findall(README.read_text(encoding="utf-8") if text is None else text)


def stated_outputs(code: str) -> List[Tuple[int, int, str]]:
    """(first line, last line, the comment's text) of each top-level-or-nested ``print(...)`` statement of ``code``
    that ends with a comment."""
    comments: Dict[int, str] = {}
    for tok in tokenize.generate_tokens(io.StringIO(code).readline):
        if tok.type == tokenize.COMMENT:
            comments[tok.start[0]] = tok.string[1:].strip()
    out = []
    for node in ast.walk(ast.parse(code)):
        if (isinstance(node, ast.Expr) and isinstance(node.value, ast.Call)
                and isinstance(node.value.func, ast.Name) and node.value.func.id == "print"):
            end = node.end_lineno or node.lineno
            if end in comments and comments[end]:
                out.append((node.lineno, end, comments[end]))
    return sorted(out)


def check_statement(stated: str, printed: str) -> Optional[str]:
    """None if ``printed`` (a print's output, without its final newline) is what ``stated`` says, else why not."""
    about = ABOUT.search(stated)
    if about is None:
        return None if printed == stated else f"prints {printed!r}, the README says {stated!r}"
    expected = float(about.group(1))
    decimals = len(about.group(2) or "")
    numbers = NUMBER.findall(printed)
    if len(numbers) != 1:
        return f"prints {printed!r}, the README says {stated!r} (one number expected)"
    value = float(numbers[0])
    if abs(round(value, decimals) - expected) > 0.5 * 10.0 ** -(decimals + 3):
        return f"prints {printed!r}, which rounds to {round(value, decimals)!r}, the README says {stated!r}"
    return None


def run_block(code: str, name: str) -> List[str]:
    """Run ``code`` with a ``print`` that records each output by the line it is called from; return the
    mismatches with the outputs its comments state (empty when it prints what it says)."""
    filename = f"<{name}>"
    printed: Dict[int, List[str]] = {}

    def recording_print(*args: Any, **kwargs: Any) -> None:
        if kwargs.get("file") not in (None, sys.stdout):
            builtins.print(*args, **kwargs)
            return
        buffer = io.StringIO()
        builtins.print(*args, **{**kwargs, "file": buffer})
        frame = sys._getframe(1)
        while frame is not None and frame.f_code.co_filename != filename:
            frame = frame.f_back
        line = frame.f_lineno if frame is not None else 0
        printed.setdefault(line, []).append(buffer.getvalue())
        sys.stdout.write(buffer.getvalue())

    namespace = {"__name__": name.replace(" ", "_"), "print": recording_print}
    exec(compile(code, filename, "exec"), namespace)
    problems = []
    for first, last, stated in stated_outputs(code):
        text = "".join(t for line in range(first, last + 1) for t in printed.get(line, []))
        if text.endswith("\n"):
            text = text[:-1]
        why = check_statement(stated, text)
        if why is not None:
            problems.append(f"line {first}: {why}")
    return problems


def test_readme_has_python_blocks() -> None:
    assert python_blocks(), "README.md has no ```python block"


def test_readme_states_outputs() -> None:
    assert any(stated_outputs(code) for code in python_blocks()), "no README block states what it prints"


@pytest.mark.parametrize("index", range(len(python_blocks())))
def test_readme_block_runs(index: int, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(ROOT)
    monkeypatch.setenv("MPLBACKEND", "Agg")  # a block that plots must not open a window
    problems = run_block(python_blocks()[index], f"README.md python block {index + 1}")
    assert not problems, f"README.md (python block {index + 1}) does not print what it says:\n" + "\n".join(problems)


# The checker itself: a wrong statement must fail.

def test_checker_catches_wrong_exact_output() -> None:
    code = "x = 0.6428590033139238\nprint('collapse', round(x, 4))   # collapse 0.6428\n"
    problems = run_block(code, "wrong exact")
    assert len(problems) == 1 and "'collapse 0.6429'" in problems[0]
    assert run_block(code.replace("0.6428\n", "0.6429\n"), "right exact") == []


def test_checker_about_is_a_tolerance() -> None:
    code = "print(round(0.3612, 3))  # first impact, about 0.36 s\n"
    assert run_block(code, "about right") == []
    assert run_block(code.replace("0.36 s", "0.4 s"), "about coarser") == []   # 0.361 rounds to 0.4
    assert len(run_block(code.replace("0.36 s", "0.37 s"), "about wrong")) == 1
    assert check_statement("about 0.361", "0.3612") is None
    assert check_statement("about 0.36", "0.3651") is not None
    assert check_statement("about 0.36", "t = 0.36, 0.37") is not None   # which number?


def test_checker_attributes_output_to_its_line() -> None:
    code = ("for i in range(2):\n    print(i)\nprint('a',\n      'b')  # a b\n"
            "def f():\n    print('inside')\nprint(f())  # None\n")
    assert run_block(code, "lines") == []   # 'inside' is printed from line 6, not by the print of line 7
    assert run_block(code.replace("# a b", "# a  b"), "lines") == ["line 3: prints 'a b', the README says 'a  b'"]
    assert stated_outputs(code) == [(3, 4, "a b"), (7, 7, "None")]


# --------------------------------------------------------------------------------------------------
# The commands of the ```sh blocks
# --------------------------------------------------------------------------------------------------

SH_FENCE = re.compile(r"^```sh[ \t]*\n(.*?)^```[ \t]*$", re.S | re.M)
MASONRY_DEM = ".venv/bin/masonry-dem "
WALL1 = "examples/ferris-tinloi-wall1.toml"


def shell_commands(text: Optional[str] = None) -> List[str]:
    """The commands of README.md's ```sh blocks, each without its comment, spaces collapsed."""
    blocks = SH_FENCE.findall(README.read_text(encoding="utf-8") if text is None else text)
    commands = (" ".join(line.split("#", 1)[0].split()) for block in blocks for line in block.splitlines())
    return [c for c in commands if c]


#: README commands of masonry-dem run here as written (in this process, from the repository root, out/ in a
#: temporary folder), with words their output must hold and the files they must write. The simulation of the El
#: Centro record gets --duration 0.3: its 31 s take a minute.
RUN_HERE: Dict[str, Tuple[Tuple[str, ...], Tuple[str, ...]]] = {
    f"run {WALL1} --json out/wall1.json --plot out/wall1.png": (("collapse multiplier: 0.6429",), ("wall1.json", "wall1.png")),
    f"run {WALL1} --method dynamic": (("method:              dynamic", "status:              collapse"), ()),
    f"run {WALL1} --method limit": (("collapse multiplier: 0.6429", "certificate:"), ()),
    "compare examples/single-block-rocking.toml --plot out/compare.png": (("static", "dynamic", "limit"), ("compare.png",)),
    f"run {WALL1} --vtk out/wall1 --csv out/wall1.csv": ((), ("wall1-blocks.vtu", "wall1-interfaces.vtu", "wall1.csv")),
    "simulate examples/ferris-tinloi-wall1-elcentro.toml --scale 3 --plot out/ec.png --gif out/ec.gif":
        (("status:              completed",), ("ec.png", "ec.gif")),
    "run examples/u-wall.toml --plot out/u-wall.png --vtk out/u-wall":
        (("collapse multiplier: 0.2960",), ("u-wall.png", "u-wall-blocks.vtu", "u-wall-interfaces.vtu")),
    "validate examples/leaf-out-of-plane.toml": (("leaf-out-of-plane", "pass", "1 case with a reference: 1 passed"), ()),
    "run examples/stone-wall.toml --plot out/stone-wall.png": (("collapse multiplier: 0.2191",), ("stone-wall.png",)),
    "run examples/rocking-portal-frame.toml --plot out/portal.png":
        (("collapse multiplier: 0.2000", "along the mechanism: λ from 0.2000 to 0.0"), ("portal.png",)),
}

#: README commands that take longer than the suite affords (the studies of 1,000 walls, J4D's explicit run, the
#: U's explicit pushover, every example by the three methods, the El Centro ladder of 8 minutes), need a cluster
#: (HOST), or are the suite itself: the test that runs each (the same command on a smaller input), "file::test".
ELSEWHERE: Dict[str, str] = {
    "make demo": "tests/python/test_cli.py::test_demo_outputs",  # masonry-dem demo, which make demo runs once built
    "make test": "Makefile::test",  # the suite itself, run by CI
    ".venv/bin/masonry-dem validate": "tests/python/test_validate.py::test_validate_examples_static",
    ".venv/bin/masonry-dem compare examples/j4d-shear-wall.toml --plot out/j4d.png":
        "tests/python/test_cli.py::test_compare",
    ".venv/bin/masonry-dem run examples/u-wall.toml --method dynamic":
        "tests/python/test_space.py::test_the_explicit_solver_finds_the_limit_analysis_multiplier_of_a_u_wall",
    ".venv/bin/python examples/u_wall_3d.py": "tests/python/test_space.py::test_the_script_example_in_3d",
    ".venv/bin/masonry-dem study examples/studies/wall1-fragility.toml --plot out/wall1-fragility.png":
        "tests/python/test_study.py::test_example_study_reads",
    ".venv/bin/masonry-dem study examples/studies/wall1-fragility.toml --resume": "tests/python/test_study.py::test_command_line",
    ".venv/bin/masonry-dem study STUDY.toml --scheduler tcp://HOST:8786 --out out/s.parquet --csv out/s.csv":
        "tests/python/test_study.py::test_command_line",
}

#: The El Centro script, run here on 0.3 s of the record at scale 1 (test_the_el_centro_script_runs).
EL_CENTRO_SCRIPT = "python examples/elcentro_wall1.py"


def test_every_readme_command_is_tested() -> None:
    """A command added to the README must be run here or named with its test; a test named must exist."""
    here = {MASONRY_DEM + c for c in RUN_HERE}
    for command in shell_commands():
        assert command in here or command in ELSEWHERE or command == EL_CENTRO_SCRIPT, f"README command not tested: {command}"
    for command, where in ELSEWHERE.items():
        assert command in shell_commands(), f"no longer in the README: {command}"
        path, name = where.split("::")
        text = (ROOT / path).read_text(encoding="utf-8")
        assert re.search(rf"^(def {name}\(|{name}:)", text, re.M), f"{where} (for {command}) does not exist"
    assert all(MASONRY_DEM + c in shell_commands() for c in RUN_HERE)


@pytest.mark.parametrize("command", list(RUN_HERE))
def test_a_readme_command_runs(command: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                               capsys: pytest.CaptureFixture[str]) -> None:
    from masonry_dem import cli

    monkeypatch.chdir(ROOT)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    args = [str(tmp_path / a) if a.startswith("out/") else a for a in command.split()]
    if args[0] == "simulate":
        args += ["--duration", "0.3"]
    status = cli.main(args)
    printed = capsys.readouterr()
    assert status == 0, (command, printed.out, printed.err)
    words, files = RUN_HERE[command]
    for word in words:
        assert word in printed.out, (command, word, printed.out)
    for name in files:
        assert (tmp_path / "out" / name).stat().st_size > 0, (command, name)


def test_the_el_centro_script_runs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                   capsys: pytest.CaptureFixture[str]) -> None:
    """examples/elcentro_wall1.py, its ladder cut to scale 1 and each run to 0.3 s of the record: the table, and no
    collapse (its figure and animation are those of masonry-dem simulate, run above)."""
    import importlib.util

    from masonry_dem.case import Case

    monkeypatch.chdir(ROOT)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    simulate = Case.simulate
    monkeypatch.setattr(Case, "simulate", lambda self, model=None, scale=None, duration=None:
                        simulate(self, model=model, scale=scale, duration=min(duration or 0.3, 0.3)))
    spec = importlib.util.spec_from_file_location("elcentro_wall1", ROOT / "examples" / "elcentro_wall1.py")
    assert spec is not None and spec.loader is not None
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    assert script.main(["--scales", "1", "--out", str(tmp_path)]) == 0
    printed = capsys.readouterr().out
    assert "PGA [g]" in printed and "stands" in printed and "no collapse up to the largest scale tried" in printed


def test_shell_commands_are_read_without_their_comments() -> None:
    text = "```sh\nmake demo   # sets up\n\n.venv/bin/masonry-dem  validate   # a table\n```\n```python\nx = 1\n```\n"
    assert shell_commands(text) == ["make demo", ".venv/bin/masonry-dem validate"]
