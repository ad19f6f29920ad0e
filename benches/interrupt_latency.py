"""Ctrl-C latency: the seconds from SIGINT to the end of a Python process running an analysis (or building a
model), median and largest of a few runs each. The signal is sent a fixed delay after the process says it
has started the call, so that it comes while the core works.

    make develop && .venv/bin/python benches/interrupt_latency.py
"""

from __future__ import annotations

import signal
import statistics
import subprocess
import sys
import time

SOLVE = """
import masonry_dem as md
m = md.Model(md.running_bond(0.4, 0.175, {courses}, {length}), gravity=10.0,
             joints={{"default": {{"friction": 0.65, "dilatancy": 0.65}}}})
print("go", flush=True)
m.{call}
"""

BUILD = """
import masonry_dem as md
b = md.running_bond(0.4, 0.175, 870, 870.0)
print("go", flush=True)
md.Model(b)
"""


def latency(script: str, delay: float, runs: int) -> tuple[float, float]:
    seconds = []
    for _ in range(runs):
        proc = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        assert proc.stdout is not None
        for line in proc.stdout:
            if "go" in line:
                break
        time.sleep(delay)
        sent = time.monotonic()
        proc.send_signal(signal.SIGINT)
        proc.wait()
        seconds.append(time.monotonic() - sent)
    return statistics.median(seconds), max(seconds)


def main() -> None:
    cases = [
        ("static, 10^4 blocks", SOLVE.format(courses=100, length=40.0, call="solve_static()"), 2.0, 5),
        ("limit, 10^4 blocks", SOLVE.format(courses=100, length=40.0, call="solve_limit()"), 1.0, 5),
        ("explicit, 10^4 blocks", SOLVE.format(courses=100, length=40.0, call="solve_dynamic()"), 2.0, 5),
        ("static, 2.5 x 10^5 blocks", SOLVE.format(courses=500, length=200.0, call="solve_static()"), 3.0, 3),
        ("model building, 1.9 x 10^6 blocks", BUILD, 0.5, 3),
    ]
    print("| run | median [s] | largest [s] |\n|---|---|---|")
    for name, script, delay, runs in cases:
        med, worst = latency(script, delay, runs)
        print(f"| {name} | {med:.2f} | {worst:.2f} |", flush=True)


if __name__ == "__main__":
    main()
