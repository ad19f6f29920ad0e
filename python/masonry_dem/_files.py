"""Reading an input file whole, within a size limit: the case and study files, the ground-motion records.

A path that is not a regular file (a FIFO, a device such as ``/dev/zero``, a folder, a socket) is refused
before it is opened, since opening a FIFO waits for a writer and reading a device never ends; a file larger
than the limit is refused from its size, before anything is read.
"""

from __future__ import annotations

import os
import stat
from typing import Union

from ._core import InputError

PathLike = Union[str, "os.PathLike[str]"]


def _kind(mode: int) -> str:
    if stat.S_ISDIR(mode):
        return "a folder"
    if stat.S_ISFIFO(mode):
        return "a FIFO"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "not a regular file"


def read_bytes(path: PathLike, limit: int, what: str) -> bytes:
    """The bytes of regular file ``path``, at most ``limit`` of them. Raises OSError when it cannot be
    read (a missing file: FileNotFoundError), InputError (starting with the file name) when it is not a
    regular file or holds more than ``limit`` bytes (a ``what``: "case file", "record")."""
    source = os.fspath(path)
    st = os.stat(source)
    if not stat.S_ISREG(st.st_mode):
        raise InputError(f"{source}: it is {_kind(st.st_mode)}, not a regular file: a {what} is read from a file")
    if st.st_size > limit:
        raise InputError(
            f"{source}: {st.st_size:,} bytes, larger than the limit of {limit // 2**20} MiB for a {what}"
        )
    with open(source, "rb") as f:
        data = f.read(limit + 1)  # never more, should the file grow meanwhile
    if len(data) > limit:
        raise InputError(f"{source}: larger than the limit of {limit // 2**20} MiB for a {what}")
    return data
