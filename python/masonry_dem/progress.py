"""A progress bar for long analyses, fed by the solvers' ``progress`` callback.

The solvers (``Model.solve_static``, ``Model.solve_dynamic``, ``Model.simulate``, ``Model.solve_limit``) call
``progress(step, multiplier, displacement, fraction)`` now and then: after each converged step (static),
every few thousand time steps (explicit), after each interior-point iteration (limit analysis: the step is
the iteration, displacement and fraction are NaN; the bar counts "iterations" with ``unit="iterations"``). :class:`ProgressBar` is such a callable; it draws a tqdm bar
on a stream (stderr by default):

>>> from masonry_dem.progress import progress_bar
>>> with progress_bar("dynamic") as bar:                      # doctest: +SKIP
...     results = model.solve_dynamic(progress=bar)

It shows the load multiplier and the number of steps, plus a percentage (and the remaining time) once the
solver reports a fraction done (displacement control, time histories; NaN under load control, whose end
is not known in advance). tqdm is imported when a bar is made; without it :func:`progress_bar` gives a
:class:`NullProgress`, which draws nothing.

The call is cheap: it stores the four numbers and redraws at most every ``interval`` seconds, so
a solver may call it as often as it likes. It never raises into the solver: a bar that fails to draw
turns itself off.
"""

from __future__ import annotations

import math
import sys
import time
from typing import IO, Any, Optional, Tuple, Union

from .report import format_multiplier, multiplier_symbol

__all__ = ["ProgressBar", "NullProgress", "progress_bar", "progress_text"]

#: Redraw at most this often [s].
DEFAULT_INTERVAL = 0.1
#: Resolution of the percentage bar (units of the tqdm counter for a fraction of 1).
_TICKS = 1000
_FORMAT_OPEN = "{desc} [{elapsed}]"
_FORMAT_FRACTION = "{desc} {percentage:3.0f}%|{bar}| [{elapsed}<{remaining}]"


def progress_text(
    step: int,
    multiplier: float,
    displacement: float,
    fraction: float,
    live: str = "horizontal_weight",
    unit: str = "steps",
    time_history: bool = False,
) -> str:
    """The numbers shown by the bar: ``λ = 0.6425, 12,345 steps``; the control displacement in mm is
    added when ``fraction`` is known (displacement control). With ``live = "top_horizontal"`` the
    multiplier is a force in N, shown as ``H = 56.9 kN``. ``unit``: the word after the count
    ("iterations" for a limit analysis). ``time_history``: the numbers of ``Model.simulate``, whose second
    is the time [s]: ``t = 1.234 s, 12,345 steps``."""
    if time_history:
        shown = f"{multiplier:.4g} s" if math.isfinite(multiplier) else "-"
        return f"t = {shown}, {int(step):,} {unit}"
    name = multiplier_symbol(live)
    lam = f"{name} = {format_multiplier(multiplier, live) if math.isfinite(multiplier) else '-'}"
    parts = [lam]
    if math.isfinite(fraction) and math.isfinite(displacement):
        mm = round(displacement * 1e3, 6) or 0.0  # no -0 nor 1e-20 for a displacement that is nil
        parts.append(f"u = {mm:.4g} mm")
    parts.append(f"{int(step):,} {unit}")
    return ", ".join(parts)


class NullProgress:
    """A progress callback that does nothing (no tqdm, or no bar wanted); a context manager too."""

    def __call__(self, step: int, multiplier: float, displacement: float, fraction: float) -> None:
        return None

    def close(self) -> None:
        return None

    def __enter__(self) -> "NullProgress":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def __bool__(self) -> bool:
        return False


class ProgressBar:
    """A tqdm progress bar as a solver ``progress`` callback.

    Args:
        label: the first word of the bar (e.g. the method, "static" or "dynamic").
        file: the stream to draw on (default: ``sys.stderr`` at creation).
        live: the live load of the model ("horizontal_weight" or "top_horizontal"), for the unit of
            the multiplier.
        interval: the bar is redrawn at most every ``interval`` seconds (default :data:`DEFAULT_INTERVAL`).
        leave: keep the last state of the bar on screen when closed (default: erase it).
        unit: the word after the count (default "steps"; "iterations" for a limit analysis).
        time_history: the callback of ``Model.simulate`` (its second number is the time [s], shown as such).

    Raises:
        ImportError: tqdm is not installed (use :func:`progress_bar` to fall back to no bar).
    """

    def __init__(
        self,
        label: str,
        file: Optional[IO[str]] = None,
        live: str = "horizontal_weight",
        interval: Optional[float] = None,
        leave: bool = False,
        unit: str = "steps",
        time_history: bool = False,
    ) -> None:
        from tqdm import tqdm  # lazily: tqdm is optional

        self.time_history = time_history
        self.label = label
        self.live = live
        self.unit = unit
        self.interval = DEFAULT_INTERVAL if interval is None else float(interval)
        self.calls = 0
        self.last: Optional[Tuple[int, float, float, float]] = None
        self._next = 0.0
        self._fraction_mode = False
        self._bar: Any = tqdm(
            total=None,
            desc=label,
            file=sys.stderr if file is None else file,
            leave=leave,
            bar_format=_FORMAT_OPEN,
            dynamic_ncols=True,
            mininterval=0.0,
            miniters=0,
        )

    def __call__(self, step: int, multiplier: float, displacement: float, fraction: float) -> None:
        """The solver's callback: store the numbers; redraw if ``interval`` has passed."""
        self.calls += 1
        self.last = (step, multiplier, displacement, fraction)
        now = time.monotonic()
        if now >= self._next:
            self._next = now + self.interval
            self._draw()

    def _draw(self) -> None:
        bar = self._bar
        if bar is None or self.last is None:
            return
        step, multiplier, displacement, fraction = self.last
        try:
            fraction = float(fraction)
            known = math.isfinite(fraction)
            if known != self._fraction_mode:  # the bar follows the latest report
                self._fraction_mode = known
                bar.total = _TICKS if known else None
                bar.bar_format = _FORMAT_FRACTION if known else _FORMAT_OPEN
            if known:
                bar.n = int(round(min(max(fraction, 0.0), 1.0) * _TICKS))
            text = progress_text(step, float(multiplier), float(displacement), fraction, self.live, self.unit,
                                 self.time_history)
            bar.set_description_str(f"{self.label}: {text}", refresh=False)
            bar.refresh()
        except Exception:  # never let a drawing problem reach the solver
            self._bar = None

    def close(self) -> None:
        """Draw the last numbers (if the bar is kept) and close the bar."""
        bar, self._bar = self._bar, None
        if bar is None:
            return
        try:
            if bar.leave:
                self._bar = bar
                self._draw()
                self._bar = None
            bar.close()
        except Exception:
            pass

    def __enter__(self) -> "ProgressBar":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()


def progress_bar(
    label: str,
    file: Optional[IO[str]] = None,
    live: str = "horizontal_weight",
    enabled: bool = True,
    leave: bool = False,
    unit: str = "steps",
    time_history: bool = False,
) -> Union[ProgressBar, NullProgress]:
    """A :class:`ProgressBar`, or a :class:`NullProgress` when ``enabled`` is false or tqdm is missing.

    Both are context managers and callables; a NullProgress is falsy, so
    ``solve(progress=bar or None)`` passes no callback at all when there is no bar.
    """
    if not enabled:
        return NullProgress()
    try:
        return ProgressBar(label, file=file, live=live, leave=leave, unit=unit, time_history=time_history)
    except ImportError:
        return NullProgress()
