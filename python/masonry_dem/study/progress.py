"""The progress bar of a study: analyses done out of the total, how many failed, and the rate; a
:data:`masonry_dem.study.runner.Progress` callback (``bar(done, failed, total)``). tqdm draws it on
stderr; without tqdm, or when it is not wanted, :func:`study_bar` gives a callback that draws nothing.
"""

from __future__ import annotations

from typing import IO, Any, Optional

from ..progress import NullProgress


class StudyBar:
    """A tqdm bar fed by ``bar(done, failed, total)``. The first call gives the rows already done (a
    resumed study), which the rate does not count."""

    def __init__(self, label: str, total: int, file: Optional[IO[str]] = None) -> None:
        from tqdm import tqdm  # lazily: tqdm is optional

        self._first = True
        self._bar: Any = tqdm(
            total=total,
            desc=label,
            unit=" analyses",
            file=file,
            dynamic_ncols=True,
            mininterval=0.2,
            leave=True,
            postfix="failed 0",
        )

    def __call__(self, done: int, failed: int, total: int) -> None:
        bar = self._bar
        if bar is None:
            return
        try:
            bar.set_postfix_str(f"failed {failed:,}", refresh=False)
            if self._first:  # the rows of a resumed study: shown, not counted in the rate
                self._first = False
                bar.initial = bar.n = bar.last_print_n = done
                bar.refresh()
            else:
                bar.update(done - bar.n)
        except Exception:  # never let drawing stop a study
            self._bar = None

    def close(self) -> None:
        bar, self._bar = self._bar, None
        if bar is not None:
            bar.close()

    def __enter__(self) -> "StudyBar":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()


class NoBar(NullProgress):
    """A study progress callback that draws nothing (falsy, a context manager)."""

    def __call__(self, done: int, failed: int, total: int) -> None:  # type: ignore[override]
        return None


def study_bar(label: str, total: int, enabled: bool = True) -> Any:
    """A :class:`StudyBar`, or a :class:`NoBar` when not ``enabled`` or tqdm is missing."""
    if not enabled:
        return NoBar()
    try:
        return StudyBar(label, total)
    except ImportError:
        return NoBar()
