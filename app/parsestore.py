"""The parse cache on disk: parsed units as JSON in the user's cache folder.

Entries are data, never code: a unit is written as nested objects naming their class, and
read back only into the dataclasses of :mod:`lightrocks.metamodel.ast`, so a planted or
corrupt entry can at worst be a cache miss, never run anything. The folder is bounded and
written whole entry by entry (:class:`lightrocks.workbench.cachestore.Folder`).
"""

from __future__ import annotations

import json
from dataclasses import fields, is_dataclass
from pathlib import Path
from typing import Any

from lightrocks.app.cachedir import cache_root
from lightrocks.metamodel import ast
from lightrocks.metamodel.grammar import SyntaxProblem, paused_gc
from lightrocks.workbench.cachestore import Folder

CLASSES = {
    name: value
    for name, value in vars(ast).items()
    if isinstance(value, type) and is_dataclass(value) and value.__module__ == ast.__name__
}
PROBLEM = "SyntaxProblem"


class DiskStore:
    """Parse results below ``folder`` (default: ``<user cache>/lightrocks/parse``), at most
    ``limit`` bytes of them (default: ``LIGHTROCKS_CACHE_BYTES``)."""

    def __init__(self, folder: Path | None = None, limit: int | None = None) -> None:
        self.entries = Folder(folder or cache_root() / "parse", limit)

    @property
    def folder(self) -> Path:
        return self.entries.folder

    def get(self, key: str) -> ast.Unit | SyntaxProblem | None:
        text = self.entries.get(key)
        if text is None:
            return None
        try:
            result = read(text)
        except (ValueError, TypeError, KeyError, RecursionError):
            return None
        return result if isinstance(result, ast.Unit | SyntaxProblem) else None

    def put(self, key: str, result: ast.Unit | SyntaxProblem) -> None:
        try:
            with paused_gc():
                text = dumps(result)
        except (ValueError, RecursionError):
            return  # a result that cannot be written only costs the next run a parse
        self.entries.put(key, text)


def dumps(result: ast.Unit | SyntaxProblem) -> str:
    """A unit (or syntax problem) as JSON text: every object names its class in ``$``. The C
    encoder writes tuples, strings and numbers itself and asks ``_object_data`` only for the
    objects, a fourth of the values of a unit."""
    return json.dumps(result, default=_object_data, check_circular=False, separators=(",", ":"))


def _object_data(value: Any) -> dict[str, Any]:
    """The members of an AST node or a syntax problem, for the JSON encoder."""
    names = _FIELD_NAMES.get(type(value))
    if names is None and is_dataclass(value) and not isinstance(value, type):
        names = ast.field_names(type(value))
    if names is not None:
        data = {"$": type(value).__name__}
        for name in names:
            data[name] = getattr(value, name)
        return data
    if isinstance(value, SyntaxProblem):
        return {"$": PROBLEM, "message": value.message, "line": value.line, "column": value.column}
    raise TypeError(f"cannot store {type(value).__name__}")


def read(text: str) -> Any:
    """The inverse of ``dumps``; anything but the known classes is rejected.
    Objects are built as the JSON reader meets them, with no second walk over the data, and
    without the cyclic collector (see ``paused_gc``): a large unit reads in a third of the
    time."""
    with paused_gc():
        return json.loads(text, object_hook=_object)


def _object(data: dict[str, Any]) -> Any:
    """One stored object, its members already built (the JSON reader's object hook)."""
    values = {k: _tuples(v) if isinstance(v, list) else v for k, v in data.items() if k != "$"}
    name = data["$"]
    if name == PROBLEM:
        return SyntaxProblem(values["message"], values["line"], values["column"])
    return _restore(CLASSES[name], values)


def _tuples(items: list[Any]) -> tuple[Any, ...]:
    return tuple(_tuples(item) if isinstance(item, list) else item for item in items)


def _restore(cls: type, values: dict[str, Any]) -> Any:
    """An instance of an AST class with exactly its stored fields, without running its
    initializer: a frozen dataclass's initializer sets each field through
    ``object.__setattr__``, which made reading a large unit slower than parsing it."""
    if values.keys() != _FIELDS[cls]:
        raise KeyError(f"fields of {cls.__name__} do not match")
    instance = object.__new__(cls)
    instance.__dict__.update(values)
    return instance


_FIELDS = {cls: {f.name for f in fields(cls)} for cls in CLASSES.values()}
_FIELD_NAMES = {cls: ast.field_names(cls) for cls in CLASSES.values()}
