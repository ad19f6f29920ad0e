"""Ctrl-C, as a user presses it: SIGINT sent to a real process (the command line, a script) while the core
runs a long analysis or builds a large model. The process must stop at once, with KeyboardInterrupt in
Python (carrying the partial results) and exit status 130 from the command line, and draw nothing after.

The deadlines here are liveness bounds on a shared machine, far above the fraction of a second the core
takes to notice the signal (BENCHMARKS.md gives the measured delays)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

#: A process must be gone this long after SIGINT [s].
DEADLINE = 10.0

# A 100-course x 100-block wall: its static analysis takes tens of seconds, so the signal comes while it runs.
BIG_WALL = """
format = 1
title = "big wall"
[geometry]
thickness = 1.0
density = 1000.0
[geometry.running_bond]
block_length = 0.4
block_height = 0.175
courses = 100
length = 40.0
[base]
kind = "fixed"
[joints]
friction = 0.65
dilatancy = 0.65
[loads]
gravity = 10.0
live = "horizontal_weight"
[analysis]
method = "static"
"""


def _interrupt_after(proc: subprocess.Popen, marker: str, delay: float) -> float:
    """Wait for ``marker`` on the process's stdout, then ``delay`` s, send SIGINT; return the seconds the
    process took to exit after it."""
    assert proc.stdout is not None
    for line in proc.stdout:
        if marker in line:
            break
    else:
        pytest.fail(f"the process ended before {marker!r}: {proc.wait()}")
    time.sleep(delay)
    sent = time.monotonic()
    proc.send_signal(signal.SIGINT)
    try:
        proc.wait(timeout=DEADLINE)
    except subprocess.TimeoutExpired:
        proc.kill()
        pytest.fail(f"still running {DEADLINE} s after Ctrl-C")
    return time.monotonic() - sent


def test_the_api_raises_keyboard_interrupt_with_the_partial_results() -> None:
    script = """
import masonry_dem as md
model = md.Model(md.running_bond(0.4, 0.175, 100, 40.0), gravity=10.0,
                 joints={"default": {"friction": 0.65, "dilatancy": 0.65}})
print("solving", flush=True)
try:
    model.solve_static()
except KeyboardInterrupt as exc:
    r = exc.results
    print("KeyboardInterrupt", r.status, r.error, r.steps == len(r.curve_multiplier), flush=True)
    raise
print("not interrupted", flush=True)
"""
    proc = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    _interrupt_after(proc, "solving", 2.0)
    out, err = proc.communicate()
    assert "KeyboardInterrupt interrupted interrupted by the user True" in out, (out, err)
    assert "Traceback" in err and err.rstrip().endswith("KeyboardInterrupt"), err  # the script's loop stops


def test_building_a_large_model_stops_on_ctrl_c() -> None:
    # a million blocks: seconds of interface search
    script = """
import masonry_dem as md
blocks = md.running_bond(0.4, 0.175, 632, 632 * 1.0)
print("building", len(blocks), flush=True)
try:
    md.Model(blocks)
except KeyboardInterrupt:
    print("KeyboardInterrupt", flush=True)
    raise
print("built", flush=True)
"""
    proc = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    _interrupt_after(proc, "building", 0.3)
    out, err = proc.communicate()
    assert "KeyboardInterrupt" in out and "built" not in out, (out, err)


def test_the_command_line_exits_130_and_draws_nothing_after(tmp_path: Path) -> None:
    case = tmp_path / "big.toml"
    case.write_text(BIG_WALL)
    png, out = tmp_path / "big.png", tmp_path / "big.json"
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    # the case file is read and the model built before the solver's progress appears; --quiet has no bar,
    # so wait for the model by time: a 10,000-block model is built in a fraction of a second
    script = (
        "import sys, masonry_dem.cli as cli; print('started', flush=True); sys.exit(cli.main(sys.argv[1:]))"
    )
    proc = subprocess.Popen(
        [sys.executable, "-c", script, "run", str(case), "--quiet", "--plot", str(png), "--json", str(out)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
    )
    _interrupt_after(proc, "started", 3.0)
    stdout, stderr = proc.communicate()
    assert proc.returncode == 130, (stdout, stderr)
    assert stderr.strip().splitlines()[-1] == "masonry-dem: error: interrupted (no plot drawn)", stderr
    assert not png.exists()
    assert '"status": "interrupted"' in out.read_text()
