"""The docstrings that help() and Jupyter show: every public class and callable of masonry_dem has one, none of the
core's sends the reader to the stubs instead of saying it, the units are in them, and no signature shows Ellipsis
(a default PyO3 could not render)."""

import inspect
import pydoc

import pytest

import masonry_dem as md


def _public():
    """(name, object) of the callables and classes of ``masonry_dem.__all__`` (the unit constants are numbers)."""
    for name in md.__all__:
        obj = getattr(md, name)
        if inspect.isclass(obj) or callable(obj):
            yield name, obj


def _members(cls):
    """(name, member) of a class's own public methods and attributes (getters of the core included)."""
    for name, member in vars(cls).items():
        if not name.startswith("_"):
            yield name, member


PUBLIC = list(_public())
CLASSES = [(name, obj) for name, obj in PUBLIC if inspect.isclass(obj)]


@pytest.mark.parametrize("name, obj", PUBLIC, ids=[name for name, _ in PUBLIC])
def test_public_objects_have_docstrings(name, obj):
    assert (obj.__doc__ or "").strip(), f"masonry_dem.{name} has no docstring"
    assert "see _core.pyi" not in obj.__doc__, f"masonry_dem.{name}'s docstring sends to the stubs"


@pytest.mark.parametrize("name, cls", CLASSES, ids=[name for name, _ in CLASSES])
def test_class_members_have_docstrings(name, cls):
    # the classes of the core, and Python classes' own methods; exceptions keep the standard ones
    if issubclass(cls, BaseException):
        return
    for member_name, member in _members(cls):
        if isinstance(member, (int, float, str, tuple, dict, list, frozenset, type(None))):
            continue  # a constant of the class, not documented one by one
        doc = inspect.getdoc(member) or ""
        assert doc.strip(), f"masonry_dem.{name}.{member_name} has no docstring"
        assert "see _core.pyi" not in doc, f"masonry_dem.{name}.{member_name}'s docstring sends to the stubs"


def test_core_docstrings_do_not_send_to_the_stubs():
    from masonry_dem import _core

    for name in dir(_core):
        obj = getattr(_core, name)
        docs = [obj.__doc__ or ""] + [inspect.getdoc(m) or "" for _, m in _members(obj)] if inspect.isclass(obj) else [obj.__doc__ or ""]
        assert not any("see _core.pyi" in d for d in docs), name


def test_help_of_simulate_gives_the_arguments_and_units():
    text = pydoc.render_doc(md.Model.simulate, renderer=pydoc.plaintext)
    for word in ("duration", "base_acceleration", "[s]", "[m/s2]", "record_interval"):
        assert word in text, word


def test_help_of_results_gives_the_attributes_meanings():
    text = pydoc.render_doc(md.Results, renderer=pydoc.plaintext)
    for word in ("collapse_multiplier", "NaN unless the status is \"collapse\"", "interface_forces", "[N]", "[m]"):
        assert word in text, word
    history = pydoc.render_doc(md.TimeHistory, renderer=pydoc.plaintext)
    assert "base_shear" in history and "[J]" in history


def test_model_signature_shows_its_arguments():
    sig = inspect.signature(md.Model)
    assert list(sig.parameters)[:2] == ["blocks", "thickness"]
    assert "top_force" in sig.parameters


def _signature(obj):
    try:
        return inspect.signature(obj)
    except (TypeError, ValueError):  # a builtin without a text signature
        return None


@pytest.mark.parametrize("name, obj", PUBLIC, ids=[name for name, _ in PUBLIC])
def test_no_signature_shows_ellipsis(name, obj):
    callables = [(name, obj)]
    if inspect.isclass(obj) and not issubclass(obj, BaseException):
        callables += [(f"{name}.{n}", m) for n, m in _members(obj) if callable(m)]
    for label, func in callables:
        sig = _signature(func)
        if sig is None:
            continue
        assert "Ellipsis" not in str(sig) and "=..." not in str(sig), f"{label}{sig}"
        assert all(p.default is not Ellipsis for p in sig.parameters.values()), f"{label}{sig}"


def _stub_docstrings():
    """{(class or None, name): docstring} of _core.pyi: functions, classes, methods, properties and attributes."""
    import ast
    from pathlib import Path

    from masonry_dem import _core

    tree = ast.parse((Path(md.__file__).parent / "_core.pyi").read_text())
    docs = {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            docs[(None, node.name)] = ast.get_docstring(node)
        elif isinstance(node, ast.ClassDef) and hasattr(_core, node.name):
            docs[(node.name, None)] = ast.get_docstring(node)
            for k, item in enumerate(node.body):
                if isinstance(item, ast.FunctionDef) and not item.name.startswith("_"):
                    docs[(node.name, item.name)] = ast.get_docstring(item)
                elif isinstance(item, ast.AnnAssign) and k + 1 < len(node.body):
                    after = node.body[k + 1]
                    if isinstance(after, ast.Expr) and isinstance(after.value, ast.Constant):
                        docs[(node.name, item.target.id)] = inspect.cleandoc(after.value.value)
    return {key: doc for key, doc in docs.items() if doc}


def test_runtime_docstrings_are_the_stubs():
    # the stubs are the reference (IDEs and the API reference read them): the core's docstrings hold the same words
    from masonry_dem import _core

    for (cls, name), doc in _stub_docstrings().items():
        owner = _core if cls is None else getattr(_core, cls)
        if name is not None and not hasattr(owner, name):
            continue  # a stub of what is not compiled in (rayleigh is masonry_dem.modal's)
        obj = owner if name is None else (getattr(_core, name) if cls is None else vars(owner)[name])
        assert inspect.cleandoc(obj.__doc__ or "") == doc, f"{cls}.{name}: runtime docstring differs from _core.pyi"
