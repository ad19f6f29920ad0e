"""Every ```python block of README.md runs (in a fresh namespace, from the repository root)."""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import List

import pytest

ROOT = Path(__file__).resolve().parents[2]
README = ROOT / "README.md"
FENCE = re.compile(r"^```python[ \t]*\n(.*?)^```[ \t]*$", re.S | re.M)


def python_blocks() -> List[str]:
    return FENCE.findall(README.read_text(encoding="utf-8"))


def test_readme_has_python_blocks() -> None:
    assert python_blocks(), "README.md has no ```python block"


@pytest.mark.parametrize("index", range(len(python_blocks())))
def test_readme_block_runs(index: int, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(ROOT)
    monkeypatch.setenv("MPLBACKEND", "Agg")  # a block that plots must not open a window
    code = python_blocks()[index]
    namespace = {"__name__": f"readme_block_{index}"}
    exec(compile(code, f"README.md (python block {index + 1})", "exec"), namespace)
