"""The notebooks of examples/ (the tutorial, the arch) run from top to bottom without an error (nbclient, an ipykernel
of this interpreter), so that they do not rot; and they are kept in the repository without outputs."""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import ipykernel  # noqa: F401  (the kernel; the `test` extra installs the three, `make test` needs them)
import nbclient
import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[2]
NOTEBOOKS = [ROOT / "examples" / "tutorial.ipynb", ROOT / "examples" / "arch.ipynb"]


@pytest.mark.parametrize("notebook", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_is_stored_without_outputs(notebook: Path) -> None:
    nb = nbformat.read(notebook, as_version=4)
    nbformat.validate(nb)
    for i, cell in enumerate(nb.cells):
        if cell.cell_type == "code":
            assert not cell.outputs and cell.execution_count is None, f"cell {i} of {notebook.name} holds outputs"


@pytest.mark.parametrize("notebook", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_runs(notebook: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # A kernelspec "python3" of this very interpreter, found first (JUPYTER_PATH comes before the user's and the
    # system's folders), so that the notebook runs against the masonry_dem being tested whatever else is installed.
    spec = tmp_path / "jupyter" / "kernels" / "python3"
    spec.mkdir(parents=True)
    (spec / "kernel.json").write_text(json.dumps({
        "argv": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"],
        "display_name": "Python 3 (masonry-dem tests)",
        "language": "python",
    }))
    monkeypatch.setenv("JUPYTER_PATH", str(tmp_path / "jupyter"))
    work = tmp_path / "work"  # the notebook's working folder: nothing is written into the repository
    work.mkdir()

    nb = nbformat.read(notebook, as_version=4)
    nb.cells.insert(0, nbformat.v4.new_code_cell("import sys; print(sys.executable)"))
    client = nbclient.NotebookClient(nb, timeout=300, kernel_name="python3", resources={"metadata": {"path": str(work)}})
    start = time.perf_counter()
    client.execute()  # raises CellExecutionError at the first cell that fails
    elapsed = time.perf_counter() - start
    print(f"{notebook.name} ran in {elapsed:.1f} s")

    assert nb.cells[0].outputs[0]["text"].strip() == sys.executable
    errors = [(i, out.get("ename")) for i, cell in enumerate(nb.cells) if cell.cell_type == "code"
              for out in cell.outputs if out.output_type == "error"]
    assert not errors, errors
    assert not list(work.iterdir()), f"{notebook.name} wrote into its working folder; it writes into a temporary one"
