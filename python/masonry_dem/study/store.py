"""The results of a study on disk: a Parquet file, appended as analyses finish, and read back to resume.

While a study runs, finished rows are written every few seconds as part files in the folder ``OUT.parts``
beside ``OUT`` (each written atomically: a part is whole or absent, whatever stops the study); at the end,
and when the study is stopped (Ctrl-C), the parts and the previous ``OUT`` are joined into ``OUT`` (one row
per analysis, sorted by row, written atomically) and the parts are removed. :func:`read_results` reads
``OUT`` and any parts left by a study that was killed; a resumed study starts from them and computes only
the rows that are missing. The file's metadata holds the study's title and fingerprint
(:meth:`Study.fingerprint`): the rows of another study are never mixed in.
"""

from __future__ import annotations

import json
import os
import time
from pathlib import Path
from typing import Any, Dict, Iterable, List, Optional, Sequence, Set, Tuple, Union

import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from .._core import InputError
from ..atomic import atomic_path, check_target, check_writable
from .model import Study
from .worker import ASSESSMENT_COLUMNS, OUTCOME_COLUMNS

PathLike = Union[str, "os.PathLike[str]"]

#: The key of the study's description in the Parquet file's metadata.
METADATA_KEY = b"masonry_dem.study"
#: Finished rows are written at least this often [s] while a study runs.
FLUSH_SECONDS = 2.0
_ARROW_TYPES = {"int": pa.int64(), "float": pa.float64(), "str": pa.string()}


def columns(study: Study) -> List[Tuple[str, str]]:
    """The columns of the study's table with their types: row, method, direction, the varied parameters
    (the direction aside), sample, seed, then the outcome (:data:`masonry_dem.study.worker.OUTCOME_COLUMNS`) and,
    when the base case has an [assessment], the seismic check's (:data:`masonry_dem.study.worker.ASSESSMENT_COLUMNS`)."""
    out = [("row", "int"), ("method", "str"), ("direction", "str")]
    for v in study.variations:
        if v.name == "direction":
            continue
        values = v.values or ()
        kind = "int" if v.name == "courses" else "str" if any(isinstance(x, str) for x in values) else "float"
        out.append((v.name, kind))
    checks = list(ASSESSMENT_COLUMNS) if study.assesses else []
    return out + [("sample", "int"), ("seed", "int")] + list(OUTCOME_COLUMNS) + checks


def schema(study: Study) -> pa.Schema:
    """The Arrow schema of the table, its metadata naming the study."""
    described = {"format": 1, "title": study.title, "fingerprint": study.fingerprint(), "analyses": study.size}
    fields = [pa.field(name, _ARROW_TYPES[kind]) for name, kind in columns(study)]
    return pa.schema(fields, metadata={METADATA_KEY: json.dumps(described).encode()})


def parts_folder(path: PathLike) -> Path:
    """The folder of the part files of ``path``."""
    return Path(os.fspath(path) + ".parts")


def study_metadata(table_schema: pa.Schema) -> Optional[Dict[str, Any]]:
    """The study's description in a file's schema (title, fingerprint, analyses), or None."""
    raw = (table_schema.metadata or {}).get(METADATA_KEY)
    return None if raw is None else dict(json.loads(raw))


def _tables(path: Path) -> List[Tuple[Path, pa.Table]]:
    """The tables of ``path`` and of its parts, those that exist."""
    files = [path] if path.is_file() else []
    folder = parts_folder(path)
    if folder.is_dir():
        files += sorted(p for p in folder.glob("part-*.parquet") if p.is_file())
    return [(f, _read(f)) for f in files]


def _read(file: Path) -> pa.Table:
    """The table of Parquet file ``file``; InputError naming it when it is damaged or not Parquet (nothing
    is changed: every file stays as it is, with the rows that can still be read)."""
    try:
        return pq.read_table(file)
    except (pa.ArrowException, OSError, ValueError) as exc:
        if isinstance(exc, OSError) and not isinstance(exc, pa.ArrowException) and exc.errno is not None:
            raise  # it cannot be read at all (permissions): the OSError names it
        reason = " ".join(str(exc).split())[:200]
        raise InputError(
            f"{file}: not a Parquet file that can be read (damaged, or not written by masonry-dem: {reason}); "
            f"nothing was changed: move it away to start again, or give another results file (--out)"
        ) from None



def _joined(tables: Sequence[pa.Table], target: Optional[pa.Schema] = None) -> pd.DataFrame:
    """One row per analysis (the first written of any duplicates), sorted by row."""
    if not tables:
        return pd.DataFrame({name: pd.Series(dtype="object") for name in (target.names if target else ())})
    table = pa.concat_tables([t.cast(target) if target is not None else t for t in tables])
    frame = table.to_pandas()
    return frame.drop_duplicates("row", keep="first").sort_values("row", kind="stable").reset_index(drop=True)


def read_results(path: PathLike) -> pd.DataFrame:
    """The rows of a study's results file ``path`` (Parquet), with those of the parts left by a study that
    was stopped or killed: one row per analysis, sorted by row. ``attrs`` holds the study's title,
    fingerprint and number of analyses."""
    tables = _tables(Path(path))
    if not tables:
        raise FileNotFoundError(f"no results at {path} (nor {parts_folder(path)})")
    frame = _joined([t for _, t in tables], tables[0][1].schema)
    frame.attrs.update(study_metadata(tables[0][1].schema) or {})
    return frame


class ResultStore:
    """The rows of a running study, in memory and (when ``path`` is given) on disk.

    ``resume``: start from the rows already in ``path`` (and its parts), which must be of this study;
    without it, an existing ``path`` is refused. ``csv``: also write the table as CSV at the end.
    """

    def __init__(
        self, study: Study, path: Optional[PathLike] = None, csv: Optional[PathLike] = None, resume: bool = False
    ):
        self.study, self.path, self.csv = study, None if path is None else Path(path), csv
        self.schema = schema(study)
        self.tables: List[pa.Table] = []
        self.buffer: List[Dict[str, Any]] = []
        self.parts: List[Path] = []
        self.written = time.monotonic()
        self.finished: Set[int] = set()
        for target in [p for p in (path, csv) if p is not None]:
            check_target(target, study.inputs)
            check_writable(target)
        if self.path is not None:
            self._open(resume)

    def _open(self, resume: bool) -> None:
        assert self.path is not None
        found = _tables(self.path)
        if found and not resume:
            raise InputError(
                f"{self.path} already holds results (or {parts_folder(self.path)} does): resume them "
                f"(--resume, resume=True) or remove them"
            )
        fingerprint = self.study.fingerprint()
        for file, table in found:
            try:
                meta = study_metadata(table.schema) or {}
            except (ValueError, TypeError):  # metadata that is not the study's JSON
                meta = {}
            if not meta:
                raise InputError(
                    f"{file} is not the results file of a masonry-dem study (its Parquet schema has no study "
                    f"description): nothing is resumed and it is left as it is; give another results file (--out)"
                )
            if meta.get("fingerprint") != fingerprint:
                raise InputError(
                    f"{file} holds the results of another study ({meta.get('title', 'untitled')!r}, fingerprint "
                    f"{meta.get('fingerprint')}; this one is {fingerprint}): nothing is resumed"
                )
            self.tables.append(table.cast(self.schema))
            if file.parent == parts_folder(self.path):
                self.parts.append(file)
        for table in self.tables:
            self.finished.update(table.column("row").to_pylist())

    def add(self, rows: Iterable[Dict[str, Any]]) -> None:
        """Keep finished rows; write them as a part when the last write is :data:`FLUSH_SECONDS` old."""
        for row in rows:
            if row["row"] not in self.finished:
                self.finished.add(row["row"])
                self.buffer.append(row)
        if time.monotonic() - self.written >= FLUSH_SECONDS:
            self.flush()

    def flush(self) -> None:
        """Write the rows kept since the last write as a part file (atomically)."""
        self.written = time.monotonic()
        if not self.buffer:
            return
        table = pa.Table.from_pylist(self.buffer, schema=self.schema)
        self.buffer = []
        self.tables.append(table)
        if self.path is None:
            return
        folder = parts_folder(self.path)
        folder.mkdir(parents=True, exist_ok=True)
        part = folder / f"part-{time.time_ns():020d}-{os.getpid()}.parquet"
        atomic_path(part, lambda tmp: pq.write_table(table, tmp))
        self.parts.append(part)

    def frame(self) -> pd.DataFrame:
        """The rows so far, one per analysis, sorted by row."""
        self.flush()
        frame = _joined(self.tables, self.schema)
        frame.attrs.update(study_metadata(self.schema) or {})
        return frame

    def finish(self) -> pd.DataFrame:
        """Join everything into the results file (and the CSV), remove the parts; the rows as a DataFrame."""
        frame = self.frame()
        if self.path is not None:
            table = pa.Table.from_pandas(frame, schema=self.schema, preserve_index=False)
            atomic_path(self.path, lambda tmp: pq.write_table(table, tmp), inputs=self.study.inputs)
            for part in self.parts:
                part.unlink(missing_ok=True)
            self.parts = []
            folder = parts_folder(self.path)
            if folder.is_dir() and not any(folder.iterdir()):
                folder.rmdir()
        if self.csv is not None:
            atomic_path(self.csv, lambda tmp: frame.to_csv(tmp, index=False), inputs=self.study.inputs)
        return frame
