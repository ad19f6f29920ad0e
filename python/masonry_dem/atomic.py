"""Atomic output files: every file masonry-dem writes goes through :func:`atomic_file` or :func:`atomic_path`.

The content is written to a temporary file in the target's own folder (a short hidden name
``.md-KEY.PID.RANDOM.tmp``, KEY a digest of the target's name, so that it fits wherever the target's name
fits), flushed and ``fsync``-ed, then renamed over the target with :func:`os.replace`, so a reader (or a
crash, a kill, a full disk) never leaves a truncated or empty target: it holds either its previous content
or the new one. The temporary file is removed on any exception, Ctrl-C included; one left behind by a
killed process is removed by the next write to the same target. An error of the writing names the target,
not the temporary file.

A target that exists and is not a regular file (a folder, a device such as ``/dev/null``, a FIFO, a
socket) is refused with :class:`InputError` rather than replaced by a regular file, and so is a target
that is the same file as one of the ``inputs`` (the case file read). A symbolic link to a file is
followed: the file it points to is replaced and the link kept. A new file gets the usual permissions
(0666 less the umask); a replaced one keeps its permission bits.
"""

from __future__ import annotations

import contextlib
import errno
import hashlib
import os
import stat
import uuid
from pathlib import Path
from typing import IO, Any, Callable, Iterable, Iterator, Optional, Union

from ._core import InputError

__all__ = ["check_target", "check_writable", "atomic_file", "atomic_path", "write_text"]

PathLike = Union[str, "os.PathLike[str]"]


def _same_file(a: Path, b: PathLike) -> bool:
    try:
        return os.path.samefile(a, b)
    except OSError:  # one of them does not exist (or cannot be looked at): not the same file
        return False


def check_target(path: PathLike, inputs: Iterable[PathLike] = ()) -> Path:
    """The file to replace for output ``path``: ``path`` with symbolic links resolved.

    Raises :class:`InputError` (one line) when the target exists and is not a regular file, or is the
    same file as one of ``inputs``; OSError when it cannot be looked at (e.g. its folder is a file).
    Does not create anything.
    """
    given = Path(path)
    if str(path) == "":
        raise InputError("empty output file name")
    target = Path(os.path.realpath(given)) if given.is_symlink() else given
    try:
        st = os.stat(target)
    except FileNotFoundError:
        return target
    if stat.S_ISDIR(st.st_mode):
        raise InputError(f"cannot write {path}: it is a folder, not a file")
    if not stat.S_ISREG(st.st_mode):
        what = (
            "a FIFO" if stat.S_ISFIFO(st.st_mode)
            else "a device" if stat.S_ISCHR(st.st_mode) or stat.S_ISBLK(st.st_mode)
            else "a socket" if stat.S_ISSOCK(st.st_mode)
            else "not a regular file"
        )
        raise InputError(f"cannot write {path}: it is {what}, not a regular file (it is not replaced)")
    for source in inputs:
        if _same_file(target, source):
            raise InputError(f"cannot write {path}: it is the input file {source} (it would be overwritten)")
    return target


def prefix_problem(prefix: PathLike) -> Optional[str]:
    """Why ``prefix`` cannot name a set of files (``PREFIX-blocks.vtu`` ...): it is empty, or it is a folder (an
    existing one, or a name ending with a separator, whose files would be ``FOLDER/-blocks.vtu``); None when it
    can."""
    name = os.fspath(prefix)
    if name == "":
        return "an empty prefix"
    if name.endswith(("/", os.sep)) or os.path.isdir(name):
        return f"{name} is a folder: give a prefix such as {os.path.join(name, 'wall')}"
    return None


def check_writable(path: PathLike) -> None:
    """Refuse (:class:`InputError`, one line naming ``path``) an output whose folder cannot be written: the
    folder, or the nearest one that exists when it is to be created, is tried with a file created and
    removed at once. Meant to run before a long analysis, so that its results are not lost at the end."""
    folder = Path(os.path.abspath(os.fspath(path))).parent
    while not folder.exists() and folder != folder.parent:
        folder = folder.parent
    if not folder.is_dir():
        raise InputError(f"cannot write {path}: {folder} is not a folder")
    probe = folder / f".md-probe.{os.getpid()}.{uuid.uuid4().hex[:8]}"
    try:
        fd = os.open(probe, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    except OSError as exc:
        raise InputError(f"cannot write {path}: the folder {folder} cannot be written ({exc.strerror or exc})") from None
    os.close(fd)
    _remove(str(probe))


def _fsync_folder(folder: Path) -> None:
    """Make the rename durable (POSIX); silently nothing where folders cannot be opened."""
    if os.name != "posix":
        return
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def _key(target: Path) -> str:
    """The part of the temporary names that says which target they are for: a digest of its name."""
    return hashlib.sha256(target.name.encode("utf-8", "surrogateescape")).hexdigest()[:12]


def _alive(pid: int) -> bool:
    """Whether process ``pid`` runs (on this machine); True when that cannot be told."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OSError, OverflowError):
        return True
    return True


def _remove_leftovers(folder: Path, target: Path) -> None:
    """Remove the temporary files of earlier writes of ``target`` whose process has died (killed while
    writing): never one of a process that still runs."""
    prefix = f".md-{_key(target)}."
    try:
        names = [n for n in os.listdir(folder) if n.startswith(prefix)]
    except OSError:
        return
    for name in names:
        parts = name[len(prefix):].split(".")
        if len(parts) >= 3 and parts[0].isdigit() and not _alive(int(parts[0])):
            _remove(str(folder / name))


def _named(exc: OSError, path: PathLike) -> OSError:
    """``exc`` naming ``path`` (the target) instead of the temporary file."""
    if exc.errno is None:
        return exc
    return type(exc)(exc.errno, exc.strerror or os.strerror(exc.errno), os.fspath(path))


def _new_temp(target: Path, path: PathLike) -> "tuple[str, int]":
    """Create (O_EXCL) an empty temporary file next to ``target``; return its name and an open fd. An error
    names ``path``, the output asked for."""
    folder = target.parent if str(target.parent) else Path(".")
    suffix = target.suffix if len(target.suffix) <= 16 else ""
    _remove_leftovers(folder, target)
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0) | getattr(os, "O_NOFOLLOW", 0)
    for _ in range(100):
        tmp = str(folder / f".md-{_key(target)}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp{suffix}")
        try:
            return tmp, os.open(tmp, flags, 0o666)
        except FileExistsError:
            continue
        except OSError as exc:
            if exc.errno == errno.ENAMETOOLONG and suffix:
                suffix = ""  # a long name whose suffix does not fit either: the temporary one goes without
                continue
            raise _named(exc, path) from None
    raise FileExistsError(errno.EEXIST, "cannot create a temporary file", os.fspath(path))


def _finish(tmp: str, target: Path) -> None:
    """Keep the permission bits of a file being replaced, rename ``tmp`` onto ``target``, sync the folder."""
    try:
        mode = stat.S_IMODE(os.stat(target).st_mode)
    except OSError:
        mode = None
    if mode is not None:
        try:
            os.chmod(tmp, mode)
        except OSError:
            pass
    os.replace(tmp, target)
    _fsync_folder(target.parent if str(target.parent) else Path("."))


def _remove(tmp: str) -> None:
    try:
        os.unlink(tmp)
    except OSError:
        pass


@contextlib.contextmanager
def atomic_file(
    path: PathLike,
    mode: str = "w",
    encoding: Optional[str] = "utf-8",
    newline: Optional[str] = "\n",
    inputs: Iterable[PathLike] = (),
) -> Iterator[IO[Any]]:
    """Open a temporary file next to ``path`` for writing (``mode`` "w" or "wb"); on a normal exit of the
    ``with`` block flush, fsync and rename it onto ``path``; on an exception remove it (``path`` untouched).

    ``path`` is checked first (:func:`check_target`). The folder must exist.
    """
    if mode not in ("w", "wb"):
        raise ValueError(f"atomic_file: mode must be 'w' or 'wb', not {mode!r}")
    target = check_target(path, inputs)
    tmp, fd = _new_temp(target, path)
    try:
        try:
            if mode == "wb":
                f: IO[Any] = os.fdopen(fd, "wb")
            else:
                f = os.fdopen(fd, "w", encoding=encoding, newline=newline)
        except BaseException:
            os.close(fd)
            raise
        with f:
            yield f
            f.flush()
            os.fsync(f.fileno())
        check_target(path, inputs)  # nothing was put in its place meanwhile
        _finish(tmp, target)
    except OSError as exc:
        _remove(tmp)
        if exc.filename in (tmp, None):
            raise _named(exc, path) from None
        raise
    except BaseException:
        _remove(tmp)
        raise


def atomic_path(
    path: PathLike, write: Callable[[str], None], inputs: Iterable[PathLike] = ()
) -> Path:
    """Call ``write(tmp)`` with the name of a temporary file next to ``path`` (it exists, empty; ``write``
    may overwrite it, e.g. a library that only takes a file name), then fsync it and rename it onto
    ``path``; on an exception remove it. Returns ``path`` as a Path."""
    target = check_target(path, inputs)
    tmp, fd = _new_temp(target, path)
    try:
        os.close(fd)
        write(tmp)
        fd = os.open(tmp, os.O_RDWR | getattr(os, "O_BINARY", 0))
        try:
            os.fsync(fd)
        finally:
            os.close(fd)
        check_target(path, inputs)
        _finish(tmp, target)
    except OSError as exc:
        _remove(tmp)
        if exc.filename in (tmp, None):
            raise _named(exc, path) from None
        raise
    except BaseException:
        _remove(tmp)
        raise
    return Path(path)


def write_text(
    path: PathLike, text: str, encoding: str = "utf-8", inputs: Iterable[PathLike] = ()
) -> Path:
    """Write ``text`` to ``path`` atomically (newlines as "\\n"); return ``path`` as a Path."""
    with atomic_file(path, "w", encoding=encoding, newline="\n", inputs=inputs) as f:
        f.write(text)
    return Path(path)
