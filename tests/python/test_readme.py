"""Every ```python block of README.md runs (in a fresh namespace, from the repository root), and prints what the
README says it prints.

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
