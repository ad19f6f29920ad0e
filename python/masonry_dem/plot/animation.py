"""An animation of a time history (``Model.simulate``): the blocks moving over time, as a GIF or an MP4.

:func:`write_animation` draws the wall at a sequence of records, the blocks moved by their displacements
relative to the ground (the base stays put), the time in the title, and under the wall the drift of the control
block against time with a cursor at the frame's time. A GIF is written with matplotlib's PillowWriter (Pillow
comes with matplotlib); an MP4 with its FFMpegWriter, which needs the ``ffmpeg`` program. For ParaView, write the
VTK time series instead (:func:`masonry_dem.write_vtk` of the history: a ``.vtu`` per record and a ``.pvd``).
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any, Iterable, Optional, Union

import numpy as np

from .._core import InputError
from ..atomic import atomic_path, check_target
from .._shapes import fixed_blocks, shapes

__all__ = ["write_animation", "ANIMATION_FORMATS", "MAX_FRAMES", "animation_frames", "moved_extent"]

#: The formats :func:`write_animation` writes, by suffix.
ANIMATION_FORMATS = (".gif", ".mp4")

#: The most frames an animation has by default (``every`` left out): a longer history is sampled more coarsely.
MAX_FRAMES = 400

PathLike = Union[str, "os.PathLike[str]"]


def moved_extent(model: Any, disp: np.ndarray, scale: float = 1.0) -> tuple:
    """((x_lo, x_hi), (y_lo, y_hi)) [m] of the blocks (the base and the supports at rest) moved by ``scale`` *
    ``disp``, a (frames, n_all, 3) array of displacements (u1 [m], u2 [m], phi [rad]), over all the frames."""
    blocks = shapes(model)
    moved = blocks.moved(np.asarray(disp, dtype=np.float64), scale)  # (f, p, 2)
    at_rest = np.isin(blocks.owner, fixed_blocks(model))
    moved[:, at_rest] = blocks.points[at_rest]
    finite = moved[np.all(np.isfinite(moved), axis=-1)]
    if finite.size == 0:
        finite = blocks.points
    return (float(finite[:, 0].min()), float(finite[:, 0].max())), (float(finite[:, 1].min()), float(finite[:, 1].max()))


def animation_frames(
    times: np.ndarray, fps: float, every: Optional[int] = None, start: Optional[float] = None,
    stop: Optional[float] = None,
) -> np.ndarray:
    """The records an animation shows, those from ``start`` to ``stop`` [s] (default: all): every ``every``-th
    one when given; else about one per 1 / ``fps`` seconds of the history (real time), but at most
    :data:`MAX_FRAMES`. The last record of the span is always shown."""
    times = np.asarray(times, dtype=np.float64)
    keep = np.ones(len(times), dtype=bool)
    if start is not None:
        keep &= times >= start
    if stop is not None:
        keep &= times <= stop
    chosen = np.flatnonzero(keep)
    if len(chosen) == 0:
        return np.zeros(0, dtype=np.int64)
    return chosen[_frames(times[chosen], fps, every)]


def _frames(times: np.ndarray, fps: float, every: Optional[int]) -> np.ndarray:
    k = len(times)
    if every is None:
        span = float(times[-1] - times[0]) if k > 1 else 0.0
        interval = float(np.median(np.diff(times))) if k > 1 else 1.0
        wanted = min(MAX_FRAMES, max(2, int(math.ceil(span * fps)) + 1))
        every = max(1, int(round(span / max(wanted - 1, 1) / interval))) if interval > 0 else 1
        every = max(every, int(math.ceil(k / MAX_FRAMES)))
    frames = np.arange(0, k, every, dtype=np.int64)
    if frames[-1] != k - 1:
        frames = np.append(frames, k - 1)
    return frames


def check_animation_format(path: Union[str, "os.PathLike[str]"]) -> None:
    """Refuse, before any run, an animation file that cannot be written: a suffix other than those of
    :data:`ANIMATION_FORMATS`, or an MP4 without the ``ffmpeg`` program (InputError)."""
    from matplotlib import animation

    suffix = Path(path).suffix.lower()
    if suffix not in ANIMATION_FORMATS:
        raise InputError(f"cannot write the animation {path}: unknown format {Path(path).suffix!r}: expected a .gif "
                         "(or .mp4) file name")
    if suffix == ".mp4" and not animation.writers.is_available("ffmpeg"):
        raise InputError(f"cannot write the animation {path}: an MP4 needs ffmpeg, which is not installed "
                         "(write a .gif instead, or install ffmpeg)")


def write_animation(
    model: Any,
    history: Any,
    path: PathLike,
    fps: float = 25,
    scale: float = 1.0,
    every: Optional[int] = None,
    title: Optional[str] = None,
    dpi: int = 80,
    start: Optional[float] = None,
    stop: Optional[float] = None,
    inputs: Iterable[PathLike] = (),
) -> Path:
    """Write an animation of a time history: the blocks moving (relative to the ground, over their dashed
    outlines at rest), the time in the title, and the drift of the control block [%] against time under the
    wall, with a cursor. With the contact update, the contacts it created are drawn in red as they appear and
    vanish, and the title counts the contacts, the new ones and those dropped so far.

    Args:
        model: the :class:`masonry_dem.Model` simulated.
        history: its :class:`masonry_dem.TimeHistory` (displacements relative to the ground).
        path: the file: ``.gif`` (Pillow) or ``.mp4`` (ffmpeg, if installed; else an InputError says so).
        fps: frames per second of the animation.
        scale: the magnification of the displacements and rotations (1: true scale).
        every: show every ``every``-th record; default: about one frame per 1 / ``fps`` seconds of the
            history (the animation plays in real time), at most :data:`MAX_FRAMES` frames.
        title: the case title, before the time in the title of each frame.
        dpi: resolution [dots per inch] of the frames (the figure is 6.4 inches wide, 512 pixels at 80, or narrower
            for a tall wall; its height follows the wall's).
        start, stop: the span of the history shown [s] (default: all of it).
        inputs: files that must not be overwritten (the case file).
    Returns:
        The path written (atomically: a temporary file in its folder, then renamed).
    Raises:
        masonry_dem.InputError: another suffix, an MP4 without ffmpeg, bad ``fps`` / ``scale`` / ``every``, a
            target that is not a regular file, or an empty history.
    """
    from matplotlib import animation
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.collections import LineCollection, PolyCollection
    from matplotlib.figure import Figure
    from matplotlib.patches import Polygon

    from ..history import check_plane, contact_sets
    from ..response import drift
    from .panels import _wall_axes, _wall_limits

    check_plane(model, "write_animation")
    target = Path(path)
    check_animation_format(target)
    if isinstance(fps, bool) or not (isinstance(fps, (int, float)) and math.isfinite(fps) and fps > 0):
        raise InputError(f"write_animation: fps must be a number > 0, got {fps!r}")
    if isinstance(scale, bool) or not (isinstance(scale, (int, float)) and math.isfinite(scale) and scale >= 0):
        raise InputError(f"write_animation: scale must be a number >= 0, got {scale!r}")
    if every is not None and (isinstance(every, bool) or not isinstance(every, int) or every < 1):
        raise InputError(f"write_animation: every must be an integer >= 1, got {every!r}")
    inputs = list(inputs)
    check_target(target, inputs)

    times = np.asarray(history.times, dtype=np.float64).reshape(-1)
    frames = animation_frames(times, float(fps), every, start, stop)
    if len(frames) == 0:
        raise InputError("write_animation: no record to show" + (" between start and stop" if len(times) else
                                                                  " (the time history is empty)"))
    disp = np.asarray(history.displacements, dtype=np.float64)
    blocks = shapes(model)
    fixed = fixed_blocks(model)
    moving = np.array([i for i in range(len(blocks)) if i not in fixed], dtype=np.int64)
    colors = ["#7f7f7f" if i == model.top_index else "#efe3c8" for i in moving]

    # the wall panel's limits: the wall with room for the mechanism, and every block in view in every frame
    (xl, xh), (yl, yh) = _wall_limits(model)
    (x_lo, x_hi), (y_lo, y_hi) = moved_extent(model, disp[frames], scale)
    box = blocks.bounds
    pad = 0.03 * (box[:, 3].max() - box[:, 1].min())
    xlim = (min(xl, x_lo - pad), max(xh, x_hi + pad))
    ylim = (min(yl, y_lo - pad), max(yh, y_hi + pad))
    tall = float(np.clip((ylim[1] - ylim[0]) / (xlim[1] - xlim[0]), 0.3, 1.6))
    width = 6.4 if tall <= 1.0 else max(4.0, 6.4 / tall)  # a tall wall: a narrower figure
    fig = Figure(figsize=(width, width * tall + 2.4), layout="constrained")
    FigureCanvasAgg(fig)
    ax_wall, ax_drift = fig.subplots(2, 1, gridspec_kw={"height_ratios": [width * tall + 0.6, 1.8]})
    for i in fixed:
        ax_wall.add_patch(Polygon(blocks.polygon(i), closed=True, facecolor="#d9d9d9", edgecolor="#555555",
                                  hatch="///", linewidth=0.8, zorder=1))
    fills = PolyCollection([], facecolors=colors, edgecolors="#5a4a3a", linewidths=0.6, zorder=2)
    ax_wall.add_collection(fills)
    outlines = [blocks.polygon(i) for i in moving]
    ax_wall.add_collection(LineCollection([np.vstack([o, o[:1]]) for o in outlines], colors="#404040",
                                          linewidths=0.5, linestyles="--", zorder=3))
    # the contacts the update created, drawn as they appear and vanish (a run without searches: none)
    updated = history.contact_counts[0] > 0
    new_contacts = LineCollection([], colors="#d62728", linewidths=1.6, zorder=4)
    ax_wall.add_collection(new_contacts)
    _wall_axes(ax_wall, model)
    ax_wall.set_xlim(*xlim)
    ax_wall.set_ylim(*ylim)
    scale_note = "true scale" if scale == 1 else f"displacements ×{scale:g}"
    note = f"relative to the ground, {scale_note}; dashed: at rest"

    d = drift(model, history) * 100.0
    ax_drift.plot(times, d, color="#1f77b4", linewidth=1.0)
    ax_drift.axhline(0.0, color="#808080", linewidth=0.6)
    cursor = ax_drift.axvline(times[0], color="#d62728", linewidth=1.0)
    if frames[-1] > frames[0]:
        ax_drift.set_xlim(times[frames[0]], times[frames[-1]])  # the span shown
    ax_drift.set_xlabel("time [s]")
    ax_drift.set_ylabel("drift [%]")
    ax_drift.grid(True, linewidth=0.4, alpha=0.6)
    heading = f"{title} — " if title else ""

    def draw(k: int, contacts: Any) -> None:
        moved = blocks.polygons(blocks.moved(disp[k], scale))
        fills.set_verts([moved[i] for i in moving])
        cursor.set_xdata([times[k], times[k]])
        line = note
        if contacts is not None:
            new_contacts.set_segments(list(contacts.ends[contacts.created]))
            line += (f"; contacts: {len(contacts.ids)}, new (red): {int(contacts.created.sum())}, "
                     f"dropped: {contacts.dropped}")
        ax_wall.set_title(f"{heading}t = {times[k]:.2f} s\n{line}", fontsize=9)

    writer: Any
    if target.suffix.lower() == ".gif":
        writer = animation.PillowWriter(fps=fps)
    else:
        writer = animation.FFMpegWriter(fps=fps, codec="h264", extra_args=["-pix_fmt", "yuv420p"])

    def write(tmp: str) -> None:
        sets = contact_sets(model, history, [int(k) for k in frames], scale) if updated else None
        with writer.saving(fig, tmp, dpi):
            for k in frames:
                draw(int(k), next(sets) if sets is not None else None)
                writer.grab_frame()

    if str(target.parent):
        target.parent.mkdir(parents=True, exist_ok=True)
    return atomic_path(target, write, inputs=inputs)
