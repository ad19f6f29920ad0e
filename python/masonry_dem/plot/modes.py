"""The figure of a modal analysis (:mod:`masonry_dem.modal`): :func:`plot_modes` draws mode shapes as deformed walls,
a panel per mode (matplotlib, imported when a figure is drawn). ``masonry_dem.plot_modes`` and
``masonry_dem.modal.plot_modes`` are this function.
"""

from __future__ import annotations

import math
import os
from typing import Any, List, Optional, Sequence, Union

import numpy as np

from .._core import InputError, Modes
from .._shapes import shapes
from ..response import wall_height

__all__ = ["plot_modes"]

#: The largest corner displacement of a drawn mode shape, as a fraction of the wall height (default scale).
MODE_FRACTION = 0.08

#: The most modes :func:`plot_modes` draws when ``k`` is not given.
DEFAULT_PANELS = 4


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

    from .panels import _draw_blocks, _wall_axes

    shape = np.asarray(m.shapes[i], dtype=np.float64)
    motion = shapes(model).vertex_motion(shape)
    peak = float(motion.max()) if len(motion) else 0.0
    if scale is None:
        scale = MODE_FRACTION * wall_height(model) / peak if peak > 0 else 0.0
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
        model: the :class:`masonry_dem.Model` of the modes, or a :class:`masonry_dem.Model3D` (a 3D panel per mode,
            :func:`masonry_dem.space.plot.modes_figure_3d`; ``ax`` then a 3D axes).
        modes: its :class:`masonry_dem.Modes` (:func:`masonry_dem.modes`).
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
    three = int(getattr(model, "dimension", 2)) == 3
    if three != (int(getattr(modes, "dimension", 2)) == 3):
        raise InputError("plot_modes: the modes are not of this model (one is 3D, the other in the plane)")
    if ax is not None:
        if path is not None:
            raise InputError("plot_modes: give either ax (draw on it) or path (write a figure), not both")
        index = _mode_indices(modes, 0 if k is None else k)
        if len(index) != 1:
            raise InputError(f"plot_modes: one mode can be drawn on an ax, got k = {k!r}")
        if three:
            from ..space.plot import plot_mode_3d

            plot_mode_3d(ax, model, modes, index[0], scale)
        else:
            _draw_mode(ax, model, modes, index[0], scale)
        return ax.figure
    if three:
        from ..space.plot import modes_figure_3d

        return modes_figure_3d(model, modes, _mode_indices(modes, k), scale, path, dpi)
    from .canvas import _finish, _new_figure
    from .figures import _aspect

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
