"""3D walls at the edges of what the core takes, seen from the command line: a limit analysis beyond the memory is
refused before it allocates, in one line. (The core's refusals of scales and settings, and the answers at friction 0,
are tested in Rust: tests/space_model.rs, tests/bad_input.rs, tests/space_limit.rs.)"""

from __future__ import annotations

import resource
import subprocess
import sys
from pathlib import Path

import masonry_dem as md

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
LEAF = EXAMPLES / "leaf-out-of-plane.toml"


def _address_space(limit: int):
    """A preexec_fn that limits the child's address space to `limit` bytes (as `prlimit --as` does)."""

    def apply() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))

    return apply


def test_a_3d_limit_analysis_beyond_the_memory_is_refused_in_one_line(tmp_path: Path) -> None:
    """A leaf of 500,251 boxes (below the 2,000,000 blocks of the limit) under an address space of 4 GB: its limit
    analysis needs about 20 GB, and the command line says so in one line with exit status 2, where the process
    aborted (SIGABRT) in the program's first allocation."""
    case = tmp_path / "leaf.toml"
    text = LEAF.read_text().replace("length = 2.0 ", "length = 400.0 ").replace("height = 1.05 ", "height = 87.5 ")
    case.write_text(text.split("[reference]")[0])
    proc = subprocess.run([sys.executable, "-m", "masonry_dem", "run", str(case), "--method", "limit"],
                          capture_output=True, text=True, timeout=300, preexec_fn=_address_space(4 * 1024**3))
    lines = proc.stderr.strip().splitlines()
    assert proc.returncode == 2, (proc.returncode, proc.stderr[-2000:])
    assert len(lines) == 1, proc.stderr
    assert lines[0] == ("masonry-dem: error: out of memory: a limit analysis of 500251 blocks needs about 20.0 GB, more "
                        "memory than this machine (or this process) can allocate"), lines
