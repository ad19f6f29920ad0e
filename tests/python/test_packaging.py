"""What a wheel needs beyond the code: the examples shipped in the package (so ``masonry-dem validate`` works from
an installed wheel), the dependencies and extras of pyproject.toml, and the errors naming the extra to install.

``make wheel-check`` builds the portable wheel and runs the demo and the validation from a fresh venv holding it
alone; these tests check the same things on the installed package (``maturin develop``) in a second or two."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import masonry_dem
from masonry_dem import validate

try:
    import tomllib
except ModuleNotFoundError:  # Python < 3.11
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[2]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))


def python(code: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", code], cwd=cwd, capture_output=True, text=True, timeout=120)


def test_examples_are_in_the_package() -> None:
    """masonry_dem/examples is in the package (in the repository a symbolic link to examples/, which maturin
    follows into the wheel) and holds every case file of examples/ with the data files they read."""
    packaged = Path(masonry_dem.__file__).parent / "examples"
    assert packaged == validate.PACKAGED_EXAMPLES
    assert packaged.is_dir(), f"{packaged}: the package has no examples (python/masonry_dem/examples -> ../../examples)"
    for source in sorted((ROOT / "examples").rglob("*.toml")) + sorted((ROOT / "examples").glob("*.csv")):
        shipped = packaged / source.relative_to(ROOT / "examples")
        assert shipped.is_file(), shipped
        assert shipped.read_bytes() == source.read_bytes()
    assert validate.default_folder() == (ROOT / "examples").resolve()


def test_default_folder_does_not_depend_on_the_current_directory(tmp_path: Path) -> None:
    """From an empty directory (no ./examples) and from one whose examples/ is something else."""
    (tmp_path / "elsewhere" / "examples").mkdir(parents=True)
    for cwd in (tmp_path, tmp_path / "elsewhere"):
        proc = python("from masonry_dem import validate; print(validate.default_folder())", cwd)
        assert proc.returncode == 0, proc.stderr
        assert Path(proc.stdout.strip()) == validate.default_folder()


def test_hard_dependencies_are_what_the_demo_and_validate_need() -> None:
    """numpy, matplotlib (the demo's plot), tqdm, meshio (--vtk): the studies' and the DataFrames' packages are
    extras, each installed by name (pip install 'masonry-dem[studies]')."""
    names = {re.split(r"[\[<>=;! ]", dep, maxsplit=1)[0] for dep in PYPROJECT["project"]["dependencies"]}
    assert names == {"numpy", "matplotlib", "tqdm", "meshio", "tomli"}
    extras = PYPROJECT["project"]["optional-dependencies"]
    for extra, needs in {"pandas": ("pandas", "pyarrow"), "studies": ("dask[distributed]", "pandas", "pyarrow"),
                         "test": ("pytest", "hypothesis", "scipy", "clarabel", "atheris")}.items():
        assert extra in extras, extra
        for name in needs:
            assert any(dep.startswith(name) for dep in extras[extra]), (extra, name)


def test_makefile_installs_the_extras_of_pyproject() -> None:
    """The Makefile names extras (maturin develop --extras), not a second list of packages."""
    makefile = (ROOT / "Makefile").read_text(encoding="utf-8")
    extras = PYPROJECT["project"]["optional-dependencies"]
    named = re.findall(r"^EXTRAS = (\S+)$", makefile, re.M)
    assert named
    for value in named:
        for extra in value.split(","):
            assert extra in extras, f"Makefile: EXTRAS names {extra!r}, not an extra of pyproject.toml"
    assert "--extras $(EXTRAS)" in makefile
    assert "pandas>=" not in makefile and "numpy>=" not in makefile


def test_studies_without_their_packages_name_the_extra(tmp_path: Path) -> None:
    """Without dask (or pandas, pyarrow) a study says which extra to install: on import, and from the command line
    as one line with exit status 1."""
    block = "import sys; sys.modules['dask'] = None; sys.modules['pyarrow'] = None; "
    proc = python(block + "import masonry_dem as md; md.run_study", tmp_path)
    assert proc.returncode == 1
    last = proc.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: masonry-dem's studies need dask[distributed], pyarrow, not installed here"), last
    assert "pip install 'masonry-dem[studies]'" in last
    proc = python(block + "from masonry_dem.cli import main; sys.exit(main(['study', 'none.toml']))", tmp_path)
    assert proc.returncode == 1, proc.stderr
    assert proc.stderr.strip() == (
        "masonry-dem: error: masonry-dem's studies need dask[distributed], pyarrow, not installed here: "
        "pip install 'masonry-dem[studies]'"
    )
