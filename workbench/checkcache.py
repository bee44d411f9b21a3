"""Check results kept for an unchanged workspace: a check whose reads all hold is not run again.

A check's findings depend on its arguments, on the checking code and on what it read from
disk (:mod:`lightrocks.workbench.reads`). An entry is found by a key over the first two and
holds the record of the third; it is used only when every read made again gives the same
result, so an edit, a new model file or package folder, or other checking code is a miss.

Two layers: whole check contexts in memory for the process (the language server, repeated
checks from Python), and findings on disk between processes when a :class:`Store` is
installed (the command line installs the bounded one of :mod:`lightrocks.app.checkstore`).
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import sys
from collections.abc import Iterable, Mapping
from functools import cache
from importlib.metadata import EntryPoints, entry_points
from pathlib import Path
from typing import Any, Protocol

from lightrocks.workbench.cachestore import Memory, installed_version
from lightrocks.workbench.diagnostics import Diagnostic
from lightrocks.workbench.reads import Reads
from lightrocks.workbench.sources import sources_digest

FORMAT = "1"  # what a stored entry means: raised to retire every entry stored before
MEMORY_ENTRIES = 4  # whole contexts are large: the last few checks of a session
GROUPS = ("lightrocks.languages", "lightrocks.language_extensions")
"""Entry-point groups whose code decides findings: languages and their extensions."""
_CHECKING_CODE = ("metamodel", "workbench")
"""Sub-packages of ``lightrocks`` whose code decides findings besides the languages."""


class Store(Protocol):
    """Findings kept between processes; a miss or an unreadable entry is ``None``."""

    def get(self, key: str) -> tuple[Reads, list[Diagnostic]] | None: ...

    def put(self, key: str, reads: Reads, findings: list[Diagnostic]) -> None: ...


_memory: Memory[tuple[Reads, Any]] = Memory(MEMORY_ENTRIES)
_store: Store | None = None


def use_store(store: Store | None) -> None:
    """Keep findings in ``store`` too (``None``: memory only)."""
    global _store
    _store = store


def key(paths: Iterable[Path], model_path: Iterable[Path], only_given: bool) -> str:
    """A digest of a check's arguments (as resolved now, and the working folder that findings
    are shown relative to) and of the code that checks."""
    digest = hashlib.blake2b(digest_size=20)
    parts = [FORMAT, sys.implementation.cache_tag, code_digest(), os.getcwd(), str(only_given)]
    parts += ["paths", *(str(p.resolve()) for p in paths)]
    parts += ["model path", *(str(p.resolve()) for p in model_path)]
    for part in parts:
        digest.update(part.encode("utf-8", "surrogateescape") + b"\x00")
    return digest.hexdigest()


def recall(entry: str, texts: Mapping[Path, str]) -> Any | None:
    """The value remembered in memory under ``entry`` if its reads still hold."""
    found = _memory.get(entry)
    if found is None or not found[0].still_hold(texts):
        return None
    return found[1]


def stored(entry: str) -> list[Diagnostic] | None:
    """The findings kept on disk under ``entry`` if their reads still hold."""
    found = _store.get(entry) if _store is not None else None
    if found is None or not found[0].still_hold({}):
        return None
    return found[1]


def remember(
    entry: str, reads: Reads, value: Any, findings: list[Diagnostic], texts: Mapping[Path, str]
) -> None:
    """Keep a check's ``value`` in memory and, read from disk alone, its findings on disk."""
    if not reads.complete:
        return
    _memory.put(entry, (reads, value))
    if _store is not None and not any(Path(name) in texts for name in reads.files):
        _store.put(entry, reads, findings)


@cache
def code_digest() -> str:
    """A digest of the code that decides findings (see :func:`checking_code`): an editable
    install changes the sources without changing any version."""
    digest = hashlib.blake2b(digest_size=20)
    places = checking_code()
    for group, entries in _registered().items():
        for entry in sorted(entries, key=lambda e: (e.name, e.value)):
            release = entry.dist.version if entry.dist is not None else ""
            digest.update(f"{group}\x00{entry.name}\x00{entry.value}\x00{release}\x00".encode())
    digest.update(installed_version().encode() + b"\x00")
    digest.update(sources_digest(places, (".py", ".tx")).encode())
    return digest.hexdigest()


def checking_code() -> set[Path]:
    """Where the code that decides findings lives: the kernel, the metamodel, and every
    registered language and extension. The application floor is not part of it, so an edit
    of the command line or the monitor keeps every cached finding."""
    places = {Path(__file__).resolve().parent.parent / name for name in _CHECKING_CODE}
    for entries in _registered().values():
        places |= {_sources(entry.module) for entry in entries}
    return places


@cache
def _registered() -> dict[str, EntryPoints]:
    """The entry points of every group in ``GROUPS``, read with one scan of the installed
    distributions (each scan costs a warm check tens of milliseconds)."""
    found = entry_points()
    return {group: found.select(group=group) for group in GROUPS}


def _sources(module: str) -> Path:
    """Where a module's code lives, found without running it: the folder of its package, or
    the file of a top-level module."""
    spec = importlib.util.find_spec(module)
    if spec is None or spec.origin is None:
        raise ModuleNotFoundError(f"no sources for module {module!r}")
    origin = Path(spec.origin).resolve()
    return origin.parent if spec.submodule_search_locations or "." in module else origin
