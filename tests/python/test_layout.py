"""The package's layout: its modules form layers that only point down (docs/architecture.md, "The Python package").

The graph of the package's imports is read from its sources with ``ast`` (nothing is imported): an edge m -> t for
every import of a module t of the package in m, relative or absolute, wherever it is (at module level, in a
function, in a class). Three readings make it the graph of what runs:

* ``from pkg import name`` is an edge to the module ``pkg.name`` when there is one (``from .. import _core`` imports
  the compiled core, not the package's ``__init__``), else to ``pkg``;
* importing ``a.b.c`` runs ``a.b``'s ``__init__`` first: an edge to it too, unless m is inside ``a.b`` (a module
  deep in a package drags in what the package's ``__init__`` imports);
* an import under ``if TYPE_CHECKING:`` never runs: no edge. A lazy module (the package root, ``case/``, ``plot/``,
  ``space/``, ``modal``) names there where the names its ``__getattr__`` imports on first use come from: importing
  such a name from it is an edge to the module the name comes from (:func:`test_lazy_names_come_from_where_they_say`
  checks that they do).

Two tests on that graph: no strongly connected component of more than one module (no import circle, at import time
or at call time), and the stages: every module is in one of :data:`STAGES` and imports from its own stage or below.
"""

from __future__ import annotations

import ast
import importlib
import sys
from pathlib import Path
from typing import Dict, List, Set, Tuple

import pytest

ROOT = Path(__file__).resolve().parents[2] / "python" / "masonry_dem"
PACKAGE = ROOT.name

#: The stages, bottom first; a module imports from its own stage or a lower one. Names are relative to the
#: package; "study.*" is every module of study/. The plane's module and the space's side by side in each stage.
STAGES: Tuple[Tuple[str, Tuple[str, ...]], ...] = (
    # the compiled core's entry points, checked: the models of both dimensions with their solvers (their methods)
    # and modal analysis; errors, units, files
    ("core", ("errors", "units", "_files", "atomic", "_lazy", "_shapes", "_checked", "space.model", "modal")),
    # what makes a model and its analysis: case files (a Case builds the model and runs the analysis), ground
    # motions, drawings
    ("input", ("dxf", "ground_motion", "case.table", "case.mapping", "case.common", "case.reader", "space.case",
               "default_case", "assessment.spectra", "assessment.parameters")),
    # what an analysis returns, read: time histories, response peaks, the result file and dicts, the reports in
    # words, comparisons
    ("results", ("history", "response", "case.result_file", "api", "_mechanism", "report", "thrust", "space.report",
                 "compare", "assessment.kinematic", "assessment.nonlinear", "assessment.pushover",
                 "assessment.verdict")),
    # figures and files: plots, VTK and CSV, progress bars
    ("output", ("_vtk", "export", "space.export", "plot.canvas", "plot.panels", "plot.time_panels", "plot.animation",
                "plot.figures", "plot.modes", "space.plot", "progress", "assessment.plot")),
    # what runs the rest: validation, studies, the command line
    ("drivers", ("validate", "study", "study.*", "cli_parser", "cli", "__main__")),
)

#: The lazy packages: their ``__init__`` imports nothing of theirs at run time but the core stage's (the root:
#: the model), and names the rest for first use; any stage may import a name from them (the edge then goes to
#: the module the name comes from, which the stages check).
FACADES = ("", "case", "plot", "space", "assessment")


def _modules() -> Dict[str, Path]:
    mods = {}
    for path in sorted(ROOT.rglob("*.py")):
        name = ".".join(path.relative_to(ROOT.parent).with_suffix("").parts)
        mods[name[: -len(".__init__")] if name.endswith(".__init__") else name] = path
    return mods


def _type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def _imports(tree: ast.AST) -> List[Tuple[ast.stmt, bool]]:
    """Every import statement of a module, anywhere in it, and whether it is under ``if TYPE_CHECKING:``."""
    found: List[Tuple[ast.stmt, bool]] = []

    def visit(node: ast.AST, typing_only: bool) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.Import, ast.ImportFrom)):
                found.append((child, typing_only))
            elif isinstance(child, ast.If) and _type_checking(child.test):
                for stmt in child.body:
                    visit(ast.Module(body=[stmt], type_ignores=[]), True)
                for stmt in child.orelse:
                    visit(ast.Module(body=[stmt], type_ignores=[]), typing_only)
            else:
                visit(child, typing_only)

    visit(tree, False)
    return found


def _targets(module: str, is_package: bool, node: ast.stmt) -> List[Tuple[str, str]]:
    """(what is imported from, name) of an import statement, for the package's own modules: ("a.b", "c") of
    ``from a.b import c``, ("a.b.c", "") of ``import a.b.c``."""
    if isinstance(node, ast.Import):
        return [(alias.name, "") for alias in node.names if alias.name.split(".")[0] == PACKAGE]
    assert isinstance(node, ast.ImportFrom)
    if node.level:
        parts = (module if is_package else module.rpartition(".")[0]).split(".")
        base = ".".join(parts[: len(parts) - node.level + 1] + ([node.module] if node.module else []))
    elif node.module and node.module.split(".")[0] == PACKAGE:
        base = node.module
    else:
        return []
    return [(base, alias.name) for alias in node.names]


def import_graph() -> Tuple[Dict[str, Dict[str, int]], Dict[str, Path]]:
    """{module: {module it imports: line of the first such import}} of the package, and the modules' files."""
    mods = _modules()
    known = set(mods) | {f"{PACKAGE}._core"}  # the compiled core: a module, not the package's __init__
    trees = {m: ast.parse(p.read_text(encoding="utf-8"), str(p)) for m, p in mods.items()}
    packages = {m for m, p in mods.items() if p.name == "__init__.py"}
    # the names each module exposes lazily, from where it names them under TYPE_CHECKING
    lazy: Dict[Tuple[str, str], str] = {}
    for m, tree in trees.items():
        for node, typing_only in _imports(tree):
            if typing_only and isinstance(node, ast.ImportFrom):
                for (base, name), alias in zip(_targets(m, m in packages, node), node.names):
                    lazy[(m, alias.asname or name)] = f"{base}.{name}" if f"{base}.{name}" in known else base
    graph: Dict[str, Dict[str, int]] = {m: {} for m in mods}

    def add(m: str, target: str, line: int) -> None:
        if target in mods and target != m:
            graph[m].setdefault(target, line)
        parts = target.split(".")
        for i in range(1, len(parts)):  # the packages on the way, whose __init__ runs first
            package = ".".join(parts[:i])
            if package in mods and not (m == package or m.startswith(package + ".")):
                graph[m].setdefault(package, line)

    for m, tree in trees.items():
        for node, typing_only in _imports(tree):
            if typing_only:
                continue
            for base, name in _targets(m, m in packages, node):
                if not name or f"{base}.{name}" in known:
                    add(m, f"{base}.{name}" if name else base, node.lineno)
                else:
                    add(m, base, node.lineno)
                    if (base, name) in lazy:
                        add(m, lazy[(base, name)], node.lineno)
    return graph, mods


def strongly_connected(graph: Dict[str, Dict[str, int]]) -> List[List[str]]:
    """The strongly connected components of more than one module (Tarjan, iterative)."""
    index: Dict[str, int] = {}
    low: Dict[str, int] = {}
    stack: List[str] = []
    on_stack: Set[str] = set()
    components = []
    for start in graph:
        if start in index:
            continue
        work = [(start, iter(graph[start]))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            v, edges = work[-1]
            for w in edges:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(graph[w])))
                    break
                if w in on_stack:
                    low[v] = min(low[v], index[w])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[v])
                if low[v] == index[v]:
                    component = []
                    while True:
                        w = stack.pop()
                        on_stack.discard(w)
                        component.append(w)
                        if w == v:
                            break
                    if len(component) > 1:
                        components.append(sorted(component))
    return components


def _circle(graph: Dict[str, Dict[str, int]], component: List[str]) -> List[str]:
    """One circle through the first module of a strongly connected component (a shortest one)."""
    inside, start = set(component), component[0]
    previous: Dict[str, str] = {}
    frontier = [start]
    while frontier:
        following = []
        for v in frontier:
            for w in graph[v]:
                if w == start:
                    path = [v]
                    while path[-1] != start:
                        path.append(previous[path[-1]])
                    return [start] + path[::-1][1:] + [start]
                if w in inside and w not in previous:
                    previous[w] = v
                    following.append(w)
        frontier = following
    raise AssertionError(f"no circle through {start}")  # pragma: no cover - a component has one


def _short(module: str) -> str:
    return module[len(PACKAGE) + 1:] if module.startswith(PACKAGE + ".") else module


def test_no_import_circle() -> None:
    graph, mods = import_graph()
    assert len(graph) > 40 and f"{PACKAGE}.cli" in graph  # the package was found
    messages = []
    for component in strongly_connected(graph):
        circle = _circle(graph, component)
        steps = [f"{_short(a)} ({mods[a].relative_to(ROOT.parent)}:{graph[a][b]}) -> {_short(b)}"
                 for a, b in zip(circle, circle[1:])]
        messages.append(f"{len(component)} modules in a circle: {', '.join(map(_short, component))}\n  e.g. "
                        + "\n  ".join(steps))
    assert not messages, "import circles (layers must only point down; docs/architecture.md):\n" + "\n".join(messages)


def _stage_of(module: str) -> Tuple[int, str]:
    name = _short(module) if module != PACKAGE else ""
    for rank, (stage, members) in enumerate(STAGES):
        for member in members:
            if name == member or (member.endswith(".*") and name.startswith(member[:-1])):
                return rank, stage
    return -1, ""


def test_stages_point_down() -> None:
    graph, mods = import_graph()
    facades = {f"{PACKAGE}.{f}" if f else PACKAGE for f in FACADES}
    unplaced = [_short(m) for m in graph if m not in facades and _stage_of(m)[0] < 0]
    assert not unplaced, f"modules in no stage (add them to STAGES in {Path(__file__).name}): {', '.join(unplaced)}"
    wrong = []
    for m, targets in graph.items():
        for t, line in targets.items():
            if t in facades:
                continue  # an import of a name from a lazy package is an edge to where the name comes from too
            if m in facades:
                if _stage_of(t)[0] > 0:
                    wrong.append(f"the package {_short(m) or PACKAGE} (a lazy package: FACADES) imports {_short(t)} at "
                                 f"run time ({mods[m].relative_to(ROOT.parent)}:{line}): name it for first use instead "
                                 "(masonry_dem._lazy)")
                continue
            (rank_m, stage_m), (rank_t, stage_t) = _stage_of(m), _stage_of(t)
            if rank_t > rank_m:
                wrong.append(f"{_short(m)} ({stage_m}) imports {_short(t)} ({stage_t}), "
                             f"{mods[m].relative_to(ROOT.parent)}:{line}")
    assert not wrong, "imports that point up a stage:\n" + "\n".join(wrong)


def _lazy_names() -> List[Tuple[str, str, str]]:
    """(lazy module, name, module it comes from) of every name a module with a ``__getattr__`` names under ``if
    TYPE_CHECKING:``."""
    out = []
    for m, path in _modules().items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        if not any(isinstance(node, ast.FunctionDef) and node.name == "__getattr__" for node in tree.body) and not any(
                isinstance(node, ast.Assign) and any(isinstance(t, ast.Tuple) and any(
                    isinstance(e, ast.Name) and e.id == "__getattr__" for e in t.elts) for t in node.targets)
                for node in tree.body):
            continue
        for node, typing_only in _imports(tree):
            if typing_only and isinstance(node, ast.ImportFrom):
                for (base, name), alias in zip(_targets(m, path.name == "__init__.py", node), node.names):
                    out.append((m, alias.asname or name, base))
    return out


def test_lazy_names_come_from_where_they_say() -> None:
    """Each name a lazy module names under TYPE_CHECKING is, at run time, the object of the module named there
    (what the graph above takes it for)."""
    wrong = []
    for module, name, source in _lazy_names():
        try:
            origin = importlib.import_module(source)
        except ImportError:  # an optional extra not installed (studies: Dask, pandas, pyarrow)
            continue
        try:
            value = getattr(importlib.import_module(module), name)
        except AttributeError as exc:
            wrong.append(f"{module}.{name}: {exc}")
            continue
        if value is not getattr(origin, name, None):
            wrong.append(f"{module}.{name} is not {source}.{name}")
    assert len(_lazy_names()) > 50 and not wrong, "\n".join(wrong)


def test_import_stays_light() -> None:
    """``import masonry_dem`` loads the core and the model: none of the packages of plots, exports and studies."""
    import subprocess

    heavy = ("matplotlib", "meshio", "mpl_toolkits", "pandas", "dask", "distributed", "pyarrow", "tqdm", "ezdxf")
    code = f"import sys, masonry_dem; print(sorted(m for m in {heavy!r} if m in sys.modules))"
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0 and proc.stdout.strip() == "[]", proc.stdout + proc.stderr
