"""Modal analysis of the elastic model: natural frequencies and mode shapes, Rayleigh damping, and a figure
(:func:`plot_modes`, of :mod:`masonry_dem.plot.modes`).

The modes solve ``K phi = omega^2 M phi`` on the free dofs: ``K`` the elastic stiffness of every interface
(every joint closed and elastic, as in the undeformed wall), ``M`` the blocks' masses and rotary inertias
(docs/modal.md). A 3D model (:class:`masonry_dem.Model3D`, boxes and polyhedra) has 6 dofs per block, each
block's full inertia tensor and the elastic law of the 3D explicit solver at its contacts' corners. The compiled
core computes them (shift-invert block Lanczos on a sparse Cholesky):

>>> import masonry_dem as md
>>> model = md.Model([[0.0, 0.0, 0.4, 1.0]])
>>> m = md.modes(model, 3)
>>> m.frequencies_hz.round(1).tolist()
[97.3, 503.3, 966.4]
>>> alpha, beta = md.rayleigh_damping(m, 0.05)   # 5% at the first two modes

Units: frequencies in Hz, angular frequencies in rad/s, ``omega^2`` and the shift in rad2/s2, masses in kg.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, List, Optional, Tuple

import numpy as np

from . import _core
from ._checked import input_errors
from ._core import InputError, Modes

if TYPE_CHECKING:  # the figure of the modes is the plots' (masonry_dem.plot.modes): named here, imported on first use
    from .plot.modes import DEFAULT_PANELS, MODE_FRACTION, plot_modes

__all__ = ["Modes", "modes", "rayleigh_damping", "plot_modes"]

_modes = input_errors(_core.modes, "modes")
_rayleigh = input_errors(_core.rayleigh, "rayleigh_damping")


def modes(model: Any, n: int = 6, shift: Optional[float] = None) -> Modes:
    """The ``n`` lowest natural modes of ``model``'s elastic joints.

    Args:
        model: a :class:`masonry_dem.Model`, or a :class:`masonry_dem.Model3D`.
        n: the number of modes, from 1 to the number of free dofs (3 per block not fixed; 6 in 3D).
        shift: ``omega^2`` [rad2/s2] around which the modes are sought: the ``n`` modes whose ``omega^2`` are
            nearest to it are returned. None (default): slightly below 0, so the lowest ``n`` (and a model
            with a mechanism or without supports is solved too: its rigid-body modes have frequency 0).
    Returns:
        A :class:`Modes`, lowest frequency first: ``frequencies_hz`` (n,) [Hz], ``angular_frequencies`` (n,)
        [rad/s], ``eigenvalues`` (n,) [rad2/s2], ``shapes`` (n, n_all, 3) (u1, u2, phi of every block, the
        base and top beam included as in ``Model.rects``; mass-normalized, ``phi^T M phi = 1``, fixed dofs
        0), ``residuals`` (n,) (``||K phi - omega^2 M phi|| / ||K phi||``), ``effective_mass`` (n, 2) [kg]
        (x, y) and ``free_mass`` (x, y) [kg]. Of a 3D model: ``shapes`` (n, n_all, 6) (ux, uy, uz, then the
        rotations about x, y, z, as ``Model3D.boxes``; ``phi^T M phi = 1`` with the full inertia tensors),
        ``effective_mass`` (n, 3) and ``free_mass`` along x, y and z; ``Modes.dimension`` is 3.
    Raises:
        InputError: ``n`` out of range, a non-finite shift, a shift at which ``K - shift M`` is singular,
            or a model with nothing free to vibrate.
        ConvergenceError: a mode's residual stays above 1e-6.
    """
    return _modes(model, n, shift)  # type: ignore[no-any-return]


def rayleigh_damping(
    frequencies: Any,
    zeta1: float = 0.05,
    zeta2: Optional[float] = None,
    pair: Tuple[int, int] = (0, 1),
) -> Tuple[float, float]:
    """Rayleigh damping ``C = alpha M + beta K`` with the ratio ``zeta1`` at one frequency and ``zeta2`` at another.

    Args:
        frequencies: a :class:`Modes` (its modes ``pair`` give the two frequencies), a :class:`masonry_dem.Model`
            or :class:`masonry_dem.Model3D` (its modes are computed), or two frequencies ``(f1, f2)`` [Hz].
        zeta1: the damping ratio at the first frequency [-] (default 5%).
        zeta2: the ratio at the second (default: ``zeta1``).
        pair: which two modes of a :class:`Modes` or a model (default the first two).
    Returns:
        ``(alpha, beta)``: ``alpha`` [1/s], ``beta`` [s]; at an angular frequency ``omega`` the ratio is
        ``alpha / (2 omega) + beta omega / 2``; give it to ``Model.simulate(rayleigh=(alpha, beta))`` (the
        mass-proportional part on the blocks, the stiffness-proportional part at the closed interfaces).
    Raises:
        InputError: frequencies not > 0 or equal, ratios < 0, or ratios needing a negative coefficient.
    """
    if isinstance(frequencies, (_core.Model, _core.Model3D)):
        frequencies = modes(frequencies, max(pair) + 1)
    if isinstance(frequencies, Modes):
        f = np.asarray(frequencies.frequencies_hz)
        if len(pair) != 2 or not all(isinstance(k, int) and 0 <= k < len(f) for k in pair):
            raise InputError(f"rayleigh_damping: pair must be two mode indices from 0 to {len(f) - 1}, got {pair!r}")
        f1, f2 = float(f[pair[0]]), float(f[pair[1]])
    else:
        try:
            f1, f2 = (float(v) for v in frequencies)
        except (TypeError, ValueError):
            raise InputError(
                f"rayleigh_damping: expected a Modes, a Model or two frequencies [Hz], got {frequencies!r}"
            ) from None
    return _rayleigh(f1, f2, zeta1, zeta2)  # type: ignore[no-any-return]


def __getattr__(name: str) -> Any:
    """``plot_modes`` (and its constants): the figure of the modes lives with the plots, in
    :mod:`masonry_dem.plot.modes` (matplotlib); this module keeps the name ``masonry_dem.modal.plot_modes``, a re-export
    imported on first use, so that the modal analysis imports nothing of the plots."""
    if name in ("plot_modes", "MODE_FRACTION", "DEFAULT_PANELS"):
        import importlib

        return getattr(importlib.import_module(".plot.modes", __package__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> List[str]:
    return sorted(set(globals()) | {"plot_modes", "MODE_FRACTION", "DEFAULT_PANELS"})
