"""Running a study on Dask (``dask.distributed``): :func:`run_study`.

The analyses go to the workers in chunks, as tasks that carry the study's case data (plain data; each
worker builds its models itself). The first tasks hold one analysis each; later ones are sized from the
analyses' measured time to about :data:`TASK_SECONDS` of work, so that the scheduling overhead stays a small
fraction of it whatever an analysis costs, and smaller towards the end (at most the analyses left divided by
:data:`TAIL_SPLIT` times the workers), so that the workers finish together; :data:`IN_FLIGHT` tasks per worker
are queued. Each row is
written as soon as its chunk comes back (:class:`~masonry_dem.study.store.ResultStore`).

Failures: an analysis that raises becomes a row with status "error" in the worker; a task whose worker
died (killed, out of memory) is run again by Dask (``distributed.scheduler.allowed-failures`` times); a
chunk that kept killing its workers is split into single analyses; one that still does is run again alone on
the cluster (a worker's death takes the analyses beside it too), and if it kills its worker then, it gets its
row with status "lost". Ctrl-C (KeyboardInterrupt in this process) cancels the tasks, writes every row
that came back and raises KeyboardInterrupt again, its ``results`` the rows written: resume the study to
finish it.
"""

from __future__ import annotations

import contextlib
import itertools
import logging
import math
import os
import signal
from typing import Any, Callable, Dict, Iterable, Iterator, List, Optional, Sequence, Tuple

import pandas as pd

from .._core import MasonryError
from .model import Item, Study
from .store import PathLike, ResultStore
from .worker import FAILED_STATUSES, failed_row, run_chunk

#: The work a task is sized to hold, from the analyses' measured time [s].
TASK_SECONDS = 1.0
#: The most analyses in one task (chunk), and the tasks queued per worker.
MAX_CHUNK = 1000
IN_FLIGHT = 2
#: Towards the end a chunk holds at most the analyses left / (TAIL_SPLIT x workers).
TAIL_SPLIT = 2
#: How long to wait for a scheduler given by address [s].
CONNECT_TIMEOUT = 30

#: A study's progress callback: ``progress(done, failed, total)``, called as rows come back.
Progress = Callable[[int, int, int], None]


def local_cluster(workers: Optional[int] = None) -> Any:
    """A ``LocalCluster`` of ``workers`` processes (default: one per core), one thread each, without the
    dashboard, without Dask's MALLOC_TRIM_THRESHOLD_ nor its profiler. Its processes ignore Ctrl-C (SIGINT,
    which a terminal sends to every process of the command): this process stops the study and closes them,
    without a traceback from each."""
    import dask
    from distributed import LocalCluster

    n = workers or os.cpu_count() or 1
    # Dask sets MALLOC_TRIM_THRESHOLD_ in the processes it starts, to give memory back to the system at once:
    # the solvers, which allocate much, run 6 to 10% slower so (benches/study_scaling.py); left out here
    environ = dict(dask.config.get("distributed.nanny.pre-spawn-environ", {}))
    environ.pop("MALLOC_TRIM_THRESHOLD_", None)
    settings = {
        "distributed.nanny.pre-spawn-environ": environ,
        # the workers' sampling profiler (every 10 ms) and the event loops' 20 ms watch cost the analyses 2%
        "distributed.worker.profile.enabled": False,
        "distributed.admin.tick.interval": "500ms",
    }
    # SIGINT ignored: inherited by the processes started now, and by those they start later
    with _sigint_ignored(), dask.config.set(settings):
        return LocalCluster(
            n_workers=n,
            threads_per_worker=1,
            processes=True,
            dashboard_address=":0",  # no dashboard, and its server on a free port: never Dask's 8787
            scheduler_kwargs={"dashboard": False},
            silence_logs=logging.ERROR,
        )


@contextlib.contextmanager
def _sigint_ignored() -> Iterator[None]:
    """SIGINT ignored meanwhile (in the main thread; elsewhere nothing changes)."""
    try:
        previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    except ValueError:  # not the main thread
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


@contextlib.contextmanager
def connect(scheduler: Any = None, workers: Optional[int] = None) -> Iterator[Any]:
    """A Dask ``Client``: ``scheduler`` itself when it is one; connected to the scheduler at that address
    ("tcp://host:8786"); else on a :func:`local_cluster` of ``workers`` processes, closed afterwards."""
    from distributed import Client

    if scheduler is not None and not isinstance(scheduler, str):
        yield scheduler
        return
    if scheduler is not None:
        try:
            client = Client(scheduler, timeout=CONNECT_TIMEOUT)
        except (OSError, TimeoutError) as exc:
            raise MasonryError(f"cannot reach the Dask scheduler at {scheduler}: {exc}") from None
        with contextlib.closing(client):
            yield client
        return
    cluster = local_cluster(workers)
    with contextlib.closing(cluster), Client(cluster) as client:
        yield client


class _Chunks:
    """The ``count`` analyses left (an iterator: a study of millions is never listed), handed out in chunks
    sized from their measured time (or of a fixed size), and smaller towards the end, so that no worker is
    left with a long chunk while the others wait."""

    def __init__(self, items: Iterable[Item], count: int, fixed: int = 0) -> None:
        self.items: Iterator[Item] = iter(items)
        self.count = count
        self.fixed = fixed
        self.seconds = 0.0
        self.measured = 0

    @property
    def left(self) -> bool:
        return self.count > 0

    def learn(self, rows: Sequence[Dict[str, Any]]) -> None:
        for row in rows:
            if math.isfinite(row["task_s"]):
                self.seconds += row["task_s"]
                self.measured += 1

    def size(self, workers: int) -> int:
        if self.fixed:
            return self.fixed
        if not self.measured:
            return 1
        mean = max(self.seconds / self.measured, 1e-6)
        timed = min(MAX_CHUNK, int(TASK_SECONDS / mean))
        return max(1, min(timed, math.ceil(self.count / (TAIL_SPLIT * workers))))

    def take(self, workers: int) -> List[Item]:
        chunk = list(itertools.islice(self.items, self.size(workers)))
        self.count = self.count - len(chunk) if chunk else 0
        return chunk


def _workers(client: Any) -> int:
    try:
        return max(1, len(client.scheduler_info().get("workers", {})))
    except Exception:  # a scheduler that does not answer now: one
        return 1


def _rows(future: Any, study: Study, items: Sequence[Item], alone: bool) -> Optional[List[Dict[str, Any]]]:
    """The rows of a finished task; None for one whose workers kept dying while other tasks ran (to be run
    again: split into single analyses, each alone on the cluster at last). Only an analysis that killed its
    worker while nothing else ran (``alone``) is the culprit: its row has status "lost"."""
    from distributed import KilledWorker

    try:
        return list(future.result())
    except KilledWorker as exc:
        if len(items) > 1 or not alone:
            return None
        return [failed_row(study, items[0], "lost", f"its worker died each time it ran it ({exc})")]
    except Exception as exc:  # the task itself failed (it catches the analyses' errors): every row says why
        return [failed_row(study, item, "error", f"{type(exc).__name__}: {exc}") for item in items]


def _compute(
    client: Any, study: Study, chunks: _Chunks, store: ResultStore, on_rows: Callable[[List[Dict[str, Any]]], None]
) -> None:
    """Run the chunks on ``client``, keeping :data:`IN_FLIGHT` tasks per worker, until none is left.

    A task whose workers kept dying is split into single analyses; a single analysis that dies with other
    tasks around (the worker's death kills them all: a bystander cannot be told from the culprit) is a
    suspect, run again once nothing else runs, one at a time."""
    from distributed import as_completed

    running: Dict[Any, Tuple[List[Item], bool]] = {}
    suspects: List[Item] = []
    queue = as_completed()

    def submit(items: List[Item], alone: bool = False) -> None:
        future = client.submit(run_chunk, study, items, pure=False, retries=1)
        running[future] = (items, alone)
        queue.add(future)

    def refill() -> None:
        if suspects:
            if not running:
                submit([suspects.pop(0)], alone=True)
            return
        workers = _workers(client)
        while chunks.left and len(running) < IN_FLIGHT * workers:
            items = chunks.take(workers)
            if items:
                submit(items)

    refill()
    try:
        for future in queue:
            items, alone = running.pop(future)
            rows = _rows(future, study, items, alone)
            if rows is None:
                if len(items) > 1:
                    for item in items:
                        submit([item])
                else:
                    suspects.extend(items)
                refill()
                continue
            chunks.learn(rows)
            store.add(rows)
            on_rows(rows)
            refill()
    except BaseException:
        client.cancel(list(running), force=True)
        raise


def run_study(
    study: Study,
    out: Optional[PathLike] = None,
    *,
    csv: Optional[PathLike] = None,
    resume: bool = False,
    scheduler: Any = None,
    workers: Optional[int] = None,
    chunk: Optional[int] = None,
    progress: Optional[Progress] = None,
) -> pd.DataFrame:
    """Run every analysis of ``study`` on Dask; return the rows, one per analysis, sorted by row.

    out: the results file (Parquet), appended as analyses finish; None keeps them in memory only.
    csv: also write the table as CSV at the end. resume: start from the rows already in ``out`` (of this
    study: its fingerprint is checked) and compute only the others; without it an existing ``out`` is
    refused. scheduler: None for a ``LocalCluster`` of ``workers`` processes (default: one per core), one
    thread each; a scheduler's address ("tcp://host:8786"); or a ``distributed.Client``. chunk: analyses per
    task (default: the study's ``chunk``, else sized automatically). progress: ``progress(done, failed,
    total)`` once at the start (done: the rows resumed) and after each task that comes back; ``failed``
    counts the rows of this run whose status is in FAILED_STATUSES. An exception it raises stops the study
    as Ctrl-C does.

    Raises KeyboardInterrupt (Ctrl-C) with the rows written as its ``results`` attribute, after writing them;
    InputError for a results file that cannot be written or holds another study's rows.
    """
    store = ResultStore(study, out, csv=csv, resume=resume)
    total = study.size
    counts = {"done": len(store.finished), "failed": 0}

    def on_rows(rows: List[Dict[str, Any]]) -> None:
        counts["done"] += len(rows)
        counts["failed"] += sum(1 for row in rows if row["status"] in FAILED_STATUSES)
        if progress is not None:
            progress(counts["done"], counts["failed"], total)

    try:
        if progress is not None:
            progress(counts["done"], counts["failed"], total)
        if counts["done"] < total:
            todo = (item for item in study.items() if item.row not in store.finished)
            chunks = _Chunks(todo, total - counts["done"], fixed=chunk if chunk is not None else study.chunk)
            with connect(scheduler, workers) as client:
                _compute(client, study, chunks, store, on_rows)
    except BaseException as exc:  # Ctrl-C, or any error: keep every row that came back
        written = store.finish()
        if isinstance(exc, KeyboardInterrupt):
            exc.results = written  # type: ignore[attr-defined]
        raise
    return store.finish()
