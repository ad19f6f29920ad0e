"""Hostile inputs, refused by name or labelled for what they give: each ends in one line on the command line
(exit status 2), never a traceback, never a hang, never a confident wrong number. Cheap: one block, short
records; a FIFO is guarded by a timeout."""

from __future__ import annotations

import json
import math
import os
import re
import subprocess
import sys
import time
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem import atomic, cli

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
ROCKING = EXAMPLES / "single-block-rocking.toml"

BLOCK_CASE = """format = 1
[geometry]
blocks = [[0.0, 0.0, 0.2, 0.6]]
[joints]
friction = 0.65
"""


def masonry_dem(*args: str, cwd: Path, timeout: float = 120) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "masonry_dem", *args], cwd=cwd, capture_output=True, text=True, timeout=timeout
    )


def one_error_line(proc: subprocess.CompletedProcess, status: int = 2) -> str:
    assert proc.returncode == status, (proc.stdout, proc.stderr)
    assert "Traceback" not in proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("masonry-dem: error: "), proc.stderr
    return lines[0]


def simulate_case(folder: Path, record: str) -> Path:
    case = folder / "th.toml"
    case.write_text(BLOCK_CASE + f'[ground_motion]\nfile = "{record}"\nunits = "g"\n[time_history]\nduration = 0.05\n')
    return case


# --------------------------------------------------------------------------------------------------
# Files that are not files, or too large
# --------------------------------------------------------------------------------------------------


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs")
@pytest.mark.parametrize("command", ["run", "simulate"])
def test_a_fifo_record_is_refused_not_waited_for(tmp_path: Path, command: str) -> None:
    os.mkfifo(tmp_path / "rec.csv")
    case = simulate_case(tmp_path, "rec.csv")
    line = one_error_line(masonry_dem(command, str(case), cwd=tmp_path, timeout=60))
    assert "rec.csv: it is a FIFO, not a regular file" in line


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs")
def test_a_fifo_case_file_is_refused_not_waited_for(tmp_path: Path) -> None:
    os.mkfifo(tmp_path / "c.toml")
    line = one_error_line(masonry_dem("run", str(tmp_path / "c.toml"), cwd=tmp_path, timeout=60))
    assert "it is a FIFO, not a regular file" in line


def test_an_overflowing_record_is_refused_without_a_warning(tmp_path: Path) -> None:
    (tmp_path / "rec.csv").write_text("0.0,0.0\n0.01,1e308\n0.02,0.0\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # numpy's overflow warning would be an error here
        with pytest.raises(md.InputError, match="must be finite numbers"):
            md.ground_motion.read_csv(tmp_path / "rec.csv", units="g")
    proc = masonry_dem("simulate", str(simulate_case(tmp_path, "rec.csv")), cwd=tmp_path)
    assert "must be finite numbers" in one_error_line(proc)
    assert "Warning" not in proc.stderr


# --------------------------------------------------------------------------------------------------
# Beyond the model's range
# --------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("max_displacement", [1e10, 1e20, -5.0])
@pytest.mark.parametrize("solver", ["solve_static", "solve_dynamic"])
def test_displacement_control_beyond_the_small_displacement_range_is_refused(max_displacement: float, solver: str) -> None:
    model = md.Model([[0.0, 0.0, 0.2, 0.6]], joints={"default": {"friction": 0.65}})
    with pytest.raises(md.InputError, match=r"beyond the small-displacement model's range: at most a tenth of the wall's size"):
        getattr(model, solver)(control="displacement", max_displacement=max_displacement)


def test_displacement_control_beyond_the_range_on_the_command_line(tmp_path: Path) -> None:
    case = tmp_path / "c.toml"
    case.write_text(BLOCK_CASE + '[analysis]\ncontrol = "displacement"\nmax_displacement = 1e10\n')
    assert "a tenth of the wall's size" in one_error_line(masonry_dem("run", str(case), cwd=tmp_path))


@pytest.mark.parametrize("solver", ["solve_static", "solve_dynamic"])
def test_max_displacement_under_load_control_is_refused(solver: str) -> None:
    model = md.Model([[0.0, 0.0, 0.2, 0.6]], joints={"default": {"friction": 0.65}})
    with pytest.raises(md.InputError, match="applies to displacement control only"):
        getattr(model, solver)(max_displacement=-1.0)
    with pytest.raises(md.InputError, match="applies to displacement control only"):
        getattr(model, solver)(control="load", max_displacement=0.001)


@pytest.mark.parametrize("peak_g", [1e30, 1e6])
def test_a_time_history_beyond_the_model_range_fails_with_the_reason(peak_g: float) -> None:
    model = md.Model([[0.0, 0.0, 0.2, 0.6]], joints={"default": {"friction": 0.65}})
    t = np.linspace(0.0, 0.05, 51)
    h = model.simulate(base_acceleration=(t, peak_g * 9.81 * np.sin(60.0 * t)), duration=0.05)
    assert h.status == "failed", h.status
    assert "left the model's range" in h.error and "block 0" in h.error


def test_a_moderate_time_history_still_completes() -> None:
    model = md.Model([[0.0, 0.0, 0.2, 0.6]], joints={"default": {"friction": 0.65}})
    t = np.linspace(0.0, 0.05, 51)
    assert model.simulate(base_acceleration=(t, 0.05 * 9.81 * np.sin(60.0 * t)), duration=0.05).status == "completed"


# --------------------------------------------------------------------------------------------------
# The Python API
# --------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("blocks", [np.ones((1, 4), dtype=bool), np.array([[0.0, 0.0, 0.2 + 0j, 0.6]]), np.zeros((0, 4))])
def test_blocks_of_booleans_complex_numbers_or_none_are_refused(blocks: Any) -> None:
    with pytest.raises(md.InputError, match="Model: "):
        md.Model(blocks)


def test_a_running_bond_with_no_block_is_refused() -> None:
    with pytest.raises(md.InputError, match="no block fits"):
        md.running_bond(0.4, 0.2, 3, length=1e-300)
    with pytest.raises(md.InputError, match="hold no block"):
        md.pattern(0.4, 0.2, [[]])


@pytest.mark.parametrize("dtype", [bool, complex])
def test_a_record_of_booleans_or_complex_numbers_is_refused(dtype: Any) -> None:
    model = md.Model([[0.0, 0.0, 0.2, 0.6]], joints={"default": {"friction": 0.65}})
    t = np.linspace(0.0, 0.05, 11)
    with pytest.raises(md.InputError, match="'base_acceleration': expected real numbers"):
        model.simulate(base_acceleration=(t, np.ones(11, dtype=dtype)), duration=0.05)


def test_a_model_being_solved_says_busy() -> None:
    model = md.Model([[0.0, 0.0, 0.2, 0.6]], joints={"default": {"friction": 0.65}})
    seen = []

    def progress(*_: Any) -> None:
        if not seen:
            try:
                model.fix(0, 0)
            except Exception as exc:  # noqa: BLE001 - recorded for the test
                seen.append(exc)

    model.solve_static(progress=progress)
    assert seen and isinstance(seen[0], md.InputError), seen
    assert "busy" in str(seen[0]) and "Already borrowed" not in str(seen[0])
    model.fix(0, 0)  # once the analysis is over, the model can be changed


# --------------------------------------------------------------------------------------------------
# Output paths
# --------------------------------------------------------------------------------------------------


def test_a_long_legal_output_name_is_written(tmp_path: Path) -> None:
    name = "x" * 245 + ".json"  # 250 characters: legal, and its temporary file fits too
    proc = masonry_dem("run", str(ROCKING), "--json", name, "-q", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert json.loads((tmp_path / name).read_text())["status"] == "collapse"
    assert [p.name for p in tmp_path.iterdir()] == [name]


@pytest.mark.parametrize("args", [["--json", ""], ["--plot", ""], ["--vtk", "out/"], ["--plot", "."], ["--csv", "out/"]])
def test_empty_or_folder_output_names_are_refused(tmp_path: Path, args: Any) -> None:
    (tmp_path / "out").mkdir()
    line = one_error_line(masonry_dem("run", str(ROCKING), *args, cwd=tmp_path))
    assert "empty" in line or "folder" in line
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"] and not any((tmp_path / "out").iterdir())


def test_a_write_error_names_the_output_not_the_temporary_file(tmp_path: Path, monkeypatch: Any) -> None:
    real_open = os.open

    def refuse_temporaries(path: Any, *args: Any, **kwargs: Any) -> int:
        if ".tmp" in os.fspath(path):
            raise PermissionError(13, "Permission denied", os.fspath(path))
        return real_open(path, *args, **kwargs)

    monkeypatch.setattr(atomic.os, "open", refuse_temporaries)
    with pytest.raises(PermissionError) as info:
        atomic.write_text(tmp_path / "x.json", "{}")
    assert info.value.filename == str(tmp_path / "x.json")
    assert ".tmp" not in str(info.value)


def test_the_leftover_of_a_killed_write_is_removed_by_the_next(tmp_path: Path) -> None:
    target = tmp_path / "x.json"
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True)
    dead_pid = int(dead.stdout)
    key = atomic._key(target)
    left = tmp_path / f".md-{key}.{dead_pid}.0123abcd.tmp.json"  # as a write killed mid-way leaves it
    alive = tmp_path / f".md-{key}.{os.getppid()}.0123abcd.tmp.json"  # a write still running: kept
    left.write_text("{")
    alive.write_text("{")
    atomic.write_text(target, "{}")
    assert target.read_text() == "{}"
    assert not left.exists() and alive.exists()


def test_an_unwritable_study_folder_is_refused_before_the_cluster(tmp_path, monkeypatch) -> None:
    from masonry_dem.study import study_from_dict
    from masonry_dem.study.store import ResultStore

    study = study_from_dict({"format": 1, "case": str(ROCKING), "study": {"methods": ["limit"]}})
    # a folder that refuses new files, on any machine and for any user (root writes into a folder made
    # read-only with chmod): creating a file there fails as the operating system says it would
    real_open = os.open

    def refusing_open(path, flags, *args, **kwargs):
        if os.path.dirname(os.fspath(path)) == str(tmp_path) and flags & os.O_CREAT:
            raise PermissionError(13, "Permission denied", os.fspath(path))
        return real_open(path, flags, *args, **kwargs)

    monkeypatch.setattr(atomic.os, "open", refusing_open)
    out = tmp_path / "x.parquet"
    with pytest.raises(md.InputError, match=rf"cannot write {re.escape(str(out))}: the folder {re.escape(str(tmp_path))} cannot be written"):
        ResultStore(study, str(out))


# --------------------------------------------------------------------------------------------------
# Studies
# --------------------------------------------------------------------------------------------------


def test_a_study_of_a_billion_analyses_is_refused_at_once() -> None:
    from masonry_dem.study import parse_study

    grids = "".join(f"[vary.{k}]\nstart = 0.3\nstop = 0.6\ncount = 1000\n" for k in ("friction", "cohesion", "density"))
    text = f'format = 1\ncase = "{ROCKING}"\n' + grids.replace("[vary.density]\nstart = 0.3\nstop = 0.6",
                                                                 "[vary.density]\nstart = 1000.0\nstop = 2000.0")
    start = time.monotonic()
    with pytest.raises(md.InputError, match=r"1,000,000,000 analyses, more than the limit of 10,000,000"):
        parse_study(text, source="s.toml")
    assert time.monotonic() - start < 2.0


@pytest.mark.parametrize("count", ["20000000", "1000000000"])
def test_a_grid_count_beyond_the_limit_is_refused_before_it_is_built(count: str) -> None:
    from masonry_dem.study import parse_study

    text = f'format = 1\ncase = "{ROCKING}"\n[vary.friction]\nstart = 0.3\nstop = 0.6\ncount = {count}\n'
    start = time.monotonic()
    with pytest.raises(md.InputError, match=r"count: must be <= 10000000|more than the limit of 10,000,000"):
        parse_study(text, source="s.toml")
    assert time.monotonic() - start < 2.0


@pytest.mark.parametrize("content", [b"PAR1 damaged \x00\x01", b"not parquet at all"])
def test_resume_on_a_damaged_results_file_names_it_and_keeps_it(tmp_path: Path, content: bytes) -> None:
    from masonry_dem.study import study_from_dict
    from masonry_dem.study.store import ResultStore

    study = study_from_dict({"format": 1, "case": str(ROCKING), "study": {"methods": ["limit"]}})
    out = tmp_path / "s.parquet"
    out.write_bytes(content)
    with pytest.raises(md.InputError, match=r"s.parquet: not a Parquet file that can be read .* nothing was changed"):
        ResultStore(study, out, resume=True)
    assert out.read_bytes() == content
    study_file = tmp_path / "s.toml"
    study_file.write_text(f'format = 1\ncase = "{ROCKING}"\n[study]\nmethods = ["limit"]\n')
    proc = masonry_dem("study", str(study_file), "--out", str(out), "--resume", "-q", cwd=tmp_path)
    assert "not a Parquet file that can be read" in one_error_line(proc)
    assert out.read_bytes() == content


def test_resume_on_a_foreign_parquet_file_says_so(tmp_path: Path) -> None:
    import pyarrow as pa
    import pyarrow.parquet as pq

    from masonry_dem.study import study_from_dict
    from masonry_dem.study.store import ResultStore

    out = tmp_path / "s.parquet"
    pq.write_table(pa.table({"a": [1, 2]}), out)
    study = study_from_dict({"format": 1, "case": str(ROCKING), "study": {"methods": ["limit"]}})
    with pytest.raises(md.InputError, match="is not the results file of a masonry-dem study"):
        ResultStore(study, out, resume=True)
    assert pq.read_table(out).num_rows == 2


# --------------------------------------------------------------------------------------------------
# The command line's last resorts
# --------------------------------------------------------------------------------------------------


def test_out_of_memory_is_one_line(monkeypatch: Any, capsys: Any) -> None:
    def no_memory(*_: Any, **__: Any) -> Any:
        raise MemoryError("cannot allocate 64.0 GB for the model")

    monkeypatch.setattr(cli, "load_case", no_memory)
    assert cli.main(["run", str(ROCKING)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["masonry-dem: error: out of memory: cannot allocate 64.0 GB for the model"]


def test_a_limit_estimate_is_written_as_one(tmp_path: Path) -> None:
    proc = masonry_dem("run", str(ROCKING), "--method", "limit", "--json", "r.json", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    data = json.loads((tmp_path / "r.json").read_text())
    assert data["status"] == "estimate" and data["collapse_multiplier"] is None
    assert math.isclose(data["last_equilibrium"], 1 / 3, rel_tol=1e-4)
    assert "neither a lower nor an upper bound" in data["note"]
    assert "estimate" in proc.stdout and "collapse multiplier: none" in proc.stdout


# --------------------------------------------------------------------------------------------------
# Inputs that were changed without a word, or refused with a message that blamed the wrong thing
# --------------------------------------------------------------------------------------------------

LEAF_CASE = EXAMPLES / "leaf-out-of-plane.toml"
DRY_3D = {"default": {"friction": 0.7, "dilatancy": 0.7}}
OUTSIDE = [5.0, 0.2, 6.0, 0.5]  # right of a facade 2 or 3 m long


@pytest.mark.parametrize(
    "make, name, span, depth",
    [
        (lambda o: md.running_bond_3d(2.0, 1.0, 0.1, 0.4, 0.2, openings=o), "running_bond_3d.openings", "x from 0 to 2 m", 0.1),
        (lambda o: md.u_wall(3.0, 1.0, 1.5, 0.2, 0.4, 0.2, openings=o), "u_wall.openings", "x from 0 to 3 m", 0.2),
        (lambda o: md.corner_wall(3.0, 1.0, 1.5, 0.2, 0.4, 0.2, openings=o), "corner.openings", "x from 0 to 3 m", 0.2),
        (lambda o: md.space.cut_openings(md.running_bond_3d(2.0, 1.0, 0.1, 0.4, 0.2), o), "openings", "x from 0 to 2 m", 0.1),
    ],
)
def test_an_opening_outside_the_wall_is_refused_by_its_index(make: Any, name: str, span: str, depth: float) -> None:
    """It was dropped without a word; one partly outside still cuts the part within (as in 2D)."""
    with pytest.raises(md.InputError) as info:
        make([[0.6, 0.2, 1.0, 0.6], OUTSIDE])
    message = str(info.value)
    assert message.startswith(f"{name}[1] [x0, z0, x1, z1] = [5, 0.2, 6, 0.5] lies outside the wall"), message
    assert f"(its facade spans {span}, z from 0 to 1 m)" in message, message
    assert info.value.key == f"{name}[1]"

    def volume(boxes: Any) -> float:
        b = np.asarray(boxes)
        return float(np.prod(b[:, 3:] - b[:, :3], axis=1).sum())

    # a door from below the ground: the 0.4 x 0.4 m of it within the facade are cut, through its depth
    removed = volume(make([])) - volume(make([[1.0, -1.0, 1.4, 0.4]]))
    assert removed == pytest.approx(0.4 * 0.4 * depth, rel=1e-12)


def test_an_opening_over_the_whole_leaf_names_the_openings() -> None:
    with pytest.raises(md.InputError, match=r"^running_bond_3d\.openings: the openings remove every block of the wall"):
        md.running_bond_3d(2.0, 1.0, 0.1, 0.4, 0.2, openings=[[-1.0, -1.0, 3.0, 3.0]])


def test_an_opening_of_three_numbers_is_asked_for_in_the_facade_coordinates() -> None:
    with pytest.raises(md.InputError, match=r"running_bond_3d\.openings\[0\]: expected 4 numbers \[x0, z0, x1, z1\], got 3"):
        md.running_bond_3d(2.0, 1.0, 0.1, 0.4, 0.2, openings=[[0.5, 0.2, 1.0]])


def _plane() -> md.Model:
    return md.Model([[0.0, 0.0, 0.2, 0.6]], joints={"default": {"friction": 0.65}})


def _box() -> md.Model3D:
    return md.Model3D([[0.0, 0.0, 0.0, 0.4, 0.6, 1.0]], joints=DRY_3D, direction=90.0)


@pytest.mark.parametrize(
    "call, needle",
    [
        (lambda: md.Model3D([[0, 0, 0, 0.4, 0.6, 1.0]], direction=True), "Model3D: 'direction' = True"),
        (lambda: md.Model3D([[0, 0, np.True_, 0.4, 0.6, 1.0]]), "Model3D: 'boxes'[0][2] = True"),
        (lambda: md.running_bond_3d(True, 1.0, 0.1, 0.4, 0.2), "running_bond_3d: 'length' = True"),
        (lambda: md.u_wall(3.0, 1.0, 1.5, 0.2, 0.4, 0.2, openings=[[1, 0.2, True, 0.6]]), "u_wall: 'openings'[0][2] = True"),
        (lambda: _box().solve_dynamic(steps=True), "Model3D.solve_dynamic: 'steps' = True"),
        (lambda: md.Model([[0, 0, True, 0.6]]), "Model: 'blocks'[0][2] = True"),
        (lambda: md.Model([[0, 0, 0.2, 0.6]], density=False), "Model: 'density' = False"),
        (lambda: md.running_bond(True, 0.2, 5, 2.0), "running_bond: 'block_length' = True"),
        (lambda: _plane().solve_static(steps=True), "Model.solve_static: 'steps' = True"),
        (lambda: _plane().solve_dynamic(control_block=True), "Model.solve_dynamic: 'control_block' = True"),
        (lambda: _plane().fix(True, 0), "Model.fix: 'block' = True"),
        (lambda: _plane().simulate(0.01, base_acceleration=([0.0, True], [0.0, 1.0])), "'base_acceleration'[0][1] = True"),
        (lambda: md.modes(_plane(), True), "modes: 'n' = True"),
    ],
)
def test_a_boolean_where_a_number_belongs_is_refused(call: Any, needle: str) -> None:
    """The core took True as the number 1 (a direction of 1 degree, a wall 1 m long)."""
    with pytest.raises(md.InputError) as info:
        call()
    assert needle in str(info.value) and "a boolean" in str(info.value), str(info.value)


def test_the_boolean_arguments_still_take_booleans() -> None:
    assert md.Model3D([[0.0, 0.0, 0.0, 0.4, 0.6, 1.0]], base=True).base_index == 1
    assert md.Model([[0.0, 0.0, 0.2, 0.6]], base=np.True_).base_index == 1
    assert _plane().simulate(0.001, large_rotations=False).status == "completed"
    assert _box().critical_time_step(time_history=True) > 0


def test_write_vtk_refuses_the_results_of_another_model_and_a_folder(tmp_path: Path) -> None:
    """The 3D export wrote NaN-filled files; a folder given as the prefix wrote FOLDER/-blocks.vtu."""
    box, leaf = _box(), md.Model3D(md.running_bond_3d(2.0, 1.05, 0.1, 0.4, 0.175), joints=DRY_3D, direction=90.0)
    plane, wall = _plane(), md.Model(md.running_bond(0.4, 0.175, 6, 2.0))
    for model, results in [(box, leaf.solve_limit()), (plane, wall.solve_limit()), (plane, box.solve_limit())]:
        with pytest.raises(md.InputError, match="^write_vtk: model does not match results"):
            md.write_vtk(model, results, tmp_path / "w")
    for model in (box, plane):
        with pytest.raises(md.InputError, match=r"^write_vtk: path_prefix: .*out/ is a folder: give a prefix such as .*out/wall"):
            md.write_vtk(model, model.solve_limit(), f"{tmp_path}/out/")
    assert sorted(p.name for p in tmp_path.iterdir()) == []


@pytest.mark.parametrize("solver", ["solve_dynamic", "solve_static"])
def test_a_fixed_control_block_is_refused(solver: str) -> None:
    """Its curve was all zeros."""
    for model in [_plane(), _box()]:
        if not hasattr(model, solver):
            continue
        with pytest.raises(md.InputError, match=r"control block 1 \(the base\) is held along [xy]"):
            getattr(model, solver)(control_block=model.base_index)


@pytest.mark.parametrize(
    "model, solver",
    [(_plane, "solve_static"), (_plane, "solve_dynamic"), (_plane, "solve_limit"), (_plane, "simulate"),
     (_box, "solve_limit"), (_box, "solve_dynamic"), (_box, "simulate")],
)
def test_a_progress_that_is_not_callable_is_refused_before_the_run(model: Any, solver: str) -> None:
    """It raised TypeError ('int' object is not callable) at the first report, mid-run."""
    args = (0.01,) if solver == "simulate" else ()
    with pytest.raises(md.InputError, match=r"progress: expected a callable, .* got int 5"):
        getattr(model(), solver)(*args, progress=5)


def test_a_case_run_with_a_progress_that_is_not_callable_is_refused() -> None:
    case = md.load_case(LEAF_CASE)
    with pytest.raises(md.InputError, match="progress: expected a callable"):
        case.solve(case.build_model(), progress="bar")


def test_plot_mechanism_3d_asks_for_3d_axes() -> None:
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    from masonry_dem.space.plot import plot_mechanism_3d

    box = _box()
    with pytest.raises(md.InputError, match=r'plot_mechanism_3d: ax must be a 3D axes \(fig.add_subplot\(projection="3d"\)\), got Axes'):
        plot_mechanism_3d(Figure().add_subplot(), box, box.solve_limit())


def test_a_study_whose_case_is_a_study_file_says_so(tmp_path: Path) -> None:
    """It said "unknown key 'case'"; so did `run` on a study file."""
    study = tmp_path / "s.toml"
    study.write_text('format = 1\ncase = "s.toml"\n[study]\nmethods = ["limit"]\n[vary.friction]\nvalues = [0.3, 0.5]\n')
    line = one_error_line(masonry_dem("study", str(study), "--workers", "1", cwd=tmp_path))
    assert 'case: "s.toml" is a study file: the base case must be a case file' in line, line
    line = one_error_line(masonry_dem("run", str(study), cwd=tmp_path))
    assert "a study file (its keys case, study, vary), not a case file: run it with masonry-dem study" in line, line


@pytest.mark.parametrize("density", [1e-300, 1e-160])
def test_a_weight_too_small_to_compute_with_is_refused_by_its_density_in_every_method(density: float) -> None:
    """The static solver failed ("the live load does no work"), the explicit one found "no collapse bracket" after
    21,000 levels, while limit analysis answered."""
    for build in (lambda: md.Model([[0.0, 0.0, 0.4, 1.0]], density=density),
                  lambda: md.Model3D([[0.0, 0.0, 0.0, 0.4, 0.6, 1.0]], density=density)):
        with pytest.raises(md.InputError, match=rf"^geometry.density = {density:.0e} kg/m3 .* below the 1.5e-154 N") as info:
            build()
        assert info.value.key == "geometry.density"


def test_the_3d_refusals_on_the_command_line(tmp_path: Path) -> None:
    text = LEAF_CASE.read_text()
    cases = {
        "outside.toml": (text.replace('first_course = "half"', "openings = [[0.4, 0.35, 0.8, 0.7], [5, 0.2, 6, 0.5]]"),
                         "geometry.leaf.openings[1] [x0, z0, x1, z1] = [5, 0.2, 6, 0.5] lies outside the wall"),
        "whole.toml": (text.replace('first_course = "half"', "openings = [[-1, -1, 3, 3]]"),
                       "geometry.leaf.openings: the openings remove every block of the wall"),
        "light.toml": (text.replace("density = 2000.0", "density = 1e-300"), "geometry.density = 1e-300 kg/m3"),
        "lone.toml": ('format = 1\n[geometry]\nboxes = [[0, 0, 0, 0.4, 0.6, 1.0]]\n[base]\nkind = "none"\n',
                      "the wall has no support"),
    }
    for name, (content, words) in cases.items():
        (tmp_path / name).write_text(content)
        line = one_error_line(masonry_dem("run", name, cwd=tmp_path))
        assert words in line, line
