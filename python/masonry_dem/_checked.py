"""The core's entry points for users, with a wrong argument type reported as :class:`InputError`.

The compiled core converts its arguments itself: a string where a number belongs, a float where an integer
belongs, or an integer too large for it raise TypeError or OverflowError there. The user-facing
``Model``, ``running_bond`` and ``pattern`` re-raise them as InputError (a subclass of MasonryError), with
the function and the argument named, so that one ``except masonry_dem.InputError`` catches every bad
input. An exception raised by a progress callback is the user's own and passes unchanged (it carries the
partial results as its ``results`` attribute).
"""

from __future__ import annotations

import functools
import inspect
import re
import reprlib
from typing import Any, Callable, Optional, Tuple, TypeVar

import numpy as np

from . import _core
from ._core import InputError

F = TypeVar("F", bound=Callable[..., Any])


def _argument(exc: BaseException, func: Callable[..., Any], args: Any, kwargs: Any) -> str:
    """The argument at fault, as "'steps' = 'x'": the core notes "while processing 'steps'" on the exception
    (PyO3), and the value is the one passed. Empty when unknown."""
    names = [m.group(1) for note in getattr(exc, "__notes__", ()) for m in [re.search(r"processing '(\w+)'", str(note))] if m]
    if not names:
        return ""
    try:
        value = inspect.signature(func).bind(*args, **kwargs).arguments.get(names[0], inspect.Parameter.empty)
    except (TypeError, ValueError):
        value = inspect.Parameter.empty
    shown = "" if value is inspect.Parameter.empty else f" = {reprlib.repr(value)}"
    return f"'{names[0]}'{shown}: "


def _real_blocks(func: str, blocks: Any) -> None:
    """Refuse block rectangles that are booleans or complex numbers (which the core would take as numbers),
    or none."""
    if blocks is None:
        return
    try:
        array = np.asarray(blocks)
    except (ValueError, TypeError):  # ragged rows: the core says which
        return
    if array.dtype.kind in "bc":  # numbers to Python, but not lengths
        raise InputError(f"{func}: blocks must be real numbers [m], got an array of {array.dtype}")
    if array.dtype == object and any(isinstance(x, (bool, np.bool_, complex, np.complexfloating)) for x in array.ravel()):
        raise InputError(f"{func}: blocks must be real numbers [m], got booleans or complex numbers")
    if array.size == 0:
        raise InputError(f"{func}: no blocks: give at least one rectangle [x0, y0, x1, y1]")


def _real_arrays(name: str, func: Callable[..., Any], args: Any, kwargs: Any) -> None:
    """Refuse a NumPy array of booleans or complex numbers given where numbers belong (the core would take
    True as 1 and drop an imaginary part), alone or in a tuple or list (a record's times and accelerations)."""
    values = list(kwargs.items()) + [(None, a) for a in args]
    for key, value in values:
        parts = value if isinstance(value, (tuple, list)) else (value,)
        for part in parts:
            if isinstance(part, np.ndarray) and part.dtype.kind in "bc":
                where = f"'{key}': " if key else ""
                raise InputError(f"{name}: {where}expected real numbers, got an array of {part.dtype}")


#: The arguments of the core's entry points that take a boolean; a boolean given to any other is refused (the core
#: would take True for the number 1), but for those that take no number, whose refusal of it the core words itself.
BOOLEAN_ARGUMENTS = frozenset(
    {"base", "large_rotations", "time_history", "along_gravity", "follow_mechanism", "bonded", "contact_update"}
)
_NO_NUMBER = frozenset({"progress", "first_course"})


def _boolean_in(value: Any, path: str = "") -> Optional[Tuple[str, Any]]:
    """Where a boolean sits in ``value`` (itself, or an entry of its lists, tuples and arrays), and the boolean:
    ("", True) for the value itself, ("[0][2]", True) for an entry; None when there is none. Dicts are not searched
    (the joints: the core names a boolean law parameter itself)."""
    if isinstance(value, (bool, np.bool_)):
        return path, value
    if isinstance(value, np.ndarray):
        if value.dtype.kind == "b" and value.size:
            return path + "[0]" * value.ndim, value.flat[0]
        if value.dtype != object:
            return None
        for index, item in np.ndenumerate(value):
            if isinstance(item, (bool, np.bool_)):
                return path + "".join(f"[{k}]" for k in index), item
        return None
    if isinstance(value, (list, tuple)):
        for k, item in enumerate(value):
            found = _boolean_in(item, f"{path}[{k}]")
            if found is not None:
                return found
    return None


def refuse_booleans(name: str, signature: Optional[inspect.Signature], args: Any, kwargs: Any) -> None:
    """Refuse a boolean given where numbers belong (any argument but those of :data:`BOOLEAN_ARGUMENTS`), alone or
    in a list of rows, with InputError naming ``name``, the argument and the entry."""
    if signature is None:
        return
    try:
        arguments = signature.bind(*args, **kwargs).arguments
    except TypeError:  # a missing or unknown argument: the core says which
        return
    for key, value in arguments.items():
        if key in BOOLEAN_ARGUMENTS or key in _NO_NUMBER:
            continue
        found = _boolean_in(value)
        if found is not None:
            where, flag = found
            raise InputError(f"{name}: '{key}'{where} = {bool(flag)}: a boolean, which '{key}' does not take (it would "
                             f"count as the number {int(bool(flag))})")


def _signature(func: Callable[..., Any]) -> Optional[inspect.Signature]:
    try:
        return inspect.signature(func)
    except (TypeError, ValueError):
        return None


def input_errors(func: F, name: str) -> F:
    """``func`` with TypeError / OverflowError of its arguments raised as InputError naming ``name``, and booleans
    given where numbers belong refused (:func:`refuse_booleans`)."""
    signature = _signature(func)

    @functools.wraps(func)
    def checked(*args: Any, **kwargs: Any) -> Any:
        _real_arrays(name, func, args, kwargs)
        refuse_booleans(name, signature, args, kwargs)
        try:
            return func(*args, **kwargs)
        except RuntimeError as exc:
            # PyO3's refusal to change a model that another thread is solving (or to solve one being changed)
            if not str(exc).startswith(("Already borrowed", "Already mutably borrowed")):
                raise
            raise InputError(
                f"{name}: the model is busy: an analysis of it runs in another thread (a model is changed only "
                "when no analysis of it runs; wait for it to end, or build another model)"
            ) from None
        except (TypeError, OverflowError) as exc:
            if hasattr(exc, "results"):  # raised by the progress callback: the user's own exception
                raise
            reason = "an integer out of range" if isinstance(exc, OverflowError) else str(exc)
            raise InputError(f"{name}: {_argument(exc, func, args, kwargs)}{reason}") from None

    return checked  # type: ignore[return-value]


running_bond = input_errors(_core.running_bond, "running_bond")
pattern = input_errors(_core.pattern, "pattern")


class Model(_core.Model):
    __doc__ = _core.Model.__doc__
    __module__ = "masonry_dem"

    def __new__(cls, *args: Any, **kwargs: Any) -> "Model":
        _real_blocks("Model", args[0] if args else kwargs.get("blocks"))
        refuse_booleans("Model", _MODEL_SIGNATURE, args, kwargs)
        return input_errors(_core.Model.__new__, "Model")(cls, *args, **kwargs)  # type: ignore[no-any-return]

    def __init__(self, *args: Any, **kwargs: Any) -> None:  # built by __new__ (the core's constructor)
        pass


# The constructor's signature as help(), Jupyter and inspect show it: the core's (its text signature, each
# argument but blocks defaulting to None, the core's default), not the (*args, **kwargs) __new__ passes on.
_MODEL_SIGNATURE = inspect.signature(_core.Model)
Model.__signature__ = _MODEL_SIGNATURE  # type: ignore[attr-defined]

for _name in ("fix", "solve_static", "solve_limit", "solve_dynamic", "simulate"):
    setattr(Model, _name, input_errors(getattr(_core.Model, _name), f"Model.{_name}"))
del _name
