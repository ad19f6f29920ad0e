"""Every output file is written safely: atomically (a failure while writing keeps the previous file and
leaves no temporary file), never onto something that is not a regular file or onto the case file, and the
command line writes its files before it prints (a closed stdout or an ASCII one loses nothing)."""

from __future__ import annotations

import errno
import json
import os
import stat
import subprocess
import sys
from pathlib import Path
from typing import Any, List

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem import atomic, cli
from masonry_dem.export import write_curve_csv, write_vtk

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
WALL1 = EXAMPLES / "ferris-tinloi-wall1.toml"
PREVIOUS = '{"previous": true}\n'
PNG = b"\x89PNG\r\n\x1a\n"


def masonry_dem(*args: str, cwd: Path, **kwargs: Any) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "masonry_dem", *args], cwd=cwd, capture_output=True, text=True, timeout=600, **kwargs
    )


def leftovers(folder: Path) -> List[str]:
    """Temporary files left in ``folder``."""
    return sorted(p.name for p in folder.iterdir() if ".tmp" in p.name)


def one_error_line(proc: subprocess.CompletedProcess, status: int) -> str:
    assert proc.returncode == status, (proc.stdout, proc.stderr)
    assert "Traceback" not in proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("masonry-dem: error: "), proc.stderr
    return lines[0]


@pytest.fixture(scope="module")
def wall1() -> Any:
    case = md.load_case(WALL1)
    model = case.build_model()
    return model, case.solve(model, "static")


# -- a failure while writing keeps the previous file ------------------------------------------------------


@pytest.mark.parametrize("exc", [OSError(errno.ENOSPC, "No space left on device"), KeyboardInterrupt()])
def test_json_failure_keeps_previous(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, exc: BaseException) -> None:
    """The disk fills (or Ctrl-C) after the new content went to the temporary file: the old file stays."""
    out = tmp_path / "r.json"
    out.write_text(PREVIOUS)

    def failing_fsync(fd: int) -> None:
        raise exc

    monkeypatch.setattr(atomic.os, "fsync", failing_fsync)
    status = cli.main(["run", str(WALL1), "--json", str(out), "--quiet"])
    assert status == (cli.EXIT_INTERRUPTED if isinstance(exc, KeyboardInterrupt) else cli.EXIT_FAILURE)
    assert out.read_text() == PREVIOUS
    assert leftovers(tmp_path) == []


def test_compare_json_failure_keeps_previous(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    out = tmp_path / "c.json"
    out.write_text(PREVIOUS)

    def failing_fsync(fd: int) -> None:
        raise OSError(errno.EIO, "Input/output error")

    monkeypatch.setattr(atomic.os, "fsync", failing_fsync)
    status = cli.main(["compare", str(EXAMPLES / "single-block-rocking.toml"), "--json", str(out), "--quiet"])
    assert status == cli.EXIT_FAILURE
    assert out.read_text() == PREVIOUS
    assert leftovers(tmp_path) == []


def test_plot_failure_midway_keeps_previous(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """savefig writes half a PNG and fails: the previous plot is still there, whole."""
    from matplotlib.figure import Figure

    png = tmp_path / "p.png"
    png.write_bytes(PNG + b"previous")

    def half_savefig(self: Figure, fname: Any, **kwargs: Any) -> None:
        if hasattr(fname, "write"):
            fname.write(PNG[:4])
        else:
            with open(fname, "wb") as f:
                f.write(PNG[:4])
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(Figure, "savefig", half_savefig)
    status = cli.main(["run", str(WALL1), "--plot", str(png), "--quiet"])
    assert status == cli.EXIT_FAILURE
    assert png.read_bytes() == PNG + b"previous"
    assert leftovers(tmp_path) == []


def test_csv_and_vtk_failure_keep_previous(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, wall1: Any) -> None:
    model, results = wall1
    csv = tmp_path / "c.csv"
    csv.write_text("previous\n")
    blocks = tmp_path / "w-blocks.vtu"
    blocks.write_text("previous\n")

    def failing_fsync(fd: int) -> None:
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(atomic.os, "fsync", failing_fsync)
    with pytest.raises(OSError):
        write_curve_csv(results, csv)
    with pytest.raises(OSError):
        write_vtk(model, results, tmp_path / "w")
    assert csv.read_text() == "previous\n"
    assert blocks.read_text() == "previous\n"
    assert not (tmp_path / "w-interfaces.vtu").exists()
    assert leftovers(tmp_path) == []


def test_atomic_file_removes_temp_on_error(tmp_path: Path) -> None:
    out = tmp_path / "x.txt"
    out.write_text("old")
    with pytest.raises(RuntimeError):
        with atomic.atomic_file(out) as f:
            f.write("new, half")
            raise RuntimeError("boom")
    assert out.read_text() == "old"
    assert leftovers(tmp_path) == []
    atomic.write_text(out, "new")
    assert out.read_text() == "new"
    assert leftovers(tmp_path) == []


# -- targets that are not regular files, and the case file -------------------------------------------------


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs")
def test_csv_onto_fifo_refused(tmp_path: Path) -> None:
    fifo = tmp_path / "f.csv"
    os.mkfifo(fifo)
    line = one_error_line(masonry_dem("run", str(WALL1), "--csv", str(fifo), cwd=tmp_path), 2)
    assert "FIFO" in line
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)
    assert leftovers(tmp_path) == []


@pytest.mark.parametrize("option", ["--csv", "--json", "--plot"])
def test_output_onto_folder_refused(tmp_path: Path, option: str) -> None:
    folder = tmp_path / "d.png"
    folder.mkdir()
    (folder / "keep").write_text("x")
    line = one_error_line(masonry_dem("run", str(WALL1), option, str(folder), cwd=tmp_path), 2)
    assert "folder" in line
    assert (folder / "keep").read_text() == "x"


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs")
def test_library_writers_refuse_fifo(tmp_path: Path, wall1: Any) -> None:
    model, results = wall1
    fifo = tmp_path / "w-interfaces.vtu"
    os.mkfifo(fifo)
    with pytest.raises(md.InputError, match="FIFO"):
        write_vtk(model, results, tmp_path / "w")
    assert not (tmp_path / "w-blocks.vtu").exists()  # refused before either file is written
    with pytest.raises(md.InputError, match="FIFO"):
        write_curve_csv(results, fifo)
    with pytest.raises(md.InputError, match="FIFO"):
        md.to_json(results, fifo, model)
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)
    assert leftovers(tmp_path) == []


@pytest.mark.parametrize("option", ["--json", "--csv", "--plot"])
def test_output_onto_case_file_refused(tmp_path: Path, option: str) -> None:
    name = "case.png" if option == "--plot" else "case.toml"  # a plot needs a figure format
    case = tmp_path / name
    case.write_text(WALL1.read_text())
    before = case.read_bytes()
    line = one_error_line(masonry_dem("run", name, option, f"./{name}", cwd=tmp_path), 2)
    assert "input file" in line
    assert case.read_bytes() == before


def test_compare_json_onto_case_file_refused(tmp_path: Path) -> None:
    case = tmp_path / "case.toml"
    case.write_text((EXAMPLES / "single-block-rocking.toml").read_text())
    before = case.read_bytes()
    one_error_line(masonry_dem("compare", "case.toml", "--json", str(case), cwd=tmp_path), 2)
    assert case.read_bytes() == before


@pytest.mark.skipif(not hasattr(os, "symlink"), reason="no symbolic links")
def test_symlink_to_case_file_refused_and_link_to_output_kept(tmp_path: Path) -> None:
    case = tmp_path / "case.toml"
    case.write_text(WALL1.read_text())
    before = case.read_bytes()
    (tmp_path / "alias.json").symlink_to("case.toml")
    one_error_line(masonry_dem("run", "case.toml", "--json", "alias.json", cwd=tmp_path), 2)
    assert case.read_bytes() == before

    (tmp_path / "real.json").write_text(PREVIOUS)
    os.chmod(tmp_path / "real.json", 0o640)
    (tmp_path / "link.json").symlink_to("real.json")
    proc = masonry_dem("run", "case.toml", "--json", "link.json", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "link.json").is_symlink()
    assert json.loads((tmp_path / "real.json").read_text())["title"] == "Ferris & Tin-Loi wall 1"
    assert stat.S_IMODE(os.stat(tmp_path / "real.json").st_mode) == 0o640


def test_same_file_for_two_outputs_refused(tmp_path: Path) -> None:
    line = one_error_line(masonry_dem("run", str(WALL1), "--json", "a.out", "--csv", "a.out", cwd=tmp_path), 2)
    assert "two outputs" in line
    assert not (tmp_path / "a.out").exists()


# -- stdout: closed, or unable to show a character ----------------------------------------------------------


def test_closed_stdout_loses_nothing(tmp_path: Path) -> None:
    """``masonry-dem run case --json X | head -0``: the reader is gone before anything is printed."""
    read_end, write_end = os.pipe()
    os.close(read_end)
    try:
        proc = subprocess.run(
            [sys.executable, "-m", "masonry_dem", "run", str(WALL1), "--json", "r.json", "--csv", "r.csv"],
            cwd=tmp_path, stdout=write_end, stderr=subprocess.PIPE, text=True, timeout=600,
        )
    finally:
        os.close(write_end)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    data = json.loads((tmp_path / "r.json").read_text())
    assert data["title"] == "Ferris & Tin-Loi wall 1" and data["status"] == "collapse"
    assert np.loadtxt(tmp_path / "r.csv", delimiter=",", skiprows=1).shape[0] > 1


def test_ascii_stdout_non_ascii_title(tmp_path: Path) -> None:
    case = tmp_path / "façade.toml"
    text = WALL1.read_text().replace('title = "Ferris & Tin-Loi wall 1"', 'title = "Mur de façade — λ"')
    case.write_text(text, encoding="utf-8")
    env = dict(os.environ, PYTHONIOENCODING="ascii", LC_ALL="C", LANG="C")
    proc = masonry_dem("run", case.name, "--json", "r.json", "--csv", "r.csv", cwd=tmp_path, env=env)
    assert proc.returncode == 0, proc.stderr
    assert "Traceback" not in proc.stderr
    assert "Mur de fa?ade" in proc.stdout
    assert "wrote r.json" in proc.stdout
    assert json.loads((tmp_path / "r.json").read_text(encoding="utf-8"))["title"] == "Mur de façade — λ"


# -- "wrote" names the file written -------------------------------------------------------------------------


def test_plot_without_suffix_reports_png(tmp_path: Path) -> None:
    proc = masonry_dem("run", str(WALL1), "--plot", "out/name", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    written = os.path.join("out", "name.png")
    assert f"wrote {written}" in proc.stdout.splitlines()[-1]
    assert (tmp_path / "out" / "name.png").read_bytes().startswith(PNG)
    assert not (tmp_path / "out" / "name").exists()
    assert leftovers(tmp_path / "out") == []


def test_plot_unknown_format_refused(tmp_path: Path) -> None:
    line = one_error_line(masonry_dem("run", str(WALL1), "--plot", "w.v2", cwd=tmp_path), 2)
    assert "format" in line


def test_files_written_before_summary(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The summary is printed after the files are written (a failing print cannot lose them)."""
    out = tmp_path / "r.json"
    seen: List[bool] = []
    real_print = cli._print

    def spy(text: str = "", flush: bool = False) -> None:
        seen.append(out.exists())
        real_print(text, flush=flush)

    monkeypatch.setattr(cli, "_print", spy)
    assert cli.main(["run", str(WALL1), "--json", str(out), "--quiet"]) == 0
    assert seen and all(seen)
