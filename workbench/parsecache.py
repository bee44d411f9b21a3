"""Parse results keyed by content: an unchanged file is never parsed twice.

Units are immutable dataclasses, so one parsed unit can serve every later check. The cache
lives in memory for a process (the language server) and on disk between processes (the
CLI), under ``$LIGHTROCKS_CACHE`` or ``$XDG_CACHE_HOME/lightrocks``. The key covers the
language, the file name shown in positions, the text and the installed version, so a stale
entry can never be returned; unreadable entries are ignored and parsed again.
"""

from __future__ import annotations

import hashlib
import os
import pickle
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path
from typing import Any

from lightrocks.metamodel.grammar import SyntaxProblem
from lightrocks.workbench.languages import Language

_memory: dict[str, Any] = {}


def parse(language: Language, text: str, shown: str) -> Any:
    """``language.parse(text, shown)``, answered from the cache when the content is known."""
    key = _key(language, text, shown)
    result = _memory.get(key)
    if result is None:
        result = _read(key)
    if result is None:
        try:
            result = language.parse(text, shown)
        except SyntaxProblem as problem:
            result = problem
        _write(key, result)
    _memory[key] = result
    if isinstance(result, SyntaxProblem):
        raise result
    return result


def _key(language: Language, text: str, shown: str) -> str:
    digest = hashlib.blake2b(digest_size=20)
    for part in (_version(), language.name, shown, text):
        digest.update(part.encode("utf-8", "surrogatepass") + b"\x00")
    return digest.hexdigest()


def _version() -> str:
    try:
        return version("lightrocks")
    except PackageNotFoundError:
        return "unknown"


def _folder() -> Path | None:
    configured = os.environ.get("LIGHTROCKS_CACHE")
    if configured == "":
        return None
    if configured:
        return Path(configured)
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "lightrocks" / "parse"


def _read(key: str) -> Any:
    folder = _folder()
    if folder is None:
        return None
    try:
        return pickle.loads((folder / key[:2] / key).read_bytes())
    except (OSError, pickle.UnpicklingError, EOFError, AttributeError, ImportError):
        return None


def _write(key: str, result: Any) -> None:
    folder = _folder()
    if folder is None:
        return
    target = folder / key[:2] / key
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        partial = target.with_suffix(f".{os.getpid()}.tmp")
        partial.write_bytes(pickle.dumps(result, protocol=pickle.HIGHEST_PROTOCOL))
        partial.replace(target)
    except (OSError, pickle.PicklingError, TypeError, RecursionError):
        return
