"""Limit analysis from Python and the command line: ``Model.solve_limit``, its certificate, the case files'
``method = "limit"``, ``masonry-dem run --method limit``, ``compare`` and ``validate`` with the limit column,
the result file (certificate, null multiplier), plots and exports of a result that has no curve.

The values: Ferris & Tin-Loi wall 1 with associative joints (psi = phi) has the exact limit multiplier
0.642857... (published 0.6429, docs/references.md, section 2); the single blocks and the stack have
closed forms (section 1). Everything else here is about the plumbing and holds whatever the multiplier.
"""

from __future__ import annotations

import json
import math
import os
import signal
import subprocess
import sys
import threading
from pathlib import Path
from types import SimpleNamespace
from typing import Any, List, Optional

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem import cli, validate
from masonry_dem.case import CERTIFICATE_KEYS, Case, result_dict, write_result_json
from masonry_dem.compare import comparison_dict, comparison_text
from masonry_dem.progress import progress_text
from masonry_dem.report import summary

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
WALL1 = EXAMPLES / "ferris-tinloi-wall1.toml"
PNG = b"\x89PNG\r\n\x1a\n"


def masonry_dem(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "masonry_dem", *args], cwd=cwd, capture_output=True, text=True, timeout=600
    )


def check_certificate(cert: Any) -> None:
    """The certificate's keys and types (a dict from the core or from the result file)."""
    assert isinstance(cert, dict) and list(cert) == list(CERTIFICATE_KEYS), cert
    for key in ("primal_residual", "dual_residual", "duality_gap"):
        assert cert[key] is None or isinstance(cert[key], float), key
    assert cert["upper_bound"] is None or isinstance(cert["upper_bound"], float)
    assert type(cert["iterations"]) is int and cert["iterations"] >= 0
    assert type(cert["sequence"]) is int and cert["sequence"] >= 0
    assert type(cert["sequence_converged"]) is bool and type(cert["peak_strengths"]) is bool


# --------------------------------------------------------------------------------------------------
# The values
# --------------------------------------------------------------------------------------------------


def test_wall1_associative_is_the_published_limit_value() -> None:
    """Ferris & Tin-Loi wall 1 with psi = mu = 0.65: 0.6429 (exact 0.642857...) within 1e-4."""
    case = md.load_case(WALL1)
    law = case.model_kwargs["joints"]["default"]
    assert law["dilatancy"] == law["friction"] == 0.65  # associative: the program's optimum is exact
    model = case.build_model()
    res = model.solve_limit(tolerance=1e-9)
    assert res.method == "limit"
    assert res.status == "collapse", res.error
    assert res.error is None
    assert abs(res.collapse_multiplier - 0.6429) <= 1e-4, res.collapse_multiplier
    cert = res.certificate
    check_certificate(cert)
    assert cert["upper_bound"] is None and cert["sequence"] == 0  # associative: no sequence
    assert cert["peak_strengths"] is False  # dry joints
    assert max(cert["primal_residual"], cert["dual_residual"], cert["duality_gap"]) <= 1e-9
    assert cert["iterations"] == res.iterations >= 1
    # the mechanism: block velocities, largest translation 1; the crack pattern has failed joints
    mech = np.asarray(res.mechanism)
    assert mech.shape == (model.n_blocks + 1, 3)
    assert np.max(np.hypot(mech[:, 0], mech[:, 1])) == pytest.approx(1.0)
    assert np.any(np.asarray(res.interface_states) != 0)


@pytest.mark.parametrize(
    "name, exact",
    [("single-block-sliding", 0.65), ("single-block-rocking", 1 / 3), ("stack-3-blocks", 0.2)],
)
def test_closed_forms(name: str, exact: float) -> None:
    # these cases have dilatancy 0: limit analysis gives an estimate (never a collapse), here the closed form
    res = md.load_case(EXAMPLES / f"{name}.toml").run(method="limit")
    assert res.status == "estimate", res.error
    assert math.isnan(res.collapse_multiplier)
    assert abs(res.last_equilibrium - exact) <= 1e-4, res.last_equilibrium
    assert res.certificate["multiplier"] == res.last_equilibrium
    assert "estimate" in res.error and "neither" in res.error
    # the same joints made associative: the exact multiplier, a collapse
    case = md.load_case(EXAMPLES / f"{name}.toml")
    kwargs = dict(case.model_kwargs)
    kwargs["joints"] = {f: dict(law, dilatancy=law["friction"]) if "friction" in law else dict(law)
                        for f, law in kwargs["joints"].items()}
    assoc = md.Model(**kwargs).solve_limit()
    assert assoc.status == "collapse", assoc.error
    assert abs(assoc.collapse_multiplier - exact) <= 1e-4, assoc.collapse_multiplier


# --------------------------------------------------------------------------------------------------
# The binding
# --------------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def wall1() -> tuple:
    model = md.load_case(WALL1).build_model()
    return model, model.solve_limit()


def test_limit_results_shape(wall1: tuple) -> None:
    """No load path: empty curve, zero displacements, no steps; a certificate whatever the status; the
    multiplier is NaN unless the status is collapse."""
    model, res = wall1
    n_all, m = len(model.rects), model.n_interfaces
    assert res.method == "limit" and res.steps == 0
    assert res.status in ("collapse", "failed", "no_equilibrium", "unbounded")
    assert len(res.curve_multiplier) == 0 and len(res.curve_displacement) == 0
    assert np.asarray(res.displacements).shape == (n_all, 3) and not np.any(res.displacements)
    assert np.asarray(res.mechanism).shape == (n_all, 3)
    assert np.asarray(res.interface_forces).shape == (m, 3)
    assert len(res.interface_states) == m and len(res.broken) == m
    assert math.isfinite(res.collapse_multiplier) == (res.status == "collapse")
    assert (res.error is None) == (res.status == "collapse")
    check_certificate(res.certificate)
    assert "limit" in repr(res)


def test_other_methods_have_no_certificate() -> None:
    model = md.Model([[0.0, 0.0, 0.4, 0.175]], gravity=10.0)
    assert model.solve_static().certificate is None
    assert md.to_dict(model.solve_static())["certificate"] is None


@pytest.mark.parametrize(
    "kwargs, word",
    [
        ({"tolerance": 0.0}, "tolerance"),
        ({"tolerance": 0.5}, "tolerance"),
        ({"tolerance": float("nan")}, "tolerance"),
        ({"max_iterations": 0}, "max_iterations"),
        ({"max_iterations": 10**9}, "max_iterations"),
        ({"max_sequence": -1}, "max_sequence"),
    ],
)
def test_bad_options(kwargs: dict, word: str) -> None:
    model = md.Model([[0.0, 0.0, 0.4, 0.175]], gravity=10.0)
    with pytest.raises(md.InputError, match=word):
        model.solve_limit(**kwargs)


def test_progress_callback() -> None:
    model = md.load_case(WALL1).build_model()
    calls: List[tuple] = []
    res = model.solve_limit(progress=lambda *a: calls.append(a))
    assert len(calls) >= 1
    steps = [c[0] for c in calls]
    assert steps == list(range(1, len(calls) + 1))  # the iterations, counted over the programs
    assert all(len(c) == 4 and math.isnan(c[2]) and math.isnan(c[3]) for c in calls)
    if res.status == "collapse":
        assert calls[-1][1] == pytest.approx(res.collapse_multiplier, rel=1e-6)


def test_an_exception_in_the_callback_is_raised_again() -> None:
    model = md.load_case(WALL1).build_model()

    class Stop(Exception):
        pass

    def stop(*args: Any) -> None:
        raise Stop("from the callback")

    with pytest.raises(Stop, match="from the callback"):
        model.solve_limit(progress=stop)
    with pytest.raises(TypeError):
        model.solve_limit(progress=lambda step: None)  # the callback receives 4 arguments


def test_ctrl_c_raises_keyboard_interrupt_with_the_partial_results() -> None:
    """SIGINT while the core runs (GIL released): the run stops at the next iteration and Ctrl-C is raised
    as KeyboardInterrupt, whose ``results`` is a Results with status "interrupted", error "interrupted by the
    user", no multiplier and no certificate."""
    # 6,400 blocks: seconds of interior-point iterations, so the signal comes while they run
    model = md.Model(md.running_bond(0.4, 0.175, 80, 32.0), gravity=10.0,
                     joints={"default": {"friction": 0.65, "dilatancy": 0.65}})
    res = None
    for _ in range(3):
        timer = threading.Timer(0.2, lambda: os.kill(os.getpid(), signal.SIGINT))
        timer.start()
        try:
            model.solve_limit()
        except KeyboardInterrupt as exc:
            res = getattr(exc, "results", None)
            if res is not None:  # raised by the core, with what it had
                break
        finally:
            timer.join()
    else:
        pytest.fail("Ctrl-C did not stop the limit analysis with its results")
    assert res.status == "interrupted" and res.error == "interrupted by the user"
    assert res.method == "limit" and math.isnan(res.collapse_multiplier) and res.certificate is None
    assert len(res.interface_states) == model.n_interfaces and len(res.mechanism) == len(model.rects)


# --------------------------------------------------------------------------------------------------
# Case files
# --------------------------------------------------------------------------------------------------

CASE = """
format = 1
[geometry]
blocks = [[0.0, 0.0, 0.4, 0.175]]
[joints]
friction = 0.65
"""


def test_case_method_limit() -> None:
    """method = "limit" alone is enough; the other [analysis] keys are still checked, then ignored."""
    case = md.parse_case(CASE + '[analysis]\nmethod = "limit"\n')
    assert case.method == "limit" and case.solver_kwargs() == {}
    res = case.run()
    assert res.method == "limit"
    text = CASE + (
        '[analysis]\nmethod = "limit"\ncontrol = "displacement"\nsteps = 3\nmax_displacement = 0.01\n'
        'tolerance = 0.5\ndamping = "none"\nthreads = 1\n'
    )
    case = md.parse_case(text)
    assert case.solver_kwargs() == {} and case.solver_kwargs("static")["tolerance"] == 0.5
    assert case.run().method == "limit"  # tolerance = 0.5 would be refused by solve_limit: not passed
    with pytest.raises(md.InputError, match="damping"):
        md.parse_case(CASE + '[analysis]\nmethod = "limit"\ndamping = "cundall"\n')
    # the method argument overrides the file's, both ways
    assert md.parse_case(CASE).run(method="limit").method == "limit"
    assert case.run(method="static").method == "static"


# --------------------------------------------------------------------------------------------------
# The result file
# --------------------------------------------------------------------------------------------------


def fake_limit(model: Any, **overrides: Any) -> SimpleNamespace:
    """An object with the attributes of a limit analysis's Results."""
    n_all, m = len(model.rects), model.n_interfaces
    values = dict(
        method="limit", status="no_equilibrium",
        error="no equilibrium under the dead loads: no admissible interface forces balance them",
        collapse_multiplier=float("nan"), curve_multiplier=np.zeros(0), curve_displacement=np.zeros(0),
        control_block=0, displacements=np.zeros((n_all, 3)), mechanism=np.zeros((n_all, 3)),
        interface_forces=np.zeros((m, 3)), interface_states=np.zeros(m, dtype=np.int64),
        broken=np.zeros(m, dtype=bool), joint_states={"elastic": m}, iterations=12, steps=0, elapsed_s=0.01,
        certificate={"primal_residual": 1e-3, "dual_residual": 1e-12, "duality_gap": float("nan"), "iterations": 12,
                     "upper_bound": None, "sequence": 0, "sequence_converged": False, "peak_strengths": False},
    )
    values.update(overrides)
    return SimpleNamespace(**values)


@pytest.mark.parametrize("status", ["no_equilibrium", "unbounded", "failed"])
def test_json_of_a_result_without_collapse(tmp_path: Path, status: str) -> None:
    model = md.load_case(WALL1).build_model()
    data = write_result_json(tmp_path / "r.json", fake_limit(model, status=status), model, "t")
    back = json.loads((tmp_path / "r.json").read_text())
    assert back == data
    assert back["collapse_multiplier"] is None
    assert back["status"] == status and back["error"].startswith("no equilibrium")
    check_certificate(back["certificate"])
    assert back["certificate"]["duality_gap"] is None  # NaN is null
    assert back["curve"] == {"multiplier": [], "displacement": []}


def test_json_of_a_real_failed_limit_analysis(tmp_path: Path) -> None:
    """One interior-point iteration cannot converge: status failed, null multiplier, the certificate kept."""
    model = md.load_case(WALL1).build_model()
    res = model.solve_limit(max_iterations=1)
    assert res.status == "failed" and "did not converge" in res.error
    data = write_result_json(tmp_path / "f.json", res, model, "wall 1")
    back = json.loads((tmp_path / "f.json").read_text())
    assert back == data and back["collapse_multiplier"] is None and back["error"] == res.error
    check_certificate(back["certificate"])
    assert back["certificate"]["iterations"] == res.certificate["iterations"]
    # to_dict holds the same certificate
    assert md.to_dict(res, model)["certificate"] == back["certificate"]


def test_json_of_an_interrupted_limit_analysis_has_a_null_certificate() -> None:
    model = md.load_case(WALL1).build_model()
    data = result_dict(fake_limit(model, status="failed", error="interrupted by the user", certificate=None), model, "t")
    assert data["certificate"] is None and data["collapse_multiplier"] is None
    assert data["error"] == "interrupted by the user"


def test_static_result_file_unchanged() -> None:
    """The other methods' result files keep their keys: no certificate; an error only when failed."""
    model = md.Model([[0.0, 0.0, 0.4, 0.175]], gravity=10.0)
    data = result_dict(model.solve_static(), model, "t")
    assert "certificate" not in data and "error" not in data


# --------------------------------------------------------------------------------------------------
# Reports
# --------------------------------------------------------------------------------------------------


def test_summary_shows_the_status_and_the_certificate() -> None:
    model = md.load_case(WALL1).build_model()
    text = summary("t", model, fake_limit(model))
    assert "method:              limit" in text
    assert "status:              no_equilibrium (no equilibrium under the dead loads" in text
    assert "collapse multiplier: none" in text
    assert "certificate:         primal residual 1.0e-03, dual residual 1.0e-12, duality gap -" in text
    assert "mechanism:           none (no collapse)" in text
    cert = dict(fake_limit(model).certificate, upper_bound=0.65, sequence=4, sequence_converged=True,
                peak_strengths=True)
    text = summary("t", model, fake_limit(model, certificate=cert))
    assert "associative upper bound 0.6500" in text and "4 programs" in text and "converged" in text
    assert "at their peak" in text
    assert progress_text(7, 0.5, float("nan"), float("nan"), unit="iterations") == "λ = 0.5000, 7 iterations"


def test_cli_no_equilibrium_exits_1(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                    capsys: pytest.CaptureFixture[str]) -> None:
    """A limit analysis without a multiplier: printed clearly, the JSON still written, exit status 1."""

    def solve(self: Case, model: md.Model, method: Optional[str] = None, progress: Any = None) -> Any:
        return fake_limit(model)

    monkeypatch.setattr(Case, "solve", solve)
    out, png = tmp_path / "n.json", tmp_path / "n.png"
    status = cli.main(["run", str(WALL1), "--method", "limit", "--json", str(out), "--plot", str(png)])
    captured = capsys.readouterr()
    assert status == 1
    assert captured.err.strip().startswith("masonry-dem: error: no collapse multiplier (no_equilibrium): no equilibrium")
    assert "status:              no_equilibrium (" in captured.out
    data = json.loads(out.read_text())
    assert data["status"] == "no_equilibrium" and data["collapse_multiplier"] is None
    assert png.read_bytes().startswith(PNG)


# --------------------------------------------------------------------------------------------------
# The command line
# --------------------------------------------------------------------------------------------------


def test_cli_run_method_limit(tmp_path: Path) -> None:
    """run --method limit: the summary, the result file with its certificate, the plot, VTK and CSV."""
    out, png, csv = tmp_path / "o" / "w1.json", tmp_path / "o" / "w1.png", tmp_path / "o" / "w1.csv"
    proc = masonry_dem("run", str(WALL1), "--method", "limit", "--json", str(out), "--plot", str(png),
                       "--vtk", str(tmp_path / "o" / "w1"), "--csv", str(csv), cwd=tmp_path)
    data = json.loads(out.read_text())
    assert proc.returncode == (0 if data["status"] == "collapse" else 1), (proc.stdout, proc.stderr)
    assert "Traceback" not in proc.stderr
    assert "method:              limit" in proc.stdout and "certificate:" in proc.stdout
    assert data["method"] == "limit" and data["curve"] == {"multiplier": [], "displacement": []}
    assert list(data)[-2 if "error" in data else -1] == "certificate"
    check_certificate(data["certificate"])
    assert (data["collapse_multiplier"] is None) == (data["status"] != "collapse")
    if data["status"] == "collapse":
        assert abs(data["collapse_multiplier"] - 0.6429) <= 1e-4
        assert "error" not in data
    assert png.read_bytes().startswith(PNG)
    assert csv.read_text() == "multiplier,displacement_m\n"  # no curve: the header only
    import meshio

    blocks = meshio.read(tmp_path / "o" / "w1-blocks.vtu")
    assert blocks.cell_data["mechanism"][0].shape == (34, 3)
    faces = meshio.read(tmp_path / "o" / "w1-interfaces.vtu")
    assert len(faces.cell_data["state"][0]) == 83


def test_cli_compare_includes_limit(tmp_path: Path) -> None:
    out, png = tmp_path / "c.json", tmp_path / "c.png"
    proc = masonry_dem("compare", str(EXAMPLES / "single-block-rocking.toml"), "--json", str(out), "--plot", str(png),
                       cwd=tmp_path)
    data = json.loads(out.read_text())
    assert list(data) == ["format", "title", "static", "dynamic", "limit", "agreement"]
    # dilatancy 0: the limit analysis is an estimate, shown as one (not a failure of the command)
    assert data["limit"]["status"] == "estimate" and "note" in data["limit"], data["limit"]
    assert data["limit"]["collapse_multiplier"] is None and data["limit"]["last_equilibrium"] > 0
    assert proc.returncode == 0, (proc.stdout, proc.stderr)
    assert "(estimate)" in proc.stdout and "limit: estimate:" in proc.stdout
    assert "Traceback" not in proc.stderr
    lines = proc.stdout.splitlines()
    assert lines[0].endswith(": static and explicit (dynamic) solvers and limit analysis")
    assert lines[2].split() == ["static", "dynamic", "limit"]
    assert "difference from static:" in proc.stdout and "limit certificate:" in proc.stdout
    assert data["limit"]["method"] == "limit"
    check_certificate(data["limit"]["certificate"])
    agree = data["agreement"]
    for key in ("multiplier_relative_difference_limit", "failed_limit", "failed_common_limit", "jaccard_limit",
                "failed_interfaces_limit", "iterations_limit", "elapsed_ratio_limit"):
        assert key in agree, key
    assert agree["iterations_limit"] == data["limit"]["certificate"]["iterations"]
    lam_s, lam_l = data["static"]["collapse_multiplier"], data["limit"]["collapse_multiplier"]
    if lam_l is not None:
        assert agree["multiplier_relative_difference_limit"] == pytest.approx((lam_l - lam_s) / lam_s)
        assert abs(lam_l - 1 / 3) <= 1e-4
    else:
        assert agree["multiplier_relative_difference_limit"] is None
    assert png.read_bytes().startswith(PNG)


def test_compare_without_limit_is_unchanged() -> None:
    """The library's two-method comparison keeps its shape when no limit analysis is given."""
    model = md.Model([[0.0, 0.0, 0.4, 0.175]], gravity=10.0)
    s, d = model.solve_static(), model.solve_dynamic()
    data = comparison_dict(s, d, model, "t")
    assert list(data) == ["format", "title", "static", "dynamic", "agreement"]
    assert not any(k.endswith("_limit") for k in data["agreement"])
    assert comparison_text(s, d, model, "t").splitlines()[0] == "t: static and explicit (dynamic) solvers"


def test_validate_runs_limit(tmp_path: Path) -> None:
    """validate: limit is a column of its own, run by default ("all") and with --method limit."""
    import shutil

    shutil.copy(EXAMPLES / "stack-3-blocks.toml", tmp_path)
    lines: List[str] = []
    rows, _ = validate.validate_folder(tmp_path, "limit", echo=lines.append)
    (row,) = rows
    assert set(row.multipliers) == {"limit"}
    assert lines[0].split()[:5] == ["case", "reference", "static", "explicit", "limit"]
    assert "time (limit)" in lines[0]
    assert validate.methods_of("all") == ("static", "dynamic", "limit")
    assert validate.methods_of("limit") == ("limit",)
    proc = subprocess.run([sys.executable, "-m", "masonry_dem", "validate", str(tmp_path), "--quiet"],
                          capture_output=True, text=True, timeout=300)
    cells = [c for c in proc.stdout.splitlines()[2].split("  ") if c.strip()]
    cells = [c.strip() for c in cells]
    assert cells[0] == "stack-3-blocks"
    assert cells[2] != "-" and cells[3] != "-" and cells[4] != "-"  # static, explicit and limit all ran
    assert cells[6].count(" / ") == 2
    assert proc.returncode == (0 if cells[-1] == "pass" else 1), (proc.stdout, proc.stderr)
    if row.failures.get("limit") is None:
        assert abs(row.multipliers["limit"] - 0.2) <= 1e-4


# --------------------------------------------------------------------------------------------------
# Plots and exports of a result without a curve
# --------------------------------------------------------------------------------------------------


def test_plots_of_a_limit_result(tmp_path: Path, wall1: tuple) -> None:
    """A limit result (the core's, whatever its status, and one that collapsed with a mechanism) in every
    figure: no curve to draw, the multiplier as a horizontal line."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from masonry_dem import plot

    model, res = wall1
    static = model.solve_static()
    collapsed = fake_limit(model, status="collapse", error=None, collapse_multiplier=0.6429,
                           mechanism=np.asarray(static.mechanism), interface_states=np.asarray(static.interface_states))
    for k, limit in enumerate((res, collapsed)):
        fig = plot.report_figure(model, limit, title="wall 1", path=tmp_path / f"r{k}.png")
        assert (tmp_path / f"r{k}.png").read_bytes().startswith(PNG)
        titles = [ax.get_title() for ax in fig.axes]
        assert any("no deformed shape" in t for t in titles) and any("no load path" in t for t in titles)
        if limit is collapsed:
            assert any("collapse velocities" in t for t in titles), titles
        plot.plot_results(model, limit, path=tmp_path / f"p{k}.png")
        fig = plot.plot_comparison(model, static, static, path=tmp_path / f"c{k}.png", limit=limit)
        assert (tmp_path / f"c{k}.png").read_bytes().startswith(PNG)
        curve = fig.axes[3]  # three walls, then the curves
        labels = [t.get_text() for t in curve.get_legend().get_texts()]
        assert any(t.startswith("limit: ") for t in labels), labels
        if limit is collapsed:  # the limit multiplier as a horizontal line
            assert any(np.allclose(line.get_ydata(), 0.6429) for line in curve.get_lines()), labels
        ax_fig = Figure()
        FigureCanvasAgg(ax_fig)
        ax = ax_fig.subplots()
        plot.plot_curve(ax, limit)
        plot.plot_curve(ax, static, limit)
        plot.plot_mechanism(ax, model, limit)
        plot.plot_cracks(ax, model, limit)


def test_a_static_collapse_on_associative_dry_joints_carries_its_check() -> None:
    """Load control on wall 1 (psi = mu, dry): the collapse comes with limit analysis's certificate, whose
    multiplier is the exact 0.6429 (0.642857...) and the static one within 10 tolerances (1e-3) below it;
    the summary says so. With psi = 0 (non-associative) limit analysis is no exact check: no certificate."""
    case = md.load_case(WALL1)
    model = case.build_model()
    res = model.solve_static(control="load")
    assert res.status == "collapse", res.error
    cert = res.certificate
    assert cert is not None and abs(cert["multiplier"] - 0.6429) <= 1e-4
    assert cert["multiplier"] * (1 - 1e-3) <= res.collapse_multiplier <= cert["multiplier"] * (1 + 1e-9)
    assert "checked against:     limit analysis, 0.6429" in summary(case.title, model, res)
    kwargs = dict(case.model_kwargs)
    kwargs["joints"] = {"default": {**kwargs["joints"]["default"], "dilatancy": 0.0}}
    assert md.Model(**kwargs).solve_static(control="load").certificate is None
