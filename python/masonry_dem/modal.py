"""Modal analysis of the elastic model: natural frequencies and mode shapes, Rayleigh damping, and a figure.

The modes solve ``K phi = omega^2 M phi`` on the free dofs: ``K`` the elastic stiffness of every interface
(every joint closed and elastic, as in the undeformed wall), ``M`` the blocks' masses and rotary inertias
(docs/modal.md). The compiled core computes them (shift-invert block Lanczos on a sparse Cholesky):

>>> import masonry_dem as md
>>> model = md.Model([[0.0, 0.0, 0.4, 1.0]])
>>> m = md.modes(model, 3)
>>> m.frequencies_hz.round(1).tolist()
[97.3, 503.3, 966.4]
>>> alpha, beta = md.rayleigh_damping(m, 0.05)   # 5% at the first two modes

Units: frequencies in Hz, angular frequencies in rad/s, ``omega^2`` and the shift in rad2/s2, masses in kg.
"""

from __future__ import annotations

import math
import os
from typing import Any, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core
from ._checked import input_errors
from ._core import InputError, Modes

__all__ = ["Modes", "modes", "rayleigh_damping", "plot_modes"]

#: The largest corner displacement of a drawn mode shape, as a fraction of the wall height (default scale).
MODE_FRACTION = 0.08

#: The most modes :func:`plot_modes` draws when ``k`` is not given.
DEFAULT_PANELS = 4

_modes = input_errors(_core.modes, "modes")
_rayleigh = input_errors(_core.rayleigh, "rayleigh_damping")


def modes(model: Any, n: int = 6, shift: Optional[float] = None) -> Modes:
    """The ``n`` lowest natural modes of ``model``'s elastic joints.

    Args:
        model: a :class:`masonry_dem.Model`.
        n: the number of modes, from 1 to the number of free dofs (3 per block not fixed).
        shift: ``omega^2`` [rad2/s2] around which the modes are sought: the ``n`` modes whose ``omega^2`` are
            nearest to it are returned. None (default): slightly below 0, so the lowest ``n`` (and a model
            with a mechanism or without supports is solved too: its rigid-body modes have frequency 0).
    Returns:
        A :class:`Modes`, lowest frequency first: ``frequencies_hz`` (n,) [Hz], ``angular_frequencies`` (n,)
        [rad/s], ``eigenvalues`` (n,) [rad2/s2], ``shapes`` (n, n_all, 3) (u1, u2, phi of every block, the
        base and top beam included as in ``Model.rects``; mass-normalized, ``phi^T M phi = 1``, fixed dofs
        0), ``residuals`` (n,) (``||K phi - omega^2 M phi|| / ||K phi||``), ``effective_mass`` (n, 2) [kg]
        (x, y) and ``free_mass`` (x, y) [kg].
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
            (its modes are computed), or two frequencies ``(f1, f2)`` [Hz].
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
    if isinstance(frequencies, _core.Model):
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


def _mode_indices(m: Modes, k: Union[None, int, Sequence[int]]) -> List[int]:
    """The modes to draw: ``k`` None (the first :data:`DEFAULT_PANELS`), an int (mode ``k``) or a sequence."""
    n = len(m)
    wanted = list(range(min(n, DEFAULT_PANELS))) if k is None else [k] if isinstance(k, (int, np.integer)) else list(k)
    bad = [i for i in wanted if not isinstance(i, (int, np.integer)) or not 0 <= i < n]
    if not wanted or bad:
        raise InputError(f"plot_modes: k must name modes from 0 to {n - 1}, got {k!r}")
    return [int(i) for i in wanted]


def _draw_mode(ax: Any, model: Any, m: Modes, i: int, scale: Optional[float]) -> float:
    """Mode ``i`` drawn on ``ax`` as the deformed wall over its undeformed outline; returns the scale used."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    from .plot.panels import _draw_blocks, _wall_axes, _wall_height
    from .report import corner_motion

    rects = np.asarray(model.rects, dtype=np.float64)
    shape = np.asarray(m.shapes[i], dtype=np.float64)
    motion = corner_motion(rects, shape)
    peak = float(motion.max()) if len(rects) else 0.0
    if scale is None:
        scale = MODE_FRACTION * _wall_height(model) / peak if peak > 0 else 0.0
    _draw_blocks(ax, model, shape, float(scale), moving=motion > 0.25 * peak if peak > 0 else None)
    _wall_axes(ax, model)
    f = float(m.frequencies_hz[i])
    free = np.asarray(m.free_mass, dtype=np.float64)
    share = np.divide(np.asarray(m.effective_mass[i]), free, out=np.zeros(2), where=free > 0)
    period = f"T = {1.0 / f:.4g} s" if f > 0 else "rigid-body mode"
    ax.set_title(f"mode {i + 1}: f = {f:.4g} Hz, {period}\neffective mass x {share[0]:.1%}, y {share[1]:.1%}", fontsize=10)
    handles = [
        Patch(facecolor="#f4a259", edgecolor="#5a4a3a", label=f"mode {i + 1}, {f:.4g} Hz (moving most)"),
        Patch(facecolor="#efe3c8", edgecolor="#5a4a3a", label="moving less"),
        Line2D([], [], color="#404040", linewidth=0.8, linestyle="--", label="undeformed"),
    ]
    # under the panel: in a row below a wide wall, stacked below a narrow one
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    columns = 3 if (x1 - x0) > 1.2 * (y1 - y0) else 1
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=columns, fontsize=7, frameon=False)
    return float(scale)


def plot_modes(
    model: Any,
    modes: Modes,
    k: Union[None, int, Sequence[int]] = None,
    ax: Any = None,
    scale: Optional[float] = None,
    path: Optional[Union[str, "os.PathLike[str]"]] = None,
    dpi: int = 150,
) -> Any:
    """Draw mode shapes as deformed walls: each mode's blocks moved along its shape, over the dashed outline.

    Args:
        model: the :class:`masonry_dem.Model` of the modes.
        modes: its :class:`Modes` (:func:`modes`).
        k: which modes (0-based): an index, a sequence of them, or None for the first four.
        ax: a matplotlib ``Axes`` to draw one mode on (``k`` an index, default 0); None makes a figure with a
            panel per mode.
        scale: the magnification of the mass-normalized shapes [-]; None draws each mode's largest corner
            displacement as 8% of the wall height.
        path: output file (PNG) of the figure (not with ``ax``), written with the Agg canvas; without it the
            figure is made through pyplot.
        dpi: resolution of the PNG.
    Returns:
        The figure (of ``ax`` when given). Each panel's title gives the mode's frequency [Hz], its period [s]
        and its effective masses along x and y (fractions of the free mass); its legend the frequency again.
    """
    if ax is not None:
        if path is not None:
            raise InputError("plot_modes: give either ax (draw on it) or path (write a figure), not both")
        index = _mode_indices(modes, 0 if k is None else k)
        if len(index) != 1:
            raise InputError(f"plot_modes: one mode can be drawn on an ax, got k = {k!r}")
        _draw_mode(ax, model, modes, index[0], scale)
        return ax.figure
    from .plot.figures import _aspect, _finish, _new_figure

    index = _mode_indices(modes, k)
    aspect = _aspect(model)
    columns = min(len(index), 2 if aspect > 1.2 else 4)
    rows = math.ceil(len(index) / columns)
    cell_w = 6.0 if aspect > 1.2 else 3.6
    cell_h = float(np.clip(cell_w / aspect + 1.2, 3.0, 8.0))
    fig = _new_figure((columns * cell_w + 0.4, rows * cell_h + 0.8), path is not None)
    for n, i in enumerate(index):
        _draw_mode(fig.add_subplot(rows, columns, n + 1), model, modes, i, scale)
    walls = int(model.n_blocks)
    heading = f"Natural modes of {walls} block{'s' if walls != 1 else ''} (elastic joints; shapes magnified)"
    return _finish(fig, heading, path, dpi)
