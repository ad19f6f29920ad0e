"""The exceptions of masonry_dem. The compiled core raises these very classes (it imports this module).

Each subclasses the standard exception it is a kind of, so that code that knows nothing of masonry_dem
still catches it: ``except ValueError`` catches an :class:`InputError`. Running out of memory is the
standard ``MemoryError``; Ctrl-C the standard ``KeyboardInterrupt`` (carrying the partial ``results``).
"""

from __future__ import annotations

from typing import Optional


class MasonryError(Exception):
    """Base class of every error raised by masonry_dem."""

    __module__ = "masonry_dem"


class InputError(MasonryError, ValueError):
    """Bad input: the message names the key, block or interface at fault.

    ``key`` is the case-file key at fault ("geometry.thickness", "joints.bed.friction") when the error
    concerns one key, else None.
    """

    __module__ = "masonry_dem"

    def __init__(self, message: str = "", key: Optional[str] = None) -> None:
        super().__init__(message)
        self.key = key


class ConvergenceError(MasonryError, ArithmeticError):
    """A solver did not converge."""

    __module__ = "masonry_dem"


class MechanismError(MasonryError):
    """The model is a mechanism before any load: it cannot stand under its dead loads."""

    __module__ = "masonry_dem"


__all__ = ["MasonryError", "InputError", "ConvergenceError", "MechanismError"]
