"""Lazy packages: a package whose ``__init__`` imports nothing of its own names where each of its public names lives,
and imports that module on first use (PEP 562's module ``__getattr__``).

This keeps ``import masonry_dem`` light (matplotlib, meshio, Dask, pandas and pyarrow load only when a name that
needs them is first used), and it keeps a package's ``__init__`` out of the import graph of its modules: a module
deep in the package (``masonry_dem.case.table``) can be imported from a lower layer without running the upper
modules the package also holds (``masonry_dem.case.reader``). Each lazy package lists the same imports under ``if
TYPE_CHECKING:`` for type checkers and IDEs; tests/python/test_layout.py reads them there as the edges of whoever
imports such a name.
"""

from __future__ import annotations

import importlib
import sys
from typing import Any, Callable, Iterable, List, Mapping, Tuple


def lazy_package(package: str, names: Mapping[str, str], public: Iterable[str]) -> Tuple[Callable[[str], Any],
                                                                                       Callable[[], List[str]]]:
    """The ``__getattr__`` and ``__dir__`` of the lazy package ``package``: ``names`` maps each name to the module
    (relative to the package, ".mapping") it is imported from on first use (then kept in the package); any other
    public name is tried as a submodule. ``public``: the names ``dir()`` lists besides those already imported."""
    shown = frozenset(public) | frozenset(names)

    def __getattr__(name: str) -> Any:
        if name in names:
            value = getattr(importlib.import_module(names[name], package), name)
            setattr(sys.modules[package], name, value)
            return value
        if not name.startswith("_"):
            try:
                return importlib.import_module(f".{name}", package)
            except ModuleNotFoundError as e:
                if e.name != f"{package}.{name}":
                    raise
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__() -> List[str]:
        return sorted(set(vars(sys.modules[package])) | shown)

    return __getattr__, __dir__
