"""The ``masonry-dem`` command line, run as a subprocess (and in-process for the failed-solver path)."""

from __future__ import annotations

import io
import json
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace
from typing import Callable, List, Optional

import pytest

import masonry_dem as md
from masonry_dem import cli
from masonry_dem import progress as progress_module
from masonry_dem.case import Case

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
Progress = Callable[[int, float, float, float], None]
PNG = b"\x89PNG\r\n\x1a\n"


def masonry_dem(*args: str, cwd: Path, module: str = "masonry_dem") -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", module, *args], cwd=cwd, capture_output=True, text=True, timeout=600)


def assert_one_line_error(proc: subprocess.CompletedProcess, status: int) -> str:
    assert proc.returncode == status, (proc.stdout, proc.stderr)
    assert "Traceback" not in proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith("masonry-dem: error: "), lines[0]
    return lines[0]


def test_help(tmp_path: Path) -> None:
    proc = masonry_dem("--help", cwd=tmp_path)
    assert proc.returncode == 0
    assert "run" in proc.stdout and "demo" in proc.stdout and "examples:" in proc.stdout
    assert "compare" in proc.stdout
    proc = masonry_dem("run", "--help", cwd=tmp_path)
    assert proc.returncode == 0
    assert "--method" in proc.stdout and "--json" in proc.stdout and "--plot" in proc.stdout
    assert "examples:" in proc.stdout
    proc = masonry_dem("--version", cwd=tmp_path)
    assert proc.returncode == 0 and md.__version__ in proc.stdout


def test_run(tmp_path: Path) -> None:
    out = tmp_path / "results" / "r.json"
    png = tmp_path / "results" / "r.png"
    proc = masonry_dem(
        "run", str(EXAMPLES / "single-block-rocking.toml"), "--json", str(out), "--plot", str(png), cwd=tmp_path
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    text = proc.stdout
    assert text.startswith("Single block rocking (0.2 x 0.6 m)\n")
    for label in (
        "blocks:",
        "interfaces:",
        "status:",
        "collapse multiplier:",
        "joint states:",
        "mechanism:",
        "elapsed:",
    ):
        assert label in text
    data = json.loads(out.read_text())
    assert data["title"] == "Single block rocking (0.2 x 0.6 m)"
    # the multiplier is printed with 4 decimals
    assert f"collapse multiplier: {data['collapse_multiplier']:.4f}" in text
    assert png.read_bytes().startswith(PNG)


def test_run_through_cli_module(tmp_path: Path) -> None:
    proc = masonry_dem("run", str(EXAMPLES / "single-block-sliding.toml"), cwd=tmp_path, module="masonry_dem.cli")
    assert proc.returncode == 0, proc.stderr
    assert "collapse multiplier:" in proc.stdout


def test_demo_default_plot(tmp_path: Path) -> None:
    proc = masonry_dem("demo", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.startswith("Ferris & Tin-Loi wall 1\n")
    assert "blocks:              33" in proc.stdout
    assert (tmp_path / "out" / "demo.png").read_bytes().startswith(PNG)


def test_demo_outputs(tmp_path: Path) -> None:
    proc = masonry_dem("demo", "--plot", "a/b/w.png", "--json", "a/w.json", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "a" / "b" / "w.png").read_bytes().startswith(PNG)
    data = json.loads((tmp_path / "a" / "w.json").read_text())
    assert data["blocks"] == 33 and data["title"] == "Ferris & Tin-Loi wall 1"
    assert not (tmp_path / "out").exists()


def test_missing_file(tmp_path: Path) -> None:
    proc = masonry_dem("run", "no-such-case.toml", cwd=tmp_path)
    line = assert_one_line_error(proc, 2)
    assert "no-such-case.toml" in line and "No such file" in line


def test_directory_as_case(tmp_path: Path) -> None:
    (tmp_path / "d.toml").mkdir()
    assert_one_line_error(masonry_dem("run", "d.toml", cwd=tmp_path), 2)


def test_bad_case_is_one_line(tmp_path: Path) -> None:
    text = (EXAMPLES / "single-block-sliding.toml").read_text().replace("friction = 0.65", "frictoin = 0.65")
    (tmp_path / "bad.toml").write_text(text)
    line = assert_one_line_error(masonry_dem("run", "bad.toml", cwd=tmp_path), 2)
    assert line.startswith("masonry-dem: error: bad.toml: unknown key 'frictoin' in [joints]")


def test_invalid_toml_is_one_line(tmp_path: Path) -> None:
    (tmp_path / "bad.toml").write_text("format = 1\n[geometry\n")
    line = assert_one_line_error(masonry_dem("run", "bad.toml", cwd=tmp_path), 2)
    assert "bad.toml: invalid TOML" in line


def test_core_input_error_is_exit_2(tmp_path: Path) -> None:
    # valid keys, but two overlapping blocks: the core refuses the model
    text = "format = 1\n[geometry]\nblocks = [[0, 0, 1, 1], [0.5, 0, 1.5, 1]]\n"
    (tmp_path / "overlap.toml").write_text(text)
    proc = masonry_dem("run", "overlap.toml", cwd=tmp_path)
    line = assert_one_line_error(proc, 2)
    assert line.startswith("masonry-dem: error: overlap.toml: ")


def test_run_dynamic(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """--method dynamic: the explicit solver on the single sliding block, collapse at mu = 0.65."""
    out = tmp_path / "d.json"
    status = cli.main(["run", str(EXAMPLES / "single-block-sliding.toml"), "--method", "dynamic", "--json", str(out)])
    captured = capsys.readouterr()
    assert status == 0, captured.err
    assert captured.err == ""  # stderr is not a terminal here: no progress bar
    assert "method:              dynamic" in captured.out
    data = json.loads(out.read_text())
    assert data["method"] == "dynamic" and data["status"] == "collapse"
    assert abs(data["collapse_multiplier"] - 0.65) <= 0.02 * 0.65


def test_compare(tmp_path: Path) -> None:
    """compare on the single rocking block: both incremental methods at 1/3 within 2%, agreement printed and
    written (the limit analysis, the third column, is checked in test_limit_api.py)."""
    out, png = tmp_path / "c" / "cmp.json", tmp_path / "c" / "cmp.png"
    proc = masonry_dem(
        "compare", str(EXAMPLES / "single-block-rocking.toml"), "--json", str(out), "--plot", str(png), cwd=tmp_path
    )
    data = json.loads(out.read_text())
    limit_ok = data["limit"]["status"] in ("collapse", "estimate")  # dilatancy 0 here: an estimate
    assert proc.returncode == (0 if limit_ok else 1), proc.stderr
    assert proc.stderr == "" or not limit_ok
    text = proc.stdout
    assert text.startswith(
        "Single block rocking (0.2 x 0.6 m): static and explicit (dynamic) solvers and limit analysis\n"
    )
    for label in (
        "status:",
        "collapse multiplier:",
        "difference",
        "failed joints:",
        "in common, Jaccard index",
        "iterations",
        "time steps",
        "elapsed:",
        "dynamic / static =",
    ):
        assert label in text, label
    assert list(data) == ["format", "title", "static", "dynamic", "limit", "agreement"]
    assert data["format"] == 1 and data["title"] == "Single block rocking (0.2 x 0.6 m)"
    assert data["static"]["method"] == "static" and data["dynamic"]["method"] == "dynamic"
    for method in ("static", "dynamic"):
        assert data[method]["status"] == "collapse"
        assert abs(data[method]["collapse_multiplier"] - 1 / 3) <= 0.02 / 3
    agree = data["agreement"]
    lam_s, lam_d = data["static"]["collapse_multiplier"], data["dynamic"]["collapse_multiplier"]
    assert agree["multiplier_relative_difference"] == pytest.approx((lam_d - lam_s) / lam_s)
    assert abs(agree["multiplier_relative_difference"]) < 0.02
    assert 0.0 <= agree["jaccard"] <= 1.0
    assert agree["failed_common"] <= min(agree["failed_static"], agree["failed_dynamic"])
    assert agree["failed_static"] == len(agree["failed_interfaces_static"])
    assert agree["time_steps_dynamic"] > 0 and agree["iterations_static"] > 0
    assert f"{lam_s:.4f}" in text and f"{lam_d:.4f}" in text
    assert png.read_bytes().startswith(PNG)


def test_compare_bad_input(tmp_path: Path) -> None:
    proc = masonry_dem("compare", "no-such-case.toml", cwd=tmp_path)
    assert_one_line_error(proc, 2)
    text = (EXAMPLES / "single-block-sliding.toml").read_text() + "damping = 'cundall'\n"
    (tmp_path / "bad.toml").write_text(text)
    line = assert_one_line_error(masonry_dem("compare", "bad.toml", cwd=tmp_path), 2)
    assert "analysis.damping: expected one of" in line


class FakeTerminal(io.StringIO):
    """A stderr that says it is a terminal."""

    def isatty(self) -> bool:
        return True


@pytest.mark.parametrize("quiet", [False, True])
def test_progress_bar_on_a_terminal(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str], quiet: bool
) -> None:
    """A bar on stderr when it is a terminal (fed by the solver's progress callback), none with --quiet."""
    import tqdm  # noqa: F401  (a declared dependency: its absence is a failure, not a skip)
    calls: List[tuple] = []
    real_solve = Case.solve

    def spying_solve(
        self: Case, model: md.Model, method: Optional[str] = None, progress: Optional[Progress] = None
    ) -> object:
        calls.append((method, progress))
        return real_solve(self, model, method, progress)

    monkeypatch.setattr(Case, "solve", spying_solve)
    monkeypatch.setattr(progress_module, "DEFAULT_INTERVAL", 0.0)  # draw at every call
    term = FakeTerminal()
    monkeypatch.setattr(sys, "stderr", term)
    args = ["run", str(EXAMPLES / "single-block-sliding.toml")] + (["--quiet"] if quiet else [])
    status = cli.main(args)
    assert status == 0
    assert "collapse multiplier:" in capsys.readouterr().out
    assert len(calls) == 1
    if quiet:
        assert calls[0][1] is None
        assert term.getvalue() == ""
    else:
        assert isinstance(calls[0][1], progress_module.ProgressBar)
        assert calls[0][1].calls >= 1
        assert "static: λ = " in term.getvalue() and "steps" in term.getvalue()


def test_quiet_flag_everywhere(tmp_path: Path) -> None:
    for command in ("run", "compare", "demo"):
        proc = masonry_dem(command, "--help", cwd=tmp_path)
        assert proc.returncode == 0 and "--quiet" in proc.stdout, command


def test_bad_arguments(tmp_path: Path) -> None:
    proc = masonry_dem("run", "x.toml", "--method", "fem", cwd=tmp_path)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr
    proc = masonry_dem(cwd=tmp_path)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr


def test_unwritable_output(tmp_path: Path) -> None:
    (tmp_path / "file").write_text("")
    proc = masonry_dem("run", str(EXAMPLES / "single-block-sliding.toml"), "--json", "file/r.json", cwd=tmp_path)
    line = assert_one_line_error(proc, 1)
    assert "cannot write" in line


def test_failed_status(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    """A solver failure prints the reason, writes the JSON and the plot, and exits with 1."""
    real_solve = Case.solve

    def failing_solve(
        self: Case, model: md.Model, method: Optional[str] = None, progress: Optional[Progress] = None
    ) -> SimpleNamespace:
        r = real_solve(self, model, method, progress)
        names: List[str] = [n for n in dir(r) if not n.startswith("_") and not callable(getattr(r, n))]
        fake = SimpleNamespace(**{n: getattr(r, n) for n in names})
        fake.status, fake.error = "failed", "no convergence at step 3"
        return fake

    monkeypatch.setattr(Case, "solve", failing_solve)
    out, png = tmp_path / "f.json", tmp_path / "f.png"
    status = cli.main(["run", str(EXAMPLES / "single-block-sliding.toml"), "--json", str(out), "--plot", str(png)])
    captured = capsys.readouterr()
    assert status == 1
    assert captured.err.strip() == "masonry-dem: error: the analysis failed: no convergence at step 3"
    assert "status:              failed (no convergence at step 3)" in captured.out
    data = json.loads(out.read_text())
    assert data["status"] == "failed" and data["error"] == "no convergence at step 3"
    assert png.read_bytes().startswith(PNG)


def interrupted_solve(real_solve, log: List[str]):  # type: ignore[no-untyped-def]
    """A Case.solve whose static run is stopped by Ctrl-C, as the core does it: KeyboardInterrupt with the
    partial Results as its ``results`` attribute."""

    def solve(self: Case, model: md.Model, method: Optional[str] = None, progress: Optional[Progress] = None) -> object:
        log.append(str(method))
        r = real_solve(self, model, method, progress)
        if method != "static":
            return r
        names = [n for n in dir(r) if not n.startswith("_") and not callable(getattr(r, n))]
        fake = SimpleNamespace(**{n: getattr(r, n) for n in names})
        fake.status, fake.error = "interrupted", "interrupted by the user"
        exc = KeyboardInterrupt()
        exc.results = fake  # type: ignore[attr-defined]
        raise exc

    return solve


def test_interrupted(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    """Ctrl-C: run writes the result file of what was computed, draws no plot, and exits with 130; compare
    does not start the second method."""
    log: List[str] = []
    monkeypatch.setattr(Case, "solve", interrupted_solve(Case.solve, log))
    out, png = tmp_path / "r.json", tmp_path / "r.png"
    case = str(EXAMPLES / "single-block-sliding.toml")
    assert cli.main(["run", case, "--method", "static", "--json", str(out), "--plot", str(png)]) == 130
    captured = capsys.readouterr()
    assert captured.err.strip() == "masonry-dem: error: interrupted (no plot drawn)"
    assert "interrupted by the user" in captured.out
    assert json.loads(out.read_text())["status"] == "interrupted"
    assert not png.exists()
    log.clear()
    assert cli.main(["compare", case]) == 130
    assert log == ["static"]
    assert capsys.readouterr().err.strip() == "masonry-dem: error: interrupted"
