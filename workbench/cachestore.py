"""Where the caches keep their entries, bounded: in memory and in a folder on disk.

Both drop the least recently used entries first. The memory holds a fixed number of
entries. The folder holds at most a number of bytes (``LIGHTROCKS_CACHE_BYTES``, default
256 MiB); its entries are files whose modification time is the time of their last use.
Several processes may share a folder: an entry is written to a temporary file and renamed
into place, and an entry that another process deleted is a miss, never an error.

A ledger beside the entries keeps the folder's size, so that no process lists the folder to
learn it: each process appends the size of every entry it writes, and sums the ledger, the
lines of other processes included (a long ledger is summed into one line), whenever it has
written a sixteenth of the limit since it last did, adding its own writes in between.
Only when the sum passes the limit is the folder listed: the least recently used
entries are deleted down to three quarters of the limit, and the ledger starts anew with
the size found. A line appended at the moment another process rewrote the ledger may be
lost; the next eviction sets the ledger right. A read marks an entry used only when its
time is older than ``TOUCH_AFTER``: a day is fine enough a grain for a cache's order of use,
and a warm check of a large workspace does not rewrite a thousand files' times.
"""

from __future__ import annotations

import os
import tempfile
import time
from contextlib import suppress
from functools import cache
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path
from typing import Generic, TypeVar

LIMIT_VARIABLE = "LIGHTROCKS_CACHE_BYTES"
DEFAULT_LIMIT = 256 * 2**20
LEDGER = "ledger"
"""The file of the sizes written, beside the folders of entries."""
LEDGER_LINES = 100
TOUCH_AFTER = 3600.0
"""Seconds after its last marked use an entry's time is set again when it is read."""
"""A ledger longer than this is summed into one line, so that it stays quick to read."""

V = TypeVar("V")


@cache
def installed_version() -> str:
    """The version of LightRocks, part of every cache key (``unknown`` when not installed)."""
    try:
        return version("lightrocks")
    except PackageNotFoundError:
        return "unknown"


class Memory(Generic[V]):
    """The ``entries`` most recently used values of a process."""

    def __init__(self, entries: int) -> None:
        self.entries = entries
        self._values: dict[str, V] = {}  # most recently used last

    def __len__(self) -> int:
        return len(self._values)

    def get(self, key: str) -> V | None:
        value = self._values.pop(key, None)
        if value is not None:
            self._values[key] = value
        return value

    def put(self, key: str, value: V) -> None:
        self._values.pop(key, None)
        self._values[key] = value
        if len(self._values) > self.entries:
            del self._values[next(iter(self._values))]

    def values(self) -> list[V]:
        return list(self._values.values())

    def clear(self) -> None:
        self._values.clear()


def configured_limit() -> int:
    """``LIGHTROCKS_CACHE_BYTES`` when it is a number of bytes (0 keeps nothing on disk),
    else ``DEFAULT_LIMIT``."""
    setting = os.environ.get(LIMIT_VARIABLE, "").strip()
    return int(setting) if setting.isdigit() else DEFAULT_LIMIT


class Folder:
    """Text entries below ``folder``, ``<key[:2]>/<key>``, at most ``limit`` bytes in all
    (default: :func:`configured_limit`)."""

    def __init__(self, folder: Path, limit: int | None = None) -> None:
        self.folder = folder
        self.limit = configured_limit() if limit is None else limit
        self._summed: int | None = None  # the ledger's sum when this process last read it
        self._since = 0  # bytes this process wrote since then

    def get(self, key: str) -> str | None:
        """The entry ``key``, now the most recently used; ``None`` when it is missing or
        unreadable."""
        path = self.folder / key[:2] / key
        try:
            with path.open("rb") as file:
                used = os.fstat(file.fileno()).st_mtime
                text = file.read().decode("utf-8")
        except (OSError, ValueError):
            return None
        if time.time() - used > TOUCH_AFTER:
            with suppress(OSError):
                os.utime(path)
        return text

    def put(self, key: str, text: str) -> None:
        """Keep ``text`` as the entry ``key``; a folder that cannot be written keeps nothing.
        An entry larger than the limit is not kept: it would be the first to go."""
        try:
            data = text.encode("utf-8")
            if len(data) > self.limit:
                return
            if not (self.folder / LEDGER).exists():
                self.evict(self.limit)  # entries written before the folder had a ledger
            _write_atomic(self.folder / key[:2] / key, data)
            if self._recorded(len(data)) > self.limit:
                self.evict(self.limit * 3 // 4)
        except (OSError, ValueError):
            return

    def evict(self, goal: int) -> None:
        """Delete the least recently used entries until at most ``goal`` bytes remain (the
        files of other processes' unfinished writes count, and go when old), and start the
        ledger anew with the size left."""
        entries = sorted(_entries(self.folder))
        size = sum(length for _, length, _ in entries)
        for _, length, path in entries:
            if size <= goal:
                break
            try:
                os.unlink(path)
            except FileNotFoundError:
                pass
            except OSError:
                continue
            size -= length
        _write_atomic(self.folder / LEDGER, b"%d\n" % size)
        self._summed, self._since = size, 0

    def _recorded(self, size: int) -> int:
        """Add ``size`` to the ledger; the folder's size as far as this process knows: the
        ledger's sum, read again once this process has written a sixteenth of the limit."""
        path = self.folder / LEDGER
        self._since += size
        if self._summed is not None and self._since < self.limit // 16:
            with path.open("ab") as ledger:
                ledger.write(b"%d\n" % size)
            return self._summed + self._since
        with path.open("ab+") as ledger:
            ledger.write(b"%d\n" % size)
            ledger.flush()
            ledger.seek(0)
            lines = ledger.read().split()
        total = sum(int(line) for line in lines if line.isdigit())
        if len(lines) > LEDGER_LINES:
            _write_atomic(path, b"%d\n" % total)
        self._summed, self._since = total, 0
        return total


def _entries(folder: Path) -> list[tuple[int, int, str]]:
    """Each file in the sub-folders of ``folder``: last use, size and path; files that
    vanish while listed are left out."""
    found = []
    with suppress(OSError), os.scandir(folder) as shards:
        for shard in shards:
            if not shard.is_dir(follow_symlinks=False):
                continue
            with suppress(OSError), os.scandir(shard.path) as files:
                for file in files:
                    with suppress(OSError):
                        status = file.stat(follow_symlinks=False)
                        found.append((status.st_mtime_ns, status.st_size, file.path))
    return found


def _write_atomic(target: Path, data: bytes) -> None:
    """Write ``data`` as ``target`` in a private folder: staged in a temporary file and
    renamed into place, so readers never see half an entry."""
    target.parent.mkdir(mode=0o700, parents=True, exist_ok=True)
    handle, staged = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.")
    try:
        with os.fdopen(handle, "wb") as file:
            file.write(data)
        os.replace(staged, target)
    except BaseException:
        Path(staged).unlink(missing_ok=True)
        raise
