"""What every figure of the package shares, in both dimensions (:mod:`.figures` in the plane,
:mod:`masonry_dem.space.plot` in 3D, :mod:`.modes`, the study's summary): a new figure on the Agg canvas for a file
or through pyplot, its heading, and its file: :func:`figure_path` and :func:`save_figure` (atomically,
:mod:`masonry_dem.atomic`).
"""

from __future__ import annotations

import os
from typing import Optional, Tuple, Union

from matplotlib.figure import Figure

from .._core import InputError
from ..atomic import atomic_file

__all__ = ["figure_path", "save_figure"]


def _finish(fig: Figure, heading: str, path: Optional[Union[str, "os.PathLike[str]"]], dpi: int,
            fontsize: float = 13) -> Figure:
    """Give ``fig`` its heading, and write it to ``path`` if given."""
    fig.suptitle(heading, fontsize=fontsize)
    if path is not None:
        save_figure(fig, path, dpi=dpi)
    return fig


def figure_path(path: Union[str, "os.PathLike[str]"]) -> "os.PathLike[str]":
    """The file a figure given ``path`` is written to: ``path`` itself when it has a suffix (its format,
    e.g. ".png", ".pdf", ".svg"), else ``path`` + "." + rcParams["savefig.format"] (".png" by default), as
    matplotlib's ``savefig`` does. A suffix that is not a format matplotlib can write is an InputError."""
    from pathlib import Path

    import matplotlib
    from matplotlib.backend_bases import FigureCanvasBase

    p = Path(path)
    if not p.suffix:
        return p.with_name(p.name + "." + str(matplotlib.rcParams["savefig.format"]).lower())
    fmt = p.suffix[1:].lower()
    supported = FigureCanvasBase.get_supported_filetypes()
    if fmt not in supported:
        raise InputError(
            f"cannot write the figure {path}: unknown format {p.suffix!r} (use one of "
            + ", ".join("." + k for k in sorted(supported))
            + ")"
        )
    return p


def save_figure(fig: Figure, path: Union[str, "os.PathLike[str]"], dpi: int = 150) -> "os.PathLike[str]":
    """Write ``fig`` to :func:`figure_path` (``path``) atomically (a temporary file in its folder, then
    renamed; a target that is not a regular file is refused); return the file written."""
    target = figure_path(path)
    fmt = os.path.splitext(os.fspath(target))[1][1:].lower()
    with atomic_file(target, "wb") as f:
        fig.savefig(f, format=fmt, dpi=dpi)
    return target


def _new_figure(size: Tuple[float, float], to_file: bool) -> Figure:
    """A figure with constrained layout: on the Agg canvas for a file (pyplot's state untouched), else
    through pyplot (for ``plt.show()`` or a notebook)."""
    if to_file:
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        fig = Figure(figsize=size, layout="constrained")
        FigureCanvasAgg(fig)
        return fig
    import matplotlib.pyplot as plt

    return plt.figure(figsize=size, layout="constrained")
